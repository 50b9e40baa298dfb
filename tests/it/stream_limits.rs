//! Issue 35, items 4, 6 and part of 14, through the real server binary: every server-streaming
//! call counts against its session's `--max-observers` and the server's `--max-streams` (a
//! cancelled stream gives its place back); connections that send no handshake are closed and the
//! number of connections is bounded (`--max-connections`, `--handshake-timeout-ms`); TakeControl,
//! HandBackControl and SetPaused after EndExercise are FAILED_PRECONDITION.

use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME, ServerProcess, connect, with_token};
use tonic::Code;

/// An exercise session of biopsy-2d: (session id, observer token, instructor token).
async fn exercise(ch: &tonic::transport::Channel) -> (String, String, String) {
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let created = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest { exercise: "biopsy-2d".into(), ..Default::default() })
        .await
        .expect("an exercise session")
        .into_inner();
    let sess = created.session.unwrap();
    (sess.session.unwrap().session_id, sess.observer_token, created.instructor_token)
}

async fn n_observers(ch: &tonic::transport::Channel, sid: &str) -> u32 {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    c.get_session(pb::GetSessionRequest { session_id: sid.into() }).await.unwrap().into_inner().n_observers
}

/// Waits (up to 20 s) until the session counts `n` streams.
async fn until_observers(ch: &tonic::transport::Channel, sid: &str, n: u32) {
    let t0 = Instant::now();
    while n_observers(ch, sid).await != n {
        assert!(t0.elapsed() < Duration::from_secs(20), "the session still counts {} streams, not {n}", n_observers(ch, sid).await);
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

fn assert_exhausted(r: Result<impl std::fmt::Debug, tonic::Status>, what: &str, limit: &str) {
    let e = r.expect_err(what);
    assert_eq!(e.code(), Code::ResourceExhausted, "{what}: {e:?}");
    assert!(e.message().contains(limit), "{what}: the message names the limit ({limit}): {}", e.message());
}

/// Item 4: WatchScore and WatchUltrasound count against `--max-observers` with Observe (per
/// session) and against `--max-streams` (the server); the extra ones are RESOURCE_EXHAUSTED
/// naming the limit; a cancelled stream gives its place back.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_watch_streams_count_against_max_observers_and_max_streams() {
    let _turn = REALTIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-observers", "3", "--max-streams", "5"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let mut ob = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let (sid, obs, _) = exercise(&ch).await;
    let score = || with_token(pb::WatchScoreRequest { session_id: sid.clone(), rate_hz: 10.0 }, &obs);
    let us = || with_token(pb::WatchUltrasoundRequest { session_id: sid.clone(), rate_hz: 5.0 }, &obs);
    let observe =
        |sid: &str, tok: &str| with_token(pb::ObserveRequest { session_id: sid.into(), rate_hz: 10.0, include_displacements: false }, tok);

    // Three streams on the session: two score watchers (never read) and one ultrasound watcher.
    let mut first = tr.watch_score(score()).await.expect("WatchScore 1").into_inner();
    let second = tr.watch_score(score()).await.expect("WatchScore 2").into_inner();
    let third = tr.watch_ultrasound(us()).await.expect("WatchUltrasound 1").into_inner();
    let st = tokio::time::timeout(Duration::from_secs(20), first.message()).await.expect("a status").unwrap().unwrap();
    assert_eq!(st.session_id, sid, "the watched stream delivers");
    until_observers(&ch, &sid, 3).await;
    for _ in 0..3 {
        assert_exhausted(tr.watch_score(score()).await, "a 4th WatchScore", "limit of 3 observers (--max-observers");
        assert_exhausted(tr.watch_ultrasound(us()).await, "a 4th WatchUltrasound", "limit of 3 observers (--max-observers");
        assert_exhausted(ob.observe(observe(&sid, &obs)).await, "a 4th Observe", "limit of 3 observers (--max-observers");
    }
    assert_eq!(n_observers(&ch, &sid).await, 3, "refused calls hold no place");

    // Cancelled: the places come back.
    drop(first);
    drop(third);
    until_observers(&ch, &sid, 1).await;
    let again_us = tr.watch_ultrasound(us()).await.expect("WatchUltrasound after a cancel").into_inner();
    let again_score = tr.watch_score(score()).await.expect("WatchScore after a cancel").into_inner();
    until_observers(&ch, &sid, 3).await;

    // The server's limit: two more streams on a second session make five; a sixth is refused
    // there although that session has room, until a stream of the first closes.
    let plain = needlesim_tests::create_example_session(&ch, "fig3-target").await;
    let sid2 = plain.session.unwrap().session_id;
    let o1 = ob.observe(observe(&sid2, &plain.observer_token)).await.expect("Observe 1 of session 2").into_inner();
    let o2 = ob.observe(observe(&sid2, &plain.observer_token)).await.expect("Observe 2 of session 2").into_inner();
    assert_exhausted(ob.observe(observe(&sid2, &plain.observer_token)).await, "a 6th stream", "limit of 5 open streams (--max-streams)");
    assert_eq!(server.metric("needlesim_streams_open"), 5.0);
    assert!(server.metric("needlesim_streams_refused") >= 10.0);
    drop(again_score);
    until_observers(&ch, &sid, 2).await;
    let o3 = ob.observe(observe(&sid2, &plain.observer_token)).await.expect("Observe once a place is free").into_inner();
    until_observers(&ch, &sid2, 3).await;
    drop((second, again_us, o1, o2, o3));
    until_observers(&ch, &sid, 0).await;
    until_observers(&ch, &sid2, 0).await;
}

/// Item 6: connections that send nothing are closed after `--handshake-timeout-ms`; past
/// `--max-connections` a connection is closed at once (counted apart); a gRPC connection that
/// made its handshake stays open and works afterwards.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_silent_connections_are_closed_and_connections_are_bounded() {
    use tokio::io::AsyncReadExt;
    let server = ServerProcess::start(&["--default-scene", "none", "--max-connections", "64", "--handshake-timeout-ms", "3000"]);
    // One working gRPC connection (HTTP/2 handshake done) takes one of the 64 places.
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    tr.list_exercises(pb::ListExercisesRequest {}).await.expect("a call before");
    // 100 connections that never send a byte: 63 take the other places, 37 are closed at once.
    let mut silent = Vec::new();
    for _ in 0..100 {
        silent.push(tokio::net::TcpStream::connect(&server.addr).await.expect("TCP connect"));
    }
    let reads = silent.into_iter().map(|mut s| {
        tokio::spawn(async move {
            let mut b = [0u8; 64];
            // EOF (or a reset) when the server closes it; a generous bound, not a timing budget.
            tokio::time::timeout(Duration::from_secs(60), s.read(&mut b)).await
        })
    });
    let mut closed = 0;
    for r in reads {
        match r.await.unwrap() {
            Ok(Ok(0)) | Ok(Err(_)) => closed += 1,
            Ok(Ok(n)) => panic!("the server sent {n} bytes to a connection that sent nothing"),
            Err(_) => {}
        }
    }
    assert_eq!(closed, 100, "every silent connection is closed by the server");
    assert_eq!(server.metric("needlesim_connections_refused"), 37.0, "past --max-connections: closed at once");
    assert_eq!(server.metric("needlesim_connections_timed_out"), 63.0, "no handshake: closed at the deadline");
    // The handshaken connection outlived the deadline and still works.
    tr.list_exercises(pb::ListExercisesRequest {}).await.expect("a call after, on the same connection");
    let ch2 = connect(&server).await;
    pb::training_service_client::TrainingServiceClient::new(ch2)
        .list_exercises(pb::ListExercisesRequest {})
        .await
        .expect("a new connection");
}

