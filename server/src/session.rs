//! A live session: one simulation stepped by its own real-time thread at a fixed rate, a column
//! worker that computes compliance columns ahead of the tip, and a fan-out thread that turns tick
//! records into statistics, observer frames, displacement fields and recordings.
//!
//! ```text
//!  IO (gRPC tasks) ──pose──▶ [latest-value slot] ──▶ RT thread ──▶ [SPSC ring of TickRecord] ──▶ fan-out
//!                                                     │  ▲                                        │
//!                                   node requests ▼  │ columns (owned boxes)                    ├─▶ broadcast (every tick)
//!                                               column worker                                  ├─▶ watch (latest)
//!                                                                                              ├─▶ histograms, stats
//!                                                                                              └─▶ recorder, field
//! ```
//!
//! The real-time thread only uses non-blocking operations on bounded queues and latest-value
//! slots, allocates nothing per tick once warmed up, does no I/O, and counts every message it
//! drops. Its schedule is drift-free: tick $k$ is due at $t_0 + k\,\Delta t$; a tick that ends after
//! the next deadline is counted as missed and the schedule skips ahead rather than bursting.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use needlesim_core::BasePose;
use needlesim_core::compliance::TissueModel;
use needlesim_core::sim::{Divergence, NodeState, SimError, Simulation, StepOutput};

use needlesim_scene::Scene;

/// Needle nodes carried by one tick record (a simulation may have more; they are counted).
pub const MAX_RECORD_NODES: usize = 128;
/// Targets carried by one tick record.
pub const MAX_RECORD_TARGETS: usize = 8;
/// Capacity of the ring between the real-time thread and the fan-out, in ticks.
const RECORD_RING: usize = 2048;
/// Capacity of the column request and delivery queues.
const COLUMN_QUEUE: usize = 512;
/// How often the real-time thread refreshes the stiffness Jacobian (six probe solves).
pub const STIFFNESS_EVERY_TICKS: u64 = 10;
/// Ticks without a fresh device pose after which the device counts as stale and the needle is
/// held where it was (50 ms at 1 kHz).
pub const DEVICE_STALE_TICKS: u64 = 50;

/// One needle node in a tick record.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeRecord {
    pub node: u32,
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

    /// The fault in words (allocates: for the IO side).
    pub fn message(&self) -> String {
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
        }
    }
}

