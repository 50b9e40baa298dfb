//! Issue 35 item 14: a client's number is echoed in an error compactly. Every number of the
//! shipped scenes, one at a time, is set to 1e300, -1e300 and 1e-300: a scene that is refused
//! says so in a short message with no run of digits that spells the number out in full.

use std::path::{Path, PathBuf};

use needlesim_core::MeshLimits;
use needlesim_scene::{SceneLimits, parse_scene, parse_scene3d};

/// A number no shipped scene holds, replaced by the value under test in the TOML text.
const SENTINEL: f64 = 7777777.25;

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// The paths of every number of a TOML document (keys, and indices in arrays).
fn float_paths(v: &toml::Value, path: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        toml::Value::Float(_) | toml::Value::Integer(_) => out.push(path.clone()),
        toml::Value::Table(t) => {
            for (k, v) in t {
                path.push(k.clone());
                float_paths(v, path, out);
                path.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                path.push(i.to_string());
                float_paths(v, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn set(v: &mut toml::Value, path: &[String], x: f64) {
    let mut cur = v;
    for p in path {
        cur = match cur {
            toml::Value::Table(t) => t.get_mut(p).unwrap(),
            toml::Value::Array(a) => &mut a[p.parse::<usize>().unwrap()],
            _ => unreachable!(),
        };
    }
    *cur = toml::Value::Float(x);
}

/// The longest run of ASCII digits in `s` (a shortest round-trip number has at most 21 between
/// 1e-4 and 1e16: 0.00012345678901234567).
fn longest_digit_run(s: &str) -> usize {
    s.split(|c: char| !c.is_ascii_digit()).map(str::len).max().unwrap_or(0)
}

#[test]
fn issue_35_every_scene_number_of_1e300_is_refused_in_a_short_message() {
    let limits = SceneLimits { mesh: MeshLimits::default(), max_session_bytes: 1280 << 20 };
    let dir = scenes_dir();
    let mut refused = 0;
    for name in ["paper-phantom", "fig3-target", "fig4-steering-toughness", "bevel-tip", "cube-phantom-3d", "behind-vessel-bevel-3d"] {
        let text = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        let doc: toml::Value = toml::from_str(&text).unwrap();
        let mut paths = Vec::new();
        float_paths(&doc, &mut Vec::new(), &mut paths);
        assert!(paths.len() > 5, "{name}: {} numbers", paths.len());
        for path in &paths {
            // The value as a client writes it (toml's writer spells a float out in full).
            let mut d = doc.clone();
            set(&mut d, path, SENTINEL);
            let with_sentinel = toml::to_string(&d).unwrap();
            assert_eq!(with_sentinel.matches("7777777.25").count(), 1, "{name}");
            for (x, written) in [(1e300, "1e300"), (-1e300, "-1e300"), (1e-300, "1e-300")] {
                let t = with_sentinel.replace("7777777.25", written);
                let r = if name.ends_with("-3d") {
                    parse_scene3d(&t, &dir, limits).map(|_| ())
                } else {
                    parse_scene(&t, &dir, limits).map(|_| ())
                };
                let Err(e) = r else { continue };
                refused += 1;
                let m = format!("{e:#}");
                assert!(longest_digit_run(&m) <= 24, "{name}, {} = {x:e}: {m}", path.join("."));
                assert!(m.chars().count() < 400, "{name}, {} = {x:e}: {} characters: {m}", path.join("."), m.chars().count());
            }
        }
    }
    assert!(refused > 50, "only {refused} refusals");
}

#[test]
fn issue_35_a_tick_rate_of_1e300_is_named_as_1e300() {
    let limits = SceneLimits { mesh: MeshLimits::default(), max_session_bytes: 1280 << 20 };
    let dir = scenes_dir();
    for (name, old) in [("paper-phantom", "tick_rate_hz = 1000\n"), ("cube-phantom-3d", "tick_rate_hz = 1000\n")] {
        let text = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        assert!(text.contains(old), "{name}");
        let text = text.replace(old, "tick_rate_hz = 1e300\n");
        let e = if name.ends_with("-3d") {
            parse_scene3d(&text, &dir, limits).map(|_| ()).unwrap_err()
        } else {
            parse_scene(&text, &dir, limits).map(|_| ()).unwrap_err()
        };
        let m = format!("{e:#}");
        assert!(m.contains("tick_rate_hz = 1e300: must be between 100 and 10000"), "{name}: {m}");
        assert!(m.len() < 200, "{name}: {m}");
    }
}
