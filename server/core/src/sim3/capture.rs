//! Stage 4 of the 3D step (module docs): the material point at a deformed position (a fixed
//! point through the compliance), the tip's capture with its distance rule, each captured point
//! spread over a disc across the shaft when the needle's contact is ([`Sim3Params::disc_radius_m`]),
//! and the points the tip passed while their columns were missing, captured late.

use crate::compliance::ContactBlocks;
use crate::contact::ContactPoint;
use crate::d3::disc::{Disc, disc_weights_into};
use crate::d3::locate::{BARYCENTRIC_TOL, barycentric};
use crate::ids::{Axis, Slot};
use crate::mixed::{Condition, MixedError};
use crate::needle::RegionNeedleParams;
use crate::viscous::{History, ScaledBlocks};

use super::state::Point;
use super::{
    BasePose3, LATE_CAPTURES_PER_TICK, LOCATE_ITERATIONS, MAX_PENDING_CAPTURES, PointState3, SimError3, Simulation3, add, dist, dot, sub,
};
#[cfg(doc)]
use super::{Sim3Params, Sim3Stats};

/// A disc counts as wholly inside the tissue when its covered share is within this of 1.
const DISC_COVER_TOL: f64 = 1e-9;

impl Simulation3 {
    /// Stage 3: the points the tip withdrew past (their deformed position beyond the tip)
    /// leave the working set.
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses a removal.
    pub(super) fn release_withdrawn(&mut self, frame: &[[f64; 3]; 3]) -> Result<(), SimError3> {
        let len = self.params.needle_length_m;
        let base = self.pose.position_m;
        for k in (0..self.pts.len()).rev() {
            let p = self.pts[k];
            let beyond = match &self.flex {
                None => dot(frame[0], sub(add(p.x_ref_m, p.u_world), base)) > len,
                Some(fx) => fx.arc_of(&p, &self.solver.frame(Slot::new(k)), add(p.x_ref_m, p.u_world)) > len,
            };
            if p.state != PointState3::Tip && beyond {
                self.remove(Slot::new(k))?;
                self.stats.releases += 1;
            }
        }
        Ok(())
    }

    /// The displacement of any contact from the working forces of the last solve,
    /// $u_q = \sum_w W_{qw} f_w$ (with columns it needs the working points' columns, with node
    /// blocks also `q`'s nodes); `None` when a block is missing. $O(d)$.
    fn contact_displacement(&self, q: &ContactPoint) -> Option<[f64; 3]> {
        let mut u = [0.0; 3];
        for p in &self.pts {
            let b = self.cache.contact_block(q, &p.contact)?;
            for r in 0..3 {
                u[r] += b[r][0] * p.f_world[0] + b[r][1] * p.f_world[1] + b[r][2] * p.f_world[2];
            }
        }
        Some(u)
    }

    /// The viscous history of a contact captured now ([`crate::viscous`]): $h = u = v$ with $v$
    /// its pseudo-elastic displacement $C_0 f$ from the working forces (`fallback_m`, the
    /// capture's fixed point's, if a block is missing); zero in an elastic tissue.
    fn captured_history(&self, contact: &ContactPoint, fallback_m: [f64; 3]) -> History<3> {
        match &self.setup.visc {
            None => History::default(),
            Some(c) => History::captured(c, self.contact_displacement(contact).unwrap_or(fallback_m)),
        }
    }

    /// The material point $X$ at deformed position `p_m`: the fixed point of $X = p - u(X)$
    /// from $X_0 = p - u_0$; `Ok(None)` when it lies outside the mesh, `Err(c)` when the
    /// displacement at an iterate `c` needs blocks that are not cached.
    // The `Ok` value holds a contact as well: both variants are the same size, on the stack.
    #[allow(clippy::result_large_err)]
    fn material_point_at(&self, p_m: [f64; 3], u0: [f64; 3]) -> Result<Option<(ContactPoint, [f64; 3])>, ContactPoint> {
        let mut x = sub(p_m, u0);
        let tol = 1e-12 * self.setup.sample_step_m;
        let mesh = self.model.mesh();
        let Ok(mut loc) = self.model.locate(x) else { return Ok(None) };
        for it in 0..LOCATE_ITERATIONS {
            if it > 0 {
                // The iterate usually stays in its tetrahedron: one barycentric test rather than
                // a search of the locator's cell.
                let w = barycentric(mesh.tet_points_m(loc.tet_idx), x);
                if w.iter().all(|&v| v >= -BARYCENTRIC_TOL) {
                    loc.weights = w;
                } else {
                    let Ok(l) = self.model.locate(x) else { return Ok(None) };
                    loc = l;
                }
            }
            let c = ContactPoint::in_tetrahedron(loc.tet_idx, loc.nodes, loc.weights);
            let next = sub(p_m, self.contact_displacement(&c).ok_or(c)?);
            let moved = dist(next, x);
            x = next;
            if moved <= tol {
                break;
            }
        }
        let Ok(loc) = self.model.locate(x) else { return Ok(None) };
        Ok(Some((ContactPoint::in_tetrahedron(loc.tet_idx, loc.nodes, loc.weights), x)))
    }

