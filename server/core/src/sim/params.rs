//! The simulation's parameters ([`SimParams`]), their validation, and the named limits on
//! everything that sizes per-step storage ([`param_limits`]).

use crate::mesh::Mesh;
use crate::needle::{BasePose, NeedleShape, RegionNeedleParams};

use super::SimError;
use crate::viscous::Viscoelastic;

/// A target embedded in the tissue: a point (radius 0) or a small disc.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetParams {
    pub name: String,
    pub center_m: [f64; 2],
    pub radius_m: f64,
}

/// How the needle holds the tissue: which points of the tissue become needle contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactModel {
    /// The paper's scheme: a mesh node whose deformed position the tip passes within
    /// [`SimParams::capture_radius_m`] becomes a needle node (put onto the shaft for a rigid
    /// needle). Reproduces the paper; the working set grows like $1/h$ as the mesh is refined.
    Nodes,
    /// Contact at material points: a point of the tissue is taken at the tip each time the tip
    /// has advanced `spacing_m` beyond the most distal contact, wherever it lies in its
    /// triangle ([`crate::contact`]); no more than two points of the working set per triangle
    /// (three collinear points would prescribe a linear field three times). The working set
    /// depends on the inserted length, not on the mesh.
    MaterialPoints {
        /// Arc length (m) between consecutive contact points along the shaft.
        spacing_m: f64,
        /// Width (m) of each contact: 0 for a point; else a patch
        /// ([`crate::ContactPoint::patch`]) spreading the contact over a segment of this
        /// length across the needle at the point, so that the contact's compliance converges
        /// under mesh refinement (a point's grows like $\ln(1/h)$ in 2D). The needle's width in
        /// the mesh-refinement study (issue 19). 2D only.
        width_m: f64,
    },
}

impl ContactModel {
    /// The default spacing of material points (m).
    pub const DEFAULT_SPACING_M: f64 = 0.002;
    /// Material points at the default spacing.
    pub const fn default_points() -> Self {
        ContactModel::MaterialPoints { spacing_m: Self::DEFAULT_SPACING_M, width_m: 0.0 }
    }
}

/// Everything the simulation needs besides the tissue model.
#[derive(Debug, Clone, PartialEq)]
pub struct SimParams {
    pub needle: NeedleShape,
    pub initial_pose: BasePose,
    /// Which points of the tissue the needle holds.
    pub contact: ContactModel,
    /// What a step does when a new contact's compliance columns are not cached: compute them
    /// itself (`true`, counted in [`super::SimStats::column_misses`]), or admit the contact at a
    /// later tick once a worker or [`super::Simulation::prefetch_columns`] has provided them
    /// (`false`, counted in [`super::SimStats::column_deferrals`]): a real-time step then never
    /// runs a sparse solve.
    pub columns_in_step: bool,
    /// A node whose deformed position lies within this lateral distance of the shaft line when
    /// the tip passes it becomes a needle node.
    pub capture_radius_m: f64,
    /// Capacity of the working set (nodes): sizes the hybrid matrix, its probe copy and the
    /// flexible coupling up front. A capture past it is dropped and counted
    /// ([`super::SimStats::capacity_drops`]).
    pub max_needle_nodes: usize,
    /// Needle parameters per tissue region (one per mesh region).
    pub regions: Vec<RegionNeedleParams>,
    pub targets: Vec<TargetParams>,
    /// Ticks per second: a step's output time is $t = k / f_{tick}$.
    pub tick_rate_hz: f64,
    /// Largest base translation accepted in one tick; larger jumps are clamped.
    pub max_base_step_m: f64,
    /// Largest base rotation accepted in one tick; larger jumps are clamped.
    pub max_base_step_rad: f64,
    /// Bound on the stick/slip iterations within one tick.
    pub max_active_set_iterations: usize,
    /// How far ahead of the tip nodes are reported as approaching (for column prefetch).
    pub lookahead_m: f64,
    /// Viscoelastic tissue: one proportional relaxation of every modulus (`None`: elastic; see
    /// [`crate::viscous`]). The tissue model's moduli are then the instantaneous ones, $E_0$.
    pub viscoelastic: Option<Viscoelastic>,
}

