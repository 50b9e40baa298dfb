//! The flexible needle of the 3D simulation: the rod's shape ([`Rod3`]), the working-set solve
//! coupled through its tangent lateral compliance, the bevel tip's lateral force, and the shape
//! brought to equilibrium after the tick.
//!
//! **Frames and values.** Each point is framed on the rod at its reference arc length $s_i$
//! (a stuck point's anchor, the tip's $L$, a slipping point's arc at the end of the last tick):
//! $F_i$ = [`Rod3::frame_at`]$(s_i)$, turned only when it differs from the solver's by more than
//! [`FRAME_TOL`] (every frame when the base turned). The prescribed values put the point on the
//! reference shape $c$ (the last equilibrium): $u = F_i\,(c(s_i) - X_i)$, the lateral components
//! $g_i$ always, the axial one for stuck and tip points. On a straight rod this is the rigid
//! needle's $u_n = -n\cdot d$, $u_b = -b\cdot d$, $u_t = s - t\cdot d$.
//!
//! **Coupled solve** (the 3D form of [`crate::beam::Coupling`]): with $N$ the lateral DOFs
//! ($n$ and $b$ of each point) with prescribed displacement, $K$ those with prescribed force
//! (a bevel tip's $n$), $G$ the rod's tangent compliance between all of them
//! ([`Rod3::tangent_compliance_into`], the frames' $n$, $b$ as directions) and $f^{ref}$ the
//! forces the reference shape is in equilibrium with,
//! $$v = g - G_{NN}(f_N - f^{ref}_N) - G_{NK}(f_K - f^{ref}_K),\qquad f_N = A v + b,$$
//! $A$ the lateral block of the solver's hybrid matrix, so one dense solve
//! $(I + G_{NN}A)\,v = g - G_{NN}(b - f^{ref}_N) - G_{NK}(f_K - f^{ref}_K)$ per solve of the
//! working set (Gaussian elimination, $O(|N|^3)$; the 2D coupling's low-rank updates after pivots
//! are not carried over yet). A stiff rod ($G \to 0$) gives $v = g$: the rigid needle.
//!
//! **Bevel.** While the tip cuts (it advanced along its tangent this tick inside the tissue) the
//! tissue pushes it sideways with $P = s_b\,\beta\,f_c\,\bar n$, $f_c$ the cutting force of the
//! region the tip is in (the axial force the tip cuts with), $\beta$ the bevel force ratio and
//! $\bar n$ the bevel's direction — the tip link's $n$, which turns with the base's roll, the rod
//! being torsionally rigid — averaged over the depth cut since the last captured point,
//! $$\bar n = \frac{\sum_k \Delta s_k\, n_k}{\sum_k \Delta s_k}$$
//! over this tick's and the earlier ticks' advances $\Delta s_k$ (its part across the tip's
//! tangent). The tissue holds the needle only at its material points, a tetrahedron diameter
//! apart (8.7 mm on the 21³ cube), so the path is what the tip's position is when a point is
//! captured; the tissue the tip cut in between, which in a real needle's path keeps the lateral
//! displacement of every bit of cut, is not there. With $P$ along the instantaneous $n$, a
//! needle spun while it cuts (duty-cycled spinning, a period of 1 mm against 8.7 mm between
//! points) bends towards wherever the bevel happens to face at each capture: the curvature is
//! the aliased sample of the spin, not its average (measured 0.685, 0.228, 0.006 of the
//! unspun curvature at δ = 0.25, 0.5, 0.75). Averaged over the cut, it is the mean
//! direction the cut had, as the unicycle models of spinning needles take it (Minhas et al.
//! 2007: the bevel's effect averages to zero over a spin); without a spin $\bar n$ is $n$ up to
//! the tip's turn over one spacing. It is a follower load at the tip of the rod (components
//! along the tip link's $n$ and $b$) in the shape's equilibrium and in $G$'s geometric
//! stiffness; the held points carry its reaction. (Not through the tip's material point: in 3D
//! a point is carried by the tip only for the few ticks until it is cut, every
//! tetrahedron diameter — 3 % of the ticks on the 21³ cube — so a force there would act
//! intermittently.) A change of $P$ enters at the next shape pass.
//!
//! **Shape.** After the active set the rod is brought to equilibrium with the working forces
//! (follower loads at the points' current arc lengths); when that moves a displacement-held point
//! more than [`SHAPE_GAP_TOL_M`] off the new shape, frames and values are refreshed on it and the
//! active set is solved again, at most [`SHAPE_PASSES`] passes a tick.

