//! The one scripted-run driver, for both dimensions: a script of base poses (a trajectory
//! sampled at the tick rate, or a list of poses) through the simulation's step ([`ScriptedSim`]:
//! the 2D `Simulation` or the 3D `Simulation3`), with the compliance of the nodes the tip
//! approaches computed between steps, as a session's worker would (`Stepper::prefetch`: their
//! columns, or on a large 3D mesh their node blocks by the simulation's own worker). One tick limit, one
//! tick rounding ($K = \mathrm{round}((t_{end} - t_0) f_{tick})$, tick $k$ at
//! $t_0 + k / f_{tick}$), one error policy; each caller takes what it needs from each tick.
//!
//! # Error policy
//! Any failed step stops the run with [`RunError::Step`], naming the tick and the script time:
//! a diverged solve, a failed solve or compliance column, and also a pose that is not finite
//! (`SimError::NonFinitePose`; in 3D also a trajectory pose that is not a unit quaternion,
//! `SimError3::Pose`). The last is the strictest of the policies the five hand-written
//! loops had (`simulate` skipped such a tick with a warning; the Simulate RPC, `plan`,
//! the identify experiments and `bench` stopped): a skipped tick would shift every later row of
//! a time series off the tick grid. A trajectory read from CSV never yields one (needlesim-trajectory
//! bounds poses to ±1e3 and sample gaps to ≥ 1 ns); samples that come from the API are checked
//! for finiteness only, so two near ±1.8e308 can interpolate to infinity, which stops the run
//! here with that error. A tick that did not converge stops the run too
//! ([`RunError::Unconverged`]), unless [`RunOptions::convergence`] keeps it.

use std::fmt;
use std::ops::ControlFlow;
use std::sync::Arc;
use std::time::Instant;

use needlesim_core::StepError;
use needlesim_core::sim::{SimError, Simulation};
use needlesim_trajectory::TrajectoryError;

use crate::convergence::{ConvergencePolicy, UnconvergedTick};
pub use crate::scripted::{RunParams, ScriptedSim};

/// The longest offline simulation, in ticks, by default: the server's Simulate limit and the
/// `simulate` command's `--max-ticks` (10⁶ ticks: 1000 s at 1 kHz, 8 MB of step times).
pub const DEFAULT_MAX_TICKS: u64 = 1_000_000;

/// The most ticks a caller may ask an in-memory run for (`max_ticks` of the Python package,
/// whose results hold about 150 bytes a tick, more with targets: 1.5 GB here): 10⁷ ticks, 10,000 s
/// at 1 kHz. A larger `max_ticks` is refused, not clamped.
pub const MAX_TICKS_LIMIT: u64 = 10 * DEFAULT_MAX_TICKS;

/// The most rows a run's per-tick storage reserves before it runs; it grows beyond as ticks run,
/// so memory follows the ticks simulated, not a length asked for.
pub const PREALLOCATED_TICKS: u64 = 1 << 16;

/// The capacity to reserve for a run of `ticks` ticks: at most [`PREALLOCATED_TICKS`].
pub fn preallocated_ticks(ticks: u64) -> usize {
    ticks.min(PREALLOCATED_TICKS) as usize
}

/// Compliance columns computed between two steps of a 2D run, by default (the budget a worker
/// would have); a 3D run computes every approaching node's ([`ScriptedSim::PREFETCH_NODES_PER_TICK`]).
pub const DEFAULT_PREFETCH_NODES_PER_TICK: usize = 8;

