//! The hybrid matrix's round-off check (issue 19): $H$ is kept by $O(d^2)$ updates for hours at
//! 1 kHz, so the step checks that its solution still satisfies the tissue's compliance relation
//! and rebuilds $H$ from scratch when it does not. One code for both dimensions (the working
//! solver [`MixedSolver<D>`] and its blocks [`ContactBlocks<D>`]): run by the 2D step
//! ([`crate::sim`]) and the 3D one ([`crate::sim3`]).
//!
//! Every [`param_limits::HYBRID_CHECK_EVERY_TICKS`] ticks, one working contact $a$ (round robin)
//! is checked against the solver's own solution (its prescribed values and the unknowns its last
//! solve gave, in world components):
//! $$r_a = u_a - \sum_{b \in \mathcal{W}} W_{ab} f_b, \qquad
//!   \rho_a = \frac{\lVert r_a \rVert_\infty}{\max\big(\lVert u_a \rVert_\infty,\ \max_i \sum_b \lvert W_{ab}\rvert_{i\cdot} \lvert f_b \rvert\big)},$$
//! with $W_{ab}$ the world compliance block of the two contacts (the blocks the solver was built
//! from: the column cache's or 3D's node blocks, scaled in a viscoelastic tissue,
//! [`crate::viscous`]; plus the contact's own series compliance on $W_{aa}$, 3D's near field), so
//! a check costs $O(d)$ block reads and nothing else. The hybrid matrix's solve is exact in exact
//! arithmetic, so $\rho_a$ measures the drift of $H$ from its definition (plus one product's
//! round-off). When $\rho_a$ exceeds [`param_limits::HYBRID_DRIFT_TOL`], $H$ is rebuilt from
//! $C_{\mathcal{W}\mathcal{W}}$ ([`crate::mixed::MixedSolver::rebuild`], $O(d^3)$ and allocating:
//! the one exception to a step's allocation-free rule, counted in
//! [`crate::SimStats::hybrid_rebuilds`] and [`crate::sim3::Sim3Stats::hybrid_rebuilds`], not
//! expected to happen) and used from the next tick.
//!
//! [`param_limits::HYBRID_CHECK_EVERY_TICKS`]: crate::sim::param_limits::HYBRID_CHECK_EVERY_TICKS
//! [`param_limits::HYBRID_DRIFT_TOL`]: crate::sim::param_limits::HYBRID_DRIFT_TOL

use crate::compliance::ContactBlocks;
use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedSolver};
use crate::sim::param_limits::HYBRID_DRIFT_TOL;

/// The check's state between ticks.
#[derive(Debug, Clone)]
pub(crate) struct DriftCheck {
    /// The slot index the next check visits.
    pub cursor: usize,
    /// The largest residual $\rho_a$ seen.
    pub max_residual: f64,
    /// The rebuild threshold ([`HYBRID_DRIFT_TOL`] unless a test set another).
    pub tol: f64,
    /// The recomputed unknowns $y = H x$, capacity the solver's DOFs.
    pub y: Vec<f64>,
}

impl DriftCheck {
    /// A check for a working set of up to `cap` contacts of `D` DOFs each.
    pub fn new<const D: usize>(cap: usize) -> Self {
        Self { cursor: 0, max_residual: 0.0, tol: HYBRID_DRIFT_TOL, y: Vec::with_capacity(D * cap) }
    }
}

/// The relative residual $\rho_a$ of contact `slot_idx` (see the module documentation); `None`
/// when a block is not cached (a contact whose columns were evicted: not expected, the cache
/// keeps working contacts' columns) or the row carries nothing (no force, no displacement).
/// The unknowns are recomputed as $y = H x$ from the prescribed values into `y` (capacity: the
/// solver's DOFs), so a prescribed value changed after the last solve (the bevel force's update)
/// does not read as drift; $O(d^2)$.
pub(crate) fn row_residual<const D: usize, C: ContactBlocks<D> + ?Sized>(
    solver: &MixedSolver<D>,
    cache: &C,
    slot_idx: usize,
    y: &mut Vec<f64>,
) -> Option<f64> {
    let contacts = solver.contacts();
    let a = contacts.get(slot_idx)?;
    let d = solver.n_dofs();
    let x = |k: usize| solver.prescribed_value(Slot::new(k / D), Axis::of_local_dof::<D>(k));
    y.clear();
    y.extend((0..d).map(|i| (0..d).map(|j| solver.hybrid(i, j) * x(j)).sum::<f64>()));
    // Local (u, f) of DOF k: the prescribed one from x, the other from y.
    let local = |k: usize| match solver.condition(Slot::new(k / D), Axis::of_local_dof::<D>(k)) {
        Condition::Displacement => (x(k), y[k]),
        Condition::Force => (y[k], x(k)),
    };
    // World components of a slot's local vector: $\sum_r F_r v_r$ over the frame's rows.
    let world = |slot: usize, v: [f64; D]| -> [f64; D] {
        let fr = solver.frame(Slot::new(slot));
        std::array::from_fn(|c| {
            let mut s = fr[0][c] * v[0];
            for r in 1..D {
                s += fr[r][c] * v[r];
            }
            s
        })
    };
    let mut wf = [0.0f64; D];
    let mut scale = [0.0f64; D];
    for (k, b) in contacts.iter().enumerate() {
        let mut w = cache.contact_block(a, b)?;
        if k == slot_idx {
            let s = solver.series_compliance(Slot::new(k));
            if s != [[0.0; D]; D] {
                for r in 0..D {
                    for c in 0..D {
                        w[r][c] += s[r][c];
                    }
                }
            }
        }
        let f = world(k, std::array::from_fn(|i| local(D * k + i).1));
        for r in 0..D {
            for c in 0..D {
                wf[r] += w[r][c] * f[c];
                scale[r] += (w[r][c] * f[c]).abs();
            }
        }
    }
    let u = world(slot_idx, std::array::from_fn(|i| local(D * slot_idx + i).0));
    let denom = (0..D).fold(0.0f64, |m, r| m.max(scale[r])).max((0..D).fold(0.0f64, |m, r| m.max(u[r].abs())));
    if denom <= 0.0 || !denom.is_finite() {
        return None;
    }
    Some((0..D).fold(0.0f64, |m, r| m.max((u[r] - wf[r]).abs())) / denom)
}

