//! Issue 17 (Foxglove): the real server with `--foxglove-addr` serves a live 3D session to a
//! Foxglove WebSocket client (the ws-protocol: advertise, subscribe, binary messageData): the
//! scene in Foxglove's `foxglove.SceneUpdate` schema (tissue surface, needle, contacts, targets)
//! and the force samples, as the session is driven in.
use futures_util::{SinkExt, StreamExt};
use needlesim_proto::v1 as pb;
use prost::Message as _;
use tokio_tungstenite::tungstenite::{Message, client::IntoClientRequest};

use needlesim_tests::{ServerProcess, connect, create_example_session, rss_bytes, with_token};

/// The foxglove.SceneUpdate fields the test reads (protobuf field numbers from Foxglove's
/// schemas: SceneUpdate.entities = 2; SceneEntity.id = 3, lines = 11, triangles = 12;
/// TriangleListPrimitive.indices = 5 (fixed32); LinePrimitive.points = 5; Point3.z = 3).
mod fx {
    #[derive(Clone, PartialEq, prost::Message)]
    pub struct SceneUpdate {
        #[prost(message, repeated, tag = "2")]
        pub entities: Vec<SceneEntity>,
    }
    #[derive(Clone, PartialEq, prost::Message)]
    pub struct SceneEntity {
        #[prost(string, tag = "3")]
        pub id: String,
        #[prost(message, repeated, tag = "11")]
        pub lines: Vec<LinePrimitive>,
        #[prost(message, repeated, tag = "12")]
        pub triangles: Vec<TriangleListPrimitive>,
    }
    #[derive(Clone, PartialEq, prost::Message)]
    pub struct LinePrimitive {
        #[prost(message, repeated, tag = "5")]
        pub points: Vec<Point3>,
    }
    #[derive(Clone, PartialEq, prost::Message)]
    pub struct TriangleListPrimitive {
        #[prost(fixed32, repeated, tag = "5")]
        pub indices: Vec<u32>,
    }
    #[derive(Clone, PartialEq, prost::Message)]
    pub struct Point3 {
        #[prost(double, tag = "1")]
        pub x: f64,
        #[prost(double, tag = "2")]
        pub y: f64,
        #[prost(double, tag = "3")]
        pub z: f64,
    }
}

