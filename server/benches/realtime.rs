//! Real-time server benchmark (issue 15): a live session at 1 kHz in the real server process, its
//! clients in other processes.
//!
//! - The server: the release `needlesim-server serve` binary (Cargo builds it for this bench), in
//!   its own process, with `--spin-margin-us` passed through.
//! - The session: the shipped `paper-phantom` scene (19 × 19 nodes, 0.1 m square, rigid 0.1 m
//!   needle), created with a shared-memory device channel.
//! - The device (`--driver device`, the default): the release `needlesim-bridge` binary in its own
//!   process (`cargo build --release -p needlesim-bridge` first), replaying the scene's example
//!   motion in a loop (`server/scenes/paper-phantom.csv`: insertion 80 mm at 20 mm/s, 2 s hold,
//!   withdrawal; 10 s a cycle) through the channel, phase-aligned with the session's ticks
//!   (`--phase-lead-us`). Its pose→force latency is exact: each force names the device pose it
//!   answers. `--driver grpc` drives the session over the gRPC Control stream from this process
//!   instead (one pose a millisecond; pose→force is then the loopback round trip to the response
//!   echoing the pose's client time).
//! - The observers: N rendering observers (60 Hz, no displacement field) over gRPC from this
//!   process (not the server's).
//!
//! Per case (a fresh session each): missed deadlines, tick start lateness p50/p99/p99.9/max and
//! compute time (the session's histograms over its whole life, from GetStats and /metrics),
//! pose→force p50/p99/p99.9/max, the fan-out's wakes and timeouts, and the spin margin's cost (the
//! time the tick thread spun, as a share of one core).
//!
//! Run: `cargo build --release -p needlesim-bridge && cargo bench -p needlesim-server --bench realtime`
//! (0, 10 and 100 observers, 6 s each), or one long case:
//! `cargo bench -p needlesim-server --bench realtime -- --seconds 600 --observers 100`.
//! Options: `--seconds S`, `--observers N[,N…]`, `--driver device|grpc`, `--spin-margin-us M`,
//! `--phase-lead-us L`, `--scene NAME` (a shipped example; `cube-phantom-3d` is the 3D session on
//! the 48,000-tetrahedron cube: the bridge replays its 6-DOF example motion, or `--driver grpc`
//! drives it through the Control3 stream), `--needle flexible|bevel` (a 3D example's needle
//! replaced, the scene sent as TOML: `flexible`, the gauge's steel rod, symmetric tip; `bevel`,
//! the thin bevel-tip needle of behind-vessel-bevel-3d — 0.64 mm, EI = 5e-4 N·m², bevel force
//! ratio 0.5 —; the bridge still replays the example's motion).

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;
use tonic::metadata::MetadataValue;

fn with_token<T>(msg: T, token: &str) -> tonic::Request<T> {
    let mut r = tonic::Request::new(msg);
    r.metadata_mut().insert("authorization", MetadataValue::try_from(format!("Bearer {token}")).unwrap());
    r
}

