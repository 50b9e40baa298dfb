"""A probing experiment from the independent reference FEM (issue 19): a phantom on a mesh
`--refine` times finer than its markers, solved by ../shared/validation/fem_ref.py (scikit-fem),
written in the formats `needlesim-lab identify probe` reads, with seeded noise.

The phantom: a `--width` x `--height` block, plane stress `--thickness`, fixed along its bottom
edge; a probe holds the top edge's middle node and moves it linearly from rest to
(`--probe-dx`, `--probe-dy`) over `--frames` camera frames `--interval` s apart. Markers sit on
every `--refine`-th node of the fine mesh (`--markers` per side), numbered row-major from the
bottom-left as `identify synth probe` numbers them. The marker pixels are those of a nominal
camera (5000 px/m, a 20 px margin, image rows growing downwards) plus Gaussian noise of
`--marker-noise-px`; metres are recovered from the noisy pixels. The probe log (100 Hz) carries
the reaction at the probe node (the force the probe applies to the tissue), plus Gaussian noise
of `--force-noise-rel` times the final force's magnitude on each component.

    python tests/support/probe_fem_ref.py --fem-ref ../shared/validation/fem_ref.py --out DIR

writes DIR/probe-tracks.csv, DIR/probe-log.csv and DIR/truth.json.
"""

import argparse
import json
import pathlib
import subprocess
import sys

import numpy as np

PX_PER_M = 5000.0
MARGIN_PX = 20.0

ap = argparse.ArgumentParser()
ap.add_argument("--fem-ref", required=True)
ap.add_argument("--out", required=True)
ap.add_argument("--markers", type=int, default=11, help="markers per side")
ap.add_argument("--refine", type=int, default=4, help="fine-mesh intervals between markers")
ap.add_argument("--width", type=float, default=0.1)
ap.add_argument("--height", type=float, default=0.1)
ap.add_argument("--thickness", type=float, default=0.01)
ap.add_argument("--young-modulus-pa", type=float, default=30e3)
ap.add_argument("--poisson-ratio", type=float, default=0.45)
ap.add_argument("--probe-dx", type=float, default=0.001)
ap.add_argument("--probe-dy", type=float, default=-0.005)
ap.add_argument("--frames", type=int, default=6)
ap.add_argument("--interval", type=float, default=0.5)
ap.add_argument("--marker-noise-px", type=float, default=0.1)
ap.add_argument("--force-noise-rel", type=float, default=0.01)
ap.add_argument("--seed", type=int, default=1)
a = ap.parse_args()
out = pathlib.Path(a.out)
out.mkdir(parents=True, exist_ok=True)

# The fine mesh: n x n nodes, each square cut along its rising diagonal.
n = (a.markers - 1) * a.refine + 1
xs, ys = np.linspace(0.0, a.width, n), np.linspace(0.0, a.height, n)
node = lambda i, j: j * n + i  # noqa: E731
nodes = [[float(xs[i]), float(ys[j])] for j in range(n) for i in range(n)]
tris = []
for j in range(n - 1):
    for i in range(n - 1):
        p, q, r, s = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
        tris += [[p, q, r], [p, r, s]]
probe = node((n - 1) // 2, n - 1)
scenario = {
    "nodes": nodes,
    "triangles": tris,
    "E": a.young_modulus_pa,
    "nu": a.poisson_ratio,
    "plane": "stress",
    "thickness": a.thickness,
    "fixed_nodes": [node(i, 0) for i in range(n)],
    "prescribed": [{"node": probe, "ux": a.probe_dx, "uy": a.probe_dy}],
    "loads": [],
}
(out / "scenario.json").write_text(json.dumps(scenario))
subprocess.run([sys.executable, a.fem_ref, str(out / "scenario.json"), str(out / "result.json")], check=True)
res = json.loads((out / "result.json").read_text())
u = np.asarray(res["displacements"], dtype=float)
reaction = next(r for r in res["reactions"] if r["node"] == probe)
f_end = np.array([reaction["rx"], reaction["ry"]], dtype=float)

rng = np.random.default_rng(a.seed)
markers = [node(i * a.refine, j * a.refine) for j in range(a.markers) for i in range(a.markers)]
t_end = (a.frames - 1) * a.interval
rows = ["frame,t_s,marker,x_px,y_px,x_m,y_m,detected"]
for k in range(a.frames):
    t = k * a.interval
    s = t / t_end
    for m, v in enumerate(markers):
        x = np.asarray(nodes[v]) + s * u[v]
        px = np.array([MARGIN_PX + x[0] * PX_PER_M, MARGIN_PX + (a.height - x[1]) * PX_PER_M])
        px = np.round((px + a.marker_noise_px * rng.standard_normal(2)) * 1e4) / 1e4
        xm = np.round(np.array([(px[0] - MARGIN_PX) / PX_PER_M, a.height - (px[1] - MARGIN_PX) / PX_PER_M]) * 1e9) / 1e9
        rows.append(f"{k},{t:.6f},{m},{px[0]:.4f},{px[1]:.4f},{xm[0]:.9f},{xm[1]:.9f},1")
(out / "probe-tracks.csv").write_text("\n".join(rows) + "\n")

sigma_f = a.force_noise_rel * float(np.hypot(*f_end))
rows = ["t_s,probe_disp_x_m,probe_disp_y_m,force_x_n,force_y_n"]
for k in range(int(round(t_end * 100.0)) + 1):
    t = k / 100.0
    s = t / t_end
    f = s * f_end + sigma_f * rng.standard_normal(2)
    rows.append(f"{t:.6f},{s * a.probe_dx:.9e},{s * a.probe_dy:.9e},{f[0]:.9e},{f[1]:.9e}")
(out / "probe-log.csv").write_text("\n".join(rows) + "\n")
truth = {
    "young_modulus_pa": a.young_modulus_pa,
    "poisson_ratio": a.poisson_ratio,
    "grid_arg": f"{a.markers},{a.markers},{a.width},{a.height}",
    "probe_marker": markers.index(probe),
    "fine_nodes_per_side": n,
    "final_force_n": f_end.tolist(),
}
(out / "truth.json").write_text(json.dumps(truth))
print(json.dumps(truth))
