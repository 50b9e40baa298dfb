//! Limits and access through the real server binary (issue 13): atomic session and observer
//! limits under concurrent requests, recordings that belong to their session, symbolic links and
//! FIFOs in the recordings folder, one controller at a time with an explicit take-over, and
//! tokens that never reach the log.

use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, connect as channel, with_token};
use tokio_stream::StreamExt;
use tonic::Code;
use tonic::transport::Channel;

const DOWN: f64 = -std::f64::consts::FRAC_PI_2;

// The tests of this file run sessions; on a 2-core machine they take turns (with every real-time
// test of tests/it/).
use needlesim_tests::REALTIME as ONE_AT_A_TIME;

fn create_request(record: bool) -> pb::CreateSessionRequest {
    pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
        tick_rate_hz: 500.0,
        record,
        device_channel: false,
    }
}

async fn create(ch: &Channel, record: bool) -> pb::CreateSessionResponse {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    c.create_session(create_request(record)).await.expect("create a session").into_inner()
}

async fn n_sessions(ch: &Channel) -> usize {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    c.list_sessions(pb::ListSessionsRequest {}).await.unwrap().into_inner().sessions.len()
}

async fn close(ch: &Channel, created: &pb::CreateSessionResponse) {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let sid = created.session.as_ref().unwrap().session_id.clone();
    c.close_session(with_token(pb::CloseSessionRequest { session_id: sid }, &created.controller_token)).await.unwrap();
}

fn pose(y_m: f64) -> pb::Pose2 {
    pb::Pose2 { x_m: 0.05, y_m, theta_rad: DOWN }
}

fn control_request(sid: &str, y_m: f64, seq: u64, take_over: bool) -> pb::ControlRequest {
    pb::ControlRequest { session_id: sid.to_owned(), base: Some(pose(y_m)), client_time_ns: 0, seq, flip_bevel: false, take_over }
}

/// A Control stream: its sender (poses in) and its response stream, or the refusal.
async fn open_control(
    ch: &Channel,
    token: &str,
    first: pb::ControlRequest,
) -> Result<(tokio::sync::mpsc::Sender<pb::ControlRequest>, tonic::Streaming<pb::ControlResponse>), tonic::Status> {
    let (tx, rx) = tokio::sync::mpsc::channel(64);
    tx.send(first).await.unwrap();
    let mut ctl = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let responses = ctl.control(with_token(tokio_stream::wrappers::ReceiverStream::new(rx), token)).await?.into_inner();
    Ok((tx, responses))
}

