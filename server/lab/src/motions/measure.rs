//! The motion suite's measurement: each case run tick by tick with the step timed alone and
//! the solver's and the thread's counters kept per tick ([`TickRecord`], [`CaseResult`]), and
//! the suite over every motion and size ([`run_suite`]).

use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use needlesim_core::compliance::TissueModel;
use needlesim_core::fixtures::{self, PHANTOM_SIDE_M};
use needlesim_core::mixed::MixedStats;
use needlesim_core::sim::SimStats;
use needlesim_offline::ConvergencePolicy;
use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};

use super::report::us;
use super::script::{MotionScript, script, sim_params};
use super::{ContactChoice, JACOBIAN_EVERY_TICKS, Motion, MotionOptions, Pace, TARGET_MAX_S, TARGET_P999_S};
use crate::bench::pct;

/// One tick's counters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TickRecord {
    pub tick: usize,
    pub step_s: f64,
    pub converged: bool,
    pub active_set_iterations: usize,
    /// Pivots of the mixed solver in this tick.
    pub pivots: u64,
    /// Frame rotations of the mixed solver in this tick.
    pub rotations: u64,
    /// Stick→slip plus slip→stick changes.
    pub stick_slip_changes: u64,
    pub captures: u64,
    pub releases: u64,
    pub deferrals: u64,
    /// Extra working-set solves on a settled flexible shape.
    pub shape_passes: u64,
    /// Working set after the step.
    pub d: usize,
    /// Time the thread spent waiting on a run queue around this step (ns; [`ThreadCounters`]):
    /// a step that waited was preempted by another process, and its time is not all the solver's.
    pub cpu_wait_ns: u64,
    /// Page faults around this step ([`ThreadCounters`]).
    pub page_faults: u64,
    /// Columns computed by the prefetch just before this step (it streams the sparse factor
    /// through the caches, so the step after it starts cold).
    pub columns_before: u64,
    /// Nanoseconds in each stage of the step ([`needlesim_core::sim::STAGE_NAMES`]).
    pub stage_ns: [u64; needlesim_core::sim::N_STAGES],
}

/// Nanoseconds on a monotonic clock since its first reading: the step's stage clock.
fn monotonic_ns() -> u64 {
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_nanos() as u64
}

/// One (motion, mesh) case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    pub motion: Motion,
    pub n: usize,
    pub contact: ContactChoice,
    pub needle_label: String,
    /// The script's poses (ticks it should step).
    pub script_ticks: usize,
    pub ticks: Vec<TickRecord>,
    /// Stiffness Jacobian times (s), one per [`JACOBIAN_EVERY_TICKS`] ticks.
    pub jacobian_s: Vec<f64>,
    pub jacobian_errors: usize,
    pub stats: SimStats,
    pub solver: MixedStats,
    /// Largest working set over the run.
    pub d_max: usize,
    /// Working set at the deepest tick.
    pub d_deepest: usize,
    /// Working set after the last tick.
    pub d_final: usize,
    /// Factorisation of the mesh (shared by its cases), s.
    pub setup_s: f64,
    /// Column prefetch between steps, total s.
    pub prefetch_s: f64,
    pub prefetched_nodes: u64,
    /// Bytes of compliance columns cached at the end of the run (never evicted).
    pub column_cache_bytes: usize,
    /// Deepest tip below the top surface over the run (m).
    pub tip_depth_max_m: f64,
    /// The tip at the deepest tick (m).
    pub tip_deepest_m: [f64; 2],
    /// Range of the applied base angle (rad).
    pub theta_range_rad: [f64; 2],
    /// Range of the tip's x over the run (m).
    pub tip_x_range_m: [f64; 2],
    /// Range of the base's x over the run (m).
    pub base_x_range_m: [f64; 2],
    /// Bevel side before the first step and after the last.
    pub bevel_side_first_last: [f64; 2],
    /// The smallest working set during the turning phase (turning motion; else 0).
    pub d_min_turning: usize,
    /// The 1-min load average at the start and end of the case.
    pub load_avg: [f64; 2],
    pub wall_s: f64,
    /// Why the run stopped early, if it did.
    pub failed: Option<String>,
}

