//! Conversions between the protocol (`needlesim.v1`) and the core, session, offline and recording
//! types: the one place where protocol messages are built and read field by field (the services
//! only name their request and response types). Errors name the offending field, as the gRPC
//! layer returns them as INVALID_ARGUMENT.

use std::collections::BTreeMap;
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use needlesim_core::num::num;
use needlesim_core::sim::{ContactModel, SimParams, StepOutput, TargetParams};
use needlesim_core::{BasePose, Material, MaterialMap, Mesh, NeedleShape, PlaneModel, RegionNeedleParams, RigidNeedle};
use needlesim_proto::v1 as pb;

use crate::status::quote;
use needlesim_core::sim3::BasePose3;
use needlesim_scene::{Scene, Scene3d, SceneFiles, SceneLimits, Trajectory};

/// The needle working-set capacity of an uploaded scene.
const UPLOADED_MAX_NEEDLE_NODES: usize = 128;
use needlesim_offline::plan::{Insertion, Plan, PlanProgress, PlanRequest};
use needlesim_session::{Session, StatsSnapshot, TickRecord};

use crate::recording::{RecordingInfo, SessionRecording};
use crate::status::ApiError;

/// A pose a client sent in `field`: present and finite (INVALID_ARGUMENT naming the field).
pub fn checked_pose_from_pb(p: Option<&pb::Pose2>, field: &str) -> Result<BasePose, ApiError> {
    let p = p.ok_or_else(|| ApiError::invalid(field, format!("{field} is missing")))?;
    let pose = pose_from_pb(p);
    if !pose.is_finite() {
        return Err(ApiError::invalid(field, format!("{field} ({}, {}, {}) is not finite", num(p.x_m), num(p.y_m), num(p.theta_rad))));
    }
    Ok(pose)
}

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
                material_point: n.n_contact > 1,
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
        d3: tick3(r, target_names),
        surface_displacement_m: vec![],
    }
}

fn v3(a: [f64; 3]) -> Option<pb::Vec3> {
    Some(pb::Vec3 { x: a[0], y: a[1], z: a[2] })
}

/// A 3D pose to the protocol's.
pub fn pose3_to_pb(position_m: [f64; 3], wxyz: [f64; 4]) -> pb::Pose3 {
    let [w, x, y, z] = wxyz;
    pb::Pose3 { position_m: v3(position_m), orientation: Some(pb::Quaternion { w, x, y, z }) }
}

/// The 3D part of a record (None for a 2D record).
fn tick3(r: &TickRecord, target_names: &[String]) -> Option<pb::Tick3> {
    if r.dimension != 3 {
        return None;
    }
    let d = &r.d3;
    Some(pb::Tick3 {
        base: Some(pose3_to_pb(d.position_m, d.orientation_wxyz)),
        force_n: v3(d.force_n),
        torque_nm: v3(d.torque_nm),
        axial_force_n: d.axial_force_n,
        tip_m: v3(d.tip_m),
        needle_shape_m: vec![
            pb::Vec3 { x: d.position_m[0], y: d.position_m[1], z: d.position_m[2] },
            pb::Vec3 { x: d.tip_m[0], y: d.tip_m[1], z: d.tip_m[2] },
        ],
        contacts: d
            .contacts()
            .iter()
            .map(|c| pb::Contact3 {
                state: match c.state {
                    0 => pb::NodeState::Stuck,
                    1 => pb::NodeState::Slipping,
                    _ => pb::NodeState::Tip,
                } as i32,
                position_m: v3(c.x_m),
                reference_m: v3(c.x_ref_m),
                force_n: v3(c.force_n),
            })
            .collect(),
        targets: d
            .targets()
            .iter()
            .map(|t| pb::TargetSphere {
                name: target_names.get(t.name_idx as usize).cloned().unwrap_or_default(),
                center_m: v3(t.centre_m),
                radius_m: t.radius_m,
                distance_m: t.distance_m,
                hit: t.hit,
                missed: t.missed,
            })
            .collect(),
        stiffness: d.stiffness.iter().flatten().copied().collect(),
    })
}

