//! 3D scenes (`dim = 3`): scene TOML → [`Scene3d`], the tetrahedral mesh with its regions,
//! materials, fixed nodes, rigid needle, initial base pose, target spheres and base trajectory
//! that the 3D simulation consumes.
//!
//! The keys mirror the 2D scene's ([`crate::SceneFile`]) where they mean the same thing
//! (regions' elasticity and needle interaction, `fixed`, `targets`, `limits`, `tick_rate_hz`);
//! what differs:
//!
//! * `dim = 3` at the top level selects this parser (2D scenes have no `dim`, or `dim = 2`);
//! * `[mesh]`: `type = "box"` with `nx`, `ny`, `nz` nodes, `size_m = [x, y, z]` and an optional
//!   `origin_m` (boundary sets `left/right` x, `front/back` y, `bottom/top` z; regions after the
//!   first claim the tetrahedra whose centroid lies in their `sphere` or `cuboid`), or
//!   `type = "msh"` with `file` (Gmsh MSH 2.2/4.1 with tetrahedra, relative to the scene file:
//!   physical volumes are the regions, matched by name, physical surfaces the boundary sets);
//! * `[needle]`: `length_m`, `gauge` or `diameter_m`, `contact_spacing_m`, `max_points`,
//!   the base position `base_m = [x, y, z]` and its orientation, either `base_quat = [w, x, y, z]`
//!   (canonical; unit norm) or `base_axis = [x, y, z]` (unit shaft direction, base to tip) with
//!   `base_roll_rad` about it (conventions: [`needlesim_trajectory::pose3`]); rigid by default,
//!   `model = "flexible"` makes it an elastic rod ([`needlesim_core::rod3`]) with `gauge` (its
//!   stainless steel EI) or `flexural_rigidity_nm2`, `n_links` (default: 2 mm links, 16..=400),
//!   and a bevel tip with `bevel_force_ratio` (default 0: symmetric) and `bevel_side` (±1,
//!   default +1: towards the base frame's $n$); `spread_contact = true` spreads each contact over a
//!   disc of the needle's radius across the shaft instead of a material point (issue 37), and
//!   `near_field = true` adds the needle's near field at each contact point
//!   (`needlesim_core::sim3::NearField3`; default false);
//! * `[[targets]]` are spheres: `center_m = [x, y, z]`, `radius_m`;
//! * `trajectory = "file.csv"` (optional, relative to the scene file): a
//!   `t_s,x_m,y_m,z_m,qw,qx,qy,qz` base trajectory ([`Trajectory3`]).
//!
//! Every bad value is an error naming its key (`needle.base_quat = [...]: must have unit norm`).
//! Parsing builds and validates the mesh but does not factorise it: [`Scene3d::tissue_model`]
//! does, when a simulation needs it. The memory a session would hold is estimated first
//! ([`estimated_session_bytes_3d`]) and an oversized scene refused with a [`SizeLimit`].

use std::path::Path;

use anyhow::{Context, Result, bail};
use needlesim_core::d3::{BoxGridParams, TetLocator, TetMaterials, TetMesh, TetMeshLimits, TetTissueModel};
use needlesim_core::num::num;
use needlesim_core::{Material, RegionNeedleParams};
use needlesim_trajectory::pose3::{RotationError, quat_from_axis_roll, unit};
use needlesim_trajectory::{Pose3, Trajectory3};
use serde::Deserialize;

use crate::limit::{self, SizeLimit};
use crate::{
    GAUGES, LimitsSpec, MAX_LOCAL_FILE_BYTES, MAX_TOML_BRACKETS, SceneFiles, SceneLimits, check_length, check_limits, check_names,
    check_region_bounds, check_region_needle_values, check_scene_text, check_toml_size, default_rate, read_local_file,
};

/// The mesh files a shipped example names: (file, text).
pub type ExampleFiles = &'static [(&'static str, &'static str)];

/// The shipped 3D examples: (name, scene TOML, trajectory CSV, mesh files it names).
pub const EXAMPLES3D: &[(&str, &str, &str, ExampleFiles)] = &[
    ("cube-phantom-3d", include_str!("../../scenes/cube-phantom-3d.toml"), include_str!("../../scenes/cube-phantom-3d.csv"), &[]),
    (
        "brachy-3d",
        include_str!("../../scenes/brachy-3d.toml"),
        include_str!("../../scenes/brachy-3d.csv"),
        &[("brachy-3d.msh", include_str!("../../scenes/brachy-3d.msh"))],
    ),
    ("fig3-target-3d", include_str!("../../scenes/fig3-target-3d.toml"), include_str!("../../scenes/fig3-target-3d.csv"), &[]),
];

/// A 3D scene as written in TOML.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene3dFile {
    /// Must be 3.
    pub dim: i64,
    pub name: Option<String>,
    pub description: Option<String>,
    #[serde(default = "default_rate")]
    pub tick_rate_hz: f64,
    pub mesh: Mesh3dSpec,
    /// Boundary sets (box faces or Gmsh physical surfaces) whose nodes are fixed.
    #[serde(default)]
    pub fixed: Vec<String>,
    pub regions: Vec<Region3dSpec>,
    pub needle: Needle3dSpec,
    #[serde(default)]
    pub targets: Vec<Target3dSpec>,
    /// A `t_s,x_m,y_m,z_m,qw,qx,qy,qz` CSV, relative to the scene file.
    pub trajectory: Option<String>,
    #[serde(default)]
    pub limits: LimitsSpec,
    /// Viscoelastic tissue: the 2D scene's `[viscoelastic]` table (`long_term_ratio = E∞/E₀`,
    /// `relaxation_time_s = τ`; the regions' `E` are the instantaneous moduli E₀). Absent: elastic.
    pub viscoelastic: Option<crate::ViscoelasticSpec>,
}

/// The mesh: a structured box or a Gmsh file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, tag = "type", rename_all = "lowercase")]
pub enum Mesh3dSpec {
    /// `nx × ny × nz` nodes over a box of `size_m`, 6 tetrahedra per cell.
    Box {
        nx: usize,
        ny: usize,
        nz: usize,
        size_m: [f64; 3],
        #[serde(default)]
        origin_m: [f64; 3],
    },
    /// A Gmsh ASCII file (2.2 or 4.1) with tetrahedra, relative to the scene file.
    Msh { file: String },
    /// A VTK unstructured grid of tetrahedra (`.vtu`, or legacy `.vtk` as ASCII), relative to
    /// the scene file: regions and boundary sets (labelled triangles) from an integer cell-data
    /// array, named by `labels` ([`crate::vtk`]).
    #[serde(alias = "vtk")]
    Vtu {
        file: String,
        /// `{ 1 = "tissue", 2 = "lesion", 11 = "back" }`: every label of the file, named.
        #[serde(default)]
        labels: std::collections::BTreeMap<String, String>,
        /// The cell-data array of the labels (default: the first of
        /// [`crate::vtk::DEFAULT_LABEL_ARRAYS`]).
        label_array: Option<String>,
    },
}

/// A tissue region: elasticity and needle interaction (the 2D region's keys, with `material`
/// from the tissue library). Written as [`Region3dToml`].
#[derive(Debug, Clone, Deserialize)]
#[serde(try_from = "Region3dToml")]
pub struct Region3dSpec {
    pub name: String,
    /// The tissue library's material the region names, if any.
    pub material: Option<String>,
    pub young_modulus_pa: f64,
    pub poisson_ratio: f64,
    /// Box meshes: the tetrahedra whose centroid lies in this sphere (later regions win).
    pub sphere: Option<SphereSpec>,
    /// Box meshes: the tetrahedra whose centroid lies in this axis-aligned box.
    pub cuboid: Option<CuboidSpec>,
    pub friction_n_per_m: f64,
    pub static_friction_ratio: f64,
    pub tip_peak_ratio: f64,
    pub tip_peak_width_m: f64,
    pub puncture_force_n: f64,
    pub cutting_force_n: f64,
    /// Viscous friction per unit length and unit slip speed, N·s/m² (rate-dependent friction,
    /// `q₀ + b·|v|`, as in 2D; 0: rate-independent).
    pub friction_damping_n_s_per_m2: f64,
}

/// A 3D region as written in TOML: every value key optional when a `material` gives it.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Region3dToml {
    pub name: String,
    pub material: Option<String>,
    pub young_modulus_pa: Option<f64>,
    pub poisson_ratio: Option<f64>,
    pub sphere: Option<SphereSpec>,
    pub cuboid: Option<CuboidSpec>,
    pub friction_n_per_m: Option<f64>,
    pub static_friction_ratio: Option<f64>,
    pub tip_peak_ratio: Option<f64>,
    pub tip_peak_width_m: Option<f64>,
    pub puncture_force_n: Option<f64>,
    pub cutting_force_n: Option<f64>,
    pub friction_damping_n_s_per_m2: Option<f64>,
}

