//! The synthetic experiment generator: probing and needle-insertion experiments simulated with the
//! FEM model, written as marker tracks ([`MarkerTracks`]) and force logs, with seeded noise.
//!
//! **Probing** ([`synth_probe`]): a rectangular phantom (an `nx × ny` grid mesh), its bottom edge
//! fixed, a probe pressing one top-surface node with a displacement ramp
//! $d(t) = d_{max}\,\min(1, t/t_{end})$. The markers are the grid nodes with both indices
//! multiples of `marker_stride`. Frame $k$ is taken at $t_k = k\,\Delta t$, frame 0 undeformed.
//! The probe log (`t_s,probe_disp_x_m,probe_disp_y_m,force_x_n,force_y_n`, [`ProbeLog`]) holds
//! the probe displacement (exact: the robot's encoders) and the force the probe applies to the
//! tissue (the reaction at the probed node), with Gaussian noise of standard deviation
//! $\sigma_F = \text{rel}\cdot\max_t |F(t)|$.
//!
//! **Needle insertion** ([`synth_needle`]): the simulator itself run on a scene along a trajectory
//! at the scene's tick rate (needlesim-offline's [`ScriptedRun`]); every mesh node is a marker,
//! sampled at the camera rate from [`Simulation::displacement_field_into`]; the base force log
//! (`t_s,force_x_n,force_y_n,depth_m`, [`ForceLog`]) at its own rate, force noise as above.
//!
//! [`Simulation::displacement_field_into`]: needlesim_core::sim::Simulation::displacement_field_into
//!
//! Marker positions are written in pixels through a nominal camera (`px_per_m`, a 20 px margin,
//! image rows downwards: the tracks render as images with `identify render`) with Gaussian noise
//! of `marker_noise_px` pixels; the metre columns (tissue frame, y up) are the noisy pixel
//! positions mapped back.

use std::ops::ControlFlow;

use anyhow::{Context, Result, bail};
use needlesim_core::{Material, MaterialMap, MeshLimits, NodeCondition, PlaneModel, RectMeshParams, StaticProblem};
use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

use crate::logs::{ForceLog, ProbeLog};
use crate::tracks::MarkerTracks;
use needlesim_scene::{Scene, Trajectory};

/// Seeded Gaussian noise (Box–Muller on a small fast generator).
pub struct Noise {
    rng: SmallRng,
}

impl Noise {
    pub fn new(seed: u64) -> Self {
        Self { rng: SmallRng::seed_from_u64(seed) }
    }
    /// A standard normal sample.
    pub fn gauss(&mut self) -> f64 {
        let u1: f64 = self.rng.random::<f64>().max(1e-300);
        let u2: f64 = self.rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// Marker and force noise and the nominal camera scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseParams {
    /// Pixels per metre of the nominal camera (y up, origin at the mesh origin).
    pub px_per_m: f64,
    /// Standard deviation of marker positions, pixels.
    pub marker_noise_px: f64,
    /// Force noise relative to the largest force magnitude of the experiment.
    pub force_noise_rel: f64,
    pub seed: u64,
}

impl Default for NoiseParams {
    /// 0.2 mm per pixel, 0.02 px marker noise, 1 % force noise, seed 1.
    fn default() -> Self {
        Self { px_per_m: 5e3, marker_noise_px: 0.02, force_noise_rel: 0.01, seed: 1 }
    }
}

/// A probing experiment to simulate.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeSynthParams {
    pub nx: usize,
    pub ny: usize,
    pub width_m: f64,
    pub height_m: f64,
    pub plane: PlaneModel,
    pub material: Material,
    /// Top-edge node index (0..nx) the probe presses; `None`: the middle one.
    pub probe_column: Option<usize>,
    /// Probe displacement at the end of the ramp.
    pub probe_disp_m: [f64; 2],
    /// Frames, including the undeformed frame 0.
    pub n_frames: usize,
    pub frame_interval_s: f64,
    /// Probe log rate.
    pub log_rate_hz: f64,
    /// Markers on every `marker_stride`-th grid node in both directions.
    pub marker_stride: usize,
    pub noise: NoiseParams,
}

impl Default for ProbeSynthParams {
    /// A 0.1 m square PVC-like phantom (E = 30 kPa, ν = 0.45, 1 cm slice), 11 × 11 nodes, the
    /// top middle node pressed 5 mm down and 1 mm sideways over 5 frames.
    fn default() -> Self {
        Self {
            nx: 11,
            ny: 11,
            width_m: 0.1,
            height_m: 0.1,
            plane: PlaneModel::Stress { thickness_m: 0.01 },
            material: Material { young_modulus_pa: 30e3, poisson_ratio: 0.45 },
            probe_column: None,
            probe_disp_m: [0.001, -0.005],
            n_frames: 6,
            frame_interval_s: 0.5,
            log_rate_hz: 100.0,
            marker_stride: 1,
            noise: NoiseParams::default(),
        }
    }
}

