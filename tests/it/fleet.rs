//! The server as an Agones game server (issue 22): the real server binary with `--agones` against
//! a local stand-in of the Agones SDK server's REST gateway (tests/support/agones_sdk_stub.py,
//! written from the documented API, logging every call with its time): Ready after start, health
//! pings at the interval and none while a session's real-time thread is stalled, the `sessions`
//! Counter following sessions as they open and close, labels, the drain on SIGTERM (a running
//! session goes on, a new one is refused with UNAVAILABLE, the process exits with status 0 once it
//! ends) and the shutdown once an allocation's sessions end.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME, TempDir, bin, python, repo_root, rss_bytes, with_token};
use serde_json::Value;

const HEALTH_MS: u64 = 200;
const STALL_MS: u64 = 300;
/// How long the test's SIGUSR2 blocks the real-time thread.
const STALL_FOR_MS: u64 = 3000;

fn now_s() -> f64 {
    SystemTime::now().duration_since(UNIX_EPOCH).expect("after 1970").as_secs_f64()
}

/// One call the stand-in received.
#[derive(Debug, Clone)]
struct Call {
    t: f64,
    method: String,
    path: String,
    body: Value,
}

/// The stand-in SDK server, killed on drop.
struct Sdk {
    child: Child,
    port: u16,
    log: PathBuf,
    _dir: TempDir,
}

impl Sdk {
    fn start() -> Self {
        Self::start_with(&[])
    }

    /// The stand-in with `extra` options (e.g. `--watch-no-newline`).
    fn start_with(extra: &[&str]) -> Self {
        let dir = TempDir::new("agones-sdk");
        let log = dir.join("calls.jsonl");
        let port_file = dir.join("port");
        let child = Command::new(python())
            .arg(repo_root().join("tests/support/agones_sdk_stub.py"))
            .arg("--log")
            .arg(&log)
            .arg("--port-file")
            .arg(&port_file)
            .args(["--counter", "sessions=0"])
            .args(extra)
            .spawn()
            .expect("the stand-in SDK server starts");
        let deadline = Instant::now() + Duration::from_secs(20);
        let port = loop {
            if let Some(p) = std::fs::read_to_string(&port_file).ok().and_then(|s| s.trim().parse().ok()) {
                break p;
            }
            assert!(Instant::now() < deadline, "the stand-in SDK server wrote no port");
            std::thread::sleep(Duration::from_millis(20));
        };
        Self { child, port, log, _dir: dir }
    }

    fn calls(&self) -> Vec<Call> {
        let text = std::fs::read_to_string(&self.log).unwrap_or_default();
        text.lines()
            .filter_map(|l| serde_json::from_str::<Value>(l).ok())
            .map(|v| Call {
                t: v["t"].as_f64().expect("a time"),
                method: v["method"].as_str().unwrap_or_default().to_owned(),
                path: v["path"].as_str().unwrap_or_default().to_owned(),
                body: v["body"].clone(),
            })
            .collect()
    }

    fn times(&self, path: &str) -> Vec<f64> {
        self.calls().into_iter().filter(|c| c.path == path).map(|c| c.t).collect()
    }

    /// The counts published to the `sessions` Counter, in order.
    fn counts(&self) -> Vec<u64> {
        self.calls()
            .into_iter()
            .filter(|c| c.method == "PATCH" && c.path == "/v1beta1/counters/sessions")
            .map(|c| c.body["count"].as_str().expect("count as a protojson int64 string").parse().expect("a number"))
            .collect()
    }

    /// Waits (up to 10 s) until `pred` holds of the calls.
    fn wait_for(&self, what: &str, pred: impl Fn(&[Call]) -> bool) {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            let calls = self.calls();
            if pred(&calls) {
                return;
            }
            assert!(Instant::now() < deadline, "timed out waiting for {what}; calls: {:#?}", &calls[calls.len().saturating_sub(8)..]);
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Sets the GameServer's state as Agones would (the stand-in's test hook).
    fn set_state(&self, state: &str) {
        let body = format!("{{\"state\":\"{state}\"}}");
        let mut s = std::net::TcpStream::connect(("127.0.0.1", self.port)).expect("connect to the stand-in");
        write!(s, "POST /__test/state HTTP/1.0\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        let mut answer = String::new();
        s.read_to_string(&mut answer).unwrap();
        assert!(answer.starts_with("HTTP/1.0 200"), "{answer}");
    }
}

impl Drop for Sdk {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The server with `--agones` against `sdk`, killed on drop unless it exited.
struct Server {
    child: Child,
    addr: String,
    stderr: std::sync::Arc<std::sync::Mutex<String>>,
    _data: TempDir,
}

impl Server {
    fn start(sdk: &Sdk) -> Self {
        let data = TempDir::new("fleet-server");
        let mut child = Command::new(bin("needlesim-server"))
            .args(["serve", "--listen", "127.0.0.1:0", "--default-scene", "none", "--max-sessions", "4", "--agones"])
            .args(["--agones-health-interval-ms", &HEALTH_MS.to_string(), "--agones-stall-ms", &STALL_MS.to_string()])
            .args(["--debug-stall-on-sigusr2-ms", &STALL_FOR_MS.to_string()])
            .arg("--data-dir")
            .arg(data.path())
            .env("AGONES_SDK_HTTP_PORT", sdk.port.to_string())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("needlesim-server starts");
        let stderr = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
        let sink = stderr.clone();
        let err = child.stderr.take().expect("piped stderr");
        std::thread::spawn(move || {
            for line in BufReader::new(err).lines().map_while(Result::ok) {
                sink.lock().unwrap().push_str(&(line + "\n"));
            }
        });
        let mut out = BufReader::new(child.stdout.take().expect("piped stdout"));
        let mut line = String::new();
        let addr = loop {
            line.clear();
            if out.read_line(&mut line).unwrap_or(0) == 0 {
                let _ = child.kill();
                panic!("the server did not start: {}", stderr.lock().unwrap());
            }
            if let Some(a) = line.trim().strip_prefix("listening on ") {
                break a.to_owned();
            }
        };
        std::thread::spawn(move || for _ in out.lines().map_while(Result::ok) {});
        Self { child, addr, stderr, _data: data }
    }

