//! The unit tests of the mixed solver.

use super::blocks::mul_t;
use super::*;
use crate::compliance::ComplianceCache;
use crate::ids::{Axis, NodeIdx, Slot};
use crate::statics::{NodeCondition, StaticProblem};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

use crate::fixtures::strain_square as model;

fn max_rel_diff<const D: usize>(s: &MixedSolver<D>, cache: &ComplianceCache<D>) -> f64 {
    let h = s.hybrid_from_scratch(cache).unwrap();
    y_rel_diff(s, &h)
}

/// The largest difference of the solver's unknowns $y$ from $H^{ref} x$, relative to the
/// size of the row's terms.
fn y_rel_diff<const D: usize>(s: &MixedSolver<D>, h: &faer::Mat<f64>) -> f64 {
    let d = s.n_dofs();
    // Compare the unknowns y = H x for the current x, relative to their size, and H itself
    // relative to its largest entry in each block row.
    let mut worst: f64 = 0.0;
    let mut y_ref = vec![0.0; d];
    for i in 0..d {
        y_ref[i] = (0..d).map(|j| h[(i, j)] * s.x[j]).sum();
    }
    for i in 0..d {
        let row_scale = (0..d).map(|j| (h[(i, j)] * s.x[j]).abs()).fold(0.0, f64::max).max(1e-300);
        worst = worst.max((s.y[i] - y_ref[i]).abs() / row_scale.max(y_ref[i].abs()));
    }
    let hmax = (0..d).flat_map(|i| (0..d).map(move |j| (i, j))).map(|(i, j)| h[(i, j)].abs()).fold(0.0, f64::max);
    let _ = hmax;
    worst
}

/// Random sequences of condition switches, frame rotations, additions and removals give the
/// same answer as a fresh solve, to 1e-9 relative, on meshes up to 50 × 50 and working sets
/// up to 60 nodes.
#[test]
fn random_updates_equal_fresh_solves() {
    for (seed, nx, max_nodes) in [(1u64, 12, 20), (2, 30, 40), (3, 50, 60)] {
        let m = model(nx);
        let mut rng = SmallRng::seed_from_u64(seed);
        let mut cache = ComplianceCache::new(m.mesh().n_nodes());
        let mut scratch = m.column_scratch();
        let mut s = MixedSolver::with_capacity(max_nodes);
        let candidates: Vec<usize> = (0..m.mesh().n_nodes()).filter(|&n| !m.is_fixed(n)).collect();
        let mut n_checks = 0;
        let mut n_mixed_rotations = 0;
        for step in 0..400 {
            let op = rng.random_range(0..10);
            if s.n_nodes() < 3 || (op < 3 && s.n_nodes() < max_nodes) {
                let node = candidates[rng.random_range(0..candidates.len())];
                if s.slot_of(NodeIdx(node)).is_some() {
                    continue;
                }
                cache.ensure(&m, node, &mut scratch).unwrap();
                s.add_node(&cache, NodeIdx(node), rng.random_range(-3.2..3.2)).unwrap();
            } else if op < 6 {
                let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                let axis = Axis::of_index(rng.random_range(0..2));
                let cond = if rng.random_bool(0.6) { Condition::Displacement } else { Condition::Force };
                let v = if cond == Condition::Displacement { rng.random_range(-1e-3..1e-3) } else { rng.random_range(-0.01..0.01) };
                s.set_condition(slot, axis, cond, v).unwrap();
            } else if op < 7 {
                let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                let a = s.angle_rad(slot) + rng.random_range(-0.5..0.5);
                s.set_angle(slot, a).unwrap();
            } else if op < 8 {
                // A slipping contact turning with the needle: a mixed-kind slot (made one if
                // there is none) rotated many times in a row, by small and large angles.
                let slot = match Slot::all(s.n_nodes()).find(|&k| s.condition(k, Axis::Axial) != s.condition(k, Axis::Lateral)) {
                    Some(k) => k,
                    None => {
                        let k = Slot::new(rng.random_range(0..s.n_nodes()));
                        let (a, b) = if rng.random_bool(0.5) { (Axis::Axial, Axis::Lateral) } else { (Axis::Lateral, Axis::Axial) };
                        s.set_condition(k, a, Condition::Displacement, rng.random_range(-1e-3..1e-3)).unwrap();
                        s.set_condition(k, b, Condition::Force, rng.random_range(-0.01..0.01)).unwrap();
                        k
                    }
                };
                for _ in 0..rng.random_range(5..30) {
                    let a =
                        s.angle_rad(slot) + if rng.random_bool(0.5) { rng.random_range(-1e-3..1e-3) } else { rng.random_range(-2.0..2.0) };
                    s.set_angle(slot, a).unwrap();
                    n_mixed_rotations += 1;
                }
            } else if op < 9 && s.n_nodes() > 3 {
                let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                s.remove_slot(slot).unwrap();
            } else {
                // fresh values on every DOF
                for k in 0..s.n_dofs() {
                    let v =
                        if s.kind[k] == Condition::Displacement { rng.random_range(-1e-3..1e-3) } else { rng.random_range(-0.01..0.01) };
                    s.x[k] = v;
                }
            }
            if step % 10 == 9 {
                s.solve();
                let e = max_rel_diff(&s, &cache);
                assert!(e < 1e-9, "seed {seed} mesh {nx}x{nx} step {step}: {} nodes, rel diff {e:e}", s.n_nodes());
                n_checks += 1;
            }
        }
        assert!(n_checks >= 30);
        assert!(s.stats().n_pivots > 50 && s.stats().n_rotations > 30 && s.stats().n_removed > 5, "{:?}", s.stats());
        assert!(n_mixed_rotations > 300, "{n_mixed_rotations} rotations of mixed-kind slots");
        // Grow to the full working set and check once more.
        while s.n_nodes() < max_nodes {
            let node = candidates[rng.random_range(0..candidates.len())];
            if s.slot_of(NodeIdx(node)).is_none() {
                cache.ensure(&m, node, &mut scratch).unwrap();
                let slot = s.add_node(&cache, NodeIdx(node), rng.random_range(-3.2..3.2)).unwrap();
                s.set_condition(slot, Axis::Lateral, Condition::Displacement, rng.random_range(-1e-3..1e-3)).unwrap();
            }
        }
        s.solve();
        let e = max_rel_diff(&s, &cache);
        assert!(e < 1e-9, "full working set of {max_nodes}: rel diff {e:e}");
    }
}