/// Step time quantiles (s): p50, p99, p99.9, max.
pub fn step_quantiles(records: &[TickRecord]) -> [f64; 4] {
    let mut t: Vec<f64> = records.iter().map(|r| r.step_s).collect();
    t.sort_by(f64::total_cmp);
    [pct(&t, 0.5), pct(&t, 0.99), pct(&t, 0.999), pct(&t, 1.0)]
}

impl CaseResult {
    /// p50, p99, p99.9, max of the step (s).
    pub fn step_quantiles(&self) -> [f64; 4] {
        step_quantiles(&self.ticks)
    }
    /// Ticks that waited on a run queue (preempted by another process) during the step.
    pub fn preempted_ticks(&self) -> usize {
        self.ticks.iter().filter(|r| r.cpu_wait_ns > 0).count()
    }
    /// p99.9 and max of the step over the ticks that never waited on a run queue (s).
    pub fn unpreempted_quantiles(&self) -> [f64; 2] {
        let mut t: Vec<f64> = self.ticks.iter().filter(|r| r.cpu_wait_ns == 0).map(|r| r.step_s).collect();
        t.sort_by(f64::total_cmp);
        [pct(&t, 0.999), pct(&t, 1.0)]
    }
    /// p50, p99, max of the Jacobian (s).
    pub fn jacobian_quantiles(&self) -> [f64; 3] {
        let mut t = self.jacobian_s.clone();
        t.sort_by(f64::total_cmp);
        [pct(&t, 0.5), pct(&t, 0.99), pct(&t, 1.0)]
    }
    /// The slowest ticks, slowest first (all, or only those no other process preempted).
    pub fn worst(&self, k: usize, unpreempted: bool) -> Vec<TickRecord> {
        let mut w: Vec<TickRecord> = self.ticks.iter().filter(|r| !unpreempted || r.cpu_wait_ns == 0).cloned().collect();
        w.sort_by(|a, b| b.step_s.total_cmp(&a.step_s));
        w.truncate(k);
        w
    }
    /// The targets this case misses (empty: all met).
    pub fn misses(&self) -> Vec<String> {
        let mut m = Vec::new();
        if let Some(why) = &self.failed {
            m.push(format!("failed: {why}"));
        }
        let [_, _, p999, max] = self.step_quantiles();
        // NaN (no ticks) misses too.
        if p999.is_nan() || p999 > TARGET_P999_S {
            m.push("p99.9".to_owned());
        }
        if max.is_nan() || max > TARGET_MAX_S {
            m.push("max".to_owned());
        }
        if self.stats.unconverged_ticks > 0 {
            m.push(format!("{} unconverged", self.stats.unconverged_ticks));
        }
        if self.stats.column_misses > 0 {
            m.push(format!("{} column misses", self.stats.column_misses));
        }
        m
    }
    /// What is not one of the targets but a run should not do: capacity overflows (a
    /// candidate-buffer growth is an allocation inside a step), failed Jacobians.
    pub fn notes(&self) -> Vec<String> {
        let s = &self.stats;
        let mut m = Vec::new();
        for (n, what) in [
            (s.capacity_drops, "contacts dropped at capacity"),
            (s.capture_overflow, "capture-list overflows"),
            (s.approaching_overflow, "approaching-list overflows"),
            (s.candidate_growths, "candidate-buffer growth (an allocation in a step)"),
            (s.curve_capacity_drops, "curve capacity drops"),
            (s.shape_capped_ticks, "ticks whose flexible shape passes stopped at their cap"),
            (self.jacobian_errors as u64, "failed Jacobians"),
        ] {
            if n > 0 {
                m.push(format!("{n} {what}"));
            }
        }
        m
    }
}

