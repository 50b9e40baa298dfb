//! The one rule for reading a local file a user names (a scene, a mesh, a trajectory, a
//! recording, a certificate, a token file): [`read_local_file`] and [`read_local_bytes`] accept a
//! regular file, not a symbolic link, of bounded size (a bound for each kind of file, below),
//! opened so that a FIFO or a device can neither block nor stream without end; errors name the
//! path and the problem and never hold the file's contents. The scene crate, the server, the CLI,
//! the device bridge, the lab tools and the Python package all read through it.
//!
//! Files on the kernel's pseudo file systems are refused too (Linux: the file system type of the
//! opened handle, `fstatfs`, is proc, sysfs, debugfs, tracefs, securityfs, cgroup, cgroup2,
//! configfs, efivarfs, bpf or pstore): their files are regular files of size 0 whose reads make
//! up their contents (`/proc/self/environ` is the process's environment, `/proc/self/pagemap`
//! reads to any bound), none is a scene, a mesh or a certificate, and checking the handle catches
//! every name for them (`/proc`, a bind mount, `../../proc`). `/dev` holds devices, refused as
//! not regular files; tmpfs (`/tmp`, `/dev/shm`) is an ordinary file system and allowed.
//!
//! What the callers parse is reported likewise without the file's lines: a TOML error as line,
//! column and the parser's words (`needlesim_scene::limit::toml_message`), a CSV error as line,
//! column name and the problem, a value quoted at most clipped.

use std::fs::File;
use std::io::Read;
use std::path::Path;

/// Largest scene, mesh or trajectory file, in bytes (256 MiB: above the text of a mesh at the
/// default node limits, far below the memory of a machine).
pub const MAX_LOCAL_FILE_BYTES: u64 = 256 << 20;

/// Largest token file (`--admin-token-file`), in bytes: a token is a line of tens of characters.
pub const MAX_TOKEN_FILE_BYTES: u64 = 4 << 10;

/// Largest PEM certificate (chain) or private key file, in bytes (1 MiB: a chain of hundreds of
/// certificates).
pub const MAX_CERTIFICATE_BYTES: u64 = 1 << 20;

/// What a file that is not a regular file is, for errors ("a directory", "a FIFO", …).
fn kind_of(t: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() { "a directory" } else { "not a file" }
}

/// Why a local file was not read: it could not be (the system's error), or it was refused.
#[derive(Debug, thiserror::Error)]
pub enum LocalFileError {
    /// Opening, inspecting or reading it failed (missing, no permission, …).
    #[error("cannot read {path}: {source}")]
    Io { path: String, source: std::io::Error },
    /// It is not a file to read: a link, not a regular file, too large, not UTF-8.
    #[error("{path}: {problem}")]
    Refused { path: String, problem: String },
}

impl LocalFileError {
    /// The path as given.
    pub fn path(&self) -> &str {
        match self {
            LocalFileError::Io { path, .. } | LocalFileError::Refused { path, .. } => path,
        }
    }

    /// Why it was not read, without the path: the system's error or the problem.
    pub fn reason(&self) -> String {
        match self {
            LocalFileError::Io { source, .. } => source.to_string(),
            LocalFileError::Refused { problem, .. } => problem.clone(),
        }
    }

    /// "cannot read the {kind} {path}: {reason}", for a tool's error (`kind`: "scene",
    /// "CA certificate", …).
    pub fn named(&self, kind: &str) -> String {
        format!("cannot read the {kind} {}: {}", self.path(), self.reason())
    }
}

/// Opens a local file for reading: refused, naming the path and the problem, when it is a
/// symbolic link (the last component: name the file it points to), not a regular file (a
/// directory, a device such as /dev/zero, a FIFO, a socket), or larger than `max_bytes`. The file
/// is opened without following a link and without blocking (`O_NOFOLLOW | O_NONBLOCK`: a FIFO
/// swapped in after the first check cannot block the open), checked again on the open handle
/// (`fstat`), then `O_NONBLOCK` is cleared. Returns the file and its size in bytes; the caller
/// still reads at most `max_bytes + 1` bytes (a file that grows), as [`read_local_bytes`] does.
pub fn open_local_file(path: &Path, max_bytes: u64) -> Result<(File, u64), LocalFileError> {
    let io = |source| LocalFileError::Io { path: path.display().to_string(), source };
    let refused = |problem: String| LocalFileError::Refused { path: path.display().to_string(), problem };
    let meta = std::fs::symlink_metadata(path).map_err(io)?;
    if meta.file_type().is_symlink() {
        return Err(refused("is a symbolic link; name the file it points to".into()));
    }
    if !meta.is_file() {
        return Err(refused(format!("not a regular file ({})", kind_of(meta.file_type()))));
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(|e| {
        #[cfg(unix)]
        if e.raw_os_error() == Some(libc::ELOOP) {
            return refused("is a symbolic link; name the file it points to".into());
        }
        io(e)
    })?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(refused(format!("not a regular file ({})", kind_of(meta.file_type()))));
    }
    #[cfg(target_os = "linux")]
    if let Some(fs) = pseudo_file_system(&file).map_err(io)? {
        return Err(refused(format!(
            "on the kernel's {fs} file system, whose files are made up as they are read; \
             local files on /proc, /sys and their kin are refused (copy it to a regular file)"
        )));
    }
    if meta.len() > max_bytes {
        return Err(refused(over(meta.len(), max_bytes)));
    }
    #[cfg(unix)]
    {
        use std::os::fd::AsRawFd;
        // SAFETY: fcntl on a descriptor this function owns; no memory is passed.
        let flags = unsafe { libc::fcntl(file.as_raw_fd(), libc::F_GETFL) };
        // SAFETY: as above.
        if flags < 0 || unsafe { libc::fcntl(file.as_raw_fd(), libc::F_SETFL, flags & !libc::O_NONBLOCK) } < 0 {
            return Err(io(std::io::Error::last_os_error()));
        }
    }
    Ok((file, meta.len()))
}