#[ignore = "run alone by tests/run (its last phase): a live 3D session whose compliance worker must keep up with the tip; on a CPU shared with other tests its captures are lost (see ARCHITECTURE, Live 3D under load)"]
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_17_a_foxglove_client_sees_a_live_3d_session() {
    let _turn = needlesim_tests::REALTIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none", "--foxglove-addr", "127.0.0.1:0"]);
    let port = {
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
        loop {
            let out = server.stdout.lock().unwrap().clone();
            if let Some(p) = out
                .lines()
                .find_map(|l| l.strip_prefix("foxglove on ws://127.0.0.1:"))
                .and_then(|r| r.split_whitespace().next().map(str::to_owned))
            {
                break p;
            }
            assert!(std::time::Instant::now() < deadline, "the server did not print its Foxglove port: {out}");
            tokio::time::sleep(std::time::Duration::from_millis(50)).await;
        }
    };
    let ch = connect(&server).await;
    let created = create_example_session(&ch, "cube-phantom-3d").await;
    let id = created.session.as_ref().unwrap().session_id.clone();

    let mut req = format!("ws://127.0.0.1:{port}").into_client_request().unwrap();
    req.headers_mut().insert("sec-websocket-protocol", "foxglove.sdk.v1".parse().unwrap());
    let (mut ws, _) = tokio_tungstenite::connect_async(req).await.expect("the Foxglove endpoint accepts a ws-protocol client");
    let (scene_topic, force_topic) = (format!("/needlesim/{id}/scene"), format!("/needlesim/{id}/force"));
    let mut channels = std::collections::BTreeMap::new();
    let deadline = tokio::time::Instant::now() + std::time::Duration::from_secs(30);
    while !(channels.contains_key(&scene_topic) && channels.contains_key(&force_topic)) {
        assert!(tokio::time::Instant::now() < deadline, "the session's channels were not advertised: {channels:?}");
        let Ok(Some(Ok(Message::Text(t)))) = tokio::time::timeout(std::time::Duration::from_secs(1), ws.next()).await else { continue };
        let v: serde_json::Value = serde_json::from_str(&t).unwrap();
        if v["op"] == "advertise" {
            for c in v["channels"].as_array().unwrap() {
                channels.insert(
                    c["topic"].as_str().unwrap().to_owned(),
                    (c["id"].as_u64().unwrap(), c["schemaName"].as_str().unwrap().to_owned()),
                );
            }
        }
    }
    assert_eq!(channels[&scene_topic].1, "foxglove.SceneUpdate");
    assert_eq!(channels[&force_topic].1, "needlesim.ForceSample");
    let subs = serde_json::json!({"op": "subscribe", "subscriptions": [
        {"id": 1, "channelId": channels[&scene_topic].0}, {"id": 2, "channelId": channels[&force_topic].0}]});
    ws.send(Message::Text(subs.to_string().into())).await.unwrap();

    // Record the session meanwhile: the recording must open in Foxglove too.
    let mut recordings = pb::recording_service_client::RecordingServiceClient::new(ch.clone());
    let start_rec = pb::StartRecordingRequest { session_id: id.clone(), include_displacements: true };
    recordings.start_recording(with_token(start_rec, &created.controller_token)).await.expect("StartRecording");

    // Drive the needle in (SetPose3 every 10 ms) while reading what Foxglove would show.
    let mut control = pb::control_service_client::ControlServiceClient::new(ch.clone());
    let (mut tips_z, mut force_z, mut surface_triangles) = (Vec::new(), Vec::new(), 0usize);
    let start = tokio::time::Instant::now();
    let q = pb::Quaternion { w: std::f64::consts::FRAC_1_SQRT_2, x: 0.0, y: std::f64::consts::FRAC_1_SQRT_2, z: 0.0 };
    let mut next_pose = start;
    // Until Foxglove has shown enough of the insertion, the tissue pushing back included (on a
    // loaded machine the compliance worker can lag the tip and the first capture comes later).
    let pushing = |f: &[f64]| f.iter().any(|&f| f > 0.01);
    while start.elapsed() < std::time::Duration::from_secs(20) && (tips_z.len() < 20 || force_z.len() < 50 || !pushing(&force_z)) {
        if tokio::time::Instant::now() >= next_pose {
            // 10 mm/s down from the scene's start (tip 5 mm above the top face) to 40 mm deep.
            let z = (0.205 - 0.01 * start.elapsed().as_secs_f64()).max(0.16);
            let base3 = pb::Pose3 { position_m: Some(pb::Vec3 { x: 0.05, y: 0.05, z }), orientation: Some(q) };
            let req = pb::SetPoseRequest3 { session_id: id.clone(), base3: Some(base3), client_id: "fx-test".into(), take_over: false };
            control.set_pose3(with_token(req, &created.controller_token)).await.expect("SetPose3");
            next_pose += std::time::Duration::from_millis(10);
        }
        let Ok(Some(Ok(Message::Binary(b)))) = tokio::time::timeout(std::time::Duration::from_millis(5), ws.next()).await else { continue };
        assert_eq!(b[0], 1, "messageData opcode");
        let payload = &b[13..];
        match u32::from_le_bytes(b[1..5].try_into().unwrap()) {
            1 => {
                let up = fx::SceneUpdate::decode(payload).expect("a foxglove.SceneUpdate");
                for e in &up.entities {
                    match e.id.as_str() {
                        "tissue" => surface_triangles = e.triangles[0].indices.len() / 3,
                        "needle" => tips_z.push(e.lines[0].points.last().unwrap().z),
                        _ => {}
                    }
                }
            }
            2 => {
                let v: serde_json::Value = serde_json::from_slice(payload).expect("force JSON");
                force_z.push(v["force_n"]["z"].as_f64().unwrap());
            }
            other => panic!("unknown subscription {other}"),
        }
    }
    // The 21³ cube's surface: 6 faces × 20² squares × 2 triangles.
    assert_eq!(surface_triangles, 6 * 400 * 2, "the tissue entity is not the cube's surface");
    assert!(tips_z.len() >= 20 && force_z.len() >= 50, "too few messages: {} scenes, {} forces", tips_z.len(), force_z.len());
    assert!(tips_z.last().unwrap() < &(tips_z[0] - 0.005), "the needle did not move down in the scene: {tips_z:?}");
    assert!(pushing(&force_z), "no upward tissue force on the needle while inserting: {force_z:?}");

    // The recording of the 3D session, read by the Python `mcap` package (tests/mcap_check.py):
    // Foxglove's scene schema with the cube's entities, and the force samples.
    let stop = pb::StopRecordingRequest { session_id: id.clone() };
    let info = recordings.stop_recording(with_token(stop, &created.controller_token)).await.expect("StopRecording").into_inner();
    let file = server.data_dir.join("recordings").join(&info.name);
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(20);
    let check = loop {
        let out = needlesim_tests::run(
            std::process::Command::new(needlesim_tests::python()).arg(needlesim_tests::repo_root().join("tests/mcap_check.py")).arg(&file),
        );
        let (o, e) = needlesim_tests::text(&out);
        if out.status.success() {
            break serde_json::from_str::<serde_json::Value>(o.trim())
                .unwrap_or_else(|err| panic!("mcap_check.py printed no JSON ({err}):\n{o}\n{e}"));
        }
        assert!(std::time::Instant::now() < deadline, "the recording {} did not become readable: {o}\n{e}", file.display());
        tokio::time::sleep(std::time::Duration::from_millis(200)).await;
    };
    let fox = &check["foxglove"];
    assert!(check["schema_names"].as_array().unwrap().iter().any(|n| n == "foxglove.SceneUpdate"), "{check}");
    assert_eq!(fox["scene_entities"], serde_json::json!(["contacts", "needle", "targets", "tissue"]), "{check}");
    assert!(fox["scene"].as_u64().unwrap() >= 10 && fox["force"].as_u64().unwrap() >= 100, "too few Foxglove messages recorded: {check}");
    // For the page's playback: the cube's surface once, and (asked for) the surface's
    // displacements in the frames 10 times a second, a displacement per surface node.
    let surface = pb::session_service_client::SessionServiceClient::new(ch.clone())
        .get_surface(with_token(pb::GetSessionRequest { session_id: id.clone() }, &created.controller_token))
        .await
        .expect("GetSurface")
        .into_inner();
    let tissue = &check["tissue"];
    assert_eq!(tissue["schemas"], serde_json::json!(["needlesim.v1.Surface"]), "{check}");
    assert_eq!(tissue["count"], 1, "the surface once: {check}");
    assert_eq!(tissue["nodes"].as_u64(), Some(surface.node_ids.len() as u64), "{check}");
    assert_eq!(tissue["triangles"].as_u64(), Some(6 * 400 * 2), "{check}");
    let seconds = check["messages"].as_f64().unwrap() / 1000.0;
    let with_field = check["displacement_frames"].as_f64().unwrap();
    // At most 10 a second; fewer when the field's thread (low priority) lags on a busy machine.
    assert!(with_field >= 2.0 && with_field <= 10.0 * seconds + 2.0, "fields in the frames, at most 10 a second over {seconds} s: {check}");
    assert_eq!(check["displacement_lengths"], serde_json::json!([3 * surface.node_ids.len()]), "{check}");
}

