//! Stages 3 and 4 of a step, the working set's membership: shaft nodes the withdrawn tip has
//! passed leave it; nodes the tip passed within the capture radius join it (the most distal
//! one carried by the tip when none is); nodes ahead of the tip are reported for prefetch.
//!
//! Every list here has a fixed capacity ([`super::param_limits`]); what does not fit is counted
//! in [`super::SimStats`].

use crate::compliance::{ColumnScratch, ComplianceCache, TissueModel};
use crate::ids::{Axis, NodeIdx};
use crate::mixed::Condition;

use super::frames::Geometry;
use super::param_limits::{MAX_APPROACHING, MAX_CAPTURES_PER_TICK};
use super::state::{NeedleNode, NodeState, State, WorkingSet};
use super::{Ctx, SimError, SimStats};

/// A node the tip passed this tick and its arc length in the tip's frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct Captured {
    pub node: NodeIdx,
    pub s_m: f64,
}

/// The buffers of the capture stage, sized up front.
pub(super) struct CaptureScratch {
    /// The spatial grid's answer to one query (grows past its reserve only by counted growth).
    pub candidates: Vec<usize>,
    /// Capacity [`MAX_CAPTURES_PER_TICK`].
    pub captured: Vec<Captured>,
    /// Work space of a compliance column computed within a step.
    pub columns: ColumnScratch,
    /// One node's two columns, $2 \cdot 2n$ values.
    pub column_buf: Vec<f64>,
}

/// Stage 3: shaft nodes beyond the (withdrawn) tip leave the needle (counted in `releases`).
///
/// Errors: [`SimError::Mixed`] when the solver cannot release a node.
pub(super) fn release_withdrawn(s_tip_m: f64, ws: &mut WorkingSet, stats: &mut SimStats) -> Result<(), SimError> {
    for slot in ws.slots().rev() {
        let nn = ws.node(slot);
        let s = match nn.state {
            NodeState::Stuck => nn.anchor_s_m,
            NodeState::Slipping => nn.s_prev_m,
            NodeState::Tip => continue,
        };
        if s > s_tip_m {
            ws.remove(slot)?;
            stats.releases += 1;
        }
    }
    Ok(())
}

/// Displacement of any node from the working forces last written out,
/// $u_j = \sum_{i \in W} C_{ji} f_i$, $O(d)$. Working nodes without cached columns contribute
/// nothing (they always have them).
pub(super) fn node_displacement(ws: &WorkingSet, cache: &ComplianceCache, node: NodeIdx) -> [f64; 2] {
    let (jx, jy) = (node.dof(0), node.dof(1));
    let mut u = [0.0; 2];
    for (nn, f) in ws.nodes.iter().zip(&ws.f_world) {
        let w = nn.node.index();
        let (Some(cx), Some(cy)) = (cache.column(w, 0), cache.column(w, 1)) else { continue };
        u[0] += cx[jx] * f[0] + cy[jx] * f[1];
        u[1] += cx[jy] * f[0] + cy[jy] * f[1];
    }
    u
}

/// Makes sure the columns of `node` are cached, computing them (counted in `column_misses`)
/// when the prefetch did not.
///
/// Errors: [`SimError::Tissue`] when the column solve fails.
fn ensure_columns(
    model: &TissueModel,
    cache: &mut ComplianceCache,
    sc: &mut CaptureScratch,
    stats: &mut SimStats,
    node: NodeIdx,
) -> Result<(), SimError> {
    if !cache.contains(node.index()) {
        model.compliance_columns_into(node.index(), &mut sc.column_buf, &mut sc.columns)?;
        cache.insert(node.index(), &sc.column_buf);
        stats.column_misses += 1;
    }
    Ok(())
}