/// Why a scripted run did not start or stopped; `E` is the simulation's error (2D by default:
/// `SimError`; 3D: `SimError3`).
#[derive(Debug, thiserror::Error)]
pub enum RunError<E: StepError = SimError> {
    /// The script is longer than the tick limit (the error names its last sample).
    #[error(transparent)]
    TooLong(#[from] TrajectoryError),
    /// The end time given is not after the script's start.
    #[error("the run's end t = {end_s} s must come after the trajectory's start ({start_s} s)")]
    BadEnd { end_s: f64, start_s: f64 },
    /// The trajectory's first pose is not a base pose (3D: not a unit quaternion); nothing ran.
    #[error("the trajectory's first pose")]
    FirstPose(#[source] Box<E>),
    /// The simulation could not be built from the scene's parameters.
    #[error("simulation")]
    Setup(#[source] Box<E>),
    /// A step failed (see the module documentation): the run stops there. A diverged step names
    /// its tick itself.
    #[error("{}", step_context(*tick, *t_s, &**source))]
    Step { tick: u64, t_s: f64, source: Box<E> },
    /// Computing the compliance (columns or node blocks) of approaching nodes after a step
    /// failed.
    #[error("the run stopped at tick {tick} (t = {t_s:.4} s): compliance prefetch")]
    Prefetch { tick: u64, t_s: f64, source: Box<E> },
    /// A tick did not converge and the run's [`ConvergencePolicy`] is `Fail`.
    #[error(transparent)]
    Unconverged(#[from] UnconvergedTick),
}

fn step_context<E: StepError>(tick: u64, t_s: f64, source: &E) -> String {
    if source.names_its_tick() {
        format!("the run stopped at t = {t_s:.4} s")
    } else {
        format!("the run stopped at tick {tick} (t = {t_s:.4} s)")
    }
}

impl<E: StepError> RunError<E> {
    /// The simulation error behind a failed step or column, if that is what stopped the run.
    pub fn sim_error(&self) -> Option<&E> {
        match self {
            RunError::Setup(e) | RunError::FirstPose(e) | RunError::Step { source: e, .. } | RunError::Prefetch { source: e, .. } => {
                Some(&**e)
            }
            RunError::TooLong(_) | RunError::BadEnd { .. } | RunError::Unconverged(_) => None,
        }
    }
}

/// The poses a run follows, one per tick, in `S`'s dimension (2D by default).
pub enum Script<'a, S: ScriptedSim = Simulation> {
    /// A trajectory sampled at the scene's tick rate from its first sample's time to its last
    /// (or to `end_s`, when earlier); the simulation starts at the first sample's pose.
    Trajectory { trajectory: &'a S::Trajectory, end_s: Option<f64> },
    /// One pose per tick, from time 0; the simulation starts at the scene's initial pose.
    Poses(&'a [S::Pose]),
}

// By hand: a derive would ask `S` itself (the simulation) to be `Clone`, `Copy` and `Debug`.
impl<S: ScriptedSim> Clone for Script<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: ScriptedSim> Copy for Script<'_, S> {}

impl<S: ScriptedSim> fmt::Debug for Script<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Script::Trajectory { trajectory, end_s } => {
                f.debug_struct("Trajectory").field("span_s", &S::span_s(trajectory)).field("end_s", end_s).finish()
            }
            Script::Poses(poses) => f.debug_tuple("Poses").field(&poses.len()).finish(),
        }
    }
}

impl<'a, S: ScriptedSim> Script<'a, S> {
    /// The whole of a trajectory.
    pub fn trajectory(trajectory: &'a S::Trajectory) -> Self {
        Script::Trajectory { trajectory, end_s: None }
    }
}

/// How a run goes.
#[derive(Debug, Clone, Copy)]
pub struct RunOptions {
    /// The most ticks (after the first) a run may take; longer scripts are refused before
    /// anything is simulated ([`RunError::TooLong`]).
    pub max_ticks: u64,
    /// Nodes whose compliance columns are computed after each step (`Some(0)`: none; the caller
    /// then provides them, e.g. from a dense inverse, through [`ScriptedRun::sim_mut`]); `None`:
    /// the dimension's own ([`ScriptedSim::PREFETCH_NODES_PER_TICK`]: 2D
    /// [`DEFAULT_PREFETCH_NODES_PER_TICK`], 3D every approaching node).
    pub prefetch_nodes_per_tick: Option<usize>,
    /// What a tick that did not converge does: stops the run ([`RunError::Unconverged`], the
    /// default) or is kept ([`crate::convergence`]).
    pub convergence: ConvergencePolicy,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self { max_ticks: DEFAULT_MAX_TICKS, prefetch_nodes_per_tick: None, convergence: ConvergencePolicy::Fail }
    }
}

/// One tick of a run, as [`ScriptedRun::next_tick`] reports it (the step's output is
/// [`ScriptedRun::output`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tick {
    /// The tick's index in the run, from 0.
    pub k: u64,
    /// The script's time at this tick, s (a trajectory's own clock).
    pub t_s: f64,
    /// The time the step took, s.
    pub step_s: f64,
}

/// What a finished run did besides its ticks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunTotals {
    /// Ticks stepped.
    pub ticks: u64,
    /// Column pairs (3D: node column triples, or nodes' blocks with the node-block store)
    /// computed between steps.
    pub prefetched_columns: u64,
    /// Whether the per-tick callback stopped the run early.
    pub stopped_early: bool,
}

