//! `ControlService`: the Control stream (poses in, one response per tick out), SetPose and
//! FlipBevel, one controller at a time through the session's control lease (held exclusively by a
//! training exercise's instructor while in control or paused: then no `take_over` gets it).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status, Streaming};

use needlesim_session::{PoseCommand, Session};

use super::{Api, BoxStream, Role, authorize, token_of};
use crate::convert::{self, ClientPose};

/// What the Control streams (2D `ControlRequest`, 3D `ControlRequest3`) need of a message.
trait ControlMessage: Send + 'static {
    fn session_id(&self) -> &str;
    /// The pose, checked against the session's dimension; `None` for a message that only flips
    /// the bevel.
    fn pose(&self, s: &Session) -> Result<Option<ClientPose>, Status>;
    fn flip_bevel(&self) -> bool;
    fn take_over(&self) -> bool;
    fn seq(&self) -> u64;
    fn client_time_ns(&self) -> u64;
}

impl ControlMessage for pb::ControlRequest {
    fn session_id(&self) -> &str {
        &self.session_id
    }
    fn pose(&self, s: &Session) -> Result<Option<ClientPose>, Status> {
        if self.flip_bevel && self.base.is_none() {
            return Ok(None);
        }
        Ok(Some(convert::checked_pose2_for(self.base.as_ref(), s.dimension())?))
    }
    fn flip_bevel(&self) -> bool {
        self.flip_bevel
    }
    fn take_over(&self) -> bool {
        self.take_over
    }
    fn seq(&self) -> u64 {
        self.seq
    }
    fn client_time_ns(&self) -> u64 {
        self.client_time_ns
    }
}

impl ControlMessage for pb::ControlRequest3 {
    fn session_id(&self) -> &str {
        &self.session_id
    }
    fn pose(&self, s: &Session) -> Result<Option<ClientPose>, Status> {
        Ok(Some(convert::checked_pose3_for(self.base3.as_ref(), s.dimension())?))
    }
    fn flip_bevel(&self) -> bool {
        false
    }
    fn take_over(&self) -> bool {
        self.take_over
    }
    fn seq(&self) -> u64 {
        self.seq
    }
    fn client_time_ns(&self) -> u64 {
        self.client_time_ns
    }
}

/// Publishes a checked pose (its dimension is the session's: [`ControlMessage::pose`]).
fn write_pose(s: &Session, pose: ClientPose, seq: u64, client_time_ns: u64) {
    match pose {
        ClientPose::Two(pose) => s.write_client_pose_from_io(PoseCommand { pose, seq, client_time_ns }),
        ClientPose::Three(pose) => {
            // Cannot fail: the pose was checked against the session's dimension.
            let _ = s.write_client_pose3_from_io(PoseCommand { pose, seq, client_time_ns });
        }
    }
}

#[tonic::async_trait]
impl pb::control_service_server::ControlService for Api {
    type ControlStream = BoxStream<pb::ControlResponse>;
    type Control3Stream = BoxStream<pb::ControlResponse>;

    async fn control(&self, req: Request<Streaming<pb::ControlRequest>>) -> Result<Response<Self::ControlStream>, Status> {
        control_stream(self, req).await
    }

    async fn control3(&self, req: Request<Streaming<pb::ControlRequest3>>) -> Result<Response<Self::Control3Stream>, Status> {
        control_stream(self, req).await
    }

    async fn set_pose(&self, req: Request<pb::SetPoseRequest>) -> Result<Response<pb::ControlResponse>, Status> {
        let r = req.get_ref();
        let s = self.state.session(&r.session_id)?;
        // The controller token, or an exercise's instructor (training_live.rs).
        let instructor = crate::training_live::authorize_pose(&self.state.training, &req, &s)?;
        let pose = convert::checked_pose2_for(r.base.as_ref(), s.dimension()).map_err(Status::from);
        match instructor {
            Some(ex) => instructor_pose(&s, &ex, pose),
            None => set_pose(&s, &req, pose, &r.client_id, r.take_over).await,
        }
    }

    async fn set_pose3(&self, req: Request<pb::SetPoseRequest3>) -> Result<Response<pb::ControlResponse>, Status> {
        let r = req.get_ref();
        let s = self.state.session(&r.session_id)?;
        let instructor = crate::training_live::authorize_pose(&self.state.training, &req, &s)?;
        let pose = convert::checked_pose3_for(r.base3.as_ref(), s.dimension()).map_err(Status::from);
        match instructor {
            Some(ex) => instructor_pose(&s, &ex, pose),
            None => set_pose(&s, &req, pose, &r.client_id, r.take_over).await,
        }
    }

