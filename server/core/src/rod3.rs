//! The flexible needle in 3D: a geometrically exact, torsionally rigid discrete rod clamped at
//! the base pose, its equilibrium under point loads, and its tangent lateral compliance (two
//! lateral directions per point) for the coupling to the tissue's material points.
//!
//! **Rod.** The shaft of length $L$ is a chain of $N$ rigid links of length $h = L/N$. Link $k$
//! carries an orthonormal frame $F_k$ (rows $[t_k, n_k, b_k]$, $t_k$ along the link); $F_{-1}$ is
//! the base pose's frame. Joint $k$ sits at the proximal end $x_k$ of link $k$ ($x_0$ the clamp)
//! and turns link $k$ against link $k-1$ by two bending angles $(\alpha_k, \beta_k)$ about
//! $n_{k-1}$ and $b_{k-1}$:
//! $$R_k = R_{k-1}\,\exp([\hat v_k]_\times),\qquad \hat v_k = (0, \alpha_k, \beta_k),\qquad x_{k+1} = x_k + h\,t_k,$$
//! ($R_k = F_k^\top$). The rotation axis of every joint is perpendicular to the tangent on both
//! sides, so the frames are transported without twist (a Bishop frame): the rod is
//! torsionally rigid and its cross-section circular (bending stiffness $EI$ in every direction).
//! Under point forces $F_j$ at shaft points $p_j$ (arc lengths $s_j$ on links $m_j$) the
//! moment at joint $k$ of the distal loads is $M_k = \sum_{m_j \ge k} (p_j - x_k)\times F_j$ and
//! the equilibrium is
//! $$r_k = (\alpha_k, \beta_k) - c_k\,(n_{k-1}\cdot M_k,\ b_{k-1}\cdot M_k) = 0,\qquad c_k = w_k/EI,$$
//! $w_0 = h/2$, $w_k = h$ (the trapezoidal rule for $\kappa = M/EI$, as the 2D [`crate::beam`]).
//! The component of $M_k$ along the tangent is carried by the torsionally rigid shaft to the
//! clamp. Positions, frames and moments are evaluated on the deformed shape: large deflections
//! and rotations are exact for the discrete model, which converges to Kirchhoff's rod as
//! $h \to 0$ (in a plane, to the elastica: tested against Bisshopp & Drucker's cantilever).
//! Loads are follower loads (given in the frame of their link, turning with it, as the tissue's
//! contact forces do) or dead loads (world vectors).
//!
//! **Why torsionally rigid.** For a steel tube $GJ/EI = 1/(1+\nu) \approx 0.77$, and the
//! torsional moments a bent needle in tissue carries are of second order: the lateral contact
//! forces $f$ act on a shaft whose lateral offset from the axis through the clamp is $\delta$,
//! so $M_t \lesssim f\,\delta$. A 22-gauge needle ($EI \approx 2\times 10^{-3}$ N·m²) 0.1 m long with
//! 0.1 N of lateral force deflects about 5 mm: $M_t \lesssim 5\times 10^{-4}$ N·m, a twist
//! $M_t L / GJ \lesssim 0.03$ rad — a bevel direction off by under 2°, and for the stiffer gauges
//! and the short inserted lengths of interest far less. Rolling the base is transmitted to the
//! tip one to one (what a clinician steering a bevel needle assumes, and what Webster et al.'s
//! unicycle model assumes); torsional windup (long, thin needles in stiff tissue) is left out.
//!
//! **Equilibrium.** Newton's method on $r(\alpha, \beta) = 0$ warm-started from the current shape.
//! The Jacobian is exact: a change of joint $i$ is a rigid rotation $\Omega$ of the distal chain
//! about $x_i$, $\Omega = R_{i-1} J_l(\hat v_i)\,\delta\hat v_i$ ($J_l$ the left Jacobian of
//! $SO(3)$). With follower loads the triple products $n_{k-1}\cdot M_k$ for $k > i$ do not change
//! (frame, arms and forces turn together), so the Jacobian is block upper triangular,
//! $$\frac{\partial r_k}{\partial \hat v_i} = -c_k P_k\big(\Omega\times M_i + (x_i - x_k)\times(\Omega\times S_i)\big)\ (k < i),
//!   \qquad \frac{\partial r_k}{\partial \hat v_k} = I - c_k P_k(\Omega\times M_k),$$
//! ($P_k = [n_{k-1}; b_{k-1}]$, $S_i = \sum_{m_j \ge i} F_j$), and its solve is a back substitution
//! of $O(N)$ with suffix sums of $\Omega\times M_i + x_i\times(\Omega\times S_i)$ and
//! $\Omega\times S_i$ (as the 2D beam's). Dead loads add the terms of forces that do not turn,
//! $D_k(\Omega) = \sum_{m_j\ge k} (p_j - x_k)\times(\Omega\times F_j)$, which fill the matrix: a dense
//! LU, only used for dead loads (the closed-form tests), never by the simulation.
//!
//! **Tangent compliance.** Linearised about a settled shape, the lateral displacement of shaft
//! point $i$ along a direction $\nu_{ia}$ ($a$ = its frame's $n$ or $b$) from a (follower)
//! force along $\nu_{jb}$ at point $j$ is
//! $$G_{ia,jb} = \nu_{ia}\cdot\sum_{l \le m_i} (\Omega_l\,\delta\hat v_l)\times(p_i - x_l),\qquad J\,\delta\hat v = c\,P\,\big((p_j - x_k)\times\nu_{jb}\big)_{k \le m_j},$$
//! the 3D analogue of [`crate::beam`]'s $G = B^\top (I - C T)^{-1} C B$, including the geometric
//! stiffness of the loads the shape carries; $O(N + d)$ per column with prefix sums, $O(d(N+d))$
//! for $d$ points (two columns each). It matches central finite differences of the settled
//! shape to 1e-6 (tested).

