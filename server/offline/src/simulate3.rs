//! The scripted `simulate` command for 3D scenes: a [`Trajectory3`] through the 3D step
//! function ([`Simulation3`]) at the scene's tick rate, a per-tick CSV, states dumped in the 3D
//! exchange format at chosen ticks with the simulation's own answer, and each target's
//! displacement and closest approach.
//!
//! **The run** is the run driver's ([`crate::driver`], the one of 2D `simulate`): tick
//! $k = 0, 1, \dots, K$ steps the base pose of the trajectory at
//! $t = t_0 + k / f_{tick}$, $K = \mathrm{round}((t_{end} - t_0) f_{tick})$; between steps the
//! compliance of the nodes ahead of the tip is computed ([`Simulation3::prefetch`], all of
//! them: their columns, or their node blocks from
//! [`AUTO_BLOCKS_MIN_NODES`](needlesim_core::sim3::AUTO_BLOCKS_MIN_NODES) mesh nodes up), so
//! the step never computes one: a new point whose compliance is missing waits a tick and is
//! counted in [`RunSummary3::column_deferrals`].
//!
//! **Dumped states** ([`dump_state`]): the static problem the tick solved
//! ([`scenario_from_snapshot`]: material points as `points`, contacts spread over discs as
//! `patches` with the simulation's own nodes and weights) with `working_points` at every
//! contact's reference position (a disc's centre) and `output_stresses`, so that fem_ref3d.py
//! answers displacements, reactions, energy, stresses, point (and patch) reactions and the point
//! compliance; and in `simulation_result` the simulation's own answer in the 3D result format:
//! the field its contact forces $f_i$ (total: constraint plus friction) cause,
//! $u = C P^\top f$ ($P$ each contact's terms: a point's barycentric weights, a disc's averaged
//! shape functions), from the columns $C$ of the contacts' nodes (those the simulation cached,
//! computed only if evicted), the support reactions $r = (K u - P^\top f)_{fixed}$, the energy
//! $\tfrac12 u^\top K u$ and the stresses from $u$, the contact reactions $f_i - f^{fr}_i$ and
//! displacements, and the point compliance $W$ at the working points.
//!
//! **Targets.** A target sphere moves with the tissue: the simulation tracks each one
//! ([`Sim3Params::targets`], `needlesim_core::sim3::targets`: the centre's displacement from the
//! points' forces every tick, $O(\text{points})$, exact for the tick's static problem; hit
//! latched when the tip comes within the radius). The run keeps the closest approach over every
//! tick and the displacement there. (The unit test checks the displaced centre against the exact
//! static solve of the dumped problem, [`solve_scenario3`].)

use std::collections::HashMap;
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

use needlesim_core::d3::assembly::{element_stiffness, element_stresses_pa, tet_dofs};
use needlesim_core::sim3::{BasePose3, PointState3, Sim3Params, SimError3, Simulation3, SnapshotPoint3, Target3, TargetState3};
use needlesim_scene::exchange3d::{
    PointCompliance3, PointReaction3, Reaction3, Scenario3, ScenarioResult3, dump_order, scenario_from_snapshot,
};
use needlesim_scene::{Scene3d, Trajectory3, TrajectoryError};

use crate::convergence::ConvergencePolicy;
use crate::driver::{RunError, RunOptions, Script, ScriptedRun, Tick, preallocated_ticks};
use crate::scripted::ScriptedSim;

/// Why a 3D run failed; each names what.
#[derive(Debug, thiserror::Error)]
pub enum Run3Error {
    /// The run driver's: the trajectory lasts more ticks than allowed (the error names its
    /// last sample's line, as in 2D), its first pose is not a base pose, the parameters are
    /// refused, or a step, a column solve or the convergence policy stopped the run at a tick
    /// (named with its time).
    #[error(transparent)]
    Run(#[from] RunError<SimError3>),
    /// Before the run: the tissue does not factorise.
    #[error("the 3D simulation cannot start: {0:#}")]
    Setup(anyhow::Error),
    /// A dump tick outside the run.
    #[error("--dump-at {tick}: the run has ticks 0..={last}")]
    DumpTick { tick: u64, last: u64 },
    /// A target centre or a needle point outside the mesh (a scene that passed validation
    /// cannot cause it), or a column solve for the target failed.
    #[error("{0}")]
    Tissue(String),
}

impl From<TrajectoryError> for Run3Error {
    fn from(e: TrajectoryError) -> Self {
        Run3Error::Run(RunError::TooLong(e))
    }
}

/// A target's record over a run.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetReport3 {
    pub name: String,
    pub radius_m: f64,
    /// The undeformed centre, m.
    pub center_m: [f64; 3],
    /// The tick of the closest approach of the tip to the displaced centre.
    pub closest_tick: u64,
    /// The closest approach, m.
    pub closest_distance_m: f64,
    /// The centre's displacement at that tick, m.
    pub displacement_at_closest_m: [f64; 3],
    /// The largest displacement magnitude of the centre over the run, m.
    pub max_displacement_m: f64,
    /// The distance from the tip to the *undeformed* centre at the closest tick, m: what the
    /// aim would have reached in rigid tissue.
    pub rigid_distance_at_closest_m: f64,
    /// Whether the tip came within the radius.
    pub hit: bool,
}

