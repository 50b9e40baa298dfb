//! The static-problem exchange format of ../shared/validation (scenario in, result out), and its
//! conversion to and from the core's types. The only place where that JSON meets the core.
//! A scenario with `"dim": 3` is a 3D problem ([`crate::exchange3d`]); [`parse_any_scenario`] and
//! [`solve_any`] take either.

use std::collections::BTreeMap;

use anyhow::{Context, Result, bail};
use needlesim_core::compliance::{ComplianceCache, TissueModel};
use needlesim_core::{Material, MaterialMap, Mesh, MeshLimits, NodeCondition, PlaneModel, StaticProblem};
use serde::de::{Error as _, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

/// A static problem (see ../shared/validation/README.md). Node ids are 0-based.
#[derive(Debug, Clone, Deserialize, Serialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    #[serde(deserialize_with = "node_coordinates")]
    pub nodes: Vec<[f64; 2]>,
    pub triangles: Vec<[i64; 3]>,
    #[serde(rename = "E")]
    pub young_modulus_pa: f64,
    pub nu: f64,
    #[serde(default = "default_plane")]
    pub plane: String,
    #[serde(default = "one")]
    pub thickness: f64,
    #[serde(rename = "E_elem", default, skip_serializing_if = "Option::is_none")]
    pub young_modulus_elem_pa: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu_elem: Option<Vec<f64>>,
    #[serde(default)]
    pub fixed_nodes: Vec<i64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub prescribed: Vec<Prescribed>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub prescribed_local: Vec<PrescribedLocal>,
    #[serde(default)]
    pub loads: Vec<Load>,
    /// Conditions at material points (contact points that need not be nodes); solved by the
    /// reference (fem_ref.py), not by [`solve_scenario`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<PointCondition>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub working_points: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub working_nodes: Option<Vec<i64>>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub output_stresses: bool,
    /// Written by `simulate --dump-state`: the simulator's own displacements, `[[ux, uy], …]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solver_displacements: Option<Vec<[f64; 2]>>,
    /// Written by `simulate --dump-state`: the needle nodes as the simulator saw them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub needle_nodes: Option<serde_json::Value>,
}

/// `nodes`, with errors that name the node. serde_json alone reports a coordinate such as 1e999
/// (beyond the range of f64, the only way JSON can spell an infinite value) as a bare
/// "number out of range".
fn node_coordinates<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<[f64; 2]>, D::Error> {
    struct Nodes;
    impl<'de> Visitor<'de> for Nodes {
        type Value = Vec<[f64; 2]>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a list of [x, y] node coordinates")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut nodes = Vec::new();
            loop {
                match seq.next_element::<[f64; 2]>() {
                    Ok(Some(xy)) => nodes.push(xy),
                    Ok(None) => return Ok(nodes),
                    Err(e) => {
                        // Keep serde_json's " at line L column C" last, where it parses it back from.
                        let msg = e.to_string();
                        let (what, at) =
                            msg.rsplit_once(" at line ").map_or((msg.as_str(), String::new()), |(w, a)| (w, format!(" at line {a}")));
                        let hint = if what.contains("out of range") {
                            ": coordinates must be finite numbers (JSON has no NaN or Infinity, and a number such as 1e999 overflows)"
                        } else {
                            ""
                        };
                        let i = nodes.len();
                        return Err(A::Error::custom(format!("node {i} (nodes[{i}]): {what}{hint}{at}")));
                    }
                }
            }
        }
    }
    deserializer.deserialize_seq(Nodes)
}

fn default_plane() -> String {
    "strain".to_owned()
}
fn one() -> f64 {
    1.0
}

/// A prescribed displacement in world components; a missing or null component is free.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Prescribed {
    pub node: i64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ux: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uy: Option<f64>,
}

/// A prescribed displacement in a frame rotated by `angle_rad`.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PrescribedLocal {
    pub node: i64,
    pub angle_rad: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ut: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub un: Option<f64>,
}

/// A material point's conditions: the frame components `ut`, `un` (frame rotated by
/// `angle_rad`) of the interpolated displacement $u(x) = \sum_k N_k(x) u_k$ prescribed where
/// given, and a world force `f` (N) applied at `x` (m, reference position).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PointCondition {
    pub x: [f64; 2],
    pub angle_rad: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ut: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub un: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f: Option<[f64; 2]>,
}

/// A nodal point force in world components.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Load {
    pub node: i64,
    #[serde(default)]
    pub fx: f64,
    #[serde(default)]
    pub fy: f64,
}

