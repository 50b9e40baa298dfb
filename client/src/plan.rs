//! `needlesim plan`: an insertion plan from the server's PlanningService, with its progress, the
//! predicted tip–target errors of the plan and of aiming straight, and the trajectory CSV.

use std::io::Write;

use anyhow::{Context, Result, anyhow, bail};
use needlesim_proto::v1 as pb;
use tokio_stream::StreamExt;

use crate::PlanArgs;
use crate::rpc::{Conn, Role};

/// The scene source: an existing file is uploaded as TOML, anything else names a shipped example.
fn scene_source(spec: &str) -> Result<pb::SceneSource> {
    let path = std::path::Path::new(spec);
    if path.is_file() {
        let text = std::fs::read_to_string(path).with_context(|| format!("cannot read the scene {}", path.display()))?;
        return Ok(pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) });
    }
    Ok(pb::SceneSource { source: Some(pb::scene_source::Source::Example(spec.to_owned())) })
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
    };
    let what = format!("planning for target '{}' in {}", a.target, a.scene);
    let mut client = pb::planning_service_client::PlanningServiceClient::new(c.channel.clone());
    let mut stream = client.plan(c.request(req)?).await.map_err(|s| c.status_error(&what, Role::None, None, &s))?.into_inner();
    let mut result = None;
    while let Some(msg) = stream.next().await {
        let m = msg.map_err(|s| c.status_error(&what, Role::None, None, &s))?;
        if let Some(r) = m.result {
            result = Some(r);
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
