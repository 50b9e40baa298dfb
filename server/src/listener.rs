//! The gRPC port's connections (issue 35): at most `--max-connections` open at once (one more is
//! accepted and closed at once, never queued), and none holds its place without working:
//!
//! - a connection must bring its first request — its headers parsed and handed to the service,
//!   over HTTP/2, HTTP/1.1 or TLS alike — within `--handshake-timeout-ms` of opening, or it is
//!   closed (a bare HTTP/2 preface, a TLS handshake, half of an HTTP/1 request's headers do not
//!   count);
//! - an HTTP/1.1 connection must bring its next request within the same time of its last
//!   response ending (an idle keep-alive connection is closed);
//! - an HTTP/1.1 request body that sends nothing for the same time is ended with an error (its
//!   connection then closes). HTTP/2 request streams are not timed out between messages: `Control`
//!   streams stay open for hours; an idle HTTP/2 connection is pinged and closed when its peer is
//!   gone (`serve.rs`). But a request message that has begun must go on arriving: one that sends
//!   nothing for the same time while the service waits for it ends its call with
//!   DEADLINE_EXCEEDED (HTTP/2 as HTTP/1.1);
//! - one HTTP/2 connection carries at most `--max-streams-per-connection` calls at once (the
//!   SETTINGS_MAX_CONCURRENT_STREAMS it advertises, `serve.rs`);
//! - the bytes of request messages received but not yet complete — what the gRPC decoder holds
//!   until a message is whole — are bounded over the whole server by `--max-pending-request-mb`
//!   ([`PendingBody`]); a call whose next bytes would pass it fails with RESOURCE_EXHAUSTED.
//!
//! Why a global budget and a stall deadline, not one or the other (issue 35: 43 streams each
//! holding 60 MiB of an unfinished message, 3 GB, with every other bound respected): the per-message
//! bound (`--max-message-bytes`) times the streams a connection may open times the connections is
//! no bound at all, so only a budget over the server bounds the memory, as a proxy's overload
//! manager or a buffer limit does; the deadline frees the budget held by a client that stops
//! mid-message, so a stalled client cannot keep it from the others for longer than the deadline.
//! The budget counts bytes as they arrive (not the length a message declares), so holding it costs
//! a client the bytes themselves. A request that is not gRPC (or is gRPC-web text, base64) counts
//! its whole body until it ends.
//!
//! The connection ([`GuardedStream`]) carries a shared state in its `ConnectInfo`
//! ([`GuardInfo`]), which [`ConnGuardLayer`] marks as each request reaches the service and as
//! its response ends. TLS handshakes are bounded by the same time (`serve.rs`). Counted in
//! /metrics.

use std::future::Future;
use std::io;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::task::{Context, Poll};
use std::time::Duration;

use axum::http::{Request, Response, Version};
use bytes::Bytes;
use futures_util::task::AtomicWaker;
use http_body::{Body, Frame, SizeHint};
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::{TcpListener, TcpStream};
use tokio_stream::Stream;
use tonic::transport::server::TcpConnectInfo;

/// The connections of the port.
#[derive(Debug, Default)]
pub struct ConnCounters {
    open: AtomicUsize,
    /// Connections closed since the allocator last gave memory back ([`ConnCounters::take_closed`]).
    closed: AtomicU64,
    refused: AtomicU64,
    timed_out: AtomicU64,
    idle_closed: AtomicU64,
    stalled_bodies: AtomicU64,
    /// Bytes of request messages received and not yet complete, all calls together.
    pending_request_bytes: AtomicU64,
    pending_refused: AtomicU64,
    stalled_messages: AtomicU64,
}

impl ConnCounters {
    /// Connections open now.
    pub fn open(&self) -> usize {
        self.open.load(Ordering::Acquire)
    }

    /// Connections closed since the last call.
    pub fn take_closed(&self) -> u64 {
        self.closed.swap(0, Ordering::Relaxed)
    }

    /// Connections closed at once because `--max-connections` were open.
    pub fn refused(&self) -> u64 {
        self.refused.load(Ordering::Relaxed)
    }

    /// Connections closed because their first request did not arrive in time.
    pub fn timed_out(&self) -> u64 {
        self.timed_out.load(Ordering::Relaxed)
    }

