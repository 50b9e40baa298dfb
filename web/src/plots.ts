//! The force plots: axial and lateral force (N) and torque (mN·m) against time and against
//! inserted depth, drawn by uPlot from bounded histories (history.ts) that grow by one sample a
//! frame.
import uPlot from "uplot";
import { AXIAL, DEPTH, type ForceHistory, type ForceSample, LATERAL, TIME, TORQUE } from "./history";
import { forceTorqueRanges } from "./ranges";

type ValueRanges = ReturnType<typeof forceTorqueRanges>;

const COLOUR = { axial: "#d95f02", lateral: "#1b9e77", torque: "#7570b3", cursor: "#7b3294" } as const;

/** The x range of the data, `pad` of its span either side (a unit span around a single value). */
function spanRange(pad: number): uPlot.Range.Function {
  return (_u, dataMin, dataMax) => {
    if (!Number.isFinite(dataMin) || !Number.isFinite(dataMax)) return [0, 1];
    if (!(dataMax > dataMin)) return [dataMin - 0.5, dataMax + 0.5];
    const p = pad * (dataMax - dataMin);
    return [dataMin - p, dataMax + p];
  };
}

/** The y axes: forces on the left, torque on the right (its own scale: a different quantity; the
 * ranges put both zeros on one line). */
function valueAxes(): uPlot.Axis[] {
  return [
    { scale: "N", label: "force (N)", size: 52, labelSize: 20 },
    { scale: "mNm", label: "torque (mN·m)", side: 1, size: 52, labelSize: 20, grid: { show: false } },
  ];
}

/** The x axis: ticks and its label close together. */
const X_AXIS: uPlot.Axis = { size: 30, labelSize: 18, labelGap: 0 };

/** The value scales of a chart, ranged by `ranges()` (computed with the data, zeros aligned). */
function valueScales(ranges: () => ValueRanges): uPlot.Scales {
  return { N: { range: () => ranges().forceN }, mNm: { range: () => ranges().torqueMnm } };
}

/** Draws a vertical line at x = `at()` (the playback cursor) over the plotting area. */
function cursorLine(xScale: string, at: () => number | null): (u: uPlot) => void {
  return (u) => {
    const x = at();
    if (x === null) return;
    const px = Math.round(u.valToPos(x, xScale, true));
    const { left, top, width, height } = u.bbox;
    if (px < left || px > left + width) return;
    const ctx = u.ctx;
    ctx.save();
    ctx.strokeStyle = COLOUR.cursor;
    ctx.lineWidth = 1.5 * devicePixelRatio;
    ctx.beginPath();
    ctx.moveTo(px, top);
    ctx.lineTo(px, top + height);
    ctx.stroke();
    ctx.restore();
  };
}

/**
 * uPlot's data for a faceted (mode 2) chart: one [x, y] pair per series after a null. Its typings
 * declare only the aligned (mode 1) layout, so this is the one place the two meet.
 */
function facetedData(x: Float64Array, ...ys: Float64Array[]): uPlot.AlignedData {
  const data: [null, ...[Float64Array, Float64Array][]] = [null, ...ys.map((y): [Float64Array, Float64Array] => [x, y])];
  return data as unknown as uPlot.AlignedData;
}

/** The force–time and force–depth charts. */
export class ForcePlots {
  private readonly byTime: uPlot;
  private readonly byDepth: uPlot;
  private cursor: ForceSample | null = null;
  private timeLabel = "time (s)";
  private shown: { history: ForceHistory; version: number; windowS: number | null } | null = null;
  private timeRanges: ValueRanges = forceTorqueRanges([], []);
  private depthRanges: ValueRanges = forceTorqueRanges([], []);

  constructor(timeEl: HTMLElement, depthEl: HTMLElement, width: number, height: number) {
    // Force against time: aligned data (times only grow). The legends name the series (the values
    // are in the readout under the tissue view); no hover cursor on a streaming plot.
    this.byTime = new uPlot(
      {
        width,
        height,
        scales: { x: { time: false, range: spanRange(0) }, ...valueScales(() => this.timeRanges) },
        axes: [{ label: () => this.timeLabel, ...X_AXIS }, ...valueAxes()],
        series: [
          { label: "time (s)" },
          { label: "axial (N)", scale: "N", stroke: COLOUR.axial, width: 1.5 },
          { label: "lateral (N)", scale: "N", stroke: COLOUR.lateral, width: 1.5 },
          { label: "torque (mN·m)", scale: "mNm", stroke: COLOUR.torque, width: 1.5 },
        ],
        cursor: { show: false },
        legend: { live: false },
        hooks: { draw: [cursorLine("x", () => this.cursor?.timeS ?? null)] },
      },
      [[], [], [], []],
      timeEl,
    );
    // Force against depth: depth goes back and forth, so each series is an (x, y) facet drawn in
    // sample order (uPlot's mode 2). uPlot draws every segment of a series with fewer points than
    // 4 × the plot's width in pixels (it merges more per pixel column, which assumes growing x):
    // the trace holds at most 1025.
    const facet = (label: string, scale: string, stroke: string): uPlot.Series => ({
      label,
      stroke,
      width: 1.5,
      facets: [
        { scale: "mm", auto: true },
        { scale, auto: true },
      ],
      paths: uPlot.paths.linear?.(),
      points: { show: false },
    });
    this.byDepth = new uPlot(
      {
        mode: 2,
        width,
        height,
        scales: { mm: { time: false, range: spanRange(0.08) }, ...valueScales(() => this.depthRanges) },
        axes: [{ scale: "mm", label: "inserted depth (mm)", ...X_AXIS }, ...valueAxes()],
        series: [
          {},
          facet("axial (N)", "N", COLOUR.axial),
          facet("lateral (N)", "N", COLOUR.lateral),
          facet("torque (mN·m)", "mNm", COLOUR.torque),
        ],
        cursor: { show: false },
        legend: { live: false },
        hooks: { draw: [cursorLine("mm", () => this.cursor?.depthMm ?? null)] },
      },
      facetedData(new Float64Array(0), new Float64Array(0), new Float64Array(0), new Float64Array(0)),
      depthEl,
    );
  }

  /**
   * Shows a history: against time its last `windowS` seconds (all when null), against depth all of
   * it; with a vertical cursor at `cursor` (playback) or none. Data changes only when the history
   * did (cheap to call every frame).
   */
  show(history: ForceHistory, windowS: number | null, cursor: ForceSample | null): void {
    const s = this.shown;
    const same = s !== null && s.history === history && s.version === history.version && s.windowS === windowS;
    this.cursor = cursor;
    if (same) {
      this.byTime.redraw(false, false);
      this.byDepth.redraw(false, false);
      return;
    }
    this.shown = { history, version: history.version, windowS };
    this.timeLabel = windowS === null ? "time (s)" : `time (s), last ${windowS} s`;
    const newestS = history.recent.newestTimeS();
    const r = history.recent.window(windowS !== null && newestS !== null ? newestS - windowS : null);
    this.timeRanges = forceTorqueRanges([r[AXIAL], r[LATERAL]], r[TORQUE]);
    this.byTime.setData([r[TIME], r[AXIAL], r[LATERAL], r[TORQUE]]);
    const d = history.trace.columns();
    this.depthRanges = forceTorqueRanges([d[AXIAL], d[LATERAL]], d[TORQUE]);
    this.byDepth.setData(facetedData(d[DEPTH], d[AXIAL], d[LATERAL], d[TORQUE]));
  }
}
