//! The gRPC port's HTTP/1.1 and HTTP/2 connections, served by hyper-util's connection builder
//! (issue 35, pass 4): tonic's transport `Server` does not let the memory HTTP/2 buffers per stream
//! be set, and hyper's default lets each stream queue 400 KiB (`DEFAULT_MAX_SEND_BUF_SIZE`,
//! 409,600 bytes) for a client that opened its windows and never reads its socket — 30 connections
//! of 100 unread GetMesh calls held 2 GB that the answer budget had already given back.
//!
//! Here a stream's send buffer is [`MAX_SEND_BUF_BYTES`] (one answer chunk, `answers.rs`): hyper
//! takes one frame of a response body and waits for room in that buffer before it asks for the
//! next, so what a body has not handed over stays with it, counted by the answer budget or bounded
//! by its stream's own rules; HTTP/2 holds at most three chunks a stream (one waiting in hyper, up
//! to two in h2's buffer: 48 KiB). Everything tonic's server did for us is kept:
//! the connection's `ConnectInfo` in every request (`listener.rs`), a call's `grpc-timeout` ([`GrpcTimeout`]), TLS with its handshake
//! deadline and ALPN `h2`, SETTINGS_MAX_CONCURRENT_STREAMS, the HTTP/2 keep-alive pings, HTTP/1.1
//! beside HTTP/2 (gRPC-web), hyper's HTTP/1 header-read timeout, and the graceful drain at
//! shutdown.

use std::convert::Infallible;
use std::future::Future;
use std::io;
use std::sync::Arc;
use std::time::Duration;

use anyhow::{Context, Result};
use axum::http::{Request, Response};
use hyper_util::rt::{TokioExecutor, TokioIo, TokioTimer};
use tokio_rustls::rustls::pki_types::pem::PemObject as _;
use tokio_rustls::rustls::pki_types::{CertificateDer, PrivateKeyDer};
use tokio_stream::{Stream, StreamExt as _};

use crate::listener::GuardedStream;

/// The bytes HTTP/2 may queue for one stream before the client reads them: one answer chunk
/// (`answers::CHUNK_BYTES`).
pub const MAX_SEND_BUF_BYTES: usize = crate::answers::CHUNK_BYTES;

/// The HTTP/2 settings of the port.
#[derive(Debug, Clone, Copy)]
pub struct Http2Settings {
    /// SETTINGS_MAX_CONCURRENT_STREAMS (`--max-streams-per-connection`).
    pub max_concurrent_streams: u32,
    /// Interval of the pings on a connection, and how long its peer has to answer one.
    pub keepalive_interval: Duration,
    pub keepalive_timeout: Duration,
}

/// TLS of the port: the certificate chain and key (PEM) and the handshake's deadline.
#[derive(Clone)]
pub struct Tls {
    acceptor: tokio_rustls::TlsAcceptor,
    handshake_timeout: Duration,
}

impl Tls {
    /// The TLS of a PEM certificate chain and private key, ALPN `h2` (as tonic's).
    pub fn from_pem(cert_pem: &[u8], key_pem: &[u8], handshake_timeout: Duration) -> Result<Self> {
        let certs = CertificateDer::pem_slice_iter(cert_pem).collect::<Result<Vec<_>, _>>().context("the TLS certificate is not PEM")?;
        let key = PrivateKeyDer::from_pem_slice(key_pem).context("the TLS key is not a PEM private key")?;
        let ring = Arc::new(tokio_rustls::rustls::crypto::ring::default_provider());
        let mut config = tokio_rustls::rustls::ServerConfig::builder_with_provider(ring)
            .with_safe_default_protocol_versions()
            .context("TLS protocol versions")?
            .with_no_client_auth()
            .with_single_cert(certs, key)
            .context("the TLS certificate and key")?;
        config.alpn_protocols.push(b"h2".to_vec());
        Ok(Self { acceptor: tokio_rustls::TlsAcceptor::from(Arc::new(config)), handshake_timeout })
    }
}

