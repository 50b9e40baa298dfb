"""Type stubs of needlesim (the compiled module needlesim._native, re-exported)."""

import os
from typing import Any, Callable, Final, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: Final[str]
#: The contact state codes of ``contact_states`` / ``needle_states`` arrays: index = code.
CONTACT_STATES: Final[list[str]]
#: The longest scripted run by default, in ticks (1000 s at 1 kHz).
DEFAULT_MAX_TICKS: Final[int]
#: The largest ``max_ticks`` a run or ``tick_poses`` accepts (10,000 s at 1 kHz): results are held in memory.
MAX_TICKS_LIMIT: Final[int]

F64Array = npt.NDArray[np.float64]
#: A trajectory: None (the scene's own), a CSV path, or an array-like of shape (n, 4) in 2D
#: (t_s, x_m, y_m, theta_rad) or (n, 8) in 3D (t_s, x_m, y_m, z_m, qw, qx, qy, qz).
TrajectoryLike = Union[None, str, os.PathLike[str], npt.ArrayLike]
#: A base pose: 3 numbers (x_m, y_m, theta_rad) in 2D, 7 (x_m, y_m, z_m, qw, qx, qy, qz) in 3D.
PoseLike = Union[Sequence[float], npt.NDArray[np.float64]]

class NeedlesimError(Exception):
    """The base of every error needlesim raises; the message is the Rust error with its causes."""

class SceneError(NeedlesimError):
    """A scene could not be loaded."""

class TrajectoryError(NeedlesimError):
    """A trajectory is refused (unreadable, malformed, not finite, not increasing, too long)."""

class PoseError(NeedlesimError):
    """A base pose is refused (wrong length, not finite, non-unit quaternion); state unchanged."""

class SimulationError(NeedlesimError):
    """The simulation could not be built, or a step failed (a diverged solve faults it)."""

class PlanError(NeedlesimError):
    """A planning request is refused (the message starts with the field) or a candidate failed."""

class ScenarioError(NeedlesimError):
    """A static problem of the exchange format is refused or its solve failed."""

class Target:
    """A target disc (2D) or sphere (3D) of a scene."""
    @property
    def name(self) -> str: ...
    @property
    def center_m(self) -> list[float]: ...
    @property
    def radius_m(self) -> float: ...

class Scene:
    """A loaded scene (see load_scene); immutable, shared by its simulations."""
    @property
    def dim(self) -> int: ...
    @property
    def name(self) -> str: ...
    @property
    def tick_rate_hz(self) -> float: ...
    @property
    def nodes_m(self) -> F64Array:
        """(n_nodes, dim) reference node coordinates, m."""
    @property
    def elements(self) -> npt.NDArray[np.int64]:
        """(n_elements, 3) triangles or (n_elements, 4) tetrahedra."""
    @property
    def fixed_nodes(self) -> npt.NDArray[np.int64]: ...
    @property
    def targets(self) -> list[Target]: ...
    @property
    def initial_pose(self) -> F64Array: ...
    @property
    def trajectory(self) -> Optional[F64Array]:
        """The scene's own trajectory samples, (n, 4) or (n, 8), or None."""

class StepResult:
    """What one step did; vectors have dim components, world frame."""
    @property
    def dim(self) -> int: ...
    @property
    def tick(self) -> int: ...
    @property
    def time_s(self) -> float: ...
    @property
    def clamped(self) -> bool: ...
    @property
    def converged(self) -> bool: ...
    @property
    def pose(self) -> F64Array: ...
    @property
    def force_n(self) -> F64Array: ...
    @property
    def torque_nm(self) -> F64Array:
        """(1,) in 2D (about z), (3,) in 3D."""
    @property
    def force_axial_n(self) -> float: ...
    @property
    def force_lateral_n(self) -> Optional[float]: ...
    @property
    def tip_m(self) -> F64Array: ...
    @property
    def inserted_length_m(self) -> float: ...
    @property
    def n_stuck(self) -> int: ...
    @property
    def n_slipping(self) -> int: ...
    @property
    def n_tip(self) -> int: ...
    @property
    def contact_states(self) -> npt.NDArray[np.int8]: ...
    @property
    def contact_reference_m(self) -> F64Array: ...
    @property
    def contact_positions_m(self) -> F64Array: ...
    @property
    def contact_forces_n(self) -> F64Array: ...
    @property
    def target_distances_m(self) -> F64Array: ...
    @property
    def target_positions_m(self) -> F64Array: ...
    @property
    def target_hits(self) -> npt.NDArray[np.bool_]: ...

class RunResult:
    """A run's time series (one row per tick) and counters."""
    @property
    def dim(self) -> int: ...
    @property
    def ticks(self) -> int: ...
    @property
    def clamped_ticks(self) -> int: ...
    @property
    def unconverged_ticks(self) -> int: ...
    @property
    def column_misses(self) -> int: ...
    @property
    def column_deferrals(self) -> int: ...
    @property
    def prefetched_columns(self) -> int: ...
    @property
    def stopped_early(self) -> bool: ...
    @property
    def t_s(self) -> F64Array: ...
    @property
    def pose(self) -> F64Array: ...
    @property
    def force_n(self) -> F64Array: ...
    @property
    def torque_nm(self) -> F64Array: ...
    @property
    def force_axial_n(self) -> F64Array: ...
    @property
    def force_lateral_n(self) -> Optional[F64Array]: ...
    @property
    def tip_m(self) -> F64Array: ...
    @property
    def inserted_length_m(self) -> F64Array: ...
    @property
    def contact_counts(self) -> npt.NDArray[np.int64]: ...
    @property
    def target_distances_m(self) -> F64Array: ...
    @property
    def target_positions_m(self) -> F64Array: ...
    @property
    def target_hits(self) -> npt.NDArray[np.bool_]: ...
    @property
    def step_times_s(self) -> F64Array: ...

class Simulation:
    """One needle in a scene's tissue, 2D or 3D as the scene is."""
    def __init__(self, scene: Scene, initial_pose: Optional[PoseLike] = None) -> None: ...
    @property
    def dim(self) -> int: ...
    @property
    def scene(self) -> Scene: ...
    @property
    def last(self) -> StepResult: ...
    def step(self, pose: PoseLike) -> StepResult: ...
    def run(
        self,
        trajectory: TrajectoryLike = None,
        *,
        progress: Optional[Callable[[int, int], Any]] = None,
        progress_every: int = 1000,
        max_ticks: int = ...,
    ) -> RunResult: ...
    def snapshot(self) -> dict[str, Any]: ...
    def dump_state(self) -> dict[str, Any]: ...

def load_scene(scene: Union[str, os.PathLike[str]], *, scale: Optional[dict[str, float]] = None) -> Scene:
    """A shipped example by name or a scene TOML file; ``scale`` multiplies region values of a
    2D scene (e.g. ``{"young_modulus_pa": 1.1}``) before it is built."""

def plan(
    scene: Scene,
    target: str,
    *,
    entry_m: Optional[Sequence[Sequence[float]]] = None,
    angles_deg: Optional[Sequence[float]] = None,
    speed_mm_s: Optional[float] = None,
    threads: int = 0,
    tolerance_fraction: float = 0.2,
    max_iterations: int = 8,
) -> dict[str, Any]:
    """The planner of ``needlesim-server plan`` (2D): the plan as the command's JSON, a dict."""
def tick_poses(
    scene: Scene, trajectory: TrajectoryLike = None, *, max_ticks: int = ...
) -> tuple[F64Array, F64Array]: ...
def solve(scenario: Union[dict[str, Any], str, os.PathLike[str]]) -> dict[str, Any]: ...
