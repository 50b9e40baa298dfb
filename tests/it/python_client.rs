//! The Python client of client/python/ against the real server: the demo (uploaded mesh, offline
//! Simulate with progress, live watch, close), health checking, server reflection, a recording
//! driven by SetPose and checked with the Python `mcap` package, a SIGKILLed Python client, and a
//! SIGKILLed server whose recording must still be readable.
//!
//! The stubs are generated with grpc_tools.protoc (client/python/generate.py) into a temporary
//! directory that is put on PYTHONPATH.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{
    ServerProcess, TempDir, connect as channel, create_example_session as create, python, repo_root, run, text, with_token,
};
use tokio_stream::StreamExt;
use tonic::transport::Channel;

/// The tests run one at a time (with every real-time test of tests/it/): each runs a 1 kHz session,
/// and the recording test counts ticks.
fn serial() -> tokio::sync::MutexGuard<'static, ()> {
    needlesim_tests::REALTIME.blocking_lock()
}

/// Runs the async part of a test on its own runtime (the serial guard is held outside it).
fn block_on<F: std::future::Future>(f: F) -> F::Output {
    tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().expect("a tokio runtime").block_on(f)
}

fn client_dir() -> PathBuf {
    repo_root().join("client/python")
}

/// Generates the stubs into a fresh temporary directory.
fn stubs() -> TempDir {
    let dir = TempDir::new("pystubs");
    let out = run(Command::new(python()).arg(client_dir().join("generate.py")).arg(dir.path()));
    let (o, e) = text(&out);
    assert!(out.status.success(), "generate.py failed:\n{o}\n{e}");
    assert!(dir.join("needlesim/v1/needlesim_pb2.py").is_file() && dir.join("needlesim/v1/needlesim_pb2_grpc.py").is_file());
    dir
}

/// `python needlesim_client.py --address ADDR ARGS…` with the stubs on PYTHONPATH.
fn client_cmd(server: &ServerProcess, stubs: &TempDir, args: &[&str]) -> Command {
    let mut cmd = Command::new(python());
    cmd.env("PYTHONPATH", stubs.path())
        .env("PYTHONUNBUFFERED", "1")
        .arg(client_dir().join("needlesim_client.py"))
        .args(["--address", &server.addr])
        .args(args);
    cmd
}

/// Runs the client to completion and returns its standard output; panics when it fails.
fn client(server: &ServerProcess, stubs: &TempDir, args: &[&str]) -> String {
    let out: Output = run(&mut client_cmd(server, stubs, args));
    let (o, e) = text(&out);
    assert!(out.status.success(), "needlesim_client.py {args:?} failed ({}):\n{o}\n{e}", out.status);
    o
}

fn mcap_check(file: &Path, tolerate_truncation: bool) -> serde_json::Value {
    let mut cmd = Command::new(python());
    cmd.arg(repo_root().join("tests/mcap_check.py")).arg(file);
    if tolerate_truncation {
        cmd.arg("--tolerate-truncation");
    }
    let out = run(&mut cmd);
    let (o, e) = text(&out);
    assert!(out.status.success(), "mcap_check.py {} failed:\n{o}\n{e}", file.display());
    serde_json::from_str(o.trim()).unwrap_or_else(|err| panic!("mcap_check.py printed no JSON ({err}):\n{o}\n{e}"))
}

/// The numbers of a line `PREFIX…` of the output, e.g. "simulate result: 201 rows, 2001 ticks".
fn numbers(line: &str) -> Vec<f64> {
    line.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .filter_map(|w| w.trim_matches(|c| c == '.' || c == 'e').parse::<f64>().ok())
        .collect()
}

fn line_with<'a>(out: &'a str, prefix: &str) -> &'a str {
    out.lines().find(|l| l.starts_with(prefix)).unwrap_or_else(|| panic!("no line `{prefix}…` in the output:\n{out}"))
}

