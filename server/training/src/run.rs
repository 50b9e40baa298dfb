//! Scripted exercise runs: an exercise resolved against its scene (targets looked up or added
//! to the simulation, tolerances defaulted to radii), a base trajectory through the scene's
//! simulation — needlesim-offline's driver (`ScriptedRun`, the run `simulate` makes) in both
//! dimensions —
//! each tick's output turned into a [`Sample`] for the [`MetricsTracker`] and the report's
//! [`Trace`], and "placed" declared at the first tick at or after each given time. In 2D the
//! tissue strain is sampled every [`STRAIN_INTERVAL_S`] of exercise time from the simulation's
//! displacement field ([`crate::strain`]). The run's tick series CSV is written on request
//! ([`RunOptions`], [`crate::expert`]) and the expert run the exercise names is read and overlaid.

use std::ops::ControlFlow;
use std::path::Path;
use std::sync::Arc;

use needlesim_core::mesh::MeshLimits;
use needlesim_core::num::num;
use needlesim_core::sim::TargetParams;
use needlesim_core::sim3::{SimError3, Simulation3, Target3};
use needlesim_offline::ScriptedSim;
use needlesim_offline::simulate3::sim3_params;
use needlesim_scene::{Scene, Scene3d, Trajectory, Trajectory3};
use serde::Serialize;

use crate::exercise::{Exercise, SceneRef, Structure, TargetSource};
use crate::expert::{ExpertError, ExpertOverlay, TickCsv, expert_overlay};
use crate::metrics::{ExerciseResult, MetricsTracker, Placement, Trace, TracePoint, TrackedTarget, TrackerSpec};
use crate::sample::Sample;
use crate::strain::StrainField;

/// Exercise time between two strain samples of a 2D scripted run, s (metrics.rs).
pub const STRAIN_INTERVAL_S: f64 = 0.01;

/// How many points the report's curves keep at most ([`Trace`]).
pub const TRACE_CAPACITY: usize = 4096;

/// Why a scripted exercise run failed; each names what.
#[derive(Debug, thiserror::Error)]
pub enum ExerciseRunError {
    /// The exercise's scene does not load.
    #[error("scene: {0:#}")]
    Scene(anyhow::Error),
    /// An exercise target does not fit the scene (`key` is the exercise's TOML key).
    #[error("{key}: {message}")]
    Target { key: String, message: String },
    /// The trajectory CSV is refused (line and column named).
    #[error("trajectory: {0}")]
    Trajectory(String),
    /// No trajectory: neither given nor shipped with the exercise.
    #[error("no trajectory: give --trajectory (exercise '{0}' ships none)")]
    NoTrajectory(String),
    /// A placement time after the trajectory's end.
    #[error("placed at t = {} s: after the trajectory's end at t = {} s", num(*t_s), num(*end_s))]
    PlacementAfterEnd { t_s: f64, end_s: f64 },
    /// The simulation failed (too long a run, a failed step: the tick is named).
    #[error("{0}")]
    Simulation(String),
    /// The expert run the exercise names (or `--expert`) cannot be read: the file and line named
    /// (its words once: a chain printed whole does not repeat them).
    #[error(transparent)]
    Expert(#[from] ExpertError),
}

/// A target as drawn in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetGeometry {
    pub name: String,
    /// Reference (undeformed) centre, m.
    pub centre_m: [f64; 3],
    pub radius_m: f64,
    pub tolerance_m: f64,
}

/// Most refused "placed" declarations an exercise keeps in full (the first ones, with their time
/// and reason; as many as a live exercise's markers): past them they are only counted, so a client
/// repeating a refused call grows neither the server nor the report.
pub const MAX_REFUSED_KEPT: usize = 1000;

/// Declarations of "placed" that were refused: the first [`MAX_REFUSED_KEPT`] as (time in s,
/// reason), and the count of all of them (the report says how many were left out).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RefusedPlacements {
    /// The first refused declarations, in order: (exercise time, s; why).
    pub first: Vec<(f64, String)>,
    /// Every refused declaration, those kept included.
    pub total: u64,
}

impl RefusedPlacements {
    /// Counts a refused declaration and keeps it if fewer than [`MAX_REFUSED_KEPT`] are kept;
    /// `why` is called only then.
    pub fn push(&mut self, t_s: f64, why: impl FnOnce() -> String) {
        self.total = self.total.saturating_add(1);
        if self.first.len() < MAX_REFUSED_KEPT {
            self.first.push((t_s, why()));
        }
    }

