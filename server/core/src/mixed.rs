//! The condensed mixed boundary-condition solve on the working set (the paper's eq. 2–3 and
//! sections 4.1–4.2), with O(d²) updates.
//!
//! Each working node $i$ has a frame angle $\theta_i$; its local DOFs are
//! $(u_t, u_n) = R(\theta_i)^\top u$ with $R(\theta) = [t\ n]$, $t = (\cos\theta, \sin\theta)$.
//! The local compliance is $C_L = A^\top C_{\mathcal{WW}} A$, $A = \mathrm{diag}(R(\theta_i))$.
//! Every local DOF has either a prescribed displacement (set $P$) or a prescribed force (set $F$).
//! The solver keeps the *hybrid matrix* $H$ (a principal pivot transform of $C_L$) that maps the
//! prescribed values $x = (u_P, f_F)$ to the unknowns $y = (f_P, u_F)$:
//! $$H = \begin{bmatrix} C_{PP}^{-1} & -C_{PP}^{-1}C_{PF} \\ C_{FP}C_{PP}^{-1} & C_{FF} - C_{FP}C_{PP}^{-1}C_{PF}\end{bmatrix}.$$
//! Switching DOF $k$ between $P$ and $F$ exchanges $x_k$ and $y_k$: with pivot $p = H_{kk} > 0$,
//! $H'_{kk} = 1/p$, $H'_{kj} = -H_{kj}/p$, $H'_{ik} = H_{ik}/p$, $H'_{ij} = H_{ij} - H_{ik}H_{kj}/p$,
//! a rank-one update of cost $O(d^2)$ (the paper's eq. 3). A frame change by $\delta$ at a node whose
//! two DOFs share a kind is $H' = G H G^\top$ with $G$ the rotation $R(-\delta)$ at that node, $O(d)$;
//! for a node with mixed kinds it is one rank-two pass over $H$, $O(d^2)$ ([`MixedSolver::set_angle`]).
//! Adding a node borders $H$ in $O(d^2)$; removing one pivots it to $F$ (zero force) and drops it.
//! Nothing here allocates after [`MixedSolver::with_capacity`].

use crate::compliance::ComplianceCache;
use crate::contact::ContactPoint;
use crate::ids::{Axis, NodeIdx, Slot};

/// What is prescribed on one local DOF.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Condition {
    /// A displacement is prescribed; the force is unknown.
    Displacement,
    /// A force is prescribed; the displacement is unknown.
    Force,
}

/// Errors of the mixed solver.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MixedError {
    /// The working set is full.
    #[error("the working set is full ({cap_nodes} nodes)")]
    Full { cap_nodes: usize },
    /// The node is already in the working set.
    #[error("node {node_idx} is already a working node")]
    AlreadyWorking { node_idx: NodeIdx },
    /// The compliance columns of a contact's node(s) are not cached.
    #[error("the compliance columns of {contact} are not cached")]
    NotCached { contact: ContactPoint },
    /// The slot does not exist.
    #[error("working slot {slot} does not exist ({n_nodes} working nodes)")]
    NoSuchSlot { slot: Slot, n_nodes: usize },
    /// Prescribing this displacement would make the system singular (the DOF is already
    /// determined by other prescribed displacements, or it has no compliance, e.g. a fixed node).
    #[error("prescribing the {axis} displacement of {contact} makes the working system singular (pivot {pivot:e})")]
    SingularPivot { contact: ContactPoint, axis: Axis, pivot: f64 },
    /// A value or angle is not finite.
    #[error("{what} of working contact {contact} is not finite")]
    NonFinite { what: &'static str, contact: ContactPoint },
}

/// Counters of the updates performed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MixedStats {
    pub n_pivots: u64,
    pub n_rotations: u64,
    pub n_added: u64,
    pub n_removed: u64,
    pub n_rebuilds: u64,
}

