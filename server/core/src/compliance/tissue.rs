//! The tissue model, written once over the dimension ([`Dim2`], [`Dim3`]): mesh, materials, fixed
//! nodes, $K$ and one sparse factorisation of $K_{ff}$, and the compliance read from it.
//!
//! [`TissueModel`] assembles $K$ ($Nn \times Nn$), removes the fixed nodes and factorises $K_{ff}$
//! once. The $N$ columns of node $w$ are $N$ sparse solves,
//! $K_{ff}\,[c_x, c_y(, c_z)] = [e_{Nw}, e_{Nw+1}(, e_{Nw+2})]$, cost $O(\mathrm{nnz}(L))$, written
//! over all $Nn$ DOFs with zeros at fixed DOFs ([`TissueModel::compliance_columns_into`], no
//! allocation once its [`ColumnScratch`] exists). A material point $x$ in an element with nodes
//! $k_i$ and weights $N_i(x)$ ([`TissueModel::locate`], 3D) has the block
//! $W_{ab} = \sum_{i,j} N_{a,i} N_{b,j}\, C_{k_{a,i} k_{b,j}}$ ($N \times N$ blocks of $C$).
//!
//! The displacement of every node under point loads $f_i$ at material points $X_i$ (the needle's
//! contacts of one tick) is one solve with the same factor
//! ([`TissueModel::displacement_for_point_loads_into`]):
//! $$u = C\,F = K_{ff}^{-1} F, \qquad F = P^\top f = \sum_i \sum_{a} N_a(X_i)\, e_{k_a(X_i)} \otimes f_i,$$
//! i.e. $u = \sum_i \sum_a N_a(X_i)\, C_{\cdot, k_a} f_i$ without forming a column — cost
//! $O(\mathrm{nnz}(L))$ however many points, and by linearity $P u = W f$ at the points themselves.
//!
//! **Per dimension** (from [`Dim`]): the fill-reducing ordering ([`Dim::NESTED_DISSECTION_MIN_NODES`]:
//! 2D always faer's AMD, so its results are those it always had; 3D a nested dissection from
//! 2000 nodes) and the point locator ([`Dim::locator`]: 3D [`crate::d3::TetLocator`]; 2D none, its
//! material points are located by the simulation's own triangle search). [`TissueModel`] without
//! a dimension is the 2D one; [`crate::d3::TetTissueModel`] and its companions are the 3D aliases.

use faer::Mat;
use faer::sparse::SparseColMat;

use crate::assembly::{ElementMaterials, assemble_stiffness_with};
use crate::dim::{Dim, Dim2};
use crate::factor::{CholeskyScratch, DofMap, FactorError, SparseCholesky};
use crate::mesh::SimplexMesh;

/// Errors of the tissue model and its compliance.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TissueError<D: Dim = Dim2> {
    /// A fixed node id does not exist (at construction).
    #[error("fixed node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownFixedNode { node_idx: usize, n_nodes: usize },
    /// A node id asked for does not exist (column computation, point loads).
    #[error("node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownNode { node_idx: usize, n_nodes: usize },
    /// No node is fixed (at construction): the tissue would float.
    #[error("no node is fixed: the tissue needs a fixed boundary")]
    NoFixedNodes,
    /// A point lies outside the mesh (point compliance; in 2D, any point).
    #[error("working point {point_idx}: {source}")]
    Locate { point_idx: usize, source: D::LocateError },
    /// Point loads: the number of forces is not the number of points.
    #[error("{n_forces} forces for {n_points} load points: one force per point")]
    LoadCount { n_points: usize, n_forces: usize },
    /// Point loads: a force has a NaN or infinite component.
    #[error("the force {force_n:?} N at load point {point_idx} is not finite")]
    NonFiniteForce { point_idx: usize, force_n: D::Point },
    /// Point loads: the output slice does not hold one value per DOF.
    #[error("the displacement output holds {len} values; the model has {n_dofs} DOFs")]
    OutputLength { len: usize, n_dofs: usize },
    /// The factorisation failed (at construction; rigid-body motion, for example).
    #[error(transparent)]
    Factor(#[from] FactorError),
}

/// The tissue: mesh, materials, fixed nodes, $K$, the factorised $K_{ff}$ and (3D) a point
/// locator. Immutable once built, so it can be shared (`Arc`) between the real-time thread and
/// column workers.
#[derive(Debug)]
pub struct TissueModel<D: Dim = Dim2> {
    mesh: SimplexMesh<D>,
    materials: ElementMaterials<D>,
    fixed: Vec<bool>,
    stiffness: SparseColMat<usize, f64>,
    chol: SparseCholesky,
    locator: D::Locator,
}

/// Scratch for [`TissueModel::compliance_columns_into`] and
/// [`TissueModel::displacement_for_point_loads_into`]; allocate once per thread.
pub struct ColumnScratch {
    rhs: Mat<f64>,
    chol: CholeskyScratch,
}

/// Nodes per leaf of the nested dissection (a leaf's nodes are ordered as they come; below a few
/// dozen the separators cost more than they save).
const ND_LEAF_NODES: usize = 64;

