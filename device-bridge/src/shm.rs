//! The shared-memory channel between a session's real-time thread (server process) and the device bridge process on the same host.
//!
//! One memory-mapped file with a fixed, versioned layout, created by the server side
//! ([`DeviceChannel::create`] → [`ServerEnd`], mode 0600) and opened by the bridge
//! ([`DeviceChannel::attach`] → [`DeviceEnd`]). It holds two single-writer slots, each a seqlock:
//! device → server ([`DevicePose`]) and server → device ([`ServerForce`]). Neither side ever
//! blocks: a read retries a bounded number of times and otherwise returns the last good value.
//!
//! # Layout (little-endian, [`LAYOUT_VERSION`] 1, [`CHANNEL_SIZE`] = 512 bytes)
//!
//! Every field is a naturally aligned `u32`/`u64` accessed only through atomics; `f64`s are stored
//! as their bit patterns, `u32`s of the slots in the low half of a `u64` word. Blocks are 128-byte
//! aligned so the two slots never share a cache line (nor an adjacent-line prefetch pair).
//!
//! | offset | size | field |
//! |-------:|-----:|-------|
//! | 0   | 8 | magic `b"NDLSIMv1"` |
//! | 8   | 4 | layout version (`u32`) |
//! | 12  | 4 | reserved (0) |
//! | 16  | 8 | total size in bytes (`u64`, 512) |
//! | 24  | 8 | generation (`u64`, random, never 0; 0 while `create` is initialising) |
//! | 32  | 4 | creator pid (`u32`) |
//! | 36  | 4 | attacher pid (`u32`, 0 when no bridge is attached) |
//! | 40  | 4 | closed (`u32`, 1 once the server end was dropped) |
//! | 44  | 84 | reserved (0) |
//! | 128 | 8 | pose slot: sequence (odd while being written, even when done, 0 = never written) |
//! | 136 | 8 | pose slot: generation of the writer |
//! | 144 | 48 | pose: `t_ns`, `x_m`, `y_m`, `theta_rad`, `buttons`, `counter` (one `u64` word each) |
//! | 192 | 64 | reserved (0) |
//! | 256 | 8 | force slot: sequence |
//! | 264 | 8 | force slot: generation of the writer |
//! | 272 | 144 | force: `t_ns`, `tick`, `force_n[2]`, `torque_nm`, `stiffness[9]` (row-major), `base[3]`, `state` |
//! | 416 | 96 | reserved (0) |
//!
//! # Freshness and stale state
//!
//! `create` truncates the file to [`CHANNEL_SIZE`] and re-initialises it in place: generation 0,
//! header, both slots zeroed, pids, and last the new random generation (release store). Re-using
//! the inode (rather than a new file) is what lets a bridge still attached to it notice:
//! [`DeviceEnd::is_current`] compares the header's generation with the one it saw at attach, and its
//! reads then return [`ReadStatus::Stale`]. Each slot carries the writer's generation, and a reader
//! accepts a value only if that generation is its own and the slot's sequence advanced since its
//! last accepted read, so values from an earlier run (or a late write from a bridge of an earlier
//! generation) are never taken as fresh.
//!
//! # Memory ordering (the seqlock)
//!
//! Writer (exactly one per slot: the server writes the force slot, the attached bridge the pose
//! slot; `attach` refuses a second live bridge): `s = seq (relaxed)`, store `s+1` (odd, relaxed),
//! **release fence**, data and slot generation (relaxed stores), store `s+2` (**release**).
//! Reader: `s1 = seq (acquire)`, retry if odd; data (relaxed loads); **acquire fence**;
//! `s2 = seq (relaxed)`; accept iff `s1 == s2`.
//! - The acquire load of `s1` synchronises with the release store of `s1` that ended write k, so all
//!   of write k's data happens-before the data loads.
//! - If any data load observed a store of a later write k+1, the reader's acquire fence (after that
//!   load) synchronises with the writer's release fence (before that store), so the odd store
//!   `s1+1` happens-before the `s2` load, which therefore returns at least `s1+1`: the read is
//!   rejected. Hence an accepted read is exactly write k (H.-J. Boehm, "Can seqlocks get along with
//!   programming language memory models?", MSPC 2012). All fields being atomics, there is no data
//!   race in the Rust model; across processes the same hardware guarantees apply (x86-64: the
//!   fences compile to nothing but compiler barriers, stores are not reordered with stores).
//!
//! A writer that died mid-write leaves the sequence odd; the next writer continues from that odd
//! value (it does not add another 1), so the slot recovers.

use std::fs::{File, OpenOptions};
use std::io;
use std::mem::{offset_of, size_of};
use std::os::unix::fs::{MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering, fence};

use memmap2::MmapRaw;

/// The 8 magic bytes at offset 0.
pub const MAGIC: [u8; 8] = *b"NDLSIMv1";
/// The layout version at offset 8; bump it on any change of the layout.
pub const LAYOUT_VERSION: u32 = 1;
/// The size of the channel file in bytes.
pub const CHANNEL_SIZE: u64 = size_of::<Layout>() as u64;
/// How many times a read retries while the writer is mid-write before giving up (≈ a few µs).
pub const READ_RETRIES: u32 = 64;