    /// How many were counted but not kept.
    pub fn left_out(&self) -> u64 {
        self.total.saturating_sub(self.first.len() as u64)
    }

    pub fn is_empty(&self) -> bool {
        self.total == 0
    }

    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

/// A finished scripted run.
#[derive(Debug, Clone, Serialize)]
pub struct ExerciseRun {
    pub exercise: String,
    pub description: String,
    pub scene: String,
    pub dim: u8,
    pub ticks: u64,
    pub tick_rate_hz: f64,
    pub result: ExerciseResult,
    /// The targets in the tracker's order.
    pub targets: Vec<TargetGeometry>,
    #[serde(skip)]
    pub structures: Vec<Structure>,
    /// The report's curves (bounded, [`TRACE_CAPACITY`]).
    #[serde(skip)]
    pub trace: Vec<TracePoint>,
    /// The placements in the order declared: (target index, placement).
    pub placements: Vec<(usize, Placement)>,
    /// Declarations refused (every target placed already), with the time: the first
    /// [`MAX_REFUSED_KEPT`] in full, all counted.
    pub refused_placements: RefusedPlacements,
    /// Markers an instructor placed on the timeline (a live exercise; none in a scripted run).
    pub markers: Vec<TimelineMarker>,
    /// The expert's run overlaid in the report, when the exercise names one ([`crate::expert`]).
    pub expert: Option<ExpertOverlay>,
    /// Why the named expert run is not overlaid (a live session's report says so instead of failing).
    pub expert_note: Option<String>,
    /// The run's tick series CSV, when asked for ([`RunOptions::ticks_every`]).
    #[serde(skip)]
    pub ticks_csv: Option<String>,
}

/// Options of a scripted run beyond the exercise's own.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunOptions {
    /// Write the tick series CSV ([`crate::expert`]), keeping every n-th tick.
    pub ticks_every: Option<u64>,
}

/// The expert overlay of `ex` for a tracker of `spec`: `Ok(None)` when the exercise names no
/// expert run, an error naming the file (and line) when it cannot be read.
pub fn expert_for(ex: &Exercise, spec: &TrackerSpec) -> Result<Option<ExpertOverlay>, ExpertError> {
    let Some(src) = &ex.expert else { return Ok(None) };
    let text = src.text.as_ref().map_err(|e| ExpertError::Read { file: src.file.clone(), message: e.clone() })?;
    expert_overlay(text, &src.file, spec).map(Some)
}

/// A marker on an exercise's timeline (a live session's instructor places them).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimelineMarker {
    /// Exercise time, s.
    pub t_s: f64,
    /// The session's tick when it was placed.
    pub tick: u64,
    pub label: String,
}

/// The resolved targets: the tracker's, the report's, and those the exercise adds to the
/// simulation (centre, radius).
type Resolved = (Vec<TrackedTarget>, Vec<TargetGeometry>, Vec<([f64; 3], f64)>);

