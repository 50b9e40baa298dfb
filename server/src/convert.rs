//! Conversions between the protocol (`needlesim.v1`) and the core and session types: the one
//! place where protocol types meet the rest of the server. Errors name the offending field, as
//! the gRPC layer returns them as INVALID_ARGUMENT.

use std::collections::BTreeMap;
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use needlesim_core::compliance::TissueModel;
use needlesim_core::sim::{SimParams, StepOutput, TargetParams};
use needlesim_core::{BasePose, Material, MaterialMap, Mesh, NeedleShape, PlaneModel, RegionNeedleParams, RigidNeedle};
use needlesim_proto::v1 as pb;

use crate::status::quote;
use needlesim_scene::{Scene, SceneLimits, Trajectory};

/// The needle working-set capacity of an uploaded scene.
const UPLOADED_MAX_NEEDLE_NODES: usize = 128;
use crate::session::TickRecord;

/// A proto pose to a core pose (finite-ness is checked by the caller or the simulation).
pub fn pose_from_pb(p: &pb::Pose2) -> BasePose {
    BasePose::new(p.x_m, p.y_m, p.theta_rad)
}

pub fn pose_to_pb(p: &BasePose) -> pb::Pose2 {
    pb::Pose2 { x_m: p.x_m, y_m: p.y_m, theta_rad: p.theta_rad }
}

fn v2(a: [f64; 2]) -> Option<pb::Vec2> {
    Some(pb::Vec2 { x: a[0], y: a[1] })
}

/// The state of target `i` (named from `target_names`).
fn target_state(target_names: &[String], i: usize, position_m: [f64; 2], distance_m: f64, hit: bool) -> pb::TargetState {
    pb::TargetState { name: target_names.get(i).cloned().unwrap_or_default(), position_m: v2(position_m), distance_m, hit }
}

/// A tick record to a frame; `targets` names the targets, `missed` the ticks the receiver missed.
pub fn frame_from_record(r: &TickRecord, target_names: &[String], missed_ticks: u64) -> pb::Frame {
    pb::Frame {
        tick: r.tick,
        time_s: r.time_s,
        base: Some(pose_to_pb(&r.base)),
        force_n: v2(r.force_n),
        torque_nm: r.torque_nm,
        force_axial_n: r.force_axial_n,
        force_lateral_n: r.force_lateral_n,
        tip_m: v2(r.tip_m),
        inserted_length_m: r.inserted_length_m,
        needle_nodes: r
            .nodes()
            .iter()
            .map(|n| pb::NeedleNode {
                node: n.node,
                state: match n.state {
                    0 => pb::NodeState::Stuck,
                    1 => pb::NodeState::Slipping,
                    _ => pb::NodeState::Tip,
                } as i32,
                position_m: v2(n.position_m),
                force_n: v2(n.force_n),
            })
            .collect(),
        targets: r.targets().iter().enumerate().map(|(i, t)| target_state(target_names, i, t.position_m, t.distance_m, t.hit)).collect(),
        node_displacement_m: vec![],
        missed_ticks,
        compute_us: r.compute_ns as f64 / 1e3,
        stiffness: r.stiffness.to_vec(),
        needle_shape_m: r.shape().iter().filter_map(|p| v2(*p)).collect(),
        bevel_side: r.bevel_side,
        faulted: r.fault.is_some(),
        fault: r.fault.map(|f| f.message()).unwrap_or_default(),
    }
}

/// A tick record to a controller response.
pub fn control_response(r: &TickRecord) -> pb::ControlResponse {
    pb::ControlResponse {
        tick: r.tick,
        time_s: r.time_s,
        force_n: v2(r.force_n),
        torque_nm: r.torque_nm,
        force_axial_n: r.force_axial_n,
        force_lateral_n: r.force_lateral_n,
        base: Some(pose_to_pb(&r.base)),
        tip_m: v2(r.tip_m),
        inserted_length_m: r.inserted_length_m,
        n_stuck: r.n_stuck,
        n_slipping: r.n_slipping,
        n_tip: r.n_tip,
        pose_seq: r.pose_seq,
        client_time_ns: r.client_time_ns,
        stiffness: r.stiffness.to_vec(),
        needle_shape_m: r.shape().iter().filter_map(|p| v2(*p)).collect(),
        bevel_side: r.bevel_side,
        faulted: r.fault.is_some(),
        fault: r.fault.map(|f| f.message()).unwrap_or_default(),
    }
}

