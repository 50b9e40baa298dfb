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
//!
//! **Who drives.** A client's pose (the triple buffer) is taken when it is new; a fresh device
//! pose, read in the same tick, wins over it. While the IO side has the device *suspended*
//! ([`crate::Session::suspend_device_from_io`]: a training session's instructor has control or the
//! exercise is paused; an atomic the thread loads once per tick) the thread still reads the channel
//! — so freshness, staleness and `device_poses` stay right — but applies no device pose (each
//! counted in `device_poses_suspended`), takes no bevel flip from its button, does not let a stale
//! device reset the pose (the instructor's), and writes the device a zero wrench and stiffness
//! (state OK, so the bridge renders zero at once instead of holding its last sample through its
//! watchdog). When the suspension is lifted the device's pose is usually far from the needle's
//! (the instructor moved it): each fresh device pose then moves the needle only
//! $v\,/\,f_{tick}$ towards it ([`DEVICE_CATCH_UP_M_PER_S`], [`DEVICE_CATCH_UP_RAD_PER_S`]: a
//! 50 mm gap takes 1 s) until a pose is within that step, counted in `device_catch_up_poses`; the
//! device still gets zero meanwhile, and then the wrench and stiffness return linearly from 0 to
//! full over [`DEVICE_FORCE_RAMP_S`]. (Without it the jump would be the core's per-tick clamp,
//! `max_base_step_m` = 2 mm a tick by default, 2 m/s, and the bridge's local model would
//! extrapolate the stiffness over the whole gap.)

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::counters::SessionCounters;
use crate::doorbell::Doorbell;
use crate::live_sim::{LiveSim, StepFail};
use crate::record::{DEVICE_STALE_TICKS, MAX_CONSECUTIVE_STEP_ERRORS, PoseCommand, STIFFNESS_EVERY_TICKS, SessionFault, TickRecord};

