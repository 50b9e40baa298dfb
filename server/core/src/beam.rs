//! The flexible needle: a geometrically exact discrete elastica clamped at the base pose, and its
//! coupling to the tissue's working set.
//!
//! **Beam.** The shaft of length $L$ is a chain of $N$ rigid links of length $h = L/N$ joined by
//! rotational springs (inextensible, bending only). Joint $k$ sits at the proximal end $x_k$ of
//! link $k$; joint 0 is the clamp at the base. Under point forces $F_j$ applied at shaft points
//! $p_j$ (arc lengths $s_j$), the moment at joint $k$ of the loads distal to it is
//! $$M_k = \sum_{j:\,s_j \ge k h} (p_j - x_k) \times F_j,$$
//! and the joint turns by $\Delta\psi_k = w_k M_k / EI$ ($w_0 = h/2$, $w_k = h$: the trapezoidal
//! rule for $\psi' = M/EI$). Link $k$ points along $\psi_k = \theta + \sum_{m \le k} \Delta\psi_m$.
//! Positions and moments are evaluated on the deformed shape, so large deflections and rotations
//! are exact for the discrete model (it converges to Kirchhoff's elastica as $h \to 0$); the
//! equilibrium is found by fixed-point iteration warm-started from the previous tick's shape.
//!
//! **Coupling.** Linearised about the current shape, the lateral deflection at shaft point $i$
//! (direction $n_i$) from a lateral force at point $j$ (direction $n_j$) is the virtual-work
//! compliance of the discrete beam
//! $$G_{ij} = \frac{1}{EI}\sum_{k \le \min(m_i, m_j)} w_k\,\big((p_i - x_k)\times n_i\big)\big((p_j - x_k)\times n_j\big),$$
//! ($m_i$ the link of point $i$), computed in $O(N + d^2)$ from prefix sums of $w_k$, $w_k x_k$ and
//! $w_k x_k x_k^\top$. The loads the shape carries add their geometric stiffness: with
//! $S_i = \sum_{j:\,m_j \ge i} F_j$ the load beyond joint $i$ (follower loads, turning with their
//! link), $\partial M_k/\partial\beta_i = [i > k]\,(x_i - x_k)\cdot S_i$, a strictly upper triangular
//! $T$; the tangent compliance is $G = B^\top (I - C T)^{-1} C B$ with $B_{kj} = [k \le m_j](p_j - x_k)\times n_j$,
//! $C = \mathrm{diag}(w_k/EI)$, and the triangular solve takes $O(N)$ per column with suffix sums,
//! so $G$ costs $O(N d + d^2)$. Each tissue node on the needle has its lateral displacement prescribed so
//! that it lies on the needle: with $g$ the values that put it on the reference shape (the last
//! equilibrium) and $f$ the lateral forces of the needle on the tissue,
//! $$v = g - G_{NN}(f_N - f^{ref}_N) - G_{NK}(f_K - f^{ref}_K),\qquad f_N = A v + b,$$
//! where $A$ is the lateral block of the working set's hybrid matrix, $b$ the lateral forces
//! from everything else and $K$ the lateral DOFs with prescribed force (a bevel tip). Hence one
//! dense solve $(I + G_{NN}A)\,v = g - G_{NN}(b - f^{ref}_N) - G_{NK}(f_K - f^{ref}_K)$ per solve
//! of the working set, its LU reused while only prescribed values change, and corrected by
//! Sherman–Morrison–Woodbury while only conditions do (a pivot changes $H$, hence $A$, by rank
//! one; see [`Coupling`]), refactorised when the slots, frames or shape change. A stiff
//! needle ($G \to 0$) gives $v = g$: the rigid needle.
//!
//! **Why this model** (rather than a co-rotational FE beam):
//! in 2D an inextensible needle is described exactly by its tangent angle along the arc, so a chain
//! of rigid links with rotational springs (moments taken on the deformed positions) is
//! geometrically exact for any rotation and deflection, has no locking or membrane stiffness to
//! tune, and gives the coupling's compliance in closed form by virtual work. It matches the
//! classical large-deflection cantilever (tip load PL²/EI = 1: deflection 0.30172 L, shortening
//! 0.05643 L) to 5e-4, and the small-load formula with second-order convergence in the link length.
//! The tissue's contact forces are follower loads (friction along the shaft, pressure across it):
//! as dead loads the axial friction made thin needles oscillate (P-δ without the tissue's support
//! in the shape update). The coupling's compliance is the tangent of that model — with the
//! geometric stiffness of the loads (a 22-gauge needle under 0.4 N: up to 17 % from the plain
//! compliance; the tangent matches finite differences of the settled shape to 1e-7) — so a tick's
//! first solve is nearly its equilibrium and the stiffness Jacobian the device renders predicts
//! base translations and rotations alike (to 1e-3 / 2e-3; without it, rotations were 19 % off).
//! Follower loads are not conservative: that Jacobian is not exactly symmetric (≈ 1 %).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor as lu_factor, solve as lu_solve};
use faer::{Accum, Conj, MatMut, MatRef, Par};

use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedSolver};
use crate::needle::{BasePose, FlexibleNeedle};

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Largest number of fixed-point iterations of the shape update.
const SHAPE_MAX_ITERATIONS: usize = 60;

/// The deformed shape of a flexible needle and the scratch of its updates (all allocated up
/// front; nothing allocates afterwards).
#[derive(Debug, Clone)]
pub struct NeedleCurve {
    length_m: f64,
    link_m: f64,
    ei_nm2: f64,
    base: BasePose,
    /// Joint rotations $\Delta\psi_k$, k = 0..N.
    joint_rad: Vec<f64>,
    /// Absolute link directions $\psi_k$.
    link_rad: Vec<f64>,
    /// Joint positions $x_0 \dots x_N$ ($x_N$ is the tip).
    pts: Vec<[f64; 2]>,
    loads: Vec<(f64, [f64; 2])>,
    new_joint: Vec<f64>,
    /// Prefix sums for the compliance: $\sum w_k$, $\sum w_k r_k$, $\sum w_k r_k r_k^\top$ with
    /// $r_k = x_k - b$.
    p0: Vec<f64>,
    p1: Vec<[f64; 2]>,
    p2: Vec<[f64; 3]>,
    /// Scratch of the tangent compliance: the load beyond each joint, a column of joint
    /// rotations and its prefix sums.
    beyond: Vec<[f64; 2]>,
    col: Vec<f64>,
    q0: Vec<f64>,
    q1: Vec<[f64; 2]>,
    point_terms: Vec<(f64, [f64; 2], usize)>,
    /// Joint positions relative to the base and joint compliances $w_k/EI$ (scratch).
    rel: Vec<[f64; 2]>,
    joint_c: Vec<f64>,
    /// Fixed-point iterations of the last shape update, and updates that hit the bound.
    pub last_iterations: usize,
    pub unconverged_updates: u64,
    /// Points or loads past `max_loads` that an update had to leave out (never expected: the
    /// simulation sizes the curve for its whole working set; counted so it is never silent).
    pub capacity_drops: u64,
}

