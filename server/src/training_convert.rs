//! The training messages (proto/needlesim/v1/training.proto) built from and read into the live
//! training layer's types — the training counterpart of `convert.rs`, kept beside it so that
//! the protocol types of issue 20 stay in one place.

use needlesim_proto::v1 as pb;
use needlesim_training::Exercise;
use needlesim_training::metrics::Placement;
use needlesim_training::run::TargetGeometry;

use crate::training_live::{LiveExercise, Snapshot};
use crate::training_ultrasound::{ProbeSpec, SliceImage};

fn vec3(v: [f64; 3]) -> pb::Vec3 {
    pb::Vec3 { x: v[0], y: v[1], z: v[2] }
}

fn of_vec3(v: Option<&pb::Vec3>) -> [f64; 3] {
    v.map_or([0.0; 3], |v| [v.x, v.y, v.z])
}

/// An exercise's description; `targets` resolved against its scene when known.
pub fn exercise_info(ex: &Exercise, targets: Option<&[TargetGeometry]>) -> pb::ExerciseInfo {
    pb::ExerciseInfo {
        name: ex.name.clone(),
        description: ex.description.clone(),
        dimension: ex.dim as u32,
        targets: targets
            .unwrap_or_default()
            .iter()
            .map(|t| pb::ExerciseTarget {
                name: t.name.clone(),
                centre_m: Some(vec3(t.centre_m)),
                radius_m: t.radius_m,
                tolerance_m: t.tolerance_m,
            })
            .collect(),
        structures: ex.spare.iter().map(|s| s.name.clone()).collect(),
        time_limit_s: ex.limits.time_s,
        reinsertion_limit: ex.limits.reinsertions,
        peak_force_limit_n: ex.limits.peak_force_n,
    }
}

/// A placement of target `idx`.
pub fn placement(ex: &LiveExercise, idx: usize, p: &Placement) -> pb::ExercisePlacement {
    pb::ExercisePlacement {
        target_index: idx as u32,
        target: ex.targets.get(idx).map(|t| t.name.clone()).unwrap_or_default(),
        t_s: p.t_s,
        error_m: p.error_m,
        on_target: p.on_target,
        depth_m: p.depth_m,
    }
}

pub fn marker(m: &needlesim_training::TimelineMarker) -> pb::ExerciseMarker {
    pb::ExerciseMarker { t_s: m.t_s, tick: m.tick, label: m.label.clone() }
}

/// The exercise's status from a snapshot.
pub fn status(ex: &LiveExercise, snap: &Snapshot) -> pb::ExerciseStatus {
    let m = &snap.metrics;
    let s = &snap.score;
    pb::ExerciseStatus {
        session_id: ex.session_id.clone(),
        exercise: ex.exercise.name.clone(),
        time_s: snap.time_s,
        tick: snap.tick,
        score: s.total,
        sub_scores: Some(pb::ExerciseSubScores {
            accuracy: s.sub.accuracy,
            efficiency: s.sub.efficiency,
            path: s.sub.path,
            force: s.sub.force,
            safety: s.sub.safety,
            time: s.sub.time,
        }),
        penalty: s.penalty,
        time_exceeded: s.time_exceeded,
        reinsertions_exceeded: s.reinsertions_exceeded,
        peak_force_exceeded: s.peak_force_exceeded,
        insertions: m.insertions,
        reinsertions: m.reinsertions,
        redirections: m.redirections,
        path_length_m: m.path_length_m,
        peak_axial_force_n: m.peak_axial_force_n,
        mean_axial_force_n: m.mean_axial_force_n,
        max_depth_m: m.max_depth_m,
        depth_m: snap.depth_m,
        targets: m
            .targets
            .iter()
            .enumerate()
            .map(|(i, t)| pb::ExerciseTargetStatus {
                name: t.name.clone(),
                tolerance_m: t.tolerance_m,
                closest_m: t.closest_m.is_finite().then_some(t.closest_m),
                placement: t.placement.as_ref().map(|p| placement(ex, i, p)),
            })
            .collect(),
        structures: m
            .structures
            .iter()
            .map(|st| pb::ExerciseStructureStatus {
                name: st.name.clone(),
                min_clearance_m: st.min_clearance_m,
                intrusion_depth_m: st.intrusion_depth_m,
                touched: st.touched,
            })
            .collect(),
        markers: snap.markers.iter().map(marker).collect(),
        controller: if snap.instructor_control { pb::ControllerRole::Instructor } else { pb::ControllerRole::Trainee } as i32,
        paused: snap.paused,
        samples: m.samples,
        finished: snap.finished.is_some(),
        report_name: snap.finished.as_ref().map(|f| f.report_name.clone()).unwrap_or_default(),
        resets: snap.resets,
    }
}

pub fn probe(p: &ProbeSpec) -> pb::UltrasoundProbe {
    match p {
        ProbeSpec::Two(p) => pb::UltrasoundProbe {
            origin_m: Some(vec3([p.origin_m[0], p.origin_m[1], 0.0])),
            e_u: Some(vec3([p.e_u[0], p.e_u[1], 0.0])),
            e_v: Some(vec3([p.e_v[0], p.e_v[1], 0.0])),
            pixel_m: p.pixel_m,
            width: p.width as u32,
            height: p.height as u32,
            thickness_m: 0.0,
        },
        ProbeSpec::Three(p) => pb::UltrasoundProbe {
            origin_m: Some(vec3(p.origin_m)),
            e_u: Some(vec3(p.e_u)),
            e_v: Some(vec3(p.e_v)),
            pixel_m: p.pixel_m,
            width: p.width as u32,
            height: p.height as u32,
            thickness_m: p.thickness_m,
        },
    }
}

/// A probe from a client, checked for a session of dimension `dim` (INVALID_ARGUMENT names the
/// field).
pub fn probe_from_pb(p: Option<&pb::UltrasoundProbe>, dim: u8) -> Result<ProbeSpec, tonic::Status> {
    let p = p.ok_or_else(|| tonic::Status::invalid_argument("probe: missing"))?;
    for (field, v) in [("origin_m", &p.origin_m), ("e_u", &p.e_u), ("e_v", &p.e_v)] {
        if v.is_none() {
            return Err(tonic::Status::invalid_argument(format!("probe.{field}: missing")));
        }
    }
    crate::training_ultrasound::checked_probe(
        dim,
        of_vec3(p.origin_m.as_ref()),
        of_vec3(p.e_u.as_ref()),
        of_vec3(p.e_v.as_ref()),
        p.pixel_m,
        p.width,
        p.height,
        p.thickness_m,
    )
    .map_err(|e| tonic::Status::invalid_argument(e.to_string()))
}

pub fn ultrasound_image(img: &SliceImage) -> pb::UltrasoundImage {
    pb::UltrasoundImage {
        tick: img.tick,
        width: img.width as u32,
        height: img.height as u32,
        gray8: img.gray8.clone(),
        probe: Some(probe(&img.probe)),
        render_us: img.render_us,
    }
}