use crate::needle::FlexibleNeedle;

/// A 3D vector.
pub type V3 = [f64; 3];
/// A frame, rows $[t, n, b]$.
pub type Frame3 = [[f64; 3]; 3];

/// Largest number of Newton iterations of a shape update.
const SHAPE_MAX_ITERATIONS: usize = 60;
/// A shape update has converged when no bending angle changes by more than this (rad).
const SHAPE_TOL_RAD: f64 = 1e-13;
/// Largest change of a bending angle per Newton iteration (rad): the step is scaled down to it
/// (a globalisation for large load increments; never active near the equilibrium).
const MAX_NEWTON_STEP_RAD: f64 = 0.2;

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(s: f64, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
fn axpy(y: &mut V3, s: f64, a: V3) {
    y[0] += s * a[0];
    y[1] += s * a[1];
    y[2] += s * a[2];
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
/// $F^\top w$: local components `w` in frame `f` to world.
fn to_world(f: &Frame3, w: V3) -> V3 {
    let mut v = scale(w[0], f[0]);
    axpy(&mut v, w[1], f[1]);
    axpy(&mut v, w[2], f[2]);
    v
}
/// $F v$: world `v` to the local components of frame `f`.
fn to_local(f: &Frame3, v: V3) -> V3 {
    [dot(f[0], v), dot(f[1], v), dot(f[2], v)]
}

/// The coefficients $(\sin\theta/\theta,\ (1-\cos\theta)/\theta^2,\ (\theta - \sin\theta)/\theta^3)$
/// of Rodrigues' formula and of the left Jacobian, by series for small $\theta$.
fn rodrigues_coeffs(theta2: f64) -> (f64, f64, f64) {
    if theta2 < 1e-6 {
        let t4 = theta2 * theta2;
        (1.0 - theta2 / 6.0 + t4 / 120.0, 0.5 - theta2 / 24.0 + t4 / 720.0, 1.0 / 6.0 - theta2 / 120.0 + t4 / 5040.0)
    } else {
        let th = theta2.sqrt();
        let (s, c) = th.sin_cos();
        (s / th, (1.0 - c) / theta2, (th - s) / (theta2 * th))
    }
}

/// $\exp([v]_\times)$ for $v = (0, \alpha, \beta)$ (local), as a matrix $E$.
fn exp_bend(alpha: f64, beta: f64) -> [[f64; 3]; 3] {
    let v = [0.0, alpha, beta];
    let (a, c1, _) = rodrigues_coeffs(alpha * alpha + beta * beta);
    let k = [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]];
    let mut e = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|m| k[i][m] * k[m][j]).sum();
            e[i][j] = if i == j { 1.0 } else { 0.0 } + a * k[i][j] + c1 * k2;
        }
    }
    e
}

/// The frame of link $k$ from link $k-1$'s: $R_k = R_{k-1}E$, i.e. row $j$ of $F_k$ is
/// $\sum_i E_{ij} F_{k-1}[i]$.
fn turn_frame(prev: &Frame3, e: &[[f64; 3]; 3]) -> Frame3 {
    let mut f = [[0.0; 3]; 3];
    for (j, row) in f.iter_mut().enumerate() {
        for i in 0..3 {
            axpy(row, e[i][j], prev[i]);
        }
    }
    f
}

/// The world rotations $\Omega$ of the distal chain per unit change of $\alpha$ and of $\beta$
/// at a joint with bending $(\alpha, \beta)$ after the frame `prev`: $R_{k-1} J_l(\hat v) e$.
fn joint_omegas(prev: &Frame3, alpha: f64, beta: f64) -> [V3; 2] {
    let v = [0.0, alpha, beta];
    let (_, c1, c2) = rodrigues_coeffs(alpha * alpha + beta * beta);
    let jl = |e: V3| {
        let ve = cross(v, e);
        let vve = cross(v, ve);
        [e[0] + c1 * ve[0] + c2 * vve[0], e[1] + c1 * ve[1] + c2 * vve[1], e[2] + c1 * ve[2] + c2 * vve[2]]
    };
    [to_world(prev, jl([0.0, 1.0, 0.0])), to_world(prev, jl([0.0, 0.0, 1.0]))]
}

/// The roll $\varphi$ of frame `new` about its axis relative to `old` swung onto that axis by
/// the smallest rotation: $n_{new} = \cos\varphi\,n_{sw} + \sin\varphi\,b_{sw}$. Exactly 0 when the
/// frames are equal.
fn roll_between(old: &Frame3, new: &Frame3) -> f64 {
    if old == new {
        return 0.0;
    }
    let (a, b) = (old[0], new[0]);
    let c = dot(a, b);
    if c <= -1.0 + 1e-12 {
        // The axis reversed: no unique swing; treat as a pure swing.
        return 0.0;
    }
    let k = cross(a, b);
    let swing = |v: V3| {
        let kv = cross(k, v);
        let kkv = dot(k, v) / (1.0 + c);
        [v[0] * c + kv[0] + kkv * k[0], v[1] * c + kv[1] + kkv * k[1], v[2] * c + kv[2] + kkv * k[2]]
    };
    let (n_sw, b_sw) = (swing(old[1]), swing(old[2]));
    dot(new[1], b_sw).atan2(dot(new[1], n_sw))
}

