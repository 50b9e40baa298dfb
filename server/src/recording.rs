//! Session recordings: the frames of a session written to an MCAP file (protobuf messages with
//! their schema), readable by Foxglove and by the `mcap` libraries, and the listing and opening
//! of the recordings of a directory.
//!
//! A [`Recorder`] owns a dedicated writer thread. The session's fan-out thread hands frames over
//! with [`Recorder::write_from_fanout`] (through [`SessionRecording`], the session's record sink), which encodes the frame and queues it without blocking (a full
//! queue drops the frame and counts it). The writer thread writes them into small chunks
//! (about [`CHUNK_BYTES`] of messages each) and hands every finished chunk to the OS at once, so
//! that a killed server leaves a file that the streaming readers can read up to its last chunk.
//! [`Recorder::finish`] (or dropping the recorder) drains the queue and writes the summary and
//! footer.
//!
//! A recording belongs to the session that made it: [`write_owner`] keeps the session id and the
//! SHA-256 digests of its tokens (never the tokens) next to it, in `<name>.owner`, which outlives
//! the session and the server. Files are opened without following symbolic links and only when
//! they are regular files (a FIFO never blocks a reader).
//!
//! Recordings are bounded on disk (issue 35; `quota.rs`): [`Recorder::start_within`] admits a
//! recording against the directory's [`DirQuota`] (`--max-recordings` files,
//! `--max-recordings-mb` bytes), and the writer thread reserves every message's bytes before
//! writing it; the first that does not fit stops the recording, which is then finished (last
//! chunk, summary and footer: a valid MCAP file) and drops the session's later frames.

use std::collections::BTreeMap;
use std::fmt;
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, SyncSender, TrySendError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use needlesim_proto::v1::Frame;
use needlesim_session::{RecordSink, Session, TickRecord};
use prost::Message as _;

use crate::quota::{DirQuota, QuotaExceeded, Reservation};

/// The topic of the frames in a recording.
pub const FRAME_TOPIC: &str = "/needlesim/frames";
/// The schema name of the frames: the full name of the protobuf message.
pub const FRAME_SCHEMA_NAME: &str = "needlesim.v1.Frame";
/// The schema and message encoding of the frames.
pub const PROTOBUF_ENCODING: &str = "protobuf";
/// The file name extension of recordings.
pub const EXTENSION: &str = "mcap";
/// The writer closes a chunk, and hands it to the OS, once it holds this many bytes of messages.
pub const CHUNK_BYTES: usize = 64 * 1024;
/// The writer also closes a non-empty chunk after this long, so that a slow stream is on disk.
pub const FLUSH_INTERVAL: Duration = Duration::from_secs(1);
/// Frames that can wait for the writer thread before [`Recorder::write_from_fanout`] drops them.
pub const QUEUE_FRAMES: usize = 8192;
/// The longest recording name, in bytes (a file name of the usual file systems).
pub const MAX_NAME_BYTES: usize = 255;
/// The longest session id a recording is named after: its name adds `-<UTC time>-<n>.mcap`.
pub const MAX_SESSION_ID_BYTES: usize = 200;
/// Bytes a recording needs to start: its header (the schemas), the summary and footer that
/// finish it, its owner file and a first chunk.
pub const START_BYTES: u64 = 512 * 1024;
/// Bytes reserved per message beyond its data: the record and index entries (47 bytes) and the
/// chunk compressor's worst case.
const MESSAGE_OVERHEAD_BYTES: u64 = 64;
/// Bytes of the summary per chunk (its chunk index), held until the recording finishes.
const CHUNK_INDEX_BYTES: u64 = 256;

/// Why a recording could not be started, written, finished or opened.
#[derive(Debug)]
pub enum RecordingError {
    /// [`Recorder::start`]: the recording directory could not be created.
    CreateDir { dir: PathBuf, source: io::Error },
    /// [`Recorder::start`]: the recording file could not be created (including: every candidate
    /// name already exists).
    CreateFile { path: PathBuf, source: io::Error },
    /// [`Recorder::start`]: the session id is empty or holds characters other than ASCII letters,
    /// digits, `-`, `_` and `.` (it becomes part of a file name).
    InvalidSessionId { session_id: String },
    /// [`Recorder::start`]: the writer thread could not be spawned.
    SpawnThread(io::Error),
    /// [`Recorder::start`] (header, schema, channel), the writer thread (a chunk) or
    /// [`Recorder::finish`] (the summary and footer): the MCAP writer failed, usually an I/O
    /// error such as a full disk. After a failed write the recording stops and later frames count
    /// as dropped; `finish` reports the first error.
    Mcap(mcap::McapError),
    /// [`Recorder::finish`]: the writer thread panicked.
    WriterPanicked,
    /// [`open_recording`]: the name is not the plain file name of a recording (it holds a path
    /// separator or `..`, or does not end in `.mcap`).
    InvalidName { name: String, reason: &'static str },
    /// [`open_recording`]: there is no recording of that name.
    NotFound { name: String },
    /// [`open_recording`]: the recording exists but could not be opened.
    Open { name: String, source: io::Error },
    /// [`open_recording`]: the name is a symbolic link, a FIFO, a directory or another file that
    /// is not a regular file: not a recording.
    NotRegularFile { name: String },
    /// [`write_owner`]: the owner file could not be written.
    WriteOwner { path: PathBuf, source: io::Error },
    /// [`Recorder::start_within`]: the recordings directory holds its limit of files or bytes.
    Quota(QuotaExceeded),
}

impl fmt::Display for RecordingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::CreateDir { dir, source } => write!(f, "cannot create the recording directory {}: {source}", dir.display()),
            Self::CreateFile { path, source } => write!(f, "cannot create the recording {}: {source}", path.display()),
            Self::InvalidSessionId { session_id } => {
                write!(f, "invalid session id {session_id:?} for a recording: use ASCII letters, digits, '-', '_' and '.'")
            }
            Self::SpawnThread(e) => write!(f, "cannot spawn the recording writer thread: {e}"),
            Self::Mcap(e) => write!(f, "cannot write the recording: {e}"),
            Self::WriterPanicked => write!(f, "the recording writer thread panicked"),
            Self::InvalidName { name, reason } => write!(f, "invalid recording name {name:?}: {reason}"),
            Self::NotFound { name } => write!(f, "no recording named {name:?}"),
            Self::Open { name, source } => write!(f, "cannot open the recording {name:?}: {source}"),
            Self::NotRegularFile { name } => write!(f, "no recording named {name:?} (it is not a regular file)"),
            Self::WriteOwner { path, source } => write!(f, "cannot write the recording's owner file {}: {source}", path.display()),
            Self::Quota(e) => write!(f, "cannot start a recording: {e}"),
        }
    }
}

