//! Physics of the insertion model: force against depth, puncture, withdrawal, stick–slip,
//! re-insertion, frames of a rotating needle against a fresh static solve, bad poses, and the
//! guarantee that no step refactorises the stiffness.

use needlesim_core::fixtures::{phantom, phantom_params};
use needlesim_core::sim::{SimParams, Simulation, StepOutput, TargetParams};
use needlesim_core::{BasePose, NeedleShape, NodeCondition, RegionNeedleParams, RigidNeedle, StaticProblem};

const FRAC_PI_2: f64 = std::f64::consts::FRAC_PI_2;

fn params(region: RegionNeedleParams, base: BasePose) -> SimParams {
    SimParams {
        initial_pose: base,
        regions: vec![region],
        targets: vec![TargetParams { name: "c".into(), center_m: [0.05, 0.05], radius_m: 0.001 }],
        ..phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))
    }
}

/// A vertical needle above the top edge, tip 5 mm outside.
fn top_base() -> BasePose {
    BasePose::new(0.05, 0.205, -FRAC_PI_2)
}

/// Steps along `poses`, prefetching columns between steps as the server's worker does.
fn run(sim: &mut Simulation, poses: impl IntoIterator<Item = BasePose>) -> Vec<StepOutput> {
    let mut outs = Vec::new();
    for p in poses {
        outs.push(sim.step(p).unwrap().clone());
        sim.prefetch_columns(16).unwrap();
    }
    outs
}

/// Vertical moves of the base at `speed` m/s from y0 to y1, one pose per 1 ms tick.
fn vertical(y0: f64, y1: f64, speed: f64) -> Vec<BasePose> {
    let n = ((y1 - y0).abs() / speed * 1000.0).round() as usize;
    (1..=n).map(|k| BasePose::new(0.05, y0 + (y1 - y0) * k as f64 / n as f64, -FRAC_PI_2)).collect()
}

fn uniform_friction() -> RegionNeedleParams {
    RegionNeedleParams { tip_peak_ratio: 0.0, ..RegionNeedleParams::default() }
}

/// Least-squares line and R².
fn fit(xs: &[f64], ys: &[f64]) -> (f64, f64, f64) {
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    let syy: f64 = ys.iter().map(|y| (y - my).powi(2)).sum();
    let slope = sxy / sxx;
    (slope, my - slope * mx, sxy * sxy / (sxx * syy))
}

#[test]
fn axial_force_grows_linearly_with_depth_under_uniform_friction() {
    let model = phantom(19);
    let region = uniform_friction();
    let mut sim = Simulation::new(model.clone(), params(region, top_base())).unwrap();
    let outs = run(&mut sim, vertical(0.205, 0.14, 0.01));
    // After the skin is punctured: depth against resisting force.
    let (mut depth, mut force) = (Vec::new(), Vec::new());
    for o in &outs {
        if o.inserted_length_m > 0.01 {
            depth.push(o.inserted_length_m);
            force.push(-o.force_axial_n);
        }
    }
    assert!(depth.len() > 3000, "the needle reached {} m", outs.last().unwrap().inserted_length_m);
    let (slope, _, r2) = fit(&depth, &force);
    // The friction is q0 per metre of inserted shaft; the tip's cutting adds a small sawtooth.
    assert!(
        (slope - region.friction_n_per_m).abs() < 0.05 * region.friction_n_per_m,
        "slope {slope} N/m vs q0 {}",
        region.friction_n_per_m
    );
    assert!(r2 > 0.98, "force against depth is not linear: R² = {r2}");
    // Every resisting force points back along the needle.
    assert!(outs.iter().all(|o| o.force_axial_n <= 1e-12));
    assert_eq!(sim.stats().column_misses, 0, "prefetch kept up");
}