/// Scene targets as (name, reference centre, radius).
fn resolve_targets(ex: &Exercise, scene_targets: &[(String, [f64; 3], f64)]) -> Result<Resolved, ExerciseRunError> {
    let mut tracked = Vec::new();
    let mut geom = Vec::new();
    let mut added = Vec::new();
    if ex.targets.is_empty() {
        for (i, (name, c, r)) in scene_targets.iter().enumerate() {
            if *r <= 0.0 {
                return Err(ExerciseRunError::Target {
                    key: "targets".into(),
                    message: format!(
                        "none given, and the scene's target '{name}' has no radius to take as tolerance: list it with tolerance_m"
                    ),
                });
            }
            tracked.push(TrackedTarget { name: name.clone(), sample_idx: i, tolerance_m: *r });
            geom.push(TargetGeometry { name: name.clone(), centre_m: *c, radius_m: *r, tolerance_m: *r });
        }
    }
    for (k, t) in ex.targets.iter().enumerate() {
        match &t.source {
            TargetSource::Scene(s) => {
                let Some(i) = scene_targets.iter().position(|x| &x.0 == s) else {
                    let names: Vec<&str> = scene_targets.iter().map(|x| x.0.as_str()).collect();
                    return Err(ExerciseRunError::Target {
                        key: format!("targets[{k}].scene_target"),
                        message: format!("'{s}' is not a target of the scene (its targets: {})", names.join(", ")),
                    });
                };
                let (_, c, r) = scene_targets[i];
                let tol = if t.tolerance_m.is_nan() { r } else { t.tolerance_m };
                if tol <= 0.0 {
                    return Err(ExerciseRunError::Target {
                        key: format!("targets[{k}].tolerance_m"),
                        message: format!("missing, and the scene's target '{s}' has no radius to take instead"),
                    });
                }
                tracked.push(TrackedTarget { name: t.name.clone(), sample_idx: i, tolerance_m: tol });
                geom.push(TargetGeometry { name: t.name.clone(), centre_m: c, radius_m: r, tolerance_m: tol });
            }
            TargetSource::New { center_m, radius_m } => {
                let idx = scene_targets.len() + added.len();
                if idx >= crate::sample::MAX_SAMPLE_TARGETS {
                    return Err(ExerciseRunError::Target {
                        key: format!("targets[{k}]"),
                        message: format!(
                            "the scene has {} targets: at most {} in all",
                            scene_targets.len(),
                            crate::sample::MAX_SAMPLE_TARGETS
                        ),
                    });
                }
                added.push((*center_m, *radius_m));
                tracked.push(TrackedTarget { name: t.name.clone(), sample_idx: idx, tolerance_m: t.tolerance_m });
                geom.push(TargetGeometry { name: t.name.clone(), centre_m: *center_m, radius_m: *radius_m, tolerance_m: t.tolerance_m });
            }
        }
    }
    Ok((tracked, geom, added))
}

/// Feeds samples to the tracker and trace and declares placements on schedule.
struct Feeder<'a> {
    tracker: MetricsTracker,
    trace: Trace,
    placed_at_s: &'a [f64],
    next: usize,
    placements: Vec<(usize, Placement)>,
    refused: RefusedPlacements,
    ticks: u64,
    ticks_csv: Option<TickCsv>,
}

impl Feeder<'_> {
    fn push(&mut self, s: &Sample) {
        self.tracker.push(s);
        self.trace.push(s, self.tracker.depth_m());
        self.ticks += 1;
        // A placement time on a tick's time counts at that tick (times printed to 1 µs).
        let mut placed = 0;
        while self.next < self.placed_at_s.len() && self.placed_at_s[self.next] <= s.t_s + 1e-9 {
            match self.tracker.place() {
                Ok(p) => self.placements.push(p),
                Err(e) => self.refused.push(s.t_s, || e.to_string()),
            }
            self.next += 1;
            placed += 1;
        }
        if let Some(c) = &mut self.ticks_csv {
            c.push(s, placed);
        }
    }
}

fn tracker_spec(ex: &Exercise, targets: Vec<TrackedTarget>) -> TrackerSpec {
    TrackerSpec {
        dims: ex.dim as usize,
        targets,
        structures: ex.spare.clone(),
        limits: ex.limits,
        weights: ex.weights,
        redirect_threshold_m: ex.redirect_threshold_m,
    }
}

/// A 2D exercise ready to simulate: its scene with the exercise's added targets appended to
/// `scene.params.targets`, the tracker's spec (sample target indices into those), and the
/// targets' geometry for the report. What a live session created from an exercise starts from.
pub struct Prepared2d {
    pub scene: Scene,
    pub spec: TrackerSpec,
    pub targets: Vec<TargetGeometry>,
}

/// Loads a 2D exercise's scene and resolves its targets ([`Prepared2d`]).
pub fn prepare_2d(ex: &Exercise, limits: &MeshLimits) -> Result<Prepared2d, ExerciseRunError> {
    let mut scene: Scene = match &ex.scene {
        SceneRef::Shipped(n) => needlesim_scene::load_scene(n, limits),
        SceneRef::File { file, text, base_dir } => {
            needlesim_scene::parse_scene(text, base_dir, limits).map_err(|e| e.context(format!("scene {file}")))
        }
    }
    .map_err(ExerciseRunError::Scene)?;
    let scene_targets: Vec<_> =
        scene.params.targets.iter().map(|t| (t.name.clone(), [t.center_m[0], t.center_m[1], 0.0], t.radius_m)).collect();
    let (tracked, geom, added) = resolve_targets(ex, &scene_targets)?;
    for (i, (c, r)) in added.into_iter().enumerate() {
        scene.params.targets.push(TargetParams { name: format!("exercise-{i}"), center_m: [c[0], c[1]], radius_m: r });
    }
    Ok(Prepared2d { scene, spec: tracker_spec(ex, tracked), targets: geom })
}

