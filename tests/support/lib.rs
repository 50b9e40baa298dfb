//! Helpers for the integration tests: locating the built binaries, the shared validation data and the Python reference tools, running them, and scratch directories.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicU64, Ordering};

/// The turn of the tests that run or time a 1 kHz session (a server session, a bridge, a browser
/// driving a session). All the integration tests run in one process (tests/it/), two at a time on a
/// 2-core machine; two such tests at once would eat each other's real-time budget, so each holds
/// this lock for its whole run: `REALTIME.lock().await` in async tests, `REALTIME.blocking_lock()`
/// in synchronous ones (outside any runtime). A tokio mutex is never poisoned: a test that fails
/// while holding it releases it as it unwinds.
pub static REALTIME: tokio::sync::Mutex<()> = tokio::sync::Mutex::const_new(());

/// The workspace root (the parent of this crate's directory).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("tests/ has a parent").to_path_buf()
}

/// The directory holding the built binaries (`target/debug`), derived from the running test
/// executable, which cargo places in `target/debug/deps/`.
pub fn target_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test knows its own executable");
    let dir = exe.parent().expect("the test executable is in a directory");
    if dir.file_name().is_some_and(|n| n == "deps") { dir.parent().expect("deps/ has a parent").to_path_buf() } else { dir.to_path_buf() }
}

/// The path of the workspace binary `name` (e.g. `needlesim-server`). Panics with instructions
/// when it has not been built: `cargo test` does not build other packages' binaries.
pub fn bin(name: &str) -> PathBuf {
    let path = target_dir().join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    assert!(path.is_file(), "{} does not exist: run cargo build --workspace --bins first (tests/run does it)", path.display());
    path
}

/// The shared validation data: `$NEEDLESIM_VALIDATION`, else `<repo>/../shared/validation`.
pub fn validation_dir() -> PathBuf {
    let dir = match std::env::var_os("NEEDLESIM_VALIDATION") {
        Some(d) => PathBuf::from(d),
        None => repo_root().join("../shared/validation"),
    };
    assert!(
        dir.join("scenarios").is_dir() && dir.join("compare.py").is_file(),
        "no validation data at {} (set NEEDLESIM_VALIDATION to the folder holding scenarios/, results/ and compare.py)",
        dir.display()
    );
    dir
}

/// The Python with numpy, scipy and scikit-fem: `$NEEDLESIM_PYTHON`, else `tests/.venv/bin/python`.
pub fn python() -> PathBuf {
    let py = match std::env::var_os("NEEDLESIM_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python"),
    };
    assert!(py.exists(), "no Python at {} (tests/run creates tests/.venv; or set NEEDLESIM_PYTHON)", py.display());
    py
}

/// A fresh directory under the system temporary directory, removed on drop (kept when
/// `NEEDLESIM_KEEP_TMP` is set, for debugging).
pub struct TempDir {
    path: PathBuf,
}

impl TempDir {
    /// Creates a new, unique, empty directory whose name contains `label`.
    pub fn new(label: &str) -> Self {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        loop {
            let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let path = std::env::temp_dir().join(format!("needlesim-{label}-{}-{n}-{nanos}", std::process::id()));
            match std::fs::create_dir(&path) {
                Ok(()) => return Self { path },
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => panic!("cannot create {}: {e}", path.display()),
            }
        }
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// A path inside the directory.
    pub fn join(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if std::env::var_os("NEEDLESIM_KEEP_TMP").is_none() {
            let _ = std::fs::remove_dir_all(&self.path);
        }
    }
}

/// Runs a command to completion, capturing its output; panics only when it cannot be started.
pub fn run(cmd: &mut Command) -> Output {
    cmd.output().unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"))
}

/// Runs `cmd` with its output captured, killing it after `limit`: a hang is a failure, a panic
/// naming the command.
pub fn run_within(cmd: &mut Command, limit: std::time::Duration) -> Output {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = cmd.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
    let (mut out, mut err) = (child.stdout.take().expect("piped"), child.stderr.take().expect("piped"));
    let out_t = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = out.read_to_end(&mut v);
        v
    });
    let err_t = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = err.read_to_end(&mut v);
        v
    });
    let deadline = std::time::Instant::now() + limit;
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait for the child") {
            break s;
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{cmd:?} did not finish within {} s", limit.as_secs_f64());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Output { status, stdout: out_t.join().expect("stdout reader"), stderr: err_t.join().expect("stderr reader") }
}

