//! The 3D planner (issue 18) on the lesion behind a vessel (server/scenes/behind-vessel-3d.toml,
//! behind-vessel-bevel-3d.toml): the straight aim crosses the vessel (and, for the bevel needle,
//! misses the lesion); the plan, replayed through `simulate` (`run3`, the vessel added as a
//! tracked sphere), reaches the lesion (distance < its radius) with the vessel's clearance kept.

use needlesim_core::MeshLimits;
use needlesim_offline::plan::PlanOptions;
use needlesim_offline::plan3::{Plan3, Plan3Request, plan3};
use needlesim_offline::simulate3::run3;
use needlesim_scene::scene3d::Target3d;
use needlesim_scene::{Scene3d, load_scene3d};

fn scene(name: &str) -> Scene3d {
    load_scene3d(&format!("{}/../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR")), &MeshLimits::default()).unwrap()
}

/// Replays the plan's trajectory through `simulate` with the structures as tracked spheres:
/// the lesion's closest approach and each structure's clearance (tip to displaced centre, less
/// its radius and the needle's).
fn replay(scene: &Scene3d, plan: &Plan3) -> (f64, Vec<f64>) {
    let mut s = scene.clone();
    let n_targets = s.targets.len();
    for st in &plan.structures {
        s.targets.push(Target3d { name: st.name.clone(), center_m: st.center_m, radius_m: st.radius_m });
    }
    let (_, summary, _) = run3(&s, &plan.trajectory3(), 10_000_000, &[], needlesim_offline::ConvergencePolicy::Fail, None).unwrap();
    let lesion = summary.targets.iter().find(|t| t.name == plan.target).unwrap().closest_distance_m;
    let clear = plan
        .structures
        .iter()
        .enumerate()
        .map(|(j, st)| summary.targets[n_targets + j].closest_distance_m - st.radius_m - 0.5 * scene.needle.diameter_m)
        .collect();
    (lesion, clear)
}

fn plan_and_check(scene_name: &str) -> Plan3 {
    let scene = scene(scene_name);
    let req = Plan3Request { target: "lesion".into(), ..Default::default() };
    let plan = plan3(&scene, &req, &PlanOptions::default(), |p| {
        println!("iteration {}: {} simulations, best error {:.3} mm", p.iteration, p.simulations, p.best_error_m * 1e3);
        std::ops::ControlFlow::Continue(())
    })
    .unwrap();
    let (replayed, clear) = replay(&scene, &plan);
    let (s, pl) = (&plan.straight, &plan.plan);
    println!(
        "{scene_name}: straight aim from {:.4?}: error {:.3} mm, clearance {:.3} mm; plan: entry {:.4?}, direction {:.4?}, rolls {:?}, depth {:.2} mm, predicted error {:.3} mm, clearance {:.3} mm; replayed: error {:.3} mm, clearance {:.3?} mm (radius {} mm, clearance to keep {} mm); {} iterations, {} simulations on {} threads, {:.1} s",
        s.entry_m,
        s.predicted_error_m * 1e3,
        s.min_clearance_m() * 1e3,
        pl.entry_m,
        pl.direction,
        pl.rolls,
        pl.depth_m * 1e3,
        pl.predicted_error_m * 1e3,
        pl.min_clearance_m() * 1e3,
        replayed * 1e3,
        clear.iter().map(|c| c * 1e3).collect::<Vec<_>>(),
        plan.target_radius_m * 1e3,
        plan.clearance_m * 1e3,
        plan.iterations,
        plan.simulations,
        plan.threads,
        plan.wall_s
    );
    // The straight aim crosses the vessel or misses the lesion.
    assert!(
        s.min_clearance_m() < plan.clearance_m || s.predicted_error_m >= plan.target_radius_m,
        "the straight aim already works: error {} m, clearance {} m",
        s.predicted_error_m,
        s.min_clearance_m()
    );
    // The replay hits and keeps the clearance.
    assert!(plan.converged, "the planner did not converge");
    assert!(replayed < plan.target_radius_m, "the replayed plan misses: {replayed} m");
    for c in &clear {
        assert!(*c >= plan.clearance_m, "the replayed plan comes {c} m from the vessel");
    }
    plan
}

/// A rigid needle: the straight line from the point above the lesion crosses the vessel; the
/// plan moves the entry on the top face and corrects the aim.
#[test]
fn a_rigid_needle_plan_reaches_the_lesion_behind_the_vessel() {
    let plan = plan_and_check("behind-vessel-3d");
    assert!(plan.plan.rolls.is_empty());
    assert!(plan.straight.min_clearance_m() < 0.0, "the straight aim should cross the vessel");
}

/// A bevel-tip needle from the same entry point: aimed straight it crosses the vessel and misses
/// the lesion; the plan rolls the bevel towards the vessel before entering and aims so that the
/// arc passes the vessel and ends in the lesion.
///
/// Ignored since issue 35: the 3D bevel needle's shape passes do not converge at its first contact
/// (tick 126 of the straight aim; the issue "3D physics at 2D's fidelity", item 4: the bevel
/// slides through the tissue), and an unconverged run is no answer; the plan below was computed
/// on those ticks. Un-ignore when the 3D bevel needle holds the tissue.
#[test]
#[ignore = "issue 37: the 3D bevel needle's shape passes do not converge (see issue_35_a_plan_whose_simulation_does_not_converge_says_so)"]
fn a_bevel_needle_plan_steers_around_the_vessel() {
    let plan = plan_and_check("behind-vessel-bevel-3d");
    assert_eq!(plan.plan.entry_m, plan.straight.entry_m, "the bevel plan keeps the entry point");
    assert_eq!(plan.plan.rolls.len(), 1);
}

/// Issue 35, item 11: a plan whose candidate simulation does not converge stops with an error
/// naming the tick rather than planning on the solver's last iterate (on ba75e0e this scene
/// planned on unconverged ticks).
#[test]
fn issue_35_a_plan_whose_simulation_does_not_converge_says_so() {
    let scene = scene("behind-vessel-bevel-3d");
    let req = Plan3Request { target: "lesion".into(), ..Default::default() };
    let e = plan3(&scene, &req, &PlanOptions::default(), |_| std::ops::ControlFlow::Continue(()))
        .expect_err("the bevel scene's straight aim does not converge");
    let m = format!("{e:#}");
    assert!(m.contains("the run stopped at tick") && m.contains("did not converge"), "{m}");
}
