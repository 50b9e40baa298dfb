//! The IO side's handle on a running session: starting its threads, publishing poses and bevel
//! flips (`*_from_io`), statistics, the record sink, closing.

use crate::spin::SpinState;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use needlesim_core::compliance::TissueModel;
use needlesim_core::d3::TetTissueModel;
use needlesim_core::sim::{SimError, Simulation};
use needlesim_core::sim3::{Sim3Params, SimError3, Simulation3, StoreKind3};
use needlesim_scene::Scene;

use crate::counters::{SessionCounters, StatsSnapshot};
use crate::doorbell::Doorbell;
use crate::fan_out::{ColumnWorker, FanOut, Field, FieldMaker, Histograms, RecordSink, Worker3, watch_device_channel};
use crate::live_sim::{Link3, Live2, Live3, LiveSim, MAX_REQUESTS3_PER_TICK};
use crate::record::{COLUMN_QUEUE, PoseCommand, PoseCommand3, RECORD_RING, TickRecord};
use crate::rt_loop::RtLoop;
use crate::surface::{BoundarySurface, SurfaceField3};

/// The tissue of a session: 2D or 3D.
#[derive(Clone)]
pub enum SessionTissue {
    Two(Arc<TissueModel>),
    /// A 3D tissue and its boundary surface (what observers draw).
    Three {
        model: Arc<TetTissueModel>,
        surface: Arc<BoundarySurface>,
    },
}

impl SessionTissue {
    /// The 2D tissue, if the session is 2D.
    pub fn two(&self) -> Option<&Arc<TissueModel>> {
        match self {
            Self::Two(t) => Some(t),
            Self::Three { .. } => None,
        }
    }
    /// 2 or 3.
    pub fn dimension(&self) -> u8 {
        match self {
            Self::Two(_) => 2,
            Self::Three { .. } => 3,
        }
    }
    /// Number of mesh nodes.
    pub fn n_nodes(&self) -> usize {
        match self {
            Self::Two(t) => t.mesh().n_nodes(),
            Self::Three { model, .. } => model.mesh().n_nodes(),
        }
    }
    /// Number of elements (triangles in 2D, tetrahedra in 3D).
    pub fn n_elements(&self) -> usize {
        match self {
            Self::Two(t) => t.mesh().n_triangles(),
            Self::Three { model, .. } => model.mesh().n_tets(),
        }
    }
}

/// The pose slot of a session, of its dimension.
enum PoseSlot {
    Two(Mutex<triple_buffer::Input<PoseCommand>>),
    Three(Mutex<triple_buffer::Input<PoseCommand3>>),
}

/// A pose of the wrong dimension for the session (a 2D pose to a 3D session or the reverse).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("a {given}D pose for a {session}D session")]
pub struct WrongDimension {
    pub given: u8,
    pub session: u8,
}

/// Starts a session's compliance worker thread (given its doorbell and the stop flag).
type SpawnWorker = Box<dyn FnOnce(Arc<Doorbell>, Arc<AtomicBool>) -> std::io::Result<JoinHandle<()>> + Send>;

/// What [`Session::launch`] needs besides the simulation.
struct Launch {
    id: String,
    scene_name: String,
    tissue: SessionTissue,
    tick_rate_hz: f64,
    target_names: Vec<String>,
    has_bevel: bool,
    device: Option<needlesim_channel::shm::ServerEnd>,
    /// Starts the compliance worker (its bell, the stop flag).
    worker: SpawnWorker,
    field_maker: FieldMaker,
}

/// The IO side's handle on a running session.
pub struct Session {
    pub id: String,
    pub scene_name: String,
    pub controller_token: String,
    pub observer_token: String,
    pub tissue: SessionTissue,
    pub tick_rate_hz: f64,
    pub target_names: Vec<String>,
    pub created_unix_ms: u64,
    pub counters: Arc<SessionCounters>,
    /// The shared-memory device channel, if the session has one.
    pub device_channel_path: Option<std::path::PathBuf>,
    /// The needle has a bevel tip (a flip changes something).
    pub has_bevel: bool,
    pose_in: PoseSlot,
    client_in_control: AtomicBool,
    /// While set the device does not drive (read by the real-time thread each tick).
    device_suspended: Arc<AtomicBool>,
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
    /// A second sink, the training layer's (issue 20: the live exercise's metrics), handed every
    /// record after `sink`, independent of it (a recording and an exercise go together).
    tap: crate::fan_out::SinkSlot,
    /// The fan-out's and the column worker's doorbells, rung at close so that they stop at once.
    bells: [Arc<Doorbell>; 2],
    threads: Mutex<Vec<JoinHandle<()>>>,
    /// Set (to `true`) first thing in [`Session::close`]: every stream of the session selects on
    /// it ([`Session::closed`]) and ends, dropping its `Arc<Session>` (issue 35, H1).
    closed: tokio::sync::watch::Sender<bool>,
}

