//! Base trajectories: the `t_s,x_m,y_m,theta_rad` CSV that scenes, the CLI (`needlesim simulate`)
//! and the device bridge's scripted devices read, parsed in one place with errors that name the
//! line and the column.
//!
//! A trajectory is a list of samples $(t_k, x_k, y_k, \theta_k)$, strictly increasing in time;
//! between samples the pose is interpolated linearly,
//! $q(t) = q_k + \frac{t - t_k}{t_{k+1} - t_k}(q_{k+1} - q_k)$, and held constant beyond the ends.

use serde::Deserialize;

pub mod pose3;

pub use pose3::{Pose3, Trajectory3, Trajectory3Error};

/// The column names, in order, of the CSV header.
pub const HEADER: [&str; 4] = ["t_s", "x_m", "y_m", "theta_rad"];

/// The largest magnitude of a position (m) or angle (rad) in a trajectory: far beyond any
/// tissue, and small enough that no interpolation or difference of two poses overflows.
pub const MAX_ABS_POSE: f64 = 1e3;

/// The shortest time between two samples (s): the segment slopes (velocities) stay finite.
pub const MIN_SAMPLE_GAP_S: f64 = 1e-9;

/// A planar base pose: position (m) and the needle's angle to the +y axis (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose2 {
    pub x_m: f64,
    pub y_m: f64,
    pub theta_rad: f64,
}

impl Pose2 {
    pub fn new(x_m: f64, y_m: f64, theta_rad: f64) -> Self {
        Self { x_m, y_m, theta_rad }
    }

    /// `self + w (other − self)`, component by component.
    fn lerp(self, other: Self, w: f64) -> Self {
        Self::new(
            self.x_m + w * (other.x_m - self.x_m),
            self.y_m + w * (other.y_m - self.y_m),
            self.theta_rad + w * (other.theta_rad - self.theta_rad),
        )
    }
}

/// Why a trajectory was refused; each names where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrajectoryError {
    /// The first line is not `t_s,x_m,y_m,theta_rad` (or cannot be read).
    #[error("trajectory line 1: the header must be t_s,x_m,y_m,theta_rad, found {found}")]
    Header { found: String },
    /// A row cannot be read: a field that is not a number, a wrong number of fields, bad UTF-8.
    #[error("trajectory line {line}: {message}")]
    Row { line: u64, message: String },
    /// A value is NaN or infinite; `row` counts samples from 1.
    #[error("trajectory row {row} (line {line}): {column} is {value}, not a finite number")]
    NonFinite { row: usize, line: u64, column: &'static str, value: f64 },
    /// A position or angle beyond ±[`MAX_ABS_POSE`]; `row` counts samples from 1.
    #[error("trajectory row {row} (line {line}): {column} = {value:e} is out of range (at most {MAX_ABS_POSE:e} in magnitude)")]
    OutOfRange { row: usize, line: u64, column: &'static str, value: f64 },
    /// A time does not increase over the previous row's.
    #[error("trajectory line {line}: t_s = {t_s} does not increase (previous {previous_s})")]
    NotIncreasing { line: u64, t_s: f64, previous_s: f64 },
    /// A time follows the previous one by less than [`MIN_SAMPLE_GAP_S`], or by more than a
    /// double can hold (the segment's slope would be infinite, or its length).
    #[error(
        "trajectory line {line}: t_s = {t_s:e} is {gap_s:e} s after the previous sample ({previous_s:e}): the gap must be a finite number of at least {MIN_SAMPLE_GAP_S:e} s"
    )]
    BadGap { line: u64, t_s: f64, previous_s: f64, gap_s: f64 },
    /// Nothing after the header.
    #[error("trajectory: no samples")]
    Empty,
    /// The trajectory lasts more ticks than allowed ([`Trajectory::tick_count`]).
    #[error(
        "{at}: t_s = {end_s:e} ends {span_s:e} s after the first sample, {ticks:e} ticks at {rate_hz} Hz: over the limit of {max_ticks} ticks (--max-ticks)"
    )]
    TooLong { at: String, end_s: f64, span_s: f64, ticks: f64, rate_hz: f64, max_ticks: u64 },
}

