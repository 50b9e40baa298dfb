//! Training (issue 20): exercise sessions in the viewer — starting one from a shipped exercise,
//! the live score and who is in control (GetStatus, polled: see watchTraining), "Placed", the
//! instructor's buttons (take control, hand back, pause, marker, end), the report, and the
//! simulated ultrasound slice
//! (WatchUltrasound, 8-bit gray drawn on a canvas beside the tissue view). A page opened with
//! `?session=ID&token=T&instructor=I` is the instructor's: it watches with T and drives and
//! instructs with I. Publishes `data-exercise`, `data-score`, `data-controller`,
//! `data-ultrasound-frames` and `data-ultrasound-tick` on `<body>` for tests.
import { Code, ConnectError } from "@connectrpc/connect";
import { auth, training } from "./api";
import { $, publish, status } from "./dom";
import { ControllerRole, type ExerciseStatus, type UltrasoundImage } from "./gen/needlesim/v1/training_pb";
import { state } from "./state";

/** The training part of the page's state. */
interface TrainingState {
  /** The watched session's exercise streams. */
  abort: AbortController | null;
  /** The instructor's token, when this page is the instructor's. */
  instructorToken: string | null;
  last: ExerciseStatus | null;
  ultrasoundFrames: number;
}

const tr: TrainingState = { abort: null, instructorToken: null, last: null, ultrasoundFrames: 0 };

/** The token that drives (the instructor's on the instructor's page). */
export function drivingToken(sessionToken: string): string {
  return tr.instructorToken ?? sessionToken;
}

/** Sets the instructor's token (from the URL) before a session is watched. */
export function setInstructorToken(token: string | null): void {
  tr.instructorToken = token;
}

const mm = (m: number): string => (m * 1e3).toFixed(1);

function controllerLabel(c: ControllerRole): string {
  return c === ControllerRole.INSTRUCTOR ? "instructor" : "trainee";
}

/** Shows a status message in the panel. */
function showStatus(st: ExerciseStatus): void {
  tr.last = st;
  $("ex-name").textContent = st.exercise;
  $("ex-score").textContent = st.score.toFixed(1);
  const who = controllerLabel(st.controller);
  $("ex-controller").textContent = who + (st.paused ? " (paused)" : "");
  $("ex-time").textContent = `${st.timeS.toFixed(1)} s`;
  $("ex-depth").textContent = `${mm(st.depthM)} mm`;
  $("ex-peak").textContent = `${st.peakAxialForceN.toFixed(2)} N`;
  $("ex-counts").textContent = `${st.insertions} / ${st.redirections}`;
  $("ex-targets").textContent = st.targets
    .map((t) => (t.placement ? `${t.name}: ${mm(t.placement.errorM)} mm${t.placement.onTarget ? " ✓" : ""}` : `${t.name}: –`))
    .join(", ");
  $("ex-markers").textContent = st.markers.map((m) => `${m.tS.toFixed(1)} s ${m.label}`).join(" · ");
  $("ex-state").textContent = st.finished ? "finished" : "running";
  $("ex-report", HTMLButtonElement).disabled = !st.finished;
  publish("score", st.score.toFixed(3));
  publish("controller", who);
  publish("paused", st.paused ? "1" : "0");
  publish("exerciseFinished", st.finished ? "1" : "0");
}

/** Draws an 8-bit gray image on the ultrasound canvas (resized to it). */
function drawSlice(img: UltrasoundImage): void {
  const canvas = $("ultrasound", HTMLCanvasElement);
  if (canvas.width !== img.width || canvas.height !== img.height) {
    canvas.width = img.width;
    canvas.height = img.height;
  }
  const ctx = canvas.getContext("2d");
  if (!ctx) return;
  const data = ctx.createImageData(img.width, img.height);
  const g = img.gray8;
  for (let i = 0; i < g.length; i++) {
    data.data[4 * i] = g[i];
    data.data[4 * i + 1] = g[i];
    data.data[4 * i + 2] = g[i];
    data.data[4 * i + 3] = 255;
  }
  ctx.putImageData(data, 0, 0);
  publish("ultrasoundFrames", ++tr.ultrasoundFrames);
  publish("ultrasoundTick", String(img.tick));
}

/** Shows or hides the panel and the slice; the instructor's buttons only on the instructor's page. */
function showPanel(on: boolean): void {
  $("training").hidden = !on;
  $("ultrasound-wrap").hidden = !on;
  $("ex-instructor").hidden = !(on && tr.instructorToken);
}

/** Follows the watched session's exercise, if it is one: its score and its ultrasound slice,
 * until another session is watched. */
