//! needlesim-session: a live session — one simulation stepped by its own real-time thread at a
//! fixed rate, a column worker that computes compliance columns ahead of the tip, and a fan-out
//! thread that turns tick records into statistics, observer channels, displacement fields and
//! whatever the service layer attaches as a [`RecordSink`] (a recording).
//!
//! ```text
//!  IO (gRPC tasks) ──pose──▶ [latest-value slot] ──▶ RT thread ──▶ [SPSC ring of TickRecord] ──▶ fan-out
//!                                                     │  ▲                                        │
//!                                   node requests ▼  │ columns (owned boxes)                    ├─▶ broadcast (every tick)
//!                                               column worker                                  ├─▶ watch (latest)
//!                                                                                              ├─▶ histograms, stats
//!                                                                                              └─▶ record sink, field
//! ```
//!
//! The real-time thread only uses non-blocking operations on bounded queues and latest-value
//! slots, allocates nothing per tick once warmed up, does no I/O and no logging, and counts every
//! message it drops. Its schedule is drift-free: tick $k$ is due at $t_0 + k\,\Delta t$; a tick
//! that ends after the next deadline is counted as missed and the schedule skips ahead rather than
//! bursting. Nothing here knows the wire protocol: conversions live in the service crate.

pub mod control_lease;
mod counters;
mod doorbell;
mod fan_out;
mod live_sim;
mod record;
mod rt_loop;
mod session;
pub mod spin;
pub mod surface;

pub use counters::{SessionCounters, StatsSnapshot};
pub use fan_out::{Field, RecordSink};
pub use record::{ContactRecord3, MAX_RECORD_CONTACTS3, MAX_RECORD_TARGETS3, PoseCommand3, Record3, TargetRecord3};
pub use record::{
    DEVICE_STALE_TICKS, FAULT_OTHER, FAULT_SOLVER, FAULT_TISSUE, MAX_CONSECUTIVE_STEP_ERRORS, MAX_RECORD_NODES, MAX_RECORD_SHAPE,
    MAX_RECORD_TARGETS, NodeRecord, PoseCommand, STIFFNESS_EVERY_TICKS, SessionFault, TargetRecord, TickRecord,
};
pub use rt_loop::{
    DEVICE_CATCH_UP_M_PER_S, DEVICE_CATCH_UP_RAD_PER_S, DEVICE_FORCE_RAMP_S, FLIP_BEVEL_BUTTON, IN_TICK, WARM_UP_TICKS,
    request_realtime_priority,
};
pub use session::{
    DEFAULT_SPIN_MARGIN, Session, SessionError, SessionTissue, WrongDimension, sessions_alive, set_rt_priority, set_spin_margin,
};
pub use surface::BoundarySurface;
