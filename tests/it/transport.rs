//! Issue 35's transport and lifecycle findings, through the real server binary and a raw HTTP/2
//! client (the `h2` crate: a receive window of 0, request messages that never end): the streams
//! of one connection are bounded and a stalled response of a static file holds no copy of it; the
//! bytes of unfinished request messages are bounded over the server and a message that stops
//! arriving is ended; SIGTERM ends the process within its grace whatever the clients hold, the
//! recordings finished; an unknown method's answer quotes a bounded part of its path.

use std::time::{Duration, Instant};

use bytes::Bytes;
use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME, ServerProcess, TempDir, connect, rss_bytes, with_token};
use prost::Message;
use tonic::Code;

/// An HTTP/2 connection to `addr` whose receive window is `window` bytes (0: the server can send
/// headers but no data), driven in the background.
async fn h2_connect(addr: &str, window: u32) -> h2::client::SendRequest<Bytes> {
    let tcp = tokio::net::TcpStream::connect(addr).await.expect("connect");
    let (send, conn) = h2::client::Builder::new()
        .initial_window_size(window)
        .initial_connection_window_size(window.max(65_535))
        .handshake::<_, Bytes>(tcp)
        .await
        .expect("HTTP/2 handshake");
    tokio::spawn(async move {
        let _ = conn.await;
    });
    send.ready().await.expect("the connection is ready")
}

fn grpc_request(addr: &str, path: &str) -> http::Request<()> {
    http::Request::builder()
        .method("POST")
        .uri(format!("http://{addr}{path}"))
        .header("content-type", "application/grpc")
        .header("te", "trailers")
        .body(())
        .unwrap()
}

/// The gRPC status of a response (its trailers-only headers, or its trailers).
async fn grpc_status(resp: h2::client::ResponseFuture) -> Option<(i32, String)> {
    let resp = resp.await.ok()?;
    let from = |h: &http::HeaderMap| {
        let code = h.get("grpc-status")?.to_str().ok()?.parse().ok()?;
        let msg = h.get("grpc-message").and_then(|m| m.to_str().ok()).unwrap_or("").to_owned();
        Some((code, msg))
    };
    if let Some(s) = from(resp.headers()) {
        return Some(s);
    }
    let mut body = resp.into_body();
    while let Some(d) = body.data().await {
        let _ = d.ok()?;
    }
    from(&body.trailers().await.ok()??)
}

/// Issue 35 (1a): one HTTP/2 connection held 5,000 `GET /dist/app.js` whose client never opened
/// its receive window — a copy of the file each, 4 GB. The server now advertises
/// SETTINGS_MAX_CONCURRENT_STREAMS (`--max-streams-per-connection`, 100 by default) and serves the
/// files from shared bytes read at start: 10 connections holding 100 stalled responses each of a
/// 1 MiB file (1,000 copies: 1 GB before) cost the server a few MB.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_stalled_http2_responses_of_static_files_are_bounded_and_share_the_file() {
    let tmp = TempDir::new("h2-static");
    let web = tmp.join("web");
    std::fs::create_dir_all(web.join("dist")).unwrap();
    std::fs::write(web.join("index.html"), "<html></html>").unwrap();
    std::fs::write(web.join("dist/app.js"), vec![b'x'; 1 << 20]).unwrap();
    let small = ServerProcess::start(&["--default-scene", "none", "--web-dir", web.to_str().unwrap(), "--max-streams-per-connection", "8"]);
    let mut send = h2_connect(&small.addr, 0).await;
    // The server's SETTINGS arrive with the first exchange.
    let (resp, _) = send.send_request(http::Request::get(format!("http://{}/index.html", small.addr)).body(()).unwrap(), true).unwrap();
    resp.await.expect("an answer");
    assert_eq!(send.current_max_send_streams(), 8, "the streams the server lets one connection open");
    drop(small);

    let server = ServerProcess::start(&["--default-scene", "none", "--web-dir", web.to_str().unwrap()]);
    let pid = server.child.id();
    let before = rss_bytes(pid);
    let mut held = Vec::new();
    for _ in 0..10 {
        let mut send = h2_connect(&server.addr, 0).await;
        let (first, _) = send.send_request(http::Request::get(format!("http://{}/", server.addr)).body(()).unwrap(), true).unwrap();
        first.await.expect("an answer");
        assert_eq!(send.current_max_send_streams(), 100, "the default --max-streams-per-connection");
        for _ in 0..100 {
            send = send.ready().await.expect("a stream");
            let req = http::Request::get(format!("http://{}/dist/app.js", server.addr)).body(()).unwrap();
            let (resp, _) = send.send_request(req, true).expect("a GET");
            held.push(resp);
        }
    }
    // Every response's headers came back (the file's data waits for a window that never opens);
    // the responses are kept (dropping one would reset its stream).
    let mut answered = Vec::new();
    for r in held.drain(..) {
        let resp = tokio::time::timeout(Duration::from_secs(30), r).await.expect("headers in time").expect("an answer");
        assert_eq!(resp.status(), 200);
        answered.push(resp);
    }
    assert_eq!(answered.len(), 1000);
    tokio::time::sleep(Duration::from_millis(500)).await;
    let grown = rss_bytes(pid).saturating_sub(before);
    assert!(grown < 100 << 20, "1,000 stalled responses of a 1 MiB file grew the server by {} MB", grown >> 20);
}

