//! The needle–tissue insertion simulation: one [`Simulation::step`] per haptic tick, from the
//! commanded base pose to forces, needle-node states, tip and targets.
//!
//! A step, in order (each stage a method taking the simulation's explicit state):
//! 1. **Pose**: reject non-finite poses, clamp jumps larger than the configured step.
//! 2. **Frames and values**: rotate every needle node's frame with the needle (section 4.2) and
//!    set its prescribed values: lateral $u_n = -n\cdot(X-b)$ keeps the node on the shaft, axial
//!    $u_t = s_a - t\cdot(X-b)$ holds a stuck node at its shaft point $s_a$ (the tip node at $s = L$).
//! 3. **Release**: shaft nodes the tip has withdrawn past leave the working set.
//! 4. **Capture**: nodes near the tip (spatial grid, never a scan) whose deformed position the tip
//!    passed within the capture radius become needle nodes. If no node is carried by the tip,
//!    the most distal one is (puncture: it is pushed until its axial reaction exceeds the
//!    region's puncture force, or its cutting force inside a region).
//! 5. **Friction**: each shaft node gets the integral of the friction distribution over its
//!    tributary segment (see [`crate::needle`]).
//! 6. **Active set**: solve; stuck nodes whose axial force exceeds static friction slip, slipping
//!    nodes whose relative motion stopped or reversed stick, the tip node punctures or, when it no
//!    longer pushes, lets go; repeat (bounded), each change an $O(d^2)$ update.
//! 7. **Output**: force and torque on the needle base, $F = -\sum_i f_i$, $\tau = \sum_i (p_i - b)\times(-f_i)$,
//!    node states, tip, targets.
//!
//! A flexible needle ([`crate::beam`]) changes stages 1, 2, 4, 6 and 7: frames follow the bent
//! shape's local tangent, prescribed values put nodes on the bent shape, the tip captures along
//! its own tangent, every solve of the working set includes the needle's lateral compliance (one
//! small dense solve), and after the tick the shape is brought to equilibrium with the new
//! forces. A bevel tip's node carries a lateral force $-s_b\beta f_t$ instead of a lateral
//! displacement, so the tip cuts sideways and the needle curves towards its bevel side.
//!
//! The tissue factorisation is never touched: compliance columns come from the cache, computed
//! ahead of time for the nodes the tip approaches ([`Simulation::prefetch_columns`]), and counted
//! when a step has to compute one itself.

use std::sync::Arc;

use crate::beam::{CoupledNode, Coupling, NeedleCurve};
use crate::compliance::{ColumnScratch, ComplianceCache, TissueError, TissueModel};
use crate::mixed::{Condition, MixedError, MixedSolver};
use crate::needle::{BasePose, NeedleShape, RegionNeedleParams};
use crate::spatial::NodeGrid;

/// A target embedded in the tissue: a point (radius 0) or a small disc.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetParams {
    pub name: String,
    pub center_m: [f64; 2],
    pub radius_m: f64,
}

/// Everything the simulation needs besides the tissue model.
#[derive(Debug, Clone, PartialEq)]
pub struct SimParams {
    pub needle: NeedleShape,
    pub initial_pose: BasePose,
    /// A node whose deformed position lies within this lateral distance of the shaft line when
    /// the tip passes it becomes a needle node.
    pub capture_radius_m: f64,
    /// Capacity of the working set.
    pub max_needle_nodes: usize,
    /// Needle parameters per tissue region (one per mesh region).
    pub regions: Vec<RegionNeedleParams>,
    pub targets: Vec<TargetParams>,
    pub tick_rate_hz: f64,
    /// Largest base translation accepted in one tick; larger jumps are clamped.
    pub max_base_step_m: f64,
    /// Largest base rotation accepted in one tick; larger jumps are clamped.
    pub max_base_step_rad: f64,
    /// Bound on the stick/slip iterations within one tick.
    pub max_active_set_iterations: usize,
    /// How far ahead of the tip nodes are reported as approaching (for column prefetch).
    pub lookahead_m: f64,
}

impl SimParams {
    /// Checks every value that does not need the mesh (ranges, finiteness, capacities); the
    /// message names the field and its allowed range. [`Simulation::new`] calls it first.
    pub fn validate(&self) -> Result<(), SimError> {
        use param_limits::*;
        let bad = |m: String| Err(SimError::InvalidParams(m));
        self.needle.validate().map_err(SimError::InvalidParams)?;
        if !self.initial_pose.is_finite() {
            let p = self.initial_pose;
            return bad(format!("initial_pose = ({}, {}, {}) must be finite", p.x_m, p.y_m, p.theta_rad));
        }
        let positive = [
            ("capture_radius_m", self.capture_radius_m),
            ("tick_rate_hz", self.tick_rate_hz),
            ("max_base_step_m", self.max_base_step_m),
            ("max_base_step_rad", self.max_base_step_rad),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return bad(format!("{name} = {v} must be finite and > 0"));
            }
        }
        if !(self.lookahead_m.is_finite() && self.lookahead_m >= 0.0) {
            return bad(format!("lookahead_m = {} must be finite and ≥ 0", self.lookahead_m));
        }
        if self.max_needle_nodes == 0 || self.max_needle_nodes > MAX_NEEDLE_NODES {
            return bad(format!("max_needle_nodes = {} must be in 1..={MAX_NEEDLE_NODES}", self.max_needle_nodes));
        }
        if self.needle.flexible().is_some() && self.max_needle_nodes > MAX_NEEDLE_NODES_FLEXIBLE {
            return bad(format!(
                "max_needle_nodes = {} must be ≤ {MAX_NEEDLE_NODES_FLEXIBLE} with a flexible needle",
                self.max_needle_nodes
            ));
        }
        if !(1..=MAX_ACTIVE_SET_ITERATIONS).contains(&self.max_active_set_iterations) {
            return bad(format!(
                "max_active_set_iterations = {} must be in 1..={MAX_ACTIVE_SET_ITERATIONS}",
                self.max_active_set_iterations
            ));
        }
        for t in &self.targets {
            if !(t.radius_m.is_finite() && t.radius_m >= 0.0) {
                return bad(format!("target '{}': radius_m = {} must be finite and ≥ 0", t.name, t.radius_m));
            }
            if !(t.center_m[0].is_finite() && t.center_m[1].is_finite()) {
                return bad(format!("target '{}': center_m {:?} is not finite", t.name, t.center_m));
            }
        }
        Ok(())
    }
}

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

/// Errors of the simulation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError {
    /// A parameter is invalid; the message names it.
    #[error("invalid simulation parameter: {0}")]
    InvalidParams(String),
    /// The commanded pose has a NaN or infinite component; the state is unchanged.
    #[error("tick {tick}: the commanded base pose ({x_m}, {y_m}, {theta_rad}) is not finite; the pose was rejected and the state kept")]
    NonFinitePose { tick: u64, x_m: f64, y_m: f64, theta_rad: f64 },
    /// The tissue model failed (computing a column).
    #[error(transparent)]
    Tissue(#[from] TissueError),
    /// The working-set solver failed.
    #[error(transparent)]
    Mixed(#[from] MixedError),
    /// A step's result is not finite or exceeds a physical bound derived from the scene
    /// ([`DivergenceBounds`]): the solve diverged. The step's output is not written (the last
    /// good one stays in [`Simulation::output`]) and every later step returns this error again:
    /// the simulation is faulted for good.
    #[error("tick {tick}: the solve diverged: {what} = {value:.3e} {unit} is not within the bound {bound:.3e} {unit}", unit = what.unit())]
    Diverged { tick: u64, what: Divergence, value: f64, bound: f64 },
}

/// Which quantity of a step diverged (see [`SimError::Diverged`]). `Copy` and coded as a small
/// integer, so a real-time thread can store it in an atomic and name it later.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Divergence {
    /// The magnitude of the force of the tissue on the needle base, $|F|$.
    Force = 1,
    /// The torque of the tissue on the needle about the base, $|\tau|$.
    Torque = 2,
    /// The magnitude of one needle node's force on the tissue.
    NodeForce = 3,
    /// The magnitude of one needle node's displacement.
    Displacement = 4,
    /// The length of shaft in the tissue.
    InsertedLength = 5,
    /// A point of the needle's shape (a joint of a flexible needle, or its tip) is not finite,
    /// or lies farther from the base than the needle is long.
    NeedleShape = 6,
}

