//! The counters a session's threads share (atomics: the real-time side takes no lock), and the
//! percentile summary the IO side reads.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::record::SessionFault;

/// Counters shared between the threads of a session (atomics: no locks on the real-time side).
#[derive(Debug, Default)]
pub struct SessionCounters {
    pub ticks: AtomicU64,
    pub missed_deadlines: AtomicU64,
    pub dropped_records: AtomicU64,
    pub dropped_column_requests: AtomicU64,
    /// Columns the real-time thread's cache evicted (unused nodes; `SimStats::columns_evicted`).
    pub columns_evicted: AtomicU64,
    /// `SimStats::column_deferrals` and `SimStats::budget_exhausted_ticks`, as of the last tick.
    pub column_deferrals: AtomicU64,
    pub budget_exhausted_ticks: AtomicU64,
    /// `SimStats::active_set_capped_ticks` and `SimStats::shape_capped_ticks` (2D), as of the
    /// last tick: ticks whose stick/slip iteration or flexible shape passes stopped at their cap.
    pub active_set_capped_ticks: AtomicU64,
    pub shape_capped_ticks: AtomicU64,
    /// 3D: `Sim3Stats::late_captures` and `Sim3Stats::pending_dropped`, as of the last tick.
    pub late_captures: AtomicU64,
    pub pending_captures_dropped: AtomicU64,
    /// `SimStats::hybrid_checks` and `SimStats::hybrid_rebuilds`, as of the last tick.
    pub hybrid_checks: AtomicU64,
    pub hybrid_rebuilds: AtomicU64,
    /// Eviction notices the real-time thread could not queue to the column worker (its ring was
    /// full): the renderer keeps that node's copy until the node is computed again.
    pub dropped_eviction_notices: AtomicU64,
    pub superseded_poses: AtomicU64,
    pub poses_written: AtomicU64,
    pub rejected_poses: AtomicU64,
    pub column_misses: AtomicU64,
    pub clamped_ticks: AtomicU64,
    pub records_truncated: AtomicU64,
    /// 1 while a device channel's bridge is stale (no fresh pose for [`DEVICE_STALE_TICKS`](crate::DEVICE_STALE_TICKS)).
    pub device_stale: AtomicU64,
    /// Times the device went stale.
    pub device_stale_events: AtomicU64,
    /// Fresh device poses read (taken, refused, or set aside while the device is suspended).
    pub device_poses: AtomicU64,
    /// Fresh device poses set aside because the device was suspended
    /// ([`Session::suspend_device_from_io`](crate::Session::suspend_device_from_io): a training
    /// session's instructor has control, or the exercise is paused).
    pub device_poses_suspended: AtomicU64,
    /// Fresh device poses, after a suspension, that moved the needle only part of the way towards
    /// the device (at most [`DEVICE_CATCH_UP_M_PER_S`](crate::DEVICE_CATCH_UP_M_PER_S) and
    /// [`DEVICE_CATCH_UP_RAD_PER_S`](crate::DEVICE_CATCH_UP_RAD_PER_S)): the catch-up's length.
    pub device_catch_up_poses: AtomicU64,
    /// 1 once the device channel is broken (its file was truncated, resized, overwritten, deleted
    /// or replaced: `needlesim_channel::shm::Broken`): the device stays stale for the rest of the session.
    pub device_channel_broken: AtomicU64,
    /// Bevel flips asked for (by clients and the device's button 0), and applied by the
    /// real-time thread.
    pub bevel_flips_requested: AtomicU64,
    pub bevel_flips_applied: AtomicU64,
    /// The duty-cycled spin a controller asked for (3D: [`crate::spin`]): one word the IO side
    /// writes and the real-time thread reads each tick ([`crate::spin::SpinCommand::to_word`]).
    pub spin_word: AtomicU64,
    /// Steps that failed other than by diverging (the solver or a compliance column): the tick
    /// held its pose and published nothing; [`MAX_CONSECUTIVE_STEP_ERRORS`](crate::MAX_CONSECUTIVE_STEP_ERRORS) in a row fault.
    pub step_errors: AtomicU64,
    /// Refreshes of the stiffness Jacobian that failed (the last one is kept; logged by the fan-out).
    pub stiffness_errors: AtomicU64,
    /// Times the real-time thread woke the parked fan-out after pushing a record (its doorbell).
    pub fanout_wakes: AtomicU64,
    /// Times the fan-out's park ended by its safety timeout instead (no record for that long: a
    /// stalled or faulted session, or a lost wake-up).
    pub fanout_timeouts: AtomicU64,
    /// Times the real-time thread woke the parked column worker after pushing column requests.
    pub column_wakes: AtomicU64,
    /// Time the real-time thread spent spinning before its deadlines, in all (ns): the CPU the
    /// spin margin costs.
    pub spin_ns: AtomicU64,
    /// Faults of the simulation (0 or 1: a faulted session stops stepping for good).
    pub faults: AtomicU64,
    /// The fault ([`SessionFault`]): its code (0: none; written last, with release ordering),
    /// tick, and value and bound as `f64` bits.
    pub fault_code: AtomicU64,
    pub fault_tick: AtomicU64,
    pub fault_value_bits: AtomicU64,
    pub fault_bound_bits: AtomicU64,
}

impl SessionCounters {
    /// The fault, if the session has one.
    pub fn fault(&self) -> Option<SessionFault> {
        let code = self.fault_code.load(Ordering::Acquire);
        (code != 0).then(|| SessionFault {
            tick: self.fault_tick.load(Ordering::Relaxed),
            code: code as u8,
            value: f64::from_bits(self.fault_value_bits.load(Ordering::Relaxed)),
            bound: f64::from_bits(self.fault_bound_bits.load(Ordering::Relaxed)),
        })
    }

    pub(crate) fn set_fault_from_rt(&self, f: &SessionFault) {
        self.fault_tick.store(f.tick, Ordering::Relaxed);
        self.fault_value_bits.store(f.value.to_bits(), Ordering::Relaxed);
        self.fault_bound_bits.store(f.bound.to_bits(), Ordering::Relaxed);
        self.fault_code.store(f.code as u64, Ordering::Release);
        self.faults.fetch_add(1, Ordering::Relaxed);
    }
}

/// Percentile summary of the tick loop, kept by the fan-out thread.
#[derive(Debug, Clone, Default)]
pub struct StatsSnapshot {
    pub ticks: u64,
    pub compute_us: [f64; 4],
    /// p50, p99, p99.9.
    pub lateness_us: [f64; 3],
    pub lateness_max_us: f64,
    pub missed_deadlines: u64,
    pub superseded_poses: u64,
    pub dropped_records: u64,
    pub column_misses: u64,
    pub column_deferrals: u64,
    pub columns_evicted: u64,
    pub budget_exhausted_ticks: u64,
    pub active_set_capped_ticks: u64,
    pub shape_capped_ticks: u64,
    pub late_captures: u64,
    pub pending_captures_dropped: u64,
    pub hybrid_checks: u64,
    pub hybrid_rebuilds: u64,
    pub rejected_poses: u64,
    pub clamped_ticks: u64,
    /// See [`SessionCounters::fanout_wakes`], [`SessionCounters::fanout_timeouts`], [`SessionCounters::spin_ns`].
    pub fanout_wakes: u64,
    pub fanout_timeouts: u64,
    pub spin_ns: u64,
    /// Faults (0 or 1) and the fault, in words.
    pub faults: u64,
    pub fault: Option<String>,
}
