//! The IO side's handle on a running session: starting its threads, publishing poses and bevel
//! flips (`*_from_io`), statistics, the record sink, closing.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use needlesim_core::compliance::TissueModel;
use needlesim_core::sim::{SimError, Simulation};
use needlesim_scene::Scene;

use crate::counters::{SessionCounters, StatsSnapshot};
use crate::doorbell::Doorbell;
use crate::fan_out::{ColumnWorker, FanOut, Field, Histograms, RecordSink, watch_device_channel};
use crate::record::{COLUMN_QUEUE, PoseCommand, RECORD_RING, TickRecord};
use crate::rt_loop::RtLoop;

/// The IO side's handle on a running session.
pub struct Session {
    pub id: String,
    pub scene_name: String,
    pub controller_token: String,
    pub observer_token: String,
    pub tissue: Arc<TissueModel>,
    pub tick_rate_hz: f64,
    pub target_names: Vec<String>,
    pub created_unix_ms: u64,
    pub counters: Arc<SessionCounters>,
    /// The shared-memory device channel, if the session has one.
    pub device_channel_path: Option<std::path::PathBuf>,
    /// The needle has a bevel tip (a flip changes something).
    pub has_bevel: bool,
    pose_in: Mutex<triple_buffer::Input<PoseCommand>>,
    client_in_control: AtomicBool,
    /// Who may drive the session over gRPC now: one controller at a time (IO side only).
    pub control: Arc<crate::control_lease::ControlLease>,
    stop: Arc<AtomicBool>,
    /// Every tick record, for full-rate observers (lagging receivers learn how many they missed).
    pub all_ticks: tokio::sync::broadcast::Sender<Arc<TickRecord>>,
    /// The latest tick record, for rendering observers.
    pub latest: tokio::sync::watch::Receiver<Arc<TickRecord>>,
    /// The latest displacement field; computed only while `field_subscribers` > 0.
    pub field: tokio::sync::watch::Receiver<Arc<Field>>,
    pub field_subscribers: Arc<AtomicU64>,
    pub n_observers: Arc<AtomicU64>,
    histograms: Arc<Mutex<Histograms>>,
    /// Where the fan-out hands every record (a recording), when one is attached.
    sink: crate::fan_out::SinkSlot,
    /// The fan-out's and the column worker's doorbells, rung at close so that they stop at once.
    bells: [Arc<Doorbell>; 2],
    threads: Mutex<Vec<JoinHandle<()>>>,
}

/// The SCHED_FIFO priority real-time threads ask for (0: none); set once at start-up.
static RT_PRIORITY: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(40);

/// Sets the SCHED_FIFO priority new sessions' real-time threads ask for (0 disables it).
pub fn set_rt_priority(priority: i32) {
    RT_PRIORITY.store(priority, Ordering::Relaxed);
}

fn rt_priority() -> i32 {
    RT_PRIORITY.load(Ordering::Relaxed)
}

/// The default spin margin: 150 µs, 15 % of a core per session at 1 kHz.
pub const DEFAULT_SPIN_MARGIN: Duration = Duration::from_micros(150);

/// How long before each deadline new sessions' real-time threads stop sleeping and spin (ns).
static SPIN_MARGIN_NS: AtomicU64 = AtomicU64::new(DEFAULT_SPIN_MARGIN.as_nanos() as u64);

/// Sets how long before each tick's deadline new sessions' real-time threads stop sleeping and
/// busy-wait ([`DEFAULT_SPIN_MARGIN`]; zero sleeps to the deadline, spinning never). The margin
/// buys a wake-up on time (an OS sleep wakes tens of µs late, more under load) for its worth of a
/// core every tick: at 1 kHz, 150 µs is 15 % of a core per session, which a 2-core machine takes
/// from the clients and the fan-outs. Capped at the tick period.
pub fn set_spin_margin(margin: Duration) {
    SPIN_MARGIN_NS.store(margin.as_nanos().min(u64::MAX as u128) as u64, Ordering::Relaxed);
}

fn spin_margin() -> Duration {
    Duration::from_nanos(SPIN_MARGIN_NS.load(Ordering::Relaxed))
}

