//! Issue 13 (hardening), items 2 and 5, through the real server binary: every call a client can
//! make the server work for is bounded (ticks, reply size, image pixels, session memory, offline
//! calls at once), and every bad request gets the status the proto promises with a short message.

use std::time::Duration;

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, connect as channel, create_example_session as create, with_token};
use prost::Message;
use tokio_stream::StreamExt;
use tonic::Code;

const DOWN: f64 = -std::f64::consts::FRAC_PI_2;
const PHANTOM: &str = include_str!("../../server/scenes/paper-phantom.toml");
const CUBE3D: &str = include_str!("../../server/scenes/cube-phantom-3d.toml");

// The tests of this file start servers that compute hard; on a 2-core machine they take turns
// (with every real-time test of tests/it/).
use needlesim_tests::REALTIME as ONE_AT_A_TIME;

fn example(name: &str) -> Option<pb::SceneSource> {
    Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example(name.into())) })
}

fn toml(text: String) -> Option<pb::SceneSource> {
    Some(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) })
}

/// The paper phantom's needle, inserted 40 mm over the first second, then held until `end_s`.
fn insertion(end_s: f64) -> Vec<pb::TrajectorySample> {
    let at = |t_s: f64, y_m: f64| pb::TrajectorySample { t_s, base: Some(pb::Pose2 { x_m: 0.05, y_m, theta_rad: DOWN }), base3: None };
    vec![at(0.0, 0.205), at(1.0, 0.165), at(end_s, 0.165)]
}

/// A field of `/proc/<pid>/status` in kB (VmHWM: peak resident set).
fn proc_status_kb(pid: u32, field: &str) -> u64 {
    let text = std::fs::read_to_string(format!("/proc/{pid}/status")).expect("/proc/<pid>/status");
    let line = text.lines().find(|l| l.starts_with(field)).unwrap_or_else(|| panic!("no {field} in /proc/{pid}/status"));
    line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).expect("a number of kB")
}

/// A 16000 × 16000 8-bit gray PNG, all black: 256 megapixels in about 250 kB (made by Python's
/// zlib: the test crate has no PNG encoder).
fn huge_png() -> Vec<u8> {
    let script = r#"
import struct, sys, zlib
w = h = 16000
def chunk(t, d):
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
c = zlib.compressobj(9)
row = bytes(w + 1)
idat = b''.join(c.compress(row) for _ in range(h)) + c.flush()
ihdr = struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0)
sys.stdout.buffer.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', idat) + chunk(b'IEND', b''))
"#;
    let out = std::process::Command::new(needlesim_tests::python()).args(["-c", script]).output().expect("python runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stdout.len() < 1 << 20, "the PNG is small on disk ({} bytes)", out.stdout.len());
    out.stdout
}

