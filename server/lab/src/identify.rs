//! The `needlesim-lab identify …` subcommands (argument parsing and file I/O only; the work is in
//! the needlesim-identify crate).

use clap::Subcommand;

/// `needlesim-lab identify <command>`.
#[derive(Subcommand, Debug)]
pub enum IdentifyCommand {
    /// Detect and track dot markers in a sequence of PNG images; writes marker tracks (CSV:
    /// frame,t_s,marker,x_px,y_px,x_m,y_m,detected).
    Track(TrackArgs),
    /// Render synthetic marker images (PNG) and frames.csv from marker tracks (their pixel
    /// columns; markers with detected = 0 are left out).
    Render(RenderArgs),
    /// Identify Young's modulus and Poisson's ratio from a probing experiment (marker tracks and
    /// a probe log t_s,probe_disp_x_m,probe_disp_y_m,force_x_n,force_y_n); prints JSON.
    Probe(ProbeArgs),
    /// Fit the needle force distribution (friction per length, tip peak) from an insertion
    /// experiment (marker tracks on every mesh node and a base force log
    /// t_s,force_x_n,force_y_n,depth_m); prints JSON, writes the fitted scene.
    Needle(NeedleArgs),
    /// Generate a synthetic probing or insertion experiment with the FEM model.
    Synth {
        #[command(subcommand)]
        what: SynthCommand,
    },
}

/// Runs one identify command.
pub fn run(cmd: IdentifyCommand) -> anyhow::Result<()> {
    match cmd {
        IdentifyCommand::Track(a) => run_track(a),
        IdentifyCommand::Render(a) => run_render(a),
        IdentifyCommand::Probe(a) => run_probe(a),
        IdentifyCommand::Needle(a) => run_needle(a),
        IdentifyCommand::Synth { what } => run_synth(what),
    }
}

// ---- identify track / identify render (marker images) ----

/// `identify track`: marker tracking in a directory of PNG images.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("polarity").required(true).args(["dark", "bright"])))]
#[command(group(clap::ArgGroup::new("scale").required(true).args(["spacing_m", "m_per_px"])))]
pub struct TrackArgs {
    /// The directory of images: frames.csv (frame,t_s,file) gives the files and their times;
    /// without it, --fps takes its *.png files in name order.
    #[arg(long)]
    pub images: std::path::PathBuf,
    /// Frame rate, frames per second: frame i of the *.png files in name order is at i / fps
    /// seconds (ignores frames.csv).
    #[arg(long)]
    pub fps: Option<f64>,
    /// The markers are dark dots on a bright background.
    #[arg(long)]
    pub dark: bool,
    /// The markers are bright dots on a dark background.
    #[arg(long)]
    pub bright: bool,
    /// Marker spacing in metres: the scale is this over the median distance between neighbouring
    /// markers in frame 0, and the marker nearest the image's bottom-left corner is at --origin-m.
    #[arg(long)]
    pub spacing_m: Option<f64>,
    /// Metres per pixel: pixel --origin-px is at --origin-m.
    #[arg(long)]
    pub m_per_px: Option<f64>,
    /// The pixel at --origin-m with --m-per-px, as x,y (default 0,0: the top-left pixel).
    #[arg(long, value_parser = parse_pair, conflicts_with = "spacing_m", allow_hyphen_values = true)]
    pub origin_px: Option<[f64; 2]>,
    /// The tissue position (metres, y up) of the origin pixel or the bottom-left marker, as x,y.
    #[arg(long, value_parser = parse_pair, default_value = "0,0", allow_hyphen_values = true)]
    pub origin_m: [f64; 2],
    /// The number of markers frame 0 must have.
    #[arg(long)]
    pub expected: Option<usize>,
    /// Gray-level threshold (0–255) instead of the automatic one.
    #[arg(long)]
    pub threshold: Option<f64>,
    /// Smallest blob taken as a marker, pixels.
    #[arg(long, default_value_t = 4)]
    pub min_area_px: usize,
    /// Largest blob taken as a marker, pixels.
    #[arg(long, default_value_t = 5000)]
    pub max_area_px: usize,
    /// Largest distance from a marker's predicted position to its detection, pixels (keep it
    /// below half the marker spacing).
    #[arg(long, default_value_t = 10.0)]
    pub max_jump_px: f64,
    /// Consecutive frames a marker may go undetected (filled in by prediction) before it is an
    /// error.
    #[arg(long, default_value_t = 2)]
    pub max_missing: usize,
    /// Where to write the marker tracks CSV.
    #[arg(short, long)]
    pub output: std::path::PathBuf,
}

