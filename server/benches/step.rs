//! Step-time benchmark of the insertion model: a full insertion and withdrawal on N × N grids,
//! reporting the per-tick compute time (p50, p99, max). Run: `cargo bench -p needlesim-server --bench step`.
//! Optional argument: the grid sizes, e.g. `-- 19 50`.

use std::sync::Arc;
use std::time::Instant;

use needlesim_core::compliance::TissueModel;
use needlesim_core::sim::{SimParams, Simulation};
use needlesim_core::{
    BasePose, Material, MaterialMap, MeshLimits, NeedleShape, PlaneModel, RectMeshParams, RegionNeedleParams, RigidNeedle,
};

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| t.lines().find(|l| l.starts_with("model name")).map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned()))
        .unwrap_or_else(|| "unknown CPU".into());
    format!("{cpu}, {} logical cores", std::thread::available_parallelism().map_or(0, |n| n.get()))
}

fn pct(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![19, 50, 100, 200] } else { sizes };
    println!("machine: {}", machine());
    println!(
        "insertion 60 mm deep at 10 mm/s, 1 s hold, withdrawal at 10 mm/s; 1 kHz ticks; 0.1 m square, E = 30 kPa, ν = 0.45, plane stress 1 cm, bottom fixed"
    );
    println!();
    println!(
        "| mesh | nodes | setup (factorise) s | columns computed | max needle nodes | ticks | step p50 µs | step p99 µs | step max µs | mean µs | misses |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for n in sizes {
        let t0 = Instant::now();
        let mesh = RectMeshParams::new(n, n, 0.1, 0.1).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 30e3, poisson_ratio: 0.45 }],
            PlaneModel::Stress { thickness_m: 0.01 },
        )
        .unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        let h = 0.1 / (n - 1) as f64;
        let x = ((n - 1) / 2) as f64 * h;
        let model = Arc::new(TissueModel::new(mesh, mats, &fixed).unwrap());
        let setup_s = t0.elapsed().as_secs_f64();
        let base = BasePose::new(x, 0.205, -std::f64::consts::FRAC_PI_2);
        let params = SimParams {
            needle: NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }),
            initial_pose: base,
            capture_radius_m: 0.3 * h,
            max_needle_nodes: 160,
            regions: vec![RegionNeedleParams::default()],
            targets: vec![],
            tick_rate_hz: 1000.0,
            max_base_step_m: 0.002,
            max_base_step_rad: 0.05,
            max_active_set_iterations: 12,
            lookahead_m: 0.01,
        };
        let mut sim = Simulation::new(model.clone(), params).unwrap();
        let mut poses = Vec::new();
        let (y0, y1) = (0.205, 0.145);
        let ticks = ((y0 - y1) / 0.01 * 1000.0) as usize;
        for k in 1..=ticks {
            poses.push(BasePose::new(x, y0 + (y1 - y0) * k as f64 / ticks as f64, base.theta_rad));
        }
        poses.extend(std::iter::repeat_n(*poses.last().unwrap(), 1000));
        for k in 1..=ticks {
            poses.push(BasePose::new(x, y1 + (y0 - y1) * k as f64 / ticks as f64, base.theta_rad));
        }
        let mut times = Vec::with_capacity(poses.len());
        let mut max_nodes = 0;
        let mut prefetched = 0;
        for p in &poses {
            let t = Instant::now();
            let o = sim.step(*p).unwrap();
            times.push(t.elapsed().as_secs_f64() * 1e6);
            max_nodes = max_nodes.max(o.needle_nodes.len());
            prefetched += sim.prefetch_columns(64).unwrap();
        }
        let mean = times.iter().sum::<f64>() / times.len() as f64;
        times.sort_by(f64::total_cmp);
        println!(
            "| {n}×{n} | {} | {setup_s:.3} | {prefetched} | {max_nodes} | {} | {:.1} | {:.1} | {:.1} | {mean:.1} | {} |",
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