    /// Stage 4 (module docs), and the approaching nodes.
    pub(super) fn capture(&mut self, prev_tip: [f64; 3], axis_pose: &BasePose3, frame: &[[f64; 3]; 3]) -> Result<(), SimError3> {
        let len = self.params.needle_length_m;
        let base = axis_pose.position_m;
        let t = frame[0];
        let has_tip = self.pts.iter().any(|p| p.state == PointState3::Tip);
        let distal = (0..self.pts.len()).max_by(|&a, &b| self.pts[a].s_prev_m.total_cmp(&self.pts[b].s_prev_m));
        let s_distal = distal.map(|k| if self.pts[k].state == PointState3::Tip { len } else { self.pts[k].s_prev_m });
        let u_d = distal.map_or([0.0; 3], |k| self.pts[k].u_world);
        // A waiting point counts as taken for the spacing of the next.
        let s_distal = self.pending.iter().map(|p| dot(t, sub(*p, base))).chain(s_distal).reduce(f64::max);
        let pending_missing = self.capture_pending(axis_pose, frame, u_d)?;
        let s_prev_tip = dot(t, sub(prev_tip, base));
        let advancing = len - s_prev_tip > 1e-9;
        let due = !has_tip && advancing && s_distal.is_none_or(|s| len - s >= self.params.spacing_m);
        if !due && let Some(first) = self.deferred_since_m.take() {
            // The tip stopped (or holds a point) before the waiting capture got its columns.
            self.push_pending(first);
        }
        let mut missing: Option<ContactPoint> = None;
        let mut candidate = if due {
            self.material_point_at(prev_tip, u_d).unwrap_or_else(|c| {
                missing = Some(c);
                None
            })
        } else {
            None
        };
        if candidate.is_some_and(|(c, x)| self.too_close(&c, x)) {
            candidate = None;
        }
        // Spread over the needle's cross-section: the disc's nodes are the ones to cache.
        let mut spread = None;
        if let Some((c, x)) = candidate {
            let (contact, disc, fell_back) = self.spread(c, x, t);
            candidate = Some((contact, x));
            spread = Some((disc, fell_back));
        }
        self.update_approaching([pending_missing, candidate.map(|c| c.0).or(missing)], u_d, axis_pose, frame);
        if missing.is_some() {
            // Node blocks: the fixed point needed a tetrahedron whose nodes are not cached.
            self.stats.column_deferrals += 1;
            self.defer_capture(prev_tip, t);
            return Ok(());
        }
        let Some((contact, x)) = candidate else { return Ok(()) };
        if self.pts.len() == self.params.max_contacts {
            self.stats.capacity_drops += 1;
            return Ok(());
        }
        if !self.cache.contains_contact(&contact) {
            self.stats.column_deferrals += 1;
            self.defer_capture(prev_tip, t);
            return Ok(());
        }
        let visc = self.captured_history(&contact, sub(prev_tip, x));
        let d = sub(visc.shifted(x), base);
        let s_new = dot(t, sub(prev_tip, base));
        let region = self.region_of(&contact);
        let entering = self.pts.is_empty() || self.last_tip_region != Some(region);
        let rp: RegionNeedleParams = self.params.regions[region];
        if !self.add_held_point(contact, frame, d, len)? {
            return Ok(());
        }
        self.last_tip_region = Some(region);
        self.deferred_since_m = None;
        let (disc, fell_back) = spread.unwrap_or((None, false));
        self.stats.patch_fallbacks += u64::from(fell_back);
        self.pts.push(Point {
            contact,
            x_ref_m: x,
            state: PointState3::Tip,
            anchor_s_m: s_new,
            s_prev_m: s_new,
            s_work_m: s_new,
            friction_n: 0.0,
            friction_new_n: 0.0,
            slip_sign: 1.0,
            release_force_n: if entering { rp.puncture_force_n } else { rp.cutting_force_n },
            region,
            f_world: [0.0; 3],
            u_world: sub(prev_tip, x),
            lat_ref_m: [-dot(frame[1], d), -dot(frame[2], d)],
            f_ref_local_n: [0.0; 3],
            disc,
            visc,
        });
        self.stats.captures += 1;
        Ok(())
    }