/// What one check did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Checked {
    /// Nothing to check (no contact, or a row with no load).
    Nothing,
    /// Within the tolerance.
    Fine,
    /// Past the tolerance: $H$ rebuilt, used from the next tick.
    Rebuilt,
    /// Past the tolerance, and the rebuild refused ([`crate::mixed::MixedError`]: a contact's columns missing
    /// or $C_{PP}$ not positive definite); the solver keeps its old $H$.
    RebuildFailed,
}

/// One check of the round robin: checks the contact at `drift.cursor` (then advances it),
/// records the residual, and rebuilds $H$ when it exceeds `drift.tol`.
pub(crate) fn check_one<const D: usize, C: ContactBlocks<D> + ?Sized>(
    solver: &mut MixedSolver<D>,
    cache: &C,
    drift: &mut DriftCheck,
) -> Checked {
    let d = solver.contacts().len();
    if d == 0 {
        return Checked::Nothing;
    }
    let slot_idx = drift.cursor % d;
    drift.cursor = (slot_idx + 1) % d;
    let Some(rho) = row_residual(solver, cache, slot_idx, &mut drift.y) else { return Checked::Nothing };
    drift.max_residual = drift.max_residual.max(rho);
    if rho <= drift.tol {
        return Checked::Fine;
    }
    match solver.rebuild(cache) {
        Ok(()) => Checked::Rebuilt,
        Err(_) => Checked::RebuildFailed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::ComplianceCache;
    use crate::contact::ContactPoint;
    use crate::fixtures::random_spd_compliance;
    use crate::ids::NodeIdx;

    /// A working set of 6 contacts on a random SPD compliance, in turned frames, with mixed
    /// conditions (half the DOFs force-prescribed) and a series compliance on one contact.
    fn solver<const D: usize>(cache: &ComplianceCache<D>) -> MixedSolver<D> {
        let mut s = MixedSolver::<D>::with_capacity(8);
        for k in 0..6 {
            let a = 0.3 * k as f64;
            let frame: [[f64; D]; D] = std::array::from_fn(|r| {
                std::array::from_fn(|c| match (r, c) {
                    (0, 0) | (1, 1) => a.cos(),
                    (0, 1) => a.sin(),
                    (1, 0) => -a.sin(),
                    _ => (r == c) as u8 as f64,
                })
            });
            let slot = s.add_contact_in_frame(cache, ContactPoint::node(NodeIdx(2 * k)), frame).unwrap();
            for i in 0..D {
                let cond = if (k + i) % 2 == 0 { Condition::Displacement } else { Condition::Force };
                s.set_condition(slot, Axis::of_local_dof::<D>(i), cond, 1e-4 * (1.0 + k as f64 - i as f64)).unwrap();
            }
        }
        let mut series = [[0.0; D]; D];
        for i in 0..D {
            series[i][i] = 2e-4;
        }
        s.add_series_compliance(Slot::new(2), series).unwrap();
        s.solve();
        s
    }

    /// In both dimensions (one code): every row of a consistent solver (series compliance
    /// included) has a residual at round-off; the compliance scaled by 1 + 1e-5 (a cache the
    /// hybrid matrix no longer matches, as when $H$ drifts) is found, the check rebuilds $H$, and
    /// after the rebuild the residual is back at round-off.
    fn a_drifted_row_is_found_and_rebuilt<const D: usize>() {
        let (_, mut cache) = random_spd_compliance::<D>(14, 5);
        let mut s = solver::<D>(&cache);
        let mut y = Vec::new();
        for k in 0..6 {
            let rho = row_residual(&s, &cache, k, &mut y).unwrap();
            assert!(rho < 1e-12, "D = {D}, row {k}: {rho:e}");
        }
        for node in 0..14 {
            let mut cols: Vec<f64> = (0..D).flat_map(|c| cache.column(node, c).unwrap().to_vec()).collect();
            cols.iter_mut().for_each(|v| *v *= 1.0 + 1e-5);
            cache.insert(node, &cols);
        }
        let rho = row_residual(&s, &cache, 2, &mut y).unwrap();
        assert!(rho > 1e-7, "D = {D}: a perturbed compliance gave a residual of only {rho:e}");
        let mut check = DriftCheck { cursor: 2, ..DriftCheck::new::<D>(8) };
        assert_eq!(check_one(&mut s, &cache, &mut check), Checked::Rebuilt);
        assert_eq!(check.cursor, 3);
        assert!(check.max_residual > 1e-7);
        s.solve();
        let after = row_residual(&s, &cache, 2, &mut y).unwrap();
        assert!(after < 1e-12, "D = {D}: after the rebuild {after:e}");
        assert_eq!(check_one(&mut s, &cache, &mut check), Checked::Fine);
    }

    #[test]
    fn a_drifted_row_is_found_and_rebuilt_in_2d_and_3d() {
        a_drifted_row_is_found_and_rebuilt::<2>();
        a_drifted_row_is_found_and_rebuilt::<3>();
    }
}
