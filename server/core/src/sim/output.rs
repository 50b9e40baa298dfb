//! Stage 7 of a step and what the simulation reports: the per-tick output ([`StepOutput`],
//! owned by the simulation and rewritten in place), the life-long counters ([`SimStats`]), and
//! the static problem of the last step ([`StateSnapshot`]).

use crate::compliance::ComplianceCache;
use crate::contact::ContactPoint;
use crate::ids::{Axis, Slot};
use crate::mixed::Condition;
use crate::needle::BasePose;

use super::capture::node_displacement;
use super::frames::Geometry;
use super::param_limits;
use super::state::{NodeState, State, WorkingSet};
use super::{Ctx, SimParams};

/// One needle contact (a node, or a material point) in a step's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeedleNodeOut {
    /// The node, or for a material point the node of its triangle with the largest weight
    /// ([`ContactPoint::nearest_node`]): for clients that know only nodes.
    pub node_idx: usize,
    /// Where the contact sits in the mesh.
    pub contact: ContactPoint,
    /// Its reference (undeformed) position.
    pub reference_m: [f64; 2],
    pub state: NodeState,
    /// Deformed position.
    pub position_m: [f64; 2],
    /// Force of the needle on the tissue node, world frame.
    pub force_n: [f64; 2],
    /// Arc length along the shaft.
    pub s_m: f64,
}

/// A target in a step's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetOut {
    /// Current (displaced) centre.
    pub position_m: [f64; 2],
    /// Distance from the tip to the centre.
    pub distance_m: f64,
    /// Whether the tip has been within the radius at any tick so far.
    pub hit: bool,
}

/// The result of a step. Owned by the simulation and reused: reading it allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct StepOutput {
    pub tick: u64,
    pub time_s: f64,
    /// The pose applied (after clamping).
    pub base: BasePose,
    /// Force of the tissue on the needle base (world frame), N.
    pub force_n: [f64; 2],
    /// Torque of the tissue on the needle about the base, N·m (counter-clockwise positive).
    pub torque_nm: f64,
    /// Axial component $t\cdot F$ (negative when the tissue resists insertion).
    pub force_axial_n: f64,
    /// Lateral component $n\cdot F$.
    pub force_lateral_n: f64,
    pub tip_m: [f64; 2],
    /// Direction of the needle at the tip (the base angle for a rigid needle).
    pub tip_angle_rad: f64,
    /// The needle's shape: base, joints, tip (two points for a rigid needle).
    pub shape_m: Vec<[f64; 2]>,
    /// Bevel side $s_b$ (+1 towards the base frame's $+n$, −1 towards $-n$; 0 for a symmetric tip).
    pub bevel_side: f64,
    /// Length of shaft between the most proximal needle node and the tip (0 outside the tissue).
    pub inserted_length_m: f64,
    pub n_stuck: usize,
    pub n_slipping: usize,
    pub n_tip: usize,
    pub needle_nodes: Vec<NeedleNodeOut>,
    pub targets: Vec<TargetOut>,
    /// Nodes ahead of the tip whose compliance columns are not cached yet, nearest first; at
    /// most [`param_limits::MAX_APPROACHING`] (the rest counted in
    /// [`SimStats::approaching_overflow`]).
    pub approaching: Vec<usize>,
    /// Nodes whose compliance columns this step evicted from its cache (at most
    /// [`param_limits::EVICTION_SWEEP_PER_TICK`]): a live loop forgets that it requested them
    /// and tells whoever keeps copies (the renderer's) to drop them.
    pub evicted: Vec<usize>,
    pub active_set_iterations: usize,
    /// Every stick/slip iteration of the tick ended with no condition left to change. `false`
    /// when one stopped at its cap ([`Self::active_set_capped`]) or at the tick's update budget
    /// ([`SimStats::budget_exhausted_ticks`]): the output is then the solution of the last
    /// pass's conditions, some of which the next tick may still change.
    pub converged: bool,
    /// The stick/slip iteration stopped at [`super::SimParams::max_active_set_iterations`]
    /// passes with conditions still changing (counted in [`SimStats::active_set_capped_ticks`]).
    pub active_set_capped: bool,
    /// Flexible needle: the shape passes stopped at their cap
    /// ([`super::param_limits::SHAPE_PASSES`]) with the settled shape still more than
    /// [`super::param_limits::SHAPE_GAP_TOL_M`] off the shape the tissue was solved on (counted
    /// in [`SimStats::shape_capped_ticks`]); always `false` for a rigid needle.
    pub shape_passes_capped: bool,
    /// The commanded pose was clamped this tick.
    pub clamped: bool,
    /// Nanoseconds spent in each stage of the step ([`super::STAGE_NAMES`]), when a benchmark
    /// injected a clock ([`super::Simulation::set_stage_clock`]); zero otherwise.
    pub stage_ns: [u64; super::N_STAGES],
}

