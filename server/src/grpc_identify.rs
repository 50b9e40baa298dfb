//! The gRPC `IdentifyService` of `needlesim.v1`: marker tracking, E/ν identification and the needle
//! force distribution, the same functions as `needlesim-lab identify …`, streaming progress.
//!
//! Like `Simulate`, these calls touch no session and need no token. Each call parses and checks
//! its inputs on a blocking worker before answering, so that bad input is the call's status
//! (INVALID_ARGUMENT naming the request field: `tracks_csv`, `probe_log_csv`, `force_log_csv`,
//! `scene`, `grid`, `trajectory_csv`, `frames`, …); a request over the size limits (frames, rows,
//! image pixels read from each PNG header before any decoding, the scene's mesh and memory) is
//! RESOURCE_EXHAUSTED, and so is a call when the server already runs its limit of offline jobs
//! (`--max-offline-jobs`, shared with Simulate and Plan; jobs.rs). The work runs on the blocking pool; progress goes through a bounded
//! channel (progress messages are dropped, never waited for, when the client reads slowly; the
//! final result is always delivered), and inconsistencies found by the fit itself (time stamps
//! that do not overlap, no usable frame) end the stream with INVALID_ARGUMENT.

use std::ops::ControlFlow;

use needlesim_identify::logs::{ForceLog, ProbeLog};
use needlesim_identify::needle_fit::{NeedleFitOptions, fit_needle, write_fitted_scene};
use needlesim_identify::probe::{ProbeFitOptions, ProbeModel, fit_probe, grid_model, register_markers};
use needlesim_identify::tracks::MarkerTracks;
use needlesim_proto::v1 as pb;
use tonic::{Request, Response, Status};

use crate::grpc::Api;
use crate::jobs::{JobKind, JobPermit};
use crate::status::{ApiError, SizeLimit, quote, status_of};

type ProgressStream = std::pin::Pin<Box<dyn tokio_stream::Stream<Item = Result<pb::IdentifyProgress, Status>> + Send + 'static>>;

/// Most images a Track call takes.
pub const MAX_TRACK_FRAMES: usize = 20_000;
/// Most CSV rows (marker tracks) a call takes.
pub const MAX_TRACK_ROWS: usize = 5_000_000;

fn invalid(field: &str) -> impl Fn(anyhow::Error) -> Status + '_ {
    move |e| ApiError::invalid(field, format!("{e:#}")).into()
}

fn parse_tracks(text: &str) -> Result<MarkerTracks, Status> {
    let rows = text.lines().count();
    if rows > MAX_TRACK_ROWS {
        return Err(Status::resource_exhausted(format!("tracks_csv has {rows} lines, over the limit of {MAX_TRACK_ROWS}")));
    }
    MarkerTracks::from_csv(text).map_err(invalid("tracks_csv"))
}

/// A progress message.
fn progress(done: usize, total: usize, stage: &str) -> pb::IdentifyProgress {
    pb::IdentifyProgress { done: done as u32, total: total as u32, stage: stage.to_owned(), result: None }
}

