//! Planning in 3D (issue 18) through a real server: `PlanningService.Plan` with a 3D scene TOML
//! streams progress and then `result3` (entry, direction, rolls, clearances, a 3D trajectory)
//! whose plan hits the target with the structure's clearance kept; the same server's `Simulate`
//! replays that trajectory to the same closest approach and clearance; bad 3D problems are
//! INVALID_ARGUMENT naming the field.

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, connect};
use tokio_stream::StreamExt;

/// The shipped scene: a block of 19 × 19 × 25 nodes, a vessel and the lesion behind it.
const SCENE_TOML: &str = include_str!("../../server/scenes/behind-vessel-3d.toml");
/// The clearance asked for, m (the planning example's).
const CLEARANCE_M: f64 = 0.0005;

/// server/scenes/behind-vessel-3d.toml as shipped (the test takes 37 s in a debug build at a
/// load average of 5 and 85 s at 8 on 2 cores: four simulations of the 9,025-node block; the
/// core is optimised in dev builds); `vessel_target` adds the vessel as
/// a tracked target sphere, so that Simulate reports the tip's distance to its displaced centre
/// (targets do not act on the tissue).
fn scene_toml(vessel_target: bool) -> String {
    let mut text = SCENE_TOML.to_string();
    if vessel_target {
        let vessel = "sphere = { center_m = [0.0317, 0.0297, 0.048], radius_m = 0.00175 }";
        assert!(text.contains(vessel), "behind-vessel-3d.toml's vessel is no longer {vessel}");
        text.push_str("\n[[targets]]\nname = \"vessel\"\ncenter_m = [0.0317, 0.0297, 0.048]\nradius_m = 0.00175\n");
    }
    text
}

fn toml_source(text: String) -> Option<pb::SceneSource> {
    Some(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) })
}

fn scene() -> Option<pb::SceneSource> {
    toml_source(scene_toml(false))
}

fn norm(v: &pb::Vec3) -> f64 {
    (v.x * v.x + v.y * v.y + v.z * v.z).sqrt()
}