impl std::error::Error for RecordingError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::CreateDir { source, .. }
            | Self::CreateFile { source, .. }
            | Self::Open { source, .. }
            | Self::WriteOwner { source, .. } => Some(source),
            Self::SpawnThread(e) => Some(e),
            Self::Mcap(e) => Some(e),
            Self::Quota(e) => Some(e),
            Self::InvalidSessionId { .. }
            | Self::WriterPanicked
            | Self::InvalidName { .. }
            | Self::NotFound { .. }
            | Self::NotRegularFile { .. } => None,
        }
    }
}

impl From<mcap::McapError> for RecordingError {
    fn from(e: mcap::McapError) -> Self {
        Self::Mcap(e)
    }
}

/// How a tick record becomes a frame (given the session's target names): the service's
/// conversion (`convert::frame_from_record`), passed in so that this module needs no import of
/// the conversions (which import this module's types).
pub type FrameOfRecord = fn(&TickRecord, &[String]) -> Frame;

/// The session's tissue for a player: a 2D session's mesh (`needlesim.v1.Mesh`) or a 3D one's
/// boundary surface (`needlesim.v1.Surface`), encoded; written once, on [`TISSUE_TOPIC`], with
/// the recording's first frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TissueMessage {
    Mesh(Vec<u8>),
    Surface(Vec<u8>),
}

impl TissueMessage {
    fn schema_name(&self) -> &'static str {
        match self {
            TissueMessage::Mesh(_) => "needlesim.v1.Mesh",
            TissueMessage::Surface(_) => "needlesim.v1.Surface",
        }
    }
}

/// What a session's recording carries beyond the frames and the Foxglove channels.
#[derive(Clone, Debug, Default)]
pub struct RecordOptions {
    /// The tissue, written once.
    pub tissue: Option<TissueMessage>,
    /// The displacement field in the frames every [`FIELD_EVERY_S`] of simulated time (the
    /// session computes it while the recording runs).
    pub include_displacements: bool,
}

/// The topic of the tissue message.
pub const TISSUE_TOPIC: &str = "/needlesim/tissue";
/// With [`RecordOptions::include_displacements`]: a field at most this often (simulated s).
pub const FIELD_EVERY_S: f64 = 0.1;

/// The recording of a live session: the session's [`RecordSink`]. Each tick record becomes a
/// frame on the fan-out thread, is encoded and queued for the writer thread.
pub struct SessionRecording {
    recorder: Recorder,
    target_names: Vec<String>,
    frame_of: FrameOfRecord,
    /// The tissue message, until it is queued with the first frame.
    tissue: Option<TissueMessage>,
    /// With displacements: the session's latest field and the subscriber count this recording
    /// holds one of (given back on drop), and the simulated time of the last field recorded.
    field: Option<FieldSubscription>,
    last_field_s: f64,
    /// For the Foxglove channels: the tissue's surface (sent with the scene every
    /// [`SURFACE_EVERY_S`]), the simulated times of the last scene and surface, and buffers.
    surface: needlesim_foxglove::Surface,
    last_scene_s: f64,
    last_surface_s: f64,
    parts: crate::foxglove_live::SceneParts,
}

/// Scenes in a recording: at most one per this many seconds of simulated time (30 Hz).
pub const SCENE_EVERY_S: f64 = 1.0 / 30.0;
/// The tissue's surface is repeated in the scene this often (s), so that a player that seeks
/// finds it within a second.
pub const SURFACE_EVERY_S: f64 = 1.0;

impl SessionRecording {
    /// Records `session`'s frames into `recorder` from the next tick on, or gives the recorder
    /// back when the session already has a record sink.
    pub fn attach(session: &Session, recorder: Recorder, frame_of: FrameOfRecord, options: RecordOptions) -> Result<(), Recorder> {
        let field = options.include_displacements.then(|| {
            session.field_subscribers.fetch_add(1, Ordering::Relaxed);
            FieldSubscription { field: session.field.clone(), subscribers: Arc::clone(&session.field_subscribers) }
        });
        let sink = Box::new(SessionRecording {
            recorder,
            target_names: session.target_names.clone(),
            frame_of,
            tissue: options.tissue,
            field,
            last_field_s: f64::NEG_INFINITY,
            surface: crate::foxglove_live::surface_of(session),
            last_scene_s: f64::NEG_INFINITY,
            last_surface_s: f64::NEG_INFINITY,
            parts: crate::foxglove_live::SceneParts::default(),
        });
        session.attach_sink_from_io(sink).map_err(|back| match back.into_any().downcast::<SessionRecording>() {
            Ok(r) => r.recorder,
            Err(_) => unreachable!("the sink just refused is the recording given"),
        })
    }

    /// The recording `session` is making, if any.
    pub fn info_of(session: &Session) -> Option<RecordingInfo> {
        session.with_sink_from_io(|sink| sink?.as_any().downcast_ref::<SessionRecording>().map(|r| r.recorder.info()))
    }

    /// Stops recording `session` and gives the recorder back (to be finished off the runtime);
    /// None when it is not recording.
    pub fn detach(session: &Session) -> Option<Recorder> {
        let sink = session.detach_sink_from_io()?;
        match sink.into_any().downcast::<SessionRecording>() {
            Ok(r) => Some(r.recorder),
            Err(_) => None,
        }
    }
}

/// A recording's subscription to the session's displacement field: the latest field, and the
/// subscriber count it holds one of, given back on drop.
struct FieldSubscription {
    field: tokio::sync::watch::Receiver<Arc<needlesim_session::Field>>,
    subscribers: Arc<AtomicU64>,
}

impl Drop for FieldSubscription {
    fn drop(&mut self) {
        self.subscribers.fetch_sub(1, Ordering::Relaxed);
    }
}

