//! `needlesim-lab motions`: the motion suite of issue 15. Five scripted motions at 1 kHz, each
//! entering the phantom (`needlesim_core::fixtures`, 0.1 m square, bottom fixed) at the top
//! centre with the tip starting 5 mm above the surface, on several grid sizes:
//!
//! - **vertical**: a rigid needle inserted 60 mm (base travel) at 10 mm/s, a 1 s hold, withdrawn
//!   at 10 mm/s (the script of `needlesim-lab bench`);
//! - **oblique**: the same along a line 40° from the vertical;
//! - **turning**: inserted 60 mm vertically, then turned ±10° about the entry point while
//!   inserted (two sine periods of 2 s), then withdrawn;
//! - **flexible**: the 22 G flexible needle of the fig4-steering scene along its Fig. 4 path
//!   (down 40 mm, 5 mm sideways, down 50 mm: the scene's CSV), then withdrawn straight up;
//! - **bevel**: the 20 G bevel-tip needle of the bevel-tip scene inserted straight 60 mm, its
//!   bevel flipped half-way ([`Simulation::flip_bevel`]), a 1 s hold, withdrawn.
//!
//! Every run has `columns_in_step: false`: the columns of the nodes the last step reported as
//! approaching are computed between steps ([`Simulation::prefetch_columns`], a bounded number per
//! tick, timed apart), and a contact whose columns are missing waits a tick (a deferral). Only
//! `step` is timed as the step; the stiffness Jacobian is computed and timed apart every
//! [`JACOBIAN_EVERY_TICKS`] ticks, as the real-time loop does. Each tick's solver counters (the
//! active-set iterations, pivots and frame rotations of [`needlesim_core::MixedSolver::stats`],
//! stick/slip changes, captures, shape passes, the working set d) are kept, so the slowest ticks
//! can be explained.

use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::ValueEnum;
use needlesim_core::compliance::TissueModel;
use needlesim_core::fixtures::{self, PHANTOM_SIDE_M};
use needlesim_core::mixed::MixedStats;
use needlesim_core::sim::{ContactModel, SimParams, SimStats};
use needlesim_core::{BasePose, MeshLimits, NeedleShape, RegionNeedleParams, RigidNeedle};
use needlesim_offline::ConvergencePolicy;
use needlesim_offline::driver::{DEFAULT_PREFETCH_NODES_PER_TICK, RunOptions, Script, ScriptedRun};
use serde_json::{Value, json};

use crate::bench::{machine, pct};

// ---------------------------------------------------------------------------------------------
// Constants of the suite.

/// Tick rate of every script (Hz).
pub const TICK_RATE_HZ: f64 = 1000.0;
/// Base travel from the start pose to the deepest point along the insertion line (m); the tip
/// starts [`START_HEIGHT_M`] above the surface, so a vertical insertion puts 55 mm of shaft in
/// the tissue.
pub const TRAVEL_M: f64 = 0.06;
/// Height of the tip above the phantom's top surface at the start (m).
pub const START_HEIGHT_M: f64 = 0.005;
/// Length of the rigid needle (m), as in the benchmark fixture.
pub const RIGID_LENGTH_M: f64 = 0.1;
/// Angle of the oblique insertion line from the vertical (rad): 40°.
pub const OBLIQUE_ANGLE_RAD: f64 = 40.0 * std::f64::consts::PI / 180.0;
/// Amplitude of the turning motion about the entry point (rad): 10°.
pub const TURN_AMPLITUDE_RAD: f64 = 10.0 * std::f64::consts::PI / 180.0;
/// Sine periods of the turning motion.
pub const TURN_PERIODS: usize = 2;
/// The real-time loop's stiffness Jacobian period (ticks; `needlesim-session`'s
/// `STIFFNESS_EVERY_TICKS`, which this crate may not depend on).
pub const JACOBIAN_EVERY_TICKS: usize = 10;
/// Working-set capacity with material points (the scene loader's default `max_nodes`).
pub const MAX_POINTS: usize = 128;
/// Working-set capacity with node capture (the flexible needle's largest: the 400 × 400 grid puts
/// two node columns, ~440 nodes, on a vertical 55 mm).
pub const MAX_CAPTURED_NODES: usize = needlesim_core::sim::param_limits::MAX_NEEDLE_NODES_FLEXIBLE;
/// Issue 15's targets: step p99.9 (s), step max (s).
pub const TARGET_P999_S: f64 = 500e-6;
/// Issue 15's target for the slowest step (s).
pub const TARGET_MAX_S: f64 = 1e-3;
/// Slowest ticks of a case kept with their counters.
pub const WORST_TICKS: usize = 5;

/// The top centre of the phantom, where every motion enters (m).
pub const ENTRY_M: [f64; 2] = [0.5 * PHANTOM_SIDE_M, PHANTOM_SIDE_M];

// ---------------------------------------------------------------------------------------------
// Options.

/// A motion of the suite.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Motion {
    Vertical,
    Oblique,
    Turning,
    Flexible,
    Bevel,
}

impl Motion {
    /// Every motion, in the suite's order.
    pub const ALL: [Motion; 5] = [Motion::Vertical, Motion::Oblique, Motion::Turning, Motion::Flexible, Motion::Bevel];
    /// Its name on the command line and in the tables.
    pub fn name(self) -> &'static str {
        match self {
            Motion::Vertical => "vertical",
            Motion::Oblique => "oblique",
            Motion::Turning => "turning",
            Motion::Flexible => "flexible",
            Motion::Bevel => "bevel",
        }
    }
}

/// Which contact model the needle uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ContactChoice {
    /// Material points every `--spacing-mm` (issue 15; the default of scenes).
    Points,
    /// The paper's node capture, with the scene loader's capture radius (half the mean edge).
    Nodes,
}

/// What to run.
#[derive(Debug, Clone)]
pub struct MotionOptions {
    /// Faster scripts (50 mm/s, 0.2 s hold, 0.4 s turning periods) and 19², 100² by default.
    pub quick: bool,
    /// Grid sizes (nodes per side); the defaults when empty.
    pub sizes: Vec<usize>,
    /// Motions to run; all when empty.
    pub motions: Vec<Motion>,
    pub contact: ContactChoice,
    /// Material-point spacing (m).
    pub spacing_m: f64,
    /// Nodes whose columns are computed between two steps.
    pub prefetch_nodes_per_tick: usize,
    /// Print a progress line per case on stderr.
    pub progress: bool,
    /// Stop a case (recorded as failed) when its column cache outgrows this many bytes: the
    /// cache keeps every column it was given (two columns of 2n doubles per node, 5.1 MB a node
    /// on 400 × 400), and the bevel motion on 400 × 400 asks for ~4200 nodes.
    pub max_column_bytes: Option<usize>,
}

impl Default for MotionOptions {
    fn default() -> Self {
        Self {
            quick: false,
            sizes: vec![],
            motions: vec![],
            contact: ContactChoice::Points,
            spacing_m: ContactModel::DEFAULT_SPACING_M,
            prefetch_nodes_per_tick: DEFAULT_PREFETCH_NODES_PER_TICK,
            progress: true,
            max_column_bytes: None,
        }
    }
}

