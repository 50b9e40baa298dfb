//! Issue 9, the fits: `needlesim-lab identify synth|probe|needle` through the real binary
//! (E and ν from synthetic probing, the needle force distribution from a synthetic insertion,
//! the round trip through a fitted scene, the input errors) and the gRPC IdentifyService through a
//! real server process.

use std::path::Path;
use std::process::Command;

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, bin, connect, run, text};

/// Runs `needlesim-lab identify ARGS…`, asserts success, returns stdout as JSON.
fn identify(args: &[&str]) -> serde_json::Value {
    let out = run(Command::new(bin("needlesim-lab")).arg("identify").args(args));
    let (o, e) = text(&out);
    assert!(out.status.success(), "identify {args:?} failed:\n{e}");
    serde_json::from_str(&o).unwrap_or_else(|err| panic!("identify {args:?}: not JSON ({err}):\n{o}"))
}

/// Runs `needlesim-lab identify ARGS…`, asserts failure, returns stderr.
fn identify_err(args: &[&str]) -> String {
    let out = run(Command::new(bin("needlesim-lab")).arg("identify").args(args));
    let (o, e) = text(&out);
    assert!(!out.status.success(), "identify {args:?} should fail, printed:\n{o}");
    e
}

fn p(path: &Path) -> &str {
    path.to_str().expect("utf-8 temp path")
}

fn f(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// Base forces of a force log CSV.
/// `identify probe` on the probe-tracks.csv and probe-log.csv that `identify synth probe` wrote
/// into `dir`, against the phantom model `model` (`--grid …` or `--scene …`).
fn fit_probe(dir: &Path, model: &[&str]) -> serde_json::Value {
    let (tracks, log) = (dir.join("probe-tracks.csv"), dir.join("probe-log.csv"));
    identify(&[&["probe", "--tracks", p(&tracks), "--probe-log", p(&log)][..], model].concat())
}

/// A CSV log (time in the first column, a header line) with every time shifted by `dt_s`.
fn shift_times(path: &Path, dt_s: f64) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut out = vec![lines.next().unwrap().to_owned()];
    for l in lines {
        let (t, rest) = l.split_once(',').unwrap();
        out.push(format!("{},{rest}", t.parse::<f64>().unwrap() + dt_s));
    }
    out.join("\n")
}

fn forces(path: &Path) -> Vec<(f64, [f64; 2])> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (c[0], [c[1], c[2]])
        })
        .collect()
}

