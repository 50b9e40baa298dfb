//! Issue 17 (item 2, end to end): the real `needlesim-bridge` process against the real server
//! process on a live 3D session (the shipped 48,000-tetrahedron `cube-phantom-3d`, 1 kHz) — the
//! scripted, virtual-operator and 6-DOF C plug-in devices through the session's shared-memory
//! channel; a SIGKILLed server (the rendered force and torque go to exactly zero within the
//! watchdog time, measured); a SIGKILLed bridge (the session ticks on, holds the needle where it
//! was, and a new bridge re-attaches and drives); and the remote bridge over the `Control3` stream
//! with 40 ms of injected round trip, whose local linear model (the 6 × 6 wrench stiffness) keeps a
//! light virtual hand still where rendering the last (40 ms stale) force makes it oscillate.
//! The 2D counterparts are `bridge_e2e.rs` and `device-bridge/tests/remote.rs`.
//!
//! The remote test is `#[ignore]`d by default: it judges a 40 ms round trip, and on a loaded 2-core
//! machine the server's I/O threads answer much later (it then fails on that precondition, named).
//!
//! Run with `--nocapture` to see the figures (latencies, missed periods, time to zero force,
//! oscillation amplitudes); the tests assert counts, exact zeros and ratios, not speed.

use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME as ONE_AT_A_TIME, ServerProcess, TempDir, bin, connect, repo_root, with_token};
use tonic::transport::Channel;

// The 2D end-to-end tests' session and bridge helpers serve here too.
use crate::bridge_e2e::{
    RemoveOnDrop, Session, check_bridge_outlived_its_server, check_session_ticked, frame, get_session, get_stats, num, spawn_bridge,
    wait_until_inserted, watch,
};

/// The cube's needle points straight down (−z): a quarter turn about +y (its TOML's `base_quat`).
const DOWN: [f64; 4] = [std::f64::consts::FRAC_1_SQRT_2, 0.0, std::f64::consts::FRAC_1_SQRT_2, 0.0];
/// The base's x and y: above the centre of the 0.1 m cube's top face (z = 0.1).
const XY: [f64; 2] = [0.05, 0.05];
/// The base's z with the tip 1 mm above the top face (the needle is 0.1 m long).
const Z_ABOVE: f64 = 0.201;
/// How long the scripted and virtual devices rest with the tip just above the tissue before they
/// insert (3 mm/s). A 3D session's worker computes the compliance of the nodes ahead of the tip
/// while it rests; a capture whose nodes are not cached yet waits for them (`column_deferrals`),
/// and on this loaded 2-core machine a needle pushed in at once, or fast, outran the worker and
/// passed through the surface without capturing it (measured: no contact over 25 mm at 3.5 mm/s
/// from a standing start; with this rest, contact from the surface on).
const REST_S: f64 = 3.0;

/// A `cube-phantom-3d` session at 1 kHz, with a device channel if `device_channel`.
async fn create_cube_session(ch: &Channel, device_channel: bool) -> Session {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let created = c
        .create_session(pb::CreateSessionRequest {
            scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("cube-phantom-3d".into())) }),
            tick_rate_hz: 1000.0,
            record: false,
            device_channel,
        })
        .await
        .expect("create a cube-phantom-3d session")
        .into_inner();
    let info = created.session.expect("the response carries the session");
    assert_eq!(info.dimension, 3, "cube-phantom-3d makes a 3D session: {info:?}");
    let channel_path = PathBuf::from(&info.device_channel_path);
    if device_channel {
        assert!(channel_path.is_file(), "the channel file {} does not exist", channel_path.display());
        assert!(!info.device_stale, "a fresh session's device is not stale before any bridge attached: {info:?}");
    }
    Session { id: info.session_id, controller_token: created.controller_token, observer_token: created.observer_token, channel_path }
}

/// A frame's 3D base pose: (position, orientation).
fn base3(f: &pb::Frame) -> ([f64; 3], [f64; 4]) {
    let b = f.d3.as_ref().and_then(|d| d.base.as_ref()).unwrap_or_else(|| panic!("a 3D frame carries d3.base: tick {}", f.tick));
    let (p, q) = (b.position_m.as_ref().expect("base position"), b.orientation.as_ref().expect("base orientation"));
    ([p.x, p.y, p.z], [q.w, q.x, q.y, q.z])
}

/// The angle (rad) between two orientations.
fn angle_between(a: [f64; 4], b: [f64; 4]) -> f64 {
    let dot: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
    2.0 * dot.abs().min(1.0).acos()
}

