//! The `PlanningService` of `needlesim.v1` (proto/needlesim/v1/planning.proto): the planner of
//! `needlesim_offline::plan` (2D scenes) or `needlesim_offline::plan3` (3D scenes: a 3D
//! example's name, a TOML with `dim = 3`, an uploaded 3D scene) on a blocking thread, its progress streamed over a bounded channel; a client that
//! goes away cancels the planning.
//!
//! Conventions follow `Simulate` (grpc/simulate.rs): no token (no session is involved), the request is
//! validated before the stream starts so that bad input is an INVALID_ARGUMENT status naming the
//! field, and size limits are RESOURCE_EXHAUSTED. At most `--max-plans` plans run at once, since
//! each uses every core; each also takes one of the `--max-offline-jobs` slots (jobs.rs), first:
//! nothing the client sent is read before, and all of it is read on a blocking thread.

use std::ops::ControlFlow;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use needlesim_proto::v1 as pb;
use tonic::{Request, Response, Status};

use crate::convert;
use crate::grpc::Api;
use crate::jobs::{JobKind, JobPermit};
use crate::status::{ApiError, status_of};
use needlesim_offline::plan::{self, PlanOptions};
use needlesim_offline::plan3;

#[tonic::async_trait]
impl pb::planning_service_server::PlanningService for Api {
    type PlanStream = crate::jobs::JobStream<pb::PlanProgress>;

    async fn plan(&self, req: Request<pb::PlanRequest>) -> Result<Response<Self::PlanStream>, Status> {
        let r = req.into_inner();
        // The slots first (issue 35): a Plan on a busy server is refused before anything of the
        // client's is read; the scene's dimension, the request and the scene are then read on a
        // blocking thread, never on the async runtime (the scene TOML is bounded besides:
        // `needlesim_scene::MAX_SCENE_TOML_BYTES`).
        let slot = self.state.jobs.try_start(JobKind::Plan)?;
        let limits = self.state.limits.scene();
        let loaded = tokio::task::spawn_blocking(move || -> Result<PlanInput, Status> {
            if convert::scene_source_is_3d(r.scene.as_ref()) {
                let preq = convert::plan3_request_from_pb(&r).map_err(Status::from)?;
                match convert::session_scene_from_pb(r.scene.as_ref(), &limits).map_err(|e| status_of("scene", &e))? {
                    convert::SessionScene::Three(scene) => Ok(PlanInput::Three(scene, preq)),
                    convert::SessionScene::Two(_) => Err(Status::internal("a 3D scene source loaded as a 2D scene")),
                }
            } else {
                let preq = convert::plan_request_from_pb(&r).map_err(Status::from)?;
                let scene = convert::scene_from_pb(r.scene.as_ref(), &limits).map_err(|e| status_of("scene", &e))?;
                Ok(PlanInput::Two(Box::new(scene), preq))
            }
        })
        .await
        .map_err(|e| Status::internal(format!("scene task: {e}")))??;
        match loaded {
            PlanInput::Two(scene, preq) => self.plan2(slot, *scene, preq).await,
            PlanInput::Three(scene, preq) => self.plan3(slot, *scene, preq).await,
        }
    }
}

/// A Plan's request and scene, read off the async runtime.
enum PlanInput {
    Two(Box<needlesim_scene::Scene>, plan::PlanRequest),
    Three(Box<needlesim_scene::Scene3d>, plan3::Plan3Request),
}

impl Api {
    /// `Plan` for a 2D scene: `needlesim_offline::plan`.
    async fn plan2(
        &self,
        slot: JobPermit,
        scene: needlesim_scene::Scene,
        preq: plan::PlanRequest,
    ) -> Result<Response<crate::jobs::JobStream<pb::PlanProgress>>, Status> {
        let opts = self.plan_options();
        stream_plan(slot, opts, move |opts, validated, progress| {
            plan::validate_request(&scene, &preq, opts)?;
            validated();
            let p = plan::plan(&scene, &preq, opts, |pr| progress(convert::plan_progress(pr)))?;
            tracing::info!(
                scene = %p.scene,
                target = %p.target,
                plan_error_mm = p.plan.predicted_error_m * 1e3,
                straight_error_mm = p.straight.predicted_error_m * 1e3,
                simulations = p.simulations,
                wall_s = p.wall_s,
                "planned"
            );
            Ok(convert::plan_final(&p))
        })
        .await
    }