impl RecordSink for SessionRecording {
    fn write_from_fanout(&mut self, rec: &TickRecord) {
        if let Some(tissue) = self.tissue.take() {
            self.recorder.queue_from_fanout(Queued {
                topic: Topic::Tissue(tissue.schema_name()),
                tick: rec.tick,
                time_s: rec.time_s,
                data: match tissue {
                    TissueMessage::Mesh(d) | TissueMessage::Surface(d) => d,
                },
            });
        }
        let mut frame = (self.frame_of)(rec, &self.target_names);
        if let Some(sub) = &mut self.field
            && rec.time_s - self.last_field_s >= FIELD_EVERY_S
            && sub.field.has_changed().unwrap_or(false)
        {
            self.last_field_s = rec.time_s;
            let u = sub.field.borrow_and_update().displacement_m.clone();
            if rec.dimension == 3 {
                frame.surface_displacement_m = u;
            } else {
                frame.node_displacement_m = u;
            }
        }
        self.recorder.write_from_fanout(&frame);
        let force = crate::foxglove_live::force_of(rec).to_json();
        self.recorder.queue_from_fanout(Queued { topic: Topic::FoxgloveForce, tick: rec.tick, time_s: rec.time_s, data: force });
        if rec.time_s - self.last_scene_s >= SCENE_EVERY_S {
            self.last_scene_s = rec.time_s;
            let with_surface = rec.time_s - self.last_surface_s >= SURFACE_EVERY_S;
            if with_surface {
                self.last_surface_s = rec.time_s;
            }
            let update = self.parts.scene_update(rec, with_surface.then_some(&self.surface));
            let data = prost::Message::encode_to_vec(&update);
            self.recorder.queue_from_fanout(Queued { topic: Topic::FoxgloveScene, tick: rec.tick, time_s: rec.time_s, data });
        }
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn into_any(self: Box<Self>) -> Box<dyn std::any::Any + Send> {
        self
    }
}

/// A recording, live or on disk.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RecordingInfo {
    /// The file name, `<session_id>-<UTC time>[-<n>].mcap`.
    pub name: String,
    /// The session id given to [`Recorder::start`].
    pub session_id: String,
    /// Bytes handed to the OS so far (live), or the file size (on disk).
    pub size_bytes: u64,
    /// Frames written by the writer thread (live; 0 when listed from disk).
    pub messages: u64,
    /// Frames dropped because the queue was full or the writer had failed (live; 0 from disk).
    pub dropped: u64,
    /// Whether the file is complete: it ends with the MCAP magic (summary and footer written).
    pub finished: bool,
}

/// Counters shared by the recorder and its writer thread.
#[derive(Default)]
struct Counters {
    /// Frames written into the MCAP writer.
    messages: AtomicU64,
    /// Frames in closed chunks handed to the OS.
    flushed_messages: AtomicU64,
    dropped: AtomicU64,
    /// Bytes handed to the OS.
    size_bytes: AtomicU64,
    finished: AtomicBool,
    /// The writer stopped: the next message would have passed the directory's byte limit.
    stopped_at_limit: AtomicBool,
}

/// Which channel a queued message goes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Topic {
    /// The project's frame (`FRAME_TOPIC`).
    Frame,
    /// Foxglove's scene (`/needlesim/<session>/scene`, foxglove.SceneUpdate).
    FoxgloveScene,
    /// The force sample for Foxglove's Plot panel (`/needlesim/<session>/force`, JSON).
    FoxgloveForce,
    /// The tissue ([`TISSUE_TOPIC`]), with its schema's name.
    Tissue(&'static str),
}

/// A message on its way to the writer thread, encoded by the caller.
struct Queued {
    topic: Topic,
    tick: u64,
    time_s: f64,
    data: Vec<u8>,
}

/// Records the frames of one session into an MCAP file on a writer thread.
pub struct Recorder {
    name: String,
    session_id: String,
    path: PathBuf,
    tx: Option<SyncSender<Queued>>,
    thread: Option<JoinHandle<Result<(), RecordingError>>>,
    counters: Arc<Counters>,
}

impl Recorder {
    /// Creates `dir` if needed and a new recording `<session_id>-<UTC time>[-<n>].mcap` in it
    /// (never overwriting a file), writes the MCAP header, the schema and the channel, and starts
    /// the writer thread.
    pub fn start(dir: &Path, session_id: &str) -> Result<Recorder, RecordingError> {
        Self::start_within(dir, session_id, &DirQuota::unlimited("recordings", EXTENSION))
    }

    /// [`Recorder::start`] within `quota` (the directory's bound on files and bytes): refused with
    /// [`RecordingError::Quota`] when the directory is full; the recording stops, finished, when
    /// its next message would pass the byte limit.
    pub fn start_within(dir: &Path, session_id: &str, quota: &Arc<DirQuota>) -> Result<Recorder, RecordingError> {
        if session_id.is_empty()
            || session_id.len() > MAX_SESSION_ID_BYTES
            || !session_id.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
        {
            return Err(RecordingError::InvalidSessionId { session_id: session_id.to_owned() });
        }
        fs::create_dir_all(dir).map_err(|source| RecordingError::CreateDir { dir: dir.to_owned(), source })?;
        let mut reservation = quota.admit(dir, START_BYTES).map_err(RecordingError::Quota)?;
        let now = SystemTime::now().duration_since(UNIX_EPOCH).unwrap_or_default();
        let stamp = utc_stamp(now.as_secs());
        let (name, path, file) = create_unique(dir, &format!("{session_id}-{stamp}"))?;
        let start_ns = u64::try_from(now.as_nanos()).unwrap_or(u64::MAX);

        let options = mcap::WriteOptions::new()
            .library(concat!("needlesim-server ", env!("CARGO_PKG_VERSION")))
            .profile("")
            // Chunks are closed by the writer thread (see CHUNK_BYTES), and buffered whole in
            // memory, so that the file only ever receives complete chunks.
            .chunk_size(None)
            .disable_seeking(true);
        let counters = Arc::new(Counters::default());
        let sink = Sink { file: BufWriter::new(file), position: 0, counters: Arc::clone(&counters) };
        let mut writer = options.create(sink)?;
        let schema_id = writer.add_schema(FRAME_SCHEMA_NAME, PROTOBUF_ENCODING, needlesim_proto::FILE_DESCRIPTOR_SET)?;
        let channel_id = writer.add_channel(schema_id, FRAME_TOPIC, PROTOBUF_ENCODING, &BTreeMap::new())?;
        let foxglove = needlesim_foxglove::McapChannels::register(&mut writer, session_id)?;
        let metadata = BTreeMap::from([
            ("session_id".to_owned(), session_id.to_owned()),
            ("start_utc".to_owned(), stamp),
            ("server_version".to_owned(), env!("CARGO_PKG_VERSION").to_owned()),
        ]);
        writer.write_metadata(&mcap::records::Metadata { name: "needlesim".to_owned(), metadata })?;
        writer.flush()?;
        // The header is written, out of START_BYTES; the rest is held for the summary (which
        // repeats the schemas: twice the header, with the tissue's) and the owner file.
        let header_bytes = counters.size_bytes.load(Ordering::Relaxed);
        reservation.spend(header_bytes, header_bytes);
        let finish_bytes = 2 * header_bytes + 2 * OWNER_MAX_BYTES;
        if reservation.held() < finish_bytes && !reservation.try_reserve(finish_bytes - reservation.held()) {
            tracing::warn!(recording = %path.display(), "recording stopped at once: the recordings directory is at its byte limit");
            reservation.count_stop();
            counters.stopped_at_limit.store(true, Ordering::Relaxed);
        }

        let (tx, rx) = mpsc::sync_channel(QUEUE_FRAMES);
        let thread_counters = Arc::clone(&counters);
        let thread = std::thread::Builder::new()
            .name(format!("recorder-{session_id}"))
            .spawn(move || {
                let w = WriterThread {
                    writer,
                    channel_id,
                    foxglove,
                    tissue_channel: None,
                    start_ns,
                    offset_ns: None,
                    counters: thread_counters,
                    pending_bytes: 0,
                    pending_messages: 0,
                    reservation,
                    chunk_overhead: header_bytes + 4096,
                    chunk_reserved: 0,
                };
                w.run(rx)
            })
            .map_err(RecordingError::SpawnThread)?;
        tracing::info!(recording = %path.display(), session_id, "recording started");
        Ok(Recorder { name, session_id: session_id.to_owned(), path, tx: Some(tx), thread: Some(thread), counters })
    }

