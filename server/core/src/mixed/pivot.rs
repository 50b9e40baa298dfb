//! The principal pivot: switching what is prescribed on one local DOF (a rank-one update of $H$).

use super::{Condition, MixedError, MixedSolver, PIVOT_TOL};
use crate::ids::{Axis, Slot};

impl<const D: usize> MixedSolver<D> {
    /// Exchanges $x_k$ and $y_k$ (the principal pivot on $k$). Leaves the state unchanged and
    /// errors when the pivot is not safely positive.
    pub(super) fn pivot(&mut self, k: usize) -> Result<(), MixedError> {
        let d = self.n_dofs();
        let st = self.stride;
        let p = self.h[k * st + k];
        let c_kk = self.c_local_diag(k);
        // Converting F -> P needs the condensed compliance p > 0; P -> F needs (C_PP^-1)_kk > 0.
        let threshold = match self.kind[k] {
            Condition::Force => PIVOT_TOL * c_kk,
            Condition::Displacement => 0.0,
        };
        if !(p > threshold && p.is_finite()) {
            return Err(MixedError::SingularPivot {
                contact: self.contact_of_slot[k / D].id(),
                axis: Axis::of_local_dof::<D>(k),
                pivot: p,
            });
        }
        for j in 0..d {
            self.tmp_row[j] = self.h[k * st + j];
            self.tmp_col[j] = self.h[j * st + k];
        }
        let inv_p = 1.0 / p;
        for i in 0..d {
            if i == k {
                continue;
            }
            let f = self.tmp_col[i] * inv_p;
            if f != 0.0 {
                let row = &mut self.h[i * st..i * st + d];
                for (hij, &rkj) in row.iter_mut().zip(&self.tmp_row[..d]) {
                    *hij -= f * rkj;
                }
            }
            self.h[i * st + k] = f;
        }
        for j in 0..d {
            self.h[k * st + j] = -self.tmp_row[j] * inv_p;
        }
        self.h[k * st + k] = inv_p;
        self.kind[k] = match self.kind[k] {
            Condition::Displacement => Condition::Force,
            Condition::Force => Condition::Displacement,
        };
        self.stats.n_pivots += 1;
        Ok(())
    }

    /// Sets what is prescribed on the local DOF of `slot` along `axis` and its value (m for a
    /// displacement, N for a force, in the slot's frame). $O(d^2)$ when the kind changes, $O(1)$
    /// otherwise.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], [`MixedError::NonFinite`] for a non-finite value, and
    /// [`MixedError::SingularPivot`] when the kind change would make the system singular (the
    /// state is then unchanged). Panics only on a programming error ([`Axis::Binormal`] in 2D).
    pub fn set_condition(&mut self, slot: Slot, axis: Axis, cond: Condition, value: f64) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        if !value.is_finite() {
            return Err(MixedError::NonFinite { what: "a prescribed value", contact: self.contact_of_slot[slot.index()].id() });
        }
        let k = Self::dof(slot, axis);
        if self.kind[k] != cond {
            self.pivot(k)?;
        }
        self.x[k] = value;
        Ok(())
    }

    /// The prescribed value of a local DOF (a displacement or a force, by its kind).
    pub fn prescribed_value(&self, slot: Slot, axis: Axis) -> f64 {
        self.x[Self::dof(slot, axis)]
    }

    /// Sets only the prescribed value of a local DOF, keeping its kind. $O(1)$.
    pub fn set_value(&mut self, slot: Slot, axis: Axis, value: f64) {
        self.x[Self::dof(slot, axis)] = value;
    }
}
