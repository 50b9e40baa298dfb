//! Insertion planning (issue 8) through the real binaries: the plan for the paper's Fig. 3 case,
//! written by `needlesim-server plan` and replayed by `needlesim-server simulate`, hits the target
//! that aiming straight misses; the PlanningService streams progress and a plan through a real
//! server (replayed by its Simulate call), and `needlesim plan` prints it; bad problems are
//! errors naming the field.

use std::path::Path;
use std::process::Command;

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, bin, connect, run, text};
use serde_json::Value;
use tokio_stream::StreamExt;

const RADIUS: f64 = 0.0015;

/// Runs `needlesim-server ARGS`; returns (stdout, stderr), panicking on failure.
fn server_ok(args: &[&str]) -> (String, String) {
    let o = run(Command::new(bin("needlesim-server")).args(args));
    let (out, err) = text(&o);
    assert!(o.status.success(), "needlesim-server {args:?} failed: {err}");
    assert!(!err.contains("panicked"), "{err}");
    (out, err)
}

/// Runs `needlesim-server ARGS`, expecting exit code 1 and one `error: …` line mentioning each of `expected`.
fn server_fails(args: &[&str], expected: &[&str]) {
    let o = run(Command::new(bin("needlesim-server")).args(args));
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "needlesim-server {args:?}: expected exit code 1, stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    let line = err.lines().find(|l| l.starts_with("error: ")).unwrap_or_else(|| panic!("no error line: {err}"));
    for e in expected {
        assert!(line.contains(e), "needlesim-server {args:?}: the error does not mention {e:?}: {line}");
    }
}

/// The target's distance column of a `simulate` CSV: (every row's distance, the last row's hit flag).
fn target_distances(path: &Path) -> (Vec<f64>, f64) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (d, h) = (col("target_biopsy_distance_m"), col("target_biopsy_hit"));
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert!(!rows.is_empty(), "{} has no rows", path.display());
    (rows.iter().map(|r| r[d]).collect(), rows.last().unwrap()[h])
}

fn min(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Issue 8's done-when: the plan for the Fig. 3 case, replayed through `simulate`, hits the target
/// (within its radius, at the end and at closest approach) where the scene's own straight-aim
/// trajectory misses it; the replay reproduces the planner's prediction.
#[test]
fn issue_8_plan_for_fig3_hits_where_straight_misses() {
    let dir = TempDir::new("plan-fig3");
    let plan_csv = dir.join("plan.csv");
    let (out, err) =
        server_ok(&["plan", "--scene", "fig3-target", "--target", "biopsy", "--trajectory-out", plan_csv.to_str().unwrap(), "--json"]);
    let plan: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("plan --json: {e}: {out}\n{err}"));
    let predicted = plan["plan"]["predicted_error_m"].as_f64().unwrap();
    let straight_predicted = plan["straight"]["predicted_error_m"].as_f64().unwrap();
    println!(
        "plan: predicted {:.3} mm; straight: predicted {:.3} mm; {} simulations",
        predicted * 1e3,
        straight_predicted * 1e3,
        plan["simulations"]
    );
    assert!(predicted < RADIUS, "the plan's predicted error {predicted} m");
    assert!(straight_predicted > RADIUS, "the straight aim's predicted error {straight_predicted} m");

    // The plan replayed through `simulate`.
    let replay = dir.join("replay.csv");
    server_ok(&["simulate", "--scene", "fig3-target", "--trajectory", plan_csv.to_str().unwrap(), "-o", replay.to_str().unwrap()]);
    let (dist, hit) = target_distances(&replay);
    let (closest, end) = (min(&dist), *dist.last().unwrap());
    println!("replayed plan: closest {:.3} mm, end {:.3} mm", closest * 1e3, end * 1e3);
    assert!(end < RADIUS, "the replayed plan ends {end} m from the displaced target");
    assert!(closest < RADIUS);
    assert_eq!(hit, 1.0);
    assert!((end - predicted).abs() < 1e-5, "replay {end} m vs predicted {predicted} m");

    // The scene's own trajectory aims straight at the undeformed centre and misses.
    let straight = dir.join("straight.csv");
    server_ok(&["simulate", "--scene", "fig3-target", "-o", straight.to_str().unwrap()]);
    let (dist, hit) = target_distances(&straight);
    println!("straight aim: closest {:.3} mm", min(&dist) * 1e3);
    assert!(min(&dist) > RADIUS, "the straight aim comes within {} m", min(&dist));
    assert_eq!(hit, 0.0);
    // The planner's straight baseline is that same line (the scene's axis through the target).
    assert!((straight_predicted - min(&dist)).abs() < 2e-4, "baseline {straight_predicted} m vs scene trajectory {} m", min(&dist));
}