    /// Encodes `frame` and queues it for the writer thread, without blocking and without file
    /// I/O. Returns false, and counts the frame as dropped, when the queue is full or the writer
    /// has stopped.
    pub fn write_from_fanout(&self, frame: &Frame) -> bool {
        self.queue_from_fanout(Queued { topic: Topic::Frame, tick: frame.tick, time_s: frame.time_s, data: frame.encode_to_vec() })
    }

    /// Queues a message for one of the Foxglove channels (encoded by the caller), as
    /// [`Recorder::write_from_fanout`].
    fn queue_from_fanout(&self, queued: Queued) -> bool {
        let Some(tx) = &self.tx else { return false };
        if self.counters.stopped_at_limit.load(Ordering::Relaxed) {
            // Stopped at the directory's byte limit: the file is finished.
            self.counters.dropped.fetch_add(1, Ordering::Relaxed);
            return false;
        }
        match tx.try_send(queued) {
            Ok(()) => true,
            Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => {
                let dropped = self.counters.dropped.fetch_add(1, Ordering::Relaxed) + 1;
                if dropped.is_power_of_two() {
                    tracing::warn!(recording = %self.name, dropped, "recording queue full or writer stopped: frames dropped");
                }
                false
            }
        }
    }

    /// The recording so far (counts are live).
    pub fn info(&self) -> RecordingInfo {
        RecordingInfo {
            name: self.name.clone(),
            session_id: self.session_id.clone(),
            size_bytes: self.counters.size_bytes.load(Ordering::Relaxed),
            messages: self.counters.messages.load(Ordering::Relaxed),
            dropped: self.counters.dropped.load(Ordering::Relaxed),
            finished: self.counters.finished.load(Ordering::Relaxed),
        }
    }

    /// The path of the recording file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes the queued frames, the summary and the footer, and joins the writer thread. This
    /// waits for file I/O (at most [`QUEUE_FRAMES`] frames and the summary): from async code, call
    /// it (or drop the recorder) in `spawn_blocking`.
    pub fn finish(mut self) -> Result<RecordingInfo, RecordingError> {
        self.finish_inner()?;
        Ok(self.info())
    }

    fn finish_inner(&mut self) -> Result<(), RecordingError> {
        // Closing the queue makes the writer thread drain it and finish the file.
        drop(self.tx.take());
        let Some(thread) = self.thread.take() else { return Ok(()) };
        let result = thread.join().unwrap_or(Err(RecordingError::WriterPanicked));
        match &result {
            Ok(()) => {
                let info = self.info();
                tracing::info!(recording = %self.path.display(), messages = info.messages, dropped = info.dropped, size_bytes = info.size_bytes, "recording finished");
            }
            Err(e) => tracing::error!(recording = %self.path.display(), error = %e, "recording failed"),
        }
        result
    }

    /// Frames in chunks handed to the OS (what survives a killed server).
    #[cfg(test)]
    fn flushed_messages(&self) -> u64 {
        self.counters.flushed_messages.load(Ordering::Relaxed)
    }
}

impl Drop for Recorder {
    /// Finishes the recording, best effort (errors are logged).
    fn drop(&mut self) {
        let _ = self.finish_inner();
    }
}

type McapWriter = mcap::Writer<Sink>;

/// The writer thread: owns the MCAP writer.
struct WriterThread {
    writer: McapWriter,
    channel_id: u16,
    /// The Foxglove scene and force channels.
    foxglove: needlesim_foxglove::McapChannels,
    /// The tissue's channel, made with its first (only) message.
    tissue_channel: Option<u16>,
    /// Wall-clock time of the start of the recording, ns since the Unix epoch.
    start_ns: u64,
    /// Added to the simulated time (ns) of a frame to give its log time; fixed by the first frame
    /// so that it is logged at `start_ns`.
    offset_ns: Option<i128>,
    counters: Arc<Counters>,
    /// Message bytes and messages in the open chunk.
    pending_bytes: usize,
    pending_messages: u64,
    /// The recording's bytes in the directory's quota: held for the summary, and for the open
    /// chunk (`chunk_reserved`) until it is written.
    reservation: Reservation,
    /// Bytes reserved with a chunk's first message: the chunk's own records and the schemas and
    /// channels a chunk may repeat (at most the header's).
    chunk_overhead: u64,
    chunk_reserved: u64,
}

impl WriterThread {
    fn run(mut self, rx: Receiver<Queued>) -> Result<(), RecordingError> {
        let mut last_flush = Instant::now();
        loop {
            if self.counters.stopped_at_limit.load(Ordering::Relaxed) {
                // At the byte limit: finish the file now; later frames are dropped.
                let counters = Arc::clone(&self.counters);
                self.finish()?;
                for _ in rx.iter() {
                    counters.dropped.fetch_add(1, Ordering::Relaxed);
                }
                return Ok(());
            }
            let timeout = FLUSH_INTERVAL.saturating_sub(last_flush.elapsed());
            match rx.recv_timeout(timeout) {
                Ok(queued) => {
                    if !self.reserve(&queued) {
                        tracing::warn!(
                            bytes = self.counters.size_bytes.load(Ordering::Relaxed),
                            "recording stopped: its next message would pass the recordings directory's byte limit (--max-recordings-mb)"
                        );
                        self.counters.dropped.fetch_add(1, Ordering::Relaxed);
                        self.reservation.count_stop();
                        self.counters.stopped_at_limit.store(true, Ordering::Relaxed);
                        continue;
                    }
                    if let Err(e) = self.write(&queued) {
                        self.counters.dropped.fetch_add(1, Ordering::Relaxed);
                        return Err(self.fail(e, rx));
                    }
                    if self.pending_bytes >= CHUNK_BYTES {
                        if let Err(e) = self.flush() {
                            return Err(self.fail(e, rx));
                        }
                        last_flush = Instant::now();
                    }
                }
                Err(RecvTimeoutError::Timeout) => {
                    if self.pending_messages > 0
                        && let Err(e) = self.flush()
                    {
                        return Err(self.fail(e, rx));
                    }
                    last_flush = Instant::now();
                }
                Err(RecvTimeoutError::Disconnected) => break,
            }
        }
        self.finish()
    }