/// What went wrong creating or attaching a channel. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ShmError {
    /// A system call failed: opening/creating the file (`create`: e.g. the directory is missing or
    /// the path is a symlink; `attach`: no permission), `fchmod`, `set_len`, `fstat` or `mmap`.
    #[error("device channel {path}: {op} failed: {source}")]
    Io {
        path: PathBuf,
        op: &'static str,
        #[source]
        source: io::Error,
    },
    /// `attach`: no file at the path (the server has not created the channel, or has closed it).
    #[error("device channel {path}: no such file (has the server created the channel?)")]
    Missing { path: PathBuf },
    /// `attach`: the file is not [`CHANNEL_SIZE`] bytes long (a short file, another program's file, or another layout).
    #[error("device channel {path}: file is {found} bytes, expected {expected}")]
    WrongSize { path: PathBuf, found: u64, expected: u64 },
    /// `attach`: the first 8 bytes are not [`MAGIC`] (not a needlesim channel, or another layout family).
    #[error("device channel {path}: wrong magic {found:?}, expected {expected:?}", found = String::from_utf8_lossy(found), expected = String::from_utf8_lossy(&MAGIC))]
    WrongMagic { path: PathBuf, found: [u8; 8] },
    /// `attach`: the layout version differs (server and bridge built from different layouts).
    #[error("device channel {path}: layout version {found}, this bridge speaks {expected}")]
    WrongVersion { path: PathBuf, found: u32, expected: u32 },
    /// `attach`: the header's size field disagrees with [`CHANNEL_SIZE`] although the file length matches.
    #[error("device channel {path}: header says {found} bytes, expected {expected}")]
    WrongHeaderSize { path: PathBuf, found: u64, expected: u64 },
    /// `attach`: the generation is 0: the server is in the middle of `create` (retry), or died during it.
    #[error("device channel {path}: not initialised yet (server still creating it, or it died while creating it)")]
    NotInitialised { path: PathBuf },
    /// `attach`: the server end was dropped (the file is about to be removed); wait for a new channel.
    #[error("device channel {path}: closed by the server (pid {creator_pid})")]
    Closed { path: PathBuf, creator_pid: u32 },
    /// `attach`: another live process is attached as the bridge; two writers would break the pose seqlock.
    #[error("device channel {path}: already attached by live pid {pid} (only one bridge per channel)")]
    AlreadyAttached { path: PathBuf, pid: u32 },
}

/// The channel is stale: the server re-created it (new generation) or closed it. Re-attach.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("device channel is stale (re-created or closed by the server): re-attach")]
pub struct Stale;

/// The device's pose, written by the bridge once per device sample.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DevicePose {
    /// `CLOCK_MONOTONIC` of the writer when sampled, ns ([`monotonic_ns`]).
    pub t_ns: u64,
    pub x_m: f64,
    pub y_m: f64,
    pub theta_rad: f64,
    pub buttons: u32,
    /// Incremented by every write (stamped by [`DeviceEnd::write_pose_from_device`]; the caller's
    /// value is ignored): a counter that stops advancing means a dead bridge.
    pub counter: u64,
}

/// The force the tissue exerts, written by the session's real-time thread once per tick.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ServerForce {
    /// `CLOCK_MONOTONIC` of the writer, ns.
    pub t_ns: u64,
    /// The real-time loop's tick.
    pub tick: u64,
    pub force_n: [f64; 2],
    pub torque_nm: f64,
    /// 3×3 Jacobian of (Fx, Fy, τ) with respect to (x, y, θ), row-major.
    pub stiffness: [f64; 9],
    /// The pose (x, y, θ) the force was computed at.
    pub base: [f64; 3],
    /// [`ServerForce::STATE_OK`], [`ServerForce::STATE_DEVICE_STALE`] or [`ServerForce::STATE_CLOSING`].
    pub state: u32,
}

impl ServerForce {
    pub const STATE_OK: u32 = 0;
    /// The server has no fresh pose: it holds the needle where it was.
    pub const STATE_DEVICE_STALE: u32 = 1;
    /// The server is shutting the channel down.
    pub const STATE_CLOSING: u32 = 2;
}

/// What a read found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReadStatus {
    /// A value written since the previous accepted read, by a writer of this generation.
    Fresh,
    /// Nothing new (or only data of another generation); `value` is the last good one, if any.
    Unchanged,
    /// The writer was mid-write through every retry; `value` is the last good one.
    Contended,
    /// ([`DeviceEnd`] only) the server re-created or closed the channel: re-attach.
    Stale,
}

/// The result of a read: the last good value and whether it is new.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<T> {
    /// The last value accepted under this generation; `None` until the first.
    pub value: Option<T>,
    pub status: ReadStatus,
    /// Reads since the last fresh one (0 when this one is fresh; counts from create/attach before the first).
    pub reads_since_fresh: u64,
}

impl<T> Sample<T> {
    /// True if `value` was written since the previous read.
    pub fn fresh(&self) -> bool {
        self.status == ReadStatus::Fresh
    }
}

