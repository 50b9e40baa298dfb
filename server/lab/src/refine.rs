//! The mesh-refinement study of issue 19: the three figure scenes (the paper phantom's
//! force–depth curve, the Fig. 3 miss, the Fig. 4 hit) run on a sequence of grids, each twice as
//! fine as the last (only `nx`/`ny` change, $h \to h/2 \to h/4 \to h/8$), with a chosen contact
//! and cutting model, and the figures that must not depend on the mesh measured on each.
//!
//! What is measured, from the run's own outputs (one tick at a time):
//! - **peak puncture force** $F_p$ (N): the largest resistance $-t\cdot F_{base}$ before the
//!   first puncture (the counter [`needlesim_core::sim::SimStats::punctures`] still 0). Before
//!   it only the tip's contact loads the tissue, so this is the force the surface gave way at.
//!   The three scenes have one region, so there is no region-boundary puncture to report.
//! - **sawtooth** $\sigma$ (N) and **slope** $b$ (N/m): the least-squares line $F \approx a + b\,d$
//!   of the resistance $F$ against the base's travel $d$ over the cutting ticks $K$ (after the
//!   first puncture, the base advancing along the needle), and the standard deviation of the
//!   residuals (the measure of the sawtooth).
//! - **mean cutting force** $\bar F_c$ (N): the mean resistance minus the friction trend, the
//!   line's value where the tip met the tissue, $\bar F_c = a + b\,d_0$, with $d_0$ the travel
//!   at the first contact (the tip at the undeformed surface). Friction grows with the length
//!   of shaft in the tissue, $d - d_0$ (the slope $b$ is about the friction per length $q_0$);
//!   what does not grow with it is what the tip meets: the cutting force and the friction peak
//!   behind the tip. Defined on the total force, not on one contact, because the two cutting
//!   models put the tip's force on different contacts (a carried contact with thresholds, the
//!   most distal shaft contact with toughness). (Taken at the puncture's travel $d_p$ instead,
//!   it would inherit the indentation's mesh dependence, below.)
//! - **indentation at puncture** $d_p - d_0$ (m): how far the base travelled from the first
//!   contact to the puncture. A force threshold on a point: in 2D the displacement under a
//!   point load grows like $\ln(1/h)$, so this does not converge with any point contact
//!   (reported, not asserted).
//! - **carried tip force** (N): with thresholds, the axial force on the contact carried by the
//!   tip ($t \cdot f$ of the contact in state `tip`, 0 at ticks with none) averaged over $K$
//!   (0 with energy-based cutting, which carries no contact inside a region).
//! - **closest approach** (m): $\min_k |c_k - p_k|$ of the tip $p_k$ to the target's displaced
//!   centre $c_k$ (the Fig. 3 miss distance; for Fig. 4 how close the steered tip came).
//!
//! The relative change between two meshes is $|a_{fine} - a_{coarse}| / |a_{fine}|$.

use std::ops::ControlFlow;
use std::path::Path;

use anyhow::{Context, Result, bail};
use needlesim_core::mesh::MeshLimits;
use needlesim_core::sim::NodeState;
use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};
use needlesim_scene::{EXAMPLES, Scene, Trajectory, parse_scene};
use std::fmt::Write as _;

/// The three figure scenes of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Figure {
    /// `paper-phantom`: vertical insertion 80 mm, hold, withdrawal (force–depth curve).
    Phantom,
    /// `fig3-target`: the oblique insertion that misses its target.
    Fig3,
    /// `fig4-steering`: the flexible needle steered into its target.
    Fig4,
}

impl Figure {
    /// The figure whose scene is named `name`.
    ///
    /// Errors: an unknown name, listing the known ones.
    pub fn parse(name: &str) -> Result<Self> {
        [Figure::Phantom, Figure::Fig3, Figure::Fig4]
            .into_iter()
            .find(|f| f.scene_name() == name)
            .with_context(|| format!("unknown scene '{name}' (known: paper-phantom, fig3-target, fig4-steering)"))
    }

    /// The shipped example's name.
    pub fn scene_name(self) -> &'static str {
        match self {
            Figure::Phantom => "paper-phantom",
            Figure::Fig3 => "fig3-target",
            Figure::Fig4 => "fig4-steering",
        }
    }

    /// The grids of the study, coarsest first: the shipped one is the second (the issue's
    /// "before" figures), each next one halves the element size ($n \to 2n - 1$ nodes a side).
    /// The study runs the first four by default; the fifth goes one halving further.
    pub fn grids(self) -> [(usize, usize); 5] {
        match self {
            Figure::Phantom => [(19, 19), (37, 37), (73, 73), (145, 145), (289, 289)],
            Figure::Fig3 => [(21, 13), (41, 25), (81, 49), (161, 97), (321, 193)],
            Figure::Fig4 => [(10, 10), (19, 19), (37, 37), (73, 73), (145, 145)],
        }
    }
}

