//! The bound on complete gRPC answers held for clients that do not read them (issue 35, finding 2:
//! 500 GetMesh answers of 3.1 MB to connections with a zero receive window held 1.7 GB, counted
//! by nothing).
//!
//! A gRPC answer that is whole as soon as its handler returns (every unary answer, whatever its
//! size: issue 35, pass 4 — 6,000 unread answers of 64,373 bytes, just under the 64 kB that were
//! counted then, held 475 MB) takes its bytes from the server's [`AnswerBudget`]
//! (`--max-held-answers-mb`); an answer that would pass it is refused with RESOURCE_EXHAUSTED
//! naming the limit. The bytes are given back when the answer is dropped: handed over whole, its
//! stream reset, its connection closed — or not taken whole within `--answer-deadline-ms`, when a
//! timer drops what is left (the client's stream is then reset). The answer is handed to HTTP/2
//! in copies of at most [`CHUNK_BYTES`], and HTTP/2 takes the next copy only once its stream's
//! send buffer (`transport::MAX_SEND_BUF_BYTES`, one chunk) has room (hyper holds one copy
//! waiting for it, h2 buffers up to two): what the client has not read stays here, counted (issue 35, pass 4: with hyper's default buffer of
//! 400 KiB a stream, clients that opened their windows and never read their sockets held 2 GB
//! that the budget had given back). Streams (an answer not whole at once) are bounded elsewhere
//! (`grpc/streams.rs`, `jobs.rs`) and pass through untouched, each holding at most the same
//! per-stream send buffer in HTTP/2.
//!
//! The bound: the bytes of answers held for clients that do not read are at most
//!
//! $$ B_\text{held} \le \text{--max-held-answers-mb} + (\text{MAX\_SEND\_BUF\_BYTES} + 2\,\text{CHUNK\_BYTES}) \cdot S \cdot C $$
//!
//! with $S$ = `--max-streams-per-connection` (100) and $C$ = `--max-connections` (at most 4096):
//! 48 KiB a stream, 4.7 MiB a connection (the budget, 256 MiB by default, is what a few
//! connections can take; the per-stream term is what every connection can hold besides).

use std::collections::VecDeque;
use std::pin::Pin;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::Duration;

use axum::body::Body;
use axum::response::Response;
use bytes::Bytes;
use http_body::{Body as _, Frame};

/// The most bytes of an answer handed to the HTTP/2 layer at once.
pub const CHUNK_BYTES: usize = 16 << 10;
/// How many frames of an answer are read at once to find whether it is whole (a unary answer is
/// its message and its trailers; over gRPC-web, the trailers are a second data frame).
const MAX_FRAMES_READ_AHEAD: usize = 8;

/// The server's bound on answer bytes held for slow readers, and its counters (`/metrics`).
#[derive(Debug)]
pub struct AnswerBudget {
    max_bytes: u64,
    deadline: Duration,
    held_bytes: AtomicU64,
    refused: AtomicU64,
    timed_out: AtomicU64,
    /// Bytes of answers dropped since the allocator last gave memory back
    /// ([`AnswerBudget::take_released`]).
    released_bytes: AtomicU64,
}

impl AnswerBudget {
    pub fn new(max_bytes: u64, deadline: Duration) -> Self {
        Self {
            max_bytes,
            deadline,
            held_bytes: AtomicU64::new(0),
            refused: AtomicU64::new(0),
            timed_out: AtomicU64::new(0),
            released_bytes: AtomicU64::new(0),
        }
    }

    /// Bytes of counted answers held now.
    pub fn held_bytes(&self) -> u64 {
        self.held_bytes.load(Ordering::Relaxed)
    }

    /// Answers refused: the budget was full.
    pub fn refused(&self) -> u64 {
        self.refused.load(Ordering::Relaxed)
    }

    /// Answers dropped because their client did not take them within the deadline.
    pub fn timed_out(&self) -> u64 {
        self.timed_out.load(Ordering::Relaxed)
    }

