//! The drift-free real-time schedule shared by a session's tick loop (server) and the device loop
//! (bridge), with an injectable [`Clock`].
//!
//! Period k is due at `start + k·period`, computed from the start in integer nanoseconds, so
//! neither the time a period's work takes nor a late wake-up shifts the deadlines after it (no
//! drift). A loop is two calls per period:
//!
//! - [`Schedule::wait`] waits until the next period's deadline (not at all when it has passed)
//!   and returns its index and its lateness (wake-up time − deadline);
//! - [`Schedule::catch_up`], once the period's work is done (or before the next wait), compares
//!   the clock with the next deadline. Behind by one period or more, it skips the periods whose
//!   time has gone (counted in [`CatchUp::skipped_periods`]) and the loop resumes at the latest
//!   period already due, instead of bursting through the missed ones back to back. Behind by less
//!   than a period, the next period runs late, at once ([`CatchUp::late`]).
//!
//! The server counts both as missed deadlines ([`CatchUp::missed_deadlines`], its
//! `missed_deadlines` counter); the bridge counts only the skipped periods (its `missed_periods`,
//! so that executed + missed periods = `--seconds` × rate, which [`Schedule::with_period_limit`]
//! keeps exact by never skipping past the last period).
//!
//! # Sleep, then spin
//!
//! An OS sleep wakes up late: on the 2-core AMD EPYC VM these loops run on, an absolute
//! `clock_nanosleep` to a 1 ms deadline woke 29 µs late at p50, 75 µs at p99 and 0.4 ms at p99.9
//! under SCHED_FIFO while a compiler ran on the other core (≈ 75 µs p50 and milliseconds at p99
//! without SCHED_FIFO). With a spin margin ([`Schedule::with_spin_margin`]), [`Schedule::wait`]
//! sleeps only until `margin` before the deadline and busy-waits the rest
//! ([`Clock::spin`]: `std::hint::spin_loop` between clock reads), so the wake-up is as late as the
//! clock read, not the timer: p99 0.1 µs with a 100 µs margin on the same machine, and only a
//! sleep that overshoots by more than the margin is late (p99.9 99 µs at 100 µs, 48 µs at 200 µs).
//! The price is the margin's worth of a core every period (15 % of a core at 150 µs and 1 kHz):
//! on a 2-core machine each live session and each device loop spinning takes that from the
//! clients, the fan-out and the compiler next door. A zero margin sleeps to the deadline (no
//! spinning). [`Wake`] says whether a wait slept and how long it spun.
//!
//! Nothing here allocates, locks or logs: it runs on real-time threads.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// A monotonic clock the schedule reads, sleeps and spins on.
pub trait Clock {
    /// The time elapsed since the clock's origin (monotonic, never going back).
    fn now(&self) -> Duration;
    /// Blocks the calling thread until [`Clock::now`] is at least `deadline` (it may wake later).
    fn sleep_until(&self, deadline: Duration);
    /// One step of a busy wait between two reads of the clock (a CPU hint; no system call).
    fn spin(&self);
}

/// The system's monotonic clock, `CLOCK_MONOTONIC`, from its own origin (the boot, on Linux), so
/// that two processes on a host read the same times: the server publishes its tick phase on this
/// clock (`shm::ServerEnd::publish_schedule_from_rt`) and the bridge aligns its device loop to it.
/// Sleeps are absolute (`clock_nanosleep` with `TIMER_ABSTIME`, restarted after a signal), so a
/// sleep interrupted or started late never shifts the deadline; spins are `std::hint::spin_loop`.
#[derive(Debug, Clone, Copy, Default)]
pub struct MonotonicClock;

impl MonotonicClock {
    /// The system's monotonic clock.
    pub fn new() -> Self {
        Self
    }
}

impl Clock for MonotonicClock {
    fn now(&self) -> Duration {
        Duration::from_nanos(crate::shm::monotonic_ns())
    }