/// `CLOCK_MONOTONIC` in nanoseconds (the clock of [`DevicePose::t_ns`] and [`ServerForce::t_ns`]; shared by processes on a host).
pub fn monotonic_ns() -> u64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: valid pointer to a timespec; CLOCK_MONOTONIC always exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut ts) };
    ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64
}

/// True if a process with this pid exists (`kill(pid, 0)`; a process of another user counts as alive).
/// Pids are reused, so "alive" can be a false positive long after a death, never a false negative.
pub fn pid_alive(pid: u32) -> bool {
    if pid == 0 || pid > i32::MAX as u32 {
        return false;
    }
    // SAFETY: signal 0 only checks existence and permission.
    let r = unsafe { libc::kill(pid as libc::pid_t, 0) };
    r == 0 || io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
}

// ---------------------------------------------------------------------------------------------
// Layout

#[repr(C, align(128))]
struct Header {
    magic: AtomicU64,
    version: AtomicU32,
    _reserved0: AtomicU32,
    total_size: AtomicU64,
    generation: AtomicU64,
    creator_pid: AtomicU32,
    attacher_pid: AtomicU32,
    closed: AtomicU32,
}

const POSE_WORDS: usize = 6;
const FORCE_WORDS: usize = 18;

#[repr(C, align(128))]
struct Slot<const N: usize> {
    seq: AtomicU64,
    generation: AtomicU64,
    words: [AtomicU64; N],
}

#[repr(C)]
struct Layout {
    header: Header,
    pose: Slot<POSE_WORDS>,
    force: Slot<FORCE_WORDS>,
}

const _: () = {
    assert!(size_of::<Layout>() == 512);
    assert!(offset_of!(Layout, header) == 0);
    assert!(offset_of!(Header, version) == 8);
    assert!(offset_of!(Header, total_size) == 16);
    assert!(offset_of!(Header, generation) == 24);
    assert!(offset_of!(Header, creator_pid) == 32);
    assert!(offset_of!(Header, attacher_pid) == 36);
    assert!(offset_of!(Header, closed) == 40);
    assert!(offset_of!(Layout, pose) == 128);
    assert!(offset_of!(Layout, force) == 256);
    assert!(offset_of!(Slot<FORCE_WORDS>, words) == 16);
};

enum RawRead {
    /// A consistent snapshot: (sequence, writer generation).
    Ok(u64, u64),
    Contended,
}

impl<const N: usize> Slot<N> {
    fn reset(&self) {
        self.seq.store(0, Ordering::Relaxed);
        self.generation.store(0, Ordering::Relaxed);
        for w in &self.words {
            w.store(0, Ordering::Relaxed);
        }
    }

    /// The single writer's seqlock write (see the module docs for the ordering argument).
    fn write(&self, generation: u64, data: &[u64; N]) {
        let s = self.seq.load(Ordering::Relaxed);
        let open = s | 1; // a writer that died mid-write left it odd: continue from there
        self.seq.store(open, Ordering::Relaxed);
        fence(Ordering::Release);
        self.generation.store(generation, Ordering::Relaxed);
        for (w, &v) in self.words.iter().zip(data) {
            w.store(v, Ordering::Relaxed);
        }
        self.seq.store(open.wrapping_add(1), Ordering::Release);
    }

    fn read(&self, out: &mut [u64; N]) -> RawRead {
        for _ in 0..READ_RETRIES {
            let s1 = self.seq.load(Ordering::Acquire);
            if s1 & 1 == 1 {
                std::hint::spin_loop();
                continue;
            }
            let g = self.generation.load(Ordering::Relaxed);
            for (o, w) in out.iter_mut().zip(&self.words) {
                *o = w.load(Ordering::Relaxed);
            }
            fence(Ordering::Acquire);
            let s2 = self.seq.load(Ordering::Relaxed);
            if s1 == s2 {
                return RawRead::Ok(s1, g);
            }
            std::hint::spin_loop();
        }
        RawRead::Contended
    }
}

impl DevicePose {
    fn encode(&self, counter: u64) -> [u64; POSE_WORDS] {
        [self.t_ns, self.x_m.to_bits(), self.y_m.to_bits(), self.theta_rad.to_bits(), self.buttons as u64, counter]
    }
    fn decode(w: &[u64; POSE_WORDS]) -> Self {
        Self {
            t_ns: w[0],
            x_m: f64::from_bits(w[1]),
            y_m: f64::from_bits(w[2]),
            theta_rad: f64::from_bits(w[3]),
            buttons: w[4] as u32,
            counter: w[5],
        }
    }
}