#[test]
fn demo_uploads_a_mesh_simulates_watches_and_closes() {
    let _serial = serial();
    block_on(async move {
        let server = ServerProcess::start(&["--default-scene", "none"]);
        let stubs = stubs();
        let out = client(&server, &stubs, &["demo"]);

        // The session of the uploaded 21 x 13 grid: 273 nodes, 2 * 20 * 12 = 480 triangles.
        let created = line_with(&out, "session created: ");
        let sid = created["session created: ".len()..].split_whitespace().next().unwrap().to_owned();
        assert!(created.contains("(273 nodes, 480 triangles, 1000 Hz)"), "{created}");

        // Progress of the 2 s offline insertion at 1 kHz, increasing up to its total.
        let progress: Vec<(f64, f64)> = out
            .lines()
            .filter(|l| l.starts_with("simulate progress: "))
            .map(|l| {
                let n = numbers(&l["simulate progress: ".len()..].replace('/', " "));
                (n[0], n[1])
            })
            .collect();
        assert!(progress.len() >= 2, "progress lines: {progress:?}\n{out}");
        assert!(progress.windows(2).all(|w| w[0].0 < w[1].0), "progress does not increase: {progress:?}");
        assert!(progress.iter().all(|p| p.1 == 2000.0), "ticks_total is not 2000: {progress:?}");
        assert_eq!(progress.last().unwrap().0, 2000.0, "the last progress is not complete: {progress:?}");

        // The result: one row every 10 ticks of 2001 ticks, and a tip that reached the target.
        let result = numbers(line_with(&out, "simulate result: "));
        assert_eq!((result[0], result[1]), (201.0, 2001.0), "rows and ticks: {out}");
        let dist = line_with(&out, "tip-target distance: ");
        let d = numbers(dist);
        let (start, end) = (d[0], d[1]);
        assert!((start - 0.035).abs() < 1e-6, "the tip starts 35 mm from the target: {dist}");
        assert!(end < 0.003 && dist.ends_with("hit True"), "the insertion does not reach the target: {dist}");

        // The live session watched for 1 s at 30 Hz.
        let watched = line_with(&out, "watched: ");
        let frames = numbers(watched)[0];
        assert!((20.0..=35.0).contains(&frames), "{frames} frames in 1 s at 30 Hz: {watched}");

        assert_eq!(line_with(&out, "session closed: "), format!("session closed: {sid}"));
        let ch = channel(&server).await;
        let listed = pb::session_service_client::SessionServiceClient::new(ch).list_sessions(pb::ListSessionsRequest {}).await.unwrap();
        assert!(listed.get_ref().sessions.is_empty(), "the demo's session is still open: {:?}", listed.get_ref().sessions);
    });
}

#[test]
fn health_checks_through_grpc_health_v1() {
    let _serial = serial();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let stubs = stubs();
    assert_eq!(client(&server, &stubs, &["health"]).trim(), "SERVING");
    assert_eq!(client(&server, &stubs, &["health", "needlesim.v1.SessionService"]).trim(), "SERVING");
    assert_eq!(client(&server, &stubs, &["health", "needlesim.v1.PlanningService"]).trim(), "SERVING");
    assert_eq!(client(&server, &stubs, &["health", "needlesim.v1.IdentifyService"]).trim(), "SERVING");
    assert_eq!(client(&server, &stubs, &["health", "needlesim.v1.NoSuchService"]).trim(), "NOT_FOUND");
}

#[test]
fn reflection_lists_every_service() {
    let _serial = serial();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let stubs = stubs();
    let out = client(&server, &stubs, &["services"]);
    let services: Vec<&str> = out.lines().map(str::trim).collect();
    for s in [
        "needlesim.v1.SessionService",
        "needlesim.v1.ControlService",
        "needlesim.v1.ObserveService",
        "needlesim.v1.SimulationService",
        "needlesim.v1.RecordingService",
        "grpc.health.v1.Health",
    ] {
        assert!(services.contains(&s), "reflection does not list {s}: {services:?}");
    }
}

