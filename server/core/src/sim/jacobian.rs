//! The local stiffness the device feels: the Jacobian of the base wrench with respect to the
//! base pose, on a copy of the working solver (the simulation's state is only read).
//!
//! **Translations** are probe solves: the held problem (contact conditions, slipping forces and,
//! for a flexible needle, its compliance and reference forces held) is linear in the base's
//! translation, so central differences are exact. The probe copies the solver once; a
//! translation changes only prescribed values, never $H$ (and for a flexible needle, the shape
//! moves rigidly, so its compliance $G$ and the coupling's LU stay too).
//!
//! **The rotation** is a directional derivative, $O(d^2)$ whatever the number of slipping nodes
//! (probes would turn every frame: an $O(d^2)$ update per mixed-kind slot). Turning the base by
//! $\delta$ turns every slot's frame by $\delta$, $v' = Q v$ with $Q = I + \delta J + O(\delta^2)$,
//! $J = \begin{bmatrix} 0 & 1 \\ -1 & 0\end{bmatrix}$. Write the turned problem's physical state
//! in the *old* frames, $(u, f) = (u_0, f_0) + \delta\,(\dot u, \dot f)$. In the new frames each
//! DOF $c$ of a slot keeps its kind and gets the prescribed value $x_c(\theta)$:
//! $(Q u)_c = x_c$ for a displacement, $(Q f)_c = x_c$ for a force. To first order
//! $$\xi_c = \dot x_c - (J w_0)_c,\qquad w_0 = u_0 \text{ (displacement DOF) or } f_0 \text{ (force DOF)},$$
//! is the rate of the prescribed value in the old frame, and the unknowns' rates are
//! $\eta = H\xi$ — one solve with the unchanged $H$. The prescribed values' rates, for a node at
//! $X$ seen from frame origin $c$ (the base $b$ for a rigid needle; the shaft point, turning
//! about $b$ with $\dot c = R_{90°}(c - b)$, for a flexible one) with axes $t$, $n$
//! ($\dot t = n$, $\dot n = -t$): lateral $u_n = o - n\cdot(X - c)$ gives
//! $\dot x_n = t\cdot(X - c) + n\cdot\dot c$; a stuck node's or the tip's axial
//! $u_t = s_a - s_0 - t\cdot(X - c)$ gives $\dot x_t = -n\cdot(X - c) + t\cdot\dot c$; prescribed
//! forces are held ($\dot x = 0$). The world rates are $R(\alpha)\dot u$, $R(\alpha)\dot f$ at
//! each slot's angle $\alpha$, and with $p = X + u$,
//! $$\dot F = -\sum_i \dot f_i,\qquad \dot\tau = \sum_i \dot u_i \times (-f_i) + (p_i - b)\times(-\dot f_i).$$
//! For a flexible needle the coupled solve is differentiated the same way: its lateral system
//! $(I + G_{NN}A)\,v = g - G_{NN}(b - f^{ref}_N) - G_{NK}(f_K - f^{ref}_K)$ holds in the turning
//! frames ($G$ and the follower reference forces turn with the needle, so they are constant
//! there), and its rate is the same system with $g \to \dot x_n + u_{0,t}$ (the lateral value's
//! rate in the old frame), $f^{ref} \to f_{0,t}$ on every slot (so that $b - f^{ref}$ becomes the
//! rate of the turned lateral force, and a bevel tip's held force contributes nothing): the
//! factorisation of the base solve is reused, no other LU is needed.

use crate::beam::CoupledNode;
use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedSolver};
use crate::needle::BasePose;

use super::flexible::{FRAME_TOL_RAD, FlexScratch};
use super::frames::{Frame, prescribe};
use super::state::{FlexState, NodeState, WorkingSet};
use super::{Ctx, SimError};

/// The base state of one slot in the probe's solve, for the rotation's derivative.
#[derive(Debug, Clone, Copy, Default)]
struct SlotBase {
    /// Local displacement and force (slot frame).
    u_local: [f64; 2],
    f_local: [f64; 2],
    /// World force and deformed position.
    f_world: [f64; 2],
    p_world: [f64; 2],
}

/// The probe's scratch: a copy of the working solver and the base state of each slot,
/// allocated once.
pub(super) struct ProbeScratch {
    pub solver: MixedSolver,
    base: Vec<SlotBase>,
}

