//! The network server: every gRPC service of `needlesim.v1`, gRPC health checking
//! (grpc.health.v1), server reflection, gRPC-web (applied to the gRPC routes only), Prometheus
//! metrics at `/metrics` and the web viewer's built files (`web_files.rs`), all on one port; TLS
//! when a certificate is configured.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use anyhow::{Context, Result};
use needlesim_proto::v1 as pb;

use crate::grpc::{Api, ServerLimits, ServerState};

/// How the server is run.
#[derive(Debug, Clone)]
pub struct ServeConfig {
    pub listen: SocketAddr,
    pub data_dir: PathBuf,
    pub web_dir: PathBuf,
    /// PEM certificate chain and private key; TLS when both are given.
    pub tls: Option<(PathBuf, PathBuf)>,
    pub limits: ServerLimits,
    pub max_message_bytes: usize,
    /// A session to create at start-up (a shipped example's name), if any.
    pub default_scene: Option<String>,
    /// Play the default scene's example trajectory in a loop until a client takes control.
    pub demo: bool,
    /// The admin token, which opens every recording (only its SHA-256 is kept).
    pub admin_token: Option<String>,
    /// Where the live Foxglove endpoint listens (`--foxglove-addr`), if anywhere.
    pub foxglove: Option<SocketAddr>,
    /// Connections the Foxglove endpoint holds at once (`--foxglove-max-clients`).
    pub foxglove_max_clients: usize,
    /// A shipped exercise to start a session of at start-up (`--exercise`, issue 20): its URLs for
    /// the trainee, the instructor and observers are printed.
    pub exercise: Option<String>,
    /// The port's connection bounds (`--max-connections`, `--handshake-timeout-ms`,
    /// `--max-streams-per-connection`, `--max-pending-request-mb`; `listener.rs`).
    pub connections: crate::listener::ConnLimits,
    /// How long connections may stay open once the sessions are closed at shutdown
    /// (`--shutdown-grace-ms`): past it the server returns without them (issue 35).
    pub shutdown_grace: std::time::Duration,
    /// Most bytes of complete gRPC answers held for clients that have not read them
    /// (`--max-held-answers-mb`; `answers.rs`).
    pub max_held_answer_bytes: u64,
    /// How long a client has to take a counted answer whole (`--answer-deadline-ms`).
    pub answer_deadline: std::time::Duration,
}

