//! A run's machinery: the progress callback, the tick bound, the 3D run through the offline
//! driver, and the one generic step of both dimensions ([`step_after_prefetch`]).

use std::ops::ControlFlow;
use std::sync::Arc;

use needlesim_core::d3::TetTissueModel;
use needlesim_core::sim3::{SimError3, Simulation3};
use needlesim_offline::{ConvergencePolicy, MAX_TICKS_LIMIT, RunError, RunOptions, RunTotals, Script, ScriptedRun, ScriptedSim};
use needlesim_scene::{Scene3d, Trajectory3};
use pyo3::prelude::*;

use crate::errors::TrajectoryError;
use crate::scene::sim3_params;

use super::results::Series;

/// Reports progress every `every` ticks (and checks for Ctrl-C); an exception stops the run.
pub(super) struct Progress<'a> {
    pub(super) callback: Option<&'a Py<PyAny>>,
    pub(super) every: u64,
    pub(super) total: u64,
    pub(super) error: Option<PyErr>,
}

impl Progress<'_> {
    pub(super) fn tick(&mut self, done: u64) -> ControlFlow<()> {
        if self.every == 0 || (!done.is_multiple_of(self.every) && done != self.total) {
            return ControlFlow::Continue(());
        }
        let r = Python::attach(|py| -> PyResult<()> {
            py.check_signals()?;
            if let Some(cb) = self.callback {
                cb.call1(py, (done, self.total))?;
            }
            Ok(())
        });
        match r {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.error = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}

/// A `max_ticks` argument: any Python int, one that no `u64` holds (negative, or 2**64 and up)
/// refused with TrajectoryError naming `max_ticks`, as one over [`MAX_TICKS_LIMIT`] is by
/// [`check_max_ticks`] (PyO3's own extraction raised OverflowError, not a NeedlesimError).
/// Anything but an int is PyO3's TypeError naming the argument.
#[derive(Debug, Clone, Copy)]
pub struct MaxTicks(pub u64);

impl<'a, 'py> FromPyObject<'a, 'py> for MaxTicks {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(v) = obj.extract::<u64>() {
            return Ok(MaxTicks(v));
        }
        if !obj.is_instance_of::<pyo3::types::PyInt>() {
            return obj.extract::<u64>().map(MaxTicks);
        }
        // An int is printed (clipped: str() refuses past 4300 digits) in the message.
        let text = obj.str().map(|s| s.to_string()).unwrap_or_else(|_| "an int of more than 4300 digits".to_owned());
        let text = needlesim_scene::limit::quote(&text);
        if obj.lt(0)? {
            return Err(TrajectoryError::new_err(format!(
                "max_ticks = {text} must be ≥ 0 (at most {MAX_TICKS_LIMIT}, needlesim.MAX_TICKS_LIMIT)"
            )));
        }
        Err(TrajectoryError::new_err(format!(
            "max_ticks = {text} is over the limit of {MAX_TICKS_LIMIT} ticks (needlesim.MAX_TICKS_LIMIT): a run's results are held in memory"
        )))
    }
}

/// Refuses a `max_ticks` argument over [`MAX_TICKS_LIMIT`] (a run's results are held in memory),
/// naming the argument and the limit.
pub(super) fn check_max_ticks(max_ticks: u64) -> PyResult<()> {
    if max_ticks > MAX_TICKS_LIMIT {
        return Err(TrajectoryError::new_err(format!(
            "max_ticks = {max_ticks} is over the limit of {MAX_TICKS_LIMIT} ticks (needlesim.MAX_TICKS_LIMIT): a run's results are held in memory"
        )));
    }
    Ok(())
}

/// The 3D scripted run, with the run driver as the 3D `simulate` runs it: tick `k = 0..=K`
/// steps the trajectory's pose at `t0 + k / rate` (`K = round((t1 - t0) rate)`, at most
/// `max_ticks`), starting at the first sample's pose, every approaching node's columns computed
/// between steps. Minimal: the rows go to `series`, no CSV; `progress` may stop it after a
/// tick. Returns the simulation and the run's totals (`stopped_early` from the progress).
pub(super) fn run3(
    scene: &Scene3d,
    tissue: &Arc<TetTissueModel>,
    traj: &Trajectory3,
    (max_ticks, convergence): (u64, ConvergencePolicy),
    series: &mut Series,
    progress: &mut Progress<'_>,
) -> Result<(Simulation3, RunTotals), RunError<SimError3>> {
    let initial = <Simulation3 as ScriptedSim>::first_pose(traj).map_err(|e| RunError::FirstPose(Box::new(e)))?;
    let opts = RunOptions { max_ticks, convergence, ..RunOptions::default() };
    let mut run = ScriptedRun::new(tissue.clone(), sim3_params(scene, initial), Script::trajectory(traj), opts)?;
    let totals = run.run(|tick, sim| {
        series.push3(sim.output(), tick.t_s, tick.step_s);
        progress.tick(tick.k + 1)
    })?;
    let (sim, finished) = run.finish()?;
    Ok((sim, RunTotals { stopped_early: totals.stopped_early, ..finished }))
}

/// One step of a simulation the Python `step` drives, in either dimension: the columns due
/// from the previous step first (`S::PREFETCH_NODES_PER_TICK` of them, as the run driver
/// computes between its steps), then the step. `prefetch_due` is set after a step and cleared
/// by the prefetch.
pub(super) fn step_after_prefetch<'s, S: ScriptedSim>(
    sim: &'s mut S,
    prefetch_due: &mut bool,
    pose: S::Pose,
) -> Result<&'s S::Output, S::Error> {
    if std::mem::take(prefetch_due) {
        sim.prefetch(S::PREFETCH_NODES_PER_TICK)?;
    }
    let out = sim.step(pose)?;
    *prefetch_due = true;
    Ok(out)
}
