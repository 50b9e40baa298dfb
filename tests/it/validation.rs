//! Validation against the independent references: every shared scenario through the real `needlesim-server solve`, the closed forms included in the reference results, and new cases (an unstructured inhomogeneous mesh, a needle held in a rotated frame) solved by the Python reference solver fem_ref.py.

use std::path::{Path, PathBuf};
use std::process::Command;

use needlesim_core::MeshLimits;
use needlesim_core::msh::parse_msh;
use needlesim_tests::{
    TempDir, compare, max_rel_error, pairs, python, read_json, report_metrics, run, server_solve, text, validation_dir, write_json,
};
use serde_json::{Value, json};

/// The tolerance of the validation README: same mesh, same elements, a direct solver.
const TOL: f64 = 1e-9;

/// Solves `scenario` with the real binary into `out`; panics with its stderr on failure.
fn solve_ok(scenario: &Path, out: &Path) -> Value {
    let o = server_solve(scenario, out, &[]);
    let (_, err) = text(&o);
    assert!(o.status.success(), "needlesim-server solve {} failed ({}):\n{err}", scenario.display(), o.status);
    read_json(out)
}

/// Runs compare.py, prints its report, and returns (passed, report).
fn compare_report(reference: &Path, candidate: &Path) -> (bool, String) {
    let o = compare(reference, candidate, TOL);
    let (out, err) = text(&o);
    println!("compare.py {} {}:\n{out}{err}", reference.display(), candidate.display());
    (o.status.success(), format!("{out}{err}"))
}

/// The metrics compare.py must report for this reference, so that a key missing from our output
/// (compare.py compares only the keys the candidate has) does not pass silently.
fn expected_metrics(reference: &Value) -> Vec<&'static str> {
    let mut m = vec!["disp_rel_l2", "disp_rel_max", "reactions_rel_max", "energy_rel"];
    if reference.get("compliance").is_some() {
        m.push("compliance_rel_fro");
    }
    if reference.get("element_stresses_sxx_syy_sxy").is_some() {
        m.push("stress_rel_max");
    }
    m
}

/// Asserts that compare.py passes and reports every metric the reference allows.
fn assert_matches_reference(reference: &Path, candidate: &Path) {
    let (ok, report) = compare_report(reference, candidate);
    assert!(ok, "{} differs from {} by more than {TOL:e}:\n{report}", candidate.display(), reference.display());
    for metric in expected_metrics(&read_json(reference)) {
        assert!(report.contains(metric), "compare.py did not check {metric}: our result lacks it\n{report}");
    }
}

