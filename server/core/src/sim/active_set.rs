//! Stages 5 and 6 of a step, the contact conditions: each shaft node's friction share, then the
//! bounded stick/slip iteration (stuck nodes slip above static friction, slipping nodes stick
//! when their motion stops or reverses, the tip's node punctures or lets go), each change an
//! $O(d^2)$ update of the working solver.

use crate::ids::{Axis, Slot};
use crate::mixed::Condition;

use super::flexible::{self, FlexScratch};
use super::frames::Geometry;
use super::param_limits::MAX_UPDATES_PER_TICK;
use super::state::{FlexState, NodeState, State, WorkingSet};
use super::{Ctx, SimError, SimParams};

/// Bound on the friction-share sweeps per active-set iteration.
const FRICTION_SWEEPS: usize = 6;

/// The friction shares have converged when no slipping node's share changes by more than this
/// fraction of the total friction (1 µN per newton: far below what a hand or a device resolves).
const FRICTION_TOL: f64 = 1e-6;

/// What changed in one active-set pass for one slot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Change {
    /// The tip's node exceeded its release force: it becomes a slipping shaft node.
    Puncture,
    /// The tip's node no longer pushes: it leaves the working set.
    LetGo,
    /// A stuck node exceeded static friction; the sign of its axial force.
    Slip(f64),
    /// A slipping node stopped or reversed; the shaft point (m) it sticks at.
    Stick(f64),
}

/// The buffers of the conditions stage, sized for the working set's capacity.
pub(super) struct ActiveSetScratch {
    /// Shaft nodes by shaft position (capacity: the working set's).
    pub order: Vec<Slot>,
    /// One pass's changes (at most one per slot).
    pub changes: Vec<(Slot, Change)>,
}

/// Stage 5: each shaft node's share of the friction distribution, from the nodes' shaft
/// positions: the anchor of a stuck node; for a slipping node its position at the end of the
/// last tick, or (`current`) in the current solution. Node $i$ between its neighbours' midpoints
/// $[a_i, b_i]$ gets $\int_{L-b_i}^{L-a_i} q(d)\,\mathrm{d}d$ (see
/// [`crate::RegionNeedleParams::friction_integral_n`]). With energy-based cutting
/// ([`crate::RegionNeedleParams::toughness_cutting_force_n`]), while the base advances and no
/// contact is carried by the tip, the most distal node's share also holds the cutting force,
/// $f_{distal} \mathrel{+}= F_c = G_c w$: the tissue ahead of the tip resists the cut with it,
/// and the node's static threshold is $\mu_s/\mu_k$ times the sum; the friction peak behind the
/// tip ($h$) is then part of the cut too, applied only while cutting (at rest and while
/// withdrawing the shares are of the plain $q_0$). The new shares are applied only when
/// some slipping node's share changes by more than `min_change_n` (always when not `current`),
/// so that the applied values always belong to the last solve. Returns the largest change (N).
pub(super) fn update_friction(
    params: &SimParams,
    geo: &Geometry<'_>,
    ws: &mut WorkingSet,
    order: &mut Vec<Slot>,
    current: bool,
    min_change_n: f64,
) -> f64 {
    let s_tip = geo.s_tip_m();
    order.clear();
    for slot in ws.slots() {
        let frame = geo.slot_frame(ws, slot);
        let nn = &mut ws.nodes[slot.index()];
        nn.s_work_m = match nn.state {
            NodeState::Stuck => nn.anchor_s_m,
            NodeState::Slipping if current => frame.coords(nn.x_kin_m()).0 + ws.solver.displacement_local(slot)[Axis::Axial],
            NodeState::Slipping => nn.s_prev_m,
            NodeState::Tip => continue,
        };
        order.push(slot);
    }
    let speed = ws.axial_speed_m_per_s;
    // The tip cuts while it advances with no contact carried (a carried one is puncturing).
    let cutting = ws.advancing && ws.nodes.iter().all(|n| n.state != NodeState::Tip);
    let nodes = &ws.nodes;
    order.sort_unstable_by(|&a, &b| nodes[a.index()].s_work_m.total_cmp(&nodes[b.index()].s_work_m));
    let k = order.len();
    let mut max_change: f64 = 0.0;
    for i in 0..k {
        let slot = order[i];
        let s = ws.node(slot).s_work_m;
        let lo = if i == 0 { s } else { 0.5 * (s + ws.node(order[i - 1]).s_work_m) };
        let hi = if i + 1 == k { s_tip.max(s) } else { 0.5 * (s + ws.node(order[i + 1]).s_work_m) };
        let rp = params.regions[ws.node(slot).region];
        let nn = ws.node_mut(slot);
        // With energy-based cutting the peak behind the tip belongs to the cut: only while cutting.
        let peak = rp.toughness_cutting_force_n.is_none() || cutting;
        nn.friction_new_n =
            rp.friction_integral_with_peak_n(s_tip - hi, s_tip - lo, peak) + rp.friction_damping_n_s_per_m2 * speed * (hi - lo);
        if let Some(fc) = rp.toughness_cutting_force_n
            && cutting
            && i + 1 == k
        {
            // Energy-based cutting: the most distal contact carries the tip's cutting force.
            nn.friction_new_n += fc;
        }
        if nn.state == NodeState::Slipping {
            max_change = max_change.max((nn.friction_new_n - nn.friction_n).abs());
        }
    }
    if max_change > min_change_n || !current {
        for &slot in order.iter() {
            let nn = &mut ws.nodes[slot.index()];
            nn.friction_n = nn.friction_new_n;
            // The kind is Force for a slipping node already pivoted; only its value changes.
            if nn.state == NodeState::Slipping && ws.solver.condition(slot, Axis::Axial) == Condition::Force {
                ws.solver.set_value(slot, Axis::Axial, nn.slip_sign * nn.friction_n);
            }
        }
    }
    max_change
}

