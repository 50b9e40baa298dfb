//! The 3D simulation's wrench stiffness ([`Simulation3::wrench_stiffness`]) against central
//! differences of the frozen-active-set problem and its derived properties, and its targets
//! (spheres moving with the tissue, hit or miss latched) on the cube phantom: hit, miss, the
//! displaced centre against an exact static solve, validation, no allocation in a warm step or
//! a warm stiffness call.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use needlesim_alloc_count::{CountingAlloc, count_on_this_thread, thread_allocations};
use needlesim_core::d3::{PointCondition, TetNodeCondition, TetStaticProblem};
use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
use needlesim_core::sim3::{
    BasePose3, MAX_TARGETS, PointState3, Sim3Params, SimError3, Simulation3, Target3, TargetState3, WrenchStiffness3, unit_axis,
};

#[global_allocator]
static GLOBAL: CountingAlloc = CountingAlloc::new();

/// Off-node entry point on the top face (z = 0.1 m).
const ENTRY: [f64; 3] = [0.0513, 0.0487, 0.1];
/// Insertion speed, m per 1 ms tick (20 mm/s).
const V: f64 = 2e-5;

fn along(p: BasePose3, d: f64) -> BasePose3 {
    let t = p.axis();
    BasePose3::from_rotation([p.position_m[0] + d * t[0], p.position_m[1] + d * t[1], p.position_m[2] + d * t[2]], p.orientation)
}

/// The phases: insert 65 mm (tip from 5 mm above to 60 mm deep), hold 300 ticks, turn 10°
/// about world y through the entry point over 500 ticks, withdraw 90 mm along the turned axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Insert,
    Hold,
    Rotate,
    Withdraw,
}

fn poses(start: BasePose3) -> Vec<(Phase, BasePose3)> {
    let mut v = Vec::new();
    let n_in = 3250;
    for k in 1..=n_in {
        v.push((Phase::Insert, along(start, V * k as f64)));
    }
    let at = along(start, V * n_in as f64);
    v.extend(std::iter::repeat_n((Phase::Hold, at), 300));
    for k in 1..=500 {
        let r = UnitQuaternion::from_axis_angle(&unit_axis([0.0, 1.0, 0.0]), 10f64.to_radians() * k as f64 / 500.0);
        v.push((Phase::Rotate, at.rotated_about(ENTRY, &r)));
    }
    let at = v.last().unwrap().1;
    for k in 1..=4500 {
        v.push((Phase::Withdraw, along(at, -V * k as f64)));
    }
    v
}

fn step(sim: &mut Simulation3, pose: BasePose3) -> u64 {
    let before = thread_allocations();
    count_on_this_thread(true);
    let r = sim.step(pose).map(|_| ());
    count_on_this_thread(false);
    let n = thread_allocations() - before;
    r.unwrap();
    sim.prefetch_columns(usize::MAX).unwrap();
    n
}

// ---------------------------------------------------------------------------------------------
// Wrench stiffness.

/// The pose moved by $\delta q = (\delta x_b, \theta)$: $x_b + \delta x_b$,
/// $R \leftarrow \exp(\hat\theta) R$ (about the base point).
fn perturbed(p: BasePose3, dq: [f64; 6]) -> BasePose3 {
    let rot = UnitQuaternion::from_scaled_axis(Vector3::new(dq[3], dq[4], dq[5]));
    BasePose3::from_rotation([p.position_m[0] + dq[0], p.position_m[1] + dq[1], p.position_m[2] + dq[2]], rot * p.orientation)
}

/// Central differences of the frozen-active-set wrench, steps `h_m` and `h_rad`.
fn fd_stiffness(sim: &Simulation3, h_m: f64, h_rad: f64) -> [[f64; 6]; 6] {
    let pose = sim.pose();
    let mut k = [[0.0; 6]; 6];
    for c in 0..6 {
        let h = if c < 3 { h_m } else { h_rad };
        let mut dq = [0.0; 6];
        dq[c] = h;
        let (fp, tp) = sim.frozen_active_set_wrench(&perturbed(pose, dq)).unwrap();
        dq[c] = -h;
        let (fm, tm) = sim.frozen_active_set_wrench(&perturbed(pose, dq)).unwrap();
        for r in 0..3 {
            k[r][c] = (fp[r] - fm[r]) / (2.0 * h);
            k[3 + r][c] = (tp[r] - tm[r]) / (2.0 * h);
        }
    }
    k
}