/// Errors starting a session.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    #[error("invalid tick rate {0} Hz: must be between 100 and 10000")]
    TickRate(f64),
    #[error(transparent)]
    Sim(#[from] SimError),
    #[error("cannot start a session thread: {0}")]
    Thread(std::io::Error),
    #[error("cannot create the device channel: {0}")]
    Device(#[from] needlesim_channel::shm::ShmError),
}

fn random_token() -> String {
    let mut b = [0u8; 16];
    getrandom::fill(&mut b).expect("the OS random source works");
    b.iter().map(|x| format!("{x:02x}")).collect()
}

impl Session {
    /// Starts the threads of a session for `scene` at `tick_rate_hz`, with a shared-memory device
    /// channel in `device_dir` when given (file `needlesim-<session id>`, mode 0600).
    pub fn start(scene: &Scene, tick_rate_hz: f64, device_dir: Option<&std::path::Path>) -> Result<Arc<Self>, SessionError> {
        if !(tick_rate_hz.is_finite() && (100.0..=10_000.0).contains(&tick_rate_hz)) {
            return Err(SessionError::TickRate(tick_rate_hz));
        }
        let mut params = scene.params.clone();
        params.tick_rate_hz = tick_rate_hz;
        let mut sim = Simulation::new(scene.tissue.clone(), params)?;
        let has_bevel = sim.bevel_side() != 0.0;
        sim.reserve_cached_nodes(4 * sim.params().max_needle_nodes + 256);
        let id = random_token()[..12].to_owned();
        let device = match device_dir {
            Some(dir) => {
                let path = dir.join(format!("needlesim-{id}"));
                Some(needlesim_channel::shm::DeviceChannel::create(&path)?)
            }
            None => None,
        };
        let device_channel_path = device.as_ref().map(|d| d.path().to_path_buf());
        let device_watch = device.as_ref().map(|d| d.watch());
        let counters = Arc::new(SessionCounters::default());
        let stop = Arc::new(AtomicBool::new(false));
        let initial = PoseCommand { pose: sim.pose(), seq: 0, client_time_ns: 0 };
        let (pose_in, pose_out) = triple_buffer::triple_buffer(&initial);
        let (rec_tx, rec_rx) = rtrb::RingBuffer::<TickRecord>::new(RECORD_RING);
        let (req_tx, req_rx) = rtrb::RingBuffer::<u32>::new(COLUMN_QUEUE);
        let (col_tx, col_rx) = rtrb::RingBuffer::<(u32, Box<[f64]>)>::new(COLUMN_QUEUE);
        let (ret_tx, ret_rx) = rtrb::RingBuffer::<Box<[f64]>>::new(COLUMN_QUEUE);
        // One second of buffering for every-tick observers; beyond it they are told what they missed.
        let (all_tx, _) = tokio::sync::broadcast::channel(1024);
        let (latest_tx, latest_rx) = tokio::sync::watch::channel(Arc::new(TickRecord::default()));
        let (field_tx, field_rx) = tokio::sync::watch::channel(Arc::new(Field::default()));
        let histograms = Arc::new(Mutex::new(Histograms {
            compute_ns: hdrhistogram::Histogram::new_with_bounds(1, 60_000_000_000, 3).expect("valid bounds"),
            lateness_ns: hdrhistogram::Histogram::new_with_bounds(1, 60_000_000_000, 3).expect("valid bounds"),
        }));
        let render_columns: Arc<Mutex<std::collections::HashMap<u32, Arc<[f64]>>>> = Arc::default();
        let field_subscribers = Arc::new(AtomicU64::new(0));
        let sink: crate::fan_out::SinkSlot = Arc::new(Mutex::new(None));
        let (rt_priority_tx, rt_priority_rx) = std::sync::mpsc::sync_channel(1);
        let fanout_bell = Arc::new(Doorbell::default());
        let column_bell = Arc::new(Doorbell::default());
        let mut threads = Vec::new();
        let period = Duration::from_secs_f64(1.0 / tick_rate_hz);

        let rt = RtLoop {
            sim,
            period,
            pose_out,
            rec_tx,
            req_tx,
            col_rx,
            ret_tx,
            requested: vec![0; scene.tissue.mesh().n_nodes()],
            counters: counters.clone(),
            stop: stop.clone(),
            record: Box::new(TickRecord::default()),
            rt_priority: rt_priority(),
            spin_margin: spin_margin().min(period),
            fanout_bell: fanout_bell.clone(),
            column_bell: column_bell.clone(),
            device_pose_counter: 0,
            device,
            device_seen: false,
            last_buttons: None,
            stiffness: [0.0; 9],
            fault: None,
            consecutive_step_errors: 0,
            rt_priority_tx,
        };
        threads.push(std::thread::Builder::new().name(format!("rt-{id}")).spawn(move || rt.run()).map_err(SessionError::Thread)?);
        if let Some(watch) = device_watch {
            let stop = stop.clone();
            let spawned = std::thread::Builder::new().name(format!("dev-{id}")).spawn(move || watch_device_channel(watch, stop));
            threads.push(spawned.map_err(SessionError::Thread)?);
        }
        let worker = ColumnWorker {
            tissue: scene.tissue.clone(),
            req_rx,
            col_tx,
            ret_rx,
            render_columns: render_columns.clone(),
            bell: column_bell.clone(),
            stop: stop.clone(),
        };
        threads.push(std::thread::Builder::new().name(format!("columns-{id}")).spawn(move || worker.run()).map_err(SessionError::Thread)?);
        let fan = FanOut {
            rec_rx,
            all_tx: all_tx.clone(),
            latest_tx,
            field_tx,
            field_subscribers: field_subscribers.clone(),
            render_columns,
            n_dofs: scene.tissue.n_dofs(),
            histograms: histograms.clone(),
            sink: sink.clone(),
            counters: counters.clone(),
            rt_priority_rx,
            session_id: id.clone(),
            bell: fanout_bell.clone(),
            stop: stop.clone(),
        };
        threads.push(std::thread::Builder::new().name(format!("fanout-{id}")).spawn(move || fan.run()).map_err(SessionError::Thread)?);
        let created_unix_ms = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_millis() as u64);
        Ok(Arc::new(Self {
            id,
            scene_name: scene.name.clone(),
            controller_token: random_token(),
            observer_token: random_token(),
            tissue: scene.tissue.clone(),
            tick_rate_hz,
            target_names: scene.target_names.clone(),
            created_unix_ms,
            counters,
            device_channel_path,
            has_bevel,
            pose_in: Mutex::new(pose_in),
            client_in_control: AtomicBool::new(false),
            control: crate::control_lease::ControlLease::new(),
            stop,
            all_ticks: all_tx,
            latest: latest_rx,
            field: field_rx,
            field_subscribers,
            n_observers: Arc::new(AtomicU64::new(0)),
            histograms,
            sink,
            bells: [fanout_bell, column_bell],
            threads: Mutex::new(threads),
        }))
    }

    /// Publishes a pose from a client (a controller, a browser, a device): the same as
    /// [`Session::write_pose_from_io`], and a scripted demo, if one plays, yields to the client.
    pub fn write_client_pose_from_io(&self, cmd: PoseCommand) {
        self.client_in_control.store(true, Ordering::Relaxed);
        self.write_pose_from_io(cmd);
    }

    /// Asks the real-time thread to turn the needle 180° about its axis at its next tick (no
    /// request is lost: the thread applies every one it has not applied yet). Returns the number
    /// of flips requested so far.
    pub fn request_bevel_flip_from_io(&self) -> u64 {
        self.counters.bevel_flips_requested.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// Whether a client has sent a pose (a scripted demo stops then).
    pub fn client_in_control(&self) -> bool {
        self.client_in_control.load(Ordering::Relaxed)
    }

    /// Publishes a pose for the next tick (latest value wins; an unconsumed one is counted as
    /// superseded). Called from IO tasks.
    pub fn write_pose_from_io(&self, cmd: PoseCommand) {
        let mut input = self.pose_in.lock().expect("pose slot lock");
        if input.consumed() {
            // the previous pose was read by a tick
        } else if self.counters.poses_written.load(Ordering::Relaxed) > 0 {
            self.counters.superseded_poses.fetch_add(1, Ordering::Relaxed);
        }
        input.write(cmd);
        self.counters.poses_written.fetch_add(1, Ordering::Relaxed);
    }

    /// The latest tick record.
    pub fn latest_record(&self) -> Arc<TickRecord> {
        self.latest.borrow().clone()
    }

    /// Percentiles and counters of the tick loop.
    pub fn stats(&self) -> StatsSnapshot {
        let h = self.histograms.lock().expect("histogram lock");
        let q = |hist: &hdrhistogram::Histogram<u64>, p: f64| hist.value_at_quantile(p) as f64 / 1e3;
        let c = &self.counters;
        StatsSnapshot {
            ticks: c.ticks.load(Ordering::Relaxed),
            compute_us: [q(&h.compute_ns, 0.5), q(&h.compute_ns, 0.99), q(&h.compute_ns, 0.999), h.compute_ns.max() as f64 / 1e3],
            lateness_us: [q(&h.lateness_ns, 0.5), q(&h.lateness_ns, 0.99), q(&h.lateness_ns, 0.999)],
            lateness_max_us: h.lateness_ns.max() as f64 / 1e3,
            missed_deadlines: c.missed_deadlines.load(Ordering::Relaxed),
            superseded_poses: c.superseded_poses.load(Ordering::Relaxed),
            dropped_records: c.dropped_records.load(Ordering::Relaxed),
            column_misses: c.column_misses.load(Ordering::Relaxed),
            column_deferrals: c.column_deferrals.load(Ordering::Relaxed),
            columns_evicted: c.columns_evicted.load(Ordering::Relaxed),
            budget_exhausted_ticks: c.budget_exhausted_ticks.load(Ordering::Relaxed),
            hybrid_checks: c.hybrid_checks.load(Ordering::Relaxed),
            hybrid_rebuilds: c.hybrid_rebuilds.load(Ordering::Relaxed),
            rejected_poses: c.rejected_poses.load(Ordering::Relaxed),
            clamped_ticks: c.clamped_ticks.load(Ordering::Relaxed),
            fanout_wakes: c.fanout_wakes.load(Ordering::Relaxed),
            fanout_timeouts: c.fanout_timeouts.load(Ordering::Relaxed),
            spin_ns: c.spin_ns.load(Ordering::Relaxed),
            faults: c.faults.load(Ordering::Relaxed),
            fault: c.fault().map(|f| f.message()),
        }
    }

    /// Resets the histograms (e.g. after warm-up, for a benchmark).
    pub fn reset_histograms(&self) {
        let mut h = self.histograms.lock().expect("histogram lock");
        h.compute_ns.reset();
        h.lateness_ns.reset();
    }

    /// Attaches the sink the fan-out hands every record to from the next record on; refused
    /// (the sink given back) while another is attached.
    pub fn attach_sink_from_io(&self, sink: Box<dyn RecordSink>) -> Result<(), Box<dyn RecordSink>> {
        let mut slot = self.sink.lock().expect("record sink lock");
        if slot.is_some() {
            return Err(sink);
        }
        *slot = Some(sink);
        Ok(())
    }

    /// Detaches the sink: the fan-out hands it no record after this returns.
    pub fn detach_sink_from_io(&self) -> Option<Box<dyn RecordSink>> {
        self.sink.lock().expect("record sink lock").take()
    }

    /// Runs `f` on the attached sink, if any (under the lock the fan-out writes through: keep it short).
    pub fn with_sink_from_io<R>(&self, f: impl FnOnce(Option<&dyn RecordSink>) -> R) -> R {
        f(self.sink.lock().expect("record sink lock").as_deref())
    }

    /// Stops the threads and waits for them, then drops the sink, if any (a recording finishes
    /// when dropped).
    pub fn close(&self) {
        self.stop.store(true, Ordering::Relaxed);
        for bell in &self.bells {
            bell.wake_from_io();
        }
        let threads: Vec<_> = std::mem::take(&mut *self.threads.lock().expect("threads lock"));
        for t in threads {
            let _ = t.join();
        }
        drop(self.detach_sink_from_io());
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        for bell in &self.bells {
            bell.wake_from_io();
        }
    }
}
