//! The frame change of a slot: a congruence when its DOFs share a kind, the direct rank-two
//! update when they differ (in any dimension, and the 2D closed form of [`MixedSolver::set_angle`]).

use super::blocks::{check_frame, frame_of_angle, invert, mul, mul_t, mul2, orthonormalized, pivot_block, rot, to_local};
use super::{Block, Condition, MixedError, MixedSolver, PIVOT_TOL};
use crate::ids::{Axis, Slot};

impl<const D: usize> MixedSolver<D> {
    /// Turns the frame of `slot` to `frame` (rows $[t, n, (b)]$, a rotation; stored
    /// re-orthonormalised, see [`MixedSolver::frame`]). Prescribed values
    /// are kept as numbers in the new frame (the caller sets them anew). $O(d)$ when the slot's
    /// DOFs share a kind, one pass over $H$ with a rank-two change, $O(Dd^2)$, when they differ
    /// (formulas in the module doc). In 2D the stored angle becomes
    /// $\operatorname{atan2}(t_y, t_x)$.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], [`MixedError::NonFinite`] or
    /// [`MixedError::NotARotation`] for a frame that is not a finite rotation, and
    /// [`MixedError::SingularPivot`] when a new displacement-prescribed direction of a slot with
    /// mixed kinds is singular; the state is then unchanged.
    pub fn set_frame(&mut self, slot: Slot, frame: Block<D>) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        let s = slot.index();
        check_frame(&frame, self.contact_of_slot[s])?;
        let frame = orthonormalized(&frame);
        if frame == self.frame[s] {
            return Ok(());
        }
        // v_new = G v_old, G = F_new F_old^T.
        let g = mul_t(&frame, &self.frame[s]);
        let k0 = D * s;
        if (1..D).all(|c| self.kind[k0 + c] == self.kind[k0]) {
            self.congruence(slot, &g);
        } else {
            self.rotate_mixed_general(slot, &g, &frame)?;
        }
        self.frame[s] = frame;
        if D == 2 {
            self.angle_rad[s] = frame[0][1].atan2(frame[0][0]);
        }
        self.stats.n_rotations += 1;
        Ok(())
    }

    /// $H' = \hat G H \hat G^\top$ with $G$ on `slot` (its DOFs share a kind). $O(d)$.
    pub(super) fn congruence(&mut self, slot: Slot, g: &Block<D>) {
        let d = self.n_dofs();
        let st = self.stride;
        let k0 = D * slot.index();
        for j in 0..d {
            let a: [f64; D] = std::array::from_fn(|e| self.h[(k0 + e) * st + j]);
            for c in 0..D {
                let mut acc = g[c][0] * a[0];
                for e in 1..D {
                    acc += g[c][e] * a[e];
                }
                self.h[(k0 + c) * st + j] = acc;
            }
        }
        for i in 0..d {
            let a: [f64; D] = std::array::from_fn(|e| self.h[i * st + k0 + e]);
            for c in 0..D {
                let mut acc = a[0] * g[c][0];
                for e in 1..D {
                    acc += a[e] * g[c][e];
                }
                self.h[i * st + k0 + c] = acc;
            }
        }
    }

    /// The direct update of a frame change of a slot with mixed kinds, in any dimension
    /// (formulas in the module doc): checks the new prescribed directions first and leaves
    /// everything unchanged when one is not safely positive, then updates $H$ in one pass. Does
    /// not touch the frame or stats.
    fn rotate_mixed_general(&mut self, slot: Slot, g: &Block<D>, new_frame: &Block<D>) -> Result<(), MixedError> {
        let s = slot.index();
        let k0 = D * s;
        let d = self.n_dofs();
        let st = self.stride;
        let is_p: [bool; D] = std::array::from_fn(|c| self.kind[k0 + c] == Condition::Displacement);
        let hss: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| self.h[(k0 + i) * st + k0 + j]));
        // The check: S = the pivot of H_ss on p (the slot's condensed compliance), S' = G S G^T,
        // then the successive pivots of S'_pp, each against that DOF's own compliance in the new
        // frame, as `pivot` checks a force-to-displacement switch.
        let mut sc = hss;
        for c in 0..D {
            if is_p[c] {
                if !(sc[c][c] > 0.0 && sc[c][c].is_finite()) {
                    return Err(MixedError::SingularPivot {
                        contact: self.contact_of_slot[s].id(),
                        axis: Axis::of_component(c),
                        pivot: sc[c][c],
                    });
                }
                sc = pivot_block(&sc, c);
            }
        }
        let mut sn = mul_t(&mul(g, &sc), g);
        let c_new = to_local(&self.c_self[s], new_frame, new_frame);
        for c in 0..D {
            if is_p[c] {
                let p = sn[c][c];
                if !(p > PIVOT_TOL * c_new[c][c] && p.is_finite()) {
                    return Err(MixedError::SingularPivot { contact: self.contact_of_slot[s].id(), axis: Axis::of_component(c), pivot: p });
                }
                sn = pivot_block(&sn, c);
            }
        }
        // A = G on same-kind pairs, B = G on mixed pairs.
        let a: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| if is_p[i] == is_p[j] { g[i][j] } else { 0.0 }));
        let b: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| if is_p[i] != is_p[j] { g[i][j] } else { 0.0 }));
        let bh = mul(&b, &hss);
        let ah = mul(&a, &hss);
        let w: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j] + bh[i][j]));
        let v: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| b[i][j] + ah[i][j]));
        // W maps x_s to x'_s, whose entries are displacements (p) and forces (q): invert it in
        // units where both are of order one (the slot's isotropic compliance scale sigma, so that
        // partial pivoting compares like with like): W~ = S W S^-1, W^-1 = S^-1 W~^-1 S.
        let sigma = ((0..D).map(|c| self.c_self[s][c][c]).sum::<f64>() / D as f64).sqrt();
        let sc_of = |c: usize| if is_p[c] { 1.0 / sigma } else { sigma };
        let w_scaled: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| sc_of(i) * w[i][j] / sc_of(j)));
        let Some(wi) =
            invert(&w_scaled).map(|m| -> Block<D> { std::array::from_fn(|i| std::array::from_fn(|j| m[i][j] * sc_of(j) / sc_of(i))) })
        else {
            let c = (0..D).find(|&c| is_p[c]).unwrap_or(0);
            return Err(MixedError::SingularPivot { contact: self.contact_of_slot[s].id(), axis: Axis::of_component(c), pivot: 0.0 });
        };
        let hss_new = mul(&v, &wi);
        let hb = mul(&hss_new, &b);
        let l: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j] - hb[i][j]));
        // The slot's old rows (H_sr), read by every other row's update.
        for c in 0..D {
            self.tmp_rows[c * st..c * st + d].copy_from_slice(&self.h[(k0 + c) * st..(k0 + c) * st + d]);
        }
        // The rank-two form of z B H_sr: with D <= 3 one kind has a single component k (the
        // other components o), and B links k only with o, so
        // z B H_sr = (sum_{e in o} z_e G_ek) H_k + z_k (sum_{c in o} G_kc H_c):
        // two streams, H_k in tmp_col and the combination in tmp_row.
        let n_p = is_p.iter().filter(|&&v| v).count();
        let lone = (0..D).find(|&c| is_p[c] == (n_p == 1)).expect("a slot of mixed kinds has a lone kind");
        self.tmp_col[..d].copy_from_slice(&self.tmp_rows[lone * st..lone * st + d]);
        self.tmp_row[..d].fill(0.0);
        for c in 0..D {
            if c != lone {
                let gkc = g[lone][c];
                for (t, &r) in self.tmp_row[..d].iter_mut().zip(&self.tmp_rows[c * st..c * st + d]) {
                    *t += gkc * r;
                }
            }
        }
        for i in 0..d {
            if i >= k0 && i < k0 + D {
                continue;
            }
            let row = &mut self.h[i * st..i * st + d];
            let hrs: [f64; D] = std::array::from_fn(|e| row[k0 + e]);
            // z = H_is W^-1 (the new H'_is); H'_ir = H_ir - z B H_sr.
            let z: [f64; D] = std::array::from_fn(|c| (0..D).map(|e| hrs[e] * wi[e][c]).sum());
            let g_lone: f64 = (0..D).filter(|&e| e != lone).map(|e| z[e] * g[e][lone]).sum();
            let z_lone = z[lone];
            if g_lone != 0.0 || z_lone != 0.0 {
                for ((hij, &r_lone), &r_comb) in row.iter_mut().zip(&self.tmp_col[..d]).zip(&self.tmp_row[..d]) {
                    *hij -= g_lone * r_lone + z_lone * r_comb;
                }
            }
            row[k0..k0 + D].copy_from_slice(&z);
        }
        for c in 0..D {
            for j in 0..d {
                let mut acc = 0.0;
                for e in 0..D {
                    acc += l[c][e] * self.tmp_rows[e * st + j];
                }
                self.h[(k0 + c) * st + j] = acc;
            }
        }
        for i in 0..D {
            for j in 0..D {
                self.h[(k0 + i) * st + k0 + j] = hss_new[i][j];
            }
        }
        Ok(())
    }
}

