//! The server side: [`DeviceChannel::create`] and the session's end of the channel, [`ServerEnd`].

use std::fs::{File, OpenOptions};
use std::io;
use std::os::unix::fs::{MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::Duration;

use super::error::{Broken, ShmError};
use super::layout::FORCE_WORDS;
use super::mapping::{ChannelWatch, Mapped, io_err, map};
use super::seqlock::{RawRead, ReaderState, read_slot};
use super::values::{DevicePose, Dimension, Sample, ServerForce};
use super::{CHANNEL_SIZE, DeviceChannel, LAYOUT_VERSION, MAGIC, OWNER_LOCK, monotonic_ns, pid_alive};
#[cfg(doc)]
use super::{DeviceEnd, ReadStatus};

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
}

/// The server's end: the session's real-time thread writes forces and reads poses.
/// Dropping it writes state [`ServerForce::STATE_CLOSING`], marks the header closed and removes the file.
pub struct ServerEnd {
    pub(super) m: Mapped,
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
