//! What Python hands a simulation: poses checked and converted, the simulations built from a
//! scene, trajectories read from a file or an array, and `needlesim.tick_poses`.

use std::path::PathBuf;
use std::sync::Arc;

use needlesim_core::BasePose;
use needlesim_core::d3::TetTissueModel;
use needlesim_core::sim::Simulation;
use needlesim_core::sim3::{BasePose3, SimError3, Simulation3};
use needlesim_offline::{RunOptions, Script, ScriptedRun, simulate};
use needlesim_scene::{MAX_ABS_POSE, Scene, Scene3d, Trajectory, Trajectory3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::errors::{NeedlesimError, PoseError, TrajectoryError, chain, run_error, sim_error, sim3_error, trajectory_error};
use crate::scene::{PyScene, SceneKind, sim3_params};

use super::results::array2;
use super::run::{MaxTicks, check_max_ticks};

pub(super) fn pose2(v: &[f64]) -> PyResult<BasePose> {
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
pub(super) fn pose3(v: &[f64], tick: u64) -> PyResult<BasePose3> {
    let [x, y, z, qw, qx, qy, qz] = v else {
        return Err(PoseError::new_err(format!("a 3D pose is (x_m, y_m, z_m, qw, qx, qy, qz): 7 numbers, not {}", v.len())));
    };
    check_range(&[("x_m", *x), ("y_m", *y), ("z_m", *z)])?;
    BasePose3::new([*x, *y, *z], [*qw, *qx, *qy, *qz]).map_err(|source| sim3_error(&SimError3::Pose { tick, source }))
}

pub(super) fn new_sim2(scene: &Scene, initial: Option<BasePose>) -> PyResult<Simulation> {
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

pub(super) fn new_sim3(scene: &Scene3d, tissue: &Arc<TetTissueModel>, initial: BasePose3) -> PyResult<Simulation3> {
    Simulation3::new(tissue.clone(), sim3_params(scene, initial)).map_err(|e| sim3_error(&e))
}

/// The scene's or the caller's trajectory, parsed.
pub(super) enum Traj {
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

pub(super) fn read_trajectory(py: Python<'_>, scene: &SceneKind, obj: Option<&Bound<'_, PyAny>>) -> PyResult<Traj> {
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
