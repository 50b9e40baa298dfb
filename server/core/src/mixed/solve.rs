//! The solve $y = Hx$ and the displacements and forces it gives, local and world.

use super::blocks::dot;
use super::{Condition, MixedSolver};
use crate::ids::Slot;

impl<const D: usize> MixedSolver<D> {
    /// Computes the unknowns $y = H x$. $O(d^2)$, no allocation.
    pub fn solve(&mut self) {
        let d = self.n_dofs();
        let st = self.stride;
        for i in 0..d {
            self.y[i] = dot(&self.h[i * st..i * st + d], &self.x[..d]);
        }
    }

    /// Local displacement $(u_t, u_n, (u_b))$ of `slot` after [`MixedSolver::solve`].
    pub fn displacement_local(&self, slot: Slot) -> [f64; D] {
        std::array::from_fn(|c| {
            let k = D * slot.index() + c;
            if self.kind[k] == Condition::Displacement { self.x[k] } else { self.y[k] }
        })
    }

    /// Local force $(f_t, f_n, (f_b))$ on `slot` after [`MixedSolver::solve`].
    pub fn force_local(&self, slot: Slot) -> [f64; D] {
        std::array::from_fn(|c| {
            let k = D * slot.index() + c;
            if self.kind[k] == Condition::Force { self.x[k] } else { self.y[k] }
        })
    }

    /// $F^\top v$: a local vector of `slot` in world coordinates.
    fn to_world(&self, slot: Slot, v: [f64; D]) -> [f64; D] {
        let f = &self.frame[slot.index()];
        std::array::from_fn(|i| {
            let mut acc = f[0][i] * v[0];
            for k in 1..D {
                acc += f[k][i] * v[k];
            }
            acc
        })
    }

    /// World displacement of `slot`.
    pub fn displacement_world(&self, slot: Slot) -> [f64; D] {
        self.to_world(slot, self.displacement_local(slot))
    }

    /// World force on `slot` (the force the needle applies to the tissue there).
    pub fn force_world(&self, slot: Slot) -> [f64; D] {
        self.to_world(slot, self.force_local(slot))
    }
}
