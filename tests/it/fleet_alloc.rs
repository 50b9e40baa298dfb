//! Allocation for clients (issue 22, item 3): the `needlesim` CLI and the Python client ask a local
//! stand-in of the Agones allocator service (tests/support/agones_allocator_stub.py, written from
//! the documented REST API: `POST /gameserverallocation`, mTLS, label selectors, Counters, the
//! 429 UnAllocated answer) for a server, and create the session on the address it returns — a
//! real needlesim-server process. The certificates (a CA, the allocator's, an allow-listed client
//! and one from another CA) are made here with the `openssl` command. Also: no match, refused and
//! untrusted certificates and an unreachable allocator are each one clear error line; the Helm
//! values in deploy/k8s/helm/ set up what a client needs.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use needlesim_tests::{ServerProcess, TempDir, bin, python, repo_root, run, text};
use serde_json::{Value, json};

const FLEET: &str = "agones.dev/fleet";

/// Certificates made with openssl (ECDSA P-256): the allocator's CA and server certificate (for
/// 127.0.0.1), a client certificate signed by the CA it allow-lists, and one signed by another CA.
struct Certs {
    dir: TempDir,
}

impl Certs {
    fn new() -> Self {
        let dir = TempDir::new("alloc-certs");
        let openssl = |args: &[&str]| {
            let out = run(Command::new("openssl").current_dir(dir.path()).args(args));
            assert!(out.status.success(), "openssl {args:?} failed (the test needs the openssl command): {}", text(&out).1);
        };
        for ca in ["ca", "rogue-ca"] {
            let subj = format!("/CN=test-{ca}");
            openssl(&[
                "req",
                "-x509",
                "-newkey",
                "ec",
                "-pkeyopt",
                "ec_paramgen_curve:prime256v1",
                "-nodes",
                "-days",
                "2",
                "-subj",
                &subj,
                "-keyout",
                &format!("{ca}.key"),
                "-out",
                &format!("{ca}.crt"),
            ]);
        }
        for (name, cn, ext, ca) in [
            ("server", "127.0.0.1", "subjectAltName=IP:127.0.0.1\nbasicConstraints=CA:FALSE\nextendedKeyUsage=serverAuth\n", "ca"),
            ("client", "needlesim-portal", "basicConstraints=CA:FALSE\nextendedKeyUsage=clientAuth\n", "ca"),
            ("intruder", "intruder", "basicConstraints=CA:FALSE\nextendedKeyUsage=clientAuth\n", "rogue-ca"),
        ] {
            std::fs::write(dir.join(&format!("{name}.ext")), ext).unwrap();
            openssl(&[
                "req",
                "-new",
                "-newkey",
                "ec",
                "-pkeyopt",
                "ec_paramgen_curve:prime256v1",
                "-nodes",
                "-subj",
                &format!("/CN={cn}"),
                "-keyout",
                &format!("{name}.key"),
                "-out",
                &format!("{name}.csr"),
            ]);
            openssl(&[
                "x509",
                "-req",
                "-in",
                &format!("{name}.csr"),
                "-CA",
                &format!("{ca}.crt"),
                "-CAkey",
                &format!("{ca}.key"),
                "-CAcreateserial",
                "-days",
                "2",
                "-extfile",
                &format!("{name}.ext"),
                "-out",
                &format!("{name}.crt"),
            ]);
        }
        Self { dir }
    }

    fn path(&self, name: &str) -> String {
        self.dir.join(name).to_str().expect("a UTF-8 temporary path").to_owned()
    }

    /// The CLI's flags for the allow-listed client.
    fn client_flags(&self) -> Vec<String> {
        ["--client-cert", "client.crt", "--client-key", "client.key", "--ca-cert", "ca.crt"]
            .chunks(2)
            .flat_map(|f| [f[0].to_owned(), self.path(f[1])])
            .collect()
    }
}

/// The stand-in allocator, killed on drop.
struct Allocator {
    child: Child,
    url: String,
    log: PathBuf,
    _dir: TempDir,
}

