//! Driving the needle from the tissue view: a drag inserts / withdraws along the needle (Alt: moves
//! the base freely, Shift: rotates), the wheel rotates; poses go out by unary SetPose, at most one
//! per 10 ms and two in flight, only the newest pending one kept. And the bevel flip.
import { create } from "@bufbuild/protobuf";
import { Pose2Schema, Pose3Schema } from "./gen/needlesim/v1/needlesim_pb";
import { auth, control } from "./api";
import { publish, status } from "./dom";
import type { Pose3 } from "./pose3";
import { type Pose, state } from "./state";
import { viewTransform } from "./view";
import { drivingToken } from "./training";

/** The pose to start from: the last commanded one, else the shown frame's base. */
/** This tab's id for SetPose: the server lets one controller drive at a time, and this tab's
 * poses share one control lease (another tab or client is refused while this one drives). */
const TAB_ID = `web-${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;

function currentPose(): Pose | null {
  const d = state.driving;
  if (d.commanded) return { ...d.commanded };
  const b = state.frame?.base;
  return b ? { xM: b.xM, yM: b.yM, thetaRad: b.thetaRad } : null;
}

function command(p: Pose): void {
  const d = state.driving;
  d.posesCommanded++;
  publish("posesCommanded", d.posesCommanded);
  publish("inFlight", d.inFlight);
  d.commanded = p;
  d.pending = p;
  pump();
}

/** Commands a 3D pose (a 3D session's driving: driving3.ts). */
export function command3(p: Pose3): void {
  const d = state.driving;
  d.posesCommanded++;
  publish("posesCommanded", d.posesCommanded);
  d.commanded3 = p;
  d.pending3 = p;
  pump();
}

/** The SetPose (2D) or SetPose3 call of the newest pending pose, or null when none waits. */
function nextCall(sessionId: string, token: string): (() => Promise<unknown>) | null {
  const d = state.driving;
  // The instructor's page drives with the instructor's token (training.ts).
  const opts = auth(drivingToken(token));
  if (d.pending3) {
    const p = d.pending3;
    d.pending3 = null;
    const [w, x, y, z] = p.quaternion;
    const [px, py, pz] = p.positionM;
    const base3 = create(Pose3Schema, { positionM: { x: px, y: py, z: pz }, orientation: { w, x, y, z } });
    return () => control.setPose3({ sessionId, base3, clientId: TAB_ID }, opts);
  }
  if (d.pending) {
    const p = d.pending;
    d.pending = null;
    const base = create(Pose2Schema, { xM: p.xM, yM: p.yM, thetaRad: p.thetaRad });
    return () => control.setPose({ sessionId, base, clientId: TAB_ID }, opts);
  }
  return null;
}

/** Sends the pending pose when the rate and the in-flight limit allow (else retries later). */
function pump(): void {
  const d = state.driving;
  const session = state.session;
  if (!(d.pending || d.pending3) || !session || d.inFlight >= 2) return;
  const now = performance.now();
  if (now - d.lastSentMs < 10) {
    setTimeout(pump, 10 - (now - d.lastSentMs));
    return;
  }
  const call = nextCall(session.id, session.token);
  if (!call) return;
  d.lastSentMs = now;
  d.inFlight++;
  call()
    .then(() => {
      d.posesAcked++;
      publish("poses", d.posesAcked);
    })
    .catch((e: unknown) => status(`SetPose: ${String(e)}`))
    .finally(() => {
      d.inFlight--;
      pump();
    });
}

/** Lets the mouse drive the needle on this canvas (the tissue view). */
export function installDriving(view: HTMLCanvasElement): void {
  view.addEventListener("mousedown", (ev) => {
    if (state.mode !== "live" || state.dim !== 2) return;
    const start = currentPose();
    if (!start) return;
    const r = view.getBoundingClientRect();
    const mPerClientPx = view.width / r.width / viewTransform(view, state).s;
    state.driving.drag = { start, clientX: ev.clientX, clientY: ev.clientY, mPerClientPx, free: ev.altKey, rotate: ev.shiftKey };
    ev.preventDefault();
  });

  window.addEventListener("mousemove", (ev) => {
    const drag = state.driving.drag;
    if (!drag) return;
    // World y points up, client y down.
    const dx = (ev.clientX - drag.clientX) * drag.mPerClientPx;
    const dy = -(ev.clientY - drag.clientY) * drag.mPerClientPx;
    const s = drag.start;
    if (drag.rotate) {
      command({ ...s, thetaRad: s.thetaRad + (ev.clientX - drag.clientX) * 0.005 });
    } else if (drag.free) {
      command({ ...s, xM: s.xM + dx, yM: s.yM + dy });
    } else {
      const c = Math.cos(s.thetaRad), sn = Math.sin(s.thetaRad);
      const along = dx * c + dy * sn;
      command({ ...s, xM: s.xM + along * c, yM: s.yM + along * sn });
    }
  });

  window.addEventListener("mouseup", () => {
    state.driving.drag = null;
  });

  view.addEventListener(
    "wheel",
    (ev) => {
      if (state.mode !== "live" || state.dim !== 2) return;
      const p = currentPose();
      if (!p) return;
      ev.preventDefault();
      command({ ...p, thetaRad: p.thetaRad - Math.sign(ev.deltaY) * 0.01 });
    },
    { passive: false },
  );
}

/** Turns the needle 180° about its axis (a bevel tip then faces the other side). */
/** SetSpin (3D): duty-cycled spinning at the duty in [0, 1] (0 stops), 1 mm per turn. */
export async function setSpin(dutyCycle: number): Promise<void> {
  const session = state.session;
  if (!session) return status("watch a session first");
  try {
    const r = await control.setSpin({ sessionId: session.id, dutyCycle, periodM: 0, clientId: TAB_ID }, auth(session.token));
    status(r.dutyCycle > 0 ? `spinning: duty ${r.dutyCycle}, one turn per ${(r.periodM * 1e3).toFixed(1)} mm` : "spin stopped");
  } catch (e) {
    status(`SetSpin: ${String(e)}`);
  }
}

export async function flipBevel(): Promise<void> {
  const session = state.session;
  if (!session) return status("watch a session first");
  try {
    const r = await control.flipBevel({ sessionId: session.id, clientId: TAB_ID }, auth(session.token));
    status(`bevel flip ${r.flipsRequested} requested`);
  } catch (e) {
    status(`FlipBevel: ${String(e)}`);
  }
}