impl ServerForce {
    fn encode(&self) -> [u64; FORCE_WORDS] {
        let mut w = [0u64; FORCE_WORDS];
        w[0] = self.t_ns;
        w[1] = self.tick;
        w[2] = self.force_n[0].to_bits();
        w[3] = self.force_n[1].to_bits();
        w[4] = self.torque_nm.to_bits();
        for (d, s) in w[5..14].iter_mut().zip(&self.stiffness) {
            *d = s.to_bits();
        }
        for (d, s) in w[14..17].iter_mut().zip(&self.base) {
            *d = s.to_bits();
        }
        w[17] = self.state as u64;
        w
    }
    fn decode(w: &[u64; FORCE_WORDS]) -> Self {
        let f = |i: usize| f64::from_bits(w[i]);
        Self {
            t_ns: w[0],
            tick: w[1],
            force_n: [f(2), f(3)],
            torque_nm: f(4),
            stiffness: std::array::from_fn(|i| f(5 + i)),
            base: [f(14), f(15), f(16)],
            state: w[17] as u32,
        }
    }
}

/// The mapping plus what a reader remembers about one slot.
struct Mapped {
    map: MmapRaw,
    path: PathBuf,
    generation: u64,
    /// (dev, ino) of the mapped file, to remove only our own file on drop.
    file_id: (u64, u64),
}

impl Mapped {
    fn layout(&self) -> &Layout {
        // SAFETY: the mapping is CHANNEL_SIZE bytes (checked before mapping), page-aligned (so
        // aligned for Layout), lives as long as self, and Layout consists only of atomics, which
        // are valid for any bit pattern and may be shared with other processes.
        unsafe { &*(self.map.as_ptr() as *const Layout) }
    }
}

#[derive(Default)]
struct ReaderState<T> {
    last_seq: u64,
    last: Option<T>,
    reads_since_fresh: u64,
}

fn read_slot<T: Copy, const N: usize>(slot: &Slot<N>, generation: u64, st: &mut ReaderState<T>, decode: fn(&[u64; N]) -> T) -> Sample<T> {
    let mut buf = [0u64; N];
    let status = match slot.read(&mut buf) {
        RawRead::Ok(seq, g) if seq != 0 && seq != st.last_seq && g == generation => {
            st.last_seq = seq;
            st.last = Some(decode(&buf));
            ReadStatus::Fresh
        }
        RawRead::Ok(..) => ReadStatus::Unchanged,
        RawRead::Contended => ReadStatus::Contended,
    };
    if status == ReadStatus::Fresh {
        st.reads_since_fresh = 0;
    } else {
        st.reads_since_fresh = st.reads_since_fresh.saturating_add(1);
    }
    Sample { value: st.last, status, reads_since_fresh: st.reads_since_fresh }
}

fn io_err<'a>(path: &'a Path, op: &'static str) -> impl FnOnce(io::Error) -> ShmError + 'a {
    move |source| ShmError::Io { path: path.to_path_buf(), op, source }
}

fn random_generation(previous: u64) -> u64 {
    let mut g = 0u64;
    // SAFETY: writes at most 8 bytes into g.
    let n = unsafe { libc::getrandom((&mut g as *mut u64).cast(), 8, 0) };
    if n != 8 {
        // Fallback: splitmix64 of time and pid.
        let mut z = monotonic_ns() ^ ((std::process::id() as u64) << 32) ^ 0x9E37_79B9_7F4A_7C15;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        g = z ^ (z >> 31);
    }
    if g == 0 || g == previous { random_generation(previous.wrapping_add(1)) } else { g }
}

/// Entry points: [`DeviceChannel::create`] (server) and [`DeviceChannel::attach`] (bridge).
pub struct DeviceChannel;

