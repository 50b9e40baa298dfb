//! The Python exceptions of `needlesim` and the mapping of the Rust errors onto them: by the
//! error's type (the failing call's kind, or the variant of a typed error), never by its text.
//! Each exception's message is the Rust error with its causes, as the CLI prints them
//! (`outer: cause: cause`, anyhow's alternate format).

use needlesim_core::StepError;
use needlesim_core::sim::SimError;
use needlesim_core::sim3::SimError3;
use needlesim_offline::RunError;
use pyo3::PyErr;
use pyo3::create_exception;
use pyo3::exceptions::PyException;

create_exception!(
    needlesim,
    NeedlesimError,
    PyException,
    "The base of every error needlesim raises. The message is the Rust error with its causes, as the \
     needlesim-server CLI prints it."
);
create_exception!(
    needlesim,
    SceneError,
    NeedlesimError,
    "A scene could not be loaded: the path is neither a file nor a shipped example, the TOML is invalid, \
     a value is out of range, the mesh is refused or its stiffness does not factorise."
);
create_exception!(
    needlesim,
    TrajectoryError,
    NeedlesimError,
    "A trajectory is refused: an unreadable file, a CSV or array that is malformed, not finite, not \
     increasing in time, of non-unit quaternions (3D), or longer than the tick limit."
);
create_exception!(
    needlesim,
    PoseError,
    NeedlesimError,
    "A commanded base pose is refused: the wrong number of components, a NaN or infinite component, \
     or (3D) an orientation quaternion whose norm is not 1. The simulation's state is unchanged."
);
create_exception!(
    needlesim,
    SimulationError,
    NeedlesimError,
    "The simulation could not be built from the scene's parameters, or a step failed: a diverged \
     solve (the simulation stays faulted), a singular working-set update, a failed compliance column."
);
create_exception!(
    needlesim,
    ScenarioError,
    NeedlesimError,
    "A static problem in the exchange format is refused (unreadable, not valid JSON of the format, \
     bad node indices, a mesh over the limits) or its solve failed."
);
create_exception!(
    needlesim,
    PlanError,
    NeedlesimError,
    "A planning request is refused (the message starts with the field that is wrong: target, entry, \
     angles_deg, speed_mm_s, tolerance_fraction) or a simulated candidate failed."
);

/// An error and its causes, `outer: cause: cause`, as anyhow's `{:#}` prints them.
pub fn chain(e: &(dyn std::error::Error + 'static)) -> String {
    let mut s = e.to_string();
    let mut cur = e.source();
    while let Some(c) = cur {
        s.push_str(": ");
        s.push_str(&c.to_string());
        cur = c.source();
    }
    s
}

/// A scene loader's error.
pub fn scene_error(e: anyhow::Error) -> PyErr {
    SceneError::new_err(format!("{e:#}"))
}

/// A static solve's error (reading, parsing or solving the scenario).
pub fn scenario_error(e: anyhow::Error) -> PyErr {
    ScenarioError::new_err(format!("{e:#}"))
}

/// A trajectory's error (any of the trajectory crate's, or reading its file).
pub fn trajectory_error(e: &(dyn std::error::Error + 'static)) -> PyErr {
    TrajectoryError::new_err(chain(e))
}

/// A 2D simulation error: a rejected pose is a [`PoseError`], the rest [`SimulationError`]s.
pub fn sim_error(e: &SimError) -> PyErr {
    match e {
        SimError::NonFinitePose { .. } => PoseError::new_err(chain(e)),
        SimError::InvalidParams(_) | SimError::Tissue(_) | SimError::Mixed(_) | SimError::Diverged { .. } => {
            SimulationError::new_err(chain(e))
        }
    }
}

/// A 3D simulation error: a rejected pose is a [`PoseError`], every other variant (parameters,
/// the working solver, a column solve, and the column stores' errors as they are added) a
/// [`SimulationError`].
pub fn sim3_error(e: &SimError3) -> PyErr {
    match e {
        SimError3::Pose { .. } => PoseError::new_err(chain(e)),
        _ => SimulationError::new_err(chain(e)),
    }
}

/// A scripted run's error, in either dimension: the script's length, end or first pose is a
/// [`TrajectoryError`], a step stopped by a rejected pose a [`PoseError`], any other failure a
/// [`SimulationError`].
pub fn run_error<E: StepError>(e: &RunError<E>) -> PyErr {
    let msg = chain(e);
    match e {
        RunError::TooLong(_) | RunError::BadEnd { .. } | RunError::FirstPose(_) => TrajectoryError::new_err(msg),
        RunError::Step { source, .. } if source.is_bad_pose() => PoseError::new_err(msg),
        RunError::Setup(_) | RunError::Step { .. } | RunError::Prefetch { .. } | RunError::Unconverged(_) => SimulationError::new_err(msg),
    }
}
