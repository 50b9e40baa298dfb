//! The web viewer (web/): its committed build is what its sources build to, and the page served by
//! the real server works in headless Chromium (tests/web_e2e.mjs: create a session, see frames,
//! drive the needle with the mouse, see the depth and the drawing change, play a recording back).
//!
//! The sources type-check: `tsc --noEmit` (strict, web/tsconfig.json) passes, and rejects a type
//! error (so the check really covers web/src/); the plots' force histories pass their unit tests
//! (web/test/history.test.mjs under `node --test`).
//!
//! Needs Node with `npm ci` done in web/ (playwright-core, esbuild, buf, protoc-gen-es, typescript) and
//! Debian's Chromium at /usr/bin/chromium (or `NEEDLESIM_CHROMIUM`): tests/run installs both.

use std::path::{Path, PathBuf};
use std::process::Command;

use needlesim_tests::{ServerProcess, TempDir, repo_root, run, text};

fn web_dir() -> PathBuf {
    repo_root().join("web")
}

fn require_node_modules() {
    let nm = web_dir().join("node_modules");
    assert!(
        nm.join(".bin/esbuild").exists() && nm.join(".bin/tsc").exists() && nm.join("playwright-core").is_dir(),
        "{} is missing or incomplete: run `npm ci` in web/ (tests/run does it)",
        nm.display()
    );
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap_or_else(|e| panic!("cannot create {}: {e}", to.display()));
    for entry in std::fs::read_dir(from).unwrap_or_else(|e| panic!("cannot read {}: {e}", from.display())) {
        let entry = entry.unwrap();
        let (src, dst) = (entry.path(), to.join(entry.file_name()));
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&src, &dst);
        } else {
            std::fs::copy(&src, &dst).unwrap_or_else(|e| panic!("cannot copy {}: {e}", src.display()));
        }
    }
}

/// Every file under `dir`, as paths relative to it, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display())) {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                out.push(path.strip_prefix(root).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

#[test]
fn committed_assets_are_what_the_sources_build_to() {
    require_node_modules();
    let web = web_dir();
    let tmp = TempDir::new("web-build");
    let copy = tmp.join("web");
    // A copy of web/ without its generated code and build, beside a copy of proto/.
    copy_tree(&repo_root().join("proto/needlesim"), &tmp.join("proto/needlesim"));
    std::fs::create_dir_all(&copy).unwrap();
    for f in ["build.sh", "buf.gen.yaml", "package.json", "package-lock.json", "index.html", "tsconfig.json"] {
        std::fs::copy(web.join(f), copy.join(f)).unwrap_or_else(|e| panic!("cannot copy web/{f}: {e}"));
    }
    copy_tree(&web.join("src"), &copy.join("src"));
    std::fs::remove_dir_all(copy.join("src/gen")).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(web.join("node_modules"), copy.join("node_modules")).unwrap();

    let out = run(Command::new("bash").arg(copy.join("build.sh")));
    let (so, se) = text(&out);
    assert!(out.status.success(), "web/build.sh failed:\n{so}\n{se}");

    for sub in ["dist", "src/gen"] {
        let (committed, rebuilt) = (web.join(sub), copy.join(sub));
        let (a, b) = (files(&committed), files(&rebuilt));
        assert_eq!(a, b, "web/{sub} holds other files than a rebuild: run web/build.sh and commit the result");
        for f in &a {
            let (x, y) = (std::fs::read(committed.join(f)).unwrap(), std::fs::read(rebuilt.join(f)).unwrap());
            assert!(x == y, "web/{sub}/{} differs from a rebuild from web/src: run web/build.sh and commit the result", f.display());
        }
        println!("web/{sub}: {} files identical to a rebuild", a.len());
    }
}

/// Runs `tsc --noEmit -p tsconfig.json` in `dir` (a web/ or a copy of it).
fn type_check(dir: &Path) -> std::process::Output {
    run(Command::new(web_dir().join("node_modules/.bin/tsc")).args(["--noEmit", "-p", "tsconfig.json"]).current_dir(dir))
}