#[test]
fn a_recording_driven_by_set_pose_holds_every_tick() {
    let _serial = serial();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let stubs = stubs();
    let tmp = TempDir::new("pyrec");
    let file = tmp.join("download.mcap");
    let out = client(&server, &stubs, &["record", "--seconds", "2", "--out", file.to_str().unwrap()]);
    let info: serde_json::Value = serde_json::from_str(out.trim()).unwrap_or_else(|e| panic!("no JSON ({e}): {out}"));
    assert_eq!(info["finished"], true, "{info}");
    assert_eq!(info["downloaded_bytes"], info["size_bytes"], "the download differs from the file: {info}");
    assert_eq!(info["dropped_records"], 0, "{info}");
    assert!(info["poses"].as_u64().unwrap() >= 50, "too few SetPose calls: {info}");
    assert_eq!(std::fs::metadata(&file).unwrap().len(), info["size_bytes"].as_u64().unwrap());

    let check = mcap_check(&file, false);
    let messages = check["messages"].as_u64().unwrap();
    let (first, last) = (check["first_sequence"].as_u64().unwrap(), check["last_sequence"].as_u64().unwrap());
    assert_eq!(messages, info["messages"].as_u64().unwrap(), "StopRecording and the file disagree: {check} {info}");
    assert_eq!(last - first + 1, messages, "the recording misses ticks: {check}");
    assert!(messages >= 1500, "{messages} messages in 2 s at 1 kHz: {check}");
    assert!(messages <= info["ticks"].as_u64().unwrap(), "more messages than ticks: {check} {info}");
    // The recording's name starts with its session's id; Foxglove's topics carry it.
    let topics: Vec<&str> = check["topics"].as_array().unwrap().iter().filter_map(|t| t.as_str()).collect();
    let sid = info["name"].as_str().unwrap().split('-').next().unwrap_or_default();
    let sid = topics.iter().find_map(|t| t.strip_suffix("/scene")).and_then(|t| t.strip_prefix("/needlesim/")).unwrap_or(sid);
    assert!(info["name"].as_str().unwrap().starts_with(sid), "the scene topic names another session: {check} {info}");
    let mut want =
        [format!("/needlesim/{sid}/force"), format!("/needlesim/{sid}/scene"), "/needlesim/frames".into(), "/needlesim/tissue".into()];
    want.sort();
    assert_eq!(topics, want, "{check}");
    // The tissue for a player: the 2D session's mesh, once.
    assert_eq!(
        check["schema_names"],
        serde_json::json!(["foxglove.SceneUpdate", "needlesim.ForceSample", "needlesim.v1.Frame", "needlesim.v1.Mesh"]),
        "{check}"
    );
    assert_eq!(check["in_order"], true, "{check}");
    assert_eq!(check["truncated"], false, "{check}");
    // Issue 17: the recording opens in Foxglove — its scene in Foxglove's schema (decoded with the
    // descriptor the file carries: the tissue, the needle, its contacts, the targets) and a force
    // sample per recorded tick for the Plot panel.
    let fox = &check["foxglove"];
    assert_eq!(fox["scene_entities"], serde_json::json!(["contacts", "needle", "targets", "tissue"]), "{check}");
    assert_eq!(fox["force"].as_u64(), Some(messages), "a force sample per recorded frame: {check}");
    assert!(fox["scene"].as_u64().unwrap() >= 30, "scenes at 30 Hz over 2 s: {check}");
    assert_eq!(fox["force_keys"], serde_json::json!(["depth_m", "force_n", "time_s", "torque_nm"]), "{check}");
}

