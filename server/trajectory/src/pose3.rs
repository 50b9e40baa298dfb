//! 3D base poses and trajectories: the `t_s,x_m,y_m,z_m,qw,qx,qy,qz` CSV of 3D scenes, parsed
//! with errors that name the line and the column, and the pose conventions of the 3D needle.
//!
//! A [`Pose3`] is the needle base's position (m) and orientation, a unit quaternion
//! $q = [w, x, y, z]$ (Hamilton, scalar first) rotating the needle's local frame into the world.
//! In the local frame the shaft runs along $+e_x$ (base to tip) and $e_y$, $e_z$ are the lateral
//! directions $n$, $b$; so the identity points the needle along world $+x$, and a 2D pose
//! $(x, y, \theta)$ is the 3D pose with $q = [\cos\frac\theta2, 0, 0, \sin\frac\theta2]$.
//! [`quat_from_axis_roll`] makes the quaternion from the shaft direction and a roll about it.
//!
//! Between samples the position is interpolated linearly and the orientation by spherical linear
//! interpolation along the shorter arc; the pose is held constant beyond the ends.

use serde::Deserialize;

use crate::{LineCounter, MAX_ABS_POSE, MIN_SAMPLE_GAP_S, clip, csv_kind_in};

/// The column names, in order, of the 3D CSV header.
pub const HEADER3: [&str; 8] = ["t_s", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"];

/// A quaternion is accepted as a rotation when $|\,\|q\| - 1| \le$ this (CSV and TOML values
/// written to 7 significant digits pass), and then normalised.
pub const UNIT_QUAT_TOL: f64 = 1e-6;

/// A 3D base pose: position (m) and orientation (unit quaternion `[w, x, y, z]`, module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose3 {
    pub position_m: [f64; 3],
    pub quat_wxyz: [f64; 4],
}

impl Default for Pose3 {
    fn default() -> Self {
        Self { position_m: [0.0; 3], quat_wxyz: [1.0, 0.0, 0.0, 0.0] }
    }
}

impl Pose3 {
    pub fn new(position_m: [f64; 3], quat_wxyz: [f64; 4]) -> Self {
        Self { position_m, quat_wxyz }
    }

    /// The needle frame's rows `[t, n, b]` in world coordinates: the shaft direction (base to
    /// tip) and the two lateral directions, `R e_x`, `R e_y`, `R e_z`.
    pub fn frame(&self) -> [[f64; 3]; 3] {
        let q = self.quat_wxyz;
        [quat_rotate(q, [1.0, 0.0, 0.0]), quat_rotate(q, [0.0, 1.0, 0.0]), quat_rotate(q, [0.0, 0.0, 1.0])]
    }

    /// The shaft direction (base to tip), a unit vector.
    pub fn axis(&self) -> [f64; 3] {
        quat_rotate(self.quat_wxyz, [1.0, 0.0, 0.0])
    }
}

/// Why a quaternion or an axis is refused.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum RotationError {
    #[error("must be finite")]
    NonFinite,
    #[error("must have unit norm (its norm is {norm}, off by more than {UNIT_QUAT_TOL:e})")]
    NotUnit { norm: f64 },
}

/// `v` divided by its norm, if the norm is within [`UNIT_QUAT_TOL`] of 1 and every entry finite.
pub fn unit<const N: usize>(v: [f64; N]) -> Result<[f64; N], RotationError> {
    if !v.iter().all(|x| x.is_finite()) {
        return Err(RotationError::NonFinite);
    }
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if (norm - 1.0).abs() > UNIT_QUAT_TOL {
        return Err(RotationError::NotUnit { norm });
    }
    Ok(v.map(|x| x / norm))
}

/// The Hamilton product `a ⊗ b` (`[w, x, y, z]`).
pub fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `v` rotated by the unit quaternion `q`: $q\,v\,q^*$.
pub fn quat_rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let [w, x, y, z] = q;
    let u = [x, y, z];
    let cross = |a: [f64; 3], b: [f64; 3]| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let t = cross(u, v).map(|c| 2.0 * c);
    let ut = cross(u, t);
    [v[0] + w * t[0] + ut[0], v[1] + w * t[1] + ut[1], v[2] + w * t[2] + ut[2]]
}