#[test]
fn force_rises_then_drops_at_skin_puncture() {
    let model = phantom(19);
    let region = RegionNeedleParams::default();
    let mut sim = Simulation::new(model, params(region, top_base())).unwrap();
    let outs = run(&mut sim, vertical(0.205, 0.19, 0.01));
    let first_puncture = outs.windows(2).position(|w| w[0].n_tip == 1 && w[1].n_tip == 0).expect("the skin is punctured");
    let before = -outs[first_puncture].force_axial_n;
    let after = -outs[first_puncture + 1].force_axial_n;
    // The carried surface node rises to the puncture force, then the force drops to friction.
    assert!(before >= 0.95 * region.puncture_force_n && before <= region.puncture_force_n * 1.05, "peak {before} N");
    assert!(after < 0.3 * before, "after puncture {after} N vs {before} N before");
    // The rise is gradual: the surface indents over several ticks.
    let rise_ticks = outs[..first_puncture].iter().filter(|o| o.n_tip == 1).count();
    assert!(rise_ticks > 50, "rise over {rise_ticks} ticks");
    assert_eq!(sim.stats().punctures as usize, outs.windows(2).filter(|w| w[0].n_tip == 1 && w[1].n_tip == 0).count());
}

#[test]
fn force_changes_sign_on_withdrawal_and_reinsertion_works() {
    let model = phantom(19);
    let mut sim = Simulation::new(model, params(uniform_friction(), top_base())).unwrap();
    let ins = run(&mut sim, vertical(0.205, 0.15, 0.01));
    let out = run(&mut sim, vertical(0.15, 0.205, 0.01));
    let depth_max = ins.last().unwrap().inserted_length_m;
    assert!(depth_max > 0.04);
    // Withdrawing, the tissue holds the needle in: the force on the base points along +t.
    let withdrawing: Vec<_> = out.iter().filter(|o| o.inserted_length_m > 0.005 && o.inserted_length_m < depth_max - 0.005).collect();
    assert!(withdrawing.len() > 1000);
    assert!(withdrawing.iter().all(|o| o.force_axial_n > 0.0), "withdrawal force must pull inwards");
    let end = out.last().unwrap();
    assert_eq!(end.needle_nodes.len(), 0, "all nodes released once withdrawn");
    assert!(end.force_n[0].abs() + end.force_n[1].abs() < 1e-12);
    // Re-insertion along the same track meets the same tissue again.
    let again = run(&mut sim, vertical(0.205, 0.15, 0.01));
    let (f1, f2) = (-ins.last().unwrap().force_axial_n, -again.last().unwrap().force_axial_n);
    assert!((f1 - f2).abs() < 0.05 * f1, "first {f1} N, again {f2} N");
    assert!((again.last().unwrap().inserted_length_m - depth_max).abs() < 0.002);
}

#[test]
fn pause_sticks_every_node_and_restart_breaks_away() {
    let model = phantom(19);
    let region = uniform_friction();
    let mut sim = Simulation::new(model, params(region, top_base())).unwrap();
    let ins = run(&mut sim, vertical(0.205, 0.16, 0.01));
    let level = -ins.last().unwrap().force_axial_n;
    assert!(ins.last().unwrap().n_slipping > 3, "steady insertion slips");
    // Hold still: relative motion stops, every shaft node sticks.
    let hold = run(&mut sim, std::iter::repeat_n(BasePose::new(0.05, 0.16, -FRAC_PI_2), 200));
    let h = hold.last().unwrap();
    assert_eq!(h.n_slipping, 0);
    assert_eq!(h.n_stuck, h.needle_nodes.len());
    assert!((-h.force_axial_n - level).abs() < 1e-9 * level.max(1.0) + 0.05 * level);
    // Restart: stuck nodes load up beyond kinetic friction before they slip (stick–slip).
    let restart = run(&mut sim, vertical(0.16, 0.15, 0.01));
    let mixed = restart.iter().filter(|o| o.n_stuck > 0 && o.n_slipping > 0).count();
    assert!(mixed > 0, "nodes break away one after another");
    let peak = restart.iter().map(|o| -o.force_axial_n).fold(0.0, f64::max);
    let steady = -restart.last().unwrap().force_axial_n;
    assert!(peak > 1.1 * level, "breakaway peak {peak} N over kinetic level {level} N");
    assert!(restart.iter().take(20).any(|o| o.n_stuck > 0));
    assert!(steady < peak);
    let st = sim.stats();
    assert!(st.stick_to_slip > 5 && st.slip_to_stick > 5, "{st:?}");
}