    /// The contact a captured material point `point` at reference position `x_m` becomes: with
    /// [`Sim3Params::disc_radius_m`] > 0 the disc of that radius centred at `x_m` across `axis`
    /// ([`ContactPoint::disc`], its weights by [`disc_weights_into`] into the scratch sized in
    /// [`Simulation3::new`]: nothing allocated); else the point itself. A disc with more than
    /// [`crate::contact::MAX_TERMS`] weighted nodes, not wholly inside the tissue, or otherwise
    /// refused stays the point, flagged (the caller counts it in [`Sim3Stats::patch_fallbacks`]
    /// once the contact is taken). Returns the contact, its disc, and whether it fell back.
    fn spread(&mut self, point: ContactPoint, x_m: [f64; 3], axis: [f64; 3]) -> (ContactPoint, Option<Disc>, bool) {
        let radius_m = self.params.disc_radius_m;
        if radius_m <= 0.0 {
            return (point, None, false);
        }
        let Some(tet) = point.tet_idx() else { return (point, None, true) };
        let disc = Disc { centre_m: x_m, axis, radius_m };
        let w = &mut self.scratch.disc;
        if disc_weights_into(self.model.mesh(), self.model.locator(), &disc, w).is_err() || w.covered_fraction() < 1.0 - DISC_COVER_TOL {
            return (point, None, true);
        }
        match ContactPoint::disc(tet, w.nodes().iter().copied().zip(w.weights().iter().copied())) {
            Ok(c) => (c, Some(disc), false),
            Err(_) => (point, None, true),
        }
    }

    /// The distance rule of a capture: whether the material point `contact` at reference
    /// position `x_m` lies within both its and a held point's tetrahedron diameters of one.
    fn too_close(&self, contact: &ContactPoint, x_m: [f64; 3]) -> bool {
        let diam = |c: &ContactPoint| c.tet_idx().map_or(0.0, |k| self.setup.tet_diam_m[k]);
        self.pts.iter().any(|p| dist(p.x_ref_m, x_m) <= diam(contact).max(diam(&p.contact)) * (1.0 + 1e-9))
    }

    /// The mesh region of a material point's tetrahedron.
    fn region_of(&self, contact: &ContactPoint) -> usize {
        let tet = contact.tet_idx().expect("a material point lies in a tetrahedron");
        self.model.mesh().region_of_tet().get(tet).copied().unwrap_or(0)
    }

    /// Adds `contact` to the solver in `frame`, held on the axis at arc length `s_m`: its
    /// lateral and binormal displacements put its reference position (`d` = $X - x_b$) on the
    /// axis, its axial one at $s$ (the tip's capture: $s = L$). Returns `false` when its
    /// conditions depend on the others' (removed again and counted in `dependent_points`).
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses it for another reason.
    fn add_held_point(&mut self, contact: ContactPoint, frame: &[[f64; 3]; 3], d: [f64; 3], s_m: f64) -> Result<bool, SimError3> {
        let blocks = ScaledBlocks { cache: &self.cache, scale: self.setup.compliance_scale };
        let slot = self.solver.add_contact_in_frame(&blocks, contact, *frame)?;
        let r = self
            .solver
            .set_condition(slot, Axis::Lateral, Condition::Displacement, -dot(frame[1], d))
            .and_then(|()| self.solver.set_condition(slot, Axis::Binormal, Condition::Displacement, -dot(frame[2], d)))
            .and_then(|()| self.solver.set_condition(slot, Axis::Axial, Condition::Displacement, s_m - dot(frame[0], d)));
        match r {
            Ok(()) => Ok(true),
            Err(MixedError::SingularPivot { .. }) => {
                self.solver.remove_slot(slot)?;
                self.stats.dependent_points += 1;
                Ok(false)
            }
            Err(e) => {
                self.solver.remove_slot(slot)?;
                Err(e.into())
            }
        }
    }

