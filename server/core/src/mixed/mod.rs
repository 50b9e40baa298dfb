//! The condensed mixed boundary-condition solve on the working set (the paper's eq. 2–3 and
//! sections 4.1–4.2), with O(d²) updates, in 2D and 3D: one code for both dimensions.
//!
//! **Frames.** Each working contact (slot) $i$ has a frame $F_i$, an orthonormal $D \times D$
//! matrix whose rows are the local axes: $[t, n]$ in 2D, $[t, n, b]$ in 3D ($t$ along the
//! needle, $n$ and $b$ across it, $b = t \times n$). Its local DOFs are $u_L = F_i\,u$ (and
//! $f_L = F_i f$). In 2D the frame is the angle $\theta_i$: $t = (\cos\theta, \sin\theta)$,
//! $n = (-\sin\theta, \cos\theta)$, $F = R(\theta)^\top$ ([`MixedSolver::set_angle`]).
//! The local compliance is $C_L = A\, C_{\mathcal{WW}} A^\top$, $A = \mathrm{diag}(F_i)$.
//!
//! **Hybrid matrix.** Every local DOF has either a prescribed displacement (set $P$) or a
//! prescribed force (set $F$). The solver keeps the *hybrid matrix* $H$ (a principal pivot
//! transform of $C_L$) that maps the prescribed values $x = (u_P, f_F)$ to the unknowns
//! $y = (f_P, u_F)$:
//! $$H = \begin{bmatrix} C_{PP}^{-1} & -C_{PP}^{-1}C_{PF} \\ C_{FP}C_{PP}^{-1} & C_{FF} - C_{FP}C_{PP}^{-1}C_{PF}\end{bmatrix}.$$
//!
//! **Pivot.** Switching DOF $k$ between $P$ and $F$ exchanges $x_k$ and $y_k$: with pivot
//! $p = H_{kk} > 0$, $H'_{kk} = 1/p$, $H'_{kj} = -H_{kj}/p$, $H'_{ik} = H_{ik}/p$,
//! $H'_{ij} = H_{ij} - H_{ik}H_{kj}/p$, a rank-one update of cost $O(d^2)$ (the paper's eq. 3).
//!
//! **Frame change** of slot $s$ from $F$ to $F'$: local vectors turn as $v' = G v$ with the
//! $D \times D$ rotation $G = F' F^\top$. Split the DOFs into the slot's $D$, $s$, and the rest,
//! $r$; split the slot's components into $p$ (displacement-prescribed) and $q$ (force).
//! From $u' = Gu$, $f' = Gf$ componentwise, with $x_s = (u_p, f_q)$, $y_s = (f_p, u_q)$:
//! $$x_s' = \mathcal A x_s + \mathcal B y_s,\qquad y_s' = \mathcal B x_s + \mathcal A y_s,\qquad
//! \mathcal A = \begin{bmatrix} G_{pp} & 0 \\ 0 & G_{qq}\end{bmatrix},\
//! \mathcal B = \begin{bmatrix} 0 & G_{pq} \\ G_{qp} & 0\end{bmatrix}.$$
//! *All the slot's DOFs share a kind* ($p$ or $q$ empty): $\mathcal B = 0$, $\mathcal A = G$,
//! so $H' = \hat G H \hat G^\top$ with $\hat G = G$ on the slot, identity elsewhere: rows and
//! columns $s$ only, $O(d)$.
//! *Mixed kinds* (a slipping contact: lateral displacements, axial force; or a bevel tip):
//! substituting $y_s = H_{ss}x_s + H_{sr}x_r$ and solving for $x_s$, with
//! $W = \mathcal A + \mathcal B H_{ss}$ and $V = \mathcal B + \mathcal A H_{ss}$:
//! $$H'_{ss} = VW^{-1},\quad H'_{sr} = (\mathcal A - H'_{ss}\mathcal B)\,H_{sr},\quad
//! H'_{rs} = H_{rs}W^{-1},\quad H'_{rr} = H_{rr} - H'_{rs}\,\mathcal B\,H_{sr}.$$
//! The rest changes by a term of rank $\operatorname{rank}\mathcal B \le 2\min(|p|, |q|) = 2$
//! (in 2D and 3D alike: the prescribed directions themselves turn, so the condensation of every
//! other DOF changes), one pass over $H$, $O(d^2)$: with $k$ the lone component of its kind and
//! $o$ the others, $\mathcal B$ links $k$ with $o$ only, so with $z = H_{is}W^{-1}$ the row update
//! is $z\mathcal B H_{sr} = \big(\sum_{e \in o} z_e G_{ek}\big) H_{k r} + z_k \big(\sum_{c \in o}
//! G_{kc} H_{cr}\big)$, two precomputed rows. This is the composition of the pivots of
//! $p$ to forces, the congruence and the pivots back, in one pass instead of $2|p| + 1$. In 2D
//! $G = cI + sJ$, $J = \begin{bmatrix} 0 & 1 \\ -1 & 0\end{bmatrix}$, so $\mathcal A = cI$ and
//! $\mathcal B = sJ$ ([`MixedSolver::set_angle`] keeps that closed form). The new
//! prescribed directions are checked before anything changes, as the round trip's pivots back
//! would be: with $S$ the slot's condensed compliance (the pivot of $H_{ss}$ on $p$) and
//! $S' = G S G^\top$, the successive pivots of $S'_{pp}$ (its Cholesky pivots) must be safely
//! positive; then $W$ is invertible.
//!
//! **Bordering.** Adding a contact borders $H$ with its $D$ rows and columns, $O(d^2)$
//! ([`MixedSolver::add_contact_in_frame`]); removing one pivots its displacement-prescribed DOFs
//! to $F$ (zero force) and drops it.
//!
//! **Dimension as a const generic.** `MixedSolver<D>` (and [`ComplianceCache<D>`](crate::compliance::ComplianceCache)) take the
//! dimension as a const generic, `D` ∈ {2, 3}, rather than a runtime field: the per-slot blocks
//! are `[[f64; D]; D]` arrays, so every $D$-loop is unrolled and the 2D code monomorphises to the
//! same 2 × 2 arithmetic as before (bit for bit: same operations in the same order), with no
//! branch on the dimension in the $O(d^2)$ loops and no `Vec<Vec>`; a runtime dimension would
//! make every block a slice and every inner loop a counted one. The default `D = 2` keeps the
//! 2D sim's types (`MixedSolver`, `ComplianceCache`) unchanged; [`MixedSolver2`] and
//! [`MixedSolver3`] name the two. The 2D API (angles: [`MixedSolver::add_contact`],
//! [`MixedSolver::set_angle`], [`MixedSolver::angle_rad`]) is a convenience over the frames of
//! the generic one ([`MixedSolver::add_contact_in_frame`], [`MixedSolver::set_frame`]); local
//! components are named by [`Axis`] (`Axial`, `Lateral` and, in 3D, `Binormal`).
//!
//! **Series compliance.** A slot may carry a compliance $S_i$ (world) in series with the tissue,
//! added to its own block: $W_{ii} \to W_{ii} + S_i$ ([`MixedSolver::add_series_compliance`];
//! the 3D needle's near field, [`crate::sim3`]). Its displacement is then the tissue's plus
//! $S_i f_i$ ([`MixedSolver::series_displacement_world`] is the second part).
//!
//! **Compliance source.** The solver reads the compliance only as contact blocks
//! $W_{ab} = P_a C P_b^\top$ when it borders $H$ or rebuilds it, through the trait
//! [`ContactBlocks`]: the column cache [`ComplianceCache`](crate::compliance::ComplianceCache) in 2D and 3D, or the 3D node-block
//! store of large meshes ([`crate::sim3::NodeBlockStore`]). The methods that read it are generic
//! over the store, monomorphised (the 2D code is the same as with the cache type written out).
//!
//! Nothing here allocates after [`MixedSolver::with_capacity`].

