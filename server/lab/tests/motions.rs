//! The motion suite's harness (`needlesim_lab::motions`) on --quick-sized cases: each motion does
//! what its name says (depth reached, the needle turned, the bevel flipped, the Fig. 4 base step),
//! the counts it reports add up tick by tick, and columns never come from inside a step. No
//! assertion on time.

use std::sync::Arc;

use needlesim_core::compliance::TissueModel;
use needlesim_core::fixtures::{self, PHANTOM_SIDE_M};
use needlesim_lab::motions::{
    CaseResult, ContactChoice, ENTRY_M, JACOBIAN_EVERY_TICKS, Motion, MotionOptions, OBLIQUE_ANGLE_RAD, Pace, START_HEIGHT_M, TRAVEL_M,
    TURN_AMPLITUDE_RAD, run_case, run_suite, script,
};

const DOWN_RAD: f64 = -std::f64::consts::FRAC_PI_2;

fn quick(sizes: &[usize], motions: &[Motion], contact: ContactChoice) -> MotionOptions {
    MotionOptions { quick: true, sizes: sizes.to_vec(), motions: motions.to_vec(), contact, progress: false, ..Default::default() }
}

/// What every case must satisfy, whatever its motion.
fn check_counts(c: &CaseResult) {
    let name = format!("{} {}x{} {:?}", c.motion.name(), c.n, c.n, c.contact);
    assert_eq!(c.failed, None, "{name}");
    assert_eq!(c.ticks.len(), c.script_ticks, "{name}: every pose stepped");
    assert_eq!(c.stats.ticks as usize, c.ticks.len(), "{name}");
    for (k, r) in c.ticks.iter().enumerate() {
        assert_eq!(r.tick, k, "{name}: ticks in order");
        assert!(r.step_s > 0.0 && r.step_s.is_finite(), "{name}: tick {k} timed");
    }
    assert_eq!(c.jacobian_s.len(), c.ticks.len().div_ceil(JACOBIAN_EVERY_TICKS), "{name}: a Jacobian every 10 ticks");
    assert_eq!(c.jacobian_errors, 0, "{name}");
    let unconverged = c.ticks.iter().filter(|r| !r.converged).count() as u64;
    assert_eq!(unconverged, c.stats.unconverged_ticks, "{name}: unconverged ticks");
    let sum = |f: fn(&needlesim_lab::motions::TickRecord) -> u64| c.ticks.iter().map(f).sum::<u64>();
    assert_eq!(sum(|r| r.pivots), c.solver.n_pivots, "{name}: pivots");
    assert_eq!(sum(|r| r.rotations), c.solver.n_rotations, "{name}: rotations");
    assert_eq!(sum(|r| r.captures), c.stats.captures, "{name}: captures");
    assert_eq!(sum(|r| r.releases), c.stats.releases, "{name}: releases");
    assert_eq!(sum(|r| r.deferrals), c.stats.column_deferrals, "{name}: deferrals");
    assert_eq!(sum(|r| r.stick_slip_changes), c.stats.stick_to_slip + c.stats.slip_to_stick, "{name}: stick/slip");
    assert_eq!(sum(|r| r.shape_passes), c.stats.shape_passes, "{name}: shape passes");
    // Columns come from the prefetch between steps, never from inside a step.
    assert_eq!(c.stats.column_misses, 0, "{name}");
    assert!(c.prefetched_nodes > 0, "{name}: columns were prefetched");
    assert!(c.stats.captures > 0 && c.stats.punctures > 0, "{name}: {:?}", c.stats);
    assert_eq!(c.stats.overflows(), 0, "{name}: {:?}", c.stats);
    // d at the deepest point, the largest over the run, and none left after the withdrawal.
    assert!(c.d_deepest > 0 && c.d_max >= c.d_deepest, "{name}: d {} max {}", c.d_deepest, c.d_max);
    assert_eq!(c.d_max, c.ticks.iter().map(|r| r.d).max().unwrap(), "{name}");
    assert_eq!(c.d_final, 0, "{name}: withdrawn");
    assert_eq!(c.ticks.last().unwrap().d, 0, "{name}");
    assert_eq!(c.stats.captures, c.stats.releases, "{name}: every contact released");
    // The quantiles are ordered.
    let [p50, p99, p999, max] = c.step_quantiles();
    assert!(p50 <= p99 && p99 <= p999 && p999 <= max, "{name}");
    assert_eq!(c.worst(1, false)[0].step_s, max, "{name}");
    // The stages are timed: inside the step, so together no longer than it.
    for r in c.worst(3, true) {
        let stages_s = r.stage_ns.iter().sum::<u64>() as f64 * 1e-9;
        assert!(
            r.cpu_wait_ns == 0 && stages_s > 0.0 && stages_s <= r.step_s,
            "{name} tick {}: stages {stages_s} s, step {} s",
            r.tick,
            r.step_s
        );
    }
}

