//! Insertion planning that accounts for tissue deformation: the entry point, angle and depth whose
//! tip reaches a target although the insertion itself moves it, found with the simulator (the
//! real-time step function, faster than real time, on worker threads).
//!
//! # Method: a virtual target on a line across the straight aim
//!
//! Let $c$ be the target's undeformed centre, $e_0$ the straight baseline's entry point and
//! $\theta_0 = \angle(c - e_0)$ its angle, with lateral direction
//! $n_0 = (-\sin\theta_0, \cos\theta_0)$. A candidate aims at the *virtual target*
//! $v(u) = c + u\,n_0$: it enters at $e_0$ with angle $\theta(u) = \angle(v(u) - e_0)$ when that
//! angle is allowed, otherwise with the nearest allowed angle $\bar\theta$ through the point of the
//! entry segment on the line $\{v + s(\cos\bar\theta, \sin\bar\theta)\}$ (clamped to the
//! segment). The candidate's base trajectory starts with the tip a few millimetres outside the
//! entry point and advances along the axis at the insertion speed.
//!
//! Simulating a candidate gives, at every tick, the tip $p_k$ and the displaced target centre
//! $c_k$; at the tick $k^*$ of closest approach, $k^* = \arg\min_k |c_k - p_k|$, the *predicted
//! error* is $E(u) = |c_{k^*} - p_{k^*}|$ and the signed lateral miss is
//! $m(u) = (c_{k^*} - p_{k^*}) \cdot n(\theta(u))$. The depth is the tip's travel beyond the entry
//! point at $k^*$, so the axial part of the miss is zero by construction and planning is the
//! scalar root problem $m(u) = 0$.
//!
//! Each iteration simulates a two-point stencil in parallel; the first is $\{0, h_0\}$ with
//! $h_0 = \max(r, 1\,\mathrm{mm})$: the straight baseline and an aim one radius across. From all
//! candidates so far the next aim is
//! - when two candidates' misses have opposite signs, the secant root inside the tightest such
//!   bracket $[u_a, u_b]$ (regula falsi), $u = u_a - m_a (u_b - u_a) / (m_b - m_a)$, kept 10 %
//!   clear of its ends;
//! - otherwise the Newton step from the best candidate $u_b$ with the finite-difference Jacobian
//!   through its nearest neighbour $u_n$ (its stencil partner), $J = (m_n - m_b) / (u_n - u_b)$,
//!   $u = u_b - m_b / J$ ($J = -1$ if $|J| < 0.1$; the step is at most 10 mm). Without
//!   deformation $m(u) = -u$ and $J = -1$: the step is the paper's virtual-target update, move the
//!   aim by the miss.
//!
//! The next stencil is $\{u, u + \delta\}$ with $\delta$ half the step, in its direction, clamped
//! to $[0.02 h_0, h_0]$, so that an undershooting step still brackets the root.
//! It stops when some candidate has $E < \tau r$ ($\tau = 0.2$ by default) or $|m| < \tau r / 4$
//! (the lateral miss is resolved; what remains of $E$ is the axial gap the tip's push keeps
//! between it and the tissue ahead, which no aim removes), when the next aim would repeat a
//! candidate, or after `max_iterations`. The plan is the candidate with the smallest $E$.
//! The set of candidates never depends on the number of threads, so neither does the result.
//!
//! # The straight baseline
//!
//! "Aiming straight" means the line from an entry point to the target's undeformed centre. Its
//! entry point $e_0$ is where the scene's own needle axis crosses the entry segment (the line the
//! scene's author picked) when it does, else the point of the segment closest to $c$ (for a
//! straight segment, the entry whose line to the target is the most perpendicular to the
//! surface). If that line's angle is not allowed, $e_0$ moves along the segment to the nearest
//! entry whose straight line is.

use std::ops::ControlFlow;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use needlesim_core::BasePose;
use needlesim_core::num::num;
use serde::{Deserialize, Serialize};

use needlesim_scene::{Scene, Trajectory};

use crate::driver::{RunOptions, Script, ScriptedRun};

/// The shipped planning examples: (name, TOML). Each names its scene and gives the defaults of
/// `needlesim-server plan` for it.
pub const PLAN_EXAMPLES: &[(&str, &str)] = &[("fig3-plan", include_str!("../../scenes/fig3-plan.toml"))];

/// A planning problem as written in TOML (server/scenes/fig3-plan.toml).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanFile {
    /// The scene (a shipped example's name or a path).
    pub scene: String,
    pub target: String,
    /// The allowed entry segment, `[[x1, y1], [x2, y2]]`.
    pub entry_m: [[f64; 2]; 2],
    /// The allowed needle angles `[min, max]`, degrees.
    pub angles_deg: [f64; 2],
    pub speed_mm_s: f64,
}

/// The shipped planning example for a scene name, if there is one.
pub fn example_for_scene(scene_name: &str) -> Result<Option<PlanFile>> {
    find_example(PLAN_EXAMPLES, scene_name, |f: &PlanFile| &f.scene)
}