/// Item 6 over TLS: a connection that sends nothing, and one that stops inside its ClientHello,
/// are closed at the deadline; a TLS client that made its handshake outlives it and works.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_silent_connections_are_closed_on_a_tls_port() {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let dir = needlesim_tests::TempDir::new("tls35");
    std::fs::write(
        dir.join("ext.cnf"),
        "subjectAltName=DNS:localhost,IP:127.0.0.1\nbasicConstraints=CA:FALSE\nextendedKeyUsage=serverAuth\n",
    )
    .unwrap();
    let openssl = |args: &[&str]| {
        let o = std::process::Command::new("openssl").args(args).current_dir(dir.path()).output().expect("openssl runs");
        assert!(o.status.success(), "openssl {args:?}: {}", String::from_utf8_lossy(&o.stderr));
    };
    let ec = ["-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes"];
    openssl(&[&["req", "-x509"][..], &ec, &["-days", "1", "-subj", "/CN=test CA", "-keyout", "ca.key", "-out", "ca.pem"]].concat());
    openssl(&[&["req"][..], &ec, &["-subj", "/CN=localhost", "-keyout", "key.pem", "-out", "leaf.csr"]].concat());
    #[rustfmt::skip]
    openssl(&["x509", "-req", "-in", "leaf.csr", "-CA", "ca.pem", "-CAkey", "ca.key", "-CAcreateserial", "-days", "1", "-out", "cert.pem", "-extfile", "ext.cnf"]);
    let (cert, key) = (dir.join("cert.pem"), dir.join("key.pem"));
    let server = ServerProcess::start(&[
        "--default-scene",
        "none",
        "--tls-cert",
        cert.to_str().unwrap(),
        "--tls-key",
        key.to_str().unwrap(),
        "--handshake-timeout-ms",
        "2000",
    ]);
    let ca = tonic::transport::Certificate::from_pem(std::fs::read(dir.join("ca.pem")).unwrap());
    let tls = tonic::transport::ClientTlsConfig::new().ca_certificate(ca).domain_name("localhost");
    let ch = tonic::transport::Channel::from_shared(format!("https://{}", server.addr))
        .unwrap()
        .tls_config(tls)
        .unwrap()
        .connect()
        .await
        .unwrap();
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch);
    tr.list_exercises(pb::ListExercisesRequest {}).await.expect("a call over TLS");
    let silent = tokio::net::TcpStream::connect(&server.addr).await.unwrap();
    let mut partial = tokio::net::TcpStream::connect(&server.addr).await.unwrap();
    // The first bytes of a TLS record header of a ClientHello, then nothing.
    partial.write_all(&[0x16, 0x03, 0x01, 0x02, 0x00]).await.unwrap();
    for (what, mut s) in [("silent", silent), ("a partial ClientHello", partial)] {
        let mut b = [0u8; 64];
        // A generous bound, not a timing budget.
        match tokio::time::timeout(Duration::from_secs(60), s.read(&mut b)).await {
            Ok(Ok(0)) | Ok(Err(_)) => {}
            Ok(Ok(n)) => panic!("{what}: the server sent {n} bytes"),
            Err(_) => panic!("{what}: the connection is still open after 60 s"),
        }
    }
    tr.list_exercises(pb::ListExercisesRequest {}).await.expect("the TLS connection outlived the deadline");
}

