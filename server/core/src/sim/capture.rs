//! Stages 3 and 4 of a step, the working set's membership: shaft nodes the withdrawn tip has
//! passed leave it; nodes the tip passed within the capture radius join it (the most distal
//! one carried by the tip when none is); nodes ahead of the tip are reported for prefetch.
//!
//! Every list here has a fixed capacity ([`super::param_limits`]); what does not fit is counted
//! in [`super::SimStats`].

use crate::compliance::{ColumnScratch, ComplianceCache, TissueModel};
use crate::contact::{ContactPoint, PatchError};
use crate::ids::{Axis, NodeIdx};
use crate::mesh::Mesh;
use crate::mixed::Condition;

use super::frames::Geometry;
use super::param_limits::{MAX_APPROACHING, MAX_CAPTURES_PER_TICK};
use super::state::{NeedleNode, NodeState, State, WorkingSet};
use super::{Ctx, SimError, SimStats};
use crate::viscous::{History, ScaledBlocks};

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
/// $u_j = \sum_{w \in W} W_{jw} f_w$, $O(d)$ ([`contact_displacement`] of the node).
pub(super) fn node_displacement(ws: &WorkingSet, cache: &ComplianceCache, node: NodeIdx) -> [f64; 2] {
    contact_displacement(ws, cache, &ContactPoint::node(node))
}

/// Displacement of any contact (a node or a material point) from the working forces last
/// written out, $u_q = \sum_{w \in W} W_{qw} f_w$ with the blocks of
/// [`ComplianceCache::contact_block`]: it needs only the working contacts' columns. $O(d)$.
/// Working contacts without cached columns contribute nothing (they always have them).
pub(super) fn contact_displacement(ws: &WorkingSet, cache: &ComplianceCache, q: &ContactPoint) -> [f64; 2] {
    let mut u = [0.0; 2];
    for (nn, f) in ws.nodes.iter().zip(&ws.f_world) {
        let Some(b) = cache.contact_block(q, &nn.contact) else { continue };
        u[0] += b[0][0] * f[0] + b[0][1] * f[1];
        u[1] += b[1][0] * f[0] + b[1][1] * f[1];
    }
    u
}

