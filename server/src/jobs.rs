//! Concurrency limits of the calls that make the server work without a session: `Simulate`,
//! `Plan` and every `IdentifyService` call. Each call takes a permit before it starts any work
//! and holds it until its worker ends (also when the client goes away); a call finding no free
//! permit is refused at once with RESOURCE_EXHAUSTED, never queued. All kinds share
//! `max_offline_jobs` permits; plans, which use every core, also take one of `max_plans`.
//!
//! A job streams its messages to its client through [`JobSender`] (issue 35, pass 4: a job blocked
//! in `blocking_send` for as long as its client kept the connection open without reading, so four
//! such calls held every slot for minutes): a message the client does not make room for within
//! `--answer-deadline-ms` stops the job (its slot is freed, what it had queued dropped) and the
//! stream ends with DEADLINE_EXCEEDED naming the flag; counted in `/metrics`
//! (`needlesim_offline_jobs_timed_out`).

use std::pin::Pin;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::Duration;

use futures_util::task::AtomicWaker;
use tokio::sync::{OwnedSemaphorePermit, Semaphore, mpsc};
use tonic::Status;

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
    /// How long a job's client has to make room for its next message (`--answer-deadline-ms`).
    deadline: Duration,
    /// Jobs stopped because their client did not take their messages within `deadline`.
    timed_out: AtomicU64,
}

/// A running offline call's permit; dropping it frees the slot.
#[derive(Debug)]
pub struct JobPermit {
    _offline: OwnedSemaphorePermit,
    _plan: Option<OwnedSemaphorePermit>,
    limiter: Arc<JobLimiter>,
}

impl JobPermit {
    /// The stream of this job's messages ([`JobLimiter::stream`]).
    pub fn stream<T: Send + 'static>(&self, capacity: usize) -> (JobSender<T>, JobStream<T>) {
        self.limiter.stream(capacity)
    }
}

impl Drop for JobPermit {
    fn drop(&mut self) {
        self.limiter.running.fetch_sub(1, Ordering::AcqRel);
    }
}

