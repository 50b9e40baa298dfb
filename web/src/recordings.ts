//! Recordings: start / stop one of the watched session, list the server's, download one and play
//! its frames back (MCAP parsed in the page: zstd by fzstd, lz4 by lz4js) with a slider and ▶:
//! 2D or 3D, drawn on the tissue the recording carries (its mesh or surface, once) and deformed
//! by the displacement field it carries (10 times a second; recordings started here ask for it).
import { fromBinary } from "@bufbuild/protobuf";
import { McapStreamReader } from "@mcap/core";
import { decompress as zstdDecompress } from "fzstd";
import { decompress as lz4Decompress } from "lz4js";
import { type Frame, FrameSchema, type Mesh, MeshSchema, type Surface, SurfaceSchema } from "./gen/needlesim/v1/needlesim_pb";
import { surface3Of } from "./frame3";
import { auth, recordings, sessions, tokens } from "./api";
import { $, publish, status } from "./dom";
import { buildMesh } from "./mesh";
import { ForceHistory, sampleOf } from "./history";
import { showFrame } from "./readout";
import { state } from "./state";

/** At most this many frames go on the timeline (recordings hold every tick). */
const MAX_PLAYBACK_FRAMES = 5000;

const recSelect = (): HTMLSelectElement => $("rec-select", HTMLSelectElement);
const slider = (): HTMLInputElement => $("slider", HTMLInputElement);

