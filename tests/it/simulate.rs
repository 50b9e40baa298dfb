//! The `simulate` command through the real binary: its `--dump-state` re-solved by the
//! independent reference solver (fem_ref.py) for axis-aligned, oblique and rotating needles at
//! several depths, the paper's Fig. 3 miss, and the errors for bad trajectories and scenes.

use std::path::Path;
use std::process::Command;

use needlesim_tests::{TempDir, bin, pairs, python, read_json, run, text, validation_dir};
use serde_json::Value;

const FRAC_PI_2: f64 = std::f64::consts::FRAC_PI_2;

/// A trajectory: `(t_s, x_m, y_m, theta_rad)` rows.
type Rows = Vec<(f64, f64, f64, f64)>;

/// Writes a trajectory CSV of `(t_s, x_m, y_m, theta_rad)` rows.
fn write_traj(path: &Path, rows: &[(f64, f64, f64, f64)]) {
    let mut s = String::from("t_s,x_m,y_m,theta_rad\n");
    for (t, x, y, a) in rows {
        s.push_str(&format!("{t},{x},{y},{a}\n"));
    }
    std::fs::write(path, s).unwrap();
}

/// Runs `needlesim-server simulate`; returns (stdout, stderr), panicking on failure.
fn simulate_ok(args: &[&str]) -> (String, String) {
    let o = run(Command::new(bin("needlesim-server")).arg("simulate").args(args));
    let (out, err) = text(&o);
    assert!(o.status.success(), "simulate {args:?} failed: {err}");
    assert!(!err.contains("panicked"), "{err}");
    (out, err)
}

/// Parses a time series CSV into header and rows of numbers.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let rows = lines.map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()).collect()).collect();
    (header, rows)
}

fn col(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"))
}

