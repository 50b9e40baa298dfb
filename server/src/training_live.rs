//! The live training layer (issue 20): a session created from an exercise, its metrics computed
//! from the session's tick records on the fan-out thread (the session's *tap*, a
//! [`RecordSink`] that builds one [`Sample`] per record and pushes it to needlesim-training's
//! [`MetricsTracker`] — never on the real-time thread), the roles (trainee = the session's
//! controller token, instructor = a token made here and returned only to the creator), pause,
//! reset, timeline markers, and the end of the exercise (final result, after-action report
//! written to `<data dir>/reports/`). The gRPC surface is `training_service.rs`, the messages are
//! built in `training_convert.rs`, the ultrasound slice is `training_ultrasound.rs`.
//!
//! **Exercise clock.** With $t_k$ the session time of record $k$ and $P_k$ the session time that
//! passed while paused up to it, a record scored at $k$ is stamped
//! $\tau_k = t_k - P_k - \tau_0$ ($\tau_0$: the first scored record's $t - P$ since the start or
//! the last reset). Paused records are not scored; $P$ grows by $t_k - t_{k-1}$ for each of them.
//!
//! **Control.** The instructor's control is the session's control lease
//! (`needlesim_session::control_lease`), held *exclusively* ([`ControlLease::take_exclusive`](needlesim_session::control_lease::ControlLease::take_exclusive))
//! while the instructor has control or the exercise is paused: taking it revokes the trainee's
//! Control stream (ABORTED), and no `take_over` can take it back. [`LiveExercise::refuse_trainee`]
//! refuses the trainee's poses with FAILED_PRECONDITION before they reach the lease (with the
//! reason: control or pause). That check alone would race with TakeControl (checked, then the
//! instructor takes control, then the trainee's stream or SetPose takes the lease over); the
//! exclusive lease closes it: the trainee's acquisition and the instructor's take are decided
//! under the lease's one lock, and every pose is written under it, so a trainee checked before the
//! take either got the lease before it (and is revoked by it: no pose of theirs lands after) or
//! is refused after it ([`Busy::Exclusive`](needlesim_session::control_lease::Busy::Exclusive), FAILED_PRECONDITION, `grpc/control.rs`). The
//! instructor's poses are written under that lease ([`LiveExercise::write_as_instructor`]). The
//! state (control, paused) and the lease change together under the exercise's state lock (lock
//! order: exercise state, then lease).
//!
//! **Tissue strain (2D).** While a 2D exercise runs it subscribes to the session's displacement
//! field (the fan-out computes it every 8 ms while anyone subscribes, $O(n\,d)$ from the contacts'
//! compliance columns, never on the real-time thread), and the tap takes a strain sample
//! ([`needlesim_training::strain`], metrics.rs) every `STRAIN_INTERVAL_S` (10 ms) of exercise
//! time from the latest field: a copy and one pass over the triangles, no allocation. The field
//! lags the record by up to a field period. The subscription ends with the exercise. 3D: none.
//!
//! **A trainee on a device.** A session created with a device channel is driven by the device
//! bridge on the real-time thread, not through the lease. While the instructor has control or the
//! exercise is paused the session's device is suspended ([`Session::suspend_device_from_io`], set
//! under the same state lock, so the flag is always "control or paused"): its poses are read and
//! counted (`device_poses_suspended`) but not applied, its button flips nothing, and the device
//! is sent zero force and stiffness. When neither holds (HandBack without a pause, Resume without
//! control) the device drives again: the needle, wherever the instructor left it, moves towards
//! the device at no more than 50 mm/s and 0.5 rad/s (`needlesim_session::DEVICE_CATCH_UP_M_PER_S`),
//! the device feeling nothing until it is there, then the force returns over 0.2 s
//! (`needlesim_session::rt_loop`'s docs). Reset and the end of the exercise leave control and
//! pause as they are.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, RwLock};

use needlesim_session::control_lease::StreamLease;
use needlesim_session::{RecordSink, Session, TickRecord};
use needlesim_training::metrics::{Placement, Trace};
use needlesim_training::run::{RefusedPlacements, STRAIN_INTERVAL_S, TRACE_CAPACITY, TargetGeometry};
use needlesim_training::strain::StrainField;
use needlesim_training::{Exercise, ExerciseRun, MetricsTracker, Sample, TimelineMarker, TrackerSpec};
use tonic::Status;

use crate::training_ultrasound::UltrasoundHub;

/// The live exercises by session id.
pub type Registry = RwLock<HashMap<String, Arc<LiveExercise>>>;

/// Longest marker label, characters.
pub const MAX_MARKER_LABEL_CHARS: usize = 200;
/// Most markers per exercise (a marker past it is refused).
pub const MAX_MARKERS: usize = 1000;

/// Who presents a token to a live exercise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Who {
    /// The session's controller token.
    Trainee,
    /// The exercise's instructor token.
    Instructor,
    /// The session's observer token.
    Observer,
}