/// The condensed solve equals a full static solve with the same local-frame conditions.
#[test]
fn condensed_solve_equals_full_static_solve() {
    let m = model(15);
    let mut cache = ComplianceCache::new(m.mesh().n_nodes());
    let mut scratch = m.column_scratch();
    let mut s = MixedSolver::with_capacity(10);
    let angle = -1.2;
    // A needle-like line of nodes: un prescribed, ut stuck on some, slipping with a load on others.
    let nodes = [217usize, 202, 187, 172, 157];
    let mut problem = StaticProblem {
        conditions: m.mesh().boundary_set("bottom").unwrap().iter().map(|&n| (n, NodeCondition::Fixed)).collect(),
        loads_n: vec![],
        points: vec![],
        patches: vec![],
    };
    for (i, &n) in nodes.iter().enumerate() {
        cache.ensure(&m, n, &mut scratch).unwrap();
        let slot = s.add_node(&cache, NodeIdx(n), 0.3).unwrap();
        s.set_angle(slot, angle).unwrap();
        let un = 1e-4 * i as f64;
        s.set_condition(slot, Axis::Lateral, Condition::Displacement, un).unwrap();
        if i % 2 == 0 {
            let ut = -2e-4 * (i + 1) as f64;
            s.set_condition(slot, Axis::Axial, Condition::Displacement, ut).unwrap();
            problem.conditions.push((n, NodeCondition::Local { frame: angle, u_m: [Some(ut), Some(un)] }));
        } else {
            let ft = -3e-3;
            s.set_condition(slot, Axis::Axial, Condition::Force, ft).unwrap();
            problem.conditions.push((n, NodeCondition::Local { frame: angle, u_m: [None, Some(un)] }));
            problem.loads_n.push((n, local_to_world([ft, 0.0], angle)));
        }
    }
    s.solve();
    let full = problem.solve(m.mesh(), m.materials()).unwrap();
    let scale = full.displacement_m.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for (slot, &n) in Slot::all(nodes.len()).zip(&nodes) {
        let u = s.displacement_world(slot);
        for c in 0..2 {
            assert!((u[c] - full.displacement_m[2 * n + c]).abs() < 1e-10 * scale, "node {n}");
        }
    }
    // Whole-mesh displacement from the working forces equals the full solve.
    let mut u_all = vec![0.0; m.n_dofs()];
    cache
        .displacement_from_forces_into(
            Slot::all(s.n_nodes()).map(|k| (s.contacts()[k.index()].nearest_node().0, s.force_world(k))),
            &mut u_all,
        )
        .unwrap();
    for (a, b) in u_all.iter().zip(&full.displacement_m) {
        assert!((a - b).abs() < 1e-10 * scale);
    }
    // Reactions: the force on a stuck node equals minus the static reaction... the static
    // reaction is K u - f at the constrained DOF, i.e. the force the needle applies.
    for (slot, &n) in Slot::all(nodes.len()).zip(&nodes) {
        let r = full.reactions_local_n.iter().find(|r| r.0 == n).unwrap();
        let f = s.force_local(slot);
        if let Some(rn) = r.2[1] {
            assert!((f[Axis::Lateral] - rn).abs() < 1e-8 * rn.abs().max(1e-6), "node {n}: {} vs {rn}", f[Axis::Lateral]);
        }
    }
}

#[test]
fn errors_leave_the_state_valid() {
    let m = model(6);
    let mut cache = ComplianceCache::new(m.mesh().n_nodes());
    let mut scratch = m.column_scratch();
    let mut s = MixedSolver::with_capacity(2);
    let n = NodeIdx;
    assert_eq!(s.add_node(&cache, n(20), 0.0).unwrap_err(), MixedError::NotCached { contact: ContactPoint::node(n(20)).id() });
    for n in [20, 21, 0] {
        cache.ensure(&m, n, &mut scratch).unwrap();
    }
    s.add_node(&cache, n(20), 0.0).unwrap();
    assert_eq!(s.add_node(&cache, n(20), 0.0).unwrap_err(), MixedError::AlreadyWorking { node_idx: n(20) });
    // A fixed node has no compliance: prescribing its displacement is singular.
    let slot = s.add_node(&cache, n(0), 0.0).unwrap();
    let e = s.set_condition(slot, Axis::Axial, Condition::Displacement, 0.0).unwrap_err();
    assert!(
        matches!(e, MixedError::SingularPivot { contact, axis: Axis::Axial, .. } if contact == ContactPoint::node(NodeIdx(0)).id()),
        "{e}"
    );
    assert_eq!(s.condition(slot, Axis::Axial), Condition::Force);
    assert_eq!(s.add_node(&cache, n(21), 0.0).unwrap_err(), MixedError::Full { cap_nodes: 2 });
    let first = Slot::new(0);
    assert!(s.set_condition(first, Axis::Axial, Condition::Displacement, f64::NAN).is_err());
    assert!(s.set_angle(first, f64::INFINITY).is_err());
    assert_eq!(
        s.set_condition(Slot::new(5), Axis::Axial, Condition::Force, 0.0).unwrap_err(),
        MixedError::NoSuchSlot { slot: Slot::new(5), n_nodes: 2 }
    );
}

