//! Stages 1-2 of the 3D step (module docs): the frame of a pose, the prescribed values that put
//! the working points on the shaft, and the arc coordinate of a point in its frame.

use crate::ids::{Axis, Slot};

use super::{BasePose3, PointState3, SimError3, Simulation3, dot, sub};

impl Simulation3 {
    /// Stage 2: every working point's frame becomes the pose's (a flexible needle's: the
    /// rod's, after its base moved), and its prescribed values put it on the shaft.
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses a frame.
    pub(super) fn set_frames(&mut self, frame: &[[f64; 3]; 3], turned: bool) -> Result<(), SimError3> {
        let pose = self.pose;
        if let Some(fx) = self.flex.as_mut() {
            fx.rod.set_base(pose.position_m, *frame);
            fx.refresh_frames(&mut self.solver, &self.pts, turned)?;
            fx.set_values(&mut self.solver, &mut self.pts);
        } else {
            for slot in Slot::all(self.pts.len()) {
                self.solver.set_frame(slot, *frame)?;
            }
            self.set_prescribed_values(frame);
        }
        Ok(())
    }

    /// The pose and frame a capture works along: the base pose's for a rigid needle, the tip
    /// tangent's for a flexible one (a pose whose axis runs through the tip along it).
    pub(super) fn capture_axis(&self, frame: &[[f64; 3]; 3]) -> (BasePose3, [[f64; 3]; 3]) {
        let len = self.params.needle_length_m;
        match &self.flex {
            None => (self.pose, *frame),
            Some(fx) => {
                let tf = fx.rod.tip_frame();
                let tip = fx.rod.tip_m();
                let base_v = [tip[0] - len * tf[0][0], tip[1] - len * tf[0][1], tip[2] - len * tf[0][2]];
                (BasePose3::from_rotation(base_v, quaternion_of_frame(&tf)), tf)
            }
        }
    }

    /// The arc coordinate of slot's reference position in its frame (a displacement's axial
    /// component adds to it): $t\cdot(X - x_b)$ for a rigid needle, [`flex::Flex3::ref_arc`]
    /// for a flexible one.
    pub(super) fn ref_arc(&self, slot: Slot, frame: &[[f64; 3]; 3], base: [f64; 3]) -> f64 {
        let p = &self.pts[slot.index()];
        match &self.flex {
            None => dot(frame[0], sub(p.x_kin_m(), base)),
            Some(fx) => fx.ref_arc(p, &self.solver.frame(slot)),
        }
    }

    fn set_prescribed_values(&mut self, frame: &[[f64; 3]; 3]) {
        let base = self.pose.position_m;
        let len = self.params.needle_length_m;
        for slot in Slot::all(self.pts.len()) {
            let p = &self.pts[slot.index()];
            let d = sub(p.x_kin_m(), base);
            self.solver.set_value(slot, Axis::Lateral, -dot(frame[1], d));
            self.solver.set_value(slot, Axis::Binormal, -dot(frame[2], d));
            match p.state {
                PointState3::Stuck => self.solver.set_value(slot, Axis::Axial, p.anchor_s_m - dot(frame[0], d)),
                PointState3::Tip => self.solver.set_value(slot, Axis::Axial, len - dot(frame[0], d)),
                PointState3::Slipping => {}
            }
        }
    }
}

/// The unit quaternion of a frame with rows $[t, n, b]$ (the rotation whose columns they are).
fn quaternion_of_frame(f: &[[f64; 3]; 3]) -> nalgebra::UnitQuaternion<f64> {
    let m = nalgebra::Matrix3::new(f[0][0], f[1][0], f[2][0], f[0][1], f[1][1], f[2][1], f[0][2], f[1][2], f[2][2]);
    nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(m))
}

/// The tip's frame of a flexible needle (the axis the targets' "ahead" is measured along).
pub(super) fn axis_frame_now(sim: &Simulation3) -> [[f64; 3]; 3] {
    sim.flex.as_ref().map_or_else(|| sim.pose.frame(), |f| f.rod.tip_frame())
}
