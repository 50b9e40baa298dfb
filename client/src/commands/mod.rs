//! The commands: [`run`] checks the local files, connects and hands each command to its module
//! (`plan`'s is [`crate::plan`]); what they share.

mod drive;
mod flip_bevel;
mod record;
mod replay;
mod scene;
pub(crate) use scene::read_local;
mod sessions;
mod simulate;
mod watch;

use std::io::Write;

use anyhow::{Result, bail};
use needlesim_proto::v1 as pb;

use crate::rpc::Conn;
use crate::traj::{AnyTrajectory, header_of};
use crate::{Cli, Command, SessionsCmd, SimulateArgs};
use drive::drive;
use flip_bevel::flip_bevel;
use record::record;
use replay::replay;
use scene::{scene_dimension, scene_source};
use sessions::{sessions_close, sessions_create, sessions_list};
use simulate::simulate;
use watch::watch;

pub async fn run(cli: Cli) -> Result<()> {
    // Replay is local: no server involved.
    if let Command::Replay(a) = &cli.command {
        return replay(a);
    }
    // Local files are checked before the server is contacted.
    let scene = match &cli.command {
        Command::Sessions(SessionsCmd::Create(a)) => Some(scene_source(&a.scene, a.mesh.as_deref())?),
        Command::Simulate(a) => Some(scene_source(&a.scene, a.mesh.as_deref())?),
        _ => None,
    };
    let traj = match &cli.command {
        Command::Drive(a) => Some(AnyTrajectory::read(&a.trajectory)?),
        Command::Simulate(SimulateArgs { trajectory: Some(p), .. }) => Some(AnyTrajectory::read(p)?),
        Command::Simulate(a) if a.scene.scene.is_some() => {
            bail!("--scene needs --trajectory TRAJ.csv (only the shipped examples have their own)")
        }
        _ => None,
    };
    // A trajectory of the wrong dimension for the scene, when the scene's is known here.
    if let (Command::Simulate(a), Some(t), Some((_, what))) = (&cli.command, &traj, &scene)
        && let Some(dim) = scene_dimension(&a.scene, a.mesh.is_some())?
        && dim != t.dimension()
    {
        let path = a.trajectory.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
        bail!(
            "--trajectory {path} is a {}D trajectory ({}) but {what} is a {dim}D scene: it needs {}",
            t.dimension(),
            header_of(t.dimension()),
            header_of(dim)
        );
    }
    let conn = Conn::connect(&cli.server, cli.token.clone(), cli.tls_ca.as_deref()).await?;
    match (cli.command, scene, traj) {
        (Command::Sessions(SessionsCmd::List { json }), ..) => sessions_list(&conn, json).await,
        (Command::Sessions(SessionsCmd::Create(a)), Some(scene), _) => sessions_create(&conn, &a, scene).await,
        (Command::Sessions(SessionsCmd::Close { id }), ..) => sessions_close(&conn, &id).await,
        (Command::Watch(a), ..) => watch(&conn, &a).await,
        (Command::Record(a), ..) => record(&conn, &a).await,
        (Command::Simulate(a), Some(scene), traj) => simulate(&conn, &a, scene, traj).await,
        (Command::Drive(a), _, Some(traj)) => drive(&conn, &a, traj).await,
        (Command::Plan(a), ..) => crate::plan::plan(&conn, &a).await,
        (Command::FlipBevel { id }, ..) => flip_bevel(&conn, &id).await,
        _ => unreachable!("every command is handled above"),
    }
}

fn out_line(line: &str) -> Result<()> {
    let mut o = std::io::stdout().lock();
    writeln!(o, "{line}")?;
    Ok(())
}

fn check_id(id: &str) -> Result<()> {
    if id.trim().is_empty() {
        bail!("the session id is empty");
    }
    Ok(())
}

fn session_client(c: &Conn) -> pb::session_service_client::SessionServiceClient<tonic::transport::Channel> {
    pb::session_service_client::SessionServiceClient::new(c.channel.clone())
}