/// Prometheus text exposition of every session's counters and percentiles, and the server's
/// streams and connections.
fn metrics_text(state: &ServerState, conns: &crate::listener::ConnCounters, answers: &crate::answers::AnswerBudget) -> String {
    use prometheus_client::encoding::EncodeLabelSet;
    use prometheus_client::metrics::family::Family;
    use prometheus_client::metrics::gauge::Gauge;
    #[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
    struct Labels {
        session: String,
    }
    let mut registry = prometheus_client::registry::Registry::with_prefix("needlesim");
    let sessions = state.sessions.read().expect("sessions lock");
    type F64Family<L> = Family<L, Gauge<f64, std::sync::atomic::AtomicU64>>;
    let mut gauges: Vec<(&str, &str, F64Family<Labels>)> = vec![
        ("ticks", "Ticks computed", Family::default()),
        ("tick_compute_p50_seconds", "Median tick compute time", Family::default()),
        ("tick_compute_p99_seconds", "99th percentile tick compute time", Family::default()),
        ("tick_lateness_p99_seconds", "99th percentile tick start lateness", Family::default()),
        ("tick_lateness_p999_seconds", "99.9th percentile tick start lateness", Family::default()),
        ("tick_lateness_max_seconds", "Largest tick start lateness", Family::default()),
        ("tick_spin_seconds", "Time the real-time thread spun before its deadlines (the spin margin's CPU cost)", Family::default()),
        ("fanout_wakes", "Times the real-time thread woke the parked fan-out after a record", Family::default()),
        ("fanout_timeouts", "Times the fan-out woke by its safety timeout (no record for 20 ms)", Family::default()),
        ("missed_deadlines", "Ticks that ended after the next deadline", Family::default()),
        ("dropped_records", "Tick records the real-time thread could not hand over", Family::default()),
        ("superseded_poses", "Poses replaced before a tick used them", Family::default()),
        ("observers", "Observers attached", Family::default()),
        ("column_misses", "Compliance columns computed inside a tick", Family::default()),
        ("column_deferrals", "Ticks at which a new contact waited for its compliance columns", Family::default()),
        ("columns_evicted", "Nodes whose cached compliance columns were evicted (unused, or the cache full)", Family::default()),
        ("budget_exhausted_ticks", "Ticks whose active-set work hit the per-tick update budget", Family::default()),
        ("active_set_capped_ticks", "Ticks whose stick/slip iteration stopped at its cap (conditions not converged)", Family::default()),
        ("shape_capped_ticks", "Ticks whose flexible needle's shape passes stopped at their cap", Family::default()),
        ("late_captures", "3D: points the tip passed without their columns, captured once the columns arrived", Family::default()),
        ("pending_captures_dropped", "3D: points waiting for their columns that were given up", Family::default()),
        ("hybrid_checks", "Round-off checks of the working solver's hybrid matrix", Family::default()),
        ("hybrid_rebuilds", "Rebuilds of the hybrid matrix after a check found it drifted (not expected)", Family::default()),
        ("dropped_eviction_notices", "Eviction notices the real-time thread could not queue to the column worker", Family::default()),
        ("faults", "Simulation faults (a diverged or failed step; the session then holds with zero force)", Family::default()),
        ("step_errors", "Steps that failed other than by diverging (held and retried; 100 in a row fault the session)", Family::default()),
        ("rejected_poses", "Poses rejected (not finite), from Control, SetPose and the device", Family::default()),
        ("device_stale", "1 while a device channel's bridge sends no fresh poses (the needle is held)", Family::default()),
        (
            "device_channel_broken",
            "1 once the device channel's file was changed under it (truncated, deleted, replaced, garbage)",
            Family::default(),
        ),
        (
            "device_suspended",
            "1 while the device does not drive (a training exercise's instructor has control or has paused it)",
            Family::default(),
        ),
        ("device_poses_suspended", "Fresh device poses set aside while the device was suspended", Family::default()),
        (
            "device_catch_up_poses",
            "Device poses after a suspension that moved the needle only part of the way (the catch-up at 50 mm/s)",
            Family::default(),
        ),
    ];
    for s in sessions.values() {
        let st = s.stats();
        let labels = Labels { session: s.id.clone() };
        let values = [
            st.ticks as f64,
            st.compute_us[0] * 1e-6,
            st.compute_us[1] * 1e-6,
            st.lateness_us[1] * 1e-6,
            st.lateness_us[2] * 1e-6,
            st.lateness_max_us * 1e-6,
            st.spin_ns as f64 * 1e-9,
            st.fanout_wakes as f64,
            st.fanout_timeouts as f64,
            st.missed_deadlines as f64,
            st.dropped_records as f64,
            st.superseded_poses as f64,
            s.n_observers.load(Ordering::Relaxed) as f64,
            st.column_misses as f64,
            st.column_deferrals as f64,
            st.columns_evicted as f64,
            st.budget_exhausted_ticks as f64,
            st.active_set_capped_ticks as f64,
            st.shape_capped_ticks as f64,
            st.late_captures as f64,
            st.pending_captures_dropped as f64,
            st.hybrid_checks as f64,
            st.hybrid_rebuilds as f64,
            s.counters.dropped_eviction_notices.load(Ordering::Relaxed) as f64,
            st.faults as f64,
            s.counters.step_errors.load(Ordering::Relaxed) as f64,
            st.rejected_poses as f64,
            s.counters.device_stale.load(Ordering::Relaxed) as f64,
            s.counters.device_channel_broken.load(Ordering::Relaxed) as f64,
            f64::from(u8::from(s.device_channel_path.is_some() && s.device_suspended())),
            s.counters.device_poses_suspended.load(Ordering::Relaxed) as f64,
            s.counters.device_catch_up_poses.load(Ordering::Relaxed) as f64,
        ];
        for ((_, _, fam), v) in gauges.iter_mut().zip(values) {
            fam.get_or_create(&labels).set(v);
        }
    }
    let n_sessions: Gauge<f64, std::sync::atomic::AtomicU64> = Gauge::default();
    n_sessions.set(sessions.len() as f64);
    registry.register("sessions", "Sessions running", n_sessions);
    let alive: Gauge<f64, std::sync::atomic::AtomicU64> = Gauge::default();
    alive.set(needlesim_session::sessions_alive() as f64);
    registry.register(
        "sessions_alive",
        "Session objects in memory, closed ones still held by something included (issue 35: returns to `sessions` once closed sessions' streams have ended)",
        alive,
    );
    let jobs = [
        ("offline_jobs_running", "Offline calls (Simulate, Plan, Identify) running", state.jobs.running() as f64),
        ("offline_jobs_peak", "The most offline calls that ever ran at once", state.jobs.peak() as f64),
        (
            "offline_jobs_rejected",
            "Offline calls refused: the server ran its limit (--max-offline-jobs, --max-plans)",
            state.jobs.rejected() as f64,
        ),
        (
            "offline_jobs_timed_out",
            "Offline calls stopped (DEADLINE_EXCEEDED): their client did not take their next message within --answer-deadline-ms",
            state.jobs.timed_out() as f64,
        ),
        (
            "streams_open",
            "Server-streaming calls open (Observe, WatchScore, WatchUltrasound, GetReport, DownloadRecording)",
            state.streams.open() as f64,
        ),
        (
            "control_streams_awaiting_first_message",
            "Control and Control3 streams open that have not sent their first message (ended after --control-first-message-ms)",
            crate::grpc::control::awaiting_first_message() as f64,
        ),
        (
            "control_streams_first_message_timeouts",
            "Control and Control3 streams ended with DEADLINE_EXCEEDED: no first message within --control-first-message-ms",
            crate::grpc::control::first_message_timeouts() as f64,
        ),
        ("streams_refused", "Streams refused: a session's --max-observers or the server's --max-streams", state.streams.refused() as f64),
        ("connections_open", "Connections open on the gRPC port", conns.open() as f64),
        ("connections_refused", "Connections closed at once: --max-connections were open", conns.refused() as f64),
        (
            "connections_timed_out",
            "Connections closed: no first request within --handshake-timeout-ms of opening",
            conns.timed_out() as f64,
        ),
        (
            "connections_idle_closed",
            "HTTP/1.1 connections closed: no next request within --handshake-timeout-ms of the last response",
            conns.idle_closed() as f64,
        ),
        (
            "connections_stalled_bodies",
            "HTTP/1.1 request bodies ended: nothing arrived for --handshake-timeout-ms",
            conns.stalled_bodies() as f64,
        ),
        (
            "pending_request_bytes",
            "Bytes of request messages received and not yet complete, all calls together (bounded by --max-pending-request-mb)",
            conns.pending_request_bytes() as f64,
        ),
        (
            "pending_request_refused",
            "Calls failed with RESOURCE_EXHAUSTED: their message would have passed --max-pending-request-mb",
            conns.pending_refused() as f64,
        ),
        (
            "stalled_request_messages",
            "Calls ended with DEADLINE_EXCEEDED: a message they had begun sent nothing for --handshake-timeout-ms",
            conns.stalled_messages() as f64,
        ),
        (
            "held_answer_bytes",
            "Bytes of complete gRPC answers (every unary answer) not yet handed to their connections (bounded by --max-held-answers-mb)",
            answers.held_bytes() as f64,
        ),
        (
            "held_answers_refused",
            "Calls answered RESOURCE_EXHAUSTED: their answer would have passed --max-held-answers-mb",
            answers.refused() as f64,
        ),
        (
            "held_answers_timed_out",
            "Answers dropped (their stream reset): not taken by the client within --answer-deadline-ms",
            answers.timed_out() as f64,
        ),
        (
            "recordings_bytes",
            "Bytes in the recordings directory (at the last start, plus writes and reservations since)",
            state.recordings_quota.bytes_used() as f64,
        ),
        (
            "recordings_refused",
            "StartRecording refused: --max-recordings or --max-recordings-mb reached",
            state.recordings_quota.refused() as f64,
        ),
        (
            "recordings_stopped_at_limit",
            "Recordings stopped and finished because their next message would pass --max-recordings-mb",
            state.recordings_quota.stopped() as f64,
        ),
        (
            "reports_bytes",
            "Bytes in the after-action reports directory (at the last report, plus its own)",
            state.reports_quota.bytes_used() as f64,
        ),
        (
            "reports_refused",
            "After-action reports not written: --max-reports or --max-reports-mb reached",
            state.reports_quota.refused() as f64,
        ),
    ];
    let fx = crate::foxglove_live::stats().unwrap_or_default();
    let endpoint = [
        (
            "agones_watch_overlong_lines",
            "Lines of the Agones SDK's watch stream over its bound (each dropped the connection)",
            crate::agones::watch_overlong_lines() as f64,
        ),
        ("foxglove_connections", "Connections to the Foxglove endpoint open now", fx.connections as f64),
        ("foxglove_clients", "Foxglove clients connected now (handshake done)", fx.clients as f64),
        (
            "foxglove_refused_connections",
            "Foxglove connections closed at once: --foxglove-max-clients were open",
            fx.refused_connections as f64,
        ),
        (
            "foxglove_failed_handshakes",
            "Foxglove connections closed without a WebSocket handshake (too slow or not Foxglove's)",
            fx.failed_handshakes as f64,
        ),
        ("foxglove_dropped_messages", "Foxglove messages dropped for slow clients (a newer one replaced them)", fx.dropped_messages as f64),
        ("foxglove_stalled_clients", "Foxglove clients closed because they did not read", fx.stalled_clients as f64),
        ("foxglove_queued_messages_max", "The most Foxglove messages waiting for one client now", fx.queued_messages_max as f64),
        ("foxglove_queued_bytes", "Bytes of Foxglove messages waiting for all clients now", fx.queued_bytes as f64),
    ];
    for (name, help, v) in jobs.into_iter().chain(endpoint) {
        let g: Gauge<f64, std::sync::atomic::AtomicU64> = Gauge::default();
        g.set(v);
        registry.register(name, help, g);
    }
    for (name, help, fam) in gauges {
        registry.register(name, help, fam);
    }
    let mut out = String::new();
    let _ = prometheus_client::encoding::text::encode(&mut out, &registry);
    out
}

