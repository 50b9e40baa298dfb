//! `needlesim-lab bench`: the same scripted insertion and withdrawal on several grid sizes,
//! stepped by three solvers side by side:
//!
//! - **ours**: the [`Simulation`] as is: compliance columns from the sparse factorisation,
//!   computed between steps by [`Simulation::prefetch_columns`], $O(d^2)$ updates. Setup is
//!   [`TissueModel::new`] (assembly and sparse factorisation).
//! - **dense**: the original paper's scheme: a dense precomputed inverse of $K_{ff}$ (faer dense
//!   Cholesky, then its inverse). Its columns feed the same simulation through
//!   [`Simulation::insert_columns`] for every approaching node, between steps. Setup is building
//!   the dense inverse. Sizes whose inverse exceeds [`DENSE_BUDGET_BYTES`] are skipped.
//! - **naive**: what a general FEM code does: every tick, a full [`StaticProblem::solve`] (fresh
//!   assembly, factorisation and solve) of the conditions the simulation applied that tick. One
//!   solve per tick is a lower bound (a naive code needs one per active-set iteration). On big
//!   meshes only a sample of ticks, spread over the script, is timed.
//!
//! Peak memory is measured by a counting global allocator (`needlesim_alloc_count::CountingAlloc`,
//! installed by the `needlesim-lab` binary, and only there): the peak of live heap bytes during one solver's run (setup and
//! all steps) above the live heap when that run started.
//!
//! The static solve of one full problem (the state at the end of the hold, deepest insertion)
//! is also timed against SciPy's `spsolve` through `server/lab/bench/scipy_static.py`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use faer::Mat;
use faer::linalg::solvers::DenseSolveCore;
use needlesim_core::compliance::TissueModel;
use needlesim_core::fixtures;
use needlesim_core::sim::{SimParams, Simulation};
use needlesim_core::{BasePose, MaterialMap, Mesh, NodeCondition, StaticProblem};
use needlesim_offline::ConvergencePolicy;
use needlesim_offline::driver::{RunOptions, Script as OfflineScript, ScriptedRun};
use serde_json::{Value, json};

use needlesim_scene::exchange::{Load, PrescribedLocal, Scenario};

// ---------------------------------------------------------------------------------------------
// Memory accounting (needlesim-alloc-count's `CountingAlloc`, the binary's global allocator).

/// Live heap bytes (0 when `CountingAlloc` is not the global allocator).
pub fn heap_current() -> usize {
    needlesim_alloc_count::live_bytes()
}

/// Starts a measurement: the peak is reset to the live heap. Returns that baseline.
fn mem_start() -> usize {
    needlesim_alloc_count::reset_peak()
}

/// Peak live heap since [`mem_start`], above its baseline.
fn mem_peak_since(baseline: usize) -> usize {
    needlesim_alloc_count::peak_bytes().saturating_sub(baseline)
}

// ---------------------------------------------------------------------------------------------
// Options and set-up.

/// Largest dense inverse the dense solver may build.
pub const DENSE_BUDGET_BYTES: u64 = 2 << 30;

/// What to run.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// Fewer sizes (19, 50, 100) and a faster script, to finish within a minute.
    pub quick: bool,
    /// Grid sizes (nodes per side); the defaults when empty.
    pub sizes: Vec<usize>,
    /// Where to write the SVG plot of step p50 against mesh size.
    pub plot: Option<PathBuf>,
    /// Skip the SciPy comparison.
    pub no_scipy: bool,
}

/// The script: insertion speed and hold, identical for the three solvers of a size.
#[derive(Debug, Clone, Copy)]
struct Script {
    speed_m_s: f64,
    hold_s: f64,
    depth_m: f64,
}