/// A finished exercise: where its report is.
#[derive(Debug, Clone)]
pub struct Finished {
    /// The report's file name in `<data dir>/reports/`.
    pub report_name: String,
    pub report_path: PathBuf,
}

/// What changes while the exercise runs (under one lock, taken by the fan-out per record and by
/// the IO side's calls).
struct ExState {
    tracker: MetricsTracker,
    trace: Trace,
    placements: Vec<(usize, Placement)>,
    /// The first [`needlesim_training::run::MAX_REFUSED_KEPT`] refused declarations, all counted.
    refused: RefusedPlacements,
    markers: Vec<TimelineMarker>,
    instructor_control: bool,
    paused: bool,
    /// The control lease, held while the instructor has control or the exercise is paused.
    hold: Option<StreamLease>,
    /// $P$: session time spent paused, s.
    paused_s: f64,
    /// $\tau_0$ (set by the first scored record).
    start_s: Option<f64>,
    prev_time_s: Option<f64>,
    last_tick: u64,
    /// Exercise time of the last scored record, s.
    last_t_s: f64,
    /// Records scored since the start or the last reset.
    ticks: u64,
    /// Set when the exercise ends: the tap scores nothing more.
    ending: bool,
    finished: Option<Finished>,
    resets: u32,
}

/// A session's exercise.
pub struct LiveExercise {
    pub session_id: String,
    pub exercise: Exercise,
    /// The targets in the tracker's order (reference centre, radius, tolerance).
    pub targets: Vec<TargetGeometry>,
    pub scene_name: String,
    pub tick_rate_hz: f64,
    instructor_token: String,
    spec: TrackerSpec,
    state: Mutex<ExState>,
    /// Serialises [`LiveExercise::end`].
    end_lock: Mutex<()>,
    /// Incremented at every change (a scored record, a placement, a marker, control, pause…):
    /// what the score watchers compare.
    changes: AtomicU64,
    /// Set when the session closes: streams end, the renderer stops.
    pub closed: AtomicBool,
    pub ultrasound: Arc<UltrasoundHub>,
    /// The last status built for the score watchers, with the change count it was built at
    /// (`training_service.rs`: built once per change for all watchers; issue 35).
    pub status_cache: Mutex<Option<(u64, Arc<needlesim_proto::v1::ExerciseStatus>)>>,
    /// The tissue strain sampler of a 2D session (module docs), while the exercise runs.
    strain: Mutex<Option<LiveStrain>>,
}

/// Tissue strain of a live 2D exercise (module docs): the session's displacement field (the
/// fan-out computes it while this subscribes), read on the tap every
/// [`STRAIN_INTERVAL_S`] of exercise time.
struct LiveStrain {
    field: tokio::sync::watch::Receiver<Arc<needlesim_session::Field>>,
    subscribers: Arc<AtomicU64>,
    strain: StrainField,
    damage_strain: f64,
    /// Exercise time of the next strain sample, s.
    next_s: f64,
}

impl LiveStrain {
    /// A strain sample at exercise time `t_s` when one is due and the field has arrived; O(n)
    /// (a copy of the field and one pass over the triangles), no allocation.
    fn sample(&mut self, tracker: &mut MetricsTracker, t_s: f64) {
        if t_s < self.next_s - 2.0 * STRAIN_INTERVAL_S {
            // The exercise was reset: its clock restarted.
            self.next_s = t_s;
        }
        if t_s + 1e-9 < self.next_s {
            return;
        }
        {
            let f = self.field.borrow();
            let u = self.strain.displacements_mut();
            if f.displacement_m.len() != u.len() {
                return;
            }
            u.copy_from_slice(&f.displacement_m);
        }
        tracker.push_strain(t_s, &self.strain.evaluate(self.damage_strain));
        self.next_s = t_s + STRAIN_INTERVAL_S;
    }
}

fn instructor_token() -> String {
    use ring::rand::SecureRandom;
    let mut b = [0u8; 16];
    ring::rand::SystemRandom::new().fill(&mut b).expect("the OS random source works");
    crate::access::to_hex(&b)
}

impl LiveExercise {
    /// The exercise of session `session_id`: a fresh tracker of `spec`, a new instructor token.
    pub fn new(
        session_id: &str,
        exercise: Exercise,
        spec: TrackerSpec,
        targets: Vec<TargetGeometry>,
        scene_name: String,
        tick_rate_hz: f64,
        ultrasound: Arc<UltrasoundHub>,
    ) -> Arc<Self> {
        Arc::new(Self {
            session_id: session_id.to_owned(),
            exercise,
            targets,
            scene_name,
            tick_rate_hz,
            instructor_token: instructor_token(),
            state: Mutex::new(ExState {
                tracker: MetricsTracker::new(spec.clone()),
                trace: Trace::new(TRACE_CAPACITY),
                placements: Vec::new(),
                refused: RefusedPlacements::default(),
                markers: Vec::new(),
                instructor_control: false,
                paused: false,
                hold: None,
                paused_s: 0.0,
                start_s: None,
                prev_time_s: None,
                last_tick: 0,
                last_t_s: 0.0,
                ticks: 0,
                ending: false,
                finished: None,
                resets: 0,
            }),
            spec,
            end_lock: Mutex::new(()),
            changes: AtomicU64::new(0),
            closed: AtomicBool::new(false),
            ultrasound,
            status_cache: Mutex::new(None),
            strain: Mutex::new(None),
        })
    }