/// A 3D trajectory CSV of (t, z) knots at the cube's centre line, pointing down.
fn trajectory3(dir: &TempDir, name: &str, knots: &[(f64, f64)]) -> PathBuf {
    let mut text = String::from("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n");
    for (t, z) in knots {
        text.push_str(&format!("{t},{},{},{z},{},{},{},{}\n", XY[0], XY[1], DOWN[0], DOWN[1], DOWN[2], DOWN[3]));
    }
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The 6-DOF example C plug-in (ABI 2), compiled with the system `cc` as `bridge_e2e.rs` compiles the 2D one.
fn example_plugin6(dir: &TempDir) -> PathBuf {
    let root = repo_root().join("device-bridge");
    let out = dir.join("libexample_device6.so");
    let status = std::process::Command::new("cc")
        .args(["-shared", "-fPIC", "-O1", "-Wall", "-Werror", "-I"])
        .arg(root.join("include"))
        .arg("-o")
        .arg(&out)
        .arg(root.join("examples/plugin/example_device6.c"))
        .arg("-lm")
        .status()
        .expect("running cc");
    assert!(status.success(), "compiling the 6-DOF example plug-in failed");
    out
}

/// The plug-in's configuration: from `z0`, moving down at `vz_m_s` (negative), pointing down
/// (a quarter turn about +y), recording its last wrench to `record` if given.
fn plugin_config(z0: f64, vz_m_s: f64, record: Option<&Path>) -> String {
    let mut c = format!("x0={} y0={} z0={z0} vz={vz_m_s} ax=0 ay=1 az=0 th0={} om=0", XY[0], XY[1], std::f64::consts::FRAC_PI_2);
    if let Some(r) = record {
        c.push_str(&format!(" record={}", r.display()));
    }
    c
}

/// Waits for a bridge to exit; returns (exit code, the JSON report, stderr).
async fn finish_bridge(child: tokio::process::Child) -> (Option<i32>, serde_json::Value, String) {
    let out = tokio::time::timeout(Duration::from_secs(90), child.wait_with_output())
        .await
        .expect("the bridge exits")
        .expect("waiting for the bridge");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let json = serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("the report is not JSON ({e}): {stdout:?}; stderr: {stderr}"));
    (out.status.code(), json, stderr)
}

fn nums(json: &serde_json::Value, key: &str) -> Vec<f64> {
    json[key]
        .as_array()
        .unwrap_or_else(|| panic!("{key} is not an array in {json}"))
        .iter()
        .map(|v| v.as_f64().unwrap_or_else(|| panic!("{key} holds a non-number in {json}")))
        .collect()
}

/// One row of the bridge's 6-DOF `--trace` CSV (a 3D session).
struct TraceRow {
    t_s: f64,
    position_m: [f64; 3],
    fresh: bool,
    server: [f64; 6],
    wrench: [f64; 6],
    gain: f64,
}

fn read_trace3(path: &Path) -> Vec<TraceRow> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some(
            "t_s,counter,x_m,y_m,z_m,qw,qx,qy,qz,fresh,tick,server_fx_n,server_fy_n,server_fz_n,server_tx_nm,server_ty_nm,server_tz_nm,\
             fx_n,fy_n,fz_n,tx_nm,ty_nm,tz_nm,gain"
        ),
        "a 3D session's trace has the 6-DOF columns"
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or_else(|_| panic!("bad trace row {l}"))).collect();
            assert_eq!(v.len(), 24, "bad trace row {l}");
            TraceRow {
                t_s: v[0],
                position_m: [v[2], v[3], v[4]],
                fresh: v[9] == 1.0,
                server: std::array::from_fn(|i| v[11 + i]),
                wrench: std::array::from_fn(|i| v[17 + i]),
                gain: v[23],
            }
        })
        .collect()
}

/// The 6-DOF plug-in's `record=` file: the last wrench it was sent and its number of writes.
fn read_record6(path: &Path) -> ([f64; 6], u64) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("the plug-in wrote no record at {}: {e}", path.display()));
    let v: Vec<f64> = text.split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(v.len(), 7, "bad record {text:?}");
    (std::array::from_fn(|i| v[i]), v[6] as u64)
}

fn norm3(v: &[f64]) -> f64 {
    v.iter().take(3).map(|x| x * x).sum::<f64>().sqrt()
}

/// How long each backend runs.
const BACKEND_SECONDS: f64 = 15.0;

