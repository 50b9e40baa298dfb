//! `needlesim-bridge`: the device loop between a haptic device and a session — its shared-memory
//! channel (`--channel PATH`, same host) or its gRPC Control stream (`--server URL --session ID
//! --token T`, the remote link of `remote.rs`: poses out through a bounded non-blocking queue,
//! responses in through a latest-value slot; `--inject-rtt-ms N` adds a delay line). With the
//! remote link `pose_to_force_us` is a true round trip (the server echoes the pose's client time).
//!
//! Every device period (tick k at `t0 + k·Δt`, drift-free; a late wake-up skips the periods it
//! missed and counts them): read the device pose → `write_pose_from_device` →
//! `read_force_from_device` → render (local model, coupling, watchdog, limits: `render.rs`) →
//! `write_force` on the device. On every exit path (end of `--seconds`, Ctrl-C/SIGTERM, a device
//! or channel error) a zero wrench is written to the device before it is closed. A channel whose
//! file was truncated, resized, overwritten, deleted or replaced (the channel crate's `shm/`: the access never
//! faults; a watcher thread checks the file every 100 ms) is lost like a closed one: the watchdog
//! ramps the force out, the zero wrench is written, and the bridge exits with status 1 and a
//! message naming the cause. So is a server that died without closing its channel (`kill -9`, a
//! crash: the watcher thread checks the creator process, `needlesim_channel::liveness`), whose
//! orphaned channel file the bridge then removes, and one from which no force came for
//! `--server-timeout-ms` (hung, stopped, or dead out of sight in another pid namespace; its file
//! is left to it). The remote link (`--server`) is held to the same silence limit (plus
//! `--inject-rtt-ms`): a stopped server whose stream stays open ends the bridge alike.
//!
//! # 2D and 3D sessions
//!
//! Everything in the loop is 6-DOF (`render.rs`, `device.rs`): the channel's header says the
//! session's dimension, and a 2D session is the same path restricted to the plane (the channel
//! carries its pose and wrench through the planar embedding of `needlesim_channel::spatial`). Only
//! the outputs differ: for a 2D session the report's `final_pose` is `[x, y, θ]` and its
//! `stiffness` the 3 × 3 `∂(Fx, Fy, τ)/∂(x, y, θ)`, and the trace has the 2D columns; for a 3D
//! one `final_pose` is `[x, y, z, qw, qx, qy, qz]`, `stiffness` the 6 × 6 row-major, and the trace
//! the 6-DOF columns. The report's `dimension` says which. The remote link (`--server`) asks the
//! session's dimension and drives a 2D session through `Control` (planar poses, 3 × 3 stiffness) and
//! a 3D one through `Control3` (6-DOF poses; force, torque and the 6 × 6 of each response's `d3`).
//!
//! # Phase-aligned with the session's ticks (`--phase-lead-us`, shared memory only)
//!
//! The session publishes its tick phase on the channel (tick k due at `origin + k·period` on
//! `CLOCK_MONOTONIC`). With the same rate, the device loop runs `--phase-lead-us` (100 µs) before
//! each tick: the pose is written just before the tick that takes it, and the loop then waits
//! (spinning, at most `--force-wait-us`) for the force that tick computes, which names the pose it
//! answers (`ServerForce::pose_counter`), and renders it in the same period: pose → force is the
//! lead plus the tick's compute time, not a period more. The wait ends early when a force written
//! after the pose arrives without answering it (the pose came too late for that tick; the next
//! pose supersedes it). Unaligned (lead 0, another rate, or a session that published no phase),
//! the loop keeps its own phase and takes the force that is there right after writing the pose,
//! which answers a pose of an earlier period. Both the lead and the wait spin on a core: on a
//! 2-core machine they compete with the server's clients (see `needlesim_channel::schedule`).
//!
//! Latency figures in the report (µs, p50/p99/p99.9/max, over the fresh forces seen):
//! - `pose_to_force_us` (shared memory): (time the bridge first saw a force) − (write time of the
//!   pose the force answers, by its `pose_counter`), over the poses answered; poses never answered
//!   (superseded before a tick took them) are counted in `unanswered_poses`. With the remote link
//!   it is a true round trip too (the server echoes the pose's client time);
//! - `force_age_us`: (time the bridge first saw a force) − its `t_ns` (the server → bridge part).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::{Context, Result, bail};
use clap::{CommandFactory, Parser, ValueEnum};
use needlesim_bridge::device::{Device, OperatorParams, PluginDevice, ScriptedDevice, Trajectory, VirtualOperator};
use needlesim_bridge::remote::{RemoteConfig, RemoteLink};
use needlesim_channel::shm::{DeviceChannel, WATCH_PERIOD};

