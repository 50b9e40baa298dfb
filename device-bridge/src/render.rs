//! The safety layer between the server's force and the device: pure (no clock, no I/O), one call per device period.
//!
//! Poses are `q = (x, y, θ)` (m, m, rad), wrenches `w = (Fx, Fy, τ)` (N, N, N·m). Each period
//! [`Renderer::update`] takes the device pose `q_d` and the latest server sample — force `w_s`,
//! stiffness Jacobian `J = ∂w/∂q` (3 × 3) and the base pose `q_s` it was computed at — and does, in order:
//!
//! 1. **Local linear model** (between server updates): `w_m = w_s + J (q_d − q_s)`.
//! 2. **Virtual coupling** (passivity): the device is joined to a virtual tool by a spring `K_c =
//!    diag(k_c, k_c, k_cθ)` and a damper `B_c = diag(b_c, b_c, b_cθ)`; the tool sits where the local
//!    model balances the spring, `w_s + J (q_t − q_s) + K_c (q_d − q_t) = 0`, i.e.
//!    `q_t = q_d + (K_c − J)⁻¹ w_m`, and the device feels the coupling:
//!    `w_c = K_c (q_t − q_d) − B_c (Δ_d − Δ_t)/Δt = K_c (K_c − J)⁻¹ w_m − B_c (q̇_d − q̇_t)`,
//!    with `q̇` the backward difference over one period. The spring in series caps the rendered
//!    stiffness (`−J_eff = ((−J)⁻¹ + K_c⁻¹)⁻¹`, never stiffer than `K_c` per axis), so choosing `k_c`
//!    below the device's passivity limit (`k < 2 b_device / Δt` for a device with physical damping
//!    `b_device`, Colgate & Schenkel 1997) keeps the rendering passive however stiff the tissue is;
//!    the damper only acts on motion relative to the tool, so free motion is not damped.
//!    `k_c = 0` on an axis pair disables the coupling (`w_c = w_m`). If `K_c − J` is singular (a
//!    negative tissue stiffness as large as the coupling) the model falls back to `w_s`.
//! 3. **Watchdog**: a sample is fresh when the server wrote it since the previous period (and its
//!    state is OK). After `watchdog_periods` periods without a fresh sample the gain `g` decreases by
//!    `1/n_r` per period, `n_r = round(ramp_s / Δt)` (at least 1), (linear ramp from its current value to 0, reached at the latest
//!    `watchdog_periods·Δt + ramp_s` after the last fresh sample) and stays 0; once fresh data
//!    returns it rises again by `1/n_r` per period (no step back to full force). `w_g = g·w_c`.
//!    Before the first sample the output is zero.
//! 4. **Limits**: the force is scaled to `|F| ≤ F_max` keeping its direction, the torque clamped to
//!    `|τ| ≤ τ_max`; a non-finite value gives zero.

use needlesim_channel::shm::ServerForce;

/// Parameters of the safety layer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderParams {
    /// The device period Δt (s).
    pub period_s: f64,
    /// Limit on |(Fx, Fy)| (N).
    pub max_force_n: f64,
    /// Limit on |τ| (N·m).
    pub max_torque_nm: f64,
    /// Periods without a fresh server sample before the ramp to zero starts.
    pub watchdog_periods: u64,
    /// Duration of the ramp from full force to zero (and back) (s); 0 = a step.
    pub ramp_s: f64,
    /// Coupling stiffness (k_c, k_c, k_cθ) in N/m, N/m, N·m/rad; 0 on all three disables the coupling.
    pub coupling_k: [f64; 3],
    /// Coupling damping (b_c, b_c, b_cθ) in N·s/m, N·s/m, N·m·s/rad.
    pub coupling_b: [f64; 3],
}

impl Default for RenderParams {
    fn default() -> Self {
        Self {
            period_s: 1e-3,
            max_force_n: 5.0,
            max_torque_nm: 0.05,
            watchdog_periods: 10,
            ramp_s: 0.05,
            coupling_k: [2000.0, 2000.0, 2.0],
            coupling_b: [2.0, 2.0, 0.002],
        }
    }
}

/// What the server last sent, as the renderer needs it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ServerSample {
    pub wrench: [f64; 3],
    /// ∂(Fx, Fy, τ)/∂(x, y, θ), row-major.
    pub stiffness: [f64; 9],
    /// The pose the wrench was computed at.
    pub base: [f64; 3],
}