#[test]
fn probing_with_one_percent_noise_recovers_e_within_2_percent_and_nu_within_0_02() {
    let dir = TempDir::new("identify-probe");
    let synth = identify(&["synth", "probe", "--young-modulus-pa", "25000", "--poisson-ratio", "0.42", "--out", p(dir.path())]);
    let grid = synth["grid_arg"].as_str().unwrap().to_owned();
    // The synthetic experiment is the FEM on the markers' own grid: the model is that mesh
    // (`--refine 1`), so that only noise separates model and data and the stated uncertainties
    // can be checked (the default twice-refined model adds a discretisation difference, +1.8 %
    // in E here, which no noise-based σ covers; data from a finer independent FEM: issue 19's test).
    let fit = fit_probe(dir.path(), &["--grid", &grid, "--refine", "1"]);
    let (e, se, nu, snu) =
        (f(&fit, "young_modulus_pa"), f(&fit, "young_modulus_sigma_pa"), f(&fit, "poisson_ratio"), f(&fit, "poisson_ratio_sigma"));
    eprintln!("E = {e:.1} ± {se:.1} Pa (truth 25000), ν = {nu:.4} ± {snu:.4} (truth 0.42), {fit}");
    assert!((e / 25e3 - 1.0).abs() < 0.02, "E = {e}");
    assert!((nu - 0.42).abs() < 0.02, "ν = {nu}");
    // The stated uncertainties are honest: the errors are within a few standard deviations.
    assert!(se > 0.0 && snu > 0.0 && (e - 25e3).abs() < 5.0 * se + 1.0 && (nu - 0.42).abs() < 5.0 * snu + 1e-4, "{fit}");
    assert_eq!(fit["probe_marker"], synth["probe_marker"]);
    // 1 % noise on the markers too: 0.25 px at 5000 px/m is 50 µm, 1 % of the 5 mm probe
    // displacement (over seeds 1–6: |ΔE| ≤ 0.3 %, |Δν| ≤ 0.0102 with σ_ν ≈ 0.0067).
    let noisy = dir.join("noisy");
    let args = ["synth", "probe", "--young-modulus-pa", "25000", "--poisson-ratio", "0.42", "--marker-noise-px", "0.25"];
    identify(&[&args[..], &["--out", p(&noisy)]].concat());
    let fit = fit_probe(&noisy, &["--grid", &grid]);
    let (e, nu, snu) = (f(&fit, "young_modulus_pa"), f(&fit, "poisson_ratio"), f(&fit, "poisson_ratio_sigma"));
    eprintln!("1 % marker noise: E = {e:.1} Pa (truth 25000), ν = {nu:.4} ± {snu:.4} (truth 0.42)");
    assert!((e / 25e3 - 1.0).abs() < 0.02 && (nu - 0.42).abs() < 0.02, "{fit}");
    // Sparse markers (every third node of a 19 × 19 phantom) registered to a scene's finer mesh:
    // the model keeps the phantom's resolution, the markers are a subset of its nodes.
    let sparse = dir.join("sparse");
    identify(&["synth", "probe", "--nx", "19", "--ny", "19", "--marker-stride", "3", "--out", p(&sparse)]);
    let fit = fit_probe(&sparse, &["--scene", "paper-phantom"]);
    let (e, nu) = (f(&fit, "young_modulus_pa"), f(&fit, "poisson_ratio"));
    eprintln!("49 markers on the paper-phantom mesh: E = {e:.1} Pa (truth 30000), ν = {nu:.4} (truth 0.45)");
    assert!((e / 30e3 - 1.0).abs() < 0.02 && (nu - 0.45).abs() < 0.02, "{fit}");
}

/// Issue 19: probing data from the independent reference FEM (scikit-fem, fem_ref.py) on a mesh
/// 4× finer than the markers, with 0.1 px marker noise and 1 % force noise, fitted as the README
/// shows it (`--grid`): E within 2 % and ν within 0.02. (Before the fit applied the measured
/// force as the model's load, the probe displacement drove a model on the markers' grid and this
/// data gave E 29 % low and ν 0.05 low: a point probe's force depends on the mesh.)
#[test]
fn issue_19_probe_data_from_an_independent_fem_4x_finer_gives_e_within_2_percent() {
    let dir = TempDir::new("identify-probe-ref");
    for (seed, e_true, nu_true) in [(1, 30e3, 0.45), (2, 25e3, 0.42), (3, 40e3, 0.3)] {
        let out = dir.join(&format!("seed{seed}"));
        let status = std::process::Command::new(needlesim_tests::python())
            .arg(needlesim_tests::repo_root().join("tests/support/probe_fem_ref.py"))
            .arg("--fem-ref")
            .arg(needlesim_tests::validation_dir().join("fem_ref.py"))
            .args(["--refine", "4", "--marker-noise-px", "0.1", "--force-noise-rel", "0.01"])
            .args(["--young-modulus-pa", &e_true.to_string(), "--poisson-ratio", &nu_true.to_string(), "--seed", &seed.to_string()])
            .arg("--out")
            .arg(&out)
            .stdout(std::process::Stdio::null())
            .status()
            .expect("run probe_fem_ref.py");
        assert!(status.success(), "probe_fem_ref.py failed");
        let truth: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("truth.json")).unwrap()).unwrap();
        let grid = truth["grid_arg"].as_str().unwrap().to_owned();
        let fit = fit_probe(&out, &["--grid", &grid]);
        let (e, nu) = (f(&fit, "young_modulus_pa"), f(&fit, "poisson_ratio"));
        eprintln!(
            "reference FEM 4x finer, seed {seed}: E = {e:.1} Pa (truth {e_true}, {:+.2} %), ν = {nu:.4} (truth {nu_true})",
            100.0 * (e / e_true - 1.0)
        );
        assert!((e / e_true - 1.0).abs() < 0.02, "E = {e} against {e_true}: {fit}");
        assert!((nu - nu_true).abs() < 0.02, "ν = {nu} against {nu_true}: {fit}");
        assert_eq!(fit["probe_marker"], truth["probe_marker"], "the probed marker found");
    }
}