fn pct(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

#[derive(Debug, Clone)]
struct Options {
    seconds: f64,
    observers: Vec<usize>,
    driver: String,
    spin_margin_us: Option<u64>,
    phase_lead_us: Option<u64>,
    scene: String,
    /// `flexible` or `bevel`: the 3D example's needle replaced (module docs).
    needle: Option<String>,
}

fn parse_options() -> Options {
    let mut o = Options {
        seconds: 6.0,
        observers: vec![0, 10, 100],
        driver: "device".into(),
        spin_margin_us: None,
        phase_lead_us: None,
        scene: "paper-phantom".into(),
        needle: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |name: &str| args.next().unwrap_or_else(|| panic!("{name} needs a value"));
        match a.as_str() {
            "--bench" => {}
            "--seconds" => o.seconds = value("--seconds").parse().expect("--seconds S"),
            "--observers" => {
                o.observers = value("--observers").split(',').map(|n| n.trim().parse().expect("--observers N[,N…]")).collect();
            }
            "--driver" => o.driver = value("--driver"),
            "--spin-margin-us" => o.spin_margin_us = Some(value("--spin-margin-us").parse().expect("--spin-margin-us M")),
            "--phase-lead-us" => o.phase_lead_us = Some(value("--phase-lead-us").parse().expect("--phase-lead-us L")),
            "--scene" => o.scene = value("--scene"),
            "--needle" => o.needle = Some(value("--needle")),
            other => panic!("unknown argument {other:?} (see the header of server/benches/realtime.rs)"),
        }
    }
    assert!(o.driver == "device" || o.driver == "grpc", "--driver device|grpc, not {:?}", o.driver);
    assert!(matches!(o.needle.as_deref(), None | Some("flexible" | "bevel")), "--needle flexible|bevel, not {:?}", o.needle);
    o
}

/// The session's scene: the shipped example, or with `--needle` its TOML (a 3D example's,
/// server/scenes/NAME.toml) with the `[needle]` table's model keys put in and its trajectory
/// key dropped (the bridge reads the motion itself; a TOML sent to the server names no file).
fn scene_source(opts: &Options) -> pb::SceneSource {
    let Some(needle) = opts.needle.as_deref() else {
        return pb::SceneSource { source: Some(pb::scene_source::Source::Example(opts.scene.clone())) };
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{}.toml", opts.scene));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("--needle needs a shipped 3D scene: {}: {e}", path.display()));
    assert!(text.lines().any(|l| l.trim() == "dim = 3"), "--needle applies to 3D scenes; {} is not one", path.display());
    assert!(text.lines().any(|l| l.trim() == "[needle]"), "{} has no [needle] table", path.display());
    let keys: &[&str] = match needle {
        "flexible" => &["model = \"flexible\""],
        _ => &["diameter_m = 0.00064", "model = \"flexible\"", "flexural_rigidity_nm2 = 5e-4", "bevel_force_ratio = 0.5"],
    };
    let mut out = String::new();
    for line in text.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        if key == "trajectory" || (needle == "bevel" && (key == "gauge" || key == "diameter_m")) {
            continue;
        }
        out.push_str(line);
        out.push('\n');
        if line.trim() == "[needle]" {
            for k in keys {
                out.push_str(k);
                out.push('\n');
            }
        }
    }
    pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(out)) }
}

/// The server process, killed on drop.
struct Server {
    child: Child,
    port: u16,
    dir: PathBuf,
}