/// The first of `examples` (name, TOML text) whose scene (`scene_of`) is `scene_name`.
///
/// Errors: an example that does not parse as `T` (naming it).
pub(crate) fn find_example<T: serde::de::DeserializeOwned>(
    examples: &[(&str, &str)],
    scene_name: &str,
    scene_of: impl Fn(&T) -> &str,
) -> Result<Option<T>> {
    for (name, text) in examples {
        let f: T = toml::from_str(text).map_err(|e| anyhow::anyhow!("planning example {name}: {}", e.to_string().trim_end()))?;
        if scene_of(&f) == scene_name {
            return Ok(Some(f));
        }
    }
    Ok(None)
}

/// A planning request that is wrong: `field` names the request's field (`target`, `entry`,
/// `angles_deg`, `speed_mm_s`), which the message starts with. Typed, so that the service answers
/// INVALID_ARGUMENT from the type, not from the words.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{message}")]
pub struct PlanInputError {
    pub field: &'static str,
    pub message: String,
}

/// A [`PlanInputError`] as the planner's `anyhow` error.
pub(crate) fn input(field: &'static str, message: String) -> anyhow::Error {
    anyhow::Error::new(PlanInputError { field, message })
}

/// What to plan. Absent fields take the shipped planning example's values for the scene (if the
/// scene has one); an absent angle range allows every direction.
#[derive(Debug, Clone, Default)]
pub struct PlanRequest {
    /// The target's name in the scene.
    pub target: String,
    /// The allowed entry region: a segment of the tissue surface between two points.
    pub entry_m: Option<[[f64; 2]; 2]>,
    /// The allowed needle angles `[min, max]`, degrees (the base pose's theta).
    pub angles_deg: Option<[f64; 2]>,
    /// The insertion speed, m/s.
    pub speed_m_s: Option<f64>,
}

/// How to plan.
#[derive(Debug, Clone)]
pub struct PlanOptions {
    /// Worker threads; 0: one per available core. The result does not depend on it.
    pub threads: usize,
    /// Stop when the predicted error is below this fraction of the target radius ($\tau$).
    pub tolerance_fraction: f64,
    /// Most iterations (each simulates a two-point stencil).
    pub max_iterations: usize,
    /// How far outside the entry point the tip starts, m.
    pub start_outside_m: f64,
    /// How long the plan's trajectory holds the final pose, s.
    pub hold_s: f64,
    /// Set from outside to abandon the planning (e.g. the gRPC client went away).
    pub cancel: Option<Arc<AtomicBool>>,
    /// Most ticks one simulated insertion may take (default 10 million for the offline command;
    /// the server passes its `--max-simulate-ticks`): a very slow speed is rejected rather than
    /// simulated for hours.
    pub max_ticks_per_simulation: u64,
}

impl Default for PlanOptions {
    fn default() -> Self {
        Self {
            threads: 0,
            tolerance_fraction: 0.2,
            max_iterations: 8,
            start_outside_m: 0.005,
            hold_s: 0.2,
            cancel: None,
            max_ticks_per_simulation: crate::driver::DEFAULT_MAX_TICKS,
        }
    }
}

/// Reported after each iteration.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PlanProgress {
    pub iteration: usize,
    pub simulations: usize,
    /// The smallest predicted tip–target error so far, m.
    pub best_error_m: f64,
    /// The straight baseline's predicted error, m.
    pub straight_error_m: f64,
}

/// One simulated insertion line.
#[derive(Debug, Clone, Serialize)]
pub struct Insertion {
    /// Where the axis crosses the entry segment, m.
    pub entry_m: [f64; 2],
    /// The needle angle (base pose theta), rad.
    pub angle_rad: f64,
    /// The tip's travel beyond the entry point at the end, m.
    pub depth_m: f64,
    /// The predicted tip–target distance at closest approach, m.
    pub predicted_error_m: f64,
    /// The signed lateral miss $(c - p)\cdot n$ at closest approach, m.
    pub lateral_miss_m: f64,
    /// The tip and the displaced target centre at closest approach, m.
    pub tip_m: [f64; 2],
    pub target_m: [f64; 2],
    /// The point aimed at, m.
    pub aim_m: [f64; 2],
}

/// The result of planning.
#[derive(Debug, Clone, Serialize)]
pub struct Plan {
    pub scene: String,
    pub target: String,
    pub target_radius_m: f64,
    /// The target's undeformed centre, m.
    pub target_center_m: [f64; 2],
    pub speed_m_s: f64,
    /// The plan.
    pub plan: Insertion,
    /// Aiming straight at the target's undeformed centre from the same entry region.
    pub straight: Insertion,
    /// The plan's base trajectory `(t_s, x_m, y_m, theta_rad)`: the tip starts outside the entry
    /// point, advances at the speed to the depth and holds.
    pub trajectory: Vec<[f64; 4]>,
    /// Whether the predicted error is within the tolerance ($\tau r$).
    pub converged: bool,
    pub iterations: usize,
    pub simulations: usize,
    pub wall_s: f64,
    pub threads: usize,
}

impl Plan {
    /// Whether the plan's tip is predicted within the target radius.
    pub fn hits(&self) -> bool {
        self.plan.predicted_error_m <= self.target_radius_m
    }

