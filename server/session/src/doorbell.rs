//! A doorbell: how the real-time thread wakes a thread that parks when it has nothing to do (the
//! fan-out, the column worker) as soon as it has queued work for it, without blocking and without
//! a system call while that thread is awake.
//!
//! The waiting thread raises a `sleeping` flag, looks at its queue once more, and parks with a
//! timeout ([`Doorbell::wait_from_worker`]). The real-time thread, after pushing to the queue,
//! reads the flag ([`Doorbell::ring_from_rt`]): down, it does nothing more (a fence and a load);
//! up, it lowers it and unparks the thread (`std::thread::Thread::unpark`: an atomic swap and one
//! futex wake, no allocation, no lock). Both sides put a sequentially consistent fence between
//! their write (the flag; the queue's tail) and their read (the queue; the flag), so at least one
//! of them sees the other's write: either the waiter finds the item and does not park, or the
//! ringer finds the flag and unparks it (Dekker's pattern). A ring that races with a waiter that
//! found its work anyway leaves an unpark token behind, which at worst makes a later park return
//! at once; the waiter then looks again and parks again. The timeout is a safety net (and bounds
//! how long a stop request can go unnoticed), never the normal path: the counts of rings and
//! timeouts say which one delivered.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering, fence};
use std::thread::Thread;
use std::time::{Duration, Instant};

/// Wakes one parked thread when the real-time thread queued something for it.
#[derive(Debug, Default)]
pub(crate) struct Doorbell {
    /// Up while the waiting thread is about to park or parked.
    sleeping: AtomicBool,
    /// The waiting thread, registered by its first wait.
    thread: OnceLock<Thread>,
}

/// How a [`Doorbell::wait_from_worker`] ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Woken {
    /// Work was there when the waiter looked again: it did not park.
    HadWork,
    /// The real-time thread rang: it found the flag up and unparked the waiter.
    Rung,
    /// The timeout passed without a ring and without work (the safety net).
    TimedOut,
}

impl Doorbell {
    /// On the real-time thread, after pushing work: wakes the waiter if it is parked or about to
    /// park. Returns whether it did (the caller counts it). Wait-free when nobody waits (a fence
    /// and a load); otherwise one atomic swap and an unpark (a futex wake).
    pub(crate) fn ring_from_rt(&self) -> bool {
        // Orders the caller's push (the queue's tail) before the load of the flag.
        fence(Ordering::SeqCst);
        if self.sleeping.load(Ordering::Relaxed) && self.sleeping.swap(false, Ordering::SeqCst) {
            if let Some(t) = self.thread.get() {
                t.unpark();
            }
            return true;
        }
        false
    }

    /// On the IO side (closing the session): wakes the waiter whatever its state, so that it sees
    /// the stop flag now rather than at its timeout.
    pub(crate) fn wake_from_io(&self) {
        self.sleeping.store(false, Ordering::SeqCst);
        if let Some(t) = self.thread.get() {
            t.unpark();
        }
    }

    /// On the waiting thread (always the same one), once its queue is empty: parks until the
    /// real-time thread rings, `has_work` says there is work, or `timeout` passes.
    pub(crate) fn wait_from_worker(&self, timeout: Duration, has_work: impl Fn() -> bool) -> Woken {
        let current = self.thread.get_or_init(std::thread::current);
        debug_assert_eq!(current.id(), std::thread::current().id(), "one waiting thread per doorbell");
        let deadline = Instant::now() + timeout;
        self.sleeping.store(true, Ordering::SeqCst);
        // Orders the store of the flag before the look at the queue (see the module docs).
        fence(Ordering::SeqCst);
        loop {
            if has_work() {
                // Down already: a ring raced with this look (its unpark token is harmless).
                return if self.sleeping.swap(false, Ordering::SeqCst) { Woken::HadWork } else { Woken::Rung };
            }
            if !self.sleeping.load(Ordering::SeqCst) {
                return Woken::Rung;
            }
            let now = Instant::now();
            if now >= deadline {
                return if self.sleeping.swap(false, Ordering::SeqCst) { Woken::TimedOut } else { Woken::Rung };
            }
            // May return early (a spurious wake-up, or a token left by an earlier ring): look again.
            std::thread::park_timeout(deadline - now);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use std::sync::atomic::AtomicU64;

    /// A waiter parked with a timeout far longer than any test is woken by the ring, not the
    /// timeout; counts, never times, are asserted.
    #[test]
    fn a_ring_wakes_a_parked_waiter_before_its_timeout() {
        let bell = Arc::new(Doorbell::default());
        let queue = Arc::new(AtomicU64::new(0));
        let (b, q) = (bell.clone(), queue.clone());
        let waiter = std::thread::spawn(move || {
            let mut outcomes = Vec::new();
            let mut taken = 0;
            while taken < 100 {
                let n = q.load(Ordering::SeqCst);
                if n > taken {
                    taken = n;
                    continue;
                }
                outcomes.push(b.wait_from_worker(Duration::from_secs(600), || q.load(Ordering::SeqCst) > taken));
            }
            outcomes
        });
        let mut rings = 0;
        for _ in 0..100 {
            // Give the waiter time to park (no assertion depends on it).
            std::thread::sleep(Duration::from_millis(1));
            queue.fetch_add(1, Ordering::SeqCst);
            rings += u64::from(bell.ring_from_rt());
        }
        let outcomes = waiter.join().unwrap();
        assert!(!outcomes.contains(&Woken::TimedOut), "a wait ended by its timeout: {outcomes:?}");
        let rung = outcomes.iter().filter(|&&o| o == Woken::Rung).count() as u64;
        assert_eq!(rung, rings, "every ring that found the flag up woke a wait, and only those: {outcomes:?}");
        assert!(rings > 0, "the waiter was never parked when work arrived");
    }

    #[test]
    fn nobody_waiting_means_no_wake() {
        let bell = Doorbell::default();
        assert!(!bell.ring_from_rt());
        assert!(!bell.ring_from_rt());
        // A waiter with work already there does not park, and leaves the flag down.
        assert_eq!(bell.wait_from_worker(Duration::from_secs(600), || true), Woken::HadWork);
        assert!(!bell.ring_from_rt());
    }

    #[test]
    fn with_no_work_and_no_ring_the_timeout_ends_the_wait() {
        let bell = Doorbell::default();
        assert_eq!(bell.wait_from_worker(Duration::from_millis(1), || false), Woken::TimedOut);
        assert!(!bell.ring_from_rt(), "the flag is down after a timeout");
    }

    #[test]
    fn a_wake_from_io_ends_a_wait_at_once() {
        let bell = Arc::new(Doorbell::default());
        let b = bell.clone();
        let waiter = std::thread::spawn(move || b.wait_from_worker(Duration::from_secs(600), || false));
        // Until the waiter registered, a wake finds no thread: retry (the waiter never times out).
        while !waiter.is_finished() {
            bell.wake_from_io();
            std::thread::sleep(Duration::from_millis(1));
        }
        assert_eq!(waiter.join().unwrap(), Woken::Rung);
    }
}