/// What a run produced besides the CSV and the dumps.
#[derive(Debug, Clone, Default)]
pub struct RunSummary3 {
    pub ticks: u64,
    pub clamped_ticks: u64,
    /// Ticks at which a new point waited for its columns (admitted later).
    pub column_deferrals: u64,
    pub prefetched_columns: u64,
    /// Ticks that did not converge (the stick/slip or the shape-pass cap): kept only by
    /// [`ConvergencePolicy::Keep`].
    pub unconverged_ticks: u64,
    /// Contacts that asked for a disc across the shaft and stayed points (`spread_contact`; more
    /// nodes than a contact holds, or a disc not wholly inside the tissue).
    pub patch_fallbacks: u64,
    pub numeric_factorisations: u64,
    pub max_points: usize,
    pub targets: Vec<TargetReport3>,
    /// Step compute times, seconds, one per tick.
    pub step_times_s: Vec<f64>,
    /// Factorisation time, s.
    pub factorise_s: f64,
}

/// The 3D simulation parameters of a scene: its needle (and its contact discs' radius, half its
/// diameter, with `spread_contact`), regions, tick rate and `[limits]`
/// (`max_base_step_m`, `max_base_step_rad`, `max_active_set_iterations`; every 3D driver, live or
/// scripted, builds its parameters here; `lookahead_m` stays the 3D default, 20 mm); the base
/// starts at `initial`.
pub fn sim3_params(scene: &Scene3d, initial: BasePose3) -> Sim3Params {
    let mut p = Sim3Params::new(scene.needle.length_m, initial);
    p.spacing_m = scene.needle.contact_spacing_m;
    if scene.needle.spread_contact {
        p.disc_radius_m = 0.5 * scene.needle.diameter_m;
    }
    p.max_base_step_m = scene.limits.max_base_step_m;
    p.max_base_step_rad = scene.limits.max_base_step_rad;
    p.max_active_set_iterations = scene.limits.max_active_set_iterations;
    p.regions = scene.regions.iter().map(|r| r.needle).collect();
    p.tick_rate_hz = scene.tick_rate_hz;
    p.max_contacts = scene.needle.max_points;
    p.viscoelastic = scene.viscoelastic;
    if scene.needle.near_field {
        p.near_field = Some(needlesim_core::sim3::NearField3::new(0.5 * scene.needle.diameter_m));
    }
    if let Some(f) = scene.needle.flexible {
        p.needle = needlesim_core::sim3::NeedleShape3::Flexible(f);
    }
    p.targets =
        scene.targets.iter().enumerate().map(|(k, t)| Target3 { centre_m: t.center_m, radius_m: t.radius_m, name_idx: k }).collect();
    p
}

/// A trajectory pose as the simulation's base pose.
pub fn base_pose3(p: &needlesim_scene::Pose3) -> Result<BasePose3, String> {
    BasePose3::new(p.position_m, p.quat_wxyz).map_err(|e| e.to_string())
}

/// What [`run3`] returns: the simulation after the last tick, the summary, and the dumped
/// states as `(tick, scenario)` in tick order.
pub type Run3Output = (Simulation3, RunSummary3, Vec<(u64, Scenario3)>);