#[test]
fn rendered_images_tracked_and_fitted_give_e_and_nu() {
    // The whole pipeline: synthetic probing → marker images (blur 1 px, noise 3 gray levels) →
    // tracking → E and ν. The nominal camera puts tissue (0, 0) at pixel (20, 520).
    let dir = TempDir::new("identify-pipeline");
    identify(&["synth", "probe", "--marker-noise-px", "0", "--out", p(dir.path())]);
    let img = dir.join("img");
    let out = run(Command::new(bin("needlesim-lab"))
        .args(["identify", "render", "--tracks"])
        .arg(dir.join("probe-tracks.csv"))
        .arg("--out-dir")
        .arg(&img)
        .args(["--width", "560", "--height", "560"]));
    assert!(out.status.success(), "{}", text(&out).1);
    let tracked = dir.join("tracked.csv");
    let out = run(Command::new(bin("needlesim-lab"))
        .args(["identify", "track", "--images"])
        .arg(&img)
        .args(["--dark", "--m-per-px", "0.0002", "--origin-px", "20,520", "--origin-m", "0,0", "--expected", "121", "-o"])
        .arg(&tracked));
    assert!(out.status.success(), "{}", text(&out).1);
    let fit = identify(&["probe", "--tracks", p(&tracked), "--probe-log", p(&dir.join("probe-log.csv")), "--grid", "11,11,0.1,0.1"]);
    let (e, nu) = (f(&fit, "young_modulus_pa"), f(&fit, "poisson_ratio"));
    eprintln!("from images: E = {e:.1} Pa (truth 30000), ν = {nu:.4} (truth 0.45), {fit}");
    assert!((e / 30e3 - 1.0).abs() < 0.02 && (nu - 0.45).abs() < 0.02, "{fit}");
}

#[test]
fn insertion_fit_recovers_friction_within_5_percent_and_the_peak_within_one_element() {
    let dir = TempDir::new("identify-needle");
    identify(&["synth", "needle", "--scene", "paper-phantom", "--t-end-s", "4", "--out", p(dir.path())]);
    let (tracks, log) = (dir.join("needle-tracks.csv"), dir.join("needle-force.csv"));
    let args = ["needle", "--tracks", p(&tracks), "--force-log", p(&log), "--scene", "paper-phantom"];
    // Truth (paper-phantom.toml): q0 = 10 N/m, h = 0.3, w = 5 mm; peak position w/2 = 2.5 mm.
    for extra in [&[][..], &["--tip-peak-ratio", "0.3"][..]] {
        let fit = identify(&[&args[..], extra].concat());
        let (q0, pos, edge) = (f(&fit, "friction_n_per_m"), f(&fit, "peak_position_m"), f(&fit, "mean_element_edge_m"));
        eprintln!("{extra:?}: q0 = {q0:.4} N/m (truth 10), peak position {:.3} mm (truth 2.5 mm), {fit}", pos * 1e3);
        assert!((q0 / 10.0 - 1.0).abs() < 0.05, "q0 = {q0}");
        assert!((pos - 0.0025).abs() < edge, "peak position {pos} m, element {edge} m");
        // The nodal forces add up to the measured base force (within a few per cent of it).
        assert!(f(&fit, "base_force_rms_diff_n") < 0.05 * f(&fit, "base_force_rms_n"), "{fit}");
    }
}