/// A 2D pose a client sent in `base` for a session of `dimension`: present and finite
/// (INVALID_ARGUMENT naming `base`, also when the session is 3D).
pub fn checked_pose2_for(base: Option<&pb::Pose2>, dimension: u8) -> Result<ClientPose, ApiError> {
    if dimension == 3 {
        return Err(ApiError::invalid(
            "base",
            "this is a 3D session: send its poses through Control3/SetPose3 (base3: position_m, orientation)",
        ));
    }
    checked_pose_from_pb(base, "base").map(ClientPose::Two)
}

/// A 3D pose a client sent in `base3` for a session of `dimension` ([`checked_pose3_from_pb`];
/// INVALID_ARGUMENT naming `base3` when the session is 2D).
pub fn checked_pose3_for(base3: Option<&pb::Pose3>, dimension: u8) -> Result<ClientPose, ApiError> {
    if dimension != 3 {
        return Err(ApiError::invalid("base3", "this is a 2D session: send its poses through Control/SetPose (base: x_m, y_m, theta_rad)"));
    }
    checked_pose3_from_pb(base3, "base3").map(ClientPose::Three)
}

/// A pose of either dimension, checked ([`checked_pose2_for`], [`checked_pose3_for`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClientPose {
    Two(BasePose),
    Three(BasePose3),
}

/// A 3D pose a client sent in `field`: present, finite, its quaternion unit (INVALID_ARGUMENT
/// naming `field.position_m` or `field.orientation`).
pub fn checked_pose3_from_pb(p: Option<&pb::Pose3>, field: &str) -> Result<BasePose3, ApiError> {
    let p = p.ok_or_else(|| ApiError::invalid(field, format!("{field} is missing")))?;
    let pos_field = format!("{field}.position_m");
    let q_field = format!("{field}.orientation");
    let v = p.position_m.as_ref().ok_or_else(|| ApiError::invalid(&pos_field, format!("{pos_field} is missing")))?;
    let position_m = [v.x, v.y, v.z];
    if !position_m.iter().all(|c| c.is_finite()) {
        return Err(ApiError::invalid(&pos_field, format!("{pos_field} ({}, {}, {}) is not finite", num(v.x), num(v.y), num(v.z))));
    }
    let q = p.orientation.as_ref().ok_or_else(|| ApiError::invalid(&q_field, format!("{q_field} is missing")))?;
    let wxyz = [q.w, q.x, q.y, q.z];
    BasePose3::new(position_m, wxyz).map_err(|e| {
        ApiError::invalid(
            &q_field,
            format!(
                "{q_field} (w {}, x {}, y {}, z {}): {e} (a unit quaternion w, x, y, z is needed)",
                num(q.w),
                num(q.x),
                num(q.y),
                num(q.z)
            ),
        )
    })
}

/// A tick record to a controller response (`target_names` name the 3D targets, by index).
pub fn control_response(r: &TickRecord, target_names: &[String]) -> pb::ControlResponse {
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
        d3: tick3(r, target_names),
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
        d3: None,
        unconverged: o.unconverged().is_some(),
    }
}

