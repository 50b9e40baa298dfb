//! Issue 35, items 1 and 2, through the real binaries: a scene from a client (`scene_toml` 2D or
//! 3D, `uploaded3d`, Simulate, an example name) makes the server open no file it names — an
//! absolute path, a `../` path, the admin token file, a FIFO — and the refusal names the key
//! without quoting any file; `simulate --scene` refuses /dev/zero, a FIFO and a link as scene or
//! mesh file, at once, and still reads a scene's own files next to it.

use std::time::Duration;

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, bin, connect};
use tonic::Code;

const PHANTOM: &str = include_str!("../../server/scenes/paper-phantom.toml");
const CUBE: &str = include_str!("../../server/scenes/cube-phantom-3d.toml");
const BRACHY: &str = include_str!("../../server/scenes/brachy-3d.toml");
const BRACHY_MSH: &str = include_str!("../../server/scenes/brachy-3d.msh");

/// The first line of the admin token file, which must never reach a client.
const SECRET: &str = "needlesim-admin-secret-35-0123456789";

fn source(s: pb::scene_source::Source) -> Option<pb::SceneSource> {
    Some(pb::SceneSource { source: Some(s) })
}

/// The paper phantom with its grid replaced by the Gmsh file `file`.
fn phantom_with_mesh_file(file: &str) -> String {
    let grid = "[mesh]\ntype = \"grid\"\nnx = 19\nny = 19\nwidth_m = 0.1\nheight_m = 0.1\n";
    assert!(PHANTOM.contains(grid));
    PHANTOM.replace(grid, &format!("[mesh]\ntype = \"msh\"\nfile = \"{file}\"\n"))
}

/// The cube phantom, smaller, its trajectory file being `file`.
fn cube_with_trajectory(file: &str) -> String {
    let small = CUBE.replace("nx = 21\nny = 21\nnz = 21", "nx = 6\nny = 6\nnz = 6");
    assert!(small.contains("trajectory = \"cube-phantom-3d.csv\""));
    small.replace("trajectory = \"cube-phantom-3d.csv\"", &format!("trajectory = \"{file}\""))
}

/// The brachytherapy phantom, its mesh file being `file`.
fn brachy_with_mesh_file(file: &str) -> String {
    assert!(BRACHY.contains("file = \"brachy-3d.msh\""));
    BRACHY.replace("file = \"brachy-3d.msh\"", &format!("file = \"{file}\""))
}

