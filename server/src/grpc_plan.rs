//! The `PlanningService` of `needlesim.v1` (proto/needlesim/v1/planning.proto): the planner of
//! `plan.rs` on a blocking thread, its progress streamed over a bounded channel; a client that
//! goes away cancels the planning.
//!
//! Conventions follow `Simulate` (grpc.rs): no token (no session is involved), the request is
//! validated before the stream starts so that bad input is an INVALID_ARGUMENT status naming the
//! field, and size limits are RESOURCE_EXHAUSTED. At most `--max-plans` plans run at once, since
//! each uses every core; each also takes one of the `--max-offline-jobs` slots (jobs.rs).

use std::ops::ControlFlow;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status};

use crate::grpc::Api;
use crate::jobs::JobKind;
use crate::plan::{self, PlanOptions, PlanRequest};
use crate::status::{ApiError, status_of};

fn vec2(v: [f64; 2]) -> pb::Vec2 {
    pb::Vec2 { x: v[0], y: v[1] }
}

/// The request's planning problem; errors name the field.
pub fn plan_request_from_pb(r: &pb::PlanRequest) -> Result<PlanRequest, Status> {
    if r.target.trim().is_empty() {
        return Err(Status::invalid_argument("target is empty: give the name of one of the scene's targets"));
    }
    let entry_m = match (&r.entry_from_m, &r.entry_to_m) {
        (None, None) => None,
        (Some(a), Some(b)) => Some([[a.x, a.y], [b.x, b.y]]),
        _ => return Err(Status::invalid_argument("entry_from_m and entry_to_m: give both ends of the entry segment, or neither")),
    };
    let angles_deg = match (r.angle_min_deg, r.angle_max_deg) {
        (None, None) => None,
        (Some(a), Some(b)) => Some([a, b]),
        _ => return Err(Status::invalid_argument("angle_min_deg and angle_max_deg: give both, or neither")),
    };
    Ok(PlanRequest { target: r.target.clone(), entry_m, angles_deg, speed_m_s: r.speed_mm_s.map(|v| v * 1e-3) })
}

/// The final message's result.
pub fn plan_result_to_pb(p: &plan::Plan) -> pb::PlanResult {
    let ins = |i: &plan::Insertion| pb::PlannedInsertion {
        entry_m: Some(vec2(i.entry_m)),
        angle_rad: i.angle_rad,
        depth_m: i.depth_m,
        predicted_error_m: i.predicted_error_m,
        tip_m: Some(vec2(i.tip_m)),
        target_m: Some(vec2(i.target_m)),
        aim_m: Some(vec2(i.aim_m)),
    };
    pb::PlanResult {
        target: p.target.clone(),
        target_radius_m: p.target_radius_m,
        target_center_m: Some(vec2(p.target_center_m)),
        speed_mm_s: p.speed_m_s * 1e3,
        plan: Some(ins(&p.plan)),
        straight: Some(ins(&p.straight)),
        trajectory: p
            .trajectory
            .iter()
            .map(|&[t, x, y, th]| pb::TrajectorySample { t_s: t, base: Some(pb::Pose2 { x_m: x, y_m: y, theta_rad: th }) })
            .collect(),
        converged: p.converged,
        iterations: p.iterations as u32,
        simulations: p.simulations as u32,
        wall_s: p.wall_s,
        threads: p.threads as u32,
    }
}

/// Whether a planner error is the caller's fault (a named field) rather than the server's.
fn is_input_error(msg: &str) -> bool {
    ["target", "entry", "angles_deg", "speed_mm_s"].iter().any(|f| msg.starts_with(&format!("{f}:")) || msg.starts_with(&format!("{f} =")))
}

#[tonic::async_trait]
impl pb::planning_service_server::PlanningService for Api {
    type PlanStream = ReceiverStream<Result<pb::PlanProgress, Status>>;

    async fn plan(&self, req: Request<pb::PlanRequest>) -> Result<Response<Self::PlanStream>, Status> {
        let r = req.into_inner();
        let preq = plan_request_from_pb(&r)?;
        let slot = self.state.jobs.try_start(JobKind::Plan)?;
        let scene = crate::grpc::load_scene_from_pb(r.scene.clone(), self.state.limits.scene()).await?;
        // Errors in the problem are statuses, not stream items: the planner's first output is a
        // validated problem or an error naming the field, so it is awaited before answering.
        let (tx, rx) = mpsc::channel(8);
        let (first_tx, first_rx) = tokio::sync::oneshot::channel::<Result<(), Status>>();
        let cancel = Arc::new(AtomicBool::new(false));
        // The client going away (the receiver dropped) cancels the planning. The watcher's sender
        // is dropped when the planning ends (`done`), or the stream would never end.
        let (watch_tx, cancel_watch) = (tx.clone(), cancel.clone());
        let (done, done_rx) = tokio::sync::oneshot::channel::<()>();
        tokio::spawn(async move {
            tokio::select! {
                _ = watch_tx.closed() => cancel_watch.store(true, Ordering::Relaxed),
                _ = done_rx => {}
            }
        });
        let opts = PlanOptions {
            cancel: Some(cancel.clone()),
            max_ticks_per_simulation: self.state.limits.max_simulate_ticks,
            ..Default::default()
        };
        tokio::task::spawn_blocking(move || {
            let _slot = slot;
            let _done = done;
            let mut first_tx = Some(first_tx);
            if let Err(e) = plan::validate_request(&scene, &preq, &opts) {
                let status = status_of("", &e);
                if let Some(f) = first_tx.take() {
                    let _ = f.send(Err(status));
                }
                return;
            }
            if let Some(f) = first_tx.take() {
                let _ = f.send(Ok(()));
            }
            let result = plan::plan(&scene, &preq, &opts, |pr| {
                let msg = pb::PlanProgress {
                    iteration: pr.iteration as u32,
                    simulations: pr.simulations as u32,
                    best_error_m: pr.best_error_m,
                    straight_error_m: pr.straight_error_m,
                    result: None,
                };
                if tx.blocking_send(Ok(msg)).is_err() { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
            });
            match result {
                Ok(p) => {
                    tracing::info!(
                        scene = %p.scene,
                        target = %p.target,
                        plan_error_mm = p.plan.predicted_error_m * 1e3,
                        straight_error_mm = p.straight.predicted_error_m * 1e3,
                        simulations = p.simulations,
                        wall_s = p.wall_s,
                        "planned"
                    );
                    let last = pb::PlanProgress {
                        iteration: p.iterations as u32,
                        simulations: p.simulations as u32,
                        best_error_m: p.plan.predicted_error_m,
                        straight_error_m: p.straight.predicted_error_m,
                        result: Some(plan_result_to_pb(&p)),
                    };
                    let _ = tx.blocking_send(Ok(last));
                }
                Err(_) if cancel.load(Ordering::Relaxed) => tracing::info!("planning cancelled: the client went away"),
                Err(e) => {
                    let msg = format!("{e:#}");
                    let status = if is_input_error(&msg) { status_of("", &e) } else { ApiError::Internal(msg).into() };
                    let _ = tx.blocking_send(Err(status));
                }
            }
        });
        first_rx.await.map_err(|_| Status::internal("the planning task ended before validating the request"))??;
        Ok(Response::new(ReceiverStream::new(rx)))
    }
}
