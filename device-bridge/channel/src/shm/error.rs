//! What can go wrong: the errors of creating and attaching a channel ([`ShmError`]), a stale
//! channel ([`Stale`]) and the causes of a broken one ([`Broken`]).

use std::io;
use std::path::PathBuf;

use super::{CHANNEL_SIZE, MAGIC, MAX_MAPPINGS};
#[cfg(doc)]
use super::{ChannelWatch, DeviceEnd};

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
    pub(super) fn encode(self) -> u64 {
        match self {
            Broken::Faulted => 1,
            Broken::Resized { found_bytes } => 2 | (found_bytes.min(u64::MAX >> 8) << 8),
            Broken::Deleted => 3,
            Broken::Replaced => 4,
            Broken::BadHeader => 5,
            Broken::ServerDied { pid } => 6 | (u64::from(pid) << 8),
        }
    }

    pub(super) fn decode(code: u64) -> Option<Broken> {
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
