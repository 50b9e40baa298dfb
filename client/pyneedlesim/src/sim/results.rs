//! What a step and a run give Python: [`StepResult`] (one tick) and [`RunResult`] (a whole
//! run's series), as NumPy arrays, with the contact-state codes.

use needlesim_core::sim::{NodeState, StepOutput};
use needlesim_core::sim3::{BasePose3, PointState3, StepOutput3, TargetState3};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;

pub(super) fn code2(s: NodeState) -> i8 {
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

pub(super) fn array2<'py, T: numpy::Element + Clone>(py: Python<'py>, rows: usize, cols: usize, v: &[T]) -> Bound<'py, PyArray2<T>> {
    Array2::from_shape_vec((rows, cols), v.to_vec()).expect("rows × cols values").into_pyarray(py)
}

pub(super) fn array3<'py, T: numpy::Element + Clone>(py: Python<'py>, shape: (usize, usize, usize), v: &[T]) -> Bound<'py, PyArray3<T>> {
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
    pub(super) fn from2(out: &StepOutput) -> Self {
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

    pub(super) fn from3(out: &StepOutput3) -> Self {
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
    pub(super) dim: usize,
    /// Ticks stepped.
    #[pyo3(get)]
    pub(super) ticks: u64,
    /// Ticks whose commanded pose was clamped.
    #[pyo3(get)]
    pub(super) clamped_ticks: u64,
    /// Ticks whose active set did not settle within the iteration bound.
    #[pyo3(get)]
    pub(super) unconverged_ticks: u64,
    /// Columns a step had to compute itself (2D; 0 in 3D, whose step never computes one).
    #[pyo3(get)]
    pub(super) column_misses: u64,
    /// Ticks at which a new contact waited a tick for its columns.
    #[pyo3(get)]
    pub(super) column_deferrals: u64,
    /// Nodes whose compliance columns were computed between steps.
    #[pyo3(get)]
    pub(super) prefetched_columns: u64,
    /// Whether the progress callback ended the run early (by raising).
    #[pyo3(get)]
    pub(super) stopped_early: bool,
    pub(super) series: Series,
}

/// The columns of a run, flat, row-major.
#[derive(Default)]
pub(super) struct Series {
    pub(super) n_targets: usize,
    pub(super) t_s: Vec<f64>,
    pub(super) pose: Vec<f64>,
    pub(super) force_n: Vec<f64>,
    pub(super) torque_nm: Vec<f64>,
    pub(super) force_axial_n: Vec<f64>,
    pub(super) force_lateral_n: Vec<f64>,
    pub(super) tip_m: Vec<f64>,
    pub(super) inserted_length_m: Vec<f64>,
    pub(super) counts: Vec<i64>,
    pub(super) target_distances_m: Vec<f64>,
    pub(super) target_positions_m: Vec<f64>,
    pub(super) target_hits: Vec<bool>,
    pub(super) step_times_s: Vec<f64>,
    pub(super) converged: Vec<bool>,
}

impl Series {
    pub(super) fn with_capacity(dim: usize, n_targets: usize, ticks: usize) -> Self {
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

    pub(super) fn push2(&mut self, out: &StepOutput, t_s: f64, step_s: f64) {
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

    pub(super) fn push3(&mut self, out: &StepOutput3, t_s: f64, step_s: f64) {
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
