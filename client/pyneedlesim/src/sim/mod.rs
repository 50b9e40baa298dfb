//! `needlesim.Simulation`: one needle in one scene's tissue, stepped pose by pose from Python
//! ([`PySimulation::step`]) or run through a whole trajectory with the GIL released
//! ([`PySimulation::run`]), 2D or 3D by the scene.
//!
//! One class for both dimensions: the scene decides (as `load_scene` does), so code written
//! against scene files need not branch, and the results have the same fields with vectors of
//! length `dim` (a pose has 3 numbers in 2D, 7 in 3D). A step computes the compliance columns
//! due from the previous step first, exactly as the run driver does between steps
//! (`needlesim_offline::ScriptedRun`, `ScriptedSim::PREFETCH_NODES_PER_TICK`: up to
//! `DEFAULT_PREFETCH_NODES_PER_TICK` nodes in 2D, every approaching node in 3D), through one
//! generic step of both dimensions ([`step_after_prefetch`]): a Python loop of `step` over a
//! trajectory's tick poses gives the `simulate` command's numbers; `run` is that driver's run.

use std::sync::Arc;

use needlesim_core::sim::Simulation;
use needlesim_core::sim3::{BasePose3, SimError3, Simulation3};
use needlesim_offline::{ConvergencePolicy, preallocated_ticks, simulate};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{NeedlesimError, SimulationError, run_error, sim_error, sim3_error, trajectory_error};
use crate::scene::{PyScene, SceneKind};

use self::inputs::{Traj, new_sim2, new_sim3, pose2, pose3, read_trajectory};
use self::results::{Series, array2, array3, code2};
use self::run::{MaxTicks, Progress, check_max_ticks, run3, step_after_prefetch};

mod inputs;
mod results;
mod run;

pub use inputs::tick_poses;
pub use results::{RunResult, StepResult};

/// The contact state codes of the `contact_states` arrays: index = code.
pub const CONTACT_STATES: [&str; 3] = ["stuck", "slipping", "tip"];

enum SimKind {
    D2 { sim: Box<Simulation>, prefetch_due: bool },
    D3 { sim: Box<Simulation3>, prefetch_due: bool },
}

/// One needle in a scene's tissue, 2D or 3D as the scene is. The base starts at
/// ``initial_pose`` (``scene.initial_pose`` when None): (x_m, y_m, theta_rad) in 2D,
/// (x_m, y_m, z_m, qw, qx, qy, qz) in 3D (a unit quaternion, scalar first; the needle points
/// along the base frame's +x).
///
/// Drive it tick by tick with :meth:`step` (from a notebook, a controller, a planner), or run
/// a whole trajectory with :meth:`run` (the GIL released, progress reported). Between steps
/// the compliance columns of the nodes the tip approaches are computed as
/// ``needlesim-server simulate`` does, so both give that command's numbers.
///
/// Raises PoseError for an initial pose that is not finite (or not unit in 3D), and
/// SimulationError when the scene's parameters are refused.
#[pyclass(module = "needlesim", name = "Simulation")]
pub struct PySimulation {
    scene: Arc<SceneKind>,
    kind: SimKind,
}

#[pymethods]
impl PySimulation {
    #[new]
    #[pyo3(signature = (scene, initial_pose=None))]
    fn new(py: Python<'_>, scene: PyRef<'_, PyScene>, initial_pose: Option<Vec<f64>>) -> PyResult<Self> {
        let scene = scene.inner.clone();
        let kind = match &*scene {
            SceneKind::D2(s) => {
                let initial = initial_pose.as_deref().map(pose2).transpose()?;
                let sim = py.detach(|| new_sim2(s, initial))?;
                SimKind::D2 { sim: Box::new(sim), prefetch_due: false }
            }
            SceneKind::D3 { scene: s, tissue } => {
                let initial = match initial_pose.as_deref() {
                    Some(v) => pose3(v, 0)?,
                    None => BasePose3::new(s.initial_pose.position_m, s.initial_pose.quat_wxyz)
                        .map_err(|source| sim3_error(&SimError3::Pose { tick: 0, source }))?,
                };
                let sim = py.detach(|| new_sim3(s, tissue, initial))?;
                SimKind::D3 { sim: Box::new(sim), prefetch_due: false }
            }
        };
        Ok(Self { scene, kind })
    }

