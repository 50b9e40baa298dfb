//! needlesim-server as a library: the gRPC service over the real-time sessions (needlesim-session)
//! and the offline runs (needlesim-offline) — the services (`grpc/`, `grpc_identify`), every
//! protocol conversion (`convert`), recordings (MCAP), the HTTP/gRPC server (`serve`), tokens,
//! offline-job permits and the one mapping of typed errors to statuses, the live training layer
//! (`training_*`: exercise sessions, roles, live score, ultrasound; issue 20); shared by the
//! `needlesim-server` binary and the tests. The measurement pipeline is needlesim-identify; the
//! `bench` and `identify` commands are needlesim-lab's.

pub mod access;
pub mod agones;
pub mod answers;
pub mod convert;
pub mod foxglove_live;
pub mod grpc;
pub mod grpc_identify;
pub mod idle;
pub mod jobs;
pub mod listener;
pub mod quota;
pub mod recording;
pub mod serve;
pub mod status;
pub mod training_convert;
pub mod training_live;
pub mod training_service;
pub mod training_ultrasound;
pub mod transport;
pub mod web_files;
