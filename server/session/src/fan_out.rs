//! Off the real-time thread: the column worker (compliance columns ahead of the tip), the
//! fan-out (tick records to histograms, the record sink, every-tick and latest-value observers,
//! and the displacement field at frame rate), and the device channel's watcher. These threads may
//! log; the real-time thread never does.
//!
//! The fan-out and the column worker do not poll: when their queue is empty they park, and the
//! real-time thread rings their doorbell after pushing a record or a column request
//! ([`crate::doorbell`]), so a record reaches the observers as soon as the tick that made it ends.
//! Their park timeouts ([`FAN_OUT_TIMEOUT`], [`COLUMN_WORKER_TIMEOUT`]) are safety nets that also
//! bound how long a stop goes unnoticed (a close rings them anyway). The remaining polls: the
//! column worker waits 200 µs when the delivery queue is full (the real-time thread drains it
//! every tick, so it is full only if the ticks stall), and the device channel's watcher checks
//! the file every [`needlesim_channel::shm::WATCH_PERIOD`] (system calls the real-time thread does
//! not make), looking at the stop flag every 10 ms.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use needlesim_core::compliance::TissueModel;

use crate::counters::SessionCounters;
use crate::doorbell::{Doorbell, Woken};
use crate::record::TickRecord;

/// The fan-out's safety net: with no record (and no ring) for this long it wakes anyway, counted
/// in [`SessionCounters::fanout_timeouts`] (a stalled or faulted session, or a lost wake-up).
pub const FAN_OUT_TIMEOUT: Duration = Duration::from_millis(20);
/// The column worker's safety net: with no request (and no ring) for this long it wakes anyway,
/// frees the column boxes the real-time thread handed back, and looks at the stop flag.
pub const COLUMN_WORKER_TIMEOUT: Duration = Duration::from_millis(50);

/// Where the fan-out hands every tick record the real-time thread published, in tick order
/// (a recording, in the service layer: the session knows no wire format). Implemented outside this
/// crate; attached with [`crate::Session::attach_sink_from_io`].
pub trait RecordSink: Send + 'static {
    /// Takes one record, on the fan-out thread. Must not block: queue the work and return (a
    /// slow sink delays every observer, never the real-time thread).
    fn write_from_fanout(&mut self, rec: &TickRecord);

    /// The sink as `Any`, so that its owner can find its own type again (e.g. to read a
    /// recording's name).
    fn as_any(&self) -> &dyn std::any::Any;

    /// The sink as `Box<dyn Any>`, so that its owner can take its own type back (e.g. to finish
    /// a recording).
    fn into_any(self: Box<Self>) -> Box<dyn std::any::Any + Send>;
}

/// The sink slot shared by the IO side (attach, detach) and the fan-out (write).
pub(crate) type SinkSlot = Arc<Mutex<Option<Box<dyn RecordSink>>>>;

pub(crate) struct Histograms {
    pub(crate) compute_ns: hdrhistogram::Histogram<u64>,
    pub(crate) lateness_ns: hdrhistogram::Histogram<u64>,
}

/// A displacement field of every node, computed by the fan-out at frame rate.
#[derive(Debug, Clone, Default)]
pub struct Field {
    pub tick: u64,
    pub displacement_m: Vec<f64>,
}

/// Set on a node index in the worker's request ring: not a request but a notice that the
/// real-time cache evicted the node's columns, so the renderer's copy goes too. Mesh nodes are
/// far fewer than 2³¹ (`MeshLimits`).
pub(crate) const EVICTED_TAG: u32 = 1 << 31;
/// Set on a node index in the worker's request ring: compute the node's columns for the
/// renderer only (a contact's node, whose share of the field the fan-out draws); without it the
/// columns go to the real-time thread only. Only contacts' columns are kept for rendering, so
/// the renderer holds a few dozen nodes' columns, not the prefetch's.
pub(crate) const RENDER_TAG: u32 = 1 << 30;

