//! Base trajectories for `needlesim drive` and `needlesim simulate`: files read here, parsed by
//! needlesim-trajectory (the one parser of the `t_s,x_m,y_m,theta_rad` CSV), and turned into the
//! API's poses.

use std::path::Path;

use anyhow::{Result, anyhow};
use needlesim_proto::v1 as pb;

/// Samples of the base pose, strictly increasing in time.
#[derive(Debug, Clone)]
pub struct Trajectory(needlesim_trajectory::Trajectory);

impl Trajectory {
    /// Reads and checks a trajectory file; errors name the file and the line.
    pub fn read(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| anyhow!("cannot read the trajectory {}: {e}", path.display()))?;
        Ok(Self(needlesim_trajectory::Trajectory::parse_csv(&text).map_err(|e| anyhow!("{}: {e}", path.display()))?))
    }

    /// First and last time.
    pub fn span_s(&self) -> (f64, f64) {
        self.0.span_s()
    }

    /// The pose at `t_s`, interpolated linearly, held constant beyond the ends.
    pub fn pose_at(&self, t_s: f64) -> pb::Pose2 {
        pose_to_pb(self.0.pose_at(t_s))
    }

    /// As the Simulate RPC wants it.
    pub fn to_pb(&self) -> Vec<pb::TrajectorySample> {
        self.0.samples.iter().map(|&(t_s, p)| pb::TrajectorySample { t_s, base: Some(pose_to_pb(p)) }).collect()
    }
}

fn pose_to_pb(p: needlesim_trajectory::Pose2) -> pb::Pose2 {
    pb::Pose2 { x_m: p.x_m, y_m: p.y_m, theta_rad: p.theta_rad }
}
