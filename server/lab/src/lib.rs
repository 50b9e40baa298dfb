//! needlesim-lab as a library: the step-time benchmark ([`bench`], with its counting allocator and
//! the helpers the server's `cargo bench` targets share), the motion suite of issue 15
//! ([`motions`]), the mesh-refinement study of issue 19 ([`refine`]) and the `identify` commands ([`identify`]), run by the `needlesim-lab` binary.

pub mod bench;
pub mod identify;
pub mod motions;
pub mod refine;
