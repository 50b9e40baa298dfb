//! The tissue view (canvas 2D): the deformed mesh coloured by strain, the undeformed outline, the
//! needle with its node states, the targets, and the world ↔ pixel transform the mouse uses.
import { type Frame, NodeState } from "./gen/needlesim/v1/needlesim_pb";
import { type Bounds, strainColour, triangleStrains } from "./mesh";
import type { ViewerState } from "./state";

/** World (m) → canvas pixels: px = ox + s·x, py = oy − s·y. */
export interface Xf {
  s: number;
  ox: number;
  oy: number;
}

export function viewTransform(canvas: HTMLCanvasElement, st: ViewerState): Xf {
  const [x0, y0, x1, y1] = st.viewBounds ?? st.mesh?.bounds ?? [-0.05, -0.05, 0.05, 0.05];
  const w = x1 - x0 || 0.1, h = y1 - y0 || 0.1;
  const pad = 24;
  const s = Math.min((canvas.width - 2 * pad) / w, (canvas.height - 2 * pad) / h);
  const ox = (canvas.width - s * w) / 2 - s * x0;
  const oy = (canvas.height + s * h) / 2 + s * y0;
  return { s, ox, oy };
}

export const toPx = (xf: Xf, x: number, y: number): [number, number] => [xf.ox + xf.s * x, xf.oy - xf.s * y];

/** Fixes the view's bounds once per session: the mesh, the needle base and the whole needle. */
export function updateViewBounds(st: ViewerState, f: Frame): void {
  if (!st.mesh || st.viewBounds) return;
  let [x0, y0, x1, y1] = st.mesh.bounds;
  const pts: [number, number][] = [];
  if (f.base) pts.push([f.base.xM, f.base.yM]);
  if (f.tipM) pts.push([f.tipM.x, f.tipM.y]);
  for (const [x, y] of pts) {
    x0 = Math.min(x0, x);
    x1 = Math.max(x1, x);
    y0 = Math.min(y0, y);
    y1 = Math.max(y1, y);
  }
  const m = 0.08 * Math.max(x1 - x0, y1 - y0);
  const b: Bounds = [x0 - m, y0 - m, x1 + m, y1 + m];
  st.viewBounds = b;
}

const NODE_COLOUR = { stuck: "#2166ac", slipping: "#f18f01", tip: "#e7298a", other: "#999" } as const;

function context2d(canvas: HTMLCanvasElement): CanvasRenderingContext2D {
  const ctx = canvas.getContext("2d");
  if (!ctx) throw new Error("this browser gives no 2D canvas context");
  return ctx;
}

