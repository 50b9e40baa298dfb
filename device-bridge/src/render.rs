//! The safety layer between the server's force and the device: pure (no clock, no I/O), one call per device period.
//!
//! Poses are 6-DOF ([`Pose6`]: position, m, and unit quaternion, world frame), wrenches
//! `w = (F, τ)` (N, N·m, world frame, on and about the base point), pose differences
//! `δ(a, b) = (p_a − p_b, log(R_a R_bᵀ))` (m, rad: a translation and a world rotation vector) and
//! the stiffness `K = ∂w/∂δ` (6 × 6): the conventions of `needlesim_channel::spatial`. A 2D
//! session or device is the same path restricted to the plane (x, y and the rotation about z; its
//! stiffness has zeros elsewhere), not a second one. Each period [`Renderer::update`] takes the
//! device pose `q_d` and the latest server sample — wrench `w_s`, stiffness `K` and the base pose
//! `q_s` it was computed at — and does, in order, on the device's *rendered axes* `A`
//! ([`DeviceOutput`]: all six for a device that renders force and torque; the three translations
//! for a force-only, "3-DOF", device):
//!
//! 1. **Local linear model** (between server updates): `w_m = w_s + K_AA δ_A(q_d, q_s)`, with
//!    `K_AA` the block of `K` on the rendered axes: the full 6 × 6 for a wrench device, the 3 × 3
//!    force–position block (N/m) for a force-only device, whose model force is
//!    `F_m = F_s + K_Fp (p_d − p_s)` and whose torque is 0. (A force-only device cannot render the
//!    torque, and a force that changes with the orientation of its unactuated gimbal is not the
//!    gradient of a potential on the rendered axes, so it could feed energy in; the orientation's
//!    effect on the force reaches the device through the server's next samples instead.)
//! 2. **Virtual coupling** (passivity): the device is joined to a virtual tool by a spring `K_c =
//!    diag(k_c)` and a damper `B_c = diag(b_c)` per axis; the tool sits at the offset `x` (a
//!    perturbation from the device pose) where the local model balances the spring,
//!    `w_m + K_AA x − K_c x = 0`, i.e. `x = (K_c − K_AA)⁻¹ w_m`, and the device feels the coupling
//!    `w_c = K_c x + B_c (x − x_prev)/Δt` — the spring plus a damper on the motion of the device
//!    relative to the tool (`(q̇_d − q̇_t) = −ẋ`, backward difference over one period). The spring
//!    in series caps the rendered stiffness (`−K_eff = ((−K)⁻¹ + K_c⁻¹)⁻¹`, never stiffer than
//!    `K_c` per axis), so choosing `k_c` below the device's passivity limit (`k < 2 b_device / Δt`
//!    for a device with physical damping `b_device`, Colgate & Schenkel 1997) keeps the rendering
//!    passive however stiff the tissue is; the damper only acts on motion relative to the tool, so
//!    free motion is not damped. `k_c = 0` on every axis disables the coupling (`w_c = w_m`). If
//!    `K_c − K_AA` is singular (a negative tissue stiffness as large as the coupling) the model
//!    falls back to `w_s`.
//! 3. **Watchdog**: a sample is fresh when the server wrote it since the previous period (and its
//!    state is OK). After `watchdog_periods` periods without a fresh sample the gain `g` decreases by
//!    `1/n_r` per period, `n_r = round(ramp_s / Δt)` (at least 1), (linear ramp from its current value to 0, reached at the latest
//!    `watchdog_periods·Δt + ramp_s` after the last fresh sample) and stays 0; once fresh data
//!    returns it rises again by `1/n_r` per period (no step back to full force). `w_g = g·w_c`.
//!    Before the first sample the output is zero.
//! 4. **Limits**: the force is scaled to `|F| ≤ F_max` keeping its direction, the torque likewise to
//!    `|τ| ≤ τ_max` (Euclidean norms; in the plane, `|τ| = |τ_z|`); a non-finite value gives zero;
//!    off the rendered axes the output is 0.

