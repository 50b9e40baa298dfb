//! Step-time benchmark of the insertion model: a full insertion and withdrawal on N × N grids,
//! reporting the per-tick compute time (p50, p99, max), for the rigid needle, a flexible 17-gauge
//! needle on the same path, and a flexible 22-gauge needle steered by a 5 mm lateral base step
//! (the Fig. 4 path). Run: `cargo bench -p needlesim-server --bench step`.
//! Optional argument: the grid sizes, e.g. `-- 19 50`.

use std::time::Instant;

use needlesim_core::fixtures::phantom_bench;
use needlesim_core::{BasePose, FlexibleNeedle, NeedleShape};
use needlesim_lab::bench::{machine, pct};
use needlesim_offline::ConvergencePolicy;
use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![19, 50, 100, 200] } else { sizes };
    println!("machine: {}", machine());
    println!(
        "insertion 60 mm deep at 10 mm/s, 1 s hold, withdrawal at 10 mm/s; 1 kHz ticks; 0.1 m square, E = 30 kPa, ν = 0.45, plane stress 1 cm, bottom fixed"
    );
    println!();
    println!(
        "| mesh | needle | nodes | setup (factorise) s | columns computed | max needle nodes | ticks | step p50 µs | step p99 µs | step max µs | mean µs | misses |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for n in sizes {
        for needle in ["rigid", "flexible 17 G", "flexible 22 G, Fig. 4 path"] {
            let t0 = Instant::now();
            let (model, mut params) = phantom_bench(n);
            let setup_s = t0.elapsed().as_secs_f64();
            let base = params.initial_pose;
            let x = base.x_m;
            let mut f = FlexibleNeedle::gauge17_steel(0.1);
            let mut poses = Vec::new();
            let (y0, y1) = (0.205, 0.145);
            let ticks = ((y0 - y1) / 0.01 * 1000.0) as usize;
            let fig4 = needle.contains("Fig. 4");
            if fig4 {
                // 22 G: EI scales with the tube's I (0.0687 × 17 G); 35 mm in, 5 mm sideways, 25 mm more.
                f.flexural_rigidity_nm2 *= 0.0687;
                let down = |from: f64, to: f64, x: f64, poses: &mut Vec<BasePose>| {
                    let m = ((from - to) / 1e-5).round() as usize;
                    poses.extend((1..=m).map(|k| BasePose::new(x, from + (to - from) * k as f64 / m as f64, base.theta_rad)));
                };
                down(y0, 0.165, x, &mut poses);
                poses.extend((1..=50).map(|k| BasePose::new(x + 0.005 * k as f64 / 50.0, 0.165, base.theta_rad)));
                down(0.165, y1, x + 0.005, &mut poses);
                poses.extend(std::iter::repeat_n(*poses.last().unwrap(), 1000));
                down(y1, y0, x + 0.005, &mut poses);
            } else {
                for k in 1..=ticks {
                    poses.push(BasePose::new(x, y0 + (y1 - y0) * k as f64 / ticks as f64, base.theta_rad));
                }
                poses.extend(std::iter::repeat_n(*poses.last().unwrap(), 1000));
                for k in 1..=ticks {
                    poses.push(BasePose::new(x, y1 + (y0 - y1) * k as f64 / ticks as f64, base.theta_rad));
                }
            }
            if needle != "rigid" {
                params.needle = NeedleShape::Flexible(f);
            }
            // The offline driver times each step alone and computes up to 64 columns between
            // steps (untimed), as this bench always has.
            let opts = RunOptions { max_ticks: u64::MAX, prefetch_nodes_per_tick: Some(64), convergence: ConvergencePolicy::Keep };
            let mut run = ScriptedRun::new(model.clone(), params, Script::Poses(&poses), opts).unwrap();
            let mut times = Vec::with_capacity(poses.len());
            let mut max_nodes = 0;
            while let Some(tick) = run.next_tick().unwrap() {
                times.push(tick.step_s * 1e6);
                max_nodes = max_nodes.max(run.output().needle_nodes.len());
            }
            let prefetched = run.prefetched_columns();
            let sim = run.sim();
            let mean = times.iter().sum::<f64>() / times.len() as f64;
            times.sort_by(f64::total_cmp);
            println!(
                "| {n}×{n} | {needle} | {} | {setup_s:.3} | {prefetched} | {max_nodes} | {} | {:.1} | {:.1} | {:.1} | {mean:.1} | {} |",
                n * n,
                times.len(),
                pct(&times, 0.5),
                pct(&times, 0.99),
                pct(&times, 1.0),
                sim.stats().column_misses
            );
            assert_eq!(model.cholesky().n_numeric_factorisations(), 1);
        }
    }
}
