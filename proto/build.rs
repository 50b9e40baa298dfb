//! Compiles every `proto/needlesim/v1/*.proto` without a system protoc: protox parses them into
//! one file descriptor set (also written to OUT_DIR for gRPC reflection), tonic-prost-build
//! generates the messages and service stubs of the `needlesim.v1` package, whose services decode
//! through `codec.rs` (`BoundedCodec`).

use std::path::PathBuf;

use prost::Message;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = "needlesim/v1";
    println!("cargo:rerun-if-changed={dir}");
    println!("cargo:rerun-if-changed=build.rs");
    let mut protos: Vec<String> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".proto"))
        .map(|name| format!("{dir}/{name}"))
        .collect();
    protos.sort();
    for p in &protos {
        println!("cargo:rerun-if-changed={p}");
    }
    let fds = protox::compile(&protos, ["."])?;
    let out = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::write(out.join("needlesim_v1_descriptor.bin"), fds.encode_to_vec())?;
    // Every service decodes through `codec.rs`: the decoded size is bounded before prost allocates.
    tonic_prost_build::configure().build_client(true).build_server(true).codec_path("crate::codec::BoundedCodec").compile_fds(fds)?;
    Ok(())
}