impl TryFrom<Region3dToml> for Region3dSpec {
    type Error = String;
    fn try_from(t: Region3dToml) -> Result<Self, String> {
        let r = crate::tissues::MaterialKeys {
            material: t.material.clone(),
            young_modulus_pa: t.young_modulus_pa,
            poisson_ratio: t.poisson_ratio,
            friction_n_per_m: t.friction_n_per_m,
            static_friction_ratio: t.static_friction_ratio,
            tip_peak_ratio: t.tip_peak_ratio,
            tip_peak_width_m: t.tip_peak_width_m,
            puncture_force_n: t.puncture_force_n,
            cutting_force_n: t.cutting_force_n,
            friction_damping_n_s_per_m2: t.friction_damping_n_s_per_m2,
        }
        .resolve(&t.name)?;
        Ok(Self {
            name: t.name,
            material: t.material,
            young_modulus_pa: r.young_modulus_pa,
            poisson_ratio: r.poisson_ratio,
            sphere: t.sphere,
            cuboid: t.cuboid,
            friction_n_per_m: r.friction_n_per_m,
            static_friction_ratio: r.static_friction_ratio,
            tip_peak_ratio: r.tip_peak_ratio,
            tip_peak_width_m: r.tip_peak_width_m,
            puncture_force_n: r.puncture_force_n,
            cutting_force_n: r.cutting_force_n,
            friction_damping_n_s_per_m2: r.friction_damping_n_s_per_m2,
        })
    }
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    pub center_m: [f64; 3],
    pub radius_m: f64,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CuboidSpec {
    pub min_m: [f64; 3],
    pub max_m: [f64; 3],
}

/// The rigid needle and its initial base pose.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Needle3dSpec {
    pub length_m: f64,
    /// A stainless steel gauge of the 2D table (16, 17, 18, 20, 21, 22, 25): its outer diameter.
    pub gauge: Option<u32>,
    /// The outer diameter (instead of a gauge); default: 18 G, 1.27 mm.
    pub diameter_m: Option<f64>,
    /// Arc length between material contact points (default 2 mm).
    pub contact_spacing_m: Option<f64>,
    /// Most material points the needle holds at once.
    #[serde(default = "d_max_points")]
    pub max_points: usize,
    /// Base position `[x, y, z]`, m.
    pub base_m: [f64; 3],
    /// Base orientation, a unit quaternion `[w, x, y, z]` (canonical).
    pub base_quat: Option<[f64; 4]>,
    /// Or: the shaft direction (base to tip), a unit vector …
    pub base_axis: Option<[f64; 3]>,
    /// … and the roll about it, rad (default 0).
    pub base_roll_rad: Option<f64>,
    /// `"rigid"` (default) or `"flexible"`.
    #[serde(default)]
    pub model: Needle3dModel,
    /// Flexible: the flexural rigidity EI, N·m² (instead of the gauge's).
    pub flexural_rigidity_nm2: Option<f64>,
    /// Flexible: links of the discrete rod (default: 2 mm long, 16..=400).
    pub n_links: Option<usize>,
    /// Flexible: the bevel's lateral over axial tip force (default 0: a symmetric tip).
    pub bevel_force_ratio: Option<f64>,
    /// Flexible: the bevel's side, +1 towards the base frame's n, −1 away (default +1).
    pub bevel_side: Option<f64>,
    /// Spread each contact over the needle's cross-section (a disc of the needle's radius across
    /// the shaft) instead of a material point (default false; issue 37).
    #[serde(default)]
    pub spread_contact: bool,
    /// The needle's near field (a sub-grid compliance between its radius and the element's
    /// equivalent radius at each contact point, `needlesim_core::sim3::NearField3`; default
    /// false).
    #[serde(default)]
    pub near_field: bool,
}

/// The needle model of a 3D scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Needle3dModel {
    #[default]
    Rigid,
    Flexible,
}

/// Default [`Needle3dSpec::max_points`]: a 0.128 m inserted length at 2 mm.
pub const DEFAULT_MAX_POINTS: usize = 64;

fn d_max_points() -> usize {
    DEFAULT_MAX_POINTS
}

/// The outer diameter of 18 G, the default needle (brachytherapy and biopsy needles).
pub const DEFAULT_DIAMETER_M: f64 = 1.270e-3;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target3dSpec {
    pub name: String,
    pub center_m: [f64; 3],
    #[serde(default)]
    pub radius_m: f64,
}

/// Where a scene's mesh came from.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshSource3d {
    Box {
        n: [usize; 3],
        size_m: [f64; 3],
        origin_m: [f64; 3],
    },
    /// A Gmsh file as named in the scene, and the MSH version read.
    Msh {
        file: String,
        version: String,
    },
    /// A VTK file as named in the scene, and the label array read.
    Vtu {
        file: String,
        label_array: String,
    },
}

/// A region of a loaded scene, in the mesh's region order.
#[derive(Debug, Clone, PartialEq)]
pub struct Region3d {
    pub name: String,
    pub material: Material,
    pub needle: RegionNeedleParams,
    /// Box meshes: the sphere the region was given by, `(centre, radius)` in m (the 3D
    /// planner's structures to spare are such regions).
    pub sphere_m: Option<([f64; 3], f64)>,
}

/// The needle of a loaded scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Needle3d {
    pub length_m: f64,
    pub diameter_m: f64,
    pub contact_spacing_m: f64,
    pub max_points: usize,
    /// A flexible (and bevel-tip) needle's rod; `None` for a rigid needle.
    pub flexible: Option<needlesim_core::needle::FlexibleNeedle>,
    /// Contacts spread over discs of radius `diameter_m / 2` across the shaft
    /// (`spread_contact`; `needlesim_core::sim3::Sim3Params::disc_radius_m`).
    pub spread_contact: bool,
    /// `near_field`: the needle's near field at each contact point.
    pub near_field: bool,
}

/// A target sphere (it moves with the tissue in the simulation).
#[derive(Debug, Clone, PartialEq)]
pub struct Target3d {
    pub name: String,
    pub center_m: [f64; 3],
    pub radius_m: f64,
}

/// A loaded, validated 3D scene: what the 3D simulation consumes.
#[derive(Debug, Clone)]
pub struct Scene3d {
    pub name: String,
    pub description: Option<String>,
    pub tick_rate_hz: f64,
    /// The mesh, with its regions and boundary sets (and `fixed`, the union of the fixed sets).
    pub mesh: TetMesh,
    pub mesh_source: MeshSource3d,
    /// One per mesh region, in the mesh's order.
    pub regions: Vec<Region3d>,
    /// The fixed boundary sets, as named in the scene.
    pub fixed_sets: Vec<String>,
    /// Their nodes, sorted, without repeats.
    pub fixed_nodes: Vec<usize>,
    pub needle: Needle3d,
    /// The initial base pose.
    pub initial_pose: Pose3,
    pub targets: Vec<Target3d>,
    /// The scene's base trajectory (its `trajectory` file, or a shipped example's).
    pub trajectory: Option<Trajectory3>,
    pub limits: LimitsSpec,
    /// Viscoelastic tissue (`[viscoelastic]`); `None`: elastic.
    pub viscoelastic: Option<needlesim_core::sim::Viscoelastic>,
}

impl Scene3d {
    /// The materials per region, validated for 3D (ν < 0.5).
    pub fn materials(&self) -> Result<TetMaterials> {
        let m: Vec<Material> = self.regions.iter().map(|r| r.material).collect();
        TetMaterials::per_region(&self.mesh, &m).context("regions")
    }

    /// Assembles `K` and factorises its free block: the slow part (seconds for 10⁴ nodes).
    pub fn tissue_model(&self) -> Result<TetTissueModel> {
        TetTissueModel::new(self.mesh.clone(), self.materials()?, &self.fixed_nodes)
            .with_context(|| format!("tissue ({} fixed nodes)", self.fixed_nodes.len()))
    }
}

/// Bytes per mesh node of the 3D model before the factor: coordinates, about 6 tetrahedra per
/// node, the assembled stiffness (15 nodes per row on a box grid: 45 non-zeros per row, 3 rows
/// per node), the point locator and the per-node vectors of the model and the simulation.
pub const MODEL_BYTES_PER_NODE_3D: u64 = 4096;
/// Bytes of the Cholesky factor per `n^{5/3}` (n nodes). The fill of a 3D mesh's factor grows far
/// faster than 2D's O(n log n): nested dissection would give O(n^{4/3}) non-zeros, but the
/// factor measured here (faer's ordering, `factor_nnz` × 12 bytes: the value and its share of the
/// row indices) grows as about n^{1.6} on box grids: 6³ nodes 0.59 MB, 11³ 11.6 MB, 16³ 71 MB,
/// 21³ 265 MB, i.e. 76, 72, 67, 65 bytes per n^{5/3} (test `factor_fill_is_bounded_by_the_estimate`).
/// Bounded with a margin at 80, falling with n, so an upper bound for larger meshes too.
pub const FACTOR_BYTES_PER_NODE_5_3: u64 = 80;
/// Bytes per mesh node of the compliance columns cached for one tissue node in 3D: three
/// columns of 3 doubles per mesh node (2D: 2 × 2).
pub const COLUMN_BYTES_PER_NODE_3D: u64 = 3 * 3 * 8;

/// The memory a session of a 3D scene with `n_nodes` mesh nodes and a needle of up to
/// `max_points` material points is estimated to hold, in bytes:
/// `n × MODEL_BYTES_PER_NODE_3D + FACTOR_BYTES_PER_NODE_5_3 × n^{5/3} + n × COLUMN_BYTES_PER_NODE_3D
/// × (8 × max_points + CACHE_LOOKAHEAD_NODES)`: the model; its factor; the column cache of the
/// points' nodes (4 per point in 3D) and the lookahead, plus the renderer's copies of the
/// points' nodes (4 more per point). The 2D estimate ([`crate::estimated_session_bytes`])
/// scaled honestly: 3 DOFs per node make each cached node's columns 2.25× larger, a point has 4
/// nodes instead of 3, and the factor fills as n^{5/3} (about 1 GB at 35k nodes, 4 GB at 42k
/// nodes ≈ 250k tetrahedra: a better fill-reducing ordering would pay off first here). Until the 3D simulation exists to be
/// measured, the column terms are the design's upper bound (full columns).
pub fn estimated_session_bytes_3d(n_nodes: usize, max_points: usize) -> u64 {
    let n = n_nodes as u64;
    let model = n.saturating_mul(MODEL_BYTES_PER_NODE_3D);
    let factor = (FACTOR_BYTES_PER_NODE_5_3 as f64 * (n as f64).powf(5.0 / 3.0)).min(u64::MAX as f64) as u64;
    let cached_nodes =
        (max_points as u64).saturating_mul(8).saturating_add(needlesim_core::sim::param_limits::CACHE_LOOKAHEAD_NODES as u64);
    let columns = n.saturating_mul(COLUMN_BYTES_PER_NODE_3D).saturating_mul(cached_nodes);
    model.saturating_add(factor).saturating_add(columns)
}