/// The orientation whose shaft direction is the unit vector `axis`, rolled by `roll_rad` about
/// it: the shortest rotation taking $e_x$ to `axis`, then the roll (right-handed about `axis`).
/// For `axis` $= -e_x$ the shortest rotation is not unique: a half turn about $e_z$ is taken (the
/// 2D pose $\theta = \pi$).
pub fn quat_from_axis_roll(axis: [f64; 3], roll_rad: f64) -> [f64; 4] {
    let [ax, ay, az] = axis;
    let q_min = if ax > -1.0 + 1e-12 {
        // [1 + e_x·a, e_x × a], normalised: the half-angle form of the shortest rotation.
        let q = [1.0 + ax, 0.0, -az, ay];
        let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        q.map(|v| v / n)
    } else {
        [0.0, 0.0, 0.0, 1.0]
    };
    let (s, c) = (0.5 * roll_rad).sin_cos();
    quat_mul([c, s * ax, s * ay, s * az], q_min)
}

/// Spherical linear interpolation from `a` to `b` (unit quaternions) along the shorter arc.
pub fn slerp(a: [f64; 4], b: [f64; 4], w: f64) -> [f64; 4] {
    let mut dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let b = if dot < 0.0 {
        dot = -dot;
        b.map(|v| -v)
    } else {
        b
    };
    let (wa, wb) = if dot > 1.0 - 1e-12 {
        (1.0 - w, w)
    } else {
        let theta = dot.min(1.0).acos();
        let s = theta.sin();
        (((1.0 - w) * theta).sin() / s, (w * theta).sin() / s)
    };
    let q = [0, 1, 2, 3].map(|i| wa * a[i] + wb * b[i]);
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    q.map(|v| v / n)
}

/// The angular velocity (rad/s, world frame) of turning from `a` to `b` in `dt_s` at a constant
/// rate along the shorter arc.
fn angular_velocity(a: [f64; 4], b: [f64; 4], dt_s: f64) -> [f64; 3] {
    let conj = [a[0], -a[1], -a[2], -a[3]];
    let mut r = quat_mul(b, conj);
    if r[0] < 0.0 {
        r = r.map(|v| -v);
    }
    let s = (r[1] * r[1] + r[2] * r[2] + r[3] * r[3]).sqrt();
    if s < 1e-15 {
        return [0.0; 3];
    }
    let angle = 2.0 * s.atan2(r[0]);
    [r[1], r[2], r[3]].map(|v| v / s * angle / dt_s)
}

/// Why a 3D trajectory was refused; each names where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Trajectory3Error {
    /// The first line is not `t_s,x_m,y_m,z_m,qw,qx,qy,qz`.
    #[error("trajectory line 1: the header must be t_s,x_m,y_m,z_m,qw,qx,qy,qz, found {found}")]
    Header { found: String },
    /// A row cannot be read: a field that is not a number, a wrong number of fields, bad UTF-8.
    #[error("trajectory line {line}: {message}")]
    Row { line: u64, message: String },
    /// A value is NaN or infinite.
    #[error("trajectory line {line}: {column} is {value}, not a finite number")]
    NonFinite { line: u64, column: &'static str, value: f64 },
    /// A position beyond ±[`MAX_ABS_POSE`].
    #[error("trajectory line {line}: {column} = {value:e} is out of range (at most {MAX_ABS_POSE:e} in magnitude)")]
    OutOfRange { line: u64, column: &'static str, value: f64 },
    /// The quaternion is not of unit norm.
    #[error(
        "trajectory line {line}: the quaternion qw,qx,qy,qz must have unit norm (its norm is {norm}, off by more than {UNIT_QUAT_TOL:e})"
    )]
    NotUnit { line: u64, norm: f64 },
    /// A time does not increase over the previous row's.
    #[error("trajectory line {line}: t_s = {t_s} does not increase (previous {previous_s})")]
    NotIncreasing { line: u64, t_s: f64, previous_s: f64 },
    /// A time follows the previous one by less than [`MIN_SAMPLE_GAP_S`] or by an infinite gap.
    #[error(
        "trajectory line {line}: t_s = {t_s:e} is {gap_s:e} s after the previous sample: the gap must be a finite number of at least {MIN_SAMPLE_GAP_S:e} s"
    )]
    BadGap { line: u64, t_s: f64, gap_s: f64 },
    /// Nothing after the header.
    #[error("trajectory: no samples")]
    Empty,
}