/// `identify render`: synthetic marker images from marker tracks.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Marker tracks CSV (frame,t_s,marker,x_px,y_px,x_m,y_m,detected); the pixel columns place the dots.
    #[arg(long)]
    pub tracks: std::path::PathBuf,
    /// Where to write frame_0000.png, … and frames.csv (created if needed).
    #[arg(long)]
    pub out_dir: std::path::PathBuf,
    /// Image width, pixels.
    #[arg(long, default_value_t = 640)]
    pub width: u32,
    /// Image height, pixels.
    #[arg(long, default_value_t = 480)]
    pub height: u32,
    /// Dot radius, pixels.
    #[arg(long, default_value_t = 4.0)]
    pub dot_radius_px: f64,
    /// Gaussian blur sigma, pixels.
    #[arg(long, default_value_t = 1.0)]
    pub blur: f64,
    /// Gaussian noise sigma, gray levels (of 255).
    #[arg(long, default_value_t = 3.0)]
    pub noise: f64,
    /// Noise seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Bright dots on a dark background (default: dark dots on a bright background).
    #[arg(long)]
    pub bright: bool,
    /// Background gray level (default 200 for dark dots, 40 for bright ones).
    #[arg(long)]
    pub background: Option<f64>,
    /// Dot contrast against the background, gray levels.
    #[arg(long, default_value_t = 120.0)]
    pub contrast: f64,
}

/// Parses `x,y` into two finite numbers.
fn parse_pair(s: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x, y] = parts.as_slice() else { return Err(format!("expected x,y, got '{s}'")) };
    let num = |v: &str| v.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| format!("'{v}' is not a finite number"));
    Ok([num(x)?, num(y)?])
}

