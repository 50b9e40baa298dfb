//! The gRPC services of `needlesim.v1`: sessions, control, observe, offline simulation and
//! recordings, on top of the session engine. Every call validates its input and answers with
//! the right status: INVALID_ARGUMENT naming the field, NOT_FOUND, PERMISSION_DENIED,
//! RESOURCE_EXHAUSTED, FAILED_PRECONDITION.

use std::collections::HashMap;
use std::path::PathBuf;
use std::pin::Pin;
use std::sync::atomic::Ordering;
use std::sync::{Arc, RwLock};
use std::time::Duration;

use needlesim_core::MeshLimits;
use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio_stream::Stream;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status, Streaming};

use crate::convert;
use crate::session::{PoseCommand, Session};

type BoxStream<T> = Pin<Box<dyn Stream<Item = Result<T, Status>> + Send + 'static>>;

/// Limits of the server.
#[derive(Debug, Clone)]
pub struct ServerLimits {
    pub max_sessions: usize,
    pub max_observers_per_session: usize,
    pub mesh: MeshLimits,
    /// Largest trajectory accepted by Simulate, in samples.
    pub max_trajectory_samples: usize,
    /// Longest offline simulation, in ticks.
    pub max_simulate_ticks: u64,
}

impl Default for ServerLimits {
    fn default() -> Self {
        Self {
            max_sessions: 16,
            max_observers_per_session: 256,
            mesh: MeshLimits { max_nodes: 250_000, max_triangles: 500_000 },
            max_trajectory_samples: 1_000_000,
            max_simulate_ticks: crate::simulate::DEFAULT_MAX_TICKS,
        }
    }
}

/// State shared by the services.
pub struct ServerState {
    pub sessions: RwLock<HashMap<String, Arc<Session>>>,
    pub limits: ServerLimits,
    pub data_dir: PathBuf,
}

impl ServerState {
    pub fn new(limits: ServerLimits, data_dir: PathBuf) -> Arc<Self> {
        Arc::new(Self { sessions: RwLock::default(), limits, data_dir })
    }

    /// Where device channels are created: tmpfs (/dev/shm) when there is one, else the data dir.
    fn device_dir(&self) -> PathBuf {
        let shm = std::path::Path::new("/dev/shm");
        if shm.is_dir() { shm.to_path_buf() } else { self.data_dir.join("devices") }
    }

    /// Starts a session and registers it.
    pub fn create_session(&self, scene: &crate::scene::Scene, tick_rate_hz: f64) -> Result<Arc<Session>, Status> {
        self.create_session_with(scene, tick_rate_hz, false)
    }

    /// Starts a session, with a shared-memory device channel when `device_channel`, and registers it.
    pub fn create_session_with(
        &self,
        scene: &crate::scene::Scene,
        tick_rate_hz: f64,
        device_channel: bool,
    ) -> Result<Arc<Session>, Status> {
        if self.sessions.read().expect("sessions lock").len() >= self.limits.max_sessions {
            return Err(Status::resource_exhausted(format!("the server runs its limit of {} sessions", self.limits.max_sessions)));
        }
        let dir = device_channel.then(|| self.device_dir());
        if let Some(d) = &dir {
            std::fs::create_dir_all(d).map_err(|e| Status::internal(format!("cannot create {}: {e}", d.display())))?;
        }
        let s = Session::start(scene, tick_rate_hz, dir.as_deref()).map_err(|e| match e {
            crate::session::SessionError::TickRate(_) => Status::invalid_argument(format!("tick_rate_hz: {e}")),
            _ => Status::internal(e.to_string()),
        })?;
        self.sessions.write().expect("sessions lock").insert(s.id.clone(), s.clone());
        tracing::info!(session = %s.id, scene = %s.scene_name, n_nodes = s.tissue.mesh().n_nodes(), tick_rate_hz, "session created");
        Ok(s)
    }