/// Item 14 (part): after EndExercise, TakeControl, HandBackControl and SetPaused are
/// FAILED_PRECONDITION (the proto's rule for an ended exercise); an instructor who had control at
/// the end has let it go.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_control_calls_after_end_exercise_are_failed_precondition() {
    let _turn = REALTIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let (sid, _, instructor) = exercise(&ch).await;
    let req = || with_token(pb::ExerciseRequest { session_id: sid.clone() }, &instructor);
    let st = tr.take_control(req()).await.expect("TakeControl while it runs").into_inner();
    assert_eq!(st.controller, pb::ControllerRole::Instructor as i32);
    let fin = tr.end_exercise(req()).await.expect("EndExercise").into_inner();
    assert!(fin.finished);
    assert_eq!(fin.controller, pb::ControllerRole::Trainee as i32, "the end lets the instructor's control go");
    for (what, r) in [
        ("TakeControl", tr.take_control(req()).await),
        ("HandBackControl", tr.hand_back_control(req()).await),
        ("SetPaused", tr.set_paused(with_token(pb::SetPausedRequest { session_id: sid.clone(), paused: true }, &instructor)).await),
    ] {
        let e = r.expect_err(what);
        assert_eq!(e.code(), Code::FailedPrecondition, "{what}: {e:?}");
        assert!(e.message().contains("the exercise has ended"), "{what}: {}", e.message());
    }
    let st = tr.get_status(req()).await.unwrap().into_inner();
    assert!(!st.paused && st.controller == pb::ControllerRole::Trainee as i32, "nothing refused took hold: {st:?}");
}