impl NeedleCurve {
    /// A straight needle at `base` with room for `max_loads` point loads (and as many points in
    /// [`Self::tangent_compliance_into`]); more are left out and counted in `capacity_drops`.
    pub fn new(params: &FlexibleNeedle, base: BasePose, max_loads: usize) -> Self {
        let n = params.n_links;
        let mut c = Self {
            length_m: params.length_m,
            link_m: params.length_m / n as f64,
            ei_nm2: params.flexural_rigidity_nm2,
            base,
            joint_rad: vec![0.0; n],
            link_rad: vec![0.0; n],
            pts: vec![[0.0; 2]; n + 1],
            loads: Vec::with_capacity(max_loads),
            new_joint: vec![0.0; n],
            p0: vec![0.0; n],
            p1: vec![[0.0; 2]; n],
            p2: vec![[0.0; 3]; n],
            beyond: vec![[0.0; 2]; n],
            col: vec![0.0; n],
            q0: vec![0.0; n],
            q1: vec![[0.0; 2]; n],
            point_terms: Vec::with_capacity(max_loads),
            rel: vec![[0.0; 2]; n],
            joint_c: vec![0.0; n],
            last_iterations: 0,
            unconverged_updates: 0,
            capacity_drops: 0,
        };
        c.rebuild_points();
        c
    }

    /// Number of links.
    pub fn n_links(&self) -> usize {
        self.joint_rad.len()
    }
    /// The joint positions, base to tip.
    pub fn points_m(&self) -> &[[f64; 2]] {
        &self.pts
    }
    /// The base pose the shape hangs from.
    pub fn base(&self) -> BasePose {
        self.base
    }

    fn weight(&self, k: usize) -> f64 {
        if k == 0 { 0.5 * self.link_m } else { self.link_m }
    }

    /// Joint positions and link directions from the joint rotations, and (`with_sums`) the
    /// prefix sums of the compliance.
    fn rebuild_points(&mut self) {
        self.rebuild(true);
    }

    fn rebuild(&mut self, with_sums: bool) {
        let mut psi = self.base.theta_rad;
        let mut x = self.base.position_m();
        self.pts[0] = x;
        let n = self.joint_rad.len();
        let mut s0 = 0.0;
        let mut s1 = [0.0; 2];
        let mut s2 = [0.0; 3];
        for k in 0..n {
            if with_sums {
                let w = self.weight(k);
                let r = [x[0] - self.base.x_m, x[1] - self.base.y_m];
                s0 += w;
                s1 = [s1[0] + w * r[0], s1[1] + w * r[1]];
                s2 = [s2[0] + w * r[0] * r[0], s2[1] + w * r[0] * r[1], s2[2] + w * r[1] * r[1]];
                self.p0[k] = s0;
                self.p1[k] = s1;
                self.p2[k] = s2;
            }
            psi += self.joint_rad[k];
            self.link_rad[k] = psi;
            let (sn, cs) = psi.sin_cos();
            x = [x[0] + self.link_m * cs, x[1] + self.link_m * sn];
            self.pts[k + 1] = x;
        }
    }

    /// Makes this curve a copy of `other` without allocating (both made from the same needle).
    pub fn copy_from(&mut self, other: &NeedleCurve) {
        self.base = other.base;
        self.joint_rad.copy_from_slice(&other.joint_rad);
        self.link_rad.copy_from_slice(&other.link_rad);
        self.pts.copy_from_slice(&other.pts);
        self.p0.copy_from_slice(&other.p0);
        self.p1.copy_from_slice(&other.p1);
        self.p2.copy_from_slice(&other.p2);
    }

    /// The tangent lateral compliance (see the module docs) between the shaft points
    /// `points[i] = (s_m, frame angle)`, with the needle carrying `loads[j] = (s_m, force on the
    /// needle in the frame of that point: along, across)`; written row-major into `out` with
    /// row stride `stride`. $O(N d + d^2)$, no allocation. With no loads it equals
    /// [`Self::compliance`].
    pub fn tangent_compliance_into(&mut self, points: &[(f64, f64)], loads: &[(f64, [f64; 2])], out: &mut [f64], stride: usize) {
        let n = self.joint_rad.len();
        // The load beyond each joint (world), follower loads turned into world axes.
        for v in self.beyond.iter_mut() {
            *v = [0.0; 2];
        }
        for (k, &(s, f_local)) in loads.iter().enumerate() {
            let (sn, cs) = points[k].1.sin_cos();
            let f = [f_local[0] * cs - f_local[1] * sn, f_local[0] * sn + f_local[1] * cs];
            let m = self.link_of(s);
            self.beyond[m] = [self.beyond[m][0] + f[0], self.beyond[m][1] + f[1]];
        }
        for k in (0..n.saturating_sub(1)).rev() {
            self.beyond[k] = [self.beyond[k][0] + self.beyond[k + 1][0], self.beyond[k][1] + self.beyond[k + 1][1]];
        }
        self.point_terms.clear();
        for &(s, a) in points {
            let t = self.compliance_terms(s, a);
            if self.point_terms.len() < self.point_terms.capacity() {
                self.point_terms.push(t);
            } else {
                self.capacity_drops += 1;
            }
        }
        let b = self.base.position_m();
        for k in 0..n {
            self.rel[k] = [self.pts[k][0] - b[0], self.pts[k][1] - b[1]];
            self.joint_c[k] = self.weight(k) / self.ei_nm2;
        }
        let m_max = self.point_terms.iter().map(|t| t.2).max().unwrap_or(0);
        for j in 0..self.point_terms.len() {
            let (aj, cj, mj) = self.point_terms[j];
            // Back substitution of (I - C T) beta = C B e_j from joint m_j down (beyond it both
            // the right-hand side and the solution vanish):
            // beta_k = rhs_k + c_k (sum_{i>k} (r_i . S_i) beta_i - r_k . sum_{i>k} S_i beta_i).
            let (mut acc_s, mut acc_v) = (0.0, [0.0; 2]);
            for k in (0..=mj).rev() {
                let (rk, ck) = (self.rel[k], self.joint_c[k]);
                let rhs = ck * (aj - (cj[0] * rk[0] + cj[1] * rk[1]));
                let beta = rhs + ck * (acc_s - (rk[0] * acc_v[0] + rk[1] * acc_v[1]));
                self.col[k] = beta;
                let sk = self.beyond[k];
                acc_s += (rk[0] * sk[0] + rk[1] * sk[1]) * beta;
                acc_v = [acc_v[0] + sk[0] * beta, acc_v[1] + sk[1] * beta];
            }
            // Lateral displacement of point i: sum_{k <= m_i} (a_i - c_i . r_k) beta_k.
            let (mut q0, mut q1) = (0.0, [0.0; 2]);
            for k in 0..=m_max {
                let rk = self.rel[k];
                if k > mj {
                    self.col[k] = 0.0;
                }
                q0 += self.col[k];
                q1 = [q1[0] + rk[0] * self.col[k], q1[1] + rk[1] * self.col[k]];
                self.q0[k] = q0;
                self.q1[k] = q1;
            }
            for (i, &(ai, ci, mi)) in self.point_terms.iter().enumerate() {
                out[i * stride + j] = ai * self.q0[mi] - (ci[0] * self.q1[mi][0] + ci[1] * self.q1[mi][1]);
            }
        }
    }

