//! The server as an Agones game server (issue 22, `serve --agones`): Ready once it listens, health
//! pings from the IO side that stop while a session's real-time thread stalls, the sessions in use
//! and the capacity published as an Agones Counter, labels for allocation selectors, reaction to
//! the SDK's game-server updates, and the drain on SIGTERM (or when the allocated sessions end):
//! running sessions finish, new ones are refused with UNAVAILABLE, then Shutdown and exit.
//!
//! **Which API.** The SDK sidecar's documented REST gateway (`http://localhost:$AGONES_SDK_HTTP_PORT`,
//! 9358 when unset; agones.dev, "REST Game Server Client API"), spoken with hyper's HTTP/1 client,
//! already in the tree through tonic and axum. Six calls are needed — `POST /ready`, `POST /health`,
//! `POST /shutdown`, `PUT /metadata/label`, `PATCH /v1beta1/counters/{name}` and the
//! newline-delimited JSON stream `GET /watch/gameserver` — so the official `agones` crate (which
//! pins an older tonic and would bring a second tonic/hyper/prost stack into the served binary)
//! and a vendored `sdk.proto` (which imports `google/api` and `protoc-gen-openapiv2` annotations
//! that protox does not bundle) both cost more than they give. `AGONES_SDK_GRPC_PORT` is not used.
//!
//! **Counters, not Lists or player tracking.** What an allocator needs is a number: sessions in
//! use against the server's capacity (`--max-sessions`). A Counter (beta, feature gate
//! `CountsAndLists`, on by default since Agones 1.41) carries exactly that, the allocator selects on
//! it (`counters: {sessions: {minAvailable: 1}}`) and a FleetAutoscaler's Counter policy buffers on
//! it; a List would carry session ids nobody selects on, and player tracking is alpha. The count is
//! set absolutely (`{"count": "n"}`), never as a difference, so a lost or repeated call does not
//! drift; the capacity is set with the first update. Labels (`agones.dev/sdk-version`,
//! `agones.dev/sdk-scene`) carry the version and the default scene for selectors.
//!
//! **Health.** A supervisor task samples every session's tick counter (`SessionCounters::ticks`, an
//! atomic the real-time thread already writes; nothing is added to the real-time thread) every
//! poll period, `min(50 ms, interval / 4)`. A session whose counter has not moved for
//! `--agones-stall-ms` makes the server unhealthy: the pings stop (Agones marks the game server
//! Unhealthy after its `failureThreshold` of missed periods) and resume if the ticks move again.
//! A session's simulation fault does not stop the pings: it holds that session with zero force, is
//! reported on the session's own stream, and restarting the pod would end the other trainees'
//! sessions without curing a bad input.
//!
//! **Drain.** On SIGTERM or SIGINT, the SDK reporting the state `Shutdown`, or — once the game
//! server was Allocated and has had a session — its last session ending, the server refuses new
//! sessions (`ServerState::begin_drain`), waits for the running ones to close up to
//! `--drain-grace-s`, calls `POST /shutdown` and returns; the server then closes what is left
//! (recordings are finished as each session closes) and exits with status 0. A second signal ends
//! the wait early.

use std::collections::{HashMap, HashSet};
use std::future::Future;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use bytes::Bytes;
use http_body_util::{BodyExt, Full, LengthLimitError, Limited};
use hyper::body::Incoming;
use hyper::{Method, Request, Response};
use hyper_util::rt::TokioIo;

use crate::grpc::ServerState;

/// The SDK server's REST port when `AGONES_SDK_HTTP_PORT` is unset (Agones' default).
pub const DEFAULT_SDK_HTTP_PORT: u16 = 9358;
/// The Agones Counter holding the sessions in use (count) and the server's capacity.
pub const SESSIONS_COUNTER: &str = "sessions";
/// The longest a single SDK call may take (they are local); a slower one counts as failed.
const CALL_TIMEOUT: Duration = Duration::from_secs(2);
/// The longest line of the watch stream kept, bytes (a GameServer's JSON is a few kB): a longer
/// one drops the connection, which is then made again after a backoff (issue 35).
pub const MAX_WATCH_LINE_BYTES: usize = 1 << 20;
/// The largest answer of a call read, bytes (the SDK server answers `{}` or a GameServer's JSON of
/// a few kB): a longer one fails the call with [`AgonesError::AnswerTooLarge`] (issue 35: an
/// endless body grew the server by 1.7 GB in the 2 s of [`CALL_TIMEOUT`]).
pub const MAX_ANSWER_BYTES: usize = 64 << 10;
/// The first and the longest wait before the watch stream is opened again, after it ended.
const WATCH_BACKOFF_MIN: Duration = Duration::from_millis(500);
const WATCH_BACKOFF_MAX: Duration = Duration::from_secs(30);

