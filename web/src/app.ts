// The needlesim web viewer: a gRPC-web client of needlesim-server (connect-web), served by the
// server itself. Draws the deformed mesh coloured by strain, the needle and targets, plots forces
// against time and depth, drives the needle with the mouse (unary SetPose) and plays back MCAP
// recordings downloaded from the server.
import { createClient, type Client } from "@connectrpc/connect";
import { createGrpcWebTransport } from "@connectrpc/connect-web";
import { create, fromBinary } from "@bufbuild/protobuf";
import { McapStreamReader } from "@mcap/core";
import { decompress as zstdDecompress } from "fzstd";
// @ts-expect-error lz4js has no type declarations
import * as lz4 from "lz4js";
import {
  ControlService,
  FrameSchema,
  type Frame,
  type Mesh,
  NodeState,
  ObserveService,
  Pose2Schema,
  RecordingService,
  SessionService,
} from "./gen/needlesim/v1/needlesim_pb";

const transport = createGrpcWebTransport({ baseUrl: window.location.origin, useBinaryFormat: true });
const sessions: Client<typeof SessionService> = createClient(SessionService, transport);
const control: Client<typeof ControlService> = createClient(ControlService, transport);
const observe: Client<typeof ObserveService> = createClient(ObserveService, transport);
const recordings: Client<typeof RecordingService> = createClient(RecordingService, transport);

const $ = <T extends HTMLElement>(id: string): T => document.getElementById(id) as T;
const view = $<HTMLCanvasElement>("view");
const plotTime = $<HTMLCanvasElement>("plot-time");
const plotDepth = $<HTMLCanvasElement>("plot-depth");
const tokenInput = $<HTMLInputElement>("token");
const sessionSelect = $<HTMLSelectElement>("session-select");
const recSelect = $<HTMLSelectElement>("rec-select");
const slider = $<HTMLInputElement>("slider");

function status(msg: string): void {
  $("status").textContent = msg;
}

function auth(token: string): { headers: Record<string, string> } {
  return { headers: { authorization: `Bearer ${token}` } };
}

// ---------------------------------------------------------------------------------------------
// State

/** Tokens the page knows, by session id (from sessions it created, or pasted / in the URL). */
const tokens = new Map<string, string>();

interface MeshGeom {
  xy: Float64Array;
  tri: Uint32Array;
  /** Per triangle: b0 b1 b2 c0 c1 c2 (divided by 2A): strain = sum(b_i ux_i), ... */
  coef: Float64Array;
  /** Boundary edges, flattened node pairs. */
  boundary: Uint32Array;
  bounds: [number, number, number, number];
}

interface Sample {
  t: number;
  depth: number;
  axial: number;
  lateral: number;
  torque: number;
}

let current: { id: string; token: string } | null = null;
/** This tab's id for SetPose: the server lets one controller drive at a time, and this tab's
 * poses share one control lease (another tab or client is refused while this one drives). */