use needlesim_channel::shm::ServerForce;
use needlesim_channel::spatial;

/// A 6-DOF pose: the base point (m, world) and the orientation (unit quaternion `(w, x, y, z)`, body → world).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose6 {
    pub position_m: [f64; 3],
    pub orientation: [f64; 4],
}

impl Default for Pose6 {
    fn default() -> Self {
        Self { position_m: [0.0; 3], orientation: spatial::IDENTITY }
    }
}

impl Pose6 {
    /// The 2D pose `(x, y, θ)`: `(x, y, 0)` and a rotation θ about +z.
    pub fn planar(q: [f64; 3]) -> Self {
        let (position_m, orientation) = spatial::pose_from_planar(q);
        Self { position_m, orientation }
    }

    /// `(x, y, θ)`: x, y and the twist about z.
    pub fn to_planar(&self) -> [f64; 3] {
        spatial::pose_to_planar(self.position_m, self.orientation)
    }

    /// `δ(self, base)`: the perturbation taking `base` to `self`.
    pub fn delta_from(&self, base: &Pose6) -> [f64; 6] {
        spatial::pose_delta(self.position_m, self.orientation, base.position_m, base.orientation)
    }
}

/// What the device renders: the axes the local model, the coupling and the limits work on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DeviceOutput {
    /// Force and torque (all six axes; a 2D device renders the planar ones, the others are 0 in a 2D session).
    #[default]
    Wrench,
    /// Force only (a 3-DOF device such as a Geomagic Touch): the three translations, torque 0.
    ForceOnly,
}

impl DeviceOutput {
    /// The number of rendered axes: the first `n` of (x, y, z, θx, θy, θz).
    pub fn axes(self) -> usize {
        match self {
            DeviceOutput::Wrench => 6,
            DeviceOutput::ForceOnly => 3,
        }
    }
}

/// Parameters of the safety layer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderParams {
    /// The device period Δt (s).
    pub period_s: f64,
    /// Limit on |F| (N).
    pub max_force_n: f64,
    /// Limit on |τ| (N·m).
    pub max_torque_nm: f64,
    /// Periods without a fresh server sample before the ramp to zero starts.
    pub watchdog_periods: u64,
    /// Duration of the ramp from full force to zero (and back) (s); 0 = a step.
    pub ramp_s: f64,
    /// Coupling stiffness per axis (x, y, z, θx, θy, θz): N/m ×3, N·m/rad ×3; 0 on all disables the coupling.
    pub coupling_k: [f64; 6],
    /// Coupling damping per axis: N·s/m ×3, N·m·s/rad ×3.
    pub coupling_b: [f64; 6],
    /// What the device renders.
    pub output: DeviceOutput,
}

impl RenderParams {
    /// Per-axis gains from a translational and a rotational value: `[t, t, t, r, r, r]`.
    pub fn per_axis(translational: f64, rotational: f64) -> [f64; 6] {
        [translational, translational, translational, rotational, rotational, rotational]
    }
}

impl Default for RenderParams {
    fn default() -> Self {
        Self {
            period_s: 1e-3,
            max_force_n: 5.0,
            max_torque_nm: 0.05,
            watchdog_periods: 10,
            ramp_s: 0.05,
            coupling_k: Self::per_axis(2000.0, 2.0),
            coupling_b: Self::per_axis(2.0, 0.002),
            output: DeviceOutput::Wrench,
        }
    }
}

/// What the server last sent, as the renderer needs it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ServerSample {
    /// `(Fx, Fy, Fz, τx, τy, τz)` (N, N·m).
    pub wrench: [f64; 6],
    /// `K = ∂w/∂δ`, `stiffness[row][col]` (module docs).
    pub stiffness: [[f64; 6]; 6],
    /// The pose the wrench was computed at.
    pub base: Pose6,
}

