//! needlesim-server as a library: the offline commands (solve, simulate, plan) and the real-time
//! server (sessions, gRPC services, recordings), shared by the `needlesim-server` binary and the
//! tests. The measurement pipeline is the needlesim-identify crate; bench and the identify
//! commands are in needlesim-lab.

pub mod access;
pub mod control_lease;
pub mod convert;
pub mod grpc;
pub mod grpc_identify;
pub mod grpc_plan;
/// The measurement pipeline, under the path grpc.rs names (`crate::identify::track::…`).
pub use needlesim_identify as identify;
pub mod jobs;
pub mod plan;
pub mod recording;
pub mod serve;
pub mod session;
pub mod simulate;
pub mod status;
