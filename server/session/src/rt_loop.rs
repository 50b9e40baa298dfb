//! The real-time loop: one tick per period on its own thread — columns in, the pose (from a client
//! or the device channel), bevel flips, the step, the stiffness Jacobian, the wrench to the device,
//! column requests, the record out. Only non-blocking operations on bounded queues and
//! latest-value slots; no allocation once warmed up, no I/O, no lock, no logging: what goes wrong
//! becomes a counter or the fault state in [`SessionCounters`], read by the fan-out and the IO side.
//!
//! Each tick starts on time to within the clock read: the schedule sleeps until the spin margin
//! before the deadline and spins the rest (`needlesim_channel::schedule`; the margin is
//! [`crate::set_spin_margin`]'s, 0 to sleep to the deadline). The tick phase is published on the
//! device channel before the first tick, so that the bridge writes each pose just before the tick
//! that uses it, and the force says which device pose it answers (`ServerForce::pose_counter`):
//! a pose reaches the device as a force within the same tick. The fan-out and the column worker
//! park when idle; the thread rings their doorbells after pushing them work
//! ([`crate::doorbell`]: no system call unless the thread is parked), and counts the wakes.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use needlesim_core::BasePose;
use needlesim_core::sim::{SimError, Simulation};

use crate::counters::SessionCounters;
use crate::doorbell::Doorbell;
use crate::fan_out::{EVICTED_TAG, RENDER_TAG};
use crate::record::{
    DEVICE_STALE_TICKS, MAX_CONSECUTIVE_STEP_ERRORS, MAX_RECORD_NODES, PoseCommand, STIFFNESS_EVERY_TICKS, SessionFault, TickRecord,
};

