//! The plain data that crosses the real-time thread's queues: the tick record (fixed size, copied
//! into the ring without allocating), its nodes and targets, the pose command, and the fault the
//! real-time thread stores as a code and numbers (put into words off it).

use needlesim_core::BasePose;
use needlesim_core::sim::{Divergence, NodeState, SimError, StepOutput, Unconverged};
use needlesim_core::sim3::{PointState3, SimError3, StepOutput3, TargetState3};

/// Needle nodes carried by one tick record (a simulation may have more; they are counted).
pub const MAX_RECORD_NODES: usize = 128;
/// Targets carried by one tick record: every target of a simulation (core's bound, 2D and 3D
/// alike), so that no live frame drops one.
pub const MAX_RECORD_TARGETS: usize = needlesim_core::sim::param_limits::MAX_TARGETS;
/// Capacity of the ring between the real-time thread and the fan-out, in ticks.
pub(crate) const RECORD_RING: usize = 2048;
/// Capacity of the column request and delivery queues.
pub(crate) const COLUMN_QUEUE: usize = 512;
/// How often the real-time thread refreshes the stiffness Jacobian (six probe solves).
pub const STIFFNESS_EVERY_TICKS: u64 = 10;
/// Ticks without a fresh device pose after which the device counts as stale and the needle is
/// held where it was (50 ms at 1 kHz).
pub const DEVICE_STALE_TICKS: u64 = 50;

/// One needle node in a tick record.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeRecord {
    /// The node, or a material point's nearest node.
    pub node: u32,
    /// The mesh nodes the contact interpolates (`contact_nodes[..n_contact]`, 1 for a node
    /// contact, 3 for a material point; a patch's three heaviest, renormalised:
    /// [`needlesim_core::ContactPoint::three_terms`]) and their weights: the contact's force
    /// loads node `contact_nodes[k]` with `contact_weights[k]` of it.
    pub contact_nodes: [u32; 3],
    pub contact_weights: [f64; 3],
    pub n_contact: u8,
    /// 0 stuck, 1 slipping, 2 tip.
    pub state: u8,
    pub position_m: [f64; 2],
    pub force_n: [f64; 2],
}

/// One target in a tick record.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TargetRecord {
    pub position_m: [f64; 2],
    pub distance_m: f64,
    pub hit: bool,
}

/// Everything one tick produced, as plain data of fixed size (copied into the ring without
/// allocation).
#[derive(Debug, Clone, Copy)]
pub struct TickRecord {
    pub tick: u64,
    pub time_s: f64,
    pub base: BasePose,
    pub force_n: [f64; 2],
    pub torque_nm: f64,
    pub force_axial_n: f64,
    pub force_lateral_n: f64,
    pub tip_m: [f64; 2],
    pub inserted_length_m: f64,
    pub n_stuck: u32,
    pub n_slipping: u32,
    pub n_tip: u32,
    pub n_nodes: u16,
    pub nodes: [NodeRecord; MAX_RECORD_NODES],
    pub n_targets: u8,
    pub targets: [TargetRecord; MAX_RECORD_TARGETS],
    /// Time spent computing this tick.
    pub compute_ns: u64,
    /// How late the tick started after its deadline.
    pub lateness_ns: u64,
    /// The newest pose command this tick used.
    pub pose_seq: u64,
    pub client_time_ns: u64,
    /// The local stiffness $\partial(F_x, F_y, \tau)/\partial(x, y, \theta)$, row-major, refreshed
    /// every [`STIFFNESS_EVERY_TICKS`] ticks.
    pub stiffness: [f64; 9],
    /// A device channel exists and its bridge stopped sending poses.
    pub device_stale: bool,
    /// The needle's shape, base to tip, down-sampled to at most [`MAX_RECORD_SHAPE`] points.
    pub n_shape: u8,
    pub shape_m: [[f64; 2]; MAX_RECORD_SHAPE],
    /// The bevel side (0: symmetric tip).
    pub bevel_side: f64,
    /// The session faulted at this record's tick: the simulation failed, the force is zero and
    /// the needle is held; no record follows.
    pub fault: Option<SessionFault>,
    /// The dimension of the session: 2, or 3 when [`TickRecord::d3`] holds the tick. A 3D
    /// record fills the 2D fields above with the planar part of the 3D tick (x, y, the twist
    /// about z), so that a 2D consumer reads something meaningful.
    pub dimension: u8,
    /// The 3D tick (all zero in a 2D session).
    pub d3: Record3,
}

/// Contact points carried by one 3D tick record (a simulation may have more; they are counted
/// in `SessionCounters::records_truncated`).
pub const MAX_RECORD_CONTACTS3: usize = 64;
/// Targets carried by one 3D tick record (the 3D simulation's own bound).
pub const MAX_RECORD_TARGETS3: usize = needlesim_core::sim3::MAX_TARGETS;

