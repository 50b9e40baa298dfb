//! Simplex meshes in either dimension: [`SimplexMesh<D>`] (storage, accessors, regions, boundary
//! sets, validation), with [`Mesh`] the 2D triangle mesh and [`crate::d3::TetMesh`] the 3D
//! tetrahedral one.
//!
//! A mesh holds node coordinates (metres), linear simplices ($N + 1$ nodes each), a region index
//! per element, region names, and named boundary node sets (for example the fixed edge or face).
//! Validation rejects anything that would give a wrong or singular stiffness, naming the item:
//! meshes over a size limit, non-finite coordinates, out-of-range or repeated node ids,
//! degenerate elements, nodes used by no element, region and boundary-set inconsistencies, and
//! what a conforming mesh cannot have: duplicate nodes (within $10^{-9}$ of the bounding-box
//! diagonal), duplicate elements and two regions of the same name. These checks are written once
//! here; what depends on the element (its measure and degeneracy test, the stored orientation,
//! the 2D overlap and 3D face checks) is a method of [`Dim`]. The 2D pieces (limits, errors,
//! overlaps, the rectangle generator) are in [`tri`]; the 3D ones in [`crate::d3::mesh`] and
//! [`crate::d3::conform`].
//!
//! The errors stay one enum per dimension ([`MeshError`], [`crate::d3::TetMeshError`]): their
//! messages name the element ("triangle 3", "tetrahedron 3") and are quoted by tests and the
//! CLI. The shared checks report a [`MeshFault`], which each dimension converts into its error.
//!
//! Costs: the duplicate checks are $O(n \log n)$ (sorting); the 2D overlaps and the 3D face and
//! probe checks are described with them.

use std::collections::BTreeMap;

pub use crate::dim::{Dim, Dim2, Dim3};

pub mod tri;

pub use tri::{DiagonalPattern, MeshError, MeshLimits, RectMeshParams};

/// The 2D linear-triangle mesh.
pub type Mesh = SimplexMesh<Dim2>;

/// Two nodes closer than this fraction of the mesh's bounding-box diagonal are the same node.
/// Far above round-off (coordinates carry 1e-16 relative precision, a mesh file's text at least
/// 1e-12 with Gmsh's 16 digits) and far below any element a solver could use (an element 1e-9
/// of the mesh is 1e18 times stiffer than the mesh's scale: its stiffness would drown in
/// round-off).
pub const DUPLICATE_NODE_TOL: f64 = 1e-9;

/// A fault found by the checks shared by both dimensions; each dimension's error type is built
/// from it (`D::MeshError: From<MeshFault<D>>`), naming the element its own way.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshFault<D: Dim> {
    /// No elements (or no nodes).
    Empty,
    /// More nodes than the limit.
    TooManyNodes { n_nodes: usize, max_nodes: usize },
    /// More elements than the limit.
    TooManyElements { n_elements: usize, max_elements: usize },
    /// A node coordinate is NaN or infinite.
    NonFiniteNode { node_idx: usize, x_m: D::Point },
    /// An element refers to a node id that does not exist.
    NodeOutOfRange { elem_idx: usize, node_idx: usize, n_nodes: usize },
    /// An element uses the same node twice.
    RepeatedNode { elem_idx: usize, node_idx: usize },
    /// A node is used by no element.
    UnusedNode { node_idx: usize, n_unused: usize },
    /// The region list does not have one entry per element.
    RegionCount { n_elements: usize, n_regions: usize },
    /// A boundary set names a node that does not exist.
    BoundaryNodeOutOfRange { set: String, node_idx: usize, n_nodes: usize },
    /// Two nodes within [`DUPLICATE_NODE_TOL`] × the bounding-box diagonal of each other.
    DuplicateNode { first_idx: usize, second_idx: usize, x_m: D::Point, tol_m: f64 },
    /// Two elements with the same nodes (in any order); `nodes` sorted.
    DuplicateElement { first_idx: usize, second_idx: usize, nodes: D::Element },
    /// Two regions with the same name.
    DuplicateRegionName { name: String, first_idx: usize, second_idx: usize },
}

/// A linear-simplex mesh in dimension `D`, built through [`SimplexMesh::new`],
/// [`SimplexMesh::with_regions`] or a structured generator, all of which validate it.
#[derive(Debug, Clone, PartialEq)]
pub struct SimplexMesh<D: Dim> {
    nodes_m: Vec<D::Point>,
    elements: Vec<D::Element>,
    region_of_element: Vec<usize>,
    region_names: Vec<String>,
    boundary_sets: BTreeMap<String, Vec<usize>>,
}

impl<D: Dim> SimplexMesh<D> {
    /// Builds and validates an explicit mesh with one region (index 0, named "tissue").
    pub fn new(nodes_m: Vec<D::Point>, elements: Vec<D::Element>, limits: &D::Limits) -> Result<Self, D::MeshError> {
        let n = elements.len();
        Self::with_regions(nodes_m, elements, vec![0; n], vec!["tissue".to_owned()], BTreeMap::new(), limits)
    }

