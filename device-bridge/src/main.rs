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

use std::io::Write;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::{Context, Result, anyhow, bail};
use clap::{CommandFactory, Parser, ValueEnum};
use needlesim_bridge::device::{
    Device, DeviceState, OperatorParams, PluginDevice, ScriptedDevice, Trajectory, VirtualOperator, force_norm,
};
use needlesim_bridge::remote::{RemoteConfig, RemoteLink, RemoteSample};
use needlesim_bridge::render::{Pose6, RenderOutput, RenderParams, Renderer, ServerSample};
use needlesim_channel::schedule::{MonotonicClock, Schedule};
use needlesim_channel::shm::{Broken, DeviceChannel, DeviceEnd, DevicePose, ReadStatus, ServerForce, WATCH_PERIOD, monotonic_ns};
use needlesim_channel::spatial::{restrict_planar_stiffness, wrench_to_planar};

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

#[derive(Debug, Default)]
struct Report {
    device: String,
    periods: u64,
    missed_periods: u64,
    fresh_forces: u64,
    watchdog_periods: u64,
    limited_periods: u64,
    pose_to_force_ns: Vec<u64>,
    force_age_ns: Vec<u64>,
    /// The loop ran phase-aligned with the session's ticks (--phase-lead-us).
    aligned: bool,
    /// Poses a force answered (by its pose counter), and poses superseded before any tick took them.
    answered_poses: u64,
    unanswered_poses: u64,
    /// Poses answered within the period that wrote them (phase-aligned), and waits that ended at
    /// --force-wait-us without a force written after the pose.
    answered_in_period: u64,
    waits_timed_out: u64,
    last_counter: u64,
    last_tick: Option<u64>,
    max_rendered_force_n: f64,
    final_pose: Pose6,
    /// The session's dimension (2 or 3): the report and the trace give 2D or 6-DOF values.
    dimension: u32,
    exit: String,
    link: String,
    render: String,
    inject_rtt_ms: f64,
    dropped_poses: u64,
    last_stiffness: Option<[[f64; 6]; 6]>,
}

fn percentile_us(v: &mut [u64], p: f64) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_unstable();
    let i = ((p * (v.len() - 1) as f64).round() as usize).min(v.len() - 1);
    Some(v[i] as f64 / 1e3)
}

fn json_num(x: Option<f64>) -> String {
    match x {
        Some(v) if v.is_finite() => format!("{v}"),
        _ => "null".into(),
    }
}

