//! The haptic device bridge library: the shared-memory channel to a session's real-time thread ([`shm`]),
//! the gRPC remote link for a bridge on another machine ([`remote`]), the devices ([`device`]) and the safety layer that renders the server's force on them ([`render`]).

pub mod device;
#[cfg(feature = "remote")]
pub mod remote;
pub mod render;
pub mod rt;
pub mod shm;
