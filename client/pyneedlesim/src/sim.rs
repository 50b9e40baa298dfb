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

use std::ops::ControlFlow;
use std::path::PathBuf;
use std::sync::Arc;

use needlesim_core::BasePose;
use needlesim_core::d3::TetTissueModel;
use needlesim_core::sim::{NodeState, Simulation, StepOutput};
use needlesim_core::sim3::{BasePose3, PointState3, SimError3, Simulation3, StepOutput3, TargetState3};
use needlesim_offline::{
    ConvergencePolicy, MAX_TICKS_LIMIT, RunError, RunOptions, RunTotals, Script, ScriptedRun, ScriptedSim, preallocated_ticks, simulate,
};
use needlesim_scene::{MAX_ABS_POSE, Scene, Scene3d, Trajectory, Trajectory3};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{
    NeedlesimError, PoseError, SimulationError, TrajectoryError, chain, run_error, sim_error, sim3_error, trajectory_error,
};
use crate::scene::{PyScene, SceneKind, sim3_params};

/// The contact state codes of the `contact_states` arrays: index = code.
pub const CONTACT_STATES: [&str; 3] = ["stuck", "slipping", "tip"];

fn code2(s: NodeState) -> i8 {
    match s {
        NodeState::Stuck => 0,
        NodeState::Slipping => 1,
        NodeState::Tip => 2,
    }
}

fn code3(s: PointState3) -> i8 {
    match s {
        PointState3::Stuck => 0,
        PointState3::Slipping => 1,
        PointState3::Tip => 2,
    }
}

fn pose3_values(p: &BasePose3) -> [f64; 7] {
    let q = p.orientation.into_inner();
    [p.position_m[0], p.position_m[1], p.position_m[2], q.w, q.i, q.j, q.k]
}

fn array2<'py, T: numpy::Element + Clone>(py: Python<'py>, rows: usize, cols: usize, v: &[T]) -> Bound<'py, PyArray2<T>> {
    Array2::from_shape_vec((rows, cols), v.to_vec()).expect("rows × cols values").into_pyarray(py)
}

fn array3<'py, T: numpy::Element + Clone>(py: Python<'py>, shape: (usize, usize, usize), v: &[T]) -> Bound<'py, PyArray3<T>> {
    Array3::from_shape_vec(shape, v.to_vec()).expect("a × b × c values").into_pyarray(py)
}

/// What one step did: the wrench on the needle base, the tip, the contacts and the targets
/// after the tick. Vectors have ``dim`` components (world frame); arrays are new copies at each
/// access.
#[pyclass(module = "needlesim", frozen)]
pub struct StepResult {
    /// 2 or 3.
    #[pyo3(get)]
    dim: usize,
    /// The tick's index, from 0 (the first step's).
    #[pyo3(get)]
    tick: u64,
    /// The simulation's time, s (tick / tick rate).
    #[pyo3(get)]
    time_s: f64,
    /// Whether the commanded pose jumped further than the scene allows per tick and was clamped.
    #[pyo3(get)]
    clamped: bool,
    /// Whether the step converged: the active set settled within its iteration bound and a
    /// flexible needle's shape passes within theirs.
    #[pyo3(get)]
    converged: bool,
    /// The axial force the tissue resists the needle with, N (positive pushing in).
    #[pyo3(get)]
    force_axial_n: f64,
    /// The lateral force on the needle, N (2D; None in 3D).
    #[pyo3(get)]
    force_lateral_n: Option<f64>,
    /// Length of shaft in the tissue, m.
    #[pyo3(get)]
    inserted_length_m: f64,
    /// Contacts stuck, slipping and carried by the tip.
    #[pyo3(get)]
    n_stuck: usize,
    #[pyo3(get)]
    n_slipping: usize,
    #[pyo3(get)]
    n_tip: usize,
    pose: Vec<f64>,
    force_n: Vec<f64>,
    torque_nm: Vec<f64>,
    tip_m: Vec<f64>,
    contact_states: Vec<i8>,
    contact_reference_m: Vec<f64>,
    contact_positions_m: Vec<f64>,
    contact_forces_n: Vec<f64>,
    target_distances_m: Vec<f64>,
    target_positions_m: Vec<f64>,
    target_hits: Vec<bool>,
}

