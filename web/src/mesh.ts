//! The tissue mesh as the page draws it: node coordinates, triangles, each triangle's
//! strain–displacement coefficients and the boundary edges; the strain field of a displacement
//! vector and its colour map.
import type { Mesh } from "./gen/needlesim/v1/needlesim_pb";

/** An axis-aligned box in metres: [x0, y0, x1, y1]. */
export type Bounds = [number, number, number, number];

export interface MeshGeom {
  /** Node coordinates (m), x y interleaved. */
  xy: Float64Array;
  /** Triangles, three node indices each. */
  tri: Uint32Array;
  /** Per triangle: b0 b1 b2 c0 c1 c2 (divided by 2A): strain = sum(b_i ux_i), ... */
  coef: Float64Array;
  /** Boundary edges, flattened node pairs. */
  boundary: Uint32Array;
  bounds: Bounds;
}

export function buildMesh(m: Mesh): MeshGeom {
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
    for (const [p, q] of [[a, b], [b, c], [c, a]] as const) {
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
export function triangleStrains(g: MeshGeom, u: ArrayLike<number>): Float64Array {
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

const STRAIN_STOPS: readonly (readonly [number, number, number])[] = [
  [247, 251, 255],
  [254, 224, 144],
  [253, 141, 60],
  [215, 48, 31],
  [127, 0, 0],
];

/** A perceptual-ish colour map (white → yellow → orange → dark red) for s in [0, 1]. */
export function strainColour(s: number): string {
  const x = Math.max(0, Math.min(1, s));
  const f = x * (STRAIN_STOPS.length - 1);
  const i = Math.min(STRAIN_STOPS.length - 2, Math.floor(f));
  const w = f - i;
  const [lo, hi] = [STRAIN_STOPS[i], STRAIN_STOPS[i + 1]];
  const c = lo.map((v, k) => Math.round(v + w * (hi[k] - v)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}