/// The frames of `dir` as `(t_s, path)`: from `--fps` over its *.png files in name order, else
/// from `dir/frames.csv`. Errors name the directory or the frames.csv line.
fn list_frames(dir: &std::path::Path, fps: Option<f64>) -> anyhow::Result<Vec<(f64, std::path::PathBuf)>> {
    use anyhow::{Context, bail};
    if !dir.is_dir() {
        bail!("{} is not a directory", dir.display());
    }
    if let Some(fps) = fps {
        if !(fps.is_finite() && fps > 0.0) {
            bail!("--fps must be a positive number, got {fps}");
        }
        let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
            .with_context(|| format!("cannot list {}", dir.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && p.extension().is_some_and(|x| x.eq_ignore_ascii_case("png")))
            .collect();
        files.sort();
        if files.is_empty() {
            bail!("no PNG images (*.png) in {}", dir.display());
        }
        return Ok(files.into_iter().enumerate().map(|(i, p)| (i as f64 / fps, p)).collect());
    }
    let index = dir.join("frames.csv");
    // Anything named frames.csv (a link, a FIFO) is read by the rule, which refuses it by name.
    if std::fs::symlink_metadata(&index).is_err() {
        bail!("{} has no frames.csv (frame,t_s,file): give --fps to take its *.png files in name order", dir.display());
    }
    let text = read_text(&index)?;
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    match lines.next() {
        Some((_, h)) if h.trim() == "frame,t_s,file" => {}
        // The line is not quoted: a file's lines never appear in errors.
        Some((i, h)) => {
            let found = needlesim_scene::limit::header_mismatch(h.split(',').map(str::trim), &["frame", "t_s", "file"]);
            bail!("{} line {}: expected the header 'frame,t_s,file', found {found}", index.display(), i + 1)
        }
        None => bail!("{} is empty: expected the header 'frame,t_s,file'", index.display()),
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        let cols: Vec<&str> = line.split(',').map(str::trim).collect();
        let [frame, t, file] = cols.as_slice() else {
            bail!("{} line {}: expected 3 columns (frame,t_s,file), found {}", index.display(), i + 1, cols.len())
        };
        if frame.parse::<usize>().ok() != Some(out.len()) {
            bail!(
                "{} line {}: frame `{}` out of order (expected {})",
                index.display(),
                i + 1,
                needlesim_scene::limit::clip(frame, 32),
                out.len()
            );
        }
        let t: f64 = t.parse().ok().filter(|t: &f64| t.is_finite()).with_context(|| {
            format!("{} line {}: t_s `{}` is not a number", index.display(), i + 1, needlesim_scene::limit::clip(t, 32))
        })?;
        out.push((t, dir.join(file)));
    }
    if out.is_empty() {
        bail!("{} lists no frames", index.display());
    }
    Ok(out)
}

/// Runs `identify track`.
fn run_track(a: TrackArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    use needlesim_identify::track::{Polarity, Scale, TrackParams, Tracker};
    let polarity = if a.bright { Polarity::Bright } else { Polarity::Dark };
    let scale = match (a.spacing_m, a.m_per_px) {
        (Some(spacing_m), _) => Scale::MarkerSpacing { spacing_m, origin_m: a.origin_m },
        (None, Some(m_per_px)) => Scale::MetresPerPixel { m_per_px, origin_px: a.origin_px.unwrap_or([0.0, 0.0]), origin_m: a.origin_m },
        (None, None) => anyhow::bail!("give --spacing-m or --m-per-px"),
    };
    let p = TrackParams {
        threshold: a.threshold,
        min_area_px: a.min_area_px,
        max_area_px: a.max_area_px,
        max_jump_px: a.max_jump_px,
        expected_markers: a.expected,
        max_missing_frames: a.max_missing,
        ..TrackParams::new(polarity, scale)
    };
    let frames = list_frames(&a.images, a.fps)?;
    let mut tracker = Tracker::new(p)?;
    for (t, path) in &frames {
        let bytes = needlesim_localfile::read_local_bytes(path, needlesim_localfile::MAX_LOCAL_FILE_BYTES)?;
        tracker.push_png(*t, &bytes).with_context(|| path.display().to_string())?;
    }
    let tracks = tracker.finish()?;
    std::fs::write(&a.output, tracks.to_csv()).with_context(|| format!("cannot write {}", a.output.display()))?;
    let filled = tracks.detected.iter().filter(|d| !**d).count();
    println!(
        "tracked {} markers over {} frames ({filled} positions filled in) -> {}",
        tracks.n_markers,
        tracks.n_frames(),
        a.output.display()
    );
    Ok(())
}

/// Runs `identify render`.
fn run_render(a: RenderArgs) -> anyhow::Result<()> {
    use needlesim_identify::render::{RenderParams, render_sequence};
    use needlesim_identify::track::Polarity;
    let tracks = read_tracks(&a.tracks)?;
    let polarity = if a.bright { Polarity::Bright } else { Polarity::Dark };
    let p = RenderParams {
        width_px: a.width,
        height_px: a.height,
        dot_radius_px: a.dot_radius_px,
        polarity,
        background: a.background.unwrap_or(if a.bright { 40.0 } else { 200.0 }),
        contrast: a.contrast,
        blur_sigma_px: a.blur,
        noise_sigma: a.noise,
        seed: a.seed,
    };
    let paths = render_sequence(&tracks, &p, &a.out_dir)?;
    println!("rendered {} frames of {} markers -> {}", paths.len(), tracks.n_markers, a.out_dir.display());
    Ok(())
}

// ---- identify probe / needle / synth (fits and synthetic experiments) ----

/// A local text file the user names (tracks, logs, a trajectory, frames.csv, a scene), read by
/// the one rule (crate needlesim-localfile): a regular file, not a link, not on /proc or /sys,
/// of at most 256 MiB, opened without blocking; errors name the path, never the contents.
fn read_text(path: &std::path::Path) -> anyhow::Result<String> {
    Ok(needlesim_localfile::read_local_file(path, needlesim_localfile::MAX_LOCAL_FILE_BYTES)?)
}

fn read_tracks(path: &std::path::Path) -> anyhow::Result<needlesim_identify::tracks::MarkerTracks> {
    use anyhow::Context;
    needlesim_identify::tracks::MarkerTracks::from_csv(&read_text(path)?).with_context(|| path.display().to_string())
}

fn plane_of(model: &str, thickness_m: f64) -> anyhow::Result<needlesim_core::PlaneModel> {
    use needlesim_core::PlaneModel;
    if !(thickness_m.is_finite() && thickness_m > 0.0) {
        anyhow::bail!("--thickness-m = {thickness_m} must be finite and > 0");
    }
    match model {
        "stress" => Ok(PlaneModel::Stress { thickness_m }),
        "strain" => Ok(PlaneModel::Strain { thickness_m }),
        m => anyhow::bail!("--plane must be stress or strain, found '{m}'"),
    }
}

/// Parses `nx,ny,width_m,height_m`.
fn parse_grid(s: &str) -> Result<(usize, usize, f64, f64), String> {
    let p: Vec<&str> = s.split(',').map(str::trim).collect();
    let [nx, ny, w, h] = p.as_slice() else { return Err(format!("expected nx,ny,width_m,height_m, got '{s}'")) };
    let int = |v: &str| v.parse::<usize>().map_err(|_| format!("'{v}' is not a node count"));
    let num =
        |v: &str| v.parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0).ok_or_else(|| format!("'{v}' is not a positive number"));
    Ok((int(nx)?, int(ny)?, num(w)?, num(h)?))
}