    /// Reserves the bytes of `queued` in the directory's quota (and the chunk's overhead with a
    /// chunk's first message); false when they would pass the limit.
    fn reserve(&mut self, queued: &Queued) -> bool {
        let data = queued.data.len() as u64;
        let mut need = data + data / 128 + MESSAGE_OVERHEAD_BYTES;
        if self.pending_messages == 0 {
            need += self.chunk_overhead + CHUNK_INDEX_BYTES;
        }
        if !self.reservation.try_reserve(need) {
            return false;
        }
        self.chunk_reserved += need;
        true
    }

    /// Writes the open chunk, the summary and the footer; the bytes written are the
    /// recording's last in the quota (what it still held is given back).
    fn finish(mut self) -> Result<(), RecordingError> {
        let before = self.counters.size_bytes.load(Ordering::Relaxed);
        self.writer.finish()?;
        // `finish` leaves the summary and footer in the buffer.
        self.writer.into_inner().flush().map_err(mcap::McapError::from)?;
        self.counters.flushed_messages.fetch_add(self.pending_messages, Ordering::Relaxed);
        let written = self.counters.size_bytes.load(Ordering::Relaxed).saturating_sub(before);
        let held = self.reservation.held();
        self.reservation.spend(held, written);
        self.counters.finished.store(true, Ordering::Relaxed);
        Ok(())
    }

    fn write(&mut self, queued: &Queued) -> Result<(), mcap::McapError> {
        let sim_ns = (queued.time_s * 1e9).round();
        let sim_ns = if sim_ns.is_finite() { sim_ns as i128 } else { 0 };
        let offset = *self.offset_ns.get_or_insert(i128::from(self.start_ns) - sim_ns);
        let time = u64::try_from((sim_ns + offset).max(0)).unwrap_or(u64::MAX);
        match queued.topic {
            Topic::Frame => {
                // MCAP sequences are 32 bits: the tick wraps after 2^32 frames.
                let header = mcap::records::MessageHeader {
                    channel_id: self.channel_id,
                    sequence: queued.tick as u32,
                    log_time: time,
                    publish_time: time,
                };
                self.writer.write_to_known_channel(&header, &queued.data)?;
                self.counters.messages.fetch_add(1, Ordering::Relaxed);
            }
            Topic::FoxgloveScene => self.foxglove.write_scene_encoded(&mut self.writer, time, &queued.data)?,
            Topic::FoxgloveForce => self.foxglove.write_force_encoded(&mut self.writer, time, &queued.data)?,
            Topic::Tissue(schema_name) => {
                let channel_id = match self.tissue_channel {
                    Some(c) => c,
                    None => {
                        let schema_id = self.writer.add_schema(schema_name, PROTOBUF_ENCODING, needlesim_proto::FILE_DESCRIPTOR_SET)?;
                        let c = self.writer.add_channel(schema_id, TISSUE_TOPIC, PROTOBUF_ENCODING, &BTreeMap::new())?;
                        self.tissue_channel = Some(c);
                        c
                    }
                };
                let header = mcap::records::MessageHeader { channel_id, sequence: 0, log_time: time, publish_time: time };
                self.writer.write_to_known_channel(&header, &queued.data)?;
            }
        }
        self.pending_bytes += queued.data.len();
        self.pending_messages += 1;
        Ok(())
    }

    /// Closes the open chunk and hands it to the OS; its reservation becomes the bytes written
    /// (its chunk index's stays held for the summary).
    fn flush(&mut self) -> Result<(), mcap::McapError> {
        let before = self.counters.size_bytes.load(Ordering::Relaxed);
        self.writer.flush()?;
        let written = self.counters.size_bytes.load(Ordering::Relaxed).saturating_sub(before);
        let chunks = u64::from(self.pending_messages > 0);
        self.reservation.spend(self.chunk_reserved.saturating_sub(chunks * CHUNK_INDEX_BYTES), written);
        self.chunk_reserved = 0;
        self.counters.flushed_messages.fetch_add(self.pending_messages, Ordering::Relaxed);
        self.pending_bytes = 0;
        self.pending_messages = 0;
        Ok(())
    }

    /// After a failed write: counts every later frame as dropped until the queue closes.
    fn fail(&mut self, e: mcap::McapError, rx: Receiver<Queued>) -> RecordingError {
        tracing::error!(error = %e, "recording write failed: dropping the remaining frames");
        for _ in rx.iter() {
            self.counters.dropped.fetch_add(1, Ordering::Relaxed);
        }
        RecordingError::Mcap(e)
    }
}

/// The file under the MCAP writer: buffered, counting the bytes handed to the OS. It does not
/// seek (the writer is told not to), but reports its position.
struct Sink {
    file: BufWriter<File>,
    position: u64,
    counters: Arc<Counters>,
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.file.write(buf)?;
        self.position += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()?;
        self.counters.size_bytes.store(self.position, Ordering::Relaxed);
        Ok(())
    }
}

impl Seek for Sink {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        match pos {
            SeekFrom::Current(0) => Ok(self.position),
            _ => Err(io::Error::new(io::ErrorKind::Unsupported, "a recording is written without seeking")),
        }
    }
}

/// Creates `<stem>.mcap` in `dir`, or `<stem>-1.mcap`, `<stem>-2.mcap`, ... if it exists.
fn create_unique(dir: &Path, stem: &str) -> Result<(String, PathBuf, File), RecordingError> {
    let mut last_error = None;
    for n in 0..1000 {
        let name = if n == 0 { format!("{stem}.{EXTENSION}") } else { format!("{stem}-{n}.{EXTENSION}") };
        let path = dir.join(&name);
        match OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(file) => return Ok((name, path, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last_error = Some((path, e)),
            Err(source) => return Err(RecordingError::CreateFile { path, source }),
        }
    }
    let (path, source) = last_error.expect("the loop ran");
    Err(RecordingError::CreateFile { path, source })
}

/// `YYYYMMDDTHHMMSSZ` for seconds since the Unix epoch (UTC).
fn utc_stamp(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}{month:02}{day:02}T{:02}{:02}{:02}Z", rem / 3600, rem / 60 % 60, rem % 60)
}