impl ProbeScratch {
    /// Scratch for a working set of at most `cap` nodes.
    pub fn new(cap: usize) -> Self {
        Self { solver: MixedSolver::with_capacity(cap), base: Vec::with_capacity(cap) }
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The force and torque of the tissue on the base, $(F_x, F_y, \tau)$, for a solved `solver`
/// whose slots are the working set's needle nodes, at base `pose`.
fn wrench_of(ws: &WorkingSet, solver: &MixedSolver, pose: &BasePose) -> [f64; 3] {
    let b = pose.position_m();
    let mut w = [0.0; 3];
    for slot in ws.slots() {
        let f = solver.force_world(slot);
        let u = solver.displacement_world(slot);
        let x = ws.node(slot).x_kin_m();
        let p = [x[0] + u[0], x[1] + u[1]];
        w[0] -= f[0];
        w[1] -= f[1];
        w[2] += cross([p[0] - b[0], p[1] - b[1]], [-f[0], -f[1]]);
    }
    w
}

/// Records each slot's solved state in `base` (the probe's base solve).
fn record_base(ws: &WorkingSet, solver: &MixedSolver, base: &mut Vec<SlotBase>) {
    base.clear();
    for slot in ws.slots() {
        let u = solver.displacement_world(slot);
        let x = ws.node(slot).x_kin_m();
        base.push(SlotBase {
            u_local: solver.displacement_local(slot),
            f_local: solver.force_local(slot),
            f_world: solver.force_world(slot),
            p_world: [x[0] + u[0], x[1] + u[1]],
        });
    }
}

/// The rates of the prescribed values of `slot` as the base turns at unit rate, $(\dot x_t,
/// \dot x_n)$ (module docs), for a node at `x_m` in a frame with origin `origin` (turning about
/// the base `b`) and angle `angle_rad`; the same DOFs as [`prescribe`] sets.
fn prescribed_rate(
    solver: &MixedSolver,
    slot: Slot,
    nn_state: NodeState,
    x_m: [f64; 2],
    origin: [f64; 2],
    b: [f64; 2],
    angle_rad: f64,
) -> [f64; 2] {
    let (sn, cs) = angle_rad.sin_cos();
    let (t, n) = ([cs, sn], [-sn, cs]);
    let r = [x_m[0] - origin[0], x_m[1] - origin[1]];
    let c_dot = [-(origin[1] - b[1]), origin[0] - b[0]];
    let dot = |a: [f64; 2], v: [f64; 2]| a[0] * v[0] + a[1] * v[1];
    let lateral = if solver.condition(slot, Axis::Lateral) == Condition::Displacement { dot(t, r) + dot(n, c_dot) } else { 0.0 };
    let axial = match nn_state {
        NodeState::Stuck | NodeState::Tip => -dot(n, r) + dot(t, c_dot),
        NodeState::Slipping => 0.0,
    };
    [axial, lateral]
}

/// The old-frame rates $\xi = \dot x - J w_0$ of the prescribed values of a slot (module docs).
fn old_frame_rate(solver: &MixedSolver, slot: Slot, x_dot: [f64; 2], base: &SlotBase) -> [f64; 2] {
    std::array::from_fn(|c| {
        let w = if solver.condition(slot, Axis::of_index(c)) == Condition::Displacement { base.u_local } else { base.f_local };
        // (J w)_0 = w_1, (J w)_1 = -w_0.
        let jw = if c == 0 { w[1] } else { -w[0] };
        x_dot[c] - jw
    })
}

/// The wrench's rate from the solved rates in `solver` (its $x = \xi$, $y = H\xi$) and the base
/// state.
fn wrench_rate(ws: &WorkingSet, solver: &MixedSolver, base: &[SlotBase], pose: &BasePose) -> [f64; 3] {
    let b = pose.position_m();
    let mut w = [0.0; 3];
    for (slot, s0) in ws.slots().zip(base) {
        let df = solver.force_world(slot);
        let du = solver.displacement_world(slot);
        w[0] -= df[0];
        w[1] -= df[1];
        w[2] += cross(du, [-s0.f_world[0], -s0.f_world[1]]) + cross([s0.p_world[0] - b[0], s0.p_world[1] - b[1]], [-df[0], -df[1]]);
    }
    w
}

/// Solves `probe` (a copy of the working set's solver, frames at `pose`) with the base at
/// `pose`, the contact conditions and slipping forces held. Allocates nothing.
fn probe_wrench_rigid(ctx: &Ctx<'_>, ws: &WorkingSet, probe: &mut MixedSolver, pose: &BasePose) -> Result<[f64; 3], SimError> {
    let shape = &ctx.params.needle;
    let s_tip = ctx.setup.s_tip_m;
    let frame = Frame::rigid(pose);
    for slot in ws.slots() {
        let nn = ws.node(slot);
        // A no-op for a translation probe (the frames are at the pose's angle already).
        probe.set_angle(slot, shape.frame_angle_at(pose, nn.s_prev_m))?;
        prescribe(probe, slot, nn, frame, nn.x_kin_m(), s_tip);
    }
    probe.solve();
    Ok(wrench_of(ws, probe, pose))
}

/// The wrench's rate as the rigid needle turns about its base, at `pose`, from `probe` solved
/// there (module docs). Two $O(d^2)$ passes: none of $H$ changes.
fn rotation_rate_rigid(ws: &WorkingSet, probe: &mut ProbeScratch, pose: &BasePose) -> [f64; 3] {
    let solver = &mut probe.solver;
    record_base(ws, solver, &mut probe.base);
    let b = pose.position_m();
    for (slot, s0) in ws.slots().zip(&probe.base) {
        let nn = ws.node(slot);
        let x_dot = prescribed_rate(solver, slot, nn.state, nn.x_kin_m(), b, b, solver.angle_rad(slot));
        let xi = old_frame_rate(solver, slot, x_dot, s0);
        for axis in Axis::BOTH {
            solver.set_value(slot, axis, xi[axis]);
        }
    }
    solver.solve();
    wrench_rate(ws, solver, &probe.base, pose)
}

/// Prescribes every slot of `probe` from the probe curve at its base (frames as they are),
/// writing the coupled view into `sc.nodes`.
fn prescribe_flexible(ctx: &Ctx<'_>, ws: &WorkingSet, probe: &mut MixedSolver, sc: &mut FlexScratch) {
    let s_tip = ctx.setup.s_tip_m;
    sc.nodes.clear();
    for slot in ws.slots() {
        let nn = ws.node(slot);
        let s_ref = nn.s_ref_m(s_tip);
        let frame = Frame::new(sc.probe_curve.point_at(s_ref), s_ref, probe.angle_rad(slot));
        let lateral = prescribe(probe, slot, nn, frame, nn.x_kin_m(), s_tip);
        sc.nodes.push(CoupledNode { s_m: s_ref, lateral_ref_m: lateral, force_ref_local_n: nn.force_ref_local_n });
    }
}

/// Sets up the flexible probe at `pose`: the solver copied, the curve copied, frames turned to
/// the shape's tangent where they are off by more than [`FRAME_TOL_RAD`] (as the next step's
/// frame refresh would), the needle's compliance computed and the coupled base state solved.
///
/// Errors: [`SimError::Mixed`] when the probe solver refuses a frame rotation.
fn base_flexible(
    ctx: &Ctx<'_>,
    ws: &WorkingSet,
    fx: &FlexState,
    probe: &mut MixedSolver,
    sc: &mut FlexScratch,
    pose: &BasePose,
) -> Result<[f64; 3], SimError> {
    probe.copy_from(&ws.solver);
    let s_tip = ctx.setup.s_tip_m;
    sc.probe_curve.copy_from(&fx.curve);
    sc.probe_curve.set_base(*pose);
    for slot in ws.slots() {
        let a = sc.probe_curve.tangent_angle_at(ws.node(slot).s_ref_m(s_tip));
        if (a - probe.angle_rad(slot)).abs() > FRAME_TOL_RAD {
            probe.set_angle(slot, a)?;
        }
    }
    prescribe_flexible(ctx, ws, probe, sc);
    sc.probe_coupling.update_compliance(&mut sc.probe_curve, probe, &sc.nodes);
    sc.probe_coupling.solve(probe, &sc.nodes);
    Ok(wrench_of(ws, probe, pose))
}

/// [`probe_wrench_rigid`] for a flexible needle set up by [`base_flexible`], translated to
/// `pose` (same angle): the shape moves rigidly with the base, frames and the needle's
/// compliance $G$ stay, so the coupling's factorisation is reused.
fn probe_wrench_flexible(ctx: &Ctx<'_>, ws: &WorkingSet, probe: &mut MixedSolver, sc: &mut FlexScratch, pose: &BasePose) -> [f64; 3] {
    sc.probe_curve.set_base(*pose);
    prescribe_flexible(ctx, ws, probe, sc);
    sc.probe_coupling.solve(probe, &sc.nodes);
    wrench_of(ws, probe, pose)
}

/// The wrench's rate as the flexible needle turns rigidly about its base, at `pose`, from the
/// probe's coupled base solve there (module docs): one coupled solve with the base's LU.
fn rotation_rate_flexible(ctx: &Ctx<'_>, ws: &WorkingSet, probe: &mut ProbeScratch, sc: &mut FlexScratch, pose: &BasePose) -> [f64; 3] {
    let s_tip = ctx.setup.s_tip_m;
    let solver = &mut probe.solver;
    record_base(ws, solver, &mut probe.base);
    let b = pose.position_m();
    sc.nodes.clear();
    for (slot, s0) in ws.slots().zip(&probe.base) {
        let nn = ws.node(slot);
        let s_ref = nn.s_ref_m(s_tip);
        let origin = sc.probe_curve.point_at(s_ref);
        let x_dot = prescribed_rate(solver, slot, nn.state, nn.x_kin_m(), origin, b, solver.angle_rad(slot));
        let xi = old_frame_rate(solver, slot, x_dot, s0);
        for axis in Axis::BOTH {
            solver.set_value(slot, axis, xi[axis]);
        }
        // The coupled system for the rates: g -> the lateral rate in the old frame, f_ref -> the
        // axial base force (see the module docs); the curve is not recomputed.
        let f_ax = s0.f_local[Axis::Axial];
        sc.nodes.push(CoupledNode { s_m: s_ref, lateral_ref_m: xi[Axis::Lateral], force_ref_local_n: [0.0, f_ax] });
    }
    sc.probe_coupling.solve(solver, &sc.nodes);
    wrench_rate(ws, solver, &probe.base, pose)
}

/// The 3 × 3 Jacobian $J_{ij} = \partial w_i / \partial q_j$ of the wrench $w = (F_x, F_y, \tau)$
/// with respect to $q = (x, y, \theta)$ at `pose` (see [`super::Simulation::stiffness_jacobian`]):
/// translations by central differences of probe solves ($h$ = 1 µm, exact: the held problem is
/// linear in them), the rotation as a directional derivative (module docs). $O(d^2)$ for a
/// rigid needle; a flexible one adds the needle's compliance and one factorisation of its
/// coupling.
///
/// Errors: [`SimError::Mixed`] when the probe solver refuses a frame rotation (a flexible
/// needle's frames brought to its shape).
pub(super) fn stiffness_jacobian(
    ctx: &Ctx<'_>,
    pose: BasePose,
    ws: &WorkingSet,
    flex: Option<&FlexState>,
    probe: &mut ProbeScratch,
    flex_sc: Option<&mut FlexScratch>,
) -> Result<[[f64; 3]; 3], SimError> {
    const H_M: f64 = 1e-6;
    let mut j = [[0.0; 3]; 3];
    let mut flex = flex.zip(flex_sc);
    if let Some((fx, sc)) = flex.as_mut() {
        base_flexible(ctx, ws, fx, &mut probe.solver, sc, &pose)?;
    } else {
        probe.solver.copy_from(&ws.solver);
    }
    for k in 0..2 {
        let (mut plus, mut minus) = (pose, pose);
        if k == 0 {
            plus.x_m += H_M;
            minus.x_m -= H_M;
        } else {
            plus.y_m += H_M;
            minus.y_m -= H_M;
        }
        let mut wrench = |q: &BasePose| match flex.as_mut() {
            Some((_, sc)) => Ok(probe_wrench_flexible(ctx, ws, &mut probe.solver, sc, q)),
            None => probe_wrench_rigid(ctx, ws, &mut probe.solver, q),
        };
        let wp = wrench(&plus)?;
        let wm = wrench(&minus)?;
        for i in 0..3 {
            j[i][k] = (wp[i] - wm[i]) / (2.0 * H_M);
        }
    }
    // The base state at `pose`, then the rotation's rate from it.
    let rate = match flex.as_mut() {
        Some((_, sc)) => {
            probe_wrench_flexible(ctx, ws, &mut probe.solver, sc, &pose);
            rotation_rate_flexible(ctx, ws, probe, sc, &pose)
        }
        None => {
            probe_wrench_rigid(ctx, ws, &mut probe.solver, &pose)?;
            rotation_rate_rigid(ws, probe, &pose)
        }
    };
    for i in 0..3 {
        j[i][2] = rate[i];
    }
    Ok(j)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::Coupling;
    use crate::fixtures::{phantom, phantom_params};
    use crate::needle::{FlexibleNeedle, NeedleShape, RigidNeedle};
    use crate::sim::{SimParams, Simulation};

    /// A needle inserted obliquely into the `n × n` phantom, turned while it goes on inserting,
    /// then pulled back: some nodes stuck, some slipping (mixed-kind slots), frames turned.
    fn turned_insertion(n: usize, needle: NeedleShape) -> Simulation {
        let a0 = -1.3f64;
        let base_at = |d: f64, a: f64| BasePose::new(0.04 + (d - 0.1) * a.cos(), 0.1 + (d - 0.1) * a.sin(), a);
        let params = SimParams { initial_pose: base_at(-0.005, a0), ..phantom_params(needle) };
        let mut sim = Simulation::new(phantom(n), params).unwrap();
        let mut poses: Vec<BasePose> = (0..=3000).map(|k| base_at(-0.005 + 0.04 * k as f64 / 3000.0, a0)).collect();
        poses.extend((1..=300).map(|k| base_at(0.035 + 0.003 * k as f64 / 300.0, a0 + 0.06 * k as f64 / 300.0)));
        for p in poses {
            sim.step(p).unwrap();
            sim.prefetch_columns(16).unwrap();
        }
        // Withdrawn at 50 mm/s until at least three nodes slip back while three stay stuck.
        let (last, t) = (sim.pose(), sim.pose().axis());
        for k in 1..=200 {
            let back = 5e-5 * k as f64;
            let o = sim.step(BasePose { x_m: last.x_m - back * t[0], y_m: last.y_m - back * t[1], ..last }).unwrap();
            if o.n_stuck >= 3 && o.n_slipping >= 3 {
                break;
            }
        }
        sim
    }

    /// Central differences $D(h)$ of the wrench over the base angle, extrapolated (Richardson)
    /// to $R(h) = (4D(h/2) - D(h))/3$, for `h`; `wrench_at` gives the wrench at an angle offset.
    fn richardson(h: f64, mut wrench_at: impl FnMut(f64) -> [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let mut d = |h: f64| {
            let (p, m) = (wrench_at(h), wrench_at(-h));
            std::array::from_fn::<f64, 3, _>(|i| (p[i] - m[i]) / (2.0 * h))
        };
        let (dh, dh2) = (d(h), d(0.5 * h));
        (dh, std::array::from_fn(|i| (4.0 * dh2[i] - dh[i]) / 3.0))
    }

    /// Checks the analytic rotation column `col` against Richardson-extrapolated central
    /// differences at several small `h`: each within `rel_tol` of the column's size plus the
    /// differences' rounding ($\epsilon\,|w|/h$), the plain differences further off at the
    /// largest $h$ than the extrapolated ones (so the agreement is not a coincidence of scale).
    fn check_rotation_column(col: [f64; 3], w0: [f64; 3], rel_tol: f64, mut wrench_at: impl FnMut(f64) -> [f64; 3]) {
        // Force components and the torque have their own scales (N/rad, N·m/rad).
        let scale = [col[0].hypot(col[1]), col[0].hypot(col[1]), col[2].abs()];
        let w_size = [w0[0].hypot(w0[1]), w0[0].hypot(w0[1]), w0[2].abs()];
        for (k, h) in [8e-3, 4e-3, 2e-3].into_iter().enumerate() {
            let (plain, extrapolated) = richardson(h, &mut wrench_at);
            for i in 0..3 {
                let tol = rel_tol * scale[i] + 1e-13 * w_size[i] / h;
                let e = (extrapolated[i] - col[i]).abs();
                println!("h {h:e} component {i}: analytic {:.9e}, central {:.9e}, Richardson {:.9e}", col[i], plain[i], extrapolated[i]);
                assert!(
                    e < tol,
                    "h {h:e} component {i}: analytic {} vs Richardson {} (error {e:e}, tolerance {tol:e})",
                    col[i],
                    extrapolated[i]
                );
                if k == 0 {
                    assert!((plain[i] - col[i]).abs() > e, "component {i}: the extrapolation should improve on the plain difference");
                }
            }
        }
    }

    /// The rigid needle's rotation column (a directional derivative) equals the limit of central
    /// differences of probe solves with every frame turned, on a turned needle with slipping
    /// nodes (mixed-kind slots), on two meshes.
    #[test]
    fn rigid_rotation_column_equals_extrapolated_central_differences() {
        for n in [25, 50] {
            let mut sim = turned_insertion(n, NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }));
            let o = sim.output().clone();
            assert!(o.n_slipping >= 3 && o.n_stuck >= 3, "stuck {} slipping {}", o.n_stuck, o.n_slipping);
            let j = sim.stiffness_jacobian().unwrap();
            let col = [j[0][2], j[1][2], j[2][2]];
            let Simulation { model, params, setup, state, .. } = &sim;
            let ctx = Ctx { model, params, setup };
            let mut probe = MixedSolver::with_capacity(params.max_needle_nodes);
            let pose = state.pose;
            let mut wrench_at = |dth: f64| {
                probe.copy_from(&state.ws.solver);
                let q = BasePose { theta_rad: pose.theta_rad + dth, ..pose };
                probe_wrench_rigid(&ctx, &state.ws, &mut probe, &q).unwrap()
            };
            let w0 = wrench_at(0.0);
            assert!((w0[0] - o.force_n[0]).abs() < 1e-12 * w0[0].hypot(w0[1]), "the probe reproduces the step's force");
            check_rotation_column(col, w0, 1e-8, wrench_at);
            // The translation columns are unchanged by the probe's rotation solve: compare with
            // fresh probes.
            let mut probe = MixedSolver::with_capacity(params.max_needle_nodes);
            for (k, dq) in [[1e-6, 0.0], [0.0, 1e-6]].into_iter().enumerate() {
                let mut at = |s: f64| {
                    probe.copy_from(&state.ws.solver);
                    probe_wrench_rigid(
                        &ctx,
                        &state.ws,
                        &mut probe,
                        &BasePose { x_m: pose.x_m + s * dq[0], y_m: pose.y_m + s * dq[1], ..pose },
                    )
                    .unwrap()
                };
                let (p, m) = (at(1.0), at(-1.0));
                for i in 0..3 {
                    assert_eq!(j[i][k], (p[i] - m[i]) / 2e-6, "column {k}");
                }
            }
        }
    }

    /// The flexible needle's rotation column (the derivative of the coupled solve, reusing its
    /// factorisation) equals the limit of central differences of coupled probe solves with the
    /// shape turned rigidly about the base, every frame turned with it and the needle's
    /// compliance recomputed on the turned shape.
    #[test]
    fn flexible_rotation_column_equals_extrapolated_central_differences() {
        let mut f = FlexibleNeedle::gauge17_steel(0.1);
        f.flexural_rigidity_nm2 *= 0.07;
        f.bevel_force_ratio = 0.2;
        let mut sim = turned_insertion(25, NeedleShape::Flexible(f));
        let o = sim.output().clone();
        assert!(o.n_slipping >= 3 && o.n_stuck >= 3, "stuck {} slipping {}", o.n_stuck, o.n_slipping);
        let j = sim.stiffness_jacobian().unwrap();
        let col = [j[0][2], j[1][2], j[2][2]];
        let Simulation { model, params, setup, state, scratch, .. } = &mut sim;
        let ctx = Ctx { model, params, setup };
        let cap = params.max_needle_nodes;
        let (fx, sc) = (state.flex.as_ref().unwrap(), scratch.flex.as_mut().unwrap());
        let pose = state.pose;
        // The frames as the Jacobian's base solve has them (brought to the shape).
        let mut based = MixedSolver::with_capacity(cap);
        base_flexible(&ctx, &state.ws, fx, &mut based, sc, &pose).unwrap();
        let base_curve = sc.probe_curve.clone();
        let mut probe = MixedSolver::with_capacity(cap);
        let mut coupling = Coupling::new(cap);
        let mut wrench_at = |dth: f64| {
            probe.copy_from(&based);
            sc.probe_curve.copy_from(&base_curve);
            let q = BasePose { theta_rad: pose.theta_rad + dth, ..pose };
            sc.probe_curve.set_base(q);
            for slot in state.ws.slots() {
                probe.set_angle(slot, based.angle_rad(slot) + dth).unwrap();
            }
            prescribe_flexible(&ctx, &state.ws, &mut probe, sc);
            coupling.update_compliance(&mut sc.probe_curve, &probe, &sc.nodes);
            coupling.solve(&mut probe, &sc.nodes);
            wrench_of(&state.ws, &probe, &q)
        };
        let w0 = wrench_at(0.0);
        check_rotation_column(col, w0, 1e-7, wrench_at);
    }
}
