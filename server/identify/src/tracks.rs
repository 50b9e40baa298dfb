//! Marker tracks: the positions of every marker in every frame, in pixels and in metres, and
//! their CSV form (the interface between tracking and the fits).
//!
//! CSV, one row per frame and marker, frames in order, markers `0..n_markers` in each frame:
//! ```text
//! frame,t_s,marker,x_px,y_px,x_m,y_m,detected
//! 0,0.000,0,103.512,88.204,0.010000,0.020000,1
//! ```
//! `detected = 0` marks a position filled in by the tracker (the marker was not found in that
//! frame); fits may use or skip such rows. Metres are in the tissue's (mesh) frame.

use anyhow::{Context, Result, bail};
use needlesim_scene::limit::{clip, header_mismatch};

/// The tracked markers of an experiment: `n_frames × n_markers` positions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MarkerTracks {
    /// Time of each frame.
    pub times_s: Vec<f64>,
    pub n_markers: usize,
    /// Pixel positions, frame-major: `positions_px[frame * n_markers + marker]`.
    pub positions_px: Vec<[f64; 2]>,
    /// Positions in metres (tissue frame), same layout.
    pub positions_m: Vec<[f64; 2]>,
    /// Whether each position was detected (false: filled in).
    pub detected: Vec<bool>,
}

impl MarkerTracks {
    /// The number of frames.
    pub fn n_frames(&self) -> usize {
        self.times_s.len()
    }
    /// Position of `marker` in `frame`, metres.
    pub fn position_m(&self, frame: usize, marker: usize) -> [f64; 2] {
        self.positions_m[frame * self.n_markers + marker]
    }
    /// Displacement of `marker` in `frame` from frame 0, metres.
    pub fn displacement_m(&self, frame: usize, marker: usize) -> [f64; 2] {
        let (p, p0) = (self.position_m(frame, marker), self.position_m(0, marker));
        [p[0] - p0[0], p[1] - p0[1]]
    }

    /// Writes the CSV form.
    pub fn to_csv(&self) -> String {
        let mut s = String::from("frame,t_s,marker,x_px,y_px,x_m,y_m,detected\n");
        for f in 0..self.n_frames() {
            for m in 0..self.n_markers {
                let k = f * self.n_markers + m;
                let (px, pm) = (self.positions_px[k], self.positions_m[k]);
                s.push_str(&format!("{f},{},{m},{},{},{},{},{}\n", self.times_s[f], px[0], px[1], pm[0], pm[1], self.detected[k] as u8));
            }
        }
        s
    }