    async fn flip_bevel(&self, req: Request<pb::FlipBevelRequest>) -> Result<Response<pb::FlipBevelResponse>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        crate::training_live::refuse_trainee(&self.state.training, &s)?;
        if !s.has_bevel {
            return Err(Status::failed_precondition(format!(
                "session {}: the needle has a symmetric tip (a rigid needle, or a flexible one without bevel_force_ratio); there is no bevel to flip",
                s.id
            )));
        }
        let r = req.get_ref();
        // A flip is driving: one controller at a time, as for SetPose.
        let flips_requested = drive_unary(&s, &req, &r.client_id, r.take_over, || s.request_bevel_flip_from_io()).await?;
        Ok(Response::new(convert::flip_bevel_response(flips_requested)))
    }

    async fn set_spin(&self, req: Request<pb::SetSpinRequest>) -> Result<Response<pb::SetSpinResponse>, Status> {
        set_spin(self, req).await
    }
}

/// SetSpin (the proto's docs): checked, then written under the control lease as a flip is.
async fn set_spin(api: &Api, req: Request<pb::SetSpinRequest>) -> Result<Response<pb::SetSpinResponse>, Status> {
    let s = api.state.session(&req.get_ref().session_id)?;
    authorize(&req, &s, Role::Controller)?;
    crate::training_live::refuse_trainee(&api.state.training, &s)?;
    if s.dimension() != 3 {
        return Err(Status::failed_precondition(format!(
            "session {}: spinning rolls a 3D needle about its own axis; a 2D needle has none (a 2D bevel turns with FlipBevel)",
            s.id
        )));
    }
    let r = req.get_ref();
    let spin =
        needlesim_session::spin::SpinCommand::new(r.duty_cycle, r.period_m).map_err(|e| Status::from(crate::status::ApiError::from(e)))?;
    // Spinning is driving: one controller at a time, as for a flip.
    drive_unary(&s, &req, &r.client_id, r.take_over, || s.set_spin_from_io(spin)).await?;
    Ok(Response::new(convert::set_spin_response(&spin)))
}

/// SetPose and SetPose3 of an exercise's instructor: the pose written under the control lease
/// the instructor holds (training_live.rs).
fn instructor_pose(
    s: &Arc<Session>,
    ex: &crate::training_live::LiveExercise,
    pose: Result<ClientPose, Status>,
) -> Result<Response<pb::ControlResponse>, Status> {
    let pose = pose.inspect_err(|_| {
        s.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
    })?;
    ex.write_as_instructor(|| {
        let seq = s.counters.poses_written.load(Ordering::Relaxed) + 1;
        write_pose(s, pose, seq, 0);
    })?;
    Ok(Response::new(convert::control_response(&s.latest_record(), &s.target_names)))
}

/// SetPose and SetPose3: one pose (checked by the caller), answered with the latest state.
async fn set_pose<T>(
    s: &Arc<Session>,
    req: &Request<T>,
    pose: Result<ClientPose, Status>,
    client_id: &str,
    take_over: bool,
) -> Result<Response<pb::ControlResponse>, Status> {
    let pose = pose.inspect_err(|_| {
        s.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
    })?;
    // One controller at a time: refused while a Control stream or another SetPose client
    // holds the lease, unless it takes over.
    drive_unary(s, req, client_id, take_over, || {
        let seq = s.counters.poses_written.load(Ordering::Relaxed) + 1;
        write_pose(s, pose, seq, 0);
    })
    .await?;
    Ok(Response::new(convert::control_response(&s.latest_record(), &s.target_names)))
}

/// A unary driving request (SetPose, SetPose3, FlipBevel, SetSpin): `write` runs under the
/// session's control lease for the client `client_id` names (else its address), which takes
/// the lease from another unary client with `take_over`.
///
/// Errors: FAILED_PRECONDITION when the lease is held (`control_refused`).
async fn drive_unary<T, R>(
    s: &Session,
    req: &Request<T>,
    client_id: &str,
    take_over: bool,
    write: impl FnOnce() -> R,
) -> Result<R, Status> {
    let client = if client_id.is_empty() { client_address(req) } else { format!("id:{client_id}") };
    s.control.with_unary(&client, take_over, write).await.map_err(|busy| control_refused(s, busy))
}

