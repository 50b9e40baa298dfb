//! The `needlesim-server exercise run` command's work (the server's main.rs only parses the
//! arguments): run an exercise scripted, print the score, write the metrics JSON and the HTML
//! report.

use std::path::Path;

use anyhow::Context as _;
use needlesim_core::mesh::MeshLimits;

use crate::exercise::{EXERCISES, ExpertSource, load_exercise};
use crate::report::report_html;
use crate::run::{RunOptions, read_trajectory, run_exercise_with};

/// `exercise run`'s arguments.
pub struct RunCommand<'a> {
    /// A shipped exercise's name or a TOML file.
    pub exercise: &'a str,
    /// The base trajectory (default: the exercise's own).
    pub trajectory: Option<&'a Path>,
    /// When "placed" is declared (default: the exercise's own).
    pub placed_at_s: Option<&'a [f64]>,
    /// The HTML report to write.
    pub report: Option<&'a Path>,
    /// The metrics JSON to write.
    pub json: Option<&'a Path>,
    /// The expert run to overlay instead of the exercise's own (a tick series CSV).
    pub expert: Option<&'a Path>,
    /// Where to write this run's tick series CSV (an expert run for later comparisons).
    pub ticks: Option<&'a Path>,
    /// Keep every n-th tick in `ticks` (≥ 1).
    pub ticks_every: u64,
    pub max_ticks: u64,
}

/// Runs the exercise ([`RunCommand`]); writes the report (HTML), the metrics (JSON) and the
/// tick series (CSV) when asked and prints a one-line summary on standard output.
pub fn run_command(cmd: &RunCommand<'_>, limits: &MeshLimits) -> anyhow::Result<()> {
    let exercise = cmd.exercise;
    let (trajectory, placed_at_s, report, json, max_ticks) = (cmd.trajectory, cmd.placed_at_s, cmd.report, cmd.json, cmd.max_ticks);
    let mut ex = load_exercise(exercise).with_context(|| format!("exercise {exercise}"))?;
    if let Some(p) = cmd.expert {
        ex.expert = Some(ExpertSource {
            file: p.display().to_string(),
            text: needlesim_scene::read_local_file(p, needlesim_scene::MAX_LOCAL_FILE_BYTES).map_err(|e| match e {
                needlesim_scene::LocalFileError::Io { source, .. } => format!("cannot read it: {source}"),
                needlesim_scene::LocalFileError::Refused { problem, .. } => format!("cannot read it: {problem}"),
            }),
        });
    }
    if cmd.ticks_every == 0 {
        anyhow::bail!("--ticks-every: 0 must be at least 1");
    }
    let csv = trajectory.map(read_trajectory).transpose()?;
    let opts = RunOptions { ticks_every: cmd.ticks.map(|_| cmd.ticks_every) };
    let run =
        run_exercise_with(&ex, csv.as_deref(), placed_at_s, max_ticks, limits, opts).with_context(|| format!("exercise {}", ex.name))?;
    if let (Some(p), Some(text)) = (cmd.ticks, &run.ticks_csv) {
        std::fs::write(p, text).with_context(|| format!("cannot write {}", p.display()))?;
    }
    if let Some(p) = json {
        let text = serde_json::to_string_pretty(&run)?;
        std::fs::write(p, text).with_context(|| format!("cannot write {}", p.display()))?;
    }
    if let Some(p) = report {
        let html = report_html(&run).map_err(|e| anyhow::anyhow!("report plot: {e}"))?;
        std::fs::write(p, html).with_context(|| format!("cannot write {}", p.display()))?;
    }
    let m = &run.result.metrics;
    println!(
        "{}: score {:.1}/100, {} insertion(s), {} redirection(s), path {:.2} mm, peak force {:.3} N, {} of {} target(s) on target",
        run.exercise,
        run.result.score.total,
        m.insertions,
        m.redirections,
        m.path_length_m * 1e3,
        m.peak_axial_force_n,
        m.targets.iter().filter(|t| t.placement.is_some_and(|p| p.on_target)).count(),
        m.targets.len()
    );
    Ok(())
}

/// The shipped exercises' names and descriptions, one a line.
pub fn list() -> String {
    let mut s = String::new();
    for (name, _, _) in EXERCISES {
        let d = load_exercise(name).map(|e| e.description).unwrap_or_else(|e| format!("(does not load: {e})"));
        s.push_str(&format!("{name}\t{d}\n"));
    }
    s
}

/// `exercise list`: prints [`list`].
pub fn list_command() -> anyhow::Result<()> {
    print!("{}", list());
    Ok(())
}