/// $\max_{ij} |H_{ij} - H^{ref}_{ij}|$ over $\max_{ij} |H^{ref}_{ij}|$ after scaling every DOF
/// by its own compliance $c_k$ (a displacement by $\sqrt{c_k}$, a force by $1/\sqrt{c_k}$),
/// so that the stiffness, compliance and dimensionless blocks of $H$ are compared alike.
fn scaled_hybrid_diff<const D: usize>(s: &MixedSolver<D>, h_ref: &faer::Mat<f64>) -> f64 {
    let d = s.n_dofs();
    let sigma: Vec<f64> = (0..d).map(|k| s.c_local_diag(k).sqrt()).collect();
    let x_scale = |k: usize| if s.kind[k] == Condition::Displacement { sigma[k] } else { 1.0 / sigma[k] };
    let y_scale = |k: usize| if s.kind[k] == Condition::Displacement { 1.0 / sigma[k] } else { sigma[k] };
    let (mut diff, mut size): (f64, f64) = (0.0, 0.0);
    for i in 0..d {
        for j in 0..d {
            let w = x_scale(j) / y_scale(i);
            diff = diff.max((s.hybrid(i, j) - h_ref[(i, j)]).abs() * w);
            size = size.max(h_ref[(i, j)].abs() * w);
        }
    }
    diff / size
}

/// Rotating mixed-kind slots (the direct rank-two update) gives the hybrid matrix of a fresh
/// dense rebuild, entry by entry, and the same matrix as the pivot → rotate → pivot round
/// trip it replaces, after thousands of rotations of every slot of a working set where half
/// the slots are slipping contacts (lateral displacement, axial force) and some are bevel-tip
/// like (axial displacement, lateral force). Tolerance: $10^{-15}\sqrt{n_{updates}}\,d$, scaled.
#[test]
fn mixed_rotations_equal_fresh_hybrid_and_the_pivot_round_trip() {
    for (seed, nx, n_nodes) in [(11u64, 15, 12), (12, 40, 40)] {
        let m = model(nx);
        let mut rng = SmallRng::seed_from_u64(seed);
        let mut cache = ComplianceCache::new(m.mesh().n_nodes());
        let mut scratch = m.column_scratch();
        let mut direct = MixedSolver::with_capacity(n_nodes);
        let candidates: Vec<usize> = (0..m.mesh().n_nodes()).filter(|&n| !m.is_fixed(n)).collect();
        while direct.n_nodes() < n_nodes {
            let node = candidates[rng.random_range(0..candidates.len())];
            if direct.slot_of(NodeIdx(node)).is_some() {
                continue;
            }
            cache.ensure(&m, node, &mut scratch).unwrap();
            let slot = direct.add_node(&cache, NodeIdx(node), rng.random_range(-3.2..3.2)).unwrap();
            let (p, f) = match slot.index() % 4 {
                0 | 1 => (Some(Axis::Lateral), Some(Axis::Axial)),
                2 => (Some(Axis::Axial), Some(Axis::Lateral)),
                _ => (None, None),
            };
            if let (Some(p), Some(f)) = (p, f) {
                direct.set_condition(slot, p, Condition::Displacement, rng.random_range(-1e-3..1e-3)).unwrap();
                direct.set_condition(slot, f, Condition::Force, rng.random_range(-0.01..0.01)).unwrap();
            }
        }
        let mut round_trip = direct.clone();
        let pivots_before = direct.stats().n_pivots;
        let n_turns = 3000;
        for _ in 0..n_turns {
            let slot = Slot::new(rng.random_range(0..n_nodes));
            let a = direct.angle_rad(slot) + rng.random_range(-0.3..0.3);
            direct.set_angle(slot, a).unwrap();
            // The scheme it replaces: pivot the displacement DOF to force, turn, pivot back.
            let mixed = round_trip.condition(slot, Axis::Axial) != round_trip.condition(slot, Axis::Lateral);
            let p = Axis::BOTH.into_iter().find(|&ax| round_trip.condition(slot, ax) == Condition::Displacement);
            if let (true, Some(p)) = (mixed, p) {
                let v = round_trip.prescribed_value(slot, p);
                round_trip.set_condition(slot, p, Condition::Force, 0.0).unwrap();
                round_trip.set_angle(slot, a).unwrap();
                round_trip.set_condition(slot, p, Condition::Displacement, v).unwrap();
            } else {
                round_trip.set_angle(slot, a).unwrap();
            }
        }
        let d = direct.n_dofs();
        let tol = 1e-15 * (n_turns as f64).sqrt() * d as f64;
        let fresh = direct.hybrid_from_scratch(&cache).unwrap();
        let e_fresh = scaled_hybrid_diff(&direct, &fresh);
        let mut rt = faer::Mat::<f64>::zeros(d, d);
        for i in 0..d {
            for j in 0..d {
                rt[(i, j)] = round_trip.hybrid(i, j);
            }
        }
        let e_rt = scaled_hybrid_diff(&direct, &rt);
        println!("mesh {nx}, d = {d}: vs fresh {e_fresh:e}, vs round trip {e_rt:e} (tolerance {tol:e})");
        assert!(e_fresh < tol && e_rt < tol, "mesh {nx}: vs fresh {e_fresh:e}, vs round trip {e_rt:e} (tolerance {tol:e})");
        // The direct update pivots nothing; the rotations are counted as before.
        assert_eq!(direct.stats().n_pivots, pivots_before);
        assert_eq!(direct.stats().n_rotations, round_trip.stats().n_rotations);
        assert!(round_trip.stats().n_pivots > direct.stats().n_pivots + 1000);
        // And the solve agrees with a fresh one.
        direct.solve();
        let e = max_rel_diff(&direct, &cache);
        assert!(e < 1e-9, "mesh {nx}: rel diff {e:e}");
    }
}

