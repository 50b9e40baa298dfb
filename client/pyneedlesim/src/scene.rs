//! `needlesim.Scene` and `needlesim.load_scene`: a 2D or 3D scene loaded (and its tissue
//! factorised) once, shared by the simulations made from it; a 2D scene's region values can be
//! scaled at load (`scale=`, e.g. a sampled Young's modulus for planning under uncertainty).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use needlesim_core::MeshLimits;
use needlesim_core::d3::TetTissueModel;
use needlesim_scene::{EXAMPLES, EXAMPLES3D, MAX_LOCAL_FILE_BYTES, Scene, Scene3d, read_local_file};
use numpy::{IntoPyArray, PyArray1, PyArray2, ndarray::Array2};
use pyo3::prelude::*;

use crate::errors::{SceneError, scene_error};

/// A loaded scene of either dimension (boxed: the two differ much in size).
pub enum SceneKind {
    /// A 2D scene: its tissue model is factorised by the loader.
    D2(Box<Scene>),
    /// A 3D scene and its factorised tissue model.
    D3 { scene: Box<Scene3d>, tissue: Arc<TetTissueModel> },
}

impl SceneKind {
    /// 2 or 3.
    pub fn dim(&self) -> usize {
        match self {
            SceneKind::D2(_) => 2,
            SceneKind::D3 { .. } => 3,
        }
    }
}

pub use needlesim_offline::simulate3::sim3_params;

/// Loads a scene as `needlesim-server simulate --scene SPEC` does: a shipped example's name
/// (2D or 3D), else a TOML file whose `dim` key (2 when absent) picks the loader. 3D tissues
/// are factorised here.
pub fn load(spec: &str, scale: &[(String, f64)]) -> anyhow::Result<SceneKind> {
    let limits = MeshLimits::default();
    let dim = if EXAMPLES.iter().any(|e| e.0 == spec) {
        2
    } else if EXAMPLES3D.iter().any(|e| e.0 == spec) {
        3
    } else {
        let path = Path::new(spec);
        if std::fs::symlink_metadata(path).is_err() {
            let d2: Vec<&str> = EXAMPLES.iter().map(|e| e.0).collect();
            let d3: Vec<&str> = EXAMPLES3D.iter().map(|e| e.0).collect();
            anyhow::bail!("scene '{spec}' is neither a file nor a shipped example (examples: {}; 3D: {})", d2.join(", "), d3.join(", "));
        }
        // A regular file of bounded size, not a link: /dev/zero or a FIFO is refused unread.
        let text = read_local_file(path, MAX_LOCAL_FILE_BYTES)?;
        needlesim_scene::scene_dim(&text).map_err(|e| e.context(format!("scene {}", path.display())))?
    };
    if dim == 2 && scale.is_empty() {
        return Ok(SceneKind::D2(Box::new(needlesim_scene::load_scene(spec, &limits)?)));
    }
    if dim == 2 {
        return Ok(SceneKind::D2(Box::new(load_scaled(spec, scale, &limits)?)));
    }
    if !scale.is_empty() {
        anyhow::bail!("scale: scaling region values is supported for 2D scenes only; '{spec}' is a 3D scene");
    }
    let scene = needlesim_scene::load_scene3d(spec, &limits)?;
    let tissue = Arc::new(scene.tissue_model().map_err(|e| e.context(format!("scene {}", scene.name)))?);
    Ok(SceneKind::D3 { scene: Box::new(scene), tissue })
}

/// The region keys `scale=` may multiply (numbers of every `[[regions]]` entry of a 2D scene).
pub const SCALABLE_REGION_KEYS: [&str; 8] = [
    "young_modulus_pa",
    "poisson_ratio",
    "friction_n_per_m",
    "static_friction_ratio",
    "tip_peak_ratio",
    "tip_peak_width_m",
    "puncture_force_n",
    "cutting_force_n",
];

