//! Step and stiffness-Jacobian times of one scripted motion, with the solver's update counts per
//! tick (issue 15, item 2's measurements).
//!
//! ```sh
//! cargo run --release -p needlesim-offline --example step_times -- turn 100
//! cargo run --release -p needlesim-offline --example step_times -- fig4 73
//! ```
//!
//! `turn N`: the paper phantom (server/scenes/paper-phantom.toml) on an N × N grid, rigid needle:
//! the tip inserted 60 mm at 10 mm/s, the inserted needle turned about its base +10°, −10° and
//! back at 10°/s, then withdrawn at 10 mm/s. `fig4 N`: the Fig. 4 steering scene
//! (fig4-steering.toml, flexible 22 G needle) on an N × N grid with its own trajectory. Columns
//! are prefetched between steps (the run driver's default); the Jacobian is taken every 10
//! ticks, as the real-time thread does, and timed separately.

use std::path::Path;

use needlesim_core::MeshLimits;
use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};
use needlesim_scene::{Trajectory, parse_scene};
use needlesim_trajectory::Pose2;

fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn summary(name: &str, mut t_s: Vec<f64>) {
    t_s.sort_by(f64::total_cmp);
    let us = |v: f64| v * 1e6;
    println!(
        "{name}: n {} p50 {:.1} µs, p99 {:.1} µs, p99.9 {:.1} µs, max {:.1} µs",
        t_s.len(),
        us(percentile(&t_s, 0.5)),
        us(percentile(&t_s, 0.99)),
        us(percentile(&t_s, 0.999)),
        us(*t_s.last().unwrap_or(&f64::NAN))
    );
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let motion = args.get(1).map_or("turn", String::as_str);
    let n: usize = args.get(2).map_or(Ok(100), |s| s.parse())?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let (file, traj) = match motion {
        "turn" => {
            let down = -std::f64::consts::FRAC_PI_2;
            let ten = 10f64.to_radians();
            let (x, y0) = (0.05, 0.205);
            let y1 = y0 - 0.065; // tip 5 mm above the surface: 60 mm deep
            let p = |t: f64, y: f64, th: f64| (t, Pose2::new(x, y, th));
            let samples = vec![
                p(0.0, y0, down),
                p(6.5, y1, down),
                p(7.5, y1, down + ten),
                p(9.5, y1, down - ten),
                p(10.5, y1, down),
                p(17.0, y0, down),
            ];
            ("paper-phantom.toml", Trajectory::from_samples(samples))
        }
        "fig4" => {
            let csv = std::fs::read_to_string(root.join("fig4-steering.csv"))?;
            ("fig4-steering.toml", Trajectory::parse_csv(&csv)?)
        }
        other => anyhow::bail!("unknown motion {other}: turn or fig4"),
    };
    let text = std::fs::read_to_string(root.join(file))?.replace("nx = 19", &format!("nx = {n}")).replace("ny = 19", &format!("ny = {n}"));
    let limits = MeshLimits { max_nodes: usize::MAX, max_triangles: usize::MAX };
    let scene = parse_scene(&text, &root, &limits)?;
    let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(&traj), RunOptions::default())?;
    let mut steps = Vec::new();
    let mut jacobians = Vec::new();
    let (mut max_pivots, mut max_rotations, mut max_d) = (0, 0, 0);
    let mut prev = run.sim().solver().stats();
    while let Some(tick) = run.next_tick()? {
        steps.push(tick.step_s);
        let st = run.sim().solver().stats();
        max_pivots = max_pivots.max(st.n_pivots - prev.n_pivots);
        max_rotations = max_rotations.max(st.n_rotations - prev.n_rotations);
        max_d = max_d.max(2 * run.sim().solver().n_nodes());
        if tick.k % 10 == 0 {
            let t = std::time::Instant::now();
            run.sim_mut().stiffness_jacobian()?;
            jacobians.push(t.elapsed().as_secs_f64());
        }
        prev = run.sim().solver().stats();
    }
    let (sim, _) = run.finish()?;
    let st = sim.stats();
    let ms = sim.solver().stats();
    println!("{motion} on {n}x{n} ({} ticks): max d = {max_d}", st.ticks);
    summary("step", steps);
    summary("jacobian", jacobians);
    println!(
        "solver: {} pivots ({:.2}/tick, max {max_pivots}), {} rotations ({:.2}/tick, max {max_rotations}); unconverged ticks {}, column misses {}",
        ms.n_pivots,
        ms.n_pivots as f64 / st.ticks as f64,
        ms.n_rotations,
        ms.n_rotations as f64 / st.ticks as f64,
        st.unconverged_ticks,
        st.column_misses
    );
    if let Some(c) = sim.coupling_stats() {
        println!("coupling: {} factorisations, {} low-rank corrections", c.factorisations, c.low_rank_updates);
    }
    Ok(())
}