impl Script {
    fn for_options(quick: bool) -> Self {
        if quick { Script { speed_m_s: 0.05, hold_s: 0.2, depth_m: 0.06 } } else { Script { speed_m_s: 0.01, hold_s: 1.0, depth_m: 0.06 } }
    }
    /// Base poses at 1 kHz and the index of the last tick of the hold.
    fn poses(&self, x: f64) -> (Vec<BasePose>, usize) {
        let theta = -std::f64::consts::FRAC_PI_2;
        let (y0, y1) = (0.205, 0.205 - self.depth_m);
        let ticks = (self.depth_m / self.speed_m_s * 1000.0).round() as usize;
        let mut poses = Vec::with_capacity(2 * ticks + 2000);
        for k in 1..=ticks {
            poses.push(BasePose::new(x, y0 + (y1 - y0) * k as f64 / ticks as f64, theta));
        }
        poses.extend(std::iter::repeat_n(*poses.last().expect("ticks > 0"), (self.hold_s * 1000.0).round() as usize));
        let end_of_hold = poses.len() - 1;
        for k in 1..=ticks {
            poses.push(BasePose::new(x, y1 + (y0 - y1) * k as f64 / ticks as f64, theta));
        }
        (poses, end_of_hold)
    }
    fn describe(&self) -> String {
        format!(
            "vertical rigid needle (0.1 m) at the node column nearest x = 0.05, tip starting 5 mm above the surface; insertion {:.0} mm deep at {:.0} mm/s, {} s hold, withdrawal at {:.0} mm/s; 1 kHz ticks; 0.1 m square, E = 30 kPa, ν = 0.45, plane stress 1 cm, bottom fixed",
            self.depth_m * 1e3,
            self.speed_m_s * 1e3,
            self.hold_s,
            self.speed_m_s * 1e3
        )
    }
}

/// The step benchmarks' phantom (`needlesim_core::fixtures`), unfactorised, with its needle.
struct Setup {
    mesh: Mesh,
    mats: MaterialMap,
    fixed: Vec<usize>,
    params: SimParams,
    /// The needle's column (m).
    x: f64,
}

fn build_setup(n: usize) -> Result<Setup> {
    let (mesh, mats, fixed) = fixtures::phantom_parts(n);
    let params = fixtures::phantom_bench_params(n);
    Ok(Setup { mesh, mats, fixed, x: params.initial_pose.x_m, params })
}

/// The benchmark tissue of `n × n` nodes (`needlesim_core::fixtures::phantom_bench`), factorised,
/// and the parameters of its vertical needle: what every step-time benchmark starts from.
pub fn grid_simulation(n: usize) -> Result<(Arc<TissueModel>, SimParams)> {
    Ok(fixtures::phantom_bench(n))
}

/// The static problem a simulation's last step solved, with the fixed nodes.
fn snapshot_problem(sim: &Simulation, fixed: &[usize]) -> StaticProblem {
    let snap = sim.snapshot();
    let mut conditions: Vec<(usize, NodeCondition)> = fixed.iter().map(|&n| (n, NodeCondition::Fixed)).collect();
    for c in &snap.conditions {
        conditions.push((c.node_idx, NodeCondition::Local { frame: c.angle_rad, u_m: [c.ut_m, c.un_m] }));
    }
    StaticProblem { conditions, loads_n: snap.node_loads_n(), points: vec![], patches: vec![] }
}

// ---------------------------------------------------------------------------------------------
// Results.