#[test]
fn issue_9_identified_parameters_reproduce_the_experiment() {
    let dir = TempDir::new("identify-roundtrip");
    let exp = dir.join("experiment");
    // The experiment: the paper-phantom insertion, hold and withdrawal, 1 % force noise.
    let synth = identify(&["synth", "needle", "--scene", "paper-phantom", "--out", p(&exp)]);
    let sigma = f(&synth, "force_sigma_n");
    let fitted = dir.join("fitted.toml");
    let fit = identify(&[
        "needle",
        "--tracks",
        p(&exp.join("needle-tracks.csv")),
        "--force-log",
        p(&exp.join("needle-force.csv")),
        "--scene",
        "paper-phantom",
        "--scene-out",
        p(&fitted),
    ]);
    let scene = std::fs::read_to_string(&fitted).unwrap();
    assert!(scene.contains(&format!("friction_n_per_m = {}", f(&fit, "friction_n_per_m"))), "{scene}");
    // Re-simulate the fitted scene along the same trajectory without noise.
    let re = dir.join("resim");
    let tr = Path::new(env!("CARGO_MANIFEST_DIR")).join("../server/scenes/paper-phantom.csv");
    identify(&[
        "synth",
        "needle",
        "--scene",
        p(&fitted),
        "--trajectory",
        p(&tr),
        "--marker-noise-px",
        "0",
        "--force-noise-rel",
        "0",
        "--out",
        p(&re),
    ]);
    let (measured, simulated) = (forces(&exp.join("needle-force.csv")), forces(&re.join("needle-force.csv")));
    assert_eq!(measured.len(), simulated.len());
    let mut sq = 0.0;
    for (m, s) in measured.iter().zip(&simulated) {
        assert!((m.0 - s.0).abs() < 1e-9);
        sq += (m.1[0] - s.1[0]).powi(2) + (m.1[1] - s.1[1]).powi(2);
    }
    // Per component; noise alone gives sigma.
    let rms = (sq / (2 * measured.len()) as f64).sqrt();
    let peak = measured.iter().map(|m| m.1[1].abs()).fold(0.0, f64::max);
    eprintln!("round trip: base force RMS difference {rms:.5} N, noise sigma {sigma:.5} N, peak force {peak:.3} N; fit {fit}");
    assert!(rms < 1.25 * sigma, "re-simulated base forces differ by {rms} N RMS, noise {sigma} N");
}