/// A step output to a series row of the offline simulation.
pub fn series_row(o: &StepOutput, t0_s: f64, target_names: &[String]) -> pb::SeriesRow {
    pb::SeriesRow {
        t_s: t0_s + o.time_s,
        base: Some(pose_to_pb(&o.base)),
        force_n: v2(o.force_n),
        torque_nm: o.torque_nm,
        force_axial_n: o.force_axial_n,
        force_lateral_n: o.force_lateral_n,
        tip_m: v2(o.tip_m),
        inserted_length_m: o.inserted_length_m,
        n_stuck: o.n_stuck as u32,
        n_slipping: o.n_slipping as u32,
        n_tip: o.n_tip as u32,
        targets: o.targets.iter().enumerate().map(|(i, t)| target_state(target_names, i, t.position_m, t.distance_m, t.hit)).collect(),
    }
}

/// The reference mesh of a tissue, for renderers.
pub fn mesh_to_pb(m: &Mesh) -> pb::Mesh {
    pb::Mesh {
        node_xy_m: m.nodes_m().iter().flat_map(|p| [p[0], p[1]]).collect(),
        triangle_nodes: m.triangles().iter().flat_map(|t| t.map(|i| i as u32)).collect(),
        triangle_region: m.region_of_tri().iter().map(|&r| r as u32).collect(),
        region_names: m.region_names().to_vec(),
    }
}

/// A trajectory from samples (errors name the sample).
pub fn trajectory_from_pb(samples: &[pb::TrajectorySample]) -> Result<Trajectory> {
    let mut out: Vec<(f64, needlesim_scene::Pose2)> = Vec::with_capacity(samples.len());
    for (i, s) in samples.iter().enumerate() {
        let base = s.base.as_ref().with_context(|| format!("trajectory[{i}].base is missing"))?;
        let p = pose_from_pb(base);
        if !(s.t_s.is_finite() && p.is_finite()) {
            bail!("trajectory[{i}]: t_s and base must be finite numbers");
        }
        if let Some((t_prev, _)) = out.last()
            && s.t_s <= *t_prev
        {
            bail!("trajectory[{i}].t_s = {} does not increase (previous {t_prev})", s.t_s);
        }
        out.push((s.t_s, needlesim_scene::pose2(p)));
    }
    if out.is_empty() {
        bail!("trajectory is empty");
    }
    Ok(Trajectory::from_samples(out))
}

/// A scene from its source. Examples and TOML go through the scene loader; uploaded scenes are
/// checked field by field.
pub fn scene_from_pb(src: Option<&pb::SceneSource>, limits: &SceneLimits) -> Result<Scene> {
    let src = src.and_then(|s| s.source.as_ref()).context("scene: one of example, scene_toml or uploaded is required")?;
    match src {
        pb::scene_source::Source::Example(name) => {
            if !needlesim_scene::EXAMPLES.iter().any(|e| e.0 == name) {
                let names: Vec<&str> = needlesim_scene::EXAMPLES.iter().map(|e| e.0).collect();
                bail!("scene.example: '{}' is not a shipped example ({})", quote(name), names.join(", "));
            }
            needlesim_scene::load_scene(name, limits)
        }
        pb::scene_source::Source::SceneToml(text) => {
            needlesim_scene::parse_scene(text, std::path::Path::new("/nonexistent"), limits).context("scene.scene_toml")
        }
        pb::scene_source::Source::Uploaded(u) => uploaded_scene(u, limits),
    }
}

