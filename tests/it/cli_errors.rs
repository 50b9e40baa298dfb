//! Bad input to the real `needlesim-server solve`: each gets a clear one-line error naming the offending item, exit code 1, no panic and no result file.

use std::path::Path;

use needlesim_tests::{TempDir, pairs, read_json, repo_root, server_solve, text, validation_dir, write_json};
use serde_json::{Value, json};

/// Two triangles on the unit square, bottom fixed, a load on a top corner.
fn square() -> Value {
    json!({
        "nodes": [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        "triangles": [[0, 1, 2], [0, 2, 3]],
        "E": 1000.0,
        "nu": 0.3,
        "plane": "strain",
        "fixed_nodes": [0, 1],
        "loads": [{"node": 2, "fx": 0.0, "fy": -1.0}],
    })
}

/// Writes `contents` to a scenario file, solves it with `args` before `solve`, and asserts a
/// clean failure whose stderr contains every string of `expected`.
fn assert_rejected_text(case: &str, contents: &str, args: &[&str], expected: &[&str]) -> String {
    let tmp = TempDir::new("cli");
    let scenario = tmp.join(&format!("{case}.json"));
    std::fs::write(&scenario, contents).expect("the scenario is written");
    assert_rejected_path(case, &scenario, args, expected)
}

fn assert_rejected(case: &str, scenario: &Value, expected: &[&str]) -> String {
    assert_rejected_text(case, &scenario.to_string(), &[], expected)
}

fn assert_rejected_path(case: &str, scenario: &Path, args: &[&str], expected: &[&str]) -> String {
    let out_dir = TempDir::new("cli-out");
    let result = out_dir.join("result.json");
    let o = server_solve(scenario, &result, args);
    let (stdout, stderr) = text(&o);
    println!("{case}: {}", stderr.trim());
    assert_eq!(o.status.code(), Some(1), "{case}: expected exit code 1, got {}\nstderr: {stderr}", o.status);
    assert!(!stderr.contains("panicked"), "{case}: the server panicked:\n{stderr}");
    assert!(!result.exists(), "{case}: a result was written despite the error");
    assert!(stdout.trim().is_empty(), "{case}: unexpected output on stdout: {stdout}");
    let line = stderr.lines().find(|l| l.starts_with("error: ")).unwrap_or_else(|| panic!("{case}: no `error: ` line in:\n{stderr}"));
    for e in expected {
        assert!(line.contains(e), "{case}: the error does not mention {e:?}:\n{line}");
    }
    line.to_owned()
}

fn with(mut base: Value, key: &str, value: Value) -> Value {
    base[key] = value;
    base
}

#[test]
fn the_valid_square_solves() {
    // The baseline every case below breaks in one place.
    let tmp = TempDir::new("cli-ok");
    let (scenario, result) = (tmp.join("ok.json"), tmp.join("ok.result.json"));
    std::fs::write(&scenario, square().to_string()).unwrap();
    let o = server_solve(&scenario, &result, &[]);
    assert!(o.status.success(), "{}", text(&o).1);
    let u = pairs(&read_json(&result), "displacements");
    assert!(u[2][1] < 0.0, "the loaded corner moves down: {u:?}");
}

#[test]
fn out_of_range_node_in_a_triangle() {
    let sc = with(square(), "triangles", json!([[0, 1, 2], [0, 2, 7]]));
    assert_rejected("out_of_range", &sc, &["triangle 1", "node 7", "only 4 nodes"]);
    let sc = with(square(), "triangles", json!([[0, 1, 2], [0, -2, 3]]));
    assert_rejected("negative_id", &sc, &["triangles[1]", "node -2"]);
}

#[test]
fn repeated_node_in_a_triangle() {
    let sc = with(square(), "triangles", json!([[0, 1, 2], [0, 2, 2]]));
    assert_rejected("repeated", &sc, &["triangle 1 uses node 2 twice"]);
}

#[test]
fn degenerate_triangle() {
    let mut sc = square();
    sc["nodes"].as_array_mut().unwrap().push(json!([2.0, 2.0]));
    sc["triangles"].as_array_mut().unwrap().push(json!([0, 2, 4]));
    assert_rejected("degenerate", &sc, &["triangle 2", "nodes [0, 2, 4]", "degenerate"]);
}

#[test]
fn non_finite_coordinate() {
    // JSON has no NaN or Infinity; 1e999 is how an infinite value arrives.
    let sc = square().to_string().replace("[1.0,1.0]", "[1e999,1.0]");
    assert!(sc.contains("1e999"), "{sc}");
    assert_rejected_text("non_finite", &sc, &[], &["node 2", "must be finite", "line 1"]);
}

#[test]
fn young_modulus_must_be_positive() {
    assert_rejected("e_zero", &with(square(), "E", json!(0.0)), &["Young's modulus E = 0 Pa", "> 0"]);
    assert_rejected("e_negative", &with(square(), "E", json!(-5.0)), &["Young's modulus E = -5 Pa", "> 0"]);
    let sc = with(square(), "E_elem", json!([1000.0, -3.0]));
    assert_rejected("e_elem_negative", &sc, &["element 1", "E = -3 Pa"]);
}

#[test]
fn poisson_ratio_must_be_in_range() {
    assert_rejected("nu_high", &with(square(), "nu", json!(0.6)), &["Poisson ratio ν = 0.6", "(−1, 0.5)"]);
    assert_rejected("nu_minus_one", &with(square(), "nu", json!(-1.0)), &["Poisson ratio ν = -1", "(−1, 0.5)"]);
    let stress = with(with(square(), "plane", json!("stress")), "nu", json!(0.7));
    assert_rejected("nu_high_stress", &stress, &["ν = 0.7", "(−1, 0.5] in plane stress"]);
}

#[test]
fn incompressible_is_rejected_in_plane_strain_only() {
    let strain = with(square(), "nu", json!(0.5));
    assert_rejected("nu_half_strain", &strain, &["ν = 0.5", "plane strain", "incompressible"]);
    // A thin incompressible sheet is fine.
    let stress = with(with(square(), "plane", json!("stress")), "nu", json!(0.5));
    let tmp = TempDir::new("cli-nu-half");
    let (scenario, result) = (tmp.join("stress.json"), tmp.join("stress.result.json"));
    std::fs::write(&scenario, stress.to_string()).unwrap();
    let o = server_solve(&scenario, &result, &[]);
    assert!(o.status.success(), "plane stress with ν = 0.5 is rejected: {}", text(&o).1);
    let u = pairs(&read_json(&result), "displacements");
    assert!(u.iter().flatten().all(|x| x.is_finite()) && u[2][1] < 0.0, "{u:?}");
}

#[test]
fn no_fixed_nodes_is_a_rigid_body() {
    let sc = with(square(), "fixed_nodes", json!([]));
    assert_rejected("no_fixed", &sc, &["rigid body"]);
    // One fixed node still lets the square rotate about it.
    let sc = with(square(), "fixed_nodes", json!([0]));
    assert_rejected("one_fixed", &sc, &["rigid body"]);
}

#[test]
fn node_used_by_no_triangle() {
    let mut sc = square();
    sc["nodes"].as_array_mut().unwrap().push(json!([3.0, 3.0]));
    assert_rejected("unused", &sc, &["node 4 is used by no triangle"]);
}

#[test]
fn load_on_an_unknown_node() {
    let mut sc = square();
    sc["loads"].as_array_mut().unwrap().push(json!({"node": 9, "fx": 1.0, "fy": 0.0}));
    assert_rejected("load_unknown", &sc, &["loads", "node 9", "0..3"]);
}

#[test]
fn mesh_over_the_size_limit() {
    let example = repo_root().join("server/examples/paper19x19.json");
    let n_nodes = read_json(&example)["nodes"].as_array().expect("nodes").len();
    assert_eq!(n_nodes, 361);
    assert_rejected_path("max_nodes", &example, &["--max-nodes", "100"], &["361 nodes", "over the limit of 100"]);
    assert_rejected_path("max_triangles", &example, &["--max-triangles", "647"], &["648 triangles", "over the limit of 647"]);
    // At the limit it is accepted.
    let tmp = TempDir::new("cli-limit");
    let o = server_solve(&example, &tmp.join("r.json"), &["--max-nodes", "361", "--max-triangles", "648"]);
    assert!(o.status.success(), "{}", text(&o).1);
}

#[test]
fn unknown_field_is_a_typo() {
    let mut sc = square();
    let fixed = sc.as_object_mut().unwrap().remove("fixed_nodes").unwrap();
    sc["fixed_node"] = fixed;
    assert_rejected("typo", &sc, &["unknown field `fixed_node`", "fixed_nodes"]);
}

#[test]
fn missing_file() {
    let tmp = TempDir::new("cli-missing");
    let path = tmp.join("does_not_exist.json");
    assert_rejected_path("missing", &path, &[], &["cannot read", "does_not_exist.json"]);
}

#[test]
fn malformed_json() {
    let text = r#"{"nodes": [[0, 0], [1, 0]], "triangles": [[0, 1, 2]"#;
    assert_rejected_text("malformed", text, &[], &["malformed.json is not a valid scenario", "EOF", "line 1"]);
    assert_rejected_text("not_json", "nodes: []", &[], &["not_json.json is not a valid scenario", "line 1 column 2"]);
}

/// Regression (issue 2 review): `working_nodes` naming a node twice is an error, not a
/// silently duplicated compliance row.
#[test]
fn issue_2_repeated_working_node_is_rejected() {
    let dir = TempDir::new("dupwork");
    let mut sc = read_json(&validation_dir().join("scenarios/s1_paper19x19_strain.json"));
    let first = sc["working_nodes"][0].clone();
    sc["working_nodes"].as_array_mut().unwrap().push(first.clone());
    let path = dir.join("dup.json");
    write_json(&path, &sc);
    let o = server_solve(&path, &dir.join("out.json"), &[]);
    let (_, err) = text(&o);
    assert!(!o.status.success());
    assert!(err.contains(&format!("working_nodes lists node {first} twice")), "{err}");
}

/// Issue 13: a node repeated instead of shared (the two triangles of the square are cut apart).
#[test]
fn issue_13_duplicate_nodes_are_rejected() {
    let mut sc = square();
    sc["nodes"] = json!([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 1.0]]);
    sc["triangles"] = json!([[0, 1, 2], [0, 4, 3]]);
    assert_rejected("duplicate_node", &sc, &["nodes 2 and 4 coincide at (1, 1)"]);
}

/// Issue 13: the same triangle twice (in another order).
#[test]
fn issue_13_duplicate_triangles_are_rejected() {
    let sc = with(square(), "triangles", json!([[0, 1, 2], [0, 2, 3], [2, 0, 1]]));
    assert_rejected("duplicate_triangle", &sc, &["triangles 0 and 2 have the same nodes [0, 1, 2]"]);
}

/// Issue 13: triangles whose interiors overlap (the square's two diagonals both used).
#[test]
fn issue_13_overlapping_triangles_are_rejected() {
    let sc = with(square(), "triangles", json!([[0, 1, 2], [0, 2, 3], [0, 1, 3]]));
    assert_rejected("overlap", &sc, &["triangles 0 (nodes [0, 1, 2]) and 2 (nodes [0, 1, 3]) overlap"]);
}
