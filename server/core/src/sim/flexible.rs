//! The flexible needle's coupling to the tissue within a step: the working-set solve with the
//! needle's lateral compliance, the bevel tip's lateral force, the shape brought to equilibrium
//! after the tick (a bounded Picard iteration), and the node frames that follow the bent shape.
//!
//! For a rigid needle the working-set solve is the plain condensed solve; every other function
//! here is only called for a flexible one.

use crate::beam::{CoupledNode, Coupling, NeedleCurve};
use crate::ids::{Axis, Slot};
use crate::mixed::Condition;
use crate::needle::{BasePose, FlexibleNeedle};

use super::SimError;
use super::frames::Geometry;
use super::state::{FlexState, NodeState, WorkingSet};

/// A frame change from the needle's bending smaller than this (rad) is not applied to a working
/// node (each one costs an $O(d^2)$ update): the lateral direction is then off by at most this
/// angle, a position error of this times the node's slip within one tick (1 nm at 10 mm/s and
/// 1 kHz), never accumulated because the values are recomputed in the node's frame every tick.
/// Rotations of the base are applied exactly, as for the rigid needle. (At 1e-5 rad a bending
/// needle turned ~19 frames a tick on the Fig. 4 path, 100 × 100: twice the step time.)
pub(super) const FRAME_TOL_RAD: f64 = 1e-4;

/// The flexible needle's scratch, sized for the working set's capacity: the coupling of the
/// working solver and of the probe solver to the needle, the probe's copy of the curve, and the
/// coupled view of the working nodes.
pub(super) struct FlexScratch {
    pub coupling: Coupling,
    pub probe_coupling: Coupling,
    pub probe_curve: NeedleCurve,
    pub nodes: Vec<CoupledNode>,
    /// The (solver update count, tick) the coupling's $G$ was computed for.
    pub g_for: Option<(u64, u64)>,
}

impl FlexScratch {
    pub fn new(f: &FlexibleNeedle, pose: BasePose, cap: usize) -> Self {
        Self {
            coupling: Coupling::new(cap),
            probe_coupling: Coupling::new(cap),
            // Built, not cloned: a clone's scratch vectors have no spare capacity.
            probe_curve: NeedleCurve::new(f, pose, cap),
            nodes: Vec::with_capacity(cap),
            g_for: None,
        }
    }
}

/// Solves the working set: directly for a rigid needle (`flex` is `None`), with the needle's
/// lateral compliance for a flexible one (recomputing $G$ when the slots, frames or shape
/// changed, or at a new `tick`).
pub(super) fn solve_working_set(ws: &mut WorkingSet, flex: Option<(&mut FlexState, &mut FlexScratch)>, s_tip_m: f64, tick: u64) {
    let Some((fx, sc)) = flex else {
        ws.solver.solve();
        return;
    };
    sc.nodes.clear();
    for nn in &ws.nodes {
        sc.nodes.push(CoupledNode { s_m: nn.s_ref_m(s_tip_m), lateral_ref_m: nn.lateral_ref_m, force_ref_local_n: nn.force_ref_local_n });
    }
    let st = ws.solver.stats();
    let version = (st.n_rotations + st.n_added + st.n_removed + st.n_rebuilds, tick);
    if sc.g_for != Some(version) {
        sc.coupling.update_compliance(&mut fx.curve, &ws.solver, &sc.nodes);
        sc.g_for = Some(version);
    }
    sc.coupling.solve(&mut ws.solver, &sc.nodes);
}

/// A bevel tip's lateral force $f_n = -s_b\,\beta\,\max(f_t, 0)$ from the tip node's current
/// axial force; returns the largest change of a prescribed value (N). As with the friction
/// ([`super::active_set::update_friction`]), the new values are applied only when that change
/// exceeds `min_change_n`: a smaller one ends the friction sweep without another solve, and the
/// conditions must stay those the last solve used, so that the state (and a snapshot of it)
/// is the solution of its own conditions.
pub(super) fn update_bevel_force(ws: &mut WorkingSet, fx: &FlexState, min_change_n: f64) -> f64 {
    if fx.bevel_ratio == 0.0 {
        return 0.0;
    }
    let (ratio, side) = (fx.bevel_ratio, fx.bevel_side);
    let is_bevel_tip =
        |ws: &WorkingSet, slot| ws.node(slot).state == NodeState::Tip && ws.solver.condition(slot, Axis::Lateral) == Condition::Force;
    let value = |ws: &WorkingSet, slot| -side * ratio * ws.solver.force_local(slot)[Axis::Axial].max(0.0);
    let mut change: f64 = 0.0;
    for slot in ws.slots() {
        if is_bevel_tip(ws, slot) {
            change = change.max((value(ws, slot) - ws.solver.prescribed_value(slot, Axis::Lateral)).abs());
        }
    }
    if change > min_change_n {
        for slot in ws.slots() {
            if is_bevel_tip(ws, slot) {
                let v = value(ws, slot);
                ws.solver.set_value(slot, Axis::Lateral, v);
            }
        }
    }
    change
}

