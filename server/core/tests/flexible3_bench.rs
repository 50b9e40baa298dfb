//! Step time of the flexible and bevel-tip needles in 3D (issue 18) on the 48,000-tetrahedron
//! cube at 1 kHz: p50 / p99 / p99.9 / max per step over all steps and over the steps during
//! which no other process had the core (`/proc/thread-self/schedstat`), the rigid needle on the
//! same script for reference. Timing only, so `#[ignore]`:
//!
//! ```sh
//! cargo test -p needlesim-core --test flexible3_bench -- --ignored --nocapture            # dev profile (the core is opt-level 3)
//! cargo test --release -p needlesim-core --test flexible3_bench -- --ignored --nocapture  # release
//! ```
//!
//! The cube: `box_phantom3(21)` (0.1 m, 21³ nodes, 48,000 tetrahedra, E = 30 kPa, ν = 0.45,
//! bottom fixed; friction 10 N/m, puncture 0.3 N), cutting force 0.2 N (so a bevel pushes
//! 0.1 N sideways), a 0.12 m needle entering the top face off-node at (51.3, 48.7) mm. The
//! needles: rigid; flexible 17-gauge steel (EI = 0.031 N·m², 60 links of 2 mm, symmetric tip);
//! bevel (EI × 0.05, about a 23-gauge, bevel force ratio 0.5: the needle of the arc tests in
//! sim3_flexible.rs). The script, 7,500 ticks of 1 ms:
//!
//! | phase | ticks | motion |
//! |---|---|---|
//! | insert | 2250 | 45 mm down at 20 mm/s (the tip from 5 mm above to 40 mm deep) |
//! | roll | 500 | a half turn about the needle's own axis, depth held |
//! | spin | 1000 | 20 mm more at 20 mm/s, duty-cycled spinning δ = 0.5 (a turn in the first half of every 1 mm) |
//! | tilt | 500 | the base turned 4° about world y through the entry point |
//! | withdraw | 3250 | 65 mm back at 20 mm/s |
//!
//! Every 10 ticks with points held, the wrench stiffness (what the live session refreshes for a
//! device's local model; a flexible needle's has the rod in series) is timed apart and together
//! with its tick's step. Columns are prefetched between steps (not timed); no step computes one
//! (asserted).

use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
use needlesim_core::needle::FlexibleNeedle;
use needlesim_core::sim3::{BasePose3, NeedleShape3, Simulation3};

mod timing;
use timing::{Times, load_avg, timed};

const ENTRY: [f64; 3] = [0.0513, 0.0487, 0.1];
/// Advance per 1 ms tick at 20 mm/s, m.
const V: f64 = 2e-5;
const PHASES: [&str; 5] = ["insert", "roll", "spin", "tilt", "withdraw"];

fn along(p: BasePose3, d: f64) -> BasePose3 {
    let t = p.axis();
    BasePose3::from_rotation([p.position_m[0] + d * t[0], p.position_m[1] + d * t[1], p.position_m[2] + d * t[2]], p.orientation)
}

/// The script of the module docs: (phase index, pose) per tick.
fn script(start: BasePose3) -> Vec<(usize, BasePose3)> {
    let mut v: Vec<(usize, BasePose3)> = (1..=2250).map(|k| (0, along(start, V * k as f64))).collect();
    let at = v.last().unwrap().1;
    for k in 1..=500 {
        v.push((1, at.rotated_about_axis(at.position_m, at.axis(), std::f64::consts::PI * k as f64 / 500.0)));
    }
    let at = v.last().unwrap().1;
    // δ = 0.5 over a 1 mm period (50 ticks): a full turn over its first 25 ticks.
    for k in 1..=1000usize {
        let p = along(at, V * k as f64);
        let (period, phase) = (k / 50, k % 50);
        let roll = std::f64::consts::TAU * (period as f64 + (phase as f64 / 25.0).min(1.0));
        v.push((2, p.rotated_about_axis(p.position_m, p.axis(), roll)));
    }
    let at = v.last().unwrap().1;
    for k in 1..=500 {
        v.push((3, at.rotated_about_axis(ENTRY, [0.0, 1.0, 0.0], 4f64.to_radians() * k as f64 / 500.0)));
    }
    let at = v.last().unwrap().1;
    v.extend((1..=3250).map(|k| (4, along(at, -V * k as f64))));
    v
}