/// One load on the rod during an update.
#[derive(Debug, Clone, Copy)]
struct Load {
    s_m: f64,
    link: usize,
    /// As given: link-frame components (follower) or world (dead).
    given: V3,
    /// World force and application point on the current shape.
    force: V3,
    point: V3,
}

/// The deformed shape of a flexible needle in 3D and the scratch of its updates (allocated up
/// front; a follower-load update and the tangent compliance allocate nothing).
#[derive(Debug, Clone)]
pub struct Rod3 {
    length_m: f64,
    link_m: f64,
    ei_nm2: f64,
    base_m: V3,
    base_frame: Frame3,
    /// Bending angles $(\alpha_k, \beta_k)$ of joint $k$.
    bend: Vec<[f64; 2]>,
    /// Link frames $F_k$.
    frames: Vec<Frame3>,
    /// Joint positions $x_0 \dots x_N$ ($x_N$ the tip).
    pts: Vec<V3>,
    loads: Vec<Load>,
    /// Per joint: $M_k$, $S_k$, the two $\Omega$, and the diagonal block's inverse.
    moment: Vec<V3>,
    beyond: Vec<V3>,
    omega: Vec<[V3; 2]>,
    diag_inv: Vec<[[f64; 2]; 2]>,
    /// Per joint and direction: $\Omega\times M + x\times(\Omega\times S)$ and $\Omega\times S$.
    w1: Vec<[V3; 2]>,
    w2: Vec<[V3; 2]>,
    rhs: Vec<[f64; 2]>,
    sol: Vec<[f64; 2]>,
    /// Prefix sums of the compliance's output map.
    q0: Vec<V3>,
    q1: Vec<V3>,
    /// Dead loads only: the dense Jacobian (row-major $2N \times 2N$), allocated on first use.
    dense: Vec<f64>,
    dead_a: Vec<f64>,
    dead_b: Vec<[[f64; 3]; 3]>,
    /// Newton iterations of the last shape update, and updates that hit the bound.
    pub last_iterations: usize,
    pub unconverged_updates: u64,
    /// Loads past the capacity an update had to leave out (never expected; counted).
    pub capacity_drops: u64,
}

impl Rod3 {
    /// A straight rod clamped at `base_m` with frame `base_frame` (rows $[t, n, b]$), with room
    /// for `max_loads` point loads.
    pub fn new(params: &FlexibleNeedle, base_m: V3, base_frame: Frame3, max_loads: usize) -> Self {
        let n = params.n_links.max(1);
        let mut r = Self {
            length_m: params.length_m,
            link_m: params.length_m / n as f64,
            ei_nm2: params.flexural_rigidity_nm2,
            base_m,
            base_frame,
            bend: vec![[0.0; 2]; n],
            frames: vec![base_frame; n],
            pts: vec![base_m; n + 1],
            loads: Vec::with_capacity(max_loads),
            moment: vec![[0.0; 3]; n],
            beyond: vec![[0.0; 3]; n],
            omega: vec![[[0.0; 3]; 2]; n],
            diag_inv: vec![[[0.0; 2]; 2]; n],
            w1: vec![[[0.0; 3]; 2]; n],
            w2: vec![[[0.0; 3]; 2]; n],
            rhs: vec![[0.0; 2]; n],
            sol: vec![[0.0; 2]; n],
            q0: vec![[0.0; 3]; n],
            q1: vec![[0.0; 3]; n],
            dense: Vec::new(),
            dead_a: Vec::new(),
            dead_b: Vec::new(),
            last_iterations: 0,
            unconverged_updates: 0,
            capacity_drops: 0,
        };
        r.rebuild();
        r
    }

    /// Number of links.
    pub fn n_links(&self) -> usize {
        self.bend.len()
    }
    /// Shaft length, m.
    pub fn length_m(&self) -> f64 {
        self.length_m
    }
    /// Flexural rigidity, N·m².
    pub fn flexural_rigidity_nm2(&self) -> f64 {
        self.ei_nm2
    }
    /// The joint positions, base to tip.
    pub fn points_m(&self) -> &[V3] {
        &self.pts
    }
    /// The link frames, base to tip.
    pub fn link_frames(&self) -> &[Frame3] {
        &self.frames
    }
    /// The bending angles $(\alpha_k, \beta_k)$ per joint.
    pub fn bending_rad(&self) -> &[[f64; 2]] {
        &self.bend
    }
    /// The clamp's position and frame.
    pub fn base(&self) -> (V3, Frame3) {
        (self.base_m, self.base_frame)
    }
    /// The tip position.
    pub fn tip_m(&self) -> V3 {
        self.pts[self.pts.len() - 1]
    }
    /// The tip link's frame.
    pub fn tip_frame(&self) -> Frame3 {
        self.frames[self.frames.len() - 1]
    }

    fn weight(&self, k: usize) -> f64 {
        if k == 0 { 0.5 * self.link_m } else { self.link_m }
    }

    /// Frames and joint positions from the bending angles.
    fn rebuild(&mut self) {
        let mut prev = self.base_frame;
        let mut x = self.base_m;
        self.pts[0] = x;
        for k in 0..self.bend.len() {
            let [a, b] = self.bend[k];
            let f = turn_frame(&prev, &exp_bend(a, b));
            self.frames[k] = f;
            x = add(x, scale(self.link_m, f[0]));
            self.pts[k + 1] = x;
            prev = f;
        }
    }

