//! What the real-time loop ([`crate::rt_loop`]) needs of a simulation, as a trait ([`LiveSim`]),
//! implemented by the 2D [`Live2`] (a [`Simulation`] and its column worker's queues) and the 3D
//! [`Live3`] (a [`Simulation3`] and its worker's queues: compliance columns or node blocks, per
//! its store). The loop owns the schedule, the pose slots, the device channel, the counters, the
//! record ring and the doorbells; the simulation side owns its step, its compliance traffic, its
//! stiffness and its part of the record. Everything here runs on the real-time thread: no
//! allocation once warmed up, no lock, no I/O, no logging; what goes wrong is counted.

use crate::spin::SpinState;
use std::sync::atomic::Ordering;

use needlesim_channel::shm::{DevicePose, ServerForce};
use needlesim_core::BasePose;
use needlesim_core::sim::{SimError, Simulation};
use needlesim_core::sim3::{BasePose3, BlockPayload, BlockRequest, SimError3, Simulation3};

use crate::counters::SessionCounters;
use crate::fan_out::{EVICTED_TAG, RENDER_TAG};
use crate::record::{MAX_RECORD_CONTACTS3, MAX_RECORD_NODES, SessionFault, TickRecord};

/// A node's columns were asked of the worker for the real-time cache.
const REQUESTED_FOR_CACHE: u8 = 1;
/// A node's columns were asked of the worker for the renderer (the node is a contact's).
const REQUESTED_FOR_RENDER: u8 = 2;

/// Why a step published nothing.
pub(crate) enum StepFail {
    /// The pose was refused (not finite, not unit): counted, the last pose held, no fault.
    RejectedPose,
    /// The step failed; `diverged` (a diverged solve, or a tick that did not converge) faults
    /// at once, anything else after a run of failures.
    Failed { diverged: bool, fault: SessionFault },
}

/// A simulation the real-time loop can drive (module docs). Every method runs on the real-time
/// thread and must not allocate once warmed up.
pub(crate) trait LiveSim: Send + 'static {
    /// The base pose a client or the device commands.
    type Pose: Copy + Send + Sync + Default + 'static;
    /// The pose the last step applied.
    fn pose(&self) -> Self::Pose;
    /// The device's 6-DOF pose as this simulation's pose (`None`: refused, e.g. not unit).
    fn pose_from_device(&self, p: &DevicePose) -> Option<Self::Pose>;
    /// `target` approached from [`LiveSim::pose`] by at most `max_step_m` of translation and
    /// `max_step_rad` of rotation (each clamped on its own), and whether `target` was reached
    /// (nothing clamped): the device's catch-up after a suspension ([`crate::rt_loop`]).
    fn towards(&self, target: &Self::Pose, max_step_m: f64, max_step_rad: f64) -> (Self::Pose, bool);
    /// Takes what the worker delivered since the last tick.
    fn absorb_from_rt(&mut self, counters: &SessionCounters);
    /// Turns the needle 180° about its axis (nothing for a needle without bevel).
    fn flip_bevel_from_rt(&mut self);
    /// The spin command word in force from this tick on ([`crate::spin`]; nothing in 2D, whose
    /// needle has no axis to roll about).
    fn set_spin_from_rt(&mut self, _word: u64) {}
    /// One step towards `pose`, filling `rec` on success.
    fn step_from_rt(&mut self, pose: Self::Pose, rec: &mut TickRecord) -> Result<(), StepFail>;
    /// Fills the pose fields of a fault's record (the needle held where it is) and zeroes the
    /// stiffness.
    fn hold_record_from_rt(&mut self, rec: &mut TickRecord);
    /// The tick rate, Hz.
    fn tick_rate_hz(&self) -> f64;
    /// Recomputes the stiffness of the wrench (`Err`: failed, the last one is kept).
    fn refresh_stiffness_from_rt(&mut self) -> Result<(), ()>;
    /// Copies the current stiffness into the record.
    fn stiffness_into(&self, rec: &mut TickRecord);
    /// The wrench, stiffness and base pose of `rec` into the device channel's force.
    fn fill_force(&self, rec: &TickRecord, force: &mut ServerForce);
    /// After the step: statistics into the counters, and requests to the worker. Returns whether
    /// any request was pushed (the loop then rings the worker's doorbell).
    fn after_step_from_rt(&mut self, counters: &SessionCounters, column_misses_before: u64) -> bool;
    /// The count of column misses so far (read before the step).
    fn column_misses(&self) -> u64;
}

