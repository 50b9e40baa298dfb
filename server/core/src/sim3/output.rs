//! Stage 7 of the 3D step (module docs) and what the simulation reports: the per-tick output
//! ([`StepOutput3`], rewritten in place), the life-long counters ([`Sim3Stats`]), and the static
//! problem the last step solved ([`Snapshot3`]).

use crate::contact::ContactPoint;
use crate::d3::disc::Disc;
use crate::ids::{Axis, Slot};
use crate::mixed::Condition;

use super::{BasePose3, PointState3, Simulation3, TargetsOut3, add, cross, dot, sub};
#[cfg(doc)]
use super::{MAX_PENDING_CAPTURES, SHAPE_GAP_TOL_M, SHAPE_PASSES, Sim3Params, targets};

/// Counters over the simulation's life.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Sim3Stats {
    pub captures: u64,
    pub punctures: u64,
    /// Points released: withdrawn past by the tip, or let go by the tip.
    pub releases: u64,
    pub stick_to_slip: u64,
    pub slip_to_stick: u64,
    /// Ticks a due capture waited for its nodes' columns (with node blocks: for the blocks of
    /// its nodes or of the tetrahedra its fixed point passed through).
    pub column_deferrals: u64,
    /// Captures refused because their conditions were dependent on the others' (not expected
    /// with the distance rule).
    pub dependent_points: u64,
    /// Captures dropped for a full working set.
    pub capacity_drops: u64,
    /// Ticks whose commanded pose was clamped.
    pub clamped_ticks: u64,
    /// Ticks whose active set did not settle within the iteration bound.
    pub unconverged_ticks: u64,
    /// Flexible needle: ticks whose shape passes stopped at [`SHAPE_PASSES`] with the settled
    /// shape still more than [`SHAPE_GAP_TOL_M`] off ([`StepOutput3::shape_passes_capped`]).
    pub shape_capped_ticks: u64,
    /// Held points torn free: their force across the shaft exceeded what their region's tissue
    /// holds (`needlesim_core::sim3::tear`; also counted in `releases`).
    pub tears: u64,
    /// Contacts taken as points although [`Sim3Params::disc_radius_m`] spreads them over a
    /// disc: the disc touched more than [`crate::contact::MAX_TERMS`] nodes or was not wholly
    /// inside the tissue (as 2D's `patch_fallbacks`).
    pub patch_fallbacks: u64,
    /// Approaching nodes not reported (list full).
    pub approaching_overflow: u64,
    /// Cached nodes evicted to make room.
    pub columns_evicted: u64,
    /// Inserts past [`Sim3Params::max_cached_nodes`] with nothing evictable.
    pub cache_over_cap: u64,
    /// Points the tip passed while their columns were missing, captured once the columns
    /// arrived (as stuck shaft points where they then were; a live session's worker behind the
    /// tip, issue 17). Included in `captures`.
    pub late_captures: u64,
    /// Waiting points given up: the tip withdrew past them, they lay too close to a held point
    /// or outside the mesh, or the waiting list ([`MAX_PENDING_CAPTURES`]) or the working set
    /// was full.
    pub pending_dropped: u64,
    /// Round-off checks of the hybrid matrix made (one row every
    /// [`crate::sim::param_limits::HYBRID_CHECK_EVERY_TICKS`] ticks, [`crate::drift`], as 2D's).
    pub hybrid_checks: u64,
    /// Of them, rebuilds of the hybrid matrix: a residual over
    /// [`crate::sim::param_limits::HYBRID_DRIFT_TOL`] (not expected; each one $O(d^3)$ and
    /// allocating).
    pub hybrid_rebuilds: u64,
    /// Rebuilds the solver refused (its old matrix kept).
    pub hybrid_rebuild_failures: u64,
}