impl StepResult {
    fn from2(out: &StepOutput) -> Self {
        let b = out.base;
        let nn = &out.needle_nodes;
        Self {
            dim: 2,
            tick: out.tick,
            time_s: out.time_s,
            clamped: out.clamped,
            converged: out.unconverged().is_none(),
            force_axial_n: out.force_axial_n,
            force_lateral_n: Some(out.force_lateral_n),
            inserted_length_m: out.inserted_length_m,
            n_stuck: out.n_stuck,
            n_slipping: out.n_slipping,
            n_tip: out.n_tip,
            pose: vec![b.x_m, b.y_m, b.theta_rad],
            force_n: out.force_n.to_vec(),
            torque_nm: vec![out.torque_nm],
            tip_m: out.tip_m.to_vec(),
            contact_states: nn.iter().map(|n| code2(n.state)).collect(),
            contact_reference_m: nn.iter().flat_map(|n| n.reference_m).collect(),
            contact_positions_m: nn.iter().flat_map(|n| n.position_m).collect(),
            contact_forces_n: nn.iter().flat_map(|n| n.force_n).collect(),
            target_distances_m: out.targets.iter().map(|t| t.distance_m).collect(),
            target_positions_m: out.targets.iter().flat_map(|t| t.position_m).collect(),
            target_hits: out.targets.iter().map(|t| t.hit).collect(),
        }
    }

    fn from3(out: &StepOutput3) -> Self {
        let c = &out.contacts;
        let count = |s: PointState3| c.iter().filter(|p| p.state == s).count();
        Self {
            dim: 3,
            tick: out.tick,
            time_s: out.time_s,
            clamped: out.clamped,
            converged: out.unconverged().is_none(),
            force_axial_n: out.axial_force_n,
            force_lateral_n: None,
            inserted_length_m: out.inserted_length_m,
            n_stuck: count(PointState3::Stuck),
            n_slipping: count(PointState3::Slipping),
            n_tip: count(PointState3::Tip),
            pose: pose3_values(&out.pose).to_vec(),
            force_n: out.base_force_n.to_vec(),
            torque_nm: out.base_torque_nm.to_vec(),
            tip_m: out.tip_m.to_vec(),
            contact_states: c.iter().map(|p| code3(p.state)).collect(),
            contact_reference_m: c.iter().flat_map(|p| p.x_ref_m).collect(),
            contact_positions_m: c.iter().flat_map(|p| p.x_m).collect(),
            contact_forces_n: c.iter().flat_map(|p| p.force_n).collect(),
            target_distances_m: out.targets.as_slice().iter().map(|t| t.distance_m).collect(),
            target_positions_m: out.targets.as_slice().iter().flat_map(|t| t.centre_m).collect(),
            target_hits: out.targets.as_slice().iter().map(|t| t.state == TargetState3::Hit).collect(),
        }
    }

    fn n_contacts(&self) -> usize {
        self.contact_states.len()
    }
}

