//! The shared-memory channel between a session's real-time thread (server process) and the device bridge process on the same host.
//!
//! One memory-mapped file with a fixed, versioned layout, created by the server side
//! ([`DeviceChannel::create`] → [`ServerEnd`], mode 0600) and opened by the bridge
//! ([`DeviceChannel::attach`] → [`DeviceEnd`]). It holds two single-writer slots, each a seqlock:
//! device → server ([`DevicePose`]) and server → device ([`ServerForce`]). Neither side ever
//! blocks: a read retries a bounded number of times and otherwise returns the last good value.
//!
//! # Layout (little-endian, [`LAYOUT_VERSION`] 3, [`CHANNEL_SIZE`] = 768 bytes)
//!
//! Every field is a naturally aligned `u32`/`u64` accessed only through atomics; `f64`s are stored
//! as their bit patterns, `u32`s of the slots in the low half of a `u64` word. Blocks are 128-byte
//! aligned so the two slots never share a cache line (nor an adjacent-line prefetch pair). Frames,
//! units and the pose perturbation of the stiffness are those of [`crate::spatial`].
//!
//! | offset | size | field |
//! |-------:|-----:|-------|
//! | 0   | 8 | magic `b"NDLSIMv1"` |
//! | 8   | 4 | layout version (`u32`) |
//! | 12  | 4 | owner lock (`u32`): [`OWNER_LOCK`] when the creator holds a shared `flock` on the file for the life of its end; 0 in files of earlier builds |
//! | 16  | 8 | total size in bytes (`u64`, 768) |
//! | 24  | 8 | generation (`u64`, random, never 0; 0 while `create` is initialising) |
//! | 32  | 4 | creator pid (`u32`) |
//! | 36  | 4 | attacher pid (`u32`, 0 when no bridge is attached) |
//! | 40  | 4 | closed (`u32`, 1 once the server end was dropped) |
//! | 44  | 4 | session dimension (`u32`, 2 or 3: [`Dimension`]) |
//! | 48  | 8 | tick origin (`u64`): `CLOCK_MONOTONIC` ns of the session's tick 0 deadline; 0 until published |
//! | 56  | 8 | tick period (`u64`, ns; valid once the origin is not 0) |
//! | 64  | 64 | reserved (0) |
//! | 128 | 8 | pose slot: sequence (odd while being written, even when done, 0 = never written) |
//! | 136 | 8 | pose slot: generation of the writer |
//! | 144 | 80 | pose: `t_ns`, `position_m[3]` (m, world), `orientation[4]` (unit quaternion w, x, y, z: body → world), `buttons`, `counter` (one `u64` word each) |
//! | 224 | 32 | reserved (0) |
//! | 256 | 8 | force slot: sequence |
//! | 264 | 8 | force slot: generation of the writer |
//! | 272 | 424 | force: `t_ns`, `tick`, `force_n[3]` (N, world, on the base point), `torque_nm[3]` (N·m, world, about the base point), `stiffness[36]` (6×6 row-major, `∂(F, τ)/∂(δp, δθ)`: N/m, N/rad, N·m/m, N·m/rad), `base_position_m[3]`, `base_orientation[4]` (the pose the wrench was computed at), `state`, `pose_counter` |
//! | 696 | 72 | reserved (0) |
//!
//! Version 2 added the tick phase (the session's tick deadlines are `origin + k·period` on
//! `CLOCK_MONOTONIC`: [`ServerEnd::publish_schedule_from_rt`], [`DeviceEnd::server_schedule`]), so
//! that a bridge can write each pose just before the tick that uses it, and the force's
//! `pose_counter` (the counter of the device pose the force was computed from), so that a bridge
//! knows which of its poses a force answers.
//!
//! Version 3 (the 6-DOF channel of issue 17, which calls it "layout version 2": the number 2 was
//! already taken by the tick phase) replaced the planar pose `(x, y, θ)` and wrench `(Fx, Fy, τ)`
//! with a 6-DOF pose (position + unit quaternion) and wrench (force + torque), the 3×3 stiffness
//! with the 6×6 and the planar base with a 6-DOF one, and added the session's dimension. A 2D
//! session rides on it unchanged in behaviour through the planar embedding of [`crate::spatial`]
//! ([`DevicePose::planar`], [`DevicePose::to_planar`], [`ServerForce::set_planar`],
//! [`ServerForce::to_planar`]). Peers of different versions refuse each other at attach: this
//! build's [`DeviceChannel::attach`] recognises a file of version 1 or 2 (magic and version, though
//! its size differs) and fails with [`ShmError::WrongVersion`] naming both versions; a bridge of an
//! earlier release attaching to a version-3 file fails on its size check ("file is 768 bytes,
//! expected 512"), never reading the new layout as the old.
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
//! # Files left behind (issue 35)
//!
//! The file outlives its processes: a server that dies without dropping its end (`kill -9`, a
//! crash) leaves it. Its creator therefore holds a shared `flock` on the file from `create` until
//! its end (and every watch handle) is dropped, and says so in the header ([`OWNER_LOCK`]); locks
//! die with their process and work across pid namespaces, so [`remove_stale_channels`] (a server
//! calls it at start-up) can tell a dead creator's file, which nobody holds, from a live one's. A
//! bridge that sees its server die removes the file itself ([`DeviceEnd::remove_if_orphaned`]).
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
//!
//! # A channel whose file changes under it (issue 13)
//!
//! The file lives in a world-visible directory (/dev/shm), so anything running as the same user
//! can truncate, shrink, grow, overwrite, delete or replace it while both processes have it
//! mapped. A truncated file makes the next access to its mapped page raise `SIGBUS`, which by
//! default kills the whole server (every session) and the bridge before it can zero its device.
//! Neither end may ever fault, whatever happens to the file; a broken channel is reported as
//! [`Broken`] ([`ReadStatus::Broken`], [`ServerEnd::broken`], [`DeviceEnd::broken`]) and stays
//! broken for the life of the end.
//!
//! - **Faults are contained.** A process-wide `SIGBUS` handler (`sigaction`, `SA_SIGINFO`,
//!   installed once on the first create/attach) looks the faulting address (`si_addr`) up in a
//!   lock-free registry of this process's channel mappings (a fixed static array of
//!   [`MAX_MAPPINGS`] slots of atomics: start, length, faulted). If it lies in one, the handler maps
//!   anonymous zero pages over that mapping (`mmap(MAP_FIXED | MAP_PRIVATE | MAP_ANONYMOUS)`, a
//!   plain system call, async-signal-safe in practice), sets the slot's faulted flag and returns:
//!   the faulting access is retried on the zero page and completes. A fault anywhere else is
//!   passed to the previous handler (Rust's stack-overflow handler, which resets the default and
//!   lets the access fault again) or, with none, the default action is restored so genuine bugs
//!   still kill the process with `SIGBUS`. The technique is the one Wayland compositors use for
//!   clients' `wl_shm` pools (weston, wlroots). A mapping is registered before its first access and
//!   unregistered before it is unmapped. Checking the file size before each access alone would
//!   not do: a truncation between the check and the access still faults. (Sealing the memory
//!   against shrinking, `memfd` + `F_SEAL_SHRINK`, would avoid the fault altogether, but a sealable
//!   memfd has no path a bridge can open; the channel is a named file by design.)
//! - **Every access validates.** Each read and write first checks, with a few relaxed loads, the
//!   faulted flag, the broken state and the header (magic, version, size; on the server end also
//!   its own generation). A garbage-filled header is noticed at the next access.
//! - **The file is watched.** What does not fault or touch the header (a deleted file, another
//!   file renamed over the path, a file shrunk within its first page or grown) is found by
//!   [`ChannelWatch::check_file`]: the path still names the mapped inode (`stat` vs. the held
//!   descriptor's dev/ino) and the held descriptor's file is still [`CHANNEL_SIZE`] bytes. It
//!   makes system calls, so it runs on a non-real-time thread every [`WATCH_PERIOD`] (the server's
//!   per-session watcher, the bridge's watcher thread); it publishes through an atomic that the
//!   real-time side reads.
//! - **Neither end trusts a broken channel.** The server end stops taking poses and writing
//!   forces (the session marks its device stale and holds the needle); the device end reports
//!   itself not current, so the bridge ramps its force to zero, writes a zero wrench and exits with
//!   an error naming the cause. Dropping a broken server end removes the file only if the path
//!   still names the file it created.

use std::fs::{File, OpenOptions};
use std::io;
use std::mem::{offset_of, size_of};
use std::os::unix::fs::{FileExt, MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, AtomicUsize, Ordering, fence};
use std::time::Duration;

use memmap2::{MmapOptions, MmapRaw};

/// The 8 magic bytes at offset 0.
pub const MAGIC: [u8; 8] = *b"NDLSIMv1";
/// The layout version at offset 8; bump it on any change of the layout.
pub const LAYOUT_VERSION: u32 = 3;
/// The size of the channel file in bytes.
pub const CHANNEL_SIZE: u64 = size_of::<Layout>() as u64;
/// How many times a read retries while the writer is mid-write before giving up (≈ a few µs).
pub const READ_RETRIES: u32 = 64;
/// Channel mappings one process can hold at once (slots of the `SIGBUS` registry; the handler scans them all).
pub const MAX_MAPPINGS: usize = 1024;
/// The header's owner-lock word in a channel whose creator holds a shared `flock` on its file for
/// as long as its end lives ([`remove_stale_channels`]).
pub const OWNER_LOCK: u32 = 1;
/// The file name of a session's channel is this prefix and the session id (12 lowercase hex digits).
pub const CHANNEL_FILE_PREFIX: &str = "needlesim-";
/// How often a watcher should call [`ChannelWatch::check_file`].
pub const WATCH_PERIOD: Duration = Duration::from_millis(100);

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
    /// `attach`: the layout version differs (server and bridge built from different layouts; an
    /// earlier layout is recognised by its magic and version even though its size differs).
    #[error("device channel {path}: layout version {found} ({}), this bridge speaks {expected} ({}): server and bridge are from different releases", layout_name(*found), layout_name(*expected))]
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
    /// `create`/`attach`: this process already holds [`MAX_MAPPINGS`] channel mappings (the `SIGBUS` registry is full).
    #[error("device channel {path}: this process already maps {max} channels", max = MAX_MAPPINGS)]
    TooManyChannels { path: PathBuf },
    /// `create`/`attach`: the file changed under the new mapping while it was being set up (e.g. truncated).
    #[error("device channel {path}: {cause}")]
    Broken { path: PathBuf, cause: Broken },
}