impl DeviceChannel {
    /// Server side: create (or take over) the channel file at `path`, mode 0600, and initialise it
    /// with a new random generation. A file left by a crashed server (or any file at the path) is
    /// truncated and re-initialised in place, so a bridge still attached to it sees the new
    /// generation and reports itself stale. Errors: [`ShmError::Io`] (open: missing directory,
    /// symlink, no permission; `fchmod`; `set_len`; `mmap`).
    pub fn create(path: impl AsRef<Path>) -> Result<ServerEnd, ShmError> {
        let path = path.as_ref();
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .mode(0o600)
            .custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC)
            .open(path)
            .map_err(io_err(path, "create"))?;
        // An existing file keeps its mode on open: force 0600.
        file.set_permissions(std::fs::Permissions::from_mode(0o600)).map_err(io_err(path, "fchmod"))?;
        file.set_len(CHANNEL_SIZE).map_err(io_err(path, "set_len"))?;
        let mapped = map(&file, path)?;
        let l = mapped.layout();
        let previous = l.header.generation.swap(0, Ordering::AcqRel);
        l.header.closed.store(0, Ordering::Relaxed);
        l.header.magic.store(u64::from_le_bytes(MAGIC), Ordering::Relaxed);
        l.header.version.store(LAYOUT_VERSION, Ordering::Relaxed);
        l.header._reserved0.store(0, Ordering::Relaxed);
        l.header.total_size.store(CHANNEL_SIZE, Ordering::Relaxed);
        l.header.creator_pid.store(std::process::id(), Ordering::Relaxed);
        l.header.attacher_pid.store(0, Ordering::Relaxed);
        l.pose.reset();
        l.force.reset();
        let generation = random_generation(previous);
        l.header.generation.store(generation, Ordering::Release);
        Ok(ServerEnd { m: Mapped { generation, ..mapped }, pose: ReaderState::default() })
    }

    /// Bridge side: open the channel the server created at `path`. Errors, in the order checked:
    /// [`ShmError::Missing`], [`ShmError::Io`] (open/fstat/mmap), [`ShmError::WrongSize`] (file
    /// length), [`ShmError::NotInitialised`] (generation 0, magic ours or still zero), [`ShmError::WrongMagic`],
    /// [`ShmError::WrongVersion`], [`ShmError::WrongHeaderSize`], [`ShmError::Closed`],
    /// [`ShmError::AlreadyAttached`] (another live process is the bridge).
    pub fn attach(path: impl AsRef<Path>) -> Result<DeviceEnd, ShmError> {
        let path = path.as_ref();
        let file = OpenOptions::new().read(true).write(true).custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC).open(path).map_err(|e| {
            match e.kind() {
                io::ErrorKind::NotFound => ShmError::Missing { path: path.to_path_buf() },
                _ => ShmError::Io { path: path.to_path_buf(), op: "open", source: e },
            }
        })?;
        let len = file.metadata().map_err(io_err(path, "fstat"))?.len();
        if len != CHANNEL_SIZE {
            return Err(ShmError::WrongSize { path: path.to_path_buf(), found: len, expected: CHANNEL_SIZE });
        }
        let mapped = map(&file, path)?;
        let h = &mapped.layout().header;
        let p = || path.to_path_buf();
        let generation = h.generation.load(Ordering::Acquire);
        let magic = h.magic.load(Ordering::Relaxed).to_le_bytes();
        // A file created but not yet initialised is all zeros (magic included).
        if generation == 0 && (magic == MAGIC || magic == [0; 8]) {
            return Err(ShmError::NotInitialised { path: p() });
        }
        if magic != MAGIC {
            return Err(ShmError::WrongMagic { path: p(), found: magic });
        }
        let version = h.version.load(Ordering::Relaxed);
        if version != LAYOUT_VERSION {
            return Err(ShmError::WrongVersion { path: p(), found: version, expected: LAYOUT_VERSION });
        }
        let size = h.total_size.load(Ordering::Relaxed);
        if size != CHANNEL_SIZE {
            return Err(ShmError::WrongHeaderSize { path: p(), found: size, expected: CHANNEL_SIZE });
        }
        if h.closed.load(Ordering::Acquire) != 0 {
            return Err(ShmError::Closed { path: p(), creator_pid: h.creator_pid.load(Ordering::Relaxed) });
        }
        let me = std::process::id();
        let mut current = h.attacher_pid.load(Ordering::Relaxed);
        loop {
            if current != 0 && current != me && pid_alive(current) {
                return Err(ShmError::AlreadyAttached { path: p(), pid: current });
            }
            match h.attacher_pid.compare_exchange(current, me, Ordering::AcqRel, Ordering::Relaxed) {
                Ok(_) => break,
                Err(now) => current = now,
            }
        }
        // Continue the pose counter of an earlier bridge of this generation, so it stays monotonic.
        let mut buf = [0u64; POSE_WORDS];
        let counter = match mapped.layout().pose.read(&mut buf) {
            RawRead::Ok(_, g) if g == generation => buf[5],
            _ => 0,
        };
        Ok(DeviceEnd { m: Mapped { generation, ..mapped }, counter, force: ReaderState::default() })
    }
}

fn map(file: &File, path: &Path) -> Result<Mapped, ShmError> {
    let meta = file.metadata().map_err(io_err(path, "fstat"))?;
    let map = MmapRaw::map_raw(file).map_err(io_err(path, "mmap"))?;
    Ok(Mapped { map, path: path.to_path_buf(), generation: 0, file_id: (meta.dev(), meta.ino()) })
}

/// The server's end: the session's real-time thread writes forces and reads poses.
/// Dropping it writes state [`ServerForce::STATE_CLOSING`], marks the header closed and removes the file.
pub struct ServerEnd {
    m: Mapped,
    pose: ReaderState<DevicePose>,
}

impl ServerEnd {
    /// Publish a force (single writer: this end). Never blocks; a few relaxed stores and fences.
    pub fn write_force_from_rt(&mut self, force: &ServerForce) {
        self.m.layout().force.write(self.m.generation, &force.encode());
    }

    /// The latest pose, fresh if the bridge wrote one since the previous call.
    pub fn read_pose_from_rt(&mut self) -> Sample<DevicePose> {
        read_slot(&self.m.layout().pose, self.m.generation, &mut self.pose, DevicePose::decode)
    }

    /// The bridge is alive: a pose arrived within the last `max_stale_reads` calls of
    /// [`Self::read_pose_from_rt`] and the attached pid (if any is recorded) exists.
    pub fn device_alive(&self, max_stale_reads: u64) -> bool {
        self.pose.last.is_some() && self.pose.reads_since_fresh <= max_stale_reads && self.attacher_pid().is_none_or(pid_alive)
    }

    /// The pid of the attached bridge, if one is attached (it may have died since: see [`pid_alive`]).
    pub fn attacher_pid(&self) -> Option<u32> {
        Some(self.m.layout().header.attacher_pid.load(Ordering::Relaxed)).filter(|&p| p != 0)
    }

