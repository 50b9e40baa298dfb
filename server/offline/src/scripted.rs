//! What the scripted driver ([`crate::driver`]) needs of a simulation beyond the core's
//! [`Stepper`]: its dimension's trajectory (sampled at the tick rate into base poses) and how
//! many compliance columns a run computes between steps. Implemented here, once per dimension,
//! for the 2D `Simulation` (a [`Trajectory`] of `(x_m, y_m, theta_rad)`) and the 3D
//! `Simulation3` (a [`Trajectory3`] of positions and unit quaternions); [`RunParams`] lets a
//! caller's parameters name the dimension, so `ScriptedRun::new(tissue, params, …)` needs no
//! type annotation in either.

use needlesim_core::Stepper;
use needlesim_core::sim::{SimParams, Simulation};
use needlesim_core::sim3::{BasePose3, Sim3Params, SimError3, Simulation3};
use needlesim_trajectory::{Pose3, Trajectory, Trajectory3, TrajectoryError};

use crate::driver::DEFAULT_PREFETCH_NODES_PER_TICK;

/// A simulation the scripted driver runs: a [`Stepper`] with its dimension's trajectory.
pub trait ScriptedSim: Stepper {
    /// The trajectory a script follows (its samples' own clock, poses interpolated between).
    type Trajectory;

    /// Nodes whose columns a run computes between two steps unless told otherwise.
    ///
    /// 2D: [`DEFAULT_PREFETCH_NODES_PER_TICK`], the budget a session's column worker has.
    /// 3D: every node the step reported as approaching (`usize::MAX`), as the 3D `simulate`,
    /// exercise runs, `plan` and the Python package always computed them: a smaller budget
    /// would defer captures and change the numbers.
    const PREFETCH_NODES_PER_TICK: usize;

    /// The first and the last sample's time, s.
    fn span_s(trajectory: &Self::Trajectory) -> (f64, f64);

    /// The ticks from the first sample to the last (or to `end_s`, when given and earlier) at
    /// `rate_hz`, $\mathrm{round}((t_{end} - t_0) f_{tick})$, if at most `max_ticks`; else the
    /// error naming the last sample (needlesim-trajectory's one tick count).
    fn tick_count(trajectory: &Self::Trajectory, end_s: Option<f64>, rate_hz: f64, max_ticks: u64) -> Result<u64, TrajectoryError>;

    /// The trajectory's pose at `t_s` as a base pose, for tick `tick` (named by the error of a
    /// pose that is not one).
    fn pose_at(trajectory: &Self::Trajectory, t_s: f64, tick: u64) -> Result<Self::Pose, Self::Error>;

    /// The trajectory's first sample as a base pose (where the simulation starts).
    fn first_pose(trajectory: &Self::Trajectory) -> Result<Self::Pose, Self::Error>;
}

/// A simulation's parameters, naming its dimension ([`RunParams::Sim`]): what lets
/// `ScriptedRun::new` infer the simulation from the parameters it is given.
pub trait RunParams: Sized {
    /// The simulation these parameters build.
    type Sim: ScriptedSim;

    /// The parameters, as the simulation's own type (they are: this only names it).
    fn into_params(self) -> <Self::Sim as Stepper>::Params;
}

impl RunParams for SimParams {
    type Sim = Simulation;

    fn into_params(self) -> SimParams {
        self
    }
}

impl RunParams for Sim3Params {
    type Sim = Simulation3;

    fn into_params(self) -> Sim3Params {
        self
    }
}

impl ScriptedSim for Simulation {
    type Trajectory = Trajectory;

    const PREFETCH_NODES_PER_TICK: usize = DEFAULT_PREFETCH_NODES_PER_TICK;

    fn span_s(trajectory: &Trajectory) -> (f64, f64) {
        trajectory.span_s()
    }

    fn tick_count(trajectory: &Trajectory, end_s: Option<f64>, rate_hz: f64, max_ticks: u64) -> Result<u64, TrajectoryError> {
        match end_s {
            None => trajectory.tick_count(rate_hz, max_ticks),
            // The span cut at `end_s`, counted as a two-sample trajectory (named
            // `trajectory[1]` when too long).
            Some(end_s) => {
                let first = trajectory.samples[0];
                Trajectory::from_samples(vec![first, (trajectory.span_s().1.min(end_s), first.1)]).tick_count(rate_hz, max_ticks)
            }
        }
    }

    fn pose_at(trajectory: &Trajectory, t_s: f64, _tick: u64) -> Result<needlesim_core::BasePose, needlesim_core::SimError> {
        Ok(needlesim_scene::base_pose(trajectory.pose_at(t_s)))
    }

    fn first_pose(trajectory: &Trajectory) -> Result<needlesim_core::BasePose, needlesim_core::SimError> {
        Ok(needlesim_scene::base_pose(trajectory.samples[0].1))
    }
}

/// A trajectory's 3D pose as the simulation's base pose; `tick` names it in the error.
fn base_pose3_at(p: &Pose3, tick: u64) -> Result<BasePose3, SimError3> {
    BasePose3::new(p.position_m, p.quat_wxyz).map_err(|source| SimError3::Pose { tick, source })
}

impl ScriptedSim for Simulation3 {
    type Trajectory = Trajectory3;

    const PREFETCH_NODES_PER_TICK: usize = usize::MAX;

    fn span_s(trajectory: &Trajectory3) -> (f64, f64) {
        trajectory.span_s()
    }

    fn tick_count(trajectory: &Trajectory3, end_s: Option<f64>, rate_hz: f64, max_ticks: u64) -> Result<u64, TrajectoryError> {
        match end_s {
            None => trajectory.tick_count(rate_hz, max_ticks),
            // The span cut at `end_s`, counted as a two-sample trajectory (named
            // `trajectory[1]` when too long).
            Some(end_s) => {
                let first = trajectory.samples[0];
                Trajectory3::from_samples(vec![first, (trajectory.span_s().1.min(end_s), first.1)]).tick_count(rate_hz, max_ticks)
            }
        }
    }

    fn pose_at(trajectory: &Trajectory3, t_s: f64, tick: u64) -> Result<BasePose3, SimError3> {
        base_pose3_at(&trajectory.pose_at(t_s), tick)
    }

    fn first_pose(trajectory: &Trajectory3) -> Result<BasePose3, SimError3> {
        base_pose3_at(&trajectory.samples[0].1, 0)
    }
}
