//! The parameters of the 3D simulation ([`Sim3Params`]) and their validation.

use crate::needle::{FlexibleNeedle, RegionNeedleParams};
use crate::viscous::Viscoelastic;

use super::near_field::NearField3;
use super::pose::BasePose3;
use super::targets::{MAX_TARGETS, Target3};

/// Everything the 3D simulation needs besides the tissue model.
#[derive(Debug, Clone, PartialEq)]
pub struct Sim3Params {
    /// Shaft length $L$ from base to tip, m.
    pub needle_length_m: f64,
    /// The base pose before the first step.
    pub initial_pose: BasePose3,
    /// Arc length between consecutive material points along the shaft, m (default 2 mm). A
    /// point is also taken only at a reference distance from every working point larger than
    /// both points' tetrahedron diameters (independent conditions), so on a coarse mesh the
    /// points are that far apart.
    pub spacing_m: f64,
    /// Radius of each contact's disc, m: 0 (the default) for a material point; else each
    /// captured contact is spread over the disc of this radius across the shaft at the point
    /// (centre the material point, axis the needle's tangent there), its weights the shape
    /// functions averaged over the disc ([`crate::d3::disc`], [`crate::ContactPoint::disc`]). A
    /// disc with more than [`crate::contact::MAX_TERMS`] nodes or not wholly inside the tissue
    /// stays a point (counted in [`super::Sim3Stats::patch_fallbacks`]). The needle's radius for
    /// `[needle] spread_contact = true` (issue 37).
    pub disc_radius_m: f64,
    /// Needle–tissue parameters per region of the mesh (one per region, in the mesh's order).
    pub regions: Vec<RegionNeedleParams>,
    /// Ticks per second: a step's output time is $t = k / f_{tick}$.
    pub tick_rate_hz: f64,
    /// Capacity of the working set (material points); sizes the solver and the output up front.
    /// A capture past it is dropped and counted.
    pub max_contacts: usize,
    /// How far ahead of the tip the nodes of the tetrahedra on the axis are reported for
    /// prefetch, m.
    pub lookahead_m: f64,
    /// Largest base translation accepted in one tick (m); larger jumps are clamped.
    pub max_base_step_m: f64,
    /// Largest base rotation accepted in one tick (rad); larger jumps are clamped.
    pub max_base_step_rad: f64,
    /// Bound on the stick/slip iterations within one tick.
    pub max_active_set_iterations: usize,
    /// Nodes whose columns the cache holds at most; inserting past it evicts the least recently
    /// used node not in use.
    pub max_cached_nodes: usize,
    /// Targets, spheres moving with the tissue (at most [`MAX_TARGETS`]; default none):
    /// [`crate::sim3::targets`].
    pub targets: Vec<Target3>,
    /// Which compliance store the simulation reads ([`StoreKind3`]).
    pub store: StoreKind3,
    /// Slots of the node-block store $M$ (its block matrix takes $72 M^2$ bytes): nodes cached
    /// at most with [`StoreKind3::NodeBlocks`]; a request past it takes the least recently used
    /// node's slot that is neither pinned nor in use.
    pub max_block_nodes: usize,
    /// The needle: rigid (the default) or a flexible rod, optionally with a bevel tip
    /// ([`NeedleShape3`]).
    pub needle: NeedleShape3,
    /// $\kappa$: a held point tears free when its force across the shaft exceeds $\kappa$ times
    /// its region's largest cutting resistance, `max(puncture_force_n, cutting_force_n)`
    /// (`needlesim_core::sim3::tear`; default [`super::DEFAULT_TEAR_FORCE_FACTOR`]).
    pub tear_force_factor: f64,
    /// The needle's near field ([`super::near_field`]): a sub-grid compliance in series with the
    /// tissue at each point; `None` (the default) for none.
    pub near_field: Option<NearField3>,
    /// Viscoelastic tissue: one proportional relaxation of every modulus ([`crate::viscous`],
    /// one code with 2D's [`crate::SimParams::viscoelastic`]); `None` (the default) for an
    /// elastic tissue. The tissue model's moduli are then the instantaneous ones, $E_0$.
    pub viscoelastic: Option<Viscoelastic>,
}

/// The needle of a 3D simulation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum NeedleShape3 {
    /// A straight rigid needle (every point in the base pose's frame).
    #[default]
    Rigid,
    /// An elastic rod clamped at the base pose ([`crate::rod3`]) coupled to the points through
    /// its tangent lateral compliance, with a bevel tip when
    /// [`FlexibleNeedle::bevel_force_ratio`] > 0 ([`super::flex`]). Its `length_m` must equal
    /// [`Sim3Params::needle_length_m`].
    Flexible(FlexibleNeedle),
}