/// Re-solves a dumped state with fem_ref.py and returns the relative L2 difference of the
/// displacement fields, and the dumped JSON.
fn resolve_with_reference(dir: &TempDir, dump: &Path, label: &str) -> (f64, Value) {
    let reference = dir.join(&format!("{label}.ref.json"));
    let o = run(Command::new(python()).arg(validation_dir().join("fem_ref.py")).arg(dump).arg(&reference));
    assert!(o.status.success(), "fem_ref.py failed: {}", text(&o).1);
    let state = read_json(dump);
    let ours = pairs(&state, "solver_displacements");
    let theirs = pairs(&read_json(&reference), "displacements");
    let num: f64 = ours.iter().zip(&theirs).map(|(a, b)| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sum();
    let den: f64 = theirs.iter().map(|b| b[0] * b[0] + b[1] * b[1]).sum();
    assert!(den > 0.0, "{label}: the reference field is zero");
    ((num / den).sqrt(), state)
}

/// Runs `simulate` on `scene` along `rows` with `--dump-state`, and re-solves the dumped state
/// with the reference ([`resolve_with_reference`]).
fn simulate_and_resolve(dir: &TempDir, scene: &Path, label: &str, rows: &[(f64, f64, f64, f64)]) -> (f64, Value) {
    let traj = dir.join(&format!("{label}.csv"));
    let dump = dir.join(&format!("{label}.state.json"));
    write_traj(&traj, rows);
    simulate_ok(&["--scene", scene.to_str().unwrap(), "--trajectory", traj.to_str().unwrap(), "--dump-state", dump.to_str().unwrap()]);
    resolve_with_reference(dir, &dump, label)
}

fn states(state: &Value) -> Vec<String> {
    state["needle_nodes"].as_array().unwrap().iter().map(|n| n["state"].as_str().unwrap().to_owned()).collect()
}

/// Every dumped needle node holds `un`; `ut` exactly when stuck or carried by the tip; and a
/// slipping node carries its friction as a load.
fn check_dump_conditions(state: &Value) {
    let nodes = state["needle_nodes"].as_array().unwrap();
    let pl = state["prescribed_local"].as_array().unwrap();
    let loads = state["loads"].as_array().unwrap();
    assert_eq!(nodes.len(), pl.len());
    for n in nodes {
        let id = n["node"].as_u64().unwrap();
        let c = pl.iter().find(|c| c["node"].as_u64() == Some(id)).expect("conditions for every needle node");
        assert!(c["un"].is_number());
        let st = n["state"].as_str().unwrap();
        assert_eq!(c["ut"].is_number(), st != "slipping", "node {id} ({st}): {c}");
        assert_eq!(loads.iter().any(|l| l["node"].as_u64() == Some(id)), st == "slipping", "node {id} ({st})");
    }
}

#[test]
fn dumped_states_resolve_to_the_same_field_with_the_reference_solver() {
    let dir = TempDir::new("dump");
    let down = -FRAC_PI_2;
    // (label, trajectory rows): the paper phantom, tip starting 5 mm above the top surface.
    let oblique = -1.2f64;
    let (ex, ey) = (0.03, 0.1);
    let ob = |d: f64, a: f64| (ex + (d - 0.1) * a.cos(), ey + (d - 0.1) * a.sin());
    let cases: Vec<(&str, Rows)> = vec![
        ("axis-20mm", vec![(0.0, 0.05, 0.205, down), (2.5, 0.05, 0.18, down)]),
        ("axis-45mm", vec![(0.0, 0.05, 0.205, down), (5.0, 0.05, 0.155, down)]),
        // Insert, hold (all stuck), move on 0.15 mm: some nodes have broken away, some not.
        (
            "axis-stick-slip",
            vec![(0.0, 0.05, 0.205, down), (4.0, 0.05, 0.165, down), (4.2, 0.05, 0.165, down), (4.23, 0.05, 0.16485, down)],
        ),
        ("oblique-30mm", {
            let (a, b) = (ob(-0.005, oblique), ob(0.03, oblique));
            vec![(0.0, a.0, a.1, oblique), (3.5, b.0, b.1, oblique)]
        }),
        ("rotating", {
            let (a, b) = (ob(-0.005, oblique), ob(0.035, oblique));
            let c = ob(0.035, oblique + 0.12);
            vec![(0.0, a.0, a.1, oblique), (4.0, b.0, b.1, oblique), (4.6, c.0, c.1, oblique + 0.12)]
        }),
    ];
    let mut seen_mixed = false;
    for (label, rows) in cases {
        let traj = dir.join(&format!("{label}.csv"));
        let dump = dir.join(&format!("{label}.state.json"));
        let series = dir.join(&format!("{label}.out.csv"));
        write_traj(&traj, &rows);
        simulate_ok(&[
            "--scene",
            "paper-phantom",
            "--trajectory",
            traj.to_str().unwrap(),
            "-o",
            series.to_str().unwrap(),
            "--dump-state",
            dump.to_str().unwrap(),
        ]);
        let (rel, state) = resolve_with_reference(&dir, &dump, label);
        let st = states(&state);
        println!("{label}: {} needle nodes {st:?}, rel L2 difference to fem_ref {rel:.3e}", st.len());
        assert!(st.len() >= 3, "{label}: the needle is in the tissue");
        check_dump_conditions(&state);
        assert!(rel <= 1e-9, "{label}: solver and reference differ by {rel:e}");
        if st.iter().any(|s| s == "stuck") && st.iter().any(|s| s == "slipping") {
            seen_mixed = true;
        }
        if label == "rotating" {
            let angles: Vec<f64> = state["prescribed_local"].as_array().unwrap().iter().map(|c| c["angle_rad"].as_f64().unwrap()).collect();
            assert!(angles.iter().all(|a| (a - (oblique + 0.12)).abs() < 1e-12), "frames follow the needle: {angles:?}");
        }
    }
    assert!(seen_mixed, "one dumped moment has both stuck and slipping nodes");
}

/// The paper's Fig. 3: the needle aimed straight at the target's undeformed centre misses it,
/// because the insertion carries the target off the axis, towards the free surface.
#[test]
fn fig3_needle_aimed_at_target_misses() {
    let dir = TempDir::new("fig3");
    let series = dir.join("fig3.csv");
    simulate_ok(&["--scene", "fig3-target", "-o", series.to_str().unwrap()]);
    let (h, rows) = read_csv(&series);
    let (dist, tx, ty, hit) =
        (col(&h, "target_biopsy_distance_m"), col(&h, "target_biopsy_x_m"), col(&h, "target_biopsy_y_m"), col(&h, "target_biopsy_hit"));
    let (bx, by, th) = (col(&h, "x_m"), col(&h, "y_m"), col(&h, "theta_rad"));
    let start = &rows[0];
    let closest = rows.iter().min_by(|a, b| a[dist].total_cmp(&b[dist])).unwrap();
    let end = rows.last().unwrap();
    let radius = 0.0015;
    // Undeformed, the target's centre lies on the needle axis.
    let lateral = |r: &Vec<f64>| {
        let (s, c) = r[th].sin_cos();
        -s * (r[tx] - r[bx]) + c * (r[ty] - r[by])
    };
    assert!(lateral(start).abs() < 1e-9, "aimed straight at the target: {}", lateral(start));
    // The tip passes the target beside it.
    let miss = closest[dist];
    println!("closest approach {:.3} mm, lateral offset {:.3} mm", miss * 1e3, lateral(closest) * 1e3);
    assert!(miss > radius + 0.0005, "miss distance {miss} m is not clear of the {radius} m target");
    assert!(miss < 0.01, "the needle passes near the target ({miss} m)");
    assert_eq!(end[hit], 0.0);
    // The target moved with the tissue, off the axis towards the free top surface (+n side),
    // away from the fixed bottom edge.
    assert!(lateral(closest) > radius, "lateral offset {} m", lateral(closest));
    let moved = (closest[tx] - start[tx]).hypot(closest[ty] - start[ty]);
    assert!(moved > 0.003, "target displaced by {moved} m");
    // The tip went past the target's depth.
    let along = |r: &Vec<f64>| {
        let (s, c) = r[th].sin_cos();
        c * (r[tx] - r[col(&h, "tip_x_m")]) + s * (r[ty] - r[col(&h, "tip_y_m")])
    };
    assert!(along(end) < 0.0, "the tip ends beyond the target");
}

#[test]
fn bad_trajectories_and_scenes_get_clear_errors() {
    let dir = TempDir::new("badtraj");
    let nan = dir.join("nan.csv");
    std::fs::write(&nan, "t_s,x_m,y_m,theta_rad\n0,0.05,0.205,-1.57\n1,NaN,0.2,-1.57\n").unwrap();
    let o = run(Command::new(bin("needlesim-server")).args(["simulate", "--scene", "paper-phantom", "--trajectory"]).arg(&nan));
    let (_, err) = text(&o);
    assert!(!o.status.success());
    assert!(err.contains("(line 3): x_m is NaN"), "{err}");
    let o = run(Command::new(bin("needlesim-server")).args(["simulate", "--scene", "no-such-scene"]));
    let (_, err) = text(&o);
    assert!(!o.status.success() && err.contains("neither a file nor a shipped example") && err.contains("paper-phantom"), "{err}");
    // A jump of 5 cm in one millisecond is clamped, said on stderr, and the run completes.
    let jump = dir.join("jump.csv");
    write_traj(
        &jump,
        &[(0.0, 0.05, 0.205, -FRAC_PI_2), (1.0, 0.05, 0.2, -FRAC_PI_2), (1.001, 0.05, 0.15, -FRAC_PI_2), (2.0, 0.05, 0.15, -FRAC_PI_2)],
    );
    let out = dir.join("jump.out.csv");
    let (_, err) = simulate_ok(&["--scene", "paper-phantom", "--trajectory", jump.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(err.contains("clamped"), "{err}");
    let (h, rows) = read_csv(&out);
    let y = col(&h, "y_m");
    let max_step = rows.windows(2).map(|w| (w[1][y] - w[0][y]).abs()).fold(0.0, f64::max);
    assert!(max_step <= 0.002 + 1e-12, "base moved {max_step} m in one tick");
    assert!(rows.iter().all(|r| r.iter().all(|v| v.is_finite())));
    let bad_scene = dir.join("bad.toml");
    std::fs::write(&bad_scene, "name = \"x\"\n[mesh]\ntype = \"grid\"\nnx = 5\nny = 5\nwidth_m = 0.1\nheight_m = 0.1\n").unwrap();
    let o = run(Command::new(bin("needlesim-server")).args(["simulate", "--scene"]).arg(&bad_scene).args(["--trajectory"]).arg(&jump));
    let (_, err) = text(&o);
    assert!(!o.status.success() && err.contains("missing field") && err.contains("regions"), "{err}");
}

/// Runs `needlesim-server simulate ARGS`, killing it after `secs` (a hang is a failure);
/// returns whether it succeeded, and its stderr.
fn simulate_within(args: &[&str], secs: u64) -> (bool, String) {
    let out =
        needlesim_tests::run_within(Command::new(bin("needlesim-server")).arg("simulate").args(args), std::time::Duration::from_secs(secs));
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    (out.status.success(), err)
}

/// The `error: ` line of a failed run's stderr.
fn error_line(err: &str) -> &str {
    err.lines().find(|l| l.starts_with("error: ")).unwrap_or_else(|| panic!("no `error: ` line in:\n{err}"))
}

/// Issue 13: bad scene values are rejected when the scene is loaded, naming the TOML key.
#[test]
fn issue_13_bad_scene_values_name_the_key() {
    let dir = TempDir::new("badvalues");
    let base = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/paper-phantom.toml")).unwrap();
    let base_line = "base = [0.05, 0.205, -1.5707963267948966]";
    assert!(base.contains(base_line) && base.contains("[needle]"));
    let traj = dir.join("traj.csv");
    write_traj(&traj, &[(0.0, 0.05, 0.205, -FRAC_PI_2), (0.1, 0.05, 0.2, -FRAC_PI_2)]);
    let cases = [
        (
            "nan_base",
            base.replace(base_line, "base = [nan, 0.205, -1.5707963267948966]"),
            "needle.base = [NaN, 0.205, -1.5707963267948966]: must be finite",
        ),
        (
            "negative_step",
            base.replace("[needle]", "[limits]\nmax_base_step_m = -1\n\n[needle]"),
            "limits.max_base_step_m = -1: must be finite and > 0",
        ),
        (
            "zero_iterations",
            base.replace("[needle]", "[limits]\nmax_active_set_iterations = 0\n\n[needle]"),
            "limits.max_active_set_iterations = 0: must be in 1..=10000",
        ),
        ("zero_nodes", base.replace(base_line, &format!("max_nodes = 0\n{base_line}")), "needle.max_nodes = 0: must be in 1..=4096"),
        (
            "huge_nodes",
            base.replace(base_line, &format!("max_nodes = 1000000000\n{base_line}")),
            "needle.max_nodes = 1000000000: must be in 1..=4096",
        ),
    ];
    for (name, toml, want) in cases {
        let path = dir.join(&format!("{name}.toml"));
        std::fs::write(&path, toml).unwrap();
        let (ok, err) =
            simulate_within(&["--scene", path.to_str().unwrap(), "--trajectory", traj.to_str().unwrap(), "-o", "/dev/null"], 60);
        assert!(!ok, "{name}: accepted");
        assert!(error_line(&err).contains(want), "{name}: {err}");
    }
}

/// Issue 13: a trajectory ending past the tick limit is an error naming its line, at once
/// (1e12 s used to abort allocating 8 TB; 1e300 s wrapped the tick count and looped forever).
#[test]
fn issue_13_trajectory_end_times_past_the_tick_limit_name_the_line() {
    let dir = TempDir::new("longtraj");
    for (name, end, comment) in [("t1e12", "1e12", ""), ("t1e300", "1e300", "# a comment line\n")] {
        let path = dir.join(&format!("{name}.csv"));
        std::fs::write(&path, format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.205,-1.57\n{comment}{end},0.05,0.1,-1.57\n")).unwrap();
        let (ok, err) = simulate_within(&["--scene", "paper-phantom", "--trajectory", path.to_str().unwrap(), "-o", "/dev/null"], 30);
        assert!(!ok, "{name}: accepted");
        let line = error_line(&err);
        let want_line = if comment.is_empty() { "trajectory line 3:" } else { "trajectory line 4:" };
        assert!(line.contains(want_line) && line.contains("over the limit of 1000000 ticks"), "{name}: {line}");
    }
    // --max-ticks sets the limit: 2 s at 1 kHz is 2000 ticks.
    let short = dir.join("short.csv");
    write_traj(&short, &[(0.0, 0.05, 0.205, -FRAC_PI_2), (2.0, 0.05, 0.2, -FRAC_PI_2)]);
    let args = ["--scene", "paper-phantom", "--trajectory", short.to_str().unwrap(), "-o", "/dev/null", "--max-ticks"];
    let (ok, err) = simulate_within(&[&args[..], &["1999"]].concat(), 60);
    assert!(!ok && error_line(&err).contains("trajectory line 3: t_s = 2e0 ends 2e0 s after the first sample, 2e3 ticks"), "{err}");
    let (ok, err) = simulate_within(&[&args[..], &["2000"]].concat(), 60);
    assert!(ok, "{err}");
}

/// Issue 13: a flexible needle with 3e4 N/m friction diverges (its nodes run off by metres). The run stops
/// with an error naming the tick, exits non-zero and writes no time series. (Its ticks stop
/// converging first, which stops a run by default since issue 35: `--keep-unconverged` lets it
/// reach the divergence bounds this test is about.)
#[test]
fn issue_13_a_diverging_offline_run_stops_naming_the_tick() {
    let dir = TempDir::new("diverge");
    let scene = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/fig4-steering.toml")).unwrap();
    assert!(scene.contains("friction_n_per_m = 10\n"));
    let path = dir.join("friction.toml");
    std::fs::write(&path, scene.replace("friction_n_per_m = 10\n", "friction_n_per_m = 3e4\n")).unwrap();
    let traj = needlesim_tests::repo_root().join("server/scenes/fig4-steering.csv");
    let out = dir.join("series.csv");
    let (ok, err) = simulate_within(
        &["--scene", path.to_str().unwrap(), "--trajectory", traj.to_str().unwrap(), "-o", out.to_str().unwrap(), "--keep-unconverged"],
        300,
    );
    assert!(!ok, "the diverging run exited 0: {err}");
    let line = error_line(&err);
    let tick: u64 = line
        .split("tick ")
        .nth(1)
        .and_then(|r| r.split(':').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no tick named: {line}"));
    assert!(line.contains("the solve diverged") && line.contains("is not within the bound"), "{line}");
    assert!(tick > 1000 && tick < 9051, "tick {tick}: {line}");
    assert!(!out.exists(), "a time series with diverged rows was written");
}

/// Issue 13: meshes a conforming mesher cannot produce are rejected, naming what is wrong: two
/// regions of one name in a Gmsh file (its physical names).
#[test]
fn issue_13_duplicate_region_names_in_a_gmsh_file_are_rejected() {
    let dir = TempDir::new("dupregion");
    let msh = std::fs::read_to_string(needlesim_tests::repo_root().join("server/core/testdata/inclusion_v22.msh")).unwrap();
    assert!(msh.contains("2 2 \"inclusion\""));
    std::fs::write(dir.join("dup.msh"), msh.replace("2 2 \"inclusion\"", "2 2 \"tissue\"")).unwrap();
    let scene = "[mesh]\ntype = \"msh\"\nfile = \"dup.msh\"\n\n[[regions]]\nname = \"tissue\"\nyoung_modulus_pa = 30e3\npoisson_ratio = 0.45\n\n[needle]\nlength_m = 0.1\nbase = [0.05, 0.205, -1.5707963267948966]\n";
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene).unwrap();
    let traj = dir.join("traj.csv");
    write_traj(&traj, &[(0.0, 0.05, 0.205, -FRAC_PI_2), (0.1, 0.05, 0.2, -FRAC_PI_2)]);
    let (ok, err) = simulate_within(&["--scene", path.to_str().unwrap(), "--trajectory", traj.to_str().unwrap(), "-o", "/dev/null"], 60);
    assert!(!ok);
    assert!(error_line(&err).contains("regions 0 and 1 are both named 'tissue'"), "{err}");
}

/// The paper phantom's scene on an `n × n` grid with the default contact (material points).
fn refined_phantom_scene(dir: &TempDir, n: usize) -> std::path::PathBuf {
    let shipped = std::fs::read_to_string(repo_scene("paper-phantom")).unwrap();
    let toml = shipped
        .replace("nx = 19", &format!("nx = {n}"))
        .replace("ny = 19", &format!("ny = {n}"))
        .replace("contact = \"nodes\"\n", "")
        .replace("name = \"paper-phantom\"", &format!("name = \"phantom-{n}-points\""));
    assert!(!toml.contains("contact ="), "the refined scene takes the default contact");
    let path = dir.join(&format!("phantom-{n}.toml"));
    std::fs::write(&path, toml).unwrap();
    path
}

fn repo_scene(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../server/scenes").join(format!("{name}.toml"))
}

/// Issue 15: with contact at material points (the default), the states of an oblique (40°)
/// insertion and of a needle turned by ±10° while inserted, on a 200 × 200 mesh, are static
/// problems with conditions at points inside triangles; fem_ref.py re-solves them (Lagrange
/// multipliers at the points) to the same displacement field (1e-9) and the same force at every
/// point (1e-8 of the largest).
#[test]
fn issue_15_material_point_states_resolve_with_the_reference_on_200x200() {
    let dir = TempDir::new("points200");
    let scene = refined_phantom_scene(&dir, 200);
    // Entry at (0.05, 0.1); the base `d` before (negative) or past the entry along angle `a`.
    let at = |d: f64, a: f64| (0.05 + (d - 0.1) * a.cos(), 0.1 + (d - 0.1) * a.sin());
    let oblique = -(90f64 - 40.0).to_radians();
    let (o0, o1) = (at(-0.005, oblique), at(0.045, oblique));
    let down = -FRAC_PI_2;
    let (v0, v1) = (at(-0.005, down), at(0.05, down));
    // Turning about the entry point with 50 mm inserted: +10°, then -10°, ending at -6°.
    let turn = |t: f64, a: f64| {
        let (x, y) = at(0.05, a);
        (t, x, y, a)
    };
    let cases: Vec<(&str, Rows)> = vec![
        ("oblique-40deg", vec![(0.0, o0.0, o0.1, oblique), (5.0, o1.0, o1.1, oblique)]),
        (
            "turning",
            vec![
                (0.0, v0.0, v0.1, down),
                (5.5, v1.0, v1.1, down),
                turn(6.5, down + 10f64.to_radians()),
                turn(8.5, down - 10f64.to_radians()),
                turn(9.0, down - 6f64.to_radians()),
            ],
        ),
    ];
    let mut kinds = std::collections::BTreeSet::new();
    for (label, rows) in cases {
        let (rel, state) = simulate_and_resolve(&dir, &scene, label, &rows);
        let points = state["points"].as_array().expect("the state has material points");
        let nodes = state["needle_nodes"].as_array().unwrap();
        println!("{label}: {} contact points {:?}, rel L2 difference to fem_ref {rel:.3e}", points.len(), states(&state));
        assert!(points.len() >= 15, "{label}: the needle holds the tissue at points along 45-50 mm");
        assert!(state["prescribed_local"].as_array().is_none_or(|p| p.is_empty()), "{label}: no node contacts");
        assert!(rel <= 1e-9, "{label}: solver and reference differ by {rel:e}");
        // The force at every point, ours against the reference's Lagrange multipliers.
        let reference = read_json(&dir.join(&format!("{label}.ref.json")));
        let theirs = reference["point_reactions"].as_array().expect("point reactions");
        assert_eq!(theirs.len(), nodes.len());
        let scale = nodes.iter().map(|n| n["fx"].as_f64().unwrap().hypot(n["fy"].as_f64().unwrap())).fold(0.0, f64::max);
        assert!(scale > 1e-3, "{label}: the points carry force ({scale} N)");
        for (k, ((ours, r), cond)) in nodes.iter().zip(theirs).zip(points).enumerate() {
            assert_eq!(r["point"].as_u64(), Some(k as u64));
            // The reference's reaction is its constraints' share; the friction (or a bevel's
            // lateral force) is the point's prescribed `f`.
            let applied = |c: usize| cond["f"].as_array().map_or(0.0, |f| f[c].as_f64().unwrap());
            for (c, (a, b)) in [("fx", "rx"), ("fy", "ry")].into_iter().enumerate() {
                let (x, y) = (ours[a].as_f64().unwrap(), r[b].as_f64().unwrap() + applied(c));
                assert!((x - y).abs() <= 1e-8 * scale, "{label}: point {k} {a} = {x} vs reference {y}");
            }
        }
        if label == "turning" {
            let angles: Vec<f64> = points.iter().map(|c| c["angle_rad"].as_f64().unwrap()).collect();
            let last = down - 6f64.to_radians();
            assert!(angles.iter().all(|a| (a - last).abs() < 1e-12), "frames follow the needle: {angles:?}");
        }
        kinds.extend(states(&state));
    }
    assert!(kinds.contains("stuck") && kinds.contains("slipping"), "stuck and slipping points were checked: {kinds:?}");
}

/// Issue 19: `simulate` reports its iteration caps — the ticks whose stick/slip iteration or
/// flexible shape passes stopped at their bound — and the shipped bevel-tip example (a flexible
/// needle with a bevel, the one that used to end a tick at the 4-pass shape cap) has none.
#[test]
fn issue_19_simulate_reports_iteration_caps_and_the_bevel_example_has_none() {
    let dir = TempDir::new("caps");
    let out = dir.path().join("bevel.csv");
    let (_, err) = simulate_ok(&["--scene", "bevel-tip", "-o", out.to_str().unwrap()]);
    let line = err.lines().find(|l| l.contains("simulated")).unwrap_or_else(|| panic!("no summary line: {err}"));
    for key in ["active_set_capped_ticks=0", "shape_capped_ticks=0", "unconverged_ticks=0"] {
        assert!(line.contains(key), "{key} not in the summary: {line}");
    }
    assert!(!err.contains("iteration cap"), "{err}");
}

/// Issue 19: contacts spread over the needle's width (`needle.spread_contact`, the shipped
/// toughness phantom refined to 73², where a 17-gauge patch spans two elements). A dumped state
/// writes each patch's force as the loads on its nodes; fem_ref.py re-solves that problem to
/// the solver's displacement field (1e-9), and the reference field then meets every patch's
/// condition: the mean displacement over the patch, $\sum_k w_k u_k$, in the patch's frame
/// equals its prescribed $u_t$ and $u_n$ (1e-9 of the largest displacement). An oblique
/// insertion and a turn, so that stuck and slipping patches are both checked.
#[test]
fn issue_19_contact_patches_resolve_with_the_reference_and_meet_their_conditions() {
    let dir = TempDir::new("patches");
    let shipped = std::fs::read_to_string(repo_scene("paper-phantom-toughness")).unwrap();
    assert!(shipped.contains("spread_contact = true"), "the shipped toughness phantom spreads its contacts");
    let scene = dir.join("phantom-73-patches.toml");
    std::fs::write(&scene, shipped.replace("nx = 19", "nx = 73").replace("ny = 19", "ny = 73")).unwrap();
    let at = |d: f64, a: f64| (0.05 + (d - 0.1) * a.cos(), 0.1 + (d - 0.1) * a.sin());
    let oblique = -(90f64 - 40.0).to_radians();
    let (o0, o1) = (at(-0.005, oblique), at(0.04, oblique));
    let down = -FRAC_PI_2;
    let (v0, v1) = (at(-0.005, down), at(0.045, down));
    let turn = |t: f64, a: f64| {
        let (x, y) = at(0.045, a);
        (t, x, y, a)
    };
    let cases: Vec<(&str, Rows)> = vec![
        ("oblique-40deg", vec![(0.0, o0.0, o0.1, oblique), (4.5, o1.0, o1.1, oblique)]),
        ("turning", vec![(0.0, v0.0, v0.1, down), (5.0, v1.0, v1.1, down), turn(6.0, down + 8f64.to_radians())]),
    ];
    let mut kinds = std::collections::BTreeSet::new();
    for (label, rows) in cases {
        let (rel, state) = simulate_and_resolve(&dir, &scene, label, &rows);
        assert!(rel <= 1e-9, "{label}: solver and reference differ by {rel:e}");
        assert!(state["points"].as_array().is_none_or(|p| p.is_empty()), "{label}: every contact is a patch");
        let nodes = state["needle_nodes"].as_array().unwrap();
        assert!(nodes.len() >= 15, "{label}: the needle holds the tissue along 40-45 mm ({} contacts)", nodes.len());
        let u = pairs(&read_json(&dir.join(&format!("{label}.ref.json"))), "displacements");
        let u_max = u.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
        assert!(u_max > 1e-4, "{label}: the tissue deforms ({u_max} m)");
        for (i, n) in nodes.iter().enumerate() {
            let p = &n["patch"];
            let terms = p["terms"].as_array().unwrap_or_else(|| panic!("{label}: contact {i} is not a patch: {n}"));
            assert!(terms.len() >= 3, "{label}: contact {i} spans {} nodes", terms.len());
            let mut mean = [0.0; 2];
            for t in terms {
                let (k, w) = (t[0].as_u64().unwrap() as usize, t[1].as_f64().unwrap());
                mean[0] += w * u[k][0];
                mean[1] += w * u[k][1];
            }
            let a = p["angle_rad"].as_f64().unwrap();
            let (ut, un) = (mean[0] * a.cos() + mean[1] * a.sin(), -mean[0] * a.sin() + mean[1] * a.cos());
            let state_name = n["state"].as_str().unwrap();
            let want_un = p["un"].as_f64().unwrap_or_else(|| panic!("{label}: patch {i} has no lateral condition"));
            assert!((un - want_un).abs() <= 1e-9 * u_max, "{label}: patch {i} ({state_name}) u_n = {un} vs {want_un}");
            match p["ut"].as_f64() {
                Some(want_ut) => assert!((ut - want_ut).abs() <= 1e-9 * u_max, "{label}: patch {i} ({state_name}) u_t = {ut} vs {want_ut}"),
                None => assert_eq!(state_name, "slipping", "{label}: patch {i} has no axial condition"),
            }
        }
        kinds.extend(states(&state));
    }
    assert!(kinds.contains("stuck") && kinds.contains("slipping"), "stuck and slipping patches were checked: {kinds:?}");
}

/// Issue 35, item 12: a dumped bevel-tip state re-solves with the reference wherever the run
/// stops. While the tip carries a contact (before it punctures), its bevel pushes sideways with
/// a force that follows the tip's axial force; the step used to update that force after its
/// last solve when the change was below the friction tolerance, so the dumped condition was not
/// the one the dumped field was solved for (before the fix: 6e-8 … 1e-6 where the run stopped
/// with the tip carrying). The shipped trajectory (insertion, hold), stopped at 30, 45, 60 and
/// 80 % of its duration: every dump re-solves to 1e-9, and the 60 % one, as in the issue, stops
/// while the tip carries a contact (the case that failed).
#[test]
fn issue_35_a_dumped_bevel_tip_state_re_solves_at_60_and_80_percent_of_the_shipped_trajectory() {
    let dir = TempDir::new("bevel-dump");
    let shipped = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/bevel-tip.csv")).unwrap();
    let rows: Rows = shipped
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("t_s"))
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            (v[0], v[1], v[2], v[3])
        })
        .collect();
    let duration_s = rows.last().unwrap().0 - rows[0].0;
    for percent in [30, 45, 60, 80] {
        // The rows before the cut, and the pose interpolated at the cut.
        let t_end = rows[0].0 + percent as f64 / 100.0 * duration_s;
        let mut cut: Rows = rows.iter().copied().filter(|r| r.0 < t_end).collect();
        let (a, b) = (*cut.last().unwrap(), rows[cut.len()]);
        let w = (t_end - a.0) / (b.0 - a.0);
        cut.push((t_end, a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2), a.3 + w * (b.3 - a.3)));
        let label = format!("bevel-{percent}");
        let (rel, state) = simulate_and_resolve(&dir, Path::new("bevel-tip"), &label, &cut);
        let st = states(&state);
        println!("{label}: {} contacts {st:?}, rel L2 difference to fem_ref {rel:.3e}", st.len());
        assert!(st.len() >= 3, "{label}: the needle is in the tissue");
        if percent == 60 {
            assert_eq!(st.last().map(String::as_str), Some("tip"), "{label}: the tip carries a contact");
        }
        assert!(rel <= 1e-9, "{label}: solver and reference differ by {rel:e}");
    }
}
