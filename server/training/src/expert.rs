//! An expert's run of an exercise, for the report's comparison: the tick series CSV that
//! `needlesim-server exercise run --ticks FILE` writes ([`TickCsv`]), read back strictly
//! ([`parse_ticks_csv`]: errors name the file and line) and turned into the report's overlay
//! ([`ExpertOverlay`]): the expert's curves and the metrics the same [`MetricsTracker`] computes
//! from the expert's samples.
//!
//! The CSV, one row every `every`-th tick plus every tick where "placed" was declared and the
//! last tick (lines starting with `#` are comments):
//!
//! ```text
//! t_s,tip_x_m,tip_y_m,tip_z_m,axis_x,axis_y,axis_z,inserted_m,contacts,axial_force_n,placed,target_<name>_x_m,target_<name>_y_m,target_<name>_z_m,...
//! ```
//!
//! with [`Sample`]'s conventions (axial force positive resisting insertion, 2D with $z = 0$),
//! `placed` the number of "placed" declarations at that tick, and one `target_<name>_*` triple
//! per exercise target: its displaced centre. The expert's metrics are those of its rows: with
//! `every` > 1 the path length is that of the polyline through the kept tips and the peak force
//! the peak over the kept rows.

use std::fmt::Write as _;

use serde::Serialize;

use crate::metrics::{ExerciseResult, MetricsTracker, Trace, TracePoint, TrackerSpec};
use crate::run::TRACE_CAPACITY;
use crate::sample::Sample;

/// The fixed leading columns of the tick series CSV (module docs).
pub const TICK_COLUMNS: [&str; 11] =
    ["t_s", "tip_x_m", "tip_y_m", "tip_z_m", "axis_x", "axis_y", "axis_z", "inserted_m", "contacts", "axial_force_n", "placed"];

/// Most rows an expert CSV may have (a 10-minute run at 1 kHz, every tick).
pub const MAX_EXPERT_ROWS: usize = 600_000;

/// Why an expert run cannot be read; each names the file (and the line when it is the content).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExpertError {
    /// The file cannot be read (missing, unreadable, not shipped with the exercise).
    #[error("expert run {file}: {message}")]
    Read { file: String, message: String },
    /// A line of the CSV is malformed (1-based line number in the file).
    #[error("expert run {file}: line {line}: {message}")]
    Line { file: String, line: usize, message: String },
}

/// The tick series CSV writer ([`TickCsv::push`] per tick, [`TickCsv::finish`] once).
#[derive(Debug, Clone)]
pub struct TickCsv {
    every: u64,
    seen: u64,
    text: String,
    /// The target columns: (sample index) in the header's order.
    target_idx: Vec<usize>,
    /// The last tick's row when it was not written.
    pending: Option<String>,
}

impl TickCsv {
    /// A writer keeping every `every`-th tick (≥ 1) for `spec`'s targets; `title` goes in the
    /// leading comment line.
    pub fn new(spec: &TrackerSpec, every: u64, title: &str) -> Self {
        let mut text = format!("# needlesim exercise tick series: {title}, every {} tick(s)\n", every.max(1));
        text.push_str(&TICK_COLUMNS.join(","));
        for t in &spec.targets {
            let _ = write!(text, ",target_{0}_x_m,target_{0}_y_m,target_{0}_z_m", t.name);
        }
        text.push('\n');
        Self { every: every.max(1), seen: 0, text, target_idx: spec.targets.iter().map(|t| t.sample_idx).collect(), pending: None }
    }

    fn row(&self, s: &Sample, placed: u32) -> String {
        let mut r = format!(
            "{},{},{},{},{},{},{},{},{},{},{}",
            s.t_s, s.tip_m[0], s.tip_m[1], s.tip_m[2], s.axis[0], s.axis[1], s.axis[2], s.inserted_m, s.contacts, s.axial_force_n, placed
        );
        for &i in &self.target_idx {
            let c = s.targets().get(i).map_or([f64::NAN; 3], |t| t.centre_m);
            let _ = write!(r, ",{},{},{}", c[0], c[1], c[2]);
        }
        r.push('\n');
        r
    }

    /// Takes a tick's sample and the number of "placed" declared at it.
    pub fn push(&mut self, s: &Sample, placed: u32) {
        let row = self.row(s, placed);
        if self.seen.is_multiple_of(self.every) || placed > 0 {
            self.text.push_str(&row);
            self.pending = None;
        } else {
            self.pending = Some(row);
        }
        self.seen += 1;
    }

    /// The CSV text (the last tick's row appended if it was not kept).
    pub fn finish(mut self) -> String {
        if let Some(r) = self.pending.take() {
            self.text.push_str(&r);
        }
        self.text
    }
}

/// One row of an expert CSV: the sample and the "placed" declarations at it.
#[derive(Debug, Clone, Copy)]
pub struct ExpertRow {
    pub sample: Sample,
    pub placed: u32,
}

