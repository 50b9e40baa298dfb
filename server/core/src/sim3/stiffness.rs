//! The stiffness of the base wrench with respect to the base pose ([`WrenchStiffness3`],
//! [`Simulation3::wrench_stiffness`]): the $6 \times 6$ Jacobian $K = \partial w / \partial q$ a
//! haptic device's local model extrapolates the wrench with between ticks.
//!
//! **The frozen problem.** The active set of the last step is held: a stuck point keeps $u_t$
//! prescribed at its shaft anchor $s_a$ (the tip's point at $L$), a slipping point keeps its axial
//! force $f_t = \sigma\varphi$, and every point keeps $u_n$, $u_b$ prescribed. The wrench on the
//! base (world, as [`StepOutput3`](super::StepOutput3) defines it)
//! $$F = -\sum_i f_i,\qquad \tau = \sum_i r_i \times (-f_i),\qquad r_i = x_i - x_b = X_i + u_i - x_b,$$
//! is then a smooth function of the base pose $q = (x_b, \theta)$, with $\theta$ a small rotation
//! vector in world applied as $R \leftarrow \exp(\hat\theta) R$ about the base point, so that every
//! frame row $e_a \in \{t, n, b\}$ moves by $\delta e_a = \theta \times e_a$. Columns of $K$ are in
//! N/m (position) and N/rad (rotation) for the force rows, N (position) and N·m/rad (rotation)
//! for the torque rows.
//!
//! **Derivation.** Write $W$ for the world working compliance ($u_i = \sum_j W_{ij} f_j$, the
//! tissue does not turn) and $f_i = \sum_a e_a \varphi_{ia}$ with the local components
//! $\varphi$. A local DOF $k = (i, a)$ has either a prescribed displacement ($k \in P$:
//! $e_a \cdot u_i = g_k$) or a prescribed force ($k \in F$: $\varphi_k$ fixed). The prescribed
//! values are $g_k = c_k - e_a \cdot (X_i - x_b)$ with $c_k \in \{0, s_a, L\}$ constant, so
//! $$\delta g_k = e_a \cdot \delta x_b - (\theta \times e_a)\cdot(X_i - x_b).$$
//! Differentiating $f_i = \sum_a e_a\varphi_{ia}$ with $\delta\varphi_F = 0$:
//! $$\delta f_i = \theta \times f_i + \sum_{a \in P_i} e_a\,\delta\varphi_{ia}.$$
//! Differentiating the condition $e_a \cdot \sum_j W_{ij} f_j = g_k$ ($k \in P$), with
//! $(\theta\times e_a)\cdot u_i = -e_a \cdot (\theta \times u_i)$ and $g = \theta \times f$
//! (per point):
//! $$\sum_{l \in P} C_{kl}\,\delta\varphi_l = \delta g_k - (\theta \times e_a)\cdot u_i - e_a \cdot (W g)_i
//! = e_a \cdot \big(\delta x_b + \theta \times r_i - (W g)_i\big) =: \rho_k,$$
//! with $C_{PP} = E_P^\top W E_P$ the local compliance on $P$. The mixed solver's hybrid matrix holds
//! $H_{PP} = C_{PP}^{-1}$ ([`crate::mixed`]), so
//! $$\delta\varphi_P = H_{PP}\,\rho_P,\qquad \delta u = W\,\delta f,$$
//! and the wrench moves by
//! $$\delta F = -\sum_i \delta f_i,\qquad
//! \delta\tau = \sum_i (\delta u_i - \delta x_b) \times (-f_i) + r_i \times (-\delta f_i).$$
//! The term $\theta \times r_i$ is the rigid motion of the shaft point, $(W g)_i$ the tissue's
//! answer to the forces turning with the frame (the slipping friction and the reactions), and
//! $\delta u_i - \delta x_b$ the motion of the lever arm, both its ends.
//!
//! **Flexible needle.** The held points sit on the rod, which bends under their forces: the
//! coupled solve prescribes $e_a\cdot u_i = g_k - \sum_{l} G_{kl}\,(\varphi_l - \varphi^{ref}_l)$
//! on the lateral DOFs (`sim3/flex.rs`: $g_k = e_a\cdot(c_i - X_i)$, $c_i$ the point's place on
//! the rod, $G$ the rod's tangent lateral compliance between the points' $n$, $b$, the
//! reference forces held in the points' frames). The clamp moves the rod as
//! [`crate::rod3::Rod3::set_base`] does: the swing $\theta_\perp = \theta - \phi\,t$ (across the
//! base axis $t$) carries the shape rigidly, $\delta c_i = \delta x_b + \theta_\perp\times(c_i - x_b)$;
//! the roll $\phi = \theta\cdot t$ leaves the centreline where it is and turns every frame about
//! its own tangent $t_i$ (torsionally rigid). So each point's frame turns by
//! $\Omega_i = \theta_\perp + \phi\,t_i$ ($= \theta$ for a straight rod), $g = \Omega_i\times f_i$,
//! $$\rho_k = (\Omega_i\times e_a)\cdot(c_i - x_i) + e_a\cdot\big(\delta x_b + \theta_\perp\times(c_i - x_b) - (W g)_i\big)$$
//! (the rigid needle's $\rho_k$ when $c_i$ lies on the axis), and the rod's bending enters
//! through $G$ — rod and tissue in series:
//! $$(C_{PP} + \tilde G_{PP})\,\delta\varphi_P = \rho_P,\qquad
//! \delta\varphi_P = (I + H_{PP}\tilde G_{PP})^{-1} H_{PP}\,\rho_P,$$
//! $\tilde G$ being $G$ on the lateral DOFs of $P$ and zero on the axial ones (the rod is
//! inextensible); $G$ changes with the pose only at second order ($\varphi = \varphi^{ref}$ at a
//! settled state). A bevel's tip force is a follower load, turning with the frames like the
//! slipping friction. The derivative reads the solver's frames, which the step turns to the
//! rod's only past [`super::FLEX_FRAME_TOL`]: against the re-solve (which turns them exactly) it
//! agrees to about that lag (tested). One LU of $I + H_{PP}\tilde G_{PP}$ per call,
//! $O(|P|^3)$, and $G$, $O(N d + d^2)$, in scratch of $(2\,m_{max})^2 + (3\,m_{max})^2$ more
//! doubles for a flexible needle.
//!
//! **Properties** (tested): the force–position block is
//! $\partial F / \partial x_b = -E_P H_{PP} E_P^\top$, symmetric and negative semidefinite
//! whatever the active set; a roll about the needle axis ($\theta = t$) changes nothing
//! ($g$ has no axial part, so $g = E_P\psi_P$, $\rho_P = -C_{PP}\psi_P$, $\delta f = 0$): the column
//! $K[:, 3..6]\,t$ vanishes; with no axial displacement prescribed (every point slipping) an
//! axial push moves nothing but the lever arm's base: $K\,(t, 0) = (0,\ t \times \sum_i f_i)$.
//!
//! **Cost.** One call assembles $W$ ($m^2$ blocks of $3 \times 3$ from the working points'
//! cached node columns, sixteen node blocks each) and, per column of $K$, two products with $W$
//! and one with $H_{PP}$: $O(d^2)$ for $d = 3m$, in scratch sized in
//! [`Simulation3::new`] ($(3\,m_{max})^2$ doubles for $W$, as much as the solver's $H$): a warm
//! call allocates nothing. The compliance is read through `targets::point_block` (one routing point, [`crate::sim3::targets`]).

