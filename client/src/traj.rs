//! Base trajectories for `needlesim drive` and `needlesim simulate`: files read here, parsed by
//! needlesim-trajectory (the one parser of the `t_s,x_m,y_m,theta_rad` CSV and of the 3D
//! `t_s,x_m,y_m,z_m,qw,qx,qy,qz` CSV), and turned into the API's poses. The header decides the
//! dimension ([`AnyTrajectory::read`]).

use std::path::Path;

use anyhow::{Result, anyhow};
use needlesim_proto::v1 as pb;
use needlesim_trajectory::pose3::HEADER3;

/// Samples of the base pose, strictly increasing in time.
#[derive(Debug, Clone)]
pub struct Trajectory(needlesim_trajectory::Trajectory);

impl Trajectory {
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
        self.0.samples.iter().map(|&(t_s, p)| pb::TrajectorySample { t_s, base: Some(pose_to_pb(p)), base3: None }).collect()
    }
}

fn pose_to_pb(p: needlesim_trajectory::Pose2) -> pb::Pose2 {
    pb::Pose2 { x_m: p.x_m, y_m: p.y_m, theta_rad: p.theta_rad }
}

/// Samples of a 3D base pose (position, unit quaternion), strictly increasing in time.
#[derive(Debug, Clone)]
pub struct Trajectory3(needlesim_trajectory::Trajectory3);

impl Trajectory3 {
    /// First and last time.
    pub fn span_s(&self) -> (f64, f64) {
        self.0.span_s()
    }

    /// The pose at `t_s`: position linear, orientation by slerp, held constant beyond the ends.
    pub fn pose_at(&self, t_s: f64) -> pb::Pose3 {
        pose3_to_pb(self.0.pose_at(t_s))
    }

    /// As the Simulate RPC wants it (`base3`).
    pub fn to_pb(&self) -> Vec<pb::TrajectorySample> {
        self.0.samples.iter().map(|&(t_s, p)| pb::TrajectorySample { t_s, base: None, base3: Some(pose3_to_pb(p)) }).collect()
    }
}

fn pose3_to_pb(p: needlesim_trajectory::Pose3) -> pb::Pose3 {
    let [x, y, z] = p.position_m;
    let [w, qx, qy, qz] = p.quat_wxyz;
    pb::Pose3 { position_m: Some(pb::Vec3 { x, y, z }), orientation: Some(pb::Quaternion { w, x: qx, y: qy, z: qz }) }
}

/// A trajectory file of either dimension.
#[derive(Debug, Clone)]
pub enum AnyTrajectory {
    Two(Trajectory),
    Three(Trajectory3),
}

impl AnyTrajectory {
    /// Reads and checks a trajectory file; its header (the first line that is not blank or a
    /// `#` comment) decides the dimension: `t_s,x_m,y_m,z_m,qw,qx,qy,qz` is 3D, anything else
    /// is read as 2D (`t_s,x_m,y_m,theta_rad`). Errors name the file and the line.
    pub fn read(path: &Path) -> Result<Self> {
        let text = needlesim_localfile::read_local_file(path, needlesim_localfile::MAX_LOCAL_FILE_BYTES)
            .map_err(|e| anyhow!("{}", e.named("trajectory")))?;
        let header = text.lines().find(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#')).unwrap_or_default();
        if header.split(',').map(str::trim).eq(HEADER3) {
            let t = needlesim_trajectory::Trajectory3::parse_csv(&text).map_err(|e| anyhow!("{}: {e}", path.display()))?;
            return Ok(Self::Three(Trajectory3(t)));
        }
        match needlesim_trajectory::Trajectory::parse_csv(&text) {
            Ok(t) => Ok(Self::Two(Trajectory(t))),
            Err(e @ needlesim_trajectory::TrajectoryError::Header { .. }) => Err(anyhow!(
                "{}: {e} (a 2D trajectory has the header t_s,x_m,y_m,theta_rad, a 3D one t_s,x_m,y_m,z_m,qw,qx,qy,qz)",
                path.display()
            )),
            Err(e) => Err(anyhow!("{}: {e}", path.display())),
        }
    }

    /// 2 or 3.
    pub fn dimension(&self) -> u32 {
        match self {
            Self::Two(_) => 2,
            Self::Three(_) => 3,
        }
    }

    /// As the Simulate RPC wants it.
    pub fn to_pb(&self) -> Vec<pb::TrajectorySample> {
        match self {
            Self::Two(t) => t.to_pb(),
            Self::Three(t) => t.to_pb(),
        }
    }
}

/// The columns of a trajectory of `dimension`, for messages.
pub fn header_of(dimension: u32) -> &'static str {
    if dimension == 3 { "t_s,x_m,y_m,z_m,qw,qx,qy,qz" } else { "t_s,x_m,y_m,theta_rad" }
}
