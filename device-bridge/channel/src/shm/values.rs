//! The values the channel carries: the session's [`Dimension`], the device's pose
//! ([`DevicePose`]) and the tissue's wrench ([`ServerForce`]), and what a read returns ([`Sample`]).

#[cfg(doc)]
use super::{Broken, DeviceEnd, monotonic_ns};

/// The dimension of the session behind a channel (header field): what the bridge drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// A 2D session: it reads the planar part of the pose (x, y and the twist about z; see
    /// [`crate::spatial`]) and answers with the planar wrench and stiffness embedded in the 6-DOF fields.
    Two = 2,
    /// A 3D session: the full 6-DOF pose and wrench.
    Three = 3,
}

impl Dimension {
    pub(super) fn from_u32(v: u32) -> Option<Self> {
        match v {
            2 => Some(Self::Two),
            3 => Some(Self::Three),
            _ => None,
        }
    }
}

/// The device's pose, written by the bridge once per device sample (frames and units: [`crate::spatial`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DevicePose {
    /// `CLOCK_MONOTONIC` of the writer when sampled, ns ([`monotonic_ns`]).
    pub t_ns: u64,
    /// The base point (the hand) in the world frame, m.
    pub position_m: [f64; 3],
    /// Unit quaternion `(w, x, y, z)`: the needle's body frame → world.
    pub orientation: [f64; 4],
    /// A bit per button, 1 = pressed.
    pub buttons: u32,
    /// Incremented by every write (stamped by [`DeviceEnd::write_pose_from_device`]; the caller's
    /// value is ignored): a counter that stops advancing means a dead bridge.
    pub counter: u64,
}

impl Default for DevicePose {
    /// At the origin, identity orientation, no button, time and counter 0.
    fn default() -> Self {
        Self { t_ns: 0, position_m: [0.0; 3], orientation: crate::spatial::IDENTITY, buttons: 0, counter: 0 }
    }
}

impl DevicePose {
    /// The 2D pose `(x_m, y_m, theta_rad)` embedded as `(x, y, 0)` and a rotation θ about +z.
    pub fn planar(t_ns: u64, q: [f64; 3], buttons: u32) -> Self {
        let (position_m, orientation) = crate::spatial::pose_from_planar(q);
        Self { t_ns, position_m, orientation, buttons, counter: 0 }
    }

    /// The 2D pose `(x_m, y_m, theta_rad)`: x, y and the twist about z ([`crate::spatial::pose_to_planar`]).
    pub fn to_planar(&self) -> [f64; 3] {
        crate::spatial::pose_to_planar(self.position_m, self.orientation)
    }
}

/// The wrench the tissue exerts, written by the session's real-time thread once per tick
/// (frames and units: [`crate::spatial`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServerForce {
    /// `CLOCK_MONOTONIC` of the writer, ns.
    pub t_ns: u64,
    /// The real-time loop's tick.
    pub tick: u64,
    /// Force on the base point, world frame, N.
    pub force_n: [f64; 3],
    /// Torque about the base point, world frame, N·m.
    pub torque_nm: [f64; 3],
    /// `K = ∂(F, τ)/∂δ` with `δ = (δp, δθ)` the perturbation of the base pose (translation, m, and
    /// a world rotation vector applied as `R ← exp(δθ̂)R`, rad): `stiffness[row][col]`, rows
    /// (Fx, Fy, Fz, τx, τy, τz), columns (δx, δy, δz, δθx, δθy, δθz); blocks in N/m, N/rad, N·m/m, N·m/rad.
    pub stiffness: [[f64; 6]; 6],
    /// The base pose the wrench was computed at: position (m, world) …
    pub base_position_m: [f64; 3],
    /// … and orientation (unit quaternion `(w, x, y, z)`).
    pub base_orientation: [f64; 4],
    /// [`ServerForce::STATE_OK`], [`ServerForce::STATE_DEVICE_STALE`] or [`ServerForce::STATE_CLOSING`].
    pub state: u32,
    /// The [`DevicePose::counter`] of the device pose this force was computed from; 0 when the
    /// tick used no device pose (a client's pose, or the needle held).
    pub pose_counter: u64,
}

impl Default for ServerForce {
    /// Zero wrench and stiffness at the origin (identity orientation), state OK, tick and counter 0.
    fn default() -> Self {
        Self {
            t_ns: 0,
            tick: 0,
            force_n: [0.0; 3],
            torque_nm: [0.0; 3],
            stiffness: [[0.0; 6]; 6],
            base_position_m: [0.0; 3],
            base_orientation: crate::spatial::IDENTITY,
            state: Self::STATE_OK,
            pose_counter: 0,
        }
    }
}

impl ServerForce {
    /// Sets the wrench, stiffness and base pose from their 2D forms: wrench `(Fx, Fy, τ)` (N, N,
    /// N·m), stiffness `∂(Fx, Fy, τ)/∂(x, y, θ)` (3×3 row-major) and base `(x, y, θ)` (the planar
    /// embedding of [`crate::spatial`]; every other component 0).
    pub fn set_planar(&mut self, wrench: [f64; 3], stiffness: &[f64; 9], base: [f64; 3]) {
        self.force_n = [wrench[0], wrench[1], 0.0];
        self.torque_nm = [0.0, 0.0, wrench[2]];
        self.stiffness = crate::spatial::embed_planar_stiffness(stiffness);
        (self.base_position_m, self.base_orientation) = crate::spatial::pose_from_planar(base);
    }

    /// The 2D forms: (wrench `(Fx, Fy, τz)`, stiffness 3×3 on (x, y, θz), base `(x, y, θ)`), the inverse of [`Self::set_planar`].
    pub fn to_planar(&self) -> ([f64; 3], [f64; 9], [f64; 3]) {
        (
            [self.force_n[0], self.force_n[1], self.torque_nm[2]],
            crate::spatial::restrict_planar_stiffness(&self.stiffness),
            crate::spatial::pose_to_planar(self.base_position_m, self.base_orientation),
        )
    }

    /// The wrench `(Fx, Fy, Fz, τx, τy, τz)`.
    pub fn wrench(&self) -> [f64; 6] {
        let (f, t) = (self.force_n, self.torque_nm);
        [f[0], f[1], f[2], t[0], t[1], t[2]]
    }
}

impl ServerForce {
    pub const STATE_OK: u32 = 0;
    /// The server has no fresh pose: it holds the needle where it was.
    pub const STATE_DEVICE_STALE: u32 = 1;
    /// The server is shutting the channel down.
    pub const STATE_CLOSING: u32 = 2;
}

/// What a read found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReadStatus {
    /// A value written since the previous accepted read, by a writer of this generation.
    Fresh,
    /// Nothing new (or only data of another generation); `value` is the last good one, if any.
    Unchanged,
    /// The writer was mid-write through every retry; `value` is the last good one.
    Contended,
    /// ([`DeviceEnd`] only) the server re-created or closed the channel: re-attach.
    Stale,
    /// The channel is broken ([`Broken`]): nothing was read; `value` is the last good one.
    Broken,
}

/// The result of a read: the last good value and whether it is new.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<T> {
    /// The last value accepted under this generation; `None` until the first.
    pub value: Option<T>,
    pub status: ReadStatus,
    /// Reads since the last fresh one (0 when this one is fresh; counts from create/attach before the first).
    pub reads_since_fresh: u64,
}

impl<T> Sample<T> {
    /// True if `value` was written since the previous read.
    pub fn fresh(&self) -> bool {
        self.status == ReadStatus::Fresh
    }
}