/// A rotation that would prescribe a displacement along a direction the other prescribed
/// displacements already determine is refused, and leaves the solver exactly as it was.
/// Two working nodes that move together (identical compliance columns, a rank-deficient
/// $C$): node 0's $x$ displacement prescribed, node 1 with $y$ displacement and $x$ force;
/// turning node 1 so its displacement direction becomes $x$ is singular.
#[test]
fn a_singular_mixed_rotation_is_refused_and_changes_nothing() {
    let (cx, cy) = (1e-3, 2e-3);
    let mut cache = ComplianceCache::new(2);
    let columns = [cx, 0.0, cx, 0.0, 0.0, cy, 0.0, cy];
    cache.insert(0, &columns);
    cache.insert(1, &columns);
    let mut s = MixedSolver::with_capacity(2);
    let a = s.add_node(&cache, NodeIdx(0), 0.0).unwrap();
    s.set_condition(a, Axis::Axial, Condition::Displacement, 1e-4).unwrap();
    // At pi/2 the axial direction of node 1 is y, its lateral one -x.
    let b = s.add_node(&cache, NodeIdx(1), std::f64::consts::FRAC_PI_2).unwrap();
    s.set_condition(b, Axis::Axial, Condition::Displacement, 2e-4).unwrap();
    s.set_condition(b, Axis::Lateral, Condition::Force, 0.01).unwrap();
    // A turn to a direction with some y in it is fine.
    s.set_angle(b, 0.3).unwrap();
    s.set_angle(b, std::f64::consts::FRAC_PI_2).unwrap();
    let before = s.clone();
    let e = s.set_angle(b, 0.0).unwrap_err();
    assert!(
        matches!(e, MixedError::SingularPivot { contact, axis: Axis::Axial, pivot } if contact == ContactPoint::node(NodeIdx(1)).id() && pivot < 1e-15 * cx),
        "{e}"
    );
    assert_eq!(s.angle_rad(b), before.angle_rad(b));
    assert_eq!(s.stats(), before.stats());
    assert_eq!((&s.kind, &s.x, &s.h), (&before.kind, &before.x, &before.h));
    // The same turn through the pivot round trip fails at its second pivot too.
    let mut rt = before.clone();
    rt.set_condition(b, Axis::Axial, Condition::Force, 0.0).unwrap();
    rt.set_angle(b, 0.0).unwrap();
    assert!(matches!(rt.set_condition(b, Axis::Axial, Condition::Displacement, 0.0), Err(MixedError::SingularPivot { .. })));
}

// ---------------------------------------------------------------------------------------
// Dimension-generic tests (3D, and the general frame change in 2D), on the mesh-free random
// SPD compliance of `fixtures::random_spd_compliance`.

use crate::fixtures::random_spd_compliance;

/// The interpolation matrix row block of `contact` in dimension `D`: $P_{(Da+c),(Di+c)} = N_i$.
fn add_interp_row<const D: usize>(p: &mut faer::Mat<f64>, a: usize, contact: &ContactPoint) {
    for (i, w) in contact.terms() {
        for c in 0..D {
            p[(D * a + c, D * i.index() + c)] += w;
        }
    }
}

/// The hybrid matrix of the solver's contacts, frames and kinds computed densely from the
/// full compliance `c` (independent of the cache and of `hybrid_from_scratch`):
/// $C_L = A P C P^\top A^\top$, then the block formula with an LU inverse of $C_{PP}$.
fn dense_hybrid<const D: usize>(s: &MixedSolver<D>, c: &[f64]) -> faer::Mat<f64> {
    let n = (c.len() as f64).sqrt() as usize;
    let d = s.n_dofs();
    let cm = faer::Mat::from_fn(n, n, |i, j| c[i * n + j]);
    let mut p = faer::Mat::<f64>::zeros(d, n);
    for (a, contact) in s.contacts().iter().enumerate() {
        add_interp_row::<D>(&mut p, a, contact);
    }
    let mut am = faer::Mat::<f64>::zeros(d, d);
    for a in 0..s.n_nodes() {
        let f = s.frame(Slot::new(a));
        for i in 0..D {
            for j in 0..D {
                am[(D * a + i, D * a + j)] = f[i][j];
            }
        }
    }
    let ap = &am * &p;
    let cl = &ap * &cm * ap.transpose();
    let pset: Vec<usize> = (0..d).filter(|&k| s.kind[k] == Condition::Displacement).collect();
    let fset: Vec<usize> = (0..d).filter(|&k| s.kind[k] == Condition::Force).collect();
    let cpp = faer::Mat::from_fn(pset.len(), pset.len(), |i, j| cl[(pset[i], pset[j])]);
    let inv = if pset.is_empty() { faer::Mat::zeros(0, 0) } else { faer::linalg::solvers::DenseSolveCore::inverse(&cpp.partial_piv_lu()) };
    let mut h = faer::Mat::<f64>::zeros(d, d);
    for (i, &pi) in pset.iter().enumerate() {
        for (j, &pj) in pset.iter().enumerate() {
            h[(pi, pj)] = inv[(i, j)];
        }
        for &fj in &fset {
            let v: f64 = (0..pset.len()).map(|k| inv[(i, k)] * cl[(pset[k], fj)]).sum();
            h[(pi, fj)] = -v;
            h[(fj, pi)] = (0..pset.len()).map(|k| cl[(fj, pset[k])] * inv[(k, i)]).sum();
        }
    }
    for &fi in &fset {
        for &fj in &fset {
            let mut v = cl[(fi, fj)];
            for &pk in &pset {
                v += cl[(fi, pk)] * h[(pk, fj)];
            }
            h[(fi, fj)] = v;
        }
    }
    h
}