    /// Moves the clamp. The new base frame is the old one swung (the smallest rotation taking
    /// the old axis to the new) and then rolled about the new axis by $\varphi$: the swing moves
    /// the shape with the clamp rigidly; the roll turns the shaft about its own centreline —
    /// torsionally rigid, every frame rolls by $\varphi$ about its tangent and the centreline
    /// stays where the swing put it — so the bending angles turn by $-\varphi$ in their
    /// $(n, b)$ plane ($\alpha' = \alpha\cos\varphi + \beta\sin\varphi$,
    /// $\beta' = -\alpha\sin\varphi + \beta\cos\varphi$; the transport of a Bishop frame commutes
    /// with a constant roll).
    pub fn set_base(&mut self, base_m: V3, base_frame: Frame3) {
        let roll = roll_between(&self.base_frame, &base_frame);
        if roll != 0.0 {
            let (sn, cs) = roll.sin_cos();
            for b in self.bend.iter_mut() {
                *b = [b[0] * cs + b[1] * sn, -b[0] * sn + b[1] * cs];
            }
        }
        self.base_m = base_m;
        self.base_frame = base_frame;
        self.rebuild();
    }

    /// Makes this rod a copy of `other`'s shape without allocating (both made from the same
    /// needle).
    pub fn copy_from(&mut self, other: &Rod3) {
        self.base_m = other.base_m;
        self.base_frame = other.base_frame;
        self.bend.copy_from_slice(&other.bend);
        self.frames.copy_from_slice(&other.frames);
        self.pts.copy_from_slice(&other.pts);
    }

    /// The link of arc length `s_m` (clamped to the shaft).
    pub fn link_of(&self, s_m: f64) -> usize {
        if s_m <= 0.0 {
            return 0;
        }
        ((s_m / self.link_m) as usize).min(self.bend.len() - 1)
    }

    /// The shaft point at arc length `s_m`; beyond the ends the shape continues straight along
    /// the end links.
    pub fn point_at(&self, s_m: f64) -> V3 {
        let k = self.link_of(s_m);
        add(self.pts[k], scale(s_m - k as f64 * self.link_m, self.frames[k][0]))
    }

    /// The frame at arc length `s_m`: link frames interpolated between link midpoints along the
    /// joint's rotation ($F_k$ turned by a fraction of joint $k+1$'s bending), so that point
    /// frames turn smoothly as points slide; the end links' frames beyond their midpoints.
    pub fn frame_at(&self, s_m: f64) -> Frame3 {
        let n = self.bend.len();
        let u = s_m / self.link_m - 0.5;
        if u <= 0.0 {
            return self.frames[0];
        }
        let k = u as usize;
        if k + 1 >= n {
            return self.frames[n - 1];
        }
        let a = u - k as f64;
        let [al, be] = self.bend[k + 1];
        turn_frame(&self.frames[k], &exp_bend(a * al, a * be))
    }

    /// The arc length of the shaft point nearest `p_m` along the frame at `s_guess_m`: one
    /// Newton step $s = s_g + t\cdot(p - c(s_g))$ (exact on a straight link).
    pub fn arc_length_near(&self, s_guess_m: f64, p_m: V3) -> f64 {
        let f = self.frame_at(s_guess_m);
        s_guess_m + dot(f[0], sub(p_m, self.point_at(s_guess_m)))
    }

    /// Loads into `self.loads` (sorted by arc length), their world forces and points.
    fn set_loads(&mut self, loads: impl Iterator<Item = (f64, V3)>) {
        self.loads.clear();
        for (s, f) in loads {
            if self.loads.len() < self.loads.capacity() {
                let s = s.clamp(0.0, self.length_m);
                let link = self.link_of(s);
                self.loads.push(Load { s_m: s, link, given: f, force: [0.0; 3], point: [0.0; 3] });
            } else {
                self.capacity_drops += 1;
            }
        }
        self.loads.sort_unstable_by(|a, b| a.s_m.total_cmp(&b.s_m));
    }

    /// The loads' world forces and points on the current shape, the suffix sums $S_k$, $M_k$
    /// (and for dead loads $A_k = \sum p_j\cdot F_j$, $B_k = \sum F_j p_j^\top$), the joints'
    /// $\Omega$, and the residual into `rhs` (as $-r$).
    fn evaluate(&mut self, follower: bool) {
        for l in self.loads.iter_mut() {
            let f = &self.frames[l.link];
            l.force = if follower { to_world(f, l.given) } else { l.given };
            l.point = add(self.pts[l.link], scale(l.s_m - l.link as f64 * self.link_m, f[0]));
        }
        let n = self.bend.len();
        let (mut s_sum, mut m_orig) = ([0.0; 3], [0.0; 3]);
        let (mut a_sum, mut b_sum) = (0.0, [[0.0; 3]; 3]);
        let mut j = self.loads.len();
        for k in (0..n).rev() {
            while j > 0 && self.loads[j - 1].link >= k {
                let l = self.loads[j - 1];
                s_sum = add(s_sum, l.force);
                m_orig = add(m_orig, cross(l.point, l.force));
                if !follower {
                    a_sum += dot(l.point, l.force);
                    for (r, row) in b_sum.iter_mut().enumerate() {
                        axpy(row, l.force[r], l.point);
                    }
                }
                j -= 1;
            }
            self.beyond[k] = s_sum;
            self.moment[k] = sub(m_orig, cross(self.pts[k], s_sum));
            if !follower {
                self.dead_a[k] = a_sum;
                self.dead_b[k] = b_sum;
            }
        }
        for k in 0..n {
            let prev = if k == 0 { self.base_frame } else { self.frames[k - 1] };
            let [a, b] = self.bend[k];
            self.omega[k] = joint_omegas(&prev, a, b);
            let c = self.weight(k) / self.ei_nm2;
            let m = self.moment[k];
            self.rhs[k] = [c * dot(prev[1], m) - a, c * dot(prev[2], m) - b];
        }
    }

