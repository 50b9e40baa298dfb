//! The needle–tissue insertion simulation: one [`Simulation::step`] per haptic tick, from the
//! commanded base pose to forces, needle-node states, tip and targets.
//!
//! A step, in order (each stage a function in its own file, taking the pieces of state it reads
//! and writes explicitly):
//! 1. **Pose** (`frames.rs`): reject non-finite poses, clamp jumps larger than the configured
//!    step.
//! 2. **Frames and values** (`frames.rs`): rotate every needle node's frame with the needle
//!    (section 4.2) and set its prescribed values: lateral $u_n = -n\cdot(X-b)$ keeps the node
//!    on the shaft, axial $u_t = s_a - t\cdot(X-b)$ holds a stuck node at its shaft point $s_a$
//!    (the tip node at $s = L$).
//! 3. **Release** (`capture.rs`): shaft nodes the tip has withdrawn past leave the working set.
//! 4. **Capture** (`capture.rs`), by the [`ContactModel`]: with material points (the default of
//!    scenes), when no contact is carried by the tip and the tip has advanced the spacing beyond
//!    the most distal one, the material point the tip passed last tick becomes the tip's
//!    contact, wherever it lies in its triangle ([`crate::contact`]); with the paper's node
//!    capture, nodes near the tip (spatial grid, never a scan) whose deformed position the tip
//!    passed within the capture radius become needle nodes, the most distal one carried by the
//!    tip when none is. The tip's contact is pushed until its axial reaction exceeds the
//!    region's puncture force (or its cutting force inside a region). With energy-based cutting
//!    ([`crate::RegionNeedleParams::toughness_cutting_force_n`]) only a surface or a region
//!    boundary is punctured so; inside a region new points join as slipping shaft contacts.
//!    A contact whose columns are not cached is admitted a tick later unless
//!    [`SimParams::columns_in_step`].
//! 5. **Friction** (`active_set.rs`): each shaft node gets the integral of the friction
//!    distribution over its tributary segment (see [`crate::needle`]); with energy-based
//!    cutting the most distal one also carries the cutting force $G_c w$ while the tip advances.
//! 6. **Active set** (`active_set.rs`): solve; stuck nodes whose axial force exceeds static
//!    friction slip, slipping nodes whose relative motion stopped or reversed stick, the tip node
//!    punctures or, when it no longer pushes, lets go; repeat (bounded), each change an
//!    $O(d^2)$ update.
//! 7. **Divergence check and output** (`divergence.rs`, `output.rs`): the solved state is checked
//!    against [`DivergenceBounds`], then written: force and torque on the needle base,
//!    $F = -\sum_i f_i$, $\tau = \sum_i (p_i - b)\times(-f_i)$, node states, tip, targets.
//!
//! A flexible needle ([`crate::beam`], `flexible.rs`) changes stages 1, 2, 4, 6 and 7: frames
//! follow the bent shape's local tangent, prescribed values put nodes on the bent shape, the tip
//! captures along its own tangent, every solve of the working set includes the needle's lateral
//! compliance (one small dense solve), and after the tick the shape is brought to equilibrium
//! with the new forces. A bevel tip's node carries a lateral force $-s_b\beta f_t$ instead of a
//! lateral displacement, so the tip cuts sideways and the needle curves towards its bevel side.
//!
//! The tissue factorisation is never touched: compliance columns come from the cache, computed
//! ahead of time for the nodes the tip approaches ([`Simulation::prefetch_columns`]), and counted
//! when a step has to compute one itself.
//!
//! The state is split three ways, as faer splits a solve into a symbolic part done once and a
//! numeric part with scratch sized up front:
//! - `setup.rs`: what [`Simulation::new`] derives once and never changes (grid, boundary,
//!   regions, targets, divergence bounds);
//! - `state.rs`: what one tick hands to the next (pose, working set and solver, column cache,
//!   needle shape, counters);
//! - `scratch.rs`: buffers sized up front from the parameters, droppable;
//!
//! plus the per-tick [`StepOutput`], rewritten in place. Parameters and their named capacity
//! limits ([`param_limits`]) are in `params.rs`; the stiffness Jacobian (probe solves and a
//! directional derivative) in `jacobian.rs`.

