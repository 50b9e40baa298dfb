//! Closing abandoned sessions (`--session-idle-timeout-s`): a session that nobody drives, watches
//! or controls for the timeout is closed as CloseSession closes it, so that clients that create
//! sessions and go away (a crashed planning tool, a closed browser tab) cannot hold every session
//! slot for good.
//!
//! A session is *in use* while any stream is open on it (Observe, WatchScore, WatchUltrasound,
//! GetReport: its observer count), a Control stream holds it, or since the last check a pose came
//! from a client or its device, or a bevel flip was asked for. The check runs a few times per
//! timeout on the async runtime and reads only counters; the close itself runs off the runtime.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

use needlesim_session::Session;
use tokio::time::Instant;

use crate::grpc::ServerState;

/// What changes while a session is driven: client poses, device poses, bevel flips.
fn driven(s: &Session) -> u64 {
    let c = &s.counters;
    c.poses_written
        .load(Ordering::Relaxed)
        .wrapping_add(c.device_poses.load(Ordering::Relaxed))
        .wrapping_add(c.bevel_flips_requested.load(Ordering::Relaxed))
}

/// Whether anything is attached to the session now: an open stream or a Control stream's hold.
fn attached(s: &Session) -> bool {
    s.n_observers.load(Ordering::Relaxed) > 0 || s.control.stream_holds()
}

/// How often a session is checked for a timeout: a quarter of it, between 100 ms and 10 s.
pub fn check_period(timeout: Duration) -> Duration {
    (timeout / 4).clamp(Duration::from_millis(100), Duration::from_secs(10))
}

/// Closes the sessions idle for `timeout`, except those in `keep` (the server's own), until the state
/// is dropped (held weakly: this task keeps nothing alive). A session is closed at most
/// `timeout + check_period(timeout)` after its last use.
pub async fn close_idle_sessions(state: std::sync::Weak<ServerState>, timeout: Duration, keep: Vec<String>) {
    let mut every = tokio::time::interval(check_period(timeout));
    every.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    // Per session: what `driven` read last, and when it was last seen in use.
    let mut seen: HashMap<String, (u64, Instant)> = HashMap::new();
    loop {
        every.tick().await;
        let Some(state) = state.upgrade() else {
            return;
        };
        let now = Instant::now();
        let sessions: Vec<Arc<Session>> = state.sessions.read().expect("sessions lock").values().cloned().collect();
        seen.retain(|id, _| sessions.iter().any(|s| &s.id == id));
        for s in sessions {
            if keep.contains(&s.id) {
                continue;
            }
            let d = driven(&s);
            let entry = seen.entry(s.id.clone()).or_insert((d, now));
            if attached(&s) || entry.0 != d {
                *entry = (d, now);
                continue;
            }
            let idle = now.saturating_duration_since(entry.1);
            if idle < timeout {
                continue;
            }
            seen.remove(&s.id);
            tracing::info!(session = %s.id, idle_s = idle.as_secs_f64(), "closing a session nobody used for --session-idle-timeout-s");
            let state = state.clone();
            // Off the runtime: the close joins the real-time thread and finishes the recording.
            let _ = tokio::task::spawn_blocking(move || state.close_session_blocking(&s)).await;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_check_period_is_a_quarter_of_the_timeout_within_bounds() {
        assert_eq!(check_period(Duration::from_secs(1800)), Duration::from_secs(10));
        assert_eq!(check_period(Duration::from_secs(2)), Duration::from_millis(500));
        assert_eq!(check_period(Duration::from_millis(10)), Duration::from_millis(100));
    }
}