impl MixedSolver<2> {
    /// The frame angle of a slot (2D).
    pub fn angle_rad(&self, slot: Slot) -> f64 {
        self.angle_rad[slot.index()]
    }

    /// Rotates the 2D frame of `slot` to `angle_rad`: [`MixedSolver::set_frame`] with the frame
    /// of the angle, computed from the turn $\delta$ itself. Prescribed values are kept as numbers
    /// in the new frame (the caller sets them anew). $O(d)$ when the slot's two DOFs share a
    /// kind, one rank-two pass over $H$, $O(d^2)$, when they differ.
    ///
    /// With $c = \cos\delta$, $s = \sin\delta$ for the turn $\delta$, the slot's local vectors
    /// turn as $v' = Q v$, $Q = R(-\delta) = cI + sJ$. *Same kinds:* $H' = G H G^\top$ with
    /// $G = Q$ on the slot, $O(d)$. *Mixed kinds:* the module doc's update with $\mathcal A = cI$,
    /// $\mathcal B = sJ$ (either order of kinds gives this form), $W = cI + sJH_{ss}$,
    /// $V = sJ + cH_{ss}$:
    /// $$H'_{ss} = VW^{-1},\quad H'_{sr} = (cI - s\,VW^{-1}J)\,H_{sr},\quad
    /// H'_{rs} = H_{rs}W^{-1},\quad H'_{rr} = H_{rr} - H_{rs}\,(s\,W^{-1}J)\,H_{sr}.$$
    /// $\det W = p'\,H_{kk}$, with $k$ the slot's displacement-prescribed DOF and $p'$ the
    /// condensed compliance along the new prescribed direction — the pivot the round trip's
    /// second pivot would take — and $p'$ is checked as [`MixedSolver::set_condition`] checks it.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], [`MixedError::NonFinite`] for a non-finite angle, and
    /// [`MixedError::SingularPivot`] when the new displacement-prescribed direction of a slot
    /// with mixed kinds is singular ($p'$ not safely positive); the state is then unchanged.
    pub fn set_angle(&mut self, slot: Slot, angle_rad: f64) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        if !angle_rad.is_finite() {
            return Err(MixedError::NonFinite { what: "the frame angle", contact: self.contact_of_slot[slot.index()].id() });
        }
        let delta = angle_rad - self.angle_rad[slot.index()];
        if delta == 0.0 {
            return Ok(());
        }
        let (k0, k1) = (slot.dof(Axis::Axial), slot.dof(Axis::Lateral));
        if self.kind[k0] != self.kind[k1] {
            self.rotate_mixed(slot, angle_rad, delta)?;
        } else {
            // v_new = Q v_old with Q = R(new)^T R(old) = R(-delta); H' = G H G^T.
            let q = rot(-delta);
            self.congruence(slot, &q);
        }
        self.angle_rad[slot.index()] = angle_rad;
        self.frame[slot.index()] = frame_of_angle(angle_rad);
        self.stats.n_rotations += 1;
        Ok(())
    }

    /// The 2D closed form of the mixed-kind frame change of [`MixedSolver::set_angle`] (formulas
    /// there): checks the new pivot first and leaves everything unchanged when it is not safely
    /// positive, then updates $H$ in one pass. Does not touch the angle or stats.
    fn rotate_mixed(&mut self, slot: Slot, angle_rad: f64, delta: f64) -> Result<(), MixedError> {
        let (k0, k1) = (slot.dof(Axis::Axial), slot.dof(Axis::Lateral));
        let d = self.n_dofs();
        let st = self.stride;
        let (s, c) = delta.sin_cos();
        let hs = [[self.h[k0 * st + k0], self.h[k0 * st + k1]], [self.h[k1 * st + k0], self.h[k1 * st + k1]]];
        // W = cI + sJ H_ss, J H = [[h10, h11], [-h00, -h01]].
        let w = [[c + s * hs[1][0], s * hs[1][1]], [-s * hs[0][0], c - s * hs[0][1]]];
        let det = w[0][0] * w[1][1] - w[0][1] * w[1][0];
        // The new pivot p' = det W / H_kk on the displacement-prescribed DOF k, checked against
        // that DOF's own compliance in the new frame, as `pivot` checks a force-to-displacement
        // switch.
        let kp = if self.kind[k0] == Condition::Displacement { k0 } else { k1 };
        let p_new = det / self.h[kp * st + kp];
        let f_new = frame_of_angle(angle_rad);
        let c_new = to_local(&self.c_self[slot.index()], &f_new, &f_new)[kp % 2][kp % 2];
        if !(p_new > PIVOT_TOL * c_new && p_new.is_finite()) {
            return Err(MixedError::SingularPivot {
                contact: self.contact_of_slot[slot.index()].id(),
                axis: Axis::of_index(kp),
                pivot: p_new,
            });
        }
        let wi = [[w[1][1] / det, -w[0][1] / det], [-w[1][0] / det, w[0][0] / det]];
        // V = sJ + c H_ss; H'_ss = V W^-1.
        let v = [[c * hs[0][0], s + c * hs[0][1]], [-s + c * hs[1][0], c * hs[1][1]]];
        let hss = mul2(v, wi);
        // (A J) = [[-a01, a00], [-a11, a10]].
        let times_j = |a: [[f64; 2]; 2]| [[-a[0][1], a[0][0]], [-a[1][1], a[1][0]]];
        // M = s W^-1 J (the rank-two term's core); L = cI - s V W^-1 J (the slot's rows).
        let wj = times_j(wi);
        let m = [[s * wj[0][0], s * wj[0][1]], [s * wj[1][0], s * wj[1][1]]];
        let hj = times_j(hss);
        let l = [[c - s * hj[0][0], -s * hj[0][1]], [-s * hj[1][0], c - s * hj[1][1]]];
        // The slot's old rows (H_sr), read by every other row's update.
        self.tmp_row[..d].copy_from_slice(&self.h[k0 * st..k0 * st + d]);
        self.tmp_col[..d].copy_from_slice(&self.h[k1 * st..k1 * st + d]);
        for i in 0..d {
            if i == k0 || i == k1 {
                continue;
            }
            let row = &mut self.h[i * st..i * st + d];
            let a = [row[k0], row[k1]];
            // H'_rr = H_rr - (a M) H_sr; H'_rs = a W^-1.
            let g0 = a[0] * m[0][0] + a[1] * m[1][0];
            let g1 = a[0] * m[0][1] + a[1] * m[1][1];
            if g0 != 0.0 || g1 != 0.0 {
                for ((hij, &r0), &r1) in row.iter_mut().zip(&self.tmp_row[..d]).zip(&self.tmp_col[..d]) {
                    *hij -= g0 * r0 + g1 * r1;
                }
            }
            row[k0] = a[0] * wi[0][0] + a[1] * wi[1][0];
            row[k1] = a[0] * wi[0][1] + a[1] * wi[1][1];
        }
        for j in 0..d {
            let (r0, r1) = (self.tmp_row[j], self.tmp_col[j]);
            self.h[k0 * st + j] = l[0][0] * r0 + l[0][1] * r1;
            self.h[k1 * st + j] = l[1][0] * r0 + l[1][1] * r1;
        }
        self.h[k0 * st + k0] = hss[0][0];
        self.h[k0 * st + k1] = hss[0][1];
        self.h[k1 * st + k0] = hss[1][0];
        self.h[k1 * st + k1] = hss[1][1];
        Ok(())
    }
}
