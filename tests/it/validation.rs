//! Validation against the independent references: every shared scenario through the real `needlesim-server solve`, the closed forms included in the reference results, and new cases (an unstructured inhomogeneous mesh, a needle held in a rotated frame) solved by the Python reference solver fem_ref.py.

use std::path::{Path, PathBuf};
use std::process::Command;

use needlesim_core::MeshLimits;
use needlesim_core::msh::parse_msh;
use needlesim_tests::{TempDir, compare, max_rel_error, pairs, python, read_json, run, server_solve, text, validation_dir, write_json};
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