/// Parses an expert CSV (module docs) against `spec`: the rows, and the names of `spec`'s
/// targets that have no columns (their placements are then not computed).
pub fn parse_ticks_csv(text: &str, file: &str, spec: &TrackerSpec) -> Result<(Vec<ExpertRow>, Vec<String>), ExpertError> {
    let line_err = |line: usize, message: String| ExpertError::Line { file: file.to_owned(), line, message };
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim_end_matches('\r'))).filter(|(_, l)| !l.starts_with('#'));
    let Some((hline, header)) = lines.next() else {
        return Err(ExpertError::Read { file: file.to_owned(), message: "empty: no header line".into() });
    };
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    if cols.len() < TICK_COLUMNS.len() || cols[..TICK_COLUMNS.len()] != TICK_COLUMNS {
        return Err(line_err(hline, format!("the header must start with {}", TICK_COLUMNS.join(","))));
    }
    if !(cols.len() - TICK_COLUMNS.len()).is_multiple_of(3) {
        return Err(line_err(hline, "the target columns must come in x, y, z triples".into()));
    }
    // Per spec target: the column of its x, if present.
    let mut missing = Vec::new();
    let mut target_cols = Vec::new();
    for t in &spec.targets {
        let x = format!("target_{}_x_m", t.name);
        match cols.iter().position(|c| *c == x) {
            Some(k)
                if cols.get(k + 1) == Some(&format!("target_{}_y_m", t.name).as_str())
                    && cols.get(k + 2) == Some(&format!("target_{}_z_m", t.name).as_str()) =>
            {
                target_cols.push((t.sample_idx, Some(k)))
            }
            Some(_) => {
                return Err(line_err(hline, format!("target_{0}_x_m must be followed by target_{0}_y_m and target_{0}_z_m", t.name)));
            }
            None => {
                missing.push(t.name.clone());
                target_cols.push((t.sample_idx, None));
            }
        }
    }
    let n_sample_targets = spec.targets.iter().map(|t| t.sample_idx + 1).max().unwrap_or(0);
    let mut rows = Vec::new();
    let mut prev_t = f64::NEG_INFINITY;
    for (line, l) in lines {
        if l.trim().is_empty() {
            continue;
        }
        if rows.len() == MAX_EXPERT_ROWS {
            return Err(line_err(line, format!("more than {MAX_EXPERT_ROWS} rows")));
        }
        let v: Vec<&str> = l.split(',').map(str::trim).collect();
        if v.len() != cols.len() {
            return Err(line_err(line, format!("{} values, the header has {} columns", v.len(), cols.len())));
        }
        let num = |k: usize| -> Result<f64, ExpertError> {
            match v[k].parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(line_err(line, format!("column {} ('{}'): '{}' is not a finite number", k + 1, cols[k], v[k]))),
            }
        };
        let count = |k: usize| -> Result<u32, ExpertError> {
            v[k].parse::<u32>()
                .map_err(|_| line_err(line, format!("column {} ('{}'): '{}' is not a count (0, 1, 2, …)", k + 1, cols[k], v[k])))
        };
        let t_s = num(0)?;
        if t_s <= prev_t {
            return Err(line_err(
                line,
                format!(
                    "t_s = {} does not increase (the row before has {})",
                    needlesim_core::num::num(t_s),
                    needlesim_core::num::num(prev_t)
                ),
            ));
        }
        prev_t = t_s;
        let tip = [num(1)?, num(2)?, num(3)?];
        let axis = [num(4)?, num(5)?, num(6)?];
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if (norm - 1.0).abs() > 1e-6 {
            return Err(line_err(line, format!("the axis ({}, {}, {}) is not a unit vector (length {norm})", axis[0], axis[1], axis[2])));
        }
        let mut s = Sample::new(t_s, tip, axis, num(7)?, count(8)?, num(9)?);
        let placed = count(10)?;
        // The sample's targets at the simulation's indices (a target without columns: far away).
        let mut centres = vec![[f64::INFINITY; 3]; n_sample_targets];
        for &(idx, k) in &target_cols {
            if let Some(k) = k {
                centres[idx] = [num(k)?, num(k + 1)?, num(k + 2)?];
            }
        }
        for c in centres {
            s.push_target(c);
        }
        rows.push(ExpertRow { sample: s, placed });
    }
    if rows.is_empty() {
        return Err(ExpertError::Read { file: file.to_owned(), message: "no rows after the header".into() });
    }
    Ok((rows, missing))
}

/// The expert's run as the report shows it.
#[derive(Debug, Clone, Serialize)]
pub struct ExpertOverlay {
    /// The file as the exercise or the command line named it.
    pub file: String,
    /// Rows read.
    pub rows: usize,
    /// The expert's metrics and score by the exercise's [`MetricsTracker`].
    pub result: ExerciseResult,
    /// What of the metrics could not be computed from the CSV (empty when everything was).
    pub notes: Vec<String>,
    /// The expert's curves.
    #[serde(skip)]
    pub trace: Vec<TracePoint>,
}