/// What goes wrong talking to the SDK server.
#[derive(Debug, thiserror::Error)]
pub enum AgonesError {
    /// `AGONES_SDK_HTTP_PORT` is set but is not a port number.
    #[error("AGONES_SDK_HTTP_PORT = '{0}' is not a port number (1..65535)")]
    BadPort(String),
    /// A flag's value is out of range (e.g. a zero health interval).
    #[error("--{flag} = {value}: {why}")]
    BadFlag { flag: &'static str, value: u64, why: &'static str },
    /// The SDK server cannot be reached (not started yet, or gone).
    #[error("the Agones SDK server at 127.0.0.1:{port} cannot be reached: {source}")]
    Unreachable { port: u16, source: std::io::Error },
    /// The HTTP exchange failed after connecting (reset, malformed answer).
    #[error("{method} {path} to the Agones SDK server: {source}")]
    Http { method: Method, path: String, source: hyper::Error },
    /// The SDK server did not answer within [`CALL_TIMEOUT`].
    #[error("{method} {path} to the Agones SDK server: no answer within {CALL_TIMEOUT:?}")]
    Timeout { method: Method, path: String },
    /// A line of the watch stream is longer than [`MAX_WATCH_LINE_BYTES`] (the connection is
    /// dropped).
    #[error("GET /watch/gameserver: a line of the Agones SDK server's stream exceeds {MAX_WATCH_LINE_BYTES} bytes without a newline")]
    WatchLineTooLong,
    /// An answer's body is longer than [`MAX_ANSWER_BYTES`] (not read further).
    #[error("{method} {path}: the Agones SDK server's answer exceeds {MAX_ANSWER_BYTES} bytes")]
    AnswerTooLarge { method: Method, path: String },
    /// The SDK server answered with an error status (e.g. 404 for a Counter the GameServer's spec
    /// does not declare, 400 for a count over the capacity).
    #[error("{method} {path}: the Agones SDK server answered {status}: {body}")]
    Status { method: Method, path: String, status: u16, body: String },
}

/// The `serve` flags of the integration (flattened into the server's options).
#[derive(clap::Args, Clone, Debug)]
pub struct AgonesArgs {
    /// Run as an Agones game server: Ready once listening, health pings, the `sessions` Counter,
    /// labels, drain on SIGTERM. The SDK server's REST port comes from AGONES_SDK_HTTP_PORT (as
    /// Agones sets it; 9358 when unset).
    #[arg(long)]
    pub agones: bool,
    /// Period of the health pings, ms (keep it below the GameServer's health periodSeconds).
    #[arg(long, value_name = "MS", default_value_t = 2000)]
    pub agones_health_interval_ms: u64,
    /// A session whose real-time thread makes no tick for this long makes the server unhealthy
    /// (its health pings stop), ms.
    #[arg(long, value_name = "MS", default_value_t = 500)]
    pub agones_stall_ms: u64,
    /// When draining (SIGTERM, Shutdown), how long running sessions may go on before they are
    /// closed, s (keep it below the pod's terminationGracePeriodSeconds).
    #[arg(long, value_name = "S", default_value_t = 1800)]
    pub drain_grace_s: u64,
    /// Tests only: a SIGUSR2 delivered to a thread blocks that thread for this long, ms (the
    /// integration test stalls a session's real-time thread with it). Not reachable by clients.
    #[arg(long, value_name = "MS", hide = true)]
    pub debug_stall_on_sigusr2_ms: Option<u64>,
}

/// How the integration runs.
#[derive(Debug, Clone)]
pub struct AgonesConfig {
    pub sdk_http_port: u16,
    pub health_interval: Duration,
    pub stall_after: Duration,
    pub drain_grace: Duration,
    /// Labels set at start (keys without Agones' `agones.dev/sdk-` prefix).
    pub labels: Vec<(String, String)>,
}

