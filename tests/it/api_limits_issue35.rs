//! Issue 35 ("Hardening, round 3"), through the real server binary: a training exercise over the
//! node limit is RESOURCE_EXHAUSTED as a session is; recordings are named as files, never as
//! paths, and bounded on disk (`--max-recordings`, `--max-recordings-mb`) as the after-action
//! reports are (`--max-reports`, `--max-reports-mb`); an Identify call whose client goes away
//! stops and frees its offline slot.

use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, connect as channel};
use tokio_stream::StreamExt;
use tonic::Code;

// These tests start servers that compute hard: they take turns with the real-time tests.
use needlesim_tests::REALTIME as ONE_AT_A_TIME;

/// Waits (generously) until the metric `name` is `value`; returns whether it got there.
async fn metric_becomes(server: &ServerProcess, name: &str, value: f64, within: Duration) -> bool {
    let deadline = Instant::now() + within;
    while Instant::now() < deadline {
        if server.metric(name) == value {
            return true;
        }
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    server.metric(name) == value
}

/// Issue 35 item 14: CreateExerciseSession of a 3D (and a 2D) exercise whose mesh is over the
/// server's node limit answers RESOURCE_EXHAUSTED naming the limit, as CreateSession does.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_exercise_over_the_node_limit_is_resource_exhausted() {
    let _turn = ONE_AT_A_TIME.lock().await;
    // block-3d has 21 × 9 × 13 = 2457 nodes; the 2D exercises' meshes have more than 200.
    let server = ServerProcess::start(&["--default-scene", "none", "--max-nodes", "200"]);
    let ch = channel(&server).await;
    let mut training = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    for exercise in ["biopsy-3d", "biopsy-2d"] {
        let req = pb::CreateExerciseSessionRequest { exercise: exercise.into(), ..Default::default() };
        let e = training.create_exercise_session(req).await.expect_err("over the node limit");
        assert_eq!(e.code(), Code::ResourceExhausted, "{exercise}: {}", e.message());
        assert!(e.message().contains("over the limit of 200"), "{exercise}: {}", e.message());
        assert!(e.message().contains(exercise), "{exercise}: {}", e.message());
    }
    assert_eq!(server.metric("needlesim_sessions"), 0.0, "no session was left behind");
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// A `side` × `side` 8-bit gray PNG, white with a 10 × 10 grid of dark 6 × 6 px markers (made by
/// Python's zlib: the test crate has no PNG encoder).
fn dotted_png(side: u32) -> Vec<u8> {
    let script = format!(
        r#"
import struct, sys, zlib
w = h = {side}
step = w // 11
def chunk(t, d):
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
plain = b'\x00' + bytes([255]) * w
row = bytearray(plain)
for i in range(1, 11):
    for x in range(i * step, i * step + 6):
        row[1 + x] = 0
dotted = bytes(row)
rows = []
for y in range(h):
    rows.append(dotted if any(i * step <= y < i * step + 6 for i in range(1, 11)) else plain)
idat = zlib.compress(b''.join(rows), 6)
ihdr = struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0)
sys.stdout.buffer.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', idat) + chunk(b'IEND', b''))
"#
    );
    let out = std::process::Command::new(needlesim_tests::python()).args(["-c", &script]).output().expect("python runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    out.stdout
}

/// A Track call of `n` copies of `png`, 0.1 s apart.
fn track_request(png: &[u8], n: usize) -> pb::TrackRequest {
    let frames = (0..n).map(|k| pb::ImageFrame { t_s: k as f64 * 0.1, png: png.to_vec() }).collect();
    pb::TrackRequest { frames, m_per_px: 1e-4, expected_markers: 100, ..Default::default() }
}

/// Issue 35: an Identify call whose client cancels (drops the stream) or disconnects stops at
/// its next frame and gives its `--max-offline-jobs` slot back (it held it until every frame was
/// tracked, minutes here), as Simulate and Plan do.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_cancelled_identify_call_stops_and_frees_its_offline_slot() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-offline-jobs", "1", "--max-message-bytes", "268435456"]);
    let png = dotted_png(3000);
    // Thousands of 9-megapixel frames: minutes of tracking, far longer than the waits below.
    let long = track_request(&png, 4000);
    let short = track_request(&png, 2);
    let running = "needlesim_offline_jobs_running";
    for how in ["cancel", "disconnect"] {
        let ch = channel(&server).await;
        let mut identify = pb::identify_service_client::IdentifyServiceClient::new(ch.clone());
        let mut stream = identify.track(long.clone()).await.expect("Track starts").into_inner();
        let first = stream.next().await.expect("a progress message").expect("progress, not an error");
        assert!(first.result.is_none() && first.done >= 1 && first.total == 4000, "{how}: {first:?}");
        assert_eq!(server.metric(running), 1.0, "{how}: the call holds the slot");
        // The slot is taken: another offline call is refused.
        let other = channel(&server).await;
        let mut other = pb::identify_service_client::IdentifyServiceClient::new(other);
        let e = other.track(short.clone()).await.expect_err("the only slot is taken");
        assert_eq!(e.code(), Code::ResourceExhausted, "{how}: {}", e.message());
        assert!(e.message().contains("--max-offline-jobs"), "{how}: {}", e.message());
        match how {
            "cancel" => drop(stream),
            _ => {
                drop(stream);
                drop(identify);
                drop(ch);
            }
        }
        // The work stops at its next frame (a fraction of a second); 60 s is a generous margin.
        assert!(metric_becomes(&server, running, 0.0, Duration::from_secs(60)).await, "{how}: the slot is still held after 60 s");
        // The slot serves the next call.
        let mut done = other.track(short.clone()).await.expect("the slot is free again").into_inner();
        let mut result = None;
        while let Some(m) = done.next().await {
            result = m.expect("a progress message").result.or(result);
        }
        match result {
            Some(pb::identify_progress::Result::Track(t)) => assert_eq!((t.n_markers, t.n_frames), (100, 2), "{how}"),
            other => panic!("{how}: {other:?}"),
        }
    }
    let log = server.stderr.lock().unwrap().clone();
    assert!(!log.contains("panicked"), "{log}");
}

