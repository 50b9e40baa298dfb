//! Insertion planning in 3D through the simulation (issue 18): the entry point, direction and —
//! for a bevel-tip needle — the rotation schedule whose tip reaches a target although the
//! insertion deforms the tissue, keeping a clearance from the structures to spare.
//!
//! # Structures to spare
//!
//! A structure is a region of the 3D scene given by a `sphere` (box meshes: a vessel, a nerve;
//! [`needlesim_scene::scene3d`]), named in the request with a clearance $c$. Like a target it is a
//! sphere of the tissue that moves with it: the simulation tracks its displaced centre $s_k$
//! ([`needlesim_core::sim3::targets`]) and the plan's clearance is
//! $$\min_k\ |p_k - s_k| - R - \tfrac{d}{2}$$
//! over the ticks of the insertion, $p_k$ the tip, $R$ the sphere's radius, $d$ the needle's
//! diameter: the needle occupies the tissue its tip cut, so the tip's path through the moving
//! tissue is the shaft's. A candidate keeps the structure when this is at least $c$.
//!
//! # Method
//!
//! Let $c$ be the target's undeformed centre and $e$ an entry point on a face of the mesh's
//! bounding box (the request's `entry_m`, a box face). A candidate aims at a *virtual target*
//! $v(u) = c + u_1 e_1 + u_2 e_2$, $(e_1, e_2)$ an orthonormal pair across the straight direction
//! $d_0 = (c - e)/|c - e|$: the base moves along $d(u) = (v - e)/|v - e|$ through $e$, the tip
//! starting `start_outside_m` outside, at the insertion speed, rolled as its schedule says.
//! Simulating it gives the tip $p_k$ and the displaced target centre $c_k$; at the closest
//! approach $k^*$ the error is $E(u) = |c_{k^*} - p_{k^*}|$ and the lateral miss
//! $m(u) = ((c_{k^*} - p_{k^*})\cdot e_1, (c_{k^*} - p_{k^*})\cdot e_2)$; the depth is the tip's
//! travel at $k^*$, so planning is the root problem $m(u) = 0$ in two unknowns.
//!
//! Each iteration simulates the stencil $\{u, u + h e_1, u + h e_2\}$ in parallel (one candidate
//! per worker thread, `threads` of them: all cores by default) and takes the Newton step with
//! the finite-difference Jacobian $J = [\,(m(u + h e_1) - m(u))/h,\ (m(u + h e_2) - m(u))/h\,]$,
//! $u \leftarrow u - J^{-1} m(u)$ ($J = -I$ when it is ill-conditioned, $|\det J| < 0.05$; the
//! step at most 10 mm): without deformation $m(u) = -u$ and the step is "move the aim by the
//! miss". $h$ is $\max(r, 1\,\mathrm{mm})$ on the first iteration, then half the last step,
//! within $[0.02, 1]\,h_0$. It stops when a candidate has $E < \tau r$, or $E < r$ and
//! $|m| < \tau r / 4$ (the lateral miss is resolved; what remains of $E$ is the axial gap the
//! tip's push keeps between it and the tissue ahead), or after `max_iterations`. The plan is, among the candidates that keep
//! every clearance, the one with the smallest $E$ (none keeps it: the largest clearance); it has
//! converged when the search stopped on the tolerance, the clearance is kept and $E < r$. The
//! candidates never depend on the thread count, so neither does the plan.
//!
//! **Entry (symmetric needles).** When the straight line from $e$ to $c$ passes a structure
//! closer than $R + c_s + d/2 + 1\,\mathrm{mm}$ (the margin for the deformation the aim search
//! corrects), the entry moves on its face within `entry_radius_m` of $e$: rings of 1 mm up to
//! the radius, 24 points each, the nearest point whose straight line to $c$ clears every
//! structure by that much (ties: the first in ring order). The aim search then runs from there.
//!
//! **Rotation schedule (bevel needles).** A bevel needle curves towards its bevel (the base
//! frame's $n$ turned by its roll, [`needlesim_core::sim3::flex`]), so its path bulges away from
//! the bevel side: a path of constant curvature $\kappa$ from $e$ to the target at distance $L$
//! lies $y(s) = \kappa s (L - s)/2$ off the chord. Every schedule of rolls changes the sign of the
//! curvature along the path, and since the chord's Green's function is positive, the single arc
//! bulges furthest at every depth: the planner rolls the bevel once, before the tip enters, to
//! face the nearest structure across the chord (its direction from the chord projected across
//! $d_0$; $e_1$ when it lies on the chord), so the path passes it on the far side, and runs the
//! aim search with that schedule from the same entry point. The schedule is a list of
//! `(depth, roll)` steps ([`RollStep`]: from that tip depth on, the base's roll about its axis;
//! the base holds its position while it turns, at `ROLL_RATE_RAD_S`); the plan's trajectory
//! carries it, so `simulate` replays it.
//!
//! **Straight aim.** "Aiming straight" is the line from $e$ (the request's entry) to $c$ with
//! the scene's initial roll: the planner simulates it and reports its error and clearance.