impl<D: Dim> TissueModel<D> {
    /// Assembles and factorises. Errors when a fixed node does not exist, when no node is fixed,
    /// and when the model is singular (see [`FactorError`]).
    pub fn new(mesh: SimplexMesh<D>, materials: ElementMaterials<D>, fixed_nodes: &[usize]) -> Result<Self, TissueError<D>> {
        let n_nodes = mesh.n_nodes();
        if fixed_nodes.is_empty() {
            return Err(TissueError::NoFixedNodes);
        }
        let mut fixed = vec![false; n_nodes];
        for &node_idx in fixed_nodes {
            if node_idx >= n_nodes {
                return Err(TissueError::UnknownFixedNode { node_idx, n_nodes });
            }
            fixed[node_idx] = true;
        }
        let stiffness = assemble_stiffness_with(&mesh, &materials, |_, _| {});
        let constrained: Vec<bool> = (0..D::N * n_nodes).map(|d| fixed[d / D::N]).collect();
        let dofs = DofMap::with_dofs_per_node(&constrained, D::N);
        // From NESTED_DISSECTION_MIN_NODES on, a nested-dissection ordering: on 3D box grids
        // 25–45 % less fill than faer's AMD, factorised 2.6–5.5 times faster, and shorter
        // elimination-tree reaches for the sparse compliance rows (BENCHMARKS.md,
        // compliance::sparse's timing). Below it AMD fills less (a 6³ box: 76 k against 49 k
        // non-zeros); 2D keeps AMD everywhere.
        let chol = match D::NESTED_DISSECTION_MIN_NODES {
            Some(min_nodes) if n_nodes >= min_nodes => {
                let fwd = super::sparse::nested_dissection_order(&mesh, &dofs, ND_LEAF_NODES);
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
            }
            _ => SparseCholesky::new(&stiffness, dofs)?,
        };
        let locator = D::locator(&mesh);
        Ok(Self { mesh, materials, fixed, stiffness, chol, locator })
    }

