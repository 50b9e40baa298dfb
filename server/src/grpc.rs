//! The gRPC services of `needlesim.v1`: sessions, control, observe, offline simulation and
//! recordings, on top of the session engine. Every call validates its input and answers with
//! the right status: INVALID_ARGUMENT naming the field, NOT_FOUND, PERMISSION_DENIED,
//! RESOURCE_EXHAUSTED, FAILED_PRECONDITION.

use std::collections::HashMap;
use std::path::PathBuf;
use std::pin::Pin;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, RwLock};
use std::time::Duration;

use needlesim_core::MeshLimits;
use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio_stream::Stream;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status, Streaming};

use crate::convert;
use crate::jobs::{JobKind, JobLimiter};
use crate::session::{PoseCommand, Session};
use crate::status::{ApiError, SizeLimit, quote, status_of};

type BoxStream<T> = Pin<Box<dyn Stream<Item = Result<T, Status>> + Send + 'static>>;

/// Limits of the server.
#[derive(Debug, Clone)]
pub struct ServerLimits {
    pub max_sessions: usize,
    pub max_observers_per_session: usize,
    pub mesh: MeshLimits,
    /// Largest trajectory accepted by Simulate, in samples.
    pub max_trajectory_samples: usize,
    /// Longest offline simulation, in ticks (one Simulate call; each simulation of a plan).
    pub max_simulate_ticks: u64,
    /// Largest estimated memory of a scene's session (`scene::estimated_session_bytes`), bytes.
    pub max_session_bytes: u64,
    /// Offline calls (Simulate, Plan, every Identify call) running at once.
    pub max_offline_jobs: usize,
    /// Plans running at once (each also takes an offline slot).
    pub max_plans: usize,
    /// Largest image a Track call decodes, in pixels (width × height, read from the header).
    pub max_image_pixels: u64,
}

impl ServerLimits {
    /// What a scene loaded for a client may cost.
    pub fn scene(&self) -> needlesim_scene::SceneLimits {
        needlesim_scene::SceneLimits { mesh: self.mesh, max_session_bytes: self.max_session_bytes }
    }
}

impl Default for ServerLimits {
    fn default() -> Self {
        Self {
            max_sessions: 16,
            max_observers_per_session: 256,
            mesh: MeshLimits { max_nodes: 250_000, max_triangles: 500_000 },
            max_trajectory_samples: 1_000_000,
            max_simulate_ticks: crate::simulate::DEFAULT_MAX_TICKS,
            max_session_bytes: 1280 << 20,
            max_offline_jobs: 4,
            max_plans: 2,
            max_image_pixels: crate::identify::track::DEFAULT_MAX_IMAGE_PIXELS,
        }
    }
}

/// State shared by the services.
pub struct ServerState {
    pub sessions: RwLock<HashMap<String, Arc<Session>>>,
    /// Sessions being started: reserved under the `sessions` write lock, so that `sessions` plus
    /// these never exceed `max_sessions`.
    pending_sessions: Arc<AtomicUsize>,
    pub limits: ServerLimits,
    pub data_dir: PathBuf,
    /// Permits of the offline calls (Simulate, Plan, Identify).
    pub jobs: Arc<JobLimiter>,
    /// The SHA-256 of the admin token (`serve --admin-token-file`), which opens every recording.
    admin_token_sha256: Option<crate::access::TokenDigest>,
}

/// A place among the `max_sessions` sessions, held while a session starts; given back when
/// dropped unless the session was registered.
pub struct SessionSlot {
    pending: Arc<AtomicUsize>,
    armed: bool,
}

impl Drop for SessionSlot {
    fn drop(&mut self) {
        if self.armed {
            self.pending.fetch_sub(1, Ordering::AcqRel);
        }
    }
}

impl ServerState {
    pub fn new(limits: ServerLimits, data_dir: PathBuf) -> Arc<Self> {
        Self::with_admin_token(limits, data_dir, None)
    }

    /// A state whose `admin_token` (if any) opens every recording; only its digest is kept.
    pub fn with_admin_token(limits: ServerLimits, data_dir: PathBuf, admin_token: Option<&str>) -> Arc<Self> {
        let jobs = JobLimiter::new(limits.max_offline_jobs, limits.max_plans);
        Arc::new(Self {
            sessions: RwLock::default(),
            pending_sessions: Arc::default(),
            limits,
            data_dir,
            admin_token_sha256: admin_token.map(crate::access::token_digest),
            jobs,
        })
    }