    fn sleep_until(&self, deadline: Duration) {
        #[cfg(target_os = "linux")]
        {
            let ts = libc::timespec { tv_sec: deadline.as_secs() as libc::time_t, tv_nsec: deadline.subsec_nanos() as libc::c_long };
            // SAFETY: a valid timespec; no remaining time is asked for (absolute sleep).
            while unsafe { libc::clock_nanosleep(libc::CLOCK_MONOTONIC, libc::TIMER_ABSTIME, &ts, std::ptr::null_mut()) } == libc::EINTR {}
        }
        #[cfg(not(target_os = "linux"))]
        {
            let now = self.now();
            if deadline > now {
                std::thread::sleep(deadline - now);
            }
        }
    }

    fn spin(&self) {
        std::hint::spin_loop();
    }
}

/// A clock that moves only when told to, for tests: [`ManualClock::advance`] stands for work, a
/// sleep until a deadline in the future ends exactly at the deadline plus the
/// [`ManualClock::set_oversleep`] amount (a late wake-up), and each spin advances the time by the
/// [`ManualClock::set_spin_step`] amount (1 µs unless set). It counts its sleeps and spins. Clones
/// share the same time and counts.
#[derive(Debug, Clone)]
pub struct ManualClock {
    now_ns: Arc<AtomicU64>,
    oversleep_ns: Arc<AtomicU64>,
    spin_step_ns: Arc<AtomicU64>,
    sleeps: Arc<AtomicU64>,
    spins: Arc<AtomicU64>,
}

impl Default for ManualClock {
    fn default() -> Self {
        Self {
            now_ns: Arc::default(),
            oversleep_ns: Arc::default(),
            spin_step_ns: Arc::new(AtomicU64::new(1_000)),
            sleeps: Arc::default(),
            spins: Arc::default(),
        }
    }
}

impl ManualClock {
    /// A clock at time zero that wakes up exactly on time and spins in steps of 1 µs.
    pub fn new() -> Self {
        Self::default()
    }

    /// Moves the time forward by `duration` (work done between two calls of the schedule).
    pub fn advance(&self, duration: Duration) {
        self.now_ns.fetch_add(duration_ns(duration), Ordering::Relaxed);
    }

    /// Every following sleep wakes up `oversleep` after the time asked for.
    pub fn set_oversleep(&self, oversleep: Duration) {
        self.oversleep_ns.store(duration_ns(oversleep), Ordering::Relaxed);
    }

    /// Every following spin advances the time by `step` (a zero step is taken as 1 ns, so that a
    /// busy wait always ends).
    pub fn set_spin_step(&self, step: Duration) {
        self.spin_step_ns.store(duration_ns(step).max(1), Ordering::Relaxed);
    }

    /// Sleeps so far (calls of [`Clock::sleep_until`] with a deadline in the future).
    pub fn sleeps(&self) -> u64 {
        self.sleeps.load(Ordering::Relaxed)
    }

    /// Spins so far (calls of [`Clock::spin`]).
    pub fn spins(&self) -> u64 {
        self.spins.load(Ordering::Relaxed)
    }
}

impl Clock for ManualClock {
    fn now(&self) -> Duration {
        Duration::from_nanos(self.now_ns.load(Ordering::Relaxed))
    }

    fn sleep_until(&self, deadline: Duration) {
        let deadline = duration_ns(deadline);
        if deadline > self.now_ns.load(Ordering::Relaxed) {
            self.sleeps.fetch_add(1, Ordering::Relaxed);
            self.now_ns.store(deadline.saturating_add(self.oversleep_ns.load(Ordering::Relaxed)), Ordering::Relaxed);
        }
    }

    fn spin(&self) {
        self.spins.fetch_add(1, Ordering::Relaxed);
        self.now_ns.fetch_add(self.spin_step_ns.load(Ordering::Relaxed), Ordering::Relaxed);
    }
}

fn duration_ns(d: Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}