/// What a layout version carried, for [`ShmError::WrongVersion`].
fn layout_name(version: u32) -> &'static str {
    match version {
        1 => "2D pose and wrench",
        2 => "2D pose and wrench, tick phase",
        3 => "6-DOF pose, wrench and 6x6 stiffness, session dimension",
        _ => "unknown to this build",
    }
}

/// The channel is stale (the server re-created it, with a new generation, or closed it: re-attach)
/// or broken (see [`DeviceEnd::broken`]: give up).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("device channel is stale (re-created or closed by the server) or broken")]
pub struct Stale;

/// Why a channel is broken: its file was changed by someone else, or (device end) the server that
/// created it died. Once broken, an end stays broken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Broken {
    /// An access to the mapping raised `SIGBUS` (the file was truncated below the page touched);
    /// the mapping now holds anonymous zeros.
    #[error("its file was truncated under the mapping (an access faulted)")]
    Faulted,
    /// [`ChannelWatch::check_file`]: the mapped file is no longer [`CHANNEL_SIZE`] bytes (truncated, shrunk or grown).
    #[error("its file is now {found_bytes} bytes, expected {expected} (truncated or resized)", expected = CHANNEL_SIZE)]
    Resized { found_bytes: u64 },
    /// [`ChannelWatch::check_file`]: no file at the path any more (deleted).
    #[error("its file was deleted")]
    Deleted,
    /// [`ChannelWatch::check_file`]: the path names another file now (renamed over, or deleted and re-created).
    #[error("its file was replaced by another file at the same path")]
    Replaced,
    /// Any access: the header's magic, version or size field is not this layout's (overwritten with
    /// garbage); on the server end also: the generation is not its own (re-initialised by someone else).
    #[error("its header was overwritten (garbage in magic, version, size or generation)")]
    BadHeader,
    /// [`ChannelWatch::check_server`] (device end): the server process that created the channel,
    /// identified at attach, is gone (killed, crashed: it never closed the channel).
    #[error("the server (pid {pid}) that created it died without closing it")]
    ServerDied { pid: u32 },
}

impl Broken {
    /// As stored in an `AtomicU64`: the cause in the low byte, a resized file's length above it. Never 0.
    fn encode(self) -> u64 {
        match self {
            Broken::Faulted => 1,
            Broken::Resized { found_bytes } => 2 | (found_bytes.min(u64::MAX >> 8) << 8),
            Broken::Deleted => 3,
            Broken::Replaced => 4,
            Broken::BadHeader => 5,
            Broken::ServerDied { pid } => 6 | (u64::from(pid) << 8),
        }
    }

    fn decode(code: u64) -> Option<Broken> {
        Some(match code & 0xff {
            0 => return None,
            1 => Broken::Faulted,
            2 => Broken::Resized { found_bytes: code >> 8 },
            3 => Broken::Deleted,
            4 => Broken::Replaced,
            6 => Broken::ServerDied { pid: (code >> 8) as u32 },
            _ => Broken::BadHeader,
        })
    }
}

/// The dimension of the session behind a channel (header field): what the bridge drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// A 2D session: it reads the planar part of the pose (x, y and the twist about z; see
    /// [`crate::spatial`]) and answers with the planar wrench and stiffness embedded in the 6-DOF fields.
    Two = 2,
    /// A 3D session: the full 6-DOF pose and wrench.
    Three = 3,
}

impl Dimension {
    fn from_u32(v: u32) -> Option<Self> {
        match v {
            2 => Some(Self::Two),
            3 => Some(Self::Three),
            _ => None,
        }
    }
}

/// The device's pose, written by the bridge once per device sample (frames and units: [`crate::spatial`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DevicePose {
    /// `CLOCK_MONOTONIC` of the writer when sampled, ns ([`monotonic_ns`]).
    pub t_ns: u64,
    /// The base point (the hand) in the world frame, m.
    pub position_m: [f64; 3],
    /// Unit quaternion `(w, x, y, z)`: the needle's body frame → world.
    pub orientation: [f64; 4],
    /// A bit per button, 1 = pressed.
    pub buttons: u32,
    /// Incremented by every write (stamped by [`DeviceEnd::write_pose_from_device`]; the caller's
    /// value is ignored): a counter that stops advancing means a dead bridge.
    pub counter: u64,
}

impl Default for DevicePose {
    /// At the origin, identity orientation, no button, time and counter 0.
    fn default() -> Self {
        Self { t_ns: 0, position_m: [0.0; 3], orientation: crate::spatial::IDENTITY, buttons: 0, counter: 0 }
    }
}

impl DevicePose {
    /// The 2D pose `(x_m, y_m, theta_rad)` embedded as `(x, y, 0)` and a rotation θ about +z.
    pub fn planar(t_ns: u64, q: [f64; 3], buttons: u32) -> Self {
        let (position_m, orientation) = crate::spatial::pose_from_planar(q);
        Self { t_ns, position_m, orientation, buttons, counter: 0 }
    }

    /// The 2D pose `(x_m, y_m, theta_rad)`: x, y and the twist about z ([`crate::spatial::pose_to_planar`]).
    pub fn to_planar(&self) -> [f64; 3] {
        crate::spatial::pose_to_planar(self.position_m, self.orientation)
    }
}

/// The wrench the tissue exerts, written by the session's real-time thread once per tick
/// (frames and units: [`crate::spatial`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServerForce {
    /// `CLOCK_MONOTONIC` of the writer, ns.
    pub t_ns: u64,
    /// The real-time loop's tick.
    pub tick: u64,
    /// Force on the base point, world frame, N.
    pub force_n: [f64; 3],
    /// Torque about the base point, world frame, N·m.
    pub torque_nm: [f64; 3],
    /// `K = ∂(F, τ)/∂δ` with `δ = (δp, δθ)` the perturbation of the base pose (translation, m, and
    /// a world rotation vector applied as `R ← exp(δθ̂)R`, rad): `stiffness[row][col]`, rows
    /// (Fx, Fy, Fz, τx, τy, τz), columns (δx, δy, δz, δθx, δθy, δθz); blocks in N/m, N/rad, N·m/m, N·m/rad.
    pub stiffness: [[f64; 6]; 6],
    /// The base pose the wrench was computed at: position (m, world) …
    pub base_position_m: [f64; 3],
    /// … and orientation (unit quaternion `(w, x, y, z)`).
    pub base_orientation: [f64; 4],
    /// [`ServerForce::STATE_OK`], [`ServerForce::STATE_DEVICE_STALE`] or [`ServerForce::STATE_CLOSING`].
    pub state: u32,
    /// The [`DevicePose::counter`] of the device pose this force was computed from; 0 when the
    /// tick used no device pose (a client's pose, or the needle held).
    pub pose_counter: u64,
}

impl Default for ServerForce {
    /// Zero wrench and stiffness at the origin (identity orientation), state OK, tick and counter 0.
    fn default() -> Self {
        Self {
            t_ns: 0,
            tick: 0,
            force_n: [0.0; 3],
            torque_nm: [0.0; 3],
            stiffness: [[0.0; 6]; 6],
            base_position_m: [0.0; 3],
            base_orientation: crate::spatial::IDENTITY,
            state: Self::STATE_OK,
            pose_counter: 0,
        }
    }
}

impl ServerForce {
    /// Sets the wrench, stiffness and base pose from their 2D forms: wrench `(Fx, Fy, τ)` (N, N,
    /// N·m), stiffness `∂(Fx, Fy, τ)/∂(x, y, θ)` (3×3 row-major) and base `(x, y, θ)` (the planar
    /// embedding of [`crate::spatial`]; every other component 0).
    pub fn set_planar(&mut self, wrench: [f64; 3], stiffness: &[f64; 9], base: [f64; 3]) {
        self.force_n = [wrench[0], wrench[1], 0.0];
        self.torque_nm = [0.0, 0.0, wrench[2]];
        self.stiffness = crate::spatial::embed_planar_stiffness(stiffness);
        (self.base_position_m, self.base_orientation) = crate::spatial::pose_from_planar(base);
    }

    /// The 2D forms: (wrench `(Fx, Fy, τz)`, stiffness 3×3 on (x, y, θz), base `(x, y, θ)`), the inverse of [`Self::set_planar`].
    pub fn to_planar(&self) -> ([f64; 3], [f64; 9], [f64; 3]) {
        (
            [self.force_n[0], self.force_n[1], self.torque_nm[2]],
            crate::spatial::restrict_planar_stiffness(&self.stiffness),
            crate::spatial::pose_to_planar(self.base_position_m, self.base_orientation),
        )
    }