#[pymethods]
impl StepResult {
    /// The base pose applied (after clamping): (x_m, y_m, theta_rad) in 2D,
    /// (x_m, y_m, z_m, qw, qx, qy, qz) in 3D.
    #[getter]
    fn pose<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.pose.clone().into_pyarray(py)
    }
    /// The force of the tissue on the needle base, N, world: shape (dim,).
    #[getter]
    fn force_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.force_n.clone().into_pyarray(py)
    }
    /// The torque of the tissue on the needle about the base, N·m: shape (1,) in 2D (about z),
    /// (3,) in 3D (world).
    #[getter]
    fn torque_nm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.torque_nm.clone().into_pyarray(py)
    }
    /// The tip's position, m: shape (dim,).
    #[getter]
    fn tip_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.tip_m.clone().into_pyarray(py)
    }
    /// Each contact's state as a code into ``needlesim.CONTACT_STATES`` (0 stuck, 1 slipping,
    /// 2 carried by the tip): int8 array of shape (n_contacts,).
    #[getter]
    fn contact_states<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i8>> {
        self.contact_states.clone().into_pyarray(py)
    }
    /// Each contact's reference (undeformed) position, m: shape (n_contacts, dim).
    #[getter]
    fn contact_reference_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.n_contacts(), self.dim, &self.contact_reference_m)
    }
    /// Each contact's current (deformed) position, m: shape (n_contacts, dim).
    #[getter]
    fn contact_positions_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.n_contacts(), self.dim, &self.contact_positions_m)
    }
    /// The force of the needle on the tissue at each contact, N, world: shape (n_contacts, dim).
    #[getter]
    fn contact_forces_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.n_contacts(), self.dim, &self.contact_forces_n)
    }
    /// Each target's distance from the tip to its displaced centre, m.
    #[getter]
    fn target_distances_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.target_distances_m.clone().into_pyarray(py)
    }
    /// Each target's displaced centre, m: shape (n_targets, dim).
    #[getter]
    fn target_positions_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.target_hits.len(), self.dim, &self.target_positions_m)
    }
    /// Whether each target has been hit (the tip within its radius at some tick; latched).
    #[getter]
    fn target_hits<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        self.target_hits.clone().into_pyarray(py)
    }
    fn __repr__(&self) -> String {
        format!(
            "StepResult(dim={}, tick={}, force_n={:?}, tip_m={:?}, inserted_length_m={}, contacts={})",
            self.dim,
            self.tick,
            self.force_n,
            self.tip_m,
            self.inserted_length_m,
            self.n_contacts()
        )
    }
}

/// A run's time series, one row per tick, and its counters. Arrays are new copies at each access.
#[pyclass(module = "needlesim", frozen)]
pub struct RunResult {
    /// 2 or 3.
    #[pyo3(get)]
    dim: usize,
    /// Ticks stepped.
    #[pyo3(get)]
    ticks: u64,
    /// Ticks whose commanded pose was clamped.
    #[pyo3(get)]
    clamped_ticks: u64,
    /// Ticks whose active set did not settle within the iteration bound.
    #[pyo3(get)]
    unconverged_ticks: u64,
    /// Columns a step had to compute itself (2D; 0 in 3D, whose step never computes one).
    #[pyo3(get)]
    column_misses: u64,
    /// Ticks at which a new contact waited a tick for its columns.
    #[pyo3(get)]
    column_deferrals: u64,
    /// Nodes whose compliance columns were computed between steps.
    #[pyo3(get)]
    prefetched_columns: u64,
    /// Whether the progress callback ended the run early (by raising).
    #[pyo3(get)]
    stopped_early: bool,
    series: Series,
}

/// The columns of a run, flat, row-major.
#[derive(Default)]
struct Series {
    n_targets: usize,
    t_s: Vec<f64>,
    pose: Vec<f64>,
    force_n: Vec<f64>,
    torque_nm: Vec<f64>,
    force_axial_n: Vec<f64>,
    force_lateral_n: Vec<f64>,
    tip_m: Vec<f64>,
    inserted_length_m: Vec<f64>,
    counts: Vec<i64>,
    target_distances_m: Vec<f64>,
    target_positions_m: Vec<f64>,
    target_hits: Vec<bool>,
    step_times_s: Vec<f64>,
    converged: Vec<bool>,
}

impl Series {
    fn with_capacity(dim: usize, n_targets: usize, ticks: usize) -> Self {
        let r = dim * (dim - 1) / 2;
        let pw = if dim == 2 { 3 } else { 7 };
        Self {
            n_targets,
            t_s: Vec::with_capacity(ticks),
            pose: Vec::with_capacity(ticks * pw),
            force_n: Vec::with_capacity(ticks * dim),
            torque_nm: Vec::with_capacity(ticks * r),
            force_axial_n: Vec::with_capacity(ticks),
            force_lateral_n: Vec::with_capacity(if dim == 2 { ticks } else { 0 }),
            tip_m: Vec::with_capacity(ticks * dim),
            inserted_length_m: Vec::with_capacity(ticks),
            counts: Vec::with_capacity(ticks * 3),
            target_distances_m: Vec::with_capacity(ticks * n_targets),
            target_positions_m: Vec::with_capacity(ticks * n_targets * dim),
            target_hits: Vec::with_capacity(ticks * n_targets),
            step_times_s: Vec::with_capacity(ticks),
            converged: Vec::with_capacity(ticks),
        }
    }