impl ServerSample {
    /// A 2D sample: wrench `(Fx, Fy, τ)`, stiffness `∂(Fx, Fy, τ)/∂(x, y, θ)` (3 × 3 row-major), base `(x, y, θ)`.
    pub fn planar(wrench: [f64; 3], stiffness: &[f64; 9], base: [f64; 3]) -> Self {
        Self {
            wrench: spatial::wrench_from_planar(wrench),
            stiffness: spatial::embed_planar_stiffness(stiffness),
            base: Pose6::planar(base),
        }
    }
}

impl From<&ServerForce> for ServerSample {
    fn from(f: &ServerForce) -> Self {
        Self { wrench: f.wrench(), stiffness: f.stiffness, base: Pose6 { position_m: f.base_position_m, orientation: f.base_orientation } }
    }
}

/// One period's result, with its intermediate values (for traces and tests).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderOutput {
    /// What to send to the device: `(Fx, Fy, Fz, τx, τy, τz)`.
    pub wrench: [f64; 6],
    /// The local model `w_m` (before coupling, gain and limits).
    pub model: [f64; 6],
    /// The watchdog gain `g` in [0, 1].
    pub gain: f64,
    /// Periods since the last fresh sample.
    pub periods_since_fresh: u64,
    /// True if a limit changed the wrench.
    pub limited: bool,
}

/// The renderer's state: the last server sample, the watchdog and the coupling's previous period.
#[derive(Debug, Clone)]
pub struct Renderer {
    params: RenderParams,
    last: Option<ServerSample>,
    periods_since_fresh: u64,
    /// The gain in steps of 1/`ramp_periods` (integers, so 0 and 1 are exact).
    gain_steps: u64,
    ramp_periods: u64,
    /// The previous period's tool offset `x`, for the coupling damper.
    prev: Option<[f64; 6]>,
}

impl Renderer {
    pub fn new(params: RenderParams) -> Self {
        let ramp_periods = if params.ramp_s > 0.0 { (params.ramp_s / params.period_s).round().max(1.0) as u64 } else { 1 };
        Self { params, last: None, periods_since_fresh: 0, gain_steps: 0, ramp_periods, prev: None }
    }

    pub fn params(&self) -> &RenderParams {
        &self.params
    }

    /// `n` device periods passed without an update (the loop woke up late and skipped them): the
    /// watchdog counts them as periods without a fresh sample, and the coupling damper restarts
    /// (its backward difference would span them).
    pub fn missed(&mut self, n: u64) {
        for _ in 0..n.min(self.params.watchdog_periods + self.ramp_periods + 1) {
            self.periods_since_fresh = self.periods_since_fresh.saturating_add(1);
            if self.periods_since_fresh > self.params.watchdog_periods {
                self.gain_steps = self.gain_steps.saturating_sub(1);
            }
        }
        self.periods_since_fresh =
            self.periods_since_fresh.saturating_add(n.saturating_sub(self.params.watchdog_periods + self.ramp_periods + 1));
        self.prev = None;
    }

    /// One device period. `fresh` is `Some` when the server wrote a new (valid) sample since the
    /// previous period, `None` otherwise (the last one is kept).
    pub fn update(&mut self, q_d: &Pose6, fresh: Option<&ServerSample>) -> RenderOutput {
        let p = self.params;
        match fresh {
            Some(s) => {
                self.last = Some(*s);
                self.periods_since_fresh = 0;
                self.gain_steps = (self.gain_steps + 1).min(self.ramp_periods);
            }
            None => {
                self.periods_since_fresh = self.periods_since_fresh.saturating_add(1);
                if self.periods_since_fresh > p.watchdog_periods {
                    self.gain_steps = self.gain_steps.saturating_sub(1);
                }
            }
        }
        let Some(s) = self.last else {
            return RenderOutput { periods_since_fresh: self.periods_since_fresh, ..Default::default() };
        };
        let n = p.output.axes();
        let model = local_model(&s, q_d, p.output);
        let coupled = if p.coupling_k[..n].iter().all(|&k| k == 0.0) {
            self.prev = None;
            model
        } else {
            match coupling_tool_offset(&s, &model, p.coupling_k, p.output) {
                Some(x) => {
                    let mut w = [0.0; 6];
                    for i in 0..n {
                        w[i] = p.coupling_k[i] * x[i];
                        if let Some(xp) = self.prev {
                            w[i] += p.coupling_b[i] * (x[i] - xp[i]) / p.period_s;
                        }
                    }
                    self.prev = Some(x);
                    w
                }
                None => {
                    self.prev = None;
                    restrict(s.wrench, n)
                }
            }
        };
        let gain = self.gain_steps as f64 / self.ramp_periods as f64;
        let scaled = coupled.map(|v| v * gain);
        let (wrench, limited) = limit(scaled, p.max_force_n, p.max_torque_nm);
        RenderOutput { wrench, model, gain, periods_since_fresh: self.periods_since_fresh, limited }
    }
}