/// The condensed mixed solver on a working set of at most `cap_nodes` nodes.
#[derive(Debug, Clone)]
pub struct MixedSolver {
    cap_nodes: usize,
    stride: usize,
    n_nodes: usize,
    contact_of_slot: Vec<ContactPoint>,
    angle_rad: Vec<f64>,
    /// World self-compliance block of each slot, to know each DOF's own compliance.
    c_self: Vec<[[f64; 2]; 2]>,
    kind: Vec<Condition>,
    x: Vec<f64>,
    y: Vec<f64>,
    h: Vec<f64>,
    tmp_row: Vec<f64>,
    tmp_col: Vec<f64>,
    tmp_c: Vec<[f64; 2]>,
    stats: MixedStats,
}

/// Relative size below which a pivot is treated as zero: $p \le \epsilon\, C_{kk}$.
const PIVOT_TOL: f64 = 1e-12;

fn rot(angle_rad: f64) -> [[f64; 2]; 2] {
    let (s, c) = angle_rad.sin_cos();
    [[c, -s], [s, c]]
}

/// $R_a^\top M R_b$ for 2 × 2 blocks.
fn to_local(m: [[f64; 2]; 2], a: f64, b: f64) -> [[f64; 2]; 2] {
    let ra = rot(a);
    let rb = rot(b);
    let mut mb = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            mb[i][j] = m[i][0] * rb[0][j] + m[i][1] * rb[1][j];
        }
    }
    let mut out = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            out[i][j] = ra[0][i] * mb[0][j] + ra[1][i] * mb[1][j];
        }
    }
    out
}

/// The product of two 2 × 2 blocks.
fn mul2(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j]))
}

impl MixedSolver {
    /// An empty solver with room for `cap_nodes` working nodes (all storage allocated here).
    pub fn with_capacity(cap_nodes: usize) -> Self {
        let stride = 2 * cap_nodes;
        Self {
            cap_nodes,
            stride,
            n_nodes: 0,
            contact_of_slot: vec![ContactPoint::node(NodeIdx(0)); cap_nodes],
            angle_rad: vec![0.0; cap_nodes],
            c_self: vec![[[0.0; 2]; 2]; cap_nodes],
            kind: vec![Condition::Force; stride],
            x: vec![0.0; stride],
            y: vec![0.0; stride],
            h: vec![0.0; stride * stride],
            tmp_row: vec![0.0; stride],
            tmp_col: vec![0.0; stride],
            tmp_c: vec![[0.0; 2]; stride],
            stats: MixedStats::default(),
        }
    }

    /// Makes this solver a copy of `other` without allocating (capacities must be equal).
    /// Panics only on a programming error (different capacities).
    pub fn copy_from(&mut self, other: &MixedSolver) {
        assert_eq!(self.cap_nodes, other.cap_nodes, "copy_from needs equal capacities");
        self.n_nodes = other.n_nodes;
        self.contact_of_slot.copy_from_slice(&other.contact_of_slot);
        self.angle_rad.copy_from_slice(&other.angle_rad);
        self.c_self.copy_from_slice(&other.c_self);
        self.kind.copy_from_slice(&other.kind);
        self.x.copy_from_slice(&other.x);
        self.y.copy_from_slice(&other.y);
        let d = other.n_dofs();
        for i in 0..d {
            let r = i * self.stride;
            self.h[r..r + d].copy_from_slice(&other.h[r..r + d]);
        }
        self.stats = other.stats;
    }