/// The 2D simulation and the queues to its column worker.
pub(crate) struct Live2 {
    pub(crate) sim: Simulation,
    pub(crate) req_tx: rtrb::Producer<u32>,
    pub(crate) col_rx: rtrb::Consumer<(u32, Box<[f64]>)>,
    pub(crate) ret_tx: rtrb::Producer<Box<[f64]>>,
    /// Per node: [`REQUESTED_FOR_CACHE`] and/or [`REQUESTED_FOR_RENDER`], until evicted.
    pub(crate) requested: Vec<u8>,
    /// The stiffness $\partial(F_x, F_y, \tau)/\partial(x, y, \theta)$, row-major.
    pub(crate) stiffness: [f64; 9],
}

impl Live2 {
    /// After the cache evicted `node`'s columns: it may be requested again, and the worker is
    /// told to drop the renderer's copy (a full ring is counted; the copy then stays until the
    /// node is computed again).
    fn forget_columns_from_rt(&mut self, node: usize, counters: &SessionCounters) {
        self.requested[node] = 0;
        if self.req_tx.push(node as u32 | EVICTED_TAG).is_err() {
            counters.dropped_eviction_notices.fetch_add(1, Ordering::Relaxed);
        }
    }
}

impl LiveSim for Live2 {
    type Pose = BasePose;

    fn pose(&self) -> BasePose {
        self.sim.pose()
    }

    fn pose_from_device(&self, p: &DevicePose) -> Option<BasePose> {
        // A 2D session takes the planar part of the 6-DOF pose (x, y, the twist about z).
        let [x_m, y_m, theta_rad] = p.to_planar();
        Some(BasePose::new(x_m, y_m, theta_rad))
    }

    fn towards(&self, target: &BasePose, max_step_m: f64, max_step_rad: f64) -> (BasePose, bool) {
        // The translation along the straight line, the angle on its own (no wrap: as the core's clamp).
        let from = self.sim.pose();
        let (dx, dy) = (target.x_m - from.x_m, target.y_m - from.y_m);
        let dist = dx.hypot(dy);
        let mut next = *target;
        let mut reached = true;
        if dist > max_step_m {
            let k = max_step_m / dist;
            (next.x_m, next.y_m) = (from.x_m + k * dx, from.y_m + k * dy);
            reached = false;
        }
        let dth = target.theta_rad - from.theta_rad;
        if dth.abs() > max_step_rad {
            next.theta_rad = from.theta_rad + max_step_rad.copysign(dth);
            reached = false;
        }
        (next, reached)
    }

    fn absorb_from_rt(&mut self, counters: &SessionCounters) {
        // Columns delivered by the worker; the box not kept goes back to be freed there.
        while let Ok((node, cols)) = self.col_rx.pop() {
            let inserted = self.sim.insert_columns_owned(node as usize, cols);
            if let Some(spare) = inserted.spare
                && let Err(rtrb::PushError::Full(spare)) = self.ret_tx.push(spare)
            {
                drop(spare);
            }
            if let Some(evicted) = inserted.evicted {
                self.forget_columns_from_rt(evicted, counters);
            }
        }
    }

    fn flip_bevel_from_rt(&mut self) {
        self.sim.flip_bevel();
    }

    fn step_from_rt(&mut self, pose: BasePose, rec: &mut TickRecord) -> Result<(), StepFail> {
        match self.sim.step(pose) {
            // The convergence policy of a live session: a tick that did not converge is not
            // an answer to push a device with; the session faults (needlesim-offline's runs stop).
            Ok(out) => match out.unconverged() {
                Some(why) => Err(StepFail::Failed { diverged: true, fault: SessionFault::unconverged(why, out.tick) }),
                None => {
                    rec.fill_from_rt(out);
                    Ok(())
                }
            },
            Err(SimError::NonFinitePose { .. }) => Err(StepFail::RejectedPose),
            Err(e) => Err(StepFail::Failed {
                diverged: matches!(e, SimError::Diverged { .. }),
                fault: SessionFault::of(&e, self.sim.stats().ticks),
            }),
        }
    }

    fn hold_record_from_rt(&mut self, rec: &mut TickRecord) {
        rec.base = self.sim.pose();
        self.stiffness = [0.0; 9];
    }

    fn tick_rate_hz(&self) -> f64 {
        self.sim.params().tick_rate_hz
    }

    fn refresh_stiffness_from_rt(&mut self) -> Result<(), ()> {
        let j = self.sim.stiffness_jacobian().map_err(|_| ())?;
        self.stiffness = [j[0][0], j[0][1], j[0][2], j[1][0], j[1][1], j[1][2], j[2][0], j[2][1], j[2][2]];
        Ok(())
    }