    /// A due capture whose columns are missing at `tip_m`. The tip keeps trying where it is
    /// each tick (a capture a tick or two late, as when an offline driver prefetches after the
    /// step, is taken at the tip as before); once the tip has gone `spacing_m` beyond where it
    /// first waited, that position waits in `pending` (the tissue point there is captured once
    /// its columns arrive, [`Self::capture_pending`]) and the next capture is due a spacing
    /// further.
    fn defer_capture(&mut self, tip_m: [f64; 3], t: [f64; 3]) {
        match self.deferred_since_m {
            None => self.deferred_since_m = Some(tip_m),
            Some(first) if dot(t, sub(tip_m, first)) >= self.params.spacing_m => {
                self.deferred_since_m = None;
                self.push_pending(first);
            }
            Some(_) => {}
        }
    }

    fn push_pending(&mut self, p_m: [f64; 3]) {
        if self.pending.len() < MAX_PENDING_CAPTURES {
            self.pending.push(p_m);
        } else {
            self.stats.pending_dropped += 1;
        }
    }

    /// The waiting points (issue 17: a live session's column worker behind the tip), oldest
    /// first, at most [`LATE_CAPTURES_PER_TICK`] per tick. The tissue point at a waiting
    /// position $p$ lies on the shaft now (the needle passed through it and nothing held it
    /// apart), at arc length $s = t \cdot (p - x_b)$: for a rigid needle the point of the axis
    /// there, for a flexible one $p$ itself. Its material point (the fixed point of
    /// [`Self::material_point_at`]) joins as a stuck shaft point anchored at $s$, with its
    /// lateral conditions as a tip capture's: no force step, the active set decides whether it
    /// slips. Dropped (counted) when the tip withdrew past it, when it lies outside the mesh or
    /// within a tetrahedron diameter of a held point, or when the working set is full.
    /// Returns the contact whose columns the first still-waiting point needs (for the
    /// prefetch), if any.
    ///
    /// Errors: [`SimError3::Mixed`] when the solver refuses the point for a reason other than
    /// dependence.
    fn capture_pending(&mut self, axis_pose: &BasePose3, frame: &[[f64; 3]; 3], u_d: [f64; 3]) -> Result<Option<ContactPoint>, SimError3> {
        let len = self.params.needle_length_m;
        let base = axis_pose.position_m;
        let t = frame[0];
        let mut first_missing = None;
        let mut admitted = 0;
        let mut k = 0;
        while k < self.pending.len() {
            let p = self.pending[k];
            let s = dot(t, sub(p, base));
            if s > len {
                self.pending.remove(k);
                self.stats.pending_dropped += 1;
                continue;
            }
            if admitted == LATE_CAPTURES_PER_TICK {
                break;
            }
            let q = if self.flex.is_some() { p } else { axis_pose.point_at(s) };
            let (contact, x) = match self.material_point_at(q, u_d) {
                Err(c) => {
                    first_missing.get_or_insert(c);
                    k += 1;
                    continue;
                }
                Ok(None) => {
                    self.pending.remove(k);
                    self.stats.pending_dropped += 1;
                    continue;
                }
                Ok(Some(found)) => found,
            };
            if !self.cache.contains_contact(&contact) {
                first_missing.get_or_insert(contact);
                k += 1;
                continue;
            }
            if self.too_close(&contact, x) || self.pts.len() == self.params.max_contacts {
                self.pending.remove(k);
                self.stats.pending_dropped += 1;
                continue;
            }
            let (contact, disc, fell_back) = self.spread(contact, x, t);
            if !self.cache.contains_contact(&contact) {
                // The disc reaches nodes beyond the point's: they are the ones to fetch.
                first_missing.get_or_insert(contact);
                k += 1;
                continue;
            }
            self.pending.remove(k);
            let visc = self.captured_history(&contact, sub(q, x));
            let d = sub(visc.shifted(x), base);
            let region = self.region_of(&contact);
            if !self.add_held_point(contact, frame, d, s)? {
                continue;
            }
            self.stats.patch_fallbacks += u64::from(fell_back);
            self.pts.push(Point {
                contact,
                x_ref_m: x,
                state: PointState3::Stuck,
                anchor_s_m: s,
                s_prev_m: s,
                s_work_m: s,
                friction_n: 0.0,
                friction_new_n: 0.0,
                slip_sign: 1.0,
                release_force_n: self.params.regions[region].cutting_force_n,
                region,
                f_world: [0.0; 3],
                u_world: sub(q, x),
                lat_ref_m: [-dot(frame[1], d), -dot(frame[2], d)],
                f_ref_local_n: [0.0; 3],
                disc,
                visc,
            });
            self.stats.captures += 1;
            self.stats.late_captures += 1;
            admitted += 1;
        }
        Ok(first_missing)
    }
}

