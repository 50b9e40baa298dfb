//! A step allocates nothing once warmed up: a counting global allocator watches every
//! allocation made inside `Simulation::step` during an insertion, a hold, a rotation and a
//! withdrawal (compliance columns are prefetched between steps, as the server's worker does), for
//! the rigid needle and for a flexible bevel-tip needle whose bevel is flipped half-way, with the
//! device's stiffness Jacobian taken every 10 ticks as the real-time thread does.

use std::alloc::{GlobalAlloc, Layout, System};

use needlesim_core::sim::{SimParams, Simulation};
use needlesim_core::{BasePose, NeedleShape, RegionNeedleParams, RigidNeedle, fixtures};

struct Counting;

// Per thread: the tests run in parallel, and only the counting thread's allocations count.
thread_local! {
    static COUNTING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    static ALLOCS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(|c| c.get()) {
            ALLOCS.with(|a| a.set(a.get() + 1));
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.with(|c| c.get()) {
            ALLOCS.with(|a| a.set(a.get() + 1));
        }
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn steps_allocate_nothing_after_warm_up() {
    run_case(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }));
}

#[test]
fn flexible_bevel_needle_steps_allocate_nothing_after_warm_up() {
    let mut f = needlesim_core::FlexibleNeedle::gauge17_steel(0.1);
    f.flexural_rigidity_nm2 *= 0.3;
    f.bevel_force_ratio = 0.2;
    run_case(NeedleShape::Flexible(f));
}

fn run_case(needle: NeedleShape) {
    let model = fixtures::phantom(25);
    let a0 = -1.3f64;
    let base_at = |d: f64, a: f64| BasePose::new(0.04 + (d - 0.1) * a.cos(), 0.1 + (d - 0.1) * a.sin(), a);
    let params = SimParams {
        initial_pose: base_at(-0.005, a0),
        targets: vec![needlesim_core::TargetParams { name: "t".into(), center_m: [0.05, 0.04], radius_m: 0.002 }],
        ..fixtures::phantom_params(needle)
    };
    let mut sim = Simulation::new(model, params).unwrap();
    let mut poses: Vec<BasePose> = (0..=4000).map(|k| base_at(-0.005 + 0.045 * k as f64 / 4000.0, a0)).collect();
    poses.extend(std::iter::repeat_n(base_at(0.04, a0), 300));
    poses.extend((0..=500).map(|k| base_at(0.04, a0 + 0.08 * k as f64 / 500.0)));
    poses.extend((0..=4500).map(|k| base_at(0.04 - 0.045 * k as f64 / 4500.0, a0 + 0.08)));
    let mut steps_with_allocation = 0;
    let mut total = 0;
    for (k, p) in poses.iter().enumerate() {
        ALLOCS.with(|a| a.set(0));
        COUNTING.with(|c| c.set(true));
        if k == poses.len() / 2 {
            sim.flip_bevel();
        }
        let r = sim.step(*p).map(|o| o.needle_nodes.len());
        let j = if k % 10 == 0 { Some(sim.stiffness_jacobian()) } else { None };
        COUNTING.with(|c| c.set(false));
        r.unwrap();
        if let Some(j) = j {
            j.unwrap();
        }
        let n = ALLOCS.with(|a| a.get());
        // The first ticks size the per-step buffers; after that nothing may allocate.
        if k >= 10 && n > 0 {
            steps_with_allocation += 1;
            total += n;
        }
        sim.prefetch_columns(16).unwrap();
    }
    let st = sim.stats();
    assert!(st.captures > 8 && st.releases > 8 && st.punctures > 3, "the run exercised the model: {st:?}");
    assert!(sim.solver().stats().n_rotations > 100);
    assert_eq!(st.column_misses, 0);
    assert_eq!(steps_with_allocation, 0, "{total} allocations inside steps after warm-up");
}