#[test]
fn every_scenario_matches_its_reference_result() {
    let v = validation_dir();
    let mut names: Vec<String> = std::fs::read_dir(v.join("scenarios"))
        .expect("scenarios/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| p.file_stem().expect("a file name").to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert!(!names.is_empty(), "no scenarios in {}", v.join("scenarios").display());
    let tmp = TempDir::new("scenarios");
    let mut failures = Vec::new();
    for name in &names {
        let scenario = v.join("scenarios").join(format!("{name}.json"));
        let reference = v.join("results").join(format!("{name}.result.json"));
        assert!(reference.is_file(), "scenario {name} has no reference result {}", reference.display());
        let out = tmp.join(&format!("{name}.result.json"));
        let o = server_solve(&scenario, &out, &[]);
        if !o.status.success() {
            failures.push(format!("{name}: needlesim-server solve failed ({}):\n{}", o.status, text(&o).1));
            continue;
        }
        let (ok, report) = compare_report(&reference, &out);
        if !ok {
            failures.push(format!("{name}: compare.py --tol {TOL:e} failed:\n{report}"));
        }
        for metric in expected_metrics(&read_json(&reference)) {
            if !report.contains(metric) {
                failures.push(format!("{name}: compare.py did not check {metric}: our result lacks it"));
            }
        }
    }
    assert!(failures.is_empty(), "{} of {} scenarios failed:\n{}", failures.len(), names.len(), failures.join("\n"));
}

/// Linear triangles reproduce the bar's linear displacement field exactly (to round-off), even on
/// the distorted grid of v1.
#[test]
fn uniaxial_bar_equals_the_closed_form() {
    let v = validation_dir();
    let tmp = TempDir::new("v1");
    let ours = solve_ok(&v.join("scenarios/v1_uniaxial_bar_strain.json"), &tmp.join("v1.json"));
    let exact = pairs(&read_json(&v.join("results/v1_uniaxial_bar_strain.result.json")), "exact_displacements");
    let err = max_rel_error(&pairs(&ours, "displacements"), &exact);
    println!("v1 max |u - u_exact| / max |u_exact| = {err:e}");
    assert!(err <= 1e-12, "v1 differs from the closed form by {err:e} (max abs error / max abs exact)");
}

/// The cantilever's discretisation error against Timoshenko–Goodier equals the reference's, so
/// our mesh, loads and elements are the reference's.
#[test]
fn cantilever_discretisation_error_equals_the_reference() {
    let v = validation_dir();
    let tmp = TempDir::new("v2");
    let name = "v2_timoshenko_cantilever_stress_33x9";
    let ours = pairs(&solve_ok(&v.join(format!("scenarios/{name}.json")), &tmp.join("v2.json")), "displacements");
    let reference = read_json(&v.join(format!("results/{name}.result.json")));
    let exact = pairs(&reference, "exact_displacements");
    let norm = |f: &dyn Fn(usize, usize) -> f64| (0..exact.len()).flat_map(|i| [f(i, 0), f(i, 1)]).map(|x| x * x).sum::<f64>().sqrt();
    let rel_l2 = norm(&|i, c| ours[i][c] - exact[i][c]) / norm(&|i, c| exact[i][c]);
    let expected = reference["nodal_rel_l2_error_vs_exact"].as_f64().expect("the reference states its error");
    println!("v2 nodal rel L2 error vs exact: ours {rel_l2:.15e}, reference {expected:.15e}");
    assert!((rel_l2 - expected).abs() <= 1e-6 * expected, "ours {rel_l2:e} vs reference {expected:e}");
}

/// The shared inclusion mesh as a scenario: tissue 15 kPa / ν 0.45, a 10× stiffer inclusion with
/// ν 0.3, plane strain, the bottom fixed, 2 mN downwards on each needle node, compliance of the
/// needle nodes and element stresses.
fn inclusion_scenario(msh_file: &str) -> Value {
    let path = validation_dir().join("meshes").join(msh_file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let msh = parse_msh(&text, &MeshLimits::default()).unwrap_or_else(|e| panic!("{msh_file}: {e}"));
    let mesh = &msh.mesh;
    let region =
        |name: &str| mesh.region_names().iter().position(|r| r == name).unwrap_or_else(|| panic!("{msh_file} has no region {name}"));
    let (tissue, inclusion) = (region("tissue"), region("inclusion"));
    let (e_tissue, nu_tissue, e_inclusion, nu_inclusion) = (15e3, 0.45, 150e3, 0.3);
    let mut e_elem = Vec::new();
    let mut nu_elem = Vec::new();
    for &r in mesh.region_of_tri() {
        let (e, nu) = match r {
            r if r == tissue => (e_tissue, nu_tissue),
            r if r == inclusion => (e_inclusion, nu_inclusion),
            r => panic!("{msh_file}: unexpected region {}", mesh.region_names()[r]),
        };
        e_elem.push(e);
        nu_elem.push(nu);
    }
    let n_inclusion = mesh.region_of_tri().iter().filter(|&&r| r == inclusion).count();
    assert!(n_inclusion > 10 && n_inclusion < mesh.n_triangles() / 2, "{msh_file}: {n_inclusion} inclusion triangles");
    let set = |name: &str| mesh.boundary_set(name).unwrap_or_else(|| panic!("{msh_file} has no node set {name}")).to_vec();
    let (fixed, needle) = (set("fixed_bottom"), set("needle"));
    assert!(!fixed.is_empty() && !needle.is_empty());
    let loads: Vec<Value> = needle.iter().map(|&n| json!({"node": n, "fx": 0.0, "fy": -0.002})).collect();
    json!({
        "name": format!("inclusion_{msh_file}"),
        "nodes": mesh.nodes_m(),
        "triangles": mesh.triangles(),
        "E": e_tissue,
        "nu": nu_tissue,
        "E_elem": e_elem,
        "nu_elem": nu_elem,
        "plane": "strain",
        "thickness": 1.0,
        "fixed_nodes": fixed,
        "loads": loads,
        "working_nodes": needle,
        "output_stresses": true,
    })
}

/// Runs fem_ref.py on a scenario; returns the reference result's path.
fn reference_solve(scenario: &Path, out: PathBuf) -> PathBuf {
    let script = validation_dir().join("fem_ref.py");
    let o = run(Command::new(python()).arg(&script).arg(scenario).arg(&out));
    let (stdout, stderr) = text(&o);
    println!("fem_ref.py: {stdout}{stderr}");
    assert!(o.status.success(), "fem_ref.py {} failed ({}):\n{stdout}{stderr}", scenario.display(), o.status);
    // The reference checks itself against a second, plain-numpy assembly.
    let cross = read_json(&out)["cross_check"]["u_rel_l2_diff_skfem_vs_numpy"].as_f64().expect("fem_ref cross check");
    assert!(cross < 1e-10, "the reference's own assemblies disagree by {cross:e}");
    out
}

#[test]
fn inclusion_mesh_matches_the_reference_solver_in_both_msh_versions() {
    let tmp = TempDir::new("inclusion");
    let scenario41 = tmp.join("inclusion_v41.json");
    write_json(&scenario41, &inclusion_scenario("inclusion_v41.msh"));
    let reference = reference_solve(&scenario41, tmp.join("inclusion_v41.ref.json"));
    let ours41 = tmp.join("inclusion_v41.result.json");
    let u41 = pairs(&solve_ok(&scenario41, &ours41), "displacements");
    assert_matches_reference(&reference, &ours41);

    let scenario22 = tmp.join("inclusion_v22.json");
    write_json(&scenario22, &inclusion_scenario("inclusion_v22.msh"));
    let u22 = pairs(&solve_ok(&scenario22, &tmp.join("inclusion_v22.result.json")), "displacements");
    let diff = max_rel_error(&u22, &u41);
    println!("MSH 2.2 vs 4.1 displacements: max rel diff {diff:e}");
    assert!(diff <= 1e-14, "the MSH 2.2 and 4.1 files give different displacements: {diff:e}");
}

/// A needle held in a rotated frame (`prescribed_local`), the path the shared scenarios do not
/// cover: on the 19 × 19 paper mesh, a needle at −45° through six grid nodes, the shaft with its
/// normal displacement prescribed and an axial load (slipping), the tip stuck (both prescribed).
#[test]
fn needle_in_a_rotated_frame_matches_the_reference_solver() {
    let v = validation_dir();
    let base = read_json(&v.join("scenarios/s1_paper19x19_strain.json"));
    let nodes = pairs(&base, "nodes");
    let h = 0.1 / 18.0;
    let node_at = |x: f64, y: f64| {
        nodes.iter().position(|p| (p[0] - x).abs() < 1e-9 && (p[1] - y).abs() < 1e-9).unwrap_or_else(|| panic!("no node at ({x}, {y})"))
    };
    let angle = -std::f64::consts::FRAC_PI_4;
    let (s, c) = angle.sin_cos();
    let needle: Vec<usize> = (0..6).map(|k| node_at((6 + k) as f64 * h, (18 - k) as f64 * h)).collect();
    let mut held = Vec::new();
    let mut loads = Vec::new();
    for (k, &n) in needle.iter().enumerate() {
        let un = 2e-4 * k as f64 / 5.0;
        if k + 1 < needle.len() {
            held.push(json!({"node": n, "angle_rad": angle, "un": un}));
            let ft = 0.002;
            loads.push(json!({"node": n, "fx": ft * c, "fy": ft * s}));
        } else {
            held.push(json!({"node": n, "angle_rad": angle, "ut": 1e-3, "un": un}));
        }
    }
    let scenario = json!({
        "name": "needle_rotated_frame_19x19",
        "nodes": base["nodes"],
        "triangles": base["triangles"],
        "E": 15e3,
        "nu": 0.45,
        "plane": "strain",
        "fixed_nodes": base["fixed_nodes"],
        "prescribed_local": held,
        "loads": loads,
        "working_nodes": needle,
        "output_stresses": true,
    });
    let tmp = TempDir::new("rotated");
    let path = tmp.join("needle.json");
    write_json(&path, &scenario);
    let reference = reference_solve(&path, tmp.join("needle.ref.json"));
    let ours_path = tmp.join("needle.result.json");
    let ours = solve_ok(&path, &ours_path);
    assert_matches_reference(&reference, &ours_path);

    // compare.py does not look at reactions_local: the needle's reactions in its own frame.
    let local = |r: &Value| -> Vec<(u64, [Option<f64>; 2])> {
        r["reactions_local"]
            .as_array()
            .expect("reactions_local is given for prescribed_local nodes")
            .iter()
            .map(|e| (e["node"].as_u64().expect("a node id"), [e["rt"].as_f64(), e["rn"].as_f64()]))
            .collect()
    };
    let (got, want) = (local(&ours), local(&read_json(&reference)));
    assert_eq!(got.len(), needle.len());
    assert_eq!(
        got.iter().map(|e| (e.0, e.1.map(|r| r.is_some()))).collect::<Vec<_>>(),
        want.iter().map(|e| (e.0, e.1.map(|r| r.is_some()))).collect::<Vec<_>>()
    );
    let values = |l: &[(u64, [Option<f64>; 2])]| l.iter().flat_map(|e| e.1.into_iter().flatten()).collect::<Vec<f64>>();
    let (g, w) = (values(&got), values(&want));
    let scale = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let err = g.iter().zip(&w).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / scale;
    println!("reactions_local: max rel diff {err:e} over {} components", w.len());
    assert!(scale > 0.0 && err <= TOL, "reactions_local differ from the reference by {err:e}");
}

// ---------------------------------------------------------------------------------------------
// 3D (README "3D scenario format"): P1 tetrahedra, material points, fem_ref3d.py.
// ---------------------------------------------------------------------------------------------

/// The tolerance of the validation README for 3D point reactions (a saddle-point solve).
const TOL_POINT_REACTIONS: f64 = 1e-8;

/// The `[[x, y, z], …]` array of `key`, as triples.
fn triples(value: &Value, key: &str) -> Vec<[f64; 3]> {
    let arr = value[key].as_array().unwrap_or_else(|| panic!("`{key}` is not an array"));
    arr.iter()
        .map(|p| {
            let f = |i: usize| p[i].as_f64().unwrap_or_else(|| panic!("`{key}` holds a non-number: {p}"));
            [f(0), f(1), f(2)]
        })
        .collect()
}

/// `max |a - b| / max |b|` over all components.
fn max_rel_error3(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len(), "different numbers of nodes");
    let err = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs())).fold(0.0, f64::max);
    let scale = b.iter().flat_map(|q| q.iter().map(|v| v.abs())).fold(0.0, f64::max);
    assert!(scale > 0.0, "the reference field is zero");
    err / scale
}