/// Counters over the simulation's life ([`super::Simulation::stats`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SimStats {
    pub ticks: u64,
    /// Columns a step had to compute itself (the prefetch did not have them ready;
    /// [`super::SimParams::columns_in_step`]).
    pub column_misses: u64,
    /// Ticks at which a new contact waited for its columns (admitted at a later tick; without
    /// [`super::SimParams::columns_in_step`]).
    pub column_deferrals: u64,
    /// Nodes whose cached compliance columns were evicted: unused for
    /// [`super::param_limits::COLUMN_KEEP_S`], or the least recently used when a column was
    /// inserted into a full cache ([`super::SimParams::max_cached_nodes`]).
    pub columns_evicted: u64,
    /// Columns inserted while every cached node was in use, so the cache grew past
    /// [`super::SimParams::max_cached_nodes`] (not expected: the bound covers a full working
    /// set and the lookahead).
    pub cache_over_cap: u64,
    /// Material points dropped because their conditions depended on the other points' (a
    /// singular pivot; not expected with the spacing rule of [`super::ContactModel`]).
    pub dependent_points: u64,
    /// Contacts taken as points although the contact model spreads them over a width: the
    /// patch touched more than [`crate::contact::MAX_TERMS`] nodes (a needle wider than about
    /// two elements) or had no length inside the mesh.
    pub patch_fallbacks: u64,
    pub clamped_ticks: u64,
    pub rejected_poses: u64,
    /// Ticks whose output is not converged ([`StepOutput::converged`] false): the stick/slip
    /// iteration hit its cap or the tick's update budget.
    pub unconverged_ticks: u64,
    /// Ticks whose stick/slip iteration stopped at
    /// [`super::SimParams::max_active_set_iterations`] passes with conditions still changing
    /// ([`StepOutput::active_set_capped`]). Zero in the shipped examples.
    pub active_set_capped_ticks: u64,
    /// Flexible needle: ticks whose shape passes stopped at
    /// [`super::param_limits::SHAPE_PASSES`] with the shape still off by more than
    /// [`super::param_limits::SHAPE_GAP_TOL_M`] ([`StepOutput::shape_passes_capped`]). Zero in
    /// the shipped examples.
    pub shape_capped_ticks: u64,
    pub captures: u64,
    pub releases: u64,
    pub punctures: u64,
    pub stick_to_slip: u64,
    pub slip_to_stick: u64,
    /// Captures dropped because the working set was full (`max_needle_nodes`).
    pub capacity_drops: u64,
    /// Nodes the tip passed that did not fit one tick's capture list
    /// ([`param_limits::MAX_CAPTURES_PER_TICK`]); left for later ticks.
    pub capture_overflow: u64,
    /// Approaching nodes not reported because [`StepOutput::approaching`] was full
    /// ([`param_limits::MAX_APPROACHING`]).
    pub approaching_overflow: u64,
    /// Spatial-grid queries that outgrew their reserved buffer
    /// ([`param_limits::NEAR_TIP_CANDIDATES`]): each one allocated inside a step.
    pub candidate_growths: u64,
    /// Ticks whose stick/slip iteration stopped at the per-tick update budget
    /// ([`param_limits::MAX_UPDATES_PER_TICK`]).
    pub budget_exhausted_ticks: u64,
    /// Flexible needle: loads or points the needle curve had to leave out past its capacity
    /// (the working set's; never expected).
    pub curve_capacity_drops: u64,
    /// Flexible needle: shape updates that did not converge within their iteration bound.
    pub shape_unconverged: u64,
    /// Bevel flips commanded.
    pub bevel_flips: u64,
    /// Extra solves of the working set on a settled needle shape (flexible needle).
    pub shape_passes: u64,
    /// Contacts whose compliance relation was checked against the hybrid matrix's solution
    /// (`drift.rs`, one every [`param_limits::HYBRID_CHECK_EVERY_TICKS`] ticks).
    pub hybrid_checks: u64,
    /// Rebuilds of the hybrid matrix after a check found it drifted past
    /// [`param_limits::HYBRID_DRIFT_TOL`] (not expected; each one $O(d^3)$ and allocating).
    pub hybrid_rebuilds: u64,
    /// Rebuilds that the solver refused (a contact's columns missing, or $C_{PP}$ not positive
    /// definite); the old hybrid matrix stays in use.
    pub hybrid_rebuild_failures: u64,
}