/// A 3D exercise ready to simulate: its scene, the tracker's spec, the targets' geometry, and
/// the targets the exercise adds, to append to `Sim3Params::targets` after the scene's.
pub struct Prepared3d {
    pub scene: Scene3d,
    pub spec: TrackerSpec,
    pub targets: Vec<TargetGeometry>,
    pub added_targets: Vec<Target3>,
}

/// Loads a 3D exercise's scene and resolves its targets ([`Prepared3d`]).
pub fn prepare_3d(ex: &Exercise, limits: &MeshLimits) -> Result<Prepared3d, ExerciseRunError> {
    let scene: Scene3d = match &ex.scene {
        SceneRef::Shipped(n) => needlesim_scene::load_scene3d(n, limits),
        SceneRef::File { file, text, base_dir } => {
            needlesim_scene::parse_scene3d(text, base_dir, limits).map_err(|e| e.context(format!("scene {file}")))
        }
    }
    .map_err(ExerciseRunError::Scene)?;
    let scene_targets: Vec<_> = scene.targets.iter().map(|t| (t.name.clone(), t.center_m, t.radius_m)).collect();
    let (tracked, geom, added) = resolve_targets(ex, &scene_targets)?;
    let added_targets =
        added.into_iter().enumerate().map(|(i, (c, r))| Target3 { centre_m: c, radius_m: r, name_idx: scene_targets.len() + i }).collect();
    Ok(Prepared3d { scene, spec: tracker_spec(ex, tracked), targets: geom, added_targets })
}

/// Runs `ex` scripted: `trajectory_csv` (or the exercise's own), "placed" declared at
/// `placed_at_s` (or the exercise's own when `None`); the expert run it names overlaid.
pub fn run_exercise(
    ex: &Exercise,
    trajectory_csv: Option<&str>,
    placed_at_s: Option<&[f64]>,
    max_ticks: u64,
    limits: &MeshLimits,
) -> Result<ExerciseRun, ExerciseRunError> {
    run_exercise_with(ex, trajectory_csv, placed_at_s, max_ticks, limits, RunOptions::default())
}