/// The result format of ../shared/validation.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ScenarioResult {
    pub name: String,
    pub n_nodes: usize,
    pub n_triangles: usize,
    pub n_dofs: usize,
    pub plane: String,
    pub thickness: f64,
    pub displacements: Vec<[f64; 2]>,
    pub reactions: Vec<Reaction>,
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub reactions_local: Vec<ReactionLocal>,
    pub reaction_sum: [f64; 2],
    pub strain_energy: f64,
    pub max_abs_displacement: f64,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub element_stresses_sxx_syy_sxy: Option<Vec<[f64; 3]>>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub compliance: Option<ComplianceBlock>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Reaction {
    pub node: usize,
    pub rx: Option<f64>,
    pub ry: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ReactionLocal {
    pub node: usize,
    pub angle_rad: f64,
    pub rt: Option<f64>,
    pub rn: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ComplianceBlock {
    pub working_nodes: Vec<usize>,
    pub dof_order: String,
    pub matrix: Vec<Vec<f64>>,
}

/// A node id from JSON: non-negative and below `n_nodes`.
fn node_id(v: i64, n_nodes: usize, what: &str) -> Result<usize> {
    if v < 0 || v as u64 >= n_nodes as u64 {
        bail!("{what} names node {v}, but the mesh has nodes 0..{} (ids are 0-based)", n_nodes.saturating_sub(1));
    }
    Ok(v as usize)
}

impl Scenario {
    /// Builds the mesh and materials, validating both.
    pub fn mesh_and_materials(&self, limits: &MeshLimits) -> Result<(Mesh, MaterialMap)> {
        let mut triangles = Vec::with_capacity(self.triangles.len());
        for (i, t) in self.triangles.iter().enumerate() {
            let mut tri = [0usize; 3];
            for k in 0..3 {
                if t[k] < 0 {
                    bail!("triangles[{i}] refers to node {}, but node ids are 0-based and non-negative", t[k]);
                }
                tri[k] = usize::try_from(t[k]).unwrap_or(usize::MAX);
            }
            triangles.push(tri);
        }
        let mesh = Mesh::new(self.nodes.clone(), triangles, limits).context("invalid mesh")?;
        let plane = match self.plane.as_str() {
            "strain" => PlaneModel::Strain { thickness_m: self.thickness },
            "stress" => PlaneModel::Stress { thickness_m: self.thickness },
            p => bail!("plane must be \"strain\" or \"stress\", found \"{p}\""),
        };
        let n_tri = mesh.n_triangles();
        let materials = if self.young_modulus_elem_pa.is_some() || self.nu_elem.is_some() {
            let e = self.young_modulus_elem_pa.clone().unwrap_or_else(|| vec![self.young_modulus_pa; n_tri]);
            let nu = self.nu_elem.clone().unwrap_or_else(|| vec![self.nu; n_tri]);
            if e.len() != n_tri {
                bail!("E_elem has {} entries but there are {n_tri} triangles", e.len());
            }
            if nu.len() != n_tri {
                bail!("nu_elem has {} entries but there are {n_tri} triangles", nu.len());
            }
            let per = e.iter().zip(&nu).map(|(&e, &nu)| Material { young_modulus_pa: e, poisson_ratio: nu }).collect();
            MaterialMap::per_element(&mesh, per, plane).context("invalid material")?
        } else {
            let m = Material { young_modulus_pa: self.young_modulus_pa, poisson_ratio: self.nu };
            MaterialMap::per_region(&mesh, &[m], plane).context("invalid material")?
        };
        Ok((mesh, materials))
    }

    /// The static problem: fixed nodes, prescribed (world entries for one node merge) and loads.
    ///
    /// Errors: a node id out of range (naming the list), or material `points` /
    /// `working_points`, which only the reference solver (fem_ref.py) takes.
    pub fn static_problem(&self, n_nodes: usize) -> Result<StaticProblem> {
        if !self.points.is_empty() || self.working_points.is_some() {
            bail!(
                "the scenario has conditions at material points ({} `points`{}): solve it with the reference solver (fem_ref.py); this solver takes node conditions only",
                self.points.len(),
                if self.working_points.is_some() { ", `working_points`" } else { "" }
            );
        }
        let mut conditions = Vec::new();
        for &n in &self.fixed_nodes {
            conditions.push((node_id(n, n_nodes, "fixed_nodes")?, NodeCondition::Fixed));
        }
        let mut world: BTreeMap<usize, (Option<f64>, Option<f64>)> = BTreeMap::new();
        for p in &self.prescribed {
            let n = node_id(p.node, n_nodes, "prescribed")?;
            let e = world.entry(n).or_default();
            if p.ux.is_some() {
                e.0 = p.ux;
            }
            if p.uy.is_some() {
                e.1 = p.uy;
            }
        }
        for (n, (ux_m, uy_m)) in world {
            conditions.push((n, NodeCondition::World { u_m: [ux_m, uy_m] }));
        }
        for p in &self.prescribed_local {
            let n = node_id(p.node, n_nodes, "prescribed_local")?;
            conditions.push((n, NodeCondition::Local { frame: p.angle_rad, u_m: [p.ut, p.un] }));
        }
        let mut loads_n = Vec::new();
        for l in &self.loads {
            loads_n.push((node_id(l.node, n_nodes, "loads")?, [l.fx, l.fy]));
        }
        Ok(StaticProblem { conditions, loads_n, points: vec![], patches: vec![] })
    }
}

/// A 2D or a 3D scenario.
#[derive(Debug, Clone)]
pub enum AnyScenario {
    /// No `dim` key (or `"dim": 2`): the 2D format.
    Dim2(Scenario),
    /// `"dim": 3`: the 3D format.
    Dim3(crate::exchange3d::Scenario3),
}

/// The result of [`solve_any`], serialised as the 2D or the 3D result format.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum AnyResult {
    Dim2(ScenarioResult),
    Dim3(crate::exchange3d::ScenarioResult3),
}

impl AnyResult {
    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        match self {
            AnyResult::Dim2(r) => r.n_nodes,
            AnyResult::Dim3(r) => r.n_nodes,
        }
    }
    /// Strain energy in J.
    pub fn strain_energy(&self) -> f64 {
        match self {
            AnyResult::Dim2(r) => r.strain_energy,
            AnyResult::Dim3(r) => r.strain_energy,
        }
    }
    /// Largest displacement component in m.
    pub fn max_abs_displacement(&self) -> f64 {
        match self {
            AnyResult::Dim2(r) => r.max_abs_displacement,
            AnyResult::Dim3(r) => r.max_abs_displacement,
        }
    }
}