/// `identify probe`: E and ν from a probing experiment.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("model").required(true).args(["grid", "scene"])))]
pub struct ProbeArgs {
    /// Marker tracks CSV (frame,t_s,marker,x_px,y_px,x_m,y_m,detected); frame 0 is the unloaded reference.
    #[arg(long)]
    pub tracks: std::path::PathBuf,
    /// Probe log CSV (t_s,probe_disp_x_m,probe_disp_y_m,force_x_n,force_y_n): the probe's
    /// displacement and the force it applies to the tissue.
    #[arg(long)]
    pub probe_log: std::path::PathBuf,
    /// The markers form a regular grid: nx,ny,width_m,height_m; the mesh is that grid (its
    /// bottom row fixed).
    #[arg(long, value_parser = parse_grid)]
    pub grid: Option<(usize, usize, f64, f64)>,
    /// A scene (TOML file or shipped example): its mesh, fixed nodes and plane model; the markers
    /// are registered to its nodes.
    #[arg(long)]
    pub scene: Option<String>,
    /// Plane model with --grid: stress (a slice) or strain.
    #[arg(long, default_value = "stress")]
    pub plane: String,
    /// Thickness with --grid, m.
    #[arg(long, default_value_t = 0.01)]
    pub thickness_m: f64,
    /// With --grid: the model mesh is this many times finer than the markers' grid.
    #[arg(long, default_value_t = needlesim_identify::probe::DEFAULT_GRID_REFINE)]
    pub refine: usize,
    /// The marker the probe presses (default: the one that follows the probe).
    #[arg(long)]
    pub probe_marker: Option<usize>,
    /// Marker noise, m (default: estimated from the residuals).
    #[arg(long)]
    pub marker_sigma_m: Option<f64>,
    /// Force noise, N, as reported (default: the force log's scatter about a straight line in
    /// the probe displacement; the fit applies the logged force as the model's load).
    #[arg(long)]
    pub force_sigma_n: Option<f64>,
}

