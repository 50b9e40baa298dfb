//! The simulation's persistent state: what one tick hands to the next (pose, working set and its
//! solver, column cache, needle shape, counters). Everything here is sized when the simulation
//! is built; a step changes values, never capacities.

use crate::beam::NeedleCurve;
use crate::compliance::ComplianceCache;
use crate::contact::ContactPoint;
use crate::ids::{NodeIdx, Slot};
use crate::mixed::{MixedError, MixedSolver};
use crate::needle::{BasePose, FlexibleNeedle};

use super::{Divergence, SimStats};

/// The contact state of a needle node (the paper's Fig. 5a).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeState {
    /// Held at a fixed point of the shaft.
    Stuck,
    /// Sliding along the shaft against friction.
    Slipping,
    /// Carried ahead of the tip until puncture.
    Tip,
}

impl NodeState {
    /// Lower-case name, as written in files.
    pub fn as_str(&self) -> &'static str {
        match self {
            NodeState::Stuck => "stuck",
            NodeState::Slipping => "slipping",
            NodeState::Tip => "tip",
        }
    }
}

/// One needle contact: a mesh node or a material point in the working set, and its contact
/// state. (Named after the paper's needle nodes; with material-point contact it is a point.)
#[derive(Debug, Clone, Copy)]
pub(super) struct NeedleNode {
    /// Where the contact sits in the mesh.
    pub contact: ContactPoint,
    /// Its reference (undeformed) position $X$.
    pub x_ref_m: [f64; 2],
    pub state: NodeState,
    /// Shaft point a stuck node is held at.
    pub anchor_s_m: f64,
    /// Arc length at the end of the previous tick.
    pub s_prev_m: f64,
    /// Kinetic friction share.
    pub friction_n: f64,
    /// A share being computed (within the friction stage).
    pub friction_new_n: f64,
    /// Shaft position used for the friction shares and the shape update (within a stage).
    pub s_work_m: f64,
    /// Direction of the friction force on the tissue along $t$ while slipping (±1).
    pub slip_sign: f64,
    /// Axial force at which a tip node is released.
    pub release_force_n: f64,
    /// The mesh region the node belongs to (index into [`super::SimParams::regions`]).
    pub region: usize,
    /// Lateral offset from the shaft the node is held at (a bevel tip's node keeps the offset it
    /// was cut at when punctured; 0 otherwise).
    pub lat_offset_m: f64,
    /// The lateral value that puts the node on the reference shape (flexible needle).
    pub lateral_ref_m: f64,
    /// The node's force on the tissue (in its frame) the reference shape carries.
    pub force_ref_local_n: [f64; 2],
    /// Viscous history (all zero in an elastic tissue; [`crate::viscous`]).
    pub visc: crate::viscous::History<2>,
}

impl NeedleNode {
    /// The position the working solver's displacement is measured from: the reference
    /// position shifted by the viscous history, $X + \tilde u$ is where the tissue point is
    /// ([`crate::viscous`]; $X$ itself in an elastic tissue).
    #[inline]
    pub fn x_kin_m(&self) -> [f64; 2] {
        [self.x_ref_m[0] + self.visc.shift_m[0], self.x_ref_m[1] + self.visc.shift_m[1]]
    }

    /// The arc length the node's frame is attached to: the anchor of a stuck node, last tick's
    /// position of a slipping one, the tip's arc length `s_tip_m` for the tip's node.
    #[inline]
    pub fn s_ref_m(&self, s_tip_m: f64) -> f64 {
        match self.state {
            NodeState::Stuck => self.anchor_s_m,
            NodeState::Slipping => self.s_prev_m,
            NodeState::Tip => s_tip_m,
        }
    }
}

/// The working set: the needle contacts by slot, the solver whose slots they are, and the map
/// from mesh node to slot for node contacts. Architecture invariant: `nodes[k]`, the solver's
/// slot `k` and (for a node contact) `slot_of_node[nodes[k].contact]` always agree (only
/// [`WorkingSet::push`] and [`WorkingSet::remove`] change them).
pub(super) struct WorkingSet {
    pub solver: MixedSolver,
    /// The needle nodes, indexed by slot.
    pub nodes: Vec<NeedleNode>,
    slot_of_node: Vec<Option<Slot>>,
    /// Each slot's force on the tissue and displacement (world) as last written out: the loads
    /// of [`super::capture::node_displacement`] between steps.
    pub f_world: Vec<[f64; 2]>,
    pub u_world: Vec<[f64; 2]>,
    /// The needle's axial speed over the tick, $|(b_k - b_{k-1})\cdot t|/\Delta t$ (m/s): the
    /// rate-dependent friction's slip speed $v$ ([`crate::needle`]; the tissue at rest).
    pub axial_speed_m_per_s: f64,
    /// The base advanced along the needle's axis over the tick, $(b_k - b_{k-1})\cdot t > 0$:
    /// the tip cuts (energy-based cutting applies its force only then).
    pub advancing: bool,
}

