//! The 3D simulation's working points: each point's contact state ([`PointState3`]) and
//! bookkeeping ([`Point`], by slot as the solver's), and their removal from the working set.

use crate::contact::ContactPoint;
use crate::d3::disc::Disc;
use crate::ids::Slot;
use crate::mixed::MixedError;
use crate::viscous::History;

use super::Simulation3;

/// The state of a contact point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointState3 {
    /// Held at its shaft anchor: $u_t$ prescribed.
    Stuck,
    /// Sliding along the shaft: $f_t$ prescribed (its friction share, against the motion).
    Slipping,
    /// Carried by the tip until puncture or cutting: $u_t$ prescribed at the tip.
    Tip,
}

/// A working point's bookkeeping (by slot, as the solver's).
#[derive(Debug, Clone, Copy)]
pub(super) struct Point {
    pub contact: ContactPoint,
    pub x_ref_m: [f64; 3],
    pub state: PointState3,
    /// Shaft arc length a stuck point is held at.
    pub anchor_s_m: f64,
    /// Shaft arc length of its deformed position at the end of the last tick.
    pub s_prev_m: f64,
    /// The arc length the friction shares use this sweep.
    pub s_work_m: f64,
    pub friction_n: f64,
    pub friction_new_n: f64,
    /// Sign of the axial friction force on the tissue (+1 while the needle goes in).
    pub slip_sign: f64,
    pub release_force_n: f64,
    pub region: usize,
    pub f_world: [f64; 3],
    pub u_world: [f64; 3],
    /// Flexible needle: the lateral values $g$ that put the point on the reference shape, and
    /// the force (its frame) the reference shape is in equilibrium with ([`flex`]).
    pub lat_ref_m: [f64; 2],
    pub f_ref_local_n: [f64; 3],
    /// The disc `contact` spreads over (centre `x_ref_m`, the tangent at capture), `None` for a
    /// material point ([`super::Sim3Params::disc_radius_m`]).
    pub disc: Option<Disc>,
    /// Viscous history (all zero in an elastic tissue; [`crate::viscous`]).
    pub visc: History<3>,
}

impl Point {
    /// The position the working solver's displacement is measured from: the reference
    /// position shifted by the viscous history ([`crate::viscous`]; $X$ itself in an elastic
    /// tissue). Where the prescribed values and the arc lengths put the point.
    #[inline]
    pub fn x_kin_m(&self) -> [f64; 3] {
        self.visc.shifted(self.x_ref_m)
    }
}

impl Simulation3 {
    pub(super) fn remove(&mut self, slot: Slot) -> Result<(), MixedError> {
        self.solver.remove_slot(slot)?;
        self.pts.swap_remove(slot.index());
        Ok(())
    }
}
