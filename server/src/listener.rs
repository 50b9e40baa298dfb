//! The gRPC port's connections (issue 35): at most `--max-connections` open at once (one more is
//! accepted and closed at once, never queued), and a connection must send its handshake — the
//! first [`HANDSHAKE_BYTES`] bytes (HTTP/2's preface is 24; a TLS ClientHello or an HTTP/1
//! request is longer) — within `--handshake-timeout-ms` or it is closed. TLS handshakes are
//! bounded by the same time (`serve.rs`); an idle HTTP/2 connection is pinged and closed when its
//! peer is gone (`serve.rs`). Counted in /metrics.

use std::io;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::task::{Context, Poll};
use std::time::Duration;

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::{TcpListener, TcpStream};
use tokio_stream::Stream;

/// Bytes a connection must send before its handshake deadline.
pub const HANDSHAKE_BYTES: usize = 24;

/// The connections of the port.
#[derive(Debug, Default)]
pub struct ConnCounters {
    open: AtomicUsize,
    refused: AtomicU64,
    timed_out: AtomicU64,
}

impl ConnCounters {
    /// Connections open now.
    pub fn open(&self) -> usize {
        self.open.load(Ordering::Acquire)
    }

    /// Connections closed at once because `--max-connections` were open.
    pub fn refused(&self) -> u64 {
        self.refused.load(Ordering::Relaxed)
    }

    /// Connections closed because they sent no handshake in time.
    pub fn timed_out(&self) -> u64 {
        self.timed_out.load(Ordering::Relaxed)
    }
}

/// The bounds of the port.
#[derive(Debug, Clone, Copy)]
pub struct ConnLimits {
    pub max_connections: usize,
    pub handshake_timeout: Duration,
}

/// The default `--max-connections`: half the soft limit of open files (the other half for
/// sessions, recordings, device channels, the Foxglove port), at most 4096.
pub fn default_max_connections() -> usize {
    let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
    // SAFETY: getrlimit writes the struct it is given.
    let nofile = if unsafe { libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) } == 0 { lim.rlim_cur } else { 1024 };
    usize::try_from(nofile / 2).unwrap_or(usize::MAX).clamp(16, 4096)
}

/// A connection holding its place among `max_connections`, closed (its reads fail) when it has
/// not sent [`HANDSHAKE_BYTES`] by its deadline.
pub struct GuardedStream {
    inner: TcpStream,
    counters: Arc<ConnCounters>,
    /// Until the handshake bytes arrived.
    deadline: Option<Pin<Box<tokio::time::Sleep>>>,
    read_bytes: usize,
}

impl Drop for GuardedStream {
    fn drop(&mut self) {
        self.counters.open.fetch_sub(1, Ordering::AcqRel);
    }
}

impl AsyncRead for GuardedStream {
    fn poll_read(mut self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<io::Result<()>> {
        let this = &mut *self;
        if let Some(d) = this.deadline.as_mut()
            && d.as_mut().poll(cx).is_ready()
        {
            this.deadline = None;
            this.read_bytes = HANDSHAKE_BYTES;
            this.counters.timed_out.fetch_add(1, Ordering::Relaxed);
            // hyper (or the TLS handshake) ends the connection on the error: the socket closes.
            return Poll::Ready(Err(io::Error::new(io::ErrorKind::TimedOut, "no handshake before the deadline")));
        }
        let before = buf.filled().len();
        let r = Pin::new(&mut this.inner).poll_read(cx, buf);
        if this.deadline.is_some() {
            this.read_bytes += buf.filled().len() - before;
            if this.read_bytes >= HANDSHAKE_BYTES {
                this.deadline = None;
            }
        }
        r
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
    type ConnectInfo = tonic::transport::server::TcpConnectInfo;

    fn connect_info(&self) -> Self::ConnectInfo {
        tonic::transport::server::Connected::connect_info(&self.inner)
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
            let conn = GuardedStream {
                inner: tcp,
                counters: counters.clone(),
                deadline: Some(Box::pin(tokio::time::sleep(limits.handshake_timeout))),
                read_bytes: 0,
            };
            return Some((Ok(conn), (listener, counters)));
        }
    })
}