/// Runs the script with `needle` on the 21³ cube; prints and returns the table rows.
fn bench(label: &str, needle: Option<NeedleShape3>) -> Vec<String> {
    let mut params = box_phantom3_params(ENTRY, 0.005);
    if let Some(n) = needle {
        params.needle = n;
    }
    params.regions[0].cutting_force_n = 0.2;
    params.max_base_step_rad = 0.5;
    let model = box_phantom3(21);
    let (n_nodes, n_tets) = (model.mesh().n_nodes(), model.mesh().n_tets());
    let mut sim = Simulation3::new(model, params).unwrap();
    let poses = script(sim.pose());
    for _ in 0..64 {
        sim.step(sim.pose()).unwrap();
        sim.prefetch_columns(usize::MAX).unwrap();
    }
    let mut all = Times::default();
    let mut phases: Vec<Times> = PHASES.iter().map(|_| Times::default()).collect();
    let (mut stiffness, mut with_stiffness) = (Times::default(), Times::default());
    let (mut max_d, mut capped) = (0, 0);
    let load_before = load_avg();
    for (k, (phase, p)) in poses.iter().enumerate() {
        let (r, dt, pre) = timed(|| sim.step(*p).map(|o| (o.contacts.len(), o.converged)));
        let (d, converged) = r.unwrap_or_else(|e| panic!("{label}, tick {k}: {e}"));
        max_d = max_d.max(d);
        capped += usize::from(!converged);
        all.push(dt, pre);
        phases[*phase].push(dt, pre);
        // The device's local model: the wrench stiffness every 10 ticks, as the live session.
        if k % 10 == 0 && d > 0 {
            let (r, dk, pk) = timed(|| sim.wrench_stiffness().map(|_| ()));
            r.unwrap_or_else(|e| panic!("{label}, tick {k}: {e}"));
            stiffness.push(dk, pk);
            with_stiffness.push(dt + dk, pre || pk);
        }
        sim.prefetch_columns(usize::MAX).unwrap();
    }
    println!("{label} needle, 21³ cube ({n_nodes} nodes, {n_tets} tets), load average before {load_before}, after {}", load_avg());
    println!("  every step: {}", all.summary());
    let mut rows = vec![format!("| {label} | all | {} |", all.row())];
    for (name, t) in PHASES.iter().zip(&mut phases) {
        println!("  {name}: {}", t.summary());
        rows.push(format!("| {label} | {name} | {} |", t.row()));
    }
    println!("  wrench stiffness (every 10 ticks): {}", stiffness.summary());
    println!("  step + stiffness on those ticks: {}", with_stiffness.summary());
    rows.push(format!("| {label} | wrench stiffness | {} |", stiffness.row()));
    rows.push(format!("| {label} | step + stiffness | {} |", with_stiffness.row()));
    println!(
        "  up to {max_d} points; unconverged ticks {capped}; shape passes beyond the first, unconverged shapes: {:?}; {:?}",
        sim.shape_stats(),
        sim.stats()
    );
    assert_eq!(sim.cache().n_computed(), 0, "no column computed in a step");
    rows
}

#[test]
#[ignore = "timing"]
fn flexible_and_bevel_step_time_on_the_cube() {
    let len = box_phantom3_params(ENTRY, 0.005).needle_length_m;
    let flexible = FlexibleNeedle::gauge17_steel(len);
    let mut bevel = flexible;
    bevel.flexural_rigidity_nm2 *= 0.05;
    bevel.bevel_force_ratio = 0.5;
    let mut rows = Vec::new();
    rows.extend(bench("rigid", None));
    rows.extend(bench("flexible", Some(NeedleShape3::Flexible(flexible))));
    rows.extend(bench("bevel", Some(NeedleShape3::Flexible(bevel))));
    println!("\n| needle | phase | steps | p50 µs | p99 | p99.9 | max | preempted | not preempted: p50 µs | p99 | p99.9 | max |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        println!("{r}");
    }
}