fn run_probe(a: ProbeArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    use needlesim_identify::probe::{ProbeFitOptions, ProbeModel, fit_probe, grid_model, register_markers};
    let tracks = read_tracks(&a.tracks)?;
    let log = needlesim_identify::logs::ProbeLog::from_csv(&read_text(&a.probe_log)?).with_context(|| a.probe_log.display().to_string())?;
    let model = match (&a.grid, &a.scene) {
        (Some((nx, ny, w, h)), _) => {
            grid_model(&tracks, *nx, *ny, *w, *h, plane_of(&a.plane, a.thickness_m)?, a.refine).context("--grid")?
        }
        (None, Some(spec)) => {
            let scene = needlesim_scene::load_scene(spec, &needlesim_core::MeshLimits::default())?;
            let mesh = scene.tissue.mesh().clone();
            let p0: Vec<[f64; 2]> = (0..tracks.n_markers).map(|m| tracks.position_m(0, m)).collect();
            let marker_node = register_markers(&mesh, &p0, 0.25 * needlesim_scene::mean_edge_m(&mesh))?;
            ProbeModel { plane: scene.tissue.materials().plane(), fixed_nodes: scene.fixed_nodes.clone(), marker_node, mesh }
        }
        (None, None) => anyhow::bail!("give --grid or --scene"),
    };
    let opts = ProbeFitOptions { probe_marker: a.probe_marker, marker_sigma_m: a.marker_sigma_m, force_sigma_n: a.force_sigma_n };
    let started = std::time::Instant::now();
    let fit = fit_probe(&tracks, &log, &model, &opts, &mut needlesim_identify::no_progress)?;
    let mut v = serde_json::to_value(&fit)?;
    v["fit_time_s"] = serde_json::json!(started.elapsed().as_secs_f64());
    println!("{}", serde_json::to_string_pretty(&v)?);
    Ok(())
}

/// `identify needle`: the needle force distribution from an insertion experiment.
#[derive(clap::Args, Debug)]
pub struct NeedleArgs {
    /// Marker tracks CSV: a marker on every mesh node of the scene; frame 0 undeformed.
    #[arg(long)]
    pub tracks: std::path::PathBuf,
    /// Base force log CSV (t_s,force_x_n,force_y_n,depth_m): the force on the needle base.
    #[arg(long)]
    pub force_log: std::path::PathBuf,
    /// The scene (TOML file or shipped example) of the phantom: mesh, material, needle.
    #[arg(long)]
    pub scene: String,
    /// The needle base trajectory CSV (t_s,x_m,y_m,theta_rad) in the experiment's time (default:
    /// the shipped example's own).
    #[arg(long)]
    pub trajectory: Option<std::path::PathBuf>,
    /// Write the scene with the fitted friction_n_per_m, tip_peak_ratio, tip_peak_width_m here.
    #[arg(long)]
    pub scene_out: Option<std::path::PathBuf>,
    /// The region whose parameters are replaced (default: the scene's first).
    #[arg(long)]
    pub region: Option<String>,
    /// Lateral half-width of the band of needle nodes around the shaft, m (default: the
    /// scene's capture radius).
    #[arg(long)]
    pub band_m: Option<f64>,
    /// Hold the tip peak height h at this value (e.g. the paper's 0.3) and fit q0 and w only.
    #[arg(long)]
    pub tip_peak_ratio: Option<f64>,
    /// Print the per-frame estimates (friction per length against depth) too.
    #[arg(long)]
    pub frames: bool,
}

/// The base scene's TOML text: the file, or the shipped example's.
fn scene_text(spec: &str) -> anyhow::Result<String> {
    if let Some(e) = needlesim_scene::EXAMPLES.iter().find(|e| e.0 == spec) {
        return Ok(e.1.to_owned());
    }
    read_text(std::path::Path::new(spec))
}