#[test]
fn sources_type_check_strictly() {
    require_node_modules();
    let web = web_dir();
    let config = std::fs::read_to_string(web.join("tsconfig.json")).expect("web/tsconfig.json");
    assert!(config.contains("\"strict\": true"), "web/tsconfig.json does not set \"strict\": true:\n{config}");
    let out = type_check(&web);
    let (so, se) = text(&out);
    assert!(out.status.success(), "tsc --noEmit found type errors in web/src:\n{so}\n{se}");

    // The same check on a copy of web/ with one type error added must fail and name it.
    let tmp = TempDir::new("web-tsc");
    let copy = tmp.join("web");
    std::fs::create_dir_all(&copy).unwrap();
    std::fs::copy(web.join("tsconfig.json"), copy.join("tsconfig.json")).unwrap();
    copy_tree(&web.join("src"), &copy.join("src"));
    #[cfg(unix)]
    std::os::unix::fs::symlink(web.join("node_modules"), copy.join("node_modules")).unwrap();
    std::fs::write(
        copy.join("src/type_error_probe.ts"),
        "//! Not a number.\nimport type { Frame } from \"./gen/needlesim/v1/needlesim_pb\";\nexport const depthM = (f: Frame): number => f.targets;\n",
    )
    .unwrap();
    let out = type_check(&copy);
    let (so, se) = text(&out);
    assert!(!out.status.success(), "tsc --noEmit accepted a type error in src/type_error_probe.ts:\n{so}\n{se}");
    assert!(so.contains("type_error_probe.ts"), "tsc did not name the file with the type error:\n{so}\n{se}");
}

/// The plots' data, bundled by esbuild and tested under `node --test` by web/test/*.test.mjs:
/// web/src/history.ts (the bounded ring against time, the thinned trace against depth) and
/// web/src/ranges.ts (value ranges, zeros of both axes aligned).
#[test]
fn plot_data_stays_bounded_ordered_and_ranged() {
    require_node_modules();
    let web = web_dir();
    let tmp = TempDir::new("web-unit");
    let out = run(Command::new(web.join("node_modules/.bin/esbuild"))
        .args([web.join("src/history.ts"), web.join("src/ranges.ts")])
        .args(["--bundle", "--format=esm", "--platform=neutral", "--log-level=warning", "--out-extension:.js=.mjs"])
        .arg(format!("--outdir={}", tmp.join("").display())));
    let (so, se) = text(&out);
    assert!(out.status.success(), "esbuild could not bundle web/src/history.ts and ranges.ts:\n{so}\n{se}");
    let mut tests = Vec::new();
    for name in ["history.test.mjs", "ranges.test.mjs"] {
        std::fs::copy(web.join("test").join(name), tmp.join(name)).unwrap_or_else(|e| panic!("web/test/{name}: {e}"));
        tests.push(tmp.join(name));
    }
    let out = run(Command::new("node").arg("--test").args(&tests));
    let (so, se) = text(&out);
    println!("{so}");
    assert!(out.status.success(), "web/test/*.test.mjs failed:\n{so}\n{se}");
    assert!(so.contains("# pass 8") && so.contains("# fail 0"), "web/test/*.test.mjs did not run their 8 tests:\n{so}");
}

/// Runs a page script (`node SCRIPT URL OUT_DIR`) in headless Chromium against a real server
/// serving web/, after removing the screenshots and summary it writes (in
/// target/web-screenshots); fails with the script's output and the server's log; returns the
/// screenshot directory and the parsed summary.
fn run_page_script(script: &str, screenshots: &[&str], summary: &str) -> (PathBuf, serde_json::Value) {
    let _turn = needlesim_tests::REALTIME.blocking_lock();
    require_node_modules();
    let chromium = std::env::var("NEEDLESIM_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".to_owned());
    assert!(
        Path::new(&chromium).exists(),
        "no Chromium at {chromium}: apt-get install chromium (tests/run does it), or set NEEDLESIM_CHROMIUM"
    );
    let web = web_dir();
    let server = ServerProcess::start(&["--default-scene", "none", "--web-dir", web.to_str().unwrap()]);
    let shots = repo_root().join("target/web-screenshots");
    for f in screenshots.iter().chain([&summary]) {
        let _ = std::fs::remove_file(shots.join(f));
    }
    let out = run(Command::new("node").arg(repo_root().join(script)).arg(server.url()).arg(&shots).env("NEEDLESIM_CHROMIUM", &chromium));
    let (so, se) = text(&out);
    println!("{so}");
    assert!(out.status.success(), "{script} failed:\n{so}\n{se}\nserver log:\n{}", server.stderr.lock().unwrap());
    let summary = needlesim_tests::read_json(&shots.join(summary));
    (shots, summary)
}