    /// The wrench `(Fx, Fy, Fz, τx, τy, τz)`.
    pub fn wrench(&self) -> [f64; 6] {
        let (f, t) = (self.force_n, self.torque_nm);
        [f[0], f[1], f[2], t[0], t[1], t[2]]
    }
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
    /// The channel is broken ([`Broken`]): nothing was read; `value` is the last good one.
    Broken,
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

/// Takes a shared `flock` on the channel file (the creator's mark: [`OWNER_LOCK`]). Shared, so
/// that a channel re-created in place while an earlier end still holds the file is marked by both;
/// a sweep holds an exclusive lock for a few system calls, so a busy lock is retried for up to 100 ms.
fn lock_shared(file: &File) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    for _ in 0..100 {
        // SAFETY: flock on a descriptor this function borrows; no memory is passed.
        if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_SH | libc::LOCK_NB) } == 0 {
            return Ok(());
        }
        let e = io::Error::last_os_error();
        match e.raw_os_error() {
            Some(libc::EINTR) => {}
            Some(libc::EWOULDBLOCK) => std::thread::sleep(Duration::from_millis(1)),
            _ => return Err(e),
        }
    }
    Err(io::Error::from_raw_os_error(libc::EWOULDBLOCK))
}

/// True for the name of a session's channel file: [`CHANNEL_FILE_PREFIX`] and 12 lowercase hex digits.
pub fn is_channel_file_name(name: &str) -> bool {
    name.strip_prefix(CHANNEL_FILE_PREFIX)
        .is_some_and(|id| id.len() == 12 && id.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b)))
}

/// What [`remove_stale_channels`] found.
#[derive(Debug, Default)]
pub struct Sweep {
    /// The stale channel files removed.
    pub removed: Vec<PathBuf>,
    /// Channel files left because a live process owns or maps them.
    pub live: usize,
    /// Files that could not be examined or removed, with the reason.
    pub errors: Vec<(PathBuf, io::Error)>,
}

/// Removes the channel files in `dir` that this user owns and whose creator is gone (issue 35: a
/// server killed with `kill -9`, or a crash, leaves its sessions' files in /dev/shm, which outlives
/// processes). A server calls it at start-up on its device directory. A file is removed only if
/// all of these hold:
/// - its name is a session channel's ([`is_channel_file_name`]), it is a regular file (not a link)
///   owned by this process's effective user, and its first 8 bytes are [`MAGIC`];
/// - nobody holds a lock on it (an exclusive `flock` is taken, and held while it is removed): every
///   live end created by this build holds a shared one ([`OWNER_LOCK`]), whatever pid namespace
///   its process runs in;
/// - a file without the owner-lock mark (written by an earlier build, which took no lock): no
///   process visible here maps it (`/proc/*/maps`). An earlier build's live server in another pid
///   namespace sharing the directory is invisible here: its channel would be taken for stale (the
///   one case this cannot tell);
/// - the path still names the file examined.
///
/// With `creator` set, only files whose header names that creator pid are considered (a test
/// harness cleaning up after the server it killed). Files of other names, other users, other
/// formats, and live channels are never touched. Makes system calls: not for a real-time thread.
pub fn remove_stale_channels(dir: &Path, creator: Option<u32>) -> io::Result<Sweep> {
    let mut sweep = Sweep::default();
    for entry in std::fs::read_dir(dir)? {
        let Ok(entry) = entry else { continue };
        let path = entry.path();
        if !entry.file_name().to_str().is_some_and(is_channel_file_name) {
            continue;
        }
        match remove_if_stale(&path, creator) {
            Ok(Some(true)) => sweep.removed.push(path),
            Ok(Some(false)) => sweep.live += 1,
            Ok(None) => {}
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => sweep.errors.push((path, e)),
        }
    }
    Ok(sweep)
}

/// One file of [`remove_stale_channels`]: `Some(true)` removed, `Some(false)` live, `None` not a
/// channel of this user (or of `creator`).
fn remove_if_stale(path: &Path, creator: Option<u32>) -> io::Result<Option<bool>> {
    use std::os::fd::AsRawFd;
    let meta = std::fs::symlink_metadata(path)?;
    // SAFETY: geteuid has no preconditions.
    if !meta.file_type().is_file() || meta.uid() != unsafe { libc::geteuid() } {
        return Ok(None);
    }
    let file = OpenOptions::new().read(true).custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC | libc::O_NONBLOCK).open(path)?;
    let held = file.metadata()?;
    let mut head = [0u8; 40];
    if held.len() < head.len() as u64 || file.read_exact_at(&mut head, 0).is_err() || head[..8] != MAGIC {
        return Ok(None);
    }
    let word = |at: usize| u32::from_le_bytes([head[at], head[at + 1], head[at + 2], head[at + 3]]);
    if creator.is_some_and(|pid| word(32) != pid) {
        return Ok(None);
    }
    // SAFETY: flock on a descriptor this function owns; no memory is passed.
    if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } != 0 {
        let e = io::Error::last_os_error();
        return if e.raw_os_error() == Some(libc::EWOULDBLOCK) { Ok(Some(false)) } else { Err(e) };
    }
    let marked = word(8) == LAYOUT_VERSION && word(12) == OWNER_LOCK;
    if !marked && crate::liveness::mapped_by_a_visible_process(held.dev(), held.ino()) {
        return Ok(Some(false));
    }
    // Still the file examined (not replaced meanwhile): remove it while the lock is held.
    match std::fs::symlink_metadata(path) {
        Ok(now) if (now.dev(), now.ino()) == (held.dev(), held.ino()) => std::fs::remove_file(path).map(|()| Some(true)),
        Ok(_) => Ok(None),
        Err(e) => Err(e),
    }
}

// ---------------------------------------------------------------------------------------------
// Layout

#[repr(C, align(128))]
struct Header {
    magic: AtomicU64,
    version: AtomicU32,
    owner_lock: AtomicU32,
    total_size: AtomicU64,
    generation: AtomicU64,
    creator_pid: AtomicU32,
    attacher_pid: AtomicU32,
    closed: AtomicU32,
    dimension: AtomicU32,
    tick_origin_ns: AtomicU64,
    tick_period_ns: AtomicU64,
}

const POSE_WORDS: usize = 10;
const FORCE_WORDS: usize = 53;

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
    assert!(size_of::<Layout>() == 768);
    assert!(offset_of!(Layout, header) == 0);
    assert!(offset_of!(Header, version) == 8);
    assert!(offset_of!(Header, owner_lock) == 12);
    assert!(offset_of!(Header, total_size) == 16);
    assert!(offset_of!(Header, generation) == 24);
    assert!(offset_of!(Header, creator_pid) == 32);
    assert!(offset_of!(Header, attacher_pid) == 36);
    assert!(offset_of!(Header, closed) == 40);
    assert!(offset_of!(Header, dimension) == 44);
    assert!(offset_of!(Header, tick_origin_ns) == 48);
    assert!(offset_of!(Header, tick_period_ns) == 56);
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
    /// Words: `t_ns`, `position_m[3]`, `orientation[4]`, `buttons`, `counter`.
    fn encode(&self, counter: u64) -> [u64; POSE_WORDS] {
        let mut w = [0u64; POSE_WORDS];
        w[0] = self.t_ns;
        for (d, s) in w[1..4].iter_mut().zip(&self.position_m) {
            *d = s.to_bits();
        }
        for (d, s) in w[4..8].iter_mut().zip(&self.orientation) {
            *d = s.to_bits();
        }
        w[8] = self.buttons as u64;
        w[9] = counter;
        w
    }
    fn decode(w: &[u64; POSE_WORDS]) -> Self {
        let f = |i: usize| f64::from_bits(w[i]);
        Self { t_ns: w[0], position_m: [f(1), f(2), f(3)], orientation: [f(4), f(5), f(6), f(7)], buttons: w[8] as u32, counter: w[9] }
    }
}

/// The pose slot's word holding the counter.
const POSE_COUNTER_WORD: usize = 9;

impl ServerForce {
    /// Words: `t_ns`, `tick`, `force_n[3]`, `torque_nm[3]`, `stiffness[36]` (row-major),
    /// `base_position_m[3]`, `base_orientation[4]`, `state`, `pose_counter`.
    fn encode(&self) -> [u64; FORCE_WORDS] {
        let mut w = [0u64; FORCE_WORDS];
        w[0] = self.t_ns;
        w[1] = self.tick;
        let floats = self
            .force_n
            .iter()
            .chain(&self.torque_nm)
            .chain(self.stiffness.iter().flatten())
            .chain(&self.base_position_m)
            .chain(&self.base_orientation);
        for (d, s) in w[2..51].iter_mut().zip(floats) {
            *d = s.to_bits();
        }
        w[51] = self.state as u64;
        w[52] = self.pose_counter;
        w
    }
    fn decode(w: &[u64; FORCE_WORDS]) -> Self {
        let f = |i: usize| f64::from_bits(w[i]);
        Self {
            t_ns: w[0],
            tick: w[1],
            force_n: [f(2), f(3), f(4)],
            torque_nm: [f(5), f(6), f(7)],
            stiffness: std::array::from_fn(|r| std::array::from_fn(|c| f(8 + 6 * r + c))),
            base_position_m: [f(44), f(45), f(46)],
            base_orientation: [f(47), f(48), f(49), f(50)],
            state: w[51] as u32,
            pose_counter: w[52],
        }
    }
}

// ---------------------------------------------------------------------------------------------
// SIGBUS containment (see the module docs)

/// One registered mapping: `start == 0` marks a free slot.
struct FaultSlot {
    start: AtomicUsize,
    len: AtomicUsize,
    faulted: AtomicBool,
}

