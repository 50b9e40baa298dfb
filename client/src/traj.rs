//! Base trajectories: `t_s,x_m,y_m,theta_rad` CSV files, checked line by line.

use std::path::Path;

use anyhow::{Result, anyhow, bail};
use needlesim_proto::v1 as pb;

/// Samples of the base pose, strictly increasing in time.
#[derive(Debug, Clone)]
pub struct Trajectory {
    pub samples: Vec<(f64, pb::Pose2)>,
}

const HEADER: [&str; 4] = ["t_s", "x_m", "y_m", "theta_rad"];

impl Trajectory {
    /// Reads and checks a trajectory file; errors name the file and the line.
    pub fn read(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| anyhow!("cannot read the trajectory {}: {e}", path.display()))?;
        Self::parse(&text).map_err(|e| anyhow!("{}: {e}", path.display()))
    }

    /// Parses the CSV text; errors start with `line N`.
    pub fn parse(text: &str) -> Result<Self> {
        let mut samples: Vec<(f64, pb::Pose2)> = Vec::new();
        let mut header_seen = false;
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let raw = raw.trim();
            if raw.is_empty() || raw.starts_with('#') {
                continue;
            }
            let rec: Vec<&str> = raw.split(',').map(str::trim).collect();
            if !header_seen {
                if rec != HEADER {
                    bail!("line {line}: the header must be t_s,x_m,y_m,theta_rad, found {raw}");
                }
                header_seen = true;
                continue;
            }
            if rec.len() != 4 {
                bail!("line {line}: expected 4 columns (t_s,x_m,y_m,theta_rad), found {}", rec.len());
            }
            let mut v = [0.0; 4];
            for (i, field) in rec.iter().copied().enumerate() {
                let x: f64 = field.parse().map_err(|_| anyhow!("line {line}: {} = {field:?} is not a number", HEADER[i]))?;
                if !x.is_finite() {
                    bail!("line {line}: {} = {field} is not a finite number", HEADER[i]);
                }
                v[i] = x;
            }
            if let Some(&(prev, _)) = samples.last()
                && v[0] <= prev
            {
                bail!("line {line}: t_s = {} does not increase (previous {prev})", v[0]);
            }
            samples.push((v[0], pb::Pose2 { x_m: v[1], y_m: v[2], theta_rad: v[3] }));
        }
        if !header_seen {
            bail!("line 1: empty file; expected the header t_s,x_m,y_m,theta_rad");
        }
        if samples.is_empty() {
            bail!("no samples after the header");
        }
        Ok(Self { samples })
    }

    /// First and last time.
    pub fn span_s(&self) -> (f64, f64) {
        (self.samples[0].0, self.samples[self.samples.len() - 1].0)
    }

    /// The pose at `t_s`, interpolated linearly, held constant beyond the ends.
    pub fn pose_at(&self, t_s: f64) -> pb::Pose2 {
        let s = &self.samples;
        if t_s <= s[0].0 {
            return s[0].1;
        }
        let k = s.partition_point(|(t, _)| *t <= t_s);
        if k >= s.len() {
            return s[s.len() - 1].1;
        }
        let (t0, a) = s[k - 1];
        let (t1, b) = s[k];
        let w = (t_s - t0) / (t1 - t0);
        pb::Pose2 {
            x_m: a.x_m + w * (b.x_m - a.x_m),
            y_m: a.y_m + w * (b.y_m - a.y_m),
            theta_rad: a.theta_rad + w * (b.theta_rad - a.theta_rad),
        }
    }

    /// As the Simulate RPC wants it.
    pub fn to_pb(&self) -> Vec<pb::TrajectorySample> {
        self.samples.iter().map(|(t, p)| pb::TrajectorySample { t_s: *t, base: Some(*p) }).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_interpolates() {
        let t = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,0,1,0\n# comment\n2, 2 ,3,1\n").unwrap();
        assert_eq!(t.samples.len(), 2);
        let p = t.pose_at(1.0);
        assert!((p.x_m - 1.0).abs() < 1e-12 && (p.y_m - 2.0).abs() < 1e-12 && (p.theta_rad - 0.5).abs() < 1e-12);
        assert_eq!(t.pose_at(5.0).x_m, 2.0);
    }

    #[test]
    fn errors_name_the_line() {
        let e = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,0,1,0\n# comment\n\n1,abc,1,0\n").unwrap_err().to_string();
        assert!(e.contains("line 5") && e.contains("x_m"), "{e}");
        let e = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,0,1,0\n1,0,1\n").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("4 columns"), "{e}");
        let e = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,0,1,0\n0,0,1,0\n").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("does not increase"), "{e}");
        let e = Trajectory::parse("t,x,y\n").unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("header"), "{e}");
        let e = Trajectory::parse("t_s,x_m,y_m,theta_rad\n0,NaN,1,0\n").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("finite"), "{e}");
    }
}