/// Control and Control3 streams waiting for their first message now.
static AWAITING_FIRST_MESSAGE: AtomicUsize = AtomicUsize::new(0);
/// Control and Control3 streams ended because no first message came in time.
static FIRST_MESSAGE_TIMEOUTS: AtomicU64 = AtomicU64::new(0);

/// Control and Control3 streams waiting for their first message now (`/metrics`).
pub(crate) fn awaiting_first_message() -> usize {
    AWAITING_FIRST_MESSAGE.load(Ordering::Relaxed)
}

/// Control and Control3 streams ended with DEADLINE_EXCEEDED: no first message within
/// `--control-first-message-ms` (`/metrics`).
pub(crate) fn first_message_timeouts() -> u64 {
    FIRST_MESSAGE_TIMEOUTS.load(Ordering::Relaxed)
}

/// The first message of a Control stream, which must come within `deadline_ms` of the stream's
/// opening (issue 35: 15,000 streams that sent nothing were held, counted by nothing, for as long
/// as their clients liked): past it, DEADLINE_EXCEEDED naming the limit, and the stream ends.
async fn first_message<M: ControlMessage>(inbound: &mut Streaming<M>, deadline_ms: u64) -> Result<M, Status> {
    struct Waiting;
    impl Drop for Waiting {
        fn drop(&mut self) {
            AWAITING_FIRST_MESSAGE.fetch_sub(1, Ordering::Relaxed);
        }
    }
    AWAITING_FIRST_MESSAGE.fetch_add(1, Ordering::Relaxed);
    let _waiting = Waiting;
    match tokio::time::timeout(std::time::Duration::from_millis(deadline_ms), inbound.message()).await {
        Ok(m) => m?.ok_or_else(|| Status::invalid_argument("the control stream ended before its first message")),
        Err(_) => {
            FIRST_MESSAGE_TIMEOUTS.fetch_add(1, Ordering::Relaxed);
            Err(Status::deadline_exceeded(format!(
                "the control stream sent no first message within {deadline_ms} ms of opening (--control-first-message-ms)"
            )))
        }
    }
}