/// Refuses a 3D scene whose [`estimated_session_bytes_3d`] is over `limits.max_session_bytes`.
pub fn check_session_memory_3d(n_nodes: usize, max_points: usize, limits: &SceneLimits) -> Result<(), SizeLimit> {
    let estimate = estimated_session_bytes_3d(n_nodes, max_points);
    if estimate <= limits.max_session_bytes {
        return Ok(());
    }
    const MIB: u64 = 1 << 20;
    Err(SizeLimit {
        what: format!("the estimated memory of a session of this 3D scene ({n_nodes} mesh nodes, up to {max_points} needle points)"),
        amount: estimate.div_ceil(MIB) as f64,
        limit: limits.max_session_bytes / MIB,
        unit: "MiB",
        hint: " (server flag --max-session-memory-mb)".to_owned(),
    })
}

/// The `dim` of a scene's TOML: 2 when absent. Errors only on a `dim` that is not 2 or 3 (a text
/// that is not TOML is left to the scene parsers, which report it).
pub fn scene_dim(text: &str) -> Result<u8> {
    #[derive(Deserialize)]
    struct Probe {
        dim: Option<toml::Value>,
    }
    // Left to the scene parsers, which refuse such a text naming the limit.
    if text.len() > crate::MAX_SCENE_TOML_BYTES || text.bytes().filter(|b| matches!(b, b'[' | b'{')).count() > MAX_TOML_BRACKETS {
        return Ok(2);
    }
    match toml::from_str::<Probe>(text) {
        Ok(Probe { dim: None }) | Err(_) => Ok(2),
        Ok(Probe { dim: Some(toml::Value::Integer(2)) }) => Ok(2),
        Ok(Probe { dim: Some(toml::Value::Integer(3)) }) => Ok(3),
        Ok(Probe { dim: Some(v) }) => bail!("dim = {}: must be 2 or 3", limit::quote(&limit::compact_numbers(&v.to_string()))),
    }
}

/// A shipped 3D example by name ([`EXAMPLES3D`], its files embedded), never a path: `None` for
/// any other name. What a name from a client resolves to.
pub fn example_scene3d(name: &str, limits: impl Into<SceneLimits>) -> Option<Result<Scene3d>> {
    let (name, toml_text, csv, files) = EXAMPLES3D.iter().find(|e| e.0 == name)?;
    let read = |f: &str| -> Result<String> {
        if f.ends_with(".csv") {
            return Ok((*csv).to_owned());
        }
        files.iter().find(|(n, _)| *n == f).map(|(_, t)| (*t).to_owned()).with_context(|| format!("{f} is not shipped"))
    };
    let scene = parse_with(toml_text, &read, &limits.into()).with_context(|| format!("example scene {name}"));
    Some(scene.and_then(|mut scene| {
        if scene.trajectory.is_none() {
            scene.trajectory = Some(Trajectory3::parse_csv(csv).with_context(|| format!("example scene {name}: trajectory"))?);
        }
        Ok(scene)
    }))
}

/// Reads a local 3D scene: the name of a shipped example, else a path to a TOML file (read by
/// [`read_local_file`], as are the files it names).
pub fn load_scene3d(spec: &str, limits: impl Into<SceneLimits>) -> Result<Scene3d> {
    let limits = &limits.into();
    if let Some(scene) = example_scene3d(spec, limits) {
        return scene;
    }
    let path = Path::new(spec);
    if std::fs::symlink_metadata(path).is_err() {
        let names: Vec<&str> = EXAMPLES3D.iter().map(|e| e.0).collect();
        bail!("3D scene '{spec}' is neither a file nor a shipped example (examples: {})", names.join(", "));
    }
    let text = read_local_file(path, MAX_LOCAL_FILE_BYTES)?;
    parse_scene3d(&text, path.parent().unwrap_or(Path::new(".")), limits).with_context(|| format!("scene {}", path.display()))
}

/// Parses a local 3D scene's TOML; `base_dir` resolves the mesh and trajectory files it names
/// ([`SceneFiles::Local`]).
pub fn parse_scene3d(text: &str, base_dir: &Path, limits: impl Into<SceneLimits>) -> Result<Scene3d> {
    parse_scene3d_with(text, SceneFiles::Local(base_dir), limits)
}

/// Parses 3D scene TOML, the mesh and trajectory files it names coming from `files`:
/// [`SceneFiles::None`] for a scene from a client, [`SceneFiles::Given`] for an upload.
pub fn parse_scene3d_with(text: &str, files: SceneFiles, limits: impl Into<SceneLimits>) -> Result<Scene3d> {
    parse_with(text, &|f: &str| files.read(f), &limits.into())
}

fn parse_with(text: &str, read: &dyn Fn(&str) -> Result<String>, limits: &SceneLimits) -> Result<Scene3d> {
    check_toml_size(text)?;
    let brackets = text.bytes().filter(|b| matches!(b, b'[' | b'{')).count();
    if brackets > MAX_TOML_BRACKETS {
        bail!("the scene TOML holds {brackets} '[' and '{{', over the limit of {MAX_TOML_BRACKETS}");
    }
    let file: Scene3dFile = toml::from_str(text).map_err(|e| anyhow::anyhow!("{}", limit::toml_message(&e, text)))?;
    build(&file, read, limits)
}

