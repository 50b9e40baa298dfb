//! The value ranges of the force plots: forces (N) on the left axis, torque (mN·m) on the right,
//! each holding zero and its data, and both with zero at the same height so that one zero line
//! serves both axes. No DOM: plain numbers.

/** A value range [lo, hi]. */
export type Range = [number, number];

/** The smallest span of each axis (so that round-off noise is not magnified). */
export const MIN_SPAN = { forceN: 0.02, torqueMnm: 0.2 } as const;

/** The fraction of a range's span added below and above the data. */
const PAD = 0.08;

/** The smallest and largest finite value of some arrays (null when they hold none). */
export function extent(...arrays: ArrayLike<number>[]): Range | null {
  let lo = Infinity, hi = -Infinity;
  for (const a of arrays) {
    for (let i = 0; i < a.length; i++) {
      const v = a[i];
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
  }
  return lo <= hi ? [lo, hi] : null;
}

/** A range holding zero and `data` (none: just zero), at least `minSpan` wide, padded. */
export function valueRange(data: Range | null, minSpan: number): Range {
  let lo = Math.min(data?.[0] ?? 0, 0);
  let hi = Math.max(data?.[1] ?? 0, 0);
  if (hi - lo < minSpan) {
    const mid = (hi + lo) / 2;
    [lo, hi] = [mid - minSpan / 2, mid + minSpan / 2];
  }
  const pad = PAD * (hi - lo);
  return [lo - pad, hi + pad];
}

/**
 * Widens ranges that hold zero (each with hi > 0) so that zero sits at the same fraction of every
 * one: the highest fraction among them; a range with zero lower down gets a lower `lo`.
 */
export function alignZeros(ranges: Range[]): Range[] {
  const zeroAt = ([lo, hi]: Range): number => -lo / (hi - lo);
  const f = Math.max(...ranges.map(zeroAt));
  return ranges.map(([lo, hi]) => (zeroAt([lo, hi]) < f ? [(-f * hi) / (1 - f), hi] : [lo, hi]));
}

/** The force and torque ranges of some samples, zeros aligned. */
export function forceTorqueRanges(forcesN: ArrayLike<number>[], torqueMnm: ArrayLike<number>): { forceN: Range; torqueMnm: Range } {
  const [forceN, torque] = alignZeros([
    valueRange(extent(...forcesN), MIN_SPAN.forceN),
    valueRange(extent(torqueMnm), MIN_SPAN.torqueMnm),
  ]);
  return { forceN, torqueMnm: torque };
}