/// How the needle holds and cuts the tissue in a variant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Model {
    /// The shipped scene's contact: the paper's node capture with node force thresholds.
    Nodes,
    /// Material points every 2 mm with the scene's force thresholds.
    Points,
    /// Material points with energy-based cutting ([`TOUGHNESS_J_PER_M2`]): puncture by the
    /// scene's force threshold on a material point, cutting by $F_c = G_c w$.
    Toughness,
    /// Energy-based cutting as [`Model::Toughness`], each contact spread over the needle's
    /// width (`needle.spread_contact`: a patch across the needle, whose compliance converges
    /// where a point's grows like $\ln(1/h)$).
    Width,
}

/// The fracture toughness of the study's energy-based variants, J/m²: $G_c w$ with a 17-gauge
/// needle's width ($w$ = 1.473 mm) gives 0.050 N, the shipped scenes' `cutting_force_n`.
pub const TOUGHNESS_J_PER_M2: f64 = 34.0;

/// The width given to the rigid needles of the energy-based variants, m (17 gauge).
pub const RIGID_DIAMETER_M: f64 = 1.473e-3;

impl Model {
    /// The model named `name` (its [`Self::label`]).
    ///
    /// Errors: an unknown name, listing the known ones.
    pub fn parse(name: &str) -> Result<Self> {
        [Model::Nodes, Model::Points, Model::Toughness, Model::Width]
            .into_iter()
            .find(|m| m.label() == name)
            .with_context(|| format!("unknown model '{name}' (known: nodes, points, toughness, width)"))
    }

    /// The model's name in tables and on the command line.
    pub fn label(self) -> &'static str {
        match self {
            Model::Nodes => "nodes",
            Model::Points => "points",
            Model::Toughness => "toughness",
            Model::Width => "width",
        }
    }
}

/// The scene TOML of a variant: the shipped example's text with its grid set to `nx × ny` and
/// its contact set by `model` (for material points the node-only `capture_radius_m` is
/// dropped). Errors when the example or one of its keys is not where the study expects it.
pub fn variant_toml(figure: Figure, nx: usize, ny: usize, model: Model) -> Result<String> {
    let (_, text, _) = EXAMPLES.iter().find(|e| e.0 == figure.scene_name()).context("the shipped example is missing")?;
    let mut out = String::with_capacity(text.len() + 64);
    let (mut saw_nx, mut saw_ny, mut saw_contact) = (false, false, false);
    for line in text.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        match key {
            "nx" => {
                out.push_str(&format!("nx = {nx}\n"));
                saw_nx = true;
            }
            "ny" => {
                out.push_str(&format!("ny = {ny}\n"));
                saw_ny = true;
            }
            "contact" => {
                saw_contact = true;
                match model {
                    Model::Nodes => out.push_str("contact = \"nodes\"\n"),
                    Model::Points => out.push_str("contact = \"points\"\n"),
                    Model::Toughness | Model::Width => {
                        out.push_str("contact = \"points\"\ncutting = \"toughness\"\n");
                        if model == Model::Width {
                            out.push_str("spread_contact = true\n");
                        }
                        if !text.contains("gauge") {
                            out.push_str(&format!("diameter_m = {RIGID_DIAMETER_M}\n"));
                        }
                    }
                }
            }
            "cutting_force_n" => {
                out.push_str(line);
                out.push('\n');
                if matches!(model, Model::Toughness | Model::Width) {
                    out.push_str(&format!("fracture_toughness_j_per_m2 = {TOUGHNESS_J_PER_M2}\n"));
                }
            }
            "capture_radius_m" if model != Model::Nodes => {}
            _ => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    if !(saw_nx && saw_ny && saw_contact) {
        bail!("example {} lacks one of nx, ny, contact", figure.scene_name());
    }
    Ok(out)
}

/// The figures measured on one run (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    pub nodes: usize,
    pub ticks: u64,
    pub peak_puncture_n: f64,
    pub mean_cutting_n: f64,
    pub carried_tip_n: f64,
    /// Base travel from the first contact to the first puncture, m.
    pub indentation_m: f64,
    pub sawtooth_n: f64,
    pub slope_n_per_m: f64,
    /// Closest approach to the scene's first target, m (NaN without targets).
    pub closest_m: f64,
    pub punctures: u64,
    /// Captures dropped because the working set was full (the node capture holds about one node
    /// per element along the shaft: on the finest Fig. 3 grid it passes the scenes' 128).
    pub capacity_drops: u64,
    /// Contacts taken as points although the model spreads them (`SimStats::patch_fallbacks`).
    pub patch_fallbacks: u64,
}