/// This thread's counters from procfs, read around each step to tell a slow step from one the
/// machine slowed: the time waited on a run queue (`/proc/thread-self/schedstat`, its second
/// field: another process had the core) and the page faults (`/proc/thread-self/stat`, minflt +
/// majflt). Missing files (a kernel without schedstats) read as `None`.
pub struct ThreadCounters {
    schedstat: Option<std::fs::File>,
    stat: Option<std::fs::File>,
    buf: String,
}

/// One reading of [`ThreadCounters`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ThreadSample {
    /// Time waited on a run queue so far (ns).
    pub wait_ns: Option<u64>,
    /// Minor and major page faults so far.
    pub page_faults: Option<u64>,
}

impl ThreadCounters {
    /// Opens this thread's files.
    pub fn open() -> Self {
        let open = |p: &str| std::fs::File::open(p).ok();
        Self { schedstat: open("/proc/thread-self/schedstat"), stat: open("/proc/thread-self/stat"), buf: String::with_capacity(512) }
    }
    fn read(file: Option<&mut std::fs::File>, buf: &mut String) -> Option<()> {
        use std::io::{Read, Seek};
        let f = file?;
        buf.clear();
        f.rewind().ok()?;
        f.read_to_string(buf).ok()?;
        Some(())
    }
    /// The counters now.
    pub fn sample(&mut self) -> ThreadSample {
        let wait_ns = Self::read(self.schedstat.as_mut(), &mut self.buf).and_then(|()| self.buf.split_whitespace().nth(1)?.parse().ok());
        let page_faults = Self::read(self.stat.as_mut(), &mut self.buf).and_then(|()| {
            // After the command name in parentheses: state, ppid, pgrp, session, tty_nr, tpgid,
            // flags, minflt, cminflt, majflt.
            let rest = &self.buf[self.buf.rfind(')')? + 1..];
            let f: Vec<&str> = rest.split_whitespace().take(10).collect();
            Some(f.get(7)?.parse::<u64>().ok()? + f.get(9)?.parse::<u64>().ok()?)
        });
        ThreadSample { wait_ns, page_faults }
    }
}

fn load_avg() -> f64 {
    std::fs::read_to_string("/proc/loadavg").ok().and_then(|s| s.split_whitespace().next().and_then(|v| v.parse().ok())).unwrap_or(f64::NAN)
}

fn range(r: &mut [f64; 2], v: f64) {
    r[0] = r[0].min(v);
    r[1] = r[1].max(v);
}

