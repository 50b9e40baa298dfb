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
  const d3 = f.d3;
  if (d3) {
    const [fx, fy, fz] = [d3.forceN?.x ?? 0, d3.forceN?.y ?? 0, d3.forceN?.z ?? 0];
    $("axial").textContent = `${d3.axialForceN.toFixed(3)} N`;
    $("lateral").textContent = `(${fx.toFixed(3)}, ${fy.toFixed(3)}, ${fz.toFixed(3)}) N`;
    const t = d3.torqueNm;
    $("torque").textContent = `(${[t?.x ?? 0, t?.y ?? 0, t?.z ?? 0].map((v) => (v * 1000).toFixed(2)).join(", ")}) mN·m`;
  }
  const states = d3 ? d3.contacts.map((c) => c.state) : f.needleNodes.map((n) => n.state);
  for (const s of states) {
    if (s === NodeState.STUCK) stuck++;
    else if (s === NodeState.SLIPPING) slipping++;
    else if (s === NodeState.TIP) tip++;
  }
  $("nodes").textContent = `${stuck}/${slipping}/${tip}`;
  const targets = d3 ? d3.targets : f.targets;
  $("targets").textContent = targets.length ? targets.map((t) => `${t.name}: ${t.hit ? "hit" : "missed"}`).join(", ") : "none";
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
