//! The mapping of a channel file: what both ends and their watchers share about it, the
//! watcher's handle ([`ChannelWatch`]), and the checks every access makes first.

use std::fs::File;
use std::io;
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use memmap2::{MmapOptions, MmapRaw};

use super::error::{Broken, ShmError};
use super::layout::Layout;
use super::sigbus::{REGISTRY, install_sigbus_handler, page_size, register_mapping, unregister_mapping};
use super::{CHANNEL_SIZE, LAYOUT_VERSION, MAGIC};
#[cfg(doc)]
use super::{DeviceEnd, WATCH_PERIOD};

/// What the ends and their watchers share about one mapped file.
pub(super) struct Shared {
    /// 0 while intact, else [`Broken::encode`] of the first cause found.
    broken: AtomicU64,
    /// Set by the server end's drop before it removes the file: a watcher then reports nothing.
    pub(super) closing: AtomicBool,
    /// The descriptor the file was mapped from, held for `fstat`.
    file: File,
    pub(super) path: PathBuf,
    /// (dev, ino) of the mapped file.
    pub(super) file_id: (u64, u64),
    /// Device end: the creator process, if it could be identified at attach ([`crate::liveness`]).
    pub(super) server: std::sync::OnceLock<crate::liveness::ProcessIdentity>,
}

impl Shared {
    /// Records `cause` unless a cause is already recorded; returns the recorded one.
    pub(super) fn set_broken(&self, cause: Broken) -> Broken {
        match self.broken.compare_exchange(0, cause.encode(), Ordering::AcqRel, Ordering::Acquire) {
            Ok(_) => cause,
            Err(code) => Broken::decode(code).unwrap_or(cause),
        }
    }

    pub(super) fn broken(&self) -> Option<Broken> {
        Broken::decode(self.broken.load(Ordering::Acquire))
    }
}

/// A handle on a channel's file for a non-real-time watcher thread: see [`ChannelWatch::check_file`].
#[derive(Clone)]
pub struct ChannelWatch {
    pub(super) shared: Arc<Shared>,
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
pub(super) struct Mapped {
    map: MmapRaw,
    pub(super) shared: Arc<Shared>,
    /// This mapping's slot in the `SIGBUS` registry.
    slot: usize,
    pub(super) generation: u64,
}

impl Mapped {
    pub(super) fn layout(&self) -> &Layout {
        // SAFETY: the mapping is CHANNEL_SIZE bytes, page-aligned (so aligned for Layout), lives as
        // long as self, and Layout consists only of atomics, which are valid for any bit pattern and
        // may be shared with other processes. If the file shrinks under it, an access faults and the
        // SIGBUS handler maps zero pages over it (the memory stays valid; see the module docs).
        unsafe { &*(self.map.as_ptr() as *const Layout) }
    }

    /// True once an access to this mapping faulted (it now holds anonymous zeros).
    pub(super) fn faulted(&self) -> bool {
        REGISTRY[self.slot].faulted.load(Ordering::Acquire)
    }

    /// The header's magic, version and size are this layout's.
    pub(super) fn header_valid(&self) -> bool {
        let h = &self.layout().header;
        h.magic.load(Ordering::Relaxed) == u64::from_le_bytes(MAGIC)
            && h.version.load(Ordering::Relaxed) == LAYOUT_VERSION
            && h.total_size.load(Ordering::Relaxed) == CHANNEL_SIZE
    }

    /// The cheap check before every access (a few loads, no system call): a recorded cause, a
    /// fault, a header that is not this layout's, and (`own_generation`, the server end) a
    /// generation that is not this end's.
    pub(super) fn check(&self, own_generation: bool) -> Result<(), Broken> {
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

pub(super) fn io_err<'a>(path: &'a Path, op: &'static str) -> impl FnOnce(io::Error) -> ShmError + 'a {
    move |source| ShmError::Io { path: path.to_path_buf(), op, source }
}

/// Maps [`CHANNEL_SIZE`] bytes of `file` shared and registers the mapping with the `SIGBUS`
/// handler before anything touches it; keeps `file` for [`ChannelWatch::check_file`].
pub(super) fn map(file: File, path: &Path) -> Result<Mapped, ShmError> {
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