    /// HTTP/1.1 connections closed because their next request did not arrive in time.
    pub fn idle_closed(&self) -> u64 {
        self.idle_closed.load(Ordering::Relaxed)
    }

    /// HTTP/1.1 request bodies ended because they sent nothing for the timeout.
    pub fn stalled_bodies(&self) -> u64 {
        self.stalled_bodies.load(Ordering::Relaxed)
    }

    /// Bytes of request messages received and not yet complete now.
    pub fn pending_request_bytes(&self) -> u64 {
        self.pending_request_bytes.load(Ordering::Acquire)
    }

    /// Calls failed because their message would have passed `--max-pending-request-mb`.
    pub fn pending_refused(&self) -> u64 {
        self.pending_refused.load(Ordering::Relaxed)
    }

    /// Calls ended because a message they had begun sent nothing for the timeout.
    pub fn stalled_messages(&self) -> u64 {
        self.stalled_messages.load(Ordering::Relaxed)
    }
}

/// The default `--max-streams-per-connection` (RFC 9113 recommends advertising no fewer than 100).
pub const DEFAULT_MAX_STREAMS_PER_CONNECTION: u32 = 100;
/// The default `--max-pending-request-mb`: eight messages of the default `--max-message-bytes`.
pub const DEFAULT_MAX_PENDING_REQUEST_MIB: u64 = 512;

/// The bounds of the port.
#[derive(Debug, Clone, Copy)]
pub struct ConnLimits {
    pub max_connections: usize,
    /// Time to the first request; for HTTP/1.1 also between requests and between the frames of a
    /// request body; for every request, between the bytes of a message that has begun.
    pub handshake_timeout: Duration,
    /// HTTP/2 streams open at once on one connection.
    pub max_streams_per_connection: u32,
    /// Bytes of request messages received and not yet complete, over the server.
    pub max_pending_request_bytes: u64,
}

impl Default for ConnLimits {
    fn default() -> Self {
        Self {
            max_connections: default_max_connections(),
            handshake_timeout: Duration::from_secs(5),
            max_streams_per_connection: DEFAULT_MAX_STREAMS_PER_CONNECTION,
            max_pending_request_bytes: DEFAULT_MAX_PENDING_REQUEST_MIB << 20,
        }
    }
}

/// The default `--max-connections`: half the soft limit of open files (the other half for
/// sessions, recordings, device channels, the Foxglove port), at most 4096.
pub fn default_max_connections() -> usize {
    let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
    // SAFETY: getrlimit writes the struct it is given.
    let nofile = if unsafe { libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) } == 0 { lim.rlim_cur } else { 1024 };
    usize::try_from(nofile / 2).unwrap_or(usize::MAX).clamp(16, 4096)
}

/// What the service tells a connection about its requests.
#[derive(Debug, Default)]
struct ConnState {
    /// A request has reached the service.
    served: AtomicBool,
    /// It was HTTP/1 (requests one after another on the connection).
    http1: AtomicBool,
    /// Requests reached the service whose responses have not ended.
    in_flight: AtomicUsize,
    /// The connection's reader, woken when its last request in flight ends (an HTTP/1.1
    /// connection then waits for its next request within the deadline).
    reader: AtomicWaker,
}

/// A connection's `ConnectInfo`: its addresses and what [`ConnGuardLayer`] tells it.
#[derive(Debug, Clone)]
pub struct GuardInfo {
    tcp: TcpConnectInfo,
    state: Arc<ConnState>,
}

/// A connection holding its place among `max_connections`, closed (its reads fail) while it has
/// no request in progress past its deadline (see the module's documentation).
pub struct GuardedStream {
    inner: TcpStream,
    counters: Arc<ConnCounters>,
    state: Arc<ConnState>,
    timeout: Duration,
    /// The deadline, while one runs.
    deadline: Pin<Box<tokio::time::Sleep>>,
    armed: bool,
    /// The deadline passed: every read fails.
    expired: bool,
}

impl Drop for GuardedStream {
    fn drop(&mut self) {
        self.counters.open.fetch_sub(1, Ordering::AcqRel);
        self.counters.closed.fetch_add(1, Ordering::Relaxed);
    }
}

impl GuardedStream {
    /// Whether the connection must bring a request by the deadline now: before its first
    /// request; for HTTP/1.1, also while no request is in progress.
    fn waits_for_a_request(&self) -> bool {
        let s = &self.state;
        !s.served.load(Ordering::Acquire) || (s.http1.load(Ordering::Acquire) && s.in_flight.load(Ordering::Acquire) == 0)
    }
}

