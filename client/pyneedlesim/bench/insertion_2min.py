"""Timing of a 2-minute simulated insertion (120,001 ticks at 1 kHz) into the paper phantom:
`Simulation.run` (the Rust loop, GIL released), a Python loop of `Simulation.step` over the
same tick poses, and the Rust `needlesim-server simulate` binary (its own wall time, from its
log line `simulated ... wall_s`). A timing script, not a test: nothing is asserted but that the
three agree on the final force.

    NEEDLESIM_SERVER=target/release/needlesim-server python client/pyneedlesim/bench/insertion_2min.py
"""

import os
import re
import subprocess
import tempfile
import time

import numpy as np

import needlesim

# In over 60 s to 75 mm, out over 60 s: 120 s at 1 kHz.
TRAJ = "t_s,x_m,y_m,theta_rad\n0,0.05,0.205,-1.5707963267948966\n60,0.05,0.125,-1.5707963267948966\n120,0.05,0.205,-1.5707963267948966\n"


def main():
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "two-minutes.csv")
        with open(path, "w") as f:
            f.write(TRAJ)
        scene = needlesim.load_scene("paper-phantom")
        t_s, poses = needlesim.tick_poses(scene, path)
        print(f"scene {scene.name}: {len(scene.nodes_m)} nodes; {len(poses)} ticks; load {os.getloadavg()}")

        t = time.perf_counter()
        run = needlesim.Simulation(scene).run(path)
        run_s = time.perf_counter() - t

        sim = needlesim.Simulation(scene, initial_pose=poses[0])
        step = sim.step
        pose_list = poses.tolist()
        t = time.perf_counter()
        for p in pose_list:
            r = step(p)
        loop_s = time.perf_counter() - t
        assert np.array_equal(r.force_n, run.force_n[-1])

        server = os.environ["NEEDLESIM_SERVER"]
        out = os.path.join(d, "cli.csv")
        t = time.perf_counter()
        p = subprocess.run([server, "simulate", "--scene", "paper-phantom", "--trajectory", path, "-o", out], capture_output=True, text=True, check=True)
        cli_process_s = time.perf_counter() - t
        log = re.sub(r"\x1b\[[0-9;]*m", "", p.stderr)  # the log's colours
        m = re.search(r"wall_s=([0-9.e+-]+)", log)
        cli_s = float(m.group(1)) if m else float("nan")

        steps = run.step_times_s
        print(f"Simulation.run:        {run_s:7.3f} s  ({run_s / len(poses) * 1e6:6.2f} us/tick; step p50 {np.median(steps) * 1e6:.1f} us)")
        print(f"Python loop of step:   {loop_s:7.3f} s  ({loop_s / len(poses) * 1e6:6.2f} us/tick)")
        print(f"needlesim-server simulate: {cli_s:7.3f} s run (its wall_s, CSV included), {cli_process_s:.3f} s process")
        print(f"ratios to the Rust loop: run {run_s / cli_s:.3f}, step loop {loop_s / cli_s:.3f}; load {os.getloadavg()}")


if __name__ == "__main__":
    main()
