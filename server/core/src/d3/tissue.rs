//! The 3D tissue model and its compliance on demand: columns of $C = K_{ff}^{-1}$ for the nodes a
//! needle touches, from one sparse factorisation, and the point compliance $W = P C P^\top$.
//!
//! [`TetTissueModel`] assembles $K$ ($3n \times 3n$), removes the fixed nodes and factorises
//! $K_{ff}$ once. The three columns of node $w$ are three sparse solves,
//! $K_{ff}\,[c_x, c_y, c_z] = [e_{3w}, e_{3w+1}, e_{3w+2}]$, cost $O(\mathrm{nnz}(L))$, written over all
//! $3n$ DOFs with zeros at fixed DOFs ([`TetTissueModel::compliance_columns_into`], no allocation
//! once its [`TetColumnScratch`] exists). A material point $x$ in a tetrahedron with nodes $k_i$ and
//! weights $N_i(x)$ ([`TetTissueModel::locate`]) has the block
//! $W_{ab} = \sum_{i,j} N_{a,i} N_{b,j}\, C_{k_{a,i} k_{b,j}}$ (3 × 3 blocks of $C$).

use faer::Mat;
use faer::sparse::SparseColMat;

use super::assembly::{TetMaterials, assemble_stiffness};
use super::locate::{LocateError, PointLocation, TetLocator};
use super::mesh::TetMesh;
use crate::factor::{CholeskyScratch, DofMap, FactorError, SparseCholesky};

/// Errors of the 3D tissue model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TetTissueError {
    /// A fixed node id does not exist (at construction).
    #[error("fixed node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownFixedNode { node_idx: usize, n_nodes: usize },
    /// A node id asked for does not exist (column computation).
    #[error("node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownNode { node_idx: usize, n_nodes: usize },
    /// No node is fixed (at construction): the tissue would float.
    #[error("no node is fixed: the tissue needs a fixed boundary")]
    NoFixedNodes,
    /// A point lies outside the mesh (point compliance).
    #[error("working point {point_idx}: {source}")]
    Locate { point_idx: usize, source: LocateError },
    /// The factorisation failed (at construction; rigid-body motion, for example).
    #[error(transparent)]
    Factor(#[from] FactorError),
}

/// The 3D tissue: mesh, materials, fixed nodes, $K$, the factorised $K_{ff}$ and a point locator.
/// Immutable once built, so it can be shared (`Arc`) between threads.
#[derive(Debug)]
pub struct TetTissueModel {
    mesh: TetMesh,
    materials: TetMaterials,
    fixed: Vec<bool>,
    stiffness: SparseColMat<usize, f64>,
    chol: SparseCholesky,
    locator: TetLocator,
}

/// Scratch for [`TetTissueModel::compliance_columns_into`]; allocate once per thread.
pub struct TetColumnScratch {
    rhs: Mat<f64>,
    chol: CholeskyScratch,
}

/// Nodes per leaf of the nested dissection (a leaf's nodes are ordered as they come; below a few
/// dozen the separators cost more than they save).
const ND_LEAF_NODES: usize = 64;
/// Meshes with fewer nodes are ordered by faer's AMD, which fills less on small meshes.
const ND_MIN_NODES: usize = 2000;