    /// 2 or 3, as the scene.
    #[getter]
    fn dim(&self) -> usize {
        self.scene.dim()
    }

    /// The scene this simulation runs in.
    #[getter]
    fn scene(&self) -> PyScene {
        PyScene { inner: self.scene.clone() }
    }

    /// Advances one tick towards the commanded base pose and returns what the tick did
    /// (a :class:`StepResult`). ``pose`` is 3 numbers (x_m, y_m, theta_rad) in 2D, 7 numbers
    /// (x_m, y_m, z_m, qw, qx, qy, qz) in 3D; a jump larger than the scene's per-tick limit
    /// is clamped (``StepResult.clamped``). The compliance columns due from the previous step
    /// are computed first, as between the ticks of ``needlesim-server simulate``.
    ///
    /// Raises PoseError for a wrong number of components, a NaN or infinite component, or a
    /// quaternion whose norm is not 1 (the state is unchanged); SimulationError when the step
    /// fails (a diverged solve leaves the simulation faulted: every later step raises too).
    fn step(&mut self, pose: Vec<f64>) -> PyResult<StepResult> {
        match &mut self.kind {
            SimKind::D2 { sim, prefetch_due } => {
                let pose = pose2(&pose)?;
                step_after_prefetch(&mut **sim, prefetch_due, pose).map(StepResult::from2).map_err(|e| sim_error(&e))
            }
            SimKind::D3 { sim, prefetch_due } => {
                let pose = pose3(&pose, sim.tick())?;
                step_after_prefetch(&mut **sim, prefetch_due, pose).map(StepResult::from3).map_err(|e| sim3_error(&e))
            }
        }
    }

    /// The last step's result (the initial state before any step).
    #[getter]
    fn last(&self) -> StepResult {
        match &self.kind {
            SimKind::D2 { sim, .. } => StepResult::from2(sim.output()),
            SimKind::D3 { sim, .. } => StepResult::from3(sim.output()),
        }
    }

