//! `ControlService`: the Control stream (poses in, one response per tick out), SetPose and
//! FlipBevel, one controller at a time through the session's control lease.

use std::sync::Arc;
use std::sync::atomic::Ordering;

use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status, Streaming};

use needlesim_session::{PoseCommand, Session};

use super::{Api, BoxStream, Role, authorize, check_pose, token_of};
use crate::convert;

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
        Ok(Response::new(convert::flip_bevel_response(flips_requested)))
    }
}

/// Who sends a request, for the control lease: its IP address (the port changes with each
/// connection a browser opens), or "unknown".
fn client_address<T>(req: &Request<T>) -> String {
    req.remote_addr().map_or_else(|| "unknown".to_owned(), |a| format!("ip:{}", a.ip()))
}

/// FAILED_PRECONDITION for a request refused by the session's control lease.
fn control_refused(s: &Session, busy: needlesim_session::control_lease::Busy) -> Status {
    Status::failed_precondition(format!("session {}: {busy}; one controller at a time (set `take_over` to take control from it)", s.id))
}

/// Sets its flag when dropped (when the task holding it ends, however it ends).
struct SetOnDrop(Arc<std::sync::atomic::AtomicBool>);

impl Drop for SetOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}