fn json_str(s: &str) -> String {
    let mut o = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => o.push_str(&format!("\\u{:04x}", c as u32)),
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

impl Report {
    fn print(&mut self, json: bool) {
        let p2f = [
            percentile_us(&mut self.pose_to_force_ns, 0.5),
            percentile_us(&mut self.pose_to_force_ns, 0.99),
            percentile_us(&mut self.pose_to_force_ns, 0.999),
            percentile_us(&mut self.pose_to_force_ns, 1.0),
        ];
        let age = [percentile_us(&mut self.force_age_ns, 0.5), percentile_us(&mut self.force_age_ns, 0.99)];
        // A 2D session: (x, y, θ) and the 3×3 ∂(Fx, Fy, τ)/∂(x, y, θ); 3D: (x, y, z, qw, qx, qy, qz) and the 6×6, row-major.
        let planar = self.dimension != 3;
        let final_pose: Vec<f64> = if planar {
            self.final_pose.to_planar().to_vec()
        } else {
            self.final_pose.position_m.iter().chain(&self.final_pose.orientation).copied().collect()
        };
        let stiffness: Option<Vec<f64>> = self
            .last_stiffness
            .map(|k| if planar { restrict_planar_stiffness(&k).to_vec() } else { k.iter().flatten().copied().collect() });
        if json {
            println!(
                "{{\"device\":{},\"periods\":{},\"missed_periods\":{},\"fresh_forces\":{},\"watchdog_periods\":{},\"limited_periods\":{},\
                 \"pose_counter\":{},\"last_server_tick\":{},\"pose_to_force_us\":{{\"p50\":{},\"p99\":{},\"p999\":{},\"max\":{}}},\
                 \"force_age_us\":{{\"p50\":{},\"p99\":{}}},\"aligned\":{},\"answered_poses\":{},\"unanswered_poses\":{},\
                 \"answered_in_period\":{},\"waits_timed_out\":{},\
                 \"max_rendered_force_n\":{},\"dimension\":{},\"final_pose\":[{}],\"final_wrench\":[{}],\"link\":{},\"render\":{},\"inject_rtt_ms\":{},\
                 \"dropped_poses\":{},\"stiffness\":{},\"exit\":{}}}",
                json_str(&self.device),
                self.periods,
                self.missed_periods,
                self.fresh_forces,
                self.watchdog_periods,
                self.limited_periods,
                self.last_counter,
                self.last_tick.map_or("null".into(), |t| t.to_string()),
                json_num(p2f[0]),
                json_num(p2f[1]),
                json_num(p2f[2]),
                json_num(p2f[3]),
                json_num(age[0]),
                json_num(age[1]),
                self.aligned,
                self.answered_poses,
                self.unanswered_poses,
                self.answered_in_period,
                self.waits_timed_out,
                self.max_rendered_force_n,
                self.dimension,
                final_pose.iter().map(|v| json_num(Some(*v))).collect::<Vec<_>>().join(","),
                if planar { "0,0,0" } else { "0,0,0,0,0,0" },
                json_str(&self.link),
                json_str(&self.render),
                self.inject_rtt_ms,
                self.dropped_poses,
                stiffness.map_or("null".into(), |j| format!("[{}]", j.iter().map(|v| json_num(Some(*v))).collect::<Vec<_>>().join(","))),
                json_str(&self.exit),
            );
        } else {
            let f = |x: Option<f64>| x.map_or("-".into(), |v| format!("{v:.1}"));
            eprintln!(
                "needlesim-bridge: {} periods ({} missed), {} fresh forces, {} periods under the watchdog, {} limited; \
                 pose→force p50 {} µs p99 {} µs p99.9 {} µs max {} µs ({}: {} poses answered, {} in their period, {} unanswered), \
                 force age p50 {} µs p99 {} µs; exit: {}",
                self.periods,
                self.missed_periods,
                self.fresh_forces,
                self.watchdog_periods,
                self.limited_periods,
                f(p2f[0]),
                f(p2f[1]),
                f(p2f[2]),
                f(p2f[3]),
                if self.aligned { "phase-aligned" } else { "own phase" },
                self.answered_poses,
                self.answered_in_period,
                self.unanswered_poses,
                f(age[0]),
                f(age[1]),
                self.exit
            );
            if let Some(j) = self.last_stiffness.filter(|_| planar).map(|k| restrict_planar_stiffness(&k)) {
                eprintln!(
                    "needlesim-bridge: last stiffness J = ∂(Fx,Fy,τ)/∂(x,y,θ): [{:.1} {:.1} {:.4}; {:.1} {:.1} {:.4}; {:.4} {:.4} {:.5}]",
                    j[0], j[1], j[2], j[3], j[4], j[5], j[6], j[7], j[8]
                );
            }
        }
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

/// The link to the session: the shared-memory channel or the gRPC remote link.
enum Link {
    /// Boxed: the end holds the last force (with its 6 × 6), much larger than the remote link.
    Shm(Box<DeviceEnd>),
    Remote(RemoteLink),
}

/// What one period's exchange with the session gave.
#[derive(Default)]
struct Exchange {
    /// A fresh, valid sample.
    fresh: Option<ServerSample>,
    tick: Option<u64>,
    /// The last value seen (fresh or not), for the trace: tick, wrench.
    last_tick: u64,
    last_wrench: [f64; 6],
    /// The link is gone (channel re-created/closed, remote stream failed).
    lost: bool,
}

/// How long the bridge waits at start for a session that has not published its tick phase yet
/// (its real-time thread publishes it before its first tick, just after creating the channel).
const PHASE_WAIT: Duration = Duration::from_millis(500);

/// Where the device loop's period 0 should fall to run `--phase-lead-us` before the session's
/// ticks (on `CLOCK_MONOTONIC`), or `None` to run on its own phase: no lead, the remote link, a
/// session that published no phase within [`PHASE_WAIT`], or one ticking at another rate (each
/// case but the first says why).
fn align_with_session(cli: &Cli, link: &Link, period: Duration) -> Option<Duration> {
    let Link::Shm(channel) = link else { return None };
    if cli.phase_lead_us == 0 {
        return None;
    }
    let lead = Duration::from_micros(cli.phase_lead_us);
    let give_up = std::time::Instant::now() + PHASE_WAIT;
    let (origin, tick) = loop {
        if let Some(phase) = channel.server_schedule() {
            break phase;
        }
        if std::time::Instant::now() >= give_up || STOP.load(Ordering::Relaxed) {
            tracing::warn!("the session published no tick phase: the device loop runs on its own phase (pose → force takes a period more)");
            return None;
        }
        std::thread::sleep(Duration::from_millis(1));
    };
    if tick != period || lead >= period {
        tracing::warn!(
            session_period = ?tick, device_period = ?period, ?lead,
            "the device loop runs on its own phase: its period is not the session's, or the lead is not shorter than it"
        );
        return None;
    }
    // Period 0 of the session is due at `origin`; ours `lead` before one of its ticks.
    Some(origin.checked_sub(lead).unwrap_or(origin + period - lead))
}

/// The write times of the last [`RING`] poses are kept, by counter, to time the force that answers each.
const RING: u64 = 1024;

/// What the device loop carries from period to period, besides the renderer and the report.
struct LoopState {
    written_ns: [u64; RING as usize],
    last_answered: u64,
    remote_last: RemoteSample,
    last_echo_seq: u64,
    prev_buttons: Option<u32>,
    flip_refused_said: bool,
    /// The period in which the link was first found lost.
    lost_since: Option<u64>,
    /// `CLOCK_MONOTONIC` ns of the last fresh force from the link (at first: the loop's start),
    /// the server's heartbeat (`--server-timeout-ms`).
    last_fresh_ns: u64,
}

impl LoopState {
    fn new() -> Self {
        Self {
            written_ns: [0; RING as usize],
            last_answered: 0,
            remote_last: RemoteSample::default(),
            last_echo_seq: 0,
            prev_buttons: None,
            flip_refused_said: false,
            lost_since: None,
            last_fresh_ns: monotonic_ns(),
        }
    }
}

/// The renderer's parameters from the command line and the device.
fn render_params(cli: &Cli, device: &dyn Device) -> Result<RenderParams> {
    if !(cli.rate_hz.is_finite() && cli.rate_hz > 0.0) {
        bail!("--rate-hz must be positive, got {}", cli.rate_hz);
    }
    let last_force = cli.render == RenderMode::LastForce;
    Ok(RenderParams {
        period_s: 1.0 / cli.rate_hz,
        max_force_n: cli.max_force_n,
        max_torque_nm: cli.max_torque_nm,
        watchdog_periods: cli.watchdog_periods(),
        ramp_s: cli.ramp_ms * 1e-3,
        coupling_k: if last_force { [0.0; 6] } else { RenderParams::per_axis(cli.coupling_k, cli.coupling_k_rot) },
        coupling_b: if last_force { [0.0; 6] } else { RenderParams::per_axis(cli.coupling_b, cli.coupling_b_rot) },
        output: device.output(),
    })
}

/// The session's dimension (2 or 3): from the channel's header, or asked by the remote link (GetSession).
fn session_dimension(link: &Link) -> Result<u32> {
    Ok(match link {
        Link::Shm(channel) => match channel.session_dimension() {
            Some(d) => d as u32,
            None => bail!("device channel: the session's dimension in the header is neither 2 nor 3"),
        },
        Link::Remote(remote) => remote.dimension() as u32,
    })
}

type Trace = std::io::BufWriter<std::fs::File>;

/// The `--trace` CSV with its header (the 2D or the 6-DOF columns), if asked for.
fn open_trace(cli: &Cli, planar: bool) -> Result<Option<Trace>> {
    let Some(p) = &cli.trace else { return Ok(None) };
    let f = std::fs::File::create(p).with_context(|| format!("--trace {}: cannot create", p.display()))?;
    let mut w = std::io::BufWriter::new(f);
    if planar {
        writeln!(w, "t_s,counter,x_m,y_m,theta_rad,fresh,tick,server_fx_n,server_fy_n,server_torque_nm,fx_n,fy_n,torque_nm,gain")?;
    } else {
        writeln!(
            w,
            "t_s,counter,x_m,y_m,z_m,qw,qx,qy,qz,fresh,tick,server_fx_n,server_fy_n,server_fz_n,server_tx_nm,server_ty_nm,server_tz_nm,\
             fx_n,fy_n,fz_n,tx_nm,ty_nm,tz_nm,gain"
        )?;
    }
    Ok(Some(w))
}

/// One period's trace row.
fn write_trace_row(
    w: &mut Trace,
    planar: bool,
    t_s: f64,
    counter: u64,
    state: &DeviceState,
    ex: &Exchange,
    out: &RenderOutput,
) -> Result<()> {
    let fresh = ex.fresh.is_some() as u8;
    if planar {
        let [x, y, th] = state.pose.to_planar();
        let (sw, rw) = (wrench_to_planar(ex.last_wrench), wrench_to_planar(out.wrench));
        writeln!(
            w,
            "{t_s},{counter},{x},{y},{th},{fresh},{},{},{},{},{},{},{},{}",
            ex.last_tick, sw[0], sw[1], sw[2], rw[0], rw[1], rw[2], out.gain
        )?;
    } else {
        // Written field by field: nothing is allocated in the device loop.
        write!(w, "{t_s},{counter}")?;
        for v in state.pose.position_m.iter().chain(&state.pose.orientation) {
            write!(w, ",{v}")?;
        }
        write!(w, ",{fresh},{}", ex.last_tick)?;
        for v in ex.last_wrench.iter().chain(&out.wrench) {
            write!(w, ",{v}")?;
        }
        writeln!(w, ",{}", out.gain)?;
    }
    Ok(())
}

/// The drift-free schedule of the device loop (period k at t0 + k·Δt: needlesim_channel::schedule),
/// t0 just before one of the session's ticks when phase-aligned (`report.aligned`), ending after
/// `--seconds` (executed plus missed periods = S·rate).
fn start_schedule(cli: &Cli, link: &Link, period: Duration, periods_total: Option<u64>, report: &mut Report) -> Schedule {
    let clock = MonotonicClock::new();
    let mut schedule = match align_with_session(cli, link, period) {
        Some(phase) => {
            report.aligned = true;
            Schedule::start_in_phase(clock, phase, period)
        }
        None => Schedule::start(clock, period),
    }
    .with_spin_margin(Duration::from_micros(cli.spin_margin_us).min(period));
    if let Some(n) = periods_total {
        schedule = schedule.with_period_limit(n);
    }
    schedule
}

/// One period's exchange over shared memory: write the pose, then read the force (phase-aligned:
/// wait for the one that answers the pose, at most `force_wait`); times the answered poses.
fn exchange_shm(
    channel: &mut DeviceEnd,
    state: &DeviceState,
    t_pose: u64,
    force_wait: Option<Duration>,
    st: &mut LoopState,
    report: &mut Report,
) -> Exchange {
    let pose = DevicePose {
        t_ns: t_pose,
        position_m: state.pose.position_m,
        orientation: state.pose.orientation,
        buttons: state.buttons,
        counter: 0,
    };
    let written = channel.write_pose_from_device(&pose).ok();
    if let Some(c) = written {
        report.last_counter = c;
        st.written_ns[(c % RING) as usize] = t_pose;
    }
    // Phase-aligned: the tick that takes this pose is due within the lead; wait for its force
    // (spinning: it comes within the tick's compute time), or for any force written after the pose
    // (the tick missed it), at most `force_wait`.
    let wait_until = force_wait.filter(|_| written.is_some()).map(|w| t_pose + w.as_nanos() as u64);
    let mut fresh: Option<ServerForce> = None;
    let sample = loop {
        let sample = channel.read_force_from_device();
        let t_seen = monotonic_ns();
        if let (ReadStatus::Fresh, Some(f)) = (sample.status, sample.value)
            && (f.state == ServerForce::STATE_OK || f.state == ServerForce::STATE_DEVICE_STALE)
        {
            st.last_fresh_ns = t_seen;
            report.force_age_ns.push(t_seen.saturating_sub(f.t_ns));
            // The pose it answers, timed at its first force, if still in the ring.
            let c = f.pose_counter;
            if c > st.last_answered && c <= report.last_counter && report.last_counter - c < RING {
                report.pose_to_force_ns.push(t_seen.saturating_sub(st.written_ns[(c % RING) as usize]));
                report.unanswered_poses += (c - st.last_answered - 1) * u64::from(st.last_answered > 0);
                report.answered_poses += 1;
                report.answered_in_period += u64::from(written == Some(c));
                st.last_answered = c;
            }
            fresh = Some(f);
        }
        let Some(until) = wait_until else { break sample };
        let answered = fresh.is_some_and(|f| f.t_ns >= t_pose || written.is_some_and(|c| f.pose_counter >= c));
        if answered || matches!(sample.status, ReadStatus::Stale | ReadStatus::Broken) {
            break sample;
        }
        if t_seen >= until {
            report.waits_timed_out += 1;
            break sample;
        }
        std::hint::spin_loop();
    };
    // The report's stiffness: the last fresh one (as with the remote link).
    if let Some(f) = &fresh {
        report.last_stiffness = Some(f.stiffness);
    }
    let sv = sample.value.unwrap_or_default();
    Exchange {
        fresh: fresh.as_ref().map(ServerSample::from),
        tick: fresh.map(|f| f.tick),
        last_tick: sv.tick,
        last_wrench: sv.wrench(),
        lost: matches!(sample.status, ReadStatus::Stale | ReadStatus::Broken) || !channel.is_current(),
    }
}

/// Logs the first non-zero stiffness at the needle base (once per run).
fn log_first_stiffness(planar: bool, k: &[[f64; 6]; 6]) {
    if planar {
        let j = restrict_planar_stiffness(k);
        tracing::info!(
            "first stiffness at the needle base: J = [{:.1} {:.1} {:.4}; {:.1} {:.1} {:.4}; {:.4} {:.4} {:.5}]",
            j[0],
            j[1],
            j[2],
            j[3],
            j[4],
            j[5],
            j[6],
            j[7],
            j[8]
        );
    } else {
        tracing::info!(
            "first stiffness at the needle base: K_Fp = ∂F/∂p = [{:.1} {:.1} {:.1}; {:.1} {:.1} {:.1}; {:.1} {:.1} {:.1}] N/m, \
             K_τθ diagonal [{:.5} {:.5} {:.5}] N·m/rad",
            k[0][0],
            k[0][1],
            k[0][2],
            k[1][0],
            k[1][1],
            k[1][2],
            k[2][0],
            k[2][1],
            k[2][2],
            k[3][3],
            k[4][4],
            k[5][5]
        );
    }
}

/// One period's exchange over the remote link: send the pose (and a bevel flip on button 0's
/// rising edge), take the latest response.
fn exchange_remote(
    remote: &mut RemoteLink,
    state: &DeviceState,
    buttons_before: Option<u32>,
    planar: bool,
    t_pose: u64,
    st: &mut LoopState,
    report: &mut Report,
) -> Exchange {
    // Button 0 pressed (rising edge): flip the bevel (the shared-memory server sees the buttons itself).
    if state.buttons & 1 != 0 && buttons_before.is_some_and(|b| b & 1 == 0) {
        if planar {
            remote.request_flip();
        } else if !st.flip_refused_said {
            // Control3 carries no bevel flip.
            st.flip_refused_said = true;
            tracing::warn!("button 0 (bevel flip) is ignored: a 3D session's Control3 stream has no bevel flip");
        }
    }
    if let Some(c) = remote.send_pose(&state.pose, t_pose) {
        report.last_counter = c;
    }
    report.dropped_poses = remote.dropped_poses;
    let fresh = remote.latest();
    let t_seen = monotonic_ns();
    if let Some(r) = &fresh {
        st.last_fresh_ns = t_seen;
        st.remote_last = *r;
        report.force_age_ns.push(t_seen.saturating_sub(r.t_published_ns));
        // The server echoes the newest pose its tick used: a true round trip.
        if r.pose_seq > st.last_echo_seq && r.client_time_ns > 0 {
            st.last_echo_seq = r.pose_seq;
            report.pose_to_force_ns.push(t_seen.saturating_sub(r.client_time_ns));
        }
        if report.last_stiffness.is_none() && r.sample.stiffness.iter().flatten().any(|&v| v != 0.0) {
            log_first_stiffness(planar, &r.sample.stiffness);
        }
        report.last_stiffness = Some(r.sample.stiffness);
    }
    Exchange {
        fresh: fresh.map(|r| r.sample),
        tick: fresh.map(|r| r.tick),
        last_tick: st.remote_last.tick,
        last_wrench: st.remote_last.sample.wrench,
        lost: remote.failure().is_some(),
    }
}

/// The error the bridge exits with once the link is lost and the force ramped out: what became of
/// the server or the channel. A channel whose server died is removed (nobody else will).
/// `silent_ms`: the channel is intact but no force came for that long (`--server-timeout-ms`).
fn lost_link_error(link: &Link, silent_ms: Option<u64>) -> anyhow::Error {
    match link {
        Link::Shm(channel) => {
            let path = channel.path().display();
            match channel.broken() {
                // The normal ends first: a server that closed the channel (and may have exited since).
                _ if channel.closed_or_recreated() => anyhow!("device channel {path}: closed or re-created by the server"),
                Some(Broken::ServerDied { pid }) => {
                    let file = match channel.remove_if_orphaned() {
                        Ok(true) => format!("its device channel {path} was removed"),
                        Ok(false) => format!("its device channel {path} was re-created or removed meanwhile"),
                        Err(e) => format!("its device channel {path} could not be removed: {e}"),
                    };
                    anyhow!("the server (pid {pid}) died without closing the session; the force was ramped to zero and {file}")
                }
                Some(why) => anyhow!("device channel {path} is broken: {why}"),
                None if channel.is_current() && silent_ms.is_some() => {
                    // A server that is gone (killed before this bridge attached, so never seen
                    // dying) leaves its file: removed only when provably stale (no live end holds it).
                    let file = match channel.remove_if_abandoned() {
                        Ok(true) => "no server holds the channel any more, so its file was removed".to_owned(),
                        Ok(false) => "the channel is left to its server".to_owned(),
                        Err(e) => format!("the channel's file could not be examined or removed: {e}"),
                    };
                    anyhow!(
                        "the server (pid {}) stopped answering: no force on device channel {path} for {} ms (--server-timeout-ms); \
                         the force was ramped to zero; {file}",
                        channel.creator_pid(),
                        silent_ms.unwrap_or_default()
                    )
                }
                _ => anyhow!("device channel {path}: closed or re-created by the server"),
            }
        }
        Link::Remote(r) => match (r.failure(), silent_ms) {
            (None, Some(ms)) => anyhow!(
                "remote link: the server stopped answering: no force for {ms} ms (--server-timeout-ms); the force was ramped to zero"
            ),
            (failure, _) => anyhow!("remote link: {}", failure.unwrap_or_default()),
        },
    }
}

fn run(cli: &Cli, link: &mut Link, device: &mut dyn Device, report: &mut Report) -> Result<()> {
    let params = render_params(cli, device)?;
    let (period_s, watchdog_periods) = (params.period_s, params.watchdog_periods);
    let last_force = cli.render == RenderMode::LastForce;
    report.dimension = session_dimension(link)?;
    let planar = report.dimension != 3;
    let mut renderer = Renderer::new(params);
    let mut trace = open_trace(cli, planar)?;
    let periods_total = cli.seconds.map(|s| (s * cli.rate_hz).round().max(0.0) as u64);
    let cap = periods_total.unwrap_or(60_000).min(1 << 22) as usize;
    report.pose_to_force_ns.reserve(cap);
    report.force_age_ns.reserve(cap);
    // The periods the link may stay lost before the bridge gives up: the watchdog's and the ramp's.
    let ramp_out_periods = watchdog_periods + (params.ramp_s / period_s).ceil() as u64 + 1;
    // The remote link's responses come after --inject-rtt-ms's delay line too.
    let server_timeout_ns = match link {
        _ if cli.server_timeout_ms == 0 => 0,
        Link::Shm(_) => cli.server_timeout_ms.saturating_mul(1_000_000),
        Link::Remote(_) => cli.server_timeout_ms.saturating_mul(1_000_000).saturating_add((cli.inject_rtt_ms * 1e6) as u64),
    };

    match needlesim_channel::rt::request_realtime_priority(cli.rt_priority) {
        Ok(()) => tracing::debug!(priority = cli.rt_priority, "the device loop runs with SCHED_FIFO"),
        Err(why) => {
            tracing::warn!("the device loop runs without real-time priority ({why}); periods may be missed under load");
            // Without SCHED_FIFO, sleeps wake up to 50 µs late (the timer slack) unless told otherwise.
            let _ = needlesim_channel::rt::request_precise_timers();
        }
    }
    let period = Duration::from_secs_f64(period_s);
    let mut schedule = start_schedule(cli, link, period, periods_total, report);
    let force_wait = report.aligned.then(|| Duration::from_micros(cli.force_wait_us).min(period * 3 / 4));
    let mut st = LoopState::new();
    loop {
        if STOP.load(Ordering::Relaxed) {
            report.exit = "signal".into();
            return Ok(());
        }
        if schedule.is_finished() {
            report.exit = "done".into();
            return Ok(());
        }
        // A period or more behind: skip (and count) the missed periods rather than burst through
        // them. Less than a period behind, the period runs late (not counted).
        let skipped = schedule.catch_up().skipped_periods;
        if skipped > 0 {
            report.missed_periods += skipped;
            renderer.missed(skipped);
            if schedule.is_finished() {
                continue;
            }
        }
        let t_s = schedule.wait().index as f64 * period_s;
        report.periods += 1;

        let state = device.read_pose(t_s)?;
        report.final_pose = state.pose;
        let buttons_before = st.prev_buttons.replace(state.buttons);
        let t_pose = monotonic_ns();
        let ex = match link {
            Link::Shm(channel) => exchange_shm(channel, &state, t_pose, force_wait, &mut st, report),
            Link::Remote(remote) => exchange_remote(remote, &state, buttons_before, planar, t_pose, &mut st, report),
        };
        if let Some(t) = ex.tick {
            report.fresh_forces += 1;
            report.last_tick = Some(t);
        }
        // The naive scheme: the last wrench as it came, no J term.
        let server = ex.fresh.map(|s| if last_force { ServerSample { stiffness: [[0.0; 6]; 6], ..s } } else { s });
        let out = renderer.update(&state.pose, server.as_ref());
        // Counted once a first force arrived (before it the output is zero for want of data, not the watchdog).
        if out.periods_since_fresh > watchdog_periods && report.fresh_forces > 0 {
            report.watchdog_periods += 1;
        }
        report.limited_periods += out.limited as u64;
        report.max_rendered_force_n = report.max_rendered_force_n.max(force_norm(&out.wrench));
        device.write_force(out.wrench)?;
        if let Some(w) = trace.as_mut() {
            write_trace_row(w, planar, t_s, report.last_counter, &state, &ex, &out)?;
        }
        // The server's heartbeat: a link on which no force came for --server-timeout-ms.
        let silent_ns = t_pose.saturating_sub(st.last_fresh_ns);
        let silent = server_timeout_ns > 0 && silent_ns > server_timeout_ns;
        // A re-created, closed or broken channel, a dead or silent server, a failed remote link:
        // let the watchdog ramp the force out, then stop.
        if ex.lost || silent {
            let since = *st.lost_since.get_or_insert(report.periods);
            if out.wrench == [0.0; 6] || report.periods - since > ramp_out_periods {
                if let Some(w) = trace.as_mut() {
                    w.flush()?;
                }
                return Err(lost_link_error(link, silent.then_some(silent_ns / 1_000_000)));
            }
        }
    }
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