/// $K$ in consistent units (N): positions scaled by the needle length $\ell$, torques divided
/// by it: $\tilde K = \mathrm{diag}(1, 1/\ell)\,K\,\mathrm{diag}(\ell, 1)$.
fn scaled(k: &[[f64; 6]; 6], ell: f64) -> [[f64; 6]; 6] {
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let mut v = k[r][c];
            if r >= 3 {
                v /= ell;
            }
            if c < 3 {
                v *= ell;
            }
            v
        })
    })
}

fn max_abs(k: &[[f64; 6]; 6]) -> f64 {
    k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()))
}

struct Checked {
    label: &'static str,
    fd_rel_err: f64,
}

/// Checks $K$ at the simulation's state: central differences, the symmetric negative
/// semidefinite force–position block, the roll column, and (with `all_slipping`) the axial
/// push column (derivations in the stiffness module docs). Also: the frozen problem at the
/// step's own pose reproduces the step's wrench, and a warm call allocates nothing.
fn check_stiffness(sim: &mut Simulation3, label: &'static str, all_slipping: bool) -> Checked {
    let ell = sim.params().needle_length_m;
    let out = sim.output().clone();
    let (f0, t0) = sim.frozen_active_set_wrench(&sim.pose()).unwrap();
    let wscale = out.base_force_n.iter().chain(&out.base_torque_nm.map(|v| v / ell)).fold(0.0f64, |m, v| m.max(v.abs()));
    for r in 0..3 {
        assert!((f0[r] - out.base_force_n[r]).abs() <= 1e-9 * wscale, "{label}: frozen force {f0:?} vs step {:?}", out.base_force_n);
        assert!(
            (t0[r] - out.base_torque_nm[r]).abs() / ell <= 1e-9 * wscale,
            "{label}: frozen torque {t0:?} vs step {:?}",
            out.base_torque_nm
        );
    }
    let k: WrenchStiffness3 = sim.wrench_stiffness().unwrap();
    // A warm call allocates nothing.
    let before = thread_allocations();
    count_on_this_thread(true);
    let again = sim.wrench_stiffness();
    count_on_this_thread(false);
    assert_eq!(thread_allocations() - before, 0, "{label}: a warm wrench_stiffness call allocated");
    assert_eq!(again.unwrap(), k, "{label}: two calls differ");

    let ks = scaled(&k.matrix, ell);
    let scale = max_abs(&ks);
    assert!(scale > 0.0);
    let fd = scaled(&fd_stiffness(sim, 1e-7, 1e-7), ell);
    let mut err: f64 = 0.0;
    for r in 0..6 {
        for c in 0..6 {
            err = err.max((fd[r][c] - ks[r][c]).abs());
        }
    }
    let fd_rel_err = err / scale;
    println!("{label}: max |K| (scaled) {scale:.4e} N, FD relative error {fd_rel_err:.2e}; K = {:?}", k.matrix);
    assert!(fd_rel_err < 1e-6, "{label}: K differs from central differences by {fd_rel_err:e} (relative)\nK  = {ks:?}\nFD = {fd:?}");

    // ∂F/∂x_b = −E_P H_PP E_Pᵀ: symmetric, negative semidefinite.
    let kfx = k.force_position();
    let fx_scale = kfx.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let m = Matrix3::from_fn(|r, c| kfx[r][c]);
    let asym = (m - m.transpose()).abs().max();
    assert!(asym <= 1e-9 * fx_scale, "{label}: force-position block not symmetric: {asym:e} of {fx_scale:e}\n{kfx:?}");
    let eig = (0.5 * (m + m.transpose())).symmetric_eigenvalues();
    assert!(eig.iter().all(|&e| e <= 1e-9 * fx_scale), "{label}: force-position block not negative semidefinite: {eig:?}");
    // A roll about the needle axis changes nothing.
    let t = sim.pose().axis();
    let roll = k.apply([0.0, 0.0, 0.0, t[0], t[1], t[2]]);
    for (r, v) in roll.iter().enumerate() {
        let v = if r < 3 { *v } else { v / ell };
        assert!(v.abs() <= 1e-9 * scale, "{label}: roll column row {r} = {v:e} (scale {scale:e})");
    }
    if all_slipping {
        // K (t, 0) = (0, t × Σ f_i) = (0, F × t).
        let f = out.base_force_n;
        let expect = [0.0, 0.0, 0.0, f[1] * t[2] - f[2] * t[1], f[2] * t[0] - f[0] * t[2], f[0] * t[1] - f[1] * t[0]];
        let push = k.apply([t[0], t[1], t[2], 0.0, 0.0, 0.0]);
        for (r, (v, e)) in push.iter().zip(expect).enumerate() {
            // Force rows in N/m, torque rows in N: both in N as in the scaled K.
            let err = if r < 3 { (v - e).abs() * ell } else { (v - e).abs() };
            assert!(err <= 1e-9 * scale, "{label}: axial push, row {r}: {v:e} vs {e:e}");
        }
    }
    Checked { label, fd_rel_err }
}