    /// Reserves a place for a new session, checking the limit and reserving in one step (under
    /// the sessions lock): concurrent creates never exceed `max_sessions`.
    pub fn reserve_session_slot(&self) -> Result<SessionSlot, Status> {
        let sessions = self.sessions.write().expect("sessions lock");
        if sessions.len() + self.pending_sessions.load(Ordering::Acquire) >= self.limits.max_sessions {
            return Err(Status::resource_exhausted(format!("the server runs its limit of {} sessions", self.limits.max_sessions)));
        }
        self.pending_sessions.fetch_add(1, Ordering::AcqRel);
        Ok(SessionSlot { pending: self.pending_sessions.clone(), armed: true })
    }

    /// Where device channels are created: tmpfs (/dev/shm) when there is one, else the data dir.
    fn device_dir(&self) -> PathBuf {
        let shm = std::path::Path::new("/dev/shm");
        if shm.is_dir() { shm.to_path_buf() } else { self.data_dir.join("devices") }
    }

    /// Starts a session and registers it.
    pub fn create_session(&self, scene: &needlesim_scene::Scene, tick_rate_hz: f64) -> Result<Arc<Session>, Status> {
        self.create_session_with(scene, tick_rate_hz, false)
    }

    /// Starts a session, with a shared-memory device channel when `device_channel`, and registers it.
    pub fn create_session_with(
        &self,
        scene: &needlesim_scene::Scene,
        tick_rate_hz: f64,
        device_channel: bool,
    ) -> Result<Arc<Session>, Status> {
        let slot = self.reserve_session_slot()?;
        self.create_session_in(slot, scene, tick_rate_hz, device_channel)
    }

    /// Starts a session in a reserved `slot`, with a shared-memory device channel when
    /// `device_channel`, and registers it.
    pub fn create_session_in(
        &self,
        mut slot: SessionSlot,
        scene: &needlesim_scene::Scene,
        tick_rate_hz: f64,
        device_channel: bool,
    ) -> Result<Arc<Session>, Status> {
        let dir = device_channel.then(|| self.device_dir());
        if let Some(d) = &dir {
            std::fs::create_dir_all(d).map_err(|e| Status::internal(format!("cannot create {}: {e}", d.display())))?;
        }
        let s = Session::start(scene, tick_rate_hz, dir.as_deref()).map_err(|e| Status::from(ApiError::from(e)))?;
        {
            // Registered and unreserved in one step.
            let mut sessions = self.sessions.write().expect("sessions lock");
            sessions.insert(s.id.clone(), s.clone());
            slot.armed = false;
            self.pending_sessions.fetch_sub(1, Ordering::AcqRel);
        }
        tracing::info!(session = %s.id, scene = %s.scene_name, n_nodes = s.tissue.mesh().n_nodes(), tick_rate_hz, "session created");
        Ok(s)
    }

    fn session(&self, id: &str) -> Result<Arc<Session>, Status> {
        if id.is_empty() {
            return Err(Status::invalid_argument("session_id is empty"));
        }
        self.sessions
            .read()
            .expect("sessions lock")
            .get(id)
            .cloned()
            .ok_or_else(|| Status::not_found(format!("no session '{}'", quote(id))))
    }

    /// Closes every session (server shutdown).
    pub fn close_all(&self) {
        let all: Vec<_> = self.sessions.write().expect("sessions lock").drain().map(|(_, s)| s).collect();
        for s in all {
            s.close();
        }
    }
}

/// What a token allows.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Controller,
    Observer,
}

fn token_of<T>(req: &Request<T>) -> Option<String> {
    let v = req.metadata().get("authorization")?.to_str().ok()?;
    v.strip_prefix("Bearer ").map(|t| t.trim().to_owned())
}

fn authorize<T>(req: &Request<T>, s: &Session, role: Role) -> Result<(), Status> {
    let Some(tok) = token_of(req) else {
        return Err(Status::permission_denied("missing token: send `authorization: Bearer <token>` metadata"));
    };
    // Constant time, and both compared (no short cut that would tell which one matched).
    let is_controller = crate::access::token_matches(&tok, &s.controller_token);
    let is_observer = crate::access::token_matches(&tok, &s.observer_token);
    let ok = match role {
        Role::Controller => is_controller,
        Role::Observer => is_observer | is_controller,
    };
    if ok {
        Ok(())
    } else {
        Err(Status::permission_denied(match role {
            Role::Controller => "wrong token: driving a session needs its controller token",
            Role::Observer => "wrong token: watching a session needs its observer or controller token",
        }))
    }
}

