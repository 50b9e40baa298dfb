//! `watch`: a session's live frames, as a view redrawn in place or as plain lines.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use anyhow::{Result, bail};
use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;

use super::{check_id, out_line, session_client};
use crate::WatchArgs;
use crate::rpc::{Conn, Role};
use crate::view::{LiveView, plain_line};

pub(super) async fn watch(c: &Conn, a: &WatchArgs) -> Result<()> {
    check_id(&a.id)?;
    if !(a.rate == 0.0 || (30.0..=120.0).contains(&a.rate)) {
        bail!("--rate {}: frames per second must be 30..120, or 0 for every tick", a.rate);
    }
    if let Some(s) = a.seconds
        && !(s.is_finite() && s > 0.0)
    {
        bail!("--seconds {s}: must be a positive number");
    }
    let plain = a.plain || !std::io::stdout().is_terminal();
    let mut obs = pb::observe_service_client::ObserveServiceClient::new(c.channel.clone());
    let req = pb::ObserveRequest { session_id: a.id.clone(), rate_hz: a.rate, include_displacements: false };
    let mut stream = obs
        .observe(c.request(req)?)
        .await
        .map_err(|s| c.status_error(&format!("watching session {}", a.id), Role::Observer, Some(&a.id), &s))?
        .into_inner();
    let end = a.seconds.map(|s| tokio::time::Instant::now() + Duration::from_secs_f64(s));
    let mut sessions = session_client(c);
    let mut stats: Option<pb::SessionStats> = None;
    let mut last_stats = Instant::now() - Duration::from_secs(10);
    let mut view = LiveView::new();
    let mut frames = 0u64;
    let ctrl_c = tokio::signal::ctrl_c();
    tokio::pin!(ctrl_c);
    if !plain {
        print!("\x1b[?25l");
    }
    let result: Result<()> = async {
        loop {
            if a.ticks.is_some_and(|n| frames >= n) {
                return Ok(());
            }
            let next = async {
                match end {
                    Some(e) => tokio::time::timeout_at(e, stream.next()).await.ok(),
                    None => Some(stream.next().await),
                }
            };
            let item = tokio::select! {
                it = next => it,
                _ = &mut ctrl_c => return Ok(()),
            };
            let frame = match item {
                None => return Ok(()),
                Some(None) => {
                    eprintln!("the server ended the stream of session {} (closed?)", a.id);
                    return Ok(());
                }
                // The session was closed while watched (the server's NOT_FOUND "session X was
                // closed"): the end of the watch, as before, not a failure.
                Some(Some(Err(s))) if s.code() == tonic::Code::NotFound => {
                    eprintln!("{}", s.message());
                    return Ok(());
                }
                Some(Some(Err(s))) => return Err(c.status_error(&format!("watching session {}", a.id), Role::Observer, Some(&a.id), &s)),
                Some(Some(Ok(f))) => f,
            };
            frames += 1;
            if plain {
                out_line(&plain_line(&frame))?;
                continue;
            }
            if last_stats.elapsed() >= Duration::from_secs(1) {
                last_stats = Instant::now();
                let req = c.request(pb::GetSessionRequest { session_id: a.id.clone() })?;
                if let Ok(Ok(r)) = tokio::time::timeout(Duration::from_millis(300), sessions.get_stats(req)).await {
                    stats = Some(r.into_inner());
                }
            }
            let lines = LiveView::render(&a.id, &frame, stats.as_ref(), frames);
            let mut o = std::io::stdout().lock();
            o.write_all(view.draw(&lines).as_bytes())?;
            o.flush()?;
        }
    }
    .await;
    if !plain {
        print!("\x1b[?25h");
        let _ = std::io::stdout().flush();
    }
    result
}