#[test]
fn wrench_stiffness_equals_central_differences_of_the_frozen_problem() {
    let mut sim = Simulation3::new(box_phantom3(9), box_phantom3_params(ENTRY, 0.005)).unwrap();
    let mut done: Vec<Checked> = Vec::new();
    let mut prev_phase = Phase::Insert;
    for (phase, pose) in poses(sim.pose()) {
        if phase == Phase::Withdraw && prev_phase == Phase::Rotate {
            let n = sim.output().contacts.len();
            assert!(n >= 2, "{n} points after the turn");
            done.push(check_stiffness(&mut sim, "after a 10° turn", false));
        }
        if phase == Phase::Rotate && prev_phase == Phase::Hold {
            let c = &sim.output().contacts;
            assert!(
                c.len() >= 2 && c.iter().all(|c| c.state != PointState3::Slipping),
                "hold: {:?}",
                c.iter().map(|c| c.state).collect::<Vec<_>>()
            );
            done.push(check_stiffness(&mut sim, "at rest, no point slipping", false));
        }
        prev_phase = phase;
        step(&mut sim, pose);
        if phase != Phase::Insert || sim.stats().punctures == 0 {
            continue;
        }
        let c = &sim.output().contacts;
        let count = |s: PointState3| c.iter().filter(|c| c.state == s).count();
        let (n_slip, n_tip, n) = (count(PointState3::Slipping), count(PointState3::Tip), c.len());
        if n_tip == 1 && n_slip >= 2 && !done.iter().any(|d| d.label == "tip and slipping") {
            done.push(check_stiffness(&mut sim, "tip and slipping", false));
        }
        if n_slip == n && n_slip >= 3 && !done.iter().any(|d| d.label == "all slipping") {
            done.push(check_stiffness(&mut sim, "all slipping", true));
        }
    }
    let labels: Vec<&str> = done.iter().map(|d| d.label).collect();
    println!("checked: {labels:?}, worst FD error {:e}", done.iter().map(|d| d.fd_rel_err).fold(0.0, f64::max));
    assert_eq!(done.len(), 4, "states reached: {labels:?}");
}

#[test]
fn no_working_point_no_stiffness() {
    // No working point: the stiffness is zero.
    let mut sim = Simulation3::new(box_phantom3(5), box_phantom3_params(ENTRY, 0.005)).unwrap();
    sim.step(sim.pose()).unwrap();
    assert_eq!(sim.wrench_stiffness().unwrap().matrix, [[0.0; 6]; 6]);
}

// ---------------------------------------------------------------------------------------------
// Targets.

fn params_with(targets: Vec<Target3>) -> Sim3Params {
    let mut p = box_phantom3_params(ENTRY, 0.005);
    p.targets = targets;
    p
}

/// Runs the insertion (65 mm), hold, turn and withdrawal with `targets`, recording each tick's
/// targets; asserts a warm step allocates nothing.
fn run_targets(targets: Vec<Target3>) -> (Simulation3, Vec<Vec<needlesim_core::sim3::TargetOut3>>) {
    let mut sim = Simulation3::new(box_phantom3(9), params_with(targets)).unwrap();
    let mut rec = Vec::new();
    let poses = poses(sim.pose());
    for (k, (_, pose)) in poses.into_iter().enumerate() {
        let allocations = step(&mut sim, pose);
        if k > 50 {
            assert_eq!(allocations, 0, "tick {k}: a warm step with targets allocated");
        }
        rec.push(sim.output().targets.as_slice().to_vec());
    }
    (sim, rec)
}

/// The latch of target `i` happens at the first tick its rule holds, and never changes after.
fn check_latch(rec: &[Vec<needlesim_core::sim3::TargetOut3>], i: usize, radius: f64, expect: TargetState3) -> u64 {
    let first = rec.iter().position(|r| r[i].state != TargetState3::Pending).unwrap_or_else(|| panic!("target {i} never latched"));
    let o = rec[first][i];
    assert_eq!(o.state, expect, "target {i}: {o:?}");
    assert_eq!(o.latched_tick, Some(first as u64), "target {i}: the latch tick is the tick of the output");
    for r in &rec[..first] {
        assert!(r[i].distance_m > radius, "target {i} was within its radius before the latch");
        assert!(r[i].latched_tick.is_none());
    }
    match expect {
        TargetState3::Hit => assert!(o.distance_m <= radius),
        TargetState3::Missed => {
            assert!(-o.ahead_m > radius, "{o:?}");
            assert!(rec[..first].iter().any(|r| -r[i].ahead_m <= radius), "missed without having been ahead");
            assert!(rec[first - 1][i].ahead_m >= -radius, "the tick before the miss the target had not been passed");
        }
        TargetState3::Pending => unreachable!(),
    }
    for r in &rec[first..] {
        assert_eq!((r[i].state, r[i].latched_tick), (expect, o.latched_tick), "target {i} un-latched");
    }
    o.latched_tick.unwrap()
}