impl Divergence {
    /// The quantity's name, as in messages.
    pub fn as_str(&self) -> &'static str {
        match self {
            Divergence::Force => "|force|",
            Divergence::Torque => "|torque|",
            Divergence::NodeForce => "|needle node force|",
            Divergence::Displacement => "|needle node displacement|",
            Divergence::InsertedLength => "inserted length",
            Divergence::NeedleShape => "needle shape distance from the base",
        }
    }
    /// The unit of the value and the bound.
    pub fn unit(&self) -> &'static str {
        match self {
            Divergence::Force | Divergence::NodeForce => "N",
            Divergence::Torque => "N·m",
            Divergence::Displacement | Divergence::InsertedLength | Divergence::NeedleShape => "m",
        }
    }
    /// The code stored by a real-time thread (never 0, which means "no fault").
    pub fn code(&self) -> u8 {
        *self as u8
    }
    /// The quantity of a code from [`Divergence::code`].
    pub fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            1 => Divergence::Force,
            2 => Divergence::Torque,
            3 => Divergence::NodeForce,
            4 => Divergence::Displacement,
            5 => Divergence::InsertedLength,
            6 => Divergence::NeedleShape,
            _ => return None,
        })
    }
}

impl std::fmt::Display for Divergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

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

/// Limits on the parameters that size per-step storage or bound a tick's work.
pub mod param_limits {
    /// Largest working-set capacity (the hybrid matrix is its square: 4096² × 8 B = 134 MB).
    pub const MAX_NEEDLE_NODES: usize = 4096;
    /// Largest working-set capacity with a flexible needle (its coupling is dense too).
    pub const MAX_NEEDLE_NODES_FLEXIBLE: usize = 1024;
    /// Largest bound on the stick/slip iterations of one tick.
    pub const MAX_ACTIVE_SET_ITERATIONS: usize = 10_000;
}

/// One needle node in a step's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeedleNodeOut {
    pub node_idx: usize,
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
    /// Nodes ahead of the tip whose compliance columns are not cached yet.
    pub approaching: Vec<usize>,
    pub active_set_iterations: usize,
    pub converged: bool,
    /// The commanded pose was clamped this tick.
    pub clamped: bool,
}

/// Counters over the simulation's life.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SimStats {
    pub ticks: u64,
    /// Columns a step had to compute itself (the prefetch did not have them ready).
    pub column_misses: u64,
    pub clamped_ticks: u64,
    pub rejected_poses: u64,
    pub unconverged_ticks: u64,
    pub captures: u64,
    pub releases: u64,
    pub punctures: u64,
    pub stick_to_slip: u64,
    pub slip_to_stick: u64,
    /// Captures dropped because the working set was full.
    pub capacity_drops: u64,
    /// Flexible needle: shape updates that did not converge within their iteration bound.
    pub shape_unconverged: u64,
    /// Bevel flips commanded.
    pub bevel_flips: u64,
    /// Extra solves of the working set on a settled needle shape (flexible needle).
    pub shape_passes: u64,
}

#[derive(Debug, Clone, Copy)]
struct NeedleNode {
    node_idx: usize,
    state: NodeState,
    /// Shaft point a stuck node is held at.
    anchor_s_m: f64,
    /// Arc length at the end of the previous tick.
    s_prev_m: f64,
    /// Kinetic friction share.
    friction_n: f64,
    /// A share being computed (scratch).
    friction_new_n: f64,
    /// Shaft position used for the friction shares (scratch).
    s_work_m: f64,
    /// Direction of the friction force on the tissue along $t$ while slipping (±1).
    slip_sign: f64,
    /// Axial force at which a tip node is released.
    release_force_n: f64,
    region: usize,
    /// Lateral offset from the shaft the node is held at (a bevel tip's node keeps the offset it
    /// was cut at when punctured; 0 otherwise).
    lat_offset_m: f64,
    /// The lateral value that puts the node on the reference shape (flexible needle).
    lateral_ref_m: f64,
    /// The node's force on the tissue (in its frame) the reference shape carries.
    force_ref_local_n: [f64; 2],
}

impl NeedleNode {
    /// The arc length the node's frame is attached to.
    fn s_ref_m(&self, s_tip_m: f64) -> f64 {
        match self.state {
            NodeState::Stuck => self.anchor_s_m,
            NodeState::Slipping => self.s_prev_m,
            NodeState::Tip => s_tip_m,
        }
    }
}

/// A frame change from the needle's bending smaller than this (rad) is not applied to a working
/// node (each one costs an $O(d^2)$ update): the lateral direction is then off by at most this
/// angle, a position error of this times the node's slip within one tick (1 nm at 10 mm/s and
/// 1 kHz), never accumulated because the values are recomputed in the node's frame every tick.
/// Rotations of the base are applied exactly, as for the rigid needle. (At 1e-5 rad a bending
/// needle turned ~19 frames a tick on the Fig. 4 path, 100 × 100: twice the step time.)
const FRAME_TOL_RAD: f64 = 1e-4;

/// Largest lateral distance (m) between a needle node and the settled needle shape left without
/// another solve on the new shape (1 µm: a thousandth of a typical capture radius).
const SHAPE_GAP_TOL_M: f64 = 1e-6;

/// Bound on the shape passes (solve, settle) per tick.
const SHAPE_PASSES: usize = 4;

/// The flexible needle's state: its shape and the coupling of each solver to it.
struct Flex {
    curve: NeedleCurve,
    coupling: Coupling,
    probe_coupling: Coupling,
    probe_curve: NeedleCurve,
    nodes: Vec<CoupledNode>,
    bevel_ratio: f64,
    bevel_side: f64,
    /// The solver update count and tick $G$ was computed for.
    g_for: Option<(u64, u64)>,
}

#[derive(Debug, Clone)]
struct LocatedTarget {
    nodes: [usize; 3],
    bary: [f64; 3],
    radius_m: f64,
    hit: bool,
}

/// What changed in one active-set pass for one slot.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Change {
    Puncture,
    LetGo,
    Slip(f64),
    Stick(f64),
}

const NO_SLOT: usize = usize::MAX;

/// A frame on the needle: coordinates $(s_0 + t\cdot(p - o),\ n\cdot(p - o))$ of a point $p$.
#[derive(Debug, Clone, Copy)]
struct Frame {
    origin: [f64; 2],
    s0: f64,
    t: [f64; 2],
    n: [f64; 2],
}

impl Frame {
    fn new(origin: [f64; 2], s0: f64, angle_rad: f64) -> Self {
        let (sn, cs) = angle_rad.sin_cos();
        Self { origin, s0, t: [cs, sn], n: [-sn, cs] }
    }
    /// The straight rigid needle's frame (the same arithmetic as [`NeedleShape::project`]).
    fn rigid(pose: &BasePose) -> Self {
        Self { origin: pose.position_m(), s0: 0.0, t: pose.axis(), n: pose.normal() }
    }
    fn coords(&self, p: [f64; 2]) -> (f64, f64) {
        let d = [p[0] - self.origin[0], p[1] - self.origin[1]];
        let s = self.t[0] * d[0] + self.t[1] * d[1];
        (if self.s0 == 0.0 { s } else { self.s0 + s }, self.n[0] * d[0] + self.n[1] * d[1])
    }
}

/// Bound on the friction-share sweeps per active-set iteration.
const FRICTION_SWEEPS: usize = 6;

/// The friction shares have converged when no slipping node's share changes by more than this
/// fraction of the total friction (1 µN per newton: far below what a hand or a device resolves).
const FRICTION_TOL: f64 = 1e-6;

/// The simulation of one needle in one tissue.
pub struct Simulation {
    model: Arc<TissueModel>,
    params: SimParams,
    cache: ComplianceCache,
    solver: MixedSolver,
    /// A copy of the solver for probing (the stiffness Jacobian), allocated once.
    probe: MixedSolver,
    col_scratch: ColumnScratch,
    col_buf: Vec<f64>,
    grid: NodeGrid,
    is_boundary: Vec<bool>,
    node_region: Vec<usize>,
    targets: Vec<LocatedTarget>,
    pose: BasePose,
    nodes: Vec<NeedleNode>,
    slot_of_node: Vec<usize>,
    f_world: Vec<[f64; 2]>,
    u_world: Vec<[f64; 2]>,
    last_tip_region: Option<usize>,
    order: Vec<usize>,
    candidates: Vec<usize>,
    captured: Vec<(usize, f64, f64)>,
    changes: Vec<(usize, Change)>,
    flex: Option<Box<Flex>>,
    out: StepOutput,
    stats: SimStats,
    tick: u64,
    bounds: DivergenceBounds,
    /// Set by the first diverged step: (tick, quantity, value, bound); every later step fails.
    diverged: Option<(u64, Divergence, f64, f64)>,
}

