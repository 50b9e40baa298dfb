//! Needle base poses in 3D and the mouse's moves on them: the needle is the base's local +x axis
//! (as the server's `Pose3`: position in metres, unit quaternion w, x, y, z, world frame);
//! inserting moves the base along it, tilting turns the axis about a world direction through the
//! base, rolling turns the base about its own axis.
import * as THREE from "three";

export interface Pose3 {
  positionM: [number, number, number];
  /** Unit quaternion [w, x, y, z]. */
  quaternion: [number, number, number, number];
}

const toThree = (q: Pose3["quaternion"]): THREE.Quaternion => new THREE.Quaternion(q[1], q[2], q[3], q[0]);
const fromThree = (q: THREE.Quaternion): Pose3["quaternion"] => {
  q.normalize();
  return [q.w, q.x, q.y, q.z];
};

/** The needle's direction (world, unit): R e_x. */
export function axisOf(p: Pose3): THREE.Vector3 {
  return new THREE.Vector3(1, 0, 0).applyQuaternion(toThree(p.quaternion));
}

/** Moves the base `dM` metres along the needle (positive: inserting). */
export function insert(p: Pose3, dM: number): Pose3 {
  const a = axisOf(p).multiplyScalar(dM);
  return { positionM: [p.positionM[0] + a.x, p.positionM[1] + a.y, p.positionM[2] + a.z], quaternion: [...p.quaternion] };
}

/** Turns the needle by `angleRad` about the world direction `axis` (through the base). */
export function tilt(p: Pose3, axis: THREE.Vector3, angleRad: number): Pose3 {
  const r = new THREE.Quaternion().setFromAxisAngle(axis.clone().normalize(), angleRad);
  return { positionM: [...p.positionM], quaternion: fromThree(r.multiply(toThree(p.quaternion))) };
}

/** Rolls the needle by `angleRad` about its own axis (a bevel tip turns with it). */
export function roll(p: Pose3, angleRad: number): Pose3 {
  const r = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), angleRad);
  return { positionM: [...p.positionM], quaternion: fromThree(toThree(p.quaternion).multiply(r)) };
}