impl AsyncRead for GuardedStream {
    fn poll_read(mut self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<io::Result<()>> {
        let this = &mut *self;
        if this.expired {
            return Poll::Ready(Err(io::Error::new(io::ErrorKind::TimedOut, "closed at its request deadline")));
        }
        // Registered before the state is read: a request ending after the read below wakes us.
        this.state.reader.register(cx.waker());
        if this.waits_for_a_request() {
            if !this.armed {
                this.armed = true;
                let at = tokio::time::Instant::now() + this.timeout;
                this.deadline.as_mut().reset(at);
            }
            if this.deadline.as_mut().poll(cx).is_ready() {
                this.expired = true;
                let first = !this.state.served.load(Ordering::Acquire);
                let counter = if first { &this.counters.timed_out } else { &this.counters.idle_closed };
                counter.fetch_add(1, Ordering::Relaxed);
                // The error ends the connection in hyper (or the TLS handshake): the socket closes.
                let what = if first { "no request before the deadline" } else { "no next request before the deadline" };
                return Poll::Ready(Err(io::Error::new(io::ErrorKind::TimedOut, what)));
            }
        } else {
            this.armed = false;
        }
        Pin::new(&mut this.inner).poll_read(cx, buf)
    }
}

impl AsyncWrite for GuardedStream {
    fn poll_write(mut self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &[u8]) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }

    fn poll_write_vectored(mut self: Pin<&mut Self>, cx: &mut Context<'_>, bufs: &[io::IoSlice<'_>]) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write_vectored(cx, bufs)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }
}

impl tonic::transport::server::Connected for GuardedStream {
    type ConnectInfo = GuardInfo;

    fn connect_info(&self) -> Self::ConnectInfo {
        GuardInfo { tcp: tonic::transport::server::Connected::connect_info(&self.inner), state: self.state.clone() }
    }
}

/// The accepted connections of `listener` within `limits`, for `serve_with_incoming`. Accept
/// errors (out of descriptors, a connection reset before it was accepted) are logged and
/// retried after a short pause, never passed on.
pub fn incoming(
    listener: TcpListener,
    limits: ConnLimits,
    counters: Arc<ConnCounters>,
) -> impl Stream<Item = io::Result<GuardedStream>> + Send + 'static {
    futures_util::stream::unfold((listener, counters), move |(listener, counters)| async move {
        loop {
            let (tcp, peer): (TcpStream, SocketAddr) = match listener.accept().await {
                Ok(c) => c,
                Err(e) => {
                    tracing::warn!(error = %e, "cannot accept a connection; retrying in 50 ms");
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            };
            let admitted =
                counters.open.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < limits.max_connections).then_some(n + 1));
            if admitted.is_err() {
                counters.refused.fetch_add(1, Ordering::Relaxed);
                tracing::debug!(%peer, max = limits.max_connections, "connection refused: --max-connections are open");
                drop(tcp);
                continue;
            }
            // State streams are many small messages: no Nagle delay behind an unacknowledged
            // one (tonic's own listener sets this; a failure only costs latency).
            let _ = tcp.set_nodelay(true);
            let conn = GuardedStream {
                inner: tcp,
                counters: counters.clone(),
                state: Arc::default(),
                timeout: limits.handshake_timeout,
                // Runs from the accept.
                deadline: Box::pin(tokio::time::sleep(limits.handshake_timeout)),
                armed: true,
                expired: false,
            };
            return Some((Ok(conn), (listener, counters)));
        }
    })
}

/// The layer (on the whole server) that tells each connection about its requests, and bounds
/// the pauses of HTTP/1.1 request bodies. It puts the connection's [`TcpConnectInfo`] into the
/// request, where tonic's `remote_addr()` finds it.
#[derive(Debug, Clone)]
pub struct ConnGuardLayer {
    counters: Arc<ConnCounters>,
    body_timeout: Duration,
    pending_budget: u64,
}

impl ConnGuardLayer {
    pub fn new(counters: Arc<ConnCounters>, limits: ConnLimits) -> Self {
        Self { counters, body_timeout: limits.handshake_timeout, pending_budget: limits.max_pending_request_bytes }
    }
}

