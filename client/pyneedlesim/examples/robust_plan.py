"""Robust planning of the paper's Fig. 3 insertion under tissue uncertainty (a notebook-style
script: run it top to bottom, or cell by cell).

The scene `fig3-target`: a needle entering a soft block at about 40 degrees, a 1.5 mm-radius
target 50 mm along its axis. Aimed straight, the needle misses: friction drags the tissue, and
the target with it. The planner (`needlesim.plan`) finds the aim that hits in the nominal tissue;
here the tissue's Young's modulus and friction are each uncertain by +-20 % (uniform, independent),
and we ask how often each plan hits, and pick a plan that hits more often:

1. the nominal plan (the Rust planner, the nominal tissue);
2. the robust plan: the nominal plan rotated about its entry point and inserted deeper, to the
   aim and depth whose sampled hit rate is highest on *training* samples (seed 1);
3. both evaluated on *fresh* samples (seed 2, 500 by default), with Wilson 95 % intervals;
4. a PNG: the training hit rate over the aim's lateral offset and the extra depth, the two hit
   probabilities with their intervals, and the distributions of the closest approach.

    python client/pyneedlesim/examples/robust_plan.py --samples 500 --train 100 --out robust_plan.png
    python client/pyneedlesim/examples/robust_plan.py --workers 2   # on a Dask LocalCluster

With ``--workers N`` (N >= 1) the samples run on a `dask.distributed` LocalCluster of N worker
processes (on a real cluster, pass its scheduler's address with ``--scheduler``); the figures
are the same to the bit, whatever N.
"""

import argparse
import json
import os
import time

import numpy as np

import needlesim
from needlesim.robust import Uncertainty, evaluate, robust_plan


