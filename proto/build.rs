//! Compiles proto/needlesim/v1/needlesim.proto without a system protoc: protox parses it into a
//! file descriptor set (also written to OUT_DIR for gRPC reflection), tonic-prost-build generates
//! the messages and service stubs.

use std::path::PathBuf;

use prost::Message;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let proto = "needlesim/v1/needlesim.proto";
    println!("cargo:rerun-if-changed={proto}");
    println!("cargo:rerun-if-changed=build.rs");
    let fds = protox::compile([proto], ["."])?;
    let out = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::write(out.join("needlesim_v1_descriptor.bin"), fds.encode_to_vec())?;
    tonic_prost_build::configure().build_client(true).build_server(true).compile_fds(fds)?;
    Ok(())
}