fn session_info(s: &Session) -> pb::SessionInfo {
    pb::SessionInfo {
        session_id: s.id.clone(),
        scene_name: s.scene_name.clone(),
        n_nodes: s.tissue.mesh().n_nodes() as u32,
        n_triangles: s.tissue.mesh().n_triangles() as u32,
        tick_rate_hz: s.tick_rate_hz,
        created_unix_ms: s.created_unix_ms,
        tick: s.counters.ticks.load(Ordering::Relaxed),
        n_observers: s.n_observers.load(Ordering::Relaxed) as u32,
        recording: s.recorder.lock().expect("recorder lock").as_ref().map(|r| r.info().name).unwrap_or_default(),
        target_names: s.target_names.clone(),
        device_channel_path: s.device_channel_path.as_ref().map(|p| p.display().to_string()).unwrap_or_default(),
        device_stale: s.counters.device_stale.load(Ordering::Relaxed) != 0,
        device_channel_broken: s.counters.device_channel_broken.load(Ordering::Relaxed) != 0,
    }
}

fn check_pose(p: Option<&pb::Pose2>, field: &str) -> Result<needlesim_core::BasePose, Status> {
    let p = p.ok_or_else(|| Status::invalid_argument(format!("{field} is missing")))?;
    let pose = convert::pose_from_pb(p);
    if !pose.is_finite() {
        return Err(Status::invalid_argument(format!("{field} ({}, {}, {}) is not finite", p.x_m, p.y_m, p.theta_rad)));
    }
    Ok(pose)
}

/// Implements all services over one shared state.
#[derive(Clone)]
pub struct Api {
    pub state: Arc<ServerState>,
}

#[tonic::async_trait]
impl pb::session_service_server::SessionService for Api {
    async fn create_session(&self, req: Request<pb::CreateSessionRequest>) -> Result<Response<pb::CreateSessionResponse>, Status> {
        let r = req.into_inner();
        // The limit is checked and a place reserved first, in one step: a create over the limit
        // costs nothing, and concurrent creates never exceed it.
        let slot = self.state.reserve_session_slot()?;
        let scene = load_scene_from_pb(r.scene.clone(), self.state.limits.scene()).await?;
        let rate = if r.tick_rate_hz == 0.0 { scene.params.tick_rate_hz } else { r.tick_rate_hz };
        if !(rate.is_finite() && (500.0..=1000.0).contains(&rate)) {
            return Err(Status::invalid_argument(format!("tick_rate_hz = {rate}: a session runs at 500..1000 Hz")));
        }
        let state = self.state.clone();
        let device = r.device_channel;
        let s = tokio::task::spawn_blocking(move || state.create_session_in(slot, &scene, rate, device))
            .await
            .map_err(|e| Status::internal(format!("session task: {e}")))??;
        if r.record {
            start_recording(&self.state, &s)?;
        }
        Ok(Response::new(pb::CreateSessionResponse {
            session: Some(session_info(&s)),
            controller_token: s.controller_token.clone(),
            observer_token: s.observer_token.clone(),
        }))
    }

    async fn list_sessions(&self, _req: Request<pb::ListSessionsRequest>) -> Result<Response<pb::ListSessionsResponse>, Status> {
        let mut sessions: Vec<_> = self.state.sessions.read().expect("sessions lock").values().map(|s| session_info(s)).collect();
        sessions.sort_by(|a, b| a.created_unix_ms.cmp(&b.created_unix_ms).then(a.session_id.cmp(&b.session_id)));
        Ok(Response::new(pb::ListSessionsResponse { sessions }))
    }

    async fn get_session(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::SessionInfo>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        Ok(Response::new(session_info(&s)))
    }

    async fn get_mesh(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::Mesh>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        Ok(Response::new(convert::mesh_to_pb(s.tissue.mesh())))
    }

    async fn get_stats(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::SessionStats>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        let st = s.stats();
        Ok(Response::new(pb::SessionStats {
            ticks: st.ticks,
            compute_p50_us: st.compute_us[0],
            compute_p99_us: st.compute_us[1],
            compute_p999_us: st.compute_us[2],
            compute_max_us: st.compute_us[3],
            lateness_p50_us: st.lateness_us[0],
            lateness_p99_us: st.lateness_us[1],
            lateness_p999_us: st.lateness_us[2],
            missed_deadlines: st.missed_deadlines,
            superseded_poses: st.superseded_poses,
            dropped_records: st.dropped_records,
            column_misses: st.column_misses,
            rejected_poses: st.rejected_poses,
            clamped_ticks: st.clamped_ticks,
            faulted: st.fault.is_some(),
            fault: st.fault.unwrap_or_default(),
        }))
    }

