//! `TrainingService` (proto/needlesim/v1/training.proto): exercise sessions, "placed", the score
//! stream, the instructor's calls, the end of an exercise and its report, the ultrasound slice.
//! The state lives in `training_live.rs`; the messages are built in `training_convert.rs`.

use std::sync::Arc;
use std::time::Duration;

use needlesim_proto::v1 as pb;
use needlesim_session::Session;
use needlesim_training::run::{prepare_2d, prepare_3d};
use needlesim_training::{EXERCISES, load_exercise};
use tonic::{Request, Response, Status};

use crate::grpc::{Api, BoxStream, ServerState, StreamPermit, token_of};
use crate::status::{ApiError, quote};
use crate::training_convert as tc;
use crate::training_live::{LiveExercise, Who};
use crate::training_ultrasound::{ProbeSpec, UltrasoundHub, default_probe_2d, default_probe_3d};

/// Bytes per report chunk.
const REPORT_CHUNK_BYTES: usize = 64 << 10;
const ALL: &[Who] = &[Who::Trainee, Who::Instructor, Who::Observer];
const DRIVERS: &[Who] = &[Who::Trainee, Who::Instructor];
const INSTRUCTOR: &[Who] = &[Who::Instructor];

/// A session created from an exercise: the session and its exercise.
pub struct ExerciseSession {
    pub session: Arc<Session>,
    pub exercise: Arc<LiveExercise>,
}

/// Starts a session of the shipped exercise `name` at `tick_rate_hz` (0: the scene's), its
/// tap attached and the exercise registered (blocking: the scene is meshed and factorised).
pub fn create_exercise_session(
    state: &Arc<ServerState>,
    name: &str,
    tick_rate_hz: f64,
    device_channel: bool,
) -> Result<ExerciseSession, Status> {
    if !EXERCISES.iter().any(|e| e.0 == name) {
        let names: Vec<&str> = EXERCISES.iter().map(|e| e.0).collect();
        return Err(Status::invalid_argument(format!("exercise: '{}' is not a shipped exercise ({})", quote(name), names.join(", "))));
    }
    // The session limit is checked and a place reserved first, in one step (as CreateSession):
    // a create on a full server is refused before the exercise is loaded, meshed or factorised.
    let slot = state.reserve_session_slot()?;
    let ex = load_exercise(name).map_err(|e| Status::internal(format!("shipped exercise {name}: {e}")))?;
    let limits = state.limits.mesh;
    let check_rate = |scene_rate: f64| {
        let rate = if tick_rate_hz == 0.0 { scene_rate } else { tick_rate_hz };
        if rate.is_finite() && (500.0..=1000.0).contains(&rate) {
            Ok(rate)
        } else {
            Err(Status::invalid_argument(format!("tick_rate_hz = {}: a session runs at 500..1000 Hz", needlesim_core::num::num(rate))))
        }
    };
    let prepare_err = |e: needlesim_training::ExerciseRunError| match ApiError::from(&e) {
        ApiError::ResourceExhausted(m) => Status::resource_exhausted(format!("exercise {name}: {m}")),
        _ => Status::internal(format!("shipped exercise {name}: {e}")),
    };
    let (s, spec, targets, probe) = if ex.dim == 2 {
        let p = prepare_2d(&ex, &limits).map_err(prepare_err)?;
        let rate = check_rate(p.scene.params.tick_rate_hz)?;
        let s = state.create_session_in(slot, &p.scene, rate, device_channel)?;
        let bbox = p.scene.tissue.mesh().bounding_box_m();
        (s, p.spec, p.targets, ProbeSpec::Two(default_probe_2d(bbox)))
    } else {
        let p = prepare_3d(&ex, &limits).map_err(prepare_err)?;
        let rate = check_rate(p.scene.tick_rate_hz)?;
        let pose = p.scene.initial_pose;
        let [w, x, y, z] = pose.quat_wxyz;
        let axis = [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)];
        let probe = ProbeSpec::Three(default_probe_3d(p.scene.mesh.nodes_m(), pose.position_m, axis));
        let s = state.create_session3_with_targets_in(slot, &p.scene, rate, device_channel, p.added_targets)?;
        (s, p.spec, p.targets, probe)
    };
    let hub = UltrasoundHub::new(probe, targets.iter().map(|t| (t.centre_m, t.radius_m)).collect());
    let live = LiveExercise::new(&s.id, ex, spec, targets, s.scene_name.clone(), s.tick_rate_hz, hub);
    if let Err(e) = crate::training_live::attach(&state.training, &s, live.clone()) {
        state.sessions.write().expect("sessions lock").remove(&s.id);
        s.close();
        return Err(e);
    }
    tracing::info!(session = %s.id, exercise = %live.exercise.name, instructor_token_sha256 = %crate::access::fingerprint(live.instructor_token()), "exercise session created");
    Ok(ExerciseSession { session: s, exercise: live })
}