/// The metrics compare.py must report for a 3D reference.
fn expected_metrics3(reference: &Value) -> Vec<&'static str> {
    let mut m = vec!["disp_rel_l2", "disp_rel_max", "reactions_rel_max", "energy_rel"];
    for (key, metric) in [
        ("compliance", "compliance_rel_fro"),
        ("element_stresses_voigt", "stress_rel_max"),
        ("point_reactions", "point_reactions_rel_max"),
        ("point_compliance", "point_compliance_rel_fro"),
    ] {
        if reference.get(key).is_some() {
            m.push(metric);
        }
    }
    m
}

/// compare.py over a 3D result: every metric the reference allows is reported, within 1e-9, and
/// the point reactions within 1e-8. Returns the failures (empty when it passes).
fn check_against_reference3(reference: &Path, candidate: &Path) -> Vec<String> {
    // compare.py applies one tolerance to every metric: run it at the point-reaction tolerance and
    // hold every other metric to TOL here.
    let o = compare(reference, candidate, TOL_POINT_REACTIONS);
    let (out, err) = text(&o);
    println!("compare.py {} {}:\n{out}{err}", reference.display(), candidate.display());
    let mut failures = Vec::new();
    if !o.status.success() {
        failures.push(format!("compare.py --tol {TOL_POINT_REACTIONS:e} failed:\n{out}{err}"));
    }
    let metrics = report_metrics(&out);
    for metric in expected_metrics3(&read_json(reference)) {
        match metrics.iter().find(|(n, _)| n == metric) {
            None => failures.push(format!("compare.py did not check {metric}: our result lacks it")),
            Some((_, v)) => {
                let tol = if metric == "point_reactions_rel_max" { TOL_POINT_REACTIONS } else { TOL };
                if v.is_nan() || *v > tol {
                    failures.push(format!("{metric} = {v:e} exceeds {tol:e}"));
                }
            }
        }
    }
    failures
}