    fn push2(&mut self, out: &StepOutput, t_s: f64, step_s: f64) {
        let b = out.base;
        self.converged.push(out.unconverged().is_none());
        self.t_s.push(t_s);
        self.pose.extend([b.x_m, b.y_m, b.theta_rad]);
        self.force_n.extend(out.force_n);
        self.torque_nm.push(out.torque_nm);
        self.force_axial_n.push(out.force_axial_n);
        self.force_lateral_n.push(out.force_lateral_n);
        self.tip_m.extend(out.tip_m);
        self.inserted_length_m.push(out.inserted_length_m);
        self.counts.extend([out.n_stuck as i64, out.n_slipping as i64, out.n_tip as i64]);
        for t in &out.targets {
            self.target_distances_m.push(t.distance_m);
            self.target_positions_m.extend(t.position_m);
            self.target_hits.push(t.hit);
        }
        self.step_times_s.push(step_s);
    }

    fn push3(&mut self, out: &StepOutput3, t_s: f64, step_s: f64) {
        let count = |s: PointState3| out.contacts.iter().filter(|p| p.state == s).count() as i64;
        self.converged.push(out.unconverged().is_none());
        self.t_s.push(t_s);
        self.pose.extend(pose3_values(&out.pose));
        self.force_n.extend(out.base_force_n);
        self.torque_nm.extend(out.base_torque_nm);
        self.force_axial_n.push(out.axial_force_n);
        self.tip_m.extend(out.tip_m);
        self.inserted_length_m.push(out.inserted_length_m);
        self.counts.extend([count(PointState3::Stuck), count(PointState3::Slipping), count(PointState3::Tip)]);
        for t in out.targets.as_slice() {
            self.target_distances_m.push(t.distance_m);
            self.target_positions_m.extend(t.centre_m);
            self.target_hits.push(t.state == TargetState3::Hit);
        }
        self.step_times_s.push(step_s);
    }

    fn rows(&self) -> usize {
        self.t_s.len()
    }
}

