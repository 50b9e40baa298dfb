//! Stages 1 and 2 of a step, and the needle geometry every stage reads: the base pose (clamped),
//! the node frames that turn with the needle, and the prescribed values that keep each needle
//! node on the shaft. The rigid/flexible distinction of the geometry lives here
//! ([`Geometry`]) and in [`super::flexible`], nowhere else.

use crate::beam::NeedleCurve;
use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedSolver};
use crate::needle::{BasePose, NeedleShape};

use super::flexible;
use super::state::{FlexState, NeedleNode, NodeState, WorkingSet};
use super::{SimError, SimParams};

/// A frame on the needle: coordinates $(s_0 + t\cdot(p - o),\ n\cdot(p - o))$ of a point $p$
/// (arc length along the shaft, lateral offset across it).
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub origin: [f64; 2],
    pub s0: f64,
    pub t: [f64; 2],
    pub n: [f64; 2],
}

impl Frame {
    /// The frame at shaft point `origin` (arc length `s0`) turned to `angle_rad`.
    pub fn new(origin: [f64; 2], s0: f64, angle_rad: f64) -> Self {
        let (sn, cs) = angle_rad.sin_cos();
        Self { origin, s0, t: [cs, sn], n: [-sn, cs] }
    }
    /// The straight rigid needle's frame (the same arithmetic as [`NeedleShape::project`]).
    pub fn rigid(pose: &BasePose) -> Self {
        Self { origin: pose.position_m(), s0: 0.0, t: pose.axis(), n: pose.normal() }
    }
    /// The coordinates (arc length m, lateral offset m) of `p` in this frame.
    #[inline]
    pub fn coords(&self, p: [f64; 2]) -> (f64, f64) {
        let d = [p[0] - self.origin[0], p[1] - self.origin[1]];
        let s = self.t[0] * d[0] + self.t[1] * d[1];
        (if self.s0 == 0.0 { s } else { self.s0 + s }, self.n[0] * d[0] + self.n[1] * d[1])
    }
}

/// The needle as the stages see it at one instant: its shape parameters, the base pose and, for
/// a flexible needle, its current curve.
#[derive(Clone, Copy)]
pub(super) struct Geometry<'a> {
    pub shape: &'a NeedleShape,
    pub pose: BasePose,
    pub curve: Option<&'a NeedleCurve>,
    /// The straight needle's frame at `pose`, computed once (rigid needle only; unused, and not
    /// computed, for a flexible one).
    rigid: Frame,
}

impl<'a> Geometry<'a> {
    pub fn new(params: &'a SimParams, pose: BasePose, flex: Option<&'a FlexState>) -> Self {
        Self::of(&params.needle, pose, flex.map(|f| &f.curve))
    }
    /// The geometry of `shape` at `pose`, bent along `curve` if it is flexible.
    pub fn of(shape: &'a NeedleShape, pose: BasePose, curve: Option<&'a NeedleCurve>) -> Self {
        let rigid = match curve {
            None => Frame::rigid(&pose),
            Some(_) => Frame { origin: [0.0; 2], s0: 0.0, t: [1.0, 0.0], n: [0.0, 1.0] },
        };
        Self { shape, pose, curve, rigid }
    }
    /// The arc length of the tip, $L$.
    #[inline]
    pub fn s_tip_m(&self) -> f64 {
        self.shape.tip_s_m()
    }
    /// The tip's position.
    #[inline]
    pub fn tip(&self) -> [f64; 2] {
        match self.curve {
            Some(c) => c.tip_m(),
            None => self.shape.tip_m(&self.pose),
        }
    }
    /// The tip's frame: captures happen along the tip's own tangent.
    #[inline]
    pub fn tip_frame(&self) -> Frame {
        match self.curve {
            Some(c) => Frame::new(c.tip_m(), self.s_tip_m(), c.tip_angle_rad()),
            None => self.rigid,
        }
    }
    /// The frame of needle node `nn` whose solver frame is at `angle_rad`: at its shaft point
    /// (flexible needle), or the straight needle's frame.
    #[inline]
    pub fn node_frame(&self, nn: &NeedleNode, angle_rad: f64) -> Frame {
        match self.curve {
            Some(c) => {
                let s_ref = nn.s_ref_m(self.s_tip_m());
                Frame::new(c.point_at(s_ref), s_ref, angle_rad)
            }
            None => self.rigid,
        }
    }
    /// [`Self::node_frame`] of working slot `slot`.
    #[inline]
    pub fn slot_frame(&self, ws: &WorkingSet, slot: Slot) -> Frame {
        self.node_frame(ws.node(slot), ws.solver.angle_rad(slot))
    }
    /// The solver frame angle and the frame of a node captured at arc length `s_m`, attached at
    /// `s_ref_m` (the tip's arc length for the tip's node, `s_m` otherwise).
    pub fn capture_frame(&self, s_ref_m: f64, s_m: f64) -> (f64, Frame) {
        match self.curve {
            Some(c) => {
                let a = c.tangent_angle_at(s_ref_m);
                (a, Frame::new(c.point_at(s_ref_m), s_ref_m, a))
            }
            None => (self.shape.frame_angle_at(&self.pose, s_m), self.rigid),
        }
    }
}

