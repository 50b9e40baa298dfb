#!/usr/bin/env python3
"""Volumetric locking of needlesim's linear elements (issue 19): the compliance of a soft block
under a small loaded patch, with linear elements (needlesim's P1 triangles and tetrahedra) and
quadratic ones (P2, which do not lock at these Poisson ratios), computed independently with
scikit-fem.

    python locking.py [--quick]

The block: the paper's 0.1 m phantom (2D: plane strain, unit thickness; 3D: a 0.1 m cube), its
bottom fixed, E = 30 kPa, a uniform pressure of 1 kPa on a patch of the top face's centre (2D:
10 mm wide; 3D: 20 mm × 20 mm), the rest free. The measure is the patch's mean vertical
displacement (m): linear elements lock, i.e. come out stiffer, as ν → 0.5. The reference is P2 on
the finest mesh (3D: 10³, P2 on 20³ being beyond SciPy's direct solver here, so in 3D the
table compares the two elements rather than converging). Prints a markdown table: for each ν, element and mesh, the displacement and its
error against the reference.
"""

import sys

import numpy as np
from skfem import (Basis, ElementTetP1, ElementTetP2, ElementTriP1, ElementTriP2, ElementVector, FacetBasis, MeshTet,
                   MeshTri, asm, condense, solve)
from skfem.helpers import dot
from skfem.models.elasticity import lame_parameters, linear_elasticity
from skfem import LinearForm

E_PA = 30e3
SIDE_M = 0.1
PATCH_M = 0.01
# 3D: a 20 mm square patch, so that a 10³ grid (h = 10 mm) has lines on its edges.
PATCH3_M = 0.02
PRESSURE_PA = 1e3


def patch_displacement(dim, n, element, nu):
    """Mean vertical displacement of the loaded patch on an n-per-side grid."""
    if dim == 2:
        mesh = MeshTri.init_tensor(np.linspace(0, SIDE_M, n + 1), np.linspace(0, SIDE_M, n + 1))
        # needlesim's plane strain: lambda = E nu / ((1 + nu)(1 - 2 nu)).
        lam, mu = lame_parameters(E_PA, nu)
        top = lambda x: np.isclose(x[1], SIDE_M) & (np.abs(x[0] - SIDE_M / 2) < PATCH_M / 2)
        bottom = lambda x: np.isclose(x[1], 0.0)
        e = ElementVector(ElementTriP1() if element == "P1" else ElementTriP2())
        up = 1
    else:
        g = np.linspace(0, SIDE_M, n + 1)
        mesh = MeshTet.init_tensor(g, g, g)
        lam, mu = lame_parameters(E_PA, nu)
        top = lambda x: np.isclose(x[2], SIDE_M) & (np.abs(x[0] - SIDE_M / 2) < PATCH3_M / 2) & (np.abs(x[1] - SIDE_M / 2) < PATCH3_M / 2)
        bottom = lambda x: np.isclose(x[2], 0.0)
        e = ElementVector(ElementTetP1() if element == "P1" else ElementTetP2())
        up = 2
    mesh = mesh.with_boundaries({"patch": top, "bottom": bottom})
    basis = Basis(mesh, e)
    K = asm(linear_elasticity(lam, mu), basis)
    fb = FacetBasis(mesh, e, facets=mesh.boundaries["patch"])

    @LinearForm
    def load(v, w):
        return -PRESSURE_PA * v[up]

    @LinearForm
    def vertical(v, w):
        return v[up]

    @LinearForm
    def one(v, w):
        return v  # summed over the basis: the integral of 1

    f = asm(load, fb)
    D = basis.get_dofs("bottom").all()
    u = solve(*condense(K, f, D=D))
    # The patch's facets are selected by their midpoints (strictly inside the patch): on grids
    # whose lines meet the patch's edges (h divides 5 mm) the patch is exactly 10 mm wide.
    patch_area = float(asm(one, FacetBasis(mesh, ElementTriP1() if dim == 2 else ElementTetP1(), facets=mesh.boundaries["patch"])).sum())
    assert abs(patch_area - (PATCH_M if dim == 2 else PATCH3_M ** 2)) < 1e-9, patch_area
    return float(asm(vertical, fb) @ u) / patch_area


def main():
    quick = "--quick" in sys.argv
    # Grid sizes whose lines meet the patch's edges.
    cases = {2: [20, 40, 80] + ([] if quick else [160]), 3: [10] if quick else [10, 20]}
    print("| dim | ν | element | grid | patch displacement (µm) | error vs P2 finest |")
    print("|---|---|---|---|---|---|")
    for dim, grids in cases.items():
        for nu in (0.3, 0.45, 0.49):
            ref_grid = grids[-1] if dim == 2 else 10
            ref = patch_displacement(dim, ref_grid, "P2", nu)
            for element in ("P1", "P2"):
                for n in grids:
                    if dim == 3 and element == "P2" and n > 10:
                        continue  # P2 on 20³ (207k DOFs) is beyond SciPy's direct solver here
                    w = ref if (element == "P2" and n == ref_grid) else patch_displacement(dim, n, element, nu)
                    print(f"| {dim}D | {nu} | {element} | {n}{'²' if dim == 2 else '³'} | {w * -1e6:.3f} | {(w - ref) / ref * 100:+.1f} % |", flush=True)


if __name__ == "__main__":
    main()