impl NeedleShape3 {
    /// The flexible needle's parameters, if it is one.
    pub fn flexible(&self) -> Option<&FlexibleNeedle> {
        match self {
            NeedleShape3::Rigid => None,
            NeedleShape3::Flexible(f) => Some(f),
        }
    }
}

/// The compliance store of a 3D simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StoreKind3 {
    /// [`StoreKind3::NodeBlocks`] from [`AUTO_BLOCKS_MIN_NODES`] mesh nodes up, else
    /// [`StoreKind3::Columns`].
    #[default]
    Auto,
    /// Full compliance columns per cached node ($72 n$ bytes each), computed by
    /// [`super::Simulation3::prefetch_columns`] or handed in by
    /// [`super::Simulation3::insert_columns`].
    Columns,
    /// Node blocks among at most [`Sim3Params::max_block_nodes`] nodes, from sparse compliance
    /// rows computed by a [`super::Sim3BlockWorker`] ([`super::Simulation3::requests_into`],
    /// [`super::Simulation3::insert_payload`]).
    NodeBlocks,
}

/// Mesh size from which [`StoreKind3::Auto`] uses node blocks: at 20,000 nodes a column set is
/// 1.4 MB and costs about 0.2 s to solve, against rows of a few ms and blocks of a few µs
/// (BENCHMARKS.md, "3D on large meshes").
pub const AUTO_BLOCKS_MIN_NODES: usize = 20_000;

impl StoreKind3 {
    /// The store used on a mesh of `n_nodes` nodes ([`StoreKind3::Auto`] resolved).
    pub fn resolve(self, n_nodes: usize) -> StoreKind3 {
        match self {
            StoreKind3::Auto if n_nodes >= AUTO_BLOCKS_MIN_NODES => StoreKind3::NodeBlocks,
            StoreKind3::Auto => StoreKind3::Columns,
            k => k,
        }
    }
}

impl Sim3Params {
    /// The defaults for a needle of `needle_length_m` in a one-region tissue: 2 mm spacing, point
    /// contacts,
    /// the phantom's [`RegionNeedleParams::default`], 1 kHz, 256 contacts, 20 mm lookahead,
    /// 2 mm and 0.05 rad per tick at most, 20 active-set iterations, 4096 cached nodes with columns, 384 with node blocks,
    /// the store chosen by mesh size ([`StoreKind3::Auto`]), no targets.
    pub fn new(needle_length_m: f64, initial_pose: BasePose3) -> Self {
        Self {
            needle_length_m,
            initial_pose,
            spacing_m: 0.002,
            disc_radius_m: 0.0,
            regions: vec![RegionNeedleParams::default()],
            tick_rate_hz: 1000.0,
            max_contacts: 256,
            lookahead_m: 0.02,
            max_base_step_m: 0.002,
            max_base_step_rad: 0.05,
            max_active_set_iterations: 20,
            max_cached_nodes: 4096,
            targets: Vec::new(),
            store: StoreKind3::Auto,
            max_block_nodes: 384,
            needle: NeedleShape3::Rigid,
            tear_force_factor: super::DEFAULT_TEAR_FORCE_FACTOR,
            near_field: None,
            viscoelastic: None,
        }
    }

