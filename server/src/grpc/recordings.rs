//! `RecordingService`: start and stop a session's recording (the session's record sink), list
//! and download the recordings a token opens.

use std::sync::Arc;

use needlesim_proto::v1 as pb;
use tonic::{Request, Response, Status};

use needlesim_session::Session;

use super::{Api, BoxStream, Role, ServerState, authorize, token_of};
use crate::convert;
use crate::status::ApiError;

/// Starts recording `s`: frames, the Foxglove channels, the tissue (its mesh or surface, once)
/// and, with `include_displacements`, the displacement field 10 times a second.
pub(crate) fn start_recording(state: &ServerState, s: &Arc<Session>, include_displacements: bool) -> Result<pb::RecordingInfo, Status> {
    if let Some(r) = crate::recording::SessionRecording::info_of(s) {
        return Err(Status::failed_precondition(format!("session {} is already recording to {}", s.id, r.name)));
    }
    let dir = state.data_dir.join("recordings");
    // A full directory (--max-recordings, --max-recordings-mb) is RESOURCE_EXHAUSTED naming the flag.
    let rec =
        crate::recording::Recorder::start_within(&dir, &s.id, &state.recordings_quota).map_err(|e| Status::from(ApiError::from(&e)))?;
    // The recording belongs to this session: its tokens (their digests) open it, also later.
    let owner = crate::recording::RecordingOwner {
        session_id: s.id.clone(),
        token_sha256: vec![crate::access::token_digest(&s.controller_token), crate::access::token_digest(&s.observer_token)],
    };
    if let Err(e) = crate::recording::write_owner(&dir, &rec.info().name, &owner) {
        drop(rec);
        return Err(Status::internal(format!("cannot start the recording: {e}")));
    }
    let info = convert::recording_info(&rec.info());
    let tissue = match &s.tissue {
        needlesim_session::SessionTissue::Three { model, surface } => {
            crate::recording::TissueMessage::Surface(prost::Message::encode_to_vec(&convert::surface_to_pb(surface, model.mesh())))
        }
        needlesim_session::SessionTissue::Two(t) => {
            crate::recording::TissueMessage::Mesh(prost::Message::encode_to_vec(&convert::mesh_to_pb(t.mesh())))
        }
    };
    let options = crate::recording::RecordOptions { tissue: Some(tissue), include_displacements };
    if let Err(rec) = crate::recording::SessionRecording::attach(s, rec, |r, names| convert::frame_from_record(r, names, 0), options) {
        // Another request started one in the meantime: this file is finished and left empty.
        let name = rec.info().name;
        drop(rec);
        let current = crate::recording::SessionRecording::info_of(s).map(|r| r.name).unwrap_or(name);
        return Err(Status::failed_precondition(format!("session {} is already recording to {current}", s.id)));
    }
    Ok(info)
}

/// What a request's token opens among the recordings.
enum RecordingAccess {
    /// The admin token: every recording.
    Admin,
    /// A session's token: the recordings whose owner lists its digest.
    Token(String),
    /// No token: no recording.
    Nothing,
}

impl RecordingAccess {
    /// The access of a request's token; a request without one opens nothing.
    fn of<T>(state: &ServerState, req: &Request<T>) -> Self {
        match (token_of(req), &state.admin_token_sha256) {
            (Some(tok), Some(admin)) if crate::access::digest_matches(&tok, admin) => Self::Admin,
            (Some(tok), _) => Self::Token(tok),
            (None, _) => Self::Nothing,
        }
    }

    fn opens(&self, owner: Option<&crate::recording::RecordingOwner>) -> bool {
        match self {
            Self::Admin => true,
            Self::Nothing => false,
            Self::Token(tok) => {
                owner.is_some_and(|o| o.token_sha256.iter().fold(false, |any, d| any | crate::access::digest_matches(tok, d)))
            }
        }
    }
}

#[tonic::async_trait]
impl pb::recording_service_server::RecordingService for Api {
    type DownloadRecordingStream = BoxStream<pb::RecordingChunk>;

