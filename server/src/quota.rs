//! Bounds on what the server keeps on disk (issue 35): the recordings directory
//! (`--max-recordings` files, `--max-recordings-mb` bytes) and the after-action reports directory
//! (`--max-reports`, `--max-reports-mb`), each a [`DirQuota`].
//!
//! A file is admitted when it starts ([`DirQuota::admit`]): the directory is scanned (so that the
//! files an operator deleted free their room at once), its files of the quota's kind are counted
//! and the bytes of all its regular files summed, and the bytes the new file needs at least are
//! reserved. A file that grows (a recording) reserves each write before making it
//! ([`Reservation::try_reserve`]) and is told no when the write would pass the limit; the bytes it
//! wrote are then counted as used ([`Reservation::spend`]). Reservations of the live files count
//! until they are spent or dropped, so that two recordings growing at once cannot together pass
//! the limit. A refused start is a [`QuotaExceeded`] (RESOURCE_EXHAUSTED naming the flag).

use std::fmt;
use std::fs;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// Why a file was not admitted: the directory holds its limit of files or bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct QuotaExceeded {
    /// "recordings" or "reports".
    pub what: &'static str,
    /// The flag that sets the limit reached (`--max-recordings`, `--max-recordings-mb`, …).
    pub flag: &'static str,
    /// Files or bytes in the directory (with the live files' reservations).
    pub amount: u64,
    /// Bytes the new file needs at least (0 for the count).
    pub need: u64,
    /// The limit, in files or bytes.
    pub limit: u64,
    /// "files" or "bytes".
    pub unit: &'static str,
}

impl fmt::Display for QuotaExceeded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { what, flag, amount, need, limit, unit } = self;
        if *need == 0 {
            write!(f, "the {what} directory holds {amount} {unit}, its limit of {limit} (server flag {flag}): delete some to make room")
        } else {
            write!(
                f,
                "the {what} directory holds {amount} {unit}; a new file needs {need} more, over the limit of {limit} {unit} \
                 (server flag {flag}): delete some to make room"
            )
        }
    }
}

impl std::error::Error for QuotaExceeded {}

/// Bytes in use in a directory and bytes reserved by its live files.
#[derive(Debug, Default)]
struct Usage {
    /// The directory's bytes at the last scan plus the bytes written since.
    used: u64,
    /// Bytes reserved and not yet written or given back.
    reserved: u64,
}

/// The bound on one directory of the data directory.
#[derive(Debug)]
pub struct DirQuota {
    /// "recordings" or "reports" (for messages).
    what: &'static str,
    /// The extension of the files counted (`mcap`, `html`).
    extension: &'static str,
    count_flag: &'static str,
    bytes_flag: &'static str,
    max_files: usize,
    max_bytes: u64,
    usage: Mutex<Usage>,
    /// Starts refused (count or bytes).
    refused: AtomicU64,
    /// Growing files stopped because their next write would pass the limit.
    stopped: AtomicU64,
}

/// `n` MiB in bytes.
pub fn mib(n: u64) -> u64 {
    n.saturating_mul(1 << 20)
}