export async function refreshRecordings(): Promise<void> {
  try {
    // A recording opens with the token of the session that made it: list those of the session watched.
    const res = await recordings.listRecordings({}, state.session ? auth(state.session.token) : {});
    recSelect().replaceChildren(
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

/** Starts or stops recording the watched session (controller token), then selects the file. */
export async function startStopRecording(start: boolean): Promise<void> {
  const session = state.session;
  if (!session) return status("watch a session first");
  try {
    const req = { sessionId: session.id };
    // With the displacement field, so that playback draws the deformed tissue.
    const info = start
      ? await recordings.startRecording({ ...req, includeDisplacements: true }, auth(session.token))
      : await recordings.stopRecording(req, auth(session.token));
    status(`${start ? "recording to" : "recorded"} ${info.name}`);
    await refreshRecordings();
    recSelect().value = info.name;
  } catch (e) {
    status(`${start ? "StartRecording" : "StopRecording"}: ${String(e)}`);
  }
}

/** What a recording holds for playback. */
export interface Recording {
  frames: Frame[];
  /** The tissue (/needlesim/tissue): a 2D session's mesh or a 3D one's surface, if recorded. */
  mesh: Mesh | null;
  surface: Surface | null;
}

/** The frames and the tissue of an MCAP file (chunked, zstd / lz4 / uncompressed; finished or not). */
export function parseMcap(bytes: Uint8Array): Recording {
  const reader = new McapStreamReader({
    decompressHandlers: {
      zstd: (buf, size) => zstdDecompress(buf, new Uint8Array(Number(size))),
      lz4: (buf, size) => Uint8Array.from(lz4Decompress(buf, Number(size))),
    },
  });
  reader.append(bytes);
  const channelSchema = new Map<number, string>();
  const schemas = new Map<number, string>();
  const out: Recording = { frames: [], mesh: null, surface: null };
  for (let rec = reader.nextRecord(); rec; rec = reader.nextRecord()) {
    if (rec.type === "Schema") schemas.set(rec.id, rec.name);
    else if (rec.type === "Channel") channelSchema.set(rec.id, schemas.get(rec.schemaId) ?? "");
    else if (rec.type === "Message") {
      const schema = channelSchema.get(rec.channelId);
      if (schema === "needlesim.v1.Frame") out.frames.push(fromBinary(FrameSchema, rec.data));
      else if (schema === "needlesim.v1.Mesh") out.mesh = fromBinary(MeshSchema, rec.data);
      else if (schema === "needlesim.v1.Surface") out.surface = fromBinary(SurfaceSchema, rec.data);
    }
  }
  return out;
}

/** Gives every frame the latest displacement field at or before it (the recording carries one
 * every 0.1 s): frames share the field's array, nothing is copied. Returns how many frames
 * carried a field of their own. */
function carryFields(frames: Frame[]): number {
  let node: number[] = [];
  let surface: number[] = [];
  let fields = 0;
  for (const f of frames) {
    if (f.nodeDisplacementM.length || f.surfaceDisplacementM.length) fields++;
    if (f.nodeDisplacementM.length) node = f.nodeDisplacementM;
    else if (node.length) f.nodeDisplacementM = node;
    if (f.surfaceDisplacementM.length) surface = f.surfaceDisplacementM;
    else if (surface.length) f.surfaceDisplacementM = surface;
  }
  return fields;
}

/** Downloads the selected recording and shows its first frame in playback mode. */
export async function loadRecording(): Promise<void> {
  const name = recSelect().value;
  if (!name) return status("no recording selected");
  try {
    status(`downloading ${name}…`);
    const parts: Uint8Array[] = [];
    let total = 0;
    for await (const chunk of recordings.downloadRecording({ name }, state.session ? auth(state.session.token) : {})) {
      parts.push(chunk.data);
      total += chunk.data.length;
    }
    const bytes = new Uint8Array(total);
    let off = 0;
    for (const p of parts) {
      bytes.set(p, off);
      off += p.length;
    }
    const rec = parseMcap(bytes);
    const all = rec.frames;
    if (!all.length) return status(`${name} holds no frames`);
    const fields = carryFields(all);
    const step = Math.max(1, Math.ceil(all.length / MAX_PLAYBACK_FRAMES));
    const frames = all.filter((_, i) => i % step === 0);
    // The tissue: the recording's own, else (older recordings) its session's, when it is still
    // open and its token known.
    const sid = name.replace(/-\d{8}T\d{6}Z.*$/, "");
    const tok = tokens.get(sid) ?? (state.session?.id === sid ? state.session.token : undefined);
    if (rec.surface) {
      state.surface3 = surface3Of(rec.surface);
      state.dim = 3;
    } else if (rec.mesh) {
      state.mesh = buildMesh(rec.mesh);
      state.viewBounds = null;
      state.dim = 2;
    } else if (tok && state.session?.id !== sid) {
      try {
        state.mesh = buildMesh(await sessions.getMesh({ sessionId: sid }, auth(tok)));
        state.viewBounds = null;
      } catch {
        /* draw without the mesh */
      }
    }
    const pb = state.playback;
    pb.frames = frames;
    pb.history = ForceHistory.of(frames.map(sampleOf));
    state.mode = "playback";
    publish("state", "playback");
    publish("playbackFrames", frames.length);
    publish("dim", state.dim);
    publish("playbackFields", fields);
    const s = slider();
    s.max = String(frames.length - 1);
    s.value = "0";
    showPlaybackFrame(0);
    status(`${name}: ${all.length} frames${step > 1 ? `, every ${step}th shown` : ""}`);
  } catch (e) {
    status(`DownloadRecording: ${String(e)}`);
  }
}

function showPlaybackFrame(i: number): void {
  const f = state.playback.frames[i];
  if (!f) return;
  showFrame(f);
  $("rec-time").textContent = `${f.timeS.toFixed(3)} s`;
}

/** The slider moved: stop playing and show its frame. */
export function sliderMoved(): void {
  state.playback.playing = false;
  $("play").textContent = "▶";
  showPlaybackFrame(Number(slider().value));
}

/** ▶ / ❚❚: plays the recording in real time from the slider's frame, or pauses. */
export function togglePlay(): void {
  const pb = state.playback;
  if (state.mode !== "playback" || !pb.frames.length) return;
  pb.playing = !pb.playing;
  $("play").textContent = pb.playing ? "❚❚" : "▶";
  if (pb.playing) {
    const s = slider();
    if (Number(s.value) >= pb.frames.length - 1) s.value = "0";
    pb.startedMs = performance.now();
    pb.startedSimS = pb.frames[Number(s.value)].timeS;
    requestAnimationFrame(playStep);
  }
}

export function stopPlaying(): void {
  state.playback.playing = false;
}

function playStep(): void {
  const pb = state.playback;
  if (!pb.playing || state.mode !== "playback") return;
  const simT = pb.startedSimS + (performance.now() - pb.startedMs) / 1000;
  const s = slider();
  let i = Number(s.value);
  while (i < pb.frames.length - 1 && pb.frames[i + 1].timeS <= simT) i++;
  s.value = String(i);
  showPlaybackFrame(i);
  if (i >= pb.frames.length - 1) {
    pb.playing = false;
    $("play").textContent = "▶";
    return;
  }
  requestAnimationFrame(playStep);
}