/// One contact point of a 3D tick (world frame).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactRecord3 {
    /// Its reference (undeformed) position, m.
    pub x_ref_m: [f64; 3],
    /// Its current position $X + u$, m.
    pub x_m: [f64; 3],
    /// The force of the needle on the tissue there, N.
    pub force_n: [f64; 3],
    /// 0 stuck, 1 slipping, 2 carried by the tip.
    pub state: u8,
}

/// One target sphere of a 3D tick (world frame).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TargetRecord3 {
    /// The index of its name in the session's target names.
    pub name_idx: u16,
    /// Displaced centre, m.
    pub centre_m: [f64; 3],
    pub radius_m: f64,
    /// Distance from the tip to the displaced centre, m.
    pub distance_m: f64,
    /// Latched: the tip came within the radius.
    pub hit: bool,
    /// Latched: the tip went past the centre without a hit.
    pub missed: bool,
}

/// The 3D part of a tick record: plain data of fixed size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record3 {
    /// The base pose applied: position, world, m …
    pub position_m: [f64; 3],
    /// … and orientation, unit quaternion $(w, x, y, z)$, needle body frame → world (the needle
    /// axis is the body's $+x$).
    pub orientation_wxyz: [f64; 4],
    /// Force of the tissue on the needle base, world, N.
    pub force_n: [f64; 3],
    /// Torque of the tissue on the needle about the base point, world, N·m.
    pub torque_nm: [f64; 3],
    /// The axial force, $-t\cdot F$, N (positive while pushing in).
    pub axial_force_n: f64,
    /// The tip, world, m.
    pub tip_m: [f64; 3],
    pub n_contacts: u8,
    pub contacts: [ContactRecord3; MAX_RECORD_CONTACTS3],
    pub n_targets: u8,
    pub targets: [TargetRecord3; MAX_RECORD_TARGETS3],
    /// $\partial(F, \tau)/\partial(x_b, \theta)$ (`needlesim_core::sim3::WrenchStiffness3`),
    /// refreshed every [`STIFFNESS_EVERY_TICKS`] ticks.
    pub stiffness: [[f64; 6]; 6],
}

impl Default for Record3 {
    fn default() -> Self {
        Self {
            position_m: [0.0; 3],
            orientation_wxyz: [1.0, 0.0, 0.0, 0.0],
            force_n: [0.0; 3],
            torque_nm: [0.0; 3],
            axial_force_n: 0.0,
            tip_m: [0.0; 3],
            n_contacts: 0,
            contacts: [ContactRecord3::default(); MAX_RECORD_CONTACTS3],
            n_targets: 0,
            targets: [TargetRecord3::default(); MAX_RECORD_TARGETS3],
            stiffness: [[0.0; 6]; 6],
        }
    }
}

impl Record3 {
    /// The contact points of this record.
    pub fn contacts(&self) -> &[ContactRecord3] {
        &self.contacts[..self.n_contacts as usize]
    }
    /// The targets of this record.
    pub fn targets(&self) -> &[TargetRecord3] {
        &self.targets[..self.n_targets as usize]
    }
}

/// Why a live session stopped stepping: plain data (a code and numbers), written by the
/// real-time thread without allocating and put into words by [`SessionFault::message`] off it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SessionFault {
    /// The tick whose step failed.
    pub tick: u64,
    /// A [`Divergence`] code (1..), or one of the `FAULT_*` codes for other solver errors.
    pub code: u8,
    /// The diverged quantity's value and bound (0 for other errors).
    pub value: f64,
    pub bound: f64,
}

/// Fault code: the tissue model failed (computing a compliance column).
pub const FAULT_TISSUE: u8 = 101;
/// Fault code: the working-set solver failed.
pub const FAULT_SOLVER: u8 = 102;
/// Fault code: any other simulation error.
pub const FAULT_OTHER: u8 = 103;
/// Fault codes: a tick that did not converge, `FAULT_UNCONVERGED + Unconverged::code()`.
pub const FAULT_UNCONVERGED: u8 = 110;

impl SessionFault {
    /// The fault of a failed step at `tick` (not for a rejected pose, which is no fault).
    pub fn of(e: &SimError, tick: u64) -> Self {
        match *e {
            SimError::Diverged { tick, what, value, bound } => Self { tick, code: what.code(), value, bound },
            SimError::Tissue(_) => Self { tick, code: FAULT_TISSUE, value: 0.0, bound: 0.0 },
            SimError::Mixed(_) => Self { tick, code: FAULT_SOLVER, value: 0.0, bound: 0.0 },
            _ => Self { tick, code: FAULT_OTHER, value: 0.0, bound: 0.0 },
        }
    }