use crate::device_loop::run;
use crate::link::Link;
use crate::report::Report;

mod device_loop;
mod link;
mod report;
mod trace;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum DeviceKind {
    /// Replay --trajectory; forces are recorded, nothing moves.
    Scripted,
    /// A simulated hand (mass, damping, PD toward --trajectory) that the rendered force pushes back.
    Virtual,
    /// A real device through a C plug-in (--plugin LIB.so, include/needlesim_device.h).
    Plugin,
}

/// Runs a haptic device against a needlesim session's shared-memory device channel.
#[derive(Debug, Parser)]
#[command(name = "needlesim-bridge", version)]
struct Cli {
    /// SCHED_FIFO priority of the device loop (1..=99; 0 = normal scheduling). Needs CAP_SYS_NICE
    /// or root; without it the bridge says so and runs at normal priority.
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(i32).range(0..=99))]
    rt_priority: i32,
    /// The session's device channel file (created by the server), for a bridge on the server's host.
    #[arg(long, value_name = "PATH", required_unless_present = "server", conflicts_with = "server")]
    channel: Option<PathBuf>,
    /// A remote link instead of --channel: the server's gRPC URL (`http://HOST:PORT`); poses go out
    /// and forces come back over the session's Control stream.
    #[arg(long, value_name = "URL", requires_all = ["session", "token"])]
    server: Option<String>,
    /// The session id (--server).
    #[arg(long, value_name = "ID", requires = "server")]
    session: Option<String>,
    /// The session's controller token (--server), sent as `authorization: Bearer <token>`.
    #[arg(long, value_name = "TOKEN", requires = "server")]
    token: Option<String>,
    /// Delay every pose going out by N/2 ms and every response coming in by N/2 ms (--server; a
    /// delay line in the bridge, to test latency without a real network). 0..=10000.
    #[arg(long, value_name = "N", default_value_t = 0.0, requires = "server", value_parser = bounded(0.0, 10_000.0))]
    inject_rtt_ms: f64,
    /// How to render between server updates: the local linear model w_s + J (q − q_s) behind the
    /// virtual coupling, or only the last received wrench (no J term, no coupling: the naive scheme).
    #[arg(long, value_enum, default_value_t = RenderMode::LocalModel)]
    render: RenderMode,
    #[arg(long, value_enum)]
    device: DeviceKind,
    /// Trajectory CSV for the scripted and virtual devices: 3D `t_s,x_m,y_m,z_m,qw,qx,qy,qz` or 2D
    /// `t_s,x_m,y_m,theta_rad` (told apart by the header; a 2D path drives a 3D session in its xy plane).
    #[arg(long, value_name = "CSV")]
    trajectory: Option<PathBuf>,
    /// Replay the trajectory in a loop instead of holding its last pose.
    #[arg(long = "loop")]
    looped: bool,
    /// The plug-in shared library (--device plugin).
    #[arg(long, value_name = "LIB.so")]
    plugin: Option<PathBuf>,
    /// The string passed to the plug-in's nsd_open.
    #[arg(long, value_name = "STR", default_value = "")]
    plugin_config: String,
    /// Device rate (Hz), 1..=10000 (haptic devices run at 500–4000 Hz).
    #[arg(long, default_value_t = 1000.0, value_parser = bounded(1.0, 10_000.0))]
    rate_hz: f64,
    /// With --channel: write each pose this long (µs) before the session's tick deadline and
    /// render the force computed from it in the same period (the session publishes its tick phase
    /// on the channel; --rate-hz must equal its tick rate). 0: run on the loop's own phase.
    /// 0..=1000000 (a lead not shorter than the period runs on the loop's own phase).
    #[arg(long, value_name = "US", default_value_t = 100, value_parser = clap::value_parser!(u64).range(0..=1_000_000))]
    phase_lead_us: u64,
    /// Phase-aligned only: the longest the loop waits (spinning) after writing a pose for the force
    /// that answers it, in µs (at most 3/4 of the period); past it, it renders what it has. 0..=1000000.
    #[arg(long, value_name = "US", default_value_t = 400, value_parser = clap::value_parser!(u64).range(0..=1_000_000))]
    force_wait_us: u64,
    /// Sleep until this long (µs) before each period, then spin (0: sleep to the period's start).
    /// Spinning starts the period on time at the cost of that much of a core every period.
    /// 0..=1000000 (capped at the period).
    #[arg(long, value_name = "US", default_value_t = 150, value_parser = clap::value_parser!(u64).range(0..=1_000_000))]
    spin_margin_us: u64,
    /// Stop after this many seconds, more than 0 and at most 604800 (a week) (default: until
    /// Ctrl-C / SIGTERM).
    #[arg(long, value_name = "S", value_parser = bounded_above_zero(604_800.0))]
    seconds: Option<f64>,
    /// Limit on |F| sent to the device (N), more than 0 and at most 50 (desktop haptic devices
    /// peak at 3–40 N).
    #[arg(long, value_name = "F", default_value_t = 5.0, value_parser = bounded_above_zero(MAX_FORCE_N))]
    max_force_n: f64,
    /// Limit on |τ| sent to the device (N·m), more than 0 and at most 5 (6-DOF desktop devices peak
    /// at 0.1–3 N·m).
    #[arg(long, value_name = "T", default_value_t = 0.05, value_parser = bounded_above_zero(MAX_TORQUE_NM))]
    max_torque_nm: f64,
    /// Device periods without a fresh server force before the ramp to zero starts (default: 10 with
    /// --channel; 50 with --server, where responses arrive every tick but with network jitter).
    /// 1..=10000, and at most 1 s at --rate-hz (the time the device keeps pushing the last force).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=10_000))]
    watchdog_periods: Option<u64>,
    /// The server is taken for gone when no force came for this long (ms), even if its channel
    /// looks intact or its stream stays open (a hung or stopped server, or one in another pid
    /// namespace whose death the bridge cannot see): the force is ramped to zero and the bridge
    /// exits with status 1. With --server the limit is this plus --inject-rtt-ms. With --channel
    /// a server that dies (`kill -9`, a crash) is noticed within about 100 ms whatever this is.
    /// 0: never. 0..=600000.
    #[arg(long, value_name = "MS", default_value_t = 2000, value_parser = clap::value_parser!(u64).range(0..=600_000))]
    server_timeout_ms: u64,
    /// Duration of the ramp to zero (and back) (ms), 0 (a step) ..=60000.
    #[arg(long, value_name = "MS", default_value_t = 50.0, value_parser = bounded(0.0, 60_000.0))]
    ramp_ms: f64,
    /// Virtual-coupling stiffness in x, y and z (N/m), 0..=50000 (desktop devices render at most a
    /// few N/mm); 0 (with --coupling-k-rot 0) disables the coupling.
    #[arg(long, value_name = "N_PER_M", default_value_t = 2000.0, value_parser = bounded(0.0, 50_000.0))]
    coupling_k: f64,
    /// Virtual-coupling stiffness about x, y and z (N·m/rad), 0..=50.
    #[arg(long, value_name = "NM_PER_RAD", default_value_t = 2.0, value_parser = bounded(0.0, 50.0))]
    coupling_k_rot: f64,
    /// Virtual-coupling damping in x, y and z (N·s/m), 0..=1000.
    #[arg(long, value_name = "NS_PER_M", default_value_t = 2.0, value_parser = bounded(0.0, 1_000.0))]
    coupling_b: f64,
    /// Virtual-coupling damping about x, y and z (N·m·s/rad), 0..=10.
    #[arg(long, value_name = "NMS_PER_RAD", default_value_t = 0.002, value_parser = bounded(0.0, 10.0))]
    coupling_b_rot: f64,
    /// Virtual operator (--device virtual): mass in x, y and z (kg), 0.01..=10 (a hand on a stylus).
    #[arg(long, value_name = "KG", value_parser = bounded(0.01, 10.0))]
    operator_mass: Option<f64>,
    /// Virtual operator: damping in x, y and z (N·s/m), 0..=1000.
    #[arg(long, value_name = "NS_PER_M", value_parser = bounded(0.0, 1_000.0))]
    operator_damping: Option<f64>,
    /// Virtual operator: PD proportional gain (grip stiffness) in x, y and z (N/m), 0..=100000.
    #[arg(long, value_name = "N_PER_M", value_parser = bounded(0.0, 100_000.0))]
    operator_kp: Option<f64>,
    /// Virtual operator: PD derivative gain in x, y and z (N·s/m), 0..=1000.
    #[arg(long, value_name = "NS_PER_M", value_parser = bounded(0.0, 1_000.0))]
    operator_kd: Option<f64>,
    /// Print the report as one JSON object on stdout (else a summary on stderr).
    #[arg(long)]
    json: bool,
    /// Write a CSV row per period (t_s, pose, server force, rendered wrench, gain) to this file: for a
    /// 2D session `x_m,y_m,theta_rad` and `(Fx, Fy, τ)`; for a 3D one `x_m,y_m,z_m,qw,qx,qy,qz` and
    /// the six wrench components (N, N·m, world).
    #[arg(long, value_name = "CSV")]
    trace: Option<PathBuf>,
}

