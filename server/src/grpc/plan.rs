//! The `PlanningService` of `needlesim.v1` (proto/needlesim/v1/planning.proto): the planner of
//! `needlesim_offline::plan` (2D scenes) or `needlesim_offline::plan3` (3D scenes: a 3D
//! example's name, a TOML with `dim = 3`, an uploaded 3D scene) on a blocking thread, its progress streamed over a bounded channel; a client that
//! goes away cancels the planning.
//!
//! Conventions follow `Simulate` (grpc/simulate.rs): no token (no session is involved), the request is
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

use crate::convert;
use crate::grpc::Api;
use crate::jobs::JobKind;
use crate::status::{ApiError, status_of};
use needlesim_offline::plan::{self, PlanOptions};
use needlesim_offline::plan3;

#[tonic::async_trait]
impl pb::planning_service_server::PlanningService for Api {
    type PlanStream = ReceiverStream<Result<pb::PlanProgress, Status>>;

    async fn plan(&self, req: Request<pb::PlanRequest>) -> Result<Response<Self::PlanStream>, Status> {
        let r = req.into_inner();
        let dim3 = convert::scene_source_is_3d(r.scene.as_ref());
        if dim3 {
            return self.plan3(r).await;
        }
        let preq = convert::plan_request_from_pb(&r).map_err(Status::from)?;
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
                let msg = convert::plan_progress(pr);
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
                    let last = convert::plan_final(&p);
                    let _ = tx.blocking_send(Ok(last));
                }
                Err(_) if cancel.load(Ordering::Relaxed) => tracing::info!("planning cancelled: the client went away"),
                Err(e) => {
                    let _ = tx.blocking_send(Err(ApiError::after_validation(&e).into()));
                }
            }
        });
        first_rx.await.map_err(|_| Status::internal("the planning task ended before validating the request"))??;
        Ok(Response::new(ReceiverStream::new(rx)))
    }
}

impl Api {
    /// `Plan` for a 3D scene: `needlesim_offline::plan3` with the same conventions (validation
    /// before the stream, progress per iteration, the client going away cancels).
    async fn plan3(&self, r: pb::PlanRequest) -> Result<Response<ReceiverStream<Result<pb::PlanProgress, Status>>>, Status> {
        let preq = convert::plan3_request_from_pb(&r).map_err(Status::from)?;
        let slot = self.state.jobs.try_start(JobKind::Plan)?;
        let scene = match crate::grpc::load_session_scene_from_pb(r.scene.clone(), self.state.limits.scene()).await? {
            convert::SessionScene::Three(s) => s,
            convert::SessionScene::Two(_) => return Err(Status::internal("a 3D scene source loaded as a 2D scene")),
        };
        let (tx, rx) = mpsc::channel(8);
        let (first_tx, first_rx) = tokio::sync::oneshot::channel::<Result<(), Status>>();
        let cancel = Arc::new(AtomicBool::new(false));
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
            if let Err(e) = plan3::validate3_request(&scene, &preq) {
                let _ = first_tx.send(Err(status_of("", &e)));
                return;
            }
            let _ = first_tx.send(Ok(()));
            let result = plan3::plan3(&scene, &preq, &opts, |pr| {
                let msg = convert::plan_progress(pr);
                if tx.blocking_send(Ok(msg)).is_err() { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
            });
            match result {
                Ok(p) => {
                    tracing::info!(
                        scene = %p.scene,
                        target = %p.target,
                        plan_error_mm = p.plan.predicted_error_m * 1e3,
                        straight_error_mm = p.straight.predicted_error_m * 1e3,
                        clearance_mm = p.plan.min_clearance_m() * 1e3,
                        simulations = p.simulations,
                        wall_s = p.wall_s,
                        "planned in 3D"
                    );
                    let _ = tx.blocking_send(Ok(convert::plan3_final(&p)));
                }
                Err(_) if cancel.load(Ordering::Relaxed) => tracing::info!("planning cancelled: the client went away"),
                Err(e) => {
                    let _ = tx.blocking_send(Err(ApiError::after_validation(&e).into()));
                }
            }
        });
        first_rx.await.map_err(|_| Status::internal("the planning task ended before validating the request"))??;
        Ok(Response::new(ReceiverStream::new(rx)))
    }
}