    /// The fault of a failed 3D step at `tick` (not for a rejected pose, which is no fault).
    pub fn of3(e: &SimError3, tick: u64) -> Self {
        let code = match e {
            SimError3::Tissue(_) | SimError3::Sparse(_) => FAULT_TISSUE,
            SimError3::Mixed(_) => FAULT_SOLVER,
            _ => FAULT_OTHER,
        };
        Self { tick, code, value: 0.0, bound: 0.0 }
    }

    /// The fault of a tick that did not converge ([`Unconverged`]): the live counterpart of an
    /// offline run's stop (needlesim-offline's convergence policy).
    pub fn unconverged(why: Unconverged, tick: u64) -> Self {
        Self { tick, code: FAULT_UNCONVERGED + why.code(), value: 0.0, bound: 0.0 }
    }

    /// The fault in words (allocates: for the IO side).
    pub fn message(&self) -> String {
        if let Some(why) = self.code.checked_sub(FAULT_UNCONVERGED).and_then(Unconverged::from_code) {
            return format!(
                "tick {}: the tick did not converge ({why}); the session stopped rather than push with an unconverged answer",
                self.tick
            );
        }
        let what = match Divergence::from_code(self.code) {
            Some(what) => return SimError::Diverged { tick: self.tick, what, value: self.value, bound: self.bound }.to_string(),
            None if self.code == FAULT_TISSUE => "the tissue model failed (a compliance column)",
            None if self.code == FAULT_SOLVER => "the working-set solver failed",
            None => "the simulation failed",
        };
        format!("tick {}: {what}", self.tick)
    }
}

/// Step failures in a row (other than a divergence, which faults at once) after which a live
/// session faults: 0.1 s at 1 kHz.
pub const MAX_CONSECUTIVE_STEP_ERRORS: u32 = 100;

/// Points of the needle's shape kept in a record.
pub const MAX_RECORD_SHAPE: usize = 33;

impl Default for TickRecord {
    fn default() -> Self {
        Self {
            tick: 0,
            time_s: 0.0,
            base: BasePose::default(),
            force_n: [0.0; 2],
            torque_nm: 0.0,
            force_axial_n: 0.0,
            force_lateral_n: 0.0,
            tip_m: [0.0; 2],
            inserted_length_m: 0.0,
            n_stuck: 0,
            n_slipping: 0,
            n_tip: 0,
            n_nodes: 0,
            nodes: [NodeRecord::default(); MAX_RECORD_NODES],
            n_targets: 0,
            targets: [TargetRecord::default(); MAX_RECORD_TARGETS],
            compute_ns: 0,
            lateness_ns: 0,
            pose_seq: 0,
            client_time_ns: 0,
            stiffness: [0.0; 9],
            device_stale: false,
            n_shape: 0,
            shape_m: [[0.0; 2]; MAX_RECORD_SHAPE],
            bevel_side: 0.0,
            fault: None,
            dimension: 2,
            d3: Record3::default(),
        }
    }
}

impl TickRecord {
    pub(crate) fn fill_from_rt(&mut self, out: &StepOutput) {
        self.tick = out.tick;
        self.time_s = out.time_s;
        self.base = out.base;
        self.force_n = out.force_n;
        self.torque_nm = out.torque_nm;
        self.force_axial_n = out.force_axial_n;
        self.force_lateral_n = out.force_lateral_n;
        self.tip_m = out.tip_m;
        self.inserted_length_m = out.inserted_length_m;
        self.n_stuck = out.n_stuck as u32;
        self.n_slipping = out.n_slipping as u32;
        self.n_tip = out.n_tip as u32;
        let n = out.needle_nodes.len().min(MAX_RECORD_NODES);
        self.n_nodes = n as u16;
        for (r, nn) in self.nodes.iter_mut().zip(&out.needle_nodes[..n]) {
            // A patch keeps its three heaviest nodes here (for drawing the field only).
            let (three, contact_weights, used) = nn.contact.three_terms();
            let contact_nodes = three.map(|j| j.index() as u32);
            let n_contact = used as u8;
            *r = NodeRecord {
                node: nn.node_idx as u32,
                contact_nodes,
                contact_weights,
                n_contact,
                state: match nn.state {
                    NodeState::Stuck => 0,
                    NodeState::Slipping => 1,
                    NodeState::Tip => 2,
                },
                position_m: nn.position_m,
                force_n: nn.force_n,
            };
        }
        // The shape, evenly down-sampled (first and last points kept).
        let n_pts = out.shape_m.len();
        let kept = n_pts.min(MAX_RECORD_SHAPE);
        self.n_shape = kept as u8;
        for (k, r) in self.shape_m.iter_mut().take(kept).enumerate() {
            let idx = if kept < 2 { 0 } else { (k * (n_pts - 1) + (kept - 1) / 2) / (kept - 1) };
            *r = out.shape_m[idx.min(n_pts - 1)];
        }
        if kept >= 2 {
            self.shape_m[kept - 1] = out.shape_m[n_pts - 1];
        }
        self.bevel_side = out.bevel_side;
        let m = out.targets.len().min(MAX_RECORD_TARGETS);
        self.n_targets = m as u8;
        for (r, t) in self.targets.iter_mut().zip(&out.targets[..m]) {
            *r = TargetRecord { position_m: t.position_m, distance_m: t.distance_m, hit: t.hit };
        }
    }