    async fn channel(&self) -> tonic::transport::Channel {
        tonic::transport::Channel::from_shared(format!("http://{}", self.addr)).unwrap().connect().await.expect("connect to the server")
    }

    /// Waits (up to `limit`) for the process to exit: its status.
    fn wait_exit(&mut self, limit: Duration) -> std::process::ExitStatus {
        let deadline = Instant::now() + limit;
        loop {
            if let Some(st) = self.child.try_wait().expect("try_wait") {
                return st;
            }
            assert!(Instant::now() < deadline, "the server did not exit within {limit:?}: {}", self.stderr.lock().unwrap());
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn signal(&self, sig: &str) {
        let st = Command::new("kill").arg(format!("-{sig}")).arg(self.child.id().to_string()).status().expect("kill runs");
        assert!(st.success());
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

async fn create(ch: &tonic::transport::Channel) -> Result<pb::CreateSessionResponse, tonic::Status> {
    create_example(ch, "paper-phantom").await
}

/// A 1 kHz session of a shipped example.
async fn create_example(ch: &tonic::transport::Channel, example: &str) -> Result<pb::CreateSessionResponse, tonic::Status> {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    c.create_session(pb::CreateSessionRequest {
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example(example.into())) }),
        tick_rate_hz: 1000.0,
        record: false,
        device_channel: false,
    })
    .await
    .map(|r| r.into_inner())
}

/// The session id in a CreateSession answer.
fn sid(s: &pb::CreateSessionResponse) -> String {
    s.session.as_ref().expect("the session's info").session_id.clone()
}

async fn close(ch: &tonic::transport::Channel, s: &pb::CreateSessionResponse) {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    c.close_session(with_token(pb::CloseSessionRequest { session_id: sid(s) }, &s.controller_token)).await.expect("close");
}

async fn ticks(ch: &tonic::transport::Channel, s: &pb::CreateSessionResponse) -> u64 {
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let st = c.get_stats(with_token(pb::GetSessionRequest { session_id: sid(s) }, &s.observer_token)).await.expect("stats");
    st.into_inner().ticks
}

/// The thread id of the session's real-time thread (named `rt-<id>`; comm keeps 15 bytes).
fn rt_tid(pid: u32, session_id: &str) -> u32 {
    let want: String = format!("rt-{session_id}").chars().take(15).collect();
    let dir = PathBuf::from(format!("/proc/{pid}/task"));
    for e in std::fs::read_dir(&dir).expect("/proc/PID/task") {
        let p = e.unwrap().path();
        if std::fs::read_to_string(p.join("comm")).is_ok_and(|c| c.trim() == want) {
            return p.file_name().unwrap().to_str().unwrap().parse().unwrap();
        }
    }
    panic!("no thread named {want} in {}", dir.display());
}

/// Sends SIGUSR2 to one thread (tgkill; std has no call for it, so through Python's ctypes):
/// the time it was sent (UNIX seconds, taken just before the system call: Python's start-up under
/// load does not count).
fn tgkill_usr2(pid: u32, tid: u32) -> f64 {
    let script = "import ctypes, os, platform, signal, sys, time\n\
                  nr = {'x86_64': 234, 'aarch64': 131}[platform.machine()]\n\
                  libc = ctypes.CDLL(None, use_errno=True)\n\
                  t = time.time()\n\
                  r = libc.syscall(nr, int(sys.argv[1]), int(sys.argv[2]), int(signal.SIGUSR2))\n\
                  print(repr(t))\n\
                  sys.exit(0 if r == 0 else 'tgkill: ' + os.strerror(ctypes.get_errno()))";
    let out = needlesim_tests::run(Command::new(python()).args(["-c", script, &pid.to_string(), &tid.to_string()]));
    assert!(out.status.success(), "tgkill failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).trim().parse().expect("the time the signal was sent")
}

fn gaps(t: &[f64]) -> Vec<f64> {
    t.windows(2).map(|w| w[1] - w[0]).collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn agones_lifecycle_health_counters_and_drain() {
    let _rt = REALTIME.lock().await;
    let sdk = Sdk::start();
    let t_spawn = now_s();
    let mut server = Server::start(&sdk);
    let ch = server.channel().await;

    // Ready after start: the first call, once; nothing before it.
    sdk.wait_for("Ready", |c| c.iter().any(|c| c.path == "/ready"));
    let calls = sdk.calls();
    let first = calls.iter().find(|c| c.path != "/watch/gameserver").expect("a call");
    assert_eq!((first.method.as_str(), first.path.as_str()), ("POST", "/ready"), "{calls:#?}");
    let t_ready = first.t;
    assert!(t_ready >= t_spawn);
    // Labels for selectors; the Counter with the capacity (--max-sessions) and no session.
    sdk.wait_for("the labels and the Counter", |c| {
        c.iter().filter(|c| c.path == "/metadata/label").count() == 2 && c.iter().any(|c| c.path.starts_with("/v1beta1/counters/"))
    });
    let calls = sdk.calls();
    let labels: Vec<(String, String)> = calls
        .iter()
        .filter(|c| c.method == "PUT" && c.path == "/metadata/label")
        .map(|c| (c.body["key"].as_str().unwrap().to_owned(), c.body["value"].as_str().unwrap().to_owned()))
        .collect();
    assert!(labels.contains(&("version".into(), env!("CARGO_PKG_VERSION").into())), "{labels:?}");
    assert!(labels.contains(&("scene".into(), "none".into())), "{labels:?}");
    let counter = calls.iter().find(|c| c.path == "/v1beta1/counters/sessions").expect("a Counter update");
    assert_eq!((counter.method.as_str(), &counter.body), ("PATCH", &serde_json::json!({"count": "0", "capacity": "4"})));

    // Health pings at the interval.
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let health = sdk.times("/health");
    assert!(health.len() >= 4, "{} health pings in 1.5 s at {HEALTH_MS} ms", health.len());
    assert!(health[0] >= t_ready, "a health ping before Ready");
    let g = gaps(&health);
    let interval = HEALTH_MS as f64 * 1e-3;
    let m = median(g.clone());
    assert!((0.75 * interval..=1.5 * interval).contains(&m), "median gap between pings {m:.3} s, interval {interval} s: {g:?}");

    // The Counter follows sessions as they open and close.
    let a = create(&ch).await.expect("create session A");
    sdk.wait_for("count 1", |_| sdk.counts().last() == Some(&1));
    let b = create(&ch).await.expect("create session B");
    sdk.wait_for("count 2", |_| sdk.counts().last() == Some(&2));
    close(&ch, &b).await;
    sdk.wait_for("count 1 again", |_| sdk.counts().last() == Some(&1));
    let mut counts = sdk.counts();
    counts.dedup();
    assert_eq!(counts, [0, 1, 2, 1], "the counts published");

    // Stall session A's real-time thread: the pings stop, and resume once it ticks again.
    let pid = server.child.id();
    let tid = rt_tid(pid, &sid(&a));
    tokio::time::sleep(Duration::from_millis(500)).await;
    let t_stall = tgkill_usr2(pid, tid);
    let left = STALL_FOR_MS as f64 * 1e-3 - (now_s() - t_stall);
    tokio::time::sleep(Duration::from_secs_f64(left.max(0.0) + 1.2)).await;
    let health = sdk.times("/health");
    let quiet_from = t_stall + (STALL_MS + HEALTH_MS + 150) as f64 * 1e-3;
    let quiet_to = t_stall + (STALL_FOR_MS - 100) as f64 * 1e-3;
    let during: Vec<f64> = health.iter().copied().filter(|t| (quiet_from..quiet_to).contains(t)).map(|t| t - t_stall).collect();
    assert!(during.is_empty(), "health pings while the real-time thread was stalled, at {during:?} s after the stall");
    assert!(health.iter().any(|t| *t < t_stall && *t > t_stall - 0.5), "no pings just before the stall");
    assert!(health.iter().any(|t| *t > quiet_to), "the pings did not resume after the stall");
    assert!(server.stderr.lock().unwrap().contains("stalled"), "the stall is logged");

    // SIGTERM drains: session A goes on, a new session is refused, A's end ends the process.
    server.signal("TERM");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let refused = create(&ch).await.expect_err("a session created while draining");
    assert_eq!(refused.code(), tonic::Code::Unavailable, "{refused:?}");
    assert!(refused.message().contains("draining"), "{}", refused.message());
    let t0 = ticks(&ch, &a).await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let t1 = ticks(&ch, &a).await;
    assert!(t1 > t0 + 100, "the running session stopped ticking while draining: {t0} → {t1}");
    assert!(sdk.times("/shutdown").is_empty(), "Shutdown before the running session ended");
    assert!(server.child.try_wait().unwrap().is_none(), "the server exited with a session running");
    let t_close = now_s();
    close(&ch, &a).await;
    let status = server.wait_exit(Duration::from_secs(10));
    assert!(status.success(), "exit status {status:?}: {}", server.stderr.lock().unwrap());
    let shutdown = sdk.times("/shutdown");
    assert_eq!(shutdown.len(), 1, "Shutdown calls: {shutdown:?}");
    assert!(shutdown[0] >= t_close);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_end_of_an_allocations_sessions_shuts_the_server_down() {
    let _rt = REALTIME.lock().await;
    let sdk = Sdk::start();
    let mut server = Server::start(&sdk);
    let ch = server.channel().await;
    sdk.wait_for("Ready", |c| c.iter().any(|c| c.path == "/ready"));
    // Not allocated: a session that ends leaves the server Ready.
    let s = create(&ch).await.expect("create");
    close(&ch, &s).await;
    tokio::time::sleep(Duration::from_millis(600)).await;
    assert!(sdk.times("/shutdown").is_empty(), "Shutdown without an allocation");
    assert!(server.child.try_wait().unwrap().is_none(), "the server exited without an allocation");
    // Allocated (the SDK's watch stream says so): once its session ends, Shutdown and exit 0.
    sdk.set_state("Allocated");
    sdk.wait_for("the watch to deliver Allocated", |_| server.stderr.lock().unwrap().contains("Allocated"));
    let s = create(&ch).await.expect("create on the allocated server");
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert!(sdk.times("/shutdown").is_empty(), "Shutdown with a session running");
    close(&ch, &s).await;
    let status = server.wait_exit(Duration::from_secs(10));
    assert!(status.success(), "exit status {status:?}: {}", server.stderr.lock().unwrap());
    assert_eq!(sdk.times("/shutdown").len(), 1);
}

/// Issue 35: a watch stream from the SDK sidecar that never sends a newline is not buffered
/// without bound: once a line passes the bound (1 MiB) the server drops the connection, says so
/// once in its log, counts it in /metrics, and opens the stream again after a backoff.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_a_watch_stream_without_newlines_is_dropped_and_reopened() {
    let sdk = Sdk::start_with(&["--watch-no-newline"]);
    let server = Server::start(&sdk);
    let deadline = Instant::now() + Duration::from_secs(60);
    let ended = loop {
        let ended: Vec<u64> =
            sdk.calls().iter().filter(|c| c.method == "WATCH_END").map(|c| c.body["bytes"].as_u64().expect("bytes sent")).collect();
        if ended.len() >= 3 {
            break ended;
        }
        assert!(
            Instant::now() < deadline,
            "the server did not drop the endless line and reconnect (streams ended: {ended:?}); stderr: {}",
            server.stderr.lock().unwrap()
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    let opened = sdk.calls().iter().filter(|c| c.method == "GET" && c.path == "/watch/gameserver").count();
    assert!(opened >= 3, "the watch stream was opened {opened} times");
    // What the stand-in got out before the drop: the 1 MiB the server held, plus what the
    // sockets' buffers took (a few MiB on loopback) — not an unbounded stream.
    for b in &ended {
        assert!(*b >= 1 << 20 && *b < 64 << 20, "bytes sent per dropped stream: {ended:?}");
    }
    let log = server.stderr.lock().unwrap().clone();
    assert_eq!(log.matches("Agones watch stream dropped").count(), 1, "the drop is logged once: {log}");
    assert!(log.contains("exceeds 1048576 bytes without a newline"), "{log}");
    let metrics = {
        let mut s = std::net::TcpStream::connect(&server.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        s.write_all(b"GET /metrics HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n").unwrap();
        let mut out = String::new();
        let _ = s.read_to_string(&mut out);
        out
    };
    let overlong: f64 = metrics
        .lines()
        .find_map(|l| l.strip_prefix("needlesim_agones_watch_overlong_lines "))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no needlesim_agones_watch_overlong_lines in /metrics: {metrics}"));
    assert!(overlong >= ended.len() as f64, "overlong lines counted: {overlong}, streams ended: {ended:?}");
}

/// Issue 35: an answer of the SDK sidecar is read up to a bound (64 kB), not for as long as the
/// sidecar sends it: a health ping answered with an endless body fails once 64 kB have come (the
/// connection dropped, the failure logged naming the bound) instead of growing the server by what
/// loopback carries in the call's 2 s timeout (1.7 GB before).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_an_endless_answer_of_the_sidecar_is_read_up_to_a_bound() {
    let sdk = Sdk::start_with(&["--endless-health"]);
    let server = Server::start(&sdk);
    let deadline = Instant::now() + Duration::from_secs(30);
    let ended = loop {
        let ended: Vec<u64> =
            sdk.calls().iter().filter(|c| c.method == "HEALTH_END").map(|c| c.body["bytes"].as_u64().expect("bytes sent")).collect();
        if ended.len() >= 3 {
            break ended;
        }
        assert!(Instant::now() < deadline, "no three health answers were dropped ({ended:?}); stderr: {}", server.stderr.lock().unwrap());
        std::thread::sleep(Duration::from_millis(50));
    };
    // The 64 kB read, plus what the sockets' buffers took on loopback: not what 2 s carry.
    for b in &ended {
        assert!(*b < 16 << 20, "bytes sent per dropped answer: {ended:?}");
    }
    let rss = rss_bytes(server.child.id());
    assert!(rss < 256 << 20, "the server's resident memory: {} MB", rss >> 20);
    let log = server.stderr.lock().unwrap().clone();
    assert!(log.contains("POST /health: the Agones SDK server's answer exceeds 65536 bytes"), "{log}");
}

/// CPU time used by process `pid` so far (user + system), seconds (clock ticks of 1/100 s).
fn cpu_s(pid: u32) -> f64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).expect("/proc/PID/stat");
    let after = &stat[stat.rfind(')').expect("comm in parentheses") + 2..];
    let f: Vec<&str> = after.split_whitespace().collect();
    // Fields 14 and 15 of proc(5) (utime, stime) are the 12th and 13th after the comm.
    (f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()) / 100.0
}

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// Sessions per machine (docs/capacity.md): for each session count, a release server with that
/// many 1 kHz paper-phantom sessions, each driven along the phantom's insertion (looped) by
/// SetPose at 100 Hz as a browser would; after 2 s of warm-up, over NEEDLESIM_CAPACITY_SECONDS
/// (10): ticks per second, missed deadlines, lateness and compute percentiles (worst session),
/// the server's CPU use, and resident memory per session. Prints a markdown table.
///
/// `NEEDLESIM_SERVER_BIN=target/release/needlesim-server cargo test -p needlesim-tests --test it --
/// fleet::capacity --ignored --nocapture` (NEEDLESIM_CAPACITY_SESSIONS=1,2,3,4 picks the counts,
/// NEEDLESIM_RT_PRIORITY the real-time priority, 40 by default as served).
/// NEEDLESIM_CAPACITY_SCENE=cube-phantom-3d measures 3D sessions instead (the 48,000-tetrahedron
/// cube), each driven by SetPose3 at 100 Hz down the cube's centre line to 60 mm and back, 8 s a
/// cycle (a triangle wave from 5 mm above the top face).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "a timing measurement: run on a quiet machine with a release server"]
async fn capacity() {
    let server_bin = std::env::var_os("NEEDLESIM_SERVER_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| needlesim_tests::target_dir().parent().expect("target/").join("release/needlesim-server"));
    assert!(server_bin.is_file(), "no release server at {} (cargo build --release -p needlesim-server)", server_bin.display());
    let counts: Vec<usize> = std::env::var("NEEDLESIM_CAPACITY_SESSIONS")
        .unwrap_or_else(|_| "1,2,3,4".into())
        .split(',')
        .map(|s| s.trim().parse().expect("NEEDLESIM_CAPACITY_SESSIONS: numbers"))
        .collect();
    let seconds: f64 = env_or("NEEDLESIM_CAPACITY_SECONDS", 10.0);
    let rt_priority: i32 = env_or("NEEDLESIM_RT_PRIORITY", 40);
    let example = std::env::var("NEEDLESIM_CAPACITY_SCENE").unwrap_or_else(|_| "paper-phantom".into());
    let three_d = example == "cube-phantom-3d";
    assert!(three_d || example == "paper-phantom", "NEEDLESIM_CAPACITY_SCENE: paper-phantom or cube-phantom-3d, not {example:?}");
    let _rt = REALTIME.lock().await;
    let scene = needlesim_scene::load_scene("paper-phantom", &needlesim_core::MeshLimits::default()).expect("the paper phantom");
    let traj = needlesim_scene::Trajectory::parse_csv(scene.example_trajectory.expect("its trajectory")).expect("a trajectory");
    let traj = std::sync::Arc::new(traj);
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let load = |label: &str| {
        let l = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
        println!("load average {label}: {}", l.split_whitespace().take(3).collect::<Vec<_>>().join(" "));
    };
    println!("{cores} cores; server {}; rt-priority {rt_priority}; scene {example}; {seconds} s per row", server_bin.display());
    load("before");
    println!(
        "| sessions | ticks/s (min) | missed deadlines | lateness p99 / p99.9 (µs, worst) | compute p99 (µs, worst) | server CPU (cores) | CPU per session | RSS per session (MiB) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut base_rss_mib = 0.0f64;
    for &n in &counts {
        let data = TempDir::new("capacity");
        let mut child = Command::new(&server_bin)
            .args(["serve", "--listen", "127.0.0.1:0", "--default-scene", "none", "--max-sessions", &n.to_string()])
            .args(["--rt-priority", &rt_priority.to_string()])
            .arg("--data-dir")
            .arg(data.path())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("the release server starts");
        let mut out = BufReader::new(child.stdout.take().unwrap());
        let mut line = String::new();
        let addr = loop {
            line.clear();
            assert!(out.read_line(&mut line).unwrap() > 0, "the server did not start");
            if let Some(a) = line.trim().strip_prefix("listening on ") {
                break a.to_owned();
            }
        };
        let pid = child.id();
        let ch = tonic::transport::Channel::from_shared(format!("http://{addr}")).unwrap().connect().await.unwrap();
        tokio::time::sleep(Duration::from_millis(300)).await;
        let rss0 = rss_bytes(pid);
        let mut sessions = Vec::new();
        for _ in 0..n {
            sessions.push(create_example(&ch, &example).await.expect("create a session"));
        }
        let rss1 = rss_bytes(pid);
        base_rss_mib = base_rss_mib.max(rss0 as f64 / (1 << 20) as f64);
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let mut drivers = Vec::new();
        for (i, s) in sessions.iter().enumerate() {
            let (ch, s, traj, stop) = (ch.clone(), s.clone(), traj.clone(), stop.clone());
            drivers.push(tokio::spawn(async move {
                let mut c = pb::control_service_client::ControlServiceClient::new(ch);
                let (t0, t1) = traj.span_s();
                let start = Instant::now();
                let mut every = tokio::time::interval(Duration::from_millis(10));
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    every.tick().await;
                    // Staggered starts, so that the sessions are not in the same phase.
                    if three_d {
                        let phase = ((start.elapsed().as_secs_f64() + i as f64 * 0.7) / 8.0).fract();
                        let depth = 0.065 * (1.0 - (2.0 * phase - 1.0).abs());
                        let h = std::f64::consts::FRAC_1_SQRT_2;
                        let req = pb::SetPoseRequest3 {
                            session_id: sid(&s),
                            base3: Some(pb::Pose3 {
                                position_m: Some(pb::Vec3 { x: 0.05, y: 0.05, z: 0.205 - depth }),
                                orientation: Some(pb::Quaternion { w: h, x: 0.0, y: h, z: 0.0 }),
                            }),
                            client_id: format!("driver-{i}"),
                            take_over: false,
                        };
                        let _ = c.set_pose3(with_token(req, &s.controller_token)).await;
                        continue;
                    }
                    let t = t0 + (start.elapsed().as_secs_f64() + i as f64 * 0.7) % (t1 - t0);
                    let p = traj.pose_at(t);
                    let req = pb::SetPoseRequest {
                        session_id: sid(&s),
                        base: Some(pb::Pose2 { x_m: p.x_m, y_m: p.y_m, theta_rad: p.theta_rad }),
                        client_id: format!("driver-{i}"),
                        take_over: false,
                    };
                    let _ = c.set_pose(with_token(req, &s.controller_token)).await;
                }
            }));
        }
        tokio::time::sleep(Duration::from_secs(2)).await;
        let mut before = Vec::new();
        for s in &sessions {
            let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
            let st = c.get_stats(with_token(pb::GetSessionRequest { session_id: sid(s) }, &s.observer_token)).await.unwrap().into_inner();
            before.push((Instant::now(), st));
        }
        let (cpu0, w0) = (cpu_s(pid), Instant::now());
        tokio::time::sleep(Duration::from_secs_f64(seconds)).await;
        let (cpu1, wall) = (cpu_s(pid), w0.elapsed().as_secs_f64());
        let mut after = Vec::new();
        for s in &sessions {
            let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
            let st = c.get_stats(with_token(pb::GetSessionRequest { session_id: sid(s) }, &s.observer_token)).await.unwrap().into_inner();
            after.push((Instant::now(), st));
        }
        stop.store(true, std::sync::atomic::Ordering::Relaxed);
        for d in drivers {
            let _ = d.await;
        }
        // Each session's rate over its own window, between its two snapshots.
        let min_rate = before
            .iter()
            .zip(&after)
            .map(|((tb, b), (ta, a))| (a.ticks - b.ticks) as f64 / ta.duration_since(*tb).as_secs_f64())
            .fold(f64::INFINITY, f64::min);
        let missed: u64 = before.iter().zip(&after).map(|((_, b), (_, a))| a.missed_deadlines - b.missed_deadlines).sum();
        let ticks: u64 = before.iter().zip(&after).map(|((_, b), (_, a))| a.ticks - b.ticks).sum();
        let worst = |f: fn(&pb::SessionStats) -> f64| after.iter().map(|(_, a)| f(a)).fold(0.0, f64::max);
        let faulted = after.iter().filter(|(_, a)| a.faulted).count();
        let cpu = (cpu1 - cpu0) / wall;
        println!(
            "| {n} | {min_rate:.0} | {missed} of {ticks} ({:.3} %){} | {:.0} / {:.0} | {:.0} | {cpu:.2} | {:.2} | {:.1} |",
            missed as f64 * 100.0 / ticks.max(1) as f64,
            if faulted > 0 { format!(", {faulted} faulted") } else { String::new() },
            worst(|a| a.lateness_p99_us),
            worst(|a| a.lateness_p999_us),
            worst(|a| a.compute_p99_us),
            cpu / n as f64,
            (rss1.saturating_sub(rss0)) as f64 / n as f64 / (1 << 20) as f64,
        );
        let _ = child.kill();
        let _ = child.wait();
    }
    println!("the server without sessions: RSS up to {base_rss_mib:.1} MiB");
    load("after");
    observer_bandwidth(&server_bin, &traj, seconds.min(5.0)).await;
}

/// Network per observer: one paper-phantom session driven as in [`capacity`], watched by
/// `Observe` at 30 and 60 Hz with and without every node's displacement; the gRPC payload per
/// second (each message's encoded length plus gRPC's 5-byte frame header; HTTP/2 and TCP add a
/// few per cent).
async fn observer_bandwidth(server_bin: &std::path::Path, traj: &std::sync::Arc<needlesim_scene::Trajectory>, seconds: f64) {
    use prost::Message;
    let data = TempDir::new("observers");
    let mut child = Command::new(server_bin)
        .args(["serve", "--listen", "127.0.0.1:0", "--default-scene", "none", "--data-dir"])
        .arg(data.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the release server starts");
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    let addr = loop {
        line.clear();
        assert!(out.read_line(&mut line).unwrap() > 0, "the server did not start");
        if let Some(a) = line.trim().strip_prefix("listening on ") {
            break a.to_owned();
        }
    };
    let ch = tonic::transport::Channel::from_shared(format!("http://{addr}")).unwrap().connect().await.unwrap();
    let s = create(&ch).await.expect("create a session");
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let driver = {
        let (ch, s, traj, stop) = (ch.clone(), s.clone(), traj.clone(), stop.clone());
        tokio::spawn(async move {
            let mut c = pb::control_service_client::ControlServiceClient::new(ch);
            let (t0, t1) = traj.span_s();
            let start = Instant::now();
            let mut every = tokio::time::interval(Duration::from_millis(10));
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                every.tick().await;
                let p = traj.pose_at(t0 + start.elapsed().as_secs_f64() % (t1 - t0));
                let req = pb::SetPoseRequest {
                    session_id: sid(&s),
                    base: Some(pb::Pose2 { x_m: p.x_m, y_m: p.y_m, theta_rad: p.theta_rad }),
                    client_id: "driver".into(),
                    take_over: false,
                };
                let _ = c.set_pose(with_token(req, &s.controller_token)).await;
            }
        })
    };
    println!("| observer | frames/s | payload (kB/s) |");
    println!("|---|---|---|");
    for (rate_hz, displacements) in [(30.0, false), (60.0, false), (30.0, true), (60.0, true)] {
        let mut c = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
        let req = pb::ObserveRequest { session_id: sid(&s), rate_hz, include_displacements: displacements };
        let mut stream = c.observe(with_token(req, &s.observer_token)).await.expect("observe").into_inner();
        let _ = stream.message().await; // the first frame, before timing
        let (mut frames, mut bytes) = (0u64, 0u64);
        let start = Instant::now();
        while start.elapsed().as_secs_f64() < seconds {
            match tokio::time::timeout(Duration::from_secs(1), stream.message()).await {
                Ok(Ok(Some(f))) => {
                    frames += 1;
                    bytes += f.encoded_len() as u64 + 5;
                }
                _ => break,
            }
        }
        let wall = start.elapsed().as_secs_f64();
        println!(
            "| {rate_hz:.0} Hz{} | {:.1} | {:.1} |",
            if displacements { ", every node's displacement" } else { "" },
            frames as f64 / wall,
            bytes as f64 / wall / 1e3
        );
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let _ = driver.await;
    let _ = child.kill();
    let _ = child.wait();
}

/// The YAML files of deploy/k8s/.
fn manifests() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo_root().join("deploy/k8s"))
        .expect("deploy/k8s")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
        .collect();
    files.sort();
    files
}

fn validate(files: &[PathBuf]) -> (bool, String) {
    let out = needlesim_tests::run(Command::new(python()).arg(repo_root().join("tests/support/validate_manifests.py")).args(files));
    let (stdout, stderr) = needlesim_tests::text(&out);
    (out.status.success(), format!("{stdout}{stderr}"))
}

/// The manifests validate: the Kubernetes kinds (and the Fleet's pod template) against the
/// Kubernetes schemas of `kubernetes-validate`, the Agones kinds against Agones' documented fields,
/// all of them against each other and the server's flags; and the validator catches each of a
/// set of broken copies.
#[test]
fn manifests_validate() {
    let files = manifests();
    let (ok, report) = validate(&files);
    assert!(ok, "{report}");
    let kinds: Vec<String> = files
        .iter()
        .flat_map(|f| {
            std::fs::read_to_string(f).unwrap().lines().filter_map(|l| l.strip_prefix("kind: ").map(str::to_owned)).collect::<Vec<_>>()
        })
        .collect();
    for k in ["Fleet", "FleetAutoscaler", "GameServerAllocation", "Role", "RoleBinding", "ServiceAccount", "Deployment", "Service"] {
        assert!(kinds.iter().any(|x| x == k), "no {k} in deploy/k8s ({kinds:?})");
    }
    assert!(report.contains("5 Kubernetes") && report.contains("6 Agones"), "{report}");
    let broken = [
        ("fleet.yaml", "capacity: 8", "capacity: 6", "!= --max-sessions"),
        (
            "fleet.yaml",
            "                  cpu: \"4\"\n                  memory: 2Gi\n                limits:",
            "                  cpu: \"2\"\n                  memory: 2Gi\n                limits:",
            "requests must equal limits",
        ),
        ("fleet.yaml", "runAsUser: 10001", "runAsUser: nobody", "runAsUser"),
        ("fleet.yaml", "                - --agones\n", "", "without --agones"),
        ("fleet.yaml", "portPolicy: Dynamic", "portPolicy: Random", "portPolicy"),
        ("fleet.yaml", "terminationGracePeriodSeconds: 1860", "terminationGracePeriodSeconds: 60", "terminationGracePeriodSeconds"),
        ("fleetautoscaler.yaml", "fleetName: needlesim", "fleetName: another", "no such Fleet"),
        ("fleetautoscaler.yaml", "key: sessions", "key: rooms", "no such Counter"),
        ("allocation.yaml", "gameServerState: Ready", "gameServerState: Shutdown", "gameServerState"),
        ("planning.yaml", "containerPort: 50051", "containerPort: fifty", "containerPort"),
        // The 3D fleet (issue 22's sizing in docs/capacity.md), its autoscaler and allocation.
        ("fleet-3d.yaml", "capacity: 4", "capacity: 8", "!= --max-sessions"),
        ("fleet-3d.yaml", "fleetName: needlesim-3d", "fleetName: needlesim-4d", "no such Fleet"),
        ("allocation-3d.yaml", "agones.dev/fleet: needlesim-3d", "agones.dev/fleet: needlesim-2d", "no such Fleet"),
    ];
    for (file, from, to, expect) in broken {
        let dir = TempDir::new("manifests");
        let mut copies = Vec::new();
        for f in &files {
            let mut text = std::fs::read_to_string(f).unwrap();
            if f.file_name().unwrap() == file {
                assert!(text.contains(from), "{file} has no {from:?}");
                text = text.replacen(from, to, 1);
            }
            let copy = dir.join(f.file_name().unwrap().to_str().unwrap());
            std::fs::write(&copy, text).unwrap();
            copies.push(copy);
        }
        let (ok, report) = validate(&copies);
        assert!(!ok && report.contains(expect), "{file}: {from:?} → {to:?} not caught (expected {expect:?}):\n{report}");
    }
}

/// The `cargo` command in `line` as (profile, packages), or None if it is not `cargo run|build`.
fn cargo_command(line: &str) -> Option<(String, Vec<String>)> {
    let line = line.split(" -- ").next()?;
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words.iter().position(|w| *w == "cargo")?;
    if !matches!(words.get(at + 1), Some(&"run") | Some(&"build")) {
        return None;
    }
    let mut profile = "dev".to_owned();
    let mut packages = Vec::new();
    let mut i = at + 2;
    while i < words.len() {
        match words[i] {
            "--release" | "-r" => profile = "release".into(),
            "--profile" => {
                profile = words.get(i + 1)?.to_string();
                i += 1;
            }
            "-p" | "--package" => {
                packages.push(words.get(i + 1)?.to_string());
                i += 1;
            }
            w if w.starts_with("--package=") => packages.push(w["--package=".len()..].to_owned()),
            _ => {}
        }
        i += 1;
    }
    packages.sort();
    Some((profile, packages))
}

/// The container image builds the same binaries as README's command (`cargo run --release -p
/// needlesim-server`): same profile, same packages, and it copies out exactly those packages'
/// binaries from that profile's directory, with the web viewer's files the server serves.
#[test]
fn the_dockerfile_builds_what_the_readme_runs() {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let section = readme.split("\n## Two commands").nth(1).expect("README has a \"Two commands\" section");
    let section = section.split("\n## ").next().unwrap();
    let readme_cmd = section.lines().find_map(cargo_command).expect("a cargo run/build command in README's \"Two commands\"");
    let dockerfile = std::fs::read_to_string(repo_root().join("Dockerfile")).unwrap();
    let builds: Vec<(String, Vec<String>)> =
        dockerfile.lines().filter(|l| l.trim_start().starts_with("RUN ")).filter_map(cargo_command).collect();
    assert_eq!(builds.len(), 1, "the Dockerfile has one cargo build: {builds:?}");
    assert_eq!(builds[0], readme_cmd, "the Dockerfile's build (profile, packages) differs from README's command");
    let (profile, packages) = readme_cmd;
    let dir = if profile == "dev" { "debug".to_owned() } else { profile };
    // The binaries those packages declare, from cargo's metadata.
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = needlesim_tests::run(Command::new(cargo).current_dir(repo_root()).args([
        "metadata",
        "--no-deps",
        "--format-version",
        "1",
        "--offline",
    ]));
    assert!(out.status.success(), "cargo metadata: {}", String::from_utf8_lossy(&out.stderr));
    let meta: Value = serde_json::from_slice(&out.stdout).unwrap();
    let mut bins: Vec<String> = meta["packages"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| packages.iter().any(|n| p["name"] == n.as_str()))
        .flat_map(|p| {
            p["targets"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|t| t["kind"][0] == "bin")
                .map(|t| t["name"].as_str().unwrap().to_owned())
                .collect::<Vec<_>>()
        })
        .collect();
    bins.sort();
    assert!(!bins.is_empty(), "the packages {packages:?} declare no binary");
    let prefix = format!("/target/{dir}/");
    let mut copied: Vec<String> = dockerfile
        .lines()
        .filter(|l| l.starts_with("COPY --from=build") && l.contains(&prefix))
        .map(|l| l.split_whitespace().nth(2).unwrap().rsplit('/').next().unwrap().to_owned())
        .collect();
    copied.sort();
    assert_eq!(copied, bins, "the binaries copied out of target/{dir}/");
    // The web viewer: index.html and what it loads, at the --web-dir the image serves.
    let index = std::fs::read_to_string(repo_root().join("web/index.html")).unwrap();
    assert!(index.contains("dist/"), "web/index.html loads its code from dist/");
    assert!(repo_root().join("web/dist").is_dir());
    for f in ["/src/web/index.html /app/web/index.html", "/src/web/dist /app/web/dist"] {
        assert!(dockerfile.contains(f), "the Dockerfile does not copy {f}");
    }
    assert!(dockerfile.contains("--web-dir=/app/web"));
    let ignore = std::fs::read_to_string(repo_root().join(".dockerignore")).unwrap();
    assert!(ignore.lines().any(|l| l.trim() == "target/"), ".dockerignore keeps target/ out of the build context");
}