    fn session(&self, id: &str) -> Result<Arc<Session>, Status> {
        if id.is_empty() {
            return Err(Status::invalid_argument("session_id is empty"));
        }
        self.sessions.read().expect("sessions lock").get(id).cloned().ok_or_else(|| Status::not_found(format!("no session '{id}'")))
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
    let ok = match role {
        Role::Controller => tok == s.controller_token,
        Role::Observer => tok == s.observer_token || tok == s.controller_token,
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
        let scene = load_scene_from_pb(r.scene.clone(), self.state.limits.mesh).await?;
        let rate = if r.tick_rate_hz == 0.0 { scene.params.tick_rate_hz } else { r.tick_rate_hz };
        if !(rate.is_finite() && (500.0..=1000.0).contains(&rate)) {
            return Err(Status::invalid_argument(format!("tick_rate_hz = {rate}: a session runs at 500..1000 Hz")));
        }
        let state = self.state.clone();
        let device = r.device_channel;
        let s = tokio::task::spawn_blocking(move || state.create_session_with(&scene, rate, device))
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
        let mut inbound = req.into_inner();
        let first =
            inbound.message().await?.ok_or_else(|| Status::invalid_argument("the control stream ended before its first message"))?;
        let s = self.state.session(&first.session_id)?;
        if token.as_deref() != Some(s.controller_token.as_str()) {
            return Err(Status::permission_denied("driving a session needs its controller token (`authorization: Bearer <token>`)"));
        }
        let pose = check_pose(first.base.as_ref(), "base")?;
        if first.flip_bevel {
            s.request_bevel_flip_from_io();
        }
        s.write_client_pose_from_io(PoseCommand { pose, seq: first.seq.max(1), client_time_ns: first.client_time_ns });
        let (tx, rx) = mpsc::channel(256);
        // When the controller closes its side, the response stream ends too.
        let client_done = Arc::new(std::sync::atomic::AtomicBool::new(false));
        // Poses in: latest value wins; a malformed message ends the stream with its reason.
        let s_in = s.clone();
        let tx_err = tx.clone();
        let done_in = client_done.clone();
        tokio::spawn(async move {
            let _done = SetOnDrop(done_in);
            let mut seq = first.seq.max(1);
            loop {
                match inbound.message().await {
                    Ok(Some(m)) if m.flip_bevel && m.base.is_none() => {
                        s_in.request_bevel_flip_from_io();
                    }
                    Ok(Some(m)) => match check_pose(m.base.as_ref(), "base") {
                        Ok(pose) => {
                            if m.flip_bevel {
                                s_in.request_bevel_flip_from_io();
                            }
                            seq = if m.seq > seq { m.seq } else { seq + 1 };
                            s_in.write_client_pose_from_io(PoseCommand { pose, seq, client_time_ns: m.client_time_ns });
                        }
                        Err(e) => {
                            s_in.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
                            let _ = tx_err.send(Err(e)).await;
                            return;
                        }
                    },
                    Ok(None) | Err(_) => return,
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
        let pose = check_pose(req.get_ref().base.as_ref(), "base")?;
        let seq = s.counters.poses_written.load(Ordering::Relaxed) + 1;
        s.write_client_pose_from_io(PoseCommand { pose, seq, client_time_ns: 0 });
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
        Ok(Response::new(pb::FlipBevelResponse { flips_requested: s.request_bevel_flip_from_io() }))
    }
}

/// Loads (parses, meshes, factorises) a scene off the async runtime; a scene over the mesh
/// limits is RESOURCE_EXHAUSTED, any other problem INVALID_ARGUMENT naming the field.
pub(crate) async fn load_scene_from_pb(
    src: Option<pb::SceneSource>,
    limits: needlesim_core::MeshLimits,
) -> Result<crate::scene::Scene, Status> {
    tokio::task::spawn_blocking(move || convert::scene_from_pb(src.as_ref(), &limits))
        .await
        .map_err(|e| Status::internal(format!("scene task: {e}")))?
        .map_err(|e| {
            let msg = format!("{e:#}");
            if msg.contains("over the limit") { Status::resource_exhausted(msg) } else { Status::invalid_argument(msg) }
        })
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
        if s.n_observers.load(Ordering::Relaxed) as usize >= self.state.limits.max_observers_per_session {
            return Err(Status::resource_exhausted(format!(
                "session {} has its limit of {} observers",
                s.id, self.state.limits.max_observers_per_session
            )));
        }
        s.n_observers.fetch_add(1, Ordering::Relaxed);
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
            return Err(Status::resource_exhausted(format!(
                "trajectory has {} samples, over the limit of {}",
                r.trajectory.len(),
                self.state.limits.max_trajectory_samples
            )));
        }
        let limits = self.state.limits.clone();
        let (tx, rx) = mpsc::channel(16);
        // Parse and validate before answering, so that errors are statuses, not stream items.
        let (scene, traj) = tokio::task::spawn_blocking(move || -> Result<_, Status> {
            let scene = convert::scene_from_pb(r.scene.as_ref(), &limits.mesh).map_err(|e| Status::invalid_argument(format!("{e:#}")))?;
            let traj = if r.trajectory.is_empty() {
                let text = scene
                    .example_trajectory
                    .ok_or_else(|| Status::invalid_argument("trajectory is empty and the scene is not a shipped example with its own"))?;
                crate::scene::Trajectory::parse_csv(text).map_err(|e| Status::internal(format!("{e:#}")))?
            } else {
                convert::trajectory_from_pb(&r.trajectory).map_err(|e| Status::invalid_argument(format!("{e:#}")))?
            };
            let (t0, t1) = traj.span_s();
            let ticks = ((t1 - t0) * scene.params.tick_rate_hz).round() as u64;
            if ticks > limits.max_simulate_ticks {
                return Err(Status::resource_exhausted(format!(
                    "the trajectory needs {ticks} ticks, over the limit of {}",
                    limits.max_simulate_ticks
                )));
            }
            Ok((scene, traj))
        })
        .await
        .map_err(|e| Status::internal(format!("simulate task: {e}")))??;
        let decimate = r.decimate.max(1) as u64;
        // A worker thread of the blocking pool: never a session's real-time thread.
        tokio::task::spawn_blocking(move || {
            let result = run_offline(&scene, &traj, decimate, &tx);
            if let Err(e) = result {
                let _ = tx.blocking_send(Err(Status::internal(format!("{e:#}"))));
            }
        });
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }
}

fn run_offline(
    scene: &crate::scene::Scene,
    traj: &crate::scene::Trajectory,
    decimate: u64,
    tx: &mpsc::Sender<Result<pb::SimulateResponse, Status>>,
) -> anyhow::Result<()> {
    let started = std::time::Instant::now();
    let mut params = scene.params.clone();
    params.initial_pose = traj.samples[0].1;
    let mut sim = needlesim_core::Simulation::new(scene.tissue.clone(), params)?;
    let rate = sim.params().tick_rate_hz;
    let (t0, t1) = traj.span_s();
    let n_ticks = ((t1 - t0) * rate).round() as u64;
    let mut rows = Vec::new();
    let mut times = Vec::with_capacity(n_ticks as usize + 1);
    let progress_every = (n_ticks / 20).max(1);
    for k in 0..=n_ticks {
        let t = std::time::Instant::now();
        let out = sim.step(traj.pose_at(t0 + k as f64 / rate))?;
        times.push(t.elapsed().as_secs_f64());
        if k % decimate == 0 || k == n_ticks {
            rows.push(convert::series_row(out, t0, &scene.target_names));
        }
        sim.prefetch_columns(8)?;
        if k % progress_every == 0 {
            let p = pb::SimulateResponse {
                event: Some(pb::simulate_response::Event::Progress(pb::SimulateProgress { ticks_done: k, ticks_total: n_ticks })),
            };
            if tx.blocking_send(Ok(p)).is_err() {
                return Ok(()); // the client went away
            }
        }
    }
    times.sort_by(f64::total_cmp);
    let pct = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize] * 1e6;
    let mut u = vec![0.0; scene.tissue.n_dofs()];
    sim.displacement_field_into(&mut u);
    let result = pb::SimulateResult {
        rows,
        ticks: sim.stats().ticks,
        wall_s: started.elapsed().as_secs_f64(),
        step_p50_us: pct(0.5),
        step_p99_us: pct(0.99),
        final_displacement_m: u,
    };
    let _ = tx.blocking_send(Ok(pb::SimulateResponse { event: Some(pb::simulate_response::Event::Result(result)) }));
    Ok(())
}

fn start_recording(state: &ServerState, s: &Arc<Session>) -> Result<pb::RecordingInfo, Status> {
    let mut slot = s.recorder.lock().expect("recorder lock");
    if let Some(r) = slot.as_ref() {
        return Err(Status::failed_precondition(format!("session {} is already recording to {}", s.id, r.info().name)));
    }
    let dir = state.data_dir.join("recordings");
    let rec = crate::recording::Recorder::start(&dir, &s.id).map_err(|e| Status::internal(format!("cannot start the recording: {e}")))?;
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

    async fn list_recordings(&self, _req: Request<pb::ListRecordingsRequest>) -> Result<Response<pb::ListRecordingsResponse>, Status> {
        let dir = self.state.data_dir.join("recordings");
        let list = tokio::task::spawn_blocking(move || crate::recording::list_recordings(&dir))
            .await
            .map_err(|e| Status::internal(format!("list task: {e}")))?;
        Ok(Response::new(pb::ListRecordingsResponse { recordings: list.iter().map(recording_info).collect() }))
    }

    async fn download_recording(
        &self,
        req: Request<pb::DownloadRecordingRequest>,
    ) -> Result<Response<Self::DownloadRecordingStream>, Status> {
        let name = req.get_ref().name.clone();
        let dir = self.state.data_dir.join("recordings");
        let file = crate::recording::open_recording(&dir, &name).map_err(|e| {
            let msg = e.to_string();
            if msg.contains("not found") || msg.contains("No such file") {
                Status::not_found(msg)
            } else {
                Status::invalid_argument(format!("name: {msg}"))
            }
        })?;
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
