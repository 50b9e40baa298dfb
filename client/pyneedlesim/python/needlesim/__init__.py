"""needlesim: real-time needle insertion simulation, from Python.

Load a scene (a shipped example by name, or a scene TOML file, 2D or 3D), step a simulation
with base poses and read forces, tip, contacts and targets as NumPy arrays, run a whole
scripted insertion (the GIL released, progress reported), and solve static problems of the
exchange format; plan an insertion (``plan``) and plan it robustly under tissue uncertainty,
serially or on a Dask cluster (the sub-module ``needlesim.robust``)::

    import needlesim
    scene = needlesim.load_scene("paper-phantom")
    sim = needlesim.Simulation(scene)
    r = sim.step((0.05, 0.2049, -1.5707963267948966))  # x_m, y_m, theta_rad
    print(r.force_n, r.tip_m)
    run = sim.run(progress=lambda done, total: print(done, "/", total))
    print(run.force_n[-1], run.inserted_length_m.max())

Errors raise subclasses of NeedlesimError (SceneError, TrajectoryError, PoseError,
SimulationError, ScenarioError, PlanError) with the Rust messages. The simulation's numerics are the Rust crates' (the compiled module
needlesim._native); needlesim.robust adds the sampling and the statistics of planning under
uncertainty.
"""

from pkgutil import extend_path

# The gRPC client's stubs (client/python/generate.py) are the sub-package needlesim.v1 in a
# directory of their own (PYTHONPATH): this package lets them in, so both import together.
__path__ = extend_path(__path__, __name__)

from ._native import (  # noqa: E402
    CONTACT_STATES,
    DEFAULT_MAX_TICKS,
    MAX_TICKS_LIMIT,
    NeedlesimError,
    PlanError,
    PoseError,
    RunResult,
    Scene,
    ScenarioError,
    SceneError,
    Simulation,
    SimulationError,
    StepResult,
    Target,
    TrajectoryError,
    __version__,
    load_scene,
    plan,
    solve,
    tick_poses,
)

__all__ = [
    "CONTACT_STATES",
    "DEFAULT_MAX_TICKS",
    "MAX_TICKS_LIMIT",
    "NeedlesimError",
    "PlanError",
    "PoseError",
    "RunResult",
    "Scene",
    "ScenarioError",
    "SceneError",
    "Simulation",
    "SimulationError",
    "StepResult",
    "Target",
    "TrajectoryError",
    "__version__",
    "load_scene",
    "plan",
    "solve",
    "tick_poses",
]
