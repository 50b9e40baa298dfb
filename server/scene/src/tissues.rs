//! The tissue library (issue 34): named materials (`material = "liver"` in a scene's region) with
//! their elasticity and needle-interaction values, each with its literature source, in
//! `tissues.toml` beside this file. A key written in the region overrides the material's; a key
//! neither gives keeps the region's default.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::Deserialize;

/// The library's text (embedded; sources and how sure each value is are its comments).
pub const TISSUES_TOML: &str = include_str!("tissues.toml");

/// One material of the library: the region keys it gives (`None`: left at the default).
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tissue {
    pub description: String,
    pub young_modulus_pa: f64,
    pub poisson_ratio: f64,
    pub friction_n_per_m: Option<f64>,
    pub static_friction_ratio: Option<f64>,
    pub tip_peak_ratio: Option<f64>,
    pub tip_peak_width_m: Option<f64>,
    pub puncture_force_n: Option<f64>,
    pub cutting_force_n: Option<f64>,
    pub friction_damping_n_s_per_m2: Option<f64>,
    /// Used only with `needle.cutting = "toughness"` (2D).
    pub fracture_toughness_j_per_m2: Option<f64>,
}

/// The library, by name.
pub fn tissues() -> &'static BTreeMap<String, Tissue> {
    static LIB: OnceLock<BTreeMap<String, Tissue>> = OnceLock::new();
    LIB.get_or_init(|| toml::from_str(TISSUES_TOML).expect("tissues.toml is valid (tested)"))
}

/// The material `name`, or an error listing the library's names.
pub fn tissue(name: &str) -> Result<&'static Tissue, String> {
    tissues().get(name).ok_or_else(|| {
        let names: Vec<&str> = tissues().keys().map(String::as_str).collect();
        format!("material = \"{}\" is not in the tissue library ({})", crate::limit::quote(name), names.join(", "))
    })
}

/// The region keys as written (all optional) with a `material`: what a region's TOML holds
/// before the material and the defaults are applied (2D and 3D).
#[derive(Debug, Clone, Default, Deserialize)]
pub struct MaterialKeys {
    pub material: Option<String>,
    pub young_modulus_pa: Option<f64>,
    pub poisson_ratio: Option<f64>,
    pub friction_n_per_m: Option<f64>,
    pub static_friction_ratio: Option<f64>,
    pub tip_peak_ratio: Option<f64>,
    pub tip_peak_width_m: Option<f64>,
    pub puncture_force_n: Option<f64>,
    pub cutting_force_n: Option<f64>,
    pub friction_damping_n_s_per_m2: Option<f64>,
}

/// A region's resolved values: written key, else the material's, else the default.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolved {
    pub young_modulus_pa: f64,
    pub poisson_ratio: f64,
    pub friction_n_per_m: f64,
    pub static_friction_ratio: f64,
    pub tip_peak_ratio: f64,
    pub tip_peak_width_m: f64,
    pub puncture_force_n: f64,
    pub cutting_force_n: f64,
    pub friction_damping_n_s_per_m2: f64,
    /// The material's fracture toughness, if it has one (applied with toughness cutting only).
    pub material_toughness_j_per_m2: Option<f64>,
}

impl MaterialKeys {
    /// Applies the material and the defaults; `region` names the region in errors.
    pub fn resolve(&self, region: &str) -> Result<Resolved, String> {
        let m = match &self.material {
            Some(name) => Some(tissue(name).map_err(|e| format!("region '{}': {e}", crate::limit::quote(region)))?),
            None => None,
        };
        let d = needlesim_core::RegionNeedleParams::default();
        let required = |v: Option<f64>, from: Option<f64>, key: &str| {
            v.or(from).ok_or_else(|| {
                format!(
                    "region '{}': {key} is missing (give it, or a material = \"…\" from the tissue library)",
                    crate::limit::quote(region)
                )
            })
        };
        let pick = |v: Option<f64>, from: Option<Option<f64>>, default: f64| v.or(from.flatten()).unwrap_or(default);
        Ok(Resolved {
            young_modulus_pa: required(self.young_modulus_pa, m.map(|m| m.young_modulus_pa), "young_modulus_pa")?,
            poisson_ratio: required(self.poisson_ratio, m.map(|m| m.poisson_ratio), "poisson_ratio")?,
            friction_n_per_m: pick(self.friction_n_per_m, m.map(|m| m.friction_n_per_m), d.friction_n_per_m),
            static_friction_ratio: pick(self.static_friction_ratio, m.map(|m| m.static_friction_ratio), d.static_friction_ratio),
            tip_peak_ratio: pick(self.tip_peak_ratio, m.map(|m| m.tip_peak_ratio), d.tip_peak_ratio),
            tip_peak_width_m: pick(self.tip_peak_width_m, m.map(|m| m.tip_peak_width_m), d.tip_peak_width_m),
            puncture_force_n: pick(self.puncture_force_n, m.map(|m| m.puncture_force_n), d.puncture_force_n),
            cutting_force_n: pick(self.cutting_force_n, m.map(|m| m.cutting_force_n), d.cutting_force_n),
            friction_damping_n_s_per_m2: pick(
                self.friction_damping_n_s_per_m2,
                m.map(|m| m.friction_damping_n_s_per_m2),
                d.friction_damping_n_s_per_m2,
            ),
            material_toughness_j_per_m2: m.and_then(|m| m.fracture_toughness_j_per_m2),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The library parses, holds at least the issue's materials, each with a source in the file,
    /// and its values pass the scene checks.
    #[test]
    fn the_library_holds_the_issues_materials_with_sources() {
        let names = ["prostate", "muscle", "fat", "skin", "kidney", "liver", "breast", "pvc_phantom", "gelatine_phantom"];
        for name in names {
            let t = tissue(name).unwrap();
            assert!(t.young_modulus_pa > 1e3 && t.young_modulus_pa < 1e7, "{name}");
            assert!(t.poisson_ratio > 0.0 && t.poisson_ratio < 0.5, "{name}");
            // Each material's table has its source tags in the comments.
            let section = TISSUES_TOML.split(&format!("[{name}]\n")).nth(1).unwrap().split("\n[").next().unwrap();
            assert!(section.contains("[measured]") || section.contains("[derived]"), "{name}: no source for E");
            let r = MaterialKeys { material: Some(name.into()), ..Default::default() }.resolve(name).unwrap();
            crate::check_region_needle_values(
                0,
                name,
                [r.friction_n_per_m, r.static_friction_ratio, r.tip_peak_ratio, r.tip_peak_width_m, r.puncture_force_n, r.cutting_force_n],
            )
            .unwrap();
        }
        let e = tissue("livr").unwrap_err();
        assert!(e.contains("\"livr\" is not in the tissue library (breast, fat,"), "{e}");
    }

    #[test]
    fn written_keys_override_the_material_and_defaults_fill_the_rest() {
        let liver = tissue("liver").unwrap();
        let keys = MaterialKeys { material: Some("liver".into()), young_modulus_pa: Some(7e3), ..Default::default() };
        let r = keys.resolve("organ").unwrap();
        assert_eq!(r.young_modulus_pa, 7e3);
        assert_eq!(r.poisson_ratio, liver.poisson_ratio);
        assert_eq!(r.cutting_force_n, liver.cutting_force_n.unwrap());
        assert_eq!(r.tip_peak_ratio, needlesim_core::RegionNeedleParams::default().tip_peak_ratio);
        let e = MaterialKeys { poisson_ratio: Some(0.4), ..Default::default() }.resolve("organ").unwrap_err();
        assert!(e.contains("region 'organ': young_modulus_pa is missing"), "{e}");
    }
}
