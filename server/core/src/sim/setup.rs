//! What the simulation derives once from the mesh and the parameters and never changes (the
//! "symbolic" part, as faer would say): the spatial grid, boundary nodes, each node's region,
//! the targets' enclosing triangles, and the divergence bounds.

use crate::compliance::TissueModel;
use crate::mesh::Mesh;
use crate::spatial::NodeGrid;

use super::{DivergenceBounds, SimError, SimParams};
use crate::viscous::ViscCoeffs;

/// A target located in the mesh: the triangle containing its centre and the barycentric
/// weights of the centre in it (the target moves with the tissue as $\sum_k w_k (X_k + u_k)$).
#[derive(Debug, Clone)]
pub(super) struct LocatedTarget {
    pub nodes: [usize; 3],
    pub bary: [f64; 3],
    pub radius_m: f64,
}

/// The simulation's fixed set-up.
pub(super) struct Setup {
    /// Mesh nodes bucketed by the mean edge length, for the nodes near the tip.
    pub grid: NodeGrid,
    /// Whether each node lies on the mesh boundary (an edge used by one triangle only).
    pub is_boundary: Vec<bool>,
    /// Each node's region: the one covering most area around it.
    pub node_region: Vec<usize>,
    pub targets: Vec<LocatedTarget>,
    pub bounds: DivergenceBounds,
    /// The arc length of the tip, $L$.
    pub s_tip_m: f64,
    /// The triangles around each node (CSR: `node_tris[node_tri_start[j]..node_tri_start[j + 1]]`).
    pub node_tri_start: Vec<usize>,
    pub node_tris: Vec<usize>,
    /// Each triangle's diameter (its longest edge, m).
    pub tri_diam_m: Vec<f64>,
    /// The longest edge of the mesh (m): every node of a triangle a line crosses lies within it
    /// of the line.
    pub max_edge_m: f64,
    /// The viscous recursion's constants (`None`: elastic tissue; [`crate::viscous`]).
    pub visc: Option<ViscCoeffs>,
    /// The working solver's scale of every compliance block: $1/\gamma$, exactly 1 when elastic.
    pub compliance_scale: f64,
}

impl Setup {
    /// Derives the set-up of `params` (validated) in `model`.
    ///
    /// Errors: [`SimError::InvalidParams`] when a target lies outside the mesh.
    pub fn new(model: &TissueModel, params: &SimParams) -> Result<Self, SimError> {
        let mesh = model.mesh();
        let mut targets = Vec::with_capacity(params.targets.len());
        for t in &params.targets {
            let (nodes, bary) = locate(mesh, t.center_m)
                .ok_or_else(|| SimError::InvalidParams(format!("target '{}' at {:?} lies outside the mesh", t.name, t.center_m)))?;
            targets.push(LocatedTarget { nodes, bary, radius_m: t.radius_m });
        }
        let (is_boundary, mean_edge) = boundary_nodes(mesh);
        let (node_tri_start, node_tris) = node_triangles(mesh);
        let tri_diam_m: Vec<f64> = mesh
            .triangles()
            .iter()
            .map(|t| {
                let p = t.map(|i| mesh.nodes_m()[i]);
                (0..3).map(|k| (p[k][0] - p[(k + 1) % 3][0]).hypot(p[k][1] - p[(k + 1) % 3][1])).fold(0.0, f64::max)
            })
            .collect();
        let max_edge_m = tri_diam_m.iter().copied().fold(0.0, f64::max);
        let visc = ViscCoeffs::new(params.viscoelastic, params.tick_rate_hz);
        Ok(Self {
            visc,
            compliance_scale: visc.map_or(1.0, |c| c.compliance_scale()),
            node_tri_start,
            node_tris,
            tri_diam_m,
            max_edge_m,
            grid: NodeGrid::new(mesh.nodes_m(), mean_edge.max(1e-9)),
            is_boundary,
            node_region: node_regions(mesh),
            targets,
            bounds: DivergenceBounds::of(model, params),
            s_tip_m: params.needle.tip_s_m(),
        })
    }
}

impl Setup {
    /// The triangle containing `p` (m) and its barycentric weights, searched among the
    /// triangles around the grid's nodes within `reach_m` of `p` (no mesh scan; `candidates` is
    /// the caller's buffer). Points on an edge or a vertex belong to the first triangle found.
    /// `None` outside the mesh.
    pub fn locate_near(&self, mesh: &Mesh, p: [f64; 2], reach_m: f64, candidates: &mut Vec<usize>) -> Option<(usize, [f64; 3])> {
        candidates.clear();
        self.grid.query_into(p, reach_m, candidates);
        let mut best: Option<(usize, [f64; 3], f64)> = None;
        for &j in candidates.iter() {
            for &ti in &self.node_tris[self.node_tri_start[j]..self.node_tri_start[j + 1]] {
                let bary = barycentric(mesh, ti, p);
                let worst = bary[0].min(bary[1]).min(bary[2]);
                if best.as_ref().is_none_or(|b| worst > b.2) {
                    best = Some((ti, bary, worst));
                }
                if worst >= 0.0 {
                    return Some((ti, bary));
                }
            }
        }
        best.filter(|b| b.2 >= -1e-12).map(|b| (b.0, b.1))
    }
}