use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedError};

use super::{BasePose3, PointState3, SimError3, Simulation3, add, cross, dot, sub};

/// The stiffness of the base wrench $w = (F, \tau)$ with respect to the base pose
/// $q = (x_b, \theta)$ (module docs): `matrix[r][c]` $= \partial w_r / \partial q_c$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WrenchStiffness3 {
    /// Rows $F_x, F_y, F_z, \tau_x, \tau_y, \tau_z$; columns $x, y, z$ of the base position (m)
    /// and of the rotation vector (rad), world.
    pub matrix: [[f64; 6]; 6],
}

impl WrenchStiffness3 {
    /// The $3 \times 3$ block $\partial F / \partial x_b$ (N/m), what a 3-DOF (position) device's
    /// local model needs: $F(x_b + \delta) \approx F + K_{Fx}\,\delta$.
    pub fn force_position(&self) -> [[f64; 3]; 3] {
        self.block(0, 0)
    }
    /// $\partial F / \partial\theta$ (N/rad).
    pub fn force_rotation(&self) -> [[f64; 3]; 3] {
        self.block(0, 3)
    }
    /// $\partial \tau / \partial x_b$ (N).
    pub fn torque_position(&self) -> [[f64; 3]; 3] {
        self.block(3, 0)
    }
    /// $\partial \tau / \partial\theta$ (N·m/rad).
    pub fn torque_rotation(&self) -> [[f64; 3]; 3] {
        self.block(3, 3)
    }
    fn block(&self, r0: usize, c0: usize) -> [[f64; 3]; 3] {
        std::array::from_fn(|r| std::array::from_fn(|c| self.matrix[r0 + r][c0 + c]))
    }
    /// The wrench change $K\,\delta q$ for a pose change $\delta q = (\delta x_b, \theta)$.
    pub fn apply(&self, dq: [f64; 6]) -> [f64; 6] {
        std::array::from_fn(|r| (0..6).map(|c| self.matrix[r][c] * dq[c]).sum())
    }
}