impl SimParams {
    /// Checks every value that does not need the mesh (ranges, finiteness, capacities); the
    /// message names the field and its allowed range. [`super::Simulation::new`] calls it first.
    ///
    /// Errors: [`SimError::InvalidParams`] for the first invalid value (a non-finite pose, a
    /// non-positive rate, radius or step bound, a negative lookahead, a capacity or iteration
    /// bound outside [`param_limits`], more than [`param_limits::MAX_TARGETS`] targets, a
    /// target's name empty, too long or repeated, a non-finite centre or a radius outside
    /// 0..=[`param_limits::MAX_LENGTH_M`]).
    pub fn validate(&self) -> Result<(), SimError> {
        use crate::num::num;
        use param_limits::*;
        let bad = |m: String| Err(SimError::InvalidParams(m));
        self.needle.validate().map_err(SimError::InvalidParams)?;
        if !self.initial_pose.is_finite() {
            let p = self.initial_pose;
            return bad(format!("initial_pose = ({}, {}, {}) must be finite", num(p.x_m), num(p.y_m), num(p.theta_rad)));
        }
        let positive = [
            ("capture_radius_m", self.capture_radius_m),
            ("tick_rate_hz", self.tick_rate_hz),
            ("max_base_step_m", self.max_base_step_m),
            ("max_base_step_rad", self.max_base_step_rad),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return bad(format!("{name} = {} must be finite and > 0", num(v)));
            }
        }
        if let ContactModel::MaterialPoints { spacing_m, width_m } = self.contact {
            if !(spacing_m.is_finite() && (MIN_CONTACT_SPACING_M..=MAX_CONTACT_SPACING_M).contains(&spacing_m)) {
                return bad(format!(
                    "contact spacing_m = {} must be in {MIN_CONTACT_SPACING_M}..={MAX_CONTACT_SPACING_M} m",
                    num(spacing_m)
                ));
            }
            if !(width_m.is_finite() && (0.0..=MAX_CONTACT_WIDTH_M).contains(&width_m)) {
                return bad(format!("contact width_m = {} must be in 0..={MAX_CONTACT_WIDTH_M} m", num(width_m)));
            }
        }
        if !(self.lookahead_m.is_finite() && self.lookahead_m >= 0.0) {
            return bad(format!("lookahead_m = {} must be finite and ≥ 0", num(self.lookahead_m)));
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
        if self.contact == ContactModel::Nodes
            && let Some(k) = self.regions.iter().position(|r| r.toughness_cutting_force_n.is_some())
        {
            return bad(format!(
                "region {k}: energy-based cutting (toughness_cutting_force_n) needs material-point contact, not the node capture"
            ));
        }
        if let Some(v) = &self.viscoelastic {
            v.validate().map_err(SimError::InvalidParams)?;
        }
        check_target_names(self.targets.iter().map(|t| t.name.as_str())).map_err(SimError::InvalidParams)?;
        for t in &self.targets {
            if !(t.radius_m.is_finite() && (0.0..=MAX_LENGTH_M).contains(&t.radius_m)) {
                return bad(format!(
                    "target '{}': radius_m = {} must be finite, ≥ 0 and ≤ {} m",
                    t.name,
                    num(t.radius_m),
                    num(MAX_LENGTH_M)
                ));
            }
            if !(t.center_m[0].is_finite() && t.center_m[1].is_finite()) {
                return bad(format!("target '{}': center_m {:?} is not finite", t.name, t.center_m));
            }
        }
        Ok(())
    }
}