/// Runs one script on a factorised model (`setup_s`: how long its factorisation took).
///
/// Errors: the simulation cannot be built from the parameters. A step, Jacobian or prefetch
/// failure mid-run does not fail: the case records it ([`CaseResult::failed`]) with the ticks
/// before it.
pub fn run_case(script: &MotionScript, model: &Arc<TissueModel>, setup_s: f64, opts: &MotionOptions) -> Result<CaseResult> {
    let started = Instant::now();
    let load_start = load_avg();
    let n = (model.mesh().n_nodes() as f64).sqrt().round() as usize;
    let params = sim_params(script, model, opts.contact, opts.spacing_m);
    let mut run = ScriptedRun::new(
        model.clone(),
        params,
        Script::Poses(&script.poses),
        RunOptions { max_ticks: u64::MAX, prefetch_nodes_per_tick: Some(0), convergence: ConvergencePolicy::Keep },
    )?;
    let mut res = CaseResult {
        motion: script.motion,
        n,
        contact: opts.contact,
        needle_label: script.needle_label.clone(),
        script_ticks: script.poses.len(),
        ticks: Vec::with_capacity(script.poses.len()),
        jacobian_s: Vec::with_capacity(script.poses.len() / JACOBIAN_EVERY_TICKS + 1),
        jacobian_errors: 0,
        stats: SimStats::default(),
        solver: MixedStats::default(),
        d_max: 0,
        d_deepest: 0,
        d_final: 0,
        setup_s,
        prefetch_s: 0.0,
        prefetched_nodes: 0,
        column_cache_bytes: 0,
        tip_depth_max_m: f64::NEG_INFINITY,
        tip_deepest_m: [f64::NAN; 2],
        theta_range_rad: [f64::INFINITY, f64::NEG_INFINITY],
        tip_x_range_m: [f64::INFINITY, f64::NEG_INFINITY],
        base_x_range_m: [f64::INFINITY, f64::NEG_INFINITY],
        bevel_side_first_last: [run.sim().bevel_side(), f64::NAN],
        d_min_turning: if script.motion == Motion::Turning { usize::MAX } else { 0 },
        load_avg: [load_start, f64::NAN],
        wall_s: 0.0,
        failed: None,
    };
    run.sim_mut().set_stage_clock(Some(monotonic_ns));
    let mut counters = ThreadCounters::open();
    let turning = script.phases.iter().position(|p| p.name == "turn").map(|i| {
        let end = script.phases.get(i + 1).map_or(script.poses.len(), |p| p.first_tick);
        script.phases[i].first_tick..end
    });
    loop {
        let k = run.next_k() as usize;
        let mut columns_before = 0;
        if k > 0 {
            // Between steps, untimed as the step: the columns of the nodes the last step reported
            // as approaching (as the server's column worker would provide them).
            let t = Instant::now();
            match run.sim_mut().prefetch_columns(opts.prefetch_nodes_per_tick) {
                Ok(c) => {
                    columns_before = c as u64;
                    res.prefetched_nodes += c as u64;
                }
                Err(e) => {
                    res.failed = Some(format!("prefetch after tick {}: {e}", k - 1));
                    break;
                }
            }
            res.prefetch_s += t.elapsed().as_secs_f64();
            let bytes = run.sim().cache().column_bytes();
            if let Some(limit) = opts.max_column_bytes
                && bytes > limit
            {
                res.failed = Some(format!(
                    "column cache {:.2} GB over the limit of {:.2} GB after tick {}",
                    bytes as f64 / 1e9,
                    limit as f64 / 1e9,
                    k - 1
                ));
                break;
            }
        }
        if script.flip_tick == Some(k) {
            run.sim_mut().flip_bevel();
        }
        let (sim_before, solver_before) = (run.sim().stats(), run.sim().solver().stats());
        let before = counters.sample();
        let tick = match run.next_tick() {
            Ok(Some(t)) => t,
            Ok(None) => break,
            Err(e) => {
                res.failed = Some(format!("{e:#}"));
                break;
            }
        };
        let after = counters.sample();
        let delta = |a: Option<u64>, b: Option<u64>| a.zip(b).map_or(0, |(a, b)| b.saturating_sub(a));
        let sim = run.sim();
        let (s, v) = (sim.stats(), sim.solver().stats());
        let out = sim.output();
        let d = out.needle_nodes.len();
        res.ticks.push(TickRecord {
            tick: k,
            step_s: tick.step_s,
            converged: out.converged,
            active_set_iterations: out.active_set_iterations,
            pivots: v.n_pivots - solver_before.n_pivots,
            rotations: v.n_rotations - solver_before.n_rotations,
            stick_slip_changes: (s.stick_to_slip + s.slip_to_stick) - (sim_before.stick_to_slip + sim_before.slip_to_stick),
            captures: s.captures - sim_before.captures,
            releases: s.releases - sim_before.releases,
            deferrals: s.column_deferrals - sim_before.column_deferrals,
            shape_passes: s.shape_passes - sim_before.shape_passes,
            d,
            cpu_wait_ns: delta(before.wait_ns, after.wait_ns),
            page_faults: delta(before.page_faults, after.page_faults),
            columns_before,
            stage_ns: out.stage_ns,
        });
        res.d_max = res.d_max.max(d);
        if k == script.deepest_tick {
            res.d_deepest = d;
            res.tip_deepest_m = out.tip_m;
        }
        if turning.as_ref().is_some_and(|r| r.contains(&k)) {
            res.d_min_turning = res.d_min_turning.min(d);
        }
        res.tip_depth_max_m = res.tip_depth_max_m.max(PHANTOM_SIDE_M - out.tip_m[1]);
        range(&mut res.theta_range_rad, out.base.theta_rad);
        range(&mut res.tip_x_range_m, out.tip_m[0]);
        range(&mut res.base_x_range_m, out.base.x_m);
        if k.is_multiple_of(JACOBIAN_EVERY_TICKS) {
            let t = Instant::now();
            let j = run.sim_mut().stiffness_jacobian();
            res.jacobian_s.push(t.elapsed().as_secs_f64());
            res.jacobian_errors += j.is_err() as usize;
        }
    }
    let sim = run.sim();
    res.stats = sim.stats();
    res.solver = sim.solver().stats();
    res.d_final = sim.output().needle_nodes.len();
    res.column_cache_bytes = sim.cache().column_bytes();
    res.bevel_side_first_last[1] = sim.bevel_side();
    if res.d_min_turning == usize::MAX {
        res.d_min_turning = 0;
    }
    res.load_avg[1] = load_avg();
    res.wall_s = started.elapsed().as_secs_f64();
    Ok(res)
}