impl Drop for Server {
    fn drop(&mut self) {
        // SIGTERM: the server closes its sessions (and removes their channel files).
        // SAFETY: kill(2) on the pid of a child we spawned and have not reaped.
        unsafe { libc::kill(self.child.id() as libc::pid_t, libc::SIGTERM) };
        let t0 = Instant::now();
        while t0.elapsed() < Duration::from_secs(5) {
            if let Ok(Some(_)) = self.child.try_wait() {
                let _ = std::fs::remove_dir_all(&self.dir);
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn start_server(opts: &Options) -> Server {
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let dir = std::env::temp_dir().join(format!("needlesim-bench-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_needlesim-server"));
    cmd.args(["serve", "--listen", &format!("127.0.0.1:{port}"), "--default-scene", "none", "--data-dir"])
        .arg(&dir)
        .arg("--web-dir")
        .arg(&dir);
    if let Some(m) = opts.spin_margin_us {
        cmd.args(["--spin-margin-us", &m.to_string()]);
    }
    let log = std::fs::File::create(dir.join("server.log")).unwrap();
    let child = cmd.env("RUST_LOG", "warn").stdout(Stdio::null()).stderr(log).spawn().expect("start needlesim-server");
    Server { child, port, dir }
}

/// The bridge binary beside the server binary (same profile).
fn bridge_binary() -> PathBuf {
    let server = Path::new(env!("CARGO_BIN_EXE_needlesim-server"));
    let p = server.with_file_name("needlesim-bridge");
    assert!(p.is_file(), "{} is missing: cargo build --release -p needlesim-bridge", p.display());
    p
}

/// The server's /metrics gauges of one session, by name (without the `needlesim_` prefix).
fn session_metrics(port: u16, session: &str) -> std::collections::HashMap<String, f64> {
    let mut s = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(s, "GET /metrics HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n").unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).unwrap();
    let label = format!("session=\"{session}\"");
    text.lines()
        .filter(|l| l.starts_with("needlesim_") && l.contains(&label))
        .filter_map(|l| {
            let name = l.split('{').next()?.trim_start_matches("needlesim_").to_owned();
            let value = l.rsplit(' ').next()?.parse().ok()?;
            Some((name, value))
        })
        .collect()
}

struct CaseResult {
    row: String,
    notes: Vec<String>,
}

async fn run_case(ch: tonic::transport::Channel, opts: &Options, port: u16, n_observers: usize) -> CaseResult {
    let secs = opts.seconds;
    let device = opts.driver == "device";
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let created = sessions
        .create_session(pb::CreateSessionRequest {
            scene: Some(scene_source(opts)),
            tick_rate_hz: 1000.0,
            record: false,
            device_channel: device,
        })
        .await
        .unwrap()
        .into_inner();
    let info = created.session.unwrap();
    let sid = info.session_id.clone();
    let (ctl, obs) = (created.controller_token, created.observer_token);
    let mut observers = Vec::new();
    for _ in 0..n_observers {
        let req = with_token(pb::ObserveRequest { session_id: sid.clone(), rate_hz: 60.0, include_displacements: false }, &obs);
        let ch = ch.clone();
        observers.push(tokio::spawn(async move {
            let mut s = pb::observe_service_client::ObserveServiceClient::new(ch).observe(req).await.unwrap().into_inner();
            let mut n = 0u64;
            while let Some(Ok(_)) = s.next().await {
                n += 1;
            }
            n
        }));
    }
    let mut notes = Vec::new();
    let (p2f, answered) = if device {
        let traj = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{}.csv", opts.scene));
        let mut cmd = Command::new(bridge_binary());
        cmd.arg("--channel").arg(&info.device_channel_path).args(["--device", "scripted", "--trajectory"]).arg(traj).args([
            "--loop",
            "--seconds",
            &secs.to_string(),
            "--json",
        ]);
        if let Some(l) = opts.phase_lead_us {
            cmd.args(["--phase-lead-us", &l.to_string()]);
        }
        let out = tokio::task::spawn_blocking(move || cmd.env("RUST_LOG", "warn").output().expect("run needlesim-bridge")).await.unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "the bridge failed: {}{}", stdout, String::from_utf8_lossy(&out.stderr));
        let r: serde_json::Value = serde_json::from_str(stdout.trim()).expect("the bridge's JSON report");
        let p = &r["pose_to_force_us"];
        let f = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
        notes.push(format!(
            "bridge: {} periods, {} missed, aligned {}, {} poses answered ({} within their period), {} unanswered, {} force waits timed out",
            r["periods"], r["missed_periods"], r["aligned"], r["answered_poses"], r["answered_in_period"], r["unanswered_poses"], r["waits_timed_out"]
        ));
        ([f(&p["p50"]), f(&p["p99"]), f(&p["p999"]), f(&p["max"])], format!("{} / {}", r["answered_poses"], r["unanswered_poses"]))
    } else {
        let mut lat = if info.dimension == 3 {
            grpc_drive3(ch.clone(), &sid, &ctl, secs).await
        } else {
            grpc_drive(ch.clone(), &sid, &ctl, secs).await
        };
        let n = lat.len();
        ([pct(&mut lat, 0.5), pct(&mut lat, 0.99), pct(&mut lat, 0.999), pct(&mut lat, 1.0)], format!("{n} / -"))
    };
    let st = sessions.get_stats(with_token(pb::GetSessionRequest { session_id: sid.clone() }, &obs)).await.unwrap().into_inner();
    let m = tokio::task::spawn_blocking({
        let sid = sid.clone();
        move || session_metrics(port, &sid)
    })
    .await
    .unwrap();
    sessions.close_session(with_token(pb::CloseSessionRequest { session_id: sid }, &ctl)).await.unwrap();
    let mut frames = Vec::new();
    for o in observers {
        frames.push(o.await.unwrap());
    }
    let min_frames = frames.iter().min().copied().unwrap_or(0);
    let g = |k: &str| m.get(k).copied().unwrap_or(f64::NAN);
    let spin_share = g("tick_spin_seconds") / (st.ticks as f64 * 1e-3);
    let row = format!(
        "| {} | {n_observers} | {} | {} ({:.4} %) | {:.2} | {:.2} | {:.1} | {:.0} | {:.1} | {:.1} | {:.1} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {answered} | {} | {:.0} / {:.0} | {:.1} % |",
        opts.driver,
        st.ticks,
        st.missed_deadlines,
        100.0 * st.missed_deadlines as f64 / st.ticks.max(1) as f64,
        st.lateness_p50_us,
        st.lateness_p99_us,
        st.lateness_p999_us,
        g("tick_lateness_max_seconds") * 1e6,
        st.compute_p50_us,
        st.compute_p99_us,
        st.compute_p999_us,
        st.compute_max_us,
        p2f[0],
        p2f[1],
        p2f[2],
        p2f[3],
        if n_observers == 0 { "-".to_owned() } else { min_frames.to_string() },
        g("fanout_wakes"),
        g("fanout_timeouts"),
        100.0 * spin_share,
    );
    notes.push(format!(
        "server: dropped records {}, column misses {}, superseded poses {}",
        st.dropped_records, st.column_misses, st.superseded_poses
    ));
    CaseResult { row, notes }
}

/// Drives the session over the Control stream (a pose a millisecond, the insertion of the old
/// benchmark: 40 mm over the case) and returns the pose→force latencies (µs) after the first second.
async fn grpc_drive(ch: tonic::transport::Channel, sid: &str, ctl: &str, secs: f64) -> Vec<f64> {
    let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest>(64);
    let epoch = Instant::now();
    let pose = move |t: f64| pb::Pose2 { x_m: 0.05, y_m: 0.205 - 0.04 * (t / secs).min(1.0), theta_rad: -std::f64::consts::FRAC_PI_2 };
    let msg = move |t: f64, client_time_ns: u64, seq: u64, session_id: String| pb::ControlRequest {
        session_id,
        base: Some(pose(t)),
        client_time_ns,
        seq,
        flip_bevel: false,
        take_over: false,
    };
    tx.send(msg(0.0, 1, 1, sid.to_owned())).await.unwrap();
    let responses = pb::control_service_client::ControlServiceClient::new(ch)
        .control(with_token(tokio_stream::wrappers::ReceiverStream::new(rx), ctl))
        .await
        .unwrap()
        .into_inner();
    let sender = spawn_pose_sender(tx, epoch, secs, msg);
    let latencies = pose_to_force_latencies(responses, epoch, secs).await;
    let _ = sender.await;
    latencies
}

/// [`grpc_drive`] for a 3D session (the cube): straight down its centre line through Control3,
/// 40 mm over the case from 5 mm above the top face.
async fn grpc_drive3(ch: tonic::transport::Channel, sid: &str, ctl: &str, secs: f64) -> Vec<f64> {
    let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest3>(64);
    let epoch = Instant::now();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let pose = move |t: f64| pb::Pose3 {
        position_m: Some(pb::Vec3 { x: 0.05, y: 0.05, z: 0.205 - 0.04 * (t / secs).min(1.0) }),
        orientation: Some(pb::Quaternion { w: h, x: 0.0, y: h, z: 0.0 }),
    };
    let msg = move |t: f64, client_time_ns: u64, seq: u64, session_id: String| pb::ControlRequest3 {
        session_id,
        base3: Some(pose(t)),
        client_time_ns,
        seq,
        take_over: false,
    };
    tx.send(msg(0.0, 1, 1, sid.to_owned())).await.unwrap();
    let responses = pb::control_service_client::ControlServiceClient::new(ch)
        .control3(with_token(tokio_stream::wrappers::ReceiverStream::new(rx), ctl))
        .await
        .unwrap()
        .into_inner();
    let sender = spawn_pose_sender(tx, epoch, secs, msg);
    let latencies = pose_to_force_latencies(responses, epoch, secs).await;
    let _ = sender.await;
    latencies
}

/// Sends `msg(t_s, client_time_ns, seq, "")` every millisecond (seq from 2: the stream's first
/// message, with the session id, is the caller's) until `secs` after `epoch`.
fn spawn_pose_sender<M: Send + 'static>(
    tx: tokio::sync::mpsc::Sender<M>,
    epoch: Instant,
    secs: f64,
    msg: impl Fn(f64, u64, u64, String) -> M + Send + 'static,
) -> tokio::task::JoinHandle<()> {
    tokio::spawn(async move {
        let mut interval = tokio::time::interval(Duration::from_millis(1));
        let mut seq = 1;
        while epoch.elapsed().as_secs_f64() < secs {
            interval.tick().await;
            seq += 1;
            let t = epoch.elapsed();
            if tx.send(msg(t.as_secs_f64(), t.as_nanos() as u64, seq, String::new())).await.is_err() {
                break;
            }
        }
    })
}

/// The pose→force latencies (µs) of a control stream's responses after the first second: from
/// the client time of a pose (ns since `epoch`) to the first response that echoes it.
async fn pose_to_force_latencies(mut responses: tonic::Streaming<pb::ControlResponse>, epoch: Instant, secs: f64) -> Vec<f64> {
    let mut latencies = Vec::new();
    let mut last_seen = 0;
    let warm = Duration::from_secs(1);
    let end = Instant::now() + Duration::from_secs_f64(secs);
    while let Ok(Some(Ok(r))) = tokio::time::timeout_at(end.into(), responses.next()).await {
        if r.client_time_ns != last_seen && r.client_time_ns > 1 {
            last_seen = r.client_time_ns;
            if epoch.elapsed() > warm {
                latencies.push((epoch.elapsed().as_nanos() as u64 - r.client_time_ns) as f64 / 1e3);
            }
        }
    }
    latencies
}

fn main() {
    let opts = parse_options();
    let server = start_server(&opts);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "machine: {}; load average before: {}; server process: {} (spin margin {}); clients in this process{}; scene {}; {} s per case",
        needlesim_lab::bench::machine(),
        load.split_whitespace().take(3).collect::<Vec<_>>().join(" "),
        env!("CARGO_BIN_EXE_needlesim-server"),
        opts.spin_margin_us.map_or("default".to_owned(), |m| format!("{m} µs")),
        if opts.driver == "device" { " and the bridge's" } else { "" },
        opts.needle.as_ref().map_or(opts.scene.clone(), |n| format!("{} with the {n} needle", opts.scene)),
        opts.seconds
    );
    println!();
    println!(
        "| driver | observers (60 Hz) | ticks | missed deadlines | lateness p50 µs | p99 | p99.9 | max | compute p50 µs | p99 | p99.9 | max | pose→force p50 µs | p99 | p99.9 | max | poses answered / unanswered | min frames/observer | fan-out wakes / timeouts | tick thread spinning |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().unwrap();
    let mut notes = Vec::new();
    rt.block_on(async {
        let url = format!("http://127.0.0.1:{}", server.port);
        let t0 = Instant::now();
        let ch = loop {
            match tonic::transport::Channel::from_shared(url.clone()).unwrap().connect().await {
                Ok(ch) => break ch,
                Err(e) if t0.elapsed() < Duration::from_secs(20) => {
                    let _ = e;
                    tokio::time::sleep(Duration::from_millis(50)).await;
                }
                Err(e) => panic!("the server did not come up: {e}"),
            }
        };
        for &n in &opts.observers {
            let r = run_case(ch.clone(), &opts, server.port, n).await;
            println!("{}", r.row);
            notes.push((n, r.notes));
        }
    });
    println!();
    for (n, ns) in notes {
        for note in ns {
            println!("- {n} observers: {note}");
        }
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("- load average after: {}", load.split_whitespace().take(3).collect::<Vec<_>>().join(" "));
    drop(server);
}