use std::ops::ControlFlow;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use needlesim_core::d3::TetTissueModel;
use needlesim_core::num::num;
use needlesim_core::sim3::{Simulation3, Target3};
use needlesim_scene::{Scene3d, Trajectory3};
use needlesim_trajectory::Pose3;
use needlesim_trajectory::pose3::quat_from_axis_roll;
use serde::{Deserialize, Serialize};

use crate::driver::{RunOptions, Script, ScriptedRun};
use crate::plan::{PlanOptions, PlanProgress, input};
use crate::scripted::ScriptedSim;
use crate::simulate3::sim3_params;

/// How fast the planned trajectory rolls the base about its axis, rad/s.
pub const ROLL_RATE_RAD_S: f64 = 10.0;
/// The margin added to a structure's radius and clearance when choosing the entry point, m.
pub const ENTRY_MARGIN_M: f64 = 0.001;

/// The shipped 3D planning examples: (name, TOML). Each names its 3D scene and gives the defaults
/// of `needlesim-server plan` for it.
pub const PLAN3_EXAMPLES: &[(&str, &str)] = &[
    ("behind-vessel-plan", include_str!("../../scenes/behind-vessel-plan.toml")),
    ("behind-vessel-bevel-plan", include_str!("../../scenes/behind-vessel-bevel-plan.toml")),
];

/// A 3D planning problem as written in TOML (server/scenes/behind-vessel-plan.toml).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan3File {
    /// The 3D scene (a shipped example's name or a path).
    pub scene: String,
    pub target: String,
    /// The entry point, on a face of the mesh's bounding box, m.
    pub entry_m: [f64; 3],
    /// How far from `entry_m` on its face the entry may move (symmetric needles), m.
    #[serde(default)]
    pub entry_radius_m: f64,
    /// The structures to spare: names of sphere regions of the scene.
    #[serde(default)]
    pub avoid: Vec<String>,
    /// The clearance to keep from them, m.
    #[serde(default)]
    pub clearance_m: f64,
    pub speed_mm_s: f64,
}

/// The shipped 3D planning example for a scene name, if there is one.
pub fn example3_for_scene(scene_name: &str) -> Result<Option<Plan3File>> {
    crate::plan::find_example(PLAN3_EXAMPLES, scene_name, |f: &Plan3File| &f.scene)
}

/// What to plan in 3D. Absent fields take the shipped planning example's values for the scene.
#[derive(Debug, Clone, Default)]
pub struct Plan3Request {
    /// The target's name in the scene.
    pub target: String,
    /// The entry point, on a face of the mesh's bounding box, m.
    pub entry_m: Option<[f64; 3]>,
    /// How far the entry may move on its face, m (symmetric needles).
    pub entry_radius_m: Option<f64>,
    /// Sphere regions of the scene to spare; `None`: the example's.
    pub avoid: Option<Vec<String>>,
    /// The clearance to keep from them, m.
    pub clearance_m: Option<f64>,
    /// The insertion speed, m/s.
    pub speed_m_s: Option<f64>,
}

/// From a tip depth on, the base's roll about its axis (rad, relative to the straight aim's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RollStep {
    pub depth_m: f64,
    pub roll_rad: f64,
}