/// Brings the shape to equilibrium with the working forces (the next solve's reference shape)
/// and returns how far (m) the displacement-prescribed needle nodes lie off it laterally.
/// A shape update that does not converge within its bound is counted in `shape_unconverged`.
pub(super) fn settle_shape(
    pose: BasePose,
    shape: &crate::needle::NeedleShape,
    ws: &mut WorkingSet,
    fx: &mut FlexState,
    sc: &mut FlexScratch,
    shape_unconverged: &mut u64,
) -> f64 {
    let s_tip = shape.tip_s_m();
    // Each node's current shaft position.
    for slot in ws.slots() {
        let nn = *ws.node(slot);
        let s = match nn.state {
            NodeState::Slipping => {
                let x = nn.x_kin_m();
                let geo = Geometry::of(shape, pose, Some(&fx.curve));
                geo.slot_frame(ws, slot).coords(x).0 + ws.solver.displacement_local(slot)[Axis::Axial]
            }
            _ => nn.s_ref_m(s_tip),
        };
        ws.node_mut(slot).s_work_m = s.min(s_tip);
    }
    // The contact forces turn with the shaft (friction along it, pressure across it).
    let (nodes, solver) = (&ws.nodes, &ws.solver);
    let loads = Slot::all(nodes.len()).map(|k| {
        let f = solver.force_local(k);
        (nodes[k.index()].s_work_m, [-f[0], -f[1]])
    });
    if !fx.curve.update_shape(loads, true) {
        *shape_unconverged += 1;
    }
    sc.g_for = None;
    // The settled shape carries these forces: the reference of the next coupled solve.
    for slot in ws.slots() {
        ws.node_mut(slot).force_ref_local_n = ws.solver.force_local(slot);
    }
    let mut gap: f64 = 0.0;
    for slot in ws.slots() {
        if ws.solver.condition(slot, Axis::Lateral) != Condition::Displacement {
            continue;
        }
        let nn = ws.node(slot);
        let x = nn.x_kin_m();
        let u = ws.solver.displacement_world(slot);
        let s = nn.s_work_m;
        let (_, lat) = fx.curve.frame_coords(s, fx.curve.tangent_angle_at(s), [x[0] + u[0], x[1] + u[1]]);
        gap = gap.max((lat - nn.lat_offset_m).abs());
    }
    gap
}

