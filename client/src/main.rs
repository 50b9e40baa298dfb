//! `needlesim`: the command-line client of the needlesim gRPC API (sessions, live view, driving,
//! recordings, offline simulation).

mod allocate;
mod commands;
mod plan;
mod rpc;
mod traj;
mod view;

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

#[derive(Debug, Parser)]
#[command(name = "needlesim", version, about = "Command-line client of the needlesim server (gRPC API needlesim.v1)")]
pub struct Cli {
    /// The server URL (http://HOST:PORT, or https:// with --tls-ca).
    #[arg(long, global = true, env = "NEEDLESIM_SERVER", default_value = "http://127.0.0.1:50051", value_name = "URL")]
    pub server: String,
    /// The session token (controller or observer), sent as `authorization: Bearer <token>`.
    #[arg(long, global = true, env = "NEEDLESIM_TOKEN", value_name = "TOKEN", hide_env_values = true)]
    pub token: Option<String>,
    /// The CA certificate (PEM) that signed the server's TLS certificate.
    #[arg(long, global = true, value_name = "PEM")]
    pub tls_ca: Option<PathBuf>,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// List, create and close sessions.
    #[command(subcommand)]
    Sessions(SessionsCmd),
    /// A live view of a session (observer token).
    Watch(WatchArgs),
    /// Record a session to an MCAP file (controller token).
    Record(RecordArgs),
    /// Print the frames of a local MCAP recording, paced by their log times.
    Replay(ReplayArgs),
    /// Run a scripted insertion offline on the server (Simulate) and write its time series.
    Simulate(SimulateArgs),
    /// Drive a session's needle along a trajectory in real time (controller token).
    Drive(DriveArgs),
    /// Plan an insertion on the server (PlanningService.Plan) that reaches a target despite the
    /// tissue deformation; prints progress and the plan, optionally writes its trajectory.
    Plan(PlanArgs),
    /// Turn a session's needle 180° about its axis: a bevel tip then faces the other side
    /// (controller token).
    FlipBevel {
        /// The session id.
        id: String,
    },
    /// Ask the Agones allocator for a needlesim server (label selectors); prints ADDRESS:PORT.
    Allocate(allocate::AllocateArgs),
}

#[derive(Debug, Subcommand)]
pub enum SessionsCmd {
    /// The open sessions.
    List {
        /// Machine-readable output.
        #[arg(long)]
        json: bool,
    },
    /// Create a session; prints its id and both tokens.
    Create(Box<CreateArgs>),
    /// Close a session (controller token).
    Close {
        /// The session id.
        id: String,
    },
}

#[derive(Debug, Args, Clone)]
#[group(required = true, multiple = false)]
pub struct SceneArgs {
    /// A shipped example scene: paper-phantom, fig3-target, fig4-steering, bevel-tip; 3D:
    /// cube-phantom-3d, brachy-3d, fig3-target-3d.
    #[arg(long, value_name = "NAME")]
    pub example: Option<String>,
    /// A scene file in the TOML format of docs/guide/scenes.md (2D, or 3D with `dim = 3`); it cannot
    /// reference files other than a 3D scene's Gmsh mesh given with --mesh.
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct CreateArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The Gmsh tetrahedral mesh (.msh) a 3D scene TOML names in `[mesh] file`, uploaded with it.
    #[arg(long, value_name = "FILE.msh")]
    pub mesh: Option<PathBuf>,
    /// Tick rate, 500..1000 Hz (default: the scene's).
    #[arg(long, value_name = "HZ")]
    pub rate: Option<f64>,
    /// Record every tick from the start.
    #[arg(long)]
    pub record: bool,
    /// Give the session a shared-memory channel for a haptic device bridge on this host
    /// (its path is printed; `needlesim-bridge --channel PATH`).
    #[arg(long)]
    pub device_channel: bool,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub alloc: allocate::CreateAllocation,
}

#[derive(Debug, Args)]
pub struct WatchArgs {
    /// The session id.
    pub id: String,
    /// Frames per second (30..120), or 0 for every tick.
    #[arg(long, value_name = "HZ", default_value_t = 30.0)]
    pub rate: f64,
    /// Stop after this many frames.
    #[arg(long, value_name = "N", conflicts_with = "seconds")]
    pub ticks: Option<u64>,
    /// Stop after this many seconds.
    #[arg(long, value_name = "S")]
    pub seconds: Option<f64>,
    /// One line per frame instead of a view redrawn in place (the default when stdout is not a terminal).
    #[arg(long)]
    pub plain: bool,
}