    /// Runs a scripted insertion as ``needlesim-server simulate`` does and returns its time
    /// series (a :class:`RunResult`, one row per tick, the same numbers as that command's CSV).
    /// The run starts afresh at the trajectory's first pose and ticks at the scene's rate from
    /// its first sample's time to its last; afterwards this simulation holds the run's final
    /// state (so :meth:`step`, :meth:`snapshot` and :meth:`dump_state` continue from there).
    ///
    /// ``trajectory``: None for the scene's own; a CSV file path (str or os.PathLike) with the
    /// header ``t_s,x_m,y_m,theta_rad`` (2D) or ``t_s,x_m,y_m,z_m,qw,qx,qy,qz`` (3D); or an
    /// array-like of shape (n, 4) or (n, 8) with those columns. It is checked as a file is.
    ///
    /// The GIL is released while it runs. Every ``progress_every`` ticks (and at the end)
    /// ``progress(ticks_done, ticks_total)`` is called, if given, and Ctrl-C is checked; an
    /// exception raised there (or KeyboardInterrupt) stops the run and propagates, the
    /// simulation then holding the state of the last tick run.
    ///
    /// A tick whose step did not converge (the stick/slip iteration or a flexible needle's
    /// shape passes at their cap) stops the run with SimulationError naming it, as
    /// ``simulate`` does, unless ``keep_unconverged`` is true (then ``RunResult.converged`` is
    /// false at such ticks).
    ///
    /// Raises TrajectoryError (unreadable or invalid trajectory, longer than ``max_ticks``, or
    /// ``max_ticks`` over ``needlesim.MAX_TICKS_LIMIT``),
    /// PoseError (a pose that is not finite), SimulationError (a failed or unconverged step);
    /// after those the simulation is unchanged.
    #[pyo3(signature = (trajectory=None, *, progress=None, progress_every=1000, max_ticks=MaxTicks(simulate::DEFAULT_MAX_TICKS), keep_unconverged=false))]
    fn run(
        &mut self,
        py: Python<'_>,
        trajectory: Option<&Bound<'_, PyAny>>,
        progress: Option<Py<PyAny>>,
        progress_every: u64,
        max_ticks: MaxTicks,
        keep_unconverged: bool,
    ) -> PyResult<RunResult> {
        let max_ticks = max_ticks.0;
        check_max_ticks(max_ticks)?;
        let convergence = ConvergencePolicy::keeping(keep_unconverged);
        let traj = read_trajectory(py, &self.scene, trajectory)?;
        let scene = self.scene.clone();
        match (&*scene, traj) {
            (SceneKind::D2(s), Traj::D2(traj)) => {
                let rate = s.params.tick_rate_hz;
                let total = traj.tick_count(rate, max_ticks).map_err(|e| trajectory_error(&e))? + 1;
                let t0 = traj.span_s().0;
                let mut series = Series::with_capacity(2, s.target_names.len(), preallocated_ticks(total));
                let mut prog = Progress { callback: progress.as_ref(), every: progress_every, total, error: None };
                let r = py.detach(|| {
                    simulate::run_observed(s, &traj, max_ticks, convergence, None, |tick, out| {
                        series.push2(out, t0 + out.time_s, tick.step_s);
                        prog.tick(tick.k + 1)
                    })
                });
                let (sim, summary) = r.map_err(|e| run_error(&e))?;
                self.kind = SimKind::D2 { sim: Box::new(sim), prefetch_due: summary.stopped_early };
                if let Some(e) = prog.error {
                    return Err(e);
                }
                Ok(RunResult {
                    dim: 2,
                    ticks: summary.ticks,
                    clamped_ticks: summary.clamped_ticks,
                    unconverged_ticks: summary.unconverged_ticks,
                    column_misses: summary.column_misses,
                    column_deferrals: summary.column_deferrals,
                    prefetched_columns: summary.prefetched_columns,
                    stopped_early: summary.stopped_early,
                    series,
                })
            }
            (SceneKind::D3 { scene: s, tissue }, Traj::D3(traj)) => {
                let total = traj.tick_count(s.tick_rate_hz, max_ticks).map_err(|e| trajectory_error(&e))? + 1;
                let mut series = Series::with_capacity(3, s.targets.len(), preallocated_ticks(total));
                let mut prog = Progress { callback: progress.as_ref(), every: progress_every, total, error: None };
                let r = py.detach(|| run3(s, tissue, &traj, (max_ticks, convergence), &mut series, &mut prog));
                let (sim, totals) = r.map_err(|e| run_error(&e))?;
                let st = sim.stats();
                let ticks = sim.tick();
                self.kind = SimKind::D3 { sim: Box::new(sim), prefetch_due: totals.stopped_early };
                if let Some(e) = prog.error {
                    return Err(e);
                }
                Ok(RunResult {
                    dim: 3,
                    ticks,
                    clamped_ticks: st.clamped_ticks,
                    unconverged_ticks: series.converged.iter().filter(|c| !**c).count() as u64,
                    column_misses: 0,
                    column_deferrals: st.column_deferrals,
                    prefetched_columns: totals.prefetched_columns,
                    stopped_early: totals.stopped_early,
                    series,
                })
            }
            _ => Err(NeedlesimError::new_err("internal: the trajectory's dimension differs from the scene's")),
        }
    }

