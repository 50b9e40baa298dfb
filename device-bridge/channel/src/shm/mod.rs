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

mod device;
mod error;
mod layout;
mod mapping;
mod seqlock;
mod server;
mod sigbus;
mod sweep;
mod values;

use std::io;
use std::mem::size_of;
use std::time::Duration;

pub use device::DeviceEnd;
pub use error::{Broken, ShmError, Stale};
pub use mapping::ChannelWatch;
pub use server::ServerEnd;
pub use sweep::{Sweep, is_channel_file_name, remove_stale_channels};
pub use values::{DevicePose, Dimension, ReadStatus, Sample, ServerForce};

use layout::Layout;

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

/// Entry points: [`DeviceChannel::create`] (server) and [`DeviceChannel::attach`] (bridge).
pub struct DeviceChannel;

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

#[cfg(test)]
mod tests;