/// Asserts that `e` is INVALID_ARGUMENT naming `field` and `key` and quoting no file.
fn assert_refused(what: &str, e: &tonic::Status, field: &str, key: &str) {
    let m = e.message();
    assert_eq!(e.code(), Code::InvalidArgument, "{what}: {m}");
    assert!(m.contains(field) && m.contains(key), "{what}: the message names {field} and {key}: {m}");
    for leak in [SECRET, "root:", "needlesim-admin"] {
        assert!(!m.contains(leak), "{what}: the message quotes a file ({leak}): {m}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_scenes_from_clients_open_no_file_they_name() {
    let dir = TempDir::new("file-refs");
    let token_file = dir.join("admin-token");
    std::fs::write(&token_file, format!("{SECRET}\n")).unwrap();
    let token = token_file.display().to_string();
    // A FIFO nobody writes to: opening it for reading would block a server thread.
    let fifo = dir.join("pipe");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs").success());
    let fifo = fifo.display().to_string();
    let server = ServerProcess::start(&["--default-scene", "none", "--admin-token-file", &token]);
    let ch = connect(&server).await;
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let mut sim = pb::simulation_service_client::SimulationServiceClient::new(ch.clone());
    let create = |scene: Option<pb::SceneSource>| {
        let mut r = tonic::Request::new(pb::CreateSessionRequest { scene, tick_rate_hz: 1000.0, ..Default::default() });
        // A call blocked on a FIFO ends here rather than hanging the test.
        r.set_timeout(Duration::from_secs(20));
        r
    };
    let up = "../../../../../../../..";

    // scene_toml, 2D: a mesh file by absolute path, by `../` path, the token file and a FIFO.
    for file in ["/etc/passwd", &format!("{up}/etc/passwd"), &token, &fifo] {
        let scene = source(pb::scene_source::Source::SceneToml(phantom_with_mesh_file(file)));
        let e = sessions.create_session(create(scene)).await.unwrap_err();
        assert_refused(&format!("2D scene_toml, mesh.file = {file}"), &e, "scene.scene_toml", "mesh.file");
        assert!(e.message().contains("cannot name files"), "{}", e.message());
    }
    // scene_toml, 3D: the trajectory file and the mesh file.
    for file in [&token, &format!("{up}{token}"), "/etc/passwd", &fifo] {
        let scene = source(pb::scene_source::Source::SceneToml(cube_with_trajectory(file)));
        let e = sessions.create_session(create(scene)).await.unwrap_err();
        assert_refused(&format!("3D scene_toml, trajectory = {file}"), &e, "scene.scene_toml", "trajectory");
        let scene = source(pb::scene_source::Source::SceneToml(brachy_with_mesh_file(file)));
        let e = sessions.create_session(create(scene)).await.unwrap_err();
        assert_refused(&format!("3D scene_toml, mesh.file = {file}"), &e, "scene.scene_toml", "mesh.file");
    }
    // uploaded3d: only the uploaded mesh may be named; a trajectory file, relative to wherever the
    // upload is put, or another mesh file is refused.
    let upload = |toml: String| {
        source(pb::scene_source::Source::Uploaded3d(pb::UploadedScene3d {
            scene_toml: toml,
            mesh_file_name: "brachy-3d.msh".into(),
            mesh_text: BRACHY_MSH.into(),
        }))
    };
    let with_traj = |file: &str| BRACHY.replace("trajectory = \"brachy-3d.csv\"", &format!("trajectory = \"{file}\""));
    assert!(BRACHY.contains("trajectory = \"brachy-3d.csv\""));
    for file in [format!("{up}{token}"), token.clone(), fifo.clone(), "brachy-3d.csv".into()] {
        let e = sessions.create_session(create(upload(with_traj(&file)))).await.unwrap_err();
        assert_refused(&format!("uploaded3d, trajectory = {file}"), &e, "scene.uploaded3d", "trajectory");
        assert!(e.message().contains("not among the files sent with the scene (brachy-3d.msh)"), "{}", e.message());
    }
    for file in [format!("{up}{token}"), format!("../{}", "brachy-3d.msh"), fifo.clone()] {
        let e = sessions.create_session(create(upload(brachy_with_mesh_file(&file)))).await.unwrap_err();
        assert_refused(&format!("uploaded3d, mesh.file = {file}"), &e, "scene.uploaded3d", "mesh.file");
    }
    // Simulate: 2D and 3D scene_toml alike.
    for (scene, key) in [(phantom_with_mesh_file(&token), "mesh.file"), (cube_with_trajectory(&token), "trajectory")] {
        let mut r = tonic::Request::new(pb::SimulateRequest {
            scene: source(pb::scene_source::Source::SceneToml(scene)),
            trajectory: vec![],
            decimate: 1,
            ..Default::default()
        });
        r.set_timeout(Duration::from_secs(20));
        let e = sim.simulate(r).await.expect_err("Simulate refuses the scene before it streams");
        assert_refused(&format!("Simulate, {key} = the token file"), &e, "scene.scene_toml", key);
    }
    // An example's name is a name, never a path.
    for name in [token.as_str(), "/etc/passwd", "server/scenes/paper-phantom.toml"] {
        let e = sessions.create_session(create(source(pb::scene_source::Source::Example(name.into())))).await.unwrap_err();
        assert_refused(&format!("example {name}"), &e, "scene.example", "not a shipped example");
    }
    // The uploaded mesh itself (no trajectory file) still makes a session: the server is alive.
    let own = BRACHY.replace("trajectory = \"brachy-3d.csv\"\n", "");
    let made = sessions.create_session(create(upload(own))).await.expect("the upload makes a 3D session").into_inner();
    assert!(made.session.is_some());
}

/// Runs `needlesim-server simulate --scene SCENE` in `dir`, expecting it to fail; its stderr.
fn simulate_fails(scene: &std::path::Path) -> String {
    let out = std::process::Command::new(bin("needlesim-server"))
        .args(["simulate", "--scene"])
        .arg(scene)
        .output()
        .expect("needlesim-server runs");
    assert!(!out.status.success(), "{}: must fail", scene.display());
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn issue_35_local_scenes_refuse_devices_fifos_and_links_and_read_their_own_files() {
    let dir = TempDir::new("file-refs-local");
    // /dev/zero as the scene and as its mesh: refused before a byte is read (the process would
    // otherwise grow without bound).
    let e = simulate_fails(std::path::Path::new("/dev/zero"));
    assert!(e.contains("/dev/zero: not a regular file (a character device)"), "{e}");
    let scene = dir.join("zero.toml");
    std::fs::write(&scene, phantom_with_mesh_file("/dev/zero")).unwrap();
    let e = simulate_fails(&scene);
    assert!(e.contains("mesh.file = \"/dev/zero\"") && e.contains("not a regular file"), "{e}");
    // A FIFO as the 3D trajectory file: refused, not waited on.
    let fifo = dir.join("pipe.csv");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs").success());
    let scene = dir.join("fifo.toml");
    std::fs::write(&scene, cube_with_trajectory("pipe.csv")).unwrap();
    let e = simulate_fails(&scene);
    assert!(e.contains("trajectory = \"pipe.csv\"") && e.contains("not a regular file (a FIFO)"), "{e}");
    // A link, as the scene and as its mesh file.
    let link = dir.join("link.toml");
    std::os::unix::fs::symlink(dir.join("zero.toml"), &link).unwrap();
    let e = simulate_fails(&link);
    assert!(e.contains("link.toml: is a symbolic link"), "{e}");
    std::fs::write(dir.join("brachy-3d.msh"), BRACHY_MSH).unwrap();
    std::os::unix::fs::symlink(dir.join("brachy-3d.msh"), dir.join("linked.msh")).unwrap();
    let scene = dir.join("linked.toml");
    std::fs::write(&scene, brachy_with_mesh_file("linked.msh")).unwrap();
    let e = simulate_fails(&scene);
    assert!(e.contains("mesh.file = \"linked.msh\"") && e.contains("is a symbolic link"), "{e}");
    // A scene's own trajectory file next to it is read: the small cube held at its first pose
    // for 10 ms.
    let shipped = include_str!("../../server/scenes/cube-phantom-3d.csv");
    let mut rows = shipped.lines().filter(|l| !l.starts_with('#'));
    let (header, first) = (rows.next().unwrap(), rows.next().unwrap());
    assert!(header.starts_with("t_s,") && first.starts_with("0,"), "{header} / {first}");
    let held = format!("0.01,{}", first.split_once(',').unwrap().1);
    std::fs::write(dir.join("traj.csv"), format!("{header}\n{first}\n{held}\n")).unwrap();
    std::fs::write(dir.join("cube.toml"), cube_with_trajectory("traj.csv")).unwrap();
    let out = std::process::Command::new(bin("needlesim-server"))
        .args(["simulate", "--scene"])
        .arg(dir.join("cube.toml"))
        .arg("-o")
        .arg(dir.join("out.csv"))
        .output()
        .expect("needlesim-server runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let rows = std::fs::read_to_string(dir.join("out.csv")).unwrap().lines().filter(|l| !l.starts_with('#')).count();
    assert_eq!(rows, 1 + 11, "a header and ticks 0..=10");
}