/// Serves the connections of `incoming` with `service` until `shutdown` resolves, then stops
/// accepting and waits for the open connections to end (each told to finish: HTTP/2 GOAWAY,
/// HTTP/1.1 after its response).
pub async fn serve<S>(
    incoming: impl Stream<Item = io::Result<GuardedStream>>,
    service: S,
    tls: Option<Tls>,
    http2: Http2Settings,
    shutdown: impl Future<Output = ()>,
) where
    S: tower::Service<Request<tonic::body::Body>, Response = Response<tonic::body::Body>, Error = Infallible> + Clone + Send + 'static,
    S::Future: Send + 'static,
{
    let mut builder = hyper_util::server::conn::auto::Builder::new(TokioExecutor::new());
    // hyper enforces its HTTP/1 header-read timeout (30 s) only with a timer.
    builder.http1().timer(TokioTimer::new());
    builder
        .http2()
        .timer(TokioTimer::new())
        .max_concurrent_streams(http2.max_concurrent_streams)
        .keep_alive_interval(http2.keepalive_interval)
        .keep_alive_timeout(http2.keepalive_timeout)
        .max_send_buf_size(MAX_SEND_BUF_BYTES);
    let graceful = hyper_util::server::graceful::GracefulShutdown::new();
    // Boxed, so that dropping it closes the listener.
    let mut incoming = Box::pin(incoming);
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let io = tokio::select! {
            () = &mut shutdown => break,
            io = incoming.next() => match io {
                Some(Ok(io)) => io,
                Some(Err(e)) => {
                    tracing::debug!(error = %e, "cannot accept a connection");
                    continue;
                }
                None => break,
            },
        };
        // Every request of the connection carries its `ConnectInfo` (`listener::ConnGuard` reads it).
        let info = tonic::transport::server::Connected::connect_info(&io);
        let service = tower::util::MapRequest::new(GrpcTimeout(service.clone()), move |req: Request<hyper::body::Incoming>| {
            let mut req = req.map(tonic::body::Body::new);
            req.extensions_mut().insert(info.clone());
            req
        });
        let service = hyper_util::service::TowerToHyperService::new(service);
        let (builder, watcher, tls) = (builder.clone(), graceful.watcher(), tls.clone());
        tokio::spawn(async move {
            let served = match tls {
                None => watcher.watch(builder.serve_connection(TokioIo::new(io), service).into_owned()).await,
                Some(tls) => match tokio::time::timeout(tls.handshake_timeout, tls.acceptor.accept(io)).await {
                    Ok(Ok(io)) => watcher.watch(builder.serve_connection(TokioIo::new(io), service).into_owned()).await,
                    Ok(Err(e)) => {
                        tracing::debug!(error = %e, "TLS handshake failed");
                        return;
                    }
                    Err(_) => {
                        tracing::debug!("TLS handshake not done within --handshake-timeout-ms");
                        return;
                    }
                },
            };
            if let Err(e) = served {
                tracing::debug!(error = %e, "connection ended with an error");
            }
        });
    }
    // Stop accepting (the listener closes) before the drain.
    drop(incoming);
    graceful.shutdown().await;
}

/// A call's `grpc-timeout` (as tonic's server honours it): a handler that has not answered within
/// it is dropped and the call answered CANCELLED, "Timeout expired".
#[derive(Debug, Clone)]
pub struct GrpcTimeout<S>(S);

impl<S> tower::Service<Request<tonic::body::Body>> for GrpcTimeout<S>
where
    S: tower::Service<Request<tonic::body::Body>, Response = Response<tonic::body::Body>, Error = Infallible>,
    S::Future: Send + 'static,
{
    type Response = Response<tonic::body::Body>;
    type Error = Infallible;
    type Future = std::pin::Pin<Box<dyn Future<Output = Result<Self::Response, Infallible>> + Send>>;

    fn poll_ready(&mut self, cx: &mut std::task::Context<'_>) -> std::task::Poll<Result<(), Infallible>> {
        self.0.poll_ready(cx)
    }

    fn call(&mut self, req: Request<tonic::body::Body>) -> Self::Future {
        let timeout = req.headers().get("grpc-timeout").and_then(|v| v.to_str().ok()).and_then(grpc_timeout);
        let answer = self.0.call(req);
        Box::pin(async move {
            match timeout {
                None => answer.await,
                Some(t) => match tokio::time::timeout(t, answer).await {
                    Ok(answer) => answer,
                    Err(_) => Ok(tonic::Status::cancelled(tonic::TimeoutExpired(()).to_string()).into_http()),
                },
            }
        })
    }
}

/// A `grpc-timeout` header's value (at most 8 digits and a unit: H M S m u n), or `None`.
fn grpc_timeout(value: &str) -> Option<Duration> {
    let unit_at = value.len().checked_sub(1)?;
    let (digits, unit) = value.split_at(unit_at);
    if digits.is_empty() || digits.len() > 8 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let n: u64 = digits.parse().ok()?;
    Some(match unit {
        "H" => Duration::from_secs(n * 3600),
        "M" => Duration::from_secs(n * 60),
        "S" => Duration::from_secs(n),
        "m" => Duration::from_millis(n),
        "u" => Duration::from_micros(n),
        "n" => Duration::from_nanos(n),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grpc_timeouts_are_read_as_the_spec_writes_them() {
        assert_eq!(grpc_timeout("5S"), Some(Duration::from_secs(5)));
        assert_eq!(grpc_timeout("250m"), Some(Duration::from_millis(250)));
        assert_eq!(grpc_timeout("2H"), Some(Duration::from_secs(7200)));
        assert_eq!(grpc_timeout("99999999n"), Some(Duration::from_nanos(99_999_999)));
        for bad in ["", "S", "5", "123456789S", "5s", "-5S", "+5S", "5.0S"] {
            assert_eq!(grpc_timeout(bad), None, "{bad}");
        }
    }
}