/// One solver on one size.
#[derive(Debug, Clone)]
struct Row {
    mesh: String,
    n_nodes: usize,
    solver: &'static str,
    setup_s: f64,
    step_times_s: Vec<f64>,
    peak_mem_bytes: usize,
    ticks: usize,
    note: String,
    extra: Vec<(&'static str, Value)>,
    skipped: Option<String>,
}

/// The `q` quantile (0..=1) of sorted values, nearest rank; NaN when empty.
pub fn pct(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

impl Row {
    fn stats(&self) -> (f64, f64, f64) {
        let mut t = self.step_times_s.clone();
        t.sort_by(f64::total_cmp);
        (pct(&t, 0.5), pct(&t, 0.99), pct(&t, 1.0))
    }
}

// ---------------------------------------------------------------------------------------------
// The three solvers.

fn run_ours(n: usize, script: &Script) -> Result<(Row, StaticProblem)> {
    let base = mem_start();
    let s = build_setup(n)?;
    let t0 = Instant::now();
    let model = Arc::new(TissueModel::new(s.mesh.clone(), s.mats.clone(), &s.fixed)?);
    let setup_s = t0.elapsed().as_secs_f64();
    let (poses, end_of_hold) = script.poses(s.x);
    // Columns are prefetched between steps, untimed: `step_s` is the step alone.
    let mut run = ScriptedRun::new(
        model.clone(),
        s.params.clone(),
        OfflineScript::Poses(&poses),
        RunOptions { max_ticks: u64::MAX, prefetch_nodes_per_tick: Some(64), convergence: ConvergencePolicy::Keep },
    )?;
    let mut times = Vec::with_capacity(poses.len());
    let mut max_nodes = 0usize;
    let mut deepest = None;
    while let Some(t) = run.next_tick()? {
        times.push(t.step_s);
        max_nodes = max_nodes.max(run.output().needle_nodes.len());
        if t.k == end_of_hold as u64 {
            deepest = Some(snapshot_problem(run.sim(), &s.fixed));
        }
    }
    let (sim, totals) = run.finish()?;
    let prefetched = totals.prefetched_columns;
    let st = sim.stats();
    let row = Row {
        mesh: format!("{n}x{n}"),
        n_nodes: n * n,
        solver: "ours",
        setup_s,
        ticks: times.len(),
        step_times_s: times,
        peak_mem_bytes: mem_peak_since(base),
        note: format!("{prefetched} column pairs prefetched between steps, {} computed in steps", st.column_misses),
        extra: vec![
            ("prefetched_columns", json!(prefetched)),
            ("column_misses", json!(st.column_misses)),
            ("max_needle_nodes", json!(max_nodes)),
            ("numeric_factorisations", json!(model.cholesky().n_numeric_factorisations())),
        ],
        skipped: None,
    };
    Ok((row, deepest.context("the script has a hold")?))
}

/// Bytes of the dense inverse of the free block of an n × n grid with the bottom row fixed.
fn dense_bytes(n: usize) -> u64 {
    let n_free = 2 * (n * n - n) as u64;
    n_free * n_free * 8
}

fn gb(bytes: u64) -> String {
    format!("{:.1} GB", bytes as f64 / 1e9)
}

fn run_dense(n: usize, script: &Script) -> Result<Row> {
    let need = dense_bytes(n);
    let mesh = format!("{n}x{n}");
    if need > DENSE_BUDGET_BYTES {
        let why = format!("dense inverse needs {} (n_free² × 8 B; budget 2 GiB)", gb(need));
        return Ok(Row {
            mesh,
            n_nodes: n * n,
            solver: "dense",
            setup_s: f64::NAN,
            step_times_s: vec![],
            peak_mem_bytes: 0,
            ticks: 0,
            note: why.clone(),
            extra: vec![("dense_inverse_bytes", json!(need))],
            skipped: Some(why),
        });
    }
    let base = mem_start();
    let s = build_setup(n)?;
    // The simulation needs a model (mesh, free DOFs, and the fallback for a column a step misses).
    let model = Arc::new(TissueModel::new(s.mesh.clone(), s.mats.clone(), &s.fixed)?);
    let t0 = Instant::now();
    let dofs = model.cholesky().dofs().clone();
    let n_free = dofs.n_free();
    let inverse = {
        let k = model.stiffness().as_ref();
        let mut dense = Mat::<f64>::zeros(n_free, n_free);
        for (fj, &dj) in dofs.free_dofs().iter().enumerate() {
            for (di, &v) in k.row_idx_of_col(dj).zip(k.val_of_col(dj)) {
                if let Some(fi) = dofs.free_index(di) {
                    dense[(fi, fj)] = v;
                }
            }
        }
        let llt = dense.llt(faer::Side::Lower).map_err(|e| anyhow::anyhow!("dense Cholesky failed: {e:?}"))?;
        drop(dense);
        llt.inverse()
    };
    let setup_s = t0.elapsed().as_secs_f64();
    let n_dofs = model.n_dofs();
    let mut buf = vec![0.0; 2 * n_dofs];
    let (poses, _) = script.poses(s.x);
    // No prefetch: the columns come from the dense inverse, between steps, untimed.
    let mut run = ScriptedRun::new(
        model.clone(),
        s.params.clone(),
        OfflineScript::Poses(&poses),
        RunOptions { max_ticks: u64::MAX, prefetch_nodes_per_tick: Some(0), convergence: ConvergencePolicy::Keep },
    )?;
    let mut times = Vec::with_capacity(poses.len());
    let mut inserted = 0usize;
    while let Some(t) = run.next_tick()? {
        times.push(t.step_s);
        // Between steps: every approaching node's columns, copied from the dense inverse.
        let sim = run.sim_mut();
        for k in 0..sim.output().approaching.len() {
            let node = sim.output().approaching[k];
            if sim.cache().contains(node) {
                continue;
            }
            buf.fill(0.0);
            for comp in 0..2 {
                let Some(f) = dofs.free_index(2 * node + comp) else { continue };
                let col = inverse.col(f);
                let out = &mut buf[comp * n_dofs..(comp + 1) * n_dofs];
                for (fi, &d) in dofs.free_dofs().iter().enumerate() {
                    out[d] = col[fi];
                }
            }
            sim.insert_columns(node, &buf);
            inserted += 1;
        }
    }
    let (sim, _) = run.finish()?;
    let st = sim.stats();
    Ok(Row {
        mesh,
        n_nodes: n * n,
        solver: "dense",
        setup_s,
        ticks: times.len(),
        step_times_s: times,
        peak_mem_bytes: mem_peak_since(base),
        note: format!("{inserted} column pairs copied from the dense inverse, {} computed in steps", st.column_misses),
        extra: vec![
            ("inserted_columns", json!(inserted)),
            ("column_misses", json!(st.column_misses)),
            ("dense_inverse_bytes", json!(need)),
        ],
        skipped: None,
    })
}

fn run_naive(n: usize, script: &Script, budget_s: f64) -> Result<Row> {
    // The conditions of every tick come from an untimed run of the simulation.
    let s = build_setup(n)?;
    let (poses, _) = script.poses(s.x);
    let n_ticks = poses.len();
    let first = {
        let t = Instant::now();
        let p = StaticProblem {
            conditions: s.fixed.iter().map(|&n| (n, NodeCondition::Fixed)).collect(),
            loads_n: vec![],
            points: vec![],
            patches: vec![],
        };
        p.solve(&s.mesh, &s.mats)?;
        t.elapsed().as_secs_f64()
    };
    let n_samples = ((budget_s / first.max(1e-9)) as usize).clamp(30, n_ticks);
    let sampled: Vec<usize> = (0..n_samples).map(|i| i * (n_ticks - 1) / (n_samples - 1).max(1)).collect();
    let problems = {
        let model = Arc::new(TissueModel::new(s.mesh.clone(), s.mats.clone(), &s.fixed)?);
        let opts = RunOptions { max_ticks: u64::MAX, prefetch_nodes_per_tick: Some(64), convergence: ConvergencePolicy::Keep };
        let mut run = ScriptedRun::new(model, s.params.clone(), OfflineScript::Poses(&poses), opts)?;
        let mut problems = Vec::with_capacity(n_samples);
        let mut next = 0;
        while let Some(t) = run.next_tick()? {
            while next < sampled.len() && sampled[next] as u64 == t.k {
                problems.push(snapshot_problem(run.sim(), &s.fixed));
                next += 1;
            }
        }
        problems
    };
    drop(s);
    let base = mem_start();
    let t0 = Instant::now();
    let s = build_setup(n)?;
    let setup_s = t0.elapsed().as_secs_f64();
    let mut times = Vec::with_capacity(problems.len());
    for p in &problems {
        let t = Instant::now();
        let sol = p.solve(&s.mesh, &s.mats)?;
        times.push(t.elapsed().as_secs_f64());
        drop(sol);
    }
    let all = problems.len() == n_ticks;
    let note = if all {
        "one full solve (assembly + factorisation + solve) per tick, every tick timed".to_owned()
    } else {
        format!("one full solve per tick; {} of {n_ticks} ticks timed (evenly spread)", problems.len())
    };
    Ok(Row {
        mesh: format!("{n}x{n}"),
        n_nodes: n * n,
        solver: "naive",
        setup_s,
        ticks: times.len(),
        step_times_s: times,
        peak_mem_bytes: mem_peak_since(base),
        note,
        extra: vec![("ticks_in_script", json!(n_ticks)), ("sampled", json!(!all))],
        skipped: None,
    })
}

// ---------------------------------------------------------------------------------------------
// The static comparison with SciPy.

#[derive(Debug, Clone)]
struct StaticRow {
    mesh: String,
    n_nodes: usize,
    ours_assembly_s: f64,
    ours_solve_s: f64,
    scipy: Result<Value, String>,
}

/// The phantom's slice thickness (`fixtures::PHANTOM_PLANE`, plane stress).
const PHANTOM_THICKNESS_M: f64 = match fixtures::PHANTOM_PLANE {
    needlesim_core::PlaneModel::Stress { thickness_m } => thickness_m,
    needlesim_core::PlaneModel::Strain { thickness_m } => thickness_m,
};

fn scenario_of(s: &Setup, p: &StaticProblem, n: usize) -> Scenario {
    let mut prescribed_local = Vec::new();
    for &(node, c) in &p.conditions {
        if let NodeCondition::Local { frame: angle_rad, u_m: [ut_m, un_m] } = c {
            prescribed_local.push(PrescribedLocal { node: node as i64, angle_rad, ut: ut_m, un: un_m });
        }
    }
    Scenario {
        name: Some(format!("bench-{n}x{n}-end-of-hold")),
        description: Some("needlesim-lab bench: the state at the end of the hold".to_owned()),
        nodes: s.mesh.nodes_m().to_vec(),
        triangles: s.mesh.triangles().iter().map(|t| t.map(|i| i as i64)).collect(),
        young_modulus_pa: fixtures::PHANTOM_MATERIAL.young_modulus_pa,
        nu: fixtures::PHANTOM_MATERIAL.poisson_ratio,
        plane: "stress".to_owned(),
        thickness: PHANTOM_THICKNESS_M,
        young_modulus_elem_pa: None,
        nu_elem: None,
        fixed_nodes: s.fixed.iter().map(|&n| n as i64).collect(),
        prescribed: vec![],
        prescribed_local,
        loads: p.loads_n.iter().map(|&(n, [fx, fy])| Load { node: n as i64, fx, fy }).collect(),
        points: vec![],
        working_points: None,
        working_nodes: None,
        output_stresses: false,
        solver_displacements: None,
        needle_nodes: None,
    }
}

/// `$NEEDLESIM_PYTHON`, else `tests/.venv/bin/python`, else `python3`.
fn find_python() -> PathBuf {
    if let Some(p) = std::env::var_os("NEEDLESIM_PYTHON") {
        return PathBuf::from(p);
    }
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/.venv/bin/python");
    if venv.exists() { venv } else { PathBuf::from("python3") }
}

fn scipy_script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("bench/scipy_static.py")
}

fn run_static(n: usize, problem: &StaticProblem, python: Option<&Path>) -> Result<StaticRow> {
    let s = build_setup(n)?;
    let t = Instant::now();
    let k = needlesim_core::assembly::assemble_stiffness(&s.mesh, &s.mats, None);
    let ours_assembly_s = t.elapsed().as_secs_f64();
    drop(k);
    // Best of three full solves (assembly, factorisation, solve).
    let mut ours_solve_s = f64::INFINITY;
    let mut energy = 0.0;
    for _ in 0..3 {
        let t = Instant::now();
        let sol = problem.solve(&s.mesh, &s.mats)?;
        ours_solve_s = ours_solve_s.min(t.elapsed().as_secs_f64());
        energy = sol.strain_energy_j;
    }
    let scipy = match python {
        None => Err("skipped (--no-scipy)".to_owned()),
        Some(py) => {
            let dir = std::env::temp_dir().join(format!("needlesim-bench-{}", std::process::id()));
            std::fs::create_dir_all(&dir)?;
            let path = dir.join(format!("state-{n}.json"));
            std::fs::write(&path, serde_json::to_string(&scenario_of(&s, problem, n))?)?;
            let out = std::process::Command::new(py).arg(scipy_script()).arg(&path).output();
            let _ = std::fs::remove_file(&path);
            let _ = std::fs::remove_dir(&dir);
            match out {
                Err(e) => Err(format!("skipped: cannot run {}: {e}", py.display())),
                Ok(o) if !o.status.success() => {
                    let err = String::from_utf8_lossy(&o.stderr);
                    let last = err.lines().last().unwrap_or("").to_owned();
                    Err(format!("skipped: {last}"))
                }
                Ok(o) => match serde_json::from_slice::<Value>(&o.stdout) {
                    Ok(mut v) => {
                        let e = v["strain_energy"].as_f64().unwrap_or(f64::NAN);
                        v["strain_energy_rel_diff_to_ours"] = json!((e - energy).abs() / energy.abs().max(1e-300));
                        Ok(v)
                    }
                    Err(e) => Err(format!("skipped: scipy_static.py printed no JSON: {e}")),
                },
            }
        }
    };
    Ok(StaticRow { mesh: format!("{n}x{n}"), n_nodes: n * n, ours_assembly_s, ours_solve_s, scipy })
}

/// Whether `python` can import scipy; the reason when not.
fn check_scipy(python: &Path) -> Result<(), String> {
    match std::process::Command::new(python).args(["-c", "import scipy, numpy"]).output() {
        Err(e) => Err(format!("no Python at {}: {e}", python.display())),
        Ok(o) if !o.status.success() => Err(format!("{} has no scipy/numpy", python.display())),
        Ok(_) => Ok(()),
    }
}

// ---------------------------------------------------------------------------------------------
// The command.

/// The machine: CPU model from /proc/cpuinfo and the number of logical cores.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| t.lines().find(|l| l.starts_with("model name")).map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned()))
        .unwrap_or_else(|| "unknown CPU".into());
    format!("{cpu}, {} logical cores", std::thread::available_parallelism().map_or(0, |n| n.get()))
}