mod active_set;
mod capture;
mod divergence;
mod drift;
mod error;
mod flexible;
mod frames;
mod jacobian;
mod output;
mod params;
mod scratch;
mod setup;
mod state;
mod unconverged;

use std::sync::Arc;

use crate::beam::NeedleCurve;
use crate::compliance::{ComplianceCache, TissueModel};
use crate::mixed::MixedSolver;
use crate::needle::BasePose;

pub use crate::viscous::Viscoelastic;
pub use divergence::DivergenceBounds;
pub use error::{Divergence, SimError};
pub use output::{LocalCondition, NeedleNodeOut, SimStats, StateSnapshot, StepOutput, TargetOut};
pub use params::{ContactModel, SimParams, TargetParams, param_limits};
pub use unconverged::Unconverged;

pub use state::NodeState;

use frames::Geometry;
use scratch::Scratch;
use setup::Setup;
use state::{Diverged, FlexState, State, WorkingSet};

/// The read-only inputs every stage may use.
#[derive(Clone, Copy)]
struct Ctx<'a> {
    model: &'a TissueModel,
    params: &'a SimParams,
    setup: &'a Setup,
}

impl From<Diverged> for SimError {
    fn from(d: Diverged) -> Self {
        SimError::Diverged { tick: d.tick, what: d.what, value: d.value, bound: d.bound }
    }
}

/// The simulation of one needle in one tissue: the facade over the stages, owning the set-up,
/// the persistent state, the scratch and the last output.
pub struct Simulation {
    model: Arc<TissueModel>,
    params: SimParams,
    setup: Setup,
    state: State,
    scratch: Scratch,
    out: StepOutput,
    /// The clock [`StepOutput::stage_ns`] is read from (none: the stages are not timed).
    stage_clock: Option<StageClock>,
}

/// A monotonic clock in nanoseconds, injected by a benchmark to time the step's stages
/// ([`Simulation::set_stage_clock`]); the core itself reads no clock.
pub type StageClock = fn() -> u64;

/// The stages [`StepOutput::stage_ns`] reports, in step order.
pub const STAGE_NAMES: [&str; N_STAGES] = [
    "pose and frames",
    "release",
    "capture",
    "friction and active set",
    "flexible shape passes",
    "divergence check",
    "output",
    "cache sweep",
];
/// Number of timed stages.
pub const N_STAGES: usize = 8;

/// Records the end of stage `k` into `out[k]` as the time since `*last`.
#[inline]
fn lap(clock: Option<StageClock>, last: &mut u64, out: &mut [u64; N_STAGES], k: usize) {
    if let Some(now) = clock {
        let t = now();
        out[k] = t.saturating_sub(*last);
        *last = t;
    }
}

impl Simulation {
    /// Validates the parameters against the model and sets up the simulation (spatial grid,
    /// boundary nodes, target locations, all per-step storage).
    ///
    /// Errors: [`SimError::InvalidParams`] when a parameter is out of range
    /// ([`SimParams::validate`]), the region parameters do not match the mesh
    /// ([`SimParams::validate_for_mesh`]), or a target lies outside the mesh.
    pub fn new(model: Arc<TissueModel>, params: SimParams) -> Result<Self, SimError> {
        params.validate()?;
        params.validate_for_mesh(model.mesh())?;
        let setup = Setup::new(&model, &params)?;
        let n_nodes = model.mesh().n_nodes();
        let cap = params.max_needle_nodes;
        let mut cache = ComplianceCache::new(n_nodes);
        cache.reserve(cap + 16);
        let flex = params.needle.flexible().map(|f| FlexState::new(f, params.initial_pose, cap));
        let geo = Geometry::new(&params, params.initial_pose, flex.as_ref());
        let out = StepOutput::initial(&params, &geo, flex.as_ref().map_or(0.0, FlexState::reported_bevel_side));
        let state = State {
            pose: params.initial_pose,
            ws: WorkingSet::new(n_nodes, cap),
            cache,
            flex,
            last_tip_region: None,
            target_hit: vec![false; params.targets.len()],
            tick: 0,
            stats: SimStats::default(),
            diverged: None,
            updates_at_tick_start: 0,
            columns_lru: state::ColumnLru::new(n_nodes),
            drift: crate::drift::DriftCheck::new::<2>(cap),
        };
        let scratch = Scratch::new(&model, &params);
        Ok(Self { model, params, setup, state, scratch, out, stage_clock: None })
    }