impl<S> tower::Layer<S> for ConnGuardLayer {
    type Service = ConnGuard<S>;

    fn layer(&self, inner: S) -> ConnGuard<S> {
        ConnGuard { inner, layer: self.clone() }
    }
}

/// See [`ConnGuardLayer`].
#[derive(Debug, Clone)]
pub struct ConnGuard<S> {
    inner: S,
    layer: ConnGuardLayer,
}

/// One request in progress on its connection, until its response body is dropped (sent, or the
/// call cancelled).
struct InFlight(Arc<ConnState>);

impl InFlight {
    fn start(state: Arc<ConnState>, version: Version) -> Self {
        if version < Version::HTTP_2 {
            state.http1.store(true, Ordering::Release);
        }
        state.in_flight.fetch_add(1, Ordering::AcqRel);
        state.served.store(true, Ordering::Release);
        Self(state)
    }
}

impl Drop for InFlight {
    fn drop(&mut self) {
        if self.0.in_flight.fetch_sub(1, Ordering::AcqRel) == 1 {
            self.0.reader.wake();
        }
    }
}

type BoxError = Box<dyn std::error::Error + Send + Sync>;

impl<S> tower::Service<Request<tonic::body::Body>> for ConnGuard<S>
where
    S: tower::Service<Request<tonic::body::Body>, Response = Response<tonic::body::Body>> + Send,
    S::Future: Send + 'static,
{
    type Response = Response<tonic::body::Body>;
    type Error = S::Error;
    type Future = Pin<Box<dyn Future<Output = Result<Self::Response, S::Error>> + Send>>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, mut req: Request<tonic::body::Body>) -> Self::Future {
        // tonic puts the connection's ConnectInfo into each request (over TLS too, beside its
        // TlsConnectInfo).
        let info = req.extensions().get::<GuardInfo>().cloned();
        let version = req.version();
        let in_flight = info.map(|info| {
            req.extensions_mut().insert(info.tcp);
            InFlight::start(info.state, version)
        });
        let (timeout, counters) = (self.layer.body_timeout, self.layer.counters.clone());
        let framed = req.headers().get(axum::http::header::CONTENT_TYPE).and_then(|v| v.to_str().ok()).is_some_and(grpc_framed);
        let budget = self.layer.pending_budget;
        if version < Version::HTTP_2 {
            let idle = counters.clone();
            req = req.map(|body| {
                tonic::body::Body::new(PendingBody::new(IdleBody::new(body, timeout, idle), budget, framed, timeout, counters))
            });
        } else {
            req = req.map(|body| tonic::body::Body::new(PendingBody::new(body, budget, framed, timeout, counters)));
        }
        let fut = self.inner.call(req);
        Box::pin(async move {
            let resp = fut.await?;
            Ok(match in_flight {
                Some(guard) => resp.map(|body| tonic::body::Body::new(GuardedBody { inner: body, _in_flight: guard })),
                None => resp,
            })
        })
    }
}

/// A response body that holds its request [`InFlight`] until it is dropped.
struct GuardedBody<B> {
    inner: B,
    _in_flight: InFlight,
}

impl<B: Body<Data = Bytes> + Unpin> Body for GuardedBody<B> {
    type Data = Bytes;
    type Error = B::Error;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, B::Error>>> {
        Pin::new(&mut self.inner).poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}

/// An HTTP/1.1 request body that sent nothing for the timeout while the service waited for it.
#[derive(Debug, thiserror::Error)]
#[error("the request body sent nothing for {} ms", .0.as_millis())]
pub struct BodyStalled(Duration);

/// An HTTP/1.1 request body whose frames must each arrive within `timeout` of the service
/// asking for them; past it, the body ends with [`BodyStalled`] (and hyper closes the
/// connection, whose request was not read to its end).
struct IdleBody<B> {
    inner: B,
    counters: Arc<ConnCounters>,
    /// Runs while the service waits for a frame.
    stall: StallTimer,
    stalled: bool,
}

impl<B> IdleBody<B> {
    fn new(inner: B, timeout: Duration, counters: Arc<ConnCounters>) -> Self {
        Self { inner, counters, stall: StallTimer::new(timeout), stalled: false }
    }
}

/// The deadline of a body's wait for its next frame: it starts when the service first finds no
/// frame, runs across the polls of that wait, and starts again after a frame arrives (the timer
/// is made at the first wait and reset after).
struct StallTimer {
    timeout: Duration,
    wait: Option<Pin<Box<tokio::time::Sleep>>>,
    waiting: bool,
}

impl StallTimer {
    fn new(timeout: Duration) -> Self {
        Self { timeout, wait: None, waiting: false }
    }

