//! The protocol's 3D messages as the 3D view's data (the one place they are read): the tissue
//! surface (GetSurface, once per session) and a frame's 3D state (`Frame.d3`, the surface
//! displacements), and the frame's forces as a plot sample.
import { type Frame, NodeState, type Surface, type Tick3, type Vec3 } from "./gen/needlesim/v1/needlesim_pb";
import type { ForceSample } from "./history";
import type { Pose3 } from "./pose3";
import type { PointState, Scene3, Surface3 } from "./view3";

export function surface3Of(s: Surface): Surface3 {
  return { positionsM: Float32Array.from(s.nodeXyzM), triangles: Uint32Array.from(s.triangles) };
}

const v3 = (v: Vec3 | undefined): [number, number, number] => [v?.x ?? 0, v?.y ?? 0, v?.z ?? 0];

function pointState(s: NodeState): PointState {
  switch (s) {
    case NodeState.STUCK:
      return "stuck";
    case NodeState.SLIPPING:
      return "slipping";
    case NodeState.TIP:
      return "tip";
    default:
      return "other";
  }
}

/** A 3D frame as the 3D view draws it (null for a frame without 3D state). */
export function scene3Of(f: Frame): Scene3 | null {
  const d = f.d3;
  if (!d) return null;
  return {
    displacementM: f.surfaceDisplacementM.length ? Float32Array.from(f.surfaceDisplacementM) : null,
    needleM: d.needleShapeM.map(v3),
    points: d.contacts.map((c) => ({ posM: v3(c.positionM), state: pointState(c.state) })),
    targets: d.targets.map((t) => ({ centreM: v3(t.centerM), radiusM: t.radiusM, hit: t.hit })),
  };
}

/** The base pose a 3D tick applied. */
export function pose3Of(d: Tick3): Pose3 | null {
  const b = d.base;
  if (!b?.positionM || !b.orientation) return null;
  const q = b.orientation;
  return { positionM: v3(b.positionM), quaternion: [q.w, q.x, q.y, q.z] };
}

/** A 3D frame's plot sample: the axial force, the force across the shaft (magnitude) and the
 * torque's magnitude about the base. */
export function sample3Of(f: Frame, d: Tick3): ForceSample {
  const [fx, fy, fz] = v3(d.forceN);
  const [tx, ty, tz] = v3(d.torqueNm);
  const axis = needleAxis(d);
  const along = fx * axis[0] + fy * axis[1] + fz * axis[2];
  const lateral = Math.hypot(fx - along * axis[0], fy - along * axis[1], fz - along * axis[2]);
  return { timeS: f.timeS, depthMm: f.insertedLengthM * 1000, axialN: d.axialForceN, lateralN: lateral, torqueMnm: Math.hypot(tx, ty, tz) * 1000 };
}

/** The shaft's direction at the base (unit; +x if the frame has no shape). */
function needleAxis(d: Tick3): [number, number, number] {
  const s = d.needleShapeM;
  if (s.length < 2) return [1, 0, 0];
  const [a, b] = [v3(s[0]), v3(s[1])];
  const n = Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) || 1;
  return [(b[0] - a[0]) / n, (b[1] - a[1]) / n, (b[2] - a[2]) / n];
}