    /// The tissue model.
    pub fn model(&self) -> &Arc<TissueModel> {
        &self.model
    }
    /// The parameters.
    pub fn params(&self) -> &SimParams {
        &self.params
    }
    /// Counters over the simulation's life (including what overflowed a capacity:
    /// [`SimStats::overflows`]).
    pub fn stats(&self) -> SimStats {
        let mut s = self.state.stats;
        s.curve_capacity_drops = self.state.flex.as_ref().map_or(0, |f| f.curve.capacity_drops)
            + self.scratch.flex.as_ref().map_or(0, |f| f.probe_curve.capacity_drops);
        s
    }
    /// The working-set solver (for its update counters).
    pub fn solver(&self) -> &MixedSolver {
        &self.state.ws.solver
    }
    /// The flexible needle's coupling counters, dense factorisations against low-rank
    /// corrections (diagnostics; `None` for a rigid needle; they restart with a new scratch).
    pub fn coupling_stats(&self) -> Option<crate::beam::CouplingStats> {
        self.scratch.flex.as_ref().map(|f| f.coupling.stats())
    }
    /// The current base pose.
    pub fn pose(&self) -> BasePose {
        self.state.pose
    }
    /// The last step's output.
    pub fn output(&self) -> &StepOutput {
        &self.out
    }
    /// The compliance cache.
    pub fn cache(&self) -> &ComplianceCache {
        &self.state.cache
    }

    /// Computes (allocating, outside any step) the compliance columns of up to `max_nodes` of
    /// the nodes the last step reported as approaching. Returns how many it computed.
    ///
    /// Errors: [`SimError::Tissue`] when a column solve fails (columns computed before it stay).
    pub fn prefetch_columns(&mut self, max_nodes: usize) -> Result<usize, SimError> {
        let cs = &mut self.scratch.capture;
        let mut n = 0;
        for k in 0..self.out.approaching.len() {
            let node = self.out.approaching[k];
            if n == max_nodes {
                break;
            }
            if !self.state.cache.contains(node) {
                self.model.compliance_columns_into(node, &mut cs.column_buf, &mut cs.columns)?;
                make_room(&self.params, &mut self.state);
                self.state.cache.insert(node, &cs.column_buf);
                n += 1;
            }
        }
        Ok(n)
    }

    /// Stores columns computed by a worker ([`TissueModel::compliance_columns_into`]); in a full
    /// cache they replace the least recently used node's ([`SimParams::max_cached_nodes`]), which
    /// is returned.
    pub fn insert_columns(&mut self, node_idx: usize, columns: &[f64]) -> Option<usize> {
        let evicted = if self.state.cache.contains(node_idx) { None } else { make_room(&self.params, &mut self.state) };
        self.state.cache.insert(node_idx, columns);
        evicted
    }

    /// Stores columns handed over as an owned box, allocating no column storage (for the
    /// real-time thread): [`Inserted::spare`] is the box not kept, to be dropped off the
    /// real-time thread; in a full cache the columns replace the least recently used node's
    /// ([`Inserted::evicted`]; [`SimParams::max_cached_nodes`]).
    pub fn insert_columns_owned(&mut self, node_idx: usize, columns: Box<[f64]>) -> Inserted {
        let evicted = if self.state.cache.contains(node_idx) { None } else { make_room(&self.params, &mut self.state) };
        Inserted { spare: self.state.cache.insert_owned(node_idx, columns), evicted }
    }

    /// Reserves bookkeeping room in the column cache for `n_nodes` more nodes.
    pub fn reserve_cached_nodes(&mut self, n_nodes: usize) {
        self.state.cache.reserve(n_nodes);
    }

    /// The bevel side $s_b$ (0 for a symmetric tip).
    pub fn bevel_side(&self) -> f64 {
        self.state.flex.as_ref().map_or(0.0, FlexState::reported_bevel_side)
    }