/// The $O(d^2)$ updates of the working solver (pivots, rotations, additions, removals) since
/// the tick began.
fn updates_this_tick(st: &State) -> u64 {
    let s = st.ws.solver.stats();
    (s.n_pivots + s.n_rotations + s.n_added + s.n_removed).saturating_sub(st.updates_at_tick_start)
}

/// The flexible needle's state and scratch together, if the needle is flexible.
fn flex_pair<'a>(fx: &'a mut Option<FlexState>, sc: &'a mut Option<FlexScratch>) -> Option<(&'a mut FlexState, &'a mut FlexScratch)> {
    fx.as_mut().zip(sc.as_mut())
}

/// How one stick/slip iteration ended.
#[derive(Debug, Clone, Copy)]
pub(super) struct Resolved {
    /// Passes made.
    pub iterations: usize,
    /// No condition was left to change.
    pub converged: bool,
    /// It stopped at `max_active_set_iterations` passes with conditions still changing (not at
    /// the tick's update budget, which [`super::SimStats::budget_exhausted_ticks`] counts).
    pub capped: bool,
}

/// Stage 6: the bounded stick/slip iteration (at most `max_active_set_iterations` passes).
/// Counts punctures, releases and stick/slip changes.
///
/// Errors: [`SimError::Mixed`] when the solver refuses a condition change or a release.
pub(super) fn resolve_active_set(
    ctx: &Ctx<'_>,
    st: &mut State,
    sc: &mut ActiveSetScratch,
    flex_sc: &mut Option<FlexScratch>,
) -> Result<Resolved, SimError> {
    let params = ctx.params;
    let s_tip = ctx.setup.s_tip_m;
    let tick = st.tick;
    // Slipping nodes just captured still need their force condition.
    for slot in st.ws.slots() {
        let nn = *st.ws.node(slot);
        if nn.state == NodeState::Slipping && st.ws.solver.condition(slot, Axis::Axial) != Condition::Force {
            st.ws.solver.set_condition(slot, Axis::Axial, Condition::Force, nn.slip_sign * nn.friction_n)?;
        }
    }
    let max_iter = params.max_active_set_iterations;
    for iter in 1..=max_iter {
        if updates_this_tick(st) > MAX_UPDATES_PER_TICK {
            // The tick's budget of O(d²) updates is spent: solve with the conditions as they
            // are (the next tick goes on from them) and say so.
            flexible::solve_working_set(&mut st.ws, flex_pair(&mut st.flex, flex_sc), s_tip, tick);
            st.stats.budget_exhausted_ticks += 1;
            return Ok(Resolved { iterations: iter, converged: false, capped: false });
        }
        flexible::solve_working_set(&mut st.ws, flex_pair(&mut st.flex, flex_sc), s_tip, tick);
        // Friction shares follow the slipping nodes' positions (a node sliding back lengthens
        // its tributary segment): a short fixed-point iteration, contracting when the friction
        // per length is small against the tissue stiffness.
        let total: f64 = st.ws.nodes.iter().map(|n| n.friction_n).sum();
        let tol = FRICTION_TOL * total.max(1e-12);
        for _ in 0..FRICTION_SWEEPS {
            let geo = Geometry::new(params, st.pose, st.flex.as_ref());
            let friction_change = update_friction(params, &geo, &mut st.ws, &mut sc.order, true, tol);
            let bevel_change = st.flex.as_ref().map_or(0.0, |fx| flexible::update_bevel_force(&mut st.ws, fx, tol));
            if friction_change <= tol && bevel_change <= tol {
                break;
            }
            flexible::solve_working_set(&mut st.ws, flex_pair(&mut st.flex, flex_sc), s_tip, tick);
        }
        let geo = Geometry::new(params, st.pose, st.flex.as_ref());
        let ws = &mut st.ws;
        sc.changes.clear();
        for slot in ws.slots() {
            let nn = *ws.node(slot);
            let f = ws.solver.force_local(slot);
            let (s0, _) = geo.slot_frame(ws, slot).coords(nn.x_kin_m());
            let s_now = s0 + ws.solver.displacement_local(slot)[Axis::Axial];
            let f_t = f[Axis::Axial];
            let change = match nn.state {
                NodeState::Tip if f_t > nn.release_force_n => Some(Change::Puncture),
                NodeState::Tip if f_t <= 0.0 => Some(Change::LetGo),
                NodeState::Stuck => {
                    let threshold = (params.regions[nn.region].static_friction_ratio * nn.friction_n).max(1e-12);
                    (f_t.abs() > threshold).then(|| Change::Slip(f_t.signum()))
                }
                NodeState::Slipping => {
                    // Consistent sliding moves the node backwards along the shaft relative to
                    // the friction it receives: slip_sign * ds < 0.
                    let ds = s_now - nn.s_prev_m;
                    (nn.slip_sign * ds >= -1e-12).then_some(Change::Stick(nn.s_prev_m))
                }
                NodeState::Tip => None,
            };
            if let Some(c) = change {
                sc.changes.push((slot, c));
            }
        }
        if sc.changes.is_empty() {
            return Ok(Resolved { iterations: iter, converged: true, capped: false });
        }
        // Apply in descending slot order so removals do not disturb pending slots.
        sc.changes.sort_unstable_by_key(|c| std::cmp::Reverse(c.0));
        for &(slot, change) in sc.changes.iter() {
            let x = ws.node(slot).x_kin_m();
            let (s0, lat0) = geo.slot_frame(ws, slot).coords(x);
            match change {
                Change::Puncture => {
                    if ws.solver.condition(slot, Axis::Lateral) == Condition::Force {
                        // A bevel tip's node stays at the lateral offset it was cut at.
                        let un = ws.solver.displacement_local(slot)[Axis::Lateral];
                        ws.node_mut(slot).lat_offset_m = un + lat0;
                        ws.node_mut(slot).lateral_ref_m = un;
                        ws.solver.set_condition(slot, Axis::Lateral, Condition::Displacement, un)?;
                    }
                    let u_t = ws.solver.displacement_local(slot)[Axis::Axial];
                    let nn = ws.node_mut(slot);
                    nn.state = NodeState::Slipping;
                    nn.slip_sign = 1.0;
                    nn.s_prev_m = s0 + u_t;
                    let value = nn.friction_n;
                    ws.solver.set_condition(slot, Axis::Axial, Condition::Force, value)?;
                    st.stats.punctures += 1;
                }
                Change::LetGo => {
                    ws.remove(slot)?;
                    st.stats.releases += 1;
                }
                Change::Slip(sign) => {
                    let nn = ws.node_mut(slot);
                    nn.state = NodeState::Slipping;
                    nn.slip_sign = sign;
                    let value = sign * nn.friction_n;
                    ws.solver.set_condition(slot, Axis::Axial, Condition::Force, value)?;
                    st.stats.stick_to_slip += 1;
                }
                Change::Stick(anchor) => {
                    let nn = ws.node_mut(slot);
                    nn.state = NodeState::Stuck;
                    nn.anchor_s_m = anchor;
                    ws.solver.set_condition(slot, Axis::Axial, Condition::Displacement, anchor - s0)?;
                    st.stats.slip_to_stick += 1;
                }
            }
        }
        if iter == max_iter {
            // Leave a state whose solution matches its conditions.
            flexible::solve_working_set(&mut st.ws, flex_pair(&mut st.flex, flex_sc), s_tip, tick);
        }
    }
    Ok(Resolved { iterations: max_iter, converged: false, capped: true })
}
