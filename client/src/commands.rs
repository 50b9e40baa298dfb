//! The commands.

use std::fmt::Write as _;
use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use anyhow::{Context, Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use prost::Message as _;
use tokio_stream::StreamExt;

use crate::rpc::{Conn, Role};
use crate::traj::{AnyTrajectory, header_of};
use crate::view::{LiveView, contact_counts3, plain_line, pose3_parts, xyz};
use crate::{Cli, Command, CreateArgs, DriveArgs, Format, RecordArgs, ReplayArgs, SceneArgs, SessionsCmd, SimulateArgs, WatchArgs};

pub async fn run(cli: Cli) -> Result<()> {
    // Replay is local: no server involved.
    if let Command::Replay(a) = &cli.command {
        return replay(a);
    }
    // Local files are checked before the server is contacted.
    let scene = match &cli.command {
        Command::Sessions(SessionsCmd::Create(a)) => Some(scene_source(&a.scene, a.mesh.as_deref())?),
        Command::Simulate(a) => Some(scene_source(&a.scene, a.mesh.as_deref())?),
        _ => None,
    };
    let traj = match &cli.command {
        Command::Drive(a) => Some(AnyTrajectory::read(&a.trajectory)?),
        Command::Simulate(SimulateArgs { trajectory: Some(p), .. }) => Some(AnyTrajectory::read(p)?),
        Command::Simulate(a) if a.scene.scene.is_some() => {
            bail!("--scene needs --trajectory TRAJ.csv (only the shipped examples have their own)")
        }
        _ => None,
    };
    // A trajectory of the wrong dimension for the scene, when the scene's is known here.
    if let (Command::Simulate(a), Some(t), Some((_, what))) = (&cli.command, &traj, &scene)
        && let Some(dim) = scene_dimension(&a.scene, a.mesh.is_some())?
        && dim != t.dimension()
    {
        let path = a.trajectory.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
        bail!(
            "--trajectory {path} is a {}D trajectory ({}) but {what} is a {dim}D scene: it needs {}",
            t.dimension(),
            header_of(t.dimension()),
            header_of(dim)
        );
    }
    let conn = Conn::connect(&cli.server, cli.token.clone(), cli.tls_ca.as_deref()).await?;
    match (cli.command, scene, traj) {
        (Command::Sessions(SessionsCmd::List { json }), ..) => sessions_list(&conn, json).await,
        (Command::Sessions(SessionsCmd::Create(a)), Some(scene), _) => sessions_create(&conn, &a, scene).await,
        (Command::Sessions(SessionsCmd::Close { id }), ..) => sessions_close(&conn, &id).await,
        (Command::Watch(a), ..) => watch(&conn, &a).await,
        (Command::Record(a), ..) => record(&conn, &a).await,
        (Command::Simulate(a), Some(scene), traj) => simulate(&conn, &a, scene, traj).await,
        (Command::Drive(a), _, Some(traj)) => drive(&conn, &a, traj).await,
        (Command::Plan(a), ..) => crate::plan::plan(&conn, &a).await,
        (Command::FlipBevel { id }, ..) => flip_bevel(&conn, &id).await,
        _ => unreachable!("every command is handled above"),
    }
}

fn out_line(line: &str) -> Result<()> {
    let mut o = std::io::stdout().lock();
    writeln!(o, "{line}")?;
    Ok(())
}

fn check_id(id: &str) -> Result<()> {
    if id.trim().is_empty() {
        bail!("the session id is empty");
    }
    Ok(())
}

fn session_client(c: &Conn) -> pb::session_service_client::SessionServiceClient<tonic::transport::Channel> {
    pb::session_service_client::SessionServiceClient::new(c.channel.clone())
}

/// The shipped 3D examples (the server's `EXAMPLES3D`); the others are 2D.
const EXAMPLES3D: [&str; 3] = ["cube-phantom-3d", "brachy-3d", "fig3-target-3d"];
/// The shipped 2D examples.
const EXAMPLES2D: [&str; 4] = ["paper-phantom", "fig3-target", "fig4-steering", "bevel-tip"];

/// The scene to send: an example, a TOML, or a 3D TOML with its Gmsh `mesh` (uploaded3d).
fn scene_source(s: &SceneArgs, mesh: Option<&std::path::Path>) -> Result<(pb::SceneSource, String)> {
    if let (Some(m), None) = (mesh, &s.scene) {
        bail!("--mesh {} goes with --scene FILE.toml (the 3D scene whose [mesh] file names it), not --example", m.display());
    }
    if let Some(name) = &s.example {
        return Ok((pb::SceneSource { source: Some(pb::scene_source::Source::Example(name.clone())) }, format!("example '{name}'")));
    }
    let Some(path) = &s.scene else { bail!("give --example NAME or --scene FILE.toml") };
    let text = std::fs::read_to_string(path).map_err(|e| anyhow!("cannot read the scene {}: {e}", path.display()))?;
    let Some(mesh) = mesh else {
        return Ok((pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) }, format!("scene {}", path.display())));
    };
    if !toml_is_3d(&text) {
        bail!("--mesh {} is for a 3D scene, but {} has no `dim = 3`", mesh.display(), path.display());
    }
    let mesh_text = std::fs::read_to_string(mesh).map_err(|e| anyhow!("cannot read the mesh {}: {e}", mesh.display()))?;
    let name = mesh
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| anyhow!("--mesh {}: the path has no file name the scene could name", mesh.display()))?;
    let upload = pb::UploadedScene3d { scene_toml: text, mesh_file_name: name.to_owned(), mesh_text };
    Ok((
        pb::SceneSource { source: Some(pb::scene_source::Source::Uploaded3d(upload)) },
        format!("scene {} with mesh {}", path.display(), mesh.display()),
    ))
}

