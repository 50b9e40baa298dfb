//! Micro-benchmark of the mixed solver's O(d²) operations in 3D at d = 3·40 = 120 (and, for
//! comparison, in 2D at d = 2·60 = 120): a pivot (a condition switch), a frame change of a slot
//! whose DOFs share a kind (O(d)) and of a slot with mixed kinds (the rank-two pass), bordering a
//! new contact, removing one, and the solve. Prints a markdown table of µs per operation.
//!
//! Run with `cargo bench -p needlesim-core --bench mixed3`. The compliance is the mesh-free
//! random SPD fixture ([`fixtures::random_spd_compliance`]); contacts are nodes and
//! tetrahedra's material points in 3D, drawn with a fixed seed. Each operation is timed alone
//! with `Instant` (the set-up between calls is not timed); median and p99 of the samples.

use std::hint::black_box;
use std::time::{Duration, Instant};

use needlesim_core::mixed::{Block, frame_of_angle};
use needlesim_core::{Axis, ComplianceCache, Condition, ContactPoint, MixedSolver, NodeIdx, Slot, fixtures};

const REPS: usize = 4000;

/// A rotation (rows t, n, b) from three angles: about z by `a`, then x by `b`, then z by `c`.
fn euler(a: f64, b: f64, c: f64) -> Block<3> {
    let rz = |t: f64| {
        let (s, co) = t.sin_cos();
        [[co, s, 0.0], [-s, co, 0.0], [0.0, 0.0, 1.0]]
    };
    let rx = |t: f64| {
        let (s, co) = t.sin_cos();
        [[1.0, 0.0, 0.0], [0.0, co, s], [0.0, -s, co]]
    };
    let mul = |p: Block<3>, q: Block<3>| -> Block<3> {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| p[i][k] * q[k][j]).sum()))
    };
    mul(rz(c), mul(rx(b), rz(a)))
}

/// A small deterministic generator (SplitMix64) in [0, 1).
struct Gen(u64);
impl Gen {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() * n as f64) as usize % n
    }
}

fn stats(mut v: Vec<Duration>) -> (f64, f64) {
    v.sort();
    let us = |d: Duration| d.as_secs_f64() * 1e6;
    (us(v[v.len() / 2]), us(v[(v.len() * 99 / 100).min(v.len() - 1)]))
}

fn time(mut f: impl FnMut() -> Duration) -> (f64, f64) {
    for _ in 0..200 {
        black_box(f());
    }
    stats((0..REPS).map(|_| f()).collect())
}

/// 3D: 40 slipping-like contacts (n, b displacement; t force on two thirds, displacement on the
/// rest), half nodes and half material points.
fn working_set_3d(cache: &ComplianceCache<3>, g: &mut Gen) -> MixedSolver<3> {
    let mut s = MixedSolver::<3>::with_capacity(41);
    let mut k = 0;
    while s.n_nodes() < 40 {
        let contact = if k % 2 == 0 {
            ContactPoint::node(NodeIdx(k / 2))
        } else {
            // Distinct points: tetrahedra of consecutive nodes past the node contacts.
            let b = 20 + k / 2;
            let w = 0.1 + 0.3 * g.next();
            ContactPoint::in_tetrahedron(k, [b, b + 1, b + 2, b + 3], [w, 0.5 - w, 0.2, 0.3])
        };
        k += 1;
        let Ok(slot) = s.add_contact_in_frame(cache, contact, euler(g.next() * 6.0, g.next() * 3.0, g.next() * 6.0)) else { continue };
        s.set_condition(slot, Axis::Lateral, Condition::Displacement, 1e-4).unwrap();
        s.set_condition(slot, Axis::Binormal, Condition::Displacement, -1e-4).unwrap();
        if slot.index() % 3 == 0 {
            s.set_condition(slot, Axis::Axial, Condition::Displacement, 1e-4).unwrap();
        }
    }
    s
}