const NAIVE_NOTE: &str = "naive = one full sparse solve (fresh assembly + factorisation + solve) per tick of the same script, with the conditions the simulation applied that tick; a lower bound, since a naive code needs one per active-set iteration";
const MEM_NOTE: &str = "peak_mem_bytes = peak live heap during the solver's run (setup and all steps) above the heap live when it started, from a counting global allocator";

/// Runs the benchmark; returns the JSON object and the markdown report.
pub fn run(opts: &BenchOptions) -> Result<(Value, String)> {
    let sizes = if !opts.sizes.is_empty() {
        opts.sizes.clone()
    } else if opts.quick {
        vec![19, 50, 100]
    } else {
        vec![19, 50, 100, 200, 400]
    };
    if let Some(&bad) = sizes.iter().find(|&&n| n < 3) {
        anyhow::bail!("grid size {bad} is too small: at least 3 nodes per side");
    }
    let script = Script::for_options(opts.quick);
    let naive_budget_s = if opts.quick { 2.0 } else { 30.0 };
    let python = if opts.no_scipy {
        None
    } else {
        let py = find_python();
        match check_scipy(&py) {
            Ok(()) => Some(py),
            Err(why) => {
                tracing::warn!("the SciPy comparison is skipped: {why}");
                None
            }
        }
    };
    let scipy_missing = (!opts.no_scipy && python.is_none())
        .then(|| "skipped: no Python with scipy ($NEEDLESIM_PYTHON, tests/.venv/bin/python, python3)".to_owned());
    let mut rows = Vec::new();
    let mut statics = Vec::new();
    for &n in &sizes {
        tracing::info!(mesh = %format!("{n}x{n}"), "ours");
        let (ours, deepest) = run_ours(n, &script)?;
        tracing::info!(mesh = %format!("{n}x{n}"), "dense");
        let dense = run_dense(n, &script)?;
        tracing::info!(mesh = %format!("{n}x{n}"), "naive");
        let naive = run_naive(n, &script, naive_budget_s)?;
        rows.extend([ours, dense, naive]);
        tracing::info!(mesh = %format!("{n}x{n}"), "static");
        let mut st = run_static(n, &deepest, python.as_deref())?;
        if let Some(why) = &scipy_missing {
            st.scipy = Err(why.clone());
        }
        statics.push(st);
    }
    let json = to_json(&rows, &statics, &script, opts);
    let md = to_markdown(&rows, &statics, &script);
    if let Some(p) = &opts.plot {
        plot(&rows, p)?;
    }
    Ok((json, md))
}

