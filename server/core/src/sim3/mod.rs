//! The 3D insertion simulation: a rigid needle with a 6-DOF base ([`BasePose3`]) in a
//! tetrahedral tissue ([`TetTissueModel`]), one [`Simulation3::step`] per haptic tick.
//!
//! It mirrors the 2D simulation ([`crate::sim`]) with contact at material points: the working
//! set is a list of points of the tissue $X_i$ (fixed inside their tetrahedra, [`ContactPoint`])
//! held by the needle, condensed by the mixed solver [`MixedSolver3`] with the point
//! compliance $W = P C P^\top$ from cached node columns ([`ComplianceCache3`]). Each point has the
//! needle frame $[t, n, b]$ of the base pose (a rigid needle: one frame for all).
//!
//! A step, in order:
//! 1. **Pose**: reject a non-finite or non-unit pose ([`SimError3::Pose`], state unchanged),
//!    clamp the jump to [`Sim3Params::max_base_step_m`] and
//!    [`Sim3Params::max_base_step_rad`].
//! 2. **Frames and values**: every point's frame becomes the new $[t, n, b]$
//!    ([`MixedSolver3::set_frame`], $O(d)$ for a stuck point, $O(d^2)$ for a slipping one; nothing
//!    when the orientation did not change), and its prescribed values put the deformed point on
//!    the shaft: with $d_i = X_i - x_b$,
//!    $$u_n = -n\cdot d_i,\qquad u_b = -b\cdot d_i,$$
//!    axially a stuck point sits at its shaft anchor $s_a$, $u_t = s_a - t\cdot d_i$, and the
//!    tip's point at the tip, $u_t = L - t\cdot d_i$.
//! 3. **Release**: a point whose deformed position lies beyond the tip ($t\cdot(x_i - x_b) > L$:
//!    the tip withdrew past it) leaves the working set.
//! 4. **Capture**: when no point is carried by the tip, the tip advanced along its axis, and it
//!    lies [`Sim3Params::spacing_m`] beyond the most distal point, the material point at the
//!    previous tip position $p$ is found as the fixed point of $X = p - u(X)$ (started from the
//!    distal point's displacement) and becomes the tip's point, carried until its axial force
//!    exceeds the region's puncture force (entering the tissue or a new region) or cutting
//!    force. It is taken only when its reference distance to every working point exceeds both
//!    points' tetrahedron diameters (so that no tetrahedron holds two points of the shaft and
//!    the conditions are independent); a point whose nodes' columns are not cached waits
//!    (counted in [`Sim3Stats::column_deferrals`]): the step never computes a column. The tip
//!    keeps trying where it is; once it has gone a spacing beyond where the capture first
//!    waited, that position waits in a list and the tissue point there joins as a stuck shaft
//!    point when its columns arrive ([`Sim3Stats::late_captures`]), so a worker behind the tip
//!    delays the points it passes rather than losing them.
//! 5. **Friction**: each shaft point gets the integral of the friction distribution of the
//!    paper's Fig. 2b over its tributary segment ([`RegionNeedleParams::friction_integral_n`]),
//!    plus the rate-dependent part $b_v |v| \lambda$ of [`crate::needle`] ($v$ the base's speed
//!    along the axis over the last tick, $\lambda$ the segment's length), as in 2D.
//! 6. **Active set**: solve; stuck points whose $|f_t|$ exceeds static friction slip (force
//!    $f_t = \pm$ their share, against the relative motion), slipping points whose relative motion
//!    stopped or reversed stick, the tip's point punctures or, pulled, lets go; bounded
//!    iterations, each change an $O(d^2)$ update.
//! 7. **Output**: the wrench on the needle base (world),
//!    $$F = -\sum_i f_i,\qquad \tau = \sum_i (x_i - x_b) \times (-f_i),$$
//!    with $f_i$ the force of the needle on the tissue at point $i$ and $x_i = X_i + u_i$; the
//!    tip, the inserted length and each point's state ([`StepOutput3`]).
//!
//! Columns are filled between steps by [`Simulation3::prefetch_columns`] (the nodes of the
//! tetrahedra on the axis ahead of the tip, the next point's first) or [`Simulation3::insert_columns`]
//! (a worker's); the cache is bounded ([`Sim3Params::max_cached_nodes`], least recently used
//! evicted).
//!
//! On large meshes ([`StoreKind3`], chosen in [`Sim3Params::store`]) the compliance is a
//! [`NodeBlockStore`] instead: the $3 \times 3$ blocks $C_{vw}$ among at most
//! [`Sim3Params::max_block_nodes`] nodes, filled by a [`Sim3BlockWorker`] from sparse compliance
//! rows. Between steps [`Simulation3::requests_into`] hands out the nodes wanted (pinned nodes,
//! then the approaching ones) with the slots they get (the least recently used node that is
//! neither pinned nor used by the last step gives its slot up), the worker answers
//! ([`Sim3BlockWorker::compute`]) and [`Simulation3::insert_payload`] copies each answer in
//! ($O(M)$, no solve); [`Simulation3::prefetch_blocks`] does the three on one thread. Everything a
//! step reads of the compliance is a contact block: the working points' blocks for the mixed
//! solver, and $u(X) = \sum_i W_{X i} f_i$ in the capture's fixed point, which needs the blocks of
//! the iterate's nodes too: when they are not ready the capture waits (counted in
//! [`Sim3Stats::column_deferrals`]). Nodes that must stay (a target's, for instance) are pinned
//! ([`Simulation3::pin_node`]): never evicted, requested first. The tissue factorisation is never touched. All per-step storage is sized in
//! [`Simulation3::new`]: a warm step allocates nothing. [`Simulation3::snapshot`] gives the static
//! problem the last step solved in the terms of the 3D exchange format's `points`.
//!
//! Besides: the stiffness of the base wrench for a device's local model
//! ([`Simulation3::wrench_stiffness`], [`stiffness`]; a flexible needle's rod in series with the
//! tissue), and targets moving with the tissue, hit
//! or miss latched, updated after stage 7 ([`targets`]).

mod flex;
mod params;
mod pose;
pub mod stiffness;
pub mod targets;
mod tear;

use std::sync::Arc;

use crate::compliance::sparse::SparseComplianceError;
use crate::compliance::{ComplianceCache3, ContactBlocks};
use crate::contact::ContactPoint;
use crate::d3::locate::{BARYCENTRIC_TOL, barycentric};
use crate::d3::{TetColumnScratch, TetTissueError, TetTissueModel};
use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedError, MixedSolver3};
use crate::needle::RegionNeedleParams;

pub use crate::compliance::store::{
    Block3, BlockPayload3 as BlockPayload, BlockRequest, BlockStoreError, ComplianceStore3, NodeBlockStore3 as NodeBlockStore,
};
pub use crate::compliance::worker::{ROWS_BATCH, Sim3BlockWorker, WorkerStats};
pub use flex::{FRAME_TOL as FLEX_FRAME_TOL, SHAPE_GAP_TOL_M, SHAPE_PASSES};
pub use params::{AUTO_BLOCKS_MIN_NODES, NeedleShape3, Sim3Params, StoreKind3};
pub use pose::{BasePose3, PoseError, UNIT_QUATERNION_TOL, unit_axis};
pub use stiffness::WrenchStiffness3;
pub use targets::{MAX_TARGETS, Target3, TargetOut3, TargetState3, TargetsOut3};
pub use tear::DEFAULT_TEAR_FORCE_FACTOR;

/// Fixed-point iterations locating the material point at a deformed position.
const LOCATE_ITERATIONS: usize = 8;
/// Bound on the friction-share sweeps per active-set iteration.
const FRICTION_SWEEPS: usize = 6;
/// Relative tolerance of the friction shares (of the total friction).
const FRICTION_TOL: f64 = 1e-6;
/// Point locations along the axis ahead of the tip per tick, for the approaching nodes.
pub const LOOKAHEAD_SAMPLES_PER_TICK: u64 = 2;
/// Lookahead samples per axis station: on the axis and at six points around it.
const LOOKAHEAD_RING: u64 = 7;
/// Capacity of the list of approaching nodes.
pub const MAX_APPROACHING: usize = 128;
/// Most points the tip passed while their columns were missing that wait to be captured
/// ([`Sim3Stats::late_captures`]); one more is dropped and counted in
/// [`Sim3Stats::pending_dropped`].
pub const MAX_PENDING_CAPTURES: usize = 64;
/// Most waiting points captured in one tick (each an $O(d^2)$ addition).
const LATE_CAPTURES_PER_TICK: usize = 2;