    /// Turns the needle 180° about its axis: the bevel faces the other side from the next step
    /// on. Returns the new side (0 and no change for a symmetric tip or a rigid needle).
    pub fn flip_bevel(&mut self) -> f64 {
        if let Some(f) = self.state.flex.as_mut()
            && f.bevel_ratio > 0.0
        {
            f.bevel_side = -f.bevel_side;
            self.state.stats.bevel_flips += 1;
        }
        self.out.bevel_side = self.bevel_side();
        self.out.bevel_side
    }

    /// The needle's current shape (joint positions base to tip), if it is flexible.
    pub fn needle_curve(&self) -> Option<&NeedleCurve> {
        self.state.flex.as_ref().map(|f| &f.curve)
    }

    /// The bounds a step's results are checked against.
    pub fn divergence_bounds(&self) -> DivergenceBounds {
        self.setup.bounds
    }

    /// Advances one tick towards the commanded base pose, stage by stage (module docs).
    ///
    /// Errors: [`SimError::NonFinitePose`] for a pose with a NaN or infinite component (the
    /// state is unchanged); [`SimError::Tissue`] or [`SimError::Mixed`] when a column or a
    /// solver update fails mid-tick; [`SimError::Diverged`] when the results are not finite or
    /// exceed [`DivergenceBounds`] — the output is then not written, and every later step fails
    /// the same way (checked in $O(d)$, plus the shape's joints for a flexible needle).
    pub fn step(&mut self, commanded: BasePose) -> Result<&StepOutput, SimError> {
        let Self { model, params, setup, state: st, scratch: sc, out, stage_clock } = self;
        let ctx = Ctx { model, params, setup };
        let clock = *stage_clock;
        let mut t_last = clock.map_or(0, |now| now());
        let mut stage_ns = [0u64; N_STAGES];
        if let Some(d) = st.diverged {
            return Err(d.into());
        }
        if !commanded.is_finite() {
            st.stats.rejected_poses += 1;
            return Err(SimError::NonFinitePose { tick: st.tick, x_m: commanded.x_m, y_m: commanded.y_m, theta_rad: commanded.theta_rad });
        }
        let s_tip = setup.s_tip_m;
        let prev_tip = Geometry::new(params, st.pose, st.flex.as_ref()).tip();
        let us = st.ws.solver.stats();
        st.updates_at_tick_start = us.n_pivots + us.n_rotations + us.n_added + us.n_removed;
        let pose_before = st.pose;
        let clamped = frames::apply_pose(params, commanded, &mut st.pose, &mut st.ws, st.flex.as_mut())?;
        let t_axis = st.pose.axis();
        let advance_m = (st.pose.x_m - pose_before.x_m) * t_axis[0] + (st.pose.y_m - pose_before.y_m) * t_axis[1];
        st.ws.axial_speed_m_per_s = advance_m.abs() * params.tick_rate_hz;
        st.ws.advancing = advance_m > 0.0;
        frames::set_prescribed_values(&Geometry::new(params, st.pose, st.flex.as_ref()), &mut st.ws);
        lap(clock, &mut t_last, &mut stage_ns, 0);
        capture::release_withdrawn(s_tip, &mut st.ws, &mut st.stats)?;
        lap(clock, &mut t_last, &mut stage_ns, 1);
        match params.contact {
            ContactModel::Nodes => capture::capture(&ctx, st, &mut sc.capture, &mut out.approaching, prev_tip)?,
            ContactModel::MaterialPoints { spacing_m, width_m } => {
                capture::capture_points(&ctx, st, &mut sc.capture, &mut out.approaching, prev_tip, spacing_m, width_m)?
            }
        }
        lap(clock, &mut t_last, &mut stage_ns, 2);
        let geo = Geometry::new(params, st.pose, st.flex.as_ref());
        active_set::update_friction(params, &geo, &mut st.ws, &mut sc.active_set.order, false, 0.0);
        let resolved = active_set::resolve_active_set(&ctx, st, &mut sc.active_set, &mut sc.flex)?;
        let (mut iterations, mut converged, mut capped) = (resolved.iterations, resolved.converged, resolved.capped);
        lap(clock, &mut t_last, &mut stage_ns, 3);
        // A flexible needle comes to equilibrium with the tick's forces; where that moves it off
        // the linearised prediction by more than SHAPE_GAP_TOL_M, the tissue is solved again on
        // the new shape (a bounded Picard iteration, which says when it stops at its bound).
        let mut shape_capped = false;
        for pass in 1..=param_limits::SHAPE_PASSES {
            let (Some(fx), Some(fsc)) = (st.flex.as_mut(), sc.flex.as_mut()) else { break };
            let gap = flexible::settle_shape(st.pose, &params.needle, &mut st.ws, fx, fsc, &mut st.stats.shape_unconverged);
            if gap <= param_limits::SHAPE_GAP_TOL_M {
                break;
            }
            if pass == param_limits::SHAPE_PASSES {
                shape_capped = true;
                break;
            }
            flexible::refresh_frames(&fx.curve, &mut st.ws, s_tip)?;
            frames::set_prescribed_values(&Geometry::new(params, st.pose, st.flex.as_ref()), &mut st.ws);
            let r = active_set::resolve_active_set(&ctx, st, &mut sc.active_set, &mut sc.flex)?;
            iterations += r.iterations;
            converged &= r.converged;
            capped |= r.capped;
            st.stats.shape_passes += 1;
        }
        lap(clock, &mut t_last, &mut stage_ns, 4);
        let geo = Geometry::new(params, st.pose, st.flex.as_ref());
        if let Err((what, value, bound)) = divergence::check(&setup.bounds, &geo, &st.ws) {
            let d = Diverged { tick: st.tick, what, value, bound };
            st.diverged = Some(d);
            return Err(d.into());
        }
        lap(clock, &mut t_last, &mut stage_ns, 5);
        output::write_output(&ctx, st, out, iterations, converged, clamped);
        out.active_set_capped = capped;
        out.shape_passes_capped = shape_capped;
        if let Some(c) = &setup.visc {
            // Each contact's history from its true displacement (written by the output stage).
            for (nn, u) in st.ws.nodes.iter_mut().zip(&st.ws.u_world) {
                nn.visc.advance(c, *u);
            }
        }
        lap(clock, &mut t_last, &mut stage_ns, 6);
        touch_and_sweep(params, model.mesh().nodes_m(), st, out);
        if st.tick % param_limits::HYBRID_CHECK_EVERY_TICKS == param_limits::HYBRID_CHECK_EVERY_TICKS - 1 {
            let blocks = crate::viscous::ScaledBlocks { cache: &st.cache, scale: setup.compliance_scale };
            let checked = crate::drift::check_one(&mut st.ws.solver, &blocks, &mut st.drift);
            st.stats.hybrid_checks += (checked != crate::drift::Checked::Nothing) as u64;
            st.stats.hybrid_rebuilds += (checked == crate::drift::Checked::Rebuilt) as u64;
            st.stats.hybrid_rebuild_failures += (checked == crate::drift::Checked::RebuildFailed) as u64;
        }
        lap(clock, &mut t_last, &mut stage_ns, 7);
        out.stage_ns = stage_ns;
        st.tick += 1;
        st.stats.ticks += 1;
        st.stats.clamped_ticks += clamped as u64;
        st.stats.unconverged_ticks += (!converged) as u64;
        st.stats.active_set_capped_ticks += capped as u64;
        st.stats.shape_capped_ticks += shape_capped as u64;
        Ok(out)
    }