/// Issue 35 (1b): 43 CreateSession streams each sending 60 MiB of a declared 60 MiB message and
/// never finishing held 3 GB until their connection closed. The bytes of unfinished messages are
/// bounded over the server (`--max-pending-request-mb`): a call whose bytes would pass it fails
/// with RESOURCE_EXHAUSTED; a message that stops arriving ends its call with DEADLINE_EXCEEDED
/// after `--handshake-timeout-ms`, and its bytes are given back.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_unfinished_request_messages_are_bounded_over_the_server_and_time_out() {
    let server = ServerProcess::start(&[
        "--default-scene",
        "none",
        "--max-message-bytes",
        &(16 << 20).to_string(),
        "--max-pending-request-mb",
        "48",
        "--handshake-timeout-ms",
        "2000",
    ]);
    let pid = server.child.id();
    let before = rss_bytes(pid);
    const LEN: usize = 16 << 20;
    let mut body = Vec::with_capacity(LEN + 4);
    body.push(0u8);
    body.extend_from_slice(&(LEN as u32).to_be_bytes());
    body.resize(LEN + 4, 0x0a);
    let body = Bytes::from(body);
    let mut calls = Vec::new();
    let mut streams = Vec::new();
    // Two connections of 8 streams: 256 MiB of unfinished messages offered.
    for _ in 0..2 {
        let mut send = h2_connect(&server.addr, 65_535).await;
        for _ in 0..8 {
            send = send.ready().await.expect("a stream");
            let (resp, mut stream) =
                send.send_request(grpc_request(&server.addr, "/needlesim.v1.SessionService/CreateSession"), false).unwrap();
            stream.send_data(body.clone(), false).expect("data queued");
            calls.push(tokio::spawn(grpc_status(resp)));
            streams.push(stream);
        }
    }
    let t0 = Instant::now();
    let mut peak = 0u64;
    let mut statuses = Vec::new();
    for c in calls {
        loop {
            peak = peak.max(rss_bytes(pid).saturating_sub(before));
            if c.is_finished() {
                break;
            }
            assert!(t0.elapsed() < Duration::from_secs(60), "the calls did not end; stderr: {}", server.stderr.lock().unwrap());
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        statuses.push(c.await.unwrap().expect("a gRPC status"));
    }
    let exhausted = statuses.iter().filter(|(c, _)| *c == Code::ResourceExhausted as i32).count();
    let stalled = statuses.iter().filter(|(c, _)| *c == Code::DeadlineExceeded as i32).count();
    assert_eq!(exhausted + stalled, 16, "{statuses:?}");
    assert!(exhausted >= 1 && stalled >= 1, "{statuses:?}");
    for (_, m) in &statuses {
        assert!(m.len() <= 1024, "{m}");
    }
    assert!(statuses.iter().any(|(_, m)| m.contains("max-pending-request-mb")), "{statuses:?}");
    // 48 MiB held at most, not the 256 MiB sent (nor a copy of each in the decoder).
    assert!(peak < 160 << 20, "unfinished messages grew the server by {} MB", peak >> 20);
    assert_eq!(server.metric("needlesim_pending_request_bytes"), 0.0, "the bytes are given back");
    assert!(server.metric("needlesim_pending_request_refused") >= 1.0);
    assert!(server.metric("needlesim_stalled_request_messages") >= 1.0);
    drop(streams);
}

