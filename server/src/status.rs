//! The one mapping from the server's typed errors to gRPC statuses: every bad value the client
//! sent is INVALID_ARGUMENT naming the field, an unknown id NOT_FOUND, a size or concurrency
//! limit RESOURCE_EXHAUSTED; messages quote at most a short prefix of what the client sent
//! ([`quote`]) and are never longer than [`MAX_MESSAGE_CHARS`].
//!
//! Domain errors reach the services either typed (`SessionError`, `RecordingError`, the core's
//! `SimError`/`MeshError`/`TissueError`/`MaterialError`, `MshError`, [`SizeLimit`]) or wrapped in
//! an `anyhow::Error` chain (scene loading, trajectories, identify); [`ApiError::from_chain`] finds
//! the typed cause in the chain by downcasting, never by matching text.

use needlesim_core::StepError;
use needlesim_core::d3::TetMeshError;
use needlesim_core::mesh::MeshError;
use needlesim_core::msh::MshError;
use needlesim_core::sim::SimError;
use needlesim_core::sim3::SimError3;
use needlesim_offline::RunError;
use needlesim_offline::plan::PlanInputError;
use tonic::Status;

use crate::quota::QuotaExceeded;
use crate::recording::RecordingError;
use needlesim_session::SessionError;
use needlesim_training::run::ExerciseRunError;

pub use needlesim_scene::limit::{MAX_QUOTE_CHARS, SizeLimit, clip, quote};

/// The longest status message, in characters (gRPC metadata must stay small).
pub const MAX_MESSAGE_CHARS: usize = 1024;

/// An error of a call, by the status it answers.
#[derive(Debug, Clone)]
pub enum ApiError {
    /// A value the client sent is wrong; `field` names it (it leads the message).
    InvalidArgument { field: String, message: String },
    /// The session, recording or other named thing does not exist.
    NotFound(String),
    /// A size, memory or concurrency limit of the server.
    ResourceExhausted(String),
    /// The state of the session forbids the call.
    FailedPrecondition(String),
    /// A missing or wrong token.
    PermissionDenied(String),
    /// The server cannot serve the call now (shutting down).
    Unavailable(String),
    /// The server's fault.
    Internal(String),
}

impl ApiError {
    /// INVALID_ARGUMENT for `field`.
    pub fn invalid(field: impl Into<String>, message: impl std::fmt::Display) -> Self {
        Self::InvalidArgument { field: field.into(), message: message.to_string() }
    }

    /// The status of an error chain whose outermost context names the field (as scene loading
    /// and the converters write them): RESOURCE_EXHAUSTED when a cause is a size limit
    /// ([`SizeLimit`], a mesh over its node or triangle count), INTERNAL when the cause is the
    /// server's (a failed solve of a valid model, a thread that could not start), else
    /// INVALID_ARGUMENT naming `field` (unless the message already starts with it).
    pub fn from_chain(field: &str, e: &anyhow::Error) -> Self {
        let msg = format!("{e:#}");
        for cause in e.chain() {
            if cause.downcast_ref::<SizeLimit>().is_some() {
                return Self::ResourceExhausted(msg);
            }
            if let Some(m) = cause.downcast_ref::<MeshError>()
                && mesh_is_size_limit(m)
            {
                return Self::ResourceExhausted(msg);
            }
            if let Some(MshError::Mesh(m)) = cause.downcast_ref::<MshError>()
                && mesh_is_size_limit(m)
            {
                return Self::ResourceExhausted(msg);
            }
            if let Some(m) = cause.downcast_ref::<TetMeshError>()
                && tet_mesh_is_size_limit(m)
            {
                return Self::ResourceExhausted(msg);
            }
            if let Some(MshError::TetMesh(m)) = cause.downcast_ref::<MshError>()
                && tet_mesh_is_size_limit(m)
            {
                return Self::ResourceExhausted(msg);
            }
            if let Some(p) = cause.downcast_ref::<PlanInputError>() {
                return Self::invalid(p.field, msg);
            }
            if let Some(r) = cause.downcast_ref::<RunError>() {
                return Self::from(r);
            }
            if let Some(r) = cause.downcast_ref::<RunError<SimError3>>() {
                return Self::from(r);
            }
            if let Some(s) = cause.downcast_ref::<SessionError>() {
                return match Self::from(s) {
                    Self::InvalidArgument { .. } => Self::invalid_with_prefix(field, msg),
                    other => other,
                };
            }
        }
        Self::invalid_with_prefix(field, msg)
    }