/// The session id in a recording name `<session_id>-<YYYYMMDDTHHMMSSZ>[-<n>].mcap`, or the
/// stem when the name is not of that form.
fn session_id_of(name: &str) -> String {
    let stem = name.strip_suffix(".mcap").unwrap_or(name);
    let is_stamp = |s: &str| s.len() == 16 && s.as_bytes()[8] == b'T' && s.ends_with('Z');
    let mut parts: Vec<&str> = stem.rsplitn(3, '-').collect();
    // parts: [last, second to last, rest] in reverse order.
    if parts.len() == 3 && parts[0].bytes().all(|b| b.is_ascii_digit()) && is_stamp(parts[1]) {
        return parts[2].to_owned();
    }
    parts = stem.rsplitn(2, '-').collect();
    if parts.len() == 2 && is_stamp(parts[0]) {
        return parts[1].to_owned();
    }
    stem.to_owned()
}

/// Whether the file ends with the MCAP magic, i.e. was finished.
fn ends_with_magic(path: &Path) -> bool {
    let read_tail = || -> io::Result<bool> {
        let mut file = open_regular(path).map_err(|e| match e {
            OpenRegularError::Io(e) => e,
            other => io::Error::other(format!("{other:?}")),
        })?;
        let len = file.metadata()?.len();
        let magic_len = mcap::MAGIC.len() as u64;
        if len < 2 * magic_len {
            return Ok(false);
        }
        file.seek(SeekFrom::Start(len - magic_len))?;
        let mut tail = [0u8; 8];
        file.read_exact(&mut tail)?;
        Ok(tail[..] == *mcap::MAGIC)
    };
    read_tail().unwrap_or(false)
}

/// The recordings (`*.mcap`) in `dir`, by name; empty when `dir` does not exist. Only
/// `name`, `session_id`, `size_bytes` and `finished` are known from the file.
pub fn list_recordings(dir: &Path) -> Vec<RecordingInfo> {
    let Ok(entries) = fs::read_dir(dir) else { return Vec::new() };
    let mut list: Vec<RecordingInfo> = entries
        .filter_map(Result::ok)
        .filter_map(|entry| {
            let name = entry.file_name().into_string().ok()?;
            let meta = entry.metadata().ok()?;
            if !meta.is_file() || !name.ends_with(".mcap") {
                return None;
            }
            Some(RecordingInfo {
                session_id: session_id_of(&name),
                size_bytes: meta.len(),
                messages: 0,
                dropped: 0,
                finished: ends_with_magic(&entry.path()),
                name,
            })
        })
        .collect();
    list.sort_by(|a, b| a.name.cmp(&b.name));
    list
}

/// Checks that `name` is the plain file name of a recording, never a path: at most
/// [`MAX_NAME_BYTES`] bytes of ASCII letters, digits, `-`, `_` and `.` (so no separator, no NUL,
/// no control or shell character), no `..`, not starting with `.`, ending in `.mcap`.
pub fn check_name(name: &str) -> Result<(), RecordingError> {
    let invalid = |reason| Err(RecordingError::InvalidName { name: name.to_owned(), reason });
    if name.contains('/') || name.contains('\\') || name.contains(std::path::MAIN_SEPARATOR) {
        return invalid("it holds a path separator");
    }
    if name.contains("..") {
        return invalid("it holds '..'");
    }
    if name.contains('\0') {
        return invalid("it holds a NUL character");
    }
    if name.len() > MAX_NAME_BYTES {
        return invalid("it is longer than 255 bytes");
    }
    if !name.bytes().all(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.')) {
        return invalid("use ASCII letters, digits, '-', '_' and '.' only");
    }
    if name.starts_with('.') {
        return invalid("it starts with '.'");
    }
    if !name.ends_with(".mcap") || name.len() <= ".mcap".len() {
        return invalid("it does not end in .mcap");
    }
    Ok(())
}

/// Opens the recording `name` in `dir` for reading. `name` must be a plain file name ending in
/// `.mcap` ([`check_name`]).
pub fn open_recording(dir: &Path, name: &str) -> Result<File, RecordingError> {
    check_name(name)?;
    match open_regular(&dir.join(name)) {
        Ok(file) => Ok(file),
        Err(OpenRegularError::NotFound) => Err(RecordingError::NotFound { name: name.to_owned() }),
        Err(OpenRegularError::NotRegular) => Err(RecordingError::NotRegularFile { name: name.to_owned() }),
        Err(OpenRegularError::Io(source)) => Err(RecordingError::Open { name: name.to_owned(), source }),
    }
}

/// Why [`open_regular`] did not open a file.
#[derive(Debug)]
enum OpenRegularError {
    /// There is no such file.
    NotFound,
    /// It is a symbolic link, FIFO, socket, device or directory.
    NotRegular,
    /// Any other error of `open` or `fstat`.
    Io(io::Error),
}

/// Opens `path` for reading only if it is a regular file: never following a symbolic link
/// (`O_NOFOLLOW`) and never waiting for a FIFO's writer (`O_NONBLOCK`, which changes nothing for
/// a regular file), then checking the opened file itself (`fstat`).
fn open_regular(path: &Path) -> Result<File, OpenRegularError> {
    use std::os::unix::fs::OpenOptionsExt;
    let file = match OpenOptions::new().read(true).custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK).open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Err(OpenRegularError::NotFound),
        // O_NOFOLLOW on a symbolic link.
        Err(e) if e.raw_os_error() == Some(libc::ELOOP) => return Err(OpenRegularError::NotRegular),
        Err(e) => return Err(OpenRegularError::Io(e)),
    };
    match file.metadata() {
        Ok(m) if m.is_file() => Ok(file),
        Ok(_) => Err(OpenRegularError::NotRegular),
        Err(e) => Err(OpenRegularError::Io(e)),
    }
}

/// The file name extension of a recording's owner file, after the recording's own name.
pub const OWNER_EXTENSION: &str = "owner";
/// Largest owner file read.
const OWNER_MAX_BYTES: u64 = 4096;

/// Whom a recording belongs to: the session that made it and the SHA-256 digests of the tokens
/// that open it (the session's controller and observer tokens).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RecordingOwner {
    pub session_id: String,
    pub token_sha256: Vec<crate::access::TokenDigest>,
}

fn owner_path(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}.{OWNER_EXTENSION}"))
}

/// Writes the owner file of the recording `name` in `dir` (`<name>.owner`: a `session_id` line
/// and one `token_sha256` line per token digest), replacing a stale one but never following a
/// symbolic link.
pub fn write_owner(dir: &Path, name: &str, owner: &RecordingOwner) -> Result<(), RecordingError> {
    use std::os::unix::fs::OpenOptionsExt;
    let path = owner_path(dir, name);
    let mut text = format!("session_id {}\n", owner.session_id);
    for d in &owner.token_sha256 {
        text.push_str(&format!("token_sha256 {}\n", crate::access::to_hex(d)));
    }
    let write = || -> io::Result<()> {
        let mut f = OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .mode(0o600)
            .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
            .open(&path)?;
        if !f.metadata()?.is_file() {
            return Err(io::Error::other("not a regular file"));
        }
        f.write_all(text.as_bytes())?;
        f.sync_all()
    };
    write().map_err(|source| RecordingError::WriteOwner { path: path.clone(), source })
}