    /// $D_k(\Omega) = \Omega(A_k - x_k\cdot S_k) - B_k\Omega + S_k(x_k\cdot\Omega)$ (dead loads).
    fn dead_d(&self, k: usize, om: V3) -> V3 {
        let x = self.pts[k];
        let s = self.beyond[k];
        let b = &self.dead_b[k];
        let bo = [dot(b[0], om), dot(b[1], om), dot(b[2], om)];
        let mut d = scale(self.dead_a[k] - dot(x, s), om);
        d = sub(d, bo);
        axpy(&mut d, dot(x, om), s);
        d
    }

    /// With follower loads evaluated: the diagonal blocks' inverses and the per-joint vectors of
    /// the back substitution.
    fn prepare_follower_jacobian(&mut self) {
        for k in 0..self.bend.len() {
            let prev = if k == 0 { self.base_frame } else { self.frames[k - 1] };
            let c = self.weight(k) / self.ei_nm2;
            let (m, s, x) = (self.moment[k], self.beyond[k], self.pts[k]);
            let mut d = [[0.0; 2]; 2];
            for col in 0..2 {
                let om = self.omega[k][col];
                let om_m = cross(om, m);
                d[0][col] = if col == 0 { 1.0 } else { 0.0 } - c * dot(prev[1], om_m);
                d[1][col] = if col == 1 { 1.0 } else { 0.0 } - c * dot(prev[2], om_m);
                let om_s = cross(om, s);
                self.w1[k][col] = add(om_m, cross(x, om_s));
                self.w2[k][col] = om_s;
            }
            let det = d[0][0] * d[1][1] - d[0][1] * d[1][0];
            self.diag_inv[k] = [[d[1][1] / det, -d[0][1] / det], [-d[1][0] / det, d[0][0] / det]];
        }
    }

    /// Solves $J\,\delta = $ `rhs` into `sol` (follower loads: block back substitution, $O(N)$).
    fn back_substitute(&mut self, last: usize) {
        let (mut acc1, mut acc2) = ([0.0; 3], [0.0; 3]);
        for k in (0..self.bend.len()).rev() {
            if k > last {
                self.sol[k] = [0.0; 2];
                continue;
            }
            let prev = if k == 0 { self.base_frame } else { self.frames[k - 1] };
            let c = self.weight(k) / self.ei_nm2;
            let v = sub(acc1, cross(self.pts[k], acc2));
            let r = [self.rhs[k][0] + c * dot(prev[1], v), self.rhs[k][1] + c * dot(prev[2], v)];
            let di = self.diag_inv[k];
            let x = [di[0][0] * r[0] + di[0][1] * r[1], di[1][0] * r[0] + di[1][1] * r[1]];
            self.sol[k] = x;
            for col in 0..2 {
                axpy(&mut acc1, x[col], self.w1[k][col]);
                axpy(&mut acc2, x[col], self.w2[k][col]);
            }
        }
    }

    /// Dead loads: the dense Jacobian and its solve (Gaussian elimination with partial
    /// pivoting) into `sol`.
    fn dense_solve(&mut self) {
        let n = self.bend.len();
        let m = 2 * n;
        for k in 0..n {
            let pk = if k == 0 { self.base_frame } else { self.frames[k - 1] };
            let c = self.weight(k) / self.ei_nm2;
            for i in 0..n {
                for col in 0..2 {
                    let om = self.omega[i][col];
                    let dm = if k < i {
                        sub(cross(om, self.moment[i]), self.dead_d(i, om))
                    } else if k == i {
                        sub(cross(om, self.moment[k]), self.dead_d(k, om))
                    } else {
                        scale(-1.0, self.dead_d(k, om))
                    };
                    for row in 0..2 {
                        let id = if k == i && row == col { 1.0 } else { 0.0 };
                        self.dense[(2 * k + row) * m + 2 * i + col] = id - c * dot(pk[1 + row], dm);
                    }
                }
            }
        }
        let mut b: Vec<f64> = self.rhs.iter().flat_map(|r| [r[0], r[1]]).collect();
        let a = &mut self.dense;
        for p in 0..m {
            let piv = (p..m).max_by(|&x, &y| a[x * m + p].abs().total_cmp(&a[y * m + p].abs())).unwrap_or(p);
            if piv != p {
                for c in 0..m {
                    a.swap(p * m + c, piv * m + c);
                }
                b.swap(p, piv);
            }
            let d = a[p * m + p];
            for r in p + 1..m {
                let f = a[r * m + p] / d;
                if f != 0.0 {
                    for c in p..m {
                        a[r * m + c] -= f * a[p * m + c];
                    }
                    b[r] -= f * b[p];
                }
            }
        }
        for p in (0..m).rev() {
            let mut v = b[p];
            for c in p + 1..m {
                v -= a[p * m + c] * b[c];
            }
            b[p] = v / a[p * m + p];
        }
        for k in 0..n {
            self.sol[k] = [b[2 * k], b[2 * k + 1]];
        }
    }

