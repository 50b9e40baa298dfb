//! The `needlesim-server exercise run` command's work (the server's main.rs only parses the
//! arguments): run an exercise scripted, print the score, write the metrics JSON and the HTML
//! report.

use std::path::Path;

use anyhow::Context as _;
use needlesim_core::mesh::MeshLimits;

use crate::exercise::{EXERCISES, load_exercise};
use crate::report::report_html;
use crate::run::{read_trajectory, run_exercise};

/// Runs `exercise` (a shipped name or a TOML file) with `trajectory` (or its own) and the
/// placements `placed_at_s` (or its own); writes `report` (HTML) and `json` (metrics) when
/// given and prints a one-line summary on standard output.
pub fn run_command(
    exercise: &str,
    trajectory: Option<&Path>,
    placed_at_s: Option<&[f64]>,
    report: Option<&Path>,
    json: Option<&Path>,
    max_ticks: u64,
    limits: &MeshLimits,
) -> anyhow::Result<()> {
    let ex = load_exercise(exercise).with_context(|| format!("exercise {exercise}"))?;
    let csv = trajectory.map(read_trajectory).transpose()?;
    let run = run_exercise(&ex, csv.as_deref(), placed_at_s, max_ticks, limits).with_context(|| format!("exercise {}", ex.name))?;
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