/// A row of a 3D Simulate time series: `d3` with the tick's 3D state (no contacts, no
/// stiffness: the counts say how many contacts), the 2D fields with its planar part (x, y, the
/// twist about z, $2\,\mathrm{atan2}(q_z, q_w)$), as a 3D session's frames carry it.
pub fn series_row3(o: &needlesim_core::sim3::StepOutput3, t_s: f64, target_names: &[String], radii_m: &[f64]) -> pb::SeriesRow {
    use needlesim_core::sim3::{PointState3, TargetState3};
    let q = o.pose.orientation.quaternion();
    let wxyz = [q.w, q.i, q.j, q.k];
    let count = |s: PointState3| o.contacts.iter().filter(|c| c.state == s).count() as u32;
    let targets = o.targets.as_slice();
    pb::SeriesRow {
        t_s,
        base: Some(pb::Pose2 { x_m: o.pose.position_m[0], y_m: o.pose.position_m[1], theta_rad: 2.0 * wxyz[3].atan2(wxyz[0]) }),
        force_n: v2([o.base_force_n[0], o.base_force_n[1]]),
        torque_nm: o.base_torque_nm[2],
        force_axial_n: -o.axial_force_n,
        force_lateral_n: 0.0,
        tip_m: v2([o.tip_m[0], o.tip_m[1]]),
        inserted_length_m: o.inserted_length_m,
        n_stuck: count(PointState3::Stuck),
        n_slipping: count(PointState3::Slipping),
        n_tip: count(PointState3::Tip),
        targets: vec![],
        d3: Some(pb::Tick3 {
            base: Some(pose3_to_pb(o.pose.position_m, wxyz)),
            force_n: v3(o.base_force_n),
            torque_nm: v3(o.base_torque_nm),
            axial_force_n: o.axial_force_n,
            tip_m: v3(o.tip_m),
            needle_shape_m: vec![
                pb::Vec3 { x: o.pose.position_m[0], y: o.pose.position_m[1], z: o.pose.position_m[2] },
                pb::Vec3 { x: o.tip_m[0], y: o.tip_m[1], z: o.tip_m[2] },
            ],
            contacts: vec![],
            targets: targets
                .iter()
                .map(|t| pb::TargetSphere {
                    name: target_names.get(t.name_idx).cloned().unwrap_or_default(),
                    center_m: v3(t.centre_m),
                    radius_m: radii_m.get(t.name_idx).copied().unwrap_or(0.0),
                    distance_m: t.distance_m,
                    hit: t.state == TargetState3::Hit,
                    missed: t.state == TargetState3::Missed,
                })
                .collect(),
            stiffness: vec![],
        }),
        unconverged: o.unconverged().is_some(),
    }
}

/// A 3D trajectory from samples: every sample's `base3` present, finite and a unit quaternion,
/// times increasing (errors name the sample).
pub fn trajectory3_from_pb(samples: &[pb::TrajectorySample]) -> Result<needlesim_scene::Trajectory3> {
    let mut out: Vec<(f64, needlesim_scene::Pose3)> = Vec::with_capacity(samples.len());
    for (i, s) in samples.iter().enumerate() {
        let field = format!("trajectory[{i}].base3");
        if s.base3.is_none() {
            bail!("{field} is missing: a 3D scene needs 3D poses (base3: position_m, orientation) in every sample");
        }
        let p = checked_pose3_from_pb(s.base3.as_ref(), &field).map_err(|e| match e {
            ApiError::InvalidArgument { message, .. } => anyhow::anyhow!(message),
            other => anyhow::anyhow!("{field}: {other:?}"),
        })?;
        if !s.t_s.is_finite() {
            bail!("trajectory[{i}].t_s = {} is not a finite number", num(s.t_s));
        }
        if let Some((t_prev, _)) = out.last() {
            let gap_s = s.t_s - *t_prev;
            if !(gap_s.is_finite() && gap_s >= needlesim_trajectory::MIN_SAMPLE_GAP_S) {
                bail!(
                    "trajectory[{i}].t_s = {} does not increase by at least {:e} s (previous {})",
                    num(s.t_s),
                    needlesim_trajectory::MIN_SAMPLE_GAP_S,
                    num(*t_prev)
                );
            }
        }
        let q = p.orientation.quaternion();
        out.push((s.t_s, needlesim_scene::Pose3::new(p.position_m, [q.w, q.i, q.j, q.k])));
    }
    if out.is_empty() {
        bail!("trajectory is empty");
    }
    Ok(needlesim_scene::Trajectory3::from_samples(out))
}