impl AgonesArgs {
    /// The configuration when `--agones` is given (the port from `AGONES_SDK_HTTP_PORT`), with
    /// the `scene` label naming `default_scene` (or `none`).
    pub fn config(&self, default_scene: Option<&str>) -> Result<Option<AgonesConfig>, AgonesError> {
        if let Some(ms) = self.debug_stall_on_sigusr2_ms {
            install_stall_on_sigusr2(Duration::from_millis(ms));
        }
        if !self.agones {
            return Ok(None);
        }
        let check = |flag: &'static str, value: u64| {
            if value == 0 { Err(AgonesError::BadFlag { flag, value, why: "must be at least 1" }) } else { Ok(value) }
        };
        let port = sdk_port(std::env::var("AGONES_SDK_HTTP_PORT").ok().as_deref())?;
        Ok(Some(AgonesConfig {
            sdk_http_port: port,
            health_interval: Duration::from_millis(check("agones-health-interval-ms", self.agones_health_interval_ms)?),
            stall_after: Duration::from_millis(check("agones-stall-ms", self.agones_stall_ms)?),
            drain_grace: Duration::from_secs(self.drain_grace_s),
            labels: vec![
                ("version".into(), label_value(env!("CARGO_PKG_VERSION"))),
                ("scene".into(), label_value(default_scene.unwrap_or("none"))),
            ],
        }))
    }
}

/// The SDK server's REST port from the value of `AGONES_SDK_HTTP_PORT` (absent: the default).
pub fn sdk_port(env: Option<&str>) -> Result<u16, AgonesError> {
    match env.map(str::trim) {
        None | Some("") => Ok(DEFAULT_SDK_HTTP_PORT),
        Some(v) => v.parse::<u16>().ok().filter(|p| *p != 0).ok_or_else(|| AgonesError::BadPort(v.to_owned())),
    }
}