/// Stage 4: interception of nodes the tip has passed, and the list of approaching nodes.
///
/// The search is centred on the material point at the tip, $q = x_{tip} - u_d$, where $u_d$ is
/// the displacement of the most distal needle node: only nodes within a few capture radii of
/// it get their exact deformed position ($O(d)$ each). Nodes ahead of the tip are reported as
/// approaching (in `approaching`, nearest first) from their reference positions shifted by
/// $u_d$, at no per-node solve cost.
///
/// Errors: [`SimError::Tissue`] when a captured node's columns cannot be computed,
/// [`SimError::Mixed`] when the solver refuses the node or its conditions.
pub(super) fn capture(
    ctx: &Ctx<'_>,
    st: &mut State,
    sc: &mut CaptureScratch,
    approaching: &mut Vec<usize>,
    prev_tip: [f64; 2],
) -> Result<(), SimError> {
    let (params, setup, model) = (ctx.params, ctx.setup, ctx.model);
    let nodes_m = model.mesh().nodes_m();
    let geo = Geometry::new(params, st.pose, st.flex.as_ref());
    let tip = geo.tip();
    let tip_frame = geo.tip_frame();
    let s_tip = geo.s_tip_m();
    let cap_r = params.capture_radius_m;
    let (s_prev_tip, _) = tip_frame.coords(prev_tip);
    let ws = &mut st.ws;
    let distal = (0..ws.len()).max_by(|&a, &b| ws.nodes[a].s_prev_m.total_cmp(&ws.nodes[b].s_prev_m));
    let u_d = distal.map_or([0.0; 2], |k| ws.u_world[k]);
    let q = [tip[0] - u_d[0], tip[1] - u_d[1]];
    let advance = (tip[0] - prev_tip[0]).hypot(tip[1] - prev_tip[1]);
    // Around the tip the tissue strains: allow a quarter of the local displacement as margin.
    let radius = 3.0 * cap_r + advance + 0.25 * u_d[0].hypot(u_d[1]);
    query_near(setup, q, radius, &mut sc.candidates, &mut st.stats);
    sc.captured.clear();
    for k in 0..sc.candidates.len() {
        let j = NodeIdx(sc.candidates[k]);
        if ws.contains(j) || model.is_fixed(j.index()) {
            continue;
        }
        let x = nodes_m[j.index()];
        let u = node_displacement(ws, &st.cache, j);
        let (s, lat) = tip_frame.coords([x[0] + u[0], x[1] + u[1]]);
        if lat.abs() <= cap_r && s <= s_tip && s >= s_prev_tip - cap_r {
            if sc.captured.len() < MAX_CAPTURES_PER_TICK {
                sc.captured.push(Captured { node: j, s_m: s });
            } else {
                st.stats.capture_overflow += 1;
            }
        }
    }
    // Approaching nodes: ahead of the tip, within the lookahead.
    approaching.clear();
    let look = params.lookahead_m;
    if look > 0.0 {
        let t = tip_frame.t;
        let centre = [q[0] + 0.5 * look * t[0], q[1] + 0.5 * look * t[1]];
        query_near(setup, centre, 0.5 * look + 2.0 * cap_r, &mut sc.candidates, &mut st.stats);
        for k in 0..sc.candidates.len() {
            let j = sc.candidates[k];
            if st.cache.contains(j) || model.is_fixed(j) {
                continue;
            }
            let x = nodes_m[j];
            let (s, lat) = tip_frame.coords([x[0] + u_d[0], x[1] + u_d[1]]);
            if lat.abs() <= 2.0 * cap_r && s > s_tip - cap_r && s <= s_tip + look {
                if approaching.len() < MAX_APPROACHING {
                    approaching.push(j);
                } else {
                    st.stats.approaching_overflow += 1;
                }
            }
        }
        // Nearest first, so a bounded prefetch takes the most urgent.
        let key = |j: &usize| tip_frame.coords([nodes_m[*j][0] + u_d[0], nodes_m[*j][1] + u_d[1]]).0;
        approaching.sort_unstable_by(|a, b| key(a).total_cmp(&key(b)));
    }
    if sc.captured.is_empty() {
        return Ok(());
    }
    sc.captured.sort_unstable_by(|a, b| a.s_m.total_cmp(&b.s_m));
    let has_tip = ws.nodes.iter().any(|n| n.state == NodeState::Tip);
    let n_cap = sc.captured.len();
    let bevel = st.flex.as_ref().is_some_and(|f| f.bevel_ratio > 0.0);
    for k in 0..n_cap {
        let Captured { node: j, s_m: s } = sc.captured[k];
        if ws.len() == params.max_needle_nodes {
            st.stats.capacity_drops += (n_cap - k) as u64;
            break;
        }
        ensure_columns(model, &mut st.cache, sc, &mut st.stats, j)?;
        let is_tip = !has_tip && k + 1 == n_cap;
        let s_ref = if is_tip { s_tip } else { s };
        let (angle, frame) = geo.capture_frame(s_ref, s);
        let x = nodes_m[j.index()];
        // A flexible needle takes the node where it is (no lateral snap onto the shaft, which
        // would pull the needle towards every node it passes); the rigid needle, as in the
        // paper, puts it on the shaft.
        let lat_offset_m = if geo.curve.is_some() {
            let u = node_displacement(ws, &st.cache, j);
            frame.coords([x[0] + u[0], x[1] + u[1]]).1
        } else {
            0.0
        };
        let slot = ws.solver.add_node(&st.cache, j, angle)?;
        let (s0, lat0) = frame.coords(x);
        let region = setup.node_region[j.index()];
        let bevel_tip = is_tip && bevel;
        let entering = setup.is_boundary[j.index()] || st.last_tip_region != Some(region);
        let rp = params.regions[region];
        let nn = NeedleNode {
            node: j,
            state: if is_tip { NodeState::Tip } else { NodeState::Slipping },
            anchor_s_m: s,
            s_prev_m: s,
            s_work_m: s,
            friction_n: 0.0,
            friction_new_n: 0.0,
            slip_sign: 1.0,
            release_force_n: if entering { rp.puncture_force_n } else { rp.cutting_force_n },
            region,
            lat_offset_m,
            lateral_ref_m: lat_offset_m - lat0,
            force_ref_local_n: [0.0; 2],
        };
        if bevel_tip {
            // The bevel's tip node slides on the bevel face: its lateral force is prescribed.
            ws.solver.set_condition(slot, Axis::Lateral, Condition::Force, 0.0)?;
        } else {
            ws.solver.set_condition(slot, Axis::Lateral, Condition::Displacement, lat_offset_m - lat0)?;
        }
        if is_tip {
            ws.solver.set_condition(slot, Axis::Axial, Condition::Displacement, s_tip - s0)?;
            st.last_tip_region = Some(region);
        }
        ws.push(slot, nn);
        st.stats.captures += 1;
    }
    Ok(())
}

/// The grid's nodes around `center_m` into `out` (cleared first); a query that outgrew the
/// buffer's reserve is counted in `candidate_growths`.
fn query_near(setup: &super::setup::Setup, center_m: [f64; 2], radius_m: f64, out: &mut Vec<usize>, stats: &mut SimStats) {
    out.clear();
    let cap = out.capacity();
    setup.grid.query_into(center_m, radius_m, out);
    if out.capacity() != cap {
        stats.candidate_growths += 1;
    }
}