fn check_motion(c: &CaseResult) {
    let name = format!("{} {}x{}", c.motion.name(), c.n, c.n);
    let vertical_depth_m = TRAVEL_M - START_HEIGHT_M;
    match c.motion {
        Motion::Vertical => {
            // A rigid needle's tip is where the pose puts it.
            assert!((c.tip_depth_max_m - vertical_depth_m).abs() < 1e-9, "{name}: {}", c.tip_depth_max_m);
            assert!((c.tip_deepest_m[0] - ENTRY_M[0]).abs() < 1e-9, "{name}");
            assert_eq!(c.theta_range_rad, [DOWN_RAD; 2], "{name}");
        }
        Motion::Oblique => {
            let along_m = TRAVEL_M - START_HEIGHT_M / OBLIQUE_ANGLE_RAD.cos();
            let want = [ENTRY_M[0] + along_m * OBLIQUE_ANGLE_RAD.sin(), ENTRY_M[1] - along_m * OBLIQUE_ANGLE_RAD.cos()];
            assert!(
                (c.tip_deepest_m[0] - want[0]).abs() < 1e-9 && (c.tip_deepest_m[1] - want[1]).abs() < 1e-9,
                "{name}: {:?}",
                c.tip_deepest_m
            );
            assert!((c.tip_depth_max_m - (PHANTOM_SIDE_M - want[1])).abs() < 1e-9, "{name}");
            assert!((c.theta_range_rad[0] - (DOWN_RAD + OBLIQUE_ANGLE_RAD)).abs() < 1e-12, "{name}");
            assert!((c.theta_range_rad[1] - c.theta_range_rad[0]).abs() < 1e-12, "{name}: held");
        }
        Motion::Turning => {
            // Really turned: ±10° on the base, the tip swept ±55 mm · sin 10°, and the needle
            // stayed in the tissue all through the turn.
            assert!((c.theta_range_rad[0] - (DOWN_RAD - TURN_AMPLITUDE_RAD)).abs() < 1e-6, "{name}: {:?}", c.theta_range_rad);
            assert!((c.theta_range_rad[1] - (DOWN_RAD + TURN_AMPLITUDE_RAD)).abs() < 1e-6, "{name}: {:?}", c.theta_range_rad);
            let sweep_m = vertical_depth_m * TURN_AMPLITUDE_RAD.sin();
            assert!((c.tip_x_range_m[0] - (ENTRY_M[0] - sweep_m)).abs() < 1e-6, "{name}: {:?}", c.tip_x_range_m);
            assert!((c.tip_x_range_m[1] - (ENTRY_M[0] + sweep_m)).abs() < 1e-6, "{name}: {:?}", c.tip_x_range_m);
            assert!(c.d_min_turning > 0, "{name}");
            // Turning against the tissue makes contacts slip and frames rotate.
            assert!(c.solver.n_rotations > 0 || c.stats.stick_to_slip > 0, "{name}: {:?} {:?}", c.solver, c.stats);
        }
        Motion::Flexible => {
            assert_eq!(c.stats.bevel_flips, 0, "{name}");
            assert!(
                (c.base_x_range_m[0] - 0.05).abs() < 1e-12 && (c.base_x_range_m[1] - 0.055).abs() < 1e-12,
                "{name}: {:?}",
                c.base_x_range_m
            );
            // 85 mm into the tissue along the Fig. 4 path (a bent needle's tip a little less deep).
            assert!(c.tip_depth_max_m > 0.08 && c.tip_depth_max_m <= 0.085 + 1e-9, "{name}: {}", c.tip_depth_max_m);
            // The tip did not follow the 5 mm base step rigidly: the needle bent.
            let tip_dx = c.tip_deepest_m[0] - 0.055;
            assert!(tip_dx.abs() > 1e-5, "{name}: tip x {:?}", c.tip_deepest_m);
            assert!(c.stats.shape_passes > 0 || c.solver.n_pivots > 0, "{name}");
        }
        Motion::Bevel => {
            assert_eq!(c.stats.bevel_flips, 1, "{name}: flipped once");
            let [first, last] = c.bevel_side_first_last;
            assert!(first.abs() == 1.0 && last == -first, "{name}: bevel side {first} → {last}");
            assert!(c.tip_depth_max_m > 0.05 && c.tip_depth_max_m <= vertical_depth_m + 1e-9, "{name}: {}", c.tip_depth_max_m);
            // The bevel pushes the tip sideways: it leaves the straight line.
            assert!(c.tip_x_range_m[1] - c.tip_x_range_m[0] > 1e-5, "{name}: {:?}", c.tip_x_range_m);
        }
    }
}