/// Runs one backend for [`BACKEND_SECONDS`] at 1 kHz against a fresh 3D session and checks the run, the insertion
/// and the wrench the device was given; returns the trace.
async fn run_backend(ch: &Channel, dir: &TempDir, name: &str, args: &[&str]) -> Vec<TraceRow> {
    let s = create_cube_session(ch, true).await;
    let seconds = BACKEND_SECONDS;
    let trace = dir.join(&format!("trace-{name}.csv"));
    let (stop_tx, stop_rx) = tokio::sync::oneshot::channel();
    let watcher = watch(ch, &s, stop_rx);
    let stats_before = get_stats(ch, &s).await;
    let ticks_before = stats_before.ticks;
    let mut full = args.to_vec();
    let secs = seconds.to_string();
    full.extend_from_slice(&["--seconds", &secs, "--trace", trace.to_str().unwrap()]);
    let bridge = spawn_bridge(&s.channel_path, &full);
    let (code, report, stderr) = finish_bridge(bridge).await;
    let _ = stop_tx.send(());
    let frames = watcher.await.unwrap();
    let stats = get_stats(ch, &s).await;
    let info = get_session(ch, &s).await;

    let periods = num(&report, &["periods"]);
    let missed = num(&report, &["missed_periods"]);
    let fresh = num(&report, &["fresh_forces"]);
    let (p50, p99) = (num(&report, &["pose_to_force_us", "p50"]), num(&report, &["pose_to_force_us", "p99"]));
    println!(
        "[3D {name}] periods {periods}, missed {missed} ({:.3} %), fresh forces {fresh} ({:.1} %), pose→force p50 {p50:.1} µs p99 {p99:.1} µs \
         ({} answered, {} in their period, {} unanswered), watchdog periods {}, max rendered force {:.3} N; server: {} ticks, compute p99 {:.1} µs, \
         missed deadlines {}, column deferrals {}, dropped records {}",
        100.0 * missed / (periods + missed),
        100.0 * fresh / periods,
        num(&report, &["answered_poses"]),
        num(&report, &["answered_in_period"]),
        num(&report, &["unanswered_poses"]),
        num(&report, &["watchdog_periods"]),
        num(&report, &["max_rendered_force_n"]),
        stats.ticks - ticks_before,
        stats.compute_p99_us,
        stats.missed_deadlines,
        stats.column_deferrals,
        stats.dropped_records
    );

    // The run completed, as a 3D one: every scheduled period executed or counted missed.
    assert_eq!(code, Some(0), "[{name}] the bridge failed: {report} {stderr}");
    assert_eq!(report["exit"], "done", "[{name}] {report}");
    assert_eq!(num(&report, &["dimension"]), 3.0, "[{name}] the bridge did not see a 3D session: {report}");
    assert!(
        (periods + missed - seconds * 1000.0).abs() <= 1.0,
        "[{name}] periods {periods} + missed {missed} ≠ {seconds} s × 1 kHz: {report}"
    );
    // Forces reached the bridge and answered its poses (how many, how fast: printed above; issue
    // 35, item 13: budgets of missed periods and latency live in the live-session benchmark).
    assert!(fresh > 0.0 && num(&report, &["answered_poses"]) > 0.0, "[{name}] no fresh force answered a pose: {report}");
    assert!(p50.is_finite() && p50 > 0.0, "[{name}] pose→force p50 {p50} µs: {report}");
    assert_eq!(num(&report, &["pose_counter"]), periods, "[{name}] every period wrote a pose: {report}");
    assert_eq!(nums(&report, "final_pose").len(), 7, "[{name}] a 3D final pose is (x, y, z, qw, qx, qy, qz): {report}");
    let k = nums(&report, "stiffness");
    assert_eq!(k.len(), 36, "[{name}] a 3D session's stiffness is the 6 × 6: {report}");
    // The tissue holds the inserted needle: restoring (negative) axial and lateral stiffness.
    println!(
        "[3D {name}] last stiffness: K_xx {:.1}, K_yy {:.1}, K_zz {:.1} N/m; K_θxθx {:.4}, K_θyθy {:.4} N·m/rad",
        k[0], k[7], k[14], k[21], k[28]
    );
    assert!(
        k[0] < 0.0 && k[7] < 0.0,
        "[{name}] the lateral stiffness at the end is not restoring: {k:?} (session faulted: {} {:?}, column deferrals {})",
        stats.faulted,
        stats.fault,
        stats.column_deferrals
    );
    // Axially: restoring for a needle held still at the end (its contacts stick); the plug-in still
    // pushes in at the end, and contacts that slip (kinetic friction) carry no axial stiffness, so
    // whether its last force came from a sticking or a slipping tick is timing (it was -0.0 N/m,
    // and once not below 0): never destabilising is what holds.
    if name == "plugin" {
        assert!(k[14] <= 1e-9, "[{name}] the axial stiffness at the end is destabilising: {k:?}");
    } else {
        assert!(k[14] < 0.0, "[{name}] the axial stiffness at the end is not restoring: {k:?}");
    }
    // The session went on ticking and dropped nothing.
    check_session_ticked(name, stats.ticks - ticks_before, stats.missed_deadlines - stats_before.missed_deadlines, seconds);
    assert_eq!(stats.dropped_records, 0, "[{name}] {stats:?}");
    assert_eq!(info.device_channel_path, s.channel_path.display().to_string());

    // The needle went in, driven by the device, straight down the centre line.
    let deepest = frames.iter().map(|f| f.inserted_length_m).fold(0.0, f64::max);
    assert!(deepest > 0.010, "[{name}] the needle went in only {deepest} m ({} frames)", frames.len());
    let end = frames.iter().rev().find(|f| f.inserted_length_m > 0.010).expect("a frame with the needle in");
    let (p, q) = base3(end);
    let axial_max = frames.iter().filter_map(|f| f.d3.as_ref()).map(|d| d.axial_force_n).fold(f64::NEG_INFINITY, f64::max);
    println!(
        "[3D {name}] last frame: inserted {:.4} m, base {p:?} {q:?}, largest axial resistance {axial_max:.3} N",
        end.inserted_length_m
    );
    assert!((p[0] - XY[0]).abs() < 0.002 && (p[1] - XY[1]).abs() < 0.002, "[{name}] the base went astray: {p:?}");
    assert!(angle_between(q, DOWN) < 0.05, "[{name}] the needle tilted: {q:?}");
    // The tissue resisted the insertion (the axial force is positive while pushing in).
    assert!(axial_max > 0.05, "[{name}] the tissue never resisted: axial force at most {axial_max} N");

    // The device was given the tissue's wrench: up (+z) against the insertion, from the server's.
    let rows = read_trace3(&trace);
    assert_eq!(rows.len() as f64, periods, "[{name}] one trace row per period");
    let up = rows.iter().filter(|r| r.fresh && r.server[2] > 0.05).collect::<Vec<_>>();
    println!("[3D {name}] {} periods with a fresh server force > 0.05 N up", up.len());
    assert!(!up.is_empty(), "[{name}] no period with a server force > 0.05 N up");
    // With the needle in and the server force up, the rendered force is up too, and close to it
    // (the coupling in series scales the model force by K_c / (K_c − K) ≈ 0.9 for this tissue).
    let agree = up.iter().filter(|r| r.wrench[2] > 0.0 && (r.wrench[2] - r.server[2]).abs() <= 0.3 * r.server[2]).count();
    assert!(
        agree as f64 > 0.9 * up.len() as f64,
        "[{name}] the rendered z force follows the server's in only {agree} of {} periods",
        up.len()
    );
    assert!(num(&report, &["max_rendered_force_n"]) > 0.05, "[{name}] no force was rendered: {report}");
    rows
}

