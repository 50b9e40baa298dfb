#!/usr/bin/env python3
"""Times SciPy's sparse direct solver on one static problem in the exchange format
(../shared/validation/README.md; `needlesim-server simulate --dump-state` writes one).

    python scipy_static.py scenario.json

Prints one JSON object: assembly_s (numpy assembly of K in CSC, local frames, the split into
free and constrained DOFs), solve_s (scipy.sparse.linalg.spsolve of the free block), n_dofs,
n_free, strain_energy and max_abs_displacement. Used by `needlesim-lab bench`.
"""

import json
import sys
import time

import numpy as np
import scipy
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def assemble(sc):
    x = np.asarray(sc["nodes"], dtype=float)
    tri = np.asarray(sc["triangles"], dtype=np.int64)
    n = len(x)
    n_t = len(tri)
    e = np.asarray(sc.get("E_elem") or [sc["E"]] * n_t, dtype=float)
    nu = np.asarray(sc.get("nu_elem") or [sc["nu"]] * n_t, dtype=float)
    t = float(sc.get("thickness", 1.0))
    mu = e / (2 * (1 + nu))
    if sc.get("plane", "strain") == "stress":
        lam = e * nu / (1 - nu**2)
    else:
        lam = e * nu / ((1 + nu) * (1 - 2 * nu))
    p = x[tri]  # (T, 3, 2)
    x1, x2, x3 = p[:, 0], p[:, 1], p[:, 2]
    det = (x2[:, 0] - x1[:, 0]) * (x3[:, 1] - x1[:, 1]) - (x3[:, 0] - x1[:, 0]) * (x2[:, 1] - x1[:, 1])
    area = 0.5 * np.abs(det)
    b = np.stack([x2[:, 1] - x3[:, 1], x3[:, 1] - x1[:, 1], x1[:, 1] - x2[:, 1]], axis=1) / det[:, None]
    c = np.stack([x3[:, 0] - x2[:, 0], x1[:, 0] - x3[:, 0], x2[:, 0] - x1[:, 0]], axis=1) / det[:, None]
    bm = np.zeros((n_t, 3, 6))
    bm[:, 0, 0::2] = b
    bm[:, 1, 1::2] = c
    bm[:, 2, 0::2] = c
    bm[:, 2, 1::2] = b
    d = np.zeros((n_t, 3, 3))
    d[:, 0, 0] = d[:, 1, 1] = lam + 2 * mu
    d[:, 0, 1] = d[:, 1, 0] = lam
    d[:, 2, 2] = mu
    ke = np.einsum("tki,tkl,tlj->tij", bm, d, bm) * (area * t)[:, None, None]
    dofs = np.stack([2 * tri[:, 0], 2 * tri[:, 0] + 1, 2 * tri[:, 1], 2 * tri[:, 1] + 1, 2 * tri[:, 2], 2 * tri[:, 2] + 1], axis=1)
    rows = np.repeat(dofs, 6, axis=1).ravel()
    cols = np.tile(dofs, (1, 6)).ravel()
    k = sp.coo_matrix((ke.ravel(), (rows, cols)), shape=(2 * n, 2 * n)).tocsc()
    return k, n


def main():
    with open(sys.argv[1]) as fh:
        sc = json.load(fh)
    t0 = time.perf_counter()
    k, n = assemble(sc)
    n_dofs = 2 * n
    constrained = np.zeros(n_dofs, dtype=bool)
    value = np.zeros(n_dofs)
    f = np.zeros(n_dofs)
    for node in sc.get("fixed_nodes", []):
        constrained[2 * node : 2 * node + 2] = True
    for pr in sc.get("prescribed", []):
        for comp, key in enumerate(("ux", "uy")):
            if pr.get(key) is not None:
                constrained[2 * pr["node"] + comp] = True
                value[2 * pr["node"] + comp] = pr[key]
    for ld in sc.get("loads", []):
        f[2 * ld["node"]] += ld.get("fx", 0.0)
        f[2 * ld["node"] + 1] += ld.get("fy", 0.0)
    # Local frames: u = T u_loc, K_loc = T^T K T, f_loc = T^T f.
    rot = sp.identity(n_dofs, format="lil")
    for pl in sc.get("prescribed_local", []):
        i, a = pl["node"], pl["angle_rad"]
        cs, sn = np.cos(a), np.sin(a)
        rot[2 * i, 2 * i], rot[2 * i, 2 * i + 1] = cs, -sn
        rot[2 * i + 1, 2 * i], rot[2 * i + 1, 2 * i + 1] = sn, cs
        for comp, key in enumerate(("ut", "un")):
            if pl.get(key) is not None:
                constrained[2 * i + comp] = True
                value[2 * i + comp] = pl[key]
    rot = rot.tocsc()
    k_loc = (rot.T @ k @ rot).tocsc()
    f_loc = rot.T @ f
    free = np.flatnonzero(~constrained)
    fixed = np.flatnonzero(constrained)
    k_ff = k_loc[free][:, free].tocsc()
    rhs = f_loc[free] - k_loc[free][:, fixed] @ value[fixed]
    t1 = time.perf_counter()
    u_free = spla.spsolve(k_ff, rhs)
    t2 = time.perf_counter()
    u_loc = value.copy()
    u_loc[free] = u_free
    u = rot @ u_loc
    energy = 0.5 * float(u @ (k @ u))
    print(
        json.dumps(
            {
                "assembly_s": t1 - t0,
                "solve_s": t2 - t1,
                "n_dofs": int(n_dofs),
                "n_free": int(len(free)),
                "strain_energy": energy,
                "max_abs_displacement": float(np.max(np.abs(u))),
                "scipy": scipy.__version__,
                "solver": "scipy.sparse.linalg.spsolve (SuperLU, default COLAMD ordering)",
            }
        )
    )


if __name__ == "__main__":
    main()
