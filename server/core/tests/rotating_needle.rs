//! The rotating-needle benchmark (issue 19): a needle turning while it is inserted, on the
//! 200 × 200 2D phantom and on the 3D cube; step-time quantiles (p50, p99, p99.9, max) with and
//! without the steps during which another process had the core. Timing only, so `#[ignore]`:
//!
//! ```sh
//! cargo test --release -p needlesim-core --test rotating_needle -- --ignored --nocapture
//! ```
//!
//! - **2D** (`rotating_2d`): the rigid 0.1 m needle enters the top centre vertically; after
//!   30 mm it goes on 30 mm more at 10 mm/s while its base turns about the entry point as
//!   $\theta = 10° \sin(2\pi t / 1\,\mathrm{s})$ (peak 0.63 rad/s: every contact's frame turns
//!   every tick and the stick/slip front runs up and down the shaft), then 1 s more of turning at
//!   full depth, then it is withdrawn. A 2D needle has no axis to roll about: rotating it is
//!   turning it in the plane, which is what costs (a frame rotation per contact, pivots per
//!   slipping contact, the stiffness Jacobian's rotation column). The stiffness Jacobian is
//!   computed every 10 ticks, as the real-time loop does, and timed apart and together with its
//!   tick's step.
//! - **3D** (`rotating_3d`): the rigid 0.12 m needle enters the 21³ cube off-node at 20 mm/s;
//!   after 40 mm it rolls about its own axis at one turn per second while going on 20 mm at
//!   10 mm/s, then rolls 1 s more at full depth, then is withdrawn.
//!
//! Columns are prefetched between steps (not timed); no step computes one.

use std::time::Instant;

use needlesim_core::BasePose;
use needlesim_core::fixtures::{box_phantom3, box_phantom3_params, phantom_bench};
use needlesim_core::sim::{ContactModel, SimParams, Simulation};
use needlesim_core::sim3::{BasePose3, Simulation3};

mod timing;
use timing::{Times, load_avg, timed};

const DOWN: f64 = -std::f64::consts::FRAC_PI_2;

#[test]
#[ignore = "timing"]
fn rotating_2d() {
    let n: usize = std::env::var("NEEDLESIM_GRID").ok().map_or(200, |v| v.parse().expect("NEEDLESIM_GRID: nodes per edge"));
    let t0 = Instant::now();
    let (model, bench) = phantom_bench(n);
    let setup_s = t0.elapsed().as_secs_f64();
    let entry = [bench.initial_pose.x_m, 0.1];
    let len = 0.1;
    let pose =
        |depth_m: f64, theta: f64| BasePose::new(entry[0] + (depth_m - len) * theta.cos(), entry[1] + (depth_m - len) * theta.sin(), theta);
    let params = SimParams {
        initial_pose: pose(-0.005, DOWN),
        contact: ContactModel::default_points(),
        columns_in_step: false,
        max_needle_nodes: 128,
        ..bench
    };
    let mut sim = Simulation::new(model, params).unwrap();
    let amp = 10f64.to_radians();
    let mut script: Vec<(&str, BasePose)> = Vec::new();
    for k in 1..=3500 {
        script.push(("insert", pose(-0.005 + 1e-5 * k as f64, DOWN)));
    }
    for k in 1..=4000 {
        let t = k as f64 * 1e-3;
        let depth = 0.03 + 1e-5 * k.min(3000) as f64;
        script.push(("rotate", pose(depth, DOWN + amp * (std::f64::consts::TAU * t).sin())));
    }
    for k in 1..=6500 {
        script.push(("withdraw", pose(0.06 - 1e-5 * k as f64, DOWN)));
    }
    let (mut step, mut jac, mut with_jac, mut rotating) = (Times::default(), Times::default(), Times::default(), Times::default());
    let (mut prefetched, mut max_d) = (0, 0);
    let load_before = load_avg();
    for (k, (phase, p)) in script.iter().enumerate() {
        let (r, dt, pre) = timed(|| sim.step(*p).map(|o| o.needle_nodes.len()));
        max_d = max_d.max(r.unwrap_or_else(|e| panic!("tick {k}: {e}")));
        step.push(dt, pre);
        if *phase == "rotate" {
            rotating.push(dt, pre);
        }
        if k % 10 == 0 {
            let (j, dj, pj) = timed(|| sim.stiffness_jacobian());
            j.unwrap();
            jac.push(dj, pj);
            with_jac.push(dt + dj, pre || pj);
        }
        prefetched += sim.prefetch_columns(8).unwrap();
    }
    let s = sim.stats();
    let u = sim.solver().stats();
    println!("2D rotating needle, {n} × {n} phantom (setup {setup_s:.2} s), load average before {load_before}, after {}", load_avg());
    println!("  every step: {}", step.summary());
    println!("  steps while rotating: {}", rotating.summary());
    println!("  stiffness Jacobian (every 10 ticks): {}", jac.summary());
    println!("  step + Jacobian on those ticks: {}", with_jac.summary());
    println!(
        "  up to {max_d} contacts; {prefetched} nodes prefetched; column misses {}, deferrals {}, unconverged {}, capped {}; pivots {}, rotations {}, stick→slip {}, slip→stick {}",
        s.column_misses,
        s.column_deferrals,
        s.unconverged_ticks,
        s.active_set_capped_ticks,
        u.n_pivots,
        u.n_rotations,
        s.stick_to_slip,
        s.slip_to_stick
    );
    assert_eq!(s.column_misses, 0);
}

