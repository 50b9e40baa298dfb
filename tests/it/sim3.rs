//! The 3D rigid-needle simulation (issue 16, part 3) against the independent reference: at
//! ticks mid-insertion (the tip carrying a point), during slipping, after a 10° turn of the base
//! and during withdrawal, the static problem the step solved ([`Simulation3::snapshot`]) is
//! written in the 3D exchange format (`points` with frames, prescribed components and friction
//! `f`) and solved by fem_ref3d.py: its point reactions plus the friction equal the
//! simulation's contact forces to 1e-8, and the displacements at the points agree to 1e-9.

use std::path::{Path, PathBuf};
use std::process::Command;

use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
use needlesim_core::sim3::{BasePose3, PointState3, Simulation3, Snapshot3};
use needlesim_scene::exchange3d::scenario_from_snapshot;
use needlesim_tests::{TempDir, python, read_json, run, text, validation_dir, write_json};
use serde_json::Value;

const ENTRY: [f64; 3] = [0.0513, 0.0487, 0.1];

/// The snapshot as a 3D exchange scenario on the phantom (the library's conversion, the one
/// `simulate --dump-state` uses).
fn scenario(sim: &Simulation3, snap: &Snapshot3, name: &str) -> Value {
    serde_json::to_value(scenario_from_snapshot(sim.model(), snap, None, name)).expect("a scenario serialises")
}

fn reference_solve3(scenario: &Path, out: PathBuf) -> Value {
    let script = validation_dir().join("fem_ref3d.py");
    let o = run(Command::new(python()).arg(&script).arg(scenario).arg(&out));
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "fem_ref3d.py {} failed ({}):\n{stdout}{stderr}", scenario.display(), o.status);
    let r = read_json(&out);
    let cross = r["cross_check"]["u_rel_l2_diff_skfem_vs_numpy"].as_f64().expect("fem_ref3d cross check");
    assert!(cross < 1e-10, "the reference's own assemblies disagree by {cross:e}");
    r
}

/// Max component error over max component magnitude.
fn rel(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let err = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs())).fold(0.0, f64::max);
    let scale = b.iter().flat_map(|q| q.iter().map(|v| v.abs())).fold(0.0, f64::max);
    assert!(scale > 0.0);
    err / scale
}

/// Solves the snapshot with fem_ref3d.py and returns (force error, displacement error).
fn check(sim: &Simulation3, tmp: &TempDir, name: &str) -> (f64, f64) {
    let snap = sim.snapshot();
    assert!(!snap.points.is_empty(), "{name}: no points");
    let path = tmp.join(&format!("{name}.json"));
    write_json(&path, &scenario(sim, &snap, name));
    let r = reference_solve3(&path, tmp.join(&format!("{name}.ref.json")));
    let pr = r["point_reactions"].as_array().expect("point reactions");
    assert_eq!(pr.len(), snap.points.len());
    let num = |v: &Value| v.as_f64().expect("a number");
    let mut ref_force = Vec::new();
    let mut ref_u = Vec::new();
    for (e, p) in pr.iter().zip(&snap.points) {
        let f = p.f_n.unwrap_or([0.0; 3]);
        ref_force.push([num(&e["rx"]) + f[0], num(&e["ry"]) + f[1], num(&e["rz"]) + f[2]]);
        ref_u.push([num(&e["u"][0]), num(&e["u"][1]), num(&e["u"][2])]);
    }
    let ours_f: Vec<[f64; 3]> = snap.points.iter().map(|p| p.force_n).collect();
    let ours_u: Vec<[f64; 3]> = snap.points.iter().map(|p| p.u_m).collect();
    let (ef, eu) = (rel(&ours_f, &ref_force), rel(&ours_u, &ref_u));
    let states: Vec<PointState3> = sim.output().contacts.iter().map(|c| c.state).collect();
    println!(
        "{name} (tick {}, {} nodes): {states:?}: forces rel err {ef:e}, displacements rel err {eu:e}",
        snap.tick,
        sim.model().mesh().n_nodes()
    );
    (ef, eu)
}

#[test]
fn snapshots_match_the_reference_solver_through_insertion_turn_and_withdrawal() {
    // 9³: three points along the shaft (the distance rule at 21.7 mm tetrahedra); 11³: more.
    for n in [9, 11] {
        snapshots_match_on(n);
    }
}

fn snapshots_match_on(n: usize) {
    let mut sim = Simulation3::new(box_phantom3(n), box_phantom3_params(ENTRY, 0.005)).unwrap();
    let tmp = TempDir::new(&format!("sim3_{n}"));
    let v = 2e-5;
    let start = sim.pose();
    let along = |p: BasePose3, d: f64| {
        let t = p.axis();
        BasePose3::from_rotation([p.position_m[0] + d * t[0], p.position_m[1] + d * t[1], p.position_m[2] + d * t[2]], p.orientation)
    };
    let step = |sim: &mut Simulation3, p: BasePose3| {
        sim.step(p).unwrap();
        sim.prefetch_columns(usize::MAX).unwrap();
    };
    let mut results = Vec::new();
    // Insertion until the tip carries a point with at least two slipping points behind it.
    let mut k = 0;
    let mut pose = start;
    let mut checked_tip = false;
    while k < 3250 {
        k += 1;
        pose = along(start, v * k as f64);
        step(&mut sim, pose);
        let c = &sim.output().contacts;
        let tip = c.iter().any(|c| c.state == PointState3::Tip);
        let slipping = c.iter().filter(|c| c.state == PointState3::Slipping).count();
        if !checked_tip && tip && slipping >= 2 {
            results.push(("mid_insertion_tip", check(&sim, &tmp, "mid_insertion_tip")));
            checked_tip = true;
        }
    }
    assert!(checked_tip, "the tip carried a point with two slipping behind it");
    results.push(("slipping", check(&sim, &tmp, "slipping")));
    assert!(sim.output().contacts.iter().filter(|c| c.state == PointState3::Slipping).count() >= 2);
    for _ in 0..200 {
        step(&mut sim, pose);
    }
    results.push(("hold_stuck", check(&sim, &tmp, "hold_stuck")));
    for j in 1..=500 {
        step(&mut sim, pose.rotated_about_axis(ENTRY, [0.0, 1.0, 0.0], 10f64.to_radians() * j as f64 / 500.0));
    }
    let pose = sim.pose();
    results.push(("after_rotation", check(&sim, &tmp, "after_rotation")));
    for j in 1..=1500 {
        step(&mut sim, along(pose, -v * j as f64));
    }
    assert!(sim.output().axial_force_n < 0.0, "withdrawing");
    results.push(("withdrawal", check(&sim, &tmp, "withdrawal")));
    let failures: Vec<String> = results
        .iter()
        .filter(|(_, (ef, eu))| !(*ef <= 1e-8 && *eu <= 1e-9))
        .map(|(n, (ef, eu))| format!("{n}: forces {ef:e} (tol 1e-8), displacements {eu:e} (tol 1e-9)"))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