/// The fallback route: a gRPC request for a service this server does not have gets the gRPC
/// status UNIMPLEMENTED (not an HTTP error from the static files); anything else is one of the web
/// viewer's built files or 404 (`web_files.rs`).
fn static_or_unimplemented(
    web: crate::web_files::WebFiles,
) -> impl Fn(axum::extract::Request) -> std::pin::Pin<Box<dyn std::future::Future<Output = axum::response::Response> + Send>> + Clone {
    move |req: axum::extract::Request| {
        let web = web.clone();
        Box::pin(async move {
            let is_grpc = req
                .headers()
                .get(axum::http::header::CONTENT_TYPE)
                .and_then(|v| v.to_str().ok())
                .is_some_and(|ct| ct.starts_with("application/grpc"));
            if is_grpc {
                return unknown_method(req.uri().path()).into_http();
            }
            web.respond(req.method(), req.uri().path())
        })
    }
}

/// The answer to a gRPC call of a method this server does not have: UNIMPLEMENTED quoting at most
/// [`crate::status::MAX_QUOTE_CHARS`] characters of the path (issue 35: a 12,000-character path
/// came back whole).
fn unknown_method(path: &str) -> tonic::Status {
    tonic::Status::unimplemented(format!("no such gRPC method: {}", crate::status::quote(path)))
}