/// Stage 1: the pose applied this tick, `cmd` with its translation clamped to
/// `max_base_step_m` and its rotation to `max_base_step_rad` from `pose`; the node frames turn
/// with the needle. Writes the new pose into `pose`; returns whether it was clamped.
///
/// Errors: [`SimError::Mixed`] when the solver refuses a frame rotation.
pub(super) fn apply_pose(
    params: &SimParams,
    cmd: BasePose,
    pose: &mut BasePose,
    ws: &mut WorkingSet,
    flex: Option<&mut FlexState>,
) -> Result<bool, SimError> {
    let mut next = cmd;
    let mut clamped = false;
    let (dx, dy) = (cmd.x_m - pose.x_m, cmd.y_m - pose.y_m);
    let dist = dx.hypot(dy);
    if dist > params.max_base_step_m {
        let k = params.max_base_step_m / dist;
        next.x_m = pose.x_m + k * dx;
        next.y_m = pose.y_m + k * dy;
        clamped = true;
    }
    let dth = cmd.theta_rad - pose.theta_rad;
    if dth.abs() > params.max_base_step_rad {
        next.theta_rad = pose.theta_rad + params.max_base_step_rad.copysign(dth);
        clamped = true;
    }
    if let Some(fx) = flex {
        fx.curve.set_base(next);
        let dth = next.theta_rad - pose.theta_rad;
        if dth != 0.0 {
            for slot in Slot::all(ws.solver.n_nodes()) {
                let a = ws.solver.angle_rad(slot) + dth;
                ws.solver.set_angle(slot, a)?;
            }
        }
        flexible::refresh_frames(&fx.curve, ws, params.needle.tip_s_m())?;
    } else if next.theta_rad != pose.theta_rad {
        for slot in Slot::all(ws.solver.n_nodes()) {
            let s = ws.node(slot).s_prev_m;
            let a = params.needle.frame_angle_at(&next, s);
            ws.solver.set_angle(slot, a)?;
        }
    }
    *pose = next;
    Ok(clamped)
}

/// Stage 2: every needle node's prescribed values from the current geometry: laterally
/// $u_n = o - n\cdot(X - x_0)$ (its offset $o$ from the shaft), axially $u_t = s_a - s(X)$ for
/// a stuck node held at $s_a$ and $u_t = L - s(X)$ for the tip's node.
pub(super) fn set_prescribed_values(geo: &Geometry<'_>, ws: &mut WorkingSet) {
    let s_tip = geo.s_tip_m();
    for slot in ws.slots() {
        let nn = *ws.node(slot);
        let x = nn.x_kin_m();
        let frame = geo.slot_frame(ws, slot);
        ws.node_mut(slot).lateral_ref_m = prescribe(&mut ws.solver, slot, &nn, frame, x, s_tip);
    }
}

/// Sets the prescribed values of working slot `slot` in `solver` from the node's reference
/// position `x_m` seen in `frame`: across the shaft (when that DOF is displacement-prescribed)
/// the value that puts the node at its lateral offset from the needle, along it the anchor of a
/// stuck node or the tip's arc length for the node the tip carries. Returns the lateral value.
pub(super) fn prescribe(solver: &mut MixedSolver, slot: Slot, nn: &NeedleNode, frame: Frame, x_m: [f64; 2], s_tip_m: f64) -> f64 {
    let (s0, lat0) = frame.coords(x_m);
    let lateral = nn.lat_offset_m - lat0;
    if solver.condition(slot, Axis::Lateral) == Condition::Displacement {
        solver.set_value(slot, Axis::Lateral, lateral);
    }
    match nn.state {
        NodeState::Stuck => solver.set_value(slot, Axis::Axial, nn.anchor_s_m - s0),
        NodeState::Tip => solver.set_value(slot, Axis::Axial, s_tip_m - s0),
        NodeState::Slipping => {}
    }
    lateral
}