impl MotionOptions {
    /// The grid sizes to run.
    pub fn sizes(&self) -> Vec<usize> {
        if !self.sizes.is_empty() {
            self.sizes.clone()
        } else if self.quick {
            vec![19, 100]
        } else {
            vec![19, 100, 200, 400]
        }
    }
    /// The motions to run.
    pub fn motions(&self) -> Vec<Motion> {
        if self.motions.is_empty() { Motion::ALL.to_vec() } else { self.motions.clone() }
    }
}

/// The speeds of the scripts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pace {
    /// Insertion and withdrawal speed (m/s).
    pub insert_m_s: f64,
    /// Hold at the deepest point (s).
    pub hold_s: f64,
    /// Period of one ±10° sine of the turning motion (s).
    pub turn_period_s: f64,
}

impl Pace {
    /// The suite's speeds: 10 mm/s, 1 s hold, 2 s turning periods.
    pub const FULL: Pace = Pace { insert_m_s: 0.01, hold_s: 1.0, turn_period_s: 2.0 };
    /// `--quick`: 50 mm/s, 0.2 s hold, 0.4 s turning periods.
    pub const QUICK: Pace = Pace { insert_m_s: 0.05, hold_s: 0.2, turn_period_s: 0.4 };
    /// The pace of the options.
    pub fn of(quick: bool) -> Pace {
        if quick { Pace::QUICK } else { Pace::FULL }
    }
}

// ---------------------------------------------------------------------------------------------
// Scripts.

/// A named stretch of a script, from `first_tick` to the next phase's.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    pub name: &'static str,
    pub first_tick: usize,
}

/// One motion's script and needle.
#[derive(Debug, Clone)]
pub struct MotionScript {
    pub motion: Motion,
    /// The simulation's initial pose (tick "−1").
    pub initial_pose: BasePose,
    /// One commanded pose per tick.
    pub poses: Vec<BasePose>,
    pub phases: Vec<Phase>,
    /// The last tick of the insertion (the deepest point).
    pub deepest_tick: usize,
    /// The bevel is flipped just before this tick's step.
    pub flip_tick: Option<usize>,
    pub needle: NeedleShape,
    /// Needle–tissue parameters of the phantom's one region.
    pub region: RegionNeedleParams,
    /// The needle in a few words.
    pub needle_label: String,
    /// The script in a sentence.
    pub description: String,
}

impl MotionScript {
    /// The phase a tick belongs to.
    pub fn phase_of(&self, tick: usize) -> &'static str {
        self.phases.iter().rev().find(|p| p.first_tick <= tick).map_or("", |p| p.name)
    }
}

/// Builds a script tick by tick.
struct PathBuilder {
    start: BasePose,
    poses: Vec<BasePose>,
    phases: Vec<Phase>,
}

impl PathBuilder {
    fn new(start: BasePose) -> Self {
        Self { start, poses: Vec::new(), phases: Vec::new() }
    }
    fn last(&self) -> BasePose {
        self.poses.last().copied().unwrap_or(self.start)
    }
    fn phase(&mut self, name: &'static str) {
        self.phases.push(Phase { name, first_tick: self.poses.len() });
    }
    /// Straight to `to` (pose components interpolated linearly) in `duration_s`, at least one tick.
    fn linear_to(&mut self, to: BasePose, duration_s: f64) {
        let from = self.last();
        let n = ((duration_s * TICK_RATE_HZ).round() as usize).max(1);
        for k in 1..=n {
            let a = k as f64 / n as f64;
            self.poses.push(BasePose::new(
                from.x_m + a * (to.x_m - from.x_m),
                from.y_m + a * (to.y_m - from.y_m),
                from.theta_rad + a * (to.theta_rad - from.theta_rad),
            ));
        }
    }
    /// Straight to `to` at `speed_m_s` (base translation).
    fn move_to(&mut self, to: BasePose, speed_m_s: f64) {
        let from = self.last();
        self.linear_to(to, (to.x_m - from.x_m).hypot(to.y_m - from.y_m) / speed_m_s);
    }
    fn hold(&mut self, duration_s: f64) {
        let p = self.last();
        let n = (duration_s * TICK_RATE_HZ).round() as usize;
        self.poses.extend(std::iter::repeat_n(p, n));
    }
}

/// The base pose of a needle of length `length_m` at angle `theta_rad` whose tip lies `s_m` of
/// arc length beyond the entry point (negative: before it, outside the tissue).
fn pose_with_tip_at(theta_rad: f64, length_m: f64, s_m: f64) -> BasePose {
    let (sin, cos) = theta_rad.sin_cos();
    let back = length_m - s_m;
    BasePose::new(ENTRY_M[0] - back * cos, ENTRY_M[1] - back * sin, theta_rad)
}

/// A straight insertion along the line at `theta_rad` through the entry point: tip from
/// [`START_HEIGHT_M`] above the surface, [`TRAVEL_M`] of travel, a hold, and back.
fn straight(length_m: f64, theta_rad: f64, pace: Pace, with_hold: bool) -> (PathBuilder, usize) {
    // 5 mm above the surface, measured vertically, on the insertion line.
    let s0 = -START_HEIGHT_M / (-theta_rad.sin());
    let start = pose_with_tip_at(theta_rad, length_m, s0);
    let deepest = pose_with_tip_at(theta_rad, length_m, s0 + TRAVEL_M);
    let mut b = PathBuilder::new(start);
    b.phase("insert");
    b.move_to(deepest, pace.insert_m_s);
    let deepest_tick = b.poses.len() - 1;
    if with_hold && pace.hold_s > 0.0 {
        b.phase("hold");
        b.hold(pace.hold_s);
    }
    (b, deepest_tick)
}

/// The vertical angle (the needle pointing down).
const DOWN_RAD: f64 = -std::f64::consts::FRAC_PI_2;

/// The suite's rigid needle.
fn rigid_needle() -> NeedleShape {
    NeedleShape::Rigid(RigidNeedle { length_m: RIGID_LENGTH_M })
}

/// The needle, region parameters and trajectory CSV of a shipped scene.
fn scene_needle(name: &str) -> Result<(NeedleShape, RegionNeedleParams, &'static str)> {
    let scene = needlesim_scene::load_scene(name, &MeshLimits::default()).with_context(|| format!("scene {name}"))?;
    anyhow::ensure!(scene.params.regions.len() == 1, "scene {name}: one region expected");
    let csv = scene.example_trajectory.with_context(|| format!("scene {name} ships no trajectory"))?;
    Ok((scene.params.needle, scene.params.regions[0], csv))
}

fn needle_label_of(needle: &NeedleShape, gauge: u32) -> String {
    match needle.flexible() {
        Some(f) if f.bevel_force_ratio > 0.0 => format!(
            "flexible {gauge} G bevel tip ({:.0} mm, EI = {:.2e} N·m², {} links, bevel ratio {})",
            f.length_m * 1e3,
            f.flexural_rigidity_nm2,
            f.n_links,
            f.bevel_force_ratio
        ),
        Some(f) => {
            format!("flexible {gauge} G ({:.0} mm, EI = {:.2e} N·m², {} links)", f.length_m * 1e3, f.flexural_rigidity_nm2, f.n_links)
        }
        None => format!("rigid {:.0} mm", needle.tip_s_m() * 1e3),
    }
}

