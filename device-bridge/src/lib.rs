//! The haptic device bridge library: the shared-memory channel to a session's real-time thread ([`shm`]).

pub mod shm;
