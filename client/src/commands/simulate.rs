//! `simulate`: runs a scene and trajectory on the server and writes its time series (CSV or
//! JSON, 2D or 3D).

use std::fmt::Write as _;
use std::io::{IsTerminal, Write};

use anyhow::{Context, Result, anyhow};
use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;

use crate::rpc::{Conn, Role};
use crate::traj::AnyTrajectory;
use crate::view::{pose3_parts, xyz};
use crate::{Format, SimulateArgs};

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

pub(super) async fn simulate(
    c: &Conn,
    a: &SimulateArgs,
    (scene, what): (pb::SceneSource, String),
    traj: Option<AnyTrajectory>,
) -> Result<()> {
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