// A live 3D session whose column worker must keep up with the needle's tip: beside other tests on
// the two cores its captures can be lost (issue 35, 13: 5 of 10 runs at load 14 never gripped), so
// it runs in tests/run's alone phase.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "a live 3D session: run alone (tests/run's alone phase)"]
async fn scripted_virtual_and_plugin_devices_insert_into_a_3d_session_at_1khz() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let dir = TempDir::new("bridge3d");
    let mut server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    // A rest with the tip 1 mm above the top face, 30 mm down over 10 s, then held.
    let traj =
        trajectory3(&dir, "insert.csv", &[(0.0, Z_ABOVE), (REST_S, Z_ABOVE), (REST_S + 10.0, Z_ABOVE - 0.030), (100.0, Z_ABOVE - 0.030)]);
    let traj = traj.to_str().unwrap();
    run_backend(&ch, &dir, "scripted", &["--device", "scripted", "--trajectory", traj]).await;
    run_backend(&ch, &dir, "virtual", &["--device", "virtual", "--trajectory", traj]).await;
    // The 6-DOF plug-in: from the tip 10 mm above the top face, 3 mm/s down (at the surface after
    // 3.7 s, 34 mm in at the end), pointing down; it records what it was sent.
    let lib = example_plugin6(&dir);
    let record = dir.join("record-plugin.txt");
    let config = plugin_config(Z_ABOVE + 0.009, -0.003, Some(&record));
    let rows =
        run_backend(&ch, &dir, "plugin", &["--device", "plugin", "--plugin", lib.to_str().unwrap(), "--plugin-config", &config]).await;
    // The plug-in was sent every period's wrench and a final zero.
    let (last, writes) = read_record6(&record);
    assert_eq!(last, [0.0; 6], "the plug-in was left pushing");
    assert_eq!(writes, rows.len() as u64 + 1, "one write per period plus the final zero");
    assert!(server.child.try_wait().unwrap().is_none(), "the server died: {}", server.stderr.lock().unwrap());
}