/// Parses a scenario of either dimension: the `dim` key decides (absent or 2: 2D, 3: 3D; any
/// other value is an error). The 2D path without `dim` is exactly [`Scenario`]'s parser.
pub fn parse_any_scenario(text: &str) -> Result<AnyScenario> {
    #[derive(Deserialize)]
    struct Probe {
        #[serde(default)]
        dim: Option<serde_json::Value>,
    }
    let probe: Probe = serde_json::from_str(text)?;
    match probe.dim {
        None => Ok(AnyScenario::Dim2(serde_json::from_str(text)?)),
        Some(d) if d.as_u64() == Some(2) => {
            let mut v: serde_json::Value = serde_json::from_str(text)?;
            if let Some(o) = v.as_object_mut() {
                o.remove("dim");
            }
            Ok(AnyScenario::Dim2(serde_json::from_value(v)?))
        }
        Some(d) if d.as_u64() == Some(3) => Ok(AnyScenario::Dim3(serde_json::from_str(text)?)),
        Some(d) => bail!("dim must be 2 or 3, found {d}"),
    }
}

/// Solves a scenario of either dimension as the `solve` command does; the 3D mesh limits are
/// [`needlesim_core::d3::TetMeshLimits::from_2d`] of `limits`.
pub fn solve_any(sc: &AnyScenario, limits: &MeshLimits) -> Result<AnyResult> {
    match sc {
        AnyScenario::Dim2(s) => solve_scenario(s, limits).map(AnyResult::Dim2),
        AnyScenario::Dim3(s) => {
            crate::exchange3d::solve_scenario3(s, &needlesim_core::d3::TetMeshLimits::from_2d(limits)).map(AnyResult::Dim3)
        }
    }
}

/// Solves a scenario as the `solve` command does.
pub fn solve_scenario(sc: &Scenario, limits: &MeshLimits) -> Result<ScenarioResult> {
    let (mesh, materials) = sc.mesh_and_materials(limits)?;
    let problem = sc.static_problem(mesh.n_nodes())?;
    let sol = problem.solve(&mesh, &materials).context("static solve failed")?;
    let displacements: Vec<[f64; 2]> = sol.displacement_m.chunks(2).map(|c| [c[0], c[1]]).collect();
    let reactions: Vec<Reaction> = sol.reactions_n.iter().map(|&(node, [rx, ry])| Reaction { node, rx, ry }).collect();
    let reaction_sum = [reactions.iter().filter_map(|r| r.rx).sum::<f64>(), reactions.iter().filter_map(|r| r.ry).sum::<f64>()];
    let element_stresses_sxx_syy_sxy = sc.output_stresses.then(|| sol.element_stresses_pa(&mesh, &materials));
    let compliance = match &sc.working_nodes {
        Some(w) if !w.is_empty() => Some(compliance_block(sc, w, mesh.clone(), materials.clone())?),
        _ => None,
    };
    let result = ScenarioResult {
        name: sc.name.clone().unwrap_or_default(),
        n_nodes: mesh.n_nodes(),
        n_triangles: mesh.n_triangles(),
        n_dofs: 2 * mesh.n_nodes(),
        plane: sc.plane.clone(),
        thickness: sc.thickness,
        max_abs_displacement: sol.displacement_m.iter().fold(0.0, |m, v| m.max(v.abs())),
        displacements,
        reactions,
        reactions_local: sol
            .reactions_local_n
            .iter()
            .map(|&(node, angle_rad, [rt, rn])| ReactionLocal { node, angle_rad, rt, rn })
            .collect(),
        reaction_sum,
        strain_energy: sol.strain_energy_j,
        element_stresses_sxx_syy_sxy,
        compliance,
    };
    if let Some(what) = first_non_finite(&result) {
        bail!(
            "{what} is not finite: a prescribed displacement, a load or a material value is too large for the solve \
             (it overflows the range of f64)"
        );
    }
    Ok(result)
}