/// A base trajectory: samples of `t_s,x_m,y_m,theta_rad`, strictly increasing in time, at least one.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    pub samples: Vec<(f64, Pose2)>,
    /// The line of the last sample in the CSV it was read from (None when not read from text).
    pub end_line: Option<u64>,
}

#[derive(Debug, Deserialize)]
struct Row {
    t_s: f64,
    x_m: f64,
    y_m: f64,
    theta_rad: f64,
}

impl Trajectory {
    /// Parses the CSV text: a header, then rows; `#` starts a comment line and fields are
    /// trimmed. Errors name the line (comment and blank lines counted) and the column. Every
    /// value is finite, positions and angles within ±[`MAX_ABS_POSE`], consecutive times at
    /// least [`MIN_SAMPLE_GAP_S`] and at most a finite double apart: so every pose and slope
    /// [`Trajectory::pose_and_velocity_at`] returns is finite.
    pub fn parse_csv(text: &str) -> Result<Self, TrajectoryError> {
        let mut rdr = csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).from_reader(text.as_bytes());
        let headers =
            rdr.headers().map_err(|e| TrajectoryError::Header { found: format!("an unreadable line ({})", csv_kind(&e)) })?.clone();
        if headers.iter().ne(HEADER) {
            return Err(TrajectoryError::Header { found: header_mismatch(headers.iter(), &HEADER) });
        }
        let mut samples: Vec<(f64, Pose2)> = Vec::new();
        let mut end_line = 0;
        let mut record = csv::StringRecord::new();
        let mut lines = LineCounter::new(text);
        let mut line_at = |byte: u64| lines.line_at(byte);
        loop {
            let more = match rdr.read_record(&mut record) {
                Ok(more) => more,
                Err(e) => {
                    let line = e.position().map_or(0, |p| line_at(p.byte()));
                    return Err(TrajectoryError::Row { line, message: csv_kind(&e) });
                }
            };
            if !more {
                break;
            }
            let line = record.position().map_or(0, |p| line_at(p.byte()));
            let row: Row = record.deserialize(Some(&headers)).map_err(|e| {
                // Name the value as written, too: "column y_m: `oops` is not a number (…)".
                let value = match e.kind() {
                    csv::ErrorKind::Deserialize { err, .. } => err.field().and_then(|f| record.get(f as usize)),
                    _ => None,
                };
                let message = match value {
                    Some(v) => format!("{}: `{}` is not a number", csv_kind(&e), clip(v, 32)),
                    None => csv_kind(&e),
                };
                TrajectoryError::Row { line, message }
            })?;
            for (column, value) in HEADER.into_iter().zip([row.t_s, row.x_m, row.y_m, row.theta_rad]) {
                if !value.is_finite() {
                    return Err(TrajectoryError::NonFinite { row: samples.len() + 1, line, column, value });
                }
            }
            for (column, value) in HEADER[1..].iter().zip([row.x_m, row.y_m, row.theta_rad]) {
                if value.abs() > MAX_ABS_POSE {
                    return Err(TrajectoryError::OutOfRange { row: samples.len() + 1, line, column, value });
                }
            }
            if let Some(&(previous_s, _)) = samples.last() {
                if row.t_s <= previous_s {
                    return Err(TrajectoryError::NotIncreasing { line, t_s: row.t_s, previous_s });
                }
                let gap_s = row.t_s - previous_s;
                if !(gap_s.is_finite() && gap_s >= MIN_SAMPLE_GAP_S) {
                    return Err(TrajectoryError::BadGap { line, t_s: row.t_s, previous_s, gap_s });
                }
            }
            samples.push((row.t_s, Pose2::new(row.x_m, row.y_m, row.theta_rad)));
            end_line = line;
        }
        if samples.is_empty() {
            return Err(TrajectoryError::Empty);
        }
        Ok(Self { samples, end_line: Some(end_line) })
    }

    /// A trajectory from samples not read from text (at least one, times increasing: the
    /// caller's to ensure).
    pub fn from_samples(samples: Vec<(f64, Pose2)>) -> Self {
        Self { samples, end_line: None }
    }

    /// The number of ticks from the first to the last sample at `rate_hz`, if at most
    /// `max_ticks`; otherwise an error naming the last sample's line. Computed in floating point
    /// and compared before any conversion, so no end time overflows the count.
    pub fn tick_count(&self, rate_hz: f64, max_ticks: u64) -> Result<u64, TrajectoryError> {
        tick_count(self.span_s(), self.end_line, self.samples.len(), rate_hz, max_ticks)
    }

    /// The pose at time `t_s`, linearly interpolated (held constant beyond the ends).
    pub fn pose_at(&self, t_s: f64) -> Pose2 {
        self.pose_and_velocity_at(t_s).0
    }

    /// The pose at `t_s` and its rate of change (the slope of the segment, per second: m/s, m/s,
    /// rad/s), zero before the first and after the last sample.
    pub fn pose_and_velocity_at(&self, t_s: f64) -> (Pose2, Pose2) {
        let s = &self.samples;
        if t_s <= s[0].0 {
            return (s[0].1, Pose2::default());
        }
        let k = s.partition_point(|(t, _)| *t <= t_s);
        if k >= s.len() {
            return (s[s.len() - 1].1, Pose2::default());
        }
        let ((t0, a), (t1, b)) = (s[k - 1], s[k]);
        let dt = t1 - t0;
        let rate = Pose2::new((b.x_m - a.x_m) / dt, (b.y_m - a.y_m) / dt, (b.theta_rad - a.theta_rad) / dt);
        (a.lerp(b, (t_s - t0) / dt), rate)
    }

    /// Start and end time (s).
    pub fn span_s(&self) -> (f64, f64) {
        (self.samples[0].0, self.samples[self.samples.len() - 1].0)
    }

    /// Time from the first to the last sample (s).
    pub fn duration_s(&self) -> f64 {
        let (t0, t1) = self.span_s();
        t1 - t0
    }
}