impl Api {
    /// The session and its exercise; FAILED_PRECONDITION for a session without one.
    fn exercise(&self, session_id: &str) -> Result<(Arc<Session>, Arc<LiveExercise>), Status> {
        let s = self.state.session(session_id)?;
        let ex = crate::training_live::exercise_of(&self.state.training, &s.id)
            .ok_or_else(|| Status::failed_precondition(format!("session {} was not created from an exercise", s.id)))?;
        Ok((s, ex))
    }

    fn exercise_for<T>(
        &self,
        req: &Request<T>,
        session_id: &str,
        allowed: &[Who],
        what: &str,
    ) -> Result<(Arc<Session>, Arc<LiveExercise>, Who), Status> {
        let (s, ex) = self.exercise(session_id)?;
        let who = ex.require(&s, token_of(req).as_deref(), allowed, what)?;
        Ok((s, ex, who))
    }
}

fn status_now(ex: &LiveExercise) -> pb::ExerciseStatus {
    tc::status(ex, &ex.snapshot())
}

/// The status now, built once per change of the exercise for all its watchers (a status with
/// many markers is large; issue 35).
fn shared_status(ex: &LiveExercise) -> Arc<pb::ExerciseStatus> {
    let changes = ex.changes();
    let mut cache = ex.status_cache.lock().expect("status cache lock");
    if let Some((c, st)) = cache.as_ref()
        && *c == changes
    {
        return st.clone();
    }
    let st = Arc::new(status_now(ex));
    *cache = Some((changes, st.clone()));
    st
}

#[tonic::async_trait]
impl pb::training_service_server::TrainingService for Api {
    async fn create_exercise_session(
        &self,
        req: Request<pb::CreateExerciseSessionRequest>,
    ) -> Result<Response<pb::CreateExerciseSessionResponse>, Status> {
        let r = req.into_inner();
        let state = self.state.clone();
        let (name, rate, device) = (r.exercise.clone(), r.tick_rate_hz, r.device_channel);
        // A full recordings directory starts nothing (issue 35).
        if r.record {
            self.state.check_recording_room()?;
        }
        let record = r.record;
        let made = tokio::task::spawn_blocking(move || {
            let made = create_exercise_session(&state, &name, rate, device)?;
            if record {
                state.start_recording_or_discard(&made.session)?;
            }
            Ok::<_, Status>(made)
        })
        .await
        .map_err(|e| Status::internal(format!("session task: {e}")))??;
        let ex = &made.exercise;
        Ok(Response::new(pb::CreateExerciseSessionResponse {
            session: Some(crate::convert::create_session_response(&made.session)),
            instructor_token: ex.instructor_token().to_owned(),
            exercise: Some(tc::exercise_info(&ex.exercise, Some(&ex.targets))),
        }))
    }

    async fn list_exercises(&self, _req: Request<pb::ListExercisesRequest>) -> Result<Response<pb::ListExercisesResponse>, Status> {
        let mut out = Vec::new();
        for (name, _, _) in EXERCISES {
            let ex = load_exercise(name).map_err(|e| Status::internal(format!("shipped exercise {name}: {e}")))?;
            out.push(tc::exercise_info(&ex, None));
        }
        Ok(Response::new(pb::ListExercisesResponse { exercises: out }))
    }

