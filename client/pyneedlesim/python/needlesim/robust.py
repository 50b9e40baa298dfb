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
  planner's own family of aims: the entry fixed, the aim moved across the target) and inserts
  it deeper by candidate extra depths, sweeps them over *training* samples, interpolates each
  sample's closest approach between the aims, and picks the aim and depth with the highest
  sampled hit rate (ties: the shallowest, then the smallest mean closest approach) -- a direct
  estimate of the quantity to maximise, with no model of the tissue;
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


def closest_approaches(
    scene: str,
    target: str,
    trajectories: Sequence[np.ndarray],
    scale: Optional[dict] = None,
    until_s: Optional[Sequence[float]] = None,
) -> np.ndarray:
    """The closest approach of the tip to ``target`` (m) along each trajectory, in the scene
    ``scene`` (a name or path) loaded with ``scale``: shape (len(trajectories),). With
    ``until_s``, the closest approach over the ticks up to each of those times (on the
    trajectory's clock): shape (len(trajectories), len(until_s)). One scene load (and
    factorisation) serves every trajectory."""
    sc = load_scene(scene, scale=scale)
    names = [t.name for t in sc.targets]
    if target not in names:
        raise ValueError(f"target {target!r} is not in scene {sc.name!r} (targets: {', '.join(names)})")
    j = names.index(target)
    cuts = None if until_s is None else np.asarray(until_s, dtype=float)
    out = np.empty((len(trajectories),) if cuts is None else (len(trajectories), cuts.size))
    for i, traj in enumerate(trajectories):
        run = Simulation(sc).run(np.asarray(traj, dtype=float))
        d = run.target_distances_m[:, j]
        if cuts is None:
            out[i] = d.min()
        else:
            running = np.minimum.accumulate(d)
            k = np.searchsorted(run.t_s, cuts, side="right") - 1
            if k.min() < 0:
                raise ValueError(f"until_s: {cuts.min()} s is before the trajectory's start ({run.t_s[0]} s)")
            out[i] = running[k]
    return out


