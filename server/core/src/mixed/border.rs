//! Bordering: adding a working contact borders $H$ with its $D$ rows and columns; removing one
//! pivots its displacement-prescribed DOFs to forces and drops it.

use super::blocks::{check_frame, frame_of_angle, orthonormalized, to_local};
use super::{Block, Condition, MixedError, MixedSolver};
use crate::compliance::ContactBlocks;
use crate::contact::ContactPoint;
use crate::ids::{Axis, NodeIdx, Slot};

impl<const D: usize> MixedSolver<D> {
    /// Adds `contact` (a node or a material point) to the working set with frame `frame` (rows
    /// $[t, n, (b)]$, a rotation; stored re-orthonormalised, see [`MixedSolver::frame`]) and
    /// every local DOF force-prescribed at zero. Needs the columns of the contact's nodes in
    /// `cache`. $O(d^2)$.
    ///
    /// Errors: [`MixedError::Full`] when all `cap_nodes` slots are taken,
    /// [`MixedError::NonFinite`] or [`MixedError::NotARotation`] for a frame that is not a
    /// finite rotation, [`MixedError::AlreadyWorking`] when the node has a slot,
    /// [`MixedError::NotCached`] when its columns are missing; the state is then unchanged.
    pub fn add_contact_in_frame<C: ContactBlocks<D> + ?Sized>(
        &mut self,
        cache: &C,
        contact: ContactPoint,
        frame: Block<D>,
    ) -> Result<Slot, MixedError> {
        if self.n_nodes == self.cap_nodes {
            return Err(MixedError::Full { cap_nodes: self.cap_nodes });
        }
        check_frame(&frame, contact)?;
        self.border(cache, contact, orthonormalized(&frame), 0.0)
    }

    /// Borders $H$ with a new slot (formulas in [`MixedSolver::add_contact_in_frame`]); `frame`
    /// is valid, `angle_rad` is kept for 2D.
    fn border<C: ContactBlocks<D> + ?Sized>(
        &mut self,
        cache: &C,
        contact: ContactPoint,
        frame: Block<D>,
        angle_rad: f64,
    ) -> Result<Slot, MixedError> {
        if self.n_nodes == self.cap_nodes {
            return Err(MixedError::Full { cap_nodes: self.cap_nodes });
        }
        if let Some(node_idx) = contact.as_node()
            && self.slot_of(node_idx).is_some()
        {
            return Err(MixedError::AlreadyWorking { node_idx });
        }
        let c_nn_world = cache.contact_block(&contact, &contact).ok_or(MixedError::NotCached { contact: contact.id() })?;
        let d = self.n_dofs();
        let st = self.stride;
        // c: local compliance between existing DOFs and the D new ones.
        for s in 0..self.n_nodes {
            let b = cache.contact_block(&self.contact_of_slot[s], &contact).ok_or(MixedError::NotCached { contact: contact.id() })?;
            let l = to_local(&b, &self.frame[s], &frame);
            for r in 0..D {
                self.tmp_c[D * s + r] = l[r];
            }
        }
        let c_nn = to_local(&c_nn_world, &frame, &frame);
        // New columns: H[i, n] = [i in F] c_i - sum_{j in P} H_ij c_j.
        // New rows:    H[n, j] = sum_{i in P} c_i H_ij + [j in F] c_j.
        // H[n, n] = C_nn + sum_{i in P} c_i H[i, n].
        // The sums run over the displacement-prescribed DOFs in increasing order (listed first),
        // and the new rows are accumulated row by row of H (contiguous), not down its columns.
        let mut n_p = 0;
        for k in 0..d {
            if self.kind[k] == Condition::Displacement {
                self.p_list[n_p] = k;
                n_p += 1;
            }
        }
        for i in 0..d {
            let mut acc = [0.0; D];
            let row = &self.h[i * st..i * st + d];
            for &j in &self.p_list[..n_p] {
                let hij = row[j];
                for c in 0..D {
                    acc[c] += hij * self.tmp_c[j][c];
                }
            }
            let is_f = self.kind[i] == Condition::Force;
            for c in 0..D {
                let base = if is_f { self.tmp_c[i][c] } else { 0.0 };
                self.h[i * st + d + c] = base - acc[c];
            }
        }
        for c in 0..D {
            self.h[(d + c) * st..(d + c) * st + d].fill(0.0);
        }
        for &i in &self.p_list[..n_p] {
            let ci = self.tmp_c[i];
            let (above, below) = self.h.split_at_mut(d * st);
            let row_i = &above[i * st..i * st + d];
            for c in 0..D {
                let new_row = &mut below[c * st..c * st + d];
                for (acc, &hij) in new_row.iter_mut().zip(row_i) {
                    *acc += ci[c] * hij;
                }
            }
        }
        for j in 0..d {
            if self.kind[j] == Condition::Force {
                for c in 0..D {
                    self.h[(d + c) * st + j] += self.tmp_c[j][c];
                }
            }
        }
        for r in 0..D {
            for c in 0..D {
                let mut v = c_nn[r][c];
                for i in 0..d {
                    if self.kind[i] == Condition::Displacement {
                        v += self.tmp_c[i][r] * self.h[i * st + d + c];
                    }
                }
                self.h[(d + r) * st + d + c] = v;
            }
        }
        let slot = self.n_nodes;
        self.contact_of_slot[slot] = contact;
        self.angle_rad[slot] = angle_rad;
        self.frame[slot] = frame;
        self.c_self[slot] = c_nn_world;
        self.series[slot] = [[0.0; D]; D];
        for c in 0..D {
            self.kind[d + c] = Condition::Force;
            self.x[d + c] = 0.0;
        }
        self.n_nodes += 1;
        self.stats.n_added += 1;
        Ok(Slot::new(slot))
    }

