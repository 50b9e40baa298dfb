//! Real-time priority and precise timers for the threads that must not be preempted or woken late:
//! a session's tick loop in the server and the device loop in the bridge.

/// Asks the OS to schedule the calling thread with the real-time policy SCHED_FIFO at
/// `priority` (1..99), so that other processes cannot preempt it. Needs CAP_SYS_NICE (or root,
/// or an rtprio limit). Errors (nothing changes) when `priority` ≤ 0, when the OS refuses, and
/// on systems other than Linux; the message says which.
pub fn request_realtime_priority(priority: i32) -> Result<(), String> {
    if priority <= 0 {
        return Err("real-time priority disabled (priority 0)".to_owned());
    }
    #[cfg(target_os = "linux")]
    {
        // SAFETY: pthread_self() is always valid for the calling thread, and `param` lives for
        // the duration of the call.
        let param = libc::sched_param { sched_priority: priority.min(99) };
        let rc = unsafe { libc::pthread_setschedparam(libc::pthread_self(), libc::SCHED_FIFO, &param) };
        if rc == 0 { Ok(()) } else { Err(format!("SCHED_FIFO priority {priority} refused: {}", std::io::Error::from_raw_os_error(rc))) }
    }
    #[cfg(not(target_os = "linux"))]
    {
        Err("real-time priority is only requested on Linux".to_owned())
    }
}

/// Asks the OS to wake the calling thread's timed sleeps on time rather than up to 50 µs late:
/// sets its timer slack to 1 ns (`prctl(PR_SET_TIMERSLACK)`; a SCHED_FIFO thread has none
/// anyway, so this matters when [`request_realtime_priority`] was refused). Errors on systems
/// other than Linux and when the OS refuses.
pub fn request_precise_timers() -> Result<(), String> {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: PR_SET_TIMERSLACK takes one integer argument and affects the calling thread only.
        let rc = unsafe { libc::prctl(libc::PR_SET_TIMERSLACK, 1 as libc::c_ulong) };
        if rc == 0 { Ok(()) } else { Err(format!("PR_SET_TIMERSLACK refused: {}", std::io::Error::last_os_error())) }
    }
    #[cfg(not(target_os = "linux"))]
    {
        Err("timer slack is only set on Linux".to_owned())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn zero_priority_is_refused_with_a_reason() {
        assert!(super::request_realtime_priority(0).unwrap_err().contains("disabled"));
    }

    #[test]
    fn the_timer_slack_can_be_reduced() {
        std::thread::spawn(|| super::request_precise_timers().unwrap()).join().unwrap();
    }
}
