//! The motion suite's scripts: one commanded pose per tick for each motion (module docs), its
//! needle and the simulation parameters of a case.

use anyhow::{Context, Result};
use needlesim_core::compliance::TissueModel;
use needlesim_core::fixtures;
use needlesim_core::sim::{ContactModel, SimParams};
use needlesim_core::{BasePose, MeshLimits, NeedleShape, RegionNeedleParams, RigidNeedle};

use super::{
    ContactChoice, ENTRY_M, MAX_CAPTURED_NODES, MAX_POINTS, Motion, OBLIQUE_ANGLE_RAD, Pace, RIGID_LENGTH_M, START_HEIGHT_M, TICK_RATE_HZ,
    TRAVEL_M, TURN_AMPLITUDE_RAD, TURN_PERIODS,
};

/// A named stretch of a script, from `first_tick` to the next phase's.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    pub name: &'static str,
    pub first_tick: usize,
}

/// One motion's script and needle.
#[derive(Debug, Clone)]
pub struct MotionScript {
    pub motion: Motion,
    /// The simulation's initial pose (tick "−1").
    pub initial_pose: BasePose,
    /// One commanded pose per tick.
    pub poses: Vec<BasePose>,
    pub phases: Vec<Phase>,
    /// The last tick of the insertion (the deepest point).
    pub deepest_tick: usize,
    /// The bevel is flipped just before this tick's step.
    pub flip_tick: Option<usize>,
    pub needle: NeedleShape,
    /// Needle–tissue parameters of the phantom's one region.
    pub region: RegionNeedleParams,
    /// The needle in a few words.
    pub needle_label: String,
    /// The script in a sentence.
    pub description: String,
}

impl MotionScript {
    /// The phase a tick belongs to.
    pub fn phase_of(&self, tick: usize) -> &'static str {
        self.phases.iter().rev().find(|p| p.first_tick <= tick).map_or("", |p| p.name)
    }
}

/// Builds a script tick by tick.
struct PathBuilder {
    start: BasePose,
    poses: Vec<BasePose>,
    phases: Vec<Phase>,
}

impl PathBuilder {
    fn new(start: BasePose) -> Self {
        Self { start, poses: Vec::new(), phases: Vec::new() }
    }
    fn last(&self) -> BasePose {
        self.poses.last().copied().unwrap_or(self.start)
    }
    fn phase(&mut self, name: &'static str) {
        self.phases.push(Phase { name, first_tick: self.poses.len() });
    }
    /// Straight to `to` (pose components interpolated linearly) in `duration_s`, at least one tick.
    fn linear_to(&mut self, to: BasePose, duration_s: f64) {
        let from = self.last();
        let n = ((duration_s * TICK_RATE_HZ).round() as usize).max(1);
        for k in 1..=n {
            let a = k as f64 / n as f64;
            self.poses.push(BasePose::new(
                from.x_m + a * (to.x_m - from.x_m),
                from.y_m + a * (to.y_m - from.y_m),
                from.theta_rad + a * (to.theta_rad - from.theta_rad),
            ));
        }
    }
    /// Straight to `to` at `speed_m_s` (base translation).
    fn move_to(&mut self, to: BasePose, speed_m_s: f64) {
        let from = self.last();
        self.linear_to(to, (to.x_m - from.x_m).hypot(to.y_m - from.y_m) / speed_m_s);
    }
    fn hold(&mut self, duration_s: f64) {
        let p = self.last();
        let n = (duration_s * TICK_RATE_HZ).round() as usize;
        self.poses.extend(std::iter::repeat_n(p, n));
    }
}

/// The base pose of a needle of length `length_m` at angle `theta_rad` whose tip lies `s_m` of
/// arc length beyond the entry point (negative: before it, outside the tissue).
fn pose_with_tip_at(theta_rad: f64, length_m: f64, s_m: f64) -> BasePose {
    let (sin, cos) = theta_rad.sin_cos();
    let back = length_m - s_m;
    BasePose::new(ENTRY_M[0] - back * cos, ENTRY_M[1] - back * sin, theta_rad)
}

/// A straight insertion along the line at `theta_rad` through the entry point: tip from
/// [`START_HEIGHT_M`] above the surface, [`TRAVEL_M`] of travel, a hold, and back.
fn straight(length_m: f64, theta_rad: f64, pace: Pace, with_hold: bool) -> (PathBuilder, usize) {
    // 5 mm above the surface, measured vertically, on the insertion line.
    let s0 = -START_HEIGHT_M / (-theta_rad.sin());
    let start = pose_with_tip_at(theta_rad, length_m, s0);
    let deepest = pose_with_tip_at(theta_rad, length_m, s0 + TRAVEL_M);
    let mut b = PathBuilder::new(start);
    b.phase("insert");
    b.move_to(deepest, pace.insert_m_s);
    let deepest_tick = b.poses.len() - 1;
    if with_hold && pace.hold_s > 0.0 {
        b.phase("hold");
        b.hold(pace.hold_s);
    }
    (b, deepest_tick)
}

