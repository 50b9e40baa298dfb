//! Targets of the 3D simulation: spheres of the tissue ([`Target3`], given in
//! [`Sim3Params::targets`](super::Sim3Params::targets)) that move with it, each latched once as
//! hit or missed ([`TargetState3`]), reported every tick in [`StepOutput3::targets`](super::StepOutput3::targets).
//!
//! **Displaced centre.** A target's centre $X_c$ is a material point: its tetrahedron and
//! barycentric weights $N$ are located once, in [`Simulation3::new`]. Each tick its displacement is
//! the working points' forces through the compliance,
//! $$u(X_c) = \sum_{j \in \mathcal W} W_{cj} f_j,\qquad W_{cj} = \sum_{a \in c}\sum_{b \in j} N_{c,a} N_{j,b}\, C_{ab},$$
//! exactly the static displacement of the problem the step solved (the only loads on the tissue
//! are the point forces $f_j$). $C_{ab}$ (node $a$'s displacement per unit force on node $b$)
//! comes from node $b$'s cached columns, which every working point's nodes have: no column is
//! computed, $O(d)$ per target per tick. All compliance reads of the 3D simulation's targets and
//! wrench stiffness go through `node_block`, which reads either store ([`ComplianceStore3`]); with
//! node blocks $C_{ab}$ needs both nodes cached, so the simulation pins the targets' free nodes
//! ([`super::Simulation3::pin_node`]).
//!
//! **Latching.** With $c'$ the displaced centre, $p$ the tip, $r$ the radius and
//! $s_c = t \cdot (c' - x_b)$ the centre's coordinate along the needle axis from the base (the
//! tip's is $L$):
//! - **Hit** at the first tick with $|p - c'| \le r$;
//! - **Missed** at the first tick, without a hit, with $L - s_c > r$ (the tip has gone past the
//!   centre's level by more than the radius) after a tick with $L - s_c \le r$ (the target was
//!   ahead of the tip, or level with it): "passed" needs the target to have been ahead, so a
//!   target behind the tip when the simulation starts stays pending until the tip comes back
//!   before it and passes it again.
//!
//! The test is made at each tick's tip position (a tick moves the tip by at most
//! [`Sim3Params::max_base_step_m`](super::Sim3Params::max_base_step_m) and rotation: at 1 kHz and
//! 20 mm/s, 20 µm; a sphere smaller than a tick's motion could be stepped over). A latched state
//! stays until [`Simulation3::reset_targets`] or a new simulation; the displaced centre and the
//! distance keep being updated.

use crate::compliance::store::ComplianceStore3;
use crate::contact::ContactPoint;
use crate::d3::TetTissueModel;

use super::{Point, SimError3, Simulation3, dist, dot, sub};

/// Capacity of the target list ([`Sim3Params::targets`](super::Sim3Params::targets)) and of
/// [`TargetsOut3`].
pub const MAX_TARGETS: usize = crate::sim::param_limits::MAX_TARGETS;

/// A target: a sphere of the tissue, given in the reference configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target3 {
    /// Reference centre, m (inside the mesh).
    pub centre_m: [f64; 3],
    /// Radius, m (> 0).
    pub radius_m: f64,
    /// The caller's index of its name (a scene's list of target names); carried to the output.
    pub name_idx: usize,
}

/// A target's latched state (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetState3 {
    /// Neither hit nor missed yet.
    Pending,
    /// The tip came within the radius of the displaced centre.
    Hit,
    /// The tip went past the displaced centre without a hit.
    Missed,
}

/// One target in a step's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetOut3 {
    pub name_idx: usize,
    /// Displaced centre $X_c + u(X_c)$, m.
    pub centre_m: [f64; 3],
    /// Its displacement $u(X_c)$, m.
    pub displacement_m: [f64; 3],
    /// Distance from the tip to the displaced centre, m.
    pub distance_m: f64,
    /// The centre's coordinate along the needle axis from the base minus the tip's,
    /// $s_c - L$, m: positive while the centre is ahead of the tip.
    pub ahead_m: f64,
    pub state: TargetState3,
    /// The tick at which `state` latched (`None` while pending).
    pub latched_tick: Option<u64>,
}

const EMPTY_OUT: TargetOut3 = TargetOut3 {
    name_idx: 0,
    centre_m: [0.0; 3],
    displacement_m: [0.0; 3],
    distance_m: 0.0,
    ahead_m: 0.0,
    state: TargetState3::Pending,
    latched_tick: None,
};

/// The targets of a step's output: a fixed-capacity list (no allocation), in the order of
/// [`Sim3Params::targets`](super::Sim3Params::targets).
#[derive(Debug, Clone, PartialEq)]
pub struct TargetsOut3 {
    len: usize,
    items: [TargetOut3; MAX_TARGETS],
}

impl Default for TargetsOut3 {
    fn default() -> Self {
        Self { len: 0, items: [EMPTY_OUT; MAX_TARGETS] }
    }
}