    /// Times the stages of every following step with `clock` into [`StepOutput::stage_ns`]
    /// (none: untimed, all zero). For benchmarks; the step's results do not depend on it.
    pub fn set_stage_clock(&mut self, clock: Option<StageClock>) {
        self.stage_clock = clock;
        self.out.stage_ns = [0; N_STAGES];
    }

    /// The largest relative residual of the hybrid matrix's solution found by the step's
    /// round-off checks so far (`drift.rs`; [`SimStats::hybrid_checks`] of them).
    pub fn hybrid_max_residual(&self) -> f64 {
        self.state.drift.max_residual
    }

    /// Sets the residual above which a check rebuilds the hybrid matrix (default
    /// [`param_limits::HYBRID_DRIFT_TOL`]); a negative value rebuilds at every check, which
    /// tests use to exercise the rebuild.
    pub fn set_hybrid_drift_tol(&mut self, tol: f64) {
        self.state.drift.tol = tol;
    }

    /// The local stiffness the device feels: the 3 × 3 Jacobian
    /// $J_{ij} = \partial w_i / \partial q_j$ of the wrench $w = (F_x, F_y, \tau)$ on the base with
    /// respect to the base pose $q = (x, y, \theta)$, at the current state with the contact
    /// conditions held (row-major). Central differences of probe solves for the translations
    /// ($h$ = 1 µm; exact, the held problem is linear in them), a directional derivative for the
    /// rotation (`jacobian.rs`): $O(d^2)$ in all, whatever the number of slipping nodes (a
    /// flexible needle adds one factorisation of its coupling); no allocation.
    /// A device bridge renders $w(q) \approx w_0 + J (q - q_0)$ between server updates.
    ///
    /// Errors: [`SimError::Mixed`] when the probe solver refuses a frame rotation (the
    /// simulation's state is untouched).
    pub fn stiffness_jacobian(&mut self) -> Result<[[f64; 3]; 3], SimError> {
        let ctx = Ctx { model: &self.model, params: &self.params, setup: &self.setup };
        let st = &self.state;
        jacobian::stiffness_jacobian(&ctx, st.pose, &st.ws, st.flex.as_ref(), &mut self.scratch.probe, self.scratch.flex.as_mut())
    }