/// A Kubernetes label value from `s`: at most 63 characters of `[A-Za-z0-9._-]`, others as `-`,
/// starting and ending alphanumeric (empty if nothing is left).
pub fn label_value(s: &str) -> String {
    let v: String = s.chars().map(|c| if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') { c } else { '-' }).take(63).collect();
    v.trim_matches(|c: char| !c.is_ascii_alphanumeric()).to_owned()
}

/// The SDK server's REST gateway on 127.0.0.1 (one connection per call: they are local and rare).
#[derive(Clone, Debug)]
pub struct SdkClient {
    port: u16,
}

impl SdkClient {
    pub fn new(port: u16) -> Self {
        Self { port }
    }

    async fn send(&self, method: Method, path: &str, body: &str) -> Result<Response<Incoming>, AgonesError> {
        let stream = tokio::net::TcpStream::connect((std::net::Ipv4Addr::LOCALHOST, self.port))
            .await
            .map_err(|source| AgonesError::Unreachable { port: self.port, source })?;
        let http = |source| AgonesError::Http { method: method.clone(), path: path.to_owned(), source };
        let (mut sender, conn) = hyper::client::conn::http1::handshake(TokioIo::new(stream)).await.map_err(http)?;
        tokio::spawn(async move {
            let _ = conn.await;
        });
        let req = Request::builder()
            .method(method.clone())
            .uri(path)
            .header(hyper::header::HOST, format!("localhost:{}", self.port))
            .header(hyper::header::CONTENT_TYPE, "application/json")
            .body(Full::new(Bytes::copy_from_slice(body.as_bytes())))
            .expect("a request built from a method, a path and a body");
        let resp = sender.send_request(req).await.map_err(http)?;
        let status = resp.status();
        if !status.is_success() {
            // At most MAX_ANSWER_BYTES are read; past them the body is not quoted.
            let text = match Limited::new(resp.into_body(), MAX_ANSWER_BYTES).collect().await {
                Ok(b) => String::from_utf8_lossy(&b.to_bytes()).into_owned(),
                Err(e) if e.is::<LengthLimitError>() => format!("(an answer of over {MAX_ANSWER_BYTES} bytes)"),
                Err(_) => String::new(),
            };
            return Err(AgonesError::Status {
                method,
                path: path.to_owned(),
                status: status.as_u16(),
                body: text.chars().take(300).collect(),
            });
        }
        Ok(resp)
    }

    /// One call: its answer's body.
    pub async fn call(&self, method: Method, path: &str, body: &str) -> Result<Bytes, AgonesError> {
        let timeout = || AgonesError::Timeout { method: method.clone(), path: path.to_owned() };
        let exchange = async {
            let resp = self.send(method.clone(), path, body).await?;
            let bytes =
                Limited::new(resp.into_body(), MAX_ANSWER_BYTES).collect().await.map_err(|e| match e.downcast::<hyper::Error>() {
                    Ok(source) => AgonesError::Http { method: method.clone(), path: path.to_owned(), source: *source },
                    Err(_) => AgonesError::AnswerTooLarge { method: method.clone(), path: path.to_owned() },
                })?;
            Ok(bytes.to_bytes())
        };
        tokio::time::timeout(CALL_TIMEOUT, exchange).await.map_err(|_| timeout())?
    }

    /// `POST /ready`: the game server can take sessions.
    pub async fn ready(&self) -> Result<(), AgonesError> {
        self.call(Method::POST, "/ready", "{}").await.map(drop)
    }

    /// `POST /health`: one health ping.
    pub async fn health(&self) -> Result<(), AgonesError> {
        self.call(Method::POST, "/health", "{}").await.map(drop)
    }

    /// `POST /shutdown`: the game server is done.
    pub async fn shutdown(&self) -> Result<(), AgonesError> {
        self.call(Method::POST, "/shutdown", "{}").await.map(drop)
    }

    /// `PUT /metadata/label`: the label `agones.dev/sdk-<key>` on the GameServer.
    pub async fn set_label(&self, key: &str, value: &str) -> Result<(), AgonesError> {
        let body = serde_json::json!({ "key": key, "value": value }).to_string();
        self.call(Method::PUT, "/metadata/label", &body).await.map(drop)
    }

    /// `PATCH /v1beta1/counters/{name}`: sets the Counter's count and, when given, its capacity
    /// (int64 values travel as JSON strings, as protojson writes them).
    pub async fn set_counter(&self, name: &str, count: u64, capacity: Option<u64>) -> Result<(), AgonesError> {
        let mut body = serde_json::json!({ "count": count.to_string() });
        if let Some(c) = capacity {
            body["capacity"] = serde_json::Value::String(c.to_string());
        }
        self.call(Method::PATCH, &format!("/v1beta1/counters/{name}"), &body.to_string()).await.map(drop)
    }

    /// `GET /watch/gameserver`: calls `on_state` with the GameServer's `status.state` of every
    /// update (newline-delimited JSON `{"result": GameServer}`) until the stream ends; calls
    /// `on_line` after every complete line (the caller resets its backoff on it).
    ///
    /// Errors: [`AgonesError::WatchLineTooLong`] when a line exceeds [`MAX_WATCH_LINE_BYTES`]
    /// (the connection is dropped), and the transport's errors.
    pub async fn watch(&self, mut on_state: impl FnMut(&str), mut on_line: impl FnMut()) -> Result<(), AgonesError> {
        let path = "/watch/gameserver";
        let resp = tokio::time::timeout(CALL_TIMEOUT, self.send(Method::GET, path, ""))
            .await
            .map_err(|_| AgonesError::Timeout { method: Method::GET, path: path.into() })??;
        let mut body = resp.into_body();
        let mut lines = LineBuffer::new(MAX_WATCH_LINE_BYTES);
        while let Some(frame) = body.frame().await {
            let frame = frame.map_err(|source| AgonesError::Http { method: Method::GET, path: path.into(), source })?;
            let Ok(data) = frame.into_data() else { continue };
            lines.push(&data, |line| {
                if let Some(state) = watch_line_state(line) {
                    on_state(&state);
                }
                on_line();
            })?;
        }
        Ok(())
    }
}

/// Splits a byte stream into newline-terminated lines of at most `max` bytes (the newline
/// included), scanning each byte once.
#[derive(Debug)]
pub struct LineBuffer {
    buf: Vec<u8>,
    max: usize,
}

impl LineBuffer {
    pub fn new(max: usize) -> Self {
        Self { buf: Vec::new(), max }
    }

    /// Adds `data`, calling `on_line` with each line it completes (without its newline).
    ///
    /// Errors: [`AgonesError::WatchLineTooLong`] when a line would exceed the bound (the buffer
    /// is then emptied; the caller drops the stream).
    pub fn push(&mut self, mut data: &[u8], mut on_line: impl FnMut(&[u8])) -> Result<(), AgonesError> {
        while let Some(nl) = data.iter().position(|b| *b == b'\n') {
            let (head, rest) = (&data[..nl], &data[nl + 1..]);
            if self.buf.len() + head.len() + 1 > self.max {
                self.buf = Vec::new();
                return Err(AgonesError::WatchLineTooLong);
            }
            if self.buf.is_empty() {
                on_line(head);
            } else {
                self.buf.extend_from_slice(head);
                on_line(&self.buf);
                self.buf.clear();
            }
            data = rest;
        }
        if self.buf.len() + data.len() >= self.max {
            self.buf = Vec::new();
            return Err(AgonesError::WatchLineTooLong);
        }
        self.buf.extend_from_slice(data);
        Ok(())
    }

    /// The bytes of the unfinished line held.
    pub fn pending(&self) -> usize {
        self.buf.len()
    }
}

/// The `result.status.state` of one line of the watch stream, if it has one.
pub fn watch_line_state(line: &[u8]) -> Option<String> {
    let v: serde_json::Value = serde_json::from_slice(line).ok()?;
    v.get("result")?.get("status")?.get("state")?.as_str().map(str::to_owned)
}

/// Finds sessions whose real-time thread stopped ticking, from their tick counters sampled on the
/// IO side.
#[derive(Default, Debug)]
pub struct StallWatch {
    /// Per session: the last tick count seen and when it last changed.
    seen: HashMap<String, (u64, Instant)>,
}

impl StallWatch {
    /// Records a sample of every live session's tick count at `now`; returns the session whose
    /// count has not moved for the longest time, if that is at least `stall_after`. Sessions absent
    /// from the sample are forgotten.
    pub fn sample(&mut self, now: Instant, ticks: &[(String, u64)], stall_after: Duration) -> Option<(String, Duration)> {
        let mut worst: Option<(String, Duration)> = None;
        for (id, t) in ticks {
            let e = self.seen.entry(id.clone()).or_insert((*t, now));
            if e.0 != *t {
                *e = (*t, now);
            }
            let idle = now.saturating_duration_since(e.1);
            if idle >= stall_after && worst.as_ref().is_none_or(|(_, w)| idle > *w) {
                worst = Some((id.clone(), idle));
            }
        }
        let live: HashSet<&String> = ticks.iter().map(|(id, _)| id).collect();
        self.seen.retain(|id, _| live.contains(id));
        worst
    }
}

/// State shared by the integration's tasks.
struct Shared {
    /// The SDK reported the state `Allocated`.
    allocated: AtomicBool,
    /// Why the server drains, once it must.
    drain: tokio::sync::watch::Sender<Option<String>>,
}

impl Shared {
    fn request_drain(&self, reason: &str) {
        self.drain.send_if_modified(|r| {
            if r.is_none() {
                *r = Some(reason.to_owned());
                true
            } else {
                false
            }
        });
    }
}

/// Starts the integration on a server that listens (Ready is sent at once) and returns the future
/// that resolves when the server should stop: after a drain, then `POST /shutdown`.
pub fn start(cfg: AgonesConfig, state: Arc<ServerState>) -> impl Future<Output = ()> + Send + 'static {
    let sdk = SdkClient::new(cfg.sdk_http_port);
    let (drain_tx, mut drain_rx) = tokio::sync::watch::channel(None);
    let shared = Arc::new(Shared { allocated: AtomicBool::new(false), drain: drain_tx });
    tracing::info!(sdk_http_port = cfg.sdk_http_port, health_interval_ms = cfg.health_interval.as_millis() as u64, "Agones integration on");
    tokio::spawn(supervise(sdk.clone(), cfg.clone(), state.clone(), shared.clone()));
    tokio::spawn(watch_game_server(sdk.clone(), shared.clone()));
    async move {
        let reason = tokio::select! {
            sig = terminate_signal() => format!("{sig} received"),
            r = drain_rx.wait_for(Option::is_some) => r.ok().and_then(|r| (*r).clone()).unwrap_or_default(),
        };
        drain(&cfg, &state, &reason).await;
        if let Err(e) = sdk.shutdown().await {
            tracing::warn!(error = %e, "Agones Shutdown failed");
        }
        drop(shared);
        tracing::info!("drained: shutting down");
    }
}

