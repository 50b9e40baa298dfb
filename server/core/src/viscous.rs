//! Viscoelastic tissue, a standard linear solid with one proportional relaxation, applied
//! through the condensed compliance: the working set's history adds two $N$-vectors per contact
//! ($N$ = 2 or 3, the dimension: one code for both simulations, [`crate::sim`] and
//! [`crate::sim3`]) and $O(d)$ work per tick.
//!
//! **The law.** Every modulus of the tissue relaxes alike (same $\nu$, one time constant for the
//! tissue): $E(t) = E_\infty + (E_0 - E_\infty)\,e^{-t/\tau}$, i.e. the stiffness matrix is
//! $K(t) = K_0\,g(t)$ with $g(t) = g_\infty + (1 - g_\infty)\,e^{-t/\tau}$, $g_\infty = E_\infty/E_0$,
//! and $K_0$ the stiffness of the scene's (instantaneous) moduli. Proportional relaxation is a
//! simplification — real tissue relaxes its shear and bulk moduli differently — that keeps
//! $K_0$'s factorisation and every cached compliance column valid: the forces of a displacement
//! history $u(s)$ are
//! $$f(t) = K_0 \int_0^t g(t - s)\,\mathrm{d}u(s) = K_0\,v(t), \qquad v(t) = g_\infty u(t) + (1 - g_\infty)\,h(t),\quad h(t) = \int_0^t e^{-(t-s)/\tau}\,\mathrm{d}u(s),$$
//! so the elastic relation holds between the forces and the *pseudo-elastic* displacement $v$
//! (the correspondence principle): $v = C_0 f$ at every DOF, and at the working contacts
//! $v_a = \sum_b W_{ab} f_b$ with the elastic blocks $W_{ab}$ of the cache.
//!
//! **Recursive update.** Over a tick $[t_{n-1}, t_n]$, $\Delta t = t_n - t_{n-1}$, with $u$
//! linear in time (the poses are given at ticks; between them the motion is taken as linear),
//! $$h_n = a\,h_{n-1} + b\,(u_n - u_{n-1}), \qquad a = e^{-\Delta t/\tau},\quad b = \frac{\tau}{\Delta t}\,(1 - a),$$
//! exactly. Hence at tick $n$
//! $$v_n = \gamma\,u_n + r_n, \qquad \gamma = g_\infty + (1 - g_\infty)\,b, \qquad r_n = (1 - g_\infty)\,(a\,h_{n-1} - b\,u_{n-1}),$$
//! with $r_n$ known before the tick's solve. The working solver therefore solves an elastic
//! problem with every compliance block scaled by $1/\gamma$ (a constant of the scene and the
//! tick rate, [`ScaledBlocks`]) for the shifted displacement $\tilde u_a = u_a + r_a/\gamma$:
//! $\tilde u_a = \sum_b (W_{ab}/\gamma) f_b$. The shift is carried as a shift of the contact's
//! reference position ($x_a + \tilde u_a - r_a/\gamma$ is where the tissue point is), so the
//! prescribed values, the stick/slip rules and the output read the true positions, and the
//! solver's forces are the total (elastic + history) forces the stick/slip decisions use.
//! After the tick $h_n$ and $u_n$ are stored. For a fixed set of contacts under prescribed
//! displacements the recursion reproduces the convolution exactly (to round-off) for any
//! piecewise-linear history: a step held still relaxes as
//! $f(t) = f_{el}\,[g_\infty + (1 - g_\infty)\tfrac{\tau}{\Delta t}(e^{\Delta t/\tau} - 1)\,e^{-t/\tau}]$
//! (a ramp over one tick, then held), which tends to $g_\infty f_{el}$ with time constant $\tau$.
//!
//! **What is approximated.** The history is kept at the working contacts only:
//! - a contact captured at tick $n$ starts with $h = u = v$ (its pseudo-elastic displacement
//!   from the working forces): as if its displacement had been applied at once. Its own
//!   displacement history before capture (it was moved by its neighbours' forces) is not known
//!   without a history at every node;
//! - a released contact's history is dropped with it (the tissue it leaves springs back at
//!   once instead of creeping back with the retardation time $\tau/g_\infty$);
//! - points off the working set (capture searches, targets, the rendered field) are placed by
//!   their pseudo-elastic displacement $v = C_0 f$, not by $u$.
//!
//! An elastic scene ($g_\infty = 1$, or no viscoelasticity) runs none of this: its results are
//! unchanged bit for bit.
//!
//! **In 3D** the same holds contact by contact ([`crate::sim3`]): the material points' history is
//! that of the solver's displacement (the needle's surface point: the tissue's plus the needle's
//! near field, [`crate::sim3::NearField3`], whose series compliance is scaled by $1/\gamma$ with
//! the blocks, since it is tissue too), and the wrench stiffness a device renders is the
//! instantaneous one of a tick, the blocks $W/\gamma$.