    /// Whether at least `min_bytes` of answers were dropped since it last said so (the count
    /// then starts again).
    pub fn take_released(&self, min_bytes: u64) -> bool {
        self.released_bytes.fetch_update(Ordering::AcqRel, Ordering::Acquire, |b| (b >= min_bytes).then_some(0)).is_ok()
    }

    /// Takes `bytes` from the budget, or `None` when they do not fit.
    fn reserve(self: &Arc<Self>, bytes: u64) -> Option<AnswerPermit> {
        let fits = self
            .held_bytes
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |held| held.checked_add(bytes).filter(|&n| n <= self.max_bytes))
            .is_ok();
        if !fits {
            self.refused.fetch_add(1, Ordering::Relaxed);
            return None;
        }
        Some(AnswerPermit { budget: self.clone(), bytes })
    }
}

/// Bytes of the budget held by one answer, given back when dropped.
#[derive(Debug)]
struct AnswerPermit {
    budget: Arc<AnswerBudget>,
    bytes: u64,
}

impl Drop for AnswerPermit {
    fn drop(&mut self) {
        self.budget.held_bytes.fetch_sub(self.bytes, Ordering::AcqRel);
        self.budget.released_bytes.fetch_add(self.bytes, Ordering::Relaxed);
    }
}

/// Whether `resp` is a gRPC answer (gRPC-web included).
fn is_grpc(resp: &Response) -> bool {
    resp.headers().get(axum::http::header::CONTENT_TYPE).and_then(|v| v.to_str().ok()).is_some_and(|ct| ct.starts_with("application/grpc"))
}

/// The middleware (`axum::middleware::from_fn`) that counts complete gRPC answers against `budget`.
pub async fn bound_held_answers(budget: Arc<AnswerBudget>, req: axum::extract::Request, next: axum::middleware::Next) -> Response {
    let resp = next.run(req).await;
    if !is_grpc(&resp) {
        return resp;
    }
    let (parts, mut body) = resp.into_parts();
    // What of the answer is ready now, without waiting: a unary answer is whole.
    let mut frames = VecDeque::new();
    let mut whole = false;
    let mut failed = None;
    let mut cx = Context::from_waker(std::task::Waker::noop());
    while frames.len() < MAX_FRAMES_READ_AHEAD {
        match Pin::new(&mut body).poll_frame(&mut cx) {
            Poll::Ready(Some(Ok(frame))) => frames.push_back(frame),
            Poll::Ready(Some(Err(e))) => {
                failed = Some(e);
                break;
            }
            Poll::Ready(None) => {
                whole = true;
                break;
            }
            Poll::Pending => break,
        }
    }
    let data_bytes: u64 = frames.iter().filter_map(|f| f.data_ref()).map(|d| d.len() as u64).sum();
    if !whole || failed.is_some() || data_bytes == 0 {
        // A stream (or a status alone): passed on as it comes.
        let held = Held { frames, permit: None };
        return Response::from_parts(parts, Body::new(AnswerBody::new(held, Some(body), failed, None)));
    }
    let Some(permit) = budget.reserve(data_bytes) else {
        let status = tonic::Status::resource_exhausted(format!(
            "the server holds {} bytes of answers for clients that have not read them; this answer of {data_bytes} bytes would pass the limit of {} bytes (--max-held-answers-mb); try again later",
            budget.held_bytes(),
            budget.max_bytes
        ));
        // Trailers-only, in the call's own content type (gRPC-web clients read it from the headers too).
        let mut refused = status.into_http::<Body>();
        if let Some(ct) = parts.headers.get(axum::http::header::CONTENT_TYPE) {
            refused.headers_mut().insert(axum::http::header::CONTENT_TYPE, ct.clone());
        }
        return refused;
    };
    let held = Held { frames, permit: Some(permit) };
    Response::from_parts(parts, Body::new(AnswerBody::new(held, None, None, Some(budget))))
}

/// What an answer still holds: its frames not yet handed over, and its permit.
struct Held {
    frames: VecDeque<Frame<Bytes>>,
    permit: Option<AnswerPermit>,
}