    async fn start_recording(&self, req: Request<pb::StartRecordingRequest>) -> Result<Response<pb::RecordingInfo>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        Ok(Response::new(start_recording(&self.state, &s, req.get_ref().include_displacements)?))
    }

    async fn stop_recording(&self, req: Request<pb::StopRecordingRequest>) -> Result<Response<pb::RecordingInfo>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Controller)?;
        let rec = crate::recording::SessionRecording::detach(&s)
            .ok_or_else(|| Status::failed_precondition(format!("session {} is not recording", s.id)))?;
        let info = tokio::task::spawn_blocking(move || rec.finish())
            .await
            .map_err(|e| Status::internal(format!("recording task: {e}")))?
            .map_err(|e| Status::internal(format!("finishing the recording: {e}")))?;
        Ok(Response::new(convert::recording_info(&info)))
    }

    async fn list_recordings(&self, req: Request<pb::ListRecordingsRequest>) -> Result<Response<pb::ListRecordingsResponse>, Status> {
        let access = RecordingAccess::of(&self.state, &req);
        let dir = self.state.data_dir.join("recordings");
        let list = tokio::task::spawn_blocking(move || {
            let mut list = crate::recording::list_recordings(&dir);
            list.retain(|r| access.opens(crate::recording::read_owner(&dir, &r.name).as_ref()));
            list
        })
        .await
        .map_err(|e| Status::internal(format!("list task: {e}")))?;
        Ok(Response::new(convert::list_recordings_response(&list)))
    }

    async fn download_recording(
        &self,
        req: Request<pb::DownloadRecordingRequest>,
    ) -> Result<Response<Self::DownloadRecordingStream>, Status> {
        let access = RecordingAccess::of(&self.state, &req);
        let name = req.get_ref().name.clone();
        let dir = self.state.data_dir.join("recordings");
        // Never follows a link and never waits for a FIFO; blocking file I/O off the runtime.
        let file = tokio::task::spawn_blocking(move || {
            let file = crate::recording::open_recording(&dir, &name).map_err(|e| Status::from(ApiError::from(&e)))?;
            let owner = crate::recording::read_owner(&dir, &name);
            if !access.opens(owner.as_ref()) {
                return Err(Status::permission_denied(match owner {
                    _ if matches!(access, RecordingAccess::Nothing) => format!(
                        "missing token: recording {name:?} opens with the observer or controller token of the session that made it \
                         (or the admin token), as `authorization: Bearer <token>` metadata"
                    ),
                    Some(o) => format!(
                        "recording {name:?} belongs to session {}: it opens with that session's observer or controller token, or the admin token",
                        o.session_id
                    ),
                    None => format!("recording {name:?} has no owner file: it opens with the admin token only"),
                }));
            }
            Ok(file)
        })
        .await
        .map_err(|e| Status::internal(format!("download task: {e}")))??;
        let permit = self.state.admit_stream(None, "DownloadRecording")?;
        // Read as the client takes the chunks (issue 35): a reader that stops holds one chunk and
        // no thread.
        struct Download {
            file: tokio::fs::File,
            offset: u64,
            done: bool,
            _permit: super::StreamPermit,
        }
        let st = Download { file: tokio::fs::File::from_std(file), offset: 0, done: false, _permit: permit };
        let chunks = futures_util::stream::unfold(st, |mut st| async move {
            use tokio::io::AsyncReadExt;
            if st.done {
                return None;
            }
            let mut buf = vec![0u8; 256 * 1024];
            match st.file.read(&mut buf).await {
                Ok(0) => None,
                Ok(n) => {
                    buf.truncate(n);
                    let chunk = convert::recording_chunk(buf, st.offset);
                    st.offset += n as u64;
                    Some((Ok(chunk), st))
                }
                Err(e) => {
                    st.done = true;
                    Some((Err(Status::internal(format!("reading the recording: {e}"))), st))
                }
            }
        });
        Ok(Response::new(Box::pin(chunks)))
    }
}