/// Standard output and standard error of a finished command, as text.
pub fn text(out: &Output) -> (String, String) {
    (String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// `needlesim-server [extra_args…] solve SCENARIO -o RESULT`.
pub fn server_solve(scenario: &Path, result: &Path, extra_args: &[&str]) -> Output {
    run(Command::new(bin("needlesim-server")).args(extra_args).arg("solve").arg(scenario).arg("-o").arg(result))
}

/// `python compare.py REF CANDIDATE --tol TOL` from the validation data.
pub fn compare(reference: &Path, candidate: &Path, tol: f64) -> Output {
    let script = validation_dir().join("compare.py");
    run(Command::new(python()).arg(script).arg(reference).arg(candidate).arg("--tol").arg(tol.to_string()))
}

/// Reads a JSON file.
/// The metrics of a compare.py report, by name.
pub fn report_metrics(report: &str) -> Vec<(String, f64)> {
    report
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            let name = it.next()?;
            let v: f64 = it.next()?.parse().ok()?;
            Some((name.to_owned(), v))
        })
        .collect()
}

pub fn read_json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// Writes a JSON file.
pub fn write_json(path: &Path, value: &serde_json::Value) {
    std::fs::write(path, serde_json::to_string(value).expect("a Value serialises"))
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
}

/// The `[[x, y], …]` array of `key` in a result JSON, as pairs.
pub fn pairs(value: &serde_json::Value, key: &str) -> Vec<[f64; 2]> {
    let arr = value[key].as_array().unwrap_or_else(|| panic!("`{key}` is not an array"));
    arr.iter()
        .map(|p| {
            let f = |i: usize| p[i].as_f64().unwrap_or_else(|| panic!("`{key}` holds a non-number: {p}"));
            [f(0), f(1)]
        })
        .collect()
}

/// `max |a - b| / max |b|` over all components; panics when the lengths differ.
pub fn max_rel_error(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    assert_eq!(a.len(), b.len(), "different numbers of nodes");
    let err = a.iter().zip(b).flat_map(|(p, q)| [(p[0] - q[0]).abs(), (p[1] - q[1]).abs()]).fold(0.0, f64::max);
    let scale = b.iter().flat_map(|q| [q[0].abs(), q[1].abs()]).fold(0.0, f64::max);
    assert!(scale > 0.0, "the reference field is zero");
    err / scale
}

/// A running `needlesim-server serve` process on a free loopback port, killed on drop.
pub struct ServerProcess {
    pub child: std::process::Child,
    pub addr: String,
    pub data_dir: TempDir,
    /// The server's standard error, collected in the background.
    pub stderr: std::sync::Arc<std::sync::Mutex<String>>,
    /// The server's standard output after its `listening on` line, collected in the background.
    pub stdout: std::sync::Arc<std::sync::Mutex<String>>,
}

impl ServerProcess {
    /// Starts the server with `extra` arguments after `serve --listen 127.0.0.1:0 --data-dir …`
    /// and waits until it prints its address.
    pub fn start(extra: &[&str]) -> Self {
        Self::start_in(TempDir::new("server"), extra)
    }

    /// As [`ServerProcess::start`], with `data_dir` as the data directory.
    pub fn start_in(data_dir: TempDir, extra: &[&str]) -> Self {
        use std::io::{BufRead, BufReader};
        let mut child = Command::new(bin("needlesim-server"))
            .args(["serve", "--listen", "127.0.0.1:0", "--data-dir"])
            .arg(data_dir.path())
            .args(extra)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("needlesim-server starts");
        let stderr = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
        if let Some(err_pipe) = child.stderr.take() {
            let sink = stderr.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(err_pipe).lines().map_while(Result::ok) {
                    sink.lock().unwrap().push_str(&line);
                    sink.lock().unwrap().push('\n');
                }
            });
        }
        let Some(stdout) = child.stdout.take() else {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the server's stdout is not piped");
        };
        let mut out = BufReader::new(stdout);
        let mut line = String::new();
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        loop {
            line.clear();
            let n = out.read_line(&mut line).unwrap_or(0);
            if let Some(addr) = line.trim().strip_prefix("listening on ") {
                let addr = addr.to_owned();
                let stdout = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
                let sink = stdout.clone();
                std::thread::spawn(move || {
                    for line in out.lines().map_while(Result::ok) {
                        sink.lock().unwrap().push_str(&line);
                        sink.lock().unwrap().push('\n');
                    }
                });
                return Self { child, addr, data_dir, stderr, stdout };
            }
            if n == 0 || std::time::Instant::now() > deadline {
                let _ = child.kill();
                let _ = child.wait();
                panic!("the server did not start: {}", stderr.lock().unwrap());
            }
        }
    }

    /// Kills the server (SIGKILL) and removes the device channel files it left (issue 35).
    pub fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        remove_channels_of(self.child.id());
    }

    /// Kills the server and starts another on the same data directory with `extra` arguments.
    pub fn restart(mut self, extra: &[&str]) -> Self {
        self.kill();
        let data_dir = std::mem::replace(&mut self.data_dir, TempDir::new("server-placeholder"));
        Self::start_in(data_dir, extra)
    }

    /// `http://ADDR`.
    pub fn url(&self) -> String {
        format!("http://{}", self.addr)
    }

    /// The server's `/metrics` page (Prometheus text, with the HTTP response's head).
    pub fn metrics(&self) -> String {
        use std::io::{Read, Write};
        let mut s = std::net::TcpStream::connect(&self.addr).unwrap();
        s.set_read_timeout(Some(std::time::Duration::from_secs(10))).unwrap();
        s.write_all(b"GET /metrics HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n").unwrap();
        let mut out = String::new();
        let _ = s.read_to_string(&mut out);
        out
    }

    /// The value of the metric `name` (its first line).
    pub fn metric(&self, name: &str) -> f64 {
        let out = self.metrics();
        let line = out.lines().find(|l| l.split_whitespace().next() == Some(name)).unwrap_or_else(|| panic!("no metric {name} in:\n{out}"));
        line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).expect("a number")
    }
}

