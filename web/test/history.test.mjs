// Unit tests of web/src/history.ts (the plots' bounded force histories), run by tests/it/web.rs with
// `node --test` after esbuild has bundled src/history.ts to ./history.mjs beside this file.
import { test } from "node:test";
import assert from "node:assert/strict";
import { ForceHistory, SampleRing, ThinnedTrace, TIME, DEPTH, AXIAL, LATERAL, TORQUE } from "./history.mjs";

/** Sample i: every column a different function of i, so a mixed-up column shows. */
const sample = (i) => ({ timeS: i, depthMm: 2 * i, axialN: -i, lateralN: i / 10, torqueMnm: i + 0.5 });

function assertSamples(cols, times, what) {
  assert.deepEqual(Array.from(cols[TIME]), times, `${what}: times`);
  assert.deepEqual(Array.from(cols[DEPTH]), times.map((i) => 2 * i), `${what}: depths`);
  assert.deepEqual(Array.from(cols[AXIAL]), times.map((i) => -i), `${what}: axial forces`);
  assert.deepEqual(Array.from(cols[LATERAL]), times.map((i) => i / 10), `${what}: lateral forces`);
  assert.deepEqual(Array.from(cols[TORQUE]), times.map((i) => i + 0.5), `${what}: torques`);
}

const range = (from, to) => Array.from({ length: to - from }, (_, k) => from + k);

test("a sample ring keeps the newest samples, oldest first, at every fill level", () => {
  const ring = new SampleRing(4);
  assertSamples(ring.window(null), [], "empty");
  assert.equal(ring.newestTimeS(), null);
  for (let n = 1; n <= 11; n++) {
    ring.push(sample(n - 1));
    assertSamples(ring.window(null), range(Math.max(0, n - 4), n), `after ${n} pushes`);
    assert.equal(ring.newestTimeS(), n - 1);
  }
  assert.equal(ring.length, 4);
});

test("a sample ring's window from a time starts at the first sample at or after it", () => {
  const ring = new SampleRing(5);
  for (let i = 0; i < 13; i++) ring.push(sample(i));
  assertSamples(ring.window(10), [10, 11, 12], "from 10 s");
  assertSamples(ring.window(9.5), [10, 11, 12], "from 9.5 s");
  assertSamples(ring.window(0), range(8, 13), "from before the oldest kept");
  assertSamples(ring.window(99), [], "from after the newest");
  ring.clear();
  assertSamples(ring.window(null), [], "cleared");
});

test("a thinned trace spans all samples with at most its capacity, evenly spaced, plus the newest", () => {
  const trace = new ThinnedTrace(8);
  for (let i = 0; i < 8; i++) trace.push(sample(i));
  assertSamples(trace.columns(), range(0, 8), "full, every sample kept");
  assert.equal(trace.keepsEvery, 1);
  for (let n = 9; n <= 1000; n++) {
    trace.push(sample(n - 1));
    const times = Array.from(trace.columns()[TIME]);
    assert.ok(times.length <= 9, `after ${n} pushes it holds ${times.length} samples`);
    assert.equal(times[0], 0, "the first sample stays");
    assert.equal(times[times.length - 1], n - 1, "the newest sample is shown");
    // The kept ones are every `keepsEvery`-th sample; the newest may come sooner after the last.
    const stride = trace.keepsEvery;
    const kept = times.length > 1 && (n - 1) % stride !== 0 ? times.slice(0, -1) : times;
    assert.deepEqual(kept, kept.map((_, k) => k * stride), `after ${n} pushes (every ${stride}th)`);
  }
  assert.equal(trace.keepsEvery, 128);
  trace.clear();
  assertSamples(trace.columns(), [], "cleared");
  trace.push(sample(5));
  assertSamples(trace.columns(), [5], "one after a clear");
});

test("a recording's history holds all its samples against time", () => {
  const h = ForceHistory.of(range(0, 300).map(sample));
  assertSamples(h.recent.window(null), range(0, 300), "against time");
  assert.ok(h.trace.columns()[TIME].length <= h.trace.capacity + 1);
  const v = h.version;
  h.push(sample(300));
  assert.ok(h.version > v, "a push changes the version");
});

test("bad capacities are refused with a clear error", () => {
  assert.throws(() => new SampleRing(0), /positive capacity/);
  assert.throws(() => new ThinnedTrace(7), /even capacity/);
});