impl Simulation {
    /// Validates the parameters against the model and sets up the simulation (spatial grid,
    /// boundary nodes, target locations, all per-step storage).
    pub fn new(model: Arc<TissueModel>, params: SimParams) -> Result<Self, SimError> {
        let mesh = model.mesh();
        let bad = |m: String| Err(SimError::InvalidParams(m));
        params.validate()?;
        if params.regions.len() != mesh.region_names().len() {
            return bad(format!(
                "the mesh has {} region(s) ({}) but needle parameters were given for {}",
                mesh.region_names().len(),
                mesh.region_names().join(", "),
                params.regions.len()
            ));
        }
        for (r, name) in params.regions.iter().zip(mesh.region_names()) {
            r.validate(name).map_err(SimError::InvalidParams)?;
        }
        let mut targets = Vec::with_capacity(params.targets.len());
        for t in &params.targets {
            let (nodes, bary) = locate(mesh, t.center_m)
                .ok_or_else(|| SimError::InvalidParams(format!("target '{}' at {:?} lies outside the mesh", t.name, t.center_m)))?;
            targets.push(LocatedTarget { nodes, bary, radius_m: t.radius_m, hit: false });
        }
        let n_nodes = mesh.n_nodes();
        // Boundary nodes: on an edge used by one triangle only.
        let mut edges: Vec<(usize, usize)> = Vec::with_capacity(3 * mesh.n_triangles());
        for t in mesh.triangles() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edges.push((a.min(b), a.max(b)));
            }
        }
        edges.sort_unstable();
        let mut is_boundary = vec![false; n_nodes];
        let mut i = 0;
        let mut edge_len_sum = 0.0;
        while i < edges.len() {
            let mut j = i + 1;
            while j < edges.len() && edges[j] == edges[i] {
                j += 1;
            }
            if j - i == 1 {
                is_boundary[edges[i].0] = true;
                is_boundary[edges[i].1] = true;
            }
            let (a, b) = (mesh.nodes_m()[edges[i].0], mesh.nodes_m()[edges[i].1]);
            edge_len_sum += (a[0] - b[0]).hypot(a[1] - b[1]);
            i = j;
        }
        // A node's region: the one covering most area around it.
        let mut area = vec![[0.0f64; 8]; n_nodes];
        let mut node_region = vec![0usize; n_nodes];
        let n_regions = mesh.region_names().len();
        if n_regions <= 8 {
            for (ti, t) in mesh.triangles().iter().enumerate() {
                let a = mesh.signed_area_m2(ti).abs();
                for &n in t {
                    area[n][mesh.region_of_tri()[ti]] += a;
                }
            }
            for n in 0..n_nodes {
                node_region[n] = (0..n_regions).max_by(|&a, &b| area[n][a].total_cmp(&area[n][b])).unwrap_or(0);
            }
        } else {
            for (ti, t) in mesh.triangles().iter().enumerate() {
                for &n in t {
                    node_region[n] = mesh.region_of_tri()[ti];
                }
            }
        }
        let mean_edge = edge_len_sum / edges.len().max(1) as f64;
        let grid = NodeGrid::new(mesh.nodes_m(), mean_edge.max(1e-9));
        let cap = params.max_needle_nodes;
        let mut cache = ComplianceCache::new(n_nodes);
        cache.reserve(cap + 16);
        let col_scratch = model.column_scratch();
        let col_buf = vec![0.0; 2 * model.n_dofs()];
        let flex = params.needle.flexible().map(|f| {
            let curve = NeedleCurve::new(f, params.initial_pose, cap);
            Box::new(Flex {
                // Built, not cloned: a clone's scratch vectors have no spare capacity.
                probe_curve: NeedleCurve::new(f, params.initial_pose, cap),
                curve,
                coupling: Coupling::new(cap),
                probe_coupling: Coupling::new(cap),
                nodes: Vec::with_capacity(cap),
                bevel_ratio: f.bevel_force_ratio,
                bevel_side: f.bevel_side,
                g_for: None,
            })
        });
        let n_shape = params.needle.flexible().map_or(2, |f| f.n_links + 1);
        let mut shape_m = Vec::with_capacity(n_shape);
        match &flex {
            Some(fx) => shape_m.extend_from_slice(fx.curve.points_m()),
            None => shape_m.extend_from_slice(&[params.initial_pose.position_m(), params.needle.tip_m(&params.initial_pose)]),
        }
        let out = StepOutput {
            shape_m,
            tip_angle_rad: params.initial_pose.theta_rad,
            bevel_side: flex.as_ref().map_or(0.0, |f| if f.bevel_ratio > 0.0 { f.bevel_side } else { 0.0 }),
            needle_nodes: Vec::with_capacity(cap),
            targets: Vec::with_capacity(targets.len()),
            approaching: Vec::with_capacity(256),
            base: params.initial_pose,
            tip_m: params.needle.tip_m(&params.initial_pose),
            converged: true,
            ..Default::default()
        };
        let bounds = DivergenceBounds::of(&model, &params);
        Ok(Self {
            bounds,
            diverged: None,
            solver: MixedSolver::with_capacity(cap),
            probe: MixedSolver::with_capacity(cap),
            pose: params.initial_pose,
            nodes: Vec::with_capacity(cap),
            slot_of_node: vec![NO_SLOT; n_nodes],
            f_world: Vec::with_capacity(cap),
            u_world: Vec::with_capacity(cap),
            last_tip_region: None,
            order: Vec::with_capacity(cap),
            candidates: Vec::with_capacity(1024),
            captured: Vec::with_capacity(64),
            changes: Vec::with_capacity(2 * cap),
            flex,
            out,
            stats: SimStats::default(),
            tick: 0,
            model,
            params,
            cache,
            col_scratch,
            col_buf,
            grid,
            is_boundary,
            node_region,
            targets,
        })
    }

    /// The tissue model.
    pub fn model(&self) -> &Arc<TissueModel> {
        &self.model
    }
    /// The parameters.
    pub fn params(&self) -> &SimParams {
        &self.params
    }
    /// Counters.
    pub fn stats(&self) -> SimStats {
        self.stats
    }
    /// The working-set solver (for its update counters).
    pub fn solver(&self) -> &MixedSolver {
        &self.solver
    }
    /// The current base pose.
    pub fn pose(&self) -> BasePose {
        self.pose
    }
    /// The last step's output.
    pub fn output(&self) -> &StepOutput {
        &self.out
    }
    /// The compliance cache.
    pub fn cache(&self) -> &ComplianceCache {
        &self.cache
    }

    /// Computes (allocating, outside any step) the compliance columns of up to `max_nodes` of
    /// the nodes the last step reported as approaching. Returns how many it computed.
    pub fn prefetch_columns(&mut self, max_nodes: usize) -> Result<usize, SimError> {
        let mut n = 0;
        for k in 0..self.out.approaching.len() {
            if n == max_nodes {
                break;
            }
            let node = self.out.approaching[k];
            if !self.cache.contains(node) {
                self.model.compliance_columns_into(node, &mut self.col_buf, &mut self.col_scratch)?;
                self.cache.insert(node, &self.col_buf);
                n += 1;
            }
        }
        Ok(n)
    }

    /// Stores columns computed by a worker ([`TissueModel::compliance_columns_into`]).
    pub fn insert_columns(&mut self, node_idx: usize, columns: &[f64]) {
        self.cache.insert(node_idx, columns);
    }

    /// Stores columns handed over as an owned box, allocating no column storage (for the
    /// real-time thread); returns the box not kept, to be dropped off the real-time thread.
    pub fn insert_columns_owned(&mut self, node_idx: usize, columns: Box<[f64]>) -> Option<Box<[f64]>> {
        self.cache.insert_owned(node_idx, columns)
    }

    /// Reserves bookkeeping room in the column cache for `n_nodes` more nodes.
    pub fn reserve_cached_nodes(&mut self, n_nodes: usize) {
        self.cache.reserve(n_nodes);
    }

    /// The bevel side $s_b$ (0 for a symmetric tip).
    pub fn bevel_side(&self) -> f64 {
        self.flex.as_ref().map_or(0.0, |f| if f.bevel_ratio > 0.0 { f.bevel_side } else { 0.0 })
    }

    /// Turns the needle 180° about its axis: the bevel faces the other side from the next step
    /// on. Returns the new side (0 and no change for a symmetric tip or a rigid needle).
    pub fn flip_bevel(&mut self) -> f64 {
        if let Some(f) = self.flex.as_mut()
            && f.bevel_ratio > 0.0
        {
            f.bevel_side = -f.bevel_side;
            self.stats.bevel_flips += 1;
        }
        self.out.bevel_side = self.bevel_side();
        self.out.bevel_side
    }

    /// The needle's current shape (joint positions base to tip), if it is flexible.
    pub fn needle_curve(&self) -> Option<&NeedleCurve> {
        self.flex.as_ref().map(|f| &f.curve)
    }

    fn tip_now(&self) -> [f64; 2] {
        match &self.flex {
            Some(f) => f.curve.tip_m(),
            None => self.params.needle.tip_m(&self.pose),
        }
    }

    /// The tip's frame: captures happen along the tip's own tangent.
    fn tip_frame(&self) -> Frame {
        match &self.flex {
            Some(f) => Frame::new(f.curve.tip_m(), self.params.needle.tip_s_m(), f.curve.tip_angle_rad()),
            None => Frame::rigid(&self.pose),
        }
    }

    /// The frame of working slot `slot`: at its node's shaft point, along the solver's frame.
    fn node_frame(&self, slot: usize) -> Frame {
        match &self.flex {
            Some(f) => {
                let s_ref = self.nodes[slot].s_ref_m(self.params.needle.tip_s_m());
                Frame::new(f.curve.point_at(s_ref), s_ref, self.solver.angle_rad(slot))
            }
            None => Frame::rigid(&self.pose),
        }
    }

    /// Solves the working set: directly for a rigid needle, with the needle's lateral compliance
    /// for a flexible one (recomputing $G$ when the slots, frames or shape changed).
    fn solve_working_set(&mut self) {
        let Some(fx) = self.flex.as_mut() else {
            self.solver.solve();
            return;
        };
        let s_tip = self.params.needle.tip_s_m();
        fx.nodes.clear();
        for nn in &self.nodes {
            fx.nodes.push(CoupledNode { s_m: nn.s_ref_m(s_tip), lateral_ref_m: nn.lateral_ref_m, force_ref_local_n: nn.force_ref_local_n });
        }
        let st = self.solver.stats();
        let version = (st.n_rotations + st.n_added + st.n_removed + st.n_rebuilds, self.tick);
        if fx.g_for != Some(version) {
            fx.coupling.update_compliance(&mut fx.curve, &self.solver, &fx.nodes);
            fx.g_for = Some(version);
        }
        fx.coupling.solve(&mut self.solver, &fx.nodes);
    }

    /// A bevel tip's lateral force from the tip's current axial force; returns the change.
    fn update_bevel_force(&mut self) -> f64 {
        let Some(fx) = self.flex.as_ref() else { return 0.0 };
        if fx.bevel_ratio == 0.0 {
            return 0.0;
        }
        let (ratio, side) = (fx.bevel_ratio, fx.bevel_side);
        let mut change: f64 = 0.0;
        for slot in 0..self.nodes.len() {
            if self.nodes[slot].state == NodeState::Tip && self.solver.condition(slot, 1) == Condition::Force {
                let value = -side * ratio * self.solver.force_local(slot)[0].max(0.0);
                change = change.max((value - self.solver.prescribed_value(slot, 1)).abs());
                self.solver.set_value(slot, 1, value);
            }
        }
        change
    }

    /// The bounds a step's results are checked against.
    pub fn divergence_bounds(&self) -> DivergenceBounds {
        self.bounds
    }

    /// Advances one tick towards the commanded base pose.
    ///
    /// Fails with [`SimError::Diverged`] when the results are not finite or exceed
    /// [`DivergenceBounds`]; the output is then not written, and every later step fails the
    /// same way (checked in $O(d)$, plus the shape's joints for a flexible needle).
    pub fn step(&mut self, commanded: BasePose) -> Result<&StepOutput, SimError> {
        if let Some((tick, what, value, bound)) = self.diverged {
            return Err(SimError::Diverged { tick, what, value, bound });
        }
        if !commanded.is_finite() {
            self.stats.rejected_poses += 1;
            return Err(SimError::NonFinitePose {
                tick: self.tick,
                x_m: commanded.x_m,
                y_m: commanded.y_m,
                theta_rad: commanded.theta_rad,
            });
        }
        let prev_tip = self.tip_now();
        let clamped = self.apply_pose(commanded)?;
        self.set_prescribed_values();
        self.release_withdrawn()?;
        self.capture(prev_tip)?;
        self.update_friction(false, 0.0);
        let (mut iterations, mut converged) = self.resolve_active_set()?;
        if self.flex.is_some() {
            // The needle comes to equilibrium with the tick's forces; where that moves it off the
            // linearised prediction by more than SHAPE_GAP_TOL_M, the tissue is solved again on
            // the new shape (a bounded Picard iteration).
            for pass in 1..=SHAPE_PASSES {
                let gap = self.settle_shape();
                if gap <= SHAPE_GAP_TOL_M || pass == SHAPE_PASSES {
                    break;
                }
                self.refresh_frames()?;
                self.set_prescribed_values();
                let (it, conv) = self.resolve_active_set()?;
                iterations += it;
                converged &= conv;
                self.stats.shape_passes += 1;
            }
        }
        if let Err((what, value, bound)) = self.check_divergence() {
            self.diverged = Some((self.tick, what, value, bound));
            return Err(SimError::Diverged { tick: self.tick, what, value, bound });
        }
        self.write_output(iterations, converged, clamped);
        self.tick += 1;
        self.stats.ticks += 1;
        self.stats.clamped_ticks += clamped as u64;
        self.stats.unconverged_ticks += (!converged) as u64;
        Ok(&self.out)
    }

    /// Flexible needle: brings the shape to equilibrium with the working forces (the next
    /// solve's reference shape) and returns how far the needle nodes lie off it laterally.
    fn settle_shape(&mut self) -> f64 {
        let s_tip = self.params.needle.tip_s_m();
        // Each node's current shaft position.
        for slot in 0..self.nodes.len() {
            let nn = self.nodes[slot];
            let s = match nn.state {
                NodeState::Slipping => {
                    let x = self.model.mesh().nodes_m()[nn.node_idx];
                    self.node_frame(slot).coords(x).0 + self.solver.displacement_local(slot)[0]
                }
                _ => nn.s_ref_m(s_tip),
            };
            self.nodes[slot].s_work_m = s.min(s_tip);
        }
        let Some(fx) = self.flex.as_deref_mut() else { return 0.0 };
        // The contact forces turn with the shaft (friction along it, pressure across it).
        let nodes = &self.nodes;
        let solver = &self.solver;
        let loads = (0..nodes.len()).map(|k| {
            let f = solver.force_local(k);
            (nodes[k].s_work_m, [-f[0], -f[1]])
        });
        if !fx.curve.update_shape(loads, true) {
            self.stats.shape_unconverged += 1;
        }
        fx.g_for = None;
        // The settled shape carries these forces: the reference of the next coupled solve.
        for slot in 0..self.nodes.len() {
            self.nodes[slot].force_ref_local_n = self.solver.force_local(slot);
        }
        let mut gap: f64 = 0.0;
        for (slot, nn) in self.nodes.iter().enumerate() {
            if self.solver.condition(slot, 1) != Condition::Displacement {
                continue;
            }
            let x = self.model.mesh().nodes_m()[nn.node_idx];
            let u = self.solver.displacement_world(slot);
            let s = nn.s_work_m;
            let (_, lat) = fx.curve.frame_coords(s, fx.curve.tangent_angle_at(s), [x[0] + u[0], x[1] + u[1]]);
            gap = gap.max((lat - nn.lat_offset_m).abs());
        }
        gap
    }

    /// Flexible needle: turns node frames to the shape's tangent where they differ by more than
    /// [`FRAME_TOL_RAD`].
    fn refresh_frames(&mut self) -> Result<(), SimError> {
        let s_tip = self.params.needle.tip_s_m();
        if let Some(fx) = self.flex.as_ref() {
            for slot in 0..self.solver.n_nodes() {
                let a = fx.curve.tangent_angle_at(self.nodes[slot].s_ref_m(s_tip));
                if (a - self.solver.angle_rad(slot)).abs() > FRAME_TOL_RAD {
                    self.solver.set_angle(slot, a)?;
                }
            }
        }
        Ok(())
    }

    /// Stage 1: clamps the pose change and rotates the node frames.
    fn apply_pose(&mut self, cmd: BasePose) -> Result<bool, SimError> {
        let mut pose = cmd;
        let mut clamped = false;
        let (dx, dy) = (cmd.x_m - self.pose.x_m, cmd.y_m - self.pose.y_m);
        let dist = dx.hypot(dy);
        if dist > self.params.max_base_step_m {
            let k = self.params.max_base_step_m / dist;
            pose.x_m = self.pose.x_m + k * dx;
            pose.y_m = self.pose.y_m + k * dy;
            clamped = true;
        }
        let dth = cmd.theta_rad - self.pose.theta_rad;
        if dth.abs() > self.params.max_base_step_rad {
            pose.theta_rad = self.pose.theta_rad + self.params.max_base_step_rad.copysign(dth);
            clamped = true;
        }
        if let Some(fx) = self.flex.as_mut() {
            fx.curve.set_base(pose);
            let dth = pose.theta_rad - self.pose.theta_rad;
            if dth != 0.0 {
                for slot in 0..self.solver.n_nodes() {
                    let a = self.solver.angle_rad(slot) + dth;
                    self.solver.set_angle(slot, a)?;
                }
            }
            self.refresh_frames()?;
        } else if pose.theta_rad != self.pose.theta_rad {
            for slot in 0..self.solver.n_nodes() {
                let s = self.nodes[slot].s_prev_m;
                let a = self.params.needle.frame_angle_at(&pose, s);
                self.solver.set_angle(slot, a)?;
            }
        }
        self.pose = pose;
        Ok(clamped)
    }

    /// Stage 2: lateral and axial prescribed values from the pose.
    fn set_prescribed_values(&mut self) {
        let s_tip = self.params.needle.tip_s_m();
        for slot in 0..self.nodes.len() {
            let nn = self.nodes[slot];
            let x = self.model.mesh().nodes_m()[nn.node_idx];
            let frame = self.node_frame(slot);
            self.nodes[slot].lateral_ref_m = prescribe(&mut self.solver, slot, &nn, frame, x, s_tip);
        }
    }

    fn remove_slot(&mut self, slot: usize) -> Result<(), SimError> {
        self.solver.remove_slot(slot)?;
        let gone = self.nodes.swap_remove(slot);
        self.f_world.swap_remove(slot);
        self.u_world.swap_remove(slot);
        self.slot_of_node[gone.node_idx] = NO_SLOT;
        if slot < self.nodes.len() {
            self.slot_of_node[self.nodes[slot].node_idx] = slot;
        }
        self.stats.releases += 1;
        Ok(())
    }

    /// Stage 3: shaft nodes beyond the (withdrawn) tip leave the needle.
    fn release_withdrawn(&mut self) -> Result<(), SimError> {
        let s_tip = self.params.needle.tip_s_m();
        for slot in (0..self.nodes.len()).rev() {
            let nn = self.nodes[slot];
            let s = match nn.state {
                NodeState::Stuck => nn.anchor_s_m,
                NodeState::Slipping => nn.s_prev_m,
                NodeState::Tip => continue,
            };
            if s > s_tip {
                self.remove_slot(slot)?;
            }
        }
        Ok(())
    }

    /// Displacement of any node from the current working forces, $O(d)$.
    fn node_displacement(&self, node_idx: usize) -> [f64; 2] {
        let mut u = [0.0; 2];
        for (slot, f) in self.f_world.iter().enumerate() {
            let w = self.nodes[slot].node_idx;
            let (Some(cx), Some(cy)) = (self.cache.column(w, 0), self.cache.column(w, 1)) else { continue };
            u[0] += cx[2 * node_idx] * f[0] + cy[2 * node_idx] * f[1];
            u[1] += cx[2 * node_idx + 1] * f[0] + cy[2 * node_idx + 1] * f[1];
        }
        u
    }

    fn ensure_columns(&mut self, node_idx: usize) -> Result<(), SimError> {
        if !self.cache.contains(node_idx) {
            self.model.compliance_columns_into(node_idx, &mut self.col_buf, &mut self.col_scratch)?;
            self.cache.insert(node_idx, &self.col_buf);
            self.stats.column_misses += 1;
        }
        Ok(())
    }

    /// Stage 4: interception of nodes the tip has passed, and the list of approaching nodes.
    ///
    /// The search is centred on the material point at the tip, $q = x_{tip} - u_d$, where $u_d$ is
    /// the displacement of the most distal needle node: only nodes within a few capture radii of
    /// it get their exact deformed position ($O(d)$ each). Nodes ahead of the tip are reported as
    /// approaching from their reference positions shifted by $u_d$, at no per-node solve cost.
    fn capture(&mut self, prev_tip: [f64; 2]) -> Result<(), SimError> {
        let shape = self.params.needle;
        let tip = self.tip_now();
        let tip_frame = self.tip_frame();
        let s_tip = shape.tip_s_m();
        let cap_r = self.params.capture_radius_m;
        let (s_prev_tip, _) = tip_frame.coords(prev_tip);
        let distal = (0..self.nodes.len()).max_by(|&a, &b| self.nodes[a].s_prev_m.total_cmp(&self.nodes[b].s_prev_m));
        let u_d = distal.map_or([0.0; 2], |k| self.u_world[k]);
        let q = [tip[0] - u_d[0], tip[1] - u_d[1]];
        let advance = (tip[0] - prev_tip[0]).hypot(tip[1] - prev_tip[1]);
        // Around the tip the tissue strains: allow a quarter of the local displacement as margin.
        let radius = 3.0 * cap_r + advance + 0.25 * u_d[0].hypot(u_d[1]);
        self.candidates.clear();
        self.grid.query_into(q, radius, &mut self.candidates);
        self.captured.clear();
        for k in 0..self.candidates.len() {
            let j = self.candidates[k];
            if self.slot_of_node[j] != NO_SLOT || self.model.is_fixed(j) {
                continue;
            }
            let x = self.model.mesh().nodes_m()[j];
            let u = self.node_displacement(j);
            let (s, lat) = tip_frame.coords([x[0] + u[0], x[1] + u[1]]);
            if lat.abs() <= cap_r && s <= s_tip && s >= s_prev_tip - cap_r && self.captured.len() < self.captured.capacity() {
                self.captured.push((j, s, lat));
            }
        }
        // Approaching nodes: ahead of the tip, within the lookahead.
        self.out.approaching.clear();
        let look = self.params.lookahead_m;
        if look > 0.0 {
            let t = tip_frame.t;
            let centre = [q[0] + 0.5 * look * t[0], q[1] + 0.5 * look * t[1]];
            self.candidates.clear();
            self.grid.query_into(centre, 0.5 * look + 2.0 * cap_r, &mut self.candidates);
            for k in 0..self.candidates.len() {
                let j = self.candidates[k];
                if self.cache.contains(j) || self.model.is_fixed(j) || self.out.approaching.len() == self.out.approaching.capacity() {
                    continue;
                }
                let x = self.model.mesh().nodes_m()[j];
                let (s, lat) = tip_frame.coords([x[0] + u_d[0], x[1] + u_d[1]]);
                if lat.abs() <= 2.0 * cap_r && s > s_tip - cap_r && s <= s_tip + look {
                    self.out.approaching.push(j);
                }
            }
            // Nearest first, so a bounded prefetch takes the most urgent.
            let nodes_m = self.model.mesh().nodes_m();
            let key = |j: &usize| tip_frame.coords([nodes_m[*j][0] + u_d[0], nodes_m[*j][1] + u_d[1]]).0;
            self.out.approaching.sort_unstable_by(|a, b| key(a).total_cmp(&key(b)));
        }
        if self.captured.is_empty() {
            return Ok(());
        }
        self.captured.sort_unstable_by(|a, b| a.1.total_cmp(&b.1));
        let has_tip = self.nodes.iter().any(|n| n.state == NodeState::Tip);
        let n_cap = self.captured.len();
        for k in 0..n_cap {
            let (j, s, _) = self.captured[k];
            if self.nodes.len() == self.params.max_needle_nodes {
                self.stats.capacity_drops += (n_cap - k) as u64;
                break;
            }
            self.ensure_columns(j)?;
            let is_tip = !has_tip && k + 1 == n_cap;
            let s_ref = if is_tip { s_tip } else { s };
            let (angle, frame) = match &self.flex {
                Some(fx) => {
                    let a = fx.curve.tangent_angle_at(s_ref);
                    (a, Frame::new(fx.curve.point_at(s_ref), s_ref, a))
                }
                None => (shape.frame_angle_at(&self.pose, s), Frame::rigid(&self.pose)),
            };
            // A flexible needle takes the node where it is (no lateral snap onto the shaft, which
            // would pull the needle towards every node it passes); the rigid needle, as in the
            // paper, puts it on the shaft.
            let lat_offset_m = if self.flex.is_some() {
                let u = self.node_displacement(j);
                let xj = self.model.mesh().nodes_m()[j];
                frame.coords([xj[0] + u[0], xj[1] + u[1]]).1
            } else {
                0.0
            };
            let slot = self.solver.add_node(&self.cache, j, angle)?;
            let x = self.model.mesh().nodes_m()[j];
            let (s0, lat0) = frame.coords(x);
            let region = self.node_region[j];
            let bevel_tip = is_tip && self.flex.as_ref().is_some_and(|f| f.bevel_ratio > 0.0);
            let entering = self.is_boundary[j] || self.last_tip_region != Some(region);
            let rp = self.params.regions[region];
            let nn = NeedleNode {
                node_idx: j,
                state: if is_tip { NodeState::Tip } else { NodeState::Slipping },
                anchor_s_m: s,
                s_prev_m: s,
                s_work_m: s,
                friction_n: 0.0,
                friction_new_n: 0.0,
                slip_sign: 1.0,
                release_force_n: if entering { rp.puncture_force_n } else { rp.cutting_force_n },
                region,
                lat_offset_m,
                lateral_ref_m: lat_offset_m - lat0,
                force_ref_local_n: [0.0; 2],
            };
            if bevel_tip {
                // The bevel's tip node slides on the bevel face: its lateral force is prescribed.
                self.solver.set_condition(slot, 1, Condition::Force, 0.0)?;
            } else {
                self.solver.set_condition(slot, 1, Condition::Displacement, lat_offset_m - lat0)?;
            }
            if is_tip {
                self.solver.set_condition(slot, 0, Condition::Displacement, s_tip - s0)?;
                self.last_tip_region = Some(region);
            }
            self.nodes.push(nn);
            self.f_world.push([0.0; 2]);
            self.u_world.push([0.0; 2]);
            self.slot_of_node[j] = slot;
            self.stats.captures += 1;
        }
        Ok(())
    }

    /// Stage 5: each shaft node's share of the friction distribution, from the nodes' shaft
    /// positions: the anchor of a stuck node; for a slipping node its position at the end of the
    /// last tick, or (`current`) in the current solution. The new shares are applied only when
    /// some slipping node's share changes by more than `min_change_n`, so that the applied values
    /// always belong to the last solve. Returns the largest change.
    fn update_friction(&mut self, current: bool, min_change_n: f64) -> f64 {
        let s_tip = self.params.needle.tip_s_m();
        self.order.clear();
        for slot in 0..self.nodes.len() {
            let frame = self.node_frame(slot);
            let nn = &mut self.nodes[slot];
            nn.s_work_m = match nn.state {
                NodeState::Stuck => nn.anchor_s_m,
                NodeState::Slipping if current => {
                    let x = self.model.mesh().nodes_m()[nn.node_idx];
                    frame.coords(x).0 + self.solver.displacement_local(slot)[0]
                }
                NodeState::Slipping => nn.s_prev_m,
                NodeState::Tip => continue,
            };
            self.order.push(slot);
        }
        let nodes = &self.nodes;
        self.order.sort_unstable_by(|&a, &b| nodes[a].s_work_m.total_cmp(&nodes[b].s_work_m));
        let k = self.order.len();
        let mut max_change: f64 = 0.0;
        for i in 0..k {
            let slot = self.order[i];
            let s = self.nodes[slot].s_work_m;
            let lo = if i == 0 { s } else { 0.5 * (s + self.nodes[self.order[i - 1]].s_work_m) };
            let hi = if i + 1 == k { s_tip.max(s) } else { 0.5 * (s + self.nodes[self.order[i + 1]].s_work_m) };
            let rp = self.params.regions[self.nodes[slot].region];
            let nn = &mut self.nodes[slot];
            nn.friction_new_n = rp.friction_integral_n(s_tip - hi, s_tip - lo);
            if nn.state == NodeState::Slipping {
                max_change = max_change.max((nn.friction_new_n - nn.friction_n).abs());
            }
        }
        if max_change > min_change_n || !current {
            for i in 0..k {
                let slot = self.order[i];
                let nn = &mut self.nodes[slot];
                nn.friction_n = nn.friction_new_n;
                // The kind is Force for a slipping node already pivoted; only its value changes.
                if nn.state == NodeState::Slipping && self.solver.condition(slot, 0) == Condition::Force {
                    self.solver.set_value(slot, 0, nn.slip_sign * nn.friction_n);
                }
            }
        }
        max_change
    }

    /// Stage 6: the bounded stick/slip iteration. Returns (iterations, converged).
    fn resolve_active_set(&mut self) -> Result<(usize, bool), SimError> {
        // Slipping nodes just captured still need their force condition.
        for slot in 0..self.nodes.len() {
            let nn = self.nodes[slot];
            if nn.state == NodeState::Slipping && self.solver.condition(slot, 0) != Condition::Force {
                self.solver.set_condition(slot, 0, Condition::Force, nn.slip_sign * nn.friction_n)?;
            }
        }
        let max_iter = self.params.max_active_set_iterations;
        for iter in 1..=max_iter {
            self.solve_working_set();
            // Friction shares follow the slipping nodes' positions (a node sliding back lengthens
            // its tributary segment): a short fixed-point iteration, contracting when the friction
            // per length is small against the tissue stiffness.
            let total: f64 = self.nodes.iter().map(|n| n.friction_n).sum();
            let tol = FRICTION_TOL * total.max(1e-12);
            for _ in 0..FRICTION_SWEEPS {
                let friction_change = self.update_friction(true, tol);
                let bevel_change = self.update_bevel_force();
                if friction_change <= tol && bevel_change <= tol {
                    break;
                }
                self.solve_working_set();
            }
            self.changes.clear();
            for slot in 0..self.nodes.len() {
                let nn = self.nodes[slot];
                let f = self.solver.force_local(slot);
                let x = self.model.mesh().nodes_m()[nn.node_idx];
                let (s0, _) = self.node_frame(slot).coords(x);
                let s_now = s0 + self.solver.displacement_local(slot)[0];
                let change = match nn.state {
                    NodeState::Tip if f[0] > nn.release_force_n => Some(Change::Puncture),
                    NodeState::Tip if f[0] <= 0.0 => Some(Change::LetGo),
                    NodeState::Stuck => {
                        let threshold = (self.params.regions[nn.region].static_friction_ratio * nn.friction_n).max(1e-12);
                        (f[0].abs() > threshold).then(|| Change::Slip(f[0].signum()))
                    }
                    NodeState::Slipping => {
                        // Consistent sliding moves the node backwards along the shaft relative to
                        // the friction it receives: slip_sign * ds < 0.
                        let ds = s_now - nn.s_prev_m;
                        (nn.slip_sign * ds >= -1e-12).then_some(Change::Stick(nn.s_prev_m))
                    }
                    NodeState::Tip => None,
                };
                if let Some(c) = change {
                    self.changes.push((slot, c));
                }
            }
            if self.changes.is_empty() {
                return Ok((iter, true));
            }
            // Apply in descending slot order so removals do not disturb pending slots.
            self.changes.sort_unstable_by_key(|c| std::cmp::Reverse(c.0));
            for k in 0..self.changes.len() {
                let (slot, change) = self.changes[k];
                let x = self.model.mesh().nodes_m()[self.nodes[slot].node_idx];
                let (s0, lat0) = self.node_frame(slot).coords(x);
                match change {
                    Change::Puncture => {
                        if self.solver.condition(slot, 1) == Condition::Force {
                            // A bevel tip's node stays at the lateral offset it was cut at.
                            let un = self.solver.displacement_local(slot)[1];
                            self.nodes[slot].lat_offset_m = un + lat0;
                            self.nodes[slot].lateral_ref_m = un;
                            self.solver.set_condition(slot, 1, Condition::Displacement, un)?;
                        }
                        let nn = &mut self.nodes[slot];
                        nn.state = NodeState::Slipping;
                        nn.slip_sign = 1.0;
                        nn.s_prev_m = s0 + self.solver.displacement_local(slot)[0];
                        let value = nn.friction_n;
                        self.solver.set_condition(slot, 0, Condition::Force, value)?;
                        self.stats.punctures += 1;
                    }
                    Change::LetGo => self.remove_slot(slot)?,
                    Change::Slip(sign) => {
                        let nn = &mut self.nodes[slot];
                        nn.state = NodeState::Slipping;
                        nn.slip_sign = sign;
                        let value = sign * nn.friction_n;
                        self.solver.set_condition(slot, 0, Condition::Force, value)?;
                        self.stats.stick_to_slip += 1;
                    }
                    Change::Stick(anchor) => {
                        let nn = &mut self.nodes[slot];
                        nn.state = NodeState::Stuck;
                        nn.anchor_s_m = anchor;
                        self.solver.set_condition(slot, 0, Condition::Displacement, anchor - s0)?;
                        self.stats.slip_to_stick += 1;
                    }
                }
            }
            if iter == max_iter {
                // Leave a state whose solution matches its conditions.
                self.solve_working_set();
            }
        }
        Ok((max_iter, false))
    }

    /// Stage 7: forces, torque, node states, targets.
    /// Checks the solved state against [`DivergenceBounds`] before it is written out: every
    /// needle node's force and displacement, the base force and torque, the inserted length and
    /// the needle's shape. Returns the first quantity out of bounds, its value and its bound.
    fn check_divergence(&self) -> Result<(), (Divergence, f64, f64)> {
        let bd = &self.bounds;
        let check = |what: Divergence, value: f64, bound: f64| if value <= bound { Ok(()) } else { Err((what, value, bound)) };
        let b = self.pose.position_m();
        let mut force = [0.0; 2];
        let mut torque = 0.0;
        let mut min_s = f64::INFINITY;
        for slot in 0..self.nodes.len() {
            let f = self.solver.force_world(slot);
            let u = self.solver.displacement_world(slot);
            check(Divergence::NodeForce, f[0].hypot(f[1]), bd.force_n)?;
            check(Divergence::Displacement, u[0].hypot(u[1]), bd.displacement_m)?;
            let x = self.model.mesh().nodes_m()[self.nodes[slot].node_idx];
            let p = [x[0] + u[0], x[1] + u[1]];
            min_s = min_s.min(self.node_frame(slot).coords(p).0);
            force[0] -= f[0];
            force[1] -= f[1];
            torque += (p[0] - b[0]) * (-f[1]) - (p[1] - b[1]) * (-f[0]);
        }
        check(Divergence::Force, force[0].hypot(force[1]), bd.force_n)?;
        check(Divergence::Torque, torque.abs(), bd.torque_nm)?;
        if !self.nodes.is_empty() {
            check(Divergence::InsertedLength, self.params.needle.tip_s_m() - min_s, bd.inserted_length_m)?;
        }
        let dist = |p: [f64; 2]| (p[0] - b[0]).hypot(p[1] - b[1]);
        if let Some(fx) = self.flex.as_ref() {
            for &p in fx.curve.points_m() {
                check(Divergence::NeedleShape, dist(p), bd.shape_radius_m)?;
            }
        }
        check(Divergence::NeedleShape, dist(self.tip_now()), bd.shape_radius_m)
    }

    fn write_output(&mut self, iterations: usize, converged: bool, clamped: bool) {
        let shape = self.params.needle;
        let b = self.pose.position_m();
        let (t, n) = (self.pose.axis(), self.pose.normal());
        let mut force = [0.0; 2];
        let mut torque = 0.0;
        let mut min_s = f64::INFINITY;
        self.out.needle_nodes.clear();
        let (mut n_stuck, mut n_slip, mut n_tip) = (0, 0, 0);
        for slot in 0..self.nodes.len() {
            let f = self.solver.force_world(slot);
            let u = self.solver.displacement_world(slot);
            self.f_world[slot] = f;
            self.u_world[slot] = u;
            let frame = self.node_frame(slot);
            let nn = &mut self.nodes[slot];
            let x = self.model.mesh().nodes_m()[nn.node_idx];
            let p = [x[0] + u[0], x[1] + u[1]];
            let (s, _) = frame.coords(p);
            nn.s_prev_m = s;
            nn.force_ref_local_n = self.solver.force_local(slot);
            min_s = min_s.min(s);
            force[0] -= f[0];
            force[1] -= f[1];
            torque += (p[0] - b[0]) * (-f[1]) - (p[1] - b[1]) * (-f[0]);
            match nn.state {
                NodeState::Stuck => n_stuck += 1,
                NodeState::Slipping => n_slip += 1,
                NodeState::Tip => n_tip += 1,
            }
            self.out.needle_nodes.push(NeedleNodeOut { node_idx: nn.node_idx, state: nn.state, position_m: p, force_n: f, s_m: s });
        }
        if let Some(fx) = self.flex.as_ref() {
            self.out.shape_m.clear();
            self.out.shape_m.extend_from_slice(fx.curve.points_m());
            self.out.tip_angle_rad = fx.curve.tip_angle_rad();
        } else {
            self.out.shape_m.clear();
            self.out.shape_m.push(b);
            self.out.shape_m.push(shape.tip_m(&self.pose));
            self.out.tip_angle_rad = self.pose.theta_rad;
        }
        let tip = self.tip_now();
        self.out.bevel_side = self.bevel_side();
        self.out.targets.clear();
        for k in 0..self.targets.len() {
            let tg = self.targets[k].clone();
            let mut pos = [0.0; 2];
            for (&node, &w) in tg.nodes.iter().zip(&tg.bary) {
                let x = self.model.mesh().nodes_m()[node];
                let u = self.node_displacement(node);
                pos[0] += w * (x[0] + u[0]);
                pos[1] += w * (x[1] + u[1]);
            }
            let distance_m = (pos[0] - tip[0]).hypot(pos[1] - tip[1]);
            let hit = tg.hit || distance_m <= tg.radius_m;
            self.targets[k].hit = hit;
            self.out.targets.push(TargetOut { position_m: pos, distance_m, hit });
        }
        let o = &mut self.out;
        o.tick = self.tick;
        o.time_s = self.tick as f64 / self.params.tick_rate_hz;
        o.base = self.pose;
        o.force_n = force;
        o.torque_nm = torque;
        o.force_axial_n = t[0] * force[0] + t[1] * force[1];
        o.force_lateral_n = n[0] * force[0] + n[1] * force[1];
        o.tip_m = tip;
        o.inserted_length_m = if self.nodes.is_empty() { 0.0 } else { (shape.tip_s_m() - min_s).max(0.0) };
        o.n_stuck = n_stuck;
        o.n_slipping = n_slip;
        o.n_tip = n_tip;
        o.active_set_iterations = iterations;
        o.converged = converged;
        o.clamped = clamped;
    }

    /// The force and torque of the tissue on the base, $(F_x, F_y, \tau)$, for a solved
    /// `solver` whose slots are this simulation's needle nodes, at base `pose`.
    fn wrench_of(&self, solver: &MixedSolver, pose: &BasePose) -> [f64; 3] {
        let b = pose.position_m();
        let mut w = [0.0; 3];
        for (slot, nn) in self.nodes.iter().enumerate() {
            let f = solver.force_world(slot);
            let u = solver.displacement_world(slot);
            let x = self.model.mesh().nodes_m()[nn.node_idx];
            let p = [x[0] + u[0], x[1] + u[1]];
            w[0] -= f[0];
            w[1] -= f[1];
            w[2] += (p[0] - b[0]) * (-f[1]) - (p[1] - b[1]) * (-f[0]);
        }
        w
    }

    /// Solves the probe copy of the working set with the base at `pose`, the contact conditions
    /// (stuck, slipping, tip) and slipping forces held as they are. Allocates nothing.
    fn probe_wrench(&mut self, pose: &BasePose) -> Result<[f64; 3], SimError> {
        if self.flex.is_some() {
            return self.probe_wrench_flexible(pose);
        }
        self.probe.copy_from(&self.solver);
        let shape = self.params.needle;
        let s_tip = shape.tip_s_m();
        for slot in 0..self.nodes.len() {
            let nn = self.nodes[slot];
            self.probe.set_angle(slot, shape.frame_angle_at(pose, nn.s_prev_m))?;
            let x = self.model.mesh().nodes_m()[nn.node_idx];
            prescribe(&mut self.probe, slot, &nn, Frame::rigid(pose), x, s_tip);
        }
        self.probe.solve();
        Ok(self.wrench_of(&self.probe, pose))
    }

    /// [`Self::probe_wrench`] for a flexible needle: its shape moved rigidly with the base, the
    /// frames following it, and the needle's compliance in the solve.
    fn probe_wrench_flexible(&mut self, pose: &BasePose) -> Result<[f64; 3], SimError> {
        self.probe.copy_from(&self.solver);
        let s_tip = self.params.needle.tip_s_m();
        let fx = self.flex.as_deref_mut().expect("called for a flexible needle");
        fx.probe_curve.copy_from(&fx.curve);
        fx.probe_curve.set_base(*pose);
        fx.nodes.clear();
        for slot in 0..self.nodes.len() {
            let nn = self.nodes[slot];
            let s_ref = nn.s_ref_m(s_tip);
            let a = fx.probe_curve.tangent_angle_at(s_ref);
            if (a - self.probe.angle_rad(slot)).abs() > FRAME_TOL_RAD {
                self.probe.set_angle(slot, a)?;
            }
            let frame = Frame::new(fx.probe_curve.point_at(s_ref), s_ref, self.probe.angle_rad(slot));
            let x = self.model.mesh().nodes_m()[nn.node_idx];
            let lateral = prescribe(&mut self.probe, slot, &nn, frame, x, s_tip);
            fx.nodes.push(CoupledNode { s_m: s_ref, lateral_ref_m: lateral, force_ref_local_n: nn.force_ref_local_n });
        }
        fx.probe_coupling.update_compliance(&mut fx.probe_curve, &self.probe, &fx.nodes);
        fx.probe_coupling.solve(&mut self.probe, &fx.nodes);
        Ok(self.wrench_of(&self.probe, pose))
    }

    /// The local stiffness the device feels: the 3 × 3 Jacobian
    /// $J_{ij} = \partial w_i / \partial q_j$ of the wrench $w = (F_x, F_y, \tau)$ on the base with
    /// respect to the base pose $q = (x, y, \theta)$, at the current state with the contact
    /// conditions held (row-major). Central differences of probe solves ($h$ = 1 µm, 1 mrad):
    /// exact for translations (the held problem is linear in them), $O(h^2)$ for the rotation.
    /// Six probe solves plus frame rotations: $O(k\,d^2)$ for $k$ slipping nodes; no allocation.
    /// A device bridge renders $w(q) \approx w_0 + J (q - q_0)$ between server updates.
    pub fn stiffness_jacobian(&mut self) -> Result<[[f64; 3]; 3], SimError> {
        let q0 = self.pose;
        let h = [1e-6, 1e-6, 1e-3];
        let mut j = [[0.0; 3]; 3];
        for k in 0..3 {
            let mut plus = q0;
            let mut minus = q0;
            match k {
                0 => {
                    plus.x_m += h[0];
                    minus.x_m -= h[0];
                }
                1 => {
                    plus.y_m += h[1];
                    minus.y_m -= h[1];
                }
                _ => {
                    plus.theta_rad += h[2];
                    minus.theta_rad -= h[2];
                }
            }
            let wp = self.probe_wrench(&plus)?;
            let wm = self.probe_wrench(&minus)?;
            for i in 0..3 {
                j[i][k] = (wp[i] - wm[i]) / (2.0 * h[k]);
            }
        }
        Ok(j)
    }

    /// Displacement of every DOF ($O(n\,d)$; for rendering at frame rate, not every tick).
    pub fn displacement_field_into(&self, out: &mut [f64]) {
        let forces = (0..self.nodes.len()).map(|k| (self.nodes[k].node_idx, self.f_world[k]));
        self.cache.displacement_from_forces_into(forces, out).expect("working nodes are cached");
    }

    /// The static problem that the last step solved: each needle node's conditions in its frame
    /// (`un` always; `ut` when stuck or carried by the tip) and the friction loads of slipping
    /// nodes (world components).
    pub fn snapshot(&self) -> StateSnapshot {
        let mut conditions = Vec::with_capacity(self.nodes.len());
        let mut loads_n = Vec::new();
        for (slot, nn) in self.nodes.iter().enumerate() {
            let angle = self.solver.angle_rad(slot);
            let val = |c| (self.solver.condition(slot, c) == Condition::Displacement).then(|| self.solver.prescribed_value(slot, c));
            conditions.push(LocalCondition { node_idx: nn.node_idx, angle_rad: angle, ut_m: val(0), un_m: val(1) });
            for c in 0..2 {
                if self.solver.condition(slot, c) == Condition::Force {
                    let mut v = [0.0; 2];
                    v[c] = self.solver.prescribed_value(slot, c);
                    let w = crate::mixed::local_to_world(v, angle);
                    loads_n.push((nn.node_idx, w));
                }
            }
        }
        StateSnapshot { conditions, loads_n, needle_nodes: self.out.needle_nodes.clone() }
    }
}