/// One period about to run, as [`Schedule::wait`] returns it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Wake {
    /// The period's index k (0 for the first; skipped periods leave gaps).
    pub index: u64,
    /// Its deadline, `k·period` after the schedule's start.
    pub deadline: Duration,
    /// Wake-up time − deadline (zero when woken early, which a clock does not do).
    pub lateness: Duration,
    /// The wait slept (it found the deadline further away than the spin margin).
    pub slept: bool,
    /// Busy-wait steps ([`Clock::spin`] calls) between the sleep (or the call) and the deadline.
    pub spins: u64,
    /// The time those steps took: from the first clock read of the busy wait to the wake-up.
    pub spun: Duration,
}

/// What [`Schedule::catch_up`] found.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CatchUp {
    /// Periods skipped because the loop was one period or more behind their deadlines.
    pub skipped_periods: u64,
    /// The next period's deadline had passed by less than a period: it runs late, at once.
    pub late: bool,
}

impl CatchUp {
    /// Deadlines missed at this check: the skipped periods, or the one the next period will run past.
    pub fn missed_deadlines(&self) -> u64 {
        self.skipped_periods + u64::from(self.late)
    }
}

/// A drift-free periodic schedule: period k is due at `start + k·period`.
#[derive(Debug)]
pub struct Schedule<C: Clock = MonotonicClock> {
    clock: C,
    start: Duration,
    period: Duration,
    /// Sleep only until this long before a deadline, then spin (zero: sleep to the deadline).
    spin_margin: Duration,
    /// The index of the next period to run.
    next: u64,
    /// Periods in all (the schedule ends after period `limit − 1`), if limited.
    limit: Option<u64>,
    skipped_periods: u64,
    late_periods: u64,
}

impl Schedule<MonotonicClock> {
    /// A schedule on the system's monotonic clock, starting now.
    pub fn start_now(period: Duration) -> Self {
        Self::start(MonotonicClock::new(), period)
    }
}

impl<C: Clock> Schedule<C> {
    /// A schedule on `clock` whose period 0 is due now. A zero `period` is taken as 1 ns.
    pub fn start(clock: C, period: Duration) -> Self {
        let start = clock.now();
        Self::start_at(clock, start, period)
    }

    /// A schedule on `clock` whose period 0 is due at `start` (a time of the clock, which may be
    /// in the past or the future). A zero `period` is taken as 1 ns.
    pub fn start_at(clock: C, start: Duration, period: Duration) -> Self {
        Self {
            clock,
            start,
            period: period.max(Duration::from_nanos(1)),
            spin_margin: Duration::ZERO,
            next: 0,
            limit: None,
            skipped_periods: 0,
            late_periods: 0,
        }
    }

    /// A schedule in phase with another one, on the same clock: period 0 is due at the first time
    /// not before now that lies a whole number of periods after `phase` (another loop's period 0
    /// deadline, moved by an offset). The device loop aligns itself so with the server's ticks.
    pub fn start_in_phase(clock: C, phase: Duration, period: Duration) -> Self {
        let period = period.max(Duration::from_nanos(1));
        let now = clock.now();
        let start = if phase >= now {
            // Whole periods before `phase` that are still not before now.
            let back = (phase - now).as_nanos() / period.as_nanos();
            phase - nanos(back * period.as_nanos())
        } else {
            let ahead = (now - phase).as_nanos().div_ceil(period.as_nanos());
            phase + nanos(ahead * period.as_nanos())
        };
        Self::start_at(clock, start, period)
    }

    /// Waits sleep-then-spin: sleeps until `margin` before each deadline and busy-waits the rest
    /// (see the module docs for the trade-off). A zero margin (the default) sleeps to the deadline.
    pub fn with_spin_margin(mut self, margin: Duration) -> Self {
        self.spin_margin = margin;
        self
    }

    /// Ends the schedule after `periods` periods (run or skipped): a catch-up never skips past the
    /// end, so run + skipped periods = `periods` once [`Schedule::is_finished`].
    pub fn with_period_limit(mut self, periods: u64) -> Self {
        self.limit = Some(periods);
        self
    }

    /// The period.
    pub fn period(&self) -> Duration {
        self.period
    }

    /// The spin margin.
    pub fn spin_margin(&self) -> Duration {
        self.spin_margin
    }