    /// The status of an error of work that began after its input was validated (a plan): the
    /// client's when a cause says so by its type ([`PlanInputError`], a size limit), else
    /// INTERNAL. Never decided by the words of the message.
    pub fn after_validation(e: &anyhow::Error) -> Self {
        match Self::from_chain("", e) {
            ApiError::InvalidArgument { .. } if !e.chain().any(|c| c.is::<PlanInputError>()) => ApiError::Internal(format!("{e:#}")),
            other => other,
        }
    }

    /// INVALID_ARGUMENT for `field`, or for the field the message starts with when `field` is
    /// empty.
    fn invalid_with_prefix(field: &str, msg: String) -> Self {
        let field = if field.is_empty() { msg.split([':', ' ', '=']).next().unwrap_or_default() } else { field };
        Self::InvalidArgument { field: field.to_owned(), message: msg }
    }
}

/// Whether a mesh error is a size limit (RESOURCE_EXHAUSTED) rather than a bad mesh.
pub fn mesh_is_size_limit(e: &MeshError) -> bool {
    matches!(e, MeshError::TooManyNodes { .. } | MeshError::TooManyTriangles { .. })
}

/// Whether a tetrahedral mesh error is a size limit (RESOURCE_EXHAUSTED), as in 2D.
pub fn tet_mesh_is_size_limit(e: &TetMeshError) -> bool {
    matches!(e, TetMeshError::TooManyNodes { .. } | TetMeshError::TooManyTets { .. })
}

impl From<&SimError> for ApiError {
    fn from(e: &SimError) -> Self {
        match e {
            // Anything else the core finds wrong with the parameters or the pose names it.
            SimError::InvalidParams(_) | SimError::NonFinitePose { .. } => ApiError::invalid("scene", e),
            _ => ApiError::Internal(e.to_string()),
        }
    }
}

/// An error and its causes, as `anyhow` writes them with `{:#}`.
fn with_causes(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        s.push_str(": ");
        s.push_str(&c.to_string());
        cause = c.source();
    }
    s
}

impl From<&SimError3> for ApiError {
    fn from(e: &SimError3) -> Self {
        match e {
            // The scene's parameters (a target outside the mesh, a value out of range) or a pose.
            SimError3::InvalidParams(_) | SimError3::Pose { .. } | SimError3::UnknownNode { .. } => ApiError::invalid("scene", e),
            _ => ApiError::Internal(e.to_string()),
        }
    }
}

/// A scripted run's error, in either dimension (`setup`: the status of the simulation's own
/// error when it could not be built).
fn from_run_error<E: StepError>(e: &RunError<E>, setup: impl FnOnce(&E) -> ApiError) -> ApiError {
    match e {
        RunError::TooLong(_) => ApiError::ResourceExhausted(with_causes(e)),
        RunError::BadEnd { .. } | RunError::FirstPose(_) => ApiError::invalid("trajectory", with_causes(e)),
        RunError::Setup(s) => setup(s),
        // A trajectory whose interpolation is not a pose (not finite; in 3D not a unit
        // quaternion) is the caller's.
        RunError::Step { source, .. } if source.is_bad_pose() => ApiError::invalid("trajectory", with_causes(e)),
        RunError::Step { .. } | RunError::Prefetch { .. } => ApiError::Internal(with_causes(e)),
        // Well-formed input whose run does not converge: kept only when the caller asks.
        RunError::Unconverged(_) => ApiError::FailedPrecondition(with_causes(e)),
    }
}

impl From<&RunError> for ApiError {
    fn from(e: &RunError) -> Self {
        from_run_error(e, |s: &SimError| ApiError::from(s))
    }
}

impl From<&RunError<SimError3>> for ApiError {
    fn from(e: &RunError<SimError3>) -> Self {
        from_run_error(e, |s: &SimError3| ApiError::from(s))
    }
}