/// Runs `work` on the blocking pool, holding `permit` until it ends, with a progress callback
/// that never blocks; sends its result (or its error's status: RESOURCE_EXHAUSTED for a size
/// limit, else INVALID_ARGUMENT) as the last stream item. When the client goes away (it cancels,
/// disconnects or drops the stream) the callback stops the work at its next frame or model
/// evaluation, as Simulate stops at its next tick, and the permit (`--max-offline-jobs`) is free
/// again (issue 35).
fn spawn_work<F>(stage: &'static str, permit: JobPermit, work: F) -> Response<ProgressStream>
where
    F: FnOnce(needlesim_identify::Progress<'_>) -> anyhow::Result<pb::identify_progress::Result> + Send + 'static,
{
    let (tx, stream) = permit.stream(16);
    tokio::task::spawn_blocking(move || {
        let _permit = permit;
        let mut report = |done: usize, total: usize| {
            if tx.is_closed() {
                return ControlFlow::Break(());
            }
            tx.offer(Ok(progress(done, total, stage)));
            ControlFlow::Continue(())
        };
        let item = match work(&mut report) {
            Ok(r) => Ok(pb::IdentifyProgress { stage: "done".to_owned(), result: Some(r), ..Default::default() }),
            Err(e) if e.chain().any(|c| c.is::<needlesim_identify::Cancelled>()) => {
                tracing::info!(stage, "identify call cancelled: the client went away");
                return;
            }
            Err(e) => Err(status_of("", &e)),
        };
        let _ = tx.send_blocking(item);
    });
    Response::new(Box::pin(stream))
}

/// The scene of a request and, when it has one, its TOML text (for the fitted scene).
fn scene_of(
    src: Option<&pb::SceneSource>,
    limits: &needlesim_scene::SceneLimits,
) -> Result<(needlesim_scene::Scene, Option<String>), Status> {
    let scene = crate::convert::scene_from_pb(src, limits).map_err(|e| status_of("scene", &e))?;
    let text = match src.and_then(|s| s.source.as_ref()) {
        Some(pb::scene_source::Source::Example(name)) => needlesim_scene::EXAMPLES.iter().find(|e| e.0 == name).map(|e| e.1.to_owned()),
        Some(pb::scene_source::Source::SceneToml(t)) => Some(t.clone()),
        _ => None,
    };
    Ok((scene, text))
}

async fn blocking<T: Send + 'static>(f: impl FnOnce() -> Result<T, Status> + Send + 'static) -> Result<T, Status> {
    tokio::task::spawn_blocking(f).await.map_err(|e| Status::internal(format!("identify task: {e}")))?
}

#[tonic::async_trait]
impl pb::identify_service_server::IdentifyService for Api {
    type TrackStream = ProgressStream;
    type ProbeStream = ProgressStream;
    type NeedleStream = ProgressStream;

    async fn track(&self, req: Request<pb::TrackRequest>) -> Result<Response<Self::TrackStream>, Status> {
        use needlesim_identify::track::{Polarity, Scale, TrackParams, track_png_bytes};
        let r = req.into_inner();
        if r.frames.is_empty() {
            return Err(Status::invalid_argument("frames is empty"));
        }
        if r.frames.len() > MAX_TRACK_FRAMES {
            return Err(Status::resource_exhausted(format!("frames has {} images, over the limit of {MAX_TRACK_FRAMES}", r.frames.len())));
        }
        // Every image's size from its header, before anything is decoded.
        let max_pixels = self.state.limits.max_image_pixels;
        for (k, f) in r.frames.iter().enumerate() {
            let header = needlesim_identify::frame::png_dimensions(&f.png);
            let (w, h) = header.map_err(|e| ApiError::invalid(format!("frames[{k}].png"), format!("not a PNG image: {e}")))?;
            let pixels = u64::from(w) * u64::from(h);
            if pixels > max_pixels {
                return Err(ApiError::from(SizeLimit {
                    what: format!("frames[{k}].png ({w} × {h} pixels)"),
                    amount: pixels as f64,
                    limit: max_pixels,
                    unit: "pixels",
                    hint: " (server flag --max-image-pixels)".to_owned(),
                })
                .into());
            }
        }
        let permit = self.state.jobs.try_start(JobKind::Identify)?;
        let v2 = |v: &Option<pb::Vec2>| v.as_ref().map_or([0.0, 0.0], |v| [v.x, v.y]);
        let scale = match (r.m_per_px > 0.0, r.spacing_m > 0.0) {
            (true, false) => Scale::MetresPerPixel { m_per_px: r.m_per_px, origin_px: v2(&r.origin_px), origin_m: v2(&r.origin_m) },
            (false, true) => Scale::MarkerSpacing { spacing_m: r.spacing_m, origin_m: v2(&r.origin_m) },
            _ => return Err(Status::invalid_argument("m_per_px, spacing_m: give exactly one scale (a positive value)")),
        };
        let mut p = TrackParams::new(if r.bright { Polarity::Bright } else { Polarity::Dark }, scale);
        p.expected_markers = (r.expected_markers > 0).then_some(r.expected_markers as usize);
        p.max_image_pixels = max_pixels;
        p.validate().map_err(invalid("track parameters"))?;
        Ok(spawn_work("track", permit, move |report| {
            let frames: Vec<(f64, &[u8])> = r.frames.iter().map(|f| (f.t_s, f.png.as_slice())).collect();
            let tracks = track_png_bytes(&frames, &p, report).map_err(|e| e.context("frames"))?;
            Ok(pb::identify_progress::Result::Track(pb::TrackResult {
                n_markers: tracks.n_markers as u32,
                n_frames: tracks.n_frames() as u32,
                n_filled: tracks.detected.iter().filter(|d| !**d).count() as u32,
                tracks_csv: tracks.to_csv(),
            }))
        }))
    }

    async fn probe(&self, req: Request<pb::ProbeRequest>) -> Result<Response<Self::ProbeStream>, Status> {
        let r = req.into_inner();
        let permit = self.state.jobs.try_start(JobKind::Identify)?;
        let limits = self.state.limits.scene();
        let (tracks, log, model) = blocking(move || {
            let tracks = parse_tracks(&r.tracks_csv)?;
            let log = ProbeLog::from_csv(&r.probe_log_csv).map_err(invalid("probe_log_csv"))?;
            let model = match (&r.grid, &r.scene) {
                (Some(g), None) => {
                    let thickness_m = if r.thickness_m == 0.0 { 0.01 } else { r.thickness_m };
                    if !(thickness_m.is_finite() && thickness_m > 0.0) {
                        return Err(Status::invalid_argument(format!(
                            "thickness_m = {} must be finite and > 0",
                            needlesim_core::num::num(thickness_m)
                        )));
                    }
                    let plane = match r.plane.as_str() {
                        "" | "stress" => needlesim_core::PlaneModel::Stress { thickness_m },
                        "strain" => needlesim_core::PlaneModel::Strain { thickness_m },
                        m => {
                            return Err(Status::invalid_argument(format!(
                                "plane must be \"stress\" or \"strain\", found \"{}\"",
                                quote(m)
                            )));
                        }
                    };
                    // The model mesh is DEFAULT_GRID_REFINE times finer than the markers' grid.
                    let refine = needlesim_identify::probe::DEFAULT_GRID_REFINE;
                    let fine = |n: u32| (n as usize).saturating_sub(1).saturating_mul(refine) + 1;
                    let model_nodes = fine(g.nx).saturating_mul(fine(g.ny));
                    if model_nodes > limits.mesh.max_nodes {
                        return Err(Status::resource_exhausted(format!(
                            "grid has {} × {} markers, a model mesh of {model_nodes} nodes ({refine} times finer), over the limit of {}",
                            g.nx, g.ny, limits.mesh.max_nodes
                        )));
                    }
                    needlesim_scene::check_session_memory(model_nodes, 0, &limits).map_err(|e| Status::from(ApiError::from(e)))?;
                    grid_model(&tracks, g.nx as usize, g.ny as usize, g.width_m, g.height_m, plane, refine).map_err(invalid("grid"))?
                }
                (None, Some(_)) => {
                    let (scene, _) = scene_of(r.scene.as_ref(), &limits)?;
                    let mesh = scene.tissue.mesh().clone();
                    let p0: Vec<[f64; 2]> = (0..tracks.n_markers).map(|m| tracks.position_m(0, m)).collect();
                    let marker_node = register_markers(&mesh, &p0, 0.25 * needlesim_scene::mean_edge_m(&mesh)).map_err(invalid("scene"))?;
                    ProbeModel { plane: scene.tissue.materials().plane(), fixed_nodes: scene.fixed_nodes.clone(), marker_node, mesh }
                }
                _ => return Err(Status::invalid_argument("grid, scene: give exactly one model")),
            };
            Ok((tracks, log, model))
        })
        .await?;
        let opts = ProbeFitOptions { probe_marker: r.probe_marker.map(|m| m as usize), ..Default::default() };
        Ok(spawn_work("probe", permit, move |report| {
            let fit = fit_probe(&tracks, &log, &model, &opts, report)?;
            Ok(pb::identify_progress::Result::Probe(pb::ProbeResult {
                young_modulus_pa: fit.young_modulus_pa,
                young_modulus_sigma_pa: fit.young_modulus_sigma_pa,
                poisson_ratio: fit.poisson_ratio,
                poisson_ratio_sigma: fit.poisson_ratio_sigma,
                displacement_rms_m: fit.displacement_rms_m,
                force_rms_n: fit.force_rms_n,
                iterations: fit.iterations as u32,
                probe_marker: fit.probe_marker as u32,
                json: serde_json::to_string(&fit)?,
            }))
        }))
    }

    async fn needle(&self, req: Request<pb::NeedleRequest>) -> Result<Response<Self::NeedleStream>, Status> {
        let r = req.into_inner();
        let permit = self.state.jobs.try_start(JobKind::Identify)?;
        let limits = self.state.limits.clone();
        let (scene, scene_toml, tracks, log, traj) = blocking(move || {
            let (scene, text) = scene_of(r.scene.as_ref(), &limits.scene())?;
            let traj = if r.trajectory_csv.trim().is_empty() {
                let text = scene.example_trajectory.ok_or_else(|| {
                    Status::invalid_argument("trajectory_csv is empty and the scene is not a shipped example with its own")
                })?;
                needlesim_scene::Trajectory::parse_csv(text).map_err(|e| Status::internal(format!("{e:#}")))?
            } else {
                needlesim_scene::Trajectory::parse_csv(&r.trajectory_csv).map_err(anyhow::Error::new).map_err(invalid("trajectory_csv"))?
            };
            let tracks = parse_tracks(&r.tracks_csv)?;
            let log = ForceLog::from_csv(&r.force_log_csv).map_err(invalid("force_log_csv"))?;
            Ok((scene, text, tracks, log, traj))
        })
        .await?;
        if let Some(h) = r.tip_peak_ratio
            && !(h.is_finite() && h >= 0.0)
        {
            return Err(Status::invalid_argument(format!("tip_peak_ratio = {} must be finite and ≥ 0", needlesim_core::num::num(h))));
        }
        let opts = NeedleFitOptions { tip_peak_ratio: r.tip_peak_ratio, ..Default::default() };
        Ok(spawn_work("needle", permit, move |report| {
            let fit = fit_needle(&scene, &tracks, &log, &traj, &opts, report)?;
            let fitted_scene_toml = match &scene_toml {
                Some(t) => write_fitted_scene(t, &fit.region, &fit)?,
                None => String::new(),
            };
            Ok(pb::identify_progress::Result::Needle(pb::NeedleResult {
                friction_n_per_m: fit.friction_n_per_m,
                friction_sigma_n_per_m: fit.friction_sigma_n_per_m,
                tip_peak_ratio: fit.tip_peak_ratio,
                tip_peak_width_m: fit.tip_peak_width_m,
                peak_position_m: fit.peak_position_m,
                base_force_rms_diff_n: fit.base_force_rms_diff_n,
                fitted_scene_toml,
                json: serde_json::to_string(&fit)?,
            }))
        }))
    }
}