    pub fn generation(&self) -> u64 {
        self.m.generation
    }

    pub fn path(&self) -> &Path {
        &self.m.path
    }
}

impl Drop for ServerEnd {
    fn drop(&mut self) {
        let l = self.m.layout();
        if l.header.generation.load(Ordering::Acquire) != self.m.generation {
            return; // someone re-created the channel in this file: it is no longer ours
        }
        let mut buf = [0u64; FORCE_WORDS];
        let mut f = match l.force.read(&mut buf) {
            RawRead::Ok(s, g) if s != 0 && g == self.m.generation => ServerForce::decode(&buf),
            _ => ServerForce::default(),
        };
        f.t_ns = monotonic_ns();
        f.state = ServerForce::STATE_CLOSING;
        self.write_force_from_rt(&f);
        let l = self.m.layout();
        l.header.closed.store(1, Ordering::Release);
        // Remove the file only if the path still names our file.
        if let Ok(meta) = std::fs::symlink_metadata(&self.m.path)
            && (meta.dev(), meta.ino()) == self.m.file_id
        {
            let _ = std::fs::remove_file(&self.m.path);
        }
    }
}

/// The bridge's end: the device thread writes poses and reads forces.
pub struct DeviceEnd {
    m: Mapped,
    counter: u64,
    force: ReaderState<ServerForce>,
}

impl DeviceEnd {
    /// Publish a pose (single writer: this end); stamps and returns the next counter (the caller's
    /// `counter` is ignored). `Err(Stale)` if the channel was re-created or closed: re-attach.
    pub fn write_pose_from_device(&mut self, pose: &DevicePose) -> Result<u64, Stale> {
        if !self.is_current() {
            return Err(Stale);
        }
        self.counter += 1;
        self.m.layout().pose.write(self.m.generation, &pose.encode(self.counter));
        Ok(self.counter)
    }

    /// The counter the next successful write will stamp, minus one (the last one written).
    pub fn pose_counter(&self) -> u64 {
        self.counter
    }

    /// The latest force, fresh if the server wrote one since the previous call;
    /// [`ReadStatus::Stale`] (value: the last good one) once the channel was re-created or closed.
    pub fn read_force_from_device(&mut self) -> Sample<ServerForce> {
        let mut s = read_slot(&self.m.layout().force, self.m.generation, &mut self.force, ServerForce::decode);
        if !self.is_current() {
            s.status = ReadStatus::Stale;
        }
        s
    }

    /// True while the channel is the one attached to: same generation, not closed.
    pub fn is_current(&self) -> bool {
        let h = &self.m.layout().header;
        h.generation.load(Ordering::Acquire) == self.m.generation && h.closed.load(Ordering::Acquire) == 0
    }

    /// The server is alive: the channel is current, a force arrived within the last
    /// `max_stale_reads` calls of [`Self::read_force_from_device`], its state is not closing, and the creator pid exists.
    pub fn server_alive(&self, max_stale_reads: u64) -> bool {
        self.is_current()
            && self.force.reads_since_fresh <= max_stale_reads
            && self.force.last.is_some_and(|f| f.state != ServerForce::STATE_CLOSING)
            && pid_alive(self.creator_pid())
    }

    pub fn creator_pid(&self) -> u32 {
        self.m.layout().header.creator_pid.load(Ordering::Relaxed)
    }

    pub fn generation(&self) -> u64 {
        self.m.generation
    }

    pub fn path(&self) -> &Path {
        &self.m.path
    }
}