    /// Builds and validates a mesh with a region index per element (indices into
    /// `region_names`, extended with generated names `region<k>` if too short) and named boundary
    /// node sets (sorted and deduplicated here). Elements are stored in [`Dim::orient`]'s
    /// orientation.
    pub fn with_regions(
        nodes_m: Vec<D::Point>,
        elements: Vec<D::Element>,
        region_of_element: Vec<usize>,
        mut region_names: Vec<String>,
        mut boundary_sets: BTreeMap<String, Vec<usize>>,
        limits: &D::Limits,
    ) -> Result<Self, D::MeshError> {
        if region_of_element.len() != elements.len() {
            return Err(MeshFault::RegionCount { n_elements: elements.len(), n_regions: region_of_element.len() }.into());
        }
        let n_regions = region_of_element.iter().copied().max().map_or(0, |m| m + 1);
        while region_names.len() < n_regions {
            region_names.push(format!("region{}", region_names.len()));
        }
        for v in boundary_sets.values_mut() {
            v.sort_unstable();
            v.dedup();
        }
        let mut mesh = Self { nodes_m, elements, region_of_element, region_names, boundary_sets };
        mesh.validate(limits)?;
        for e in &mut mesh.elements {
            let p = D::element_points(&mesh.nodes_m, e);
            D::orient(e, &p);
        }
        Ok(mesh)
    }

