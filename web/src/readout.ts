//! Shows a frame: makes it the drawn one and writes its numbers (depth, forces, node states,
//! targets, bevel) under the tissue view and on `<body>` for tests.
import { type Frame, NodeState } from "./gen/needlesim/v1/needlesim_pb";
import { $, publish } from "./dom";
import { state } from "./state";
import { updateViewBounds } from "./view";

export function showFrame(f: Frame): void {
  state.frame = f;
  updateViewBounds(state, f);
  const depth = $("depth");
  depth.textContent = `${(f.insertedLengthM * 1000).toFixed(2)} mm`;
  depth.dataset.depthM = String(f.insertedLengthM);
  publish("depthM", f.insertedLengthM);
  $("axial").textContent = `${f.forceAxialN.toFixed(3)} N`;
  $("lateral").textContent = `${f.forceLateralN.toFixed(3)} N`;
  $("torque").textContent = `${(f.torqueNm * 1000).toFixed(2)} mN·m`;
  let stuck = 0, slipping = 0, tip = 0;
  for (const n of f.needleNodes) {
    if (n.state === NodeState.STUCK) stuck++;
    else if (n.state === NodeState.SLIPPING) slipping++;
    else if (n.state === NodeState.TIP) tip++;
  }
  $("nodes").textContent = `${stuck}/${slipping}/${tip}`;
  $("targets").textContent = f.targets.length ? f.targets.map((t) => `${t.name}: ${t.hit ? "hit" : "missed"}`).join(", ") : "none";
  $("bevel").textContent = f.bevelSide === 0 ? "symmetric" : f.bevelSide > 0 ? "+n side" : "−n side";
  publish("bevelSide", f.bevelSide);
  // A faulted session (its solve diverged) holds the needle with zero force: say so.
  publish("fault", f.faulted ? f.fault : "");
  if (f.faulted) $("status").textContent = `session faulted: ${f.fault}`;
  state.dirty = true;
}

/** The frame counter of the live stream. */
export function showFramesReceived(n: number): void {
  publish("frames", n);
  $("frames").textContent = String(n);
}
