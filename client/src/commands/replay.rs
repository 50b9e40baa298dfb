//! `replay`: plays a recorded MCAP file's frames back as plain lines (local: no server).

use std::time::{Duration, Instant};

use anyhow::{Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use prost::Message as _;

use super::out_line;
use crate::ReplayArgs;
use crate::view::plain_line;

const FRAME_SCHEMA: &str = "needlesim.v1.Frame";

/// Largest recording `replay` reads (it reads the file whole): 2 GiB, two million frames at
/// 1 kHz (over half an hour of a session).
pub(crate) const MAX_REPLAY_BYTES: u64 = 2 << 30;

pub(super) fn replay(a: &ReplayArgs) -> Result<()> {
    if !(a.speed.is_finite() && a.speed >= 0.0) {
        bail!("--speed {}: must be 0 (as fast as possible) or a positive factor", a.speed);
    }
    let path = a.file.display();
    // By the one rule for local files: a regular file, not a link, opened without blocking.
    let data = needlesim_localfile::read_local_bytes(&a.file, MAX_REPLAY_BYTES).map_err(|e| anyhow!("{}", e.named("recording")))?;
    if !data.starts_with(mcap::MAGIC) {
        bail!("{path} is not an MCAP file (it does not start with the MCAP magic bytes)");
    }
    let stream = mcap::MessageStream::new(&data).map_err(|e| anyhow!("{path} is not an MCAP file: {e}"))?;
    let start = Instant::now();
    let mut first_log: Option<u64> = None;
    let mut n = 0u64;
    for msg in stream {
        let msg = msg.map_err(|e| anyhow!("{path}: a damaged MCAP record after {n} frames: {e}"))?;
        let is_frame = msg.channel.message_encoding == "protobuf" && msg.channel.schema.as_ref().is_some_and(|s| s.name == FRAME_SCHEMA);
        if !is_frame {
            continue;
        }
        let frame = pb::Frame::decode(&msg.data[..])
            .map_err(|e| anyhow!("{path}: message {} (log time {} ns) is not a Frame: {e}", n + 1, msg.log_time))?;
        if a.speed > 0.0 {
            let t0 = *first_log.get_or_insert(msg.log_time);
            let due = Duration::from_secs_f64(msg.log_time.saturating_sub(t0) as f64 * 1e-9 / a.speed);
            if let Some(wait) = due.checked_sub(start.elapsed()) {
                std::thread::sleep(wait);
            }
        }
        out_line(&plain_line(&frame))?;
        n += 1;
    }
    if n == 0 {
        bail!("{path}: no {FRAME_SCHEMA} messages in the recording");
    }
    eprintln!("replayed {n} frames from {path}");
    Ok(())
}