#[test]
fn page_drives_the_needle_in_headless_chromium() {
    let (shots, summary) = run_page_script(
        "tests/web_e2e.mjs",
        &["view-before.png", "view-after.png", "plots.png", "page.png", "playback.png"],
        "summary.json",
    );
    let f = |k: &str| summary[k].as_f64().unwrap_or_else(|| panic!("summary.json has no number `{k}`: {summary}"));
    assert!(f("frames") >= 10.0, "too few frames: {summary}");
    assert!(f("poses") >= 1.0, "no pose was sent: {summary}");
    assert!(f("depth1") > f("depth0") + 0.01, "the drag did not insert the needle: {summary}");
    assert!(f("playbackFrames") > 10.0, "the recording did not play back: {summary}");
    assert_eq!(summary["plotsChanged"], true, "the force plots did not change as the needle advanced: {summary}");

    let read = |name: &str| std::fs::read(shots.join(name)).unwrap_or_else(|e| panic!("no screenshot {name}: {e}"));
    let (before, after) = (read("view-before.png"), read("view-after.png"));
    for (name, png) in [
        ("view-before.png", &before),
        ("view-after.png", &after),
        ("plots.png", &read("plots.png")),
        ("page.png", &read("page.png")),
        ("playback.png", &read("playback.png")),
    ] {
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 5000, "{name} is not a real screenshot ({} bytes)", png.len());
    }
    assert_ne!(before, after, "the tissue view did not change as the needle advanced");
    println!("screenshots in {}", shots.display());
}

/// Issue 17 (3D in the browser): a live 3D session (cube-phantom-3d) in the page's three.js view —
/// the tissue drawn, the mouse drives the needle in (depth grows, the picture changes), the
/// section plane changes the picture, and the drive's recording plays back in 3D
/// (tests/web3d_e2e.mjs; WebGL through SwiftShader).
#[test]
fn issue_17_page_shows_and_drives_a_3d_session_in_headless_chromium() {
    let (shots, summary) = run_page_script(
        "tests/web3d_e2e.mjs",
        &["view3-before.png", "view3-after.png", "view3-section.png", "page3.png", "playback3-first.png", "playback3-last.png"],
        "summary3.json",
    );
    let f = |k: &str| summary[k].as_f64().unwrap_or_else(|| panic!("summary3.json has no number `{k}`: {summary}"));
    assert!(f("frames") >= 10.0, "too few frames: {summary}");
    assert!(f("poses") >= 1.0, "no 3D pose was sent: {summary}");
    // The cube fills a good part of the view; a blank or failed WebGL canvas would be white.
    assert!(f("drawnShare") > 0.05, "the tissue is not drawn: {summary}");
    assert!(f("depth1") > f("depth0") + 0.015, "the drag did not insert the needle: {summary}");
    assert_eq!(summary["changedByInsertion"], true, "the picture did not change as the needle went in: {summary}");
    assert_eq!(summary["changedBySection"], true, "the section plane did not change the picture: {summary}");
    // The drive's recording plays back in 3D on the recording's own surface, deformed by the
    // fields it carries (10 a second), from the start of the drive to its depth.
    assert_eq!(f("playbackDim"), 3.0, "the recording did not play back in 3D: {summary}");
    assert!(f("playbackFrames") > 10.0, "too few frames played back: {summary}");
    assert!(f("playbackFields") >= 1.0, "the recording carries no displacement field: {summary}");
    assert!(f("playbackDepth1") > f("playbackDepth0") + 0.015, "the playback does not go from the start to the depth: {summary}");
    assert_eq!(summary["playbackChanged"], true, "the first and last played-back frames look the same: {summary}");
    for name in ["view3-before.png", "view3-after.png", "view3-section.png", "page3.png", "playback3-first.png", "playback3-last.png"] {
        let png = std::fs::read(shots.join(name)).unwrap_or_else(|e| panic!("no screenshot {name}: {e}"));
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 5000, "{name} is not a real screenshot ({} bytes)", png.len());
    }
}