/// One contact point in a step's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOut3 {
    pub state: PointState3,
    /// Its frame, rows $[t, n, b]$.
    pub frame: [[f64; 3]; 3],
    /// Reference position $X$, m.
    pub x_ref_m: [f64; 3],
    /// Current position $X + u$ of the tissue's material point, m (with the needle's near field,
    /// [`Sim3Params::near_field`], the needle's surface point less the near-field part).
    pub x_m: [f64; 3],
    /// Force of the needle on the tissue there, world, N.
    pub force_n: [f64; 3],
    /// Its kinetic friction share, N.
    pub friction_n: f64,
}

/// The per-tick output, rewritten in place.
#[derive(Debug, Clone, PartialEq)]
pub struct StepOutput3 {
    /// The tick this output belongs to (0 for the initial output).
    pub tick: u64,
    /// $t = k / f_{tick}$, s.
    pub time_s: f64,
    /// The pose applied (after clamping).
    pub pose: BasePose3,
    pub clamped: bool,
    /// Force of the tissue on the needle base, world, N: $F = -\sum_i f_i$.
    pub base_force_n: [f64; 3],
    /// Torque of the tissue on the needle about the base point, world, N·m.
    pub base_torque_nm: [f64; 3],
    /// The axial force the tissue resists the needle with, $t\cdot\sum_i f_i = -t\cdot F$, N:
    /// positive while pushing in, negative while pulling out.
    pub axial_force_n: f64,
    /// Tip position, m.
    pub tip_m: [f64; 3],
    /// Length of shaft from the most proximal contact to the tip (0 without contacts), m.
    pub inserted_length_m: f64,
    /// The working points, in slot order.
    pub contacts: Vec<ContactOut3>,
    /// Nodes (not cached) of the tetrahedra on the axis ahead of the tip, the next point's
    /// first: what [`Simulation3::prefetch_columns`] computes.
    pub approaching: Vec<usize>,
    pub active_set_iterations: usize,
    /// The stick/slip iteration settled within `max_active_set_iterations` passes
    /// ([`StepOutput3::unconverged`] says why not).
    pub converged: bool,
    /// Flexible needle: the shape passes stopped at their cap with the shape still changing
    /// (counted in [`Sim3Stats::shape_capped_ticks`]); always `false` for a rigid needle.
    pub shape_passes_capped: bool,
    /// The targets ([`Sim3Params::targets`]): displaced centres, distances, latched states
    /// ([`targets`]).
    pub targets: TargetsOut3,
}

/// One contact of [`Snapshot3`], in the exchange format's terms (`points`: `x`, `frame`, `ut`,
/// `un`, `ub`, `f`; a disc as `patches`: its nodes and weights instead of `x`), with the
/// simulation's answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnapshotPoint3 {
    /// Reference position, m (a disc's centre).
    pub x_m: [f64; 3],
    /// Where the contact sits in the mesh: a material point's tetrahedron and barycentric
    /// weights, or a disc's nodes and weights ([`ContactPoint::terms`]).
    pub contact: ContactPoint,
    /// The disc the contact spreads over (its axis as captured), `None` for a material point.
    pub disc: Option<Disc>,
    /// Frame rows $[t, n, b]$ as the solver holds them.
    pub frame: [[f64; 3]; 3],
    /// Prescribed displacement components (m), `None` where free: the tissue's (with a needle near
    /// field, the needle's values less its near-field part, so that the tissue alone re-solves it).
    pub ut: Option<f64>,
    pub un: Option<f64>,
    pub ub: Option<f64>,
    /// The prescribed (friction) force, world, N; `None` for a point with every component
    /// prescribed.
    pub f_n: Option<[f64; 3]>,
    /// The simulation's total force of the needle on the tissue there, world, N (constraint
    /// reaction plus `f_n`).
    pub force_n: [f64; 3],
    /// The simulation's displacement there, world, m.
    pub u_m: [f64; 3],
}

/// The static problem the last step solved.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot3 {
    pub tick: u64,
    pub points: Vec<SnapshotPoint3>,
}

