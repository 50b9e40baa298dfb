//! Linear-elastic materials per region, in plane strain or plane stress.
//!
//! Stress from strain in Voigt form $[\sigma_{xx}, \sigma_{yy}, \sigma_{xy}] = D\,[\varepsilon_{xx}, \varepsilon_{yy}, \gamma_{xy}]$
//! (engineering shear $\gamma_{xy} = 2\varepsilon_{xy}$), with
//! $\sigma = 2\mu\varepsilon + \lambda\,\mathrm{tr}(\varepsilon) I$, $\mu = E / (2(1+\nu))$ and
//! $\lambda = E\nu / ((1+\nu)(1-2\nu))$ in plane strain, $\lambda = E\nu/(1-\nu^2)$ in plane stress.

/// Errors in material parameters, naming the region.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MaterialError {
    /// Young's modulus is not finite, positive and at most
    /// [`crate::sim::param_limits::MAX_YOUNG_MODULUS_PA`].
    #[error("{region}: Young's modulus E = {} Pa must be finite, > 0 and ≤ {:e} Pa", crate::num::num(*young_modulus_pa), crate::sim::param_limits::MAX_YOUNG_MODULUS_PA)]
    YoungModulus { region: String, young_modulus_pa: f64 },
    /// Poisson's ratio is outside (−1, 0.5] in plane stress, or outside (−1, 0.5) in plane strain.
    #[error("{region}: Poisson ratio ν = {} must be finite and in {}", crate::num::num(*poisson_ratio), if *.plane_strain { "(−1, 0.5) in plane strain (ν = 0.5, incompressible, makes λ infinite)" } else { "(−1, 0.5] in plane stress" })]
    PoissonRatio { region: String, poisson_ratio: f64, plane_strain: bool },
    /// The thickness is not finite, positive and at most [`crate::sim::param_limits::MAX_LENGTH_M`].
    #[error("thickness {} m must be finite, > 0 and ≤ {} m", crate::num::num(*thickness_m), crate::num::num(crate::sim::param_limits::MAX_LENGTH_M))]
    Thickness { thickness_m: f64 },
    /// The number of materials does not match the number of regions of the mesh.
    #[error("the mesh has {n_regions} region(s) but {n_materials} material(s) were given")]
    Count { n_regions: usize, n_materials: usize },
}

/// Isotropic linear elasticity of one region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    pub young_modulus_pa: f64,
    pub poisson_ratio: f64,
}

/// The 2D idealisation, with the out-of-plane thickness that scales stiffness and forces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneModel {
    /// $\varepsilon_{zz} = 0$; forces are per `thickness_m` of depth.
    Strain { thickness_m: f64 },
    /// $\sigma_{zz} = 0$; a thin sheet of `thickness_m`.
    Stress { thickness_m: f64 },
}

impl PlaneModel {
    /// The out-of-plane thickness in metres.
    pub fn thickness_m(&self) -> f64 {
        match *self {
            PlaneModel::Strain { thickness_m } | PlaneModel::Stress { thickness_m } => thickness_m,
        }
    }
    /// Whether this is plane strain.
    pub fn is_strain(&self) -> bool {
        matches!(self, PlaneModel::Strain { .. })
    }
    /// Checks the thickness.
    pub fn validate(&self) -> Result<(), MaterialError> {
        let thickness_m = self.thickness_m();
        if !(thickness_m.is_finite() && thickness_m > 0.0 && thickness_m <= crate::sim::param_limits::MAX_LENGTH_M) {
            return Err(MaterialError::Thickness { thickness_m });
        }
        Ok(())
    }
}