/// Control and Control3: poses in, one response per tick out; both tasks end, and the response
/// stream with NOT_FOUND, when the session closes (issue 35, H1).
async fn control_stream<M: ControlMessage>(
    api: &Api,
    req: Request<Streaming<M>>,
) -> Result<Response<BoxStream<pb::ControlResponse>>, Status> {
    let token = token_of(&req);
    let client = client_address(&req);
    let mut inbound = req.into_inner();
    let first = first_message(&mut inbound, api.state.limits.control_first_message_ms).await?;
    let s = api.state.session(first.session_id())?;
    if !token.as_deref().is_some_and(|t| crate::access::token_matches(t, &s.controller_token)) {
        return Err(Status::permission_denied("driving a session needs its controller token (`authorization: Bearer <token>`)"));
    }
    // An exercise whose instructor has control, or which is paused, refuses the trainee (and, if
    // the instructor takes control between this check and the lease below, the lease refuses:
    // the instructor holds it exclusively; training_live.rs, "Control").
    crate::training_live::refuse_trainee(&api.state.training, &s)?;
    // The first message must carry a pose (a flip alone is refused as a missing base).
    let pose = match first.pose(&s)? {
        Some(p) => p,
        None => return Err(convert::checked_pose2_for(None, s.dimension()).map_err(Status::from).unwrap_err()),
    };
    // A faulted session steps no more: a stream opened on it would wait for ticks forever.
    if let Some(e) = faulted(&s) {
        return Err(e);
    }
    // One controller at a time: this stream holds the session's control lease until it ends.
    let mut lease = s.control.acquire_stream(&client, first.take_over()).await.map_err(|busy| control_refused(&s, busy))?;
    if first.take_over() {
        tracing::info!(session = %s.id, %client, "a Control stream took control over");
    }
    lease.write_if_held(|| {
        if first.flip_bevel() {
            s.request_bevel_flip_from_io();
        }
        write_pose(&s, pose, first.seq().max(1), first.client_time_ns());
    });
    let (tx, rx) = mpsc::channel(256);
    // When the controller closes its side, the response stream ends too: the task reading the
    // poses holds `client_done`, whose drop wakes the task writing the responses (which may
    // wait for a tick that never comes: a faulted session makes none).
    let (client_done, mut client_gone) = tokio::sync::oneshot::channel::<()>();
    // Poses in: latest value wins; a malformed message ends the stream with its reason, and so
    // does a take-over by another client.
    let s_in = s.clone();
    let tx_err = tx.clone();
    let done_in = client_done;
    let closed_in = s.closed();
    tokio::spawn(async move {
        let _done = done_in;
        let mut seq = first.seq().max(1);
        tokio::pin!(closed_in);
        loop {
            let msg = tokio::select! {
                // The session closed: the response stream ends with the status (`of_session`);
                // this task lets go of the session and its lease.
                () = &mut closed_in => return,
                m = inbound.message() => m,
                () = lease.revoked() => {
                    let _ = tx_err.send(Err(Status::aborted(format!(
                        "control of session {} was taken over by another client", s_in.id
                    )))).await;
                    return;
                }
            };
            let held = match msg {
                Ok(Some(m)) => match m.pose(&s_in) {
                    Ok(None) => lease.write_if_held(|| {
                        s_in.request_bevel_flip_from_io();
                    }),
                    Ok(Some(pose)) => {
                        seq = if m.seq() > seq { m.seq() } else { seq + 1 };
                        lease.write_if_held(|| {
                            if m.flip_bevel() {
                                s_in.request_bevel_flip_from_io();
                            }
                            write_pose(&s_in, pose, seq, m.client_time_ns());
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
                let _ = tx_err.send(Err(Status::aborted(format!("control of session {} was taken over by another client", s_in.id)))).await;
                return;
            }
        }
    });
    // Responses out: one per tick; a slow controller skips ticks rather than delaying anyone.
    let mut ticks = s.all_ticks.subscribe();
    let names = s.target_names.clone();
    let closed_out = s.closed();
    let s_out = s.clone();
    tokio::spawn(async move {
        tokio::pin!(closed_out);
        // Faulted since the check above, before `ticks` subscribed: its last tick was missed.
        if let Some(e) = faulted(&s_out) {
            let _ = tx.send(Err(e)).await;
            return;
        }
        loop {
            // Ends at the session's close (whose `all_ticks` sender lives as long as the session:
            // no `Closed` comes while anything holds it), when the response stream is dropped,
            // and when the controller closed its side.
            let tick = tokio::select! {
                () = &mut closed_out => return,
                () = tx.closed() => return,
                _ = &mut client_gone => return,
                t = ticks.recv() => t,
            };
            match tick {
                Ok(rec) => {
                    // The tick that faulted is the last response: the session steps no more.
                    let last = rec.fault.is_some();
                    if tx.send(Ok(convert::control_response(&rec, &names))).await.is_err() || last {
                        return;
                    }
                }
                Err(tokio::sync::broadcast::error::RecvError::Lagged(_)) => {
                    // The skipped ticks may have held the faulted one.
                    if let Some(e) = faulted(&s_out) {
                        let _ = tx.send(Err(e)).await;
                        return;
                    }
                }
                Err(tokio::sync::broadcast::error::RecvError::Closed) => return,
            }
        }
    });
    // Ends with NOT_FOUND when the session closes (`streams::of_session`).
    Ok(Response::new(super::streams::of_session(&s, Box::pin(ReceiverStream::new(rx)))))
}

/// Who sends a request, for the control lease: its IP address (the port changes with each
/// connection a browser opens), or "unknown".
fn client_address<T>(req: &Request<T>) -> String {
    req.remote_addr().map_or_else(|| "unknown".to_owned(), |a| format!("ip:{}", a.ip()))
}

/// FAILED_PRECONDITION for a request refused by the session's control lease.
fn control_refused(s: &Session, busy: needlesim_session::control_lease::Busy) -> Status {
    use needlesim_session::control_lease::Busy;
    match busy {
        // Held exclusively by a training exercise's instructor (training_live.rs): reached by a
        // trainee whose check passed just before TakeControl or SetPaused.
        Busy::Exclusive => Status::failed_precondition(format!(
            "session {}: {busy} while in control or while the exercise is paused; the trainee's poses are refused until control is handed back and the exercise resumes",
            s.id
        )),
        Busy::Stream | Busy::Unary => Status::failed_precondition(format!(
            "session {}: {busy}; one controller at a time (set `take_over` to take control from it)",
            s.id
        )),
    }
}

/// FAILED_PRECONDITION naming the fault, if the session faulted (it steps no more).
fn faulted(s: &Session) -> Option<Status> {
    let fault = s.counters.fault()?;
    Some(Status::failed_precondition(format!(
        "session {} faulted ({}): it steps no more; close it and start a new one",
        s.id,
        fault.message()
    )))
}
