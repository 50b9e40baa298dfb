//! The 3D pieces of the tetrahedral mesh [`TetMesh`] (= [`SimplexMesh<Dim3>`]): its limits and
//! errors (messages naming the tetrahedron), the degeneracy test, the 3D accessor names, the
//! structured box grid, and their validation. Storage and the checks shared with 2D are in
//! [`crate::mesh`]; the conformity checks in [`super::conform`].
//!
//! A [`TetMesh`] holds node coordinates $x_i \in \mathbb R^3$ (metres), linear 4-node tetrahedra,
//! a region index per tetrahedron, region names, and named boundary node sets. Every stored
//! tetrahedron $[a, b, c, d]$ has a positive signed volume
//! $V = \tfrac16 \det[x_b - x_a,\; x_c - x_a,\; x_d - x_a] > 0$: [`TetMesh::new`] and
//! [`TetMesh::with_regions`] accept either orientation and swap the last two nodes of a negative
//! one (the exchange format allows any orientation; element stiffness and stresses do not depend
//! on the order). The Gmsh reader ([`crate::msh::parse_msh3d`]) instead *rejects* a negative
//! tetrahedron, naming its tag and line: Gmsh writes positive ones, so a negative one means a
//! broken file.
//!
//! Validation rejects what would give a wrong or singular stiffness, naming the element index:
//! out-of-range and repeated node ids, degenerate tetrahedra ($|V| \le 10^{-12} h^3$ with $h$ the
//! element's longest edge), two tetrahedra with the same node set, non-finite coordinates, nodes
//! used by no tetrahedron, region and boundary-set inconsistencies, and meshes over the
//! [`TetMeshLimits`]; and what a conforming mesh cannot have ([`super::conform`]): coincident
//! nodes (a crack), a face shared by more than two tetrahedra or by two on the same side of it,
//! and tissue just outside a boundary face (a tetrahedron or a part lying inside others).

use std::collections::BTreeMap;

use crate::mesh::{Dim3, MeshFault, MeshLimits, SimplexMesh};

/// The limits a tetrahedral mesh is checked against, so that a user's mesh cannot exhaust memory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetMeshLimits {
    /// At most this many nodes.
    pub max_nodes: usize,
    /// At most this many tetrahedra.
    pub max_tets: usize,
}

impl Default for TetMeshLimits {
    /// One million nodes and six million tetrahedra (a 100³-node box grid has 5.9 M).
    fn default() -> Self {
        Self { max_nodes: 1_000_000, max_tets: 6_000_000 }
    }
}

impl TetMeshLimits {
    /// The 3D limits implied by the server's 2D [`MeshLimits`]: the same node limit, and three
    /// times the triangle limit as tetrahedra (a structured grid has about 2 triangles per node in
    /// 2D and 6 tetrahedra per node in 3D).
    pub fn from_2d(limits: &MeshLimits) -> Self {
        Self { max_nodes: limits.max_nodes, max_tets: limits.max_triangles.saturating_mul(3) }
    }
}