    /// The mesh.
    pub fn mesh(&self) -> &SimplexMesh<D> {
        &self.mesh
    }
    /// The materials.
    pub fn materials(&self) -> &ElementMaterials<D> {
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
    /// Number of DOFs, $Nn$.
    pub fn n_dofs(&self) -> usize {
        D::N * self.mesh.n_nodes()
    }
    /// The element holding `x_m` (reference position) and its barycentric weights (3D; a 2D
    /// model locates no point: [`crate::statics::tri::NoPointLocationError`]).
    pub fn locate(&self, x_m: D::Point) -> Result<D::PointLocation, D::LocateError> {
        D::locate(&self.locator, &self.mesh, x_m)
    }
    /// The point locator ([`Dim::locator`]; 3D: a [`crate::d3::TetLocator`]).
    pub fn locator(&self) -> &D::Locator {
        &self.locator
    }
    /// Scratch for column computations.
    pub fn column_scratch(&self) -> ColumnScratch {
        ColumnScratch { rhs: Mat::zeros(self.chol.n_free(), D::N), chol: self.chol.scratch(D::N) }
    }

    /// Writes the $N$ compliance columns of node `node_idx` into `out` (length $N \cdot Nn$: the
    /// column for a unit $f_x$, then $f_y$ (then $f_z$), each over all DOFs, zero at fixed DOFs).
    /// A fixed node has zero columns. Errors only for an unknown node. Allocates nothing.
    pub fn compliance_columns_into(&self, node_idx: usize, out: &mut [f64], scratch: &mut ColumnScratch) -> Result<(), TissueError<D>> {
        let n_nodes = self.mesh.n_nodes();
        if node_idx >= n_nodes {
            return Err(TissueError::UnknownNode { node_idx, n_nodes });
        }
        self.chol.node_columns_into(node_idx, out, &mut scratch.rhs, &mut scratch.chol);
        Ok(())
    }

    /// Writes into `out_m` (length $Nn$, DOF $N\cdot\mathrm{node} + \mathrm{axis}$, m) the
    /// displacement of every node under the point loads `forces_n[i]` (N, world) at the located
    /// material points `points[i]`: $u = K_{ff}^{-1} P^\top f$ (module docs), zero at fixed DOFs.
    /// One sparse solve of one right-hand side, cost $O(\mathrm{nnz}(L))$ whatever the number of
    /// points; allocates nothing. Loads on a fixed node's DOFs go to the support (they move
    /// nothing). No points: $u = 0$.
    ///
    /// Errors (nothing is written): [`TissueError::LoadCount`] when `forces_n` and `points`
    /// differ in length, [`TissueError::OutputLength`] when `out_m` is not $Nn$ long,
    /// [`TissueError::UnknownNode`] when a point names a node the mesh does not have, and
    /// [`TissueError::NonFiniteForce`] when a force component is NaN or infinite.
    pub fn displacement_for_point_loads_into(
        &self,
        points: &[D::PointLocation],
        forces_n: &[D::Point],
        out_m: &mut [f64],
        scratch: &mut ColumnScratch,
    ) -> Result<(), TissueError<D>> {
        let (n_nodes, n_dofs) = (self.mesh.n_nodes(), self.n_dofs());
        if points.len() != forces_n.len() {
            return Err(TissueError::LoadCount { n_points: points.len(), n_forces: forces_n.len() });
        }
        if out_m.len() != n_dofs {
            return Err(TissueError::OutputLength { len: out_m.len(), n_dofs });
        }
        for (point_idx, (p, f)) in points.iter().zip(forces_n).enumerate() {
            if let Some(&node_idx) = D::location_terms(p).1.iter().find(|&&v| v >= n_nodes) {
                return Err(TissueError::UnknownNode { node_idx, n_nodes });
            }
            if !f.as_ref().iter().all(|x| x.is_finite()) {
                return Err(TissueError::NonFiniteForce { point_idx, force_n: *f });
            }
        }
        let dofs = self.chol.dofs();
        let mut rhs = scratch.rhs.as_mut().subcols_mut(0, 1);
        rhs.fill(0.0);
        for (p, f) in points.iter().zip(forces_n) {
            let (_, nodes, weights) = D::location_terms(p);
            for (&node, &weight) in nodes.iter().zip(weights) {
                for (axis, &f_axis) in f.as_ref().iter().enumerate() {
                    if let Some(free) = dofs.free_index(D::dof(node, axis)) {
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

    /// The compliance $C_{ww}$ of the given nodes' DOFs, row-major $Nm \times Nm$, order
    /// $[u_x(w_0), u_y(w_0), (u_z(w_0),) u_x(w_1), \dots]$ (allocates; not for the real-time
    /// thread). Errors only for an unknown node.
    pub fn node_compliance(&self, nodes: &[usize]) -> Result<Vec<f64>, TissueError<D>> {
        // Each node as a point of weight 1 on it (and 0 on the element's other corners).
        let unit_nodes: Vec<Vec<usize>> = nodes.iter().map(|&n| vec![n; D::NODES_PER_ELEMENT]).collect();
        let weights: Vec<f64> = (0..D::NODES_PER_ELEMENT).map(|k| if k == 0 { 1.0 } else { 0.0 }).collect();
        let terms: Vec<(&[usize], &[f64])> = unit_nodes.iter().map(|n| (n.as_slice(), weights.as_slice())).collect();
        self.compliance_of_terms(&terms)
    }

    /// The point compliance $W = P K_{ff}^{-1} P^\top$ of located points, row-major
    /// $Nm \times Nm$, order $[u_x(p_0), u_y(p_0), (u_z(p_0),) u_x(p_1), \dots]$, from the columns
    /// of the points' element nodes (allocates; not for the real-time thread). Errors only for an
    /// unknown node.
    pub fn point_compliance(&self, points: &[D::PointLocation]) -> Result<Vec<f64>, TissueError<D>> {
        let terms: Vec<(&[usize], &[f64])> = points
            .iter()
            .map(|p| {
                let (_, nodes, weights) = D::location_terms(p);
                (nodes, weights)
            })
            .collect();
        self.compliance_of_terms(&terms)
    }

    /// $W = P C P^\top$ for points given as `(nodes, weights)`, $P_a = [N_{a,i} I]_i$.
    fn compliance_of_terms(&self, points: &[(&[usize], &[f64])]) -> Result<Vec<f64>, TissueError<D>> {
        let n_dofs = self.n_dofs();
        let m = points.len();
        let d = D::N * m;
        let mut w = vec![0.0; d * d];
        let mut scratch = self.column_scratch();
        let mut cols = vec![0.0; D::N * n_dofs];
        // Column of W for force axis `axis` at point b: sum_j N_bj C[:, N k_bj + axis], restricted
        // by P on the rows.
        for (b, &(nodes_b, weights_b)) in points.iter().enumerate() {
            for (&node_bj, &weight_bj) in nodes_b.iter().zip(weights_b) {
                if weight_bj == 0.0 {
                    continue;
                }
                self.compliance_columns_into(node_bj, &mut cols, &mut scratch)?;
                for axis in 0..D::N {
                    let col = &cols[axis * n_dofs..(axis + 1) * n_dofs];
                    for (a, &(nodes_a, weights_a)) in points.iter().enumerate() {
                        for r in 0..D::N {
                            let v: f64 = (0..nodes_a.len()).map(|i| weights_a[i] * col[D::dof(nodes_a[i], r)]).sum();
                            w[(D::N * a + r) * d + D::N * b + axis] += weight_bj * v;
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

    /// [`TissueModel::point_compliance`] at reference positions; errors name the point that
    /// lies outside the mesh.
    pub fn point_compliance_at(&self, x_m: &[D::Point]) -> Result<Vec<f64>, TissueError<D>> {
        let locs = x_m
            .iter()
            .enumerate()
            .map(|(point_idx, &x)| self.locate(x).map_err(|source| TissueError::Locate { point_idx, source }))
            .collect::<Result<Vec<_>, _>>()?;
        self.point_compliance(&locs)
    }
}