    fn stiffness_into(&self, rec: &mut TickRecord) {
        rec.stiffness = self.stiffness;
    }

    fn fill_force(&self, r: &TickRecord, force: &mut ServerForce) {
        // The 2D wrench, stiffness and base embedded in the channel's 6-DOF fields.
        force.set_planar([r.force_n[0], r.force_n[1], r.torque_nm], &self.stiffness, [r.base.x_m, r.base.y_m, r.base.theta_rad]);
    }

    fn column_misses(&self) -> u64 {
        self.sim.stats().column_misses
    }

    fn after_step_from_rt(&mut self, counters: &SessionCounters, misses_before: u64) -> bool {
        for k in 0..self.sim.output().evicted.len() {
            let node = self.sim.output().evicted[k];
            self.forget_columns_from_rt(node, counters);
        }
        let st = self.sim.stats();
        counters.column_misses.fetch_add(st.column_misses - misses_before, Ordering::Relaxed);
        counters.columns_evicted.store(st.columns_evicted, Ordering::Relaxed);
        counters.column_deferrals.store(st.column_deferrals, Ordering::Relaxed);
        counters.budget_exhausted_ticks.store(st.budget_exhausted_ticks, Ordering::Relaxed);
        counters.active_set_capped_ticks.store(st.active_set_capped_ticks, Ordering::Relaxed);
        counters.shape_capped_ticks.store(st.shape_capped_ticks, Ordering::Relaxed);
        counters.hybrid_checks.store(st.hybrid_checks, Ordering::Relaxed);
        counters.hybrid_rebuilds.store(st.hybrid_rebuilds, Ordering::Relaxed);
        counters.clamped_ticks.store(st.clamped_ticks, Ordering::Relaxed);
        if self.sim.output().needle_nodes.len() > MAX_RECORD_NODES {
            counters.records_truncated.fetch_add(1, Ordering::Relaxed);
        }
        // Ask the worker for the columns of approaching nodes (for this thread's cache), and for
        // the renderer's copies of the contacts' nodes (the fan-out renders their share of the
        // field; it keeps no copy of a column only the prefetch needed).
        let out = self.sim.output();
        let (requested, req_tx) = (&mut self.requested, &mut self.req_tx);
        let cache_nodes = out.approaching.iter().map(|&j| (j, REQUESTED_FOR_CACHE, 0));
        // The nodes the record keeps for each contact (a patch's three heaviest).
        let render_nodes = out.needle_nodes.iter().flat_map(|nn| {
            let (three, _, used) = nn.contact.three_terms();
            (0..used).map(move |k| (three[k].index(), REQUESTED_FOR_RENDER, RENDER_TAG))
        });
        let mut requested_any = false;
        for (node, flag, tag) in cache_nodes.chain(render_nodes) {
            if requested[node] & flag == 0 {
                if req_tx.push(node as u32 | tag).is_ok() {
                    requested[node] |= flag;
                    requested_any = true;
                } else {
                    counters.dropped_column_requests.fetch_add(1, Ordering::Relaxed);
                    break;
                }
            }
        }
        requested_any
    }
}

/// The compliance traffic of a 3D session, per the simulation's store.
pub(crate) enum Link3 {
    /// Columns: node requests out, `(node, 9n columns)` in, boxes back to be reused or freed.
    Columns {
        req_tx: rtrb::Producer<u32>,
        col_rx: rtrb::Consumer<(u32, Box<[f64]>)>,
        ret_tx: rtrb::Producer<Box<[f64]>>,
        /// Per node: requested and not evicted since.
        requested: Vec<bool>,
        /// Requests sent and not yet answered (at most [`MAX_OUTSTANDING_COLUMNS3`]).
        outstanding: usize,
    },
    /// Node blocks: [`BlockRequest`]s out (in the order the store reserved them: none is ever
    /// dropped, the loop asks for at most the ring's free room), payloads in (in the same
    /// order), payload boxes back for reuse.
    Blocks {
        req_tx: rtrb::Producer<BlockRequest>,
        pay_rx: rtrb::Consumer<Box<BlockPayload>>,
        ret_tx: rtrb::Producer<Box<BlockPayload>>,
        /// The request list, sized once.
        reqs: Vec<BlockRequest>,
    },
}

