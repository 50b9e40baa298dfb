//! Issue 35's transport and lifecycle findings, through the real server binary and a raw HTTP/2
//! client (the `h2` crate: a receive window of 0, request messages that never end): the streams
//! of one connection are bounded and a stalled response of a static file holds no copy of it; the
//! bytes of unfinished request messages are bounded over the server and a message that stops
//! arriving is ended; SIGTERM ends the process within its grace whatever the clients hold, the
//! recordings finished; an unknown method's answer quotes a bounded part of its path. Round 3: a
//! message's decoded size is bounded before it is decoded; complete answers held for clients that
//! do not read are bounded and dropped at a deadline; a Control stream without a first message ends.

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

/// A gRPC message of `body` framed (uncompressed).
fn framed(body: &[u8]) -> Bytes {
    let mut out = Vec::with_capacity(body.len() + 5);
    out.push(0u8);
    out.extend_from_slice(&(body.len() as u32).to_be_bytes());
    out.extend_from_slice(body);
    Bytes::from(out)
}

/// `grpc-message` as sent (percent-encoded), decoded.
fn percent_decoded(m: &str) -> String {
    let b = m.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%'
            && let Some(v) = m.get(i + 1..i + 3).and_then(|h| u8::from_str_radix(h, 16).ok())
        {
            out.push(v);
            i += 3;
            continue;
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// A protobuf varint.
fn varint(mut v: u64) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let b = (v & 0x7f) as u8;
        v >>= 7;
        if v == 0 {
            out.push(b);
            return out;
        }
        out.push(b | 0x80);
    }
}

