//! `needlesim plan`: an insertion plan from the server's PlanningService, with its progress, the
//! predicted tip–target errors of the plan and of aiming straight, and the trajectory CSV; for a
//! 3D scene also the entry point, direction, rotation schedule and clearances from the
//! structures to spare ([`Plan3Args`]).

use std::io::Write;

use anyhow::{Context, Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;

use crate::PlanArgs;
use crate::rpc::{Conn, Role};

/// The scene source: an existing file (not a directory) is uploaded as TOML, read by the one rule
/// for local files (a link, a FIFO or a device is refused, naming it), anything else names a
/// shipped example.
fn scene_source(spec: &str) -> Result<pb::SceneSource> {
    let path = std::path::Path::new(spec);
    if std::fs::symlink_metadata(path).is_ok_and(|m| !m.is_dir()) {
        let text = crate::commands::read_local(path, "scene")?;
        return Ok(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) });
    }
    Ok(pb::SceneSource { source: Some(pb::scene_source::Source::Example(spec.to_owned())) })
}

/// `needlesim plan`'s 3D options (flattened into `PlanArgs`).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct Plan3Args {
    /// 3D scenes: the entry point x,y,z in metres, on a face of the mesh's bounding box (default:
    /// the scene's 3D planning example's).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub entry_point: Option<Vec<f64>>,
    /// 3D scenes: how far the entry may move on its face to clear the structures, metres.
    #[arg(long, value_name = "M")]
    pub entry_radius_m: Option<f64>,
    /// 3D scenes: sphere regions of the scene to keep clear of (comma-separated names).
    #[arg(long, value_delimiter = ',', value_name = "REGION,...")]
    pub avoid: Option<Vec<String>>,
    /// 3D scenes: the clearance to keep from them, metres.
    #[arg(long, value_name = "M")]
    pub clearance_m: Option<f64>,
}

fn v3(v: &Option<pb::Vec3>) -> [f64; 3] {
    v.as_ref().map_or([f64::NAN; 3], |v| [v.x, v.y, v.z])
}

fn insertion3_json(i: &pb::PlannedInsertion3) -> serde_json::Value {
    serde_json::json!({
        "entry_m": v3(&i.entry_m),
        "direction": v3(&i.direction),
        "rolls": i.rolls.iter().map(|r| serde_json::json!({"depth_m": r.depth_m, "roll_rad": r.roll_rad})).collect::<Vec<_>>(),
        "depth_m": i.depth_m,
        "predicted_error_m": i.predicted_error_m,
        "tip_m": v3(&i.tip_m),
        "target_m": v3(&i.target_m),
        "aim_m": v3(&i.aim_m),
        "clearances_m": i.clearances_m,
    })
}