fn run_needle(a: NeedleArgs) -> anyhow::Result<()> {
    use anyhow::Context;
    use needlesim_identify::needle_fit::{NeedleFitOptions, fit_needle, write_fitted_scene};
    let scene = needlesim_scene::load_scene(&a.scene, &needlesim_core::MeshLimits::default())?;
    let traj = match (&a.trajectory, scene.example_trajectory) {
        (Some(p), _) => needlesim_scene::Trajectory::parse_csv(&read_text(p)?).with_context(|| p.display().to_string())?,
        (None, Some(text)) => needlesim_scene::Trajectory::parse_csv(text)?,
        (None, None) => anyhow::bail!("--trajectory is needed: the scene is not a shipped example with its own"),
    };
    let tracks = read_tracks(&a.tracks)?;
    let log = needlesim_identify::logs::ForceLog::from_csv(&read_text(&a.force_log)?).with_context(|| a.force_log.display().to_string())?;
    let started = std::time::Instant::now();
    let mut fit = fit_needle(
        &scene,
        &tracks,
        &log,
        &traj,
        &NeedleFitOptions { band_m: a.band_m, tip_tol_m: None, tip_peak_ratio: a.tip_peak_ratio },
        &mut needlesim_identify::no_progress,
    )?;
    let elapsed = started.elapsed().as_secs_f64();
    if let Some(r) = &a.region {
        fit.region = r.clone();
    }
    if let Some(out) = &a.scene_out {
        let text = write_fitted_scene(&scene_text(&a.scene)?, &fit.region, &fit)?;
        // The written scene must load (a relative mesh file must still resolve from its directory).
        needlesim_scene::parse_scene(&text, out.parent().unwrap_or(std::path::Path::new(".")), &needlesim_core::MeshLimits::default())
            .context("the fitted scene does not load")?;
        std::fs::write(out, text).with_context(|| format!("cannot write {}", out.display()))?;
    }
    let mut v = serde_json::to_value(&fit)?;
    if !a.frames {
        v.as_object_mut().map(|o| o.remove("frames"));
    }
    v["fit_time_s"] = serde_json::json!(elapsed);
    println!("{}", serde_json::to_string_pretty(&v)?);
    Ok(())
}

/// `identify synth …`.
#[derive(Subcommand, Debug)]
pub enum SynthCommand {
    /// A probing experiment on a grid phantom: writes probe-tracks.csv and probe-log.csv.
    Probe(SynthProbeArgs),
    /// A needle insertion simulated on a scene: writes needle-tracks.csv and needle-force.csv.
    Needle(SynthNeedleArgs),
}

/// Noise and camera options of `identify synth`.
#[derive(clap::Args, Debug)]
pub struct SynthNoiseArgs {
    /// Nominal camera scale, pixels per metre.
    #[arg(long, default_value_t = 5e3)]
    pub px_per_m: f64,
    /// Marker position noise (standard deviation), pixels.
    #[arg(long, default_value_t = 0.02)]
    pub marker_noise_px: f64,
    /// Force noise relative to the largest force.
    #[arg(long, default_value_t = 0.01)]
    pub force_noise_rel: f64,
    /// Noise seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output directory (created if needed).
    #[arg(long)]
    pub out: std::path::PathBuf,
}

impl SynthNoiseArgs {
    fn params(&self) -> needlesim_identify::experiment::NoiseParams {
        needlesim_identify::experiment::NoiseParams {
            px_per_m: self.px_per_m,
            marker_noise_px: self.marker_noise_px,
            force_noise_rel: self.force_noise_rel,
            seed: self.seed,
        }
    }
}

/// `identify synth probe`.
#[derive(clap::Args, Debug)]
pub struct SynthProbeArgs {
    /// Grid nodes along x and y.
    #[arg(long, default_value_t = 11)]
    pub nx: usize,
    #[arg(long, default_value_t = 11)]
    pub ny: usize,
    #[arg(long, default_value_t = 0.1)]
    pub width_m: f64,
    #[arg(long, default_value_t = 0.1)]
    pub height_m: f64,
    #[arg(long, default_value_t = 30e3)]
    pub young_modulus_pa: f64,
    #[arg(long, default_value_t = 0.45)]
    pub poisson_ratio: f64,
    /// stress or strain.
    #[arg(long, default_value = "stress")]
    pub plane: String,
    #[arg(long, default_value_t = 0.01)]
    pub thickness_m: f64,
    /// Probe displacement at the end of the ramp, x,y in m.
    #[arg(long, value_parser = parse_pair, default_value = "0.001,-0.005", allow_hyphen_values = true)]
    pub probe_disp_m: [f64; 2],
    /// Frames, including the unloaded frame 0.
    #[arg(long, default_value_t = 6)]
    pub frames: usize,
    #[arg(long, default_value_t = 0.5)]
    pub frame_interval_s: f64,
    #[arg(long, default_value_t = 100.0)]
    pub log_rate_hz: f64,
    /// Markers on every n-th grid node.
    #[arg(long, default_value_t = 1)]
    pub marker_stride: usize,
    #[command(flatten)]
    pub noise: SynthNoiseArgs,
}