/// Errors found while checking a tetrahedral mesh, each naming the offending item.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TetMeshError {
    /// The mesh has no tetrahedra (or no nodes).
    #[error("the mesh is empty: it needs at least one tetrahedron")]
    Empty,
    /// More nodes than [`TetMeshLimits::max_nodes`].
    #[error("the mesh has {n_nodes} nodes, over the limit of {max_nodes}")]
    TooManyNodes { n_nodes: usize, max_nodes: usize },
    /// More tetrahedra than [`TetMeshLimits::max_tets`].
    #[error("the mesh has {n_tets} tetrahedra, over the limit of {max_tets}")]
    TooManyTets { n_tets: usize, max_tets: usize },
    /// A node coordinate is NaN or infinite.
    #[error("node {node_idx} has a non-finite coordinate {x_m:?}")]
    NonFiniteNode { node_idx: usize, x_m: [f64; 3] },
    /// A tetrahedron refers to a node id that does not exist.
    #[error("tetrahedron {tet_idx} refers to node {node_idx}, but the mesh has only {n_nodes} nodes (ids are 0-based)")]
    NodeOutOfRange { tet_idx: usize, node_idx: usize, n_nodes: usize },
    /// A tetrahedron uses the same node twice.
    #[error("tetrahedron {tet_idx} uses node {node_idx} twice")]
    RepeatedNode { tet_idx: usize, node_idx: usize },
    /// A tetrahedron's volume is zero relative to its size: $|V| \le 10^{-12} h^3$.
    #[error(
        "tetrahedron {tet_idx} (nodes {nodes:?}) is degenerate: its volume {volume_m3:e} m³ is zero relative to its longest edge {longest_edge_m:e} m"
    )]
    Degenerate { tet_idx: usize, nodes: [usize; 4], volume_m3: f64, longest_edge_m: f64 },
    /// Two tetrahedra have the same four nodes (in any order).
    #[error("tetrahedra {first_idx} and {second_idx} have the same nodes {nodes:?}")]
    DuplicateTet { first_idx: usize, second_idx: usize, nodes: [usize; 4] },
    /// A node is not used by any tetrahedron: its stiffness would be zero.
    #[error("node {node_idx} is used by no tetrahedron ({n_unused} unused node(s) in all)")]
    UnusedNode { node_idx: usize, n_unused: usize },
    /// The region list does not have one entry per tetrahedron.
    #[error("the mesh has {n_tets} tetrahedra but {n_regions} region entries")]
    RegionCount { n_tets: usize, n_regions: usize },
    /// Two regions have the same name.
    #[error("regions {first_idx} and {second_idx} are both named '{name}': region names must be unique")]
    DuplicateRegionName { name: String, first_idx: usize, second_idx: usize },
    /// A boundary set names a node that does not exist.
    #[error("boundary set '{set}' names node {node_idx}, but the mesh has only {n_nodes} nodes")]
    BoundaryNodeOutOfRange { set: String, node_idx: usize, n_nodes: usize },
    /// Two nodes lie within [`super::conform::DUPLICATE_NODE_TOL`] × the bounding-box diagonal of
    /// each other: a mesh that repeats a node instead of sharing it is cut apart there (a crack).
    #[error(
        "nodes {first_idx} and {second_idx} coincide at ({}, {}, {}) m (within {tol_m:e} m): a node must appear once and be shared by its tetrahedra; a repeated node cuts the mesh apart (a crack)",
        x_m[0], x_m[1], x_m[2]
    )]
    DuplicateNode { first_idx: usize, second_idx: usize, x_m: [f64; 3], tol_m: f64 },
    /// A triangular face belongs to more than two tetrahedra.
    #[error("the face with nodes {face:?} belongs to {n_tets} tetrahedra ({}, {}, {}, …): at most two tetrahedra meet at a face", tets[0], tets[1], tets[2])]
    FaceSharedByMany { face: [usize; 3], tets: [usize; 3], n_tets: usize },
    /// The interiors of two tetrahedra intersect: the tissue there would be counted twice.
    #[error("tetrahedra {first_idx} (nodes {first_nodes:?}) and {second_idx} (nodes {second_nodes:?}) overlap")]
    OverlappingTets { first_idx: usize, first_nodes: [usize; 4], second_idx: usize, second_nodes: [usize; 4] },
    /// Box grid parameters are out of range.
    #[error("invalid box grid: {0}")]
    InvalidBox(String),
}

/// A tetrahedron is degenerate when $|V| \le$ this $\times\, h^3$ ($h$: its longest edge). A regular
/// tetrahedron has $V = h^3 / (6\sqrt2) \approx 0.118\,h^3$.
pub const DEGENERATE_VOLUME_TOL: f64 = 1e-12;

/// A 3D linear-tetrahedron mesh, built through [`TetMesh::new`], [`TetMesh::with_regions`] or
/// [`BoxGridParams::build`], all of which validate it. DOF layout of everything built on it:
/// $[u_{x0}, u_{y0}, u_{z0}, u_{x1}, \dots]$, DOF $= 3\cdot\mathrm{node} + \mathrm{axis}$.
pub type TetMesh = SimplexMesh<Dim3>;

impl From<MeshFault<Dim3>> for TetMeshError {
    fn from(f: MeshFault<Dim3>) -> Self {
        match f {
            MeshFault::Empty => Self::Empty,
            MeshFault::TooManyNodes { n_nodes, max_nodes } => Self::TooManyNodes { n_nodes, max_nodes },
            MeshFault::TooManyElements { n_elements, max_elements } => Self::TooManyTets { n_tets: n_elements, max_tets: max_elements },
            MeshFault::NonFiniteNode { node_idx, x_m } => Self::NonFiniteNode { node_idx, x_m },
            MeshFault::NodeOutOfRange { elem_idx, node_idx, n_nodes } => Self::NodeOutOfRange { tet_idx: elem_idx, node_idx, n_nodes },
            MeshFault::RepeatedNode { elem_idx, node_idx } => Self::RepeatedNode { tet_idx: elem_idx, node_idx },
            MeshFault::UnusedNode { node_idx, n_unused } => Self::UnusedNode { node_idx, n_unused },
            MeshFault::RegionCount { n_elements, n_regions } => Self::RegionCount { n_tets: n_elements, n_regions },
            MeshFault::BoundaryNodeOutOfRange { set, node_idx, n_nodes } => Self::BoundaryNodeOutOfRange { set, node_idx, n_nodes },
            MeshFault::DuplicateNode { first_idx, second_idx, x_m, tol_m } => Self::DuplicateNode { first_idx, second_idx, x_m, tol_m },
            MeshFault::DuplicateElement { first_idx, second_idx, nodes } => Self::DuplicateTet { first_idx, second_idx, nodes },
            MeshFault::DuplicateRegionName { name, first_idx, second_idx } => Self::DuplicateRegionName { name, first_idx, second_idx },
        }
    }
}