fn uploaded_scene(u: &pb::UploadedScene, scene_limits: &SceneLimits) -> Result<Scene> {
    let limits = &scene_limits.mesh;
    let mesh = u.mesh.as_ref().context("scene.uploaded.mesh is missing")?;
    if mesh.node_xy_m.len() % 2 != 0 {
        bail!("scene.uploaded.mesh.node_xy_m has {} values: it must hold x, y pairs", mesh.node_xy_m.len());
    }
    if mesh.triangle_nodes.len() % 3 != 0 {
        bail!("scene.uploaded.mesh.triangle_nodes has {} values: it must hold triples", mesh.triangle_nodes.len());
    }
    let n_nodes = mesh.node_xy_m.len() / 2;
    if n_nodes > limits.max_nodes {
        let e = needlesim_core::MeshError::TooManyNodes { n_nodes, max_nodes: limits.max_nodes };
        return Err(anyhow::Error::new(e).context("scene.uploaded.mesh"));
    }
    let n_tri = mesh.triangle_nodes.len() / 3;
    let region_of_tri: Vec<usize> = if mesh.triangle_region.is_empty() {
        vec![0; n_tri]
    } else if mesh.triangle_region.len() != n_tri {
        bail!("scene.uploaded.mesh.triangle_region has {} entries for {n_tri} triangles", mesh.triangle_region.len());
    } else {
        mesh.triangle_region.iter().map(|&r| r as usize).collect()
    };
    if u.regions.is_empty() {
        bail!("scene.uploaded.regions: at least one region is needed");
    }
    if let Some(&r) = region_of_tri.iter().find(|&&r| r >= u.regions.len()) {
        bail!("scene.uploaded.mesh.triangle_region names region {r}, but {} regions were given", u.regions.len());
    }
    let nodes: Vec<[f64; 2]> = mesh.node_xy_m.chunks(2).map(|c| [c[0], c[1]]).collect();
    let tris: Vec<[usize; 3]> = mesh.triangle_nodes.chunks(3).map(|c| [c[0] as usize, c[1] as usize, c[2] as usize]).collect();
    let names: Vec<String> = u.regions.iter().map(|r| r.name.clone()).collect();
    let m = Mesh::with_regions(nodes, tris, region_of_tri, names, BTreeMap::new(), limits).context("scene.uploaded.mesh")?;
    let plane = match u.plane.as_str() {
        "" | "stress" => PlaneModel::Stress { thickness_m: if u.thickness_m == 0.0 { 0.01 } else { u.thickness_m } },
        "strain" => PlaneModel::Strain { thickness_m: if u.thickness_m == 0.0 { 1.0 } else { u.thickness_m } },
        p => bail!("scene.uploaded.plane must be \"stress\" or \"strain\", found \"{}\"", quote(p)),
    };
    let materials: Vec<Material> =
        u.regions.iter().map(|r| Material { young_modulus_pa: r.young_modulus_pa, poisson_ratio: r.poisson_ratio }).collect();
    let mats = MaterialMap::per_region(&m, &materials, plane).context("scene.uploaded.regions")?;
    let fixed: Vec<usize> = u.fixed_nodes.iter().map(|&n| n as usize).collect();
    if let Some(&n) = fixed.iter().find(|&&n| n >= m.n_nodes()) {
        bail!("scene.uploaded.fixed_nodes names node {n}, but the mesh has {} nodes", m.n_nodes());
    }
    let mean_edge = needlesim_scene::mean_edge_m(&m);
    needlesim_scene::check_session_memory(m.n_nodes(), UPLOADED_MAX_NEEDLE_NODES, scene_limits).context("scene.uploaded.mesh")?;
    let tissue = Arc::new(TissueModel::new(m, mats, &fixed).context("scene.uploaded (tissue model)")?);
    let d = RegionNeedleParams::default();
    let or = |v: f64, dflt: f64| if v == 0.0 { dflt } else { v };
    let base = u.needle_base.as_ref().context("scene.uploaded.needle_base is missing")?;
    if !pose_from_pb(base).is_finite() {
        bail!("scene.uploaded.needle_base ({}, {}, {}) is not finite", base.x_m, base.y_m, base.theta_rad);
    }
    let params = SimParams {
        needle: NeedleShape::Rigid(RigidNeedle { length_m: or(u.needle_length_m, 0.1) }),
        initial_pose: pose_from_pb(base),
        capture_radius_m: or(u.capture_radius_m, 0.5 * mean_edge),
        max_needle_nodes: UPLOADED_MAX_NEEDLE_NODES,
        regions: u
            .regions
            .iter()
            .map(|r| RegionNeedleParams {
                friction_n_per_m: or(r.friction_n_per_m, d.friction_n_per_m),
                static_friction_ratio: or(r.static_friction_ratio, d.static_friction_ratio),
                tip_peak_ratio: or(r.tip_peak_ratio, d.tip_peak_ratio),
                tip_peak_width_m: or(r.tip_peak_width_m, d.tip_peak_width_m),
                puncture_force_n: or(r.puncture_force_n, d.puncture_force_n),
                cutting_force_n: or(r.cutting_force_n, d.cutting_force_n),
            })
            .collect(),
        targets: u
            .targets
            .iter()
            .map(|t| TargetParams {
                name: t.name.clone(),
                center_m: t.center_m.as_ref().map_or([f64::NAN; 2], |c| [c.x, c.y]),
                radius_m: t.radius_m,
            })
            .collect(),
        tick_rate_hz: or(u.tick_rate_hz, 1000.0),
        max_base_step_m: 0.002,
        max_base_step_rad: 0.05,
        max_active_set_iterations: 12,
        lookahead_m: 0.01,
    };
    // Validate the needle parameters now, so the error reaches the caller as INVALID_ARGUMENT.
    needlesim_core::Simulation::new(tissue.clone(), params.clone()).context("scene.uploaded")?;
    Ok(Scene {
        name: if u.name.is_empty() { "uploaded".to_owned() } else { u.name.clone() },
        tissue,
        params,
        fixed_nodes: fixed,
        target_names: u.targets.iter().map(|t| t.name.clone()).collect(),
        example_trajectory: None,
    })
}
