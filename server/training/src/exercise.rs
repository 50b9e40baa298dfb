//! Exercises: the TOML format, its validation (errors name the key), and the shipped examples
//! (server/scenes/exercises/, embedded like the scenes).
//!
//! ```toml
//! name = "biopsy-2d"
//! description = "…"
//! scene = "fig3-target"            # a shipped scene, or a scene file relative to this file
//! trajectory = "biopsy-2d.csv"     # optional: the example's scripted run (relative)
//! placed_at_s = [5.5]              # optional: when the example declares "placed"
//! expert = "biopsy-2d-expert.csv"  # optional: an expert's run (the tick series CSV that
//!                                  # `exercise run --ticks` writes, expert.rs), overlaid in the report
//!
//! [[targets]]                      # optional: default = every scene target, tolerance = radius
//! scene_target = "biopsy"          # a target of the scene (the simulation moves it), or
//! # name = "seed-2"; center_m = [x, y(, z)]; radius_m = r   (a new one, tracked the same way)
//! tolerance_m = 0.002
//!
//! [[spare]]                        # structures to spare, world coordinates
//! name = "vessel"
//! shape = "sphere"                 # or "box": min_m = [...], max_m = [...]
//! center_m = [x, y(, z)]           # 2 values in 2D (a circle), 3 in 3D
//! radius_m = 0.003
//! margin_m = 0.002                 # full safety score at this clearance or more
//!
//! [limits]                         # exceeding one costs `penalty` points of the score
//! time_s = 60
//! reinsertions = 1
//! peak_force_n = 3
//! penalty = 10
//!
//! [weights]                        # relative weights of the sub-scores (metrics.rs)
//! accuracy = 4
//! efficiency = 1
//! path = 1
//! force = 1
//! safety = 2
//! time = 1
//!
//! [metrics]
//! redirect_threshold_m = 0.005     # the withdrawal (and re-advance) that makes a redirection
//! damage_strain = 0.3              # equivalent strain above which tissue counts as damaged (2D, strain.rs)
//! ```

use std::path::{Path, PathBuf};

use needlesim_core::num::num;
use serde::Deserialize;

use crate::geometry::Shape;

/// The shipped exercises: (name, exercise TOML, files it names: (file name, contents)).
pub type ExerciseFiles = &'static [(&'static str, &'static str)];

/// The shipped exercises (server/scenes/exercises/), embedded.
pub const EXERCISES: &[(&str, &str, ExerciseFiles)] = &[
    (
        "biopsy-2d",
        include_str!("../../scenes/exercises/biopsy-2d.toml"),
        &[
            ("biopsy-2d.csv", include_str!("../../scenes/exercises/biopsy-2d.csv")),
            ("biopsy-2d-expert.csv", include_str!("../../scenes/exercises/biopsy-2d-expert.csv")),
        ],
    ),
    (
        "brachy-2d",
        include_str!("../../scenes/exercises/brachy-2d.toml"),
        &[BLOCK_2D, ("brachy-2d.csv", include_str!("../../scenes/exercises/brachy-2d.csv"))],
    ),
    (
        "spare-2d",
        include_str!("../../scenes/exercises/spare-2d.toml"),
        &[BLOCK_2D, ("spare-2d.csv", include_str!("../../scenes/exercises/spare-2d.csv"))],
    ),
    (
        "biopsy-3d",
        include_str!("../../scenes/exercises/biopsy-3d.toml"),
        &[
            ("biopsy-3d.csv", include_str!("../../scenes/exercises/biopsy-3d.csv")),
            ("biopsy-3d-expert.csv", include_str!("../../scenes/exercises/biopsy-3d-expert.csv")),
        ],
    ),
    (
        "brachy-3d",
        include_str!("../../scenes/exercises/brachy-3d.toml"),
        &[BLOCK_3D, ("brachy-3d.csv", include_str!("../../scenes/exercises/brachy-3d.csv"))],
    ),
    (
        "spare-3d",
        include_str!("../../scenes/exercises/spare-3d.toml"),
        &[BLOCK_3D, ("spare-3d.csv", include_str!("../../scenes/exercises/spare-3d.csv"))],
    ),
];