    /// Finds the equilibrium shape under point forces on the needle `(s_m, force)`, warm-started
    /// from the current shape (Newton, module docs). With `follower` the force is given in the
    /// frame of its link (components along $t$, $n$, $b$) and turns with it; without, it is a
    /// world vector (a dead load: a dense solve that allocates its matrix on first use — for
    /// tests, the simulation's loads are follower loads). Returns whether it converged (no
    /// bending angle changing by more than 1e-13 rad); the shape is left at the last iterate
    /// otherwise (counted in `unconverged_updates`).
    pub fn update_shape(&mut self, loads: impl Iterator<Item = (f64, V3)>, follower: bool) -> bool {
        self.set_loads(loads);
        let n = self.bend.len();
        if !follower && self.dense.len() != 4 * n * n {
            self.dense = vec![0.0; 4 * n * n];
            self.dead_a = vec![0.0; n];
            self.dead_b = vec![[[0.0; 3]; 3]; n];
        }
        for it in 1..=SHAPE_MAX_ITERATIONS {
            self.evaluate(follower);
            if follower {
                self.prepare_follower_jacobian();
                self.back_substitute(n - 1);
            } else {
                self.dense_solve();
            }
            let change = self.sol.iter().flat_map(|s| [s[0].abs(), s[1].abs()]).fold(0.0, f64::max);
            let damp = if change > MAX_NEWTON_STEP_RAD { MAX_NEWTON_STEP_RAD / change } else { 1.0 };
            for k in 0..n {
                self.bend[k][0] += damp * self.sol[k][0];
                self.bend[k][1] += damp * self.sol[k][1];
            }
            self.rebuild();
            self.last_iterations = it;
            if change <= SHAPE_TOL_RAD {
                return true;
            }
        }
        self.unconverged_updates += 1;
        false
    }

    /// The tangent lateral compliance (module docs) of the settled shape carrying the follower
    /// `loads` (`(s_m, force on the needle in its link's frame)`), between the shaft points
    /// `points[i] = (s_m, [ν_i0, ν_i1])` (two world directions each, normally the point frame's
    /// $n$ and $b$): `out[(2i+a)·stride + 2j+b]` is the displacement of point $i$ along
    /// $\nu_{ia}$ per newton of follower force along $\nu_{jb}$ at point $j$, m/N.
    /// $O(d(N + d))$, no allocation (loads within the capacity).
    pub fn tangent_compliance_into(&mut self, points: &[(f64, [V3; 2])], loads: &[(f64, V3)], out: &mut [f64], stride: usize) {
        self.set_loads(loads.iter().copied());
        self.evaluate(true);
        self.prepare_follower_jacobian();
        let n = self.bend.len();
        for (j, &(sj, nu_j)) in points.iter().enumerate() {
            let mj = self.link_of(sj);
            let pj = self.point_at(sj);
            for (bcol, &nu) in nu_j.iter().enumerate() {
                for k in 0..n {
                    if k > mj {
                        self.rhs[k] = [0.0; 2];
                        continue;
                    }
                    let prev = if k == 0 { self.base_frame } else { self.frames[k - 1] };
                    let c = self.weight(k) / self.ei_nm2;
                    let arm = cross(sub(pj, self.pts[k]), nu);
                    self.rhs[k] = [c * dot(prev[1], arm), c * dot(prev[2], arm)];
                }
                self.back_substitute(mj);
                // Prefix sums: q0 = Σ δv Ω, q1 = Σ δv Ω × x_l.
                let (mut q0, mut q1) = ([0.0; 3], [0.0; 3]);
                for l in 0..n {
                    let mut w = scale(self.sol[l][0], self.omega[l][0]);
                    axpy(&mut w, self.sol[l][1], self.omega[l][1]);
                    q0 = add(q0, w);
                    q1 = add(q1, cross(w, self.pts[l]));
                    self.q0[l] = q0;
                    self.q1[l] = q1;
                }
                for (i, &(si, nu_i)) in points.iter().enumerate() {
                    let mi = self.link_of(si);
                    let dp = sub(cross(self.q0[mi], self.point_at(si)), self.q1[mi]);
                    for (a, &nia) in nu_i.iter().enumerate() {
                        out[(2 * i + a) * stride + 2 * j + bcol] = dot(nia, dp);
                    }
                }
            }
        }
    }

    /// World force `f` at arc length `s_m` in the components of its link's frame (what
    /// [`Self::update_shape`] takes as a follower load).
    pub fn to_link_frame(&self, s_m: f64, f: V3) -> V3 {
        to_local(&self.frames[self.link_of(s_m.clamp(0.0, self.length_m))], f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{UnitQuaternion, Vector3};

    fn needle(ei: f64, n: usize) -> FlexibleNeedle {
        FlexibleNeedle { length_m: 0.1, flexural_rigidity_nm2: ei, n_links: n, bevel_force_ratio: 0.0, bevel_side: 1.0 }
    }

    /// An oblique base frame (no axis along a world axis).
    fn oblique_frame() -> Frame3 {
        let q = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::new(0.3, -0.5, 0.8)), 1.1);
        let m = q.to_rotation_matrix();
        let m = m.matrix();
        [[m[(0, 0)], m[(1, 0)], m[(2, 0)]], [m[(0, 1)], m[(1, 1)], m[(2, 1)]], [m[(0, 2)], m[(1, 2)], m[(2, 2)]]]
    }

