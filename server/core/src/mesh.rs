//! Triangle meshes: explicit meshes, the structured rectangle generator, and their validation.
//!
//! A [`Mesh`] holds node coordinates (metres), linear triangles as given (clockwise or
//! counter-clockwise), a region index per triangle, and named boundary node sets (for
//! example the fixed edge). Validation rejects anything that would give a wrong or singular
//! stiffness: out-of-range or repeated node ids, zero-area triangles, non-finite coordinates,
//! nodes used by no triangle, and meshes over a size limit.

use std::collections::BTreeMap;

/// The limits a mesh is checked against, so that a user's mesh cannot exhaust memory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshLimits {
    /// At most this many nodes.
    pub max_nodes: usize,
    /// At most this many triangles.
    pub max_triangles: usize,
}

impl Default for MeshLimits {
    /// One million nodes and two million triangles: a 1000 × 1000 grid.
    fn default() -> Self {
        Self { max_nodes: 1_000_000, max_triangles: 2_000_000 }
    }
}

/// Errors found while checking a mesh, each naming the offending item.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// The mesh has no triangles (or no nodes).
    #[error("the mesh is empty: it needs at least one triangle")]
    Empty,
    /// More nodes than [`MeshLimits::max_nodes`].
    #[error("the mesh has {n_nodes} nodes, over the limit of {max_nodes}")]
    TooManyNodes { n_nodes: usize, max_nodes: usize },
    /// More triangles than [`MeshLimits::max_triangles`].
    #[error("the mesh has {n_triangles} triangles, over the limit of {max_triangles}")]
    TooManyTriangles { n_triangles: usize, max_triangles: usize },
    /// A node coordinate is NaN or infinite.
    #[error("node {node_idx} has a non-finite coordinate ({x}, {y})")]
    NonFiniteNode { node_idx: usize, x: f64, y: f64 },
    /// A triangle refers to a node id that does not exist.
    #[error("triangle {tri_idx} refers to node {node_idx}, but the mesh has only {n_nodes} nodes (ids are 0-based)")]
    NodeOutOfRange { tri_idx: usize, node_idx: usize, n_nodes: usize },
    /// A triangle uses the same node twice.
    #[error("triangle {tri_idx} uses node {node_idx} twice")]
    RepeatedNode { tri_idx: usize, node_idx: usize },
    /// A triangle's area is zero (collinear or coincident vertices) relative to its size.
    #[error("triangle {tri_idx} (nodes {nodes:?}) is degenerate: its area {area_m2:e} m² is zero relative to its size")]
    Degenerate { tri_idx: usize, nodes: [usize; 3], area_m2: f64 },
    /// A node is not used by any triangle: its stiffness would be zero.
    #[error("node {node_idx} is used by no triangle ({n_unused} unused node(s) in all)")]
    UnusedNode { node_idx: usize, n_unused: usize },
    /// The region list does not have one entry per triangle.
    #[error("the mesh has {n_triangles} triangles but {n_regions} region entries")]
    RegionCount { n_triangles: usize, n_regions: usize },
    /// A boundary set names a node that does not exist.
    #[error("boundary set '{set}' names node {node_idx}, but the mesh has only {n_nodes} nodes")]
    BoundaryNodeOutOfRange { set: String, node_idx: usize, n_nodes: usize },
    /// Rectangle generator parameters are out of range.
    #[error("invalid rectangle mesh: {0}")]
    InvalidRectangle(String),
}

/// A 2D linear-triangle mesh. Built through [`Mesh::new`] or [`RectMeshParams::build`], both of
/// which validate it.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    nodes_m: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
    region_of_tri: Vec<usize>,
    region_names: Vec<String>,
    boundary_sets: BTreeMap<String, Vec<usize>>,
}

impl Mesh {
    /// Builds and validates an explicit mesh with one region (index 0, named "tissue").
    pub fn new(nodes_m: Vec<[f64; 2]>, triangles: Vec<[usize; 3]>, limits: &MeshLimits) -> Result<Self, MeshError> {
        let n_tri = triangles.len();
        Self::with_regions(nodes_m, triangles, vec![0; n_tri], vec!["tissue".to_owned()], BTreeMap::new(), limits)
    }