/// The ticks from `t0` to `t1` at `rate_hz`, `round((t1 - t0) rate_hz)`, if at most `max_ticks`;
/// else [`TrajectoryError::TooLong`] naming the last sample: `trajectory line {end_line}` (read
/// from CSV) or `trajectory[{n_samples - 1}]`. Compared in floating point before any conversion,
/// so no span overflows the count. Shared by 2D and 3D trajectories.
pub(crate) fn tick_count(
    (t0, t1): (f64, f64),
    end_line: Option<u64>,
    n_samples: usize,
    rate_hz: f64,
    max_ticks: u64,
) -> Result<u64, TrajectoryError> {
    let ticks = ((t1 - t0) * rate_hz).round();
    if ticks.is_nan() || ticks > max_ticks as f64 {
        let at = match end_line {
            Some(l) => format!("trajectory line {l}"),
            None => format!("trajectory[{}]", n_samples.saturating_sub(1)),
        };
        return Err(TrajectoryError::TooLong { at, end_s: t1, span_s: t1 - t0, ticks, rate_hz, max_ticks });
    }
    Ok(ticks as u64)
}

/// How a CSV header whose columns are `found` differs from `want`, without quoting it (a file's
/// lines never appear in errors): "a header whose column 2 is not x_m", or "a header of 3
/// columns" when it is `want` cut short or with more after. For "…, found {this}".
pub fn header_mismatch<'a>(found: impl IntoIterator<Item = &'a str>, want: &[&str]) -> String {
    let found: Vec<&str> = found.into_iter().collect();
    match found.iter().zip(want).position(|(f, w)| f != w) {
        Some(i) => format!("a header whose column {} is not {}", i + 1, want[i]),
        None => format!("a header of {} columns", found.len()),
    }
}