#[pymethods]
impl RunResult {
    /// Each tick's time on the trajectory's clock, s: shape (ticks,).
    #[getter]
    fn t_s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series.t_s.clone().into_pyarray(py)
    }
    /// The base pose applied at each tick: shape (ticks, 3) (x_m, y_m, theta_rad) in 2D,
    /// (ticks, 7) (x_m, y_m, z_m, qw, qx, qy, qz) in 3D.
    #[getter]
    fn pose<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let w = if self.dim == 2 { 3 } else { 7 };
        array2(py, self.series.rows(), w, &self.series.pose)
    }
    /// The force of the tissue on the base, N: shape (ticks, dim).
    #[getter]
    fn force_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.series.rows(), self.dim, &self.series.force_n)
    }
    /// The torque about the base, N·m: shape (ticks, 1) in 2D, (ticks, 3) in 3D.
    #[getter]
    fn torque_nm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.series.rows(), self.dim * (self.dim - 1) / 2, &self.series.torque_nm)
    }
    /// The axial force, N: shape (ticks,).
    #[getter]
    fn force_axial_n<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series.force_axial_n.clone().into_pyarray(py)
    }
    /// The lateral force, N: shape (ticks,) in 2D; None in 3D.
    #[getter]
    fn force_lateral_n<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        (self.dim == 2).then(|| self.series.force_lateral_n.clone().into_pyarray(py))
    }
    /// The tip's position, m: shape (ticks, dim).
    #[getter]
    fn tip_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.series.rows(), self.dim, &self.series.tip_m)
    }
    /// The inserted length, m: shape (ticks,).
    #[getter]
    fn inserted_length_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series.inserted_length_m.clone().into_pyarray(py)
    }
    /// Whether each tick converged: bool array (ticks,); all true unless the run was asked to
    /// keep unconverged ticks (``keep_unconverged=True``).
    #[getter]
    fn converged<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        self.series.converged.clone().into_pyarray(py)
    }
    /// Contacts stuck, slipping and carried by the tip at each tick: int64 array (ticks, 3).
    #[getter]
    fn contact_counts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        array2(py, self.series.rows(), 3, &self.series.counts)
    }
    /// Each target's distance from the tip to its displaced centre, m: shape (ticks, n_targets).
    #[getter]
    fn target_distances_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        array2(py, self.series.rows(), self.series.n_targets, &self.series.target_distances_m)
    }
    /// Each target's displaced centre, m: shape (ticks, n_targets, dim).
    #[getter]
    fn target_positions_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        array3(py, (self.series.rows(), self.series.n_targets, self.dim), &self.series.target_positions_m)
    }
    /// Whether each target has been hit by that tick (latched): bool array (ticks, n_targets).
    #[getter]
    fn target_hits<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<bool>> {
        array2(py, self.series.rows(), self.series.n_targets, &self.series.target_hits)
    }
    /// The time each step took, s: shape (ticks,).
    #[getter]
    fn step_times_s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.series.step_times_s.clone().into_pyarray(py)
    }
    fn __repr__(&self) -> String {
        let stopped = if self.stopped_early { "True" } else { "False" };
        format!("RunResult(dim={}, ticks={}, stopped_early={stopped})", self.dim, self.ticks)
    }
}

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

fn pose2(v: &[f64]) -> PyResult<BasePose> {
    match v {
        [x, y, th] => {
            check_range(&[("x_m", *x), ("y_m", *y), ("theta_rad", *th)])?;
            Ok(BasePose::new(*x, *y, *th))
        }
        _ => Err(PoseError::new_err(format!("a 2D pose is (x_m, y_m, theta_rad): 3 numbers, not {}", v.len()))),
    }
}

/// A stepped pose's positions and angles within ±[`MAX_ABS_POSE`], the bound a trajectory's are
/// held to (`run` refused what `step` took): PoseError naming the component, the state unchanged.
/// A NaN or infinite component is the step's to refuse (the simulation's non-finite pose error).
fn check_range(values: &[(&str, f64)]) -> PyResult<()> {
    for &(name, v) in values {
        if v.is_finite() && v.abs() > MAX_ABS_POSE {
            return Err(PoseError::new_err(format!(
                "{name} = {} is out of range (at most {MAX_ABS_POSE:e} in magnitude, as in a trajectory); the pose was rejected and the state kept",
                needlesim_core::num::num(v)
            )));
        }
    }
    Ok(())
}

/// A 3D pose from 7 numbers; a refused one is reported as the step would (naming `tick`).
fn pose3(v: &[f64], tick: u64) -> PyResult<BasePose3> {
    let [x, y, z, qw, qx, qy, qz] = v else {
        return Err(PoseError::new_err(format!("a 3D pose is (x_m, y_m, z_m, qw, qx, qy, qz): 7 numbers, not {}", v.len())));
    };
    check_range(&[("x_m", *x), ("y_m", *y), ("z_m", *z)])?;
    BasePose3::new([*x, *y, *z], [*qw, *qx, *qy, *qz]).map_err(|source| sim3_error(&SimError3::Pose { tick, source }))
}

fn new_sim2(scene: &Scene, initial: Option<BasePose>) -> PyResult<Simulation> {
    let mut params = scene.params.clone();
    if let Some(p) = initial {
        if ![p.x_m, p.y_m, p.theta_rad].iter().all(|v| v.is_finite()) {
            let num = needlesim_core::num::num;
            return Err(PoseError::new_err(format!(
                "the initial pose ({}, {}, {}) is not finite",
                num(p.x_m),
                num(p.y_m),
                num(p.theta_rad)
            )));
        }
        params.initial_pose = p;
    }
    Simulation::new(scene.tissue.clone(), params).map_err(|e| sim_error(&e))
}