/// `identify synth needle`.
#[derive(clap::Args, Debug)]
pub struct SynthNeedleArgs {
    /// The scene (TOML file or shipped example).
    #[arg(long, default_value = "paper-phantom")]
    pub scene: String,
    /// Trajectory CSV (default: the shipped example's own).
    #[arg(long)]
    pub trajectory: Option<std::path::PathBuf>,
    /// Stop at this time, s (default: the trajectory's end).
    #[arg(long)]
    pub t_end_s: Option<f64>,
    #[arg(long, default_value_t = 30.0)]
    pub frame_rate_hz: f64,
    #[arg(long, default_value_t = 100.0)]
    pub log_rate_hz: f64,
    #[command(flatten)]
    pub noise: SynthNoiseArgs,
}

fn write_out(dir: &std::path::Path, name: &str, text: &str) -> anyhow::Result<()> {
    use anyhow::Context;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let p = dir.join(name);
    std::fs::write(&p, text).with_context(|| format!("cannot write {}", p.display()))
}

fn run_synth(cmd: SynthCommand) -> anyhow::Result<()> {
    use anyhow::Context;
    use needlesim_identify::experiment::{NeedleSynthParams, ProbeSynthParams, synth_needle, synth_probe};
    match cmd {
        SynthCommand::Probe(a) => {
            let p = ProbeSynthParams {
                nx: a.nx,
                ny: a.ny,
                width_m: a.width_m,
                height_m: a.height_m,
                plane: plane_of(&a.plane, a.thickness_m)?,
                material: needlesim_core::Material { young_modulus_pa: a.young_modulus_pa, poisson_ratio: a.poisson_ratio },
                probe_column: None,
                probe_disp_m: a.probe_disp_m,
                n_frames: a.frames,
                frame_interval_s: a.frame_interval_s,
                log_rate_hz: a.log_rate_hz,
                marker_stride: a.marker_stride,
                noise: a.noise.params(),
            };
            let ex = synth_probe(&p)?;
            write_out(&a.noise.out, "probe-tracks.csv", &ex.tracks.to_csv())?;
            write_out(&a.noise.out, "probe-log.csv", &ex.log.to_csv())?;
            let [mx, my] = ex.marker_grid;
            println!(
                "{}",
                serde_json::to_string_pretty(&serde_json::json!({
                    "markers": ex.tracks.n_markers,
                    "marker_grid": [mx, my],
                    "frames": ex.tracks.n_frames(),
                    "probe_marker": ex.probe_marker,
                    "grid_arg": format!("{mx},{my},{},{}", a.width_m, a.height_m),
                    "out": a.noise.out.display().to_string(),
                }))?
            );
        }
        SynthCommand::Needle(a) => {
            let scene = needlesim_scene::load_scene(&a.scene, &needlesim_core::MeshLimits::default())?;
            let traj = match (&a.trajectory, scene.example_trajectory) {
                (Some(p), _) => needlesim_scene::Trajectory::parse_csv(&read_text(p)?).with_context(|| p.display().to_string())?,
                (None, Some(text)) => needlesim_scene::Trajectory::parse_csv(text)?,
                (None, None) => anyhow::bail!("--trajectory is needed: the scene is not a shipped example with its own"),
            };
            let p = NeedleSynthParams {
                frame_rate_hz: a.frame_rate_hz,
                log_rate_hz: a.log_rate_hz,
                t_end_s: a.t_end_s,
                noise: a.noise.params(),
            };
            let ex = synth_needle(&scene, &traj, &p)?;
            write_out(&a.noise.out, "needle-tracks.csv", &ex.tracks.to_csv())?;
            write_out(&a.noise.out, "needle-force.csv", &ex.log.to_csv())?;
            println!(
                "{}",
                serde_json::to_string_pretty(&serde_json::json!({
                    "markers": ex.tracks.n_markers,
                    "frames": ex.tracks.n_frames(),
                    "force_samples": ex.log.times_s.len(),
                    "force_sigma_n": ex.force_sigma_n,
                    "out": a.noise.out.display().to_string(),
                }))?
            );
        }
    }
    Ok(())
}