    fn validate(&self, limits: &D::Limits) -> Result<(), D::MeshError> {
        let n_nodes = self.nodes_m.len();
        let (max_nodes, max_elements) = D::max_counts(limits);
        if self.elements.is_empty() || n_nodes == 0 {
            return Err(MeshFault::Empty.into());
        }
        if n_nodes > max_nodes {
            return Err(MeshFault::TooManyNodes { n_nodes, max_nodes }.into());
        }
        if self.elements.len() > max_elements {
            return Err(MeshFault::TooManyElements { n_elements: self.elements.len(), max_elements }.into());
        }
        for (node_idx, &x_m) in self.nodes_m.iter().enumerate() {
            if !x_m.as_ref().iter().all(|v| v.is_finite()) {
                return Err(MeshFault::NonFiniteNode { node_idx, x_m }.into());
            }
        }
        let mut used = vec![false; n_nodes];
        for (elem_idx, e) in self.elements.iter().enumerate() {
            let ids = e.as_ref();
            for (k, &node_idx) in ids.iter().enumerate() {
                if node_idx >= n_nodes {
                    return Err(MeshFault::NodeOutOfRange { elem_idx, node_idx, n_nodes }.into());
                }
                if ids[..k].contains(&node_idx) {
                    return Err(MeshFault::RepeatedNode { elem_idx, node_idx }.into());
                }
                used[node_idx] = true;
            }
            D::check_shape(elem_idx, e, &D::element_points(&self.nodes_m, e))?;
        }
        let n_unused = used.iter().filter(|u| !**u).count();
        if let Some(node_idx) = used.iter().position(|u| !*u) {
            return Err(MeshFault::UnusedNode { node_idx, n_unused }.into());
        }
        for (set, nodes) in &self.boundary_sets {
            if let Some(&node_idx) = nodes.iter().find(|&&i| i >= n_nodes) {
                return Err(MeshFault::BoundaryNodeOutOfRange { set: set.clone(), node_idx, n_nodes }.into());
            }
        }
        let mut names: Vec<(&str, usize)> = self.region_names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
        names.sort_unstable();
        if let Some(w) = names.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(MeshFault::DuplicateRegionName { name: w[0].0.to_owned(), first_idx: w[0].1, second_idx: w[1].1 }.into());
        }
        D::check_conformity(self)
    }

    /// Nodes within `DUPLICATE_NODE_TOL × diagonal` of each other: nodes are binned into square
    /// (cubic) cells of that size (sorted by cell, $O(n \log n)$), and each is compared with the
    /// nodes of its own cell and of the neighbouring cells that come after it in the sort order.
    /// A 2D cell is a 3D one with $z$ index 0, so the pairs compared, and the first duplicate
    /// found, are those of the former 2D search.
    pub(crate) fn check_duplicate_nodes(&self) -> Result<(), D::MeshError> {
        let nodes = &self.nodes_m;
        let (lo, hi) = self.bounding_box_m();
        let tol_m = DUPLICATE_NODE_TOL * D::norm(D::point_from_fn(|k| hi[k] - lo[k]));
        if !(tol_m > 0.0) {
            return Ok(()); // a single point: degenerate elements were rejected before
        }
        // Cell indices stay far inside i64: the mesh spans at most 1e9 cells per axis.
        let cell = |p: D::Point| {
            let mut c = [0i64; 3];
            for k in 0..D::N {
                c[k] = ((p[k] - lo[k]) / tol_m).floor() as i64;
            }
            c
        };
        let mut keyed: Vec<([i64; 3], usize)> = nodes.iter().enumerate().map(|(i, &p)| (cell(p), i)).collect();
        keyed.sort_unstable();
        let close = |a: usize, b: usize| dist_sq::<D>(nodes[a], nodes[b]) <= tol_m * tol_m;
        let found = |a: usize, b: usize| {
            let (first_idx, second_idx) = (a.min(b), a.max(b));
            MeshFault::<D>::DuplicateNode { first_idx, second_idx, x_m: nodes[first_idx], tol_m }.into()
        };
        for (k, &([cx, cy, cz], a)) in keyed.iter().enumerate() {
            // Same column (cx, cy): the following entries with z cell cz or cz + 1.
            for &([cx2, cy2, cz2], b) in &keyed[k + 1..] {
                if cx2 != cx || cy2 != cy || cz2 > cz + 1 {
                    break;
                }
                if close(a, b) {
                    return Err(found(a, b));
                }
            }
            // The columns after it: (cx, cy + 1) and (cx + 1, cy - 1 ..= cy + 1), z cells cz ± 1.
            for (x, y) in [(cx, cy + 1), (cx + 1, cy - 1), (cx + 1, cy), (cx + 1, cy + 1)] {
                let start = keyed.partition_point(|e| e.0 < [x, y, cz - 1]);
                for &([x2, y2, z2], b) in &keyed[start..] {
                    if x2 != x || y2 != y || z2 > cz + 1 {
                        break;
                    }
                    if close(a, b) {
                        return Err(found(a, b));
                    }
                }
            }
        }
        Ok(())
    }

    /// Two elements with the same node set: sorted node lists, sorted, $O(n \log n)$.
    pub(crate) fn check_duplicate_elements(&self) -> Result<(), D::MeshError> {
        let mut sorted: Vec<(D::Element, usize)> = self
            .elements
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let mut s = *e;
                s.as_mut().sort_unstable();
                (s, i)
            })
            .collect();
        sorted.sort_unstable();
        match sorted.windows(2).find(|w| w[0].0 == w[1].0) {
            Some(w) => Err(MeshFault::DuplicateElement { first_idx: w[0].1, second_idx: w[1].1, nodes: w[0].0 }.into()),
            None => Ok(()),
        }
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes_m.len()
    }
    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.elements.len()
    }
    /// Number of DOFs, $N n$.
    pub fn n_dofs(&self) -> usize {
        D::N * self.nodes_m.len()
    }
    /// Node coordinates in metres.
    pub fn nodes_m(&self) -> &[D::Point] {
        &self.nodes_m
    }
    /// Elements as node index tuples, in [`Dim::orient`]'s orientation.
    pub fn elements(&self) -> &[D::Element] {
        &self.elements
    }
    /// The region index of each element.
    pub fn region_of_element(&self) -> &[usize] {
        &self.region_of_element
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
    pub fn set_boundary_set(&mut self, name: &str, mut nodes: Vec<usize>) -> Result<(), D::MeshError> {
        nodes.sort_unstable();
        nodes.dedup();
        if let Some(&node_idx) = nodes.iter().find(|&&i| i >= self.n_nodes()) {
            return Err(MeshFault::BoundaryNodeOutOfRange { set: name.to_owned(), node_idx, n_nodes: self.n_nodes() }.into());
        }
        self.boundary_sets.insert(name.to_owned(), nodes);
        Ok(())
    }
    /// The corner coordinates of element `elem_idx`.
    pub fn element_points_m(&self, elem_idx: usize) -> D::ElementPoints {
        D::element_points(&self.nodes_m, &self.elements[elem_idx])
    }
    /// The signed measure of element `elem_idx` ([`Dim::signed_measure`]: m² or m³).
    pub fn signed_measure(&self, elem_idx: usize) -> f64 {
        D::signed_measure(&self.element_points_m(elem_idx))
    }
    /// The axis-aligned bounding box `(min, max)` in m.
    pub fn bounding_box_m(&self) -> (D::Point, D::Point) {
        let mut lo = D::point_from_fn(|_| f64::INFINITY);
        let mut hi = D::point_from_fn(|_| f64::NEG_INFINITY);
        for p in &self.nodes_m {
            for k in 0..D::N {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }
    /// Nodes whose coordinate `axis` (0 = x, 1 = y, 2 = z) lies within `tol_m` of `value_m`, in
    /// index order.
    pub fn nodes_where(&self, axis: usize, value_m: f64, tol_m: f64) -> Vec<usize> {
        (0..self.n_nodes()).filter(|&i| (self.nodes_m[i][axis] - value_m).abs() <= tol_m).collect()
    }
}

/// The squared distance $|a - b|^2$, summed over the axes in order.
#[inline]
pub(crate) fn dist_sq<D: Dim>(a: D::Point, b: D::Point) -> f64 {
    let mut s = 0.0;
    for k in 0..D::N {
        let d = a[k] - b[k];
        s += d * d;
    }
    s
}
