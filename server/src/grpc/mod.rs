//! The gRPC services of `needlesim.v1`, one module per service — sessions, control, observe,
//! simulate (offline), recordings, plan — over one shared state ([`ServerState`]); identify is in
//! `grpc_identify.rs`. Every call validates its input and answers with the right status
//! (`status.rs`): INVALID_ARGUMENT naming the field, NOT_FOUND, PERMISSION_DENIED,
//! RESOURCE_EXHAUSTED, FAILED_PRECONDITION. Messages are built and read in `convert.rs`.

pub(crate) mod control;
mod observe;
pub mod plan;
mod recordings;
mod sessions;
mod simulate;
mod streams;

pub(crate) use recordings::start_recording;
pub use simulate::SERIES_CHUNK_ROWS;
pub(crate) use streams::of_session;
pub use streams::{StreamLimiter, StreamPermit};

use std::collections::HashMap;
use std::path::PathBuf;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, RwLock};

use needlesim_core::MeshLimits;
use needlesim_proto::v1 as pb;
use needlesim_session::Session;
use tokio_stream::Stream;
use tonic::{Request, Status};

use crate::convert;
use crate::jobs::JobLimiter;
use crate::status::{ApiError, quote, status_of};

pub(crate) type BoxStream<T> = Pin<Box<dyn Stream<Item = Result<T, Status>> + Send + 'static>>;