impl Simulation3 {
    /// The static problem the last step solved: per working point its reference position (and
    /// its terms: a point's tetrahedron or a disc's nodes and weights), frame, prescribed displacement components, prescribed (friction) force in world
    /// components, and the simulation's force and displacement there. Allocates (not for the
    /// real-time thread).
    pub fn snapshot(&self) -> Snapshot3 {
        let points = Slot::all(self.pts.len())
            .map(|slot| {
                let p = &self.pts[slot.index()];
                let frame = self.solver.frame(slot);
                // The tissue's problem: the needle's near field taken off the prescribed
                // displacements (the solved forces give it; zero without a near field).
                let nf = self.solver.series_displacement_world(slot);
                let nf_local = |a: Axis| dot(frame[a.index()], nf);
                let disp = |a: Axis| {
                    (self.solver.condition(slot, a) == Condition::Displacement).then(|| self.solver.prescribed_value(slot, a) - nf_local(a))
                };
                let mut f = [0.0; 3];
                let mut any_force = false;
                for a in Axis::ALL3 {
                    if self.solver.condition(slot, a) == Condition::Force {
                        any_force = true;
                        let v = self.solver.prescribed_value(slot, a);
                        for c in 0..3 {
                            f[c] += v * frame[a.index()][c];
                        }
                    }
                }
                SnapshotPoint3 {
                    x_m: p.x_ref_m,
                    contact: p.contact,
                    disc: p.disc,
                    frame,
                    ut: disp(Axis::Axial),
                    un: disp(Axis::Lateral),
                    ub: disp(Axis::Binormal),
                    f_n: any_force.then_some(f),
                    force_n: self.solver.force_world(slot),
                    u_m: sub(self.solver.displacement_world(slot), nf),
                }
            })
            .collect();
        Snapshot3 { tick: self.out.tick, points }
    }

    /// Stage 7: forces, wrench, tip, points; each point's arc length for the next tick; the
    /// working points' nodes marked in use.
    pub(super) fn write_output(&mut self, frame: &[[f64; 3]; 3], clamped: bool, iterations: usize, converged: bool) {
        let base = self.pose.position_m;
        let len = self.params.needle_length_m;
        let out = &mut self.out;
        out.tick = self.tick;
        out.time_s = self.tick as f64 / self.params.tick_rate_hz;
        out.pose = self.pose;
        out.clamped = clamped;
        out.tip_m = match &self.flex {
            None => self.pose.point_at(len),
            Some(fx) => fx.rod.tip_m(),
        };
        out.active_set_iterations = iterations;
        out.converged = converged;
        out.contacts.clear();
        let (mut force, mut torque, mut s_min) = ([0.0; 3], [0.0; 3], f64::INFINITY);
        for slot in Slot::all(self.pts.len()) {
            let f = self.solver.force_world(slot);
            let p = &mut self.pts[slot.index()];
            // The true displacement (the solver's is measured from the shifted reference,
            // [`crate::viscous`]).
            let u = p.visc.shifted(self.solver.displacement_world(slot));
            p.f_world = f;
            p.u_world = u;
            let x = add(p.x_ref_m, u);
            let r = sub(x, base);
            let neg = [-f[0], -f[1], -f[2]];
            force = add(force, neg);
            torque = add(torque, cross(r, neg));
            let (s, point_frame) = match &self.flex {
                None => (dot(frame[0], r), *frame),
                Some(fx) => {
                    let pf = self.solver.frame(slot);
                    (fx.arc_of(p, &pf, x), pf)
                }
            };
            p.s_prev_m = s;
            s_min = s_min.min(s);
            for n in p.contact.nodes() {
                self.stamp[n.index()] = self.tick + 1;
            }
            out.contacts.push(ContactOut3 {
                state: p.state,
                frame: point_frame,
                x_ref_m: p.x_ref_m,
                x_m: sub(x, self.solver.series_displacement_world(slot)),
                force_n: f,
                friction_n: p.friction_n,
            });
        }
        out.base_force_n = force;
        out.base_torque_nm = torque;
        out.axial_force_n = -dot(frame[0], force);
        out.inserted_length_m = if s_min.is_finite() { (len - s_min).max(0.0) } else { 0.0 };
    }
}
