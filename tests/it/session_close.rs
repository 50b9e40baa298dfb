//! Issue 35, H1 of the hostile pass, through the real server binary: after CloseSession every
//! stream of the session ends with NOT_FOUND "session X was closed" — Observe (every tick and at
//! a rate, with and without displacements), Control, Control3, WatchScore, WatchUltrasound,
//! GetReport — whether its client reads or not, gives its place back (`needlesim_streams_open`),
//! and lets go of the session, whose memory is then freed (`needlesim_sessions_alive`, the
//! server's RSS). Before, an every-tick Observe and the Control streams waited for ticks that never
//! came, holding the session (a 3D one's solver) and their stream permits for good.

use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME, ServerProcess, connect, create_example_session, with_token};
use tokio::task::JoinHandle;
use tonic::Code;

/// Generous: the streams end within milliseconds on a quiet machine; this is not a budget.
const BOUND: Duration = Duration::from_secs(20);

/// The first message of `stream` (within 60 s: a loaded machine), then the rest read to the end
/// in a task: the number of messages and how the stream ended (`Ok` for a plain end).
async fn first_then_drain<T: std::fmt::Debug + Send + 'static>(
    what: &'static str,
    mut stream: tonic::Streaming<T>,
) -> JoinHandle<(u64, Result<(), tonic::Status>)> {
    let first = tokio::time::timeout(Duration::from_secs(60), stream.message()).await.unwrap_or_else(|_| panic!("{what}: no message"));
    assert!(matches!(first, Ok(Some(_))), "{what}: the stream delivers before the close: {first:?}");
    drain(stream)
}

/// Reads `stream` to its end in a task: the number of messages and how it ended.
fn drain<T: Send + 'static>(mut stream: tonic::Streaming<T>) -> JoinHandle<(u64, Result<(), tonic::Status>)> {
    tokio::spawn(async move {
        let mut n = 0;
        loop {
            match stream.message().await {
                Ok(Some(_)) => n += 1,
                Ok(None) => return (n, Ok(())),
                Err(e) => return (n, Err(e)),
            }
        }
    })
}

/// The stream read by `reader` ends within [`BOUND`] with NOT_FOUND naming the closed session.
async fn assert_ends_closed(what: &str, sid: &str, reader: JoinHandle<(u64, Result<(), tonic::Status>)>) {
    let (n, end) = tokio::time::timeout(BOUND, reader)
        .await
        .unwrap_or_else(|_| panic!("{what}: still open {BOUND:?} after CloseSession"))
        .expect("the reader task");
    let e = end.expect_err(&format!("{what}: ended without a status after {n} messages"));
    assert_eq!(e.code(), Code::NotFound, "{what}: {e:?}");
    assert_eq!(e.message(), format!("session {sid} was closed"), "{what}");
    println!("{what}: {n} more messages, then {:?} {:?}", e.code(), e.message());
}