impl TetTissueModel {
    /// Assembles and factorises. Errors when a fixed node does not exist, when no node is fixed,
    /// and when the model is singular (see [`FactorError`]).
    pub fn new(mesh: TetMesh, materials: TetMaterials, fixed_nodes: &[usize]) -> Result<Self, TetTissueError> {
        let n_nodes = mesh.n_nodes();
        if fixed_nodes.is_empty() {
            return Err(TetTissueError::NoFixedNodes);
        }
        let mut fixed = vec![false; n_nodes];
        for &node_idx in fixed_nodes {
            if node_idx >= n_nodes {
                return Err(TetTissueError::UnknownFixedNode { node_idx, n_nodes });
            }
            fixed[node_idx] = true;
        }
        let stiffness = assemble_stiffness(&mesh, &materials);
        let constrained: Vec<bool> = (0..3 * n_nodes).map(|d| fixed[d / 3]).collect();
        // A nested-dissection ordering: on box grids 25–45 % less fill than faer's AMD, factorised
        // 2.6–5.5 times faster, and shorter elimination-tree reaches for the sparse compliance rows
        // (BENCHMARKS.md, d3::sparse_compliance's timing).
        // Below ND_MIN_NODES AMD fills less (a 6³ box: 76 k against 49 k non-zeros).
        let dofs = DofMap::with_dofs_per_node(&constrained, 3);
        let chol = if n_nodes < ND_MIN_NODES {
            SparseCholesky::new(&stiffness, dofs)?
        } else {
            let fwd = super::sparse_compliance::nested_dissection_order(&mesh, &dofs, ND_LEAF_NODES);
            let mut inv = vec![0usize; fwd.len()];
            for (k, &f) in fwd.iter().enumerate() {
                inv[f] = k;
            }
            let perm = faer::perm::PermRef::new_checked(&fwd, &inv, fwd.len());
            SparseCholesky::with_ordering(
                &stiffness,
                dofs,
                faer::sparse::linalg::cholesky::SymmetricOrdering::Custom(perm),
                Default::default(),
            )?
        };
        let locator = TetLocator::new(&mesh);
        Ok(Self { mesh, materials, fixed, stiffness, chol, locator })
    }

    /// The mesh.
    pub fn mesh(&self) -> &TetMesh {
        &self.mesh
    }
    /// The materials.
    pub fn materials(&self) -> &TetMaterials {
        &self.materials
    }
    /// The full stiffness $K$ (all DOFs, both triangles).
    pub fn stiffness(&self) -> &SparseColMat<usize, f64> {
        &self.stiffness
    }
    /// The factorisation of $K_{ff}$.
    pub fn cholesky(&self) -> &SparseCholesky {
        &self.chol
    }
    /// Whether node `node_idx` is fixed.
    pub fn is_fixed(&self, node_idx: usize) -> bool {
        self.fixed[node_idx]
    }
    /// Number of DOFs, $3n$.
    pub fn n_dofs(&self) -> usize {
        3 * self.mesh.n_nodes()
    }
    /// The tetrahedron holding `x_m` (reference position) and its barycentric weights.
    pub fn locate(&self, x_m: [f64; 3]) -> Result<PointLocation, LocateError> {
        self.locator.locate(&self.mesh, x_m)
    }
    /// Scratch for column computations.
    pub fn column_scratch(&self) -> TetColumnScratch {
        TetColumnScratch { rhs: Mat::zeros(self.chol.n_free(), 3), chol: self.chol.scratch(3) }
    }

    /// Writes the three compliance columns of node `node_idx` into `out` (length $3 \cdot 3n$: the
    /// column for a unit $f_x$, then $f_y$, then $f_z$, each over all DOFs, zero at fixed DOFs). A
    /// fixed node has zero columns. Errors only for an unknown node. Allocates nothing.
    pub fn compliance_columns_into(&self, node_idx: usize, out: &mut [f64], scratch: &mut TetColumnScratch) -> Result<(), TetTissueError> {
        let n_nodes = self.mesh.n_nodes();
        if node_idx >= n_nodes {
            return Err(TetTissueError::UnknownNode { node_idx, n_nodes });
        }
        self.chol.node_columns_into(node_idx, out, &mut scratch.rhs, &mut scratch.chol);
        Ok(())
    }

    /// The compliance $C_{ww}$ of the given nodes' DOFs, row-major $3m \times 3m$, order
    /// $[u_x(w_0), u_y(w_0), u_z(w_0), u_x(w_1), \dots]$ (allocates; not for the real-time thread).
    pub fn node_compliance(&self, nodes: &[usize]) -> Result<Vec<f64>, TetTissueError> {
        let unit = |n: usize| PointLocation { tet_idx: usize::MAX, nodes: [n; 4], weights: [1.0, 0.0, 0.0, 0.0] };
        self.point_compliance(&nodes.iter().map(|&n| unit(n)).collect::<Vec<_>>())
    }

