//! Issue 34: VTK meshes. A VTU written by meshio from the shipped brachy-3d.msh (regions as the
//! integer cell data `gmsh:physical`) converts back with `needlesim-server mesh` to the same
//! regions and volumes (1e-9), and a scene on it gives `simulate`'s CSV of the `.msh` scene to
//! 1e-12; the same for a 2D triangle mesh; an uploaded VTU makes a 3D session; bad input is
//! refused by the command naming the problem.

use std::path::{Path, PathBuf};
use std::process::Command;

use needlesim_core::MeshLimits;
use needlesim_core::d3::{TetMesh, TetMeshLimits};
use needlesim_core::msh::{parse_msh, parse_msh3d};
use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, bin, connect, repo_root, run, text, with_token};

/// The labels of brachy-3d.msh's physical groups.
const BRACHY_LABELS: &str = "1=tissue,2=prostate,3=urethra,11=rectum_wall,12=back,13=front";

/// The test Python with `meshio` importable (installed with its pip when missing), or why not.
fn python_with_meshio() -> Result<PathBuf, String> {
    let py = match std::env::var_os("NEEDLESIM_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => repo_root().join("tests/.venv/bin/python"),
    };
    if !py.exists() {
        return Err(format!("no Python at {} (tests/run creates tests/.venv; or set NEEDLESIM_PYTHON)", py.display()));
    }
    let has = |py: &Path| Command::new(py).args(["-c", "import meshio"]).output().is_ok_and(|o| o.status.success());
    if !has(&py) {
        let o = Command::new(&py).args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check", "meshio==5.3.5"]).output();
        if !has(&py) {
            let why = o.map(|o| String::from_utf8_lossy(&o.stderr).into_owned()).unwrap_or_else(|e| e.to_string());
            return Err(format!("meshio cannot be installed into {}: {why}", py.display()));
        }
    }
    Ok(py)
}

/// Writes `msh` as meshio's VTU (base64 binary, uncompressed: exact coordinates), ASCII VTU and
/// ASCII legacy VTK into `dir` as `stem.vtu`, `stem-ascii.vtu`, `stem.vtk`; the labels are
/// `gmsh:physical`, the only cell data (meshio's cell sets dropped).
fn meshio_vtk(py: &Path, msh: &Path, dir: &Path, stem: &str) {
    let script = format!(
        "import meshio\nm = meshio.read({msh:?})\nc = meshio.Mesh(m.points, m.cells, cell_data={{'gmsh:physical': m.cell_data['gmsh:physical']}})\n\
         meshio.vtu.write({b:?}, c, binary=True, compression=None)\nmeshio.vtu.write({a:?}, c, binary=False)\nmeshio.vtk.write({l:?}, c, binary=False)\n",
        msh = msh.to_str().unwrap(),
        b = dir.join(format!("{stem}.vtu")).to_str().unwrap(),
        a = dir.join(format!("{stem}-ascii.vtu")).to_str().unwrap(),
        l = dir.join(format!("{stem}.vtk")).to_str().unwrap(),
    );
    let o = Command::new(py).args(["-c", &script]).output().expect("run python");
    assert!(o.status.success(), "meshio failed: {}", String::from_utf8_lossy(&o.stderr));
}

/// `needlesim-server mesh INPUT --labels LABELS -o OUT`.
fn mesh_command(input: &Path, labels: &str, out: &Path) -> std::process::Output {
    run(Command::new(bin("needlesim-server")).arg("mesh").arg(input).args(["--labels", labels, "-o"]).arg(out))
}

fn volumes(m: &TetMesh) -> Vec<f64> {
    let mut v = vec![0.0; m.region_names().len()];
    for t in 0..m.n_tets() {
        v[m.region_of_tet()[t]] += m.volume_m3(t);
    }
    v
}

/// Two `simulate` CSVs agree: the same header and rows, every number within `tol`.
fn assert_csv_close(a: &str, b: &str, tol: f64) -> f64 {
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    assert_eq!(la.len(), lb.len(), "row counts");
    assert!(la.len() > 100, "a time series: {a:.300}");
    assert_eq!(la[0], lb[0], "headers");
    let mut worst = 0.0f64;
    for (k, (ra, rb)) in la.iter().zip(&lb).enumerate().skip(1) {
        for (x, y) in ra.split(',').zip(rb.split(',')) {
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) => {
                    worst = worst.max((x - y).abs());
                    assert!((x - y).abs() <= tol, "row {k}: {x} vs {y}\n{ra}\n{rb}");
                }
                _ => assert_eq!(x, y, "row {k}"),
            }
        }
    }
    worst
}