/// The CSV header for a scene's targets.
pub fn csv_header3(target_names: &[String]) -> String {
    let mut h = String::from(
        "tick,t_s,x_m,y_m,z_m,qw,qx,qy,qz,fx_n,fy_n,fz_n,torque_x_nm,torque_y_nm,torque_z_nm,f_axial_n,tip_x_m,tip_y_m,tip_z_m,inserted_m,n_points,n_stuck,n_slipping,n_tip",
    );
    for n in target_names {
        let _ = write!(h, ",target_{n}_distance_m,target_{n}_x_m,target_{n}_y_m,target_{n}_z_m,target_{n}_hit");
    }
    h
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Runs `traj` through a new 3D simulation of `scene` (module docs), appending each tick's row
/// to `csv` (when given) and dumping the state at each tick of `dump_ticks` (sorted or not;
/// returned as `(tick, scenario)` in tick order). A trajectory of more than `max_ticks` ticks
/// is refused before anything runs.
pub fn run3(
    scene: &Scene3d,
    traj: &Trajectory3,
    max_ticks: u64,
    dump_ticks: &[u64],
    convergence: ConvergencePolicy,
    mut csv: Option<&mut String>,
) -> Result<Run3Output, Run3Error> {
    let rate = scene.tick_rate_hz;
    let last_k = traj.tick_count(rate, max_ticks)?;
    if let Some(&bad) = dump_ticks.iter().find(|&&k| k > last_k) {
        return Err(Run3Error::DumpTick { tick: bad, last: last_k });
    }
    // The first pose before the factorisation, which takes seconds on a large mesh.
    let initial = <Simulation3 as ScriptedSim>::first_pose(traj).map_err(|e| RunError::FirstPose(Box::new(e)))?;
    let started = Instant::now();
    let model = Arc::new(scene.tissue_model().map_err(Run3Error::Setup)?);
    let factorise_s = started.elapsed().as_secs_f64();
    let opts = RunOptions { max_ticks, prefetch_nodes_per_tick: None, convergence };
    let mut run = ScriptedRun::new(model.clone(), sim3_params(scene, initial), Script::trajectory(traj), opts)?;
    let mut reports: Vec<TargetReport3> = scene
        .targets
        .iter()
        .map(|t| TargetReport3 {
            name: t.name.clone(),
            radius_m: t.radius_m,
            center_m: t.center_m,
            closest_tick: 0,
            closest_distance_m: f64::INFINITY,
            displacement_at_closest_m: [0.0; 3],
            max_displacement_m: 0.0,
            rigid_distance_at_closest_m: f64::INFINITY,
            hit: false,
        })
        .collect();
    if let Some(c) = csv.as_deref_mut() {
        let names: Vec<String> = scene.targets.iter().map(|t| t.name.clone()).collect();
        c.push_str(&csv_header3(&names));
        if convergence == ConvergencePolicy::Keep {
            c.push_str(",converged");
        }
        c.push('\n');
    }
    let mut summary = RunSummary3 { step_times_s: Vec::with_capacity(preallocated_ticks(last_k)), factorise_s, ..Default::default() };
    let mut dumps = Vec::new();
    while let Some(Tick { k, t_s, step_s }) = run.next_tick()? {
        summary.step_times_s.push(step_s);
        let sim = run.sim();
        let out = sim.output();
        summary.unconverged_ticks += out.unconverged().is_some() as u64;
        summary.max_points = summary.max_points.max(out.contacts.len());
        for (r, t) in reports.iter_mut().zip(out.targets.as_slice()) {
            r.max_displacement_m = r.max_displacement_m.max(dist(t.displacement_m, [0.0; 3]));
            if t.distance_m < r.closest_distance_m {
                r.closest_distance_m = t.distance_m;
                r.closest_tick = k;
                r.displacement_at_closest_m = t.displacement_m;
                r.rigid_distance_at_closest_m = dist(out.tip_m, r.center_m);
            }
            r.hit = t.state == TargetState3::Hit;
        }
        if let Some(c) = csv.as_deref_mut() {
            write_csv_row3(c, k, t_s, out);
            if convergence == ConvergencePolicy::Keep {
                c.pop();
                c.push_str(if out.unconverged().is_some() { ",0\n" } else { ",1\n" });
            }
        }
        if dump_ticks.contains(&k) {
            dumps.push((k, dump_state(scene, sim).map_err(|e| Run3Error::Tissue(format!("tick {k}: {e:#}")))?));
        }
    }
    // The columns due after the last tick, as every tick's: counted in the summary.
    let (sim, totals) = run.finish()?;
    let st = sim.stats();
    summary.ticks = totals.ticks;
    summary.prefetched_columns = totals.prefetched_columns;
    summary.clamped_ticks = st.clamped_ticks;
    summary.column_deferrals = st.column_deferrals;
    summary.patch_fallbacks = st.patch_fallbacks;
    summary.numeric_factorisations = model.cholesky().n_numeric_factorisations();
    summary.targets = reports;
    Ok((sim, summary, dumps))
}

/// One CSV row ([`csv_header3`]'s columns).
fn write_csv_row3(c: &mut String, k: u64, t_s: f64, out: &needlesim_core::sim3::StepOutput3) {
    let p = out.pose.position_m;
    let q = out.pose.orientation.quaternion();
    let (f, m) = (out.base_force_n, out.base_torque_nm);
    let count = |s: PointState3| out.contacts.iter().filter(|c| c.state == s).count();
    let _ = write!(
        c,
        "{k},{t_s:.6},{},{},{},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{},{},{},{},{},{}",
        p[0],
        p[1],
        p[2],
        q.w,
        q.i,
        q.j,
        q.k,
        f[0],
        f[1],
        f[2],
        m[0],
        m[1],
        m[2],
        out.axial_force_n,
        out.tip_m[0],
        out.tip_m[1],
        out.tip_m[2],
        out.inserted_length_m,
        out.contacts.len(),
        count(PointState3::Stuck),
        count(PointState3::Slipping),
        count(PointState3::Tip),
    );
    for t in out.targets.as_slice() {
        let _ =
            write!(c, ",{:e},{},{},{},{}", t.distance_m, t.centre_m[0], t.centre_m[1], t.centre_m[2], (t.state == TargetState3::Hit) as u8);
    }
    c.push('\n');
}

/// The state of `sim` as a 3D scenario with the simulation's own answer (module docs).
pub fn dump_state(scene: &Scene3d, sim: &Simulation3) -> anyhow::Result<Scenario3> {
    let model = sim.model();
    let snap = sim.snapshot();
    let states: Vec<PointState3> = sim.output().contacts.iter().map(|c| c.state).collect();
    let mut sc = scenario_from_snapshot(model, &snap, Some(&states), &format!("{}-tick-{}", scene.name, snap.tick));
    sc.description = Some(format!("needlesim-server simulate --dump-state: {} at tick {}", scene.name, snap.tick));
    sc.output_stresses = true;
    if !snap.points.is_empty() {
        sc.working_points = Some(dump_order(&snap).into_iter().map(|k| snap.points[k].x_m).collect());
    }
    sc.simulation_result = Some(Box::new(simulation_result(sim, &sc)?));
    Ok(sc)
}

/// The simulation's answer to its own static problem `sc` (module docs).
#[allow(clippy::needless_range_loop)] // symmetric (i, j) index pairs of W
fn simulation_result(sim: &Simulation3, sc: &Scenario3) -> anyhow::Result<ScenarioResult3> {
    let model = sim.model();
    let mesh = model.mesh();
    let mats = model.materials();
    let n_dofs = model.n_dofs();
    let snap = sim.snapshot();
    // The contacts in the dump's order: points, then patches (discs).
    let pts: Vec<&SnapshotPoint3> = dump_order(&snap).into_iter().map(|k| &snap.points[k]).collect();
    // The working points (every contact's reference position) located as points, for W.
    let locs = pts
        .iter()
        .map(|p| model.locate(p.x_m).map_err(|e| anyhow::anyhow!("needle point at {:?}: {e}", p.x_m)))
        .collect::<Result<Vec<_>, _>>()?;
    // The columns of every node a contact or a working point holds: the simulation's cached
    // ones (with a column store), computed if evicted or with node blocks.
    let cached = |n: usize, c: usize| sim.cache().columns().and_then(|cc| cc.column(n, c));
    let mut computed: HashMap<usize, Vec<f64>> = HashMap::new();
    let mut scratch = model.column_scratch();
    let term_nodes = pts.iter().flat_map(|p| p.contact.nodes().iter().map(|n| n.index()));
    for n in term_nodes.chain(locs.iter().flat_map(|l| l.nodes)) {
        if !(0..3).all(|c| cached(n, c).is_some()) && !computed.contains_key(&n) {
            let mut buf = vec![0.0; 3 * n_dofs];
            model.compliance_columns_into(n, &mut buf, &mut scratch)?;
            computed.insert(n, buf);
        }
    }
    let column = |n: usize, c: usize| -> &[f64] {
        match cached(n, c) {
            Some(col) if !computed.contains_key(&n) => col,
            _ => &computed[&n][c * n_dofs..(c + 1) * n_dofs],
        }
    };
    // u = C Pᵀ f and Pᵀ f, through each contact's own terms (a point's tetrahedron, a disc's
    // nodes).
    let mut u = vec![0.0; n_dofs];
    let mut pf = vec![0.0; n_dofs];
    for p in &pts {
        for (node, w) in p.contact.terms() {
            if w == 0.0 {
                continue;
            }
            for c in 0..3 {
                let fc = w * p.force_n[c];
                pf[3 * node.index() + c] += fc;
                if fc != 0.0 {
                    for (o, x) in u.iter_mut().zip(column(node.index(), c)) {
                        *o += x * fc;
                    }
                }
            }
        }
    }
    // K u element by element: the reactions at the fixed nodes and the energy.
    let mut ku = vec![0.0; n_dofs];
    for t in 0..mesh.n_tets() {
        let k = element_stiffness(mesh, mats, t);
        let dofs = tet_dofs(&mesh.tets()[t]);
        for (a, &da) in dofs.iter().enumerate() {
            ku[da] += (0..12).map(|b| k[a][b] * u[dofs[b]]).sum::<f64>();
        }
    }
    let energy = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
    let reactions = sc
        .fixed_nodes
        .iter()
        .map(|&n| {
            let n = n as usize;
            let r = |c: usize| Some(ku[3 * n + c] - pf[3 * n + c]);
            Reaction3 { node: n, rx: r(0), ry: r(1), rz: r(2) }
        })
        .collect();
    let n_points = pts.iter().filter(|p| !p.contact.is_disc()).count();
    let point_reactions = pts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let f = p.f_n.unwrap_or([0.0; 3]);
            let r = [p.force_n[0] - f[0], p.force_n[1] - f[1], p.force_n[2] - f[2]];
            let local = |a: usize, given: Option<f64>| given.map(|_| p.frame[a][0] * r[0] + p.frame[a][1] * r[1] + p.frame[a][2] * r[2]);
            let (kind, index) = if i < n_points { ("point", i) } else { ("patch", i - n_points) };
            PointReaction3 {
                point: i,
                kind: kind.to_owned(),
                index,
                rx: r[0],
                ry: r[1],
                rz: r[2],
                rt: local(0, p.ut),
                rn: local(1, p.un),
                rb: local(2, p.ub),
                u: p.u_m,
            }
        })
        .collect();
    // W = P C Pᵀ from the same columns.
    let np = locs.len();
    let d = 3 * np;
    let mut w = vec![vec![0.0; d]; d];
    for (b, lb) in locs.iter().enumerate() {
        for j in 0..4 {
            let wj = lb.weights[j];
            if wj == 0.0 {
                continue;
            }
            for c in 0..3 {
                let col = column(lb.nodes[j], c);
                for (a, la) in locs.iter().enumerate() {
                    for r in 0..3 {
                        let v: f64 = (0..4).map(|i| la.weights[i] * col[3 * la.nodes[i] + r]).sum();
                        w[3 * a + r][3 * b + c] += wj * v;
                    }
                }
            }
        }
    }
    for i in 0..d {
        for j in 0..i {
            let v = 0.5 * (w[i][j] + w[j][i]);
            w[i][j] = v;
            w[j][i] = v;
        }
    }
    Ok(ScenarioResult3 {
        name: sc.name.clone().unwrap_or_default(),
        dim: 3,
        n_nodes: mesh.n_nodes(),
        n_tetrahedra: mesh.n_tets(),
        max_abs_displacement: u.iter().fold(0.0, |m, v| m.max(v.abs())),
        element_stresses_voigt: Some(element_stresses_pa(mesh, mats, &u)),
        displacements: u.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
        reactions,
        reactions_local: vec![],
        point_reactions,
        disc_weights: vec![],
        strain_energy: energy,
        compliance: None,
        point_compliance: (np > 0).then(|| PointCompliance3 {
            working_points: pts.iter().map(|p| p.x_m).collect(),
            dof_order: "[ux(p0), uy(p0), uz(p0), ux(p1), ...]".to_owned(),
            matrix: w,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_scene::exchange3d::solve_scenario3;

    const SCENE: &str = r#"
dim = 3
name = "small"
fixed = ["bottom"]
[mesh]
type = "box"
nx = 13
ny = 13
nz = 13
size_m = [0.06, 0.06, 0.06]
[[regions]]
name = "gel"
young_modulus_pa = 20e3
poisson_ratio = 0.45
friction_n_per_m = 20
[needle]
length_m = 0.1
contact_spacing_m = 0.002
base_m = [0.0311, 0.0297, 0.165]
base_quat = [0.7071067811865475, 0.0, 0.7071067811865475, 0.0]
[[targets]]
name = "t"
center_m = [0.031, 0.0305, 0.02]
radius_m = 0.001
"#;
    const TRAJ: &str = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0.0311,0.0297,0.165,0.7071067811865475,0,0.7071067811865475,0\n3.5,0.0311,0.0297,0.13,0.7071067811865475,0,0.7071067811865475,0\n";

    fn scene() -> Scene3d {
        needlesim_scene::parse_scene3d(SCENE, std::path::Path::new("."), &needlesim_core::MeshLimits::default()).unwrap()
    }

    /// The target displacement from the columns equals the exact static solve of the dumped
    /// problem, interpolated at the centre; the dumped simulation result equals that solve.
    #[test]
    fn target_displacement_and_dumped_answer_equal_the_static_solve() {
        let sc = scene();
        let traj = Trajectory3::parse_csv(TRAJ).unwrap();
        let mut csv = String::new();
        let (sim, summary, dumps) = run3(&sc, &traj, 10_000, &[2000, 3500], ConvergencePolicy::Fail, Some(&mut csv)).unwrap();
        assert_eq!(summary.ticks, 3501);
        assert_eq!(dumps.iter().map(|d| d.0).collect::<Vec<_>>(), vec![2000, 3500]);
        assert_eq!(csv.lines().count(), 3502);
        let (_, state) = &dumps[1];
        let n_points: Vec<&str> = csv.lines().skip(1).step_by(250).map(|l| l.split(',').nth(20).unwrap()).collect();
        assert!(state.points.len() >= 3, "the needle holds points: {n_points:?}");
        let exact = solve_scenario3(state, &needlesim_core::d3::TetMeshLimits::default()).unwrap();
        let ours = state.simulation_result.as_ref().unwrap();
        let rel = |a: &[[f64; 3]], b: &[[f64; 3]]| {
            let e = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs())).fold(0.0, f64::max);
            e / b.iter().flat_map(|q| q.iter().map(|v| v.abs())).fold(0.0, f64::max)
        };
        let e = rel(&ours.displacements, &exact.displacements);
        assert!(e <= 1e-9, "displacements differ by {e:e}");
        assert!((ours.strain_energy - exact.strain_energy).abs() <= 1e-9 * exact.strain_energy.abs());
        // The target's centre from the last row of the CSV against the exact field there.
        let loc = sim.model().locate(sc.targets[0].center_m).unwrap();
        let u_exact: [f64; 3] = std::array::from_fn(|c| (0..4).map(|j| loc.weights[j] * exact.displacements[loc.nodes[j]][c]).sum());
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let last: Vec<f64> = csv.lines().last().unwrap().split(',').map(|v| v.parse().unwrap()).collect();
        let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
        let moved = [last[col("target_t_x_m")], last[col("target_t_y_m")], last[col("target_t_z_m")]];
        let scale = u_exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 1e-7, "the target moved: {u_exact:?}");
        for c in 0..3 {
            let got = moved[c] - sc.targets[0].center_m[c];
            assert!((got - u_exact[c]).abs() <= 1e-9 * scale + 1e-15, "component {c}: {got} vs {}", u_exact[c]);
        }
        assert!(summary.targets[0].closest_distance_m.is_finite());
    }

    /// Issue 37 item 6: the run driver fills the node-block store with the simulation's own
    /// worker (it stopped at tick 0: `prefetch_columns` needs the columns store), and the run
    /// gives the columns store's CSV to round-off: the same rows, every number within 1e-9 of
    /// its column's largest magnitude, the counts and states equal. The trajectory inserts
    /// 35 mm past the target, moves the base 1 mm sideways and holds.
    #[test]
    fn issue_37_offline_3d_runs_with_the_node_block_store_as_with_columns() {
        use needlesim_core::sim3::StoreKind3;
        let sc = scene();
        let traj = Trajectory3::parse_csv(&format!(
            "{TRAJ}4.0,0.0321,0.0297,0.13,0.7071067811865475,0,0.7071067811865475,0\n4.3,0.0321,0.0297,0.13,0.7071067811865475,0,0.7071067811865475,0\n"
        ))
        .unwrap();
        let model = Arc::new(sc.tissue_model().unwrap());
        let names: Vec<String> = sc.targets.iter().map(|t| t.name.clone()).collect();
        let run_with = |store: StoreKind3| {
            let mut params = sim3_params(&sc, base_pose3(&sc.initial_pose).unwrap());
            params.store = store;
            let mut run = ScriptedRun::new(model.clone(), params, Script::trajectory(&traj), RunOptions::default()).unwrap();
            let mut csv = csv_header3(&names) + "\n";
            while let Some(Tick { k, t_s, .. }) = run.next_tick().unwrap() {
                write_csv_row3(&mut csv, k, t_s, run.output());
            }
            let (sim, totals) = run.finish().unwrap();
            (csv, sim, totals)
        };
        let (columns, sim_c, totals_c) = run_with(StoreKind3::Columns);
        let (blocks, sim_b, totals_b) = run_with(StoreKind3::NodeBlocks);
        assert!(sim_c.cache().columns().is_some() && sim_b.cache().blocks().is_some(), "each run used the store it was given");
        assert!(totals_b.prefetched_columns > 0, "the node-block run prefetched nothing");
        assert_eq!((totals_c.ticks, totals_b.ticks), (4301, 4301));
        assert_eq!(sim_b.stats().column_deferrals, sim_c.stats().column_deferrals);
        let parse =
            |csv: &str| -> Vec<Vec<f64>> { csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect() };
        let (c, b) = (parse(&columns), parse(&blocks));
        assert_eq!(c.len(), b.len());
        let header: Vec<&str> = columns.lines().next().unwrap().split(',').collect();
        let max_points = c.iter().map(|r| r[header.iter().position(|h| *h == "n_points").unwrap()]).fold(0.0, f64::max);
        assert!(max_points >= 3.0, "the needle held points: {max_points}");
        let mut worst = 0.0f64;
        for (j, name) in header.iter().enumerate() {
            let scale = c.iter().chain(&b).fold(0.0f64, |m, r| m.max(r[j].abs()));
            for (k, (rc, rb)) in c.iter().zip(&b).enumerate() {
                worst = worst.max((rc[j] - rb[j]).abs() / scale.max(f64::MIN_POSITIVE));
                assert!(
                    (rc[j] - rb[j]).abs() <= 1e-9 * scale,
                    "tick {k}, {name}: columns {} vs node blocks {} (column scale {scale:e})",
                    rc[j],
                    rb[j]
                );
            }
        }
        println!("largest difference: {worst:.2e} of its column's scale; {max_points} points at most");
    }

    /// Issue 35: a 3D scene's `[limits] max_base_step_m` and `max_base_step_rad` reach the
    /// simulation (they were validated and dropped: every 3D driver moved the base 2 mm and
    /// 0.05 rad a tick): a jump commanded at once is taken at most that far each tick.
    #[test]
    fn issue_35_a_3d_scenes_base_step_limits_bound_every_tick() {
        let text = SCENE.replace("[[targets]]", "[limits]\nmax_base_step_m = 1e-4\nmax_base_step_rad = 1e-3\n\n[[targets]]");
        let sc = needlesim_scene::parse_scene3d(&text, std::path::Path::new("."), &needlesim_core::MeshLimits::default()).unwrap();
        let params = sim3_params(&sc, base_pose3(&sc.initial_pose).unwrap());
        assert_eq!((params.max_base_step_m, params.max_base_step_rad), (1e-4, 1e-3));
        let mut sim = Simulation3::new(Arc::new(sc.tissue_model().unwrap()), params).unwrap();
        let start = sim.pose();
        // 5 mm sideways and turned 0.1 rad, above the tissue (the tip starts 5 mm above it).
        let p = start.position_m;
        let far = BasePose3::from_rotation([p[0] + 0.005, p[1], p[2]], start.orientation).rotated_about_axis(p, [0.0, 1.0, 0.0], 0.1);
        let mut prev = start;
        for k in 0..30 {
            let o = sim.step(far).unwrap();
            let moved_m = dist(o.pose.position_m, prev.position_m);
            let turned_rad = prev.orientation.angle_to(&o.pose.orientation);
            assert!(o.clamped, "tick {k}: the jump was taken at once");
            assert!(moved_m <= 1e-4 * (1.0 + 1e-9), "tick {k}: the base moved {moved_m} m, over max_base_step_m = 1e-4");
            assert!(turned_rad <= 1e-3 * (1.0 + 1e-9), "tick {k}: the base turned {turned_rad} rad, over max_base_step_rad = 1e-3");
            assert!(moved_m > 0.5e-4 || turned_rad > 0.5e-3, "tick {k}: the base did not move towards the pose");
            prev = o.pose;
        }
    }

    /// Issue 37: `[needle] spread_contact = true` makes every contact a disc of the needle's
    /// radius (half its diameter: the default 18 G here); without the key the contacts are points.
    #[test]
    fn issue_37_spread_contact_gives_discs_of_the_needles_radius() {
        let plain = sim3_params(&scene(), base_pose3(&scene().initial_pose).unwrap());
        assert_eq!(plain.disc_radius_m, 0.0);
        let text = SCENE.replace("[needle]\n", "[needle]\nspread_contact = true\ndiameter_m = 0.0008\n");
        let sc = needlesim_scene::parse_scene3d(&text, std::path::Path::new("."), &needlesim_core::MeshLimits::default()).unwrap();
        assert!(sc.needle.spread_contact);
        assert_eq!(sim3_params(&sc, base_pose3(&sc.initial_pose).unwrap()).disc_radius_m, 0.0004);
        // The run's summary counts the discs that stayed points: with a 9.5 mm needle on 5 mm
        // tetrahedra every disc touches more nodes than a contact holds; none without the key.
        let wide = needlesim_scene::parse_scene3d(
            &SCENE.replace("[needle]\n", "[needle]\nspread_contact = true\ndiameter_m = 0.0095\n"),
            std::path::Path::new("."),
            &needlesim_core::MeshLimits::default(),
        )
        .unwrap();
        let traj = Trajectory3::parse_csv(TRAJ).unwrap();
        let (_, points, _) = run3(&scene(), &traj, 10_000, &[], ConvergencePolicy::Fail, None).unwrap();
        let (sim, discs, _) = run3(&wide, &traj, 10_000, &[], ConvergencePolicy::Fail, None).unwrap();
        assert_eq!(points.patch_fallbacks, 0);
        let st = sim.stats();
        assert!(st.captures > 0 && st.patch_fallbacks > 0, "{st:?}");
        assert_eq!(discs.patch_fallbacks, st.patch_fallbacks);
    }

    /// The run driver's first-pose check in 3D: a trajectory whose first quaternion is not a
    /// unit one is refused before anything runs, naming it (the Simulate RPC, exercise runs and
    /// the Python package get the same error).
    #[test]
    fn a_first_pose_that_is_not_a_unit_quaternion_is_refused_before_the_run() {
        let pose = needlesim_scene::Pose3::new([0.0311, 0.0297, 0.165], [0.9, 0.0, 0.7071067811865475, 0.0]);
        let traj = Trajectory3::from_samples(vec![(0.0, pose), (0.01, pose)]);
        let e = run3(&scene(), &traj, 10_000, &[], ConvergencePolicy::Fail, None).err().unwrap();
        assert!(matches!(e, Run3Error::Run(RunError::FirstPose(ref p)) if matches!(**p, SimError3::Pose { tick: 0, .. })), "{e:?}");
        assert!(format!("{:#}", anyhow::Error::from(e)).starts_with("the trajectory's first pose: tick 0: "));
    }

    #[test]
    fn a_dump_tick_past_the_run_is_refused() {
        let traj = Trajectory3::parse_csv(TRAJ).unwrap();
        let e = run3(&scene(), &traj, 10_000, &[9999], ConvergencePolicy::Fail, None).err().unwrap().to_string();
        assert!(e.contains("--dump-at 9999") && e.contains("0..=3500"), "{e}");
        let e = run3(&scene(), &traj, 100, &[], ConvergencePolicy::Fail, None).err().unwrap().to_string();
        assert!(e.contains("over the limit of 100 ticks"), "{e}");
    }

    /// Issue 35 item 14: a trajectory 1e17 s long is refused naming its last line and the
    /// number of ticks it would take (not a count that wrapped to 0), before anything runs.
    #[test]
    fn issue_35_a_trajectory_of_1e17_s_is_refused_naming_its_line_and_ticks() {
        let text = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0.05,0.05,0.11,0.7071067811865476,0,0.7071067811865476,0\n# a comment\n1e17,0.05,0.05,0.1,0.7071067811865476,0,0.7071067811865476,0\n";
        let traj = Trajectory3::parse_csv(text).unwrap();
        for max_ticks in [1_000_000, u64::MAX] {
            let e = run3(&scene(), &traj, max_ticks, &[], ConvergencePolicy::Fail, None).err().unwrap().to_string();
            assert!(e.starts_with("trajectory line 4: t_s = 1e17 ends 1e17 s after the first sample, 1e20 ticks at 1000 Hz"), "{e}");
            assert!(e.contains(&format!("over the limit of {max_ticks} ticks")), "{e}");
        }
    }
}
