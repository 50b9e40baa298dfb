"""needlesim.robust: planning an insertion under tissue uncertainty, and the sweeps it needs,
serial or on a Dask cluster.

The planner (:func:`needlesim.plan`) plans for the nominal tissue: its aim compensates the
target's displacement in that tissue. The displacement grows with the friction that drags the
tissue and shrinks with its stiffness, so a plan that hits the nominal tissue can miss a softer
one. Here:

- :class:`Uncertainty` samples the tissue's Young's modulus and friction as factors on the
  scene's values: sample ``i`` of seed ``s`` draws from ``numpy.random.default_rng(
  SeedSequence([s, i]))``, so a sample depends on its index only, never on which worker runs it
  or in what order;
- :func:`sweep` simulates candidate trajectories under samples 0..n-1 and returns each one's
  closest approach to the target, :math:`d_{ij} = \\min_k |c_k - p_k|` (tip :math:`p_k`,
  displaced target centre :math:`c_k` at tick :math:`k`): a hit is :math:`d_{ij} < r`. With a
  ``dask.distributed`` client the samples run as tasks on its workers; each task is a scene name,
  the scale factors and the trajectories (a few hundred bytes), so workers need only this
  package;
- :func:`robust_plan` rotates the nominal plan about its entry point by candidate angles (the
  planner's own family of aims: the entry fixed, the aim moved across the target), sweeps them
  over *training* samples, interpolates each sample's closest approach between the candidates,
  and picks the angle with the highest sampled hit rate (ties: the smallest mean closest
  approach) -- a direct estimate of the quantity to maximise, with no model of the tissue;
- :func:`evaluate` compares plans on *fresh* samples (another seed, so the choice's optimism on
  its training samples does not leak into the figure), with Wilson confidence intervals.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional, Sequence

import numpy as np

from ._native import Simulation, load_scene, plan

#: The normal quantile of a two-sided 95 % interval.
Z95 = 1.959963984540054


@dataclass(frozen=True)
class Uncertainty:
    """Relative uncertainty of the tissue's Young's modulus and friction (of every region).

    ``distribution``: ``"uniform"`` draws each factor uniformly from
    :math:`[1 - \\rho, 1 + \\rho]` (``rho`` the relative half-width: "E ± 20 %" is 0.2);
    ``"normal"`` from :math:`\\mathcal{N}(1, \\rho)` clipped to :math:`[0.05, 3]`. E and friction
    are drawn independently, E first.
    """

    young_modulus_rel: float = 0.2
    friction_rel: float = 0.2
    distribution: str = "uniform"

    def __post_init__(self):
        if self.distribution not in ("uniform", "normal"):
            raise ValueError(f"distribution = {self.distribution!r}: must be 'uniform' or 'normal'")
        for name in ("young_modulus_rel", "friction_rel"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 0.0 <= v < 1.0):
                raise ValueError(f"{name} = {v}: must be finite, >= 0 and < 1")

    def scale(self, seed: int, index: int) -> dict[str, float]:
        """The factors of sample ``index`` of ``seed``: ``{"young_modulus_pa": ..,
        "friction_n_per_m": ..}`` (the ``scale`` of :func:`needlesim.load_scene`)."""
        rng = np.random.default_rng(np.random.SeedSequence([int(seed), int(index)]))
        if self.distribution == "uniform":
            e = rng.uniform(1.0 - self.young_modulus_rel, 1.0 + self.young_modulus_rel)
            f = rng.uniform(1.0 - self.friction_rel, 1.0 + self.friction_rel)
        else:
            e = float(np.clip(rng.normal(1.0, self.young_modulus_rel), 0.05, 3.0))
            f = float(np.clip(rng.normal(1.0, self.friction_rel), 0.05, 3.0))
        return {"young_modulus_pa": float(e), "friction_n_per_m": float(f)}


def closest_approaches(scene: str, target: str, trajectories: Sequence[np.ndarray], scale: Optional[dict] = None) -> np.ndarray:
    """The closest approach of the tip to ``target`` (m) along each trajectory, in the scene
    ``scene`` (a name or path) loaded with ``scale``: one float per trajectory. One scene load
    (and factorisation) serves every trajectory."""
    sc = load_scene(scene, scale=scale)
    names = [t.name for t in sc.targets]
    if target not in names:
        raise ValueError(f"target {target!r} is not in scene {sc.name!r} (targets: {', '.join(names)})")
    j = names.index(target)
    out = np.empty(len(trajectories))
    for i, traj in enumerate(trajectories):
        run = Simulation(sc).run(np.asarray(traj, dtype=float))
        out[i] = run.target_distances_m[:, j].min()
    return out


def _sample_unit(scene: str, target: str, trajectories: list, uncertainty: Uncertainty, seed: int, index: int) -> np.ndarray:
    """One work unit of a sweep: sample ``index`` of ``seed``, every trajectory."""
    return closest_approaches(scene, target, trajectories, uncertainty.scale(seed, index))


def work_unit_args(scene: str, target: str, trajectories: Sequence[np.ndarray], uncertainty: Uncertainty, seed: int, index: int) -> tuple:
    """The arguments of one sample's work unit, as :func:`sweep` sends them to a worker."""
    return (scene, target, [np.asarray(t, dtype=float) for t in trajectories], uncertainty, int(seed), int(index))