    /// Builds and validates a mesh with a region index per triangle (indices into `region_names`,
    /// which is extended with generated names if too short) and named boundary node sets.
    pub fn with_regions(
        nodes_m: Vec<[f64; 2]>,
        triangles: Vec<[usize; 3]>,
        region_of_tri: Vec<usize>,
        mut region_names: Vec<String>,
        boundary_sets: BTreeMap<String, Vec<usize>>,
        limits: &MeshLimits,
    ) -> Result<Self, MeshError> {
        if region_of_tri.len() != triangles.len() {
            return Err(MeshError::RegionCount { n_triangles: triangles.len(), n_regions: region_of_tri.len() });
        }
        let n_regions = region_of_tri.iter().copied().max().map_or(0, |m| m + 1);
        while region_names.len() < n_regions {
            region_names.push(format!("region{}", region_names.len()));
        }
        let mesh = Self { nodes_m, triangles, region_of_tri, region_names, boundary_sets };
        mesh.validate(limits)?;
        Ok(mesh)
    }

    fn validate(&self, limits: &MeshLimits) -> Result<(), MeshError> {
        let n_nodes = self.nodes_m.len();
        if self.triangles.is_empty() || n_nodes == 0 {
            return Err(MeshError::Empty);
        }
        if n_nodes > limits.max_nodes {
            return Err(MeshError::TooManyNodes { n_nodes, max_nodes: limits.max_nodes });
        }
        if self.triangles.len() > limits.max_triangles {
            return Err(MeshError::TooManyTriangles { n_triangles: self.triangles.len(), max_triangles: limits.max_triangles });
        }
        for (node_idx, &[x, y]) in self.nodes_m.iter().enumerate() {
            if !x.is_finite() || !y.is_finite() {
                return Err(MeshError::NonFiniteNode { node_idx, x, y });
            }
        }
        let mut used = vec![false; n_nodes];
        for (tri_idx, tri) in self.triangles.iter().enumerate() {
            for (k, &node_idx) in tri.iter().enumerate() {
                if node_idx >= n_nodes {
                    return Err(MeshError::NodeOutOfRange { tri_idx, node_idx, n_nodes });
                }
                if tri[..k].contains(&node_idx) {
                    return Err(MeshError::RepeatedNode { tri_idx, node_idx });
                }
                used[node_idx] = true;
            }
            let area_m2 = self.signed_area_m2(tri_idx).abs();
            let [a, b, c] = tri.map(|i| self.nodes_m[i]);
            let longest_sq = [dist_sq(a, b), dist_sq(b, c), dist_sq(c, a)].into_iter().fold(0.0, f64::max);
            // A triangle whose area is below 1e-12 of the square of its longest edge is flat to
            // round-off: its element stiffness would be meaningless.
            if !(area_m2 > 1e-12 * longest_sq) {
                return Err(MeshError::Degenerate { tri_idx, nodes: *tri, area_m2 });
            }
        }
        let n_unused = used.iter().filter(|u| !**u).count();
        if let Some(node_idx) = used.iter().position(|u| !*u) {
            return Err(MeshError::UnusedNode { node_idx, n_unused });
        }
        for (set, nodes) in &self.boundary_sets {
            if let Some(&node_idx) = nodes.iter().find(|&&i| i >= n_nodes) {
                return Err(MeshError::BoundaryNodeOutOfRange { set: set.clone(), node_idx, n_nodes });
            }
        }
        Ok(())
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes_m.len()
    }
    /// Number of triangles.
    pub fn n_triangles(&self) -> usize {
        self.triangles.len()
    }
    /// Node coordinates in metres.
    pub fn nodes_m(&self) -> &[[f64; 2]] {
        &self.nodes_m
    }
    /// Triangles as node index triples, in the orientation given.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }
    /// The region index of each triangle.
    pub fn region_of_tri(&self) -> &[usize] {
        &self.region_of_tri
    }
    /// Region names, indexed by region index.
    pub fn region_names(&self) -> &[String] {
        &self.region_names
    }
    /// Named boundary node sets (sorted, without repeats).
    pub fn boundary_sets(&self) -> &BTreeMap<String, Vec<usize>> {
        &self.boundary_sets
    }
    /// The node set with this name, if any.
    pub fn boundary_set(&self, name: &str) -> Option<&[usize]> {
        self.boundary_sets.get(name).map(Vec::as_slice)
    }
    /// Adds or replaces a named node set (sorted and deduplicated).
    pub fn set_boundary_set(&mut self, name: &str, mut nodes: Vec<usize>) -> Result<(), MeshError> {
        nodes.sort_unstable();
        nodes.dedup();
        if let Some(&node_idx) = nodes.iter().find(|&&i| i >= self.n_nodes()) {
            return Err(MeshError::BoundaryNodeOutOfRange { set: name.to_owned(), node_idx, n_nodes: self.n_nodes() });
        }
        self.boundary_sets.insert(name.to_owned(), nodes);
        Ok(())
    }

