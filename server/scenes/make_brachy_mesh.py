"""Makes server/scenes/brachy-3d.msh, the mesh of the brachytherapy-like 3D example scene.

A block of soft tissue, 80 × 100 × 80 mm (x across, y along the insertion, z up), entered
through its front face (y = 0, the perineum) along +y. Inside it:

* ``prostate`` — an ellipsoid, semi-axes 20 × 17 × 16 mm, centred at (40, 60, 42) mm: the stiff
  inclusion the needles aim into;
* ``urethra`` — a channel of radius 3 mm along y at x = 40 mm, z = 46 mm, from y = 35 mm to the
  back face, through the prostate: the sensitive structure the needles must avoid;
* ``tissue`` — the rest of the block;
* a cylindrical cavity of radius 10 mm along y at x = 40 mm, z = 12 mm, below the prostate, for
  the rectum holding the ultrasound probe: its wall is the physical surface ``rectum_wall``, fixed
  by the scene (the probe holds it); ``back`` (y = 100 mm, towards the pubic arch and bladder) is
  the other fixed surface; ``front`` (the skin at y = 0) is named too.

Physical volumes become the scene's regions and physical surfaces its boundary sets (see
``parse_msh3d`` in server/core/src/msh.rs). The mesh is about 6 mm in the tissue and 3 mm in
and around the prostate and urethra: about 4,600 nodes and 22,000 linear tetrahedra, MSH 4.1
ASCII, about 0.9 MB. Meshing is single-threaded with a fixed seed, so a given Gmsh version makes
the same file (tests/it/scenes3d.rs regenerates it and compares counts and region volumes).

Usage (the ``gmsh`` pip wheel, e.g. in tests/.venv)::

    python server/scenes/make_brachy_mesh.py [OUTPUT.msh]

The default output is brachy-3d.msh beside this script. Prints a JSON summary (node and
tetrahedron counts, the regions' geometric volumes in m³).
"""

import json
import os
import sys

import gmsh

MM = 1e-3
BLOCK = (80 * MM, 100 * MM, 80 * MM)
PROSTATE_CENTRE = (40 * MM, 60 * MM, 42 * MM)
PROSTATE_SEMI_AXES = (20 * MM, 17 * MM, 16 * MM)
URETHRA = {"x": 40 * MM, "z": 46 * MM, "y0": 35 * MM, "radius": 3 * MM}
RECTUM = {"x": 40 * MM, "z": 12 * MM, "radius": 10 * MM}
SIZE_TISSUE = 6.0 * MM
SIZE_FINE = 3.0 * MM