/// The suite: every motion on every size.
pub struct Suite {
    pub pace: Pace,
    pub scripts: Vec<MotionScript>,
    pub cases: Vec<CaseResult>,
}

/// Runs the suite.
///
/// Errors: a grid under 3 nodes per side, a scene that does not load, a model that does not
/// factorise, parameters the simulation refuses.
pub fn run_suite(opts: &MotionOptions) -> Result<Suite> {
    let sizes = opts.sizes();
    if let Some(&bad) = sizes.iter().find(|&&n| n < 3) {
        anyhow::bail!("grid size {bad} is too small: at least 3 nodes per side");
    }
    let pace = Pace::of(opts.quick);
    let scripts: Vec<MotionScript> = opts.motions().into_iter().map(|m| script(m, pace)).collect::<Result<_>>()?;
    let total = sizes.len() * scripts.len();
    let mut cases = Vec::with_capacity(total);
    for &n in &sizes {
        let (mesh, mats, fixed) = fixtures::phantom_parts(n);
        let t = Instant::now();
        let model = Arc::new(TissueModel::new(mesh, mats, &fixed).with_context(|| format!("factorising the {n}x{n} phantom"))?);
        let setup_s = t.elapsed().as_secs_f64();
        for s in &scripts {
            if opts.progress {
                eprintln!(
                    "[{}/{total}] {} {n}x{n} ({:?}): {} ticks… (load {:.2})",
                    cases.len() + 1,
                    s.motion.name(),
                    opts.contact,
                    s.poses.len(),
                    load_avg()
                );
            }
            let c = run_case(s, &model, setup_s, opts)?;
            if opts.progress {
                let [p50, p99, p999, max] = c.step_quantiles();
                let misses = c.misses();
                eprintln!(
                    "[{}/{total}] {} {n}x{n}: p50 {} p99 {} p99.9 {} max {} µs, {} unconverged, {} misses, {} deferrals, d {} (max {}), prefetch {:.1} s ({:.2} GB of columns), wall {:.1} s, load {:.2}{}{}",
                    cases.len() + 1,
                    s.motion.name(),
                    us(p50),
                    us(p99),
                    us(p999),
                    us(max),
                    c.stats.unconverged_ticks,
                    c.stats.column_misses,
                    c.stats.column_deferrals,
                    c.d_deepest,
                    c.d_max,
                    c.prefetch_s,
                    c.column_cache_bytes as f64 / 1e9,
                    c.wall_s,
                    c.load_avg[1],
                    if misses.is_empty() { " — targets met".to_owned() } else { format!(" — misses: {}", misses.join(", ")) },
                    if c.notes().is_empty() { String::new() } else { format!(" ({})", c.notes().join(", ")) }
                );
            }
            cases.push(c);
        }
    }
    Ok(Suite { pace, scripts, cases })
}