impl Allocator {
    /// Serves `servers` (the stub's game-server list); HTTPS with mTLS when `certs` is given.
    fn start(servers: &Value, certs: Option<&Certs>) -> Self {
        let dir = TempDir::new("allocator");
        let list = dir.join("servers.json");
        std::fs::write(&list, servers.to_string()).unwrap();
        let (log, port_file) = (dir.join("calls.jsonl"), dir.join("port"));
        let mut cmd = Command::new(python());
        cmd.arg(repo_root().join("tests/support/agones_allocator_stub.py"))
            .arg("--game-servers")
            .arg(&list)
            .arg("--log")
            .arg(&log)
            .arg("--port-file")
            .arg(&port_file)
            .stdout(Stdio::null());
        if let Some(c) = certs {
            cmd.args(["--tls-cert", &c.path("server.crt"), "--tls-key", &c.path("server.key"), "--client-ca", &c.path("ca.crt")]);
        }
        let mut child = cmd.spawn().expect("the stand-in allocator starts");
        let deadline = Instant::now() + Duration::from_secs(20);
        let port: u16 = loop {
            if let Some(p) = std::fs::read_to_string(&port_file).ok().and_then(|s| s.trim().parse().ok()) {
                break p;
            }
            if Instant::now() > deadline || child.try_wait().ok().flatten().is_some() {
                let _ = child.kill();
                panic!("the stand-in allocator wrote no port");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let scheme = if certs.is_some() { "https" } else { "http" };
        Self { child, url: format!("{scheme}://127.0.0.1:{port}"), log, _dir: dir }
    }

    /// The requests it received: (status, body, allocated game server).
    fn calls(&self) -> Vec<(u64, Value, Option<String>)> {
        std::fs::read_to_string(&self.log)
            .unwrap_or_default()
            .lines()
            .map(|l| serde_json::from_str::<Value>(l).expect("a JSON log line"))
            .map(|v| (v["status"].as_u64().unwrap(), v["body"].clone(), v["game_server"].as_str().map(str::to_owned)))
            .collect()
    }
}

impl Drop for Allocator {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A port nothing listens on.
fn closed_port() -> u16 {
    let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    l.local_addr().unwrap().port()
}

/// The fleet the stand-in serves: first a decoy of another fleet (on a closed port), then the
/// real server, with room for `capacity` sessions, both in namespace "trainees".
fn fleet(server_addr: &str, capacity: u64) -> Value {
    let port: u16 = server_addr.rsplit(':').next().unwrap().parse().unwrap();
    json!([
        {"name": "needlesim-canary-x1", "namespace": "trainees", "address": "127.0.0.1", "nodeName": "node-a",
         "ports": [{"name": "grpc", "port": closed_port()}],
         "labels": {FLEET: "needlesim-canary", "agones.dev/sdk-scene": "none"},
         "counters": {"sessions": {"count": 0, "capacity": capacity}}},
        {"name": "needlesim-7xk2p", "namespace": "trainees", "address": "127.0.0.1", "nodeName": "node-b",
         "ports": [{"name": "metrics", "port": closed_port()}, {"name": "grpc", "port": port}],
         "labels": {FLEET: "needlesim", "agones.dev/sdk-scene": "none"},
         "counters": {"sessions": {"count": 0, "capacity": capacity}}},
    ])
}

/// `needlesim ARGS…` with no allocator or server from the environment.
fn needlesim(args: &[String]) -> Output {
    run(Command::new(bin("needlesim")).env_remove("NEEDLESIM_ALLOCATOR").env_remove("NEEDLESIM_SERVER").args(args))
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| (*s).to_owned()).collect()
}

/// Runs the CLI, expecting success: its standard output.
fn ok(args: &[String]) -> String {
    let out = needlesim(args);
    let (o, e) = text(&out);
    assert!(out.status.success(), "needlesim {args:?} failed:\n{o}\n{e}");
    o
}

/// Runs the CLI, expecting one `error: ` line naming each of `expected`.
fn fails(args: &[String], expected: &[&str]) -> String {
    let out = needlesim(args);
    let (o, e) = text(&out);
    assert_eq!(out.status.code(), Some(1), "needlesim {args:?} should fail with status 1:\n{o}\n{e}");
    let lines: Vec<&str> = e.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "needlesim {args:?}: one error line expected:\n{e}");
    assert!(lines[0].starts_with("error: "), "{}", lines[0]);
    assert!(!e.contains("panicked"), "{e}");
    for x in expected {
        assert!(lines[0].contains(x), "needlesim {args:?}: the error does not mention {x:?}:\n{}", lines[0]);
    }
    lines[0].to_owned()
}

/// The session ids the server lists.
fn listed(server: &ServerProcess) -> Vec<String> {
    let v: Value = serde_json::from_str(&ok(&strings(&["--server", &server.url(), "sessions", "list", "--json"]))).unwrap();
    v.as_array().unwrap().iter().map(|s| s["session_id"].as_str().unwrap().to_owned()).collect()
}

#[test]
fn cli_allocates_over_mtls_and_creates_the_session_on_the_allocated_server() {
    let _rt = needlesim_tests::REALTIME.blocking_lock();
    let certs = Certs::new();
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let alloc = Allocator::start(&fleet(&server.addr, 2), Some(&certs));
    let base = |extra: &[&str]| {
        let mut a = strings(&["--allocator", &alloc.url, "--namespace", "trainees"]);
        a.extend(certs.client_flags());
        a.extend(strings(extra));
        a
    };

    // `allocate`: the address and the port named grpc of the server whose labels match (not the
    // decoy listed first, nor its metrics port).
    let mut args = strings(&["allocate"]);
    args.extend(base(&["--selector", "agones.dev/fleet=needlesim,agones.dev/sdk-scene=none"]));
    assert_eq!(ok(&args).trim(), server.addr);
    let calls = alloc.calls();
    assert_eq!(calls.len(), 1, "{calls:?}");
    let (status, body, gs) = &calls[0];
    assert_eq!((*status, gs.as_deref()), (200, Some("needlesim-7xk2p")));
    assert_eq!(body["namespace"], "trainees");
    let sel = &body["gameServerSelectors"];
    assert_eq!(sel[0]["matchLabels"], json!({FLEET: "needlesim", "agones.dev/sdk-scene": "none"}));
    assert_eq!((sel[0]["gameServerState"].as_str(), sel[1]["gameServerState"].as_str()), (Some("ALLOCATED"), Some("READY")));
    assert_eq!(body["counters"]["sessions"]["action"], "Increment");

    // `sessions create --allocate`: the session is on the allocated server, whose URL it prints.
    let mut args = strings(&["sessions", "create", "--example", "paper-phantom", "--json", "--allocate"]);
    args.extend(base(&["--selector", "agones.dev/fleet=needlesim"]));
    let before = listed(&server);
    let created: Value = serde_json::from_str(&ok(&args)).expect("sessions create --json prints JSON");
    assert_eq!(created["server"], server.url(), "{created}");
    let id = created["session_id"].as_str().expect("a session id").to_owned();
    assert!(!before.contains(&id) && listed(&server).contains(&id), "session {id} is not on the allocated server");
    assert!(!created["controller_token"].as_str().unwrap_or_default().is_empty());

    // The server now holds its two places (each allocation reserved one): a third finds none —
    // the request asks for a free place — and says so.
    let mut args = strings(&["allocate"]);
    args.extend(base(&["--selector", "agones.dev/fleet=needlesim"]));
    fails(&args, &["no needlesim server available", "namespace 'trainees'", "[agones.dev/fleet=needlesim]", "429"]);
    assert_eq!(alloc.calls().last().unwrap().0, 429);

    // Close the session (its controller token) on the server it was created on.
    let ctl = created["controller_token"].as_str().unwrap();
    ok(&strings(&["--server", &server.url(), "--token", ctl, "sessions", "close", &id]));
}

#[test]
fn python_allocates_and_creates_a_session_with_grpcio() {
    let _rt = needlesim_tests::REALTIME.blocking_lock();
    let certs = Certs::new();
    let stubs = TempDir::new("alloc-pystubs");
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let alloc = Allocator::start(&fleet(&server.addr, 4), Some(&certs));
    let py = |selector: &str, create: bool| {
        let mut cmd = Command::new(python());
        cmd.env_remove("NEEDLESIM_ALLOCATOR")
            .arg(repo_root().join("client/python/needlesim_allocate.py"))
            .args(["--allocator", &alloc.url, "--namespace", "trainees", "--selector", selector])
            .args(certs.client_flags());
        if create {
            cmd.args(["--create", "paper-phantom", "--stubs"]).arg(stubs.path());
        }
        run(&mut cmd)
    };
    let out = py("agones.dev/fleet=needlesim", true);
    let (o, e) = text(&out);
    assert!(out.status.success(), "needlesim_allocate.py failed:\n{o}\n{e}");
    let v: Value = serde_json::from_str(&o).expect("one JSON object");
    assert_eq!((v["target"].as_str(), v["game_server"].as_str()), (Some(server.addr.as_str()), Some("needlesim-7xk2p")), "{v}");
    let id = v["session_id"].as_str().expect("a session id");
    assert!(listed(&server).contains(&id.to_owned()), "session {id} is not on the allocated server");
    let (_, body, _) = alloc.calls().pop().unwrap();
    assert_eq!(body["gameServerSelectors"][0]["matchLabels"], json!({FLEET: "needlesim"}));
    assert_eq!(body["namespace"], "trainees");

    // No match: a clear error, the allocator's 429, nothing created.
    let n = listed(&server).len();
    let out = py("agones.dev/fleet=nothing", true);
    let (o, e) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{o}\n{e}");
    assert!(e.contains("error: no needlesim server available") && e.contains("[agones.dev/fleet=nothing]"), "{e}");
    assert!(!e.contains("Traceback"), "{e}");
    assert_eq!(alloc.calls().last().unwrap().0, 429);
    assert_eq!(listed(&server).len(), n);
}

/// Path of a file that does not exist.
fn missing(dir: &Path) -> String {
    dir.join("no-such.pem").to_str().unwrap().to_owned()
}

#[test]
fn no_match_refused_or_untrusted_certificates_and_an_unreachable_allocator_are_clear_errors() {
    let certs = Certs::new();
    let alloc = Allocator::start(&fleet(&format!("127.0.0.1:{}", closed_port()), 8), Some(&certs));
    let with = |flags: &[(&str, &str)], selector: &str| {
        let mut a = strings(&["allocate", "--allocator", &alloc.url, "--namespace", "trainees", "--selector", selector]);
        for (f, v) in flags {
            a.push((*f).to_owned());
            a.push(if v.ends_with(".crt") || v.ends_with(".key") { certs.path(v) } else { (*v).to_owned() });
        }
        a
    };
    let client = [("--client-cert", "client.crt"), ("--client-key", "client.key"), ("--ca-cert", "ca.crt")];

    // No server carries the labels: the allocator's UnAllocated answer, named as such.
    fails(&with(&client, "agones.dev/fleet=nothing"), &["no needlesim server available", "[agones.dev/fleet=nothing]", "429"]);
    assert_eq!(alloc.calls().last().map(|c| c.0), Some(429));
    let n = alloc.calls().len();

    // A client certificate from a CA the allocator does not allow-list; none at all; an allocator
    // certificate the given CA did not sign: refused in the TLS handshake, before any request.
    let intruder = [("--client-cert", "intruder.crt"), ("--client-key", "intruder.key"), ("--ca-cert", "ca.crt")];
    fails(&with(&intruder, "agones.dev/fleet=needlesim"), &["refused the client certificate", "--client-cert"]);
    fails(&with(&[("--ca-cert", "ca.crt")], "agones.dev/fleet=needlesim"), &["requires a client certificate, none was given"]);
    let wrong_ca = [("--client-cert", "client.crt"), ("--client-key", "client.key"), ("--ca-cert", "rogue-ca.crt")];
    fails(&with(&wrong_ca, "agones.dev/fleet=needlesim"), &["does not trust", "UnknownIssuer", "--ca-cert"]);
    assert_eq!(alloc.calls().len(), n, "a request got through with bad certificates");

    // Files: missing, or not what the flag says.
    let mut args = with(&client, "agones.dev/fleet=needlesim");
    let at = args.iter().position(|a| a == "--client-cert").unwrap() + 1;
    args[at] = missing(certs.dir.path());
    fails(&args, &["--client-cert", "no-such.pem", "cannot read it"]);
    args[at] = certs.path("client.key");
    fails(&args, &["--client-cert", "no CERTIFICATE"]);
    args[at] = certs.path("intruder.crt");
    fails(&args, &["--client-key", "does not go with --client-cert"]);

    // Unreachable; malformed selectors and URLs; --allocate without an allocator.
    let mut args = with(&client, "agones.dev/fleet=needlesim");
    args[2] = format!("https://127.0.0.1:{}", closed_port());
    fails(&args, &["cannot reach the Agones allocator", "refused"]);
    fails(&with(&client, "fleet"), &["--selector", "not KEY=VALUE"]);
    fails(&with(&client, "Agones.Dev/fleet=x"), &["not a Kubernetes label key"]);
    let mut args = with(&client, "agones.dev/fleet=needlesim");
    args[2] = "allocator.example:443".into();
    fails(&args, &["--allocator", "no scheme"]);
    fails(&strings(&["sessions", "create", "--example", "paper-phantom", "--allocate"]), &["no allocator", "--allocator"]);
    fails(&strings(&["sessions", "create", "--example", "paper-phantom", "--selector", "a=b"]), &["--allocate"]);
    assert_eq!(alloc.calls().len(), n);
}

/// An allocator with TLS disabled (plain HTTP) and labels-only selection (`--no-counter`, for an
/// Agones without Counters): the request carries no Counter filter, and a Ready server is taken.
#[test]
fn a_plain_http_allocator_and_labels_only_selection() {
    let port = closed_port();
    let alloc = Allocator::start(&fleet(&format!("127.0.0.1:{port}"), 0), None);
    let args = strings(&["allocate", "--allocator", &alloc.url, "--namespace", "trainees", "--no-counter", "--json"]);
    let mut a = args.clone();
    a.extend(strings(&["--selector", "agones.dev/fleet=needlesim"]));
    // Capacity 0: with the Counter filter no server would match; labels alone take the Ready one.
    let v: Value = serde_json::from_str(&ok(&a)).unwrap();
    assert_eq!((v["port"].as_u64(), v["game_server"].as_str()), (Some(port as u64), Some("needlesim-7xk2p")), "{v}");
    assert_eq!(v["server"], format!("http://127.0.0.1:{port}"));
    let (_, body, _) = alloc.calls().pop().unwrap();
    assert_eq!(body, json!({"namespace": "trainees", "gameServerSelectors": [{"matchLabels": {FLEET: "needlesim"}}]}));
    // Now Allocated: a labels-only request (Ready servers) finds none.
    fails(&a, &["no needlesim server available"]);
    // Certificates make no sense over plain HTTP.
    let mut a = args;
    a.extend(strings(&["--ca-cert", "/dev/null"]));
    fails(&a, &["--ca-cert needs an https:// allocator URL"]);
}

/// The Agones Helm values a client's allocation needs (deploy/k8s/helm/agones-values.yaml): the
/// allocator installed with its REST API behind mTLS, a client certificate generated for the
/// fleet's namespace, Counters enabled; and the guide's allocation commands (docs/guide/fleet.md) use flags the CLI has.
#[test]
fn helm_values_and_readme_set_up_allocation_for_clients() {
    let values = repo_root().join("deploy/k8s/helm/agones-values.yaml");
    let script = "import json, sys, yaml\nprint(json.dumps(yaml.safe_load(open(sys.argv[1]))))";
    let out = run(Command::new(python()).args(["-c", script]).arg(&values));
    assert!(out.status.success(), "{}", text(&out).1);
    let v: Value = serde_json::from_str(&text(&out).0).unwrap();
    let a = &v["agones"]["allocator"];
    assert_eq!(a["install"], true);
    assert_eq!(a["service"]["http"]["enabled"], true, "the REST API the clients use");
    assert_eq!((a["disableMTLS"].as_bool(), a["disableTLS"].as_bool()), (Some(false), Some(false)));
    assert_eq!(a["generateClientTLS"], true, "the allocator-client.default secret");
    assert!(v["agones"]["featureGates"].as_str().unwrap_or_default().contains("CountsAndLists=true"));
    let fleet = std::fs::read_to_string(repo_root().join("deploy/k8s/fleet.yaml")).unwrap();
    assert!(fleet.contains("counters:\n        sessions:"), "the Fleet declares the sessions Counter the allocation asks for");
    let ns: Vec<&str> = v["gameservers"]["namespaces"].as_array().unwrap().iter().map(|x| x.as_str().unwrap()).collect();
    assert!(ns.contains(&"default"), "the fleet's namespace (the manifests carry none: default) gets a client certificate: {ns:?}");

    // The guide's "Running a fleet" (docs/guide/fleet.md): each `needlesim …` line's flags are the CLI's.
    let section = std::fs::read_to_string(repo_root().join("docs/guide/fleet.md")).unwrap();
    let mut checked = 0;
    for line in section.lines().map(str::trim).filter(|l| l.starts_with("needlesim ")) {
        let words: Vec<&str> = line.split('#').next().unwrap().split_whitespace().collect();
        let sub: Vec<String> = words[1..].iter().take_while(|w| !w.starts_with('-')).map(|w| (*w).to_owned()).collect();
        let mut help_args = sub.clone();
        help_args.push("--help".into());
        let help = ok(&help_args);
        for flag in words.iter().filter(|w| w.starts_with("--")) {
            let flag = flag.split('=').next().unwrap();
            assert!(help.contains(flag), "docs/guide/fleet.md: `{line}`: needlesim {} has no {flag}", sub.join(" "));
        }
        checked += 1;
    }
    assert!(checked >= 2, "docs/guide/fleet.md shows `needlesim allocate` and `sessions create --allocate` ({checked} lines)");
}