/// The frame components of `reactions_local` / `point_reactions` agree with the reference (compare.py
/// does not look at them): same components given, values within `tol` of the largest.
fn assert_frame_components_match(ours: &Value, reference: &Value, key: &str, id: &str, tol: f64) {
    let get = |r: &Value| -> Vec<(u64, [Option<f64>; 3])> {
        r[key]
            .as_array()
            .unwrap_or_else(|| panic!("{key} is missing"))
            .iter()
            .map(|e| (e[id].as_u64().expect("an id"), [e["rt"].as_f64(), e["rn"].as_f64(), e["rb"].as_f64()]))
            .collect()
    };
    let (got, want) = (get(ours), get(reference));
    assert_eq!(
        got.iter().map(|e| (e.0, e.1.map(|r| r.is_some()))).collect::<Vec<_>>(),
        want.iter().map(|e| (e.0, e.1.map(|r| r.is_some()))).collect::<Vec<_>>(),
        "{key}: the same components are given"
    );
    let values = |l: &[(u64, [Option<f64>; 3])]| l.iter().flat_map(|e| e.1.into_iter().flatten()).collect::<Vec<f64>>();
    let (g, w) = (values(&got), values(&want));
    let scale = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let err = g.iter().zip(&w).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / scale;
    println!("{key} frame components: max rel diff {err:e} over {} components", w.len());
    assert!(scale > 0.0 && err <= tol, "{key} frame components differ from the reference by {err:e}");
}

