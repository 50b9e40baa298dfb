//! The README's five-minute tour, run as written (issue 33): its CLI lines against a real
//! `--demo` server, its Python snippet in the test venv, its exercise commands; so the tour a
//! newcomer copies cannot drift from the binaries. Only what cannot end by itself is bounded
//! (`watch` gets `--ticks`), and the relative paths are read from the repository's root.

use std::process::Command;
use std::time::Duration;

use needlesim_tests::{ServerProcess, TempDir, bin, python, repo_root, run_within, text};

/// The tour: the README's text from its heading to the next `## ` heading.
fn tour_section() -> String {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).expect("README.md");
    let start = readme.find("## A five-minute tour").expect("the README has `## A five-minute tour`");
    let rest = &readme[start + 3..];
    let end = rest.find("\n## ").map_or(rest.len(), |e| e);
    rest[..end].to_owned()
}

/// The fenced blocks of `text` with the given language, each block's lines without their
/// indentation.
fn fenced(text: &str, lang: &str) -> Vec<Vec<String>> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<String>> = None;
    for line in text.lines() {
        let t = line.trim();
        match (&mut current, t.strip_prefix("```")) {
            (None, Some(l)) if l == lang => current = Some(Vec::new()),
            (Some(_), Some("")) => blocks.extend(current.take()),
            (Some(b), None) => b.push(t.to_owned()),
            _ => {}
        }
    }
    blocks
}

/// The inline code spans of `text` (lines joined, so a span may wrap) that start with `prefix`.
fn inline_commands(text: &str, prefix: &str) -> Vec<String> {
    let joined = text.lines().map(str::trim).collect::<Vec<_>>().join(" ");
    joined.split('`').skip(1).step_by(2).filter(|s| s.starts_with(prefix)).map(str::to_owned).collect()
}

/// A command line's words, its `# comment` removed; arguments that name a file of the
/// repository made absolute (the tour is run from the repository's root).
fn words(line: &str) -> Vec<String> {
    let code = line.split(" #").next().unwrap_or_default();
    code.split_whitespace()
        .map(|w| {
            let in_repo = repo_root().join(w);
            if w.contains('/') && in_repo.exists() { in_repo.display().to_string() } else { w.to_owned() }
        })
        .collect()
}

fn value_after<'a>(out: &'a str, label: &str) -> &'a str {
    out.lines().find_map(|l| l.strip_prefix(label)).map(str::trim).unwrap_or_else(|| panic!("no `{label}` line in:\n{out}"))
}

fn run_ok(cmd: &mut Command, what: &str, limit: Duration) -> String {
    let out = run_within(cmd, limit);
    let (o, e) = text(&out);
    assert!(out.status.success(), "the tour's `{what}` failed ({}):\nstdout: {o}\nstderr: {e}", out.status);
    assert!(!e.contains("panicked"), "the tour's `{what}` panicked:\n{e}");
    o
}