    /// The static problem the last step solved, as a dict of NumPy arrays.
    ///
    /// 2D: ``node_idx`` (int64), ``is_point`` (bool: a material point, else a mesh node),
    /// ``reference_m`` (n, 2), ``angle_rad``, ``ut_m``, ``un_m`` (NaN where the component is
    /// free), ``load_n`` (n, 2) per condition; and per needle contact ``needle_node_idx``,
    /// ``needle_states`` (codes of CONTACT_STATES), ``needle_positions_m``, ``needle_forces_n``.
    ///
    /// 3D: per working point ``x_m`` (n, 3), ``frame`` (n, 3, 3: rows t, n, b), ``ut_m``,
    /// ``un_m``, ``ub_m`` (NaN where free), ``f_n`` (n, 3; NaN rows where every component is
    /// prescribed), ``force_n`` and ``u_m`` (n, 3); and ``tick``.
    fn snapshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let opt = |v: Option<f64>| v.unwrap_or(f64::NAN);
        match &self.kind {
            SimKind::D2 { sim, .. } => {
                let s = sim.snapshot();
                let c = &s.conditions;
                let n = c.len();
                d.set_item("node_idx", c.iter().map(|c| c.node_idx as i64).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("is_point", c.iter().map(|c| c.contact.as_node().is_none()).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("reference_m", array2(py, n, 2, &c.iter().flat_map(|c| c.reference_m).collect::<Vec<_>>()))?;
                d.set_item("angle_rad", c.iter().map(|c| c.angle_rad).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("ut_m", c.iter().map(|c| opt(c.ut_m)).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("un_m", c.iter().map(|c| opt(c.un_m)).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("load_n", array2(py, n, 2, &c.iter().flat_map(|c| c.load_n).collect::<Vec<_>>()))?;
                let nn = &s.needle_nodes;
                let m = nn.len();
                d.set_item("needle_node_idx", nn.iter().map(|x| x.node_idx as i64).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("needle_states", nn.iter().map(|x| code2(x.state)).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("needle_positions_m", array2(py, m, 2, &nn.iter().flat_map(|x| x.position_m).collect::<Vec<_>>()))?;
                d.set_item("needle_forces_n", array2(py, m, 2, &nn.iter().flat_map(|x| x.force_n).collect::<Vec<_>>()))?;
            }
            SimKind::D3 { sim, .. } => {
                let s = sim.snapshot();
                let p = &s.points;
                let n = p.len();
                d.set_item("tick", s.tick)?;
                d.set_item("x_m", array2(py, n, 3, &p.iter().flat_map(|p| p.x_m).collect::<Vec<_>>()))?;
                d.set_item("frame", array3(py, (n, 3, 3), &p.iter().flat_map(|p| p.frame.into_iter().flatten()).collect::<Vec<_>>()))?;
                d.set_item("ut_m", p.iter().map(|p| opt(p.ut)).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("un_m", p.iter().map(|p| opt(p.un)).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("ub_m", p.iter().map(|p| opt(p.ub)).collect::<Vec<_>>().into_pyarray(py))?;
                d.set_item("f_n", array2(py, n, 3, &p.iter().flat_map(|p| p.f_n.unwrap_or([f64::NAN; 3])).collect::<Vec<_>>()))?;
                d.set_item("force_n", array2(py, n, 3, &p.iter().flat_map(|p| p.force_n).collect::<Vec<_>>()))?;
                d.set_item("u_m", array2(py, n, 3, &p.iter().flat_map(|p| p.u_m).collect::<Vec<_>>()))?;
            }
        }
        Ok(d)
    }

    /// The current state as a static problem in the exchange format (a dict, as
    /// ``needlesim-server simulate --dump-state`` writes it): the mesh, materials, support, the
    /// needle's conditions and loads, with the solver's own displacements
    /// (``solver_displacements``) and needle nodes. :func:`needlesim.solve` re-solves it.
    ///
    /// In 3D the 3D exchange format (``"dim": 3``: tetrahedra, material points with frames and
    /// conditions, and the simulation's own answer under ``simulation_result``), as
    /// ``needlesim-server simulate --dump-state`` writes it for a 3D scene.
    fn dump_state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = match (&self.kind, &*self.scene) {
            (SimKind::D2 { sim, .. }, SceneKind::D2(scene)) => serde_json::to_string(&simulate::dump_state(scene, sim)),
            (SimKind::D3 { sim, .. }, SceneKind::D3 { scene, .. }) => {
                let state = needlesim_offline::simulate3::dump_state(scene, sim).map_err(|e| SimulationError::new_err(format!("{e:#}")))?;
                serde_json::to_string(&state)
            }
            _ => unreachable!("a simulation is built from its scene's dimension"),
        }
        .map_err(|e| NeedlesimError::new_err(e.to_string()))?;
        py.import("json")?.call_method1("loads", (text,))
    }

    fn __repr__(&self) -> String {
        let (tick, name) = match (&self.kind, &*self.scene) {
            (SimKind::D2 { sim, .. }, SceneKind::D2(s)) => (sim.output().tick, s.name.as_str()),
            (SimKind::D3 { sim, .. }, SceneKind::D3 { scene, .. }) => (sim.tick(), scene.name.as_str()),
            _ => (0, "?"),
        };
        format!("Simulation(scene={name:?}, dim={}, tick={tick})", self.scene.dim())
    }
}
