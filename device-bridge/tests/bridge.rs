//! The device backends and the real `needlesim-bridge` binary against a fake server loop written here
//! (the test owns the channel's `ServerEnd` and writes forces at 1 kHz from a known linear stiffness),
//! in 2D sessions and in 3D ones (6-DOF poses, a known 6×6 stiffness; a fake session in a child
//! process that is SIGKILLed).

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use needlesim_bridge::device::{Device, PluginDevice};
use needlesim_channel::schedule::Schedule;
use needlesim_channel::shm::{DeviceChannel, Dimension, ServerEnd, ServerForce, monotonic_ns};
use needlesim_channel::spatial::{pose_delta, quat_normalize};

const BIN: &str = env!("CARGO_BIN_EXE_needlesim-bridge");
/// The fake tissue: w = J q (linear, so the bridge's local model is exact).
const J: [f64; 9] = [-200.0, 10.0, 0.0, 5.0, -300.0, 0.0, 0.0, 0.0, -0.05];

fn temp_dir(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!("needlesim-bridge-test-{}-{}-{name}", std::process::id(), N.fetch_add(1, Ordering::Relaxed)));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn env_wrench(q: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|j| J[3 * i + j] * q[j]).sum())
}

/// Compiles `examples/plugin/{source}` with `defines` into `{lib}` in the target's scratch dir.
fn build_plugin(source: &str, lib: &str, defines: &[&str]) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    // Built under a private name and renamed into place (a process still using an older copy keeps its inode).
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(lib);
    let building = out.with_extension(format!("so.{}", std::process::id()));
    // The system C compiler ($CC, else `cc`), called directly: the `cc` crate as a dev-dependency
    // made `cargo test` rebuild every crate whose build script uses it (ring, zstd, lz4 and all
    // above them) after `cargo build --bins`, about 3 minutes of CI.
    let compiler = std::env::var_os("CC").unwrap_or_else(|| "cc".into());
    let status = std::process::Command::new(compiler)
        .args(["-O1", "-shared", "-fPIC", "-Wall", "-Werror", "-I"])
        .arg(root.join("include"))
        .args(defines)
        .arg("-o")
        .arg(&building)
        .arg(root.join("examples/plugin").join(source))
        .arg("-lm")
        .status()
        .expect("running the C compiler");
    assert!(status.success(), "compiling the example plug-in {source} failed");
    std::fs::rename(&building, &out).unwrap();
    out
}

/// The 2D example plug-in (ABI 1), examples/plugin/example_device.c (once per test binary).
fn example_plugin() -> &'static Path {
    static LIB: OnceLock<PathBuf> = OnceLock::new();
    LIB.get_or_init(|| build_plugin("example_device.c", "libexample_device.so", &[]))
}

/// The 6-DOF example plug-in (ABI 2), examples/plugin/example_device6.c (once per test binary).
fn example_plugin6() -> &'static Path {
    static LIB: OnceLock<PathBuf> = OnceLock::new();
    LIB.get_or_init(|| build_plugin("example_device6.c", "libexample_device6.so", &[]))
}

/// A fake session: reads the pose every millisecond and writes w = J q at it, until `writing` is
/// cleared; like a session, it publishes its tick phase and names the pose each force answers.
struct FakeServer {
    writing: Arc<AtomicBool>,
    quit: Arc<AtomicBool>,
    handle: JoinHandle<(ServerEnd, ServerStats)>,
}

#[derive(Debug, Default)]
struct ServerStats {
    fresh_poses: u64,
    last_counter: u64,
    counters_increasing: bool,
    ticks: u64,
}

impl FakeServer {
    fn start(mut server: ServerEnd) -> Self {
        let writing = Arc::new(AtomicBool::new(true));
        let quit = Arc::new(AtomicBool::new(false));
        let (w, q) = (writing.clone(), quit.clone());
        let handle = std::thread::spawn(move || {
            let mut st = ServerStats { counters_increasing: true, ..Default::default() };
            // As a session's tick thread does (without the privilege it runs at normal priority).
            let _ = needlesim_channel::rt::request_realtime_priority(40);
            let mut schedule = Schedule::start_now(Duration::from_millis(1));
            server.publish_schedule_from_rt(schedule.start_time().as_nanos() as u64, 1_000_000);
            while !q.load(Ordering::Relaxed) {
                schedule.wait();
                schedule.catch_up();
                let s = server.read_pose_from_rt();
                if s.fresh() {
                    let c = s.value.unwrap().counter;
                    st.counters_increasing &= c > st.last_counter;
                    st.last_counter = c;
                    st.fresh_poses += 1;
                }
                if let (Some(p), true) = (s.value, w.load(Ordering::Relaxed)) {
                    let q = p.to_planar();
                    st.ticks += 1;
                    let mut force = ServerForce { t_ns: monotonic_ns(), tick: st.ticks, pose_counter: p.counter, ..Default::default() };
                    force.set_planar(env_wrench(q), &J, q);
                    server.write_force_from_rt(&force);
                }
            }
            // The bridge's last pose, had it come after the last tick (the bridge has exited by now).
            let s = server.read_pose_from_rt();
            if s.fresh() {
                let c = s.value.unwrap().counter;
                st.counters_increasing &= c > st.last_counter;
                st.last_counter = c;
                st.fresh_poses += 1;
            }
            (server, st)
        });
        Self { writing, quit, handle }
    }

    fn stop(self) -> (ServerEnd, ServerStats) {
        self.quit.store(true, Ordering::Relaxed);
        self.handle.join().unwrap()
    }
}

fn write_trajectory(dir: &Path) -> PathBuf {
    let p = dir.join("traj.csv");
    // 1.5 s ramp to (10 mm, −5 mm, 0.1 rad), then hold.
    std::fs::write(&p, "t_s,x_m,y_m,theta_rad\n0,0,0,0\n1.5,0.01,-0.005,0.1\n3,0.01,-0.005,0.1\n").unwrap();
    p
}

fn bridge(args: &[&str]) -> Output {
    Command::new(BIN).args(args).env("RUST_LOG", "warn").output().unwrap()
}

/// The `--json` report, as (key, raw value) lookups.
fn json_field<'a>(json: &'a str, key: &str) -> &'a str {
    let k = format!("\"{key}\":");
    let start = json.find(&k).unwrap_or_else(|| panic!("no {key} in {json}")) + k.len();
    let rest = &json[start..];
    let end =
        if rest.starts_with('[') || rest.starts_with('{') { rest.find([']', '}']).unwrap() + 1 } else { rest.find([',', '}']).unwrap() };
    &rest[..end]
}

fn json_num(json: &str, key: &str) -> f64 {
    json_field(json, key).parse().unwrap_or_else(|_| panic!("{key} not a number in {json}"))
}

struct TraceRow {
    t_s: f64,
    counter: u64,
    q: [f64; 3],
    fresh: bool,
    /// The last force the server wrote (fresh this period or not): (Fx, Fy, τ).
    server: [f64; 3],
    wrench: [f64; 3],
    gain: f64,
}

fn read_trace(path: &Path) -> Vec<TraceRow> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t_s,counter,x_m,y_m,theta_rad,fresh,tick,server_fx_n,server_fy_n,server_torque_nm,fx_n,fy_n,torque_nm,gain"
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            TraceRow {
                t_s: v[0],
                counter: v[1] as u64,
                q: [v[2], v[3], v[4]],
                fresh: v[5] == 1.0,
                server: [v[7], v[8], v[9]],
                wrench: [v[10], v[11], v[12]],
                gain: v[13],
            }
        })
        .collect()
}