impl Drop for DeviceEnd {
    fn drop(&mut self) {
        // Detach, so that another bridge may attach; a no-op if someone else has taken over or the
        // channel was re-created (this process may have re-attached to the new generation).
        if self.m.layout().header.generation.load(Ordering::Acquire) != self.m.generation {
            return;
        }
        let _ = self.m.layout().header.attacher_pid.compare_exchange(std::process::id(), 0, Ordering::AcqRel, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::FileExt;
    use std::sync::atomic::AtomicUsize;

    fn temp_path(name: &str) -> PathBuf {
        static N: AtomicUsize = AtomicUsize::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        std::env::temp_dir().join(format!("needlesim-shm-test-{}-{n}-{name}", std::process::id()))
    }

    fn patch(path: &Path, offset: u64, bytes: &[u8]) {
        OpenOptions::new().write(true).open(path).unwrap().write_all_at(bytes, offset).unwrap();
    }

    fn force(tick: u64) -> ServerForce {
        ServerForce {
            t_ns: monotonic_ns(),
            tick,
            force_n: [1.5, -2.5],
            torque_nm: 0.25,
            stiffness: std::array::from_fn(|i| i as f64 * 10.0 + tick as f64),
            base: [0.01, 0.02, 0.3],
            state: ServerForce::STATE_OK,
        }
    }

    #[test]
    fn round_trip_both_slots() {
        let path = temp_path("rt");
        let mut server = DeviceChannel::create(&path).unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.generation(), server.generation());
        assert_eq!(server.attacher_pid(), Some(std::process::id()));
        assert_eq!(device.creator_pid(), std::process::id());

        // Nothing written yet: no value, not fresh, not alive.
        let s = server.read_pose_from_rt();
        assert_eq!((s.value, s.status), (None, ReadStatus::Unchanged));
        assert!(!server.device_alive(10));
        let f = device.read_force_from_device();
        assert_eq!((f.value, f.status), (None, ReadStatus::Unchanged));
        assert!(!device.server_alive(10));

        for k in 1..=3u64 {
            let pose = DevicePose { t_ns: monotonic_ns(), x_m: 0.1 * k as f64, y_m: -0.2, theta_rad: 0.3, buttons: 0b101, counter: 999 };
            assert_eq!(device.write_pose_from_device(&pose).unwrap(), k);
            let s = server.read_pose_from_rt();
            assert!(s.fresh());
            assert_eq!(s.reads_since_fresh, 0);
            assert_eq!(s.value, Some(DevicePose { counter: k, ..pose }));
            let again = server.read_pose_from_rt();
            assert_eq!((again.status, again.value, again.reads_since_fresh), (ReadStatus::Unchanged, s.value, 1));
            assert!(server.device_alive(1));
            assert!(!server.device_alive(0));

            let fw = force(100 + k);
            server.write_force_from_rt(&fw);
            let f = device.read_force_from_device();
            assert!(f.fresh());
            assert_eq!(f.value, Some(fw));
            assert!(device.server_alive(0));
            let again = device.read_force_from_device();
            assert_eq!((again.status, again.value), (ReadStatus::Unchanged, Some(fw)));
        }
        assert!(device.is_current());

        // Closing: the bridge sees state 2 and a closed, removed channel.
        drop(server);
        assert!(!path.exists());
        let f = device.read_force_from_device();
        assert_eq!(f.status, ReadStatus::Stale);
        assert_eq!(f.value.unwrap().state, ServerForce::STATE_CLOSING);
        assert_eq!(f.value.unwrap().tick, 103);
        assert!(!device.is_current());
        assert!(!device.server_alive(10));
        assert_eq!(device.write_pose_from_device(&DevicePose::default()), Err(Stale));
    }

    #[test]
    fn stale_state_from_a_crashed_server_is_never_fresh() {
        let path = temp_path("stale");
        let mut old_server = DeviceChannel::create(&path).unwrap();
        let mut old_device = DeviceChannel::attach(&path).unwrap();
        old_server.write_force_from_rt(&force(7));
        old_device.write_pose_from_device(&DevicePose { x_m: 1.0, ..Default::default() }).unwrap();
        let old_generation = old_server.generation();
        std::mem::forget(old_server); // crash: no cleanup, the mapping and the file stay
        assert!(path.exists());

        // A crashed server of another (dead) pid left the file: pretend so.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead = child.id();
        child.wait().unwrap();
        patch(&path, 32, &dead.to_le_bytes());

        let mut server = DeviceChannel::create(&path).unwrap();
        assert_ne!(server.generation(), old_generation);
        assert_eq!(std::fs::metadata(&path).unwrap().len(), CHANNEL_SIZE);

        // The old bridge end notices and refuses to write.
        assert!(!old_device.is_current());
        assert_eq!(old_device.read_force_from_device().status, ReadStatus::Stale);
        assert!(!old_device.server_alive(u64::MAX));
        assert_eq!(old_device.write_pose_from_device(&DevicePose::default()), Err(Stale));

        // The new server sees no pose; a new bridge sees no force.
        let s = server.read_pose_from_rt();
        assert_eq!((s.value, s.status), (None, ReadStatus::Unchanged));
        let mut device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.pose_counter(), 0);
        let f = device.read_force_from_device();
        assert_eq!((f.value, f.status), (None, ReadStatus::Unchanged));

        // A late write from a bridge of the old generation (raced past its is_current check) is ignored.
        // SAFETY-free way to simulate it: write into the slot with the old generation directly.
        old_device.m.layout().pose.write(old_generation, &DevicePose { x_m: 9.0, ..Default::default() }.encode(5));
        assert!(!server.read_pose_from_rt().fresh());

        // The new pair works.
        device.write_pose_from_device(&DevicePose { x_m: 2.0, ..Default::default() }).unwrap();
        let s = server.read_pose_from_rt();
        assert!(s.fresh());
        assert_eq!(s.value.unwrap().x_m, 2.0);
        drop(old_device); // must not detach the new bridge
        assert_eq!(server.attacher_pid(), Some(std::process::id()));
    }