/// What a session is, for listings.
pub fn session_info(s: &Session) -> pb::SessionInfo {
    use std::sync::atomic::Ordering;
    pb::SessionInfo {
        session_id: s.id.clone(),
        scene_name: s.scene_name.clone(),
        n_nodes: s.tissue.n_nodes() as u32,
        n_triangles: if s.dimension() == 2 { s.tissue.n_elements() as u32 } else { 0 },
        dimension: s.dimension() as u32,
        n_tetrahedra: if s.dimension() == 3 { s.tissue.n_elements() as u32 } else { 0 },
        tick_rate_hz: s.tick_rate_hz,
        created_unix_ms: s.created_unix_ms,
        tick: s.counters.ticks.load(Ordering::Relaxed),
        n_observers: s.n_observers.load(Ordering::Relaxed) as u32,
        recording: SessionRecording::info_of(s).map(|r| r.name).unwrap_or_default(),
        target_names: s.target_names.clone(),
        device_channel_path: s.device_channel_path.as_ref().map(|p| p.display().to_string()).unwrap_or_default(),
        device_stale: s.counters.device_stale.load(Ordering::Relaxed) != 0,
        device_channel_broken: s.counters.device_channel_broken.load(Ordering::Relaxed) != 0,
        device_suspended: s.device_channel_path.is_some() && s.device_suspended(),
        device_poses_suspended: s.counters.device_poses_suspended.load(Ordering::Relaxed),
    }
}

/// A new session and its tokens (the one answer that carries them).
pub fn create_session_response(s: &Session) -> pb::CreateSessionResponse {
    pb::CreateSessionResponse {
        session: Some(session_info(s)),
        controller_token: s.controller_token.clone(),
        observer_token: s.observer_token.clone(),
    }
}

/// The sessions, oldest first (ties by id).
pub fn list_sessions_response(mut sessions: Vec<Arc<Session>>) -> pb::ListSessionsResponse {
    sessions.sort_by(|a, b| a.created_unix_ms.cmp(&b.created_unix_ms).then(a.id.cmp(&b.id)));
    pb::ListSessionsResponse { sessions: sessions.iter().map(|s| session_info(s)).collect() }
}

/// The recordings a token opens.
pub fn list_recordings_response(list: &[RecordingInfo]) -> pb::ListRecordingsResponse {
    pb::ListRecordingsResponse { recordings: list.iter().map(recording_info).collect() }
}

/// The tick loop's percentiles and counters.
pub fn session_stats(st: &StatsSnapshot) -> pb::SessionStats {
    pb::SessionStats {
        ticks: st.ticks,
        compute_p50_us: st.compute_us[0],
        compute_p99_us: st.compute_us[1],
        compute_p999_us: st.compute_us[2],
        compute_max_us: st.compute_us[3],
        lateness_p50_us: st.lateness_us[0],
        lateness_p99_us: st.lateness_us[1],
        lateness_p999_us: st.lateness_us[2],
        missed_deadlines: st.missed_deadlines,
        superseded_poses: st.superseded_poses,
        dropped_records: st.dropped_records,
        column_misses: st.column_misses,
        column_deferrals: st.column_deferrals,
        columns_evicted: st.columns_evicted,
        budget_exhausted_ticks: st.budget_exhausted_ticks,
        active_set_capped_ticks: st.active_set_capped_ticks,
        shape_capped_ticks: st.shape_capped_ticks,
        late_captures: st.late_captures,
        pending_captures_dropped: st.pending_captures_dropped,
        hybrid_checks: st.hybrid_checks,
        hybrid_rebuilds: st.hybrid_rebuilds,
        rejected_poses: st.rejected_poses,
        clamped_ticks: st.clamped_ticks,
        faulted: st.fault.is_some(),
        fault: st.fault.clone().unwrap_or_default(),
    }
}