impl SimStats {
    /// Everything that did not fit a fixed capacity, summed: captures past the working set or
    /// the tick's capture list, approaching nodes past the list, curve loads past capacity, and
    /// grid queries that grew their buffer. Zero in a run whose limits were never reached.
    pub fn overflows(&self) -> u64 {
        self.capacity_drops + self.capture_overflow + self.approaching_overflow + self.curve_capacity_drops + self.candidate_growths
    }
}

/// One needle contact's conditions in its frame, as in the exchange format's
/// `prescribed_local` (a node) or `points` (a material point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalCondition {
    /// The node, or the material point's nearest node ([`NeedleNodeOut::node_idx`]).
    pub node_idx: usize,
    /// Where the contact sits; for a material point its reference position is `reference_m`.
    pub contact: ContactPoint,
    pub reference_m: [f64; 2],
    /// The world force prescribed on its force-kind components (friction, a bevel's lateral
    /// force), N.
    pub load_n: [f64; 2],
    pub angle_rad: f64,
    pub ut_m: Option<f64>,
    pub un_m: Option<f64>,
}

/// The static problem of the last step (see [`super::Simulation::snapshot`]).
#[derive(Debug, Clone, PartialEq)]
pub struct StateSnapshot {
    pub conditions: Vec<LocalCondition>,
    pub needle_nodes: Vec<NeedleNodeOut>,
}

impl StateSnapshot {
    /// The loads of node contacts as nodal forces (node, world force N), for a nodal static
    /// problem ([`crate::StaticProblem`]); material points' loads are in their conditions.
    pub fn node_loads_n(&self) -> Vec<(usize, [f64; 2])> {
        self.conditions.iter().filter(|c| c.contact.as_node().is_some() && c.load_n != [0.0; 2]).map(|c| (c.node_idx, c.load_n)).collect()
    }
}

impl StepOutput {
    /// The output before the first step: the needle at `params.initial_pose`, every list
    /// allocated to its capacity (needle nodes: the working set's; approaching:
    /// [`param_limits::MAX_APPROACHING`]; shape: the curve's joints).
    pub(super) fn initial(params: &SimParams, geo: &Geometry<'_>, bevel_side: f64) -> Self {
        let n_shape = params.needle.flexible().map_or(2, |f| f.n_links + 1);
        let mut shape_m = Vec::with_capacity(n_shape);
        write_shape(geo, &mut shape_m);
        StepOutput {
            shape_m,
            tip_angle_rad: params.initial_pose.theta_rad,
            bevel_side,
            needle_nodes: Vec::with_capacity(params.max_needle_nodes),
            targets: Vec::with_capacity(params.targets.len()),
            approaching: Vec::with_capacity(param_limits::MAX_APPROACHING),
            evicted: Vec::with_capacity(param_limits::EVICTION_SWEEP_PER_TICK),
            base: params.initial_pose,
            tip_m: geo.tip(),
            converged: true,
            active_set_capped: false,
            shape_passes_capped: false,
            ..Default::default()
        }
    }
}

/// The needle's shape points: the curve's joints, or base and tip of a rigid needle.
fn write_shape(geo: &Geometry<'_>, shape_m: &mut Vec<[f64; 2]>) {
    shape_m.clear();
    match geo.curve {
        Some(c) => shape_m.extend_from_slice(c.points_m()),
        None => {
            shape_m.push(geo.pose.position_m());
            shape_m.push(geo.shape.tip_m(&geo.pose));
        }
    }
}