    /// The trajectory in the CSV format `simulate` reads.
    pub fn trajectory_csv(&self) -> String {
        let mut s = String::from("t_s,x_m,y_m,theta_rad\n");
        for [t, x, y, th] in &self.trajectory {
            s.push_str(&format!("{t},{x},{y},{th}\n"));
        }
        s
    }

    /// The trajectory as the scene module's type.
    pub fn trajectory(&self) -> Trajectory {
        Trajectory::from_samples(self.trajectory.iter().map(|&[t, x, y, th]| (t, needlesim_scene::Pose2::new(x, y, th))).collect())
    }
}

/// The validated problem.
struct Problem {
    target_idx: usize,
    target_name: String,
    center: [f64; 2],
    radius: f64,
    seg: [[f64; 2]; 2],
    angles: [f64; 2],
    speed: f64,
    length: f64,
}

/// An insertion line: entry point and angle.
#[derive(Debug, Clone, Copy)]
struct Line {
    entry: [f64; 2],
    theta: f64,
    aim: [f64; 2],
}

/// A simulated candidate.
#[derive(Debug, Clone)]
struct Eval {
    u: f64,
    line: Line,
    miss: f64,
    distance: f64,
    depth: f64,
    tip: [f64; 2],
    target: [f64; 2],
    /// The tick of closest approach and the base pose there.
    t_closest_s: f64,
    start: BasePose,
    at_closest: BasePose,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}
fn lerp(a: [f64; 2], b: [f64; 2], w: f64) -> [f64; 2] {
    [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]
}
fn dir(theta: f64) -> [f64; 2] {
    [theta.cos(), theta.sin()]
}
fn normal(theta: f64) -> [f64; 2] {
    [-theta.sin(), theta.cos()]
}