    async fn close_session(&self, req: Request<pb::CloseSessionRequest>) -> Result<Response<pb::CloseSessionResponse>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        self.state.sessions.write().expect("sessions lock").remove(&s.id);
        tokio::task::spawn_blocking(move || s.close()).await.map_err(|e| Status::internal(format!("close: {e}")))?;
        Ok(Response::new(pb::CloseSessionResponse {}))
    }
}

#[tonic::async_trait]
impl pb::control_service_server::ControlService for Api {
    type ControlStream = BoxStream<pb::ControlResponse>;

    async fn control(&self, req: Request<Streaming<pb::ControlRequest>>) -> Result<Response<Self::ControlStream>, Status> {
        let token = token_of(&req);
        let client = client_address(&req);
        let mut inbound = req.into_inner();
        let first =
            inbound.message().await?.ok_or_else(|| Status::invalid_argument("the control stream ended before its first message"))?;
        let s = self.state.session(&first.session_id)?;
        if !token.as_deref().is_some_and(|t| crate::access::token_matches(t, &s.controller_token)) {
            return Err(Status::permission_denied("driving a session needs its controller token (`authorization: Bearer <token>`)"));
        }
        let pose = check_pose(first.base.as_ref(), "base")?;
        // One controller at a time: this stream holds the session's control lease until it ends.
        let mut lease = s.control.acquire_stream(&client, first.take_over).await.map_err(|busy| control_refused(&s, busy))?;
        if first.take_over {
            tracing::info!(session = %s.id, %client, "a Control stream took control over");
        }
        lease.write_if_held(|| {
            if first.flip_bevel {
                s.request_bevel_flip_from_io();
            }
            s.write_client_pose_from_io(PoseCommand { pose, seq: first.seq.max(1), client_time_ns: first.client_time_ns });
        });
        let (tx, rx) = mpsc::channel(256);
        // When the controller closes its side, the response stream ends too.
        let client_done = Arc::new(std::sync::atomic::AtomicBool::new(false));
        // Poses in: latest value wins; a malformed message ends the stream with its reason, and so
        // does a take-over by another client.
        let s_in = s.clone();
        let tx_err = tx.clone();
        let done_in = client_done.clone();
        tokio::spawn(async move {
            let _done = SetOnDrop(done_in);
            let mut seq = first.seq.max(1);
            loop {
                let msg = tokio::select! {
                    m = inbound.message() => m,
                    () = lease.revoked() => {
                        let _ = tx_err.send(Err(Status::aborted(format!(
                            "control of session {} was taken over by another client", s_in.id
                        )))).await;
                        return;
                    }
                };
                let held = match msg {
                    Ok(Some(m)) if m.flip_bevel && m.base.is_none() => lease.write_if_held(|| {
                        s_in.request_bevel_flip_from_io();
                    }),
                    Ok(Some(m)) => match check_pose(m.base.as_ref(), "base") {
                        Ok(pose) => {
                            seq = if m.seq > seq { m.seq } else { seq + 1 };
                            lease.write_if_held(|| {
                                if m.flip_bevel {
                                    s_in.request_bevel_flip_from_io();
                                }
                                s_in.write_client_pose_from_io(PoseCommand { pose, seq, client_time_ns: m.client_time_ns });
                            })
                        }
                        Err(e) => {
                            s_in.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
                            let _ = tx_err.send(Err(e)).await;
                            return;
                        }
                    },
                    Ok(None) | Err(_) => return,
                };
                if !held {
                    // Taken over between the message and its write: the pose was not used.
                    let _ =
                        tx_err.send(Err(Status::aborted(format!("control of session {} was taken over by another client", s_in.id)))).await;
                    return;
                }
            }
        });
        // Responses out: one per tick; a slow controller skips ticks rather than delaying anyone.
        let mut ticks = s.all_ticks.subscribe();
        tokio::spawn(async move {
            loop {
                if client_done.load(Ordering::Relaxed) {
                    return;
                }
                match ticks.recv().await {
                    Ok(rec) => {
                        if tx.send(Ok(convert::control_response(&rec))).await.is_err() {
                            return;
                        }
                    }
                    Err(tokio::sync::broadcast::error::RecvError::Lagged(_)) => continue,
                    Err(tokio::sync::broadcast::error::RecvError::Closed) => return,
                }
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }

    async fn set_pose(&self, req: Request<pb::SetPoseRequest>) -> Result<Response<pb::ControlResponse>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        let pose = check_pose(req.get_ref().base.as_ref(), "base").inspect_err(|_| {
            s.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
        })?;
        let r = req.get_ref();
        let client = if r.client_id.is_empty() { client_address(&req) } else { format!("id:{}", r.client_id) };
        // One controller at a time: refused while a Control stream or another SetPose client
        // holds the lease, unless it takes over.
        s.control
            .with_unary(&client, r.take_over, || {
                let seq = s.counters.poses_written.load(Ordering::Relaxed) + 1;
                s.write_client_pose_from_io(PoseCommand { pose, seq, client_time_ns: 0 });
            })
            .await
            .map_err(|busy| control_refused(&s, busy))?;
        Ok(Response::new(convert::control_response(&s.latest_record())))
    }

    async fn flip_bevel(&self, req: Request<pb::FlipBevelRequest>) -> Result<Response<pb::FlipBevelResponse>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        if !s.has_bevel {
            return Err(Status::failed_precondition(format!(
                "session {}: the needle has a symmetric tip (a rigid needle, or a flexible one without bevel_force_ratio); there is no bevel to flip",
                s.id
            )));
        }
        let r = req.get_ref();
        let client = if r.client_id.is_empty() { client_address(&req) } else { format!("id:{}", r.client_id) };
        // A flip is driving: one controller at a time, as for SetPose.
        let flips_requested = s
            .control
            .with_unary(&client, r.take_over, || s.request_bevel_flip_from_io())
            .await
            .map_err(|busy| control_refused(&s, busy))?;
        Ok(Response::new(pb::FlipBevelResponse { flips_requested }))
    }
}

/// Who sends a request, for the control lease: its IP address (the port changes with each
/// connection a browser opens), or "unknown".
fn client_address<T>(req: &Request<T>) -> String {
    req.remote_addr().map_or_else(|| "unknown".to_owned(), |a| format!("ip:{}", a.ip()))
}

/// FAILED_PRECONDITION for a request refused by the session's control lease.
fn control_refused(s: &Session, busy: crate::control_lease::Busy) -> Status {
    Status::failed_precondition(format!("session {}: {busy}; one controller at a time (set `take_over` to take control from it)", s.id))
}

/// Loads (parses, meshes, factorises) a scene off the async runtime; a scene over the mesh or
/// memory limits is RESOURCE_EXHAUSTED, any other problem INVALID_ARGUMENT naming the field
/// (`status::ApiError::from_chain`).
pub(crate) async fn load_scene_from_pb(
    src: Option<pb::SceneSource>,
    limits: needlesim_scene::SceneLimits,
) -> Result<needlesim_scene::Scene, Status> {
    tokio::task::spawn_blocking(move || convert::scene_from_pb(src.as_ref(), &limits))
        .await
        .map_err(|e| Status::internal(format!("scene task: {e}")))?
        .map_err(|e| status_of("scene", &e))
}

/// Sets its flag when dropped (when the task holding it ends, however it ends).
struct SetOnDrop(Arc<std::sync::atomic::AtomicBool>);

impl Drop for SetOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Counts an observer for as long as it lives.
struct ObserverGuard {
    session: Arc<Session>,
    wants_field: bool,
}

impl Drop for ObserverGuard {
    fn drop(&mut self) {
        self.session.n_observers.fetch_sub(1, Ordering::Relaxed);
        if self.wants_field {
            self.session.field_subscribers.fetch_sub(1, Ordering::Relaxed);
        }
    }
}

#[tonic::async_trait]
impl pb::observe_service_server::ObserveService for Api {
    type ObserveStream = BoxStream<pb::Frame>;