/// [`run_exercise`] with [`RunOptions`].
pub fn run_exercise_with(
    ex: &Exercise,
    trajectory_csv: Option<&str>,
    placed_at_s: Option<&[f64]>,
    max_ticks: u64,
    limits: &MeshLimits,
    opts: RunOptions,
) -> Result<ExerciseRun, ExerciseRunError> {
    let csv = trajectory_csv.or(ex.trajectory_csv.as_deref()).ok_or_else(|| ExerciseRunError::NoTrajectory(ex.name.clone()))?;
    let placed = placed_at_s.unwrap_or(&ex.placed_at_s);
    // A time that is not finite would never be reached: "placed" would be silently not declared.
    if let Some(&t) = placed.iter().find(|t| !t.is_finite()) {
        return Err(ExerciseRunError::Target { key: "placed-at".into(), message: format!("{} is not a finite time (s)", num(t)) });
    }
    if let Some(w) = placed.windows(2).find(|w| w[1] < w[0]) {
        return Err(ExerciseRunError::Target {
            key: "placed-at".into(),
            message: format!("times must increase ({} after {})", num(w[1]), num(w[0])),
        });
    }
    if ex.dim == 2 {
        let Prepared2d { scene, spec, targets: geom } = prepare_2d(ex, limits)?;
        let ticks_csv = opts.ticks_every.map(|n| TickCsv::new(&spec, n, &ex.name));
        let traj = Trajectory::parse_csv(csv).map_err(|e| ExerciseRunError::Trajectory(e.to_string()))?;
        let end_s = traj.span_s().1;
        if let Some(&t) = placed.iter().find(|&&t| t > end_s + 1e-9) {
            return Err(ExerciseRunError::PlacementAfterEnd { t_s: t, end_s });
        }
        let mut f = Feeder {
            tracker: MetricsTracker::new(spec),
            trace: Trace::new(TRACE_CAPACITY),
            placed_at_s: placed,
            next: 0,
            placements: vec![],
            refused: RefusedPlacements::default(),
            ticks: 0,
            ticks_csv,
        };
        // The same run as `simulate` (needlesim-offline's driver), with the strain sampled every
        // STRAIN_INTERVAL_S of exercise time from the simulation's displacement field.
        let sim_err = |e: needlesim_offline::RunError| ExerciseRunError::Simulation(format!("{e:#}"));
        let opts = needlesim_offline::RunOptions { max_ticks, ..Default::default() };
        let mut run = needlesim_offline::ScriptedRun::new(
            scene.tissue.clone(),
            scene.params.clone(),
            needlesim_offline::Script::trajectory(&traj),
            opts,
        )
        .map_err(sim_err)?;
        let mut strain = StrainField::new(scene.tissue.mesh().nodes_m(), scene.tissue.mesh().triangles());
        let mut next_strain_s = f64::NEG_INFINITY;
        run.run(|tick, sim| {
            f.push(&Sample::from_2d(sim.output(), tick.t_s));
            if tick.t_s >= next_strain_s - 1e-9 {
                sim.displacement_field_into(strain.displacements_mut());
                f.tracker.push_strain(tick.t_s, &strain.evaluate(ex.damage_strain));
                next_strain_s = if next_strain_s.is_finite() { next_strain_s + STRAIN_INTERVAL_S } else { tick.t_s + STRAIN_INTERVAL_S };
            }
            ControlFlow::Continue(())
        })
        .map_err(sim_err)?;
        run.finish().map_err(sim_err)?;
        finish(ex, scene.name.clone(), scene.params.tick_rate_hz, geom, f)
    } else {
        let Prepared3d { scene, spec, targets: geom, added_targets } = prepare_3d(ex, limits)?;
        let ticks_csv = opts.ticks_every.map(|n| TickCsv::new(&spec, n, &ex.name));
        let traj = Trajectory3::parse_csv(csv).map_err(|e| ExerciseRunError::Trajectory(e.to_string()))?;
        let t1 = traj.span_s().1;
        if let Some(&t) = placed.iter().find(|&&t| t > t1 + 1e-9) {
            return Err(ExerciseRunError::PlacementAfterEnd { t_s: t, end_s: t1 });
        }
        let rate = scene.tick_rate_hz;
        let initial = <Simulation3 as ScriptedSim>::first_pose(&traj).map_err(|e| match e {
            SimError3::Pose { source, .. } => ExerciseRunError::Trajectory(format!("the first pose: {source}")),
            e => ExerciseRunError::Trajectory(format!("the first pose: {e}")),
        })?;
        let model = Arc::new(scene.tissue_model().map_err(ExerciseRunError::Scene)?);
        let mut params = sim3_params(&scene, initial);
        params.targets.extend(added_targets);
        let mut f = Feeder {
            tracker: MetricsTracker::new(spec),
            trace: Trace::new(TRACE_CAPACITY),
            placed_at_s: placed,
            next: 0,
            placements: vec![],
            refused: RefusedPlacements::default(),
            ticks: 0,
            ticks_csv,
        };
        // The same run as the 3D `simulate` (needlesim-offline's driver: every column ahead of
        // the tip between steps; one convergence policy, `Fail`: an exercise is scored on
        // converged ticks only).
        let sim_err = |e: needlesim_offline::RunError<SimError3>| match e {
            needlesim_offline::RunError::Setup(e) => ExerciseRunError::Simulation(format!("the 3D simulation cannot start: {e}")),
            e => ExerciseRunError::Simulation(format!("{e:#}")),
        };
        let opts = needlesim_offline::RunOptions { max_ticks, ..Default::default() };
        let mut run =
            needlesim_offline::ScriptedRun::new(model, params, needlesim_offline::Script::trajectory(&traj), opts).map_err(sim_err)?;
        run.run(|tick, sim| {
            f.push(&Sample::from_3d(sim.output(), tick.t_s));
            ControlFlow::Continue(())
        })
        .map_err(sim_err)?;
        run.finish().map_err(sim_err)?;
        finish(ex, scene.name.clone(), rate, geom, f)
    }
}