    /// Twice-signed area convention: positive for counter-clockwise triangles. Returns the signed
    /// area $A = \tfrac12[(x_2-x_1)(y_3-y_1) - (x_3-x_1)(y_2-y_1)]$ in m².
    pub fn signed_area_m2(&self, tri_idx: usize) -> f64 {
        let [a, b, c] = self.triangles[tri_idx].map(|i| self.nodes_m[i]);
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
    }

    /// The axis-aligned bounding box `([xmin, ymin], [xmax, ymax])`.
    pub fn bounding_box_m(&self) -> ([f64; 2], [f64; 2]) {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in &self.nodes_m {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    /// Nodes whose coordinate `axis` (0 = x, 1 = y) lies within `tol_m` of `value_m`, in index order.
    pub fn nodes_where(&self, axis: usize, value_m: f64, tol_m: f64) -> Vec<usize> {
        (0..self.n_nodes()).filter(|&i| (self.nodes_m[i][axis] - value_m).abs() <= tol_m).collect()
    }
}

fn dist_sq(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

/// How the structured generator splits each grid cell into two triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DiagonalPattern {
    /// Every diagonal runs bottom-left to top-right.
    Right,
    /// The diagonal direction alternates in a checkerboard ("union jack"); the default, since it
    /// is free of the directional bias of [`DiagonalPattern::Right`].
    #[default]
    Alternate,
}

/// A structured rectangle of `nx × ny` nodes; node id $j\,n_x + i$ ($i$ along x, $j$ along y),
/// counter-clockwise triangles. Boundary sets `bottom`, `top`, `left`, `right` are named.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RectMeshParams {
    pub nx: usize,
    pub ny: usize,
    pub width_m: f64,
    pub height_m: f64,
    pub origin_m: [f64; 2],
    pub pattern: DiagonalPattern,
}

impl RectMeshParams {
    /// A `nx × ny` grid over `[0, width] × [0, height]` with the alternating pattern.
    pub fn new(nx: usize, ny: usize, width_m: f64, height_m: f64) -> Self {
        Self { nx, ny, width_m, height_m, origin_m: [0.0, 0.0], pattern: DiagonalPattern::Alternate }
    }