impl Material {
    /// Checks E and ν for the given plane model; `region` names the item in the error, e.g.
    /// `region tissue` or `element 12`.
    pub fn validate(&self, plane: PlaneModel, region: &str) -> Result<(), MaterialError> {
        let (e, nu) = (self.young_modulus_pa, self.poisson_ratio);
        if !(e.is_finite() && e > 0.0 && e <= crate::sim::param_limits::MAX_YOUNG_MODULUS_PA) {
            return Err(MaterialError::YoungModulus { region: region.to_owned(), young_modulus_pa: e });
        }
        // ν = 0.5 (incompressible) is a valid thin sheet in plane stress, but makes λ infinite in plane strain.
        let upper_ok = if plane.is_strain() { nu < 0.5 } else { nu <= 0.5 };
        if !(nu.is_finite() && nu > -1.0 && upper_ok) {
            return Err(MaterialError::PoissonRatio { region: region.to_owned(), poisson_ratio: nu, plane_strain: plane.is_strain() });
        }
        Ok(())
    }

    /// The Lamé parameters $(\lambda, \mu)$ in Pa for the plane model.
    pub fn lame_pa(&self, plane: PlaneModel) -> (f64, f64) {
        let (e, nu) = (self.young_modulus_pa, self.poisson_ratio);
        let mu = e / (2.0 * (1.0 + nu));
        let lambda = if plane.is_strain() { e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)) } else { e * nu / (1.0 - nu * nu) };
        (lambda, mu)
    }

    /// The 3 × 3 Voigt matrix $D$ (row-major), as in the module docs.
    pub fn d_matrix(&self, plane: PlaneModel) -> [[f64; 3]; 3] {
        let (e, nu) = (self.young_modulus_pa, self.poisson_ratio);
        if plane.is_strain() {
            let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
            [[c * (1.0 - nu), c * nu, 0.0], [c * nu, c * (1.0 - nu), 0.0], [0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0]]
        } else {
            let c = e / (1.0 - nu * nu);
            [[c, c * nu, 0.0], [c * nu, c, 0.0], [0.0, 0.0, c * (1.0 - nu) / 2.0]]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d_matrix_matches_lame_form() {
        for plane in [PlaneModel::Strain { thickness_m: 1.0 }, PlaneModel::Stress { thickness_m: 0.01 }] {
            let m = Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 };
            let (l, mu) = m.lame_pa(plane);
            let d = m.d_matrix(plane);
            let scale = d[0][0];
            assert!((d[0][0] - (l + 2.0 * mu)).abs() < 1e-12 * scale);
            assert!((d[0][1] - l).abs() < 1e-12 * scale);
            assert!((d[2][2] - mu).abs() < 1e-12 * scale);
        }
    }

    #[test]
    fn invalid_parameters_are_named() {
        let strain = PlaneModel::Strain { thickness_m: 1.0 };
        let e = Material { young_modulus_pa: 0.0, poisson_ratio: 0.3 }.validate(strain, "region lesion").unwrap_err();
        assert!(e.to_string().contains("region lesion: Young's modulus E = 0 Pa"), "{e}");
        let e = Material { young_modulus_pa: f64::NAN, poisson_ratio: 0.3 }.validate(strain, "a").unwrap_err();
        assert!(e.to_string().contains("E = NaN"), "{e}");
        let e = Material { young_modulus_pa: 1.0, poisson_ratio: 0.5 }.validate(strain, "a").unwrap_err();
        assert!(e.to_string().contains("ν = 0.5") && e.to_string().contains("plane strain"), "{e}");
        let stress = PlaneModel::Stress { thickness_m: 1.0 };
        assert!(Material { young_modulus_pa: 1.0, poisson_ratio: 0.5 }.validate(stress, "a").is_ok());
        assert!(Material { young_modulus_pa: 1.0, poisson_ratio: 0.51 }.validate(stress, "a").is_err());
        assert!(Material { young_modulus_pa: 1.0, poisson_ratio: -1.0 }.validate(stress, "a").is_err());
        assert!(Material { young_modulus_pa: 1.0, poisson_ratio: -0.99 }.validate(stress, "a").is_ok());
        let e = PlaneModel::Stress { thickness_m: -1.0 }.validate().unwrap_err();
        assert!(e.to_string().contains("thickness -1 m"), "{e}");
    }
}