/// Regression (issue 13): the session limit was a read-then-insert race (24 concurrent creates
/// with `--max-sessions 6` left 7 sessions); the observer limit was written the same way. Now
/// 32 concurrent creates, twenty times over, never leave more than 6 sessions, and 32
/// concurrent observers never exceed `--max-observers 6`.
#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn issue_13_concurrent_creates_and_observers_never_exceed_the_limits() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-sessions", "6", "--max-observers", "6"]);
    let ch = channel(&server).await;
    for trial in 0..20 {
        // A watcher lists the sessions all along the burst.
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let watcher = {
            let (ch, stop) = (ch.clone(), stop.clone());
            tokio::spawn(async move {
                let mut most = 0;
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    most = most.max(n_sessions(&ch).await);
                    tokio::time::sleep(Duration::from_millis(5)).await;
                }
                most
            })
        };
        let creates: Vec<_> = (0..32)
            .map(|_| {
                let ch = ch.clone();
                tokio::spawn(async move {
                    let mut c = pb::session_service_client::SessionServiceClient::new(ch);
                    c.create_session(create_request(false)).await
                })
            })
            .collect();
        let mut created = Vec::new();
        for c in creates {
            match c.await.unwrap() {
                Ok(r) => created.push(r.into_inner()),
                Err(s) => assert_eq!(s.code(), Code::ResourceExhausted, "trial {trial}: {s:?}"),
            }
        }
        stop.store(true, std::sync::atomic::Ordering::Relaxed);
        let most_seen = watcher.await.unwrap();
        let live = n_sessions(&ch).await;
        assert!(
            created.len() <= 6 && live <= 6 && most_seen <= 6,
            "trial {trial}: {} created, {live} live, {most_seen} seen at once",
            created.len()
        );
        assert_eq!(created.len(), 6, "trial {trial}: every free place is used");
        if trial == 0 {
            // Observers: 32 at once on one session with --max-observers 6, twenty times.
            let sid = created[0].session.as_ref().unwrap().session_id.clone();
            let tok = created[0].observer_token.clone();
            for round in 0..20 {
                let opens: Vec<_> = (0..32)
                    .map(|_| {
                        let (ch, sid, tok) = (ch.clone(), sid.clone(), tok.clone());
                        tokio::spawn(async move {
                            let mut o = pb::observe_service_client::ObserveServiceClient::new(ch);
                            let req = pb::ObserveRequest { session_id: sid, rate_hz: 0.0, include_displacements: false };
                            o.observe(with_token(req, &tok)).await
                        })
                    })
                    .collect();
                let mut streams = Vec::new();
                for o in opens {
                    match o.await.unwrap() {
                        Ok(s) => streams.push(s.into_inner()),
                        Err(s) => assert_eq!(s.code(), Code::ResourceExhausted, "round {round}: {s:?}"),
                    }
                }
                let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
                let info = sessions.get_session(pb::GetSessionRequest { session_id: sid.clone() }).await.unwrap().into_inner();
                assert!(
                    streams.len() <= 6 && info.n_observers <= 6,
                    "round {round}: {} streams, {} observers",
                    streams.len(),
                    info.n_observers
                );
                assert_eq!(streams.len(), 6, "round {round}: every free place is used");
                drop(streams);
                // The server notices the observers left at their next frame.
                let deadline = Instant::now() + Duration::from_secs(30);
                while sessions.get_session(pb::GetSessionRequest { session_id: sid.clone() }).await.unwrap().into_inner().n_observers > 0 {
                    assert!(Instant::now() < deadline, "round {round}: observers are not released");
                    tokio::time::sleep(Duration::from_millis(20)).await;
                }
            }
        }
        for c in &created {
            close(&ch, c).await;
        }
    }
}