    /// Working nodes.
    pub fn n_nodes(&self) -> usize {
        self.n_nodes
    }
    /// Number of working DOFs $d = 2m$.
    pub fn n_dofs(&self) -> usize {
        2 * self.n_nodes
    }
    /// Capacity in nodes.
    pub fn cap_nodes(&self) -> usize {
        self.cap_nodes
    }
    /// Update counters.
    pub fn stats(&self) -> MixedStats {
        self.stats
    }
    /// The contact of each slot (a mesh node or a material point).
    pub fn contacts(&self) -> &[ContactPoint] {
        &self.contact_of_slot[..self.n_nodes]
    }
    /// The slot of a mesh node working as a node contact, if it is one. $O(m)$.
    pub fn slot_of(&self, node_idx: NodeIdx) -> Option<Slot> {
        self.contacts().iter().position(|c| c.as_node() == Some(node_idx)).map(Slot::new)
    }
    /// The frame angle of a slot.
    pub fn angle_rad(&self, slot: Slot) -> f64 {
        self.angle_rad[slot.index()]
    }
    /// The condition kind of a slot's local component along `axis`.
    pub fn condition(&self, slot: Slot, axis: Axis) -> Condition {
        self.kind[slot.dof(axis)]
    }
    /// The hybrid matrix entry $H_{ij}$ between local DOFs $i$, $j$ ([`Slot::dof`]).
    /// For the flexible needle's coupling, tests and diagnostics.
    pub fn hybrid(&self, i: usize, j: usize) -> f64 {
        self.h[i * self.stride + j]
    }

    fn check_slot(&self, slot: Slot) -> Result<(), MixedError> {
        if slot.index() >= self.n_nodes { Err(MixedError::NoSuchSlot { slot, n_nodes: self.n_nodes }) } else { Ok(()) }
    }

    /// The local compliance of DOF `k` (its own, before any condensation).
    fn c_local_diag(&self, k: usize) -> f64 {
        let s = k / 2;
        let a = self.angle_rad[s];
        to_local(self.c_self[s], a, a)[k % 2][k % 2]
    }

    /// Adds mesh node `node_idx` to the working set ([`MixedSolver::add_contact`] of the node).
    ///
    /// Errors: those of [`MixedSolver::add_contact`].
    pub fn add_node(&mut self, cache: &ComplianceCache, node_idx: NodeIdx, angle_rad: f64) -> Result<Slot, MixedError> {
        self.add_contact(cache, ContactPoint::node(node_idx), angle_rad)
    }