/// A 10-million-tick Simulate is refused, a 100 000-tick one arrives in bounded chunks, a
/// 16000 × 16000 PNG is refused from its header: the server's peak RSS stays under 400 MiB.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_simulate_and_track_stay_within_a_memory_budget() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&[
        "--default-scene",
        "none",
        "--max-simulate-ticks",
        "200000",
        "--max-image-pixels",
        "25000000",
        "--max-offline-jobs",
        "2",
        "--max-session-memory-mb",
        "256",
    ]);
    let ch = channel(&server).await;
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());

    // 10 000 s at 1 kHz: 10 million ticks, over the limit.
    let req =
        pb::SimulateRequest { scene: example("paper-phantom"), trajectory: insertion(10_000.0), decimate: 1, keep_unconverged: false };
    let e = sim.simulate(req).await.expect_err("a 10M-tick Simulate is refused");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("10000000 ticks") && e.message().contains("--max-simulate-ticks"), "{}", e.message());

    // 100 s: 100 001 rows, streamed in chunks of at most 1000 rows, none over 1 MiB.
    let req = pb::SimulateRequest { scene: example("paper-phantom"), trajectory: insertion(100.0), decimate: 1, keep_unconverged: false };
    let mut stream = sim.simulate(req).await.expect("Simulate starts").into_inner();
    let (mut rows, mut chunks, mut largest_bytes, mut result) = (0usize, 0usize, 0usize, None);
    while let Some(m) = stream.next().await {
        let m = m.expect("a simulate message");
        largest_bytes = largest_bytes.max(m.encoded_len());
        match m.event {
            Some(pb::simulate_response::Event::Series(c)) => {
                assert!(!c.rows.is_empty() && c.rows.len() <= 1000, "a chunk of {} rows", c.rows.len());
                rows += c.rows.len();
                chunks += 1;
            }
            Some(pb::simulate_response::Event::Result(r)) => result = Some(r),
            _ => {}
        }
    }
    let result = result.expect("a result");
    assert_eq!(result.ticks, 100_001);
    assert_eq!(rows, 100_001, "every tick's row arrives");
    assert!(chunks >= 101, "{chunks} chunks");
    assert!(largest_bytes < 1 << 20, "largest message {largest_bytes} bytes");

    // A 256-megapixel PNG: refused from its header, nothing decoded.
    let mut identify = pb::identify_service_client::IdentifyServiceClient::new(ch.clone()).max_decoding_message_size(64 << 20);
    let req = pb::TrackRequest { frames: vec![pb::ImageFrame { t_s: 0.0, png: huge_png() }], m_per_px: 1e-4, ..Default::default() };
    let e = identify.track(req).await.expect_err("a 16000 × 16000 image is refused");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("16000 × 16000") && e.message().contains("--max-image-pixels"), "{}", e.message());

    let peak_mib = proc_status_kb(server.child.id(), "VmHWM") as f64 / 1024.0;
    println!("server peak RSS (VmHWM): {peak_mib:.0} MiB");
    assert!(peak_mib < 400.0, "the server's peak RSS is {peak_mib:.0} MiB");
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// 40 Simulates at once against `--max-offline-jobs 3`: at most 3 run, the others are refused
/// with RESOURCE_EXHAUSTED, and the slots come back when the clients go away.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_forty_concurrent_simulates_are_limited_to_max_offline_jobs() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-offline-jobs", "3"]);
    let ch = channel(&server).await;
    // 600 s of simulated time each (600 001 ticks): none ends during the test.
    let calls: Vec<_> = (0..40)
        .map(|_| {
            let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
            tokio::spawn(async move {
                let req = pb::SimulateRequest {
                    scene: example("paper-phantom"),
                    trajectory: insertion(600.0),
                    decimate: 1000,
                    keep_unconverged: false,
                };
                sim.simulate(req).await.map(|r| r.into_inner())
            })
        })
        .collect();
    let mut streams = Vec::new();
    let mut refused = 0;
    for c in calls {
        match c.await.unwrap() {
            Ok(s) => streams.push(s),
            Err(e) => {
                assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
                assert!(e.message().contains("--max-offline-jobs"), "{}", e.message());
                refused += 1;
            }
        }
    }
    println!("{} accepted, {refused} refused", streams.len());
    assert_eq!(streams.len(), 3, "exactly the limit runs ({refused} refused)");
    assert_eq!(refused, 37);
    assert_eq!(server.metric("needlesim_offline_jobs_running"), 3.0);
    assert_eq!(server.metric("needlesim_offline_jobs_peak"), 3.0);
    assert_eq!(server.metric("needlesim_offline_jobs_rejected"), 37.0);
    // The accepted ones are running: each streams progress.
    for s in &mut streams {
        let m = tokio::time::timeout(Duration::from_secs(120), s.next()).await.expect("progress in time");
        assert!(m.expect("a message").is_ok());
    }
    // Clients that go away free their slots: a new call is accepted again.
    drop(streams);
    let deadline = std::time::Instant::now() + Duration::from_secs(60);
    while server.metric("needlesim_offline_jobs_running") > 0.0 {
        assert!(std::time::Instant::now() < deadline, "the cancelled jobs did not end");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    let req = pb::SimulateRequest { scene: example("paper-phantom"), trajectory: insertion(2.0), decimate: 10, keep_unconverged: false };
    let mut s = sim.simulate(req).await.expect("accepted once the slots are free").into_inner();
    while let Some(m) = s.next().await {
        m.expect("a simulate message");
    }
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// A 31 × 31000 grid (961 000 nodes, under the 1M-node limit) is refused at once at default
/// settings, naming its estimated memory and the limit, without the server building it.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_a_huge_grid_session_is_refused_by_its_memory_estimate() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let text = PHANTOM.replace("nx = 19", "nx = 31").replace("ny = 19", "ny = 31000");
    let req = pb::CreateSessionRequest { scene: toml(text), tick_rate_hz: 1000.0, ..Default::default() };
    let e = sessions.create_session(req).await.expect_err("the grid is refused");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(
        e.message().contains("961000 mesh nodes") && e.message().contains("MiB") && e.message().contains("--max-session-memory-mb"),
        "{}",
        e.message()
    );
    let peak_mib = proc_status_kb(server.child.id(), "VmHWM") as f64 / 1024.0;
    println!("server peak RSS (VmHWM): {peak_mib:.0} MiB: {}", e.message());
    assert!(peak_mib < 400.0, "the server's peak RSS is {peak_mib:.0} MiB");
    // The shipped examples fit.
    for name in ["paper-phantom", "fig3-target", "fig4-steering", "bevel-tip"] {
        let r =
            sessions.create_session(pb::CreateSessionRequest { scene: example(name), tick_rate_hz: 1000.0, ..Default::default() }).await;
        let r = r.unwrap_or_else(|e| panic!("{name}: {e:?}")).into_inner();
        let sid = r.session.unwrap().session_id;
        sessions.close_session(with_token(pb::CloseSessionRequest { session_id: sid }, &r.controller_token)).await.unwrap();
    }
}