    /// The instructor's token (for the creator's response only; never logged).
    pub fn instructor_token(&self) -> &str {
        &self.instructor_token
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, ExState> {
        self.state.lock().expect("exercise state lock")
    }

    fn changed(&self) {
        self.changes.fetch_add(1, Ordering::Release);
    }

    /// The change counter ([`LiveExercise::changes`]).
    pub fn changes(&self) -> u64 {
        self.changes.load(Ordering::Acquire)
    }

    /// Who presents `token` (compared in constant time, all three compared).
    pub fn who(&self, s: &Session, token: Option<&str>) -> Option<Who> {
        let tok = token?;
        let trainee = crate::access::token_matches(tok, &s.controller_token);
        let instructor = crate::access::token_matches(tok, &self.instructor_token);
        let observer = crate::access::token_matches(tok, &s.observer_token);
        if instructor {
            Some(Who::Instructor)
        } else if trainee {
            Some(Who::Trainee)
        } else if observer {
            Some(Who::Observer)
        } else {
            None
        }
    }

    /// The caller's role if it is among `allowed`; PERMISSION_DENIED naming what is needed.
    pub fn require(&self, s: &Session, token: Option<&str>, allowed: &[Who], what: &str) -> Result<Who, Status> {
        match self.who(s, token) {
            Some(w) if allowed.contains(&w) => Ok(w),
            _ => {
                let names: Vec<&str> = allowed
                    .iter()
                    .map(|w| match w {
                        Who::Trainee => "controller (trainee)",
                        Who::Instructor => "instructor",
                        Who::Observer => "observer",
                    })
                    .collect();
                Err(Status::permission_denied(format!("{what} needs the session's {} token", names.join(" or "))))
            }
        }
    }

    /// Takes one tick record (the tap, on the fan-out thread; module docs for the clock).
    fn score_record(&self, rec: &TickRecord) {
        let mut st = self.lock();
        if st.ending {
            return;
        }
        let dt = st.prev_time_s.map_or(0.0, |p| (rec.time_s - p).max(0.0));
        st.prev_time_s = Some(rec.time_s);
        if st.paused {
            st.paused_s += dt;
            return;
        }
        let shifted = rec.time_s - st.paused_s;
        let start = *st.start_s.get_or_insert(shifted);
        let t_s = shifted - start;
        let s = sample_of(rec, t_s);
        st.tracker.push(&s);
        let depth = st.tracker.depth_m();
        st.trace.push(&s, depth);
        st.last_tick = rec.tick;
        st.last_t_s = t_s;
        st.ticks += 1;
        if let Some(ls) = self.strain.lock().expect("exercise strain lock").as_mut() {
            ls.sample(&mut st.tracker, t_s);
        }
        drop(st);
        self.changed();
    }

    /// Starts sampling the tissue strain of 2D session `s` (subscribes to its displacement field).
    fn start_strain(&self, s: &Session) {
        let Some(tissue) = s.tissue.two() else { return };
        let mesh = tissue.mesh();
        s.field_subscribers.fetch_add(1, Ordering::AcqRel);
        *self.strain.lock().expect("exercise strain lock") = Some(LiveStrain {
            field: s.field.clone(),
            subscribers: s.field_subscribers.clone(),
            strain: StrainField::new(mesh.nodes_m(), mesh.triangles()),
            damage_strain: self.exercise.damage_strain,
            next_s: 0.0,
        });
    }

    /// Stops sampling the strain (unsubscribes from the field); idempotent.
    fn stop_strain(&self) {
        if let Some(ls) = self.strain.lock().expect("exercise strain lock").take() {
            ls.subscribers.fetch_sub(1, Ordering::AcqRel);
        }
    }

    /// Refuses the trainee's poses while the instructor has control or the exercise is paused.
    pub fn refuse_trainee(&self) -> Result<(), Status> {
        let st = self.lock();
        if st.instructor_control {
            return Err(Status::failed_precondition(format!(
                "session {}: the instructor has control; the trainee's poses are refused until the instructor hands control back",
                self.session_id
            )));
        }
        if st.paused {
            return Err(Status::failed_precondition(format!(
                "session {}: the exercise is paused by the instructor; poses are refused until it resumes",
                self.session_id
            )));
        }
        Ok(())
    }

    /// Runs `write` (the instructor's pose) under the lease the instructor holds;
    /// FAILED_PRECONDITION when the instructor does not have control.
    pub fn write_as_instructor(&self, write: impl FnOnce()) -> Result<(), Status> {
        let st = self.lock();
        if !st.instructor_control {
            return Err(Status::failed_precondition(format!(
                "session {}: the instructor drives only while holding control: call TakeControl first",
                self.session_id
            )));
        }
        match &st.hold {
            Some(lease) if lease.write_if_held(write) => Ok(()),
            _ => Err(Status::failed_precondition(format!(
                "session {}: the control lease was taken by another client; call TakeControl again",
                self.session_id
            ))),
        }
    }

    /// Holds the session's control lease exclusively (revoking the trainee's stream) unless this
    /// exercise holds it already, and suspends the session's device; under the state lock.
    fn hold(st: &mut ExState, s: &Session) {
        if !st.hold.as_ref().is_some_and(StreamLease::is_held) {
            // A previous hold is no longer the holder: dropping it releases nothing.
            st.hold = Some(s.control.take_exclusive());
        }
        s.suspend_device_from_io(true);
    }

    /// Lets the lease go and the device drive again once neither control nor a pause holds;
    /// under the state lock.
    fn release_if_free(st: &mut ExState, s: &Session) {
        if !st.instructor_control && !st.paused {
            st.hold = None;
            s.suspend_device_from_io(false);
        }
    }

    /// The instructor takes control (idempotent): the exclusive lease, the device suspended;
    /// FAILED_PRECONDITION once the exercise has ended.
    pub fn take_control(&self, s: &Session) -> Result<(), Status> {
        let mut st = self.lock();
        if st.ending {
            return Err(self.ended());
        }
        st.instructor_control = true;
        Self::hold(&mut st, s);
        drop(st);
        self.changed();
        Ok(())
    }

    /// The instructor hands control back (idempotent); the lease is let go and the device drives
    /// again unless paused. FAILED_PRECONDITION once the exercise has ended (its end handed
    /// control back already: [`LiveExercise::end`]).
    pub fn hand_back(&self, s: &Session) -> Result<(), Status> {
        let mut st = self.lock();
        if st.ending {
            return Err(self.ended());
        }
        st.instructor_control = false;
        Self::release_if_free(&mut st, s);
        drop(st);
        self.changed();
        Ok(())
    }

    /// Pauses or resumes (module docs); the lease is held and the device suspended while paused.
    /// FAILED_PRECONDITION once the exercise has ended.
    pub fn set_paused(&self, s: &Session, paused: bool) -> Result<(), Status> {
        let mut st = self.lock();
        if st.ending {
            return Err(self.ended());
        }
        st.paused = paused;
        if paused {
            Self::hold(&mut st, s);
        } else {
            Self::release_if_free(&mut st, s);
        }
        drop(st);
        self.changed();
        Ok(())
    }

    /// Restarts the metrics, placements and markers (the clock from zero at the next record).
    pub fn reset(&self) -> Result<(), Status> {
        let mut st = self.lock();
        if st.ending {
            return Err(self.ended());
        }
        st.tracker = MetricsTracker::new(self.spec.clone());
        st.trace = Trace::new(TRACE_CAPACITY);
        st.placements.clear();
        st.refused.clear();
        st.markers.clear();
        st.paused_s = 0.0;
        st.start_s = None;
        st.last_t_s = 0.0;
        st.ticks = 0;
        st.resets += 1;
        drop(st);
        self.changed();
        Ok(())
    }

    fn ended(&self) -> Status {
        Status::failed_precondition(format!("session {}: the exercise has ended", self.session_id))
    }

    /// "Placed": the nearest target not yet placed, at the last scored record.
    pub fn place(&self) -> Result<(usize, Placement), Status> {
        let mut st = self.lock();
        if st.ending {
            return Err(self.ended());
        }
        if st.paused {
            return Err(Status::failed_precondition(format!("session {}: the exercise is paused", self.session_id)));
        }
        let t = st.last_t_s;
        let r = st.tracker.place();
        match r {
            Ok(p) => {
                st.placements.push(p);
                drop(st);
                self.changed();
                Ok(p)
            }
            Err(e) => {
                let msg = e.to_string();
                st.refused.push(t, || msg.clone());
                drop(st);
                self.changed();
                Err(Status::failed_precondition(format!("session {}: {msg}", self.session_id)))
            }
        }
    }

    /// A marker at the exercise's current time.
    pub fn add_marker(&self, label: &str) -> Result<TimelineMarker, Status> {
        let n = label.chars().count();
        if n > MAX_MARKER_LABEL_CHARS {
            return Err(Status::invalid_argument(format!("label: {n} characters, at most {MAX_MARKER_LABEL_CHARS}")));
        }
        if label.chars().any(char::is_control) {
            return Err(Status::invalid_argument("label: control characters are not allowed"));
        }
        let mut st = self.lock();
        if st.ending {
            return Err(self.ended());
        }
        if st.markers.len() >= MAX_MARKERS {
            return Err(Status::resource_exhausted(format!("session {}: at most {MAX_MARKERS} markers", self.session_id)));
        }
        let m = TimelineMarker { t_s: st.last_t_s, tick: st.last_tick, label: label.to_owned() };
        st.markers.push(m.clone());
        drop(st);
        self.changed();
        Ok(m)
    }

    /// A consistent view of the exercise now.
    pub fn snapshot(&self) -> Snapshot {
        let st = self.lock();
        Snapshot {
            score: st.tracker.score(),
            metrics: st.tracker.metrics(),
            depth_m: st.tracker.depth_m(),
            time_s: st.last_t_s,
            tick: st.last_tick,
            markers: st.markers.clone(),
            instructor_control: st.instructor_control,
            paused: st.paused,
            finished: st.finished.clone(),
            resets: st.resets,
        }
    }

    /// Ends the exercise (idempotent): scores nothing more, lets the instructor's control and a
    /// pause go (they could not be handed back or resumed once the calls refuse an ended
    /// exercise, so the lease is freed and `s`'s device drives again, even if the report then
    /// fails), renders the report and writes it to `<data_dir>/reports/<session>-<exercise>.html`
    /// within `reports` (`--max-reports`, `--max-reports-mb`: past them no report is written and
    /// the call is RESOURCE_EXHAUSTED naming the flag). Blocking (the report's plots): call it off
    /// the async runtime.
    pub fn end(&self, s: &Session, data_dir: &Path, reports: &Arc<crate::quota::DirQuota>) -> Result<Finished, Status> {
        let _serial = self.end_lock.lock().expect("exercise end lock");
        let run = {
            let mut st = self.lock();
            if let Some(f) = &st.finished {
                return Ok(f.clone());
            }
            st.ending = true;
            if st.instructor_control || st.paused {
                st.instructor_control = false;
                st.paused = false;
                Self::release_if_free(&mut st, s);
            }
            self.stop_strain();
            ExerciseRun {
                exercise: self.exercise.name.clone(),
                description: self.exercise.description.clone(),
                scene: self.scene_name.clone(),
                dim: self.exercise.dim,
                ticks: st.ticks,
                tick_rate_hz: self.tick_rate_hz,
                result: st.tracker.clone().finish(),
                targets: self.targets.clone(),
                structures: self.exercise.spare.clone(),
                trace: st.trace.points(),
                placements: st.placements.clone(),
                refused_placements: st.refused.clone(),
                markers: st.markers.clone(),
                expert: None,
                expert_note: None,
                ticks_csv: None,
            }
        };
        // The expert run the exercise names: overlaid, or a note in the report saying why not.
        let mut run = run;
        match needlesim_training::run::expert_for(&self.exercise, &self.spec) {
            Ok(e) => run.expert = e,
            Err(e) => run.expert_note = Some(format!("the expert run could not be read: {e}")),
        }
        let html = needlesim_training::report::report_html(&run)
            .map_err(|e| Status::internal(format!("the report of session {} cannot be drawn: {e}", self.session_id)))?;
        let dir = data_dir.join("reports");
        std::fs::create_dir_all(&dir).map_err(|e| Status::internal(format!("cannot create {}: {e}", dir.display())))?;
        let report_name = format!("{}-{}.html", self.session_id, self.exercise.name);
        let report_path = dir.join(&report_name);
        let mut room = reports.admit(&dir, html.len() as u64).map_err(|e| {
            tracing::warn!(session = %self.session_id, "no after-action report: {e}");
            Status::from(crate::status::ApiError::from(&e))
        })?;
        std::fs::write(&report_path, &html).map_err(|e| Status::internal(format!("cannot write {}: {e}", report_path.display())))?;
        room.spend(html.len() as u64, html.len() as u64);
        tracing::info!(session = %self.session_id, exercise = %self.exercise.name, score = run.result.score.total, report = %report_path.display(), "exercise ended");
        let f = Finished { report_name, report_path };
        self.lock().finished = Some(f.clone());
        self.changed();
        Ok(f)
    }
}

/// The exercise at one moment ([`LiveExercise::snapshot`]).
#[derive(Debug, Clone)]
pub struct Snapshot {
    pub score: needlesim_training::Score,
    pub metrics: needlesim_training::Metrics,
    pub depth_m: f64,
    pub time_s: f64,
    pub tick: u64,
    pub markers: Vec<TimelineMarker>,
    pub instructor_control: bool,
    pub paused: bool,
    pub finished: Option<Finished>,
    pub resets: u32,
}

/// The session's tap: every tick record to the exercise's tracker, on the fan-out thread.
struct TrainingTap {
    ex: Arc<LiveExercise>,
}

impl RecordSink for TrainingTap {
    fn write_from_fanout(&mut self, rec: &TickRecord) {
        self.ex.score_record(rec);
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn into_any(self: Box<Self>) -> Box<dyn std::any::Any + Send> {
        self
    }
}

/// Attaches `ex`'s tap to its session and registers it; FAILED_PRECONDITION if the session has a
/// tap already.
pub fn attach(registry: &Registry, s: &Session, ex: Arc<LiveExercise>) -> Result<(), Status> {
    s.attach_tap_from_io(Box::new(TrainingTap { ex: ex.clone() }))
        .map_err(|_| Status::failed_precondition(format!("session {} has a training tap already", s.id)))?;
    ex.start_strain(s);
    registry.write().expect("training registry lock").insert(s.id.clone(), ex);
    Ok(())
}

/// The exercise of a session, if it has one.
pub fn exercise_of(registry: &Registry, session_id: &str) -> Option<Arc<LiveExercise>> {
    registry.read().expect("training registry lock").get(session_id).cloned()
}

/// Before a pose, a flip or a new Control stream of the session's controller token: refused
/// while an exercise's instructor has control or the exercise is paused.
pub fn refuse_trainee(registry: &Registry, s: &Session) -> Result<(), Status> {
    match exercise_of(registry, &s.id) {
        Some(ex) => ex.refuse_trainee(),
        None => Ok(()),
    }
}

/// SetPose / SetPose3's authorisation: `Ok(None)` for the trainee (the controller token) when the
/// trainee may drive, `Ok(Some(exercise))` for the instructor of an exercise (who writes under its
/// lease: [`LiveExercise::write_as_instructor`]); the session's usual PERMISSION_DENIED otherwise.
pub fn authorize_pose<T>(registry: &Registry, req: &tonic::Request<T>, s: &Session) -> Result<Option<Arc<LiveExercise>>, Status> {
    let Some(ex) = exercise_of(registry, &s.id) else {
        crate::grpc::authorize(req, s, crate::grpc::Role::Controller)?;
        return Ok(None);
    };
    let token = crate::grpc::token_of(req);
    match ex.who(s, token.as_deref()) {
        Some(Who::Instructor) => Ok(Some(ex)),
        Some(Who::Trainee) => {
            ex.refuse_trainee()?;
            Ok(None)
        }
        _ => {
            crate::grpc::authorize(req, s, crate::grpc::Role::Controller)?;
            Ok(None)
        }
    }
}

/// A create that failed: the session's exercise leaves the registry without a report.
pub fn discard(registry: &Registry, session_id: &str) {
    let ex = registry.write().expect("training registry lock").remove(session_id);
    if let Some(ex) = ex {
        ex.closed.store(true, Ordering::Release);
        ex.changed();
    }
}

/// The session closes: its exercise ends (report written) and leaves the registry. Blocking.
pub fn on_close(registry: &Registry, data_dir: &Path, reports: &Arc<crate::quota::DirQuota>, s: &Session) {
    let ex = registry.write().expect("training registry lock").remove(&s.id);
    if let Some(ex) = ex {
        ex.closed.store(true, Ordering::Release);
        if let Err(e) = ex.end(s, data_dir, reports) {
            tracing::error!(session = %s.id, "the exercise's report: {}", e.message());
        }
        ex.changed();
    }
}

/// The training sample of one tick record (needlesim-training's conventions, `sample.rs`): the
/// axis is the last segment of the recorded shape (the rigid needle's is its base angle), the
/// axial force positive while pushing in; 3D from the record's 3D part (axis $R e_x$).
pub fn sample_of(rec: &TickRecord, t_s: f64) -> Sample {
    if rec.dimension == 3 {
        let d = &rec.d3;
        let [w, x, y, z] = d.orientation_wxyz;
        let axis = [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)];
        let mut s = Sample::new(t_s, d.tip_m, axis, rec.inserted_length_m, d.n_contacts as u32, d.axial_force_n);
        s.base_force_n = d.force_n;
        for t in d.targets() {
            s.push_target(t.centre_m);
        }
        return s;
    }
    let axis = {
        let n = rec.n_shape as usize;
        let theta = rec.base.theta_rad;
        let (dx, dy) = if n >= 2 {
            let (a, b) = (rec.shape_m[n - 2], rec.shape_m[n - 1]);
            (b[0] - a[0], b[1] - a[1])
        } else {
            (theta.cos(), theta.sin())
        };
        let len = dx.hypot(dy);
        if len > 0.0 { [dx / len, dy / len, 0.0] } else { [theta.cos(), theta.sin(), 0.0] }
    };
    let mut s = Sample::new(
        t_s,
        [rec.tip_m[0], rec.tip_m[1], 0.0],
        axis,
        rec.inserted_length_m,
        rec.n_stuck + rec.n_slipping + rec.n_tip,
        -rec.force_axial_n,
    );
    s.base_force_n = [rec.force_n[0], rec.force_n[1], 0.0];
    for t in &rec.targets[..rec.n_targets as usize] {
        s.push_target([t.position_m[0], t.position_m[1], 0.0]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::training_ultrasound::{ProbeSpec, default_probe_2d};

    fn exercise() -> Arc<LiveExercise> {
        let ex = needlesim_training::load_exercise("biopsy-2d").unwrap();
        let spec = TrackerSpec {
            dims: 2,
            targets: vec![],
            structures: vec![],
            limits: ex.limits,
            weights: ex.weights,
            redirect_threshold_m: ex.redirect_threshold_m,
        };
        let hub = UltrasoundHub::new(ProbeSpec::Two(default_probe_2d(([0.0, 0.0], [0.1, 0.06]))), vec![]);
        LiveExercise::new("s", ex, spec, vec![], "fig3-target".into(), 1000.0, hub)
    }

    /// A 2D record at tick `k` (1 kHz), the tip `depth_m` along −y below (0, 0.06), in contact.
    fn record(k: u64, depth_m: f64) -> TickRecord {
        let mut r = TickRecord { tick: k, time_s: k as f64 * 1e-3, dimension: 2, n_tip: 1, ..TickRecord::default() };
        r.base = needlesim_core::BasePose::new(0.0, 0.16 - depth_m, -std::f64::consts::FRAC_PI_2);
        r.tip_m = [0.0, 0.06 - depth_m];
        r
    }

    #[test]
    fn the_exercise_clock_stops_while_paused_and_restarts_at_a_reset() {
        let ex = exercise();
        for k in 0..=1000 {
            ex.score_record(&record(k, k as f64 * 1e-5));
        }
        ex.lock().paused = true;
        for k in 1001..=2000 {
            ex.score_record(&record(k, 0.01));
        }
        ex.lock().paused = false;
        for k in 2001..=3000 {
            ex.score_record(&record(k, 0.01 + (k - 2000) as f64 * 1e-5));
        }
        let snap = ex.snapshot();
        // 1 s before the pause, 1 s after it (the first record after it is 1 ms after the last).
        assert_eq!(snap.metrics.samples, 2001);
        assert!((snap.time_s - 2.0).abs() < 1e-9, "exercise time {} s", snap.time_s);
        assert!((snap.metrics.time_s - 2.0).abs() < 1e-9, "metrics time {} s", snap.metrics.time_s);
        assert_eq!(snap.tick, 3000);
        // The tip went 10 mm in, was held while paused, then 10 mm more: 20 mm of path.
        assert!((snap.metrics.path_length_m - 0.02).abs() < 1e-9, "path {} m", snap.metrics.path_length_m);
        let m = ex.add_marker("here").unwrap();
        assert_eq!((m.tick, m.t_s), (3000, snap.time_s));
        ex.reset().unwrap();
        let snap = ex.snapshot();
        assert_eq!((snap.metrics.samples, snap.markers.len(), snap.resets), (0, 0, 1));
        ex.score_record(&record(3001, 0.02));
        ex.score_record(&record(3002, 0.02));
        let snap = ex.snapshot();
        assert_eq!(snap.metrics.samples, 2);
        assert!((snap.time_s - 1e-3).abs() < 1e-12, "the clock restarts at the reset: {} s", snap.time_s);
    }

    /// Issue 20's race, step by step: the trainee's check passes, then the instructor takes
    /// control, then the trainee's stream or SetPose reaches the lease (with `take_over`): refused,
    /// and the instructor keeps driving. The device is suspended while control or a pause holds.
    #[tokio::test]
    async fn issue_20_a_trainee_checked_just_before_take_control_cannot_take_the_lease_after_it() {
        use needlesim_session::control_lease::Busy;
        let scene = needlesim_scene::load_scene("paper-phantom", &needlesim_core::MeshLimits::default()).unwrap();
        let s = Session::start(&scene, 1000.0, None).unwrap();
        let ex = exercise();
        let mut trainee = s.control.acquire_stream("trainee", false).await.unwrap();
        assert!(ex.refuse_trainee().is_ok(), "the trainee's check passes");
        ex.take_control(&s).unwrap();
        trainee.revoked().await;
        assert!(!trainee.write_if_held(|| panic!("the revoked trainee writes")));
        assert!(s.device_suspended());
        assert_eq!(s.control.acquire_stream("trainee", true).await.err(), Some(Busy::Exclusive));
        assert_eq!(s.control.with_unary("trainee", true, || panic!("the trainee writes")).await, Err::<(), _>(Busy::Exclusive));
        let mut wrote = false;
        ex.write_as_instructor(|| wrote = true).unwrap();
        assert!(wrote, "the instructor drives");
        // Paused, then handed back: still locked (the pause holds); resumed: free.
        ex.set_paused(&s, true).unwrap();
        ex.hand_back(&s).unwrap();
        assert!(s.device_suspended(), "paused: the device stays suspended");
        assert_eq!(ex.refuse_trainee().unwrap_err().code(), tonic::Code::FailedPrecondition);
        assert_eq!(s.control.acquire_stream("trainee", true).await.err(), Some(Busy::Exclusive));
        ex.set_paused(&s, false).unwrap();
        assert!(!s.device_suspended());
        assert!(ex.refuse_trainee().is_ok());
        assert!(s.control.acquire_stream("trainee", false).await.is_ok(), "the lease is free again");
        s.close();
    }

    /// Issue 35: TakeControl, HandBackControl and SetPaused after the end are FAILED_PRECONDITION;
    /// an instructor who held control at the end has let it go (the trainee drives again).
    #[tokio::test]
    async fn issue_35_control_calls_after_the_end_are_refused_and_the_hold_is_let_go() {
        let scene = needlesim_scene::load_scene("paper-phantom", &needlesim_core::MeshLimits::default()).unwrap();
        let s = Session::start(&scene, 1000.0, None).unwrap();
        let ex = exercise();
        ex.take_control(&s).unwrap();
        assert!(s.device_suspended());
        let dir = std::env::temp_dir().join(format!("needlesim-training-end-{}", std::process::id()));
        ex.end(&s, &dir, &crate::quota::DirQuota::unlimited("reports", "html")).unwrap();
        assert!(!s.device_suspended(), "the end lets the instructor's hold go");
        assert!(ex.refuse_trainee().is_ok());
        assert!(s.control.acquire_stream("trainee", false).await.is_ok(), "the lease is free after the end");
        for (what, r) in
            [("TakeControl", ex.take_control(&s)), ("HandBackControl", ex.hand_back(&s)), ("SetPaused", ex.set_paused(&s, true))]
        {
            let e = r.unwrap_err();
            assert_eq!(e.code(), tonic::Code::FailedPrecondition, "{what}");
            assert!(e.message().contains("has ended"), "{what}: {}", e.message());
        }
        assert!(!s.device_suspended(), "nothing refused took hold");
        s.close();
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn markers_are_checked_and_an_ended_exercise_takes_nothing() {
        let scene = needlesim_scene::load_scene("paper-phantom", &needlesim_core::MeshLimits::default()).unwrap();
        let s = Session::start(&scene, 1000.0, None).unwrap();
        let ex = exercise();
        assert_eq!(ex.add_marker(&"x".repeat(201)).unwrap_err().code(), tonic::Code::InvalidArgument);
        assert_eq!(ex.add_marker("a\nb").unwrap_err().code(), tonic::Code::InvalidArgument);
        // No target in this spec: every placement is refused, and counted.
        ex.score_record(&record(0, 0.0));
        assert_eq!(ex.place().unwrap_err().code(), tonic::Code::FailedPrecondition);
        let dir = std::env::temp_dir().join(format!("needlesim-training-live-{}", std::process::id()));
        let f = ex.end(&s, &dir, &crate::quota::DirQuota::unlimited("reports", "html")).unwrap();
        assert!(f.report_path.is_file());
        let html = std::fs::read_to_string(&f.report_path).unwrap();
        assert!(html.contains("Refused declarations"), "the refused placement is in the report");
        let samples = ex.snapshot().metrics.samples;
        ex.score_record(&record(1, 0.0));
        assert_eq!(ex.snapshot().metrics.samples, samples, "an ended exercise scores no more records");
        assert_eq!(ex.add_marker("late").unwrap_err().code(), tonic::Code::FailedPrecondition);
        assert_eq!(
            ex.end(&s, &dir, &crate::quota::DirQuota::unlimited("reports", "html")).unwrap().report_name,
            f.report_name,
            "ending twice: the same report"
        );
        s.close();
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_2d_sample_takes_its_axis_from_the_needle_shape_and_its_targets_from_the_record() {
        let mut r = record(5, 0.01);
        r.n_shape = 3;
        r.shape_m[0] = [0.0, 0.1];
        r.shape_m[1] = [0.0, 0.08];
        r.shape_m[2] = [0.003, 0.04];
        r.force_axial_n = -0.5;
        r.n_targets = 1;
        r.targets[0].position_m = [0.003, 0.0];
        let s = sample_of(&r, 0.25);
        let n = (0.003f64 * 0.003 + 0.04 * 0.04).sqrt();
        assert!((s.axis[0] - 0.003 / n).abs() < 1e-15 && (s.axis[1] + 0.04 / n).abs() < 1e-15);
        assert_eq!((s.t_s, s.axial_force_n, s.contacts), (0.25, 0.5, 1));
        assert_eq!(s.targets().len(), 1);
        assert!((s.targets()[0].distance_m - (0.003f64.powi(2) + 0.05f64.powi(2)).sqrt()).abs() < 1e-15);
        // Without a shape: the base angle.
        r.n_shape = 0;
        let s = sample_of(&r, 0.25);
        assert!((s.axis[0]).abs() < 1e-15 && (s.axis[1] + 1.0).abs() < 1e-15);
    }
}
