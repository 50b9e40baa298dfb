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
//! **Compliance source.** The solver reads the compliance only as contact blocks
//! $W_{ab} = P_a C P_b^\top$ when it borders $H$ or rebuilds it, through the trait
//! [`ContactBlocks`]: the column cache [`ComplianceCache`](crate::compliance::ComplianceCache) in 2D and 3D, or the 3D node-block
//! store of large meshes ([`crate::sim3::NodeBlockStore`]). The methods that read it are generic
//! over the store, monomorphised (the 2D code is the same as with the cache type written out).
//!
//! Nothing here allocates after [`MixedSolver::with_capacity`].

use crate::compliance::ContactBlocks;
use crate::contact::{ContactId, ContactPoint};
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
    /// World self-compliance block of each slot, to know each DOF's own compliance.
    c_self: Vec<Block<D>>,
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

fn rot(angle_rad: f64) -> [[f64; 2]; 2] {
    let (s, c) = angle_rad.sin_cos();
    [[c, -s], [s, c]]
}

/// The 2D frame of angle $\theta$: rows $t = (\cos\theta, \sin\theta)$,
/// $n = (-\sin\theta, \cos\theta)$, i.e. $R(\theta)^\top$.
pub fn frame_of_angle(angle_rad: f64) -> Block<2> {
    let (s, c) = angle_rad.sin_cos();
    [[c, s], [-s, c]]
}

/// $F_a M F_b^\top$ for $D \times D$ blocks (a world block to the local frames of $a$ and $b$).
/// The sums run in index order from the first product, so in 2D this is bit for bit the former
/// $R_a^\top M R_b$.
#[inline]
fn to_local<const D: usize>(m: &Block<D>, fa: &Block<D>, fb: &Block<D>) -> Block<D> {
    let mb: Block<D> = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = m[i][0] * fb[j][0];
            for k in 1..D {
                acc += m[i][k] * fb[j][k];
            }
            acc
        })
    });
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = fa[i][0] * mb[0][j];
            for k in 1..D {
                acc += fa[i][k] * mb[k][j];
            }
            acc
        })
    })
}

/// The product $AB$ of two $D \times D$ blocks.
#[inline]
fn mul<const D: usize>(a: &Block<D>, b: &Block<D>) -> Block<D> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = a[i][0] * b[0][j];
            for k in 1..D {
                acc += a[i][k] * b[k][j];
            }
            acc
        })
    })
}

/// $A B^\top$.
#[inline]
fn mul_t<const D: usize>(a: &Block<D>, b: &Block<D>) -> Block<D> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = a[i][0] * b[j][0];
            for k in 1..D {
                acc += a[i][k] * b[j][k];
            }
            acc
        })
    })
}

/// The product of two 2 × 2 blocks.
fn mul2(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j]))
}

/// The principal pivot of a small block on index `k` (the formulas of the module doc); the
/// caller has checked $m_{kk} \ne 0$.
fn pivot_block<const D: usize>(m: &Block<D>, k: usize) -> Block<D> {
    let inv_p = 1.0 / m[k][k];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| match (i == k, j == k) {
            (true, true) => inv_p,
            (true, false) => -m[k][j] * inv_p,
            (false, true) => m[i][k] * inv_p,
            (false, false) => m[i][j] - m[i][k] * m[k][j] * inv_p,
        })
    })
}

/// The inverse of a $D \times D$ block by Gauss–Jordan elimination with partial pivoting; `None`
/// when a pivot is zero or not finite.
fn invert<const D: usize>(m: &Block<D>) -> Option<Block<D>> {
    let mut a = *m;
    let mut inv: Block<D> = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
    for col in 0..D {
        let mut piv = col;
        for r in col + 1..D {
            if a[r][col].abs() > a[piv][col].abs() {
                piv = r;
            }
        }
        let p = a[piv][col];
        if !(p != 0.0 && p.is_finite()) {
            return None;
        }
        a.swap(col, piv);
        inv.swap(col, piv);
        let inv_p = 1.0 / p;
        for j in 0..D {
            a[col][j] *= inv_p;
            inv[col][j] *= inv_p;
        }
        for r in 0..D {
            if r != col {
                let f = a[r][col];
                if f != 0.0 {
                    for j in 0..D {
                        a[r][j] -= f * a[col][j];
                        inv[r][j] -= f * inv[col][j];
                    }
                }
            }
        }
    }
    Some(inv)
}

/// The determinant of a 2 × 2 or 3 × 3 block.
fn det<const D: usize>(m: &Block<D>) -> f64 {
    match D {
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        3 => {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        }
        _ => unreachable!("a solver is 2D or 3D"),
    }
}