    #[test]
    fn frames_stay_orthonormal_and_rebuild_is_consistent() {
        let mut r = Rod3::new(&needle(0.01, 30), [0.01, 0.02, -0.03], oblique_frame(), 8);
        assert!(r.update_shape([(0.1, [0.0, 0.3, -0.2]), (0.05, [-0.1, 0.1, 0.2])].into_iter(), true));
        for f in r.link_frames() {
            for i in 0..3 {
                for j in 0..3 {
                    let e = dot(f[i], f[j]) - if i == j { 1.0 } else { 0.0 };
                    assert!(e.abs() < 1e-13, "{e}");
                }
            }
            assert!((dot(cross(f[0], f[1]), f[2]) - 1.0).abs() < 1e-13);
        }
        // Consecutive links turn about an axis perpendicular to both tangents: no twist, so
        // t_{k-1} x t_k is the rotation axis and n, b turn about it alone.
        for k in 1..r.n_links() {
            let [a, b] = r.bending_rad()[k];
            let axis = to_world(&r.link_frames()[k - 1], [0.0, a, b]);
            assert!(dot(axis, r.link_frames()[k - 1][0]).abs() < 1e-15);
            assert!(dot(axis, r.link_frames()[k][0]).abs() < 1e-15);
        }
    }

    #[test]
    fn small_tip_load_matches_cantilever_formula_in_both_directions() {
        // Tip deflection P L^3 / 3EI along a load in any lateral direction; O(h^2).
        let (ei, l, p) = (0.03, 0.1, 1e-4);
        let f0 = oblique_frame();
        let mut errs = Vec::new();
        for n in [20, 40, 80] {
            let mut r = Rod3::new(&needle(ei, n), [0.0; 3], f0, 8);
            let dir = add(scale(0.6, f0[1]), scale(0.8, f0[2]));
            assert!(r.update_shape([(l, scale(p, dir))].into_iter(), false));
            let exact = p * l.powi(3) / (3.0 * ei);
            let d = r.tip_m();
            errs.push((dot(d, dir) - exact).abs() / exact);
            // Nothing out of the load's plane (to rounding of the 0.1 m tip position).
            let out = dot(d, cross(f0[0], dir));
            assert!(out.abs() < 1e-15 * l, "n={n}: out of plane {out:e} m");
        }
        assert!(errs[2] < 1e-3 && errs[1] / errs[2] > 3.5, "{errs:?}");
    }

    /// Cantilever with a dead tip load perpendicular to the undeformed axis, $PL^2/EI = 1$:
    /// tip deflection 0.30172 L and axial shortening 0.05643 L (Bisshopp & Drucker 1945), in an
    /// oblique plane (the load along $0.6n + 0.8b$ of an oblique base frame) and along $b$; the
    /// tip stays in the plane of the axis and the load.
    #[test]
    fn large_tip_load_matches_the_elastica_in_any_plane() {
        let (ei, l) = (0.03, 0.1);
        let p = ei / (l * l);
        let f0 = oblique_frame();
        let base = [0.01, -0.02, 0.03];
        for (cn, cb) in [(0.6, 0.8), (0.0, 1.0), (1.0, 0.0)] {
            let dir = add(scale(cn, f0[1]), scale(cb, f0[2]));
            let mut r = Rod3::new(&needle(ei, 200), base, f0, 8);
            for step in 1..=10 {
                let f = p * step as f64 / 10.0;
                assert!(r.update_shape([(l, scale(f, dir))].into_iter(), false), "step {step}");
            }
            let d = sub(r.tip_m(), base);
            let (lateral, axial) = (dot(d, dir), dot(d, f0[0]));
            let out_of_plane = dot(d, cross(f0[0], dir));
            println!(
                "load ({cn}, {cb}): lateral {:.6} L, shortening {:.6} L, out of plane {out_of_plane:e} m",
                lateral / l,
                1.0 - axial / l
            );
            assert!((lateral / l - 0.30172).abs() < 5e-4, "lateral {}", lateral / l);
            assert!((1.0 - axial / l - 0.05643).abs() < 5e-4, "shortening {}", 1.0 - axial / l);
            assert!(out_of_plane.abs() < 1e-12 * l, "out of plane {out_of_plane:e}");
        }
    }

    /// A follower couple at the end (two opposite follower forces $\pm F b$ on the last link, a
    /// moment $F a$ about $-n$) bends the rod into a circular arc: every joint turns by
    /// $h\kappa$ ($h\kappa/2$ at the clamp), $\kappa = Fa/EI$, so the joints are the vertices of a
    /// regular polygon inscribed in the circle of radius $h / (2\sin(h\kappa/2))$ tangent to the
    /// base axis at the clamp, in the plane of $t$ and $b$ (exact for the discrete rod; a 115°
    /// arc).
    #[test]
    fn end_couple_bends_into_a_circular_arc() {
        let (ei, l, n) = (0.02, 0.1, 100);
        let f0 = oblique_frame();
        let h = l / n as f64;
        let kappa = 20.0;
        let arm = 0.5 * h;
        let f = kappa * ei / arm;
        let mut r = Rod3::new(&needle(ei, n), [0.0; 3], f0, 8);
        for step in 1..=20 {
            let a = step as f64 / 20.0;
            assert!(r.update_shape([(l, [0.0, 0.0, a * f]), (l - arm, [0.0, 0.0, -a * f])].into_iter(), true), "step {step}");
        }
        let radius = h / (2.0 * (0.5 * h * kappa).sin());
        let centre = scale(radius, f0[2]);
        let mut worst: f64 = 0.0;
        for (k, &x) in r.points_m().iter().enumerate() {
            let dx = sub(x, centre);
            worst = worst.max((dot(dx, dx).sqrt() - radius).abs());
            assert!(dot(x, f0[1]).abs() < 1e-15, "joint {k} out of the plane");
        }
        println!("worst radius error {worst:e} m of {radius} m");
        assert!(worst < 1e-13, "worst radius error {worst:e}");
    }

