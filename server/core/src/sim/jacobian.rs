//! The local stiffness the device feels: the Jacobian of the base wrench with respect to the
//! base pose, from probe solves on a copy of the working solver (the simulation's state is
//! only read).

use crate::beam::CoupledNode;
use crate::mixed::MixedSolver;
use crate::needle::BasePose;

use super::flexible::{FRAME_TOL_RAD, FlexScratch};
use super::frames::{Frame, prescribe};
use super::state::{FlexState, WorkingSet};
use super::{Ctx, SimError};

/// The probe's scratch: a copy of the working solver allocated once.
pub(super) struct ProbeScratch {
    pub solver: MixedSolver,
}

/// The force and torque of the tissue on the base, $(F_x, F_y, \tau)$, for a solved `solver`
/// whose slots are the working set's needle nodes, at base `pose`.
fn wrench_of(ws: &WorkingSet, solver: &MixedSolver, pose: &BasePose) -> [f64; 3] {
    let b = pose.position_m();
    let mut w = [0.0; 3];
    for slot in ws.slots() {
        let f = solver.force_world(slot);
        let u = solver.displacement_world(slot);
        let x = ws.node(slot).x_ref_m;
        let p = [x[0] + u[0], x[1] + u[1]];
        w[0] -= f[0];
        w[1] -= f[1];
        w[2] += (p[0] - b[0]) * (-f[1]) - (p[1] - b[1]) * (-f[0]);
    }
    w
}

/// Solves the probe copy of the working set with the base at `pose`, the contact conditions
/// (stuck, slipping, tip) and slipping forces held as they are. Allocates nothing.
fn probe_wrench_rigid(ctx: &Ctx<'_>, ws: &WorkingSet, probe: &mut MixedSolver, pose: &BasePose) -> Result<[f64; 3], SimError> {
    probe.copy_from(&ws.solver);
    let shape = &ctx.params.needle;
    let s_tip = ctx.setup.s_tip_m;
    let frame = Frame::rigid(pose);
    for slot in ws.slots() {
        let nn = ws.node(slot);
        probe.set_angle(slot, shape.frame_angle_at(pose, nn.s_prev_m))?;
        prescribe(probe, slot, nn, frame, nn.x_ref_m, s_tip);
    }
    probe.solve();
    Ok(wrench_of(ws, probe, pose))
}

/// [`probe_wrench_rigid`] for a flexible needle: its shape moved rigidly with the base, the
/// frames following it, and the needle's compliance in the solve.
fn probe_wrench_flexible(
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
    sc.nodes.clear();
    for slot in ws.slots() {
        let nn = ws.node(slot);
        let s_ref = nn.s_ref_m(s_tip);
        let a = sc.probe_curve.tangent_angle_at(s_ref);
        if (a - probe.angle_rad(slot)).abs() > FRAME_TOL_RAD {
            probe.set_angle(slot, a)?;
        }
        let frame = Frame::new(sc.probe_curve.point_at(s_ref), s_ref, probe.angle_rad(slot));
        let lateral = prescribe(probe, slot, nn, frame, nn.x_ref_m, s_tip);
        sc.nodes.push(CoupledNode { s_m: s_ref, lateral_ref_m: lateral, force_ref_local_n: nn.force_ref_local_n });
    }
    sc.probe_coupling.update_compliance(&mut sc.probe_curve, probe, &sc.nodes);
    sc.probe_coupling.solve(probe, &sc.nodes);
    Ok(wrench_of(ws, probe, pose))
}

/// The 3 × 3 Jacobian $J_{ij} = \partial w_i / \partial q_j$ of the wrench $w = (F_x, F_y, \tau)$
/// with respect to $q = (x, y, \theta)$ at `pose` (see [`super::Simulation::stiffness_jacobian`]).
///
/// Errors: [`SimError::Mixed`] when the probe solver refuses a frame rotation.
pub(super) fn stiffness_jacobian(
    ctx: &Ctx<'_>,
    pose: BasePose,
    ws: &WorkingSet,
    flex: Option<&FlexState>,
    probe: &mut ProbeScratch,
    flex_sc: Option<&mut FlexScratch>,
) -> Result<[[f64; 3]; 3], SimError> {
    let h = [1e-6, 1e-6, 1e-3];
    let mut j = [[0.0; 3]; 3];
    let mut flex = flex.zip(flex_sc);
    for k in 0..3 {
        let (mut plus, mut minus) = (pose, pose);
        match k {
            0 => {
                plus.x_m += h[0];
                minus.x_m -= h[0];
            }
            1 => {
                plus.y_m += h[1];
                minus.y_m -= h[1];
            }
            _ => {
                plus.theta_rad += h[2];
                minus.theta_rad -= h[2];
            }
        }
        let mut wrench = |q: &BasePose| match flex.as_mut() {
            Some((fx, sc)) => probe_wrench_flexible(ctx, ws, fx, &mut probe.solver, sc, q),
            None => probe_wrench_rigid(ctx, ws, &mut probe.solver, q),
        };
        let wp = wrench(&plus)?;
        let wm = wrench(&minus)?;
        for i in 0..3 {
            j[i][k] = (wp[i] - wm[i]) / (2.0 * h[k]);
        }
    }
    Ok(j)
}