export async function watchTraining(id: string, token: string): Promise<void> {
  tr.abort?.abort();
  tr.last = null;
  tr.ultrasoundFrames = 0;
  const abort = new AbortController();
  tr.abort = abort;
  const opts = { ...auth(token), signal: abort.signal };
  let first: ExerciseStatus;
  try {
    first = await training.getStatus({ sessionId: id }, auth(token));
  } catch (e) {
    showPanel(false);
    publish("exercise", "none");
    if (!(e instanceof ConnectError && e.code === Code.FailedPrecondition)) status(`GetStatus: ${String(e)}`);
    return;
  }
  showPanel(true);
  showStatus(first);
  publish("exercise", first.exercise);
  void (async () => {
    try {
      for await (const img of training.watchUltrasound({ sessionId: id, rateHz: 15 }, opts)) drawSlice(img);
    } catch (e) {
      if (!abort.signal.aborted) status(`WatchUltrasound: ${String(e)}`);
    }
  })();
  // The score by polling GetStatus (5 Hz) rather than the WatchScore stream: gRPC-web runs over
  // HTTP/1.1, where a browser keeps at most 6 connections per server and every open stream holds
  // one — with the frames and the slice streaming, a third stream per tab leaves a second tab
  // (an observer beside the trainee) no connection for its SetPose calls.
  while (!abort.signal.aborted) {
    await new Promise((r) => setTimeout(r, SCORE_POLL_MS));
    if (abort.signal.aborted) return;
    try {
      const st = await training.getStatus({ sessionId: id }, opts);
      if (!abort.signal.aborted) showStatus(st);
    } catch (e) {
      if (!abort.signal.aborted) status(`GetStatus: ${String(e)}`);
      return;
    }
  }
}

/** How often the page asks for the exercise's status, ms. */
const SCORE_POLL_MS = 200;

/** Runs a training call with the driving token, showing the status it returns or its error. */
async function call(what: string, f: (id: string, opts: { headers: Record<string, string> }) => Promise<ExerciseStatus | undefined>): Promise<void> {
  const s = state.session;
  if (!s) return;
  try {
    const st = await f(s.id, auth(drivingToken(s.token)));
    if (st) showStatus(st);
    status("");
  } catch (e) {
    status(`${what}: ${e instanceof ConnectError ? e.rawMessage : String(e)}`);
  }
}

/** Starts a session of the chosen exercise; this page becomes the trainee's and shows the
 * instructor's and the observers' links. Returns the session id and the trainee's token. */
export async function createExercise(): Promise<{ id: string; token: string } | null> {
  const exercise = $("exercise-select", HTMLSelectElement).value;
  try {
    status(`starting exercise ${exercise}…`);
    const res = await training.createExerciseSession({ exercise });
    const s = res.session;
    const id = s?.session?.sessionId ?? "";
    if (!s || !id) throw new Error("no session in the answer");
    const link = (params: Record<string, string>): string => {
      const u = new URL(window.location.href);
      u.search = new URLSearchParams({ session: id, ...params }).toString();
      return u.toString();
    };
    const set = (elId: string, href: string): void => {
      const a = $(elId, HTMLAnchorElement);
      a.href = href;
      a.hidden = false;
    };
    set("link-trainee", link({ token: s.controllerToken }));
    set("link-instructor", link({ token: s.observerToken, instructor: res.instructorToken }));
    set("link-observer", link({ token: s.observerToken }));
    tr.instructorToken = null;
    status("");
    return { id, token: s.controllerToken };
  } catch (e) {
    status(`CreateExerciseSession: ${String(e)}`);
    return null;
  }
}

/** Wires the panel's buttons. */
export function installTraining(): void {
  $("ex-place").addEventListener("click", () => void call("Place", async (sessionId, o) => (await training.place({ sessionId }, o)).status));
  $("ex-take").addEventListener("click", () => void call("TakeControl", (sessionId, o) => training.takeControl({ sessionId }, o)));
  $("ex-hand-back").addEventListener("click", () => void call("HandBackControl", (sessionId, o) => training.handBackControl({ sessionId }, o)));
  $("ex-pause").addEventListener(
    "click",
    () => void call("SetPaused", (sessionId, o) => training.setPaused({ sessionId, paused: !(tr.last?.paused ?? false) }, o)),
  );
  $("ex-reset").addEventListener("click", () => void call("ResetExercise", (sessionId, o) => training.resetExercise({ sessionId }, o)));
  $("ex-add-marker").addEventListener(
    "click",
    () =>
      void call("AddMarker", async (sessionId, o) => {
        await training.addMarker({ sessionId, label: $("ex-marker-label", HTMLInputElement).value }, o);
        return training.getStatus({ sessionId }, o);
      }),
  );
  $("ex-end").addEventListener("click", () => void call("EndExercise", (sessionId, o) => training.endExercise({ sessionId }, o)));
  $("ex-report").addEventListener("click", () => void openReport());
}

/** Downloads the ended exercise's report and opens it in a new tab. */
async function openReport(): Promise<void> {
  const s = state.session;
  if (!s) return;
  try {
    const parts: Uint8Array[] = [];
    for await (const c of training.getReport({ sessionId: s.id }, auth(s.token))) parts.push(c.html);
    const blob = new Blob(parts as BlobPart[], { type: "text/html" });
    window.open(URL.createObjectURL(blob), "_blank");
  } catch (e) {
    status(`GetReport: ${String(e)}`);
  }
}