    /// `Plan` for a 3D scene: `needlesim_offline::plan3` with the same conventions (validation
    /// before the stream, progress per iteration, the client going away cancels).
    async fn plan3(
        &self,
        slot: JobPermit,
        scene: needlesim_scene::Scene3d,
        preq: plan3::Plan3Request,
    ) -> Result<Response<crate::jobs::JobStream<pb::PlanProgress>>, Status> {
        let opts = self.plan_options();
        stream_plan(slot, opts, move |opts, validated, progress| {
            plan3::validate3_request(&scene, &preq)?;
            validated();
            let p = plan3::plan3(&scene, &preq, opts, |pr| progress(convert::plan_progress(pr)))?;
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
            Ok(convert::plan3_final(&p))
        })
        .await
    }

    /// The planners' options: the server's tick limit per simulation (the cancel flag is
    /// [`stream_plan`]'s).
    fn plan_options(&self) -> PlanOptions {
        PlanOptions { max_ticks_per_simulation: self.state.limits.max_simulate_ticks, ..Default::default() }
    }
}

/// Runs a planner on a blocking thread and streams it: `run(opts, validated, progress)` checks
/// the request first and calls `validated()` once it is valid — an error before that is the
/// call's status (INVALID_ARGUMENT naming the field), so bad input never opens a stream — then
/// sends its progress through `progress` (which breaks when the client has gone) and returns the
/// final message. The client going away sets the cancel flag in `opts`, which ends the planning;
/// an error after validation is the stream's last item. The job slot is held until the end.
async fn stream_plan<R>(
    slot: JobPermit,
    mut opts: PlanOptions,
    run: R,
) -> Result<Response<crate::jobs::JobStream<pb::PlanProgress>>, Status>
where
    R: FnOnce(&PlanOptions, &mut dyn FnMut(), &mut dyn FnMut(pb::PlanProgress) -> ControlFlow<()>) -> anyhow::Result<pb::PlanProgress>
        + Send
        + 'static,
{
    let (tx, stream) = slot.stream(8);
    let (first_tx, first_rx) = tokio::sync::oneshot::channel::<Result<(), Status>>();
    let cancel = Arc::new(AtomicBool::new(false));
    // The client going away (the receiver dropped) cancels the planning. The watcher's sender
    // is dropped when the planning ends (`done`), or the stream would never end.
    let (closed, cancel_watch) = (tx.closed(), cancel.clone());
    let (done, done_rx) = tokio::sync::oneshot::channel::<()>();
    tokio::spawn(async move {
        tokio::select! {
            () = closed => cancel_watch.store(true, Ordering::Relaxed),
            _ = done_rx => {}
        }
    });
    opts.cancel = Some(cancel.clone());
    tokio::task::spawn_blocking(move || {
        let _slot = slot;
        let _done = done;
        let mut first_tx = Some(first_tx);
        let mut validated = || {
            if let Some(f) = first_tx.take() {
                let _ = f.send(Ok(()));
            }
        };
        let mut progress = |msg: pb::PlanProgress| {
            if tx.send_blocking(Ok(msg)).is_err() { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
        };
        let result = run(&opts, &mut validated, &mut progress);
        match (result, first_tx.take()) {
            // Not yet validated: the error is the call's status.
            (Err(e), Some(f)) => {
                let _ = f.send(Err(status_of("", &e)));
            }
            (Ok(last), _) => {
                let _ = tx.send_blocking(Ok(last));
            }
            (Err(_), None) if cancel.load(Ordering::Relaxed) => tracing::info!("planning cancelled: the client went away"),
            (Err(e), None) => {
                let _ = tx.send_blocking(Err(ApiError::after_validation(&e).into()));
            }
        }
    });
    first_rx.await.map_err(|_| Status::internal("the planning task ended before validating the request"))??;
    Ok(Response::new(stream))
}