/// The answer to FlipBevel: the flips requested so far.
pub fn flip_bevel_response(flips_requested: u64) -> pb::FlipBevelResponse {
    pb::FlipBevelResponse { flips_requested }
}

/// The spin command in force.
pub fn set_spin_response(spin: &needlesim_session::spin::SpinCommand) -> pb::SetSpinResponse {
    pb::SetSpinResponse { duty_cycle: spin.duty_cycle(), period_m: spin.period_m() }
}

/// A recording, live or on disk.
pub fn recording_info(i: &RecordingInfo) -> pb::RecordingInfo {
    pb::RecordingInfo {
        name: i.name.clone(),
        session_id: i.session_id.clone(),
        size_bytes: i.size_bytes,
        messages: i.messages,
        finished: i.finished,
    }
}

/// A piece of a recording's file at `offset`.
pub fn recording_chunk(data: Vec<u8>, offset: u64) -> pb::RecordingChunk {
    pb::RecordingChunk { data, offset }
}

/// The request's planning problem; errors name the field.
pub fn plan_request_from_pb(r: &pb::PlanRequest) -> Result<PlanRequest, ApiError> {
    if r.target.trim().is_empty() {
        return Err(ApiError::invalid("target", "target is empty: give the name of one of the scene's targets"));
    }
    let entry_m = match (&r.entry_from_m, &r.entry_to_m) {
        (None, None) => None,
        (Some(a), Some(b)) => Some([[a.x, a.y], [b.x, b.y]]),
        _ => {
            return Err(ApiError::invalid(
                "entry_from_m and entry_to_m",
                "entry_from_m and entry_to_m: give both ends of the entry segment, or neither",
            ));
        }
    };
    let angles_deg = match (r.angle_min_deg, r.angle_max_deg) {
        (None, None) => None,
        (Some(a), Some(b)) => Some([a, b]),
        _ => return Err(ApiError::invalid("angle_min_deg and angle_max_deg", "angle_min_deg and angle_max_deg: give both, or neither")),
    };
    Ok(PlanRequest { target: r.target.clone(), entry_m, angles_deg, speed_m_s: r.speed_mm_s.map(|v| v * 1e-3) })
}

/// A progress message of the Plan stream, after an iteration.
pub fn plan_progress(pr: &PlanProgress) -> pb::PlanProgress {
    pb::PlanProgress {
        iteration: pr.iteration as u32,
        simulations: pr.simulations as u32,
        best_error_m: pr.best_error_m,
        straight_error_m: pr.straight_error_m,
        result: None,
        result3: None,
    }
}

/// The last message of the Plan stream, with the plan.
pub fn plan_final(p: &Plan) -> pb::PlanProgress {
    pb::PlanProgress {
        iteration: p.iterations as u32,
        simulations: p.simulations as u32,
        best_error_m: p.plan.predicted_error_m,
        straight_error_m: p.straight.predicted_error_m,
        result: Some(plan_result_to_pb(p)),
        result3: None,
    }
}

/// A 3D planning request (the 3D fields of `PlanRequest`; the 2D entry segment and angles are
/// refused, naming them).
pub fn plan3_request_from_pb(r: &pb::PlanRequest) -> Result<needlesim_offline::plan3::Plan3Request, ApiError> {
    if r.target.trim().is_empty() {
        return Err(ApiError::invalid("target", "target is empty: give the name of one of the scene's targets"));
    }
    if r.entry_from_m.is_some() || r.entry_to_m.is_some() || r.angle_min_deg.is_some() || r.angle_max_deg.is_some() {
        return Err(ApiError::invalid(
            "entry_from_m",
            "entry_from_m, entry_to_m, angle_min_deg, angle_max_deg: a 3D scene's plan takes entry_point_m (and entry_radius_m) instead",
        ));
    }
    Ok(needlesim_offline::plan3::Plan3Request {
        target: r.target.clone(),
        entry_m: r.entry_point_m.as_ref().map(|v| [v.x, v.y, v.z]),
        entry_radius_m: r.entry_radius_m,
        avoid: if r.avoid.is_empty() { None } else { Some(r.avoid.clone()) },
        clearance_m: r.clearance_m,
        speed_m_s: r.speed_mm_s.map(|v| v * 1e-3),
    })
}

