//! The `needlesim` CLI end to end against the real server: sessions, watch, drive, record and
//! replay, simulate (CSV and JSON), and its error paths (unreachable server, refused tokens,
//! unknown sessions, bad files): a one-line `error: …` on stderr, exit code 1, never a panic.

use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use needlesim_tests::{ServerProcess, TempDir, bin, text};
use serde_json::Value;

/// The tests that run a 1 kHz session take turns (2-core machines), with every real-time test of
/// tests/it/.
fn turn() -> tokio::sync::MutexGuard<'static, ()> {
    needlesim_tests::REALTIME.blocking_lock()
}

/// Runs `needlesim ARGS` (without the NEEDLESIM_* environment unless `env` sets it), killing it
/// after 60 s.
fn needlesim_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(bin("needlesim"));
    cmd.args(args).env_remove("NEEDLESIM_SERVER").env_remove("NEEDLESIM_TOKEN");
    for (k, v) in env {
        cmd.env(k, v);
    }
    needlesim_tests::run_within(&mut cmd, Duration::from_secs(60))
}

fn needlesim(args: &[&str]) -> Output {
    needlesim_env(args, &[])
}

/// Asserts success and returns stdout.
fn ok(args: &[&str], o: &Output) -> String {
    let (stdout, stderr) = text(o);
    assert!(o.status.success(), "needlesim {args:?} failed ({}):\nstdout: {stdout}\nstderr: {stderr}", o.status);
    assert!(!stderr.contains("panicked"), "needlesim {args:?} panicked:\n{stderr}");
    stdout
}

fn run_ok(args: &[&str]) -> String {
    ok(args, &needlesim(args))
}