/// Bad scene values answer INVALID_ARGUMENT naming the key, from CreateSession and Simulate.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_bad_scene_values_are_invalid_argument_naming_the_field() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    let base = "base = [0.05, 0.205, -1.5707963267948966]";
    assert!(PHANTOM.contains(base));
    let limits = |kv: &str| format!("{PHANTOM}\n[limits]\n{kv}\n");
    let cases = [
        (PHANTOM.replace(base, "base = [nan, 0.205, -1.5707963267948966]"), "needle.base"),
        (limits("max_base_step_m = -1"), "limits.max_base_step_m"),
        (limits("max_active_set_iterations = 0"), "limits.max_active_set_iterations"),
        (PHANTOM.replace(base, &format!("{base}\nmax_nodes = 0")), "needle.max_nodes"),
        (PHANTOM.replace(base, &format!("{base}\nmax_nodes = 1000000000")), "needle.max_nodes"),
    ];
    for (text, field) in cases {
        let req = pb::CreateSessionRequest { scene: toml(text.clone()), tick_rate_hz: 1000.0, ..Default::default() };
        let e = sessions.create_session(req).await.expect_err(field);
        assert_eq!(e.code(), Code::InvalidArgument, "{field}: {}", e.message());
        assert!(e.message().contains(field), "{field}: {}", e.message());
        let req = pb::SimulateRequest { scene: toml(text), trajectory: insertion(2.0), decimate: 10, keep_unconverged: false };
        let e = sim.simulate(req).await.expect_err(field);
        assert_eq!(e.code(), Code::InvalidArgument, "Simulate, {field}: {}", e.message());
        assert!(e.message().contains(field), "{field}: {}", e.message());
    }
    // An uploaded scene's NaN needle base, too.
    let mesh = pb::Mesh { node_xy_m: vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0], triangle_nodes: vec![0, 1, 2], ..Default::default() };
    let up = pb::UploadedScene {
        mesh: Some(mesh),
        regions: vec![pb::Region { name: "t".into(), young_modulus_pa: 1e4, poisson_ratio: 0.3, ..Default::default() }],
        fixed_nodes: vec![0, 1],
        needle_base: Some(pb::Pose2 { x_m: f64::NAN, y_m: 0.0, theta_rad: 0.0 }),
        ..Default::default()
    };
    let req = pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Uploaded(up)) }),
        ..Default::default()
    };
    let e = sessions.create_session(req).await.expect_err("NaN base");
    assert_eq!(e.code(), Code::InvalidArgument, "{}", e.message());
    assert!(e.message().contains("scene.uploaded.needle_base"), "{}", e.message());
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Messages quote at most a short prefix of what the client sent: a 100 KB session id is
/// NOT_FOUND (not a metadata-size error), a 100 KB example name INVALID_ARGUMENT.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_messages_quote_a_short_prefix_of_the_input() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let long = "x".repeat(100_000);
    let e = sessions.get_session(pb::GetSessionRequest { session_id: long.clone() }).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound, "{}", e.message());
    assert!(e.message().len() < 200 && e.message().contains("xxxx…"), "{}", e.message());
    let e = sessions.create_session(pb::CreateSessionRequest { scene: example(&long), ..Default::default() }).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "{}", e.message());
    assert!(e.message().len() < 300 && e.message().contains("scene.example"), "{}", e.message());
    // A TOML error quoting a 100 KB line.
    let e = sessions
        .create_session(pb::CreateSessionRequest { scene: toml(format!("name = {long}")), ..Default::default() })
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "{}", e.message());
    assert!(e.message().len() <= 4 * 1024, "{} bytes", e.message().len());
}

