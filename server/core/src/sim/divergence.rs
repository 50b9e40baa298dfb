//! The divergence check: physical bounds derived from the scene ([`DivergenceBounds`]) and the
//! check of a solved tick against them, before anything is written out.

use crate::compliance::TissueModel;

use super::frames::Geometry;
use super::state::WorkingSet;
use super::{Divergence, SimParams};

/// Physical bounds on a step's results, derived from the scene when the simulation is built;
/// a step beyond any of them has diverged ([`SimError::Diverged`]). Deliberately generous (a
/// factor $\kappa = 100$ over what the scene could produce), so that they only catch a runaway
/// solve, never a hard but valid insertion.
///
/// With $E_{max}$ the stiffest region's Young's modulus, $t$ the slice thickness, $D$ the mesh's
/// bounding-box diagonal, $L$ the needle length, $r_c$ the capture radius, $q_{0,r}$, $h_r$,
/// $\rho_r$ region $r$'s friction per length, tip peak and static ratio, $P_r$, $C_r$ its
/// puncture and cutting forces and $\beta$ the bevel force ratio:
/// - force: $F_{max} = \kappa\,(1 + \beta)\,\big[E_{max}\,t\,(D + L) + L \max_r q_{0,r}(1 + h_r)\rho_r + \max_r \max(P_r, C_r)\big]$
///   — the first term is the force that strains the whole tissue section by one (an elastic
///   force beyond it means displacements larger than the tissue), the others every friction
///   and cutting force the needle can carry; it bounds both the base force and each node's force;
/// - torque: $\tau_{max} = F_{max}\,(L + D)$;
/// - displacement of a needle node: $u_{max} = \kappa\,(D + L)$;
/// - inserted length: $\ell_{max} = 1.5\,L + 10\,r_c$ (it can exceed $L$ only by nodes slipping
///   off behind the base);
/// - needle shape: every point within $1.01\,L$ of the base (the beam is inextensible).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DivergenceBounds {
    pub force_n: f64,
    pub torque_nm: f64,
    pub displacement_m: f64,
    pub inserted_length_m: f64,
    pub shape_radius_m: f64,
}

impl DivergenceBounds {
    /// The margin $\kappa$ over the scene's physical scales.
    pub const FACTOR: f64 = 100.0;

    /// The bounds of `params` in `model` (formulas above).
    pub fn of(model: &TissueModel, params: &SimParams) -> Self {
        let mats = model.materials();
        let e_max = mats.material_of_tri().iter().map(|m| m.young_modulus_pa).fold(0.0, f64::max);
        let t = mats.plane().thickness_m();
        let (lo, hi) = model.mesh().bounding_box_m();
        let d = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        let l = params.needle.tip_s_m();
        let friction =
            params.regions.iter().map(|r| r.friction_n_per_m * (1.0 + r.tip_peak_ratio) * r.static_friction_ratio).fold(0.0, f64::max);
        let cut = params.regions.iter().map(|r| r.puncture_force_n.max(r.cutting_force_n)).fold(0.0, f64::max);
        let beta = params.needle.flexible().map_or(0.0, |f| f.bevel_force_ratio);
        let force_n = Self::FACTOR * (1.0 + beta) * (e_max * t * (d + l) + l * friction + cut);
        Self {
            force_n,
            torque_nm: force_n * (l + d),
            displacement_m: Self::FACTOR * (d + l),
            inserted_length_m: 1.5 * l + 10.0 * params.capture_radius_m,
            shape_radius_m: 1.01 * l,
        }
    }
}

/// Checks the solved state against `bounds` before it is written out: every needle node's
/// force and displacement, the base force and torque, the inserted length and the needle's
/// shape. $O(d)$, plus the joints of a flexible needle. Returns the first quantity out of
/// bounds, its value and its bound.
pub(super) fn check(bounds: &DivergenceBounds, geo: &Geometry<'_>, ws: &WorkingSet) -> Result<(), (Divergence, f64, f64)> {
    let bd = bounds;
    let check = |what: Divergence, value: f64, bound: f64| if value <= bound { Ok(()) } else { Err((what, value, bound)) };
    let b = geo.pose.position_m();
    let mut force = [0.0; 2];
    let mut torque = 0.0;
    let mut min_s = f64::INFINITY;
    for slot in ws.slots() {
        let f = ws.solver.force_world(slot);
        let u = ws.solver.displacement_world(slot);
        check(Divergence::NodeForce, f[0].hypot(f[1]), bd.force_n)?;
        check(Divergence::Displacement, u[0].hypot(u[1]), bd.displacement_m)?;
        let x = ws.node(slot).x_kin_m();
        let p = [x[0] + u[0], x[1] + u[1]];
        min_s = min_s.min(geo.slot_frame(ws, slot).coords(p).0);
        force[0] -= f[0];
        force[1] -= f[1];
        torque += (p[0] - b[0]) * (-f[1]) - (p[1] - b[1]) * (-f[0]);
    }
    check(Divergence::Force, force[0].hypot(force[1]), bd.force_n)?;
    check(Divergence::Torque, torque.abs(), bd.torque_nm)?;
    if ws.len() > 0 {
        check(Divergence::InsertedLength, geo.s_tip_m() - min_s, bd.inserted_length_m)?;
    }
    let dist = |p: [f64; 2]| (p[0] - b[0]).hypot(p[1] - b[1]);
    if let Some(curve) = geo.curve {
        for &p in curve.points_m() {
            check(Divergence::NeedleShape, dist(p), bd.shape_radius_m)?;
        }
    }
    check(Divergence::NeedleShape, dist(geo.tip()), bd.shape_radius_m)
}
