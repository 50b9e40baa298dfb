//! Driving a 3D session's needle with the mouse on the 3D view. A plain drag orbits the camera
//! (three.js OrbitControls); with Ctrl held, a vertical drag inserts (up) or withdraws (down)
//! along the needle; Ctrl+Shift tilts the needle about the camera's axes through the base; Alt
//! rolls it about its own axis. Poses go out through `send` (unary SetPose, rate-limited by the
//! caller's pump).
import * as THREE from "three";
import { insert, type Pose3, roll, tilt } from "./pose3";

/** Metres of insertion per pixel of drag. */
export const INSERT_M_PER_PX = 0.1e-3;
/** Radians of tilt or roll per pixel of drag. */
export const TURN_RAD_PER_PX = 0.004;

interface Drag3 {
  start: Pose3;
  clientX: number;
  clientY: number;
  mode: "insert" | "tilt" | "roll";
}

/** The mode a mouse-down with these modifiers drives, or null (the camera orbits). */
export function modeOf(ev: { ctrlKey: boolean; shiftKey: boolean; altKey: boolean }): Drag3["mode"] | null {
  if (ev.altKey) return "roll";
  if (ev.ctrlKey && ev.shiftKey) return "tilt";
  if (ev.ctrlKey) return "insert";
  return null;
}

/** The pose a drag of (dx, dy) client pixels gives, from `start`. */
export function dragged(start: Pose3, mode: Drag3["mode"], dxPx: number, dyPx: number, camera: THREE.Camera): Pose3 {
  switch (mode) {
    case "insert":
      return insert(start, -dyPx * INSERT_M_PER_PX);
    case "roll":
      return roll(start, dxPx * TURN_RAD_PER_PX);
    case "tilt": {
      // Horizontal drag: about the camera's up axis; vertical: about its right axis.
      const up = new THREE.Vector3(0, 1, 0).applyQuaternion(camera.quaternion);
      const right = new THREE.Vector3(1, 0, 0).applyQuaternion(camera.quaternion);
      return tilt(tilt(start, up, dxPx * TURN_RAD_PER_PX), right, dyPx * TURN_RAD_PER_PX);
    }
  }
}

/**
 * Lets the mouse drive on `canvas`. `current()` is the pose to start a drag from (the last
 * commanded one, else the shown frame's); `send(pose)` commands one; `setOrbit(on)` turns the
 * camera's own mouse handling off during a drive.
 */
export function installDriving3(
  canvas: HTMLCanvasElement,
  camera: () => THREE.Camera,
  current: () => Pose3 | null,
  send: (p: Pose3) => void,
  setOrbit: (on: boolean) => void,
): void {
  let drag: Drag3 | null = null;
  canvas.addEventListener(
    "pointerdown",
    (ev) => {
      const mode = modeOf(ev);
      const start = current();
      if (!mode || !start) return;
      drag = { start, clientX: ev.clientX, clientY: ev.clientY, mode };
      setOrbit(false);
      ev.preventDefault();
      ev.stopImmediatePropagation();
    },
    { capture: true },
  );
  window.addEventListener("pointermove", (ev) => {
    if (!drag) return;
    send(dragged(drag.start, drag.mode, ev.clientX - drag.clientX, ev.clientY - drag.clientY, camera()));
  });
  window.addEventListener("pointerup", () => {
    if (!drag) return;
    drag = null;
    setOrbit(true);
  });
}