#[test]
fn no_step_refactorises_and_prefetch_avoids_misses() {
    let model = phantom(19);
    assert_eq!(model.cholesky().n_numeric_factorisations(), 1);
    let mut sim = Simulation::new(model.clone(), params(RegionNeedleParams::default(), top_base())).unwrap();
    run(&mut sim, vertical(0.205, 0.14, 0.01));
    run(&mut sim, vertical(0.14, 0.205, 0.01));
    assert_eq!(model.cholesky().n_numeric_factorisations(), 1, "a step refactorised K");
    assert!(sim.stats().ticks > 12_000);
    assert_eq!(sim.stats().column_misses, 0);
    assert!(sim.stats().captures > 10);
    // Without prefetch the step computes columns itself, and counts each one.
    let mut cold = Simulation::new(model.clone(), params(RegionNeedleParams::default(), top_base())).unwrap();
    for p in vertical(0.205, 0.17, 0.01) {
        cold.step(p).unwrap();
    }
    assert!(cold.stats().column_misses > 3);
    assert_eq!(cold.stats().column_misses, cold.cache().len() as u64, "every cached column was a miss");
    assert_eq!(model.cholesky().n_numeric_factorisations(), 1);
}

/// The simulator's state, re-solved as a full static problem with the same local-frame
/// conditions, gives the same displacement field: checks frames, values and forces of a needle
/// that is inserted obliquely and then rotated.
#[test]
fn rotating_oblique_needle_state_equals_fresh_static_solve() {
    let model = phantom(25);
    let a0 = -1.2;
    let entry = [0.03, 0.1];
    let base_at = |d: f64, a: f64| BasePose::new(entry[0] + (d - 0.1) * a.cos(), entry[1] + (d - 0.1) * a.sin(), a);
    let mut sim = Simulation::new(model.clone(), params(RegionNeedleParams::default(), base_at(-0.004, a0))).unwrap();
    let mut poses: Vec<BasePose> = (1..=4000).map(|k| base_at(-0.004 + 0.044 * k as f64 / 4000.0, a0)).collect();
    // Rotate about the entry point by 0.1 rad while holding the depth.
    let last = *poses.last().unwrap();
    poses.extend((1..=500).map(|k| {
        let a = a0 + 0.1 * k as f64 / 500.0;
        let d = 0.04;
        let _ = last;
        base_at(d, a)
    }));
    let outs = run(&mut sim, poses);
    let o = outs.last().unwrap();
    assert!(o.needle_nodes.len() >= 5, "{} needle nodes", o.needle_nodes.len());
    assert!(sim.solver().stats().n_rotations > 100);
    assert!(o.torque_nm.abs() > 0.0);
    let snap = sim.snapshot();
    let mut problem = StaticProblem {
        conditions: model.mesh().boundary_set("bottom").unwrap().iter().map(|&n| (n, NodeCondition::Fixed)).collect(),
        loads_n: snap.node_loads_n(),
        points: vec![],
        patches: vec![],
    };
    for c in &snap.conditions {
        problem.conditions.push((c.node_idx, NodeCondition::Local { frame: c.angle_rad, u_m: [c.ut_m, c.un_m] }));
    }
    let fresh = problem.solve(model.mesh(), model.materials()).unwrap();
    let mut u = vec![0.0; model.n_dofs()];
    sim.displacement_field_into(&mut u);
    let norm = fresh.displacement_m.iter().map(|v| v * v).sum::<f64>().sqrt();
    let diff = u.iter().zip(&fresh.displacement_m).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
    assert!(diff < 1e-9 * norm, "rel diff {}", diff / norm);
    // The base force equals minus the sum of the static reactions on the needle nodes.
    let mut f = [0.0; 2];
    for (node, r) in &fresh.reactions_n {
        if snap.conditions.iter().any(|c| c.node_idx == *node) {
            f[0] -= r[0].unwrap();
            f[1] -= r[1].unwrap();
        }
    }
    for (node, l) in &snap.node_loads_n() {
        let _ = node;
        f[0] -= l[0];
        f[1] -= l[1];
    }
    for k in 0..2 {
        assert!((f[k] - o.force_n[k]).abs() < 1e-8 * (o.force_n[0].hypot(o.force_n[1])), "force {f:?} vs {:?}", o.force_n);
    }
}