/// The done-when of issue 34's VTK item: mesh → same regions, volumes and sets; the scene on the
/// VTU simulates as the `.msh` scene.
#[test]
fn brachy_vtu_from_meshio_converts_back_and_simulates_as_the_msh_scene() {
    let py = match python_with_meshio() {
        Ok(p) => p,
        Err(why) => {
            eprintln!("SKIPPED brachy_vtu_from_meshio_converts_back_and_simulates_as_the_msh_scene: {why}");
            return;
        }
    };
    let scenes = repo_root().join("server/scenes");
    let dir = TempDir::new("vtk-brachy");
    meshio_vtk(&py, &scenes.join("brachy-3d.msh"), dir.path(), "brachy");
    let limits = TetMeshLimits::default();
    let shipped = parse_msh3d(&std::fs::read_to_string(scenes.join("brachy-3d.msh")).unwrap(), &limits).unwrap().mesh;
    for input in ["brachy.vtu", "brachy-ascii.vtu", "brachy.vtk"] {
        let out = dir.join(&format!("{input}.msh"));
        let o = mesh_command(&dir.join(input), BRACHY_LABELS, &out);
        let (stdout, err) = text(&o);
        assert!(o.status.success(), "{input}: {err}");
        assert!(stdout.contains("3D, 4559 nodes, 22397 elements"), "{input}: {stdout}");
        let back = parse_msh3d(&std::fs::read_to_string(&out).unwrap(), &limits).unwrap();
        assert_eq!(back.version, "4.1");
        let m = &back.mesh;
        assert_eq!(m.region_names(), shipped.region_names(), "{input}");
        assert_eq!(m.boundary_sets(), shipped.boundary_sets(), "{input}: the same boundary sets, node for node");
        assert_eq!((m.n_nodes(), m.n_tets()), (shipped.n_nodes(), shipped.n_tets()), "{input}");
        for ((name, a), b) in m.region_names().iter().zip(volumes(m)).zip(volumes(&shipped)) {
            assert!((a - b).abs() <= 1e-9 * b, "{input}: region {name}: {a:e} m³ vs {b:e} m³");
        }
        if input == "brachy.vtu" {
            assert_eq!(m.nodes_m(), shipped.nodes_m(), "binary VTU: the coordinates exactly");
        }
    }
    // The scene on the binary VTU against the shipped .msh scene.
    let toml = std::fs::read_to_string(scenes.join("brachy-3d.toml")).unwrap();
    let old = "[mesh]\ntype = \"msh\"\nfile = \"brachy-3d.msh\"\n";
    assert!(toml.contains(old));
    let vtu_mesh = "[mesh]\ntype = \"vtu\"\nfile = \"brachy.vtu\"\nlabels = { 1 = \"tissue\", 2 = \"prostate\", 3 = \"urethra\", 11 = \"rectum_wall\", 12 = \"back\", 13 = \"front\" }\n";
    std::fs::write(dir.join("brachy-vtu.toml"), toml.replace(old, vtu_mesh)).unwrap();
    std::fs::copy(scenes.join("brachy-3d.csv"), dir.join("brachy-3d.csv")).unwrap();
    let simulate = |scene: &Path| {
        let o = run(Command::new(bin("needlesim-server")).args(["simulate", "--scene"]).arg(scene));
        let (out, err) = text(&o);
        assert!(o.status.success(), "{}: {err}", scene.display());
        out
    };
    let csv_msh = simulate(&scenes.join("brachy-3d.toml"));
    let csv_vtu = simulate(&dir.join("brachy-vtu.toml"));
    let worst = assert_csv_close(&csv_msh, &csv_vtu, 1e-12);
    eprintln!("brachy-3d on the VTU: {} rows, largest difference from the .msh scene {worst:e}", csv_vtu.lines().count() - 1);
}