/// A 3D base trajectory: samples strictly increasing in time, at least one, quaternions
/// normalised.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory3 {
    pub samples: Vec<(f64, Pose3)>,
    /// The line of the last sample in the CSV it was read from (None when not read from text).
    pub end_line: Option<u64>,
}

#[derive(Debug, Deserialize)]
struct Row3 {
    t_s: f64,
    x_m: f64,
    y_m: f64,
    z_m: f64,
    qw: f64,
    qx: f64,
    qy: f64,
    qz: f64,
}

impl Trajectory3 {
    /// Parses the CSV text: the header [`HEADER3`], then rows; `#` starts a comment line, fields
    /// are trimmed. Errors name the line (comment and blank lines counted) and the column. Every
    /// value finite, positions within ±[`MAX_ABS_POSE`], quaternions of unit norm within
    /// [`UNIT_QUAT_TOL`] (stored normalised), times increasing by at least [`MIN_SAMPLE_GAP_S`].
    pub fn parse_csv(text: &str) -> Result<Self, Trajectory3Error> {
        let mut rdr = csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).from_reader(text.as_bytes());
        let headers = rdr
            .headers()
            .map_err(|e| Trajectory3Error::Header { found: format!("an unreadable line ({})", csv_kind_in(&e, &HEADER3)) })?
            .clone();
        if headers.iter().ne(HEADER3) {
            return Err(Trajectory3Error::Header { found: crate::header_mismatch(headers.iter(), &HEADER3) });
        }
        let mut lines = LineCounter::new(text);
        let mut samples: Vec<(f64, Pose3)> = Vec::new();
        let mut end_line = 0;
        let mut record = csv::StringRecord::new();
        loop {
            let more = rdr.read_record(&mut record).map_err(|e| {
                let line = e.position().map_or(0, |p| lines.line_at(p.byte()));
                Trajectory3Error::Row { line, message: csv_kind_in(&e, &HEADER3) }
            })?;
            if !more {
                break;
            }
            let line = record.position().map_or(0, |p| lines.line_at(p.byte()));
            let row: Row3 = record.deserialize(Some(&headers)).map_err(|e| {
                let value = match e.kind() {
                    csv::ErrorKind::Deserialize { err, .. } => err.field().and_then(|f| record.get(f as usize)),
                    _ => None,
                };
                let message = match value {
                    Some(v) => format!("{}: `{}` is not a number", csv_kind_in(&e, &HEADER3), clip(v, 32)),
                    None => csv_kind_in(&e, &HEADER3),
                };
                Trajectory3Error::Row { line, message }
            })?;
            let values = [row.t_s, row.x_m, row.y_m, row.z_m, row.qw, row.qx, row.qy, row.qz];
            for (column, value) in HEADER3.into_iter().zip(values) {
                if !value.is_finite() {
                    return Err(Trajectory3Error::NonFinite { line, column, value });
                }
            }
            for (column, value) in HEADER3[1..4].iter().zip([row.x_m, row.y_m, row.z_m]) {
                if value.abs() > MAX_ABS_POSE {
                    return Err(Trajectory3Error::OutOfRange { line, column, value });
                }
            }
            let q = unit([row.qw, row.qx, row.qy, row.qz]).map_err(|e| match e {
                RotationError::NotUnit { norm } => Trajectory3Error::NotUnit { line, norm },
                RotationError::NonFinite => Trajectory3Error::NotUnit { line, norm: f64::NAN },
            })?;
            if let Some(&(previous_s, _)) = samples.last() {
                if row.t_s <= previous_s {
                    return Err(Trajectory3Error::NotIncreasing { line, t_s: row.t_s, previous_s });
                }
                let gap_s = row.t_s - previous_s;
                if !(gap_s.is_finite() && gap_s >= MIN_SAMPLE_GAP_S) {
                    return Err(Trajectory3Error::BadGap { line, t_s: row.t_s, gap_s });
                }
            }
            samples.push((row.t_s, Pose3::new([row.x_m, row.y_m, row.z_m], q)));
            end_line = line;
        }
        if samples.is_empty() {
            return Err(Trajectory3Error::Empty);
        }
        Ok(Self { samples, end_line: Some(end_line) })
    }

    /// A trajectory from samples not read from text (at least one, times increasing, unit
    /// quaternions: the caller's to ensure).
    pub fn from_samples(samples: Vec<(f64, Pose3)>) -> Self {
        Self { samples, end_line: None }
    }

    /// The number of ticks from the first to the last sample at `rate_hz`, if at most
    /// `max_ticks`; otherwise [`crate::TrajectoryError::TooLong`] naming the last sample's line
    /// (as [`crate::Trajectory::tick_count`]).
    pub fn tick_count(&self, rate_hz: f64, max_ticks: u64) -> Result<u64, crate::TrajectoryError> {
        crate::tick_count(self.span_s(), self.end_line, self.samples.len(), rate_hz, max_ticks)
    }

    /// The pose at `t_s` (module docs: linear position, slerp orientation, ends held).
    pub fn pose_at(&self, t_s: f64) -> Pose3 {
        self.pose_and_velocity_at(t_s).0
    }

    /// The pose at `t_s`, its linear velocity (m/s) and angular velocity (rad/s, world frame);
    /// both zero before the first and after the last sample.
    pub fn pose_and_velocity_at(&self, t_s: f64) -> (Pose3, [f64; 3], [f64; 3]) {
        let s = &self.samples;
        if t_s <= s[0].0 {
            return (s[0].1, [0.0; 3], [0.0; 3]);
        }
        let k = s.partition_point(|(t, _)| *t <= t_s);
        if k >= s.len() {
            return (s[s.len() - 1].1, [0.0; 3], [0.0; 3]);
        }
        let ((t0, a), (t1, b)) = (s[k - 1], s[k]);
        let dt = t1 - t0;
        let w = (t_s - t0) / dt;
        let position_m = [0, 1, 2].map(|i| a.position_m[i] + w * (b.position_m[i] - a.position_m[i]));
        let velocity = [0, 1, 2].map(|i| (b.position_m[i] - a.position_m[i]) / dt);
        let pose = Pose3::new(position_m, slerp(a.quat_wxyz, b.quat_wxyz, w));
        (pose, velocity, angular_velocity(a.quat_wxyz, b.quat_wxyz, dt))
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

#[cfg(test)]
mod tests {
    use super::*;

    const H: &str = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n";
    const DOWN: &str = "0.7071067811865476,0,0.7071067811865476,0";

    fn err(text: &str) -> String {
        Trajectory3::parse_csv(text).unwrap_err().to_string()
    }

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn conventions_identity_points_along_x_and_down_is_a_quarter_turn_about_y() {
        assert_eq!(Pose3::default().axis(), [1.0, 0.0, 0.0]);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let down = Pose3::new([0.0; 3], [s, 0.0, s, 0.0]);
        assert!(close(&down.axis(), &[0.0, 0.0, -1.0], 1e-15), "{:?}", down.axis());
        assert!(close(&quat_from_axis_roll([0.0, 0.0, -1.0], 0.0), &[s, 0.0, s, 0.0], 1e-15));
        // The 2D pose (θ about z) and the antiparallel case.
        let th: f64 = 0.7;
        let q = quat_from_axis_roll([th.cos(), th.sin(), 0.0], 0.0);
        assert!(close(&q, &[(th / 2.0).cos(), 0.0, 0.0, (th / 2.0).sin()], 1e-15), "{q:?}");
        let q = quat_from_axis_roll([-1.0, 0.0, 0.0], 0.0);
        assert!(close(&Pose3::new([0.0; 3], q).axis(), &[-1.0, 0.0, 0.0], 1e-15));
        // A roll turns n and b about t and keeps t.
        for axis in [[0.0, 0.0, -1.0], [0.6, 0.0, -0.8], [0.48, 0.6, -0.64]] {
            let f0 = Pose3::new([0.0; 3], quat_from_axis_roll(axis, 0.0)).frame();
            let f1 = Pose3::new([0.0; 3], quat_from_axis_roll(axis, std::f64::consts::FRAC_PI_2)).frame();
            assert!(close(&f0[0], &axis, 1e-15) && close(&f1[0], &axis, 1e-15));
            assert!(close(&f1[1], &f0[2], 1e-15), "a quarter roll takes n to b: {f0:?} {f1:?}");
        }
    }

    #[test]
    fn parses_and_interpolates_position_linearly_and_orientation_by_slerp() {
        let t = Trajectory3::parse_csv(&format!("{H}0,0,0,0.2,1,0,0,0\n# comment\n2,0,0,0.1,{DOWN}\n")).unwrap();
        assert_eq!(t.samples.len(), 2);
        let (p, v, w) = t.pose_and_velocity_at(1.0);
        assert!(close(&p.position_m, &[0.0, 0.0, 0.15], 1e-15));
        let q45 = [(std::f64::consts::PI / 8.0).cos(), 0.0, (std::f64::consts::PI / 8.0).sin(), 0.0];
        assert!(close(&p.quat_wxyz, &q45, 1e-15), "{:?}", p.quat_wxyz);
        assert!(close(&v, &[0.0, 0.0, -0.05], 1e-15));
        assert!(close(&w, &[0.0, std::f64::consts::FRAC_PI_4, 0.0], 1e-12), "{w:?}");
        assert_eq!(t.pose_at(9.0), t.samples[1].1);
        assert_eq!(t.pose_and_velocity_at(-1.0).1, [0.0; 3]);
        assert_eq!(t.duration_s(), 2.0);
    }

    #[test]
    fn errors_name_the_line_and_the_column() {
        let e = err(&format!("{H}0,0,0,0,1,0,0,0\n# comment\n\n1,abc,0,0,1,0,0,0\n"));
        assert!(e.starts_with("trajectory line 5: column x_m") && e.contains("`abc` is not a number"), "{e}");
        assert_eq!(err(&format!("{H}0,0,0,0,1,0,0\n")), "trajectory line 2: 7 fields where the header has 8");
        assert_eq!(
            err(&format!("{H}0,0,0,0,1,0,0,0\n1,0,0,0,1,0,0.1,0\n")),
            "trajectory line 3: the quaternion qw,qx,qy,qz must have unit norm (its norm is 1.004987562112089, off by more than 1e-6)"
        );
        assert_eq!(err(&format!("{H}0,0,0,0,1,0,0,0\n0,0,0,0,1,0,0,0\n")), "trajectory line 3: t_s = 0 does not increase (previous 0)");
        assert_eq!(err(&format!("{H}0,0,0,NaN,1,0,0,0\n")), "trajectory line 2: z_m is NaN, not a finite number");
        assert!(err(&format!("{H}0,0,2e3,0,1,0,0,0\n")).starts_with("trajectory line 2: y_m = 2e3 is out of range"));
        assert!(err(&format!("{H}0,0,0,0,1,0,0,0\n1e-300,0,0,0,1,0,0,0\n")).starts_with("trajectory line 3: t_s = 1e-300"));
        assert_eq!(
            err("t_s,x_m,y_m,theta_rad\n0,0,0,0\n"),
            "trajectory line 1: the header must be t_s,x_m,y_m,z_m,qw,qx,qy,qz, found a header whose column 4 is not z_m"
        );
        assert_eq!(err(H), "trajectory: no samples");
        // Seven digits pass and are normalised.
        let t = Trajectory3::parse_csv(&format!("{H}0,0,0,0,0.7071068,0,0.7071068,0\n")).unwrap();
        let q = t.samples[0].1.quat_wxyz;
        assert!((q.iter().map(|v| v * v).sum::<f64>() - 1.0).abs() < 1e-15);
    }
}
