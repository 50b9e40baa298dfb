//! `needlesim-server`: the needlesim server and its offline commands.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use needlesim_core::MeshLimits;

use needlesim_offline::{plan, simulate, simulate3};
use needlesim_scene::{self as scene, exchange};
use needlesim_server::{agones, grpc, serve};

#[derive(Parser)]
#[command(name = "needlesim-server", version, about = "Real-time needle insertion simulator: server and offline tools")]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// With no command: the server's options (see `serve --help`).
    #[command(flatten)]
    serve: ServeArgs,
    #[command(flatten)]
    limits: LimitArgs,
}

#[derive(Args, Clone, Copy)]
struct LimitArgs {
    /// Largest mesh accepted, in nodes.
    #[arg(long, global = true, default_value_t = MeshLimits::default().max_nodes)]
    max_nodes: usize,
    /// Largest mesh accepted, in triangles.
    #[arg(long, global = true, default_value_t = MeshLimits::default().max_triangles)]
    max_triangles: usize,
}

#[derive(Args, Clone)]
struct ServeArgs {
    /// Address and port to listen on.
    #[arg(long, default_value = "127.0.0.1:50051")]
    listen: std::net::SocketAddr,
    /// Where recordings and other data are written.
    #[arg(long, default_value = "needlesim-data")]
    data_dir: PathBuf,
    /// The static files of the web viewer.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../web"))]
    web_dir: PathBuf,
    /// PEM certificate chain: with --tls-key, serve over TLS.
    #[arg(long, requires = "tls_key")]
    tls_cert: Option<PathBuf>,
    /// PEM private key for --tls-cert.
    #[arg(long, requires = "tls_cert")]
    tls_key: Option<PathBuf>,
    /// Most sessions at once.
    #[arg(long, default_value_t = 16)]
    max_sessions: usize,
    /// Most streams open on one session: its Observe, WatchScore, WatchUltrasound and GetReport
    /// calls count together; one more is refused with RESOURCE_EXHAUSTED.
    #[arg(long, default_value_t = 256)]
    max_observers: usize,
    /// Most server-streaming calls open at once on the whole server (Observe, WatchScore,
    /// WatchUltrasound, GetReport, DownloadRecording); one more is refused with RESOURCE_EXHAUSTED.
    #[arg(long, default_value_t = grpc::ServerLimits::default().max_streams)]
    max_streams: usize,
    /// Most connections open at once on the gRPC port; one more is closed at once. Default: half
    /// the limit of open files (`ulimit -n`), at most 4096.
    #[arg(long, value_name = "N")]
    max_connections: Option<usize>,
    /// A connection whose first request (its headers, over HTTP/2, HTTP/1.1 or TLS) has not
    /// arrived within this time is closed, in ms; so is an HTTP/1.1 connection without a next
    /// request this long after a response, and an HTTP/1.1 request body that sends nothing this
    /// long is ended. HTTP/2 streams (Control) are never timed out.
    #[arg(long, value_name = "MS", default_value_t = 5000, value_parser = clap::value_parser!(u64).range(1..))]
    handshake_timeout_ms: u64,
    /// At shutdown, how long connections may stay open once the sessions are closed and their
    /// recordings finished, ms; then the server exits without them (a client that never reads a
    /// stream or never ends a request body cannot hold it).
    #[arg(long, value_name = "MS", default_value_t = 3000)]
    shutdown_grace_ms: u64,
    /// Most HTTP/2 streams (calls) open at once on one connection (SETTINGS_MAX_CONCURRENT_STREAMS);
    /// a client opens more only as earlier ones end.
    #[arg(long, value_name = "N", default_value_t = needlesim_server::listener::DEFAULT_MAX_STREAMS_PER_CONNECTION,
          value_parser = clap::value_parser!(u32).range(1..))]
    max_streams_per_connection: u32,
    /// Most bytes of request messages received but not yet complete, over all calls of the
    /// server, MiB (at least --max-message-bytes); a call whose message would pass it fails with
    /// RESOURCE_EXHAUSTED. Also: a message that stops arriving for --handshake-timeout-ms is ended.
    #[arg(long, value_name = "MIB", default_value_t = needlesim_server::listener::DEFAULT_MAX_PENDING_REQUEST_MIB)]
    max_pending_request_mb: u64,
    /// Most MiB of complete gRPC answers (every unary answer) held for clients that have not read
    /// them, over the whole server; one more is answered RESOURCE_EXHAUSTED.
    #[arg(long, value_name = "MIB", default_value_t = 256)]
    max_held_answers_mb: u64,
    /// How long a client has to take such an answer whole, ms; then it is dropped (the call's
    /// stream is reset). Also how long an offline job (Simulate, Plan, Identify) waits for its
    /// client to take its next message; then it stops, frees its slot and its stream ends with
    /// DEADLINE_EXCEEDED.
    #[arg(long, value_name = "MS", default_value_t = 30_000, value_parser = clap::value_parser!(u64).range(1..))]
    answer_deadline_ms: u64,
    /// Largest gRPC message accepted, in bytes.
    #[arg(long, default_value_t = 64 << 20)]
    max_message_bytes: usize,
    /// Largest estimated memory of one session's scene, MiB (mesh, factor and the compliance
    /// columns of a full needle; docs/guide/security.md). Also bounds the scenes of
    /// Simulate, Plan and Identify calls.
    #[arg(long, default_value_t = grpc::ServerLimits::default().max_session_bytes >> 20)]
    max_session_memory_mb: u64,
    /// Longest Simulate call (and each simulation of a plan), in ticks (1 to 10⁷).
    #[arg(long, default_value_t = grpc::ServerLimits::default().max_simulate_ticks, value_parser = clap::value_parser!(u64).range(1..=needlesim_offline::MAX_TICKS_LIMIT))]
    max_simulate_ticks: u64,
    /// Offline calls (Simulate, Plan, every Identify call) running at once; more are refused with
    /// RESOURCE_EXHAUSTED.
    #[arg(long, default_value_t = grpc::ServerLimits::default().max_offline_jobs)]
    max_offline_jobs: usize,
    /// Plans running at once (each also takes an offline job slot).
    #[arg(long, default_value_t = grpc::ServerLimits::default().max_plans)]
    max_plans: usize,
    /// Largest image a Track call decodes, in pixels (width × height from the PNG header).
    #[arg(long, default_value_t = grpc::ServerLimits::default().max_image_pixels)]
    max_image_pixels: u64,
    /// Most recordings (`.mcap` files) in `<data-dir>/recordings/`: StartRecording is refused
    /// with RESOURCE_EXHAUSTED when it holds this many.
    #[arg(long, value_name = "N", default_value_t = grpc::ServerLimits::default().max_recordings)]
    max_recordings: usize,
    /// Most MiB in `<data-dir>/recordings/`: StartRecording is refused when too little is left
    /// to start (512 KiB), and a recording that would grow past the limit is stopped and finished.
    #[arg(long, value_name = "MIB", default_value_t = grpc::ServerLimits::default().max_recordings_bytes >> 20)]
    max_recordings_mb: u64,
    /// Most after-action reports (`.html` files) in `<data-dir>/reports/`: ending an exercise
    /// whose report would pass it answers RESOURCE_EXHAUSTED and writes no report.
    #[arg(long, value_name = "N", default_value_t = grpc::ServerLimits::default().max_reports)]
    max_reports: usize,
    /// Most MiB in `<data-dir>/reports/` (as --max-reports).
    #[arg(long, value_name = "MIB", default_value_t = grpc::ServerLimits::default().max_reports_bytes >> 20)]
    max_reports_mb: u64,
    /// How long a Control or Control3 stream may wait for its first message, ms; then it ends
    /// with DEADLINE_EXCEEDED.
    #[arg(long, value_name = "MS", default_value_t = grpc::ServerLimits::default().control_first_message_ms,
          value_parser = clap::value_parser!(u64).range(1..))]
    control_first_message_ms: u64,
    /// A session that nobody drives (no pose from a client or its device), watches (no open
    /// stream) or holds control of for this long is closed as CloseSession closes it (its
    /// recording finished, an exercise's report written), in s; 0: never. The default session
    /// (--default-scene) is never closed this way.
    #[arg(long, value_name = "S", default_value_t = grpc::ServerLimits::default().session_idle_timeout_s)]
    session_idle_timeout_s: u64,
    /// The example scene of the default session ("none" for no default session).
    #[arg(long, default_value = "paper-phantom")]
    default_scene: String,
    /// Play the default scene's insertion in a loop until someone takes control, and print the
    /// URL to open.
    #[arg(long)]
    demo: bool,
    /// Start a session of this shipped exercise (issue 20: biopsy-2d, brachy-2d, spare-2d,
    /// biopsy-3d, brachy-3d, spare-3d) and print the viewer's URLs for the trainee, the instructor
    /// and observers.
    #[arg(long, value_name = "NAME")]
    exercise: Option<String>,
    /// A file holding the admin token (one line, at least 16 characters), which lists and
    /// downloads every recording. Without it, a recording opens only with its session's tokens.
    #[arg(long, value_name = "FILE")]
    admin_token_file: Option<PathBuf>,
    /// SCHED_FIFO priority of the sessions' real-time threads (1..99; 0 = normal scheduling).
    /// Needs CAP_SYS_NICE or root; without it the server says so and runs at normal priority.
    #[arg(long, default_value_t = 40)]
    rt_priority: i32,
    /// How long before each tick's deadline the sessions' real-time threads stop sleeping and
    /// spin, in µs (0: sleep to the deadline, never spin). Spinning wakes the tick on time (a sleep
    /// alone wakes tens of µs late, more under load) at the cost of the margin's worth of a core
    /// per session every tick: 150 µs at 1 kHz is 15 % of a core per session.
    #[arg(long, value_name = "US", default_value_t = needlesim_session::DEFAULT_SPIN_MARGIN.as_micros() as u64)]
    spin_margin_us: u64,
    /// The Agones game-server integration (`--agones` and its options; docs/guide/fleet.md).
    #[command(flatten)]
    fleet: agones::AgonesArgs,
    /// Serve live sessions to the Foxglove app over its WebSocket protocol on this address
    /// (e.g. 127.0.0.1:8765; port 0 picks one). Off by default. The protocol carries no
    /// tokens: every live session is visible to whoever reaches the port — keep it on loopback
    /// or a trusted network.
    #[arg(long, value_name = "ADDR")]
    foxglove_addr: Option<std::net::SocketAddr>,
    /// Connections the Foxglove endpoint holds at once (more are closed at once; a connection
    /// without a WebSocket handshake within 5 s is closed too).
    #[arg(long, value_name = "N", default_value_t = needlesim_foxglove::LiveOptions::default().max_clients)]
    foxglove_max_clients: usize,
}