impl DirQuota {
    /// A quota of `max_files` files ending in `.extension` and `max_bytes` bytes; `count_flag`
    /// and `bytes_flag` name the server flags that set them.
    pub fn new(
        what: &'static str,
        extension: &'static str,
        (count_flag, max_files): (&'static str, usize),
        (bytes_flag, max_bytes): (&'static str, u64),
    ) -> Arc<Self> {
        Arc::new(Self {
            what,
            extension,
            count_flag,
            bytes_flag,
            max_files,
            max_bytes,
            usage: Mutex::default(),
            refused: AtomicU64::new(0),
            stopped: AtomicU64::new(0),
        })
    }

    /// No bound (the unit tests, the offline commands).
    pub fn unlimited(what: &'static str, extension: &'static str) -> Arc<Self> {
        Self::new(what, extension, ("(none)", usize::MAX), ("(none)", u64::MAX))
    }

    fn usage(&self) -> std::sync::MutexGuard<'_, Usage> {
        // A panic while holding the lock leaves plain numbers behind: keep using them.
        self.usage.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Admits a new file in `dir` that needs at least `need` bytes: scans `dir`, checks the file
    /// count and the bytes (with the live files' reservations), and reserves `need`.
    pub fn admit(self: &Arc<Self>, dir: &Path, need: u64) -> Result<Reservation, QuotaExceeded> {
        let mut usage = self.usage();
        let (files, bytes) = scan(dir, self.extension);
        usage.used = bytes;
        let refuse = |e: QuotaExceeded| {
            self.refused.fetch_add(1, Ordering::Relaxed);
            Err(e)
        };
        if files >= self.max_files {
            return refuse(QuotaExceeded {
                what: self.what,
                flag: self.count_flag,
                amount: files as u64,
                need: 0,
                limit: self.max_files as u64,
                unit: "files",
            });
        }
        let in_use = usage.used.saturating_add(usage.reserved);
        if in_use.saturating_add(need) > self.max_bytes {
            return refuse(QuotaExceeded {
                what: self.what,
                flag: self.bytes_flag,
                amount: in_use,
                need,
                limit: self.max_bytes,
                unit: "bytes",
            });
        }
        usage.reserved += need;
        Ok(Reservation { quota: Arc::clone(self), held: need })
    }

    /// Bytes in the directory (at the last scan, plus the writes since) and reserved.
    pub fn bytes_used(&self) -> u64 {
        let usage = self.usage();
        usage.used.saturating_add(usage.reserved)
    }

    /// Starts refused.
    pub fn refused(&self) -> u64 {
        self.refused.load(Ordering::Relaxed)
    }

    /// Growing files stopped at the limit.
    pub fn stopped(&self) -> u64 {
        self.stopped.load(Ordering::Relaxed)
    }

    /// The flag of the byte limit (for messages).
    pub fn bytes_flag(&self) -> &'static str {
        self.bytes_flag
    }
}

/// Files ending in `.extension` in `dir` and the bytes of all its regular files (symbolic links
/// are not followed and not counted); (0, 0) when `dir` does not exist.
fn scan(dir: &Path, extension: &str) -> (usize, u64) {
    let Ok(entries) = fs::read_dir(dir) else { return (0, 0) };
    let (mut files, mut bytes) = (0usize, 0u64);
    for entry in entries.filter_map(Result::ok) {
        // `DirEntry::metadata` does not follow a symbolic link.
        let Ok(meta) = entry.metadata() else { continue };
        if !meta.is_file() {
            continue;
        }
        bytes = bytes.saturating_add(meta.len());
        if Path::new(&entry.file_name()).extension().is_some_and(|e| e == extension) {
            files += 1;
        }
    }
    (files, bytes)
}

/// Bytes reserved in a [`DirQuota`] for one file; what is still held is given back on drop.
#[derive(Debug)]
pub struct Reservation {
    quota: Arc<DirQuota>,
    held: u64,
}

impl Reservation {
    /// Reserves `n` more bytes; false (nothing reserved) when that would pass the limit.
    pub fn try_reserve(&mut self, n: u64) -> bool {
        let mut usage = self.quota.usage();
        if usage.used.saturating_add(usage.reserved).saturating_add(n) > self.quota.max_bytes {
            return false;
        }
        usage.reserved += n;
        self.held += n;
        true
    }

    /// Counts `written` bytes as used, out of `reserved` bytes of this reservation (given back;
    /// at most what is held).
    pub fn spend(&mut self, reserved: u64, written: u64) {
        let reserved = reserved.min(self.held);
        let mut usage = self.quota.usage();
        usage.reserved = usage.reserved.saturating_sub(reserved);
        usage.used = usage.used.saturating_add(written);
        self.held -= reserved;
    }

    /// Bytes still held.
    pub fn held(&self) -> u64 {
        self.held
    }

    /// Counts the file as stopped at the limit (for `/metrics`).
    pub fn count_stop(&self) {
        self.quota.stopped.fetch_add(1, Ordering::Relaxed);
    }
}

impl Drop for Reservation {
    fn drop(&mut self) {
        let mut usage = self.quota.usage();
        usage.reserved = usage.reserved.saturating_sub(self.held);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn admits_within_the_count_and_the_bytes_and_reserves_growth() {
        let dir = std::env::temp_dir().join(format!("needlesim-quota-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let q = DirQuota::new("recordings", "mcap", ("--max-recordings", 2), ("--max-recordings-mb", 1000));
        fs::write(dir.join("a.mcap"), vec![0u8; 300]).unwrap();
        fs::write(dir.join("a.mcap.owner"), vec![0u8; 100]).unwrap();
        let mut r = q.admit(&dir, 200).unwrap();
        assert_eq!(q.bytes_used(), 600);
        // A second admission sees the first's reservation.
        let e = q.admit(&dir, 500).unwrap_err();
        assert_eq!((e.flag, e.amount, e.need, e.limit), ("--max-recordings-mb", 600, 500, 1000));
        assert!(e.to_string().contains("--max-recordings-mb"), "{e}");
        // Growth: reserved before the write, counted after it.
        assert!(r.try_reserve(300));
        assert!(!r.try_reserve(200), "900 + 200 > 1000");
        r.spend(300, 250);
        assert_eq!(q.bytes_used(), 850);
        drop(r);
        assert_eq!(q.bytes_used(), 650, "the unspent reservation is given back");
        // The count: two .mcap files (the owner file is not one).
        fs::write(dir.join("b.mcap"), b"x").unwrap();
        let e = q.admit(&dir, 1).unwrap_err();
        assert_eq!((e.flag, e.amount, e.limit), ("--max-recordings", 2, 2));
        assert_eq!(q.refused(), 2);
        // Deleting files frees their room at the next start.
        fs::remove_file(dir.join("b.mcap")).unwrap();
        fs::remove_file(dir.join("a.mcap")).unwrap();
        assert!(q.admit(&dir, 800).is_ok());
        fs::remove_dir_all(&dir).unwrap();
    }
}