    /// Adds `contact` (a node or a material point) to the working set with frame angle
    /// `angle_rad` and both local DOFs force-prescribed at zero. Needs the columns of the
    /// contact's nodes in `cache`. $O(d^2)$.
    ///
    /// Errors: [`MixedError::Full`] when all `cap_nodes` slots are taken,
    /// [`MixedError::NonFinite`] for a non-finite angle, [`MixedError::AlreadyWorking`] when the
    /// node has a slot, [`MixedError::NotCached`] when its columns are missing; the state is then
    /// unchanged.
    pub fn add_contact(&mut self, cache: &ComplianceCache, contact: ContactPoint, angle_rad: f64) -> Result<Slot, MixedError> {
        if self.n_nodes == self.cap_nodes {
            return Err(MixedError::Full { cap_nodes: self.cap_nodes });
        }
        if !angle_rad.is_finite() {
            return Err(MixedError::NonFinite { what: "the frame angle", contact });
        }
        if let Some(node_idx) = contact.as_node()
            && self.slot_of(node_idx).is_some()
        {
            return Err(MixedError::AlreadyWorking { node_idx });
        }
        let c_nn_world = cache.contact_block(&contact, &contact).ok_or(MixedError::NotCached { contact })?;
        let d = self.n_dofs();
        let st = self.stride;
        // c: local compliance between existing DOFs and the two new ones.
        for s in 0..self.n_nodes {
            let b = cache.contact_block(&self.contact_of_slot[s], &contact).ok_or(MixedError::NotCached { contact })?;
            let l = to_local(b, self.angle_rad[s], angle_rad);
            self.tmp_c[2 * s] = l[0];
            self.tmp_c[2 * s + 1] = l[1];
        }
        let c_nn = to_local(c_nn_world, angle_rad, angle_rad);
        // New columns: H[i, n] = [i in F] c_i - sum_{j in P} H_ij c_j.
        // New rows:    H[n, j] = sum_{i in P} c_i H_ij + [j in F] c_j.
        // H[n, n] = C_nn + sum_{i in P} c_i H[i, n].
        let (n0, n1) = (d, d + 1);
        for i in 0..d {
            let mut acc = [0.0; 2];
            for j in 0..d {
                if self.kind[j] == Condition::Displacement {
                    let hij = self.h[i * st + j];
                    acc[0] += hij * self.tmp_c[j][0];
                    acc[1] += hij * self.tmp_c[j][1];
                }
            }
            let is_f = self.kind[i] == Condition::Force;
            for c in 0..2 {
                let base = if is_f { self.tmp_c[i][c] } else { 0.0 };
                self.h[i * st + d + c] = base - acc[c];
            }
        }
        for j in 0..d {
            let mut acc = [0.0; 2];
            for i in 0..d {
                if self.kind[i] == Condition::Displacement {
                    let hij = self.h[i * st + j];
                    acc[0] += self.tmp_c[i][0] * hij;
                    acc[1] += self.tmp_c[i][1] * hij;
                }
            }
            let is_f = self.kind[j] == Condition::Force;
            for c in 0..2 {
                let base = if is_f { self.tmp_c[j][c] } else { 0.0 };
                self.h[(d + c) * st + j] = acc[c] + base;
            }
        }
        for r in 0..2 {
            for c in 0..2 {
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
        self.c_self[slot] = c_nn_world;
        self.kind[n0] = Condition::Force;
        self.kind[n1] = Condition::Force;
        self.x[n0] = 0.0;
        self.x[n1] = 0.0;
        self.n_nodes += 1;
        self.stats.n_added += 1;
        Ok(Slot::new(slot))
    }

    /// Exchanges $x_k$ and $y_k$ (the principal pivot on $k$). Leaves the state unchanged and
    /// errors when the pivot is not safely positive.
    fn pivot(&mut self, k: usize) -> Result<(), MixedError> {
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
            return Err(MixedError::SingularPivot { contact: self.contact_of_slot[k / 2], axis: Axis::of_index(k), pivot: p });
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
    /// displacement, N for a force, in the node's frame). $O(d^2)$ when the kind changes, $O(1)$
    /// otherwise.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], [`MixedError::NonFinite`] for a non-finite value, and
    /// [`MixedError::SingularPivot`] when the kind change would make the system singular (the
    /// state is then unchanged).
    pub fn set_condition(&mut self, slot: Slot, axis: Axis, cond: Condition, value: f64) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        if !value.is_finite() {
            return Err(MixedError::NonFinite { what: "a prescribed value", contact: self.contact_of_slot[slot.index()] });
        }
        let k = slot.dof(axis);
        if self.kind[k] != cond {
            self.pivot(k)?;
        }
        self.x[k] = value;
        Ok(())
    }

    /// The prescribed value of a local DOF (a displacement or a force, by its kind).
    pub fn prescribed_value(&self, slot: Slot, axis: Axis) -> f64 {
        self.x[slot.dof(axis)]
    }

    /// Sets only the prescribed value of a local DOF, keeping its kind. $O(1)$.
    pub fn set_value(&mut self, slot: Slot, axis: Axis, value: f64) {
        self.x[slot.dof(axis)] = value;
    }

    /// Rotates the frame of `slot` to `angle_rad`. Prescribed values are kept as numbers in the
    /// new frame (the caller sets them anew). $O(d)$ when the slot's two DOFs share a kind, one
    /// rank-two pass over $H$, $O(d^2)$, when they differ.
    ///
    /// With $c = \cos\delta$, $s = \sin\delta$ for the turn $\delta$ and
    /// $J = \begin{bmatrix} 0 & 1 \\ -1 & 0 \end{bmatrix}$, the slot's local vectors turn as
    /// $v' = Q v$, $Q = R(-\delta) = cI + sJ$. Split the DOFs into the slot's two, $s$, and the
    /// rest, $r$.
    ///
    /// *Same kinds:* $x_s' = Q x_s$ and $y_s' = Q y_s$, so $H' = G H G^\top$ with $G = Q$ on the
    /// slot: rows and columns $s$ only, $O(d)$.
    ///
    /// *Mixed kinds* (one displacement, one force prescribed: a slipping contact): the pairs
    /// $x_s = (x_a, x_l)$, $y_s = (y_a, y_l)$ mix across the kinds. Componentwise from
    /// $u' = Qu$, $f' = Qf$ (either order of kinds gives the same form):
    /// $$x_s' = c\,x_s + sJ\,y_s, \qquad y_s' = sJ\,x_s + c\,y_s.$$
    /// Substituting $y_s = H_{ss}x_s + H_{sr}x_r$ and solving for $x_s$ with
    /// $W = cI + sJH_{ss}$ and $V = sJ + cH_{ss}$:
    /// $$H'_{ss} = VW^{-1},\quad H'_{sr} = (cI - s\,VW^{-1}J)\,H_{sr},\quad
    /// H'_{rs} = H_{rs}W^{-1},\quad H'_{rr} = H_{rr} - H_{rs}\,(s\,W^{-1}J)\,H_{sr}.$$
    /// The rest changes by a rank-two term (the prescribed direction itself turns, so the
    /// condensation of every other DOF changes; generically of rank two, so no exact update can
    /// touch fewer than $d^2$ entries). This is the composition of the pivot to uniform kinds,
    /// the congruence and the pivot back, done in one pass over $H$ instead of two.
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
            return Err(MixedError::NonFinite { what: "the frame angle", contact: self.contact_of_slot[slot.index()] });
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
            let d = self.n_dofs();
            let st = self.stride;
            for j in 0..d {
                let (a, b) = (self.h[k0 * st + j], self.h[k1 * st + j]);
                self.h[k0 * st + j] = q[0][0] * a + q[0][1] * b;
                self.h[k1 * st + j] = q[1][0] * a + q[1][1] * b;
            }
            for i in 0..d {
                let (a, b) = (self.h[i * st + k0], self.h[i * st + k1]);
                self.h[i * st + k0] = a * q[0][0] + b * q[0][1];
                self.h[i * st + k1] = a * q[1][0] + b * q[1][1];
            }
        }
        self.angle_rad[slot.index()] = angle_rad;
        self.stats.n_rotations += 1;
        Ok(())
    }