fn num(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

fn ours_of<'a>(rows: &'a [Row], mesh: &str) -> Option<&'a Row> {
    rows.iter().find(|r| r.mesh == mesh && r.solver == "ours")
}

fn to_json(rows: &[Row], statics: &[StaticRow], script: &Script, opts: &BenchOptions) -> Value {
    let results: Vec<Value> = rows
        .iter()
        .map(|r| {
            let mut o = json!({"mesh": r.mesh, "n_nodes": r.n_nodes, "solver": r.solver});
            if let Some(why) = &r.skipped {
                o["skipped"] = json!(why);
            } else {
                let (p50, p99, max) = r.stats();
                o["setup_s"] = num(r.setup_s);
                o["step_p50_s"] = num(p50);
                o["step_p99_s"] = num(p99);
                o["step_max_s"] = num(max);
                o["peak_mem_bytes"] = json!(r.peak_mem_bytes);
                o["ticks"] = json!(r.ticks);
                if let Some(ours) = ours_of(rows, &r.mesh) {
                    o["ratio_step_p50_to_ours"] = num(p50 / ours.stats().0);
                    o["ratio_setup_to_ours"] = num(r.setup_s / ours.setup_s);
                }
            }
            o["note"] = json!(r.note);
            for (k, v) in &r.extra {
                o[*k] = v.clone();
            }
            o
        })
        .collect();
    let st: Vec<Value> = statics
        .iter()
        .map(|s| {
            let mut o = json!({"mesh": s.mesh, "n_nodes": s.n_nodes, "ours_assembly_s": s.ours_assembly_s, "ours_solve_s": s.ours_solve_s});
            match &s.scipy {
                Ok(v) => o["scipy"] = v.clone(),
                Err(why) => o["scipy"] = json!({"skipped": why}),
            }
            o
        })
        .collect();
    json!({
        "machine": machine(),
        "quick": opts.quick,
        "script": script.describe(),
        "naive": NAIVE_NOTE,
        "peak_mem": MEM_NOTE,
        "results": results,
        "static": {
            "what": "one full static solve of the state at the end of the hold (deepest insertion): ours = StaticProblem::solve (assembly + sparse Cholesky + solve, best of 3; ours_assembly_s is the assembly alone); scipy = server/lab/bench/scipy_static.py, numpy assembly and scipy.sparse.linalg.spsolve timed separately",
            "results": st,
        },
    })
}

