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
//!
//! The displacement of every node under point loads $f_i$ at material points $X_i$ (the needle's
//! contacts of one tick) is one solve with the same factor
//! ([`TetTissueModel::displacement_for_point_loads_into`]):
//! $$u = C\,F = K_{ff}^{-1} F, \qquad F = P^\top f = \sum_i \sum_{a} N_a(X_i)\, e_{k_a(X_i)} \otimes f_i,$$
//! i.e. $u = \sum_i \sum_a N_a(X_i)\, C_{\cdot, k_a} f_i$ without forming a column — cost
//! $O(\mathrm{nnz}(L))$ however many points, and by linearity $P u = W f$ at the points themselves.

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
    /// Point loads: the number of forces is not the number of points.
    #[error("{n_forces} forces for {n_points} load points: one force per point")]
    LoadCount { n_points: usize, n_forces: usize },
    /// Point loads: a force has a NaN or infinite component.
    #[error("the force {force_n:?} N at load point {point_idx} is not finite")]
    NonFiniteForce { point_idx: usize, force_n: [f64; 3] },
    /// Point loads: the output slice does not hold one value per DOF.
    #[error("the displacement output holds {len} values; the model has {n_dofs} DOFs")]
    OutputLength { len: usize, n_dofs: usize },
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

/// Scratch for [`TetTissueModel::compliance_columns_into`] and
/// [`TetTissueModel::displacement_for_point_loads_into`]; allocate once per thread.
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

    /// Writes into `out_m` (length $3n$, DOF $3\cdot\mathrm{node} + \mathrm{axis}$, m) the
    /// displacement of every node under the point loads `forces_n[i]` (N, world) at the located
    /// material points `points[i]`: $u = K_{ff}^{-1} P^\top f$ (module docs), zero at fixed DOFs.
    /// One sparse solve of one right-hand side, cost $O(\mathrm{nnz}(L))$ whatever the number of
    /// points; allocates nothing. Loads on a fixed node's DOFs go to the support (they move
    /// nothing). No points: $u = 0$.
    ///
    /// Errors (nothing is written): [`TetTissueError::LoadCount`] when `forces_n` and `points`
    /// differ in length, [`TetTissueError::OutputLength`] when `out_m` is not $3n$ long,
    /// [`TetTissueError::UnknownNode`] when a point names a node the mesh does not have, and
    /// [`TetTissueError::NonFiniteForce`] when a force component is NaN or infinite.
    pub fn displacement_for_point_loads_into(
        &self,
        points: &[PointLocation],
        forces_n: &[[f64; 3]],
        out_m: &mut [f64],
        scratch: &mut TetColumnScratch,
    ) -> Result<(), TetTissueError> {
        let (n_nodes, n_dofs) = (self.mesh.n_nodes(), self.n_dofs());
        if points.len() != forces_n.len() {
            return Err(TetTissueError::LoadCount { n_points: points.len(), n_forces: forces_n.len() });
        }
        if out_m.len() != n_dofs {
            return Err(TetTissueError::OutputLength { len: out_m.len(), n_dofs });
        }
        for (point_idx, (p, f)) in points.iter().zip(forces_n).enumerate() {
            if let Some(&node_idx) = p.nodes.iter().find(|&&v| v >= n_nodes) {
                return Err(TetTissueError::UnknownNode { node_idx, n_nodes });
            }
            if !f.iter().all(|x| x.is_finite()) {
                return Err(TetTissueError::NonFiniteForce { point_idx, force_n: *f });
            }
        }
        let dofs = self.chol.dofs();
        let mut rhs = scratch.rhs.as_mut().subcols_mut(0, 1);
        rhs.fill(0.0);
        for (p, f) in points.iter().zip(forces_n) {
            for (&node, &weight) in p.nodes.iter().zip(&p.weights) {
                for (axis, &f_axis) in f.iter().enumerate() {
                    if let Some(free) = dofs.free_index(3 * node + axis) {
                        rhs[(free, 0)] += weight * f_axis;
                    }
                }
            }
        }
        self.chol.solve_in_place(rhs.as_mut(), &mut scratch.chol);
        out_m.fill(0.0);
        for (free, &dof) in dofs.free_dofs().iter().enumerate() {
            out_m[dof] = rhs[(free, 0)];
        }
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

    /// The displacement under point loads (one solve) equals $\sum_i \sum_a N_a C_{\cdot,a} f_i$
    /// built from the compliance columns, at every DOF (the surface nodes among them: the session's
    /// surface field is this sum restricted to them), is zero at the fixed DOFs, and at the points
    /// themselves equals $W f$ with the point compliance.
    #[test]
    fn point_load_displacement_is_the_sum_of_compliance_columns() {
        let m = model();
        let n_dofs = m.n_dofs();
        // Three points inside, one in a tetrahedron touching the fixed bottom (z = 4 mm).
        let xs = [[0.031, 0.042, 0.077], [0.051, 0.011, 0.033], [0.0712, 0.0555, 0.004], [0.0499, 0.0401, 0.0903]];
        let forces = [[0.3, -0.1, -0.8], [-0.05, 0.2, 0.4], [0.1, 0.1, -0.6], [0.0, -0.25, 0.15]];
        let locs: Vec<PointLocation> = xs.iter().map(|&x| m.locate(x).unwrap()).collect();
        assert!(locs.iter().any(|l| l.nodes.iter().any(|&v| m.is_fixed(v))), "a point next to the support");
        let mut scratch = m.column_scratch();
        let mut u = vec![f64::NAN; n_dofs];
        m.displacement_for_point_loads_into(&locs, &forces, &mut u, &mut scratch).unwrap();
        let mut want = vec![0.0; n_dofs];
        let mut cols = vec![0.0; 3 * n_dofs];
        for (l, f) in locs.iter().zip(&forces) {
            for (&node, &weight) in l.nodes.iter().zip(&l.weights) {
                m.compliance_columns_into(node, &mut cols, &mut scratch).unwrap();
                for (axis, &fa) in f.iter().enumerate() {
                    for (w, c) in want.iter_mut().zip(&cols[axis * n_dofs..(axis + 1) * n_dofs]) {
                        *w += weight * fa * c;
                    }
                }
            }
        }
        let scale = want.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        assert!(scale > 1e-6, "the loads move the tissue: {scale} m");
        for d in 0..n_dofs {
            assert!((u[d] - want[d]).abs() <= 1e-12 * scale, "dof {d}: {} vs {}", u[d], want[d]);
            if m.is_fixed(d / 3) {
                assert_eq!(u[d], 0.0, "fixed dof {d}");
            }
        }
        // At the points: P u = W f.
        let w = m.point_compliance(&locs).unwrap();
        let f: Vec<f64> = forces.iter().flatten().copied().collect();
        for (a, l) in locs.iter().enumerate() {
            for r in 0..3 {
                let pu: f64 = (0..4).map(|k| l.weights[k] * u[3 * l.nodes[k] + r]).sum();
                let wf: f64 = (0..f.len()).map(|j| w[(3 * a + r) * f.len() + j] * f[j]).sum();
                assert!((pu - wf).abs() <= 1e-12 * scale, "point {a} axis {r}: {pu} vs {wf}");
            }
        }
        // No points: no displacement, over whatever was there.
        m.displacement_for_point_loads_into(&[], &[], &mut u, &mut scratch).unwrap();
        assert!(u.iter().all(|&v| v == 0.0));
    }

    /// Bad input to the point-load solve is refused with the error naming it, and nothing is written.
    #[test]
    fn point_load_errors() {
        let m = model();
        let n_dofs = m.n_dofs();
        let mut scratch = m.column_scratch();
        let good = m.locate([0.05, 0.04, 0.05]).unwrap();
        let mut u = vec![7.0; n_dofs];
        let e = m.displacement_for_point_loads_into(&[good, good], &[[0.0; 3]], &mut u, &mut scratch).unwrap_err();
        assert_eq!(e, TetTissueError::LoadCount { n_points: 2, n_forces: 1 });
        let e = m.displacement_for_point_loads_into(&[good], &[[0.0; 3]], &mut u[1..], &mut scratch).unwrap_err();
        assert_eq!(e, TetTissueError::OutputLength { len: n_dofs - 1, n_dofs });
        let bad = PointLocation { nodes: [0, 1, 2, 48], ..good };
        let e = m.displacement_for_point_loads_into(&[good, bad], &[[0.0; 3]; 2], &mut u, &mut scratch).unwrap_err();
        assert_eq!(e, TetTissueError::UnknownNode { node_idx: 48, n_nodes: 48 });
        let e = m.displacement_for_point_loads_into(&[good, good], &[[0.0; 3], [0.0, f64::NAN, 1.0]], &mut u, &mut scratch).unwrap_err();
        assert!(matches!(e, TetTissueError::NonFiniteForce { point_idx: 1, .. }), "{e:?}");
        assert!(e.to_string().contains("load point 1"), "{e}");
        assert!(u.iter().all(|&v| v == 7.0), "nothing written on an error");
    }

    /// A 3D insertion's contact points sit where the one solve puts the tissue: interpolating
    /// $u = K_{ff}^{-1} P^\top f$ of the tick's contact forces at each contact's reference
    /// position gives its deformed position $x_i - X_i$ (the simulation's own displacements, from
    /// its point compliance); and the shared model solves the same from another thread.
    #[test]
    fn point_load_displacement_puts_the_contacts_where_the_simulation_has_them() {
        use crate::fixtures::{box_phantom3, box_phantom3_params};
        use crate::sim3::{BasePose3, Simulation3};
        let model = box_phantom3(9);
        let mut sim = Simulation3::new(model.clone(), box_phantom3_params([0.0513, 0.0487, 0.1], 0.005)).unwrap();
        let start = sim.pose();
        let p0 = start.position_m;
        // 40 mm down, then 1.5 mm sideways (lateral loads too).
        for k in 1..=2000 {
            sim.step(BasePose3::from_rotation([p0[0], p0[1], p0[2] - 2e-5 * k as f64], start.orientation)).unwrap();
            sim.prefetch_columns(usize::MAX).unwrap();
        }
        for k in 1..=150 {
            sim.step(BasePose3::from_rotation([p0[0] + 1e-5 * k as f64, p0[1], p0[2] - 0.04], start.orientation)).unwrap();
            sim.prefetch_columns(usize::MAX).unwrap();
        }
        let out = sim.output();
        assert!(out.contacts.len() >= 2, "the needle holds points: {}", out.contacts.len());
        let locs: Vec<PointLocation> = out.contacts.iter().map(|c| model.locate(c.x_ref_m).unwrap()).collect();
        let forces: Vec<[f64; 3]> = out.contacts.iter().map(|c| c.force_n).collect();
        let mut u = vec![0.0; model.n_dofs()];
        model.displacement_for_point_loads_into(&locs, &forces, &mut u, &mut model.column_scratch()).unwrap();
        let (mut err, mut size, mut lateral) = (0.0_f64, 0.0_f64, 0.0_f64);
        for (c, l) in out.contacts.iter().zip(&locs) {
            for r in 0..3 {
                let at: f64 = (0..4).map(|k| l.weights[k] * u[3 * l.nodes[k] + r]).sum();
                let want = c.x_m[r] - c.x_ref_m[r];
                err = err.max((at - want).abs());
                size = size.max(want.abs());
            }
            lateral = lateral.max(c.force_n[0].abs());
        }
        assert!(size > 1e-4 && lateral > 1e-3, "the tissue moved ({size} m) under lateral loads ({lateral} N)");
        assert!(err <= 1e-9 * size, "contacts off their solved positions by {err:e} m (displacements up to {size:e} m)");
        let (m2, l2, f2) = (model.clone(), locs.clone(), forces.clone());
        let other = std::thread::spawn(move || {
            let mut u = vec![0.0; m2.n_dofs()];
            m2.displacement_for_point_loads_into(&l2, &f2, &mut u, &mut m2.column_scratch()).unwrap();
            u
        })
        .join()
        .unwrap();
        assert_eq!(other, u, "the same solve from another thread");
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