/// A 2D triangle VTU (meshio's, from the core's 2D test mesh): `mesh` gives back its regions and
/// areas, and a 2D scene on it simulates as the scene on the `.msh`.
#[test]
fn a_2d_triangle_vtu_converts_back_and_simulates_as_its_msh() {
    let py = match python_with_meshio() {
        Ok(p) => p,
        Err(why) => {
            eprintln!("SKIPPED a_2d_triangle_vtu_converts_back_and_simulates_as_its_msh: {why}");
            return;
        }
    };
    let dir = TempDir::new("vtk-2d");
    let msh = repo_root().join("server/core/testdata/inclusion_v41.msh");
    std::fs::copy(&msh, dir.join("inclusion.msh")).unwrap();
    meshio_vtk(&py, &msh, dir.path(), "inclusion");
    let labels = "1=tissue,2=inclusion,11=fixed_bottom,12=needle";
    let limits = MeshLimits::default();
    let shipped = parse_msh(&std::fs::read_to_string(&msh).unwrap(), &limits).unwrap().mesh;
    let area = |m: &needlesim_core::Mesh| {
        let mut a = vec![0.0; m.region_names().len()];
        for (t, &r) in m.triangles().iter().zip(m.region_of_tri()) {
            let p = t.map(|i| m.nodes_m()[i]);
            a[r] += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])).abs();
        }
        a
    };
    for input in ["inclusion.vtu", "inclusion-ascii.vtu", "inclusion.vtk"] {
        let out = dir.join(&format!("{input}.msh"));
        let o = mesh_command(&dir.join(input), labels, &out);
        assert!(o.status.success(), "{input}: {}", text(&o).1);
        let m = parse_msh(&std::fs::read_to_string(&out).unwrap(), &limits).unwrap().mesh;
        assert_eq!(m.region_names(), shipped.region_names(), "{input}");
        assert_eq!(m.boundary_sets(), shipped.boundary_sets(), "{input}");
        for ((name, a), b) in m.region_names().iter().zip(area(&m)).zip(area(&shipped)) {
            assert!((a - b).abs() <= 1e-9 * b, "{input}: region {name}: {a:e} m² vs {b:e} m²");
        }
    }
    let scene = |mesh: &str| {
        format!(
            "name = \"inclusion\"\nfixed = [\"fixed_bottom\"]\n\n{mesh}\n[[regions]]\nname = \"tissue\"\nmaterial = \"pvc_phantom\"\n\n\
             [[regions]]\nname = \"inclusion\"\nmaterial = \"pvc_phantom\"\nyoung_modulus_pa = 90e3\n\n\
             [needle]\nlength_m = 0.1\nbase = [0.05, 0.205, -1.5707963267948966]\n"
        )
    };
    std::fs::write(dir.join("msh.toml"), scene("[mesh]\ntype = \"msh\"\nfile = \"inclusion.msh\"\n")).unwrap();
    std::fs::write(
        dir.join("vtu.toml"),
        scene("[mesh]\ntype = \"vtu\"\nfile = \"inclusion.vtu\"\nlabels = { 1 = \"tissue\", 2 = \"inclusion\", 11 = \"fixed_bottom\", 12 = \"needle\" }\n"),
    )
    .unwrap();
    let traj = repo_root().join("server/scenes/paper-phantom.csv");
    let simulate = |scene: &str| {
        let o =
            run(Command::new(bin("needlesim-server")).args(["simulate", "--scene"]).arg(dir.join(scene)).arg("--trajectory").arg(&traj));
        let (out, err) = text(&o);
        assert!(o.status.success(), "{scene}: {err}");
        out
    };
    let worst = assert_csv_close(&simulate("msh.toml"), &simulate("vtu.toml"), 1e-12);
    eprintln!("2D inclusion on the VTU: largest difference from the .msh scene {worst:e}");
}