fn new_sim3(scene: &Scene3d, tissue: &Arc<TetTissueModel>, initial: BasePose3) -> PyResult<Simulation3> {
    Simulation3::new(tissue.clone(), sim3_params(scene, initial)).map_err(|e| sim3_error(&e))
}

/// The scene's or the caller's trajectory, parsed.
enum Traj {
    D2(Trajectory),
    D3(Trajectory3),
}

/// A trajectory as CSV text from a (rows, columns) array, for the trajectory crate's parser
/// (which checks it as it checks a file): `{}` writes each f64 so that it reads back exactly.
fn csv_from_array(header: &str, arr: &PyReadonlyArray2<'_, f64>) -> String {
    let a = arr.as_array();
    let mut s = String::with_capacity(header.len() + 1 + a.len() * 24);
    s.push_str(header);
    s.push('\n');
    for row in a.rows() {
        let cells: Vec<String> = row.iter().map(|v| format!("{v}")).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    s
}

fn read_trajectory(py: Python<'_>, scene: &SceneKind, obj: Option<&Bound<'_, PyAny>>) -> PyResult<Traj> {
    let dim = scene.dim();
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return match scene {
            SceneKind::D2(s) => match s.example_trajectory {
                Some(text) => Trajectory::parse_csv(text).map(Traj::D2).map_err(|e| trajectory_error(&e)),
                None => Err(TrajectoryError::new_err(format!(
                    "scene '{}' has no trajectory of its own (not a shipped example): pass one",
                    s.name
                ))),
            },
            SceneKind::D3 { scene, .. } => match &scene.trajectory {
                Some(t) => Ok(Traj::D3(t.clone())),
                None => Err(TrajectoryError::new_err(format!("scene '{}' names no trajectory: pass one", scene.name))),
            },
        };
    };
    let (text, label) = if obj.is_instance_of::<pyo3::types::PyString>() || obj.hasattr("__fspath__")? {
        let path: PathBuf = obj.extract()?;
        let text = needlesim_scene::read_local_file(&path, needlesim_scene::MAX_LOCAL_FILE_BYTES)
            .map_err(|e| TrajectoryError::new_err(format!("{e:#}")))?;
        (text, path.display().to_string())
    } else {
        let np = py.import("numpy")?;
        // C-contiguous and aligned (numpy copies only when it must): an array unpickled from
        // out-of-band buffers (Dask, pickle protocol 5) can be unaligned, and reading one as a
        // slice would panic (issue 21's hung Dask sweep: the panic could not travel back).
        let arr = np.call_method1("require", (obj, "float64", ("C", "A")))?;
        let cols = if dim == 2 { 4 } else { 8 };
        let header = if dim == 2 { "t_s,x_m,y_m,theta_rad" } else { "t_s,x_m,y_m,z_m,qw,qx,qy,qz" };
        let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
        if shape.len() != 2 || shape[1] != cols {
            return Err(TrajectoryError::new_err(format!(
                "a {dim}D trajectory array has shape (n, {cols}) with columns {header}; this one has shape {shape:?}"
            )));
        }
        let arr: PyReadonlyArray2<'_, f64> = arr.extract()?;
        (csv_from_array(header, &arr), "the trajectory array (its row k is line k + 2)".to_owned())
    };
    let with_label = |m: String| TrajectoryError::new_err(format!("{label}: {m}"));
    match dim {
        2 => Trajectory::parse_csv(&text).map(Traj::D2).map_err(|e| with_label(chain(&e))),
        _ => Trajectory3::parse_csv(&text).map(Traj::D3).map_err(|e| with_label(chain(&e))),
    }
}

/// Reports progress every `every` ticks (and checks for Ctrl-C); an exception stops the run.
struct Progress<'a> {
    callback: Option<&'a Py<PyAny>>,
    every: u64,
    total: u64,
    error: Option<PyErr>,
}