#[test]
fn every_3d_scenario_matches_its_reference_result() {
    let v = validation_dir();
    let mut names: Vec<String> = std::fs::read_dir(v.join("scenarios3d"))
        .expect("scenarios3d/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| p.file_stem().expect("a file name").to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert!(names.len() >= 3, "expected the 3D scenarios in {}", v.join("scenarios3d").display());
    let tmp = TempDir::new("scenarios3d");
    let mut failures = Vec::new();
    for name in &names {
        let scenario = v.join("scenarios3d").join(format!("{name}.json"));
        let reference = v.join("results3d").join(format!("{name}.result.json"));
        assert!(reference.is_file(), "scenario {name} has no reference result {}", reference.display());
        let out = tmp.join(&format!("{name}.result.json"));
        let o = server_solve(&scenario, &out, &[]);
        if !o.status.success() {
            failures.push(format!("{name}: needlesim-server solve failed ({}):\n{}", o.status, text(&o).1));
            continue;
        }
        failures.extend(check_against_reference3(&reference, &out).into_iter().map(|f| format!("{name}: {f}")));
        let (ours, want) = (read_json(&out), read_json(&reference));
        if want.get("point_reactions").is_some() {
            assert_frame_components_match(&ours, &want, "point_reactions", "point", TOL_POINT_REACTIONS);
        }
    }
    assert!(failures.is_empty(), "{} of {} 3D scenarios failed:\n{}", failures.len(), names.len(), failures.join("\n"));
}

/// Linear tetrahedra reproduce the bar's linear field exactly (to round-off) on distorted tets.
#[test]
fn uniaxial_bar_3d_equals_the_closed_form() {
    let v = validation_dir();
    let tmp = TempDir::new("v3");
    let ours = solve_ok(&v.join("scenarios3d/v3_uniaxial_bar_3d.json"), &tmp.join("v3.json"));
    let exact = triples(&read_json(&v.join("results3d/v3_uniaxial_bar_3d.result.json")), "exact_displacements");
    let err = max_rel_error3(&triples(&ours, "displacements"), &exact);
    println!("v3 max |u - u_exact| / max |u_exact| = {err:e}");
    assert!(err <= 1e-12, "v3 differs from the closed form by {err:e} (max abs error / max abs exact)");
}

/// The s3d2 scenario with its mesh, regions and fixed nodes taken from a Gmsh file.
fn cube_sphere_scenario(msh_file: &str) -> Value {
    use needlesim_core::d3::TetMeshLimits;
    use needlesim_core::msh::parse_msh3d;
    let v = validation_dir();
    let path = v.join("meshes").join(msh_file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let msh = parse_msh3d(&text, &TetMeshLimits::default()).unwrap_or_else(|e| panic!("{msh_file}: {e}"));
    let mesh = &msh.mesh;
    let lesion = mesh.region_names().iter().position(|r| r == "lesion").expect("a lesion region");
    assert!(mesh.region_names().iter().any(|r| r == "tissue"), "a tissue region");
    let mut sc = read_json(&v.join("scenarios3d/s3d2_gmsh_cube_sphere.json"));
    let e = sc["E"].as_f64().expect("E");
    let e_elem: Vec<f64> = mesh.region_of_tet().iter().map(|&r| if r == lesion { 10.0 * e } else { e }).collect();
    let bottom = mesh.boundary_set("bottom").expect("a bottom surface").to_vec();
    assert!(bottom.iter().all(|&n| mesh.nodes_m()[n][2].abs() < 1e-12));
    let obj = sc.as_object_mut().expect("an object");
    obj.insert("name".into(), json!(format!("cube_sphere_{msh_file}")));
    obj.insert("nodes".into(), json!(mesh.nodes_m()));
    obj.insert("tetrahedra".into(), json!(mesh.tets()));
    obj.insert("E_elem".into(), json!(e_elem));
    obj.insert("fixed_nodes".into(), json!(bottom));
    sc
}

/// The Gmsh cube with a lesion read from MSH 4.1 and 2.2 is s3d2's mesh (nodes, tetrahedra,
/// lesion, fixed bottom), and both files give the reference result.
#[test]
fn gmsh_cube_sphere_in_both_msh_versions_gives_the_s3d2_result() {
    let v = validation_dir();
    let s3d2 = read_json(&v.join("scenarios3d/s3d2_gmsh_cube_sphere.json"));
    let reference = v.join("results3d/s3d2_gmsh_cube_sphere.result.json");
    let tmp = TempDir::new("cube_sphere");
    let mut displacements = Vec::new();
    for file in ["cube_sphere_v41.msh", "cube_sphere_v22.msh"] {
        let sc = cube_sphere_scenario(file);
        assert_eq!(sc["nodes"], s3d2["nodes"], "{file}: the nodes are s3d2's");
        assert_eq!(sc["tetrahedra"], s3d2["tetrahedra"], "{file}: the tetrahedra are s3d2's");
        assert_eq!(sc["E_elem"], s3d2["E_elem"], "{file}: the lesion is s3d2's");
        let mut fixed: Vec<u64> = s3d2["fixed_nodes"].as_array().unwrap().iter().map(|n| n.as_u64().unwrap()).collect();
        fixed.sort_unstable();
        assert_eq!(sc["fixed_nodes"], json!(fixed), "{file}: the bottom is s3d2's fixed set");
        let path = tmp.join(&format!("{file}.json"));
        write_json(&path, &sc);
        let out = tmp.join(&format!("{file}.result.json"));
        displacements.push(triples(&solve_ok(&path, &out), "displacements"));
        let failures = check_against_reference3(&reference, &out);
        assert!(failures.is_empty(), "{file}:\n{}", failures.join("\n"));
    }
    let diff = max_rel_error3(&displacements[1], &displacements[0]);
    println!("MSH 2.2 vs 4.1 displacements: max rel diff {diff:e}");
    assert!(diff <= 1e-14, "the MSH 2.2 and 4.1 files give different displacements: {diff:e}");
}

/// Runs fem_ref3d.py on a scenario; returns the reference result's path.
fn reference_solve3(scenario: &Path, out: PathBuf) -> PathBuf {
    let script = validation_dir().join("fem_ref3d.py");
    let o = run(Command::new(python()).arg(&script).arg(scenario).arg(&out));
    let (stdout, stderr) = text(&o);
    println!("fem_ref3d.py: {stdout}{stderr}");
    assert!(o.status.success(), "fem_ref3d.py {} failed ({}):\n{stdout}{stderr}", scenario.display(), o.status);
    let cross = read_json(&out)["cross_check"]["u_rel_l2_diff_skfem_vs_numpy"].as_f64().expect("fem_ref3d cross check");
    assert!(cross < 1e-10, "the reference's own assemblies disagree by {cross:e}");
    out
}

/// An orthonormal frame `[t, n, b]` with `t` along `dir`.
fn frame_along(dir: [f64; 3]) -> [[f64; 3]; 3] {
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let scale = |v: [f64; 3], s: f64| v.map(|x| x * s);
    let t = scale(dir, 1.0 / norm(dir));
    let helper = if t[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let d = helper[0] * t[0] + helper[1] * t[1] + helper[2] * t[2];
    let n = [helper[0] - d * t[0], helper[1] - d * t[1], helper[2] - d * t[2]];
    let n = scale(n, 1.0 / norm(n));
    let b = [t[1] * n[2] - t[2] * n[1], t[2] * n[0] - t[0] * n[2], t[0] * n[1] - t[1] * n[0]];
    [t, n, b]
}

/// A tilted needle of material points from `entry` along `dir` (unit), `count` points
/// `spacing_m` apart; the two deepest stuck, the rest slipping with 15 mN of friction along t.
fn needle_points(entry: [f64; 3], dir: [f64; 3], count: usize, spacing_m: f64) -> (Vec<Value>, Vec<[f64; 3]>) {
    let frame = frame_along(dir);
    let t = frame[0];
    let mut points = Vec::new();
    let mut xs = Vec::new();
    for k in 0..count {
        let s = spacing_m * (k as f64 + 0.5);
        let x = [entry[0] + s * t[0], entry[1] + s * t[1], entry[2] + s * t[2]];
        let (un, ub) = (4e-4 * k as f64 / count as f64, -1e-4);
        let p = if k + 2 >= count {
            json!({"x": x, "frame": frame, "ut": 6e-4, "un": un, "ub": ub})
        } else {
            json!({"x": x, "frame": frame, "un": un, "ub": ub, "f": t.map(|c| 0.015 * c)})
        };
        points.push(p);
        xs.push(x);
    }
    (points, xs)
}

/// An inhomogeneous box grid from our own builder (a stiff spherical inclusion and a stiffer,
/// less compressible top layer, per-element E and ν), the bottom fixed, a side node with world
/// components, three top nodes held in a tilted frame (one stuck, two slipping with an axial
/// load), nodal loads, and a tilted needle of material points (stuck and slipping) — against
/// fem_ref3d.py, solved at run time.
#[test]
fn inhomogeneous_box_with_a_tilted_needle_matches_the_reference_solver() {
    use needlesim_core::d3::{BoxGridParams, TetMeshLimits};
    let grid = BoxGridParams::new([7, 6, 8], [0.1, 0.08, 0.12]);
    let mesh = grid.build(&TetMeshLimits::default()).expect("the box grid builds");
    let (mut e_elem, mut nu_elem) = (Vec::new(), Vec::new());
    for t in 0..mesh.n_tets() {
        let c = mesh.tet_points_m(t).iter().fold([0.0; 3], |a, p| [a[0] + p[0] / 4.0, a[1] + p[1] / 4.0, a[2] + p[2] / 4.0]);
        let r2 = (c[0] - 0.05).powi(2) + (c[1] - 0.04).powi(2) + (c[2] - 0.05).powi(2);
        let (e, nu) = if r2 < 0.02f64.powi(2) {
            (120e3, 0.3)
        } else if c[2] > 0.1 {
            (40e3, 0.35)
        } else {
            (15e3, 0.45)
        };
        e_elem.push(e);
        nu_elem.push(nu);
    }
    assert!(e_elem.iter().filter(|&&e| e == 120e3).count() > 10, "the inclusion has elements");
    let top = mesh.boundary_set("top").expect("a top set");
    let tilt = frame_along([0.3, -0.2, -1.0]);
    let held = [top[3], top[10], top[17]];
    let prescribed_local: Vec<Value> = held
        .iter()
        .enumerate()
        .map(|(k, &n)| {
            if k == 0 {
                json!({"node": n, "frame": tilt, "ut": 5e-4, "un": 1e-4, "ub": -2e-4})
            } else {
                json!({"node": n, "frame": tilt, "un": 1e-4 * k as f64, "ub": 0.0})
            }
        })
        .collect();
    let mut loads: Vec<Value> =
        held[1..].iter().map(|&n| json!({"node": n, "fx": 0.01 * tilt[0][0], "fy": 0.01 * tilt[0][1], "fz": 0.01 * tilt[0][2]})).collect();
    loads.push(json!({"node": grid.node(6, 3, 4), "fx": -0.02, "fy": 0.005, "fz": 0.0}));
    loads.push(json!({"node": grid.node(6, 3, 4), "fx": -0.01, "fy": 0.0, "fz": 0.003}));
    let (points, xs) = needle_points([0.047, 0.041, 0.12], [0.25, 0.15, -1.0], 6, 0.016);
    let scenario = json!({
        "name": "box_inclusion_tilted_needle",
        "dim": 3,
        "nodes": mesh.nodes_m(),
        "tetrahedra": mesh.tets(),
        "E": 15e3,
        "nu": 0.45,
        "E_elem": e_elem,
        "nu_elem": nu_elem,
        "fixed_nodes": mesh.boundary_set("bottom").expect("a bottom set"),
        "prescribed": [{"node": grid.node(0, 2, 5), "ux": 2e-4}, {"node": grid.node(0, 2, 5), "uz": -1e-4}],
        "prescribed_local": prescribed_local,
        "loads": loads,
        "points": points,
        "working_nodes": held,
        "working_points": xs,
        "output_stresses": true,
    });
    let tmp = TempDir::new("box3d");
    let path = tmp.join("box.json");
    write_json(&path, &scenario);
    let reference = reference_solve3(&path, tmp.join("box.ref.json"));
    let ours_path = tmp.join("box.result.json");
    let ours = solve_ok(&path, &ours_path);
    let failures = check_against_reference3(&reference, &ours_path);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let want = read_json(&reference);
    assert_frame_components_match(&ours, &want, "reactions_local", "node", TOL);
    assert_frame_components_match(&ours, &want, "point_reactions", "point", TOL_POINT_REACTIONS);
    // The points' displacements u(x).
    let u = |r: &Value| {
        r["point_reactions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| {
                let f = |i: usize| e["u"][i].as_f64().unwrap();
                [f(0), f(1), f(2)]
            })
            .collect::<Vec<_>>()
    };
    let err = max_rel_error3(&u(&ours), &u(&want));
    println!("point displacements: max rel diff {err:e}");
    assert!(err <= TOL, "point displacements differ by {err:e}");
}

/// The Gmsh cube with its lesion, a needle tilted through the lesion's side (material points,
/// stuck and slipping), a top node in a tilted frame and loads — against fem_ref3d.py.
#[test]
fn gmsh_cube_with_a_tilted_needle_matches_the_reference_solver() {
    let mut sc = cube_sphere_scenario("cube_sphere_v22.msh");
    let nodes = triples(&sc, "nodes");
    let top: Vec<usize> = (0..nodes.len()).filter(|&i| (nodes[i][2] - 0.1).abs() < 1e-12).collect();
    let tilt = frame_along([-0.2, 0.1, -1.0]);
    let (points, xs) = needle_points([0.058, 0.047, 0.1], [-0.2, 0.1, -1.0], 7, 0.008);
    let obj = sc.as_object_mut().expect("an object");
    obj.insert("name".into(), json!("cube_sphere_tilted_needle"));
    obj.insert("points".into(), json!(points));
    obj.insert("working_points".into(), json!(xs));
    obj.insert("prescribed_local".into(), json!([{"node": top[5], "frame": tilt, "un": 2e-4, "ub": 1e-4}]));
    obj.insert("loads".into(), json!([{"node": top[9], "fx": 0.0, "fy": 0.01, "fz": -0.02}]));
    obj.insert("working_nodes".into(), json!([top[5], top[9]]));
    let tmp = TempDir::new("cube3d");
    let path = tmp.join("cube.json");
    write_json(&path, &sc);
    let reference = reference_solve3(&path, tmp.join("cube.ref.json"));
    let ours_path = tmp.join("cube.result.json");
    let ours = solve_ok(&path, &ours_path);
    let failures = check_against_reference3(&reference, &ours_path);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let want = read_json(&reference);
    assert_frame_components_match(&ours, &want, "reactions_local", "node", TOL);
    assert_frame_components_match(&ours, &want, "point_reactions", "point", TOL_POINT_REACTIONS);
}

/// The disc weights of two results, as node → weight maps per disc.
fn disc_weights(r: &Value) -> Vec<std::collections::BTreeMap<u64, f64>> {
    r["disc_weights"]
        .as_array()
        .unwrap_or_else(|| panic!("no disc_weights in the result"))
        .iter()
        .map(|d| {
            let nodes = d["nodes"].as_array().expect("nodes").iter().map(|v| v.as_u64().expect("a node"));
            nodes.zip(d["weights"].as_array().expect("weights").iter().map(|v| v.as_f64().expect("a weight"))).collect()
        })
        .collect()
}

/// Issue 37 (item 7): `solve` takes the `discs` of the validation format. The reference integrates
/// a disc by a polar quadrature (about 1e-4); ours integrates exactly (`d3::disc`): the result
/// within 1e-3 of the reference's, the weights on the same nodes within 1e-4, and the reactions
/// named by kind and index.
#[test]
fn issue_37_solve_takes_discs_within_the_references_quadrature() {
    let v = validation_dir();
    let name = "s3d3_cube_oblique_needle_discs";
    let scenario = v.join("scenarios3d_spread").join(format!("{name}.json"));
    let reference = v.join("results3d_spread").join(format!("{name}.result.json"));
    let tmp = TempDir::new("discs3d");
    let out = tmp.join("discs.result.json");
    let ours = solve_ok(&scenario, &out);
    let o = compare(&reference, &out, 1e-3);
    let (report, err) = text(&o);
    println!("compare.py --tol 1e-3:\n{report}{err}");
    assert!(o.status.success(), "the disc scenario differs from the reference beyond its quadrature:\n{report}{err}");
    let metrics = report_metrics(&report);
    for metric in expected_metrics3(&read_json(&reference)) {
        assert!(metrics.iter().any(|(n, _)| n == metric), "compare.py did not check {metric}:\n{report}");
    }
    let want = read_json(&reference);
    let (got_w, want_w) = (disc_weights(&ours), disc_weights(&want));
    assert_eq!(got_w.len(), want_w.len(), "one weight set per disc");
    let mut worst = 0.0f64;
    for (j, (g, w)) in got_w.iter().zip(&want_w).enumerate() {
        assert_eq!(g.keys().collect::<Vec<_>>(), w.keys().collect::<Vec<_>>(), "disc {j}: the same nodes");
        let sum: f64 = g.values().sum();
        assert!((sum - 1.0).abs() < 1e-12, "disc {j}: weights sum to {sum}");
        worst = g.iter().fold(worst, |m, (k, x)| m.max((x - w[k]).abs()));
    }
    println!("disc weights: max |w − w_ref| = {worst:e}");
    assert!(worst < 1e-4, "disc weights differ from the reference's quadrature by {worst:e}");
    let reactions = ours["point_reactions"].as_array().expect("point reactions");
    assert_eq!(reactions.len(), got_w.len());
    for (j, r) in reactions.iter().enumerate() {
        assert_eq!((r["kind"].as_str(), r["index"].as_u64()), (Some("disc"), Some(j as u64)), "{r}");
    }
}

/// Issue 37 (item 7): `patches` (explicit weights) re-solve to round-off: the reference's own disc
/// weights written as patches give the reference's answer to 1e-9 (point reactions 1e-8), and a
/// patch problem of our own (two patches sharing nodes, a load, a frame node) matches fem_ref3d.py.
#[test]
fn issue_37_solve_takes_patches_to_round_off() {
    let v = validation_dir();
    let name = "s3d3_cube_oblique_needle_discs";
    let mut sc = read_json(&v.join("scenarios3d_spread").join(format!("{name}.json")));
    let reference = v.join("results3d_spread").join(format!("{name}.result.json"));
    let want = read_json(&reference);
    let discs = sc["discs"].as_array().expect("discs").clone();
    let patches: Vec<Value> = discs
        .iter()
        .zip(want["disc_weights"].as_array().expect("disc_weights"))
        .map(|(d, w)| {
            let mut p = d.as_object().expect("a disc").clone();
            for k in ["x", "axis", "radius"] {
                p.remove(k);
            }
            p.insert("nodes".into(), w["nodes"].clone());
            p.insert("weights".into(), w["weights"].clone());
            Value::Object(p)
        })
        .collect();
    let obj = sc.as_object_mut().expect("an object");
    obj.remove("discs");
    obj.insert("patches".into(), json!(patches));
    let tmp = TempDir::new("patches3d");
    let path = tmp.join("patches.json");
    write_json(&path, &sc);
    let out = tmp.join("patches.result.json");
    let ours = solve_ok(&path, &out);
    let failures = check_against_reference3(&reference, &out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_frame_components_match(&ours, &want, "point_reactions", "point", TOL_POINT_REACTIONS);
    for (j, r) in ours["point_reactions"].as_array().expect("point reactions").iter().enumerate() {
        assert_eq!((r["kind"].as_str(), r["index"].as_u64()), (Some("patch"), Some(j as u64)), "{r}");
    }

    // Our own: a box, points and patches together (patches sharing a node), a load, against fem_ref3d.py.
    let grid = needlesim_core::d3::BoxGridParams::new([5, 5, 5], [0.04, 0.04, 0.04]);
    let mesh = grid.build(&needlesim_core::d3::TetMeshLimits::default()).expect("a box");
    let bottom: Vec<usize> = (0..mesh.n_nodes()).filter(|&i| mesh.nodes_m()[i][2] < 1e-12).collect();
    let frame = frame_along([0.1, -0.2, -1.0]);
    let patch = |nodes: [usize; 3], weights: [f64; 3], extra: Value| {
        let mut p = json!({"nodes": nodes, "weights": weights, "frame": frame});
        p.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        p
    };
    let sc = json!({
        "name": "box_patches", "dim": 3,
        "nodes": mesh.nodes_m(), "tetrahedra": mesh.tets(), "E": 5000.0, "nu": 0.45,
        "fixed_nodes": bottom,
        "points": [{"x": [0.021, 0.018, 0.035], "frame": frame, "ut": -1e-4, "un": 0.0, "ub": 0.0}],
        "patches": [
            patch([grid.node(2, 2, 3), grid.node(3, 2, 3), grid.node(2, 3, 3)], [0.5, 0.3, 0.2], json!({"un": 5e-5, "ub": -2e-5, "f": [0.0, 0.0, -0.01]})),
            patch([grid.node(2, 2, 3), grid.node(2, 2, 2), grid.node(1, 2, 2)], [0.2, 0.6, 0.2], json!({"ut": 2e-5})),
        ],
        "loads": [{"node": grid.node(4, 4, 4), "fx": 0.01, "fy": 0.0, "fz": 0.0}],
        "output_stresses": true,
    });
    let path = tmp.join("box_patches.json");
    write_json(&path, &sc);
    let reference = reference_solve3(&path, tmp.join("box_patches.ref.json"));
    let out = tmp.join("box_patches.result.json");
    let ours = solve_ok(&path, &out);
    let failures = check_against_reference3(&reference, &out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_frame_components_match(&ours, &read_json(&reference), "point_reactions", "point", TOL_POINT_REACTIONS);
    let kinds: Vec<_> = ours["point_reactions"].as_array().unwrap().iter().map(|r| (r["kind"].clone(), r["index"].clone())).collect();
    assert_eq!(kinds, vec![(json!("point"), json!(0)), (json!("patch"), json!(0)), (json!("patch"), json!(1))]);
}