/// Waits (up to [`BOUND`]) until the server's metric `name` reads `value`.
async fn until_metric(server: &ServerProcess, name: &str, value: f64) {
    let t0 = Instant::now();
    loop {
        let v = server.metric(name);
        if v == value {
            return;
        }
        assert!(t0.elapsed() < BOUND, "{name} is {v}, not {value}, {BOUND:?} after CloseSession");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

/// An exercise session of biopsy-2d (with a device channel and a recording when asked):
/// (session info, controller token, observer token).
async fn exercise(ch: &tonic::transport::Channel, device_and_record: bool) -> (pb::SessionInfo, String, String) {
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let req = pb::CreateExerciseSessionRequest {
        exercise: "biopsy-2d".into(),
        device_channel: device_and_record,
        record: device_and_record,
        ..Default::default()
    };
    let created = tr.create_exercise_session(req).await.expect("an exercise session").into_inner();
    let sess = created.session.unwrap();
    (sess.session.unwrap(), sess.controller_token, sess.observer_token)
}

async fn close(ch: &tonic::transport::Channel, sid: &str, controller: &str) {
    pb::session_service_client::SessionServiceClient::new(ch.clone())
        .close_session(with_token(pb::CloseSessionRequest { session_id: sid.into() }, controller))
        .await
        .expect("CloseSession");
}

/// Every stream kind of a 2D session — its exercise's streams, its Foxglove channels, a device
/// channel and a recording attached — ends at CloseSession with NOT_FOUND, read or not, and the
/// session object is freed.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_every_stream_of_a_closed_2d_session_ends_with_not_found_and_frees_it() {
    let _turn = REALTIME.lock().await;
    let mut server = ServerProcess::start(&["--default-scene", "none", "--foxglove-addr", "127.0.0.1:0"]);
    let ch = connect(&server).await;
    let (info, ctl, obs) = exercise(&ch, true).await;
    let sid = info.session_id.clone();
    let channel_path = std::path::PathBuf::from(&info.device_channel_path);
    assert!(channel_path.exists(), "the device channel {} exists", channel_path.display());
    // A second exercise, ended: its report's stream, never read.
    let (ended, ended_ctl, ended_obs) = exercise(&ch, false).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let mut ob = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let ex_req = |sid: &str, tok: &str| with_token(pb::ExerciseRequest { session_id: sid.into() }, tok);
    tr.end_exercise(ex_req(&ended.session_id, &ended_ctl)).await.expect("EndExercise");
    let report = tr.get_report(ex_req(&ended.session_id, &ended_obs)).await.expect("GetReport").into_inner();

    let observe = |rate_hz: f64, include_displacements: bool| {
        with_token(pb::ObserveRequest { session_id: sid.clone(), rate_hz, include_displacements }, &obs)
    };
    let mut readers = Vec::new();
    let every_tick = ob.observe(observe(0.0, false)).await.expect("Observe every tick").into_inner();
    readers.push(("Observe every tick", first_then_drain("Observe every tick", every_tick).await));
    let mut rendering = ob.observe(observe(60.0, true)).await.expect("Observe 60 Hz").into_inner();
    let frame = tokio::time::timeout(Duration::from_secs(60), rendering.message()).await.expect("a frame").unwrap().unwrap();
    assert!(!frame.node_displacement_m.is_empty(), "the 60 Hz stream carries the displacements");
    readers.push(("Observe 60 Hz with displacements", drain(rendering)));
    let rate = ob.observe(observe(30.0, false)).await.expect("Observe 30 Hz").into_inner();
    readers.push(("Observe 30 Hz", first_then_drain("Observe 30 Hz", rate).await));
    // Never read: a logger that stopped reading, the displacement field subscribed.
    let unread = ob.observe(observe(0.0, true)).await.expect("Observe every tick, unread").into_inner();

    // A controller that keeps its request stream open (holds the still pose it started at).
    let (poses, poses_rx) = tokio::sync::mpsc::channel(4);
    poses.send(pb::ControlRequest { session_id: sid.clone(), base: frame.base, seq: 1, ..Default::default() }).await.unwrap();
    let mut cc = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let control = cc.control(with_token(tokio_stream::wrappers::ReceiverStream::new(poses_rx), &ctl)).await.expect("Control");
    readers.push(("Control", first_then_drain("Control", control.into_inner()).await));

    let score = tr.watch_score(with_token(pb::WatchScoreRequest { session_id: sid.clone(), rate_hz: 10.0 }, &obs)).await;
    readers.push(("WatchScore", first_then_drain("WatchScore", score.expect("WatchScore").into_inner()).await));
    let us = tr.watch_ultrasound(with_token(pb::WatchUltrasoundRequest { session_id: sid.clone(), rate_hz: 5.0 }, &obs)).await;
    readers.push(("WatchUltrasound", first_then_drain("WatchUltrasound", us.expect("WatchUltrasound").into_inner()).await));

    // Six streams of the first session counted, and the report's unless it was sent whole already.
    let open = server.metric("needlesim_streams_open");
    assert!(open == 6.0 || open == 7.0, "{open} streams open");
    close(&ch, &sid, &ctl).await;
    close(&ch, &ended.session_id, &ended_ctl).await;
    for (what, reader) in readers {
        assert_ends_closed(what, &sid, reader).await;
    }
    // The streams nobody reads gave their places back, and nothing holds either session now
    // (nor their Foxglove publishers, the ultrasound renderer, the recording, the device watcher).
    until_metric(&server, "needlesim_streams_open", 0.0).await;
    until_metric(&server, "needlesim_sessions_alive", 0.0).await;
    assert_eq!(server.metric("needlesim_sessions"), 0.0);
    assert!(!channel_path.exists(), "the device channel {} was removed", channel_path.display());
    // Read now, the unread streams end with the same status (after what was in flight).
    assert_ends_closed("Observe every tick, unread until the close", &sid, drain(unread)).await;
    let (n, end) = tokio::time::timeout(BOUND, drain(report)).await.expect("GetReport ends").unwrap();
    match end {
        // The report was small enough to be on its way whole before the close.
        Ok(()) => assert!(n > 0, "GetReport ended with no chunk"),
        Err(e) => {
            assert_eq!(e.code(), Code::NotFound, "GetReport: {e:?}");
            assert_eq!(e.message(), format!("session {} was closed", ended.session_id));
        }
    }
    // The controller's request stream, still open, holds nothing.
    drop(poses);
    assert!(server.child.try_wait().unwrap().is_none(), "the server died: {}", server.stderr.lock().unwrap());
}

/// The server's resident memory, kB.
fn rss_kb(pid: u32) -> u64 {
    needlesim_tests::rss_bytes(pid) / 1024
}

const DOWN: [f64; 4] = [std::f64::consts::FRAC_1_SQRT_2, 0.0, std::f64::consts::FRAC_1_SQRT_2, 0.0];

/// 3D sessions (cube-phantom-3d, the solver ~100 MB each) with a Control3 stream whose client
/// keeps its request stream open and never reads, and an every-tick Observe never read: after
/// CloseSession nothing holds them and the server's memory goes back down.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_closed_3d_sessions_with_unread_control3_streams_are_freed() {
    const N: usize = 3;
    let _turn = REALTIME.lock().await;
    let mut server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let pid = server.child.id();
    let rss0 = rss_kb(pid);
    let mut zombies = Vec::new();
    // What the first session took, open and ticking with its streams.
    let mut one = 0;
    for i in 0..N {
        let created = create_example_session(&ch, "cube-phantom-3d").await;
        let info = created.session.clone().unwrap();
        assert_eq!(info.dimension, 3);
        let sid = info.session_id.clone();
        let (poses, poses_rx) = tokio::sync::mpsc::channel(4);
        let base3 = pb::Pose3 {
            position_m: Some(pb::Vec3 { x: 0.05, y: 0.05, z: 0.205 }),
            orientation: Some(pb::Quaternion { w: DOWN[0], x: DOWN[1], y: DOWN[2], z: DOWN[3] }),
        };
        poses.send(pb::ControlRequest3 { session_id: sid.clone(), base3: Some(base3), seq: 1, ..Default::default() }).await.unwrap();
        let mut cc = pb::control_service_client::ControlServiceClient::new(ch.clone());
        let control = cc
            .control3(with_token(tokio_stream::wrappers::ReceiverStream::new(poses_rx), &created.controller_token))
            .await
            .expect("Control3")
            .into_inner();
        let mut ob = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
        let req = pb::ObserveRequest { session_id: sid.clone(), rate_hz: 0.0, include_displacements: false };
        let observe = ob.observe(with_token(req, &created.observer_token)).await.expect("Observe").into_inner();
        // Let the session tick with its streams open.
        tokio::time::sleep(Duration::from_secs(1)).await;
        if i == 0 {
            one = rss_kb(pid).saturating_sub(rss0);
        }
        close(&ch, &sid, &created.controller_token).await;
        zombies.push((sid, poses, control, observe));
    }
    until_metric(&server, "needlesim_streams_open", 0.0).await;
    until_metric(&server, "needlesim_sessions_alive", 0.0).await;
    // The allocator gives freed memory back within 2 s of streams closing (serve.rs).
    tokio::time::sleep(Duration::from_secs(5)).await;
    let after = rss_kb(pid);
    println!(
        "server RSS: {} MB at the start, +{} MB with the first session open, {} MB after closing {N} 3D sessions with their Control3 streams unread",
        rss0 / 1024,
        one / 1024,
        after / 1024
    );
    // Each session takes tens of MB; held, all N would still be there. A wide margin: up to half
    // of what they took may stay with the allocator.
    assert!(one > 30 * 1024, "a 3D session took memory: {one} kB");
    assert!(
        after < rss0 + N as u64 * one / 2,
        "the closed sessions' memory stayed: {rss0} kB at the start, +{one} kB per session, {after} kB after closing {N}"
    );
    // The clients, reading now, get what was in flight, then NOT_FOUND.
    for (sid, poses, control, observe) in zombies {
        assert_ends_closed("Control3 unread until the close", &sid, drain(control)).await;
        assert_ends_closed("Observe every tick unread until the close", &sid, drain(observe)).await;
        drop(poses);
    }
    assert!(server.child.try_wait().unwrap().is_none(), "the server died: {}", server.stderr.lock().unwrap());
}