/// A tetrahedron is degenerate when $|V| \le$ [`DEGENERATE_VOLUME_TOL`] $\times\, h^3$ ($h$: its
/// longest edge): flat to round-off, its element stiffness would be meaningless.
pub(crate) fn check_shape(tet_idx: usize, tet: &[usize; 4], p: &[[f64; 3]; 4]) -> Result<(), TetMeshError> {
    let volume_m3 = signed_volume_m3(p[0], p[1], p[2], p[3]);
    let longest_edge_m = longest_edge_m(*p);
    if !(volume_m3.abs() > DEGENERATE_VOLUME_TOL * longest_edge_m.powi(3)) {
        return Err(TetMeshError::Degenerate { tet_idx, nodes: *tet, volume_m3, longest_edge_m });
    }
    Ok(())
}

/// The signed volume $\tfrac16 \det[b - a, c - a, d - a]$ in m³.
pub fn signed_volume_m3(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let u = sub(b, a);
    let v = sub(c, a);
    let w = sub(d, a);
    dot(u, cross(v, w)) / 6.0
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// The longest edge of four points, in m.
pub fn longest_edge_m(p: [[f64; 3]; 4]) -> f64 {
    let mut h2 = 0.0f64;
    for i in 0..4 {
        for j in i + 1..4 {
            let e = sub(p[i], p[j]);
            h2 = h2.max(dot(e, e));
        }
    }
    h2.sqrt()
}

/// The 3D names of the mesh's accessors.
impl TetMesh {
    /// Number of tetrahedra.
    pub fn n_tets(&self) -> usize {
        self.n_elements()
    }
    /// Tetrahedra as node index quadruples, positively oriented.
    pub fn tets(&self) -> &[[usize; 4]] {
        self.elements()
    }
    /// The region index of each tetrahedron.
    pub fn region_of_tet(&self) -> &[usize] {
        self.region_of_element()
    }
    /// The corner coordinates of tetrahedron `tet_idx`.
    pub fn tet_points_m(&self, tet_idx: usize) -> [[f64; 3]; 4] {
        self.element_points_m(tet_idx)
    }
    /// The volume of tetrahedron `tet_idx` (positive), in m³.
    pub fn volume_m3(&self, tet_idx: usize) -> f64 {
        self.signed_measure(tet_idx)
    }
}

/// A structured box grid $[0, l_x] \times [0, l_y] \times [0, l_z]$ with `n[0] × n[1] × n[2]` nodes.
///
/// Node $(i, j, k)$ has index $i + n_x (j + n_y k)$ and coordinates $(i\,l_x/(n_x-1), \dots)$
/// (the last node of each axis exactly at $l$). Each hexahedral cell is split into the 6
/// tetrahedra of the Kuhn (Freudenthal) subdivision: all share the cell diagonal from its corner
/// $(0,0,0)$ to $(1,1,1)$, one per order of the three axes. Every cell is split the same way, so
/// each face of a cell is cut along the same diagonal from both sides: the mesh is conforming.
/// Each tetrahedron has volume $h_x h_y h_z / 6$. One region, "tissue". Boundary node sets, z up:
/// "left" ($x = 0$), "right" ($x = l_x$), "front" ($y = 0$), "back" ($y = l_y$), "bottom"
/// ($z = 0$), "top" ($z = l_z$).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxGridParams {
    /// Nodes along x, y, z (each ≥ 2).
    pub n: [usize; 3],
    /// Edge lengths along x, y, z, in m.
    pub size_m: [f64; 3],
}

impl BoxGridParams {
    /// A grid of `n` nodes per axis over a box of `size_m`.
    pub fn new(n: [usize; 3], size_m: [f64; 3]) -> Self {
        Self { n, size_m }
    }

    /// The node index of grid node `(i, j, k)`.
    pub fn node(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.n[0] * (j + self.n[1] * k)
    }