/// The last message of a 3D Plan stream, with the plan.
pub fn plan3_final(p: &needlesim_offline::plan3::Plan3) -> pb::PlanProgress {
    let v3 = |v: [f64; 3]| pb::Vec3 { x: v[0], y: v[1], z: v[2] };
    let ins = |i: &needlesim_offline::plan3::Insertion3| pb::PlannedInsertion3 {
        entry_m: Some(v3(i.entry_m)),
        direction: Some(v3(i.direction)),
        rolls: i.rolls.iter().map(|r| pb::RollStep { depth_m: r.depth_m, roll_rad: r.roll_rad }).collect(),
        depth_m: i.depth_m,
        predicted_error_m: i.predicted_error_m,
        tip_m: Some(v3(i.tip_m)),
        target_m: Some(v3(i.target_m)),
        aim_m: Some(v3(i.aim_m)),
        clearances_m: i.clearances_m.clone(),
    };
    let result3 = pb::PlanResult3 {
        target: p.target.clone(),
        target_radius_m: p.target_radius_m,
        target_center_m: Some(v3(p.target_center_m)),
        speed_mm_s: p.speed_m_s * 1e3,
        plan: Some(ins(&p.plan)),
        straight: Some(ins(&p.straight)),
        trajectory: p
            .trajectory
            .iter()
            .map(|&[t, x, y, z, qw, qx, qy, qz]| pb::TrajectorySample3 {
                t_s: t,
                base: Some(pb::Pose3 { position_m: Some(v3([x, y, z])), orientation: Some(pb::Quaternion { w: qw, x: qx, y: qy, z: qz }) }),
            })
            .collect(),
        converged: p.converged,
        iterations: p.iterations as u32,
        simulations: p.simulations as u32,
        wall_s: p.wall_s,
        threads: p.threads as u32,
        structures: p
            .structures
            .iter()
            .map(|s| pb::Structure3 { name: s.name.clone(), center_m: Some(v3(s.center_m)), radius_m: s.radius_m })
            .collect(),
        clearance_m: p.clearance_m,
        bevel: p.bevel,
    };
    pb::PlanProgress {
        iteration: p.iterations as u32,
        simulations: p.simulations as u32,
        best_error_m: p.plan.predicted_error_m,
        straight_error_m: p.straight.predicted_error_m,
        result: None,
        result3: Some(result3),
    }
}

/// A plan's result.
pub fn plan_result_to_pb(p: &Plan) -> pb::PlanResult {
    let vec2 = |v: [f64; 2]| pb::Vec2 { x: v[0], y: v[1] };
    let ins = |i: &Insertion| pb::PlannedInsertion {
        entry_m: Some(vec2(i.entry_m)),
        angle_rad: i.angle_rad,
        depth_m: i.depth_m,
        predicted_error_m: i.predicted_error_m,
        tip_m: Some(vec2(i.tip_m)),
        target_m: Some(vec2(i.target_m)),
        aim_m: Some(vec2(i.aim_m)),
    };
    pb::PlanResult {
        target: p.target.clone(),
        target_radius_m: p.target_radius_m,
        target_center_m: Some(vec2(p.target_center_m)),
        speed_mm_s: p.speed_m_s * 1e3,
        plan: Some(ins(&p.plan)),
        straight: Some(ins(&p.straight)),
        trajectory: p
            .trajectory
            .iter()
            .map(|&[t, x, y, th]| pb::TrajectorySample { t_s: t, base: Some(pb::Pose2 { x_m: x, y_m: y, theta_rad: th }), base3: None })
            .collect(),
        converged: p.converged,
        iterations: p.iterations as u32,
        simulations: p.simulations as u32,
        wall_s: p.wall_s,
        threads: p.threads as u32,
    }
}