use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedSolver3};
use crate::needle::FlexibleNeedle;
use crate::rod3::{Frame3, Rod3, V3};

use super::{Point, PointState3, dot, sub};

/// A frame change from bending smaller than this (largest entry, ≈ rad) is not applied to a
/// point (each costs an $O(d)$ or $O(d^2)$ update); the values are recomputed in the point's
/// frame every tick, so the error does not accumulate (as the 2D `FRAME_TOL_RAD`).
pub const FRAME_TOL: f64 = 1e-4;
/// Largest lateral distance (m) between a held point and the settled shape left without another
/// solve on the new shape.
pub const SHAPE_GAP_TOL_M: f64 = 1e-6;
/// Bound on the shape passes per tick.
pub const SHAPE_PASSES: usize = 4;

/// The flexible needle's state and scratch, sized for the working set's capacity.
#[derive(Clone)]
pub(super) struct Flex3 {
    pub rod: Rod3,
    pub bevel_ratio: f64,
    pub bevel_side: f64,
    /// The bevel's lateral force on the tip this tick, N, in the tip link's frame (its $n$ and
    /// $b$ components; module docs, "Bevel").
    pub tip_load_n: [f64; 2],
    /// The bevel force the reference shape is in equilibrium with.
    tip_load_ref_n: [f64; 2],
    /// The bevel's direction (world, the tip link's $n$) integrated over the depth cut since
    /// the last captured point, and that depth (m).
    bevel_dir_sum: V3,
    bevel_cut_m: f64,
    cap: usize,
    /// $G$ over the lateral DOFs $2i + c$ (row-major, stride $2\,$cap) and what it was computed for.
    g: Vec<f64>,
    g_for: Option<(u64, u64, u64)>,
    shape_version: u64,
    points: Vec<(f64, [V3; 2])>,
    loads: Vec<(f64, V3)>,
    n_dofs: Vec<usize>,
    k_dofs: Vec<usize>,
    m: Vec<f64>,
    rhs: Vec<f64>,
    y: Vec<f64>,
    /// Shape passes beyond the first, and shape updates that did not converge.
    pub shape_passes: u64,
    pub shape_unconverged: u64,
}

/// The lateral axes, in the order of $G$'s DOFs.
const LAT: [Axis; 2] = [Axis::Lateral, Axis::Binormal];

impl Flex3 {
    pub fn new(f: &FlexibleNeedle, base_m: V3, frame: Frame3, cap: usize) -> Self {
        let n2 = 2 * cap;
        Self {
            rod: Rod3::new(f, base_m, frame, cap + 1),
            bevel_ratio: f.bevel_force_ratio,
            bevel_side: f.bevel_side,
            tip_load_n: [0.0; 2],
            tip_load_ref_n: [0.0; 2],
            bevel_dir_sum: [0.0; 3],
            bevel_cut_m: 0.0,
            cap,
            g: vec![0.0; n2 * n2],
            g_for: None,
            shape_version: 0,
            points: Vec::with_capacity(cap),
            loads: Vec::with_capacity(cap + 1),
            n_dofs: Vec::with_capacity(n2),
            k_dofs: Vec::with_capacity(n2),
            m: vec![0.0; n2 * n2],
            rhs: vec![0.0; n2],
            y: vec![0.0; n2],
            shape_passes: 0,
            shape_unconverged: 0,
        }
    }

