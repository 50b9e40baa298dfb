//! `TetTissueModel::displacement_for_point_loads_into` allocates nothing once its scratch and
//! output exist: a counting global allocator watches every allocator call made inside the solves
//! (the 3D ultrasound slice's renderer makes one per image).

use needlesim_alloc_count::{CountingAlloc, count_on_this_thread, thread_allocations};
use needlesim_core::d3::PointLocation;
use needlesim_core::fixtures::box_phantom3;

#[global_allocator]
static GLOBAL: CountingAlloc = CountingAlloc::new();

#[test]
fn point_load_solves_allocate_nothing() {
    let model = box_phantom3(9);
    // A needle's worth of points down the middle, dragged down and sideways.
    let points: Vec<PointLocation> = (0..12).map(|k| model.locate([0.0513, 0.0487, 0.099 - 0.005 * k as f64]).unwrap()).collect();
    let mut forces: Vec<[f64; 3]> = (0..12).map(|k| [0.01, -0.004, -0.02 * (1.0 + k as f64)]).collect();
    let mut scratch = model.column_scratch();
    let mut u = vec![0.0; model.n_dofs()];
    count_on_this_thread(true);
    let before = thread_allocations();
    for step in 0..20 {
        forces[step % 12][0] += 1e-3;
        model.displacement_for_point_loads_into(&points, &forces, &mut u, &mut scratch).unwrap();
    }
    // The error paths too (a mismatch, a non-finite force).
    assert!(model.displacement_for_point_loads_into(&points[..3], &forces, &mut u, &mut scratch).is_err());
    forces[4][1] = f64::NAN;
    assert!(model.displacement_for_point_loads_into(&points, &forces, &mut u, &mut scratch).is_err());
    let calls = thread_allocations() - before;
    count_on_this_thread(false);
    assert!(u.iter().any(|&v| v != 0.0), "the loads moved the tissue");
    assert_eq!(calls, 0, "allocator calls inside the solves");
}