    /// Fills the record from a 3D step (`radii_m`: the targets' radii, in the simulation's order),
    /// the 2D fields with its planar part. Allocates nothing.
    pub(crate) fn fill_from_rt3(&mut self, out: &StepOutput3, radii_m: &[f64]) {
        let q = out.pose.orientation;
        let wxyz = [q.w, q.i, q.j, q.k];
        let d = &mut self.d3;
        d.position_m = out.pose.position_m;
        d.orientation_wxyz = wxyz;
        d.force_n = out.base_force_n;
        d.torque_nm = out.base_torque_nm;
        d.axial_force_n = out.axial_force_n;
        d.tip_m = out.tip_m;
        let n = out.contacts.len().min(MAX_RECORD_CONTACTS3);
        d.n_contacts = n as u8;
        let (mut stuck, mut slipping, mut tip) = (0, 0, 0);
        for (r, c) in d.contacts.iter_mut().zip(&out.contacts[..n]) {
            let state = match c.state {
                PointState3::Stuck => 0,
                PointState3::Slipping => 1,
                PointState3::Tip => 2,
            };
            *r = ContactRecord3 { x_ref_m: c.x_ref_m, x_m: c.x_m, force_n: c.force_n, state };
        }
        for c in &out.contacts {
            match c.state {
                PointState3::Stuck => stuck += 1,
                PointState3::Slipping => slipping += 1,
                PointState3::Tip => tip += 1,
            }
        }
        let targets = out.targets.as_slice();
        let m = targets.len().min(MAX_RECORD_TARGETS3);
        d.n_targets = m as u8;
        for (r, t) in d.targets.iter_mut().zip(&targets[..m]) {
            *r = TargetRecord3 {
                name_idx: t.name_idx as u16,
                centre_m: t.centre_m,
                radius_m: radii_m.get(t.name_idx).copied().unwrap_or(0.0),
                distance_m: t.distance_m,
                hit: t.state == TargetState3::Hit,
                missed: t.state == TargetState3::Missed,
            };
        }
        // The planar part, for 2D consumers.
        self.dimension = 3;
        self.tick = out.tick;
        self.time_s = out.time_s;
        let [x_m, y_m, theta_rad] = needlesim_channel::spatial::pose_to_planar(out.pose.position_m, wxyz);
        self.base = BasePose::new(x_m, y_m, theta_rad);
        self.force_n = [out.base_force_n[0], out.base_force_n[1]];
        self.torque_nm = out.base_torque_nm[2];
        self.force_axial_n = -out.axial_force_n;
        self.force_lateral_n = 0.0;
        self.tip_m = [out.tip_m[0], out.tip_m[1]];
        self.inserted_length_m = out.inserted_length_m;
        self.n_stuck = stuck;
        self.n_slipping = slipping;
        self.n_tip = tip;
        self.n_nodes = 0;
        self.n_targets = 0;
        self.n_shape = 2;
        self.shape_m[0] = [out.pose.position_m[0], out.pose.position_m[1]];
        self.shape_m[1] = self.tip_m;
        self.bevel_side = 0.0;
    }

    /// The needle nodes of this record.
    pub fn nodes(&self) -> &[NodeRecord] {
        &self.nodes[..self.n_nodes as usize]
    }
    /// The nodes and weights of a record's contact ([`NodeRecord::contact_nodes`]).
    pub fn contact_terms(nn: &NodeRecord) -> impl Iterator<Item = (u32, f64)> + '_ {
        let n = nn.n_contact as usize;
        nn.contact_nodes[..n].iter().copied().zip(nn.contact_weights[..n].iter().copied())
    }
    /// The targets of this record.
    pub fn targets(&self) -> &[TargetRecord] {
        &self.targets[..self.n_targets as usize]
    }
    /// The needle's shape of this record.
    pub fn shape(&self) -> &[[f64; 2]] {
        &self.shape_m[..self.n_shape as usize]
    }
}

/// A pose command from a controller: a 2D [`BasePose`] (the default) or a 3D
/// [`BasePose3`](needlesim_core::sim3::BasePose3) ([`PoseCommand3`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PoseCommand<P = BasePose> {
    pub pose: P,
    pub seq: u64,
    pub client_time_ns: u64,
}

/// A 3D pose command.
pub type PoseCommand3 = PoseCommand<needlesim_core::sim3::BasePose3>;