    /// The tangent compliance is the derivative of the settled shape: central differences of
    /// the settled shape under a small extra follower force along each lateral direction of each
    /// point, with axial compression and lateral loads in both directions (geometric stiffness
    /// matters), to 1e-6 of the largest entry.
    #[test]
    fn tangent_compliance_matches_finite_differences_of_the_shape() {
        let ei = 0.0022;
        let f0 = oblique_frame();
        let base = [0.02, 0.0, -0.01];
        let s_pts = [0.04, 0.0713, 0.1];
        let loads = [(0.04, [-0.1, 0.02, -0.015]), (0.0713, [-0.1, -0.01, 0.03]), (0.1, [-0.2, 0.03, 0.02])];
        let settle = |r: &mut Rod3, extra: Option<(usize, V3)>| {
            for step in 1..=10 {
                let a = step as f64 / 10.0;
                let ls = loads.iter().enumerate().map(|(k, &(s, f))| {
                    let add_f = extra.filter(|e| e.0 == k).map_or([0.0; 3], |e| e.1);
                    (s, add(scale(a, f), add_f))
                });
                assert!(r.update_shape(ls, true));
            }
        };
        let mut r0 = Rod3::new(&needle(ei, 50), base, f0, 8);
        settle(&mut r0, None);
        let points: Vec<(f64, [V3; 2])> = s_pts
            .iter()
            .map(|&s| {
                let f = r0.frame_at(s);
                (s, [f[1], f[2]])
            })
            .collect();
        let d = points.len();
        let mut g = vec![0.0; 4 * d * d];
        r0.tangent_compliance_into(&points, &loads, &mut g, 2 * d);
        let gmax = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let eps = 1e-5;
        let mut worst: f64 = 0.0;
        for j in 0..d {
            for b in 0..2 {
                // The extra force along ν_jb as a follower load on point j's link.
                let nu_local = r0.to_link_frame(points[j].0, points[j].1[b]);
                let mut rp = r0.clone();
                settle(&mut rp, Some((j, scale(eps, nu_local))));
                let mut rm = r0.clone();
                settle(&mut rm, Some((j, scale(-eps, nu_local))));
                for i in 0..d {
                    let dp = sub(rp.point_at(points[i].0), rm.point_at(points[i].0));
                    for a in 0..2 {
                        let fd = dot(points[i].1[a], dp) / (2.0 * eps);
                        let gt = g[(2 * i + a) * 2 * d + 2 * j + b];
                        worst = worst.max((gt - fd).abs() / gmax);
                        assert!((gt - fd).abs() < 1e-6 * gmax, "G[{i}{a}][{j}{b}]: tangent {gt:.9e}, finite difference {fd:.9e}");
                    }
                }
            }
        }
        println!("largest |G| {gmax:e} m/N, worst difference / largest {worst:e}");
        // The geometric stiffness matters here: the unloaded compliance differs by > 5 %.
        let mut r_free = r0.clone();
        let mut g0 = vec![0.0; 4 * d * d];
        r_free.tangent_compliance_into(&points, &[], &mut g0, 2 * d);
        let last = 4 * d * d - 1;
        assert!((g0[last] - g[last]).abs() > 0.05 * g[last].abs(), "unloaded {} loaded {}", g0[last], g[last]);
    }

    /// Swinging the base (turning its axis) moves the bent shape with it rigidly; rolling it
    /// about its own axis leaves the centreline where it is and rolls every frame about its
    /// tangent by the same angle.
    #[test]
    fn a_swing_moves_the_shape_rigidly_and_a_roll_turns_the_shaft_in_place() {
        let mut r = Rod3::new(&needle(0.03, 40), [0.0; 3], oblique_frame(), 8);
        r.update_shape([(0.1, [0.0, 0.5, 0.2])].into_iter(), true);
        let (b0, f0) = r.base();
        let pts0 = r.points_m().to_vec();
        let frames0 = r.link_frames().to_vec();
        // A roll by 90° about t: n -> b, b -> -n.
        let f1 = [f0[0], f0[2], scale(-1.0, f0[1])];
        r.set_base(b0, f1);
        for (k, (p, q)) in r.points_m().iter().zip(&pts0).enumerate() {
            assert!(dot(sub(*p, *q), sub(*p, *q)).sqrt() < 1e-15, "joint {k} moved");
        }
        for (f, g) in r.link_frames().iter().zip(&frames0) {
            // Rolled by 90° about the (unchanged) tangent: n' = b, b' = -n.
            for c in 0..3 {
                assert!((f[0][c] - g[0][c]).abs() < 1e-14 && (f[1][c] - g[2][c]).abs() < 1e-14 && (f[2][c] + g[1][c]).abs() < 1e-14);
            }
        }
        // A swing: the base axis turned by 0.3 rad about n; the shape turns with it.
        let q = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::new(f1[1][0], f1[1][1], f1[1][2])), 0.3);
        let rot = |v: V3| {
            let w = q * Vector3::new(v[0], v[1], v[2]);
            [w.x, w.y, w.z]
        };
        let f2 = [rot(f1[0]), rot(f1[1]), rot(f1[2])];
        let before = r.tip_m();
        r.set_base(b0, f2);
        let (lb, la) = (to_local(&f1, before), to_local(&f2, r.tip_m()));
        for c in 0..3 {
            assert!((la[c] - lb[c]).abs() < 1e-15, "{la:?} {lb:?}");
        }
    }
}