#[test]
fn issue_33_the_readmes_tour_runs_as_written() {
    let _turn = needlesim_tests::REALTIME.blocking_lock();
    let tour = tour_section();
    let work = TempDir::new("tour");
    assert!(tour.contains("cargo run --release -p needlesim-server -- --demo"), "the tour starts from the demo:\n{tour}");
    let server = ServerProcess::start(&["--demo"]);
    let url = server.url();

    // 2. The CLI block, line by line, in order; ID and the tokens from `sessions create`.
    let cli: Vec<String> = fenced(&tour, "sh").concat();
    assert!(cli.len() >= 4 && cli.iter().all(|l| l.starts_with("needlesim ")), "the tour's CLI block: {cli:?}");
    let (mut id, mut controller, mut observer) = (String::new(), String::new(), String::new());
    let mut ran = Vec::new();
    for line in &cli {
        let mut args: Vec<String> = words(line)[1..]
            .iter()
            .map(|w| match w.as_str() {
                "ID" => id.clone(),
                "CONTROLLER" => controller.clone(),
                "OBSERVER" => observer.clone(),
                _ => w.clone(),
            })
            .collect();
        let sub = args.iter().find(|a| !a.starts_with('-') && !a.chars().all(|c| c.is_ascii_hexdigit())).cloned().unwrap_or_default();
        if sub == "watch" {
            args.extend(["--ticks".to_owned(), "3".to_owned()]);
        }
        let mut cmd = Command::new(bin("needlesim"));
        cmd.arg("--server").arg(&url).args(&args).current_dir(work.path()).env_remove("NEEDLESIM_SERVER").env_remove("NEEDLESIM_TOKEN");
        let out = run_ok(&mut cmd, line, Duration::from_secs(120));
        match sub.as_str() {
            "sessions" => {
                id = value_after(&out, "session").to_owned();
                controller = value_after(&out, "controller token").to_owned();
                observer = value_after(&out, "observer token").to_owned();
                assert!(!id.is_empty() && controller.len() >= 16 && observer.len() >= 16 && controller != observer, "{out}");
            }
            "watch" => {
                let frames: Vec<&str> = out.lines().filter(|l| l.starts_with("tick=")).collect();
                assert_eq!(frames.len(), 3, "watch --ticks 3 prints three frames:\n{out}");
            }
            "drive" => {
                assert!(out.contains("final depth"), "drive prints its summary:\n{out}");
                assert!(out.contains("final force    axial"), "{out}");
            }
            "simulate" => {
                let csv_name = args.iter().skip_while(|a| *a != "-o").nth(1).expect("simulate -o FILE");
                let csv = std::fs::read_to_string(work.join(csv_name)).expect("simulate wrote its CSV");
                assert!(csv.lines().next().is_some_and(|h| h.starts_with("t_s,")), "a CSV with a header");
                assert!(csv.lines().count() > 100, "a time series: {} lines", csv.lines().count());
            }
            other => panic!("the tour runs `needlesim {other}`, which this test does not know how to check: {line}"),
        }
        ran.push(sub);
    }
    for sub in ["sessions", "watch", "drive", "simulate"] {
        assert!(ran.iter().any(|r| r == sub), "the tour shows `needlesim {sub}`: {cli:?}");
    }

    // 3. The Python snippet, as written.
    let snippets = fenced(&tour, "python");
    assert_eq!(snippets.len(), 1, "one Python snippet in the tour");
    let py = run_ok(
        Command::new(python()).arg("-c").arg(snippets[0].join("\n")).current_dir(work.path()),
        "the Python snippet",
        Duration::from_secs(120),
    );
    assert!(py.trim_start().starts_with('('), "it prints the force array's shape, then the closest distance: {py}");

    // 4. The exercise: served (three URLs), and run offline to a report.
    let exercise = inline_commands(&tour, "needlesim-server ");
    let serve = exercise.iter().find(|c| c.contains(" serve ")).expect("the tour serves an exercise");
    let serve_args = words(serve);
    assert_eq!(serve_args[1], "serve", "{serve}");
    let ex_server = ServerProcess::start(&serve_args[2..].iter().map(String::as_str).collect::<Vec<_>>());
    let deadline = std::time::Instant::now() + Duration::from_secs(60);
    let urls = loop {
        let out = ex_server.stdout.lock().unwrap().clone();
        if ["trainee:", "instructor:", "observers:"].iter().all(|k| out.contains(k)) || std::time::Instant::now() > deadline {
            break out;
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    for role in ["trainee:", "instructor:", "observers:"] {
        let link = value_after(urls.lines().map(str::trim).find(|l| l.starts_with(role)).unwrap_or_default(), role);
        assert!(link.starts_with(&format!("{}/?session=", ex_server.url())), "the {role} URL: {urls}");
    }
    let offline = exercise.iter().find(|c| c.contains(" exercise run ")).expect("the tour runs an exercise offline");
    let offline_args = words(offline);
    run_ok(Command::new(bin("needlesim-server")).args(&offline_args[1..]).current_dir(work.path()), offline, Duration::from_secs(300));
    let report_name = offline_args.iter().skip_while(|a| *a != "-o").nth(1).expect("exercise run -o FILE");
    let report = std::fs::read_to_string(work.join(report_name)).expect("exercise run wrote its report");
    assert!(report.contains("<html") && report.contains("spare-3d"), "an HTML report of the exercise");
    drop(server);
}
