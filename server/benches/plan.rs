//! Planning benchmark (issue 8): the wall time of planning the paper's Fig. 3 insertion (median
//! over a few runs), the simulations per plan, and the predicted errors of the plan and of aiming
//! straight, with one worker thread and with one per core, at 10 mm/s and at 1 mm/s.
//! Run: `cargo bench -p needlesim-server --bench plan` (optional argument: the number of runs).

use std::ops::ControlFlow;
use std::time::Instant;

use needlesim_core::MeshLimits;
use needlesim_lab::bench::{machine, pct};
use needlesim_offline::plan::{PlanOptions, PlanRequest, plan};
use needlesim_scene::load_scene;

fn main() {
    let runs: usize = std::env::args().skip(1).find_map(|a| a.parse().ok()).unwrap_or(5);
    println!("machine: {}", machine());
    let t0 = Instant::now();
    let scene = load_scene("fig3-target", &MeshLimits::default()).expect("the fig3-target example loads");
    println!(
        "scene fig3-target: {} nodes, loaded and factorised in {:.3} s; target 'biopsy' (radius 1.5 mm); the planning example's entry region and angles; inserted at 10 mm/s (the example's speed) and at 1 mm/s (ten times the ticks per simulation)",
        scene.tissue.mesh().n_nodes(),
        t0.elapsed().as_secs_f64()
    );
    println!();
    println!(
        "| speed mm/s | threads | runs | plan wall p50 ms | min ms | max ms | simulations | iterations | wall ms per simulation | plan error mm | straight error mm |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut thread_counts = vec![1];
    if cores > 1 {
        thread_counts.push(cores);
    }
    for (speed_mm_s, threads) in [10.0, 1.0].into_iter().flat_map(|v| thread_counts.iter().map(move |&t| (v, t))) {
        let req = PlanRequest { target: "biopsy".into(), speed_m_s: Some(speed_mm_s * 1e-3), ..Default::default() };
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..runs.max(1) {
            let t = Instant::now();
            let p =
                plan(&scene, &req, &PlanOptions { threads, ..Default::default() }, |_| ControlFlow::Continue(())).expect("planning works");
            times.push(t.elapsed().as_secs_f64() * 1e3);
            last = Some(p);
        }
        times.sort_by(f64::total_cmp);
        let p = last.expect("at least one run");
        println!(
            "| {speed_mm_s} | {threads} | {} | {:.1} | {:.1} | {:.1} | {} | {} | {:.1} | {:.3} | {:.3} |",
            times.len(),
            pct(&times, 0.5),
            pct(&times, 0.0),
            pct(&times, 1.0),
            p.simulations,
            p.iterations,
            pct(&times, 0.5) / p.simulations as f64,
            p.plan.predicted_error_m * 1e3,
            p.straight.predicted_error_m * 1e3
        );
    }
    println!();
    println!(
        "Each iteration simulates a two-point stencil, in parallel when there are two threads; the plan is the same for every thread count."
    );
}