/// `w` with the components from `n` on set to 0.
fn restrict(w: [f64; 6], n: usize) -> [f64; 6] {
    std::array::from_fn(|i| if i < n { w[i] } else { 0.0 })
}

/// `w_s + K_AA δ_A(q_d, q_s)` on the rendered axes, 0 elsewhere (module docs, step 1).
pub fn local_model(s: &ServerSample, q_d: &Pose6, output: DeviceOutput) -> [f64; 6] {
    let n = output.axes();
    let d = q_d.delta_from(&s.base);
    std::array::from_fn(|i| if i < n { s.wrench[i] + (0..n).map(|j| s.stiffness[i][j] * d[j]).sum::<f64>() } else { 0.0 })
}

/// The virtual tool's offset from the device `x = (K_c − K_AA)⁻¹ w_m` on the rendered axes (0
/// elsewhere); `None` if `K_c − K_AA` is (nearly) singular.
pub fn coupling_tool_offset(s: &ServerSample, w_m: &[f64; 6], k_c: [f64; 6], output: DeviceOutput) -> Option<[f64; 6]> {
    let n = output.axes();
    let a: [[f64; 6]; 6] = std::array::from_fn(|r| std::array::from_fn(|c| if r == c { k_c[r] } else { 0.0 } - s.stiffness[r][c]));
    solve(&a, w_m, n)
}