/// The largest `--max-force-n` (N): above what any desktop haptic device exerts (Geomagic Touch
/// 3.3 N, Force Dimension omega.x 12 N, sigma.7 20 N, Haption Virtuose 6D 31 N peak).
const MAX_FORCE_N: f64 = 50.0;
/// The largest `--max-torque-nm` (N·m): above the 6-DOF desktop devices' peak torques
/// (sigma.7 0.4 N·m, Phantom Premium 6DOF 0.5 N·m, Virtuose 6D 3.1 N·m).
const MAX_TORQUE_NM: f64 = 5.0;
/// The longest the watchdog may keep rendering the last force without a fresh one
/// (`--watchdog-periods` / `--rate-hz`).
const MAX_WATCHDOG_S: f64 = 1.0;

/// A clap value parser for a finite number in `[lo, hi]`: the error names the range, clap names
/// the flag (issue 35: `--ramp-ms 1e300` panicked, `--max-force-n nan` or `inf` disabled the limit).
fn bounded(lo: f64, hi: f64) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let v: f64 = s.trim().parse().map_err(|e| format!("{e}"))?;
        if v.is_finite() && (lo..=hi).contains(&v) { Ok(v) } else { Err(format!("must be a finite number from {lo} to {hi}")) }
    }
}

/// As [`bounded`], for a number that must be more than 0 and at most `hi`.
fn bounded_above_zero(hi: f64) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let v: f64 = s.trim().parse().map_err(|e| format!("{e}"))?;
        if v.is_finite() && v > 0.0 && v <= hi { Ok(v) } else { Err(format!("must be a finite number more than 0 and at most {hi}")) }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum RenderMode {
    /// w_s + J (q_d − q_s), virtual coupling, watchdog, limits.
    LocalModel,
    /// The last received wrench only (watchdog and limits still apply).
    LastForce,
}