/// A chunk of series rows of the Simulate stream.
pub fn series_chunk(rows: Vec<pb::SeriesRow>) -> pb::SimulateResponse {
    pb::SimulateResponse { event: Some(pb::simulate_response::Event::Series(pb::SeriesChunk { rows })) }
}

/// A progress message of the Simulate stream.
pub fn simulate_progress(ticks_done: u64, ticks_total: u64) -> pb::SimulateResponse {
    pb::SimulateResponse { event: Some(pb::simulate_response::Event::Progress(pb::SimulateProgress { ticks_done, ticks_total })) }
}

/// The last message of the Simulate stream: ticks, wall time, step time p50 and p99 (µs), the
/// final displacement of every node.
pub fn simulate_result(ticks: u64, wall_s: f64, step_us: [f64; 2], final_displacement_m: Vec<f64>) -> pb::SimulateResponse {
    let result = pb::SimulateResult { rows: vec![], ticks, wall_s, step_p50_us: step_us[0], step_p99_us: step_us[1], final_displacement_m };
    pb::SimulateResponse { event: Some(pb::simulate_response::Event::Result(result)) }
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
            bail!("trajectory[{i}].t_s = {} does not increase (previous {})", num(s.t_s), num(*t_prev));
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
        // A client's name resolves to a shipped example only, never to a path; its TOML names no
        // files (`SceneFiles::None`): the server opens no file a client names.
        pb::scene_source::Source::Example(name) => needlesim_scene::example_scene(name, limits).unwrap_or_else(|| {
            let names: Vec<&str> = needlesim_scene::EXAMPLES.iter().map(|e| e.0).collect();
            bail!("scene.example: '{}' is not a shipped example ({})", quote(name), names.join(", "))
        }),
        pb::scene_source::Source::SceneToml(text) => {
            needlesim_scene::parse_scene_with(text, SceneFiles::None, limits).context("scene.scene_toml")
        }
        pb::scene_source::Source::Uploaded(u) => uploaded_scene(u, limits),
        pb::scene_source::Source::Uploaded3d(_) => bail!("scene.uploaded3d: a 3D scene makes a live session only (CreateSession)"),
    }
}

/// The scene of a new session: 2D or 3D.
pub enum SessionScene {
    Two(Box<Scene>),
    Three(Box<Scene3d>),
}

/// Whether a scene source is a 3D scene (a 3D example's name, a TOML with `dim = 3`, an uploaded
/// 3D scene), as [`session_scene_from_pb`] decides.
pub fn scene_source_is_3d(src: Option<&pb::SceneSource>) -> bool {
    match src.and_then(|s| s.source.as_ref()) {
        Some(pb::scene_source::Source::Example(name)) => needlesim_scene::EXAMPLES3D.iter().any(|e| e.0 == name),
        Some(pb::scene_source::Source::SceneToml(text)) => needlesim_scene::scene_dim(text).is_ok_and(|d| d == 3),
        Some(pb::scene_source::Source::Uploaded3d(_)) => true,
        _ => false,
    }
}