/// The 3D plan through the service: progress messages, then a plan that hits the lesion
/// (predicted error below its radius) with the vessel's clearance kept, where the straight aim
/// from above the lesion crosses the vessel; the plan's trajectory replayed by the same server's
/// `Simulate` comes as close to the lesion as predicted and keeps the clearance.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn planning_service_plans_in_3d_and_simulate_replays_the_plan() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut planner = pb::planning_service_client::PlanningServiceClient::new(ch.clone());
    let started = std::time::Instant::now();
    let req = pb::PlanRequest { scene: scene(), target: "lesion".into(), clearance_m: Some(CLEARANCE_M), ..Default::default() };
    let mut stream = planner.plan(req).await.expect("Plan starts").into_inner();
    let (mut progress, mut result) = (0, None);
    while let Some(m) = stream.next().await {
        let m = m.expect("a progress message");
        assert!(result.is_none(), "a message after the final one");
        assert!(m.result.is_none(), "a 2D result for a 3D scene");
        match m.result3 {
            Some(r) => result = Some(r),
            None => {
                assert!(m.iteration >= 1 && m.simulations >= 1 && m.best_error_m.is_finite(), "{m:?}");
                progress += 1;
            }
        }
    }
    let plan_wall_s = started.elapsed().as_secs_f64();
    assert!(progress >= 1, "no progress message");
    let r = result.expect("a final message with the 3D plan");
    let (p, s) = (r.plan.clone().unwrap(), r.straight.clone().unwrap());
    println!(
        "3D plan over gRPC: straight error {:.3} mm, clearance {:.3} mm; plan entry {:?}, error {:.3} mm, clearance {:.3} mm, depth {:.2} mm; {} iterations, {} simulations on {} threads, planner {:.1} s, call {plan_wall_s:.1} s, {progress} progress messages",
        s.predicted_error_m * 1e3,
        s.clearances_m[0] * 1e3,
        p.entry_m,
        p.predicted_error_m * 1e3,
        p.clearances_m[0] * 1e3,
        p.depth_m * 1e3,
        r.iterations,
        r.simulations,
        r.threads,
        r.wall_s
    );
    assert_eq!(r.target, "lesion");
    assert_eq!(r.structures.len(), 1);
    assert_eq!(r.structures[0].name, "vessel");
    let vessel_radius_m = r.structures[0].radius_m;
    assert!((vessel_radius_m - 0.00175).abs() < 1e-15, "the vessel's radius {vessel_radius_m} m");
    assert!((r.clearance_m - CLEARANCE_M).abs() < 1e-15, "the clearance asked for: {}", r.clearance_m);
    assert!(!r.bevel && p.rolls.is_empty(), "a rigid needle's plan has no rolls");
    assert_eq!((p.clearances_m.len(), s.clearances_m.len()), (1, 1));
    // The straight aim crosses the vessel; the plan hits with the clearance kept.
    assert!(s.clearances_m[0] < 0.0, "the straight aim clears the vessel by {} m", s.clearances_m[0]);
    assert!(r.converged, "the planner did not converge");
    assert!(p.predicted_error_m < r.target_radius_m, "plan error {} m, radius {} m", p.predicted_error_m, r.target_radius_m);
    assert!(p.clearances_m[0] >= CLEARANCE_M, "the plan comes {} m from the vessel", p.clearances_m[0]);
    let d = p.direction.unwrap();
    assert!((norm(&d) - 1.0).abs() < 1e-9, "{d:?}");
    assert!((p.entry_m.unwrap().z - 0.08).abs() < 1e-9, "the entry is on the top face: {:?}", p.entry_m);
    assert!(p.depth_m > 0.0);
    assert!(r.trajectory.len() >= 2);
    assert!(r.trajectory.windows(2).all(|w| w[1].t_s > w[0].t_s));

    // The plan's trajectory replayed by Simulate on the same server, the vessel tracked as a
    // target: the lesion's closest approach is the predicted error, the vessel's clearance (tip
    // to its displaced centre, less its radius and the needle's) the predicted one.
    let trajectory: Vec<pb::TrajectorySample> =
        r.trajectory.iter().map(|s| pb::TrajectorySample { t_s: s.t_s, base: None, base3: s.base }).collect();
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch);
    let sreq = pb::SimulateRequest { scene: toml_source(scene_toml(true)), trajectory, decimate: 1, keep_unconverged: false };
    let mut stream = sim.simulate(sreq).await.expect("Simulate starts").into_inner();
    let mut rows = Vec::new();
    while let Some(m) = stream.next().await {
        if let Some(pb::simulate_response::Event::Series(chunk)) = m.expect("simulate message").event {
            rows.extend(chunk.rows);
        }
    }
    assert!(!rows.is_empty(), "no rows");
    let closest = |name: &str| {
        rows.iter()
            .map(|row| {
                let t = row.d3.as_ref().expect("a 3D row").targets.iter().find(|t| t.name == name);
                t.unwrap_or_else(|| panic!("no target {name} in a row")).distance_m
            })
            .fold(f64::INFINITY, f64::min)
    };
    let parsed = needlesim_scene::parse_scene3d(&scene_toml(true), std::path::Path::new("."), &needlesim_core::MeshLimits::default())
        .expect("the scene parses");
    let needle_radius_m = 0.5 * parsed.needle.diameter_m;
    let (lesion, vessel) = (closest("lesion"), closest("vessel") - vessel_radius_m - needle_radius_m);
    println!(
        "replayed by Simulate: {} rows, lesion closest {:.6} mm (predicted {:.6} mm), vessel clearance {:.6} mm (predicted {:.6} mm)",
        rows.len(),
        lesion * 1e3,
        p.predicted_error_m * 1e3,
        vessel * 1e3,
        p.clearances_m[0] * 1e3
    );
    assert!(lesion < r.target_radius_m, "the replayed plan misses the lesion by {lesion} m");
    assert!(vessel >= CLEARANCE_M, "the replayed plan comes {vessel} m from the vessel");
    assert!((lesion - p.predicted_error_m).abs() < 1e-9, "replay {lesion} m vs predicted {} m", p.predicted_error_m);
    assert!((vessel - p.clearances_m[0]).abs() < 1e-9, "replay clearance {vessel} m vs predicted {} m", p.clearances_m[0]);
}

/// Bad 3D problems are INVALID_ARGUMENT statuses naming the field, before any stream opens.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_3d_plans_name_the_field() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut planner = pb::planning_service_client::PlanningServiceClient::new(ch);
    let lesion = |r: pb::PlanRequest| pb::PlanRequest { scene: scene(), target: "lesion".into(), ..r };
    let bad = [
        (lesion(pb::PlanRequest { avoid: vec!["artery".into()], ..Default::default() }), "avoid: no region named 'artery'"),
        (
            lesion(pb::PlanRequest {
                entry_from_m: Some(pb::Vec2 { x: 0.0, y: 0.0 }),
                entry_to_m: Some(pb::Vec2 { x: 0.01, y: 0.0 }),
                ..Default::default()
            }),
            "entry_point_m",
        ),
        (
            lesion(pb::PlanRequest { entry_point_m: Some(pb::Vec3 { x: 0.03, y: 0.03, z: 0.05 }), ..Default::default() }),
            "is not on a face of the mesh's bounding box",
        ),
        (lesion(pb::PlanRequest { clearance_m: Some(-0.001), ..Default::default() }), "clearance_m = -0.001"),
        (pb::PlanRequest { scene: scene(), target: "tumour".into(), ..Default::default() }, "no target named 'tumour'"),
    ];
    for (req, expect) in bad {
        let Err(e) = planner.plan(req).await else { panic!("{expect}: expected an error status") };
        assert_eq!(e.code(), tonic::Code::InvalidArgument, "{e:?}");
        assert!(e.message().contains(expect), "{expect:?} not in {}", e.message());
    }
}