/// Computes compliance columns off the real-time thread.
pub(crate) struct ColumnWorker {
    pub(crate) tissue: Arc<TissueModel>,
    pub(crate) req_rx: rtrb::Consumer<u32>,
    pub(crate) col_tx: rtrb::Producer<(u32, Box<[f64]>)>,
    pub(crate) ret_rx: rtrb::Consumer<Box<[f64]>>,
    pub(crate) render_columns: Arc<Mutex<std::collections::HashMap<u32, Arc<[f64]>>>>,
    /// Rung by the real-time thread after it pushes requests.
    pub(crate) bell: Arc<Doorbell>,
    pub(crate) stop: Arc<AtomicBool>,
}

impl ColumnWorker {
    pub(crate) fn run(mut self) {
        let mut scratch = self.tissue.column_scratch();
        let len = 2 * self.tissue.n_dofs();
        while !self.stop.load(Ordering::Relaxed) {
            while self.ret_rx.pop().is_ok() {}
            let Ok(node) = self.req_rx.pop() else {
                self.bell.wait_from_worker(COLUMN_WORKER_TIMEOUT, || !self.req_rx.is_empty() || self.stop.load(Ordering::Relaxed));
                continue;
            };
            if node & EVICTED_TAG != 0 {
                self.render_columns.lock().expect("render columns lock").remove(&(node & !EVICTED_TAG));
                continue;
            }
            let for_render = node & RENDER_TAG != 0;
            let node = node & !RENDER_TAG;
            if for_render && self.render_columns.lock().expect("render columns lock").contains_key(&node) {
                continue;
            }
            let mut cols = vec![0.0; len].into_boxed_slice();
            if let Err(e) = self.tissue.compliance_columns_into(node as usize, &mut cols, &mut scratch) {
                tracing::error!("column of node {node}: {e}");
                continue;
            }
            if for_render {
                self.render_columns.lock().expect("render columns lock").insert(node, Arc::from(cols));
                continue;
            }
            let mut item = (node, cols);
            loop {
                match self.col_tx.push(item) {
                    Ok(()) => break,
                    Err(rtrb::PushError::Full(back)) => {
                        if self.stop.load(Ordering::Relaxed) {
                            return;
                        }
                        item = back;
                        std::thread::sleep(Duration::from_micros(200));
                    }
                }
            }
        }
    }
}

/// The 3D session's compliance worker: columns of requested nodes, or node blocks
/// ([`needlesim_core::sim3::Sim3BlockWorker`]), per the simulation's store. Answers in request
/// order; waits (200 µs polls) when the delivery ring is full rather than drop an answer.
pub(crate) enum Worker3 {
    Columns {
        model: Arc<needlesim_core::d3::TetTissueModel>,
        req_rx: rtrb::Consumer<u32>,
        col_tx: rtrb::Producer<(u32, Box<[f64]>)>,
        ret_rx: rtrb::Consumer<Box<[f64]>>,
    },
    Blocks {
        worker: Box<needlesim_core::sim3::Sim3BlockWorker>,
        req_rx: rtrb::Consumer<needlesim_core::sim3::BlockRequest>,
        pay_tx: rtrb::Producer<Box<needlesim_core::sim3::BlockPayload>>,
        ret_rx: rtrb::Consumer<Box<needlesim_core::sim3::BlockPayload>>,
    },
}

/// Pushes `item` into `tx`, waiting while the ring is full; false when stopped meanwhile.
fn push_waiting<T>(tx: &mut rtrb::Producer<T>, mut item: T, stop: &AtomicBool) -> bool {
    loop {
        match tx.push(item) {
            Ok(()) => return true,
            Err(rtrb::PushError::Full(back)) => {
                if stop.load(Ordering::Relaxed) {
                    return false;
                }
                item = back;
                std::thread::sleep(Duration::from_micros(200));
            }
        }
    }
}