/// Whether the columns of every node of `contact` are cached; when they are not, computes them
/// inside the step (`columns_in_step`, counted in `column_misses`) or leaves the contact for a
/// later tick (counted in `column_deferrals`) and returns `false`.
///
/// Errors: [`SimError::Tissue`] when a column solve fails.
fn ensure_columns(
    model: &TissueModel,
    columns_in_step: bool,
    cache: &mut ComplianceCache,
    sc: &mut CaptureScratch,
    stats: &mut SimStats,
    contact: &ContactPoint,
) -> Result<bool, SimError> {
    if cache.contains_contact(contact) {
        return Ok(true);
    }
    if !columns_in_step {
        stats.column_deferrals += 1;
        return Ok(false);
    }
    for node in contact.nodes() {
        if !cache.contains(node.index()) {
            model.compliance_columns_into(node.index(), &mut sc.column_buf, &mut sc.columns)?;
            cache.insert(node.index(), &sc.column_buf);
            stats.column_misses += 1;
        }
    }
    Ok(true)
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
        if st.cache.contains(j.index()) {
            // Near the tip, a node can be captured at any tick (a flexing shaft sweeps it even
            // while withdrawing): in use, kept from eviction.
            st.columns_lru.touch(j.index(), st.tick);
        }
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
            if model.is_fixed(j) {
                continue;
            }
            let x = nodes_m[j];
            let (s, lat) = tip_frame.coords([x[0] + u_d[0], x[1] + u_d[1]]);
            if lat.abs() <= 2.0 * cap_r && s > s_tip - cap_r && s <= s_tip + look {
                if st.cache.contains(j) {
                    // Cached and ahead: in use (kept from eviction).
                    st.columns_lru.touch(j, st.tick);
                } else if approaching.len() < MAX_APPROACHING {
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
        if !ensure_columns(model, params.columns_in_step, &mut st.cache, sc, &mut st.stats, &ContactPoint::node(j))? {
            // Admitted at a later tick, when the tip has passed it by a little more.
            continue;
        }
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
        let visc = setup.visc.map_or_else(History::default, |c| History::captured(&c, node_displacement(ws, &st.cache, j)));
        let slot =
            ws.solver.add_contact(&ScaledBlocks { cache: &st.cache, scale: setup.compliance_scale }, ContactPoint::node(j), angle)?;
        let (s0, lat0) = frame.coords([x[0] + visc.shift_m[0], x[1] + visc.shift_m[1]]);
        let region = setup.node_region[j.index()];
        let bevel_tip = is_tip && bevel;
        let entering = setup.is_boundary[j.index()] || st.last_tip_region != Some(region);
        let rp = params.regions[region];
        let nn = NeedleNode {
            contact: ContactPoint::node(j),
            x_ref_m: x,
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
            visc,
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

/// Fixed-point iterations locating the material point at a deformed position.
const LOCATE_ITERATIONS: usize = 8;

/// The material point $X$ that the deformation has carried to `p_m`: the fixed point of
/// $X = p - u(X)$ ([`contact_displacement`] at $X$'s interpolation), started from
/// $X_0 = p - u_0$. Converges when the displacement gradient is below 1 (a tissue not turned
/// inside out). Returns the triangle, weights and $X$, or `None` when $X$ lies outside the mesh.
fn material_point_at(
    ctx: &Ctx<'_>,
    st: &State,
    candidates: &mut Vec<usize>,
    p_m: [f64; 2],
    u0: [f64; 2],
) -> Option<(ContactPoint, [f64; 2])> {
    let (setup, mesh) = (ctx.setup, ctx.model.mesh());
    let mut x = [p_m[0] - u0[0], p_m[1] - u0[1]];
    let tol = 1e-12 * setup.max_edge_m;
    for _ in 0..LOCATE_ITERATIONS {
        let (tri, bary) = setup.locate_near(mesh, x, setup.max_edge_m, candidates)?;
        let c = ContactPoint::in_triangle(tri, mesh.triangles()[tri], bary);
        let u = contact_displacement(&st.ws, &st.cache, &c);
        let next = [p_m[0] - u[0], p_m[1] - u[1]];
        let moved = (next[0] - x[0]).hypot(next[1] - x[1]);
        x = next;
        if moved <= tol {
            break;
        }
    }
    let (tri, bary) = setup.locate_near(mesh, x, setup.max_edge_m, candidates)?;
    Some((ContactPoint::in_triangle(tri, mesh.triangles()[tri], bary), x))
}

/// Most pieces of one patch's segment (one per triangle it crosses).
const MAX_PATCH_PIECES: usize = 32;

/// The contact patch ([`ContactPoint::patch`]) of width `width_m` across the needle at the
/// material point `x_m` (reference coordinates; `dir` the unit direction across the needle):
/// the segment $[x - \tfrac w2 d,\ x + \tfrac w2 d]$ walked triangle by triangle. In the
/// triangle holding the point just past the walked part, the segment's barycentric weights are
/// affine in its parameter $\sigma \in [0, 1]$, $\lambda_i(\sigma) = \lambda_i(a) + \sigma\,
/// (\lambda_i(b) - \lambda_i(a))$, so the piece ends at the first root of a decreasing
/// $\lambda_i$; the piece's weight is its length times $\lambda(\sigma_{mid})$ (exact for linear
/// shape functions). Parts outside the mesh are skipped in steps of 1/64 of the segment.
/// Allocates nothing.
///
/// Errors: [`PatchError`] when the segment touches more than [`crate::contact::MAX_TERMS`]
/// nodes or has no length inside the mesh (the caller then keeps the point).
fn patch_at(
    setup: &super::setup::Setup,
    mesh: &Mesh,
    candidates: &mut Vec<usize>,
    centre_tri: usize,
    x_m: [f64; 2],
    dir: [f64; 2],
    width_m: f64,
) -> Result<ContactPoint, PatchError> {
    let half = 0.5 * width_m;
    let a = [x_m[0] - half * dir[0], x_m[1] - half * dir[1]];
    let b = [x_m[0] + half * dir[0], x_m[1] + half * dir[1]];
    let at = |sigma: f64| [a[0] + sigma * (b[0] - a[0]), a[1] + sigma * (b[1] - a[1])];
    let mut pieces = [([0usize; 3], [0.0f64; 3], 0.0f64); MAX_PATCH_PIECES];
    let mut n_pieces = 0;
    let nudge = 1e-9;
    let mut sigma = 0.0f64;
    // Each pass either ends a piece at a root past `sigma + nudge` or steps 1/64: bounded.
    for _ in 0..4 * MAX_PATCH_PIECES + 64 {
        if sigma >= 1.0 - nudge {
            break;
        }
        let probe = (sigma + nudge).min(1.0);
        let Some((tri, _)) = setup.locate_near(mesh, at(probe), setup.max_edge_m, candidates) else {
            sigma = (sigma + 1.0 / 64.0).min(1.0);
            continue;
        };
        let la = super::setup::barycentric(mesh, tri, a);
        let lb = super::setup::barycentric(mesh, tri, b);
        let mut end = 1.0f64;
        for i in 0..3 {
            let d = lb[i] - la[i];
            if d < 0.0 {
                let root = -la[i] / d;
                if root > probe && root < end {
                    end = root;
                }
            }
        }
        let end = end.max(probe);
        if n_pieces == MAX_PATCH_PIECES {
            return Err(PatchError::TooManyNodes);
        }
        let mid = 0.5 * (sigma + end);
        let bary = [0, 1, 2].map(|i| (la[i] + mid * (lb[i] - la[i])).clamp(0.0, 1.0));
        pieces[n_pieces] = (mesh.triangles()[tri], bary, (end - sigma) * width_m);
        n_pieces += 1;
        sigma = end;
    }
    ContactPoint::patch(centre_tri, pieces[..n_pieces].iter().copied())
}

/// The tip's straight path within one tick, from its position at the last tick to the current
/// one, with both ends' arc lengths in the tip's frame.
#[derive(Debug, Clone, Copy)]
struct TipPath {
    from_m: [f64; 2],
    to_m: [f64; 2],
    s_from_m: f64,
    s_to_m: f64,
}

impl TipPath {
    /// The point a fraction `lambda` of the way.
    fn at(&self, lambda: f64) -> [f64; 2] {
        [self.from_m[0] + lambda * (self.to_m[0] - self.from_m[0]), self.from_m[1] + lambda * (self.to_m[1] - self.from_m[1])]
    }
}

/// Bisection steps locating an event within a tick: to the tick's advance / 2^24 (about 1 nm
/// at 1 kHz and 20 mm/s).
const BISECTIONS: usize = 24;

/// The material point the next contact takes, located within the tick (issue 19: tick-rate
/// independence). A discrete step sees an event only at the first tick past it; taking the
/// point at the tick's end (or the last tick's tip) would make which material point the needle
/// carries, and so the force–depth curve, depend on the tick rate. Instead the tip's path
/// within the tick is taken as straight, $p(\lambda) = x_{k-1} + \lambda (x_k - x_{k-1})$, and:
/// - with a contact behind the tip, the point is the one at the arc length where it was due,
///   $s_{due} = s_{distal} + \text{spacing}$:
///   $\lambda = \operatorname{clamp}\big((s_{due} - s_{k-1}) / (s_k - s_{k-1}),\ 0,\ 1\big)$
///   (clamped: a contact admitted late, after waiting for its columns or for room from the
///   other points, is taken where the tip was at the last tick, as before);
/// - with none (the needle enters the tissue), the point where the path crosses the mesh's
///   boundary, by bisection on whether $p(\lambda)$ lies in a triangle (undeformed tissue: no
///   contact holds it); when the last tick's tip was already inside (a contact that waited),
///   that point;
/// - when that point lies too close to a working point (`far_enough` says no: the spacing rule
///   of [`capture_points`]), the first point along the rest of the path that does not, by
///   bisection (none when even the tip's does not: a later tick takes it).
///
/// The material point at $p$ is then the fixed point of [`material_point_at`] with the
/// displacement field the last tick left (the tissue between the last contact and the tip is
/// loaded only by the contacts behind it, which hold still within a tick up to friction's
/// sliding). The tip then pushes it to where the tip is now: a quasi-static state, the same
/// as if it had been captured on time. Returns the contact, its reference position $X$ and $p$.
fn capture_point_within_tick(
    ctx: &Ctx<'_>,
    st: &State,
    candidates: &mut Vec<usize>,
    path: TipPath,
    s_due_m: Option<f64>,
    u_d: [f64; 2],
    far_enough: impl Fn(&ContactPoint, [f64; 2]) -> bool,
) -> Option<(ContactPoint, [f64; 2], [f64; 2])> {
    let lambda_due = match s_due_m {
        Some(s_due) => ((s_due - path.s_from_m) / (path.s_to_m - path.s_from_m)).clamp(0.0, 1.0),
        None => {
            let (setup, mesh) = (ctx.setup, ctx.model.mesh());
            let inside = |candidates: &mut Vec<usize>, p: [f64; 2]| {
                setup.locate_near(mesh, [p[0] - u_d[0], p[1] - u_d[1]], setup.max_edge_m, candidates).is_some()
            };
            if inside(candidates, path.from_m) {
                0.0
            } else if !inside(candidates, path.to_m) {
                return None;
            } else {
                // Outside at 0, inside at 1: the crossing, from inside.
                let (mut lo, mut hi) = (0.0f64, 1.0f64);
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (lo + hi);
                    if inside(candidates, path.at(mid)) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                hi
            }
        }
    };
    let mut point_at = |lambda: f64| {
        let p = path.at(lambda);
        material_point_at(ctx, st, candidates, p, u_d).map(|(c, x)| (c, x, p))
    };
    let ok = |found: &Option<(ContactPoint, [f64; 2], [f64; 2])>| found.as_ref().is_some_and(|(c, x, _)| far_enough(c, *x));
    let due = point_at(lambda_due);
    if ok(&due) || lambda_due >= 1.0 {
        return due.filter(|(c, x, _)| far_enough(c, *x));
    }
    // The due point lies too close to another: the first point along the path that does not.
    let end = point_at(1.0);
    if !ok(&end) {
        return None;
    }
    let (mut lo, mut hi, mut found) = (lambda_due, 1.0f64, end);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        let at_mid = point_at(mid);
        if ok(&at_mid) {
            (hi, found) = (mid, at_mid);
        } else {
            lo = mid;
        }
    }
    found
}

/// Stage 4 with material-point contact ([`super::ContactModel::MaterialPoints`]): when no
/// contact is carried by the tip, the tip has advanced along its axis since the last tick, and
/// it lies `spacing_m` of arc length beyond the most distal contact, the material point the tip
/// passed where the contact was due (located within the tick: [`capture_point_within_tick`];
/// at the tissue's surface for the first) becomes the tip's contact: carried until its axial force exceeds the puncture or cutting force
/// (with energy-based cutting, inside a region it joins as a slipping shaft contact instead, and
/// the cutting force $G_c w$ rides on the most distal contact: `active_set::update_friction`). It is
/// taken only at a reference distance from every working point of at least both points'
/// triangle diameters, so that no segment of the shaft inside one triangle holds two points
/// (along a straight needle, the points' conditions are then independent). Nodes of the
/// triangles ahead of the tip are reported for prefetch, the next contact's first.
///
/// Errors: [`SimError::Tissue`] when a column computed in the step fails,
/// [`SimError::Mixed`] when the solver refuses the point's conditions for a reason other than
/// dependence (a dependent point is dropped and counted in `dependent_points`).
pub(super) fn capture_points(
    ctx: &Ctx<'_>,
    st: &mut State,
    sc: &mut CaptureScratch,
    approaching: &mut Vec<usize>,
    prev_tip: [f64; 2],
    spacing_m: f64,
    width_m: f64,
) -> Result<(), SimError> {
    let (params, setup, model) = (ctx.params, ctx.setup, ctx.model);
    let mesh = model.mesh();
    let nodes_m = mesh.nodes_m();
    let geo = Geometry::new(params, st.pose, st.flex.as_ref());
    let tip = geo.tip();
    let tip_frame = geo.tip_frame();
    let s_tip = geo.s_tip_m();
    let ws = &st.ws;
    let has_tip = ws.nodes.iter().any(|n| n.state == NodeState::Tip);
    let distal = (0..ws.len()).max_by(|&a, &b| ws.nodes[a].s_prev_m.total_cmp(&ws.nodes[b].s_prev_m));
    let s_distal = distal.map(|k| if ws.nodes[k].state == NodeState::Tip { s_tip } else { ws.nodes[k].s_prev_m });
    let u_d = distal.map_or([0.0; 2], |k| ws.u_world[k]);
    let (s_prev_tip, _) = tip_frame.coords(prev_tip);
    let advancing = s_tip - s_prev_tip > 1e-9;
    let due = !has_tip && advancing && s_distal.is_none_or(|s| s_tip - s >= spacing_m);
    // Where within the tick the tip reached the point that is due (module docs of
    // `capture_point_within_tick`): the same material point at any tick rate.
    // The point is taken only at a reference distance from every working point of at least
    // both points' triangle diameters.
    let diam = |c: &ContactPoint| c.tri_idx().map_or(0.0, |t| setup.tri_diam_m[t]);
    let far_enough = |c: &ContactPoint, x: [f64; 2]| {
        st.ws.nodes.iter().all(|nn| {
            let d = (nn.x_ref_m[0] - x[0]).hypot(nn.x_ref_m[1] - x[1]);
            d > diam(c).max(diam(&nn.contact)) * (1.0 + 1e-9)
        })
    };
    // Where within the tick the tip reached the point that is due: the same material point at
    // any tick rate.
    let candidate = if due {
        let tip_path = TipPath { from_m: prev_tip, to_m: tip, s_from_m: s_prev_tip, s_to_m: s_tip };
        capture_point_within_tick(ctx, st, &mut sc.candidates, tip_path, s_distal.map(|s| s + spacing_m), u_d, far_enough)
    } else {
        None
    };
    // Spread over the needle's width (a patch across the needle), when the model says so; a
    // patch that cannot be made leaves the point (counted when it is taken).
    let mut fell_back = false;
    let candidate = match candidate {
        Some((c, x, p)) if width_m > 0.0 => {
            let t = tip_frame.t;
            let tri = c.tri_idx().expect("a material point lies in a triangle");
            match patch_at(setup, mesh, &mut sc.candidates, tri, x, [-t[1], t[0]], width_m) {
                Ok(patch) => Some((patch, x, p)),
                Err(_) => {
                    fell_back = true;
                    Some((c, x, p))
                }
            }
        }
        other => other,
    };
    // Approaching nodes: the next contact's nodes first, then the nodes of the triangles the
    // axis crosses ahead of the tip.
    approaching.clear();
    if let Some((c, _, _)) = candidate {
        for n in c.nodes() {
            if st.cache.contains(n.index()) {
                st.columns_lru.touch(n.index(), st.tick);
            } else if !approaching.contains(&n.index()) {
                approaching.push(n.index());
            }
        }
    }
    let look = params.lookahead_m;
    let band = setup.max_edge_m;
    if look > 0.0 {
        let t = tip_frame.t;
        let q = [tip[0] - u_d[0], tip[1] - u_d[1]];
        let centre = [q[0] + 0.5 * look * t[0], q[1] + 0.5 * look * t[1]];
        query_near(setup, centre, 0.5 * look + band, &mut sc.candidates, &mut st.stats);
        let first = approaching.len();
        for k in 0..sc.candidates.len() {
            let j = sc.candidates[k];
            if model.is_fixed(j) || approaching[..first].contains(&j) {
                continue;
            }
            let x = nodes_m[j];
            let (s, lat) = tip_frame.coords([x[0] + u_d[0], x[1] + u_d[1]]);
            if lat.abs() <= band && s > s_tip - band && s <= s_tip + look {
                if st.cache.contains(j) {
                    // Cached and ahead: in use (kept from eviction).
                    st.columns_lru.touch(j, st.tick);
                } else if approaching.len() < MAX_APPROACHING {
                    approaching.push(j);
                } else {
                    st.stats.approaching_overflow += 1;
                }
            }
        }
        let key = |j: &usize| tip_frame.coords([nodes_m[*j][0] + u_d[0], nodes_m[*j][1] + u_d[1]]).0;
        approaching[first..].sort_unstable_by(|a, b| key(a).total_cmp(&key(b)));
    }
    let Some((contact, x, p_due)) = candidate else { return Ok(()) };
    if st.ws.len() == params.max_needle_nodes {
        st.stats.capacity_drops += 1;
        return Ok(());
    }
    if !ensure_columns(model, params.columns_in_step, &mut st.cache, sc, &mut st.stats, &contact)? {
        return Ok(());
    }
    let (s_new, _) = tip_frame.coords(p_due);
    let (angle, frame) = geo.capture_frame(s_tip, s_new);
    // A flexible needle takes the point where it is; the rigid one puts it on the shaft (it
    // lies there up to the tip's lateral motion within the tick).
    let lat_offset_m = if geo.curve.is_some() { frame.coords(p_due).1 } else { 0.0 };
    let visc = ctx.setup.visc.map_or_else(History::default, |c| History::captured(&c, contact_displacement(&st.ws, &st.cache, &contact)));
    let (s0, lat0) = frame.coords([x[0] + visc.shift_m[0], x[1] + visc.shift_m[1]]);
    let tri = contact.tri_idx().expect("a material point lies in a triangle");
    let region = mesh.region_of_tri()[tri];
    let entering = st.ws.len() == 0 || st.last_tip_region != Some(region);
    let rp = params.regions[region];
    let bevel = st.flex.as_ref().is_some_and(|f| f.bevel_ratio > 0.0);
    // Energy-based cutting: inside a region the tip is not carried by a point that it cuts
    // past at a threshold; the point is taken as a slipping shaft contact, and the cutting
    // force rides on the most distal contact (`active_set::update_friction`).
    let carried = entering || rp.toughness_cutting_force_n.is_none();
    let ws = &mut st.ws;
    let slot = ws.solver.add_contact(&ScaledBlocks { cache: &st.cache, scale: ctx.setup.compliance_scale }, contact, angle)?;
    let lateral = if bevel && carried {
        ws.solver.set_condition(slot, Axis::Lateral, Condition::Force, 0.0)
    } else {
        ws.solver.set_condition(slot, Axis::Lateral, Condition::Displacement, lat_offset_m - lat0)
    };
    // A slipping point gets its axial force condition at the start of the active-set stage.
    let axial = lateral
        .and_then(|()| if carried { ws.solver.set_condition(slot, Axis::Axial, Condition::Displacement, s_tip - s0) } else { Ok(()) });
    match axial {
        Ok(()) => {}
        Err(crate::mixed::MixedError::SingularPivot { .. }) => {
            // Its conditions depend on the other points' (not expected with the distance rule).
            ws.solver.remove_slot(slot)?;
            st.stats.dependent_points += 1;
            return Ok(());
        }
        Err(e) => {
            ws.solver.remove_slot(slot)?;
            return Err(e.into());
        }
    }
    st.last_tip_region = Some(region);
    st.stats.patch_fallbacks += u64::from(fell_back);
    ws.push(
        slot,
        NeedleNode {
            contact,
            x_ref_m: x,
            state: if carried { NodeState::Tip } else { NodeState::Slipping },
            anchor_s_m: s_new,
            s_prev_m: s_new,
            s_work_m: s_new,
            friction_n: 0.0,
            friction_new_n: 0.0,
            slip_sign: 1.0,
            release_force_n: if entering { rp.puncture_force_n } else { rp.cutting_force_n },
            region,
            lat_offset_m,
            lateral_ref_m: lat_offset_m - lat0,
            force_ref_local_n: [0.0; 2],
            visc,
        },
    );
    st.stats.captures += 1;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{phantom, phantom_params};
    use crate::needle::{NeedleShape, RigidNeedle};

    /// A patch's weights are the shape functions averaged over its segment: for any nodal field
    /// the patch interpolates the segment's mean of the piecewise-linear field. Checked against
    /// a fine midpoint quadrature of the interpolated field (oblique segments crossing several
    /// triangles, on the phantom's 19² grid, seeded), and exactly for a linear field (its mean is
    /// its value at the centre). A segment half outside the mesh averages the part inside.
    #[test]
    fn a_patch_interpolates_the_mean_over_its_segment() {
        use rand::{Rng, SeedableRng};
        let model = phantom(19);
        let params = phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }));
        let setup = super::super::setup::Setup::new(&model, &params).unwrap();
        let mesh = model.mesh();
        let mut cand = Vec::with_capacity(64);
        let mut rng = rand::rngs::SmallRng::seed_from_u64(19);
        let field: Vec<f64> = (0..mesh.n_nodes()).map(|_| rng.random_range(-1.0..1.0)).collect();
        let interp = |p: [f64; 2], cand: &mut Vec<usize>| {
            let (tri, bary) = setup.locate_near(mesh, p, setup.max_edge_m, cand)?;
            Some((0..3).map(|i| bary[i] * field[mesh.triangles()[tri][i]]).sum::<f64>())
        };
        let h = 0.1 / 18.0;
        for case in 0..20 {
            let x = [rng.random_range(0.02..0.08), rng.random_range(0.02..0.08)];
            let ang: f64 = rng.random_range(0.0..std::f64::consts::PI);
            let dir = [ang.cos(), ang.sin()];
            let width = rng.random_range(0.3..2.0) * h;
            let (tri, _) = setup.locate_near(mesh, x, setup.max_edge_m, &mut cand).unwrap();
            let patch = patch_at(&setup, mesh, &mut cand, tri, x, dir, width).unwrap();
            let got = patch.interpolate(|k| [field[k.index()], mesh.nodes_m()[k.index()][0]]);
            let n = 20_000;
            let mean = (0..n)
                .map(|k| {
                    let s = (k as f64 + 0.5) / n as f64 - 0.5;
                    interp([x[0] + s * width * dir[0], x[1] + s * width * dir[1]], &mut cand).unwrap()
                })
                .sum::<f64>()
                / n as f64;
            assert!((got[0] - mean).abs() < 1e-6, "case {case}: patch {} against the quadrature {mean}", got[0]);
            assert!((got[1] - x[0]).abs() < 1e-12 * x[0], "case {case}: the mean of x is the centre's x");
            assert!(patch.nodes().len() >= 3, "case {case}");
        }
        // Half outside: a segment across the top surface averages the inside half.
        let x = [0.05 + 0.3 * h, 0.1];
        let (tri, _) = setup.locate_near(mesh, x, setup.max_edge_m, &mut cand).unwrap();
        let patch = patch_at(&setup, mesh, &mut cand, tri, x, [0.0, 1.0], h).unwrap();
        let y = patch.interpolate(|k| [mesh.nodes_m()[k.index()][1]])[0];
        assert!((y - (0.1 - 0.25 * h)).abs() < h / 64.0, "{y}");
        // Far wider than the elements: more nodes than a contact holds.
        assert_eq!(patch_at(&setup, mesh, &mut cand, tri, [0.05, 0.05], [1.0, 0.0], 10.0 * h), Err(PatchError::TooManyNodes));
    }
}

