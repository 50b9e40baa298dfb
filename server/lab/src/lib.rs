//! needlesim-lab as a library: the step-time benchmark ([`bench`], with its counting allocator and
//! the helpers the server's `cargo bench` targets share) and the `identify` commands ([`identify`]),
//! run by the `needlesim-lab` binary.

pub mod bench;
pub mod identify;