#[test]
fn bad_poses_are_rejected_or_clamped_and_state_stays_valid() {
    let model = phantom(19);
    let mut sim = Simulation::new(model, params(RegionNeedleParams::default(), top_base())).unwrap();
    run(&mut sim, vertical(0.205, 0.17, 0.01));
    let before = sim.output().clone();
    let pose = sim.pose();
    let e = sim.step(BasePose::new(f64::NAN, 0.17, -FRAC_PI_2)).unwrap_err();
    assert!(e.to_string().contains("not finite") && e.to_string().contains("rejected"), "{e}");
    assert_eq!(sim.pose(), pose);
    assert_eq!(sim.output().tick, before.tick);
    assert_eq!(sim.stats().ticks, before.tick + 1);
    assert_eq!(sim.stats().rejected_poses, 1);
    // A 5 cm jump in one tick moves the base by the configured 2 mm only.
    let o = sim.step(BasePose::new(0.05, 0.12, -FRAC_PI_2)).unwrap().clone();
    assert!(o.clamped);
    assert!((o.base.y_m - (0.17 - 0.002)).abs() < 1e-12);
    let o = sim.step(BasePose::new(0.05, 0.168, -FRAC_PI_2 + 1.0)).unwrap().clone();
    assert!(o.clamped && (o.base.theta_rad - (-FRAC_PI_2 + 0.05)).abs() < 1e-12);
    // The simulation goes on normally.
    let o = sim.step(BasePose::new(0.05, 0.168, -FRAC_PI_2 + 0.05)).unwrap().clone();
    assert!(!o.clamped && o.force_axial_n.is_finite());
    assert_eq!(sim.stats().clamped_ticks, 2);
}

#[test]
fn invalid_parameters_are_named() {
    let model = phantom(7);
    let mut p = params(RegionNeedleParams::default(), top_base());
    p.targets[0].center_m = [0.5, 0.5];
    let e = Simulation::new(model.clone(), p).err().unwrap();
    assert!(e.to_string().contains("target 'c'") && e.to_string().contains("outside the mesh"), "{e}");
    let mut p = params(RegionNeedleParams::default(), top_base());
    p.capture_radius_m = 0.0;
    assert!(Simulation::new(model.clone(), p).err().unwrap().to_string().contains("capture_radius_m = 0"));
    let mut p = params(RegionNeedleParams::default(), top_base());
    p.regions.push(RegionNeedleParams::default());
    assert!(Simulation::new(model.clone(), p).err().unwrap().to_string().contains("1 region(s)"));
    let mut p = params(RegionNeedleParams::default(), top_base());
    p.needle = NeedleShape::Rigid(RigidNeedle { length_m: -1.0 });
    assert!(Simulation::new(model, p).err().unwrap().to_string().contains("needle length -1"));
}

/// The stiffness Jacobian predicts the wrench change of a small base move (all nodes stuck, so
/// no condition changes), and computing it leaves the simulation untouched.
#[test]
fn stiffness_jacobian_predicts_small_moves() {
    jacobian_case(None, 1e-6, Some(2e-3));
}

/// The same for a flexible 22-gauge needle: the Jacobian includes the needle's compliance and
/// the geometric stiffness of the loads it carries (it is softer across the needle than the
/// rigid one's), so a step — which also settles the shape — follows it for translations and
/// rotations alike. (The contact forces are follower loads, not conservative: J need not be
/// symmetric, and is not, by about 1 %.)
#[test]
fn flexible_stiffness_jacobian_predicts_small_moves() {
    let mut f = needlesim_core::FlexibleNeedle::gauge17_steel(0.1);
    f.flexural_rigidity_nm2 *= 0.0687;
    let j_flex = jacobian_case(Some(NeedleShape::Flexible(f)), 1e-3, Some(2e-3));
    let j_rigid = jacobian_case(None, 1e-6, Some(2e-3));
    let n = BasePose::new(0.0, 0.0, -1.25).normal();
    let lat = |j: [[f64; 3]; 3]| n[0] * (j[0][0] * n[0] + j[0][1] * n[1]) + n[1] * (j[1][0] * n[0] + j[1][1] * n[1]);
    println!("lateral stiffness: rigid {:.1} N/m, flexible 22 G {:.1} N/m", lat(j_rigid), lat(j_flex));
    assert!(lat(j_flex) < 0.0 && lat(j_flex) > 0.9 * lat(j_rigid), "the flexible needle is softer sideways");
}