/// tonic answers a request message over `--max-message-bytes` with OUT_OF_RANGE; the API promises
/// RESOURCE_EXHAUSTED for size limits, so a trailers-only answer with OUT_OF_RANGE (which no
/// service of ours gives) becomes RESOURCE_EXHAUSTED.
fn size_limit_status(mut resp: axum::response::Response) -> axum::response::Response {
    let out_of_range = (tonic::Code::OutOfRange as i32).to_string();
    if resp.headers().get("grpc-status").is_some_and(|v| v.as_bytes() == out_of_range.as_bytes()) {
        let exhausted = (tonic::Code::ResourceExhausted as i32).to_string();
        resp.headers_mut().insert("grpc-status", axum::http::HeaderValue::from_str(&exhausted).expect("digits"));
    }
    resp
}

/// Plays `traj` on `session` in a loop (poses every 2 ms, interpolated) until a client sends a
/// pose or the session closes.
async fn play_demo(session: Arc<needlesim_session::Session>, traj: needlesim_scene::Trajectory) {
    let (t0, t1) = traj.span_s();
    let mut interval = tokio::time::interval(std::time::Duration::from_millis(2));
    let start = tokio::time::Instant::now();
    let mut seq = 0u64;
    loop {
        interval.tick().await;
        if session.client_in_control() {
            tracing::info!(session = %session.id, "a client took control: the demo stops");
            return;
        }
        if session.is_closed() || Arc::strong_count(&session) == 1 {
            return;
        }
        let t = t0 + start.elapsed().as_secs_f64() % (t1 - t0).max(1e-3);
        seq += 1;
        session.write_pose_from_io(needlesim_session::PoseCommand {
            pose: needlesim_scene::base_pose(traj.pose_at(t)),
            seq,
            client_time_ns: 0,
        });
    }
}

