//! needlesim-py: the native part (`needlesim._native`) of the Python package `needlesim`,
//! built by maturin as an abi3 wheel (client/pyneedlesim/pyproject.toml). It wraps the Rust
//! crates without re-implementing them: scenes (`needlesim_scene::load_scene`,
//! `load_scene3d`), the 2D and 3D simulations (`needlesim_core::sim::Simulation`,
//! `needlesim_core::sim3::Simulation3`), the scripted run of the `simulate` command
//! (`needlesim_offline::simulate::run_observed`), the planner (`needlesim_offline::plan`) and the
//! static solve of the exchange format (`needlesim_scene::exchange::solve_any`). Typed Rust errors become the exceptions of
//! [`errors`], with the Rust messages. Long calls (loading a 3D scene, a run, a solve) release
//! the GIL.
//!
//! The pure-Python layer (python/needlesim/__init__.py) re-exports these names, and is where
//! Python-side features (sampling, distributed sweeps) are to be added.

mod errors;
mod plan;
mod scene;
mod sim;

use std::path::PathBuf;

use needlesim_core::MeshLimits;
use needlesim_scene::exchange::{parse_any_scenario, solve_any};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::errors::scenario_error;

/// Solves a static problem in the exchange format (2D, or 3D with ``"dim": 3``) as
/// ``needlesim-server solve`` does and returns its result as a dict (displacements,
/// reactions, strain energy, …; the format of the validation suite).
///
/// ``scenario``: a dict of the format, its JSON text (a str starting with ``{``), or the path
/// of a JSON file (str or os.PathLike). The GIL is released during the solve.
///
/// Raises ScenarioError naming what is wrong (unreadable, not the format, bad indices, a mesh
/// over the limits, a singular problem).
#[pyfunction]
fn solve<'py>(py: Python<'py>, scenario: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let json = py.import("json")?;
    let (text, label) = if scenario.is_instance_of::<PyDict>() {
        (json.call_method1("dumps", (scenario,))?.extract::<String>()?, "the scenario".to_owned())
    } else if scenario.is_instance_of::<PyString>() && scenario.extract::<String>()?.trim_start().starts_with('{') {
        (scenario.extract::<String>()?, "the scenario".to_owned())
    } else {
        let path: PathBuf = scenario.extract()?;
        let text = needlesim_scene::read_local_file(&path, needlesim_scene::MAX_LOCAL_FILE_BYTES)
            .map_err(|e| errors::ScenarioError::new_err(format!("{e:#}")))?;
        (text, path.display().to_string())
    };
    let result = py
        .detach(|| -> anyhow::Result<String> {
            use anyhow::Context as _;
            let sc = parse_any_scenario(&text).with_context(|| format!("{label} is not a valid scenario"))?;
            let r = solve_any(&sc, &MeshLimits::default()).with_context(|| label.clone())?;
            Ok(serde_json::to_string(&r)?)
        })
        .map_err(scenario_error)?;
    json.call_method1("loads", (result,))
}

/// The native module; `needlesim/__init__.py` re-exports it.
#[pymodule]
#[pyo3(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_function(wrap_pyfunction!(scene::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(sim::tick_poses, m)?)?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<scene::Target>()?;
    m.add_class::<sim::PySimulation>()?;
    m.add_class::<sim::StepResult>()?;
    m.add_class::<sim::RunResult>()?;
    m.add("NeedlesimError", py.get_type::<errors::NeedlesimError>())?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("TrajectoryError", py.get_type::<errors::TrajectoryError>())?;
    m.add("PoseError", py.get_type::<errors::PoseError>())?;
    m.add("SimulationError", py.get_type::<errors::SimulationError>())?;
    m.add("ScenarioError", py.get_type::<errors::ScenarioError>())?;
    m.add("PlanError", py.get_type::<errors::PlanError>())?;
    m.add("CONTACT_STATES", sim::CONTACT_STATES.to_vec())?;
    m.add("DEFAULT_MAX_TICKS", needlesim_offline::DEFAULT_MAX_TICKS)?;
    m.add("MAX_TICKS_LIMIT", needlesim_offline::MAX_TICKS_LIMIT)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
