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

use clap::ValueEnum;
use needlesim_core::fixtures::PHANTOM_SIDE_M;
use needlesim_core::sim::ContactModel;
use needlesim_offline::driver::DEFAULT_PREFETCH_NODES_PER_TICK;

mod measure;
mod report;
mod script;

pub use measure::{CaseResult, Suite, ThreadCounters, ThreadSample, TickRecord, run_case, run_suite, step_quantiles};
pub use report::{ticks_csv, to_json, to_markdown};
pub use script::{MotionScript, Phase, script, sim_params};

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

#[cfg(test)]
mod tests {
    use super::script::{DOWN_RAD, scene_needle};
    use super::*;
    use needlesim_core::BasePose;
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