/// The spectral condition number of $C_{PP}$, the block of the local working compliance
/// the hybrid matrix inverts (1 when nothing is displacement-prescribed).
fn cond_local<const D: usize>(s: &MixedSolver<D>, c: &[f64]) -> f64 {
    let h = dense_hybrid(s, c);
    let pset: Vec<usize> = (0..s.n_dofs()).filter(|&k| s.kind[k] == Condition::Displacement).collect();
    if pset.is_empty() {
        return 1.0;
    }
    // H_PP = C_PP^-1: its spectrum is the reciprocal of C_PP's.
    let hpp = faer::Mat::from_fn(pset.len(), pset.len(), |i, j| 0.5 * (h[(pset[i], pset[j])] + h[(pset[j], pset[i])]));
    let ev = hpp.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
    let (lo, hi) = ev.iter().fold((f64::MAX, 0.0f64), |(lo, hi), &e| (lo.min(e), hi.max(e)));
    assert!(lo > 0.0, "C_PP is positive definite");
    hi / lo
}

/// A rotation matrix from a unit quaternion $(w, x, y, z)$ (normalised here).
fn rotation_of_quaternion(q: [f64; 4]) -> Block<3> {
    let nq = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|v| v / nq);
    [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
    ]
}

/// A random rotation: uniform (a normalised Gaussian-like quaternion) or, when `small`, within
/// about $10^{-3}$ rad of the identity.
fn random_rotation(rng: &mut SmallRng, small: bool) -> Block<3> {
    if small {
        let e = 5e-4;
        rotation_of_quaternion([1.0, rng.random_range(-e..e), rng.random_range(-e..e), rng.random_range(-e..e)])
    } else {
        loop {
            let q: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
            let n2: f64 = q.iter().map(|v| v * v).sum();
            if n2 > 1e-2 && n2 <= 1.0 {
                return rotation_of_quaternion(q);
            }
        }
    }
}

/// A random contact among `n_nodes` nodes: a node, or a material point of a random
/// "tetrahedron" (four distinct nodes) with random barycentric weights.
fn random_contact_3d(rng: &mut SmallRng, n_nodes: usize, tet_idx: usize) -> ContactPoint {
    if rng.random_bool(0.4) {
        return ContactPoint::node(NodeIdx(rng.random_range(0..n_nodes)));
    }
    let mut nodes = [0usize; 4];
    let mut k = 0;
    while k < 4 {
        let v = rng.random_range(0..n_nodes);
        if !nodes[..k].contains(&v) {
            nodes[k] = v;
            k += 1;
        }
    }
    let raw: [f64; 4] = std::array::from_fn(|_| rng.random_range(0.05..1.0));
    let sum: f64 = raw.iter().sum();
    ContactPoint::in_tetrahedron(tet_idx, nodes, raw.map(|w| w / sum))
}

/// The solver's observable state, to check that a refused operation changed nothing.
fn snapshot<const D: usize>(s: &MixedSolver<D>) -> (Vec<Condition>, Vec<f64>, Vec<f64>, Vec<Block<D>>, MixedStats, usize) {
    (s.kind.clone(), s.x.clone(), s.h.clone(), s.frame.clone(), s.stats(), s.n_nodes())
}

/// The compliance block between two 3D contacts equals $P_a C P_b^\top$ of the dense
/// compliance, and $W_{ab} = W_{ba}^\top$.
#[test]
fn contact_blocks_in_3d_equal_the_dense_interpolation() {
    let n_nodes = 12;
    let (c, cache) = random_spd_compliance::<3>(n_nodes, 7);
    let n = 3 * n_nodes;
    let mut rng = SmallRng::seed_from_u64(70);
    for t in 0..50 {
        let (a, b) = (random_contact_3d(&mut rng, n_nodes, t), random_contact_3d(&mut rng, n_nodes, t + 1));
        let wab = cache.contact_block(&a, &b).unwrap();
        let wba = cache.contact_block(&b, &a).unwrap();
        let mut pa = faer::Mat::<f64>::zeros(3, n);
        let mut pb = faer::Mat::<f64>::zeros(3, n);
        add_interp_row::<3>(&mut pa, 0, &a);
        add_interp_row::<3>(&mut pb, 0, &b);
        let cm = faer::Mat::from_fn(n, n, |i, j| c[i * n + j]);
        let dense = &pa * &cm * pb.transpose();
        for i in 0..3 {
            for j in 0..3 {
                assert!((wab[i][j] - dense[(i, j)]).abs() < 1e-17, "{a} / {b}");
                assert!((wab[i][j] - wba[j][i]).abs() < 1e-17);
            }
        }
    }
}

