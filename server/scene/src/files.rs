//! Where the files a scene names (`mesh.file`, a 3D `trajectory`) come from: one rule for every
//! caller. A scene sent to the server names no files ([`SceneFiles::None`]), an upload carries its
//! own by plain name ([`SceneFiles::Given`]), and only a user's local scene reads files next to it
//! ([`SceneFiles::Local`]), through [`read_local_file`] (the crate needlesim-localfile, shared with
//! the CLI and the device bridge): a regular file, not a link, of bounded size, opened so that a
//! FIFO or a device can neither block nor stream without end.

use std::path::Path;

use anyhow::{Result, bail};
pub use needlesim_localfile::{LocalFileError, MAX_LOCAL_FILE_BYTES, read_local_file};

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