    /// The bevel's lateral tip force for this tick (module docs, "Bevel"): the tip advanced
    /// `advance_m` along its tangent, inside the tissue or not, cutting with `cutting_force_n`;
    /// `captured` when a point was captured this tick (the cut since then starts now).
    pub fn update_bevel(&mut self, advance_m: f64, inside: bool, cutting_force_n: f64, captured: bool) {
        if captured {
            self.bevel_dir_sum = [0.0; 3];
            self.bevel_cut_m = 0.0;
        }
        if !(inside && advance_m > 1e-9) || self.bevel_ratio == 0.0 {
            self.tip_load_n = [0.0; 2];
            return;
        }
        let f = self.rod.tip_frame();
        for c in 0..3 {
            self.bevel_dir_sum[c] += advance_m * f[1][c];
        }
        self.bevel_cut_m += advance_m;
        let p = self.bevel_side * self.bevel_ratio * cutting_force_n / self.bevel_cut_m;
        self.tip_load_n = [p * dot(f[1], self.bevel_dir_sum), p * dot(f[2], self.bevel_dir_sum)];
    }

    /// The reference arc length of a point (module docs).
    pub fn s_ref(&self, p: &Point) -> f64 {
        match p.state {
            PointState3::Stuck => p.anchor_s_m,
            PointState3::Tip => self.rod.length_m(),
            PointState3::Slipping => p.s_prev_m,
        }
    }

    /// The arc coordinate of the point's reference position in its frame $F$ (the
    /// displacement's axial component adds to it): $s_i + t\cdot(X - c(s_i))$.
    pub fn ref_arc(&self, p: &Point, frame: &Frame3) -> f64 {
        let s = self.s_ref(p);
        s + dot(frame[0], sub(p.x_kin_m(), self.rod.point_at(s)))
    }

    /// The arc length of a deformed position $x$ of a point in frame $F$.
    pub fn arc_of(&self, p: &Point, frame: &Frame3, x: V3) -> f64 {
        let s = self.s_ref(p);
        s + dot(frame[0], sub(x, self.rod.point_at(s)))
    }

    /// Turns the points' frames to the rod's where they differ by more than [`FRAME_TOL`]
    /// (all of them when `exact`).
    pub fn refresh_frames(&self, solver: &mut MixedSolver3, pts: &[Point], exact: bool) -> Result<(), crate::mixed::MixedError> {
        for slot in Slot::all(pts.len()) {
            let f = self.rod.frame_at(self.s_ref(&pts[slot.index()]));
            let old = solver.frame(slot);
            let mut diff: f64 = 0.0;
            for r in 0..3 {
                for c in 0..3 {
                    diff = diff.max((f[r][c] - old[r][c]).abs());
                }
            }
            if exact || diff > FRAME_TOL {
                solver.set_frame(slot, f)?;
            }
        }
        Ok(())
    }

    /// Sets the values that put each point on the reference shape and records $g$.
    pub fn set_values(&self, solver: &mut MixedSolver3, pts: &mut [Point]) {
        for slot in Slot::all(pts.len()) {
            let p = &pts[slot.index()];
            let f = solver.frame(slot);
            let d = sub(self.rod.point_at(self.s_ref(p)), p.x_kin_m());
            let u = [dot(f[0], d), dot(f[1], d), dot(f[2], d)];
            for (c, &ax) in LAT.iter().enumerate() {
                if solver.condition(slot, ax) == Condition::Displacement {
                    solver.set_value(slot, ax, u[1 + c]);
                }
            }
            if p.state != PointState3::Slipping {
                solver.set_value(slot, Axis::Axial, u[0]);
            }
            pts[slot.index()].lat_ref_m = [u[1], u[2]];
        }
    }