/// The per-call storage of [`Simulation3::wrench_stiffness`], sized once for the working-set
/// capacity.
#[derive(Debug, Clone)]
pub(super) struct StiffnessScratch {
    /// World working compliance $W$, row-major, stride $d$ of the call.
    w: Vec<f64>,
    /// The displacement-prescribed local DOFs, increasing.
    p_dofs: Vec<usize>,
    /// Per point (3 each): $g = \theta \times f$, $W g$, $\delta f$, $\delta u$.
    g: Vec<f64>,
    wg: Vec<f64>,
    df: Vec<f64>,
    du: Vec<f64>,
    /// $\rho_P$ and $\delta\varphi_P$.
    rho: Vec<f64>,
    dphi: Vec<f64>,
    /// Per point: $f_i$, $r_i$, frame.
    f: Vec<[f64; 3]>,
    r: Vec<[f64; 3]>,
    frame: Vec<[[f64; 3]; 3]>,
    /// A flexible needle's: the rod's $G$ (stride $2\,$cap), $I + H_{PP}\tilde G_{PP}$ and its
    /// LU's row swaps (empty for a rigid needle).
    g_rod: Vec<f64>,
    m: Vec<f64>,
    piv: Vec<usize>,
    /// A flexible needle's: each point's reference point on the rod, $c(s_i)$.
    c: Vec<[f64; 3]>,
}

impl StiffnessScratch {
    pub(super) fn with_capacity(cap_points: usize, flexible: bool) -> Self {
        let d = 3 * cap_points;
        let (g_len, m_len, piv_len) = if flexible { (4 * cap_points * cap_points, d * d, d) } else { (0, 0, 0) };
        Self {
            w: vec![0.0; d * d],
            p_dofs: Vec::with_capacity(d),
            g: vec![0.0; d],
            wg: vec![0.0; d],
            df: vec![0.0; d],
            du: vec![0.0; d],
            rho: vec![0.0; d],
            dphi: vec![0.0; d],
            f: vec![[0.0; 3]; cap_points],
            r: vec![[0.0; 3]; cap_points],
            frame: vec![[[0.0; 3]; 3]; cap_points],
            g_rod: vec![0.0; g_len],
            m: vec![0.0; m_len],
            piv: vec![0; piv_len],
            c: vec![[0.0; 3]; if flexible { cap_points } else { 0 }],
        }
    }
}