#[cfg(test)]
mod tests {
    use crate::d3::disc::{DiscWeights, disc_weights_into};
    use crate::fixtures::{box_phantom3, box_phantom3_params};
    use crate::sim3::{BasePose3, Simulation3};

    /// Issue 37: with `disc_radius_m` > 0 a captured contact is the disc across the shaft at its
    /// material point: its terms are [`disc_weights_into`]'s for that disc (same nodes, same
    /// weights), and they interpolate a linear field to its value at the disc's centre (the
    /// mean of a linear field over a disc). A distorted field checks the weights, not only
    /// their sum.
    #[test]
    fn issue_37_a_disc_contact_has_the_discs_weights_and_interpolates_a_linear_field_to_its_centre() {
        let model = box_phantom3(13);
        let mut params = box_phantom3_params([0.0513, 0.0487, 0.1], 0.005);
        params.disc_radius_m = 0.635e-3;
        let mut sim = Simulation3::new(model.clone(), params).unwrap();
        let start = sim.pose();
        for k in 1..=3250 {
            let p = start.position_m;
            sim.step(BasePose3::from_rotation([p[0], p[1], p[2] - 2e-5 * k as f64], start.orientation)).unwrap();
            sim.prefetch_columns(usize::MAX).unwrap();
        }
        let mesh = model.mesh();
        let mut w = DiscWeights::with_capacity(64);
        let field = |x: [f64; 3]| [0.3 + 2.0 * x[0] - 5.0 * x[1] + 7.0 * x[2], -1.0 + 11.0 * x[0] + 0.5 * x[2], 4.0 * x[1] - 3.0 * x[2]];
        let mut discs = 0;
        let mut several_tets = 0;
        for p in &sim.pts {
            let Some(disc) = p.disc else { continue };
            discs += 1;
            assert!(p.contact.is_disc(), "a point with a disc is a disc contact");
            assert_eq!(disc.centre_m, p.x_ref_m, "the disc is centred at the material point");
            assert!((disc.radius_m - 0.635e-3).abs() < 1e-18);
            disc_weights_into(mesh, model.locator(), &disc, &mut w).unwrap();
            let ours: Vec<(usize, f64)> = p.contact.terms().map(|(n, v)| (n.index(), v)).collect();
            let want: Vec<(usize, f64)> = w.nodes().iter().copied().zip(w.weights().iter().copied()).filter(|t| t.1 != 0.0).collect();
            assert_eq!(ours, want, "the contact's terms are the disc's weights");
            several_tets += usize::from(ours.len() > 4);
            let got = p.contact.interpolate(|n| field(mesh.nodes_m()[n.index()]));
            let at_centre = field(disc.centre_m);
            for c in 0..3 {
                assert!((got[c] - at_centre[c]).abs() < 1e-13, "component {c}: {} against {} at the centre", got[c], at_centre[c]);
            }
        }
        eprintln!("{discs} discs of {} contacts, {several_tets} across faces; {:?}", sim.pts.len(), sim.stats());
        assert!(discs >= 4, "the needle holds discs: {discs} of {}", sim.pts.len());
        assert!(several_tets >= 1, "some disc crosses a face: {several_tets}");
        // A held point without a disc fell back, and was counted.
        let points = sim.pts.len() - discs;
        assert!(points as u64 <= sim.stats().patch_fallbacks, "{points} points, {:?}", sim.stats());
    }
}
