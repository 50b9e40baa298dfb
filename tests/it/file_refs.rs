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

/// `bin args…` under a 2 GB address-space limit (a binary that read /dev/zero would otherwise
/// take the machine's memory) with a deadline (a FIFO would block it): its exit status, stdout and
/// stderr.
fn run_limited(bin: &std::path::Path, args: &[&std::ffi::OsStr]) -> (Option<i32>, String, String) {
    let mut cmd = std::process::Command::new("sh");
    cmd.args(["-c", "ulimit -v 2000000 && exec \"$0\" \"$@\""]).arg(bin).args(args).stdin(std::process::Stdio::null());
    let t = std::time::Instant::now();
    let out = needlesim_tests::run_within(&mut cmd, Duration::from_secs(20));
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(t.elapsed() < Duration::from_secs(5), "{} {args:?}: refused at once, not after {:?}: {stderr}", bin.display(), t.elapsed());
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into_owned(), stderr)
}

/// Issue 35 (finding 5): the CLI (`--scene`, `--mesh`, `--trajectory`, `replay FILE`, `--tls-ca`),
/// the bridge (`--trajectory`), the server (`--admin-token-file`, `--tls-cert`, `--tls-key`) and
/// the pure-Python client read local files outside the one rule: /dev/zero was read to 2 GB, a
/// FIFO blocked in open() for good, a link to another file was followed. Each now goes through
/// `needlesim-localfile` (Python: its copy of the rule) and is refused at once, naming the path
/// and the problem, with a bound fitting the kind of file.
#[test]
fn issue35_clients_the_bridge_and_the_server_read_local_files_by_the_one_rule() {
    use std::ffi::OsStr;
    let dir = TempDir::new("file-refs-tools");
    let fifo = dir.join("pipe");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs").success());
    let secret = dir.join("secret");
    std::fs::write(&secret, format!("{SECRET}\nroot:x:0:0:root:/root:/bin/bash\n")).unwrap();
    let link = dir.join("link");
    std::os::unix::fs::symlink(&secret, &link).unwrap();
    let big_pem = dir.join("big.pem");
    std::fs::write(&big_pem, "#".repeat((1 << 20) + 1)).unwrap();
    let big_token = dir.join("big-token");
    std::fs::write(&big_token, "t".repeat(5000)).unwrap();
    let brachy = dir.join("brachy-3d.toml");
    std::fs::write(&brachy, BRACHY).unwrap();
    let zero = std::path::Path::new("/dev/zero");
    let (p, s) = (|p: &std::path::Path| p.as_os_str().to_owned(), OsStr::new);
    let (cli, server, bridge) = (bin("needlesim"), bin("needlesim-server"), bin("needlesim-bridge"));
    let a_fifo = "not a regular file (a FIFO)";
    let a_device = "not a regular file (a character device)";
    let a_link = "is a symbolic link; name the file it points to";
    let offline = s("http://127.0.0.1:1");
    let channel = dir.join("channel.shm");
    let _session = needlesim_channel::shm::DeviceChannel::create(&channel).expect("a device channel");
    let serve = |extra: &[std::ffi::OsString]| {
        let mut v: Vec<std::ffi::OsString> =
            ["serve", "--listen", "127.0.0.1:0", "--default-scene", "none", "--data-dir"].iter().map(|a| a.into()).collect();
        v.push(p(&dir.join("data")));
        v.extend(extra.iter().cloned());
        v
    };
    let cases: Vec<(&std::path::Path, Vec<std::ffi::OsString>, String)> = vec![
        (
            cli.as_path(),
            vec![s("--server").into(), offline.into(), s("sessions").into(), s("create").into(), s("--scene").into(), p(zero)],
            format!("cannot read the scene /dev/zero: {a_device}"),
        ),
        (
            cli.as_path(),
            vec![s("--server").into(), offline.into(), s("sessions").into(), s("create").into(), s("--scene").into(), p(&fifo)],
            format!("cannot read the scene {}: {a_fifo}", fifo.display()),
        ),
        (
            cli.as_path(),
            vec![
                s("--server").into(),
                offline.into(),
                s("sessions").into(),
                s("create").into(),
                s("--scene").into(),
                p(&brachy),
                s("--mesh").into(),
                p(&link),
            ],
            format!("cannot read the mesh {}: {a_link}", link.display()),
        ),
        (
            cli.as_path(),
            vec![
                s("--server").into(),
                offline.into(),
                s("--token").into(),
                s("x").into(),
                s("drive").into(),
                s("deadbeef").into(),
                s("--trajectory").into(),
                p(&fifo),
            ],
            format!("cannot read the trajectory {}: {a_fifo}", fifo.display()),
        ),
        (cli.as_path(), vec![s("replay").into(), p(zero)], format!("cannot read the recording /dev/zero: {a_device}")),
        (cli.as_path(), vec![s("replay").into(), p(&fifo)], format!("cannot read the recording {}: {a_fifo}", fifo.display())),
        (
            cli.as_path(),
            vec![
                s("--tls-ca").into(),
                p(&fifo),
                s("--server").into(),
                s("https://127.0.0.1:1").into(),
                s("sessions").into(),
                s("list").into(),
            ],
            format!("cannot read the CA certificate {}: {a_fifo}", fifo.display()),
        ),
        (
            cli.as_path(),
            vec![
                s("--tls-ca").into(),
                p(&big_pem),
                s("--server").into(),
                s("https://127.0.0.1:1").into(),
                s("sessions").into(),
                s("list").into(),
            ],
            format!("{}: 1048577 bytes, over the limit of 1048576 bytes", big_pem.display()),
        ),
        (
            bridge.as_path(),
            vec![
                s("--channel").into(),
                p(&channel),
                s("--device").into(),
                s("scripted").into(),
                s("--trajectory").into(),
                p(&fifo),
                s("--seconds").into(),
                s("1").into(),
            ],
            format!("cannot read the trajectory {}: {a_fifo}", fifo.display()),
        ),
        (
            server.as_path(),
            serve(&[s("--admin-token-file").into(), p(&link)]),
            format!("--admin-token-file: cannot read the token file {}: {a_link}", link.display()),
        ),
        (
            server.as_path(),
            serve(&[s("--admin-token-file").into(), p(&big_token)]),
            format!("cannot read the token file {}: 5000 bytes, over the limit of 4096 bytes", big_token.display()),
        ),
        (
            server.as_path(),
            serve(&[s("--tls-cert").into(), p(&fifo), s("--tls-key").into(), p(&secret)]),
            format!("cannot read the TLS certificate {}: {a_fifo}", fifo.display()),
        ),
        (
            server.as_path(),
            serve(&[s("--tls-cert").into(), p(&secret), s("--tls-key").into(), p(&link)]),
            format!("cannot read the TLS key {}: {a_link}", link.display()),
        ),
    ];
    for (bin, args, want) in &cases {
        let args: Vec<&OsStr> = args.iter().map(|a| a.as_os_str()).collect();
        let (code, _, stderr) = run_limited(bin, &args);
        println!("{} {args:?}: {}", bin.display(), stderr.trim());
        assert_eq!(code, Some(1), "{} {args:?}: {stderr}", bin.display());
        assert!(stderr.contains(want.as_str()), "{} {args:?}: the error says {want:?}: {stderr}", bin.display());
        assert!(!stderr.contains(SECRET) && !stderr.contains("root:"), "{} {args:?}: a file is quoted: {stderr}", bin.display());
    }
    // The pure-Python client: its copy of the rule.
    let client = needlesim_tests::repo_root().join("client/python");
    let script = format!(
        "import sys\nsys.path.insert(0, {client:?})\nimport needlesim_client as nc\n\
         for f in ['/dev/zero', {fifo:?}, {link:?}]:\n    try:\n        nc.read_trajectory_csv(f)\n        print('read', f)\n    except ValueError as e:\n        print('refused:', e)\n\
         try:\n    nc.read_local_file({big_pem:?}, nc.MAX_CERTIFICATE_BYTES)\nexcept ValueError as e:\n    print('refused:', e)\n",
        client = client.display().to_string(),
        fifo = fifo.display().to_string(),
        link = link.display().to_string(),
        big_pem = big_pem.display().to_string(),
    );
    let python = needlesim_tests::python();
    let (code, stdout, stderr) = run_limited(&python, &[s("-c"), s(&script)]);
    assert_eq!(code, Some(0), "{stderr}");
    for want in [
        format!("refused: /dev/zero: {a_device}"),
        format!("refused: {}: {a_fifo}", fifo.display()),
        format!("refused: {}: {a_link}", link.display()),
        format!("refused: {}: 1048577 bytes, over the limit of 1048576 bytes", big_pem.display()),
    ] {
        assert!(stdout.contains(&want), "the Python client says {want:?}:\n{stdout}");
    }
}

