//! The training layer's scripted runs (issue 20): each shipped exercise runs through
//! `needlesim-server exercise run` with its known trajectory, and its metrics equal a hand
//! computation from the time series `needlesim-server simulate` writes for the same scene and
//! trajectory (targeting error to 1e-6 m, counts exact); the after-action report parses as HTML
//! and carries the metrics; bad exercises are refused naming the key.

use std::path::Path;
use std::process::Command;

use needlesim_tests::{TempDir, bin, python, read_json, repo_root, run, text};

/// An exercise's inputs as its TOML states them (server/scenes/exercises/).
struct Case {
    name: &'static str,
    dim: usize,
    /// The scene as `simulate --scene` takes it (a shipped name, or a path from the repository root).
    scene: &'static str,
    trajectory: &'static str,
    placed_at_s: &'static [f64],
    /// The exercise's targets (scene target names), in its order.
    targets: &'static [&'static str],
    /// Spheres (circles in 2D) to spare: centre, radius.
    spare: &'static [([f64; 3], f64)],
    redirect_threshold_m: f64,
}

const VESSEL_2D: ([f64; 3], f64) = ([0.0455524837323155, 0.04378054948187973, 0.0], 0.002);
const NERVE_2D: ([f64; 3], f64) = ([0.055114787550040546, 0.03184060200722471, 0.0], 0.0015);
const VESSEL_3D: ([f64; 3], f64) = ([0.04298133329356934, 0.024, 0.04071637170940382], 0.002);
const NERVE_3D: ([f64; 3], f64) = ([0.05447199994035401, 0.021, 0.031074557564105734], 0.0015);

const CASES: &[Case] = &[
    Case {
        name: "biopsy-2d",
        dim: 2,
        scene: "fig3-target",
        trajectory: "server/scenes/exercises/biopsy-2d.csv",
        placed_at_s: &[6.0],
        targets: &["biopsy"],
        spare: &[],
        redirect_threshold_m: 0.005,
    },
    Case {
        name: "brachy-2d",
        dim: 2,
        scene: "server/scenes/exercises/block-2d.toml",
        trajectory: "server/scenes/exercises/brachy-2d.csv",
        placed_at_s: &[7.0, 9.0, 11.0],
        targets: &["seed-1", "seed-2", "seed-3"],
        spare: &[],
        redirect_threshold_m: 0.005,
    },
    Case {
        name: "spare-2d",
        dim: 2,
        scene: "server/scenes/exercises/block-2d.toml",
        trajectory: "server/scenes/exercises/spare-2d.csv",
        placed_at_s: &[9.0],
        targets: &["biopsy"],
        spare: &[VESSEL_2D, NERVE_2D],
        redirect_threshold_m: 0.005,
    },
    Case {
        name: "biopsy-3d",
        dim: 3,
        scene: "fig3-target-3d",
        trajectory: "server/scenes/exercises/biopsy-3d.csv",
        placed_at_s: &[6.0],
        targets: &["biopsy"],
        spare: &[],
        redirect_threshold_m: 0.005,
    },
    Case {
        name: "brachy-3d",
        dim: 3,
        scene: "server/scenes/exercises/block-3d.toml",
        trajectory: "server/scenes/exercises/brachy-3d.csv",
        placed_at_s: &[7.0, 9.0, 11.0],
        targets: &["seed-1", "seed-2", "seed-3"],
        spare: &[],
        redirect_threshold_m: 0.005,
    },
    Case {
        name: "spare-3d",
        dim: 3,
        scene: "server/scenes/exercises/block-3d.toml",
        trajectory: "server/scenes/exercises/spare-3d.csv",
        placed_at_s: &[9.0],
        targets: &["biopsy"],
        spare: &[VESSEL_3D, NERVE_3D],
        redirect_threshold_m: 0.005,
    },
];

/// One row of simulate's CSV, in the terms of the metrics.
struct Row {
    t_s: f64,
    tip: [f64; 3],
    axis: [f64; 3],
    contacts: u32,
    /// Positive resisting insertion.
    axial_n: f64,
    /// Displaced centres of the case's targets, in its order.
    centres: Vec<[f64; 3]>,
}