/// A request over `--max-message-bytes` is RESOURCE_EXHAUSTED, as the proto promises for size
/// limits (tonic's own answer is OUT_OF_RANGE).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_an_oversized_message_is_resource_exhausted() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-message-bytes", "100000"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let text = format!("{PHANTOM}\n# {}\n", "x".repeat(200_000));
    let e = sessions.create_session(pb::CreateSessionRequest { scene: toml(text), ..Default::default() }).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    // The server goes on.
    create(&ch, "paper-phantom").await;
}

/// A recording that does not exist is NOT_FOUND; SetPose rejections are counted in GetStats.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_missing_recording_is_not_found_and_set_pose_rejections_are_counted() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let created = create(&ch, "paper-phantom").await;
    let sid = created.session.clone().unwrap().session_id;
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    let e = rec
        .download_recording(with_token(pb::DownloadRecordingRequest { name: "nope.mcap".into() }, &created.controller_token))
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::NotFound, "{}", e.message());
    let mut control = pb::control_service_client::ControlServiceClient::new(ch.clone());
    for x_m in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let bad =
            pb::SetPoseRequest { session_id: sid.clone(), base: Some(pb::Pose2 { x_m, y_m: 0.2, theta_rad: DOWN }), ..Default::default() };
        let e = control.set_pose(with_token(bad, &created.controller_token)).await.unwrap_err();
        assert_eq!(e.code(), Code::InvalidArgument);
    }
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let stats =
        sessions.get_stats(with_token(pb::GetSessionRequest { session_id: sid }, &created.observer_token)).await.unwrap().into_inner();
    assert_eq!(stats.rejected_poses, 3);
}