/// What holds however punctually the two loops ran (issue 35, item 13: a count or a latency that
/// timing decides fails loaded machines' runs at random): every scheduled period ran or was
/// counted missed, each period wrote one pose, the server saw them with advancing counters up to
/// the last one, forces reached the bridge and answered its poses. How many periods were missed,
/// how many forces were fresh and how fast they came are printed (the JSON report), and measured
/// with the real session by the live-session benchmark (`cargo bench -p needlesim-server --bench
/// realtime`, BENCHMARKS.md).
fn check_rate_and_counters(json: &str, rows: &[TraceRow], st: &ServerStats, seconds: f64) {
    let periods = json_num(json, "periods");
    let missed = json_num(json, "missed_periods");
    let expect = seconds * 1000.0;
    assert!((periods + missed - expect).abs() <= 2.0, "periods {periods} + missed {missed} vs {expect}: {json}");
    assert!(json_num(json, "pose_counter") == periods, "{json}");
    assert_eq!(rows.len() as f64, periods, "one trace row per period");
    assert!(rows.windows(2).all(|w| w[1].counter == w[0].counter + 1 && w[1].t_s > w[0].t_s));
    assert!(st.counters_increasing);
    assert_eq!(st.last_counter, periods as u64, "the server's last pose counter is the bridge's last");
    assert!(st.fresh_poses > 0 && json_num(json, "fresh_forces") > 0.0, "{json}");
    let answered = json_num(json, "answered_poses");
    assert!(answered > 0.0 && answered + json_num(json, "unanswered_poses") <= periods, "{json}");
    assert!(json_num(json_field(json, "pose_to_force_us"), "p50") > 0.0, "{json}");
}

/// Issue 35 (item 13): which pose each fresh force of the trace answers, matched by its wrench
/// (the fake session writes `w = J q` at the pose it read, and a trajectory that moves every
/// period makes each pose's wrench distinct): `Some(j)`, the row that wrote the pose, for each
/// fresh row. Panics if a fresh force answers no pose written so far (a wrong or future pose).
fn answered_rows(rows: &[TraceRow]) -> Vec<Option<usize>> {
    let close = |a: &[f64; 3], b: &[f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + y.abs()));
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            r.fresh.then(|| {
                (0..=i)
                    .rev()
                    .find(|&j| close(&r.server, &env_wrench(rows[j].q)))
                    .unwrap_or_else(|| panic!("t {} s: the force {:?} answers none of the poses written so far", r.t_s, r.server))
            })
        })
        .collect()
}