impl From<&ServerForce> for ServerSample {
    fn from(f: &ServerForce) -> Self {
        Self { wrench: [f.force_n[0], f.force_n[1], f.torque_nm], stiffness: f.stiffness, base: f.base }
    }
}

/// One period's result, with its intermediate values (for traces and tests).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RenderOutput {
    /// What to send to the device.
    pub wrench: [f64; 3],
    /// The local model `w_m` (before coupling, gain and limits).
    pub model: [f64; 3],
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
    /// Previous (q_d, q_t), for the coupling damper.
    prev: Option<([f64; 3], [f64; 3])>,
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
    pub fn update(&mut self, q_d: [f64; 3], fresh: Option<&ServerSample>) -> RenderOutput {
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
        let model = local_model(&s, q_d);
        let coupled = if p.coupling_k.iter().all(|&k| k == 0.0) {
            self.prev = None;
            model
        } else {
            match coupling_tool_pose(&s, &model, q_d, p.coupling_k) {
                Some(q_t) => {
                    let mut w = [0.0; 3];
                    for i in 0..3 {
                        w[i] = p.coupling_k[i] * (q_t[i] - q_d[i]);
                        if let Some((pd, pt)) = self.prev {
                            let rel_vel = ((q_d[i] - pd[i]) - (q_t[i] - pt[i])) / p.period_s;
                            w[i] -= p.coupling_b[i] * rel_vel;
                        }
                    }
                    self.prev = Some((q_d, q_t));
                    w
                }
                None => {
                    self.prev = None;
                    s.wrench
                }
            }
        };
        let gain = self.gain_steps as f64 / self.ramp_periods as f64;
        let scaled = coupled.map(|v| v * gain);
        let (wrench, limited) = limit(scaled, p.max_force_n, p.max_torque_nm);
        RenderOutput { wrench, model, gain, periods_since_fresh: self.periods_since_fresh, limited }
    }
}

/// `w_s + J (q_d − q_s)`.
pub fn local_model(s: &ServerSample, q_d: [f64; 3]) -> [f64; 3] {
    let dq = [q_d[0] - s.base[0], q_d[1] - s.base[1], q_d[2] - s.base[2]];
    std::array::from_fn(|i| s.wrench[i] + (0..3).map(|j| s.stiffness[3 * i + j] * dq[j]).sum::<f64>())
}

/// The virtual tool pose `q_t = q_d + (K_c − J)⁻¹ w_m`; `None` if `K_c − J` is (nearly) singular.
pub fn coupling_tool_pose(s: &ServerSample, w_m: &[f64; 3], q_d: [f64; 3], k_c: [f64; 3]) -> Option<[f64; 3]> {
    let a: [f64; 9] = std::array::from_fn(|idx| if idx / 3 == idx % 3 { k_c[idx / 3] } else { 0.0 } - s.stiffness[idx]);
    let x = solve3(&a, w_m)?;
    Some([q_d[0] + x[0], q_d[1] + x[1], q_d[2] + x[2]])
}