/// The server's shutdown (SIGTERM) closes the sessions before it waits for the open calls to
/// finish: their streams end with NOT_FOUND and the server exits, where an every-tick Observe or
/// a rendering one held the graceful shutdown for as long as its client stayed.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_sigterm_ends_the_sessions_streams_and_the_server_exits() {
    let _turn = REALTIME.lock().await;
    let mut server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let created = create_example_session(&ch, "fig3-target").await;
    let sid = created.session.unwrap().session_id;
    let mut ob = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let observe = |rate_hz: f64| {
        with_token(pb::ObserveRequest { session_id: sid.clone(), rate_hz, include_displacements: false }, &created.observer_token)
    };
    let every_tick = first_then_drain("Observe every tick", ob.observe(observe(0.0)).await.expect("Observe").into_inner()).await;
    let rendering = first_then_drain("Observe 30 Hz", ob.observe(observe(30.0)).await.expect("Observe").into_inner()).await;
    let killed = std::process::Command::new("kill").args(["-TERM", &server.child.id().to_string()]).status().expect("kill");
    assert!(killed.success());
    assert_ends_closed("Observe every tick at SIGTERM", &sid, every_tick).await;
    assert_ends_closed("Observe 30 Hz at SIGTERM", &sid, rendering).await;
    let t0 = Instant::now();
    let status = loop {
        if let Some(status) = server.child.try_wait().unwrap() {
            break status;
        }
        assert!(t0.elapsed() < BOUND, "the server still runs {BOUND:?} after SIGTERM: {}", server.stderr.lock().unwrap());
        tokio::time::sleep(Duration::from_millis(100)).await;
    };
    assert!(status.success(), "the server exited with {status}: {}", server.stderr.lock().unwrap());
}

