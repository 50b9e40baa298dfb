//! The experiment logs the fits read: the probe log (probe displacement and applied force) and
//! the needle base force log, as CSV with an exact header; and linear interpolation of a logged
//! series at the frame times. Always built (the service parses these logs); the synthetic
//! experiments that write them are in `experiment` (feature `synthetic`).

use anyhow::{Context, Result, bail};
use needlesim_core::num::num;
use needlesim_scene::limit::{clip, header_mismatch};

/// Linear interpolation of `values` sampled at increasing `times` (clamped at the ends).
pub fn interp<const N: usize>(times: &[f64], values: &[[f64; N]], t: f64) -> [f64; N] {
    if t <= times[0] {
        return values[0];
    }
    let k = times.partition_point(|&x| x <= t);
    if k >= times.len() {
        return values[times.len() - 1];
    }
    let w = (t - times[k - 1]) / (times[k] - times[k - 1]);
    std::array::from_fn(|i| values[k - 1][i] + w * (values[k][i] - values[k - 1][i]))
}

/// Parses a numeric CSV with an exact header; rows are `N` finite numbers, the first column (a
/// time) strictly increasing. Errors name the file kind and the line.
pub fn parse_numeric_csv<const N: usize>(kind: &str, header: &[&str; N], text: &str) -> Result<Vec<[f64; N]>> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let found = lines.next().map(|(_, l)| l.trim()).unwrap_or("");
    let want = header.join(",");
    if found != want {
        // Not quoted: a file's lines never appear in errors (a value is, clipped).
        bail!("{kind}: the header must be '{want}', found {}", header_mismatch(found.split(',').map(str::trim), header));
    }
    let mut rows: Vec<[f64; N]> = Vec::new();
    for (i, line) in lines {
        let ln = i + 1;
        let cols: Vec<&str> = line.split(',').map(str::trim).collect();
        if cols.len() != N {
            bail!("{kind} line {ln}: expected {N} columns, found {}", cols.len());
        }
        let mut row = [0.0; N];
        for k in 0..N {
            let v: f64 =
                cols[k].parse().with_context(|| format!("{kind} line {ln}: {} `{}` is not a number", header[k], clip(cols[k], 32)))?;
            if !v.is_finite() {
                bail!("{kind} line {ln}: {} is not finite", header[k]);
            }
            row[k] = v;
        }
        if let Some(prev) = rows.last()
            && row[0] <= prev[0]
        {
            bail!("{kind} line {ln}: {} = {} does not come after {}", header[0], num(row[0]), num(prev[0]));
        }
        rows.push(row);
    }
    if rows.is_empty() {
        bail!("{kind}: no rows after the header");
    }
    Ok(rows)
}

/// A probe log: the probe's displacement and the force it applies to the tissue over time.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ProbeLog {
    pub times_s: Vec<f64>,
    pub disp_m: Vec<[f64; 2]>,
    pub force_n: Vec<[f64; 2]>,
}

const PROBE_HEADER: [&str; 5] = ["t_s", "probe_disp_x_m", "probe_disp_y_m", "force_x_n", "force_y_n"];
const FORCE_HEADER: [&str; 4] = ["t_s", "force_x_n", "force_y_n", "depth_m"];

impl ProbeLog {
    pub fn to_csv(&self) -> String {
        let mut s = PROBE_HEADER.join(",") + "\n";
        for k in 0..self.times_s.len() {
            let (d, f) = (self.disp_m[k], self.force_n[k]);
            s.push_str(&format!("{},{:e},{:e},{:e},{:e}\n", self.times_s[k], d[0], d[1], f[0], f[1]));
        }
        s
    }
    /// Parses the CSV form (errors name the line).
    pub fn from_csv(text: &str) -> Result<Self> {
        let rows = parse_numeric_csv("probe log", &PROBE_HEADER, text)?;
        Ok(Self {
            times_s: rows.iter().map(|r| r[0]).collect(),
            disp_m: rows.iter().map(|r| [r[1], r[2]]).collect(),
            force_n: rows.iter().map(|r| [r[3], r[4]]).collect(),
        })
    }
}

/// A needle base force log: the force on the needle base and the insertion depth over time.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ForceLog {
    pub times_s: Vec<f64>,
    pub force_n: Vec<[f64; 2]>,
    pub depth_m: Vec<f64>,
}

impl ForceLog {
    pub fn to_csv(&self) -> String {
        let mut s = FORCE_HEADER.join(",") + "\n";
        for k in 0..self.times_s.len() {
            let f = self.force_n[k];
            s.push_str(&format!("{},{:e},{:e},{:e}\n", self.times_s[k], f[0], f[1], self.depth_m[k]));
        }
        s
    }
    /// Parses the CSV form (errors name the line).
    pub fn from_csv(text: &str) -> Result<Self> {
        let rows = parse_numeric_csv("force log", &FORCE_HEADER, text)?;
        Ok(Self {
            times_s: rows.iter().map(|r| r[0]).collect(),
            force_n: rows.iter().map(|r| [r[1], r[2]]).collect(),
            depth_m: rows.iter().map(|r| r[3]).collect(),
        })
    }
}