impl WorkingSet {
    /// An empty working set for a mesh of `n_nodes` nodes with room for `cap` needle nodes.
    pub fn new(n_nodes: usize, cap: usize) -> Self {
        Self {
            solver: MixedSolver::with_capacity(cap),
            nodes: Vec::with_capacity(cap),
            slot_of_node: vec![None; n_nodes],
            f_world: Vec::with_capacity(cap),
            u_world: Vec::with_capacity(cap),
            axial_speed_m_per_s: 0.0,
            advancing: false,
        }
    }
    /// Number of needle nodes.
    #[inline]
    pub fn len(&self) -> usize {
        self.nodes.len()
    }
    /// The slots `0..len`.
    #[inline]
    pub fn slots(&self) -> impl DoubleEndedIterator<Item = Slot> + ExactSizeIterator + use<> {
        Slot::all(self.nodes.len())
    }
    /// The needle node in `slot`.
    #[inline]
    pub fn node(&self, slot: Slot) -> &NeedleNode {
        &self.nodes[slot.index()]
    }
    /// The needle node in `slot`, mutable.
    #[inline]
    pub fn node_mut(&mut self, slot: Slot) -> &mut NeedleNode {
        &mut self.nodes[slot.index()]
    }
    /// Whether mesh node `node` is a needle node (a node contact).
    #[inline]
    pub fn contains(&self, node: NodeIdx) -> bool {
        self.slot_of_node[node.index()].is_some()
    }
    /// Records `nn`, just added to the solver in `slot` (the next free one).
    pub fn push(&mut self, slot: Slot, nn: NeedleNode) {
        debug_assert_eq!(slot.index(), self.nodes.len(), "slots are dense");
        if let Some(j) = nn.contact.as_node() {
            self.slot_of_node[j.index()] = Some(slot);
        }
        self.nodes.push(nn);
        self.f_world.push([0.0; 2]);
        self.u_world.push([0.0; 2]);
    }
    /// Removes `slot` from the solver and the set; the last slot moves into its place.
    ///
    /// Errors: those of [`MixedSolver::remove_slot`] (the set is then unchanged).
    pub fn remove(&mut self, slot: Slot) -> Result<(), MixedError> {
        self.solver.remove_slot(slot)?;
        let k = slot.index();
        let gone = self.nodes.swap_remove(k);
        self.f_world.swap_remove(k);
        self.u_world.swap_remove(k);
        if let Some(j) = gone.contact.as_node() {
            self.slot_of_node[j.index()] = None;
        }
        if k < self.nodes.len()
            && let Some(j) = self.nodes[k].contact.as_node()
        {
            self.slot_of_node[j.index()] = Some(slot);
        }
        Ok(())
    }
}

/// The persistent state of a flexible needle: its shape and which side its bevel faces.
pub(super) struct FlexState {
    pub curve: NeedleCurve,
    /// Bevel force ratio $\beta$ (0 for a symmetric tip), from the parameters.
    pub bevel_ratio: f64,
    /// Bevel side $s_b$ (±1), flipped by [`super::Simulation::flip_bevel`].
    pub bevel_side: f64,
}

impl FlexState {
    pub fn new(f: &FlexibleNeedle, pose: BasePose, cap: usize) -> Self {
        Self { curve: NeedleCurve::new(f, pose, cap), bevel_ratio: f.bevel_force_ratio, bevel_side: f.bevel_side }
    }
    /// The bevel side the output reports: $s_b$, or 0 for a symmetric tip.
    pub fn reported_bevel_side(&self) -> f64 {
        if self.bevel_ratio > 0.0 { self.bevel_side } else { 0.0 }
    }
}

/// The first divergence of the simulation; every later step fails with it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Diverged {
    pub tick: u64,
    pub what: Divergence,
    pub value: f64,
    pub bound: f64,
}

/// Everything a tick hands to the next.
pub(super) struct State {
    /// The base pose applied by the last step (after clamping).
    pub pose: BasePose,
    pub ws: WorkingSet,
    /// Compliance columns by mesh node; filled by prefetch, workers, or a step's miss.
    pub cache: ComplianceCache,
    /// The flexible needle's shape (`None` for a rigid needle).
    pub flex: Option<FlexState>,
    /// The region the tip last entered (a tip node entering a new region needs its puncture
    /// force rather than its cutting force).
    pub last_tip_region: Option<usize>,
    /// Whether each target has been hit at any tick so far.
    pub target_hit: Vec<bool>,
    /// The number of the next tick.
    pub tick: u64,
    pub stats: SimStats,
    pub diverged: Option<Diverged>,
    /// The solver's update count (pivots, rotations, additions, removals) when the tick began:
    /// the base of the per-tick budget ([`super::param_limits::MAX_UPDATES_PER_TICK`]).
    pub updates_at_tick_start: u64,
    /// The cache's use stamps and eviction sweep.
    pub columns_lru: ColumnLru,
    /// The hybrid matrix's round-off check (`drift.rs`).
    pub drift: crate::drift::DriftCheck,
}

/// When each node's cached columns were last used, for eviction: `stamp[j]` is 1 + the last
/// tick at which node `j` was a working contact's node or in the lookahead (0: never).
#[derive(Debug, Clone)]
pub(super) struct ColumnLru {
    pub stamp: Vec<u64>,
    /// The next cache slot the sweep visits.
    pub cursor: usize,
}

impl ColumnLru {
    pub fn new(n_nodes: usize) -> Self {
        Self { stamp: vec![0; n_nodes], cursor: 0 }
    }
    /// Marks `node_idx` as used at tick `tick`.
    #[inline]
    pub fn touch(&mut self, node_idx: usize, tick: u64) {
        self.stamp[node_idx] = tick + 1;
    }
}
