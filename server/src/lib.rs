//! needlesim-server as a library: the gRPC service over the real-time sessions (needlesim-session)
//! and the offline runs (needlesim-offline) — the services (`grpc/`, `grpc_identify`), every
//! protocol conversion (`convert`), recordings (MCAP), the HTTP/gRPC server (`serve`), tokens,
//! offline-job permits and the one mapping of typed errors to statuses — plus, until they move
//! out, the measurement pipeline (`identify`) and `bench`; shared by the `needlesim-server` binary
//! and the tests.

pub mod access;
pub mod bench;
pub mod convert;
pub mod grpc;
pub mod grpc_identify;
pub mod identify;
pub mod jobs;
pub mod recording;
pub mod serve;
pub mod status;