/// Bad planning problems: errors naming the field, exit code 1, no panic.
#[test]
fn bad_problems_name_the_field() {
    let base = ["plan", "--scene", "fig3-target", "--target"];
    let with = |extra: &[&'static str]| base.iter().copied().chain(extra.iter().copied()).collect::<Vec<&str>>();
    server_fails(&with(&["tumour"]), &["target: no target named 'tumour'", "biopsy"]);
    server_fails(&with(&["biopsy", "--angles-deg", "-20,-60"]), &["angles_deg: the range [-20, -60] is empty"]);
    server_fails(&with(&["biopsy", "--entry", "0,0.2,0.04,0.2"]), &["entry:", "outside the mesh"]);
    server_fails(&with(&["biopsy", "--angles-deg", "10,30"]), &["angles_deg:", "from no point of the entry segment"]);
    server_fails(&with(&["biopsy", "--speed-mm-s", "0"]), &["speed_mm_s = 0"]);
    server_fails(&with(&["biopsy", "--entry", "0,0.06,0.04"]), &["--entry takes 4 numbers"]);
    // A needle too short to reach the target from the entry region.
    let dir = TempDir::new("plan-short");
    let scene = dir.join("short.toml");
    let toml = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/fig3-target.toml")).unwrap();
    assert!(toml.contains("length_m = 0.1\n"));
    std::fs::write(&scene, toml.replace("length_m = 0.1\n", "length_m = 0.03\n")).unwrap();
    server_fails(&["plan", "--scene", scene.to_str().unwrap(), "--target", "biopsy"], &["beyond the needle's length", "needle.length_m"]);
}

fn example(name: &str) -> Option<pb::SceneSource> {
    Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example(name.into())) })
}