/// Column requests with the 3D worker at once, at most. A node's columns take the worker a few
/// milliseconds on a 10k-node mesh; with the queue this short a capture's node waits for at
/// most this many others (issue 17: a FIFO of a whole lookahead's nodes deferred the first
/// captures after a puncture for 0.2 s).
pub(crate) const MAX_OUTSTANDING_COLUMNS3: usize = 2;

/// Requests per tick to the 3D worker, at most.
pub(crate) const MAX_REQUESTS3_PER_TICK: usize = 64;

/// The 3D simulation and the queues to its worker.
pub(crate) struct Live3 {
    pub(crate) sim: Simulation3,
    pub(crate) link: Link3,
    /// The targets' radii, by name index.
    pub(crate) radii_m: Vec<f64>,
    pub(crate) stiffness: [[f64; 6]; 6],
    /// Compliance payloads the simulation refused (a protocol error; counted, never expected).
    pub(crate) refused_payloads: u64,
    /// The duty-cycled spin ([`crate::spin`]): the command word in force and the roll's state.
    pub(crate) spin_word: u64,
    pub(crate) spin: SpinState,
    /// The spin's roll (rad) in the pose of the last successful step: [`LiveSim::pose`] takes it
    /// off again.
    pub(crate) applied_roll_rad: f64,
}

impl LiveSim for Live3 {
    type Pose = BasePose3;