#[test]
fn inconsistent_inputs_are_errors_naming_the_problem() {
    let dir = TempDir::new("identify-errors");
    identify(&["synth", "probe", "--out", p(dir.path())]);
    let (tracks, log) = (dir.join("probe-tracks.csv"), dir.join("probe-log.csv"));
    let base = ["probe", "--tracks", p(&tracks), "--probe-log", p(&log)];
    // Marker count changes: frame 2 loses its last marker.
    let text = std::fs::read_to_string(&tracks).unwrap();
    let cut: Vec<&str> = text.lines().filter(|l| !l.starts_with("2,") || l.split(',').nth(2).is_none_or(|m| m != "120")).collect();
    let bad = dir.join("lost-marker.csv");
    std::fs::write(&bad, cut.join("\n")).unwrap();
    let e = identify_err(&["probe", "--tracks", p(&bad), "--probe-log", p(&log), "--grid", "11,11,0.1,0.1"]);
    assert!(e.contains("frame 2 has 120 markers but frame 0 has 121"), "{e}");
    // A mesh that does not cover the markers: a 0.1 m phantom (markers 10 mm apart) against a
    // 0.05 m wide grid scene with the same spacing.
    let small = dir.join("small.toml");
    let scene = include_str!("../../server/scenes/paper-phantom.toml")
        .replace("nx = 19\nny = 19\nwidth_m = 0.1", "nx = 6\nny = 11\nwidth_m = 0.05");
    std::fs::write(&small, scene).unwrap();
    let e = identify_err(&[&base[..], &["--scene", p(&small)]].concat());
    assert!(e.contains("mesh does not cover marker 6 at (0.0"), "{e}");
    // The grid does not match the marker count.
    let e = identify_err(&[&base[..], &["--grid", "10,11,0.1,0.1"]].concat());
    assert!(e.contains("--grid: a grid of 10 × 11 markers has 110 nodes but the tracks have 121 markers"), "{e}");
    // Force and image time stamps that do not overlap.
    let shifted = dir.join("late-log.csv");
    std::fs::write(&shifted, shift_times(&log, 100.0)).unwrap();
    let e = identify_err(&["probe", "--tracks", p(&tracks), "--probe-log", p(&shifted), "--grid", "11,11,0.1,0.1"]);
    assert!(e.contains("probe log covers t = 100..102.5 s but frames cover 0..2.5 s"), "{e}");
    // Too few frames.
    let one: Vec<&str> = text.lines().filter(|l| l.starts_with("frame") || l.starts_with("0,")).collect();
    let single = dir.join("one-frame.csv");
    std::fs::write(&single, one.join("\n")).unwrap();
    let e = identify_err(&["probe", "--tracks", p(&single), "--probe-log", p(&log), "--grid", "11,11,0.1,0.1"]);
    assert!(e.contains("1 frame(s): the fit needs at least 2"), "{e}");
    // The needle fit: a force log from another time, and tracks that miss mesh nodes.
    let nd = dir.join("needle");
    identify(&["synth", "needle", "--t-end-s", "1", "--frame-rate-hz", "10", "--out", p(&nd)]);
    let late_force = dir.join("late-force.csv");
    std::fs::write(&late_force, shift_times(&nd.join("needle-force.csv"), 50.0)).unwrap();
    let nt = nd.join("needle-tracks.csv");
    let e = identify_err(&["needle", "--tracks", p(&nt), "--force-log", p(&late_force), "--scene", "paper-phantom"]);
    assert!(e.contains("force log covers t = 50..51 s but frames cover 0..1 s"), "{e}");
    let e = identify_err(&["needle", "--tracks", p(&tracks), "--force-log", p(&nd.join("needle-force.csv")), "--scene", "paper-phantom"]);
    assert!(e.contains("the tracks have 121 markers for 361 mesh nodes"), "{e}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn grpc_probe_and_needle_stream_progress_and_results() {
    let dir = TempDir::new("identify-grpc");
    identify(&["synth", "probe", "--out", p(dir.path())]);
    let tracks_csv = std::fs::read_to_string(dir.join("probe-tracks.csv")).unwrap();
    let probe_log_csv = std::fs::read_to_string(dir.join("probe-log.csv")).unwrap();
    let server = ServerProcess::start(&[]);
    let ch = connect(&server).await;
    let mut c = pb::identify_service_client::IdentifyServiceClient::new(ch);
    let grid = pb::GridSpec { nx: 11, ny: 11, width_m: 0.1, height_m: 0.1 };
    let req =
        pb::ProbeRequest { tracks_csv: tracks_csv.clone(), probe_log_csv: probe_log_csv.clone(), grid: Some(grid), ..Default::default() };
    let mut stream = c.probe(req).await.expect("probe call").into_inner();
    let (mut n_progress, mut result) = (0, None);
    while let Some(msg) = stream.message().await.expect("stream item") {
        match msg.result {
            Some(pb::identify_progress::Result::Probe(r)) => result = Some(r),
            Some(other) => panic!("unexpected result {other:?}"),
            None => {
                assert!(msg.done >= 1 && msg.stage == "probe", "{msg:?}");
                n_progress += 1;
            }
        }
    }
    let r = result.expect("a final result");
    assert!(n_progress >= 1, "no progress message");
    assert!((r.young_modulus_pa / 30e3 - 1.0).abs() < 0.02 && (r.poisson_ratio - 0.45).abs() < 0.02, "{r:?}");
    assert!(r.json.contains("\"young_modulus_sigma_pa\""));
    // Bad input: the status names the field.
    let bad = pb::ProbeRequest { tracks_csv: "x,y\n".into(), probe_log_csv, grid: Some(grid), ..Default::default() };
    let st = c.probe(bad).await.expect_err("bad tracks");
    assert_eq!(st.code(), tonic::Code::InvalidArgument);
    assert!(st.message().starts_with("tracks_csv: marker tracks: line 1 must be the header"), "{}", st.message());
    let none = pb::ProbeRequest { tracks_csv, probe_log_csv: String::new(), grid: Some(grid), ..Default::default() };
    let st = c.probe(none).await.expect_err("empty log");
    assert!(st.message().starts_with("probe_log_csv:"), "{}", st.message());
    // Track: rendered marker images in, marker tracks out.
    let img = dir.join("img");
    let out = run(Command::new(bin("needlesim-lab"))
        .args(["identify", "render", "--tracks"])
        .arg(dir.join("probe-tracks.csv"))
        .arg("--out-dir")
        .arg(&img)
        .args(["--width", "560", "--height", "560"]));
    assert!(out.status.success(), "{}", text(&out).1);
    let frames: Vec<pb::ImageFrame> = (0..6)
        .map(|k| pb::ImageFrame { t_s: 0.5 * k as f64, png: std::fs::read(img.join(format!("frame_{k:04}.png"))).unwrap() })
        .collect();
    let req = pb::TrackRequest { frames, m_per_px: 2e-4, origin_px: Some(pb::Vec2 { x: 20.0, y: 520.0 }), ..Default::default() };
    let mut stream = c.track(req).await.expect("track call").into_inner();
    let mut tracked = None;
    while let Some(msg) = stream.message().await.expect("stream item") {
        if let Some(pb::identify_progress::Result::Track(r)) = msg.result {
            tracked = Some(r);
        }
    }
    let t = tracked.expect("a track result");
    assert_eq!((t.n_markers, t.n_frames), (121, 6), "{t:?}");
    assert!(t.tracks_csv.starts_with("frame,t_s,marker,x_px,y_px,x_m,y_m,detected\n"));
    // Needle: a short insertion on the shipped phantom; the result carries the fitted scene.
    let nd = dir.join("needle");
    identify(&["synth", "needle", "--t-end-s", "3", "--frame-rate-hz", "10", "--out", p(&nd)]);
    let req = pb::NeedleRequest {
        tracks_csv: std::fs::read_to_string(nd.join("needle-tracks.csv")).unwrap(),
        force_log_csv: std::fs::read_to_string(nd.join("needle-force.csv")).unwrap(),
        scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
        ..Default::default()
    };
    let mut stream = c.needle(req.clone()).await.expect("needle call").into_inner();
    let mut result = None;
    while let Some(msg) = stream.message().await.expect("stream item") {
        if let Some(pb::identify_progress::Result::Needle(r)) = msg.result {
            result = Some(r);
        }
    }
    let r = result.expect("a needle result");
    assert!((r.friction_n_per_m / 10.0 - 1.0).abs() < 0.05, "{r:?}");
    assert!(r.fitted_scene_toml.contains(&format!("friction_n_per_m = {}", r.friction_n_per_m)), "{}", r.fitted_scene_toml);
    // Time stamps that do not overlap end the stream with INVALID_ARGUMENT.
    let late = pb::NeedleRequest { force_log_csv: "t_s,force_x_n,force_y_n,depth_m\n100,0,0,0\n101,0,0,0\n".into(), ..req };
    let mut stream = c.needle(late).await.expect("needle call").into_inner();
    let st = loop {
        match stream.message().await {
            Ok(Some(_)) => continue,
            Ok(None) => panic!("the stream ended without an error"),
            Err(st) => break st,
        }
    };
    assert_eq!(st.code(), tonic::Code::InvalidArgument);
    assert!(st.message().contains("force log covers t = 100..101 s but frames cover 0.."), "{}", st.message());
}