    /// A frame arrived, or the wait does not count: the next wait starts a new deadline.
    fn progressed(&mut self) {
        self.waiting = false;
    }

    /// The body has no frame now: whether this wait has lasted `timeout` (else `cx` is woken
    /// when it has).
    fn expired(&mut self, cx: &mut Context<'_>) -> bool {
        let at = tokio::time::Instant::now() + self.timeout;
        let wait = self.wait.get_or_insert_with(|| Box::pin(tokio::time::sleep_until(at)));
        if !self.waiting {
            self.waiting = true;
            wait.as_mut().reset(at);
        }
        wait.as_mut().poll(cx).is_ready()
    }
}

impl<B> Body for IdleBody<B>
where
    B: Body<Data = Bytes> + Unpin,
    B::Error: Into<BoxError>,
{
    type Data = Bytes;
    type Error = BoxError;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, BoxError>>> {
        let this = &mut *self;
        if this.stalled {
            return Poll::Ready(None);
        }
        match Pin::new(&mut this.inner).poll_frame(cx) {
            Poll::Ready(frame) => {
                this.stall.progressed();
                Poll::Ready(frame.map(|f| f.map_err(Into::into)))
            }
            Poll::Pending => {
                if !this.stall.expired(cx) {
                    return Poll::Pending;
                }
                this.stalled = true;
                this.counters.stalled_bodies.fetch_add(1, Ordering::Relaxed);
                Poll::Ready(Some(Err(BodyStalled(this.stall.timeout).into())))
            }
        }
    }

    fn is_end_stream(&self) -> bool {
        self.stalled || self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        if self.stalled { SizeHint::with_exact(0) } else { self.inner.size_hint() }
    }
}

/// Whether a request's body is gRPC's length-prefixed messages as sent (gRPC, gRPC-web binary;
/// not gRPC-web text, which is base64).
fn grpc_framed(content_type: &str) -> bool {
    let ct = content_type.trim_start().to_ascii_lowercase();
    ct.starts_with("application/grpc") && !ct.starts_with("application/grpc-web-text")
}

/// Where a body of gRPC messages is: within a message's 5-byte prefix or within its bytes.
#[derive(Debug, Default)]
struct Framing {
    prefix: [u8; 5],
    /// Bytes of the prefix received (5 once the message's length is known).
    have: usize,
    /// Bytes of the message still to come after its prefix.
    left: u64,
}

impl Framing {
    /// Bytes of the message in progress after `data`, `held` of it received before.
    fn feed(&mut self, mut held: u64, mut data: &[u8]) -> u64 {
        while !data.is_empty() {
            if self.have < 5 {
                let n = (5 - self.have).min(data.len());
                self.prefix[self.have..self.have + n].copy_from_slice(&data[..n]);
                self.have += n;
                held += n as u64;
                data = &data[n..];
                if self.have == 5 {
                    self.left = u64::from(u32::from_be_bytes([self.prefix[1], self.prefix[2], self.prefix[3], self.prefix[4]]));
                }
            } else {
                let n = usize::try_from(self.left).unwrap_or(usize::MAX).min(data.len());
                self.left -= n as u64;
                held += n as u64;
                data = &data[n..];
            }
            if self.have == 5 && self.left == 0 {
                // The message is whole: the decoder takes it and its bytes are freed.
                self.have = 0;
                held = 0;
            }
        }
        held
    }
}

/// A request body whose bytes of messages in progress count against the server's budget
/// (`--max-pending-request-mb`, see the module's documentation), and whose message in progress
/// must not pause for longer than `stall` while the service waits for it.
struct PendingBody<B> {
    inner: B,
    counters: Arc<ConnCounters>,
    budget: u64,
    /// The messages' framing; `None`: the whole body counts until it ends.
    framing: Option<Framing>,
    /// Bytes this body holds in the budget now.
    held: u64,
    /// Runs while the service waits for the rest of a message.
    stall: StallTimer,
    failed: bool,
}

impl<B> PendingBody<B> {
    fn new(inner: B, budget: u64, framed: bool, stall: Duration, counters: Arc<ConnCounters>) -> Self {
        Self { inner, counters, budget, framing: framed.then(Framing::default), held: 0, stall: StallTimer::new(stall), failed: false }
    }

