//! `needlesim-lab`: the offline lab tools, the step-time benchmark (`bench`), the motion suite
//! (`motions`) and the measurement pipeline (`identify …`). The only binary whose global allocator counts (for bench's
//! peak-memory figures); the real-time server runs on the system allocator.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use needlesim_lab::{bench, identify, motions, refine};

/// Counts heap bytes for `bench`'s peak-memory figures (relaxed atomic adds per allocation; no
/// thread turns allocation counting on).
#[global_allocator]
static ALLOC: needlesim_alloc_count::CountingAlloc = needlesim_alloc_count::CountingAlloc::new();

#[derive(Parser)]
#[command(name = "needlesim-lab", version, about = "Offline lab tools of needlesim: step-time benchmark and the measurement pipeline")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The measurement pipeline: marker tracking, E/ν identification, needle force distribution.
    Identify {
        #[command(subcommand)]
        command: identify::IdentifyCommand,
    },
    /// Step-time benchmark: ours (sparse columns on demand) vs a dense inverse vs a full solve per tick.
    Bench {
        /// Fewer sizes (19×19, 50×50, 100×100) and a faster script (50 mm/s, 0.2 s hold): about a minute at most.
        #[arg(long)]
        quick: bool,
        /// Print the results as one JSON object instead of a markdown table.
        #[arg(long)]
        json: bool,
        /// Write a log-log SVG plot of step p50 against mesh nodes.
        #[arg(long)]
        plot: Option<PathBuf>,
        /// Grid sizes (nodes per side), e.g. --sizes 19,50; default 19,50,100,200,400 (19,50,100 with --quick).
        #[arg(long, value_delimiter = ',')]
        sizes: Vec<usize>,
        /// Skip the static-solve comparison with SciPy.
        #[arg(long)]
        no_scipy: bool,
    },
    /// The motion suite (issue 15): vertical, oblique 40°, turning ±10°, flexible Fig. 4 path and
    /// bevel flip on several meshes; step p50/p99/p99.9/max, Jacobian, unconverged ticks, column
    /// misses and deferrals, d at the deepest point.
    Motions {
        /// Faster scripts (50 mm/s, 0.2 s hold, 0.4 s turning periods) on 19×19 and 100×100.
        #[arg(long)]
        quick: bool,
        /// Print the results as one JSON object instead of markdown.
        #[arg(long)]
        json: bool,
        /// Grid sizes (nodes per side); default 19,100,200,400 (19,100 with --quick).
        #[arg(long, value_delimiter = ',')]
        sizes: Vec<usize>,
        /// Motions to run (default: all).
        #[arg(long, value_delimiter = ',', value_enum)]
        motions: Vec<motions::Motion>,
        /// Contact model: material points (default) or the paper's node capture.
        #[arg(long, value_enum, default_value = "points")]
        contact: motions::ContactChoice,
        /// Material-point spacing (mm).
        #[arg(long, default_value_t = 2.0)]
        spacing_mm: f64,
        /// Nodes whose compliance columns are computed between two steps.
        #[arg(long, default_value_t = needlesim_offline::driver::DEFAULT_PREFETCH_NODES_PER_TICK)]
        prefetch_per_tick: usize,
        /// Also write the JSON object (with the slowest ticks' counters) to this file.
        #[arg(long)]
        json_out: Option<PathBuf>,
        /// Stop a case when its column cache (never evicted; 5.1 MB a node on 400×400) passes
        /// this many GB: bevel on 400×400 needs about 21 GB.
        #[arg(long)]
        max_column_gb: Option<f64>,
        /// Also write every tick of every case (counters and stage times) as CSV to this file.
        #[arg(long)]
        ticks_csv: Option<PathBuf>,
    },
    /// The mesh-refinement study (issue 19): the paper phantom, Fig. 3 and Fig. 4 on grids
    /// h, h/2, h/4, h/8 (the shipped grid is h/2… see `refine` module docs) with each contact
    /// model; peak puncture force, mean cutting force, sawtooth, closest approach.
    Refine {
        /// Models to compare: nodes, points, toughness, width (default: all four).
        #[arg(long, value_delimiter = ',')]
        models: Vec<String>,
        /// Scenes (default: paper-phantom,fig3-target,fig4-steering).
        #[arg(long, value_delimiter = ',')]
        scenes: Vec<String>,
        /// Only the first N grids of each scene (coarsest first; default 4, at most 5).
        #[arg(long, default_value_t = 4)]
        grids: usize,
    },
}

fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_env_filter(tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "info".into()))
        .init();
    let result = match Cli::parse().command {
        Command::Bench { quick, json, plot, sizes, no_scipy } => run_bench(bench::BenchOptions { quick, sizes, plot, no_scipy }, json),
        Command::Motions { quick, json, sizes, motions, contact, spacing_mm, prefetch_per_tick, json_out, max_column_gb, ticks_csv } => {
            run_motions(
                motions::MotionOptions {
                    quick,
                    sizes,
                    motions,
                    contact,
                    spacing_m: spacing_mm * 1e-3,
                    prefetch_nodes_per_tick: prefetch_per_tick,
                    progress: true,
                    max_column_bytes: max_column_gb.map(|gb| (gb * 1e9) as usize),
                },
                json,
                json_out,
                ticks_csv,
            )
        }
        Command::Identify { command } => identify::run(command),
        Command::Refine { models, scenes, grids } => run_refine(&models, &scenes, grids),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run_bench(opts: bench::BenchOptions, json: bool) -> Result<()> {
    let (value, markdown) = bench::run(&opts)?;
    if json {
        println!("{}", serde_json::to_string(&value)?);
    } else {
        print!("{markdown}");
    }
    Ok(())
}

fn run_motions(opts: motions::MotionOptions, json: bool, json_out: Option<PathBuf>, ticks_csv: Option<PathBuf>) -> Result<()> {
    let suite = motions::run_suite(&opts)?;
    if let Some(path) = ticks_csv {
        std::fs::write(&path, motions::ticks_csv(&suite)).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let value = motions::to_json(&suite, &opts);
    if let Some(path) = json_out {
        std::fs::write(&path, serde_json::to_string_pretty(&value)?).with_context(|| format!("cannot write {}", path.display()))?;
    }
    if json {
        println!("{}", serde_json::to_string(&value)?);
    } else {
        print!("{}", motions::to_markdown(&suite, &opts));
    }
    Ok(())
}

fn run_refine(models: &[String], scenes: &[String], grids: usize) -> Result<()> {
    let models = if models.is_empty() {
        vec!["nodes".to_owned(), "points".to_owned(), "toughness".to_owned(), "width".to_owned()]
    } else {
        models.to_vec()
    };
    let models = models.iter().map(|m| refine::Model::parse(m)).collect::<Result<Vec<_>>>()?;
    let scenes =
        if scenes.is_empty() { vec!["paper-phantom".into(), "fig3-target".into(), "fig4-steering".into()] } else { scenes.to_vec() };
    let mut studies = Vec::new();
    for name in &scenes {
        let figure = refine::Figure::parse(name)?;
        studies.push(refine::study(figure, &models, grids, |line| eprintln!("{line}"))?);
    }
    print!("{}", refine::to_markdown(&studies));
    Ok(())
}
