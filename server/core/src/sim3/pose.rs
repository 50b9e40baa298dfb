//! The 6-DOF base pose of the rigid needle in 3D, its needle frame, and the per-tick clamp.
//!
//! The base frame is the world frame rotated by the unit quaternion $q = [w, x, y, z]$ (Hamilton,
//! scalar first; rotation $R$). The needle leaves the base along the base frame's local $+x$, the
//! convention of the 3D scenes' poses (`needlesim_trajectory::pose3`) and of the 2D needle at
//! $\theta = 0$: the identity points the needle along world $+x$, and
//! [`BasePose3::straight_down`] (a quarter turn about $+y$) points it down, world $-z$, into the
//! top face of a phantom whose $z$ is up. The needle frame's rows are
//! $$t = R\,e_x,\quad n = R\,e_y,\quad b = t \times n = R\,e_z,$$
//! so the roll of the base about the shaft turns $n$ and $b$ (a bevel tip will use it) and leaves
//! $t$. A shaft point at arc length $s$ from the base is $p(s) = x_b + s\,t$.

use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};

/// Largest $\big|\,\|q\| - 1\big|$ accepted for an orientation given as four numbers.
pub const UNIT_QUATERNION_TOL: f64 = 1e-6;

/// Why a base pose is refused.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum PoseError {
    /// A component of the position (m) or of the orientation quaternion is NaN or infinite.
    #[error("the base {what} has a non-finite component")]
    NonFinite {
        /// "position" or "orientation".
        what: &'static str,
    },
    /// The orientation quaternion's norm is farther than [`UNIT_QUATERNION_TOL`] from 1.
    #[error("the base orientation quaternion has norm {}, not 1 (tolerance {UNIT_QUATERNION_TOL:e})", crate::num::num(*norm))]
    NotUnit { norm: f64 },
}

/// The pose of the needle base: position (m) and orientation (unit quaternion).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BasePose3 {
    /// Base position, world, m.
    pub position_m: [f64; 3],
    /// Base orientation; the needle axis is its local $+x$ (module docs).
    pub orientation: UnitQuaternion<f64>,
}

impl Default for BasePose3 {
    fn default() -> Self {
        Self { position_m: [0.0; 3], orientation: UnitQuaternion::identity() }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl BasePose3 {
    /// A pose from a position (m) and a quaternion `[w, x, y, z]` whose norm is 1 within
    /// [`UNIT_QUATERNION_TOL`] (it is then normalised).
    ///
    /// Errors: [`PoseError::NonFinite`] naming the position or the orientation,
    /// [`PoseError::NotUnit`] for a quaternion that is not unit.
    pub fn new(position_m: [f64; 3], quaternion_wxyz: [f64; 4]) -> Result<Self, PoseError> {
        if !position_m.iter().all(|v| v.is_finite()) {
            return Err(PoseError::NonFinite { what: "position" });
        }
        if !quaternion_wxyz.iter().all(|v| v.is_finite()) {
            return Err(PoseError::NonFinite { what: "orientation" });
        }
        let [w, x, y, z] = quaternion_wxyz;
        let q = Quaternion::new(w, x, y, z);
        let norm = q.norm();
        if (norm - 1.0).abs() > UNIT_QUATERNION_TOL {
            return Err(PoseError::NotUnit { norm });
        }
        Ok(Self { position_m, orientation: UnitQuaternion::new_normalize(q) })
    }

    /// A pose from a position and a rotation given as a unit quaternion (checked by
    /// [`BasePose3::check`] when stepped).
    pub fn from_rotation(position_m: [f64; 3], orientation: UnitQuaternion<f64>) -> Self {
        Self { position_m, orientation }
    }

    /// The pose at `position_m` pointing the needle straight down (world $-z$): a quarter turn
    /// about world $+y$, so $n = +y$ and $b = +x$.
    pub fn straight_down(position_m: [f64; 3]) -> Self {
        Self { position_m, orientation: UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2) }
    }

    /// A pose at `position_m` whose needle axis $t$ is `axis` (normalised; any length > 0), with
    /// the smallest rotation from the identity (world $+x$).
    pub fn looking_along(position_m: [f64; 3], axis: [f64; 3]) -> Self {
        let a = Vector3::new(axis[0], axis[1], axis[2]);
        let q = UnitQuaternion::rotation_between(&Vector3::x(), &a)
            .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI));
        Self { position_m, orientation: q }
    }

    /// The pose turned by `rotation` about the point `pivot_m` (world): position
    /// $p' = c + R_\Delta (p - c)$, orientation $q' = q_\Delta q$.
    pub fn rotated_about(&self, pivot_m: [f64; 3], rotation: &UnitQuaternion<f64>) -> Self {
        let d = Vector3::new(self.position_m[0] - pivot_m[0], self.position_m[1] - pivot_m[1], self.position_m[2] - pivot_m[2]);
        let r = rotation * d;
        Self { position_m: [pivot_m[0] + r.x, pivot_m[1] + r.y, pivot_m[2] + r.z], orientation: rotation * self.orientation }
    }

    /// The pose turned by `angle_rad` about the world axis `axis` (normalised) through
    /// `pivot_m` ([`BasePose3::rotated_about`]).
    pub fn rotated_about_axis(&self, pivot_m: [f64; 3], axis: [f64; 3], angle_rad: f64) -> Self {
        self.rotated_about(pivot_m, &UnitQuaternion::from_axis_angle(&unit_axis(axis), angle_rad))
    }

    /// Checks that every component is finite and the quaternion is unit (it may have been built
    /// unchecked from raw parts).
    pub fn check(&self) -> Result<(), PoseError> {
        if !self.position_m.iter().all(|v| v.is_finite()) {
            return Err(PoseError::NonFinite { what: "position" });
        }
        let q = self.orientation.quaternion();
        if !q.coords.iter().all(|v| v.is_finite()) {
            return Err(PoseError::NonFinite { what: "orientation" });
        }
        let norm = q.norm();
        if (norm - 1.0).abs() > UNIT_QUATERNION_TOL {
            return Err(PoseError::NotUnit { norm });
        }
        Ok(())
    }

    /// The needle frame, rows $[t, n, b]$ (module docs).
    pub fn frame(&self) -> [[f64; 3]; 3] {
        let r = self.orientation.to_rotation_matrix();
        let m = r.matrix();
        let col = |j: usize, s: f64| [s * m[(0, j)], s * m[(1, j)], s * m[(2, j)]];
        [col(0, 1.0), col(1, 1.0), col(2, 1.0)]
    }

    /// The needle axis $t$.
    pub fn axis(&self) -> [f64; 3] {
        self.frame()[0]
    }

    /// The shaft point at arc length `s_m` from the base, $x_b + s\,t$.
    pub fn point_at(&self, s_m: f64) -> [f64; 3] {
        let t = self.axis();
        [self.position_m[0] + s_m * t[0], self.position_m[1] + s_m * t[1], self.position_m[2] + s_m * t[2]]
    }

    /// The arc length of the projection of `p_m` onto the shaft line, $t\cdot(p - x_b)$.
    pub fn arc_length_of(&self, p_m: [f64; 3]) -> f64 {
        let b = self.position_m;
        dot(self.axis(), [p_m[0] - b[0], p_m[1] - b[1], p_m[2] - b[2]])
    }

    /// This pose moved towards `target` by at most `max_step_m` of translation and
    /// `max_step_rad` of rotation (each clamped on its own: the translation along the straight
    /// line, the rotation along the shortest arc, $q' = \exp(\theta_{max}\,\hat a/2)\,q$ for a
    /// relative rotation $q_\Delta = q_{target} q^{-1}$ of angle $\theta > \theta_{max}$ about
    /// $\hat a$). Returns the pose and whether anything was clamped.
    pub fn clamped_towards(&self, target: &BasePose3, max_step_m: f64, max_step_rad: f64) -> (BasePose3, bool) {
        let mut clamped = false;
        let p = self.position_m;
        let d = [target.position_m[0] - p[0], target.position_m[1] - p[1], target.position_m[2] - p[2]];
        let dist = dot(d, d).sqrt();
        let position_m = if dist > max_step_m {
            clamped = true;
            let k = max_step_m / dist;
            [p[0] + k * d[0], p[1] + k * d[1], p[2] + k * d[2]]
        } else {
            target.position_m
        };
        let rel = target.orientation * self.orientation.inverse();
        let orientation = match rel.axis_angle() {
            Some((axis, angle)) if angle > max_step_rad => {
                clamped = true;
                UnitQuaternion::from_axis_angle(&axis, max_step_rad) * self.orientation
            }
            _ => target.orientation,
        };
        (BasePose3 { position_m, orientation }, clamped)
    }
}