impl Worker3 {
    pub(crate) fn run(self, bell: Arc<Doorbell>, stop: Arc<AtomicBool>) {
        match self {
            Worker3::Columns { model, mut req_rx, mut col_tx, mut ret_rx } => {
                let mut scratch = model.column_scratch();
                let len = 3 * model.n_dofs();
                let mut spare: Vec<Box<[f64]>> = Vec::new();
                while !stop.load(Ordering::Relaxed) {
                    while let Ok(b) = ret_rx.pop() {
                        if spare.len() < 8 {
                            spare.push(b);
                        }
                    }
                    let Ok(node) = req_rx.pop() else {
                        bell.wait_from_worker(COLUMN_WORKER_TIMEOUT, || !req_rx.is_empty() || stop.load(Ordering::Relaxed));
                        continue;
                    };
                    let mut cols = spare.pop().unwrap_or_else(|| vec![0.0; len].into_boxed_slice());
                    if let Err(e) = model.compliance_columns_into(node as usize, &mut cols, &mut scratch) {
                        // Answered all the same, with nothing (refused there, counted as a
                        // step error): the real-time side counts its requests in flight.
                        tracing::error!("3D columns of node {node}: {e}");
                        cols = Box::default();
                    }
                    if !push_waiting(&mut col_tx, (node, cols), &stop) {
                        return;
                    }
                }
            }
            Worker3::Blocks { mut worker, mut req_rx, mut pay_tx, mut ret_rx } => {
                let mut batch = Vec::with_capacity(needlesim_core::sim3::ROWS_BATCH);
                let mut spare: Vec<Box<needlesim_core::sim3::BlockPayload>> = Vec::new();
                while !stop.load(Ordering::Relaxed) {
                    while let Ok(b) = ret_rx.pop() {
                        spare.push(b);
                    }
                    batch.clear();
                    while batch.len() < needlesim_core::sim3::ROWS_BATCH
                        && let Ok(r) = req_rx.pop()
                    {
                        batch.push(r);
                    }
                    if batch.is_empty() {
                        bell.wait_from_worker(COLUMN_WORKER_TIMEOUT, || !req_rx.is_empty() || stop.load(Ordering::Relaxed));
                        continue;
                    }
                    let payloads = match worker.compute(&batch) {
                        Ok(p) => p,
                        Err(e) => {
                            // Not expected (the simulation requests its own nodes and slots);
                            // those nodes stay pending: their captures wait.
                            tracing::error!("3D node blocks: {e}");
                            continue;
                        }
                    };
                    for p in payloads {
                        let mut b = spare.pop().unwrap_or_else(|| Box::new(p.clone()));
                        b.node_idx = p.node_idx;
                        b.slot = p.slot;
                        b.blocks.clone_from(&p.blocks);
                        if !push_waiting(&mut pay_tx, b, &stop) {
                            return;
                        }
                    }
                }
            }
        }
    }
}

/// Distributes tick records off the real-time thread.
pub(crate) struct FanOut {
    pub(crate) rec_rx: rtrb::Consumer<TickRecord>,
    pub(crate) all_tx: tokio::sync::broadcast::Sender<Arc<TickRecord>>,
    pub(crate) latest_tx: tokio::sync::watch::Sender<Arc<TickRecord>>,
    pub(crate) field_tx: tokio::sync::watch::Sender<Arc<Field>>,
    pub(crate) field_subscribers: Arc<AtomicU64>,
    pub(crate) field_maker: FieldMaker,
    pub(crate) histograms: Arc<Mutex<Histograms>>,
    pub(crate) sink: SinkSlot,
    /// The second sink (`Session::attach_tap_from_io`), handed each record after `sink`.
    pub(crate) tap: SinkSlot,
    pub(crate) counters: Arc<SessionCounters>,
    /// The real-time thread's one report on its scheduling priority, logged here (the real-time
    /// thread does not log).
    pub(crate) rt_priority_rx: std::sync::mpsc::Receiver<Result<i32, String>>,
    pub(crate) session_id: String,
    /// Rung by the real-time thread after it pushes a record.
    pub(crate) bell: Arc<Doorbell>,
    pub(crate) stop: Arc<AtomicBool>,
}