    /// Displacement of every DOF ($O(n\,d)$; for rendering at frame rate, not every tick).
    pub fn displacement_field_into(&self, out: &mut [f64]) {
        output::displacement_field_into(&self.state.ws, &self.state.cache, out);
    }

    /// The static problem that the last step solved: each needle node's conditions in its frame
    /// (`un` always; `ut` when stuck or carried by the tip) and the friction loads of slipping
    /// nodes (world components).
    pub fn snapshot(&self) -> StateSnapshot {
        output::snapshot(&self.state.ws, &self.out)
    }
}

/// What [`Simulation::insert_columns_owned`] did with the columns.
#[derive(Debug)]
pub struct Inserted {
    /// The box not kept (the node's previous columns, or reused storage's), to be dropped off
    /// the real-time thread.
    pub spare: Option<Box<[f64]>>,
    /// The node evicted to make room (the cache was full).
    pub evicted: Option<usize>,
}

/// The last stage of a step: marks the nodes in use (working contacts' nodes and the
/// lookahead's, the latter in the capture stage) and sweeps
/// [`param_limits::EVICTION_SWEEP_PER_TICK`] cache slots round robin, evicting nodes unused for
/// [`param_limits::COLUMN_KEEP_S`]. With the paper's node capture ([`ContactModel::Nodes`]) a
/// node near the shaft can be captured again whenever the shaft sweeps it (a flexing needle
/// does, even while withdrawing), so nodes within three capture radii (plus the largest contact
/// displacement) of the needle are kept too; material points are only taken ahead of an
/// advancing tip, which the lookahead covers. $O(d)$ (plus the needle's joints per visited
/// slot); allocates nothing (the cache reserved its free list).
fn touch_and_sweep(params: &SimParams, nodes_m: &[[f64; 2]], st: &mut State, out: &mut StepOutput) {
    let tick = st.tick;
    for nn in &st.ws.nodes {
        for n in nn.contact.nodes() {
            st.columns_lru.touch(n.index(), tick);
        }
    }
    for &j in &out.approaching {
        st.columns_lru.touch(j, tick);
    }
    out.evicted.clear();
    let keep_ticks = (param_limits::COLUMN_KEEP_S * params.tick_rate_hz).ceil() as u64;
    let n_slots = st.cache.n_slots();
    let shaft_band_m = match params.contact {
        ContactModel::Nodes => {
            let u_max = st.ws.u_world.iter().fold(0.0f64, |m, u| m.max(u[0].hypot(u[1])));
            Some(3.0 * params.capture_radius_m + u_max)
        }
        ContactModel::MaterialPoints { .. } => None,
    };
    let geo = Geometry::new(params, st.pose, st.flex.as_ref());
    let near_shaft = |x: [f64; 2], band_m: f64| match geo.curve {
        Some(c) => c.points_m().windows(2).any(|w| segment_distance_m(x, w[0], w[1]) <= band_m),
        None => segment_distance_m(x, [st.pose.x_m, st.pose.y_m], geo.tip()) <= band_m,
    };
    for _ in 0..param_limits::EVICTION_SWEEP_PER_TICK.min(n_slots) {
        let slot = st.columns_lru.cursor % n_slots;
        st.columns_lru.cursor = slot + 1;
        if let Some(j) = st.cache.node_in_slot(slot)
            && st.columns_lru.stamp[j] + keep_ticks <= tick + 1
            && shaft_band_m.is_none_or(|band_m| !near_shaft(nodes_m[j], band_m))
        {
            st.cache.evict(j);
            out.evicted.push(j);
            st.stats.columns_evicted += 1;
        }
    }
}