/// Refuses new sessions and waits until the running ones end, the grace period is over, or a
/// second signal comes.
async fn drain(cfg: &AgonesConfig, state: &ServerState, reason: &str) {
    state.begin_drain();
    let n = state.session_count();
    tracing::info!(reason, sessions = n, grace_s = cfg.drain_grace.as_secs(), "draining: new sessions are refused, running ones finish");
    let deadline = tokio::time::Instant::now() + cfg.drain_grace;
    let mut poll = tokio::time::interval(Duration::from_millis(50));
    let second = terminate_signal();
    tokio::pin!(second);
    loop {
        tokio::select! {
            _ = poll.tick() => {}
            sig = &mut second => {
                tracing::warn!(signal = sig, sessions = state.session_count(), "second signal: closing the running sessions now");
                return;
            }
        }
        let n = state.session_count();
        if n == 0 {
            return;
        }
        if tokio::time::Instant::now() >= deadline {
            tracing::warn!(sessions = n, "drain grace period over: closing the running sessions");
            return;
        }
    }
}

/// SIGTERM or SIGINT, whichever comes first: its name.
pub async fn terminate_signal() -> &'static str {
    let mut term = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()).ok();
    tokio::select! {
        _ = tokio::signal::ctrl_c() => "SIGINT",
        _ = async {
            match term.as_mut() {
                Some(t) => {
                    t.recv().await;
                }
                None => std::future::pending::<()>().await,
            }
        } => "SIGTERM",
    }
}

