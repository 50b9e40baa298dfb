//! Issue 35, items 3 and 11 through the real binary: a 3D scene's `[limits]` on the base step
//! apply to `simulate`; a run whose ticks do not converge stops with an error naming the tick,
//! unless `--keep-unconverged` keeps them, marked in the CSV.

use std::process::Command;

use needlesim_tests::{TempDir, bin, repo_root, run, text};

/// A small 3D box with a `[limits]` table: the needle's tip starts 5 mm above the top face.
const SCENE3: &str = r#"
dim = 3
name = "limits-3d"
fixed = ["bottom"]
[mesh]
type = "box"
nx = 7
ny = 7
nz = 7
size_m = [0.06, 0.06, 0.06]
[[regions]]
name = "gel"
young_modulus_pa = 20e3
poisson_ratio = 0.45
friction_n_per_m = 20
[needle]
length_m = 0.1
contact_spacing_m = 0.002
base_m = [0.0311, 0.0297, 0.165]
base_quat = [0.7071067811865475, 0.0, 0.7071067811865475, 0.0]
[limits]
max_base_step_m = 1e-4
max_base_step_rad = 1e-3
"#;

/// `needlesim-server simulate` of `scene` along `traj` into `out` (`--keep-unconverged` when
/// `keep`): whether it succeeded, and its standard error.
fn simulate(scene: &std::path::Path, traj: &std::path::Path, out: &std::path::Path, keep: bool) -> (bool, String) {
    let mut cmd = Command::new(bin("needlesim-server"));
    cmd.arg("simulate");
    if keep {
        cmd.arg("--keep-unconverged");
    }
    let o = run(cmd.arg("--scene").arg(scene).arg("--trajectory").arg(traj).arg("-o").arg(out));
    (o.status.success(), text(&o).1)
}

/// A CSV's header and rows of numbers.
fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(str::to_owned).collect();
    (header, lines.map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()).collect()).collect())
}

#[test]
fn issue_35_simulate_applies_a_3d_scenes_base_step_limits() {
    let dir = TempDir::new("issue35-limits3d");
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, SCENE3).unwrap();
    // At t = 0.01 s the base is commanded 5 mm sideways and turned 0.2 rad about y (the
    // quaternion of the start turned by 0.2 rad about y: a half-angle 0.1 added).
    let (h0, h1) = (std::f64::consts::FRAC_PI_4, std::f64::consts::FRAC_PI_4 + 0.1);
    let traj = dir.path().join("traj.csv");
    std::fs::write(
        &traj,
        format!(
            "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0.0311,0.0297,0.165,{},0,{},0\n0.01,0.0311,0.0297,0.165,{},0,{},0\n0.011,0.0361,0.0297,0.165,{},0,{},0\n0.3,0.0361,0.0297,0.165,{},0,{},0\n",
            h0.cos(),
            h0.sin(),
            h0.cos(),
            h0.sin(),
            h1.cos(),
            h1.sin(),
            h1.cos(),
            h1.sin()
        ),
    )
    .unwrap();
    let out = dir.path().join("out.csv");
    let (ok, err) = simulate(&scene, &traj, &out, false);
    assert!(ok, "simulate failed: {err}");
    let (header, rows) = read_csv(&out);
    let col = |n: &str| header.iter().position(|h| h == n).unwrap();
    let (x, qw, qy) = (col("x_m"), col("qw"), col("qy"));
    let mut moved_max: f64 = 0.0;
    let mut turned_max: f64 = 0.0;
    for w in rows.windows(2) {
        let moved = (w[1][x] - w[0][x]).abs();
        // Both orientations are turns about y: the angle between them is twice the half-angle difference.
        let turned = 2.0 * (w[1][qy].atan2(w[1][qw]) - w[0][qy].atan2(w[0][qw])).abs();
        assert!(moved <= 1e-4 * (1.0 + 1e-9), "tick {}: the base moved {moved} m, over max_base_step_m = 1e-4", w[1][0]);
        assert!(turned <= 1e-3 * (1.0 + 1e-9), "tick {}: the base turned {turned} rad, over max_base_step_rad = 1e-3", w[1][0]);
        moved_max = moved_max.max(moved);
        turned_max = turned_max.max(turned);
    }
    // The clamped base does get there, at the limit's pace: 50 ticks of 0.1 mm, 200 of 1 mrad.
    assert!(moved_max > 0.99e-4 && turned_max > 0.99e-3, "the base never moved at the limit: {moved_max} m, {turned_max} rad");
    let last = rows.last().unwrap();
    assert!((last[x] - 0.0361).abs() < 1e-9, "the base reached the commanded x: {}", last[x]);
    assert!((last[qy].atan2(last[qw]) - h1).abs() < 1e-9, "the base reached the commanded turn: {last:?}");
}

