//! Where the files a scene names (`mesh.file`, a 3D `trajectory`) come from: one rule for every
//! caller. A scene sent to the server names no files ([`SceneFiles::None`]), an upload carries its
//! own by plain name ([`SceneFiles::Given`]), and only a user's local scene reads files next to it
//! ([`SceneFiles::Local`]), through [`read_local_file`]: a regular file, not a link, of bounded
//! size, opened so that a FIFO or a device can neither block nor stream without end.

use std::io::Read;
use std::path::Path;

use anyhow::{Result, bail};

/// Largest local file a scene, its mesh or its trajectory may be, in bytes (256 MiB: above the
/// text of a mesh at the default node limits, far below the memory of a machine).
pub const MAX_LOCAL_FILE_BYTES: u64 = 256 << 20;

/// Where the files a scene's TOML names are read from.
#[derive(Debug, Clone, Copy)]
pub enum SceneFiles<'a> {
    /// A local scene (command line, Python): files relative to this directory, each read by
    /// [`read_local_file`].
    Local(&'a Path),
    /// A scene from the API (`scene_toml`, Simulate, a shipped example): it names no files, and a
    /// reference is refused without anything being opened.
    None,
    /// Files sent with the scene (an upload), by plain name: `(name, text)`; any other name is
    /// refused without anything being opened.
    Given(&'a [(&'a str, &'a str)]),
}

impl SceneFiles<'_> {
    /// The text of the file `file` that a scene names; the caller adds the key (`mesh.file = …`).
    /// The error of a refused or unreadable file never holds the file's contents.
    pub fn read(&self, file: &str) -> Result<String> {
        match self {
            SceneFiles::Local(dir) => Ok(read_local_file(&dir.join(file), MAX_LOCAL_FILE_BYTES)?),
            SceneFiles::None => {
                bail!(
                    "a scene sent to the server cannot name files: send the mesh with the scene (scene.uploaded, scene.uploaded3d) or use a generated mesh, and the trajectory in the request"
                )
            }
            SceneFiles::Given(files) => match files.iter().find(|(name, _)| *name == file) {
                Some((_, text)) => Ok((*text).to_owned()),
                None => {
                    let names: Vec<&str> = files.iter().map(|(n, _)| *n).collect();
                    bail!("not among the files sent with the scene ({}); a scene sent to the server names no other files", names.join(", "))
                }
            },
        }
    }
}

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

/// Reads a local text file of at most `max_bytes` bytes: refused, naming the path and the
/// problem, when it is a symbolic link (the last component: name the file it points to), not a
/// regular file (a directory, a device such as /dev/zero, a FIFO, a socket), larger than
/// `max_bytes`, or not UTF-8. The file is opened without following a link and without blocking
/// (a FIFO swapped in after the check), checked again on the open handle, and read at most
/// `max_bytes + 1` bytes (a file that grows). Errors never hold the file's contents.
pub fn read_local_file(path: &Path, max_bytes: u64) -> Result<String, LocalFileError> {
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
    let file = options.open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(refused(format!("not a regular file ({})", kind_of(meta.file_type()))));
    }
    let over = |n: u64| refused(format!("{n} bytes, over the limit of {max_bytes} bytes"));
    if meta.len() > max_bytes {
        return Err(over(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(max_bytes.saturating_add(1)).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(over(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| refused(format!("not UTF-8 text (invalid byte at offset {})", e.utf8_error().valid_up_to())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn temp_dir(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("needlesim-scene-files-{test}-{}", std::process::id()));
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

    #[test]
    fn issue_35_api_scenes_name_no_files_and_uploads_only_their_own() {
        let dir = temp_dir("api");
        std::fs::write(dir.join("a.msh"), "secret").unwrap();
        for name in ["/etc/passwd", "../../../../etc/passwd", "a.msh"] {
            let e = format!("{:#}", SceneFiles::None.read(name).unwrap_err());
            assert!(e.contains("cannot name files") && !e.contains("root:") && !e.contains("secret"), "{e}");
        }
        let given = [("mesh.msh", "the mesh")];
        assert_eq!(SceneFiles::Given(&given).read("mesh.msh").unwrap(), "the mesh");
        for name in ["/etc/passwd", "../mesh.msh", "./mesh.msh", "a.msh"] {
            let e = format!("{:#}", SceneFiles::Given(&given).read(name).unwrap_err());
            assert!(e.contains("not among the files sent with the scene (mesh.msh)"), "{e}");
        }
        assert_eq!(SceneFiles::Local(&dir).read("a.msh").unwrap(), "secret");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn issue_35_scene_loaders_apply_the_rule() {
        use crate::{EXAMPLES, SceneLimits, load_scene, load_scene3d, parse_scene, parse_scene_with, parse_scene3d_with};
        let limits = &SceneLimits::from(&needlesim_core::MeshLimits::default());
        let phantom = EXAMPLES[0].1;
        let grid = "[mesh]\ntype = \"grid\"\nnx = 19\nny = 19\nwidth_m = 0.1\nheight_m = 0.1\n";
        assert!(phantom.contains(grid));
        let with_mesh = |f: &str| phantom.replace(grid, &format!("[mesh]\ntype = \"msh\"\nfile = \"{f}\"\n"));
        // From a client: nothing is opened, the key is named.
        let e = format!("{:#}", parse_scene_with(&with_mesh("/etc/passwd"), SceneFiles::None, limits).err().unwrap());
        assert!(e.contains("mesh.file = \"/etc/passwd\": a scene sent to the server cannot name files") && !e.contains("root:"), "{e}");
        let cube = include_str!("../../scenes/cube-phantom-3d.toml").replace("cube-phantom-3d.csv", "/etc/passwd");
        let e = format!("{:#}", parse_scene3d_with(&cube, SceneFiles::None, limits).err().unwrap());
        assert!(e.contains("trajectory = \"/etc/passwd\": a scene sent to the server cannot name files") && !e.contains("root:"), "{e}");
        // Local: /dev/zero as the scene or as its mesh is refused unread.
        for e in [
            format!("{:#}", load_scene("/dev/zero", limits).err().unwrap()),
            format!("{:#}", load_scene3d("/dev/zero", limits).unwrap_err()),
        ] {
            assert!(e.contains("/dev/zero: not a regular file (a character device)"), "{e}");
        }
        let e = format!("{:#}", parse_scene(&with_mesh("/dev/zero"), Path::new("."), limits).err().unwrap());
        assert!(e.contains("mesh.file = \"/dev/zero\"") && e.contains("not a regular file"), "{e}");
    }
}