/// Regression (issue 13): ListRecordings and DownloadRecording needed no token, so anyone read
/// any session's recording. Now a recording opens with its session's tokens (also after the
/// session closed) or the admin token, and with nothing else.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_recordings_open_with_their_sessions_tokens_only() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let secrets = TempDir::new("admin-token");
    let admin = "admin-token-0123456789abcdef";
    std::fs::write(secrets.join("admin"), format!("{admin}\n")).unwrap();
    let admin_file = secrets.join("admin").display().to_string();
    let server = ServerProcess::start(&["--default-scene", "none", "--admin-token-file", &admin_file]);
    let ch = channel(&server).await;
    let a = create(&ch, true).await;
    let b = create(&ch, true).await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    let stop = |created: &pb::CreateSessionResponse| {
        let sid = created.session.as_ref().unwrap().session_id.clone();
        let token = created.controller_token.clone();
        let mut rec = rec.clone();
        async move { rec.stop_recording(with_token(pb::StopRecordingRequest { session_id: sid }, &token)).await.unwrap().into_inner() }
    };
    let rec_a = stop(&a).await;
    let rec_b = stop(&b).await;
    close(&ch, &a).await;

    let list = |tok: Option<String>| {
        let mut rec = rec.clone();
        async move {
            let req = match tok {
                Some(t) => with_token(pb::ListRecordingsRequest {}, &t),
                None => tonic::Request::new(pb::ListRecordingsRequest {}),
            };
            rec.list_recordings(req).await.map(|r| r.into_inner().recordings.into_iter().map(|i| i.name).collect::<Vec<_>>())
        }
    };
    assert_eq!(list(None).await.unwrap(), Vec::<String>::new(), "no token, no recording");
    assert_eq!(list(Some("not-a-token".into())).await.unwrap(), Vec::<String>::new());
    // Session A closed; its tokens still open its recording, and only its.
    assert_eq!(list(Some(a.observer_token.clone())).await.unwrap(), vec![rec_a.name.clone()]);
    assert_eq!(list(Some(a.controller_token.clone())).await.unwrap(), vec![rec_a.name.clone()]);
    assert_eq!(list(Some(b.observer_token.clone())).await.unwrap(), vec![rec_b.name.clone()]);
    let mut all = vec![rec_a.name.clone(), rec_b.name.clone()];
    all.sort();
    assert_eq!(list(Some(admin.to_owned())).await.unwrap(), all);

    let download = |name: String, tok: Option<String>| {
        let mut rec = rec.clone();
        async move {
            let req = match tok {
                Some(t) => with_token(pb::DownloadRecordingRequest { name }, &t),
                None => tonic::Request::new(pb::DownloadRecordingRequest { name }),
            };
            let mut chunks = rec.download_recording(req).await?.into_inner();
            let mut bytes = Vec::new();
            while let Some(c) = chunks.next().await {
                bytes.extend(c?.data);
            }
            Ok::<_, tonic::Status>(bytes)
        }
    };
    for tok in [None, Some(b.controller_token.clone()), Some(b.observer_token.clone()), Some("x".repeat(32))] {
        let e = download(rec_a.name.clone(), tok.clone()).await.unwrap_err();
        assert_eq!(e.code(), Code::PermissionDenied, "{tok:?}: {e:?}");
    }
    let from_disk = std::fs::read(server.data_dir.join("recordings").join(&rec_a.name)).unwrap();
    assert!(from_disk.len() > 100);
    assert_eq!(download(rec_a.name.clone(), Some(a.observer_token.clone())).await.unwrap(), from_disk);
    assert_eq!(download(rec_a.name.clone(), Some(admin.to_owned())).await.unwrap(), from_disk);
    // The owner file keeps digests, never the tokens.
    let owner = std::fs::read_to_string(server.data_dir.join("recordings").join(format!("{}.owner", rec_a.name))).unwrap();
    assert!(!owner.contains(&a.controller_token) && !owner.contains(&a.observer_token), "{owner}");
    close(&ch, &b).await;
    // After a restart (same data directory, no admin token), the closed sessions' tokens still
    // open their recordings, and only theirs.
    drop(ch);
    let server = server.restart(&["--default-scene", "none"]);
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(channel(&server).await);
    let names = |tok: &str| {
        let mut rec = rec.clone();
        let req = with_token(pb::ListRecordingsRequest {}, tok);
        async move { rec.list_recordings(req).await.unwrap().into_inner().recordings.into_iter().map(|i| i.name).collect::<Vec<_>>() }
    };
    assert_eq!(names(&a.observer_token).await, vec![rec_a.name.clone()]);
    assert_eq!(names(&b.controller_token).await, vec![rec_b.name.clone()]);
    assert_eq!(names(admin).await, Vec::<String>::new(), "the admin token is not configured any more");
    let mut chunks = rec
        .download_recording(with_token(pb::DownloadRecordingRequest { name: rec_a.name.clone() }, &a.controller_token))
        .await
        .unwrap()
        .into_inner();
    let mut bytes = Vec::new();
    while let Some(c) = chunks.next().await {
        bytes.extend(c.unwrap().data);
    }
    assert_eq!(bytes, from_disk);
}

/// Regression (issue 13): a symbolic link in the recordings folder was served (a link to a file
/// outside it, such as /etc/passwd), and a FIFO there blocked the async workers until health
/// checks timed out. Now neither is a recording (NOT_FOUND, even for the admin token) and
/// health keeps answering.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_links_and_fifos_in_the_recordings_folder_are_not_served_and_do_not_block() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let secrets = TempDir::new("admin-token");
    let admin = "admin-token-0123456789abcdef";
    std::fs::write(secrets.join("admin"), admin).unwrap();
    let admin_file = secrets.join("admin").display().to_string();
    let server = ServerProcess::start(&["--default-scene", "none", "--admin-token-file", &admin_file]);
    let dir = server.data_dir.join("recordings");
    std::fs::create_dir_all(&dir).unwrap();
    let secret = secrets.join("secret.txt");
    std::fs::write(&secret, "root:x:0:0:secret").unwrap();
    std::os::unix::fs::symlink(&secret, dir.join("leak.mcap")).unwrap();
    let fifo = dir.join("fifo.mcap");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success(), "mkfifo");
    let ch = channel(&server).await;
    let rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());

    let mut r = rec.clone();
    let e = r.download_recording(with_token(pb::DownloadRecordingRequest { name: "leak.mcap".into() }, admin)).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound, "{e:?}");
    // More FIFO downloads at once than the server has async workers.
    let fifo_downloads: Vec<_> = (0..8)
        .map(|_| {
            let mut r = rec.clone();
            tokio::spawn(async move {
                let req = with_token(pb::DownloadRecordingRequest { name: "fifo.mcap".into() }, admin);
                tokio::time::timeout(Duration::from_secs(60), r.download_recording(req)).await.map(|res| res.map(|_| ()))
            })
        })
        .collect();
    tokio::time::sleep(Duration::from_millis(300)).await;
    let mut health = tonic_health::pb::health_client::HealthClient::new(ch.clone());
    let answer =
        tokio::time::timeout(Duration::from_secs(20), health.check(tonic_health::pb::HealthCheckRequest { service: String::new() })).await;
    let status = answer.expect("health answers while FIFO downloads are pending").unwrap().into_inner().status;
    assert_eq!(status, tonic_health::pb::health_check_response::ServingStatus::Serving as i32);
    for d in fifo_downloads {
        let e = d.await.unwrap().expect("a FIFO download does not block").unwrap_err();
        assert_eq!(e.code(), Code::NotFound, "{e:?}");
    }
    let mut r = rec.clone();
    let names = r.list_recordings(with_token(pb::ListRecordingsRequest {}, admin)).await.unwrap().into_inner().recordings;
    assert!(names.is_empty(), "links and FIFOs are not listed: {names:?}");
}