/// Stage 7: writes the solved tick into `out` (forces $F = -\sum_i f_i$ and torque
/// $\tau = \sum_i (p_i - b)\times(-f_i)$ on the base, node states, shape, tip, targets) and
/// keeps each node's world force, displacement, arc length and reference force for the next
/// tick. Allocates nothing: every list has its capacity from [`StepOutput::initial`].
pub(super) fn write_output(ctx: &Ctx<'_>, st: &mut State, out: &mut StepOutput, iterations: usize, converged: bool, clamped: bool) {
    let nodes_m = ctx.model.mesh().nodes_m();
    let geo = Geometry::new(ctx.params, st.pose, st.flex.as_ref());
    let pose = st.pose;
    let b = pose.position_m();
    let (t, n) = (pose.axis(), pose.normal());
    let mut force = [0.0; 2];
    let mut torque = 0.0;
    let mut min_s = f64::INFINITY;
    out.needle_nodes.clear();
    let (mut n_stuck, mut n_slip, mut n_tip) = (0, 0, 0);
    let ws = &mut st.ws;
    for slot in ws.slots() {
        let k = slot.index();
        let f = ws.solver.force_world(slot);
        let shift = ws.node(slot).visc.shift_m;
        let u_solver = ws.solver.displacement_world(slot);
        // The true displacement (the solver's is measured from the shifted reference).
        let u = [u_solver[0] + shift[0], u_solver[1] + shift[1]];
        ws.f_world[k] = f;
        ws.u_world[k] = u;
        let frame = geo.slot_frame(ws, slot);
        let f_local = ws.solver.force_local(slot);
        let nn = ws.node_mut(slot);
        let x = nn.x_ref_m;
        let p = [x[0] + u[0], x[1] + u[1]];
        let (s, _) = frame.coords(p);
        nn.s_prev_m = s;
        nn.force_ref_local_n = f_local;
        min_s = min_s.min(s);
        force[0] -= f[0];
        force[1] -= f[1];
        torque += (p[0] - b[0]) * (-f[1]) - (p[1] - b[1]) * (-f[0]);
        match nn.state {
            NodeState::Stuck => n_stuck += 1,
            NodeState::Slipping => n_slip += 1,
            NodeState::Tip => n_tip += 1,
        }
        out.needle_nodes.push(NeedleNodeOut {
            node_idx: nn.contact.nearest_node().index(),
            contact: nn.contact,
            reference_m: x,
            state: nn.state,
            position_m: p,
            force_n: f,
            s_m: s,
        });
    }
    write_shape(&geo, &mut out.shape_m);
    out.tip_angle_rad = geo.curve.map_or(pose.theta_rad, |c| c.tip_angle_rad());
    let tip = geo.tip();
    out.bevel_side = st.flex.as_ref().map_or(0.0, |f| f.reported_bevel_side());
    out.targets.clear();
    for (k, tg) in ctx.setup.targets.iter().enumerate() {
        let mut pos = [0.0; 2];
        for (&node, &w) in tg.nodes.iter().zip(&tg.bary) {
            let x = nodes_m[node];
            let u = node_displacement(&st.ws, &st.cache, crate::ids::NodeIdx(node));
            pos[0] += w * (x[0] + u[0]);
            pos[1] += w * (x[1] + u[1]);
        }
        let distance_m = (pos[0] - tip[0]).hypot(pos[1] - tip[1]);
        let hit = st.target_hit[k] || distance_m <= tg.radius_m;
        st.target_hit[k] = hit;
        out.targets.push(TargetOut { position_m: pos, distance_m, hit });
    }
    out.tick = st.tick;
    out.time_s = st.tick as f64 / ctx.params.tick_rate_hz;
    out.base = pose;
    out.force_n = force;
    out.torque_nm = torque;
    out.force_axial_n = t[0] * force[0] + t[1] * force[1];
    out.force_lateral_n = n[0] * force[0] + n[1] * force[1];
    out.tip_m = tip;
    out.inserted_length_m = if st.ws.len() == 0 { 0.0 } else { (geo.s_tip_m() - min_s).max(0.0) };
    out.n_stuck = n_stuck;
    out.n_slipping = n_slip;
    out.n_tip = n_tip;
    out.active_set_iterations = iterations;
    out.converged = converged;
    out.clamped = clamped;
}

/// The static problem the last step solved (see [`super::Simulation::snapshot`]). Allocates.
pub(super) fn snapshot(ws: &WorkingSet, out: &StepOutput) -> StateSnapshot {
    let mut conditions = Vec::with_capacity(ws.len());
    for slot in ws.slots() {
        let nn = ws.node(slot);
        let angle = ws.solver.angle_rad(slot);
        let val = |a| (ws.solver.condition(slot, a) == Condition::Displacement).then(|| ws.solver.prescribed_value(slot, a));
        let mut v = [0.0; 2];
        for axis in Axis::BOTH {
            if ws.solver.condition(slot, axis) == Condition::Force {
                v[axis] = ws.solver.prescribed_value(slot, axis);
            }
        }
        conditions.push(LocalCondition {
            node_idx: nn.contact.nearest_node().index(),
            contact: nn.contact,
            reference_m: nn.x_ref_m,
            load_n: crate::mixed::local_to_world(v, angle),
            angle_rad: angle,
            ut_m: val(Axis::Axial),
            un_m: val(Axis::Lateral),
        });
    }
    StateSnapshot { conditions, needle_nodes: out.needle_nodes.clone() }
}

/// The displacement of every DOF from the working forces last written out, $O(n\,d)$.
pub(super) fn displacement_field_into(ws: &WorkingSet, cache: &ComplianceCache, out: &mut [f64]) {
    let forces = Slot::all(ws.len()).flat_map(|k| {
        let f = ws.f_world[k.index()];
        ws.node(k).contact.terms().map(move |(j, w)| (j.index(), [w * f[0], w * f[1]]))
    });
    cache.displacement_from_forces_into(forces, out).expect("working contacts are cached");
}
