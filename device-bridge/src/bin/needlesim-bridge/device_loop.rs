//! The device loop ([`run`]): one period per device tick on a drift-free schedule, pose out,
//! force in, rendered and written to the device; what it carries from period to period.

use std::io::Write;
use std::sync::atomic::Ordering;
use std::time::Duration;

use anyhow::{Result, bail};
use needlesim_bridge::device::{Device, force_norm};
use needlesim_bridge::remote::RemoteSample;
use needlesim_bridge::render::{RenderParams, Renderer, ServerSample};
use needlesim_channel::schedule::{MonotonicClock, Schedule};
use needlesim_channel::shm::monotonic_ns;

use crate::link::{Link, align_with_session, exchange_remote, exchange_shm, lost_link_error, session_dimension};
use crate::report::Report;
use crate::trace::{open_trace, write_trace_row};
use crate::{Cli, RenderMode, STOP};

/// The write times of the last [`RING`] poses are kept, by counter, to time the force that answers each.
pub(crate) const RING: u64 = 1024;

/// What the device loop carries from period to period, besides the renderer and the report.
pub(crate) struct LoopState {
    pub(crate) written_ns: [u64; RING as usize],
    pub(crate) last_answered: u64,
    pub(crate) remote_last: RemoteSample,
    pub(crate) last_echo_seq: u64,
    pub(crate) prev_buttons: Option<u32>,
    pub(crate) flip_refused_said: bool,
    /// The period in which the link was first found lost.
    pub(crate) lost_since: Option<u64>,
    /// `CLOCK_MONOTONIC` ns of the last fresh force from the link (at first: the loop's start),
    /// the server's heartbeat (`--server-timeout-ms`).
    pub(crate) last_fresh_ns: u64,
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

pub(crate) fn run(cli: &Cli, link: &mut Link, device: &mut dyn Device, report: &mut Report) -> Result<()> {
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