/// The PlanningService through a real server: progress, then a plan whose predicted error is
/// within the radius and whose trajectory, replayed by the same server's Simulate, hits; bad
/// problems are INVALID_ARGUMENT naming the field; the `needlesim plan` CLI prints the plan.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn planning_service_streams_progress_and_a_plan_that_hits() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut planner = pb::planning_service_client::PlanningServiceClient::new(ch.clone());
    let req = pb::PlanRequest { scene: example("fig3-target"), target: "biopsy".into(), ..Default::default() };
    let mut stream = planner.plan(req).await.expect("Plan starts").into_inner();
    let (mut progress, mut result) = (0, None);
    while let Some(m) = stream.next().await {
        let m = m.expect("a progress message");
        assert!(result.is_none(), "a message after the final one");
        match m.result {
            Some(r) => result = Some(r),
            None => {
                assert!(m.iteration >= 1 && m.simulations >= 1 && m.best_error_m.is_finite());
                progress += 1;
            }
        }
    }
    assert!(progress >= 1, "no progress message");
    let r = result.expect("a final message with the plan");
    let (p, s) = (r.plan.unwrap(), r.straight.unwrap());
    assert!(p.predicted_error_m < r.target_radius_m, "plan {} m", p.predicted_error_m);
    assert!(s.predicted_error_m > r.target_radius_m, "straight {} m", s.predicted_error_m);
    assert!((r.target_radius_m - RADIUS).abs() < 1e-12);
    assert!(r.trajectory.len() >= 2);

    // Replayed by Simulate on the same server.
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    let sreq =
        pb::SimulateRequest { scene: example("fig3-target"), trajectory: r.trajectory.clone(), decimate: 1, keep_unconverged: false };
    let mut stream = sim.simulate(sreq).await.expect("Simulate starts").into_inner();
    let mut rows = Vec::new();
    while let Some(m) = stream.next().await {
        if let Some(pb::simulate_response::Event::Series(chunk)) = m.expect("simulate message").event {
            rows.extend(chunk.rows);
        }
    }
    let end = rows.last().expect("rows").targets[0].distance_m;
    assert!(end < RADIUS, "the replayed plan ends {end} m from the target");

    // Bad problems are statuses naming the field.
    let bad = [
        (pb::PlanRequest { scene: example("fig3-target"), target: "tumour".into(), ..Default::default() }, "target"),
        (
            pb::PlanRequest {
                scene: example("fig3-target"),
                target: "biopsy".into(),
                angle_min_deg: Some(-20.0),
                angle_max_deg: Some(-60.0),
                ..Default::default()
            },
            "angles_deg: the range [-20, -60] is empty",
        ),
        (
            pb::PlanRequest { scene: example("fig3-target"), target: "biopsy".into(), angle_min_deg: Some(-20.0), ..Default::default() },
            "angle_max_deg",
        ),
        (pb::PlanRequest { scene: example("no-such-scene"), target: "biopsy".into(), ..Default::default() }, "no-such-scene"),
    ];
    for (req, expect) in bad {
        let Err(e) = planner.plan(req).await else { panic!("{expect}: expected an error status") };
        assert_eq!(e.code(), tonic::Code::InvalidArgument, "{e:?}");
        assert!(e.message().contains(expect), "{expect:?} not in {}", e.message());
    }

    // An insertion so slow that each simulation would exceed the server's tick limit.
    let slow = pb::PlanRequest { scene: example("fig3-target"), target: "biopsy".into(), speed_mm_s: Some(1e-6), ..Default::default() };
    let Err(e) = planner.plan(slow).await else { panic!("a 1 nm/s insertion was accepted") };
    assert_eq!(e.code(), tonic::Code::ResourceExhausted, "{e:?}");
    assert!(e.message().contains("speed_mm_s") && e.message().contains("over the limit"), "{}", e.message());

    // The CLI against the same server.
    let dir = TempDir::new("plan-cli");
    let traj = dir.join("plan.csv");
    let url = server.url();
    let args = ["plan", "--server", &url, "--scene", "fig3-target", "--target", "biopsy", "--trajectory-out", traj.to_str().unwrap()];
    let o = run(Command::new(bin("needlesim")).args(args));
    let (out, err) = text(&o);
    assert!(o.status.success(), "needlesim plan failed: {err}");
    assert!(err.contains("iteration 1:"), "no progress on stderr: {err}");
    assert!(out.contains("the plan hits the target") && out.contains("straight"), "{out}");
    let csv = std::fs::read_to_string(&traj).unwrap();
    assert!(csv.starts_with("t_s,x_m,y_m,theta_rad\n") && csv.lines().count() == r.trajectory.len() + 1, "{csv}");
    let o = run(Command::new(bin("needlesim")).args(["plan", "--server", &url, "--scene", "fig3-target", "--target", "biopsy", "--json"]));
    let (out, err) = text(&o);
    assert!(o.status.success(), "needlesim plan --json failed: {err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert!(v["plan"]["predicted_error_m"].as_f64().unwrap() < RADIUS);
    let o = run(Command::new(bin("needlesim")).args(["plan", "--server", &url, "--scene", "fig3-target", "--target", "tumour"]));
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.starts_with("error: ") && err.contains("target: no target named 'tumour'"), "{err}");

    // A client that goes away after the first progress message cancels the planning (slowed to
    // 1 mm/s so that it is still running): the server logs the cancellation and no plan.
    let slow = pb::PlanRequest { scene: example("fig3-target"), target: "biopsy".into(), speed_mm_s: Some(1.0), ..Default::default() };
    // The server logs each completed plan (three so far; its log is read in the background).
    let planned_before = 3;
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    while server.stderr.lock().unwrap().matches(" planned ").count() < planned_before {
        assert!(std::time::Instant::now() < deadline, "three completed plans are not logged:\n{}", server.stderr.lock().unwrap());
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    let mut stream = planner.plan(slow).await.expect("Plan starts").into_inner();
    let first = stream.next().await.expect("a first message").expect("a progress message");
    assert!(first.result.is_none(), "the slow plan finished in one iteration");
    drop(stream);
    drop(planner);
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
    loop {
        let log = server.stderr.lock().unwrap().clone();
        if log.contains("planning cancelled: the client went away") {
            assert_eq!(log.matches(" planned ").count(), planned_before, "the cancelled plan completed:\n{log}");
            break;
        }
        assert!(std::time::Instant::now() < deadline, "the planning was not cancelled:\n{log}");
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
}
