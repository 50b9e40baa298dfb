//! The haptic device bridge library: the devices ([`device`]), the safety layer that renders the server's force on them ([`render`])
//! and the gRPC remote link for a bridge on another machine ([`remote`]). The shared-memory channel to a session's
//! real-time thread, real-time priority and the device loop's schedule are in the `needlesim-channel` crate.

pub mod device;
pub mod remote;
pub mod render;