/// A session's scene from its source: a 3D example name, a 3D TOML (`dim = 3`) or an uploaded 3D
/// scene load with the 3D loader (its limits), anything else as [`scene_from_pb`].
pub fn session_scene_from_pb(src: Option<&pb::SceneSource>, limits: &SceneLimits) -> Result<SessionScene> {
    match src.and_then(|s| s.source.as_ref()) {
        Some(pb::scene_source::Source::Example(name)) if needlesim_scene::EXAMPLES3D.iter().any(|e| e.0 == name) => {
            let scene = needlesim_scene::example_scene3d(name, limits).context("scene.example: not a shipped 3D example")??;
            Ok(SessionScene::Three(Box::new(scene)))
        }
        Some(pb::scene_source::Source::SceneToml(text)) if needlesim_scene::scene_dim(text).is_ok_and(|d| d == 3) => {
            let scene = needlesim_scene::parse_scene3d_with(text, SceneFiles::None, limits).context("scene.scene_toml")?;
            Ok(SessionScene::Three(Box::new(scene)))
        }
        Some(pb::scene_source::Source::Uploaded3d(u)) => uploaded_scene3d(u, limits).map(|s| SessionScene::Three(Box::new(s))),
        _ => scene_from_pb(src, limits).map(|s| SessionScene::Two(Box::new(s))),
    }
}

/// An uploaded 3D scene: its TOML may name the uploaded mesh, by `mesh_file_name`, and no other
/// file (`SceneFiles::Given`: resolved in memory, nothing is written or opened).
fn uploaded_scene3d(u: &pb::UploadedScene3d, limits: &SceneLimits) -> Result<Scene3d> {
    let name = &u.mesh_file_name;
    let plain = !name.is_empty()
        && name.len() <= 255
        && name.chars().all(|c| c.is_ascii_alphanumeric() || "._-".contains(c))
        && !name.starts_with('.');
    if !plain {
        bail!(
            "scene.uploaded3d.mesh_file_name '{}': a plain file name is needed (letters, digits, '.', '_', '-'; not starting with '.')",
            quote(name)
        );
    }
    let max = limits.mesh.max_nodes.saturating_mul(512).max(1 << 20);
    if u.mesh_text.len() > max {
        return Err(anyhow::Error::new(needlesim_scene::SizeLimit {
            what: "scene.uploaded3d.mesh_text".into(),
            amount: (u.mesh_text.len() as u64 >> 20) as f64,
            limit: max as u64 >> 20,
            unit: "MiB",
            hint: " (the server's node limit bounds the mesh text)".into(),
        }));
    }
    let files = [(name.as_str(), u.mesh_text.as_str())];
    needlesim_scene::parse_scene3d_with(&u.scene_toml, SceneFiles::Given(&files), limits).context("scene.uploaded3d")
}

/// The boundary surface of a 3D session's tissue.
pub fn surface_to_pb(surface: &needlesim_session::BoundarySurface, mesh: &needlesim_core::d3::TetMesh) -> pb::Surface {
    let nodes_m = mesh.nodes_m();
    pb::Surface {
        node_ids: surface.nodes.clone(),
        node_xyz_m: surface.nodes.iter().flat_map(|&v| nodes_m[v as usize]).collect(),
        triangles: surface.triangles.iter().flatten().copied().collect(),
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
    let tissue = Arc::new(needlesim_scene::tissue_model(m, mats, &fixed).context("scene.uploaded (tissue model)")?);
    let d = RegionNeedleParams::default();
    let or = |v: f64, dflt: f64| if v == 0.0 { dflt } else { v };
    let base = u.needle_base.as_ref().context("scene.uploaded.needle_base is missing")?;
    if !pose_from_pb(base).is_finite() {
        bail!("scene.uploaded.needle_base ({}, {}, {}) is not finite", num(base.x_m), num(base.y_m), num(base.theta_rad));
    }
    let params = SimParams {
        needle: NeedleShape::Rigid(RigidNeedle { length_m: or(u.needle_length_m, 0.1) }),
        initial_pose: pose_from_pb(base),
        contact: if u.node_capture {
            ContactModel::Nodes
        } else {
            ContactModel::MaterialPoints { spacing_m: or(u.contact_spacing_m, ContactModel::DEFAULT_SPACING_M), width_m: 0.0 }
        },
        columns_in_step: false,
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
                ..d
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
        max_active_set_iterations: 64,
        lookahead_m: 0.01,
        viscoelastic: None,
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