/// Asserts a clean failure: exit code 1, no panic, nothing on stdout, one `error: ` line on
/// stderr containing every string of `expected`. Returns that line.
fn assert_fails(args: &[&str], o: &Output, expected: &[&str]) -> String {
    let (stdout, stderr) = text(o);
    println!("{args:?}: {}", stderr.trim());
    assert_eq!(o.status.code(), Some(1), "needlesim {args:?}: expected exit code 1, got {}\nstderr: {stderr}", o.status);
    assert!(!stderr.contains("panicked"), "needlesim {args:?} panicked:\n{stderr}");
    assert!(stdout.trim().is_empty(), "needlesim {args:?}: unexpected stdout: {stdout}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "needlesim {args:?}: expected one line on stderr, got:\n{stderr}");
    assert!(lines[0].starts_with("error: "), "needlesim {args:?}: not an `error: ` line: {}", lines[0]);
    for e in expected {
        assert!(lines[0].contains(e), "needlesim {args:?}: the error does not mention {e:?}:\n{}", lines[0]);
    }
    lines[0].to_owned()
}

struct Created {
    id: String,
    controller: String,
    observer: String,
}

fn create(url: &str, example: &str) -> Created {
    let args = ["--server", url, "sessions", "create", "--example", example, "--json"];
    let v: Value = serde_json::from_str(&run_ok(&args)).expect("sessions create --json prints JSON");
    let s = |k: &str| v[k].as_str().unwrap_or_else(|| panic!("no string `{k}` in {v}")).to_owned();
    let c = Created { id: s("session_id"), controller: s("controller_token"), observer: s("observer_token") };
    assert!(!c.id.is_empty() && !c.controller.is_empty() && !c.observer.is_empty() && c.controller != c.observer, "{v}");
    assert_eq!(v["scene"], example);
    c
}

/// The ids of the `sessions list` table (first column, after the header).
fn listed_ids(url: &str) -> Vec<String> {
    let out = run_ok(&["--server", url, "sessions", "list"]);
    let mut lines = out.lines();
    let header = lines.next().unwrap_or_default();
    for col in ["id", "scene", "nodes", "rate", "tick", "observers", "recording"] {
        assert!(header.split_whitespace().any(|c| c == col), "the table header lacks {col}: {header}");
    }
    lines.map(|l| l.split_whitespace().next().unwrap_or_default().to_owned()).collect()
}

/// `key=value` fields of a `watch --plain` / `replay` line.
fn field(line: &str, key: &str) -> f64 {
    line.split_whitespace()
        .find_map(|kv| kv.strip_prefix(key).and_then(|r| r.strip_prefix('=')))
        .unwrap_or_else(|| panic!("no {key}= in {line}"))
        .parse()
        .unwrap_or_else(|e| panic!("{key} in {line}: {e}"))
}

fn write(path: &Path, s: &str) {
    std::fs::write(path, s).expect("write a test file");
}

const DOWN: &str = "-1.5707963267948966";

#[test]
fn sessions_create_list_close() {
    let _turn = turn();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let url = server.url();
    assert!(listed_ids(&url).is_empty(), "a server without a default scene lists no sessions");

    // The human output names the session and both tokens.
    let args = ["--server", url.as_str(), "sessions", "create", "--example", "paper-phantom"];
    let human = run_ok(&args);
    let value_of = |label: &str| {
        human
            .lines()
            .find_map(|l| l.strip_prefix(label))
            .map(|v| v.trim().to_owned())
            .unwrap_or_else(|| panic!("no `{label}` line in:\n{human}"))
    };
    let (id1, ctl1) = (value_of("session "), value_of("controller token "));
    assert!(!value_of("observer token ").is_empty() && !ctl1.is_empty());

    let b = create(&url, "paper-phantom");
    let ids = listed_ids(&url);
    assert!(ids.contains(&id1) && ids.contains(&b.id), "both sessions are listed: {ids:?}");
    assert_eq!(ids.len(), 2, "{ids:?}");
    let json: Value = serde_json::from_str(&run_ok(&["--server", &url, "sessions", "list", "--json"])).unwrap();
    assert_eq!(json.as_array().map(Vec::len), Some(2), "{json}");
    assert_eq!(json[0]["n_nodes"], 361, "{json}");

    // A wrong token, or the observer token, cannot close it; a missing token neither.
    for token in ["not-the-token", b.observer.as_str()] {
        let args = ["--server", &url, "--token", token, "sessions", "close", &b.id];
        assert_fails(&args, &needlesim(&args), &["the token was refused", "driving a session needs its controller token"]);
    }
    let args = ["--server", &url, "sessions", "close", &b.id];
    assert_fails(&args, &needlesim(&args), &["the token was refused", "controller token"]);
    assert!(listed_ids(&url).contains(&b.id), "a refused close closed the session");

    // The controller token closes it (from the environment here).
    let args = ["sessions", "close", &b.id];
    let out = ok(&args, &needlesim_env(&args, &[("NEEDLESIM_SERVER", &url), ("NEEDLESIM_TOKEN", &b.controller)]));
    assert!(out.contains(&b.id), "{out}");
    let ids = listed_ids(&url);
    assert_eq!(ids, vec![id1.clone()], "only the first session is left");

    // Closing it again: unknown session.
    let args = ["--server", &url, "--token", &b.controller, "sessions", "close", &b.id];
    assert_fails(&args, &needlesim(&args), &["no session", &b.id]);
    run_ok(&["--server", &url, "--token", &ctl1, "sessions", "close", &id1]);
    assert!(listed_ids(&url).is_empty());
}

/// Issue 8: `needlesim flip-bevel` turns a bevel-tip needle; a symmetric one has nothing to flip.
#[test]
fn flip_bevel_command() {
    let _turn = turn();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let url = server.url();
    let bevel = create(&url, "bevel-tip");
    let out = run_ok(&["--server", &url, "--token", &bevel.controller, "flip-bevel", &bevel.id]);
    assert!(out.contains("bevel flip 1 requested"), "{out}");
    let out = run_ok(&["--server", &url, "--token", &bevel.controller, "flip-bevel", &bevel.id]);
    assert!(out.contains("bevel flip 2 requested"), "{out}");
    let args = ["--server", url.as_str(), "--token", bevel.observer.as_str(), "flip-bevel", bevel.id.as_str()];
    assert_fails(&args, &needlesim(&args), &["controller token"]);
    let rigid = create(&url, "paper-phantom");
    let args = ["--server", url.as_str(), "--token", rigid.controller.as_str(), "flip-bevel", rigid.id.as_str()];
    assert_fails(&args, &needlesim(&args), &["symmetric tip"]);
}

#[test]
fn watch_drive_record_replay() {
    let _turn = turn();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let url = server.url();
    let s = create(&url, "paper-phantom");
    let tmp = TempDir::new("cli-drive");

    // watch --plain --ticks N: N lines, each with the depth and the forces, in tick order.
    let watch = |token: &str, n: &str| -> Vec<String> {
        let out = run_ok(&["--server", &url, "--token", token, "watch", &s.id, "--plain", "--ticks", n]);
        out.lines().map(str::to_owned).collect()
    };
    let before = watch(&s.observer, "5");
    assert_eq!(before.len(), 5, "{before:?}");
    let mut prev = -1.0;
    for l in &before {
        let tick = field(l, "tick");
        assert!(tick > prev, "ticks in order: {before:?}");
        prev = tick;
        assert_eq!(field(l, "depth_mm"), 0.0, "the needle starts outside the tissue: {l}");
        field(l, "f_axial_n");
        field(l, "f_lateral_n");
        field(l, "torque_nm");
        assert!(l.contains("target_centre_mm="), "{l}");
    }
    // Watching needs a token.
    let args = ["--server", &url, "watch", &s.id, "--plain", "--ticks", "1"];
    assert_fails(&args, &needlesim(&args), &["the token was refused", "observer or controller token"]);
    let args = ["--server", &url, "--token", &s.observer, "watch", "no-such-session", "--plain", "--ticks", "1"];
    assert_fails(&args, &needlesim(&args), &["no session 'no-such-session'"]);

    // Drive a 2 s insertion: the tip from 5 mm above the top to 20 mm deep.
    let traj = tmp.join("insert.csv");
    write(&traj, &format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.205,{DOWN}\n2,0.05,0.18,{DOWN}\n"));
    let traj_s = traj.to_str().unwrap();
    for token in ["wrong", s.observer.as_str()] {
        let args = ["--server", &url, "--token", token, "drive", &s.id, "--trajectory", traj_s];
        assert_fails(&args, &needlesim(&args), &["the token was refused", "driving a session needs its controller token"]);
    }
    let args = ["--server", &url, "--token", &s.controller, "drive", "no-such-session", "--trajectory", traj_s];
    assert_fails(&args, &needlesim(&args), &["no session 'no-such-session'"]);
    let started = Instant::now();
    let summary = run_ok(&["--server", &url, "--token", &s.controller, "drive", &s.id, "--trajectory", traj_s]);
    let took = started.elapsed().as_secs_f64();
    println!("{summary}");
    assert!((1.9..10.0).contains(&took), "a 2 s trajectory is played in real time, took {took} s");
    let num = |label: &str| -> f64 {
        let l = summary.lines().find(|l| l.starts_with(label)).unwrap_or_else(|| panic!("no `{label}` in:\n{summary}"));
        l[label.len()..].split_whitespace().next().unwrap().trim_end_matches(',').parse().unwrap_or_else(|e| panic!("{l}: {e}"))
    };
    let sent = num("poses sent");
    assert!((1500.0..=2100.0).contains(&sent), "about 2000 poses at 1 kHz, sent {sent}");
    assert!(num("responses") > 1000.0, "{summary}");
    let depth = num("final depth");
    assert!((15.0..25.0).contains(&depth), "driven to about 20 mm: {depth}");
    assert!(summary.contains("final force    axial -"), "the tissue resists the insertion:\n{summary}");
    let p50 = summary.lines().find(|l| l.starts_with("latency")).and_then(|l| l.split_whitespace().nth(2)).unwrap();
    assert!(p50.parse::<f64>().is_ok_and(|v| v > 0.0 && v < 100.0), "latency p50 in ms: {summary}");

    // The session holds the last pose: the depth increased, the force resists.
    let after = watch(&s.controller, "3");
    assert_eq!(after.len(), 3, "{after:?}");
    for l in &after {
        let d = field(l, "depth_mm");
        assert!((15.0..25.0).contains(&d), "the depth increased to about 20 mm: {l}");
        assert!(field(l, "f_axial_n") < 0.0, "{l}");
        assert!(field(l, "stuck") + field(l, "slipping") + field(l, "tip") > 0.0, "needle nodes in the tissue: {l}");
    }

    // Record 1 s and replay it.
    let mcap = tmp.join("rec.mcap");
    let mcap_s = mcap.to_str().unwrap();
    let args = ["--server", &url, "--token", &s.observer, "record", &s.id, "--out", mcap_s, "--seconds", "1"];
    assert_fails(&args, &needlesim(&args), &["the token was refused", "controller token"]);
    assert!(!mcap.exists(), "a refused recording leaves no file");
    let out = run_ok(&["--server", &url, "--token", &s.controller, "record", &s.id, "--out", mcap_s, "--seconds", "1"]);
    assert!(out.contains("recorded"), "{out}");
    let bytes = std::fs::read(&mcap).expect("the recording is written");
    assert!(bytes.starts_with(b"\x89MCAP0\r\n") && bytes.ends_with(b"\x89MCAP0\r\n"), "a complete MCAP file");
    let replay = run_ok(&["replay", mcap_s, "--speed", "0"]);
    let lines: Vec<&str> = replay.lines().collect();
    assert!(lines.len() > 500, "a second at 1 kHz, replayed {} frames", lines.len());
    let ticks: Vec<f64> = lines.iter().map(|l| field(l, "tick")).collect();
    assert!(ticks.windows(2).all(|w| w[1] > w[0]), "frames in tick order");
    let t: Vec<f64> = lines.iter().map(|l| field(l, "t_s")).collect();
    assert!(t.windows(2).all(|w| w[1] > w[0]), "frames in time order");
    assert!((0.5..1.5).contains(&(t[t.len() - 1] - t[0])), "about 1 s of frames: {} .. {}", t[0], t[t.len() - 1]);
    for l in [lines[0], lines[lines.len() - 1]] {
        assert!((15.0..25.0).contains(&field(l, "depth_mm")), "{l}");
        assert!(field(l, "f_axial_n") < 0.0, "{l}");
    }
    // Paced by the log times: the same second takes about a second at --speed 1, half at 2.
    let started = Instant::now();
    let paced = run_ok(&["replay", mcap_s, "--speed", "2"]);
    let took = started.elapsed().as_secs_f64();
    assert_eq!(paced.lines().count(), lines.len());
    assert!((0.3..1.0).contains(&took), "--speed 2 replays 1 s in about 0.5 s, took {took}");
}

#[test]
fn simulate_csv_and_json() {
    let _turn = turn();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let url = server.url();
    let tmp = TempDir::new("cli-sim");

    let csv = run_ok(&["--server", &url, "simulate", "--example", "paper-phantom", "--decimate", "10", "--format", "csv"]);
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let expect = "t_s,x_m,y_m,theta_rad,fx_n,fy_n,torque_nm,f_axial_n,f_lateral_n,tip_x_m,tip_y_m,inserted_m,n_stuck,n_slipping,n_tip,\
                  target_centre_distance_m,target_centre_x_m,target_centre_y_m,target_centre_hit";
    assert_eq!(header.join(","), expect);
    let rows: Vec<Vec<f64>> =
        lines.map(|l| l.split(',').map(|v| v.parse().unwrap_or_else(|e| panic!("{v} in {l}: {e}"))).collect()).collect();
    assert!(rows.iter().all(|r| r.len() == header.len()), "every row has every column");
    // The example's 10 s trajectory at 1 kHz, one row in 10.
    assert!((990..=1010).contains(&rows.len()), "{} rows", rows.len());
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (ins, axial, t) = (col("inserted_m"), col("f_axial_n"), col("t_s"));
    assert!(rows.windows(2).all(|w| w[1][t] > w[0][t]), "rows in time order");
    // The first row at the greatest depth: the end of the insertion (the hold and the withdrawal
    // after it keep that depth for a while).
    let deepest = rows.iter().reduce(|a, b| if b[ins] > a[ins] { b } else { a }).unwrap();
    assert!(deepest[ins] > 0.01, "the example inserts more than 10 mm: {}", deepest[ins]);
    assert!(deepest[axial] < 0.0, "the axial force at the deepest point resists the insertion: {}", deepest[axial]);

    // JSON into a file: the same series.
    let out = tmp.join("sim.json");
    let args = [
        "--server",
        &url,
        "simulate",
        "--example",
        "paper-phantom",
        "--decimate",
        "10",
        "--format",
        "json",
        "--out",
        out.to_str().unwrap(),
    ];
    let stdout = run_ok(&args);
    assert!(stdout.trim().is_empty(), "--out writes nothing to stdout: {stdout}");
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).expect("JSON output");
    let jrows = v["rows"].as_array().expect("rows");
    assert_eq!(jrows.len(), rows.len());
    assert!(v["ticks"].as_u64().is_some_and(|n| n > 9000), "{}", v["ticks"]);
    let depth = |r: &Value| r["inserted_m"].as_f64().unwrap();
    let j = jrows.iter().reduce(|a, b| if depth(b) > depth(a) { b } else { a }).unwrap();
    assert!((j["inserted_m"].as_f64().unwrap() - deepest[ins]).abs() < 1e-9);
    assert!(j["f_axial_n"].as_f64().unwrap() < 0.0);
    assert!(j["target_centre_distance_m"].as_f64().is_some());

    // A custom trajectory: a 1 s insertion, one row per 100 ticks.
    let traj = tmp.join("t.csv");
    write(&traj, &format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.205,{DOWN}\n1,0.05,0.185,{DOWN}\n"));
    let csv =
        run_ok(&["--server", &url, "simulate", "--example", "paper-phantom", "--trajectory", traj.to_str().unwrap(), "--decimate", "100"]);
    assert_eq!(csv.lines().count(), 1 + 11, "{csv}");
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    let y: f64 = last[2].parse().unwrap();
    assert!((y - 0.185).abs() < 1e-9, "the last row is at the trajectory's end: {y}");

    let args = ["--server", &url, "simulate", "--example", "no-such-example"];
    assert_fails(&args, &needlesim(&args), &["no-such-example"]);
}

#[test]
fn unreachable_server_and_bad_files() {
    // A closed port.
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let url = format!("http://127.0.0.1:{port}");
    for args in [
        vec!["--server", url.as_str(), "sessions", "list"],
        vec!["--server", url.as_str(), "watch", "abc", "--plain", "--ticks", "1"],
        vec!["--server", url.as_str(), "simulate", "--example", "paper-phantom"],
    ] {
        let line = assert_fails(&args, &needlesim(&args), &["cannot reach the needlesim server at", &url, "is it running?"]);
        assert!(line.contains("needlesim-server serve"), "{line}");
    }
    // The environment names the server too.
    let args = ["sessions", "list"];
    assert_fails(&args, &needlesim_env(&args, &[("NEEDLESIM_SERVER", &url)]), &["cannot reach", &url]);

    let tmp = TempDir::new("cli-bad");
    // A trajectory with a bad value on line 4 (after a comment line).
    let bad = tmp.join("bad.csv");
    write(&bad, &format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.205,{DOWN}\n# a comment\n1,0.05,oops,{DOWN}\n"));
    let bad_s = bad.to_str().unwrap();
    for args in [
        vec!["--server", url.as_str(), "--token", "t", "drive", "abc", "--trajectory", bad_s],
        vec!["--server", url.as_str(), "simulate", "--example", "paper-phantom", "--trajectory", bad_s],
    ] {
        assert_fails(&args, &needlesim(&args), &[bad_s, "line 4", "y_m", "oops"]);
    }
    // Too few columns; times that do not increase; a wrong header.
    let cases = [
        (format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.205,{DOWN}\n1,0.05,0.2\n"), "line 3"),
        (format!("t_s,x_m,y_m,theta_rad\n0,0.05,0.205,{DOWN}\n1,0.05,0.2,{DOWN}\n1,0.05,0.2,{DOWN}\n"), "line 4"),
        ("t,x,y\n0,1,2\n".to_owned(), "line 1"),
    ];
    for (contents, line) in cases {
        write(&bad, &contents);
        let args = ["--server", url.as_str(), "--token", "t", "drive", "abc", "--trajectory", bad_s];
        assert_fails(&args, &needlesim(&args), &[bad_s, line]);
    }
    // Missing files, and a file that is not MCAP.
    let missing = tmp.join("missing.csv");
    let args = ["--server", url.as_str(), "drive", "abc", "--trajectory", missing.to_str().unwrap()];
    assert_fails(&args, &needlesim(&args), &["missing.csv"]);
    let args = ["replay", bad_s];
    assert_fails(&args, &needlesim(&args), &[bad_s, "not an MCAP file"]);
    let args = ["--server", url.as_str(), "sessions", "create", "--scene", missing.to_str().unwrap()];
    assert_fails(&args, &needlesim(&args), &["missing.csv"]);
}