/// A simulated probing experiment and its ground truth.
#[derive(Debug, Clone)]
pub struct ProbeExperiment {
    pub tracks: MarkerTracks,
    pub log: ProbeLog,
    /// The marker the probe presses.
    pub probe_marker: usize,
    /// Grid node of each marker.
    pub marker_nodes: Vec<usize>,
    /// Markers per row and per column.
    pub marker_grid: [usize; 2],
}

/// Margin of the nominal camera image around the phantom, pixels.
pub const CAMERA_MARGIN_PX: f64 = 20.0;

/// Marker tracks through the nominal camera: pixel $(x_0 + (x - o_x)s,\ x_0 + (y_{top} - y)s)$
/// with $x_0$ = [`CAMERA_MARGIN_PX`] (image rows grow downwards), noise added in pixels, metres
/// recovered from the noisy pixels. `frame` is (the mesh's lower-left corner $o$, its top $y_{top}$).
fn to_tracks(
    times: Vec<f64>,
    positions_m: Vec<[f64; 2]>,
    n_markers: usize,
    frame: ([f64; 2], f64),
    noise: &NoiseParams,
    rng: &mut Noise,
) -> MarkerTracks {
    let s = noise.px_per_m;
    let (ox, top) = (frame.0[0], frame.1);
    let m0 = CAMERA_MARGIN_PX;
    let mut px = Vec::with_capacity(positions_m.len());
    let mut m = Vec::with_capacity(positions_m.len());
    for p in positions_m {
        let ideal = [m0 + (p[0] - ox) * s, m0 + (top - p[1]) * s];
        // Rounded as a tracker would report them (1e-4 px), which keeps the CSV short.
        let q = ideal.map(|v| ((v + noise.marker_noise_px * rng.gauss()) * 1e4).round() / 1e4);
        px.push(q);
        // Metres rounded to 1 nm (far below any marker noise), again for a short CSV.
        m.push([ox + (q[0] - m0) / s, top - (q[1] - m0) / s].map(|v| (v * 1e9).round() / 1e9));
    }
    let n = m.len();
    MarkerTracks { times_s: times, n_markers, positions_px: px, positions_m: m, detected: vec![true; n] }
}

fn check_noise(n: &NoiseParams) -> Result<()> {
    if !(n.px_per_m.is_finite() && n.px_per_m > 0.0) {
        bail!("px_per_m = {} must be finite and > 0", n.px_per_m);
    }
    if !(n.marker_noise_px.is_finite() && n.marker_noise_px >= 0.0) {
        bail!("marker_noise_px = {} must be finite and ≥ 0", n.marker_noise_px);
    }
    if !(n.force_noise_rel.is_finite() && n.force_noise_rel >= 0.0) {
        bail!("force_noise_rel = {} must be finite and ≥ 0", n.force_noise_rel);
    }
    Ok(())
}

