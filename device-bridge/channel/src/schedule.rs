//! The drift-free real-time schedule shared by a session's tick loop (server) and the device loop
//! (bridge), with an injectable [`Clock`].
//!
//! Period k is due at `start + k·period`, computed from the start in integer nanoseconds, so
//! neither the time a period's work takes nor a late wake-up shifts the deadlines after it (no
//! drift). A loop is two calls per period:
//!
//! - [`Schedule::wait`] sleeps until the next period's deadline (not at all when it has passed)
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
//! Nothing here allocates, locks or logs: it runs on real-time threads.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// A monotonic clock the schedule reads and sleeps on.
pub trait Clock {
    /// The time elapsed since the clock's origin (monotonic, never going back).
    fn now(&self) -> Duration;
    /// Blocks the calling thread for (at least) `duration`.
    fn sleep(&self, duration: Duration);
}

/// The system's monotonic clock ([`Instant`], `CLOCK_MONOTONIC` on Linux) and [`std::thread::sleep`].
#[derive(Debug, Clone, Copy)]
pub struct MonotonicClock {
    origin: Instant,
}

impl MonotonicClock {
    /// A clock whose origin is now.
    pub fn new() -> Self {
        Self { origin: Instant::now() }
    }
}

impl Default for MonotonicClock {
    fn default() -> Self {
        Self::new()
    }
}

impl Clock for MonotonicClock {
    fn now(&self) -> Duration {
        self.origin.elapsed()
    }

    fn sleep(&self, duration: Duration) {
        std::thread::sleep(duration);
    }
}

/// A clock that moves only when told to, for tests: [`ManualClock::advance`] stands for work,
/// and a sleep advances the time by exactly the duration asked for plus the
/// [`ManualClock::set_oversleep`] amount (a late wake-up). Clones share the same time.
#[derive(Debug, Clone, Default)]
pub struct ManualClock {
    now_ns: Arc<AtomicU64>,
    oversleep_ns: Arc<AtomicU64>,
}

impl ManualClock {
    /// A clock at time zero that wakes up exactly on time.
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
}

impl Clock for ManualClock {
    fn now(&self) -> Duration {
        Duration::from_nanos(self.now_ns.load(Ordering::Relaxed))
    }

    fn sleep(&self, duration: Duration) {
        self.advance(duration + Duration::from_nanos(self.oversleep_ns.load(Ordering::Relaxed)));
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
        Self { clock, start, period: period.max(Duration::from_nanos(1)), next: 0, limit: None, skipped_periods: 0, late_periods: 0 }
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
        let ns = self.period.as_nanos() * u128::from(k);
        // Seconds fit a u64 for any k·period below 5·10¹¹ years.
        Duration::new((ns / 1_000_000_000) as u64, (ns % 1_000_000_000) as u32)
    }

    /// Sleeps until the next period's deadline (returns at once when it has passed) and
    /// returns that period; the following call returns the period after it.
    pub fn wait(&mut self) -> Wake {
        let index = self.next;
        let deadline = self.deadline(index);
        let due = self.start + deadline;
        let now = self.clock.now();
        if due > now {
            self.clock.sleep(due - now);
        }
        let lateness = self.clock.now().saturating_sub(due);
        self.next += 1;
        Wake { index, deadline, lateness }
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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn a_zero_period_is_one_nanosecond() {
        let s = Schedule::start(ManualClock::new(), Duration::ZERO);
        assert_eq!(s.period(), Duration::from_nanos(1));
        assert_eq!(s.deadline(7), Duration::from_nanos(7));
    }
}