#[cfg(test)]
mod convergence {
    use super::*;
    use crate::fixtures::{phantom, phantom_params};
    use crate::needle::{NeedleShape, RigidNeedle};

    /// Issue 19: a contact patch's compliance converges under mesh refinement where a point's
    /// grows like $\ln(1/h)$ (2D). The same material place (inside the phantom, a 17-gauge
    /// width across a vertical needle) on grids $h \dots h/8$: the point's lateral compliance
    /// grows by about the same amount at every halving, $\frac{\ln 2}{4\pi\mu_{eff}}$ per unit
    /// thickness; the patch's increments shrink geometrically once $h$ falls below the width.
    #[test]
    fn issue_19_a_patch_compliance_converges_where_a_point_grows_like_log_1_over_h() {
        let width_m = 1.473e-3;
        // A node of every grid (the point's compliance then grows as the theory says).
        let x = [0.05, 0.05];
        let mut point = Vec::new();
        let mut patch = Vec::new();
        for n in [19, 37, 73, 145, 289] {
            let model = phantom(n);
            let params = phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }));
            let setup = super::super::setup::Setup::new(&model, &params).unwrap();
            let mesh = model.mesh();
            let mut cand = Vec::with_capacity(64);
            let (tri, bary) = setup.locate_near(mesh, x, setup.max_edge_m, &mut cand).unwrap();
            let p = ContactPoint::in_triangle(tri, mesh.triangles()[tri], bary);
            let q = patch_at(&setup, mesh, &mut cand, tri, x, [1.0, 0.0], width_m).unwrap();
            let mut cache = ComplianceCache::new(mesh.n_nodes());
            let mut scratch = model.column_scratch();
            for c in [&p, &q] {
                for k in c.nodes() {
                    cache.ensure(&model, k.index(), &mut scratch).unwrap();
                }
            }
            point.push(cache.contact_block(&p, &p).unwrap()[0][0]);
            patch.push(cache.contact_block(&q, &q).unwrap()[0][0]);
        }
        let steps = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).collect::<Vec<f64>>();
        let (dp, dq) = (steps(&point), steps(&patch));
        eprintln!("point {point:?}\npatch {patch:?}\nsteps point {dp:?}\nsteps patch {dq:?}");
        // The point's compliance grows by the same amount at every halving (measured 7.3e-4,
        // 7.0e-4, 6.9e-4, 6.8e-4 m/N per unit force: the log law).
        for d in &dp {
            assert!((d - dp[0]).abs() < 0.1 * dp[0], "the point's compliance is not growing like ln(1/h): {dp:?}");
        }
        // The patch's steps shrink at every halving (measured ratios 0.78, 0.76, 0.62 as h falls
        // from 3.8 w to w / 4), and the last is a third of the point's.
        for w in dq.windows(2) {
            assert!(w[1] > 0.0 && w[1] < 0.8 * w[0], "the patch's compliance is not converging: {dq:?}");
        }
        let last = dq.len() - 1;
        assert!(dq[last] < 0.7 * dq[last - 1], "{dq:?}");
        assert!(dq[last] < 0.35 * dp[last], "patch {dq:?} against point {dp:?}");
    }
}