use crate::compliance::ContactBlocks;
use crate::contact::ContactPoint;

/// A standard linear solid with one relaxation for the whole tissue (module docs):
/// $E(t) = E_\infty + (E_0 - E_\infty)\,e^{-t/\tau}$ with $E_0$ the tissue's moduli.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viscoelastic {
    /// $g_\infty = E_\infty / E_0$, in (0, 1]: the long-term fraction of the instantaneous
    /// stiffness (1: elastic).
    pub long_term_ratio: f64,
    /// Relaxation time $\tau$ at constant strain, s.
    pub relaxation_time_s: f64,
}

impl Viscoelastic {
    /// Checks the values; the message names the field and its range.
    pub fn validate(&self) -> Result<(), String> {
        let g = self.long_term_ratio;
        if !(g.is_finite() && g > 0.0 && g <= 1.0) {
            return Err(format!("viscoelastic long_term_ratio = {} must be in (0, 1]", crate::num::num(g)));
        }
        let tau = self.relaxation_time_s;
        if !(tau.is_finite() && tau > 0.0) {
            return Err(format!("viscoelastic relaxation_time_s = {} must be finite and > 0", crate::num::num(tau)));
        }
        Ok(())
    }

    /// The normalised relaxation function $g(t) = g_\infty + (1 - g_\infty)\,e^{-t/\tau}$.
    pub fn relaxation(&self, t_s: f64) -> f64 {
        self.long_term_ratio + (1.0 - self.long_term_ratio) * (-t_s / self.relaxation_time_s).exp()
    }
}

/// The recursion's constants for one tick length (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ViscCoeffs {
    /// $a = e^{-\Delta t/\tau}$.
    pub a: f64,
    /// $b = (\tau/\Delta t)(1 - a)$.
    pub b: f64,
    /// $1 - g_\infty$.
    pub one_minus_g: f64,
    /// $\gamma = g_\infty + (1 - g_\infty) b$.
    pub gamma: f64,
}

impl ViscCoeffs {
    /// The constants at `tick_rate_hz`; `None` for an elastic tissue ($g_\infty = 1$ or none),
    /// which then takes none of the viscous paths.
    pub fn new(v: Option<Viscoelastic>, tick_rate_hz: f64) -> Option<Self> {
        let v = v?;
        if v.long_term_ratio >= 1.0 {
            return None;
        }
        let dt = 1.0 / tick_rate_hz;
        let x = dt / v.relaxation_time_s;
        let a = (-x).exp();
        // (1 − e^{−x})/x without cancellation for small x.
        let b = if x > 1e-6 { -(-x).exp_m1() / x } else { 1.0 - 0.5 * x + x * x / 6.0 };
        let one_minus_g = 1.0 - v.long_term_ratio;
        Some(Self { a, b, one_minus_g, gamma: v.long_term_ratio + one_minus_g * b })
    }

    /// The scale of every compliance block in the working solver, $1/\gamma$.
    pub fn compliance_scale(&self) -> f64 {
        1.0 / self.gamma
    }
}

/// A contact's viscous history (world components, m): $h_{n-1}$, $u_{n-1}$ and the shift
/// $-r_n/\gamma$ of its reference position for the coming tick, in the `D` world components
/// of the dimension. All zero in an elastic tissue.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct History<const D: usize> {
    pub h_m: [f64; D],
    pub u_prev_m: [f64; D],
    pub shift_m: [f64; D],
}

impl<const D: usize> Default for History<D> {
    fn default() -> Self {
        Self { h_m: [0.0; D], u_prev_m: [0.0; D], shift_m: [0.0; D] }
    }
}

impl<const D: usize> History<D> {
    /// The history of a contact captured with pseudo-elastic displacement `v_m`: $h = u = v$.
    pub fn captured(c: &ViscCoeffs, v_m: [f64; D]) -> Self {
        let mut hist = Self { h_m: v_m, u_prev_m: v_m, shift_m: [0.0; D] };
        hist.shift_m = hist.next_shift(c);
        hist
    }