/// Factorises the row-major `n × n` matrix `a` in place as $P A = L U$ (partial pivoting; `L`
/// unit lower, below the diagonal; `piv[p]` the row swapped with row `p` at step `p`). Returns
/// the smallest pivot's magnitude relative to the largest entry (0 for a singular matrix).
fn lu_factor(a: &mut [f64], piv: &mut [usize], n: usize) -> f64 {
    let scale = a[..n * n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut smallest = f64::INFINITY;
    for p in 0..n {
        let mut best = p;
        for r in p + 1..n {
            if a[r * n + p].abs() > a[best * n + p].abs() {
                best = r;
            }
        }
        piv[p] = best;
        if best != p {
            for c in 0..n {
                a.swap(p * n + c, best * n + c);
            }
        }
        let d = a[p * n + p];
        smallest = smallest.min(d.abs());
        if d == 0.0 {
            continue;
        }
        for r in p + 1..n {
            let f = a[r * n + p] / d;
            a[r * n + p] = f;
            if f != 0.0 {
                for c in p + 1..n {
                    a[r * n + c] -= f * a[p * n + c];
                }
            }
        }
    }
    if n == 0 { 1.0 } else { smallest / scale.max(f64::MIN_POSITIVE) }
}

/// Solves $A x = b$ in place (`b` becomes `x`) with [`lu_factor`]'s factors.
fn lu_solve(a: &[f64], piv: &[usize], b: &mut [f64], n: usize) {
    for p in 0..n {
        b.swap(p, piv[p]);
    }
    for r in 0..n {
        let mut v = b[r];
        for c in 0..r {
            v -= a[r * n + c] * b[c];
        }
        b[r] = v;
    }
    for r in (0..n).rev() {
        let mut v = b[r];
        for c in r + 1..n {
            v -= a[r * n + c] * b[c];
        }
        b[r] = v / a[r * n + r];
    }
}

/// `out = W v` for the first `d` entries ($W$ row-major with stride `d`).
fn mat_vec(w: &[f64], d: usize, v: &[f64], out: &mut [f64]) {
    for (i, o) in out[..d].iter_mut().enumerate() {
        *o = w[i * d..(i + 1) * d].iter().zip(&v[..d]).map(|(a, b)| a * b).sum();
    }
}

impl Simulation3 {
    /// The stiffness of the base wrench with respect to the base pose at the state of the last
    /// step, with its active set frozen (derivation in [`crate::sim3::stiffness`]). $O(d^2)$;
    /// allocates nothing.
    ///
    /// Errors: [`SimError3::Mixed`] with [`MixedError::NotCached`] when a working point's node
    /// columns are no longer cached (not expected: the cache never evicts the nodes the last
    /// step used).
    pub fn wrench_stiffness(&mut self) -> Result<WrenchStiffness3, SimError3> {
        let m = self.solver.n_nodes();
        let d = 3 * m;
        let base = self.pose.position_m;
        let frame0 = self.pose.frame();
        let scale = self.setup.compliance_scale;
        let s = &mut self.stiffness;
        let solver = &self.solver;
        let contacts = solver.contacts();
        // The state: forces, lever arms, frames; W; the prescribed DOFs.
        for slot in Slot::all(m) {
            let i = slot.index();
            let f = solver.force_world(slot);
            let u = solver.displacement_world(slot);
            s.f[i] = f;
            s.r[i] = sub(add(self.pts[i].x_kin_m(), u), base);
            s.frame[i] = solver.frame(slot);
        }
        for a in 0..m {
            for b in 0..m {
                let blk = super::targets::point_block(&self.cache, &contacts[a], &contacts[b])
                    .ok_or(MixedError::NotCached { contact: contacts[b].id() })?;
                // The working solver's blocks: $W/\gamma$ in a viscoelastic tissue (a tick's
                // instantaneous stiffness, [`crate::viscous`]); as they are when elastic.
                let blk = if scale == 1.0 { blk } else { blk.map(|row| row.map(|x| x * scale)) };
                for (r, row) in blk.iter().enumerate() {
                    s.w[(3 * a + r) * d + 3 * b..(3 * a + r) * d + 3 * b + 3].copy_from_slice(row);
                }
            }
        }
        s.p_dofs.clear();
        for k in 0..d {
            if solver.condition(Slot::new(k / 3), Axis::of_local_dof::<3>(k)) == Condition::Displacement {
                s.p_dofs.push(k);
            }
        }
        let np = s.p_dofs.len();
        // A flexible needle: the rod in series (module docs), M = I + H_PP G̃_PP factorised once.
        let flexible = match self.flex.as_mut() {
            None => false,
            Some(fx) => {
                for (i, p) in self.pts.iter().enumerate() {
                    s.c[i] = fx.rod.point_at(fx.s_ref(p));
                }
                fx.compliance_into(solver, &self.pts, &mut s.g_rod);
                let stride = fx.compliance_stride();
                // G̃ between local DOFs k = 3i + a and l = 3j + b: G's lateral DOFs 2i + a − 1.
                let g_rod = &s.g_rod;
                let lateral = |k: usize| Axis::of_local_dof::<3>(k) != Axis::Axial;
                let gt = |k: usize, l: usize| {
                    if lateral(k) && lateral(l) { g_rod[(2 * (k / 3) + k % 3 - 1) * stride + 2 * (l / 3) + l % 3 - 1] } else { 0.0 }
                };
                for q in 0..np {
                    let k = s.p_dofs[q];
                    for r in 0..np {
                        let l = s.p_dofs[r];
                        let mut v = if q == r { 1.0 } else { 0.0 };
                        for &e in &s.p_dofs {
                            if lateral(e) {
                                v += solver.hybrid(k, e) * gt(e, l);
                            }
                        }
                        s.m[q * np + r] = v;
                    }
                }
                let conditioning = lu_factor(&mut s.m[..np * np], &mut s.piv[..np], np);
                if !(conditioning > 1e-14) {
                    return Err(SimError3::SingularRodCoupling { tick: self.tick, pivot: conditioning });
                }
                true
            }
        };
        let mut matrix = [[0.0; 6]; 6];
        for c in 0..6 {
            let mut dx = [0.0; 3];
            let mut theta = [0.0; 3];
            if c < 3 {
                dx[c] = 1.0;
            } else {
                theta[c - 3] = 1.0;
            }
            let rotating = c >= 3;
            // Each point's frame turns by Ω_i: θ for a rigid needle; for a flexible one the
            // swing θ_⊥ and the roll φ about the point's own tangent (module docs).
            let axis = frame0[0];
            let roll = dot(theta, axis);
            let swing = sub(theta, axis.map(|v| roll * v));
            let omega = |i: usize| if flexible { add(swing, s.frame[i][0].map(|v| roll * v)) } else { theta };
            // g = Ω × f and W g.
            for i in 0..m {
                let g = cross(omega(i), s.f[i]);
                s.g[3 * i..3 * i + 3].copy_from_slice(&g);
            }
            if rotating {
                mat_vec(&s.w, d, &s.g, &mut s.wg);
            } else {
                s.wg[..d].fill(0.0);
            }
            // ρ_P, δφ_P = H_PP ρ_P.
            for (q, &k) in s.p_dofs.iter().enumerate() {
                let i = k / 3;
                let e = s.frame[i][k % 3];
                let wg = [s.wg[3 * i], s.wg[3 * i + 1], s.wg[3 * i + 2]];
                s.rho[q] = if flexible {
                    // (Ω_i × e)·(c_i − x_i) + e·(δx_b + θ_⊥ × (c_i − x_b) − (W g)_i).
                    let c_rel = sub(s.c[i], base);
                    dot(cross(omega(i), e), sub(c_rel, s.r[i])) + dot(e, sub(add(dx, cross(swing, c_rel)), wg))
                } else {
                    dot(e, sub(add(dx, cross(theta, s.r[i])), wg))
                };
            }
            for q in 0..np {
                let k = s.p_dofs[q];
                s.dphi[q] = s.p_dofs.iter().zip(&s.rho[..np]).map(|(&l, &rho)| solver.hybrid(k, l) * rho).sum();
            }
            if flexible {
                lu_solve(&s.m[..np * np], &s.piv[..np], &mut s.dphi[..np], np);
            }
            // δf = g + E_P δφ_P, δu = W δf.
            s.df[..d].copy_from_slice(&s.g[..d]);
            for (q, &k) in s.p_dofs.iter().enumerate() {
                let i = k / 3;
                let e = s.frame[i][k % 3];
                for x in 0..3 {
                    s.df[3 * i + x] += e[x] * s.dphi[q];
                }
            }
            mat_vec(&s.w, d, &s.df, &mut s.du);
            // δF, δτ.
            let (mut d_force, mut d_torque) = ([0.0; 3], [0.0; 3]);
            for i in 0..m {
                let df = [s.df[3 * i], s.df[3 * i + 1], s.df[3 * i + 2]];
                let du = [s.du[3 * i], s.du[3 * i + 1], s.du[3 * i + 2]];
                let neg_f = s.f[i].map(|v| -v);
                d_force = sub(d_force, df);
                d_torque = add(d_torque, add(cross(sub(du, dx), neg_f), cross(s.r[i], df.map(|v| -v))));
            }
            for r in 0..3 {
                matrix[r][c] = d_force[r];
                matrix[3 + r][c] = d_torque[r];
            }
        }
        Ok(WrenchStiffness3 { matrix })
    }

    /// The base wrench $(F, \tau)$ of the last step's point set re-solved with its active set
    /// frozen (stuck and tip points held at their anchors, slipping points keeping their axial
    /// force, every point held across the shaft) at the base pose `pose`: what
    /// [`Simulation3::wrench_stiffness`] differentiates, for finite-difference checks. Works on a
    /// copy of the working solver (frames turned by its own updates, not the formulas above);
    /// allocates; not for the real-time thread. At the last step's pose it returns that step's
    /// wrench.
    ///
    /// Errors: [`SimError3::Pose`] for a non-finite or non-unit `pose`; [`SimError3::Mixed`]
    /// when the solver refuses the turned frames (a singular prescribed direction).
    ///
    /// A flexible needle: its rod moved with the clamp (its shape in the base frame kept), every
    /// point's frame turned to the rod's, the values put the points on it, and one coupled solve
    /// with the rod's tangent compliance at the reference forces (`sim3/flex.rs`) — the
    /// linearised equilibrium [`Self::wrench_stiffness`] differentiates; at the step's pose it
    /// differs from the step's wrench by what the step's last shape update left
    /// ([`super::SHAPE_GAP_TOL_M`] at most between points and rod).
    #[doc(hidden)]
    pub fn frozen_active_set_wrench(&self, pose: &BasePose3) -> Result<([f64; 3], [f64; 3]), SimError3> {
        pose.check().map_err(|source| SimError3::Pose { tick: self.tick, source })?;
        let mut solver = self.solver.clone();
        let frame = pose.frame();
        let base = pose.position_m;
        let len = self.params.needle_length_m;
        let mut pts = self.pts.clone();
        if let Some(fx) = &self.flex {
            let mut fx = fx.clone();
            fx.rod.set_base(base, frame);
            fx.refresh_frames(&mut solver, &pts, true)?;
            fx.set_values(&mut solver, &mut pts);
            fx.solve(&mut solver, &pts, self.tick);
        }
        for slot in Slot::all(self.pts.len()).filter(|_| self.flex.is_none()) {
            solver.set_frame(slot, frame)?;
            let p = &self.pts[slot.index()];
            let dref = sub(p.x_kin_m(), base);
            solver.set_value(slot, Axis::Lateral, -dot(frame[1], dref));
            solver.set_value(slot, Axis::Binormal, -dot(frame[2], dref));
            match p.state {
                PointState3::Stuck => solver.set_value(slot, Axis::Axial, p.anchor_s_m - dot(frame[0], dref)),
                PointState3::Tip => solver.set_value(slot, Axis::Axial, len - dot(frame[0], dref)),
                PointState3::Slipping => {}
            }
        }
        solver.solve();
        let (mut force, mut torque) = ([0.0; 3], [0.0; 3]);
        for slot in Slot::all(pts.len()) {
            let f = solver.force_world(slot);
            let x = add(pts[slot.index()].x_kin_m(), solver.displacement_world(slot));
            let neg = f.map(|v| -v);
            force = add(force, neg);
            torque = add(torque, cross(sub(x, base), neg));
        }
        Ok((force, torque))
    }
}
