//! `SimulationService.Simulate`: an offline run (the run driver of needlesim-offline) on a
//! blocking worker, its time series streamed in chunks.

use std::ops::ControlFlow;

use needlesim_core::num::num;
use needlesim_core::sim::Simulation;
use needlesim_core::sim3::Simulation3;
use needlesim_offline::{RunError, RunTotals, ScriptedRun, ScriptedSim, Tick};
use needlesim_proto::v1 as pb;
use tonic::{Request, Response, Status};

use super::{Api, BoxStream};
use crate::convert;
use crate::jobs::{JobKind, JobSender};
use crate::status::{ApiError, SizeLimit, status_of};

#[tonic::async_trait]
impl pb::simulation_service_server::SimulationService for Api {
    type SimulateStream = BoxStream<pb::SimulateResponse>;

    async fn simulate(&self, req: Request<pb::SimulateRequest>) -> Result<Response<Self::SimulateStream>, Status> {
        let r = req.into_inner();
        if r.trajectory.len() > self.state.limits.max_trajectory_samples {
            return Err(ApiError::from(SizeLimit {
                what: "trajectory".to_owned(),
                amount: r.trajectory.len() as f64,
                limit: self.state.limits.max_trajectory_samples as u64,
                unit: "samples",
                hint: String::new(),
            })
            .into());
        }
        // Held by the worker until it ends; refused at once when the server is busy.
        let permit = self.state.jobs.try_start(JobKind::Simulate)?;
        let limits = self.state.limits.clone();
        let (tx, stream) = self.state.jobs.stream(16);
        // Parse and validate before answering, so that errors are statuses, not stream items.
        let job = tokio::task::spawn_blocking(move || -> Result<_, Status> {
            let scene = convert::session_scene_from_pb(r.scene.as_ref(), &limits.scene()).map_err(|e| status_of("scene", &e))?;
            // The trajectory's own count (compared in floating point: no saturated number), the
            // message naming its last sample, the span and the limit.
            let too_long = |counted: Result<u64, needlesim_trajectory::TrajectoryError>| -> Result<(), Status> {
                match counted {
                    Err(needlesim_trajectory::TrajectoryError::TooLong { at, end_s, span_s, ticks, rate_hz, max_ticks }) => {
                        Err(ApiError::ResourceExhausted(format!(
                            "{at}: t_s = {} ends {} s after the first sample: {} ticks at {} Hz, over the limit of {max_ticks} ticks (server flag --max-simulate-ticks)",
                            num(end_s),
                            num(span_s),
                            num(ticks),
                            num(rate_hz)
                        ))
                        .into())
                    }
                    Err(e) => Err(status_of("trajectory", &anyhow::Error::new(e))),
                    Ok(_) => Ok(()),
                }
            };
            let scene = match scene {
                convert::SessionScene::Two(scene) => scene,
                convert::SessionScene::Three(scene) => {
                    let traj = if r.trajectory.is_empty() {
                        scene.trajectory.clone().ok_or_else(|| {
                            Status::invalid_argument("trajectory is empty and the 3D scene names no trajectory of its own")
                        })?
                    } else {
                        convert::trajectory3_from_pb(&r.trajectory).map_err(|e| status_of("trajectory", &e))?
                    };
                    too_long(traj.tick_count(scene.tick_rate_hz, limits.max_simulate_ticks))?;
                    return Ok(Job::Three(scene, traj));
                }
            };
            if let Some(i) = r.trajectory.iter().position(|s| s.base3.is_some()) {
                return Err(ApiError::invalid(
                    format!("trajectory[{i}].base3"),
                    format!("trajectory[{i}].base3: the scene is 2D: its samples take base (x_m, y_m, theta_rad), not base3"),
                )
                .into());
            }
            let traj = if r.trajectory.is_empty() {
                let text = scene
                    .example_trajectory
                    .ok_or_else(|| Status::invalid_argument("trajectory is empty and the scene is not a shipped example with its own"))?;
                needlesim_scene::Trajectory::parse_csv(text).map_err(|e| Status::internal(format!("{e:#}")))?
            } else {
                convert::trajectory_from_pb(&r.trajectory).map_err(|e| status_of("trajectory", &e))?
            };
            too_long(traj.tick_count(scene.params.tick_rate_hz, limits.max_simulate_ticks))?;
            Ok(Job::Two(scene, traj))
        })
        .await
        .map_err(|e| Status::internal(format!("simulate task: {e}")))??;
        let decimate = r.decimate.max(1) as u64;
        let convergence = needlesim_offline::ConvergencePolicy::keeping(r.keep_unconverged);
        let limits_ticks = self.state.limits.max_simulate_ticks;
        // A worker thread of the blocking pool: never a session's real-time thread.
        tokio::task::spawn_blocking(move || {
            let _permit = permit;
            let result = match &job {
                Job::Two(scene, traj) => {
                    run_offline(scene, traj, (limits_ticks, convergence), decimate, &tx).map_err(|e| ApiError::from(&e))
                }
                Job::Three(scene, traj) => run_offline3(scene, traj, (limits_ticks, convergence), decimate, &tx),
            };
            if let Err(e) = result {
                let _ = tx.send_blocking(Err(e.into()));
            }
        });
        Ok(Response::new(Box::pin(stream)))
    }
}

/// What a Simulate call runs: a 2D scene and trajectory, or a 3D one.
enum Job {
    Two(Box<needlesim_scene::Scene>, needlesim_scene::Trajectory),
    Three(Box<needlesim_scene::Scene3d>, needlesim_scene::Trajectory3),
}

