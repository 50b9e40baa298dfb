//! `sessions list`, `sessions create` and `sessions close`.

use std::fmt::Write as _;

use anyhow::{Result, anyhow};
use needlesim_proto::v1 as pb;

use super::{check_id, out_line, session_client};
use crate::CreateArgs;
use crate::rpc::{Conn, Role};

pub(super) async fn sessions_list(c: &Conn, json: bool) -> Result<()> {
    let r = session_client(c)
        .list_sessions(c.request(pb::ListSessionsRequest {})?)
        .await
        .map_err(|s| c.status_error("listing sessions", Role::None, None, &s))?
        .into_inner();
    if json {
        let v: Vec<serde_json::Value> = r.sessions.iter().map(session_json).collect();
        return out_line(&serde_json::to_string_pretty(&serde_json::Value::Array(v))?);
    }
    let mut rows = vec![["id", "scene", "nodes", "rate", "tick", "observers", "recording"].map(String::from).to_vec()];
    for s in &r.sessions {
        rows.push(vec![
            s.session_id.clone(),
            s.scene_name.clone(),
            s.n_nodes.to_string(),
            format!("{} Hz", s.tick_rate_hz),
            s.tick.to_string(),
            s.n_observers.to_string(),
            if s.recording.is_empty() { "-".to_owned() } else { s.recording.clone() },
        ]);
    }
    let widths: Vec<usize> = (0..7).map(|i| rows.iter().map(|r| r[i].chars().count()).max().unwrap_or(0)).collect();
    for r in &rows {
        let mut line = String::new();
        for (i, cell) in r.iter().enumerate() {
            if i + 1 == r.len() {
                line.push_str(cell);
            } else {
                let _ = write!(line, "{cell:<w$}  ", w = widths[i]);
            }
        }
        out_line(line.trim_end())?;
    }
    if r.sessions.is_empty() {
        eprintln!("(no sessions on {})", c.url);
    }
    Ok(())
}

fn session_json(s: &pb::SessionInfo) -> serde_json::Value {
    serde_json::json!({
        "session_id": s.session_id,
        "scene": s.scene_name,
        "n_nodes": s.n_nodes,
        "n_triangles": s.n_triangles,
        "tick_rate_hz": s.tick_rate_hz,
        "tick": s.tick,
        "n_observers": s.n_observers,
        "recording": s.recording,
        "targets": s.target_names,
        "created_unix_ms": s.created_unix_ms,
        "device_channel_path": s.device_channel_path,
        "device_stale": s.device_stale,
        "dimension": s.dimension.max(2),
        "n_tetrahedra": s.n_tetrahedra,
    })
}

pub(super) async fn sessions_create(c: &Conn, a: &CreateArgs, (scene, what): (pb::SceneSource, String)) -> Result<()> {
    let r = session_client(c)
        .create_session(c.request(pb::CreateSessionRequest {
            scene: Some(scene),
            tick_rate_hz: a.rate.unwrap_or(0.0),
            record: a.record,
            device_channel: a.device_channel,
        })?)
        .await
        .map_err(|s| c.status_error(&format!("creating a session from {what}"), Role::None, None, &s))?
        .into_inner();
    let s = r.session.ok_or_else(|| anyhow!("the server answered without the session"))?;
    if a.json {
        let mut v = session_json(&s);
        v["controller_token"] = r.controller_token.into();
        v["observer_token"] = r.observer_token.into();
        v["server"] = c.url.clone().into();
        return out_line(&serde_json::to_string_pretty(&v)?);
    }
    out_line(&format!("session           {}", s.session_id))?;
    if s.dimension == 3 {
        out_line(&format!(
            "scene             {} (3D: {} nodes, {} tetrahedra, {} Hz)",
            s.scene_name, s.n_nodes, s.n_tetrahedra, s.tick_rate_hz
        ))?;
    } else {
        out_line(&format!("scene             {} ({} nodes, {} triangles, {} Hz)", s.scene_name, s.n_nodes, s.n_triangles, s.tick_rate_hz))?;
    }
    out_line(&format!("controller token  {}", r.controller_token))?;
    out_line(&format!("observer token    {}", r.observer_token))?;
    if !s.recording.is_empty() {
        out_line(&format!("recording         {}", s.recording))?;
    }
    if !s.device_channel_path.is_empty() {
        out_line(&format!("device channel    {}", s.device_channel_path))?;
    }
    Ok(())
}

pub(super) async fn sessions_close(c: &Conn, id: &str) -> Result<()> {
    check_id(id)?;
    session_client(c)
        .close_session(c.request(pb::CloseSessionRequest { session_id: id.to_owned() })?)
        .await
        .map_err(|s| c.status_error(&format!("closing session {id}"), Role::Controller, Some(id), &s))?;
    out_line(&format!("closed session {id}"))
}