/// Issue 35: a recording's name is a file name, never a path: over 255 bytes (it was an
/// INTERNAL "File name too long") or with characters outside letters, digits, `-`, `_` and `.`
/// (a space, a newline: they were looked up, NOT_FOUND) is INVALID_ARGUMENT naming `name`, as
/// `../` always was.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_recording_names_are_short_safe_file_names() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch);
    let long = format!("{}.mcap", "a".repeat(300));
    for name in [long.as_str(), "a b.mcap", "a\nb.mcap", "a;b.mcap", "é.mcap", "../x.mcap", ".hidden.mcap"] {
        let req = pb::DownloadRecordingRequest { name: name.into() };
        let e = match rec.download_recording(req).await {
            Err(e) => e,
            Ok(mut stream) => stream.get_mut().next().await.and_then(Result::err).unwrap_or_else(|| panic!("{name:?} was opened")),
        };
        assert_eq!(e.code(), Code::InvalidArgument, "{name:?}: {}", e.message());
        assert!(e.message().starts_with("name: "), "{name:?}: {}", e.message());
        assert!(e.message().len() < 400, "{name:?}: {}", e.message());
    }
    // A well-formed name that is not there is still NOT_FOUND.
    let e = rec.download_recording(pb::DownloadRecordingRequest { name: "s-1-20240229T123456Z.mcap".into() }).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound, "{}", e.message());
}