/// Simulates a probing experiment.
///
/// Errors: a mesh the generator rejects, a probe column outside `0..nx`, fewer than 2 frames, a
/// stride that leaves fewer than 2 markers per row or column, non-positive rates or intervals,
/// invalid noise parameters or material.
pub fn synth_probe(p: &ProbeSynthParams) -> Result<ProbeExperiment> {
    check_noise(&p.noise)?;
    if p.n_frames < 2 {
        bail!("n_frames = {} must be at least 2 (the undeformed frame and a loaded one)", p.n_frames);
    }
    if !(p.frame_interval_s.is_finite() && p.frame_interval_s > 0.0 && p.log_rate_hz.is_finite() && p.log_rate_hz > 0.0) {
        bail!("frame_interval_s and log_rate_hz must be finite and > 0");
    }
    let mesh = RectMeshParams::new(p.nx, p.ny, p.width_m, p.height_m).build(&MeshLimits::default()).context("phantom mesh")?;
    let col = p.probe_column.unwrap_or(p.nx / 2);
    if col >= p.nx {
        bail!("probe column {col} is outside the top edge (0..{})", p.nx);
    }
    let stride = p.marker_stride.max(1);
    if !(p.nx - 1).is_multiple_of(stride) || !(p.ny - 1).is_multiple_of(stride) || (p.nx - 1) / stride < 1 || (p.ny - 1) / stride < 1 {
        bail!("marker_stride {stride} must divide nx - 1 = {} and ny - 1 = {}", p.nx - 1, p.ny - 1);
    }
    if !col.is_multiple_of(stride) {
        bail!("the probed column {col} must carry a marker (a multiple of marker_stride {stride})");
    }
    let mats = MaterialMap::per_region(&mesh, &[p.material], p.plane).context("material")?;
    let probe_node = (p.ny - 1) * p.nx + col;
    // Unit solutions: the probe node moved by (1, 0) and by (0, 1) (linearity).
    let mut unit = Vec::new();
    for d in [[1.0, 0.0], [0.0, 1.0]] {
        let mut conditions: Vec<(usize, NodeCondition)> = (0..p.nx).map(|i| (i, NodeCondition::Fixed)).collect();
        conditions.push((probe_node, NodeCondition::World { u_m: [Some(d[0]), Some(d[1])] }));
        let sol =
            StaticProblem { conditions, loads_n: vec![], points: vec![], patches: vec![] }.solve(&mesh, &mats).context("probe solve")?;
        let r = sol.reactions_n.iter().find(|r| r.0 == probe_node).map(|r| [r.1[0].unwrap_or(0.0), r.1[1].unwrap_or(0.0)]);
        unit.push((sol.displacement_m, r.unwrap_or([0.0; 2])));
    }
    let t_end = (p.n_frames - 1) as f64 * p.frame_interval_s;
    let disp_at = |t: f64| {
        let a = (t / t_end).clamp(0.0, 1.0);
        [a * p.probe_disp_m[0], a * p.probe_disp_m[1]]
    };
    let force_at = |d: [f64; 2]| [0, 1].map(|c| d[0] * unit[0].1[c] + d[1] * unit[1].1[c]);
    let mut rng = Noise::new(p.noise.seed);
    // Markers.
    let (mx, my) = ((p.nx - 1) / stride + 1, (p.ny - 1) / stride + 1);
    let marker_nodes: Vec<usize> = (0..my).flat_map(|j| (0..mx).map(move |i| j * stride * p.nx + i * stride)).collect();
    let probe_marker = marker_nodes.iter().position(|&n| n == probe_node).expect("probe column carries a marker");
    let mut times = Vec::new();
    let mut positions = Vec::new();
    for k in 0..p.n_frames {
        let t = k as f64 * p.frame_interval_s;
        times.push(t);
        let d = disp_at(t);
        for &n in &marker_nodes {
            let x = mesh.nodes_m()[n];
            let u = [0, 1].map(|c| d[0] * unit[0].0[2 * n + c] + d[1] * unit[1].0[2 * n + c]);
            positions.push([x[0] + u[0], x[1] + u[1]]);
        }
    }
    let tracks = to_tracks(times, positions, marker_nodes.len(), ([0.0, 0.0], p.height_m), &p.noise, &mut rng);
    let n_log = (t_end * p.log_rate_hz).round() as usize + 1;
    let f_max = force_at(p.probe_disp_m);
    let sigma_f = p.noise.force_noise_rel * f_max[0].hypot(f_max[1]);
    let mut log = ProbeLog::default();
    for k in 0..n_log {
        let t = k as f64 / p.log_rate_hz;
        let d = disp_at(t);
        let f = force_at(d);
        log.times_s.push(t);
        log.disp_m.push(d);
        log.force_n.push([f[0] + sigma_f * rng.gauss(), f[1] + sigma_f * rng.gauss()]);
    }
    Ok(ProbeExperiment { tracks, log, probe_marker, marker_nodes, marker_grid: [mx, my] })
}

/// A needle insertion to simulate.
#[derive(Debug, Clone, PartialEq)]
pub struct NeedleSynthParams {
    /// Camera frame rate.
    pub frame_rate_hz: f64,
    /// Base force log rate.
    pub log_rate_hz: f64,
    /// Stop at this time (default: the trajectory's end).
    pub t_end_s: Option<f64>,
    pub noise: NoiseParams,
}

impl Default for NeedleSynthParams {
    /// 30 Hz camera, 100 Hz force log, default noise.
    fn default() -> Self {
        Self { frame_rate_hz: 30.0, log_rate_hz: 100.0, t_end_s: None, noise: NoiseParams::default() }
    }
}

/// A simulated insertion: marker tracks (every mesh node, in node order) and the base force log.
#[derive(Debug, Clone)]
pub struct NeedleExperiment {
    pub tracks: MarkerTracks,
    pub log: ForceLog,
    /// The noise-free base force at the log times.
    pub true_force_n: Vec<[f64; 2]>,
    /// The force noise standard deviation used, N.
    pub force_sigma_n: f64,
}

