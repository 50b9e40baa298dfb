#!/usr/bin/env python3
"""The 3D mesh-refinement study of issue 37 ("3D physics at 2D's fidelity"), from `simulate`'s CSV.

Refined copies of cube-phantom-3d (only nx = ny = nz change; every other key as shipped, so the
scene's default contact and cutting models) run two trajectories through the real binary:

- the issue's: vertical to 50 mm depth at 20 mm/s, hold 0.25 s, the base 1 mm sideways (+x) over
  0.5 s, hold 0.5 s. Measured: the axial force when the tip is 30 mm deep; the centre target's
  displacement when the tip is 10 mm above its centre; the lateral force at the end.
- the shipped vertical insertion (cube-phantom-3d.csv, 75 mm): the lateral force as a share of
  the axial force at 70 mm depth, and the largest tick-to-tick step of the axial force during
  steady insertion (depth 10-70 mm, the base moving), as a share of the force.

Usage: refine3d.py [--spread-contact] [--near-field] NEEDLESIM_SERVER [N ...]   (default N: 16 21 26
31). Prints a Markdown table; a mesh that does not run is reported with simulate's error.
`--spread-contact` adds `spread_contact = true` to the scene's `[needle]` (each contact a disc of
the needle's radius across the shaft, issue 37 item 1); `--near-field` adds `near_field = true`
(the needle's sub-grid compliance; off as shipped). Without them every key but the grid is the
shipped scene's.
"""
import csv
import math
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "..", "scenes")
TOP_M = 0.1  # the cube's top face
TIP0_Z_M = 0.105  # the tip's height at the start (base 0.205, 0.1 m needle)
CENTRE = (0.05, 0.05, 0.05)
QUAT = "0.7071067811865475,0,0.7071067811865475,0"


def issue_trajectory(path):
    """Vertical to 50 mm depth at 20 mm/s, hold 0.25 s, 1 mm +x over 0.5 s, hold 0.5 s."""
    travel = TIP0_Z_M - (TOP_M - 0.05)
    t1 = travel / 0.02
    z1 = 0.205 - travel
    rows = [(0.0, 0.05, 0.205), (t1, 0.05, z1), (t1 + 0.25, 0.05, z1), (t1 + 0.75, 0.051, z1), (t1 + 1.25, 0.051, z1)]
    with open(path, "w") as f:
        f.write("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n")
        for t, x, z in rows:
            f.write(f"{t!r},{x!r},0.05,{z!r},{QUAT}\n")


def refined_scene(n, trajectory, path, spread=False, near_field=False):
    text = open(os.path.join(SCENES, "cube-phantom-3d.toml")).read()
    keys = (["spread_contact = true"] if spread else []) + (["near_field = true"] if near_field else [])
    if keys:
        text, k = re.subn(r"(?m)^\[needle\]$", "[needle]\n" + "\n".join(keys), text)
        assert k == 1, "[needle] in cube-phantom-3d.toml"
    for axis in "xyz":
        text, k = re.subn(rf"(?m)^n{axis} = \d+$", f"n{axis} = {n}", text)
        assert k == 1, f"n{axis} in cube-phantom-3d.toml"
    text = re.sub(r'(?m)^trajectory = ".*"$', f'trajectory = "{trajectory}"', text)
    text = re.sub(r'(?m)^name = ".*"$', f'name = "cube-phantom-3d-{n}"', text, count=1)
    with open(path, "w") as f:
        f.write(text)


def run(server, scene, out):
    p = subprocess.run([server, "simulate", "--scene", scene, "-o", out], capture_output=True, text=True)
    if p.returncode != 0:
        return (p.stderr.strip().splitlines() or ["failed"])[-1]
    return None


def rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def first(rs, pred):
    return next((r for r in rs if pred(r)), None)


def issue_metrics(rs):
    depth = lambda r: TOP_M - r["tip_z_m"]
    r30 = first(rs, lambda r: depth(r) >= 0.03)
    r10 = first(rs, lambda r: r["tip_z_m"] <= CENTRE[2] + 0.01)
    disp = math.dist((r10["target_centre_x_m"], r10["target_centre_y_m"], r10["target_centre_z_m"]), CENTRE) if r10 else float("nan")
    last = rs[-1]
    return {
        "axial force at 30 mm (N)": abs(r30["f_axial_n"]) if r30 else float("nan"),
        "target displacement, tip 10 mm above (mm)": 1e3 * disp,
        "lateral force after the 1 mm move (N)": math.hypot(last["fx_n"], last["fy_n"]),
    }


def vertical_metrics(rs):
    depth = lambda r: TOP_M - r["tip_z_m"]
    r70 = first(rs, lambda r: depth(r) >= 0.07)
    share = math.hypot(r70["fx_n"], r70["fy_n"]) / abs(r70["f_axial_n"]) if r70 else float("nan")
    worst = 0.0
    for a, b in zip(rs, rs[1:]):
        if 0.01 <= depth(a) and depth(b) <= 0.07 and b["z_m"] < a["z_m"] and abs(b["f_axial_n"]) > 0:
            worst = max(worst, abs(b["f_axial_n"] - a["f_axial_n"]) / abs(b["f_axial_n"]))
    return {"lateral / axial at 70 mm (%)": 100 * share, "largest axial step, 10-70 mm (%)": 100 * worst}


def main():
    args = sys.argv[1:]
    spread = "--spread-contact" in args
    near_field = "--near-field" in args
    args = [a for a in args if a not in ("--spread-contact", "--near-field")]
    if not args:
        sys.exit(__doc__)
    server = args[0]
    ns = [int(a) for a in args[1:]] or [16, 21, 26, 31]
    table = []
    with tempfile.TemporaryDirectory() as tmp:
        traj = os.path.join(tmp, "issue37.csv")
        issue_trajectory(traj)
        shipped = os.path.abspath(os.path.join(SCENES, "cube-phantom-3d.csv"))
        for n in ns:
            row = {"n": n}
            for label, trajectory, metrics in [("issue", traj, issue_metrics), ("vertical", shipped, vertical_metrics)]:
                scene = os.path.join(tmp, f"cube-{n}-{label}.toml")
                refined_scene(n, trajectory, scene, spread, near_field)
                out = os.path.join(tmp, f"cube-{n}-{label}.csv")
                err = run(server, scene, out)
                if err:
                    row[f"{label} error"] = err
                    continue
                row.update(metrics(rows(out)))
            table.append(row)
            print(row, file=sys.stderr)
    keys = [k for k in table[0] if k != "n"] if table else []
    for r in table:
        keys += [k for k in r if k not in keys and k != "n"]
    print("| n³ | " + " | ".join(keys) + " |")
    print("|---|" + "---|" * len(keys))
    for r in table:
        cells = [r.get(k, "") for k in keys]
        print(f"| {r['n']} | " + " | ".join(f"{c:.4g}" if isinstance(c, float) else str(c) for c in cells) + " |")


if __name__ == "__main__":
    main()