def build(out_path):
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.add("brachy-3d")
        occ = gmsh.model.occ
        lx, ly, lz = BLOCK
        block = occ.addBox(0, 0, 0, lx, ly, lz)
        rectum = occ.addCylinder(RECTUM["x"], 0, RECTUM["z"], 0, ly, 0, RECTUM["radius"])
        body, _ = occ.cut([(3, block)], [(3, rectum)])
        cx, cy, cz = PROSTATE_CENTRE
        ax, ay, az = PROSTATE_SEMI_AXES
        prostate = occ.addSphere(cx, cy, cz, 1.0)
        occ.dilate([(3, prostate)], cx, cy, cz, ax, ay, az)
        urethra = occ.addCylinder(URETHRA["x"], URETHRA["y0"], URETHRA["z"], 0, ly - URETHRA["y0"], 0, URETHRA["radius"])
        # Fragment: conforming volumes; then sort them out by their centres of mass.
        occ.fragment(body, [(3, prostate), (3, urethra)])
        occ.synchronize()

        def inside_urethra(p):
            return (p[0] - URETHRA["x"]) ** 2 + (p[2] - URETHRA["z"]) ** 2 < URETHRA["radius"] ** 2 and p[1] > URETHRA["y0"]

        def inside_prostate(p):
            return sum(((p[i] - PROSTATE_CENTRE[i]) / PROSTATE_SEMI_AXES[i]) ** 2 for i in range(3)) < 1.0

        # The urethra's pieces have their centres on its axis; of the rest, the largest is the
        # tissue (its centre of mass may well lie inside the prostate), the others the prostate.
        groups = {"tissue": [], "prostate": [], "urethra": []}
        rest = []
        for dim, tag in gmsh.model.getEntities(3):
            if inside_urethra(occ.getCenterOfMass(dim, tag)):
                groups["urethra"].append(tag)
            else:
                rest.append((occ.getMass(dim, tag), tag))
        rest.sort()
        groups["tissue"].append(rest.pop()[1])
        for _, tag in rest:
            if not inside_prostate(occ.getCenterOfMass(3, tag)):
                raise SystemExit(f"volume {tag} is neither tissue, prostate nor urethra")
            groups["prostate"].append(tag)
        for k, v in groups.items():
            if not v:
                raise SystemExit(f"no volume found for {k}")

        # Boundary surfaces by position.
        eps = 1e-6
        front, back, rectum_wall = [], [], []
        for dim, tag in gmsh.model.getEntities(2):
            xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(dim, tag)
            com = occ.getCenterOfMass(dim, tag)
            if ymax < eps and ymin > -eps:
                front.append(tag)
            elif ymin > ly - eps and ymax < ly + eps:
                back.append(tag)
            elif abs(((com[0] - RECTUM["x"]) ** 2 + (com[2] - RECTUM["z"]) ** 2) ** 0.5) < RECTUM["radius"] * 0.7 and (
                zmax <= RECTUM["z"] + RECTUM["radius"] + eps and ymax - ymin > ly - eps
            ):
                rectum_wall.append(tag)
        # The curved wall's centre of mass lies inside the cylinder; check by bounding box too.
        if not (front and back and rectum_wall):
            raise SystemExit(f"boundary surfaces not found: front {front} back {back} rectum_wall {rectum_wall}")

        for tag, (name, ents) in enumerate(groups.items(), start=1):
            gmsh.model.addPhysicalGroup(3, ents, tag, name)
        for tag, (name, ents) in enumerate((("rectum_wall", rectum_wall), ("back", back), ("front", front)), start=11):
            gmsh.model.addPhysicalGroup(2, ents, tag, name)

        # Sizes: fine within 5 mm of the prostate and urethra, coarse elsewhere.
        fine_surfaces = [t for _, t in gmsh.model.getBoundary([(3, v) for v in groups["prostate"] + groups["urethra"]], oriented=False)]
        dist = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(dist, "SurfacesList", fine_surfaces)
        thr = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(thr, "InField", dist)
        gmsh.model.mesh.field.setNumber(thr, "SizeMin", SIZE_FINE)
        gmsh.model.mesh.field.setNumber(thr, "SizeMax", SIZE_TISSUE)
        gmsh.model.mesh.field.setNumber(thr, "DistMin", 2 * MM)
        gmsh.model.mesh.field.setNumber(thr, "DistMax", 8 * MM)
        inside = gmsh.model.mesh.field.add("Constant")
        gmsh.model.mesh.field.setNumber(inside, "VIn", SIZE_FINE)
        gmsh.model.mesh.field.setNumber(inside, "VOut", SIZE_TISSUE)
        gmsh.model.mesh.field.setNumbers(inside, "VolumesList", groups["prostate"] + groups["urethra"])
        mn = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(mn, "FieldsList", [thr, inside])
        gmsh.model.mesh.field.setAsBackgroundMesh(mn)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.optimize("")

        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.write(out_path)

        summary = {"nodes": 0, "tetrahedra": 0, "volumes_m3": {}}
        used = set()
        for name, ents in groups.items():
            vol = 0.0
            for v in ents:
                vol += occ.getMass(3, v)
                types, _, nodes = gmsh.model.mesh.getElements(3, v)
                for t, ns in zip(types, nodes):
                    if t == 4:
                        summary["tetrahedra"] += len(ns) // 4
                        used.update(int(n) for n in ns)
            summary["volumes_m3"][name] = vol
        summary["nodes"] = len(used)
        return summary
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "brachy-3d.msh")
    print(json.dumps(build(out), indent=1))