/// Sessions' recordings in `server`'s directory, on disk: (name, bytes).
fn recordings_on_disk(server: &ServerProcess) -> Vec<(String, u64)> {
    let dir = server.data_dir.join("recordings");
    let mut v: Vec<(String, u64)> = std::fs::read_dir(&dir)
        .map(|it| {
            it.filter_map(Result::ok)
                .filter(|e| e.file_name().to_string_lossy().ends_with(".mcap"))
                .map(|e| (e.file_name().to_string_lossy().into_owned(), e.metadata().unwrap().len()))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// Bytes of every file in `dir`.
fn dir_bytes(dir: &std::path::Path) -> u64 {
    std::fs::read_dir(dir).map(|it| it.filter_map(Result::ok).map(|e| e.metadata().map_or(0, |m| m.len())).sum()).unwrap_or(0)
}

/// Issue 35: StartRecording is refused with RESOURCE_EXHAUSTED naming the flag when the
/// recordings directory holds `--max-recordings` files, or when `--max-recordings-mb` leaves
/// too little room to start; deleting files makes room again without a restart.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_start_recording_is_refused_at_max_recordings_and_max_recordings_mb() {
    let _turn = ONE_AT_A_TIME.lock().await;
    // The count: two recordings, then the third is refused.
    let server = ServerProcess::start(&["--default-scene", "none", "--max-recordings", "2"]);
    let ch = channel(&server).await;
    let created = needlesim_tests::create_example_session(&ch, "paper-phantom").await;
    let (sid, token) = (created.session.clone().expect("a session").session_id, created.controller_token.clone());
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    let start = || needlesim_tests::with_token(pb::StartRecordingRequest { session_id: sid.clone(), include_displacements: false }, &token);
    let stop = || needlesim_tests::with_token(pb::StopRecordingRequest { session_id: sid.clone() }, &token);
    for _ in 0..2 {
        rec.start_recording(start()).await.expect("StartRecording");
        // Distinct names: the recording's name has the second it started.
        tokio::time::sleep(Duration::from_millis(1100)).await;
        rec.stop_recording(stop()).await.expect("StopRecording");
    }
    let e = rec.start_recording(start()).await.expect_err("a third recording");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("--max-recordings") && e.message().contains("2 files"), "{}", e.message());
    assert_eq!(recordings_on_disk(&server).len(), 2);
    assert_eq!(server.metric("needlesim_recordings_refused"), 1.0);
    let (first, _) = recordings_on_disk(&server)[0].clone();
    std::fs::remove_file(server.data_dir.join("recordings").join(&first)).unwrap();
    rec.start_recording(start()).await.expect("room again after a delete");
    rec.stop_recording(stop()).await.expect("StopRecording");
    drop(server);

    // The bytes: a directory already holding 1 MiB against --max-recordings-mb 1.
    let data = needlesim_tests::TempDir::new("server");
    std::fs::create_dir_all(data.join("recordings")).unwrap();
    std::fs::write(data.join("recordings/old.mcap"), vec![0u8; 1 << 20]).unwrap();
    let server = ServerProcess::start_in(data, &["--default-scene", "none", "--max-recordings-mb", "1"]);
    let ch = channel(&server).await;
    let created = needlesim_tests::create_example_session(&ch, "paper-phantom").await;
    let (sid, token) = (created.session.clone().expect("a session").session_id, created.controller_token.clone());
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    let start = || needlesim_tests::with_token(pb::StartRecordingRequest { session_id: sid.clone(), include_displacements: false }, &token);
    let e = rec.start_recording(start()).await.expect_err("a full directory");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("--max-recordings-mb"), "{}", e.message());
    assert_eq!(recordings_on_disk(&server), vec![("old.mcap".to_owned(), 1 << 20)], "no file was made");
    std::fs::remove_file(server.data_dir.join("recordings/old.mcap")).unwrap();
    rec.start_recording(start()).await.expect("room again after a delete");
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Issue 35: a recording that grows to `--max-recordings-mb` is stopped and finished at the
/// limit (a valid MCAP file with its summary, read by the Python `mcap` package), not left to
/// fill the disk; StopRecording then answers its info, and the next StartRecording is refused.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_recording_reaching_max_recordings_mb_is_stopped_and_finished() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-recordings-mb", "2"]);
    let ch = channel(&server).await;
    let created = needlesim_tests::create_example_session(&ch, "paper-phantom").await;
    let (sid, token) = (created.session.clone().expect("a session").session_id, created.controller_token.clone());
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    let start = || needlesim_tests::with_token(pb::StartRecordingRequest { session_id: sid.clone(), include_displacements: true }, &token);
    rec.start_recording(start()).await.expect("StartRecording");
    // The session ticks at 1 kHz with the displacement field 10 times a second: the recording
    // reaches 2 MiB within a minute or so; 600 s is a generous margin.
    let stopped = metric_becomes(&server, "needlesim_recordings_stopped_at_limit", 1.0, Duration::from_secs(600)).await;
    assert!(stopped, "the recording was not stopped: {:?}", recordings_on_disk(&server));
    // It stays under the limit while the session goes on.
    tokio::time::sleep(Duration::from_secs(3)).await;
    let dir = server.data_dir.join("recordings");
    let bytes = dir_bytes(&dir);
    assert!(bytes <= 2 << 20, "{bytes} bytes in the recordings directory");
    let on_disk = recordings_on_disk(&server);
    assert_eq!(on_disk.len(), 1, "{on_disk:?}");
    assert!(on_disk[0].1 > 1 << 20, "the recording used the room it had: {on_disk:?}");
    let info = rec.stop_recording(needlesim_tests::with_token(pb::StopRecordingRequest { session_id: sid.clone() }, &token)).await;
    let info = info.expect("StopRecording").into_inner();
    assert!(info.finished, "{info:?}");
    assert_eq!(dir_bytes(&dir), bytes, "nothing was written after the stop");
    // A valid MCAP file: the seeking reader uses its summary.
    let check = crate::cli3d::mcap_check(&dir.join(&on_disk[0].0));
    assert!(check["messages"].as_u64().unwrap_or(0) > 1000, "{check}");
    assert_eq!(check["truncated"], serde_json::json!(false), "{check}");
    // No room for another.
    let e = rec.start_recording(start()).await.expect_err("the directory is full");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("--max-recordings-mb"), "{}", e.message());
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Issue 35: the after-action reports written to `<data-dir>/reports/` are bounded by
/// `--max-reports` (and `--max-reports-mb`): past it EndExercise answers RESOURCE_EXHAUSTED
/// naming the flag and writes nothing.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_after_action_reports_are_bounded_by_max_reports() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-reports", "1"]);
    let ch = channel(&server).await;
    let mut training = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let reports = server.data_dir.join("reports");
    let count = || std::fs::read_dir(&reports).map(|it| it.count()).unwrap_or(0);
    for k in 0..2 {
        let req = pb::CreateExerciseSessionRequest { exercise: "biopsy-2d".into(), ..Default::default() };
        let created = training.create_exercise_session(req).await.expect("CreateExerciseSession").into_inner();
        let session = created.session.and_then(|s| s.session).expect("a session");
        let end = needlesim_tests::with_token(pb::ExerciseRequest { session_id: session.session_id.clone() }, &created.instructor_token);
        let r = training.end_exercise(end).await;
        if k == 0 {
            r.expect("the first report is written");
            assert_eq!(count(), 1);
        } else {
            let e = r.expect_err("a second report is over --max-reports 1");
            assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
            assert!(e.message().contains("--max-reports"), "{}", e.message());
            assert_eq!(count(), 1, "no second report was written");
        }
    }
    assert_eq!(server.metric("needlesim_reports_refused"), 1.0);
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// The shipped paper-phantom scene's TOML.
fn paper_phantom_toml() -> String {
    std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/paper-phantom.toml")).expect("the shipped scene")
}