fn main() {
    let mut rows: Vec<(String, (f64, f64))> = Vec::new();
    // ---- 3D, d = 120 ----
    let n3 = 60;
    let (_, cache3) = fixtures::random_spd_compliance::<3>(n3, 11);
    let mut g = Gen(5);
    let mut s = working_set_3d(&cache3, &mut g);
    assert_eq!(s.n_dofs(), 120);
    rows.push((
        "3D pivot (condition switch of t)".into(),
        time(|| {
            let slot = Slot::new(1 + 3 * g.below(13));
            let to = if s.condition(slot, Axis::Axial) == Condition::Force { Condition::Displacement } else { Condition::Force };
            let t0 = Instant::now();
            s.set_condition(slot, Axis::Axial, to, 0.0).unwrap();
            t0.elapsed()
        }),
    ));
    let mut s = working_set_3d(&cache3, &mut g);
    rows.push((
        "3D frame change, slot of one kind (t, n, b displacement)".into(),
        time(|| {
            let slot = Slot::new(3 * g.below(13));
            let f = euler(g.next() * 6.0, g.next() * 3.0, g.next() * 6.0);
            let t0 = Instant::now();
            s.set_frame(slot, f).unwrap();
            t0.elapsed()
        }),
    ));
    rows.push((
        "3D frame change, slot of mixed kinds (n, b displacement, t force)".into(),
        time(|| {
            let slot = Slot::new(1 + 3 * g.below(13));
            let f0 = s.frame(slot);
            let q = euler(0.02 * (g.next() - 0.5), 0.02 * (g.next() - 0.5), 0.02 * (g.next() - 0.5));
            let f: Block<3> = std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| f0[i][k] * q[j][k]).sum()));
            let t0 = Instant::now();
            s.set_frame(slot, f).unwrap();
            t0.elapsed()
        }),
    ));
    let base = working_set_3d(&cache3, &mut g);
    let mut s = base.clone();
    rows.push((
        "3D border a tetrahedron's point (39 → 40 contacts)".into(),
        time(|| {
            s.copy_from(&base);
            s.remove_slot(Slot::new(39)).unwrap();
            let b = g.below(n3 - 4);
            let contact = ContactPoint::in_tetrahedron(999, [b, b + 1, b + 2, b + 3], [0.1, 0.2, 0.3, 0.4]);
            let f = euler(1.0, 0.5, 0.2);
            let t0 = Instant::now();
            black_box(s.add_contact_in_frame(&cache3, contact, f).unwrap());
            t0.elapsed()
        }),
    ));
    rows.push((
        "3D remove a slot with 2 prescribed displacements (40 → 39)".into(),
        time(|| {
            s.copy_from(&base);
            let slot = Slot::new(1 + 3 * g.below(13));
            let t0 = Instant::now();
            s.remove_slot(slot).unwrap();
            t0.elapsed()
        }),
    ));
    s.copy_from(&base);
    rows.push((
        "3D solve y = H x".into(),
        time(|| {
            let t0 = Instant::now();
            s.solve();
            t0.elapsed()
        }),
    ));
    // ---- 2D, d = 120, for comparison ----
    let n2 = 90;
    let (_, cache2) = fixtures::random_spd_compliance::<2>(n2, 12);
    let mut s2 = MixedSolver::<2>::with_capacity(61);
    for k in 0..60 {
        let slot = s2.add_node(&cache2, NodeIdx(k), g.next() * 6.0).unwrap();
        s2.set_condition(slot, Axis::Lateral, Condition::Displacement, 1e-4).unwrap();
        if k % 3 == 0 {
            s2.set_condition(slot, Axis::Axial, Condition::Displacement, 1e-4).unwrap();
        }
    }
    let base2 = s2.clone();
    rows.push((
        "2D pivot (condition switch of t)".into(),
        time(|| {
            let slot = Slot::new(1 + 3 * g.below(19));
            let to = if s2.condition(slot, Axis::Axial) == Condition::Force { Condition::Displacement } else { Condition::Force };
            let t0 = Instant::now();
            s2.set_condition(slot, Axis::Axial, to, 0.0).unwrap();
            t0.elapsed()
        }),
    ));
    s2.copy_from(&base2);
    rows.push((
        "2D set_angle, slot of mixed kinds (closed form)".into(),
        time(|| {
            let slot = Slot::new(1 + 3 * g.below(19));
            let a = s2.angle_rad(slot) + 0.02 * (g.next() - 0.5);
            let t0 = Instant::now();
            s2.set_angle(slot, a).unwrap();
            t0.elapsed()
        }),
    ));
    rows.push((
        "2D set_frame, slot of mixed kinds (general form)".into(),
        time(|| {
            let slot = Slot::new(1 + 3 * g.below(19));
            let f = frame_of_angle(s2.angle_rad(slot) + 0.02 * (g.next() - 0.5));
            let t0 = Instant::now();
            s2.set_frame(slot, f).unwrap();
            t0.elapsed()
        }),
    ));
    let mut s2b = base2.clone();
    rows.push((
        "2D border a node (59 → 60 contacts)".into(),
        time(|| {
            s2b.copy_from(&base2);
            s2b.remove_slot(Slot::new(59)).unwrap();
            let t0 = Instant::now();
            black_box(s2b.add_node(&cache2, NodeIdx(59), 0.3).unwrap());
            t0.elapsed()
        }),
    ));
    println!("| operation (d = 120) | median µs | p99 µs |\n|---|---:|---:|");
    for (what, (p50, p99)) in rows {
        println!("| {what} | {p50:.2} | {p99:.2} |");
    }
}