/// An answer's body: its frames read ahead, then the rest of `inner` (a stream's), handed over in
/// chunks of at most [`CHUNK_BYTES`]. A counted answer is dropped by a timer at the deadline.
struct AnswerBody {
    held: Arc<Mutex<Option<Held>>>,
    inner: Option<Body>,
    failed: Option<axum::Error>,
    deadline_ms: u64,
    /// Dropped with the body: tells the deadline timer to stop.
    _alive: Option<tokio::sync::oneshot::Sender<()>>,
}

impl AnswerBody {
    fn new(held: Held, inner: Option<Body>, failed: Option<axum::Error>, budget: Option<Arc<AnswerBudget>>) -> Self {
        let held = Arc::new(Mutex::new(Some(held)));
        let (mut alive, mut deadline_ms) = (None, 0);
        if let Some(budget) = budget {
            let (tx, gone) = tokio::sync::oneshot::channel::<()>();
            alive = Some(tx);
            deadline_ms = budget.deadline.as_millis() as u64;
            let reaped = held.clone();
            tokio::spawn(async move {
                tokio::select! {
                    () = tokio::time::sleep(budget.deadline) => {
                        let dropped = reaped.lock().expect("answer lock").take();
                        // Anything left (a small answer's data may wait in HTTP/2, its trailers here)
                        // is an answer not taken whole.
                        if dropped.is_some_and(|h| !h.frames.is_empty()) {
                            budget.timed_out.fetch_add(1, Ordering::Relaxed);
                            // Counted in /metrics (`needlesim_held_answers_timed_out`); a log line each would let a
                            // client fill the log.
                            tracing::debug!(deadline_ms = budget.deadline.as_millis() as u64, "an answer not taken by its client within --answer-deadline-ms was dropped");
                        }
                    }
                    _ = gone => {}
                }
            });
        }
        Self { held, inner, failed, deadline_ms, _alive: alive }
    }
}

/// The error that resets the stream of an answer dropped at its deadline.
#[derive(Debug)]
struct NotTaken(u64);

impl std::fmt::Display for NotTaken {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the answer was not taken by the client within {} ms (--answer-deadline-ms)", self.0)
    }
}

impl std::error::Error for NotTaken {}

impl http_body::Body for AnswerBody {
    type Data = Bytes;
    type Error = Box<dyn std::error::Error + Send + Sync>;

    fn poll_frame(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, Self::Error>>> {
        let this = self.get_mut();
        {
            let mut slot = this.held.lock().expect("answer lock");
            let Some(held) = slot.as_mut() else {
                return Poll::Ready(Some(Err(Box::new(NotTaken(this.deadline_ms)))));
            };
            if let Some(frame) = held.frames.pop_front() {
                let frame = match frame.into_data() {
                    Ok(mut data) if data.len() > CHUNK_BYTES => {
                        // A copy: the rest of the answer stays here, where the timer can drop it.
                        let chunk = Bytes::copy_from_slice(&data[..CHUNK_BYTES]);
                        let rest = data.split_off(CHUNK_BYTES);
                        held.frames.push_front(Frame::data(rest));
                        Frame::data(chunk)
                    }
                    Ok(data) => Frame::data(data),
                    Err(other) => other,
                };
                return Poll::Ready(Some(Ok(frame)));
            }
            // All handed over: the bytes go back to the budget.
            if this.inner.is_none() {
                held.permit.take();
            }
        }
        if let Some(e) = this.failed.take() {
            return Poll::Ready(Some(Err(Box::new(e))));
        }
        match this.inner.as_mut() {
            Some(inner) => Pin::new(inner).poll_frame(cx).map_err(|e| Box::new(e) as Self::Error),
            None => Poll::Ready(None),
        }
    }

    fn is_end_stream(&self) -> bool {
        // Dropped at the deadline: not ended, the next poll says why.
        let empty = self.held.lock().ok().and_then(|h| h.as_ref().map(|h| h.frames.is_empty())).unwrap_or(false);
        empty && self.failed.is_none() && self.inner.as_ref().is_none_or(|b| b.is_end_stream())
    }
}