/// Issue 35 (hostile pass, finding 1): with the recordings directory full, CreateSession and
/// CreateExerciseSession with `record` answered RESOURCE_EXHAUSTED but left their session
/// running — a `--max-sessions` place and a real-time thread that nobody could close, no token
/// having been returned. A create succeeds whole or leaves nothing.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_create_refused_for_its_recording_leaves_no_session() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-recordings", "0"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let req = pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
        record: true,
        ..Default::default()
    };
    let e = sessions.create_session(req).await.expect_err("no room for a recording");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("--max-recordings"), "{}", e.message());
    let mut training = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let req = pb::CreateExerciseSessionRequest { exercise: "biopsy-2d".into(), record: true, ..Default::default() };
    let e = training.create_exercise_session(req).await.expect_err("no room for a recording");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("--max-recordings"), "{}", e.message());
    let list = sessions.list_sessions(pb::ListSessionsRequest {}).await.expect("ListSessions").into_inner();
    assert!(list.sessions.is_empty(), "sessions left behind: {:?}", list.sessions.iter().map(|s| &s.session_id).collect::<Vec<_>>());
    assert!(metric_becomes(&server, "needlesim_sessions_alive", 0.0, Duration::from_secs(10)).await, "a session is still alive");
    assert_eq!(server.metric("needlesim_sessions"), 0.0);
    // The places are free: the same creates without a recording succeed.
    let req = pb::CreateExerciseSessionRequest { exercise: "biopsy-2d".into(), ..Default::default() };
    training.create_exercise_session(req).await.expect("an exercise without a recording");
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Issue 35 (hostile pass, finding 2): CreateExerciseSession loaded, meshed and factorised its
/// exercise before it checked `--max-sessions` (15 s of CPU for 40 refused calls). The limit is
/// checked and a place reserved first, as CreateSession does: on a full server an exercise whose
/// preparation would fail (over `--max-nodes`) is refused for the session limit, not the mesh.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_exercise_on_a_full_server_is_refused_before_it_is_prepared() {
    let server = ServerProcess::start(&["--default-scene", "none", "--max-sessions", "0", "--max-nodes", "200"]);
    let ch = channel(&server).await;
    let mut training = pb::training_service_client::TrainingServiceClient::new(ch);
    for exercise in ["biopsy-3d", "biopsy-2d"] {
        let req = pb::CreateExerciseSessionRequest { exercise: exercise.into(), ..Default::default() };
        let e = training.create_exercise_session(req).await.expect_err("the server is full");
        assert_eq!(e.code(), Code::ResourceExhausted, "{exercise}: {}", e.message());
        assert!(e.message().contains("limit of 0 sessions"), "{exercise}: the session limit first: {}", e.message());
    }
}