/// Turns node frames to the shape's tangent where they differ by more than [`FRAME_TOL_RAD`].
///
/// Errors: [`SimError::Mixed`] when the solver refuses a rotation.
pub(super) fn refresh_frames(curve: &NeedleCurve, ws: &mut WorkingSet, s_tip_m: f64) -> Result<(), SimError> {
    for slot in Slot::all(ws.solver.n_nodes()) {
        let a = curve.tangent_angle_at(ws.node(slot).s_ref_m(s_tip_m));
        if (a - ws.solver.angle_rad(slot)).abs() > FRAME_TOL_RAD {
            ws.solver.set_angle(slot, a)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::fixtures::{phantom, phantom_params};
    use crate::needle::{BasePose, FlexibleNeedle, NeedleShape};
    use crate::sim::{SimParams, Simulation};

    /// The flexible needle's coupling corrected by Sherman–Morrison–Woodbury after pivots gives
    /// the run that refactorises after every pivot: an oblique insertion, hold, turn and
    /// withdrawal of a soft bevel-tip needle on the 50 × 50 phantom with two thousand stick/slip
    /// changes, compared tick by tick (force, torque, tip, every needle node); the same contact
    /// events happen in both, and the reference's refactorisations after pivots are low-rank
    /// corrections in the other (refactorisations only past the bound).
    #[test]
    fn low_rank_corrected_coupling_gives_the_refactorising_run() {
        let mut f = FlexibleNeedle::gauge17_steel(0.1);
        f.flexural_rigidity_nm2 *= 0.1;
        f.bevel_force_ratio = 0.2;
        let a0 = -1.3f64;
        let base_at = |d: f64, a: f64| BasePose::new(0.04 + (d - 0.1) * a.cos(), 0.1 + (d - 0.1) * a.sin(), a);
        let params = SimParams { initial_pose: base_at(-0.005, a0), ..phantom_params(NeedleShape::Flexible(f)) };
        let model = phantom(50);
        let mut fast = Simulation::new(model.clone(), params.clone()).unwrap();
        let mut reference = Simulation::new(model, params).unwrap();
        reference.scratch.flex.as_mut().unwrap().coupling.set_max_low_rank(0);
        let mut poses: Vec<BasePose> = (0..=3000).map(|k| base_at(-0.005 + 0.045 * k as f64 / 3000.0, a0)).collect();
        poses.extend(std::iter::repeat_n(base_at(0.04, a0), 200));
        poses.extend((0..=400).map(|k| base_at(0.04, a0 + 0.08 * (k as f64 / 400.0 * std::f64::consts::PI).sin())));
        poses.extend((0..=3000).map(|k| base_at(0.04 - 0.045 * k as f64 / 3000.0, a0)));
        let (mut worst_f, mut worst_x): (f64, f64) = (0.0, 0.0);
        for (k, p) in poses.iter().enumerate() {
            let (a, b) = (fast.step(*p).unwrap().clone(), reference.step(*p).unwrap().clone());
            assert_eq!((a.n_stuck, a.n_slipping, a.n_tip), (b.n_stuck, b.n_slipping, b.n_tip), "tick {k}");
            let f_scale = b.force_n[0].hypot(b.force_n[1]).max(1e-3);
            let mut df = (a.force_n[0] - b.force_n[0]).hypot(a.force_n[1] - b.force_n[1]) / f_scale;
            df = df.max((a.torque_nm - b.torque_nm).abs() / (f_scale * 0.1));
            let mut dx = (a.tip_m[0] - b.tip_m[0]).hypot(a.tip_m[1] - b.tip_m[1]);
            for (na, nb) in a.needle_nodes.iter().zip(&b.needle_nodes) {
                assert_eq!(na.node_idx, nb.node_idx, "tick {k}");
                df = df.max((na.force_n[0] - nb.force_n[0]).hypot(na.force_n[1] - nb.force_n[1]) / f_scale);
                dx = dx.max((na.position_m[0] - nb.position_m[0]).hypot(na.position_m[1] - nb.position_m[1]));
            }
            (worst_f, worst_x) = (worst_f.max(df), worst_x.max(dx));
            // Forces relative to the needle's total, positions relative to the 0.1 m phantom: the
            // coupled systems' condition numbers reach 1e5, so single solves differ by up to
            // 1e-11 (measured: 4e-11 and 3e-14 m at worst over the run).
            assert!(df < 1e-9 && dx < 1e-11 * 0.1, "tick {k}: force difference {df:e} (relative), position difference {dx:e} m");
            fast.prefetch_columns(16).unwrap();
            reference.prefetch_columns(16).unwrap();
        }
        let (sa, sb) = (fast.stats(), reference.stats());
        assert_eq!((sa.stick_to_slip, sa.slip_to_stick, sa.captures), (sb.stick_to_slip, sb.slip_to_stick, sb.captures));
        let (ca, cb) = (fast.coupling_stats().unwrap(), reference.coupling_stats().unwrap());
        println!("worst relative force difference {worst_f:e}, position {worst_x:e} m; {sa:?}; corrected {ca:?}, reference {cb:?}");
        assert!(sa.stick_to_slip + sa.slip_to_stick > 300, "{sa:?}");
        // A pivot-driven factorisation of the reference is a correction here, a factorisation past
        // the bound, or nothing when the pivots cancelled; the others follow the shape, refreshed
        // every tick and shape pass.
        assert!(ca.low_rank_updates > 300 && ca.factorisations + ca.low_rank_updates <= cb.factorisations, "{ca:?} vs {cb:?}");
        assert_eq!(cb.low_rank_updates, 0);
    }
}
