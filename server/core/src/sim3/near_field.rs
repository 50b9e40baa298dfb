//! The needle's near field (sub-grid compliance, issue 37): what the tetrahedra cannot resolve
//! of the tissue between the needle's radius $a$ and an equivalent radius $r_e = \beta h$ of the
//! element (a well model's correction, Peaceman 1978/1983), added at each material point as a
//! compliance in series with the tissue ([`crate::mixed::MixedSolver::add_series_compliance`]).
//!
//! A shaft point holding a tributary length $s$ of a line load $q = f/s$ sees, between $r = a$
//! and $r = r_e$, the displacement difference of the 2D Kelvin solution (plane strain, across
//! the shaft) and of antiplane shear (along it), $\mu = E / (2(1+\nu))$:
//! $$c_\perp = \frac{(3 - 4\nu)\ln(r_e/a)}{8\pi\mu(1-\nu)\,s},\qquad c_\parallel = \frac{\ln(r_e/a)}{2\pi\mu\,s},$$
//! as the block $S = c_\perp (I - t t^\top) + c_\parallel t t^\top$ on the point's own compliance
//! ($t$ the needle's tangent when the point joins; only where $r_e > a$). $h = (6V)^{1/3}$ of the
//! point's tetrahedron (the cell edge of a Kuhn-split box grid, [`crate::d3::BoxGridParams`]);
//! $s$ the reference distance to the nearest held point when it joins, or
//! $\max(\text{spacing}, \text{tetrahedron diameter})$ (what the capture rule spaces points by)
//! for the first. $\beta$ is calibrated on the discrete problem, one for each direction
//! ([`NEAR_FIELD_BETA_AXIAL`], [`NEAR_FIELD_BETA_LATERAL`]).
//!
//! The stick and slip conditions prescribe the needle's surface point (the solver's
//! displacement, tissue plus near field); the tissue's material point, reported in the output
//! and the snapshot, is that minus the near-field part $S f$.

use crate::ids::Slot;

use super::{SimError3, Simulation3, dist};

/// $\beta_\parallel = r_e / h$ along the needle: the radius at which the analytic field of a line
/// load (antiplane) gives the FE displacement of a line of point loads at $r = 3h$ from the loads,
/// geometric mean over the line's position in the cell of a Kuhn-split box grid
/// (docs/guide/physics.md, "The needle's near field (3D)"; the test `near_field_calibration`).
pub const NEAR_FIELD_BETA_AXIAL: f64 = 0.44;
/// $\beta_\perp = r_e / h$ across the needle (plane strain), calibrated as
/// [`NEAR_FIELD_BETA_AXIAL`].
pub const NEAR_FIELD_BETA_LATERAL: f64 = 0.87;

/// The near-field model of a 3D simulation ([`super::Sim3Params::near_field`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearField3 {
    /// The needle's outer radius $a$, m.
    pub needle_radius_m: f64,
    /// $\beta_\parallel$ (default [`NEAR_FIELD_BETA_AXIAL`]).
    pub beta_axial: f64,
    /// $\beta_\perp$ (default [`NEAR_FIELD_BETA_LATERAL`]).
    pub beta_lateral: f64,
}

impl NearField3 {
    /// The model for a needle of outer radius `needle_radius_m` with the calibrated $\beta$.
    pub fn new(needle_radius_m: f64) -> Self {
        Self { needle_radius_m, beta_axial: NEAR_FIELD_BETA_AXIAL, beta_lateral: NEAR_FIELD_BETA_LATERAL }
    }

    /// $(c_\parallel, c_\perp)$ in m/N for element size `h_m`, tributary length `s_m` and
    /// material $(E, \nu)$ (module docs); each zero where its $\beta h \le a$.
    pub fn compliances(&self, h_m: f64, s_m: f64, young_modulus_pa: f64, poisson_ratio: f64) -> (f64, f64) {
        if !(s_m > 0.0) {
            return (0.0, 0.0);
        }
        let mu = young_modulus_pa / (2.0 * (1.0 + poisson_ratio));
        let ln = |beta: f64| (beta * h_m / self.needle_radius_m).ln().max(0.0);
        let c_par = ln(self.beta_axial) / (2.0 * std::f64::consts::PI * mu * s_m);
        let c_perp = (3.0 - 4.0 * poisson_ratio) * ln(self.beta_lateral) / (8.0 * std::f64::consts::PI * mu * (1.0 - poisson_ratio) * s_m);
        (c_par, c_perp)
    }
}