/// Ready (retried until the sidecar answers), labels, then every poll period: stall check, health
/// ping when due and healthy, the Counter when the session count changed, the end of an
/// allocation's sessions.
async fn supervise(sdk: SdkClient, cfg: AgonesConfig, state: Arc<ServerState>, shared: Arc<Shared>) {
    let mut backoff = Duration::from_millis(50);
    loop {
        match sdk.ready().await {
            Ok(()) => break,
            Err(e) => {
                tracing::warn!(error = %e, "Agones Ready failed; retrying");
                tokio::time::sleep(backoff).await;
                backoff = (backoff * 2).min(Duration::from_secs(2));
            }
        }
    }
    tracing::info!("Agones: Ready");
    for (k, v) in &cfg.labels {
        if let Err(e) = sdk.set_label(k, v).await {
            tracing::warn!(error = %e, label = %k, "Agones SetLabel failed");
        }
    }
    let capacity = state.limits.max_sessions as u64;
    let poll_period = (cfg.health_interval / 4).clamp(Duration::from_millis(5), Duration::from_millis(50));
    let mut poll = tokio::time::interval(poll_period);
    poll.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    let mut stalls = StallWatch::default();
    let mut unhealthy: Option<String> = None;
    let mut next_health = Instant::now();
    let mut published: Option<u64> = None;
    let mut had_session_while_allocated = false;
    let mut counter_errors = 0u64;
    loop {
        poll.tick().await;
        let ticks: Vec<(String, u64)> = state
            .sessions
            .read()
            .expect("sessions lock")
            .values()
            .map(|s| (s.id.clone(), s.counters.ticks.load(Ordering::Relaxed)))
            .collect();
        let now = Instant::now();
        match (stalls.sample(now, &ticks, cfg.stall_after), &unhealthy) {
            (Some((id, idle)), None) => {
                tracing::error!(session = %id, idle_ms = idle.as_millis() as u64, "a session's real-time thread stalled: Agones health pings stop");
                unhealthy = Some(id);
            }
            (None, Some(id)) => {
                tracing::warn!(session = %id, "the real-time threads tick again: Agones health pings resume");
                unhealthy = None;
                next_health = now;
            }
            _ => {}
        }
        if unhealthy.is_none() && now >= next_health {
            if let Err(e) = sdk.health().await {
                tracing::warn!(error = %e, "Agones health ping failed");
            }
            next_health += cfg.health_interval;
            if next_health < now {
                next_health = now + cfg.health_interval;
            }
        }
        let count = state.sessions.read().expect("sessions lock").len() as u64;
        if published != Some(count) {
            match sdk.set_counter(SESSIONS_COUNTER, count, published.is_none().then_some(capacity)).await {
                Ok(()) => published = Some(count),
                Err(e) => {
                    counter_errors += 1;
                    if counter_errors.is_power_of_two() {
                        tracing::warn!(error = %e, errors = counter_errors, "Agones UpdateCounter failed");
                    }
                }
            }
        }
        if shared.allocated.load(Ordering::Acquire) {
            if count > 0 {
                had_session_while_allocated = true;
            } else if had_session_while_allocated {
                shared.request_drain("the allocated sessions ended");
            }
        }
    }
}