    /// The direct update of [`MixedSolver::set_angle`] for a slot whose two DOFs have different
    /// kinds (formulas there): checks the new pivot first and leaves everything unchanged when it
    /// is not safely positive, then updates $H$ in one pass. Does not touch the angle or stats.
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
        let old_angle = self.angle_rad[slot.index()];
        self.angle_rad[slot.index()] = angle_rad;
        let c_new = self.c_local_diag(kp);
        self.angle_rad[slot.index()] = old_angle;
        if !(p_new > PIVOT_TOL * c_new && p_new.is_finite()) {
            return Err(MixedError::SingularPivot { contact: self.contact_of_slot[slot.index()], axis: Axis::of_index(kp), pivot: p_new });
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

    /// Removes `slot` from the working set (its force becomes zero). The last slot moves into
    /// its place. $O(d^2)$ when a displacement was prescribed on it, else $O(d)$.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], or [`MixedError::SingularPivot`] when a prescribed
    /// displacement cannot be released (not expected: that pivot is always positive).
    pub fn remove_slot(&mut self, slot: Slot) -> Result<(), MixedError> {
        self.check_slot(slot)?;
        for axis in Axis::BOTH {
            let k = slot.dof(axis);
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
        for c in 0..2 {
            let (i, j) = (2 * a + c, 2 * b + c);
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
        self.c_self.swap(a, b);
    }

    /// Computes the unknowns $y = H x$. $O(d^2)$, no allocation.
    pub fn solve(&mut self) {
        let d = self.n_dofs();
        let st = self.stride;
        for i in 0..d {
            self.y[i] = dot(&self.h[i * st..i * st + d], &self.x[..d]);
        }
    }

    /// Local displacement $(u_t, u_n)$ of `slot` after [`MixedSolver::solve`].
    pub fn displacement_local(&self, slot: Slot) -> [f64; 2] {
        std::array::from_fn(|c| {
            let k = 2 * slot.index() + c;
            if self.kind[k] == Condition::Displacement { self.x[k] } else { self.y[k] }
        })
    }
    /// Local force $(f_t, f_n)$ on `slot` after [`MixedSolver::solve`].
    pub fn force_local(&self, slot: Slot) -> [f64; 2] {
        std::array::from_fn(|c| {
            let k = 2 * slot.index() + c;
            if self.kind[k] == Condition::Force { self.x[k] } else { self.y[k] }
        })
    }
    /// World displacement of `slot`.
    pub fn displacement_world(&self, slot: Slot) -> [f64; 2] {
        local_to_world(self.displacement_local(slot), self.angle_rad[slot.index()])
    }
    /// World force on `slot` (the force the needle applies to the tissue node).
    pub fn force_world(&self, slot: Slot) -> [f64; 2] {
        local_to_world(self.force_local(slot), self.angle_rad[slot.index()])
    }

    /// Rebuilds $H$ from $C_{\mathcal{WW}}$ from scratch with a dense factorisation: the reference
    /// for the $O(d^2)$ updates, $O(d^3)$ and allocating, never called inside a real-time step.
    pub fn rebuild(&mut self, cache: &ComplianceCache) -> Result<(), MixedError> {
        let h = self.hybrid_from_scratch(cache)?;
        let d = self.n_dofs();
        for i in 0..d {
            for j in 0..d {
                self.h[i * self.stride + j] = h[(i, j)];
            }
        }
        self.stats.n_rebuilds += 1;
        Ok(())
    }

    /// The hybrid matrix for the current nodes, frames and kinds, computed from scratch.
    pub fn hybrid_from_scratch(&self, cache: &ComplianceCache) -> Result<faer::Mat<f64>, MixedError> {
        let d = self.n_dofs();
        let mut cl = faer::Mat::<f64>::zeros(d, d);
        for a in 0..self.n_nodes {
            for b in 0..self.n_nodes {
                let (ca, cb) = (&self.contact_of_slot[a], &self.contact_of_slot[b]);
                let blk = cache.contact_block(ca, cb).ok_or(MixedError::NotCached { contact: *cb })?;
                let l = to_local(blk, self.angle_rad[a], self.angle_rad[b]);
                for i in 0..2 {
                    for j in 0..2 {
                        cl[(2 * a + i, 2 * b + j)] = l[i][j];
                    }
                }
            }
        }
        let sym = cl.transpose().to_owned();
        let cl = (&cl + &sym) * faer::Scale(0.5);
        let p: Vec<usize> = (0..d).filter(|&k| self.kind[k] == Condition::Displacement).collect();
        let f: Vec<usize> = (0..d).filter(|&k| self.kind[k] == Condition::Force).collect();
        let cpp = faer::Mat::from_fn(p.len(), p.len(), |i, j| cl[(p[i], p[j])]);
        let cpf = faer::Mat::from_fn(p.len(), f.len(), |i, j| cl[(p[i], f[j])]);
        let mut h = faer::Mat::<f64>::zeros(d, d);
        let (hpp, hpf) = if p.is_empty() {
            (faer::Mat::zeros(0, 0), faer::Mat::zeros(0, f.len()))
        } else {
            let llt = cpp.llt(faer::Side::Lower).map_err(|_| {
                let k = p[0];
                MixedError::SingularPivot { contact: self.contact_of_slot[k / 2], axis: Axis::of_index(k), pivot: 0.0 }
            })?;
            let inv = faer::linalg::solvers::DenseSolveCore::inverse(&llt);
            let hpf = -(&inv * &cpf);
            (inv, hpf)
        };
        for (i, &pi) in p.iter().enumerate() {
            for (j, &pj) in p.iter().enumerate() {
                h[(pi, pj)] = hpp[(i, j)];
            }
            for (j, &fj) in f.iter().enumerate() {
                h[(pi, fj)] = hpf[(i, j)];
                // H_FP = C_FP C_PP^-1 = -H_PF^T.
                h[(fj, pi)] = -hpf[(i, j)];
            }
        }
        for (i, &fi) in f.iter().enumerate() {
            for (j, &fj) in f.iter().enumerate() {
                // C_FF - C_FP C_PP^-1 C_PF = C_FF + C_FP H_PF.
                let mut v = cl[(fi, fj)];
                for (k, &pk) in p.iter().enumerate() {
                    v += cl[(fi, pk)] * hpf[(k, j)];
                }
                h[(fi, fj)] = v;
                let _ = i;
            }
        }
        Ok(h)
    }
}

/// $a \cdot b$ with eight independent partial sums, so that the additions pipeline and
/// vectorise (one chain of additions is latency-bound: this is the solve's inner loop).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        tail += x * y;
    }
    ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])) + tail
}