impl SimParams {
    /// The most nodes whose compliance columns a simulation keeps cached at once (the storage
    /// is reused, so the column memory is bounded by this times $2 \cdot 2n \cdot 8$ bytes):
    /// `max_needle_nodes + CACHE_LOOKAHEAD_NODES`, with contact patches (a width > 0, up to
    /// twelve nodes each, neighbours sharing some) `4 × max_needle_nodes + CACHE_LOOKAHEAD_NODES`. A column inserted when the cache is full
    /// evicts the least recently used node that no working contact uses and that was not in the
    /// last tick's lookahead; only when every cached node is in use does the cache exceed it
    /// (counted in [`crate::sim::SimStats::cache_over_cap`]).
    pub fn max_cached_nodes(&self) -> usize {
        let per_contact = match self.contact {
            ContactModel::MaterialPoints { width_m, .. } if width_m > 0.0 => 4,
            _ => 1,
        };
        per_contact * self.max_needle_nodes + param_limits::CACHE_LOOKAHEAD_NODES
    }
}

impl SimParams {
    /// Checks the parameters against the mesh: one set of needle parameters per mesh region,
    /// each valid. [`super::Simulation::new`] calls it after [`SimParams::validate`].
    ///
    /// Errors: [`SimError::InvalidParams`] naming the region count or the region and field.
    pub fn validate_for_mesh(&self, mesh: &Mesh) -> Result<(), SimError> {
        if self.regions.len() != mesh.region_names().len() {
            return Err(SimError::InvalidParams(format!(
                "the mesh has {} region(s) ({}) but needle parameters were given for {}",
                mesh.region_names().len(),
                mesh.region_names().join(", "),
                self.regions.len()
            )));
        }
        for (r, name) in self.regions.iter().zip(mesh.region_names()) {
            r.validate(name).map_err(SimError::InvalidParams)?;
        }
        Ok(())
    }
}

/// Limits on the parameters that size per-step storage or bound a tick's work, and the fixed
/// capacities of the per-tick lists. Architecture invariant: every list a step fills has one of
/// these capacities, allocated before the first step; what does not fit is counted in
/// [`super::SimStats`] (see [`super::SimStats::overflows`]), never dropped silently.
pub mod param_limits {
    /// Most targets a simulation carries, 2D or 3D (every live frame and tick record carries
    /// each of them: the bound sizes both).
    pub const MAX_TARGETS: usize = 16;
    /// Longest name of a target (characters); names are non-empty and unique in a scene.
    pub const MAX_NAME_CHARS: usize = 64;
    /// Largest length of the physics a client may state (m): a needle's length, a target's
    /// radius, the plane's thickness, a friction peak's width. Far beyond any needle or
    /// phantom; a length past it only disables the physics (a step over a 10¹⁰⁰ m needle).
    pub const MAX_LENGTH_M: f64 = 10.0;
    /// Largest Young's modulus of a tissue region (Pa), 2D and 3D: a thousand times steel's.
    pub const MAX_YOUNG_MODULUS_PA: f64 = 1e12;
    /// Largest magnitude of a region's needle parameters (friction N/m, forces N, ratios,
    /// damping N·s/m², fracture toughness J/m²): tissues need at most tens.
    pub const MAX_REGION_VALUE: f64 = 1e6;