/// How the fan-out computes a displacement field.
pub(crate) enum FieldMaker {
    /// 2D: every node's, from the contacts' columns the column worker keeps for rendering.
    Two { render_columns: Arc<Mutex<std::collections::HashMap<u32, Arc<[f64]>>>>, n_dofs: usize },
    /// 3D: the boundary surface's nodes' ([`crate::surface`]); computed on a thread of its own
    /// (its column solves take milliseconds: they must not hold up the records), which the
    /// fan-out starts and hands the latest record (a full hand-over is skipped).
    Three(crate::surface::SurfaceField3),
    /// The running 3D field thread's inbox.
    ThreeThread(std::sync::mpsc::SyncSender<Arc<TickRecord>>),
}

/// The nice value of a 3D session's surface-field thread (the worker and the fan-out keep 0).
const FIELD_THREAD_NICE: i32 = 10;

/// How often the fan-out computes the displacement field while someone wants it.
const FIELD_PERIOD: Duration = Duration::from_millis(8);

impl FanOut {
    pub(crate) fn run(mut self) {
        if let FieldMaker::Three(_) = &self.field_maker {
            let (tx, rx) = std::sync::mpsc::sync_channel::<Arc<TickRecord>>(1);
            let FieldMaker::Three(mut maker) = std::mem::replace(&mut self.field_maker, FieldMaker::ThreeThread(tx)) else {
                unreachable!()
            };
            let field_tx = self.field_tx.clone();
            let spawned = std::thread::Builder::new().name(format!("field-{}", self.session_id)).spawn(move || {
                // The surface picture may lag; the compliance worker's columns, which captures
                // wait for, must not: under contention this thread yields to it (a loaded
                // machine otherwise let the field starve the worker and the needle passed
                // through the tissue without a capture). A refusal only costs that preference.
                let _ = needlesim_channel::rt::lower_thread_priority(FIELD_THREAD_NICE);
                // Ends when the fan-out drops its sender.
                while let Ok(rec) = rx.recv() {
                    let field = Field { tick: rec.tick, displacement_m: maker.field(&rec.d3) };
                    field_tx.send_replace(Arc::new(field));
                }
            });
            if let Err(e) = spawned {
                tracing::error!(session = %self.session_id, "cannot start the surface field thread: {e}; no surface displacements");
            }
        }
        let mut last_field = Instant::now() - FIELD_PERIOD;
        let mut field_tick = None;
        let mut latest: Option<Arc<TickRecord>> = None;
        let mut stiffness_errors_logged = 0;
        while !self.stop.load(Ordering::Relaxed) {
            self.log_rt_reports(&mut stiffness_errors_logged);
            let mut any = false;
            while let Ok(rec) = self.rec_rx.pop() {
                any = true;
                {
                    let mut h = self.histograms.lock().expect("histogram lock");
                    let _ = h.compute_ns.record(rec.compute_ns.max(1));
                    let _ = h.lateness_ns.record(rec.lateness_ns.max(1));
                }
                let rec = Arc::new(rec);
                if let Some(sink) = self.sink.lock().expect("record sink lock").as_mut() {
                    sink.write_from_fanout(&rec);
                }
                if let Some(tap) = self.tap.lock().expect("record tap lock").as_mut() {
                    tap.write_from_fanout(&rec);
                }
                let _ = self.all_tx.send(rec.clone());
                latest = Some(rec);
            }
            if let Some(rec) = &latest {
                if any {
                    self.latest_tx.send_replace(rec.clone());
                }
                // At most every FIELD_PERIOD, for a record whose field is not out yet (a field
                // subscriber of a session that stopped stepping gets it at the next timeout).
                if self.field_subscribers.load(Ordering::Relaxed) > 0
                    && last_field.elapsed() >= FIELD_PERIOD
                    && field_tick != Some(rec.tick)
                {
                    last_field = Instant::now();
                    field_tick = Some(rec.tick);
                    match &mut self.field_maker {
                        FieldMaker::Two { render_columns, n_dofs } => {
                            let field = field_for(rec, render_columns, *n_dofs);
                            self.field_tx.send_replace(Arc::new(field));
                        }
                        FieldMaker::ThreeThread(tx) => {
                            // Busy: this record is skipped, the thread takes a later one.
                            let _ = tx.try_send(rec.clone());
                        }
                        FieldMaker::Three(_) => {}
                    }
                }
            }
            if !any
                && self.bell.wait_from_worker(FAN_OUT_TIMEOUT, || !self.rec_rx.is_empty() || self.stop.load(Ordering::Relaxed))
                    == Woken::TimedOut
            {
                self.counters.fanout_timeouts.fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    /// Puts into the log what the real-time thread only counted or reported through a queue: its
    /// scheduling priority (once), failures of the stiffness Jacobian (at counts 1, 2, 4, …).
    fn log_rt_reports(&self, stiffness_errors_logged: &mut u64) {
        match self.rt_priority_rx.try_recv() {
            Ok(Ok(priority)) => tracing::debug!(session = %self.session_id, priority, "real-time thread runs with SCHED_FIFO"),
            Ok(Err(why)) => tracing::warn!(
                session = %self.session_id,
                "the real-time thread runs without real-time priority ({why}); ticks may be late under load"
            ),
            Err(_) => {}
        }
        let errors = self.counters.stiffness_errors.load(Ordering::Relaxed);
        if errors > *stiffness_errors_logged && errors.is_power_of_two() {
            tracing::error!(session = %self.session_id, errors, "the stiffness Jacobian failed; the last one is kept");
        }
        *stiffness_errors_logged = errors;
    }
}

/// $u = \sum_w C_{:,w} f_w$ from the columns the worker computed (2D).
fn field_for(rec: &TickRecord, render_columns: &Mutex<std::collections::HashMap<u32, Arc<[f64]>>>, n_dofs: usize) -> Field {
    let mut u = vec![0.0; n_dofs];
    let cols = render_columns.lock().expect("render columns lock");
    for nn in rec.nodes() {
        for (node, weight) in TickRecord::contact_terms(nn) {
            let Some(c) = cols.get(&node) else { continue };
            for comp in 0..2 {
                let f = weight * nn.force_n[comp];
                if f != 0.0 {
                    for (o, v) in u.iter_mut().zip(&c[comp * n_dofs..(comp + 1) * n_dofs]) {
                        *o += v * f;
                    }
                }
            }
        }
    }
    Field { tick: rec.tick, displacement_m: u }
}

/// The session's device-channel watcher (a non-real-time thread): checks the channel's file every
/// [`needlesim_channel::shm::WATCH_PERIOD`] (deleted, replaced, resized: system calls the real-time
/// thread does not make), which the real-time thread then sees as a broken channel; logs the cause
/// once, whoever found it.
pub(crate) fn watch_device_channel(watch: needlesim_channel::shm::ChannelWatch, stop: Arc<AtomicBool>) {
    const STEP: Duration = Duration::from_millis(10);
    let mut since_check = Duration::ZERO;
    while !stop.load(Ordering::Relaxed) {
        std::thread::sleep(STEP);
        since_check += STEP;
        if since_check < needlesim_channel::shm::WATCH_PERIOD {
            continue;
        }
        since_check = Duration::ZERO;
        if let Err(why) = watch.check_file() {
            tracing::warn!(
                channel = %watch.path().display(),
                "device channel broken: {why}; the device is stale for the rest of the session (the needle is held, other clients may still drive it)"
            );
            return;
        }
    }
}