    async fn observe(&self, req: Request<pb::ObserveRequest>) -> Result<Response<Self::ObserveStream>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        let r = req.into_inner();
        if !(r.rate_hz.is_finite() && r.rate_hz >= 0.0 && r.rate_hz <= s.tick_rate_hz) {
            return Err(Status::invalid_argument(format!(
                "rate_hz = {}: 0 (every tick) or up to the tick rate {} Hz",
                r.rate_hz, s.tick_rate_hz
            )));
        }
        // Checked and counted in one step: concurrent observers never exceed the limit.
        let max = self.state.limits.max_observers_per_session as u64;
        if s.n_observers.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < max).then_some(n + 1)).is_err() {
            return Err(Status::resource_exhausted(format!(
                "session {} has its limit of {} observers",
                s.id, self.state.limits.max_observers_per_session
            )));
        }
        if r.include_displacements {
            s.field_subscribers.fetch_add(1, Ordering::Relaxed);
        }
        let guard = ObserverGuard { session: s.clone(), wants_field: r.include_displacements };
        let (tx, rx) = mpsc::channel(64);
        if r.rate_hz == 0.0 {
            // Every tick, or an exact count of the ticks this stream missed.
            let mut ticks = s.all_ticks.subscribe();
            tokio::spawn(async move {
                let _guard = guard;
                let names = _guard.session.target_names.clone();
                let mut missed = 0u64;
                loop {
                    match ticks.recv().await {
                        Ok(rec) => {
                            if tx.send(Ok(convert::frame_from_record(&rec, &names, missed))).await.is_err() {
                                return;
                            }
                            missed = 0;
                        }
                        Err(tokio::sync::broadcast::error::RecvError::Lagged(n)) => missed += n,
                        Err(tokio::sync::broadcast::error::RecvError::Closed) => return,
                    }
                }
            });
        } else {
            // Rendering: the latest frame at the requested rate; a slow client only slows itself.
            let period = Duration::from_secs_f64(1.0 / r.rate_hz);
            let mut latest = s.latest.clone();
            let mut field = s.field.clone();
            tokio::spawn(async move {
                let _guard = guard;
                let names = _guard.session.target_names.clone();
                let mut interval = tokio::time::interval(period);
                interval.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
                let mut last_tick = u64::MAX;
                loop {
                    interval.tick().await;
                    if latest.has_changed().is_err() {
                        return;
                    }
                    let rec = latest.borrow_and_update().clone();
                    if rec.tick == last_tick {
                        continue;
                    }
                    last_tick = rec.tick;
                    let mut frame = convert::frame_from_record(&rec, &names, 0);
                    if r.include_displacements {
                        frame.node_displacement_m = field.borrow_and_update().displacement_m.clone();
                    }
                    if tx.send(Ok(frame)).await.is_err() {
                        return;
                    }
                }
            });
        }
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }
}