/// Issue 35 (pass 4, item 6): `needlesim-lab identify` read its files with std::fs, outside the
/// one rule: `render --tracks /dev/zero` read until out of memory, `probe --tracks FIFO` hung, a
/// frames.csv link was followed and its first line quoted (pointed at /proc/self/environ, the
/// environment). Each file it reads now goes through needlesim-localfile: refused at once, naming
/// the path and the problem, and no line of a file is quoted (frames.csv's header neither).
#[test]
fn issue_35_the_lab_reads_local_files_by_the_one_rule_and_quotes_no_line() {
    use std::ffi::OsStr;
    let dir = TempDir::new("file-refs-lab");
    let lab = bin("needlesim-lab");
    let fifo = dir.join("pipe.csv");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs").success());
    let secret = dir.join("secret.csv");
    std::fs::write(&secret, format!("frame,t_s,file_{SECRET}\n0,0,a.png\n")).unwrap();
    // frames.csv: a link to the secret, a link to the environment, the secret itself.
    let (linked, environ, plain) = (dir.join("linked"), dir.join("environ"), dir.join("plain"));
    for d in [&linked, &environ, &plain] {
        std::fs::create_dir_all(d).unwrap();
    }
    std::os::unix::fs::symlink(&secret, linked.join("frames.csv")).unwrap();
    std::os::unix::fs::symlink("/proc/self/environ", environ.join("frames.csv")).unwrap();
    std::fs::copy(&secret, plain.join("frames.csv")).unwrap();
    let (p, s) = (|p: &std::path::Path| p.as_os_str().to_owned(), OsStr::new);
    let track = |images: &std::path::Path| -> Vec<std::ffi::OsString> {
        ["identify", "track", "--m-per-px", "0.001", "--dark", "--output"]
            .iter()
            .map(|a| a.into())
            .chain([p(&dir.join("out.csv")), s("--images").into(), p(images)])
            .collect()
    };
    let probe = |tracks: &std::path::Path, log: &std::path::Path| -> Vec<std::ffi::OsString> {
        vec![
            s("identify").into(),
            s("probe").into(),
            s("--tracks").into(),
            p(tracks),
            s("--probe-log").into(),
            p(log),
            s("--grid").into(),
            s("3,3,0.01,0.01").into(),
        ]
    };
    let a_link = "is a symbolic link; name the file it points to";
    let cases: Vec<(Vec<std::ffi::OsString>, String)> = vec![
        (
            vec![
                s("identify").into(),
                s("render").into(),
                s("--tracks").into(),
                s("/dev/zero").into(),
                s("--out-dir").into(),
                p(&dir.join("r")),
            ],
            "/dev/zero: not a regular file (a character device)".into(),
        ),
        (probe(&fifo, &fifo), format!("{}: not a regular file (a FIFO)", fifo.display())),
        (probe(&secret, &fifo), "found a header whose column 3 is not marker".into()),
        (probe(std::path::Path::new("/proc/self/environ"), &fifo), "/proc/self/environ: on the kernel's proc file system".into()),
        (track(&linked), format!("{}: {a_link}", linked.join("frames.csv").display())),
        (track(&environ), format!("{}: {a_link}", environ.join("frames.csv").display())),
        (
            track(&plain),
            format!(
                "{} line 1: expected the header 'frame,t_s,file', found a header whose column 3 is not file",
                plain.join("frames.csv").display()
            ),
        ),
    ];
    for (args, want) in &cases {
        let args: Vec<&OsStr> = args.iter().map(|a| a.as_os_str()).collect();
        let (code, _, stderr) = run_limited(&lab, &args);
        println!("needlesim-lab {args:?}: {}", stderr.trim());
        assert_eq!(code, Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(want.as_str()), "{args:?}: the error says {want:?}: {stderr}");
        assert!(!stderr.contains(SECRET) && !stderr.contains("PATH=") && !stderr.contains("HOME="), "{args:?}: a file is quoted: {stderr}");
    }
}