impl From<&SessionError> for ApiError {
    fn from(e: &SessionError) -> Self {
        match e {
            SessionError::TickRate(_) => ApiError::invalid("tick_rate_hz", e),
            SessionError::Sim(s) => ApiError::from(s),
            SessionError::Sim3(s) => ApiError::from(s),
            _ => ApiError::Internal(e.to_string()),
        }
    }
}

impl From<SessionError> for ApiError {
    fn from(e: SessionError) -> Self {
        ApiError::from(&e)
    }
}

impl From<&QuotaExceeded> for ApiError {
    /// A directory of the data directory at its `--max-…` limit (`quota.rs`).
    fn from(e: &QuotaExceeded) -> Self {
        ApiError::ResourceExhausted(e.to_string())
    }
}

impl From<&ExerciseRunError> for ApiError {
    /// A shipped exercise that does not start: its scene over the server's size limits
    /// (`--max-nodes`, `--max-triangles`) is RESOURCE_EXHAUSTED, as CreateSession's is (issue 35
    /// item 14); anything else is the server's (INTERNAL): the client only named the exercise.
    fn from(e: &ExerciseRunError) -> Self {
        match e {
            ExerciseRunError::Scene(scene) => match ApiError::from_chain("exercise", scene) {
                ApiError::ResourceExhausted(_) => ApiError::ResourceExhausted(e.to_string()),
                _ => ApiError::Internal(e.to_string()),
            },
            _ => ApiError::Internal(e.to_string()),
        }
    }
}

impl From<&RecordingError> for ApiError {
    fn from(e: &RecordingError) -> Self {
        match e {
            RecordingError::NotFound { name } | RecordingError::NotRegularFile { name } => {
                ApiError::NotFound(format!("no recording '{}'", quote(name)))
            }
            RecordingError::InvalidName { name, reason } => ApiError::invalid("name", format!("'{}': {reason}", quote(name))),
            RecordingError::Quota(_) => ApiError::ResourceExhausted(e.to_string()),
            _ => ApiError::Internal(e.to_string()),
        }
    }
}

impl From<needlesim_session::spin::SpinError> for ApiError {
    fn from(e: needlesim_session::spin::SpinError) -> Self {
        use needlesim_session::spin::SpinError;
        match e {
            SpinError::DutyCycle(_) => ApiError::invalid("duty_cycle", e),
            SpinError::Period(_) => ApiError::invalid("period_m", e),
        }
    }
}

impl From<SizeLimit> for ApiError {
    fn from(e: SizeLimit) -> Self {
        ApiError::ResourceExhausted(e.to_string())
    }
}

impl From<ApiError> for Status {
    fn from(e: ApiError) -> Self {
        // At most MAX_MESSAGE_CHARS characters, the "…" of a cut message included.
        let m = |s: String| if s.chars().count() <= MAX_MESSAGE_CHARS { s } else { clip(&s, MAX_MESSAGE_CHARS - 1) };
        match e {
            ApiError::InvalidArgument { field, message } => Status::invalid_argument(m(if message.starts_with(&field) {
                message
            } else if message.is_empty() {
                quote(&field)
            } else {
                format!("{}: {message}", quote(&field))
            })),
            ApiError::NotFound(s) => Status::not_found(m(s)),
            ApiError::ResourceExhausted(s) => Status::resource_exhausted(m(s)),
            ApiError::FailedPrecondition(s) => Status::failed_precondition(m(s)),
            ApiError::PermissionDenied(s) => Status::permission_denied(m(s)),
            ApiError::Unavailable(s) => Status::unavailable(m(s)),
            ApiError::Internal(s) => Status::internal(m(s)),
        }
    }
}