    /// The target names, in order: at most [`MAX_TARGETS`], each non-empty and at most
    /// [`MAX_NAME_CHARS`] characters, no two alike. The message names the target by index and
    /// quotes its name clipped to [`MAX_NAME_CHARS`].
    pub fn check_target_names<'a>(names: impl ExactSizeIterator<Item = &'a str>) -> Result<(), String> {
        let n = names.len();
        if n > MAX_TARGETS {
            return Err(format!("targets: {n} given, at most {MAX_TARGETS}"));
        }
        let mut seen: Vec<&str> = Vec::with_capacity(n);
        for (k, name) in names.enumerate() {
            check_name(&format!("targets[{k}]"), name)?;
            if let Some(first) = seen.iter().position(|o| *o == name) {
                return Err(format!("targets[{k}]: the name '{name}' is already used by targets[{first}]; target names must be unique"));
            }
            seen.push(name);
        }
        Ok(())
    }

    /// A name of a scene's item (`what`, e.g. `targets[3]`): non-empty, at most [`MAX_NAME_CHARS`]
    /// characters (the message quotes it clipped).
    pub fn check_name(what: &str, name: &str) -> Result<(), String> {
        if name.is_empty() {
            return Err(format!("{what}: the name is empty"));
        }
        let n = name.chars().count();
        if n > MAX_NAME_CHARS {
            let head: String = name.chars().take(MAX_NAME_CHARS).collect();
            return Err(format!("{what}: the name '{head}…' has {n} characters, at most {MAX_NAME_CHARS}"));
        }
        Ok(())
    }

    /// Largest working-set capacity (the hybrid matrix is its square: 4096² × 8 B = 134 MB).
    pub const MAX_NEEDLE_NODES: usize = 4096;
    /// Largest working-set capacity with a flexible needle (its coupling is dense too).
    pub const MAX_NEEDLE_NODES_FLEXIBLE: usize = 1024;
    /// Smallest spacing of material contact points (m): 10 µm, far below any element a mesh
    /// limit admits along a needle; the per-triangle rule bounds the density on coarser meshes.
    pub const MIN_CONTACT_SPACING_M: f64 = 1e-5;
    /// Largest spacing of material contact points (m).
    pub const MAX_CONTACT_SPACING_M: f64 = 1.0;
    /// Largest width of a contact patch (m): a 7-gauge needle (a patch wider than the elements
    /// falls back to a point when it touches more than [`crate::contact::MAX_TERMS`] nodes,
    /// counted in `patch_fallbacks`).
    pub const MAX_CONTACT_WIDTH_M: f64 = 0.005;
    /// Largest bound on the stick/slip iterations of one tick.
    pub const MAX_ACTIVE_SET_ITERATIONS: usize = 10_000;

    /// The per-tick budget of $O(d^2)$ updates of the working solver (pivots, frame rotations,
    /// additions, removals): the stick/slip iteration stops once a tick has made more, solves
    /// with the conditions as they are (the next tick goes on from them) and counts the tick in
    /// [`crate::sim::SimStats::budget_exhausted_ticks`] (and as unconverged). A turning needle
    /// rotates every contact once and pivots a few (tens of updates at 2 mm spacing); only
    /// pathological input reaches it. At $d = 120$ local DOFs one update is ~15k flops, so the
    /// budget bounds a tick's active-set work near 10 M flops.
    pub const MAX_UPDATES_PER_TICK: u64 = 640;
    /// Capacity of one tick's capture list: nodes the tip passed within the capture radius in
    /// one tick (a few at a capture radius below the mesh spacing). Candidates past it are left
    /// for later ticks and counted in [`crate::sim::SimStats::capture_overflow`].
    pub const MAX_CAPTURES_PER_TICK: usize = 64;
    /// Capacity of [`crate::sim::StepOutput::approaching`]: uncached nodes ahead of the tip
    /// reported for prefetch. Nodes past it are not reported this tick and are counted in
    /// [`crate::sim::SimStats::approaching_overflow`].
    pub const MAX_APPROACHING: usize = 256;
    /// Capacity reserved up front for the spatial grid's answer to one query near the tip. A
    /// query returning more grows the buffer (an allocation inside a step, once); each growth
    /// is counted in [`crate::sim::SimStats::candidate_growths`].
    pub const NEAR_TIP_CANDIDATES: usize = 1024;
    /// How long a node's cached compliance columns are kept after the last tick that used them
    /// (a working contact's node, or a node in the lookahead ahead of the tip), in seconds of
    /// simulated time; then they are evicted by the step's sweep. Long enough for a slow
    /// insertion to reach a node it prefetched, short enough that a path's band of nodes does
    /// not pile up behind the tip (issue 15: a 400 × 400 bevel run held 16 GB of columns).
    pub const COLUMN_KEEP_S: f64 = 2.0;
    /// Cached nodes the step's eviction sweep visits per tick (round robin): the sweep costs
    /// O(1) per tick and visits the whole cache every `len / EVICTION_SWEEP_PER_TICK` ticks.
    pub const EVICTION_SWEEP_PER_TICK: usize = 4;
    /// Cached nodes in use at once beyond the working set's: the lookahead's nodes. With the
    /// working set's `max_needle_nodes` it makes the cache's bound
    /// ([`crate::sim::SimParams::max_cached_nodes`]).
    pub const CACHE_LOOKAHEAD_NODES: usize = MAX_APPROACHING;
    /// Ticks between two checks of the hybrid matrix's round-off drift (one working contact
    /// each, round robin; `drift.rs`): $O(d)$ block reads every 16 ticks.
    pub const HYBRID_CHECK_EVERY_TICKS: u64 = 16;
    /// Relative residual of a contact's compliance relation above which the hybrid matrix is
    /// rebuilt from scratch (`drift.rs`).
    pub const HYBRID_DRIFT_TOL: f64 = 1e-9;
    /// Largest lateral distance (m) between a flexible needle's node and the settled needle
    /// shape left without another solve on the new shape (1 µm: a thousandth of a typical
    /// capture radius).
    pub const SHAPE_GAP_TOL_M: f64 = 1e-6;
    /// Bound on a flexible needle's shape passes (solve, settle) per tick; a tick that ends at
    /// it with the gap above [`SHAPE_GAP_TOL_M`] says so
    /// ([`crate::sim::StepOutput::shape_passes_capped`], counted in
    /// [`crate::sim::SimStats::shape_capped_ticks`]).
    pub const SHAPE_PASSES: usize = 6;
}