fn finite<const N: usize>(v: &[f64; N]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The initial base orientation from `base_quat`, or `base_axis` and `base_roll_rad`.
fn base_orientation(n: &Needle3dSpec) -> Result<[f64; 4]> {
    let why = |e: RotationError| e.to_string();
    match (n.base_quat, n.base_axis) {
        (Some(_), Some(_)) => bail!("needle: give either base_quat or base_axis (with base_roll_rad), not both"),
        (None, None) => bail!("needle: the base orientation is missing: give base_quat = [w, x, y, z] or base_axis = [x, y, z]"),
        (Some(q), None) => {
            if n.base_roll_rad.is_some() {
                bail!("needle.base_roll_rad goes with base_axis; with base_quat the roll is in the quaternion");
            }
            unit(q).map_err(|e| anyhow::anyhow!("needle.base_quat = {q:?}: {}", why(e)))
        }
        (None, Some(a)) => {
            let a = unit(a).map_err(|e| anyhow::anyhow!("needle.base_axis = {a:?}: {}", why(e)))?;
            let roll = n.base_roll_rad.unwrap_or(0.0);
            if !(roll.is_finite() && roll.abs() <= 100.0) {
                bail!("needle.base_roll_rad = {}: must be finite and within ±100 rad", num(roll));
            }
            Ok(quat_from_axis_roll(a, roll))
        }
    }
}

fn needle(n: &Needle3dSpec) -> Result<Needle3d> {
    use needlesim_core::sim::param_limits::{MAX_CONTACT_SPACING_M, MAX_NEEDLE_NODES, MIN_CONTACT_SPACING_M};
    if !(n.length_m.is_finite() && n.length_m > 0.0) {
        bail!("needle.length_m = {}: must be finite and > 0", num(n.length_m));
    }
    check_length("needle.length_m", n.length_m)?;
    let diameter_m = match (n.gauge, n.diameter_m) {
        (Some(_), Some(_)) => bail!("needle: give either gauge or diameter_m, not both"),
        (Some(g), None) => match GAUGES.iter().find(|(gg, _, _)| *gg == g) {
            Some(&(_, od, _)) => od,
            None => bail!("needle.gauge = {g} is not in the table (16, 17, 18, 20, 21, 22, 25); give diameter_m instead"),
        },
        (None, Some(d)) => {
            if !(d.is_finite() && d > 0.0 && d <= 0.01) {
                bail!("needle.diameter_m = {}: must be finite, > 0 and at most 0.01 m", num(d));
            }
            d
        }
        (None, None) => DEFAULT_DIAMETER_M,
    };
    let spacing = n.contact_spacing_m.unwrap_or(needlesim_core::sim::ContactModel::DEFAULT_SPACING_M);
    if !(spacing.is_finite() && (MIN_CONTACT_SPACING_M..=MAX_CONTACT_SPACING_M).contains(&spacing)) {
        bail!("needle.contact_spacing_m = {}: must be between {MIN_CONTACT_SPACING_M} and {MAX_CONTACT_SPACING_M} m", num(spacing));
    }
    if !(1..=MAX_NEEDLE_NODES).contains(&n.max_points) {
        bail!("needle.max_points = {}: must be in 1..={MAX_NEEDLE_NODES}", n.max_points);
    }
    if !finite(&n.base_m) {
        bail!("needle.base_m = {:?}: must be finite", n.base_m);
    }
    Ok(Needle3d {
        length_m: n.length_m,
        diameter_m,
        contact_spacing_m: spacing,
        max_points: n.max_points,
        flexible: flexible(n)?,
        spread_contact: n.spread_contact,
        near_field: n.near_field,
    })
}

/// The flexible needle's rod from `model = "flexible"` and its keys; those keys with a rigid
/// needle are an error naming them.
fn flexible(n: &Needle3dSpec) -> Result<Option<needlesim_core::needle::FlexibleNeedle>> {
    use needlesim_core::needle::FlexibleNeedle;
    if n.model == Needle3dModel::Rigid {
        for (key, given) in [
            ("flexural_rigidity_nm2", n.flexural_rigidity_nm2.is_some()),
            ("n_links", n.n_links.is_some()),
            ("bevel_force_ratio", n.bevel_force_ratio.is_some()),
            ("bevel_side", n.bevel_side.is_some()),
        ] {
            if given {
                bail!("needle.{key} is for a flexible needle: add model = \"flexible\"");
            }
        }
        return Ok(None);
    }
    let mut f = FlexibleNeedle::gauge17_steel(n.length_m);
    match (n.gauge, n.flexural_rigidity_nm2) {
        (Some(_), Some(_)) => bail!("needle: give either gauge or flexural_rigidity_nm2, not both"),
        (Some(g), None) => {
            let Some(&(_, od, id)) = GAUGES.iter().find(|(gg, _, _)| *gg == g) else {
                bail!("needle.gauge = {g} is not in the table (16, 17, 18, 20, 21, 22, 25); give flexural_rigidity_nm2 instead");
            };
            f.flexural_rigidity_nm2 = crate::STEEL_E_PA * FlexibleNeedle::tube_second_moment_m4(od, id);
        }
        (None, Some(ei)) => {
            if !(ei.is_finite() && ei > 0.0) {
                bail!("needle.flexural_rigidity_nm2 = {}: must be finite and > 0", num(ei));
            }
            f.flexural_rigidity_nm2 = ei;
        }
        (None, None) => {
            let (_, od, id) = GAUGES.iter().find(|(g, _, _)| *g == 18).copied().expect("18 G is in the table");
            f.flexural_rigidity_nm2 = crate::STEEL_E_PA * FlexibleNeedle::tube_second_moment_m4(od, id);
        }
    }
    if let Some(k) = n.n_links {
        if !(1..=400).contains(&k) {
            bail!("needle.n_links = {k}: must be in 1..=400");
        }
        f.n_links = k;
    }
    if let Some(b) = n.bevel_force_ratio {
        if !(b.is_finite() && (0.0..=10.0).contains(&b)) {
            bail!("needle.bevel_force_ratio = {}: must be finite, ≥ 0 and at most 10", num(b));
        }
        f.bevel_force_ratio = b;
    }
    if let Some(side) = n.bevel_side {
        if side != 1.0 && side != -1.0 {
            bail!("needle.bevel_side = {}: must be +1 or -1", num(side));
        }
        f.bevel_side = side;
    }
    Ok(Some(f))
}

fn build(f: &Scene3dFile, read: &dyn Fn(&str) -> Result<String>, scene_limits: &SceneLimits) -> Result<Scene3d> {
    if f.dim != 3 {
        bail!("dim = {}: a 3D scene has dim = 3 (2D scenes load with the 2D loader)", f.dim);
    }
    if !(f.tick_rate_hz.is_finite() && (100.0..=10_000.0).contains(&f.tick_rate_hz)) {
        bail!("tick_rate_hz = {}: must be between 100 and 10000", num(f.tick_rate_hz));
    }
    if f.regions.is_empty() {
        bail!("regions: at least one region is needed");
    }
    check_scene_text(f.name.as_deref(), f.description.as_deref())?;
    if let Some(v) = &f.viscoelastic {
        v.check()?;
    }
    check_names(f.regions.iter().map(|r| r.name.as_str()), f.targets.iter().map(|t| t.name.as_str()))?;
    let needle = needle(&f.needle)?;
    let quat = base_orientation(&f.needle)?;
    for (k, r) in f.regions.iter().enumerate() {
        if let Some(first) = f.regions[..k].iter().position(|o| o.name == r.name) {
            bail!("regions[{k}]: the name '{}' is already used by regions[{first}]; region names must be unique", r.name);
        }
        check_region_needle_values(
            k,
            &r.name,
            [r.friction_n_per_m, r.static_friction_ratio, r.tip_peak_ratio, r.tip_peak_width_m, r.puncture_force_n, r.cutting_force_n],
        )?;
        let b = r.friction_damping_n_s_per_m2;
        if !(b.is_finite() && b >= 0.0) {
            bail!("regions[{k}] ('{}').friction_damping_n_s_per_m2 = {}: must be finite and ≥ 0", r.name, num(b));
        }
        check_region_bounds(k, &r.name, r.young_modulus_pa, &[("friction_damping_n_s_per_m2", b)])?;
    }
    for (k, t) in f.targets.iter().enumerate() {
        if !finite(&t.center_m) {
            bail!("targets[{k}] ('{}').center_m = {:?}: must be finite", t.name, t.center_m);
        }
        if !(t.radius_m.is_finite() && t.radius_m >= 0.0) {
            bail!("targets[{k}] ('{}').radius_m = {}: must be finite and ≥ 0", t.name, num(t.radius_m));
        }
        check_length(&format!("targets[{k}] ('{}').radius_m", t.name), t.radius_m)?;
    }
    check_limits(&f.limits)?;
    let tet_limits = TetMeshLimits::from_2d(&scene_limits.mesh);

    let (mut mesh, mesh_source) = match &f.mesh {
        Mesh3dSpec::Box { nx, ny, nz, size_m, origin_m } => {
            if !finite(origin_m) {
                bail!("mesh.origin_m = {origin_m:?}: must be finite");
            }
            if !(finite(size_m) && size_m.iter().all(|&l| l > 0.0)) {
                bail!("mesh.size_m = {size_m:?}: must be finite and > 0");
            }
            for (key, v) in [("nx", nx), ("ny", ny), ("nz", nz)] {
                if *v < 2 {
                    bail!("mesh.{key} = {v}: must be at least 2");
                }
            }
            let n_nodes = nx.saturating_mul(*ny).saturating_mul(*nz);
            // Refused before the mesh is built when the node count alone is over the budget.
            if n_nodes <= tet_limits.max_nodes {
                check_session_memory_3d(n_nodes, needle.max_points, scene_limits).context("mesh")?;
            }
            let grid = BoxGridParams::new([*nx, *ny, *nz], *size_m).build(&tet_limits).context("mesh")?;
            let mesh = box_regions(grid, *origin_m, &f.regions, &tet_limits)?;
            (mesh, MeshSource3d::Box { n: [*nx, *ny, *nz], size_m: *size_m, origin_m: *origin_m })
        }
        Mesh3dSpec::Msh { file } => {
            if let Some((k, r)) = f.regions.iter().enumerate().find(|(_, r)| r.sphere.is_some() || r.cuboid.is_some()) {
                bail!("regions[{k}] ('{}'): sphere and cuboid apply to box meshes; a Gmsh mesh's regions are its physical volumes", r.name);
            }
            let key = || format!("mesh.file = \"{}\"", limit::quote(file));
            let text = read(file).with_context(key)?;
            let m = needlesim_core::msh::parse_msh3d(&text, &tet_limits).with_context(key)?;
            (m.mesh, MeshSource3d::Msh { file: file.clone(), version: m.version })
        }
        Mesh3dSpec::Vtu { file, labels, label_array } => {
            if let Some((k, r)) = f.regions.iter().enumerate().find(|(_, r)| r.sphere.is_some() || r.cuboid.is_some()) {
                bail!("regions[{k}] ('{}'): sphere and cuboid apply to box meshes; a VTK mesh's regions are its labels", r.name);
            }
            let key = || format!("mesh.file = \"{}\"", limit::quote(file));
            let opts = crate::vtk::VtkOptions {
                labels: crate::vtk::LabelMap::from_table(labels).context("mesh")?,
                label_array: label_array.clone(),
            };
            let text = read(file).with_context(key)?;
            let m = crate::vtk::read_vtk(&text, 3, &opts).with_context(key)?;
            let mesh = m.to_tet_mesh(&tet_limits).with_context(key)?;
            (mesh, MeshSource3d::Vtu { file: file.clone(), label_array: m.label_array })
        }
    };
    check_session_memory_3d(mesh.n_nodes(), needle.max_points, scene_limits).context("mesh")?;

    // Regions in the mesh's order, matched by name; every TOML region must be a mesh region.
    for (k, r) in f.regions.iter().enumerate() {
        if !mesh.region_names().contains(&r.name) {
            bail!("regions[{k}]: '{}' is not a region of the mesh (mesh regions: {})", r.name, mesh.region_names().join(", "));
        }
    }
    let mut regions = Vec::new();
    for rname in mesh.region_names() {
        let r = f
            .regions
            .iter()
            .find(|r| &r.name == rname)
            .with_context(|| format!("regions: the mesh has a region '{rname}' but no [[regions]] entry is named so"))?;
        regions.push(Region3d {
            name: r.name.clone(),
            material: Material { young_modulus_pa: r.young_modulus_pa, poisson_ratio: r.poisson_ratio },
            needle: RegionNeedleParams {
                friction_n_per_m: r.friction_n_per_m,
                static_friction_ratio: r.static_friction_ratio,
                tip_peak_ratio: r.tip_peak_ratio,
                tip_peak_width_m: r.tip_peak_width_m,
                puncture_force_n: r.puncture_force_n,
                cutting_force_n: r.cutting_force_n,
                friction_damping_n_s_per_m2: r.friction_damping_n_s_per_m2,
                ..Default::default()
            },
            sphere_m: r.sphere.map(|sp| (sp.center_m, sp.radius_m)),
        });
    }
    let materials: Vec<Material> = regions.iter().map(|r| r.material).collect();
    TetMaterials::per_region(&mesh, &materials).context("regions")?;

    if f.fixed.is_empty() {
        bail!("fixed: name at least one boundary set to fix (the tissue would float)");
    }
    let mut fixed = Vec::new();
    for (k, set) in f.fixed.iter().enumerate() {
        let nodes = mesh.boundary_set(set).with_context(|| {
            let names: Vec<&String> = mesh.boundary_sets().keys().collect();
            format!("fixed[{k}]: the mesh has no boundary set '{}' (it has: {})", limit::quote(set), limit::quote(&format!("{names:?}")))
        })?;
        fixed.extend_from_slice(nodes);
    }
    fixed.sort_unstable();
    fixed.dedup();
    if !mesh.boundary_sets().contains_key("fixed") {
        mesh = with_set(mesh, "fixed", fixed.clone(), &tet_limits)?;
    }

    let locator = TetLocator::new(&mesh);
    for (k, t) in f.targets.iter().enumerate() {
        if locator.locate(&mesh, t.center_m).is_err() {
            bail!("targets[{k}] ('{}').center_m = {:?}: not inside the mesh", t.name, t.center_m);
        }
    }
    let trajectory = match &f.trajectory {
        None => None,
        Some(file) => {
            let key = || format!("trajectory = \"{}\"", limit::quote(file));
            let text = read(file).with_context(key)?;
            Some(Trajectory3::parse_csv(&text).with_context(key)?)
        }
    };
    Ok(Scene3d {
        name: f.name.clone().unwrap_or_else(|| "scene".to_owned()),
        description: f.description.clone(),
        tick_rate_hz: f.tick_rate_hz,
        mesh,
        mesh_source,
        regions,
        fixed_sets: f.fixed.clone(),
        fixed_nodes: fixed,
        needle,
        initial_pose: Pose3::new(f.needle.base_m, quat),
        targets: f.targets.iter().map(|t| Target3d { name: t.name.clone(), center_m: t.center_m, radius_m: t.radius_m }).collect(),
        trajectory,
        limits: f.limits.clone(),
        viscoelastic: f.viscoelastic.map(|v| v.model()),
    })
}

/// `mesh` with the node set `name` added.
fn with_set(mesh: TetMesh, name: &str, nodes: Vec<usize>, limits: &TetMeshLimits) -> Result<TetMesh> {
    let mut sets = mesh.boundary_sets().clone();
    sets.insert(name.to_owned(), nodes);
    Ok(TetMesh::with_regions(
        mesh.nodes_m().to_vec(),
        mesh.tets().to_vec(),
        mesh.region_of_tet().to_vec(),
        mesh.region_names().to_vec(),
        sets,
        limits,
    )?)
}

/// Whether a point (a centroid) lies in a region's shape.
type Inside = Box<dyn Fn(&[f64; 3]) -> bool>;

/// A box grid moved to `origin_m`, its regions from the scene: the first region is the
/// background, each later one claims the tetrahedra whose centroid lies in its sphere or cuboid.
fn box_regions(grid: TetMesh, origin_m: [f64; 3], regions: &[Region3dSpec], limits: &TetMeshLimits) -> Result<TetMesh> {
    let r0 = &regions[0];
    if r0.sphere.is_some() || r0.cuboid.is_some() {
        bail!("regions[0] ('{}') is the background of a box mesh and takes no sphere or cuboid", r0.name);
    }
    let nodes: Vec<[f64; 3]> = grid.nodes_m().iter().map(|p| [p[0] + origin_m[0], p[1] + origin_m[1], p[2] + origin_m[2]]).collect();
    let centroids: Vec<[f64; 3]> = grid
        .tets()
        .iter()
        .map(|t| t.iter().fold([0.0; 3], |c, &n| [c[0] + nodes[n][0] / 4.0, c[1] + nodes[n][1] / 4.0, c[2] + nodes[n][2] / 4.0]))
        .collect();
    let mut region_of_tet = vec![0usize; grid.n_tets()];
    for (ri, r) in regions.iter().enumerate().skip(1) {
        let inside: Inside = match (r.sphere, r.cuboid) {
            (Some(s), None) => {
                if !(finite(&s.center_m) && s.radius_m.is_finite() && s.radius_m > 0.0) {
                    bail!("regions[{ri}] ('{}').sphere: must have a finite center_m and a radius_m > 0", r.name);
                }
                Box::new(move |c| (0..3).map(|i| (c[i] - s.center_m[i]).powi(2)).sum::<f64>() <= s.radius_m * s.radius_m)
            }
            (None, Some(b)) => {
                if !(finite(&b.min_m) && finite(&b.max_m) && (0..3).all(|i| b.min_m[i] < b.max_m[i])) {
                    bail!("regions[{ri}] ('{}').cuboid: min_m must be finite and below max_m on every axis", r.name);
                }
                Box::new(move |c| (0..3).all(|i| b.min_m[i] <= c[i] && c[i] <= b.max_m[i]))
            }
            (Some(_), Some(_)) => bail!("regions[{ri}] ('{}'): give either sphere or cuboid, not both", r.name),
            (None, None) => bail!("regions[{ri}] ('{}'): a box mesh region after the first needs a sphere or a cuboid", r.name),
        };
        let mut claimed = 0;
        for (ti, c) in centroids.iter().enumerate() {
            if inside(c) {
                region_of_tet[ti] = ri;
                claimed += 1;
            }
        }
        if claimed == 0 {
            bail!("regions[{ri}] ('{}'): its shape holds the centroid of no tetrahedron", r.name);
        }
    }
    // Later regions may have claimed every tetrahedron of an earlier one: drop empty regions
    // from the mesh's list would renumber; instead refuse, naming it.
    for (ri, r) in regions.iter().enumerate() {
        if !region_of_tet.contains(&ri) {
            bail!("regions[{ri}] ('{}'): no tetrahedron is left in it (later regions cover it)", r.name);
        }
    }
    let names = regions.iter().map(|r| r.name.clone()).collect();
    Ok(TetMesh::with_regions(nodes, grid.tets().to_vec(), region_of_tet, names, grid.boundary_sets().clone(), limits)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_core::MeshLimits;

    const CUBE: &str = include_str!("../../scenes/cube-phantom-3d.toml");
    const CUBE_CSV: &str = include_str!("../../scenes/cube-phantom-3d.csv");

    /// The server's default session budget (1280 MiB).
    fn server() -> SceneLimits {
        SceneLimits { mesh: MeshLimits::default(), max_session_bytes: 1280 << 20 }
    }

    /// Parses `text`, its trajectory file being the cube's CSV, or `csv` when given.
    fn parse(text: &str, csv: Option<&str>) -> Result<Scene3d> {
        let read = |f: &str| -> Result<String> {
            if f.ends_with(".csv") {
                return Ok(csv.unwrap_or(CUBE_CSV).to_owned());
            }
            let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(f);
            std::fs::read_to_string(&p).with_context(|| format!("cannot read {}", p.display()))
        };
        parse_with(text, &read, &server())
    }

    /// Issue 37: the 2D scene's `[viscoelastic]` table in a 3D scene, off unless given, checked
    /// as in 2D (the message names the key).
    #[test]
    fn issue_37_viscoelastic_key() {
        assert_eq!(parse(CUBE, None).unwrap().viscoelastic, None);
        let table = |g: &str, tau: &str| format!("{CUBE}\n[viscoelastic]\nlong_term_ratio = {g}\nrelaxation_time_s = {tau}\n");
        let v = parse(&table("0.5", "2.0"), None).unwrap().viscoelastic.unwrap();
        assert_eq!((v.long_term_ratio, v.relaxation_time_s), (0.5, 2.0));
        let e = format!("{:#}", parse(&table("0", "2.0"), None).unwrap_err());
        assert!(e.contains("viscoelastic.long_term_ratio = 0: must be in (0, 1]"), "{e}");
        let e = format!("{:#}", parse(&table("0.5", "-1"), None).unwrap_err());
        assert!(e.contains("viscoelastic.relaxation_time_s = -1: must be finite and > 0"), "{e}");
    }

    /// Issue 37: `[needle] near_field` is off unless set, and a boolean.
    #[test]
    fn issue_37_near_field_key() {
        let cube = include_str!("../../scenes/cube-phantom-3d.toml");
        assert!(!parse(cube, None).unwrap().needle.near_field);
        let on = cube.replacen("[needle]", "[needle]\nnear_field = true", 1);
        assert!(parse(&on, None).unwrap().needle.near_field);
        let bad = cube.replacen("[needle]", "[needle]\nnear_field = 1", 1);
        let e = format!("{:#}", parse(&bad, None).unwrap_err());
        assert!(e.contains("near_field"), "{e}");
    }

    /// Issue 35: a 3D scene's `name` and `description` are bounded as a 2D scene's, and so is
    /// its TOML, before it is parsed.
    #[test]
    fn issue_35_scene3d_text_and_toml_size_are_bounded() {
        let e = error("name = \"cube-phantom-3d\"", &format!("name = \"{}\"", "n".repeat(200_000)));
        assert!(e.starts_with("name: the name 'nnn") && e.ends_with("has 200000 characters, at most 64") && e.len() < 200, "{e}");
        let old = "description = \"0.1 m PVC-like cube phantom, 21^3 nodes, fixed at the bottom; vertical insertion and withdrawal\"";
        let e = error(old, &format!("description = \"{}\"", "d".repeat(5000)));
        assert!(e.starts_with("description: 'ddd") && e.ends_with("has 5000 characters, at most 1024") && e.len() < 200, "{e}");
        let big = format!("{}\n# {}\n", small_cube("dim = 3", "dim = 3"), "x".repeat(crate::MAX_SCENE_TOML_BYTES));
        let e = parse(&big, None).expect_err("over the size limit");
        assert!(e.downcast_ref::<SizeLimit>().is_some(), "{e:#}");
        assert!(format!("{e:#}").contains("over the limit of 262144 bytes"), "{e:#}");
    }

    /// The cube scene, smaller (fast in debug builds), with `old` replaced by `new`.
    fn small_cube(old: &str, new: &str) -> String {
        let base = CUBE.replace("nx = 21\nny = 21\nnz = 21", "nx = 6\nny = 6\nnz = 6");
        assert!(base.contains(old), "{old}");
        base.replace(old, new)
    }

    fn error(old: &str, new: &str) -> String {
        format!("{:#}", parse(&small_cube(old, new), None).err().unwrap_or_else(|| panic!("{new}: must be rejected")))
    }

    #[test]
    fn issue_35_a_3d_scene_bounds_its_targets_and_its_physics() {
        use needlesim_core::sim::param_limits::MAX_TARGETS;
        let old = "[[targets]]\nname = \"centre\"\ncenter_m = [0.05, 0.05, 0.05]\nradius_m = 0.002\n";
        let targets = |n: usize, name: &dyn Fn(usize) -> String| -> String {
            (0..n).map(|k| format!("[[targets]]\nname = \"{}\"\ncenter_m = [0.05, 0.05, 0.05]\nradius_m = 0.002\n\n", name(k))).collect()
        };
        let s = parse(&small_cube(old, &targets(MAX_TARGETS, &|k| format!("t{k}"))), None).unwrap();
        assert_eq!(s.targets.len(), MAX_TARGETS);
        assert_eq!(error(old, &targets(MAX_TARGETS + 1, &|k| format!("t{k}"))), "targets: 17 given, at most 16");
        assert_eq!(error(old, &targets(1, &|_| String::new())), "targets[0]: the name is empty");
        let e = error(old, &targets(1, &|_| "n".repeat(100_000)));
        assert!(e.starts_with("targets[0]: the name 'nnn") && e.ends_with("…' has 100000 characters, at most 64"), "{e}");
        assert_eq!(
            error(old, &targets(3, &|k| ["x", "y", "x"][k].into())),
            "targets[2]: the name 'x' is already used by targets[0]; target names must be unique"
        );
        let e = error("name = \"gel\"", &format!("name = \"{}\"", "g".repeat(100_000)));
        assert!(e.starts_with("regions[0]: the name 'ggg") && e.len() < 150, "{e}");
        for (old, new, want) in [
            ("radius_m = 0.002", "radius_m = 1e300", "targets[0] ('centre').radius_m = 1e300: must be at most 10 m"),
            ("length_m = 0.1", "length_m = 1e3", "needle.length_m = 1000: must be at most 10 m"),
            ("young_modulus_pa = 30e3", "young_modulus_pa = 1e300", "regions[0] ('gel').young_modulus_pa = 1e300: must be at most 1e12 Pa"),
            ("friction_n_per_m = 10", "friction_n_per_m = 1e7", "regions[0] ('gel').friction_n_per_m = 10000000: must be at most 1e6"),
            ("cutting_force_n = 0.05", "cutting_force_n = 1e300", "regions[0] ('gel').cutting_force_n = 1e300: must be at most 1e6"),
            (
                "friction_n_per_m = 10",
                "friction_n_per_m = 10\nfriction_damping_n_s_per_m2 = 1e7",
                "regions[0] ('gel').friction_damping_n_s_per_m2 = 10000000: must be at most 1e6",
            ),
            ("dim = 3", &format!("dim = \"{}\"", "d".repeat(100_000)), ""),
        ] {
            let e = error(old, new);
            if want.is_empty() {
                // The parser's error (dim is a number) quotes a short excerpt of the line.
                assert!(e.starts_with("TOML parse error at line") && !e.contains(&"d".repeat(65)) && e.len() < 400, "{e}");
            } else {
                assert_eq!(e, want);
            }
        }
    }

    #[test]
    fn shipped_examples_load_with_their_meshes_regions_fixed_sets_and_trajectories() {
        for (name, ..) in EXAMPLES3D {
            let s = load_scene3d(name, server()).unwrap_or_else(|e| panic!("{name}: {e:#}"));
            assert_eq!(&s.name, name);
            assert!(!s.fixed_nodes.is_empty() && s.fixed_nodes.len() < s.mesh.n_nodes() / 2, "{name}");
            assert_eq!(s.mesh.boundary_set("fixed").unwrap(), &s.fixed_nodes[..]);
            let traj = s.trajectory.as_ref().expect("a trajectory");
            assert!(traj.samples.len() >= 2 && traj.duration_s() > 1.0, "{name}");
            // The trajectory starts at the scene's initial pose.
            let p0 = traj.samples[0].1;
            assert!((0..3).all(|i| (p0.position_m[i] - s.initial_pose.position_m[i]).abs() < 1e-12), "{name}");
            assert!((0..4).all(|i| (p0.quat_wxyz[i] - s.initial_pose.quat_wxyz[i]).abs() < 1e-12), "{name}");
            // The tip starts outside the tissue, aimed into it.
            let (tip, axis) = (s.initial_pose.position_m, s.initial_pose.axis());
            let tip = [0, 1, 2].map(|i| tip[i] + s.needle.length_m * axis[i]);
            assert!(TetLocator::new(&s.mesh).locate(&s.mesh, tip).is_err(), "{name}: the tip starts inside");
            let entered = [0, 1, 2].map(|i| tip[i] + 0.01 * axis[i]);
            assert!(TetLocator::new(&s.mesh).locate(&s.mesh, entered).is_ok(), "{name}: 5 mm on, the tip is not in the tissue");
        }
        let cube = load_scene3d("cube-phantom-3d", server()).unwrap();
        assert_eq!((cube.mesh.n_nodes(), cube.mesh.n_tets()), (21 * 21 * 21, 6 * 20 * 20 * 20));
        assert_eq!(cube.fixed_nodes.len(), 21 * 21);
        assert!(cube.fixed_nodes.iter().all(|&n| cube.mesh.nodes_m()[n][2] == 0.0));
        assert_eq!(
            cube.needle,
            Needle3d {
                length_m: 0.1,
                diameter_m: 1.270e-3,
                contact_spacing_m: 0.002,
                max_points: 64,
                flexible: None,
                spread_contact: false,
                near_field: false
            }
        );
        assert_eq!(cube.regions[0].material.young_modulus_pa, 30e3);
        assert!(matches!(cube.mesh_source, MeshSource3d::Box { n: [21, 21, 21], .. }));
        let s = std::f64::consts::FRAC_1_SQRT_2;
        assert!((cube.initial_pose.axis()[2] + 1.0).abs() < 1e-15 && (cube.initial_pose.quat_wxyz[0] - s).abs() < 1e-15);

        let b = load_scene3d("brachy-3d", server()).unwrap();
        assert!(matches!(&b.mesh_source, MeshSource3d::Msh { version, .. } if version.starts_with("4.1")), "{:?}", b.mesh_source);
        assert!((2_000..=30_000).contains(&b.mesh.n_tets()), "{} tets", b.mesh.n_tets());
        let names: Vec<&str> = b.regions.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["tissue", "prostate", "urethra"]);
        assert_eq!(b.regions[1].material.young_modulus_pa, 60e3);
        assert_eq!(b.fixed_sets, ["rectum_wall", "back"]);
        // The rectal wall is the cylinder r = 10 mm about (x, z) = (40, 12) mm.
        for &n in b.mesh.boundary_set("rectum_wall").unwrap() {
            let p = b.mesh.nodes_m()[n];
            assert!((((p[0] - 0.04).powi(2) + (p[2] - 0.012).powi(2)).sqrt() - 0.01).abs() < 2e-4, "{p:?}");
        }
        // Region volumes: the prostate ellipsoid less the urethra through it, within the
        // discretisation of the curved surfaces.
        let mut vol = [0.0; 3];
        for t in 0..b.mesh.n_tets() {
            vol[b.mesh.region_of_tet()[t]] += b.mesh.volume_m3(t);
        }
        let ellipsoid = 4.0 / 3.0 * std::f64::consts::PI * 0.02 * 0.017 * 0.016;
        assert!((vol[1] / ellipsoid - 0.96).abs() < 0.04, "prostate {} of {ellipsoid}", vol[1]);
        let box_less_rectum = 0.08 * 0.1 * 0.08 - std::f64::consts::PI * 0.01f64.powi(2) * 0.1;
        assert!(((vol[0] + vol[1] + vol[2]) / box_less_rectum - 1.0).abs() < 0.005, "{vol:?}");
        // The seed target lies in the prostate.
        let loc = TetLocator::new(&b.mesh).locate(&b.mesh, b.targets[0].center_m).unwrap();
        assert_eq!(b.mesh.region_of_tet()[loc.tet_idx], 1);
    }

    #[test]
    fn box_scenes_resolve_regions_by_shape_and_origin() {
        let text = small_cube(
            "[needle]",
            "[[regions]]\nname = \"lesion\"\nyoung_modulus_pa = 3e5\npoisson_ratio = 0.4\nsphere = { center_m = [0.05, 0.05, 0.05], radius_m = 0.03 }\n\n\
             [[regions]]\nname = \"slab\"\nyoung_modulus_pa = 1e5\npoisson_ratio = 0.4\ncuboid = { min_m = [0, 0, 0], max_m = [0.1, 0.1, 0.02] }\n\n[needle]",
        )
        .replace("size_m = [0.1, 0.1, 0.1]", "size_m = [0.1, 0.1, 0.1]\norigin_m = [0.0, 0.0, 0.0]");
        let s = parse(&text, None).unwrap();
        assert_eq!((s.mesh.n_nodes(), s.mesh.n_tets()), (216, 750));
        assert_eq!(s.mesh.region_names(), ["gel", "lesion", "slab"]);
        for (t, &r) in s.mesh.region_of_tet().iter().enumerate() {
            let c = s.mesh.tet_points_m(t).iter().fold([0.0; 3], |a, p| [a[0] + p[0] / 4.0, a[1] + p[1] / 4.0, a[2] + p[2] / 4.0]);
            let in_sphere = ((c[0] - 0.05).powi(2) + (c[1] - 0.05).powi(2) + (c[2] - 0.05).powi(2)).sqrt() <= 0.03;
            let want = if c[2] <= 0.02 {
                2
            } else if in_sphere {
                1
            } else {
                0
            };
            assert_eq!(r, want, "tet {t} at {c:?}");
        }
        // An origin moves the mesh; the sets stay faces.
        let s = parse(&small_cube("size_m = [0.1, 0.1, 0.1]", "size_m = [0.1, 0.1, 0.1]\norigin_m = [1.0, 0.0, -0.1]"), None);
        let e = format!("{:#}", s.err().unwrap());
        assert!(e.contains("targets[0] ('centre').center_m = [0.05, 0.05, 0.05]: not inside the mesh"), "{e}");
        let moved = small_cube("size_m = [0.1, 0.1, 0.1]", "size_m = [0.1, 0.1, 0.1]\norigin_m = [0.0, 0.0, -0.1]")
            .replace("center_m = [0.05, 0.05, 0.05]", "center_m = [0.05, 0.05, -0.05]");
        let s = parse(&moved, None).unwrap();
        assert!(s.fixed_nodes.iter().all(|&n| s.mesh.nodes_m()[n][2] == -0.1));
        // The model factorises: the fixed face holds the box.
        let model = s.tissue_model().unwrap();
        assert_eq!(model.n_dofs(), 3 * 216);
    }

    /// `model = "flexible"` gives the rod: a gauge's EI (its tube), or EI directly, the bevel
    /// keys, 2 mm links by default.
    #[test]
    fn flexible_and_bevel_needles_parse() {
        use needlesim_core::needle::FlexibleNeedle;
        let s =
            parse(&small_cube("gauge = 18", "gauge = 22\nmodel = \"flexible\"\nbevel_force_ratio = 0.4\nbevel_side = -1"), None).unwrap();
        let f = s.needle.flexible.expect("a flexible needle");
        let (_, od, id) = crate::GAUGES.iter().find(|g| g.0 == 22).copied().unwrap();
        assert_eq!(f.flexural_rigidity_nm2, crate::STEEL_E_PA * FlexibleNeedle::tube_second_moment_m4(od, id));
        assert_eq!((f.length_m, f.n_links, f.bevel_force_ratio, f.bevel_side), (0.1, 50, 0.4, -1.0));
        let s = parse(&small_cube("gauge = 18", "model = \"flexible\"\nflexural_rigidity_nm2 = 0.002\nn_links = 20"), None).unwrap();
        let f = s.needle.flexible.unwrap();
        assert_eq!((f.flexural_rigidity_nm2, f.n_links, f.bevel_force_ratio), (0.002, 20, 0.0));
        assert_eq!(parse(&small_cube("gauge = 18", "gauge = 18\nmodel = \"rigid\""), None).unwrap().needle.flexible, None);
    }

    /// Rate-dependent friction reaches the 3D regions' needle parameters (0 by default).
    #[test]
    fn friction_damping_reaches_the_regions() {
        let text = small_cube("gauge = 18", "gauge = 18");
        assert_eq!(parse(&text, None).unwrap().regions[0].needle.friction_damping_n_s_per_m2, 0.0);
        let damped = text.replace("friction_n_per_m = 10", "friction_n_per_m = 10\nfriction_damping_n_s_per_m2 = 500");
        assert_ne!(damped, text);
        assert_eq!(parse(&damped, None).unwrap().regions[0].needle.friction_damping_n_s_per_m2, 500.0);
    }

    #[test]
    fn bad_values_name_the_key() {
        let q = "base_quat = [0.7071067811865475, 0.0, 0.7071067811865475, 0.0]";
        let cases = [
            (q, "base_quat = [1.0, 0.0, 0.1, 0.0]", "needle.base_quat = [1.0, 0.0, 0.1, 0.0]: must have unit norm (its norm is 1.0049"),
            (q, "base_quat = [0.0, 0.0, 0.0, 0.0]", "needle.base_quat = [0.0, 0.0, 0.0, 0.0]: must have unit norm"),
            (q, "base_quat = [nan, 0.0, 0.0, 1.0]", "needle.base_quat = [NaN, 0.0, 0.0, 1.0]: must be finite"),
            (q, "base_axis = [0.0, 0.0, -2.0]", "needle.base_axis = [0.0, 0.0, -2.0]: must have unit norm"),
            (q, "base_axis = [0.0, 0.0, -1.0]\nbase_roll_rad = inf", "needle.base_roll_rad = inf: must be finite"),
            (q, "", "needle: the base orientation is missing"),
            (q, "base_quat = [1.0, 0.0, 0.0, 0.0]\nbase_axis = [1.0, 0.0, 0.0]", "give either base_quat or base_axis"),
            (q, &format!("{q}\nbase_roll_rad = 0.5"), "needle.base_roll_rad goes with base_axis"),
            ("base_m = [0.05, 0.05, 0.205]", "base_m = [0.05, inf, 0.205]", "needle.base_m = [0.05, inf, 0.205]: must be finite"),
            ("base_m = [0.05, 0.05, 0.205]", "base_m = [0.05, 0.05]", "base_m"),
            ("length_m = 0.1", "length_m = -0.1", "needle.length_m = -0.1: must be finite and > 0"),
            ("gauge = 18", "gauge = 19", "needle.gauge = 19 is not in the table"),
            ("gauge = 18", "gauge = 18\ndiameter_m = 0.001", "give either gauge or diameter_m"),
            ("gauge = 18", "diameter_m = 0", "needle.diameter_m = 0: must be finite, > 0"),
            ("contact_spacing_m = 0.002", "contact_spacing_m = 0", "needle.contact_spacing_m = 0: must be between"),
            ("max_points = 64", "max_points = 0", "needle.max_points = 0: must be in 1..=4096"),
            ("gauge = 18", "gauge = 18\nstiffness = 1.0", "unknown field `stiffness`"),
            ("gauge = 18", "gauge = 18\nmodel = \"bendy\"", "unknown variant `bendy`, expected `rigid` or `flexible`"),
            (
                "gauge = 18",
                "gauge = 18\nbevel_force_ratio = 0.3",
                "needle.bevel_force_ratio is for a flexible needle: add model = \"flexible\"",
            ),
            (
                "gauge = 18",
                "gauge = 18\nmodel = \"flexible\"\nflexural_rigidity_nm2 = 0.01",
                "needle: give either gauge or flexural_rigidity_nm2",
            ),
            ("gauge = 18", "model = \"flexible\"\nflexural_rigidity_nm2 = -1", "needle.flexural_rigidity_nm2 = -1: must be finite and > 0"),
            ("gauge = 18", "gauge = 19\nmodel = \"flexible\"", "needle.gauge = 19 is not in the table"),
            ("gauge = 18", "gauge = 18\nmodel = \"flexible\"\nn_links = 0", "needle.n_links = 0: must be in 1..=400"),
            ("gauge = 18", "gauge = 18\nmodel = \"flexible\"\nbevel_force_ratio = -0.1", "needle.bevel_force_ratio = -0.1: must be finite"),
            ("gauge = 18", "gauge = 18\nmodel = \"flexible\"\nbevel_side = 0.5", "needle.bevel_side = 0.5: must be +1 or -1"),
            ("nx = 6", "nx = 1", "mesh.nx = 1: must be at least 2"),
            ("size_m = [0.1, 0.1, 0.1]", "size_m = [0.1, -0.1, 0.1]", "mesh.size_m = [0.1, -0.1, 0.1]: must be finite and > 0"),
            ("type = \"box\"", "type = \"grid\"", "unknown variant `grid`, expected one of `box`, `msh`, `vtk`, `vtu`"),
            ("young_modulus_pa = 30e3", "young_modulus_pa = -1", "regions"),
            ("poisson_ratio = 0.45", "poisson_ratio = 0.5", "regions"),
            ("friction_n_per_m = 10", "friction_n_per_m = -3", "regions[0] ('gel').friction_n_per_m = -3: must be finite and ≥ 0"),
            (
                "friction_n_per_m = 10",
                "friction_n_per_m = 10\nfriction_damping_n_s_per_m2 = -1",
                "regions[0] ('gel').friction_damping_n_s_per_m2 = -1: must be finite and ≥ 0",
            ),
            (
                "static_friction_ratio = 1.3",
                "static_friction_ratio = 0.5",
                "regions[0] ('gel').static_friction_ratio = 0.5: must be finite and ≥ 1",
            ),
            (
                "fixed = [\"bottom\"]",
                "fixed = [\"floor\"]",
                "fixed[0]: the mesh has no boundary set 'floor' (it has: [\"back\", \"bottom\"",
            ),
            ("fixed = [\"bottom\"]", "fixed = []", "fixed: name at least one boundary set"),
            ("radius_m = 0.002", "radius_m = -1", "targets[0] ('centre').radius_m = -1: must be finite and ≥ 0"),
            ("center_m = [0.05, 0.05, 0.05]", "center_m = [0.05, 0.05]", "center_m"),
            (
                "center_m = [0.05, 0.05, 0.05]",
                "center_m = [0.05, 0.05, 0.5]",
                "targets[0] ('centre').center_m = [0.05, 0.05, 0.5]: not inside the mesh",
            ),
            ("tick_rate_hz = 1000", "tick_rate_hz = 1e9", "tick_rate_hz = 1000000000: must be between 100 and 10000"),
            ("dim = 3", "dim = 4", "dim = 4: a 3D scene has dim = 3"),
            ("[needle]", "[limits]\nmax_base_step_m = -1\n\n[needle]", "limits.max_base_step_m = -1: must be finite and > 0"),
            (
                "[needle]",
                "[[regions]]\nname = \"gel\"\nyoung_modulus_pa = 1e4\npoisson_ratio = 0.3\n\n[needle]",
                "regions[1]: the name 'gel' is already used by regions[0]",
            ),
            (
                "[needle]",
                "[[regions]]\nname = \"blob\"\nyoung_modulus_pa = 1e4\npoisson_ratio = 0.3\n\n[needle]",
                "regions[1] ('blob'): a box mesh region after the first needs a sphere or a cuboid",
            ),
            (
                "[needle]",
                "[[regions]]\nname = \"blob\"\nyoung_modulus_pa = 1e4\npoisson_ratio = 0.3\nsphere = { center_m = [5, 5, 5], radius_m = 0.01 }\n\n[needle]",
                "regions[1] ('blob'): its shape holds the centroid of no tetrahedron",
            ),
            ("trajectory = \"cube-phantom-3d.csv\"", "trajectory = \"nowhere.toml\"", "trajectory = \"nowhere.toml\": cannot read"),
        ];
        for (old, new, want) in cases {
            let e = error(old, new);
            assert!(e.contains(want), "{new}: {e}");
        }
        // The axis form is the quaternion form.
        let a = parse(&small_cube(q, "base_axis = [0.0, 0.0, -1.0]"), None).unwrap();
        let b = parse(&small_cube(q, q), None).unwrap();
        assert!((0..4).all(|i| (a.initial_pose.quat_wxyz[i] - b.initial_pose.quat_wxyz[i]).abs() < 1e-15));
        let r = parse(&small_cube(q, "base_axis = [0.0, 0.0, -1.0]\nbase_roll_rad = 1.5707963267948966"), None).unwrap();
        let (fa, fr) = (a.initial_pose.frame(), r.initial_pose.frame());
        assert!((0..3).all(|i| (fa[0][i] - fr[0][i]).abs() < 1e-15 && (fa[2][i] - fr[1][i]).abs() < 1e-15), "{fa:?} {fr:?}");
    }

    #[test]
    fn the_trajectory_csvs_errors_name_the_line() {
        let bad = "# comment\nt_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0.05,0.05,0.205,1,0,0,0\n1,0.05,0.05,0.2,0.9,0,0,0\n";
        let e = format!("{:#}", parse(&small_cube("nx = 6", "nx = 6"), Some(bad)).err().unwrap());
        assert!(
            e.contains("trajectory = \"cube-phantom-3d.csv\": trajectory line 4: the quaternion qw,qx,qy,qz must have unit norm"),
            "{e}"
        );
        let bad = "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0.05,0.05,0.205,1,0,0,0\n\n1,0.05,oops,0.2,1,0,0,0\n";
        let e = format!("{:#}", parse(&small_cube("nx = 6", "nx = 6"), Some(bad)).err().unwrap());
        assert!(e.contains("trajectory line 4: column y_m") && e.contains("`oops` is not a number"), "{e}");
    }

    #[test]
    fn msh_scenes_check_regions_and_fixed_sets_against_the_mesh() {
        let brachy = include_str!("../../scenes/brachy-3d.toml");
        let read_brachy = |old: &str, new: &str| {
            assert!(brachy.contains(old), "{old}");
            format!("{:#}", parse(&brachy.replace(old, new), None).expect_err("rejected"))
        };
        let e = read_brachy("name = \"urethra\"", "name = \"bladder\"");
        assert!(e.contains("regions[2]: 'bladder' is not a region of the mesh (mesh regions: tissue, prostate, urethra)"), "{e}");
        let e = read_brachy("fixed = [\"rectum_wall\", \"back\"]", "fixed = [\"rectum_wall\", \"pubis\"]");
        assert!(e.contains("fixed[1]: the mesh has no boundary set 'pubis'") && e.contains("\"rectum_wall\""), "{e}");
        // A mesh region without an entry.
        let cut = brachy.find("[[regions]]\nname = \"urethra\"").unwrap();
        let needle = brachy.find("[needle]").unwrap();
        let without = format!("{}{}", &brachy[..cut], &brachy[needle..]);
        let e = format!("{:#}", parse(&without, None).err().unwrap());
        assert!(e.contains("the mesh has a region 'urethra' but no [[regions]] entry is named so"), "{e}");
        let e = read_brachy("name = \"urethra\"", "name = \"urethra\"\nsphere = { center_m = [0, 0, 0], radius_m = 1 }");
        assert!(e.contains("regions[2] ('urethra'): sphere and cuboid apply to box meshes"), "{e}");
        let e = read_brachy("file = \"brachy-3d.msh\"", "file = \"missing.msh\"");
        assert!(e.contains("mesh.file = \"missing.msh\": cannot read"), "{e}");
        // A broken file: the MSH error names its line.
        let dir = std::env::temp_dir().join(format!("needlesim-scene3d-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let msh = include_str!("../../scenes/brachy-3d.msh").replacen("$EndNodes", "$EndNodez", 1);
        std::fs::write(dir.join("brachy-3d.msh"), msh).unwrap();
        std::fs::write(dir.join("brachy-3d.csv"), include_str!("../../scenes/brachy-3d.csv")).unwrap();
        let e = format!("{:#}", parse_scene3d(brachy, &dir, server()).err().unwrap());
        assert!(e.contains("mesh.file = \"brachy-3d.msh\": MSH line"), "{e}");
        // The validation suite's Gmsh cube, in both versions, as a scene.
        let validation = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation/meshes");
        for v in ["v41", "v22"] {
            let Ok(text) = std::fs::read_to_string(validation.join(format!("cube_sphere_{v}.msh"))) else {
                eprintln!("skipped: no validation meshes at {}", validation.display());
                continue;
            };
            std::fs::write(dir.join("cube.msh"), text).unwrap();
            let scene =
                small_cube("type = \"box\"\nnx = 6\nny = 6\nnz = 6\nsize_m = [0.1, 0.1, 0.1]", "type = \"msh\"\nfile = \"cube.msh\"")
                    .replace("name = \"gel\"", "name = \"tissue\"")
                    .replace("[needle]", "[[regions]]\nname = \"lesion\"\nyoung_modulus_pa = 3e5\npoisson_ratio = 0.45\n\n[needle]")
                    .replace("trajectory = \"cube-phantom-3d.csv\"\n", "");
            let s = parse_scene3d(&scene, &dir, server()).unwrap_or_else(|e| panic!("{v}: {e:#}"));
            assert_eq!((s.mesh.n_nodes(), s.mesh.n_tets()), (2284, 10074), "{v}");
            assert_eq!(s.mesh.region_names(), ["tissue", "lesion"]);
            assert!(s.fixed_nodes.iter().all(|&n| s.mesh.nodes_m()[n][2].abs() < 1e-12), "{v}");
            assert!(s.trajectory.is_none());
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn the_memory_estimate_refuses_oversized_meshes_and_fits_the_examples() {
        // The examples fit the server's default budget; an 81³ box does not, refused before
        // the mesh is built, with a SizeLimit in the chain.
        assert!(estimated_session_bytes_3d(21 * 21 * 21, 64) < 1280 << 20);
        let e = parse(&CUBE.replace("nx = 21\nny = 21\nnz = 21", "nx = 81\nny = 81\nnz = 81"), None).err().unwrap();
        let size = e.chain().find_map(|c| c.downcast_ref::<SizeLimit>()).unwrap_or_else(|| panic!("not a size limit: {e:#}"));
        assert_eq!((size.amount, size.limit), (estimated_session_bytes_3d(81 * 81 * 81, 64).div_ceil(1 << 20) as f64, 1280));
        assert!(format!("{e:#}").starts_with("mesh: the estimated memory of a session of this 3D scene (531441 mesh nodes"), "{e:#}");
        // More needle points, more cached columns.
        assert!(estimated_session_bytes_3d(9261, 128) > estimated_session_bytes_3d(9261, 64));
        // 3D costs more than 2D per node: 3 DOFs, 4 nodes per point, n^{5/3} fill.
        assert!(estimated_session_bytes_3d(9261, 64) > crate::estimated_session_bytes(9261, 64));
    }

    /// The factor term bounds the measured fill of box grids (12 bytes per non-zero of `L`).
    #[test]
    fn factor_fill_is_bounded_by_the_estimate() {
        for n in [6usize, 11, 16] {
            let s = parse(&CUBE.replace("nx = 21\nny = 21\nnz = 21", &format!("nx = {n}\nny = {n}\nnz = {n}")), None).unwrap();
            let model = s.tissue_model().unwrap();
            let measured = 12 * model.cholesky().factor_nnz() as u64;
            let nodes = (n * n * n) as f64;
            let bound = FACTOR_BYTES_PER_NODE_5_3 as f64 * nodes.powf(5.0 / 3.0);
            eprintln!("{n}³: factor {measured} bytes, estimate {bound:.0}");
            assert!((measured as f64) < bound, "{n}³: {measured} bytes over {bound}");
        }
    }

    #[test]
    fn dim_selects_the_loader_and_2d_scenes_are_unchanged() {
        assert_eq!(scene_dim(CUBE).unwrap(), 3);
        let paper = include_str!("../../scenes/paper-phantom.toml");
        assert_eq!(scene_dim(paper).unwrap(), 2);
        assert_eq!(scene_dim("not toml [").unwrap(), 2);
        assert!(format!("{:#}", scene_dim("dim = \"3\"").err().unwrap()).contains("dim = \"3\": must be 2 or 3"));
        let lim = MeshLimits::default();
        let e = crate::parse_scene(CUBE, Path::new("."), &lim).err().unwrap();
        assert!(format!("{e:#}").contains("dim = 3: this is a 3D scene"), "{e:#}");
        let with_dim = crate::parse_scene(&format!("dim = 2\n{paper}"), Path::new("."), &lim).unwrap();
        assert_eq!(with_dim.tissue.mesh().n_nodes(), 361);
        let e = crate::parse_scene(&format!("dim = 5\n{paper}"), Path::new("."), &lim).err().unwrap();
        assert!(format!("{e:#}").contains("dim = 5: must be 2 or 3"), "{e:#}");
        let e = parse(&CUBE.replace("dim = 3\n", ""), None).err().unwrap();
        assert!(format!("{e:#}").contains("missing field `dim`"), "{e:#}");
    }
}