/// Runs the simulator on `scene` along `traj` and samples an experiment.
///
/// Errors: a rate that is not finite and positive, an end time before the trajectory's start,
/// invalid noise parameters, and any simulation error (with the time it happened).
pub fn synth_needle(scene: &Scene, traj: &Trajectory, p: &NeedleSynthParams) -> Result<NeedleExperiment> {
    check_noise(&p.noise)?;
    if !(p.frame_rate_hz.is_finite() && p.frame_rate_hz > 0.0 && p.log_rate_hz.is_finite() && p.log_rate_hz > 0.0) {
        bail!("frame_rate_hz and log_rate_hz must be finite and > 0");
    }
    let t0 = traj.span_s().0;
    if let Some(te) = p.t_end_s
        && !(te.is_finite() && te > t0)
    {
        bail!("t_end_s = {te} must come after the trajectory's start ({t0} s)");
    }
    // The one run driver: the trajectory at the scene's tick rate, 8 nodes' columns between steps.
    let script = Script::Trajectory { trajectory: traj, end_s: p.t_end_s };
    let opts = RunOptions { max_ticks: u64::MAX, ..Default::default() };
    let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), script, opts)?;
    let rate = scene.params.tick_rate_hz;
    let mesh = scene.tissue.mesh();
    let n = mesh.n_nodes();
    let mut u = vec![0.0; 2 * n];
    let (mut next_frame, mut next_log) = (0u64, 0u64);
    let (mut times, mut positions) = (Vec::new(), Vec::new());
    let mut log = ForceLog::default();
    run.run(|tick, sim| {
        let t = tick.k as f64 / rate;
        let out = sim.output();
        let (force, depth) = (out.force_n, out.inserted_length_m);
        // A sample is due when its time is within half a tick of this tick.
        while (next_log as f64 / p.log_rate_hz) <= t + 0.5 / rate {
            log.times_s.push(t0 + next_log as f64 / p.log_rate_hz);
            log.force_n.push(force);
            log.depth_m.push(depth);
            next_log += 1;
        }
        if (next_frame as f64 / p.frame_rate_hz) <= t + 0.5 / rate {
            sim.displacement_field_into(&mut u);
            times.push(t0 + next_frame as f64 / p.frame_rate_hz);
            for (i, x) in mesh.nodes_m().iter().enumerate() {
                positions.push([x[0] + u[2 * i], x[1] + u[2 * i + 1]]);
            }
            next_frame += 1;
        }
        ControlFlow::Continue(())
    })?;
    let mut rng = Noise::new(p.noise.seed);
    let (lo, hi) = mesh.bounding_box_m();
    let tracks = to_tracks(times, positions, n, (lo, hi[1]), &p.noise, &mut rng);
    let f_max = log.force_n.iter().map(|f| f[0].hypot(f[1])).fold(0.0, f64::max);
    let sigma = p.noise.force_noise_rel * f_max;
    let true_force_n = log.force_n.clone();
    for f in &mut log.force_n {
        *f = [f[0] + sigma * rng.gauss(), f[1] + sigma * rng.gauss()];
    }
    Ok(NeedleExperiment { tracks, log, true_force_n, force_sigma_n: sigma })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probe_experiment_is_seeded_and_consistent() {
        let p = ProbeSynthParams::default();
        let a = synth_probe(&p).unwrap();
        let b = synth_probe(&p).unwrap();
        assert_eq!(a.tracks, b.tracks);
        assert_eq!(a.log, b.log);
        assert_eq!(a.tracks.n_frames(), 6);
        // The probed marker follows the probe (up to the marker noise).
        let d = a.tracks.displacement_m(5, a.probe_marker);
        assert!((d[1] + 0.005).abs() < 1e-5 && (d[0] - 0.001).abs() < 1e-5, "{d:?}");
        // The probe pushes down: the tissue pushes back, so the applied force points down.
        assert!(a.log.force_n.last().unwrap()[1] < 0.0);
        let back = ProbeLog::from_csv(&a.log.to_csv()).unwrap();
        assert_eq!(back.times_s.len(), a.log.times_s.len());
        let e = ProbeLog::from_csv("t_s,probe_disp_x_m\n").unwrap_err().to_string();
        assert!(e.contains("header must be"), "{e}");
        let e = ForceLog::from_csv("t_s,force_x_n,force_y_n,depth_m\n0,1,2,3\n0,1,2,3\n").unwrap_err().to_string();
        assert!(e.contains("line 3: t_s = 0 does not come after 0"), "{e}");
    }
}