    /// One tick on: $h_n = a h_{n-1} + b (u_n - u_{n-1})$, $u_{n-1} \leftarrow u_n$, and the
    /// shift for the next tick. $O(1)$, no allocation.
    pub fn advance(&mut self, c: &ViscCoeffs, u_m: [f64; D]) {
        for k in 0..D {
            self.h_m[k] = c.a * self.h_m[k] + c.b * (u_m[k] - self.u_prev_m[k]);
            self.u_prev_m[k] = u_m[k];
        }
        self.shift_m = self.next_shift(c);
    }

    /// $-r/\gamma$ with $r = (1 - g_\infty)(a h - b u)$ from the stored $h$, $u$.
    fn next_shift(&self, c: &ViscCoeffs) -> [f64; D] {
        let k = -c.one_minus_g / c.gamma;
        std::array::from_fn(|i| k * (c.a * self.h_m[i] - c.b * self.u_prev_m[i]))
    }

    /// `x_m` shifted by the history: the position the working solver's displacement is
    /// measured from when `x_m` is the contact's reference position (module docs).
    #[inline]
    pub fn shifted(&self, x_m: [f64; D]) -> [f64; D] {
        std::array::from_fn(|i| x_m[i] + self.shift_m[i])
    }
}

/// A store's elastic blocks scaled by a constant (the working solver's $W_{ab}/\gamma$), in
/// either dimension and over any store ([`ContactBlocks`]: the column cache, 3D's node blocks);
/// a scale of exactly 1 returns the blocks bit for bit.
pub(crate) struct ScaledBlocks<'a, C: ?Sized> {
    pub cache: &'a C,
    pub scale: f64,
}

impl<const D: usize, C: ContactBlocks<D> + ?Sized> ContactBlocks<D> for ScaledBlocks<'_, C> {
    #[inline]
    fn contact_block(&self, a: &ContactPoint, b: &ContactPoint) -> Option<[[f64; D]; D]> {
        let w = self.cache.contact_block(a, b)?;
        Some(w.map(|row| row.map(|x| x * self.scale)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recursion reproduces the convolution of a piecewise-linear history (direct
    /// quadrature of each linear piece in closed form) to round-off, and γ, a, b are the
    /// closed forms' values.
    #[test]
    fn recursion_equals_the_convolution_of_a_piecewise_linear_history() {
        let v = Viscoelastic { long_term_ratio: 0.35, relaxation_time_s: 0.07 };
        let rate = 1000.0;
        let c = ViscCoeffs::new(Some(v), rate).unwrap();
        let dt = 1.0 / rate;
        // A seeded zig-zag history of one component.
        let n = 400;
        let u: Vec<f64> = (0..=n).map(|k| 1e-3 * ((k as f64 * 0.037).sin() + 0.3 * ((k * 7 % 13) as f64 / 13.0))).collect();
        let mut hist = History::<2>::captured(&c, [u[0], 0.0]);
        for k in 1..=n {
            // v_n from the recursion: γ u_n + r_n = γ (u_n − shift), the shift being −r_n/γ.
            let v_rec = c.gamma * (u[k] - hist.shift_m[0]);
            // v_n by the convolution: u(0) applied at t = 0 (g(t_k) u_0), then each linear piece.
            let t = k as f64 * dt;
            let tau = v.relaxation_time_s;
            let mut v_conv = v.relaxation(t) * u[0];
            for j in 1..=k {
                let slope = (u[j] - u[j - 1]) / dt;
                let (s0, s1) = ((j - 1) as f64 * dt, j as f64 * dt);
                // ∫ g(t − s) ds over [s0, s1].
                let int = v.long_term_ratio * dt + (1.0 - v.long_term_ratio) * tau * ((-(t - s1) / tau).exp() - (-(t - s0) / tau).exp());
                v_conv += slope * int;
            }
            assert!((v_rec - v_conv).abs() <= 1e-12 * v_conv.abs().max(1e-3), "tick {k}: {v_rec} vs {v_conv}");
            hist.advance(&c, [u[k], 0.0]);
        }
    }

    #[test]
    fn elastic_tissue_takes_no_viscous_path_and_bad_values_are_named() {
        assert_eq!(ViscCoeffs::new(None, 1000.0), None);
        assert_eq!(ViscCoeffs::new(Some(Viscoelastic { long_term_ratio: 1.0, relaxation_time_s: 1.0 }), 1000.0), None);
        let bad = Viscoelastic { long_term_ratio: 0.0, relaxation_time_s: 1.0 }.validate().unwrap_err();
        assert!(bad.contains("long_term_ratio"), "{bad}");
        let bad = Viscoelastic { long_term_ratio: 0.5, relaxation_time_s: -1.0 }.validate().unwrap_err();
        assert!(bad.contains("relaxation_time_s"), "{bad}");
    }
}