#[allow(clippy::declare_interior_mutable_const)] // each array element is its own slot
const FREE_SLOT: FaultSlot = FaultSlot { start: AtomicUsize::new(0), len: AtomicUsize::new(0), faulted: AtomicBool::new(false) };
static REGISTRY: [FaultSlot; MAX_MAPPINGS] = [FREE_SLOT; MAX_MAPPINGS];

/// The `SIGBUS` action found when the handler was installed, to chain to for faults not ours.
struct PrevAction(std::cell::UnsafeCell<std::mem::MaybeUninit<libc::sigaction>>);
// SAFETY: written once, before PREV_READY is set (release) and before our handler is installed;
// only read after PREV_READY was seen set (acquire).
unsafe impl Sync for PrevAction {}
static PREV: PrevAction = PrevAction(std::cell::UnsafeCell::new(std::mem::MaybeUninit::uninit()));
static PREV_READY: AtomicBool = AtomicBool::new(false);
static INSTALLED: std::sync::OnceLock<Result<(), i32>> = std::sync::OnceLock::new();

fn page_size() -> usize {
    // SAFETY: sysconf has no preconditions.
    let p = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    if p > 0 { p as usize } else { 4096 }
}

/// Installs the process-wide `SIGBUS` handler once; the result of that one attempt (an errno on failure).
fn install_sigbus_handler() -> Result<(), i32> {
    *INSTALLED.get_or_init(|| {
        // SAFETY: plain sigaction calls with valid pointers; PREV is written before PREV_READY and
        // before our handler can run.
        unsafe {
            let mut old: libc::sigaction = std::mem::zeroed();
            if libc::sigaction(libc::SIGBUS, std::ptr::null(), &mut old) != 0 {
                return Err(io::Error::last_os_error().raw_os_error().unwrap_or(0));
            }
            (*PREV.0.get()).write(old);
            PREV_READY.store(true, Ordering::Release);
            let mut sa: libc::sigaction = std::mem::zeroed();
            sa.sa_sigaction = on_sigbus as *const () as libc::sighandler_t;
            sa.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK | libc::SA_RESTART;
            libc::sigemptyset(&mut sa.sa_mask);
            if libc::sigaction(libc::SIGBUS, &sa, std::ptr::null_mut()) != 0 {
                return Err(io::Error::last_os_error().raw_os_error().unwrap_or(0));
            }
        }
        Ok(())
    })
}

/// The `SIGBUS` handler: async-signal-safe (atomics, `mmap`, `sigaction`, `raise`; errno preserved).
extern "C" fn on_sigbus(sig: libc::c_int, info: *mut libc::siginfo_t, ctx: *mut libc::c_void) {
    // SAFETY: errno is thread-local; info is the kernel's siginfo for this signal.
    unsafe {
        let errno = *libc::__errno_location();
        // Only a fault raised by the kernel (si_code > 0) carries an address; a SIGBUS sent by kill
        // (si_code <= 0) is never ours.
        if !info.is_null() && (*info).si_code > 0 {
            let addr = (*info).si_addr() as usize;
            for slot in &REGISTRY {
                let start = slot.start.load(Ordering::Acquire);
                if start == 0 {
                    continue;
                }
                let len = slot.len.load(Ordering::Acquire);
                if addr >= start && addr - start < len {
                    let p = libc::mmap(
                        start as *mut libc::c_void,
                        len,
                        libc::PROT_READ | libc::PROT_WRITE,
                        libc::MAP_FIXED | libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                        -1,
                        0,
                    );
                    if p as usize == start {
                        slot.faulted.store(true, Ordering::Release);
                        *libc::__errno_location() = errno;
                        return; // the access is retried on the zero page
                    }
                    break;
                }
            }
        }
        *libc::__errno_location() = errno;
        chain_sigbus(sig, info, ctx);
    }
}

/// A fault that is not ours: the previous handler, or the default action (the process dies of `SIGBUS`).
unsafe fn chain_sigbus(sig: libc::c_int, info: *mut libc::siginfo_t, ctx: *mut libc::c_void) {
    // SAFETY: PREV was fully written before PREV_READY was set; the previous handler is called as
    // the kernel would have called it.
    unsafe {
        if PREV_READY.load(Ordering::Acquire) {
            let prev = (*PREV.0.get()).assume_init_ref();
            let h = prev.sa_sigaction;
            if h != libc::SIG_DFL && h != libc::SIG_IGN {
                if prev.sa_flags & libc::SA_SIGINFO != 0 {
                    let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) = std::mem::transmute(h);
                    f(sig, info, ctx);
                } else {
                    let f: extern "C" fn(libc::c_int) = std::mem::transmute(h);
                    f(sig);
                }
                return;
            }
        }
        let mut dfl: libc::sigaction = std::mem::zeroed();
        dfl.sa_sigaction = libc::SIG_DFL;
        libc::sigemptyset(&mut dfl.sa_mask);
        libc::sigaction(sig, &dfl, std::ptr::null_mut());
        if info.is_null() || (*info).si_code <= 0 {
            libc::raise(sig); // sent, not a fault: deliver it again under the default action
        }
        // A fault: returning re-executes the access, which faults again and kills the process.
    }
}

/// Registers `[start, start + len)` for the handler; the slot index, or `None` if the registry is full.
fn register_mapping(start: usize, len: usize) -> Option<usize> {
    for (i, slot) in REGISTRY.iter().enumerate() {
        if slot.start.load(Ordering::Relaxed) == 0 && slot.start.compare_exchange(0, start, Ordering::AcqRel, Ordering::Relaxed).is_ok() {
            slot.faulted.store(false, Ordering::Relaxed);
            slot.len.store(len, Ordering::Release);
            return Some(i);
        }
    }
    None
}

fn unregister_mapping(i: usize) {
    let slot = &REGISTRY[i];
    slot.len.store(0, Ordering::Release);
    slot.faulted.store(false, Ordering::Relaxed);
    slot.start.store(0, Ordering::Release);
}

// ---------------------------------------------------------------------------------------------
// The mapping

/// What the ends and their watchers share about one mapped file.
struct Shared {
    /// 0 while intact, else [`Broken::encode`] of the first cause found.
    broken: AtomicU64,
    /// Set by the server end's drop before it removes the file: a watcher then reports nothing.
    closing: AtomicBool,
    /// The descriptor the file was mapped from, held for `fstat`.
    file: File,
    path: PathBuf,
    /// (dev, ino) of the mapped file.
    file_id: (u64, u64),
    /// Device end: the creator process, if it could be identified at attach ([`crate::liveness`]).
    server: std::sync::OnceLock<crate::liveness::ProcessIdentity>,
}

impl Shared {
    /// Records `cause` unless a cause is already recorded; returns the recorded one.
    fn set_broken(&self, cause: Broken) -> Broken {
        match self.broken.compare_exchange(0, cause.encode(), Ordering::AcqRel, Ordering::Acquire) {
            Ok(_) => cause,
            Err(code) => Broken::decode(code).unwrap_or(cause),
        }
    }

    fn broken(&self) -> Option<Broken> {
        Broken::decode(self.broken.load(Ordering::Acquire))
    }
}

/// A handle on a channel's file for a non-real-time watcher thread: see [`ChannelWatch::check_file`].
#[derive(Clone)]
pub struct ChannelWatch {
    shared: Arc<Shared>,
}

impl ChannelWatch {
    /// Checks the file behind the mapping and marks the channel broken if it changed: the path no
    /// longer exists ([`Broken::Deleted`]), names another file ([`Broken::Replaced`]), or the
    /// mapped file is not [`CHANNEL_SIZE`] bytes ([`Broken::Resized`]). Returns the channel's
    /// broken cause, this one or one found earlier (by an access: [`Broken::Faulted`],
    /// [`Broken::BadHeader`]). `Ok` once the server end is closing (it removes the file itself).
    /// Makes system calls (`lstat`, `fstat`): call it from a non-real-time thread, every
    /// [`WATCH_PERIOD`] or so. A `stat` failing for another reason than a missing file is ignored.
    pub fn check_file(&self) -> Result<(), Broken> {
        let sh = &self.shared;
        if let Some(b) = sh.broken() {
            return Err(b);
        }
        if sh.closing.load(Ordering::Acquire) {
            return Ok(());
        }
        let cause = match std::fs::symlink_metadata(&sh.path) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => Some(Broken::Deleted),
            Ok(meta) if (meta.dev(), meta.ino()) != sh.file_id => Some(Broken::Replaced),
            _ => match sh.file.metadata() {
                Ok(meta) if meta.len() != CHANNEL_SIZE => Some(Broken::Resized { found_bytes: meta.len() }),
                _ => None,
            },
        };
        // The server end may have started closing (and removed the file) during the checks.
        match cause {
            Some(c) if !sh.closing.load(Ordering::Acquire) => Err(sh.set_broken(c)),
            _ => Ok(()),
        }
    }

    /// Device end: checks that the server process that created the channel (identified at
    /// attach: [`DeviceEnd::server_identified`]) still runs, and marks the channel broken with
    /// [`Broken::ServerDied`] if it does not: its pid is gone, a zombie, or another process. `Ok`
    /// when the creator could not be identified (another pid namespace: see [`crate::liveness`]),
    /// and on the server end. Makes system calls (reads `/proc/PID/stat`): a non-real-time thread,
    /// every [`WATCH_PERIOD`] or so, as [`Self::check_file`].
    pub fn check_server(&self) -> Result<(), Broken> {
        let sh = &self.shared;
        if let Some(b) = sh.broken() {
            return Err(b);
        }
        match sh.server.get() {
            Some(id) if crate::liveness::state_of(id) == crate::liveness::ProcessState::Dead => {
                Err(sh.set_broken(Broken::ServerDied { pid: id.pid }))
            }
            _ => Ok(()),
        }
    }

    /// The cause, if the channel was found broken (by an access or by [`Self::check_file`]).
    pub fn broken(&self) -> Option<Broken> {
        self.shared.broken()
    }

    pub fn path(&self) -> &Path {
        &self.shared.path
    }
}

