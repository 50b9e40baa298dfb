//! needlesim-scene: the file formats of the solver's inputs. Scene files (TOML, edited by users)
//! and their conversion to the core's tissue model and simulation parameters; the exchange format
//! of the validation suite ([`exchange`]); base trajectories ([`Trajectory`], from
//! needlesim-trajectory). Shipped examples live in server/scenes and are embedded in the binary.

pub mod exchange;
pub mod exchange3d;
pub mod files;
pub mod limit;
pub mod scene3d;
pub mod tissues;
pub mod vtk;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use needlesim_core::compliance::TissueModel;
use needlesim_core::mesh::DiagonalPattern;
use needlesim_core::num::num;
use needlesim_core::sim::{ContactModel, SimParams, TargetParams, Viscoelastic, param_limits};
use needlesim_core::{
    BasePose, FlexibleNeedle, Material, MaterialMap, Mesh, MeshLimits, NeedleShape, PlaneModel, RectMeshParams, RegionNeedleParams,
    RigidNeedle,
};
use serde::Deserialize;

pub use files::{LocalFileError, MAX_LOCAL_FILE_BYTES, SceneFiles, read_local_file};
pub use limit::SizeLimit;
pub use needlesim_trajectory::{MAX_ABS_POSE, Pose2, Trajectory, TrajectoryError};
pub use needlesim_trajectory::{Pose3, Trajectory3, Trajectory3Error};
pub use scene3d::{
    EXAMPLES3D, Scene3d, estimated_session_bytes_3d, example_scene3d, load_scene3d, parse_scene3d, parse_scene3d_with, scene_dim,
};

/// The shipped examples: (name, scene TOML, trajectory CSV).
pub const EXAMPLES: &[(&str, &str, &str)] = &[
    ("paper-phantom", include_str!("../../scenes/paper-phantom.toml"), include_str!("../../scenes/paper-phantom.csv")),
    ("fig3-target", include_str!("../../scenes/fig3-target.toml"), include_str!("../../scenes/fig3-target.csv")),
    ("fig4-steering", include_str!("../../scenes/fig4-steering.toml"), include_str!("../../scenes/fig4-steering.csv")),
    ("bevel-tip", include_str!("../../scenes/bevel-tip.toml"), include_str!("../../scenes/bevel-tip.csv")),
];

/// A scene as written in TOML.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// 2 when given: 2D scenes need no `dim`; `dim = 3` scenes are read by [`scene3d`].
    pub dim: Option<i64>,
    pub name: Option<String>,
    pub description: Option<String>,
    /// Haptic tick rate.
    #[serde(default = "default_rate")]
    pub tick_rate_hz: f64,
    pub mesh: MeshSpec,
    #[serde(default)]
    pub plane: PlaneSpec,
    /// Boundary sets (by name) whose nodes are fixed, e.g. `["bottom"]`.
    #[serde(default)]
    pub fixed: Vec<String>,
    /// Further fixed nodes by index.
    #[serde(default)]
    pub fixed_nodes: Vec<usize>,
    pub regions: Vec<RegionSpec>,
    pub needle: NeedleSpec,
    #[serde(default)]
    pub targets: Vec<TargetSpec>,
    #[serde(default)]
    pub limits: LimitsSpec,
    /// Viscoelastic tissue: `[viscoelastic] long_term_ratio = E∞/E₀, relaxation_time_s = τ`, one
    /// standard-linear-solid relaxation of every modulus (the regions' `E` are the
    /// instantaneous moduli E₀). Absent: elastic.
    pub viscoelastic: Option<ViscoelasticSpec>,
}

/// The `[viscoelastic]` table: $E(t) = E_\infty + (E_0 - E_\infty) e^{-t/\tau}$ for every region.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViscoelasticSpec {
    /// $E_\infty / E_0$, in (0, 1].
    pub long_term_ratio: f64,
    /// $\tau$, s (> 0).
    pub relaxation_time_s: f64,
}

impl ViscoelasticSpec {
    /// Checks the values (2D and 3D scenes); the message names the key.
    pub fn check(&self) -> Result<()> {
        let g = self.long_term_ratio;
        if !(g.is_finite() && g > 0.0 && g <= 1.0) {
            bail!("viscoelastic.long_term_ratio = {}: must be in (0, 1] (E∞/E₀)", num(g));
        }
        let tau = self.relaxation_time_s;
        if !(tau.is_finite() && tau > 0.0) {
            bail!("viscoelastic.relaxation_time_s = {}: must be finite and > 0", num(tau));
        }
        Ok(())
    }

    /// The core's model.
    pub fn model(&self) -> Viscoelastic {
        Viscoelastic { long_term_ratio: self.long_term_ratio, relaxation_time_s: self.relaxation_time_s }
    }
}

fn default_rate() -> f64 {
    1000.0
}

/// The mesh: a generated grid or a Gmsh file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, tag = "type", rename_all = "lowercase")]
pub enum MeshSpec {
    /// A structured rectangle of `nx × ny` nodes; boundary sets bottom, top, left, right.
    Grid {
        nx: usize,
        ny: usize,
        width_m: f64,
        height_m: f64,
        #[serde(default)]
        origin_m: [f64; 2],
        #[serde(default)]
        pattern: PatternSpec,
    },
    /// A Gmsh ASCII file (2.2 or 4.1), relative to the scene file.
    Msh { file: PathBuf },
    /// A VTK unstructured grid of triangles (`.vtu`, or legacy `.vtk` as ASCII), relative to the
    /// scene file: regions from an integer cell-data array, named by `labels` ([`vtk`]).
    #[serde(alias = "vtk")]
    Vtu {
        file: PathBuf,
        /// `{ 1 = "tissue", 2 = "lesion" }`: every label of the file, named.
        #[serde(default)]
        labels: std::collections::BTreeMap<String, String>,
        /// The cell-data array of the labels (default: the first of [`vtk::DEFAULT_LABEL_ARRAYS`]).
        label_array: Option<String>,
    },
}

#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum PatternSpec {
    #[default]
    Alternate,
    Right,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// "stress" (a slice of given thickness) or "strain".
    pub model: String,
    pub thickness_m: f64,
}

impl Default for PlaneSpec {
    fn default() -> Self {
        Self { model: "stress".to_owned(), thickness_m: 0.01 }
    }
}

/// A tissue region: elasticity and needle interaction. Written as [`RegionToml`]: a `material`
/// from the tissue library ([`tissues`]) gives the keys the region does not write; the
/// defaults fill the rest.
#[derive(Debug, Clone, Deserialize)]
#[serde(try_from = "RegionToml")]
pub struct RegionSpec {
    pub name: String,
    /// The tissue library's material the region names, if any.
    pub material: Option<String>,
    pub young_modulus_pa: f64,
    pub poisson_ratio: f64,
    /// For grid meshes: the triangles whose centroid lies in this disc belong to the region
    /// (later regions win). Absent for the first (background) region; for .msh files regions are
    /// matched by physical-group name.
    pub disc: Option<DiscSpec>,
    pub friction_n_per_m: f64,
    pub static_friction_ratio: f64,
    pub tip_peak_ratio: f64,
    pub tip_peak_width_m: f64,
    pub puncture_force_n: f64,
    pub cutting_force_n: f64,
    /// Viscous friction per unit length and unit slip speed, N·s/m² (rate-dependent friction,
    /// `q₀ + b·|v|`; 0: rate-independent). 2D and 3D.
    pub friction_damping_n_s_per_m2: f64,
    /// Fracture toughness $G_c$, J/m², with `needle.cutting = "toughness"` (required then, for
    /// every region): the tip cuts with the force $G_c w$ ($w$ the needle's diameter) instead of
    /// cutting past contacts at `cutting_force_n`.
    pub fracture_toughness_j_per_m2: Option<f64>,
    /// The material's $G_c$, applied with `needle.cutting = "toughness"` when the region writes
    /// none.
    pub material_toughness_j_per_m2: Option<f64>,
}

/// A region as written in TOML: every value key optional when a `material` gives it.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionToml {
    pub name: String,
    /// A material of the tissue library ([`tissues::tissues`]).
    pub material: Option<String>,
    pub young_modulus_pa: Option<f64>,
    pub poisson_ratio: Option<f64>,
    pub disc: Option<DiscSpec>,
    pub friction_n_per_m: Option<f64>,
    pub static_friction_ratio: Option<f64>,
    pub tip_peak_ratio: Option<f64>,
    pub tip_peak_width_m: Option<f64>,
    pub puncture_force_n: Option<f64>,
    pub cutting_force_n: Option<f64>,
    pub friction_damping_n_s_per_m2: Option<f64>,
    pub fracture_toughness_j_per_m2: Option<f64>,
}