/// Errors of the 3D simulation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError3 {
    /// At [`Simulation3::new`]: a parameter out of range or not matching the mesh (the message
    /// names it).
    #[error("invalid 3D simulation parameters: {0}")]
    InvalidParams(String),
    /// At [`Simulation3::step`]: the commanded pose is not finite or its quaternion not unit;
    /// the state is unchanged.
    #[error("tick {tick}: {source}")]
    Pose { tick: u64, source: PoseError },
    /// At [`Simulation3::step`]: the working solver refused an update mid-tick (a frame, a
    /// condition switch or a release made the system singular); the tick is lost.
    #[error(transparent)]
    Mixed(#[from] MixedError),
    /// At [`Simulation3::prefetch_columns`]: a column solve failed (columns computed before it
    /// stay).
    #[error(transparent)]
    Tissue(#[from] TetTissueError),
    /// A call that needs the other compliance store ([`StoreKind3`]): `call` names it.
    #[error("Simulation3::{call} needs the {needs} store; this simulation uses {has}")]
    WrongStore { call: &'static str, needs: &'static str, has: &'static str },
    /// At [`Simulation3::insert_payload`]: a payload that does not answer the oldest pending
    /// request (see [`NodeBlockStore`]'s protocol).
    #[error(transparent)]
    Blocks(#[from] BlockStoreError),
    /// At [`Simulation3::prefetch_blocks`] or [`Simulation3::block_worker`]: the worker refused
    /// a request or the factor.
    #[error(transparent)]
    Sparse(#[from] SparseComplianceError),
    /// At [`Simulation3::wrench_stiffness`] of a flexible needle: rod and tissue in series,
    /// $I + H_{PP}\tilde G_{PP}$, has a pivot below 1e-14 of its largest entry (not expected:
    /// both compliances are positive semidefinite and the tissue's definite).
    #[error("tick {tick}: the flexible needle's stiffness is singular (smallest relative pivot {pivot:e})")]
    SingularRodCoupling { tick: u64, pivot: f64 },
    /// At [`Simulation3::pin_node`]: the node does not exist.
    #[error("node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownNode { node_idx: usize, n_nodes: usize },
}

/// What [`Simulation3::insert_columns_owned`] returns: the evicted node, if any, and the box not
/// kept.
pub type InsertedColumns = (Option<usize>, Option<Box<[f64]>>);

/// The state of a contact point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointState3 {
    /// Held at its shaft anchor: $u_t$ prescribed.
    Stuck,
    /// Sliding along the shaft: $f_t$ prescribed (its friction share, against the motion).
    Slipping,
    /// Carried by the tip until puncture or cutting: $u_t$ prescribed at the tip.
    Tip,
}

/// Counters over the simulation's life.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Sim3Stats {
    pub captures: u64,
    pub punctures: u64,
    /// Points released: withdrawn past by the tip, or let go by the tip.
    pub releases: u64,
    pub stick_to_slip: u64,
    pub slip_to_stick: u64,
    /// Ticks a due capture waited for its nodes' columns (with node blocks: for the blocks of
    /// its nodes or of the tetrahedra its fixed point passed through).
    pub column_deferrals: u64,
    /// Captures refused because their conditions were dependent on the others' (not expected
    /// with the distance rule).
    pub dependent_points: u64,
    /// Captures dropped for a full working set.
    pub capacity_drops: u64,
    /// Ticks whose commanded pose was clamped.
    pub clamped_ticks: u64,
    /// Ticks whose active set did not settle within the iteration bound.
    pub unconverged_ticks: u64,
    /// Flexible needle: ticks whose shape passes stopped at [`SHAPE_PASSES`] with the settled
    /// shape still more than [`SHAPE_GAP_TOL_M`] off ([`StepOutput3::shape_passes_capped`]).
    pub shape_capped_ticks: u64,
    /// Held points torn free: their force across the shaft exceeded what their region's tissue
    /// holds (`needlesim_core::sim3::tear`; also counted in `releases`).
    pub tears: u64,
    /// Approaching nodes not reported (list full).
    pub approaching_overflow: u64,
    /// Cached nodes evicted to make room.
    pub columns_evicted: u64,
    /// Inserts past [`Sim3Params::max_cached_nodes`] with nothing evictable.
    pub cache_over_cap: u64,
    /// Points the tip passed while their columns were missing, captured once the columns
    /// arrived (as stuck shaft points where they then were; a live session's worker behind the
    /// tip, issue 17). Included in `captures`.
    pub late_captures: u64,
    /// Waiting points given up: the tip withdrew past them, they lay too close to a held point
    /// or outside the mesh, or the waiting list ([`MAX_PENDING_CAPTURES`]) or the working set
    /// was full.
    pub pending_dropped: u64,
}

/// One contact point in a step's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOut3 {
    pub state: PointState3,
    /// Its frame, rows $[t, n, b]$.
    pub frame: [[f64; 3]; 3],
    /// Reference position $X$, m.
    pub x_ref_m: [f64; 3],
    /// Current position $X + u$, m.
    pub x_m: [f64; 3],
    /// Force of the needle on the tissue there, world, N.
    pub force_n: [f64; 3],
    /// Its kinetic friction share, N.
    pub friction_n: f64,
}

/// The per-tick output, rewritten in place.
#[derive(Debug, Clone, PartialEq)]
pub struct StepOutput3 {
    /// The tick this output belongs to (0 for the initial output).
    pub tick: u64,
    /// $t = k / f_{tick}$, s.
    pub time_s: f64,
    /// The pose applied (after clamping).
    pub pose: BasePose3,
    pub clamped: bool,
    /// Force of the tissue on the needle base, world, N: $F = -\sum_i f_i$.
    pub base_force_n: [f64; 3],
    /// Torque of the tissue on the needle about the base point, world, N·m.
    pub base_torque_nm: [f64; 3],
    /// The axial force the tissue resists the needle with, $t\cdot\sum_i f_i = -t\cdot F$, N:
    /// positive while pushing in, negative while pulling out.
    pub axial_force_n: f64,
    /// Tip position, m.
    pub tip_m: [f64; 3],
    /// Length of shaft from the most proximal contact to the tip (0 without contacts), m.
    pub inserted_length_m: f64,
    /// The working points, in slot order.
    pub contacts: Vec<ContactOut3>,
    /// Nodes (not cached) of the tetrahedra on the axis ahead of the tip, the next point's
    /// first: what [`Simulation3::prefetch_columns`] computes.
    pub approaching: Vec<usize>,
    pub active_set_iterations: usize,
    /// The stick/slip iteration settled within `max_active_set_iterations` passes
    /// ([`StepOutput3::unconverged`] says why not).
    pub converged: bool,
    /// Flexible needle: the shape passes stopped at their cap with the shape still changing
    /// (counted in [`Sim3Stats::shape_capped_ticks`]); always `false` for a rigid needle.
    pub shape_passes_capped: bool,
    /// The targets ([`Sim3Params::targets`]): displaced centres, distances, latched states
    /// ([`targets`]).
    pub targets: TargetsOut3,
}

/// One point of [`Snapshot3`], in the exchange format's terms (`points`: `x`, `frame`, `ut`,
/// `un`, `ub`, `f`), with the simulation's answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnapshotPoint3 {
    /// Reference position, m.
    pub x_m: [f64; 3],
    /// Frame rows $[t, n, b]$ as the solver holds them.
    pub frame: [[f64; 3]; 3],
    /// Prescribed displacement components (m), `None` where free.
    pub ut: Option<f64>,
    pub un: Option<f64>,
    pub ub: Option<f64>,
    /// The prescribed (friction) force, world, N; `None` for a point with every component
    /// prescribed.
    pub f_n: Option<[f64; 3]>,
    /// The simulation's total force of the needle on the tissue there, world, N (constraint
    /// reaction plus `f_n`).
    pub force_n: [f64; 3],
    /// The simulation's displacement there, world, m.
    pub u_m: [f64; 3],
}

/// The static problem the last step solved.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot3 {
    pub tick: u64,
    pub points: Vec<SnapshotPoint3>,
}