fn us(v: f64) -> String {
    if v.is_finite() { format!("{:.1}", v * 1e6) } else { "—".to_owned() }
}

fn secs(v: f64) -> String {
    if v >= 0.01 { format!("{v:.3}") } else { format!("{v:.2e}") }
}

fn ratio(v: f64) -> String {
    if !v.is_finite() {
        "—".to_owned()
    } else if v < 0.01 {
        format!("{v:.1e}×")
    } else if v >= 10.0 {
        format!("{v:.0}×")
    } else {
        format!("{v:.2}×")
    }
}

fn to_markdown(rows: &[Row], statics: &[StaticRow], script: &Script) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "machine: {}\n", machine());
    let _ = writeln!(s, "script: {}\n", script.describe());
    let _ = writeln!(
        s,
        "| mesh | nodes | solver | setup s | ticks timed | step p50 µs | step p99 µs | step max µs | peak heap MiB | p50 / ours | setup / ours | note |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        if let Some(why) = &r.skipped {
            let _ = writeln!(s, "| {} | {} | {} | — | — | — | — | — | — | — | — | skipped: {why} |", r.mesh, r.n_nodes, r.solver);
            continue;
        }
        let (p50, p99, max) = r.stats();
        let (rs, rt) = ours_of(rows, &r.mesh).map_or((f64::NAN, f64::NAN), |o| (p50 / o.stats().0, r.setup_s / o.setup_s));
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.1} | {} | {} | {} |",
            r.mesh,
            r.n_nodes,
            r.solver,
            secs(r.setup_s),
            r.ticks,
            us(p50),
            us(p99),
            us(max),
            r.peak_mem_bytes as f64 / (1u64 << 20) as f64,
            ratio(rs),
            ratio(rt),
            r.note
        );
    }
    let _ = writeln!(s, "\n{NAIVE_NOTE}.\n\n{MEM_NOTE}.\n");
    let _ = writeln!(s, "Static solve of the state at the end of the hold (deepest insertion):\n");
    let _ = writeln!(
        s,
        "| mesh | nodes | ours assembly s | ours full solve s | scipy assembly s | scipy spsolve s | scipy / ours (full) | energy rel. diff |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for st in statics {
        match &st.scipy {
            Ok(v) => {
                let a = v["assembly_s"].as_f64().unwrap_or(f64::NAN);
                let b = v["solve_s"].as_f64().unwrap_or(f64::NAN);
                let d = v["strain_energy_rel_diff_to_ours"].as_f64().unwrap_or(f64::NAN);
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.4} | {:.4} | {a:.4} | {b:.4} | {} | {d:.1e} |",
                    st.mesh,
                    st.n_nodes,
                    st.ours_assembly_s,
                    st.ours_solve_s,
                    ratio((a + b) / st.ours_solve_s)
                );
            }
            Err(why) => {
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.4} | {:.4} | — | — | — | {why} |",
                    st.mesh, st.n_nodes, st.ours_assembly_s, st.ours_solve_s
                );
            }
        }
    }
    s
}