impl RegionToml {
    fn keys(&self) -> tissues::MaterialKeys {
        tissues::MaterialKeys {
            material: self.material.clone(),
            young_modulus_pa: self.young_modulus_pa,
            poisson_ratio: self.poisson_ratio,
            friction_n_per_m: self.friction_n_per_m,
            static_friction_ratio: self.static_friction_ratio,
            tip_peak_ratio: self.tip_peak_ratio,
            tip_peak_width_m: self.tip_peak_width_m,
            puncture_force_n: self.puncture_force_n,
            cutting_force_n: self.cutting_force_n,
            friction_damping_n_s_per_m2: self.friction_damping_n_s_per_m2,
        }
    }
}

impl TryFrom<RegionToml> for RegionSpec {
    type Error = String;
    fn try_from(t: RegionToml) -> Result<Self, String> {
        let r = t.keys().resolve(&t.name)?;
        Ok(Self {
            name: t.name,
            material: t.material,
            young_modulus_pa: r.young_modulus_pa,
            poisson_ratio: r.poisson_ratio,
            disc: t.disc,
            friction_n_per_m: r.friction_n_per_m,
            static_friction_ratio: r.static_friction_ratio,
            tip_peak_ratio: r.tip_peak_ratio,
            tip_peak_width_m: r.tip_peak_width_m,
            puncture_force_n: r.puncture_force_n,
            cutting_force_n: r.cutting_force_n,
            friction_damping_n_s_per_m2: r.friction_damping_n_s_per_m2,
            fracture_toughness_j_per_m2: t.fracture_toughness_j_per_m2,
            material_toughness_j_per_m2: r.material_toughness_j_per_m2,
        })
    }
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscSpec {
    pub center_m: [f64; 2],
    pub radius_m: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeedleSpec {
    pub length_m: f64,
    /// Initial base pose `[x_m, y_m, theta_rad]`.
    pub base: [f64; 3],
    /// With `contact = "nodes"`: a node within this lateral distance (m) of the shaft when the
    /// tip passes it becomes a needle node (default: half the mean edge length).
    pub capture_radius_m: Option<f64>,
    /// `points` (default): contact at material points `contact_spacing_m` apart along the
    /// shaft; `nodes`: the original paper's node capture.
    #[serde(default)]
    pub contact: ContactSpec,
    /// Arc length (m) between material contact points (default 2 mm).
    pub contact_spacing_m: Option<f64>,
    #[serde(default = "d_max_nodes")]
    pub max_nodes: usize,
    /// `rigid` (default) or `flexible`.
    #[serde(default)]
    pub model: NeedleModelSpec,
    /// Flexible needle: the gauge of a stainless steel needle (16, 17, 18, 20, 21, 22, 25;
    /// default 17), setting its flexural rigidity.
    pub gauge: Option<u32>,
    /// Flexible needle: the flexural rigidity EI in N·m² (instead of a gauge).
    pub flexural_rigidity_nm2: Option<f64>,
    /// Flexible needle: links of the discrete beam (default: one per 2 mm, at least 16).
    pub n_links: Option<usize>,
    /// Flexible needle: bevel tip, lateral over axial tip force (default 0: symmetric tip).
    pub bevel_force_ratio: Option<f64>,
    /// Flexible needle: initial bevel side, +1 or -1 (towards the needle's +n or -n).
    pub bevel_side: Option<f64>,
    /// How the tip cuts inside a region: `thresholds` (default: the contact at the tip is
    /// carried until its force exceeds the region's `cutting_force_n`) or `toughness`
    /// (energy-based, mesh-independent: the force $G_c w$ while the tip advances; needs
    /// `contact = "points"`, `diameter_m` or a gauge, and every region's
    /// `fracture_toughness_j_per_m2`).
    #[serde(default)]
    pub cutting: CuttingSpec,
    /// The needle's outer diameter $w$, m (the crack width of energy-based cutting); default
    /// for a flexible needle with a gauge: the gauge's outer diameter.
    pub diameter_m: Option<f64>,
    /// Spread each contact over the needle's width (`diameter_m` or the gauge's) instead of a
    /// point: a patch across the needle, whose compliance converges under mesh refinement
    /// (a point's grows like $\ln(1/h)$ in 2D). Needs `contact = "points"` and a width.
    #[serde(default)]
    pub spread_contact: bool,
}

/// How the tip cuts inside a region ([`NeedleSpec::cutting`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CuttingSpec {
    #[default]
    Thresholds,
    Toughness,
}

impl NeedleSpec {
    /// The crack width $w$ of energy-based cutting: `diameter_m`, else the gauge's outer
    /// diameter; `None` when neither is given.
    pub fn cutting_width_m(&self) -> Option<f64> {
        self.diameter_m.or_else(|| self.gauge.and_then(|g| GAUGES.iter().find(|(gg, _, _)| *gg == g).map(|&(_, od, _)| od)))
    }
}

/// How the needle holds the tissue ([`needlesim_core::sim::ContactModel`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactSpec {
    #[default]
    Points,
    Nodes,
}

/// The needle model a scene chooses.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NeedleModelSpec {
    #[default]
    Rigid,
    Flexible,
}

/// Regular-wall stainless steel needle gauges: (gauge, outer, inner diameter in m).
const GAUGES: [(u32, f64, f64); 7] = [
    (16, 1.651e-3, 1.194e-3),
    (17, 1.473e-3, 1.067e-3),
    (18, 1.270e-3, 0.838e-3),
    (20, 0.908e-3, 0.603e-3),
    (21, 0.819e-3, 0.514e-3),
    (22, 0.718e-3, 0.413e-3),
    (25, 0.515e-3, 0.260e-3),
];

/// Young's modulus of the stainless steel of the gauge table, Pa.
const STEEL_E_PA: f64 = 193e9;

impl NeedleSpec {
    /// The needle's shape parameters; errors name the offending key.
    pub fn shape(&self) -> Result<NeedleShape> {
        let flexible_keys = [
            ("gauge", self.gauge.is_some()),
            ("flexural_rigidity_nm2", self.flexural_rigidity_nm2.is_some()),
            ("n_links", self.n_links.is_some()),
            ("bevel_force_ratio", self.bevel_force_ratio.is_some()),
            ("bevel_side", self.bevel_side.is_some()),
        ];
        match self.model {
            NeedleModelSpec::Rigid => {
                if let Some((key, _)) = flexible_keys.iter().find(|(_, set)| *set) {
                    bail!("needle.{key} needs needle.model = \"flexible\" (the needle is rigid)");
                }
                Ok(NeedleShape::Rigid(RigidNeedle { length_m: self.length_m }))
            }
            NeedleModelSpec::Flexible => {
                let mut f = FlexibleNeedle::gauge17_steel(self.length_m);
                if self.gauge.is_some() && self.flexural_rigidity_nm2.is_some() {
                    bail!("needle: give either gauge or flexural_rigidity_nm2, not both");
                }
                if let Some(g) = self.gauge {
                    let Some(&(_, od, id)) = GAUGES.iter().find(|(gg, _, _)| *gg == g) else {
                        bail!("needle.gauge = {g} is not in the table (16, 17, 18, 20, 21, 22, 25); give flexural_rigidity_nm2 instead");
                    };
                    f.flexural_rigidity_nm2 = STEEL_E_PA * FlexibleNeedle::tube_second_moment_m4(od, id);
                }
                if let Some(ei) = self.flexural_rigidity_nm2 {
                    f.flexural_rigidity_nm2 = ei;
                }
                if let Some(n) = self.n_links {
                    f.n_links = n;
                }
                if let Some(b) = self.bevel_force_ratio {
                    f.bevel_force_ratio = b;
                }
                if let Some(side) = self.bevel_side {
                    f.bevel_side = side;
                }
                let shape = NeedleShape::Flexible(f);
                shape.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
                Ok(shape)
            }
        }
    }
}