/// Issue 35 (item 7): a SIGKILLed server (no closing state: its channel file stays) with a bridge
/// mid-insertion into a 3D session — the scripted device (the case found: the bridge ramped its
/// wrench to zero, then ran on to the end of `--seconds`, exited 0 and left the `/dev/shm` file) and
/// the 6-DOF plug-in, each on a server of its own. Now, long before its `--seconds`, the bridge
/// notices the death: the rendered force and torque ramp monotonically to exactly zero after the
/// watchdog's periods, it removes the file and exits with status 1 naming the cause, and the
/// plug-in device is left at zero.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_sigkilled_server_ends_each_3d_bridge_at_zero_force_and_removes_its_channel() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let dir = TempDir::new("bridge3d-kill-server");
    let lib = example_plugin6(&dir);
    let record = dir.join("record.txt");
    // A rest with the tip 1 mm above the top face, then 30 mm down over 10 s, then held.
    let traj =
        trajectory3(&dir, "insert.csv", &[(0.0, Z_ABOVE), (REST_S, Z_ABOVE), (REST_S + 10.0, Z_ABOVE - 0.030), (1000.0, Z_ABOVE - 0.030)]);
    // From the tip 10 mm above the top face, 4 mm/s down.
    let config = plugin_config(Z_ABOVE + 0.009, -0.004, Some(&record));
    let devices: [(&str, Vec<&str>); 2] = [
        ("scripted", vec!["--device", "scripted", "--trajectory", traj.to_str().unwrap()]),
        ("plugin", vec!["--device", "plugin", "--plugin", lib.to_str().unwrap(), "--plugin-config", &config]),
    ];
    let (watchdog, ramp_ms) = (10u64, 50.0);
    for (name, args) in devices {
        let mut server = ServerProcess::start(&["--default-scene", "none"]);
        let ch = connect(&server).await;
        let s = create_cube_session(&ch, true).await;
        let _chan_file = RemoveOnDrop(s.channel_path.clone());
        let trace = dir.join(&format!("trace-{name}.csv"));
        let mut full = args.clone();
        let (w, r) = (watchdog.to_string(), ramp_ms.to_string());
        // Far longer than the run takes: it ends when the bridge notices the death, not at 600 s.
        full.extend_from_slice(&["--seconds", "600", "--watchdog-periods", &w, "--ramp-ms", &r, "--trace", trace.to_str().unwrap()]);
        let bridge = spawn_bridge(&s.channel_path, &full);
        wait_until_inserted(&ch, &s, 0.005).await;
        let server_pid = server.child.id();
        server.child.kill().expect("SIGKILL the server"); // std's kill is SIGKILL: no closing state, the file stays
        server.child.wait().unwrap();
        let out = finish_bridge(bridge).await;
        assert_eq!(num(&out.1, &["dimension"]), 3.0, "[{name}] {}", out.1);
        let rows = read_trace3(&trace);
        let row = |r: &TraceRow| (r.t_s, r.fresh, norm3(&r.wrench).max(norm3(&r.wrench[3..])), r.gain);
        check_bridge_outlived_its_server(name, &out, server_pid, &s.channel_path, &rows, row, (watchdog, ramp_ms));
        if name == "plugin" {
            // The plug-in pushed and twisted before the death (the zeros after it prove something).
            let last_fresh = rows.iter().rev().find(|r| r.fresh).expect("fresh forces").t_s;
            let torque_before = rows.iter().filter(|r| r.t_s > last_fresh - 0.1 && r.t_s <= last_fresh).map(|r| norm3(&r.wrench[3..]));
            assert!(torque_before.fold(0.0, f64::max) > 0.0, "no torque was rendered before the kill");
            let (last, writes) = read_record6(&record);
            assert_eq!(last, [0.0; 6], "the plug-in was left pushing");
            assert_eq!(writes, rows.len() as u64 + 1, "one write per period plus the final zero");
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_sigkilled_bridge_leaves_the_3d_session_intact_and_reattachable() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let dir = TempDir::new("bridge3d-kill-bridge");
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let s = create_cube_session(&ch, true).await;
    // A rest, in 30 mm over 8 s, then held.
    let insert =
        trajectory3(&dir, "insert.csv", &[(0.0, Z_ABOVE), (REST_S, Z_ABOVE), (REST_S + 8.0, Z_ABOVE - 0.030), (100.0, Z_ABOVE - 0.030)]);
    let mut first = spawn_bridge(&s.channel_path, &["--device", "scripted", "--trajectory", insert.to_str().unwrap(), "--seconds", "60"]);
    tokio::time::sleep(Duration::from_secs_f64(REST_S + 8.5)).await;
    let driven = frame(&ch, &s).await;
    assert!(driven.inserted_length_m > 0.010, "the first bridge did not insert the needle: {} m", driven.inserted_length_m);
    assert!(!get_session(&ch, &s).await.device_stale, "stale while the bridge runs");
    let stats_before = get_stats(&ch, &s).await;

    first.start_kill().expect("SIGKILL the bridge");
    let killed = Instant::now();
    first.wait().await.unwrap(); // reaped: its pid no longer counts as an attached bridge
    let stale_after = loop {
        if get_session(&ch, &s).await.device_stale {
            break killed.elapsed();
        }
        // A hang guard, not a speed bound (issue 35, item 13): the time is printed.
        assert!(killed.elapsed() < Duration::from_secs(20), "device_stale not set 20 s after the bridge was killed");
        tokio::time::sleep(Duration::from_millis(5)).await;
    };
    println!("3D killed bridge: device_stale after {stale_after:?}");

    // The session keeps ticking, drops nothing, and holds the needle (6-DOF pose, depth, tip) where it was.
    // Points the tip passed while the compliance worker was behind are captured once their
    // columns arrive (late captures, which move `inserted_length_m`: on a loaded machine, after
    // the needle stopped): two frames 300 ms apart once those have landed (a hang guard of 20 s;
    // a needle that kept moving would never settle).
    let settle = Instant::now();
    let (held1, held2) = loop {
        let a = frame(&ch, &s).await;
        tokio::time::sleep(Duration::from_millis(300)).await;
        let b = frame(&ch, &s).await;
        if a.inserted_length_m == b.inserted_length_m || settle.elapsed() > Duration::from_secs(20) {
            break (a, b);
        }
    };
    let stats_after = get_stats(&ch, &s).await;
    assert!(held2.tick > held1.tick, "frames stopped ticking: {} → {}", held1.tick, held2.tick);
    assert!(stats_after.ticks > stats_before.ticks, "stats stopped ticking: {} → {}", stats_before.ticks, stats_after.ticks);
    assert_eq!(stats_after.dropped_records, 0, "{stats_after:?}");
    assert_eq!(base3(&held1), base3(&held2), "the needle moved without a device");
    assert_eq!(held1.inserted_length_m, held2.inserted_length_m);
    let tip = |f: &pb::Frame| f.d3.as_ref().and_then(|d| d.tip_m).map(|t| [t.x, t.y, t.z]).expect("d3.tip_m");
    assert_eq!(tip(&held1), tip(&held2), "the tip moved without a device");
    assert!(
        (held2.inserted_length_m - driven.inserted_length_m).abs() < 0.001,
        "{} vs {}",
        held2.inserted_length_m,
        driven.inserted_length_m
    );
    let (p_held, q_held) = base3(&held2);
    assert!((p_held[2] - (Z_ABOVE - 0.030)).abs() < 0.001, "the needle was not held where the bridge left it: {p_held:?}");
    assert!(angle_between(q_held, DOWN) < 0.01, "{q_held:?}");
    let info = get_session(&ch, &s).await;
    assert!(info.device_stale, "{info:?}");
    assert!(!info.device_channel_broken, "{info:?}");
    assert!(s.channel_path.is_file(), "the channel file went away with the bridge");

    // A new bridge on the same channel path drives again: out by 15 mm from where it was held.
    let z_held = p_held[2];
    let withdraw = trajectory3(&dir, "withdraw.csv", &[(0.0, z_held), (2.0, z_held + 0.015), (10.0, z_held + 0.015)]);
    let second = spawn_bridge(&s.channel_path, &["--device", "scripted", "--trajectory", withdraw.to_str().unwrap(), "--seconds", "3"]);
    let reattached = Instant::now();
    let fresh_again = loop {
        if !get_session(&ch, &s).await.device_stale {
            break reattached.elapsed();
        }
        assert!(reattached.elapsed() < Duration::from_secs(20), "device_stale still set 20 s after a new bridge attached");
        tokio::time::sleep(Duration::from_millis(5)).await;
    };
    println!("3D re-attached bridge: device_stale cleared after {fresh_again:?} (process start included)");
    tokio::time::sleep(Duration::from_millis(2200)).await;
    assert!(!get_session(&ch, &s).await.device_stale, "stale while the second bridge runs");
    let (code, report, stderr) = finish_bridge(second).await;
    // After the run (the session holds the needle where the bridge left it): where the trajectory
    // ends, however late the bridge started or how many periods it missed.
    let moved = frame(&ch, &s).await;
    println!("3D re-attached bridge: report {report}");
    println!("held at {:.4} m, after the second bridge {:.4} m", held2.inserted_length_m, moved.inserted_length_m);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(num(&report, &["dimension"]), 3.0, "{report}");
    assert!(num(&report, &["fresh_forces"]) > 0.0, "{report}");
    assert!(
        moved.inserted_length_m < held2.inserted_length_m - 0.010,
        "the second bridge did not move the needle: {} → {} m",
        held2.inserted_length_m,
        moved.inserted_length_m
    );
    let (p_moved, _) = base3(&moved);
    assert!((p_moved[2] - (z_held + 0.015)).abs() < 0.002, "the second bridge's pose was not applied: {p_moved:?}");
    let stats_end = get_stats(&ch, &s).await;
    assert_eq!(stats_end.dropped_records, 0, "{stats_end:?}");
}

/// The remote test's light hand with a light grip (as in `device-bridge/tests/remote.rs`): stable
/// against the tissue without delay, unstable against 40 ms old forces.
const OPERATOR: [&str; 8] = ["--operator-mass", "0.05", "--operator-damping", "0.2", "--operator-kp", "80", "--operator-kd", "1.5"];
/// The needle is first put [`REMOTE_DEPTH_M`] in by a scripted bridge on the session's channel
/// (a rest, then 20 mm over 6 s), which then exits; the remote bridge takes over from that held
/// pose: its hand rests 0.5 s, pushes 3 mm deeper over 0.5 s (the disturbance) and holds.
/// (Inserting through the remote link itself gave no contact on this loaded machine: with the
/// poses of a gRPC stream the 3D session's captures kept waiting for their compliance columns —
/// `column_deferrals` grew, the needle passed the surface untouched — where the same insertion
/// through the device channel captured from the surface on. A server-side finding, reported.)
const REMOTE_DEPTH_M: f64 = 0.020;
const REMOTE_SECONDS: f64 = 6.0;
/// When the remote hand's push ends.
const REMOTE_PUSHED_S: f64 = 1.0;

/// Oscillation over [t0, t1): the peak-to-peak of x, y and z (mm) and the RMS of the translational speed (mm/s).
#[derive(Debug, Clone, Copy)]
struct Osc {
    pp_mm: [f64; 3],
    rms_v_mm_s: f64,
}

impl Osc {
    fn pp_max_mm(&self) -> f64 {
        self.pp_mm.iter().copied().fold(0.0, f64::max)
    }
}

fn oscillation(rows: &[TraceRow], t0: f64, t1: f64) -> Osc {
    let w: Vec<&TraceRow> = rows.iter().filter(|r| r.t_s >= t0 && r.t_s < t1).collect();
    assert!(w.len() > 100, "only {} rows in [{t0}, {t1})", w.len());
    let pp = |i: usize| {
        let (lo, hi) = w.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| (lo.min(r.position_m[i]), hi.max(r.position_m[i])));
        (hi - lo) * 1e3
    };
    let v2: Vec<f64> = w
        .windows(2)
        .map(|p| {
            let dt = p[1].t_s - p[0].t_s;
            (0..3).map(|i| ((p[1].position_m[i] - p[0].position_m[i]) / dt).powi(2)).sum::<f64>()
        })
        .collect();
    Osc { pp_mm: [pp(0), pp(1), pp(2)], rms_v_mm_s: (v2.iter().sum::<f64>() / v2.len() as f64).sqrt() * 1e3 }
}

