//! The bridge's link to the session: the shared-memory channel or the gRPC remote link, one
//! period's exchange over either, the alignment with the session's tick phase, and the error a
//! lost link ends the bridge with.

use std::sync::atomic::Ordering;
use std::time::Duration;

use anyhow::{Result, anyhow, bail};
use needlesim_bridge::device::DeviceState;
use needlesim_bridge::remote::RemoteLink;
use needlesim_bridge::render::ServerSample;
use needlesim_channel::shm::{Broken, DeviceEnd, DevicePose, ReadStatus, ServerForce, monotonic_ns};
use needlesim_channel::spatial::restrict_planar_stiffness;

use crate::device_loop::{LoopState, RING};
use crate::report::Report;
use crate::{Cli, STOP};

/// The link to the session: the shared-memory channel or the gRPC remote link.
pub(crate) enum Link {
    /// Boxed: the end holds the last force (with its 6 × 6), much larger than the remote link.
    Shm(Box<DeviceEnd>),
    Remote(RemoteLink),
}

/// What one period's exchange with the session gave.
#[derive(Default)]
pub(crate) struct Exchange {
    /// A fresh, valid sample.
    pub(crate) fresh: Option<ServerSample>,
    pub(crate) tick: Option<u64>,
    /// The last value seen (fresh or not), for the trace: tick, wrench.
    pub(crate) last_tick: u64,
    pub(crate) last_wrench: [f64; 6],
    /// The link is gone (channel re-created/closed, remote stream failed).
    pub(crate) lost: bool,
}

/// How long the bridge waits at start for a session that has not published its tick phase yet
/// (its real-time thread publishes it before its first tick, just after creating the channel).
const PHASE_WAIT: Duration = Duration::from_millis(500);

/// Where the device loop's period 0 should fall to run `--phase-lead-us` before the session's
/// ticks (on `CLOCK_MONOTONIC`), or `None` to run on its own phase: no lead, the remote link, a
/// session that published no phase within [`PHASE_WAIT`], or one ticking at another rate (each
/// case but the first says why).
pub(crate) fn align_with_session(cli: &Cli, link: &Link, period: Duration) -> Option<Duration> {
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

/// The session's dimension (2 or 3): from the channel's header, or asked by the remote link (GetSession).
pub(crate) fn session_dimension(link: &Link) -> Result<u32> {
    Ok(match link {
        Link::Shm(channel) => match channel.session_dimension() {
            Some(d) => d as u32,
            None => bail!("device channel: the session's dimension in the header is neither 2 nor 3"),
        },
        Link::Remote(remote) => remote.dimension() as u32,
    })
}

/// One period's exchange over shared memory: write the pose, then read the force (phase-aligned:
/// wait for the one that answers the pose, at most `force_wait`); times the answered poses.
pub(crate) fn exchange_shm(
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
pub(crate) fn exchange_remote(
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
pub(crate) fn lost_link_error(link: &Link, silent_ms: Option<u64>) -> anyhow::Error {
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