/// The mapping plus what a reader remembers about one slot.
struct Mapped {
    map: MmapRaw,
    shared: Arc<Shared>,
    /// This mapping's slot in the `SIGBUS` registry.
    slot: usize,
    generation: u64,
}

impl Mapped {
    fn layout(&self) -> &Layout {
        // SAFETY: the mapping is CHANNEL_SIZE bytes, page-aligned (so aligned for Layout), lives as
        // long as self, and Layout consists only of atomics, which are valid for any bit pattern and
        // may be shared with other processes. If the file shrinks under it, an access faults and the
        // SIGBUS handler maps zero pages over it (the memory stays valid; see the module docs).
        unsafe { &*(self.map.as_ptr() as *const Layout) }
    }

    /// True once an access to this mapping faulted (it now holds anonymous zeros).
    fn faulted(&self) -> bool {
        REGISTRY[self.slot].faulted.load(Ordering::Acquire)
    }

    /// The header's magic, version and size are this layout's.
    fn header_valid(&self) -> bool {
        let h = &self.layout().header;
        h.magic.load(Ordering::Relaxed) == u64::from_le_bytes(MAGIC)
            && h.version.load(Ordering::Relaxed) == LAYOUT_VERSION
            && h.total_size.load(Ordering::Relaxed) == CHANNEL_SIZE
    }

    /// The cheap check before every access (a few loads, no system call): a recorded cause, a
    /// fault, a header that is not this layout's, and (`own_generation`, the server end) a
    /// generation that is not this end's.
    fn check(&self, own_generation: bool) -> Result<(), Broken> {
        if let Some(b) = self.shared.broken() {
            return Err(b);
        }
        if self.faulted() {
            return Err(self.shared.set_broken(Broken::Faulted));
        }
        if !self.header_valid() || (own_generation && self.layout().header.generation.load(Ordering::Acquire) != self.generation) {
            // A fault during the loads above (zeros) is the better cause.
            let cause = if self.faulted() { Broken::Faulted } else { Broken::BadHeader };
            return Err(self.shared.set_broken(cause));
        }
        Ok(())
    }
}

impl Drop for Mapped {
    fn drop(&mut self) {
        // Before `map` is unmapped (fields drop after this): the handler must never map over an
        // address range that may by now belong to something else.
        unregister_mapping(self.slot);
    }
}

#[derive(Default)]
struct ReaderState<T> {
    last_seq: u64,
    last: Option<T>,
    reads_since_fresh: u64,
}

impl<T: Copy> ReaderState<T> {
    /// The sample of a read that did not happen: the channel is broken.
    fn broken(&mut self) -> Sample<T> {
        self.reads_since_fresh = self.reads_since_fresh.saturating_add(1);
        Sample { value: self.last, status: ReadStatus::Broken, reads_since_fresh: self.reads_since_fresh }
    }
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
    /// symlink, no permission; `fchmod`; `set_len`; `mmap`). The channel of a 2D session
    /// ([`Dimension::Two`]); see [`Self::create_with_dimension`].
    pub fn create(path: impl AsRef<Path>) -> Result<ServerEnd, ShmError> {
        Self::create_with_dimension(path, Dimension::Two)
    }

    /// [`Self::create`] for a session of `dimension`, published in the header for the bridge
    /// ([`DeviceEnd::session_dimension`]).
    pub fn create_with_dimension(path: impl AsRef<Path>, dimension: Dimension) -> Result<ServerEnd, ShmError> {
        let path = path.as_ref();
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .mode(0o600)
            .custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC)
            .open(path)
            .map_err(io_err(path, "create"))?;
        // The owner's mark, before the file holds anything: while this end (its descriptor) lives,
        // remove_stale_channels leaves the file alone, however this process is seen from elsewhere.
        lock_shared(&file).map_err(io_err(path, "flock"))?;
        // An existing file keeps its mode on open: force 0600.
        file.set_permissions(std::fs::Permissions::from_mode(0o600)).map_err(io_err(path, "fchmod"))?;
        file.set_len(CHANNEL_SIZE).map_err(io_err(path, "set_len"))?;
        let mapped = map(file, path)?;
        let l = mapped.layout();
        let previous = l.header.generation.swap(0, Ordering::AcqRel);
        l.header.closed.store(0, Ordering::Relaxed);
        l.header.magic.store(u64::from_le_bytes(MAGIC), Ordering::Relaxed);
        l.header.version.store(LAYOUT_VERSION, Ordering::Relaxed);
        l.header.owner_lock.store(OWNER_LOCK, Ordering::Relaxed);
        l.header.total_size.store(CHANNEL_SIZE, Ordering::Relaxed);
        l.header.creator_pid.store(std::process::id(), Ordering::Relaxed);
        l.header.attacher_pid.store(0, Ordering::Relaxed);
        l.header.dimension.store(dimension as u32, Ordering::Relaxed);
        l.header.tick_origin_ns.store(0, Ordering::Relaxed);
        l.header.tick_period_ns.store(0, Ordering::Relaxed);
        l.pose.reset();
        l.force.reset();
        let generation = random_generation(previous);
        l.header.generation.store(generation, Ordering::Release);
        let mut mapped = mapped;
        mapped.generation = generation;
        // Truncated while being initialised: the stores above went to zero pages.
        if mapped.faulted() {
            return Err(ShmError::Broken { path: path.to_path_buf(), cause: Broken::Faulted });
        }
        Ok(ServerEnd { m: mapped, pose: ReaderState::default() })
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
        // A channel of an earlier layout (another size): name both versions rather than the sizes.
        let mut head = [0u8; 12];
        if len != CHANNEL_SIZE && len >= 12 && file.read_exact_at(&mut head, 0).is_ok() && head[..8] == MAGIC {
            let found = u32::from_le_bytes([head[8], head[9], head[10], head[11]]);
            if (1..LAYOUT_VERSION).contains(&found) {
                return Err(ShmError::WrongVersion { path: path.to_path_buf(), found, expected: LAYOUT_VERSION });
            }
        }
        if len != CHANNEL_SIZE {
            return Err(ShmError::WrongSize { path: path.to_path_buf(), found: len, expected: CHANNEL_SIZE });
        }
        let mut mapped = map(file, path)?;
        let h = &mapped.layout().header;
        let p = || path.to_path_buf();
        let generation = h.generation.load(Ordering::Acquire);
        let magic = h.magic.load(Ordering::Relaxed).to_le_bytes();
        if mapped.faulted() {
            return Err(ShmError::Broken { path: p(), cause: Broken::Faulted });
        }
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
            RawRead::Ok(_, g) if g == generation => buf[POSE_COUNTER_WORD],
            _ => 0,
        };
        mapped.generation = generation;
        if mapped.faulted() {
            return Err(ShmError::Broken { path: p(), cause: Broken::Faulted });
        }
        // The creator, to watch for its death (ChannelWatch::check_server), if it is visible here.
        let creator = mapped.layout().header.creator_pid.load(Ordering::Relaxed);
        let (dev, ino) = mapped.shared.file_id;
        if let Some(id) = crate::liveness::identify_mapper(creator, dev, ino) {
            let _ = mapped.shared.server.set(id);
        }
        Ok(DeviceEnd { m: mapped, counter, force: ReaderState::default() })
    }
}

/// Maps [`CHANNEL_SIZE`] bytes of `file` shared and registers the mapping with the `SIGBUS`
/// handler before anything touches it; keeps `file` for [`ChannelWatch::check_file`].
fn map(file: File, path: &Path) -> Result<Mapped, ShmError> {
    let meta = file.metadata().map_err(io_err(path, "fstat"))?;
    if let Err(errno) = install_sigbus_handler() {
        return Err(ShmError::Io { path: path.to_path_buf(), op: "sigaction(SIGBUS)", source: io::Error::from_raw_os_error(errno) });
    }
    let map = MmapOptions::new().len(CHANNEL_SIZE as usize).map_raw(&file).map_err(io_err(path, "mmap"))?;
    let len = (CHANNEL_SIZE as usize).div_ceil(page_size()) * page_size();
    let slot = register_mapping(map.as_ptr() as usize, len).ok_or_else(|| ShmError::TooManyChannels { path: path.to_path_buf() })?;
    let shared = Arc::new(Shared {
        broken: AtomicU64::new(0),
        closing: AtomicBool::new(false),
        file,
        path: path.to_path_buf(),
        file_id: (meta.dev(), meta.ino()),
        server: std::sync::OnceLock::new(),
    });
    Ok(Mapped { map, shared, slot, generation: 0 })
}

/// The server's end: the session's real-time thread writes forces and reads poses.
/// Dropping it writes state [`ServerForce::STATE_CLOSING`], marks the header closed and removes the file.
pub struct ServerEnd {
    m: Mapped,
    pose: ReaderState<DevicePose>,
}

impl ServerEnd {
    /// Publish a force (single writer: this end). Never blocks; a few relaxed stores and fences.
    /// Nothing is written once the channel is broken.
    pub fn write_force_from_rt(&mut self, force: &ServerForce) {
        if self.m.check(true).is_ok() {
            self.m.layout().force.write(self.m.generation, &force.encode());
        }
    }