    #[test]
    fn create_over_a_copied_leftover_file() {
        // A file copied from a live channel (same bytes as a crashed server would leave).
        let src = temp_path("copy-src");
        let path = temp_path("copy-dst");
        let mut server = DeviceChannel::create(&src).unwrap();
        server.write_force_from_rt(&force(3));
        std::fs::copy(&src, &path).unwrap();
        let mut fresh = DeviceChannel::create(&path).unwrap();
        assert_ne!(fresh.generation(), server.generation());
        assert!(!fresh.read_pose_from_rt().fresh());
        let mut device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.read_force_from_device().value, None);
        fresh.write_force_from_rt(&force(4));
        assert_eq!(device.read_force_from_device().value.unwrap().tick, 4);
    }

    #[test]
    fn attach_errors_name_the_problem() {
        let missing = temp_path("missing");
        let e = DeviceChannel::attach(&missing).err().unwrap();
        assert!(matches!(e, ShmError::Missing { .. }), "{e}");
        let msg = e.to_string();
        assert!(msg.contains(&missing.display().to_string()) && msg.contains("no such file"), "{msg}");

        let short = temp_path("short");
        std::fs::write(&short, b"NDLSIMv1 too short").unwrap();
        let msg = DeviceChannel::attach(&short).err().unwrap().to_string();
        assert!(msg.contains(&short.display().to_string()) && msg.contains("is 18 bytes, expected 512"), "{msg}");

        let magic = temp_path("magic");
        let _server = DeviceChannel::create(&magic).unwrap();
        patch(&magic, 0, b"NOTMAGIC");
        let msg = DeviceChannel::attach(&magic).err().unwrap().to_string();
        assert!(msg.contains(&magic.display().to_string()) && msg.contains("wrong magic \"NOTMAGIC\""), "{msg}");

        let version = temp_path("version");
        let _server2 = DeviceChannel::create(&version).unwrap();
        patch(&version, 8, &7u32.to_le_bytes());
        let msg = DeviceChannel::attach(&version).err().unwrap().to_string();
        assert!(msg.contains(&version.display().to_string()) && msg.contains("layout version 7, this bridge speaks 1"), "{msg}");

        let zeros = temp_path("zeros");
        std::fs::write(&zeros, [0u8; 512]).unwrap();
        let msg = DeviceChannel::attach(&zeros).err().unwrap().to_string();
        assert!(msg.contains(&zeros.display().to_string()) && msg.contains("not initialised yet"), "{msg}");

        let busy = temp_path("busy");
        let _server3 = DeviceChannel::create(&busy).unwrap();
        patch(&busy, 36, &1u32.to_le_bytes()); // pid 1 is always alive
        let msg = DeviceChannel::attach(&busy).err().unwrap().to_string();
        assert!(msg.contains("already attached by live pid 1"), "{msg}");

        let closed = temp_path("closed");
        let server4 = DeviceChannel::create(&closed).unwrap();
        let keep = std::fs::read(&closed).unwrap();
        drop(server4);
        let mut closed_bytes = keep;
        closed_bytes[40] = 1;
        std::fs::write(&closed, &closed_bytes).unwrap();
        let msg = DeviceChannel::attach(&closed).err().unwrap().to_string();
        assert!(msg.contains("closed by the server"), "{msg}");

        for p in [short, zeros, closed] {
            let _ = std::fs::remove_file(p);
        }
    }

    #[test]
    fn file_mode_is_0600_even_over_an_existing_file() {
        let path = temp_path("mode");
        std::fs::write(&path, b"x").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o666)).unwrap();
        let _server = DeviceChannel::create(&path).unwrap();
        let meta = std::fs::metadata(&path).unwrap();
        assert_eq!(meta.permissions().mode() & 0o777, 0o600);
        assert_eq!(meta.len(), CHANNEL_SIZE);
        let path2 = temp_path("mode-new");
        let _server2 = DeviceChannel::create(&path2).unwrap();
        assert_eq!(std::fs::metadata(&path2).unwrap().permissions().mode() & 0o777, 0o600);
    }

    #[test]
    fn a_writer_that_died_mid_write_does_not_wedge_the_slot() {
        let path = temp_path("odd");
        let mut server = DeviceChannel::create(&path).unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        device.write_pose_from_device(&DevicePose { x_m: 1.0, ..Default::default() }).unwrap();
        assert!(server.read_pose_from_rt().fresh());
        server.m.layout().pose.seq.fetch_add(1, Ordering::Relaxed); // odd: a write in progress forever
        let s = server.read_pose_from_rt();
        assert_eq!(s.status, ReadStatus::Contended);
        assert_eq!(s.value.unwrap().x_m, 1.0);
        drop(device);
        let mut device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.pose_counter(), 0); // the slot was mid-write: counter not readable, restart
        device.write_pose_from_device(&DevicePose { x_m: 2.0, ..Default::default() }).unwrap();
        let s = server.read_pose_from_rt();
        assert!(s.fresh());
        assert_eq!(s.value.unwrap().x_m, 2.0);
    }

    #[test]
    fn reattach_continues_the_counter_and_pid_alive_works() {
        let path = temp_path("reattach");
        let mut server = DeviceChannel::create(&path).unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        for _ in 0..5 {
            device.write_pose_from_device(&DevicePose::default()).unwrap();
        }
        drop(device);
        assert_eq!(server.attacher_pid(), None);
        let mut device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.write_pose_from_device(&DevicePose::default()).unwrap(), 6);
        assert_eq!(server.read_pose_from_rt().value.unwrap().counter, 6);

        assert!(pid_alive(std::process::id()));
        assert!(pid_alive(1));
        assert!(!pid_alive(0));
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        assert!(!pid_alive(pid));
    }
}