/// Issue 35, finding 1: a 60 MiB SimulateRequest of 31,457,280 empty trajectory samples (2 bytes
/// each on the wire) took the server from 28 to 3,490 MB before it said the trajectory was over its
/// limit; so did Track's frames, CreateSession's uploaded regions and Plan's `avoid`. The codec now
/// estimates the decoded size from the wire format before prost allocates: such a message is
/// RESOURCE_EXHAUSTED naming the field's number path, its count of elements and the limit, and the
/// server barely grows.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_decoded_size_is_bounded_before_decoding() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let pid = server.child.id();
    let before = rss_bytes(pid);
    // 8,000,000 empty samples: 16 MiB on the wire, 870 MB once decoded by prost.
    let n = 8_000_000usize;
    let simulate = b"\x12\x00".repeat(n);
    // CreateSessionRequest{scene(1): SceneSource{uploaded(3): UploadedScene{regions(3): [Region{}; m]}}}
    let m = 2_000_000usize;
    let regions = b"\x1a\x00".repeat(m);
    let mut uploaded = vec![0x1a];
    uploaded.extend(varint(regions.len() as u64));
    uploaded.extend_from_slice(&regions);
    let mut create = vec![0x0a];
    create.extend(varint(uploaded.len() as u64));
    create.extend_from_slice(&uploaded);
    let cases: [(&str, Vec<u8>, &str, usize); 4] = [
        ("/needlesim.v1.SimulationService/Simulate", simulate, "field 2 has", n),
        ("/needlesim.v1.SessionService/CreateSession", create, "field 1.3.3 has", m),
        ("/needlesim.v1.IdentifyService/Track", b"\x0a\x00".repeat(m), "field 1 has", m),
        ("/needlesim.v1.PlanningService/Plan", b"\x52\x00".repeat(m), "field 10 has", m),
    ];
    for (path, msg, field, count) in cases {
        let mut send = h2_connect(&server.addr, 65_535).await;
        let (resp, mut body) = send.send_request(grpc_request(&server.addr, path), false).unwrap();
        body.send_data(framed(&msg), true).expect("data queued");
        let call = tokio::spawn(grpc_status(resp));
        let t0 = Instant::now();
        let mut peak = 0u64;
        while !call.is_finished() {
            peak = peak.max(rss_bytes(pid).saturating_sub(before));
            assert!(t0.elapsed() < Duration::from_secs(120), "{path}: no answer; stderr: {}", server.stderr.lock().unwrap());
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
        let (code, message) = call.await.unwrap().expect("a gRPC status");
        let message = percent_decoded(&message);
        assert_eq!(code, Code::ResourceExhausted as i32, "{path}: {message}");
        assert!(message.contains(&format!("{field} {count} elements")), "{path}: {message}");
        assert!(message.contains("over the limit of"), "{path}: {message}");
        // The message's own bytes (16 MiB, held while it arrives and walked), not its decoded form.
        assert!(peak < 200 << 20, "{path}: the server grew by {} MB", peak >> 20);
    }
    // A request within the limits is decoded and answered as before (here: its scene is unknown).
    let ch = connect(&server).await;
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch);
    let req = pb::SimulateRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("no-such-scene".into())) }),
        trajectory: vec![pb::TrajectorySample::default(); 1000],
        ..Default::default()
    };
    let e = sim.simulate(req).await.expect_err("an unknown scene");
    assert_ne!(e.code(), Code::ResourceExhausted, "{e:?}");
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Issue 35, finding 2: 500 GetMesh answers of 3.1 MB to connections with a zero receive window
/// were held whole (1.7 GB), counted by nothing. A complete answer over 64 kB now takes its bytes
/// from `--max-held-answers-mb` (RESOURCE_EXHAUSTED past it, naming the flag) until it is dropped;
/// an answer its client has not taken within `--answer-deadline-ms` is dropped and its bytes given
/// back (`/metrics`: needlesim_held_answer_bytes, needlesim_held_answers_timed_out).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_unread_unary_answers_are_bounded_and_dropped_at_their_deadline() {
    let server = ServerProcess::start(&["--default-scene", "none", "--max-held-answers-mb", "1", "--answer-deadline-ms", "3000"]);
    let ch = connect(&server).await;
    // A 61 × 61-node grid: a GetMesh answer of about 110 kB.
    let phantom = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/paper-phantom.toml")).unwrap();
    let s = needlesim_tests::create_toml_session(&ch, phantom.replace("nx = 19", "nx = 61").replace("ny = 19", "ny = 61")).await;
    let session_id = s.session.clone().expect("a session").session_id;
    let get = pb::GetSessionRequest { session_id: session_id.clone() };
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mesh = sessions.get_mesh(with_token(get.clone(), &s.observer_token)).await.expect("GetMesh").into_inner();
    let answer_bytes = mesh.encoded_len() as u64 + 5;
    assert!(answer_bytes > 64 << 10, "{answer_bytes}");
    let fit = ((1u64 << 20) / answer_bytes) as usize;

    // A client that never reads: `fit` answers are held, the next two refused.
    let mut send = h2_connect(&server.addr, 0).await;
    let mut held = Vec::new();
    let mut refused = Vec::new();
    for k in 0..fit + 2 {
        send = send.ready().await.expect("a stream");
        let mut req = grpc_request(&server.addr, "/needlesim.v1.SessionService/GetMesh");
        req.headers_mut().insert("authorization", format!("Bearer {}", s.observer_token).parse().unwrap());
        let (resp, mut body) = send.send_request(req, false).unwrap();
        body.send_data(framed(&get.encode_to_vec()), true).unwrap();
        let resp = tokio::time::timeout(Duration::from_secs(30), resp).await.expect("headers in time").expect("an answer");
        match resp.headers().get("grpc-status") {
            // Trailers-only: refused.
            Some(code) => {
                refused.push((k, code.to_str().unwrap().to_owned(), percent_decoded(resp.headers()["grpc-message"].to_str().unwrap())))
            }
            None => held.push(resp),
        }
    }
    assert_eq!(held.len(), fit, "refused: {refused:?}");
    assert_eq!(refused.len(), 2, "{refused:?}");
    for (_, code, message) in &refused {
        assert_eq!(code, &(Code::ResourceExhausted as i32).to_string(), "{message}");
        assert!(message.contains("--max-held-answers-mb") && message.contains("limit of 1048576 bytes"), "{message}");
    }
    let held_bytes = server.metric("needlesim_held_answer_bytes");
    assert!(held_bytes >= (fit as u64 * (answer_bytes - 5)) as f64, "{held_bytes}");
    assert_eq!(server.metric("needlesim_held_answers_refused"), 2.0);

    // Past the deadline the held answers are dropped and their bytes given back.
    let t0 = Instant::now();
    while server.metric("needlesim_held_answer_bytes") != 0.0 {
        assert!(
            t0.elapsed() < Duration::from_secs(15),
            "the held answers were not dropped: {}",
            server.metric("needlesim_held_answer_bytes")
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    assert!(t0.elapsed() >= Duration::from_secs(1), "dropped before the deadline");
    assert_eq!(server.metric("needlesim_held_answers_timed_out"), fit as f64);
    // Another client is answered again.
    let again = sessions.get_mesh(with_token(get, &s.observer_token)).await.expect("GetMesh after the deadline").into_inner();
    assert_eq!(again.node_xy_m.len(), mesh.node_xy_m.len());
    assert_eq!(server.metric("needlesim_held_answer_bytes"), 0.0);
    drop(held);
}

/// Issue 35, finding 3: 15,000 Control streams that never sent a first message were held (10 kB
/// each), counted by nothing, still open after 90 s. Such a stream now ends with DEADLINE_EXCEEDED
/// after `--control-first-message-ms` (5 s by default), and the ones waiting are in `/metrics`.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_control_streams_without_a_first_message_end_at_their_deadline() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let mut send = h2_connect(&server.addr, 65_535).await;
    let mut calls = Vec::new();
    let mut bodies = Vec::new();
    let t0 = Instant::now();
    for k in 0..40 {
        send = send.ready().await.expect("a stream");
        let path = if k % 2 == 0 { "/needlesim.v1.ControlService/Control" } else { "/needlesim.v1.ControlService/Control3" };
        let (resp, body) = send.send_request(grpc_request(&server.addr, path), false).unwrap();
        calls.push(tokio::spawn(grpc_status(resp)));
        bodies.push(body);
    }
    let waiting = loop {
        let n = server.metric("needlesim_control_streams_awaiting_first_message");
        if n == 40.0 || t0.elapsed() > Duration::from_secs(4) {
            break n;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    };
    assert_eq!(waiting, 40.0, "the streams waiting for their first message are counted");
    for c in calls {
        let (code, message) =
            tokio::time::timeout(Duration::from_secs(20), c).await.expect("the stream ended in time").unwrap().expect("a gRPC status");
        let message = percent_decoded(&message);
        assert_eq!(code, Code::DeadlineExceeded as i32, "{message}");
        assert!(message.contains("no first message within 5000 ms") && message.contains("--control-first-message-ms"), "{message}");
    }
    assert!(t0.elapsed() >= Duration::from_millis(4500), "ended after {:?}", t0.elapsed());
    assert_eq!(server.metric("needlesim_control_streams_awaiting_first_message"), 0.0);
    assert_eq!(server.metric("needlesim_control_streams_first_message_timeouts"), 40.0);
    drop(bodies);
}

/// Issue 35, pass 4 (1): an unknown-field group (field 1000, wire types 3 and 4) after a
/// SimulateRequest's empty samples made the codec's walk give up, and the decoder then skipped the
/// decoded-size bound: prost skipped the group and decoded 60 MiB of samples into 3.5 GB. A group
/// in the request message is now refused with INVALID_ARGUMENT naming its field, before anything
/// is decoded; a group inside a field (UploadedScene) is walked past, its regions still counted.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_group_in_a_request_is_refused_and_does_not_turn_off_the_size_bound() {
    const GROUP_1000: &[u8] = b"\xc3\x3e\xc4\x3e";
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let pid = server.child.id();
    let before = rss_bytes(pid);
    // 6,000,000 empty samples (12 MiB on the wire, 650 MB decoded), then the group.
    let n = 6_000_000usize;
    let mut simulate = b"\x12\x00".repeat(n);
    simulate.extend_from_slice(GROUP_1000);
    // The group inside UploadedScene, after 1,300,000 empty regions (over the decoded bound).
    let m = 1_300_000usize;
    let mut regions = b"\x1a\x00".repeat(m);
    regions.extend_from_slice(GROUP_1000);
    let mut uploaded = vec![0x1a];
    uploaded.extend(varint(regions.len() as u64));
    uploaded.extend_from_slice(&regions);
    let mut create = vec![0x0a];
    create.extend(varint(uploaded.len() as u64));
    create.extend_from_slice(&uploaded);
    let cases: [(&str, Vec<u8>, Code, &str); 3] = [
        ("/needlesim.v1.SimulationService/Simulate", simulate, Code::InvalidArgument, "has a group at field 1000"),
        // A group alone, first: the same.
        ("/needlesim.v1.SimulationService/Simulate", GROUP_1000.to_vec(), Code::InvalidArgument, "has a group at field 1000"),
        ("/needlesim.v1.SessionService/CreateSession", create, Code::ResourceExhausted, &format!("field 1.3.3 has {m} elements")),
    ];
    for (path, msg, want, says) in cases {
        let mut send = h2_connect(&server.addr, 65_535).await;
        let (resp, mut body) = send.send_request(grpc_request(&server.addr, path), false).unwrap();
        body.send_data(framed(&msg), true).expect("data queued");
        let call = tokio::spawn(grpc_status(resp));
        let t0 = Instant::now();
        let mut peak = 0u64;
        while !call.is_finished() {
            peak = peak.max(rss_bytes(pid).saturating_sub(before));
            assert!(t0.elapsed() < Duration::from_secs(120), "{path}: no answer; stderr: {}", server.stderr.lock().unwrap());
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
        let (code, message) = call.await.unwrap().expect("a gRPC status");
        let message = percent_decoded(&message);
        assert_eq!(code, want as i32, "{path}: {message}");
        assert!(message.contains(says), "{path}: {message}");
        // The message's own bytes (12 MiB, held while it arrives and walked), not its decoded form.
        assert!(peak < 200 << 20, "{path}: the server grew by {} MB", peak >> 20);
    }
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// An HTTP/2 connection to `addr` written by hand that never reads its socket (whose receive
/// buffer is small), having opened its receive windows to 2^31 − 1: every byte the server sends
/// stays in the server's buffers. Sends a unary call of `path` with `message` on each of `n` streams.
async fn h2_never_reading(addr: &str, path: &str, token: &str, message: &[u8], n: u32) -> tokio::net::TcpStream {
    use tokio::io::AsyncWriteExt;
    let socket = tokio::net::TcpSocket::new_v4().unwrap();
    socket.set_recv_buffer_size(4096).unwrap();
    let mut tcp = socket.connect(addr.parse().unwrap()).await.expect("connect");
    let frame = |kind: u8, flags: u8, stream: u32, payload: &[u8]| {
        let mut f = (payload.len() as u32).to_be_bytes()[1..].to_vec();
        f.extend([kind, flags]);
        f.extend(stream.to_be_bytes());
        f.extend_from_slice(payload);
        f
    };
    let mut out = b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n".to_vec();
    // SETTINGS: ENABLE_PUSH 0, INITIAL_WINDOW_SIZE 2^31 - 1; then the connection's window.
    out.extend(frame(0x4, 0, 0, &[0, 2, 0, 0, 0, 0, 0, 4, 0x7f, 0xff, 0xff, 0xff]));
    out.extend(frame(0x8, 0, 0, &(0x7fff_ffffu32 - 65_535).to_be_bytes()));
    // HPACK: each header a literal without indexing, its name new, no Huffman.
    let mut block = Vec::new();
    let authorization = format!("Bearer {token}");
    for (name, value) in [
        (":method", "POST"),
        (":scheme", "http"),
        (":path", path),
        (":authority", addr),
        ("content-type", "application/grpc"),
        ("te", "trailers"),
        ("authorization", authorization.as_str()),
    ] {
        assert!(name.len() < 127 && value.len() < 127);
        block.push(0);
        block.push(name.len() as u8);
        block.extend_from_slice(name.as_bytes());
        block.push(value.len() as u8);
        block.extend_from_slice(value.as_bytes());
    }
    for k in 0..n {
        let stream = 2 * k + 1;
        out.extend(frame(0x1, 0x4, stream, &block));
        out.extend(frame(0x0, 0x1, stream, &framed(message)));
    }
    tcp.write_all(&out).await.expect("the requests are written");
    tcp
}

/// Issue 35, pass 4 (2): the answer budget was given back once an answer's last slice was handed
/// to HTTP/2, but HTTP/2 (hyper's default) took up to 400 KiB of each stream for a client that had
/// opened its windows and never read its socket: 30 connections of 100 unread GetMesh calls of
/// 380 kB held 2 GB with `needlesim_held_answer_bytes` at 0. Each stream's send buffer is now one
/// chunk (16 KiB), so what the client has not read stays with the answer, counted.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_answers_a_client_does_not_read_stay_counted_whatever_its_windows() {
    let server = ServerProcess::start(&["--default-scene", "none", "--answer-deadline-ms", "60000"]);
    let ch = connect(&server).await;
    // A 61 × 61-node grid: a GetMesh answer of about 110 kB (under hyper's 400 KiB a stream).
    let phantom = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/paper-phantom.toml")).unwrap();
    let s = needlesim_tests::create_toml_session(&ch, phantom.replace("nx = 19", "nx = 61").replace("ny = 19", "ny = 61")).await;
    let get = pb::GetSessionRequest { session_id: s.session.clone().expect("a session").session_id };
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mesh = sessions.get_mesh(with_token(get.clone(), &s.observer_token)).await.expect("GetMesh").into_inner();
    let answer_bytes = mesh.encoded_len() as u64 + 5;
    assert!(answer_bytes > 100_000, "{answer_bytes}");
    let (conns, streams) = (2u32, 60u32);
    let mut held = Vec::new();
    for _ in 0..conns {
        held.push(
            h2_never_reading(&server.addr, "/needlesim.v1.SessionService/GetMesh", &s.observer_token, &get.encode_to_vec(), streams).await,
        );
    }
    // Every call answered: the answers wait, counted, but for what the sockets took (a few
    // hundred kB) and a chunk or two a stream in HTTP/2.
    let total = u64::from(conns * streams) * answer_bytes;
    let t0 = Instant::now();
    let mut counted = 0.0;
    while t0.elapsed() < Duration::from_secs(20) {
        tokio::time::sleep(Duration::from_millis(500)).await;
        counted = server.metric("needlesim_held_answer_bytes");
        if counted >= 0.7 * total as f64 {
            break;
        }
    }
    assert!(counted >= 0.7 * total as f64, "{counted} of {total} bytes of unread answers counted");
    drop(held);
    // The connections closed, the answers are dropped and their bytes given back.
    let t0 = Instant::now();
    while server.metric("needlesim_held_answer_bytes") != 0.0 {
        assert!(t0.elapsed() < Duration::from_secs(10), "{}", server.metric("needlesim_held_answer_bytes"));
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
}

/// Issue 35, pass 4 (3): answers up to 64 kB were not counted: 6,000 unread GetMesh answers of
/// 64,373 bytes held 475 MB and none timed out. Every unary answer is now counted, and dropped
/// at `--answer-deadline-ms`.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_small_unread_answers_are_counted_and_dropped_at_their_deadline() {
    let server = ServerProcess::start(&["--default-scene", "none", "--answer-deadline-ms", "2000"]);
    let ch = connect(&server).await;
    let s = needlesim_tests::create_example_session(&ch, "paper-phantom").await;
    let get = pb::GetSessionRequest { session_id: s.session.clone().expect("a session").session_id };
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mesh = sessions.get_mesh(with_token(get.clone(), &s.observer_token)).await.expect("GetMesh").into_inner();
    let answer_bytes = mesh.encoded_len() as u64;
    assert!(answer_bytes < 64 << 10, "{answer_bytes}");
    let mut send = h2_connect(&server.addr, 0).await;
    let mut held = Vec::new();
    let n = 50;
    for _ in 0..n {
        send = send.ready().await.expect("a stream");
        let mut req = grpc_request(&server.addr, "/needlesim.v1.SessionService/GetMesh");
        req.headers_mut().insert("authorization", format!("Bearer {}", s.observer_token).parse().unwrap());
        let (resp, mut body) = send.send_request(req, false).unwrap();
        body.send_data(framed(&get.encode_to_vec()), true).unwrap();
        held.push(tokio::time::timeout(Duration::from_secs(30), resp).await.expect("headers in time").expect("an answer"));
    }
    let counted = server.metric("needlesim_held_answer_bytes");
    assert!(counted >= (n * answer_bytes) as f64, "{counted} bytes counted of {n} answers of {answer_bytes}");
    let t0 = Instant::now();
    while server.metric("needlesim_held_answers_timed_out") < n as f64 {
        assert!(t0.elapsed() < Duration::from_secs(15), "{}", server.metric("needlesim_held_answers_timed_out"));
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    assert_eq!(server.metric("needlesim_held_answer_bytes"), 0.0);
    drop(held);
}

/// Issue 35, pass 4 (4): a Simulate whose client kept its connection open and never read held its
/// offline job slot for as long as it liked (the job blocked sending), so four such calls refused
/// everyone else's. A job whose client does not take its next message within
/// `--answer-deadline-ms` now stops, frees its slot and ends its stream with DEADLINE_EXCEEDED.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_unread_simulate_frees_its_offline_slot_at_the_deadline() {
    let server = ServerProcess::start(&["--default-scene", "none", "--max-offline-jobs", "1", "--answer-deadline-ms", "2000"]);
    let req = pb::SimulateRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
        ..Default::default()
    };
    let mut send = h2_connect(&server.addr, 0).await;
    let (resp, mut body) = send.send_request(grpc_request(&server.addr, "/needlesim.v1.SimulationService/Simulate"), false).unwrap();
    body.send_data(framed(&req.encode_to_vec()), true).unwrap();
    let unread = tokio::time::timeout(Duration::from_secs(30), resp).await.expect("headers in time").expect("an answer");
    let t0 = Instant::now();
    while server.metric("needlesim_offline_jobs_timed_out") < 1.0 {
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "the unread Simulate still holds its slot: {} running",
            server.metric("needlesim_offline_jobs_running")
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    assert_eq!(server.metric("needlesim_offline_jobs_running"), 0.0);
    // Another client runs its Simulate while the unread call's connection stays open.
    let ch = connect(&server).await;
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch);
    let mut stream = sim.simulate(pb::SimulateRequest { decimate: 1000, ..req }).await.expect("a slot").into_inner();
    let mut messages = 0;
    while let Some(m) = stream.message().await.expect("the simulation runs") {
        messages += 1;
        drop(m);
    }
    assert!(messages > 0);
    assert_eq!(server.metric("needlesim_offline_jobs_rejected"), 0.0);
    // (The unread stream's status, DEADLINE_EXCEEDED naming the flag, waits for its window:
    // `jobs.rs`'s unit test reads it.)
    drop(unread);
}
