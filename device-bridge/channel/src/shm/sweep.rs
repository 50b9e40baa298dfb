//! Channel files left behind (issue 35): finding and removing the files of dead creators
//! ([`remove_stale_channels`]).

use std::fs::OpenOptions;
use std::io;
use std::os::unix::fs::{FileExt, MetadataExt, OpenOptionsExt};
use std::path::{Path, PathBuf};

use super::{CHANNEL_FILE_PREFIX, LAYOUT_VERSION, MAGIC, OWNER_LOCK};

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
        match remove_if_stale(&path, creator, None) {
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
/// channel of this user (or of `creator`, or not the file `(dev, ino)` when `file_id` is given).
pub(super) fn remove_if_stale(path: &Path, creator: Option<u32>, file_id: Option<(u64, u64)>) -> io::Result<Option<bool>> {
    use std::os::fd::AsRawFd;
    let meta = std::fs::symlink_metadata(path)?;
    // SAFETY: geteuid has no preconditions.
    if !meta.file_type().is_file() || meta.uid() != unsafe { libc::geteuid() } {
        return Ok(None);
    }
    let file = OpenOptions::new().read(true).custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC | libc::O_NONBLOCK).open(path)?;
    let held = file.metadata()?;
    if file_id.is_some_and(|id| id != (held.dev(), held.ino())) {
        return Ok(None);
    }
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