/// The distance from `x` to the segment from `a` to `b`.
fn segment_distance_m(x: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let ax = [x[0] - a[0], x[1] - a[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    let s = if len2 > 0.0 { ((ax[0] * ab[0] + ax[1] * ab[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
    (ax[0] - s * ab[0]).hypot(ax[1] - s * ab[1])
}

/// Before a column enters a full cache ([`SimParams::max_cached_nodes`]): evicts the least
/// recently used node that the last step did not use (the working set's and the lookahead's
/// nodes are stamped with the last step). $O(\text{cache})$, only when full. Returns the node
/// evicted; `None` when there was room, or when every cached node is in use (the cache then
/// grows past its bound, counted in [`SimStats::cache_over_cap`]).
fn make_room(params: &SimParams, st: &mut State) -> Option<usize> {
    if st.cache.len() < params.max_cached_nodes() {
        return None;
    }
    let in_use = st.tick; // the stamp of a node the last step (tick − 1) used
    let mut victim: Option<(usize, u64)> = None;
    for slot in 0..st.cache.n_slots() {
        if let Some(j) = st.cache.node_in_slot(slot) {
            let stamp = st.columns_lru.stamp[j];
            if stamp < in_use && victim.is_none_or(|(_, s)| stamp < s) {
                victim = Some((j, stamp));
            }
        }
    }
    match victim {
        Some((j, _)) => {
            st.cache.evict(j);
            st.stats.columns_evicted += 1;
            Some(j)
        }
        None => {
            st.stats.cache_over_cap += 1;
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{phantom, phantom_params};
    use crate::needle::{FlexibleNeedle, NeedleShape};

    /// The scratch carries nothing between ticks that is not rebuilt: replacing it mid-run with
    /// a fresh one changes no output bit (flexible bevel needle: couplings, LU, probe curve).
    #[test]
    fn scratch_is_droppable() {
        let mut f = FlexibleNeedle::gauge17_steel(0.1);
        f.flexural_rigidity_nm2 *= 0.3;
        f.bevel_force_ratio = 0.2;
        let params = phantom_params(NeedleShape::Flexible(f));
        let model = phantom(25);
        let a0 = -1.3f64;
        let base_at = |d: f64| BasePose::new(0.04 + (d - 0.1) * a0.cos(), 0.1 + (d - 0.1) * a0.sin(), a0);
        let params = SimParams { initial_pose: base_at(-0.005), ..params };
        let mut a = Simulation::new(model.clone(), params.clone()).unwrap();
        let mut b = Simulation::new(model, params).unwrap();
        for k in 0..1500 {
            let pose = base_at(-0.005 + 0.045 * k as f64 / 1500.0);
            if k % 50 == 25 {
                b.scratch = Scratch::new(&b.model, &b.params);
            }
            let (oa, ob) = (a.step(pose).unwrap().clone(), b.step(pose).unwrap().clone());
            assert_eq!((oa.force_n, oa.torque_nm, oa.tip_m), (ob.force_n, ob.torque_nm, ob.tip_m), "tick {k}");
            assert_eq!(oa.needle_nodes, ob.needle_nodes, "tick {k}");
            if k % 10 == 0 {
                assert_eq!(a.stiffness_jacobian().unwrap(), b.stiffness_jacobian().unwrap(), "tick {k}");
            }
            a.prefetch_columns(16).unwrap();
            b.prefetch_columns(16).unwrap();
        }
        assert!(a.stats().captures > 5, "{:?}", a.stats());
    }
}