    /// Generates and validates the mesh.
    pub fn build(&self, limits: &MeshLimits) -> Result<Mesh, MeshError> {
        let Self { nx, ny, width_m, height_m, origin_m, pattern } = *self;
        if nx < 2 || ny < 2 {
            return Err(MeshError::InvalidRectangle(format!("nx and ny must be at least 2, got {nx} × {ny}")));
        }
        if !(width_m.is_finite() && width_m > 0.0 && height_m.is_finite() && height_m > 0.0) {
            return Err(MeshError::InvalidRectangle(format!("width and height must be finite and positive, got {width_m} × {height_m}")));
        }
        if !(origin_m[0].is_finite() && origin_m[1].is_finite()) {
            return Err(MeshError::InvalidRectangle(format!("origin must be finite, got {origin_m:?}")));
        }
        let n_nodes = nx.saturating_mul(ny);
        if n_nodes > limits.max_nodes {
            return Err(MeshError::TooManyNodes { n_nodes, max_nodes: limits.max_nodes });
        }
        // Coordinates as numpy's linspace computes them, so generated meshes match references bit for bit.
        let lin = |n: usize, len: f64, k: usize| if k + 1 == n { len } else { k as f64 * (len / (n - 1) as f64) };
        let mut nodes = Vec::with_capacity(n_nodes);
        for j in 0..ny {
            for i in 0..nx {
                nodes.push([origin_m[0] + lin(nx, width_m, i), origin_m[1] + lin(ny, height_m, j)]);
            }
        }
        let mut tris = Vec::with_capacity(2 * (nx - 1) * (ny - 1));
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let a = j * nx + i;
                let (b, c, d) = (a + 1, a + nx + 1, a + nx);
                if pattern == DiagonalPattern::Right || (i + j) % 2 == 0 {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        let mut sets = BTreeMap::new();
        sets.insert("bottom".to_owned(), (0..nx).collect());
        sets.insert("top".to_owned(), ((ny - 1) * nx..ny * nx).collect());
        sets.insert("left".to_owned(), (0..ny).map(|j| j * nx).collect());
        sets.insert("right".to_owned(), (0..ny).map(|j| j * nx + nx - 1).collect());
        let n_tri = tris.len();
        Mesh::with_regions(nodes, tris, vec![0; n_tri], vec!["tissue".to_owned()], sets, limits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lim() -> MeshLimits {
        MeshLimits::default()
    }

    #[test]
    fn rectangle_counts_and_orientation() {
        for pattern in [DiagonalPattern::Right, DiagonalPattern::Alternate] {
            let m = RectMeshParams { pattern, ..RectMeshParams::new(5, 4, 2.0, 1.0) }.build(&lim()).unwrap();
            assert_eq!(m.n_nodes(), 20);
            assert_eq!(m.n_triangles(), 24);
            let total: f64 = (0..m.n_triangles()).map(|t| m.signed_area_m2(t)).sum();
            assert!((total - 2.0).abs() < 1e-12, "areas sum to the rectangle: {total}");
            assert!((0..m.n_triangles()).all(|t| m.signed_area_m2(t) > 0.0));
            assert_eq!(m.boundary_set("left").unwrap(), &[0, 5, 10, 15]);
            assert_eq!(m.boundary_set("top").unwrap(), &[15, 16, 17, 18, 19]);
        }
    }

    #[test]
    fn patterns_differ_where_expected() {
        let r = RectMeshParams { pattern: DiagonalPattern::Right, ..RectMeshParams::new(3, 3, 1.0, 1.0) }.build(&lim()).unwrap();
        let a = RectMeshParams::new(3, 3, 1.0, 1.0).build(&lim()).unwrap();
        assert_eq!(r.triangles()[0], a.triangles()[0]);
        assert_eq!(r.triangles()[2], [1, 2, 5]);
        assert_eq!(a.triangles()[2], [1, 2, 4]);
    }

    #[test]
    fn errors_name_the_item() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        let e = Mesh::new(nodes.clone(), vec![[0, 1, 7]], &lim()).unwrap_err();
        assert!(e.to_string().contains("triangle 0 refers to node 7"), "{e}");
        let e = Mesh::new(nodes.clone(), vec![[0, 1, 2], [1, 1, 3]], &lim()).unwrap_err();
        assert!(e.to_string().contains("triangle 1 uses node 1 twice"), "{e}");
        let e = Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], vec![[0, 1, 2]], &lim()).unwrap_err();
        assert!(e.to_string().contains("triangle 0") && e.to_string().contains("degenerate"), "{e}");
        let e = Mesh::new(nodes.clone(), vec![[0, 1, 2]], &lim()).unwrap_err();
        assert!(e.to_string().contains("node 3 is used by no triangle"), "{e}");
        let mut bad = nodes.clone();
        bad[2] = [f64::NAN, 1.0];
        let e = Mesh::new(bad, vec![[0, 1, 2], [1, 3, 2]], &lim()).unwrap_err();
        assert!(e.to_string().contains("node 2 has a non-finite coordinate"), "{e}");
        let small = MeshLimits { max_nodes: 100, max_triangles: 1000 };
        let e = RectMeshParams::new(11, 10, 1.0, 1.0).build(&small).unwrap_err();
        assert!(e.to_string().contains("110 nodes, over the limit of 100"), "{e}");
        let e = Mesh::new(nodes, vec![[0, 1, 2], [1, 3, 2]], &small)
            .map(|_| ())
            .and_then(|_| RectMeshParams::new(1, 3, 1.0, 1.0).build(&small).map(|_| ()));
        assert!(e.unwrap_err().to_string().contains("at least 2"));
    }

    #[test]
    fn clockwise_triangles_are_accepted() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let m = Mesh::new(nodes, vec![[0, 2, 1]], &lim()).unwrap();
        assert!(m.signed_area_m2(0) < 0.0);
    }
}