/// The Foxglove port a server printed (`foxglove on ws://127.0.0.1:PORT`).
async fn foxglove_port(server: &ServerProcess) -> u16 {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
    loop {
        let out = server.stdout.lock().unwrap().clone();
        if let Some(p) =
            out.lines().find_map(|l| l.strip_prefix("foxglove on ws://127.0.0.1:")).and_then(|r| r.split_whitespace().next()?.parse().ok())
        {
            return p;
        }
        assert!(std::time::Instant::now() < deadline, "the server did not print its Foxglove port: {out}");
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
}

/// The value of the unlabelled metric `needlesim_{name}`.
fn gauge(metrics: &str, name: &str) -> f64 {
    let prefix = format!("needlesim_{name} ");
    metrics
        .lines()
        .find_map(|l| l.strip_prefix(prefix.as_str()))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no needlesim_{name} in /metrics:\n{metrics}"))
}

/// The sum of `needlesim_{name}{…}` over its labels.
fn gauge_sum(metrics: &str, name: &str) -> f64 {
    let prefix = format!("needlesim_{name}{{");
    metrics.lines().filter(|l| l.starts_with(&prefix)).filter_map(|l| l.rsplit(' ').next()?.parse::<f64>().ok()).sum()
}

type Ws = tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

/// A Foxglove WebSocket client on `port` (its socket's receive buffer `rcvbuf` bytes when given),
/// subscribed to every channel advertised within 30 s of a session's two: the subscription ids
/// 1, 2, … in the order advertised.
async fn subscribed_client(port: u16, rcvbuf: Option<u32>) -> Ws {
    let sock = tokio::net::TcpSocket::new_v4().unwrap();
    if let Some(n) = rcvbuf {
        sock.set_recv_buffer_size(n).unwrap();
    }
    let tcp = sock.connect(([127, 0, 0, 1], port).into()).await.expect("connect to the Foxglove port");
    let mut req = format!("ws://127.0.0.1:{port}").into_client_request().unwrap();
    req.headers_mut().insert("sec-websocket-protocol", "foxglove.sdk.v1".parse().unwrap());
    let (mut ws, _) = tokio_tungstenite::client_async(req, tokio_tungstenite::MaybeTlsStream::Plain(tcp))
        .await
        .expect("the Foxglove endpoint accepts a ws-protocol client");
    let mut channels = Vec::new();
    let deadline = tokio::time::Instant::now() + std::time::Duration::from_secs(30);
    while channels.len() < 2 {
        assert!(tokio::time::Instant::now() < deadline, "no session's channels were advertised");
        let Ok(Some(Ok(Message::Text(t)))) = tokio::time::timeout(std::time::Duration::from_secs(1), ws.next()).await else { continue };
        let v: serde_json::Value = serde_json::from_str(&t).unwrap();
        if v["op"] == "advertise" {
            channels.extend(v["channels"].as_array().unwrap().iter().map(|c| c["id"].as_u64().unwrap()));
        }
    }
    let subs: Vec<_> = channels.iter().enumerate().map(|(i, c)| serde_json::json!({"id": i + 1, "channelId": c})).collect();
    ws.send(Message::Text(serde_json::json!({"op": "subscribe", "subscriptions": subs}).to_string().into())).await.unwrap();
    ws
}

/// Issue 35: Foxglove clients that subscribe to a live session and never read cost the server at
/// most the latest scene and a few force samples each — older messages are dropped and counted —
/// not an ever-growing backlog (19 MB a client before), and the session keeps ticking.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_foxglove_clients_that_never_read_hold_only_the_latest_messages() {
    let _turn = needlesim_tests::REALTIME.lock().await;
    // The default session: the paper phantom, live at 1 kHz.
    let server = ServerProcess::start(&["--foxglove-addr", "127.0.0.1:0"]);
    let port = foxglove_port(&server).await;
    const CLIENTS: usize = 12;
    let mut idle = Vec::new();
    for _ in 0..CLIENTS {
        idle.push(subscribed_client(port, Some(4096)).await);
    }
    let rss_before = rss_bytes(server.child.id());
    // Until the server has dropped plenty for them (their sockets are full): far more than one
    // client's bound of messages each.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    let page = loop {
        let page = server.metrics();
        if gauge(&page, "foxglove_dropped_messages") > (CLIENTS * 100) as f64 {
            break page;
        }
        assert!(std::time::Instant::now() < deadline, "no messages dropped for the clients that do not read:\n{page}");
        tokio::time::sleep(std::time::Duration::from_millis(200)).await;
    };
    assert_eq!(gauge(&page, "foxglove_clients"), CLIENTS as f64, "{page}");
    // The bound: the latest scene and 16 force samples per client (needlesim_foxglove's
    // SCENE_KEEP and FORCE_KEEP).
    let queued = gauge(&page, "foxglove_queued_messages_max");
    assert!(queued <= 17.0, "{queued} messages wait for one client");
    let rss_after = rss_bytes(server.child.id());
    let growth_mb = (rss_after as f64 - rss_before as f64) / 1e6;
    eprintln!("RSS {:.1} MB → {:.1} MB with {CLIENTS} clients not reading", rss_before as f64 / 1e6, rss_after as f64 / 1e6);
    // Loose: a 2D scene is tens of kB, so the bound is well under a MB a client.
    assert!(growth_mb < 100.0, "the server grew by {growth_mb:.0} MB for {CLIENTS} clients that do not read");
    // The session ticks on.
    let ticks = gauge_sum(&page, "ticks");
    tokio::time::sleep(std::time::Duration::from_millis(500)).await;
    let later = gauge_sum(&server.metrics(), "ticks");
    assert!(later > ticks + 100.0, "the session stopped ticking: {ticks} → {later}");
    // A client that reads still gets the session's scene and force.
    let mut ws = subscribed_client(port, None).await;
    let mut seen = std::collections::BTreeSet::new();
    let deadline = tokio::time::Instant::now() + std::time::Duration::from_secs(30);
    while seen.len() < 2 {
        assert!(tokio::time::Instant::now() < deadline, "the reading client got only subscriptions {seen:?}");
        let Ok(Some(Ok(Message::Binary(b)))) = tokio::time::timeout(std::time::Duration::from_secs(1), ws.next()).await else { continue };
        assert_eq!(b[0], 1, "messageData opcode");
        seen.insert(u32::from_le_bytes(b[1..5].try_into().unwrap()));
    }
    drop(idle);
}