/// A raw HTTP/1.1 exchange (`Connection: close`) of `method path` on loopback: the path is sent as
/// written (no client normalises `..` away); returns the status code and the whole answer.
fn http1(addr: &str, method: &str, path: &str) -> (u16, String) {
    use std::io::{Read, Write};
    let mut s = std::net::TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(std::time::Duration::from_secs(20))).unwrap();
    s.write_all(format!("{method} {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n").as_bytes()).unwrap();
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let text = String::from_utf8_lossy(&out).into_owned();
    let code =
        text.split_whitespace().nth(1).and_then(|c| c.parse().ok()).unwrap_or_else(|| panic!("{method} {path}: no status: {text:?}"));
    (code, text)
}

/// Issue 35: the server serves the viewer's built page and nothing else of its `--web-dir`: `/`
/// (index.html) and dist/app.js, dist/app.css with their types; the sources, README.md,
/// package.json, the tests, a symbolic link inside dist/ (to a file outside), other methods and
/// paths that try to leave the folder (`..`, `%2e%2e`, `//`) are 404 (were: 200 for README.md,
/// package.json, src/, test/ and the link). Needs no Node.
#[test]
fn issue_35_only_the_viewer_s_built_files_are_served() {
    let web = web_dir();
    let tmp = TempDir::new("web-served");
    let dir = tmp.join("web");
    copy_tree(&web.join("dist"), &dir.join("dist"));
    for f in ["index.html", "README.md", "package.json", "build.sh", "tsconfig.json"] {
        std::fs::copy(web.join(f), dir.join(f)).unwrap_or_else(|e| panic!("cannot copy web/{f}: {e}"));
    }
    copy_tree(&web.join("test"), &dir.join("test"));
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::copy(web.join("src/main.ts"), dir.join("src/main.ts")).unwrap();
    std::fs::write(tmp.join("secret.txt"), "SECRET-OUTSIDE-WEB").unwrap();
    std::os::unix::fs::symlink(tmp.join("secret.txt"), dir.join("dist/secret.js")).unwrap();
    std::os::unix::fs::symlink(tmp.join("secret.txt"), dir.join("dist/secret.css")).unwrap();
    let server = ServerProcess::start(&["--default-scene", "none", "--web-dir", dir.to_str().unwrap()]);

    let (code, page) = http1(&server.addr, "GET", "/?session=abc&token=def");
    assert_eq!(code, 200, "{page}");
    assert!(page.to_ascii_lowercase().contains("content-type: text/html") && page.contains("dist/app.js"), "{page}");
    let (code, index) = http1(&server.addr, "GET", "/index.html");
    assert_eq!(code, 200, "{index}");
    for (path, ty, file) in [("/dist/app.js", "text/javascript", "dist/app.js"), ("/dist/app.css", "text/css", "dist/app.css")] {
        let (code, text) = http1(&server.addr, "GET", path);
        assert_eq!(code, 200, "{path}: {}", &text[..text.len().min(300)]);
        assert!(text.to_ascii_lowercase().contains(&format!("content-type: {ty}")), "{path}: {}", &text[..300]);
        let len = std::fs::metadata(web.join(file)).unwrap().len();
        assert!(text.to_ascii_lowercase().contains(&format!("content-length: {len}")), "{path}: {}", &text[..300]);
    }
    let (code, head) = http1(&server.addr, "HEAD", "/dist/app.js");
    assert_eq!(code, 200, "{head}");

    for path in [
        "/README.md",
        "/package.json",
        "/build.sh",
        "/tsconfig.json",
        "/src/main.ts",
        "/test/history.test.mjs",
        "/dist/secret.js",
        "/dist/secret.css",
        "/dist/",
        "/dist",
        "/dist/../README.md",
        "/../secret.txt",
        "/dist/../../secret.txt",
        "/%2e%2e/secret.txt",
        "/dist/%2e%2e/%2e%2e/secret.txt",
        "/dist/..%2f..%2fsecret.txt",
        "/%2fetc%2fpasswd",
        "//etc/passwd",
        "/dist//etc/passwd",
        "/dist/app.js/",
        "/index.html/..",
        "/nope.html",
    ] {
        let (code, text) = http1(&server.addr, "GET", path);
        assert_eq!(code, 404, "GET {path}: {text}");
        assert!(!text.contains("SECRET-OUTSIDE-WEB") && !text.contains("\"name\": \"needlesim-web\""), "GET {path}: {text}");
    }
    let (code, text) = http1(&server.addr, "POST", "/index.html");
    assert_eq!(code, 405, "POST /index.html: {text}");
    let (code, text) = http1(&server.addr, "DELETE", "/README.md");
    assert_eq!(code, 404, "DELETE /README.md: {text}");
}
