//! The bound on server-streaming calls (issue 35): every stream a client holds open — Observe,
//! WatchScore, WatchUltrasound, GetReport, DownloadRecording — takes a [`StreamPermit`], counted
//! against its session's `--max-observers` (when it watches a session) and the server's
//! `--max-streams`; a call past either is RESOURCE_EXHAUSTED naming the limit. The permit lives in
//! the response stream itself, so a cancelled stream gives its place back as soon as tonic drops
//! the stream. (Control streams are not counted: the control lease admits one per session.
//! Simulate, Plan and Identify are bounded by the offline-job permits, `jobs.rs`.)

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

use needlesim_session::Session;
use tonic::Status;

/// The server's count of open streams.
#[derive(Debug)]
pub struct StreamLimiter {
    max: usize,
    open: Arc<AtomicUsize>,
    refused: AtomicU64,
    /// Streams closed since the allocator last gave memory back ([`StreamLimiter::take_closed`]).
    closed: Arc<AtomicU64>,
}

/// A place among the streams (per session and on the server), given back when dropped.
#[derive(Debug)]
pub struct StreamPermit {
    open: Arc<AtomicUsize>,
    closed: Arc<AtomicU64>,
    session: Option<Arc<AtomicU64>>,
}

impl Drop for StreamPermit {
    fn drop(&mut self) {
        if let Some(n) = &self.session {
            n.fetch_sub(1, Ordering::AcqRel);
        }
        self.open.fetch_sub(1, Ordering::AcqRel);
        self.closed.fetch_add(1, Ordering::Relaxed);
    }
}

impl StreamLimiter {
    pub fn new(max: usize) -> Self {
        Self { max, open: Arc::default(), refused: AtomicU64::new(0), closed: Arc::default() }
    }

    /// Streams open now.
    pub fn open(&self) -> usize {
        self.open.load(Ordering::Acquire)
    }

    /// Streams refused (either limit) since the start.
    pub fn refused(&self) -> u64 {
        self.refused.load(Ordering::Relaxed)
    }

    /// Streams closed since the last call (for the allocator's trim, `serve.rs`).
    pub fn take_closed(&self) -> u64 {
        self.closed.swap(0, Ordering::Relaxed)
    }

    /// A permit for one `what` stream (the call's name, for the message), of `session` if it
    /// watches one (`max_per_session` there, counted in its `n_observers`); checked and counted
    /// in one step, so concurrent calls never exceed either limit.
    pub fn admit(&self, session: Option<&Session>, max_per_session: usize, what: &str) -> Result<StreamPermit, Status> {
        let session_count = match session {
            Some(s) => {
                let max = max_per_session as u64;
                if s.n_observers.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < max).then_some(n + 1)).is_err() {
                    self.refused.fetch_add(1, Ordering::Relaxed);
                    return Err(Status::resource_exhausted(format!(
                        "{what}: session {} has its limit of {max_per_session} observers (--max-observers; its Observe, WatchScore, \
                         WatchUltrasound and GetReport streams count together)",
                        s.id
                    )));
                }
                Some(s.n_observers.clone())
            }
            None => None,
        };
        if self.open.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < self.max).then_some(n + 1)).is_err() {
            if let Some(n) = &session_count {
                n.fetch_sub(1, Ordering::AcqRel);
            }
            self.refused.fetch_add(1, Ordering::Relaxed);
            return Err(Status::resource_exhausted(format!(
                "{what}: the server has its limit of {} open streams (--max-streams); close a stream or try later",
                self.max
            )));
        }
        Ok(StreamPermit { open: self.open.clone(), closed: self.closed.clone(), session: session_count })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_server_limit_refuses_past_it_and_a_dropped_permit_gives_its_place_back() {
        let l = StreamLimiter::new(2);
        let a = l.admit(None, 0, "DownloadRecording").unwrap();
        let _b = l.admit(None, 0, "DownloadRecording").unwrap();
        let e = l.admit(None, 0, "DownloadRecording").unwrap_err();
        assert_eq!(e.code(), tonic::Code::ResourceExhausted);
        assert!(e.message().contains("limit of 2 open streams (--max-streams)"), "{}", e.message());
        assert_eq!((l.open(), l.refused()), (2, 1));
        drop(a);
        assert_eq!(l.open(), 1);
        assert_eq!(l.take_closed(), 1);
        l.admit(None, 0, "DownloadRecording").unwrap();
    }
}