    /// Recomputes $G$ when the slots, frames, shape or tick changed.
    fn ensure_g(&mut self, solver: &MixedSolver3, pts: &[Point], tick: u64) {
        let st = solver.stats();
        let version = (st.n_rotations + st.n_added + st.n_removed + st.n_rebuilds, self.shape_version, tick);
        if self.g_for == Some(version) {
            return;
        }
        let mut g = std::mem::take(&mut self.g);
        self.compliance_into(solver, pts, &mut g);
        self.g = g;
        self.g_for = Some(version);
    }

    /// The rod's tangent lateral compliance $G$ between the points' $n$, $b$ directions (the
    /// solver's frames) on the current shape carrying the reference forces, into `out` (row-major,
    /// lateral DOF $2i + c$, stride $2\,$cap; `out` holds at least $(2\,\mathrm{cap})^2$). Leaves
    /// the shape and the cached $G$ as they are (what [`Simulation3::wrench_stiffness`] reads).
    ///
    /// [`Simulation3::wrench_stiffness`]: super::Simulation3::wrench_stiffness
    pub fn compliance_into(&mut self, solver: &MixedSolver3, pts: &[Point], out: &mut [f64]) {
        self.points.clear();
        self.loads.clear();
        for slot in Slot::all(pts.len()) {
            let p = &pts[slot.index()];
            let f = solver.frame(slot);
            let s = self.s_ref(p);
            self.points.push((s, [f[1], f[2]]));
            // The needle carries the opposite of the reference force on the tissue.
            let fr = p.f_ref_local_n;
            let w = [
                -(fr[0] * f[0][0] + fr[1] * f[1][0] + fr[2] * f[2][0]),
                -(fr[0] * f[0][1] + fr[1] * f[1][1] + fr[2] * f[2][1]),
                -(fr[0] * f[0][2] + fr[1] * f[1][2] + fr[2] * f[2][2]),
            ];
            self.loads.push((s, self.rod.to_link_frame(s, w)));
        }
        if self.tip_load_ref_n != [0.0; 2] {
            self.loads.push((self.rod.length_m(), [0.0, self.tip_load_ref_n[0], self.tip_load_ref_n[1]]));
        }
        let stride = 2 * self.cap;
        self.rod.tangent_compliance_into(&self.points, &self.loads, out, stride);
    }

    /// The stride of [`Self::compliance_into`]'s rows.
    pub fn compliance_stride(&self) -> usize {
        2 * self.cap
    }

    /// The coupled solve of the working set (module docs).
    pub fn solve(&mut self, solver: &mut MixedSolver3, pts: &[Point], tick: u64) {
        self.ensure_g(solver, pts, tick);
        let d = pts.len();
        self.n_dofs.clear();
        self.k_dofs.clear();
        for a in 0..2 * d {
            if solver.condition(Slot::new(a / 2), LAT[a % 2]) == Condition::Displacement {
                self.n_dofs.push(a);
            } else {
                self.k_dofs.push(a);
            }
        }
        let nn = self.n_dofs.len();
        let dof = |a: usize| Slot::new(a / 2).local_dof::<3>(LAT[a % 2]);
        let lat = |a: usize| (Slot::new(a / 2), LAT[a % 2]);
        solver.solve();
        // b = y_N - A v at the current values.
        for (r, &a) in self.n_dofs.iter().enumerate() {
            let (s, ax) = lat(a);
            let mut y = solver.force_local(s)[ax.index()];
            for &b in &self.n_dofs {
                let (sb, axb) = lat(b);
                y -= solver.hybrid(dof(a), dof(b)) * solver.prescribed_value(sb, axb);
            }
            self.y[r] = y;
        }
        let stride = 2 * self.cap;
        let f_ref = |a: usize| pts[a / 2].f_ref_local_n[1 + a % 2];
        // M = I + G_NN A (row-major nn × nn) and the right-hand side.
        for (r, &a) in self.n_dofs.iter().enumerate() {
            for (c, &b) in self.n_dofs.iter().enumerate() {
                let mut v = if r == c { 1.0 } else { 0.0 };
                for &e in &self.n_dofs {
                    v += self.g[a * stride + e] * solver.hybrid(dof(e), dof(b));
                }
                self.m[r * nn + c] = v;
            }
            let mut rhs = pts[a / 2].lat_ref_m[a % 2];
            for (c, &b) in self.n_dofs.iter().enumerate() {
                rhs -= self.g[a * stride + b] * (self.y[c] - f_ref(b));
            }
            for &k in &self.k_dofs {
                let (sk, axk) = lat(k);
                rhs -= self.g[a * stride + k] * (solver.prescribed_value(sk, axk) - f_ref(k));
            }
            self.rhs[r] = rhs;
        }
        solve_dense(&mut self.m[..nn * nn], &mut self.rhs[..nn], nn);
        for (r, &a) in self.n_dofs.iter().enumerate() {
            let (s, ax) = lat(a);
            solver.set_value(s, ax, self.rhs[r]);
        }
        solver.solve();
    }