/// Prints (or writes) a 3D plan's result.
fn print_result3(a: &PlanArgs, r: &pb::PlanResult3) -> Result<()> {
    let (p, s) = (r.plan.clone().unwrap_or_default(), r.straight.clone().unwrap_or_default());
    let samples: Vec<[f64; 8]> = r
        .trajectory
        .iter()
        .map(|t| {
            let b = t.base.unwrap_or_default();
            let [x, y, z] = v3(&b.position_m);
            let q = b.orientation.unwrap_or_default();
            [t.t_s, x, y, z, q.w, q.x, q.y, q.z]
        })
        .collect();
    if let Some(path) = &a.trajectory_out {
        let mut text = String::from("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n");
        for [t, x, y, z, qw, qx, qy, qz] in &samples {
            text.push_str(&format!("{t},{x},{y},{z},{qw},{qx},{qy},{qz}\n"));
        }
        std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let mut out = std::io::stdout().lock();
    let min_clear = |i: &pb::PlannedInsertion3| i.clearances_m.iter().copied().fold(f64::INFINITY, f64::min);
    if a.json {
        let v = serde_json::json!({
            "target": r.target,
            "target_radius_m": r.target_radius_m,
            "target_center_m": v3(&r.target_center_m),
            "speed_mm_s": r.speed_mm_s,
            "structures": r.structures.iter().map(|s| serde_json::json!({"name": s.name, "center_m": v3(&s.center_m), "radius_m": s.radius_m})).collect::<Vec<_>>(),
            "clearance_m": r.clearance_m,
            "bevel": r.bevel,
            "plan": insertion3_json(&p),
            "straight": insertion3_json(&s),
            "trajectory": samples,
            "converged": r.converged,
            "iterations": r.iterations,
            "simulations": r.simulations,
            "wall_s": r.wall_s,
            "threads": r.threads,
        });
        writeln!(out, "{v}")?;
        return Ok(());
    }
    let names: Vec<&str> = r.structures.iter().map(|s| s.name.as_str()).collect();
    writeln!(
        out,
        "target '{}' (radius {:.2} mm), sparing [{}] by {:.2} mm",
        r.target,
        r.target_radius_m * 1e3,
        names.join(", "),
        r.clearance_m * 1e3
    )?;
    for (name, i) in [("plan", &p), ("straight", &s)] {
        let (e, d) = (v3(&i.entry_m), v3(&i.direction));
        let rolls: Vec<String> =
            i.rolls.iter().map(|r| format!("{:.1}° from {:.1} mm", r.roll_rad.to_degrees(), r.depth_m * 1e3)).collect();
        writeln!(
            out,
            "{name:<9} entry ({:.2}, {:.2}, {:.2}) mm, direction ({:.4}, {:.4}, {:.4}), rolls [{}], depth {:.2} mm: predicted tip–target error {:.3} mm, clearance {:.3} mm",
            e[0] * 1e3,
            e[1] * 1e3,
            e[2] * 1e3,
            d[0],
            d[1],
            d[2],
            rolls.join(", "),
            i.depth_m * 1e3,
            i.predicted_error_m * 1e3,
            min_clear(i) * 1e3
        )?;
    }
    let hits = p.predicted_error_m < r.target_radius_m && min_clear(&p) >= r.clearance_m;
    writeln!(
        out,
        "{} ({} simulations, {} iterations, {:.2} s on the server's {} threads){}",
        if hits {
            "the plan hits the target with the clearance kept"
        } else {
            "the plan does not reach the target with the clearance kept"
        },
        r.simulations,
        r.iterations,
        r.wall_s,
        r.threads,
        a.trajectory_out.as_ref().map(|t| format!("; trajectory written to {}", t.display())).unwrap_or_default()
    )?;
    Ok(())
}

fn v2(v: &Option<pb::Vec2>) -> [f64; 2] {
    v.as_ref().map_or([f64::NAN; 2], |v| [v.x, v.y])
}

fn insertion_json(i: &pb::PlannedInsertion) -> serde_json::Value {
    serde_json::json!({
        "entry_m": v2(&i.entry_m),
        "angle_rad": i.angle_rad,
        "depth_m": i.depth_m,
        "predicted_error_m": i.predicted_error_m,
        "tip_m": v2(&i.tip_m),
        "target_m": v2(&i.target_m),
        "aim_m": v2(&i.aim_m),
    })
}

pub async fn plan(c: &Conn, a: &PlanArgs) -> Result<()> {
    let entry = match a.entry.as_deref() {
        None => None,
        Some(&[x1, y1, x2, y2]) => Some((pb::Vec2 { x: x1, y: y1 }, pb::Vec2 { x: x2, y: y2 })),
        Some(v) => bail!("--entry takes 4 numbers x1,y1,x2,y2 (metres), found {}", v.len()),
    };
    let angles = match a.angles_deg.as_deref() {
        None => None,
        Some(&[lo, hi]) => Some((lo, hi)),
        Some(v) => bail!("--angles-deg takes 2 numbers min,max (degrees), found {}", v.len()),
    };
    let scene = scene_source(&a.scene)?;
    let req = pb::PlanRequest {
        scene: Some(scene),
        target: a.target.clone(),
        entry_from_m: entry.as_ref().map(|e| e.0),
        entry_to_m: entry.as_ref().map(|e| e.1),
        angle_min_deg: angles.map(|v| v.0),
        angle_max_deg: angles.map(|v| v.1),
        speed_mm_s: a.speed_mm_s,
        entry_point_m: match a.d3.entry_point.as_deref() {
            None => None,
            Some(&[x, y, z]) => Some(pb::Vec3 { x, y, z }),
            Some(v) => bail!("--entry-point takes 3 numbers x,y,z (metres), found {}", v.len()),
        },
        entry_radius_m: a.d3.entry_radius_m,
        avoid: a.d3.avoid.clone().unwrap_or_default(),
        clearance_m: a.d3.clearance_m,
    };
    let what = format!("planning for target '{}' in {}", a.target, a.scene);
    let mut client = pb::planning_service_client::PlanningServiceClient::new(c.channel.clone());
    let mut stream = client.plan(c.request(req)?).await.map_err(|s| c.status_error(&what, Role::None, None, &s))?.into_inner();
    let mut result = None;
    let mut result3 = None;
    while let Some(msg) = stream.next().await {
        let m = msg.map_err(|s| c.status_error(&what, Role::None, None, &s))?;
        if let Some(r) = m.result {
            result = Some(r);
        } else if let Some(r) = m.result3 {
            result3 = Some(r);
        } else if !a.json {
            eprintln!(
                "iteration {}: {} simulations, best predicted error {:.3} mm (straight aim {:.3} mm)",
                m.iteration,
                m.simulations,
                m.best_error_m * 1e3,
                m.straight_error_m * 1e3
            );
        }
    }
    if let Some(r3) = result3 {
        return print_result3(a, &r3);
    }
    let r = result.ok_or_else(|| anyhow!("{what}: the server ended the stream without a plan"))?;
    let (p, s) = (r.plan.unwrap_or_default(), r.straight.unwrap_or_default());
    if let Some(path) = &a.trajectory_out {
        let mut text = String::from("t_s,x_m,y_m,theta_rad\n");
        for t in &r.trajectory {
            let b = t.base.unwrap_or_default();
            text.push_str(&format!("{},{},{},{}\n", t.t_s, b.x_m, b.y_m, b.theta_rad));
        }
        std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let mut out = std::io::stdout().lock();
    if a.json {
        let v = serde_json::json!({
            "target": r.target,
            "target_radius_m": r.target_radius_m,
            "target_center_m": v2(&r.target_center_m),
            "speed_mm_s": r.speed_mm_s,
            "plan": insertion_json(&p),
            "straight": insertion_json(&s),
            "trajectory": r.trajectory.iter().map(|t| {
                let b = t.base.unwrap_or_default();
                [t.t_s, b.x_m, b.y_m, b.theta_rad]
            }).collect::<Vec<_>>(),
            "converged": r.converged,
            "iterations": r.iterations,
            "simulations": r.simulations,
            "wall_s": r.wall_s,
            "threads": r.threads,
        });
        writeln!(out, "{v}")?;
        return Ok(());
    }
    writeln!(out, "target '{}' (radius {:.2} mm)", r.target, r.target_radius_m * 1e3)?;
    for (name, i) in [("plan", &p), ("straight", &s)] {
        let e = v2(&i.entry_m);
        writeln!(
            out,
            "{name:<9} entry ({:.2}, {:.2}) mm, angle {:.2}°, depth {:.2} mm: predicted tip–target error {:.3} mm",
            e[0] * 1e3,
            e[1] * 1e3,
            i.angle_rad.to_degrees(),
            i.depth_m * 1e3,
            i.predicted_error_m * 1e3
        )?;
    }
    writeln!(
        out,
        "{} ({} simulations, {} iterations, {:.2} s on the server's {} threads){}",
        if p.predicted_error_m <= r.target_radius_m {
            "the plan hits the target"
        } else {
            "the plan does not reach the target within its radius"
        },
        r.simulations,
        r.iterations,
        r.wall_s,
        r.threads,
        a.trajectory_out.as_ref().map(|t| format!("; trajectory written to {}", t.display())).unwrap_or_default()
    )?;
    Ok(())
}