/** Draws the shown frame (or just the mesh, or nothing yet) on the tissue view. */
export function drawView(canvas: HTMLCanvasElement, st: ViewerState): void {
  const ctx = context2d(canvas);
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = "#ffffff";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  const xf = viewTransform(canvas, st);
  const f = st.frame;
  if (st.mesh) {
    const g = st.mesh;
    const u = f?.nodeDisplacementM ?? [];
    const hasU = u.length >= g.xy.length;
    const strains = triangleStrains(g, u);
    let max = 0;
    for (const e of strains) max = Math.max(max, e);
    // A colour scale that follows the field but does not flicker: rises at once, decays slowly.
    st.strainScale = Math.max(1e-4, max > st.strainScale ? max : 0.98 * st.strainScale + 0.02 * max);
    const nt = g.tri.length / 3;
    const px = new Float64Array(g.xy.length);
    for (let i = 0; i < g.xy.length; i += 2) {
      const x = g.xy[i] + (hasU ? u[i] : 0), y = g.xy[i + 1] + (hasU ? u[i + 1] : 0);
      px[i] = xf.ox + xf.s * x;
      px[i + 1] = xf.oy - xf.s * y;
    }
    ctx.lineWidth = 0.5;
    ctx.strokeStyle = "rgba(60,60,60,0.35)";
    for (let t = 0; t < nt; t++) {
      const a = g.tri[3 * t], b = g.tri[3 * t + 1], c = g.tri[3 * t + 2];
      ctx.beginPath();
      ctx.moveTo(px[2 * a], px[2 * a + 1]);
      ctx.lineTo(px[2 * b], px[2 * b + 1]);
      ctx.lineTo(px[2 * c], px[2 * c + 1]);
      ctx.closePath();
      ctx.fillStyle = strainColour(strains[t] / st.strainScale);
      ctx.fill();
      if (nt < 20000) ctx.stroke();
    }
    // The undeformed outline.
    ctx.save();
    ctx.setLineDash([5, 4]);
    ctx.strokeStyle = "#1f4e9c";
    ctx.lineWidth = 1.2;
    ctx.beginPath();
    for (let i = 0; i < g.boundary.length; i += 2) {
      const p = g.boundary[i], q = g.boundary[i + 1];
      ctx.moveTo(...toPx(xf, g.xy[2 * p], g.xy[2 * p + 1]));
      ctx.lineTo(...toPx(xf, g.xy[2 * q], g.xy[2 * q + 1]));
    }
    ctx.stroke();
    ctx.restore();
    drawColourBar(canvas, ctx, st.strainScale);
  }
  if (f) {
    // Targets: filled green when hit, red ring when missed.
    for (const t of f.targets) {
      if (!t.positionM) continue;
      const [x, y] = toPx(xf, t.positionM.x, t.positionM.y);
      ctx.beginPath();
      ctx.arc(x, y, 7, 0, 2 * Math.PI);
      ctx.lineWidth = 2.5;
      ctx.strokeStyle = t.hit ? "#1a9850" : "#d73027";
      ctx.fillStyle = t.hit ? "rgba(26,152,80,0.6)" : "rgba(215,48,39,0.12)";
      ctx.fill();
      ctx.stroke();
      ctx.fillStyle = "#222";
      ctx.font = "11px system-ui, sans-serif";
      ctx.fillText(`${t.name} ${t.hit ? "hit" : `${(t.distanceM * 1000).toFixed(1)} mm`}`, x + 10, y - 8);
    }
    // The needle: its streamed shape (bent when flexible), or from the base along theta for its
    // length (frames of older recordings carry no shape).
    if (f.base) {
      const b = f.base;
      ctx.lineCap = "round";
      ctx.lineJoin = "round";
      ctx.strokeStyle = "#333";
      ctx.lineWidth = 3;
      ctx.beginPath();
      if (f.needleShapeM.length >= 2) {
        f.needleShapeM.forEach((p, i) => (i === 0 ? ctx.moveTo(...toPx(xf, p.x, p.y)) : ctx.lineTo(...toPx(xf, p.x, p.y))));
      } else {
        if (f.tipM) st.needleLengthM = Math.hypot(f.tipM.x - b.xM, f.tipM.y - b.yM) || st.needleLengthM;
        const ex = b.xM + st.needleLengthM * Math.cos(b.thetaRad), ey = b.yM + st.needleLengthM * Math.sin(b.thetaRad);
        ctx.moveTo(...toPx(xf, b.xM, b.yM));
        ctx.lineTo(...toPx(xf, ex, ey));
      }
      ctx.stroke();
      const [bx, by] = toPx(xf, b.xM, b.yM);
      ctx.fillStyle = "#333";
      ctx.fillRect(bx - 6, by - 6, 12, 12);
    }
    for (const n of f.needleNodes) {
      if (!n.positionM) continue;
      const [x, y] = toPx(xf, n.positionM.x, n.positionM.y);
      ctx.beginPath();
      ctx.arc(x, y, n.state === NodeState.TIP ? 5 : 4, 0, 2 * Math.PI);
      ctx.fillStyle =
        n.state === NodeState.STUCK
          ? NODE_COLOUR.stuck
          : n.state === NodeState.SLIPPING
            ? NODE_COLOUR.slipping
            : n.state === NodeState.TIP
              ? NODE_COLOUR.tip
              : NODE_COLOUR.other;
      ctx.fill();
    }
  }
  // Legend of the node states.
  ctx.font = "11px system-ui, sans-serif";
  const legend: [string, string][] = [
    ["stuck", NODE_COLOUR.stuck],
    ["slipping", NODE_COLOUR.slipping],
    ["tip", NODE_COLOUR.tip],
  ];
  legend.forEach(([name, colour], i) => {
    ctx.fillStyle = colour;
    ctx.beginPath();
    ctx.arc(14, 14 + 15 * i, 4, 0, 2 * Math.PI);
    ctx.fill();
    ctx.fillStyle = "#222";
    ctx.fillText(name, 24, 18 + 15 * i);
  });
  if (st.mode === "playback") {
    ctx.fillStyle = "#7b3294";
    ctx.fillText("PLAYBACK", canvas.width - 70, 16);
  }
}

function drawColourBar(canvas: HTMLCanvasElement, ctx: CanvasRenderingContext2D, scale: number): void {
  const x = canvas.width - 24, y0 = 30, h = 150;
  for (let i = 0; i < h; i++) {
    ctx.fillStyle = strainColour(1 - i / h);
    ctx.fillRect(x, y0 + i, 12, 1);
  }
  ctx.strokeStyle = "#666";
  ctx.strokeRect(x, y0, 12, h);
  ctx.fillStyle = "#222";
  ctx.font = "10px system-ui, sans-serif";
  ctx.textAlign = "right";
  ctx.fillText(`strain ${scale.toExponential(1)}`, x + 12, y0 - 6);
  ctx.fillText("0", x - 3, y0 + h);
  ctx.textAlign = "left";
}
