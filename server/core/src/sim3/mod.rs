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
//!    delays the points it passes rather than losing them. With
//!    [`Sim3Params::disc_radius_m`] > 0 (`[needle] spread_contact = true`) each captured point is
//!    spread over the disc of that radius across the shaft there (centre $X$, axis the tangent
//!    $t$): its weights are the shape functions averaged over the disc, $w_k = \frac{1}{\pi r^2}
//!    \int_{\mathcal D} N_k\,\mathrm dA$ ([`crate::d3::disc`], exact), so its conditions are on the
//!    tissue's mean displacement over the needle's cross-section; a disc with more than
//!    [`crate::contact::MAX_TERMS`] nodes or not wholly inside the tissue stays a point
//!    ([`Sim3Stats::patch_fallbacks`]). With [`Sim3Params::near_field`] each new point gets the needle's near field, a
//!    compliance in series with the tissue on its own block ([`near_field`]).
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
//!
//! The code follows the 2D simulation's split ([`crate::sim`]): `setup.rs` derives what never
//! changes and builds the simulation, [`Simulation3`]'s fields are the state one tick hands to
//! the next (the working points in `state.rs`), `scratch.rs` holds the buffers a stage fills
//! within a tick; the stages are in `frames.rs` (1-2), `capture.rs` (3-4, with the approaching
//! nodes in `approaching.rs`), `active_set.rs` (5-6) and `output.rs` (7), the compliance store's
//! plumbing between steps in `prefetch.rs`.

mod active_set;
mod approaching;
mod capture;
mod error;
mod flex;
mod frames;
mod near_field;
mod output;
mod params;
mod pose;
mod prefetch;
mod scratch;
mod setup;
mod state;
pub mod stiffness;
pub mod targets;
mod tear;

use std::sync::Arc;

use crate::d3::TetTissueModel;
use crate::mixed::MixedSolver3;
#[cfg(doc)]
use crate::{compliance::ComplianceCache3, contact::ContactPoint, needle::RegionNeedleParams};

pub use crate::compliance::store::{
    Block3, BlockPayload3 as BlockPayload, BlockRequest, BlockStoreError, ComplianceStore3, NodeBlockStore3 as NodeBlockStore,
};
pub use crate::compliance::worker::{ROWS_BATCH, Sim3BlockWorker, WorkerStats};
pub use error::SimError3;
pub use flex::{FRAME_TOL as FLEX_FRAME_TOL, SHAPE_GAP_TOL_M, SHAPE_PASSES};
pub use near_field::{NEAR_FIELD_BETA_AXIAL, NEAR_FIELD_BETA_LATERAL, NearField3};
pub use output::{ContactOut3, Sim3Stats, Snapshot3, SnapshotPoint3, StepOutput3};
pub use params::{AUTO_BLOCKS_MIN_NODES, NeedleShape3, Sim3Params, StoreKind3};
pub use pose::{BasePose3, PoseError, UNIT_QUATERNION_TOL, unit_axis};
pub use prefetch::InsertedColumns;
pub use state::PointState3;
pub use stiffness::WrenchStiffness3;
pub use targets::{MAX_TARGETS, Target3, TargetOut3, TargetState3, TargetsOut3};
pub use tear::DEFAULT_TEAR_FORCE_FACTOR;

use frames::axis_frame_now;
use scratch::Scratch3;
use setup::Setup3;
use state::Point;

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
    /// What never changes ([`setup`]).
    setup: Setup3,
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
    /// The stages' buffers ([`scratch`]).
    scratch: Scratch3,
    out: StepOutput3,
    /// Scratch of [`Simulation3::wrench_stiffness`].
    stiffness: stiffness::StiffnessScratch,
    /// The targets' located centres and latch bookkeeping.
    targets: targets::TargetTracker,
    /// The flexible needle ([`flex`]); `None` for a rigid one.
    flex: Option<flex::Flex3>,
    /// The round-off check of the hybrid matrix ([`crate::drift`]).
    drift: crate::drift::DriftCheck,
}

impl Simulation3 {
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
        self.set_frames(&frame, turned)?;
        // 3. Release of the points the tip withdrew past.
        self.release_withdrawn(&frame)?;
        // 4. Capture, along the tip's tangent (a rigid needle's axis).
        let (axis_pose, axis_frame) = self.capture_axis(&frame);
        let captures_before = self.stats.captures;
        self.capture(prev_tip, &axis_pose, &axis_frame)?;
        // The bevel cuts sideways while the tip advances inside the tissue ([`flex`]).
        if let Some(fx) = self.flex.as_mut() {
            let advance = dot(axis_frame[0], sub(fx.rod.tip_m(), prev_tip));
            let inside = !self.pts.is_empty();
            let cut = self.params.regions[self.last_tip_region.unwrap_or(0)].cutting_force_n;
            fx.update_bevel(advance, inside, cut, self.stats.captures != captures_before);
        }
        // The needle's near field on the points captured this tick ([`near_field`]).
        self.apply_near_field()?;
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
        if let Some(c) = &self.setup.visc {
            // Each point's history from its true displacement (written by the output stage).
            for p in &mut self.pts {
                p.visc.advance(c, p.u_world);
            }
        }
        let target_frame = if self.flex.is_some() { axis_frame_now(self) } else { frame };
        self.update_targets(&target_frame);
        self.check_drift();
        self.tick += 1;
        Ok(&self.out)
    }
}

impl Simulation3 {
    /// One row of the hybrid matrix checked every
    /// [`crate::sim::param_limits::HYBRID_CHECK_EVERY_TICKS`] ticks against the blocks the solver
    /// was built from, and the matrix rebuilt on drift ([`crate::drift`], one code with 2D's).
    fn check_drift(&mut self) {
        use crate::drift::{Checked, check_one};
        use crate::sim::param_limits::HYBRID_CHECK_EVERY_TICKS;
        if self.tick % HYBRID_CHECK_EVERY_TICKS != HYBRID_CHECK_EVERY_TICKS - 1 {
            return;
        }
        let blocks = crate::viscous::ScaledBlocks { cache: &self.cache, scale: self.setup.compliance_scale };
        let checked = check_one(&mut self.solver, &blocks, &mut self.drift);
        self.stats.hybrid_checks += (checked != Checked::Nothing) as u64;
        self.stats.hybrid_rebuilds += (checked == Checked::Rebuilt) as u64;
        self.stats.hybrid_rebuild_failures += (checked == Checked::RebuildFailed) as u64;
    }

    /// The largest relative residual of the hybrid matrix's solution found by the step's
    /// round-off checks so far ([`crate::drift`]; [`Sim3Stats::hybrid_checks`] of them).
    pub fn hybrid_max_residual(&self) -> f64 {
        self.drift.max_residual
    }

    /// Sets the residual above which a check rebuilds the hybrid matrix (default
    /// [`crate::sim::param_limits::HYBRID_DRIFT_TOL`]); a negative value rebuilds at every
    /// check, which tests use to exercise the rebuild.
    pub fn set_hybrid_drift_tol(&mut self, tol: f64) {
        self.drift.tol = tol;
    }
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
