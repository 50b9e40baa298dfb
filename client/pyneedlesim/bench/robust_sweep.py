"""Timing of the robust-planning evaluation sweep on the Fig. 3 scene: N samples (E and friction
+-20 %, seed 2) of the nominal plan and a second aim, run serially here and on a Dask
LocalCluster of 1 and 2 worker processes (one thread each). A timing script, not a test: it
asserts only that every run gives the serial run's closest approaches to the bit, and prints
the wall times, the per-sample cost and the bytes moved per sample (the pickled work unit and
its result).

    python client/pyneedlesim/bench/robust_sweep.py --samples 500
"""

import argparse
import os
import pickle
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import needlesim
from needlesim.robust import Uncertainty, rotate_trajectory, sweep, work_unit_args


def main():
    # Dask's worker processes are spawned: they import this file as a module, so nothing
    # may run at import time (it would start a cluster inside each worker).
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=500)
    ap.add_argument("--distribution", default="uniform", choices=["uniform", "normal"])
    args = ap.parse_args()

    SCENE, TARGET = "fig3-target", "biopsy"
    nominal = needlesim.plan(needlesim.load_scene(SCENE), TARGET)
    base = np.asarray(nominal["trajectory"])
    trajs = [base, rotate_trajectory(base, nominal["plan"]["entry_m"], 0.005)]
    unc = Uncertainty(0.2, 0.2, args.distribution)
    n = args.samples

    unit = pickle.dumps(work_unit_args(SCENE, TARGET, trajs, unc, 2, 0))
    print(f"{n} samples x {len(trajs)} insertions of {base[-1, 0]:.2f} s ({int(round(base[-1, 0] * 1000)) + 1} ticks); load {os.getloadavg()}")
    print(f"bytes per sample: work unit {len(unit)} (pickled arguments), result {len(pickle.dumps(np.zeros(len(trajs))))}")

    t = time.perf_counter()
    serial = sweep(SCENE, TARGET, trajs, unc, seed=2, n=n)
    serial_s = time.perf_counter() - t
    print(f"serial: {serial_s:.2f} s ({serial_s / n * 1e3:.1f} ms per sample); load {os.getloadavg()}")

    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
            client.run(lambda: __import__("needlesim").load_scene(SCENE) is not None)  # import and warm each worker (a Scene does not pickle: return a bool)
            t = time.perf_counter()
            d = sweep(SCENE, TARGET, trajs, unc, seed=2, n=n, client=client)
            wall_s = time.perf_counter() - t
        same = d.tobytes() == serial.tobytes()
        print(f"dask LocalCluster {workers} worker(s): {wall_s:.2f} s ({wall_s / n * 1e3:.1f} ms per sample); bit-identical to serial: {same}; load {os.getloadavg()}")
        assert same


if __name__ == "__main__":
    main()