impl TickRecord {
    fn fill(&mut self, out: &StepOutput) {
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
            *r = NodeRecord {
                node: nn.node_idx as u32,
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

    /// The needle nodes of this record.
    pub fn nodes(&self) -> &[NodeRecord] {
        &self.nodes[..self.n_nodes as usize]
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

/// A pose command from a controller.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PoseCommand {
    pub pose: BasePose,
    pub seq: u64,
    pub client_time_ns: u64,
}

/// Counters shared between the threads of a session (atomics: no locks on the real-time side).
#[derive(Debug, Default)]
pub struct SessionCounters {
    pub ticks: AtomicU64,
    pub missed_deadlines: AtomicU64,
    pub dropped_records: AtomicU64,
    pub dropped_column_requests: AtomicU64,
    pub superseded_poses: AtomicU64,
    pub poses_written: AtomicU64,
    pub rejected_poses: AtomicU64,
    pub column_misses: AtomicU64,
    pub clamped_ticks: AtomicU64,
    pub records_truncated: AtomicU64,
    /// 1 while a device channel's bridge is stale (no fresh pose for [`DEVICE_STALE_TICKS`]).
    pub device_stale: AtomicU64,
    /// Times the device went stale.
    pub device_stale_events: AtomicU64,
    /// Fresh device poses taken.
    pub device_poses: AtomicU64,
    /// 1 once the device channel is broken (its file was truncated, resized, overwritten, deleted
    /// or replaced: `needlesim_channel::shm::Broken`): the device stays stale for the rest of the session.
    pub device_channel_broken: AtomicU64,
    /// Bevel flips asked for (by clients and the device's button 0), and applied by the
    /// real-time thread.
    pub bevel_flips_requested: AtomicU64,
    pub bevel_flips_applied: AtomicU64,
    /// Steps that failed other than by diverging (the solver or a compliance column): the tick
    /// held its pose and published nothing; [`MAX_CONSECUTIVE_STEP_ERRORS`] in a row fault.
    pub step_errors: AtomicU64,
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

    fn set_fault_from_rt(&self, f: &SessionFault) {
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
    pub lateness_us: [f64; 3],
    pub missed_deadlines: u64,
    pub superseded_poses: u64,
    pub dropped_records: u64,
    pub column_misses: u64,
    pub rejected_poses: u64,
    pub clamped_ticks: u64,
    /// Faults (0 or 1) and the fault, in words.
    pub faults: u64,
    pub fault: Option<String>,
}

struct Histograms {
    compute_ns: hdrhistogram::Histogram<u64>,
    lateness_ns: hdrhistogram::Histogram<u64>,
}

/// A displacement field of every node, computed by the fan-out at frame rate.
#[derive(Debug, Clone, Default)]
pub struct Field {
    pub tick: u64,
    pub displacement_m: Vec<f64>,
}

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
    /// Frames to record, when a recording is active (set by the IO side, read by the fan-out).
    pub recorder: Arc<Mutex<Option<crate::recording::Recorder>>>,
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
        let recorder = Arc::new(Mutex::new(None));
        let mut threads = Vec::new();

        let rt = RtLoop {
            sim,
            period: Duration::from_secs_f64(1.0 / tick_rate_hz),
            pose_out,
            rec_tx,
            req_tx,
            col_rx,
            ret_tx,
            requested: vec![false; scene.tissue.mesh().n_nodes()],
            counters: counters.clone(),
            stop: stop.clone(),
            record: Box::new(TickRecord::default()),
            rt_priority: rt_priority(),
            device,
            device_seen: false,
            last_buttons: None,
            stiffness: [0.0; 9],
            fault: None,
            consecutive_step_errors: 0,
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
            recorder: recorder.clone(),
            target_names: scene.target_names.clone(),
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
            recorder,
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
            missed_deadlines: c.missed_deadlines.load(Ordering::Relaxed),
            superseded_poses: c.superseded_poses.load(Ordering::Relaxed),
            dropped_records: c.dropped_records.load(Ordering::Relaxed),
            column_misses: c.column_misses.load(Ordering::Relaxed),
            rejected_poses: c.rejected_poses.load(Ordering::Relaxed),
            clamped_ticks: c.clamped_ticks.load(Ordering::Relaxed),
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

    /// Stops the threads and waits for them; the recording, if any, is finished.
    pub fn close(&self) {
        self.stop.store(true, Ordering::Relaxed);
        let threads: Vec<_> = std::mem::take(&mut *self.threads.lock().expect("threads lock"));
        for t in threads {
            let _ = t.join();
        }
        if let Some(r) = self.recorder.lock().expect("recorder lock").take()
            && let Err(e) = r.finish()
        {
            tracing::warn!(session = %self.id, "finishing the recording failed: {e}");
        }
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

thread_local! {
    /// True on a session's real-time thread while it computes a tick (after its first ticks),
    /// so that a counting allocator in a test can prove that ticks allocate nothing.
    pub static IN_TICK: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Ticks after which the real-time thread counts as warmed up.
pub const WARM_UP_TICKS: u64 = 200;

/// The real-time loop's state.
struct RtLoop {
    sim: Simulation,
    period: Duration,
    pose_out: triple_buffer::Output<PoseCommand>,
    rec_tx: rtrb::Producer<TickRecord>,
    req_tx: rtrb::Producer<u32>,
    col_rx: rtrb::Consumer<(u32, Box<[f64]>)>,
    ret_tx: rtrb::Producer<Box<[f64]>>,
    requested: Vec<bool>,
    counters: Arc<SessionCounters>,
    stop: Arc<AtomicBool>,
    record: Box<TickRecord>,
    rt_priority: i32,
    /// The server end of the device channel, if any.
    device: Option<needlesim_channel::shm::ServerEnd>,
    /// A device pose has been received at least once.
    device_seen: bool,
    /// The device's buttons at its previous fresh pose (None before the first).
    last_buttons: Option<u32>,
    stiffness: [f64; 9],
    /// Set when a step failed: no more steps, zero force, the needle held.
    fault: Option<SessionFault>,
    /// Step failures (other than a divergence) in a row; [`MAX_CONSECUTIVE_STEP_ERRORS`] fault.
    consecutive_step_errors: u32,
}

/// The session's device-channel watcher (a non-real-time thread): checks the channel's file every
/// [`needlesim_channel::shm::WATCH_PERIOD`] (deleted, replaced, resized: system calls the real-time
/// thread does not make), which the real-time thread then sees as a broken channel; logs the cause
/// once, whoever found it.
fn watch_device_channel(watch: needlesim_channel::shm::ChannelWatch, stop: Arc<AtomicBool>) {
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

/// The device button (bit of `DevicePose::buttons`) that turns the needle 180° about its axis,
/// on each press (rising edge).
pub const FLIP_BEVEL_BUTTON: u32 = 1;

pub use needlesim_channel::rt::request_realtime_priority;
use needlesim_channel::schedule::Schedule;

impl RtLoop {
    fn run(mut self) {
        match request_realtime_priority(self.rt_priority) {
            Ok(()) => tracing::debug!(priority = self.rt_priority, "real-time thread runs with SCHED_FIFO"),
            Err(why) => tracing::warn!("the real-time thread runs without real-time priority ({why}); ticks may be late under load"),
        }
        // Drift-free: tick k at start + k·period (needlesim_channel::schedule).
        let mut schedule = Schedule::start_now(self.period);
        let mut pose = self.sim.pose();
        let mut last_seq = 0;
        let mut last_client_time = 0;
        while !self.stop.load(Ordering::Relaxed) {
            let wake = schedule.wait();
            self.tick_from_rt(&mut pose, &mut last_seq, &mut last_client_time, wake.lateness);
            // Behind by a period or more: the skipped ticks are missed deadlines; behind by less,
            // the next tick runs late at once, one missed deadline.
            let missed = schedule.catch_up().missed_deadlines();
            if missed > 0 {
                self.counters.missed_deadlines.fetch_add(missed, Ordering::Relaxed);
            }
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
            if let Some(spare) = self.sim.insert_columns_owned(node as usize, cols)
                && let Err(rtrb::PushError::Full(spare)) = self.ret_tx.push(spare)
            {
                drop(spare);
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
                }
            } else if sample.fresh()
                && let Some(p) = sample.value
            {
                *pose = BasePose::new(p.x_m, p.y_m, p.theta_rad);
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
                    self.record.fill(out);
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
                Err(e) => tracing::error!("stiffness: {e}"),
            }
        }
        self.record.stiffness = self.stiffness;
        self.record.device_stale = device_stale;
        if let Some(dev) = self.device.as_mut() {
            let r = &self.record;
            dev.write_force_from_rt(&needlesim_channel::shm::ServerForce {
                t_ns: needlesim_channel::shm::monotonic_ns(),
                tick: r.tick,
                force_n: r.force_n,
                torque_nm: r.torque_nm,
                stiffness: self.stiffness,
                base: [r.base.x_m, r.base.y_m, r.base.theta_rad],
                state: if device_stale {
                    needlesim_channel::shm::ServerForce::STATE_DEVICE_STALE
                } else {
                    needlesim_channel::shm::ServerForce::STATE_OK
                },
            });
        }
        let st = self.sim.stats();
        self.counters.column_misses.fetch_add(st.column_misses - misses_before, Ordering::Relaxed);
        self.counters.clamped_ticks.store(st.clamped_ticks, Ordering::Relaxed);
        if self.sim.output().needle_nodes.len() > MAX_RECORD_NODES {
            self.counters.records_truncated.fetch_add(1, Ordering::Relaxed);
        }
        // Ask the worker for the columns of approaching nodes, and of needle nodes whose columns
        // a tick computed itself (so that the fan-out can render their share of the field).
        let out = self.sim.output();
        let n_app = out.approaching.len();
        for k in 0..n_app + out.needle_nodes.len() {
            let out = self.sim.output();
            let node = if k < n_app { out.approaching[k] } else { out.needle_nodes[k - n_app].node_idx };
            if !self.requested[node] {
                if self.req_tx.push(node as u32).is_ok() {
                    self.requested[node] = true;
                } else {
                    self.counters.dropped_column_requests.fetch_add(1, Ordering::Relaxed);
                    break;
                }
            }
        }
        self.record.pose_seq = *last_seq;
        self.record.client_time_ns = *last_client_time;
        self.record.lateness_ns = lateness.as_nanos() as u64;
        self.record.compute_ns = t0.elapsed().as_nanos() as u64;
        // A tick that did not step publishes nothing (observers never see a tick twice).
        if (stepped || just_faulted) && self.rec_tx.push(*self.record).is_err() {
            self.counters.dropped_records.fetch_add(1, Ordering::Relaxed);
        }
        self.counters.ticks.fetch_add(1, Ordering::Relaxed);
    }
}

/// Computes compliance columns off the real-time thread.
struct ColumnWorker {
    tissue: Arc<TissueModel>,
    req_rx: rtrb::Consumer<u32>,
    col_tx: rtrb::Producer<(u32, Box<[f64]>)>,
    ret_rx: rtrb::Consumer<Box<[f64]>>,
    render_columns: Arc<Mutex<std::collections::HashMap<u32, Arc<[f64]>>>>,
    stop: Arc<AtomicBool>,
}

impl ColumnWorker {
    fn run(mut self) {
        let mut scratch = self.tissue.column_scratch();
        let len = 2 * self.tissue.n_dofs();
        while !self.stop.load(Ordering::Relaxed) {
            while self.ret_rx.pop().is_ok() {}
            let Ok(node) = self.req_rx.pop() else {
                std::thread::sleep(Duration::from_micros(500));
                continue;
            };
            let mut cols = vec![0.0; len].into_boxed_slice();
            if let Err(e) = self.tissue.compliance_columns_into(node as usize, &mut cols, &mut scratch) {
                tracing::error!("column of node {node}: {e}");
                continue;
            }
            self.render_columns.lock().expect("render columns lock").insert(node, Arc::from(&cols[..]));
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

/// Distributes tick records off the real-time thread.
struct FanOut {
    rec_rx: rtrb::Consumer<TickRecord>,
    all_tx: tokio::sync::broadcast::Sender<Arc<TickRecord>>,
    latest_tx: tokio::sync::watch::Sender<Arc<TickRecord>>,
    field_tx: tokio::sync::watch::Sender<Arc<Field>>,
    field_subscribers: Arc<AtomicU64>,
    render_columns: Arc<Mutex<std::collections::HashMap<u32, Arc<[f64]>>>>,
    n_dofs: usize,
    histograms: Arc<Mutex<Histograms>>,
    recorder: Arc<Mutex<Option<crate::recording::Recorder>>>,
    target_names: Vec<String>,
    stop: Arc<AtomicBool>,
}

/// How often the fan-out computes the displacement field while someone wants it.
const FIELD_PERIOD: Duration = Duration::from_millis(8);

impl FanOut {
    fn run(mut self) {
        let mut last_field = Instant::now() - FIELD_PERIOD;
        let mut latest: Option<Arc<TickRecord>> = None;
        while !self.stop.load(Ordering::Relaxed) {
            let mut any = false;
            while let Ok(rec) = self.rec_rx.pop() {
                any = true;
                {
                    let mut h = self.histograms.lock().expect("histogram lock");
                    let _ = h.compute_ns.record(rec.compute_ns.max(1));
                    let _ = h.lateness_ns.record(rec.lateness_ns.max(1));
                }
                let rec = Arc::new(rec);
                if let Some(r) = self.recorder.lock().expect("recorder lock").as_ref() {
                    r.write_from_io(&crate::convert::frame_from_record(&rec, &self.target_names, 0));
                }
                let _ = self.all_tx.send(rec.clone());
                latest = Some(rec);
            }
            if let Some(rec) = &latest {
                self.latest_tx.send_replace(rec.clone());
                if self.field_subscribers.load(Ordering::Relaxed) > 0 && last_field.elapsed() >= FIELD_PERIOD {
                    last_field = Instant::now();
                    let field = self.field_for(rec);
                    self.field_tx.send_replace(Arc::new(field));
                }
            }
            if !any {
                std::thread::sleep(Duration::from_micros(250));
            }
        }
    }

    /// $u = \sum_w C_{:,w} f_w$ from the columns the worker computed.
    fn field_for(&self, rec: &TickRecord) -> Field {
        let mut u = vec![0.0; self.n_dofs];
        let cols = self.render_columns.lock().expect("render columns lock");
        for nn in rec.nodes() {
            if let Some(c) = cols.get(&nn.node) {
                for comp in 0..2 {
                    let f = nn.force_n[comp];
                    if f != 0.0 {
                        for (o, v) in u.iter_mut().zip(&c[comp * self.n_dofs..(comp + 1) * self.n_dofs]) {
                            *o += v * f;
                        }
                    }
                }
            }
        }
        Field { tick: rec.tick, displacement_m: u }
    }
}