const TAB_ID = `web-${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;
let mesh: MeshGeom | null = null;
let frame: Frame | null = null;
let frames = 0;
let samples: Sample[] = [];
let streamAbort: AbortController | null = null;
let needleLength = 0;
let strainScale = 1e-3;
let dirty = true;
let mode: "live" | "playback" = "live";
let playback: Frame[] = [];
let playing = false;
let viewBounds: [number, number, number, number] | null = null;

// ---------------------------------------------------------------------------------------------
// Mesh geometry and strain

function buildMesh(m: Mesh): MeshGeom {
  const xy = Float64Array.from(m.nodeXyM);
  const tri = Uint32Array.from(m.triangleNodes);
  const nt = tri.length / 3;
  const coef = new Float64Array(nt * 6);
  const edges = new Map<string, number>();
  for (let t = 0; t < nt; t++) {
    const a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    const xa = xy[2 * a], ya = xy[2 * a + 1], xb = xy[2 * b], yb = xy[2 * b + 1], xc = xy[2 * c], yc = xy[2 * c + 1];
    const twoA = (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya);
    const inv = twoA !== 0 ? 1 / twoA : 0;
    coef[6 * t] = (yb - yc) * inv;
    coef[6 * t + 1] = (yc - ya) * inv;
    coef[6 * t + 2] = (ya - yb) * inv;
    coef[6 * t + 3] = (xc - xb) * inv;
    coef[6 * t + 4] = (xa - xc) * inv;
    coef[6 * t + 5] = (xb - xa) * inv;
    for (const [p, q] of [[a, b], [b, c], [c, a]]) {
      const key = p < q ? `${p},${q}` : `${q},${p}`;
      edges.set(key, (edges.get(key) ?? 0) + 1);
    }
  }
  const boundary: number[] = [];
  for (const [key, n] of edges) {
    if (n === 1) boundary.push(...key.split(",").map(Number));
  }
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (let i = 0; i < xy.length; i += 2) {
    x0 = Math.min(x0, xy[i]);
    x1 = Math.max(x1, xy[i]);
    y0 = Math.min(y0, xy[i + 1]);
    y1 = Math.max(y1, xy[i + 1]);
  }
  return { xy, tri, coef, boundary: Uint32Array.from(boundary), bounds: [x0, y0, x1, y1] };
}

/** The magnitude (Frobenius norm of the small-strain tensor) of every triangle's constant strain. */
function triangleStrains(g: MeshGeom, u: ArrayLike<number>): Float64Array {
  const nt = g.tri.length / 3;
  const out = new Float64Array(nt);
  if (u.length < g.xy.length) return out;
  for (let t = 0; t < nt; t++) {
    let exx = 0, eyy = 0, gxy = 0;
    for (let k = 0; k < 3; k++) {
      const n = g.tri[3 * t + k];
      const b = g.coef[6 * t + k], c = g.coef[6 * t + 3 + k];
      const ux = u[2 * n], uy = u[2 * n + 1];
      exx += b * ux;
      eyy += c * uy;
      gxy += c * ux + b * uy;
    }
    const exy = 0.5 * gxy;
    out[t] = Math.sqrt(exx * exx + eyy * eyy + 2 * exy * exy);
  }
  return out;
}

/** A perceptual-ish colour map (white → yellow → orange → dark red) for s in [0, 1]. */
function strainColour(s: number): string {
  const x = Math.max(0, Math.min(1, s));
  const stops = [
    [247, 251, 255],
    [254, 224, 144],
    [253, 141, 60],
    [215, 48, 31],
    [127, 0, 0],
  ];
  const f = x * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(f));
  const w = f - i;
  const c = stops[i].map((v, k) => Math.round(v + w * (stops[i + 1][k] - v)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

// ---------------------------------------------------------------------------------------------
// Drawing the tissue view

interface Xf {
  s: number;
  ox: number;
  oy: number;
}

function viewTransform(): Xf {
  const [x0, y0, x1, y1] = viewBounds ?? mesh?.bounds ?? [-0.05, -0.05, 0.05, 0.05];
  const w = x1 - x0 || 0.1, h = y1 - y0 || 0.1;
  const pad = 24;
  const s = Math.min((view.width - 2 * pad) / w, (view.height - 2 * pad) / h);
  const ox = (view.width - s * w) / 2 - s * x0;
  const oy = (view.height + s * h) / 2 + s * y0;
  return { s, ox, oy };
}

const toPx = (xf: Xf, x: number, y: number): [number, number] => [xf.ox + xf.s * x, xf.oy - xf.s * y];
const toWorld = (xf: Xf, px: number, py: number): [number, number] => [(px - xf.ox) / xf.s, (xf.oy - py) / xf.s];

/** Bounds that hold the mesh, the needle base and the whole needle, fixed once per session. */
function updateViewBounds(f: Frame): void {
  if (!mesh || viewBounds) return;
  let [x0, y0, x1, y1] = mesh.bounds;
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
  viewBounds = [x0 - m, y0 - m, x1 + m, y1 + m];
}

function drawView(): void {
  const ctx = view.getContext("2d")!;
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = "#ffffff";
  ctx.fillRect(0, 0, view.width, view.height);
  const xf = viewTransform();
  const f = frame;
  if (mesh) {
    const g = mesh;
    const u = f?.nodeDisplacementM ?? [];
    const hasU = u.length >= g.xy.length;
    const strains = triangleStrains(g, u);
    let max = 0;
    for (const e of strains) max = Math.max(max, e);
    // A colour scale that follows the field but does not flicker: rises at once, decays slowly.
    strainScale = Math.max(1e-4, max > strainScale ? max : 0.98 * strainScale + 0.02 * max);
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
      ctx.fillStyle = strainColour(strains[t] / strainScale);
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
    drawColourBar(ctx, strainScale);
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
        if (f.tipM) needleLength = Math.hypot(f.tipM.x - b.xM, f.tipM.y - b.yM) || needleLength;
        const ex = b.xM + needleLength * Math.cos(b.thetaRad), ey = b.yM + needleLength * Math.sin(b.thetaRad);
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
      ctx.fillStyle = n.state === NodeState.STUCK ? "#2166ac" : n.state === NodeState.SLIPPING ? "#f18f01" : n.state === NodeState.TIP ? "#e7298a" : "#999";
      ctx.fill();
    }
  }
  // Legend of the node states.
  ctx.font = "11px system-ui, sans-serif";
  const legend: [string, string][] = [
    ["stuck", "#2166ac"],
    ["slipping", "#f18f01"],
    ["tip", "#e7298a"],
  ];
  legend.forEach(([name, colour], i) => {
    ctx.fillStyle = colour;
    ctx.beginPath();
    ctx.arc(14, 14 + 15 * i, 4, 0, 2 * Math.PI);
    ctx.fill();
    ctx.fillStyle = "#222";
    ctx.fillText(name, 24, 18 + 15 * i);
  });
  if (mode === "playback") {
    ctx.fillStyle = "#7b3294";
    ctx.fillText("PLAYBACK", view.width - 70, 16);
  }
}

function drawColourBar(ctx: CanvasRenderingContext2D, scale: number): void {
  const x = view.width - 24, y0 = 30, h = 150;
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

// ---------------------------------------------------------------------------------------------
// Plots

interface Series {
  key: "axial" | "lateral" | "torque";
  label: string;
  colour: string;
  /** The smallest span of the value axis (so that round-off noise is not magnified). */
  minSpan: number;
}

const SERIES: Series[] = [
  { key: "axial", label: "axial force (N)", colour: "#d95f02", minSpan: 0.02 },
  { key: "lateral", label: "lateral force (N)", colour: "#1b9e77", minSpan: 0.02 },
  { key: "torque", label: "torque (N·m)", colour: "#7570b3", minSpan: 2e-4 },
];

function fmt(v: number): string {
  return v !== 0 && Math.abs(v) < 1e-2 ? v.toExponential(1) : v.toPrecision(3);
}

function niceRange(lo: number, hi: number): [number, number] {
  if (!(hi > lo)) {
    const m = Math.max(Math.abs(lo), 1e-6);
    return [lo - m, hi + m];
  }
  const pad = 0.08 * (hi - lo);
  return [lo - pad, hi + pad];
}

function drawPlot(canvas: HTMLCanvasElement, data: Sample[], xOf: (s: Sample) => number, xLabel: string, cursor: number | null): void {
  const ctx = canvas.getContext("2d")!;
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  const left = 64, right = 10, top = 6, bottom = 22;
  const ph = (canvas.height - top - bottom) / SERIES.length;
  const pw = canvas.width - left - right;
  let xMin = Infinity, xMax = -Infinity;
  for (const s of data) {
    const x = xOf(s);
    if (x < xMin) xMin = x;
    if (x > xMax) xMax = x;
  }
  [xMin, xMax] = data.length ? niceRange(xMin, xMax) : [0, 1];
  ctx.font = "10px system-ui, sans-serif";
  SERIES.forEach((ser, i) => {
    const y0 = top + i * ph;
    let lo = Infinity, hi = -Infinity;
    for (const s of data) {
      lo = Math.min(lo, s[ser.key]);
      hi = Math.max(hi, s[ser.key]);
    }
    lo = Math.min(lo, 0);
    hi = Math.max(hi, 0);
    if (!data.length) [lo, hi] = [-ser.minSpan / 2, ser.minSpan / 2];
    if (hi - lo < ser.minSpan) {
      const mid = (hi + lo) / 2;
      [lo, hi] = [mid - ser.minSpan / 2, mid + ser.minSpan / 2];
    }
    [lo, hi] = niceRange(lo, hi);
    const X = (x: number) => left + ((x - xMin) / (xMax - xMin)) * pw;
    const Y = (v: number) => y0 + ph - 4 - ((v - lo) / (hi - lo)) * (ph - 8);
    ctx.strokeStyle = "#ccc";
    ctx.strokeRect(left, y0 + 2, pw, ph - 4);
    ctx.beginPath();
    ctx.moveTo(left, Y(0));
    ctx.lineTo(left + pw, Y(0));
    ctx.stroke();
    ctx.fillStyle = "#333";
    ctx.textAlign = "right";
    ctx.fillText(fmt(hi), left - 3, y0 + 12);
    ctx.fillText(fmt(lo), left - 3, y0 + ph - 4);
    ctx.textAlign = "left";
    ctx.fillStyle = ser.colour;
    ctx.fillText(ser.label, left + 4, y0 + 13);
    ctx.strokeStyle = ser.colour;
    ctx.lineWidth = 1.3;
    ctx.beginPath();
    const step = Math.max(1, Math.floor(data.length / (2 * pw)));
    for (let k = 0; k < data.length; k += step) {
      const s = data[k];
      if (k === 0) ctx.moveTo(X(xOf(s)), Y(s[ser.key]));
      else ctx.lineTo(X(xOf(s)), Y(s[ser.key]));
    }
    ctx.stroke();
    ctx.lineWidth = 1;
    if (cursor !== null) {
      ctx.strokeStyle = "#7b3294";
      ctx.beginPath();
      ctx.moveTo(X(cursor), y0 + 2);
      ctx.lineTo(X(cursor), y0 + ph - 2);
      ctx.stroke();
    }
  });
  ctx.fillStyle = "#333";
  ctx.textAlign = "left";
  ctx.fillText(fmt(xMin), left, canvas.height - 6);
  ctx.textAlign = "right";
  ctx.fillText(fmt(xMax), left + pw, canvas.height - 6);
  ctx.textAlign = "center";
  ctx.fillText(xLabel, left + pw / 2, canvas.height - 6);
  ctx.textAlign = "left";
}

function sampleOf(f: Frame): Sample {
  return { t: f.timeS, depth: f.insertedLengthM * 1000, axial: f.forceAxialN, lateral: f.forceLateralN, torque: f.torqueNm };
}

function drawPlots(): void {
  if (mode === "playback") {
    const data = playback.map(sampleOf);
    const cur = frame ? sampleOf(frame) : null;
    drawPlot(plotTime, data, (s) => s.t, "time (s)", cur ? cur.t : null);
    drawPlot(plotDepth, data, (s) => s.depth, "inserted depth (mm)", cur ? cur.depth : null);
    return;
  }
  const tEnd = samples.length ? samples[samples.length - 1].t : 0;
  const recent = samples.filter((s) => s.t >= tEnd - 20);
  drawPlot(plotTime, recent, (s) => s.t, "time (s), last 20 s", null);
  drawPlot(plotDepth, samples, (s) => s.depth, "inserted depth (mm)", null);
}

// ---------------------------------------------------------------------------------------------
// Readout

function showFrame(f: Frame): void {
  frame = f;
  updateViewBounds(f);
  $("depth").textContent = `${(f.insertedLengthM * 1000).toFixed(2)} mm`;
  $("depth").dataset.depthM = String(f.insertedLengthM);
  document.body.dataset.depthM = String(f.insertedLengthM);
  $("axial").textContent = `${f.forceAxialN.toFixed(3)} N`;
  $("lateral").textContent = `${f.forceLateralN.toFixed(3)} N`;
  $("torque").textContent = `${(f.torqueNm * 1000).toFixed(2)} mN·m`;
  let st = 0, sl = 0, tp = 0;
  for (const n of f.needleNodes) {
    if (n.state === NodeState.STUCK) st++;
    else if (n.state === NodeState.SLIPPING) sl++;
    else if (n.state === NodeState.TIP) tp++;
  }
  $("nodes").textContent = `${st}/${sl}/${tp}`;
  $("targets").textContent = f.targets.length ? f.targets.map((t) => `${t.name}: ${t.hit ? "hit" : "missed"}`).join(", ") : "none";
  $("bevel").textContent = f.bevelSide === 0 ? "symmetric" : f.bevelSide > 0 ? "+n side" : "−n side";
  document.body.dataset.bevelSide = String(f.bevelSide);
  dirty = true;
}

/** Turns the needle 180° about its axis (a bevel tip then faces the other side). */
async function flipBevel(): Promise<void> {
  if (!current) return status("watch a session first");
  try {
    const r = await control.flipBevel({ sessionId: current.id }, auth(current.token));
    status(`bevel flip ${r.flipsRequested} requested`);
  } catch (e) {
    status(`FlipBevel: ${String(e)}`);
  }
}

function render(): void {
  if (dirty) {
    dirty = false;
    drawView();
    drawPlots();
  }
  requestAnimationFrame(render);
}

// ---------------------------------------------------------------------------------------------
// Sessions

async function refreshSessions(select?: string): Promise<void> {
  try {
    const res = await sessions.listSessions({});
    const keep = select ?? sessionSelect.value;
    sessionSelect.replaceChildren(
      ...res.sessions.map((s) => {
        const o = document.createElement("option");
        o.value = s.sessionId;
        o.textContent = `${s.sessionId} (${s.sceneName}, ${s.nNodes} nodes${tokens.has(s.sessionId) ? ", token known" : ""})`;
        return o;
      }),
    );
    if (keep && res.sessions.some((s) => s.sessionId === keep)) sessionSelect.value = keep;
    const known = tokens.get(sessionSelect.value);
    if (known) tokenInput.value = known;
  } catch (e) {
    status(`ListSessions: ${String(e)}`);
  }
}

async function createFromExample(): Promise<void> {
  const example = $<HTMLSelectElement>("example-select").value;
  try {
    status(`creating a session of ${example}…`);
    const res = await sessions.createSession({ scene: { source: { case: "example", value: example } } });
    const id = res.session?.sessionId ?? "";
    tokens.set(id, res.controllerToken);
    await refreshSessions(id);
    tokenInput.value = res.controllerToken;
    status("");
    await watch(id, res.controllerToken);
  } catch (e) {
    status(`CreateSession: ${String(e)}`);
  }
}

async function watch(id: string, token: string): Promise<void> {
  streamAbort?.abort();
  mode = "live";
  current = { id, token };
  tokens.set(id, token);
  mesh = null;
  frame = null;
  viewBounds = null;
  samples = [];
  frames = 0;
  commanded = null;
  document.body.dataset.frames = "0";
  document.body.dataset.session = id;
  $("frames").textContent = "0";
  const url = new URL(window.location.href);
  url.searchParams.set("session", id);
  url.searchParams.set("token", token);
  window.history.replaceState(null, "", url);
  try {
    mesh = buildMesh(await sessions.getMesh({ sessionId: id }, auth(token)));
  } catch (e) {
    status(`GetMesh: ${String(e)}`);
    return;
  }
  const abort = new AbortController();
  streamAbort = abort;
  document.body.dataset.state = "live";
  status("");
  try {
    const stream = observe.observe({ sessionId: id, rateHz: 60, includeDisplacements: true }, { ...auth(token), signal: abort.signal });
    for await (const f of stream) {
      frames++;
      document.body.dataset.frames = String(frames);
      $("frames").textContent = String(frames);
      samples.push(sampleOf(f));
      if (samples.length > 30000) samples = samples.slice(-20000);
      if (mode === "live") showFrame(f);
    }
    if (!abort.signal.aborted) status("the session's frame stream ended");
  } catch (e) {
    if (!abort.signal.aborted) status(`Observe: ${String(e)}`);
  }
}

// ---------------------------------------------------------------------------------------------
// Driving the needle (unary SetPose, at most ~100 Hz)

interface Pose {
  x: number;
  y: number;
  theta: number;
}

let commanded: Pose | null = null;
let pending: Pose | null = null;
let inFlight = 0;
let lastSent = 0;
let posesSent = 0;

function currentPose(): Pose | null {
  if (commanded) return { ...commanded };
  const b = frame?.base;
  return b ? { x: b.xM, y: b.yM, theta: b.thetaRad } : null;
}

let posesCommanded = 0;

function command(p: Pose): void {
  posesCommanded++;
  document.body.dataset.posesCommanded = String(posesCommanded);
  document.body.dataset.inFlight = String(inFlight);
  commanded = p;
  pending = p;
  pump();
}

function pump(): void {
  if (!pending || !current || inFlight >= 2) return;
  const now = performance.now();
  if (now - lastSent < 10) {
    setTimeout(pump, 10 - (now - lastSent));
    return;
  }
  const p = pending;
  pending = null;
  lastSent = now;
  inFlight++;
  const { id, token } = current;
  control
    .setPose({ sessionId: id, base: create(Pose2Schema, { xM: p.x, yM: p.y, thetaRad: p.theta }), clientId: TAB_ID }, auth(token))
    .then(() => {
      posesSent++;
      document.body.dataset.poses = String(posesSent);
    })
    .catch((e) => status(`SetPose: ${String(e)}`))
    .finally(() => {
      inFlight--;
      pump();
    });
}

let drag: { start: Pose; wx: number; wy: number; px: number; free: boolean; rotate: boolean } | null = null;

function eventWorld(ev: MouseEvent): [number, number] {
  const r = view.getBoundingClientRect();
  const px = ((ev.clientX - r.left) * view.width) / r.width;
  const py = ((ev.clientY - r.top) * view.height) / r.height;
  return toWorld(viewTransform(), px, py);
}

view.addEventListener("mousedown", (ev) => {
  if (mode !== "live") return;
  const start = currentPose();
  if (!start) return;
  const [wx, wy] = eventWorld(ev);
  drag = { start, wx, wy, px: ev.clientX, free: ev.altKey, rotate: ev.shiftKey };
  ev.preventDefault();
});

window.addEventListener("mousemove", (ev) => {
  if (!drag) return;
  const [wx, wy] = eventWorld(ev);
  const dx = wx - drag.wx, dy = wy - drag.wy;
  const s = drag.start;
  if (drag.rotate) {
    command({ ...s, theta: s.theta + (ev.clientX - drag.px) * 0.005 });
  } else if (drag.free) {
    command({ ...s, x: s.x + dx, y: s.y + dy });
  } else {
    const c = Math.cos(s.theta), sn = Math.sin(s.theta);
    const along = dx * c + dy * sn;
    command({ ...s, x: s.x + along * c, y: s.y + along * sn });
  }
});

window.addEventListener("mouseup", () => {
  drag = null;
});

view.addEventListener(
  "wheel",
  (ev) => {
    if (mode !== "live") return;
    const p = currentPose();
    if (!p) return;
    ev.preventDefault();
    command({ ...p, theta: p.theta - Math.sign(ev.deltaY) * 0.01 });
  },
  { passive: false },
);

// ---------------------------------------------------------------------------------------------
// Recordings

async function refreshRecordings(): Promise<void> {
  try {
    // A recording opens with the token of the session that made it: list those of the session watched.
    const res = await recordings.listRecordings({}, current ? auth(current.token) : {});
    recSelect.replaceChildren(
      ...res.recordings.map((r) => {
        const o = document.createElement("option");
        o.value = r.name;
        o.textContent = `${r.name} (${r.messages} frames${r.finished ? "" : ", recording"})`;
        return o;
      }),
    );
  } catch (e) {
    status(`ListRecordings: ${String(e)}`);
  }
}

async function startStopRecording(start: boolean): Promise<void> {
  if (!current) return status("watch a session first");
  try {
    const req = { sessionId: current.id };
    const info = start ? await recordings.startRecording(req, auth(current.token)) : await recordings.stopRecording(req, auth(current.token));
    status(`${start ? "recording to" : "recorded"} ${info.name}`);
    await refreshRecordings();
    recSelect.value = info.name;
  } catch (e) {
    status(`${start ? "StartRecording" : "StopRecording"}: ${String(e)}`);
  }
}

/** The Frame messages of an MCAP file (chunked, zstd / lz4 / uncompressed; finished or not). */
export function parseMcapFrames(bytes: Uint8Array): Frame[] {
  const reader = new McapStreamReader({
    decompressHandlers: {
      zstd: (buf, size) => zstdDecompress(buf, new Uint8Array(Number(size))),
      lz4: (buf, size) => Uint8Array.from(lz4.decompress(buf, Number(size))),
    },
  });
  reader.append(bytes);
  const frameChannels = new Set<number>();
  const schemas = new Map<number, string>();
  const out: Frame[] = [];
  for (let rec = reader.nextRecord(); rec; rec = reader.nextRecord()) {
    if (rec.type === "Schema") schemas.set(rec.id, rec.name);
    else if (rec.type === "Channel" && schemas.get(rec.schemaId) === "needlesim.v1.Frame") frameChannels.add(rec.id);
    else if (rec.type === "Message" && frameChannels.has(rec.channelId)) out.push(fromBinary(FrameSchema, rec.data));
  }
  return out;
}

async function loadRecording(): Promise<void> {
  const name = recSelect.value;
  if (!name) return status("no recording selected");
  try {
    status(`downloading ${name}…`);
    const parts: Uint8Array[] = [];
    let total = 0;
    for await (const chunk of recordings.downloadRecording({ name }, current ? auth(current.token) : {})) {
      parts.push(chunk.data);
      total += chunk.data.length;
    }
    const bytes = new Uint8Array(total);
    let off = 0;
    for (const p of parts) {
      bytes.set(p, off);
      off += p.length;
    }
    const all = parseMcapFrames(bytes);
    if (!all.length) return status(`${name} holds no frames`);
    // Keep at most ~5000 frames for the timeline (recordings hold every tick).
    const step = Math.max(1, Math.ceil(all.length / 5000));
    playback = all.filter((_, i) => i % step === 0);
    // The recording's session, when it is still open and its token known, gives the mesh.
    const sid = name.replace(/-\d{8}T\d{6}Z.*$/, "");
    const tok = tokens.get(sid) ?? (current?.id === sid ? current.token : undefined);
    if (tok && current?.id !== sid) {
      try {
        mesh = buildMesh(await sessions.getMesh({ sessionId: sid }, auth(tok)));
        viewBounds = null;
      } catch {
        /* draw without the mesh */
      }
    }
    mode = "playback";
    document.body.dataset.state = "playback";
    document.body.dataset.playbackFrames = String(playback.length);
    slider.max = String(playback.length - 1);
    slider.value = "0";
    showPlayback(0);
    status(`${name}: ${all.length} frames${step > 1 ? `, every ${step}th shown` : ""}`);
  } catch (e) {
    status(`DownloadRecording: ${String(e)}`);
  }
}

function showPlayback(i: number): void {
  const f = playback[i];
  if (!f) return;
  showFrame(f);
  $("rec-time").textContent = `${f.timeS.toFixed(3)} s`;
}

let playT0 = 0;
let playSim0 = 0;

function playStep(): void {
  if (!playing || mode !== "playback") return;
  const simT = playSim0 + (performance.now() - playT0) / 1000;
  let i = Number(slider.value);
  while (i < playback.length - 1 && playback[i + 1].timeS <= simT) i++;
  slider.value = String(i);
  showPlayback(i);
  if (i >= playback.length - 1) {
    playing = false;
    $("play").textContent = "▶";
    return;
  }
  requestAnimationFrame(playStep);
}

// ---------------------------------------------------------------------------------------------
// Wiring

$("refresh-sessions").addEventListener("click", () => void refreshSessions());
sessionSelect.addEventListener("change", () => {
  tokenInput.value = tokens.get(sessionSelect.value) ?? "";
});
$("connect").addEventListener("click", () => {
  const id = sessionSelect.value;
  const tok = tokenInput.value.trim();
  if (!id) return status("no session selected");
  if (!tok) return status("paste the session's controller or observer token (printed in the server log)");
  void watch(id, tok);
});
$("create").addEventListener("click", () => void createFromExample());
$("flip-bevel").addEventListener("click", () => void flipBevel());
$("rec-refresh").addEventListener("click", () => void refreshRecordings());
$("rec-start").addEventListener("click", () => void startStopRecording(true));
$("rec-stop").addEventListener("click", () => void startStopRecording(false));
$("rec-load").addEventListener("click", () => void loadRecording());
$("live").addEventListener("click", () => {
  playing = false;
  if (current) void watch(current.id, current.token);
});
slider.addEventListener("input", () => {
  playing = false;
  $("play").textContent = "▶";
  showPlayback(Number(slider.value));
});
$("play").addEventListener("click", () => {
  if (mode !== "playback" || !playback.length) return;
  playing = !playing;
  $("play").textContent = playing ? "❚❚" : "▶";
  if (playing) {
    if (Number(slider.value) >= playback.length - 1) slider.value = "0";
    playT0 = performance.now();
    playSim0 = playback[Number(slider.value)].timeS;
    requestAnimationFrame(playStep);
  }
});

async function main(): Promise<void> {
  requestAnimationFrame(render);
  const params = new URLSearchParams(window.location.search);
  const sid = params.get("session");
  const tok = params.get("token");
  if (sid && tok) tokens.set(sid, tok);
  await refreshSessions(sid ?? undefined);
  void refreshRecordings();
  document.body.dataset.ready = "1";
  if (sid && tok) {
    tokenInput.value = tok;
    await watch(sid, tok);
  }
}

void main();