fn read_rows(csv: &str, case: &Case) -> Vec<Row> {
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or_else(|e| panic!("{x}: {e}"))).collect();
            let g = |name: &str| v[col(name)];
            let centres = case
                .targets
                .iter()
                .map(|t| {
                    let z = if case.dim == 3 { g(&format!("target_{t}_z_m")) } else { 0.0 };
                    [g(&format!("target_{t}_x_m")), g(&format!("target_{t}_y_m")), z]
                })
                .collect();
            if case.dim == 2 {
                let th = g("theta_rad");
                Row {
                    t_s: g("t_s"),
                    tip: [g("tip_x_m"), g("tip_y_m"), 0.0],
                    axis: [th.cos(), th.sin(), 0.0],
                    contacts: (g("n_stuck") + g("n_slipping") + g("n_tip")) as u32,
                    axial_n: -g("f_axial_n"),
                    centres,
                }
            } else {
                // The needle is the base's local +x: R e_x of the unit quaternion.
                let (w, x, y, z) = (g("qw"), g("qx"), g("qy"), g("qz"));
                Row {
                    t_s: g("t_s"),
                    tip: [g("tip_x_m"), g("tip_y_m"), g("tip_z_m")],
                    axis: [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)],
                    contacts: g("n_points") as u32,
                    axial_n: g("f_axial_n"),
                    centres,
                }
            }
        })
        .collect()
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The metrics by hand, from the definitions (needlesim-training's metrics.rs docs), written
/// out again here as plainly as possible.
struct Hand {
    insertions: u64,
    redirections: u64,
    path_m: f64,
    peak_n: f64,
    mean_n: f64,
    time_s: f64,
    /// Per target of the case: error at its placement.
    errors: Vec<Option<f64>>,
    /// Per structure: min clearance over in-tissue rows.
    clearances: Vec<f64>,
}

fn by_hand(rows: &[Row], case: &Case) -> Hand {
    let mut h = Hand {
        insertions: 0,
        redirections: 0,
        path_m: 0.0,
        peak_n: 0.0,
        mean_n: 0.0,
        time_s: rows.last().unwrap().t_s - rows[0].t_s,
        errors: vec![None; case.targets.len()],
        clearances: vec![f64::INFINITY; case.spare.len()],
    };
    let (mut entry, mut inside, mut withdrawing, mut extreme) = ([0.0; 3], false, false, 0.0f64);
    let (mut sum, mut n_in) = (0.0, 0u64);
    let w = case.redirect_threshold_m;
    for (k, r) in rows.iter().enumerate() {
        let now_in = r.contacts > 0;
        let mut depth = 0.0;
        if now_in {
            if !inside {
                h.insertions += 1;
                entry = r.tip;
                withdrawing = false;
                extreme = 0.0;
            } else {
                h.path_m += dist(r.tip, rows[k - 1].tip);
            }
            depth = (0..3).map(|i| (r.tip[i] - entry[i]) * r.axis[i]).sum::<f64>();
            if !withdrawing && depth < extreme - w {
                withdrawing = true;
                extreme = depth;
            } else if withdrawing && depth > extreme + w {
                h.redirections += 1;
                withdrawing = false;
                extreme = depth;
            } else if withdrawing {
                extreme = extreme.min(depth);
            } else {
                extreme = extreme.max(depth);
            }
            sum += r.axial_n.abs();
            n_in += 1;
            for (c, (centre, radius)) in h.clearances.iter_mut().zip(case.spare) {
                // The shaft from the tip back to the entry: its closest point to the centre.
                let s = (0..case.dim).map(|i| (r.tip[i] - centre[i]) * r.axis[i]).sum::<f64>().clamp(0.0, depth.max(0.0));
                let p: Vec<f64> = (0..case.dim).map(|i| r.tip[i] - s * r.axis[i] - centre[i]).collect();
                *c = c.min(p.iter().map(|x| x * x).sum::<f64>().sqrt() - radius);
            }
        }
        let _ = depth;
        inside = now_in;
        h.peak_n = h.peak_n.max(r.axial_n.abs());
        for &tp in case.placed_at_s {
            if (r.t_s - tp).abs() < 5e-7 {
                // The nearest target not yet placed.
                let (i, e) = (0..case.targets.len())
                    .filter(|&i| h.errors[i].is_none())
                    .map(|i| (i, dist(r.tip, r.centres[i])))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .expect("a target left to place");
                h.errors[i] = Some(e);
            }
        }
    }
    h.mean_n = sum / n_in as f64;
    h
}

fn run_case(case: &Case) {
    let root = repo_root();
    let tmp = TempDir::new(&format!("training-{}", case.name));
    let scene = if case.scene.ends_with(".toml") { root.join(case.scene).display().to_string() } else { case.scene.to_owned() };
    let csv_path = tmp.join("sim.csv");
    let out = run(Command::new(bin("needlesim-server"))
        .args(["simulate", "--scene", &scene, "--trajectory"])
        .arg(root.join(case.trajectory))
        .arg("-o")
        .arg(&csv_path));
    assert!(out.status.success(), "{}: simulate failed: {}", case.name, text(&out).1);
    let out = run(Command::new(bin("needlesim-server"))
        .args(["exercise", "run", case.name, "--json"])
        .arg(tmp.join("m.json"))
        .arg("-o")
        .arg(tmp.join("r.html")));
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "{}: exercise run failed: {stderr}", case.name);
    assert!(stdout.starts_with(&format!("{}: score ", case.name)), "{stdout}");
    let rows = read_rows(&std::fs::read_to_string(&csv_path).unwrap(), case);
    let hand = by_hand(&rows, case);
    let j = read_json(&tmp.join("m.json"));
    let m = &j["result"]["metrics"];
    let f = |k: &str| m[k].as_f64().unwrap_or_else(|| panic!("{}: no {k} in {m}", case.name));
    let u = |k: &str| m[k].as_u64().unwrap_or_else(|| panic!("{}: no {k}", case.name));
    assert_eq!(j["ticks"].as_u64().unwrap(), rows.len() as u64, "{}", case.name);
    assert_eq!((u("insertions"), u("redirections")), (hand.insertions, hand.redirections), "{}", case.name);
    assert!((f("path_length_m") - hand.path_m).abs() < 1e-6, "{}: path {} vs {}", case.name, f("path_length_m"), hand.path_m);
    assert!((f("peak_axial_force_n") - hand.peak_n).abs() <= 1e-9 * hand.peak_n.max(1.0), "{}", case.name);
    assert!((f("mean_axial_force_n") - hand.mean_n).abs() <= 1e-9 * hand.mean_n.max(1.0), "{}", case.name);
    assert!((f("time_s") - hand.time_s).abs() < 1e-6, "{}", case.name);
    let targets = m["targets"].as_array().unwrap();
    assert_eq!(targets.len(), case.targets.len());
    for (i, t) in targets.iter().enumerate() {
        assert_eq!(t["name"].as_str().unwrap(), case.targets[i]);
        let e = t["placement"]["error_m"].as_f64();
        match (e, hand.errors[i]) {
            (Some(e), Some(h)) => assert!((e - h).abs() < 1e-6, "{} target {}: error {e} vs by hand {h}", case.name, case.targets[i]),
            other => panic!("{} target {}: placements differ: {other:?}", case.name, case.targets[i]),
        }
    }
    let structures = m["structures"].as_array().unwrap();
    assert_eq!(structures.len(), case.spare.len());
    for (s, c) in structures.iter().zip(&hand.clearances) {
        let got = s["min_clearance_m"].as_f64().unwrap();
        assert!((got - c).abs() < 1e-6, "{} {}: clearance {got} vs by hand {c}", case.name, s["name"]);
        assert_eq!(s["touched"].as_bool().unwrap(), *c <= 0.0);
        assert!((s["intrusion_depth_m"].as_f64().unwrap() - (-c).max(0.0)).abs() < 1e-6);
    }
    check_report(&tmp.join("r.html"), &j, case.name);
}

