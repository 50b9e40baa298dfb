//! Issue 19: the shipped 2D examples (the built-in scenes with their example trajectories and the
//! 2D training exercises' scripted runs) never end a tick at an iteration cap: no stick/slip
//! iteration stops at `max_active_set_iterations`, no flexible needle's shape passes stop at
//! their bound, no tick is left unconverged.

use std::path::Path;

use needlesim_core::MeshLimits;
use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};
use needlesim_scene::Trajectory;

/// Runs `scene` along `trajectory` (CSV text) and returns its statistics.
fn run(scene: &str, trajectory: &str) -> needlesim_core::sim::SimStats {
    let scene = needlesim_scene::load_scene(scene, &MeshLimits::default()).unwrap_or_else(|e| panic!("{scene}: {e:#}"));
    let traj = Trajectory::parse_csv(trajectory).unwrap();
    let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(&traj), RunOptions::default()).unwrap();
    run.run(|_, _| std::ops::ControlFlow::Continue(())).unwrap();
    run.sim().stats()
}

/// `key = "value"` of a flat TOML file.
fn toml_value(text: &str, key: &str) -> Option<String> {
    text.lines().find_map(|l| {
        let (k, v) = l.split_once('=')?;
        (k.trim() == key).then(|| v.trim().trim_matches('"').to_owned())
    })
}

#[test]
fn issue_19_the_shipped_2d_examples_never_stop_at_an_iteration_cap() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut cases: Vec<(String, String)> = ["paper-phantom", "fig3-target", "fig4-steering", "bevel-tip"]
        .iter()
        .map(|n| (n.to_string(), std::fs::read_to_string(scenes.join(format!("{n}.csv"))).unwrap()))
        .collect();
    for entry in std::fs::read_dir(scenes.join("exercises")).unwrap() {
        let path = entry.unwrap().path();
        if !path.to_string_lossy().ends_with("-2d.toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if let (Some(scene), Some(csv)) = (toml_value(&text, "scene"), toml_value(&text, "trajectory")) {
            // A scene file is named relative to the exercise, a built-in scene by its name.
            let scene = if scene.ends_with(".toml") { path.with_file_name(scene).to_string_lossy().into_owned() } else { scene };
            cases.push((scene, std::fs::read_to_string(path.with_file_name(csv)).unwrap()));
        }
    }
    assert!(cases.len() >= 7, "{} cases", cases.len());
    for (scene, csv) in &cases {
        let s = run(scene, csv);
        println!(
            "{scene}: {} ticks, {} captures, {} shape passes; capped: active set {}, shape {}",
            s.ticks, s.captures, s.shape_passes, s.active_set_capped_ticks, s.shape_capped_ticks
        );
        assert!(s.ticks > 1000 && s.captures > 0, "{scene}: {s:?}");
        assert_eq!((s.active_set_capped_ticks, s.shape_capped_ticks, s.unconverged_ticks), (0, 0, 0), "{scene}: {s:?}");
    }
}