#[tonic::async_trait]
impl pb::simulation_service_server::SimulationService for Api {
    type SimulateStream = BoxStream<pb::SimulateResponse>;

    async fn simulate(&self, req: Request<pb::SimulateRequest>) -> Result<Response<Self::SimulateStream>, Status> {
        let r = req.into_inner();
        if r.trajectory.len() > self.state.limits.max_trajectory_samples {
            return Err(ApiError::from(SizeLimit {
                what: "trajectory".to_owned(),
                amount: r.trajectory.len() as u64,
                limit: self.state.limits.max_trajectory_samples as u64,
                unit: "samples",
                hint: String::new(),
            })
            .into());
        }
        // Held by the worker until it ends; refused at once when the server is busy.
        let permit = self.state.jobs.try_start(JobKind::Simulate)?;
        let limits = self.state.limits.clone();
        let (tx, rx) = mpsc::channel(16);
        // Parse and validate before answering, so that errors are statuses, not stream items.
        let (scene, traj) = tokio::task::spawn_blocking(move || -> Result<_, Status> {
            let scene = convert::scene_from_pb(r.scene.as_ref(), &limits.scene()).map_err(|e| status_of("scene", &e))?;
            let traj = if r.trajectory.is_empty() {
                let text = scene
                    .example_trajectory
                    .ok_or_else(|| Status::invalid_argument("trajectory is empty and the scene is not a shipped example with its own"))?;
                needlesim_scene::Trajectory::parse_csv(text).map_err(|e| Status::internal(format!("{e:#}")))?
            } else {
                convert::trajectory_from_pb(&r.trajectory).map_err(|e| status_of("trajectory", &e))?
            };
            let (t0, t1) = traj.span_s();
            let ticks = ((t1 - t0) * scene.params.tick_rate_hz).round() as u64;
            if ticks > limits.max_simulate_ticks {
                return Err(ApiError::from(SizeLimit {
                    what: format!("the trajectory ({:.3} s at {} Hz)", t1 - t0, scene.params.tick_rate_hz),
                    amount: ticks,
                    limit: limits.max_simulate_ticks,
                    unit: "ticks",
                    hint: " (server flag --max-simulate-ticks)".to_owned(),
                })
                .into());
            }
            Ok((scene, traj))
        })
        .await
        .map_err(|e| Status::internal(format!("simulate task: {e}")))??;
        let decimate = r.decimate.max(1) as u64;
        // A worker thread of the blocking pool: never a session's real-time thread.
        tokio::task::spawn_blocking(move || {
            let _permit = permit;
            if let Err(e) = run_offline(&scene, &traj, decimate, &tx) {
                let _ = tx.blocking_send(Err(ApiError::from(&e).into()));
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }
}

/// Rows of the time series per `SeriesChunk` message (about 200 bytes each without targets).
pub const SERIES_CHUNK_ROWS: usize = 1000;

/// Runs an offline simulation, streaming progress, the time series in chunks of at most
/// [`SERIES_CHUNK_ROWS`] rows, then the result. Memory is bounded by one chunk and the channel,
/// whatever the length: step times go into a histogram, not a list. Ends early, without error,
/// when the client goes away.
fn run_offline(
    scene: &needlesim_scene::Scene,
    traj: &needlesim_scene::Trajectory,
    decimate: u64,
    tx: &mpsc::Sender<Result<pb::SimulateResponse, Status>>,
) -> Result<(), needlesim_core::SimError> {
    use pb::simulate_response::Event;
    let send = |event: Event| tx.blocking_send(Ok(pb::SimulateResponse { event: Some(event) })).is_ok();
    let started = std::time::Instant::now();
    let mut params = scene.params.clone();
    params.initial_pose = needlesim_scene::base_pose(traj.samples[0].1);
    let mut sim = needlesim_core::Simulation::new(scene.tissue.clone(), params)?;
    let rate = sim.params().tick_rate_hz;
    let (t0, t1) = traj.span_s();
    let n_ticks = ((t1 - t0) * rate).round() as u64;
    let mut chunk = Vec::with_capacity(SERIES_CHUNK_ROWS);
    let mut step_ns = hdrhistogram::Histogram::<u64>::new_with_bounds(1, 60_000_000_000, 3).expect("valid bounds");
    let progress_every = (n_ticks / 20).max(1);
    for k in 0..=n_ticks {
        if tx.is_closed() {
            return Ok(()); // the client went away
        }
        let t = std::time::Instant::now();
        let out = sim.step(needlesim_scene::base_pose(traj.pose_at(t0 + k as f64 / rate)))?;
        step_ns.saturating_record((t.elapsed().as_nanos() as u64).max(1));
        if k % decimate == 0 || k == n_ticks {
            chunk.push(convert::series_row(out, t0, &scene.target_names));
            if chunk.len() == SERIES_CHUNK_ROWS && !send(Event::Series(pb::SeriesChunk { rows: std::mem::take(&mut chunk) })) {
                return Ok(());
            }
        }
        sim.prefetch_columns(8)?;
        if k % progress_every == 0 && !send(Event::Progress(pb::SimulateProgress { ticks_done: k, ticks_total: n_ticks })) {
            return Ok(());
        }
    }
    if !chunk.is_empty() && !send(Event::Series(pb::SeriesChunk { rows: chunk })) {
        return Ok(());
    }
    let mut u = vec![0.0; scene.tissue.n_dofs()];
    sim.displacement_field_into(&mut u);
    let result = pb::SimulateResult {
        rows: vec![],
        ticks: sim.stats().ticks,
        wall_s: started.elapsed().as_secs_f64(),
        step_p50_us: step_ns.value_at_quantile(0.5) as f64 * 1e-3,
        step_p99_us: step_ns.value_at_quantile(0.99) as f64 * 1e-3,
        final_displacement_m: u,
    };
    send(Event::Result(result));
    Ok(())
}

fn start_recording(state: &ServerState, s: &Arc<Session>) -> Result<pb::RecordingInfo, Status> {
    let mut slot = s.recorder.lock().expect("recorder lock");
    if let Some(r) = slot.as_ref() {
        return Err(Status::failed_precondition(format!("session {} is already recording to {}", s.id, r.info().name)));
    }
    let dir = state.data_dir.join("recordings");
    let rec = crate::recording::Recorder::start(&dir, &s.id).map_err(|e| Status::internal(format!("cannot start the recording: {e}")))?;
    // The recording belongs to this session: its tokens (their digests) open it, also later.
    let owner = crate::recording::RecordingOwner {
        session_id: s.id.clone(),
        token_sha256: vec![crate::access::token_digest(&s.controller_token), crate::access::token_digest(&s.observer_token)],
    };
    if let Err(e) = crate::recording::write_owner(&dir, &rec.info().name, &owner) {
        drop(rec);
        return Err(Status::internal(format!("cannot start the recording: {e}")));
    }
    let info = recording_info(&rec.info());
    *slot = Some(rec);
    Ok(info)
}

fn recording_info(i: &crate::recording::RecordingInfo) -> pb::RecordingInfo {
    pb::RecordingInfo {
        name: i.name.clone(),
        session_id: i.session_id.clone(),
        size_bytes: i.size_bytes,
        messages: i.messages,
        finished: i.finished,
    }
}

/// What a request's token opens among the recordings.
enum RecordingAccess {
    /// The admin token: every recording.
    Admin,
    /// A session's token: the recordings whose owner lists its digest.
    Token(String),
    /// No token: no recording.
    Nothing,
}

impl RecordingAccess {
    /// The access of a request's token; a request without one opens nothing.
    fn of<T>(state: &ServerState, req: &Request<T>) -> Self {
        match (token_of(req), &state.admin_token_sha256) {
            (Some(tok), Some(admin)) if crate::access::digest_matches(&tok, admin) => Self::Admin,
            (Some(tok), _) => Self::Token(tok),
            (None, _) => Self::Nothing,
        }
    }

    fn opens(&self, owner: Option<&crate::recording::RecordingOwner>) -> bool {
        match self {
            Self::Admin => true,
            Self::Nothing => false,
            Self::Token(tok) => {
                owner.is_some_and(|o| o.token_sha256.iter().fold(false, |any, d| any | crate::access::digest_matches(tok, d)))
            }
        }
    }
}

#[tonic::async_trait]
impl pb::recording_service_server::RecordingService for Api {
    type DownloadRecordingStream = BoxStream<pb::RecordingChunk>;

    async fn start_recording(&self, req: Request<pb::StartRecordingRequest>) -> Result<Response<pb::RecordingInfo>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        Ok(Response::new(start_recording(&self.state, &s)?))
    }

    async fn stop_recording(&self, req: Request<pb::StopRecordingRequest>) -> Result<Response<pb::RecordingInfo>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        let rec = s
            .recorder
            .lock()
            .expect("recorder lock")
            .take()
            .ok_or_else(|| Status::failed_precondition(format!("session {} is not recording", s.id)))?;
        let info = tokio::task::spawn_blocking(move || rec.finish())
            .await
            .map_err(|e| Status::internal(format!("recording task: {e}")))?
            .map_err(|e| Status::internal(format!("finishing the recording: {e}")))?;
        Ok(Response::new(recording_info(&info)))
    }

    async fn list_recordings(&self, req: Request<pb::ListRecordingsRequest>) -> Result<Response<pb::ListRecordingsResponse>, Status> {
        let access = RecordingAccess::of(&self.state, &req);
        let dir = self.state.data_dir.join("recordings");
        let list = tokio::task::spawn_blocking(move || {
            let mut list = crate::recording::list_recordings(&dir);
            list.retain(|r| access.opens(crate::recording::read_owner(&dir, &r.name).as_ref()));
            list
        })
        .await
        .map_err(|e| Status::internal(format!("list task: {e}")))?;
        Ok(Response::new(pb::ListRecordingsResponse { recordings: list.iter().map(recording_info).collect() }))
    }

    async fn download_recording(
        &self,
        req: Request<pb::DownloadRecordingRequest>,
    ) -> Result<Response<Self::DownloadRecordingStream>, Status> {
        let access = RecordingAccess::of(&self.state, &req);
        let name = req.get_ref().name.clone();
        let dir = self.state.data_dir.join("recordings");
        // Never follows a link and never waits for a FIFO; blocking file I/O off the runtime.
        let file = tokio::task::spawn_blocking(move || {
            let file = crate::recording::open_recording(&dir, &name).map_err(|e| Status::from(ApiError::from(&e)))?;
            let owner = crate::recording::read_owner(&dir, &name);
            if !access.opens(owner.as_ref()) {
                return Err(Status::permission_denied(match owner {
                    _ if matches!(access, RecordingAccess::Nothing) => format!(
                        "missing token: recording {name:?} opens with the observer or controller token of the session that made it \
                         (or the admin token), as `authorization: Bearer <token>` metadata"
                    ),
                    Some(o) => format!(
                        "recording {name:?} belongs to session {}: it opens with that session's observer or controller token, or the admin token",
                        o.session_id
                    ),
                    None => format!("recording {name:?} has no owner file: it opens with the admin token only"),
                }));
            }
            Ok(file)
        })
        .await
        .map_err(|e| Status::internal(format!("download task: {e}")))??;
        let (tx, rx) = mpsc::channel(8);
        tokio::task::spawn_blocking(move || {
            use std::io::Read;
            let mut file = file;
            let mut offset = 0u64;
            let mut buf = vec![0u8; 256 * 1024];
            loop {
                match file.read(&mut buf) {
                    Ok(0) => return,
                    Ok(n) => {
                        let chunk = pb::RecordingChunk { data: buf[..n].to_vec(), offset };
                        offset += n as u64;
                        if tx.blocking_send(Ok(chunk)).is_err() {
                            return;
                        }
                    }
                    Err(e) => {
                        let _ = tx.blocking_send(Err(Status::internal(format!("reading the recording: {e}"))));
                        return;
                    }
                }
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }
}