fn plot(rows: &[Row], path: &Path) -> Result<()> {
    use plotters::prelude::*;
    type Series<'a> = (&'a str, RGBColor, Vec<(f64, f64)>);
    let series: Vec<Series> = [("ours", BLUE), ("dense", RED), ("naive", BLACK)]
        .into_iter()
        .map(|(name, colour)| {
            let pts = rows.iter().filter(|r| r.solver == name && r.skipped.is_none()).map(|r| (r.n_nodes as f64, r.stats().0)).collect();
            (name, colour, pts)
        })
        .collect();
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.2.iter().copied()).filter(|p| p.1 > 0.0).collect();
    anyhow::ensure!(!all.is_empty(), "nothing to plot");
    let (x0, x1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (y0, y1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    let err = |e: &dyn std::fmt::Display| anyhow::anyhow!("plot: {e}");
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption("Step time p50 against mesh size", ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0 / 1.5..x1 * 1.5).log_scale(), (y0 / 3.0..y1 * 3.0).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("mesh nodes")
        .y_desc("step time p50 (s)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v:.0}"))
        .draw()
        .map_err(|e| err(&e))?;
    for (name, colour, pts) in &series {
        if pts.is_empty() {
            continue;
        }
        let c = *colour;
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label(*name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.filled()))).map_err(|e| err(&e))?;
    }
    chart.configure_series_labels().background_style(WHITE).border_style(BLACK).draw().map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn script_is_symmetric_and_holds() {
        let s = Script::for_options(true);
        let (poses, end) = s.poses(0.05);
        assert_eq!(poses.len(), 1200 + 200 + 1200);
        assert_eq!(end, 1399);
        assert!((poses[end].y_m - 0.145).abs() < 1e-12);
        assert!((poses.last().unwrap().y_m - 0.205).abs() < 1e-12);
    }

    #[test]
    fn dense_budget_skips_big_grids() {
        assert!(dense_bytes(50) < DENSE_BUDGET_BYTES);
        assert!(dense_bytes(100) > DENSE_BUDGET_BYTES);
    }
}