    /// Moves the clamp to `base`; the shape moves with it rigidly (the joint rotations stay).
    pub fn set_base(&mut self, base: BasePose) {
        self.base = base;
        self.rebuild_points();
    }

    /// The link of arc length `s_m` (clamped to the shaft).
    fn link_of(&self, s_m: f64) -> usize {
        let n = self.joint_rad.len();
        if s_m <= 0.0 {
            return 0;
        }
        ((s_m / self.link_m) as usize).min(n - 1)
    }

    /// The shaft point at arc length `s_m`; beyond the ends the shape continues straight along
    /// the end links (the tip's tangent ahead of the tip).
    pub fn point_at(&self, s_m: f64) -> [f64; 2] {
        let k = self.link_of(s_m);
        let d = s_m - k as f64 * self.link_m;
        let (sn, cs) = self.link_rad[k].sin_cos();
        [self.pts[k][0] + d * cs, self.pts[k][1] + d * sn]
    }

    /// The tangent angle at arc length `s_m`: link directions interpolated linearly between link
    /// midpoints (so node frames turn smoothly as nodes slide).
    pub fn tangent_angle_at(&self, s_m: f64) -> f64 {
        let n = self.joint_rad.len();
        let u = s_m / self.link_m - 0.5;
        if u <= 0.0 {
            return self.link_rad[0];
        }
        let k = u as usize;
        if k + 1 >= n {
            return self.link_rad[n - 1];
        }
        let a = u - k as f64;
        (1.0 - a) * self.link_rad[k] + a * self.link_rad[k + 1]
    }

    /// The tip position.
    pub fn tip_m(&self) -> [f64; 2] {
        self.pts[self.pts.len() - 1]
    }
    /// The tip's tangent angle.
    pub fn tip_angle_rad(&self) -> f64 {
        self.link_rad[self.link_rad.len() - 1]
    }

    /// Coordinates of `p_m` in the frame at arc length `s_ref_m` with angle `angle_rad`:
    /// $(s_{ref} + t\cdot(p - c),\ n\cdot(p - c))$, $c$ the shaft point at $s_{ref}$.
    pub fn frame_coords(&self, s_ref_m: f64, angle_rad: f64, p_m: [f64; 2]) -> (f64, f64) {
        let c = self.point_at(s_ref_m);
        let (sn, cs) = angle_rad.sin_cos();
        let d = [p_m[0] - c[0], p_m[1] - c[1]];
        (s_ref_m + cs * d[0] + sn * d[1], -sn * d[0] + cs * d[1])
    }

    /// The per-point terms of the compliance: $(r \times n,\ c = (n_y, -n_x),\ \text{link})$ with
    /// $r = p - b$, so that the moment arm at joint $k$ is $r\times n - c\cdot(x_k - b)$.
    fn compliance_terms(&self, s_m: f64, angle_rad: f64) -> (f64, [f64; 2], usize) {
        let b = self.base.position_m();
        let p = self.point_at(s_m);
        let r = [p[0] - b[0], p[1] - b[1]];
        let nrm = [-angle_rad.sin(), angle_rad.cos()];
        (cross(r, nrm), [nrm[1], -nrm[0]], self.link_of(s_m))
    }

    fn compliance_from_terms(&self, ti: (f64, [f64; 2], usize), tj: (f64, [f64; 2], usize)) -> f64 {
        let ((ai, ci, li), (aj, cj, lj)) = (ti, tj);
        let k = li.min(lj);
        let (s0, s1, s2) = (self.p0[k], self.p1[k], self.p2[k]);
        let c1i = ci[0] * s1[0] + ci[1] * s1[1];
        let c1j = cj[0] * s1[0] + cj[1] * s1[1];
        let c2 = ci[0] * (s2[0] * cj[0] + s2[1] * cj[1]) + ci[1] * (s2[1] * cj[0] + s2[2] * cj[1]);
        (ai * aj * s0 - ai * c1j - aj * c1i + c2) / self.ei_nm2
    }

    /// Lateral compliance between shaft point `i` (arc `s_i`, lateral direction angle of its frame
    /// `a_i`) and point `j` ($G_{ij}$ above), m/N.
    pub fn compliance(&self, s_i: f64, a_i: f64, s_j: f64, a_j: f64) -> f64 {
        self.compliance_from_terms(self.compliance_terms(s_i, a_i), self.compliance_terms(s_j, a_j))
    }

