//! The shipped 3D example's Gmsh mesh is what its script makes: server/scenes/make_brachy_mesh.py
//! is run into a temporary directory with the test Python (the `gmsh` wheel) and the result
//! compared with the committed server/scenes/brachy-3d.msh — physical groups, node and
//! tetrahedron counts, region volumes.

use std::process::Command;

use needlesim_core::d3::{TetMesh, TetMeshLimits};
use needlesim_core::msh::parse_msh3d;
use needlesim_tests::{TempDir, repo_root};

/// The test Python with `gmsh` importable (installed with its pip when missing), or why not.
fn python_with_gmsh() -> Result<std::path::PathBuf, String> {
    let py = match std::env::var_os("NEEDLESIM_PYTHON") {
        Some(p) => std::path::PathBuf::from(p),
        None => repo_root().join("tests/.venv/bin/python"),
    };
    if !py.exists() {
        return Err(format!("no Python at {} (tests/run creates tests/.venv; or set NEEDLESIM_PYTHON)", py.display()));
    }
    let has = |py: &std::path::Path| Command::new(py).args(["-c", "import gmsh"]).output().is_ok_and(|o| o.status.success());
    if !has(&py) {
        let o = Command::new(&py).args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check", "gmsh==4.15.2"]).output();
        if !has(&py) {
            let why = o.map(|o| String::from_utf8_lossy(&o.stderr).into_owned()).unwrap_or_else(|e| e.to_string());
            return Err(format!("gmsh cannot be installed into {}: {why}", py.display()));
        }
    }
    Ok(py)
}

/// Region volumes (m³) in region order.
fn region_volumes(m: &TetMesh) -> Vec<f64> {
    let mut v = vec![0.0; m.region_names().len()];
    for t in 0..m.n_tets() {
        v[m.region_of_tet()[t]] += m.volume_m3(t);
    }
    v
}

#[test]
fn brachy_3d_msh_is_what_its_script_makes() {
    let py = match python_with_gmsh() {
        Ok(p) => p,
        Err(why) => {
            eprintln!("SKIPPED brachy_3d_msh_is_what_its_script_makes: {why}");
            return;
        }
    };
    let scenes = repo_root().join("server/scenes");
    let dir = TempDir::new("brachy3d");
    let out = dir.path().join("brachy-3d.msh");
    let o = Command::new(&py).arg(scenes.join("make_brachy_mesh.py")).arg(&out).output().expect("run the script");
    assert!(o.status.success(), "make_brachy_mesh.py failed: {}", String::from_utf8_lossy(&o.stderr));
    let limits = TetMeshLimits::default();
    let made = parse_msh3d(&std::fs::read_to_string(&out).unwrap(), &limits).expect("the script's mesh parses");
    let committed =
        parse_msh3d(&std::fs::read_to_string(scenes.join("brachy-3d.msh")).unwrap(), &limits).expect("the committed mesh parses");
    assert_eq!(made.version, committed.version);
    let (a, b) = (&made.mesh, &committed.mesh);
    assert_eq!(a.region_names(), b.region_names());
    assert_eq!(a.boundary_sets().keys().collect::<Vec<_>>(), b.boundary_sets().keys().collect::<Vec<_>>());
    // Another Gmsh version may place a few nodes differently: counts within 5 %, volumes 1 %.
    let close = |x: usize, y: usize| (x as f64 - y as f64).abs() <= 0.05 * y as f64;
    assert!(
        close(a.n_nodes(), b.n_nodes()) && close(a.n_tets(), b.n_tets()),
        "made {} nodes / {} tets, committed {} / {}",
        a.n_nodes(),
        a.n_tets(),
        b.n_nodes(),
        b.n_tets()
    );
    for ((name, va), vb) in a.region_names().iter().zip(region_volumes(a)).zip(region_volumes(b)) {
        assert!((va / vb - 1.0).abs() < 0.01, "region {name}: made {va:e} m³, committed {vb:e} m³");
    }
    if a.n_nodes() != b.n_nodes() || a.n_tets() != b.n_tets() {
        eprintln!(
            "note: this Gmsh makes {} nodes / {} tets, the committed file has {} / {}",
            a.n_nodes(),
            a.n_tets(),
            b.n_nodes(),
            b.n_tets()
        );
    }
}