    fn release(&mut self) {
        let held = std::mem::take(&mut self.held);
        if held > 0 {
            self.counters.pending_request_bytes.fetch_sub(held, Ordering::AcqRel);
        }
    }

    /// Ends the call with `status`: nothing more is read of the body.
    fn fail(&mut self, status: tonic::Status) -> Poll<Option<Result<Frame<Bytes>, BoxError>>> {
        self.failed = true;
        self.release();
        Poll::Ready(Some(Err(Box::new(status))))
    }
}

impl<B> Drop for PendingBody<B> {
    fn drop(&mut self) {
        self.release();
    }
}

impl<B> Body for PendingBody<B>
where
    B: Body<Data = Bytes> + Unpin,
    B::Error: Into<BoxError>,
{
    type Data = Bytes;
    type Error = BoxError;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, BoxError>>> {
        let this = &mut *self;
        if this.failed {
            return Poll::Ready(None);
        }
        match Pin::new(&mut this.inner).poll_frame(cx) {
            Poll::Ready(Some(Ok(frame))) => {
                this.stall.progressed();
                if let Some(data) = frame.data_ref() {
                    let after = match &mut this.framing {
                        Some(f) => f.feed(this.held, data),
                        None => this.held.saturating_add(data.len() as u64),
                    };
                    if after > this.held {
                        let (add, budget) = (after - this.held, this.budget);
                        let admitted = this
                            .counters
                            .pending_request_bytes
                            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |p| p.checked_add(add).filter(|&n| n <= budget));
                        if admitted.is_err() {
                            this.counters.pending_refused.fetch_add(1, Ordering::Relaxed);
                            return this.fail(tonic::Status::resource_exhausted(format!(
                                "the request messages being received on this server hold {} MiB, its bound \
                                 (--max-pending-request-mb): this call's message in progress ({after} bytes so far) is refused",
                                budget >> 20
                            )));
                        }
                    } else {
                        this.counters.pending_request_bytes.fetch_sub(this.held - after, Ordering::AcqRel);
                    }
                    this.held = after;
                }
                Poll::Ready(Some(Ok(frame)))
            }
            Poll::Ready(Some(Err(e))) => {
                this.release();
                Poll::Ready(Some(Err(e.into())))
            }
            Poll::Ready(None) => {
                this.release();
                Poll::Ready(None)
            }
            Poll::Pending => {
                if this.held == 0 {
                    // Between messages: a stream may wait as long as it likes.
                    this.stall.progressed();
                    return Poll::Pending;
                }
                if !this.stall.expired(cx) {
                    return Poll::Pending;
                }
                this.counters.stalled_messages.fetch_add(1, Ordering::Relaxed);
                let held = this.held;
                this.fail(tonic::Status::deadline_exceeded(format!(
                    "the request message stopped arriving: nothing for {} ms (--handshake-timeout-ms) after {held} bytes of it",
                    this.stall.timeout.as_millis()
                )))
            }
        }
    }

    fn is_end_stream(&self) -> bool {
        self.failed || self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        if self.failed { SizeHint::with_exact(0) } else { self.inner.size_hint() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_counts_the_bytes_of_the_message_in_progress() {
        let mut f = Framing::default();
        // A whole message of 3 bytes, then the prefix and 2 bytes of one of 10.
        let mut data = vec![0, 0, 0, 0, 3, 1, 2, 3];
        data.extend([0, 0, 0, 0, 10, 1, 2]);
        assert_eq!(f.feed(0, &data), 7);
        assert_eq!(f.feed(7, &[0; 7]), 14);
        // Its last byte: whole, nothing held; an empty message holds nothing either.
        assert_eq!(f.feed(14, &[9, 0, 0, 0, 0, 0]), 0);
        // A prefix split across frames.
        assert_eq!(f.feed(0, &[0, 0]), 2);
        assert_eq!(f.feed(2, &[0, 1, 0, 7]), 6);
        assert!(grpc_framed("application/grpc") && grpc_framed("application/grpc-web+proto") && !grpc_framed("application/grpc-web-text"));
        assert!(!grpc_framed("text/plain"));
    }
}