/// Random sequences in 3D — contacts added (nodes and tetrahedra's material points, random
/// frames), condition switches (pivots), frame changes by random rotations (small and large,
/// on slots of uniform and of mixed kinds), new values, removals — give the hybrid matrix and
/// the unknowns of a dense computation from the full compliance, after every operation.
/// Tolerance: $10^{-14}\,\kappa(C_{PP})\, d$ on the DOF-scaled $H$ and on $y$ (row-relative),
/// with $\kappa(C_{PP})$ the condition number of the block the hybrid matrix inverts; no
/// growth with the number of operations is allowed (the worst seen is a quarter of it).
/// A refused operation (a singular pivot) must leave the state exactly as it was.
#[test]
fn random_3d_updates_equal_a_dense_computation() {
    for (seed, n_nodes, cap) in [(31u64, 12usize, 8usize), (32, 12, 10), (33, 16, 12)] {
        let (c, cache) = random_spd_compliance::<3>(n_nodes, seed);
        let mut rng = SmallRng::seed_from_u64(seed * 1000);
        let mut s = MixedSolver3::with_capacity(cap);
        let (mut n_checks, mut n_mixed_rot, mut n_uniform_rot, mut n_points, mut n_refused) = (0, 0, 0, 0, 0);
        let mut worst: f64 = 0.0;
        for step in 0..1500 {
            let op = rng.random_range(0..12);
            let before = snapshot(&s);
            let result = if s.n_nodes() < 2 || (op < 2 && s.n_nodes() < cap) {
                let contact = random_contact_3d(&mut rng, n_nodes, step);
                let frame = random_rotation(&mut rng, false);
                match s.add_contact_in_frame(&cache, contact, frame) {
                    Err(MixedError::AlreadyWorking { .. }) => continue,
                    r => {
                        n_points += usize::from(contact.tet_idx().is_some());
                        r.map(|_| ())
                    }
                }
            } else if op < 6 {
                let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                let axis = Axis::of_component(rng.random_range(0..3));
                let cond = if rng.random_bool(0.6) { Condition::Displacement } else { Condition::Force };
                let v = if cond == Condition::Displacement { rng.random_range(-1e-3..1e-3) } else { rng.random_range(-0.01..0.01) };
                s.set_condition(slot, axis, cond, v)
            } else if op < 9 {
                let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                let small = rng.random_bool(0.5);
                let q = random_rotation(&mut rng, small);
                let f = s.frame(slot);
                // The needle turned by q: the new axes are q t, q n, q b (rows F q^T).
                let f_new: Block<3> = mul_t(&f, &q);
                let kinds = Axis::ALL3.map(|a| s.condition(slot, a));
                let mixed = kinds.iter().any(|&k| k != kinds[0]);
                let r = s.set_frame(slot, f_new);
                if r.is_ok() {
                    if mixed {
                        n_mixed_rot += 1;
                    } else {
                        n_uniform_rot += 1;
                    }
                }
                r
            } else if op < 10 && s.n_nodes() > 2 {
                s.remove_slot(Slot::new(rng.random_range(0..s.n_nodes())))
            } else {
                for k in 0..s.n_dofs() {
                    let slot = Slot::new(k / 3);
                    let axis = Axis::of_local_dof::<3>(k);
                    let v = if s.condition(slot, axis) == Condition::Displacement {
                        rng.random_range(-1e-3..1e-3)
                    } else {
                        rng.random_range(-0.01..0.01)
                    };
                    s.set_value(slot, axis, v);
                }
                Ok(())
            };
            if let Err(e) = result {
                assert!(matches!(e, MixedError::SingularPivot { .. }), "step {step}: {e}");
                assert!(snapshot(&s) == before, "step {step}: a refused operation changed the state");
                n_refused += 1;
                continue;
            }
            s.solve();
            let h_ref = dense_hybrid(&s, &c);
            let kappa = cond_local(&s, &c);
            let tol = 1e-14 * kappa * s.n_dofs() as f64;
            let (eh, ey) = (scaled_hybrid_diff(&s, &h_ref), y_rel_diff(&s, &h_ref));
            worst = worst.max(eh / tol).max(ey / tol);
            assert!(eh < tol && ey < tol, "seed {seed} step {step}: d = {}, H diff {eh:e}, y diff {ey:e}, tolerance {tol:e}", s.n_dofs());
            n_checks += 1;
        }
        println!(
            "seed {seed}: {n_checks} checks, worst error / tolerance {worst:.2e}, {:?}, {n_mixed_rot} mixed and {n_uniform_rot} uniform rotations, {n_points} points, {n_refused} refused",
            s.stats()
        );
        assert!(n_checks > 1000 && n_mixed_rot > 100 && n_uniform_rot > 50 && n_points > 20, "{:?}", s.stats());
        // The cache-based rebuild (contact blocks, 3 × 3 frames) agrees with the dense one.
        let e_rebuild = scaled_hybrid_diff(&s, &s.hybrid_from_scratch(&cache).unwrap());
        assert!(e_rebuild < 1e-14 * cond_local(&s, &c) * s.n_dofs() as f64, "rebuild: {e_rebuild:e}");
        assert!(s.stats().n_pivots > 200 && s.stats().n_removed > 20, "{:?}", s.stats());
    }
}