    /// Publishes the session's tick phase: tick k is due at `origin_ns + k·period_ns` on
    /// `CLOCK_MONOTONIC` (the real-time thread, once, before its first tick). A bridge reads it
    /// with [`DeviceEnd::server_schedule`] to write each pose just before the tick that uses it.
    /// Two stores; nothing is written once the channel is broken, or for a zero origin or period.
    pub fn publish_schedule_from_rt(&mut self, origin_ns: u64, period_ns: u64) {
        if origin_ns == 0 || period_ns == 0 || self.m.check(true).is_err() {
            return;
        }
        let h = &self.m.layout().header;
        h.tick_period_ns.store(period_ns, Ordering::Relaxed);
        // Release: a reader that sees the origin sees the period.
        h.tick_origin_ns.store(origin_ns, Ordering::Release);
    }

    /// The latest pose, fresh if the bridge wrote one since the previous call;
    /// [`ReadStatus::Broken`] (nothing read) once the channel is broken.
    pub fn read_pose_from_rt(&mut self) -> Sample<DevicePose> {
        if self.m.check(true).is_err() {
            return self.pose.broken();
        }
        read_slot(&self.m.layout().pose, self.m.generation, &mut self.pose, DevicePose::decode)
    }

    /// Why the channel is broken, if it is (checked now, cheaply; deletion, replacement and resizing
    /// are found by a [`ChannelWatch`]). Real-time safe.
    pub fn broken(&self) -> Option<Broken> {
        self.m.check(true).err()
    }

    /// A handle for a non-real-time thread to watch the file with ([`ChannelWatch::check_file`]).
    pub fn watch(&self) -> ChannelWatch {
        ChannelWatch { shared: self.m.shared.clone() }
    }

    /// The bridge is alive: the channel is not broken, a pose arrived within the last
    /// `max_stale_reads` calls of [`Self::read_pose_from_rt`] and the attached pid (if any is recorded) exists.
    pub fn device_alive(&self, max_stale_reads: u64) -> bool {
        self.broken().is_none()
            && self.pose.last.is_some()
            && self.pose.reads_since_fresh <= max_stale_reads
            && self.attacher_pid().is_none_or(pid_alive)
    }

    /// The pid of the attached bridge, if one is attached (it may have died since: see [`pid_alive`]).
    pub fn attacher_pid(&self) -> Option<u32> {
        Some(self.m.layout().header.attacher_pid.load(Ordering::Relaxed)).filter(|&p| p != 0)
    }

    pub fn generation(&self) -> u64 {
        self.m.generation
    }

    pub fn path(&self) -> &Path {
        &self.m.shared.path
    }
}