/// One remote run: a fresh 3D session, the needle put in through its channel, then driven by a
/// virtual operator through `--server` (Control3) with 40 ms of injected round trip; returns the
/// report and the trace.
async fn run_remote(ch: &Channel, server: &ServerProcess, dir: &TempDir, render: &str) -> (serde_json::Value, Vec<TraceRow>) {
    let s = create_cube_session(ch, true).await;
    let z_in = Z_ABOVE - REMOTE_DEPTH_M;
    let insert = trajectory3(dir, "remote-insert.csv", &[(0.0, Z_ABOVE), (REST_S, Z_ABOVE), (REST_S + 6.0, z_in), (100.0, z_in)]);
    let secs = (REST_S + 6.5).to_string();
    let inserter = spawn_bridge(&s.channel_path, &["--device", "scripted", "--trajectory", insert.to_str().unwrap(), "--seconds", &secs]);
    let (code, report, stderr) = finish_bridge(inserter).await;
    assert_eq!(code, Some(0), "[remote {render}] the inserting bridge failed: {report}\n{stderr}");
    let held = frame(ch, &s).await;
    assert!(held.inserted_length_m > 0.010, "[remote {render}] the needle was not put in: {} m", held.inserted_length_m);
    // The device goes stale 50 ticks after its last pose: gRPC poses drive from then on.
    let t0 = Instant::now();
    while !get_session(ch, &s).await.device_stale {
        assert!(t0.elapsed() < Duration::from_secs(2), "[remote {render}] the device did not go stale after its bridge exited");
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let z_push = z_in - 0.003;
    let traj = trajectory3(dir, "remote.csv", &[(0.0, z_in), (REMOTE_PUSHED_S - 0.5, z_in), (REMOTE_PUSHED_S, z_push), (100.0, z_push)]);
    let trace = dir.join(&format!("trace-remote-{render}.csv"));
    let child = tokio::process::Command::new(bin("needlesim-bridge"))
        .args(["--server", &server.url(), "--session", &s.id, "--token", &s.controller_token, "--device", "virtual", "--trajectory"])
        .arg(&traj)
        .args(OPERATOR)
        .args(["--inject-rtt-ms", "40", "--render", render, "--seconds", &REMOTE_SECONDS.to_string(), "--json", "--trace"])
        .arg(&trace)
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .kill_on_drop(true)
        .spawn()
        .expect("needlesim-bridge starts");
    let (code, report, stderr) = finish_bridge(child).await;
    assert_eq!(code, Some(0), "bridge --render {render} failed: {report}\n{stderr}");
    println!("[remote {render}] {report}");
    // The session took the remote poses: its base is where the operator held it.
    let f = frame(ch, &s).await;
    let (p, _) = base3(&f);
    let st = get_stats(ch, &s).await;
    println!(
        "[remote {render}] the session's base at the end {p:?}, inserted {:.4} m; server: {} ticks, missed deadlines {}, column deferrals {}, \
         clamped ticks {}, rejected poses {}, superseded poses {}",
        f.inserted_length_m, st.ticks, st.missed_deadlines, st.column_deferrals, st.clamped_ticks, st.rejected_poses, st.superseded_poses
    );
    // Closed: its 1 kHz thread would take from the next run's on this 2-core machine.
    pb::session_service_client::SessionServiceClient::new(ch.clone())
        .close_session(with_token(pb::CloseSessionRequest { session_id: s.id.clone() }, &s.controller_token))
        .await
        .expect("closing the remote run's session");
    (report, read_trace3(&trace))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "timing: judges a 40 ms round trip, which a loaded machine's server does not keep (p50 up to 1 s measured at load 12–21); run with --ignored on a quiet machine"]
async fn the_remote_3d_bridge_at_40ms_holds_still_where_the_last_force_oscillates() {
    let _turn = ONE_AT_A_TIME.lock().await;
    let dir = TempDir::new("bridge3d-remote");
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let (local_report, local) = run_remote(&ch, &server, &dir, "local-model").await;
    let (naive_report, naive) = run_remote(&ch, &server, &dir, "last-force").await;

    let settle = oscillation(&local, REMOTE_PUSHED_S + 0.5, REMOTE_PUSHED_S + 1.0);
    let late_local = oscillation(&local, REMOTE_SECONDS - 0.5, REMOTE_SECONDS);
    let hold_local = oscillation(&local, REMOTE_SECONDS - 1.0, REMOTE_SECONDS);
    let late_naive = oscillation(&naive, REMOTE_SECONDS - 0.5, REMOTE_SECONDS);
    let hold_naive = oscillation(&naive, REMOTE_SECONDS - 1.0, REMOTE_SECONDS);
    println!("[remote] local-model: just after the insertion {settle:?}, last second {hold_local:?}, last 0.5 s {late_local:?}");
    println!("[remote] last-force:  last second {hold_naive:?}, last 0.5 s {late_naive:?}");
    for (name, j) in [("local-model", &local_report), ("last-force", &naive_report)] {
        println!(
            "[remote {name}] fresh forces {}, watchdog periods {}, limited periods {}, max rendered force {:.3} N, round trip p50 {:.1} ms p99 {:.1} ms",
            num(j, &["fresh_forces"]),
            num(j, &["watchdog_periods"]),
            num(j, &["limited_periods"]),
            num(j, &["max_rendered_force_n"]),
            num(j, &["pose_to_force_us", "p50"]) / 1e3,
            num(j, &["pose_to_force_us", "p99"]) / 1e3
        );
    }
    for (name, j, rows) in [("local-model", &local_report, &local), ("last-force", &naive_report, &naive)] {
        assert_eq!(j["link"], "remote", "{j}");
        assert_eq!(j["render"], name, "{j}");
        assert_eq!(num(j, &["dimension"]), 3.0, "the remote bridge did not drive the session as 3D: {j}");
        let periods = num(j, &["periods"]);
        assert_eq!(periods + num(j, &["missed_periods"]), REMOTE_SECONDS * 1000.0, "{j}");
        assert_eq!(rows.len() as f64, periods, "one trace row per period: {j}");
        // How regularly the responses come is the loaded machine's (the server's I/O threads wait
        // for a core: on this 2-core machine at load 19, 600–1100 responses in 6 s, round trip
        // p99 120–550 ms, the watchdog firing in 1–18 % of the periods): reported above, not
        // asserted. What is asserted is that they come, and every period sent its pose.
        assert!(num(j, &["fresh_forces"]) > 0.0, "{j}");
        assert_eq!(num(j, &["pose_counter"]), periods, "every period queued its pose: {j}");
        // The round trip (pose sent → the response echoing it seen) includes the injected 40 ms.
        let rtt_ms = num(j, &["pose_to_force_us", "p50"]) / 1e3;
        // (As in 2D, at most 80 ms: a p50 beyond it is not the 40 ms scenario this test judges —
        // the server's I/O answered late, a machine too loaded for it; measured here 44–61 ms,
        // once 144 ms at load 21.)
        assert!((39.0..80.0).contains(&rtt_ms), "round trip p50 {rtt_ms} ms, not the injected 40 ms (+ at most 40 ms): {j}");
        println!("[remote {name}] round trip p50 {rtt_ms:.1} ms, p99 {:.1} ms", num(j, &["pose_to_force_us", "p99"]) / 1e3);
        assert!(rows.iter().any(|r| r.wrench[2] != 0.0), "[{name}] no force was rendered");
        assert_eq!(nums(j, "final_pose").len(), 7, "{j}");
    }
    // The 6 × 6 came over Control3: restoring axially (z) and laterally (x, y), stiffer axially than the grip.
    let k = nums(&local_report, "stiffness");
    assert_eq!(k.len(), 36, "{local_report}");
    println!(
        "[remote] stiffness at the needle base: K_xx {:.1}, K_yy {:.1}, K_zz {:.1} N/m; K_θxθx {:.4}, K_θyθy {:.4}, K_θzθz {:.5} N·m/rad",
        k[0], k[7], k[14], k[21], k[28], k[35]
    );
    assert!(k[14] < -80.0 && k[0] < 0.0 && k[7] < 0.0, "{k:?}");
    // The local model held the hand where the trajectory put it, the needle straight down.
    let q_end: [f64; 4] = nums(&local_report, "final_pose")[3..].try_into().unwrap();
    assert!(angle_between(q_end, DOWN) < 0.05, "local model: the needle tilted: {q_end:?}");
    let z_end = local.last().unwrap().position_m[2];
    assert!((z_end - (Z_ABOVE - REMOTE_DEPTH_M - 0.003)).abs() < 0.006, "local model: final z {z_end}");

    // Judged on the last 0.5 s (as in 2D): a stall of this shared machine kicks the virtual hand,
    // and the kick must have decayed by then with the local model, not with the last force.
    // (a) The local model: still, and no growth.
    assert!(late_local.pp_max_mm() < 0.3, "local model oscillates: {late_local:?}");
    assert!(late_local.rms_v_mm_s < 3.0, "local model oscillates: {late_local:?}");
    assert!(late_local.rms_v_mm_s <= settle.rms_v_mm_s + 0.5, "local model does not decay: {settle:?} → {late_local:?}");
    // (b) The last force: a sustained oscillation, many times larger — on whichever axis (in 3D
    // the naive hand has measured to go unstable laterally, ±80 mm in x and y, more than axially).
    assert!(late_naive.pp_max_mm() > 3.0, "last force does not oscillate: {late_naive:?}");
    assert!(late_naive.pp_max_mm() > 10.0 * late_local.pp_max_mm().max(0.05), "last force {late_naive:?} vs local model {late_local:?}");
    assert!(late_naive.rms_v_mm_s > 10.0 * late_local.rms_v_mm_s.max(1.0), "last force {late_naive:?} vs local model {late_local:?}");
}