    /// When period 0 is due, in the clock's time (on [`MonotonicClock`]: `CLOCK_MONOTONIC`).
    pub fn start_time(&self) -> Duration {
        self.start
    }

    /// The clock.
    pub fn clock(&self) -> &C {
        &self.clock
    }

    /// The index of the next period [`Schedule::wait`] will return.
    pub fn next_index(&self) -> u64 {
        self.next
    }

    /// With a period limit, whether every period was run or skipped (never without one).
    pub fn is_finished(&self) -> bool {
        self.limit.is_some_and(|n| self.next >= n)
    }

    /// Periods skipped so far (see [`CatchUp::skipped_periods`]).
    pub fn skipped_periods(&self) -> u64 {
        self.skipped_periods
    }

    /// Periods that ran late so far because the one before overran its successor's deadline (see [`CatchUp::late`]).
    pub fn late_periods(&self) -> u64 {
        self.late_periods
    }

    /// Period k's deadline, measured from the schedule's start: k·period, exactly (integer nanoseconds).
    pub fn deadline(&self, k: u64) -> Duration {
        nanos(self.period.as_nanos() * u128::from(k))
    }

    /// Waits until the next period's deadline (returns at once when it has passed) and returns
    /// that period; the following call returns the period after it. With a spin margin, sleeps
    /// until the margin before the deadline, then spins to it (neither when the deadline is
    /// nearer than the margin, or has passed).
    pub fn wait(&mut self) -> Wake {
        let index = self.next;
        let deadline = self.deadline(index);
        let due = self.start + deadline;
        let mut now = self.clock.now();
        let mut slept = false;
        if due > now && due - now > self.spin_margin {
            self.clock.sleep_until(due - self.spin_margin);
            slept = true;
            now = self.clock.now();
        }
        let spin_from = now;
        let mut spins = 0;
        while now < due {
            self.clock.spin();
            spins += 1;
            now = self.clock.now();
        }
        self.next += 1;
        Wake { index, deadline, lateness: now - due, slept, spins, spun: now - spin_from }
    }

    /// Compares the clock with the next period's deadline: a period or more behind, skips ahead
    /// to the latest period already due (never past the period limit); less than a period
    /// behind, reports the next period as late. Call it after a period's work.
    pub fn catch_up(&mut self) -> CatchUp {
        let due = self.start + self.deadline(self.next);
        let now = self.clock.now();
        if now <= due {
            return CatchUp::default();
        }
        let behind_periods = u64::try_from((now - due).as_nanos() / self.period.as_nanos()).unwrap_or(u64::MAX);
        if behind_periods == 0 {
            self.late_periods += 1;
            return CatchUp { skipped_periods: 0, late: true };
        }
        let skipped_periods = match self.limit {
            Some(n) => behind_periods.min(n.saturating_sub(self.next)),
            None => behind_periods,
        };
        self.next += skipped_periods;
        self.skipped_periods += skipped_periods;
        CatchUp { skipped_periods, late: false }
    }
}