/// The status of an error chain (see [`ApiError::from_chain`]).
pub fn status_of(field: &str, e: &anyhow::Error) -> Status {
    ApiError::from_chain(field, e).into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quote_cuts_long_input_at_a_char_boundary() {
        assert_eq!(quote("abc"), "abc");
        let long = "é".repeat(100_000);
        let q = quote(&long);
        assert_eq!(q.chars().count(), MAX_QUOTE_CHARS + 1);
        assert!(q.ends_with('…'));
    }

    #[test]
    fn chains_map_by_type_not_text() {
        let size = anyhow::Error::new(MeshError::TooManyNodes { n_nodes: 10, max_nodes: 5 }).context("mesh");
        assert_eq!(Status::from(ApiError::from_chain("scene", &size)).code(), tonic::Code::ResourceExhausted);
        let bad = anyhow::Error::new(MeshError::Empty).context("mesh");
        let st = Status::from(ApiError::from_chain("scene", &bad));
        assert_eq!(st.code(), tonic::Code::InvalidArgument);
        assert!(st.message().starts_with("scene: mesh: "), "{}", st.message());
        // The words of a size error in a message are not a size error.
        let text = anyhow::anyhow!("name 'over the limit' is not a region");
        assert_eq!(Status::from(ApiError::from_chain("scene", &text)).code(), tonic::Code::InvalidArgument);
        let lim = SizeLimit { what: "x".into(), amount: 2.0, limit: 1, unit: "MiB", hint: String::new() };
        let wrapped = anyhow::Error::new(lim).context("scene.scene_toml");
        assert_eq!(Status::from(ApiError::from_chain("scene", &wrapped)).code(), tonic::Code::ResourceExhausted);
        let sim = anyhow::Error::new(SessionError::Sim(SimError::InvalidParams("max_base_step_m = -1".into())));
        assert_eq!(Status::from(ApiError::from_chain("scene", &sim)).code(), tonic::Code::InvalidArgument);
    }

    /// Noticed in stop 41: a 3D plan whose candidate run did not converge ended INTERNAL (the
    /// chain's 3D run error was not read), where 2D's is FAILED_PRECONDITION.
    #[test]
    fn an_unconverged_run_after_validation_is_failed_precondition_in_both_dimensions() {
        let tick = needlesim_offline::UnconvergedTick { tick: 7, t_s: 0.007, why: needlesim_core::sim::Unconverged::ActiveSetCap };
        let two = anyhow::Error::new(RunError::<SimError>::Unconverged(tick)).context("candidate 3");
        let three = anyhow::Error::new(RunError::<SimError3>::Unconverged(tick)).context("candidate 3");
        for e in [two, three] {
            let st = Status::from(ApiError::after_validation(&e));
            assert_eq!(st.code(), tonic::Code::FailedPrecondition, "{}", st.message());
            assert!(st.message().contains("stopped at tick 7"), "{}", st.message());
        }
    }

    #[test]
    fn messages_are_bounded() {
        let st = Status::from(ApiError::Internal("x".repeat(1 << 20)));
        assert!(st.message().chars().count() <= MAX_MESSAGE_CHARS);
    }

    #[test]
    fn issue_35_messages_are_at_most_the_limit_with_the_ellipsis() {
        for n in [MAX_MESSAGE_CHARS - 1, MAX_MESSAGE_CHARS, MAX_MESSAGE_CHARS + 1, 1 << 20] {
            let st = Status::from(ApiError::Internal("é".repeat(n)));
            assert_eq!(st.message().chars().count(), n.min(MAX_MESSAGE_CHARS), "{n}");
            assert_eq!(st.message().ends_with('…'), n > MAX_MESSAGE_CHARS, "{n}");
            // With the field's prefix.
            let st = Status::from(ApiError::invalid("scene", "x".repeat(n)));
            assert!(st.message().chars().count() <= MAX_MESSAGE_CHARS, "{n}");
        }
    }

    #[test]
    fn issue_35_a_tet_mesh_over_its_limits_is_resource_exhausted() {
        for e in [TetMeshError::TooManyNodes { n_nodes: 10, max_nodes: 5 }, TetMeshError::TooManyTets { n_tets: 10, max_tets: 5 }] {
            let chain = anyhow::Error::new(e.clone()).context("mesh");
            assert_eq!(Status::from(ApiError::from_chain("scene", &chain)).code(), tonic::Code::ResourceExhausted);
            let chain = anyhow::Error::new(MshError::TetMesh(e)).context("mesh.file");
            assert_eq!(Status::from(ApiError::from_chain("scene", &chain)).code(), tonic::Code::ResourceExhausted);
        }
        let bad = anyhow::Error::new(TetMeshError::Empty).context("mesh");
        assert_eq!(Status::from(ApiError::from_chain("scene", &bad)).code(), tonic::Code::InvalidArgument);
    }
}