thread_local! {
    /// True on a session's real-time thread while it computes a tick (after its first ticks),
    /// so that a counting allocator in a test can prove that ticks allocate nothing.
    pub static IN_TICK: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Ticks after which the real-time thread counts as warmed up.
pub const WARM_UP_TICKS: u64 = 200;

/// The real-time loop's state.
/// The real-time loop's state, generic over the simulation ([`LiveSim`]: 2D or 3D).
pub(crate) struct RtLoop<S: LiveSim> {
    /// The simulation and its worker's queues.
    pub(crate) sim: S,
    pub(crate) period: Duration,
    pub(crate) pose_out: triple_buffer::Output<PoseCommand<S::Pose>>,
    pub(crate) rec_tx: rtrb::Producer<TickRecord>,
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
    /// Set by the IO side while the device must not drive ([`crate::Session::suspend_device_from_io`]);
    /// loaded once per tick.
    pub(crate) device_suspended: Arc<AtomicBool>,
    /// After a suspension, until the needle has reached the device's pose: each fresh device pose
    /// moves the needle at most the catch-up step towards it (module docs).
    pub(crate) device_catching_up: bool,
    /// The gain on the wrench and stiffness written to the device: 0 while suspended or catching
    /// up, then back to 1 in [`DEVICE_FORCE_RAMP_S`] (module docs).
    pub(crate) device_force_gain: f64,
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

/// After a suspension of the device, the needle follows it again at no more than this speed
/// until it has reached the device's pose (m/s; per fresh device pose, $v/f_{tick}$).
pub const DEVICE_CATCH_UP_M_PER_S: f64 = 0.05;
/// … and turns towards it at no more than this rate (rad/s).
pub const DEVICE_CATCH_UP_RAD_PER_S: f64 = 0.5;
/// Once caught up, the wrench and stiffness written to the device return to full in this long
/// (a linear ramp, s).
pub const DEVICE_FORCE_RAMP_S: f64 = 0.2;

use needlesim_channel::rt::request_precise_timers;
pub use needlesim_channel::rt::request_realtime_priority;
use needlesim_channel::schedule::Schedule;

impl<S: LiveSim> RtLoop<S> {
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

    fn tick_from_rt(&mut self, pose: &mut S::Pose, last_seq: &mut u64, last_client_time: &mut u64, lateness: Duration) {
        let warm = self.counters.ticks.load(Ordering::Relaxed) >= WARM_UP_TICKS;
        IN_TICK.with(|c| c.set(warm));
        self.compute_tick_from_rt(pose, last_seq, last_client_time, lateness);
        IN_TICK.with(|c| c.set(false));
    }

    fn compute_tick_from_rt(&mut self, pose: &mut S::Pose, last_seq: &mut u64, last_client_time: &mut u64, lateness: Duration) {
        let t0 = Instant::now();
        self.sim.absorb_from_rt(&self.counters);
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
        // Set by the IO side (a training session's instructor has control, or the exercise is
        // paused): the device's poses are read and counted but not applied.
        let suspended = self.device.is_some() && self.device_suspended.load(Ordering::Relaxed);
        if suspended {
            self.device_catching_up = true;
            // The force answers no device pose.
            self.device_pose_counter = 0;
        }
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
                if suspended {
                    self.counters.device_poses_suspended.fetch_add(1, Ordering::Relaxed);
                } else {
                    match self.sim.pose_from_device(&p) {
                        Some(q) if self.device_catching_up => {
                            // Back from a suspension: towards the device at the catch-up speed.
                            let rate = self.sim.tick_rate_hz();
                            let (next, reached) = self.sim.towards(&q, DEVICE_CATCH_UP_M_PER_S / rate, DEVICE_CATCH_UP_RAD_PER_S / rate);
                            *pose = next;
                            self.device_pose_counter = p.counter;
                            if reached {
                                self.device_catching_up = false;
                            } else {
                                self.counters.device_catch_up_poses.fetch_add(1, Ordering::Relaxed);
                            }
                        }
                        Some(q) => {
                            *pose = q;
                            self.device_pose_counter = p.counter;
                        }
                        None => {
                            self.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
                        }
                    }
                }
                // Button 0 pressed (rising edge): flip the bevel (not while suspended: the
                // trainee's flips are refused then).
                if !suspended
                    && let Some(prev) = self.last_buttons
                    && p.buttons & FLIP_BEVEL_BUTTON != 0
                    && prev & FLIP_BEVEL_BUTTON == 0
                {
                    self.counters.bevel_flips_requested.fetch_add(1, Ordering::Relaxed);
                }
                self.last_buttons = Some(p.buttons);
                self.device_seen = true;
                self.counters.device_poses.fetch_add(1, Ordering::Relaxed);
            } else if self.device_seen && sample.reads_since_fresh > DEVICE_STALE_TICKS {
                // Hold the needle where the device left it, unless a client moves it (while
                // suspended the device does not drive: the pose is the instructor's).
                device_stale = true;
                if !client_pose && !suspended {
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
                self.sim.flip_bevel_from_rt();
            }
            self.counters.bevel_flips_applied.store(requested, Ordering::Relaxed);
        }
        let misses_before = self.sim.column_misses();
        // A faulted session steps no more; the tick that faulted publishes one record saying so.
        let mut just_faulted = false;
        let stepped = if self.fault.is_some() {
            *pose = self.sim.pose();
            false
        } else {
            self.sim.set_spin_from_rt(self.counters.spin_word.load(Ordering::Relaxed));
            match self.sim.step_from_rt(*pose, &mut self.record) {
                Ok(()) => {
                    self.consecutive_step_errors = 0;
                    true
                }
                Err(StepFail::RejectedPose) => {
                    self.counters.rejected_poses.fetch_add(1, Ordering::Relaxed);
                    *pose = self.sim.pose();
                    false
                }
                Err(StepFail::Failed { diverged: false, .. }) if self.consecutive_step_errors + 1 < MAX_CONSECUTIVE_STEP_ERRORS => {
                    // Another failure of the step (the solver or a compliance column) may pass
                    // with the next pose: hold the last pose, publish nothing, count it; only a
                    // run of them faults the session.
                    self.consecutive_step_errors += 1;
                    self.counters.step_errors.fetch_add(1, Ordering::Relaxed);
                    *pose = self.sim.pose();
                    false
                }
                Err(StepFail::Failed { diverged, fault }) => {
                    // A diverged solve (or a failure that persists) cannot go on pushing: zero
                    // force, hold the last pose, and tell the others (the message is put into
                    // words off this thread).
                    if !diverged {
                        self.counters.step_errors.fetch_add(1, Ordering::Relaxed);
                    }
                    self.fail_from_rt(fault);
                    *pose = self.sim.pose();
                    just_faulted = true;
                    false
                }
            }
        };
        if stepped && self.counters.ticks.load(Ordering::Relaxed).is_multiple_of(STIFFNESS_EVERY_TICKS) {
            // On failure the last Jacobian is kept; counted here, logged by the fan-out.
            if self.sim.refresh_stiffness_from_rt().is_err() {
                self.counters.stiffness_errors.fetch_add(1, Ordering::Relaxed);
            }
        }
        self.sim.stiffness_into(&mut self.record);
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
            self.sim.fill_force(r, &mut force);
            // Zero while suspended or catching up (a hand that does not drive is not pushed),
            // then a ramp back to full: the wrench and the stiffness the bridge's local model
            // extrapolates with, scaled alike.
            self.device_force_gain = if suspended || self.device_catching_up {
                0.0
            } else {
                (self.device_force_gain + 1.0 / (DEVICE_FORCE_RAMP_S * self.sim.tick_rate_hz()).max(1.0)).min(1.0)
            };
            if self.device_force_gain < 1.0 {
                let g = self.device_force_gain;
                force.force_n = force.force_n.map(|v| g * v);
                force.torque_nm = force.torque_nm.map(|v| g * v);
                force.stiffness = force.stiffness.map(|row| row.map(|v| g * v));
            }
            dev.write_force_from_rt(&force);
        }
        let requested_any = self.sim.after_step_from_rt(&self.counters, misses_before);
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

    /// The session faults: the record says so, with zero force at the held pose.
    fn fail_from_rt(&mut self, fault: SessionFault) {
        self.counters.set_fault_from_rt(&fault);
        self.fault = Some(fault);
        let r = &mut *self.record;
        r.tick = fault.tick;
        r.time_s = fault.tick as f64 / self.sim.tick_rate_hz();
        r.force_n = [0.0; 2];
        r.torque_nm = 0.0;
        r.force_axial_n = 0.0;
        r.force_lateral_n = 0.0;
        r.fault = Some(fault);
        self.sim.hold_record_from_rt(r);
    }
}