/// $R(\theta)\,v$.
pub fn local_to_world(v: [f64; 2], angle_rad: f64) -> [f64; 2] {
    let (s, c) = angle_rad.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// $R(\theta)^\top v$.
pub fn world_to_local(v: [f64; 2], angle_rad: f64) -> [f64; 2] {
    let (s, c) = angle_rad.sin_cos();
    [c * v[0] + s * v[1], -s * v[0] + c * v[1]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ids::{Axis, NodeIdx, Slot};
    use crate::statics::{NodeCondition, StaticProblem};
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    use crate::fixtures::strain_square as model;

    fn max_rel_diff(s: &MixedSolver, cache: &ComplianceCache) -> f64 {
        let h = s.hybrid_from_scratch(cache).unwrap();
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
                        let a = s.angle_rad(slot)
                            + if rng.random_bool(0.5) { rng.random_range(-1e-3..1e-3) } else { rng.random_range(-2.0..2.0) };
                        s.set_angle(slot, a).unwrap();
                        n_mixed_rotations += 1;
                    }
                } else if op < 9 && s.n_nodes() > 3 {
                    let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                    s.remove_slot(slot).unwrap();
                } else {
                    // fresh values on every DOF
                    for k in 0..s.n_dofs() {
                        let v = if s.kind[k] == Condition::Displacement {
                            rng.random_range(-1e-3..1e-3)
                        } else {
                            rng.random_range(-0.01..0.01)
                        };
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
                problem.conditions.push((n, NodeCondition::Local { angle_rad: angle, ut_m: Some(ut), un_m: Some(un) }));
            } else {
                let ft = -3e-3;
                s.set_condition(slot, Axis::Axial, Condition::Force, ft).unwrap();
                problem.conditions.push((n, NodeCondition::Local { angle_rad: angle, ut_m: None, un_m: Some(un) }));
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
        assert_eq!(s.add_node(&cache, n(20), 0.0).unwrap_err(), MixedError::NotCached { contact: ContactPoint::node(n(20)) });
        for n in [20, 21, 0] {
            cache.ensure(&m, n, &mut scratch).unwrap();
        }
        s.add_node(&cache, n(20), 0.0).unwrap();
        assert_eq!(s.add_node(&cache, n(20), 0.0).unwrap_err(), MixedError::AlreadyWorking { node_idx: n(20) });
        // A fixed node has no compliance: prescribing its displacement is singular.
        let slot = s.add_node(&cache, n(0), 0.0).unwrap();
        let e = s.set_condition(slot, Axis::Axial, Condition::Displacement, 0.0).unwrap_err();
        assert!(
            matches!(e, MixedError::SingularPivot { contact, axis: Axis::Axial, .. } if contact == ContactPoint::node(NodeIdx(0))),
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
    fn scaled_hybrid_diff(s: &MixedSolver, h_ref: &faer::Mat<f64>) -> f64 {
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
            matches!(e, MixedError::SingularPivot { contact, axis: Axis::Axial, pivot } if contact == ContactPoint::node(NodeIdx(1)) && pivot < 1e-15 * cx),
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
}