thread_local! {
    /// True on a session's real-time thread while it computes a tick (after its first ticks),
    /// so that a counting allocator in a test can prove that ticks allocate nothing.
    pub static IN_TICK: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Ticks after which the real-time thread counts as warmed up.
pub const WARM_UP_TICKS: u64 = 200;

/// A node's columns were asked of the worker for the real-time cache.
const REQUESTED_FOR_CACHE: u8 = 1;
/// A node's columns were asked of the worker for the renderer (the node is a contact's).
const REQUESTED_FOR_RENDER: u8 = 2;

/// The real-time loop's state.
pub(crate) struct RtLoop {
    pub(crate) sim: Simulation,
    pub(crate) period: Duration,
    pub(crate) pose_out: triple_buffer::Output<PoseCommand>,
    pub(crate) rec_tx: rtrb::Producer<TickRecord>,
    pub(crate) req_tx: rtrb::Producer<u32>,
    pub(crate) col_rx: rtrb::Consumer<(u32, Box<[f64]>)>,
    pub(crate) ret_tx: rtrb::Producer<Box<[f64]>>,
    /// Per node: [`REQUESTED_FOR_CACHE`] and/or [`REQUESTED_FOR_RENDER`], until evicted.
    pub(crate) requested: Vec<u8>,
    pub(crate) counters: Arc<SessionCounters>,
    pub(crate) stop: Arc<AtomicBool>,
    pub(crate) record: Box<TickRecord>,
    pub(crate) rt_priority: i32,
    /// Sleep until this long before each deadline, then spin (zero: sleep to the deadline).
    pub(crate) spin_margin: Duration,
    /// Rung after a record is pushed (the fan-out parks when the ring is empty).
    pub(crate) fanout_bell: Arc<Doorbell>,
    /// Rung after column requests are pushed (the column worker parks when it has none).
    pub(crate) column_bell: Arc<Doorbell>,
    /// The counter of the device pose the current pose came from (0: not from the device).
    pub(crate) device_pose_counter: u64,
    /// The server end of the device channel, if any.
    pub(crate) device: Option<needlesim_channel::shm::ServerEnd>,
    /// A device pose has been received at least once.
    pub(crate) device_seen: bool,
    /// The device's buttons at its previous fresh pose (None before the first).
    pub(crate) last_buttons: Option<u32>,
    pub(crate) stiffness: [f64; 9],
    /// Set when a step failed: no more steps, zero force, the needle held.
    pub(crate) fault: Option<SessionFault>,
    /// Step failures (other than a divergence) in a row; [`MAX_CONSECUTIVE_STEP_ERRORS`] fault.
    pub(crate) consecutive_step_errors: u32,
    /// Where the thread reports, once, whether it got its real-time priority (the fan-out logs it).
    pub(crate) rt_priority_tx: std::sync::mpsc::SyncSender<Result<i32, String>>,
}

/// The device button (bit of `DevicePose::buttons`) that turns the needle 180° about its axis,
/// on each press (rising edge).
pub const FLIP_BEVEL_BUTTON: u32 = 1;

use needlesim_channel::rt::request_precise_timers;
pub use needlesim_channel::rt::request_realtime_priority;
use needlesim_channel::schedule::Schedule;

impl RtLoop {
    pub(crate) fn run(mut self) {
        // Reported, not logged: the fan-out puts it into the log.
        let priority = request_realtime_priority(self.rt_priority).map(|()| self.rt_priority);
        if priority.is_err() {
            // Without SCHED_FIFO a sleep may wake up to 50 µs late (the timer slack) on top of the
            // scheduler's delay; the spin margin absorbs what it can. Best effort.
            let _ = request_precise_timers();
        }
        let _ = self.rt_priority_tx.try_send(priority);
        // Drift-free: tick k at start + k·period (needlesim_channel::schedule), on CLOCK_MONOTONIC.
        let mut schedule = Schedule::start_now(self.period).with_spin_margin(self.spin_margin);
        if let Some(dev) = self.device.as_mut() {
            dev.publish_schedule_from_rt(schedule.start_time().as_nanos() as u64, self.period.as_nanos() as u64);
        }
        let mut pose = self.sim.pose();
        let mut last_seq = 0;
        let mut last_client_time = 0;
        while !self.stop.load(Ordering::Relaxed) {
            let wake = schedule.wait();
            if wake.spins > 0 {
                self.counters.spin_ns.fetch_add(wake.spun.as_nanos() as u64, Ordering::Relaxed);
            }
            self.tick_from_rt(&mut pose, &mut last_seq, &mut last_client_time, wake.lateness);
            // Behind by a period or more: the skipped ticks are missed deadlines; behind by less,
            // the next tick runs late at once, one missed deadline.
            let missed = schedule.catch_up().missed_deadlines();
            if missed > 0 {
                self.counters.missed_deadlines.fetch_add(missed, Ordering::Relaxed);
            }
        }
    }

    /// After the cache evicted `node`'s columns: it may be requested again, and the worker is
    /// told to drop the renderer's copy (a full ring is counted; the copy then stays until the
    /// node is computed again).
    fn forget_columns_from_rt(&mut self, node: usize) {
        self.requested[node] = 0;
        if self.req_tx.push(node as u32 | EVICTED_TAG).is_err() {
            self.counters.dropped_eviction_notices.fetch_add(1, Ordering::Relaxed);
        }
    }

    fn tick_from_rt(&mut self, pose: &mut BasePose, last_seq: &mut u64, last_client_time: &mut u64, lateness: Duration) {
        let warm = self.counters.ticks.load(Ordering::Relaxed) >= WARM_UP_TICKS;
        IN_TICK.with(|c| c.set(warm));
        self.compute_tick_from_rt(pose, last_seq, last_client_time, lateness);
        IN_TICK.with(|c| c.set(false));
    }

    fn compute_tick_from_rt(&mut self, pose: &mut BasePose, last_seq: &mut u64, last_client_time: &mut u64, lateness: Duration) {
        let t0 = Instant::now();
        // Columns delivered by the worker; the box not kept goes back to be freed there.
        while let Ok((node, cols)) = self.col_rx.pop() {
            let inserted = self.sim.insert_columns_owned(node as usize, cols);
            if let Some(spare) = inserted.spare
                && let Err(rtrb::PushError::Full(spare)) = self.ret_tx.push(spare)
            {
                drop(spare);
            }
            if let Some(evicted) = inserted.evicted {
                self.forget_columns_from_rt(evicted);
            }
        }
        // A pose written since the last tick is new, whatever its seq (a controller that takes
        // over may start counting again from where its predecessor was).
        let client_pose = self.pose_out.update();
        let cmd = *self.pose_out.output_buffer();
        if client_pose {
            *pose = cmd.pose;
            *last_seq = cmd.seq;
            *last_client_time = cmd.client_time_ns;
            self.device_pose_counter = 0;
        }
        // A device on the shared-memory channel drives the needle while it sends poses; when it
        // stops, the needle is held where it was and the device is marked stale.
        let mut device_stale = false;
        if let Some(dev) = self.device.as_mut() {
            let sample = dev.read_pose_from_rt();
            if sample.status == needlesim_channel::shm::ReadStatus::Broken {
                // The channel's file was changed under it: no device can reach this session any
                // more. Stale for good; hold the needle unless a client moves it.
                self.counters.device_channel_broken.store(1, Ordering::Relaxed);
                device_stale = true;
                if !client_pose {
                    *pose = self.sim.pose();
                    self.device_pose_counter = 0;
                }
            } else if sample.fresh()
                && let Some(p) = sample.value
            {
                // A 2D session takes the planar part of the 6-DOF pose (x, y, the twist about z).
                let [x_m, y_m, theta_rad] = p.to_planar();
                *pose = BasePose::new(x_m, y_m, theta_rad);
                self.device_pose_counter = p.counter;
                // Button 0 pressed (rising edge): flip the bevel.
                if let Some(prev) = self.last_buttons
                    && p.buttons & FLIP_BEVEL_BUTTON != 0
                    && prev & FLIP_BEVEL_BUTTON == 0
                {
                    self.counters.bevel_flips_requested.fetch_add(1, Ordering::Relaxed);
                }
                self.last_buttons = Some(p.buttons);
                self.device_seen = true;
                self.counters.device_poses.fetch_add(1, Ordering::Relaxed);
            } else if self.device_seen && sample.reads_since_fresh > DEVICE_STALE_TICKS {
                // Hold the needle where the device left it, unless a client moves it.
                device_stale = true;
                if !client_pose {
                    *pose = self.sim.pose();
                    self.device_pose_counter = 0;
                }
            }
            let was = self.counters.device_stale.swap(device_stale as u64, Ordering::Relaxed);
            if device_stale && was == 0 {
                self.counters.device_stale_events.fetch_add(1, Ordering::Relaxed);
            }
        }
        // Bevel flips asked for since the last tick (an even number cancels out).
        let requested = self.counters.bevel_flips_requested.load(Ordering::Relaxed);
        let applied = self.counters.bevel_flips_applied.load(Ordering::Relaxed);
        if requested > applied {
            if (requested - applied) % 2 == 1 {
                self.sim.flip_bevel();
            }
            self.counters.bevel_flips_applied.store(requested, Ordering::Relaxed);
        }
        let misses_before = self.sim.stats().column_misses;
        // A faulted session steps no more; the tick that faulted publishes one record saying so.
        let mut just_faulted = false;
        let stepped = if self.fault.is_some() {
            *pose = self.sim.pose();
            false
        } else {
            match self.sim.step(*pose) {
                Ok(out) => {
                    self.record.fill_from_rt(out);
                    self.consecutive_step_errors = 0;
                    true
                }
                Err(SimError::NonFinitePose { .. }) => {
                    self.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
                    *pose = self.sim.pose();
                    false
                }
                Err(e) if !matches!(e, SimError::Diverged { .. }) && self.consecutive_step_errors + 1 < MAX_CONSECUTIVE_STEP_ERRORS => {
                    // Another failure of the step (the solver or a compliance column) may pass
                    // with the next pose: hold the last pose, publish nothing, count it; only a
                    // run of them faults the session.
                    self.consecutive_step_errors += 1;
                    self.counters.step_errors.fetch_add(1, Ordering::Relaxed);
                    *pose = self.sim.pose();
                    false
                }
                Err(e) => {
                    // A diverged solve (or a failure that persists) cannot go on pushing: zero
                    // force, hold the last pose, and tell the others (the message is put into
                    // words off this thread).
                    if !matches!(e, SimError::Diverged { .. }) {
                        self.counters.step_errors.fetch_add(1, Ordering::Relaxed);
                    }
                    let fault = SessionFault::of(&e, self.sim.stats().ticks);
                    self.counters.set_fault_from_rt(&fault);
                    self.fault = Some(fault);
                    let r = &mut *self.record;
                    r.tick = fault.tick;
                    r.time_s = fault.tick as f64 / self.sim.params().tick_rate_hz;
                    r.force_n = [0.0; 2];
                    r.torque_nm = 0.0;
                    r.force_axial_n = 0.0;
                    r.force_lateral_n = 0.0;
                    r.fault = Some(fault);
                    r.base = self.sim.pose();
                    self.stiffness = [0.0; 9];
                    *pose = self.sim.pose();
                    just_faulted = true;
                    false
                }
            }
        };
        if stepped && self.counters.ticks.load(Ordering::Relaxed).is_multiple_of(STIFFNESS_EVERY_TICKS) {
            match self.sim.stiffness_jacobian() {
                Ok(j) => self.stiffness = [j[0][0], j[0][1], j[0][2], j[1][0], j[1][1], j[1][2], j[2][0], j[2][1], j[2][2]],
                // The last Jacobian is kept; counted here, logged by the fan-out.
                Err(_) => {
                    self.counters.stiffness_errors.fetch_add(1, Ordering::Relaxed);
                }
            }
        }
        self.record.stiffness = self.stiffness;
        self.record.device_stale = device_stale;
        if let Some(dev) = self.device.as_mut() {
            let r = &self.record;
            let mut force = needlesim_channel::shm::ServerForce {
                t_ns: needlesim_channel::shm::monotonic_ns(),
                tick: r.tick,
                state: if device_stale {
                    needlesim_channel::shm::ServerForce::STATE_DEVICE_STALE
                } else {
                    needlesim_channel::shm::ServerForce::STATE_OK
                },
                // The device pose this force answers (none when the tick did not step on it).
                pose_counter: if stepped { self.device_pose_counter } else { 0 },
                ..Default::default()
            };
            // The 2D wrench, stiffness and base embedded in the channel's 6-DOF fields.
            force.set_planar([r.force_n[0], r.force_n[1], r.torque_nm], &self.stiffness, [r.base.x_m, r.base.y_m, r.base.theta_rad]);
            dev.write_force_from_rt(&force);
        }
        for k in 0..self.sim.output().evicted.len() {
            let node = self.sim.output().evicted[k];
            self.forget_columns_from_rt(node);
        }
        let st = self.sim.stats();
        self.counters.column_misses.fetch_add(st.column_misses - misses_before, Ordering::Relaxed);
        self.counters.columns_evicted.store(st.columns_evicted, Ordering::Relaxed);
        self.counters.column_deferrals.store(st.column_deferrals, Ordering::Relaxed);
        self.counters.budget_exhausted_ticks.store(st.budget_exhausted_ticks, Ordering::Relaxed);
        self.counters.hybrid_checks.store(st.hybrid_checks, Ordering::Relaxed);
        self.counters.hybrid_rebuilds.store(st.hybrid_rebuilds, Ordering::Relaxed);
        self.counters.clamped_ticks.store(st.clamped_ticks, Ordering::Relaxed);
        if self.sim.output().needle_nodes.len() > MAX_RECORD_NODES {
            self.counters.records_truncated.fetch_add(1, Ordering::Relaxed);
        }
        // Ask the worker for the columns of approaching nodes (for this thread's cache), and for
        // the renderer's copies of the contacts' nodes (the fan-out renders their share of the
        // field; it keeps no copy of a column only the prefetch needed).
        let out = self.sim.output();
        let n_app = out.approaching.len();
        let n_req = n_app + 3 * out.needle_nodes.len();
        let mut requested_any = false;
        for k in 0..n_req {
            let out = self.sim.output();
            let (node, flag, tag) = if k < n_app {
                (out.approaching[k], REQUESTED_FOR_CACHE, 0)
            } else {
                let nn = &out.needle_nodes[(k - n_app) / 3];
                match nn.contact.nodes().get((k - n_app) % 3) {
                    Some(j) => (j.index(), REQUESTED_FOR_RENDER, RENDER_TAG),
                    None => continue,
                }
            };
            if self.requested[node] & flag == 0 {
                if self.req_tx.push(node as u32 | tag).is_ok() {
                    self.requested[node] |= flag;
                    requested_any = true;
                } else {
                    self.counters.dropped_column_requests.fetch_add(1, Ordering::Relaxed);
                    break;
                }
            }
        }
        if requested_any && self.column_bell.ring_from_rt() {
            self.counters.column_wakes.fetch_add(1, Ordering::Relaxed);
        }
        self.record.pose_seq = *last_seq;
        self.record.client_time_ns = *last_client_time;
        self.record.lateness_ns = lateness.as_nanos() as u64;
        self.record.compute_ns = t0.elapsed().as_nanos() as u64;
        // A tick that did not step publishes nothing (observers never see a tick twice).
        if stepped || just_faulted {
            if self.rec_tx.push(*self.record).is_err() {
                self.counters.dropped_records.fetch_add(1, Ordering::Relaxed);
            } else if self.fanout_bell.ring_from_rt() {
                self.counters.fanout_wakes.fetch_add(1, Ordering::Relaxed);
            }
        }
        self.counters.ticks.fetch_add(1, Ordering::Relaxed);
    }
}