/// Interval of the HTTP/2 pings on a connection, and how long its peer has to answer one.
const HTTP2_KEEPALIVE_INTERVAL: std::time::Duration = std::time::Duration::from_secs(30);
const HTTP2_KEEPALIVE_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(20);

/// Bytes of answers dropped (sent or not) that make the allocator give memory back: a few large
/// answers, or many small ones, not every small answer.
const TRIM_AFTER_ANSWER_BYTES: u64 = 1 << 20;

/// Gives the memory of closed streams and closed sessions back to the system (issue 35): glibc
/// keeps freed blocks in its per-thread arenas, so a burst of large messages (a status with 1,000
/// markers is 219 kB) would stay with the process after its streams closed, and so would part of
/// a closed session's matrices. Every 2 s, if streams closed, sessions were freed, connections
/// closed (their HTTP/2 buffers), at least [`TRIM_AFTER_ANSWER_BYTES`] of answers were dropped
/// (issue 35, pass 4: answers under the counted size were not, and 530 MB stayed after every
/// connection had closed) or Control streams timed out waiting for their first message since, the
/// free pages are returned (`malloc_trim`, off the async runtime; the real-time threads do not
/// allocate, so they never wait on it).
async fn give_back_stream_memory(
    state: SharedState,
    answers: Arc<crate::answers::AnswerBudget>,
    conns: Arc<crate::listener::ConnCounters>,
) {
    let mut every = tokio::time::interval(std::time::Duration::from_secs(2));
    every.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    let mut alive = needlesim_session::sessions_alive();
    let mut control_timeouts = crate::grpc::control::first_message_timeouts();
    loop {
        every.tick().await;
        if Arc::strong_count(&state) == 1 {
            return;
        }
        let (was, now) = (alive, needlesim_session::sessions_alive());
        alive = now;
        // (Both counters are taken: neither is left to trigger a later, needless trim.)
        let (streams_closed, answers_released) = (state.streams.take_closed(), answers.take_released(TRIM_AFTER_ANSWER_BYTES));
        let conns_closed = conns.take_closed();
        let (timeouts_were, timeouts) = (control_timeouts, crate::grpc::control::first_message_timeouts());
        control_timeouts = timeouts;
        if streams_closed == 0 && !answers_released && conns_closed == 0 && timeouts == timeouts_were && now >= was {
            continue;
        }
        #[cfg(all(target_os = "linux", target_env = "gnu"))]
        {
            // SAFETY: malloc_trim only releases free memory of the allocator's arenas.
            let _ = tokio::task::spawn_blocking(|| unsafe { libc::malloc_trim(0) }).await;
        }
    }
}

