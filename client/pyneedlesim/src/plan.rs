//! `needlesim.plan`: the offline planner (`needlesim_offline::plan`, the `needlesim-server plan`
//! command) from Python, for a 2D scene: the entry point, angle and depth whose tip reaches a
//! target although the insertion moves it. The GIL is released while it plans.

use std::ops::ControlFlow;

use needlesim_offline::plan::{PlanInputError, PlanOptions, PlanRequest, plan as plan_insertion};
use pyo3::prelude::*;

use crate::errors::{NeedlesimError, PlanError};
use crate::scene::{PyScene, SceneKind};

/// Plans an insertion into a 2D scene that reaches ``target`` although the insertion itself
/// drags the target off the needle's axis, as ``needlesim-server plan`` does, and returns the
/// plan as a dict (the command's JSON): ``plan`` and ``straight`` (aiming straight at the
/// undeformed centre) with ``entry_m``, ``angle_rad``, ``depth_m``, ``predicted_error_m``,
/// ``lateral_miss_m``, ``tip_m``, ``target_m``, ``aim_m``; ``trajectory`` (rows ``t_s, x_m,
/// y_m, theta_rad``, a trajectory :meth:`Simulation.run` accepts), ``target_radius_m``,
/// ``target_center_m``, ``speed_m_s``, ``converged``, ``iterations``, ``simulations``,
/// ``wall_s``, ``threads``.
///
/// ``entry_m`` (the allowed entry segment ``[[x1, y1], [x2, y2]]``), ``angles_deg`` (the allowed
/// base angles ``[min, max]``) and ``speed_mm_s`` default to the scene's planning example
/// (fig3-target has one). ``threads``: worker threads, 0 for one per core (the plan does not
/// depend on it). ``tolerance_fraction`` and ``max_iterations``: the stopping rule (see the
/// planner's documentation). The GIL is released while it plans.
///
/// Raises PlanError naming the request's field that is wrong (``target``, ``entry``,
/// ``angles_deg``, ``speed_mm_s``), or when a simulated candidate fails; NeedlesimError for a
/// 3D scene.
#[pyfunction]
#[pyo3(signature = (scene, target, *, entry_m=None, angles_deg=None, speed_mm_s=None, threads=0, tolerance_fraction=0.2, max_iterations=8))]
#[allow(clippy::too_many_arguments)] // Python keyword arguments
pub fn plan<'py>(
    py: Python<'py>,
    scene: PyRef<'_, PyScene>,
    target: String,
    entry_m: Option<[[f64; 2]; 2]>,
    angles_deg: Option<[f64; 2]>,
    speed_mm_s: Option<f64>,
    threads: usize,
    tolerance_fraction: f64,
    max_iterations: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let kind = scene.inner.clone();
    let SceneKind::D2(s) = &*kind else {
        return Err(NeedlesimError::new_err("plan: planning is implemented for 2D scenes; this scene is 3D"));
    };
    if !(tolerance_fraction.is_finite() && tolerance_fraction > 0.0) {
        return Err(PlanError::new_err(format!("tolerance_fraction = {tolerance_fraction}: must be finite and > 0")));
    }
    let req = PlanRequest { target, entry_m, angles_deg, speed_m_s: speed_mm_s.map(|v| v * 1e-3) };
    let opts = PlanOptions { threads, tolerance_fraction, max_iterations, ..PlanOptions::default() };
    let text = py
        .detach(|| -> anyhow::Result<String> {
            let p = plan_insertion(s, &req, &opts, |_| ControlFlow::Continue(()))?;
            Ok(serde_json::to_string(&p)?)
        })
        .map_err(|e| {
            // The field of a bad request starts the message already (PlanInputError).
            let input = e.downcast_ref::<PlanInputError>().is_some();
            PlanError::new_err(if input { e.to_string() } else { format!("{e:#}") })
        })?;
    py.import("json")?.call_method1("loads", (text,))
}