def _sample_unit(scene: str, target: str, trajectories: list, uncertainty: Uncertainty, seed: int, index: int, until_s=None) -> np.ndarray:
    """One work unit of a sweep: sample ``index`` of ``seed``, every trajectory."""
    return closest_approaches(scene, target, trajectories, uncertainty.scale(seed, index), until_s)


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
    until_s: Optional[Sequence[float]] = None,
) -> np.ndarray:
    """The closest approach (m) of each trajectory under samples ``0..n-1`` of ``seed``: shape
    (n, len(trajectories)), row ``i`` from sample ``i`` whoever computed it; with ``until_s``
    (see :func:`closest_approaches`) shape (n, len(trajectories), len(until_s)).

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
            rows.append(_sample_unit(scene, target, trajs, uncertainty, seed, i, until_s))
            if progress is not None:
                progress(i + 1, n)
    else:
        # One task per sample; gathered in the order of the futures, i.e. of the sample index,
        # whichever worker ran them and in whatever order they finished.
        futures = [client.submit(_sample_unit, scene, target, trajs, uncertainty, seed, i, until_s, pure=False) for i in range(n)]
        rows = client.gather(futures)
    shape = (n, len(trajs)) if until_s is None else (n, len(trajs), len(until_s))
    return np.array(rows, dtype=float).reshape(shape)


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


def deepen_trajectory(trajectory: np.ndarray, extra_m: float) -> np.ndarray:
    """A plan's trajectory (:func:`needlesim.plan`'s: a straight advance from row 0 to row 1 at
    constant speed, then holds) advancing ``extra_m`` further along its axis at the same speed,
    the holds shifted by the extra time."""
    t = np.array(trajectory, dtype=float)
    if t.shape[0] < 2 or t.shape[1] != 4:
        raise ValueError(f"trajectory: a plan's (n >= 2 rows of t_s, x_m, y_m, theta_rad), not shape {t.shape}")
    speed = math.hypot(t[1, 1] - t[0, 1], t[1, 2] - t[0, 2]) / (t[1, 0] - t[0, 0])
    dt = extra_m / speed
    th = t[1, 3]
    end = t[1, 1:3] + extra_m * np.array([math.cos(th), math.sin(th)])
    t[1:, 0] += dt
    t[1:, 1:3] = end
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
    # At hits = 0 (n) the lower (upper) bound is exactly 0 (1); rounding gave 1 - 1e-16 at 30 of
    # 30, below the estimate, and a negative error bar in the example's figure.
    lo = 0.0 if hits == 0 else min(p, max(0.0, centre - half))
    hi = 1.0 if hits == n else max(p, min(1.0, centre + half))
    return (lo, hi)


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
    #: Its rotation from the nominal plan about the entry point, rad, and its aim's lateral
    #: offset at the target's distance, m.
    angle_offset_rad: float
    lateral_offset_m: float
    #: How much deeper than the nominal plan it inserts, m.
    extra_depth_m: float
    #: The candidates: aims (lateral offsets, m) x extra depths (m); their closest approaches on
    #: the training samples, shape (n_train, n_aims, n_depths).
    candidate_offsets_m: np.ndarray
    extra_depths_m: np.ndarray
    training_closest_m: np.ndarray
    #: The training hit rate on the fine grid of aims ``grid_offsets_m`` (rows) x extra depths.
    grid_offsets_m: np.ndarray
    grid_hit_rate: np.ndarray
    #: The training hit rate of the nominal plan (aim 0, extra depth 0).
    nominal_training_hit_rate: float


def robust_plan(
    scene: str,
    target: str,
    uncertainty: Uncertainty,
    *,
    seed: int,
    n_train: int,
    lateral_offsets_m: Sequence[float] = tuple(np.linspace(-2e-3, 2e-3, 9)),
    extra_depths_m: Sequence[float] = tuple(np.linspace(0.0, 6e-3, 13)),
    nominal: Optional[dict] = None,
    client: Any = None,
) -> RobustPlan:
    """A plan maximising the probability of a hit under ``uncertainty``: an aim and a depth.

    The candidate aims rotate the nominal plan (``nominal``, else :func:`needlesim.plan` of the
    scene) about its entry point so that its aim moves across the target by
    ``lateral_offsets_m`` (at the target's distance from the entry; include 0, the nominal) --
    the planner's own family of aims, the entry fixed. The candidate depths go
    ``extra_depths_m`` beyond the nominal depth (include 0): a softer or more adherent tissue
    pushes the target further along the needle. Each aim is simulated to the deepest depth under
    training samples ``0..n_train-1`` of ``seed``, and the closest approach of each shallower
    depth is read off the same run (the ticks until the shallower plan would stop: the same
    poses, without its final 0.2 s hold). Each sample's closest approach is interpolated
    linearly between neighbouring aims on a grid 10 times finer; the plan is the grid point of
    highest hit rate, ties broken by the smallest extra depth (as deep as needed, no deeper),
    then by the smallest mean closest approach. The choice is an estimate on the training
    samples: evaluate it on fresh ones (:func:`evaluate`).
    """
    if isinstance(n_train, bool) or not isinstance(n_train, (int, np.integer)) or n_train < 1:
        raise ValueError(f"n_train = {n_train!r}: must be an integer of at least 1 (the plan is chosen on the training samples)")
    if nominal is None:
        nominal = plan(load_scene(scene), target)
    entry = nominal["plan"]["entry_m"]
    reach = math.dist(entry, nominal["target_center_m"])
    offsets = np.array(sorted(float(u) for u in lateral_offsets_m))
    depths = np.array(sorted(float(d) for d in extra_depths_m))
    if offsets.size < 2 or depths.size < 1 or depths[0] < 0:
        raise ValueError("lateral_offsets_m: at least two; extra_depths_m: at least one, none negative")
    base = np.asarray(nominal["trajectory"], dtype=float)
    deepest = deepen_trajectory(base, float(depths[-1]))
    cands = [rotate_trajectory(deepest, entry, u / reach) for u in offsets]
    until = base[1, 0] + depths / nominal["speed_m_s"]
    d = sweep(scene, target, cands, uncertainty, seed=seed, n=n_train, client=client, until_s=until)
    grid = np.linspace(offsets[0], offsets[-1], 10 * (offsets.size - 1) + 1)
    # dg[s, g, k]: sample s, aim grid[g], depth k.
    dg = np.stack([np.stack([np.interp(grid, offsets, d[s_, :, k]) for k in range(depths.size)], axis=1) for s_ in range(n_train)])
    radius = nominal["target_radius_m"]
    rate = (dg < radius).mean(axis=0)
    mean = dg.mean(axis=0)
    g_idx, k_idx = np.meshgrid(np.arange(grid.size), np.arange(depths.size), indexing="ij")
    best = np.flatnonzero(rate.ravel() == rate.max())
    key = np.lexsort((mean.ravel()[best], k_idx.ravel()[best]))  # by depth, then mean distance
    g, k = int(g_idx.ravel()[best[key[0]]]), int(k_idx.ravel()[best[key[0]]])
    angle = float(grid[g]) / reach
    j0 = int(np.argmin(np.abs(offsets)))
    return RobustPlan(
        nominal=nominal,
        trajectory=rotate_trajectory(deepen_trajectory(base, float(depths[k])), entry, angle),
        angle_offset_rad=angle,
        lateral_offset_m=float(grid[g]),
        extra_depth_m=float(depths[k]),
        candidate_offsets_m=offsets,
        extra_depths_m=depths,
        training_closest_m=d,
        grid_offsets_m=grid,
        grid_hit_rate=rate,
        nominal_training_hit_rate=float((d[:, j0, 0] < radius).mean()) if offsets[j0] == 0.0 else float("nan"),
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
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n = {n!r}: must be an integer of at least 1 (a hit rate needs a sample)")
    d = sweep(scene, target, trajectories, uncertainty, seed=seed, n=n, client=client)
    radius = next(t.radius_m for t in load_scene(scene).targets if t.name == target)  # sweep checked the name
    return [PlanEvaluation(d[:, j].copy(), radius) for j in range(d.shape[1])]