/// The owner of the recording `name` in `dir`, or `None` when it has no (readable, well-formed)
/// owner file: such a recording opens with the admin token only.
pub fn read_owner(dir: &Path, name: &str) -> Option<RecordingOwner> {
    let path = owner_path(dir, name);
    let file = open_regular(&path).ok()?;
    let mut text = String::new();
    file.take(OWNER_MAX_BYTES).read_to_string(&mut text).ok()?;
    let mut session_id = None;
    let mut token_sha256 = Vec::new();
    for line in text.lines() {
        match line.split_once(' ') {
            Some(("session_id", id)) => session_id = Some(id.to_owned()),
            Some(("token_sha256", hex)) => token_sha256.push(crate::access::digest_from_hex(hex)?),
            _ => return None,
        }
    }
    Some(RecordingOwner { session_id: session_id?, token_sha256 })
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_proto::v1::{NeedleNode, NodeState, Pose2, TargetState, Vec2};

    fn frame(tick: u64) -> Frame {
        let t = tick as f64 * 1e-3;
        let v = |x: f64, y: f64| Some(Vec2 { x, y });
        Frame {
            tick,
            time_s: t,
            base: Some(Pose2 { x_m: 0.01 * t, y_m: -0.002 * t.sin(), theta_rad: 0.05 * t.cos() }),
            force_n: v(0.3 * t, -0.1 * t),
            torque_nm: 1e-3 * t,
            force_axial_n: 0.31 * t,
            force_lateral_n: -0.05 * t,
            tip_m: v(0.02 + 0.01 * t, 0.001),
            inserted_length_m: 0.01 * t,
            needle_nodes: (0..6)
                .map(|i| NeedleNode {
                    node: 40 + i,
                    state: if i == 5 { NodeState::Tip } else { NodeState::Stuck } as i32,
                    position_m: v(0.02 + 0.001 * f64::from(i), 1e-4 * f64::from(i)),
                    force_n: v(0.01 * f64::from(i) * t, -0.002),
                    material_point: i % 2 == 0,
                })
                .collect(),
            targets: vec![TargetState { name: "lesion".into(), position_m: v(0.05, 0.0), distance_m: 0.05 - 0.01 * t, hit: false }],
            node_displacement_m: (0..16).map(|i| 1e-5 * f64::from(i) * t).collect(),
            needle_shape_m: vec![Vec2 { x: 0.0, y: 0.1 }, Vec2 { x: 0.001 * t, y: 0.0 }],
            bevel_side: if tick.is_multiple_of(2) { 1.0 } else { -1.0 },
            missed_ticks: 0,
            compute_us: 120.0 + (tick % 7) as f64,
            stiffness: (0..9).map(|i| -10.0 * f64::from(i) - t).collect(),
            faulted: false,
            fault: String::new(),
            d3: None,
            surface_displacement_m: vec![],
        }
    }

    fn temp_dir(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("needlesim-recording-{test}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir
    }

    /// Copies `path` to `$NEEDLESIM_KEEP_TMP/<as_name>` when that variable is set (for
    /// tests/mcap_check.py).
    fn keep(path: &Path, as_name: &str) {
        if let Some(keep) = std::env::var_os("NEEDLESIM_KEEP_TMP") {
            let keep = PathBuf::from(keep);
            fs::create_dir_all(&keep).unwrap();
            fs::copy(path, keep.join(as_name)).unwrap();
        }
    }

    /// Writes frames, waiting for the queue rather than dropping them.
    fn write_all(recorder: &Recorder, frames: &[Frame]) {
        for f in frames {
            while !recorder.write_from_fanout(f) {
                std::thread::sleep(Duration::from_millis(1));
            }
        }
    }

    /// Decodes the messages of an MCAP file up to its end or its first error (a truncated end);
    /// returns them and whether an error ended them.
    fn read_frames(bytes: &[u8], ignore_end_magic: bool) -> (Vec<(mcap::Message<'static>, Frame)>, bool) {
        let mut out = Vec::new();
        let stream = if ignore_end_magic {
            mcap::read::MessageStream::new_with_options(bytes, mcap::read::Options::IgnoreEndMagic.into())
        } else {
            mcap::read::MessageStream::new(bytes)
        };
        for m in stream.unwrap() {
            match m {
                Ok(m) => {
                    let f = Frame::decode(&m.data[..]).unwrap();
                    out.push((m, f));
                }
                Err(_) => return (out, true),
            }
        }
        (out, false)
    }

    #[test]
    fn records_and_reads_back_frames() {
        let dir = temp_dir("roundtrip");
        let frames: Vec<Frame> = (0..2000).map(|t| frame(1000 + t)).collect();
        let recorder = Recorder::start(&dir, "s-42").unwrap();
        let name = recorder.info().name;
        assert!(name.starts_with("s-42-") && name.ends_with(".mcap"), "{name}");
        write_all(&recorder, &frames);
        let info = recorder.finish().unwrap();
        assert_eq!((info.messages, info.dropped, info.finished), (2000, 0, true));
        assert_eq!(info.session_id, "s-42");
        let path = dir.join(&info.name);
        assert_eq!(info.size_bytes, fs::metadata(&path).unwrap().len());
        keep(&path, "roundtrip.mcap");

        let bytes = fs::read(&path).unwrap();
        let (read, error) = read_frames(&bytes, false);
        assert!(!error);
        assert_eq!(read.len(), frames.len());
        let start = read[0].0.log_time;
        for ((m, f), original) in read.iter().zip(&frames) {
            assert_eq!(f, original);
            assert_eq!(m.sequence, original.tick as u32);
            assert_eq!(m.log_time, m.publish_time);
            assert_eq!(m.log_time - start, (original.time_s * 1e9).round() as u64 - 1_000_000_000);
            assert_eq!(m.channel.topic, FRAME_TOPIC);
            assert_eq!(m.channel.message_encoding, PROTOBUF_ENCODING);
            let schema = m.channel.schema.as_ref().unwrap();
            assert_eq!((schema.name.as_str(), schema.encoding.as_str()), (FRAME_SCHEMA_NAME, PROTOBUF_ENCODING));
            assert_eq!(&schema.data[..], needlesim_proto::FILE_DESCRIPTOR_SET);
        }
        // The summary is there and indexes several small chunks.
        let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
        assert_eq!(summary.stats.as_ref().unwrap().message_count, 2000);
        assert!(summary.chunk_indexes.len() >= 4, "{} chunks", summary.chunk_indexes.len());
        assert!(summary.chunk_indexes.iter().all(|c| c.uncompressed_size < 2 * CHUNK_BYTES as u64));

        // A second recording of the same session gets its own file; both are listed.
        let second = Recorder::start(&dir, "s-42").unwrap();
        assert_ne!(second.info().name, info.name);
        let listed = list_recordings(&dir);
        assert_eq!(listed.len(), 2);
        let first = listed.iter().find(|r| r.name == info.name).unwrap();
        assert_eq!((first.session_id.as_str(), first.size_bytes, first.finished), ("s-42", info.size_bytes, true));
        let live = listed.iter().find(|r| r.name != info.name).unwrap();
        assert_eq!((live.session_id.as_str(), live.finished), ("s-42", false));
        drop(second); // finishes on drop
        assert!(list_recordings(&dir).iter().all(|r| r.finished));
        open_recording(&dir, &info.name).unwrap();
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn flushed_chunks_survive_a_crash() {
        let dir = temp_dir("crash");
        let frames: Vec<Frame> = (0..3000).map(frame).collect();
        let recorder = Recorder::start(&dir, "crash").unwrap();
        write_all(&recorder, &frames);
        // Wait until the writer has handed most frames to the OS in closed chunks, then take the
        // file as a killed server would leave it: no last chunk, no summary, no footer.
        let deadline = Instant::now() + Duration::from_secs(10);
        while recorder.flushed_messages() < 2500 {
            assert!(Instant::now() < deadline, "only {} frames flushed", recorder.flushed_messages());
            std::thread::sleep(Duration::from_millis(5));
        }
        let flushed = recorder.flushed_messages();
        let bytes = fs::read(recorder.path()).unwrap();
        assert!(!bytes.ends_with(mcap::MAGIC));
        let copy = dir.join("crash-copy.mcap");
        fs::write(&copy, &bytes).unwrap();
        keep(&copy, "truncated.mcap");
        assert!(list_recordings(&dir).iter().any(|r| r.name == "crash-copy.mcap" && !r.finished));

        // The streaming reader reads every flushed chunk, then reports the truncated end.
        for ignore_end_magic in [false, true] {
            let (read, error) = read_frames(&bytes, ignore_end_magic);
            // Without IgnoreEndMagic the missing end is an error after the last message.
            assert!(error || ignore_end_magic);
            assert!(read.len() as u64 >= flushed, "{} of {flushed} flushed frames read", read.len());
            assert!(read.len() >= 2500);
            for ((_, f), original) in read.iter().zip(&frames) {
                assert_eq!(f, original);
            }
        }
        // Cutting the file anywhere (a kill in the middle of a write) loses at most the last chunk.
        let (whole, _) = read_frames(&bytes, false);
        for cut in [bytes.len() - 1, bytes.len() - 1000, bytes.len() * 3 / 4] {
            let (read, error) = read_frames(&bytes[..cut], false);
            assert!(error);
            assert!(read.len() + 400 >= whole.len() * cut / bytes.len(), "{} frames from {cut} bytes", read.len());
            assert!(read.iter().zip(&frames).all(|((_, f), o)| f == o));
        }
        let info = recorder.finish().unwrap();
        assert_eq!(info.messages, 3000);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn open_recording_rejects_bad_names() {
        let dir = temp_dir("names");
        fs::create_dir_all(&dir).unwrap();
        for name in ["../x.mcap", "a/b.mcap", "x.txt", "a\\b.mcap", "..mcap", ".mcap", ""] {
            match open_recording(&dir, name) {
                Err(e @ RecordingError::InvalidName { .. }) => assert!(e.to_string().contains(&format!("{name:?}")), "{e}"),
                other => panic!("{name:?}: {other:?}"),
            }
        }
        let e = open_recording(&dir, "missing.mcap").unwrap_err();
        assert!(matches!(e, RecordingError::NotFound { .. }), "{e:?}");
        assert!(e.to_string().contains("missing.mcap"));
        assert!(matches!(Recorder::start(&dir, "../evil"), Err(RecordingError::InvalidSessionId { .. })));
        assert!(list_recordings(&dir.join("nowhere")).is_empty());
        fs::remove_dir_all(&dir).unwrap();
    }

    /// Regression (issue 13): a symbolic link in the recordings folder was followed, and a FIFO
    /// blocked the reader until a writer came. Neither is a recording now, and neither blocks.
    #[test]
    fn issue_13_links_and_fifos_are_not_recordings() {
        let dir = temp_dir("links");
        fs::create_dir_all(&dir).unwrap();
        let secret = dir.join("secret.txt");
        fs::write(&secret, "secret").unwrap();
        std::os::unix::fs::symlink(&secret, dir.join("link.mcap")).unwrap();
        let fifo = std::ffi::CString::new(dir.join("fifo.mcap").into_os_string().into_encoded_bytes()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0, "mkfifo");
        let e = open_recording(&dir, "link.mcap").unwrap_err();
        assert!(matches!(e, RecordingError::NotRegularFile { .. }), "{e:?}");
        // On a thread with a timeout: the old code blocked here forever.
        let d = dir.clone();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || tx.send(format!("{:?}", open_recording(&d, "fifo.mcap"))).unwrap());
        let got = rx.recv_timeout(Duration::from_secs(10)).expect("opening a FIFO does not block");
        assert!(got.contains("NotRegularFile"), "{got}");
        assert!(list_recordings(&dir).is_empty(), "{:?}", list_recordings(&dir));
        // Owner files: round trip; a link is not read.
        let owner = RecordingOwner { session_id: "s1".into(), token_sha256: vec![crate::access::token_digest("t")] };
        write_owner(&dir, "a.mcap", &owner).unwrap();
        assert_eq!(read_owner(&dir, "a.mcap"), Some(owner.clone()));
        std::os::unix::fs::symlink(dir.join("a.mcap.owner"), dir.join("b.mcap.owner")).unwrap();
        assert_eq!(read_owner(&dir, "b.mcap"), None);
        assert!(write_owner(&dir, "b.mcap", &owner).is_err(), "writing through a link");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn names() {
        assert_eq!(utc_stamp(0), "19700101T000000Z");
        assert_eq!(utc_stamp(1_709_210_096), "20240229T123456Z");
        assert_eq!(session_id_of("s-42-20240229T123456Z.mcap"), "s-42");
        assert_eq!(session_id_of("s-42-20240229T123456Z-3.mcap"), "s-42");
        assert_eq!(session_id_of("other.mcap"), "other");
    }
}
