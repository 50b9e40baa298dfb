//! The needlesim web viewer: a gRPC-web client of needlesim-server (connect-web), served by the
//! server itself. Draws the deformed mesh coloured by strain, the needle and targets, plots forces
//! against time and depth (uPlot), drives the needle with the mouse (unary SetPose) and plays back
//! MCAP recordings downloaded from the server. This entry wires the page's controls to the modules
//! and runs the draw loop.
import "uplot/dist/uPlot.min.css";
import "./style.css";
import { tokens } from "./api";
import { $, publish } from "./dom";
import { flipBevel, installDriving, setSpin } from "./driving";
import { sampleOf } from "./history";
import { ForcePlots } from "./plots";
import { loadRecording, refreshRecordings, sliderMoved, startStopRecording, stopPlaying, togglePlay } from "./recordings";
import { createFromExample, refreshSessions, selectedSessionChanged, watch, watchSelected } from "./sessions";
import { state } from "./state";
import { drawView } from "./view";
import { command3 } from "./driving";
import { installDriving3 } from "./driving3";
import { pose3Of, scene3Of } from "./frame3";
import { TissueView3 } from "./view3";
import { createExercise, installTraining, setInstructorToken } from "./training";

/** The live time plot's window (s). */
const LIVE_WINDOW_S = 20;
const PLOT_WIDTH_PX = 500;
const PLOT_HEIGHT_PX = 220;

const view = $("view", HTMLCanvasElement);
const view3Canvas = $("view3", HTMLCanvasElement);
/** The 3D view, made when the first 3D session is shown (WebGL only then). */
let view3: TissueView3 | null = null;
let view3Surface: unknown = null;
let view3Draws = 0;

/** Shows the 2D or the 3D view, as the session is; draws the 3D one. */
function render3(): void {
  const is3 = state.dim === 3;
  view.hidden = is3;
  view3Canvas.hidden = !is3;
  $("controls3").hidden = !is3;
  if (!is3 || !state.surface3) return;
  if (!view3) {
    view3 = new TissueView3(view3Canvas);
    const v = view3;
    installDriving3(
      view3Canvas,
      () => v.camera,
      () => state.driving.commanded3 ?? (state.frame?.d3 ? pose3Of(state.frame.d3) : null),
      (p) => {
        if (state.mode === "live") command3(p);
      },
      (on) => {
        v.controls.enabled = on;
      },
    );
    v.controls.addEventListener("change", () => {
      state.dirty = true;
    });
  }
  if (view3Surface !== state.surface3) {
    view3Surface = state.surface3;
    view3.setSurface(state.surface3);
  }
  view3.setSection($("section-on", HTMLInputElement).checked, Number($("section-at", HTMLInputElement).value));
  const s = state.frame ? scene3Of(state.frame) : null;
  if (s) view3.show(s);
  view3.render();
  publish("view3Draws", ++view3Draws);
}
const plots = new ForcePlots($("plot-time"), $("plot-depth"), PLOT_WIDTH_PX, PLOT_HEIGHT_PX);

/** Draws what changed, once per animation frame: the tissue view and the plots. */
function render(): void {
  if (state.dirty) {
    state.dirty = false;
    if (state.dim === 3) render3();
    else {
      view3Canvas.hidden = true;
      $("controls3").hidden = true;
      view.hidden = false;
      drawView(view, state);
    }
    const pb = state.playback;
    if (state.mode === "playback" && pb.history) {
      plots.show(pb.history, null, state.frame ? sampleOf(state.frame) : null);
    } else {
      plots.show(state.history, LIVE_WINDOW_S, null);
    }
  }
  requestAnimationFrame(render);
}

installDriving(view);
$("refresh-sessions").addEventListener("click", () => void refreshSessions());
$("session-select").addEventListener("change", selectedSessionChanged);
$("connect").addEventListener("click", watchSelected);
$("create").addEventListener("click", () => void createFromExample());
$("flip-bevel").addEventListener("click", () => void flipBevel());
$("spin").addEventListener("click", () => void setSpin(Number(($("spin-duty") as HTMLInputElement).value)));
$("rec-refresh").addEventListener("click", () => void refreshRecordings());
$("rec-start").addEventListener("click", () => void startStopRecording(true));
$("rec-stop").addEventListener("click", () => void startStopRecording(false));
$("rec-load").addEventListener("click", () => void loadRecording());
$("live").addEventListener("click", () => {
  stopPlaying();
  if (state.session) void watch(state.session.id, state.session.token);
});
$("slider").addEventListener("input", sliderMoved);
for (const id of ["section-on", "section-at"]) {
  $(id).addEventListener("input", () => {
    state.dirty = true;
  });
}
$("play").addEventListener("click", togglePlay);
installTraining();
$("create-exercise").addEventListener("click", () => {
  void (async () => {
    const made = await createExercise();
    if (!made) return;
    tokens.set(made.id, made.token);
    await refreshSessions(made.id);
    $("token", HTMLInputElement).value = made.token;
    await watch(made.id, made.token);
  })();
});

async function main(): Promise<void> {
  requestAnimationFrame(render);
  const params = new URLSearchParams(window.location.search);
  const sid = params.get("session");
  const tok = params.get("token");
  setInstructorToken(params.get("instructor"));
  if (sid && tok) tokens.set(sid, tok);
  await refreshSessions(sid ?? undefined);
  void refreshRecordings();
  publish("ready", "1");
  if (sid && tok) {
    $("token", HTMLInputElement).value = tok;
    await watch(sid, tok);
  }
}

void main();
