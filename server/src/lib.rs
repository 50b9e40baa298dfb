//! needlesim-server as a library: the scene format, the exchange format of the validation suite,
//! the offline commands (solve, simulate, bench), and the real-time server (sessions, gRPC
//! services, recordings), shared by the `needlesim-server` binary and the tests.

pub mod access;
pub mod bench;
pub mod control_lease;
pub mod convert;
pub mod grpc;
pub mod grpc_identify;
pub mod grpc_plan;
pub mod identify;
pub mod jobs;
pub mod plan;
pub mod recording;
pub mod serve;
pub mod session;
pub mod simulate;
pub mod status;