/// Issue 35 (2): with a Simulate stream whose client never reads, or a unary call whose body
/// never ends, the server still ran 60 s after SIGTERM. It now closes the sessions (their
/// recordings finished), gives the connections `--shutdown-grace-ms`, and exits.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_sigterm_exits_within_its_grace_whatever_the_clients_hold() {
    let _turn = REALTIME.lock().await;
    let mut server = ServerProcess::start(&["--default-scene", "none", "--shutdown-grace-ms", "2000", "--handshake-timeout-ms", "60000"]);
    let ch = connect(&server).await;
    let s = needlesim_tests::create_example_session(&ch, "paper-phantom").await;
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    rec.start_recording(with_token(
        pb::StartRecordingRequest { session_id: s.session.clone().expect("a session").session_id, include_displacements: false },
        &s.controller_token,
    ))
    .await
    .expect("a recording starts");
    tokio::time::sleep(Duration::from_millis(500)).await;

    // One connection that never reads: a Simulate stream, and a ListSessions whose message never ends.
    let mut send = h2_connect(&server.addr, 0).await;
    let msg = pb::SimulateRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
        ..Default::default()
    }
    .encode_to_vec();
    let mut framed = vec![0u8];
    framed.extend_from_slice(&(msg.len() as u32).to_be_bytes());
    framed.extend_from_slice(&msg);
    let (sim, mut sim_body) = send.send_request(grpc_request(&server.addr, "/needlesim.v1.SimulationService/Simulate"), false).unwrap();
    sim_body.send_data(Bytes::from(framed), true).unwrap();
    send = send.ready().await.unwrap();
    let (_list, mut list_body) = send.send_request(grpc_request(&server.addr, "/needlesim.v1.SessionService/ListSessions"), false).unwrap();
    list_body.send_data(Bytes::from_static(&[0, 0, 0, 0, 10, 0]), false).unwrap();
    let sim = tokio::time::timeout(Duration::from_secs(30), sim).await.expect("Simulate's headers").expect("Simulate answers");
    assert_eq!(sim.status(), 200);
    tokio::time::sleep(Duration::from_secs(1)).await;

    let pid = server.child.id();
    let st = std::process::Command::new("kill").args(["-TERM", &pid.to_string()]).status().expect("kill runs");
    assert!(st.success());
    let t0 = Instant::now();
    let status = loop {
        if let Some(st) = server.child.try_wait().expect("try_wait") {
            break st;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(15),
            "the server still runs {:?} after SIGTERM: {}",
            t0.elapsed(),
            server.stderr.lock().unwrap()
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    };
    let took = t0.elapsed();
    assert!(status.success(), "{status:?}: {}", server.stderr.lock().unwrap());
    assert!(took >= Duration::from_millis(1900), "the connections were given their grace: exited after {took:?}");
    let recordings: Vec<_> = std::fs::read_dir(server.data_dir.join("recordings"))
        .expect("the recordings directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mcap"))
        .collect();
    assert_eq!(recordings.len(), 1, "{recordings:?}");
    let bytes = std::fs::read(&recordings[0]).unwrap();
    assert!(bytes.ends_with(b"\x89MCAP0\r\n"), "the recording is finished (MCAP footer magic): {} bytes", bytes.len());
    drop(send);
}

/// Issue 35 (3): a call of an unknown method with a path of 12,000 characters was answered
/// "no such gRPC method: /…" 12,040 characters long. The path is quoted clipped (64 characters).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_unknown_method_s_long_path_is_quoted_clipped() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut grpc = tonic::client::Grpc::new(ch);
    grpc.ready().await.unwrap();
    let path = format!("/needlesim.v1.Nope/{}", "A".repeat(12_000));
    let path = http::uri::PathAndQuery::from_maybe_shared(path).unwrap();
    let codec = tonic_prost::ProstCodec::<pb::ListSessionsRequest, pb::ListSessionsResponse>::default();
    let e = grpc.unary(tonic::Request::new(pb::ListSessionsRequest {}), path, codec).await.unwrap_err();
    assert_eq!(e.code(), Code::Unimplemented, "{e:?}");
    assert!(e.message().starts_with("no such gRPC method: /needlesim.v1.Nope/AAA"), "{}", e.message());
    assert!(e.message().chars().count() <= 1024, "{} characters", e.message().chars().count());
    assert!(e.message().matches('A').count() <= 64, "{} characters: {}", e.message().len(), &e.message()[..100]);
}