/// Runs the held insertion with `needle` (rigid when None), checks J against small moves to
/// `tol_translation` (and `tol_rotation`, when given) of the change, and returns J.
fn jacobian_case(needle: Option<NeedleShape>, tol_translation: f64, tol_rotation: Option<f64>) -> [[f64; 3]; 3] {
    let model = phantom(25);
    let params = |r: RegionNeedleParams, b: BasePose| {
        let mut p = params(r, b);
        if let Some(n) = needle {
            p.needle = n;
        }
        p
    };
    let a0 = -1.25f64;
    let base_at = |d: f64, a: f64| BasePose::new(0.04 + (d - 0.1) * a.cos(), 0.1 + (d - 0.1) * a.sin(), a);
    let mut poses: Vec<BasePose> = (1..=3500).map(|k| base_at(-0.005 + 0.04 * k as f64 / 3500.0, a0)).collect();
    poses.extend(std::iter::repeat_n(*poses.last().unwrap(), 300));
    let mut a = Simulation::new(model.clone(), params(RegionNeedleParams::default(), base_at(-0.005, a0))).unwrap();
    let mut b = Simulation::new(model.clone(), params(RegionNeedleParams::default(), base_at(-0.005, a0))).unwrap();
    run(&mut a, poses.clone());
    run(&mut b, poses);
    let held = a.output().clone();
    assert!(held.n_stuck >= 5 && held.n_slipping == 0, "all nodes stuck after the hold");
    let j = a.stiffness_jacobian().unwrap();
    // Computing J leaves the state as it was: both simulations step identically.
    let q0 = a.pose();
    let nudge = BasePose::new(q0.x_m + 1e-6, q0.y_m, q0.theta_rad);
    let oa = a.step(nudge).unwrap().clone();
    let ob = b.step(nudge).unwrap().clone();
    assert_eq!(oa.force_n, ob.force_n);
    assert_eq!(oa.torque_nm, ob.torque_nm);
    let w = |o: &needlesim_core::StepOutput| [o.force_n[0], o.force_n[1], o.torque_nm];
    let w0 = w(&held);
    let scale = [w0[0].hypot(w0[1]), w0[0].hypot(w0[1]), w0[2].abs().max(1e-6)];
    // Translations: the held problem is linear in them.
    // (move, tolerance relative to the change): translations are exact; the rotation column is
    // a central difference and the move itself has second-order terms.
    let moves =
        [(0, [2e-6, 0.0, 0.0], Some(tol_translation)), (1, [0.0, -3e-6, 0.0], Some(tol_translation)), (2, [0.0, 0.0, 2e-4], tol_rotation)];
    for (k, dq, tol) in moves {
        let Some(tol) = tol else { continue };
        let mut sim = Simulation::new(model.clone(), params(RegionNeedleParams::default(), base_at(-0.005, a0))).unwrap();
        let mut poses: Vec<BasePose> = (1..=3500).map(|k| base_at(-0.005 + 0.04 * k as f64 / 3500.0, a0)).collect();
        poses.extend(std::iter::repeat_n(*poses.last().unwrap(), 300));
        run(&mut sim, poses);
        let o = sim.step(BasePose::new(q0.x_m + dq[0], q0.y_m + dq[1], q0.theta_rad + dq[2])).unwrap().clone();
        assert_eq!(o.n_slipping, 0, "the move must not unstick nodes");
        let got = w(&o);
        for i in 0..3 {
            let predicted = w0[i] + (0..3).map(|c| j[i][c] * dq[c]).sum::<f64>();
            let change = (got[i] - w0[i]).abs().max(1e-12);
            assert!(
                (got[i] - predicted).abs() < tol * change.max(1e-6 * scale[i]),
                "component {i} of move {k}: got {} predicted {predicted} (J {j:?})",
                got[i]
            );
        }
    }
    // The lateral stiffness resists a lateral move of the base.
    let n = a.pose().normal();
    let lateral_stiffness = n[0] * (j[0][0] * n[0] + j[0][1] * n[1]) + n[1] * (j[1][0] * n[0] + j[1][1] * n[1]);
    assert!(lateral_stiffness < 0.0, "a lateral push meets a restoring force: {lateral_stiffness}");
    j
}

