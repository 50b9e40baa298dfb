//! Sparse Cholesky factorisation of the stiffness restricted to its free DOFs, with faer.
//!
//! The free block $K_{ff}$ is Jacobi-scaled, $\hat K = S K_{ff} S$ with $S = \mathrm{diag}(K_{ii}^{-1/2})$,
//! so that every diagonal entry is 1. Its Cholesky factor $\hat K = L L^\top$ is computed with a
//! fill-reducing ordering: symbolic analysis once ([`SparseCholesky::new`]), numeric factorisation
//! after, and solves reuse caller-owned scratch ([`CholeskyScratch`]) so they allocate nothing.
//!
//! A model with rigid-body motion (too few or badly placed fixed DOFs) has a singular $K_{ff}$.
//! On the scaled matrix the smallest pivot $L_{jj}^2$ of such a model is at round-off level,
//! while a constrained model's pivots stay far above it; pivots below [`SINGULAR_PIVOT`] are
//! reported as [`FactorError::Singular`].

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Mat, MatMut, Par, Side, Spec};

/// Smallest acceptable squared pivot of the Jacobi-scaled matrix (whose diagonal is 1).
pub const SINGULAR_PIVOT: f64 = 1e-12;

/// Errors of the factorisation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FactorError {
    /// Every DOF is constrained: there is nothing to solve for.
    #[error("every degree of freedom is constrained: nothing is free to move")]
    NothingFree,
    /// A free DOF has no stiffness at all (it belongs to no element).
    #[error("DOF {dof} (node {node}, {comp}) has zero stiffness")]
    ZeroStiffness { dof: usize, node: usize, comp: &'static str },
    /// The free block is singular: the model can move as a rigid body.
    #[error(
        "the stiffness is singular: the model can move as a rigid body (smallest scaled pivot {min_pivot:e}). Fix enough nodes to stop translation and rotation of every connected part"
    )]
    Singular { min_pivot: f64 },
    /// faer could not allocate or analyse the matrix.
    #[error("sparse factorisation failed: {0}")]
    Faer(String),
}

/// Maps global DOFs to the free DOFs of a reduced system.
#[derive(Debug, Clone, PartialEq)]
pub struct DofMap {
    free_of_dof: Vec<usize>,
    dof_of_free: Vec<usize>,
    dofs_per_node: usize,
}

impl DofMap {
    /// Marker for a constrained DOF in [`DofMap::free_index`].
    const CONSTRAINED: usize = usize::MAX;

    /// `constrained[d]` is true for each constrained DOF; 2 DOFs per node (2D, $d = 2\,\mathrm{node} + \mathrm{axis}$).
    pub fn new(constrained: &[bool]) -> Self {
        Self::with_dofs_per_node(constrained, 2)
    }

    /// As [`DofMap::new`] with `dofs_per_node` DOFs per node ($d = \mathrm{dofs\_per\_node}\cdot\mathrm{node} + \mathrm{axis}$):
    /// 2 in 2D, 3 in 3D. Only errors use it, to name the node and axis of a DOF.
    pub fn with_dofs_per_node(constrained: &[bool], dofs_per_node: usize) -> Self {
        assert!((1..=3).contains(&dofs_per_node), "1 to 3 DOFs per node");
        let mut free_of_dof = vec![Self::CONSTRAINED; constrained.len()];
        let mut dof_of_free = Vec::with_capacity(constrained.len());
        for (d, &c) in constrained.iter().enumerate() {
            if !c {
                free_of_dof[d] = dof_of_free.len();
                dof_of_free.push(d);
            }
        }
        Self { free_of_dof, dof_of_free, dofs_per_node }
    }
    /// DOFs per node (2 in 2D, 3 in 3D).
    pub fn dofs_per_node(&self) -> usize {
        self.dofs_per_node
    }
    /// The free index of a global DOF, or `None` when it is constrained.
    pub fn free_index(&self, dof: usize) -> Option<usize> {
        let f = self.free_of_dof[dof];
        (f != Self::CONSTRAINED).then_some(f)
    }
    /// Global DOF of each free index.
    pub fn free_dofs(&self) -> &[usize] {
        &self.dof_of_free
    }
    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.dof_of_free.len()
    }
    /// Number of global DOFs.
    pub fn n_dofs(&self) -> usize {
        self.free_of_dof.len()
    }
}