/// A working point's bookkeeping (by slot, as the solver's).
#[derive(Debug, Clone, Copy)]
struct Point {
    contact: ContactPoint,
    x_ref_m: [f64; 3],
    state: PointState3,
    /// Shaft arc length a stuck point is held at.
    anchor_s_m: f64,
    /// Shaft arc length of its deformed position at the end of the last tick.
    s_prev_m: f64,
    /// The arc length the friction shares use this sweep.
    s_work_m: f64,
    friction_n: f64,
    friction_new_n: f64,
    /// Sign of the axial friction force on the tissue (+1 while the needle goes in).
    slip_sign: f64,
    release_force_n: f64,
    region: usize,
    f_world: [f64; 3],
    u_world: [f64; 3],
    /// Flexible needle: the lateral values $g$ that put the point on the reference shape, and
    /// the force (its frame) the reference shape is in equilibrium with ([`flex`]).
    lat_ref_m: [f64; 2],
    f_ref_local_n: [f64; 3],
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Change {
    Puncture,
    LetGo,
    Slip(f64),
    Stick(f64),
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// The simulation of one rigid needle in one 3D tissue.
pub struct Simulation3 {
    model: Arc<TetTissueModel>,
    params: Sim3Params,
    /// Longest edge of each tetrahedron, m.
    tet_diam_m: Vec<f64>,
    /// Step of the axis sampling for approaching nodes (half the shortest tetrahedron edge
    /// scale), m.
    sample_step_m: f64,
    /// The largest tetrahedron diameter, m.
    max_diam_m: f64,
    pose: BasePose3,
    solver: MixedSolver3,
    pts: Vec<Point>,
    /// Where the tip was when a capture was due but its columns were missing (world, m),
    /// oldest first: captured later ([`Sim3Stats::late_captures`]).
    pending: Vec<[f64; 3]>,
    /// Where the tip was when the due capture first waited for columns (world, m); the tip
    /// keeps trying where it is, and only once it has gone a spacing further (or stopped) does
    /// this point join `pending`.
    deferred_since_m: Option<[f64; 3]>,
    /// The base's speed along the needle axis over the last tick, m/s (rate-dependent
    /// friction, [`RegionNeedleParams::friction_damping_n_s_per_m2`]).
    axial_speed_m_per_s: f64,
    cache: ComplianceStore3,
    /// Nodes never evicted ([`Simulation3::pin_node`]).
    pinned: Vec<bool>,
    pins: Vec<usize>,
    /// 1 + the last tick a node's columns were used (0: never).
    stamp: Vec<u64>,
    last_tip_region: Option<usize>,
    tick: u64,
    stats: Sim3Stats,
    order: Vec<Slot>,
    changes: Vec<(Slot, Change)>,
    column_buf: Vec<f64>,
    column_scratch: Option<TetColumnScratch>,
    out: StepOutput3,
    /// Scratch of [`Simulation3::wrench_stiffness`].
    stiffness: stiffness::StiffnessScratch,
    /// The targets' located centres and latch bookkeeping.
    targets: targets::TargetTracker,
    /// The flexible needle ([`flex`]); `None` for a rigid one.
    flex: Option<flex::Flex3>,
}

impl Simulation3 {
    /// Validates the parameters against the model and sizes all per-step storage.
    ///
    /// Errors: [`SimError3::InvalidParams`] for a parameter out of range
    /// ([`Sim3Params::validate`]), a number of region parameters other than the mesh's, or a
    /// target whose centre lies outside the mesh (naming it).
    pub fn new(model: Arc<TetTissueModel>, params: Sim3Params) -> Result<Self, SimError3> {
        let mesh = model.mesh();
        params.validate(mesh.region_names().len().max(1)).map_err(SimError3::InvalidParams)?;
        let tet_diam_m: Vec<f64> = (0..mesh.n_tets()).map(|t| crate::d3::mesh::longest_edge_m(mesh.tet_points_m(t))).collect();
        let min_diam = tet_diam_m.iter().copied().fold(f64::INFINITY, f64::min);
        let max_diam_m = tet_diam_m.iter().copied().fold(0.0, f64::max);
        let n_nodes = mesh.n_nodes();
        let cap = params.max_contacts;
        let (cache, column_buf) = match params.store.resolve(n_nodes) {
            StoreKind3::NodeBlocks => (ComplianceStore3::Blocks(NodeBlockStore::new(n_nodes, params.max_block_nodes)), Vec::new()),
            _ => {
                let mut c = ComplianceCache3::for_nodes(n_nodes);
                c.reserve(params.max_cached_nodes.min(n_nodes) + 16);
                (ComplianceStore3::Columns(c), vec![0.0; 9 * n_nodes])
            }
        };
        let pose = params.initial_pose;
        let targets = targets::TargetTracker::new(&model, &params.targets)?;
        let flex = params.needle.flexible().map(|f| flex::Flex3::new(f, pose.position_m, pose.frame(), cap));
        let mut out = StepOutput3 {
            tick: 0,
            time_s: 0.0,
            pose,
            clamped: false,
            base_force_n: [0.0; 3],
            base_torque_nm: [0.0; 3],
            axial_force_n: 0.0,
            tip_m: pose.point_at(params.needle_length_m),
            inserted_length_m: 0.0,
            contacts: Vec::with_capacity(cap),
            approaching: Vec::with_capacity(MAX_APPROACHING),
            active_set_iterations: 0,
            converged: true,
            shape_passes_capped: false,
            targets: TargetsOut3::default(),
        };
        targets.initial_output(out.tip_m, pose.axis(), &mut out.targets);
        let mut sim = Self {
            tet_diam_m,
            sample_step_m: 0.25 * min_diam,
            max_diam_m,
            pose,
            solver: MixedSolver3::with_capacity(cap),
            pts: Vec::with_capacity(cap),
            pending: Vec::with_capacity(MAX_PENDING_CAPTURES),
            deferred_since_m: None,
            axial_speed_m_per_s: 0.0,
            cache,
            pinned: vec![false; n_nodes],
            pins: Vec::new(),
            stamp: vec![0; n_nodes],
            last_tip_region: None,
            tick: 0,
            stats: Sim3Stats::default(),
            order: Vec::with_capacity(cap),
            changes: Vec::with_capacity(cap),
            column_buf,
            column_scratch: None,
            out,
            stiffness: stiffness::StiffnessScratch::with_capacity(cap, flex.is_some()),
            targets,
            flex,
            model,
            params,
        };
        // A target's displaced centre reads C(target node, working node): with node blocks both
        // must be cached, so the targets' (free) nodes are pinned.
        let target_nodes: Vec<usize> = sim.targets.nodes().filter(|&v| !sim.model.is_fixed(v)).collect();
        for v in target_nodes {
            sim.pin_node(v)?;
        }
        Ok(sim)
    }

    /// The tissue model.
    pub fn model(&self) -> &Arc<TetTissueModel> {
        &self.model
    }
    /// The parameters.
    pub fn params(&self) -> &Sim3Params {
        &self.params
    }
    /// The pose applied by the last step.
    pub fn pose(&self) -> BasePose3 {
        self.pose
    }
    /// The last step's output.
    pub fn output(&self) -> &StepOutput3 {
        &self.out
    }
    /// Counters over the simulation's life.
    pub fn stats(&self) -> Sim3Stats {
        self.stats
    }
    /// The working solver (for its update counters: [`MixedSolver3::stats`]).
    pub fn solver(&self) -> &MixedSolver3 {
        &self.solver
    }
    /// The compliance store (columns or node blocks).
    pub fn cache(&self) -> &ComplianceStore3 {
        &self.cache
    }
    /// The number of the next tick.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// Computes (allocating, outside any step) the columns of up to `max_nodes` of the nodes the
    /// last step reported as approaching, nearest first. Returns how many it computed.
    ///
    /// Errors: [`SimError3::Tissue`] when a column solve fails (those before it stay);
    /// [`SimError3::WrongStore`] with node blocks (use [`Simulation3::prefetch_blocks`]).
    pub fn prefetch_columns(&mut self, max_nodes: usize) -> Result<usize, SimError3> {
        self.columns_mut("prefetch_columns")?;
        let mut n = 0;
        // The pinned nodes first, then the approaching ones.
        for k in 0..self.pins.len() + self.out.approaching.len() {
            let node = if k < self.pins.len() { self.pins[k] } else { self.out.approaching[k - self.pins.len()] };
            if n == max_nodes {
                break;
            }
            if !self.cache.contains(node) {
                let scratch = self.column_scratch.get_or_insert_with(|| self.model.column_scratch());
                self.model.compliance_columns_into(node, &mut self.column_buf, scratch)?;
                self.make_room();
                if let ComplianceStore3::Columns(c) = &mut self.cache {
                    c.insert(node, &self.column_buf);
                }
                self.stamp[node] = self.tick + 1;
                n += 1;
            }
        }
        Ok(n)
    }

    /// Stores the columns of `node_idx` computed elsewhere
    /// ([`TetTissueModel::compliance_columns_into`], length $9n$); in a full cache they replace
    /// the least recently used node's, which is returned.
    ///
    /// Errors: [`SimError3::WrongStore`] with node blocks.
    pub fn insert_columns(&mut self, node_idx: usize, columns: &[f64]) -> Result<Option<usize>, SimError3> {
        let evicted = if self.columns_mut("insert_columns")?.contains(node_idx) { None } else { self.make_room() };
        self.columns_mut("insert_columns")?.insert(node_idx, columns);
        self.stamp[node_idx] = self.tick + 1;
        Ok(evicted)
    }

    /// [`Simulation3::insert_columns`] for columns handed over as an owned box (length $9n$):
    /// the box is kept, or copied into reused storage, so that nothing is allocated (a real-time
    /// thread receiving a worker's columns). Returns the evicted node, if any, and the box not
    /// kept (for the caller to hand back to the worker).
    ///
    /// Errors: [`SimError3::WrongStore`] with node blocks (the box is dropped).
    pub fn insert_columns_owned(&mut self, node_idx: usize, columns: Box<[f64]>) -> Result<InsertedColumns, SimError3> {
        let evicted = if self.columns_mut("insert_columns_owned")?.contains(node_idx) { None } else { self.make_room() };
        let spare = self.columns_mut("insert_columns_owned")?.insert_owned(node_idx, columns);
        self.stamp[node_idx] = self.tick + 1;
        Ok((evicted, spare))
    }

    fn columns_mut(&mut self, call: &'static str) -> Result<&mut ComplianceCache3, SimError3> {
        match &mut self.cache {
            ComplianceStore3::Columns(c) => Ok(c),
            ComplianceStore3::Blocks(_) => Err(SimError3::WrongStore { call, needs: "columns", has: "node-block" }),
        }
    }

    fn blocks_mut(&mut self, call: &'static str) -> Result<&mut NodeBlockStore, SimError3> {
        match &mut self.cache {
            ComplianceStore3::Blocks(b) => Ok(b),
            ComplianceStore3::Columns(_) => Err(SimError3::WrongStore { call, needs: "node-block", has: "columns" }),
        }
    }

    /// Whether node `j` may give up its cached data: not pinned, not used by the last step.
    fn evictable(&self, j: usize) -> bool {
        !self.pinned[j] && self.stamp[j] < self.tick
    }

    /// Evicts the least recently used cached node that the last step did not use and that is
    /// not pinned, when the column cache is full.
    fn make_room(&mut self) -> Option<usize> {
        let ComplianceStore3::Columns(cache) = &self.cache else { return None };
        if cache.len() < self.params.max_cached_nodes {
            return None;
        }
        let mut victim: Option<(usize, u64)> = None;
        for slot in 0..cache.n_slots() {
            if let Some(j) = cache.node_in_slot(slot) {
                let s = self.stamp[j];
                if self.evictable(j) && victim.is_none_or(|(_, v)| s < v) {
                    victim = Some((j, s));
                }
            }
        }
        match victim {
            Some((j, _)) => {
                if let ComplianceStore3::Columns(c) = &mut self.cache {
                    c.evict(j);
                }
                self.stats.columns_evicted += 1;
                Some(j)
            }
            None => {
                self.stats.cache_over_cap += 1;
                None
            }
        }
    }

    /// Pins `node_idx`: its compliance data is never evicted, and it is fetched before the
    /// approaching nodes ([`Simulation3::prefetch_columns`], [`Simulation3::requests_into`]).
    /// For what a step reads beyond the working points (a target's element nodes: with node
    /// blocks, $C_{vw}$ needs both nodes cached). Idempotent; allocates (between steps).
    ///
    /// Errors: [`SimError3::UnknownNode`].
    pub fn pin_node(&mut self, node_idx: usize) -> Result<(), SimError3> {
        let n_nodes = self.pinned.len();
        if node_idx >= n_nodes {
            return Err(SimError3::UnknownNode { node_idx, n_nodes });
        }
        if !self.pinned[node_idx] {
            self.pinned[node_idx] = true;
            self.pins.push(node_idx);
        }
        Ok(())
    }

    /// Unpins `node_idx` (it may be evicted again); nothing for an unknown or unpinned node.
    pub fn unpin_node(&mut self, node_idx: usize) {
        if self.pinned.get(node_idx).copied().unwrap_or(false) {
            self.pinned[node_idx] = false;
            self.pins.retain(|&v| v != node_idx);
        }
    }

    /// The pinned nodes, in the order they were pinned (a live session's worker fetches them
    /// before the approaching nodes).
    pub fn pinned_nodes(&self) -> &[usize] {
        &self.pins
    }

    /// Whether `node_idx` is pinned.
    pub fn is_pinned(&self, node_idx: usize) -> bool {
        self.pinned.get(node_idx).copied().unwrap_or(false)
    }

    /// With node blocks: up to `max_nodes` requests for the worker, appended to `out` (cleared
    /// first), for the pinned nodes not cached, then the approaching ones (nearest first); each
    /// reserves its slot ([`NodeBlockStore::reserve`]: an empty one, else the least recently
    /// used node's that is neither pinned nor used by the last step, evicted now; when there is
    /// none, counted in [`Sim3Stats::cache_over_cap`] and the list ends). Nodes already
    /// requested are not requested again. Returns how many. Allocates nothing when `out` has
    /// room.
    ///
    /// Errors: [`SimError3::WrongStore`] with columns.
    pub fn requests_into(&mut self, max_nodes: usize, out: &mut Vec<BlockRequest>) -> Result<usize, SimError3> {
        self.blocks_mut("requests_into")?;
        out.clear();
        let n_pins = self.pins.len();
        for k in 0..n_pins + self.out.approaching.len() {
            if out.len() == max_nodes {
                break;
            }
            let node = if k < n_pins { self.pins[k] } else { self.out.approaching[k - n_pins] };
            let ComplianceStore3::Blocks(store) = &self.cache else { unreachable!("checked above") };
            if self.model.is_fixed(node) || store.contains(node) || store.is_pending(node) {
                continue;
            }
            let Some(slot) = store.choose_slot(|j| self.evictable(j), |j| self.stamp[j]) else {
                self.stats.cache_over_cap += 1;
                break;
            };
            let (req, evicted) = self.blocks_mut("requests_into")?.reserve(node, slot)?;
            if evicted.is_some() {
                self.stats.columns_evicted += 1;
            }
            self.stamp[node] = self.tick + 1;
            out.push(req);
        }
        Ok(out.len())
    }

    /// With node blocks: applies a worker's answer (payloads in the order of the requests),
    /// $O(M)$ copies, no solve, no allocation.
    ///
    /// Errors: [`SimError3::WrongStore`] with columns; [`SimError3::Blocks`] for a payload that
    /// answers no pending request (nothing changes).
    pub fn insert_payload(&mut self, payload: &BlockPayload) -> Result<(), SimError3> {
        self.blocks_mut("insert_payload")?.insert(payload)?;
        Ok(())
    }

    /// A worker for this simulation's node-block store (same model, same number of slots).
    ///
    /// Errors: [`SimError3::WrongStore`] with columns; [`SimError3::Sparse`] passed on from
    /// [`Sim3BlockWorker::new`].
    pub fn block_worker(&self) -> Result<Sim3BlockWorker, SimError3> {
        let ComplianceStore3::Blocks(store) = &self.cache else {
            return Err(SimError3::WrongStore { call: "block_worker", needs: "node-block", has: "columns" });
        };
        Ok(Sim3BlockWorker::new(Arc::clone(&self.model), store.cap())?)
    }

    /// With node blocks, on this thread between steps: [`Simulation3::requests_into`] (up to
    /// `max_nodes`), [`Sim3BlockWorker::compute`], [`Simulation3::insert_payload`]. Returns how
    /// many nodes it inserted. Allocates (the request list).
    ///
    /// Errors: those of the three.
    pub fn prefetch_blocks(&mut self, worker: &mut Sim3BlockWorker, max_nodes: usize) -> Result<usize, SimError3> {
        let mut reqs = Vec::new();
        self.requests_into(max_nodes, &mut reqs)?;
        if reqs.is_empty() {
            return Ok(0);
        }
        for p in worker.compute(&reqs)? {
            self.insert_payload(p)?;
        }
        Ok(reqs.len())
    }

    /// The static problem the last step solved: per working point its reference position,
    /// frame, prescribed displacement components, prescribed (friction) force in world
    /// components, and the simulation's force and displacement there. Allocates (not for the
    /// real-time thread).
    pub fn snapshot(&self) -> Snapshot3 {
        let points = Slot::all(self.pts.len())
            .map(|slot| {
                let p = &self.pts[slot.index()];
                let frame = self.solver.frame(slot);
                let disp =
                    |a: Axis| (self.solver.condition(slot, a) == Condition::Displacement).then(|| self.solver.prescribed_value(slot, a));
                let mut f = [0.0; 3];
                let mut any_force = false;
                for a in Axis::ALL3 {
                    if self.solver.condition(slot, a) == Condition::Force {
                        any_force = true;
                        let v = self.solver.prescribed_value(slot, a);
                        for c in 0..3 {
                            f[c] += v * frame[a.index()][c];
                        }
                    }
                }
                SnapshotPoint3 {
                    x_m: p.x_ref_m,
                    frame,
                    ut: disp(Axis::Axial),
                    un: disp(Axis::Lateral),
                    ub: disp(Axis::Binormal),
                    f_n: any_force.then_some(f),
                    force_n: self.solver.force_world(slot),
                    u_m: self.solver.displacement_world(slot),
                }
            })
            .collect();
        Snapshot3 { tick: self.out.tick, points }
    }

    /// Advances one tick towards the commanded base pose (stages in the module docs).
    ///
    /// Errors: [`SimError3::Pose`] for a non-finite or non-unit pose (nothing changes);
    /// [`SimError3::Mixed`] when the working solver refuses an update mid-tick.
    pub fn step(&mut self, commanded: BasePose3) -> Result<&StepOutput3, SimError3> {
        commanded.check().map_err(|source| SimError3::Pose { tick: self.tick, source })?;
        let len = self.params.needle_length_m;
        let prev_tip = match &self.flex {
            None => self.pose.point_at(len),
            Some(fx) => fx.rod.tip_m(),
        };
        let (pose, clamped) = self.pose.clamped_towards(&commanded, self.params.max_base_step_m, self.params.max_base_step_rad);
        if clamped {
            self.stats.clamped_ticks += 1;
        }
        let turned = pose.orientation != self.pose.orientation;
        let frame = pose.frame();
        self.axial_speed_m_per_s = dot(frame[0], sub(pose.position_m, self.pose.position_m)).abs() * self.params.tick_rate_hz;
        self.pose = pose;
        // 2. Frames and prescribed values.
        if let Some(fx) = self.flex.as_mut() {
            fx.rod.set_base(pose.position_m, frame);
            fx.refresh_frames(&mut self.solver, &self.pts, turned)?;
            fx.set_values(&mut self.solver, &mut self.pts);
        } else {
            for slot in Slot::all(self.pts.len()) {
                self.solver.set_frame(slot, frame)?;
            }
            self.set_prescribed_values(&frame);
        }
        // 3. Release of the points the tip withdrew past.
        for k in (0..self.pts.len()).rev() {
            let p = self.pts[k];
            let beyond = match &self.flex {
                None => dot(frame[0], sub(add(p.x_ref_m, p.u_world), pose.position_m)) > len,
                Some(fx) => fx.arc_of(&p, &self.solver.frame(Slot::new(k)), add(p.x_ref_m, p.u_world)) > len,
            };
            if p.state != PointState3::Tip && beyond {
                self.remove(Slot::new(k))?;
                self.stats.releases += 1;
            }
        }
        // 4. Capture, along the tip's tangent (a rigid needle's axis).
        let (axis_pose, axis_frame) = match &self.flex {
            None => (pose, frame),
            Some(fx) => {
                let tf = fx.rod.tip_frame();
                let tip = fx.rod.tip_m();
                let base_v = [tip[0] - len * tf[0][0], tip[1] - len * tf[0][1], tip[2] - len * tf[0][2]];
                (BasePose3::from_rotation(base_v, quaternion_of_frame(&tf)), tf)
            }
        };
        let captures_before = self.stats.captures;
        self.capture(prev_tip, &axis_pose, &axis_frame)?;
        // The bevel cuts sideways while the tip advances inside the tissue ([`flex`]).
        if let Some(fx) = self.flex.as_mut() {
            let advance = dot(axis_frame[0], sub(fx.rod.tip_m(), prev_tip));
            let inside = !self.pts.is_empty();
            let cut = self.params.regions[self.last_tip_region.unwrap_or(0)].cutting_force_n;
            fx.update_bevel(advance, inside, cut, self.stats.captures != captures_before);
        }
        // 5, 6. Friction and active set.
        self.update_friction(&frame, false, 0.0);
        let (mut iterations, mut converged) = self.resolve_active_set(&frame)?;
        // A flexible needle comes to equilibrium with the tick's forces; where that moves it
        // off the held points, the active set is solved again on the new shape.
        let mut shape_capped = false;
        for pass in 1..=flex::SHAPE_PASSES {
            let Some(fx) = self.flex.as_mut() else { break };
            let gap = fx.settle(&self.solver, &mut self.pts);
            if gap <= flex::SHAPE_GAP_TOL_M {
                break;
            }
            if pass == flex::SHAPE_PASSES {
                shape_capped = true;
                break;
            }
            fx.shape_passes += 1;
            fx.refresh_frames(&mut self.solver, &self.pts, false)?;
            fx.set_values(&mut self.solver, &mut self.pts);
            let (it, conv) = self.resolve_active_set(&frame)?;
            iterations += it;
            converged = conv;
        }
        // Tissue dragged past what it holds tears free ([`tear`]).
        if let Some((it, conv)) = self.tear_overloaded(&frame)? {
            iterations += it;
            converged = conv;
        }
        if !converged {
            self.stats.unconverged_ticks += 1;
        }
        self.stats.shape_capped_ticks += shape_capped as u64;
        self.solver.solve();
        // 7. Output.
        self.write_output(&frame, clamped, iterations, converged);
        self.out.shape_passes_capped = shape_capped;
        let target_frame = if self.flex.is_some() { axis_frame_now(self) } else { frame };
        self.update_targets(&target_frame);
        self.tick += 1;
        Ok(&self.out)
    }

    /// The arc coordinate of slot's reference position in its frame (a displacement's axial
    /// component adds to it): $t\cdot(X - x_b)$ for a rigid needle, [`flex::Flex3::ref_arc`]
    /// for a flexible one.
    fn ref_arc(&self, slot: Slot, frame: &[[f64; 3]; 3], base: [f64; 3]) -> f64 {
        let p = &self.pts[slot.index()];
        match &self.flex {
            None => dot(frame[0], sub(p.x_ref_m, base)),
            Some(fx) => fx.ref_arc(p, &self.solver.frame(slot)),
        }
    }

    /// Solves the working set: plainly for a rigid needle, coupled to the rod for a flexible one.
    fn solve_working(&mut self) {
        match self.flex.as_mut() {
            None => self.solver.solve(),
            Some(fx) => fx.solve(&mut self.solver, &self.pts, self.tick),
        }
    }

    /// The flexible needle's rod (`None` for a rigid needle): its shape, frames and counters.
    pub fn rod(&self) -> Option<&crate::rod3::Rod3> {
        self.flex.as_ref().map(|f| &f.rod)
    }

    /// Flexible needle: (shape passes beyond the first, shape updates that did not converge)
    /// over the simulation's life; `None` for a rigid needle.
    pub fn shape_stats(&self) -> Option<(u64, u64)> {
        self.flex.as_ref().map(|f| (f.shape_passes, f.shape_unconverged))
    }

    fn remove(&mut self, slot: Slot) -> Result<(), MixedError> {
        self.solver.remove_slot(slot)?;
        self.pts.swap_remove(slot.index());
        Ok(())
    }

    fn set_prescribed_values(&mut self, frame: &[[f64; 3]; 3]) {
        let base = self.pose.position_m;
        let len = self.params.needle_length_m;
        for slot in Slot::all(self.pts.len()) {
            let p = &self.pts[slot.index()];
            let d = sub(p.x_ref_m, base);
            self.solver.set_value(slot, Axis::Lateral, -dot(frame[1], d));
            self.solver.set_value(slot, Axis::Binormal, -dot(frame[2], d));
            match p.state {
                PointState3::Stuck => self.solver.set_value(slot, Axis::Axial, p.anchor_s_m - dot(frame[0], d)),
                PointState3::Tip => self.solver.set_value(slot, Axis::Axial, len - dot(frame[0], d)),
                PointState3::Slipping => {}
            }
        }
    }

    /// The displacement of any contact from the working forces of the last solve,
    /// $u_q = \sum_w W_{qw} f_w$ (with columns it needs the working points' columns, with node
    /// blocks also `q`'s nodes); `None` when a block is missing. $O(d)$.
    fn contact_displacement(&self, q: &ContactPoint) -> Option<[f64; 3]> {
        let mut u = [0.0; 3];
        for p in &self.pts {
            let b = self.cache.contact_block(q, &p.contact)?;
            for r in 0..3 {
                u[r] += b[r][0] * p.f_world[0] + b[r][1] * p.f_world[1] + b[r][2] * p.f_world[2];
            }
        }
        Some(u)
    }

    /// The material point $X$ at deformed position `p_m`: the fixed point of $X = p - u(X)$
    /// from $X_0 = p - u_0$; `Ok(None)` when it lies outside the mesh, `Err(c)` when the
    /// displacement at an iterate `c` needs blocks that are not cached.
    // The `Ok` value holds a contact as well: both variants are the same size, on the stack.
    #[allow(clippy::result_large_err)]
    fn material_point_at(&self, p_m: [f64; 3], u0: [f64; 3]) -> Result<Option<(ContactPoint, [f64; 3])>, ContactPoint> {
        let mut x = sub(p_m, u0);
        let tol = 1e-12 * self.sample_step_m;
        let mesh = self.model.mesh();
        let Ok(mut loc) = self.model.locate(x) else { return Ok(None) };
        for it in 0..LOCATE_ITERATIONS {
            if it > 0 {
                // The iterate usually stays in its tetrahedron: one barycentric test rather than
                // a search of the locator's cell.
                let w = barycentric(mesh.tet_points_m(loc.tet_idx), x);
                if w.iter().all(|&v| v >= -BARYCENTRIC_TOL) {
                    loc.weights = w;
                } else {
                    let Ok(l) = self.model.locate(x) else { return Ok(None) };
                    loc = l;
                }
            }
            let c = ContactPoint::in_tetrahedron(loc.tet_idx, loc.nodes, loc.weights);
            let next = sub(p_m, self.contact_displacement(&c).ok_or(c)?);
            let moved = dist(next, x);
            x = next;
            if moved <= tol {
                break;
            }
        }
        let Ok(loc) = self.model.locate(x) else { return Ok(None) };
        Ok(Some((ContactPoint::in_tetrahedron(loc.tet_idx, loc.nodes, loc.weights), x)))
    }

    fn push_approaching(&mut self, node: usize) {
        if self.model.is_fixed(node) {
            return;
        }
        if self.cache.contains(node) {
            self.stamp[node] = self.tick + 1;
        } else if !self.out.approaching.contains(&node) {
            if self.out.approaching.len() < MAX_APPROACHING {
                self.out.approaching.push(node);
            } else {
                self.stats.approaching_overflow += 1;
            }
        }
    }

    /// The approaching nodes (for prefetch), kept across ticks: nodes now cached or out of the
    /// band around the axis ahead of the tip (lateral distance and arc length within a
    /// tetrahedron diameter of the lookahead segment) leave the list; the axis ahead and a ring
    /// of six points around each of its stations are located [`LOOKAHEAD_SAMPLES_PER_TICK`]
    /// samples per tick, round robin (a point location costs microseconds: the whole segment
    /// each tick would cost tens), and the candidates' nodes (a waiting point's, then the tip's)
    /// go first. Sorted nearest first. $O(\text{list})$, no allocation.
    fn update_approaching(&mut self, candidates: [Option<ContactPoint>; 2], u_d: [f64; 3], axis_pose: &BasePose3, frame: &[[f64; 3]; 3]) {
        let len = self.params.needle_length_m;
        let look = self.params.lookahead_m;
        let h = self.sample_step_m;
        let band = self.max_diam_m;
        let base = axis_pose.position_m;
        let model = Arc::clone(&self.model);
        let nodes_m = model.mesh().nodes_m();
        let t = frame[0];
        let (s_lo, s_hi) = (len - 4.0 * h - band, len + look + band);
        let coords = |j: usize| {
            let d = sub(add(nodes_m[j], u_d), base);
            let s = dot(t, d);
            let lat = sub(d, [s * t[0], s * t[1], s * t[2]]);
            (s, dot(lat, lat).sqrt())
        };
        let cache = &self.cache;
        self.out.approaching.retain(|&j| {
            let (s, lat) = coords(j);
            !cache.contains(j) && lat <= band && s >= s_lo && s <= s_hi
        });
        if look > 0.0 {
            // Sample i of the round robin: station i mod n along the axis, offset across it by
            // the ring position i div n (none, or 0.5 h in one of six directions 60° apart).
            // An axis along a mesh line runs on tetrahedron edges and faces, where a point
            // location finds one of the tetrahedra around it; the material point a capture
            // locates later (deformed, through the fixed point) may lie in any of them.
            let n = ((look + 4.0 * h) / h).ceil() as u64 + 1;
            let (nrm, bin) = (frame[1], frame[2]);
            for k in 0..LOOKAHEAD_SAMPLES_PER_TICK {
                let i = (LOOKAHEAD_SAMPLES_PER_TICK * self.tick + k) % (LOOKAHEAD_RING * n);
                let (station, ring) = (i % n, i / n);
                let mut q = sub(axis_pose.point_at(len - 4.0 * h + station as f64 * h), u_d);
                if ring > 0 {
                    let phi = std::f64::consts::FRAC_PI_3 * ring as f64;
                    let (c, sn) = (0.5 * h * phi.cos(), 0.5 * h * phi.sin());
                    q = add(q, [c * nrm[0] + sn * bin[0], c * nrm[1] + sn * bin[1], c * nrm[2] + sn * bin[2]]);
                }
                if let Ok(loc) = self.model.locate(q) {
                    for node in loc.nodes {
                        self.push_approaching(node);
                    }
                }
            }
        }
        let key = |j: &usize| coords(*j).0;
        self.out.approaching.sort_unstable_by(|a, b| key(a).total_cmp(&key(b)));
        // The candidates' nodes go first, the first candidate's before the second's.
        for c in candidates.into_iter().rev().flatten() {
            for k in 0..4 {
                let node = c.nodes()[k].index();
                if self.model.is_fixed(node) || self.cache.contains(node) {
                    continue;
                }
                if let Some(pos) = self.out.approaching.iter().position(|&j| j == node) {
                    self.out.approaching.remove(pos);
                } else if self.out.approaching.len() == MAX_APPROACHING {
                    self.out.approaching.pop();
                    self.stats.approaching_overflow += 1;
                }
                self.out.approaching.insert(0, node);
            }
        }
    }

    /// Stage 4 (module docs), and the approaching nodes.
    fn capture(&mut self, prev_tip: [f64; 3], axis_pose: &BasePose3, frame: &[[f64; 3]; 3]) -> Result<(), SimError3> {
        let len = self.params.needle_length_m;
        let base = axis_pose.position_m;
        let t = frame[0];
        let has_tip = self.pts.iter().any(|p| p.state == PointState3::Tip);
        let distal = (0..self.pts.len()).max_by(|&a, &b| self.pts[a].s_prev_m.total_cmp(&self.pts[b].s_prev_m));
        let s_distal = distal.map(|k| if self.pts[k].state == PointState3::Tip { len } else { self.pts[k].s_prev_m });
        let u_d = distal.map_or([0.0; 3], |k| self.pts[k].u_world);
        // A waiting point counts as taken for the spacing of the next.
        let s_distal = self.pending.iter().map(|p| dot(t, sub(*p, base))).chain(s_distal).reduce(f64::max);
        let pending_missing = self.capture_pending(axis_pose, frame, u_d)?;
        let s_prev_tip = dot(t, sub(prev_tip, base));
        let advancing = len - s_prev_tip > 1e-9;
        let due = !has_tip && advancing && s_distal.is_none_or(|s| len - s >= self.params.spacing_m);
        if !due && let Some(first) = self.deferred_since_m.take() {
            // The tip stopped (or holds a point) before the waiting capture got its columns.
            self.push_pending(first);
        }
        let mut missing: Option<ContactPoint> = None;
        let mut candidate = if due {
            self.material_point_at(prev_tip, u_d).unwrap_or_else(|c| {
                missing = Some(c);
                None
            })
        } else {
            None
        };
        if candidate.is_some_and(|(c, x)| self.too_close(&c, x)) {
            candidate = None;
        }
        self.update_approaching([pending_missing, candidate.map(|c| c.0).or(missing)], u_d, axis_pose, frame);
        if missing.is_some() {
            // Node blocks: the fixed point needed a tetrahedron whose nodes are not cached.
            self.stats.column_deferrals += 1;
            self.defer_capture(prev_tip, t);
            return Ok(());
        }
        let Some((contact, x)) = candidate else { return Ok(()) };
        if self.pts.len() == self.params.max_contacts {
            self.stats.capacity_drops += 1;
            return Ok(());
        }
        if !self.cache.contains_contact(&contact) {
            self.stats.column_deferrals += 1;
            self.defer_capture(prev_tip, t);
            return Ok(());
        }
        let d = sub(x, base);
        let s_new = dot(t, sub(prev_tip, base));
        let region = self.region_of(&contact);
        let entering = self.pts.is_empty() || self.last_tip_region != Some(region);
        let rp: RegionNeedleParams = self.params.regions[region];
        if !self.add_held_point(contact, frame, d, len)? {
            return Ok(());
        }
        self.last_tip_region = Some(region);
        self.deferred_since_m = None;
        self.pts.push(Point {
            contact,
            x_ref_m: x,
            state: PointState3::Tip,
            anchor_s_m: s_new,
            s_prev_m: s_new,
            s_work_m: s_new,
            friction_n: 0.0,
            friction_new_n: 0.0,
            slip_sign: 1.0,
            release_force_n: if entering { rp.puncture_force_n } else { rp.cutting_force_n },
            region,
            f_world: [0.0; 3],
            u_world: sub(prev_tip, x),
            lat_ref_m: [-dot(frame[1], d), -dot(frame[2], d)],
            f_ref_local_n: [0.0; 3],
        });
        self.stats.captures += 1;
        Ok(())
    }

    /// The distance rule of a capture: whether the material point `contact` at reference
    /// position `x_m` lies within both its and a held point's tetrahedron diameters of one.
    fn too_close(&self, contact: &ContactPoint, x_m: [f64; 3]) -> bool {
        let diam = |c: &ContactPoint| c.tet_idx().map_or(0.0, |k| self.tet_diam_m[k]);
        self.pts.iter().any(|p| dist(p.x_ref_m, x_m) <= diam(contact).max(diam(&p.contact)) * (1.0 + 1e-9))
    }

    /// The mesh region of a material point's tetrahedron.
    fn region_of(&self, contact: &ContactPoint) -> usize {
        let tet = contact.tet_idx().expect("a material point lies in a tetrahedron");
        self.model.mesh().region_of_tet().get(tet).copied().unwrap_or(0)
    }

    /// Adds `contact` to the solver in `frame`, held on the axis at arc length `s_m`: its
    /// lateral and binormal displacements put its reference position (`d` = $X - x_b$) on the
    /// axis, its axial one at $s$ (the tip's capture: $s = L$). Returns `false` when its
    /// conditions depend on the others' (removed again and counted in `dependent_points`).
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses it for another reason.
    fn add_held_point(&mut self, contact: ContactPoint, frame: &[[f64; 3]; 3], d: [f64; 3], s_m: f64) -> Result<bool, SimError3> {
        let slot = self.solver.add_contact_in_frame(&self.cache, contact, *frame)?;
        let r = self
            .solver
            .set_condition(slot, Axis::Lateral, Condition::Displacement, -dot(frame[1], d))
            .and_then(|()| self.solver.set_condition(slot, Axis::Binormal, Condition::Displacement, -dot(frame[2], d)))
            .and_then(|()| self.solver.set_condition(slot, Axis::Axial, Condition::Displacement, s_m - dot(frame[0], d)));
        match r {
            Ok(()) => Ok(true),
            Err(MixedError::SingularPivot { .. }) => {
                self.solver.remove_slot(slot)?;
                self.stats.dependent_points += 1;
                Ok(false)
            }
            Err(e) => {
                self.solver.remove_slot(slot)?;
                Err(e.into())
            }
        }
    }

    /// A due capture whose columns are missing at `tip_m`. The tip keeps trying where it is
    /// each tick (a capture a tick or two late, as when an offline driver prefetches after the
    /// step, is taken at the tip as before); once the tip has gone `spacing_m` beyond where it
    /// first waited, that position waits in `pending` (the tissue point there is captured once
    /// its columns arrive, [`Self::capture_pending`]) and the next capture is due a spacing
    /// further.
    fn defer_capture(&mut self, tip_m: [f64; 3], t: [f64; 3]) {
        match self.deferred_since_m {
            None => self.deferred_since_m = Some(tip_m),
            Some(first) if dot(t, sub(tip_m, first)) >= self.params.spacing_m => {
                self.deferred_since_m = None;
                self.push_pending(first);
            }
            Some(_) => {}
        }
    }

    fn push_pending(&mut self, p_m: [f64; 3]) {
        if self.pending.len() < MAX_PENDING_CAPTURES {
            self.pending.push(p_m);
        } else {
            self.stats.pending_dropped += 1;
        }
    }

    /// The waiting points (issue 17: a live session's column worker behind the tip), oldest
    /// first, at most [`LATE_CAPTURES_PER_TICK`] per tick. The tissue point at a waiting
    /// position $p$ lies on the shaft now (the needle passed through it and nothing held it
    /// apart), at arc length $s = t \cdot (p - x_b)$: for a rigid needle the point of the axis
    /// there, for a flexible one $p$ itself. Its material point (the fixed point of
    /// [`Self::material_point_at`]) joins as a stuck shaft point anchored at $s$, with its
    /// lateral conditions as a tip capture's: no force step, the active set decides whether it
    /// slips. Dropped (counted) when the tip withdrew past it, when it lies outside the mesh or
    /// within a tetrahedron diameter of a held point, or when the working set is full.
    /// Returns the contact whose columns the first still-waiting point needs (for the
    /// prefetch), if any.
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses the point for a reason other than
    /// dependence.
    fn capture_pending(&mut self, axis_pose: &BasePose3, frame: &[[f64; 3]; 3], u_d: [f64; 3]) -> Result<Option<ContactPoint>, SimError3> {
        let len = self.params.needle_length_m;
        let base = axis_pose.position_m;
        let t = frame[0];
        let mut first_missing = None;
        let mut admitted = 0;
        let mut k = 0;
        while k < self.pending.len() {
            let p = self.pending[k];
            let s = dot(t, sub(p, base));
            if s > len {
                self.pending.remove(k);
                self.stats.pending_dropped += 1;
                continue;
            }
            if admitted == LATE_CAPTURES_PER_TICK {
                break;
            }
            let q = if self.flex.is_some() { p } else { axis_pose.point_at(s) };
            let (contact, x) = match self.material_point_at(q, u_d) {
                Err(c) => {
                    first_missing.get_or_insert(c);
                    k += 1;
                    continue;
                }
                Ok(None) => {
                    self.pending.remove(k);
                    self.stats.pending_dropped += 1;
                    continue;
                }
                Ok(Some(found)) => found,
            };
            if !self.cache.contains_contact(&contact) {
                first_missing.get_or_insert(contact);
                k += 1;
                continue;
            }
            self.pending.remove(k);
            if self.too_close(&contact, x) || self.pts.len() == self.params.max_contacts {
                self.stats.pending_dropped += 1;
                continue;
            }
            let d = sub(x, base);
            let region = self.region_of(&contact);
            if !self.add_held_point(contact, frame, d, s)? {
                continue;
            }
            self.pts.push(Point {
                contact,
                x_ref_m: x,
                state: PointState3::Stuck,
                anchor_s_m: s,
                s_prev_m: s,
                s_work_m: s,
                friction_n: 0.0,
                friction_new_n: 0.0,
                slip_sign: 1.0,
                release_force_n: self.params.regions[region].cutting_force_n,
                region,
                f_world: [0.0; 3],
                u_world: sub(q, x),
                lat_ref_m: [-dot(frame[1], d), -dot(frame[2], d)],
                f_ref_local_n: [0.0; 3],
            });
            self.stats.captures += 1;
            self.stats.late_captures += 1;
            admitted += 1;
        }
        Ok(first_missing)
    }

    /// Stage 5: the friction shares from the points' arc lengths (the anchor of a stuck point;
    /// a slipping one's at the end of the last tick, or in the current solution when
    /// `current`). Point $i$ between its neighbours' midpoints $[a_i, b_i]$ (the most proximal
    /// from its own $s$, the most distal to the tip) gets $\int_{L-b_i}^{L-a_i} q(\ell)\,d\ell$.
    /// Applied when a slipping point's share changes by more than `min_change_n` (always when
    /// not `current`). Returns the largest change.
    fn update_friction(&mut self, frame: &[[f64; 3]; 3], current: bool, min_change_n: f64) -> f64 {
        let len = self.params.needle_length_m;
        let base = self.pose.position_m;
        self.order.clear();
        for slot in Slot::all(self.pts.len()) {
            let s0 = self.ref_arc(slot, frame, base);
            let u_t = if current { self.solver.displacement_local(slot)[Axis::Axial] } else { 0.0 };
            let p = &mut self.pts[slot.index()];
            p.s_work_m = match p.state {
                PointState3::Stuck => p.anchor_s_m,
                PointState3::Slipping if current => s0 + u_t,
                PointState3::Slipping => p.s_prev_m,
                PointState3::Tip => continue,
            };
            self.order.push(slot);
        }
        let pts = &self.pts;
        self.order.sort_unstable_by(|&a, &b| pts[a.index()].s_work_m.total_cmp(&pts[b.index()].s_work_m));
        let k = self.order.len();
        let mut max_change: f64 = 0.0;
        for i in 0..k {
            let s = self.pts[self.order[i].index()].s_work_m;
            let lo = if i == 0 { s } else { 0.5 * (s + self.pts[self.order[i - 1].index()].s_work_m) };
            let hi = if i + 1 == k { len.max(s) } else { 0.5 * (s + self.pts[self.order[i + 1].index()].s_work_m) };
            let p = &mut self.pts[self.order[i].index()];
            let rp = &self.params.regions[p.region];
            p.friction_new_n =
                rp.friction_integral_n(len - hi, len - lo) + rp.friction_damping_n_s_per_m2 * self.axial_speed_m_per_s * (hi - lo);
            if p.state == PointState3::Slipping {
                max_change = max_change.max((p.friction_new_n - p.friction_n).abs());
            }
        }
        if max_change > min_change_n || !current {
            for i in 0..k {
                let slot = self.order[i];
                let p = &mut self.pts[slot.index()];
                p.friction_n = p.friction_new_n;
                if p.state == PointState3::Slipping && self.solver.condition(slot, Axis::Axial) == Condition::Force {
                    self.solver.set_value(slot, Axis::Axial, p.slip_sign * p.friction_n);
                }
            }
        }
        max_change
    }

    /// Stage 6: the bounded stick/slip iteration. Returns (iterations, converged).
    fn resolve_active_set(&mut self, frame: &[[f64; 3]; 3]) -> Result<(usize, bool), SimError3> {
        let base = self.pose.position_m;
        let max_iter = self.params.max_active_set_iterations;
        for iter in 1..=max_iter {
            self.solve_working();
            let total: f64 = self.pts.iter().map(|p| p.friction_n).sum();
            let tol = FRICTION_TOL * total.max(1e-12);
            for _ in 0..FRICTION_SWEEPS {
                if self.update_friction(frame, true, tol) <= tol {
                    break;
                }
                self.solve_working();
            }
            self.changes.clear();
            for slot in Slot::all(self.pts.len()) {
                let p = self.pts[slot.index()];
                let f_t = self.solver.force_local(slot)[Axis::Axial];
                let s_now = self.ref_arc(slot, frame, base) + self.solver.displacement_local(slot)[Axis::Axial];
                let change = match p.state {
                    PointState3::Tip if f_t > p.release_force_n => Some(Change::Puncture),
                    PointState3::Tip if f_t <= 0.0 => Some(Change::LetGo),
                    PointState3::Tip => None,
                    PointState3::Stuck => {
                        let threshold = (self.params.regions[p.region].static_friction_ratio * p.friction_n).max(1e-12);
                        (f_t.abs() > threshold).then(|| Change::Slip(f_t.signum()))
                    }
                    PointState3::Slipping => (p.slip_sign * (s_now - p.s_prev_m) >= -1e-12).then_some(Change::Stick(p.s_prev_m)),
                };
                if let Some(c) = change {
                    self.changes.push((slot, c));
                }
            }
            if self.changes.is_empty() {
                return Ok((iter, true));
            }
            self.changes.sort_unstable_by_key(|c| std::cmp::Reverse(c.0));
            for i in 0..self.changes.len() {
                let (slot, change) = self.changes[i];
                let s0 = self.ref_arc(slot, frame, base);
                match change {
                    Change::Puncture => {
                        let u_t = self.solver.displacement_local(slot)[Axis::Axial];
                        let p = &mut self.pts[slot.index()];
                        p.state = PointState3::Slipping;
                        p.slip_sign = 1.0;
                        p.s_prev_m = s0 + u_t;
                        let v = p.friction_n;
                        self.solver.set_condition(slot, Axis::Axial, Condition::Force, v)?;
                        self.stats.punctures += 1;
                    }
                    Change::LetGo => {
                        self.remove(slot)?;
                        self.stats.releases += 1;
                    }
                    Change::Slip(sign) => {
                        let p = &mut self.pts[slot.index()];
                        p.state = PointState3::Slipping;
                        p.slip_sign = sign;
                        let v = sign * p.friction_n;
                        self.solver.set_condition(slot, Axis::Axial, Condition::Force, v)?;
                        self.stats.stick_to_slip += 1;
                    }
                    Change::Stick(anchor) => {
                        let p = &mut self.pts[slot.index()];
                        p.state = PointState3::Stuck;
                        p.anchor_s_m = anchor;
                        self.solver.set_condition(slot, Axis::Axial, Condition::Displacement, anchor - s0)?;
                        self.stats.slip_to_stick += 1;
                    }
                }
            }
        }
        Ok((max_iter, false))
    }

    /// Stage 7: forces, wrench, tip, points; each point's arc length for the next tick; the
    /// working points' nodes marked in use.
    fn write_output(&mut self, frame: &[[f64; 3]; 3], clamped: bool, iterations: usize, converged: bool) {
        let base = self.pose.position_m;
        let len = self.params.needle_length_m;
        let out = &mut self.out;
        out.tick = self.tick;
        out.time_s = self.tick as f64 / self.params.tick_rate_hz;
        out.pose = self.pose;
        out.clamped = clamped;
        out.tip_m = match &self.flex {
            None => self.pose.point_at(len),
            Some(fx) => fx.rod.tip_m(),
        };
        out.active_set_iterations = iterations;
        out.converged = converged;
        out.contacts.clear();
        let (mut force, mut torque, mut s_min) = ([0.0; 3], [0.0; 3], f64::INFINITY);
        for slot in Slot::all(self.pts.len()) {
            let f = self.solver.force_world(slot);
            let u = self.solver.displacement_world(slot);
            let p = &mut self.pts[slot.index()];
            p.f_world = f;
            p.u_world = u;
            let x = add(p.x_ref_m, u);
            let r = sub(x, base);
            let neg = [-f[0], -f[1], -f[2]];
            force = add(force, neg);
            torque = add(torque, cross(r, neg));
            let (s, point_frame) = match &self.flex {
                None => (dot(frame[0], r), *frame),
                Some(fx) => {
                    let pf = self.solver.frame(slot);
                    (fx.arc_of(p, &pf, x), pf)
                }
            };
            p.s_prev_m = s;
            s_min = s_min.min(s);
            for n in p.contact.nodes() {
                self.stamp[n.index()] = self.tick + 1;
            }
            out.contacts.push(ContactOut3 {
                state: p.state,
                frame: point_frame,
                x_ref_m: p.x_ref_m,
                x_m: x,
                force_n: f,
                friction_n: p.friction_n,
            });
        }
        out.base_force_n = force;
        out.base_torque_nm = torque;
        out.axial_force_n = -dot(frame[0], force);
        out.inserted_length_m = if s_min.is_finite() { (len - s_min).max(0.0) } else { 0.0 };
    }
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The unit quaternion of a frame with rows $[t, n, b]$ (the rotation whose columns they are).
fn quaternion_of_frame(f: &[[f64; 3]; 3]) -> nalgebra::UnitQuaternion<f64> {
    let m = nalgebra::Matrix3::new(f[0][0], f[1][0], f[2][0], f[0][1], f[1][1], f[2][1], f[0][2], f[1][2], f[2][2]);
    nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(m))
}

/// The tip's frame of a flexible needle (the axis the targets' "ahead" is measured along).
fn axis_frame_now(sim: &Simulation3) -> [[f64; 3]; 3] {
    sim.flex.as_ref().map_or_else(|| sim.pose.frame(), |f| f.rod.tip_frame())
}