    async fn place(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<pb::PlaceResponse>, Status> {
        let (_, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, DRIVERS, "Place")?;
        let (i, p) = ex.place()?;
        Ok(Response::new(pb::PlaceResponse { placement: Some(tc::placement(&ex, i, &p)), status: Some(status_now(&ex)) }))
    }

    type WatchScoreStream = BoxStream<pb::ExerciseStatus>;

    async fn watch_score(&self, req: Request<pb::WatchScoreRequest>) -> Result<Response<Self::WatchScoreStream>, Status> {
        let r = req.get_ref();
        let rate = if r.rate_hz == 0.0 { 10.0 } else { r.rate_hz };
        if !(rate.is_finite() && (1.0..=60.0).contains(&rate)) {
            return Err(Status::invalid_argument(format!("rate_hz = {}: 1..60 updates per second", needlesim_core::num::num(rate))));
        }
        let (s, ex, _) = self.exercise_for(&req, &r.session_id, ALL, "WatchScore")?;
        let permit = self.state.admit_stream(Some(&s), "WatchScore")?;
        let mut every = tokio::time::interval(Duration::from_secs_f64(1.0 / rate));
        every.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        // Pulled (issue 35): a status is made when the client's connection takes one, so a reader
        // that stops holds none queued; the status is built once per change for every watcher.
        struct Watch {
            ex: Arc<LiveExercise>,
            every: tokio::time::Interval,
            seen: Option<u64>,
            done: bool,
            _permit: StreamPermit,
        }
        let st = Watch { ex, every, seen: None, done: false, _permit: permit };
        let statuses = futures_util::stream::unfold(st, |mut st| async move {
            if st.done {
                return None;
            }
            loop {
                st.every.tick().await;
                let changes = st.ex.changes();
                if st.seen == Some(changes) {
                    continue;
                }
                st.seen = Some(changes);
                let status = shared_status(&st.ex);
                st.done = status.finished;
                return Some((Ok(status.as_ref().clone()), st));
            }
        });
        Ok(Response::new(crate::grpc::of_session(&s, Box::pin(statuses))))
    }

    async fn get_status(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<pb::ExerciseStatus>, Status> {
        let (_, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, ALL, "GetStatus")?;
        Ok(Response::new(status_now(&ex)))
    }

    async fn take_control(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<pb::ExerciseStatus>, Status> {
        let (s, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, INSTRUCTOR, "TakeControl")?;
        ex.take_control(&s)?;
        tracing::info!(session = %s.id, "the instructor took control");
        Ok(Response::new(status_now(&ex)))
    }

    async fn hand_back_control(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<pb::ExerciseStatus>, Status> {
        let (s, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, INSTRUCTOR, "HandBackControl")?;
        ex.hand_back(&s)?;
        tracing::info!(session = %s.id, "the instructor handed control back");
        Ok(Response::new(status_now(&ex)))
    }

    async fn set_paused(&self, req: Request<pb::SetPausedRequest>) -> Result<Response<pb::ExerciseStatus>, Status> {
        let (s, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, INSTRUCTOR, "SetPaused")?;
        ex.set_paused(&s, req.get_ref().paused)?;
        Ok(Response::new(status_now(&ex)))
    }

    async fn reset_exercise(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<pb::ExerciseStatus>, Status> {
        let (_, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, INSTRUCTOR, "ResetExercise")?;
        ex.reset()?;
        Ok(Response::new(status_now(&ex)))
    }

    async fn add_marker(&self, req: Request<pb::AddMarkerRequest>) -> Result<Response<pb::ExerciseMarker>, Status> {
        let (_, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, INSTRUCTOR, "AddMarker")?;
        let m = ex.add_marker(&req.get_ref().label)?;
        Ok(Response::new(tc::marker(&m)))
    }

    async fn end_exercise(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<pb::ExerciseStatus>, Status> {
        let (s, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, DRIVERS, "EndExercise")?;
        let (dir, reports) = (self.state.data_dir.clone(), self.state.reports_quota.clone());
        let (ex2, s2) = (ex.clone(), s.clone());
        tokio::task::spawn_blocking(move || ex2.end(&s2, &dir, &reports))
            .await
            .map_err(|e| Status::internal(format!("report task: {e}")))??;
        Ok(Response::new(status_now(&ex)))
    }

    type GetReportStream = BoxStream<pb::ExerciseReportChunk>;

    async fn get_report(&self, req: Request<pb::ExerciseRequest>) -> Result<Response<Self::GetReportStream>, Status> {
        let (s, ex, _) = self.exercise_for(&req, &req.get_ref().session_id, ALL, "GetReport")?;
        let Some(f) = ex.snapshot().finished else {
            return Err(Status::failed_precondition(format!("session {}: the exercise has not ended (EndExercise)", s.id)));
        };
        let permit = self.state.admit_stream(Some(&s), "GetReport")?;
        let html = tokio::fs::read(&f.report_path).await.map_err(|e| Status::internal(format!("cannot read the report: {e}")))?;
        // One copy of the report, cut into chunks as the client takes them.
        let html = bytes::Bytes::from(html);
        let chunks = futures_util::stream::unfold((html, permit), |(mut rest, permit)| async move {
            if rest.is_empty() {
                return None;
            }
            let chunk = rest.split_to(rest.len().min(REPORT_CHUNK_BYTES));
            Some((Ok(pb::ExerciseReportChunk { html: chunk.to_vec() }), (rest, permit)))
        });
        Ok(Response::new(crate::grpc::of_session(&s, Box::pin(chunks))))
    }

    type WatchUltrasoundStream = BoxStream<pb::UltrasoundImage>;

    async fn watch_ultrasound(&self, req: Request<pb::WatchUltrasoundRequest>) -> Result<Response<Self::WatchUltrasoundStream>, Status> {
        let r = req.get_ref();
        let rate = if r.rate_hz == 0.0 { crate::training_ultrasound::DEFAULT_RATE_HZ } else { r.rate_hz };
        if !(rate.is_finite() && (1.0..=crate::training_ultrasound::MAX_RATE_HZ).contains(&rate)) {
            return Err(Status::invalid_argument(format!(
                "rate_hz = {}: 1..{} images per second",
                needlesim_core::num::num(rate),
                crate::training_ultrasound::MAX_RATE_HZ
            )));
        }
        let (s, ex, _) = self.exercise_for(&req, &r.session_id, ALL, "WatchUltrasound")?;
        let permit = self.state.admit_stream(Some(&s), "WatchUltrasound")?;
        let ex_closed = ex.clone();
        let closed = Arc::new(move || ex_closed.closed.load(std::sync::atomic::Ordering::Acquire));
        let (images, watching) = ex
            .ultrasound
            .watch(s.clone(), closed, rate)
            .map_err(|e| Status::internal(format!("cannot start the ultrasound renderer: {e}")))?;
        // Pulled (issue 35): the latest image when the client's connection takes one.
        struct Watch {
            ex: Arc<LiveExercise>,
            images: tokio::sync::watch::Receiver<Option<Arc<crate::training_ultrasound::SliceImage>>>,
            _watching: crate::training_ultrasound::Watching,
            _permit: StreamPermit,
        }
        let st = Watch { ex, images, _watching: watching, _permit: permit };
        let images = futures_util::stream::unfold(st, |mut st| async move {
            loop {
                if st.ex.closed.load(std::sync::atomic::Ordering::Acquire) {
                    return None;
                }
                // Woken by a new image, or every 0.5 s to see the session closed.
                let changed = tokio::select! {
                    c = st.images.changed() => c,
                    () = tokio::time::sleep(Duration::from_millis(500)) => continue,
                };
                if changed.is_err() {
                    return None;
                }
                let img = st.images.borrow_and_update().clone();
                if let Some(img) = img {
                    return Some((Ok(tc::ultrasound_image(&img)), st));
                }
            }
        });
        Ok(Response::new(crate::grpc::of_session(&s, Box::pin(images))))
    }

    async fn set_probe(&self, req: Request<pb::SetProbeRequest>) -> Result<Response<pb::UltrasoundProbe>, Status> {
        let r = req.get_ref();
        let (s, ex, _) = self.exercise_for(&req, &r.session_id, DRIVERS, "SetProbe")?;
        let p = tc::probe_from_pb(r.probe.as_ref(), s.dimension())?;
        ex.ultrasound.set_probe(p);
        Ok(Response::new(tc::probe(&p)))
    }
}