/// A factorised free block $K_{ff}$, ready for solves. Immutable once built, so one factor can
/// serve several threads, each with its own [`CholeskyScratch`].
#[derive(Debug)]
pub struct SparseCholesky {
    dofs: DofMap,
    symbolic: SymbolicCholesky<usize>,
    scaled_upper: SparseColMat<usize, f64>,
    l_values: Vec<f64>,
    scale: Vec<f64>,
    n_numeric_factorisations: u64,
}

/// Scratch for solves with up to `max_rhs` right-hand sides at once.
pub struct CholeskyScratch {
    buf: MemBuffer,
    max_rhs: usize,
}

impl SparseCholesky {
    /// Extracts the free block of the full stiffness `k_full` (both triangles stored), analyses
    /// its pattern once and factorises it.
    ///
    /// Errors: [`FactorError::NothingFree`] when every DOF is constrained,
    /// [`FactorError::ZeroStiffness`] when a free DOF has no stiffness, and
    /// [`FactorError::Singular`] when the model is not held against rigid-body motion.
    pub fn new(k_full: &SparseColMat<usize, f64>, dofs: DofMap) -> Result<Self, FactorError> {
        Self::with_params(k_full, dofs, CholeskySymbolicParams::default())
    }

    /// As [`SparseCholesky::new`], with faer's symbolic parameters (tests force the simplicial
    /// or the supernodal variant through them).
    pub fn with_params(k_full: &SparseColMat<usize, f64>, dofs: DofMap, params: CholeskySymbolicParams<'_>) -> Result<Self, FactorError> {
        Self::with_ordering(k_full, dofs, SymmetricOrdering::Amd, params)
    }

    /// As [`SparseCholesky::with_params`], with the fill-reducing ordering of the free DOFs (faer's
    /// AMD by default; a custom permutation, e.g. a nested dissection, in free-DOF numbering).
    pub fn with_ordering(
        k_full: &SparseColMat<usize, f64>,
        dofs: DofMap,
        ordering: SymmetricOrdering<'_, usize>,
        params: CholeskySymbolicParams<'_>,
    ) -> Result<Self, FactorError> {
        let n = dofs.n_free();
        if n == 0 {
            return Err(FactorError::NothingFree);
        }
        let sym = k_full.symbolic();
        let vals = k_full.val();
        let mut diag = vec![0.0; n];
        for (f, &d) in dofs.free_dofs().iter().enumerate() {
            for p in sym.col_ptr()[d]..sym.col_ptr()[d + 1] {
                if sym.row_idx()[p] == d {
                    diag[f] += vals[p];
                }
            }
        }
        if let Some(f) = diag.iter().position(|&v| !(v > 0.0)) {
            let dof = dofs.free_dofs()[f];
            let per = dofs.dofs_per_node();
            return Err(FactorError::ZeroStiffness { dof, node: dof / per, comp: ["x", "y", "z"][dof % per] });
        }
        let scale: Vec<f64> = diag.iter().map(|v| 1.0 / v.sqrt()).collect();
        let mut triplets = Vec::with_capacity(vals.len() / 2 + n);
        for (fj, &dj) in dofs.free_dofs().iter().enumerate() {
            for p in sym.col_ptr()[dj]..sym.col_ptr()[dj + 1] {
                if let Some(fi) = dofs.free_index(sym.row_idx()[p])
                    && fi <= fj
                {
                    triplets.push(Triplet::new(fi, fj, vals[p] * scale[fi] * scale[fj]));
                }
            }
        }
        let scaled_upper = SparseColMat::try_new_from_triplets(n, n, &triplets).map_err(|e| FactorError::Faer(format!("{e:?}")))?;
        let symbolic = factorize_symbolic_cholesky(scaled_upper.symbolic(), Side::Upper, ordering, params)
            .map_err(|e| FactorError::Faer(format!("{e:?}")))?;
        let mut this = Self { dofs, l_values: vec![0.0; symbolic.len_val()], symbolic, scaled_upper, scale, n_numeric_factorisations: 0 };
        this.factorize_numeric()?;
        Ok(this)
    }