/// Issue 35 (hostile pass, finding 3): Plan parsed the client's whole scene TOML on the async
/// runtime (`scene_source_is_3d`) before it took an offline slot: two 59 MB TOMLs stalled every
/// other call for 38 s. A scene TOML is bounded (256 KiB, `needlesim_scene::MAX_SCENE_TOML_BYTES`)
/// for every call that takes one, refused naming the limit; and Plan takes its slot before it
/// reads anything of the request (a Plan on a full server is refused even with a request it
/// would refuse, counted in `needlesim_offline_jobs_rejected`).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_scene_toml_is_bounded_and_plan_takes_its_slot_before_reading_it() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    // A valid scene padded with a comment past the limit.
    let big = format!("{}\n# {}\n", paper_phantom_toml(), "x".repeat(300 << 10));
    let scene = || Some(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(big.clone())) });
    let check = |what: &str, e: tonic::Status| {
        assert_eq!(e.code(), Code::ResourceExhausted, "{what}: {}", e.message());
        assert!(e.message().contains("scene TOML") && e.message().contains("over the limit of 262144 bytes"), "{what}: {}", e.message());
        assert!(e.message().len() < 400, "{what}: {}", e.message());
    };
    let mut planning = pb::planning_service_client::PlanningServiceClient::new(ch.clone());
    let req = pb::PlanRequest { scene: scene(), target: "centre".into(), ..Default::default() };
    check("Plan", planning.plan(req).await.expect_err("oversize"));
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let req = pb::CreateSessionRequest { scene: scene(), ..Default::default() };
    check("CreateSession", sessions.create_session(req).await.expect_err("oversize"));
    let mut simulation = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    let req = pb::SimulateRequest { scene: scene(), ..Default::default() };
    check("Simulate", simulation.simulate(req).await.expect_err("oversize"));
    assert_eq!(server.metric("needlesim_sessions"), 0.0);
    drop(server);

    // With no plan slot, a Plan is refused before its request or scene is read: an empty target
    // (INVALID_ARGUMENT once read) in a 3D TOML answers RESOURCE_EXHAUSTED.
    let server = ServerProcess::start(&["--default-scene", "none", "--max-plans", "0"]);
    let ch = channel(&server).await;
    let mut planning = pb::planning_service_client::PlanningServiceClient::new(ch);
    let toml = format!("dim = 3\n# {}\n", "y".repeat(200 << 10));
    let req =
        pb::PlanRequest { scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(toml)) }), ..Default::default() };
    let e = planning.plan(req).await.expect_err("no plan slot");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert!(e.message().contains("--max-plans"), "{}", e.message());
    assert_eq!(server.metric("needlesim_offline_jobs_rejected"), 1.0);
}