/// `theta` shifted by whole turns into $[m - \pi, m + \pi)$, $m$ the middle of the range.
fn wrap_near(theta: f64, angles: [f64; 2]) -> f64 {
    let mid = 0.5 * (angles[0] + angles[1]);
    let tau = std::f64::consts::TAU;
    mid + (theta - mid + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI
}

fn in_range(theta: f64, angles: [f64; 2]) -> bool {
    let t = wrap_near(theta, angles);
    t >= angles[0] - 1e-12 && t <= angles[1] + 1e-12
}

/// Whether `p` lies in (or within `tol` of) a triangle of the mesh.
fn in_mesh(scene: &Scene, p: [f64; 2], tol: f64) -> bool {
    let mesh = scene.tissue.mesh();
    let nodes = mesh.nodes_m();
    mesh.triangles().iter().any(|t| {
        let (a, b, c) = (nodes[t[0]], nodes[t[1]], nodes[t[2]]);
        // Distance from p to the triangle: 0 inside, else to the nearest edge.
        let cross = |o: [f64; 2], q: [f64; 2], r: [f64; 2]| (q[0] - o[0]) * (r[1] - o[1]) - (q[1] - o[1]) * (r[0] - o[0]);
        let (d1, d2, d3) = (cross(a, b, p), cross(b, c, p), cross(c, a, p));
        let inside = (d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) || (d1 <= 0.0 && d2 <= 0.0 && d3 <= 0.0);
        inside || [(a, b), (b, c), (c, a)].iter().any(|&(q, r)| dist_to_segment(p, q, r) <= tol)
    })
}

fn dist_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let w = if l2 > 0.0 { (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
    norm(sub(p, lerp(a, b, w)))
}

fn validate(scene: &Scene, req: &PlanRequest) -> Result<Problem> {
    let defaults = example_for_scene(&scene.name)?;
    let targets = &scene.params.targets;
    let Some(target_idx) = targets.iter().position(|t| t.name == req.target) else {
        let names: Vec<&str> = targets.iter().map(|t| t.name.as_str()).collect();
        if names.is_empty() {
            return Err(input("target", format!("target: scene '{}' has no targets (a scene lists them as [[targets]])", scene.name)));
        }
        return Err(input(
            "target",
            format!(
                "target: no target named '{}' in scene '{}' (targets: {})",
                needlesim_scene::limit::quote(&req.target),
                scene.name,
                names.join(", ")
            ),
        ));
    };
    let tg = &targets[target_idx];
    let seg = match (req.entry_m, &defaults) {
        (Some(s), _) => s,
        (None, Some(d)) => d.entry_m,
        (None, None) => {
            return Err(input(
                "entry",
                format!("entry: scene '{}' has no planning example, so the entry segment must be given", scene.name),
            ));
        }
    };
    if !seg.iter().flatten().all(|v| v.is_finite()) {
        return Err(input("entry", format!("entry: the segment {seg:?} has a coordinate that is not a finite number")));
    }
    let (lo, hi) = scene.tissue.mesh().bounding_box_m();
    let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let seg_len = norm(sub(seg[1], seg[0]));
    if seg_len <= 1e-9 * size {
        return Err(input(
            "entry",
            format!(
                "entry: the segment's two points ({}, {}) and ({}, {}) coincide",
                num(seg[0][0]),
                num(seg[0][1]),
                num(seg[1][0]),
                num(seg[1][1])
            ),
        ));
    }
    for k in 0..=20 {
        let p = lerp(seg[0], seg[1], k as f64 / 20.0);
        if !in_mesh(scene, p, 1e-9 * size) {
            return Err(input(
                "entry",
                format!(
                    "entry: the point ({}, {}) of the entry segment ({}, {})–({}, {}) is outside the mesh (bounding box ({}, {})–({}, {}))",
                    num(p[0]),
                    num(p[1]),
                    num(seg[0][0]),
                    num(seg[0][1]),
                    num(seg[1][0]),
                    num(seg[1][1]),
                    num(lo[0]),
                    num(lo[1]),
                    num(hi[0]),
                    num(hi[1])
                ),
            ));
        }
    }
    let angles_deg = match (req.angles_deg, &defaults) {
        (Some(a), _) => a,
        (None, Some(d)) if req.entry_m.is_none() => d.angles_deg,
        _ => [-180.0, 180.0],
    };
    if !angles_deg.iter().all(|a| a.is_finite()) {
        return Err(input(
            "angles_deg",
            format!("angles_deg: [{}, {}] is not a pair of finite numbers", num(angles_deg[0]), num(angles_deg[1])),
        ));
    }
    if angles_deg[0] > angles_deg[1] {
        return Err(input(
            "angles_deg",
            format!(
                "angles_deg: the range [{}, {}] is empty (the first angle must not exceed the second)",
                num(angles_deg[0]),
                num(angles_deg[1])
            ),
        ));
    }
    if angles_deg[1] - angles_deg[0] > 360.0 {
        return Err(input(
            "angles_deg",
            format!("angles_deg: the range [{}, {}] spans more than 360°", num(angles_deg[0]), num(angles_deg[1])),
        ));
    }
    let speed = match (req.speed_m_s, &defaults) {
        (Some(v), _) => v,
        (None, Some(d)) => d.speed_mm_s * 1e-3,
        (None, None) => 0.01,
    };
    let max_speed = scene.params.max_base_step_m * scene.params.tick_rate_hz;
    if !(speed.is_finite() && speed > 0.0 && speed <= max_speed) {
        return Err(input(
            "speed_mm_s",
            format!(
                "speed_mm_s = {}: must be > 0 and at most {} mm/s (limits.max_base_step_m × tick_rate_hz)",
                num(speed * 1e3),
                num(max_speed * 1e3)
            ),
        ));
    }
    let length = scene.params.needle.tip_s_m();
    let reach = dist_to_segment(tg.center_m, seg[0], seg[1]);
    if reach >= length {
        return Err(input(
            "target",
            format!(
                "target: '{}' is {:.1} mm from the nearest entry point, beyond the needle's length of {:.1} mm (needle.length_m)",
                tg.name,
                reach * 1e3,
                length * 1e3
            ),
        ));
    }
    Ok(Problem {
        target_idx,
        target_name: tg.name.clone(),
        center: tg.center_m,
        radius: tg.radius_m,
        seg,
        angles: [angles_deg[0].to_radians(), angles_deg[1].to_radians()],
        speed,
        length,
    })
}

/// The straight baseline's entry point (see the module documentation).
fn straight_entry(scene: &Scene, p: &Problem) -> Result<[f64; 2]> {
    let [a, b] = p.seg;
    let ab = sub(b, a);
    let base = scene.params.initial_pose;
    let t = base.axis();
    // base + s t = a + w (b - a)
    let det = ab[0] * t[1] - ab[1] * t[0];
    let mut preferred = None;
    if det.abs() > 1e-12 {
        let d = sub(a, base.position_m());
        let w = (d[1] * t[0] - d[0] * t[1]) / det;
        let s = (ab[0] * d[1] - ab[1] * d[0]) / det;
        if (0.0..=1.0).contains(&w) && s > 0.0 {
            preferred = Some(w);
        }
    }
    let w0 = preferred.unwrap_or_else(|| {
        let l2 = dot(ab, ab);
        (dot(sub(p.center, a), ab) / l2).clamp(0.0, 1.0)
    });
    let angle_at = |w: f64| {
        let e = lerp(a, b, w);
        let d = sub(p.center, e);
        d[1].atan2(d[0])
    };
    if in_range(angle_at(w0), p.angles) {
        return Ok(lerp(a, b, w0));
    }
    let n = 2000;
    let best = (0..=n).map(|k| k as f64 / n as f64).filter(|&w| in_range(angle_at(w), p.angles)).min_by(|x, y| {
        let (dx, dy) = ((x - w0).abs(), (y - w0).abs());
        dx.total_cmp(&dy)
    });
    match best {
        Some(w) => Ok(lerp(a, b, w)),
        None => Err(input(
            "angles_deg",
            format!(
                "angles_deg: from no point of the entry segment does a straight line to target '{}' have an angle in [{:.1}, {:.1}]°",
                p.target_name,
                p.angles[0].to_degrees(),
                p.angles[1].to_degrees()
            ),
        )),
    }
}

/// The insertion line aiming at the virtual target `v` (see the module documentation).
fn line_for(p: &Problem, e0: [f64; 2], v: [f64; 2]) -> Line {
    let d = sub(v, e0);
    let theta = wrap_near(d[1].atan2(d[0]), p.angles);
    if theta >= p.angles[0] && theta <= p.angles[1] {
        return Line { entry: e0, theta, aim: v };
    }
    let th = theta.clamp(p.angles[0], p.angles[1]);
    // v + s dir(th) = a + w (b - a)
    let [a, b] = p.seg;
    let (ab, t) = (sub(b, a), dir(th));
    let det = ab[0] * t[1] - ab[1] * t[0];
    let w = if det.abs() > 1e-15 {
        let dd = sub(a, v);
        ((dd[1] * t[0] - dd[0] * t[1]) / det).clamp(0.0, 1.0)
    } else {
        0.5
    };
    Line { entry: lerp(a, b, w), theta: th, aim: v }
}

/// Simulates one insertion line until the tip is past the target (or at its deepest), returning
/// the closest approach.
fn evaluate(scene: &Scene, p: &Problem, opts: &PlanOptions, u: f64, line: Line, cancel: &AtomicBool) -> Result<Eval> {
    let eval_started = Instant::now();
    let (t, n) = (dir(line.theta), normal(line.theta));
    let l = p.length;
    let outside = opts.start_outside_m;
    // The tip may go 20 mm past the target's depth along this axis, within the needle's length.
    let target_depth = dot(sub(p.center, line.entry), t);
    let max_depth = (target_depth + 0.02).min(0.98 * l).max(0.0);
    let base_at = |depth: f64| {
        let q = [line.entry[0] + (depth - l) * t[0], line.entry[1] + (depth - l) * t[1]];
        BasePose::new(q[0], q[1], line.theta)
    };
    let start = base_at(-outside);
    let end = base_at(max_depth);
    let span = (outside + max_depth) / p.speed;
    let traj = Trajectory::from_samples(vec![(0.0, needlesim_scene::pose2(start)), (span, needlesim_scene::pose2(end))]);
    // The run driver starts the simulation at the trajectory's first pose, `start`.
    let run_opts = RunOptions { max_ticks: opts.max_ticks_per_simulation, ..RunOptions::default() };
    let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(&traj), run_opts)?;
    let rate = scene.params.tick_rate_hz;
    let pass_m = 0.003 + 2.0 * p.radius;
    // (distance, tick, tip, target, lateral miss) at the closest approach so far.
    type Closest = (f64, u64, [f64; 2], [f64; 2], f64);
    let mut best: Option<Closest> = None;
    loop {
        let k = run.next_k();
        if k < run.ticks_total() && k % 64 == 0 && cancel.load(Ordering::Relaxed) {
            bail!("planning cancelled");
        }
        let Some(tick) = run.next_tick()? else { break };
        let (k, out) = (tick.k, run.output());
        let tip = out.tip_m;
        let tg = out.targets.get(p.target_idx).context("the simulation reports no such target")?;
        let d = sub(tg.position_m, tip);
        let dist = norm(d);
        if best.is_none_or(|b| dist < b.0) {
            best = Some((dist, k, tip, tg.position_m, dot(d, n)));
        }
        // Past the target along the axis, and moving away from it: stop.
        if dot(d, t) < -pass_m {
            break;
        }
    }
    let (distance, k, tip, target, miss) = best.context("no tick was simulated")?;
    tracing::debug!(u, ticks = run.sim().stats().ticks, elapsed_ms = eval_started.elapsed().as_secs_f64() * 1e3, "candidate simulated");
    let t_closest_s = k as f64 / rate;
    Ok(Eval {
        u,
        line,
        miss,
        distance,
        depth: dot(sub(tip, line.entry), t),
        tip,
        target,
        t_closest_s,
        start,
        at_closest: needlesim_scene::base_pose(traj.pose_at(t_closest_s)),
    })
}

/// Evaluates candidates on `threads` workers; the results are in the candidates' order.
fn evaluate_all(
    scene: &Scene,
    p: &Problem,
    opts: &PlanOptions,
    cands: &[(f64, Line)],
    threads: usize,
    cancel: &AtomicBool,
) -> Result<Vec<Eval>> {
    let next = AtomicUsize::new(0);
    let workers = threads.clamp(1, cands.len().max(1));
    let mut results: Vec<Option<Result<Eval>>> = (0..cands.len()).map(|_| None).collect();
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                s.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(&(u, line)) = cands.get(i) else { break };
                        mine.push((i, evaluate(scene, p, opts, u, line, cancel)));
                    }
                    mine
                })
            })
            .collect();
        for h in handles {
            match h.join() {
                Ok(mine) => {
                    for (i, r) in mine {
                        results[i] = Some(r);
                    }
                }
                Err(_) => {
                    // A panicking worker: report it rather than propagate the panic.
                    for r in results.iter_mut().filter(|r| r.is_none()) {
                        *r = Some(Err(anyhow::anyhow!("a planning worker panicked")));
                    }
                }
            }
        }
    });
    results.into_iter().map(|r| r.unwrap_or_else(|| Err(anyhow::anyhow!("a candidate was not evaluated")))).collect()
}