    /// Finds the equilibrium shape under point forces on the needle `(s_m, force)`, warm-started
    /// from the current shape. With `follower` the force is given in the local frame of the
    /// shaft at $s$ (tangential, normal) and turns with it, as the tissue's contact forces do
    /// (friction along the shaft, pressure across it, the cutting force along the tip); without,
    /// it is a fixed world vector (a dead load). Returns whether it converged (no joint
    /// turning by more than 1e-13 rad between iterates); the shape is left at the last iterate otherwise (counted).
    pub fn update_shape(&mut self, loads: impl Iterator<Item = (f64, [f64; 2])>, follower: bool) -> bool {
        self.loads.clear();
        for (s, f) in loads {
            if self.loads.len() < self.loads.capacity() {
                self.loads.push((s.clamp(0.0, self.length_m), f));
            } else {
                self.capacity_drops += 1;
            }
        }
        self.loads.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let n = self.joint_rad.len();
        // Converged when no joint turns by more than 1e-13 rad between iterates.
        let tol = 1e-13;
        let mut relax = 1.0;
        let mut prev_change = f64::INFINITY;
        for it in 1..=SHAPE_MAX_ITERATIONS {
            // Suffix sums of the distal loads: F = Σ F_j, A = Σ (p_j - b) × F_j.
            let b = self.base.position_m();
            let mut fsum = [0.0; 2];
            let mut asum = 0.0;
            let mut j = self.loads.len();
            for k in (0..n).rev() {
                let start = k as f64 * self.link_m;
                while j > 0 && (self.loads[j - 1].0 >= start || k == 0) {
                    let (s, f_given) = self.loads[j - 1];
                    let p = self.point_at(s);
                    let f = if follower {
                        let (sn, cs) = self.link_rad[self.link_of(s)].sin_cos();
                        [f_given[0] * cs - f_given[1] * sn, f_given[0] * sn + f_given[1] * cs]
                    } else {
                        f_given
                    };
                    fsum = [fsum[0] + f[0], fsum[1] + f[1]];
                    asum += cross([p[0] - b[0], p[1] - b[1]], f);
                    j -= 1;
                }
                let r = [self.pts[k][0] - b[0], self.pts[k][1] - b[1]];
                let m = asum - cross(r, fsum);
                self.new_joint[k] = self.weight(k) * m / self.ei_nm2;
            }
            let mut change: f64 = 0.0;
            for k in 0..n {
                let d = self.new_joint[k] - self.joint_rad[k];
                change = change.max(d.abs());
                self.joint_rad[k] += relax * d;
            }
            self.rebuild(false);
            self.last_iterations = it;
            if change <= tol {
                self.rebuild_points();
                return true;
            }
            if change > prev_change {
                relax = (relax * 0.5).max(0.05);
            }
            prev_change = change;
        }
        self.rebuild_points();
        self.unconverged_updates += 1;
        false
    }
}

/// Most pivoted DOFs a [`Coupling`] absorbs into its factorisation by a low-rank correction
/// before it refactorises (it also refactorises when the correction's rank exceeds a third of
/// the lateral system's size, where the correction stops being cheaper than a new LU).
pub const MAX_LOW_RANK: usize = 16;

/// Counters of a [`Coupling`]'s factorisation work (diagnostics).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CouplingStats {
    /// Dense LU factorisations of $M = I + G_{NN}A$.
    pub factorisations: u64,
    /// Low-rank (Woodbury) corrections built instead of a factorisation after pivots.
    pub low_rank_updates: u64,
}

/// The tissue–needle coupling of one working-set solver: the dense lateral system above, with
/// its storage allocated once for `cap_nodes` working nodes.
///
/// **Updates after pivots.** The LU of $M_0 = I + G_{NN}A_0$ is kept (the *base*) while only the
/// working solver's conditions change. A pivot changes $H$ by rank one, and after pivots on a
/// set $S$ of DOFs (those whose kind differs from the base's; a DOF pivoted twice is back) the
/// principal pivot transform on $S$ maps the current $H$ back to the base's, so
/// $$A = A_0 + U\,C^{-1}V,\qquad U = H_{NS},\ C = H_{SS},\ V = H_{SN}$$
/// (current $H$; $S$ never meets $N$, whose change is a new system). Hence
/// $M = M_0 + (G_{NN}U)\,C^{-1}V$ and, by Sherman–Morrison–Woodbury, with $Z = M_0^{-1}G_{NN}U$,
/// $$M^{-1}r = z - Z\,(C + VZ)^{-1}\,V z,\qquad z = M_0^{-1}r,$$
/// an $|S| \times |S|$ capacitance system. Building $Z$ costs $O(|S|\,n^2)$ against $O(n^3)$ for a
/// new LU; each solve then adds $O(|S|\,n)$. A change of the slots, the frames, the shape ($G$)
/// or of which slots are in $N$ refactorises, and so does a set $S$ larger than
/// [`MAX_LOW_RANK`] or $n/3$.
pub struct Coupling {
    cap: usize,
    /// Slots whose lateral displacement is prescribed (N) and with prescribed lateral force (K).
    n_slots: Vec<Slot>,
    k_slots: Vec<Slot>,
    /// $G$ over all slots (row-major, stride `cap`).
    g: Vec<f64>,
    points: Vec<(f64, f64)>,
    loads: Vec<(f64, [f64; 2])>,
    /// $I + G_{NN}A$, then its LU factors (column-major, leading dimension `cap`).
    m: Vec<f64>,
    /// $G_{NN}$ and $A$ gathered (column-major, leading dimension `cap`) for the product.
    g_nn: Vec<f64>,
    a_nn: Vec<f64>,
    /// Each slot's reference lateral force in its frame.
    f_ref_lat: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    buf: MemBuffer,
    rhs: Vec<f64>,
    y_cur: Vec<f64>,
    /// The (solver update count without pivots, shape version) the base LU belongs to, its N
    /// slots, whether each DOF was displacement-prescribed then, and the pivot count the
    /// low-rank correction was built for.
    factored_for: Option<(u64, u64)>,
    base_slots: Vec<Slot>,
    base_disp: Vec<bool>,
    corrected_for: u64,
    /// The low-rank correction: the pivoted DOFs $S$, $Z$ (column-major, leading dimension
    /// `cap`), $V$ (row-major, stride `cap`), the capacitance $C + VZ$ and its LU (column-major,
    /// leading dimension [`MAX_LOW_RANK`]), and a work vector.
    s_dofs: Vec<usize>,
    z: Vec<f64>,
    v_sn: Vec<f64>,
    cap_lu: Vec<f64>,
    cap_perm: Vec<usize>,
    cap_perm_inv: Vec<usize>,
    w: Vec<f64>,
    max_low_rank: usize,
    /// Bumped whenever G is recomputed.
    shape_version: u64,
    stats: CouplingStats,
}

/// One working node as the coupling sees it: its shaft position, its reference lateral value $g$
/// and the force on the tissue (in its frame, along and across: the contact forces are follower
/// loads, so they turn with the needle) the reference shape was in equilibrium with.
#[derive(Debug, Clone, Copy)]
pub struct CoupledNode {
    pub s_m: f64,
    pub lateral_ref_m: f64,
    pub force_ref_local_n: [f64; 2],
}

