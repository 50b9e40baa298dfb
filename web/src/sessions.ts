//! Sessions: the server's list, creating one from a shipped example, and watching one (its mesh
//! once, then its live frame stream).
import { auth, observe, sessions, tokens } from "./api";
import { $, publish, status } from "./dom";
import { buildMesh } from "./mesh";
import { sample3Of, surface3Of } from "./frame3";
import { showFrame, showFramesReceived } from "./readout";
import { resetForSession, state } from "./state";
import { sampleOf } from "./history";
import { watchTraining } from "./training";

const sessionSelect = (): HTMLSelectElement => $("session-select", HTMLSelectElement);
const tokenInput = (): HTMLInputElement => $("token", HTMLInputElement);

/** Lists the server's sessions, keeping (or selecting) `select`; fills in a known token. */
export async function refreshSessions(select?: string): Promise<void> {
  const list = sessionSelect();
  try {
    const res = await sessions.listSessions({});
    const keep = select ?? list.value;
    list.replaceChildren(
      ...res.sessions.map((s) => {
        const o = document.createElement("option");
        o.value = s.sessionId;
        o.textContent = `${s.sessionId} (${s.sceneName}, ${s.nNodes} nodes${tokens.has(s.sessionId) ? ", token known" : ""})`;
        return o;
      }),
    );
    if (keep && res.sessions.some((s) => s.sessionId === keep)) list.value = keep;
    const known = tokens.get(list.value);
    if (known) tokenInput().value = known;
  } catch (e) {
    status(`ListSessions: ${String(e)}`);
  }
}

/** Creates a session of the chosen example, keeps its controller token and watches it. */
export async function createFromExample(): Promise<void> {
  const example = $("example-select", HTMLSelectElement).value;
  try {
    status(`creating a session of ${example}…`);
    const res = await sessions.createSession({ scene: { source: { case: "example", value: example } } });
    const id = res.session?.sessionId ?? "";
    tokens.set(id, res.controllerToken);
    await refreshSessions(id);
    tokenInput().value = res.controllerToken;
    status("");
    await watch(id, res.controllerToken);
  } catch (e) {
    status(`CreateSession: ${String(e)}`);
  }
}

/** Watches the selected session with the pasted token. */
export function watchSelected(): void {
  const id = sessionSelect().value;
  const token = tokenInput().value.trim();
  if (!id) return status("no session selected");
  if (!token) return status("paste the session's controller or observer token (printed in the server log)");
  void watch(id, token);
}

/** Fills in the known token of the selected session (or clears the field). */
export function selectedSessionChanged(): void {
  tokenInput().value = tokens.get(sessionSelect().value) ?? "";
}

/** Shows a session live: its mesh, then its frames at 60 Hz with displacements, until another
 * session is watched or the stream ends. */
export async function watch(id: string, token: string): Promise<void> {
  state.streamAbort?.abort();
  resetForSession(id, token);
  tokens.set(id, token);
  showFramesReceived(0);
  publish("session", id);
  const url = new URL(window.location.href);
  url.searchParams.set("session", id);
  url.searchParams.set("token", token);
  window.history.replaceState(null, "", url);
  try {
    const info = await sessions.getSession({ sessionId: id }, auth(token));
    if (info.dimension === 3) {
      state.surface3 = surface3Of(await sessions.getSurface({ sessionId: id }, auth(token)));
      state.dim = 3;
    } else {
      state.mesh = buildMesh(await sessions.getMesh({ sessionId: id }, auth(token)));
    }
    publish("dim", state.dim);
  } catch (e) {
    status(`opening the session: ${String(e)}`);
    return;
  }
  const abort = new AbortController();
  state.streamAbort = abort;
  // An exercise session's score, control and ultrasound slice (training.ts; hidden otherwise).
  void watchTraining(id, token);
  publish("state", "live");
  status("");
  try {
    const stream = observe.observe({ sessionId: id, rateHz: 60, includeDisplacements: true }, { ...auth(token), signal: abort.signal });
    for await (const f of stream) {
      showFramesReceived(++state.framesReceived);
      state.history.push(f.d3 ? sample3Of(f, f.d3) : sampleOf(f));
      if (state.mode === "live") showFrame(f);
    }
    if (!abort.signal.aborted) status("the session's frame stream ended");
  } catch (e) {
    if (!abort.signal.aborted) status(`Observe: ${String(e)}`);
  }
}