/// Regression (issue 13): two Control streams on one session were both accepted and their poses
/// interleaved. Now the second is refused with FAILED_PRECONDITION, and so is SetPose while a
/// stream drives; once the first stream ends, the next one gets control.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_a_second_controller_is_refused() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let created = create(&ch, false).await;
    let sid = created.session.as_ref().unwrap().session_id.clone();
    let tok = created.controller_token.clone();
    let (tx1, mut resp1) = open_control(&ch, &tok, control_request(&sid, 0.205, 1, false)).await.expect("the first stream drives");
    resp1.next().await.unwrap().unwrap();
    let Err(e) = open_control(&ch, &tok, control_request(&sid, 0.19, 1, false)).await else { panic!("a second stream is accepted") };
    assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
    assert!(e.message().contains("take_over"), "the refusal says how to take over: {}", e.message());
    let mut ctl = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let set = |take_over: bool| pb::SetPoseRequest { session_id: sid.clone(), base: Some(pose(0.19)), client_id: "web".into(), take_over };
    let e = ctl.set_pose(with_token(set(false), &tok)).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
    // The first stream still drives, undisturbed: its pose holds.
    tx1.send(control_request("", 0.204, 2, false)).await.unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let r = resp1.next().await.unwrap().unwrap();
        if (r.base.unwrap().y_m - 0.204).abs() < 1e-12 {
            break;
        }
        assert!(Instant::now() < deadline, "the first stream's pose is not applied");
    }
    // It ends: the next stream drives.
    drop(tx1);
    while resp1.next().await.is_some() {}
    let (tx3, mut resp3) = open_control(&ch, &tok, control_request(&sid, 0.203, 1, false)).await.expect("the next stream drives");
    resp3.next().await.unwrap().unwrap();
    drop(tx3);
    while resp3.next().await.is_some() {}
    // No stream: a browser's SetPose calls keep working, one after another.
    for _ in 0..5 {
        ctl.set_pose(with_token(set(false), &tok)).await.expect("SetPose while no stream drives");
    }
    close(&ch, &created).await;
}

