//! The 3D static-problem exchange format of ../shared/validation (README "3D scenario format",
//! `"dim": 3`, and "3D result format"), and its conversion to and from the core's `d3` types.

use std::collections::BTreeMap;

use anyhow::{Context, Result, bail};
use needlesim_core::Dim3;
use needlesim_core::Material;
use needlesim_core::d3::disc::{Disc, DiscWeights, disc_weights_into};
use needlesim_core::d3::{
    PointCondition, TetLocator, TetMaterials, TetMesh, TetMeshLimits, TetNodeCondition, TetStaticProblem, TetTissueModel,
};
use needlesim_core::sim3::{PointState3, Snapshot3};
use needlesim_core::statics::PatchCondition;
use serde::{Deserialize, Serialize};

/// A 3D static problem. Node ids are 0-based; tetrahedra may have either orientation.
#[derive(Debug, Clone, Deserialize, Serialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Scenario3 {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Must be 3.
    pub dim: u8,
    pub nodes: Vec<[f64; 3]>,
    pub tetrahedra: Vec<[i64; 4]>,
    #[serde(rename = "E")]
    pub young_modulus_pa: f64,
    pub nu: f64,
    #[serde(rename = "E_elem", default, skip_serializing_if = "Option::is_none")]
    pub young_modulus_elem_pa: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu_elem: Option<Vec<f64>>,
    #[serde(default)]
    pub fixed_nodes: Vec<i64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub prescribed: Vec<Prescribed3>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub prescribed_local: Vec<PrescribedLocal3>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<Load3>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<Point3>,
    /// Contacts spread over the tissue with explicit weights (after the points).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub patches: Vec<Patch3>,
    /// Contacts spread over discs across the needle (after the patches): weights computed here.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub discs: Vec<Disc3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub working_nodes: Option<Vec<i64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub working_points: Option<Vec<[f64; 3]>>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub output_stresses: bool,
    /// A dumped simulation state (`simulate --dump-state`): each of `points` with the
    /// simulation's state and answer there. Ignored by the solvers.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub needle_points: Option<Vec<NeedlePoint3>>,
    /// A dumped simulation state: the simulation's own answer to this problem in the 3D result
    /// format (compare it with the reference's by compare.py). Ignored by the solvers.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulation_result: Option<Box<ScenarioResult3>>,
}

/// One needle contact of a dumped simulation state, in the order of `points`, then `patches`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NeedlePoint3 {
    /// `stuck`, `slipping` or `tip`.
    pub state: String,
    /// The simulation's total force of the needle on the tissue there (constraint plus `f`),
    /// world, N.
    pub force: [f64; 3],
    /// The simulation's displacement there, world, m.
    pub u: [f64; 3],
    /// A patch's disc (a contact spread over the needle's cross-section): the same contact as a
    /// `discs` entry would give it, to check its weights against another quadrature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub disc: Option<NeedleDisc3>,
}

/// The disc of a dumped patch: centre `x` (m, reference), unit `axis` (the needle's tangent when
/// the contact was taken), `radius` (m), as in `discs`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NeedleDisc3 {
    pub x: [f64; 3],
    pub axis: [f64; 3],
    pub radius: f64,
}

/// Prescribed world components; a missing or null component is free.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Prescribed3 {
    pub node: i64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ux: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uy: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uz: Option<f64>,
}

/// Components prescribed in a node frame `[t, n, b]` (orthonormal rows).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PrescribedLocal3 {
    pub node: i64,
    pub frame: [[f64; 3]; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ut: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub un: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ub: Option<f64>,
}

/// A nodal force in world components, N.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Load3 {
    pub node: i64,
    #[serde(default)]
    pub fx: f64,
    #[serde(default)]
    pub fy: f64,
    #[serde(default)]
    pub fz: f64,
}

/// A material point at reference position `x` (m): frame components of $u(x)$ prescribed where
/// given, and a world force `f` (N) applied at it.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Point3 {
    pub x: [f64; 3],
    pub frame: [[f64; 3]; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ut: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub un: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ub: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f: Option<[f64; 3]>,
}