/// Issue 35 (pass 4, item 7): a scene's parse error quoted the line it failed on (the TOML
/// parser's snippet): `simulate --scene /proc/self/environ` printed the environment, a scene with
/// a secret on its first line printed the secret, and a session created from it by the CLI echoed
/// it back from the server. A TOML error now names the file, line and column and the parser's
/// words only, and files on /proc and /sys are refused unread (/proc/self/pagemap was read up to
/// the 256 MiB bound).
#[test]
fn issue_35_scene_parse_errors_name_line_and_column_and_proc_files_are_refused() {
    use std::ffi::OsStr;
    let dir = TempDir::new("file-refs-parse");
    let secret = dir.join("secret.toml");
    std::fs::write(&secret, format!("name = \"x\"\n{SECRET} = = broken\n")).unwrap();
    let server = bin("needlesim-server");
    let (code, _, stderr) = run_limited(&server, &[OsStr::new("simulate"), OsStr::new("--scene"), secret.as_os_str()]);
    println!("simulate --scene secret.toml: {}", stderr.trim());
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains(&format!("scene {}: TOML parse error at line 2, column ", secret.display())), "{stderr}");
    assert!(!stderr.contains(SECRET) && !stderr.contains("broken") && !stderr.contains(" | "), "the line is quoted: {stderr}");
    for proc_file in ["/proc/self/environ", "/proc/self/pagemap", "/proc/self/cmdline", "/sys/kernel/mm/transparent_hugepage/enabled"] {
        if std::fs::symlink_metadata(proc_file).is_err() {
            continue;
        }
        let (code, _, stderr) = run_limited(&server, &[OsStr::new("simulate"), OsStr::new("--scene"), OsStr::new(proc_file)]);
        println!("simulate --scene {proc_file}: {}", stderr.trim());
        assert_eq!(code, Some(1), "{stderr}");
        assert!(stderr.contains(&format!("{proc_file}: on the kernel's ")) && stderr.contains("/proc, /sys"), "{stderr}");
        assert!(!stderr.contains("PATH=") && !stderr.contains("simulate"), "{proc_file} is quoted: {stderr}");
    }
    // The CLI sends the scene to a server, whose refusal it prints: the secret line is not in it.
    let live = ServerProcess::start(&["--default-scene", "none"]);
    let url = live.url();
    let (code, _, stderr) = run_limited(
        &bin("needlesim"),
        &[
            OsStr::new("--server"),
            OsStr::new(&url),
            OsStr::new("sessions"),
            OsStr::new("create"),
            OsStr::new("--scene"),
            secret.as_os_str(),
        ],
    );
    println!("needlesim sessions create --scene secret.toml: {}", stderr.trim());
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("TOML parse error at line 2, column "), "{stderr}");
    assert!(!stderr.contains(SECRET) && !stderr.contains("broken"), "the line is quoted: {stderr}");
}