    /// The pose the last step applied without the spin's roll (the needle's pose itself when it
    /// does not spin): what the loop holds and what a device catches up with, so that holding
    /// the needle never adds the roll twice.
    fn pose(&self) -> BasePose3 {
        let p = self.sim.pose();
        if self.applied_roll_rad == 0.0 {
            return p;
        }
        let unroll = nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Vector3::x_axis(), -self.applied_roll_rad);
        BasePose3::from_rotation(p.position_m, p.orientation * unroll)
    }

    fn pose_from_device(&self, p: &DevicePose) -> Option<BasePose3> {
        BasePose3::new(p.position_m, p.orientation).ok()
    }

    fn towards(&self, target: &BasePose3, max_step_m: f64, max_step_rad: f64) -> (BasePose3, bool) {
        let (next, clamped) = self.pose().clamped_towards(target, max_step_m, max_step_rad);
        (next, !clamped)
    }

    fn absorb_from_rt(&mut self, counters: &SessionCounters) {
        match &mut self.link {
            Link3::Columns { col_rx, ret_tx, requested, outstanding, .. } => {
                while let Ok((node, cols)) = col_rx.pop() {
                    // Every request is answered once (an empty box when the worker failed).
                    *outstanding = outstanding.saturating_sub(1);
                    match self.sim.insert_columns_owned(node as usize, cols) {
                        Ok((evicted, spare)) => {
                            if let Some(evicted) = evicted {
                                requested[evicted] = false;
                                counters.columns_evicted.fetch_add(1, Ordering::Relaxed);
                            }
                            // Back to the worker to be reused; a full ring frees it here (not
                            // expected: the ring is longer than the delivery ring).
                            if let Some(spare) = spare
                                && let Err(rtrb::PushError::Full(spare)) = ret_tx.push(spare)
                            {
                                drop(spare);
                            }
                        }
                        Err(_) => self.refused_payloads += 1,
                    }
                }
            }
            Link3::Blocks { pay_rx, ret_tx, .. } => {
                while let Ok(p) = pay_rx.pop() {
                    if self.sim.insert_payload(&p).is_err() {
                        self.refused_payloads += 1;
                    }
                    if let Err(rtrb::PushError::Full(p)) = ret_tx.push(p) {
                        drop(p);
                    }
                }
            }
        }
    }

    fn flip_bevel_from_rt(&mut self) {
        // A 3D needle's bevel turns with the base's roll (the pose, or the spin): a flip is a
        // roll the controller commands.
    }

    fn set_spin_from_rt(&mut self, word: u64) {
        self.spin_word = word;
    }

    fn step_from_rt(&mut self, pose: BasePose3, rec: &mut TickRecord) -> Result<(), StepFail> {
        let tick = self.sim.tick();
        let mut rolled = pose;
        self.spin.apply_from_rt(self.spin_word, &mut rolled);
        match self.sim.step(rolled) {
            Ok(out) => match out.unconverged() {
                Some(why) => Err(StepFail::Failed { diverged: true, fault: SessionFault::unconverged(why, out.tick) }),
                None => {
                    self.applied_roll_rad = self.spin.roll_rad();
                    rec.fill_from_rt3(out, &self.radii_m);
                    Ok(())
                }
            },
            Err(SimError3::Pose { .. }) => Err(StepFail::RejectedPose),
            Err(e) => Err(StepFail::Failed { diverged: false, fault: SessionFault::of3(&e, tick) }),
        }
    }

    fn hold_record_from_rt(&mut self, rec: &mut TickRecord) {
        let p = self.sim.pose();
        let q = p.orientation;
        rec.dimension = 3;
        rec.d3.position_m = p.position_m;
        rec.d3.orientation_wxyz = [q.w, q.i, q.j, q.k];
        rec.d3.force_n = [0.0; 3];
        rec.d3.torque_nm = [0.0; 3];
        rec.d3.axial_force_n = 0.0;
        let [x_m, y_m, theta_rad] = needlesim_channel::spatial::pose_to_planar(p.position_m, rec.d3.orientation_wxyz);
        rec.base = BasePose::new(x_m, y_m, theta_rad);
        self.stiffness = [[0.0; 6]; 6];
    }

    fn tick_rate_hz(&self) -> f64 {
        self.sim.params().tick_rate_hz
    }

    fn refresh_stiffness_from_rt(&mut self) -> Result<(), ()> {
        self.stiffness = self.sim.wrench_stiffness().map_err(|_| ())?.matrix;
        Ok(())
    }

    fn stiffness_into(&self, rec: &mut TickRecord) {
        rec.d3.stiffness = self.stiffness;
        // The planar restriction, for 2D consumers.
        rec.stiffness = needlesim_channel::spatial::restrict_planar_stiffness(&self.stiffness);
    }

    fn fill_force(&self, r: &TickRecord, force: &mut ServerForce) {
        force.force_n = r.d3.force_n;
        force.torque_nm = r.d3.torque_nm;
        force.stiffness = self.stiffness;
        force.base_position_m = r.d3.position_m;
        force.base_orientation = r.d3.orientation_wxyz;
    }

    fn column_misses(&self) -> u64 {
        // A 3D step never computes a column: a missing one defers a capture (counted below).
        0
    }

    fn after_step_from_rt(&mut self, counters: &SessionCounters, _misses_before: u64) -> bool {
        let st = self.sim.stats();
        counters.column_deferrals.store(st.column_deferrals, Ordering::Relaxed);
        counters.late_captures.store(st.late_captures, Ordering::Relaxed);
        counters.pending_captures_dropped.store(st.pending_dropped, Ordering::Relaxed);
        counters.clamped_ticks.store(st.clamped_ticks, Ordering::Relaxed);
        counters.step_errors.fetch_add(std::mem::take(&mut self.refused_payloads), Ordering::Relaxed);
        if self.sim.output().contacts.len() > MAX_RECORD_CONTACTS3 {
            counters.records_truncated.fetch_add(1, Ordering::Relaxed);
        }
        let mut requested_any = false;
        match &mut self.link {
            Link3::Columns { req_tx, requested, outstanding, .. } => {
                // The pinned nodes, then the approaching ones nearest first (the capture's
                // candidate leads that list), while fewer than MAX_OUTSTANDING_COLUMNS3 are
                // with the worker: the worker answers in order, so a short queue is what lets
                // a node needed now overtake the ones a lookahead asked for earlier.
                let pins = self.sim.pinned_nodes();
                let out = self.sim.output();
                for &node in pins.iter().chain(&out.approaching) {
                    if *outstanding >= MAX_OUTSTANDING_COLUMNS3 {
                        break;
                    }
                    if requested[node] || self.sim.cache().contains(node) {
                        continue;
                    }
                    if req_tx.push(node as u32).is_ok() {
                        requested[node] = true;
                        *outstanding += 1;
                        requested_any = true;
                    } else {
                        counters.dropped_column_requests.fetch_add(1, Ordering::Relaxed);
                        break;
                    }
                }
            }
            Link3::Blocks { req_tx, reqs, .. } => {
                // Never more than the ring takes: a reserved slot whose request is lost would
                // stay pending for good.
                let room = req_tx.slots().min(MAX_REQUESTS3_PER_TICK);
                let before = st.columns_evicted;
                if room > 0 && self.sim.requests_into(room, reqs).is_ok() {
                    for r in reqs.iter() {
                        // Cannot fail: at most `room` requests.
                        let _ = req_tx.push(*r);
                        requested_any = true;
                    }
                }
                let evicted = self.sim.stats().columns_evicted - before;
                if evicted > 0 {
                    counters.columns_evicted.fetch_add(evicted, Ordering::Relaxed);
                }
            }
        }
        requested_any
    }
}