#[test]
fn a_killed_python_client_leaves_the_session_healthy() {
    let _serial = serial();
    block_on(async move {
        let server = ServerProcess::start(&["--default-scene", "none"]);
        let stubs = stubs();
        let ch = channel(&server).await;
        let created = create(&ch, "paper-phantom").await;
        let sid = created.session.as_ref().unwrap().session_id.clone();
        let (ctl_tok, obs_tok) = (created.controller_token.clone(), created.observer_token.clone());

        let mut child = client_cmd(&server, &stubs, &["hold", "--session", &sid, "--token", &ctl_tok])
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start the Python client");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
        assert!(line.starts_with("holding: "), "the client did not get its streams going: {line:?}");
        let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
        let info = sessions.get_session(pb::GetSessionRequest { session_id: sid.clone() }).await.unwrap().into_inner();
        assert_eq!(info.n_observers, 1, "the client's observer is not counted: {info:?}");
        tokio::time::sleep(Duration::from_secs(1)).await;
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();

        // The server notices that the observer is gone.
        let deadline = Instant::now() + Duration::from_secs(5);
        loop {
            let info = sessions.get_session(pb::GetSessionRequest { session_id: sid.clone() }).await.unwrap().into_inner();
            if info.n_observers == 0 {
                break;
            }
            assert!(Instant::now() < deadline, "the killed client's observer is still counted: {info:?}");
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        // The session keeps ticking, dropped nothing, and serves a new observer and controller.
        let stats = |sessions: &mut pb::session_service_client::SessionServiceClient<Channel>| {
            let req = with_token(pb::GetSessionRequest { session_id: sid.clone() }, &obs_tok);
            let mut c = sessions.clone();
            async move { c.get_stats(req).await.unwrap().into_inner() }
        };
        let s1 = stats(&mut sessions).await;
        tokio::time::sleep(Duration::from_millis(500)).await;
        let s2 = stats(&mut sessions).await;
        assert!(s2.ticks >= s1.ticks + 250, "the session stalled: {} -> {} ticks in 0.5 s", s1.ticks, s2.ticks);
        assert_eq!(s2.dropped_records, 0, "{s2:?}");

        let mut obs = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
        let req = with_token(pb::ObserveRequest { session_id: sid.clone(), rate_hz: 0.0, include_displacements: false }, &obs_tok);
        let mut stream = obs.observe(req).await.expect("a new observer").into_inner();
        let mut ticks = Vec::new();
        let end = Instant::now() + Duration::from_millis(500);
        while let Ok(Some(Ok(f))) = tokio::time::timeout_at(end.into(), stream.next()).await {
            ticks.push(f.tick);
        }
        assert!(ticks.len() >= 200, "the new observer got {} frames in 0.5 s", ticks.len());
        assert!(ticks.windows(2).all(|w| w[0] < w[1]), "frames out of order");
        let mut ctl = pb::control_service_client::ControlServiceClient::new(ch.clone());
        let pose = pb::Pose2 { x_m: 0.05, y_m: 0.2, theta_rad: -std::f64::consts::FRAC_PI_2 };
        ctl.set_pose(with_token(
            pb::SetPoseRequest { session_id: sid.clone(), base: Some(pose), client_id: String::new(), take_over: false },
            &ctl_tok,
        ))
        .await
        .expect("a new controller");
    });
}

#[test]
fn a_killed_server_leaves_a_readable_recording() {
    let _serial = serial();
    block_on(async move {
        let mut server = ServerProcess::start(&["--default-scene", "none"]);
        let ch = channel(&server).await;
        let created = create(&ch, "paper-phantom").await;
        let sid = created.session.as_ref().unwrap().session_id.clone();
        let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
        let info = rec
            .start_recording(with_token(
                pb::StartRecordingRequest { session_id: sid.clone(), include_displacements: false },
                &created.controller_token,
            ))
            .await
            .expect("start a recording")
            .into_inner();
        tokio::time::sleep(Duration::from_millis(2200)).await;
        server.child.kill().unwrap(); // SIGKILL
        server.child.wait().unwrap();

        let dir = server.data_dir.join("recordings");
        let files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "mcap"))
            .collect();
        assert_eq!(files, vec![dir.join(&info.name)], "the recordings after the crash");
        let check = mcap_check(&files[0], true);
        let messages = check["messages"].as_u64().unwrap();
        assert!(messages >= 1, "nothing of 2 s of recording survived the crash: {check}");
        let (first, last) = (check["first_sequence"].as_u64().unwrap(), check["last_sequence"].as_u64().unwrap());
        assert_eq!(last - first + 1, messages, "the surviving recording misses ticks: {check}");
        assert_eq!(check["in_order"], true, "{check}");
        assert_eq!(check["truncated"], true, "a killed server cannot have finished the file: {check}");
        assert!(check["schema_names"].as_array().unwrap().iter().any(|n| n == "needlesim.v1.Frame"), "{check}");
        eprintln!("after the crash: {check}");
    });
}
