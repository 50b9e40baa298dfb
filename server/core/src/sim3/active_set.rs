//! Stages 5-6 of the 3D step (module docs): the friction shares over the points' tributary
//! segments, and the bounded stick/slip iteration on the working solver.

use crate::ids::{Axis, Slot};
use crate::mixed::Condition;

use super::{FRICTION_SWEEPS, FRICTION_TOL, PointState3, SimError3, Simulation3};

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Change {
    Puncture,
    LetGo,
    Slip(f64),
    Stick(f64),
}

impl Simulation3 {
    /// Solves the working set: plainly for a rigid needle, coupled to the rod for a flexible one.
    fn solve_working(&mut self) {
        match self.flex.as_mut() {
            None => self.solver.solve(),
            Some(fx) => fx.solve(&mut self.solver, &self.pts, self.tick),
        }
    }

    /// Stage 5: the friction shares from the points' arc lengths (the anchor of a stuck point;
    /// a slipping one's at the end of the last tick, or in the current solution when
    /// `current`). Point $i$ between its neighbours' midpoints $[a_i, b_i]$ (the most proximal
    /// from its own $s$, the most distal to the tip) gets $\int_{L-b_i}^{L-a_i} q(\ell)\,d\ell$.
    /// Applied when a slipping point's share changes by more than `min_change_n` (always when
    /// not `current`). Returns the largest change.
    pub(super) fn update_friction(&mut self, frame: &[[f64; 3]; 3], current: bool, min_change_n: f64) -> f64 {
        let len = self.params.needle_length_m;
        let base = self.pose.position_m;
        self.scratch.order.clear();
        for slot in Slot::all(self.pts.len()) {
            let s0 = self.ref_arc(slot, frame, base);
            let u_t = if current { self.solver.displacement_local(slot)[Axis::Axial] } else { 0.0 };
            let p = &mut self.pts[slot.index()];
            p.s_work_m = match p.state {
                PointState3::Stuck => p.anchor_s_m,
                PointState3::Slipping if current => s0 + u_t,
                PointState3::Slipping => p.s_prev_m,
                PointState3::Tip => continue,
            };
            self.scratch.order.push(slot);
        }
        let pts = &self.pts;
        self.scratch.order.sort_unstable_by(|&a, &b| pts[a.index()].s_work_m.total_cmp(&pts[b.index()].s_work_m));
        let k = self.scratch.order.len();
        let mut max_change: f64 = 0.0;
        for i in 0..k {
            let s = self.pts[self.scratch.order[i].index()].s_work_m;
            let lo = if i == 0 { s } else { 0.5 * (s + self.pts[self.scratch.order[i - 1].index()].s_work_m) };
            let hi = if i + 1 == k { len.max(s) } else { 0.5 * (s + self.pts[self.scratch.order[i + 1].index()].s_work_m) };
            let p = &mut self.pts[self.scratch.order[i].index()];
            let rp = &self.params.regions[p.region];
            p.friction_new_n =
                rp.friction_integral_n(len - hi, len - lo) + rp.friction_damping_n_s_per_m2 * self.axial_speed_m_per_s * (hi - lo);
            if p.state == PointState3::Slipping {
                max_change = max_change.max((p.friction_new_n - p.friction_n).abs());
            }
        }
        if max_change > min_change_n || !current {
            for i in 0..k {
                let slot = self.scratch.order[i];
                let p = &mut self.pts[slot.index()];
                p.friction_n = p.friction_new_n;
                if p.state == PointState3::Slipping && self.solver.condition(slot, Axis::Axial) == Condition::Force {
                    self.solver.set_value(slot, Axis::Axial, p.slip_sign * p.friction_n);
                }
            }
        }
        max_change
    }

    /// Stage 6: the bounded stick/slip iteration. Returns (iterations, converged).
    pub(super) fn resolve_active_set(&mut self, frame: &[[f64; 3]; 3]) -> Result<(usize, bool), SimError3> {
        let base = self.pose.position_m;
        let max_iter = self.params.max_active_set_iterations;
        for iter in 1..=max_iter {
            self.solve_working();
            let total: f64 = self.pts.iter().map(|p| p.friction_n).sum();
            let tol = FRICTION_TOL * total.max(1e-12);
            for _ in 0..FRICTION_SWEEPS {
                if self.update_friction(frame, true, tol) <= tol {
                    break;
                }
                self.solve_working();
            }
            self.scratch.changes.clear();
            for slot in Slot::all(self.pts.len()) {
                let p = self.pts[slot.index()];
                let f_t = self.solver.force_local(slot)[Axis::Axial];
                let s_now = self.ref_arc(slot, frame, base) + self.solver.displacement_local(slot)[Axis::Axial];
                let change = match p.state {
                    PointState3::Tip if f_t > p.release_force_n => Some(Change::Puncture),
                    PointState3::Tip if f_t <= 0.0 => Some(Change::LetGo),
                    PointState3::Tip => None,
                    PointState3::Stuck => {
                        let threshold = (self.params.regions[p.region].static_friction_ratio * p.friction_n).max(1e-12);
                        (f_t.abs() > threshold).then(|| Change::Slip(f_t.signum()))
                    }
                    PointState3::Slipping => (p.slip_sign * (s_now - p.s_prev_m) >= -1e-12).then_some(Change::Stick(p.s_prev_m)),
                };
                if let Some(c) = change {
                    self.scratch.changes.push((slot, c));
                }
            }
            if self.scratch.changes.is_empty() {
                return Ok((iter, true));
            }
            self.scratch.changes.sort_unstable_by_key(|c| std::cmp::Reverse(c.0));
            for i in 0..self.scratch.changes.len() {
                let (slot, change) = self.scratch.changes[i];
                let s0 = self.ref_arc(slot, frame, base);
                match change {
                    Change::Puncture => {
                        let u_t = self.solver.displacement_local(slot)[Axis::Axial];
                        let p = &mut self.pts[slot.index()];
                        p.state = PointState3::Slipping;
                        p.slip_sign = 1.0;
                        p.s_prev_m = s0 + u_t;
                        let v = p.friction_n;
                        self.solver.set_condition(slot, Axis::Axial, Condition::Force, v)?;
                        self.stats.punctures += 1;
                    }
                    Change::LetGo => {
                        self.remove(slot)?;
                        self.stats.releases += 1;
                    }
                    Change::Slip(sign) => {
                        let p = &mut self.pts[slot.index()];
                        p.state = PointState3::Slipping;
                        p.slip_sign = sign;
                        let v = sign * p.friction_n;
                        self.solver.set_condition(slot, Axis::Axial, Condition::Force, v)?;
                        self.stats.stick_to_slip += 1;
                    }
                    Change::Stick(anchor) => {
                        let p = &mut self.pts[slot.index()];
                        p.state = PointState3::Stuck;
                        p.anchor_s_m = anchor;
                        self.solver.set_condition(slot, Axis::Axial, Condition::Displacement, anchor - s0)?;
                        self.stats.slip_to_stick += 1;
                    }
                }
            }
        }
        Ok((max_iter, false))
    }
}