    /// Checks every value against its range, and the regions against the mesh's
    /// `n_regions`; the message names the field.
    pub fn validate(&self, n_regions: usize) -> Result<(), String> {
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 { Ok(()) } else { Err(format!("{name} = {} must be finite and > 0", crate::num::num(v))) }
        };
        pos("needle_length_m", self.needle_length_m)?;
        let max_len = crate::sim::param_limits::MAX_LENGTH_M;
        if self.needle_length_m > max_len {
            return Err(format!("needle_length_m = {} must be ≤ {} m", crate::num::num(self.needle_length_m), crate::num::num(max_len)));
        }
        pos("spacing_m", self.spacing_m)?;
        pos("tick_rate_hz", self.tick_rate_hz)?;
        pos("max_base_step_m", self.max_base_step_m)?;
        pos("max_base_step_rad", self.max_base_step_rad)?;
        pos("tear_force_factor", self.tear_force_factor)?;
        if !(self.disc_radius_m.is_finite() && self.disc_radius_m >= 0.0 && self.disc_radius_m <= max_len) {
            return Err(format!(
                "disc_radius_m = {} must be finite, ≥ 0 and ≤ {} m",
                crate::num::num(self.disc_radius_m),
                crate::num::num(max_len)
            ));
        }
        if !(self.lookahead_m.is_finite() && self.lookahead_m >= 0.0) {
            return Err(format!("lookahead_m = {} must be finite and ≥ 0", crate::num::num(self.lookahead_m)));
        }
        if !(1..=4096).contains(&self.max_contacts) {
            return Err(format!("max_contacts = {} must be in 1..=4096", self.max_contacts));
        }
        let max_iter = crate::sim::param_limits::MAX_ACTIVE_SET_ITERATIONS;
        if !(1..=max_iter).contains(&self.max_active_set_iterations) {
            return Err(format!("max_active_set_iterations = {} must be in 1..={max_iter}", self.max_active_set_iterations));
        }
        if !(16..=2048).contains(&self.max_block_nodes) {
            return Err(format!("max_block_nodes = {} must be in 16..=2048", self.max_block_nodes));
        }
        if self.max_cached_nodes < 16 {
            return Err(format!("max_cached_nodes = {} must be ≥ 16", self.max_cached_nodes));
        }
        self.initial_pose.check().map_err(|e| format!("initial_pose: {e}"))?;
        if self.regions.len() != n_regions {
            return Err(format!("regions: {} given, the mesh has {n_regions}", self.regions.len()));
        }
        for (k, r) in self.regions.iter().enumerate() {
            r.validate(&format!("{k}"))?;
        }
        if let Some(nf) = &self.near_field {
            pos("near_field.needle_radius_m", nf.needle_radius_m)?;
            pos("near_field.beta_axial", nf.beta_axial)?;
            pos("near_field.beta_lateral", nf.beta_lateral)?;
        }
        if let Some(v) = &self.viscoelastic {
            v.validate()?;
        }
        self.validate_targets()?;
        self.validate_needle()
    }

    /// A flexible needle: its length equal to `needle_length_m`, EI finite and > 0, 1..=400
    /// links, a bevel force ratio finite and ≥ 0, a bevel side of ±1 (the message names the
    /// field).
    fn validate_needle(&self) -> Result<(), String> {
        let Some(f) = self.needle.flexible() else { return Ok(()) };
        if f.length_m != self.needle_length_m {
            return Err(format!(
                "needle.length_m = {} must equal needle_length_m = {}",
                crate::num::num(f.length_m),
                crate::num::num(self.needle_length_m)
            ));
        }
        if !(f.flexural_rigidity_nm2.is_finite() && f.flexural_rigidity_nm2 > 0.0) {
            return Err(format!("needle.flexural_rigidity_nm2 = {} must be finite and > 0", crate::num::num(f.flexural_rigidity_nm2)));
        }
        if !(1..=400).contains(&f.n_links) {
            return Err(format!("needle.n_links = {} must be in 1..=400", f.n_links));
        }
        if !(f.bevel_force_ratio.is_finite() && f.bevel_force_ratio >= 0.0) {
            return Err(format!("needle.bevel_force_ratio = {} must be finite and ≥ 0", crate::num::num(f.bevel_force_ratio)));
        }
        if f.bevel_side != 1.0 && f.bevel_side != -1.0 {
            return Err(format!("needle.bevel_side = {} must be +1 or -1", crate::num::num(f.bevel_side)));
        }
        Ok(())
    }

    /// The targets: at most [`MAX_TARGETS`], finite centres, finite radii > 0 (the message names
    /// the target's index). Whether a centre lies in the mesh is checked by
    /// [`crate::sim3::Simulation3::new`].
    fn validate_targets(&self) -> Result<(), String> {
        if self.targets.len() > MAX_TARGETS {
            return Err(format!("targets: {} given, at most {MAX_TARGETS}", self.targets.len()));
        }
        for (k, t) in self.targets.iter().enumerate() {
            if !t.centre_m.iter().all(|v| v.is_finite()) {
                return Err(format!("targets[{k}]: centre_m = {:?} must be finite", t.centre_m));
            }
            let max_len = crate::sim::param_limits::MAX_LENGTH_M;
            if !(t.radius_m.is_finite() && t.radius_m > 0.0 && t.radius_m <= max_len) {
                return Err(format!(
                    "targets[{k}]: radius_m = {} must be finite, > 0 and ≤ {} m",
                    crate::num::num(t.radius_m),
                    crate::num::num(max_len)
                ));
            }
        }
        Ok(())
    }
}