/// At most `n` characters of `s`, with "…" appended when cut: a client's text quoted in a
/// message. The one clipping of quoted text; `needlesim_scene::limit` re-exports it.
pub fn clip(s: &str, n: usize) -> String {
    match s.char_indices().nth(n) {
        None => s.to_owned(),
        Some((i, _)) => format!("{}…", &s[..i]),
    }
}

/// Line numbers of csv records from their byte offsets, counting comment and blank lines too (the
/// csv reader's own count skips them); newlines are counted once, from the previous record on.
pub(crate) struct LineCounter<'a> {
    text: &'a str,
    counted_byte: usize,
    counted_line: u64,
}

impl<'a> LineCounter<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Self { text, counted_byte: 0, counted_line: 1 }
    }

    /// The 1-based line of the record at `byte` (records are asked for in increasing order).
    pub(crate) fn line_at(&mut self, byte: u64) -> u64 {
        let text = self.text;
        // A record's position can be that of comment or blank lines before it: skip them.
        let mut byte = (byte as usize).min(text.len());
        loop {
            match text.as_bytes().get(byte) {
                Some(b'#') => byte = text[byte..].find('\n').map_or(text.len(), |i| byte + i + 1),
                Some(b'\n' | b'\r') => byte += 1,
                _ => break,
            }
        }
        if byte > self.counted_byte {
            self.counted_line += text.as_bytes()[self.counted_byte..byte].iter().filter(|&&b| b == b'\n').count() as u64;
            self.counted_byte = byte;
        }
        self.counted_line
    }
}

/// A csv error as a short message naming the column.
fn csv_kind(e: &csv::Error) -> String {
    csv_kind_in(e, &HEADER)
}

