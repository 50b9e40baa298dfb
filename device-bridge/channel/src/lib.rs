//! `needlesim-channel`: what a session's real-time thread (server) and the device loop (bridge) share —
//! the shared-memory device channel ([`shm`]), real-time priority ([`rt`]) and the drift-free real-time
//! schedule with an injectable clock ([`schedule`]).
//!
//! Architecture invariant: no async runtime, RPC, protocol, plug-in loading or logging crate
//! (see Cargo.toml); its code runs on real-time threads.

pub mod liveness;
pub mod rt;
pub mod schedule;
pub mod shm;
pub mod spatial;