const BLOCK_2D: (&str, &str) = ("block-2d.toml", include_str!("../../scenes/exercises/block-2d.toml"));
const BLOCK_3D: (&str, &str) = ("block-3d.toml", include_str!("../../scenes/exercises/block-3d.toml"));

/// Why an exercise is refused; each names the key or the file.
#[derive(Debug, thiserror::Error)]
pub enum ExerciseError {
    /// The exercise is neither a file nor a shipped exercise.
    #[error("exercise '{0}' is neither a file nor a shipped exercise (shipped: {1})")]
    NotFound(String, String),
    /// A file could not be read.
    #[error("cannot read {path}: {source}")]
    Read { path: String, source: std::io::Error },
    /// The TOML does not parse or has an unknown key or a value of the wrong type.
    #[error("exercise TOML: {0}")]
    Toml(String),
    /// A value is out of range or inconsistent; `key` is the TOML key.
    #[error("{key}: {message}")]
    Invalid { key: String, message: String },
}

fn invalid(key: impl Into<String>, message: impl Into<String>) -> ExerciseError {
    ExerciseError::Invalid { key: key.into(), message: message.into() }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExerciseFile {
    name: String,
    description: Option<String>,
    scene: String,
    trajectory: Option<String>,
    #[serde(default)]
    placed_at_s: Vec<f64>,
    expert: Option<String>,
    #[serde(default)]
    targets: Vec<TargetSpec>,
    #[serde(default)]
    spare: Vec<SpareSpec>,
    #[serde(default)]
    limits: LimitsFile,
    #[serde(default)]
    weights: WeightsFile,
    #[serde(default)]
    metrics: MetricsFile,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TargetSpec {
    scene_target: Option<String>,
    name: Option<String>,
    center_m: Option<Vec<f64>>,
    radius_m: Option<f64>,
    tolerance_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpareSpec {
    name: String,
    shape: String,
    center_m: Option<Vec<f64>>,
    radius_m: Option<f64>,
    min_m: Option<Vec<f64>>,
    max_m: Option<Vec<f64>>,
    margin_m: Option<f64>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct LimitsFile {
    time_s: Option<f64>,
    reinsertions: Option<i64>,
    peak_force_n: Option<f64>,
    penalty: Option<f64>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct WeightsFile {
    accuracy: Option<f64>,
    efficiency: Option<f64>,
    path: Option<f64>,
    force: Option<f64>,
    safety: Option<f64>,
    time: Option<f64>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct MetricsFile {
    redirect_threshold_m: Option<f64>,
    damage_strain: Option<f64>,
}

/// Where an exercise's target comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum TargetSource {
    /// The scene's target of this name.
    Scene(String),
    /// A target the exercise adds to the simulation (tracked like the scene's).
    New { center_m: [f64; 3], radius_m: f64 },
}

/// A target of the exercise.
#[derive(Debug, Clone, PartialEq)]
pub struct ExerciseTarget {
    pub name: String,
    pub source: TargetSource,
    /// Largest targeting error that counts as placed on target, m (metrics.rs).
    pub tolerance_m: f64,
}

/// A structure to spare.
#[derive(Debug, Clone, PartialEq)]
pub struct Structure {
    pub name: String,
    pub shape: Shape,
    /// The clearance at which its safety sub-score is full, m (> 0).
    pub margin_m: f64,
}

/// The exercise's limits; exceeding one costs `penalty` points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    pub time_s: f64,
    pub reinsertions: u32,
    pub peak_force_n: f64,
    pub penalty: f64,
}

/// The sub-scores' weights (metrics.rs); non-negative, not all zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    pub accuracy: f64,
    pub efficiency: f64,
    pub path: f64,
    pub force: f64,
    pub safety: f64,
    pub time: f64,
}

/// How the scene is given.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneRef {
    /// A shipped scene's name (needlesim-scene's examples).
    Shipped(String),
    /// A scene TOML's text and the directory its relative files resolve against (`file` is
    /// how the exercise named it).
    File { file: String, text: String, base_dir: PathBuf },
}

/// An expert run the exercise names: the file as named, and its text or why it cannot be read
/// (kept, not refused at parse time: a live session still reports without it, with a note).
#[derive(Debug, Clone, PartialEq)]
pub struct ExpertSource {
    pub file: String,
    pub text: Result<String, String>,
}

/// A validated exercise.
#[derive(Debug, Clone, PartialEq)]
pub struct Exercise {
    pub name: String,
    pub description: String,
    pub scene: SceneRef,
    /// 2 or 3, from the scene.
    pub dim: u8,
    /// Empty: every scene target, with its radius as tolerance (resolved when the scene loads).
    pub targets: Vec<ExerciseTarget>,
    pub spare: Vec<Structure>,
    pub limits: Limits,
    pub weights: Weights,
    pub redirect_threshold_m: f64,
    /// The equivalent strain above which tissue counts as damaged ([`crate::strain`]; default
    /// [`DEFAULT_DAMAGE_STRAIN`]).
    pub damage_strain: f64,
    /// The example's trajectory CSV text, when the exercise names one.
    pub trajectory_csv: Option<String>,
    pub placed_at_s: Vec<f64>,
    /// The expert run to compare with (`expert`), if named.
    pub expert: Option<ExpertSource>,
}

/// The default `damage_strain`: 30 % equivalent strain (a training threshold for the shipped
/// exercises, not a measured tissue property: set it per exercise).
pub const DEFAULT_DAMAGE_STRAIN: f64 = 0.3;

/// Most targets and structures of an exercise.
pub const MAX_EXERCISE_TARGETS: usize = crate::sample::MAX_SAMPLE_TARGETS;
/// Most structures to spare.
pub const MAX_STRUCTURES: usize = 16;

/// Reads an exercise: a shipped exercise's name ([`EXERCISES`]) or a TOML file.
pub fn load_exercise(spec: &str) -> Result<Exercise, ExerciseError> {
    if let Some((_, text, files)) = EXERCISES.iter().find(|e| e.0 == spec) {
        let read = |f: &str| -> Result<String, ExerciseError> {
            files.iter().find(|(n, _)| *n == f).map(|(_, t)| (*t).to_owned()).ok_or_else(|| ExerciseError::Read {
                path: f.to_owned(),
                source: std::io::Error::new(std::io::ErrorKind::NotFound, "not shipped with the exercise"),
            })
        };
        return parse_with(text, &read, Path::new("server/scenes/exercises"));
    }
    let path = Path::new(spec);
    if !path.exists() {
        let names: Vec<&str> = EXERCISES.iter().map(|e| e.0).collect();
        return Err(ExerciseError::NotFound(spec.to_owned(), names.join(", ")));
    }
    let text = read_local(path)?;
    parse_exercise(&text, path.parent().unwrap_or(Path::new(".")))
}

/// Parses exercise TOML; `base_dir` resolves the files it names.
pub fn parse_exercise(text: &str, base_dir: &Path) -> Result<Exercise, ExerciseError> {
    let read = |f: &str| read_local(&base_dir.join(f));
    parse_with(text, &read, base_dir)
}

/// A local file an exercise names: a regular file, not a link, of bounded size
/// ([`needlesim_scene::read_local_file`]); the error names the path and the problem.
fn read_local(path: &Path) -> Result<String, ExerciseError> {
    use needlesim_scene::LocalFileError;
    needlesim_scene::read_local_file(path, needlesim_scene::MAX_LOCAL_FILE_BYTES).map_err(|e| match e {
        LocalFileError::Io { path, source } => ExerciseError::Read { path, source },
        LocalFileError::Refused { path, problem } => ExerciseError::Read { path, source: std::io::Error::other(problem) },
    })
}

fn positive(key: &str, v: f64) -> Result<f64, ExerciseError> {
    if v.is_finite() && v > 0.0 && v <= 1e6 { Ok(v) } else { Err(invalid(key, format!("{} must be finite and in (0, 1e6]", num(v)))) }
}

fn point(key: &str, v: &[f64], dim: u8) -> Result<[f64; 3], ExerciseError> {
    if v.len() != dim as usize {
        return Err(invalid(key, format!("has {} values, the scene is {dim}D: give {dim}", v.len())));
    }
    if let Some(x) = v.iter().find(|x| !x.is_finite() || x.abs() > 1e3) {
        return Err(invalid(key, format!("{} must be finite and within ±1e3 m", num(*x))));
    }
    Ok([v[0], v[1], if dim == 3 { v[2] } else { 0.0 }])
}

fn parse_with(text: &str, read: &dyn Fn(&str) -> Result<String, ExerciseError>, base_dir: &Path) -> Result<Exercise, ExerciseError> {
    let brackets = text.bytes().filter(|&b| b == b'[' || b == b'{').count();
    if brackets > needlesim_scene::MAX_TOML_BRACKETS {
        return Err(ExerciseError::Toml(format!("{brackets} brackets, more than {}", needlesim_scene::MAX_TOML_BRACKETS)));
    }
    let f: ExerciseFile = toml::from_str(text).map_err(|e| ExerciseError::Toml(needlesim_scene::limit::toml_message(&e, text)))?;
    if f.name.trim().is_empty() || f.name.len() > 128 {
        return Err(invalid("name", "must be 1 to 128 characters"));
    }
    // The scene: shipped (2D or 3D) or a file named relative to the exercise.
    let (scene, dim) = if needlesim_scene::EXAMPLES.iter().any(|e| e.0 == f.scene) {
        (SceneRef::Shipped(f.scene.clone()), 2)
    } else if needlesim_scene::EXAMPLES3D.iter().any(|e| e.0 == f.scene) {
        (SceneRef::Shipped(f.scene.clone()), 3)
    } else {
        let text = read(&f.scene).map_err(|e| invalid("scene", format!("'{}' is not a shipped scene, and {e}", f.scene)))?;
        let dim = needlesim_scene::scene_dim(&text).map_err(|e| invalid("scene", format!("{}: {e:#}", f.scene)))?;
        let p = base_dir.join(&f.scene);
        (SceneRef::File { file: f.scene.clone(), text, base_dir: p.parent().unwrap_or(base_dir).to_path_buf() }, dim)
    };
    let mut targets = Vec::new();
    if f.targets.len() > MAX_EXERCISE_TARGETS {
        return Err(invalid("targets", format!("{} targets, at most {MAX_EXERCISE_TARGETS}", f.targets.len())));
    }
    for (i, t) in f.targets.iter().enumerate() {
        let key = |k: &str| format!("targets[{i}].{k}");
        let tolerance = t.tolerance_m.map(|v| positive(&key("tolerance_m"), v)).transpose()?;
        let (name, source, radius) = match (&t.scene_target, &t.center_m) {
            (Some(s), None) => {
                if t.radius_m.is_some() {
                    return Err(invalid(key("radius_m"), "a scene target's radius is the scene's"));
                }
                (t.name.clone().unwrap_or_else(|| s.clone()), TargetSource::Scene(s.clone()), None)
            }
            (None, Some(c)) => {
                let centre = point(&key("center_m"), c, dim)?;
                let r =
                    positive(&key("radius_m"), t.radius_m.ok_or_else(|| invalid(key("radius_m"), "missing (a new target needs one)"))?)?;
                let name = t.name.clone().ok_or_else(|| invalid(key("name"), "missing (a new target needs one)"))?;
                (name, TargetSource::New { center_m: centre, radius_m: r }, Some(r))
            }
            (Some(_), Some(_)) => return Err(invalid(key("center_m"), "give either scene_target or center_m, not both")),
            (None, None) => return Err(invalid(key("scene_target"), "missing: name a scene target, or give center_m and radius_m")),
        };
        // A scene target's tolerance defaults to its radius, resolved when the scene loads (NaN until then).
        let tolerance_m = tolerance.or(radius).unwrap_or(f64::NAN);
        if targets.iter().any(|x: &ExerciseTarget| x.name == name) {
            return Err(invalid(key("name"), format!("'{name}' appears twice")));
        }
        targets.push(ExerciseTarget { name, source, tolerance_m });
    }
    if f.spare.len() > MAX_STRUCTURES {
        return Err(invalid("spare", format!("{} structures, at most {MAX_STRUCTURES}", f.spare.len())));
    }
    let mut spare = Vec::new();
    for (i, s) in f.spare.iter().enumerate() {
        let key = |k: &str| format!("spare[{i}].{k}");
        let shape = match s.shape.as_str() {
            "sphere" | "circle" => {
                if s.min_m.is_some() || s.max_m.is_some() {
                    return Err(invalid(key("min_m"), "a sphere has center_m and radius_m"));
                }
                let c = s.center_m.as_deref().ok_or_else(|| invalid(key("center_m"), "missing"))?;
                Shape::Sphere {
                    centre_m: point(&key("center_m"), c, dim)?,
                    radius_m: positive(&key("radius_m"), s.radius_m.ok_or_else(|| invalid(key("radius_m"), "missing"))?)?,
                }
            }
            "box" | "rectangle" => {
                if s.center_m.is_some() || s.radius_m.is_some() {
                    return Err(invalid(key("center_m"), "a box has min_m and max_m"));
                }
                let lo = point(&key("min_m"), s.min_m.as_deref().ok_or_else(|| invalid(key("min_m"), "missing"))?, dim)?;
                let hi = point(&key("max_m"), s.max_m.as_deref().ok_or_else(|| invalid(key("max_m"), "missing"))?, dim)?;
                if (0..dim as usize).any(|k| hi[k] <= lo[k]) {
                    return Err(invalid(key("max_m"), "every component must exceed min_m's"));
                }
                Shape::Box { min_m: lo, max_m: hi }
            }
            other => return Err(invalid(key("shape"), format!("'{other}': expected \"sphere\" (\"circle\") or \"box\" (\"rectangle\")"))),
        };
        let margin_m = positive(&key("margin_m"), s.margin_m.unwrap_or(0.002))?;
        if let Some(first) = spare.iter().position(|x: &Structure| x.name == s.name) {
            return Err(invalid(
                key("name"),
                format!("'{}' is already the name of spare[{first}]: structure names must be unique", s.name),
            ));
        }
        spare.push(Structure { name: s.name.clone(), shape, margin_m });
    }
    let l = &f.limits;
    let reinsertions = l.reinsertions.unwrap_or(3);
    if !(0..=1000).contains(&reinsertions) {
        return Err(invalid("limits.reinsertions", format!("{reinsertions} must be in 0..=1000")));
    }
    let penalty = l.penalty.unwrap_or(10.0);
    if !(penalty.is_finite() && (0.0..=100.0).contains(&penalty)) {
        return Err(invalid("limits.penalty", format!("{} must be in [0, 100]", num(penalty))));
    }
    let limits = Limits {
        time_s: positive("limits.time_s", l.time_s.unwrap_or(600.0))?,
        reinsertions: reinsertions as u32,
        peak_force_n: positive("limits.peak_force_n", l.peak_force_n.unwrap_or(5.0))?,
        penalty,
    };
    let w = &f.weights;
    let weight = |key: &str, v: Option<f64>, d: f64| -> Result<f64, ExerciseError> {
        let v = v.unwrap_or(d);
        if v.is_finite() && (0.0..=1e3).contains(&v) {
            Ok(v)
        } else {
            Err(invalid(format!("weights.{key}"), format!("{} must be in [0, 1000]", num(v))))
        }
    };
    let weights = Weights {
        accuracy: weight("accuracy", w.accuracy, 4.0)?,
        efficiency: weight("efficiency", w.efficiency, 1.0)?,
        path: weight("path", w.path, 1.0)?,
        force: weight("force", w.force, 1.0)?,
        safety: weight("safety", w.safety, 2.0)?,
        time: weight("time", w.time, 1.0)?,
    };
    if weights.accuracy + weights.efficiency + weights.path + weights.force + weights.safety + weights.time <= 0.0 {
        return Err(invalid("weights", "all are zero: at least one must be positive"));
    }
    let redirect_threshold_m = positive("metrics.redirect_threshold_m", f.metrics.redirect_threshold_m.unwrap_or(0.005))?;
    let damage_strain = positive("metrics.damage_strain", f.metrics.damage_strain.unwrap_or(DEFAULT_DAMAGE_STRAIN))?;
    let trajectory_csv = f.trajectory.as_deref().map(|t| read(t).map_err(|e| invalid("trajectory", e.to_string()))).transpose()?;
    let expert = f.expert.as_deref().map(|file| ExpertSource { file: file.to_owned(), text: read(file).map_err(|e| e.to_string()) });
    if let Some(x) = f.placed_at_s.iter().find(|x| !x.is_finite()) {
        return Err(invalid("placed_at_s", format!("{x} is not finite")));
    }
    if f.placed_at_s.windows(2).any(|w| w[1] < w[0]) {
        return Err(invalid("placed_at_s", "times must be in increasing order"));
    }
    Ok(Exercise {
        name: f.name,
        description: f.description.unwrap_or_default(),
        scene,
        dim,
        targets,
        spare,
        limits,
        weights,
        redirect_threshold_m,
        damage_strain,
        trajectory_csv,
        placed_at_s: f.placed_at_s,
        expert,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse_exercise(text, Path::new(".")).unwrap_err().to_string()
    }

    #[test]
    fn every_shipped_exercise_parses() {
        for (name, _, _) in EXERCISES {
            let ex = load_exercise(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(&ex.name, name);
            assert!(ex.trajectory_csv.is_some() && !ex.placed_at_s.is_empty(), "{name} ships a scripted run");
        }
    }

    #[test]
    fn errors_name_the_key() {
        let base = "name = \"x\"\nscene = \"fig3-target\"\n";
        assert!(err(&format!("{base}[[targets]]\nscene_target = \"biopsy\"\ntolerance_m = -1\n")).starts_with("targets[0].tolerance_m:"));
        assert!(
            err(&format!("{base}[[spare]]\nname = \"v\"\nshape = \"sphere\"\ncenter_m = [0.0, 0.0, 0.0]\nradius_m = 0.01\n"))
                .starts_with("spare[0].center_m: has 3 values, the scene is 2D")
        );
        assert!(err(&format!("{base}[[spare]]\nname = \"v\"\nshape = \"cone\"\n")).starts_with("spare[0].shape:"));
        assert!(
            err(&format!("{base}[[spare]]\nname = \"v\"\nshape = \"box\"\nmin_m = [0.0, 0.0]\nmax_m = [0.01, -0.01]\n"))
                .starts_with("spare[0].max_m:")
        );
        assert!(err(&format!("{base}[limits]\nreinsertions = -1\n")).starts_with("limits.reinsertions:"));
        assert!(
            err(&format!("{base}[weights]\naccuracy = 0\nefficiency = 0\npath = 0\nforce = 0\nsafety = 0\ntime = 0\n"))
                .starts_with("weights:")
        );
        assert!(err(&format!("{base}[metrics]\nredirect_threshold_m = nan\n")).starts_with("metrics.redirect_threshold_m:"));
        assert!(err(&format!("{base}[metrics]\ndamage_strain = 0\n")).starts_with("metrics.damage_strain: 0 must be"));
        assert!(err(&format!("{base}[[targets]]\nname = \"t\"\n")).starts_with("targets[0].scene_target: missing"));
        assert!(err("name = \"x\"\nscene = \"no-such-scene.toml\"\n").starts_with("scene: 'no-such-scene.toml' is not a shipped scene"));
        assert!(err(&format!("{base}bogus = 1\n")).contains("bogus"));
        assert!(err(&format!("{base}placed_at_s = [2.0, 1.0]\n")).starts_with("placed_at_s:"));
    }

    #[test]
    fn issue_35_two_structures_of_one_name_are_refused_naming_it() {
        let base = "name = \"x\"\nscene = \"fig3-target\"\n";
        let sphere =
            |name: &str, x: f64| format!("[[spare]]\nname = \"{name}\"\nshape = \"sphere\"\ncenter_m = [{x}, 0.05]\nradius_m = 0.003\n");
        let two = format!("{base}{}{}", sphere("vessel", 0.01), sphere("nerve", 0.02));
        assert_eq!(parse_exercise(&two, Path::new(".")).unwrap().spare.len(), 2);
        let e = err(&format!("{base}{}{}{}", sphere("vessel", 0.01), sphere("nerve", 0.02), sphere("vessel", 0.03)));
        assert!(e.starts_with("spare[2].name: 'vessel' is already the name of spare[0]"), "{e}");
    }

    #[test]
    fn issue_35_numbers_in_exercise_errors_are_short() {
        let base = "name = \"x\"\nscene = \"fig3-target\"\n";
        let e = err(&format!("{base}[[targets]]\nscene_target = \"biopsy\"\ntolerance_m = 1e300\n"));
        assert_eq!(e, "targets[0].tolerance_m: 1e300 must be finite and in (0, 1e6]");
        let e = err(&format!("{base}[weights]\naccuracy = -1e300\n"));
        assert_eq!(e, "weights.accuracy: -1e300 must be in [0, 1000]");
    }
}