/// The script of a motion at a pace.
///
/// Errors: a shipped scene (fig4-steering, bevel-tip) that does not load or has no trajectory.
pub fn script(motion: Motion, pace: Pace) -> Result<MotionScript> {
    let v_mm_s = pace.insert_m_s * 1e3;
    let travel_mm = TRAVEL_M * 1e3;
    let region = RegionNeedleParams::default();
    match motion {
        Motion::Vertical | Motion::Oblique => {
            let angle = if motion == Motion::Oblique { OBLIQUE_ANGLE_RAD } else { 0.0 };
            let (mut b, deepest_tick) = straight(RIGID_LENGTH_M, DOWN_RAD + angle, pace, true);
            b.phase("withdraw");
            b.move_to(b.start, pace.insert_m_s);
            let how = if motion == Motion::Oblique { "along a line 40° from the vertical (towards +x)" } else { "vertically" };
            Ok(MotionScript {
                motion,
                initial_pose: b.start,
                deepest_tick,
                flip_tick: None,
                needle: rigid_needle(),
                region,
                needle_label: needle_label_of(&rigid_needle(), 0),
                description: format!(
                    "inserted {how} through the top centre, {travel_mm:.0} mm of base travel at {v_mm_s:.0} mm/s, {} s hold, withdrawn at {v_mm_s:.0} mm/s",
                    pace.hold_s
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
        Motion::Turning => {
            let (mut b, deepest_tick) = straight(RIGID_LENGTH_M, DOWN_RAD, pace, false);
            // The tip's arc length beyond the entry point, held while the needle turns about it.
            let s_tip_m = TRAVEL_M - START_HEIGHT_M;
            b.phase("turn");
            let n = (TURN_PERIODS as f64 * pace.turn_period_s * TICK_RATE_HZ).round() as usize;
            for k in 1..=n {
                let t_s = k as f64 / TICK_RATE_HZ;
                let phi = TURN_AMPLITUDE_RAD * (std::f64::consts::TAU * t_s / pace.turn_period_s).sin();
                b.poses.push(pose_with_tip_at(DOWN_RAD + phi, RIGID_LENGTH_M, s_tip_m));
            }
            b.phase("withdraw");
            b.move_to(b.start, pace.insert_m_s);
            Ok(MotionScript {
                motion,
                initial_pose: b.start,
                deepest_tick,
                flip_tick: None,
                needle: rigid_needle(),
                region,
                needle_label: needle_label_of(&rigid_needle(), 0),
                description: format!(
                    "inserted vertically {travel_mm:.0} mm at {v_mm_s:.0} mm/s, turned ±10° about the entry point ({TURN_PERIODS} sine periods of {} s, peak {:.2} rad/s), withdrawn at {v_mm_s:.0} mm/s",
                    pace.turn_period_s,
                    TURN_AMPLITUDE_RAD * std::f64::consts::TAU / pace.turn_period_s
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
        Motion::Flexible => {
            let (needle, region, csv) = scene_needle("fig4-steering")?;
            let traj = needlesim_scene::Trajectory::parse_csv(csv).context("fig4-steering.csv")?;
            let samples = &traj.samples;
            anyhow::ensure!(samples.len() >= 2, "fig4-steering.csv: at least two samples");
            let start = needlesim_scene::base_pose(samples[0].1);
            // The CSV's own insertion speed (its first segment) sets the time scale.
            let (t1, p1) = (samples[1].0 - samples[0].0, needlesim_scene::base_pose(samples[1].1));
            let csv_speed_m_s = (p1.x_m - start.x_m).hypot(p1.y_m - start.y_m) / t1;
            let time_scale = csv_speed_m_s / pace.insert_m_s;
            let mut b = PathBuilder::new(start);
            let names = ["insert", "sideways", "insert"];
            for (k, w) in samples.windows(2).enumerate() {
                b.phase(names.get(k).copied().unwrap_or("insert"));
                b.linear_to(needlesim_scene::base_pose(w[1].1), (w[1].0 - w[0].0) * time_scale);
            }
            let deepest_tick = b.poses.len() - 1;
            let last = b.last();
            b.phase("withdraw");
            b.move_to(BasePose::new(last.x_m, start.y_m, last.theta_rad), pace.insert_m_s);
            let gauge = 22;
            Ok(MotionScript {
                motion,
                initial_pose: start,
                deepest_tick,
                flip_tick: None,
                needle_label: needle_label_of(&needle, gauge),
                needle,
                region,
                description: format!(
                    "the Fig. 4 path of fig4-steering.csv at {v_mm_s:.0} mm/s: base down {:.0} mm, {:.0} mm sideways in {:.0} ms, down {:.0} mm; then withdrawn straight up at {v_mm_s:.0} mm/s",
                    (start.y_m - p1.y_m) * 1e3,
                    samples.get(2).map_or(0.0, |s| (s.1.x_m - p1.x_m) * 1e3),
                    samples.get(2).map_or(0.0, |s| (s.0 - samples[1].0) * time_scale * 1e3),
                    samples.get(3).map_or(0.0, |s| (samples[2].1.y_m - s.1.y_m) * 1e3),
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
        Motion::Bevel => {
            let (needle, region, _) = scene_needle("bevel-tip")?;
            let (mut b, deepest_tick) = straight(needle.tip_s_m(), DOWN_RAD, pace, true);
            b.phase("withdraw");
            b.move_to(b.start, pace.insert_m_s);
            // Half-way through the insertion.
            let flip_tick = deepest_tick / 2;
            Ok(MotionScript {
                motion,
                initial_pose: b.start,
                deepest_tick,
                flip_tick: Some(flip_tick),
                needle_label: needle_label_of(&needle, 20),
                needle,
                region,
                description: format!(
                    "inserted straight {travel_mm:.0} mm at {v_mm_s:.0} mm/s, the bevel flipped half-way ({:.0} mm of travel), {} s hold, withdrawn at {v_mm_s:.0} mm/s; bevel-tip's region (cutting force {} N)",
                    travel_mm / 2.0,
                    pace.hold_s,
                    region.cutting_force_n
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
    }
}

/// The simulation parameters of a script on a model: the fixture's ([`fixtures::phantom_params`])
/// with the script's needle, pose and region, the chosen contact, and no column ever computed in
/// a step.
pub fn sim_params(script: &MotionScript, model: &TissueModel, contact: ContactChoice, spacing_m: f64) -> SimParams {
    let (contact, max_needle_nodes) = match contact {
        ContactChoice::Points => (ContactModel::MaterialPoints { spacing_m, width_m: 0.0 }, MAX_POINTS),
        ContactChoice::Nodes => (ContactModel::Nodes, MAX_CAPTURED_NODES),
    };
    SimParams {
        initial_pose: script.initial_pose,
        contact,
        columns_in_step: false,
        capture_radius_m: 0.5 * needlesim_scene::mean_edge_m(model.mesh()),
        max_needle_nodes,
        regions: vec![script.region],
        tick_rate_hz: TICK_RATE_HZ,
        ..fixtures::phantom_params(script.needle)
    }
}

// ---------------------------------------------------------------------------------------------
// Measurement.

/// One tick's counters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TickRecord {
    pub tick: usize,
    pub step_s: f64,
    pub converged: bool,
    pub active_set_iterations: usize,
    /// Pivots of the mixed solver in this tick.
    pub pivots: u64,
    /// Frame rotations of the mixed solver in this tick.
    pub rotations: u64,
    /// Stick→slip plus slip→stick changes.
    pub stick_slip_changes: u64,
    pub captures: u64,
    pub releases: u64,
    pub deferrals: u64,
    /// Extra working-set solves on a settled flexible shape.
    pub shape_passes: u64,
    /// Working set after the step.
    pub d: usize,
    /// Time the thread spent waiting on a run queue around this step (ns; [`ThreadCounters`]):
    /// a step that waited was preempted by another process, and its time is not all the solver's.
    pub cpu_wait_ns: u64,
    /// Page faults around this step ([`ThreadCounters`]).
    pub page_faults: u64,
    /// Columns computed by the prefetch just before this step (it streams the sparse factor
    /// through the caches, so the step after it starts cold).
    pub columns_before: u64,
    /// Nanoseconds in each stage of the step ([`needlesim_core::sim::STAGE_NAMES`]).
    pub stage_ns: [u64; needlesim_core::sim::N_STAGES],
}

/// Nanoseconds on a monotonic clock since its first reading: the step's stage clock.
fn monotonic_ns() -> u64 {
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_nanos() as u64
}

/// One (motion, mesh) case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    pub motion: Motion,
    pub n: usize,
    pub contact: ContactChoice,
    pub needle_label: String,
    /// The script's poses (ticks it should step).
    pub script_ticks: usize,
    pub ticks: Vec<TickRecord>,
    /// Stiffness Jacobian times (s), one per [`JACOBIAN_EVERY_TICKS`] ticks.
    pub jacobian_s: Vec<f64>,
    pub jacobian_errors: usize,
    pub stats: SimStats,
    pub solver: MixedStats,
    /// Largest working set over the run.
    pub d_max: usize,
    /// Working set at the deepest tick.
    pub d_deepest: usize,
    /// Working set after the last tick.
    pub d_final: usize,
    /// Factorisation of the mesh (shared by its cases), s.
    pub setup_s: f64,
    /// Column prefetch between steps, total s.
    pub prefetch_s: f64,
    pub prefetched_nodes: u64,
    /// Bytes of compliance columns cached at the end of the run (never evicted).
    pub column_cache_bytes: usize,
    /// Deepest tip below the top surface over the run (m).
    pub tip_depth_max_m: f64,
    /// The tip at the deepest tick (m).
    pub tip_deepest_m: [f64; 2],
    /// Range of the applied base angle (rad).
    pub theta_range_rad: [f64; 2],
    /// Range of the tip's x over the run (m).
    pub tip_x_range_m: [f64; 2],
    /// Range of the base's x over the run (m).
    pub base_x_range_m: [f64; 2],
    /// Bevel side before the first step and after the last.
    pub bevel_side_first_last: [f64; 2],
    /// The smallest working set during the turning phase (turning motion; else 0).
    pub d_min_turning: usize,
    /// The 1-min load average at the start and end of the case.
    pub load_avg: [f64; 2],
    pub wall_s: f64,
    /// Why the run stopped early, if it did.
    pub failed: Option<String>,
}

/// Step time quantiles (s): p50, p99, p99.9, max.
pub fn step_quantiles(records: &[TickRecord]) -> [f64; 4] {
    let mut t: Vec<f64> = records.iter().map(|r| r.step_s).collect();
    t.sort_by(f64::total_cmp);
    [pct(&t, 0.5), pct(&t, 0.99), pct(&t, 0.999), pct(&t, 1.0)]
}

impl CaseResult {
    /// p50, p99, p99.9, max of the step (s).
    pub fn step_quantiles(&self) -> [f64; 4] {
        step_quantiles(&self.ticks)
    }
    /// Ticks that waited on a run queue (preempted by another process) during the step.
    pub fn preempted_ticks(&self) -> usize {
        self.ticks.iter().filter(|r| r.cpu_wait_ns > 0).count()
    }
    /// p99.9 and max of the step over the ticks that never waited on a run queue (s).
    pub fn unpreempted_quantiles(&self) -> [f64; 2] {
        let mut t: Vec<f64> = self.ticks.iter().filter(|r| r.cpu_wait_ns == 0).map(|r| r.step_s).collect();
        t.sort_by(f64::total_cmp);
        [pct(&t, 0.999), pct(&t, 1.0)]
    }
    /// p50, p99, max of the Jacobian (s).
    pub fn jacobian_quantiles(&self) -> [f64; 3] {
        let mut t = self.jacobian_s.clone();
        t.sort_by(f64::total_cmp);
        [pct(&t, 0.5), pct(&t, 0.99), pct(&t, 1.0)]
    }
    /// The slowest ticks, slowest first (all, or only those no other process preempted).
    pub fn worst(&self, k: usize, unpreempted: bool) -> Vec<TickRecord> {
        let mut w: Vec<TickRecord> = self.ticks.iter().filter(|r| !unpreempted || r.cpu_wait_ns == 0).cloned().collect();
        w.sort_by(|a, b| b.step_s.total_cmp(&a.step_s));
        w.truncate(k);
        w
    }
    /// The targets this case misses (empty: all met).
    pub fn misses(&self) -> Vec<String> {
        let mut m = Vec::new();
        if let Some(why) = &self.failed {
            m.push(format!("failed: {why}"));
        }
        let [_, _, p999, max] = self.step_quantiles();
        // NaN (no ticks) misses too.
        if p999.is_nan() || p999 > TARGET_P999_S {
            m.push("p99.9".to_owned());
        }
        if max.is_nan() || max > TARGET_MAX_S {
            m.push("max".to_owned());
        }
        if self.stats.unconverged_ticks > 0 {
            m.push(format!("{} unconverged", self.stats.unconverged_ticks));
        }
        if self.stats.column_misses > 0 {
            m.push(format!("{} column misses", self.stats.column_misses));
        }
        m
    }
    /// What is not one of the targets but a run should not do: capacity overflows (a
    /// candidate-buffer growth is an allocation inside a step), failed Jacobians.
    pub fn notes(&self) -> Vec<String> {
        let s = &self.stats;
        let mut m = Vec::new();
        for (n, what) in [
            (s.capacity_drops, "contacts dropped at capacity"),
            (s.capture_overflow, "capture-list overflows"),
            (s.approaching_overflow, "approaching-list overflows"),
            (s.candidate_growths, "candidate-buffer growth (an allocation in a step)"),
            (s.curve_capacity_drops, "curve capacity drops"),
            (s.shape_capped_ticks, "ticks whose flexible shape passes stopped at their cap"),
            (self.jacobian_errors as u64, "failed Jacobians"),
        ] {
            if n > 0 {
                m.push(format!("{n} {what}"));
            }
        }
        m
    }
}

/// This thread's counters from procfs, read around each step to tell a slow step from one the
/// machine slowed: the time waited on a run queue (`/proc/thread-self/schedstat`, its second
/// field: another process had the core) and the page faults (`/proc/thread-self/stat`, minflt +
/// majflt). Missing files (a kernel without schedstats) read as `None`.
pub struct ThreadCounters {
    schedstat: Option<std::fs::File>,
    stat: Option<std::fs::File>,
    buf: String,
}

/// One reading of [`ThreadCounters`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ThreadSample {
    /// Time waited on a run queue so far (ns).
    pub wait_ns: Option<u64>,
    /// Minor and major page faults so far.
    pub page_faults: Option<u64>,
}

impl ThreadCounters {
    /// Opens this thread's files.
    pub fn open() -> Self {
        let open = |p: &str| std::fs::File::open(p).ok();
        Self { schedstat: open("/proc/thread-self/schedstat"), stat: open("/proc/thread-self/stat"), buf: String::with_capacity(512) }
    }
    fn read(file: Option<&mut std::fs::File>, buf: &mut String) -> Option<()> {
        use std::io::{Read, Seek};
        let f = file?;
        buf.clear();
        f.rewind().ok()?;
        f.read_to_string(buf).ok()?;
        Some(())
    }
    /// The counters now.
    pub fn sample(&mut self) -> ThreadSample {
        let wait_ns = Self::read(self.schedstat.as_mut(), &mut self.buf).and_then(|()| self.buf.split_whitespace().nth(1)?.parse().ok());
        let page_faults = Self::read(self.stat.as_mut(), &mut self.buf).and_then(|()| {
            // After the command name in parentheses: state, ppid, pgrp, session, tty_nr, tpgid,
            // flags, minflt, cminflt, majflt.
            let rest = &self.buf[self.buf.rfind(')')? + 1..];
            let f: Vec<&str> = rest.split_whitespace().take(10).collect();
            Some(f.get(7)?.parse::<u64>().ok()? + f.get(9)?.parse::<u64>().ok()?)
        });
        ThreadSample { wait_ns, page_faults }
    }
}

fn load_avg() -> f64 {
    std::fs::read_to_string("/proc/loadavg").ok().and_then(|s| s.split_whitespace().next().and_then(|v| v.parse().ok())).unwrap_or(f64::NAN)
}

fn range(r: &mut [f64; 2], v: f64) {
    r[0] = r[0].min(v);
    r[1] = r[1].max(v);
}

/// Runs one script on a factorised model (`setup_s`: how long its factorisation took).
///
/// Errors: the simulation cannot be built from the parameters. A step, Jacobian or prefetch
/// failure mid-run does not fail: the case records it ([`CaseResult::failed`]) with the ticks
/// before it.
pub fn run_case(script: &MotionScript, model: &Arc<TissueModel>, setup_s: f64, opts: &MotionOptions) -> Result<CaseResult> {
    let started = Instant::now();
    let load_start = load_avg();
    let n = (model.mesh().n_nodes() as f64).sqrt().round() as usize;
    let params = sim_params(script, model, opts.contact, opts.spacing_m);
    let mut run = ScriptedRun::new(
        model.clone(),
        params,
        Script::Poses(&script.poses),
        RunOptions { max_ticks: u64::MAX, prefetch_nodes_per_tick: Some(0), convergence: ConvergencePolicy::Keep },
    )?;
    let mut res = CaseResult {
        motion: script.motion,
        n,
        contact: opts.contact,
        needle_label: script.needle_label.clone(),
        script_ticks: script.poses.len(),
        ticks: Vec::with_capacity(script.poses.len()),
        jacobian_s: Vec::with_capacity(script.poses.len() / JACOBIAN_EVERY_TICKS + 1),
        jacobian_errors: 0,
        stats: SimStats::default(),
        solver: MixedStats::default(),
        d_max: 0,
        d_deepest: 0,
        d_final: 0,
        setup_s,
        prefetch_s: 0.0,
        prefetched_nodes: 0,
        column_cache_bytes: 0,
        tip_depth_max_m: f64::NEG_INFINITY,
        tip_deepest_m: [f64::NAN; 2],
        theta_range_rad: [f64::INFINITY, f64::NEG_INFINITY],
        tip_x_range_m: [f64::INFINITY, f64::NEG_INFINITY],
        base_x_range_m: [f64::INFINITY, f64::NEG_INFINITY],
        bevel_side_first_last: [run.sim().bevel_side(), f64::NAN],
        d_min_turning: if script.motion == Motion::Turning { usize::MAX } else { 0 },
        load_avg: [load_start, f64::NAN],
        wall_s: 0.0,
        failed: None,
    };
    run.sim_mut().set_stage_clock(Some(monotonic_ns));
    let mut counters = ThreadCounters::open();
    let turning = script.phases.iter().position(|p| p.name == "turn").map(|i| {
        let end = script.phases.get(i + 1).map_or(script.poses.len(), |p| p.first_tick);
        script.phases[i].first_tick..end
    });
    loop {
        let k = run.next_k() as usize;
        let mut columns_before = 0;
        if k > 0 {
            // Between steps, untimed as the step: the columns of the nodes the last step reported
            // as approaching (as the server's column worker would provide them).
            let t = Instant::now();
            match run.sim_mut().prefetch_columns(opts.prefetch_nodes_per_tick) {
                Ok(c) => {
                    columns_before = c as u64;
                    res.prefetched_nodes += c as u64;
                }
                Err(e) => {
                    res.failed = Some(format!("prefetch after tick {}: {e}", k - 1));
                    break;
                }
            }
            res.prefetch_s += t.elapsed().as_secs_f64();
            let bytes = run.sim().cache().column_bytes();
            if let Some(limit) = opts.max_column_bytes
                && bytes > limit
            {
                res.failed = Some(format!(
                    "column cache {:.2} GB over the limit of {:.2} GB after tick {}",
                    bytes as f64 / 1e9,
                    limit as f64 / 1e9,
                    k - 1
                ));
                break;
            }
        }
        if script.flip_tick == Some(k) {
            run.sim_mut().flip_bevel();
        }
        let (sim_before, solver_before) = (run.sim().stats(), run.sim().solver().stats());
        let before = counters.sample();
        let tick = match run.next_tick() {
            Ok(Some(t)) => t,
            Ok(None) => break,
            Err(e) => {
                res.failed = Some(format!("{e:#}"));
                break;
            }
        };
        let after = counters.sample();
        let delta = |a: Option<u64>, b: Option<u64>| a.zip(b).map_or(0, |(a, b)| b.saturating_sub(a));
        let sim = run.sim();
        let (s, v) = (sim.stats(), sim.solver().stats());
        let out = sim.output();
        let d = out.needle_nodes.len();
        res.ticks.push(TickRecord {
            tick: k,
            step_s: tick.step_s,
            converged: out.converged,
            active_set_iterations: out.active_set_iterations,
            pivots: v.n_pivots - solver_before.n_pivots,
            rotations: v.n_rotations - solver_before.n_rotations,
            stick_slip_changes: (s.stick_to_slip + s.slip_to_stick) - (sim_before.stick_to_slip + sim_before.slip_to_stick),
            captures: s.captures - sim_before.captures,
            releases: s.releases - sim_before.releases,
            deferrals: s.column_deferrals - sim_before.column_deferrals,
            shape_passes: s.shape_passes - sim_before.shape_passes,
            d,
            cpu_wait_ns: delta(before.wait_ns, after.wait_ns),
            page_faults: delta(before.page_faults, after.page_faults),
            columns_before,
            stage_ns: out.stage_ns,
        });
        res.d_max = res.d_max.max(d);
        if k == script.deepest_tick {
            res.d_deepest = d;
            res.tip_deepest_m = out.tip_m;
        }
        if turning.as_ref().is_some_and(|r| r.contains(&k)) {
            res.d_min_turning = res.d_min_turning.min(d);
        }
        res.tip_depth_max_m = res.tip_depth_max_m.max(PHANTOM_SIDE_M - out.tip_m[1]);
        range(&mut res.theta_range_rad, out.base.theta_rad);
        range(&mut res.tip_x_range_m, out.tip_m[0]);
        range(&mut res.base_x_range_m, out.base.x_m);
        if k.is_multiple_of(JACOBIAN_EVERY_TICKS) {
            let t = Instant::now();
            let j = run.sim_mut().stiffness_jacobian();
            res.jacobian_s.push(t.elapsed().as_secs_f64());
            res.jacobian_errors += j.is_err() as usize;
        }
    }
    let sim = run.sim();
    res.stats = sim.stats();
    res.solver = sim.solver().stats();
    res.d_final = sim.output().needle_nodes.len();
    res.column_cache_bytes = sim.cache().column_bytes();
    res.bevel_side_first_last[1] = sim.bevel_side();
    if res.d_min_turning == usize::MAX {
        res.d_min_turning = 0;
    }
    res.load_avg[1] = load_avg();
    res.wall_s = started.elapsed().as_secs_f64();
    Ok(res)
}

/// The suite: every motion on every size.
pub struct Suite {
    pub pace: Pace,
    pub scripts: Vec<MotionScript>,
    pub cases: Vec<CaseResult>,
}

/// Runs the suite.
///
/// Errors: a grid under 3 nodes per side, a scene that does not load, a model that does not
/// factorise, parameters the simulation refuses.
pub fn run_suite(opts: &MotionOptions) -> Result<Suite> {
    let sizes = opts.sizes();
    if let Some(&bad) = sizes.iter().find(|&&n| n < 3) {
        anyhow::bail!("grid size {bad} is too small: at least 3 nodes per side");
    }
    let pace = Pace::of(opts.quick);
    let scripts: Vec<MotionScript> = opts.motions().into_iter().map(|m| script(m, pace)).collect::<Result<_>>()?;
    let total = sizes.len() * scripts.len();
    let mut cases = Vec::with_capacity(total);
    for &n in &sizes {
        let (mesh, mats, fixed) = fixtures::phantom_parts(n);
        let t = Instant::now();
        let model = Arc::new(TissueModel::new(mesh, mats, &fixed).with_context(|| format!("factorising the {n}x{n} phantom"))?);
        let setup_s = t.elapsed().as_secs_f64();
        for s in &scripts {
            if opts.progress {
                eprintln!(
                    "[{}/{total}] {} {n}x{n} ({:?}): {} ticks… (load {:.2})",
                    cases.len() + 1,
                    s.motion.name(),
                    opts.contact,
                    s.poses.len(),
                    load_avg()
                );
            }
            let c = run_case(s, &model, setup_s, opts)?;
            if opts.progress {
                let [p50, p99, p999, max] = c.step_quantiles();
                let misses = c.misses();
                eprintln!(
                    "[{}/{total}] {} {n}x{n}: p50 {} p99 {} p99.9 {} max {} µs, {} unconverged, {} misses, {} deferrals, d {} (max {}), prefetch {:.1} s ({:.2} GB of columns), wall {:.1} s, load {:.2}{}{}",
                    cases.len() + 1,
                    s.motion.name(),
                    us(p50),
                    us(p99),
                    us(p999),
                    us(max),
                    c.stats.unconverged_ticks,
                    c.stats.column_misses,
                    c.stats.column_deferrals,
                    c.d_deepest,
                    c.d_max,
                    c.prefetch_s,
                    c.column_cache_bytes as f64 / 1e9,
                    c.wall_s,
                    c.load_avg[1],
                    if misses.is_empty() { " — targets met".to_owned() } else { format!(" — misses: {}", misses.join(", ")) },
                    if c.notes().is_empty() { String::new() } else { format!(" ({})", c.notes().join(", ")) }
                );
            }
            cases.push(c);
        }
    }
    Ok(Suite { pace, scripts, cases })
}

// ---------------------------------------------------------------------------------------------
// Output.

fn us(v: f64) -> String {
    if v.is_finite() { format!("{:.1}", v * 1e6) } else { "—".to_owned() }
}

fn num(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

fn targets_cell(misses: &[String], notes: &[String]) -> String {
    let mut cell = if misses.is_empty() { "met".to_owned() } else { format!("**misses**: {}", misses.join(", ")) };
    if !notes.is_empty() {
        let _ = write!(cell, "; _{}_", notes.join(", "));
    }
    cell
}

fn contact_label(c: ContactChoice, spacing_m: f64) -> String {
    match c {
        ContactChoice::Points => format!("material points every {:.1} mm", spacing_m * 1e3),
        ContactChoice::Nodes => "node capture, radius ½ mean edge".to_owned(),
    }
}

fn record_json(r: &TickRecord, phase: &str) -> Value {
    json!({
        "tick": r.tick, "phase": phase, "step_s": r.step_s, "converged": r.converged,
        "active_set_iterations": r.active_set_iterations, "pivots": r.pivots, "rotations": r.rotations,
        "stick_slip_changes": r.stick_slip_changes, "captures": r.captures, "releases": r.releases,
        "deferrals": r.deferrals, "shape_passes": r.shape_passes, "d": r.d, "cpu_wait_s": r.cpu_wait_ns as f64 * 1e-9,
        "page_faults": r.page_faults, "columns_before": r.columns_before,
        "stage_us": needlesim_core::sim::STAGE_NAMES.iter().zip(r.stage_ns).map(|(name, ns)| (name.to_string(), json!(ns as f64 * 1e-3))).collect::<serde_json::Map<_, _>>(),
    })
}

/// Every tick of every case as CSV: the case, the tick and its phase, the step time, the
/// counters of [`TickRecord`] and the time of each stage ([`needlesim_core::sim::STAGE_NAMES`]).
pub fn ticks_csv(suite: &Suite) -> String {
    use std::fmt::Write as _;
    let mut out = String::from(
        "motion,mesh,tick,phase,step_us,cpu_wait_us,page_faults,columns_before,active_set_iterations,pivots,rotations,stick_slip_changes,captures,releases,deferrals,shape_passes,d",
    );
    for name in needlesim_core::sim::STAGE_NAMES {
        let _ = write!(out, ",{}_us", name.replace(' ', "_"));
    }
    out.push('\n');
    for c in &suite.cases {
        let script = suite.scripts.iter().find(|s| s.motion == c.motion);
        for r in &c.ticks {
            let phase = script.map_or("", |sc| sc.phase_of(r.tick));
            let _ = write!(
                out,
                "{},{}x{},{},{phase},{:.3},{:.3},{},{},{},{},{},{},{},{},{},{},{}",
                c.motion.name(),
                c.n,
                c.n,
                r.tick,
                r.step_s * 1e6,
                r.cpu_wait_ns as f64 * 1e-3,
                r.page_faults,
                r.columns_before,
                r.active_set_iterations,
                r.pivots,
                r.rotations,
                r.stick_slip_changes,
                r.captures,
                r.releases,
                r.deferrals,
                r.shape_passes,
                r.d
            );
            for ns in r.stage_ns {
                let _ = write!(out, ",{:.3}", ns as f64 * 1e-3);
            }
            out.push('\n');
        }
    }
    out
}

/// The suite as one JSON object.
pub fn to_json(suite: &Suite, opts: &MotionOptions) -> Value {
    let script_of = |m: Motion| suite.scripts.iter().find(|s| s.motion == m);
    let cases: Vec<Value> = suite
        .cases
        .iter()
        .map(|c| {
            let [p50, p99, p999, max] = c.step_quantiles();
            let [j50, j99, jmax] = c.jacobian_quantiles();
            let s = &c.stats;
            let phase = |r: &TickRecord| script_of(c.motion).map_or("", |sc| sc.phase_of(r.tick));
            let worst: Vec<Value> = c.worst(WORST_TICKS, false).iter().map(|r| record_json(r, phase(r))).collect();
            let worst_unpreempted: Vec<Value> = c.worst(WORST_TICKS, true).iter().map(|r| record_json(r, phase(r))).collect();
            let unconverged: Vec<Value> = c
                .ticks
                .iter()
                .filter(|r| !r.converged)
                .take(20)
                .map(|r| record_json(r, script_of(c.motion).map_or("", |sc| sc.phase_of(r.tick))))
                .collect();
            // Columns prefetched before the ticks of each phase.
            let mut by_phase = serde_json::Map::new();
            if let Some(sc) = script_of(c.motion) {
                for r in &c.ticks {
                    let e = by_phase.entry(sc.phase_of(r.tick)).or_insert(json!(0));
                    *e = json!(e.as_u64().unwrap_or(0) + r.columns_before);
                }
            }
            let slow: Vec<&TickRecord> = c.ticks.iter().filter(|r| r.step_s > TARGET_P999_S).collect();
            let mut o = json!({
                "motion": c.motion.name(), "mesh": format!("{}x{}", c.n, c.n), "n_nodes": c.n * c.n,
                "needle": c.needle_label, "contact": contact_label(c.contact, opts.spacing_m),
                "ticks": c.ticks.len(), "script_ticks": c.script_ticks,
                "step_p50_s": num(p50), "step_p99_s": num(p99), "step_p999_s": num(p999), "step_max_s": num(max),
                "ticks_over_500us": slow.len(), "ticks_over_1ms": c.ticks.iter().filter(|r| r.step_s > TARGET_MAX_S).count(),
                "jacobian_p50_s": num(j50), "jacobian_p99_s": num(j99), "jacobian_max_s": num(jmax),
                "jacobian_count": c.jacobian_s.len(), "jacobian_errors": c.jacobian_errors,
                "unconverged_ticks": s.unconverged_ticks, "column_misses": s.column_misses, "column_deferrals": s.column_deferrals,
                "d_deepest": c.d_deepest, "d_max": c.d_max, "d_final": c.d_final,
                "setup_s": c.setup_s, "prefetch_s": c.prefetch_s, "prefetched_nodes": c.prefetched_nodes, "column_cache_bytes": c.column_cache_bytes,
                "preempted_ticks": c.preempted_ticks(),
                "unpreempted_step_p999_s": num(c.unpreempted_quantiles()[0]), "unpreempted_step_max_s": num(c.unpreempted_quantiles()[1]),
            });
            let counters = json!({
                "captures": s.captures, "releases": s.releases, "punctures": s.punctures,
                "stick_to_slip": s.stick_to_slip, "slip_to_stick": s.slip_to_stick, "shape_passes": s.shape_passes,
                "shape_unconverged": s.shape_unconverged, "dependent_points": s.dependent_points, "bevel_flips": s.bevel_flips,
                "active_set_capped_ticks": s.active_set_capped_ticks, "shape_capped_ticks": s.shape_capped_ticks,
                "hybrid_checks": s.hybrid_checks, "hybrid_rebuilds": s.hybrid_rebuilds,
                "clamped_ticks": s.clamped_ticks, "overflows": s.overflows(),
                "pivots": c.solver.n_pivots, "rotations": c.solver.n_rotations, "rebuilds": c.solver.n_rebuilds,
                "max_active_set_iterations": c.ticks.iter().map(|r| r.active_set_iterations).max().unwrap_or(0),
                "tip_depth_max_m": num(c.tip_depth_max_m), "tip_deepest_m": [num(c.tip_deepest_m[0]), num(c.tip_deepest_m[1])],
                "theta_range_rad": [num(c.theta_range_rad[0]), num(c.theta_range_rad[1])],
                "tip_x_range_m": [num(c.tip_x_range_m[0]), num(c.tip_x_range_m[1])],
                "load_avg_1min": [num(c.load_avg[0]), num(c.load_avg[1])], "wall_s": c.wall_s,
                "worst_ticks": worst, "worst_unpreempted_ticks": worst_unpreempted, "unconverged": unconverged, "prefetched_nodes_by_phase": by_phase, "misses": c.misses(), "notes": c.notes(), "failed": c.failed,
            });
            let overflows = json!({
                "capacity_drops": s.capacity_drops, "capture_overflow": s.capture_overflow,
                "approaching_overflow": s.approaching_overflow, "candidate_growths": s.candidate_growths,
                "curve_capacity_drops": s.curve_capacity_drops,
            });
            for more in [counters, overflows] {
                if let (Some(o), Value::Object(more)) = (o.as_object_mut(), more) {
                    o.extend(more);
                }
            }
            o
        })
        .collect();
    let scripts: Vec<Value> = suite
        .scripts
        .iter()
        .map(|s| json!({"motion": s.motion.name(), "needle": s.needle_label, "ticks": s.poses.len(), "script": s.description}))
        .collect();
    json!({
        "machine": machine(),
        "quick": opts.quick,
        "contact": contact_label(opts.contact, opts.spacing_m),
        "prefetch_nodes_per_tick": opts.prefetch_nodes_per_tick,
        "jacobian_every_ticks": JACOBIAN_EVERY_TICKS,
        "targets": {"step_p999_s": TARGET_P999_S, "step_max_s": TARGET_MAX_S, "unconverged_ticks": 0, "column_misses": 0},
        "scripts": scripts,
        "cases": cases,
    })
}

/// The suite as markdown: the set-up, the main table, and the slowest tick of every case.
pub fn to_markdown(suite: &Suite, opts: &MotionOptions) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "machine: {}\n", machine());
    let _ = writeln!(
        s,
        "phantom: 0.1 m square, E = 30 kPa, ν = 0.45, plane stress 1 cm, bottom fixed; entry at the top centre, tip starting 5 mm above the surface; 1 kHz; contact: {}; `columns_in_step: false`, columns of approaching nodes prefetched between steps ({} nodes per tick, not timed as the step); Jacobian every {JACOBIAN_EVERY_TICKS} ticks, timed apart.\n",
        contact_label(opts.contact, opts.spacing_m),
        opts.prefetch_nodes_per_tick
    );
    for sc in &suite.scripts {
        let _ = writeln!(s, "- **{}** ({}, {} ticks): {}", sc.motion.name(), sc.needle_label, sc.poses.len(), sc.description);
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "| motion | mesh | ticks | step p50 µs | p99 µs | p99.9 µs | max µs | preempted ticks: count, p99.9 / max µs without them | Jacobian p50 / p99 / max µs | unconverged | column misses | deferrals | d deepest (max) | setup s | prefetch s (nodes, GB cached) | targets |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for c in &suite.cases {
        let [p50, p99, p999, max] = c.step_quantiles();
        let [j50, j99, jmax] = c.jacobian_quantiles();
        let misses = c.misses();
        let _ = writeln!(
            s,
            "| {} | {}² | {} | {} | {} | {} | {} | {}: {} / {} | {} / {} / {} | {} | {} | {} | {} ({}) | {:.3} | {:.2} ({}, {:.2}) | {} |",
            c.motion.name(),
            c.n,
            c.ticks.len(),
            us(p50),
            us(p99),
            us(p999),
            us(max),
            c.preempted_ticks(),
            us(c.unpreempted_quantiles()[0]),
            us(c.unpreempted_quantiles()[1]),
            us(j50),
            us(j99),
            us(jmax),
            c.stats.unconverged_ticks,
            c.stats.column_misses,
            c.stats.column_deferrals,
            c.d_deepest,
            c.d_max,
            c.setup_s,
            c.prefetch_s,
            c.prefetched_nodes,
            c.column_cache_bytes as f64 / 1e9,
            targets_cell(&misses, &c.notes())
        );
    }
    let _ = writeln!(
        s,
        "\nPreempted ticks waited on a run queue during the step (`/proc/thread-self/schedstat`): another process had the core. The targets are judged on all ticks.\n"
    );
    let _ = writeln!(
        s,
        "The slowest tick of each case that did not wait on a run queue (its counters; pivots and rotations of the mixed solver within the tick):\n"
    );
    let _ = writeln!(
        s,
        "| motion | mesh | tick (phase) | step µs | active-set iterations | pivots | rotations | stick↔slip | captures / releases | shape passes | d | page faults | columns prefetched before | ticks > 500 µs (preempted) | case totals: pivots / rotations / stick↔slip |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for c in &suite.cases {
        let phase_of = |t: usize| suite.scripts.iter().find(|sc| sc.motion == c.motion).map_or("", |sc| sc.phase_of(t));
        let over = c.ticks.iter().filter(|r| r.step_s > TARGET_P999_S).count();
        let over_preempted = c.ticks.iter().filter(|r| r.step_s > TARGET_P999_S && r.cpu_wait_ns > 0).count();
        let worst = c.ticks.iter().filter(|r| r.cpu_wait_ns == 0).max_by(|a, b| a.step_s.total_cmp(&b.step_s));
        if let Some(w) = worst {
            let _ = writeln!(
                s,
                "| {} | {}² | {} ({}) | {} | {} | {} | {} | {} | {} / {} | {} | {} | {} | {} | {over} ({over_preempted}) | {} / {} / {} |",
                c.motion.name(),
                c.n,
                w.tick,
                phase_of(w.tick),
                us(w.step_s),
                w.active_set_iterations,
                w.pivots,
                w.rotations,
                w.stick_slip_changes,
                w.captures,
                w.releases,
                w.shape_passes,
                w.d,
                w.page_faults,
                w.columns_before,
                c.solver.n_pivots,
                c.solver.n_rotations,
                c.stats.stick_to_slip + c.stats.slip_to_stick
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_core::fixtures::PHANTOM_BASE_Y_M;

    #[test]
    fn straight_scripts_start_above_the_surface_and_come_back() {
        for m in [Motion::Vertical, Motion::Oblique, Motion::Bevel] {
            let sc = script(m, Pace::QUICK).unwrap();
            let tip = |p: &BasePose| sc.needle.tip_m(p);
            let t0 = tip(&sc.initial_pose);
            assert!((t0[1] - (PHANTOM_SIDE_M + START_HEIGHT_M)).abs() < 1e-12, "{m:?}: {t0:?}");
            // The tip's start lies on the line through the entry point.
            let (s, lat) = sc.needle.project(&sc.initial_pose, ENTRY_M);
            assert!(lat.abs() < 1e-12 && s > sc.needle.tip_s_m(), "{m:?}");
            let deep = sc.poses[sc.deepest_tick];
            let travel = (deep.x_m - sc.initial_pose.x_m).hypot(deep.y_m - sc.initial_pose.y_m);
            assert!((travel - TRAVEL_M).abs() < 1e-12, "{m:?}: {travel}");
            assert_eq!(*sc.poses.last().unwrap(), sc.initial_pose, "{m:?}");
            // At most one tick's travel at the pace.
            for w in sc.poses.windows(2) {
                assert!((w[1].x_m - w[0].x_m).hypot(w[1].y_m - w[0].y_m) <= Pace::QUICK.insert_m_s / TICK_RATE_HZ * (1.0 + 1e-9));
            }
        }
        assert!((script(Motion::Oblique, Pace::FULL).unwrap().initial_pose.theta_rad - (DOWN_RAD + OBLIQUE_ANGLE_RAD)).abs() < 1e-15);
    }

    #[test]
    fn turning_pivots_about_the_entry_point() {
        let sc = script(Motion::Turning, Pace::FULL).unwrap();
        let turn = sc.phases.iter().find(|p| p.name == "turn").unwrap().first_tick;
        let end = sc.phases.iter().find(|p| p.name == "withdraw").unwrap().first_tick;
        assert_eq!(end - turn, (TURN_PERIODS as f64 * 2.0 * TICK_RATE_HZ) as usize);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &sc.poses[turn..end] {
            let (s, lat) = sc.needle.project(p, ENTRY_M);
            assert!(lat.abs() < 1e-12 && (s - (RIGID_LENGTH_M - (TRAVEL_M - START_HEIGHT_M))).abs() < 1e-12);
            lo = lo.min(p.theta_rad - DOWN_RAD);
            hi = hi.max(p.theta_rad - DOWN_RAD);
        }
        assert!((hi - TURN_AMPLITUDE_RAD).abs() < 1e-6 && (lo + TURN_AMPLITUDE_RAD).abs() < 1e-6, "{lo} {hi}");
    }

    /// The flexible script at full pace is fig4-steering.csv sampled at 1 kHz, then a withdrawal.
    #[test]
    fn flexible_script_follows_the_fig4_csv() {
        let sc = script(Motion::Flexible, Pace::FULL).unwrap();
        let (_, _, csv) = scene_needle("fig4-steering").unwrap();
        let traj = needlesim_scene::Trajectory::parse_csv(csv).unwrap();
        for k in 0..=sc.deepest_tick {
            let want = needlesim_scene::base_pose(traj.pose_at((k + 1) as f64 / TICK_RATE_HZ));
            let got = sc.poses[k];
            assert!((want.x_m - got.x_m).abs() < 1e-9 && (want.y_m - got.y_m).abs() < 1e-9, "tick {k}: {want:?} {got:?}");
        }
        assert_eq!(sc.deepest_tick + 1, 9050);
        let f = sc.needle.flexible().unwrap();
        assert_eq!(f.bevel_force_ratio, 0.0);
        let last = sc.poses.last().unwrap();
        assert!((last.y_m - PHANTOM_BASE_Y_M).abs() < 1e-12 && (last.x_m - 0.055).abs() < 1e-12);
    }
}
