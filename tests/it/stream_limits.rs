//! Issue 35, items 4, 6 and part of 14, through the real server binary: every server-streaming
//! call counts against its session's `--max-observers` and the server's `--max-streams` (a
//! cancelled stream gives its place back); connections that bring no request are closed and the
//! number of connections is bounded (`--max-connections`, `--handshake-timeout-ms`: a connection's
//! first request, an HTTP/1.1 connection's next one, an HTTP/1.1 body that stalls); TakeControl,
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
    // Round 2: a client that completes the TLS handshake but sends no request is closed too
    // (was: open for good). `openssl s_client` exits when the server closes the connection.
    let mut client = std::process::Command::new("openssl")
        .args(["s_client", "-connect", &server.addr, "-quiet"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("openssl s_client runs");
    let t0 = Instant::now();
    let exited = loop {
        if let Some(st) = client.try_wait().unwrap() {
            break Some(st);
        }
        if t0.elapsed() > Duration::from_secs(20) {
            break None;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    };
    let _ = client.kill();
    let out = client.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(exited.is_some(), "a TLS connection without a request is still open after 20 s: {err}");
    assert!(err.contains("verify return"), "the TLS handshake was made before the close: {err}");
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

/// Reads `s` until the server closes it (EOF or a reset) within `limit`; the bytes it sent
/// before (an HTTP answer, HTTP/2 settings), or an error if it is still open.
async fn closed_within(s: &mut tokio::net::TcpStream, limit: Duration) -> Result<Vec<u8>, String> {
    use tokio::io::AsyncReadExt;
    let mut got = Vec::new();
    let mut buf = [0u8; 4096];
    let end = tokio::time::Instant::now() + limit;
    loop {
        match tokio::time::timeout_at(end, s.read(&mut buf)).await {
            Ok(Ok(0)) | Ok(Err(_)) => return Ok(got),
            Ok(Ok(n)) => got.extend_from_slice(&buf[..n]),
            Err(_) => return Err(format!("still open after {limit:?}; it sent: {:?}", String::from_utf8_lossy(&got))),
        }
    }
}

/// A connection to the server that has sent `bytes`.
async fn sent(server: &ServerProcess, bytes: &[u8]) -> tokio::net::TcpStream {
    use tokio::io::AsyncWriteExt;
    let mut s = tokio::net::TcpStream::connect(&server.addr).await.expect("TCP connect");
    s.write_all(bytes).await.expect("write");
    s
}

/// HTTP/2's client preface.
const H2_PREFACE: &[u8] = b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n";

/// A generous bound for a close due after a 1 s deadline (the machine stalls; not a budget).
const CLOSE_BOUND: Duration = Duration::from_secs(15);

/// Item 6, round 2: the deadline ends at a connection's first request, not at its first bytes.
/// With `--handshake-timeout-ms 1000`, a connection that sends only HTTP/2's preface, one that
/// sends the preface and its SETTINGS (the whole HTTP/2 handshake) but no request, and one that
/// sends half of an HTTP/1.1 request's headers are all closed within a few seconds (were: open
/// for good, open for good, closed by hyper after 30 s), counted as timed out; a gRPC client that
/// made its call keeps its connection past the deadline.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_connections_are_closed_until_their_first_request_arrives() {
    let server = ServerProcess::start(&["--default-scene", "none", "--handshake-timeout-ms", "1000"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    tr.list_exercises(pb::ListExercisesRequest {}).await.expect("a call before");
    let settings: &[u8] = &[0, 0, 0, 4, 0, 0, 0, 0, 0];
    let mut conns = vec![
        ("the HTTP/2 preface alone", sent(&server, H2_PREFACE).await),
        ("the HTTP/2 preface and SETTINGS", sent(&server, &[H2_PREFACE, settings].concat()).await),
        ("half of an HTTP/1.1 request's headers", sent(&server, b"GET /metrics HTTP/1.1\r\nHost: x\r\n").await),
    ];
    for (what, s) in &mut conns {
        closed_within(s, CLOSE_BOUND).await.unwrap_or_else(|e| panic!("{what}: {e}"));
    }
    assert_eq!(server.metric("needlesim_connections_timed_out"), 3.0, "each closed at its deadline");
    tr.list_exercises(pb::ListExercisesRequest {}).await.expect("the gRPC connection outlived the deadline");
}

/// A gRPC-web (HTTP/1.1) request for `path` carrying `msg`, with `extra` header lines.
fn grpc_web_request(path: &str, msg: &impl prost::Message, extra: &str) -> Vec<u8> {
    let body = msg.encode_to_vec();
    let mut framed = vec![0u8];
    framed.extend_from_slice(&u32::try_from(body.len()).unwrap().to_be_bytes());
    framed.extend_from_slice(&body);
    let head = format!(
        "POST {path} HTTP/1.1\r\nHost: x\r\nContent-Type: application/grpc-web+proto\r\nX-Grpc-Web: 1\r\nContent-Length: {}\r\n{extra}\r\n",
        framed.len()
    );
    [head.as_bytes(), &framed].concat()
}

/// Item 6, round 2: an HTTP/1.1 request whose headers are complete but whose body stalls (no
/// byte of it, or 10 of 1000) is ended after `--handshake-timeout-ms` and its connection closed
/// within a few seconds (was: open for good), counted in `needlesim_connections_stalled_bodies`;
/// HTTP/2 streams are not timed out: a Control stream whose client sends nothing for 4 s (four
/// deadlines) still moves the needle afterwards.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_stalled_http1_request_body_is_ended_but_not_an_idle_control_stream() {
    let _turn = REALTIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--handshake-timeout-ms", "1000"]);
    let head = "POST /needlesim.v1.SessionService/ListSessions HTTP/1.1\r\nHost: x\r\nContent-Type: application/grpc-web+proto\r\n\
                X-Grpc-Web: 1\r\nContent-Length: 1000\r\n\r\n";
    let mut conns = vec![
        ("headers, no body", sent(&server, head.as_bytes()).await),
        ("headers, 10 of 1000 body bytes", sent(&server, &[head.as_bytes(), &[0u8; 10]].concat()).await),
    ];
    for (what, s) in &mut conns {
        closed_within(s, CLOSE_BOUND).await.unwrap_or_else(|e| panic!("{what}: {e}"));
    }
    assert_eq!(server.metric("needlesim_connections_stalled_bodies"), 2.0);

    let ch = connect(&server).await;
    let created = needlesim_tests::create_example_session(&ch, "fig3-target").await;
    let sid = created.session.unwrap().session_id;
    let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest>(4);
    let pose = |seq: u64| pb::ControlRequest {
        session_id: if seq == 1 { sid.clone() } else { String::new() },
        base: Some(pb::Pose2 { x_m: 0.05, y_m: 0.205 - 0.001 * seq as f64, theta_rad: -std::f64::consts::FRAC_PI_2 }),
        seq,
        ..Default::default()
    };
    tx.send(pose(1)).await.unwrap();
    let mut ctl = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let mut responses = ctl
        .control(with_token(tokio_stream::wrappers::ReceiverStream::new(rx), &created.controller_token))
        .await
        .expect("a Control stream")
        .into_inner();
    // Read every tick's response, and note the newest pose the session used.
    let (seq_tx, mut seq_rx) = tokio::sync::watch::channel(0u64);
    let reader = tokio::spawn(async move {
        while let Ok(Some(r)) = responses.message().await {
            seq_tx.send_replace(r.pose_seq);
        }
    });
    let until_seq = |rx: &mut tokio::sync::watch::Receiver<u64>, seq: u64| {
        let mut rx = rx.clone();
        async move { tokio::time::timeout(Duration::from_secs(20), rx.wait_for(|s| *s >= seq)).await.is_ok_and(|r| r.is_ok()) }
    };
    assert!(until_seq(&mut seq_rx, 1).await, "the first pose was used");
    // The client's request stream sends nothing for four deadlines.
    tokio::time::sleep(Duration::from_secs(4)).await;
    tx.send(pose(2)).await.expect("the Control stream is still open");
    assert!(until_seq(&mut seq_rx, 2).await, "a pose after the pause was used: the stream was not timed out");
    assert!(!reader.is_finished(), "the responses still flow");
    drop(tx);
    let _ = tokio::time::timeout(Duration::from_secs(20), reader).await;
}

/// Item 6, round 2: an HTTP/1.1 keep-alive connection that sends no next request after its
/// response is closed within a few seconds of the 1 s deadline (was: after hyper's 30 s), counted
/// in `needlesim_connections_idle_closed`; a long gRPC-web response over HTTP/1.1 (a browser's
/// Observe) is a request in progress: it outlives four deadlines.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_idle_http1_keep_alive_connection_is_closed_but_not_a_streaming_one() {
    use tokio::io::AsyncReadExt;
    let _turn = REALTIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--handshake-timeout-ms", "1000"]);
    let mut s = sent(&server, b"GET /metrics HTTP/1.1\r\nHost: x\r\n\r\n").await;
    let t0 = Instant::now();
    let answer = closed_within(&mut s, CLOSE_BOUND).await.unwrap_or_else(|e| panic!("an idle keep-alive connection: {e}"));
    let answer = String::from_utf8_lossy(&answer);
    assert!(answer.starts_with("HTTP/1.1 200") && answer.contains("needlesim_sessions"), "the request was answered first: {answer}");
    println!("idle keep-alive connection closed after {:.1} s", t0.elapsed().as_secs_f64());
    assert_eq!(server.metric("needlesim_connections_idle_closed"), 1.0);

    let ch = connect(&server).await;
    let created = needlesim_tests::create_example_session(&ch, "fig3-target").await;
    let observe = pb::ObserveRequest { session_id: created.session.unwrap().session_id, rate_hz: 30.0, include_displacements: false };
    let mut s = sent(
        &server,
        &grpc_web_request(
            "/needlesim.v1.ObserveService/Observe",
            &observe,
            &format!("Authorization: Bearer {}\r\n", created.observer_token),
        ),
    )
    .await;
    let t0 = Instant::now();
    let (mut total, mut late) = (0usize, 0usize);
    let mut buf = [0u8; 65536];
    while t0.elapsed() < Duration::from_secs(5) {
        match tokio::time::timeout(Duration::from_secs(5), s.read(&mut buf)).await {
            Ok(Ok(0)) | Ok(Err(_)) => {
                panic!("the Observe stream over HTTP/1.1 was closed after {:.1} s ({total} bytes)", t0.elapsed().as_secs_f64())
            }
            Ok(Ok(n)) => {
                total += n;
                if t0.elapsed() > Duration::from_secs(4) {
                    late += n;
                }
            }
            Err(_) => panic!("no frame for 5 s"),
        }
    }
    assert!(late > 0, "frames still arrive after four deadlines ({total} bytes in all)");
}