/// Runs a loaded scene along `traj` and measures it (module docs).
///
/// Errors: a failed run (the driver's error).
pub fn measure(scene: &Scene, traj: &Trajectory) -> Result<Measured> {
    let opts = RunOptions::default();
    let mut run = ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(traj), opts)?;
    let mut peak_puncture_n: f64 = 0.0;
    let mut closest_m = f64::INFINITY;
    let mut prev_base: Option<[f64; 2]> = None;
    let mut travel_m = 0.0;
    let mut puncture_travel_m = f64::NAN;
    let mut contact_travel_m = f64::NAN;
    // Sums over the cutting ticks: count, tip force, and the least-squares sums of (d, F).
    let (mut n, mut sum_tip) = (0.0, 0.0);
    let (mut sd, mut sf, mut sdd, mut sdf, mut sff) = (0.0, 0.0, 0.0, 0.0, 0.0);
    run.run(|_, sim| {
        let out = sim.output();
        let (c, s) = (out.base.theta_rad.cos(), out.base.theta_rad.sin());
        let resistance = -out.force_axial_n;
        if let Some(t) = out.targets.first() {
            closest_m = closest_m.min(t.distance_m);
        }
        let base = [out.base.x_m, out.base.y_m];
        let advance = prev_base.map_or(0.0, |p| (base[0] - p[0]) * c + (base[1] - p[1]) * s);
        prev_base = Some(base);
        travel_m += advance;
        if contact_travel_m.is_nan() && sim.stats().captures > 0 {
            contact_travel_m = travel_m;
        }
        if sim.stats().punctures == 0 {
            peak_puncture_n = peak_puncture_n.max(resistance);
        } else if advance > 1e-9 {
            if puncture_travel_m.is_nan() {
                puncture_travel_m = travel_m;
            }
            let tip_angle = out.tip_angle_rad;
            let t = [tip_angle.cos(), tip_angle.sin()];
            let tip_force: f64 =
                out.needle_nodes.iter().filter(|nn| nn.state == NodeState::Tip).map(|nn| nn.force_n[0] * t[0] + nn.force_n[1] * t[1]).sum();
            n += 1.0;
            sum_tip += tip_force;
            sd += travel_m;
            sf += resistance;
            sdd += travel_m * travel_m;
            sdf += travel_m * resistance;
            sff += resistance * resistance;
        }
        ControlFlow::Continue(())
    })?;
    let (sim, _) = run.finish()?;
    let stats = sim.stats();
    let slope = (n * sdf - sd * sf) / (n * sdd - sd * sd);
    let intercept = (sf - slope * sd) / n;
    // Residual sum of squares of the line, from the sums.
    let rss =
        sff - 2.0 * intercept * sf - 2.0 * slope * sdf + n * intercept * intercept + 2.0 * intercept * slope * sd + slope * slope * sdd;
    Ok(Measured {
        nodes: scene.tissue.mesh().n_nodes(),
        ticks: stats.ticks,
        peak_puncture_n,
        mean_cutting_n: intercept + slope * contact_travel_m,
        carried_tip_n: sum_tip / n,
        indentation_m: puncture_travel_m - contact_travel_m,
        sawtooth_n: (rss.max(0.0) / n).sqrt(),
        slope_n_per_m: slope,
        closest_m: if closest_m.is_finite() { closest_m } else { f64::NAN },
        punctures: stats.punctures,
        capacity_drops: stats.capacity_drops,
        patch_fallbacks: stats.patch_fallbacks,
    })
}

/// Builds the variant of `figure` on `nx × ny` with `model` and measures it along the shipped
/// trajectory.
pub fn run_variant(figure: Figure, nx: usize, ny: usize, model: Model) -> Result<Measured> {
    let text = variant_toml(figure, nx, ny, model)?;
    let scene = parse_scene(&text, Path::new("server/scenes"), &MeshLimits::default())
        .with_context(|| format!("{} on {nx}x{ny} ({})", figure.scene_name(), model.label()))?;
    let (_, _, csv) = EXAMPLES.iter().find(|e| e.0 == figure.scene_name()).context("the shipped example is missing")?;
    let traj = Trajectory::parse_csv(csv)?;
    measure(&scene, &traj).with_context(|| format!("{} on {nx}x{ny} ({})", figure.scene_name(), model.label()))
}

