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

/// Lowers the calling thread's scheduling share: its nice value becomes `nice` (1..19; Linux
/// keeps a nice value per thread), so that under contention the threads at the default 0 get
/// about 1.25^nice times its CPU time. For work that may lag (a picture for observers) beside
/// work that must not (the compliance a capture waits for). Errors (nothing changes) for `nice`
/// outside 1..19, when the OS refuses, and on systems other than Linux.
pub fn lower_thread_priority(nice: i32) -> Result<(), String> {
    if !(1..=19).contains(&nice) {
        return Err(format!("nice {nice} is outside 1..19"));
    }
    #[cfg(target_os = "linux")]
    {
        // SAFETY: gettid has no arguments; setpriority with PRIO_PROCESS and a thread id changes
        // that thread's nice value only.
        let rc = unsafe { libc::setpriority(libc::PRIO_PROCESS, libc::gettid() as libc::id_t, nice) };
        if rc == 0 { Ok(()) } else { Err(format!("nice {nice} refused: {}", std::io::Error::last_os_error())) }
    }
    #[cfg(not(target_os = "linux"))]
    {
        Err("thread priorities are only lowered on Linux".to_owned())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_thread_lowers_its_own_priority_only() {
        let nice_of = |tid: i32| {
            let stat = std::fs::read_to_string(format!("/proc/thread-self/../{tid}/stat")).unwrap_or_default();
            // Field 19 (after the parenthesised name): the nice value.
            stat.rsplit(')').next().and_then(|rest| rest.split_whitespace().nth(16)).and_then(|v| v.parse::<i32>().ok())
        };
        let main_tid = unsafe { libc::gettid() };
        let before = nice_of(main_tid);
        let child = std::thread::spawn(move || {
            super::lower_thread_priority(10).unwrap();
            nice_of(unsafe { libc::gettid() })
        })
        .join()
        .unwrap();
        assert_eq!(child, Some(10), "the calling thread's nice value");
        assert_eq!(nice_of(main_tid), before, "other threads keep theirs");
        assert!(super::lower_thread_priority(0).unwrap_err().contains("outside 1..19"));
    }

    #[test]
    fn zero_priority_is_refused_with_a_reason() {
        assert!(super::request_realtime_priority(0).unwrap_err().contains("disabled"));
    }

    #[test]
    fn the_timer_slack_can_be_reduced() {
        std::thread::spawn(|| super::request_precise_timers().unwrap()).join().unwrap();
    }
}