impl Cli {
    fn watchdog_periods(&self) -> u64 {
        self.watchdog_periods.unwrap_or(if self.server.is_some() { 50 } else { 10 })
    }

    /// What one flag's range cannot say: the watchdog's time, `--watchdog-periods` (or its default)
    /// at `--rate-hz`, is at most [`MAX_WATCHDOG_S`]. Checked before anything starts.
    fn check_combined(&self) -> Result<(), String> {
        let watchdog_s = self.watchdog_periods() as f64 / self.rate_hz;
        if watchdog_s > MAX_WATCHDOG_S {
            return Err(format!(
                "--watchdog-periods {} at --rate-hz {} keeps the last force for {watchdog_s} s without a fresh one: at most {MAX_WATCHDOG_S} s \
                 (lower --watchdog-periods or raise --rate-hz)",
                self.watchdog_periods(),
                self.rate_hz
            ));
        }
        Ok(())
    }
}

static STOP: AtomicBool = AtomicBool::new(false);

extern "C" fn on_signal(_: libc::c_int) {
    STOP.store(true, Ordering::Relaxed);
}

fn install_signal_handlers() {
    for sig in [libc::SIGINT, libc::SIGTERM] {
        // SAFETY: the handler only stores to an atomic (async-signal-safe).
        unsafe { libc::signal(sig, on_signal as *const () as libc::sighandler_t) };
    }
}

