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
//! a node with mixed kinds is pivoted to a uniform kind, rotated and pivoted back, $O(d^2)$.
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
    /// new frame (the caller sets them anew). $O(d)$, or $O(d^2)$ for a node with mixed kinds.
    ///
    /// Errors: [`MixedError::NoSuchSlot`], [`MixedError::NonFinite`] for a non-finite angle, and
    /// [`MixedError::SingularPivot`] when a node with mixed kinds cannot be pivoted back (it is
    /// then left force-prescribed at zero on that DOF).
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
        // Make both kinds equal: pivot a displacement DOF to force (always a positive pivot).
        let mixed_pivot = if self.kind[k0] != self.kind[k1] {
            let k = if self.kind[k0] == Condition::Displacement { k0 } else { k1 };
            self.pivot(k)?;
            Some(k)
        } else {
            None
        };
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
        self.angle_rad[slot.index()] = angle_rad;
        self.stats.n_rotations += 1;
        if let Some(k) = mixed_pivot
            && let Err(e) = self.pivot(k)
        {
            // Leave a consistent state: the node stays force-prescribed on that DOF.
            self.x[k] = 0.0;
            return Err(e);
        }
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
            let row = &self.h[i * st..i * st + d];
            self.y[i] = row.iter().zip(&self.x[..d]).map(|(a, b)| a * b).sum();
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
                } else if op < 8 {
                    let slot = Slot::new(rng.random_range(0..s.n_nodes()));
                    let a = s.angle_rad(slot) + rng.random_range(-0.5..0.5);
                    s.set_angle(slot, a).unwrap();
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
}