#[test]
fn example_plugin_through_the_backend() {
    let lib = example_plugin();
    let mut dev = PluginDevice::open(lib, "x0=0.01 y0=-0.02 th0=0.5 vx=0.1").unwrap();
    assert_eq!(dev.name(), "plugin:libexample_device.so");
    assert_eq!(dev.abi_version(), 1);
    let s1 = dev.read_pose(0.0).unwrap();
    std::thread::sleep(Duration::from_millis(20));
    let s2 = dev.read_pose(0.0).unwrap();
    // The 2D pose through the planar mapping: (x, y, 0), a rotation θ about +z.
    let (q1, q2) = (s1.pose.to_planar(), s2.pose.to_planar());
    assert!(q1[0] >= 0.01 && q2[0] > q1[0] + 0.1 * 0.015 && q2[0] < 0.01 + 0.1 * 1.0, "{s1:?} {s2:?}");
    assert_eq!((q2[1], s2.pose.position_m[2], s2.buttons), (-0.02, 0.0, 1));
    assert!((q2[2] - 0.5).abs() < 1e-15, "{q2:?}");
    assert_eq!([s2.pose.orientation[1], s2.pose.orientation[2]], [0.0, 0.0]);

    // The planar part of the wrench reaches the 2D device (Fz, τx, τy are not its axes).
    dev.write_force([1.0, -2.0, 7.0, 8.0, 9.0, 0.03]).unwrap();
    // SAFETY: the example's extra export, `long nsd_example_last_force(void*, double[3])`.
    let last = unsafe {
        let f = dev
            .library()
            .get::<unsafe extern "C" fn(*mut std::ffi::c_void, *mut f64) -> std::ffi::c_long>(b"nsd_example_last_force\0")
            .unwrap();
        let mut out = [0.0; 3];
        let n = f(dev.handle(), out.as_mut_ptr());
        (out, n)
    };
    assert_eq!(last, ([1.0, -2.0, 0.03], 1));

    let e = dev.write_force([f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap_err().to_string();
    assert!(e.contains("nsd_write_force returned 1: example device: NaN force"), "{e}");
    dev.close();
    assert!(dev.read_pose(0.0).is_err());

    let e = PluginDevice::open(lib, "bogus").err().unwrap().to_string();
    assert!(e.contains("nsd_open failed: example device: bad config entry 'bogus'"), "{e}");
    let e = format!("{:#}", PluginDevice::open("/nonexistent/libnope.so", "").err().unwrap());
    assert!(e.contains("plug-in /nonexistent/libnope.so: cannot load"), "{e}");
}

#[test]
fn missing_channel_and_bad_arguments_are_clear_errors() {
    let dir = temp_dir("errors");
    let chan = dir.join("nope.shm");
    let out = bridge(&["--channel", chan.to_str().unwrap(), "--device", "scripted", "--trajectory", "x.csv"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(&format!("device channel {}: no such file (has the server created the channel?)", chan.display())), "{err}");

    let server = DeviceChannel::create(&chan).unwrap();
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "t_s,x_m,y_m,theta_rad\n0,0,0,0\n1,0,oops,0\n").unwrap();
    let out = bridge(&["--channel", chan.to_str().unwrap(), "--device", "virtual", "--trajectory", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(&format!("{}: trajectory line 3: column y_m", bad.display())) && err.contains("`oops` is not a number"), "{err}");
    let out = bridge(&["--channel", chan.to_str().unwrap(), "--device", "plugin"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("--device plugin needs --plugin LIB.so"));
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn scripted_device_against_a_fake_server() {
    let dir = temp_dir("scripted");
    let chan = dir.join("session.shm");
    let traj = write_trajectory(&dir);
    let trace = dir.join("trace.csv");
    let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
    let out = bridge(&[
        "--channel",
        chan.to_str().unwrap(),
        "--device",
        "scripted",
        "--trajectory",
        traj.to_str().unwrap(),
        "--seconds",
        "2",
        "--coupling-k",
        "0",
        "--coupling-k-rot",
        "0",
        "--json",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let (_server, st) = server.stop();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    let rows = read_trace(&trace);
    check_rate_and_counters(&json, &rows, &st, 2.0);
    assert_eq!(json_field(&json, "device"), "\"scripted\"");
    // The environment is linear, so the local model renders it exactly at the device's pose, fresh or not.
    let full: Vec<_> = rows.iter().filter(|r| r.gain == 1.0).collect();
    assert!(full.len() >= 1800, "{} rows at full gain", full.len());
    for r in &full {
        let w = env_wrench(r.q);
        assert!(r.wrench.iter().zip(&w).all(|(a, b)| (a - b).abs() < 1e-9), "t {}: {:?} vs {w:?}", r.t_s, r.wrench);
    }
    // The ramp in at the start is linear (50 ms default).
    assert!(rows.iter().filter(|r| r.gain > 0.0 && r.gain < 1.0).count() >= 40);
    assert_eq!(json_field(&json, "final_wrench"), "[0,0,0]");
    assert!(json_num(&json, "max_rendered_force_n") > 1.5);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 15: the device loop runs just before the fake session's ticks (its published phase) and
/// waits for the force of each pose, to render it in the period that wrote it; on its own phase
/// (`--phase-lead-us 0`) it never waits. Issue 35 (item 13): how many poses are answered in their
/// own period depends on how punctually both loops wake up (a loaded machine, no SCHED_FIFO: once
/// in CI 114 of 2,000, each answer a period late), so it is printed here and measured with the real
/// session by the live-session benchmark (`cargo bench -p needlesim-server --bench realtime`,
/// "poses answered in their own period"). What is asserted holds whatever the timing: the loop
/// took the session's phase; every force it took answers a pose it had already written (matched
/// by the pose's wrench); and the report's in-period count is the trace's.
#[test]
fn a_phase_aligned_loop_gets_the_force_of_each_pose_in_the_same_period() {
    let dir = temp_dir("aligned");
    let chan = dir.join("session.shm");
    let trace = dir.join("trace.csv");
    // Moving every period of the 2 s run (a distinct wrench per pose).
    let traj = dir.join("traj.csv");
    std::fs::write(&traj, "t_s,x_m,y_m,theta_rad\n0,0,0,0\n3,0.01,-0.005,0.1\n").unwrap();
    let run = |extra: &[&str]| {
        let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
        let mut args = vec![
            "--channel",
            chan.to_str().unwrap(),
            "--device",
            "scripted",
            "--trajectory",
            traj.to_str().unwrap(),
            "--seconds",
            "2",
            "--coupling-k",
            "0",
            "--coupling-k-rot",
            "0",
            "--json",
            "--trace",
            trace.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = bridge(&args);
        let (server_end, st) = server.stop();
        drop(server_end);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let json = String::from_utf8(out.stdout).unwrap();
        eprintln!("{json}");
        let rows = read_trace(&trace);
        check_rate_and_counters(&json, &rows, &st, 2.0);
        // Each fresh force answers a pose already written; those of the same row were answered in
        // their own period, and the report counts exactly those.
        let answers = answered_rows(&rows);
        let in_period = answers.iter().enumerate().filter(|&(i, a)| *a == Some(i)).count() as f64;
        assert_eq!(json_num(&json, "answered_in_period"), in_period, "the report's in-period count is not the trace's: {json}");
        assert!(json_num(&json, "answered_poses") >= in_period, "{json}");
        let late: Vec<usize> = answers.iter().enumerate().filter_map(|(i, a)| a.map(|j| i - j)).collect();
        eprintln!(
            "{} fresh forces: {in_period} answered the pose of their own period, the others {} periods late at most",
            late.len(),
            late.iter().max().copied().unwrap_or(0)
        );
        json
    };
    let json = run(&[]);
    assert_eq!(json_field(&json, "aligned"), "true", "{json}");

    let json = run(&["--phase-lead-us", "0"]);
    assert_eq!(json_field(&json, "aligned"), "false", "{json}");
    assert_eq!(json_num(&json, "waits_timed_out"), 0.0, "an unaligned loop does not wait: {json}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn virtual_operator_is_pushed_back_by_the_rendered_tissue() {
    let dir = temp_dir("virtual");
    let chan = dir.join("session.shm");
    let traj = write_trajectory(&dir);
    let trace = dir.join("trace.csv");
    let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
    let out = bridge(&[
        "--channel",
        chan.to_str().unwrap(),
        "--device",
        "virtual",
        "--trajectory",
        traj.to_str().unwrap(),
        "--seconds",
        "2.2",
        "--json",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let (_server, st) = server.stop();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    let rows = read_trace(&trace);
    check_rate_and_counters(&json, &rows, &st, 2.2);
    // At rest the hand's PD (kp = 300 N/m) balances the tissue seen through the coupling
    // (k_eff = k_t k_c / (k_t + k_c), k_c = 2000): x = kp x_ref / (kp + k_eff) (the off-diagonal
    // terms of J are small; 3 % tolerance).
    let k_eff = 200.0 * 2000.0 / 2200.0;
    let expect = 300.0 * 0.01 / (300.0 + k_eff);
    let x = rows.last().unwrap().q[0];
    assert!((x - expect).abs() < 0.03 * expect, "x {x} vs {expect}");
    // The rendered force opposes the displacement, and at rest equals the series-coupled tissue force.
    let last = rows.last().unwrap();
    assert!(last.wrench[0] < 0.0 && (last.wrench[0] + k_eff * x).abs() < 0.05 * k_eff * x, "{:?}", last.wrench);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs the bridge with the example plug-in; the fake server stops writing after `feed` (a SIGKILLed
/// server: its forces stop, the channel stays). Returns (json, trace rows, recorded final force line).
fn plugin_run(name: &str, seconds: f64, feed: Duration, extra: &[&str]) -> (String, Vec<TraceRow>, String, ServerStats) {
    let dir = temp_dir(name);
    let chan = dir.join("session.shm");
    let trace = dir.join("trace.csv");
    let record = dir.join("record.txt");
    let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
    let config = format!("x0=0.004 y0=-0.002 th0=0.05 vx=0.002 record={}", record.display());
    let secs = seconds.to_string();
    let mut args = vec![
        "--channel",
        chan.to_str().unwrap(),
        "--device",
        "plugin",
        "--plugin",
        example_plugin().to_str().unwrap(),
        "--plugin-config",
        &config,
        "--seconds",
        &secs,
        "--json",
        "--trace",
        trace.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let child = Command::new(BIN).args(&args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    std::thread::sleep(feed);
    server.writing.store(false, Ordering::Relaxed);
    let out = child.wait_with_output().unwrap();
    let (_server, st) = server.stop();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    let result = (json, read_trace(&trace), std::fs::read_to_string(&record).unwrap(), st);
    let _ = std::fs::remove_dir_all(&dir);
    result
}

#[test]
fn watchdog_ramps_the_plugin_force_to_zero_when_the_server_stops() {
    let (json, rows, record, _st) =
        plugin_run("watchdog", 1.5, Duration::from_millis(700), &["--watchdog-periods", "20", "--ramp-ms", "100"]);
    let last_fresh = rows.iter().rev().find(|r| r.fresh).expect("some fresh forces").t_s;
    assert!((0.4..1.0).contains(&last_fresh), "last fresh force at {last_fresh} s");
    // Full force just before the server stopped.
    let before = rows.iter().find(|r| r.t_s > last_fresh - 0.05).unwrap();
    assert!(before.wrench[0].hypot(before.wrench[1]) > 0.5, "{:?}", before.wrench);
    // Unchanged for the watchdog's 20 periods, then a linear ramp over 100 ms, then exactly zero.
    for r in rows.iter().filter(|r| r.t_s > last_fresh) {
        let n = ((r.t_s - last_fresh) * 1000.0).round();
        let expect_gain = if n <= 20.0 { 1.0 } else { (1.0 - (n - 20.0) / 100.0).max(0.0) };
        assert!((r.gain - expect_gain).abs() < 1e-9, "t {} (+{n} periods): gain {} vs {expect_gain}", r.t_s, r.gain);
        if n >= 120.0 {
            assert_eq!(r.wrench, [0.0; 3], "t {}", r.t_s);
        }
    }
    assert!(json_num(&json, "watchdog_periods") > 500.0, "{json}");
    // The device was left with a zero force (written at exit, after the last period).
    let f: Vec<f64> = record.split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(&f[..3], &[0.0, 0.0, 0.0]);
    assert_eq!(f[3], rows.len() as f64 + 1.0, "one write per period plus the final zero");
}

/// Issue 35 (item 7): a server that is alive but stopped answering (hung, stopped, or dead out of
/// the bridge's sight in another pid namespace) ends the bridge after `--server-timeout-ms` without
/// a force: the watchdog ramps the force out, and the bridge exits with status 1 naming the cause,
/// leaving the channel file to its server.
#[test]
fn issue_35_a_silent_server_ends_the_bridge_after_the_server_timeout() {
    let dir = temp_dir("silent");
    let chan = dir.join("session.shm");
    let trace = dir.join("trace.csv");
    let traj = write_trajectory(&dir);
    let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
    let child = Command::new(BIN)
        .args(["--channel", chan.to_str().unwrap(), "--device", "scripted", "--trajectory", traj.to_str().unwrap()])
        .args(["--seconds", "60", "--server-timeout-ms", "300", "--json", "--trace", trace.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Answer until the bridge has seen forces, then fall silent (the process and the channel stay).
    let t = Instant::now();
    while !std::fs::read_to_string(&trace).is_ok_and(|text| text.lines().skip(1).any(|l| l.split(',').nth(5) == Some("1"))) {
        assert!(t.elapsed() < Duration::from_secs(60), "the bridge never got a force");
        std::thread::sleep(Duration::from_millis(20));
    }
    server.writing.store(false, Ordering::Relaxed);
    let out = child.wait_with_output().unwrap();
    let (server_end, _st) = server.stop();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let cause = format!("the server (pid {}) stopped answering: no force on device channel {}", std::process::id(), chan.display());
    assert!(stderr.contains(&cause) && stderr.contains("(--server-timeout-ms)"), "{stderr}");
    assert!(chan.exists(), "the bridge removed the channel of a live server");
    let rows = read_trace(&trace);
    let last_fresh = rows.iter().rev().find(|r| r.fresh).expect("fresh forces").t_s;
    let last = rows.last().unwrap();
    assert!(last.t_s >= last_fresh + 0.3 - 1e-9, "it gave up {} s after the last force", last.t_s - last_fresh);
    assert_eq!((last.wrench, last.gain), ([0.0; 3], 0.0), "the force was not ramped out");
    drop(server_end);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Not a test: a server end in another process for
/// [`issue35_a_bridge_on_a_dead_servers_channel_removes_the_file`] (runs only with
/// `NEEDLESIM_CHANNEL_CREATOR=PATH`: creates the channel, then waits to be killed).
#[test]
#[ignore = "helper process of issue35_a_bridge_on_a_dead_servers_channel_removes_the_file, not a test"]
fn channel_creator_process() {
    let Some(path) = std::env::var_os("NEEDLESIM_CHANNEL_CREATOR") else { return };
    let _server = DeviceChannel::create(Path::new(&path)).unwrap();
    std::thread::sleep(Duration::from_secs(120));
}

/// Issue 35 (finding 6c): a bridge started on the channel of a server killed before it attached
/// (never seen dying) ran into `--server-timeout-ms`, exited 1 and left the file in /dev/shm,
/// though the README says it removes it. No live end holds the file's lock: the bridge removes it
/// and says so (a live but silent server's file is left: the test above).
#[test]
fn issue35_a_bridge_on_a_dead_servers_channel_removes_the_file() {
    let dir = temp_dir("dead-before-attach");
    let chan = dir.join("session.shm");
    let traj = write_trajectory(&dir);
    let mut server = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "channel_creator_process", "--ignored", "--nocapture", "--test-threads", "1"])
        .env("NEEDLESIM_CHANNEL_CREATOR", &chan)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while DeviceChannel::attach(&chan).is_err() {
        assert!(t0.elapsed() < Duration::from_secs(20), "the channel was not created");
        std::thread::sleep(Duration::from_millis(10));
    }
    let server_pid = server.id();
    server.kill().unwrap(); // SIGKILL: no closing state, the channel file stays
    server.wait().unwrap();
    assert!(chan.exists());
    let out = Command::new(BIN)
        .args(["--channel", chan.to_str().unwrap(), "--device", "scripted", "--trajectory", traj.to_str().unwrap()])
        .args(["--seconds", "30", "--server-timeout-ms", "300"])
        .output()
        .unwrap();
    let removed = !chan.exists();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(&format!("the server (pid {server_pid}) stopped answering")), "{stderr}");
    assert!(stderr.contains("no server holds the channel any more, so its file was removed"), "{stderr}");
    assert!(removed, "the bridge left the dead server's channel file {}", chan.display());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn exit_leaves_a_zero_force_on_the_device_even_under_full_force() {
    // The server feeds until after the bridge exits: the last rendered wrench is not zero.
    let (json, rows, record, _st) = plugin_run("exit", 0.8, Duration::from_millis(1500), &[]);
    let last = rows.last().unwrap();
    assert!(last.wrench[0].hypot(last.wrench[1]) > 0.5 && last.gain == 1.0, "{:?}", last.wrench);
    let f: Vec<f64> = record.split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(&f[..3], &[0.0, 0.0, 0.0]);
    assert_eq!(json_field(&json, "exit"), "\"done\"");
}

#[test]
fn sigterm_and_a_closed_channel_end_with_a_zero_force() {
    for mode in ["sigterm", "close"] {
        let dir = temp_dir(mode);
        let chan = dir.join("session.shm");
        let record = dir.join("record.txt");
        let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
        let config = format!("x0=0.004 y0=-0.002 record={}", record.display());
        let child = Command::new(BIN)
            .args(["--channel", chan.to_str().unwrap(), "--device", "plugin", "--plugin", example_plugin().to_str().unwrap()])
            .args(["--plugin-config", &config, "--json"])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(600));
        let (server_end, _st) = server.stop();
        let t = Instant::now();
        if mode == "sigterm" {
            // SAFETY: signalling our own child.
            assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) }, 0);
        } else {
            drop(server_end); // marks the channel closed and removes the file
        }
        let out = child.wait_with_output().unwrap();
        let elapsed = t.elapsed();
        let json = String::from_utf8(out.stdout).unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        if mode == "sigterm" {
            assert!(out.status.success(), "{stderr}");
            assert_eq!(json_field(&json, "exit"), "\"signal\"");
        } else {
            // Ramped out by the watchdog (10 periods + 50 ms), then an error exit.
            assert_eq!(out.status.code(), Some(1), "{stderr}");
            assert!(stderr.contains("closed or re-created by the server"), "{stderr}");
            // (How soon is printed, not asserted: issue 35, item 13. Without --seconds, only the
            // close ends the run: the exit status and the message above are the behaviour.)
            eprintln!("the bridge exited {elapsed:?} after the channel was closed");
        }
        let f: Vec<f64> = std::fs::read_to_string(&record).unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
        assert_eq!(&f[..3], &[0.0, 0.0, 0.0], "{mode}");
        assert!(f[3] > 100.0, "{mode}: {f:?}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// The bridge against the real server (a session with a device channel, the paper phantom's insertion
/// replayed by the scripted device), then a SIGKILLed server: the rendered force ramps to zero, and
/// the bridge removes the channel file and exits with status 1 naming the cause (issue 35, item 7).
/// Needs the server and CLI binaries: `cargo build -p needlesim-server -p needlesim-client`, then
/// `cargo test -p needlesim-bridge --test bridge -- --ignored`.
#[test]
#[ignore = "needs target/debug/needlesim-server and needlesim (cargo build -p needlesim-server -p needlesim-client)"]
fn real_server_session_and_a_killed_server() {
    let bin_dir = std::env::current_exe().unwrap().parent().unwrap().parent().unwrap().to_path_buf();
    let (server_bin, cli_bin) = (bin_dir.join("needlesim-server"), bin_dir.join("needlesim"));
    assert!(server_bin.exists() && cli_bin.exists(), "build {} and {} first", server_bin.display(), cli_bin.display());
    let dir = temp_dir("real");
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let listen = format!("127.0.0.1:{port}");
    /// Kills the server if an assertion fails before the test does.
    struct KillOnDrop(std::process::Child);
    impl Drop for KillOnDrop {
        fn drop(&mut self) {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
    let mut server = Command::new(&server_bin)
        .args(["serve", "--listen", &listen, "--default-scene", "none", "--rt-priority", "0", "--data-dir"])
        .arg(dir.join("data"))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .map(KillOnDrop)
        .unwrap();
    let t = Instant::now();
    while std::net::TcpStream::connect(&listen).is_err() {
        assert!(t.elapsed() < Duration::from_secs(20), "the server did not start listening on {listen}");
        std::thread::sleep(Duration::from_millis(50));
    }
    let url = format!("http://{listen}");
    let created = Command::new(&cli_bin)
        .args(["--server", &url, "sessions", "create", "--example", "paper-phantom", "--device-channel", "--json"])
        .output()
        .unwrap();
    let created_json = String::from_utf8(created.stdout).unwrap();
    assert!(created.status.success(), "{created_json} {}", String::from_utf8_lossy(&created.stderr));
    let chan = json_field(&created_json, "device_channel_path").trim().trim_matches('"').to_owned();
    assert!(Path::new(&chan).exists(), "{created_json}");
    /// The SIGKILLed server leaves its channel file behind.
    struct RemoveOnDrop(PathBuf);
    impl Drop for RemoveOnDrop {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }
    let _chan_file = RemoveOnDrop(PathBuf::from(&chan));

    let traj = Path::new(env!("CARGO_MANIFEST_DIR")).join("../server/scenes/paper-phantom.csv");
    let trace = dir.join("trace.csv");
    let bridge = Command::new(BIN)
        .args(["--channel", &chan, "--device", "scripted", "--trajectory", traj.to_str().unwrap(), "--seconds", "30", "--json"])
        .args(["--max-force-n", "20", "--trace", trace.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(3000));
    let server_pid = server.0.id();
    server.0.kill().unwrap(); // SIGKILL: no closing state, the channel file stays
    server.0.wait().unwrap();
    let out = bridge.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(&format!("the server (pid {server_pid}) died")), "{stderr}");
    assert!(!Path::new(&chan).exists(), "the bridge left the dead server's channel file");
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    let rows = read_trace(&trace);
    assert!(json_num(&json, "fresh_forces") > 0.0, "{json}");
    assert!(json_num(&json, "max_rendered_force_n") > 0.0, "the needle met no tissue: {json}");
    let last_fresh = rows.iter().rev().find(|r| r.fresh).unwrap().t_s;
    assert!(last_fresh > 0.5, "{last_fresh}");
    // Default watchdog: 10 periods, then a 50 ms ramp.
    for r in rows.iter().filter(|r| r.t_s > last_fresh + 0.061) {
        assert_eq!(r.wrench, [0.0; 3], "t {}", r.t_s);
    }
    assert_eq!(rows.last().unwrap().wrench, [0.0; 3], "the bridge exited before the ramp ended");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13: every change to the live channel file while the bridge drives the plug-in (which
/// records the last force it was sent). The bridge neither dies of SIGBUS (truncation) nor runs on
/// with a channel nobody can reach (deletion, replacement): it ramps the force out, leaves a zero
/// force on the device, and exits with status 1 and a message naming the cause. The fake server
/// (this process) survives every change too.
#[test]
fn issue_13_a_broken_channel_ends_the_bridge_with_a_zero_force() {
    // (kind, the causes the bridge may name: a truncation is found by the next access, or, if the
    // watcher thread runs first, by the size check.)
    let cases: [(&str, &[&str]); 6] = [
        ("truncate", &["was truncated under the mapping", "is now 0 bytes, expected 768"]),
        ("shrink", &["is now 256 bytes, expected 768"]),
        ("grow", &["is now 1048576 bytes, expected 768"]),
        ("garbage", &["header was overwritten"]),
        ("delete", &["was deleted"]),
        ("replace", &["was replaced by another file"]),
    ];
    for (kind, causes) in cases {
        let dir = temp_dir(&format!("broken-{kind}"));
        let chan = dir.join("session.shm");
        let record = dir.join("record.txt");
        let trace = dir.join("trace.csv");
        let server = FakeServer::start(DeviceChannel::create(&chan).unwrap());
        // Off the origin and moving: the fake tissue pushes back (w = J q ≠ 0).
        let config = format!("x0=0.004 y0=-0.002 th0=0.05 vx=0.002 record={}", record.display());
        let child = Command::new(BIN)
            .args(["--channel", chan.to_str().unwrap(), "--device", "plugin", "--plugin", example_plugin().to_str().unwrap()])
            .args(["--plugin-config", &config, "--seconds", "30", "--json", "--trace", trace.to_str().unwrap()])
            .env("RUST_LOG", "warn")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Wait until the bridge renders a force from the fake server.
        let t0 = Instant::now();
        while !std::fs::read_to_string(&trace).is_ok_and(|t| t.lines().count() > 500) {
            assert!(t0.elapsed() < Duration::from_secs(30), "{kind}: the bridge did not start tracing");
            std::thread::sleep(Duration::from_millis(20));
        }
        let file = || std::fs::OpenOptions::new().write(true).open(&chan).unwrap();
        match kind {
            "truncate" => file().set_len(0).unwrap(),
            "shrink" => file().set_len(256).unwrap(),
            "grow" => file().set_len(1 << 20).unwrap(),
            "garbage" => std::os::unix::fs::FileExt::write_all_at(&file(), &[0xA5; 512], 0).unwrap(),
            "delete" => std::fs::remove_file(&chan).unwrap(),
            "replace" => {
                let tmp = dir.join("replacement");
                std::fs::copy(&chan, &tmp).unwrap();
                std::fs::rename(&tmp, &chan).unwrap();
            }
            _ => unreachable!(),
        }
        let broken_at = Instant::now();
        let out = child.wait_with_output().unwrap();
        let exited_after = broken_at.elapsed();
        let (_server_end, st) = server.stop();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let json = String::from_utf8(out.stdout).unwrap();
        println!("{kind}: the bridge exited {exited_after:?} after the change: {}", stderr.trim());
        assert_eq!(out.status.code(), Some(1), "{kind}: {:?} {stderr}", out.status);
        assert!(stderr.contains("is broken") && causes.iter().any(|c| stderr.contains(c)), "{kind}: {stderr}");
        // (The exit string may hold commas, which json_field does not parse: the report's tail.)
        let exit = &json[json.find("\"exit\":").expect("an exit field")..];
        assert!(exit.contains("is broken") && causes.iter().any(|c| exit.contains(c)), "{kind}: {json}");
        // Well before --seconds 30: the bridge noticed.
        assert!(exited_after < Duration::from_secs(20), "{kind}: {exited_after:?}");
        let rows = read_trace(&trace);
        let pushing = rows.iter().map(|r| r.wrench[0].hypot(r.wrench[1])).fold(0.0, f64::max);
        assert!(pushing > 0.1, "{kind}: no force was rendered before the change ({pushing} N): the zero below proves nothing");
        let f: Vec<f64> = std::fs::read_to_string(&record).unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
        assert_eq!(&f[..3], &[0.0, 0.0, 0.0], "{kind}: the device was left pushing");
        assert_eq!(f[3], rows.len() as f64 + 1.0, "{kind}: one write per period plus the final zero");
        assert!(st.ticks > 500, "{kind}: {st:?}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

// ---------------------------------------------------------------------------------------------
// 3D sessions

/// The fake 3D tissue: every pose is answered with the wrench `W0` and the stiffness [`k6`] at the
/// fixed base [`base3`], so the bridge's local model renders `W0 + K δ(q_d, base)` exactly.
const W0: [f64; 6] = [0.2, -0.1, 0.3, 0.002, -0.001, 0.0015];

/// A dense 6×6 (seeded), blocks of the sizes a needle in tissue gives: N/m, N/rad, N·m/m, N·m/rad.
fn k6() -> [[f64; 6]; 6] {
    let mut z = 0x5EED_u64;
    let mut rnd = move || {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut x = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((x ^ (x >> 31)) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    std::array::from_fn(|r| {
        std::array::from_fn(|c| match (r < 3, c < 3) {
            (true, true) => rnd() * 100.0 - if r == c { 300.0 } else { 0.0 },
            (true, false) | (false, true) => rnd() * 1.0,
            (false, false) => rnd() * 0.01 - if r == c { 0.03 } else { 0.0 },
        })
    })
}

fn base3() -> ([f64; 3], [f64; 4]) {
    ([0.001, -0.002, 0.003], quat_normalize([0.95, 0.1, -0.2, 0.05]).unwrap())
}

fn expected_wrench3(p: [f64; 3], q: [f64; 4]) -> [f64; 6] {
    let (bp, bq) = base3();
    let d = pose_delta(p, q, bp, bq);
    let k = k6();
    std::array::from_fn(|i| W0[i] + (0..6).map(|j| k[i][j] * d[j]).sum::<f64>())
}

/// One tick loop of the fake 3D session (this thread or the child process) until `quit`;
/// returns the last pose read and the ticks that wrote a force.
fn fake_session_3d(server: &mut ServerEnd, quit: &AtomicBool) -> (Option<needlesim_channel::shm::DevicePose>, u64) {
    let _ = needlesim_channel::rt::request_realtime_priority(40);
    let mut schedule = Schedule::start_now(Duration::from_millis(1));
    server.publish_schedule_from_rt(schedule.start_time().as_nanos() as u64, 1_000_000);
    let (bp, bq) = base3();
    let mut ticks = 0u64;
    let mut last = None;
    while !quit.load(Ordering::Relaxed) {
        schedule.wait();
        schedule.catch_up();
        let s = server.read_pose_from_rt();
        if let Some(p) = s.value {
            last = Some(p);
            ticks += 1;
            server.write_force_from_rt(&ServerForce {
                t_ns: monotonic_ns(),
                tick: ticks,
                force_n: [W0[0], W0[1], W0[2]],
                torque_nm: [W0[3], W0[4], W0[5]],
                stiffness: k6(),
                base_position_m: bp,
                base_orientation: bq,
                state: ServerForce::STATE_OK,
                pose_counter: if s.fresh() { p.counter } else { 0 },
            });
        }
    }
    (last, ticks)
}

/// One row of the bridge's 3D `--trace`.
#[derive(Debug)]
struct TraceRow3 {
    t_s: f64,
    p: [f64; 3],
    q: [f64; 4],
    fresh: bool,
    wrench: [f64; 6],
    gain: f64,
}

fn read_trace3(path: &Path) -> Vec<TraceRow3> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t_s,counter,x_m,y_m,z_m,qw,qx,qy,qz,fresh,tick,server_fx_n,server_fy_n,server_fz_n,server_tx_nm,server_ty_nm,server_tz_nm,\
         fx_n,fy_n,fz_n,tx_nm,ty_nm,tz_nm,gain"
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 24, "{l}");
            TraceRow3 {
                t_s: v[0],
                p: [v[2], v[3], v[4]],
                q: [v[5], v[6], v[7], v[8]],
                fresh: v[9] == 1.0,
                wrench: std::array::from_fn(|i| v[17 + i]),
                gain: v[23],
            }
        })
        .collect()
}

/// A 3D trajectory CSV drives a 3D session: the session side reads the 6-DOF poses intact (its last
/// pose is the trajectory's last, bit for bit), and the bridge renders the known 6×6 at each pose
/// offset from the base: `W0 + K δ(q_d, base)` on every row at full gain.
#[test]
fn scripted_3d_trajectory_renders_the_6x6_against_a_fake_3d_session() {
    let dir = temp_dir("scripted3d");
    let chan = dir.join("session.shm");
    let traj = dir.join("traj3.csv");
    // To 4 mm, −3 mm, 2 mm and 0.2 rad about (1, 2, 2)/3 over 1 s, then hold.
    let (s, c) = (0.1f64.sin(), 0.1f64.cos());
    let text = format!(
        "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0.004,-0.003,0.002,{c},{},{},{}\n2,0.004,-0.003,0.002,{c},{},{},{}\n",
        s / 3.0,
        2.0 * s / 3.0,
        2.0 * s / 3.0,
        s / 3.0,
        2.0 * s / 3.0,
        2.0 * s / 3.0
    );
    std::fs::write(&traj, &text).unwrap();
    let trace = dir.join("trace.csv");
    let mut server = DeviceChannel::create_with_dimension(&chan, Dimension::Three).unwrap();
    let quit = Arc::new(AtomicBool::new(false));
    let q2 = quit.clone();
    let session = std::thread::spawn(move || {
        let r = fake_session_3d(&mut server, &q2);
        (server, r)
    });
    let out = bridge(&[
        "--channel",
        chan.to_str().unwrap(),
        "--device",
        "scripted",
        "--trajectory",
        traj.to_str().unwrap(),
        "--seconds",
        "1.5",
        "--coupling-k",
        "0",
        "--coupling-k-rot",
        "0",
        "--max-force-n",
        "50",
        "--max-torque-nm",
        "5",
        "--json",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    quit.store(true, Ordering::Relaxed);
    let (_server, (last_pose, ticks)) = session.join().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    assert_eq!(json_num(&json, "dimension"), 3.0, "{json}");
    assert_eq!(json_field(&json, "final_wrench"), "[0,0,0,0,0,0]");
    assert!(ticks > 500 && json_num(&json, "fresh_forces") > 500.0, "{ticks} {json}");
    // The session side got the 6-DOF pose intact: the trajectory's last, exactly.
    let want = needlesim_trajectory::Trajectory3::parse_csv(&text).unwrap().samples.last().unwrap().1;
    let got = last_pose.expect("the session read poses");
    assert_eq!((got.position_m, got.orientation), (want.position_m, want.quat_wxyz));
    let final_pose: Vec<f64> = json_field(&json, "final_pose").trim_matches(['[', ']']).split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(final_pose, want.position_m.iter().chain(&want.quat_wxyz).copied().collect::<Vec<_>>());
    // The local model in 3D, at every pose of the path (rows at full gain).
    let rows = read_trace3(&trace);
    let full: Vec<_> = rows.iter().filter(|r| r.gain == 1.0).collect();
    assert!(full.len() >= 1200, "{} rows at full gain", full.len());
    let mut moved = 0;
    for r in &full {
        let w = expected_wrench3(r.p, r.q);
        assert!(r.wrench.iter().zip(&w).all(|(a, b)| (a - b).abs() < 1e-9), "t {}: {:?} vs {w:?}", r.t_s, r.wrench);
        moved += usize::from((r.wrench[0] - W0[0]).abs() > 0.1 && (r.wrench[5] - W0[5]).abs() > 1e-4);
    }
    assert!(moved > 500, "the offsets barely changed the wrench ({moved} rows): the check above proves little");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Not a test: the fake 3D session process of [`a_sigkilled_3d_session_leaves_the_6dof_plugin_at_zero`]
/// (runs only with `NEEDLESIM_FAKE_SESSION_3D=PATH`, until killed).
#[test]
#[ignore = "helper process of a_sigkilled_3d_session_leaves_the_6dof_plugin_at_zero, not a test"]
fn fake_session_3d_process() {
    let Some(path) = std::env::var_os("NEEDLESIM_FAKE_SESSION_3D") else { return };
    let mut server = DeviceChannel::create_with_dimension(&path, Dimension::Three).unwrap();
    fake_session_3d(&mut server, &AtomicBool::new(false));
}

/// A 3D session in another process drives the 6-DOF example plug-in (ABI 2) through the bridge and
/// is SIGKILLed (no closing state, the channel file stays): the bridge's commanded wrench holds for
/// the watchdog's periods, ramps linearly to exactly zero, and the device is left at zero. Issue 35
/// (item 7): the bridge then notices that the session's process died, removes the channel file it
/// left, and exits with status 1 naming the cause (it ran on to the end of `--seconds` and exited 0).
#[test]
fn a_sigkilled_3d_session_leaves_the_6dof_plugin_at_zero() {
    let dir = temp_dir("killed3d");
    let chan = dir.join("session.shm");
    let record = dir.join("record.txt");
    let trace = dir.join("trace.csv");
    let mut session = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "fake_session_3d_process", "--ignored", "--nocapture", "--test-threads", "1"])
        .env("NEEDLESIM_FAKE_SESSION_3D", &chan)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while DeviceChannel::attach(&chan).map(|d| d.server_schedule().is_none()).unwrap_or(true) {
        assert!(t0.elapsed() < Duration::from_secs(20), "the fake session did not start");
        std::thread::sleep(Duration::from_millis(10));
    }
    // Off the base and turning: the known 6×6 pushes and twists.
    let config = format!("x0=0.004 y0=-0.002 z0=0.006 vz=0.002 ax=1 ay=0 az=1 th0=0.1 om=0.2 dof=6 record={}", record.display());
    let bridge = Command::new(BIN)
        .args(["--channel", chan.to_str().unwrap(), "--device", "plugin", "--plugin", example_plugin6().to_str().unwrap()])
        // Far longer than the run takes: it ends when the bridge notices the death, not at 30 s.
        .args(["--plugin-config", &config, "--seconds", "30", "--watchdog-periods", "20", "--ramp-ms", "100"])
        .args(["--max-force-n", "50", "--max-torque-nm", "5", "--json", "--trace", trace.to_str().unwrap()])
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(700));
    let session_pid = session.id();
    session.kill().unwrap(); // SIGKILL
    session.wait().unwrap();
    let out = bridge.wait_with_output().unwrap();
    let removed = !chan.exists();
    let _ = std::fs::remove_file(&chan); // left by the killed session, if the bridge did not remove it
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(&format!("the server (pid {session_pid}) died")) && stderr.contains("was removed"), "{stderr}");
    assert!(removed, "the bridge left the dead session's channel file {}", chan.display());
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    assert!(json_field(&json, "exit").contains("died"), "{json}");
    assert_eq!(json_num(&json, "dimension"), 3.0, "{json}");
    assert_eq!(json_field(&json, "device"), "\"plugin:libexample_device6.so\"");
    let rows = read_trace3(&trace);
    let last_fresh = rows.iter().rev().find(|r| r.fresh).expect("some fresh forces").t_s;
    assert!(last_fresh > 0.05, "last fresh force at {last_fresh} s");
    let before = rows.iter().find(|r| r.t_s > last_fresh - 0.05).unwrap();
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm(&before.wrench[..3]) > 0.5 && norm(&before.wrench[3..]) > 1e-3, "not pushing before the kill: {:?}", before.wrench);
    for r in rows.iter().filter(|r| r.t_s > last_fresh) {
        let n = ((r.t_s - last_fresh) * 1000.0).round();
        let expect_gain = if n <= 20.0 { 1.0 } else { (1.0 - (n - 20.0) / 100.0).max(0.0) };
        assert!((r.gain - expect_gain).abs() < 1e-9, "t {} (+{n} periods): gain {} vs {expect_gain}", r.t_s, r.gain);
        if n >= 120.0 {
            assert_eq!(r.wrench, [0.0; 6], "t {}: still pushing after the watchdog", r.t_s);
        }
    }
    // It ran until the ramp was over (not to the end of --seconds), and ended at zero.
    let last = rows.last().unwrap();
    assert!(last.t_s > last_fresh + 0.12 - 1e-9 && last.t_s < 29.0, "last period at {} s (last fresh force at {last_fresh} s)", last.t_s);
    assert_eq!((last.wrench, last.gain), ([0.0; 6], 0.0), "the bridge exited before the ramp ended");
    let f: Vec<f64> = std::fs::read_to_string(&record).unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(&f[..6], &[0.0; 6], "the device was left pushing: {f:?}");
    assert_eq!(f[6], rows.len() as f64 + 1.0, "one write per period plus the final zero");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The plug-in ABI versions: 2 (6-DOF, force-only or wrench output) and 1 (2D, see
/// `example_plugin_through_the_backend`) load; an unknown version and a bad output DOF are refused
/// with messages naming them.
#[test]
fn plugin_abi_2_loads_and_an_unknown_version_is_refused() {
    let lib = example_plugin6();
    let mut dev = PluginDevice::open(lib, "x0=0.01 y0=0.02 z0=-0.03 ax=1 ay=1 az=0 th0=0.4 dof=3 buttons=5").unwrap();
    assert_eq!((dev.abi_version(), dev.output()), (2, needlesim_bridge::render::DeviceOutput::ForceOnly));
    let s = dev.read_pose(0.0).unwrap();
    assert_eq!((s.pose.position_m, s.buttons), ([0.01, 0.02, -0.03], 5));
    // A rotation of 0.4 rad about (1, 1, 0)/√2.
    let (sn, cs) = (0.2f64.sin(), 0.2f64.cos());
    let want = [cs, sn / 2f64.sqrt(), sn / 2f64.sqrt(), 0.0];
    assert!(s.pose.orientation.iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-15), "{:?} vs {want:?}", s.pose.orientation);
    let w = [1.0, -2.0, 3.0, 0.01, -0.02, 0.03];
    dev.write_force(w).unwrap();
    // SAFETY: the example's extra export, `long nsd_example_last_wrench(void*, double[6])`.
    let last = unsafe {
        let f = dev
            .library()
            .get::<unsafe extern "C" fn(*mut std::ffi::c_void, *mut f64) -> std::ffi::c_long>(b"nsd_example_last_wrench\0")
            .unwrap();
        let mut out = [0.0; 6];
        let n = f(dev.handle(), out.as_mut_ptr());
        (out, n)
    };
    assert_eq!(last, (w, 1));
    let e = dev.write_force([0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0]).unwrap_err().to_string();
    assert!(e.contains("nsd_write_wrench returned 1: example device6: NaN wrench"), "{e}");
    dev.close();
    let dev6 = PluginDevice::open(lib, "dof=6").unwrap();
    assert_eq!(dev6.output(), needlesim_bridge::render::DeviceOutput::Wrench);
    drop(dev6);

    let e = PluginDevice::open(lib, "dof=4").err().unwrap().to_string();
    assert!(e.contains("nsd_output_dof returned 4, expected 3 (force only) or 6 (force and torque)"), "{e}");
    let e = PluginDevice::open(lib, "az=0").err().unwrap().to_string();
    assert!(e.contains("nsd_open failed: example device6: zero rotation axis"), "{e}");

    let future = build_plugin("example_device6.c", "libexample_device_abi7.so", &["-DEXAMPLE_ABI_VERSION=7"]);
    let e = PluginDevice::open(&future, "").err().unwrap().to_string();
    assert!(
        e.contains(&format!(
            "plug-in {}: unknown ABI version 7 (nsd_abi_version); this bridge loads ABI 2 (6-DOF) and ABI 1 (2D)",
            future.display()
        )),
        "{e}"
    );
}

/// The bridge refuses a channel of the previous (2D-only) layout, naming both layout versions.
#[test]
fn the_bridge_refuses_a_channel_of_the_previous_layout() {
    let dir = temp_dir("layout2");
    let chan = dir.join("old.shm");
    let mut old = vec![0u8; 512];
    old[..8].copy_from_slice(b"NDLSIMv1");
    old[8..12].copy_from_slice(&2u32.to_le_bytes());
    old[16..24].copy_from_slice(&512u64.to_le_bytes());
    old[24..32].copy_from_slice(&77u64.to_le_bytes());
    std::fs::write(&chan, &old).unwrap();
    let out = bridge(&["--channel", chan.to_str().unwrap(), "--device", "plugin", "--plugin", example_plugin6().to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("layout version 2 (2D pose and wrench, tick phase), this bridge speaks 3 (6-DOF pose"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The virtual operator (a 6-axis spring–damper hand) follows a 3D path against the fake 3D tissue
/// through the real bridge and comes to rest where, on every axis, its grip balances the rendered
/// wrench: `kp_i e_i + w_i = 0`, with `e = δ(q_ref, q)` the pose error (default grip 300 N/m,
/// 0.3 N·m/rad; at rest the damping terms vanish).
#[test]
fn virtual_operator_in_3d_rests_where_its_grip_balances_the_rendered_wrench() {
    let dir = temp_dir("virtual3d");
    let chan = dir.join("session.shm");
    let traj = dir.join("traj3.csv");
    let (s, c) = (0.05f64.sin(), 0.05f64.cos());
    std::fs::write(&traj, format!("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.5,0.003,-0.002,0.004,{c},0,{s},0\n")).unwrap();
    let trace = dir.join("trace.csv");
    let mut server = DeviceChannel::create_with_dimension(&chan, Dimension::Three).unwrap();
    let quit = Arc::new(AtomicBool::new(false));
    let q2 = quit.clone();
    let session = std::thread::spawn(move || {
        let r = fake_session_3d(&mut server, &q2);
        (server, r)
    });
    let out = bridge(&[
        "--channel",
        chan.to_str().unwrap(),
        "--device",
        "virtual",
        "--trajectory",
        traj.to_str().unwrap(),
        "--seconds",
        "2.5",
        "--max-force-n",
        "50",
        "--max-torque-nm",
        "5",
        "--json",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    quit.store(true, Ordering::Relaxed);
    let _ = session.join().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json = String::from_utf8(out.stdout).unwrap();
    eprintln!("{json}");
    let rows = read_trace3(&trace);
    let last = rows.last().unwrap();
    let e = pose_delta([0.003, -0.002, 0.004], [c, 0.0, s, 0.0], last.p, last.q);
    let kp = [300.0, 300.0, 300.0, 0.3, 0.3, 0.3];
    for i in 0..6 {
        let (grip, w) = (kp[i] * e[i], last.wrench[i]);
        let scale = if i < 3 { 0.01 } else { 1e-4 };
        assert!((grip + w).abs() < 0.05 * w.abs() + scale, "axis {i}: grip {grip} vs rendered {w} (pose error {e:?})");
    }
    // The tissue pushed it off the path (so the balance above is not trivially 0 = 0).
    assert!(last.wrench[..3].iter().map(|v| v * v).sum::<f64>().sqrt() > 0.3, "{:?}", last.wrench);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A force-only ("3-DOF") ABI 2 plug-in in a 3D session: the bridge renders the force–position
/// block of the 6×6 alone, `F = F_s + K_Fp (p_d − p_s)`, and never a torque.
#[test]
fn a_force_only_plugin_gets_the_force_position_block_and_no_torque() {
    let dir = temp_dir("force-only");
    let chan = dir.join("session.shm");
    let trace = dir.join("trace.csv");
    let mut server = DeviceChannel::create_with_dimension(&chan, Dimension::Three).unwrap();
    let quit = Arc::new(AtomicBool::new(false));
    let q2 = quit.clone();
    let session = std::thread::spawn(move || {
        let r = fake_session_3d(&mut server, &q2);
        (server, r)
    });
    // Moving and turning, so that the rotation block would show if it were used.
    let config = "x0=0.004 y0=-0.002 z0=0.006 vx=0.003 ax=0 ay=1 az=0 th0=0.2 om=0.5 dof=3";
    let out = bridge(&[
        "--channel",
        chan.to_str().unwrap(),
        "--device",
        "plugin",
        "--plugin",
        example_plugin6().to_str().unwrap(),
        "--plugin-config",
        config,
        "--seconds",
        "0.8",
        "--coupling-k",
        "0",
        "--coupling-k-rot",
        "0",
        "--max-force-n",
        "50",
        "--json",
        "--trace",
        trace.to_str().unwrap(),
    ]);
    quit.store(true, Ordering::Relaxed);
    let _ = session.join().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let rows = read_trace3(&trace);
    let (bp, _) = base3();
    let k = k6();
    let full: Vec<_> = rows.iter().filter(|r| r.gain == 1.0).collect();
    assert!(full.len() > 300, "{} rows at full gain", full.len());
    for r in &full {
        assert_eq!(&r.wrench[3..], &[0.0; 3], "t {}: a torque was sent to a force-only device", r.t_s);
        let want: [f64; 3] = std::array::from_fn(|i| W0[i] + (0..3).map(|j| k[i][j] * (r.p[j] - bp[j])).sum::<f64>());
        assert!(r.wrench[..3].iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-9), "t {}: {:?} vs {want:?}", r.t_s, r.wrench);
        // The full 6×6 would differ by the rotation block's share: the check above tells them apart.
        let full6 = expected_wrench3(r.p, r.q);
        assert!((0..3).any(|i| (full6[i] - want[i]).abs() > 1e-4), "t {}: the rotation block contributes nothing here", r.t_s);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