/// Reads the expert CSV `text` (named `file`) against `spec` ([`parse_ticks_csv`]) and runs
/// its rows through a [`MetricsTracker`] of `spec`: "placed" declared `placed` times after each
/// row's sample, as in a scripted run.
pub fn expert_overlay(text: &str, file: &str, spec: &TrackerSpec) -> Result<ExpertOverlay, ExpertError> {
    let (rows, missing) = parse_ticks_csv(text, file, spec)?;
    let mut tracker = MetricsTracker::new(spec.clone());
    let mut trace = Trace::new(TRACE_CAPACITY);
    let mut notes = Vec::new();
    if !missing.is_empty() {
        notes.push(format!("no columns for target(s) {}: their placements are not computed", missing.join(", ")));
    }
    let mut refused = 0;
    for r in &rows {
        tracker.push(&r.sample);
        trace.push(&r.sample, tracker.depth_m());
        for _ in 0..r.placed {
            if tracker.place().is_err() {
                refused += 1;
            }
        }
    }
    if refused > 0 {
        notes.push(format!("{refused} \"placed\" declaration(s) of the expert refused (every target placed already)"));
    }
    Ok(ExpertOverlay { file: file.to_owned(), rows: rows.len(), result: tracker.finish(), notes, trace: trace.points() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exercise::{Limits, Weights};
    use crate::metrics::TrackedTarget;

    fn spec() -> TrackerSpec {
        TrackerSpec {
            dims: 2,
            targets: vec![TrackedTarget { name: "t".into(), sample_idx: 0, tolerance_m: 0.002 }],
            structures: vec![],
            limits: Limits { time_s: 60.0, reinsertions: 1, peak_force_n: 3.0, penalty: 10.0 },
            weights: Weights { accuracy: 4.0, efficiency: 1.0, path: 1.0, force: 1.0, safety: 0.0, time: 1.0 },
            redirect_threshold_m: 0.005,
        }
    }

    fn sample(k: u64) -> Sample {
        let x = 0.001 * k as f64;
        let mut s = Sample::new(0.01 * k as f64, [x, 0.0, 0.0], [1.0, 0.0, 0.0], x, (k > 0) as u32, 0.1 * k as f64);
        s.push_target([0.0105, 0.0003, 0.0]);
        s
    }

    #[test]
    fn a_written_tick_series_reads_back_to_the_same_metrics() {
        let sp = spec();
        let mut csv = TickCsv::new(&sp, 1, "test");
        let mut direct = MetricsTracker::new(sp.clone());
        for k in 0..=12 {
            let s = sample(k);
            direct.push(&s);
            let placed = (k == 10) as u32;
            if placed == 1 {
                direct.place().unwrap();
            }
            csv.push(&s, placed);
        }
        let text = csv.finish();
        let o = expert_overlay(&text, "x.csv", &sp).unwrap();
        assert_eq!(o.rows, 13);
        assert!(o.notes.is_empty(), "{:?}", o.notes);
        assert_eq!(o.result, direct.finish());
    }

    #[test]
    fn decimation_keeps_placements_and_the_last_tick() {
        let sp = spec();
        let mut csv = TickCsv::new(&sp, 5, "test");
        for k in 0..=12 {
            csv.push(&sample(k), (k == 7) as u32);
        }
        let (rows, _) = parse_ticks_csv(&csv.finish(), "x.csv", &sp).unwrap();
        let ks: Vec<u64> = rows.iter().map(|r| (r.sample.t_s / 0.01).round() as u64).collect();
        assert_eq!(ks, [0, 5, 7, 10, 12]);
        assert_eq!(rows[2].placed, 1);
    }

    #[test]
    fn malformed_rows_are_refused_naming_the_file_and_line() {
        let sp = spec();
        let mut csv = TickCsv::new(&sp, 1, "test");
        for k in 0..4 {
            csv.push(&sample(k), 0);
        }
        let good = csv.finish();
        // Line 1 is the comment, 2 the header, 3.. the rows.
        let lines: Vec<String> = good.lines().map(str::to_owned).collect();
        let mut bad = lines.clone();
        let mut v: Vec<&str> = bad[4].split(',').collect();
        v[2] = "abc";
        bad[4] = v.join(",");
        let e = parse_ticks_csv(&bad.join("\n"), "e.csv", &sp).unwrap_err().to_string();
        assert_eq!(e, "expert run e.csv: line 5: column 3 ('tip_y_m'): 'abc' is not a finite number");
        let mut short = lines.clone();
        let cut = short[3].rfind(',').unwrap();
        short[3].truncate(cut);
        let e = parse_ticks_csv(&short.join("\n"), "e.csv", &sp).unwrap_err().to_string();
        assert_eq!(e, "expert run e.csv: line 4: 13 values, the header has 14 columns");
        let mut back = lines.clone();
        back.swap(3, 4);
        let e = parse_ticks_csv(&back.join("\n"), "e.csv", &sp).unwrap_err().to_string();
        assert!(e.starts_with("expert run e.csv: line 5: t_s = 0.01 does not increase"), "{e}");
        let e = parse_ticks_csv("t_s,x\n", "e.csv", &sp).unwrap_err().to_string();
        assert!(e.starts_with("expert run e.csv: line 1: the header must start with t_s,tip_x_m"), "{e}");
    }
}