impl Coupling {
    /// Storage for `cap_nodes` working nodes.
    pub fn new(cap_nodes: usize) -> Self {
        let cap = cap_nodes.max(1);
        let r = MAX_LOW_RANK;
        let req = lu_factor::lu_in_place_scratch::<usize, f64>(cap, cap, Par::Seq, Default::default())
            .or(lu_solve::solve_in_place_scratch::<usize, f64>(cap, r, Par::Seq))
            .or(lu_factor::lu_in_place_scratch::<usize, f64>(r, r, Par::Seq, Default::default()))
            .or(lu_solve::solve_in_place_scratch::<usize, f64>(r, 1, Par::Seq));
        Self {
            cap,
            n_slots: Vec::with_capacity(cap),
            k_slots: Vec::with_capacity(cap),
            g: vec![0.0; cap * cap],
            points: Vec::with_capacity(cap),
            loads: Vec::with_capacity(cap),
            m: vec![0.0; cap * cap],
            g_nn: vec![0.0; cap * cap],
            a_nn: vec![0.0; cap * cap],
            f_ref_lat: vec![0.0; cap],
            perm: vec![0; cap],
            perm_inv: vec![0; cap],
            buf: MemBuffer::new(req),
            rhs: vec![0.0; cap],
            y_cur: vec![0.0; cap],
            factored_for: None,
            base_slots: Vec::with_capacity(cap),
            base_disp: vec![false; 2 * cap],
            corrected_for: 0,
            s_dofs: Vec::with_capacity(r),
            z: vec![0.0; cap * r],
            v_sn: vec![0.0; r * cap],
            cap_lu: vec![0.0; r * r],
            cap_perm: vec![0; r],
            cap_perm_inv: vec![0; r],
            w: vec![0.0; r],
            max_low_rank: r,
            shape_version: 0,
            stats: CouplingStats::default(),
        }
    }

    /// The factorisation counters.
    pub fn stats(&self) -> CouplingStats {
        self.stats
    }

    /// Sets the largest rank of a low-rank correction (clamped to [`MAX_LOW_RANK`]; 0 refactorises
    /// after every pivot, the reference the corrections are tested against).
    pub fn set_max_low_rank(&mut self, rank: usize) {
        self.max_low_rank = rank.min(MAX_LOW_RANK);
        self.factored_for = None;
    }

    /// Recomputes $G$ for the solver's slots on `curve` (call after the shape, the frames or the
    /// slots changed). $O(d^2)$.
    pub fn update_compliance(&mut self, curve: &mut NeedleCurve, solver: &MixedSolver, nodes: &[CoupledNode]) {
        let d = solver.n_nodes().min(nodes.len());
        self.points.clear();
        self.loads.clear();
        for (slot, node) in Slot::all(d).zip(nodes) {
            self.points.push((node.s_m, solver.angle_rad(slot)));
            // The needle carries the opposite of the force on the tissue.
            self.loads.push((node.s_m, [-node.force_ref_local_n[0], -node.force_ref_local_n[1]]));
        }
        curve.tangent_compliance_into(&self.points, &self.loads, &mut self.g, self.cap);
        self.shape_version += 1;
    }

    /// Solves the working set with the needle's lateral compliance: sets the lateral values of
    /// the displacement-prescribed slots to $v$ and solves.
    pub fn solve(&mut self, solver: &mut MixedSolver, nodes: &[CoupledNode]) {
        let d = solver.n_nodes();
        self.n_slots.clear();
        self.k_slots.clear();
        for slot in Slot::all(d) {
            if solver.condition(slot, Axis::Lateral) == Condition::Displacement {
                self.n_slots.push(slot);
            } else {
                self.k_slots.push(slot);
            }
        }
        let nn = self.n_slots.len();
        // b = y_N - A v at the current values.
        solver.solve();
        for (a, &si) in self.n_slots.iter().enumerate() {
            let mut y = solver.force_local(si)[Axis::Lateral];
            for &sj in &self.n_slots {
                y -= solver.hybrid(si.dof(Axis::Lateral), sj.dof(Axis::Lateral)) * solver.prescribed_value(sj, Axis::Lateral);
            }
            self.y_cur[a] = y;
        }
        self.prepare(solver);
        let cap = self.cap;
        // rhs = g - G_NN (b - f_ref_N) - G_NK (f_K - f_ref_K).
        for slot in 0..d {
            self.f_ref_lat[slot] = nodes[slot].force_ref_local_n[Axis::Lateral];
        }
        for (a, &si) in self.n_slots.iter().enumerate() {
            let (i, lat) = (si.index(), Axis::Lateral);
            let mut r = nodes[i].lateral_ref_m;
            for (c, &sc) in self.n_slots.iter().enumerate() {
                r -= self.g[i * cap + sc.index()] * (self.y_cur[c] - self.f_ref_lat[sc.index()]);
            }
            for &sk in &self.k_slots {
                r -= self.g[i * cap + sk.index()] * (solver.prescribed_value(sk, lat) - self.f_ref_lat[sk.index()]);
            }
            self.rhs[a] = r;
        }
        if nn > 0 {
            let lu = MatRef::from_column_major_slice_with_stride(&self.m[..], nn, nn, cap);
            let perm = faer::perm::PermRef::new_checked(&self.perm[..nn], &self.perm_inv[..nn], nn);
            let rhs = MatMut::from_column_major_slice_mut(&mut self.rhs[..nn], nn, 1);
            lu_solve::solve_in_place_with_conj(lu, lu, perm, Conj::No, rhs, Par::Seq, MemStack::new(&mut self.buf));
            self.apply_correction(nn);
        }
        for (a, &si) in self.n_slots.iter().enumerate() {
            solver.set_value(si, Axis::Lateral, self.rhs[a]);
        }
        solver.solve();
    }

    /// Brings the factorisation up to date with `solver`: nothing when only values changed, a
    /// low-rank correction when only pivots did (within the bound), else a new base LU.
    fn prepare(&mut self, solver: &MixedSolver) {
        let st = solver.stats();
        let structure = (st.n_rotations + st.n_added + st.n_removed + st.n_rebuilds, self.shape_version);
        if self.factored_for != Some(structure) || self.base_slots != self.n_slots {
            self.factor_base(solver, structure);
            return;
        }
        if st.n_pivots == self.corrected_for {
            return;
        }
        // S: the DOFs whose kind differs from the base's (N's lateral DOFs are unchanged here).
        let limit = self.max_low_rank.min(self.n_slots.len() / 3);
        self.s_dofs.clear();
        for k in 0..solver.n_dofs() {
            let disp = solver.condition(Slot::new(k / 2), Axis::of_index(k)) == Condition::Displacement;
            if disp != self.base_disp[k] {
                if self.s_dofs.len() == limit {
                    self.factor_base(solver, structure);
                    return;
                }
                self.s_dofs.push(k);
            }
        }
        self.build_correction(solver);
        self.corrected_for = st.n_pivots;
    }