/// Parses the report with Python's html.parser: every non-void element closed in order, no
/// external reference (src/href attributes, url(...) other than fragments), three SVG plots;
/// the metric cells' values equal the JSON's.
fn check_report(html: &Path, j: &serde_json::Value, name: &str) {
    let script = r##"
import json, sys
from html.parser import HTMLParser
VOID = {"meta", "br", "img", "input", "link", "hr", "area", "base", "col", "source", "wbr"}
class P(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.metrics, self.errors, self.svgs, self.external = [], {}, [], 0, []
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "svg": self.svgs += 1
        for k in ("src", "href", "xlink:href"):
            if k in a and not a[k].startswith("#"): self.external.append(a[k])
        if "data-metric" in a: self.metrics[a["data-metric"]] = float(a["data-value"])
        if tag not in VOID: self.stack.append(tag)
    def handle_startendtag(self, tag, attrs):
        a = dict(attrs)
        for k in ("src", "href", "xlink:href"):
            if k in a and not a[k].startswith("#"): self.external.append(a[k])
    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append("</%s> closes %s" % (tag, self.stack[-1] if self.stack else "nothing"))
        else:
            self.stack.pop()
p = P()
p.feed(open(sys.argv[1], encoding="utf-8").read())
p.close()
print(json.dumps({"metrics": p.metrics, "errors": p.errors, "open": p.stack, "svgs": p.svgs, "external": p.external}))
"##;
    let out = run(Command::new(python()).arg("-c").arg(script).arg(html));
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "{name}: html.parser: {stderr}");
    let r: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(r["errors"].as_array().unwrap().len(), 0, "{name}: {}", r["errors"]);
    assert_eq!(r["open"].as_array().unwrap().len(), 0, "{name}: unclosed {}", r["open"]);
    assert_eq!(r["svgs"].as_u64().unwrap(), 3, "{name}: three inline SVG plots");
    assert_eq!(r["external"].as_array().unwrap().len(), 0, "{name}: external references {}", r["external"]);
    let text = std::fs::read_to_string(html).unwrap();
    assert!(!text.contains("url(http") && !text.contains("@import"), "{name}: an external URL in CSS");
    let hm = &r["metrics"];
    let m = &j["result"]["metrics"];
    for k in ["insertions", "redirections", "path_length_m", "peak_axial_force_n", "mean_axial_force_n", "time_s"] {
        let (a, b) = (hm[k].as_f64().unwrap_or_else(|| panic!("{name}: no {k} in the report")), m[k].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{name}: {k} {a} in the report, {b} in the JSON");
    }
    let score = j["result"]["score"]["total"].as_f64().unwrap();
    assert!((hm["score"].as_f64().unwrap() - score).abs() <= 1e-12 * score.max(1.0));
    // Tissue strain (2D scripted runs): finite, sampled every 10 ms of exercise time, reported.
    let st = &m["strain"];
    if j["dim"].as_u64().unwrap() == 2 {
        let n = st["strain_samples"].as_u64().unwrap();
        let time_s = m["time_s"].as_f64().unwrap();
        assert_eq!(n, (time_s / 0.01).round() as u64 + 1, "{name}: a strain sample every 10 ms");
        let peak = st["peak_strain"].as_f64().unwrap();
        let area = st["damaged_area_m2"].as_f64().unwrap();
        assert!(peak.is_finite() && peak > 0.0 && area.is_finite() && area >= 0.0, "{name}: strain {st}");
        assert_eq!(area > 0.0, peak > st["damage_strain"].as_f64().unwrap(), "{name}: an area above the threshold iff the peak is: {st}");
        assert!(st["samples_above"].as_u64().unwrap() <= n);
        for (k, v) in [
            ("peak_strain", peak),
            ("damaged_area_m2", area),
            ("strain_samples", n as f64),
            ("strain_samples_above", st["samples_above"].as_f64().unwrap()),
        ] {
            let got = hm[k].as_f64().unwrap_or_else(|| panic!("{name}: no {k} in the report"));
            assert!((got - v).abs() <= 1e-12 * v.abs().max(1.0), "{name}: {k} {got} in the report, {v} in the JSON");
        }
    } else {
        assert_eq!(st["strain_samples"].as_u64().unwrap(), 0, "{name}: not computed in 3D");
    }
    for (i, t) in m["targets"].as_array().unwrap().iter().enumerate() {
        let e = t["placement"]["error_m"].as_f64().unwrap();
        assert!((hm[format!("target_{i}_error_m")].as_f64().unwrap() - e).abs() <= 1e-12 * e.max(1.0));
    }
}

#[test]
fn shipped_2d_exercises_match_a_hand_computation_from_simulate() {
    for case in CASES.iter().filter(|c| c.dim == 2) {
        run_case(case);
    }
}

#[test]
fn shipped_3d_exercises_match_a_hand_computation_from_simulate() {
    for case in CASES.iter().filter(|c| c.dim == 3) {
        run_case(case);
    }
}

#[test]
fn every_shipped_exercise_is_tested() {
    let out = run(Command::new(bin("needlesim-server")).args(["exercise", "list"]));
    let (stdout, _) = text(&out);
    let listed: Vec<&str> = stdout.lines().filter_map(|l| l.split('\t').next()).collect();
    let tested: Vec<&str> = CASES.iter().map(|c| c.name).collect();
    assert_eq!(listed, tested);
}

#[test]
fn bad_exercises_and_placements_are_refused_naming_what() {
    let tmp = TempDir::new("training-errors");
    let bad = tmp.join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"bad\"\nscene = \"fig3-target\"\n[[spare]]\nname = \"v\"\nshape = \"sphere\"\ncenter_m = [0.01, 0.02]\nradius_m = -1\n",
    )
    .unwrap();
    let out = run(Command::new(bin("needlesim-server")).args(["exercise", "run"]).arg(&bad));
    let (_, stderr) = text(&out);
    assert!(!out.status.success() && stderr.contains("spare[0].radius_m: -1 must be finite and in (0, 1e6]"), "{stderr}");
    let out = run(Command::new(bin("needlesim-server")).args(["exercise", "run", "biopsy-2d", "--placed-at", "99"]));
    let (_, stderr) = text(&out);
    assert!(!out.status.success() && stderr.contains("placed at t = 99 s: after the trajectory's end at t = 6 s"), "{stderr}");
    let out = run(Command::new(bin("needlesim-server")).args(["exercise", "run", "no-such-exercise"]));
    let (_, stderr) = text(&out);
    assert!(!out.status.success() && stderr.contains("neither a file nor a shipped exercise (shipped: biopsy-2d"), "{stderr}");
    // A scene target the scene lacks.
    std::fs::write(&bad, "name = \"bad\"\nscene = \"fig3-target\"\n[[targets]]\nscene_target = \"nope\"\n").unwrap();
    let out = run(Command::new(bin("needlesim-server"))
        .args(["exercise", "run"])
        .arg(&bad)
        .args(["--trajectory"])
        .arg(repo_root().join("server/scenes/fig3-target.csv")));
    let (_, stderr) = text(&out);
    assert!(
        !out.status.success() && stderr.contains("targets[0].scene_target: 'nope' is not a target of the scene (its targets: biopsy)"),
        "{stderr}"
    );
}

