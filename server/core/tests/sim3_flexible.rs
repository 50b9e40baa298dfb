//! The flexible and bevel-tip needle in 3D (issue 18) on the cube phantom: a stiff flexible
//! needle gives the rigid needle over an insertion with a tilted base and a roll; no allocation
//! in a warm step; a bevel needle follows an arc in its bevel's plane, bends back when rolled
//! 180°, into the new plane when rolled 90°; duty-cycled spinning lowers the curvature.

use nalgebra::UnitQuaternion;
use needlesim_alloc_count::{CountingAlloc, count_on_this_thread, thread_allocations};
use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
use needlesim_core::needle::FlexibleNeedle;
use needlesim_core::sim3::{BasePose3, NeedleShape3, Sim3Params, Simulation3, StepOutput3, unit_axis};

#[global_allocator]
static GLOBAL: CountingAlloc = CountingAlloc::new();

/// Off-node entry point on the top face (z = 0.1 m).
const ENTRY: [f64; 3] = [0.0513, 0.0487, 0.1];
/// Insertion speed, m per 1 ms tick (20 mm/s).
const V: f64 = 2e-5;

fn flexible(len: f64, ei_scale: f64, bevel: f64) -> NeedleShape3 {
    let mut f = FlexibleNeedle::gauge17_steel(len);
    f.flexural_rigidity_nm2 *= ei_scale;
    f.n_links = 40;
    f.bevel_force_ratio = bevel;
    NeedleShape3::Flexible(f)
}

fn along(p: BasePose3, d: f64) -> BasePose3 {
    let t = p.axis();
    BasePose3::from_rotation([p.position_m[0] + d * t[0], p.position_m[1] + d * t[1], p.position_m[2] + d * t[2]], p.orientation)
}

/// A tilted insertion (the base turned 8° about an oblique horizontal axis through the entry
/// point) of 40 mm, a 90° roll about the needle axis, 10 mm more, a 4° turn about world y
/// through the entry point, a withdrawal of 30 mm.
fn tilted_roll_poses(start: BasePose3) -> Vec<BasePose3> {
    let tilt = UnitQuaternion::from_axis_angle(&unit_axis([0.6, 0.8, 0.0]), 8f64.to_radians());
    let s = start.rotated_about(ENTRY, &tilt);
    let mut v: Vec<BasePose3> = (1..=2250).map(|k| along(s, V * k as f64)).collect();
    let at = *v.last().unwrap();
    for k in 1..=300 {
        v.push(at.rotated_about_axis(at.position_m, at.axis(), 0.5 * std::f64::consts::PI * k as f64 / 300.0));
    }
    let at = *v.last().unwrap();
    v.extend((1..=500).map(|k| along(at, V * k as f64)));
    let at = *v.last().unwrap();
    for k in 1..=300 {
        let r = UnitQuaternion::from_axis_angle(&unit_axis([0.0, 1.0, 0.0]), 4f64.to_radians() * k as f64 / 300.0);
        v.push(at.rotated_about(ENTRY, &r));
    }
    let at = *v.last().unwrap();
    v.extend((1..=1500).map(|k| along(at, -V * k as f64)));
    v
}

fn run(params: Sim3Params, poses: &[BasePose3], n: usize, mut each: impl FnMut(usize, &StepOutput3, u64)) -> Simulation3 {
    let mut sim = Simulation3::new(box_phantom3(n), params).unwrap();
    for (k, p) in poses.iter().enumerate() {
        let before = thread_allocations();
        count_on_this_thread(true);
        let r = sim.step(*p).map(|_| ());
        count_on_this_thread(false);
        let allocations = thread_allocations() - before;
        r.unwrap();
        each(k, sim.output(), allocations);
        sim.prefetch_columns(usize::MAX).unwrap();
    }
    sim
}