/// Issue 35 (hostile pass, finding 4): a scene's `name` had no bound: a 20 MiB name was accepted
/// and then carried by every ListSessions answer (past default clients' message limit) and log
/// line. The name is at most 64 characters and the description 1024, refused naming the key.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_scene_name_and_description_are_bounded() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch);
    let base = paper_phantom_toml();
    let description = "description = \"0.1 m PVC-like phantom, 19 x 19 nodes, fixed at the bottom; vertical insertion and withdrawal\"";
    assert!(base.contains("name = \"paper-phantom\"") && base.contains(description));
    let cases = [
        (base.replace("name = \"paper-phantom\"", &format!("name = \"{}\"", "n".repeat(100_000))), "name: the name 'nnn", "at most 64"),
        (base.replace(description, &format!("description = \"{}\"", "d".repeat(2000))), "description: 'ddd", "at most 1024"),
    ];
    for (toml, start, limit) in cases {
        let req = pb::CreateSessionRequest {
            scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(toml)) }),
            ..Default::default()
        };
        let e = sessions.create_session(req).await.expect_err("refused");
        assert_eq!(e.code(), Code::InvalidArgument, "{}", e.message());
        assert!(e.message().contains(start) && e.message().contains(limit) && e.message().len() < 300, "{}", e.message());
    }
    let list = sessions.list_sessions(pb::ListSessionsRequest {}).await.expect("ListSessions").into_inner();
    assert!(list.sessions.is_empty());
}

/// Issue 35 (hostile pass, finding 5): WatchUltrasound's refused `rate_hz` was written with all
/// its digits (1e300 as 301); it is written compactly, as WatchScore's.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_refused_ultrasound_rate_is_written_compactly() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut training = pb::training_service_client::TrainingServiceClient::new(ch);
    for (rate, written) in [(1e300, "rate_hz = 1e300:"), (-1e300, "rate_hz = -1e300:"), (1e-300, "rate_hz = 1e-300:")] {
        let req = pb::WatchUltrasoundRequest { session_id: "any".into(), rate_hz: rate };
        let e = training.watch_ultrasound(req).await.expect_err("refused");
        assert_eq!(e.code(), Code::InvalidArgument, "{}", e.message());
        assert!(e.message().starts_with(written) && e.message().len() < 100, "{}", e.message());
    }
}

/// Issue 35 (finding 6b): a Simulate over the tick limit said "18446744073709551615 ticks" (a
/// saturated count) and named no sample; it names the sample that ends the trajectory, its time,
/// the count as it is and the limit.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue35_a_simulate_over_the_tick_limit_names_the_sample_unsaturated() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch);
    let sample =
        |t_s: f64| pb::TrajectorySample { t_s, base: Some(pb::Pose2 { x_m: 0.05, y_m: 0.21, theta_rad: -1.57 }), ..Default::default() };
    let req = pb::SimulateRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
        trajectory: vec![sample(0.0), sample(1e-300), sample(1e300)],
        ..Default::default()
    };
    let e = sim.simulate(req).await.expect_err("over the tick limit");
    assert_eq!(e.code(), Code::ResourceExhausted, "{}", e.message());
    assert_eq!(
        e.message(),
        "trajectory[2]: t_s = 1e300 ends 1e300 s after the first sample: 1e303 ticks at 1000 Hz, over the limit of 1000000 ticks (server flag --max-simulate-ticks)"
    );
}
