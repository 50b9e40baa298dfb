//! The viewer's state: one explicit object, owned by the page, that every module reads and
//! writes (instead of module-level variables), and the resets that go with a new session.
import type { Frame } from "./gen/needlesim/v1/needlesim_pb";
import type { Bounds, MeshGeom } from "./mesh";
import { ForceHistory } from "./history";
import type { Pose3 } from "./pose3";
import type { Surface3 } from "./view3";

/** A needle base pose: position (m) and direction (rad). */
export interface Pose {
  xM: number;
  yM: number;
  thetaRad: number;
}

/** A mouse drag on the tissue view, from its start. */
export interface Drag {
  /** The pose when the drag began. */
  start: Pose;
  /** Where it began, in client pixels (CSS). */
  clientX: number;
  clientY: number;
  /** Metres per client pixel, frozen when the drag began: the drag follows the mouse's travel
   * even if the page's layout shifts under it (issue 15's CI run: a header that wrapped mid-drag
   * moved the canvas and shortened the insertion). */
  mPerClientPx: number;
  /** Alt: move the base freely; Shift: rotate. */
  free: boolean;
  rotate: boolean;
}

export interface DrivingState {
  /** The pose last commanded from the page (null: follow the frames). */
  commanded: Pose | null;
  /** The pose waiting to be sent (only the newest is kept). */
  pending: Pose | null;
  /** The same for a 3D session. */
  commanded3: Pose3 | null;
  pending3: Pose3 | null;
  /** SetPose calls in flight (at most two). */
  inFlight: number;
  /** When the last SetPose went out (performance.now(), ms). */
  lastSentMs: number;
  /** Poses commanded by the mouse / wheel, and poses the server acknowledged. */
  posesCommanded: number;
  posesAcked: number;
  drag: Drag | null;
}

export interface PlaybackState {
  /** The frames of the loaded recording (at most ~5000, evenly thinned). */
  frames: Frame[];
  /** Their force history, for the plots. */
  history: ForceHistory | null;
  playing: boolean;
  /** When ▶ was pressed (performance.now(), ms) and the recording's time then (s). */
  startedMs: number;
  startedSimS: number;
}

export interface ViewerState {
  /** The watched session and the token used for it. */
  session: { id: string; token: string } | null;
  mode: "live" | "playback";
  mesh: MeshGeom | null;
  /** 2 or 3: the watched session's (or the played recording's) dimension. */
  dim: 2 | 3;
  /** A 3D session's tissue surface (GetSurface). */
  surface3: Surface3 | null;
  /** The frame shown (the latest live one, or the playback cursor's). */
  frame: Frame | null;
  /** Frames received from the live stream of this session. */
  framesReceived: number;
  /** Aborts the live stream. */
  streamAbort: AbortController | null;
  /** The live force history (a bounded ring against time, a thinned trace against depth). */
  history: ForceHistory;
  /** |tip − base| of the last frame that had a tip (for frames without a needle shape). */
  needleLengthM: number;
  /** The strain that maps to the top of the colour scale. */
  strainScale: number;
  /** The tissue view's world box, fixed once per session. */
  viewBounds: Bounds | null;
  /** Something changed since the last draw. */
  dirty: boolean;
  driving: DrivingState;
  playback: PlaybackState;
}

export const state: ViewerState = {
  session: null,
  mode: "live",
  mesh: null,
  dim: 2,
  surface3: null,
  frame: null,
  framesReceived: 0,
  streamAbort: null,
  history: new ForceHistory(),
  needleLengthM: 0,
  strainScale: 1e-3,
  viewBounds: null,
  dirty: true,
  driving: { commanded: null, pending: null, commanded3: null, pending3: null, inFlight: 0, lastSentMs: 0, posesCommanded: 0, posesAcked: 0, drag: null },
  playback: { frames: [], history: null, playing: false, startedMs: 0, startedSimS: 0 },
};

/** Forgets what belonged to the previous session (its mesh, frames, history and commanded pose). */
export function resetForSession(id: string, token: string): void {
  state.mode = "live";
  state.session = { id, token };
  state.mesh = null;
  state.dim = 2;
  state.surface3 = null;
  state.frame = null;
  state.viewBounds = null;
  state.history.clear();
  state.framesReceived = 0;
  state.driving.commanded = null;
  state.driving.commanded3 = null;
  state.dirty = true;
}