#[cfg(test)]
mod tests {
    use super::param_limits::*;
    use super::*;
    use crate::fixtures::{PHANTOM_MATERIAL, PHANTOM_PLANE, box_phantom3_params, phantom_params};
    use crate::material::{Material, MaterialError, PlaneModel};
    use crate::needle::RigidNeedle;
    use crate::sim3::Target3;

    fn params() -> SimParams {
        phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))
    }

    fn target(name: &str) -> TargetParams {
        TargetParams { name: name.to_owned(), center_m: [0.05, 0.05], radius_m: 0.002 }
    }

    fn refusal(p: &SimParams) -> String {
        match p.validate() {
            Err(SimError::InvalidParams(m)) => m,
            other => panic!("accepted or another error: {other:?}"),
        }
    }

    #[test]
    fn issue_35_targets_are_bounded_in_number_and_name() {
        let names: Vec<String> = (0..=MAX_TARGETS).map(|k| format!("t{k}")).collect();
        let mut p = params();
        p.targets = names[..MAX_TARGETS].iter().map(|n| target(n)).collect();
        p.validate().unwrap();
        p.targets = names.iter().map(|n| target(n)).collect();
        assert_eq!(refusal(&p), format!("targets: {} given, at most {MAX_TARGETS}", MAX_TARGETS + 1));
        p.targets = vec![target("a"), target("")];
        assert_eq!(refusal(&p), "targets[1]: the name is empty");
        let long = "é".repeat(100_000);
        p.targets = vec![target(&"n".repeat(MAX_NAME_CHARS)), target(&long)];
        let m = refusal(&p);
        assert!(m.starts_with("targets[1]: the name 'éé") && m.ends_with("…' has 100000 characters, at most 64"), "{m}");
        assert!(m.chars().count() < 150, "{m}");
        p.targets = vec![target("a"), target("b"), target("a")];
        assert_eq!(refusal(&p), "targets[2]: the name 'a' is already used by targets[0]; target names must be unique");
        p.targets = vec![TargetParams { radius_m: 11.0, ..target("far") }];
        assert_eq!(refusal(&p), "target 'far': radius_m = 11 must be finite, ≥ 0 and ≤ 10 m");
        // 3D: one bound.
        assert_eq!(crate::sim3::MAX_TARGETS, MAX_TARGETS);
        let mut p3 = box_phantom3_params([0.05, 0.05, 0.1], 0.005);
        p3.targets = vec![Target3 { centre_m: [0.05; 3], radius_m: 1e300, name_idx: 0 }];
        assert_eq!(p3.validate(1).unwrap_err(), "targets[0]: radius_m = 1e300 must be finite, > 0 and ≤ 10 m");
    }

    #[test]
    fn issue_35_physical_bounds_that_disable_the_physics_are_refused() {
        let mut p = params();
        p.needle = NeedleShape::Rigid(RigidNeedle { length_m: 10.0 });
        p.validate().unwrap();
        p.needle = NeedleShape::Rigid(RigidNeedle { length_m: 1e300 });
        assert_eq!(refusal(&p), "needle length 1e300 m must be finite, > 0 and ≤ 10 m");
        let mut p3 = box_phantom3_params([0.05, 0.05, 0.1], 0.005);
        p3.needle_length_m = 10.5;
        assert_eq!(p3.validate(1).unwrap_err(), "needle_length_m = 10.5 must be ≤ 10 m");
        // Region magnitudes, 2D (the simulation) and 3D alike.
        let region = RegionNeedleParams { friction_n_per_m: 1e7, ..RegionNeedleParams::default() };
        let m = region.validate("tissue").unwrap_err();
        assert_eq!(m, "region tissue: friction_n_per_m = 10000000 must be finite and ≥ 0, at most 1e6");
        let mut p3 = box_phantom3_params([0.05, 0.05, 0.1], 0.005);
        p3.regions = vec![RegionNeedleParams { cutting_force_n: 2e6, ..RegionNeedleParams::default() }];
        assert!(p3.validate(1).unwrap_err().contains("cutting_force_n = 2000000 must be finite and ≥ 0, at most 1e6"));
        let wide = RegionNeedleParams { tip_peak_width_m: 20.0, ..RegionNeedleParams::default() };
        assert!(wide.validate("r").unwrap_err().contains("tip_peak_width_m = 20 must be finite and > 0, at most 10 m"));
        RegionNeedleParams { friction_n_per_m: 1e6, ..RegionNeedleParams::default() }.validate("r").unwrap();
        // Young's modulus, 2D and 3D through one constant; the plane's thickness.
        let steel = Material { young_modulus_pa: MAX_YOUNG_MODULUS_PA, ..PHANTOM_MATERIAL };
        steel.validate(PHANTOM_PLANE, "r").unwrap();
        crate::d3::assembly::validate_material(&steel, "r").unwrap();
        let hard = Material { young_modulus_pa: 1e13, ..PHANTOM_MATERIAL };
        let e = hard.validate(PHANTOM_PLANE, "region r").unwrap_err();
        assert_eq!(e.to_string(), "region r: Young's modulus E = 10000000000000 Pa must be finite, > 0 and ≤ 1e12 Pa");
        let e = crate::d3::assembly::validate_material(&hard, "region r").unwrap_err();
        assert_eq!(e.to_string(), "region r: Young's modulus E = 10000000000000 Pa must be finite, > 0 and ≤ 1e12 Pa");
        let thick = PlaneModel::Strain { thickness_m: 1e300 };
        assert_eq!(thick.validate(), Err(MaterialError::Thickness { thickness_m: 1e300 }));
        assert_eq!(thick.validate().unwrap_err().to_string(), "thickness 1e300 m must be finite, > 0 and ≤ 10 m");
        PlaneModel::Stress { thickness_m: MAX_LENGTH_M }.validate().unwrap();
    }
}