/// Whether a scene TOML declares `dim = 3` (a top-level key line; the server decides for real).
fn toml_is_3d(text: &str) -> bool {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or_default().replace([' ', '\t'], ""))
        .take_while(|l| !l.starts_with('['))
        .any(|l| l == "dim=3")
}

/// The dimension of a scene when it can be told here (a shipped example, a TOML); None for an
/// unknown example name (the server names the examples).
fn scene_dimension(s: &SceneArgs, with_mesh: bool) -> Result<Option<u32>> {
    if let Some(name) = &s.example {
        return Ok(if EXAMPLES3D.contains(&name.as_str()) {
            Some(3)
        } else if EXAMPLES2D.contains(&name.as_str()) {
            Some(2)
        } else {
            None
        });
    }
    match &s.scene {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| anyhow!("cannot read the scene {}: {e}", p.display()))?;
            Ok(Some(if with_mesh || toml_is_3d(&text) { 3 } else { 2 }))
        }
        None => Ok(None),
    }
}

// ---------------------------------------------------------------------------------------------
// sessions

async fn sessions_list(c: &Conn, json: bool) -> Result<()> {
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

async fn sessions_create(c: &Conn, a: &CreateArgs, (scene, what): (pb::SceneSource, String)) -> Result<()> {
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

async fn sessions_close(c: &Conn, id: &str) -> Result<()> {
    check_id(id)?;
    session_client(c)
        .close_session(c.request(pb::CloseSessionRequest { session_id: id.to_owned() })?)
        .await
        .map_err(|s| c.status_error(&format!("closing session {id}"), Role::Controller, Some(id), &s))?;
    out_line(&format!("closed session {id}"))
}

async fn flip_bevel(c: &Conn, id: &str) -> Result<()> {
    check_id(id)?;
    let r = pb::control_service_client::ControlServiceClient::new(c.channel.clone())
        .flip_bevel(c.request(pb::FlipBevelRequest { session_id: id.to_owned(), ..Default::default() })?)
        .await
        .map_err(|s| c.status_error(&format!("flipping the bevel of session {id}"), Role::Controller, Some(id), &s))?
        .into_inner();
    out_line(&format!("bevel flip {} requested for session {id}", r.flips_requested))
}

// ---------------------------------------------------------------------------------------------
// watch

async fn watch(c: &Conn, a: &WatchArgs) -> Result<()> {
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

// ---------------------------------------------------------------------------------------------
// record and replay

async fn record(c: &Conn, a: &RecordArgs) -> Result<()> {
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

const FRAME_SCHEMA: &str = "needlesim.v1.Frame";

fn replay(a: &ReplayArgs) -> Result<()> {
    if !(a.speed.is_finite() && a.speed >= 0.0) {
        bail!("--speed {}: must be 0 (as fast as possible) or a positive factor", a.speed);
    }
    let path = a.file.display();
    let data = std::fs::read(&a.file).map_err(|e| anyhow!("cannot read {path}: {e}"))?;
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

// ---------------------------------------------------------------------------------------------
// simulate

fn csv_header(target_names: &[String]) -> String {
    let mut h =
        String::from("t_s,x_m,y_m,theta_rad,fx_n,fy_n,torque_nm,f_axial_n,f_lateral_n,tip_x_m,tip_y_m,inserted_m,n_stuck,n_slipping,n_tip");
    for n in target_names {
        let _ = write!(h, ",target_{n}_distance_m,target_{n}_x_m,target_{n}_y_m,target_{n}_hit");
    }
    h
}

fn csv_row(r: &pb::SeriesRow) -> String {
    let b = r.base.unwrap_or_default();
    let f = r.force_n.unwrap_or_default();
    let t = r.tip_m.unwrap_or_default();
    let mut s = format!(
        "{:.6},{},{},{},{:e},{:e},{:e},{:e},{:e},{},{},{},{},{},{}",
        r.t_s,
        b.x_m,
        b.y_m,
        b.theta_rad,
        f.x,
        f.y,
        r.torque_nm,
        r.force_axial_n,
        r.force_lateral_n,
        t.x,
        t.y,
        r.inserted_length_m,
        r.n_stuck,
        r.n_slipping,
        r.n_tip
    );
    for tg in &r.targets {
        let p = tg.position_m.unwrap_or_default();
        let _ = write!(s, ",{:e},{},{},{}", tg.distance_m, p.x, p.y, u8::from(tg.hit));
    }
    s
}

fn row_json(r: &pb::SeriesRow) -> serde_json::Value {
    let b = r.base.unwrap_or_default();
    let f = r.force_n.unwrap_or_default();
    let t = r.tip_m.unwrap_or_default();
    let mut m = serde_json::Map::new();
    for (k, v) in [
        ("t_s", r.t_s),
        ("x_m", b.x_m),
        ("y_m", b.y_m),
        ("theta_rad", b.theta_rad),
        ("fx_n", f.x),
        ("fy_n", f.y),
        ("torque_nm", r.torque_nm),
        ("f_axial_n", r.force_axial_n),
        ("f_lateral_n", r.force_lateral_n),
        ("tip_x_m", t.x),
        ("tip_y_m", t.y),
        ("inserted_m", r.inserted_length_m),
    ] {
        m.insert(k.to_owned(), serde_json::json!(v));
    }
    m.insert("n_stuck".into(), r.n_stuck.into());
    m.insert("n_slipping".into(), r.n_slipping.into());
    m.insert("n_tip".into(), r.n_tip.into());
    for tg in &r.targets {
        let p = tg.position_m.unwrap_or_default();
        let n = &tg.name;
        m.insert(format!("target_{n}_distance_m"), serde_json::json!(tg.distance_m));
        m.insert(format!("target_{n}_x_m"), serde_json::json!(p.x));
        m.insert(format!("target_{n}_y_m"), serde_json::json!(p.y));
        m.insert(format!("target_{n}_hit"), u8::from(tg.hit).into());
    }
    serde_json::Value::Object(m)
}

/// The columns of a 3D time series: those of `needlesim-server simulate` for a 3D scene.
fn csv_header3(target_names: &[String]) -> String {
    let mut h = String::from(
        "tick,t_s,x_m,y_m,z_m,qw,qx,qy,qz,fx_n,fy_n,fz_n,torque_x_nm,torque_y_nm,torque_z_nm,f_axial_n,tip_x_m,tip_y_m,tip_z_m,inserted_m,n_points,n_stuck,n_slipping,n_tip",
    );
    for n in target_names {
        let _ = write!(h, ",target_{n}_distance_m,target_{n}_x_m,target_{n}_y_m,target_{n}_z_m,target_{n}_hit");
    }
    h
}

/// The values of a 3D row in [`csv_header3`]'s order (`tick` first; the counts and hits as
/// numbers).
fn row3_values(tick: u64, r: &pb::SeriesRow, d: &pb::Tick3) -> Vec<(String, f64)> {
    let (p, q) = pose3_parts(d.base.as_ref());
    let (f, m, t) = (xyz(d.force_n.as_ref()), xyz(d.torque_nm.as_ref()), xyz(d.tip_m.as_ref()));
    let mut v: Vec<(String, f64)> = [
        ("tick", tick as f64),
        ("t_s", r.t_s),
        ("x_m", p[0]),
        ("y_m", p[1]),
        ("z_m", p[2]),
        ("qw", q[0]),
        ("qx", q[1]),
        ("qy", q[2]),
        ("qz", q[3]),
        ("fx_n", f[0]),
        ("fy_n", f[1]),
        ("fz_n", f[2]),
        ("torque_x_nm", m[0]),
        ("torque_y_nm", m[1]),
        ("torque_z_nm", m[2]),
        ("f_axial_n", d.axial_force_n),
        ("tip_x_m", t[0]),
        ("tip_y_m", t[1]),
        ("tip_z_m", t[2]),
        ("inserted_m", r.inserted_length_m),
        ("n_points", f64::from(r.n_stuck + r.n_slipping + r.n_tip)),
        ("n_stuck", f64::from(r.n_stuck)),
        ("n_slipping", f64::from(r.n_slipping)),
        ("n_tip", f64::from(r.n_tip)),
    ]
    .into_iter()
    .map(|(k, x)| (k.to_owned(), x))
    .collect();
    for tg in &d.targets {
        let c = xyz(tg.center_m.as_ref());
        let n = &tg.name;
        v.push((format!("target_{n}_distance_m"), tg.distance_m));
        v.push((format!("target_{n}_x_m"), c[0]));
        v.push((format!("target_{n}_y_m"), c[1]));
        v.push((format!("target_{n}_z_m"), c[2]));
        v.push((format!("target_{n}_hit"), f64::from(u8::from(tg.hit))));
    }
    v
}

/// A 3D CSV row (as `needlesim-server simulate` writes it: forces and torques in `{:e}`, the
/// rest shortest round-trip, counts as integers).
fn csv_row3(tick: u64, r: &pb::SeriesRow, d: &pb::Tick3) -> String {
    let vals = row3_values(tick, r, d);
    let mut s = String::new();
    for (k, (name, x)) in vals.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        let _ = match name.as_str() {
            "tick" | "n_points" | "n_stuck" | "n_slipping" | "n_tip" => write!(s, "{}", *x as u64),
            n if n.ends_with("_hit") => write!(s, "{}", *x as u64),
            "t_s" => write!(s, "{x:.6}"),
            n if n.starts_with('f') || n.starts_with("torque") || n.ends_with("_distance_m") => write!(s, "{x:e}"),
            _ => write!(s, "{x}"),
        };
    }
    s
}

async fn simulate(c: &Conn, a: &SimulateArgs, (scene, what): (pb::SceneSource, String), traj: Option<AnyTrajectory>) -> Result<()> {
    let trajectory = traj.map(|t| t.to_pb()).unwrap_or_default();
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(c.channel.clone());
    let what = format!("simulating {what}");
    let mut stream = sim
        .simulate(c.request(pb::SimulateRequest { scene: Some(scene), trajectory, decimate: a.decimate, keep_unconverged: false })?)
        .await
        .map_err(|s| c.status_error(&what, Role::None, None, &s))?
        .into_inner();
    let bar = if std::io::stderr().is_terminal() {
        indicatif::ProgressBar::new(0).with_style(
            indicatif::ProgressStyle::with_template("{spinner} simulating [{bar:40}] {pos}/{len} ticks ({percent}%, eta {eta})")
                .map_err(|e| anyhow!("progress bar: {e}"))?
                .progress_chars("=> "),
        )
    } else {
        indicatif::ProgressBar::hidden()
    };
    let mut result = None;
    // The time series arrives in chunks before the result.
    let mut rows = Vec::new();
    while let Some(ev) = stream.next().await {
        let ev = ev.map_err(|s| {
            bar.finish_and_clear();
            c.status_error(&what, Role::None, None, &s)
        })?;
        match ev.event {
            Some(pb::simulate_response::Event::Progress(p)) => {
                bar.set_length(p.ticks_total);
                bar.set_position(p.ticks_done);
            }
            Some(pb::simulate_response::Event::Series(chunk)) => rows.extend(chunk.rows),
            Some(pb::simulate_response::Event::Result(r)) => result = Some(r),
            None => {}
        }
    }
    bar.finish_and_clear();
    let mut r = result.ok_or_else(|| anyhow!("{what}: the server ended the stream without a result"))?;
    rows.append(&mut r.rows);
    r.rows = rows;
    let is_3d = r.rows.first().is_some_and(|row| row.d3.is_some());
    let names: Vec<String> = match r.rows.first() {
        Some(pb::SeriesRow { d3: Some(d), .. }) => d.targets.iter().map(|t| t.name.clone()).collect(),
        Some(row) => row.targets.iter().map(|t| t.name.clone()).collect(),
        None => vec![],
    };
    // The tick of each row: every `decimate`-th, and the last.
    let d = u64::from(a.decimate.max(1));
    let n_rows = r.rows.len();
    let tick_of = |j: usize| if j + 1 == n_rows { r.ticks.saturating_sub(1) } else { j as u64 * d };
    let mut text = String::new();
    match a.format {
        Format::Csv if is_3d => {
            text.push_str(&csv_header3(&names));
            text.push('\n');
            for (j, row) in r.rows.iter().enumerate() {
                text.push_str(&csv_row3(tick_of(j), row, row.d3.as_ref().unwrap_or(&pb::Tick3::default())));
                text.push('\n');
            }
        }
        Format::Json if is_3d => {
            let rows: Vec<serde_json::Value> = r
                .rows
                .iter()
                .enumerate()
                .map(|(j, row)| {
                    let vals = row3_values(tick_of(j), row, row.d3.as_ref().unwrap_or(&pb::Tick3::default()));
                    serde_json::Value::Object(
                        vals.into_iter()
                            .map(|(k, x)| {
                                // Counts, ticks and hits as integers, as in the CSV.
                                let count = k == "tick" || k.starts_with("n_") || k.ends_with("_hit");
                                let v = if count { serde_json::json!(x as u64) } else { serde_json::json!(x) };
                                (k, v)
                            })
                            .collect(),
                    )
                })
                .collect();
            let v = serde_json::json!({
                "dimension": 3,
                "ticks": r.ticks,
                "wall_s": r.wall_s,
                "step_p50_us": r.step_p50_us,
                "step_p99_us": r.step_p99_us,
                "decimate": d,
                "targets": names,
                "rows": rows,
            });
            text = serde_json::to_string(&v)?;
            text.push('\n');
        }
        Format::Csv => {
            text.push_str(&csv_header(&names));
            text.push('\n');
            for row in &r.rows {
                text.push_str(&csv_row(row));
                text.push('\n');
            }
        }
        Format::Json => {
            let v = serde_json::json!({
                "ticks": r.ticks,
                "wall_s": r.wall_s,
                "step_p50_us": r.step_p50_us,
                "step_p99_us": r.step_p99_us,
                "decimate": a.decimate.max(1),
                "targets": names,
                "rows": r.rows.iter().map(row_json).collect::<Vec<_>>(),
            });
            text = serde_json::to_string(&v)?;
            text.push('\n');
        }
    }
    match &a.out {
        Some(p) => std::fs::write(p, &text).with_context(|| format!("cannot write {}", p.display()))?,
        None => std::io::stdout().lock().write_all(text.as_bytes())?,
    }
    eprintln!(
        "simulated {} ticks in {:.2} s on the server (step p50 {:.1} µs, p99 {:.1} µs); {} rows{}",
        r.ticks,
        r.wall_s,
        r.step_p50_us,
        r.step_p99_us,
        r.rows.len(),
        a.out.as_ref().map(|p| format!(" written to {}", p.display())).unwrap_or_default()
    );
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// drive

fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

/// Sends a pose every millisecond until the trajectory's span has played, its end pose last (or
/// forever with `repeat`, or until Ctrl-C): `make(t_s, seq)` builds the message for trajectory
/// time `t_s`.
/// Returns the last seq sent and whether Ctrl-C ended it.
async fn send_poses<R: Send + 'static>(
    tx: tokio::sync::mpsc::Sender<R>,
    (t0, span): (f64, f64),
    repeat: bool,
    make: impl Fn(f64, u64) -> R + Send + 'static,
) -> (u64, bool) {
    let mut interval = tokio::time::interval(Duration::from_millis(1));
    interval.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let start = Instant::now();
    let mut seq = 1u64;
    let ctrl_c = tokio::signal::ctrl_c();
    tokio::pin!(ctrl_c);
    loop {
        tokio::select! {
            _ = interval.tick() => {}
            _ = &mut ctrl_c => return (seq, true),
        }
        let el = start.elapsed().as_secs_f64();
        let (t, last) = if repeat && span > 0.0 {
            (t0 + el % span, false)
        } else if el >= span {
            // The trajectory's end pose, exactly, last.
            (t0 + span, true)
        } else {
            (t0 + el, false)
        };
        seq += 1;
        if tx.send(make(t, seq)).await.is_err() || last {
            return (seq, false);
        }
    }
}

/// The header of `drive --log` for a session of `dimension`.
fn log_header(dimension: u32) -> &'static str {
    if dimension == 3 {
        "tick,t_s,x_m,y_m,z_m,qw,qx,qy,qz,fx_n,fy_n,fz_n,torque_x_nm,torque_y_nm,torque_z_nm,f_axial_n,inserted_m,n_points,n_stuck,n_slipping,n_tip,pose_seq"
    } else {
        "tick,t_s,x_m,y_m,theta_rad,fx_n,fy_n,torque_nm,f_axial_n,f_lateral_n,inserted_m,n_stuck,n_slipping,n_tip,pose_seq"
    }
}

/// A `drive --log` row: the pose the tick applied and what it answered, every value shortest
/// round-trip (exact).
fn log_row(r: &pb::ControlResponse) -> String {
    if let Some(d) = &r.d3 {
        let (p, q) = pose3_parts(d.base.as_ref());
        let (f, m) = (xyz(d.force_n.as_ref()), xyz(d.torque_nm.as_ref()));
        let (stuck, slipping, tip) = contact_counts3(d);
        return format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{stuck},{slipping},{tip},{}",
            r.tick,
            r.time_s,
            p[0],
            p[1],
            p[2],
            q[0],
            q[1],
            q[2],
            q[3],
            f[0],
            f[1],
            f[2],
            m[0],
            m[1],
            m[2],
            d.axial_force_n,
            r.inserted_length_m,
            d.contacts.len(),
            r.pose_seq
        );
    }
    let b = r.base.unwrap_or_default();
    let f = r.force_n.unwrap_or_default();
    format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        r.tick,
        r.time_s,
        b.x_m,
        b.y_m,
        b.theta_rad,
        f.x,
        f.y,
        r.torque_nm,
        r.force_axial_n,
        r.force_lateral_n,
        r.inserted_length_m,
        r.n_stuck,
        r.n_slipping,
        r.n_tip,
        r.pose_seq
    )
}

async fn drive(c: &Conn, a: &DriveArgs, traj: AnyTrajectory) -> Result<()> {
    check_id(&a.id)?;
    let id = a.id.clone();
    let what = format!("driving session {id}");
    // The session's dimension decides the stream (Control or Control3): a trajectory of the
    // other dimension is refused before anything moves.
    let info = session_client(c)
        .get_session(c.request(pb::GetSessionRequest { session_id: id.clone() })?)
        .await
        .map_err(|s| c.status_error(&what, Role::Controller, Some(&id), &s))?
        .into_inner();
    let dim = info.dimension.max(2);
    if dim != traj.dimension() {
        bail!(
            "{what}: session {id} ({}) is {dim}D and takes a {dim}D trajectory ({}), but {} is {}D ({})",
            info.scene_name,
            header_of(dim),
            a.trajectory.display(),
            traj.dimension(),
            header_of(traj.dimension())
        );
    }
    let mut log = match &a.log {
        Some(p) => {
            let mut f = std::io::BufWriter::new(std::fs::File::create(p).map_err(|e| anyhow!("cannot create {}: {e}", p.display()))?);
            writeln!(f, "{}", log_header(dim)).map_err(|e| anyhow!("cannot write {}: {e}", p.display()))?;
            Some((f, p.clone()))
        }
        None => None,
    };
    let epoch = Instant::now();
    let now_ns = move || u64::try_from(epoch.elapsed().as_nanos()).unwrap_or(u64::MAX).max(1);
    let mut ctl = pb::control_service_client::ControlServiceClient::new(c.channel.clone());
    let (repeat, take_over) = (a.repeat, a.take_over);
    let (mut responses, keep_open, sender) = match traj {
        AnyTrajectory::Two(traj) => {
            let (t0, t1) = traj.span_s();
            let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest>(64);
            tx.send(pb::ControlRequest {
                session_id: id.clone(),
                base: Some(traj.pose_at(t0)),
                client_time_ns: now_ns(),
                seq: 1,
                flip_bevel: false,
                take_over,
            })
            .await
            .map_err(|_| anyhow!("{what}: the request stream closed"))?;
            let responses = ctl
                .control(c.request(tokio_stream::wrappers::ReceiverStream::new(rx))?)
                .await
                .map_err(|s| c.status_error(&what, Role::Controller, Some(&id), &s))?
                .into_inner();
            let make = move |t: f64, seq: u64| pb::ControlRequest {
                session_id: String::new(),
                base: Some(traj.pose_at(t)),
                client_time_ns: now_ns(),
                seq,
                flip_bevel: false,
                take_over: false,
            };
            // The request side stays open until the last pose is answered (closing it ends the
            // response stream).
            let keep_open: Box<dyn std::any::Any + Send> = Box::new(tx.clone());
            (responses, keep_open, tokio::spawn(send_poses(tx, (t0, t1 - t0), repeat, make)))
        }
        AnyTrajectory::Three(traj) => {
            let (t0, t1) = traj.span_s();
            let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest3>(64);
            tx.send(pb::ControlRequest3 {
                session_id: id.clone(),
                base3: Some(traj.pose_at(t0)),
                client_time_ns: now_ns(),
                seq: 1,
                take_over,
            })
            .await
            .map_err(|_| anyhow!("{what}: the request stream closed"))?;
            let responses = ctl
                .control3(c.request(tokio_stream::wrappers::ReceiverStream::new(rx))?)
                .await
                .map_err(|s| c.status_error(&what, Role::Controller, Some(&id), &s))?
                .into_inner();
            let make = move |t: f64, seq: u64| pb::ControlRequest3 {
                session_id: String::new(),
                base3: Some(traj.pose_at(t)),
                client_time_ns: now_ns(),
                seq,
                take_over: false,
            };
            // The request side stays open until the last pose is answered (closing it ends the
            // response stream).
            let keep_open: Box<dyn std::any::Any + Send> = Box::new(tx.clone());
            (responses, keep_open, tokio::spawn(send_poses(tx, (t0, t1 - t0), repeat, make)))
        }
    };
    tokio::pin!(sender);
    let mut n_resp = 0u64;
    let mut last: Option<pb::ControlResponse> = None;
    let mut last_seq = 0u64;
    let mut latencies_ms: Vec<f64> = Vec::new();
    let mut log_error: Option<std::io::Error> = None;
    // Returns the seq of the newest pose the response's tick used.
    let mut on_response = |r: pb::ControlResponse| -> u64 {
        n_resp += 1;
        if r.pose_seq != last_seq && r.client_time_ns > 0 {
            last_seq = r.pose_seq;
            latencies_ms.push(now_ns().saturating_sub(r.client_time_ns) as f64 * 1e-6);
        }
        if let Some((f, _)) = log.as_mut()
            && log_error.is_none()
            && let Err(e) = writeln!(f, "{}", log_row(&r))
        {
            log_error = Some(e);
        }
        let used = r.pose_seq;
        last = Some(r);
        used
    };
    let mut used = 0u64;
    let (sent, interrupted) = loop {
        tokio::select! {
            done = &mut sender => break done.map_err(|e| anyhow!("{what}: the sender task failed: {e}"))?,
            r = responses.next() => match r {
                Some(Ok(r)) => {
                    // The faulted tick is the session's last: nothing more will move.
                    let faulted = r.faulted;
                    used = used.max(on_response(r));
                    if faulted {
                        break (0, false);
                    }
                }
                Some(Err(s)) => return Err(c.status_error(&what, Role::Controller, Some(&id), &s)),
                None => bail!("{what}: the server ended the control stream (session closed?)"),
            },
        }
    };
    // The responses to the last poses: until a tick has used the last pose (at most 2 s: the
    // session holds it anyway), then a short grace period.
    let until_used = tokio::time::Instant::now() + Duration::from_secs(2);
    while used < sent
        && let Ok(Some(Ok(r))) = tokio::time::timeout_at(until_used, responses.next()).await
    {
        used = used.max(on_response(r));
    }
    drop(keep_open);
    let grace = tokio::time::Instant::now() + Duration::from_millis(50);
    while let Ok(Some(Ok(r))) = tokio::time::timeout_at(grace, responses.next()).await {
        on_response(r);
    }
    drop(responses);
    if let Some((mut f, p)) = log {
        if let Some(e) = log_error {
            bail!("cannot write {}: {e}", p.display());
        }
        f.flush().map_err(|e| anyhow!("cannot write {}: {e}", p.display()))?;
    }
    if let Some(r) = last.as_ref().filter(|r| r.faulted) {
        bail!(
            "{what}: the session faulted at tick {} (t {:.3} s): {}; its force is zero and it steps no more (close it and start a new one)",
            r.tick,
            r.time_s,
            r.fault
        );
    }
    latencies_ms.sort_by(f64::total_cmp);
    if interrupted {
        eprintln!("interrupted");
    }
    out_line(&format!("poses sent     {sent}"))?;
    out_line(&format!("responses      {n_resp}"))?;
    if let Some(r) = &last {
        out_line(&format!("final tick     {} (t {:.3} s)", r.tick, r.time_s))?;
        out_line(&format!("final depth    {:.3} mm", r.inserted_length_m * 1e3))?;
        match &r.d3 {
            Some(d) => {
                let (f, m) = (xyz(d.force_n.as_ref()), xyz(d.torque_nm.as_ref()));
                let (stuck, slipping, tip) = contact_counts3(d);
                let t = xyz(d.tip_m.as_ref());
                out_line(&format!("final tip      ({:.3}, {:.3}, {:.3}) mm", t[0] * 1e3, t[1] * 1e3, t[2] * 1e3))?;
                out_line(&format!("final force    ({:.5}, {:.5}, {:.5}) N, axial {:.5} N", f[0], f[1], f[2], d.axial_force_n))?;
                out_line(&format!("final torque   ({:.3e}, {:.3e}, {:.3e}) N·m", m[0], m[1], m[2]))?;
                out_line(&format!("final contacts {} (stuck {stuck}, slipping {slipping}, tip {tip})", d.contacts.len()))?;
            }
            None => out_line(&format!(
                "final force    axial {:.5} N, lateral {:.5} N, torque {:.3e} N·m",
                r.force_axial_n, r.force_lateral_n, r.torque_nm
            ))?,
        }
    }
    if latencies_ms.is_empty() {
        out_line("latency        (no echoes)")?;
    } else {
        out_line(&format!(
            "latency        p50 {:.3} ms, p99 {:.3} ms ({} samples)",
            percentile(&latencies_ms, 0.5),
            percentile(&latencies_ms, 0.99),
            latencies_ms.len()
        ))?;
    }
    if let Some(p) = &a.log {
        out_line(&format!("log            {} ({n_resp} rows)", p.display()))?;
    }
    Ok(())
}
