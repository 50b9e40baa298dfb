//! The bound on server-streaming calls (issue 35): every stream a client holds open — Observe,
//! WatchScore, WatchUltrasound, GetReport, DownloadRecording — takes a [`StreamPermit`], counted
//! against its session's `--max-observers` (when it watches a session) and the server's
//! `--max-streams`; a call past either is RESOURCE_EXHAUSTED naming the limit. The permit lives in
//! the response stream itself, so a cancelled stream gives its place back as soon as tonic drops
//! the stream. (Control streams are not counted: the control lease admits one per session, and one that
//! sends no first message within `--control-first-message-ms` ends, `control.rs`.
//! Simulate, Plan and Identify are bounded by the offline-job permits, `jobs.rs`.)
//!
//! Every stream of a session ends when the session closes (issue 35, H1): [`of_session`] wraps
//! it, and [`Session::close`] signals it first thing. The stream's state (its `Arc<Session>`, its
//! receivers, its permit) is dropped at once by a watcher task, whether or not the client reads;
//! a client that reads gets NOT_FOUND "session X was closed" ([`closed_status`]) as the stream's
//! last message, the status any later call on the session gets.

use std::pin::Pin;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};

use needlesim_session::Session;
use tokio_stream::Stream;
use tonic::Status;

use super::BoxStream;

/// The status a stream of a closed session ends with: NOT_FOUND, as every later call on it.
pub(crate) fn closed_status(session_id: &str) -> Status {
    Status::not_found(format!("session {session_id} was closed"))
}

/// `inner`, a stream of session `s`, ended when `s` closes: its next item is then
/// [`closed_status`], and `inner` (with whatever it holds: the `Arc<Session>`, receivers, its
/// [`StreamPermit`]) is dropped at the close by a watcher task, also while tonic does not poll
/// the stream (a client that does not read). Closed first: records still queued are not sent.
pub(crate) fn of_session<T: Send + 'static>(s: &Session, inner: BoxStream<T>) -> BoxStream<T> {
    until_closed([s.closed(), s.closed()], s.id.clone(), inner)
}

/// [`of_session`] for the session `session_id` whose close both `closed` futures await (one for
/// the watcher task, one polled by the stream).
fn until_closed<T: Send + 'static, F: std::future::Future<Output = ()> + Send + 'static>(
    [closed, closed_too]: [F; 2],
    session_id: String,
    inner: BoxStream<T>,
) -> BoxStream<T> {
    let slot: Arc<Mutex<Option<BoxStream<T>>>> = Arc::new(Mutex::new(Some(inner)));
    let (alive, gone) = tokio::sync::oneshot::channel::<()>();
    let reaped = slot.clone();
    tokio::spawn(async move {
        tokio::select! {
            () = closed => {
                let inner = reaped.lock().expect("session stream lock").take();
                drop(inner);
            }
            // The stream was dropped (ended, or cancelled by its client).
            _ = gone => {}
        }
    });
    Box::pin(SessionStream { slot, closed: Box::pin(closed_too), session_id, ended: false, _alive: alive })
}

/// A stream of a session until it closes ([`of_session`]).
struct SessionStream<T> {
    slot: Arc<Mutex<Option<BoxStream<T>>>>,
    closed: Pin<Box<dyn std::future::Future<Output = ()> + Send>>,
    session_id: String,
    ended: bool,
    /// Dropped with the stream: tells the watcher task to stop.
    _alive: tokio::sync::oneshot::Sender<()>,
}

impl<T> Stream for SessionStream<T> {
    type Item = Result<T, Status>;

    fn poll_next(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Self::Item>> {
        let this = self.get_mut();
        if this.ended {
            return Poll::Ready(None);
        }
        let closed = this.closed.as_mut().poll(cx).is_ready();
        let mut slot = this.slot.lock().expect("session stream lock");
        let item = match slot.as_mut() {
            Some(inner) if !closed => inner.as_mut().poll_next(cx),
            // Closed (the watcher may have dropped the inner stream already).
            _ => Poll::Ready(Some(Err(closed_status(&this.session_id)))),
        };
        if matches!(item, Poll::Ready(None) | Poll::Ready(Some(Err(_)))) {
            this.ended = true;
            let inner = slot.take();
            drop(slot);
            drop(inner);
        }
        item
    }
}

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
    use futures_util::StreamExt as _;

    /// Sets its flag when dropped.
    struct Dropped(Arc<std::sync::atomic::AtomicBool>);

    impl Drop for Dropped {
        fn drop(&mut self) {
            self.0.store(true, Ordering::SeqCst);
        }
    }

    /// A stream that never yields, holding `flag` (as a stream holds its session and permit).
    fn pending_holding(flag: Arc<std::sync::atomic::AtomicBool>) -> BoxStream<u32> {
        let held = Dropped(flag);
        Box::pin(futures_util::stream::pending::<Result<u32, Status>>().map(move |x| {
            let _ = &held;
            x
        }))
    }

    #[tokio::test]
    async fn a_closed_session_drops_its_streams_state_unpolled_and_ends_them_with_not_found() {
        let (tx, rx) = tokio::sync::watch::channel(false);
        let closed = || {
            let mut rx = rx.clone();
            async move {
                let _ = rx.wait_for(|c| *c).await;
            }
        };
        let dropped = Arc::new(std::sync::atomic::AtomicBool::new(false));
        let mut stream = until_closed([closed(), closed()], "abc".into(), pending_holding(dropped.clone()));
        // Open: nothing to send, nothing dropped.
        assert!(tokio::time::timeout(std::time::Duration::from_millis(50), stream.next()).await.is_err());
        assert!(!dropped.load(Ordering::SeqCst));
        // Closed: the inner stream is dropped although nobody polls the outer one.
        tx.send_replace(true);
        let t0 = std::time::Instant::now();
        while !dropped.load(Ordering::SeqCst) {
            assert!(t0.elapsed() < std::time::Duration::from_secs(10), "the inner stream was not dropped");
            tokio::time::sleep(std::time::Duration::from_millis(5)).await;
        }
        let e = stream.next().await.expect("an item").expect_err("the close status");
        assert_eq!((e.code(), e.message()), (tonic::Code::NotFound, "session abc was closed"));
        assert!(stream.next().await.is_none(), "then the end");
    }

    #[tokio::test]
    async fn a_stream_that_ends_before_the_close_ends_plainly_and_its_watcher_stops() {
        let (tx, rx) = tokio::sync::watch::channel(false);
        let closed = || {
            let mut rx = rx.clone();
            async move {
                let _ = rx.wait_for(|c| *c).await;
            }
        };
        let inner: BoxStream<u32> = Box::pin(futures_util::stream::iter([Ok(1), Ok(2)]));
        let stream = until_closed([closed(), closed()], "abc".into(), inner);
        let got: Vec<u32> = stream.map(|r| r.unwrap()).collect().await;
        assert_eq!(got, [1, 2]);
        // The watcher task let go of its receiver when the stream was dropped.
        let t0 = std::time::Instant::now();
        while tx.receiver_count() > 1 {
            assert!(t0.elapsed() < std::time::Duration::from_secs(10), "the watcher task still waits");
            tokio::time::sleep(std::time::Duration::from_millis(5)).await;
        }
    }

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
