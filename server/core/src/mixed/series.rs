//! A compliance in series with the tissue at one slot: added to the slot's own block of the
//! working compliance by pivots on $H$ (the 3D needle's near field, [`crate::sim3`]).

use super::blocks::to_local;
use super::{Block, Condition, MixedError, MixedSolver};
use crate::ids::Slot;

impl<const D: usize> MixedSolver<D> {
    /// Adds the world block `s` (symmetric, positive semi-definite) to the own compliance block
    /// of `slot`: $W_{ii} \to W_{ii} + S$, as if the slot's contact had the compliance $S$ in
    /// series with the tissue. The conditions and prescribed values stay. With every DOF of the
    /// slot force-prescribed this is $H_{ss} \mathrel{+}= F S F^\top$ ($H_{FF} = C_{FF} -
    /// C_{FP} C_{PP}^{-1} C_{PF}$ changes only in the slot's own block); the slot's
    /// displacement-prescribed DOFs are pivoted to forces first and back after, so at most
    /// $2D$ pivots, $O(d^2)$, no allocation. The added block is kept
    /// ([`MixedSolver::series_compliance`]) and included by [`MixedSolver::rebuild`].
    ///
    /// Errors: [`MixedError::NoSuchSlot`], [`MixedError::NonFinite`] for a non-finite block,
    /// [`MixedError::SingularPivot`] should a pivot back be singular (not expected: adding a
    /// positive semi-definite block only raises it); the state is unchanged on the first two.
    pub fn add_series_compliance(&mut self, slot: Slot, s: Block<D>) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        let contact = self.contact_of_slot[slot.index()];
        if !s.iter().flatten().all(|v| v.is_finite()) {
            return Err(MixedError::NonFinite { what: "a series compliance", contact: contact.id() });
        }
        let base = D * slot.index();
        let mut was_p = [false; D];
        for (c, p) in was_p.iter_mut().enumerate() {
            if self.kind[base + c] == Condition::Displacement {
                self.pivot(base + c)?;
                *p = true;
            }
        }
        let f = self.frame[slot.index()];
        let s_local = to_local(&s, &f, &f);
        let st = self.stride;
        for r in 0..D {
            for c in 0..D {
                self.h[(base + r) * st + base + c] += s_local[r][c];
                self.c_self[slot.index()][r][c] += s[r][c];
                self.series[slot.index()][r][c] += s[r][c];
            }
        }
        for (c, &p) in was_p.iter().enumerate() {
            if p {
                self.pivot(base + c)?;
            }
        }
        Ok(())
    }

    /// The series compliance added at `slot` (world; zero unless
    /// [`MixedSolver::add_series_compliance`] was called on it).
    pub fn series_compliance(&self, slot: Slot) -> Block<D> {
        self.series[slot.index()]
    }

    /// The part of the slot's displacement taken by its series compliance, $S f$ (world, after
    /// [`MixedSolver::solve`]): [`MixedSolver::displacement_world`] minus this is the tissue's.
    pub fn series_displacement_world(&self, slot: Slot) -> [f64; D] {
        let f = self.force_world(slot);
        let s = &self.series[slot.index()];
        std::array::from_fn(|i| (0..D).map(|j| s[i][j] * f[j]).sum())
    }
}

#[cfg(test)]
mod tests {
    use crate::contact::ContactPoint;
    use crate::fixtures::random_spd_compliance;
    use crate::ids::{Axis, NodeIdx, Slot};
    use crate::mixed::{Condition, MixedSolver3};

    /// Adding a series block to a slot with mixed conditions, among slots with displacements
    /// prescribed, gives the hybrid matrix a from-scratch build of $C + S$ gives, and the
    /// solution satisfies $u = (C + S) f$ on every DOF.
    #[test]
    fn series_block_matches_a_rebuild_and_the_compliance() {
        let (_, cache) = random_spd_compliance::<3>(6, 37);
        let mut s = MixedSolver3::with_capacity(6);
        let c = 0.6_f64.cos();
        let sn = 0.6_f64.sin();
        let frame = [[c, sn, 0.0], [-sn, c, 0.0], [0.0, 0.0, 1.0]];
        for v in 0..4 {
            s.add_contact_in_frame(&cache, ContactPoint::node(NodeIdx(v)), frame).unwrap();
        }
        // Slot 0 stuck (all displacements), slot 1 slipping (axial force), slot 2 free, slot 3
        // lateral only.
        for a in Axis::ALL3 {
            s.set_condition(Slot::new(0), a, Condition::Displacement, 1e-3 * (a.index() as f64 + 1.0)).unwrap();
        }
        s.set_condition(Slot::new(1), Axis::Lateral, Condition::Displacement, -2e-3).unwrap();
        s.set_condition(Slot::new(1), Axis::Binormal, Condition::Displacement, 0.5e-3).unwrap();
        s.set_condition(Slot::new(1), Axis::Axial, Condition::Force, 0.3).unwrap();
        s.set_condition(Slot::new(2), Axis::Axial, Condition::Force, -0.2).unwrap();
        s.set_condition(Slot::new(3), Axis::Lateral, Condition::Displacement, 1.5e-3).unwrap();
        let (c_par, c_perp) = (0.4, 0.25);
        let t = frame[0];
        let block: [[f64; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| c_perp * (if i == j { 1.0 } else { 0.0 }) + (c_par - c_perp) * t[i] * t[j]));
        for k in [1, 0, 3] {
            s.add_series_compliance(Slot::new(k), block).unwrap();
        }
        let h = s.hybrid_from_scratch(&cache).unwrap();
        let d = s.n_dofs();
        let scale = (0..d).map(|i| h[(i, i)].abs()).fold(0.0, f64::max);
        for i in 0..d {
            for j in 0..d {
                assert!((s.hybrid(i, j) - h[(i, j)]).abs() <= 1e-10 * scale, "H[{i},{j}] {} vs {}", s.hybrid(i, j), h[(i, j)]);
            }
        }
        s.solve();
        // u_a = sum_b C_ab f_b + S_a f_a, world.
        for a in 0..4 {
            let sa = Slot::new(a);
            let mut u = s.series_displacement_world(sa);
            for b in 0..4 {
                let sb = Slot::new(b);
                let blk = cache.contact_block(&ContactPoint::node(NodeIdx(a)), &ContactPoint::node(NodeIdx(b))).unwrap();
                let f = s.force_world(sb);
                for i in 0..3 {
                    u[i] += (0..3).map(|j| blk[i][j] * f[j]).sum::<f64>();
                }
            }
            let got = s.displacement_world(sa);
            for i in 0..3 {
                assert!((u[i] - got[i]).abs() <= 1e-10 * 1e-3, "slot {a} axis {i}: {} vs {}", u[i], got[i]);
            }
        }
        // Slot 2 had none added; slot 0 keeps its prescribed values.
        assert_eq!(s.series_compliance(Slot::new(2)), [[0.0; 3]; 3]);
        assert_eq!(s.series_compliance(Slot::new(0)), block);
        assert_eq!(s.prescribed_value(Slot::new(0), Axis::Binormal), 3e-3);
    }
}