/// The largest differences (force relative to the rigid run's largest force, position relative
/// to the 0.1 m cube) of a flexible needle `ei_scale` times stiffer than 17-gauge steel from the
/// rigid needle over [`tilted_roll_poses`], tick by tick (wrench, tip, each point), asserting
/// the same contact events; and the warm steps that allocated.
fn stiff_against_rigid(ei_scale: f64) -> (f64, f64, usize) {
    let rigid_params = box_phantom3_params(ENTRY, 0.005);
    let poses = tilted_roll_poses(rigid_params.initial_pose);
    let mut rigid = Vec::new();
    run(rigid_params.clone(), &poses, 13, |_, o, _| rigid.push(o.clone()));
    let flex_params = Sim3Params { needle: flexible(rigid_params.needle_length_m, ei_scale, 0.0), ..rigid_params };
    let mut flex = Vec::new();
    let mut allocating = 0;
    let sim = run(flex_params, &poses, 13, |k, o, a| {
        flex.push(o.clone());
        if k >= 100 && a > 0 {
            allocating += 1;
        }
    });
    let f_scale = rigid.iter().flat_map(|o| o.base_force_n).fold(0.0f64, |m, v| m.max(v.abs()));
    let (mut worst_f, mut worst_x): (f64, f64) = (0.0, 0.0);
    for (k, (a, b)) in flex.iter().zip(&rigid).enumerate() {
        assert_eq!(a.contacts.len(), b.contacts.len(), "tick {k}");
        for c in 0..3 {
            worst_f = worst_f.max((a.base_force_n[c] - b.base_force_n[c]).abs() / f_scale);
            worst_f = worst_f.max((a.base_torque_nm[c] - b.base_torque_nm[c]).abs() / (0.1 * f_scale));
            worst_x = worst_x.max((a.tip_m[c] - b.tip_m[c]).abs() / 0.1);
        }
        for (ca, cb) in a.contacts.iter().zip(&b.contacts) {
            assert_eq!(ca.state, cb.state, "tick {k}");
            for c in 0..3 {
                worst_f = worst_f.max((ca.force_n[c] - cb.force_n[c]).abs() / f_scale);
                worst_x = worst_x.max((ca.x_m[c] - cb.x_m[c]).abs() / 0.1);
            }
        }
    }
    let max_points = rigid.iter().map(|o| o.contacts.len()).max().unwrap();
    println!(
        "EI x {ei_scale:e}: {} ticks, up to {max_points} points, largest force {f_scale:.4} N: worst relative force difference {worst_f:e}, position {worst_x:e}; shape passes, unconverged {:?}",
        rigid.len(),
        sim.shape_stats()
    );
    assert!(max_points >= 4, "the insertion held {max_points} points");
    (worst_f, worst_x, allocating)
}

/// A stiff flexible needle is the rigid needle: the difference is the rod's own compliance
/// (a 17-gauge needle 10⁶ times stiffer still bends: 0.12 m, $L^3/3EI \approx 2\times10^{-8}$ m/N,
/// against tissue points of several hundred N/m: measured 2e-5 of the largest force at
/// EI × 10⁶), so it falls as $1/EI$ — a hundred times from EI × 10⁶ to EI × 10⁸ (within 10 %) —
/// and at EI × 10⁸ it is below 1e-6 over an insertion with a tilted base, a 90° roll and a turn.
/// A warm step of the flexible needle allocates nothing.
#[test]
fn a_stiff_flexible_needle_is_the_rigid_needle() {
    let (f6, x6, alloc6) = stiff_against_rigid(1e6);
    let (f8, x8, alloc8) = stiff_against_rigid(1e8);
    println!("force ratio {:.4}, position ratio {:.4}", f6 / f8, x6 / x8);
    assert!(f8 < 1e-6 && x8 < 1e-6, "EI x 1e8: force {f8:e}, position {x8:e}");
    assert!((f6 / f8 / 100.0 - 1.0).abs() < 0.1, "the difference does not scale as 1/EI: {f6:e} at 1e6, {f8:e} at 1e8");
    assert!((x6 / x8 / 100.0 - 1.0).abs() < 0.1, "the difference does not scale as 1/EI: {x6:e} at 1e6, {x8:e} at 1e8");
    assert_eq!(alloc6 + alloc8, 0, "warm flexible steps allocated");
}