/// Solves the 3 × 3 system `A x = b` (row-major) by Cramer's rule; `None` if `|det A|` is below
/// 1e-12 of the product of the row norms (or anything is non-finite).
pub fn solve3(a: &[f64; 9], b: &[f64; 3]) -> Option<[f64; 3]> {
    let det = |m: &[f64; 9]| m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
    let d = det(a);
    let scale: f64 = (0..3).map(|r| (a[3 * r].powi(2) + a[3 * r + 1].powi(2) + a[3 * r + 2].powi(2)).sqrt()).product();
    if !d.is_finite() || d.abs() <= 1e-12 * scale || scale == 0.0 {
        return None;
    }
    let x: [f64; 3] = std::array::from_fn(|c| {
        let mut m = *a;
        for r in 0..3 {
            m[3 * r + c] = b[r];
        }
        det(&m) / d
    });
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Scales (Fx, Fy) to `|F| ≤ max_force` (same direction) and clamps `|τ| ≤ max_torque`; non-finite → 0.
/// Returns the wrench and whether it changed.
pub fn limit(w: [f64; 3], max_force: f64, max_torque: f64) -> ([f64; 3], bool) {
    if !w.iter().all(|v| v.is_finite()) {
        return ([0.0; 3], true);
    }
    let mut out = w;
    let mut limited = false;
    let f = w[0].hypot(w[1]);
    if f > max_force {
        let s = max_force.max(0.0) / f;
        out[0] *= s;
        out[1] *= s;
        limited = true;
    }
    if w[2].abs() > max_torque {
        out[2] = max_torque.max(0.0).copysign(w[2]);
        limited = true;
    }
    (out, limited)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_coupling() -> RenderParams {
        RenderParams { coupling_k: [0.0; 3], coupling_b: [0.0; 3], ramp_s: 0.0, ..Default::default() }
    }

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn limits_clamp_magnitude_and_keep_direction() {
        let (w, lim) = limit([3.0, 4.0, 0.01], 2.5, 0.05);
        assert!(lim);
        assert!(close(w, [1.5, 2.0, 0.01], 1e-15));
        let (w, lim) = limit([0.3, -0.4, -0.2], 5.0, 0.05);
        assert!(lim);
        assert_eq!(w, [0.3, -0.4, -0.05]);
        assert_eq!(limit([1.0, 1.0, 0.0], 5.0, 0.05), ([1.0, 1.0, 0.0], false));
        assert_eq!(limit([f64::NAN, 1.0, 0.0], 5.0, 0.05), ([0.0; 3], true));
        assert_eq!(limit([f64::INFINITY, 0.0, 0.0], 5.0, 0.05).0, [0.0; 3]);
    }

    #[test]
    fn local_model_is_exact_for_a_linear_environment() {
        // Environment w(q) = w0 + K q; the server evaluated it at base q_s.
        let k = [-200.0, 10.0, 0.5, 5.0, -300.0, -1.0, 0.1, 0.2, -0.05];
        let w0 = [0.1, -0.2, 0.001];
        let env = |q: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| w0[i] + (0..3).map(|j| k[3 * i + j] * q[j]).sum::<f64>()) };
        let q_s = [0.001, -0.002, 0.01];
        let s = ServerSample { wrench: env(q_s), stiffness: k, base: q_s };
        let q_d = [0.0015, -0.0025, 0.012];
        assert!(close(local_model(&s, q_d), env(q_d), 1e-12));
        let mut r = Renderer::new(RenderParams { max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() });
        assert_eq!(r.update(q_d, None).wrench, [0.0; 3], "nothing before the first sample");
        let out = r.update(q_d, Some(&s));
        assert!(close(out.wrench, env(q_d), 1e-12), "{out:?}");
        // Between updates the model follows the device.
        let q2 = [0.002, -0.001, 0.0];
        assert!(close(r.update(q2, None).wrench, env(q2), 1e-12));
    }

    #[test]
    fn watchdog_ramps_to_zero_then_holds_and_ramps_back() {
        let p = RenderParams { watchdog_periods: 5, ramp_s: 0.010, max_force_n: 100.0, ..no_coupling() };
        let mut r = Renderer::new(p);
        let s = ServerSample { wrench: [1.0, 0.0, 0.0], ..Default::default() };
        // Ramp in from 0 over 10 periods.
        for k in 1..=12 {
            let out = r.update([0.0; 3], Some(&s));
            let g = (k as f64 / 10.0).min(1.0);
            assert!((out.wrench[0] - g).abs() < 1e-12, "ramp-in period {k}: {out:?}");
        }
        // The server stops: 5 periods at full force, then −0.1 per period, zero after 15, held.
        let mut seen = vec![];
        for _ in 0..40 {
            seen.push(r.update([0.0; 3], None).wrench[0]);
        }
        for (k, f) in seen.iter().enumerate() {
            let n = k as f64 + 1.0; // periods since fresh
            let expect = if n <= 5.0 { 1.0 } else { (1.0 - (n - 5.0) * 0.1).max(0.0) };
            assert!((f - expect).abs() < 1e-9, "period {n}: {f} vs {expect}");
        }
        assert_eq!(seen[14..], vec![0.0; 26][..]);
        // Fresh data: back up gradually, not a step.
        let out = r.update([0.0; 3], Some(&s));
        assert!((out.wrench[0] - 0.1).abs() < 1e-12 && out.periods_since_fresh == 0);
        // Skipped periods count as periods without data: 4 fresh → gain 0.5, then 5 + 3 missed → 0.2.
        for _ in 0..4 {
            r.update([0.0; 3], Some(&s));
        }
        r.missed(8);
        let out = r.update([0.0; 3], None);
        assert!((out.wrench[0] - 0.1).abs() < 1e-12 && out.periods_since_fresh == 9, "{out:?}");
        r.missed(1_000_000);
        assert_eq!(r.update([0.0; 3], None).periods_since_fresh, 1_000_010);
    }

    #[test]
    fn coupling_is_the_series_spring_and_damps_relative_motion() {
        let kc = [1000.0, 1000.0, 1.0];
        let p = RenderParams { coupling_k: kc, coupling_b: [0.0; 3], max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() };
        let mut r = Renderer::new(p);
        // Diagonal tissue stiffness k_t: the series stiffness is k_t k_c / (k_t + k_c).
        let kt = [3000.0, 1000.0, 0.5];
        let s = ServerSample { wrench: [0.0; 3], stiffness: [-kt[0], 0.0, 0.0, 0.0, -kt[1], 0.0, 0.0, 0.0, -kt[2]], base: [0.0; 3] };
        let q = [0.001, -0.002, 0.1];
        let out = r.update(q, Some(&s));
        let expect: [f64; 3] = std::array::from_fn(|i| -kt[i] * kc[i] / (kt[i] + kc[i]) * q[i]);
        assert!(close(out.wrench, expect, 1e-12), "{out:?} vs {expect:?}");
        // Never stiffer than the coupling, however stiff the tissue.
        let stiff = ServerSample { stiffness: [-1e9, 0.0, 0.0, 0.0, -1e9, 0.0, 0.0, 0.0, -1e9], ..s };
        let out = r.update(q, Some(&stiff));
        assert!(close(out.wrench, [-1.0, 2.0, -0.1], 1e-5), "{out:?}");
        // A free tool (J = 0): the tool follows the device, no force, no damping on free motion.
        let p = RenderParams { coupling_b: [5.0, 5.0, 0.01], ..p };
        let mut r = Renderer::new(p);
        let free = ServerSample { wrench: [0.5, 0.0, 0.0], stiffness: [0.0; 9], base: [0.0; 3] };
        r.update([0.0; 3], Some(&free));
        let out = r.update([0.01, 0.0, 0.0], Some(&free));
        assert!(close(out.wrench, [0.5, 0.0, 0.0], 1e-12), "{out:?}");
        // Against a very stiff wall the tool stays: the damper acts on the device's velocity.
        let mut r = Renderer::new(p);
        r.update([0.0; 3], Some(&stiff));
        let out = r.update([1e-4, 0.0, 0.0], Some(&stiff));
        // spring ≈ −k_c·1e-4 = −0.1, damper ≈ −b_c·(1e-4/1e-3) = −0.5
        assert!((out.wrench[0] - (-0.6)).abs() < 1e-4, "{out:?}");
    }

    #[test]
    fn singular_coupling_falls_back_to_the_server_wrench() {
        let kc = [1000.0, 1000.0, 1.0];
        let p = RenderParams { coupling_k: kc, max_force_n: 1e9, max_torque_nm: 1e9, ..no_coupling() };
        let mut r = Renderer::new(p);
        let s = ServerSample { wrench: [0.3, 0.2, 0.01], stiffness: [1000.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], base: [0.0; 3] };
        assert_eq!(r.update([0.1, 0.1, 0.1], Some(&s)).wrench, [0.3, 0.2, 0.01]);
        assert_eq!(solve3(&[1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 0.0, 1.0], &[1.0, 1.0, 1.0]), None);
        let x = solve3(&[2.0, 0.0, 0.0, 0.0, 4.0, 1.0, 0.0, 1.0, 3.0], &[2.0, 5.0, 4.0]).unwrap();
        assert!(close(x, [1.0, 1.0, 1.0], 1e-14));
    }

    #[test]
    fn limits_apply_after_the_model() {
        let p = RenderParams { max_force_n: 1.0, max_torque_nm: 0.01, ..no_coupling() };
        let mut r = Renderer::new(p);
        let s = ServerSample { wrench: [0.0, 0.0, 0.0], stiffness: [-1000.0, 0.0, 0.0, 0.0, -1000.0, 0.0, 0.0, 0.0, -1.0], base: [0.0; 3] };
        let out = r.update([0.003, 0.004, 0.5], Some(&s));
        assert!(out.limited);
        assert!(close(out.wrench, [-0.6, -0.8, -0.01], 1e-12), "{out:?}");
        assert!(close(out.model, [-3.0, -4.0, -0.5], 1e-12));
    }
}
