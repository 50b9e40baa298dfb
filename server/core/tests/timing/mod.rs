//! Step-time collection for the core's `#[ignore]` timing benchmarks (rotating_needle.rs,
//! flexible3_bench.rs): quantiles of all steps and of the steps during which no other process
//! had the core, read from `/proc/thread-self/schedstat`.

// Each benchmark uses a part of it.
#![allow(dead_code)]

use std::time::{Duration, Instant};

/// Time this thread waited on a run queue (ns), from `/proc/thread-self/schedstat`: a step
/// during which it grew was preempted (another process had the core).
pub fn run_queue_wait_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat").ok().and_then(|s| s.split_whitespace().nth(1)?.parse().ok()).unwrap_or(0)
}

/// The load average over 1, 5 and 15 minutes, as `uptime` prints it.
pub fn load_avg() -> String {
    std::fs::read_to_string("/proc/loadavg").map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" ")).unwrap_or_default()
}

/// Step times, each with whether it was preempted.
#[derive(Default)]
pub struct Times {
    pub all: Vec<Duration>,
    pub calm: Vec<Duration>,
}

impl Times {
    pub fn push(&mut self, dt: Duration, preempted: bool) {
        self.all.push(dt);
        if !preempted {
            self.calm.push(dt);
        }
    }

    /// The `p`-quantile of `v` (sorted), µs.
    fn q(v: &[Duration], p: f64) -> f64 {
        v[((v.len() as f64 * p) as usize).min(v.len() - 1)].as_secs_f64() * 1e6
    }

    /// "p50 / p99 / p99.9 / max µs" of all steps, and p99.9 / max without the preempted ones.
    pub fn summary(&mut self) -> String {
        self.all.sort_unstable();
        self.calm.sort_unstable();
        format!(
            "{} steps: p50 {:.1} / p99 {:.1} / p99.9 {:.1} / max {:.1} µs; without the {} preempted: p99.9 {:.1} / max {:.1} µs",
            self.all.len(),
            Self::q(&self.all, 0.5),
            Self::q(&self.all, 0.99),
            Self::q(&self.all, 0.999),
            Self::q(&self.all, 1.0),
            self.all.len() - self.calm.len(),
            Self::q(&self.calm, 0.999),
            Self::q(&self.calm, 1.0)
        )
    }

    /// A Markdown table row: steps, p50 / p99 / p99.9 / max of all steps, preempted steps, and
    /// p50 / p99 / p99.9 / max of the others (µs).
    pub fn row(&mut self) -> String {
        self.all.sort_unstable();
        self.calm.sort_unstable();
        let (a, c) = (&self.all, &self.calm);
        format!(
            "{} | {:.1} | {:.1} | {:.1} | {:.1} | {} | {:.1} | {:.1} | {:.1} | {:.1}",
            a.len(),
            Self::q(a, 0.5),
            Self::q(a, 0.99),
            Self::q(a, 0.999),
            Self::q(a, 1.0),
            a.len() - c.len(),
            Self::q(c, 0.5),
            Self::q(c, 0.99),
            Self::q(c, 0.999),
            Self::q(c, 1.0)
        )
    }
}

/// Times `f` and whether the thread was preempted meanwhile.
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration, bool) {
    let w0 = run_queue_wait_ns();
    let t = Instant::now();
    let r = f();
    let dt = t.elapsed();
    (r, dt, run_queue_wait_ns() > w0)
}
