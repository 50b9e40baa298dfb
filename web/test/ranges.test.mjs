// Unit tests of web/src/ranges.ts (the force plots' value ranges), run by tests/it/web.rs with
// `node --test` after esbuild has bundled src/ranges.ts to ./ranges.mjs beside this file.
import { test } from "node:test";
import assert from "node:assert/strict";
import { alignZeros, extent, forceTorqueRanges, MIN_SPAN, valueRange } from "./ranges.mjs";

const zeroAt = ([lo, hi]) => -lo / (hi - lo);
const holds = ([lo, hi], [a, b]) => lo <= a && b <= hi;

test("extent finds the finite bounds of several arrays, or null", () => {
  assert.deepEqual(extent([3, -1], new Float64Array([7, 2])), [-1, 7]);
  assert.deepEqual(extent([NaN, 4]), [4, 4]);
  assert.equal(extent([], new Float64Array(0)), null);
});

test("a value range holds zero and the data, padded, at least its minimum span", () => {
  const r = valueRange([-0.3, -0.1], 0.02);
  assert.ok(holds(r, [-0.3, 0]) && r[0] < -0.3 && r[1] > 0, `${r}`);
  const flat = valueRange([1e-9, 1e-9], 0.02);
  assert.ok(flat[1] - flat[0] >= 0.02, `a flat signal gets the minimum span: ${flat}`);
  assert.ok(holds(flat, [0, 1e-9]));
  const none = valueRange(null, 0.2);
  assert.ok(Math.abs(none[0] + none[1]) < 1e-12 && none[1] > 0.1, `no data: symmetric about zero: ${none}`);
});

test("aligned ranges put zero at the same height and still hold their data", () => {
  const cases = [
    [[-0.3, 0.25], [0, 8.75]],
    [[-0.4, 0], [-2, 9]],
    [[0, 1], [-1, 0]],
    [null, [-3, 1]],
  ];
  for (const [f, t] of cases) {
    const [rf, rt] = alignZeros([valueRange(f, MIN_SPAN.forceN), valueRange(t, MIN_SPAN.torqueMnm)]);
    assert.ok(Math.abs(zeroAt(rf) - zeroAt(rt)) < 1e-12, `zeros at ${zeroAt(rf)} and ${zeroAt(rt)} for ${f} / ${t}`);
    if (f) assert.ok(holds(rf, f), `force range ${rf} lost ${f}`);
    assert.ok(holds(rt, t), `torque range ${rt} lost ${t}`);
  }
  const { forceN, torqueMnm } = forceTorqueRanges([[-0.3, 0.1], new Float64Array([0.05])], [0, 8.75]);
  assert.ok(holds(forceN, [-0.3, 0.1]) && holds(torqueMnm, [0, 8.75]));
  assert.ok(Math.abs(zeroAt(forceN) - zeroAt(torqueMnm)) < 1e-12);
});