/// `Session` objects alive in this process ([`sessions_alive`]).
static SESSIONS_ALIVE: AtomicU64 = AtomicU64::new(0);

/// How many `Session` objects are alive in this process: counted when one starts, uncounted when
/// the last `Arc` of it is dropped, so a closed session whose streams or tasks still hold it
/// (and with it its tissue, its solver's matrices) shows here (issue 35, H1; `/metrics`).
pub fn sessions_alive() -> u64 {
    SESSIONS_ALIVE.load(Ordering::Relaxed)
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
    #[error(transparent)]
    Sim3(#[from] SimError3),
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
            Some(dir) => Some(needlesim_channel::shm::DeviceChannel::create(dir.join(format!("needlesim-{id}")))?),
            None => None,
        };
        let (req_tx, req_rx) = rtrb::RingBuffer::<u32>::new(COLUMN_QUEUE);
        let (col_tx, col_rx) = rtrb::RingBuffer::<(u32, Box<[f64]>)>::new(COLUMN_QUEUE);
        let (ret_tx, ret_rx) = rtrb::RingBuffer::<Box<[f64]>>::new(COLUMN_QUEUE);
        let render_columns: Arc<Mutex<std::collections::HashMap<u32, Arc<[f64]>>>> = Arc::default();
        let tissue = scene.tissue.clone();
        let worker_render = render_columns.clone();
        let worker_id = id.clone();
        let worker = Box::new(move |bell: Arc<Doorbell>, stop: Arc<AtomicBool>| {
            let w = ColumnWorker { tissue, req_rx, col_tx, ret_rx, render_columns: worker_render, bell, stop };
            std::thread::Builder::new().name(format!("columns-{worker_id}")).spawn(move || w.run())
        });
        let live = Live2 { req_tx, col_rx, ret_tx, requested: vec![0; scene.tissue.mesh().n_nodes()], stiffness: [0.0; 9], sim };
        let launch = Launch {
            id,
            scene_name: scene.name.clone(),
            tissue: SessionTissue::Two(scene.tissue.clone()),
            tick_rate_hz,
            target_names: scene.target_names.clone(),
            has_bevel,
            device,
            worker,
            field_maker: FieldMaker::Two { render_columns, n_dofs: scene.tissue.n_dofs() },
        };
        Self::launch(live, launch, PoseSlot::Two)
    }

    /// Starts the threads of a 3D session: `params` for [`Simulation3::new`] (their tick rate is
    /// the session's, checked as in [`Session::start`]), `model` the tissue, `target_names` by
    /// the targets' name indices, a shared-memory device channel of layout dimension 3 in
    /// `device_dir` when given. The worker computes columns or node blocks per
    /// [`Sim3Params::store`] (resolved for the mesh).
    pub fn start3(
        scene_name: &str,
        model: Arc<TetTissueModel>,
        params: Sim3Params,
        target_names: Vec<String>,
        device_dir: Option<&std::path::Path>,
    ) -> Result<Arc<Self>, SessionError> {
        let tick_rate_hz = params.tick_rate_hz;
        if !(tick_rate_hz.is_finite() && (100.0..=10_000.0).contains(&tick_rate_hz)) {
            return Err(SessionError::TickRate(tick_rate_hz));
        }
        let mut radii_m = vec![0.0; target_names.len().max(params.targets.iter().map(|t| t.name_idx + 1).max().unwrap_or(0))];
        for t in &params.targets {
            radii_m[t.name_idx] = t.radius_m;
        }
        let n_nodes = model.mesh().n_nodes();
        let kind = params.store.resolve(n_nodes);
        let sim = Simulation3::new(model.clone(), params)?;
        let id = random_token()[..12].to_owned();
        let device = match device_dir {
            Some(dir) => Some(needlesim_channel::shm::DeviceChannel::create_with_dimension(
                dir.join(format!("needlesim-{id}")),
                needlesim_channel::shm::Dimension::Three,
            )?),
            None => None,
        };
        let worker_id = id.clone();
        let (link, worker3) = if kind == StoreKind3::NodeBlocks {
            let worker = Box::new(sim.block_worker()?);
            // Short rings: a payload holds a block per slot.
            let (req_tx, req_rx) = rtrb::RingBuffer::new(MAX_REQUESTS3_PER_TICK);
            let (pay_tx, pay_rx) = rtrb::RingBuffer::new(MAX_REQUESTS3_PER_TICK);
            let (ret_tx, ret_rx) = rtrb::RingBuffer::new(2 * MAX_REQUESTS3_PER_TICK);
            let reqs = Vec::with_capacity(MAX_REQUESTS3_PER_TICK);
            (Link3::Blocks { req_tx, pay_rx, ret_tx, reqs }, Worker3::Blocks { worker, req_rx, pay_tx, ret_rx })
        } else {
            let (req_tx, req_rx) = rtrb::RingBuffer::new(COLUMN_QUEUE);
            let (col_tx, col_rx) = rtrb::RingBuffer::new(MAX_REQUESTS3_PER_TICK);
            let (ret_tx, ret_rx) = rtrb::RingBuffer::new(2 * MAX_REQUESTS3_PER_TICK);
            (
                Link3::Columns { req_tx, col_rx, ret_tx, requested: vec![false; n_nodes], outstanding: 0 },
                Worker3::Columns { model: model.clone(), req_rx, col_tx, ret_rx },
            )
        };
        let worker = Box::new(move |bell: Arc<Doorbell>, stop: Arc<AtomicBool>| {
            std::thread::Builder::new().name(format!("blocks-{worker_id}")).spawn(move || worker3.run(bell, stop))
        });
        let surface = Arc::new(BoundarySurface::of(model.mesh()));
        let live = Live3 {
            sim,
            link,
            radii_m,
            stiffness: [[0.0; 6]; 6],
            refused_payloads: 0,
            spin_word: 0,
            spin: SpinState::default(),
            applied_roll_rad: 0.0,
        };
        let launch = Launch {
            id,
            scene_name: scene_name.to_owned(),
            tissue: SessionTissue::Three { model: model.clone(), surface: surface.clone() },
            tick_rate_hz,
            target_names,
            has_bevel: false,
            device,
            worker,
            field_maker: FieldMaker::Three(SurfaceField3::new(model, surface)),
        };
        Self::launch(live, launch, PoseSlot::Three)
    }

    /// Starts the real-time thread on `sim`, the device watcher, the worker and the fan-out.
    fn launch<S: LiveSim>(
        sim: S,
        l: Launch,
        slot: impl FnOnce(Mutex<triple_buffer::Input<PoseCommand<S::Pose>>>) -> PoseSlot,
    ) -> Result<Arc<Self>, SessionError> {
        let Launch { id, scene_name, tissue, tick_rate_hz, target_names, has_bevel, device, worker, field_maker } = l;
        let device_channel_path = device.as_ref().map(|d| d.path().to_path_buf());
        let device_watch = device.as_ref().map(|d| d.watch());
        let counters = Arc::new(SessionCounters::default());
        let stop = Arc::new(AtomicBool::new(false));
        let device_suspended = Arc::new(AtomicBool::new(false));
        let initial = PoseCommand { pose: sim.pose(), seq: 0, client_time_ns: 0 };
        let (pose_in, pose_out) = triple_buffer::triple_buffer(&initial);
        let (rec_tx, rec_rx) = rtrb::RingBuffer::<TickRecord>::new(RECORD_RING);
        // One second of buffering for every-tick observers; beyond it they are told what they missed.
        let (all_tx, _) = tokio::sync::broadcast::channel(1024);
        let (latest_tx, latest_rx) = tokio::sync::watch::channel(Arc::new(TickRecord::default()));
        let (field_tx, field_rx) = tokio::sync::watch::channel(Arc::new(Field::default()));
        let histograms = Arc::new(Mutex::new(Histograms {
            compute_ns: hdrhistogram::Histogram::new_with_bounds(1, 60_000_000_000, 3).expect("valid bounds"),
            lateness_ns: hdrhistogram::Histogram::new_with_bounds(1, 60_000_000_000, 3).expect("valid bounds"),
        }));
        let field_subscribers = Arc::new(AtomicU64::new(0));
        let sink: crate::fan_out::SinkSlot = Arc::new(Mutex::new(None));
        let tap: crate::fan_out::SinkSlot = Arc::new(Mutex::new(None));
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
            device_suspended: device_suspended.clone(),
            device_catching_up: false,
            device_force_gain: 1.0,
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
        threads.push(worker(column_bell.clone(), stop.clone()).map_err(SessionError::Thread)?);
        let fan = FanOut {
            rec_rx,
            all_tx: all_tx.clone(),
            latest_tx,
            field_tx,
            field_subscribers: field_subscribers.clone(),
            field_maker,
            histograms: histograms.clone(),
            sink: sink.clone(),
            tap: tap.clone(),
            counters: counters.clone(),
            rt_priority_rx,
            session_id: id.clone(),
            bell: fanout_bell.clone(),
            stop: stop.clone(),
        };
        threads.push(std::thread::Builder::new().name(format!("fanout-{id}")).spawn(move || fan.run()).map_err(SessionError::Thread)?);
        SESSIONS_ALIVE.fetch_add(1, Ordering::Relaxed);
        let created_unix_ms = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_millis() as u64);
        Ok(Arc::new(Self {
            id,
            scene_name,
            controller_token: random_token(),
            observer_token: random_token(),
            tissue,
            tick_rate_hz,
            target_names,
            created_unix_ms,
            counters,
            device_channel_path,
            has_bevel,
            pose_in: slot(Mutex::new(pose_in)),
            client_in_control: AtomicBool::new(false),
            device_suspended,
            control: crate::control_lease::ControlLease::new(),
            stop,
            all_ticks: all_tx,
            latest: latest_rx,
            field: field_rx,
            field_subscribers,
            n_observers: Arc::new(AtomicU64::new(0)),
            histograms,
            sink,
            tap,
            bells: [fanout_bell, column_bell],
            threads: Mutex::new(threads),
            closed: tokio::sync::watch::Sender::new(false),
        }))
    }

    /// Publishes a pose from a client (a controller, a browser, a device): the same as
    /// [`Session::write_pose_from_io`], and a scripted demo, if one plays, yields to the client.
    pub fn write_client_pose_from_io(&self, cmd: PoseCommand) {
        self.client_in_control.store(true, Ordering::Relaxed);
        self.write_pose_from_io(cmd);
    }

    /// Sets the duty-cycled spin (a 3D session's needle rolls about its own axis as it is
    /// inserted: [`crate::spin`]) from the real-time thread's next tick; a `duty_cycle` of 0
    /// stops it where it is. Checked by the caller ([`crate::spin::SpinCommand::new`]).
    pub fn set_spin_from_io(&self, spin: crate::spin::SpinCommand) {
        self.counters.spin_word.store(spin.to_word(), Ordering::Relaxed);
    }

    /// Asks the real-time thread to turn the needle 180° about its axis at its next tick (no
    /// request is lost: the thread applies every one it has not applied yet). Returns the number
    /// of flips requested so far.
    pub fn request_bevel_flip_from_io(&self) -> u64 {
        self.counters.bevel_flips_requested.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// Suspends the device (`true`) or lets it drive again (`false`): while suspended the
    /// real-time thread, from its next tick, applies none of the device channel's poses (it still
    /// reads and counts them: `device_poses_suspended`) and writes the device zero force and
    /// stiffness; when lifted, the needle catches up with the device at a bounded speed and the
    /// force ramps back (`rt_loop`'s module docs). Nothing for a session without a device channel.
    /// The training layer's switch (an instructor has control, or the exercise is paused).
    pub fn suspend_device_from_io(&self, suspended: bool) {
        self.device_suspended.store(suspended, Ordering::Relaxed);
    }

    /// Whether the device is suspended ([`Session::suspend_device_from_io`]).
    pub fn device_suspended(&self) -> bool {
        self.device_suspended.load(Ordering::Relaxed)
    }

    /// Whether a client has sent a pose (a scripted demo stops then).
    pub fn client_in_control(&self) -> bool {
        self.client_in_control.load(Ordering::Relaxed)
    }

    /// Publishes a pose for the next tick (latest value wins; an unconsumed one is counted as
    /// superseded). Called from IO tasks. A 3D session ignores it (the service checks the
    /// dimension first: [`Session::dimension`]; 3D poses go through [`Session::write_pose3_from_io`]).
    pub fn write_pose_from_io(&self, cmd: PoseCommand) {
        if let PoseSlot::Two(slot) = &self.pose_in {
            self.write_slot(slot, cmd);
        }
    }

    /// Publishes a 3D pose for the next tick, as [`Session::write_pose_from_io`] does a 2D one.
    ///
    /// Errors: [`WrongDimension`] for a 2D session (nothing is written).
    pub fn write_pose3_from_io(&self, cmd: PoseCommand3) -> Result<(), WrongDimension> {
        match &self.pose_in {
            PoseSlot::Three(slot) => {
                self.write_slot(slot, cmd);
                Ok(())
            }
            PoseSlot::Two(_) => Err(WrongDimension { given: 3, session: 2 }),
        }
    }

    /// [`Session::write_pose3_from_io`], and a scripted demo yields to the client.
    pub fn write_client_pose3_from_io(&self, cmd: PoseCommand3) -> Result<(), WrongDimension> {
        self.write_pose3_from_io(cmd)?;
        self.client_in_control.store(true, Ordering::Relaxed);
        Ok(())
    }

    /// 2 or 3.
    pub fn dimension(&self) -> u8 {
        self.tissue.dimension()
    }

    fn write_slot<P: Copy + Send>(&self, slot: &Mutex<triple_buffer::Input<PoseCommand<P>>>, cmd: PoseCommand<P>) {
        let mut input = slot.lock().expect("pose slot lock");
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
            active_set_capped_ticks: c.active_set_capped_ticks.load(Ordering::Relaxed),
            shape_capped_ticks: c.shape_capped_ticks.load(Ordering::Relaxed),
            late_captures: c.late_captures.load(Ordering::Relaxed),
            pending_captures_dropped: c.pending_captures_dropped.load(Ordering::Relaxed),
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

    /// Attaches the second sink, the tap (the training layer's), as [`Session::attach_sink_from_io`]
    /// does the first; refused (given back) while another tap is attached.
    pub fn attach_tap_from_io(&self, tap: Box<dyn RecordSink>) -> Result<(), Box<dyn RecordSink>> {
        let mut slot = self.tap.lock().expect("record tap lock");
        if slot.is_some() {
            return Err(tap);
        }
        *slot = Some(tap);
        Ok(())
    }

    /// Detaches the tap: the fan-out hands it no record after this returns.
    pub fn detach_tap_from_io(&self) -> Option<Box<dyn RecordSink>> {
        self.tap.lock().expect("record tap lock").take()
    }

    /// Whether [`Session::close`] has begun.
    pub fn is_closed(&self) -> bool {
        *self.closed.borrow()
    }

    /// Resolves once [`Session::close`] begins (at once if it has; also if the session is
    /// dropped). Holds no reference to the session: a stream that selects on it and ends drops
    /// its own.
    pub fn closed(&self) -> impl std::future::Future<Output = ()> + Send + 'static {
        let mut rx = self.closed.subscribe();
        async move {
            // An error is the sender gone with the session: closed too.
            let _ = rx.wait_for(|closed| *closed).await;
        }
    }

    /// Signals the close to the session's streams ([`Session::closed`]), stops the threads and
    /// waits for them, then drops the sink, if any (a recording finishes when dropped).
    pub fn close(&self) {
        self.closed.send_replace(true);
        self.stop.store(true, Ordering::Relaxed);
        for bell in &self.bells {
            bell.wake_from_io();
        }
        let threads: Vec<_> = std::mem::take(&mut *self.threads.lock().expect("threads lock"));
        for t in threads {
            let _ = t.join();
        }
        drop(self.detach_sink_from_io());
        drop(self.detach_tap_from_io());
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        SESSIONS_ALIVE.fetch_sub(1, Ordering::Relaxed);
        self.stop.store(true, Ordering::Relaxed);
        for bell in &self.bells {
            bell.wake_from_io();
        }
    }
}