/// Runs the server until `shutdown` resolves. Prints `listening on ADDR` once bound.
pub async fn serve(config: ServeConfig, shutdown: impl std::future::Future<Output = ()> + Send + 'static) -> Result<()> {
    serve_with(config, |_| shutdown).await
}

/// As [`serve`], with the shutdown future made from the server's state once it listens (the
/// Agones integration sends Ready then, and drains before it resolves).
pub async fn serve_with<F>(config: ServeConfig, shutdown: impl FnOnce(SharedState) -> F) -> Result<()>
where
    F: std::future::Future<Output = ()> + Send + 'static,
{
    std::fs::create_dir_all(&config.data_dir).with_context(|| format!("cannot create the data directory {}", config.data_dir.display()))?;
    let state = ServerState::with_admin_token(config.limits.clone(), config.data_dir.clone(), config.admin_token.as_deref());
    remove_stale_device_channels(&state.device_dir());
    let mut demo_session = None;
    let mut default_session = None;
    if let Some(name) = &config.default_scene {
        let scene = needlesim_scene::load_scene(name, config.limits.scene())?;
        let rate = scene.params.tick_rate_hz;
        let s = state.create_session(&scene, rate).map_err(|e| anyhow::anyhow!("default session: {}", e.message()))?;
        // Tokens are never logged: their fingerprints are; the tokens go to the terminal once.
        tracing::info!(
            session = %s.id,
            controller_token_sha256 = %crate::access::fingerprint(&s.controller_token),
            observer_token_sha256 = %crate::access::fingerprint(&s.observer_token),
            "default session '{}' at {} Hz",
            s.scene_name,
            rate
        );
        if config.demo {
            let traj = needlesim_scene::Trajectory::parse_csv(scene.example_trajectory.context("--demo needs a shipped example scene")?)?;
            tokio::spawn(play_demo(s.clone(), traj));
            demo_session = Some(s.clone());
        }
        default_session = Some(s);
    }
    let api = Api { state: state.clone() };
    let max = config.max_message_bytes;
    let (health_reporter, health_service) = tonic_health::server::health_reporter();
    health_reporter.set_serving::<pb::session_service_server::SessionServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::control_service_server::ControlServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::observe_service_server::ObserveServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::simulation_service_server::SimulationServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::recording_service_server::RecordingServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::planning_service_server::PlanningServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::identify_service_server::IdentifyServiceServer<Api>>().await;
    health_reporter.set_serving::<pb::training_service_server::TrainingServiceServer<Api>>().await;
    let reflection_builder = || {
        tonic_reflection::server::Builder::configure()
            .register_encoded_file_descriptor_set(needlesim_proto::FILE_DESCRIPTOR_SET)
            .register_encoded_file_descriptor_set(tonic_health::pb::FILE_DESCRIPTOR_SET)
    };
    let reflection = reflection_builder().build_v1().context("reflection service")?;
    // v1alpha too: grpcio's and older grpcurl's reflection clients speak only v1alpha.
    let reflection_alpha = reflection_builder().build_v1alpha().context("reflection service (v1alpha)")?;
    let routes = tonic::service::Routes::builder()
        .add_service(pb::session_service_server::SessionServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::control_service_server::ControlServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::observe_service_server::ObserveServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::simulation_service_server::SimulationServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::planning_service_server::PlanningServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::recording_service_server::RecordingServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::identify_service_server::IdentifyServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(pb::training_service_server::TrainingServiceServer::new(api.clone()).max_decoding_message_size(max))
        .add_service(health_service)
        .add_service(reflection)
        .add_service(reflection_alpha)
        .clone()
        .routes();
    let web = crate::web_files::WebFiles::load(&config.web_dir);
    let (n_files, web_bytes) = web.size();
    tracing::info!(web_dir = %config.web_dir.display(), files = n_files, bytes = web_bytes, "the web viewer's files are read");
    // gRPC-web on the gRPC routes only: as a plain layer it would answer 400 to static files.
    let metrics_state = state.clone();
    let conns = Arc::new(crate::listener::ConnCounters::default());
    let metrics_conns = conns.clone();
    // Complete answers held for clients that do not read them are bounded (issue 35, `answers.rs`).
    let answers = Arc::new(crate::answers::AnswerBudget::new(config.max_held_answer_bytes, config.answer_deadline));
    let metrics_answers = answers.clone();
    let answers_layer = answers.clone();
    let app = routes
        .into_axum_router()
        .route_layer(tonic_web::GrpcWebLayer::new())
        .route("/metrics", axum::routing::get(move || std::future::ready(metrics_text(&metrics_state, &metrics_conns, &metrics_answers))))
        .fallback(static_or_unimplemented(web))
        .layer(axum::middleware::from_fn(move |req, next| crate::answers::bound_held_answers(answers_layer.clone(), req, next)))
        .layer(tower::util::MapResponseLayer::new(size_limit_status));
    // An idle HTTP/2 connection is pinged; one whose peer does not answer is closed (issue 35).
    // At most --max-streams-per-connection calls at once on one HTTP/2 connection (issue 35: none
    // was advertised, and one connection held 5,000 responses). Each stream's HTTP/2 send buffer
    // is one answer chunk (`transport.rs`).
    let http2 = crate::transport::Http2Settings {
        max_concurrent_streams: config.connections.max_streams_per_connection,
        keepalive_interval: HTTP2_KEEPALIVE_INTERVAL,
        keepalive_timeout: HTTP2_KEEPALIVE_TIMEOUT,
    };
    let mut tls = None;
    if let Some((cert, key)) = &config.tls {
        // By the one rule for local files: a regular file, not a link, at most 1 MiB.
        let read = |path: &std::path::Path, kind: &str| {
            needlesim_localfile::read_local_bytes(path, needlesim_localfile::MAX_CERTIFICATE_BYTES)
                .map_err(|e| anyhow::anyhow!("{}", e.named(kind)))
        };
        let cert = read(cert, "TLS certificate")?;
        let key = read(key, "TLS key")?;
        tls = Some(crate::transport::Tls::from_pem(&cert, &key, config.connections.handshake_timeout).context("TLS configuration")?);
    }
    let listener = tokio::net::TcpListener::bind(config.listen).await.with_context(|| format!("cannot listen on {}", config.listen))?;
    let addr = listener.local_addr()?;
    tracing::info!(%addr, tls = config.tls.is_some(), data_dir = %config.data_dir.display(), "needlesim-server listening");
    println!("listening on {addr}");
    if let Some(fx) = config.foxglove {
        let port = crate::foxglove_live::start(fx, config.foxglove_max_clients, state.clone()).await?;
        tracing::info!(port, "Foxglove endpoint listening");
        println!("foxglove on ws://{}:{port} (Foxglove app: Open connection → Foxglove WebSocket)", fx.ip());
    }
    if let Some(s) = &demo_session {
        let scheme = if config.tls.is_some() { "https" } else { "http" };
        println!(
            "demo: open {scheme}://{addr}/?session={}&token={} (a scripted insertion plays until you take control)",
            s.id, s.controller_token
        );
    }
    if let (Some(s), None) = (&default_session, &demo_session) {
        println!("default session {}: controller token {}, observer token {}", s.id, s.controller_token, s.observer_token);
    }
    // The sessions the server made itself (the default one, --exercise's) are never closed for
    // being idle: they are what the printed URLs point to.
    let mut kept_sessions: Vec<String> = default_session.iter().map(|s| s.id.clone()).collect();
    if let Some(name) = &config.exercise {
        let st = state.clone();
        let name = name.clone();
        let made = tokio::task::spawn_blocking(move || crate::training_service::create_exercise_session(&st, &name, 0.0, false))
            .await
            .context("exercise session task")?
            .map_err(|e| anyhow::anyhow!("exercise session: {}", e.message()))?;
        let scheme = if config.tls.is_some() { "https" } else { "http" };
        let (s, ex) = (&made.session, &made.exercise);
        println!("exercise '{}' in session {}:", ex.exercise.name, s.id);
        println!("  trainee:    {scheme}://{addr}/?session={}&token={}", s.id, s.controller_token);
        println!("  instructor: {scheme}://{addr}/?session={}&token={}&instructor={}", s.id, s.observer_token, ex.instructor_token());
        println!("  observers:  {scheme}://{addr}/?session={}&token={}", s.id, s.observer_token);
        kept_sessions.push(s.id.clone());
    }
    drop(demo_session);
    drop(default_session);
    let shutdown = shutdown(state.clone());
    // At the signal the sessions close first (their device channel files are removed, and their
    // streams end with NOT_FOUND, `grpc/streams.rs`): the graceful drain below waits for every
    // open stream, which a client may hold for as long as it likes (issue 35).
    // The graceful drain itself is bounded (issue 35): a client that never reads its Simulate
    // stream, or never ends a request body, would hold it for ever; `shutdown_grace` after the
    // sessions are closed (their recordings finished), the server returns without those
    // connections (`main` then stops the runtime without waiting for their tasks).
    let closing = state.clone();
    let sessions_closed = Arc::new(tokio::sync::Notify::new());
    let closed_tx = sessions_closed.clone();
    let shutdown = async move {
        shutdown.await;
        tokio::task::spawn_blocking(move || closing.close_all()).await.ok();
        closed_tx.notify_one();
    };
    tokio::spawn(give_back_stream_memory(state.clone(), answers, conns.clone()));
    if state.limits.session_idle_timeout_s > 0 {
        let timeout = std::time::Duration::from_secs(state.limits.session_idle_timeout_s);
        tokio::spawn(crate::idle::close_idle_sessions(Arc::downgrade(&state), timeout, kept_sessions));
    }
    // Tells each connection when its requests arrive and end (the deadlines of `listener.rs`) and
    // bounds the pauses of HTTP/1.1 request bodies.
    let guard = crate::listener::ConnGuardLayer::new(conns.clone(), config.connections);
    let incoming = crate::listener::incoming(listener, config.connections, conns.clone());
    let service = tower::Layer::layer(&guard, tonic::service::Routes::from(app).prepare());
    let serving = crate::transport::serve(incoming, service, tls, http2, shutdown);
    let grace = config.shutdown_grace;
    let result = tokio::select! {
        () = serving => Ok::<(), anyhow::Error>(()),
        () = async {
            sessions_closed.notified().await;
            tokio::time::sleep(grace).await;
        } => {
            tracing::warn!(
                grace_ms = grace.as_millis() as u64,
                connections = conns.open(),
                "connections still open --shutdown-grace-ms after the sessions closed: stopping without them"
            );
            Ok(())
        }
    };
    let closing = state.clone();
    tokio::task::spawn_blocking(move || closing.close_all()).await.ok();
    result
}

/// Removes the device channel files in `dir` left by servers that died without closing their
/// sessions (`kill -9`, a crash: shared memory outlives processes), never a live server's
/// (`needlesim_channel::shm::remove_stale_channels`: a live channel's creator holds a lock on it).
/// Issue 35: 81 such files had piled up in /dev/shm.
fn remove_stale_device_channels(dir: &std::path::Path) {
    match needlesim_channel::shm::remove_stale_channels(dir, None) {
        Ok(sweep) => {
            if !sweep.removed.is_empty() {
                tracing::info!(dir = %dir.display(), removed = sweep.removed.len(), live = sweep.live, "removed the device channel files of servers that are gone");
            }
            for (path, e) in &sweep.errors {
                tracing::warn!(path = %path.display(), "cannot check or remove a stale device channel file: {e}");
            }
        }
        // No device directory yet (data_dir/devices is created with the first channel): nothing left over.
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => tracing::warn!(dir = %dir.display(), "cannot look for stale device channel files: {e}"),
    }
}

/// Shared handle for tests and benchmarks that embed the server.
pub type SharedState = Arc<ServerState>;