/// A scripted run in progress: a simulation (2D by default) and where it is in its script.
pub struct ScriptedRun<'a, S: ScriptedSim = Simulation> {
    sim: S,
    script: Script<'a, S>,
    /// The script's time at tick 0, s.
    t0_s: f64,
    rate_hz: f64,
    /// Ticks the run steps: 0..ticks_total.
    ticks_total: u64,
    next_k: u64,
    /// The previous tick's prefetch is still due (done at the start of the next tick, so a caller
    /// that stops pays none).
    prefetch_due: bool,
    prefetch_nodes_per_tick: usize,
    prefetched_columns: u64,
    convergence: ConvergencePolicy,
}

impl<'a, S: ScriptedSim> ScriptedRun<'a, S> {
    /// A run of `script` on a new simulation of `tissue` with `params` (its initial pose is
    /// the trajectory's first pose for a trajectory script). The length is checked here, before
    /// anything is simulated. The dimension is the parameters' ([`RunParams`]).
    pub fn new<P: RunParams<Sim = S>>(
        tissue: Arc<S::Model>,
        params: P,
        script: Script<'a, S>,
        opts: RunOptions,
    ) -> Result<Self, RunError<S::Error>> {
        let mut params = params.into_params();
        let rate_hz = S::tick_rate_hz(&params);
        let (t0_s, ticks_total) = match script {
            Script::Trajectory { trajectory, end_s } => {
                let t0_s = S::span_s(trajectory).0;
                if let Some(end_s) = end_s
                    && !(end_s.is_finite() && end_s > t0_s)
                {
                    return Err(RunError::BadEnd { end_s, start_s: t0_s });
                }
                let ticks = S::tick_count(trajectory, end_s, rate_hz, opts.max_ticks)?.saturating_add(1);
                let first = S::first_pose(trajectory).map_err(|e| RunError::FirstPose(Box::new(e)))?;
                S::set_initial_pose(&mut params, first);
                (t0_s, ticks)
            }
            Script::Poses(poses) => {
                let n = poses.len() as u64;
                if n > opts.max_ticks.saturating_add(1) {
                    return Err(RunError::TooLong(TrajectoryError::TooLong {
                        at: format!("pose[{}]", n - 1),
                        end_s: (n - 1) as f64 / rate_hz,
                        span_s: (n - 1) as f64 / rate_hz,
                        ticks: (n - 1) as f64,
                        rate_hz,
                        max_ticks: opts.max_ticks,
                    }));
                }
                (0.0, n)
            }
        };
        let sim = S::new(tissue, params).map_err(|e| RunError::Setup(Box::new(e)))?;
        Ok(Self {
            sim,
            script,
            t0_s,
            rate_hz,
            ticks_total,
            next_k: 0,
            prefetch_due: false,
            prefetch_nodes_per_tick: opts.prefetch_nodes_per_tick.unwrap_or(S::PREFETCH_NODES_PER_TICK),
            prefetched_columns: 0,
            convergence: opts.convergence,
        })
    }

    /// Ticks the whole run steps.
    pub fn ticks_total(&self) -> u64 {
        self.ticks_total
    }

    /// The index of the last tick (a run steps ticks `0..=last_tick()`; 0 for an empty run).
    pub fn last_tick(&self) -> u64 {
        self.ticks_total.saturating_sub(1)
    }

    /// The index of the tick [`next_tick`](Self::next_tick) steps next.
    pub fn next_k(&self) -> u64 {
        self.next_k
    }

    /// The script's time at tick 0, s.
    pub fn t0_s(&self) -> f64 {
        self.t0_s
    }

    /// The script's time at tick `k`, s: $t_0 + k / f_{tick}$.
    pub fn t_at_tick(&self, k: u64) -> f64 {
        self.t0_s + k as f64 / self.rate_hz
    }

    /// The script's pose at tick `k` (an error only for a 3D trajectory pose that is not a base
    /// pose: `SimError3::Pose`, naming tick `k`).
    pub fn pose_at_tick(&self, k: u64) -> Result<S::Pose, S::Error> {
        match self.script {
            Script::Trajectory { trajectory, .. } => S::pose_at(trajectory, self.t_at_tick(k), k),
            Script::Poses(poses) => Ok(poses[k as usize]),
        }
    }

    /// Computes the columns due from the previous tick, then steps the next tick; `None` when
    /// the script is done. The step's output is [`output`](Self::output).
    pub fn next_tick(&mut self) -> Result<Option<Tick>, RunError<S::Error>> {
        self.prefetch_now()?;
        if self.next_k >= self.ticks_total {
            return Ok(None);
        }
        let k = self.next_k;
        let t_s = self.t_at_tick(k);
        let step_error = |source| RunError::Step { tick: k, t_s, source: Box::new(source) };
        let pose = self.pose_at_tick(k).map_err(step_error)?;
        let started = Instant::now();
        let stepped = self.sim.step(pose).map(|_| ());
        let step_s = started.elapsed().as_secs_f64();
        stepped.map_err(step_error)?;
        self.convergence.check(k, t_s, self.sim.unconverged())?;
        self.next_k = k + 1;
        self.prefetch_due = true;
        Ok(Some(Tick { k, t_s, step_s }))
    }