    /// Parses the CSV form; errors name the line and what is wrong (a marker count that changes
    /// between frames, frames or markers out of order, times that do not increase, bad numbers).
    pub fn from_csv(text: &str) -> Result<Self> {
        let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
        let header = lines.next().map(|(_, l)| l.trim()).unwrap_or("");
        if header != "frame,t_s,marker,x_px,y_px,x_m,y_m,detected" {
            // Not quoted: a file's lines never appear in errors (a value is, clipped).
            bail!(
                "marker tracks: line 1 must be the header 'frame,t_s,marker,x_px,y_px,x_m,y_m,detected', found {}",
                header_mismatch(header.split(',').map(str::trim), &["frame", "t_s", "marker", "x_px", "y_px", "x_m", "y_m", "detected"])
            );
        }
        let mut out = MarkerTracks::default();
        let mut markers_in_frame = 0usize;
        for (i, line) in lines {
            let ln = i + 1;
            let cols: Vec<&str> = line.split(',').map(str::trim).collect();
            if cols.len() != 8 {
                bail!("marker tracks line {ln}: expected 8 columns, found {}", cols.len());
            }
            let num = |k: usize, name: &str| -> Result<f64> {
                let v: f64 =
                    cols[k].parse().with_context(|| format!("marker tracks line {ln}: {name} `{}` is not a number", clip(cols[k], 32)))?;
                if !v.is_finite() {
                    bail!("marker tracks line {ln}: {name} is not finite");
                }
                Ok(v)
            };
            let frame: usize =
                cols[0].parse().with_context(|| format!("marker tracks line {ln}: frame `{}` is not an index", clip(cols[0], 32)))?;
            let marker: usize =
                cols[2].parse().with_context(|| format!("marker tracks line {ln}: marker `{}` is not an index", clip(cols[2], 32)))?;
            let t = num(1, "t_s")?;
            if frame == out.times_s.len() {
                if frame > 0 && markers_in_frame != out.n_markers {
                    bail!("marker tracks line {ln}: frame {} has {markers_in_frame} markers but frame 0 has {}", frame - 1, out.n_markers);
                }
                if let Some(&prev) = out.times_s.last()
                    && t <= prev
                {
                    bail!("marker tracks line {ln}: frame {frame} time {t} s does not come after {prev} s");
                }
                out.times_s.push(t);
                markers_in_frame = 0;
            } else if frame.checked_add(1) != Some(out.times_s.len()) {
                bail!(
                    "marker tracks line {ln}: frame {frame} out of order (expected {} or {})",
                    out.times_s.len().saturating_sub(1),
                    out.times_s.len()
                );
            }
            if marker != markers_in_frame {
                bail!("marker tracks line {ln}: marker {marker} out of order (expected {markers_in_frame})");
            }
            if frame > 0 && marker >= out.n_markers {
                bail!("marker tracks line {ln}: frame {frame} has more markers than frame 0 ({})", out.n_markers);
            }
            markers_in_frame += 1;
            if frame == 0 {
                out.n_markers = markers_in_frame;
            }
            out.positions_px.push([num(3, "x_px")?, num(4, "y_px")?]);
            out.positions_m.push([num(5, "x_m")?, num(6, "y_m")?]);
            out.detected.push(match cols[7] {
                "1" => true,
                "0" => false,
                other => bail!("marker tracks line {ln}: detected must be 0 or 1, found `{}`", clip(other, 32)),
            });
        }
        if out.times_s.is_empty() {
            bail!("marker tracks: no rows after the header");
        }
        if markers_in_frame != out.n_markers {
            bail!("marker tracks: the last frame has {markers_in_frame} markers but frame 0 has {}", out.n_markers);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_round_trip_and_errors() {
        let t = MarkerTracks {
            times_s: vec![0.0, 0.5],
            n_markers: 2,
            positions_px: vec![[1.5, 2.25], [3.0, 4.0], [1.75, 2.5], [3.125, 4.0]],
            positions_m: vec![[0.01, 0.02], [0.03, 0.04], [0.0101, 0.0202], [0.0301, 0.04]],
            detected: vec![true, true, false, true],
        };
        let back = MarkerTracks::from_csv(&t.to_csv()).unwrap();
        assert_eq!(back, t);
        assert!((back.displacement_m(1, 0)[0] - 1e-4).abs() < 1e-15);
        let mut missing = t.to_csv();
        missing = missing.lines().take(4).collect::<Vec<_>>().join("\n");
        let e = MarkerTracks::from_csv(&missing).unwrap_err().to_string();
        assert!(e.contains("last frame has 1 markers"), "{e}");
        let bad = t.to_csv().replace("0.5,1,", "0.5,2,");
        assert!(MarkerTracks::from_csv(&bad).unwrap_err().to_string().contains("marker 2 out of order"));
    }

    /// Found by the fuzzer (issue 13): a frame index of usize::MAX overflowed `frame + 1` (a panic
    /// in debug builds) instead of being reported out of order.
    #[test]
    fn issue_13_huge_frame_index_is_an_error() {
        let text = "frame,t_s,marker,x_px,y_px,x_m,y_m,detected\n0,0,0,1,1,0,0,1\n18446744073709551615,0.1,0,1,1,0,0,1\n";
        let e = MarkerTracks::from_csv(text).unwrap_err().to_string();
        assert_eq!(e, "marker tracks line 3: frame 18446744073709551615 out of order (expected 0 or 1)");
    }
}