/// Take-over (issue 13): a Control stream whose first message sets `take_over` revokes the
/// stream that drives (it ends with ABORTED) and its poses are applied; SetPose with `take_over`
/// does the same.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_take_over_revokes_the_controller() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = channel(&server).await;
    let created = create(&ch, false).await;
    let sid = created.session.as_ref().unwrap().session_id.clone();
    let tok = created.controller_token.clone();
    let (_tx1, mut resp1) = open_control(&ch, &tok, control_request(&sid, 0.205, 1, false)).await.unwrap();
    resp1.next().await.unwrap().unwrap();
    let (tx2, mut resp2) = open_control(&ch, &tok, control_request(&sid, 0.2, 1, true)).await.expect("take-over is accepted");
    let ended = tokio::time::timeout(Duration::from_secs(10), async {
        loop {
            match resp1.next().await {
                Some(Ok(_)) => continue,
                Some(Err(s)) => return Some(s),
                None => return None,
            }
        }
    })
    .await
    .expect("the revoked stream ends");
    let s = ended.expect("the revoked stream ends with a status");
    assert_eq!(s.code(), Code::Aborted, "{s:?}");
    assert!(s.message().contains("taken over"), "{}", s.message());
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let r = resp2.next().await.unwrap().unwrap();
        let y = r.base.unwrap().y_m;
        if (y - 0.2).abs() < 1e-12 {
            break;
        }
        assert!(Instant::now() < deadline, "the new controller's pose is not applied");
    }
    // SetPose takes over from the stream.
    let mut ctl = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let req = pb::SetPoseRequest { session_id: sid.clone(), base: Some(pose(0.198)), client_id: "web".into(), take_over: true };
    ctl.set_pose(with_token(req, &tok)).await.expect("SetPose with take_over");
    let e = loop {
        match resp2.next().await {
            Some(Ok(_)) => continue,
            Some(Err(s)) => break s,
            None => panic!("the revoked stream ended without a status"),
        }
    };
    assert_eq!(e.code(), Code::Aborted, "{e:?}");
    drop(tx2);
    // Another SetPose client is refused while "web" holds the lease.
    let req = pb::SetPoseRequest { session_id: sid.clone(), base: Some(pose(0.19)), client_id: "cli".into(), take_over: false };
    let e = ctl.set_pose(with_token(req, &tok)).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
    // The CLI: `needlesim drive` is refused while another client drives; `--take-over` drives.
    let (_tx4, _resp4) = open_control(&ch, &tok, control_request(&sid, 0.2, 1, true)).await.unwrap();
    let dir = TempDir::new("take-over");
    let traj = dir.join("traj.csv");
    std::fs::write(&traj, format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.2,{DOWN}\n0.2,0.05,0.199,{DOWN}\n")).unwrap();
    let drive = |extra: &[&str]| {
        let mut cmd = std::process::Command::new(needlesim_tests::bin("needlesim"));
        cmd.args(["--server", &server.url(), "--token", &tok, "drive", &sid, "--trajectory", traj.to_str().unwrap()]).args(extra);
        needlesim_tests::run(&mut cmd)
    };
    let refused = drive(&[]);
    let (_, err) = needlesim_tests::text(&refused);
    assert!(!refused.status.success() && err.contains("take_over"), "drive while another client drives: {err}");
    let took = drive(&["--take-over"]);
    let (out, err) = needlesim_tests::text(&took);
    assert!(took.status.success(), "drive --take-over:\n{out}\n{err}");
    close(&ch, &created).await;
}

/// Regression (issue 13): the default session's controller token was logged at INFO. Now the
/// log shows fingerprints only; `--demo` prints its URL (with the token) to the terminal once.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_13_tokens_are_never_logged() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let server = ServerProcess::start(&["--demo"]);
    let deadline = Instant::now() + Duration::from_secs(30);
    let url = loop {
        if let Some(l) = server.stdout.lock().unwrap().lines().find(|l| l.starts_with("demo: open ")).map(str::to_owned) {
            break l;
        }
        assert!(Instant::now() < deadline, "no demo URL on stdout");
        tokio::time::sleep(Duration::from_millis(50)).await;
    };
    let token = url.split("token=").nth(1).unwrap().split(|c: char| !c.is_ascii_hexdigit()).next().unwrap().to_owned();
    assert_eq!(token.len(), 32, "{url}");
    // A session created over gRPC, recorded and driven: its tokens are not logged either.
    let ch = channel(&server).await;
    let created = create(&ch, true).await;
    let sid = created.session.as_ref().unwrap().session_id.clone();
    let mut ctl = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let req = pb::SetPoseRequest { session_id: sid.clone(), base: Some(pose(0.2)), client_id: String::new(), take_over: false };
    ctl.set_pose(with_token(req, &created.controller_token)).await.unwrap();
    close(&ch, &created).await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let log = server.stderr.lock().unwrap().clone();
    assert!(log.contains("default session"), "the default session is logged:\n{log}");
    for t in [&token, &created.controller_token, &created.observer_token] {
        assert!(!log.contains(t.as_str()), "a token is in the log:\n{log}");
    }
    let stdout = server.stdout.lock().unwrap().clone();
    assert_eq!(stdout.matches(token.as_str()).count(), 1, "the demo token is printed once:\n{stdout}");
}