/// Limits of the server.
#[derive(Debug, Clone)]
pub struct ServerLimits {
    pub max_sessions: usize,
    /// Most streams a client holds open on one session (Observe, WatchScore, WatchUltrasound,
    /// GetReport; `--max-observers`).
    pub max_observers_per_session: usize,
    /// Most server-streaming calls open at once on the whole server (`--max-streams`; `streams.rs`).
    pub max_streams: usize,
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
    /// Most recordings (`.mcap` files) in `<data dir>/recordings/` (`--max-recordings`).
    pub max_recordings: usize,
    /// Most bytes in `<data dir>/recordings/` (`--max-recordings-mb`).
    pub max_recordings_bytes: u64,
    /// Most after-action reports (`.html` files) in `<data dir>/reports/` (`--max-reports`).
    pub max_reports: usize,
    /// Most bytes in `<data dir>/reports/` (`--max-reports-mb`).
    pub max_reports_bytes: u64,
    /// How long a Control or Control3 stream may wait for its first message, ms
    /// (`--control-first-message-ms`; issue 35): then it ends with DEADLINE_EXCEEDED.
    pub control_first_message_ms: u64,
    /// How long a client has to take a counted answer whole, and to make room for an offline
    /// job's next message, ms (`--answer-deadline-ms`; issue 35): `answers.rs`, `jobs.rs`.
    pub answer_deadline_ms: u64,
    /// A session that nobody drives, watches or controls for this long is closed, s
    /// (`--session-idle-timeout-s`; 0: never; `idle.rs`).
    pub session_idle_timeout_s: u64,
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
            max_streams: 1024,
            mesh: MeshLimits { max_nodes: 250_000, max_triangles: 500_000 },
            max_trajectory_samples: 1_000_000,
            max_simulate_ticks: needlesim_offline::DEFAULT_MAX_TICKS,
            max_session_bytes: 1280 << 20,
            max_offline_jobs: 4,
            max_plans: 2,
            max_image_pixels: needlesim_identify::track::DEFAULT_MAX_IMAGE_PIXELS,
            max_recordings: 1000,
            max_recordings_bytes: crate::quota::mib(10240),
            max_reports: 1000,
            max_reports_bytes: crate::quota::mib(1024),
            control_first_message_ms: 5000,
            answer_deadline_ms: 30_000,
            session_idle_timeout_s: 1800,
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
    /// Set by [`ServerState::begin_drain`] (issue 22, `agones.rs`): new sessions are refused.
    draining: AtomicBool,
    /// The live exercises, by session id (issue 20, `training_live.rs`).
    pub training: crate::training_live::Registry,
    /// The open server-streaming calls (issue 35, `streams.rs`).
    pub streams: StreamLimiter,
    /// The bound on `<data dir>/recordings/` (issue 35, `quota.rs`).
    pub recordings_quota: Arc<crate::quota::DirQuota>,
    /// The bound on `<data dir>/reports/`, the after-action reports (issue 35, `quota.rs`).
    pub reports_quota: Arc<crate::quota::DirQuota>,
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
        let jobs = JobLimiter::new(limits.max_offline_jobs, limits.max_plans, std::time::Duration::from_millis(limits.answer_deadline_ms));
        let streams = StreamLimiter::new(limits.max_streams);
        let recordings_quota = crate::quota::DirQuota::new(
            "recordings",
            crate::recording::EXTENSION,
            ("--max-recordings", limits.max_recordings),
            ("--max-recordings-mb", limits.max_recordings_bytes),
        );
        let reports_quota = crate::quota::DirQuota::new(
            "reports",
            "html",
            ("--max-reports", limits.max_reports),
            ("--max-reports-mb", limits.max_reports_bytes),
        );
        Arc::new(Self {
            sessions: RwLock::default(),
            pending_sessions: Arc::default(),
            limits,
            data_dir,
            admin_token_sha256: admin_token.map(crate::access::token_digest),
            jobs,
            draining: AtomicBool::new(false),
            training: Default::default(),
            streams,
            recordings_quota,
            reports_quota,
        })
    }

    /// Reserves a place for a new session, checking the limit and reserving in one step (under
    /// the sessions lock): concurrent creates never exceed `max_sessions`.
    pub fn reserve_session_slot(&self) -> Result<SessionSlot, Status> {
        let sessions = self.sessions.write().expect("sessions lock");
        if self.draining.load(Ordering::Acquire) {
            return Err(Status::unavailable(
                "the server is draining for shutdown: running sessions finish, new ones are refused; ask the allocator for another server",
            ));
        }
        if sessions.len() + self.pending_sessions.load(Ordering::Acquire) >= self.limits.max_sessions {
            return Err(Status::resource_exhausted(format!("the server runs its limit of {} sessions", self.limits.max_sessions)));
        }
        self.pending_sessions.fetch_add(1, Ordering::AcqRel);
        Ok(SessionSlot { pending: self.pending_sessions.clone(), armed: true })
    }

    /// Drain (server shutdown, issue 22): from now on new sessions are refused with UNAVAILABLE;
    /// running ones go on. Set under the sessions lock, so no reservation slips past it.
    pub fn begin_drain(&self) {
        let _sessions = self.sessions.write().expect("sessions lock");
        self.draining.store(true, Ordering::Release);
    }

    /// Sessions running plus those being started.
    pub fn session_count(&self) -> usize {
        let sessions = self.sessions.read().expect("sessions lock");
        sessions.len() + self.pending_sessions.load(Ordering::Acquire)
    }

    /// Where device channels are created: tmpfs (/dev/shm) when there is one, else the data dir.
    pub(crate) fn device_dir(&self) -> PathBuf {
        let shm = std::path::Path::new("/dev/shm");
        if shm.is_dir() { shm.to_path_buf() } else { self.data_dir.join("devices") }
    }

    /// A permit for one `what` stream, of `session` if it watches one: counted against
    /// `--max-observers` there and `--max-streams` on the server (`streams.rs`).
    pub(crate) fn admit_stream(&self, session: Option<&Session>, what: &str) -> Result<StreamPermit, Status> {
        self.streams.admit(session, self.limits.max_observers_per_session, what)
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
        slot: SessionSlot,
        scene: &needlesim_scene::Scene,
        tick_rate_hz: f64,
        device_channel: bool,
    ) -> Result<Arc<Session>, Status> {
        let dir = device_channel.then(|| self.device_dir());
        if let Some(d) = &dir {
            std::fs::create_dir_all(d).map_err(|e| Status::internal(format!("cannot create {}: {e}", d.display())))?;
        }
        let s = Session::start(scene, tick_rate_hz, dir.as_deref()).map_err(|e| Status::from(ApiError::from(e)))?;
        Ok(self.register(slot, s))
    }

    /// Starts a 3D session of `scene` at `tick_rate_hz` in a reserved `slot` (its tissue
    /// factorised here), with a shared-memory device channel of dimension 3 when `device_channel`,
    /// and registers it.
    pub fn create_session3_in(
        &self,
        slot: SessionSlot,
        scene: &needlesim_scene::Scene3d,
        tick_rate_hz: f64,
        device_channel: bool,
    ) -> Result<Arc<Session>, Status> {
        self.create_session3_with_targets_in(slot, scene, tick_rate_hz, device_channel, Vec::new())
    }

    /// [`ServerState::create_session3_in`] with `extra_targets` appended to the scene's (an
    /// exercise's own targets, named `exercise-<i>`).
    pub fn create_session3_with_targets_in(
        &self,
        slot: SessionSlot,
        scene: &needlesim_scene::Scene3d,
        tick_rate_hz: f64,
        device_channel: bool,
        extra_targets: Vec<needlesim_core::sim3::Target3>,
    ) -> Result<Arc<Session>, Status> {
        let dir = device_channel.then(|| self.device_dir());
        if let Some(d) = &dir {
            std::fs::create_dir_all(d).map_err(|e| Status::internal(format!("cannot create {}: {e}", d.display())))?;
        }
        let model = Arc::new(scene.tissue_model().map_err(|e| status_of("scene", &e))?);
        let initial =
            needlesim_offline::simulate3::base_pose3(&scene.initial_pose).map_err(|e| Status::from(ApiError::invalid("scene", e)))?;
        let mut params = needlesim_offline::simulate3::sim3_params(scene, initial);
        params.tick_rate_hz = tick_rate_hz;
        let mut names: Vec<String> = scene.targets.iter().map(|t| t.name.clone()).collect();
        names.extend((0..extra_targets.len()).map(|i| format!("exercise-{i}")));
        params.targets.extend(extra_targets);
        let s = Session::start3(&scene.name, model, params, names, dir.as_deref()).map_err(|e| Status::from(ApiError::from(e)))?;
        Ok(self.register(slot, s))
    }

    /// Whether a recording could start now (`--max-recordings`, `--max-recordings-mb`): checked
    /// before a create with `record` does any work, so that a full directory costs nothing and
    /// starts no session (issue 35). RESOURCE_EXHAUSTED naming the flag, as StartRecording.
    pub(crate) fn check_recording_room(&self) -> Result<(), Status> {
        let dir = self.data_dir.join("recordings");
        // Admitted and given back at once: the recording's own start admits again.
        let probe = self.recordings_quota.admit(&dir, crate::recording::START_BYTES);
        probe.map(drop).map_err(|e| Status::from(ApiError::from(&crate::recording::RecordingError::Quota(e))))
    }

    /// Undoes a create that failed after its session was registered (a recording that could not
    /// start): the session leaves the registry and its exercise's (no report: the exercise never
    /// began for the client, who got no token) and is closed. Blocking (joins its threads).
    pub(crate) fn discard_session(&self, s: &Arc<Session>) {
        self.sessions.write().expect("sessions lock").remove(&s.id);
        crate::training_live::discard(&self.training, &s.id);
        s.close();
        tracing::info!(session = %s.id, "session discarded: its create failed");
    }

    /// The recording a create asked for, started as the create's last step: a create succeeds
    /// whole or leaves nothing, so a recording that cannot start (the directory filled since
    /// [`Self::check_recording_room`]) discards the session, whose tokens nobody got. Blocking.
    pub(crate) fn start_recording_or_discard(&self, s: &Arc<Session>) -> Result<(), Status> {
        start_recording(self, s, false).inspect_err(|_| self.discard_session(s)).map(drop)
    }

    /// Registers a started session and frees its reservation.
    pub(crate) fn register(&self, mut slot: SessionSlot, s: Arc<Session>) -> Arc<Session> {
        {
            // Registered and unreserved in one step.
            let mut sessions = self.sessions.write().expect("sessions lock");
            sessions.insert(s.id.clone(), s.clone());
            slot.armed = false;
            self.pending_sessions.fetch_sub(1, Ordering::AcqRel);
        }
        tracing::info!(session = %s.id, scene = %s.scene_name, dimension = s.dimension(), n_nodes = s.tissue.n_nodes(), tick_rate_hz = s.tick_rate_hz, "session created");
        s
    }

    pub(crate) fn session(&self, id: &str) -> Result<Arc<Session>, Status> {
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

    /// Removes `s` from the sessions (if it is still the one under its id) and closes it: its
    /// real-time thread stops, its recording is finished, an exercise's report is written.
    /// Blocking: call it off the async runtime (CloseSession, `idle.rs`).
    pub fn close_session_blocking(&self, s: &Arc<Session>) {
        {
            let mut sessions = self.sessions.write().expect("sessions lock");
            if sessions.get(&s.id).is_some_and(|held| Arc::ptr_eq(held, s)) {
                sessions.remove(&s.id);
            }
        }
        s.close();
        crate::training_live::on_close(&self.training, &self.data_dir, &self.reports_quota, s);
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
pub(crate) enum Role {
    Controller,
    Observer,
}

pub(crate) fn token_of<T>(req: &Request<T>) -> Option<String> {
    let v = req.metadata().get("authorization")?.to_str().ok()?;
    v.strip_prefix("Bearer ").map(|t| t.trim().to_owned())
}

pub(crate) fn authorize<T>(req: &Request<T>, s: &Session, role: Role) -> Result<(), Status> {
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

/// Implements all services over one shared state.
#[derive(Clone)]
pub struct Api {
    pub state: Arc<ServerState>,
}

/// Loads (parses, meshes, factorises) a session's scene, 2D or 3D
/// ([`convert::session_scene_from_pb`]), off the async runtime; a scene over the mesh, memory or
/// TOML size limits is RESOURCE_EXHAUSTED, any other problem INVALID_ARGUMENT naming the field
/// (`status::ApiError::from_chain`).
pub(crate) async fn load_session_scene_from_pb(
    src: Option<pb::SceneSource>,
    limits: needlesim_scene::SceneLimits,
) -> Result<convert::SessionScene, Status> {
    tokio::task::spawn_blocking(move || convert::session_scene_from_pb(src.as_ref(), &limits))
        .await
        .map_err(|e| Status::internal(format!("scene task: {e}")))?
        .map_err(|e| status_of("scene", &e))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The codec's bound on decoded sizes (needlesim-proto's `codec.rs`, issue 35) lets a Simulate
    /// trajectory at the server's sample limit through: the two limits stay in step.
    #[test]
    fn a_trajectory_at_the_sample_limit_fits_the_decoded_size_bound() {
        let samples = ServerLimits::default().max_trajectory_samples as u64;
        assert!(samples <= needlesim_proto::codec::MAX_REPEATED_MESSAGES, "{samples}");
    }

    /// Issue 35 (hostile pass, finding 1): a create that fails after its session was registered
    /// (a recording that could not start) is undone whole: the session and its exercise leave
    /// the registries, its `--max-sessions` place is free again, and no report is written.
    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn issue_35_a_discarded_session_leaves_nothing_behind() {
        let dir = std::env::temp_dir().join(format!("needlesim-discard-{}", std::process::id()));
        let state = ServerState::new(ServerLimits { max_sessions: 1, ..Default::default() }, dir.clone());
        let st = state.clone();
        let made = tokio::task::spawn_blocking(move || crate::training_service::create_exercise_session(&st, "biopsy-2d", 0.0, false))
            .await
            .unwrap()
            .unwrap();
        assert!(state.reserve_session_slot().is_err(), "the server is full");
        let (st, s) = (state.clone(), made.session.clone());
        tokio::task::spawn_blocking(move || st.discard_session(&s)).await.unwrap();
        assert!(state.sessions.read().unwrap().is_empty());
        assert!(crate::training_live::exercise_of(&state.training, &made.session.id).is_none());
        assert!(made.exercise.closed.load(Ordering::Acquire));
        assert!(state.reserve_session_slot().is_ok(), "its place is free again");
        let reports = dir.join("reports");
        assert!(!reports.exists() || reports.read_dir().unwrap().next().is_none(), "no report for a create that failed");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
