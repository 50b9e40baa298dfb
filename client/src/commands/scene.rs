//! The scene a command sends (`sessions create`, `simulate`): a shipped example, a TOML, or a 3D
//! TOML with its Gmsh mesh, and its dimension when it can be told here.

use anyhow::{Result, anyhow, bail};
use needlesim_proto::v1 as pb;

use crate::SceneArgs;

/// The shipped 3D examples (the server's `EXAMPLES3D`); the others are 2D.
const EXAMPLES3D: [&str; 3] = ["cube-phantom-3d", "brachy-3d", "fig3-target-3d"];
/// The shipped 2D examples.
const EXAMPLES2D: [&str; 4] = ["paper-phantom", "fig3-target", "fig4-steering", "bevel-tip"];

/// The scene to send: an example, a TOML, or a 3D TOML with its Gmsh `mesh` (uploaded3d).
pub(super) fn scene_source(s: &SceneArgs, mesh: Option<&std::path::Path>) -> Result<(pb::SceneSource, String)> {
    if let (Some(m), None) = (mesh, &s.scene) {
        bail!("--mesh {} goes with --scene FILE.toml (the 3D scene whose [mesh] file names it), not --example", m.display());
    }
    if let Some(name) = &s.example {
        return Ok((pb::SceneSource { source: Some(pb::scene_source::Source::Example(name.clone())) }, format!("example '{name}'")));
    }
    let Some(path) = &s.scene else { bail!("give --example NAME or --scene FILE.toml") };
    let text = read_local(path, "scene")?;
    let Some(mesh) = mesh else {
        return Ok((pb::SceneSource { source: Some(pb::scene_source::Source::SceneToml(text)) }, format!("scene {}", path.display())));
    };
    if !toml_is_3d(&text) {
        bail!("--mesh {} is for a 3D scene, but {} has no `dim = 3`", mesh.display(), path.display());
    }
    let mesh_text = read_local(mesh, "mesh")?;
    let name = mesh
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| anyhow!("--mesh {}: the path has no file name the scene could name", mesh.display()))?;
    let upload = pb::UploadedScene3d { scene_toml: text, mesh_file_name: name.to_owned(), mesh_text };
    Ok((
        pb::SceneSource { source: Some(pb::scene_source::Source::Uploaded3d(upload)) },
        format!("scene {} with mesh {}", path.display(), mesh.display()),
    ))
}

/// A scene or mesh file named on the command line, by the one rule for local files (a regular
/// file, not a link, at most [`needlesim_localfile::MAX_LOCAL_FILE_BYTES`], opened without
/// blocking); `kind` names it in the error.
pub(crate) fn read_local(path: &std::path::Path, kind: &str) -> Result<String> {
    needlesim_localfile::read_local_file(path, needlesim_localfile::MAX_LOCAL_FILE_BYTES).map_err(|e| anyhow!("{}", e.named(kind)))
}

/// Whether a scene TOML declares `dim = 3` (a top-level key line; the server decides for real).
fn toml_is_3d(text: &str) -> bool {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or_default().replace([' ', '\t'], ""))
        .take_while(|l| !l.starts_with('['))
        .any(|l| l == "dim=3")
}

/// The dimension of a scene when it can be told here (a shipped example, a TOML); None for an
/// unknown example name (the server names the examples).
pub(super) fn scene_dimension(s: &SceneArgs, with_mesh: bool) -> Result<Option<u32>> {
    if let Some(name) = &s.example {
        return Ok(if EXAMPLES3D.contains(&name.as_str()) {
            Some(3)
        } else if EXAMPLES2D.contains(&name.as_str()) {
            Some(2)
        } else {
            None
        });
    }
    match &s.scene {
        Some(p) => {
            let text = read_local(p, "scene")?;
            Ok(Some(if with_mesh || toml_is_3d(&text) { 3 } else { 2 }))
        }
        None => Ok(None),
    }
}