impl Simulation3 {
    /// Adds the near field to every working point that has none yet (those captured this tick),
    /// in the frame it has now. $O(m)$ per tick, $O(d^2)$ per point added; nothing without
    /// [`super::Sim3Params::near_field`].
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses the update (not expected).
    pub(super) fn apply_near_field(&mut self) -> Result<(), SimError3> {
        let Some(nf) = self.params.near_field else { return Ok(()) };
        let mesh = self.model.mesh();
        for k in 0..self.pts.len() {
            let slot = Slot::new(k);
            if self.solver.series_compliance(slot) != [[0.0; 3]; 3] {
                continue;
            }
            let p = &self.pts[k];
            let Some(tet) = p.contact.tet_idx() else { continue };
            let h_m = (6.0 * mesh.volume_m3(tet).abs()).cbrt();
            if nf.beta_axial.max(nf.beta_lateral) * h_m <= nf.needle_radius_m {
                // The mesh resolves the needle here: nothing to add (checked before the
                // $O(m)$ search below, which would otherwise run every tick).
                continue;
            }
            let nearest =
                (0..self.pts.len()).filter(|&j| j != k).map(|j| dist(self.pts[j].x_ref_m, p.x_ref_m)).fold(f64::INFINITY, f64::min);
            let s_m = if nearest.is_finite() { nearest } else { self.params.spacing_m.max(self.setup.tet_diam_m[tet]) };
            let mat = self.model.materials().material_of_tet()[tet];
            let (c_par, c_perp) = nf.compliances(h_m, s_m, mat.young_modulus_pa, mat.poisson_ratio);
            if c_par == 0.0 && c_perp == 0.0 {
                continue;
            }
            let t = self.solver.frame(slot)[0];
            // Scaled as the tissue's blocks in a viscoelastic tissue (1/γ, [`crate::viscous`]).
            let scale = self.setup.compliance_scale;
            let block: [[f64; 3]; 3] = std::array::from_fn(|i| {
                std::array::from_fn(|j| (c_perp * (if i == j { 1.0 } else { 0.0 }) + (c_par - c_perp) * t[i] * t[j]) * scale)
            });
            self.solver.add_series_compliance(slot, block)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed forms: $c_\parallel / c_\perp = 4(1-\nu)/(3-4\nu)$, $c \propto \ln(\beta h/a)/s$,
    /// zero when $\beta h \le a$.
    #[test]
    fn compliances_follow_the_closed_forms() {
        let nf = NearField3 { needle_radius_m: 0.5e-3, beta_axial: 0.25, beta_lateral: 0.25 };
        let (e, nu) = (30e3, 0.45);
        let mu = e / (2.0 * (1.0 + nu));
        let (c_par, c_perp) = nf.compliances(8e-3, 2e-3, e, nu);
        let ln = (2e-3_f64 / 0.5e-3).ln();
        assert!((c_par - ln / (2.0 * std::f64::consts::PI * mu * 2e-3)).abs() <= 1e-12 * c_par);
        assert!((c_par / c_perp - 4.0 * (1.0 - nu) / (3.0 - 4.0 * nu)).abs() <= 1e-12);
        let (c2, _) = nf.compliances(8e-3, 4e-3, e, nu);
        assert!((c2 - 0.5 * c_par).abs() <= 1e-12 * c_par);
        assert_eq!(nf.compliances(2e-3, 2e-3, e, nu), (0.0, 0.0));
        // Each direction by its own β.
        let nf2 = NearField3 { beta_lateral: 0.5, ..nf };
        let (p2, q2) = nf2.compliances(8e-3, 2e-3, e, nu);
        assert_eq!(p2, c_par);
        assert!((q2 / c_perp - (4e-3_f64 / 0.5e-3).ln() / ln).abs() <= 1e-12);
    }
}
