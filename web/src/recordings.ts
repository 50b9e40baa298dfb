//! Recordings: start / stop one of the watched session, list the server's, download one and play
//! its frames back (MCAP parsed in the page: zstd by fzstd, lz4 by lz4js) with a slider and ▶.
import { fromBinary } from "@bufbuild/protobuf";
import { McapStreamReader } from "@mcap/core";
import { decompress as zstdDecompress } from "fzstd";
import { decompress as lz4Decompress } from "lz4js";
import { type Frame, FrameSchema } from "./gen/needlesim/v1/needlesim_pb";
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
    const info = start ? await recordings.startRecording(req, auth(session.token)) : await recordings.stopRecording(req, auth(session.token));
    status(`${start ? "recording to" : "recorded"} ${info.name}`);
    await refreshRecordings();
    recSelect().value = info.name;
  } catch (e) {
    status(`${start ? "StartRecording" : "StopRecording"}: ${String(e)}`);
  }
}

/** The Frame messages of an MCAP file (chunked, zstd / lz4 / uncompressed; finished or not). */
export function parseMcapFrames(bytes: Uint8Array): Frame[] {
  const reader = new McapStreamReader({
    decompressHandlers: {
      zstd: (buf, size) => zstdDecompress(buf, new Uint8Array(Number(size))),
      lz4: (buf, size) => Uint8Array.from(lz4Decompress(buf, Number(size))),
    },
  });
  reader.append(bytes);
  const frameChannels = new Set<number>();
  const schemas = new Map<number, string>();
  const out: Frame[] = [];
  for (let rec = reader.nextRecord(); rec; rec = reader.nextRecord()) {
    if (rec.type === "Schema") schemas.set(rec.id, rec.name);
    else if (rec.type === "Channel" && schemas.get(rec.schemaId) === "needlesim.v1.Frame") frameChannels.add(rec.id);
    else if (rec.type === "Message" && frameChannels.has(rec.channelId)) out.push(fromBinary(FrameSchema, rec.data));
  }
  return out;
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
    const all = parseMcapFrames(bytes);
    if (!all.length) return status(`${name} holds no frames`);
    const step = Math.max(1, Math.ceil(all.length / MAX_PLAYBACK_FRAMES));
    const frames = all.filter((_, i) => i % step === 0);
    // The recording's session, when it is still open and its token known, gives the mesh.
    const sid = name.replace(/-\d{8}T\d{6}Z.*$/, "");
    const tok = tokens.get(sid) ?? (state.session?.id === sid ? state.session.token : undefined);
    if (tok && state.session?.id !== sid) {
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