/// Fig. 4's steering scene with 1e4 N/m of friction: its flexible needle's shape passes stop at
/// their cap on many ticks (the issue: 1,602 such ticks, the inserted length jumping between 0
/// and 49 mm, a 1,320 N force in one tick, and `simulate` exited 0 with a warning).
fn sticky_fig4(dir: &TempDir) -> std::path::PathBuf {
    let text = std::fs::read_to_string(repo_root().join("server/scenes/fig4-steering.toml")).unwrap();
    assert!(text.contains("friction_n_per_m = 10\n"));
    let scene = dir.path().join("sticky.toml");
    std::fs::write(&scene, text.replace("friction_n_per_m = 10\n", "friction_n_per_m = 1e4\n")).unwrap();
    scene
}

#[test]
fn issue_35_a_run_that_does_not_converge_stops_naming_the_tick_unless_kept() {
    let dir = TempDir::new("issue35-unconverged");
    let scene = sticky_fig4(&dir);
    let traj = repo_root().join("server/scenes/fig4-steering.csv");
    let out = dir.path().join("out.csv");
    let (ok, err) = simulate(&scene, &traj, &out, false);
    assert!(!ok, "simulate exited 0 on a run that does not converge: {err}");
    assert!(!err.contains("panicked"), "{err}");
    let at = err.find("the run stopped at tick ").unwrap_or_else(|| panic!("the error names no tick: {err}"));
    let tick: u64 = err[at + "the run stopped at tick ".len()..].split(' ').next().unwrap().parse().unwrap();
    assert!(err.contains("did not converge") && err.contains("--keep-unconverged"), "{err}");
    assert!(!out.exists(), "no time series is written for a run that stopped");

    // Kept: the run ends, and the CSV's last column marks the ticks that did not converge, the
    // first of them the tick the default run stopped at.
    let (ok, err) = simulate(&scene, &traj, &out, true);
    assert!(ok, "simulate --keep-unconverged failed: {err}");
    let (header, rows) = read_csv(&out);
    assert_eq!(header.last().map(String::as_str), Some("converged"), "{header:?}");
    let c = header.len() - 1;
    let unconverged: Vec<usize> = rows.iter().enumerate().filter(|(_, r)| r[c] == 0.0).map(|(k, _)| k).collect();
    assert!(rows.iter().all(|r| r[c] == 0.0 || r[c] == 1.0));
    assert_eq!(unconverged.first().map(|&k| k as u64), Some(tick), "the first unconverged row is the tick the run stopped at");
    assert!(unconverged.len() > 100, "{} unconverged ticks", unconverged.len());
    println!("{} of {} ticks unconverged, the first at tick {tick}", unconverged.len(), rows.len());
}

/// The same through the Simulate RPC: FAILED_PRECONDITION naming the tick, or with
/// `keep_unconverged` the whole series, its unconverged rows marked.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_simulate_rpc_stops_at_an_unconverged_tick_unless_kept() {
    use needlesim_proto::v1 as pb;
    use tokio_stream::StreamExt;
    let server = needlesim_tests::ServerProcess::start(&["--default-scene", "none"]);
    let ch = needlesim_tests::connect(&server).await;
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch);
    let dir = TempDir::new("issue35-rpc");
    let scene = std::fs::read_to_string(sticky_fig4(&dir)).unwrap();
    let csv = std::fs::read_to_string(repo_root().join("server/scenes/fig4-steering.csv")).unwrap();
    let trajectory: Vec<pb::TrajectorySample> = csv
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("t_s") && !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            pb::TrajectorySample { t_s: v[0], base: Some(pb::Pose2 { x_m: v[1], y_m: v[2], theta_rad: v[3] }), base3: None }
        })
        .collect();
    let req = |keep: bool| pb::SimulateRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(scene.clone())) }),
        trajectory: trajectory.clone(),
        decimate: 1,
        keep_unconverged: keep,
    };
    let mut stream = sim.simulate(req(false)).await.expect("Simulate starts").into_inner();
    let mut error = None;
    while let Some(m) = stream.next().await {
        if let Err(e) = m {
            error = Some(e);
            break;
        }
    }
    let e = error.expect("the stream ends with an error");
    assert_eq!(e.code(), tonic::Code::FailedPrecondition, "{}", e.message());
    assert!(e.message().contains("the run stopped at tick ") && e.message().contains("did not converge"), "{}", e.message());
    let mut stream = sim.simulate(req(true)).await.expect("Simulate starts").into_inner();
    let mut marks = Vec::new();
    let mut finished = false;
    while let Some(m) = stream.next().await {
        match m.expect("a kept run streams to the end").event {
            Some(pb::simulate_response::Event::Series(c)) => marks.extend(c.rows.iter().map(|r| r.unconverged)),
            Some(pb::simulate_response::Event::Result(_)) => finished = true,
            _ => {}
        }
    }
    assert!(finished, "the kept run ends with its result");
    let first = marks.iter().position(|&u| u).expect("unconverged rows are marked");
    assert!(e.message().contains(&format!("the run stopped at tick {first} ")), "the first marked row {first}: {}", e.message());
    assert!(marks.iter().filter(|&&u| u).count() > 100);
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}