fn open_device(cli: &Cli) -> Result<Box<dyn Device>> {
    let traj = || -> Result<Trajectory> {
        let path = cli.trajectory.as_ref().with_context(|| format!("--device {:?} needs --trajectory CSV", cli.device))?;
        Trajectory::load(path, cli.looped)
    };
    Ok(match cli.device {
        DeviceKind::Scripted => Box::new(ScriptedDevice::new(traj()?)),
        DeviceKind::Virtual => {
            let mut p = OperatorParams::default();
            let set = |arr: &mut [f64; 6], v: Option<f64>, name: &str, positive: bool| -> Result<()> {
                if let Some(v) = v {
                    if !(v.is_finite() && if positive { v > 0.0 } else { v >= 0.0 }) {
                        bail!("--{name} must be {}, got {v}", if positive { "positive" } else { "non-negative" });
                    }
                    arr[..3].fill(v);
                }
                Ok(())
            };
            set(&mut p.mass, cli.operator_mass, "operator-mass", true)?;
            set(&mut p.damping, cli.operator_damping, "operator-damping", false)?;
            set(&mut p.kp, cli.operator_kp, "operator-kp", false)?;
            set(&mut p.kd, cli.operator_kd, "operator-kd", false)?;
            Box::new(VirtualOperator::new(traj()?, p))
        }
        DeviceKind::Plugin => {
            let lib = cli.plugin.as_ref().context("--device plugin needs --plugin LIB.so")?;
            Box::new(PluginDevice::open(lib, &cli.plugin_config)?)
        }
    })
}

fn main() {
    tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_env_filter(tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "info".into()))
        .init();
    let cli = Cli::parse();
    if let Err(msg) = cli.check_combined() {
        Cli::command().error(clap::error::ErrorKind::ValueValidation, msg).exit();
    }
    install_signal_handlers();
    // The link first: a missing or stale channel, an unreachable server never touches the device.
    let link = match (&cli.channel, &cli.server) {
        (Some(path), _) => DeviceChannel::attach(path).map(|end| Link::Shm(Box::new(end))).map_err(anyhow::Error::from),
        (None, Some(url)) => {
            RemoteLink::connect(RemoteConfig {
                url: url.clone(),
                session_id: cli.session.clone().unwrap_or_default(),
                token: cli.token.clone().unwrap_or_default(),
                inject_rtt: Duration::from_secs_f64(cli.inject_rtt_ms * 1e-3),
                // Just below the device loop's.
                rt_priority: (cli.rt_priority - 1).max(0),
            })
            .map(Link::Remote)
        }
        (None, None) => unreachable!("clap requires --channel or --server"),
    };
    let mut link = match link {
        Ok(l) => l,
        Err(e) => {
            eprintln!("needlesim-bridge: {e:#}");
            std::process::exit(1);
        }
    };
    // A changed channel file that never faults (deleted, replaced, resized) is found by a watcher
    // thread (system calls stay out of the device loop); the loop sees it as a broken channel.
    if let Link::Shm(channel) = &link {
        if !channel.server_identified() {
            tracing::warn!(
                pid = channel.creator_pid(),
                "the server process that created the channel is not visible from here (another pid namespace?): \
                 its death is noticed only when no force comes for --server-timeout-ms"
            );
        }
        let watch = channel.watch();
        let spawned = std::thread::Builder::new().name("channel-watch".into()).spawn(move || {
            while !STOP.load(Ordering::Relaxed) && watch.check_file().is_ok() && watch.check_server().is_ok() {
                std::thread::sleep(WATCH_PERIOD);
            }
        });
        if let Err(e) = spawned {
            eprintln!("needlesim-bridge: cannot start the channel watcher thread: {e}");
            std::process::exit(1);
        }
    }
    let mut device = match open_device(&cli) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("needlesim-bridge: {e:#}");
            std::process::exit(1);
        }
    };
    let (link_name, target) = match (&cli.channel, &cli.server) {
        (Some(p), _) => ("shm", p.display().to_string()),
        (None, s) => ("remote", s.clone().unwrap_or_default()),
    };
    tracing::info!(device = device.name(), link = link_name, to = %target, rate_hz = cli.rate_hz, render = ?cli.render, "starting");
    let mut report = Report {
        device: device.name().to_string(),
        link: link_name.into(),
        render: cli.render.to_possible_value().map_or(String::new(), |v| v.get_name().to_string()),
        inject_rtt_ms: cli.inject_rtt_ms,
        ..Default::default()
    };
    let result = run(&cli, &mut link, device.as_mut(), &mut report);
    // Never leave a haptic device pushing: zero first, whatever happened.
    if let Err(e) = device.write_force([0.0; 6]) {
        eprintln!("needlesim-bridge: writing the final zero force failed: {e:#}");
    }
    device.close();
    if let Link::Remote(r) = &mut link {
        r.close(Duration::from_millis(500));
    }
    let code = match &result {
        Ok(()) => 0,
        Err(e) => {
            report.exit = format!("error: {e:#}");
            1
        }
    };
    if report.periods > 0 || cli.json {
        report.print(cli.json);
    }
    if let Err(e) = result {
        eprintln!("needlesim-bridge: {e:#}");
    }
    std::process::exit(code);
}