/// The kernel's pseudo file systems, by `statfs` magic (linux/magic.h), whose files are refused.
#[cfg(target_os = "linux")]
const PSEUDO_FILE_SYSTEMS: [(u32, &str); 11] = [
    (0x0000_9fa0, "proc"),
    (0x6265_6572, "sysfs"),
    (0x6462_6720, "debugfs"),
    (0x7472_6163, "tracefs"),
    (0x7363_6673, "securityfs"),
    (0x0027_e0eb, "cgroup"),
    (0x6367_7270, "cgroup2"),
    (0x6265_6570, "configfs"),
    (0xde5e_81e4, "efivarfs"),
    (0xcafe_4a11, "bpf"),
    (0x6165_676c, "pstore"),
];

/// The name of the pseudo file system `file` is on ([`PSEUDO_FILE_SYSTEMS`]), by `fstatfs` on
/// the open handle; `None` on any other.
#[cfg(target_os = "linux")]
fn pseudo_file_system(file: &File) -> std::io::Result<Option<&'static str>> {
    use std::os::fd::AsRawFd;
    let mut st = std::mem::MaybeUninit::<libc::statfs>::uninit();
    // SAFETY: fstatfs writes a statfs into the buffer it is given, on a descriptor we own.
    if unsafe { libc::fstatfs(file.as_raw_fd(), st.as_mut_ptr()) } < 0 {
        return Err(std::io::Error::last_os_error());
    }
    // SAFETY: fstatfs succeeded, so it filled the struct.
    let st = unsafe { st.assume_init() };
    // f_type is a signed word on some targets: compare its low 32 bits, the magic's width.
    let magic = st.f_type as u64 as u32;
    Ok(PSEUDO_FILE_SYSTEMS.iter().find(|(m, _)| *m == magic).map(|(_, name)| *name))
}

fn over(n: u64, max_bytes: u64) -> String {
    format!("{n} bytes, over the limit of {max_bytes} bytes")
}

/// Reads a local file of at most `max_bytes` bytes, by the rule of [`open_local_file`] (a
/// regular file, not a link, opened without blocking, within the bound), reading at most
/// `max_bytes + 1` bytes (a file that grows is refused). Errors never hold the file's contents.
pub fn read_local_bytes(path: &Path, max_bytes: u64) -> Result<Vec<u8>, LocalFileError> {
    let (file, len) = open_local_file(path, max_bytes)?;
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|source| LocalFileError::Io { path: path.display().to_string(), source })?;
    if bytes.len() as u64 > max_bytes {
        return Err(LocalFileError::Refused { path: path.display().to_string(), problem: over(bytes.len() as u64, max_bytes) });
    }
    Ok(bytes)
}