def sweep(
    scene: str,
    target: str,
    trajectories: Sequence[np.ndarray],
    uncertainty: Uncertainty,
    *,
    seed: int,
    n: int,
    client: Any = None,
    progress: Any = None,
) -> np.ndarray:
    """The closest approach (m) of each trajectory under samples ``0..n-1`` of ``seed``: shape
    (n, len(trajectories)), row ``i`` from sample ``i`` whoever computed it.

    ``client``: a ``dask.distributed.Client`` to run the samples on (one task per sample), or
    None to run them here, one after another. ``progress(done, n)`` is called as samples finish
    (serial runs only).
    """
    if n < 0:
        raise ValueError(f"n = {n}: must be >= 0")
    trajs = [np.asarray(t, dtype=float) for t in trajectories]
    if client is None:
        rows = []
        for i in range(n):
            rows.append(_sample_unit(scene, target, trajs, uncertainty, seed, i))
            if progress is not None:
                progress(i + 1, n)
    else:
        # One task per sample; gathered in the order of the futures, i.e. of the sample index,
        # whichever worker ran them and in whatever order they finished.
        futures = [client.submit(_sample_unit, scene, target, trajs, uncertainty, seed, i, pure=False) for i in range(n)]
        rows = client.gather(futures)
    return np.array(rows, dtype=float).reshape(n, len(trajs))


def rotate_trajectory(trajectory: np.ndarray, pivot_m: Sequence[float], angle_rad: float) -> np.ndarray:
    """A 2D trajectory (rows t_s, x_m, y_m, theta_rad) rotated by ``angle_rad`` about the point
    ``pivot_m``: the same insertion through the same entry point, aimed ``angle_rad`` further
    counter-clockwise."""
    t = np.array(trajectory, dtype=float)
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    dx, dy = t[:, 1] - pivot_m[0], t[:, 2] - pivot_m[1]
    t[:, 1] = pivot_m[0] + c * dx - s * dy
    t[:, 2] = pivot_m[1] + s * dx + c * dy
    t[:, 3] += angle_rad
    return t


def wilson_interval(hits: int, n: int, z: float = Z95) -> tuple[float, float]:
    """The Wilson score interval of a binomial proportion ``hits / n`` (95 % by default):
    :math:`\\frac{\\hat p + z^2/2n \\pm z\\sqrt{\\hat p(1-\\hat p)/n + z^2/4n^2}}{1 + z^2/n}`."""
    if n <= 0 or not 0 <= hits <= n:
        raise ValueError(f"hits = {hits}, n = {n}: need 0 <= hits <= n and n > 0")
    p = hits / n
    d = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / d
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / d
    return (max(0.0, centre - half), min(1.0, centre + half))