/// Checks that `f` is a finite rotation ([`MixedError::NonFinite`], [`MixedError::NotARotation`]).
fn check_frame<const D: usize>(f: &Block<D>, contact: ContactPoint) -> Result<(), MixedError> {
    if !f.iter().flatten().all(|v| v.is_finite()) {
        return Err(MixedError::NonFinite { what: "the frame", contact: contact.id() });
    }
    let fft = mul_t(f, f);
    let mut err: f64 = 0.0;
    for i in 0..D {
        for j in 0..D {
            err = err.max((fft[i][j] - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    let d = det(f);
    if !(err <= FRAME_TOL && d > 0.0) {
        return Err(MixedError::NotARotation { contact: contact.id(), orthonormality_error: err, det: d });
    }
    Ok(())
}

/// The frame `f` (a rotation to [`FRAME_TOL`]) made orthonormal to rounding: Gram–Schmidt on
/// $t$ and $n$, and in 3D $b = t \times n$. Frames are stored this way so that a frame change's
/// $G = F' F^\top$ is the exact map between the two local bases (with $F^\top$ standing for
/// $F^{-1}$); otherwise frames composed over many ticks would drift from orthonormality and
/// $H$ from the frames with them.
fn orthonormalized<const D: usize>(f: &Block<D>) -> Block<D> {
    let dot = |a: &[f64; D], b: &[f64; D]| (0..D).map(|k| a[k] * b[k]).sum::<f64>();
    let mut out = *f;
    let nt = dot(&out[0], &out[0]).sqrt();
    out[0] = out[0].map(|v| v / nt);
    let tn = dot(&out[0], &out[1]);
    out[1] = std::array::from_fn(|k| out[1][k] - tn * out[0][k]);
    let nn = dot(&out[1], &out[1]).sqrt();
    out[1] = out[1].map(|v| v / nn);
    if D == 3 {
        let (t, n) = (out[0], out[1]);
        out[2] = std::array::from_fn(|k| t[(k + 1) % D] * n[(k + 2) % D] - t[(k + 2) % D] * n[(k + 1) % D]);
    }
    out
}

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
        for c in 0..D {
            self.kind[d + c] = Condition::Force;
            self.x[d + c] = 0.0;
        }
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
    fn congruence(&mut self, slot: Slot, g: &Block<D>) {
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
    }

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

    /// Rebuilds $H$ from $C_{\mathcal{WW}}$ from scratch with a dense factorisation: the reference
    /// for the $O(d^2)$ updates, $O(d^3)$ and allocating, never called inside a real-time step.
    ///
    /// Errors: those of [`MixedSolver::hybrid_from_scratch`].
    pub fn rebuild<C: ContactBlocks<D> + ?Sized>(&mut self, cache: &C) -> Result<(), MixedError> {
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

    /// The hybrid matrix for the current contacts, frames and kinds, computed from scratch (a
    /// dense Cholesky of $C_{PP}$).
    ///
    /// Errors: [`MixedError::NotCached`] when a contact's columns are missing,
    /// [`MixedError::SingularPivot`] (naming the first displacement-prescribed DOF, pivot 0)
    /// when $C_{PP}$ is not positive definite.
    pub fn hybrid_from_scratch<C: ContactBlocks<D> + ?Sized>(&self, cache: &C) -> Result<faer::Mat<f64>, MixedError> {
        let d = self.n_dofs();
        let mut cl = faer::Mat::<f64>::zeros(d, d);
        for a in 0..self.n_nodes {
            for b in 0..self.n_nodes {
                let (ca, cb) = (&self.contact_of_slot[a], &self.contact_of_slot[b]);
                let blk = cache.contact_block(ca, cb).ok_or(MixedError::NotCached { contact: cb.id() })?;
                let l = to_local(&blk, &self.frame[a], &self.frame[b]);
                for i in 0..D {
                    for j in 0..D {
                        cl[(D * a + i, D * b + j)] = l[i][j];
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
                MixedError::SingularPivot { contact: self.contact_of_slot[k / D].id(), axis: Axis::of_local_dof::<D>(k), pivot: 0.0 }
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
        for &fi in &f {
            for (j, &fj) in f.iter().enumerate() {
                // C_FF - C_FP C_PP^-1 C_PF = C_FF + C_FP H_PF.
                let mut v = cl[(fi, fj)];
                for (k, &pk) in p.iter().enumerate() {
                    v += cl[(fi, pk)] * hpf[(k, j)];
                }
                h[(fi, fj)] = v;
            }
        }
        Ok(h)
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
        let inv =
            if pset.is_empty() { faer::Mat::zeros(0, 0) } else { faer::linalg::solvers::DenseSolveCore::inverse(&cpp.partial_piv_lu()) };
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
                assert!(
                    eh < tol && ey < tol,
                    "seed {seed} step {step}: d = {}, H diff {eh:e}, y diff {ey:e}, tolerance {tol:e}",
                    s.n_dofs()
                );
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
        println!(
            "2D general vs closed form {e_between:e}, closed vs dense {e_closed:e}, general vs dense {e_general:e} (tolerance {tol:e})"
        );
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
}