/// Reads a local text file of at most `max_bytes` bytes ([`read_local_bytes`]), refused when it
/// is not UTF-8 (the offset named, the bytes never quoted).
pub fn read_local_file(path: &Path, max_bytes: u64) -> Result<String, LocalFileError> {
    let bytes = read_local_bytes(path, max_bytes)?;
    String::from_utf8(bytes).map_err(|e| LocalFileError::Refused {
        path: path.display().to_string(),
        problem: format!("not UTF-8 text (invalid byte at offset {})", e.utf8_error().valid_up_to()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn temp_dir(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("needlesim-localfile-{test}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn refused(path: &Path, max_bytes: u64) -> String {
        format!("{:#}", read_local_file(path, max_bytes).err().unwrap_or_else(|| panic!("{}: must be refused", path.display())))
    }

    #[test]
    fn issue_35_devices_fifos_links_and_oversized_files_are_refused_without_reading_them() {
        let dir = temp_dir("refused");
        // /dev/zero would be read without end: refused before anything is read.
        let e = refused(Path::new("/dev/zero"), MAX_LOCAL_FILE_BYTES);
        assert!(e.contains("/dev/zero") && e.contains("not a regular file") && e.contains("character device"), "{e}");
        // A FIFO nobody writes to would block the reader: refused, not opened.
        let fifo = dir.join("pipe.msh");
        let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0, "mkfifo");
        let e = refused(&fifo, MAX_LOCAL_FILE_BYTES);
        assert!(e.contains("pipe.msh") && e.contains("not a regular file (a FIFO)"), "{e}");
        // A link, even to a readable regular file, is not followed.
        let secret = dir.join("secret.txt");
        std::fs::write(&secret, "root:x:0:0:root:/root:/bin/bash\n").unwrap();
        let link = dir.join("mesh.msh");
        std::os::unix::fs::symlink(&secret, &link).unwrap();
        let e = refused(&link, MAX_LOCAL_FILE_BYTES);
        assert!(e.contains("mesh.msh") && e.contains("symbolic link") && !e.contains("root:"), "{e}");
        // A link to /dev/zero likewise.
        let zero = dir.join("zero.toml");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        assert!(refused(&zero, MAX_LOCAL_FILE_BYTES).contains("symbolic link"));
        // A directory.
        assert!(refused(&dir, MAX_LOCAL_FILE_BYTES).contains("not a regular file (a directory)"));
        // Over the bound, by one byte; at the bound it is read.
        let big = dir.join("big.csv");
        std::fs::write(&big, "x".repeat(101)).unwrap();
        let e = refused(&big, 100);
        assert!(e.contains("big.csv") && e.contains("101 bytes, over the limit of 100 bytes") && !e.contains("xxx"), "{e}");
        assert_eq!(read_local_file(&big, 101).unwrap().len(), 101);
        // Not UTF-8: refused without quoting the bytes.
        let bin = dir.join("bin.msh");
        std::fs::write(&bin, b"ab\xff\xfe").unwrap();
        let e = refused(&bin, 100);
        assert!(e.contains("not UTF-8 text (invalid byte at offset 2)"), "{e}");
        // A missing file names its path.
        assert!(refused(&dir.join("missing.msh"), 100).contains("missing.msh"));
        // A regular file is read.
        assert_eq!(read_local_file(&secret, 100).unwrap(), "root:x:0:0:root:/root:/bin/bash\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn issue_35_files_on_proc_and_sys_are_refused_without_reading_them() {
        // /proc/self/environ would put the environment in a parse error; /proc/self/pagemap reads
        // to any bound; a /sys file is no scene either: refused by the handle's file system.
        for (path, fs) in [
            ("/proc/self/environ", "proc"),
            ("/proc/self/pagemap", "proc"),
            ("/proc/self/cmdline", "proc"),
            ("/proc/self/root/proc/self/environ", "proc"),
            ("/sys/kernel/mm/transparent_hugepage/enabled", "sysfs"),
        ] {
            if std::fs::symlink_metadata(path).is_err() {
                continue;
            }
            let e = read_local_bytes(Path::new(path), MAX_LOCAL_FILE_BYTES).unwrap_err();
            let m = e.to_string();
            assert!(matches!(e, LocalFileError::Refused { .. }), "{m}");
            assert!(m.starts_with(&format!("{path}: on the kernel's {fs} file system")) && m.contains("/proc, /sys"), "{m}");
            assert!(!m.contains("PATH=") && !m.contains("HOME="), "{m}");
        }
        // A regular file elsewhere (the temporary directory, tmpfs or not) is still read.
        let dir = temp_dir("proc");
        std::fs::write(dir.join("a.toml"), "a = 1\n").unwrap();
        assert_eq!(read_local_file(&dir.join("a.toml"), 100).unwrap(), "a = 1\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn issue35_bytes_are_read_by_the_same_rule_and_the_handle_blocks_again() {
        let dir = temp_dir("bytes");
        let e = read_local_bytes(Path::new("/dev/zero"), 10).unwrap_err();
        assert_eq!(e.named("recording"), "cannot read the recording /dev/zero: not a regular file (a character device)");
        let bin = dir.join("bin");
        std::fs::write(&bin, b"ab\xff\xfe").unwrap();
        assert_eq!(read_local_bytes(&bin, 4).unwrap(), b"ab\xff\xfe");
        assert!(read_local_bytes(&bin, 3).unwrap_err().reason().contains("4 bytes, over the limit of 3 bytes"));
        let (file, len) = open_local_file(&bin, 4).unwrap();
        use std::os::fd::AsRawFd;
        let flags = unsafe { libc::fcntl(file.as_raw_fd(), libc::F_GETFL) };
        assert_eq!((len, flags & libc::O_NONBLOCK), (4, 0), "O_NONBLOCK is cleared after the check");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