    /// Removes `slot` from the working set (its force becomes zero). The last slot moves into
    /// its place. $O(d^2)$ per prescribed displacement on it, else $O(d)$.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], or [`MixedError::SingularPivot`] when a prescribed
    /// displacement cannot be released (not expected: that pivot is always positive).
    pub fn remove_slot(&mut self, slot: Slot) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        for axis in Axis::all::<D>() {
            let k = Self::dof(slot, axis);
            if self.kind[k] == Condition::Displacement {
                self.pivot(k)?;
            }
        }
        let last = self.n_nodes - 1;
        if slot.index() != last {
            self.swap_slots(slot.index(), last);
        }
        self.n_nodes -= 1;
        self.stats.n_removed += 1;
        Ok(())
    }

    fn swap_slots(&mut self, a: usize, b: usize) {
        let d = self.n_dofs();
        let st = self.stride;
        for c in 0..D {
            let (i, j) = (D * a + c, D * b + c);
            for col in 0..d {
                self.h.swap(i * st + col, j * st + col);
            }
            for row in 0..d {
                self.h.swap(row * st + i, row * st + j);
            }
            self.kind.swap(i, j);
            self.x.swap(i, j);
            self.y.swap(i, j);
        }
        self.contact_of_slot.swap(a, b);
        self.angle_rad.swap(a, b);
        self.frame.swap(a, b);
        self.c_self.swap(a, b);
        self.series.swap(a, b);
    }
}

impl MixedSolver<2> {
    /// Adds mesh node `node_idx` to the working set ([`MixedSolver::add_contact`] of the node).
    ///
    /// Errors: those of [`MixedSolver::add_contact`].
    pub fn add_node<C: ContactBlocks<2> + ?Sized>(&mut self, cache: &C, node_idx: NodeIdx, angle_rad: f64) -> Result<Slot, MixedError> {
        self.add_contact(cache, ContactPoint::node(node_idx), angle_rad)
    }

    /// Adds `contact` (a node or a material point) to the 2D working set with frame angle
    /// `angle_rad` ([`frame_of_angle`]) and both local DOFs force-prescribed at zero. Needs the
    /// columns of the contact's nodes in `cache`. $O(d^2)$.
    ///
    /// Errors: [`MixedError::Full`] when all `cap_nodes` slots are taken,
    /// [`MixedError::NonFinite`] for a non-finite angle, [`MixedError::AlreadyWorking`] when the
    /// node has a slot, [`MixedError::NotCached`] when its columns are missing; the state is then
    /// unchanged.
    pub fn add_contact<C: ContactBlocks<2> + ?Sized>(
        &mut self,
        cache: &C,
        contact: ContactPoint,
        angle_rad: f64,
    ) -> Result<Slot, MixedError> {
        if self.n_nodes == self.cap_nodes {
            return Err(MixedError::Full { cap_nodes: self.cap_nodes });
        }
        if !angle_rad.is_finite() {
            return Err(MixedError::NonFinite { what: "the frame angle", contact: contact.id() });
        }
        self.border(cache, contact, frame_of_angle(angle_rad), angle_rad)
    }
}
