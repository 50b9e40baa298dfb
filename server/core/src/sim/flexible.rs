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

/// Largest lateral distance (m) between a needle node and the settled needle shape left without
/// another solve on the new shape (1 µm: a thousandth of a typical capture radius).
pub(super) const SHAPE_GAP_TOL_M: f64 = 1e-6;

/// Bound on the shape passes (solve, settle) per tick.
pub(super) const SHAPE_PASSES: usize = 4;

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
/// axial force; returns the largest change of a prescribed value (N).
pub(super) fn update_bevel_force(ws: &mut WorkingSet, fx: &FlexState) -> f64 {
    if fx.bevel_ratio == 0.0 {
        return 0.0;
    }
    let (ratio, side) = (fx.bevel_ratio, fx.bevel_side);
    let mut change: f64 = 0.0;
    for slot in ws.slots() {
        if ws.node(slot).state == NodeState::Tip && ws.solver.condition(slot, Axis::Lateral) == Condition::Force {
            let value = -side * ratio * ws.solver.force_local(slot)[Axis::Axial].max(0.0);
            change = change.max((value - ws.solver.prescribed_value(slot, Axis::Lateral)).abs());
            ws.solver.set_value(slot, Axis::Lateral, value);
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
                let x = nn.x_ref_m;
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
        let x = nn.x_ref_m;
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
