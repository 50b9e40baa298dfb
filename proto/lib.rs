//! The versioned gRPC API of needlesim (`needlesim.v1`), generated from
//! proto/needlesim/v1/needlesim.proto at build time (no system protoc needed).

pub mod codec;

/// Messages and service stubs of `needlesim.v1`.
pub mod v1 {
    #![allow(clippy::all, missing_docs)]
    tonic::include_proto!("needlesim.v1");
}

/// The encoded file descriptor set of the API, for gRPC server reflection.
pub const FILE_DESCRIPTOR_SET: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/needlesim_v1_descriptor.bin"));