impl Drop for ServerProcess {
    fn drop(&mut self) {
        self.kill();
    }
}

/// Removes the device channel files in /dev/shm that the dead process `pid` created (a SIGKILLed
/// server closes none of its sessions, and shared memory outlives processes: issue 35 found 81 such
/// files after test runs). Only files whose creator is gone (nobody holds their owner lock) and
/// whose header names `pid`: another test's live server is never touched.
pub fn remove_channels_of(pid: u32) {
    let dir = Path::new("/dev/shm");
    if dir.is_dir() {
        let _ = needlesim_channel::shm::remove_stale_channels(dir, Some(pid));
    }
}

/// A gRPC channel to a running server.
pub async fn connect(server: &ServerProcess) -> tonic::transport::Channel {
    tonic::transport::Channel::from_shared(server.url()).unwrap().connect().await.expect("connect to the server")
}

/// A request carrying `token` as `authorization: Bearer <token>` metadata.
pub fn with_token<T>(msg: T, token: &str) -> tonic::Request<T> {
    let mut r = tonic::Request::new(msg);
    r.metadata_mut().insert("authorization", tonic::metadata::MetadataValue::try_from(format!("Bearer {token}")).unwrap());
    r
}

/// Creates a 1 kHz session from a shipped example (no recording, no device channel).
pub async fn create_example_session(ch: &tonic::transport::Channel, example: &str) -> needlesim_proto::v1::CreateSessionResponse {
    create_session_from(ch, needlesim_proto::v1::scene_source::Source::Example(example.into())).await
}

/// Creates a 1 kHz session from a scene TOML's text (no recording, no device channel).
pub async fn create_toml_session(ch: &tonic::transport::Channel, toml: String) -> needlesim_proto::v1::CreateSessionResponse {
    create_session_from(ch, needlesim_proto::v1::scene_source::Source::SceneToml(toml)).await
}

async fn create_session_from(
    ch: &tonic::transport::Channel,
    source: needlesim_proto::v1::scene_source::Source,
) -> needlesim_proto::v1::CreateSessionResponse {
    use needlesim_proto::v1 as pb;
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    c.create_session(pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(source) }),
        tick_rate_hz: 1000.0,
        record: false,
        device_channel: false,
    })
    .await
    .expect("create a session")
    .into_inner()
}

/// The current frame of a session: the first frame of a fresh 60 Hz observer stream (5 s at most).
pub async fn latest_frame(ch: &tonic::transport::Channel, session_id: &str, observer_token: &str) -> needlesim_proto::v1::Frame {
    use needlesim_proto::v1 as pb;
    use tokio_stream::StreamExt;
    let mut c = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let req =
        with_token(pb::ObserveRequest { session_id: session_id.to_owned(), rate_hz: 60.0, include_displacements: false }, observer_token);
    let mut stream = c.observe(req).await.expect("Observe").into_inner();
    tokio::time::timeout(std::time::Duration::from_secs(5), stream.next())
        .await
        .expect("a frame within 5 s")
        .expect("the stream yields a frame")
        .expect("the frame is not an error")
}

/// The resident memory of process `pid`, bytes (VmRSS of /proc/PID/status).
pub fn rss_bytes(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).expect("/proc/PID/status");
    let kb: u64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.split_whitespace().next()?.parse().ok())
        .expect("VmRSS in /proc/PID/status");
    kb * 1024
}