    /// The point compliance $W = P K_{ff}^{-1} P^\top$ of located points, row-major
    /// $3m \times 3m$, order $[u_x(p_0), u_y(p_0), u_z(p_0), u_x(p_1), \dots]$, from the columns
    /// of the points' element nodes (allocates; not for the real-time thread). Errors only for an
    /// unknown node.
    pub fn point_compliance(&self, points: &[PointLocation]) -> Result<Vec<f64>, TetTissueError> {
        let n_dofs = self.n_dofs();
        let m = points.len();
        let d = 3 * m;
        let mut w = vec![0.0; d * d];
        let mut scratch = self.column_scratch();
        let mut cols = vec![0.0; 3 * n_dofs];
        // Column of W for force axis `axis` at point b: sum_j N_bj C[:, 3 k_bj + axis], restricted
        // by P on the rows.
        for (b, pb) in points.iter().enumerate() {
            for j in 0..4 {
                if pb.weights[j] == 0.0 {
                    continue;
                }
                self.compliance_columns_into(pb.nodes[j], &mut cols, &mut scratch)?;
                for axis in 0..3 {
                    let col = &cols[axis * n_dofs..(axis + 1) * n_dofs];
                    for (a, pa) in points.iter().enumerate() {
                        for r in 0..3 {
                            let v: f64 = (0..4).map(|i| pa.weights[i] * col[3 * pa.nodes[i] + r]).sum();
                            w[(3 * a + r) * d + 3 * b + axis] += pb.weights[j] * v;
                        }
                    }
                }
            }
        }
        // Symmetrise (the two triangles differ by solve round-off).
        for i in 0..d {
            for j in 0..i {
                let v = 0.5 * (w[i * d + j] + w[j * d + i]);
                w[i * d + j] = v;
                w[j * d + i] = v;
            }
        }
        Ok(w)
    }

    /// [`TetTissueModel::point_compliance`] at reference positions; errors name the point that
    /// lies outside the mesh.
    pub fn point_compliance_at(&self, x_m: &[[f64; 3]]) -> Result<Vec<f64>, TetTissueError> {
        let locs = x_m
            .iter()
            .enumerate()
            .map(|(point_idx, &x)| self.locate(x).map_err(|source| TetTissueError::Locate { point_idx, source }))
            .collect::<Result<Vec<_>, _>>()?;
        self.point_compliance(&locs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use nalgebra::DMatrix;

    fn model() -> TetTissueModel {
        let mesh = BoxGridParams::new([4, 3, 4], [0.1, 0.08, 0.1]).build(&TetMeshLimits::default()).unwrap();
        // Two materials: the upper half 5x stiffer.
        let mats: Vec<Material> = (0..mesh.n_tets())
            .map(|t| {
                let z = mesh.tet_points_m(t).iter().map(|p| p[2]).sum::<f64>() / 4.0;
                Material { young_modulus_pa: if z > 0.05 { 75e3 } else { 15e3 }, poisson_ratio: 0.45 }
            })
            .collect();
        let mats = TetMaterials::per_element(&mesh, mats).unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        TetTissueModel::new(mesh, mats, &fixed).unwrap()
    }

    /// The columns equal those of $K_{ff}^{-1}$ computed densely, zero at the fixed DOFs.
    #[test]
    fn columns_equal_the_dense_inverse() {
        let m = model();
        let n_dofs = m.n_dofs();
        let kd = m.stiffness().to_dense();
        let free: Vec<usize> = (0..n_dofs).filter(|&d| !m.is_fixed(d / 3)).collect();
        let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| kd[(free[i], free[j])]);
        let inv = kff.try_inverse().unwrap();
        let scale = inv.amax();
        let mut scratch = m.column_scratch();
        let mut out = vec![0.0; 3 * n_dofs];
        for node in [0, 13, 20, m.mesh().n_nodes() - 1] {
            m.compliance_columns_into(node, &mut out, &mut scratch).unwrap();
            for axis in 0..3 {
                let col = &out[axis * n_dofs..(axis + 1) * n_dofs];
                match free.iter().position(|&d| d == 3 * node + axis) {
                    None => assert!(col.iter().all(|&v| v == 0.0), "fixed node {node} has zero columns"),
                    Some(j) => {
                        for d in 0..n_dofs {
                            let want = free.iter().position(|&f| f == d).map_or(0.0, |i| inv[(i, j)]);
                            assert!((col[d] - want).abs() < 1e-10 * scale, "node {node} axis {axis} dof {d}: {} vs {want}", col[d]);
                        }
                    }
                }
            }
        }
        // The node compliance block is the dense one.
        let nodes = [13, 20];
        let c = m.node_compliance(&nodes).unwrap();
        for (a, &na) in nodes.iter().enumerate() {
            for (b, &nb) in nodes.iter().enumerate() {
                for r in 0..3 {
                    for s in 0..3 {
                        let i = free.iter().position(|&f| f == 3 * na + r).unwrap();
                        let j = free.iter().position(|&f| f == 3 * nb + s).unwrap();
                        assert!((c[(3 * a + r) * 6 + 3 * b + s] - inv[(i, j)]).abs() < 1e-10 * scale);
                    }
                }
            }
        }
        assert_eq!(
            m.compliance_columns_into(999, &mut out, &mut scratch).unwrap_err(),
            TetTissueError::UnknownNode { node_idx: 999, n_nodes: 48 }
        );
    }

    /// $W = P C P^\top$ against the dense product at random material points.
    #[test]
    fn point_compliance_is_p_c_pt() {
        let m = model();
        let n_dofs = m.n_dofs();
        let kd = m.stiffness().to_dense();
        let free: Vec<usize> = (0..n_dofs).filter(|&d| !m.is_fixed(d / 3)).collect();
        let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| kd[(free[i], free[j])]);
        let inv = kff.try_inverse().unwrap();
        let xs = [[0.031, 0.042, 0.077], [0.051, 0.011, 0.033], [0.099, 0.07, 0.1]];
        let w = m.point_compliance_at(&xs).unwrap();
        let locs: Vec<PointLocation> = xs.iter().map(|&x| m.locate(x).unwrap()).collect();
        let mut p = DMatrix::<f64>::zeros(9, free.len());
        for (a, l) in locs.iter().enumerate() {
            for i in 0..4 {
                for r in 0..3 {
                    if let Some(f) = free.iter().position(|&d| d == 3 * l.nodes[i] + r) {
                        p[(3 * a + r, f)] += l.weights[i];
                    }
                }
            }
        }
        let want = &p * &inv * p.transpose();
        let scale = want.amax();
        for i in 0..9 {
            for j in 0..9 {
                assert!((w[i * 9 + j] - want[(i, j)]).abs() < 1e-10 * scale, "({i}, {j})");
            }
        }
        let e = m.point_compliance_at(&[[0.0, 0.0, 0.5]]).unwrap_err();
        assert!(e.to_string().starts_with("working point 0: the point"), "{e}");
    }