/// A unit axis for [`UnitQuaternion::from_axis_angle`] from three components (normalised).
pub fn unit_axis(v: [f64; 3]) -> Unit<Vector3<f64>> {
    Unit::new_normalize(Vector3::new(v[0], v[1], v[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_a_right_handed_rotation_with_t_along_x_at_identity() {
        assert_eq!(BasePose3::default().frame(), [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let d = BasePose3::straight_down([0.0; 3]).frame();
        let want = [[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
        for i in 0..3 {
            for j in 0..3 {
                assert!((d[i][j] - want[i][j]).abs() < 1e-15, "{d:?}");
            }
        }
        let q = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
        let f = BasePose3::from_rotation([0.0; 3], q).frame();
        let c = [f[0][1] * f[1][2] - f[0][2] * f[1][1], f[0][2] * f[1][0] - f[0][0] * f[1][2], f[0][0] * f[1][1] - f[0][1] * f[1][0]];
        for k in 0..3 {
            assert!((c[k] - f[2][k]).abs() < 1e-15);
        }
        let l = BasePose3::looking_along([0.0; 3], [0.3, 0.1, -1.0]);
        let t = l.axis();
        let n = (0.09f64 + 0.01 + 1.0).sqrt();
        assert!((t[0] - 0.3 / n).abs() < 1e-15 && (t[2] + 1.0 / n).abs() < 1e-15);
    }

    #[test]
    fn bad_poses_are_named_and_steps_are_clamped() {
        assert_eq!(BasePose3::new([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]), Err(PoseError::NonFinite { what: "position" }));
        assert_eq!(BasePose3::new([0.0; 3], [1.0, f64::INFINITY, 0.0, 0.0]), Err(PoseError::NonFinite { what: "orientation" }));
        assert!(matches!(BasePose3::new([0.0; 3], [1.0, 0.1, 0.0, 0.0]), Err(PoseError::NotUnit { .. })));
        let a = BasePose3::default();
        let b = BasePose3::from_rotation([0.01, 0.0, 0.0], UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 0.5));
        let (c, clamped) = a.clamped_towards(&b, 1e-3, 0.01);
        assert!(clamped);
        assert!((c.position_m[0] - 1e-3).abs() < 1e-15);
        assert!((c.orientation.angle_to(&a.orientation) - 0.01).abs() < 1e-12);
        assert!((c.orientation.angle_to(&b.orientation) - 0.49).abs() < 1e-12);
        let (d, clamped) = a.clamped_towards(&b, 1.0, 1.0);
        assert!(!clamped && d == b);
    }
}