/// The `mesh` command refuses bad input, naming the problem, and writes nothing.
#[test]
fn the_mesh_command_refuses_bad_input_naming_the_problem() {
    let dir = TempDir::new("vtk-bad");
    let cube = "# vtk DataFile Version 4.2\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n\
                CELLS 2 10\n4 0 1 2 3\n4 1 2 3 4\nCELL_TYPES 2\n10\n10\nCELL_DATA 2\nSCALARS labels int 1\nLOOKUP_TABLE default\n1\n2\n";
    std::fs::write(dir.join("cube.vtk"), cube).unwrap();
    // The second tetrahedron (1, 2, 3, 4) is positive: (1,1,1) lies beyond the face 1-2-3.
    let out = dir.join("out.msh");
    let o = mesh_command(&dir.join("cube.vtk"), "1=a,2=b", &out);
    assert!(o.status.success(), "{}", text(&o).1);
    std::fs::remove_file(&out).unwrap();
    let inverted = cube.replace("4 1 2 3 4", "4 2 1 3 4");
    std::fs::write(dir.join("inverted.vtk"), inverted).unwrap();
    std::fs::write(dir.join("hex.vtk"), cube.replace("CELL_TYPES 2\n10\n10", "CELL_TYPES 2\n10\n12")).unwrap();
    std::fs::write(dir.join("broken.vtu"), "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece>")
        .unwrap();
    std::fs::write(dir.join("head.nii.gz"), [0x1f, 0x8b, 0, 0]).unwrap();
    // One byte over the local-file limit, sparse: refused before it is read.
    let big = std::fs::File::create(dir.join("big.vtu")).unwrap();
    big.set_len(needlesim_scene::MAX_LOCAL_FILE_BYTES + 1).unwrap();
    drop(big);
    for (input, labels, want) in [
        ("cube.vtk", "1=a", "unknown label: 1 cells are labelled 2 (1 tetrahedra), which the labels map (1=a) does not name"),
        ("cube.vtk", "1=a,2=b,3=c", "empty region: label 3 ('c') of the labels map is on no cell of the file"),
        ("cube.vtk", "", "labels missing"),
        ("inverted.vtk", "1=a,2=b", "inverted element: tetrahedron 1 (cell 1 of the file) has a negative volume"),
        ("hex.vtk", "1=a,2=b", "unsupported cell type: 1 cells of VTK type 12 (hexahedron)"),
        ("broken.vtu", "1=a", "malformed VTK XML"),
        ("head.nii.gz", "1=a", "labelmaps (NIfTI, NRRD) are not yet supported"),
        ("big.vtu", "1=a", "over the limit of 268435456 bytes"),
    ] {
        let o = mesh_command(&dir.join(input), labels, &out);
        let (_, err) = text(&o);
        assert!(!o.status.success() && !err.contains("panicked"), "{input}: {err}");
        assert!(err.contains(want), "{input}: the error names the problem ({want}): {err}");
        assert!(!out.exists(), "{input}: nothing written");
    }
}

/// Over the API a VTU comes as the uploaded mesh of `uploaded3d` (text, within the upload
/// limit) and makes a session; a `scene_toml` naming a VTU file is refused unread.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_uploaded_vtu_makes_a_3d_session_and_a_named_one_is_refused() {
    let py = match python_with_meshio() {
        Ok(p) => p,
        Err(why) => {
            eprintln!("SKIPPED an_uploaded_vtu_makes_a_3d_session_and_a_named_one_is_refused: {why}");
            return;
        }
    };
    let scenes = repo_root().join("server/scenes");
    let dir = TempDir::new("vtk-upload");
    meshio_vtk(&py, &scenes.join("brachy-3d.msh"), dir.path(), "brachy");
    let toml = std::fs::read_to_string(scenes.join("brachy-3d.toml")).unwrap().replace("trajectory = \"brachy-3d.csv\"\n", "").replace(
        "[mesh]\ntype = \"msh\"\nfile = \"brachy-3d.msh\"\n",
        "[mesh]\ntype = \"vtu\"\nfile = \"brachy.vtu\"\nlabels = { 1 = \"tissue\", 2 = \"prostate\", 3 = \"urethra\", 11 = \"rectum_wall\", 12 = \"back\", 13 = \"front\" }\n",
    );
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let req = |source| pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(source) }),
        tick_rate_hz: 1000.0,
        record: false,
        device_channel: false,
    };
    let upload = pb::UploadedScene3d {
        scene_toml: toml.clone(),
        mesh_file_name: "brachy.vtu".into(),
        mesh_text: std::fs::read_to_string(dir.join("brachy.vtu")).unwrap(),
    };
    let created =
        c.create_session(req(pb::scene_source::Source::Uploaded3d(upload))).await.expect("the uploaded VTU makes a session").into_inner();
    let info = created.session.unwrap();
    assert_eq!((info.dimension, info.n_tetrahedra), (3, 22397), "{info:?}");
    c.close_session(with_token(pb::CloseSessionRequest { session_id: info.session_id }, &created.controller_token)).await.unwrap();
    let e = c.create_session(req(pb::scene_source::Source::SceneToml(toml))).await.expect_err("a scene naming a file is refused");
    assert_eq!(e.code(), tonic::Code::InvalidArgument, "{e:?}");
    assert!(e.message().contains("mesh.file = \"brachy.vtu\": a scene sent to the server cannot name files"), "{}", e.message());
}