fn finish(
    ex: &Exercise,
    scene: String,
    rate: f64,
    targets: Vec<crate::run::TargetGeometry>,
    f: Feeder<'_>,
) -> Result<ExerciseRun, ExerciseRunError> {
    let expert = expert_for(ex, f.tracker.spec())?;
    Ok(ExerciseRun {
        exercise: ex.name.clone(),
        description: ex.description.clone(),
        scene,
        dim: ex.dim,
        ticks: f.ticks,
        tick_rate_hz: rate,
        trace: f.trace.points(),
        result: f.tracker.finish(),
        targets,
        structures: ex.spare.clone(),
        placements: f.placements,
        refused_placements: f.refused,
        markers: Vec::new(),
        expert,
        expert_note: None,
        ticks_csv: f.ticks_csv.map(TickCsv::finish),
    })
}

/// Reads a trajectory file for [`run_exercise`] (a helper for the command line).
pub fn read_trajectory(path: &Path) -> Result<String, ExerciseRunError> {
    needlesim_scene::read_local_file(path, needlesim_scene::MAX_LOCAL_FILE_BYTES)
        .map_err(|e| ExerciseRunError::Trajectory(format!("{e:#}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exercise::parse_exercise;

    #[test]
    fn a_target_the_exercise_adds_moves_like_the_scene_target_at_the_same_place() {
        let text = "name = \"t\"\nscene = \"fig3-target\"\n[[targets]]\nscene_target = \"biopsy\"\ntolerance_m = 0.002\n\
                    [[targets]]\nname = \"copy\"\ncenter_m = [0.05830222215594891, 0.027860619515673035]\nradius_m = 0.0015\ntolerance_m = 0.002\n";
        let ex = parse_exercise(text, Path::new(".")).unwrap();
        let csv = include_str!("../../scenes/exercises/biopsy-2d.csv");
        let run = run_exercise(&ex, Some(csv), Some(&[6.0, 6.0]), 100_000, &MeshLimits::default()).unwrap();
        assert_eq!(run.placements.len(), 2);
        let (a, b) = (run.placements[0].1, run.placements[1].1);
        assert_eq!(a.t_s, b.t_s);
        assert!((a.error_m - b.error_m).abs() < 1e-12, "{} vs {}", a.error_m, b.error_m);
        // Both moved with the tissue: the error is not the distance to the undeformed centre.
        let rigid = crate::sample::dist3(a.tip_m, [0.05830222215594891, 0.027860619515673035, 0.0]);
        assert!((a.error_m - rigid).abs() > 1e-3, "error {} vs rigid {rigid}", a.error_m);
    }

    #[test]
    fn issue_35_a_placement_time_that_is_not_finite_is_refused() {
        let csv = include_str!("../../scenes/exercises/biopsy-2d.csv");
        let text = "name = \"t\"\nscene = \"fig3-target\"\n[[targets]]\nscene_target = \"biopsy\"\ntolerance_m = 0.002\n";
        let ex = parse_exercise(text, Path::new(".")).unwrap();
        for (placed, want) in [
            (vec![f64::NAN], "placed-at: NaN is not a finite time (s)"),
            (vec![1.0, f64::INFINITY], "placed-at: inf is not a finite time (s)"),
            (vec![2.0, 1e300, 1.0], "placed-at: times must increase (1 after 1e300)"),
        ] {
            let e = run_exercise(&ex, Some(csv), Some(&placed), 100_000, &MeshLimits::default()).unwrap_err().to_string();
            assert_eq!(e, want);
        }
        let e = run_exercise(&ex, Some(csv), Some(&[1e300]), 100_000, &MeshLimits::default()).unwrap_err().to_string();
        assert!(e.starts_with("placed at t = 1e300 s: after the trajectory's end at t = "), "{e}");
    }

    #[test]
    fn scene_target_names_and_missing_tolerances_are_checked_against_the_scene() {
        let csv = include_str!("../../scenes/exercises/biopsy-2d.csv");
        let ex = parse_exercise("name = \"t\"\nscene = \"fig3-target\"\n[[targets]]\nscene_target = \"nope\"\n", Path::new(".")).unwrap();
        let e = run_exercise(&ex, Some(csv), Some(&[]), 100_000, &MeshLimits::default()).unwrap_err().to_string();
        assert_eq!(e, "targets[0].scene_target: 'nope' is not a target of the scene (its targets: biopsy)");
    }
}