/// A 2D scene (an example's name or a TOML file) with the region values `scale` names multiplied
/// by its factors in every region, then loaded as the file would be: the TOML is parsed, edited
/// and written back (floats print shortest round-trip, so a factor of 1 changes nothing), and the
/// loader checks the scaled values as it checks a file's.
fn load_scaled(spec: &str, scale: &[(String, f64)], limits: &MeshLimits) -> anyhow::Result<Scene> {
    use anyhow::Context as _;
    let (text, base_dir, example_csv) = match EXAMPLES.iter().find(|e| e.0 == spec) {
        Some((_, toml_text, csv)) => ((*toml_text).to_owned(), PathBuf::from("server/scenes"), Some(*csv)),
        None => {
            let path = Path::new(spec);
            let text = read_local_file(path, MAX_LOCAL_FILE_BYTES)?;
            (text, path.parent().unwrap_or(Path::new(".")).to_path_buf(), None)
        }
    };
    let mut table: toml::Table =
        text.parse().map_err(|e: toml::de::Error| anyhow::anyhow!("scene {spec}: {}", needlesim_scene::limit::toml_message(&e, &text)))?;
    let Some(regions) = table.get_mut("regions").and_then(|r| r.as_array_mut()) else {
        anyhow::bail!("scale: scene {spec} has no [[regions]] to scale");
    };
    for (key, factor) in scale {
        if !SCALABLE_REGION_KEYS.contains(&key.as_str()) {
            anyhow::bail!(
                "scale: '{}' is not a region value that can be scaled (one of: {})",
                needlesim_scene::limit::quote(key),
                SCALABLE_REGION_KEYS.join(", ")
            );
        }
        if !(factor.is_finite() && *factor > 0.0) {
            anyhow::bail!("scale: the factor of '{key}' is {}; it must be finite and > 0", needlesim_core::num::num(*factor));
        }
        for (k, region) in regions.iter_mut().enumerate() {
            let value = region.get(key.as_str()).and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)));
            let Some(value) = value else {
                anyhow::bail!("scale: regions[{k}] of scene {spec} does not set {key} as a number; write it in the scene to scale it");
            };
            region.as_table_mut().expect("a [[regions]] entry is a table").insert(key.clone(), toml::Value::Float(value * factor));
        }
    }
    let scaled = toml::to_string(&table).context("writing the scaled scene")?;
    let mut scene = needlesim_scene::parse_scene(&scaled, &base_dir, limits).with_context(|| format!("scene {spec} scaled"))?;
    scene.example_trajectory = example_csv;
    Ok(scene)
}

/// A target of a scene: a disc (2D) or a sphere (3D) that moves with the tissue.
#[pyclass(module = "needlesim", frozen, get_all)]
pub struct Target {
    /// The target's name, as in the scene file.
    pub name: String,
    /// Its undeformed centre, m (length 2 or 3).
    pub center_m: Vec<f64>,
    /// Its radius, m: the tip within it is a hit.
    pub radius_m: f64,
}

#[pymethods]
impl Target {
    fn __repr__(&self) -> String {
        format!("Target(name={:?}, center_m={:?}, radius_m={})", self.name, self.center_m, self.radius_m)
    }
}

/// A loaded scene: the tissue (mesh, materials, fixed nodes; its stiffness factorised), the
/// needle, the targets and, for a shipped example or a 3D scene naming one, its own base
/// trajectory. Made by :func:`needlesim.load_scene`; immutable, shared by the simulations made
/// from it (pickling is not supported: a worker loads the scene by name or path).
#[pyclass(module = "needlesim", name = "Scene", frozen)]
pub struct PyScene {
    pub inner: Arc<SceneKind>,
}