impl JobLimiter {
    /// At most `max_offline_jobs` offline calls at once, of which at most `max_plans` plans.
    /// A job's client has `deadline` to make room for each of its messages ([`JobSender`]).
    pub fn new(max_offline_jobs: usize, max_plans: usize, deadline: Duration) -> Arc<Self> {
        Arc::new(Self {
            deadline,
            timed_out: AtomicU64::new(0),
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

    /// Offline calls stopped so far because their client did not take their messages in time.
    pub fn timed_out(&self) -> u64 {
        self.timed_out.load(Ordering::Relaxed)
    }

    /// The stream of a job's messages to its client: the job (on a blocking thread) sends through
    /// the [`JobSender`], at most `capacity` messages wait; the call answers the [`JobStream`].
    /// Must be called within the runtime.
    pub fn stream<T: Send + 'static>(self: &Arc<Self>, capacity: usize) -> (JobSender<T>, JobStream<T>) {
        let (tx, rx) = mpsc::channel(capacity);
        let shared = Arc::new(StreamShared { rx: Mutex::new(Some(rx)), ended: Mutex::new(None), waker: AtomicWaker::new() });
        let sender = JobSender { tx, shared: shared.clone(), limiter: self.clone(), runtime: tokio::runtime::Handle::current() };
        (sender, JobStream { shared, done: false })
    }
}

/// What a job's sender and its stream share.
struct StreamShared<T> {
    /// Taken (and the messages waiting dropped) when the job times out.
    rx: Mutex<Option<mpsc::Receiver<Result<T, Status>>>>,
    /// The status the stream ends with once `rx` is taken.
    ended: Mutex<Option<Status>>,
    waker: AtomicWaker,
}

/// The job's end of its stream ([`JobLimiter::stream`]).
pub struct JobSender<T> {
    tx: mpsc::Sender<Result<T, Status>>,
    shared: Arc<StreamShared<T>>,
    limiter: Arc<JobLimiter>,
    runtime: tokio::runtime::Handle,
}

/// The job's stream ended: its client went away, or did not take its messages in time (the
/// stream then ends with DEADLINE_EXCEEDED). The job stops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamEnded;

impl<T> JobSender<T> {
    /// Whether the stream has ended (the job should stop).
    pub fn is_closed(&self) -> bool {
        self.tx.is_closed()
    }

    /// A receiver dropped when the client goes away or the job times out (for a watcher task).
    pub fn closed(&self) -> impl Future<Output = ()> + Send + 'static
    where
        T: Send + 'static,
    {
        let tx = self.tx.clone();
        async move { tx.closed().await }
    }

    /// Sends `item` if there is room now, else drops it (a progress message the next replaces).
    pub fn offer(&self, item: Result<T, Status>) {
        let _ = self.tx.try_send(item);
    }

    /// Sends `item` from the job's blocking thread, waiting at most the deadline for its client
    /// to make room. Never call it on the async runtime.
    pub fn send_blocking(&self, item: Result<T, Status>) -> Result<(), StreamEnded> {
        let item = match self.tx.try_send(item) {
            Ok(()) => return Ok(()),
            Err(mpsc::error::TrySendError::Closed(_)) => return Err(StreamEnded),
            Err(mpsc::error::TrySendError::Full(item)) => item,
        };
        let deadline = self.limiter.deadline;
        // The timer is made inside the runtime (this thread may be outside it: a planner's worker).
        match self.runtime.block_on(async { tokio::time::timeout(deadline, self.tx.send(item)).await }) {
            Ok(Ok(())) => Ok(()),
            Ok(Err(_)) => Err(StreamEnded),
            Err(_) => {
                self.time_out();
                Err(StreamEnded)
            }
        }
    }

    /// Ends the stream with DEADLINE_EXCEEDED and drops what waits in it.
    fn time_out(&self) {
        self.limiter.timed_out.fetch_add(1, Ordering::Relaxed);
        let ms = self.limiter.deadline.as_millis();
        // Counted in /metrics; a log line each would let a client fill the log.
        tracing::debug!(deadline_ms = ms as u64, "an offline job's client did not take its messages: the job stops");
        *self.shared.ended.lock().expect("job stream lock") = Some(Status::deadline_exceeded(format!(
            "the client did not take this call's messages within {ms} ms (--answer-deadline-ms): the job was stopped and its slot freed"
        )));
        let rx = self.shared.rx.lock().expect("job stream lock").take();
        drop(rx);
        self.shared.waker.wake();
    }
}

/// The call's end of a job's stream ([`JobLimiter::stream`]).
pub struct JobStream<T> {
    shared: Arc<StreamShared<T>>,
    done: bool,
}

impl<T> Drop for JobStream<T> {
    fn drop(&mut self) {
        // The client went away: the sender sees the stream closed and the job stops.
        let rx = self.shared.rx.lock().map(|mut rx| rx.take());
        drop(rx);
    }
}

impl<T> tokio_stream::Stream for JobStream<T> {
    type Item = Result<T, Status>;

    fn poll_next(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Self::Item>> {
        if self.done {
            return Poll::Ready(None);
        }
        self.shared.waker.register(cx.waker());
        let polled = self.shared.rx.lock().expect("job stream lock").as_mut().map(|rx| rx.poll_recv(cx));
        match polled {
            Some(Poll::Ready(None)) => {
                self.done = true;
                Poll::Ready(None)
            }
            Some(p) => p,
            // Timed out: the status, then the end.
            None => {
                self.done = true;
                Poll::Ready(self.shared.ended.lock().expect("job stream lock").take().map(Err))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permits_are_bounded_per_kind_and_freed_on_drop() {
        let l = JobLimiter::new(3, 1, Duration::from_secs(30));
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

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_job_whose_client_does_not_read_stops_at_the_deadline() {
        use tokio_stream::StreamExt as _;
        let l = JobLimiter::new(1, 1, Duration::from_millis(300));
        let permit = l.try_start(JobKind::Simulate).unwrap();
        let (tx, mut stream) = l.stream::<u32>(2);
        let job = tokio::task::spawn_blocking(move || {
            let _permit = permit;
            let mut sent = 0;
            while tx.send_blocking(Ok(sent)).is_ok() {
                sent += 1;
            }
            sent
        });
        // Nobody reads: two messages fit, the third waits the deadline, and the job stops.
        let t0 = std::time::Instant::now();
        assert_eq!(job.await.unwrap(), 2);
        assert!(t0.elapsed() >= Duration::from_millis(300), "{:?}", t0.elapsed());
        assert_eq!((l.running(), l.timed_out()), (0, 1));
        // The stream ends with the status (what waited was dropped).
        let e = stream.next().await.expect("a status").expect_err("the deadline");
        assert_eq!(e.code(), tonic::Code::DeadlineExceeded);
        assert!(e.message().contains("within 300 ms (--answer-deadline-ms)"), "{}", e.message());
        assert!(stream.next().await.is_none());

        // A client that reads gets every message and the end.
        let (tx, stream) = l.stream::<u32>(2);
        std::thread::spawn(move || {
            for k in 0..10 {
                tx.send_blocking(Ok(k)).unwrap();
            }
        });
        let got: Vec<u32> = stream.map(|r| r.unwrap()).collect().await;
        assert_eq!(got, (0..10).collect::<Vec<_>>());
        assert_eq!(l.timed_out(), 1);
    }
}