#[test]
fn a_target_on_the_axis_is_hit_and_one_off_the_axis_is_missed() {
    let r = 0.002;
    let on_axis = Target3 { centre_m: [ENTRY[0], ENTRY[1], 0.06], radius_m: r, name_idx: 7 };
    let off_axis = Target3 { centre_m: [ENTRY[0] + 0.006, ENTRY[1], 0.06], radius_m: r, name_idx: 3 };
    let (mut sim, rec) = run_targets(vec![on_axis, off_axis]);
    let hit = check_latch(&rec, 0, r, TargetState3::Hit);
    let miss = check_latch(&rec, 1, r, TargetState3::Missed);
    let (h, m) = (rec[hit as usize][0], rec[miss as usize][1]);
    println!("on axis: hit at tick {hit}, distance {:.3} mm, displacement {:?} m", h.distance_m * 1e3, h.displacement_m);
    println!("off axis: missed at tick {miss}, distance {:.3} mm, displacement {:?} m", m.distance_m * 1e3, m.displacement_m);
    assert_eq!((h.name_idx, m.name_idx), (7, 3));
    // The tissue moved the targets (the needle pushes it down).
    assert!(h.displacement_m[2] < 0.0 && m.displacement_m[2] < 0.0);
    // Reset: pending again, then latched anew by the next steps' rule.
    sim.reset_targets();
    assert!(sim.output().targets.as_slice().iter().all(|o| o.state == TargetState3::Pending && o.latched_tick.is_none()));
}

#[test]
fn the_displaced_centre_equals_an_exact_static_solve_of_the_snapshot() {
    let centre = [ENTRY[0] + 0.004, ENTRY[1] - 0.003, 0.05];
    let mut sim = Simulation3::new(box_phantom3(9), params_with(vec![Target3 { centre_m: centre, radius_m: 0.001, name_idx: 0 }])).unwrap();
    let model = sim.model().clone();
    let mesh = model.mesh();
    let loc = model.locate(centre).unwrap();
    let fixed: Vec<(usize, TetNodeCondition)> =
        mesh.boundary_set("bottom").unwrap().iter().map(|&n| (n, TetNodeCondition::Fixed)).collect();
    let checks = [1500usize, 3000, 3400, 3800, 4300];
    let mut n_checked = 0;
    for (k, (_, pose)) in poses(sim.pose()).into_iter().enumerate() {
        step(&mut sim, pose);
        if !checks.contains(&k) {
            continue;
        }
        let snap = sim.snapshot();
        assert!(!snap.points.is_empty(), "tick {k}: no points");
        let problem = TetStaticProblem {
            conditions: fixed.clone(),
            loads_n: Vec::new(),
            points: snap
                .points
                .iter()
                .map(|p| PointCondition { x_m: p.x_m, frame: p.frame, u_m: [p.ut, p.un, p.ub], force_n: p.f_n.unwrap_or([0.0; 3]) })
                .collect(),
            patches: vec![],
        };
        let sol = problem.solve(mesh, model.materials()).unwrap();
        let u_ref: [f64; 3] =
            std::array::from_fn(|c| (0..4).map(|a| loc.weights[a] * sol.displacement_m[3 * loc.nodes[a] + c]).sum::<f64>());
        let o = sim.output().targets.as_slice()[0];
        let scale = sol.displacement_m.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = (0..3).map(|c| (o.displacement_m[c] - u_ref[c]).abs()).fold(0.0, f64::max);
        let states: Vec<PointState3> = sim.output().contacts.iter().map(|c| c.state).collect();
        println!(
            "tick {k}: {states:?}: target u {:?} vs exact {u_ref:?}, error {:.2e} of max |u| {scale:.3e}",
            o.displacement_m,
            err / scale
        );
        assert!(err <= 1e-9 * scale, "tick {k}: displaced centre off by {err:e} (max |u| {scale:e})");
        for ((x, x0), u) in o.centre_m.iter().zip(centre).zip(o.displacement_m) {
            assert_eq!(*x, x0 + u);
        }
        n_checked += 1;
    }
    assert_eq!(n_checked, checks.len());
}

