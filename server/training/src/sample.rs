//! The tick sample the metrics read: one small fixed-size struct, built from a 2D
//! [`StepOutput`] or a 3D [`StepOutput3`] here and nowhere else (2D embedded in 3D as $z = 0$).
//!
//! Conventions: positions in world metres; `axis` is the unit direction of the needle at the tip
//! (base → tip); `axial_force_n` is the force the tissue resists the needle with along that axis,
//! **positive while pushing in** (the 3D output's sign; the 2D output's `force_axial_n` is
//! $t\cdot F$, negative while resisting, so it is negated).

use needlesim_core::sim::StepOutput;
use needlesim_core::sim3::StepOutput3;

/// Most targets a sample carries (core's bound on a simulation's targets, 2D and 3D).
pub const MAX_SAMPLE_TARGETS: usize = needlesim_core::sim::param_limits::MAX_TARGETS;

/// A target in a sample: its displaced centre and the tip's distance to it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SampleTarget {
    /// Displaced centre, world, m.
    pub centre_m: [f64; 3],
    /// $|x_{tip} - c|$, m.
    pub distance_m: f64,
}

/// What the training layer needs of one tick. `Copy`, no heap: a live session can build one per
/// tick on its fan-out thread and push it without allocating.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The tick's time, s (a trajectory's own clock offline, the session's clock live).
    pub t_s: f64,
    /// Tip position, world, m.
    pub tip_m: [f64; 3],
    /// Unit direction of the needle at the tip (base → tip).
    pub axis: [f64; 3],
    /// Inserted length as the simulation reports it: shaft from the most proximal contact to the
    /// tip, m (informative: with node capture it lags the tip's depth; the metrics measure depth
    /// from the entry point instead).
    pub inserted_m: f64,
    /// Contacts the needle holds (stuck, slipping, tip): the needle is in the tissue when > 0.
    pub contacts: u32,
    /// Axial force of the tissue on the needle, N, positive resisting insertion (module docs).
    pub axial_force_n: f64,
    /// Force of the tissue on the needle base, world, N.
    pub base_force_n: [f64; 3],
    n_targets: usize,
    targets: [SampleTarget; MAX_SAMPLE_TARGETS],
}

impl Sample {
    /// A sample with no targets (tests, synthetic streams).
    pub fn new(t_s: f64, tip_m: [f64; 3], axis: [f64; 3], inserted_m: f64, contacts: u32, axial_force_n: f64) -> Self {
        Self {
            t_s,
            tip_m,
            axis,
            inserted_m,
            contacts,
            axial_force_n,
            base_force_n: [0.0; 3],
            n_targets: 0,
            targets: [SampleTarget::default(); MAX_SAMPLE_TARGETS],
        }
    }

    /// Adds a target (its displaced centre; the distance from this sample's tip is computed).
    /// Past [`MAX_SAMPLE_TARGETS`] the target is ignored and `false` returned.
    pub fn push_target(&mut self, centre_m: [f64; 3]) -> bool {
        if self.n_targets == MAX_SAMPLE_TARGETS {
            return false;
        }
        self.targets[self.n_targets] = SampleTarget { centre_m, distance_m: dist3(self.tip_m, centre_m) };
        self.n_targets += 1;
        true
    }

    /// The targets, in the simulation's order.
    pub fn targets(&self) -> &[SampleTarget] {
        &self.targets[..self.n_targets]
    }

    /// From a 2D step output, at time `t_s` (module docs for the conventions).
    pub fn from_2d(out: &StepOutput, t_s: f64) -> Self {
        let a = out.tip_angle_rad;
        let mut s = Self::new(
            t_s,
            [out.tip_m[0], out.tip_m[1], 0.0],
            [a.cos(), a.sin(), 0.0],
            out.inserted_length_m,
            (out.n_stuck + out.n_slipping + out.n_tip) as u32,
            -out.force_axial_n,
        );
        s.base_force_n = [out.force_n[0], out.force_n[1], 0.0];
        for t in out.targets.iter().take(MAX_SAMPLE_TARGETS) {
            s.targets[s.n_targets] = SampleTarget { centre_m: [t.position_m[0], t.position_m[1], 0.0], distance_m: t.distance_m };
            s.n_targets += 1;
        }
        s
    }

    /// From a 3D step output, at time `t_s`: the axis is the base orientation's $R e_x$ (the
    /// rigid 3D needle).
    pub fn from_3d(out: &StepOutput3, t_s: f64) -> Self {
        let q = out.pose.orientation.quaternion();
        let (w, x, y, z) = (q.w, q.i, q.j, q.k);
        let axis = [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)];
        let mut s = Self::new(t_s, out.tip_m, axis, out.inserted_length_m, out.contacts.len() as u32, out.axial_force_n);
        s.base_force_n = out.base_force_n;
        for t in out.targets.as_slice().iter().take(MAX_SAMPLE_TARGETS) {
            s.targets[s.n_targets] = SampleTarget { centre_m: t.centre_m, distance_m: t.distance_m };
            s.n_targets += 1;
        }
        s
    }
}

/// Euclidean distance.
pub fn dist3(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