/// In 3D the condensed solve is the mixed problem on the working compliance: every slot's
/// world displacement is $\sum_b W_{ab} f_b$ of the world forces, and the prescribed local
/// values hold.
#[test]
fn condensed_3d_solve_satisfies_the_working_compliance() {
    let n_nodes = 14;
    let (_, cache) = random_spd_compliance::<3>(n_nodes, 41);
    let mut rng = SmallRng::seed_from_u64(4100);
    let mut s = MixedSolver3::with_capacity(9);
    let mut t = 0;
    while s.n_nodes() < 9 {
        let contact = random_contact_3d(&mut rng, n_nodes, t);
        t += 1;
        let Ok(slot) = s.add_contact_in_frame(&cache, contact, random_rotation(&mut rng, false)) else { continue };
        // A needle-like pattern: n and b held, t stuck on some, slipping with a load on others.
        for axis in [Axis::Lateral, Axis::Binormal] {
            s.set_condition(slot, axis, Condition::Displacement, rng.random_range(-1e-3..1e-3)).unwrap();
        }
        let ax = if slot.index() % 2 == 0 { Condition::Displacement } else { Condition::Force };
        s.set_condition(slot, Axis::Axial, ax, rng.random_range(-1e-3..1e-3)).unwrap();
    }
    s.solve();
    let scale = Slot::all(9).map(|k| s.displacement_world(k).iter().fold(0.0f64, |m, v| m.max(v.abs()))).fold(0.0, f64::max);
    for a in Slot::all(9) {
        let mut u = [0.0; 3];
        for b in Slot::all(9) {
            let w = cache.contact_block(&s.contacts()[a.index()], &s.contacts()[b.index()]).unwrap();
            let f = s.force_world(b);
            for i in 0..3 {
                for j in 0..3 {
                    u[i] += w[i][j] * f[j];
                }
            }
        }
        let uw = s.displacement_world(a);
        for i in 0..3 {
            assert!((u[i] - uw[i]).abs() < 1e-11 * scale, "slot {a}: {u:?} vs {uw:?}");
        }
        let ul = s.displacement_local(a);
        for axis in Axis::ALL3 {
            if s.condition(a, axis) == Condition::Displacement {
                assert_eq!(ul[axis], s.prescribed_value(a, axis));
            } else {
                assert_eq!(s.force_local(a)[axis], s.prescribed_value(a, axis));
            }
        }
    }
}

/// The general frame change (any dimension) applied in 2D through `set_frame` gives the same
/// hybrid matrix as the 2D closed form of `set_angle`, after thousands of turns of slipping
/// and bevel-like slots, and both equal a fresh rebuild.
#[test]
fn general_frame_change_in_2d_equals_the_closed_form() {
    let n_nodes = 20;
    let (c, cache) = random_spd_compliance::<2>(n_nodes, 51);
    let mut rng = SmallRng::seed_from_u64(5100);
    let mut closed = MixedSolver2::with_capacity(12);
    for node in 0..12 {
        let slot = closed.add_node(&cache, NodeIdx(node), rng.random_range(-3.2..3.2)).unwrap();
        let (p, f) = if node % 3 == 2 { (Axis::Axial, Axis::Lateral) } else { (Axis::Lateral, Axis::Axial) };
        if node % 4 != 3 {
            closed.set_condition(slot, p, Condition::Displacement, rng.random_range(-1e-3..1e-3)).unwrap();
            closed.set_condition(slot, f, Condition::Force, rng.random_range(-0.01..0.01)).unwrap();
        }
    }
    let mut general = closed.clone();
    let n_turns = 3000;
    for _ in 0..n_turns {
        let slot = Slot::new(rng.random_range(0..12));
        let a = closed.angle_rad(slot) + rng.random_range(-0.3..0.3);
        closed.set_angle(slot, a).unwrap();
        general.set_frame(slot, frame_of_angle(a)).unwrap();
    }
    let d = closed.n_dofs();
    let tol = 1e-15 * (n_turns as f64).sqrt() * d as f64;
    let mut hg = faer::Mat::<f64>::zeros(d, d);
    for i in 0..d {
        for j in 0..d {
            hg[(i, j)] = general.hybrid(i, j);
        }
    }
    let e_between = scaled_hybrid_diff(&closed, &hg);
    let e_closed = scaled_hybrid_diff(&closed, &dense_hybrid(&closed, &c));
    let e_general = scaled_hybrid_diff(&general, &dense_hybrid(&general, &c));
    println!("2D general vs closed form {e_between:e}, closed vs dense {e_closed:e}, general vs dense {e_general:e} (tolerance {tol:e})");
    assert!(e_between < tol && e_closed < tol && e_general < tol);
    assert_eq!(closed.stats().n_pivots, general.stats().n_pivots);
    for k in Slot::all(12) {
        assert!(
            (closed.angle_rad(k) - general.angle_rad(k))
                .rem_euclid(std::f64::consts::TAU)
                .min((general.angle_rad(k) - closed.angle_rad(k)).rem_euclid(std::f64::consts::TAU))
                < 1e-12
        );
    }
}

