//! Benchmark of the tissue model's pieces on structured grids: factorisation, one compliance column pair, the condensed mixed solve and one condition switch. Prints a markdown table.
//!
//! Run with `cargo bench -p needlesim-core --bench tissue`. Every grid is a 0.1 m square,
//! E = 15 kPa, ν = 0.45, plane strain, bottom edge fixed, alternating diagonals. Working nodes and
//! which of their DOFs are displacement-prescribed are drawn with a fixed seed, so runs are
//! comparable. Timings are per call, from `Instant` around the call only (setup excluded).

use std::hint::black_box;
use std::time::{Duration, Instant};

use needlesim_core::{
    Axis, ComplianceCache, Condition, Material, MaterialMap, MeshLimits, MixedSolver, NodeIdx, PlaneModel, RectMeshParams, Slot,
    TissueModel,
};
use rand::rngs::SmallRng;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};

const SEED: u64 = 20_240_611;
const GRIDS: [usize; 4] = [19, 50, 100, 200];

/// How long to sample one operation: stop at `max_reps` calls or when `budget` is spent, but take
/// at least `min_reps`.
struct Plan {
    min_reps: usize,
    max_reps: usize,
    budget: Duration,
}

struct Row {
    grid: usize,
    n_nodes: usize,
    n_dofs: usize,
    n_free: usize,
    nnz_l: usize,
    what: String,
    samples: Vec<Duration>,
}

/// Calls `f` (which returns the time of the measured part) according to `plan`, after `warmup` calls.
fn sample(plan: &Plan, warmup: usize, mut f: impl FnMut() -> Duration) -> Vec<Duration> {
    for _ in 0..warmup {
        black_box(f());
    }
    let start = Instant::now();
    let mut out = Vec::with_capacity(plan.max_reps.min(1 << 20));
    while out.len() < plan.max_reps && (out.len() < plan.min_reps || start.elapsed() < plan.budget) {
        out.push(f());
    }
    out
}