/// The vertical angle (the needle pointing down).
pub(super) const DOWN_RAD: f64 = -std::f64::consts::FRAC_PI_2;

/// The suite's rigid needle.
fn rigid_needle() -> NeedleShape {
    NeedleShape::Rigid(RigidNeedle { length_m: RIGID_LENGTH_M })
}

/// The needle, region parameters and trajectory CSV of a shipped scene.
pub(super) fn scene_needle(name: &str) -> Result<(NeedleShape, RegionNeedleParams, &'static str)> {
    let scene = needlesim_scene::load_scene(name, &MeshLimits::default()).with_context(|| format!("scene {name}"))?;
    anyhow::ensure!(scene.params.regions.len() == 1, "scene {name}: one region expected");
    let csv = scene.example_trajectory.with_context(|| format!("scene {name} ships no trajectory"))?;
    Ok((scene.params.needle, scene.params.regions[0], csv))
}

fn needle_label_of(needle: &NeedleShape, gauge: u32) -> String {
    match needle.flexible() {
        Some(f) if f.bevel_force_ratio > 0.0 => format!(
            "flexible {gauge} G bevel tip ({:.0} mm, EI = {:.2e} N·m², {} links, bevel ratio {})",
            f.length_m * 1e3,
            f.flexural_rigidity_nm2,
            f.n_links,
            f.bevel_force_ratio
        ),
        Some(f) => {
            format!("flexible {gauge} G ({:.0} mm, EI = {:.2e} N·m², {} links)", f.length_m * 1e3, f.flexural_rigidity_nm2, f.n_links)
        }
        None => format!("rigid {:.0} mm", needle.tip_s_m() * 1e3),
    }
}