/// The ids of the server's sessions (ListSessions).
async fn session_ids(ch: &tonic::transport::Channel) -> Vec<String> {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let list = c.list_sessions(pb::ListSessionsRequest {}).await.expect("ListSessions").into_inner();
    list.sessions.into_iter().map(|s| s.session_id).collect()
}

/// Issue 35 (bounded by design): a session its client abandoned (created, never driven, watched
/// or controlled) is closed after `--session-idle-timeout-s`, so that clients that go away cannot
/// hold every session slot; a session with a stream open stays for as long as the stream does,
/// then goes the same way; the server's own default session stays.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_abandoned_session_is_closed_after_the_idle_timeout() {
    let _turn = REALTIME.lock().await;
    let server = ServerProcess::start(&["--session-idle-timeout-s", "2"]);
    let ch = connect(&server).await;
    let ids = session_ids(&ch).await;
    assert_eq!(ids.len(), 1, "the default session: {ids:?}");
    let default = ids[0].clone();
    let abandoned = create_example_session(&ch, "paper-phantom").await.session.unwrap().session_id;
    let watched = create_example_session(&ch, "paper-phantom").await;
    let watched_id = watched.session.clone().unwrap().session_id;
    let mut ob = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let req = pb::ObserveRequest { session_id: watched_id.clone(), rate_hz: 30.0, include_displacements: false };
    let observe = ob.observe(with_token(req, &watched.observer_token)).await.expect("Observe").into_inner();
    let reader = drain(observe);
    // Closed within the timeout plus a check period (2.5 s); 20 s for a loaded machine.
    let t0 = Instant::now();
    while session_ids(&ch).await.contains(&abandoned) {
        assert!(t0.elapsed() < BOUND, "the abandoned session {abandoned} is still open after {BOUND:?}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let closed_after = t0.elapsed();
    assert!(closed_after >= Duration::from_millis(1900), "closed before its timeout: {closed_after:?}");
    // Watched the whole time: still open, and well past the timeout.
    tokio::time::sleep(Duration::from_secs(3)).await;
    let ids = session_ids(&ch).await;
    assert!(ids.contains(&watched_id) && ids.contains(&default), "{ids:?}");
    assert!(!reader.is_finished(), "the observer's stream is still open");
    reader.abort();
    let t1 = Instant::now();
    while session_ids(&ch).await.contains(&watched_id) {
        assert!(t1.elapsed() < BOUND, "the session {watched_id} is still open {BOUND:?} after its last stream closed");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    println!("abandoned session closed {closed_after:?} after creation; the watched one {:?} after its stream closed", t1.elapsed());
    until_metric(&server, "needlesim_sessions_alive", 1.0).await;
    assert_eq!(session_ids(&ch).await, vec![default], "the default session stays");
}