@dataclass
class PlanEvaluation:
    """A plan's closest approaches over samples and its hit rate."""

    closest_m: np.ndarray
    radius_m: float

    @property
    def n(self) -> int:
        return int(self.closest_m.size)

    @property
    def hits(self) -> int:
        return int(np.count_nonzero(self.closest_m < self.radius_m))

    @property
    def hit_probability(self) -> float:
        return self.hits / self.n

    @property
    def interval(self) -> tuple[float, float]:
        """The Wilson 95 % interval of the hit probability."""
        return wilson_interval(self.hits, self.n)

    def __repr__(self) -> str:
        lo, hi = self.interval
        q = np.quantile(self.closest_m, [0.5, 0.9]) * 1e3
        return (
            f"hit probability {self.hit_probability:.3f} ({self.hits}/{self.n}; 95 % CI {lo:.3f}-{hi:.3f}); "
            f"closest approach median {q[0]:.2f} mm, 90 % {q[1]:.2f} mm"
        )


@dataclass
class RobustPlan:
    """The result of :func:`robust_plan`."""

    nominal: dict
    #: The robust plan's trajectory (rows t_s, x_m, y_m, theta_rad).
    trajectory: np.ndarray
    #: Its rotation from the nominal plan about the entry point, rad.
    angle_offset_rad: float
    #: The candidates' rotations, rad, and their closest approaches on the training samples,
    #: shape (n_train, n_candidates).
    candidate_offsets_rad: np.ndarray
    training_closest_m: np.ndarray
    #: The interpolated hit rate on the training samples over ``grid_offsets_rad``.
    grid_offsets_rad: np.ndarray
    grid_hit_rate: np.ndarray


def robust_plan(
    scene: str,
    target: str,
    uncertainty: Uncertainty,
    *,
    seed: int,
    n_train: int,
    lateral_offsets_m: Sequence[float] = tuple(np.linspace(-2e-3, 2e-3, 9)),
    nominal: Optional[dict] = None,
    client: Any = None,
) -> RobustPlan:
    """A plan maximising the probability of a hit under ``uncertainty``.

    The candidates rotate the nominal plan (``nominal``, else :func:`needlesim.plan` of the
    scene) about its entry point so that its aim moves across the target by
    ``lateral_offsets_m`` (at the target's distance from the entry; include 0, the nominal).
    Each is simulated under training samples ``0..n_train-1`` of ``seed``; each sample's closest
    approach is interpolated linearly between neighbouring candidates on a grid 20 times finer,
    and the chosen rotation maximises the fraction of samples with a closest approach under the
    radius, ties broken by the smallest mean closest approach.
    """
    if nominal is None:
        nominal = plan(load_scene(scene), target)
    entry = nominal["plan"]["entry_m"]
    reach = math.dist(entry, nominal["target_center_m"])
    offsets = np.array(sorted(float(u) for u in lateral_offsets_m)) / reach
    if offsets.size < 2:
        raise ValueError("lateral_offsets_m: at least two candidates are needed")
    base = np.asarray(nominal["trajectory"], dtype=float)
    cands = [rotate_trajectory(base, entry, a) for a in offsets]
    d = sweep(scene, target, cands, uncertainty, seed=seed, n=n_train, client=client)
    grid = np.linspace(offsets[0], offsets[-1], 20 * (offsets.size - 1) + 1)
    dg = np.array([np.interp(grid, offsets, row) for row in d]).reshape(n_train, grid.size)
    rate = (dg < nominal["target_radius_m"]).mean(axis=0)
    mean = dg.mean(axis=0)
    best = np.flatnonzero(rate == rate.max())
    k = int(best[np.argmin(mean[best])])
    return RobustPlan(
        nominal=nominal,
        trajectory=rotate_trajectory(base, entry, float(grid[k])),
        angle_offset_rad=float(grid[k]),
        candidate_offsets_rad=offsets,
        training_closest_m=d,
        grid_offsets_rad=grid,
        grid_hit_rate=rate,
    )


def evaluate(
    scene: str,
    target: str,
    trajectories: Sequence[np.ndarray],
    uncertainty: Uncertainty,
    *,
    seed: int,
    n: int,
    client: Any = None,
) -> list[PlanEvaluation]:
    """Each trajectory's closest approaches and hit rate over samples ``0..n-1`` of ``seed``
    (the same samples for every trajectory, so their comparison is paired)."""
    d = sweep(scene, target, trajectories, uncertainty, seed=seed, n=n, client=client)
    radius = next(t.radius_m for t in load_scene(scene).targets if t.name == target)  # sweep checked the name
    return [PlanEvaluation(d[:, j].copy(), radius) for j in range(d.shape[1])]