    /// Brings the rod to equilibrium with the working forces (follower loads at the points'
    /// current arc lengths), records them as the reference forces, and returns how far (m) the
    /// displacement-held points lie off the new shape laterally.
    pub fn settle(&mut self, solver: &MixedSolver3, pts: &mut [Point]) -> f64 {
        let len = self.rod.length_m();
        self.loads.clear();
        for slot in Slot::all(pts.len()) {
            let p = &pts[slot.index()];
            let f = solver.frame(slot);
            let s = match p.state {
                PointState3::Slipping => self.arc_of(p, &f, super::add(p.x_kin_m(), solver.displacement_world(slot))),
                _ => self.s_ref(p),
            }
            .min(len);
            let fw = solver.force_world(slot);
            self.loads.push((s, self.rod.to_link_frame(s, [-fw[0], -fw[1], -fw[2]])));
        }
        if self.tip_load_n != [0.0; 2] {
            self.loads.push((len, [0.0, self.tip_load_n[0], self.tip_load_n[1]]));
        }
        self.tip_load_ref_n = self.tip_load_n;
        let loads = std::mem::take(&mut self.loads);
        if !self.rod.update_shape(loads.iter().copied(), true) {
            self.shape_unconverged += 1;
        }
        self.loads = loads;
        self.shape_version += 1;
        let mut gap: f64 = 0.0;
        for slot in Slot::all(pts.len()) {
            pts[slot.index()].f_ref_local_n = solver.force_local(slot);
            let p = &pts[slot.index()];
            let f = solver.frame(slot);
            let x = super::add(p.x_kin_m(), solver.displacement_world(slot));
            let off = sub(x, self.rod.point_at(self.s_ref(p)));
            for (c, &ax) in LAT.iter().enumerate() {
                if solver.condition(slot, ax) == Condition::Displacement {
                    gap = gap.max(dot(f[1 + c], off).abs());
                }
            }
        }
        gap
    }
}

/// Solves the dense row-major `n × n` system `a x = b` in place (`b` becomes `x`) by Gaussian
/// elimination with partial pivoting; no allocation.
fn solve_dense(a: &mut [f64], b: &mut [f64], n: usize) {
    for p in 0..n {
        let mut piv = p;
        for r in p + 1..n {
            if a[r * n + p].abs() > a[piv * n + p].abs() {
                piv = r;
            }
        }
        if piv != p {
            for c in 0..n {
                a.swap(p * n + c, piv * n + c);
            }
            b.swap(p, piv);
        }
        let d = a[p * n + p];
        for r in p + 1..n {
            let f = a[r * n + p] / d;
            if f != 0.0 {
                for c in p..n {
                    a[r * n + c] -= f * a[p * n + c];
                }
                b[r] -= f * b[p];
            }
        }
    }
    for p in (0..n).rev() {
        let mut v = b[p];
        for c in p + 1..n {
            v -= a[p * n + c] * b[c];
        }
        b[p] = v / a[p * n + p];
    }
}