/// Follows the SDK's game-server updates (reconnecting, with a backoff that doubles while the
/// stream fails before its first line, up to [`WATCH_BACKOFF_MAX`]): logs each state, remembers
/// Allocated, drains on Shutdown. A line over [`MAX_WATCH_LINE_BYTES`] is logged once as a warning
/// (then at debug level) and counted ([`watch_overlong_lines`], `/metrics`
/// `needlesim_agones_watch_overlong_lines`).
async fn watch_game_server(sdk: SdkClient, shared: Arc<Shared>) {
    let mut last = String::new();
    let mut backoff = WATCH_BACKOFF_MIN;
    let mut warned = false;
    loop {
        let mut got_line = false;
        let r = sdk
            .watch(
                |state| {
                    if state != last {
                        tracing::info!(state, "Agones game server state");
                        last = state.to_owned();
                    }
                    match state {
                        "Allocated" => shared.allocated.store(true, Ordering::Release),
                        "Shutdown" => shared.request_drain("the game server's state is Shutdown"),
                        _ => {}
                    }
                },
                || got_line = true,
            )
            .await;
        if got_line {
            backoff = WATCH_BACKOFF_MIN;
        }
        match r {
            Err(e @ AgonesError::WatchLineTooLong) => {
                WATCH_OVERLONG_LINES.fetch_add(1, Ordering::Relaxed);
                if !warned {
                    warned = true;
                    tracing::warn!(error = %e, "Agones watch stream dropped; reconnecting with backoff (logged once)");
                } else {
                    tracing::debug!(error = %e, "Agones watch stream dropped");
                }
            }
            Err(e) => tracing::debug!(error = %e, "Agones watch ended"),
            Ok(()) => {}
        }
        tokio::time::sleep(backoff).await;
        backoff = (backoff * 2).min(WATCH_BACKOFF_MAX);
    }
}

/// Watch-stream lines over [`MAX_WATCH_LINE_BYTES`] since start (each dropped the connection).
static WATCH_OVERLONG_LINES: AtomicU64 = AtomicU64::new(0);

/// Watch-stream lines over [`MAX_WATCH_LINE_BYTES`] since start (each dropped the connection).
pub fn watch_overlong_lines() -> u64 {
    WATCH_OVERLONG_LINES.load(Ordering::Relaxed)
}

/// How long the test-only SIGUSR2 handler blocks, ns.
static STALL_NS: AtomicU64 = AtomicU64::new(0);

extern "C" fn stall_handler(_sig: libc::c_int) {
    let ns = STALL_NS.load(Ordering::Relaxed);
    let ts = libc::timespec { tv_sec: (ns / 1_000_000_000) as libc::time_t, tv_nsec: (ns % 1_000_000_000) as libc::c_long };
    // SAFETY: nanosleep is async-signal-safe; `ts` lives for the call.
    unsafe {
        libc::nanosleep(&ts, std::ptr::null_mut());
    }
}