/// One simulated insertion.
#[derive(Debug, Clone, Serialize)]
pub struct Insertion3 {
    /// Where the axis crosses the entry face, m.
    pub entry_m: [f64; 3],
    /// The unit shaft direction, base to tip.
    pub direction: [f64; 3],
    /// The rotation schedule (empty: no roll).
    pub rolls: Vec<RollStep>,
    /// The commanded tip depth beyond the entry point (the base's travel) at the closest
    /// approach, m: where the plan's trajectory stops.
    pub depth_m: f64,
    /// The predicted tip–target distance at closest approach, m.
    pub predicted_error_m: f64,
    /// The lateral miss $m$ in $(e_1, e_2)$, m.
    pub lateral_miss_m: [f64; 2],
    /// The tip and the displaced target centre at closest approach, m.
    pub tip_m: [f64; 3],
    pub target_m: [f64; 3],
    /// The (virtual) point aimed at, m.
    pub aim_m: [f64; 3],
    /// Per structure (request order): the smallest clearance along the insertion, m (negative:
    /// the needle crossed it).
    pub clearances_m: Vec<f64>,
}

impl Insertion3 {
    /// The smallest clearance over the structures (infinite without any).
    pub fn min_clearance_m(&self) -> f64 {
        self.clearances_m.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// A structure kept clear of.
#[derive(Debug, Clone, Serialize)]
pub struct Structure3 {
    pub name: String,
    pub center_m: [f64; 3],
    pub radius_m: f64,
}

/// The result of planning in 3D.
#[derive(Debug, Clone, Serialize)]
pub struct Plan3 {
    pub scene: String,
    pub target: String,
    pub target_radius_m: f64,
    pub target_center_m: [f64; 3],
    pub structures: Vec<Structure3>,
    pub clearance_m: f64,
    pub bevel: bool,
    pub speed_m_s: f64,
    pub plan: Insertion3,
    /// Aiming straight at the target's undeformed centre from the request's entry point.
    pub straight: Insertion3,
    /// The plan's base trajectory `(t_s, x_m, y_m, z_m, qw, qx, qy, qz)`: the tip starts
    /// outside the entry point, advances at the speed (holding while it rolls) to the depth, and
    /// holds.
    pub trajectory: Vec<[f64; 8]>,
    /// Whether the predicted error is within the tolerance and the clearance kept.
    pub converged: bool,
    pub iterations: usize,
    pub simulations: usize,
    pub wall_s: f64,
    pub threads: usize,
}

impl Plan3 {
    /// Whether the plan's tip is predicted within the target radius with every clearance kept.
    pub fn hits(&self) -> bool {
        self.plan.predicted_error_m < self.target_radius_m && self.plan.min_clearance_m() >= self.clearance_m
    }

    /// The trajectory in the 3D CSV format `simulate` reads.
    pub fn trajectory_csv(&self) -> String {
        let mut s = String::from("t_s,x_m,y_m,z_m,qw,qx,qy,qz\n");
        for [t, x, y, z, qw, qx, qy, qz] in &self.trajectory {
            s.push_str(&format!("{t},{x},{y},{z},{qw},{qx},{qy},{qz}\n"));
        }
        s
    }

    /// The trajectory as the scene module's type (what `simulate` replays).
    pub fn trajectory3(&self) -> Trajectory3 {
        Trajectory3::from_samples(
            self.trajectory.iter().map(|&[t, x, y, z, qw, qx, qy, qz]| (t, Pose3::new([x, y, z], [qw, qx, qy, qz]))).collect(),
        )
    }
}

/// The validated problem.
struct Problem3 {
    target_idx: usize,
    target_name: String,
    center: [f64; 3],
    radius: f64,
    entry: [f64; 3],
    /// The entry face: its axis and coordinate.
    face: (usize, f64),
    entry_radius: f64,
    structures: Vec<Structure3>,
    clearance: f64,
    needle_radius: f64,
    /// The bevel's side (+1: towards the base frame's n).
    bevel_side: f64,
    speed: f64,
    length: f64,
    bevel: bool,
    /// The scene's initial roll about the shaft (the straight aim's).
    roll0: f64,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(s: f64, a: [f64; 3]) -> [f64; 3] {
    [s * a[0], s * a[1], s * a[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    scale(1.0 / norm(a), a)
}

/// An orthonormal pair across the unit `d`: $e_1$ the horizontal one (perpendicular to $d$ and
/// world $z$; world $x$ when $d$ is vertical), $e_2 = d \times e_1$.
fn across(d: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let h = cross([0.0, 0.0, 1.0], d);
    let e1 = if norm(h) > 1e-9 { unit(h) } else { unit(cross(d, [0.0, 1.0, 0.0])) };
    (e1, cross(d, e1))
}

/// The distance from `p` to the segment `[a, b]`.
fn dist_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let w = if l2 > 0.0 { (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
    norm(sub(p, add(a, scale(w, ab))))
}

/// The roll about the shaft of a pose relative to the shortest rotation taking $e_x$ to its
/// axis (the `base_axis` + `base_roll_rad` convention of the 3D scenes).
fn roll_of(p: &Pose3) -> f64 {
    let f = p.frame();
    let q0 = Pose3::new([0.0; 3], quat_from_axis_roll(f[0], 0.0)).frame();
    // n = cos φ n0 + sin φ b0.
    dot(f[1], q0[2]).atan2(dot(f[1], q0[1]))
}

fn validate(scene: &Scene3d, req: &Plan3Request) -> Result<Problem3> {
    let defaults = example3_for_scene(&scene.name)?;
    let Some(target_idx) = scene.targets.iter().position(|t| t.name == req.target) else {
        let names: Vec<&str> = scene.targets.iter().map(|t| t.name.as_str()).collect();
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
    let tg = &scene.targets[target_idx];
    let entry = match (req.entry_m, &defaults) {
        (Some(e), _) => e,
        (None, Some(d)) => d.entry_m,
        (None, None) => {
            return Err(input(
                "entry",
                format!("entry: scene '{}' has no 3D planning example, so the entry point must be given", scene.name),
            ));
        }
    };
    if !entry.iter().all(|v| v.is_finite()) {
        return Err(input("entry", format!("entry: {entry:?} has a coordinate that is not a finite number")));
    }
    let (lo, hi) = bounding_box(scene);
    let size = norm(sub(hi, lo));
    let tol = 1e-6 * size;
    let face = (0..3).flat_map(|a| [(a, lo[a]), (a, hi[a])]).find(|&(a, v)| (entry[a] - v).abs() <= tol);
    let inside = (0..3).all(|a| entry[a] >= lo[a] - tol && entry[a] <= hi[a] + tol);
    let Some(face) = face.filter(|_| inside) else {
        return Err(input(
            "entry",
            format!(
                "entry: ({}, {}, {}) is not on a face of the mesh's bounding box ({:?}–{:?})",
                num(entry[0]),
                num(entry[1]),
                num(entry[2]),
                lo,
                hi
            ),
        ));
    };
    let entry_radius = req.entry_radius_m.or(defaults.as_ref().map(|d| d.entry_radius_m)).unwrap_or(0.0);
    if !(entry_radius.is_finite() && entry_radius >= 0.0) {
        return Err(input("entry_radius_m", format!("entry_radius_m = {}: must be a finite number ≥ 0", num(entry_radius))));
    }
    let avoid = req.avoid.clone().or(defaults.as_ref().map(|d| d.avoid.clone())).unwrap_or_default();
    let mut structures = Vec::new();
    for name in &avoid {
        let Some(r) = scene.regions.iter().find(|r| &r.name == name) else {
            let names: Vec<&str> = scene.regions.iter().filter(|r| r.sphere_m.is_some()).map(|r| r.name.as_str()).collect();
            return Err(input(
                "avoid",
                format!(
                    "avoid: no region named '{}' in scene '{}' (sphere regions: {})",
                    needlesim_scene::limit::quote(name),
                    scene.name,
                    if names.is_empty() { "none".to_string() } else { names.join(", ") }
                ),
            ));
        };
        let Some((c, rad)) = r.sphere_m else {
            return Err(input(
                "avoid",
                format!("avoid: region '{name}' is not given by a sphere (structures to spare are sphere regions)"),
            ));
        };
        structures.push(Structure3 { name: name.clone(), center_m: c, radius_m: rad });
    }
    let clearance = req.clearance_m.or(defaults.as_ref().map(|d| d.clearance_m)).unwrap_or(0.0);
    if !(clearance.is_finite() && clearance >= 0.0) {
        return Err(input("clearance_m", format!("clearance_m = {}: must be a finite number ≥ 0", num(clearance))));
    }
    let speed = match (req.speed_m_s, &defaults) {
        (Some(v), _) => v,
        (None, Some(d)) => d.speed_mm_s * 1e-3,
        (None, None) => 0.02,
    };
    let max_speed = 0.002 * scene.tick_rate_hz;
    if !(speed.is_finite() && speed > 0.0 && speed <= max_speed) {
        return Err(input(
            "speed_mm_s",
            format!("speed_mm_s = {}: must be > 0 and at most {} mm/s", num(speed * 1e3), num(max_speed * 1e3)),
        ));
    }
    let length = scene.needle.length_m;
    let reach = norm(sub(tg.center_m, entry));
    if reach + 0.02 >= length {
        return Err(input(
            "target",
            format!(
                "target: '{}' is {:.1} mm from the entry point; the needle of {:.1} mm (needle.length_m) must reach 20 mm past it",
                tg.name,
                reach * 1e3,
                length * 1e3
            ),
        ));
    }
    let bevel = scene.needle.flexible.is_some_and(|f| f.bevel_force_ratio != 0.0);
    Ok(Problem3 {
        target_idx,
        target_name: tg.name.clone(),
        center: tg.center_m,
        radius: tg.radius_m,
        entry,
        face,
        entry_radius,
        structures,
        clearance,
        needle_radius: 0.5 * scene.needle.diameter_m,
        bevel_side: scene.needle.flexible.map_or(1.0, |f| f.bevel_side),
        speed,
        length,
        bevel,
        roll0: roll_of(&scene.initial_pose),
    })
}

fn bounding_box(scene: &Scene3d) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in scene.mesh.nodes_m() {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    (lo, hi)
}

/// The smallest distance of the straight line from `e` to the target to any structure's
/// surface, less the needle's radius (infinite without structures).
fn straight_clearance(p: &Problem3, e: [f64; 3]) -> f64 {
    p.structures.iter().map(|s| dist_to_segment(s.center_m, e, p.center) - s.radius_m - p.needle_radius).fold(f64::INFINITY, f64::min)
}

/// The entry point of a symmetric needle (module docs, "Entry").
fn choose_entry(p: &Problem3) -> [f64; 3] {
    let need = p.clearance + ENTRY_MARGIN_M;
    if straight_clearance(p, p.entry) >= need || p.entry_radius <= 0.0 {
        return p.entry;
    }
    let (ax, _) = p.face;
    let (u, v) = ((ax + 1) % 3, (ax + 2) % 3);
    let rings = (p.entry_radius / 0.001).floor().max(1.0) as usize;
    for ring in 1..=rings {
        let rad = p.entry_radius * ring as f64 / rings as f64;
        for k in 0..24 {
            let a = std::f64::consts::TAU * k as f64 / 24.0;
            let mut e = p.entry;
            e[u] += rad * a.cos();
            e[v] += rad * a.sin();
            if straight_clearance(p, e) >= need {
                return e;
            }
        }
    }
    p.entry
}

/// An insertion to simulate.
#[derive(Debug, Clone)]
struct Candidate {
    entry: [f64; 3],
    dir: [f64; 3],
    aim: [f64; 3],
    rolls: Vec<RollStep>,
}

/// The base trajectory of an insertion along `dir` through `entry` to the tip depth `depth_m`
/// (module docs), then a hold of `hold_s`.
fn trajectory(p: &Problem3, c: &Candidate, roll0: f64, depth_m: f64, outside_m: f64, hold_s: f64) -> Trajectory3 {
    let l = p.length;
    let pose = |depth: f64, roll: f64| {
        let pos = add(c.entry, scale(depth - l, c.dir));
        Pose3::new(pos, quat_from_axis_roll(c.dir, roll))
    };
    let mut t = 0.0;
    let mut d = -outside_m;
    let mut roll = roll0;
    let mut samples = vec![(t, pose(d, roll))];
    for step in &c.rolls {
        let at = step.depth_m.clamp(d, depth_m);
        if at > d {
            t += (at - d) / p.speed;
            d = at;
            samples.push((t, pose(d, roll)));
        }
        let turn = roll0 + step.roll_rad - roll;
        // Sub-steps of at most π/4, so that the interpolation turns the intended way.
        let n = (turn.abs() / std::f64::consts::FRAC_PI_4).ceil() as usize;
        for k in 1..=n {
            t += turn.abs() / n as f64 / ROLL_RATE_RAD_S;
            samples.push((t, pose(d, roll + turn * k as f64 / n as f64)));
        }
        roll += turn;
    }
    if depth_m > d {
        t += (depth_m - d) / p.speed;
        samples.push((t, pose(depth_m, roll)));
    }
    if hold_s > 0.0 {
        samples.push((t + hold_s, pose(depth_m, roll)));
    }
    Trajectory3::from_samples(samples)
}

/// A simulated candidate.
#[derive(Debug, Clone)]
struct Eval {
    cand: Candidate,
    miss: [f64; 2],
    error: f64,
    depth: f64,
    tip: [f64; 3],
    target: [f64; 3],
    clearances: Vec<f64>,
}

impl Eval {
    fn insertion(&self) -> Insertion3 {
        Insertion3 {
            entry_m: self.cand.entry,
            direction: self.cand.dir,
            rolls: self.cand.rolls.clone(),
            depth_m: self.depth,
            predicted_error_m: self.error,
            lateral_miss_m: self.miss,
            tip_m: self.tip,
            target_m: self.target,
            aim_m: self.cand.aim,
            clearances_m: self.clearances.clone(),
        }
    }

    fn min_clearance(&self) -> f64 {
        self.clearances.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// What every candidate shares.
struct Ctx<'a> {
    scene: &'a Scene3d,
    model: Arc<TetTissueModel>,
    p: &'a Problem3,
    opts: &'a PlanOptions,
    basis: ([f64; 3], [f64; 3]),
    roll0: f64,
    cancel: &'a AtomicBool,
    simulations: &'a AtomicUsize,
}

/// Simulates a candidate until the tip is 5 mm past its closest approach to the target (or at
/// its deepest), returning the closest approach and the clearances.
fn evaluate(ctx: &Ctx, cand: Candidate) -> Result<Eval> {
    let p = ctx.p;
    let target_depth = dot(sub(p.center, cand.entry), cand.dir);
    let max_depth = (target_depth + 0.02).min(0.98 * p.length);
    let traj = trajectory(p, &cand, ctx.roll0, max_depth, ctx.opts.start_outside_m, 0.0);
    let first = <Simulation3 as ScriptedSim>::first_pose(&traj).map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut params = sim3_params(ctx.scene, first);
    let tg = &ctx.scene.targets[p.target_idx];
    params.targets = vec![Target3 { centre_m: tg.center_m, radius_m: tg.radius_m.max(1e-6), name_idx: 0 }];
    for (k, s) in p.structures.iter().enumerate() {
        params.targets.push(Target3 { centre_m: s.center_m, radius_m: s.radius_m, name_idx: k + 1 });
    }
    // The run driver (every approaching node's columns between steps, the convergence policy
    // `Fail`), as `simulate` runs the plan's trajectory.
    let run_opts = RunOptions { max_ticks: ctx.opts.max_ticks_per_simulation, ..RunOptions::default() };
    let mut run = ScriptedRun::new(ctx.model.clone(), params, Script::trajectory(&traj), run_opts)?;
    let mut best = (f64::INFINITY, 0.0, [0.0; 3], [0.0; 3]);
    let mut clear = vec![f64::INFINITY; p.structures.len()];
    loop {
        if run.next_k() < run.ticks_total() && ctx.cancel.load(Ordering::Relaxed) {
            bail!("planning cancelled");
        }
        let Some(tick) = run.next_tick()? else { break };
        let out = run.output();
        let tgs = out.targets.as_slice();
        let d = tgs[0].distance_m;
        if d < best.0 {
            // The commanded tip depth (the base's travel): a flexible needle's tip lags it.
            let q = traj.pose_at(tick.t_s);
            best = (d, dot(sub(q.position_m, cand.entry), cand.dir) + p.length, out.tip_m, tgs[0].centre_m);
        }
        for (j, s) in p.structures.iter().enumerate() {
            clear[j] = clear[j].min(tgs[j + 1].distance_m - s.radius_m - p.needle_radius);
        }
        if d > best.0 + 0.005 {
            break;
        }
    }
    ctx.simulations.fetch_add(1, Ordering::Relaxed);
    let (e1, e2) = ctx.basis;
    let gap = sub(best.3, best.2);
    Ok(Eval { cand, miss: [dot(gap, e1), dot(gap, e2)], error: best.0, depth: best.1, tip: best.2, target: best.3, clearances: clear })
}

/// Evaluates candidates on up to `threads` scoped threads, in order.
fn evaluate_all(ctx: &Ctx, cands: Vec<Candidate>, threads: usize) -> Result<Vec<Eval>> {
    let n = cands.len();
    let next = AtomicUsize::new(0);
    let slots: Vec<std::sync::Mutex<Option<Result<Eval>>>> = (0..n).map(|_| std::sync::Mutex::new(None)).collect();
    std::thread::scope(|s| {
        for _ in 0..threads.min(n).max(1) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= n {
                        break;
                    }
                    let r = evaluate(ctx, cands[i].clone());
                    *slots[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
                }
            });
        }
    });
    slots.into_iter().map(|m| m.into_inner().unwrap_or_else(|e| e.into_inner()).expect("every candidate evaluated")).collect()
}

/// The candidate aiming at $c + u_1 e_1 + u_2 e_2$ from `entry` with `rolls`.
fn candidate(p: &Problem3, basis: ([f64; 3], [f64; 3]), entry: [f64; 3], u: [f64; 2], rolls: &[RollStep]) -> Candidate {
    let aim = add(p.center, add(scale(u[0], basis.0), scale(u[1], basis.1)));
    Candidate { entry, dir: unit(sub(aim, entry)), aim, rolls: rolls.to_vec() }
}

/// The aim search from `entry` with the schedule `rolls` (module docs); `report` after each
/// iteration. Returns every candidate simulated and the iterations run.
fn aim_search(
    ctx: &Ctx,
    entry: [f64; 3],
    rolls: &[RollStep],
    threads: usize,
    report: &mut dyn FnMut(usize, f64) -> ControlFlow<()>,
) -> Result<(Vec<Eval>, usize, bool)> {
    let p = ctx.p;
    let h0 = p.radius.max(0.001);
    let tol = ctx.opts.tolerance_fraction * p.radius;
    let mut all: Vec<Eval> = Vec::new();
    let (mut u, mut h) = ([0.0, 0.0], h0);
    let mut iterations = 0;
    let mut resolved = false;
    for it in 1..=ctx.opts.max_iterations.max(1) {
        iterations = it;
        let stencil = vec![
            candidate(p, ctx.basis, entry, u, rolls),
            candidate(p, ctx.basis, entry, [u[0] + h, u[1]], rolls),
            candidate(p, ctx.basis, entry, [u[0], u[1] + h], rolls),
        ];
        let ev = evaluate_all(ctx, stencil, threads)?;
        let (m0, m1, m2) = (ev[0].miss, ev[1].miss, ev[2].miss);
        all.extend(ev);
        let best = all.iter().map(|e| e.error).fold(f64::INFINITY, f64::min);
        if report(it, best).is_break() {
            bail!("planning cancelled");
        }
        if all.iter().any(|e| e.error < tol || (e.error < p.radius && e.miss[0].hypot(e.miss[1]) < 0.25 * tol)) {
            resolved = true;
            break;
        }
        // J columns: ∂m/∂u1, ∂m/∂u2.
        let j = [[(m1[0] - m0[0]) / h, (m2[0] - m0[0]) / h], [(m1[1] - m0[1]) / h, (m2[1] - m0[1]) / h]];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let step = if det.abs() < 0.05 {
            m0
        } else {
            // −J⁻¹ m0.
            [-(j[1][1] * m0[0] - j[0][1] * m0[1]) / det, -(-j[1][0] * m0[0] + j[0][0] * m0[1]) / det]
        };
        let len = step[0].hypot(step[1]);
        let s = if len > 0.01 { 0.01 / len } else { 1.0 };
        u = [u[0] + s * step[0], u[1] + s * step[1]];
        h = (0.5 * s * len).clamp(0.02 * h0, h0);
    }
    Ok((all, iterations, resolved))
}

/// Checks a request without planning: the errors [`plan3`] would return first (a
/// [`PlanInputError`] naming the field).
pub fn validate3_request(scene: &Scene3d, req: &Plan3Request) -> Result<()> {
    validate(scene, req).map(|_| ())
}

/// Plans an insertion in 3D (module docs), calling `progress` after each iteration;
/// `ControlFlow::Break` from it stops the planning (an error).
pub fn plan3(
    scene: &Scene3d,
    req: &Plan3Request,
    opts: &PlanOptions,
    mut progress: impl FnMut(&PlanProgress) -> ControlFlow<()>,
) -> Result<Plan3> {
    let started = Instant::now();
    let p = validate(scene, req)?;
    let threads = if opts.threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { opts.threads };
    let model = Arc::new(scene.tissue_model()?);
    let stop = AtomicBool::new(false);
    let cancel = opts.cancel.as_deref().unwrap_or(&stop);
    let simulations = AtomicUsize::new(0);
    let d0 = unit(sub(p.center, p.entry));
    let ctx = Ctx { scene, model, p: &p, opts, basis: across(d0), roll0: p.roll0, cancel, simulations: &simulations };
    let straight = evaluate(&ctx, candidate(&p, ctx.basis, p.entry, [0.0, 0.0], &[]))?;
    let straight_error = straight.error;
    let mut report = |it: usize, best: f64| {
        progress(&PlanProgress {
            iteration: it,
            simulations: simulations.load(Ordering::Relaxed),
            best_error_m: best.min(straight_error),
            straight_error_m: straight_error,
        })
    };
    let (entry, rolls) = if p.bevel { (p.entry, bevel_schedule(&p, d0, opts.start_outside_m)) } else { (choose_entry(&p), Vec::new()) };
    // The aim search's unknowns are across the straight line from its entry.
    let ctx = Ctx { basis: across(unit(sub(p.center, entry))), ..ctx };
    let (mut all, iterations, resolved) = aim_search(&ctx, entry, &rolls, threads, &mut report)?;
    // The plan: among the candidates that keep the clearance, the smallest error; if none does,
    // the largest clearance.
    let keeps = |e: &Eval| e.min_clearance() >= p.clearance;
    all.sort_by(|a, b| match (keeps(a), keeps(b)) {
        (true, false) => std::cmp::Ordering::Less,
        (false, true) => std::cmp::Ordering::Greater,
        (true, true) => a.error.total_cmp(&b.error),
        (false, false) => b.min_clearance().total_cmp(&a.min_clearance()),
    });
    let best = all.into_iter().next().context("no candidate was simulated")?;
    let converged = resolved && keeps(&best) && best.error < p.radius;
    let traj = trajectory(&p, &best.cand, p.roll0, best.depth, opts.start_outside_m, opts.hold_s);
    Ok(Plan3 {
        scene: scene.name.clone(),
        target: p.target_name.clone(),
        target_radius_m: p.radius,
        target_center_m: p.center,
        structures: p.structures.clone(),
        clearance_m: p.clearance,
        bevel: p.bevel,
        speed_m_s: p.speed,
        plan: best.insertion(),
        straight: straight.insertion(),
        trajectory: traj
            .samples
            .iter()
            .map(|(t, q)| {
                let ([x, y, z], [qw, qx, qy, qz]) = (q.position_m, q.quat_wxyz);
                [*t, x, y, z, qw, qx, qy, qz]
            })
            .collect(),
        converged,
        iterations,
        simulations: simulations.load(Ordering::Relaxed),
        wall_s: started.elapsed().as_secs_f64(),
        threads,
    })
}

/// The bevel needle's schedule (module docs, "Rotation schedule"): one roll before the tip
/// enters, turning the bevel to face the nearest structure across the chord.
fn bevel_schedule(p: &Problem3, d0: [f64; 3], outside_m: f64) -> Vec<RollStep> {
    let Some(s) = p
        .structures
        .iter()
        .min_by(|a, b| dist_to_segment(a.center_m, p.entry, p.center).total_cmp(&dist_to_segment(b.center_m, p.entry, p.center)))
    else {
        return Vec::new();
    };
    let rel = sub(s.center_m, p.entry);
    let mut w = sub(rel, scale(dot(rel, d0), d0));
    if norm(w) < 1e-9 {
        w = across(d0).0;
    }
    let w = scale(p.bevel_side, unit(w));
    // The bevel (base frame's n at roll φ from the straight aim's frame) along w.
    let f0 = Pose3::new([0.0; 3], quat_from_axis_roll(d0, p.roll0)).frame();
    let phi = dot(w, f0[2]).atan2(dot(w, f0[1]));
    vec![RollStep { depth_m: -outside_m, roll_rad: phi }]
}