/// Issue 13: the divergence checks run in every step without allocating; a flexible 22-gauge
/// needle with 1e4 N/m friction (Fig. 4's steering path) diverges, and that step — and every
/// one after it, which fails the same way — allocates nothing and leaves the last good output.
#[test]
fn issue_13_a_diverging_step_is_caught_without_allocating() {
    use needlesim_core::sim::{Divergence, SimError};
    let model = fixtures::phantom(19);
    let mut f = needlesim_core::FlexibleNeedle::gauge17_steel(0.1);
    f.flexural_rigidity_nm2 = 193e9 * needlesim_core::FlexibleNeedle::tube_second_moment_m4(0.718e-3, 0.413e-3);
    let down = -std::f64::consts::FRAC_PI_2;
    let params = SimParams {
        // Half the mean edge length (diagonals included), as the scene loader sets it.
        capture_radius_m: 0.5 * (2.0 + std::f64::consts::SQRT_2) / 3.0 * 0.1 / 18.0,
        max_needle_nodes: 128,
        regions: vec![RegionNeedleParams { friction_n_per_m: 1e4, ..Default::default() }],
        ..fixtures::phantom_params(NeedleShape::Flexible(f))
    };
    let mut sim = Simulation::new(model, params).unwrap();
    // Fig. 4's path, four times faster: down 40 mm, 5 mm sideways, down 50 mm.
    let mut poses: Vec<BasePose> = (0..=1000).map(|k| BasePose::new(0.05, 0.205 - 0.04 * k as f64 / 1000.0, down)).collect();
    poses.extend((0..=12).map(|k| BasePose::new(0.05 + 0.005 * k as f64 / 12.0, 0.165, down)));
    poses.extend((0..=1250).map(|k| BasePose::new(0.055, 0.165 - 0.05 * k as f64 / 1250.0, down)));
    // Then out and in again, twice.
    for _ in 0..2 {
        poses.extend((0..=1000).map(|k| BasePose::new(0.055, 0.115 + 0.06 * k as f64 / 1000.0, down)));
        poses.extend((0..=1000).map(|k| BasePose::new(0.055, 0.175 - 0.06 * k as f64 / 1000.0, down)));
    }
    let mut diverged = None;
    for (k, p) in poses.iter().enumerate() {
        let last_good = (sim.output().tick, sim.output().force_n);
        let misses = sim.stats().column_misses;
        ALLOCS.with(|a| a.set(0));
        COUNTING.with(|c| c.set(true));
        let r = sim.step(*p).map(|o| o.force_n);
        COUNTING.with(|c| c.set(false));
        let n = ALLOCS.with(|a| a.get());
        match r {
            Ok(force_n) => {
                assert!(force_n[0].hypot(force_n[1]) <= sim.divergence_bounds().force_n);
                // A column the prefetch did not deliver is the one allowed allocation.
                assert!(k < 10 || n == 0 || sim.stats().column_misses > misses, "tick {k}: {n} allocations in a step");
            }
            Err(e @ SimError::Diverged { .. }) => {
                assert_eq!(n, 0, "the diverged step allocated {n} times");
                assert_eq!((sim.output().tick, sim.output().force_n), last_good, "the diverged state was written out");
                diverged = Some(e);
                break;
            }
            Err(e) => panic!("tick {k}: {e}"),
        }
        sim.prefetch_columns(16).unwrap();
    }
    let Some(SimError::Diverged { tick, what, value, bound }) = diverged.clone() else { panic!("the run never diverged") };
    assert!(value.is_nan() || value > bound, "{what:?} = {value} within {bound}");
    assert!(matches!(what, Divergence::InsertedLength | Divergence::NodeForce | Divergence::Force | Divergence::Displacement), "{what:?}");
    assert!(tick > 1000, "diverged at tick {tick}");
    // Faulted for good: every later step returns the same error, allocating nothing.
    for _ in 0..3 {
        COUNTING.with(|c| c.set(true));
        let again = sim.step(BasePose::new(0.05, 0.2, down)).map(|_| ()).unwrap_err();
        COUNTING.with(|c| c.set(false));
        assert_eq!(again.to_string(), diverged.as_ref().unwrap().to_string()); // NaN ≠ NaN: compare the text
    }
    assert_eq!(ALLOCS.with(|a| a.get()), 0);
}