fn array2<T: numpy::Element>(py: Python<'_>, rows: usize, cols: usize, v: Vec<T>) -> Bound<'_, PyArray2<T>> {
    Array2::from_shape_vec((rows, cols), v).expect("rows × cols values").into_pyarray(py)
}

#[pymethods]
impl PyScene {
    /// 2 for a triangle-mesh scene, 3 for a tetrahedral one.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        match &*self.inner {
            SceneKind::D2(s) => s.name.clone(),
            SceneKind::D3 { scene, .. } => scene.name.clone(),
        }
    }

    /// Ticks per second of its simulations, Hz.
    #[getter]
    fn tick_rate_hz(&self) -> f64 {
        match &*self.inner {
            SceneKind::D2(s) => s.params.tick_rate_hz,
            SceneKind::D3 { scene, .. } => scene.tick_rate_hz,
        }
    }

    /// The mesh's node coordinates (reference configuration), m: float64 array of shape
    /// (n_nodes, dim). A new copy at each access.
    #[getter]
    fn nodes_m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        match &*self.inner {
            SceneKind::D2(s) => {
                let n = s.tissue.mesh().nodes_m();
                array2(py, n.len(), 2, n.iter().flatten().copied().collect())
            }
            SceneKind::D3 { scene, .. } => {
                let n = scene.mesh.nodes_m();
                array2(py, n.len(), 3, n.iter().flatten().copied().collect())
            }
        }
    }

    /// The mesh's elements as node indices: int64 array of shape (n_elements, 3) for
    /// triangles (2D) or (n_elements, 4) for tetrahedra (3D).
    #[getter]
    fn elements<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        match &*self.inner {
            SceneKind::D2(s) => {
                let t = s.tissue.mesh().triangles();
                array2(py, t.len(), 3, t.iter().flatten().map(|&i| i as i64).collect())
            }
            SceneKind::D3 { scene, .. } => {
                let t = scene.mesh.tets();
                array2(py, t.len(), 4, t.iter().flatten().map(|&i| i as i64).collect())
            }
        }
    }

    /// The nodes held fixed (the support), sorted: int64 array.
    #[getter]
    fn fixed_nodes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let f = match &*self.inner {
            SceneKind::D2(s) => &s.fixed_nodes,
            SceneKind::D3 { scene, .. } => &scene.fixed_nodes,
        };
        f.iter().map(|&i| i as i64).collect::<Vec<_>>().into_pyarray(py)
    }

    /// The scene's targets, in the file's order.
    #[getter]
    fn targets(&self) -> Vec<Target> {
        match &*self.inner {
            SceneKind::D2(s) => s
                .params
                .targets
                .iter()
                .map(|t| Target { name: t.name.clone(), center_m: t.center_m.to_vec(), radius_m: t.radius_m })
                .collect(),
            SceneKind::D3 { scene, .. } => {
                scene.targets.iter().map(|t| Target { name: t.name.clone(), center_m: t.center_m.to_vec(), radius_m: t.radius_m }).collect()
            }
        }
    }

    /// The base pose before the first step: (x_m, y_m, theta_rad) in 2D,
    /// (x_m, y_m, z_m, qw, qx, qy, qz) in 3D, as a float64 array.
    #[getter]
    fn initial_pose<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        match &*self.inner {
            SceneKind::D2(s) => {
                let p = s.params.initial_pose;
                vec![p.x_m, p.y_m, p.theta_rad].into_pyarray(py)
            }
            SceneKind::D3 { scene, .. } => {
                let p = scene.initial_pose;
                let mut v = p.position_m.to_vec();
                v.extend(p.quat_wxyz);
                v.into_pyarray(py)
            }
        }
    }

    /// The scene's own base trajectory (a shipped example's, or the file a 3D scene names), as
    /// its samples: float64 array of shape (n, 4) with columns t_s, x_m, y_m, theta_rad (2D) or
    /// (n, 8) with t_s, x_m, y_m, z_m, qw, qx, qy, qz (3D); None when the scene has none.
    #[getter]
    fn trajectory<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        match &*self.inner {
            SceneKind::D2(s) => {
                let Some(text) = s.example_trajectory else { return Ok(None) };
                let t = needlesim_scene::Trajectory::parse_csv(text).map_err(|e| crate::errors::trajectory_error(&e))?;
                let v: Vec<f64> = t.samples.iter().flat_map(|(t, p)| [*t, p.x_m, p.y_m, p.theta_rad]).collect();
                Ok(Some(array2(py, t.samples.len(), 4, v)))
            }
            SceneKind::D3 { scene, .. } => Ok(scene.trajectory.as_ref().map(|t| {
                let v: Vec<f64> = t
                    .samples
                    .iter()
                    .flat_map(|(t, p)| {
                        let mut r = vec![*t];
                        r.extend(p.position_m);
                        r.extend(p.quat_wxyz);
                        r
                    })
                    .collect();
                array2(py, t.samples.len(), 8, v)
            })),
        }
    }

    fn __repr__(&self) -> String {
        let (n_nodes, n_el) = match &*self.inner {
            SceneKind::D2(s) => (s.tissue.mesh().n_nodes(), s.tissue.mesh().n_triangles()),
            SceneKind::D3 { scene, .. } => (scene.mesh.n_nodes(), scene.mesh.n_tets()),
        };
        format!("Scene(name={:?}, dim={}, nodes={n_nodes}, elements={n_el})", self.name(), self.dim())
    }
}

/// Loads a scene: the name of a shipped example (2D: paper-phantom, fig3-target,
/// fig4-steering, bevel-tip; 3D: cube-phantom-3d, brachy-3d, fig3-target-3d), as
/// ``needlesim-server simulate --scene`` accepts, or the path (str or os.PathLike) of a scene
/// TOML file, 2D or 3D by its ``dim`` key. The tissue's stiffness is factorised here (seconds
/// for a large 3D mesh; the GIL is released meanwhile).
///
/// ``scale`` (2D scenes): a dict of region keys to factors, each key's value multiplied by its
/// factor in every region before the scene is built, e.g. ``{"young_modulus_pa": 1.1,
/// "friction_n_per_m": 0.9}`` for a tissue 10 % stiffer with 10 % less friction (keys:
/// young_modulus_pa, poisson_ratio, friction_n_per_m, static_friction_ratio, tip_peak_ratio,
/// tip_peak_width_m, puncture_force_n, cutting_force_n; the scene must write the key in each
/// region). The scaled values are checked as a file's are.
///
/// Raises SceneError naming what is wrong (a path that is neither a file nor an example, an
/// invalid TOML, a value out of range, a mesh over the limits, a key that cannot be scaled, a
/// factor that is not finite and positive).
#[pyfunction]
#[pyo3(signature = (scene, *, scale=None))]
pub fn load_scene(py: Python<'_>, scene: PathBuf, scale: Option<std::collections::BTreeMap<String, f64>>) -> PyResult<PyScene> {
    let Some(spec) = scene.to_str().map(str::to_owned) else {
        return Err(SceneError::new_err(format!("scene path {} is not valid UTF-8", scene.display())));
    };
    let scale: Vec<(String, f64)> = scale.unwrap_or_default().into_iter().collect();
    let kind = py.detach(move || load(&spec, &scale)).map_err(scene_error)?;
    Ok(PyScene { inner: Arc::new(kind) })
}