impl TargetsOut3 {
    /// The targets.
    pub fn as_slice(&self) -> &[TargetOut3] {
        &self.items[..self.len]
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// The node block $C_{ab}$ (world, $3\times3$): node `a`'s displacement per unit force on node
/// `b`, from `b`'s cached columns; `None` when they are not cached. The only compliance read of
/// this module and of [`super::stiffness`].
#[inline]
pub(super) fn node_block(cache: &ComplianceStore3, a: usize, b: usize) -> Option<[[f64; 3]; 3]> {
    cache.block(a, b)
}

/// The compliance block between two contacts, $W_{ab} = \sum_i\sum_j N_{a,i}N_{b,j}\,C_{ij}$, from
/// [`node_block`]; `None` when a node of `b` is not cached.
pub(super) fn point_block(cache: &ComplianceStore3, a: &ContactPoint, b: &ContactPoint) -> Option<[[f64; 3]; 3]> {
    let mut out = [[0.0; 3]; 3];
    for (j, wj) in b.terms() {
        for (i, wi) in a.terms() {
            let blk = node_block(cache, i.index(), j.index())?;
            let w = wi * wj;
            for r in 0..3 {
                for c in 0..3 {
                    out[r][c] += w * blk[r][c];
                }
            }
        }
    }
    Some(out)
}

/// The targets' fixed data and latch bookkeeping.
#[derive(Debug, Clone)]
pub(super) struct TargetTracker {
    specs: Vec<Target3>,
    contacts: Vec<ContactPoint>,
    /// Whether the target has been ahead of (or level with) the tip at some tick.
    was_ahead: Vec<bool>,
}

impl TargetTracker {
    /// The nodes of the targets' tetrahedra: pinned in the simulation's store, so that the
    /// blocks the displaced centres need are there with node blocks too.
    pub(super) fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.contacts.iter().flat_map(|c| c.terms().map(|(n, _)| n.index()))
    }

    /// Locates every target's centre. Errors: [`SimError3::InvalidParams`] naming the target whose
    /// centre lies outside the mesh.
    pub(super) fn new(model: &TetTissueModel, specs: &[Target3]) -> Result<Self, SimError3> {
        let mut contacts = Vec::with_capacity(specs.len());
        for (k, t) in specs.iter().enumerate() {
            let loc = model.locate(t.centre_m).map_err(|e| {
                SimError3::InvalidParams(format!("targets[{k}]: the centre {:?} m does not lie in the mesh ({e})", t.centre_m))
            })?;
            contacts.push(ContactPoint::in_tetrahedron(loc.tet_idx, loc.nodes, loc.weights));
        }
        Ok(Self { specs: specs.to_vec(), contacts, was_ahead: vec![false; specs.len()] })
    }

    /// The output before any step: reference centres, pending.
    pub(super) fn initial_output(&self, tip_m: [f64; 3], axis: [f64; 3], out: &mut TargetsOut3) {
        out.len = self.specs.len();
        for (o, t) in out.items.iter_mut().zip(&self.specs) {
            *o = TargetOut3 {
                name_idx: t.name_idx,
                centre_m: t.centre_m,
                displacement_m: [0.0; 3],
                distance_m: dist(tip_m, t.centre_m),
                ahead_m: dot(axis, sub(t.centre_m, tip_m)),
                state: TargetState3::Pending,
                latched_tick: None,
            };
        }
    }
}

impl Simulation3 {
    /// Output stage of the targets (module docs): displaced centres from the working points'
    /// forces of this step (`Point::f_world`, written by the output stage), distances, latches.
    /// $O(d)$ per target; allocates nothing.
    pub(super) fn update_targets(&mut self, frame: &[[f64; 3]; 3]) {
        let tr = &mut self.targets;
        let out = &mut self.out.targets;
        let tip = self.out.tip_m;
        let t = frame[0];
        let tick = self.out.tick;
        for k in 0..tr.specs.len() {
            let spec = tr.specs[k];
            let u = target_displacement(&self.cache, &tr.contacts[k], &self.pts);
            let c = [spec.centre_m[0] + u[0], spec.centre_m[1] + u[1], spec.centre_m[2] + u[2]];
            let distance_m = dist(tip, c);
            // s_c − L = t·(c − x_b) − t·(p − x_b) = t·(c − p).
            let ahead_m = dot(t, sub(c, tip));
            let o = &mut out.items[k];
            o.centre_m = c;
            o.displacement_m = u;
            o.distance_m = distance_m;
            o.ahead_m = ahead_m;
            if o.state == TargetState3::Pending {
                if distance_m <= spec.radius_m {
                    o.state = TargetState3::Hit;
                    o.latched_tick = Some(tick);
                } else if -ahead_m > spec.radius_m {
                    if tr.was_ahead[k] {
                        o.state = TargetState3::Missed;
                        o.latched_tick = Some(tick);
                    }
                } else {
                    tr.was_ahead[k] = true;
                }
            }
        }
    }

    /// Un-latches every target: pending again, as at creation (their displaced centres stay
    /// those of the last step).
    pub fn reset_targets(&mut self) {
        self.targets.was_ahead.fill(false);
        for o in self.out.targets.items[..self.out.targets.len].iter_mut() {
            o.state = TargetState3::Pending;
            o.latched_tick = None;
        }
    }
}

/// $u(X_c) = \sum_j W_{cj} f_j$ over the working points (a point whose columns are missing, which
/// the cache's eviction rule excludes for points in use, contributes nothing).
fn target_displacement(cache: &ComplianceStore3, target: &ContactPoint, pts: &[Point]) -> [f64; 3] {
    let mut u = [0.0; 3];
    for p in pts {
        let Some(b) = point_block(cache, target, &p.contact) else { continue };
        for r in 0..3 {
            u[r] += b[r][0] * p.f_world[0] + b[r][1] * p.f_world[1] + b[r][2] * p.f_world[2];
        }
    }
    u
}