/// A csv error as a short message naming the column of `header`.
pub(crate) fn csv_kind_in(e: &csv::Error, header: &[&str]) -> String {
    match e.kind() {
        csv::ErrorKind::Deserialize { err, .. } => {
            let field = err.field().and_then(|f| header.get(f as usize).copied()).unwrap_or("?");
            format!("column {field} ({})", err.kind())
        }
        csv::ErrorKind::UnequalLengths { expected_len, len, .. } => format!("{len} fields where the header has {expected_len}"),
        _ => e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: &str = "t_s,x_m,y_m,theta_rad\n";

    fn err(text: &str) -> String {
        Trajectory::parse_csv(text).unwrap_err().to_string()
    }

    #[test]
    fn parses_interpolates_and_holds_the_ends() {
        let t = Trajectory::parse_csv(&format!("{H}0,0,1,0\n# comment\n2, 2 ,3,1\n")).unwrap();
        assert_eq!(t.samples.len(), 2);
        assert_eq!(t.end_line, Some(4));
        assert_eq!(t.pose_at(1.0), Pose2::new(1.0, 2.0, 0.5));
        assert_eq!(t.pose_at(-1.0), Pose2::new(0.0, 1.0, 0.0));
        assert_eq!(t.pose_at(7.0), Pose2::new(2.0, 3.0, 1.0));
        let (p, v) = t.pose_and_velocity_at(0.5);
        assert_eq!((p, v), (Pose2::new(0.5, 1.5, 0.25), Pose2::new(1.0, 1.0, 0.5)));
        assert_eq!(t.pose_and_velocity_at(9.0).1, Pose2::default(), "at rest after the end");
        assert_eq!((t.span_s(), t.duration_s()), ((0.0, 2.0), 2.0));
    }

    #[test]
    fn errors_name_the_line_counting_comments_and_the_column() {
        let e = err(&format!("{H}0,0,1,0\n# comment\n\n1,abc,1,0\n"));
        assert!(e.starts_with("trajectory line 5: column x_m") && e.contains("`abc` is not a number"), "{e}");
        let e = err(&format!("{H}0,0,1,0\n1,0,1\n"));
        assert_eq!(e, "trajectory line 3: 3 fields where the header has 4");
        let e = err(&format!("{H}0,0,0,0\n0,1,2,0\n"));
        assert_eq!(e, "trajectory line 3: t_s = 0 does not increase (previous 0)");
        let e = err("t,x,y\n0,0,0\n");
        assert_eq!(e, "trajectory line 1: the header must be t_s,x_m,y_m,theta_rad, found a header whose column 1 is not t_s");
        // issue 35's hostile passes: a header is never quoted (a file's lines never appear in
        // errors), however long; a header cut short or with more columns is told by its count.
        let e = err(&format!("SECRET{}\n0,0,0,0\n", "x".repeat(100_000)));
        assert_eq!(e, "trajectory line 1: the header must be t_s,x_m,y_m,theta_rad, found a header whose column 1 is not t_s");
        let e = err("t_s,x_m,y_m\n0,0,0\n");
        assert_eq!(e, "trajectory line 1: the header must be t_s,x_m,y_m,theta_rad, found a header of 3 columns");
        let e = err("t_s,x_m,y_m,theta_rad,secret_sk_live\n0,0,0,0,0\n");
        assert!(e.ends_with("found a header of 5 columns") && !e.contains("secret"), "{e}");
        let e = err(&format!("{H}0,0,0,0\n1,NaN,2,0\n"));
        assert_eq!(e, "trajectory row 2 (line 3): x_m is NaN, not a finite number");
        assert_eq!(err(H), "trajectory: no samples");
        assert!(err("").starts_with("trajectory line 1: the header must be"), "{}", err(""));
        let long = "9".repeat(100) + "x";
        assert!(err(&format!("{H}0,{long},0,0\n")).contains("…` is not a number"), "a client's value is clipped");
    }

    /// Issue 13 (found by the long fuzzing run of the one parser): finite but huge values were
    /// accepted and interpolated to infinity (`1e308` then `-1e308`: the difference overflows),
    /// and samples a subnormal time apart gave infinite slopes.
    #[test]
    fn issue_13_huge_poses_and_gaps_are_refused_not_interpolated_to_infinity() {
        let e = err(&format!("{H}0.14,1e308,0.03,0.04\n0.34,-1e308,0.08,0.04\n"));
        assert_eq!(e, "trajectory row 1 (line 2): x_m = 1e308 is out of range (at most 1e3 in magnitude)");
        let e = err(&format!("{H}0,0,0,0\n1,0,0,-2e3\n"));
        assert!(e.starts_with("trajectory row 2 (line 3): theta_rad = -2e3 is out of range"), "{e}");
        let e = err(&format!("{H}0,0,0,0\n1e-300,1,0,0\n"));
        assert!(e.starts_with("trajectory line 3: t_s = 1e-300 is 1e-300 s after the previous sample"), "{e}");
        let e = err(&format!("{H}-1e308,0,0,0\n1e308,1,0,0\n"));
        assert!(e.contains("is inf s after the previous sample"), "{e}");
        // At the bounds every sample and slope is finite.
        let t = Trajectory::parse_csv(&format!("{H}0,-1e3,1e3,-1e3\n1e-9,1e3,-1e3,1e3\n")).unwrap();
        let (p, v) = t.pose_and_velocity_at(0.5e-9);
        assert!([p.x_m, p.y_m, p.theta_rad, v.x_m, v.y_m, v.theta_rad].iter().all(|x| x.is_finite()), "{p:?} {v:?}");
    }

    #[test]
    fn tick_count_is_bounded_without_overflow() {
        let t = Trajectory::parse_csv(&format!("{H}0,0,0,0\n2,0,0,0\n")).unwrap();
        assert_eq!(t.tick_count(1000.0, 2000), Ok(2000));
        let e = t.tick_count(1000.0, 1999).unwrap_err().to_string();
        assert!(e.starts_with("trajectory line 3: t_s = 2e0 ends 2e0 s after the first sample, 2e3 ticks"), "{e}");
        let far = Trajectory::from_samples(vec![(0.0, Pose2::default()), (1e300, Pose2::default())]);
        assert!(matches!(far.tick_count(1e10, u64::MAX), Err(TrajectoryError::TooLong { .. })));
    }
}