    /// Factorises $M_0 = I + G_{NN}A$ for the current solver (the new base).
    fn factor_base(&mut self, solver: &MixedSolver, structure: (u64, u64)) {
        let (cap, nn) = (self.cap, self.n_slots.len());
        // M = I + G_NN A (column-major), the product by faer.
        for (c, &sc) in self.n_slots.iter().enumerate() {
            for (a, &sa) in self.n_slots.iter().enumerate() {
                self.g_nn[c * cap + a] = self.g[sa.index() * cap + sc.index()];
                self.a_nn[c * cap + a] = solver.hybrid(sa.dof(Axis::Lateral), sc.dof(Axis::Lateral));
                self.m[c * cap + a] = if a == c { 1.0 } else { 0.0 };
            }
        }
        faer::linalg::matmul::matmul(
            MatMut::from_column_major_slice_with_stride_mut(&mut self.m[..], nn, nn, cap),
            Accum::Add,
            MatRef::from_column_major_slice_with_stride(&self.g_nn[..], nn, nn, cap),
            MatRef::from_column_major_slice_with_stride(&self.a_nn[..], nn, nn, cap),
            1.0,
            Par::Seq,
        );
        let mat = MatMut::from_column_major_slice_with_stride_mut(&mut self.m[..], nn, nn, cap);
        let _ = lu_factor::lu_in_place(
            mat,
            &mut self.perm[..nn],
            &mut self.perm_inv[..nn],
            Par::Seq,
            MemStack::new(&mut self.buf),
            Default::default(),
        );
        self.factored_for = Some(structure);
        self.base_slots.clear();
        self.base_slots.extend_from_slice(&self.n_slots);
        for k in 0..solver.n_dofs() {
            self.base_disp[k] = solver.condition(Slot::new(k / 2), Axis::of_index(k)) == Condition::Displacement;
        }
        self.corrected_for = solver.stats().n_pivots;
        self.s_dofs.clear();
        self.stats.factorisations += 1;
    }

    /// Builds $Z = M_0^{-1}G_{NN}H_{NS}$, $V = H_{SN}$ and the LU of $C + VZ$ for the current $S$
    /// (nothing when $S$ is empty).
    fn build_correction(&mut self, solver: &MixedSolver) {
        let (cap, nn, r) = (self.cap, self.n_slots.len(), self.s_dofs.len());
        if r == 0 {
            return;
        }
        let lat = Axis::Lateral;
        // Z = G_NN U, column by column: Z[:, c] = sum_b G_NN[:, b] H[N_b, s_c].
        for (c, &sc) in self.s_dofs.iter().enumerate() {
            let zc = &mut self.z[c * cap..c * cap + nn];
            zc.fill(0.0);
            for (b, &sb) in self.n_slots.iter().enumerate() {
                let h = solver.hybrid(sb.dof(lat), sc);
                if h != 0.0 {
                    for (za, &ga) in zc.iter_mut().zip(&self.g_nn[b * cap..b * cap + nn]) {
                        *za += ga * h;
                    }
                }
            }
            for (b, &sb) in self.n_slots.iter().enumerate() {
                self.v_sn[c * cap + b] = solver.hybrid(sc, sb.dof(lat));
            }
        }
        // Z = M_0^-1 (G_NN U).
        let lu = MatRef::from_column_major_slice_with_stride(&self.m[..], nn, nn, cap);
        let perm = faer::perm::PermRef::new_checked(&self.perm[..nn], &self.perm_inv[..nn], nn);
        let zm = MatMut::from_column_major_slice_with_stride_mut(&mut self.z[..], nn, r, cap);
        lu_solve::solve_in_place_with_conj(lu, lu, perm, Conj::No, zm, Par::Seq, MemStack::new(&mut self.buf));
        // The capacitance C + V Z (column-major, leading dimension MAX_LOW_RANK), factorised.
        let ld = MAX_LOW_RANK;
        for j in 0..r {
            for i in 0..r {
                let vz: f64 = self.v_sn[i * cap..i * cap + nn].iter().zip(&self.z[j * cap..j * cap + nn]).map(|(v, z)| v * z).sum();
                self.cap_lu[j * ld + i] = solver.hybrid(self.s_dofs[i], self.s_dofs[j]) + vz;
            }
        }
        let mat = MatMut::from_column_major_slice_with_stride_mut(&mut self.cap_lu[..], r, r, ld);
        let _ = lu_factor::lu_in_place(
            mat,
            &mut self.cap_perm[..r],
            &mut self.cap_perm_inv[..r],
            Par::Seq,
            MemStack::new(&mut self.buf),
            Default::default(),
        );
        self.stats.low_rank_updates += 1;
    }

