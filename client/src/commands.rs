//! The commands.

use std::fmt::Write as _;
use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use anyhow::{Context, Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use prost::Message as _;
use tokio_stream::StreamExt;

use crate::rpc::{Conn, Role};
use crate::traj::Trajectory;
use crate::view::{LiveView, plain_line};
use crate::{Cli, Command, CreateArgs, DriveArgs, Format, RecordArgs, ReplayArgs, SceneArgs, SessionsCmd, SimulateArgs, WatchArgs};

pub async fn run(cli: Cli) -> Result<()> {
    // Replay is local: no server involved.
    if let Command::Replay(a) = &cli.command {
        return replay(a);
    }
    // Local files are checked before the server is contacted.
    let scene = match &cli.command {
        Command::Sessions(SessionsCmd::Create(a)) => Some(scene_source(&a.scene)?),
        Command::Simulate(a) => Some(scene_source(&a.scene)?),
        _ => None,
    };
    let traj = match &cli.command {
        Command::Drive(a) => Some(Trajectory::read(&a.trajectory)?),
        Command::Simulate(SimulateArgs { trajectory: Some(p), .. }) => Some(Trajectory::read(p)?),
        Command::Simulate(a) if a.scene.scene.is_some() => {
            bail!("--scene needs --trajectory TRAJ.csv (only the shipped examples have their own)")
        }
        _ => None,
    };
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

fn scene_source(s: &SceneArgs) -> Result<(pb::SceneSource, String)> {
    if let Some(name) = &s.example {
        return Ok((pb::SceneSource { source: Some(pb::scene_source::Source::Example(name.clone())) }, format!("example '{name}'")));
    }
    let Some(path) = &s.scene else { bail!("give --example NAME or --scene FILE.toml") };
    let text = std::fs::read_to_string(path).map_err(|e| anyhow!("cannot read the scene {}: {e}", path.display()))?;
    Ok((pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) }, format!("scene {}", path.display())))
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
    out_line(&format!("scene             {} ({} nodes, {} triangles, {} Hz)", s.scene_name, s.n_nodes, s.n_triangles, s.tick_rate_hz))?;
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

async fn simulate(c: &Conn, a: &SimulateArgs, (scene, what): (pb::SceneSource, String), traj: Option<Trajectory>) -> Result<()> {
    let trajectory = traj.map(|t| t.to_pb()).unwrap_or_default();
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(c.channel.clone());
    let what = format!("simulating {what}");
    let mut stream = sim
        .simulate(c.request(pb::SimulateRequest { scene: Some(scene), trajectory, decimate: a.decimate })?)
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
    let names: Vec<String> = r.rows.first().map(|row| row.targets.iter().map(|t| t.name.clone()).collect()).unwrap_or_default();
    let mut text = String::new();
    match a.format {
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

async fn drive(c: &Conn, a: &DriveArgs, traj: Trajectory) -> Result<()> {
    check_id(&a.id)?;
    let (t0, t1) = traj.span_s();
    let span = t1 - t0;
    let id = a.id.clone();
    let what = format!("driving session {id}");
    let epoch = Instant::now();
    let now_ns = move || u64::try_from(epoch.elapsed().as_nanos()).unwrap_or(u64::MAX).max(1);
    let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest>(64);
    tx.send(pb::ControlRequest {
        session_id: id.clone(),
        base: Some(traj.pose_at(t0)),
        client_time_ns: now_ns(),
        seq: 1,
        flip_bevel: false,
        take_over: a.take_over,
    })
    .await
    .map_err(|_| anyhow!("{what}: the request stream closed"))?;
    let mut ctl = pb::control_service_client::ControlServiceClient::new(c.channel.clone());
    let mut responses = ctl
        .control(c.request(tokio_stream::wrappers::ReceiverStream::new(rx))?)
        .await
        .map_err(|s| c.status_error(&what, Role::Controller, Some(&id), &s))?
        .into_inner();
    let repeat = a.repeat;
    let sender = tokio::spawn(async move {
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
            let t = if repeat && span > 0.0 {
                t0 + el % span
            } else if el > span {
                return (seq, false);
            } else {
                t0 + el
            };
            seq += 1;
            let m = pb::ControlRequest {
                session_id: String::new(),
                base: Some(traj.pose_at(t)),
                client_time_ns: now_ns(),
                seq,
                flip_bevel: false,
                take_over: false,
            };
            if tx.send(m).await.is_err() {
                return (seq, false);
            }
        }
    });
    tokio::pin!(sender);
    let mut n_resp = 0u64;
    let mut last: Option<pb::ControlResponse> = None;
    let mut last_seq = 0u64;
    let mut latencies_ms: Vec<f64> = Vec::new();
    let mut on_response = |r: pb::ControlResponse| {
        n_resp += 1;
        if r.pose_seq != last_seq && r.client_time_ns > 0 {
            last_seq = r.pose_seq;
            latencies_ms.push(now_ns().saturating_sub(r.client_time_ns) as f64 * 1e-6);
        }
        last = Some(r);
    };
    let (sent, interrupted) = loop {
        tokio::select! {
            done = &mut sender => break done.map_err(|e| anyhow!("{what}: the sender task failed: {e}"))?,
            r = responses.next() => match r {
                Some(Ok(r)) => on_response(r),
                Some(Err(s)) => return Err(c.status_error(&what, Role::Controller, Some(&id), &s)),
                None => bail!("{what}: the server ended the control stream (session closed?)"),
            },
        }
    };
    // The responses to the last poses: a short grace period.
    let grace = tokio::time::Instant::now() + Duration::from_millis(50);
    while let Ok(Some(Ok(r))) = tokio::time::timeout_at(grace, responses.next()).await {
        on_response(r);
    }
    drop(responses);
    latencies_ms.sort_by(f64::total_cmp);
    if interrupted {
        eprintln!("interrupted");
    }
    out_line(&format!("poses sent     {sent}"))?;
    out_line(&format!("responses      {n_resp}"))?;
    if let Some(r) = &last {
        out_line(&format!("final tick     {} (t {:.3} s)", r.tick, r.time_s))?;
        out_line(&format!("final depth    {:.3} mm", r.inserted_length_m * 1e3))?;
        out_line(&format!(
            "final force    axial {:.5} N, lateral {:.5} N, torque {:.3e} N·m",
            r.force_axial_n, r.force_lateral_n, r.torque_nm
        ))?;
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
    Ok(())
}