#[derive(Subcommand)]
// Parsed once at start-up: the size of the `serve` variant (its many options) costs nothing.
#[allow(clippy::large_enum_variant)]
enum Command {
    /// Start the gRPC server (the default when no command is given).
    Serve(ServeArgs),
    /// Print a summary of the paper-phantom insertion, offline.
    Summary,
    /// Solve a static problem in the exchange format of the validation suite (2D, or 3D with `"dim": 3`).
    Solve {
        /// The scenario JSON (nodes, triangles or tetrahedra, E, nu, fixed_nodes, prescribed, loads, points, …).
        scenario: PathBuf,
        /// Where to write the result JSON (standard output when absent).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Run a scripted insertion through the real-time step function, offline (2D, or 3D for a
    /// scene with `dim = 3`).
    Simulate {
        /// A scene TOML file, or a shipped example's name (paper-phantom, fig3-target; 3D:
        /// cube-phantom-3d, brachy-3d, fig3-target-3d).
        #[arg(long)]
        scene: String,
        /// The base trajectory CSV (2D: t_s,x_m,y_m,theta_rad; 3D: t_s,x_m,y_m,z_m,qw,qx,qy,qz);
        /// defaults to the scene's own.
        #[arg(long)]
        trajectory: Option<PathBuf>,
        /// Where to write the time series CSV (standard output when absent).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Write the final state as a static problem in the validation exchange format.
        #[arg(long)]
        dump_state: Option<PathBuf>,
        /// 3D scenes: also dump the state at these ticks (the CSV's `tick` column), one file
        /// per tick, `state-<tick>.json` in the directory of --dump-state.
        #[arg(long, value_delimiter = ',', value_name = "TICK,...")]
        dump_at: Option<Vec<u64>>,
        /// The longest run, in ticks (the server's Simulate limit by default): a trajectory
        /// lasting longer is an error naming its last line.
        #[arg(long, default_value_t = simulate::DEFAULT_MAX_TICKS, value_parser = clap::value_parser!(u64).range(1..=needlesim_offline::MAX_TICKS_LIMIT))]
        max_ticks: u64,
        /// Keep ticks whose step did not converge (the stick/slip iteration or the flexible
        /// needle's shape passes at their cap), marked 0 in a last CSV column `converged`;
        /// without it the first such tick stops the run with an error naming it.
        #[arg(long)]
        keep_unconverged: bool,
    },
    /// Plan an insertion that reaches a target despite the tissue deformation it causes.
    Plan(PlanArgs),
    /// Convert a VTK mesh (.vtu, ASCII .vtk; tetrahedra, or triangles in 2D) with integer cell
    /// labels to Gmsh MSH 4.1 whose physical groups are named by the labels.
    Mesh {
        /// The input mesh (.vtu or .vtk; labelmaps .nii/.nii.gz/.nrrd are not yet supported).
        input: PathBuf,
        /// The labels' names: LABEL=NAME,... (e.g. 1=tissue,2=lesion,11=back); every label of
        /// the file must be named.
        #[arg(long)]
        labels: String,
        /// The cell-data array holding the labels (default: gmsh:physical, CellEntityIds,
        /// labels or region, the first present).
        #[arg(long)]
        label_array: Option<String>,
        /// The MSH file to write.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Training exercises (needlesim-training): `run` one scripted, `list` the shipped ones.
    #[command(subcommand)]
    Exercise(ExerciseCommand),
}

#[derive(Subcommand)]
enum ExerciseCommand {
    /// Run an exercise scripted: metrics, score and the after-action report.
    Run {
        /// An exercise TOML file, or a shipped exercise's name (`exercise list`).
        exercise: String,
        /// The base trajectory CSV (defaults to the exercise's own).
        #[arg(long)]
        trajectory: Option<PathBuf>,
        /// Times (s) at which "placed" is declared (defaults to the exercise's own).
        #[arg(long, value_delimiter = ',', value_name = "T1,T2,...")]
        placed_at: Option<Vec<f64>>,
        /// Where to write the after-action report (HTML).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Where to write the metrics (JSON).
        #[arg(long)]
        json: Option<PathBuf>,
        /// An expert's run to overlay in the report (a tick series CSV written by --ticks),
        /// instead of the one the exercise names.
        #[arg(long)]
        expert: Option<PathBuf>,
        /// Where to write this run's tick series CSV (usable later as an expert run).
        #[arg(long)]
        ticks: Option<PathBuf>,
        /// Keep every n-th tick in --ticks (placements and the last tick always kept).
        #[arg(long, default_value_t = 1)]
        ticks_every: u64,
        #[arg(long, default_value_t = simulate::DEFAULT_MAX_TICKS, value_parser = clap::value_parser!(u64).range(1..=needlesim_offline::MAX_TICKS_LIMIT))]
        max_ticks: u64,
    },
    /// List the shipped exercises.
    List,
}

/// `plan`'s arguments; absent ones take the scene's planning example's values (server/scenes/fig3-plan.toml).
#[derive(Args)]
struct PlanArgs {
    /// A scene TOML file, or a shipped example's name (fig3-target).
    #[arg(long)]
    scene: String,
    /// The target's name in the scene.
    #[arg(long)]
    target: String,
    /// The allowed entry segment on the tissue surface, x1,y1,x2,y2 in metres (default: the
    /// scene's planning example, for fig3-target server/scenes/fig3-plan.toml).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_name = "X1,Y1,X2,Y2")]
    entry: Option<Vec<f64>>,
    /// The allowed needle angles min,max in degrees (base pose theta: base→tip, counter-clockwise
    /// from +x; default: the planning example's when --entry is absent too, else any).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_name = "MIN,MAX")]
    angles_deg: Option<Vec<f64>>,
    /// The insertion speed in mm/s (default: the planning example's, else 10).
    #[arg(long)]
    speed_mm_s: Option<f64>,
    /// 3D scenes: the entry point x,y,z in metres, on a face of the mesh's bounding box
    /// (default: the scene's 3D planning example's, server/scenes/behind-vessel-plan.toml).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_name = "X,Y,Z")]
    entry_point: Option<Vec<f64>>,
    /// 3D scenes: how far the entry may move on its face to clear the structures, metres.
    #[arg(long)]
    entry_radius_m: Option<f64>,
    /// 3D scenes: sphere regions of the scene to keep clear of (comma-separated names).
    #[arg(long, value_delimiter = ',')]
    avoid: Option<Vec<String>>,
    /// 3D scenes: the clearance to keep from them, metres.
    #[arg(long)]
    clearance_m: Option<f64>,
    /// Write the plan's base trajectory (t_s,x_m,y_m,theta_rad; in 3D t_s,x_m,y_m,z_m,qw,qx,qy,qz),
    /// replayable by `simulate`.
    #[arg(long)]
    trajectory_out: Option<PathBuf>,
    /// Print the plan as one JSON object.
    #[arg(long)]
    json: bool,
    /// Worker threads (0: one per core).
    #[arg(long, default_value_t = 0)]
    threads: usize,
}

fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        // Colour only on a terminal: logs piped to a file or a collector stay plain text.
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_env_filter(tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| "info".into()))
        .init();
    let cli = Cli::parse();
    let limits = MeshLimits { max_nodes: cli.limits.max_nodes, max_triangles: cli.limits.max_triangles };
    let result = match cli.command {
        Some(Command::Solve { scenario, output }) => solve(&scenario, output.as_deref(), &limits),
        Some(Command::Simulate { scene, trajectory, output, dump_state, dump_at, max_ticks, keep_unconverged }) => {
            let convergence = needlesim_offline::ConvergencePolicy::keeping(keep_unconverged);
            match is_3d_scene(&scene) {
                Ok(true) => run_simulate3(
                    &scene,
                    trajectory.as_deref(),
                    output.as_deref(),
                    dump_state.as_deref(),
                    dump_at.as_deref().unwrap_or_default(),
                    (max_ticks, convergence),
                    &limits,
                ),
                Ok(false) if dump_at.is_some() => Err(anyhow::anyhow!("--dump-at is for 3D scenes (dim = 3); scene '{scene}' is 2D")),
                Ok(false) => {
                    run_simulate(&scene, trajectory.as_deref(), output.as_deref(), dump_state.as_deref(), (max_ticks, convergence), &limits)
                }
                Err(e) => Err(e),
            }
        }
        Some(Command::Plan(args)) => match is_3d_scene(&args.scene) {
            Ok(true) => run_plan3(&args, &limits),
            Ok(false) => run_plan(&args, &limits),
            Err(e) => Err(e),
        },
        Some(Command::Exercise(ExerciseCommand::Run {
            exercise,
            trajectory,
            placed_at,
            output,
            json,
            expert,
            ticks,
            ticks_every,
            max_ticks,
        })) => needlesim_training::cli::run_command(
            &needlesim_training::cli::RunCommand {
                exercise: &exercise,
                trajectory: trajectory.as_deref(),
                placed_at_s: placed_at.as_deref(),
                report: output.as_deref(),
                json: json.as_deref(),
                expert: expert.as_deref(),
                ticks: ticks.as_deref(),
                ticks_every,
                max_ticks,
            },
            &limits,
        ),
        Some(Command::Exercise(ExerciseCommand::List)) => needlesim_training::cli::list_command(),
        Some(Command::Mesh { input, labels, label_array, output }) => mesh(&input, &labels, label_array, &output),
        Some(Command::Summary) => summary(&limits),
        Some(Command::Serve(args)) => run_serve(args, &limits),
        None => run_serve(cli.serve, &limits),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// The `mesh` command: reads, converts and checks (needlesim_scene::vtk::convert_to_msh), writes.
fn mesh(input: &std::path::Path, labels: &str, label_array: Option<String>, output: &std::path::Path) -> Result<()> {
    use needlesim_scene::vtk;
    let name = input.display().to_string();
    vtk::check_mesh_input(&name)?;
    let opts = vtk::VtkOptions { labels: vtk::LabelMap::parse_list(labels)?, label_array };
    let text = read_local(input)?;
    let c = vtk::convert_to_msh(&name, &text, &opts).with_context(|| name.clone())?;
    std::fs::write(output, &c.msh).with_context(|| format!("cannot write {}", output.display()))?;
    let regions: Vec<String> =
        c.mesh.regions.iter().zip(c.mesh.region_measures()).map(|((l, n), v)| format!("{l}={n} ({v:.6e})")).collect();
    let sets: Vec<String> = c.mesh.boundary.iter().map(|(l, n, cells)| format!("{l}={n} ({} cells)", cells.len())).collect();
    println!(
        "{}: {}D, {} nodes, {} elements; regions (label=name (measure)): {}; boundary sets: {}; labels from '{}'",
        output.display(),
        c.mesh.dim,
        c.mesh.nodes_m.len(),
        c.mesh.elements.len(),
        regions.join(", "),
        if sets.is_empty() { "none".to_owned() } else { sets.join(", ") },
        c.mesh.label_array
    );
    Ok(())
}

fn solve(scenario: &std::path::Path, output: Option<&std::path::Path>, limits: &MeshLimits) -> Result<()> {
    let text = read_local(scenario)?;
    let sc = exchange::parse_any_scenario(&text).with_context(|| format!("{} is not a valid scenario", scenario.display()))?;
    let t0 = std::time::Instant::now();
    let result = exchange::solve_any(&sc, limits).with_context(|| format!("{}", scenario.display()))?;
    tracing::info!(
        scenario = %scenario.display(),
        n_nodes = result.n_nodes(),
        strain_energy_j = result.strain_energy(),
        max_abs_displacement_m = result.max_abs_displacement(),
        elapsed_ms = t0.elapsed().as_secs_f64() * 1e3,
        "solved"
    );
    let json = serde_json::to_string(&result)?;
    match output {
        Some(p) => std::fs::write(p, json).with_context(|| format!("cannot write {}", p.display()))?,
        None => println!("{json}"),
    }
    Ok(())
}

fn run_simulate(
    scene_spec: &str,
    trajectory: Option<&std::path::Path>,
    output: Option<&std::path::Path>,
    dump: Option<&std::path::Path>,
    (max_ticks, convergence): (u64, needlesim_offline::ConvergencePolicy),
    limits: &MeshLimits,
) -> Result<()> {
    let scene = scene::load_scene(scene_spec, limits)?;
    let traj = match (trajectory, scene.example_trajectory) {
        (Some(p), _) => {
            let text = read_local(p)?;
            scene::Trajectory::parse_csv(&text).with_context(|| format!("{}", p.display()))?
        }
        (None, Some(text)) => scene::Trajectory::parse_csv(text)?,
        (None, None) => anyhow::bail!("--trajectory is needed: scene '{scene_spec}' is not a shipped example with its own"),
    };
    let mut csv = String::new();
    let t0 = std::time::Instant::now();
    let (sim, summary) = simulate::run(&scene, &traj, max_ticks, convergence, Some(&mut csv))?;
    let mut times = summary.step_times_s.clone();
    times.sort_by(f64::total_cmp);
    let pct = |q: f64| times.get(((times.len() as f64 - 1.0) * q).round() as usize).copied().unwrap_or(0.0) * 1e6;
    tracing::info!(
        scene = %scene.name,
        n_nodes = scene.tissue.mesh().n_nodes(),
        ticks = summary.ticks,
        step_p50_us = pct(0.5),
        step_p99_us = pct(0.99),
        step_max_us = pct(1.0),
        column_misses = summary.column_misses,
        column_deferrals = summary.column_deferrals,
        prefetched_columns = summary.prefetched_columns,
        clamped_ticks = summary.clamped_ticks,
        unconverged_ticks = summary.unconverged_ticks,
        active_set_capped_ticks = summary.active_set_capped_ticks,
        shape_capped_ticks = summary.shape_capped_ticks,
        patch_fallbacks = summary.patch_fallbacks,
        wall_s = t0.elapsed().as_secs_f64(),
        "simulated"
    );
    if summary.active_set_capped_ticks + summary.shape_capped_ticks > 0 {
        tracing::warn!(
            "{} ticks ended at the stick/slip iteration cap and {} at the flexible needle's shape-pass cap: their contact conditions or needle shape are the last iterate, not converged (kept by --keep-unconverged: the CSV's converged column is 0 there)",
            summary.active_set_capped_ticks,
            summary.shape_capped_ticks
        );
    }
    match output {
        Some(p) => std::fs::write(p, &csv).with_context(|| format!("cannot write {}", p.display()))?,
        None => print!("{csv}"),
    }
    if let Some(p) = dump {
        let state = simulate::dump_state(&scene, &sim);
        std::fs::write(p, serde_json::to_string(&state)?).with_context(|| format!("cannot write {}", p.display()))?;
    }
    Ok(())
}

/// Whether a scene spec names a 3D scene: a shipped 3D example, or a file whose `dim` is 3.
fn is_3d_scene(spec: &str) -> Result<bool> {
    if scene::EXAMPLES3D.iter().any(|e| e.0 == spec) {
        return Ok(true);
    }
    let path = std::path::Path::new(spec);
    if !std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        return Ok(false); // a link, a device, a FIFO: the 2D loader names the problem
    }
    let text = read_local(path)?;
    Ok(scene::scene_dim(&text).with_context(|| format!("scene {}", path.display()))? == 3)
}

/// `simulate` for a 3D scene ([`simulate3`]).
fn run_simulate3(
    scene_spec: &str,
    trajectory: Option<&std::path::Path>,
    output: Option<&std::path::Path>,
    dump: Option<&std::path::Path>,
    dump_at: &[u64],
    (max_ticks, convergence): (u64, needlesim_offline::ConvergencePolicy),
    limits: &MeshLimits,
) -> Result<()> {
    if !dump_at.is_empty() && dump.is_none() {
        anyhow::bail!("--dump-at needs --dump-state (its files go next to it, state-<tick>.json)");
    }
    let scene = scene::load_scene3d(scene_spec, limits)?;
    let traj = match (trajectory, &scene.trajectory) {
        (Some(p), _) => {
            let text = read_local(p)?;
            if text
                .lines()
                .find(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
                .is_some_and(|h| h.split(',').map(str::trim).eq(["t_s", "x_m", "y_m", "theta_rad"]))
            {
                anyhow::bail!(
                    "--trajectory {}: a 2D trajectory (t_s,x_m,y_m,theta_rad) for the 3D scene '{}': a 3D scene needs t_s,x_m,y_m,z_m,qw,qx,qy,qz",
                    p.display(),
                    scene.name
                );
            }
            scene::Trajectory3::parse_csv(&text).with_context(|| format!("--trajectory {}", p.display()))?
        }
        (None, Some(t)) => t.clone(),
        (None, None) => anyhow::bail!("--trajectory is needed: 3D scene '{scene_spec}' names no trajectory file"),
    };
    let mut ticks: Vec<u64> = dump_at.to_vec();
    let last_k = ((traj.span_s().1 - traj.span_s().0) * scene.tick_rate_hz).round() as u64;
    if dump.is_some() {
        ticks.push(last_k);
    }
    ticks.sort_unstable();
    ticks.dedup();
    let mut csv = String::new();
    let t0 = std::time::Instant::now();
    let (_sim, summary, dumps) = simulate3::run3(&scene, &traj, max_ticks, &ticks, convergence, Some(&mut csv))?;
    let mut times = summary.step_times_s.clone();
    times.sort_by(f64::total_cmp);
    let pct = |q: f64| times.get(((times.len() as f64 - 1.0) * q).round() as usize).copied().unwrap_or(0.0) * 1e6;
    tracing::info!(
        scene = %scene.name,
        n_nodes = scene.mesh.n_nodes(),
        n_tets = scene.mesh.n_tets(),
        ticks = summary.ticks,
        factorise_s = summary.factorise_s,
        step_p50_us = pct(0.5),
        step_p99_us = pct(0.99),
        step_max_us = pct(1.0),
        max_points = summary.max_points,
        column_deferrals = summary.column_deferrals,
        prefetched_columns = summary.prefetched_columns,
        clamped_ticks = summary.clamped_ticks,
        unconverged_ticks = summary.unconverged_ticks,
        patch_fallbacks = summary.patch_fallbacks,
        numeric_factorisations = summary.numeric_factorisations,
        wall_s = t0.elapsed().as_secs_f64(),
        "simulated"
    );
    if summary.unconverged_ticks > 0 {
        tracing::warn!(
            "{} ticks did not converge (kept by --keep-unconverged: the CSV's converged column is 0 there)",
            summary.unconverged_ticks
        );
    }
    let rate = scene.tick_rate_hz;
    for t in &summary.targets {
        let u = t.displacement_at_closest_m;
        eprintln!(
            "target '{}' (radius {:.2} mm): closest tip approach {:.3} mm at tick {} (t = {:.3} s), the centre displaced by {:.3} mm there ({:.3}, {:.3}, {:.3}) mm, at most {:.3} mm over the run; tip to the undeformed centre there {:.3} mm: {}",
            t.name,
            t.radius_m * 1e3,
            t.closest_distance_m * 1e3,
            t.closest_tick,
            traj.span_s().0 + t.closest_tick as f64 / rate,
            (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt() * 1e3,
            u[0] * 1e3,
            u[1] * 1e3,
            u[2] * 1e3,
            t.max_displacement_m * 1e3,
            t.rigid_distance_at_closest_m * 1e3,
            if t.hit { "hit" } else { "missed" }
        );
    }
    match output {
        Some(p) => std::fs::write(p, &csv).with_context(|| format!("cannot write {}", p.display()))?,
        None => print!("{csv}"),
    }
    if let Some(p) = dump {
        let dir = p.parent().unwrap_or(std::path::Path::new(""));
        for (k, state) in &dumps {
            let json = serde_json::to_string(state)?;
            if *k == last_k {
                std::fs::write(p, &json).with_context(|| format!("cannot write {}", p.display()))?;
            }
            if dump_at.contains(k) {
                let f = dir.join(format!("state-{k}.json"));
                std::fs::write(&f, &json).with_context(|| format!("cannot write {}", f.display()))?;
            }
        }
    }
    Ok(())
}

fn run_plan(a: &PlanArgs, limits: &MeshLimits) -> Result<()> {
    let entry_m = match a.entry.as_deref() {
        None => None,
        Some(&[x1, y1, x2, y2]) => Some([[x1, y1], [x2, y2]]),
        Some(v) => anyhow::bail!("--entry takes 4 numbers x1,y1,x2,y2 (metres), found {}", v.len()),
    };
    let angles_deg = match a.angles_deg.as_deref() {
        None => None,
        Some(&[lo, hi]) => Some([lo, hi]),
        Some(v) => anyhow::bail!("--angles-deg takes 2 numbers min,max (degrees), found {}", v.len()),
    };
    let scene = scene::load_scene(&a.scene, limits)?;
    let req = plan::PlanRequest { target: a.target.clone(), entry_m, angles_deg, speed_m_s: a.speed_mm_s.map(|v| v * 1e-3) };
    let opts = plan::PlanOptions { threads: a.threads, ..Default::default() };
    let p = plan::plan(&scene, &req, &opts, plan_progress_printer(a.json))?;
    if let Some(path) = &a.trajectory_out {
        std::fs::write(path, p.trajectory_csv()).with_context(|| format!("cannot write {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string(&p)?);
        return Ok(());
    }
    let line = |name: &str, i: &plan::Insertion| {
        println!(
            "{name:<9} entry ({:.2}, {:.2}) mm, angle {:.2}°, depth {:.2} mm: predicted tip–target error {:.3} mm",
            i.entry_m[0] * 1e3,
            i.entry_m[1] * 1e3,
            i.angle_rad.to_degrees(),
            i.depth_m * 1e3,
            i.predicted_error_m * 1e3
        );
    };
    println!("target '{}' (radius {:.2} mm) in scene {}", p.target, p.target_radius_m * 1e3, p.scene);
    line("plan", &p.plan);
    line("straight", &p.straight);
    println!(
        "{} ({} simulations, {} iterations, {:.2} s on {} threads){}",
        if p.hits() { "the plan hits the target" } else { "the plan does not reach the target within its radius" },
        p.simulations,
        p.iterations,
        p.wall_s,
        p.threads,
        a.trajectory_out.as_ref().map(|t| format!("; trajectory written to {}", t.display())).unwrap_or_default()
    );
    Ok(())
}

/// The planners' progress on stderr, a line per iteration (nothing when `quiet`).
fn plan_progress_printer(quiet: bool) -> impl FnMut(&plan::PlanProgress) -> std::ops::ControlFlow<()> {
    move |pr| {
        if !quiet {
            eprintln!(
                "iteration {}: {} simulations, best predicted error {:.3} mm (straight aim {:.3} mm)",
                pr.iteration,
                pr.simulations,
                pr.best_error_m * 1e3,
                pr.straight_error_m * 1e3
            );
        }
        std::ops::ControlFlow::Continue(())
    }
}

/// `plan` for a 3D scene (`needlesim_offline::plan3`).
fn run_plan3(a: &PlanArgs, limits: &MeshLimits) -> Result<()> {
    if a.entry.is_some() || a.angles_deg.is_some() {
        anyhow::bail!("--entry and --angles-deg are for 2D scenes; a 3D scene's plan takes --entry-point x,y,z (and --entry-radius-m)");
    }
    let entry_m = match a.entry_point.as_deref() {
        None => None,
        Some(&[x, y, z]) => Some([x, y, z]),
        Some(v) => anyhow::bail!("--entry-point takes 3 numbers x,y,z (metres), found {}", v.len()),
    };
    let scene = scene::load_scene3d(&a.scene, limits)?;
    let req = needlesim_offline::plan3::Plan3Request {
        target: a.target.clone(),
        entry_m,
        entry_radius_m: a.entry_radius_m,
        avoid: a.avoid.clone(),
        clearance_m: a.clearance_m,
        speed_m_s: a.speed_mm_s.map(|v| v * 1e-3),
    };
    let opts = plan::PlanOptions { threads: a.threads, ..Default::default() };
    let p = needlesim_offline::plan3::plan3(&scene, &req, &opts, plan_progress_printer(a.json))?;
    if let Some(path) = &a.trajectory_out {
        std::fs::write(path, p.trajectory_csv()).with_context(|| format!("cannot write {}", path.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string(&p)?);
        return Ok(());
    }
    let line = |name: &str, i: &needlesim_offline::plan3::Insertion3| {
        let rolls: Vec<String> =
            i.rolls.iter().map(|r| format!("{:.1}° from {:.1} mm", r.roll_rad.to_degrees(), r.depth_m * 1e3)).collect();
        println!(
            "{name:<9} entry ({:.2}, {:.2}, {:.2}) mm, direction ({:.4}, {:.4}, {:.4}), rolls [{}], depth {:.2} mm: predicted tip–target error {:.3} mm, clearance {:.3} mm",
            i.entry_m[0] * 1e3,
            i.entry_m[1] * 1e3,
            i.entry_m[2] * 1e3,
            i.direction[0],
            i.direction[1],
            i.direction[2],
            rolls.join(", "),
            i.depth_m * 1e3,
            i.predicted_error_m * 1e3,
            i.min_clearance_m() * 1e3
        );
    };
    let names: Vec<&str> = p.structures.iter().map(|s| s.name.as_str()).collect();
    println!(
        "target '{}' (radius {:.2} mm) in scene {}, sparing [{}] by {:.2} mm",
        p.target,
        p.target_radius_m * 1e3,
        p.scene,
        names.join(", "),
        p.clearance_m * 1e3
    );
    line("plan", &p.plan);
    line("straight", &p.straight);
    println!(
        "{} ({} simulations, {} iterations, {:.2} s on {} threads){}",
        if p.hits() {
            "the plan hits the target with the clearance kept"
        } else {
            "the plan does not reach the target with the clearance kept"
        },
        p.simulations,
        p.iterations,
        p.wall_s,
        p.threads,
        a.trajectory_out.as_ref().map(|t| format!("; trajectory written to {}", t.display())).unwrap_or_default()
    );
    Ok(())
}

/// With no command: the paper's phantom, inserted and withdrawn, summarised every half second.
fn summary(limits: &MeshLimits) -> Result<()> {
    let scene = scene::load_scene("paper-phantom", limits)?;
    let traj = scene::Trajectory::parse_csv(scene.example_trajectory.expect("a shipped example has a trajectory"))?;
    let mut csv = String::new();
    let (sim, summary) =
        simulate::run(&scene, &traj, simulate::DEFAULT_MAX_TICKS, needlesim_offline::ConvergencePolicy::Fail, Some(&mut csv))?;
    println!(
        "needlesim: {} ({} nodes), {} ticks at {} Hz",
        scene.name,
        scene.tissue.mesh().n_nodes(),
        summary.ticks,
        sim.params().tick_rate_hz
    );
    println!("{:>6} {:>9} {:>10} {:>6} {:>8} {:>11}", "t [s]", "depth [mm]", "axial [N]", "stuck", "slipping", "target [mm]");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name);
    let (ti, di, fi, si, pi, gi) =
        (col("t_s"), col("inserted_m"), col("f_axial_n"), col("n_stuck"), col("n_slipping"), col("target_centre_distance_m"));
    for (k, line) in lines.enumerate() {
        if k % 500 != 0 {
            continue;
        }
        let v: Vec<&str> = line.split(',').collect();
        let num = |i: Option<usize>| i.and_then(|i| v.get(i)).and_then(|s| s.parse::<f64>().ok()).unwrap_or(f64::NAN);
        println!("{:>6.2} {:>9.1} {:>10.3} {:>6} {:>8} {:>11.1}", num(ti), num(di) * 1e3, num(fi), num(si), num(pi), num(gi) * 1e3);
    }
    let mut times = summary.step_times_s;
    times.sort_by(f64::total_cmp);
    let p = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize] * 1e6;
    println!("step time: p50 {:.1} µs, p99 {:.1} µs, max {:.1} µs (debug builds are slower; use --release)", p(0.5), p(0.99), p(1.0));
    println!("full time series: needlesim-server simulate --scene paper-phantom -o paper-phantom.csv");
    Ok(())
}

/// A local file named on the command line (scenario, trajectory, scene): a regular file, not a
/// link, of at most [`scene::MAX_LOCAL_FILE_BYTES`] ([`scene::read_local_file`]).
fn read_local(path: &std::path::Path) -> Result<String> {
    Ok(scene::read_local_file(path, scene::MAX_LOCAL_FILE_BYTES)?)
}

/// The admin token in `path`: its first line, trimmed, of at least 16 characters. The file is read
/// by the one rule for local files (a regular file, not a link, at most
/// [`needlesim_localfile::MAX_TOKEN_FILE_BYTES`]; never quoted in an error).
fn read_admin_token(path: &std::path::Path) -> Result<String> {
    let text = needlesim_localfile::read_local_file(path, needlesim_localfile::MAX_TOKEN_FILE_BYTES)
        .map_err(|e| anyhow::anyhow!("--admin-token-file: {}", e.named("token file")))?;
    let token = text.lines().next().unwrap_or("").trim().to_owned();
    if token.len() < 16 {
        anyhow::bail!(
            "--admin-token-file {}: the token on its first line has {} characters; at least 16 are needed",
            path.display(),
            token.len()
        );
    }
    Ok(token)
}

fn run_serve(args: ServeArgs, limits: &MeshLimits) -> Result<()> {
    needlesim_session::set_rt_priority(args.rt_priority);
    needlesim_session::set_spin_margin(std::time::Duration::from_micros(args.spin_margin_us));
    let fleet = args.fleet.config((args.default_scene != "none").then_some(args.default_scene.as_str()))?;
    let config = serve::ServeConfig {
        listen: args.listen,
        data_dir: args.data_dir,
        web_dir: args.web_dir,
        tls: args.tls_cert.zip(args.tls_key),
        limits: grpc::ServerLimits {
            max_sessions: args.max_sessions,
            max_observers_per_session: args.max_observers,
            max_streams: args.max_streams,
            mesh: *limits,
            max_session_bytes: args.max_session_memory_mb.saturating_mul(1 << 20),
            max_simulate_ticks: args.max_simulate_ticks,
            max_offline_jobs: args.max_offline_jobs,
            max_plans: args.max_plans,
            max_image_pixels: args.max_image_pixels,
            max_recordings: args.max_recordings,
            max_recordings_bytes: needlesim_server::quota::mib(args.max_recordings_mb),
            max_reports: args.max_reports,
            max_reports_bytes: needlesim_server::quota::mib(args.max_reports_mb),
            control_first_message_ms: args.control_first_message_ms,
            answer_deadline_ms: args.answer_deadline_ms,
            session_idle_timeout_s: args.session_idle_timeout_s,
            ..Default::default()
        },
        max_message_bytes: args.max_message_bytes,
        default_scene: (args.default_scene != "none").then_some(args.default_scene),
        demo: args.demo,
        admin_token: args.admin_token_file.as_deref().map(read_admin_token).transpose()?,
        foxglove: args.foxglove_addr,
        foxglove_max_clients: args.foxglove_max_clients,
        exercise: args.exercise,
        connections: needlesim_server::listener::ConnLimits {
            max_connections: args.max_connections.unwrap_or_else(needlesim_server::listener::default_max_connections),
            handshake_timeout: std::time::Duration::from_millis(args.handshake_timeout_ms),
            max_streams_per_connection: args.max_streams_per_connection,
            max_pending_request_bytes: needlesim_server::quota::mib(args.max_pending_request_mb)
                .max(u64::try_from(args.max_message_bytes).unwrap_or(u64::MAX).saturating_add(5)),
        },
        shutdown_grace: std::time::Duration::from_millis(args.shutdown_grace_ms),
        max_held_answer_bytes: needlesim_server::quota::mib(args.max_held_answers_mb),
        answer_deadline: std::time::Duration::from_millis(args.answer_deadline_ms),
    };
    let runtime = tokio::runtime::Builder::new_multi_thread().enable_all().build().context("tokio runtime")?;
    let result = if let Some(cfg) = fleet {
        runtime.block_on(serve::serve_with(config, |state| agones::start(cfg, state)))
    } else {
        runtime.block_on(serve::serve(config, async {
            // Ctrl-C or SIGTERM: close every session (its device channel file is removed too).
            agones::terminate_signal().await;
            tracing::info!("shutting down");
        }))
    };
    // The sessions are closed and their recordings finished; what is left (the tasks of
    // connections past --shutdown-grace-ms, offline work blocked on a client that does not read)
    // is not waited for: dropping the runtime would wait for its blocking tasks without bound.
    runtime.shutdown_timeout(SHUTDOWN_LEFTOVERS);
    result
}

/// How long the runtime's remaining tasks get once `serve` has returned.
const SHUTDOWN_LEFTOVERS: std::time::Duration = std::time::Duration::from_millis(500);

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::Cli;

    /// Tick limits a run holds in memory are bounded by `MAX_TICKS_LIMIT` at the command line
    /// (issue 35's hostile pass: `--max-ticks` and `--max-simulate-ticks` were taken unchecked).
    #[test]
    fn issue_35_tick_limits_over_max_ticks_limit_are_refused_naming_the_flag() {
        let over = (needlesim_offline::MAX_TICKS_LIMIT + 1).to_string();
        for args in [
            vec!["needlesim-server", "--max-simulate-ticks", &over],
            vec!["needlesim-server", "simulate", "--scene", "s.toml", "--max-ticks", &over],
            vec!["needlesim-server", "simulate", "--scene", "s.toml", "--max-ticks", "0"],
        ] {
            let e = Cli::try_parse_from(&args).err().unwrap_or_else(|| panic!("{args:?} was accepted")).to_string();
            assert!(e.contains("max-") && e.contains("ticks"), "{args:?}: {e}");
        }
        let at = needlesim_offline::MAX_TICKS_LIMIT.to_string();
        assert!(Cli::try_parse_from(["needlesim-server", "--max-simulate-ticks", &at]).is_ok());
    }
}