impl Drop for ServerEnd {
    fn drop(&mut self) {
        self.m.shared.closing.store(true, Ordering::Release);
        let l = self.m.layout();
        let valid = self.m.header_valid();
        let generation = l.header.generation.load(Ordering::Acquire);
        if valid && generation != self.m.generation {
            return; // someone re-created the channel in this file: it is no longer ours
        }
        // Tell a bridge we are closing, if the mapping still shows our channel (a deleted or
        // replaced file is still shared with a bridge that has it mapped).
        if valid && !self.m.faulted() {
            let mut buf = [0u64; FORCE_WORDS];
            let mut f = match l.force.read(&mut buf) {
                RawRead::Ok(s, g) if s != 0 && g == self.m.generation => ServerForce::decode(&buf),
                _ => ServerForce::default(),
            };
            f.t_ns = monotonic_ns();
            f.state = ServerForce::STATE_CLOSING;
            l.force.write(self.m.generation, &f.encode());
            l.header.closed.store(1, Ordering::Release);
        }
        // Remove the file (ours, even if truncated or overwritten) only if the path still names it.
        let sh = &self.m.shared;
        if let Ok(meta) = std::fs::symlink_metadata(&sh.path)
            && (meta.dev(), meta.ino()) == sh.file_id
        {
            let _ = std::fs::remove_file(&sh.path);
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
    /// `counter` is ignored). `Err(Stale)` if the channel was re-created or closed (re-attach) or
    /// is broken ([`Self::broken`]); nothing is written then.
    pub fn write_pose_from_device(&mut self, pose: &DevicePose) -> Result<u64, Stale> {
        if !self.is_current() {
            return Err(Stale);
        }
        self.counter += 1;
        self.m.layout().pose.write(self.m.generation, &pose.encode(self.counter));
        Ok(self.counter)
    }

    /// The session's tick phase, once its real-time thread published it
    /// ([`ServerEnd::publish_schedule_from_rt`]): (the `CLOCK_MONOTONIC` time of tick 0's
    /// deadline, the tick period); tick k is due at `origin + k·period`. `None` before, and when
    /// the channel is not current.
    pub fn server_schedule(&self) -> Option<(Duration, Duration)> {
        if !self.is_current() {
            return None;
        }
        let h = &self.m.layout().header;
        let origin = h.tick_origin_ns.load(Ordering::Acquire);
        let period = h.tick_period_ns.load(Ordering::Relaxed);
        (origin != 0 && period != 0).then(|| (Duration::from_nanos(origin), Duration::from_nanos(period)))
    }

    /// The dimension of the session behind the channel (what the bridge drives); `None` for a
    /// value this layout does not define (a garbled header).
    pub fn session_dimension(&self) -> Option<Dimension> {
        Dimension::from_u32(self.m.layout().header.dimension.load(Ordering::Relaxed))
    }

    /// The counter the next successful write will stamp, minus one (the last one written).
    pub fn pose_counter(&self) -> u64 {
        self.counter
    }

    /// The latest force, fresh if the server wrote one since the previous call;
    /// [`ReadStatus::Stale`] (value: the last good one) once the channel was re-created or closed;
    /// [`ReadStatus::Broken`] (nothing read) once it is broken.
    pub fn read_force_from_device(&mut self) -> Sample<ServerForce> {
        if self.m.check(false).is_err() {
            return self.force.broken();
        }
        let mut s = read_slot(&self.m.layout().force, self.m.generation, &mut self.force, ServerForce::decode);
        if self.m.check(false).is_err() {
            s.status = ReadStatus::Broken;
        } else if !self.is_current() {
            s.status = ReadStatus::Stale;
        }
        s
    }

    /// True while the channel is the one attached to: same generation, not closed, not broken.
    pub fn is_current(&self) -> bool {
        let h = &self.m.layout().header;
        self.m.check(false).is_ok() && h.generation.load(Ordering::Acquire) == self.m.generation && h.closed.load(Ordering::Acquire) == 0
    }

    /// The server closed the channel (state closing written, header closed) or re-created it: the
    /// normal ends of a channel, as opposed to [`Self::broken`].
    pub fn closed_or_recreated(&self) -> bool {
        let h = &self.m.layout().header;
        self.m.header_valid() && (h.generation.load(Ordering::Acquire) != self.m.generation || h.closed.load(Ordering::Acquire) != 0)
    }

    /// Why the channel is broken, if it is (checked now, cheaply; deletion, replacement and
    /// resizing are found by a [`ChannelWatch`]).
    pub fn broken(&self) -> Option<Broken> {
        self.m.check(false).err()
    }

    /// A handle for a non-real-time thread to watch the file with ([`ChannelWatch::check_file`]).
    pub fn watch(&self) -> ChannelWatch {
        ChannelWatch { shared: self.m.shared.clone() }
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

    /// True if the server process was identified at attach (it runs in this pid namespace and maps
    /// the file), so that [`ChannelWatch::check_server`] can tell when it dies.
    pub fn server_identified(&self) -> bool {
        self.m.shared.server.get().is_some()
    }

    /// Removes the channel's file after its server died ([`Broken::ServerDied`]): nobody else will
    /// (a killed server never closes it), and shared memory outlives processes. Only if the path
    /// still names the mapped file and no new server re-created the channel in it (the
    /// generation is still the one attached to). `Ok(true)` if the file was removed.
    pub fn remove_if_orphaned(&self) -> io::Result<bool> {
        if !matches!(self.m.shared.broken(), Some(Broken::ServerDied { .. })) || self.m.faulted() {
            return Ok(false);
        }
        if !self.m.header_valid() || self.m.layout().header.generation.load(Ordering::Acquire) != self.m.generation {
            return Ok(false);
        }
        let sh = &self.m.shared;
        match std::fs::symlink_metadata(&sh.path) {
            Ok(meta) if (meta.dev(), meta.ino()) == sh.file_id => std::fs::remove_file(&sh.path).map(|()| true),
            Ok(_) => Ok(false),
            Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(false),
            Err(e) => Err(e),
        }
    }

    pub fn generation(&self) -> u64 {
        self.m.generation
    }

    pub fn path(&self) -> &Path {
        &self.m.shared.path
    }
}

impl Drop for DeviceEnd {
    fn drop(&mut self) {
        // Detach, so that another bridge may attach; a no-op if someone else has taken over or the
        // channel was re-created (this process may have re-attached to the new generation).
        if self.m.faulted() || self.m.layout().header.generation.load(Ordering::Acquire) != self.m.generation {
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

    fn at_x(x_m: f64) -> DevicePose {
        DevicePose { position_m: [x_m, 0.0, 0.0], ..Default::default() }
    }

    fn force(tick: u64) -> ServerForce {
        ServerForce {
            t_ns: monotonic_ns(),
            tick,
            force_n: [1.5, -2.5, 0.75],
            torque_nm: [0.25, -0.125, 0.0625],
            stiffness: std::array::from_fn(|r| std::array::from_fn(|c| (6 * r + c) as f64 * 10.0 + tick as f64)),
            base_position_m: [0.01, 0.02, -0.03],
            base_orientation: crate::spatial::quat_normalize([0.9, 0.1, -0.2, 0.3]).unwrap(),
            state: ServerForce::STATE_OK,
            pose_counter: tick + 7,
        }
    }

    #[test]
    fn the_tick_phase_is_published_once_and_reset_by_a_new_channel() {
        let path = temp_path("phase");
        let mut server = DeviceChannel::create(&path).unwrap();
        let device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.server_schedule(), None, "nothing published yet");
        server.publish_schedule_from_rt(0, 1_000_000);
        assert_eq!(device.server_schedule(), None, "a zero origin is not published");
        server.publish_schedule_from_rt(123_456_789, 1_000_000);
        assert_eq!(device.server_schedule(), Some((Duration::from_nanos(123_456_789), Duration::from_millis(1))));
        // Re-created in place (a new session in the same file): the phase is gone with the old generation.
        let _server2 = DeviceChannel::create(&path).unwrap();
        assert_eq!(device.server_schedule(), None, "a stale end has no phase");
        let again = DeviceChannel::attach(&path).unwrap();
        assert_eq!(again.server_schedule(), None, "the new channel has not published its phase");
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
            let pose = DevicePose {
                t_ns: monotonic_ns(),
                position_m: [0.1 * k as f64, -0.2, 0.05],
                orientation: crate::spatial::quat_normalize([0.5, -0.5, 0.25, 0.7]).unwrap(),
                buttons: 0b101,
                counter: 999,
            };
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
        old_device.write_pose_from_device(&at_x(1.0)).unwrap();
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
        old_device.m.layout().pose.write(old_generation, &at_x(9.0).encode(5));
        assert!(!server.read_pose_from_rt().fresh());

        // The new pair works.
        device.write_pose_from_device(&at_x(2.0)).unwrap();
        let s = server.read_pose_from_rt();
        assert!(s.fresh());
        assert_eq!(s.value.unwrap().position_m[0], 2.0);
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
        assert!(msg.contains(&short.display().to_string()) && msg.contains("is 18 bytes, expected 768"), "{msg}");

        let magic = temp_path("magic");
        let _server = DeviceChannel::create(&magic).unwrap();
        patch(&magic, 0, b"NOTMAGIC");
        let msg = DeviceChannel::attach(&magic).err().unwrap().to_string();
        assert!(msg.contains(&magic.display().to_string()) && msg.contains("wrong magic \"NOTMAGIC\""), "{msg}");

        let version = temp_path("version");
        let _server2 = DeviceChannel::create(&version).unwrap();
        patch(&version, 8, &7u32.to_le_bytes());
        let msg = DeviceChannel::attach(&version).err().unwrap().to_string();
        assert!(
            msg.contains(&version.display().to_string()) && msg.contains("layout version 7 (unknown to this build), this bridge speaks 3"),
            "{msg}"
        );

        let zeros = temp_path("zeros");
        std::fs::write(&zeros, [0u8; CHANNEL_SIZE as usize]).unwrap();
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

    /// A channel file of the 2D-only layout (version 2, 512 bytes, as a server of the previous
    /// release creates it, or leaves behind in /dev/shm): refused naming both versions, not the sizes.
    #[test]
    fn a_channel_of_the_previous_layout_is_refused_naming_both_versions() {
        let path = temp_path("layout-v2");
        let mut old = vec![0u8; 512];
        old[..8].copy_from_slice(&MAGIC);
        old[8..12].copy_from_slice(&2u32.to_le_bytes());
        old[16..24].copy_from_slice(&512u64.to_le_bytes());
        old[24..32].copy_from_slice(&0x1234u64.to_le_bytes());
        std::fs::write(&path, &old).unwrap();
        let e = DeviceChannel::attach(&path).err().unwrap();
        assert!(matches!(e, ShmError::WrongVersion { found: 2, expected: 3, .. }), "{e}");
        let msg = e.to_string();
        assert!(msg.contains("layout version 2 (2D pose and wrench, tick phase), this bridge speaks 3 (6-DOF pose"), "{msg}");
        // Version 1 likewise; a same-size file with another version is named too.
        old[8..12].copy_from_slice(&1u32.to_le_bytes());
        std::fs::write(&path, &old).unwrap();
        assert!(
            DeviceChannel::attach(&path).err().unwrap().to_string().contains("layout version 1 (2D pose and wrench), this bridge speaks 3")
        );
        // A server creating over the old file re-initialises it in the new layout.
        let server = DeviceChannel::create_with_dimension(&path, Dimension::Three).unwrap();
        assert_eq!(std::fs::metadata(&path).unwrap().len(), CHANNEL_SIZE);
        let device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.session_dimension(), Some(Dimension::Three));
        drop(device);
        drop(server);
        let _server2d = DeviceChannel::create(&path).unwrap();
        assert_eq!(DeviceChannel::attach(&path).unwrap().session_dimension(), Some(Dimension::Two));
    }

    /// A 6-DOF pose and wrench cross the channel bit for bit, and the 2D forms round-trip through it.
    #[test]
    fn six_dof_values_and_the_planar_forms_cross_intact() {
        let path = temp_path("6dof");
        let mut server = DeviceChannel::create_with_dimension(&path, Dimension::Three).unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        let q = crate::spatial::quat_normalize([0.3, -0.6, 0.2, 0.7]).unwrap();
        let pose = DevicePose { t_ns: 42, position_m: [0.011, -0.022, 0.033], orientation: q, buttons: 0b11, counter: 0 };
        device.write_pose_from_device(&pose).unwrap();
        let got = server.read_pose_from_rt().value.unwrap();
        assert_eq!(got, DevicePose { counter: 1, ..pose });
        let f = force(9);
        server.write_force_from_rt(&f);
        assert_eq!(device.read_force_from_device().value.unwrap(), f);

        // 2D through the 6-DOF fields.
        let planar = DevicePose::planar(7, [0.05, -0.01, -1.2], 1);
        device.write_pose_from_device(&planar).unwrap();
        let back = server.read_pose_from_rt().value.unwrap().to_planar();
        assert_eq!(&back[..2], &[0.05, -0.01]);
        assert!((back[2] + 1.2).abs() < 1e-15, "{back:?}");
        let mut f2 = ServerForce::default();
        let j: [f64; 9] = std::array::from_fn(|i| i as f64 - 4.5);
        f2.set_planar([0.5, -0.25, 0.002], &j, [0.05, -0.01, -1.2]);
        server.write_force_from_rt(&f2);
        let (w, k, base) = device.read_force_from_device().value.unwrap().to_planar();
        assert_eq!((w, k), ([0.5, -0.25, 0.002], j));
        assert!((base[2] + 1.2).abs() < 1e-15 && base[..2] == [0.05, -0.01], "{base:?}");
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
        device.write_pose_from_device(&at_x(1.0)).unwrap();
        assert!(server.read_pose_from_rt().fresh());
        server.m.layout().pose.seq.fetch_add(1, Ordering::Relaxed); // odd: a write in progress forever
        let s = server.read_pose_from_rt();
        assert_eq!(s.status, ReadStatus::Contended);
        assert_eq!(s.value.unwrap().position_m[0], 1.0);
        drop(device);
        let mut device = DeviceChannel::attach(&path).unwrap();
        assert_eq!(device.pose_counter(), 0); // the slot was mid-write: counter not readable, restart
        device.write_pose_from_device(&at_x(2.0)).unwrap();
        let s = server.read_pose_from_rt();
        assert!(s.fresh());
        assert_eq!(s.value.unwrap().position_m[0], 2.0);
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

    /// The changes to a live channel's file of issue 13.
    #[derive(Debug, Clone, Copy)]
    enum Mutation {
        TruncateToZero,
        ShrinkToHalf,
        Grow,
        GarbageFill,
        Delete,
        /// A copy of the channel's bytes (a valid-looking header) renamed over the path.
        Replace,
    }

    const MUTATIONS: [Mutation; 6] =
        [Mutation::TruncateToZero, Mutation::ShrinkToHalf, Mutation::Grow, Mutation::GarbageFill, Mutation::Delete, Mutation::Replace];

    fn mutate(path: &Path, m: Mutation) {
        let open = || OpenOptions::new().write(true).open(path).unwrap();
        match m {
            Mutation::TruncateToZero => open().set_len(0).unwrap(),
            Mutation::ShrinkToHalf => open().set_len(CHANNEL_SIZE / 2).unwrap(),
            Mutation::Grow => open().set_len(1 << 20).unwrap(),
            Mutation::GarbageFill => {
                // Same length, same inode: every byte overwritten (splitmix64 noise).
                let mut z = 0x1234_5678_9abc_def0u64;
                let bytes: Vec<u8> = (0..CHANNEL_SIZE / 8)
                    .flat_map(|_| {
                        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
                        let mut x = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                        (x ^ (x >> 31)).to_le_bytes()
                    })
                    .collect();
                open().write_all_at(&bytes, 0).unwrap();
            }
            Mutation::Delete => std::fs::remove_file(path).unwrap(),
            Mutation::Replace => {
                let tmp = path.with_extension("replacement");
                std::fs::copy(path, &tmp).unwrap();
                std::fs::rename(&tmp, path).unwrap();
            }
        }
    }

    fn expected(m: Mutation) -> Broken {
        match m {
            Mutation::TruncateToZero => Broken::Faulted,
            Mutation::ShrinkToHalf => Broken::Resized { found_bytes: CHANNEL_SIZE / 2 },
            Mutation::Grow => Broken::Resized { found_bytes: 1 << 20 },
            Mutation::GarbageFill => Broken::BadHeader,
            Mutation::Delete => Broken::Deleted,
            Mutation::Replace => Broken::Replaced,
        }
    }

    fn pose(x_m: f64) -> DevicePose {
        DevicePose::planar(monotonic_ns(), [x_m, 0.1, 0.2], 0)
    }

    /// Every change to a live channel's file: neither end faults (this test process survives the
    /// truncation, which killed it with SIGBUS before), both report the channel broken with the
    /// cause, reads keep the last good value, writes are refused or harmless, and dropping the ends
    /// removes the file only while the path still names it.
    #[test]
    fn issue_13_every_change_to_the_file_breaks_both_ends_without_a_fault() {
        for m in MUTATIONS {
            let path = temp_path(&format!("mutate-{m:?}"));
            let mut server = DeviceChannel::create(&path).unwrap();
            let mut device = DeviceChannel::attach(&path).unwrap();
            let (server_watch, device_watch) = (server.watch(), device.watch());
            device.write_pose_from_device(&pose(1.0)).unwrap();
            assert!(server.read_pose_from_rt().fresh(), "{m:?}");
            server.write_force_from_rt(&force(1));
            assert!(device.read_force_from_device().fresh(), "{m:?}");
            assert_eq!((server_watch.check_file(), device_watch.check_file()), (Ok(()), Ok(())), "{m:?}");

            mutate(&path, m);

            // Accesses first (a truncation faults on them), then the watchers (the rest).
            let s = server.read_pose_from_rt();
            server.write_force_from_rt(&force(2));
            let w = device.write_pose_from_device(&pose(2.0));
            let f = device.read_force_from_device();
            let _ = (server_watch.check_file(), device_watch.check_file());
            let want = expected(m);
            assert_eq!(server.broken(), Some(want), "{m:?}");
            assert_eq!(device.broken(), Some(want), "{m:?}");
            assert_eq!(server_watch.check_file(), Err(want), "{m:?}");
            assert_eq!(device_watch.check_file(), Err(want), "{m:?}");
            if matches!(m, Mutation::TruncateToZero | Mutation::GarbageFill) {
                // Found by the accesses themselves, no watcher needed.
                assert_eq!(s.status, ReadStatus::Broken, "{m:?}");
                assert_eq!(f.status, ReadStatus::Broken, "{m:?}");
                assert_eq!(w, Err(Stale), "{m:?}");
            }
            // From now on: broken, nothing read, the last good values kept.
            let s = server.read_pose_from_rt();
            assert_eq!(s.status, ReadStatus::Broken, "{m:?}");
            assert_eq!(s.value.map(|p| p.position_m[0]), Some(1.0), "{m:?}");
            assert!(!server.device_alive(u64::MAX), "{m:?}");
            server.write_force_from_rt(&force(3));
            let f = device.read_force_from_device();
            assert_eq!(f.status, ReadStatus::Broken, "{m:?}");
            // The accesses found truncation and garbage at once; the others only the watcher (a
            // shrink within the first page, a grown, deleted or replaced file still share memory).
            // (A shrink to half, 384 bytes, keeps the force slot's sequence and tick, which lie
            // below the new end of file, in the still-shared page: the write of tick 2 arrives.)
            let last_tick = if matches!(m, Mutation::TruncateToZero | Mutation::GarbageFill) { 1 } else { 2 };
            assert_eq!(f.value.map(|f| f.tick), Some(last_tick), "{m:?}");
            assert!(!device.is_current() && !device.server_alive(u64::MAX), "{m:?}");
            assert!(!device.closed_or_recreated(), "{m:?}: broken is not the normal end of a channel");
            assert_eq!(device.write_pose_from_device(&pose(3.0)), Err(Stale), "{m:?}");

            drop(device);
            drop(server);
            match m {
                // The replacement is someone else's file: it stays.
                Mutation::Replace => {
                    assert!(path.exists(), "{m:?}");
                    std::fs::remove_file(&path).unwrap();
                }
                // Our own file, whatever was done to it, is removed.
                _ => assert!(!path.exists(), "{m:?}: the server end left its broken file behind"),
            }
            // A watcher that outlives the ends keeps its verdict.
            assert_eq!(server_watch.check_file(), Err(want), "{m:?}");
        }
    }

    #[test]
    fn issue_13_a_normal_close_is_not_reported_broken() {
        let path = temp_path("close-watch");
        let server = DeviceChannel::create(&path).unwrap();
        let device = DeviceChannel::attach(&path).unwrap();
        let (server_watch, device_watch) = (server.watch(), device.watch());
        drop(server); // closes and removes the file
        assert!(!path.exists());
        assert_eq!(server_watch.check_file(), Ok(()), "the server end's own close is no breakage");
        assert!(device.closed_or_recreated());
        assert!(!device.is_current());
        // The bridge's watcher sees the file gone: broken too, but the bridge reports the close first.
        assert_eq!(device_watch.check_file(), Err(Broken::Deleted));
    }

    #[test]
    fn issue_13_a_file_truncated_while_attaching_or_creating_is_an_error_not_a_fault() {
        let path = temp_path("truncated-attach");
        let server = DeviceChannel::create(&path).unwrap();
        // A mapping of a zero-length file (as if truncated between attach's size check and its
        // reads): the header reads fault, and attach reports it.
        let file = OpenOptions::new().read(true).write(true).open(&path).unwrap();
        file.set_len(0).unwrap();
        let mapped = map(file, &path).unwrap();
        assert_eq!(mapped.check(false), Err(Broken::Faulted));
        assert!(mapped.faulted());
        assert_eq!(mapped.layout().header.magic.load(Ordering::Relaxed), 0, "the mapping now reads zeros");
        drop(mapped);
        let e = DeviceChannel::attach(&path).err().unwrap();
        assert!(matches!(e, ShmError::WrongSize { found: 0, .. }), "{e}");
        drop(server);
    }

    #[test]
    fn issue_13_the_registry_is_reused_after_drop() {
        // More channels over time than registry slots, never more than a few at once.
        for i in 0..(MAX_MAPPINGS + 16) {
            let path = temp_path("registry");
            let server = DeviceChannel::create(&path).unwrap();
            assert!(server.broken().is_none(), "channel {i}");
        }
        let slots_in_use = REGISTRY.iter().filter(|s| s.start.load(Ordering::Relaxed) != 0).count();
        assert!(slots_in_use < 64, "{slots_in_use} registry slots still in use after every channel was dropped");
    }

    /// Issue 35 (L4): stale channel files piled up in /dev/shm. A sweep removes the channels whose
    /// creator is gone and nothing else: not a live channel (its creator holds the owner lock),
    /// not an unmarked channel of an earlier build that a live process maps, not a file under
    /// another name, not a file that is not a channel, not a symbolic link; with a creator pid,
    /// only that creator's.
    #[test]
    fn issue_35_a_sweep_removes_only_the_channels_whose_creator_is_gone() {
        static N: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!("needlesim-sweep-{}-{}", std::process::id(), N.fetch_add(1, Ordering::Relaxed)));
        std::fs::create_dir(&dir).unwrap();
        let at = |id: &str| dir.join(format!("{CHANNEL_FILE_PREFIX}{id}"));
        let live = DeviceChannel::create(at("000000000001")).unwrap();
        let bytes = std::fs::read(live.path()).unwrap();
        assert_eq!(u32::from_le_bytes(bytes[12..16].try_into().unwrap()), OWNER_LOCK, "create marks the header");
        let copy = |id: &str, patches: &[(usize, &[u8])]| {
            let mut b = bytes.clone();
            for (offset, with) in patches {
                b[*offset..*offset + with.len()].copy_from_slice(with);
            }
            std::fs::write(at(id), b).unwrap();
            at(id)
        };
        // A marked channel nobody holds: its creator is gone.
        let stale = copy("000000000002", &[]);
        // Unmarked (an earlier build's): gone unless a visible process maps it.
        let unmarked = copy("000000000003", &[(12, &0u32.to_le_bytes())]);
        let unmarked_mapped = copy("000000000004", &[(12, &0u32.to_le_bytes())]);
        let mapping = unsafe { memmap2::Mmap::map(&File::open(&unmarked_mapped).unwrap()) }.unwrap();
        // Another creator's stale channel: left by a sweep for this creator only.
        let other_creator = copy("000000000005", &[(32, &0x7fff_fff0u32.to_le_bytes())]);
        // Not ours to judge: other names, other contents, a link to a stale channel.
        let other_name = copy("shm-test-x", &[]);
        let upper_case = copy("00000000000A", &[]);
        let not_a_channel = at("000000000006");
        std::fs::write(&not_a_channel, [0x5Au8; 768]).unwrap();
        let target = copy("link-target", &[]);
        let link = at("000000000008");
        std::os::unix::fs::symlink(&target, &link).unwrap();

        let me = std::process::id();
        let sweep = remove_stale_channels(&dir, Some(me)).unwrap();
        assert!(sweep.errors.is_empty(), "{:?}", sweep.errors);
        let mut removed = sweep.removed.clone();
        removed.sort();
        assert_eq!(removed, vec![stale.clone(), unmarked.clone()]);
        assert_eq!(sweep.live, 2, "the live channel and the mapped unmarked one");
        for kept in [live.path(), &unmarked_mapped, &other_creator, &other_name, &upper_case, &not_a_channel, &target, &link] {
            assert!(std::fs::symlink_metadata(kept).is_ok(), "{} was removed", kept.display());
        }
        let sweep = remove_stale_channels(&dir, None).unwrap();
        assert_eq!(sweep.removed, vec![other_creator.clone()]);
        // The live channel keeps working, and its end removes its file when dropped.
        assert!(live.broken().is_none());
        let live_path = live.path().to_path_buf();
        drop(live);
        assert!(!live_path.exists());
        drop(mapping);
        assert_eq!(remove_stale_channels(&dir, None).unwrap().removed, vec![unmarked_mapped]);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