    /// Runs to the end of the script, calling `on_tick` after each step (before the columns
    /// for the next are computed); `ControlFlow::Break` ends the run there, without error.
    pub fn run(&mut self, mut on_tick: impl FnMut(&Tick, &S) -> ControlFlow<()>) -> Result<RunTotals, RunError<S::Error>> {
        let mut stopped_early = false;
        while let Some(tick) = self.next_tick()? {
            if on_tick(&tick, &self.sim).is_break() {
                stopped_early = true;
                self.prefetch_due = false;
                break;
            }
        }
        Ok(self.totals(stopped_early))
    }

    fn prefetch_now(&mut self) -> Result<(), RunError<S::Error>> {
        if !std::mem::take(&mut self.prefetch_due) || self.prefetch_nodes_per_tick == 0 {
            return Ok(());
        }
        let k = self.next_k - 1;
        let t_s = self.t_at_tick(k);
        let n = self.sim.prefetch(self.prefetch_nodes_per_tick).map_err(|source| RunError::Prefetch {
            tick: k,
            t_s,
            source: Box::new(source),
        })?;
        self.prefetched_columns += n as u64;
        Ok(())
    }

    fn totals(&self, stopped_early: bool) -> RunTotals {
        RunTotals { ticks: self.next_k, prefetched_columns: self.prefetched_columns, stopped_early }
    }

    /// The output of the last step.
    pub fn output(&self) -> &S::Output {
        self.sim.output()
    }

    /// The simulation (its state after the last step).
    pub fn sim(&self) -> &S {
        &self.sim
    }

    /// The simulation, for a caller that supplies compliance columns itself
    /// (`RunOptions::prefetch_nodes_per_tick = Some(0)`).
    pub fn sim_mut(&mut self) -> &mut S {
        &mut self.sim
    }

    /// Column pairs computed between steps so far.
    pub fn prefetched_columns(&self) -> u64 {
        self.prefetched_columns
    }

    /// Ends the run: the simulation in its final state. Columns still due for the last tick
    /// are computed first, as a run to the end always has.
    pub fn finish(mut self) -> Result<(S, RunTotals), RunError<S::Error>> {
        self.prefetch_now()?;
        let totals = self.totals(false);
        Ok((self.sim, totals))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_core::BasePose;
    use needlesim_scene::Trajectory;

    fn scene() -> needlesim_scene::Scene {
        needlesim_scene::load_scene("paper-phantom", &needlesim_core::MeshLimits::default()).unwrap()
    }

    #[test]
    fn a_run_steps_every_tick_of_the_trajectory_and_can_stop_early() {
        let scene = scene();
        let traj = Trajectory::parse_csv(scene.example_trajectory.unwrap()).unwrap();
        let opts = RunOptions::default();
        let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(&traj), opts).unwrap();
        let total = run.ticks_total();
        assert_eq!(total, traj.tick_count(scene.params.tick_rate_hz, u64::MAX).unwrap() + 1);
        let mut seen = 0;
        let totals = run
            .run(|tick, _| {
                assert_eq!(tick.k, seen);
                seen += 1;
                if seen == 10 { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
            })
            .unwrap();
        assert_eq!((totals.ticks, totals.stopped_early), (10, true));
        // The length is checked before anything is simulated.
        let short = RunOptions { max_ticks: 5, ..opts };
        let e = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(&traj), short).err().unwrap();
        assert!(matches!(e, RunError::TooLong(_)), "{e}");
    }

    #[test]
    fn a_pose_that_is_not_finite_stops_the_run_naming_the_tick() {
        let scene = scene();
        let p = scene.params.initial_pose;
        let poses = [p, p, BasePose::new(f64::NAN, p.y_m, p.theta_rad), p];
        let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::Poses(&poses), RunOptions::default()).unwrap();
        let e = run.run(|_, _| ControlFlow::Continue(())).unwrap_err();
        assert!(matches!(e, RunError::Step { tick: 2, ref source, .. } if matches!(**source, SimError::NonFinitePose { .. })), "{e:?}");
        assert!(e.to_string().starts_with("the run stopped at tick 2 (t = 0.0020 s)"), "{e}");
    }
}