/// Issue 35 item 14: a 3D mesh over the node limit is RESOURCE_EXHAUSTED, as a 2D one is and as
/// the README says, from CreateSession and Simulate; a number of 1e300 in a scene is echoed as
/// "1e300" in a short message (it was 301 digits), in 2D and 3D.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_3d_node_limit_is_resource_exhausted_and_numbers_are_echoed_short() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    // The cube without its trajectory file (a scene from the API names no files).
    let cube: String = CUBE3D.lines().filter(|l| !l.starts_with("trajectory")).map(|l| format!("{l}\n")).collect();
    let grid = "nx = 21\nny = 21\nnz = 21\n";
    assert!(cube.contains(grid) && cube.contains("tick_rate_hz = 1000\n"));
    let big = cube.replace(grid, "nx = 101\nny = 101\nnz = 101\n");
    let e = sessions.create_session(pb::CreateSessionRequest { scene: toml(big.clone()), ..Default::default() }).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("1030301 nodes, over the limit of 1000000"), "{}", e.message());
    let e =
        sim.simulate(pb::SimulateRequest { scene: toml(big), trajectory: vec![], decimate: 10, ..Default::default() }).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "Simulate: {}", e.message());
    // 1e300, 2D and 3D.
    for (dim, text) in [(2, PHANTOM.to_owned()), (3, cube)] {
        assert!(text.contains("tick_rate_hz = 1000\n"), "{dim}D");
        let text = text.replace("tick_rate_hz = 1000\n", "tick_rate_hz = 1e300\n");
        let e = sessions.create_session(pb::CreateSessionRequest { scene: toml(text), ..Default::default() }).await.unwrap_err();
        assert_eq!(e.code(), Code::InvalidArgument, "{dim}D: {}", e.message());
        assert!(e.message().contains("tick_rate_hz = 1e300: must be between 100 and 10000"), "{dim}D: {}", e.message());
        assert!(e.message().len() < 200, "{dim}D: {}", e.message());
    }
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Issue 35 (hardening, inputs): a scene's targets are bounded by core's limit, 16, 2D and 3D,
/// from CreateSession, Simulate and an upload (INVALID_ARGUMENT naming the bound); a 2D session
/// with 16 targets carries every one in its live frames (a tick record held 8 and dropped the
/// rest); a 17th target's physics past its bounds (a 1e13 Pa region) is refused by name.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_targets_are_bounded_and_live_frames_carry_every_one() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    let one = "[[targets]]\nname = \"centre\"\ncenter_m = [0.05, 0.05]\nradius_m = 0.002\n";
    assert!(PHANTOM.contains(one));
    let targets2 = |n: usize| -> String {
        (0..n)
            .map(|k| format!("[[targets]]\nname = \"t{k}\"\ncenter_m = [0.05, {}]\nradius_m = 0.002\n\n", 0.02 + 0.004 * k as f64))
            .collect()
    };
    let want = "targets: 17 given, at most 16";
    let text = PHANTOM.replace(one, &targets2(17));
    let e = sessions
        .create_session(pb::CreateSessionRequest { scene: toml(text.clone()), tick_rate_hz: 1000.0, ..Default::default() })
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "{}", e.message());
    assert!(e.message().contains(want), "{}", e.message());
    let e = sim.simulate(pb::SimulateRequest { scene: toml(text), trajectory: insertion(2.0), decimate: 10, ..Default::default() }).await;
    let e = match e {
        Err(e) => e,
        Ok(r) => r.into_inner().next().await.expect("a message").expect_err("17 targets"),
    };
    assert_eq!(e.code(), Code::InvalidArgument, "Simulate: {}", e.message());
    assert!(e.message().contains(want), "Simulate: {}", e.message());
    // 3D, as TOML.
    let cube: String = CUBE3D.lines().filter(|l| !l.starts_with("trajectory")).map(|l| format!("{l}\n")).collect();
    let one3 = "[[targets]]\nname = \"centre\"\ncenter_m = [0.05, 0.05, 0.05]\nradius_m = 0.002\n";
    assert!(cube.contains(one3));
    let many3: String = (0..17).map(|k| one3.replace("centre", &format!("c{k}"))).collect();
    let e = sessions.create_session(pb::CreateSessionRequest { scene: toml(cube.replace(one3, &many3)), ..Default::default() }).await;
    let e = e.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "3D: {}", e.message());
    assert!(e.message().contains(want), "3D: {}", e.message());
    // An upload.
    let mesh =
        pb::Mesh { node_xy_m: vec![0.0, 0.0, 0.1, 0.0, 0.1, 0.1, 0.0, 0.1], triangle_nodes: vec![0, 1, 2, 0, 2, 3], ..Default::default() };
    let target = |k: usize| pb::Target { name: format!("u{k}"), center_m: Some(pb::Vec2 { x: 0.05, y: 0.05 }), radius_m: 0.001 };
    let up = |n: usize, young_modulus_pa: f64| pb::UploadedScene {
        mesh: Some(mesh.clone()),
        regions: vec![pb::Region { name: "t".into(), young_modulus_pa, poisson_ratio: 0.3, ..Default::default() }],
        fixed_nodes: vec![0, 1],
        needle_base: Some(pb::Pose2 { x_m: 0.05, y_m: 0.2, theta_rad: -std::f64::consts::FRAC_PI_2 }),
        targets: (0..n).map(target).collect(),
        ..Default::default()
    };
    let uploaded = |u| pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Uploaded(u)) }),
        ..Default::default()
    };
    let e = sessions.create_session(uploaded(up(17, 1e4))).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "upload: {}", e.message());
    assert!(e.message().contains(want), "upload: {}", e.message());
    let e = sessions.create_session(uploaded(up(1, 1e13))).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "upload, 1e13 Pa: {}", e.message());
    assert!(e.message().contains("Young's modulus E = 10000000000000 Pa must be finite, > 0 and ≤ 1e12 Pa"), "{}", e.message());
    // 16 targets: every live frame carries all of them, by name.
    let text = PHANTOM.replace(one, &targets2(16));
    let made = sessions
        .create_session(pb::CreateSessionRequest { scene: toml(text), tick_rate_hz: 1000.0, ..Default::default() })
        .await
        .expect("16 targets")
        .into_inner();
    let sid = made.session.expect("session").session_id;
    let frame = needlesim_tests::latest_frame(&ch, &sid, &made.observer_token).await;
    let names: Vec<&str> = frame.targets.iter().map(|t| t.name.as_str()).collect();
    let want_names: Vec<String> = (0..16).map(|k| format!("t{k}")).collect();
    assert_eq!(names, want_names.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}