/// Issue 14: every fixed capacity a step fills is a named limit whose overflow is counted. A
/// 3 cm jump of the base (allowed by a large step bound) with a wide capture radius passes far
/// more nodes in one tick than the capture list holds, reports more approaching nodes than
/// their list holds, queries more grid nodes than the reserved buffer, and fills the working
/// set: each is counted, none is silent, and the simulation keeps stepping.
#[test]
fn overflows_of_fixed_capacities_are_counted() {
    use needlesim_core::sim::param_limits::{MAX_APPROACHING, MAX_CAPTURES_PER_TICK};
    let model = phantom(100);
    let p = SimParams {
        // The near-tip buffer is reserved for the lookahead query (2 cm, a 1 cm band: ~4200
        // nodes here); the capture query after a 3 cm jump covers ~6300.
        capture_radius_m: 0.005,
        max_needle_nodes: 32,
        max_base_step_m: 0.05,
        lookahead_m: 0.02,
        ..phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))
    };
    let mut sim = Simulation::new(model, p).unwrap();
    sim.step(top_base()).unwrap();
    assert_eq!(sim.output().approaching.len(), MAX_APPROACHING, "the approaching list filled");
    let first = sim.stats();
    assert!(first.approaching_overflow > 0, "{first:?}");
    sim.step(BasePose::new(0.05, 0.175, -FRAC_PI_2)).unwrap();
    let st = sim.stats();
    assert!(st.capture_overflow > 0, "more than {MAX_CAPTURES_PER_TICK} nodes passed in one tick: {st:?}");
    assert!(st.capacity_drops > 0 && st.captures == 32, "the working set filled: {st:?}");
    assert!(st.candidate_growths > 0, "the grid query outgrew its buffer: {st:?}");
    assert_eq!(
        st.overflows(),
        st.capacity_drops + st.capture_overflow + st.approaching_overflow + st.candidate_growths + st.curve_capacity_drops
    );
    sim.step(BasePose::new(0.05, 0.17, -FRAC_PI_2)).unwrap();
}

/// Issue 15: a tick's active-set work is bounded. A needle holding ~200 nodes (node capture
/// with a 5 mm radius on a 60 × 60 mesh) turned by 0.05 rad in single ticks changes the
/// conditions of many nodes at once: the stick/slip iteration stops at the per-tick budget of
/// O(d²) updates (counted), every tick still solves, and the run goes on.
#[test]
fn issue_15_the_per_tick_update_budget_bounds_a_pathological_tick() {
    use needlesim_core::sim::param_limits::MAX_UPDATES_PER_TICK;
    let model = phantom(60);
    let p = SimParams {
        capture_radius_m: 0.005,
        max_needle_nodes: 400,
        max_active_set_iterations: 10_000,
        ..params(RegionNeedleParams::default(), top_base())
    };
    let mut sim = Simulation::new(model, p).unwrap();
    run(&mut sim, vertical(0.205, 0.14, 0.05));
    let d = sim.output().needle_nodes.len();
    assert!(d > 150, "the needle holds {d} nodes");
    let mut worst = 0;
    for k in 0..40 {
        let theta = -FRAC_PI_2 + if k % 2 == 0 { 0.05 } else { -0.05 };
        let before = sim.solver().stats();
        let o = sim.step(BasePose::new(0.05, 0.14, theta)).unwrap().clone();
        let after = sim.solver().stats();
        let updates = (after.n_pivots + after.n_rotations + after.n_added + after.n_removed)
            - (before.n_pivots + before.n_rotations + before.n_added + before.n_removed);
        worst = worst.max(updates);
        assert!(o.force_n.iter().all(|f| f.is_finite()));
        // The check runs before each pass: a pass can add at most one update per contact, plus
        // the frame rotations and captures that precede the iteration.
        assert!(updates <= MAX_UPDATES_PER_TICK + 4 * d as u64, "tick {k}: {updates} updates with d = {d}");
    }
    let st = sim.stats();
    assert!(st.budget_exhausted_ticks > 0 && st.unconverged_ticks >= st.budget_exhausted_ticks, "{st:?} (worst {worst} updates)");
}
