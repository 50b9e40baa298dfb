//! The force histories the plots draw: each frame's forces as a sample, a bounded ring of the latest
//! samples (against time) and a thinned trace of all of them (against depth). No DOM: plain data.
import type { Frame } from "./gen/needlesim/v1/needlesim_pb";

/** One frame's forces, in the plots' units. */
export interface ForceSample {
  timeS: number;
  depthMm: number;
  axialN: number;
  lateralN: number;
  torqueMnm: number;
}

export function sampleOf(f: Frame): ForceSample {
  return { timeS: f.timeS, depthMm: f.insertedLengthM * 1000, axialN: f.forceAxialN, lateralN: f.forceLateralN, torqueMnm: f.torqueNm * 1000 };
}

/** The columns every history keeps, in this order. */
const COLUMNS = ["timeS", "depthMm", "axialN", "lateralN", "torqueMnm"] as const;
/** Column indices. */
export const [TIME, DEPTH, AXIAL, LATERAL, TORQUE] = [0, 1, 2, 3, 4] as const;

/** A history's samples as columns (time, depth, axial, lateral, torque), oldest first. */
export type Columns = readonly [Float64Array, Float64Array, Float64Array, Float64Array, Float64Array];

function newColumns(len: number): Columns {
  return [new Float64Array(len), new Float64Array(len), new Float64Array(len), new Float64Array(len), new Float64Array(len)];
}

function sliceColumns(c: Columns, from: number, to: number): Columns {
  return [c[0].subarray(from, to), c[1].subarray(from, to), c[2].subarray(from, to), c[3].subarray(from, to), c[4].subarray(from, to)];
}

/**
 * A bounded ring of the latest samples (in time order). Each sample is stored twice, at slot i and
 * at i + capacity, so the newest samples are always one contiguous run of each column: uPlot gets
 * subarrays of it, never a copy.
 */
export class SampleRing {
  readonly capacity: number;
  private readonly cols: Columns;
  /** The slot of the next write, in [0, capacity). */
  private next = 0;
  private len = 0;

  constructor(capacity: number) {
    if (!(Number.isInteger(capacity) && capacity > 0)) throw new RangeError(`a sample ring needs a positive capacity, not ${capacity}`);
    this.capacity = capacity;
    this.cols = newColumns(2 * capacity);
  }

  get length(): number {
    return this.len;
  }

  clear(): void {
    this.next = 0;
    this.len = 0;
  }

  push(s: ForceSample): void {
    const { next, capacity } = this;
    COLUMNS.forEach((key, c) => {
      this.cols[c][next] = s[key];
      this.cols[c][next + capacity] = s[key];
    });
    this.next = (next + 1) % capacity;
    this.len = Math.min(this.len + 1, capacity);
  }

  /** The time of the newest sample (null when empty). */
  newestTimeS(): number | null {
    return this.len ? this.cols[TIME][(this.next - 1 + this.capacity) % this.capacity] : null;
  }

  /** The samples from time `fromS` on (all when null), oldest first. */
  window(fromS: number | null): Columns {
    const start = (this.next - this.len + this.capacity) % this.capacity;
    let lo = start;
    const end = start + this.len;
    if (fromS !== null) {
      // Times only grow within a session: the first sample at or after fromS, by bisection.
      const t = this.cols[TIME];
      let hi = end;
      while (lo < hi) {
        const mid = (lo + hi) >>> 1;
        if (t[mid] < fromS) lo = mid + 1;
        else hi = mid;
      }
    }
    return sliceColumns(this.cols, lo, end);
  }
}

/**
 * A whole history at a bounded resolution: it keeps every `stride`-th sample, and when it is full it
 * drops every other kept sample and doubles the stride, so it always spans everything since it was
 * cleared with at most `capacity` evenly spaced samples — plus the newest one, so the trace ends at
 * the current frame.
 */
export class ThinnedTrace {
  readonly capacity: number;
  /** Kept samples in slots [0, len), the newest (when not kept) in slot len. */
  private readonly cols: Columns;
  private len = 0;
  private hasNewest = false;
  private stride = 1;
  private sinceKept = 0;

  constructor(capacity: number) {
    if (!(Number.isInteger(capacity) && capacity >= 2 && capacity % 2 === 0)) {
      throw new RangeError(`a thinned trace needs an even capacity of at least 2, not ${capacity}`);
    }
    this.capacity = capacity;
    this.cols = newColumns(capacity + 1);
  }

  /** Every how many samples one is kept. */
  get keepsEvery(): number {
    return this.stride;
  }

  clear(): void {
    this.len = 0;
    this.hasNewest = false;
    this.stride = 1;
    this.sinceKept = 0;
  }

  push(s: ForceSample): void {
    const due = this.len === 0 || ++this.sinceKept >= this.stride;
    if (due && this.len === this.capacity) {
      // Keep the samples at even positions: still evenly spaced, at twice the stride, and this
      // sample (capacity · stride after the first) falls on the new grid.
      for (const col of this.cols) {
        for (let i = 0; i < this.capacity / 2; i++) col[i] = col[2 * i];
      }
      this.len = this.capacity / 2;
      this.stride *= 2;
    }
    COLUMNS.forEach((key, c) => {
      this.cols[c][this.len] = s[key];
    });
    if (due) {
      this.len++;
      this.sinceKept = 0;
      this.hasNewest = false;
    } else {
      this.hasNewest = true;
    }
  }

  /** The kept samples and the newest, oldest first. */
  columns(): Columns {
    return sliceColumns(this.cols, 0, this.len + (this.hasNewest ? 1 : 0));
  }
}

/** The force history of a session or a recording: recent samples against time, all against depth. */
export class ForceHistory {
  readonly recent: SampleRing;
  readonly trace: ThinnedTrace;
  /** Grows with every change (so that a plot redraws its data only when it changed). */
  version = 0;

  /**
   * `recentCapacity`: samples kept for the time plot (4096: 20 s up to ~200 frames/s);
   * `traceCapacity`: for the depth plot (1024: below 4 × its width in pixels, see plots.ts).
   */
  constructor(recentCapacity = 4096, traceCapacity = 1024) {
    this.recent = new SampleRing(recentCapacity);
    this.trace = new ThinnedTrace(traceCapacity);
  }

  /** The history of a recording: all its samples against time, a thinned trace against depth. */
  static of(samples: readonly ForceSample[]): ForceHistory {
    const h = new ForceHistory(Math.max(1, samples.length));
    for (const s of samples) h.push(s);
    return h;
  }

  push(s: ForceSample): void {
    this.recent.push(s);
    this.trace.push(s);
    this.version++;
  }

  clear(): void {
    this.recent.clear();
    this.trace.clear();
    this.version++;
  }
}
