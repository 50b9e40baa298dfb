//! `record`: records a session on the server for a while and downloads the MCAP file.

use std::io::Write;
use std::time::Duration;

use anyhow::{Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;

use super::{check_id, out_line};
use crate::RecordArgs;
use crate::rpc::{Conn, Role};

pub(super) async fn record(c: &Conn, a: &RecordArgs) -> Result<()> {
    check_id(&a.id)?;
    if !(a.seconds.is_finite() && a.seconds > 0.0) {
        bail!("--seconds {}: must be a positive number", a.seconds);
    }
    // Fail on an unwritable output before the recording starts.
    let mut file = std::fs::File::create(&a.out).map_err(|e| anyhow!("cannot create {}: {e}", a.out.display()))?;
    let result = record_into(c, a, &mut file).await;
    if result.is_err() {
        drop(file);
        let _ = std::fs::remove_file(&a.out);
    }
    result
}

async fn record_into(c: &Conn, a: &RecordArgs, file: &mut std::fs::File) -> Result<()> {
    let id = a.id.as_str();
    let mut rec = pb::recording_service_client::RecordingServiceClient::new(c.channel.clone());
    let started = rec
        .start_recording(c.request(pb::StartRecordingRequest { session_id: id.to_owned(), include_displacements: false })?)
        .await
        .map_err(|s| c.status_error(&format!("starting a recording of session {id}"), Role::Controller, Some(id), &s))?
        .into_inner();
    eprintln!("recording session {id} to {} on the server for {} s…", started.name, a.seconds);
    tokio::select! {
        _ = tokio::time::sleep(Duration::from_secs_f64(a.seconds)) => {}
        _ = tokio::signal::ctrl_c() => eprintln!("interrupted: stopping the recording"),
    }
    let info = rec
        .stop_recording(c.request(pb::StopRecordingRequest { session_id: id.to_owned() })?)
        .await
        .map_err(|s| c.status_error(&format!("stopping the recording of session {id}"), Role::Controller, Some(id), &s))?
        .into_inner();
    let what = format!("downloading recording {}", info.name);
    let mut chunks = rec
        .download_recording(c.request(pb::DownloadRecordingRequest { name: info.name.clone() })?)
        .await
        .map_err(|s| c.status_error(&what, Role::Controller, None, &s))?
        .into_inner();
    let mut written = 0u64;
    while let Some(chunk) = chunks.next().await {
        let chunk = chunk.map_err(|s| c.status_error(&what, Role::Controller, None, &s))?;
        if chunk.offset != written {
            bail!("{what}: a chunk at offset {} arrived after {written} bytes", chunk.offset);
        }
        file.write_all(&chunk.data).map_err(|e| anyhow!("cannot write {}: {e}", a.out.display()))?;
        written += chunk.data.len() as u64;
    }
    file.flush().map_err(|e| anyhow!("cannot write {}: {e}", a.out.display()))?;
    if info.size_bytes > 0 && written != info.size_bytes {
        bail!("{what}: got {written} bytes, the server reported {}", info.size_bytes);
    }
    out_line(&format!("recorded {} frames ({written} bytes) of session {id} to {} (server: {})", info.messages, a.out.display(), info.name))
}