impl Progress<'_> {
    fn tick(&mut self, done: u64) -> ControlFlow<()> {
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
fn check_max_ticks(max_ticks: u64) -> PyResult<()> {
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
fn run3(
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
fn step_after_prefetch<'s, S: ScriptedSim>(sim: &'s mut S, prefetch_due: &mut bool, pose: S::Pose) -> Result<&'s S::Output, S::Error> {
    if std::mem::take(prefetch_due) {
        sim.prefetch(S::PREFETCH_NODES_PER_TICK)?;
    }
    let out = sim.step(pose)?;
    *prefetch_due = true;
    Ok(out)
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

/// `tick_poses`' result: the tick times and the poses.
type TickPoses<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>);

/// The base pose of each tick of a scripted run, as :meth:`Simulation.run` and
/// ``needlesim-server simulate`` command them: the trajectory sampled at the scene's tick rate
/// from its first sample's time to its last. Returns ``(t_s, poses)``: shape (ticks,) and
/// (ticks, 3) in 2D (x_m, y_m, theta_rad), (ticks, 7) in 3D (x_m, y_m, z_m, qw, qx, qy, qz).
/// Stepping ``Simulation(scene, initial_pose=poses[0])`` through them reproduces the run.
///
/// ``trajectory`` and ``max_ticks`` are as for :meth:`Simulation.run`. Raises TrajectoryError.
#[pyfunction]
#[pyo3(signature = (scene, trajectory=None, *, max_ticks=MaxTicks(simulate::DEFAULT_MAX_TICKS)))]
pub fn tick_poses<'py>(
    py: Python<'py>,
    scene: PyRef<'_, PyScene>,
    trajectory: Option<&Bound<'py, PyAny>>,
    max_ticks: MaxTicks,
) -> PyResult<TickPoses<'py>> {
    let max_ticks = max_ticks.0;
    check_max_ticks(max_ticks)?;
    let kind = scene.inner.clone();
    let traj = read_trajectory(py, &kind, trajectory)?;
    match (&*kind, traj) {
        (SceneKind::D2(s), Traj::D2(traj)) => {
            let opts = RunOptions { max_ticks, ..RunOptions::default() };
            // The driver's own sampling (ScriptedRun::pose_at_tick), not a copy of it.
            let run = ScriptedRun::new(s.tissue.clone(), s.params.clone(), Script::trajectory(&traj), opts).map_err(|e| run_error(&e))?;
            let n = run.ticks_total();
            let t: Vec<f64> = (0..n).map(|k| run.t_at_tick(k)).collect();
            let mut p = Vec::with_capacity(3 * n as usize);
            for k in 0..n {
                // A 2D trajectory pose is always a base pose (a pose that is not finite is the
                // step's to refuse).
                let b = run.pose_at_tick(k).map_err(|e| sim_error(&e))?;
                p.extend([b.x_m, b.y_m, b.theta_rad]);
            }
            Ok((t.into_pyarray(py), array2(py, n as usize, 3, &p)))
        }
        (SceneKind::D3 { scene: s, .. }, Traj::D3(traj)) => {
            let rate = s.tick_rate_hz;
            let t0 = traj.span_s().0;
            let n = traj.tick_count(rate, max_ticks).map_err(|e| trajectory_error(&e))? as usize + 1;
            let t: Vec<f64> = (0..n).map(|k| t0 + k as f64 / rate).collect();
            let p: Vec<f64> = t
                .iter()
                .flat_map(|&t| {
                    let q = traj.pose_at(t);
                    [q.position_m[0], q.position_m[1], q.position_m[2], q.quat_wxyz[0], q.quat_wxyz[1], q.quat_wxyz[2], q.quat_wxyz[3]]
                })
                .collect();
            Ok((t.into_pyarray(py), array2(py, n, 7, &p)))
        }
        _ => Err(NeedlesimError::new_err("internal: the trajectory's dimension differs from the scene's")),
    }
}