    /// Timing on the 21³ box grid (48 000 tetrahedra), bottom fixed; run in release:
    /// `cargo test --release -p needlesim-core --lib d3::tissue::tests::timing_21_cubed -- --ignored --nocapture`.
    #[test]
    #[ignore = "timing; run in release"]
    fn timing_21_cubed() {
        use std::time::Instant;
        let t0 = Instant::now();
        let mesh = BoxGridParams::new([21, 21, 21], [0.1, 0.1, 0.1]).build(&TetMeshLimits::default()).unwrap();
        let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }]).unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        let t_mesh = t0.elapsed();
        let t1 = Instant::now();
        let m = TetTissueModel::new(mesh, mats, &fixed).unwrap();
        let t_model = t1.elapsed();
        let mut scratch = m.column_scratch();
        let mut out = vec![0.0; 3 * m.n_dofs()];
        let nodes: Vec<usize> = (0..m.mesh().n_nodes()).filter(|&n| !m.is_fixed(n)).step_by(37).take(200).collect();
        let t2 = Instant::now();
        for &n in &nodes {
            m.compliance_columns_into(n, &mut out, &mut scratch).unwrap();
        }
        let per_node = t2.elapsed() / nodes.len() as u32;
        println!(
            "21^3 box: {} nodes, {} tets, factor nnz {}, mesh {:?}, assemble + factorise (and locator) {:?}, 3 columns per node {:?} (mean of {})",
            m.mesh().n_nodes(),
            m.mesh().n_tets(),
            m.cholesky().factor_nnz(),
            t_mesh,
            t_model,
            per_node,
            nodes.len()
        );
    }
}