mod blocks;
mod border;
mod frame_change;
mod pivot;
mod rebuild;
mod series;
mod solve;

#[cfg(doc)]
use crate::compliance::ContactBlocks;
use crate::contact::{ContactId, ContactPoint};
use crate::ids::{Axis, NodeIdx, Slot};

use blocks::to_local;
pub use blocks::{frame_of_angle, local_to_world, world_to_local};

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
    NotCached { contact: ContactId },
    /// The slot does not exist.
    #[error("working slot {slot} does not exist ({n_nodes} working nodes)")]
    NoSuchSlot { slot: Slot, n_nodes: usize },
    /// Prescribing this displacement would make the system singular (the DOF is already
    /// determined by other prescribed displacements, or it has no compliance, e.g. a fixed node).
    /// Raised by a condition switch, and by a frame change of a slot with mixed kinds whose new
    /// prescribed direction is singular.
    #[error("prescribing the {axis} displacement of {contact} makes the working system singular (pivot {pivot:e})")]
    SingularPivot { contact: ContactId, axis: Axis, pivot: f64 },
    /// A value, angle or frame is not finite.
    #[error("{what} of working contact {contact} is not finite")]
    NonFinite { what: &'static str, contact: ContactId },
    /// A frame given to [`MixedSolver::add_contact_in_frame`] or [`MixedSolver::set_frame`] is
    /// not a rotation: $\max_{ij} |(F F^\top - I)_{ij}| > 10^{-9}$ or $\det F < 0$.
    #[error("the frame of {contact} is not a rotation (orthonormality error {orthonormality_error:e}, determinant {det:e})")]
    NotARotation { contact: ContactId, orthonormality_error: f64, det: f64 },
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

/// A $D \times D$ block.
pub type Block<const D: usize> = [[f64; D]; D];

/// The condensed mixed solver in dimension `D` (2, the default, or 3) on a working set of at
/// most `cap_nodes` contacts.
#[derive(Debug, Clone)]
pub struct MixedSolver<const D: usize = 2> {
    cap_nodes: usize,
    stride: usize,
    n_nodes: usize,
    contact_of_slot: Vec<ContactPoint>,
    /// 2D: the frame angle of each slot, as given ([`MixedSolver::set_angle`]); in 3D unused.
    angle_rad: Vec<f64>,
    /// The frame of each slot, rows $[t, n, (b)]$: $u_L = F u$.
    frame: Vec<Block<D>>,
    /// World self-compliance block of each slot, to know each DOF's own compliance (the
    /// series compliance included).
    c_self: Vec<Block<D>>,
    /// World compliance in series with the tissue at each slot, added to its own block
    /// ([`MixedSolver::add_series_compliance`]; zero unless added).
    series: Vec<Block<D>>,
    kind: Vec<Condition>,
    x: Vec<f64>,
    y: Vec<f64>,
    h: Vec<f64>,
    tmp_row: Vec<f64>,
    tmp_col: Vec<f64>,
    /// The slot's old rows of $H$ in a general frame change ($D$ rows of `stride`).
    tmp_rows: Vec<f64>,
    tmp_c: Vec<[f64; D]>,
    /// The displacement-prescribed DOFs, in increasing order, while bordering.
    p_list: Vec<usize>,
    stats: MixedStats,
}

/// The 2D solver (frames are angles).
pub type MixedSolver2 = MixedSolver<2>;
/// The 3D solver (frames are rotations with rows $[t, n, b]$).
pub type MixedSolver3 = MixedSolver<3>;

/// Relative size below which a pivot is treated as zero: $p \le \epsilon\, C_{kk}$.
const PIVOT_TOL: f64 = 1e-12;

/// Largest $|(F F^\top - I)_{ij}|$ accepted for a frame.
const FRAME_TOL: f64 = 1e-9;

impl<const D: usize> MixedSolver<D> {
    /// An empty solver with room for `cap_nodes` working contacts (all storage allocated here).
    /// Panics only on a programming error (`D` not 2 or 3).
    pub fn with_capacity(cap_nodes: usize) -> Self {
        assert!(D == 2 || D == 3, "a mixed solver is 2D or 3D");
        let stride = D * cap_nodes;
        let identity: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
        Self {
            cap_nodes,
            stride,
            n_nodes: 0,
            contact_of_slot: vec![ContactPoint::node(NodeIdx(0)); cap_nodes],
            angle_rad: vec![0.0; cap_nodes],
            frame: vec![identity; cap_nodes],
            c_self: vec![[[0.0; D]; D]; cap_nodes],
            series: vec![[[0.0; D]; D]; cap_nodes],
            kind: vec![Condition::Force; stride],
            x: vec![0.0; stride],
            y: vec![0.0; stride],
            h: vec![0.0; stride * stride],
            tmp_row: vec![0.0; stride],
            tmp_col: vec![0.0; stride],
            tmp_rows: vec![0.0; D * stride],
            tmp_c: vec![[0.0; D]; stride],
            p_list: vec![0; stride],
            stats: MixedStats::default(),
        }
    }

    /// Makes this solver a copy of `other` without allocating (capacities must be equal).
    /// Panics only on a programming error (different capacities).
    pub fn copy_from(&mut self, other: &MixedSolver<D>) {
        assert_eq!(self.cap_nodes, other.cap_nodes, "copy_from needs equal capacities");
        self.n_nodes = other.n_nodes;
        self.contact_of_slot.copy_from_slice(&other.contact_of_slot);
        self.angle_rad.copy_from_slice(&other.angle_rad);
        self.frame.copy_from_slice(&other.frame);
        self.c_self.copy_from_slice(&other.c_self);
        self.series.copy_from_slice(&other.series);
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

    /// Working contacts.
    pub fn n_nodes(&self) -> usize {
        self.n_nodes
    }
    /// Number of working DOFs $d = Dm$.
    pub fn n_dofs(&self) -> usize {
        D * self.n_nodes
    }
    /// Capacity in contacts.
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
    /// The frame of a slot (rows $t, n, (b)$ in world coordinates): the one given, made
    /// orthonormal to rounding (Gram–Schmidt on $t$, $n$; $b = t \times n$), which moves it by no
    /// more than the $10^{-9}$ a frame may be off.
    pub fn frame(&self, slot: Slot) -> Block<D> {
        self.frame[slot.index()]
    }
    /// The local DOF of `slot` along `axis`. Panics only on a programming error (an axis the
    /// dimension does not have: [`Axis::Binormal`] in 2D).
    #[inline]
    fn dof(slot: Slot, axis: Axis) -> usize {
        assert!(axis.index() < D, "the {axis} axis in a {D}D solver");
        D * slot.index() + axis.index()
    }
    /// The condition kind of a slot's local component along `axis`.
    pub fn condition(&self, slot: Slot, axis: Axis) -> Condition {
        self.kind[Self::dof(slot, axis)]
    }
    /// The hybrid matrix entry $H_{ij}$ between local DOFs $i$, $j$ ([`Slot::local_dof`]).
    /// For the flexible needle's coupling, tests and diagnostics.
    pub fn hybrid(&self, i: usize, j: usize) -> f64 {
        self.h[i * self.stride + j]
    }

    fn check_slot(&self, slot: Slot) -> Result<(), MixedError> {
        if slot.index() >= self.n_nodes { Err(MixedError::NoSuchSlot { slot, n_nodes: self.n_nodes }) } else { Ok(()) }
    }

    /// The local compliance of DOF `k` (its own, before any condensation).
    fn c_local_diag(&self, k: usize) -> f64 {
        let s = k / D;
        let f = &self.frame[s];
        to_local(&self.c_self[s], f, f)[k % D][k % D]
    }
}

#[cfg(test)]
mod tests;