fn percentile(sorted: &[Duration], q: f64) -> Duration {
    // Nearest rank: the smallest sample with at least a fraction q of the samples at or below it.
    let rank = ((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
    sorted[rank - 1]
}

fn fmt(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1e-3 { format!("{:.2} ms", s * 1e3) } else { format!("{:.2} µs", s * 1e6) }
}

fn machine() -> String {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpuinfo
        .lines()
        .find_map(|l| l.strip_prefix("model name").and_then(|r| r.split_once(':')).map(|(_, v)| v.trim().to_owned()))
        .unwrap_or_else(|| "unknown".to_owned());
    let nproc = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{model}, nproc = {nproc}")
}

/// A working set of `n_nodes` random free nodes with random frame angles and `n_p` random
/// displacement-prescribed DOFs (the rest force-prescribed), all values random.
fn working_set(model: &TissueModel, cache: &mut ComplianceCache, rng: &mut SmallRng, n_nodes: usize, n_p: usize) -> MixedSolver {
    let mut free: Vec<usize> = (0..model.mesh().n_nodes()).filter(|&n| !model.is_fixed(n)).collect();
    free.shuffle(rng);
    let mut scratch = model.column_scratch();
    let mut s = MixedSolver::with_capacity(n_nodes);
    for &node in &free[..n_nodes] {
        cache.ensure(model, node, &mut scratch).expect("columns of a free node");
        s.add_node(cache, NodeIdx(node), rng.random_range(-std::f64::consts::PI..std::f64::consts::PI)).expect("room for the node");
    }
    let mut dofs: Vec<usize> = (0..2 * n_nodes).collect();
    dofs.shuffle(rng);
    for (i, &k) in dofs.iter().enumerate() {
        let (cond, v) = if i < n_p {
            (Condition::Displacement, rng.random_range(-1e-3..1e-3))
        } else {
            (Condition::Force, rng.random_range(-0.01..0.01))
        };
        s.set_condition(Slot::new(k / 2), Axis::of_index(k), cond, v).expect("a non-singular pivot");
    }
    s
}

/// Largest difference between the maintained hybrid matrix and a fresh one, relative to the
/// largest entry of each row (a check that the timed updates computed the right thing).
fn drift(s: &MixedSolver, cache: &ComplianceCache) -> f64 {
    let h = s.hybrid_from_scratch(cache).expect("a fresh hybrid matrix");
    let d = s.n_dofs();
    let mut worst = 0.0f64;
    for i in 0..d {
        let scale = (0..d).map(|j| h[(i, j)].abs()).fold(0.0, f64::max);
        for j in 0..d {
            worst = worst.max((s.hybrid(i, j) - h[(i, j)]).abs() / scale);
        }
    }
    worst
}

fn main() {
    // `cargo bench` passes `--bench`; ignore arguments.
    let t_start = Instant::now();
    let mut rng = SmallRng::seed_from_u64(SEED);
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for &n in &GRIDS {
        let mesh = RectMeshParams::new(n, n, 0.1, 0.1).build(&MeshLimits::default()).expect("grid");
        let plane = PlaneModel::Strain { thickness_m: 1.0 };
        let materials =
            MaterialMap::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }], plane).expect("material");
        let fixed = mesh.boundary_set("bottom").expect("bottom edge").to_vec();

        // Factorisation: assembly + symbolic + numeric, as TissueModel::new does them.
        let plan = Plan { min_reps: 10, max_reps: 500, budget: Duration::from_secs(8) };
        let factor = sample(&plan, 1, || {
            let (m, mats) = (mesh.clone(), materials.clone());
            let t0 = Instant::now();
            let model = TissueModel::new(m, mats, &fixed).expect("a fixed tissue factorises");
            let dt = t0.elapsed();
            drop(black_box(model));
            dt
        });
        let model = TissueModel::new(mesh.clone(), materials.clone(), &fixed).expect("factorises");
        let chol = model.cholesky();
        let (n_nodes, n_dofs, n_free, nnz_l) = (model.mesh().n_nodes(), model.n_dofs(), chol.n_free(), chol.factor_nnz());
        notes.push(format!("{n}×{n}: faer chose the {} factorisation", if chol.is_supernodal() { "supernodal" } else { "simplicial" }));
        let row = |what: &str, samples| Row { grid: n, n_nodes, n_dofs, n_free, nnz_l, what: what.to_owned(), samples };
        rows.push(row("factorisation (TissueModel::new)", factor));

        // One compliance column pair (two sparse solves) of a random free node.
        let free: Vec<usize> = (0..n_nodes).filter(|&i| !model.is_fixed(i)).collect();
        let mut out = vec![0.0; 2 * n_dofs];
        let mut scratch = model.column_scratch();
        let plan = Plan { min_reps: 50, max_reps: 20_000, budget: Duration::from_secs(3) };
        let columns = sample(&plan, 5, || {
            let node = free[rng.random_range(0..free.len())];
            let t0 = Instant::now();
            model.compliance_columns_into(node, &mut out, &mut scratch).expect("a free node");
            let dt = t0.elapsed();
            black_box(&out);
            dt
        });
        rows.push(row("compliance column pair", columns));

        // The mixed solve and one P <-> F switch, for two working sets.
        let mut cache = ComplianceCache::new(n_nodes);
        for (n_work, n_p) in [(30usize, 20usize), (60, 60)] {
            let d = 2 * n_work;
            let mut s = working_set(&model, &mut cache, &mut rng, n_work, n_p);
            let plan = Plan { min_reps: 1000, max_reps: 200_000, budget: Duration::from_secs(1) };
            let solve = sample(&plan, 1000, || {
                let t0 = Instant::now();
                s.solve();
                let dt = t0.elapsed();
                black_box(s.displacement_local(Slot::new(0)));
                dt
            });
            rows.push(row(&format!("MixedSolver::solve, {n_work} nodes, {n_p} P / {} F DOFs", d - n_p), solve));

            // Each call switches one DOF; the next call switches it back, then on to another DOF.
            let mut order: Vec<usize> = (0..d).collect();
            order.shuffle(&mut rng);
            let mut call = 0usize;
            let switch = sample(&plan, 1000, || {
                let k = order[(call / 2) % d];
                call += 1;
                let (slot, comp) = (Slot::new(k / 2), Axis::of_index(k));
                let (cond, v) = match s.condition(slot, comp) {
                    Condition::Force => (Condition::Displacement, 1e-4),
                    Condition::Displacement => (Condition::Force, 1e-3),
                };
                let t0 = Instant::now();
                s.set_condition(slot, comp, cond, v).expect("a non-singular pivot");
                t0.elapsed()
            });
            notes.push(format!(
                "{n}×{n}, {n_work} working nodes: after {} timed switches the updated hybrid matrix differs from a fresh one by {:.1e} (relative to each row's largest entry)",
                switch.len() + 1000,
                drift(&s, &cache)
            ));
            rows.push(row(&format!("set_condition P↔F switch, {n_work} nodes (d = {d})"), switch));
        }
    }

    println!("## needlesim-core tissue benchmark\n");
    println!("Machine: {}. Profile: bench (release, opt-level 3), faer sequential (Par::Seq).", machine());
    println!("Grids: 0.1 m square, E = 15 kPa, ν = 0.45, plane strain, bottom fixed; seed {SEED}.\n");
    println!("| grid | nodes | DOFs (free) | nnz(L) | operation | reps | median | p90 | p99 | max |");
    println!("|---|---:|---:|---:|---|---:|---:|---:|---:|---:|");
    for r in &rows {
        let mut s = r.samples.clone();
        s.sort_unstable();
        println!(
            "| {g}×{g} | {} | {} ({}) | {} | {} | {} | {} | {} | {} | {} |",
            r.n_nodes,
            r.n_dofs,
            r.n_free,
            r.nnz_l,
            r.what,
            s.len(),
            fmt(percentile(&s, 0.5)),
            fmt(percentile(&s, 0.9)),
            fmt(percentile(&s, 0.99)),
            fmt(*s.last().expect("at least one sample")),
            g = r.grid,
        );
    }
    println!();
    for n in &notes {
        println!("- {n}");
    }
    println!("\nTotal benchmark time {:.1} s.", t_start.elapsed().as_secs_f64());
}