/// Whether the peer closed `s` (EOF or reset) within `limit`.
fn closed_within(s: &mut std::net::TcpStream, limit: std::time::Duration) -> Result<(), String> {
    use std::io::Read;
    s.set_read_timeout(Some(limit)).unwrap();
    let mut buf = [0u8; 1024];
    loop {
        match s.read(&mut buf) {
            Ok(0) => return Ok(()),
            Ok(_) => continue, // an HTTP error answer, then the close
            Err(e) if e.kind() == std::io::ErrorKind::ConnectionReset => return Ok(()),
            Err(e) => return Err(format!("still open after {limit:?}: {e}")),
        }
    }
}

/// Issue 35: connections to the Foxglove port that never complete the WebSocket handshake (none
/// sent, or a request dribbled byte by byte) are closed within a few seconds, connections over
/// `--foxglove-max-clients` are closed at once, and a Foxglove client connects afterwards.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_foxglove_connections_without_a_handshake_are_closed_and_bounded() {
    use std::io::Write;
    let server = ServerProcess::start(&["--default-scene", "none", "--foxglove-addr", "127.0.0.1:0", "--foxglove-max-clients", "4"]);
    let port = foxglove_port(&server).await;
    let mut idle: Vec<std::net::TcpStream> = (0..4).map(|_| std::net::TcpStream::connect(("127.0.0.1", port)).unwrap()).collect();
    idle[0].write_all(b"GET / HTTP/1.1\r\nHost: x\r\n").unwrap();
    // Over the bound: closed at once.
    let mut over = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    closed_within(&mut over, std::time::Duration::from_secs(3)).expect("a connection over --foxglove-max-clients");
    // The idle ones, within the handshake's few seconds (one keeps sending a header line a
    // second meanwhile).
    let dribble = {
        let mut s = idle[0].try_clone().unwrap();
        std::thread::spawn(move || {
            for i in 0..30 {
                std::thread::sleep(std::time::Duration::from_secs(1));
                if s.write_all(format!("X-Slow-{i}: 1\r\n").as_bytes()).is_err() {
                    return;
                }
            }
        })
    };
    for (i, s) in idle.iter_mut().enumerate() {
        closed_within(s, std::time::Duration::from_secs(20)).unwrap_or_else(|e| panic!("connection {i} without a handshake: {e}"));
    }
    dribble.join().unwrap();
    // Counted (the counters follow the close by a moment).
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    let page = loop {
        let page = server.metrics();
        if gauge(&page, "foxglove_failed_handshakes") >= 4.0 && gauge(&page, "foxglove_connections") == 0.0 {
            break page;
        }
        assert!(std::time::Instant::now() < deadline, "{page}");
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    };
    assert!(gauge(&page, "foxglove_refused_connections") >= 1.0, "{page}");
    assert_eq!(gauge(&page, "foxglove_failed_handshakes"), 4.0, "{page}");
    // A Foxglove client still connects and is greeted.
    let mut req = format!("ws://127.0.0.1:{port}").into_client_request().unwrap();
    req.headers_mut().insert("sec-websocket-protocol", "foxglove.sdk.v1".parse().unwrap());
    let (mut ws, _) = tokio_tungstenite::connect_async(req).await.expect("a Foxglove client connects after the idle ones went");
    let Ok(Some(Ok(Message::Text(t)))) = tokio::time::timeout(std::time::Duration::from_secs(10), ws.next()).await else {
        panic!("no serverInfo")
    };
    assert!(t.contains("\"serverInfo\""), "{t}");
}