/// A contact spread over the tissue: frame components of the weighted node sum
/// $u_p = \sum_k w_k u_k$ prescribed where given, and a world force `f` (N) acting as the nodal
/// loads $w_k f$.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Patch3 {
    pub nodes: Vec<i64>,
    pub weights: Vec<f64>,
    pub frame: [[f64; 3]; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ut: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub un: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ub: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f: Option<[f64; 3]>,
}

/// A patch over the disc of `radius` (m) centred at `x` across `axis`: its weights are the shape
/// functions averaged over the disc (`needlesim_core::d3::disc`, exact).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Disc3 {
    pub x: [f64; 3],
    pub axis: [f64; 3],
    pub radius: f64,
    pub frame: [[f64; 3]; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ut: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub un: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ub: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub f: Option<[f64; 3]>,
}

/// The weights a disc was given.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct DiscWeights3 {
    pub disc: usize,
    pub nodes: Vec<usize>,
    pub weights: Vec<f64>,
}

/// The 3D result format.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ScenarioResult3 {
    pub name: String,
    pub dim: u8,
    pub n_nodes: usize,
    pub n_tetrahedra: usize,
    pub displacements: Vec<[f64; 3]>,
    pub reactions: Vec<Reaction3>,
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub reactions_local: Vec<ReactionLocal3>,
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub point_reactions: Vec<PointReaction3>,
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub disc_weights: Vec<DiscWeights3>,
    pub strain_energy: f64,
    pub max_abs_displacement: f64,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub element_stresses_voigt: Option<Vec<[f64; 6]>>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub compliance: Option<NodeCompliance3>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub point_compliance: Option<PointCompliance3>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Reaction3 {
    pub node: usize,
    pub rx: Option<f64>,
    pub ry: Option<f64>,
    pub rz: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ReactionLocal3 {
    pub node: usize,
    pub rt: Option<f64>,
    pub rn: Option<f64>,
    pub rb: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PointReaction3 {
    /// The index among points, then patches, then discs.
    pub point: usize,
    /// `point`, `patch` or `disc`.
    #[serde(default = "point_kind")]
    pub kind: String,
    /// The index in its own list.
    #[serde(default)]
    pub index: usize,
    pub rx: f64,
    pub ry: f64,
    pub rz: f64,
    pub rt: Option<f64>,
    pub rn: Option<f64>,
    pub rb: Option<f64>,
    pub u: [f64; 3],
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct NodeCompliance3 {
    pub working_nodes: Vec<usize>,
    pub dof_order: String,
    pub matrix: Vec<Vec<f64>>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PointCompliance3 {
    pub working_points: Vec<[f64; 3]>,
    pub dof_order: String,
    pub matrix: Vec<Vec<f64>>,
}

fn point_kind() -> String {
    "point".to_owned()
}

/// A node id from JSON: non-negative and below `n_nodes`; `what` names the key and index.
fn node_id(v: i64, n_nodes: usize, what: &str) -> Result<usize> {
    if v < 0 || v as u64 >= n_nodes as u64 {
        bail!("{what} names node {v}, but the mesh has nodes 0..{} (ids are 0-based)", n_nodes.saturating_sub(1));
    }
    Ok(v as usize)
}

impl Scenario3 {
    /// Builds the mesh and materials, validating both. Errors name the key and index.
    pub fn mesh_and_materials(&self, limits: &TetMeshLimits) -> Result<(TetMesh, TetMaterials)> {
        if self.dim != 3 {
            bail!("dim must be 3 for a scenario with tetrahedra, found {}", self.dim);
        }
        let mut tets = Vec::with_capacity(self.tetrahedra.len());
        for (i, t) in self.tetrahedra.iter().enumerate() {
            let mut tet = [0usize; 4];
            for k in 0..4 {
                if t[k] < 0 {
                    bail!("tetrahedra[{i}] refers to node {}, but node ids are 0-based and non-negative", t[k]);
                }
                tet[k] = usize::try_from(t[k]).unwrap_or(usize::MAX);
            }
            tets.push(tet);
        }
        let mesh = TetMesh::new(self.nodes.clone(), tets, limits).context("invalid mesh")?;
        let n = mesh.n_tets();
        let materials = if self.young_modulus_elem_pa.is_some() || self.nu_elem.is_some() {
            let e = self.young_modulus_elem_pa.clone().unwrap_or_else(|| vec![self.young_modulus_pa; n]);
            let nu = self.nu_elem.clone().unwrap_or_else(|| vec![self.nu; n]);
            if e.len() != n {
                bail!("E_elem has {} entries but there are {n} tetrahedra", e.len());
            }
            if nu.len() != n {
                bail!("nu_elem has {} entries but there are {n} tetrahedra", nu.len());
            }
            let per = e.iter().zip(&nu).map(|(&e, &nu)| Material { young_modulus_pa: e, poisson_ratio: nu }).collect();
            TetMaterials::per_element(&mesh, per).context("invalid material (E_elem / nu_elem)")?
        } else {
            let m = Material { young_modulus_pa: self.young_modulus_pa, poisson_ratio: self.nu };
            TetMaterials::per_region(&mesh, &[m]).context("invalid material (E / nu)")?
        };
        Ok((mesh, materials))
    }

    /// The static problem: fixed nodes, prescribed (world entries for one node merge),
    /// prescribed_local, loads and points. Errors name the key and index.
    pub fn static_problem(&self, n_nodes: usize) -> Result<TetStaticProblem> {
        let mut conditions = Vec::new();
        for (i, &n) in self.fixed_nodes.iter().enumerate() {
            conditions.push((node_id(n, n_nodes, &format!("fixed_nodes[{i}]"))?, TetNodeCondition::Fixed));
        }
        let mut world: BTreeMap<usize, [Option<f64>; 3]> = BTreeMap::new();
        for (i, p) in self.prescribed.iter().enumerate() {
            let n = node_id(p.node, n_nodes, &format!("prescribed[{i}]"))?;
            let e = world.entry(n).or_default();
            for (a, v) in [p.ux, p.uy, p.uz].into_iter().enumerate() {
                if v.is_some() {
                    e[a] = v;
                }
            }
        }
        for (n, u_m) in world {
            if u_m.iter().any(Option::is_some) {
                conditions.push((n, TetNodeCondition::World { u_m }));
            }
        }
        for (i, p) in self.prescribed_local.iter().enumerate() {
            let n = node_id(p.node, n_nodes, &format!("prescribed_local[{i}]"))?;
            conditions.push((n, TetNodeCondition::Local { frame: p.frame, u_m: [p.ut, p.un, p.ub] }));
        }
        let mut loads_n = Vec::new();
        for (i, l) in self.loads.iter().enumerate() {
            loads_n.push((node_id(l.node, n_nodes, &format!("loads[{i}]"))?, [l.fx, l.fy, l.fz]));
        }
        let points = self
            .points
            .iter()
            .map(|p| PointCondition { x_m: p.x, frame: p.frame, u_m: [p.ut, p.un, p.ub], force_n: p.f.unwrap_or([0.0; 3]) })
            .collect();
        let patches = self
            .patches
            .iter()
            .enumerate()
            .map(|(j, p)| {
                let nodes = p
                    .nodes
                    .iter()
                    .enumerate()
                    .map(|(k, &v)| node_id(v, n_nodes, &format!("patches[{j}].nodes[{k}]")))
                    .collect::<Result<Vec<_>>>()?;
                Ok(PatchCondition {
                    nodes,
                    weights: p.weights.clone(),
                    frame: p.frame,
                    u_m: [p.ut, p.un, p.ub],
                    force_n: p.f.unwrap_or([0.0; 3]),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(TetStaticProblem { conditions, loads_n, points, patches })
    }

    /// The `discs` as patches on `mesh`, with the weights they were given. Errors name the disc.
    pub fn disc_patches(&self, mesh: &TetMesh) -> Result<(Vec<PatchCondition<Dim3>>, Vec<DiscWeights3>)> {
        if self.discs.is_empty() {
            return Ok((Vec::new(), Vec::new()));
        }
        let locator = TetLocator::new(mesh);
        let mut w = DiscWeights::with_capacity(mesh.n_nodes());
        let mut patches = Vec::with_capacity(self.discs.len());
        let mut weights = Vec::with_capacity(self.discs.len());
        for (j, d) in self.discs.iter().enumerate() {
            disc_weights_into(mesh, &locator, &Disc { centre_m: d.x, axis: d.axis, radius_m: d.radius }, &mut w)
                .with_context(|| format!("discs[{j}]"))?;
            patches.push(PatchCondition {
                nodes: w.nodes().to_vec(),
                weights: w.weights().to_vec(),
                frame: d.frame,
                u_m: [d.ut, d.un, d.ub],
                force_n: d.f.unwrap_or([0.0; 3]),
            });
            weights.push(DiscWeights3 { disc: j, nodes: w.nodes().to_vec(), weights: w.weights().to_vec() });
        }
        Ok((patches, weights))
    }
}

/// Solves a 3D scenario as the `solve` command does.
pub fn solve_scenario3(sc: &Scenario3, limits: &TetMeshLimits) -> Result<ScenarioResult3> {
    let (mesh, materials) = sc.mesh_and_materials(limits)?;
    let mut problem = sc.static_problem(mesh.n_nodes())?;
    let (disc_patches, disc_weights) = sc.disc_patches(&mesh)?;
    problem.patches.extend(disc_patches);
    let sol = problem.solve(&mesh, &materials).context("static solve failed")?;
    let displacements: Vec<[f64; 3]> = sol.displacement_m.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let reactions = sol.reactions_n.iter().map(|&(node, [rx, ry, rz])| Reaction3 { node, rx, ry, rz }).collect();
    let reactions_local = sol.reactions_local_n.iter().map(|&(node, _, [rt, rn, rb])| ReactionLocal3 { node, rt, rn, rb }).collect();
    let n_patches = sc.patches.len();
    let point_reactions = sol
        .point_reactions
        .iter()
        .map(|r| (r.force_n, r.local_n, r.u_m))
        .chain(sol.patch_reactions.iter().map(|r| (r.force_n, r.local_n, r.u_m)))
        .enumerate()
        .map(|(point, (f, l, u))| {
            let (kind, index) = match point.checked_sub(sc.points.len()) {
                None => ("point", point),
                Some(j) if j < n_patches => ("patch", j),
                Some(j) => ("disc", j - n_patches),
            };
            PointReaction3 { point, kind: kind.to_owned(), index, rx: f[0], ry: f[1], rz: f[2], rt: l[0], rn: l[1], rb: l[2], u }
        })
        .collect();
    let element_stresses_voigt = sc.output_stresses.then(|| sol.element_stresses_pa(&mesh, &materials));
    let working_nodes = sc.working_nodes.as_deref().filter(|w| !w.is_empty());
    let working_points = sc.working_points.as_deref().filter(|w| !w.is_empty());
    let (mut compliance, mut point_compliance) = (None, None);
    if working_nodes.is_some() || working_points.is_some() {
        let n_nodes = mesh.n_nodes();
        let fixed = sc
            .fixed_nodes
            .iter()
            .enumerate()
            .map(|(i, &n)| node_id(n, n_nodes, &format!("fixed_nodes[{i}]")))
            .collect::<Result<Vec<_>>>()?;
        let model = TetTissueModel::new(mesh.clone(), materials.clone(), &fixed)
            .context("the compliance needs fixed_nodes that hold the tissue")?;
        let square = |w: Vec<f64>, d: usize| w.chunks(d).map(<[f64]>::to_vec).collect::<Vec<_>>();
        if let Some(w) = working_nodes {
            let nodes =
                w.iter().enumerate().map(|(i, &n)| node_id(n, n_nodes, &format!("working_nodes[{i}]"))).collect::<Result<Vec<_>>>()?;
            let c = model.node_compliance(&nodes)?;
            compliance = Some(NodeCompliance3 {
                dof_order: "[ux(w0), uy(w0), uz(w0), ux(w1), ...]".to_owned(),
                matrix: square(c, 3 * nodes.len()),
                working_nodes: nodes,
            });
        }
        if let Some(x) = working_points {
            let w = model.point_compliance_at(x)?;
            point_compliance = Some(PointCompliance3 {
                working_points: x.to_vec(),
                dof_order: "[ux(p0), uy(p0), uz(p0), ux(p1), ...]".to_owned(),
                matrix: square(w, 3 * x.len()),
            });
        }
    }
    let result = ScenarioResult3 {
        name: sc.name.clone().unwrap_or_default(),
        dim: 3,
        n_nodes: mesh.n_nodes(),
        n_tetrahedra: mesh.n_tets(),
        max_abs_displacement: sol.displacement_m.iter().fold(0.0, |m, v| m.max(v.abs())),
        displacements,
        reactions,
        reactions_local,
        point_reactions,
        disc_weights,
        strain_energy: sol.strain_energy_j,
        element_stresses_voigt,
        compliance,
        point_compliance,
    };
    if let Some(what) = first_non_finite(&result) {
        bail!(
            "{what} is not finite: a prescribed displacement, a load or a material value is too large for the solve \
             (it overflows the range of f64)"
        );
    }
    Ok(result)
}

/// The name of a point state in dumped states (`needle_points[].state`).
pub fn point_state_name(s: PointState3) -> &'static str {
    match s {
        PointState3::Stuck => "stuck",
        PointState3::Slipping => "slipping",
        PointState3::Tip => "tip",
    }
}

/// The order in which a snapshot's contacts are written ([`scenario_from_snapshot`]): the
/// material points, then the discs (`patches`), each in the snapshot's order; the reference's
/// `point_reactions` come in this order.
pub fn dump_order(snap: &Snapshot3) -> Vec<usize> {
    let is_disc = |k: &usize| snap.points[*k].contact.is_disc();
    let n = snap.points.len();
    (0..n).filter(|k| !is_disc(k)).chain((0..n).filter(is_disc)).collect()
}

/// The static problem a 3D simulation tick solved ([`Snapshot3`], from
/// `Simulation3::snapshot`) as a scenario on the simulation's tissue `model`: its nodes and
/// tetrahedra, materials (`E`, `nu`, and `E_elem`, `nu_elem` when the tetrahedra differ), its
/// fixed nodes, and one entry per needle contact: a material point as a `points` entry
/// (reference position `x`), a contact spread over a disc (`[needle] spread_contact`) as a
/// `patches` entry (its nodes and weights as the simulation holds them), each with its frame
/// rows `[t, n, b]`, the prescribed components (`ut` for a stuck point or the tip's, `un`, `ub`
/// always) and the friction `f` (world, N) of a slipping one. The simulation's state and
/// answer at each contact go to `needle_points` (in the order of `points`, then `patches`:
/// [`dump_order`]; a patch's with its disc) when `states` is given (one per contact, in the
/// snapshot's order). `working_points`, `output_stresses` and `simulation_result` are left for
/// the caller.
pub fn scenario_from_snapshot(model: &TetTissueModel, snap: &Snapshot3, states: Option<&[PointState3]>, name: &str) -> Scenario3 {
    let order = dump_order(snap);
    let mesh = model.mesh();
    let mats = model.materials().material_of_tet();
    let uniform = mats.windows(2).all(|w| w[0] == w[1]);
    let first = mats.first().copied().unwrap_or(Material { young_modulus_pa: 0.0, poisson_ratio: 0.0 });
    Scenario3 {
        name: Some(name.to_owned()),
        description: Some(format!("a 3D needle simulation's static problem at tick {}", snap.tick)),
        dim: 3,
        nodes: mesh.nodes_m().to_vec(),
        tetrahedra: mesh.tets().iter().map(|t| t.map(|i| i as i64)).collect(),
        young_modulus_pa: first.young_modulus_pa,
        nu: first.poisson_ratio,
        young_modulus_elem_pa: (!uniform).then(|| mats.iter().map(|m| m.young_modulus_pa).collect()),
        nu_elem: (!uniform).then(|| mats.iter().map(|m| m.poisson_ratio).collect()),
        fixed_nodes: (0..mesh.n_nodes()).filter(|&n| model.is_fixed(n)).map(|n| n as i64).collect(),
        points: snap
            .points
            .iter()
            .filter(|p| !p.contact.is_disc())
            .map(|p| Point3 { x: p.x_m, frame: p.frame, ut: p.ut, un: p.un, ub: p.ub, f: p.f_n })
            .collect(),
        patches: snap
            .points
            .iter()
            .filter(|p| p.contact.is_disc())
            .map(|p| Patch3 {
                nodes: p.contact.nodes().iter().map(|n| n.index() as i64).collect(),
                weights: p.contact.terms().map(|(_, w)| w).collect(),
                frame: p.frame,
                ut: p.ut,
                un: p.un,
                ub: p.ub,
                f: p.f_n,
            })
            .collect(),
        needle_points: states.map(|st| {
            order
                .iter()
                .map(|&k| {
                    let p = &snap.points[k];
                    NeedlePoint3 {
                        state: point_state_name(st[k]).to_owned(),
                        force: p.force_n,
                        u: p.u_m,
                        disc: p.disc.map(|d| {
                            let n = d.axis.iter().map(|v| v * v).sum::<f64>().sqrt();
                            NeedleDisc3 { x: d.centre_m, axis: d.axis.map(|v| v / n), radius: d.radius_m }
                        }),
                    }
                })
                .collect()
        }),
        ..Scenario3::default()
    }
}

/// The first value of a 3D result that is not finite, named.
fn first_non_finite(r: &ScenarioResult3) -> Option<String> {
    let fin = |v: &[Option<f64>]| v.iter().flatten().all(|x| x.is_finite());
    if let Some(i) = r.displacements.iter().position(|d| !d.iter().all(|x| x.is_finite())) {
        return Some(format!("the displacement of node {i}"));
    }
    if let Some(x) = r.reactions.iter().find(|x| !fin(&[x.rx, x.ry, x.rz])) {
        return Some(format!("the reaction at node {}", x.node));
    }
    if let Some(x) = r.point_reactions.iter().find(|x| !fin(&[Some(x.rx), Some(x.ry), Some(x.rz), x.rt, x.rn, x.rb])) {
        return Some(format!("the reaction of point {}", x.point));
    }
    if !r.strain_energy.is_finite() {
        return Some("the strain energy".to_owned());
    }
    if let Some(i) = r.element_stresses_voigt.iter().flatten().position(|s| !s.iter().all(|x| x.is_finite())) {
        return Some(format!("the stress of tetrahedron {i}"));
    }
    if r.compliance
        .iter()
        .flat_map(|c| c.matrix.iter().flatten())
        .chain(r.point_compliance.iter().flat_map(|c| c.matrix.iter().flatten()))
        .any(|x| !x.is_finite())
    {
        return Some("the compliance block".to_owned());
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_TETS: &str = r#"{"dim": 3, "nodes": [[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,1,1]], "tetrahedra": [[0,2,1,3],[1,2,3,4]],
        "E": 1000, "nu": 0.3, "fixed_nodes": [0, 1, 2], "loads": [{"node": 4, "fz": 0.5}], "working_nodes": [3, 4],
        "points": [{"x": [0.5, 0.5, 0.6], "frame": [[0,0,1],[1,0,0],[0,1,0]], "un": 0.001, "f": [0, 0, 0.1]}],
        "working_points": [[0.5, 0.5, 0.6]], "output_stresses": true}"#;

    #[test]
    fn a_small_scenario_solves_with_every_key() {
        let sc: Scenario3 = serde_json::from_str(TWO_TETS).unwrap();
        let r = solve_scenario3(&sc, &TetMeshLimits::default()).unwrap();
        assert_eq!((r.n_nodes, r.n_tetrahedra, r.dim), (5, 2, 3));
        assert_eq!(r.reactions.iter().map(|x| x.node).collect::<Vec<_>>(), vec![0, 1, 2]);
        assert_eq!(r.point_reactions.len(), 1);
        let p = &r.point_reactions[0];
        assert!(p.rt.is_none() && p.rn.is_some() && p.rb.is_none());
        assert!((p.u[0] - 0.001).abs() < 1e-15, "the point holds its prescribed un = ux: {:?}", p.u);
        assert_eq!(r.compliance.as_ref().unwrap().matrix.len(), 6);
        assert_eq!(r.point_compliance.as_ref().unwrap().matrix.len(), 3);
        assert_eq!(r.element_stresses_voigt.as_ref().unwrap().len(), 2);
        // Force balance: supports + point constraint + loads.
        let fz: f64 = r.reactions.iter().filter_map(|x| x.rz).sum::<f64>() + p.rz + 0.5 + 0.1;
        assert!(fz.abs() < 1e-12, "{fz}");
    }

    #[test]
    fn bad_input_names_the_key_and_index() {
        let lim = TetMeshLimits::default();
        let solve = |text: &str| {
            let sc: Scenario3 = serde_json::from_str(text).unwrap();
            format!("{:#}", solve_scenario3(&sc, &lim).unwrap_err())
        };
        let e = solve(&TWO_TETS.replace("\"loads\": [{\"node\": 4", "\"loads\": [{\"node\": 9"));
        assert!(e.contains("loads[0] names node 9"), "{e}");
        let e = solve(&TWO_TETS.replace("[1,2,3,4]]", "[1,2,3,-4]]"));
        assert!(e.contains("tetrahedra[1] refers to node -4"), "{e}");
        let e = solve(&TWO_TETS.replace("[1,2,3,4]]", "[1,2,3,1]]"));
        assert!(e.contains("tetrahedron 1 uses node 1 twice"), "{e}");
        let e = solve(&TWO_TETS.replace("\"frame\": [[0,0,1]", "\"frame\": [[0,0,2]"));
        assert!(e.contains("point 0: the frame must be three orthonormal rows"), "{e}");
        let e = solve(&TWO_TETS.replace("\"working_points\": [[0.5, 0.5, 0.6]]", "\"working_points\": [[0.5, 0.5, 0.6], [2, 2, 2]]"));
        assert!(e.contains("working point 1: the point (2, 2, 2) m lies outside the mesh"), "{e}");
        let e = solve(&TWO_TETS.replace("\"nu\": 0.3", "\"nu\": 0.5"));
        assert!(e.contains("Poisson ratio"), "{e}");
        let e = serde_json::from_str::<Scenario3>(&TWO_TETS.replace("\"dim\": 3", "\"dim\": 3, \"plane\": \"strain\"")).unwrap_err();
        assert!(e.to_string().contains("unknown field `plane`"), "{e}");
    }

    /// A simulation's snapshot, converted, solved by the exchange solver: the point reactions
    /// plus the friction are the simulation's contact forces and the point displacements its
    /// displacements; the JSON round trip keeps the problem.
    #[test]
    fn a_snapshot_converts_to_the_problem_the_simulation_solved() {
        use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
        use needlesim_core::sim3::{BasePose3, Simulation3};
        let mut sim = Simulation3::new(box_phantom3(7), box_phantom3_params([0.0513, 0.0487, 0.1], 0.005)).unwrap();
        let start = sim.pose();
        for k in 1..=2500 {
            let p = start.position_m;
            sim.step(BasePose3::from_rotation([p[0], p[1], p[2] - 2e-5 * k as f64], start.orientation)).unwrap();
            sim.prefetch_columns(usize::MAX).unwrap();
        }
        let snap = sim.snapshot();
        let states: Vec<PointState3> = sim.output().contacts.iter().map(|c| c.state).collect();
        assert!(snap.points.len() >= 2, "the needle holds points: {states:?}");
        assert!(states.contains(&PointState3::Slipping), "{states:?}");
        let sc = scenario_from_snapshot(sim.model(), &snap, Some(&states), "snap");
        assert_eq!(sc.fixed_nodes.len(), 49, "the bottom face of a 7x7x7 grid");
        assert!(sc.young_modulus_elem_pa.is_none(), "one material");
        let back: Scenario3 = serde_json::from_str(&serde_json::to_string(&sc).unwrap()).unwrap();
        assert_eq!(back.needle_points, sc.needle_points);
        assert_eq!(back.points.len(), snap.points.len());
        let r = solve_scenario3(&back, &TetMeshLimits::default()).unwrap();
        let (mut ef, mut eu, mut sf, mut su) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for ((pr, p), np) in r.point_reactions.iter().zip(&snap.points).zip(back.needle_points.as_ref().unwrap()) {
            let f = p.f_n.unwrap_or([0.0; 3]);
            let total = [pr.rx + f[0], pr.ry + f[1], pr.rz + f[2]];
            for (k, t) in total.iter().enumerate() {
                ef = ef.max((t - np.force[k]).abs());
                eu = eu.max((pr.u[k] - np.u[k]).abs());
                sf = sf.max(np.force[k].abs());
                su = su.max(np.u[k].abs());
            }
        }
        assert!(sf > 0.0 && su > 0.0);
        assert!(ef / sf <= 1e-8, "point forces differ by {:e} relative", ef / sf);
        assert!(eu / su <= 1e-9, "point displacements differ by {:e} relative", eu / su);
    }
}