/// The barycentric weights of `p` in triangle `ti` (in the triangle's node order).
pub(super) fn barycentric(mesh: &Mesh, ti: usize, p: [f64; 2]) -> [f64; 3] {
    let [a, b, c] = mesh.triangles()[ti].map(|i| mesh.nodes_m()[i]);
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    let l1 = ((b[0] - p[0]) * (c[1] - p[1]) - (c[0] - p[0]) * (b[1] - p[1])) / det;
    let l2 = ((c[0] - p[0]) * (a[1] - p[1]) - (a[0] - p[0]) * (c[1] - p[1])) / det;
    [l1, l2, 1.0 - l1 - l2]
}

/// The triangles around each node, in CSR form (start offsets, triangle indices).
fn node_triangles(mesh: &Mesh) -> (Vec<usize>, Vec<usize>) {
    let mut start = vec![0usize; mesh.n_nodes() + 1];
    for t in mesh.triangles() {
        for &n in t {
            start[n + 1] += 1;
        }
    }
    for j in 0..mesh.n_nodes() {
        start[j + 1] += start[j];
    }
    let mut fill = start.clone();
    let mut tris = vec![0usize; start[mesh.n_nodes()]];
    for (ti, t) in mesh.triangles().iter().enumerate() {
        for &n in t {
            tris[fill[n]] = ti;
            fill[n] += 1;
        }
    }
    (start, tris)
}

/// The boundary flag of every node (on an edge used by one triangle only) and the mean edge
/// length (m).
fn boundary_nodes(mesh: &Mesh) -> (Vec<bool>, f64) {
    let n_nodes = mesh.n_nodes();
    let mut edges: Vec<(usize, usize)> = Vec::with_capacity(3 * mesh.n_triangles());
    for t in mesh.triangles() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort_unstable();
    let mut is_boundary = vec![false; n_nodes];
    let mut i = 0;
    let mut edge_len_sum = 0.0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j] == edges[i] {
            j += 1;
        }
        if j - i == 1 {
            is_boundary[edges[i].0] = true;
            is_boundary[edges[i].1] = true;
        }
        let (a, b) = (mesh.nodes_m()[edges[i].0], mesh.nodes_m()[edges[i].1]);
        edge_len_sum += (a[0] - b[0]).hypot(a[1] - b[1]);
        i = j;
    }
    (is_boundary, edge_len_sum / edges.len().max(1) as f64)
}

/// Most regions for which a node's region is chosen by area ([`node_regions`]): the per-node
/// area tally is a fixed array of this many entries. With more regions, a node takes the region
/// of the last triangle touching it (exact away from region borders).
pub(super) const MAX_REGIONS_BY_AREA: usize = 8;

/// Each node's region: the one covering most area around it (with more than
/// [`MAX_REGIONS_BY_AREA`] regions, the region of the last triangle touching it).
fn node_regions(mesh: &Mesh) -> Vec<usize> {
    let n_nodes = mesh.n_nodes();
    let mut area = vec![[0.0f64; MAX_REGIONS_BY_AREA]; n_nodes];
    let mut node_region = vec![0usize; n_nodes];
    let n_regions = mesh.region_names().len();
    if n_regions <= MAX_REGIONS_BY_AREA {
        for (ti, t) in mesh.triangles().iter().enumerate() {
            let a = mesh.signed_area_m2(ti).abs();
            for &n in t {
                area[n][mesh.region_of_tri()[ti]] += a;
            }
        }
        for n in 0..n_nodes {
            node_region[n] = (0..n_regions).max_by(|&a, &b| area[n][a].total_cmp(&area[n][b])).unwrap_or(0);
        }
    } else {
        for (ti, t) in mesh.triangles().iter().enumerate() {
            for &n in t {
                node_region[n] = mesh.region_of_tri()[ti];
            }
        }
    }
    node_region
}

/// The triangle containing `p` and its barycentric coordinates (a setup-time scan).
fn locate(mesh: &Mesh, p: [f64; 2]) -> Option<([usize; 3], [f64; 3])> {
    let mut best: Option<([usize; 3], [f64; 3], f64)> = None;
    for (ti, t) in mesh.triangles().iter().enumerate() {
        let bary = barycentric(mesh, ti, p);
        let worst = bary[0].min(bary[1]).min(bary[2]);
        if best.as_ref().is_none_or(|bst| worst > bst.2) {
            best = Some((*t, bary, worst));
        }
    }
    best.filter(|b| b.2 >= -1e-9).map(|b| (b.0, b.1))
}