/// Solves `A x = b` on the leading `n × n` block (`n ≤ 6`; `x` is 0 beyond `n`) by Gaussian
/// elimination with partial pivoting; `None` if `|det A|` is below 1e-12 of the product of the
/// row norms (Hadamard's bound: the rows are nearly dependent), or anything is non-finite.
pub fn solve(a: &[[f64; 6]; 6], b: &[f64; 6], n: usize) -> Option<[f64; 6]> {
    let n = n.min(6);
    let mut m = *a;
    let mut x = *b;
    let scale: f64 = (0..n).map(|r| m[r][..n].iter().map(|v| v * v).sum::<f64>().sqrt()).product();
    let mut det = 1.0f64;
    for col in 0..n {
        let piv = (col..n).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        if piv != col {
            m.swap(piv, col);
            x.swap(piv, col);
        }
        let d = m[col][col];
        det *= d;
        if d == 0.0 {
            return None;
        }
        let pivot_row = m[col];
        for r in col + 1..n {
            let f = m[r][col] / d;
            for (v, p) in m[r][col..n].iter_mut().zip(&pivot_row[col..n]) {
                *v -= f * p;
            }
            x[r] -= f * x[col];
        }
    }
    if !det.is_finite() || det.abs() <= 1e-12 * scale || scale == 0.0 {
        return None;
    }
    for r in (0..n).rev() {
        let mut v = x[r];
        for c in r + 1..n {
            v -= m[r][c] * x[c];
        }
        x[r] = v / m[r][r];
    }
    for v in x.iter_mut().skip(n) {
        *v = 0.0;
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Scales the force to `|F| ≤ max_force` and the torque to `|τ| ≤ max_torque` (same directions);
/// non-finite → 0. Returns the wrench and whether it changed.
pub fn limit(w: [f64; 6], max_force: f64, max_torque: f64) -> ([f64; 6], bool) {
    if !w.iter().all(|v| v.is_finite()) {
        return ([0.0; 6], true);
    }
    let mut out = w;
    let mut limited = false;
    for (range, max) in [(0..3, max_force), (3..6, max_torque)] {
        let norm = w[range.clone()].iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > max {
            let s = max.max(0.0) / norm;
            for v in &mut out[range] {
                *v *= s;
            }
            limited = true;
        }
    }
    (out, limited)
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_channel::spatial::{pose_apply, quat_normalize, wrench_to_planar};

    fn no_coupling() -> RenderParams {
        RenderParams { coupling_k: [0.0; 6], coupling_b: [0.0; 6], ramp_s: 0.0, ..Default::default() }
    }

    fn close<const N: usize>(a: [f64; N], b: [f64; N], tol: f64) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
    }

    /// The 2D path: a planar pose in, the planar wrench out.
    fn update2(r: &mut Renderer, q: [f64; 3], s: Option<&ServerSample>) -> [f64; 3] {
        let out = r.update(&Pose6::planar(q), s);
        assert_eq!([out.wrench[2], out.wrench[3], out.wrench[4]], [0.0; 3], "off-plane output in a 2D session: {out:?}");
        wrench_to_planar(out.wrench)
    }

    /// Seeded uniform samples in [-1, 1).
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        use rand::{Rng, SeedableRng};
        let mut g = rand::rngs::SmallRng::seed_from_u64(seed);
        move || g.random_range(-1.0..1.0)
    }

    #[test]
    fn limits_clamp_magnitude_and_keep_direction() {
        let (w, lim) = limit([3.0, 4.0, 0.0, 0.0, 0.0, 0.01], 2.5, 0.05);
        assert!(lim);
        assert!(close(w, [1.5, 2.0, 0.0, 0.0, 0.0, 0.01], 1e-15));
        let (w, lim) = limit([0.3, -0.4, 0.0, 0.0, 0.0, -0.2], 5.0, 0.05);
        assert!(lim);
        assert_eq!(w, [0.3, -0.4, 0.0, 0.0, 0.0, -0.05]);
        assert_eq!(limit([1.0, 1.0, 0.0, 0.0, 0.0, 0.0], 5.0, 0.05), ([1.0, 1.0, 0.0, 0.0, 0.0, 0.0], false));
        assert_eq!(limit([f64::NAN, 1.0, 0.0, 0.0, 0.0, 0.0], 5.0, 0.05), ([0.0; 6], true));
        assert_eq!(limit([f64::INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0], 5.0, 0.05).0, [0.0; 6]);
        // 3D: |F| and |τ| are Euclidean norms, directions kept.
        let (w, lim) = limit([2.0, -4.0, 4.0, 0.03, 0.0, -0.04], 3.0, 0.025);
        assert!(lim);
        assert!(close(w, [1.0, -2.0, 2.0, 0.015, 0.0, -0.02], 1e-15), "{w:?}");
    }

    #[test]
    fn local_model_is_exact_for_a_linear_environment_in_2d() {
        // Environment w(q) = w0 + K q; the server evaluated it at base q_s.
        let k = [-200.0, 10.0, 0.5, 5.0, -300.0, -1.0, 0.1, 0.2, -0.05];
        let w0 = [0.1, -0.2, 0.001];
        let env = |q: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| w0[i] + (0..3).map(|j| k[3 * i + j] * q[j]).sum::<f64>()) };
        let q_s = [0.001, -0.002, 0.01];
        let s = ServerSample::planar(env(q_s), &k, q_s);
        let q_d = [0.0015, -0.0025, 0.012];
        assert!(close(wrench_to_planar(local_model(&s, &Pose6::planar(q_d), DeviceOutput::Wrench)), env(q_d), 1e-12));
        let mut r = Renderer::new(RenderParams { max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() });
        assert_eq!(update2(&mut r, q_d, None), [0.0; 3], "nothing before the first sample");
        let out = update2(&mut r, q_d, Some(&s));
        assert!(close(out, env(q_d), 1e-12), "{out:?}");
        // Between updates the model follows the device.
        let q2 = [0.002, -0.001, 0.0];
        assert!(close(update2(&mut r, q2, None), env(q2), 1e-12));
    }

    /// A known 6×6 and a known pose offset (translation and a rotation about a skew axis, applied
    /// as `R ← exp(δθ̂)R` to a tilted base): the model is `w_s + K δ`, every component.
    #[test]
    fn local_model_renders_the_6x6_for_a_6dof_offset() {
        let mut rnd = rng(3);
        let k: [[f64; 6]; 6] = std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                rnd()
                    * if r < 3 {
                        if c < 3 { 500.0 } else { 2.0 }
                    } else if c < 3 {
                        2.0
                    } else {
                        0.05
                    }
            })
        });
        let base = Pose6 { position_m: [0.01, 0.02, -0.05], orientation: quat_normalize([0.8, 0.2, -0.4, 0.1]).unwrap() };
        let w_s = [0.3, -0.1, 0.7, 0.002, -0.001, 0.003];
        let s = ServerSample { wrench: w_s, stiffness: k, base };
        let d = [0.001, -0.002, 0.0015, 0.01, -0.02, 0.015];
        let (p, q) = pose_apply(base.position_m, base.orientation, d);
        let q_d = Pose6 { position_m: p, orientation: q };
        let expect: [f64; 6] = std::array::from_fn(|i| w_s[i] + (0..6).map(|j| k[i][j] * d[j]).sum::<f64>());
        let got = local_model(&s, &q_d, DeviceOutput::Wrench);
        assert!(close(got, expect, 1e-12), "{got:?} vs {expect:?}");
        // Rendered as is without coupling (limits out of the way).
        let mut r = Renderer::new(RenderParams { max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() });
        assert!(close(r.update(&q_d, Some(&s)).wrench, expect, 1e-12));
        // A force-only device: the force–position block alone, no torque.
        let got = local_model(&s, &q_d, DeviceOutput::ForceOnly);
        let expect_f: [f64; 6] = std::array::from_fn(|i| if i < 3 { w_s[i] + (0..3).map(|j| k[i][j] * d[j]).sum::<f64>() } else { 0.0 });
        assert!(close(got, expect_f, 1e-12), "{got:?} vs {expect_f:?}");
        let mut r = Renderer::new(RenderParams { max_force_n: 1e9, max_torque_nm: 1e9, output: DeviceOutput::ForceOnly, ..no_coupling() });
        assert!(close(r.update(&q_d, Some(&s)).wrench, expect_f, 1e-12));
    }

    #[test]
    fn watchdog_ramps_to_zero_then_holds_and_ramps_back() {
        let p = RenderParams { watchdog_periods: 5, ramp_s: 0.010, max_force_n: 100.0, ..no_coupling() };
        let mut r = Renderer::new(p);
        // A 3D wrench: every component ramps together.
        let w = [1.0, -0.5, 0.25, 0.01, -0.02, 0.005];
        let s = ServerSample { wrench: w, ..Default::default() };
        let q = Pose6::default();
        // Ramp in from 0 over 10 periods.
        for k in 1..=12 {
            let out = r.update(&q, Some(&s));
            let g = (k as f64 / 10.0).min(1.0);
            assert!(close(out.wrench, w.map(|v| v * g), 1e-12), "ramp-in period {k}: {out:?}");
        }
        // The server stops: 5 periods at full force, then −0.1 per period, zero after 15, held.
        let mut seen = vec![];
        for _ in 0..40 {
            seen.push(r.update(&q, None).wrench);
        }
        for (k, f) in seen.iter().enumerate() {
            let n = k as f64 + 1.0; // periods since fresh
            let expect = if n <= 5.0 { 1.0 } else { (1.0 - (n - 5.0) * 0.1).max(0.0) };
            assert!(close(*f, w.map(|v| v * expect), 1e-9), "period {n}: {f:?} vs gain {expect}");
        }
        assert_eq!(seen[14..], vec![[0.0; 6]; 26][..]);
        // Fresh data: back up gradually, not a step.
        let out = r.update(&q, Some(&s));
        assert!((out.wrench[0] - 0.1).abs() < 1e-12 && out.periods_since_fresh == 0);
        // Skipped periods count as periods without data: 4 fresh → gain 0.5, then 5 + 3 missed → 0.2.
        for _ in 0..4 {
            r.update(&q, Some(&s));
        }
        r.missed(8);
        let out = r.update(&q, None);
        assert!((out.wrench[0] - 0.1).abs() < 1e-12 && out.periods_since_fresh == 9, "{out:?}");
        r.missed(1_000_000);
        assert_eq!(r.update(&q, None).periods_since_fresh, 1_000_010);
    }

    #[test]
    fn coupling_is_the_series_spring_and_damps_relative_motion() {
        let kc = [1000.0, 1000.0, 1.0];
        let k6 = [kc[0], kc[1], 1000.0, 1.0, 1.0, kc[2]];
        let p = RenderParams { coupling_k: k6, coupling_b: [0.0; 6], max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() };
        let mut r = Renderer::new(p);
        // Diagonal tissue stiffness k_t: the series stiffness is k_t k_c / (k_t + k_c).
        let kt = [3000.0, 1000.0, 0.5];
        let s = ServerSample::planar([0.0; 3], &[-kt[0], 0.0, 0.0, 0.0, -kt[1], 0.0, 0.0, 0.0, -kt[2]], [0.0; 3]);
        let q = [0.001, -0.002, 0.1];
        let out = update2(&mut r, q, Some(&s));
        let expect: [f64; 3] = std::array::from_fn(|i| -kt[i] * kc[i] / (kt[i] + kc[i]) * q[i]);
        assert!(close(out, expect, 1e-12), "{out:?} vs {expect:?}");
        // Never stiffer than the coupling, however stiff the tissue.
        let stiff = ServerSample::planar([0.0; 3], &[-1e9, 0.0, 0.0, 0.0, -1e9, 0.0, 0.0, 0.0, -1e9], [0.0; 3]);
        let out = update2(&mut r, q, Some(&stiff));
        assert!(close(out, [-1.0, 2.0, -0.1], 1e-5), "{out:?}");
        // A free tool (K = 0): the tool follows the device, no force, no damping on free motion.
        let p = RenderParams { coupling_b: RenderParams::per_axis(5.0, 0.01), ..p };
        let mut r = Renderer::new(p);
        let free = ServerSample::planar([0.5, 0.0, 0.0], &[0.0; 9], [0.0; 3]);
        update2(&mut r, [0.0; 3], Some(&free));
        let out = update2(&mut r, [0.01, 0.0, 0.0], Some(&free));
        assert!(close(out, [0.5, 0.0, 0.0], 1e-12), "{out:?}");
        // Against a very stiff wall the tool stays: the damper acts on the device's velocity.
        let mut r = Renderer::new(p);
        update2(&mut r, [0.0; 3], Some(&stiff));
        let out = update2(&mut r, [1e-4, 0.0, 0.0], Some(&stiff));
        // spring ≈ −k_c·1e-4 = −0.1, damper ≈ −b_c·(1e-4/1e-3) = −0.5
        assert!((out[0] - (-0.6)).abs() < 1e-4, "{out:?}");
    }

    /// In 3D, a diagonal 6×6 tissue stiffness behind the coupling gives the series stiffness on each
    /// of the six axes (a small offset of the device from the base, translation and rotation).
    #[test]
    fn coupling_in_3d_is_the_series_spring_per_axis() {
        let kc = [1000.0, 800.0, 1200.0, 1.0, 0.8, 1.5];
        let kt = [3000.0, 400.0, 1200.0, 0.5, 2.0, 1.5];
        let p = RenderParams { coupling_k: kc, coupling_b: [0.0; 6], max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() };
        let mut r = Renderer::new(p);
        let base = Pose6 { position_m: [0.0, 0.0, 0.1], orientation: quat_normalize([0.9, 0.1, 0.3, -0.2]).unwrap() };
        let s = ServerSample {
            wrench: [0.0; 6],
            stiffness: std::array::from_fn(|i| std::array::from_fn(|j| if i == j { -kt[i] } else { 0.0 })),
            base,
        };
        let d = [0.001, -0.002, 0.0005, 0.01, -0.005, 0.02];
        let (pp, qq) = pose_apply(base.position_m, base.orientation, d);
        let out = r.update(&Pose6 { position_m: pp, orientation: qq }, Some(&s));
        let expect: [f64; 6] = std::array::from_fn(|i| -kt[i] * kc[i] / (kt[i] + kc[i]) * d[i]);
        assert!(close(out.wrench, expect, 1e-12), "{out:?} vs {expect:?}");
        // Force-only: the translations alone, no torque, same series stiffness.
        let mut r = Renderer::new(RenderParams { output: DeviceOutput::ForceOnly, ..p });
        let out = r.update(&Pose6 { position_m: pp, orientation: qq }, Some(&s));
        assert!(close(out.wrench, [expect[0], expect[1], expect[2], 0.0, 0.0, 0.0], 1e-12), "{out:?}");
    }

    #[test]
    fn singular_coupling_falls_back_to_the_server_wrench() {
        let p = RenderParams { coupling_k: RenderParams::per_axis(1000.0, 1.0), max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() };
        let mut r = Renderer::new(p);
        let s = ServerSample::planar([0.3, 0.2, 0.01], &[1000.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], [0.0; 3]);
        assert_eq!(update2(&mut r, [0.1, 0.1, 0.1], Some(&s)), [0.3, 0.2, 0.01]);
        let m = |rows: [[f64; 3]; 3]| -> [[f64; 6]; 6] {
            std::array::from_fn(|r| std::array::from_fn(|c| if r < 3 && c < 3 { rows[r][c] } else { 0.0 }))
        };
        assert_eq!(solve(&m([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]), &[1.0; 6], 3), None);
        let x = solve(&m([[2.0, 0.0, 0.0], [0.0, 4.0, 1.0], [0.0, 1.0, 3.0]]), &[2.0, 5.0, 4.0, 9.0, 9.0, 9.0], 3).unwrap();
        assert!(close(x, [1.0, 1.0, 1.0, 0.0, 0.0, 0.0], 1e-14), "{x:?}");
        // A dense 6×6 against its known solution.
        let mut rnd = rng(11);
        let a: [[f64; 6]; 6] = std::array::from_fn(|r| std::array::from_fn(|c| rnd() + if r == c { 3.0 } else { 0.0 }));
        let x_true = [0.5, -1.0, 2.0, 0.25, -0.75, 1.5];
        let b: [f64; 6] = std::array::from_fn(|r| (0..6).map(|c| a[r][c] * x_true[c]).sum());
        assert!(close(solve(&a, &b, 6).unwrap(), x_true, 1e-12));
    }

    #[test]
    fn limits_apply_after_the_model() {
        let p = RenderParams { max_force_n: 1.0, max_torque_nm: 0.01, ..no_coupling() };
        let mut r = Renderer::new(p);
        let s = ServerSample::planar([0.0; 3], &[-1000.0, 0.0, 0.0, 0.0, -1000.0, 0.0, 0.0, 0.0, -1.0], [0.0; 3]);
        let out = r.update(&Pose6::planar([0.003, 0.004, 0.5]), Some(&s));
        assert!(out.limited);
        assert!(close(wrench_to_planar(out.wrench), [-0.6, -0.8, -0.01], 1e-12), "{out:?}");
        assert!(close(wrench_to_planar(out.model), [-3.0, -4.0, -0.5], 1e-12));
    }
}
