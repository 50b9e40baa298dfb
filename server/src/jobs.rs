//! Concurrency limits of the calls that make the server work without a session: `Simulate`,
//! `Plan` and every `IdentifyService` call. Each call takes a permit before it starts any work
//! and holds it until its worker ends (also when the client goes away); a call finding no free
//! permit is refused at once with RESOURCE_EXHAUSTED, never queued. All kinds share
//! `max_offline_jobs` permits; plans, which use every core, also take one of `max_plans`.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

use tokio::sync::{OwnedSemaphorePermit, Semaphore};

use crate::status::ApiError;

/// The kind of an offline call.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JobKind {
    Simulate,
    Plan,
    Identify,
}

impl JobKind {
    fn name(self) -> &'static str {
        match self {
            JobKind::Simulate => "Simulate",
            JobKind::Plan => "Plan",
            JobKind::Identify => "Identify",
        }
    }
}

/// The permits of the offline calls and counters of their use (read by `/metrics`).
#[derive(Debug)]
pub struct JobLimiter {
    offline: Arc<Semaphore>,
    plans: Arc<Semaphore>,
    max_offline_jobs: usize,
    max_plans: usize,
    running: AtomicUsize,
    /// The most calls that ever ran at once.
    peak: AtomicUsize,
    /// Calls refused with RESOURCE_EXHAUSTED.
    rejected: AtomicU64,
}

/// A running offline call's permit; dropping it frees the slot.
#[derive(Debug)]
pub struct JobPermit {
    _offline: OwnedSemaphorePermit,
    _plan: Option<OwnedSemaphorePermit>,
    limiter: Arc<JobLimiter>,
}

impl Drop for JobPermit {
    fn drop(&mut self) {
        self.limiter.running.fetch_sub(1, Ordering::AcqRel);
    }
}

impl JobLimiter {
    /// At most `max_offline_jobs` offline calls at once, of which at most `max_plans` plans.
    pub fn new(max_offline_jobs: usize, max_plans: usize) -> Arc<Self> {
        Arc::new(Self {
            offline: Arc::new(Semaphore::new(max_offline_jobs)),
            plans: Arc::new(Semaphore::new(max_plans)),
            max_offline_jobs,
            max_plans,
            running: AtomicUsize::new(0),
            peak: AtomicUsize::new(0),
            rejected: AtomicU64::new(0),
        })
    }

    /// A permit for a `kind` call, or RESOURCE_EXHAUSTED naming the limit and its flag.
    pub fn try_start(self: &Arc<Self>, kind: JobKind) -> Result<JobPermit, ApiError> {
        let refuse = |what: String| {
            self.rejected.fetch_add(1, Ordering::Relaxed);
            ApiError::ResourceExhausted(what)
        };
        let plan = match kind {
            JobKind::Plan => Some(self.plans.clone().try_acquire_owned().map_err(|_| {
                refuse(format!("the server already runs its limit of {} plans (server flag --max-plans); try again later", self.max_plans))
            })?),
            _ => None,
        };
        let offline = self.offline.clone().try_acquire_owned().map_err(|_| {
            refuse(format!(
                "{}: the server already runs its limit of {} offline jobs (Simulate, Plan, Identify; server flag --max-offline-jobs); try again later",
                kind.name(),
                self.max_offline_jobs
            ))
        })?;
        let now = self.running.fetch_add(1, Ordering::AcqRel) + 1;
        self.peak.fetch_max(now, Ordering::AcqRel);
        Ok(JobPermit { _offline: offline, _plan: plan, limiter: self.clone() })
    }

    /// Offline calls running now.
    pub fn running(&self) -> usize {
        self.running.load(Ordering::Acquire)
    }

    /// The most offline calls that ever ran at once.
    pub fn peak(&self) -> usize {
        self.peak.load(Ordering::Acquire)
    }

    /// Offline calls refused so far.
    pub fn rejected(&self) -> u64 {
        self.rejected.load(Ordering::Relaxed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permits_are_bounded_per_kind_and_freed_on_drop() {
        let l = JobLimiter::new(3, 1);
        let p1 = l.try_start(JobKind::Plan).unwrap();
        assert!(matches!(l.try_start(JobKind::Plan), Err(ApiError::ResourceExhausted(m)) if m.contains("--max-plans")));
        let s1 = l.try_start(JobKind::Simulate).unwrap();
        let i1 = l.try_start(JobKind::Identify).unwrap();
        assert!(matches!(l.try_start(JobKind::Simulate), Err(ApiError::ResourceExhausted(m)) if m.contains("--max-offline-jobs")));
        assert_eq!((l.running(), l.peak(), l.rejected()), (3, 3, 2));
        drop(p1);
        // The plan's offline slot is free again, and the plan slot too.
        let p2 = l.try_start(JobKind::Plan).unwrap();
        drop((s1, i1, p2));
        assert_eq!((l.running(), l.peak()), (0, 3));
    }
}