/// The script of a motion at a pace.
///
/// Errors: a shipped scene (fig4-steering, bevel-tip) that does not load or has no trajectory.
pub fn script(motion: Motion, pace: Pace) -> Result<MotionScript> {
    let v_mm_s = pace.insert_m_s * 1e3;
    let travel_mm = TRAVEL_M * 1e3;
    let region = RegionNeedleParams::default();
    match motion {
        Motion::Vertical | Motion::Oblique => {
            let angle = if motion == Motion::Oblique { OBLIQUE_ANGLE_RAD } else { 0.0 };
            let (mut b, deepest_tick) = straight(RIGID_LENGTH_M, DOWN_RAD + angle, pace, true);
            b.phase("withdraw");
            b.move_to(b.start, pace.insert_m_s);
            let how = if motion == Motion::Oblique { "along a line 40° from the vertical (towards +x)" } else { "vertically" };
            Ok(MotionScript {
                motion,
                initial_pose: b.start,
                deepest_tick,
                flip_tick: None,
                needle: rigid_needle(),
                region,
                needle_label: needle_label_of(&rigid_needle(), 0),
                description: format!(
                    "inserted {how} through the top centre, {travel_mm:.0} mm of base travel at {v_mm_s:.0} mm/s, {} s hold, withdrawn at {v_mm_s:.0} mm/s",
                    pace.hold_s
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
        Motion::Turning => {
            let (mut b, deepest_tick) = straight(RIGID_LENGTH_M, DOWN_RAD, pace, false);
            // The tip's arc length beyond the entry point, held while the needle turns about it.
            let s_tip_m = TRAVEL_M - START_HEIGHT_M;
            b.phase("turn");
            let n = (TURN_PERIODS as f64 * pace.turn_period_s * TICK_RATE_HZ).round() as usize;
            for k in 1..=n {
                let t_s = k as f64 / TICK_RATE_HZ;
                let phi = TURN_AMPLITUDE_RAD * (std::f64::consts::TAU * t_s / pace.turn_period_s).sin();
                b.poses.push(pose_with_tip_at(DOWN_RAD + phi, RIGID_LENGTH_M, s_tip_m));
            }
            b.phase("withdraw");
            b.move_to(b.start, pace.insert_m_s);
            Ok(MotionScript {
                motion,
                initial_pose: b.start,
                deepest_tick,
                flip_tick: None,
                needle: rigid_needle(),
                region,
                needle_label: needle_label_of(&rigid_needle(), 0),
                description: format!(
                    "inserted vertically {travel_mm:.0} mm at {v_mm_s:.0} mm/s, turned ±10° about the entry point ({TURN_PERIODS} sine periods of {} s, peak {:.2} rad/s), withdrawn at {v_mm_s:.0} mm/s",
                    pace.turn_period_s,
                    TURN_AMPLITUDE_RAD * std::f64::consts::TAU / pace.turn_period_s
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
        Motion::Flexible => {
            let (needle, region, csv) = scene_needle("fig4-steering")?;
            let traj = needlesim_scene::Trajectory::parse_csv(csv).context("fig4-steering.csv")?;
            let samples = &traj.samples;
            anyhow::ensure!(samples.len() >= 2, "fig4-steering.csv: at least two samples");
            let start = needlesim_scene::base_pose(samples[0].1);
            // The CSV's own insertion speed (its first segment) sets the time scale.
            let (t1, p1) = (samples[1].0 - samples[0].0, needlesim_scene::base_pose(samples[1].1));
            let csv_speed_m_s = (p1.x_m - start.x_m).hypot(p1.y_m - start.y_m) / t1;
            let time_scale = csv_speed_m_s / pace.insert_m_s;
            let mut b = PathBuilder::new(start);
            let names = ["insert", "sideways", "insert"];
            for (k, w) in samples.windows(2).enumerate() {
                b.phase(names.get(k).copied().unwrap_or("insert"));
                b.linear_to(needlesim_scene::base_pose(w[1].1), (w[1].0 - w[0].0) * time_scale);
            }
            let deepest_tick = b.poses.len() - 1;
            let last = b.last();
            b.phase("withdraw");
            b.move_to(BasePose::new(last.x_m, start.y_m, last.theta_rad), pace.insert_m_s);
            let gauge = 22;
            Ok(MotionScript {
                motion,
                initial_pose: start,
                deepest_tick,
                flip_tick: None,
                needle_label: needle_label_of(&needle, gauge),
                needle,
                region,
                description: format!(
                    "the Fig. 4 path of fig4-steering.csv at {v_mm_s:.0} mm/s: base down {:.0} mm, {:.0} mm sideways in {:.0} ms, down {:.0} mm; then withdrawn straight up at {v_mm_s:.0} mm/s",
                    (start.y_m - p1.y_m) * 1e3,
                    samples.get(2).map_or(0.0, |s| (s.1.x_m - p1.x_m) * 1e3),
                    samples.get(2).map_or(0.0, |s| (s.0 - samples[1].0) * time_scale * 1e3),
                    samples.get(3).map_or(0.0, |s| (samples[2].1.y_m - s.1.y_m) * 1e3),
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
        Motion::Bevel => {
            let (needle, region, _) = scene_needle("bevel-tip")?;
            let (mut b, deepest_tick) = straight(needle.tip_s_m(), DOWN_RAD, pace, true);
            b.phase("withdraw");
            b.move_to(b.start, pace.insert_m_s);
            // Half-way through the insertion.
            let flip_tick = deepest_tick / 2;
            Ok(MotionScript {
                motion,
                initial_pose: b.start,
                deepest_tick,
                flip_tick: Some(flip_tick),
                needle_label: needle_label_of(&needle, 20),
                needle,
                region,
                description: format!(
                    "inserted straight {travel_mm:.0} mm at {v_mm_s:.0} mm/s, the bevel flipped half-way ({:.0} mm of travel), {} s hold, withdrawn at {v_mm_s:.0} mm/s; bevel-tip's region (cutting force {} N)",
                    travel_mm / 2.0,
                    pace.hold_s,
                    region.cutting_force_n
                ),
                poses: b.poses,
                phases: b.phases,
            })
        }
    }
}

/// The simulation parameters of a script on a model: the fixture's ([`fixtures::phantom_params`])
/// with the script's needle, pose and region, the chosen contact, and no column ever computed in
/// a step.
pub fn sim_params(script: &MotionScript, model: &TissueModel, contact: ContactChoice, spacing_m: f64) -> SimParams {
    let (contact, max_needle_nodes) = match contact {
        ContactChoice::Points => (ContactModel::MaterialPoints { spacing_m, width_m: 0.0 }, MAX_POINTS),
        ContactChoice::Nodes => (ContactModel::Nodes, MAX_CAPTURED_NODES),
    };
    SimParams {
        initial_pose: script.initial_pose,
        contact,
        columns_in_step: false,
        capture_radius_m: 0.5 * needlesim_scene::mean_edge_m(model.mesh()),
        max_needle_nodes,
        regions: vec![script.region],
        tick_rate_hz: TICK_RATE_HZ,
        ..fixtures::phantom_params(script.needle)
    }
}