/// One needle node's conditions in its frame, as in the exchange format's `prescribed_local`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalCondition {
    pub node_idx: usize,
    pub angle_rad: f64,
    pub ut_m: Option<f64>,
    pub un_m: Option<f64>,
}

/// The static problem of the last step (see [`Simulation::snapshot`]).
#[derive(Debug, Clone, PartialEq)]
pub struct StateSnapshot {
    pub conditions: Vec<LocalCondition>,
    pub loads_n: Vec<(usize, [f64; 2])>,
    pub needle_nodes: Vec<NeedleNodeOut>,
}

/// Sets the prescribed values of working slot `slot` in `solver` from the node's reference
/// position `x_m` seen in `frame`: across the shaft (when that DOF is displacement-prescribed)
/// the value that puts the node at its lateral offset from the needle, along it the anchor of a
/// stuck node or the tip's arc length for the node the tip carries. Returns the lateral value.
fn prescribe(solver: &mut MixedSolver, slot: usize, nn: &NeedleNode, frame: Frame, x_m: [f64; 2], s_tip_m: f64) -> f64 {
    let (s0, lat0) = frame.coords(x_m);
    let lateral = nn.lat_offset_m - lat0;
    if solver.condition(slot, 1) == Condition::Displacement {
        solver.set_value(slot, 1, lateral);
    }
    match nn.state {
        NodeState::Stuck => solver.set_value(slot, 0, nn.anchor_s_m - s0),
        NodeState::Tip => solver.set_value(slot, 0, s_tip_m - s0),
        NodeState::Slipping => {}
    }
    lateral
}

/// The triangle containing `p` and its barycentric coordinates (a setup-time scan).
fn locate(mesh: &crate::mesh::Mesh, p: [f64; 2]) -> Option<([usize; 3], [f64; 3])> {
    let mut best: Option<([usize; 3], [f64; 3], f64)> = None;
    for (ti, t) in mesh.triangles().iter().enumerate() {
        let [a, b, c] = t.map(|i| mesh.nodes_m()[i]);
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let l1 = ((b[0] - p[0]) * (c[1] - p[1]) - (c[0] - p[0]) * (b[1] - p[1])) / det;
        let l2 = ((c[0] - p[0]) * (a[1] - p[1]) - (a[0] - p[0]) * (c[1] - p[1])) / det;
        let l3 = 1.0 - l1 - l2;
        let worst = l1.min(l2).min(l3);
        if best.as_ref().is_none_or(|bst| worst > bst.2) {
            best = Some((*t, [l1, l2, l3], worst));
        }
        let _ = ti;
    }
    best.filter(|b| b.2 >= -1e-9).map(|b| (b.0, b.1))
}