/// The first value of a result that is not finite, named (inputs near the range of f64, such as a
/// prescribed displacement of 1e308 m, overflow in the solve).
fn first_non_finite(r: &ScenarioResult) -> Option<String> {
    let all_finite = |v: &[Option<f64>]| v.iter().flatten().all(|x| x.is_finite());
    if let Some(i) = r.displacements.iter().position(|d| !all_finite(&[Some(d[0]), Some(d[1])])) {
        return Some(format!("the displacement of node {i}"));
    }
    if let Some(x) = r.reactions.iter().find(|x| !all_finite(&[x.rx, x.ry])) {
        return Some(format!("the reaction at node {}", x.node));
    }
    if let Some(x) = r.reactions_local.iter().find(|x| !all_finite(&[x.rt, x.rn])) {
        return Some(format!("the local reaction at node {}", x.node));
    }
    if !r.strain_energy.is_finite() {
        return Some("the strain energy".to_owned());
    }
    if let Some(i) = r.element_stresses_sxx_syy_sxy.iter().flatten().position(|s| !s.iter().all(|x| x.is_finite())) {
        return Some(format!("the stress of triangle {i}"));
    }
    if r.compliance.iter().flat_map(|c| c.matrix.iter().flatten()).any(|x| !x.is_finite()) {
        return Some("the compliance block".to_owned());
    }
    None
}

/// $C = K_{ff}^{-1}$ restricted to the working nodes, where only `fixed_nodes` are removed.
fn compliance_block(sc: &Scenario, working: &[i64], mesh: Mesh, materials: MaterialMap) -> Result<ComplianceBlock> {
    let n_nodes = mesh.n_nodes();
    let fixed = sc.fixed_nodes.iter().map(|&n| node_id(n, n_nodes, "fixed_nodes")).collect::<Result<Vec<_>>>()?;
    let nodes = working.iter().map(|&n| node_id(n, n_nodes, "working_nodes")).collect::<Result<Vec<_>>>()?;
    if let Some(n) = nodes.iter().enumerate().find_map(|(i, n)| nodes[..i].contains(n).then_some(*n)) {
        bail!("working_nodes lists node {n} twice");
    }
    let model = TissueModel::new(mesh, materials, &fixed).context("the compliance needs fixed_nodes that hold the tissue")?;
    if let Some(&n) = nodes.iter().find(|&&n| model.is_fixed(n)) {
        bail!("working_nodes names node {n}, which is fixed: its compliance is zero");
    }
    let mut cache = ComplianceCache::new(n_nodes);
    let mut scratch = model.column_scratch();
    for &n in &nodes {
        cache.ensure(&model, n, &mut scratch)?;
    }
    let d = 2 * nodes.len();
    let mut c = vec![0.0; d * d];
    cache.working_block_into(&nodes, &mut c).expect("all columns cached above");
    Ok(ComplianceBlock {
        working_nodes: nodes,
        dof_order: "[ux(w0), uy(w0), ux(w1), uy(w1), ...]".to_owned(),
        matrix: c.chunks(d).map(<[f64]>::to_vec).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by the fuzzer (issue 13): a prescribed displacement of 1e308 m solved to NaN and
    /// infinite values, returned as a result (written as nulls) instead of an error.
    #[test]
    fn issue_13_an_overflowing_solve_is_an_error() {
        let text = r#"{"nodes": [[0, 0], [1, 0], [1, 1], [0, 1]], "triangles": [[0, 1, 2], [0, 2, 3]], "E": 1000, "nu": 0.3,
            "fixed_nodes": [0, 1], "prescribed": [{"node": 2, "uy": 1e308}]}"#;
        let sc: Scenario = serde_json::from_str(text).unwrap();
        let e = solve_scenario(&sc, &MeshLimits::default()).unwrap_err().to_string();
        assert!(e.contains("is not finite") && e.contains("too large"), "{e}");
        // The same problem with a displacement in range solves.
        let sc: Scenario = serde_json::from_str(&text.replace("1e308", "1e-3")).unwrap();
        let r = solve_scenario(&sc, &MeshLimits::default()).unwrap();
        assert!(first_non_finite(&r).is_none() && r.max_abs_displacement >= 1e-3);
    }
}