def main():
    # Dask's LocalCluster spawns its worker processes, and a spawned process imports this file:
    # nothing may run at import time (it would start a cluster inside each worker).
    # %% Arguments
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=500, help="evaluation samples (seed 2)")
    ap.add_argument("--train", type=int, default=100, help="training samples of the robust plan (seed 1)")
    ap.add_argument("--distribution", default="uniform", choices=["uniform", "normal"])
    ap.add_argument("--rel", type=float, default=0.2, help="relative uncertainty of E and of friction")
    ap.add_argument("--workers", type=int, default=0, help="Dask LocalCluster worker processes (0: serial here)")
    ap.add_argument("--scheduler", default=None, help="a Dask scheduler's address instead of a LocalCluster")
    ap.add_argument("--out", default="robust_plan.png")
    ap.add_argument("--json", default=None, help="also write the figures as JSON here")
    args = ap.parse_args()

    SCENE, TARGET = "fig3-target", "biopsy"
    unc = Uncertainty(young_modulus_rel=args.rel, friction_rel=args.rel, distribution=args.distribution)

    client = cluster = None
    if args.scheduler or args.workers > 0:
        import dask
        from dask.distributed import Client, LocalCluster

        # Generous connection timeouts: on a loaded machine a worker process takes a while to start.
        dask.config.set({"distributed.comm.timeouts.connect": "300s", "distributed.comm.timeouts.tcp": "300s"})

        if args.scheduler:
            client = Client(args.scheduler)
        else:
            cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
            client = Client(cluster)

    # %% The nominal plan
    started = time.perf_counter()
    scene = needlesim.load_scene(SCENE)
    nominal = needlesim.plan(scene, TARGET)
    radius_m = nominal["target_radius_m"]
    print(
        f"nominal plan: angle {np.degrees(nominal['plan']['angle_rad']):.2f} deg, predicted error "
        f"{nominal['plan']['predicted_error_m'] * 1e3:.3f} mm (straight: {nominal['straight']['predicted_error_m'] * 1e3:.3f} mm), "
        f"radius {radius_m * 1e3} mm"
    )

    # %% The robust plan (training samples, seed 1)
    rp = robust_plan(SCENE, TARGET, unc, seed=1, n_train=args.train, nominal=nominal, client=client)
    print(
        f"robust plan: aim {rp.lateral_offset_m * 1e3:+.2f} mm across ({np.degrees(rp.angle_offset_rad):+.3f} deg), "
        f"{rp.extra_depth_m * 1e3:.1f} mm deeper; training hit rate {rp.grid_hit_rate.max():.3f} against "
        f"{rp.nominal_training_hit_rate:.3f} nominal ({args.train} samples)"
    )

    # %% Both on fresh samples (seed 2)
    t_eval = time.perf_counter()
    ev_nominal, ev_robust = evaluate(SCENE, TARGET, [np.asarray(nominal["trajectory"]), rp.trajectory], unc, seed=2, n=args.samples, client=client)
    eval_s = time.perf_counter() - t_eval
    both = int(np.count_nonzero((ev_nominal.closest_m < radius_m) & (ev_robust.closest_m < radius_m)))
    print(f"nominal: {ev_nominal}")
    print(f"robust:  {ev_robust}")
    print(
        f"paired: robust hits where nominal misses {ev_robust.hits - both}, the reverse {ev_nominal.hits - both}; "
        f"evaluation {eval_s:.1f} s ({eval_s / max(1, args.samples) * 1e3:.1f} ms per sample of 2 insertions), "
        f"total {time.perf_counter() - started:.1f} s, workers {args.workers or 'serial'}, load {os.getloadavg()[0]:.2f}"
    )

    # %% The figure
    import matplotlib  # noqa: E402

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    u_mm, dd_mm = rp.grid_offsets_m * 1e3, rp.extra_depths_m * 1e3
    im = ax[0].pcolormesh(u_mm, dd_mm, rp.grid_hit_rate.T, shading="nearest", cmap="viridis", vmin=0, vmax=1)
    fig.colorbar(im, ax=ax[0], label="training hit rate")
    ax[0].plot([0.0], [0.0], "o", color="tab:blue", mec="w", ms=9, label="nominal plan")
    ax[0].plot([rp.lateral_offset_m * 1e3], [rp.extra_depth_m * 1e3], "*", color="tab:orange", mec="w", ms=14, label="robust plan")
    ax[0].set(xlabel="aim offset across the target (mm)", ylabel="extra depth (mm)", title=f"training samples ({args.train}, seed 1)")
    ax[0].legend(loc="upper left")
    names = ["nominal", "robust"]
    evs = [ev_nominal, ev_robust]
    p = [e.hit_probability for e in evs]
    err = np.array([[pi - e.interval[0], e.interval[1] - pi] for pi, e in zip(p, evs)]).T
    ax[1].bar(names, p, yerr=err, capsize=8, color=["tab:blue", "tab:orange"])
    for k, e in enumerate(evs):
        ax[1].text(k, 0.03, f"{e.hit_probability:.3f}\n[{e.interval[0]:.3f}, {e.interval[1]:.3f}]", ha="center", color="w")
    ax[1].set(ylim=(0, 1.02), ylabel="hit probability (Wilson 95 %)", title=f"fresh samples ({args.samples}, seed 2)")
    bins = np.linspace(0, max(e.closest_m.max() for e in evs) * 1e3, 40)
    for e, n, c in zip(evs, names, ["tab:blue", "tab:orange"]):
        ax[2].hist(e.closest_m * 1e3, bins=bins, alpha=0.6, label=n, color=c)
    ax[2].axvline(radius_m * 1e3, color="k", ls=":", label="target radius")
    ax[2].set(xlabel="closest approach of the tip (mm)", ylabel="samples", title=f"E and friction ±{args.rel:.0%} ({args.distribution})")
    ax[2].legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")

    if args.json:
        with open(args.json, "w") as f:
            json.dump(
                {
                    "samples": args.samples,
                    "train": args.train,
                    "distribution": args.distribution,
                    "rel": args.rel,
                    "radius_m": radius_m,
                    "robust_angle_offset_rad": rp.angle_offset_rad,
                    "robust_lateral_offset_m": rp.lateral_offset_m,
                    "robust_extra_depth_m": rp.extra_depth_m,
                    "nominal": {"hits": ev_nominal.hits, "interval": ev_nominal.interval, "closest_m": ev_nominal.closest_m.tolist()},
                    "robust": {"hits": ev_robust.hits, "interval": ev_robust.interval, "closest_m": ev_robust.closest_m.tolist()},
                    "eval_s": eval_s,
                },
                f,
            )

    if client is not None:
        client.close()
    if cluster is not None:
        cluster.close()


if __name__ == "__main__":
    main()
