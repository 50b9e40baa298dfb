//! `SessionService`: create (a scene loaded off the runtime, within the session limit; with its
//! recording, or nothing), list, get, mesh, statistics, close.

use needlesim_proto::v1 as pb;
use tonic::{Request, Response, Status};

use super::{Api, Role, authorize, load_session_scene_from_pb};
use crate::convert;
use crate::status::ApiError;

#[tonic::async_trait]
impl pb::session_service_server::SessionService for Api {
    async fn create_session(&self, req: Request<pb::CreateSessionRequest>) -> Result<Response<pb::CreateSessionResponse>, Status> {
        let mut r = req.into_inner();
        // The limit is checked and a place reserved first, in one step: a create over the limit
        // costs nothing, and concurrent creates never exceed it.
        let slot = self.state.reserve_session_slot()?;
        // So is the room for its recording: a full recordings directory starts nothing.
        if r.record {
            self.state.check_recording_room()?;
        }
        let scene = load_session_scene_from_pb(r.scene.take(), self.state.limits.scene()).await?;
        let scene_rate = match &scene {
            convert::SessionScene::Two(s) => s.params.tick_rate_hz,
            convert::SessionScene::Three(s) => s.tick_rate_hz,
        };
        let rate = if r.tick_rate_hz == 0.0 { scene_rate } else { r.tick_rate_hz };
        if !(rate.is_finite() && (500.0..=1000.0).contains(&rate)) {
            return Err(Status::invalid_argument(format!(
                "tick_rate_hz = {}: a session runs at 500..1000 Hz",
                needlesim_core::num::num(rate)
            )));
        }
        let state = self.state.clone();
        let device = r.device_channel;
        let record = r.record;
        let s = tokio::task::spawn_blocking(move || {
            let s = match scene {
                convert::SessionScene::Two(scene) => state.create_session_in(slot, &scene, rate, device),
                convert::SessionScene::Three(scene) => state.create_session3_in(slot, &scene, rate, device),
            }?;
            if record {
                state.start_recording_or_discard(&s)?;
            }
            Ok::<_, Status>(s)
        })
        .await
        .map_err(|e| Status::internal(format!("session task: {e}")))??;
        Ok(Response::new(convert::create_session_response(&s)))
    }

    async fn list_sessions(&self, _req: Request<pb::ListSessionsRequest>) -> Result<Response<pb::ListSessionsResponse>, Status> {
        let sessions: Vec<_> = self.state.sessions.read().expect("sessions lock").values().cloned().collect();
        Ok(Response::new(convert::list_sessions_response(sessions)))
    }

    async fn get_session(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::SessionInfo>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        Ok(Response::new(convert::session_info(&s)))
    }

    async fn get_mesh(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::Mesh>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        match s.tissue.two() {
            Some(t) => Ok(Response::new(convert::mesh_to_pb(t.mesh()))),
            None => Err(ApiError::FailedPrecondition(format!("session {} is 3D: its tissue's surface comes from GetSurface", s.id)).into()),
        }
    }

    async fn get_surface(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::Surface>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        match &s.tissue {
            needlesim_session::SessionTissue::Three { model, surface } => Ok(Response::new(convert::surface_to_pb(surface, model.mesh()))),
            needlesim_session::SessionTissue::Two(_) => {
                Err(ApiError::FailedPrecondition(format!("session {} is 2D: its mesh comes from GetMesh", s.id)).into())
            }
        }
    }

    async fn get_stats(&self, req: Request<pb::GetSessionRequest>) -> Result<Response<pb::SessionStats>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        let st = s.stats();
        Ok(Response::new(convert::session_stats(&st)))
    }

    async fn close_session(&self, req: Request<pb::CloseSessionRequest>) -> Result<Response<pb::CloseSessionResponse>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        let state = self.state.clone();
        // An exercise ends with its session: its report is written (training_live.rs).
        tokio::task::spawn_blocking(move || state.close_session_blocking(&s)).await.map_err(|e| Status::internal(format!("close: {e}")))?;
        Ok(Response::new(pb::CloseSessionResponse {}))
    }
}