    fn factorize_numeric(&mut self) -> Result<(), FactorError> {
        let par = Par::Seq;
        let req = self.symbolic.factorize_numeric_llt_scratch::<f64>(par, Spec::default());
        let mut buf = MemBuffer::try_new(req).map_err(|e| FactorError::Faer(format!("{e:?}")))?;
        self.n_numeric_factorisations += 1;
        let result = self.symbolic.factorize_numeric_llt::<f64>(
            &mut self.l_values,
            self.scaled_upper.as_ref(),
            Side::Upper,
            LltRegularization::default(),
            par,
            MemStack::new(&mut buf),
            Spec::default(),
        );
        if result.is_err() {
            return Err(FactorError::Singular { min_pivot: 0.0 });
        }
        let min_pivot = self.min_squared_pivot();
        if !(min_pivot > SINGULAR_PIVOT) {
            return Err(FactorError::Singular { min_pivot });
        }
        Ok(())
    }

    /// The smallest squared diagonal entry $L_{jj}^2$ of the scaled factor.
    pub fn min_squared_pivot(&self) -> f64 {
        let mut min = f64::INFINITY;
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let col_ptr = s.col_ptr();
                for j in 0..s.ncols() {
                    min = min.min(self.l_values[col_ptr[j]].powi(2));
                }
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let llt = faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef::new(s, &self.l_values);
                for k in 0..s.n_supernodes() {
                    let m = llt.supernode(k).val();
                    for j in 0..m.ncols() {
                        min = min.min(m[(j, j)].powi(2));
                    }
                }
            }
        }
        min
    }

    /// The DOF map of this reduced system.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }
    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.dofs.n_free()
    }
    /// How many numeric factorisations this object has performed (1 after construction).
    pub fn n_numeric_factorisations(&self) -> u64 {
        self.n_numeric_factorisations
    }
    /// Whether faer chose the supernodal variant.
    pub fn is_supernodal(&self) -> bool {
        matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_))
    }
    /// Non-zeros of the factor $L$.
    pub fn factor_nnz(&self) -> usize {
        self.l_values.len()
    }
    /// faer's symbolic factorisation: the fill-reducing permutation ([`SymbolicCholesky::perm`])
    /// and the simplicial or supernodal structure of $L$. Read by
    /// [`crate::compliance::sparse`], which walks $L$ itself.
    pub fn symbolic(&self) -> &SymbolicCholesky<usize> {
        &self.symbolic
    }
    /// The numeric values of $L$ (the factor of the Jacobi-scaled, permuted $\hat K$), laid out as
    /// [`SparseCholesky::symbolic`] describes.
    pub fn l_values(&self) -> &[f64] {
        &self.l_values
    }
    /// The Jacobi scaling $S = \mathrm{diag}(K_{ii}^{-1/2})$ per free DOF: $K_{ff}^{-1} = S \hat K^{-1} S$.
    pub fn scale(&self) -> &[f64] {
        &self.scale
    }

    /// Scratch for solves with up to `max_rhs` right-hand sides; allocate it once, outside any
    /// real-time loop.
    pub fn scratch(&self, max_rhs: usize) -> CholeskyScratch {
        let req = self.symbolic.solve_in_place_scratch::<f64>(max_rhs.max(1), Par::Seq);
        CholeskyScratch { buf: MemBuffer::new(req), max_rhs: max_rhs.max(1) }
    }

    /// Writes the compliance columns of node `node_idx` into `out`: for each of its $p$ DOFs
    /// ($p$ = [`DofMap::dofs_per_node`]) the column $K_{ff}^{-1} e$ of a unit load, over all DOFs
    /// (zero at constrained ones), one after another ($p \cdot N$ values, $N$ = all DOFs). A node
    /// with constrained DOFs gets zero columns. `rhs` is $n_{free} \times p$ scratch. Allocates
    /// nothing; panics only on a programming error (`out`, `rhs` or `scratch` of the wrong size).
    pub fn node_columns_into(&self, node_idx: usize, out: &mut [f64], rhs: &mut Mat<f64>, scratch: &mut CholeskyScratch) {
        let dofs = &self.dofs;
        let (per, n_dofs) = (dofs.dofs_per_node(), dofs.n_dofs());
        assert_eq!(out.len(), per * n_dofs, "out holds {per} full columns");
        out.fill(0.0);
        if (0..per).any(|axis| dofs.free_index(per * node_idx + axis).is_none()) {
            return;
        }
        rhs.fill(0.0);
        for axis in 0..per {
            let f = dofs.free_index(per * node_idx + axis).expect("checked above");
            rhs[(f, axis)] = 1.0;
        }
        self.solve_in_place(rhs.as_mut(), scratch);
        for axis in 0..per {
            let col = &mut out[axis * n_dofs..(axis + 1) * n_dofs];
            for (f, &d) in dofs.free_dofs().iter().enumerate() {
                col[d] = rhs[(f, axis)];
            }
        }
    }

    /// Solves $K_{ff} X = B$ in place for the columns of `rhs` (free-DOF numbering). Allocates
    /// nothing; panics only on a programming error (wrong row count, or more columns than the
    /// scratch was sized for).
    pub fn solve_in_place(&self, mut rhs: MatMut<'_, f64>, scratch: &mut CholeskyScratch) {
        assert_eq!(rhs.nrows(), self.n_free(), "rhs rows must equal the free DOFs");
        assert!(rhs.ncols() <= scratch.max_rhs, "scratch sized for {} rhs", scratch.max_rhs);
        // K_ff = S^-1 K^ S^-1, so K_ff x = b  <=>  K^ (S^-1 x) = S b.
        for j in 0..rhs.ncols() {
            for i in 0..rhs.nrows() {
                rhs[(i, j)] *= self.scale[i];
            }
        }
        LltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            rhs.as_mut(),
            Par::Seq,
            MemStack::new(&mut scratch.buf),
        );
        for j in 0..rhs.ncols() {
            for i in 0..rhs.nrows() {
                rhs[(i, j)] *= self.scale[i];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::{MaterialMap, assemble_stiffness};
    use crate::material::{Material, PlaneModel};
    use crate::mesh::{MeshLimits, RectMeshParams};
    use faer::Mat;
    use faer::sparse::linalg::SupernodalThreshold;

    fn model(nx: usize) -> (crate::mesh::Mesh, SparseColMat<usize, f64>) {
        let mesh = RectMeshParams::new(nx, nx, 0.1, 0.1).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }],
            PlaneModel::Strain { thickness_m: 1.0 },
        )
        .unwrap();
        let k = assemble_stiffness(&mesh, &mats, None);
        (mesh, k)
    }

    fn bottom_fixed(mesh: &crate::mesh::Mesh) -> DofMap {
        let mut c = vec![false; 2 * mesh.n_nodes()];
        for &n in mesh.boundary_set("bottom").unwrap() {
            c[2 * n] = true;
            c[2 * n + 1] = true;
        }
        DofMap::new(&c)
    }

    #[test]
    fn solve_matches_dense_for_both_variants() {
        let (mesh, k) = model(7);
        let dofs = bottom_fixed(&mesh);
        let kd = k.to_dense();
        let free = dofs.free_dofs().to_vec();
        let kff = Mat::from_fn(free.len(), free.len(), |i, j| kd[(free[i], free[j])]);
        let b = Mat::from_fn(free.len(), 2, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
            let f = SparseCholesky::with_params(&k, dofs.clone(), params).unwrap();
            assert_eq!(f.is_supernodal(), threshold == SupernodalThreshold::FORCE_SUPERNODAL);
            let mut x = b.clone();
            let mut scratch = f.scratch(2);
            f.solve_in_place(x.as_mut(), &mut scratch);
            let r = &kff * &x - &b;
            assert!(r.norm_max() < 1e-12 * b.norm_max() * 1e3, "residual {}", r.norm_max());
            // The smallest pivot agrees with the dense factor's, within the ordering-independent
            // bound: min over pivots is at least λ_min of the scaled matrix.
            assert!(f.min_squared_pivot() > SINGULAR_PIVOT);
        }
    }

    #[test]
    fn rigid_body_motion_is_detected_in_both_variants() {
        let (mesh, k) = model(6);
        // Only the x DOFs of the bottom edge fixed: the body can still translate in y.
        let mut c = vec![false; 2 * mesh.n_nodes()];
        for &n in mesh.boundary_set("bottom").unwrap() {
            c[2 * n] = true;
        }
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
            let e = SparseCholesky::with_params(&k, DofMap::new(&c), params).unwrap_err();
            assert!(matches!(e, FactorError::Singular { .. }), "{e}");
            assert!(e.to_string().contains("rigid body"), "{e}");
        }
        // Nothing fixed at all.
        let e = SparseCholesky::new(&k, DofMap::new(&vec![false; 2 * mesh.n_nodes()])).unwrap_err();
        assert!(matches!(e, FactorError::Singular { .. }), "{e}");
        let e = SparseCholesky::new(&k, DofMap::new(&vec![true; 2 * mesh.n_nodes()])).unwrap_err();
        assert_eq!(e, FactorError::NothingFree);
    }
}
