//! `drive`: streams a trajectory's poses to a session (Control or Control3) in real time, logs
//! what each tick answered and reports the final state and the latency.

use std::io::Write;
use std::time::{Duration, Instant};

use anyhow::{Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;

use super::{check_id, out_line, session_client};
use crate::DriveArgs;
use crate::rpc::{Conn, Role};
use crate::traj::{AnyTrajectory, header_of};
use crate::view::{contact_counts3, pose3_parts, xyz};

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

pub(super) async fn drive(c: &Conn, a: &DriveArgs, traj: AnyTrajectory) -> Result<()> {
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