    /// `rhs` (already $z = M_0^{-1}r$) becomes $M^{-1}r = z - Z(C + VZ)^{-1}Vz$.
    fn apply_correction(&mut self, nn: usize) {
        let (cap, r) = (self.cap, self.s_dofs.len());
        if r == 0 {
            return;
        }
        for i in 0..r {
            self.w[i] = self.v_sn[i * cap..i * cap + nn].iter().zip(&self.rhs[..nn]).map(|(v, z)| v * z).sum();
        }
        let ld = MAX_LOW_RANK;
        let lu = MatRef::from_column_major_slice_with_stride(&self.cap_lu[..], r, r, ld);
        let perm = faer::perm::PermRef::new_checked(&self.cap_perm[..r], &self.cap_perm_inv[..r], r);
        let w = MatMut::from_column_major_slice_mut(&mut self.w[..r], r, 1);
        lu_solve::solve_in_place_with_conj(lu, lu, perm, Conj::No, w, Par::Seq, MemStack::new(&mut self.buf));
        for (c, &wc) in self.w[..r].iter().enumerate() {
            for (x, &zc) in self.rhs[..nn].iter_mut().zip(&self.z[c * cap..c * cap + nn]) {
                *x -= zc * wc;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn needle(ei: f64, n: usize) -> FlexibleNeedle {
        FlexibleNeedle { length_m: 0.1, flexural_rigidity_nm2: ei, n_links: n, bevel_force_ratio: 0.0, bevel_side: 1.0 }
    }

    #[test]
    fn small_tip_load_matches_cantilever_formula_and_compliance() {
        // Tip deflection P L^3 / 3EI; the discrete beam converges at O(h^2).
        let (ei, l, p) = (0.03, 0.1, 1e-4);
        let mut errs = Vec::new();
        for n in [20, 40, 80] {
            let mut c = NeedleCurve::new(&needle(ei, n), BasePose::new(0.0, 0.0, 0.0), 8);
            assert!(c.update_shape([(l, [0.0, p])].into_iter(), false));
            let exact = p * l.powi(3) / (3.0 * ei);
            errs.push((c.tip_m()[1] - exact).abs() / exact);
            // The linearised compliance agrees with the (nearly linear) response.
            let g = c.compliance(l, 0.0, l, 0.0);
            assert!((g * p - c.tip_m()[1]).abs() < 1e-6 * exact, "n={n}");
        }
        assert!(errs[2] < 1e-3 && errs[1] / errs[2] > 3.5, "{errs:?}");
        // A load at mid-length: w(L) = P a^2 (3L - a) / 6EI with a = L/2.
        let mut c = NeedleCurve::new(&needle(ei, 80), BasePose::new(0.0, 0.0, 0.0), 8);
        c.update_shape([(0.05, [0.0, p])].into_iter(), false);
        let exact = p * 0.05f64.powi(2) * (3.0 * l - 0.05) / (6.0 * ei);
        assert!((c.tip_m()[1] - exact).abs() < 2e-3 * exact);
        // Symmetry of G for points on different links, and rotation invariance.
        let g12 = c.compliance(0.03, 0.0, 0.08, 0.0);
        let g21 = c.compliance(0.08, 0.0, 0.03, 0.0);
        assert!((g12 - g21).abs() < 1e-15 * g12.abs().max(1.0));
    }

    #[test]
    fn large_tip_load_matches_the_elastica() {
        // Cantilever with a dead tip load perpendicular to the undeformed axis, P L^2 / EI = 1:
        // tip deflection 0.30172 L and axial shortening 0.05643 L (Bisshopp & Drucker 1945).
        let (ei, l) = (0.03, 0.1);
        let p = ei / (l * l);
        let mut c = NeedleCurve::new(&needle(ei, 200), BasePose::new(0.01, -0.02, 0.7), 8);
        let (t, n) = (c.base().axis(), c.base().normal());
        // Load stepping, as the simulation does tick by tick.
        for step in 1..=20 {
            let f = p * step as f64 / 20.0;
            assert!(c.update_shape([(l, [f * n[0], f * n[1]])].into_iter(), false));
        }
        let tip = c.tip_m();
        let d = [tip[0] - 0.01, tip[1] + 0.02];
        let lateral = d[0] * n[0] + d[1] * n[1];
        let axial = d[0] * t[0] + d[1] * t[1];
        assert!((lateral / l - 0.30172).abs() < 5e-4, "lateral {}", lateral / l);
        assert!((1.0 - axial / l - 0.05643).abs() < 5e-4, "shortening {}", 1.0 - axial / l);
    }

    /// The tangent compliance is the derivative of the settled shape: a small extra lateral
    /// load at point j moves point i by G_ij times it, with 0.4 N of axial follower load on a thin
    /// needle (where the geometric stiffness changes G by tens of per cent).
    #[test]
    fn tangent_compliance_matches_finite_differences_of_the_shape() {
        let ei = 0.0022;
        let pts = [(0.04, 0.0), (0.07, 0.0), (0.1, 0.0)];
        let base_loads = [(0.04, [-0.1, 0.02]), (0.07, [-0.1, -0.01]), (0.1, [-0.2, 0.03])];
        let settle = |extra: Option<(usize, f64)>| {
            let mut c = NeedleCurve::new(&needle(ei, 50), BasePose::new(0.0, 0.0, 0.0), 8);
            for step in 1..=10 {
                let a = step as f64 / 10.0;
                let loads = base_loads.iter().enumerate().map(|(k, &(s, f))| {
                    let add = extra.filter(|e| e.0 == k).map_or(0.0, |e| e.1);
                    (s, [a * f[0], a * f[1] + add])
                });
                assert!(c.update_shape(loads, true));
            }
            c
        };
        let mut c0 = settle(None);
        // Frames along the settled shape, loads in those frames.
        let points: Vec<(f64, f64)> = pts.iter().map(|&(s, _)| (s, c0.link_rad[c0.link_of(s)])).collect();
        let mut g = [0.0; 9];
        c0.tangent_compliance_into(&points, &base_loads, &mut g, 3);
        let mut g_plain = [0.0; 9];
        for i in 0..3 {
            for j in 0..3 {
                g_plain[i * 3 + j] = c0.compliance(points[i].0, points[i].1, points[j].0, points[j].1);
            }
        }
        let eps = 1e-5;
        for j in 0..3 {
            let c1 = settle(Some((j, eps)));
            for i in 0..3 {
                let (p0, p1) = (c0.point_at(points[i].0), c1.point_at(points[i].0));
                let nrm = [-points[i].1.sin(), points[i].1.cos()];
                let fd = ((p1[0] - p0[0]) * nrm[0] + (p1[1] - p0[1]) * nrm[1]) / eps;
                let (gt, gp) = (g[i * 3 + j], g_plain[i * 3 + j]);
                println!("G[{i}][{j}]: tangent {gt:.6e}, plain {gp:.6e}, finite difference {fd:.6e}");
                assert!(
                    (gt - fd).abs() < 2e-3 * fd.abs().max(1e-3 * g[8].abs()),
                    "G[{i}][{j}]: tangent {gt:.6e}, plain {gp:.6e}, finite difference {fd:.6e}"
                );
            }
        }
        // The axial load matters here: the plain compliance is off by more than 5 %.
        assert!((g_plain[8] - g[8]).abs() > 0.05 * g[8].abs(), "plain {} tangent {}", g_plain[8], g[8]);
    }

    #[test]
    fn moving_the_base_moves_the_shape_rigidly() {
        let mut c = NeedleCurve::new(&needle(0.03, 50), BasePose::new(0.0, 0.0, 0.0), 8);
        c.update_shape([(0.1, [0.0, 0.5])].into_iter(), false);
        let before = c.tip_m();
        c.set_base(BasePose::new(0.01, 0.02, std::f64::consts::FRAC_PI_2));
        let after = c.tip_m();
        // Rotated by 90° about the base, then translated.
        assert!((after[0] - (0.01 - before[1])).abs() < 1e-15 && (after[1] - (0.02 + before[0])).abs() < 1e-15);
        let (s, lat) = c.frame_coords(0.1, c.tip_angle_rad(), after);
        assert!((s - 0.1).abs() < 1e-15 && lat.abs() < 1e-15);
    }

    /// The coupled solve with low-rank corrections after pivots equals the one that refactorises
    /// after every pivot: an oblique needle through the strain square, its nodes' axial
    /// conditions switched at random (stick/slip; some slots with a prescribed lateral force,
    /// like a bevel tip), a coupled solve after each change, compared slot by slot relative to
    /// the largest displacement and force, to $4\sqrt{n}\,\kappa(M)\,\epsilon$ (the accuracy either
    /// path can have; measured up to $1.4\,\kappa\epsilon$); corrections stand in for most
    /// factorisations, and a set of pivots past the bound refactorises.
    #[test]
    fn low_rank_corrections_equal_refactorising() {
        use crate::compliance::ComplianceCache;
        use crate::ids::NodeIdx;
        use rand::rngs::SmallRng;
        use rand::{Rng, SeedableRng};
        let model = crate::fixtures::strain_square(25);
        let mut cache = ComplianceCache::new(model.mesh().n_nodes());
        let mut scratch = model.column_scratch();
        let mut f = FlexibleNeedle::gauge17_steel(0.2);
        f.flexural_rigidity_nm2 *= 0.1;
        // An oblique needle (no symmetry decouples its lateral and axial DOFs), with the nodes
        // within 2.5 mm of its line below the surface as its working set.
        let angle = -1.2f64;
        let (t, nrm) = ([angle.cos(), angle.sin()], [-angle.sin(), angle.cos()]);
        let base = BasePose::new(0.05 - 0.05 * t[0], 0.1 - 0.05 * t[1], angle);
        let mut curve = NeedleCurve::new(&f, base, 64);
        let mut rng = SmallRng::seed_from_u64(7);
        let mut s = MixedSolver::with_capacity(64);
        let mut nodes = Vec::new();
        for n in 0..model.mesh().n_nodes() {
            let x = model.mesh().nodes_m()[n];
            let d = [x[0] - base.x_m, x[1] - base.y_m];
            let (along, across) = (t[0] * d[0] + t[1] * d[1], nrm[0] * d[0] + nrm[1] * d[1]);
            if model.is_fixed(n) || across.abs() > 2.5e-3 || s.n_nodes() == 64 {
                continue;
            }
            cache.ensure(&model, n, &mut scratch).unwrap();
            let slot = s.add_node(&cache, NodeIdx(n), angle).unwrap();
            nodes.push(CoupledNode { s_m: along, lateral_ref_m: rng.random_range(-1e-4..1e-4), force_ref_local_n: [0.0; 2] });
            if slot.index() % 7 != 3 {
                s.set_condition(slot, Axis::Lateral, Condition::Displacement, 0.0).unwrap();
            } else {
                s.set_condition(slot, Axis::Lateral, Condition::Force, rng.random_range(-0.01..0.01)).unwrap();
            }
            s.set_condition(slot, Axis::Axial, Condition::Force, rng.random_range(-0.01..0.01)).unwrap();
        }
        let m = s.n_nodes();
        let n_lateral = Slot::all(m).filter(|&k| s.condition(k, Axis::Lateral) == Condition::Displacement).count();
        let (mut fast, mut reference) = (Coupling::new(64), Coupling::new(64));
        reference.set_max_low_rank(0);
        fast.update_compliance(&mut curve, &s, &nodes);
        reference.update_compliance(&mut curve, &s, &nodes);
        let mut r = s.clone();
        let mut worst: f64 = 0.0;
        for step in 0..600 {
            let slot = Slot::new(rng.random_range(0..m));
            match rng.random_range(0..4) {
                0 | 1 => {
                    // Stick or slip: the axial condition switches (a rank-one change of H).
                    let cond = match s.condition(slot, Axis::Axial) {
                        Condition::Force => Condition::Displacement,
                        Condition::Displacement => Condition::Force,
                    };
                    let v = if cond == Condition::Displacement { rng.random_range(-1e-4..1e-4) } else { rng.random_range(-0.01..0.01) };
                    s.set_condition(slot, Axis::Axial, cond, v).unwrap();
                    r.set_condition(slot, Axis::Axial, cond, v).unwrap();
                }
                2 => {
                    let v = rng.random_range(-0.01..0.01);
                    if s.condition(slot, Axis::Axial) == Condition::Force {
                        s.set_value(slot, Axis::Axial, v);
                        r.set_value(slot, Axis::Axial, v);
                    }
                }
                _ => {
                    // Several pivots at once, sometimes more than the bound.
                    for _ in 0..rng.random_range(1..12) {
                        let k = Slot::new(rng.random_range(0..m));
                        let cond = match s.condition(k, Axis::Axial) {
                            Condition::Force => Condition::Displacement,
                            Condition::Displacement => Condition::Force,
                        };
                        s.set_condition(k, Axis::Axial, cond, 0.0).unwrap();
                        r.set_condition(k, Axis::Axial, cond, 0.0).unwrap();
                    }
                }
            }
            fast.solve(&mut s, &nodes);
            reference.solve(&mut r, &nodes);
            let (mut du, mut df, mut su, mut sf): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
            for k in Slot::all(m) {
                for c in 0..2 {
                    du = du.max((s.displacement_local(k)[c] - r.displacement_local(k)[c]).abs());
                    df = df.max((s.force_local(k)[c] - r.force_local(k)[c]).abs());
                    su = su.max(r.displacement_local(k)[c].abs());
                    sf = sf.max(r.force_local(k)[c].abs());
                }
            }
            let e = (du / su).max(df / sf);
            // The condition number of M = I + G_NN A: the accuracy either path can have.
            let lat: Vec<usize> = reference.n_slots.iter().map(|k| k.index()).collect();
            let mm = faer::Mat::<f64>::from_fn(lat.len(), lat.len(), |i, j| {
                let ga: f64 = lat.iter().map(|&b| reference.g[lat[i] * reference.cap + b] * r.hybrid(2 * b + 1, 2 * lat[j] + 1)).sum();
                ga + if i == j { 1.0 } else { 0.0 }
            });
            let sv = mm.singular_values().unwrap();
            let kappa = sv[0] / sv[sv.len() - 1];
            worst = worst.max(e / (kappa * f64::EPSILON));
            let tol = 4.0 * (n_lateral as f64).sqrt() * kappa * f64::EPSILON;
            assert!(e < tol, "step {step}: relative difference {e:e}, tolerance {tol:e} (condition number {kappa:e}; {:?})", fast.stats());
        }
        let (fs, rs) = (fast.stats(), reference.stats());
        println!("worst relative difference / (kappa eps) {worst:e}; {n_lateral} lateral unknowns; corrected {fs:?}, reference {rs:?}");
        assert!(fs.low_rank_updates > 200, "{fs:?}");
        assert!(fs.factorisations > 5 && 4 * fs.factorisations < rs.factorisations, "{fs:?} vs {rs:?}");
        assert_eq!(rs.low_rank_updates, 0);
    }
}