/// Tests only (`--debug-stall-on-sigusr2-ms`): a SIGUSR2 sent to one thread (tgkill) blocks that
/// thread for `stall`, so a test can stall a session's real-time thread from outside.
fn install_stall_on_sigusr2(stall: Duration) {
    STALL_NS.store(stall.as_nanos().min(u64::MAX as u128) as u64, Ordering::Relaxed);
    // SAFETY: a plain sigaction with a handler that only calls async-signal-safe functions.
    unsafe {
        let mut sa: libc::sigaction = std::mem::zeroed();
        sa.sa_sigaction = stall_handler as extern "C" fn(libc::c_int) as libc::sighandler_t;
        sa.sa_flags = libc::SA_RESTART;
        libc::sigemptyset(&mut sa.sa_mask);
        libc::sigaction(libc::SIGUSR2, &sa, std::ptr::null_mut());
    }
    tracing::warn!(stall_ms = stall.as_millis() as u64, "test hook on: SIGUSR2 blocks the thread it is sent to");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn port_from_env() {
        assert_eq!(sdk_port(None).unwrap(), DEFAULT_SDK_HTTP_PORT);
        assert_eq!(sdk_port(Some("")).unwrap(), DEFAULT_SDK_HTTP_PORT);
        assert_eq!(sdk_port(Some("59358")).unwrap(), 59358);
        for bad in ["0", "70000", "http", "-1"] {
            let e = sdk_port(Some(bad)).unwrap_err().to_string();
            assert!(e.contains("AGONES_SDK_HTTP_PORT") && e.contains(bad), "{e}");
        }
    }

    #[test]
    fn label_values_are_kubernetes_label_values() {
        assert_eq!(label_value("paper-phantom"), "paper-phantom");
        assert_eq!(label_value("0.1.0"), "0.1.0");
        assert_eq!(label_value("my scene/v2!"), "my-scene-v2");
        assert_eq!(label_value(&"x".repeat(100)).len(), 63);
        assert_eq!(label_value("--"), "");
    }

    #[test]
    fn watch_lines_give_the_state() {
        let line = br#"{"result":{"object_meta":{"name":"local"},"status":{"state":"Allocated","address":"127.0.0.1"}}}"#;
        assert_eq!(watch_line_state(line).as_deref(), Some("Allocated"));
        assert_eq!(watch_line_state(b"{\"result\":{}}"), None);
        assert_eq!(watch_line_state(b"not json"), None);
    }

    #[test]
    fn issue_35_watch_lines_split_across_chunks_are_joined_and_an_overlong_line_is_refused() {
        let mut lines = LineBuffer::new(16);
        let mut got: Vec<Vec<u8>> = Vec::new();
        lines.push(b"ab\ncd", |l| got.push(l.to_vec())).unwrap();
        lines.push(b"ef\n\ngh", |l| got.push(l.to_vec())).unwrap();
        assert_eq!(got, [b"ab".to_vec(), b"cdef".to_vec(), b"".to_vec()]);
        assert_eq!(lines.pending(), 2);
        // 15 bytes and the newline fit; 16 without a newline do not.
        lines.push(b"0123456789abc\n", |l| got.push(l.to_vec())).unwrap();
        assert_eq!(got.last().unwrap(), b"gh0123456789abc");
        let mut lines = LineBuffer::new(16);
        for _ in 0..3 {
            lines.push(b"xxxxx", |_| panic!("no line")).unwrap();
        }
        assert!(matches!(lines.push(b"x", |_| panic!("no line")), Err(AgonesError::WatchLineTooLong)));
        assert_eq!(lines.pending(), 0, "the partial line is let go");
        let mut lines = LineBuffer::new(16);
        assert!(matches!(lines.push(&[b'y'; 40], |_| panic!("no line")), Err(AgonesError::WatchLineTooLong)));
        let mut lines = LineBuffer::new(16);
        lines.push(b"yyyyyyyy", |_| panic!("no line")).unwrap();
        assert!(matches!(lines.push(b"yyyyyyyyy\n", |_| panic!("no line")), Err(AgonesError::WatchLineTooLong)));
    }

    #[test]
    fn a_stalled_counter_is_found_and_a_ticking_one_is_not() {
        let t0 = Instant::now();
        let ms = Duration::from_millis;
        let mut w = StallWatch::default();
        let s = |a: u64, b: u64| vec![("a".to_owned(), a), ("b".to_owned(), b)];
        assert_eq!(w.sample(t0, &s(0, 0), ms(100)), None);
        // a ticks, b does not: b stalls once 100 ms have passed since its last change.
        assert_eq!(w.sample(t0 + ms(60), &s(60, 0), ms(100)), None);
        assert_eq!(w.sample(t0 + ms(120), &s(120, 0), ms(100)), Some(("b".to_owned(), ms(120))));
        // b ticks again: healthy; a stops: stalled 100 ms after its last change (at 120 ms).
        assert_eq!(w.sample(t0 + ms(200), &s(120, 1), ms(100)), None);
        assert_eq!(w.sample(t0 + ms(230), &s(120, 2), ms(100)), Some(("a".to_owned(), ms(110))));
        // A closed session is forgotten; a new one with the same id starts afresh.
        assert_eq!(w.sample(t0 + ms(240), &[("b".to_owned(), 3)], ms(100)), None);
        assert_eq!(w.sample(t0 + ms(300), &s(120, 4), ms(100)), None);
    }
}