/// Rows of the time series per `SeriesChunk` message (about 200 bytes each without targets).
pub const SERIES_CHUNK_ROWS: usize = 1000;

/// Runs an offline 2D simulation with the run driver ([`stream_run`]); the result carries the
/// final displacement field.
fn run_offline(
    scene: &needlesim_scene::Scene,
    traj: &needlesim_scene::Trajectory,
    (max_ticks, convergence): (u64, needlesim_offline::ConvergencePolicy),
    decimate: u64,
    tx: &JobSender<pb::SimulateResponse>,
) -> Result<(), needlesim_offline::RunError> {
    let started = std::time::Instant::now();
    let opts = needlesim_offline::RunOptions { max_ticks, convergence, ..Default::default() };
    let run =
        needlesim_offline::ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), needlesim_offline::Script::trajectory(traj), opts)?;
    let t0 = run.t0_s();
    let row = |sim: &Simulation, _: &Tick| convert::series_row(sim.output(), t0, &scene.target_names);
    stream_run(run, decimate, tx, row, |sim, _, step_us| {
        let mut u = vec![0.0; scene.tissue.n_dofs()];
        sim.displacement_field_into(&mut u);
        convert::simulate_result(sim.stats().ticks, started.elapsed().as_secs_f64(), step_us, u)
    })
}

/// The 3D counterpart of [`run_offline`]: the same driver and stream as `needlesim-server
/// simulate` for a 3D scene (`needlesim_offline::simulate3::run3`), so both give the same rows
/// (with `d3`); the result carries no displacement field.
fn run_offline3(
    scene: &needlesim_scene::Scene3d,
    traj: &needlesim_scene::Trajectory3,
    (max_ticks, convergence): (u64, needlesim_offline::ConvergencePolicy),
    decimate: u64,
    tx: &JobSender<pb::SimulateResponse>,
) -> Result<(), ApiError> {
    use needlesim_offline::simulate3::sim3_params;
    let started = std::time::Instant::now();
    let initial = <Simulation3 as needlesim_offline::ScriptedSim>::first_pose(traj)
        .map_err(|e| ApiError::from(&needlesim_offline::RunError::FirstPose(Box::new(e))))?;
    let model = std::sync::Arc::new(scene.tissue_model().map_err(|e| ApiError::Internal(format!("the 3D tissue: {e:#}")))?);
    let opts = needlesim_offline::RunOptions { max_ticks, convergence, ..Default::default() };
    let script = needlesim_offline::Script::trajectory(traj);
    let run = needlesim_offline::ScriptedRun::new(model, sim3_params(scene, initial), script, opts).map_err(|e| ApiError::from(&e))?;
    let names: Vec<String> = scene.targets.iter().map(|t| t.name.clone()).collect();
    let radii_m: Vec<f64> = scene.targets.iter().map(|t| t.radius_m).collect();
    let row = |sim: &Simulation3, tick: &Tick| convert::series_row3(sim.output(), tick.t_s, &names, &radii_m);
    stream_run(run, decimate, tx, row, |_, totals, step_us| {
        convert::simulate_result(totals.ticks, started.elapsed().as_secs_f64(), step_us, vec![])
    })
    .map_err(|e| ApiError::from(&e))
}

/// Runs a scripted run to its end, streaming progress, the time series (`row` of every
/// `decimate`-th tick and the last) in chunks of at most [`SERIES_CHUNK_ROWS`] rows, then
/// `result` of the final simulation. Memory is bounded by one chunk and the channel, whatever
/// the length: step times go into a histogram, not a list. Ends early, without error, when the
/// client goes away.
fn stream_run<S: ScriptedSim>(
    mut run: ScriptedRun<'_, S>,
    decimate: u64,
    tx: &JobSender<pb::SimulateResponse>,
    row: impl Fn(&S, &Tick) -> pb::SeriesRow,
    result: impl FnOnce(&S, RunTotals, [f64; 2]) -> pb::SimulateResponse,
) -> Result<(), RunError<S::Error>> {
    let send = |response: pb::SimulateResponse| tx.send_blocking(Ok(response)).is_ok();
    let n_ticks = run.last_tick();
    let mut chunk = Vec::with_capacity(SERIES_CHUNK_ROWS);
    let mut step_ns = hdrhistogram::Histogram::<u64>::new_with_bounds(1, 60_000_000_000, 3).expect("valid bounds");
    let progress_every = (n_ticks / 20).max(1);
    let mut client_gone = false;
    run.run(|tick, sim| {
        if tx.is_closed() {
            client_gone = true;
            return ControlFlow::Break(());
        }
        let k = tick.k;
        step_ns.saturating_record(((tick.step_s * 1e9) as u64).max(1));
        if k % decimate == 0 || k == n_ticks {
            chunk.push(row(sim, tick));
            if chunk.len() == SERIES_CHUNK_ROWS && !send(convert::series_chunk(std::mem::take(&mut chunk))) {
                client_gone = true;
                return ControlFlow::Break(());
            }
        }
        if k % progress_every == 0 && !send(convert::simulate_progress(k, n_ticks)) {
            client_gone = true;
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    })?;
    if client_gone || (!chunk.is_empty() && !send(convert::series_chunk(chunk))) {
        return Ok(());
    }
    let (sim, totals) = run.finish()?;
    let step_us = [step_ns.value_at_quantile(0.5) as f64 * 1e-3, step_ns.value_at_quantile(0.99) as f64 * 1e-3];
    send(result(&sim, totals, step_us));
    Ok(())
}
