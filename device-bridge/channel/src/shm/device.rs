//! The bridge side: [`DeviceChannel::attach`] and the device loop's end of the channel, [`DeviceEnd`].

use std::fs::OpenOptions;
use std::io;
use std::os::unix::fs::{FileExt, MetadataExt, OpenOptionsExt};
use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::Duration;

#[cfg(doc)]
use super::ServerEnd;
use super::error::{Broken, ShmError, Stale};
use super::layout::{POSE_COUNTER_WORD, POSE_WORDS};
use super::mapping::{ChannelWatch, Mapped, io_err, map};
use super::seqlock::{RawRead, ReaderState, read_slot};
use super::values::{DevicePose, Dimension, ReadStatus, Sample, ServerForce};
use super::{CHANNEL_SIZE, DeviceChannel, LAYOUT_VERSION, MAGIC, pid_alive};

impl DeviceChannel {
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

/// The bridge's end: the device thread writes poses and reads forces.
pub struct DeviceEnd {
    pub(super) m: Mapped,
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

    /// Removes the channel's file when its server is gone although the bridge did not see it die
    /// (issue 35: a server killed before the bridge attached is never identified, so no
    /// [`Broken::ServerDied`]; the file stayed in /dev/shm). Removed only if it is provably stale:
    /// the path still names the mapped file, the channel is still the generation attached to and
    /// names the same creator, and nobody holds the file's lock, which every live server end holds
    /// (shared) for its life whatever pid namespace it runs in (the sweep's rule,
    /// [`super::remove_stale_channels`]; a file of an earlier build, without that lock, is mapped
    /// by this bridge and so never taken for stale here). `Ok(true)` if the file was removed.
    pub fn remove_if_abandoned(&self) -> io::Result<bool> {
        if self.m.faulted() || !self.m.header_valid() {
            return Ok(false);
        }
        if self.m.layout().header.generation.load(Ordering::Acquire) != self.m.generation {
            return Ok(false);
        }
        let sh = &self.m.shared;
        match super::sweep::remove_if_stale(&sh.path, Some(self.creator_pid()), Some(sh.file_id)) {
            Ok(removed) => Ok(removed == Some(true)),
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