fn insertion(e: &Eval) -> Insertion {
    Insertion {
        entry_m: e.line.entry,
        angle_rad: e.line.theta,
        depth_m: e.depth,
        predicted_error_m: e.distance,
        lateral_miss_m: e.miss,
        tip_m: e.tip,
        target_m: e.target,
        aim_m: e.line.aim,
    }
}

/// The candidate with the smallest predicted error (the first of equals).
fn best_of(all: &[Eval]) -> &Eval {
    all.iter().reduce(|a, b| if b.distance < a.distance { b } else { a }).expect("candidates were evaluated")
}

/// The next aim $u$: the secant root inside the tightest bracket of a sign change of the lateral
/// miss when there is one (regula falsi), else a Newton step from the best candidate with the
/// secant slope through its nearest neighbour in $u$ ($-1$, the virtual-target step, when that
/// slope is degenerate), at most 10 mm.
fn next_aim(all: &[Eval], best: &Eval) -> f64 {
    let mut pts: Vec<(f64, f64)> = all.iter().map(|e| (e.u, e.miss)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.dedup_by(|a, b| a.0 == b.0);
    let bracket =
        pts.windows(2).filter(|w| w[0].1.signum() != w[1].1.signum()).min_by(|x, y| (x[1].0 - x[0].0).total_cmp(&(y[1].0 - y[0].0)));
    if let Some(w) = bracket {
        let ((u0, m0), (u1, m1)) = (w[0], w[1]);
        let root = u0 - m0 * (u1 - u0) / (m1 - m0);
        // Keep clear of the ends, where regula falsi stalls.
        let margin = 0.1 * (u1 - u0);
        return root.clamp(u0 + margin, u1 - margin);
    }
    let neighbour = pts.iter().filter(|q| q.0 != best.u).min_by(|x, y| (x.0 - best.u).abs().total_cmp(&(y.0 - best.u).abs()));
    let slope = neighbour.map(|&(u, m)| (m - best.miss) / (u - best.u)).filter(|j| j.abs() >= 0.1).unwrap_or(-1.0);
    best.u + (-best.miss / slope).clamp(-0.01, 0.01)
}

/// Checks a planning problem without simulating: the errors `plan` would give for bad input,
/// each naming the field (`target`, `entry`, `angles_deg`, `speed_mm_s`).
pub fn validate_request(scene: &Scene, req: &PlanRequest, opts: &PlanOptions) -> Result<()> {
    let p = validate(scene, req)?;
    check_ticks(scene, &p, opts)?;
    straight_entry(scene, &p)?;
    Ok(())
}

/// The longest simulated insertion (from outside to the needle's full length) within the limit.
fn check_ticks(scene: &Scene, p: &Problem, opts: &PlanOptions) -> Result<()> {
    let path_m = opts.start_outside_m + p.length;
    let rate_hz = scene.params.tick_rate_hz;
    let ticks = (path_m / p.speed * rate_hz).ceil();
    if ticks.is_nan() || ticks > opts.max_ticks_per_simulation as f64 {
        let e = needlesim_scene::limit::SizeLimit {
            what: format!(
                "a simulated insertion at this speed ({} m from outside to the needle's full length in {} s at {} Hz)",
                num((path_m * 1e6).round() / 1e6),
                num(path_m / p.speed),
                num(rate_hz)
            ),
            amount: ticks,
            limit: opts.max_ticks_per_simulation,
            unit: "ticks",
            hint: String::new(),
        };
        return Err(anyhow::Error::new(e).context(format!("speed_mm_s = {}", num(p.speed * 1e3))));
    }
    Ok(())
}

/// Plans an insertion into `scene` reaching `req.target` (see the module documentation).
/// `progress` is called after each iteration; returning `Break` abandons the planning.
pub fn plan(
    scene: &Scene,
    req: &PlanRequest,
    opts: &PlanOptions,
    mut progress: impl FnMut(&PlanProgress) -> ControlFlow<()>,
) -> Result<Plan> {
    let started = Instant::now();
    let p = validate(scene, req)?;
    check_ticks(scene, &p, opts)?;
    let e0 = straight_entry(scene, &p)?;
    let d0 = sub(p.center, e0);
    let theta0 = d0[1].atan2(d0[0]);
    let n0 = normal(theta0);
    let threads = if opts.threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { opts.threads };
    let cancel_own = Arc::new(AtomicBool::new(false));
    let cancel = opts.cancel.clone().unwrap_or(cancel_own);
    let tol = if p.radius > 0.0 { opts.tolerance_fraction * p.radius } else { 1e-4 };
    let lateral_tol = 0.25 * tol;
    // At least 1 mm, so that the first finite difference spans a mesh-scale change of the aim.
    let h0 = p.radius.max(1e-3);
    let line_at = |u: f64| {
        let v = [p.center[0] + u * n0[0], p.center[1] + u * n0[1]];
        // The straight baseline aims at the centre from e0 itself, whatever the angle range.
        if u == 0.0 { Line { entry: e0, theta: wrap_near(theta0, p.angles), aim: v } } else { line_for(&p, e0, v) }
    };
    let mut all: Vec<Eval> = Vec::new();
    // The first stencil: the straight baseline and an aim one radius across.
    let mut stencil = [0.0, h0];
    let mut iterations = 0;
    let mut converged = false;
    while iterations < opts.max_iterations.max(1) {
        iterations += 1;
        let cands = stencil.map(|u| (u, line_at(u)));
        let evals = evaluate_all(scene, &p, opts, &cands, threads, &cancel).context("simulating the candidates")?;
        all.extend(evals);
        let best = best_of(&all);
        let pr =
            PlanProgress { iteration: iterations, simulations: all.len(), best_error_m: best.distance, straight_error_m: all[0].distance };
        tracing::debug!(iteration = iterations, u = best.u, miss_mm = best.miss * 1e3, best_error_mm = best.distance * 1e3, "planning");
        // Converged: the error is within tolerance, or its lateral part is resolved (what is left
        // is the gap the tip's push keeps ahead of it, which no aim changes).
        if best.distance < tol || best.miss.abs() < lateral_tol {
            converged = true;
            let _ = progress(&pr);
            break;
        }
        if progress(&pr).is_break() {
            cancel.store(true, Ordering::Relaxed);
            bail!("planning cancelled");
        }
        let next = next_aim(&all, best);
        if all.iter().any(|e| (e.u - next).abs() < 1e-7) {
            break; // stagnated: the aim would repeat a candidate
        }
        // The second stencil point continues past the prediction by half the step, so that an
        // undershooting step still brackets the root.
        let delta = (0.5 * (next - best.u).abs()).clamp(0.02 * h0, h0) * (next - best.u).signum();
        stencil = [next, next + delta];
    }
    let straight = &all[0];
    let best = best_of(&all);
    let t1 = best.t_closest_s;
    let end = best.at_closest;
    let mut trajectory = vec![[0.0, best.start.x_m, best.start.y_m, best.start.theta_rad], [t1, end.x_m, end.y_m, end.theta_rad]];
    if opts.hold_s > 0.0 {
        trajectory.push([t1 + opts.hold_s, end.x_m, end.y_m, end.theta_rad]);
    }
    Ok(Plan {
        scene: scene.name.clone(),
        target: p.target_name.clone(),
        target_radius_m: p.radius,
        target_center_m: p.center,
        speed_m_s: p.speed,
        plan: insertion(best),
        straight: insertion(straight),
        trajectory,
        converged,
        iterations,
        simulations: all.len(),
        wall_s: started.elapsed().as_secs_f64(),
        threads,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_core::MeshLimits;

    fn fig3() -> Scene {
        needlesim_scene::load_scene("fig3-target", &MeshLimits::default()).unwrap()
    }

    /// Issue 35 (hostile pass, finding 5): a refused request's numbers are written compactly
    /// (1e300, not 301 digits), wherever the message quotes them.
    #[test]
    fn issue_35_refused_plan_numbers_are_written_compactly() {
        let scene = fig3();
        let refused = |r: PlanRequest| format!("{:#}", validate(&scene, &r).err().expect("refused"));
        let req = |entry_m, angles_deg, speed_m_s| PlanRequest { target: "biopsy".into(), entry_m, angles_deg, speed_m_s };
        for (r, want) in [
            (req(None, Some([1e300, -1e300]), None), "angles_deg: the range [1e300, -1e300] is empty"),
            (req(None, Some([-1e300, 1e300]), None), "angles_deg: the range [-1e300, 1e300] spans more than 360°"),
            (
                req(Some([[1e300, 1e300], [1e300, 1e300]]), None, None),
                "entry: the segment's two points (1e300, 1e300) and (1e300, 1e300) coincide",
            ),
            (req(Some([[0.0, 0.06], [1e300, 0.06]]), None, None), "of the entry segment (0, 0.06)–(1e300, 0.06) is outside the mesh"),
            (req(None, None, Some(1e300)), "speed_mm_s = 1e303: must be > 0"),
            (req(None, None, Some(-1e-300)), "speed_mm_s = -1e-297: must be > 0"),
        ] {
            let e = refused(r);
            assert!(e.contains(want) && e.len() < 300, "{e}");
        }
    }

    /// Issue 35 (finding 6b): `speed_mm_s = 1e-300` was "18446744073709551615 ticks" (a
    /// saturated count): the message says the path, its time and the count as they are.
    #[test]
    fn issue35_a_speed_too_slow_names_the_time_and_the_count_unsaturated() {
        let scene = fig3();
        let req = PlanRequest { target: "biopsy".into(), speed_m_s: Some(1e-300 * 1e-3), ..Default::default() };
        let e = validate_request(&scene, &req, &PlanOptions::default()).unwrap_err();
        assert!(e.chain().any(|c| c.downcast_ref::<needlesim_scene::limit::SizeLimit>().is_some()), "still a size limit: {e:#}");
        let e = format!("{e:#}");
        assert!(e.starts_with("speed_mm_s = 1e-300: a simulated insertion at this speed ("), "{e}");
        assert!(e.contains(" s at 1000 Hz) is ") && e.contains("e30") && e.contains("ticks, over the limit of 1000000 ticks"), "{e}");
        assert!(!e.contains("18446744073709551615") && e.len() < 300, "{e}");
    }

    #[test]
    fn the_example_parses_and_the_baseline_is_the_scenes_own_axis() {
        let scene = fig3();
        let d = example_for_scene("fig3-target").unwrap().unwrap();
        assert_eq!(d.target, "biopsy");
        let p = validate(&scene, &PlanRequest { target: "biopsy".into(), ..Default::default() }).unwrap();
        let e0 = straight_entry(&scene, &p).unwrap();
        assert!((e0[0] - 0.02).abs() < 1e-9 && (e0[1] - 0.06).abs() < 1e-9, "{e0:?}");
    }

    #[test]
    fn lines_clamp_the_angle_and_move_the_entry() {
        let scene = fig3();
        let p = validate(&scene, &PlanRequest { target: "biopsy".into(), angles_deg: Some([-45.0, -35.0]), ..Default::default() }).unwrap();
        let e0 = [0.02, 0.06];
        // Aiming far below the target needs a steeper angle than allowed: the angle clamps to -45°
        // and the entry moves back (left) so that the line still passes through the virtual target.
        let v = [p.center[0], p.center[1] - 0.02];
        let l = line_for(&p, e0, v);
        assert!((l.theta - (-45f64).to_radians()).abs() < 1e-12);
        let lateral = dot(sub(v, l.entry), normal(l.theta));
        assert!(lateral.abs() < 1e-12, "{lateral}");
        assert!((l.entry[1] - 0.06).abs() < 1e-12 && l.entry[0] > 0.0 && l.entry[0] < 0.02, "{:?}", l.entry);
    }

    #[test]
    fn bad_inputs_name_the_field() {
        let scene = fig3();
        let err = |r: PlanRequest| format!("{:#}", plan(&scene, &r, &PlanOptions::default(), |_| ControlFlow::Continue(())).unwrap_err());
        let e = err(PlanRequest { target: "tumour".into(), ..Default::default() });
        assert!(e.contains("target: no target named 'tumour'") && e.contains("biopsy"), "{e}");
        let e = err(PlanRequest { target: "biopsy".into(), angles_deg: Some([-20.0, -60.0]), ..Default::default() });
        assert!(e.contains("angles_deg: the range [-20, -60] is empty"), "{e}");
        let e = err(PlanRequest { target: "biopsy".into(), entry_m: Some([[0.0, 0.2], [0.04, 0.2]]), ..Default::default() });
        assert!(e.contains("entry: the point (0, 0.2)") && e.contains("outside the mesh"), "{e}");
        let e = err(PlanRequest { target: "biopsy".into(), speed_m_s: Some(-1.0), ..Default::default() });
        assert!(e.contains("speed_mm_s = -1000"), "{e}");
        let e = err(PlanRequest { target: "biopsy".into(), angles_deg: Some([10.0, 30.0]), ..Default::default() });
        assert!(e.contains("angles_deg: from no point of the entry segment"), "{e}");
    }

    #[test]
    fn the_plan_does_not_depend_on_the_thread_count_and_can_be_cancelled() {
        let scene = fig3();
        let req = PlanRequest { target: "biopsy".into(), ..Default::default() };
        let run = |threads| plan(&scene, &req, &PlanOptions { threads, ..Default::default() }, |_| ControlFlow::Continue(())).unwrap();
        let (a, b) = (run(1), run(3));
        assert_eq!(a.trajectory, b.trajectory);
        assert_eq!(a.plan.predicted_error_m.to_bits(), b.plan.predicted_error_m.to_bits());
        assert_eq!(a.simulations, b.simulations);
        assert!(a.hits() && a.straight.predicted_error_m > a.target_radius_m, "{a:?}");
        // Planning moved the aim: the plan is not the straight line.
        assert!((a.plan.angle_rad - a.straight.angle_rad).abs() > 1e-3);
        let mut calls = 0;
        let e = plan(&scene, &req, &PlanOptions::default(), |_| {
            calls += 1;
            ControlFlow::Break(())
        })
        .unwrap_err();
        assert!(e.to_string().contains("cancelled") && calls == 1, "{e}");
    }

    #[test]
    fn an_unreachable_target_is_an_error() {
        let text = include_str!("../../scenes/fig3-target.toml").replace("length_m = 0.1", "length_m = 0.03");
        let scene = needlesim_scene::parse_scene(&text, std::path::Path::new("."), &MeshLimits::default()).unwrap();
        let e = plan(&scene, &PlanRequest { target: "biopsy".into(), ..Default::default() }, &PlanOptions::default(), |_| {
            ControlFlow::Continue(())
        })
        .unwrap_err();
        assert!(format!("{e:#}").contains("beyond the needle's length of 30.0 mm (needle.length_m)"), "{e:#}");
    }
}