    /// Builds and validates the mesh. Errors: fewer than 2 nodes on an axis, a size that is not
    /// finite and positive ([`TetMeshError::InvalidBox`]), or over the limits.
    pub fn build(&self, limits: &TetMeshLimits) -> Result<TetMesh, TetMeshError> {
        let [nx, ny, nz] = self.n;
        if self.n.iter().any(|&n| n < 2) {
            return Err(TetMeshError::InvalidBox(format!("needs at least 2 nodes per axis, got {:?}", self.n)));
        }
        if !self.size_m.iter().all(|&l| l.is_finite() && l > 0.0) {
            return Err(TetMeshError::InvalidBox(format!("sizes must be finite and > 0, got {:?} m", self.size_m)));
        }
        let n_nodes = nx.checked_mul(ny).and_then(|v| v.checked_mul(nz)).unwrap_or(usize::MAX);
        if n_nodes > limits.max_nodes {
            return Err(TetMeshError::TooManyNodes { n_nodes, max_nodes: limits.max_nodes });
        }
        let n_tets = 6 * (nx - 1) * (ny - 1) * (nz - 1);
        if n_tets > limits.max_tets {
            return Err(TetMeshError::TooManyTets { n_tets, max_tets: limits.max_tets });
        }
        let coord = |i: usize, n: usize, l: f64| if i + 1 == n { l } else { i as f64 * (l / (n - 1) as f64) };
        let mut nodes_m = Vec::with_capacity(n_nodes);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    nodes_m.push([coord(i, nx, self.size_m[0]), coord(j, ny, self.size_m[1]), coord(k, nz, self.size_m[2])]);
                }
            }
        }
        // The six axis orders; each path 000 -> +e_a -> +e_b -> 111 is one tetrahedron.
        const ORDERS: [[usize; 3]; 6] = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
        let mut tets = Vec::with_capacity(n_tets);
        for k in 0..nz - 1 {
            for j in 0..ny - 1 {
                for i in 0..nx - 1 {
                    for order in ORDERS {
                        let mut c = [i, j, k];
                        let mut t = [0usize; 4];
                        t[0] = self.node(c[0], c[1], c[2]);
                        for (s, &axis) in order.iter().enumerate() {
                            c[axis] += 1;
                            t[s + 1] = self.node(c[0], c[1], c[2]);
                        }
                        tets.push(t);
                    }
                }
            }
        }
        let mut sets = BTreeMap::new();
        let face = |axis: usize, at_end: bool| -> Vec<usize> {
            let last = self.n[axis] - 1;
            let mut v = Vec::new();
            for k in 0..nz {
                for j in 0..ny {
                    for i in 0..nx {
                        let c = [i, j, k][axis];
                        if (at_end && c == last) || (!at_end && c == 0) {
                            v.push(self.node(i, j, k));
                        }
                    }
                }
            }
            v
        };
        for (name, axis, at_end) in
            [("left", 0, false), ("right", 0, true), ("front", 1, false), ("back", 1, true), ("bottom", 2, false), ("top", 2, true)]
        {
            sets.insert(name.to_owned(), face(axis, at_end));
        }
        let n_t = tets.len();
        TetMesh::with_regions(nodes_m, tets, vec![0; n_t], vec!["tissue".to_owned()], sets, limits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_tet() -> (Vec<[f64; 3]>, Vec<[usize; 4]>) {
        (vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]], vec![[0, 1, 2, 3], [1, 2, 3, 4]])
    }

    #[test]
    fn box_grid_volumes_sum_to_the_box_and_sets_are_faces() {
        let p = BoxGridParams::new([4, 3, 5], [0.1, 0.05, 0.2]);
        let m = p.build(&TetMeshLimits::default()).unwrap();
        assert_eq!(m.n_nodes(), 60);
        assert_eq!(m.n_tets(), 6 * 3 * 2 * 4);
        let vol: f64 = (0..m.n_tets()).map(|t| m.volume_m3(t)).sum();
        assert!((vol - 0.1 * 0.05 * 0.2).abs() < 1e-15, "volume {vol}");
        let cell = 0.1 / 3.0 * 0.05 / 2.0 * 0.2 / 4.0;
        for t in 0..m.n_tets() {
            assert!((m.volume_m3(t) - cell / 6.0).abs() < 1e-12 * cell, "tet {t}");
        }
        for (name, axis, value) in
            [("left", 0, 0.0), ("right", 0, 0.1), ("front", 1, 0.0), ("back", 1, 0.05), ("bottom", 2, 0.0), ("top", 2, 0.2)]
        {
            assert_eq!(m.boundary_set(name).unwrap(), m.nodes_where(axis, value, 1e-12).as_slice(), "{name}");
        }
        // Conforming: every interior triangular face is shared by exactly two tetrahedra, every
        // boundary face lies on the box surface.
        let mut faces: BTreeMap<[usize; 3], usize> = BTreeMap::new();
        for t in m.tets() {
            for skip in 0..4 {
                let mut f = [0; 3];
                let mut k = 0;
                for (i, &n) in t.iter().enumerate() {
                    if i != skip {
                        f[k] = n;
                        k += 1;
                    }
                }
                f.sort_unstable();
                *faces.entry(f).or_default() += 1;
            }
        }
        let on_surface = |f: &[usize; 3]| {
            (0..3).any(|axis| {
                let (lo, hi) = (0.0, p.size_m[axis]);
                f.iter().all(|&n| (m.nodes_m()[n][axis] - lo).abs() < 1e-12) || f.iter().all(|&n| (m.nodes_m()[n][axis] - hi).abs() < 1e-12)
            })
        };
        for (f, &count) in &faces {
            assert!(count == 2 || (count == 1 && on_surface(f)), "face {f:?} shared by {count}");
        }
    }

    #[test]
    fn negative_tets_are_reoriented() {
        let (nodes, _) = unit_tet();
        let m = TetMesh::new(nodes, vec![[0, 2, 1, 3], [1, 2, 3, 4]], &TetMeshLimits::default()).unwrap();
        assert!(m.volume_m3(0) > 0.0 && m.volume_m3(1) > 0.0);
        assert!((m.volume_m3(0) - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn validation_names_the_element() {
        let lim = TetMeshLimits::default();
        let (nodes, tets) = unit_tet();
        assert!(TetMesh::new(nodes.clone(), tets.clone(), &lim).is_ok());
        let e = TetMesh::new(nodes.clone(), vec![[0, 1, 2, 3], [1, 2, 3, 7]], &lim).unwrap_err();
        assert_eq!(e, TetMeshError::NodeOutOfRange { tet_idx: 1, node_idx: 7, n_nodes: 5 });
        assert!(e.to_string().starts_with("tetrahedron 1 refers to node 7"), "{e}");
        let e = TetMesh::new(nodes.clone(), vec![[0, 1, 2, 3], [1, 2, 2, 4]], &lim).unwrap_err();
        assert_eq!(e, TetMeshError::RepeatedNode { tet_idx: 1, node_idx: 2 });
        let e = TetMesh::new(nodes.clone(), vec![[0, 1, 2, 3], [1, 2, 3, 4], [3, 2, 1, 0]], &lim).unwrap_err();
        assert_eq!(e, TetMeshError::DuplicateTet { first_idx: 0, second_idx: 2, nodes: [0, 1, 2, 3] });
        // A flat tetrahedron: node 4 moved into the plane of 1, 2, 3 (x + y + z = 1).
        let mut flat = nodes.clone();
        flat[4] = [0.5, 0.5, 0.0];
        let e = TetMesh::new(flat, tets.clone(), &lim).unwrap_err();
        assert!(matches!(e, TetMeshError::Degenerate { tet_idx: 1, nodes: [1, 2, 3, 4], .. }), "{e}");
        assert!(e.to_string().starts_with("tetrahedron 1 (nodes [1, 2, 3, 4]) is degenerate"), "{e}");
        // Size-aware: the same shape scaled to 1 µm is fine.
        let tiny: Vec<[f64; 3]> = nodes.iter().map(|p| p.map(|v| v * 1e-6)).collect();
        assert!(TetMesh::new(tiny, tets.clone(), &lim).is_ok());
        let mut unused = nodes.clone();
        unused.push([5.0, 5.0, 5.0]);
        let e = TetMesh::new(unused, tets.clone(), &lim).unwrap_err();
        assert_eq!(e, TetMeshError::UnusedNode { node_idx: 5, n_unused: 1 });
        let mut nan = nodes.clone();
        nan[2][1] = f64::NAN;
        assert!(matches!(TetMesh::new(nan, tets.clone(), &lim).unwrap_err(), TetMeshError::NonFiniteNode { node_idx: 2, .. }));
        let small = TetMeshLimits { max_nodes: 10, max_tets: 1 };
        assert_eq!(TetMesh::new(nodes, tets, &small).unwrap_err(), TetMeshError::TooManyTets { n_tets: 2, max_tets: 1 });
        let e = BoxGridParams::new([1, 3, 3], [1.0; 3]).build(&lim).unwrap_err();
        assert!(matches!(e, TetMeshError::InvalidBox(_)), "{e}");
    }
}