/// Relative change $|a - b| / |b|$ from `a` (coarser) to `b` (finer).
pub fn rel_change(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// One figure's rows of the study: every grid of [`Figure::grids`] with every model.
#[derive(Debug, Clone)]
pub struct FigureStudy {
    pub figure: Figure,
    /// (model, grid, measured), in the order run.
    pub rows: Vec<(Model, (usize, usize), Measured)>,
}

impl FigureStudy {
    /// The two finest grids' figures for `model`, coarser first.
    pub fn finest_pair(&self, model: Model) -> Option<(Measured, Measured)> {
        let m: Vec<Measured> = self.rows.iter().filter(|r| r.0 == model).map(|r| r.2).collect();
        (m.len() >= 2).then(|| (m[m.len() - 2], m[m.len() - 1]))
    }
}

/// Runs the study of `figure` for `models` on its grids (all four, or the first `max_grids`),
/// calling `progress` after each run.
pub fn study(figure: Figure, models: &[Model], max_grids: usize, mut progress: impl FnMut(&str)) -> Result<FigureStudy> {
    let mut rows = Vec::new();
    for &model in models {
        for &(nx, ny) in figure.grids().iter().take(max_grids) {
            let started = std::time::Instant::now();
            let m = run_variant(figure, nx, ny, model)?;
            progress(&format!("{} {nx}x{ny} {}: {:.1} s", figure.scene_name(), model.label(), started.elapsed().as_secs_f64()));
            rows.push((model, (nx, ny), m));
        }
    }
    Ok(FigureStudy { figure, rows })
}

/// The study as a markdown table, with the change between the two finest meshes per model.
pub fn to_markdown(studies: &[FigureStudy]) -> String {
    let mut s = String::new();
    for st in studies {
        let _ = writeln!(s, "\n### {}\n", st.figure.scene_name());
        let _ = writeln!(
            s,
            "| model | grid | nodes | peak puncture (N) | mean cutting (N) | closest approach (mm) | carried tip (N) | sawtooth σ (mN) | slope (N/m) | indentation (mm) |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
        for (model, (nx, ny), m) in &st.rows {
            let _ = writeln!(
                s,
                "| {} | {nx}×{ny} | {} | {:.4} | {:.4} | {:.3} | {:.4} | {:.1} | {:.2} | {:.2} |",
                model.label(),
                m.nodes,
                m.peak_puncture_n,
                m.mean_cutting_n,
                m.closest_m * 1e3,
                m.carried_tip_n,
                m.sawtooth_n * 1e3,
                m.slope_n_per_m,
                m.indentation_m * 1e3,
            );
            if m.patch_fallbacks > 0 {
                let _ = writeln!(s, "|  | ({} contacts taken as points: the patch did not fit) | | | | | | | | |", m.patch_fallbacks);
            }
            if m.capacity_drops > 0 {
                let _ = writeln!(s, "|  | (working set full: {} captures dropped) | | | | | | | | |", m.capacity_drops);
            }
        }
        let mut models: Vec<Model> = Vec::new();
        for r in &st.rows {
            if !models.contains(&r.0) {
                models.push(r.0);
            }
        }
        for model in models {
            if let Some((a, b)) = st.finest_pair(model) {
                let closest = if st.figure == Figure::Phantom {
                    // The phantom's target lies on the axis: the tip passes through it.
                    String::new()
                } else {
                    format!(", closest approach {:.1} %", 100.0 * rel_change(a.closest_m, b.closest_m))
                };
                let _ = writeln!(
                    s,
                    "\n{}: change between the two finest meshes: peak puncture {:.1} %, mean cutting {:.1} %{closest}; sawtooth {:.1} %, indentation {:.1} %",
                    model.label(),
                    100.0 * rel_change(a.peak_puncture_n, b.peak_puncture_n),
                    100.0 * rel_change(a.mean_cutting_n, b.mean_cutting_n),
                    100.0 * rel_change(a.sawtooth_n, b.sawtooth_n),
                    100.0 * rel_change(a.indentation_m, b.indentation_m),
                );
            }
        }
    }
    s
}