#[test]
fn bad_targets_are_refused_naming_them() {
    let good = Target3 { centre_m: [0.05, 0.05, 0.05], radius_m: 0.002, name_idx: 0 };
    let cases: Vec<(Vec<Target3>, &str)> = vec![
        (vec![good, Target3 { radius_m: 0.0, ..good }], "targets[1]: radius_m = 0"),
        (vec![Target3 { radius_m: f64::NAN, ..good }], "targets[0]: radius_m = NaN"),
        (vec![good, good, Target3 { centre_m: [0.05, f64::INFINITY, 0.05], ..good }], "targets[2]: centre_m"),
        (vec![good, Target3 { centre_m: [0.05, 0.05, 0.15], ..good }], "targets[1]: the centre"),
        (vec![good; MAX_TARGETS + 1], "at most"),
    ];
    let model = box_phantom3(5);
    for (targets, expect) in cases {
        let e = Simulation3::new(model.clone(), params_with(targets)).err().expect("refused");
        assert!(matches!(e, SimError3::InvalidParams(_)), "{e}");
        assert!(e.to_string().contains(expect), "{e} does not contain {expect:?}");
    }
    assert!(Simulation3::new(model, params_with(vec![good; MAX_TARGETS])).is_ok());
}

// ---------------------------------------------------------------------------------------------
// Timing (not asserted): `cargo test --release -p needlesim-core --test sim3_stiffness_targets
// -- --ignored --nocapture timing`.

fn percentiles(mut v: Vec<f64>) -> String {
    v.sort_by(f64::total_cmp);
    let q = |p: f64| v[((v.len() - 1) as f64 * p).round() as usize];
    format!("n {} p50 {:.2} p99 {:.2} p99.9 {:.2} max {:.2} µs", v.len(), q(0.5), q(0.99), q(0.999), v[v.len() - 1])
}

/// Step time with [`MAX_TARGETS`] targets and the time of a warm wrench-stiffness call, over the
/// insertion, hold, turn and withdrawal on the 21³ cube phantom.
#[test]
#[ignore = "timing: run in release, on a quiet machine"]
fn timing_of_the_stiffness_and_of_steps_with_targets() {
    let targets: Vec<Target3> = (0..MAX_TARGETS)
        .map(|k| Target3 { centre_m: [0.03 + 0.003 * k as f64, 0.05, 0.02 + 0.004 * k as f64], radius_m: 0.002, name_idx: k })
        .collect();
    let mut sim = Simulation3::new(box_phantom3(21), params_with(targets)).unwrap();
    let (mut t_step, mut t_k, mut max_points) = (Vec::new(), Vec::new(), 0);
    for (_, pose) in poses(sim.pose()) {
        let t0 = std::time::Instant::now();
        sim.step(pose).unwrap();
        t_step.push(t0.elapsed().as_secs_f64() * 1e6);
        let n = sim.output().contacts.len();
        max_points = max_points.max(n);
        if n > 0 {
            let t0 = std::time::Instant::now();
            std::hint::black_box(sim.wrench_stiffness().unwrap());
            t_k.push(t0.elapsed().as_secs_f64() * 1e6);
        }
        sim.prefetch_columns(usize::MAX).unwrap();
    }
    println!("21³ phantom, {MAX_TARGETS} targets, up to {max_points} points");
    println!("step: {}", percentiles(t_step));
    println!("wrench_stiffness: {}", percentiles(t_k));
}

/// Targets observe only: the same run with and without them gives the same wrench and points
/// bit for bit, and the stiffness call changes nothing either.
#[test]
fn targets_and_the_stiffness_change_nothing_in_the_simulation() {
    let t = Target3 { centre_m: [ENTRY[0], ENTRY[1], 0.07], radius_m: 0.002, name_idx: 0 };
    let mut with = Simulation3::new(box_phantom3(7), params_with(vec![t; 4])).unwrap();
    let mut without = Simulation3::new(box_phantom3(7), params_with(Vec::new())).unwrap();
    for (k, (_, pose)) in poses(with.pose()).into_iter().enumerate().take(2500) {
        step(&mut with, pose);
        step(&mut without, pose);
        if k % 7 == 0 && !with.output().contacts.is_empty() {
            with.wrench_stiffness().unwrap();
        }
        let (a, b) = (with.output(), without.output());
        assert_eq!((a.base_force_n, a.base_torque_nm, &a.contacts), (b.base_force_n, b.base_torque_nm, &b.contacts), "tick {k}");
    }
    assert!(with.stats().captures >= 2);
}