#[test]
#[ignore = "timing"]
fn rotating_3d() {
    let n: usize = std::env::var("NEEDLESIM_GRID").ok().map_or(21, |v| v.parse().expect("NEEDLESIM_GRID: nodes per edge"));
    let entry = [0.0513, 0.0487, 0.1];
    let t0 = Instant::now();
    let model = box_phantom3(n);
    let setup_s = t0.elapsed().as_secs_f64();
    let params = box_phantom3_params(entry, 0.005);
    let (n_nodes, n_tets) = (model.mesh().n_nodes(), model.mesh().n_tets());
    let mut sim = Simulation3::new(model, params).unwrap();
    let start = sim.pose();
    let t_axis = start.axis();
    let down = |p: BasePose3, d: f64| {
        BasePose3::from_rotation(
            [p.position_m[0] + d * t_axis[0], p.position_m[1] + d * t_axis[1], p.position_m[2] + d * t_axis[2]],
            p.orientation,
        )
    };
    let mut script: Vec<(&str, BasePose3)> = Vec::new();
    for k in 1..=2250 {
        script.push(("insert", down(start, 2e-5 * k as f64)));
    }
    let at = script.last().unwrap().1;
    for k in 1..=3000 {
        let moved = down(at, 1e-5 * k.min(2000) as f64);
        // One turn a second about the needle's own axis (through its base).
        let rolled = moved.rotated_about_axis(moved.position_m, t_axis, std::f64::consts::TAU * k as f64 * 1e-3);
        script.push(("roll", rolled));
    }
    let at = script.last().unwrap().1;
    for k in 1..=3500 {
        script.push(("withdraw", down(at, -2e-5 * k as f64)));
    }
    for _ in 0..64 {
        sim.step(sim.pose()).unwrap();
        sim.prefetch_columns(usize::MAX).unwrap();
    }
    let (mut step, mut rolling) = (Times::default(), Times::default());
    let mut max_d = 0;
    let load_before = load_avg();
    for (k, (phase, p)) in script.iter().enumerate() {
        let (r, dt, pre) = timed(|| sim.step(*p).map(|o| o.contacts.len()));
        max_d = max_d.max(r.unwrap_or_else(|e| panic!("tick {k}: {e}")));
        step.push(dt, pre);
        if *phase == "roll" {
            rolling.push(dt, pre);
        }
        sim.prefetch_columns(usize::MAX).unwrap();
    }
    let s = sim.stats();
    let u = sim.solver().stats();
    println!(
        "3D rolling needle, {n}³ cube ({n_nodes} nodes, {n_tets} tets; setup {setup_s:.2} s), load average before {load_before}, after {}",
        load_avg()
    );
    println!("  every step: {}", step.summary());
    println!("  steps while rolling: {}", rolling.summary());
    println!("  up to {max_d} contacts; {s:?}; pivots {}, rotations {}", u.n_pivots, u.n_rotations);
    assert_eq!(sim.cache().n_computed(), 0, "no column computed in a step");
}