/// An expert CSV's rows (the tick series `exercise run --ticks` writes) in the terms of
/// [`by_hand`], read here by column name; and the times at which it declared "placed".
fn read_expert_rows(csv: &str, case: &Case) -> (Vec<Row>, Vec<f64>) {
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    let mut placed = Vec::new();
    let rows = lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or_else(|e| panic!("{x}: {e}"))).collect();
            let g = |name: &str| v[col(name)];
            for _ in 0..g("placed") as u32 {
                placed.push(g("t_s"));
            }
            Row {
                t_s: g("t_s"),
                tip: [g("tip_x_m"), g("tip_y_m"), g("tip_z_m")],
                axis: [g("axis_x"), g("axis_y"), g("axis_z")],
                contacts: g("contacts") as u32,
                axial_n: g("axial_force_n"),
                centres: case
                    .targets
                    .iter()
                    .map(|t| [g(&format!("target_{t}_x_m")), g(&format!("target_{t}_y_m")), g(&format!("target_{t}_z_m"))])
                    .collect(),
            }
        })
        .collect();
    (rows, placed)
}

/// The report's expert table (`data-expert` / `data-trainee` cells) and every SVG text, parsed
/// with Python's html.parser.
fn expert_table(html: &Path) -> serde_json::Value {
    let script = r##"
import json, sys
from html.parser import HTMLParser
class P(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.expert, self.trainee, self.texts, self.in_svg, self.in_text, self.note = {}, {}, [], 0, False, None
        self.in_note = False
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "svg": self.in_svg += 1
        if tag == "text" and self.in_svg: self.in_text = True; self.texts.append("")
        if "data-expert" in a: self.expert[a["data-expert"]] = float(a["data-value"])
        if "data-trainee" in a: self.trainee[a["data-trainee"]] = float(a["data-value"])
        if a.get("id") == "expert-note": self.in_note = True; self.note = ""
    def handle_endtag(self, tag):
        if tag == "svg": self.in_svg -= 1
        if tag == "text": self.in_text = False
        if tag == "p": self.in_note = False
    def handle_data(self, d):
        if self.in_text: self.texts[-1] += d
        if self.in_note: self.note += d
p = P()
p.feed(open(sys.argv[1], encoding="utf-8").read())
p.close()
print(json.dumps({"expert": p.expert, "trainee": p.trainee, "texts": p.texts, "note": p.note}))
"##;
    let out = run(Command::new(python()).arg("-c").arg(script).arg(html));
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "html.parser: {stderr}");
    serde_json::from_str(stdout.trim()).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

/// The shipped biopsy exercises name an expert run: the report overlays it (the legend label in
/// the three plots) and its comparison table's expert column equals the metrics computed here
/// from the shipped expert CSV by the definitions; the trainee column equals the run's JSON.
#[test]
fn the_expert_run_is_overlaid_and_its_metrics_match_a_hand_computation() {
    let root = repo_root();
    for name in ["biopsy-2d", "biopsy-3d"] {
        let case = CASES.iter().find(|c| c.name == name).unwrap();
        let tmp = TempDir::new(&format!("training-expert-{name}"));
        let out = run(Command::new(bin("needlesim-server"))
            .args(["exercise", "run", name, "--json"])
            .arg(tmp.join("m.json"))
            .arg("-o")
            .arg(tmp.join("r.html")));
        assert!(out.status.success(), "{name}: {}", text(&out).1);
        check_report(&tmp.join("r.html"), &read_json(&tmp.join("m.json")), name);
        let file = format!("{name}-expert.csv");
        let csv = std::fs::read_to_string(root.join("server/scenes/exercises").join(&file)).unwrap();
        let (rows, placed) = read_expert_rows(&csv, case);
        assert_eq!(placed, case.placed_at_s, "{name}: the expert declared placed at its exercise's times");
        let hand = by_hand(&rows, &Case { placed_at_s: Box::leak(placed.into_boxed_slice()), ..*case });
        let r = expert_table(&tmp.join("r.html"));
        let label = format!("expert ({file})");
        let texts: Vec<&str> = r["texts"].as_array().unwrap().iter().map(|t| t.as_str().unwrap().trim()).collect();
        assert_eq!(texts.iter().filter(|t| **t == label).count(), 3, "{name}: the legend label in each plot: {texts:?}");
        assert_eq!(texts.iter().filter(|t| **t == "trainee").count(), 3, "{name}: {texts:?}");
        let e = &r["expert"];
        let g = |k: &str| e[k].as_f64().unwrap_or_else(|| panic!("{name}: no expert {k} in {e}"));
        for (k, v) in [
            ("time_s", hand.time_s),
            ("path_length_m", hand.path_m),
            ("peak_axial_force_n", hand.peak_n),
            ("mean_axial_force_n", hand.mean_n),
            ("insertions", hand.insertions as f64),
            ("redirections", hand.redirections as f64),
            ("target_0_error_m", hand.errors[0].expect("the expert placed the target")),
        ] {
            assert!(close(g(k), v), "{name}: expert {k} {} in the report, {v} by hand", g(k));
        }
        let j = read_json(&tmp.join("m.json"));
        let m = &j["result"]["metrics"];
        for k in ["time_s", "path_length_m", "peak_axial_force_n", "mean_axial_force_n"] {
            let (a, b) = (r["trainee"][k].as_f64().unwrap(), m[k].as_f64().unwrap());
            assert!(close(a, b), "{name}: trainee {k} {a} in the table, {b} in the JSON");
        }
        assert!(close(j["expert"]["result"]["metrics"]["path_length_m"].as_f64().unwrap(), hand.path_m), "{name}: the JSON's expert");
    }
}

/// A run's own tick series (`--ticks`, every tick) read back as the expert gives exactly the
/// run's metrics; a malformed or missing expert file is an error naming the file and line.
#[test]
fn a_runs_tick_series_is_its_own_expert_and_bad_expert_files_are_refused_naming_the_line() {
    let tmp = TempDir::new("training-expert-ticks");
    let ticks = tmp.join("ticks.csv");
    let out = run(Command::new(bin("needlesim-server"))
        .args(["exercise", "run", "brachy-2d", "--ticks"])
        .arg(&ticks)
        .arg("--json")
        .arg(tmp.join("a.json")));
    assert!(out.status.success(), "{}", text(&out).1);
    let a = read_json(&tmp.join("a.json"));
    let n_rows = std::fs::read_to_string(&ticks).unwrap().lines().filter(|l| !l.starts_with('#')).count() - 1;
    assert_eq!(n_rows as u64, a["ticks"].as_u64().unwrap(), "one row a tick");
    let out = run(Command::new(bin("needlesim-server"))
        .args(["exercise", "run", "brachy-2d", "--expert"])
        .arg(&ticks)
        .arg("--json")
        .arg(tmp.join("b.json")));
    assert!(out.status.success(), "{}", text(&out).1);
    let b = read_json(&tmp.join("b.json"));
    let (tm, em) = (&a["result"]["metrics"], &b["expert"]["result"]["metrics"]);
    for k in ["time_s", "path_length_m", "peak_axial_force_n", "mean_axial_force_n", "insertions", "redirections", "max_depth_m"] {
        assert!(close(tm[k].as_f64().unwrap(), em[k].as_f64().unwrap()), "{k}: run {} vs expert {}", tm[k], em[k]);
    }
    for (x, y) in tm["targets"].as_array().unwrap().iter().zip(em["targets"].as_array().unwrap()) {
        let (ex, ey) = (x["placement"]["error_m"].as_f64().unwrap(), y["placement"]["error_m"].as_f64().unwrap());
        assert!(close(ex, ey), "{}: {ex} vs {ey}", x["name"]);
    }
    assert!(close(a["result"]["score"]["total"].as_f64().unwrap(), b["expert"]["result"]["score"]["total"].as_f64().unwrap()));
    // Line 1 is the comment, 2 the header: corrupt the tip's y on line 7.
    let mut lines: Vec<String> = std::fs::read_to_string(&ticks).unwrap().lines().map(str::to_owned).collect();
    let mut v: Vec<String> = lines[6].split(',').map(str::to_owned).collect();
    v[2] = "abc".into();
    lines[6] = v.join(",");
    let bad = tmp.join("bad.csv");
    std::fs::write(&bad, lines.join("\n")).unwrap();
    let out = run(Command::new(bin("needlesim-server")).args(["exercise", "run", "brachy-2d", "--expert"]).arg(&bad));
    let (_, stderr) = text(&out);
    let want = format!("expert run {}: line 7: column 3 ('tip_y_m'): 'abc' is not a finite number", bad.display());
    assert!(!out.status.success() && stderr.contains(&want), "{stderr}");
    let missing = tmp.join("no-such.csv");
    let out = run(Command::new(bin("needlesim-server")).args(["exercise", "run", "brachy-2d", "--expert"]).arg(&missing));
    let (_, stderr) = text(&out);
    assert!(!out.status.success() && stderr.contains(&format!("expert run {}: cannot read it", missing.display())), "{stderr}");
}

/// Issue 35 (careless input): `exercise run --placed-at nan` was silently ignored (a time never
/// reached: "placed" never declared, exit 0); a time that is not finite is refused naming the flag,
/// and a huge one is echoed compactly.
#[test]
fn issue_35_a_placement_time_that_is_not_finite_is_refused_naming_the_flag() {
    for (arg, want) in [
        ("nan", "placed-at: NaN is not a finite time (s)"),
        ("1,inf", "placed-at: inf is not a finite time (s)"),
        ("-inf", "placed-at: -inf is not a finite time (s)"),
        ("1e300", "placed at t = 1e300 s: after the trajectory's end at t = 6 s"),
    ] {
        let out = run(Command::new(bin("needlesim-server")).args(["exercise", "run", "biopsy-2d", &format!("--placed-at={arg}")]));
        let (_, stderr) = text(&out);
        assert!(!out.status.success() && stderr.contains(want), "--placed-at {arg}: {stderr}");
    }
}