#[derive(Debug, Args)]
pub struct RecordArgs {
    /// The session id.
    pub id: String,
    /// The MCAP file to write.
    #[arg(long, value_name = "FILE.mcap")]
    pub out: PathBuf,
    /// How long to record.
    #[arg(long, value_name = "S", default_value_t = 1.0)]
    pub seconds: f64,
}

#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The MCAP recording.
    pub file: PathBuf,
    /// Playback speed (1 = real time, 0 = as fast as possible).
    #[arg(long, value_name = "X", default_value_t = 1.0)]
    pub speed: f64,
}

#[derive(Debug, Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Csv,
    Json,
}

#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The Gmsh tetrahedral mesh (.msh) a 3D scene TOML names in `[mesh] file`, uploaded with it.
    #[arg(long, value_name = "FILE.msh")]
    pub mesh: Option<PathBuf>,
    /// The base trajectory (t_s,x_m,y_m,theta_rad; for a 3D scene t_s,x_m,y_m,z_m,qw,qx,qy,qz);
    /// default: the example's own.
    #[arg(long, value_name = "TRAJ.csv")]
    pub trajectory: Option<PathBuf>,
    /// Keep one row every N ticks.
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub decimate: u32,
    /// Write here instead of standard output.
    #[arg(long, short = 'o', value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
}

#[derive(Debug, Args)]
pub struct DriveArgs {
    /// The session id.
    pub id: String,
    /// The base trajectory, played in real time at 1 kHz: t_s,x_m,y_m,theta_rad for a 2D
    /// session, t_s,x_m,y_m,z_m,qw,qx,qy,qz (position, unit quaternion body → world) for a 3D one.
    #[arg(long, value_name = "TRAJ.csv")]
    pub trajectory: PathBuf,
    /// Write every response (one per tick: the pose the tick applied, force, torque) as CSV.
    #[arg(long, value_name = "FILE.csv")]
    pub log: Option<PathBuf>,
    /// Repeat the trajectory until interrupted (Ctrl-C).
    #[arg(long = "loop")]
    pub repeat: bool,
    /// Take control from whoever drives the session now (one controller at a time: without
    /// this, driving a session someone else drives is refused).
    #[arg(long)]
    pub take_over: bool,
}

#[derive(Debug, Args)]
pub struct PlanArgs {
    /// A shipped example's name (fig3-target) or a scene TOML file.
    #[arg(long, value_name = "NAME|FILE.toml")]
    pub scene: String,
    /// The target's name in the scene.
    #[arg(long)]
    pub target: String,
    /// The allowed entry segment on the tissue surface, x1,y1,x2,y2 in metres (default: the scene's planning example).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_name = "X1,Y1,X2,Y2")]
    pub entry: Option<Vec<f64>>,
    /// The allowed needle angles min,max in degrees (base pose theta: base to tip, counter-clockwise from +x).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_name = "MIN,MAX")]
    pub angles_deg: Option<Vec<f64>>,
    /// The insertion speed in mm/s.
    #[arg(long, value_name = "MM_PER_S")]
    pub speed_mm_s: Option<f64>,
    /// Write the plan's base trajectory (t_s,x_m,y_m,theta_rad), replayable by `simulate` and `drive`.
    #[arg(long, value_name = "PLAN.csv")]
    pub trajectory_out: Option<PathBuf>,
    /// Print the result as one JSON object.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub d3: plan::Plan3Args,
}

fn main() {
    let cli = Cli::parse();
    let runtime = match tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build() {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: cannot start the async runtime: {e}");
            std::process::exit(1);
        }
    };
    let result = runtime.block_on(async {
        match allocate::before_command(cli).await? {
            Some(cli) => commands::run(cli).await,
            None => Ok(()),
        }
    });
    // Streams still open (observe, control) must not keep the process alive.
    runtime.shutdown_background();
    if let Err(e) = result {
        // `needlesim … | head` closes stdout early: not an error worth reporting.
        if e.chain().any(|c| c.downcast_ref::<std::io::Error>().is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)) {
            std::process::exit(0);
        }
        let msg = format!("{e:#}").replace('\n', " ");
        eprintln!("error: {msg}");
        std::process::exit(1);
    }
}