/// Every motion on the two --quick meshes with material points.
#[test]
fn quick_suite_does_what_each_motion_says() {
    let opts = quick(&[19, 100], &[], ContactChoice::Points);
    let suite = run_suite(&opts).unwrap();
    assert_eq!(suite.pace, Pace::QUICK);
    assert_eq!(suite.cases.len(), 2 * Motion::ALL.len());
    for c in &suite.cases {
        check_counts(c);
        check_motion(c);
    }
    // The output names every case.
    let md = needlesim_lab::motions::to_markdown(&suite, &opts);
    for m in Motion::ALL {
        assert!(md.contains(&format!("| {} | 100² |", m.name())), "{md}");
    }
    let json = needlesim_lab::motions::to_json(&suite, &opts);
    assert_eq!(json["cases"].as_array().unwrap().len(), suite.cases.len());
    assert!(json["cases"][0]["step_p999_s"].as_f64().is_some());
}

/// Material points: d at the deepest point is set by the spacing, not the mesh, once the
/// triangles are smaller than the spacing; node capture puts more contacts on the same shaft.
#[test]
fn material_points_bound_d_by_the_spacing() {
    let sc = script(Motion::Vertical, Pace::QUICK).unwrap();
    let run = |n: usize, contact: ContactChoice| {
        let model: Arc<TissueModel> = fixtures::phantom(n);
        let c = run_case(&sc, &model, 0.0, &quick(&[n], &[Motion::Vertical], contact)).unwrap();
        check_counts(&c);
        c.d_deepest
    };
    let (d100, d150) = (run(100, ContactChoice::Points), run(150, ContactChoice::Points));
    let spacing_m = MotionOptions::default().spacing_m;
    let expected = (TRAVEL_M - START_HEIGHT_M) / spacing_m;
    for d in [d100, d150] {
        assert!((d as f64 - expected).abs() <= 3.0, "d = {d}, 55 mm / 2 mm = {expected}");
    }
    assert!(d100.abs_diff(d150) <= 1, "{d100} vs {d150}");
    let nodes100 = run(100, ContactChoice::Nodes);
    assert!(nodes100 > 2 * d100, "node capture {nodes100} vs points {d100}");
}

/// A column-cache limit stops the case where the cache passes it, and says so.
#[test]
fn column_cache_limit_stops_a_case() {
    let sc = script(Motion::Vertical, Pace::QUICK).unwrap();
    let model = fixtures::phantom(19);
    let one_node_bytes = 2 * 2 * model.mesh().n_nodes() * std::mem::size_of::<f64>();
    let opts = MotionOptions { max_column_bytes: Some(3 * one_node_bytes), ..quick(&[19], &[Motion::Vertical], ContactChoice::Points) };
    let c = run_case(&sc, &model, 0.0, &opts).unwrap();
    assert!(c.failed.as_deref().is_some_and(|w| w.contains("column cache")), "{:?}", c.failed);
    assert!(c.ticks.len() < c.script_ticks && !c.misses().is_empty());
    assert!(c.prefetched_nodes > 3);
    let unlimited = run_case(&sc, &model, 0.0, &quick(&[19], &[Motion::Vertical], ContactChoice::Points)).unwrap();
    assert_eq!(unlimited.stats.column_misses, 0, "no column computed in a step");
    // Every cached column came from the prefetch (slots are reused after evictions, issue 15).
    assert!(unlimited.column_cache_bytes <= unlimited.prefetched_nodes as usize * one_node_bytes);
}