/// A duration of `ns` nanoseconds (seconds fit a u64 for any k·period below 5·10¹¹ years).
fn nanos(ns: u128) -> Duration {
    Duration::new((ns / 1_000_000_000) as u64, (ns % 1_000_000_000) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    const MS: Duration = Duration::from_millis(1);

    fn ms(x: f64) -> Duration {
        Duration::from_secs_f64(x * 1e-3)
    }

    #[test]
    fn deadlines_do_not_drift_with_work_or_late_wake_ups() {
        // A period with no exact binary fraction of a second; work and a late wake-up every period.
        let period = Duration::from_nanos(333_333);
        let clock = ManualClock::new();
        clock.set_oversleep(Duration::from_nanos(20_000));
        let mut s = Schedule::start(clock.clone(), period);
        const N: u64 = 1_000_000;
        for k in 0..N {
            let w = s.wait();
            assert_eq!(w.index, k);
            assert_eq!(w.deadline, Duration::from_nanos(333_333 * k));
            // Period 0 is due at the start: no sleep, on time. Later ones wake 20 µs late, never more.
            let expected_lateness = if k == 0 { Duration::ZERO } else { Duration::from_nanos(20_000) };
            assert_eq!(w.lateness, expected_lateness, "period {k}");
            clock.advance(Duration::from_nanos(100_000));
            assert_eq!(s.catch_up(), CatchUp::default(), "period {k}");
        }
        // A schedule that slept one period after each period's work would now be N·(100 + 20) µs behind.
        assert_eq!(clock.now(), Duration::from_nanos(333_333 * (N - 1) + 20_000 + 100_000));
        assert_eq!((s.skipped_periods(), s.late_periods()), (0, 0));
    }

    #[test]
    fn a_period_or_more_behind_skips_ahead_and_counts_the_skipped_periods() {
        let clock = ManualClock::new();
        let mut s = Schedule::start(clock.clone(), MS);
        assert_eq!(s.wait().index, 0);
        clock.advance(ms(3.5)); // period 0 overran the deadlines of periods 1 and 2
        let c = s.catch_up();
        assert_eq!(c, CatchUp { skipped_periods: 2, late: false });
        assert_eq!(c.missed_deadlines(), 2);
        // Resumes at period 3 (due at 3 ms, already passed): at once, 0.5 ms late.
        let w = s.wait();
        assert_eq!((w.index, w.deadline, w.lateness), (3, 3 * MS, ms(0.5)));
        assert_eq!(clock.now(), ms(3.5));
        // Back on time: period 4 sleeps until 4 ms.
        assert_eq!(s.catch_up(), CatchUp::default());
        let w = s.wait();
        assert_eq!((w.index, w.lateness), (4, Duration::ZERO));
        assert_eq!(clock.now(), 4 * MS);
        assert_eq!((s.skipped_periods(), s.late_periods()), (2, 0));
    }

    #[test]
    fn less_than_a_period_behind_runs_the_next_period_late_without_skipping() {
        let clock = ManualClock::new();
        let mut s = Schedule::start(clock.clone(), MS);
        s.wait();
        clock.advance(ms(1.4));
        let c = s.catch_up();
        assert_eq!(c, CatchUp { skipped_periods: 0, late: true });
        assert_eq!(c.missed_deadlines(), 1);
        let w = s.wait();
        assert_eq!((w.index, w.lateness), (1, ms(0.4)));
        assert_eq!(clock.now(), ms(1.4));
        assert_eq!((s.skipped_periods(), s.late_periods()), (0, 1));
    }

    #[test]
    fn the_boundaries_exactly_on_time_and_exactly_one_period_behind() {
        let clock = ManualClock::new();
        let mut s = Schedule::start(clock.clone(), MS);
        s.wait();
        clock.advance(MS); // ends exactly at period 1's deadline: on time
        assert_eq!(s.catch_up(), CatchUp::default());
        assert_eq!(s.wait().lateness, Duration::ZERO);
        clock.advance(2 * MS); // ends exactly at period 3's deadline: period 2 is skipped
        assert_eq!(s.catch_up(), CatchUp { skipped_periods: 1, late: false });
        let w = s.wait();
        assert_eq!((w.index, w.lateness), (3, Duration::ZERO));
    }

    #[test]
    fn a_long_stall_does_not_burst() {
        let clock = ManualClock::new();
        let mut s = Schedule::start(clock.clone(), MS);
        s.wait();
        clock.advance(ms(10.5));
        s.catch_up();
        // Until 20 ms, the loop (no work) runs periods 10 to 20, only the first
        // without sleeping: the 10 missed ones are not run back to back.
        let mut ran = 0;
        let mut ran_without_sleeping = 0;
        while clock.now() < 20 * MS {
            let before = clock.now();
            let w = s.wait();
            ran += 1;
            ran_without_sleeping += u64::from(clock.now() == before);
            assert!(w.lateness < MS, "period {} ran {:?} late", w.index, w.lateness);
            assert_eq!(s.catch_up(), CatchUp::default());
        }
        assert_eq!((ran, ran_without_sleeping), (11, 1));
        assert_eq!(s.skipped_periods(), 9);
    }

    #[test]
    fn the_period_limit_caps_the_skip_so_run_plus_skipped_is_the_limit() {
        let clock = ManualClock::new();
        let mut s = Schedule::start(clock.clone(), MS).with_period_limit(5);
        let mut ran = 0;
        while !s.is_finished() {
            s.wait();
            ran += 1;
            if ran == 2 {
                clock.advance(50 * MS); // far past the end
            }
            s.catch_up();
        }
        assert_eq!(ran, 2);
        assert_eq!(s.skipped_periods(), 3);
        assert_eq!(s.next_index(), 5);
        // Finished: nothing more to skip.
        assert_eq!(s.catch_up(), CatchUp::default());
    }

    #[test]
    fn the_monotonic_clock_sleeps_until_the_deadlines() {
        let t0 = Instant::now();
        let mut s = Schedule::start_now(MS);
        for k in 0..5 {
            assert_eq!(s.wait().index, k);
        }
        // Period 4 is due 4 ms after the start; an overloaded machine may wake later, never earlier.
        assert!(t0.elapsed() >= 4 * MS);
    }

    #[test]
    fn sleep_then_spin_wakes_exactly_at_the_deadline_after_one_sleep() {
        // The sleep wakes 30 µs late, inside the 200 µs margin: the spin ends on the deadline.
        let clock = ManualClock::new();
        clock.set_oversleep(Duration::from_micros(30));
        let mut s = Schedule::start(clock.clone(), MS).with_spin_margin(Duration::from_micros(200));
        let w = s.wait();
        assert_eq!((w.index, w.lateness, w.slept, w.spins), (0, Duration::ZERO, false, 0), "period 0 is due at the start");
        clock.advance(Duration::from_micros(100)); // work
        let w = s.wait();
        // Slept from 0.1 ms until 0.8 ms (woke at 0.83 ms), then 170 spins of 1 µs to 1 ms.
        assert_eq!((w.index, w.lateness, w.slept, w.spins, w.spun), (1, Duration::ZERO, true, 170, Duration::from_micros(170)));
        assert_eq!(clock.now(), MS, "the wake-up is at the deadline, not after");
        assert_eq!((clock.sleeps(), clock.spins()), (1, 170));
    }

    #[test]
    fn a_deadline_nearer_than_the_margin_is_spun_to_without_sleeping() {
        let clock = ManualClock::new();
        clock.set_spin_step(Duration::from_micros(2));
        let mut s = Schedule::start(clock.clone(), MS).with_spin_margin(Duration::from_micros(150));
        s.wait();
        clock.advance(Duration::from_micros(900)); // 100 µs left: less than the margin
        let w = s.wait();
        assert_eq!((w.lateness, w.slept, w.spins), (Duration::ZERO, false, 50));
        assert_eq!(clock.now(), MS);
        assert_eq!((clock.sleeps(), clock.spins()), (0, 50));
    }

    #[test]
    fn a_sleep_overshooting_the_margin_is_late_by_the_rest_and_does_not_spin() {
        let clock = ManualClock::new();
        clock.set_oversleep(Duration::from_micros(250));
        let mut s = Schedule::start(clock.clone(), MS).with_spin_margin(Duration::from_micros(100));
        s.wait();
        let w = s.wait();
        // Slept until 0.9 ms, woke at 1.15 ms: 150 µs late, nothing left to spin.
        assert_eq!((w.lateness, w.slept, w.spins), (Duration::from_micros(150), true, 0));
        assert_eq!((clock.sleeps(), clock.spins()), (1, 0));
    }

    #[test]
    fn a_zero_margin_sleeps_to_the_deadline_and_never_spins() {
        let clock = ManualClock::new();
        clock.set_oversleep(Duration::from_micros(40));
        let mut s = Schedule::start(clock.clone(), MS);
        assert_eq!(s.spin_margin(), Duration::ZERO);
        for k in 0..100u64 {
            let w = s.wait();
            assert_eq!(w.spins, 0);
            assert_eq!(w.lateness, if k == 0 { Duration::ZERO } else { Duration::from_micros(40) });
            s.catch_up();
        }
        assert_eq!((clock.sleeps(), clock.spins()), (99, 0));
    }

    #[test]
    fn sleep_then_spin_keeps_every_deadline_over_many_periods() {
        // Work of 300 µs, sleeps 50 µs late, margin 120 µs, spin steps of 700 ns (not dividing the
        // period): every wake-up within one step of its deadline, one sleep per period.
        let clock = ManualClock::new();
        clock.set_oversleep(Duration::from_micros(50));
        clock.set_spin_step(Duration::from_nanos(700));
        let mut s = Schedule::start(clock.clone(), MS).with_spin_margin(Duration::from_micros(120));
        const N: u64 = 10_000;
        for k in 0..N {
            let w = s.wait();
            assert_eq!(w.index, k);
            assert!(w.lateness < Duration::from_nanos(700), "period {k}: {:?} late", w.lateness);
            assert_eq!(w.slept, k > 0, "period {k}");
            clock.advance(Duration::from_micros(300));
            assert_eq!(s.catch_up(), CatchUp::default());
        }
        assert_eq!(clock.sleeps(), N - 1);
        // 70 µs spun per period: 100 steps of 700 ns.
        assert_eq!(clock.spins(), (N - 1) * 100);
    }

    #[test]
    fn a_schedule_in_phase_starts_at_the_next_aligned_time() {
        let clock = ManualClock::new();
        clock.advance(Duration::from_micros(10_250)); // now: 10.25 ms
        // Another loop's period 0 was due at 3.9 ms: this one's first deadline is 10.9 ms.
        let s = Schedule::start_in_phase(clock.clone(), Duration::from_micros(3_900), MS);
        assert_eq!(s.start_time(), Duration::from_micros(10_900));
        // A phase in the future is moved back to the first aligned time not before now.
        let s = Schedule::start_in_phase(clock.clone(), Duration::from_micros(15_100), MS);
        assert_eq!(s.start_time(), Duration::from_micros(11_100));
        // Exactly now stays now.
        let s = Schedule::start_in_phase(clock.clone(), Duration::from_micros(7_250), MS);
        assert_eq!(s.start_time(), Duration::from_micros(10_250));
        let mut s = s.with_spin_margin(Duration::from_micros(100));
        let w = s.wait();
        assert_eq!((w.index, w.lateness, w.slept), (0, Duration::ZERO, false));
    }

    #[test]
    fn a_schedule_started_in_the_past_catches_up_and_one_in_the_future_waits() {
        let clock = ManualClock::new();
        clock.advance(5 * MS);
        let mut s = Schedule::start_at(clock.clone(), Duration::from_micros(2_500), MS);
        assert_eq!(s.catch_up(), CatchUp { skipped_periods: 2, late: false });
        let w = s.wait();
        assert_eq!((w.index, w.lateness), (2, Duration::from_micros(500)));
        let mut s = Schedule::start_at(clock.clone(), 7 * MS, MS);
        let w = s.wait();
        assert_eq!((w.index, w.lateness, w.slept), (0, Duration::ZERO, true));
        assert_eq!(clock.now(), 7 * MS);
    }

    #[test]
    fn the_monotonic_clock_spins_to_the_deadlines() {
        let t0 = Instant::now();
        let mut s = Schedule::start_now(MS).with_spin_margin(Duration::from_micros(200));
        for k in 0..5 {
            assert_eq!(s.wait().index, k);
        }
        // Never earlier than the deadline; no bound on how late (a loaded machine).
        assert!(t0.elapsed() >= 4 * MS);
        assert!(MonotonicClock.now() >= s.start_time() + 4 * MS);
    }

    #[test]
    fn a_zero_period_is_one_nanosecond() {
        let s = Schedule::start(ManualClock::new(), Duration::ZERO);
        assert_eq!(s.period(), Duration::from_nanos(1));
        assert_eq!(s.deadline(7), Duration::from_nanos(7));
    }
}