fn d_max_nodes() -> usize {
    128
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetSpec {
    pub name: String,
    pub center_m: [f64; 2],
    #[serde(default)]
    pub radius_m: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitsSpec {
    #[serde(default = "d_step_m")]
    pub max_base_step_m: f64,
    #[serde(default = "d_step_rad")]
    pub max_base_step_rad: f64,
    #[serde(default = "d_iters")]
    pub max_active_set_iterations: usize,
    #[serde(default = "d_lookahead")]
    pub lookahead_m: f64,
}

fn d_step_m() -> f64 {
    0.002
}
fn d_step_rad() -> f64 {
    0.05
}
/// A slip front crossing the working set takes one pass per contact it reaches (60 mm at 2 mm
/// spacing: 30); the per-tick update budget bounds the work whatever the bound.
fn d_iters() -> usize {
    64
}
fn d_lookahead() -> f64 {
    0.01
}

impl Default for LimitsSpec {
    fn default() -> Self {
        Self {
            max_base_step_m: d_step_m(),
            max_base_step_rad: d_step_rad(),
            max_active_set_iterations: d_iters(),
            lookahead_m: d_lookahead(),
        }
    }
}

/// A loaded scene: the factorised tissue and the simulation parameters.
pub struct Scene {
    pub name: String,
    pub tissue: Arc<TissueModel>,
    pub params: SimParams,
    pub fixed_nodes: Vec<usize>,
    pub target_names: Vec<String>,
    /// The example trajectory shipped with the scene, if any.
    pub example_trajectory: Option<&'static str>,
}

/// What a scene may cost: the mesh's node and triangle counts and the memory a session of it
/// would hold ([`estimated_session_bytes`]). A scene over either is refused before its model is
/// factorised, with a [`SizeLimit`] (RESOURCE_EXHAUSTED) or `MeshError::TooMany*` in the chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneLimits {
    pub mesh: MeshLimits,
    /// Largest [`estimated_session_bytes`] of a scene, bytes.
    pub max_session_bytes: u64,
}

impl From<&MeshLimits> for SceneLimits {
    /// The mesh limits only (offline commands on the user's own machine): no memory bound.
    fn from(mesh: &MeshLimits) -> Self {
        Self { mesh: *mesh, max_session_bytes: u64::MAX }
    }
}

impl From<&SceneLimits> for SceneLimits {
    fn from(l: &SceneLimits) -> Self {
        *l
    }
}

/// Bytes per mesh node of the model, before the factor's fill: coordinates, triangles, the
/// assembled stiffness (about 18 non-zeros per row of 2 rows), the symbolic analysis and the
/// per-node vectors of the model and the simulation.
pub const MODEL_BYTES_PER_NODE: u64 = 1024;
/// Bytes per node and per doubling of the node count of the sparse Cholesky factor (nested
/// dissection on a 2D mesh fills O(n log n)).
pub const FACTOR_BYTES_PER_NODE_LOG2: u64 = 128;
/// Bytes per mesh node of the compliance columns cached for one needle node: two columns of
/// 2 doubles per mesh node.
pub const COLUMN_BYTES_PER_NODE: u64 = 2 * 2 * 8;

/// The memory a session of a scene with `n_nodes` mesh nodes and a needle of up to
/// `max_needle_nodes` working nodes (contacts) is estimated to hold, in bytes:
/// `n × (MODEL_BYTES_PER_NODE + FACTOR_BYTES_PER_NODE_LOG2 × ⌈log2 n⌉) + n × COLUMN_BYTES_PER_NODE
/// × (max_needle_nodes + CACHE_LOOKAHEAD_NODES + 3 × max_needle_nodes)`: the model and its
/// factor; the real-time column cache, bounded by `SimParams::max_cached_nodes` (a full working
/// set and the lookahead; columns the needle left are evicted); and the renderer's copies of the
/// contacts' nodes (up to 3 per material point). Calibrated as an upper bound: a 400 × 400 grid
/// measures 377 MiB of model and factor (BENCHMARKS.md) against 508 MiB estimated, a 31 × 31000
/// grid 2.6 GB against 3.4 GB.
pub fn estimated_session_bytes(n_nodes: usize, max_needle_nodes: usize) -> u64 {
    let n = n_nodes as u64;
    let log2_n = u64::from(64 - n.max(2).saturating_sub(1).leading_zeros());
    let model = n.saturating_mul(MODEL_BYTES_PER_NODE + FACTOR_BYTES_PER_NODE_LOG2 * log2_n);
    let cached_nodes =
        (max_needle_nodes as u64).saturating_mul(4).saturating_add(needlesim_core::sim::param_limits::CACHE_LOOKAHEAD_NODES as u64);
    let columns = n.saturating_mul(COLUMN_BYTES_PER_NODE).saturating_mul(cached_nodes);
    model.saturating_add(columns)
}

/// Refuses a scene whose [`estimated_session_bytes`] is over `limits.max_session_bytes`.
pub fn check_session_memory(n_nodes: usize, max_needle_nodes: usize, limits: &SceneLimits) -> Result<(), SizeLimit> {
    let estimate = estimated_session_bytes(n_nodes, max_needle_nodes);
    if estimate <= limits.max_session_bytes {
        return Ok(());
    }
    const MIB: u64 = 1 << 20;
    Err(SizeLimit {
        what: format!("the estimated memory of a session of this scene ({n_nodes} mesh nodes, up to {max_needle_nodes} needle nodes)"),
        amount: estimate.div_ceil(MIB) as f64,
        limit: limits.max_session_bytes / MIB,
        unit: "MiB",
        hint: " (server flag --max-session-memory-mb)".to_owned(),
    })
}

/// A shipped example by name ([`EXAMPLES`]), never a path: `None` for any other name. What a
/// name from a client resolves to.
pub fn example_scene(name: &str, limits: impl Into<SceneLimits>) -> Option<Result<Scene>> {
    let (name, toml_text, csv) = EXAMPLES.iter().find(|e| e.0 == name)?;
    let scene = parse_scene_with(toml_text, SceneFiles::None, limits).with_context(|| format!("example scene {name}"));
    Some(scene.map(|mut s| {
        s.example_trajectory = Some(csv);
        s
    }))
}

/// Reads a local scene: the name of a shipped example, else a path to a TOML file (read by
/// [`read_local_file`], as are the files it names).
pub fn load_scene(spec: &str, limits: impl Into<SceneLimits>) -> Result<Scene> {
    let limits = &limits.into();
    if let Some(scene) = example_scene(spec, limits) {
        return scene;
    }
    let path = Path::new(spec);
    if std::fs::symlink_metadata(path).is_err() {
        let names: Vec<&str> = EXAMPLES.iter().map(|e| e.0).collect();
        bail!("scene '{spec}' is neither a file nor a shipped example (examples: {})", names.join(", "));
    }
    let text = read_local_file(path, MAX_LOCAL_FILE_BYTES)?;
    parse_scene(&text, path.parent().unwrap_or(Path::new(".")), limits).with_context(|| format!("scene {}", path.display()))
}

/// Most `[` and `{` a scene's TOML may hold, wherever they stand. The TOML parser recurses once
/// per open bracket on some of its error paths, so the count bounds its stack depth: a scene
/// needs a few per region and target, and 1024 recursions fit a 2 MiB thread stack even in a
/// debug build (about 0.9 kB a level).
pub const MAX_TOML_BRACKETS: usize = 1024;

/// Most bytes of a scene's TOML, 2D or 3D, wherever it comes from (a client's `scene_toml`, an
/// upload's, a local file, an exercise): a scene is a few kB — its mesh is a grid, a box or a
/// file of its own, never inline — so this leaves room for comments while it bounds the parse
/// (issue 35: a 59 MB TOML of 3 M keys held a server thread for seconds).
pub const MAX_SCENE_TOML_BYTES: usize = 256 << 10;

/// Longest scene `name`, in characters (as a target's or a region's name): the name travels in
/// every ListSessions answer and log line of its sessions.
pub const MAX_SCENE_NAME_CHARS: usize = param_limits::MAX_NAME_CHARS;

/// Longest scene `description`, in characters.
pub const MAX_SCENE_DESCRIPTION_CHARS: usize = 1024;

/// A scene TOML of at most [`MAX_SCENE_TOML_BYTES`], checked before it is parsed: a
/// [`SizeLimit`] (RESOURCE_EXHAUSTED in the service) naming the limit otherwise.
pub(crate) fn check_toml_size(text: &str) -> Result<()> {
    if text.len() > MAX_SCENE_TOML_BYTES {
        return Err(anyhow::Error::new(SizeLimit {
            what: "the scene TOML".to_owned(),
            amount: text.len() as f64,
            limit: MAX_SCENE_TOML_BYTES as u64,
            unit: "bytes",
            hint: " (a scene is a few kB; a mesh comes as a file or an upload of its own)".to_owned(),
        }));
    }
    Ok(())
}

/// A scene's free text: `name` at most [`MAX_SCENE_NAME_CHARS`] characters (and not empty when
/// given), `description` at most [`MAX_SCENE_DESCRIPTION_CHARS`]; the error names the key and the
/// limit and quotes the text clipped. Shared by 2D and 3D scenes.
pub(crate) fn check_scene_text(name: Option<&str>, description: Option<&str>) -> Result<()> {
    if let Some(n) = name {
        param_limits::check_name("name", n).map_err(anyhow::Error::msg)?;
    }
    if let Some(d) = description {
        let chars = d.chars().count();
        if chars > MAX_SCENE_DESCRIPTION_CHARS {
            bail!("description: '{}' has {chars} characters, at most {MAX_SCENE_DESCRIPTION_CHARS}", limit::quote(d));
        }
    }
    Ok(())
}

/// Parses a local scene's TOML; `base_dir` resolves relative mesh files ([`SceneFiles::Local`]).
pub fn parse_scene(text: &str, base_dir: &Path, limits: impl Into<SceneLimits>) -> Result<Scene> {
    parse_scene_with(text, SceneFiles::Local(base_dir), limits)
}

/// Parses scene TOML, the mesh file it names (if any) coming from `files`: [`SceneFiles::None`]
/// for a scene from a client.
pub fn parse_scene_with(text: &str, files: SceneFiles, limits: impl Into<SceneLimits>) -> Result<Scene> {
    check_toml_size(text)?;
    let brackets = text.bytes().filter(|b| matches!(b, b'[' | b'{')).count();
    if brackets > MAX_TOML_BRACKETS {
        bail!("the scene TOML holds {brackets} '[' and '{{', over the limit of {MAX_TOML_BRACKETS}");
    }
    if scene_dim(text)? == 3 {
        bail!("dim = 3: this is a 3D scene; load it with the 3D scene loader (needlesim_scene::load_scene3d)");
    }
    let mut file: SceneFile = toml::from_str(text).map_err(|e| anyhow::anyhow!("{}", limit::toml_message(&e, text)))?;
    // A material's fracture toughness applies with energy-based cutting only, when the region
    // writes none.
    if file.needle.cutting == CuttingSpec::Toughness {
        for r in &mut file.regions {
            r.fracture_toughness_j_per_m2 = r.fracture_toughness_j_per_m2.or(r.material_toughness_j_per_m2);
        }
    }
    build_scene(&file, files, &limits.into())
}

/// Checks every number of the scene that the mesh and material checks do not, before anything
/// is built; each error names the key as written in the TOML and its allowed range.
fn check_values(f: &SceneFile) -> Result<()> {
    use needlesim_core::sim::param_limits::{MAX_NEEDLE_NODES, MAX_NEEDLE_NODES_FLEXIBLE};
    check_scene_text(f.name.as_deref(), f.description.as_deref())?;
    check_names(f.regions.iter().map(|r| r.name.as_str()), f.targets.iter().map(|t| t.name.as_str()))?;
    if !(f.tick_rate_hz.is_finite() && (100.0..=10_000.0).contains(&f.tick_rate_hz)) {
        bail!("tick_rate_hz = {}: must be between 100 and 10000", num(f.tick_rate_hz));
    }
    let n = &f.needle;
    if !(n.length_m.is_finite() && n.length_m > 0.0) {
        bail!("needle.length_m = {}: must be finite and > 0", num(n.length_m));
    }
    check_length("needle.length_m", n.length_m)?;
    if !(f.plane.thickness_m.is_finite() && f.plane.thickness_m > 0.0) {
        bail!("plane.thickness_m = {}: must be finite and > 0", num(f.plane.thickness_m));
    }
    check_length("plane.thickness_m", f.plane.thickness_m)?;
    if !n.base.iter().all(|v| v.is_finite()) {
        bail!("needle.base = [{}, {}, {}]: must be finite", num(n.base[0]), num(n.base[1]), num(n.base[2]));
    }
    if let Some(s) = n.contact_spacing_m {
        use needlesim_core::sim::param_limits::{MAX_CONTACT_SPACING_M, MIN_CONTACT_SPACING_M};
        if !(s.is_finite() && (MIN_CONTACT_SPACING_M..=MAX_CONTACT_SPACING_M).contains(&s)) {
            bail!("needle.contact_spacing_m = {}: must be between {MIN_CONTACT_SPACING_M} and {MAX_CONTACT_SPACING_M} m", num(s));
        }
        if n.contact == ContactSpec::Nodes {
            bail!("needle.contact_spacing_m is set but needle.contact = \"nodes\": the spacing applies to material points only");
        }
    }
    if let Some(r) = n.capture_radius_m
        && !(r.is_finite() && r > 0.0)
    {
        bail!("needle.capture_radius_m = {}: must be finite and > 0", num(r));
    }
    if let Some(d) = n.diameter_m
        && !(d.is_finite() && d > 0.0 && d <= 0.02)
    {
        bail!("needle.diameter_m = {}: must be finite, > 0 and ≤ 0.02 m", num(d));
    }
    if n.cutting == CuttingSpec::Toughness {
        if n.contact == ContactSpec::Nodes {
            bail!(
                "needle.cutting = \"toughness\" needs needle.contact = \"points\" (energy-based cutting acts at material points, not captured nodes)"
            );
        }
        if n.cutting_width_m().is_none() {
            bail!("needle.cutting = \"toughness\" needs the needle's width: give needle.diameter_m (or a gauge for a flexible needle)");
        }
    }
    if n.spread_contact {
        if n.contact == ContactSpec::Nodes {
            bail!("needle.spread_contact = true needs needle.contact = \"points\" (a captured node is a node)");
        }
        if n.cutting_width_m().is_none() {
            bail!("needle.spread_contact = true needs the needle's width: give needle.diameter_m (or a gauge for a flexible needle)");
        }
    }
    for (k, r) in f.regions.iter().enumerate() {
        match (n.cutting, r.fracture_toughness_j_per_m2) {
            (CuttingSpec::Toughness, None) => {
                bail!("regions[{k}] '{}': needle.cutting = \"toughness\" needs fracture_toughness_j_per_m2 in every region", r.name)
            }
            (CuttingSpec::Thresholds, Some(_)) => bail!(
                "regions[{k}] '{}': fracture_toughness_j_per_m2 is set but needle.cutting is not \"toughness\" (the region would cut at cutting_force_n)",
                r.name
            ),
            (_, Some(g)) if !(g.is_finite() && g >= 0.0) => {
                bail!("regions[{k}] '{}': fracture_toughness_j_per_m2 = {}: must be finite and ≥ 0", r.name, num(g))
            }
            _ => {}
        }
        let toughness = r.fracture_toughness_j_per_m2.unwrap_or(0.0);
        check_region_bounds(
            k,
            &r.name,
            r.young_modulus_pa,
            &[("friction_damping_n_s_per_m2", r.friction_damping_n_s_per_m2), ("fracture_toughness_j_per_m2", toughness)],
        )?;
    }
    let max_nodes = if n.model == NeedleModelSpec::Flexible { MAX_NEEDLE_NODES_FLEXIBLE } else { MAX_NEEDLE_NODES };
    if !(1..=max_nodes).contains(&n.max_nodes) {
        bail!("needle.max_nodes = {}: must be in 1..={max_nodes}", n.max_nodes);
    }
    for (k, r) in f.regions.iter().enumerate() {
        if let Some(first) = f.regions[..k].iter().position(|o| o.name == r.name) {
            bail!("regions[{k}]: the name '{}' is already used by regions[{first}]; region names must be unique", r.name);
        }
        check_region_needle_values(
            k,
            &r.name,
            [r.friction_n_per_m, r.static_friction_ratio, r.tip_peak_ratio, r.tip_peak_width_m, r.puncture_force_n, r.cutting_force_n],
        )?;
    }
    for (k, t) in f.targets.iter().enumerate() {
        if !t.center_m.iter().all(|v| v.is_finite()) {
            bail!("targets[{k}] ('{}').center_m = [{}, {}]: must be finite", t.name, num(t.center_m[0]), num(t.center_m[1]));
        }
        if !(t.radius_m.is_finite() && t.radius_m >= 0.0) {
            bail!("targets[{k}] ('{}').radius_m = {}: must be finite and ≥ 0", t.name, num(t.radius_m));
        }
        check_length(&format!("targets[{k}] ('{}').radius_m", t.name), t.radius_m)?;
    }
    for (k, r) in f.regions.iter().enumerate() {
        let b = r.friction_damping_n_s_per_m2;
        if !(b.is_finite() && b >= 0.0) {
            bail!("regions[{k}] ('{}').friction_damping_n_s_per_m2 = {}: must be finite and ≥ 0", r.name, num(b));
        }
    }
    if let Some(v) = &f.viscoelastic {
        v.check()?;
    }
    if let Some(d) = f.dim
        && d != 2
    {
        bail!("dim = {d}: must be 2 or 3");
    }
    check_limits(&f.limits)
}

/// Checks a region's needle keys (friction, static ratio, tip peak ratio and width, puncture and
/// cutting force, in that order), naming `regions[k] ('name').key`: shared by 2D and 3D scenes.
pub(crate) fn check_region_needle_values(k: usize, name: &str, values: [f64; 6]) -> Result<()> {
    let keys = ["friction_n_per_m", "static_friction_ratio", "tip_peak_ratio", "tip_peak_width_m", "puncture_force_n", "cutting_force_n"];
    type Rule = (fn(f64) -> bool, &'static str);
    let rules: [Rule; 6] = [
        (|v| v >= 0.0, "finite and ≥ 0"),
        (|v| v >= 1.0, "finite and ≥ 1"),
        (|v| v >= 0.0, "finite and ≥ 0"),
        (|v| v > 0.0, "finite and > 0"),
        (|v| v >= 0.0, "finite and ≥ 0"),
        (|v| v >= 0.0, "finite and ≥ 0"),
    ];
    for ((key, v), (ok, rule)) in keys.into_iter().zip(values).zip(rules) {
        if !(v.is_finite() && ok(v)) {
            bail!("regions[{k}] ('{name}').{key} = {}: must be {rule}", num(v));
        }
        if key == "tip_peak_width_m" {
            check_length(&format!("regions[{k}] ('{name}').{key}"), v)?;
        }
    }
    check_region_bounds(k, name, 0.0, &keys.into_iter().zip(values).filter(|(key, _)| *key != "tip_peak_width_m").collect::<Vec<_>>())
}

/// The names of a scene's regions and targets and the number of targets, against core's
/// parameter limits ([`param_limits::check_name`], [`param_limits::check_target_names`]),
/// checked before any message quotes a name: shared by 2D and 3D scenes.
pub(crate) fn check_names<'a>(regions: impl Iterator<Item = &'a str>, targets: impl ExactSizeIterator<Item = &'a str>) -> Result<()> {
    for (k, name) in regions.enumerate() {
        param_limits::check_name(&format!("regions[{k}]"), name).map_err(anyhow::Error::msg)?;
    }
    param_limits::check_target_names(targets).map_err(anyhow::Error::msg)
}

/// A length of the scene (`key` as written) at most [`param_limits::MAX_LENGTH_M`] (its sign and
/// finiteness are checked beside it).
pub(crate) fn check_length(key: &str, v: f64) -> Result<()> {
    if v > param_limits::MAX_LENGTH_M {
        bail!("{key} = {}: must be at most {} m", num(v), num(param_limits::MAX_LENGTH_M));
    }
    Ok(())
}

/// A region's Young's modulus at most [`param_limits::MAX_YOUNG_MODULUS_PA`] and its other
/// magnitudes (`values`, keys as written) at most [`param_limits::MAX_REGION_VALUE`], naming
/// `regions[k] ('name').key` and the bound: shared by 2D and 3D scenes (signs are checked beside).
pub(crate) fn check_region_bounds(k: usize, name: &str, young_modulus_pa: f64, values: &[(&str, f64)]) -> Result<()> {
    use param_limits::{MAX_REGION_VALUE, MAX_YOUNG_MODULUS_PA};
    if young_modulus_pa > MAX_YOUNG_MODULUS_PA {
        bail!("regions[{k}] ('{name}').young_modulus_pa = {}: must be at most {MAX_YOUNG_MODULUS_PA:e} Pa", num(young_modulus_pa));
    }
    for &(key, v) in values {
        if v > MAX_REGION_VALUE {
            bail!("regions[{k}] ('{name}').{key} = {}: must be at most {MAX_REGION_VALUE:e}", num(v));
        }
    }
    Ok(())
}

/// Checks the `[limits]` table, naming `limits.key`: shared by 2D and 3D scenes.
pub(crate) fn check_limits(l: &LimitsSpec) -> Result<()> {
    use needlesim_core::sim::param_limits::MAX_ACTIVE_SET_ITERATIONS;
    for (key, v) in [("max_base_step_m", l.max_base_step_m), ("max_base_step_rad", l.max_base_step_rad)] {
        if !(v.is_finite() && v > 0.0) {
            bail!("limits.{key} = {}: must be finite and > 0", num(v));
        }
    }
    if !(1..=MAX_ACTIVE_SET_ITERATIONS).contains(&l.max_active_set_iterations) {
        bail!("limits.max_active_set_iterations = {}: must be in 1..={MAX_ACTIVE_SET_ITERATIONS}", l.max_active_set_iterations);
    }
    if !(l.lookahead_m.is_finite() && l.lookahead_m >= 0.0) {
        bail!("limits.lookahead_m = {}: must be finite and ≥ 0", num(l.lookahead_m));
    }
    Ok(())
}

fn build_scene(f: &SceneFile, files: SceneFiles, scene_limits: &SceneLimits) -> Result<Scene> {
    let limits = &scene_limits.mesh;
    if f.regions.is_empty() {
        bail!("regions: at least one region is needed");
    }
    check_values(f)?;
    let mut mesh = match &f.mesh {
        MeshSpec::Grid { nx, ny, width_m, height_m, origin_m, pattern } => {
            let pattern = match pattern {
                PatternSpec::Alternate => DiagonalPattern::Alternate,
                PatternSpec::Right => DiagonalPattern::Right,
            };
            // Refused before the mesh is built when the node count alone is over the budget.
            if nx.saturating_mul(*ny) <= limits.max_nodes {
                check_session_memory(nx.saturating_mul(*ny), f.needle.max_nodes, scene_limits).context("mesh")?;
            }
            let m = RectMeshParams { nx: *nx, ny: *ny, width_m: *width_m, height_m: *height_m, origin_m: *origin_m, pattern }
                .build(limits)
                .context("mesh")?;
            assign_disc_regions(m, &f.regions, limits)?
        }
        MeshSpec::Msh { file } => {
            let file = file.to_string_lossy();
            let key = || format!("mesh.file = \"{}\"", limit::quote(&file));
            let text = files.read(&file).with_context(key)?;
            needlesim_core::msh::parse_msh(&text, limits).with_context(key)?.mesh
        }
        MeshSpec::Vtu { file, labels, label_array } => {
            let file = file.to_string_lossy();
            let key = || format!("mesh.file = \"{}\"", limit::quote(&file));
            let opts = vtk::VtkOptions { labels: vtk::LabelMap::from_table(labels).context("mesh")?, label_array: label_array.clone() };
            let text = files.read(&file).with_context(key)?;
            vtk::read_vtk(&text, 2, &opts).and_then(|m| m.to_tri_mesh(limits)).with_context(key)?
        }
    };
    // Materials and needle parameters in the mesh's region order, matched by name.
    let mut materials = Vec::new();
    let mut needle_params = Vec::new();
    for rname in mesh.region_names() {
        let r = f
            .regions
            .iter()
            .find(|r| &r.name == rname)
            .with_context(|| format!("regions: the mesh has a region '{rname}' but no [[regions]] entry is named so"))?;
        materials.push(Material { young_modulus_pa: r.young_modulus_pa, poisson_ratio: r.poisson_ratio });
        needle_params.push(RegionNeedleParams {
            friction_n_per_m: r.friction_n_per_m,
            static_friction_ratio: r.static_friction_ratio,
            tip_peak_ratio: r.tip_peak_ratio,
            tip_peak_width_m: r.tip_peak_width_m,
            puncture_force_n: r.puncture_force_n,
            cutting_force_n: r.cutting_force_n,
            friction_damping_n_s_per_m2: r.friction_damping_n_s_per_m2,
            toughness_cutting_force_n: match (f.needle.cutting, r.fracture_toughness_j_per_m2, f.needle.cutting_width_m()) {
                (CuttingSpec::Toughness, Some(g), Some(w)) => Some(g * w),
                _ => None,
            },
        });
    }
    for r in &f.regions {
        if !mesh.region_names().contains(&r.name) {
            bail!("regions: '{}' is not a region of the mesh (mesh regions: {})", r.name, mesh.region_names().join(", "));
        }
    }
    let plane = match f.plane.model.as_str() {
        "stress" => PlaneModel::Stress { thickness_m: f.plane.thickness_m },
        "strain" => PlaneModel::Strain { thickness_m: f.plane.thickness_m },
        m => bail!("plane.model must be \"stress\" or \"strain\", found \"{}\"", limit::quote(m)),
    };
    let mats = MaterialMap::per_region(&mesh, &materials, plane).context("regions")?;
    let mut fixed = f.fixed_nodes.clone();
    for set in &f.fixed {
        let nodes = mesh.boundary_set(set).with_context(|| {
            let names: Vec<&String> = mesh.boundary_sets().keys().collect();
            format!("fixed: the mesh has no boundary set '{}' (it has: {})", limit::quote(set), limit::quote(&format!("{names:?}")))
        })?;
        fixed.extend_from_slice(nodes);
    }
    fixed.sort_unstable();
    fixed.dedup();
    if let Some(&n) = fixed.iter().find(|&&n| n >= mesh.n_nodes()) {
        bail!("fixed_nodes: node {n} does not exist (the mesh has {} nodes)", mesh.n_nodes());
    }
    let n_fixed = fixed.len();
    check_session_memory(mesh.n_nodes(), f.needle.max_nodes, scene_limits).context("mesh")?;
    // Keep the boundary sets on the mesh (the fixed set gets a name for later reference).
    mesh.set_boundary_set("fixed", fixed.clone()).context("fixed")?;
    let tissue = Arc::new(tissue_model(mesh, mats, &fixed).with_context(|| format!("tissue ({n_fixed} fixed nodes)"))?);
    let mean_edge = mean_edge_m(tissue.mesh());
    let n = &f.needle;
    if n.model == NeedleModelSpec::Flexible
        && let Some(r) = n.capture_radius_m
        && r < 0.45 * mean_edge
    {
        // A curved path runs between node columns: with a smaller radius the tip can pass
        // between nodes without cutting any.
        tracing::warn!(
            "needle.capture_radius_m = {r} m is less than half the mean edge length ({:.4} m): a flexible needle's curved path may pass between nodes",
            0.5 * mean_edge
        );
    }
    let params = SimParams {
        needle: n.shape()?,
        initial_pose: BasePose::new(n.base[0], n.base[1], n.base[2]),
        contact: match n.contact {
            ContactSpec::Nodes => ContactModel::Nodes,
            ContactSpec::Points => ContactModel::MaterialPoints {
                spacing_m: n.contact_spacing_m.unwrap_or(ContactModel::DEFAULT_SPACING_M),
                width_m: if n.spread_contact { n.cutting_width_m().unwrap_or(0.0) } else { 0.0 },
            },
        },
        // The real-time thread never runs a sparse solve: offline drivers prefetch, live
        // sessions have a column worker.
        columns_in_step: false,
        capture_radius_m: n.capture_radius_m.unwrap_or(0.5 * mean_edge),
        max_needle_nodes: n.max_nodes,
        regions: needle_params,
        targets: f.targets.iter().map(|t| TargetParams { name: t.name.clone(), center_m: t.center_m, radius_m: t.radius_m }).collect(),
        tick_rate_hz: f.tick_rate_hz,
        max_base_step_m: f.limits.max_base_step_m,
        max_base_step_rad: f.limits.max_base_step_rad,
        max_active_set_iterations: f.limits.max_active_set_iterations,
        lookahead_m: f.limits.lookahead_m,
        viscoelastic: f.viscoelastic.map(|v| v.model()),
    };
    // Everything else the simulation checks (the needle's shape; a target outside the mesh, …):
    // a scene that loads makes a simulation.
    needlesim_core::Simulation::new(tissue.clone(), params.clone()).context("needle")?;
    Ok(Scene {
        name: f.name.clone().unwrap_or_else(|| "scene".to_owned()),
        tissue,
        params,
        fixed_nodes: fixed,
        target_names: f.targets.iter().map(|t| t.name.clone()).collect(),
        example_trajectory: None,
    })
}

/// The mean edge length of a mesh's triangles (each shared edge counted twice), the scale of
/// the default capture radius.
/// The factorised 2D tissue of `mesh` held at `fixed` ([`TissueModel::new`]). Not generic and
/// never inlined: needlesim-core's generic code is compiled in the crate that instantiates it, at
/// that crate's opt-level (Cargo.toml), and this crate is optimised in dev builds where the
/// server crate is not; the server builds uploaded meshes' tissues through here.
///
/// Errors: [`TissueModel::new`]'s.
#[inline(never)]
pub fn tissue_model(mesh: Mesh, materials: MaterialMap, fixed: &[usize]) -> Result<TissueModel, needlesim_core::compliance::TissueError> {
    TissueModel::new(mesh, materials, fixed)
}

pub fn mean_edge_m(mesh: &Mesh) -> f64 {
    let mut sum = 0.0;
    for t in mesh.triangles() {
        for k in 0..3 {
            let (a, b) = (mesh.nodes_m()[t[k]], mesh.nodes_m()[t[(k + 1) % 3]]);
            sum += (a[0] - b[0]).hypot(a[1] - b[1]);
        }
    }
    sum / (3 * mesh.n_triangles()) as f64
}

/// Regions of a generated grid: the first region is the background; each later region with a
/// `disc` claims the triangles whose centroid lies inside it.
fn assign_disc_regions(mesh: Mesh, regions: &[RegionSpec], limits: &MeshLimits) -> Result<Mesh> {
    if regions[0].disc.is_some() {
        bail!("regions[0] ('{}') is the background of a grid mesh and takes no disc", regions[0].name);
    }
    let mut region_of_tri = vec![0usize; mesh.n_triangles()];
    for (ri, r) in regions.iter().enumerate().skip(1) {
        let d = r.disc.with_context(|| format!("regions[{ri}] ('{}'): a grid mesh region after the first needs a disc", r.name))?;
        if !(d.radius_m.is_finite() && d.radius_m > 0.0 && d.center_m.iter().all(|v| v.is_finite())) {
            bail!("regions[{ri}] ('{}'): disc must have a finite centre and a radius > 0", r.name);
        }
        for (ti, t) in mesh.triangles().iter().enumerate() {
            let c = t.iter().fold([0.0; 2], |acc, &n| [acc[0] + mesh.nodes_m()[n][0] / 3.0, acc[1] + mesh.nodes_m()[n][1] / 3.0]);
            if (c[0] - d.center_m[0]).hypot(c[1] - d.center_m[1]) <= d.radius_m {
                region_of_tri[ti] = ri;
            }
        }
    }
    let names = regions.iter().map(|r| r.name.clone()).collect();
    Ok(Mesh::with_regions(mesh.nodes_m().to_vec(), mesh.triangles().to_vec(), region_of_tri, names, mesh.boundary_sets().clone(), limits)?)
}

/// The core's base pose of a trajectory's pose.
pub fn base_pose(p: Pose2) -> BasePose {
    BasePose::new(p.x_m, p.y_m, p.theta_rad)
}

/// A trajectory's pose of the core's base pose.
pub fn pose2(p: BasePose) -> Pose2 {
    Pose2::new(p.x_m, p.y_m, p.theta_rad)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped energy-based variants load with $F_c = G_c w$ per region, and every wrong
    /// combination of the keys is refused with a message naming the key.
    #[test]
    fn toughness_cutting_keys() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        for (file, width_m) in [
            ("paper-phantom-toughness.toml", 1.473e-3),
            ("fig3-target-toughness.toml", 1.473e-3),
            ("fig4-steering-toughness.toml", 0.718e-3),
        ] {
            let s = load_scene(dir.join(file).to_str().unwrap(), &MeshLimits::default()).unwrap();
            let fc = s.params.regions[0].toughness_cutting_force_n.expect("energy-based cutting");
            assert!((fc - 34.0 * width_m).abs() <= 1e-12, "{file}: F_c = {fc}");
            // Each contact spread over the needle's width (issue 19: converges under refinement).
            assert_eq!(s.params.contact, ContactModel::MaterialPoints { spacing_m: ContactModel::DEFAULT_SPACING_M, width_m }, "{file}");
        }
        // The shipped node scenes keep the threshold model.
        assert!(load_scene("paper-phantom", &MeshLimits::default()).unwrap().params.regions[0].toughness_cutting_force_n.is_none());
        let base = std::fs::read_to_string(dir.join("paper-phantom-toughness.toml")).unwrap();
        let err = |text: String| format!("{:#}", parse_scene(&text, Path::new("."), &MeshLimits::default()).err().expect("refused"));
        let e = err(base.replace("contact = \"points\"", "contact = \"nodes\""));
        assert!(e.contains("needle.cutting") && e.contains("points"), "{e}");
        let e = err(base.replace("diameter_m = 0.001473\n", ""));
        assert!(e.contains("diameter_m"), "{e}");
        // A spread contact needs material points and a width.
        let no_toughness = base.replace("cutting = \"toughness\"\n", "").replace("fracture_toughness_j_per_m2 = 34.0\n", "");
        let e = err(no_toughness.replace("contact = \"points\"", "contact = \"nodes\""));
        assert!(e.contains("needle.spread_contact") && e.contains("points"), "{e}");
        let e = err(no_toughness.replace("diameter_m = 0.001473\n", ""));
        assert!(e.contains("needle.spread_contact") && e.contains("diameter_m"), "{e}");
        let e = err(no_toughness.replace("diameter_m = 0.001473", "diameter_m = 0.008"));
        assert!(e.contains("width_m = 0.008"), "{e}");
        let e = err(base.replace("fracture_toughness_j_per_m2 = 34.0\n", ""));
        assert!(e.contains("fracture_toughness_j_per_m2") && e.contains("tissue"), "{e}");
        let e = err(base.replace("cutting = \"toughness\"\n", ""));
        assert!(e.contains("fracture_toughness_j_per_m2") && e.contains("cutting"), "{e}");
        let e = err(base.replace("= 34.0", "= -1.0"));
        assert!(e.contains("fracture_toughness_j_per_m2 = -1"), "{e}");
        let e = err(base.replace("diameter_m = 0.001473", "diameter_m = nan"));
        assert!(e.contains("needle.diameter_m"), "{e}");
        let e = err(base.replace("cutting = \"toughness\"", "cutting = \"energy\""));
        assert!(e.contains("energy"), "{e}");
    }

    #[test]
    fn shipped_examples_load() {
        for (name, _, csv) in EXAMPLES {
            let s = load_scene(name, &MeshLimits::default()).unwrap();
            assert!(s.tissue.mesh().n_nodes() > 100);
            Trajectory::parse_csv(csv).unwrap();
        }
    }

    /// Issue 13, found by the long fuzzing run: a mutated scene made the TOML parser recurse
    /// (`on_inline_table_open`, on an error path) until the 2 MiB test thread's stack overflowed,
    /// which aborts the process — the server, in a CreateSession. The exact input was not kept
    /// (an abort prints no case); the count of brackets bounds that recursion whatever the path.
    /// This test runs on a 2 MiB stack, as tokio's blocking threads have: within the limit the
    /// parser stays within it, past it the scene is refused before parsing.
    #[test]
    fn issue_13_bracket_count_bounds_the_toml_parsers_recursion() {
        let base = include_str!("../../scenes/paper-phantom.toml");
        let run = |text: String| {
            std::thread::Builder::new()
                .stack_size(2 << 20)
                .spawn(move || parse_scene(&text, Path::new("."), &MeshLimits::default()).err().map(|e| format!("{e:#}")))
                .unwrap()
                .join()
                .expect("the scene thread ends")
        };
        for open in ["{a", "{a=", "{a={", "[{a=", "{"] {
            let e = run(format!("{base}\nx = {}\n", open.repeat(MAX_TOML_BRACKETS))).expect("refused");
            assert!(e.contains("over the limit of 1024"), "{open}: {e}");
        }
        // Just under the limit, nested as deep as it allows: an error from the parser, not an
        // overflow.
        let n = MAX_TOML_BRACKETS - base.bytes().filter(|b| matches!(b, b'[' | b'{')).count();
        for open in ["{a", "{a=", "[{a="] {
            let per = open.matches(['[', '{']).count();
            let e = run(format!("{base}\nx = {}\n", open.repeat(n / per))).expect("a TOML error");
            assert!(e.contains("TOML parse error"), "{open}: {e}");
        }
    }

    #[test]
    fn issue_13_session_memory_estimate_refuses_a_31_by_31000_grid_and_fits_400_by_400() {
        let fits_400 = SceneLimits { mesh: MeshLimits::default(), max_session_bytes: 4608 << 20 };
        let server = SceneLimits { mesh: MeshLimits::default(), max_session_bytes: 1280 << 20 };
        let base = include_str!("../../scenes/paper-phantom.toml");
        let huge = base.replace("nx = 19", "nx = 31").replace("ny = 19", "ny = 31000");
        let e = parse_scene(&huge, Path::new("."), server).err().unwrap();
        let size = e.chain().find_map(|c| c.downcast_ref::<SizeLimit>()).unwrap_or_else(|| panic!("not a size limit: {e:#}"));
        assert_eq!((size.amount, size.limit), (estimated_session_bytes(961_000, 128).div_ceil(1 << 20) as f64, 1280));
        // The benchmark's largest grid, with its bounded column cache (issue 15), needs a server
        // started with 4.5 GiB per session; the offline commands have no memory bound.
        let big = base.replace("nx = 19", "nx = 400").replace("ny = 19", "ny = 400");
        assert!(parse_scene(&big, Path::new("."), server).is_err());
        assert_eq!(parse_scene(&big, Path::new("."), fits_400).unwrap().tissue.mesh().n_nodes(), 160_000);
        // 100 × 100 fits the default.
        let medium = base.replace("nx = 19", "nx = 100").replace("ny = 19", "ny = 100");
        assert!(parse_scene(&medium, Path::new("."), server).is_ok());
        // The estimate bounds the measured figures: 2.6 GB at 31 × 31000 when built (issue 13);
        // 377 MiB of model and factor at 400 × 400 (BENCHMARKS.md).
        assert!(estimated_session_bytes(961_000, 0) > 2_600_000_000);
        assert!(estimated_session_bytes(160_000, 0) > 377 << 20);
    }

    #[test]
    fn scene_errors_name_the_field() {
        let base = include_str!("../../scenes/paper-phantom.toml");
        let lim = MeshLimits::default();
        let e = parse_scene(&base.replace("young_modulus_pa = 30e3", "young_modulus_pa = -1"), Path::new("."), &lim).err().unwrap();
        assert!(format!("{e:#}").contains("Young's modulus E = -1"), "{e:#}");
        let e = parse_scene(&base.replace("fixed = [\"bottom\"]", "fixed = [\"floor\"]"), Path::new("."), &lim).err().unwrap();
        assert!(format!("{e:#}").contains("no boundary set 'floor'"), "{e:#}");
        let e = parse_scene(&base.replace("length_m = ", "lenght_m = "), Path::new("."), &lim).err().unwrap();
        assert!(format!("{e:#}").contains("lenght_m"), "{e:#}");
        let e = parse_scene(&base.replace("friction_n_per_m = 10", "friction_n_per_m = -3"), Path::new("."), &lim).err().unwrap();
        assert!(format!("{e:#}").contains("regions[0] ('tissue').friction_n_per_m = -3: must be finite and ≥ 0"), "{e:#}");
    }

    /// `n` targets named by `name(k)`, as TOML.
    fn targets_toml(n: usize, name: impl Fn(usize) -> String) -> String {
        (0..n).map(|k| format!("[[targets]]\nname = \"{}\"\ncenter_m = [0.05, 0.05]\nradius_m = 0.002\n\n", name(k))).collect()
    }

    #[test]
    fn issue_35_a_2d_scene_bounds_its_targets() {
        use needlesim_core::sim::param_limits::MAX_TARGETS;
        let old = "[[targets]]\nname = \"centre\"\ncenter_m = [0.05, 0.05]\nradius_m = 0.002\n";
        let base = include_str!("../../scenes/paper-phantom.toml");
        let ok = base.replace(old, &targets_toml(MAX_TARGETS, |k| format!("t{k}")));
        let s = parse_scene(&ok, Path::new("."), &MeshLimits::default()).unwrap();
        assert_eq!(s.params.targets.len(), MAX_TARGETS);
        let e = scene_error(old, &targets_toml(MAX_TARGETS + 1, |k| format!("t{k}")));
        assert_eq!(e, "targets: 17 given, at most 16");
        let e = scene_error(old, &targets_toml(2, |k| if k == 0 { "a".into() } else { String::new() }));
        assert_eq!(e, "targets[1]: the name is empty");
        let e = scene_error(old, &targets_toml(1, |_| "n".repeat(100_000)));
        assert!(e.starts_with("targets[0]: the name 'nnn") && e.ends_with("…' has 100000 characters, at most 64"), "{e}");
        assert!(e.len() < 150, "{e}");
        let e = scene_error("name = \"tissue\"", &format!("name = \"{}\"", "r".repeat(100_000)));
        assert!(e.starts_with("regions[0]: the name 'rrr") && e.len() < 150, "{e}");
        let e = scene_error(old, &targets_toml(2, |_| "same".into()));
        assert_eq!(e, "targets[1]: the name 'same' is already used by targets[0]; target names must be unique");
        let e = scene_error("radius_m = 0.002", "radius_m = 1e300");
        assert_eq!(e, "targets[0] ('centre').radius_m = 1e300: must be at most 10 m");
    }

    #[test]
    fn issue_35_a_2d_scene_refuses_physics_past_its_bounds() {
        for (old, new, want) in [
            ("length_m = 0.1", "length_m = 11", "needle.length_m = 11: must be at most 10 m"),
            ("thickness_m = 0.01", "thickness_m = 1e300", "plane.thickness_m = 1e300: must be at most 10 m"),
            ("thickness_m = 0.01", "thickness_m = -1", "plane.thickness_m = -1: must be finite and > 0"),
            (
                "young_modulus_pa = 30e3",
                "young_modulus_pa = 1e13",
                "regions[0] ('tissue').young_modulus_pa = 10000000000000: must be at most 1e12 Pa",
            ),
            ("friction_n_per_m = 10", "friction_n_per_m = 1e7", "regions[0] ('tissue').friction_n_per_m = 10000000: must be at most 1e6"),
            ("puncture_force_n = 0.3", "puncture_force_n = 1e300", "regions[0] ('tissue').puncture_force_n = 1e300: must be at most 1e6"),
            (
                "static_friction_ratio = 1.3",
                "static_friction_ratio = 2e6",
                "regions[0] ('tissue').static_friction_ratio = 2000000: must be at most 1e6",
            ),
            ("tip_peak_width_m = 0.005", "tip_peak_width_m = 12", "regions[0] ('tissue').tip_peak_width_m = 12: must be at most 10 m"),
            (
                "cutting_force_n = 0.05",
                "cutting_force_n = 0.05\nfriction_damping_n_s_per_m2 = 1e9",
                "regions[0] ('tissue').friction_damping_n_s_per_m2 = 1000000000: must be at most 1e6",
            ),
            ("model = \"stress\"", &format!("model = \"{}\"", "s".repeat(100_000)), ""),
            ("tick_rate_hz = 1000\n", &format!("dim = \"{}\"\ntick_rate_hz = 1000\n", "s".repeat(100_000)), ""),
        ] {
            let e = scene_error(old, new);
            if want.is_empty() {
                // A string of the client's is quoted clipped.
                assert!(e.contains("\"sss") && e.contains('…') && !e.contains(&"s".repeat(65)) && e.len() < 160, "{e}");
            } else {
                assert_eq!(e, want);
            }
        }
        // The bounds themselves are accepted.
        let base = include_str!("../../scenes/paper-phantom.toml");
        let edge =
            base.replace("young_modulus_pa = 30e3", "young_modulus_pa = 1e12").replace("friction_n_per_m = 10", "friction_n_per_m = 1e6");
        parse_scene(&edge, Path::new("."), &MeshLimits::default()).unwrap();
    }

    /// Issue 35: a scene's `name` and `description` are bounded (they travel in every
    /// ListSessions answer and log line), and so is the whole TOML, before it is parsed; the
    /// errors name the key or the TOML and the limit, quoting little.
    #[test]
    fn issue_35_scene_text_and_toml_size_are_bounded() {
        let e = scene_error("name = \"paper-phantom\"", &format!("name = \"{}\"", "n".repeat(200_000)));
        assert!(e.starts_with("name: the name 'nnn") && e.ends_with("has 200000 characters, at most 64") && e.len() < 200, "{e}");
        assert_eq!(scene_error("name = \"paper-phantom\"", "name = \"\""), "name: the name is empty");
        let old = "description = \"0.1 m PVC-like phantom, 19 x 19 nodes, fixed at the bottom; vertical insertion and withdrawal\"";
        let e = scene_error(old, &format!("description = \"{}\"", "d".repeat(1025)));
        assert!(e.starts_with("description: 'ddd") && e.ends_with("has 1025 characters, at most 1024") && e.len() < 200, "{e}");
        // At the limits: accepted.
        let base = include_str!("../../scenes/paper-phantom.toml");
        let edge = base
            .replace("name = \"paper-phantom\"", &format!("name = \"{}\"", "é".repeat(MAX_SCENE_NAME_CHARS)))
            .replace(old, &format!("description = \"{}\"", "d".repeat(MAX_SCENE_DESCRIPTION_CHARS)));
        let scene = parse_scene(&edge, Path::new("."), &MeshLimits::default()).unwrap();
        assert_eq!(scene.name.chars().count(), MAX_SCENE_NAME_CHARS);
        // A TOML over the size limit is refused before it is parsed, as a size limit.
        let big = format!("{base}\n# {}\n", "x".repeat(MAX_SCENE_TOML_BYTES));
        let e = parse_scene(&big, Path::new("."), &MeshLimits::default()).err().expect("over the size limit");
        assert!(e.downcast_ref::<SizeLimit>().is_some(), "{e:#}");
        let e = format!("{e:#}");
        assert!(e.starts_with("the scene TOML is ") && e.contains("over the limit of 262144 bytes") && e.len() < 200, "{e}");
        assert_eq!(scene_dim(&big).unwrap(), 2, "the dimension probe does not parse it either");
    }

    /// The scene with `old` replaced by `new` (which must occur), parsed; the error's text.
    fn scene_error(old: &str, new: &str) -> String {
        let base = include_str!("../../scenes/paper-phantom.toml");
        assert!(base.contains(old), "{old}");
        let e = parse_scene(&base.replace(old, new), Path::new("."), &MeshLimits::default()).err().expect("the scene must be rejected");
        format!("{e:#}")
    }

    #[test]
    fn issue_13_bad_scene_values_name_the_field() {
        let base_line = "base = [0.05, 0.205, -1.5707963267948966]";
        let cases = [
            (base_line, "base = [nan, 0.205, -1.5707963267948966]", "needle.base = [NaN, 0.205, -1.5707963267948966]: must be finite"),
            (base_line, "base = [0.05, inf, 0.0]", "needle.base = [0.05, inf, 0]: must be finite"),
            ("[needle]", "[limits]\nmax_base_step_m = -1\n\n[needle]", "limits.max_base_step_m = -1: must be finite and > 0"),
            (
                "[needle]",
                "[limits]\nmax_active_set_iterations = 0\n\n[needle]",
                "limits.max_active_set_iterations = 0: must be in 1..=10000",
            ),
            ("[needle]", "[limits]\nlookahead_m = nan\n\n[needle]", "limits.lookahead_m = NaN: must be finite and ≥ 0"),
            (base_line, "max_nodes = 0\nbase = [0.05, 0.205, 0]", "needle.max_nodes = 0: must be in 1..=4096"),
            (base_line, "max_nodes = 1000000000\nbase = [0.05, 0.205, 0]", "needle.max_nodes = 1000000000: must be in 1..=4096"),
            (base_line, "capture_radius_m = -0.001\nbase = [0.05, 0.205, 0]", "needle.capture_radius_m = -0.001: must be finite and > 0"),
            ("contact = \"nodes\"", "contact_spacing_m = 0", "needle.contact_spacing_m = 0: must be between 0.00001 and 1 m"),
            ("contact = \"nodes\"", "contact = \"nodes\"\ncontact_spacing_m = 0.001", "the spacing applies to material points only"),
            ("contact = \"nodes\"", "contact = \"edges\"", "unknown variant `edges`, expected `points` or `nodes`"),
            ("length_m = 0.1", "length_m = inf", "needle.length_m = inf: must be finite and > 0"),
            ("radius_m = 0.002", "radius_m = nan", "targets[0] ('centre').radius_m = NaN: must be finite and ≥ 0"),
            ("tick_rate_hz = 1000", "tick_rate_hz = 1e9", "tick_rate_hz = 1000000000: must be between 100 and 10000"),
            ("puncture_force_n = 0.3", "puncture_force_n = -0.3", "regions[0] ('tissue').puncture_force_n = -0.3: must be finite and ≥ 0"),
        ];
        for (old, new, want) in cases {
            let e = scene_error(old, new);
            assert!(e.contains(want), "{new}: {e}");
        }
        // A flexible needle's working set is bounded tighter.
        let e = scene_error(base_line, "model = \"flexible\"\nmax_nodes = 2000\nbase = [0.05, 0.205, 0]");
        assert!(e.contains("needle.max_nodes = 2000: must be in 1..=1024"), "{e}");
        // Two regions or targets of one name.
        let e = scene_error(
            "[needle]",
            "[[regions]]\nname = \"tissue\"\nyoung_modulus_pa = 1e4\npoisson_ratio = 0.3\ndisc = { center_m = [0.05, 0.05], radius_m = 0.01 }\n\n[needle]",
        );
        assert!(e.contains("regions[1]: the name 'tissue' is already used by regions[0]"), "{e}");
        let e = scene_error("[[targets]]", "[[targets]]\nname = \"centre\"\ncenter_m = [0.05, 0.06]\n\n[[targets]]");
        assert!(e.contains("targets[1]: the name 'centre' is already used by targets[0]"), "{e}");
    }
}