/// A singular 3D pivot is refused with the typed error naming the contact and the axis, and
/// changes nothing: a tetrahedron's point whose four nodes all have their $x$ displacement
/// prescribed cannot have its own $x$ (axial, identity frame) prescribed; a frame change
/// that turns a prescribed direction of a slipping point onto that direction is refused
/// too; a frame that is not a rotation is refused.
#[test]
fn a_singular_3d_pivot_is_refused_with_the_contact_named() {
    let (_, cache) = random_spd_compliance::<3>(8, 61);
    let identity: Block<3> = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut s = MixedSolver3::with_capacity(6);
    for node in 0..4 {
        let slot = s.add_contact_in_frame(&cache, ContactPoint::node(NodeIdx(node)), identity).unwrap();
        s.set_condition(slot, Axis::Axial, Condition::Displacement, 1e-4).unwrap();
    }
    let point = ContactPoint::in_tetrahedron(17, [0, 1, 2, 3], [0.1, 0.2, 0.3, 0.4]);
    let slot = s.add_contact_in_frame(&cache, point, identity).unwrap();
    let before = snapshot(&s);
    let e = s.set_condition(slot, Axis::Axial, Condition::Displacement, 0.0).unwrap_err();
    assert!(matches!(e, MixedError::SingularPivot { contact, axis: Axis::Axial, .. } if contact == point.id()), "{e}");
    assert!(e.to_string().contains("axial (t) displacement of the material point in tetrahedron 17 (nodes 0, 1, 2, 3)"), "{e}");
    assert!(snapshot(&s) == before);
    // y and z are free: prescribe them (a point held across a needle along x), then turn the
    // frame so that n points along x: refused, unchanged.
    s.set_condition(slot, Axis::Lateral, Condition::Displacement, 0.0).unwrap();
    s.set_condition(slot, Axis::Binormal, Condition::Displacement, 0.0).unwrap();
    let turned = [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]];
    let before = snapshot(&s);
    let e = s.set_frame(slot, turned).unwrap_err();
    assert!(matches!(e, MixedError::SingularPivot { contact, axis: Axis::Lateral, .. } if contact == point.id()), "{e}");
    assert!(snapshot(&s) == before);
    // A small turn is fine.
    s.set_frame(slot, rotation_of_quaternion([1.0, 0.0, 0.0, 0.1])).unwrap();
    let e = s.set_frame(slot, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]).unwrap_err();
    assert!(matches!(e, MixedError::NotARotation { contact, .. } if contact == point.id()), "{e}");
    let e = s.set_frame(slot, [[1.0, 1e-6, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap_err();
    assert!(matches!(e, MixedError::NotARotation { .. }), "{e}");
    let e = s.add_contact_in_frame(&cache, ContactPoint::node(NodeIdx(5)), [[f64::NAN; 3]; 3]).unwrap_err();
    assert!(matches!(e, MixedError::NonFinite { .. }), "{e}");
}

/// In 3D the direct mixed-kind frame change equals the round trip it replaces (pivot the
/// slot's prescribed displacements to forces, turn with the congruence, pivot back) and a
/// dense computation, after thousands of turns of slots with one displacement and two forces
/// (a tip), two displacements and one force (a slipping point) and one kind; it pivots
/// nothing.
#[test]
fn mixed_3d_frame_changes_equal_the_pivot_round_trip() {
    let n_nodes = 30;
    let (c, cache) = random_spd_compliance::<3>(n_nodes, 81);
    let mut rng = SmallRng::seed_from_u64(8100);
    let mut direct = MixedSolver3::with_capacity(16);
    for node in 0..16 {
        let slot = direct.add_contact_in_frame(&cache, ContactPoint::node(NodeIdx(node)), random_rotation(&mut rng, false)).unwrap();
        let p: &[Axis] = match node % 4 {
            0 | 1 => &[Axis::Lateral, Axis::Binormal],
            2 => &[Axis::Axial],
            _ => &[],
        };
        for &axis in p {
            direct.set_condition(slot, axis, Condition::Displacement, rng.random_range(-1e-3..1e-3)).unwrap();
        }
    }
    let mut round_trip = direct.clone();
    let pivots_before = direct.stats().n_pivots;
    let n_turns = 2000;
    for _ in 0..n_turns {
        let slot = Slot::new(rng.random_range(0..16));
        let small = rng.random_bool(0.3);
        let q = random_rotation(&mut rng, small);
        let f_new = mul_t(&direct.frame(slot), &q);
        direct.set_frame(slot, f_new).unwrap();
        let p: Vec<Axis> = Axis::ALL3.into_iter().filter(|&a| round_trip.condition(slot, a) == Condition::Displacement).collect();
        let values: Vec<f64> = p.iter().map(|&a| round_trip.prescribed_value(slot, a)).collect();
        for &a in &p {
            round_trip.set_condition(slot, a, Condition::Force, 0.0).unwrap();
        }
        round_trip.set_frame(slot, f_new).unwrap();
        for (&a, &v) in p.iter().zip(&values) {
            round_trip.set_condition(slot, a, Condition::Displacement, v).unwrap();
        }
    }
    let d = direct.n_dofs();
    let mut rt = faer::Mat::<f64>::zeros(d, d);
    for i in 0..d {
        for j in 0..d {
            rt[(i, j)] = round_trip.hybrid(i, j);
        }
    }
    let tol = 1e-14 * cond_local(&direct, &c) * d as f64;
    let (e_rt, e_dense) = (scaled_hybrid_diff(&direct, &rt), scaled_hybrid_diff(&direct, &dense_hybrid(&direct, &c)));
    println!("3D d = {d}: direct vs round trip {e_rt:e}, vs dense {e_dense:e} (tolerance {tol:e})");
    assert!(e_rt < tol && e_dense < tol, "direct vs round trip {e_rt:e}, vs dense {e_dense:e} (tolerance {tol:e})");
    assert_eq!(direct.stats().n_pivots, pivots_before);
    assert_eq!(direct.stats().n_rotations, round_trip.stats().n_rotations);
    assert!(round_trip.stats().n_pivots > direct.stats().n_pivots + 1000);
}
