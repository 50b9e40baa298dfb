//! Compliance entries of $C = K_{ff}^{-1}$ from sparse forward solves (selected inversion along
//! elimination-tree paths), without ever forming a column of length $Nn$ — written once for
//! both dimensions, $N$ DOFs per node (the const generic `N`, 2 or 3: blocks are $N \times N$
//! arrays the compiler unrolls).
//!
//! # Mathematics
//!
//! [`SparseCholesky`] factorises the Jacobi-scaled free block $\hat K = S K_{ff} S$,
//! $S = \mathrm{diag}(K_{ii}^{-1/2})$, with a fill-reducing permutation $Q$ (faer's convention:
//! $(Q b)_k = b_{\mathrm{fwd}(k)}$, so $Q e_i = e_{\mathrm{inv}(i)}$):
//! $$Q \hat K Q^\top = L L^\top .$$
//! Hence $K_{ff}^{-1} = S Q^\top L^{-\top} L^{-1} Q S$ and, for free DOFs $i, j$,
//! $$C_{ij} = e_i^\top K_{ff}^{-1} e_j = y_i^\top y_j, \qquad y_i = s_i\, L^{-1} e_{\mathrm{inv}(i)} .$$
//! The forward solve of a unit vector only reaches the ancestors of its column in the elimination
//! tree of $L$: $y_i$ is non-zero only on the path from column $\mathrm{inv}(i)$ to the root (its
//! "reach"). faer's supernodal factor groups columns into supernodes $\sigma$ with a dense
//! trapezoidal block $L_{[\sigma] \cup R_\sigma,\,\sigma}$ ($R_\sigma$ the row pattern below the
//! diagonal block, all in ancestors of $\sigma$); a simplicial factor is read as one-column
//! supernodes. The reach of a node (its $N$ DOFs) is the union of the supernode-tree paths from its
//! DOFs' supernodes; the forward solve visits it in ascending order:
//! $$x_\sigma \leftarrow L_{\sigma\sigma}^{-1} x_\sigma, \qquad x_{R_\sigma} \leftarrow x_{R_\sigma} - L_{R_\sigma \sigma}\, x_\sigma ,$$
//! with cost $\sum_{\sigma \in \mathrm{reach}} |\sigma| (|\sigma| + |R_\sigma|)$ per right-hand
//! side, independent of $n$ for a fixed path length. A node's [`NodeRows`] hold
//! $Y_v = [y_{Nv}, \dots, y_{Nv+N-1}]$ on its reach only (a fixed node: empty, $C = 0$).
//!
//! A node block is a sparse dot product over the common part of the two reaches (an upward-closed
//! set: from the lowest common ancestors to the root):
//! $$C_{vw} = Y_v^\top Y_w \in \mathbb{R}^{N\times N}, \qquad (C_{vw})_{rs} = \sum_{\sigma \in \mathrm{reach}(v) \cap \mathrm{reach}(w)} y_{Nv+r,\sigma}^\top\, y_{Nw+s,\sigma} .$$
//! A material point $a$ inside an element with nodes $v_{a,k}$ and barycentric weights $N_{a,k}$
//! ($\sum_k N_{a,k} = 1$) has $u(a) = \sum_k N_{a,k} u(v_{a,k})$, i.e. $P_a = [N_{a,k} I_N]_k$, so
//! the point block of $W = P C P^\top$ is
//! $$W_{ab} = \sum_{k} \sum_{l} N_{a,k} N_{b,l}\, C_{v_{a,k} v_{b,l}} .$$
//!
//! # Use
//! [`SparseFactorView`] is the immutable walkable view of a factor (shareable between threads);
//! [`SparseFactorView::rows_into`] computes a node's rows allocation-free into caller storage with
//! a [`SparseRowsScratch`] sized once (a dense work vector whose touched entries — the reach — are
//! reset after each solve, so no $O(n)$ work per node); [`SparseFactorView::rows_batch_into`] solves
//! for $k$ nodes at once ($Nk$ right-hand sides on the union of their reaches, dense kernels per
//! supernode), which reads each block of $L$ once per batch — the solve is bound by reading $L$ on
//! the reach, so batching is what makes rows cheap. [`SparseCompliance`] adds a per-node cache
//! ([`SparseCompliance::prefetch`] in batches), the node and point blocks, and point rows
//! $Y_a = \sum_k N_{a,k} Y_{v_{a,k}}$ ([`SparseCompliance::point_rows`]) so that a point block is
//! one sparse dot product. The reach length, hence the cost and the memory per node, depends on
//! the ordering: [`nested_dissection_order`] gives shorter reaches and less fill than faer's AMD
//! on box grids. No I/O.
//!
//! Both dimensions run the same code: the 3D simulation keeps its compliance this way on large
//! meshes; the 2D tests check the node blocks against the dense columns.

use std::borrow::Cow;

use crate::compliance::TissueModel;
use crate::dim::Dim;
use crate::factor::SparseCholesky;
use crate::mesh::SimplexMesh;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;

/// Errors of the sparse compliance.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SparseComplianceError {
    /// The factor is not of a model of this dimension (at construction): its DOF map has
    /// `dofs_per_node` DOFs per node, not `expected`.
    #[error("the factor has {dofs_per_node} DOFs per node; the {expected}D sparse compliance needs {expected}")]
    WrongDofsPerNode { dofs_per_node: usize, expected: usize },
    /// A node asked for (rows, node block, or a point's element node) does not exist.
    #[error("node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownNode { node_idx: usize, n_nodes: usize },
    /// [`SparseFactorView::with_pattern`] was given the pattern of another factor.
    #[error("the factor pattern belongs to another factor")]
    PatternMismatch,
}

/// The compliance rows $Y_v$ of one node on its reach (see the module documentation): the
/// supernodes of the reach in ascending order, and per supernode its columns' values for the $N$
/// force axes. Units: m/N after the dot product ($C$ in m/N, each $y$ in $\sqrt{\mathrm{m/N}}$).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NodeRows<const N: usize> {
    /// Supernodes of the reach, ascending.
    supernodes: Vec<usize>,
    /// `starts[k]` is the offset of supernode `supernodes[k]`'s first column in each axis' values;
    /// `starts[supernodes.len()]` is the reach length.
    starts: Vec<usize>,
    /// Axis-major values: `values[axis * len + offset]`, `len` the reach length.
    values: Vec<f64>,
}

impl<const N: usize> NodeRows<N> {
    /// Number of stored entries per axis (the reach length in factor columns; 0 for a fixed node).
    pub fn len(&self) -> usize {
        self.starts.last().copied().unwrap_or(0)
    }
    /// Whether the node has no stored rows (a fixed node: its compliance is zero).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Number of supernodes on the reach.
    pub fn n_supernodes(&self) -> usize {
        self.supernodes.len()
    }
    /// The values of force axis `axis` (0 = x, 1 = y, 2 = z) on the reach.
    pub fn axis(&self, axis: usize) -> &[f64] {
        let len = self.len();
        &self.values[axis * len..(axis + 1) * len]
    }
    /// Heap bytes held (capacity, not length).
    pub fn heap_bytes(&self) -> usize {
        (self.supernodes.capacity() + self.starts.capacity()) * std::mem::size_of::<usize>()
            + self.values.capacity() * std::mem::size_of::<f64>()
    }
    fn clear(&mut self) {
        self.supernodes.clear();
        self.starts.clear();
        self.values.clear();
    }
}

/// Scratch for [`SparseFactorView::rows_into`], sized once for a factor ($Nn_\mathrm{free}$
/// doubles, one flag per supernode); allocate once per thread.
#[derive(Debug, Clone)]
pub struct SparseRowsScratch {
    /// Dense work vector, interleaved `x[N * column + axis]`; zero between solves.
    x: Vec<f64>,
    /// Whether a supernode is on the current reach; false between solves.
    on_reach: Vec<bool>,
    /// The current reach.
    reach: Vec<usize>,
    /// Batched solves: compact row of each factor column on the union reach (`usize::MAX` off it).
    pos: Vec<usize>,
    /// Batched solves: per supernode, the batch member that last put it on its own reach.
    stamp: Vec<u64>,
    /// Batched solves: the stamp generation.
    generation: u64,
    /// Batched solves: the right-hand sides on the union reach, row-major (reach × N batch).
    xb: Vec<f64>,
    /// Batched solves: the product $L_{R_\sigma\sigma} X_\sigma$, row-major.
    tmp: Vec<f64>,
}

/// The structure of a [`SparseFactorView`] without the factor's values (see
/// [`SparseFactorView::pattern`]): owned, so a worker holding the model in an `Arc` keeps it and
/// borrows a view per call ([`SparseFactorView::with_pattern`]).
#[derive(Debug, Clone)]
pub struct FactorPattern {
    free_of_dof: Vec<usize>,
    col_of_free: Vec<usize>,
    sn_of_col: Vec<usize>,
    sn_begin: Vec<usize>,
    sn_val: Vec<usize>,
    sn_pat: Vec<usize>,
    pattern: Vec<usize>,
    sn_parent: Vec<usize>,
    n_nodes: usize,
    supernodal: bool,
}

/// An immutable, walkable view of a [`SparseCholesky`] factor with `N` DOFs per node: per supernode its
/// first column, value offset, row pattern below the diagonal block and parent in the supernode
/// elimination tree. `Sync`: one view can serve several threads, each with its own scratch.
#[derive(Debug)]
pub struct SparseFactorView<'f, const N: usize> {
    l_values: &'f [f64],
    /// Jacobi scale per free DOF.
    scale: &'f [f64],
    /// Free index of each global DOF (`usize::MAX` when fixed).
    free_of_dof: Cow<'f, [usize]>,
    /// Factor column of each free DOF ($\mathrm{inv}(i)$).
    col_of_free: Cow<'f, [usize]>,
    /// Supernode of each factor column.
    sn_of_col: Cow<'f, [usize]>,
    /// First column of each supernode, plus $n_\mathrm{free}$.
    sn_begin: Cow<'f, [usize]>,
    /// Offset of each supernode's column-major block in `l_values`, plus its end.
    sn_val: Cow<'f, [usize]>,
    /// Offset of each supernode's pattern in `pattern`, plus its end.
    sn_pat: Cow<'f, [usize]>,
    /// Row patterns below the diagonal blocks, in the order of the blocks' rows.
    pattern: Cow<'f, [usize]>,
    /// Parent supernode (`usize::MAX` for a root).
    sn_parent: Cow<'f, [usize]>,
    n_nodes: usize,
    supernodal: bool,
}

impl<'f, const N: usize> SparseFactorView<'f, N> {
    /// The view of `chol`, whose DOF map must have `N` DOFs per node
    /// ([`SparseComplianceError::WrongDofsPerNode`] otherwise). $O(n + \mathrm{nnz\ pattern})$.
    pub fn new(chol: &'f SparseCholesky) -> Result<Self, SparseComplianceError> {
        let dofs = chol.dofs();
        if dofs.dofs_per_node() != N {
            return Err(SparseComplianceError::WrongDofsPerNode { dofs_per_node: dofs.dofs_per_node(), expected: N });
        }
        let n = dofs.n_free();
        let n_dofs = dofs.n_dofs();
        let free_of_dof: Vec<usize> = (0..n_dofs).map(|d| dofs.free_index(d).unwrap_or(usize::MAX)).collect();
        let symbolic = chol.symbolic();
        let col_of_free: Vec<usize> = match symbolic.perm() {
            Some(p) => p.arrays().1.to_vec(),
            None => (0..n).collect(),
        };
        let (mut sn_begin, mut sn_val, mut sn_pat, mut pattern) = (vec![0], vec![0], vec![0], Vec::new());
        let supernodal = match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                // Column j: diagonal first, then the rows below it.
                let (cp, ri) = (s.col_ptr(), s.row_idx());
                for j in 0..n {
                    sn_begin.push(j + 1);
                    sn_val.push(cp[j + 1]);
                    pattern.extend_from_slice(&ri[cp[j] + 1..cp[j + 1]]);
                    sn_pat.push(pattern.len());
                }
                false
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let view = faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef::new(s, chol.l_values());
                sn_val = s.col_ptr_for_val().to_vec();
                for k in 0..s.n_supernodes() {
                    let sn = view.supernode(k);
                    sn_begin.push(sn.start() + sn.val().ncols());
                    pattern.extend_from_slice(sn.pattern());
                    sn_pat.push(pattern.len());
                }
                true
            }
        };
        let n_sn = sn_begin.len() - 1;
        let mut sn_of_col = vec![0; n];
        let mut sn_parent = vec![usize::MAX; n_sn];
        for s in 0..n_sn {
            sn_of_col[sn_begin[s]..sn_begin[s + 1]].fill(s);
        }
        for s in 0..n_sn {
            // The parent holds the lowest row below the diagonal block.
            if let Some(&r) = pattern[sn_pat[s]..sn_pat[s + 1]].iter().min() {
                sn_parent[s] = sn_of_col[r];
            }
        }
        Ok(Self {
            l_values: chol.l_values(),
            scale: chol.scale(),
            free_of_dof: Cow::Owned(free_of_dof),
            col_of_free: Cow::Owned(col_of_free),
            sn_of_col: Cow::Owned(sn_of_col),
            sn_begin: Cow::Owned(sn_begin),
            sn_val: Cow::Owned(sn_val),
            sn_pat: Cow::Owned(sn_pat),
            pattern: Cow::Owned(pattern),
            sn_parent: Cow::Owned(sn_parent),
            n_nodes: n_dofs / N,
            supernodal,
        })
    }

    /// The walkable structure of this view without the factor's values (owned, `Send`), from
    /// which [`SparseFactorView::with_pattern`] rebuilds a view of the same factor in $O(1)$:
    /// for a worker that owns the model (`Arc`) and cannot keep a borrowing view.
    pub fn pattern(&self) -> FactorPattern {
        FactorPattern {
            free_of_dof: self.free_of_dof.to_vec(),
            col_of_free: self.col_of_free.to_vec(),
            sn_of_col: self.sn_of_col.to_vec(),
            sn_begin: self.sn_begin.to_vec(),
            sn_val: self.sn_val.to_vec(),
            sn_pat: self.sn_pat.to_vec(),
            pattern: self.pattern.to_vec(),
            sn_parent: self.sn_parent.to_vec(),
            n_nodes: self.n_nodes,
            supernodal: self.supernodal,
        }
    }

    /// The view of `chol` with the structure `pattern` taken from [`SparseFactorView::pattern`]
    /// of the same factor, borrowed: $O(1)$, no allocation.
    ///
    /// Errors: [`SparseComplianceError::PatternMismatch`] when `pattern` does not fit `chol`
    /// (another factor: different numbers of DOFs, free DOFs or factor values).
    pub fn with_pattern(chol: &'f SparseCholesky, pattern: &'f FactorPattern) -> Result<Self, SparseComplianceError> {
        let dofs = chol.dofs();
        let fits = dofs.dofs_per_node() == N
            && pattern.free_of_dof.len() == dofs.n_dofs()
            && pattern.col_of_free.len() == dofs.n_free()
            && pattern.sn_val.last().copied() == Some(chol.l_values().len());
        if !fits {
            return Err(SparseComplianceError::PatternMismatch);
        }
        Ok(Self {
            l_values: chol.l_values(),
            scale: chol.scale(),
            free_of_dof: Cow::Borrowed(&pattern.free_of_dof),
            col_of_free: Cow::Borrowed(&pattern.col_of_free),
            sn_of_col: Cow::Borrowed(&pattern.sn_of_col),
            sn_begin: Cow::Borrowed(&pattern.sn_begin),
            sn_val: Cow::Borrowed(&pattern.sn_val),
            sn_pat: Cow::Borrowed(&pattern.sn_pat),
            pattern: Cow::Borrowed(&pattern.pattern),
            sn_parent: Cow::Borrowed(&pattern.sn_parent),
            n_nodes: pattern.n_nodes,
            supernodal: pattern.supernodal,
        })
    }

    /// Number of mesh nodes.
    pub fn n_nodes(&self) -> usize {
        self.n_nodes
    }
    /// Number of supernodes (columns, for a simplicial factor).
    pub fn n_supernodes(&self) -> usize {
        self.sn_parent.len()
    }
    /// Whether the factor is supernodal.
    pub fn is_supernodal(&self) -> bool {
        self.supernodal
    }
    /// Non-zeros of $L$ (dense supernode blocks counted whole).
    pub fn factor_nnz(&self) -> usize {
        self.l_values.len()
    }

    /// Scratch for [`SparseFactorView::rows_into`].
    pub fn scratch(&self) -> SparseRowsScratch {
        let (n, n_sn) = (self.col_of_free.len(), self.n_supernodes());
        SparseRowsScratch {
            x: vec![0.0; N * n],
            on_reach: vec![false; n_sn],
            reach: Vec::with_capacity(n_sn),
            pos: vec![usize::MAX; n],
            stamp: vec![0; n_sn],
            generation: 0,
            xb: Vec::new(),
            tmp: Vec::new(),
        }
    }

    /// Computes node `node_idx`'s rows $Y_v$ into `out` (its storage reused; allocation-free
    /// once `out` has held a reach at least as long). A fixed node gets empty rows. Errors only
    /// for an unknown node ([`SparseComplianceError::UnknownNode`]).
    pub fn rows_into(&self, node_idx: usize, scratch: &mut SparseRowsScratch, out: &mut NodeRows<N>) -> Result<(), SparseComplianceError> {
        if node_idx >= self.n_nodes {
            return Err(SparseComplianceError::UnknownNode { node_idx, n_nodes: self.n_nodes });
        }
        out.clear();
        out.starts.push(0);
        let SparseRowsScratch { x, on_reach, reach, .. } = scratch;
        debug_assert_eq!(x.len(), N * self.col_of_free.len(), "scratch of another factor");
        // Right-hand sides s_i e_inv(i) and the reach: the union of the supernode-tree paths.
        reach.clear();
        for axis in 0..N {
            let f = self.free_of_dof[N * node_idx + axis];
            if f == usize::MAX {
                continue;
            }
            let col = self.col_of_free[f];
            x[N * col + axis] = self.scale[f];
            let mut s = self.sn_of_col[col];
            while s != usize::MAX && !on_reach[s] {
                on_reach[s] = true;
                reach.push(s);
                s = self.sn_parent[s];
            }
        }
        reach.sort_unstable();
        // Forward solve restricted to the reach (ascending = children before parents).
        for &s in reach.iter() {
            let b = self.sn_begin[s];
            let w = self.sn_begin[s + 1] - b;
            let pat = &self.pattern[self.sn_pat[s]..self.sn_pat[s + 1]];
            let nrows = w + pat.len();
            let block = &self.l_values[self.sn_val[s]..self.sn_val[s + 1]];
            for c in 0..w {
                let lc = &block[c * nrows..(c + 1) * nrows];
                let j = N * (b + c);
                let inv = 1.0 / lc[c];
                let xc: [f64; N] = std::array::from_fn(|a| x[j + a] * inv);
                x[j..j + N].copy_from_slice(&xc);
                if xc.iter().all(|&v| v == 0.0) {
                    continue;
                }
                for (r, &l) in lc.iter().enumerate().take(w).skip(c + 1) {
                    let k = N * (b + r);
                    for a in 0..N {
                        x[k + a] -= l * xc[a];
                    }
                }
                for (&row, &l) in pat.iter().zip(&lc[w..]) {
                    let k = N * row;
                    for a in 0..N {
                        x[k + a] -= l * xc[a];
                    }
                }
            }
        }
        // Gather axis-major, reset the touched entries.
        let len: usize = reach.iter().map(|&s| self.sn_begin[s + 1] - self.sn_begin[s]).sum();
        out.values.resize(N * len, 0.0);
        let mut off = 0;
        for &s in reach.iter() {
            out.supernodes.push(s);
            for col in self.sn_begin[s]..self.sn_begin[s + 1] {
                for axis in 0..N {
                    out.values[axis * len + off] = x[N * col + axis];
                    x[N * col + axis] = 0.0;
                }
                off += 1;
            }
            out.starts.push(off);
            on_reach[s] = false;
        }
        Ok(())
    }

    /// As [`SparseFactorView::rows_into`] for several nodes at once (`outs[t]` gets `nodes[t]`'s
    /// rows): one forward solve with $Nk$ right-hand sides over the union of their reaches, with
    /// dense kernels per supernode (a triangular solve with $L_{\sigma\sigma}$ and a product with
    /// $L_{R_\sigma\sigma}$), so each block of $L$ is read once for the batch rather than once per
    /// node. Nodes near each other share most of their reach. The scratch grows to the largest
    /// union reach × $Nk$ and is kept. Errors only for an unknown node (nothing computed then).
    pub fn rows_batch_into(
        &self,
        nodes: &[usize],
        scratch: &mut SparseRowsScratch,
        outs: &mut [NodeRows<N>],
    ) -> Result<(), SparseComplianceError> {
        use faer::linalg::matmul::matmul;
        use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
        use faer::{Accum, MatMut, MatRef, Par};
        assert_eq!(nodes.len(), outs.len(), "one output per node");
        if let Some(&node_idx) = nodes.iter().find(|&&v| v >= self.n_nodes) {
            return Err(SparseComplianceError::UnknownNode { node_idx, n_nodes: self.n_nodes });
        }
        let m = N * nodes.len();
        let SparseRowsScratch { on_reach, reach, pos, stamp, generation, xb, tmp, .. } = scratch;
        // Each node's own reach, and their union.
        reach.clear();
        for (&v, out) in nodes.iter().zip(outs.iter_mut()) {
            *generation += 1;
            out.clear();
            for axis in 0..N {
                let f = self.free_of_dof[N * v + axis];
                if f == usize::MAX {
                    continue;
                }
                let mut s = self.sn_of_col[self.col_of_free[f]];
                while s != usize::MAX && stamp[s] != *generation {
                    stamp[s] = *generation;
                    out.supernodes.push(s);
                    if !on_reach[s] {
                        on_reach[s] = true;
                        reach.push(s);
                    }
                    s = self.sn_parent[s];
                }
            }
            out.supernodes.sort_unstable();
        }
        reach.sort_unstable();
        let mut len = 0;
        for &s in reach.iter() {
            for p in &mut pos[self.sn_begin[s]..self.sn_begin[s + 1]] {
                *p = len;
                len += 1;
            }
        }
        xb.clear();
        xb.resize(len * m, 0.0);
        for (t, &v) in nodes.iter().enumerate() {
            for axis in 0..N {
                let f = self.free_of_dof[N * v + axis];
                if f != usize::MAX {
                    xb[pos[self.col_of_free[f]] * m + N * t + axis] = self.scale[f];
                }
            }
        }
        for &s in reach.iter() {
            let b = self.sn_begin[s];
            let w = self.sn_begin[s + 1] - b;
            let pat = &self.pattern[self.sn_pat[s]..self.sn_pat[s + 1]];
            let l = MatRef::from_column_major_slice(&self.l_values[self.sn_val[s]..self.sn_val[s + 1]], w + pat.len(), w);
            let p0 = pos[b];
            solve_lower_triangular_in_place(
                l.subrows(0, w),
                MatMut::from_row_major_slice_mut(&mut xb[p0 * m..(p0 + w) * m], w, m),
                Par::Seq,
            );
            if pat.is_empty() {
                continue;
            }
            tmp.clear();
            tmp.resize(pat.len() * m, 0.0);
            matmul(
                MatMut::from_row_major_slice_mut(&mut tmp[..], pat.len(), m),
                Accum::Replace,
                l.subrows(w, pat.len()),
                MatRef::from_row_major_slice(&xb[p0 * m..(p0 + w) * m], w, m),
                1.0,
                Par::Seq,
            );
            for (&row, t) in pat.iter().zip(tmp.chunks_exact(m)) {
                let p = pos[row];
                for (x, &d) in xb[p * m..(p + 1) * m].iter_mut().zip(t) {
                    *x -= d;
                }
            }
        }
        for (t, out) in outs.iter_mut().enumerate() {
            let lt: usize = out.supernodes.iter().map(|&s| self.sn_begin[s + 1] - self.sn_begin[s]).sum();
            out.values.resize(N * lt, 0.0);
            out.starts.push(0);
            let mut off = 0;
            for &s in &out.supernodes {
                for &p in &pos[self.sn_begin[s]..self.sn_begin[s + 1]] {
                    for axis in 0..N {
                        out.values[axis * lt + off] = xb[p * m + N * t + axis];
                    }
                    off += 1;
                }
                out.starts.push(off);
            }
        }
        for &s in reach.iter() {
            on_reach[s] = false;
            pos[self.sn_begin[s]..self.sn_begin[s + 1]].fill(usize::MAX);
        }
        Ok(())
    }

    /// The node block $C_{vw} = Y_v^\top Y_w$ (m/N; `[r][s]` = displacement axis r of v under a
    /// unit force along axis s at w) from two nodes' rows.
    pub fn block(a: &NodeRows<N>, b: &NodeRows<N>) -> [[f64; N]; N] {
        let mut c = [[0.0; N]; N];
        let (la, lb) = (a.len(), b.len());
        let (mut i, mut j) = (0, 0);
        let (na, nb) = (a.supernodes.len(), b.supernodes.len());
        while i < na && j < nb {
            match a.supernodes[i].cmp(&b.supernodes[j]) {
                std::cmp::Ordering::Less => i += 1,
                std::cmp::Ordering::Greater => j += 1,
                std::cmp::Ordering::Equal => {
                    // A run of common supernodes is contiguous in both.
                    let (i0, j0) = (i, j);
                    while i < na && j < nb && a.supernodes[i] == b.supernodes[j] {
                        i += 1;
                        j += 1;
                    }
                    let (ra, rb) = (a.starts[i0]..a.starts[i], b.starts[j0]..b.starts[j]);
                    let ya: [&[f64]; N] = std::array::from_fn(|r| &a.values[r * la..][ra.clone()]);
                    let yb: [&[f64]; N] = std::array::from_fn(|s| &b.values[s * lb..][rb.clone()]);
                    let d = dot_nxn(ya, yb);
                    for r in 0..N {
                        for s in 0..N {
                            c[r][s] += d[r][s];
                        }
                    }
                }
            }
        }
        c
    }
}

/// The $N^2$ dot products $a_r^\top b_s$ of $N$ pairs of equal-length vectors in one pass (each
/// vector read once; four lanes per product, vectorisable).
fn dot_nxn<const N: usize>(a: [&[f64]; N], b: [&[f64]; N]) -> [[f64; N]; N] {
    const W: usize = 4;
    let n = a[0].len();
    debug_assert!(a.iter().chain(&b).all(|v| v.len() == n));
    let mut acc = [[[0.0; W]; N]; N];
    let full = n / W * W;
    let mut k = 0;
    while k < full {
        let xa: [[f64; W]; N] = std::array::from_fn(|r| <[f64; W]>::try_from(&a[r][k..k + W]).expect("W lanes"));
        let xb: [[f64; W]; N] = std::array::from_fn(|s| <[f64; W]>::try_from(&b[s][k..k + W]).expect("W lanes"));
        for r in 0..N {
            for s in 0..N {
                for l in 0..W {
                    acc[r][s][l] += xa[r][l] * xb[s][l];
                }
            }
        }
        k += W;
    }
    let mut out = [[0.0; N]; N];
    for r in 0..N {
        for s in 0..N {
            let tail: f64 = (full..n).map(|k| a[r][k] * b[s][k]).sum();
            out[r][s] = (acc[r][s][0] + acc[r][s][1]) + (acc[r][s][2] + acc[r][s][3]) + tail;
        }
    }
    out
}

/// A nested-dissection ordering of the free DOFs of a model from its node coordinates, for
/// [`SparseCholesky::with_ordering`] (as `SymmetricOrdering::Custom`): returns `fwd`, the free
/// DOF placed at each factor column (`fwd[k]` = free index; a permutation of `0..n_free`).
///
/// Recursive coordinate bisection of the node graph (element edges): a set of more than
/// `leaf_nodes` nodes is split at the median coordinate along its longest extent into a left part
/// $A$ and a right part $B$; the separator $S$ is the nodes of $A$ with a neighbour in $B$, so no
/// edge joins $A \setminus S$ and $B$. Order: $A \setminus S$ (recursively), $B$ (recursively),
/// then $S$; a node's free DOFs are consecutive. In the elimination tree the separators are the
/// ancestors, so a DOF's reach is its leaf's path through one separator per level (on a box grid,
/// planes of $O(n^{2/3})$ nodes at the top). `dofs` must have `D::N` DOFs per node and the mesh's
/// node count (a programming error otherwise: panics).
pub fn nested_dissection_order<D: Dim>(mesh: &SimplexMesh<D>, dofs: &crate::factor::DofMap, leaf_nodes: usize) -> Vec<usize> {
    let n_nodes = mesh.n_nodes();
    assert_eq!(dofs.n_dofs(), D::N * n_nodes, "a DOF map of this mesh with N DOFs per node");
    // Node adjacency (CSR) from the elements' edges.
    let k = D::NODES_PER_ELEMENT;
    let mut pairs: Vec<(usize, usize)> = Vec::with_capacity(k * (k - 1) * mesh.n_elements());
    for t in mesh.elements() {
        for i in 0..k {
            for j in 0..k {
                if i != j {
                    pairs.push((t[i], t[j]));
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut adj_ptr = vec![0; n_nodes + 1];
    for &(a, _) in &pairs {
        adj_ptr[a + 1] += 1;
    }
    for v in 0..n_nodes {
        adj_ptr[v + 1] += adj_ptr[v];
    }
    let adj: Vec<usize> = pairs.iter().map(|&(_, b)| b).collect();
    let x = mesh.nodes_m();
    let mut side = vec![0u8; n_nodes];
    let mut node_order = Vec::with_capacity(n_nodes);
    // Explicit stack: (nodes, separator to emit after them).
    enum Task {
        Split(Vec<usize>),
        Emit(Vec<usize>),
    }
    let mut stack = vec![Task::Split((0..n_nodes).collect())];
    while let Some(task) = stack.pop() {
        let mut set = match task {
            Task::Emit(sep) => {
                node_order.extend(sep);
                continue;
            }
            Task::Split(set) => set,
        };
        if set.len() <= leaf_nodes.max(1) {
            node_order.extend(set);
            continue;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &v in &set {
            for a in 0..D::N {
                lo[a] = lo[a].min(x[v][a]);
                hi[a] = hi[a].max(x[v][a]);
            }
        }
        let axis = (0..D::N).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).expect("N axes");
        set.sort_unstable_by(|&a, &b| x[a][axis].total_cmp(&x[b][axis]));
        let cut = x[set[set.len() / 2]][axis];
        let mut mid = set.partition_point(|&v| x[v][axis] < cut);
        if mid == 0 {
            mid = set.partition_point(|&v| x[v][axis] <= cut);
        }
        if mid == 0 || mid == set.len() {
            node_order.extend(set);
            continue;
        }
        let right = set.split_off(mid);
        let left = set;
        for &v in &right {
            side[v] = 2;
        }
        let (sep, rest): (Vec<usize>, Vec<usize>) =
            left.into_iter().partition(|&v| adj[adj_ptr[v]..adj_ptr[v + 1]].iter().any(|&w| side[w] == 2));
        for &v in &right {
            side[v] = 0;
        }
        // Popped in reverse: left rest, right, then the separator.
        stack.push(Task::Emit(sep));
        stack.push(Task::Split(right));
        stack.push(Task::Split(rest));
    }
    let mut fwd = Vec::with_capacity(dofs.n_free());
    for v in node_order {
        for axis in 0..D::N {
            if let Some(f) = dofs.free_index(D::dof(v, axis)) {
                fwd.push(f);
            }
        }
    }
    fwd
}

/// A material point as its element's nodes and their weights $N_{a,k}$ (for
/// [`SparseCompliance::point_rows`] and [`SparseCompliance::point_block`]).
pub trait PointTerms {
    /// The nodes and their weights, equally long.
    fn terms(&self) -> (&[usize], &[f64]);
}

impl PointTerms for crate::d3::PointLocation {
    fn terms(&self) -> (&[usize], &[f64]) {
        (&self.nodes, &self.weights)
    }
}

/// The sparse compliance of a factor with a per-node cache of rows: node blocks $C_{vw}$ and point
/// blocks $W_{ab}$ (see the module documentation). Computing a node's rows allocates its cache
/// entry (exact size); blocks of cached nodes allocate nothing.
#[derive(Debug)]
pub struct SparseCompliance<'f, const N: usize> {
    view: SparseFactorView<'f, N>,
    scratch: SparseRowsScratch,
    rows: Vec<Option<NodeRows<N>>>,
    cached_bytes: usize,
    n_cached: usize,
}

impl<'f, const N: usize> SparseCompliance<'f, N> {
    /// The sparse compliance of a tissue model's factor (`D::N` must be `N`: checked when compiled).
    pub fn new<D: Dim>(model: &'f TissueModel<D>) -> Self {
        const { assert!(D::N == N, "a model of N dimensions") };
        Self::from_factor(model.cholesky()).expect("a TissueModel<D>'s factor has D::N DOFs per node")
    }
    /// The sparse compliance of a factor with `N` DOFs per node
    /// ([`SparseComplianceError::WrongDofsPerNode`] otherwise).
    pub fn from_factor(chol: &'f SparseCholesky) -> Result<Self, SparseComplianceError> {
        let view = SparseFactorView::new(chol)?;
        let scratch = view.scratch();
        let rows = vec![None; view.n_nodes()];
        Ok(Self { view, scratch, rows, cached_bytes: 0, n_cached: 0 })
    }
    /// The walkable factor view.
    pub fn view(&self) -> &SparseFactorView<'f, N> {
        &self.view
    }
    /// Nodes whose rows are cached.
    pub fn n_cached(&self) -> usize {
        self.n_cached
    }
    /// Heap bytes held by the cached rows.
    pub fn cached_bytes(&self) -> usize {
        self.cached_bytes
    }
    /// Drops every cached node's rows.
    pub fn clear_cache(&mut self) {
        self.rows.iter_mut().for_each(|r| *r = None);
        self.cached_bytes = 0;
        self.n_cached = 0;
    }

    fn ensure(&mut self, node_idx: usize) -> Result<(), SparseComplianceError> {
        let n_nodes = self.view.n_nodes();
        if node_idx >= n_nodes {
            return Err(SparseComplianceError::UnknownNode { node_idx, n_nodes });
        }
        if self.rows[node_idx].is_none() {
            // A batch of one: the dense kernels beat the scalar loop of `rows_into` (about 1.4x).
            let mut r = NodeRows::default();
            self.view.rows_batch_into(std::slice::from_ref(&node_idx), &mut self.scratch, std::slice::from_mut(&mut r))?;
            self.cached_bytes += r.heap_bytes();
            self.n_cached += 1;
            self.rows[node_idx] = Some(r);
        }
        Ok(())
    }

    /// Computes and caches the rows of the uncached nodes among `nodes` with batched solves of up
    /// to `batch` nodes each ([`SparseFactorView::rows_batch_into`]): what a worker does ahead of
    /// the needle. Errors only for an unknown node (nothing cached then).
    pub fn prefetch(&mut self, nodes: &[usize], batch: usize) -> Result<(), SparseComplianceError> {
        let n_nodes = self.view.n_nodes();
        if let Some(&node_idx) = nodes.iter().find(|&&v| v >= n_nodes) {
            return Err(SparseComplianceError::UnknownNode { node_idx, n_nodes });
        }
        let mut todo: Vec<usize> = nodes.iter().copied().filter(|&v| self.rows[v].is_none()).collect();
        todo.sort_unstable();
        todo.dedup();
        for chunk in todo.chunks(batch.max(1)) {
            let mut outs = vec![NodeRows::default(); chunk.len()];
            self.view.rows_batch_into(chunk, &mut self.scratch, &mut outs)?;
            for (&v, r) in chunk.iter().zip(outs) {
                self.cached_bytes += r.heap_bytes();
                self.n_cached += 1;
                self.rows[v] = Some(r);
            }
        }
        Ok(())
    }

    /// The rows of a material point, $Y_a = \sum_k N_{a,k} Y_{v_{a,k}}$ on the union of its nodes'
    /// reaches (nodes' rows computed and cached as needed), so that a point block is one sparse
    /// dot product: $W_{ab} = Y_a^\top Y_b$ = [`SparseFactorView::block`]`(&ya, &yb)`. Errors only
    /// for an unknown node.
    pub fn point_rows(&mut self, a: &impl PointTerms) -> Result<NodeRows<N>, SparseComplianceError> {
        let (nodes, weights) = a.terms();
        for (&v, &nk) in nodes.iter().zip(weights) {
            if nk != 0.0 {
                self.ensure(v)?;
            }
        }
        let view = &self.view;
        let SparseRowsScratch { x, on_reach, reach, .. } = &mut self.scratch;
        reach.clear();
        for (&v, &nk) in nodes.iter().zip(weights) {
            if nk == 0.0 {
                continue;
            }
            let r = self.rows[v].as_ref().expect("ensured");
            let lr = r.len();
            for (i, &s) in r.supernodes.iter().enumerate() {
                if !on_reach[s] {
                    on_reach[s] = true;
                    reach.push(s);
                }
                for (off, col) in (r.starts[i]..r.starts[i + 1]).zip(view.sn_begin[s]..) {
                    for axis in 0..N {
                        x[N * col + axis] += nk * r.values[axis * lr + off];
                    }
                }
            }
        }
        reach.sort_unstable();
        let len: usize = reach.iter().map(|&s| view.sn_begin[s + 1] - view.sn_begin[s]).sum();
        let mut out = NodeRows { supernodes: reach.clone(), starts: Vec::with_capacity(reach.len() + 1), values: vec![0.0; N * len] };
        out.starts.push(0);
        let mut off = 0;
        for &s in reach.iter() {
            for col in view.sn_begin[s]..view.sn_begin[s + 1] {
                for axis in 0..N {
                    out.values[axis * len + off] = x[N * col + axis];
                    x[N * col + axis] = 0.0;
                }
                off += 1;
            }
            out.starts.push(off);
            on_reach[s] = false;
        }
        Ok(out)
    }

    /// The rows $Y_v$ of node `node_idx`, computed on first use and cached. Errors only for an
    /// unknown node.
    pub fn sparse_rows(&mut self, node_idx: usize) -> Result<&NodeRows<N>, SparseComplianceError> {
        self.ensure(node_idx)?;
        Ok(self.rows[node_idx].as_ref().expect("ensured"))
    }

    /// The node block $C_{ij}$ (m/N), rows of uncached nodes computed. Errors only for an unknown
    /// node.
    pub fn block(&mut self, i: usize, j: usize) -> Result<[[f64; N]; N], SparseComplianceError> {
        self.ensure(i)?;
        self.ensure(j)?;
        let (a, b) = (self.rows[i].as_ref().expect("ensured"), self.rows[j].as_ref().expect("ensured"));
        Ok(SparseFactorView::block(a, b))
    }

    /// The point block $W_{ab} = \sum_{k,l} N_{a,k} N_{b,l} C_{v_{a,k} v_{b,l}}$ (m/N) of two
    /// material points; nodes with zero weight are skipped. Errors only for an unknown node.
    pub fn point_block(&mut self, a: &impl PointTerms, b: &impl PointTerms) -> Result<[[f64; N]; N], SparseComplianceError> {
        let mut w = [[0.0; N]; N];
        let ((nodes_a, weights_a), (nodes_b, weights_b)) = (a.terms(), b.terms());
        for (&va, &na) in nodes_a.iter().zip(weights_a) {
            if na == 0.0 {
                continue;
            }
            for (&vb, &nb) in nodes_b.iter().zip(weights_b) {
                if nb == 0.0 {
                    continue;
                }
                let c = self.block(va, vb)?;
                let nn = na * nb;
                for r in 0..N {
                    for s in 0..N {
                        w[r][s] += nn * c[r][s];
                    }
                }
            }
        }
        Ok(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
    use crate::d3::TetMaterials;
    use crate::d3::locate::PointLocation;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use crate::d3::{NodeRows, SparseCompliance, SparseFactorView, TetTissueModel};
    use crate::factor::DofMap;
    use faer::sparse::linalg::SupernodalThreshold;
    use faer::sparse::linalg::cholesky::CholeskySymbolicParams;
    use nalgebra::DMatrix;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    /// A box grid, bottom fixed, the upper half 5x stiffer.
    fn model(cells: [usize; 3]) -> TetTissueModel {
        let mesh = BoxGridParams::new(cells, [0.1, 0.08, 0.1]).build(&TetMeshLimits::default()).unwrap();
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

    fn factor(m: &TetTissueModel, threshold: SupernodalThreshold) -> SparseCholesky {
        let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
        SparseCholesky::with_params(m.stiffness(), m.cholesky().dofs().clone(), params).unwrap()
    }

    /// The dense $K_{ff}^{-1}$ over all DOFs (zero rows and columns at fixed DOFs).
    fn dense_inverse(m: &TetTissueModel) -> DMatrix<f64> {
        let n_dofs = m.n_dofs();
        let kd = m.stiffness().to_dense();
        let free: Vec<usize> = (0..n_dofs).filter(|&d| !m.is_fixed(d / 3)).collect();
        let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| kd[(free[i], free[j])]);
        let inv = kff.try_inverse().unwrap();
        let mut full = DMatrix::zeros(n_dofs, n_dofs);
        for (i, &di) in free.iter().enumerate() {
            for (j, &dj) in free.iter().enumerate() {
                full[(di, dj)] = inv[(i, j)];
            }
        }
        full
    }

    /// Every node block equals the dense inverse, for the simplicial and the supernodal factor.
    #[test]
    fn blocks_equal_the_dense_inverse_for_both_variants() {
        let m = model([4, 3, 4]);
        let inv = dense_inverse(&m);
        let tol = 1e-10 * inv.amax();
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let chol = factor(&m, threshold);
            let mut sc = SparseCompliance::from_factor(&chol).unwrap();
            assert_eq!(sc.view().is_supernodal(), threshold == SupernodalThreshold::FORCE_SUPERNODAL);
            let n_nodes = m.mesh().n_nodes();
            for i in 0..n_nodes {
                for j in 0..n_nodes {
                    let c = sc.block(i, j).unwrap();
                    for (r, row) in c.iter().enumerate() {
                        for (s, &v) in row.iter().enumerate() {
                            let want = inv[(3 * i + r, 3 * j + s)];
                            assert!((v - want).abs() < tol, "{threshold:?} C[{i},{j}][{r}][{s}] = {v} vs {want}");
                        }
                    }
                }
                if m.is_fixed(i) {
                    assert!(sc.sparse_rows(i).unwrap().is_empty(), "a fixed node has no rows");
                }
            }
            assert_eq!(sc.n_cached(), n_nodes);
            assert!(sc.cached_bytes() > 0);
        }
    }

    /// On a larger grid (supernodal by faer's default choice), blocks of seeded random node pairs
    /// equal the full columns of [`TetTissueModel::compliance_columns_into`], and the reach is a
    /// small part of the $3n$ DOFs.
    #[test]
    fn blocks_equal_full_columns() {
        let m = model([9, 8, 10]);
        let n_dofs = m.n_dofs();
        let n_nodes = m.mesh().n_nodes();
        let mut sc = SparseCompliance::new(&m);
        let mut rng = SmallRng::seed_from_u64(16);
        let mut scratch = m.column_scratch();
        let mut cols = vec![0.0; 3 * n_dofs];
        let mut total_len = 0;
        let n_cols = 12;
        for _ in 0..n_cols {
            let j = rng.random_range(0..n_nodes);
            m.compliance_columns_into(j, &mut cols, &mut scratch).unwrap();
            let scale = cols.iter().fold(0.0_f64, |a, v| a.max(v.abs())).max(f64::MIN_POSITIVE);
            total_len += sc.sparse_rows(j).unwrap().len();
            // Against every node of a random sample, and j itself.
            let mut others: Vec<usize> = (0..20).map(|_| rng.random_range(0..n_nodes)).collect();
            others.push(j);
            for &i in &others {
                let c = sc.block(i, j).unwrap();
                let ct = sc.block(j, i).unwrap();
                for r in 0..3 {
                    for s in 0..3 {
                        let want = cols[s * n_dofs + 3 * i + r];
                        assert!((c[r][s] - want).abs() < 1e-10 * scale, "C[{i},{j}][{r}][{s}] = {} vs {want}", c[r][s]);
                        assert!((ct[s][r] - c[r][s]).abs() < 1e-12 * scale, "symmetry");
                    }
                }
            }
        }
        let mean_len = total_len as f64 / n_cols as f64;
        assert!(mean_len < 0.5 * n_dofs as f64, "mean reach {mean_len} of {n_dofs} DOFs");
    }

    /// Point blocks equal [`TetTissueModel::point_compliance`] at seeded random material points.
    #[test]
    fn point_blocks_equal_point_compliance() {
        let m = model([6, 5, 7]);
        let mut sc = SparseCompliance::new(&m);
        let mut rng = SmallRng::seed_from_u64(3);
        let locs: Vec<PointLocation> = (0..6)
            .map(|_| m.locate([rng.random_range(0.0..0.1), rng.random_range(0.0..0.08), rng.random_range(0.0..0.1)]).unwrap())
            .collect();
        let w = m.point_compliance(&locs).unwrap();
        let d = 3 * locs.len();
        let scale = w.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (a, la) in locs.iter().enumerate() {
            for (b, lb) in locs.iter().enumerate() {
                let blk = sc.point_block(la, lb).unwrap();
                for r in 0..3 {
                    for s in 0..3 {
                        let want = w[(3 * a + r) * d + 3 * b + s];
                        assert!((blk[r][s] - want).abs() < 1e-10 * scale, "W[{a},{b}][{r}][{s}] = {} vs {want}", blk[r][s]);
                    }
                }
            }
        }
    }

    /// Batched rows equal one-node rows (a fixed node and a repeated node included), for both
    /// factor variants; prefetched blocks equal computed ones; point rows give the point blocks.
    #[test]
    fn batched_rows_and_point_rows_agree() {
        let m = model([6, 5, 7]);
        let n_nodes = m.mesh().n_nodes();
        let fixed = (0..n_nodes).find(|&v| m.is_fixed(v)).unwrap();
        let mut rng = SmallRng::seed_from_u64(7);
        let mut nodes: Vec<usize> = (0..9).map(|_| rng.random_range(0..n_nodes)).collect();
        nodes.extend([fixed, nodes[0], n_nodes - 1]);
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let chol = factor(&m, threshold);
            let view = SparseFactorView::new(&chol).unwrap();
            let mut scratch = view.scratch();
            let mut outs = vec![NodeRows::default(); nodes.len()];
            view.rows_batch_into(&nodes, &mut scratch, &mut outs).unwrap();
            assert!(scratch.on_reach.iter().all(|&f| !f) && scratch.pos.iter().all(|&p| p == usize::MAX), "scratch reset");
            let mut one = NodeRows::default();
            for (&v, got) in nodes.iter().zip(&outs) {
                view.rows_into(v, &mut scratch, &mut one).unwrap();
                assert_eq!((&got.supernodes, &got.starts), (&one.supernodes, &one.starts), "node {v}");
                let scale = one.values.iter().fold(0.0_f64, |a, x| a.max(x.abs())).max(f64::MIN_POSITIVE);
                for (a, b) in got.values.iter().zip(&one.values) {
                    assert!((a - b).abs() < 1e-12 * scale, "{threshold:?} node {v}: {a} vs {b}");
                }
            }
            assert!(outs[nodes.len() - 3].is_empty(), "the fixed node");
            let e = view.rows_batch_into(&[0, n_nodes], &mut scratch, &mut outs[..2]).unwrap_err();
            assert_eq!(e, SparseComplianceError::UnknownNode { node_idx: n_nodes, n_nodes });
        }
        let mut pre = SparseCompliance::new(&m);
        pre.prefetch(&nodes, 4).unwrap();
        assert_eq!(pre.n_cached(), nodes.len() - 1);
        let mut sc = SparseCompliance::new(&m);
        for &a in &nodes {
            for &b in &nodes {
                let (x, y) = (pre.block(a, b).unwrap(), sc.block(a, b).unwrap());
                let scale = y.iter().flatten().fold(1e-300_f64, |acc, v| acc.max(v.abs()));
                for r in 0..3 {
                    for c in 0..3 {
                        assert!((x[r][c] - y[r][c]).abs() <= 1e-12 * scale);
                    }
                }
            }
        }
        assert_eq!(pre.prefetch(&[n_nodes], 4).unwrap_err(), SparseComplianceError::UnknownNode { node_idx: n_nodes, n_nodes });
        let locs: Vec<PointLocation> = (0..4)
            .map(|_| m.locate([rng.random_range(0.0..0.1), rng.random_range(0.0..0.08), rng.random_range(0.0..0.1)]).unwrap())
            .collect();
        let rows: Vec<NodeRows> = locs.iter().map(|l| sc.point_rows(l).unwrap()).collect();
        for (la, ra) in locs.iter().zip(&rows) {
            for (lb, rb) in locs.iter().zip(&rows) {
                let want = sc.point_block(la, lb).unwrap();
                let got = SparseFactorView::block(ra, rb);
                let scale = want.iter().flatten().fold(0.0_f64, |acc, v| acc.max(v.abs()));
                for r in 0..3 {
                    for c in 0..3 {
                        assert!((got[r][c] - want[r][c]).abs() < 1e-12 * scale, "{} vs {}", got[r][c], want[r][c]);
                    }
                }
            }
        }
    }

    /// The nested-dissection ordering is a permutation, and a factor made with it gives the dense
    /// inverse's blocks (both variants).
    #[test]
    fn nested_dissection_factor_gives_the_dense_inverse() {
        let m = model([5, 4, 6]);
        let inv = dense_inverse(&m);
        let tol = 1e-10 * inv.amax();
        let fwd = nested_dissection_order(m.mesh(), m.cholesky().dofs(), 8);
        let n = m.cholesky().n_free();
        let mut seen = vec![false; n];
        fwd.iter().for_each(|&f| seen[f] = true);
        assert!(fwd.len() == n && seen.iter().all(|&b| b), "a permutation of the free DOFs");
        let mut inv_perm = vec![0; n];
        for (k, &f) in fwd.iter().enumerate() {
            inv_perm[f] = k;
        }
        let perm = faer::perm::PermRef::new_checked(&fwd, &inv_perm, n);
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
            let chol = SparseCholesky::with_ordering(
                m.stiffness(),
                m.cholesky().dofs().clone(),
                faer::sparse::linalg::cholesky::SymmetricOrdering::Custom(perm),
                params,
            )
            .unwrap();
            let mut sc = SparseCompliance::from_factor(&chol).unwrap();
            let n_nodes = m.mesh().n_nodes();
            for i in (0..n_nodes).step_by(3) {
                for j in 0..n_nodes {
                    let c = sc.block(i, j).unwrap();
                    for r in 0..3 {
                        for s in 0..3 {
                            assert!((c[r][s] - inv[(3 * i + r, 3 * j + s)]).abs() < tol, "{threshold:?} C[{i},{j}]");
                        }
                    }
                }
            }
        }
    }

    /// Typed errors: an unknown node (rows, blocks, points) and a factor that is not 3D.
    #[test]
    fn errors() {
        let m = model([2, 2, 2]);
        let n_nodes = m.mesh().n_nodes();
        let mut sc = SparseCompliance::new(&m);
        let unknown = SparseComplianceError::UnknownNode { node_idx: n_nodes, n_nodes };
        assert_eq!(sc.sparse_rows(n_nodes).unwrap_err(), unknown);
        assert_eq!(sc.block(0, n_nodes).unwrap_err(), unknown);
        let bad = PointLocation { tet_idx: 0, nodes: [0, 1, 2, n_nodes], weights: [0.25; 4] };
        let good = m.locate([0.05, 0.04, 0.05]).unwrap();
        assert_eq!(sc.point_block(&good, &bad).unwrap_err(), unknown);
        let mut scratch = sc.view().scratch();
        let mut rows = NodeRows::default();
        assert_eq!(
            sc.view().rows_into(n_nodes + 5, &mut scratch, &mut rows).unwrap_err(),
            SparseComplianceError::UnknownNode { node_idx: n_nodes + 5, n_nodes }
        );
        assert!(unknown.to_string().contains("does not exist"));
        // The same matrix labelled as 2 DOFs per node.
        let constrained: Vec<bool> = (0..m.n_dofs()).map(|d| m.is_fixed(d / 3)).collect();
        let chol2 = SparseCholesky::new(m.stiffness(), DofMap::with_dofs_per_node(&constrained, 2)).unwrap();
        assert_eq!(
            SparseCompliance::from_factor(&chol2).unwrap_err(),
            SparseComplianceError::WrongDofsPerNode { dofs_per_node: 2, expected: 3 }
        );
    }

    /// 2D runs the same code: on a plane-strain square (bottom fixed) the $2 \times 2$ node blocks
    /// of the sparse path, $C_{vw} = Y_v^\top Y_w$, equal the entries of the dense path's
    /// compliance columns ([`crate::compliance::TissueModel::compliance_columns_into`]) for every
    /// pair of nodes, with a simplicial and a supernodal factor, a fixed node has no rows, point
    /// blocks are the weighted sums of node blocks, and the block worker and store hand the same
    /// blocks to a 2D contact read ([`crate::compliance::ContactBlocks`]) as the column cache.
    /// Tolerance: $\varepsilon\,\kappa$-sized, $10^3\, n_\mathrm{dof}\, \varepsilon \max|C|$.
    #[test]
    fn two_d_node_blocks_equal_the_dense_columns() {
        use crate::compliance::store::{ComplianceStore, NodeBlockStore};
        use crate::compliance::worker::BlockWorker;
        use crate::compliance::{ComplianceCache, ContactBlocks};
        use crate::contact::ContactPoint;
        use crate::dim::Dim2;
        let m = crate::fixtures::strain_square(10);
        let (n_nodes, n_dofs) = (m.mesh().n_nodes(), m.n_dofs());
        let mut cache = ComplianceCache::<2>::new(n_nodes);
        let mut col_scratch = m.column_scratch();
        for v in 0..n_nodes {
            cache.ensure(&m, v, &mut col_scratch).unwrap();
        }
        let mut scale = 0.0_f64;
        for v in 0..n_nodes {
            for c in 0..2 {
                scale = cache.column(v, c).unwrap().iter().fold(scale, |a, x| a.max(x.abs()));
            }
        }
        assert!(scale > 1e-6, "the square is soft: {scale} m/N");
        let tol = 1e3 * n_dofs as f64 * f64::EPSILON * scale;
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
            let chol = SparseCholesky::with_params(m.stiffness(), m.cholesky().dofs().clone(), params).unwrap();
            let mut sc = super::SparseCompliance::<2>::from_factor(&chol).unwrap();
            assert_eq!(sc.view().is_supernodal(), threshold == SupernodalThreshold::FORCE_SUPERNODAL);
            let mut worst = 0.0_f64;
            for a in 0..n_nodes {
                for b in 0..n_nodes {
                    let c = sc.block(a, b).unwrap();
                    let want = cache.block(a, b).unwrap();
                    for r in 0..2 {
                        for s in 0..2 {
                            worst = worst.max((c[r][s] - want[r][s]).abs());
                            assert!(
                                (c[r][s] - want[r][s]).abs() <= tol,
                                "{threshold:?} C[{a},{b}][{r}][{s}] = {} vs {}",
                                c[r][s],
                                want[r][s]
                            );
                        }
                    }
                }
                assert_eq!(sc.sparse_rows(a).unwrap().is_empty(), m.is_fixed(a), "node {a}: rows iff free");
            }
            assert!(worst <= tol, "{threshold:?}: {worst:e} > {tol:e}");
        }
        // The square's own factor (AMD, as the model chose), through the worker and the store.
        let mut sc = super::SparseCompliance::<2>::new(&m);
        let mut worker = BlockWorker::<Dim2, 2>::new(std::sync::Arc::new(crate::fixtures::strain_square(10)), 6).unwrap();
        let mut store = NodeBlockStore::<2>::new(n_nodes, 6);
        let (tri, pts) = ([57usize, 58, 68], [[0.2, 0.5, 0.3], [0.6, 0.1, 0.3]]);
        let mut requests = Vec::new();
        for (slot, &v) in [57usize, 58, 68, 79, 80].iter().enumerate() {
            requests.push(store.reserve(v, slot).unwrap().0);
        }
        for p in worker.compute(&requests).unwrap() {
            store.insert(p).unwrap();
        }
        let store = ComplianceStore::Blocks(store);
        let (pa, pb) = (ContactPoint::in_triangle(0, tri, pts[0]), ContactPoint::in_triangle(0, tri, pts[1]));
        let (got, want) = (store.contact_block(&pa, &pb).unwrap(), ContactBlocks::<2>::contact_block(&cache, &pa, &pb).unwrap());
        for r in 0..2 {
            for s in 0..2 {
                assert!((got[r][s] - want[r][s]).abs() <= tol, "W[{r}][{s}] {} vs {}", got[r][s], want[r][s]);
            }
        }
        assert_eq!(store.block(79, 57).unwrap(), sc.block(79, 57).unwrap(), "the worker's blocks are the sparse compliance's");
        assert!(store.block(79, 3).is_none(), "node 3 not in the store");
    }

    /// A view rebuilt from its pattern ([`SparseFactorView::with_pattern`]) computes the same rows
    /// bit for bit; the pattern of another factor is refused.
    #[test]
    fn a_view_from_its_pattern_is_the_same_view() {
        let m = model([3, 2, 2]);
        let view = SparseFactorView::new(m.cholesky()).unwrap();
        let pattern = view.pattern();
        let again = SparseFactorView::with_pattern(m.cholesky(), &pattern).unwrap();
        let nodes: Vec<usize> = (0..m.mesh().n_nodes()).filter(|&v| !m.is_fixed(v)).collect();
        let (mut a, mut b) = (vec![NodeRows::default(); nodes.len()], vec![NodeRows::default(); nodes.len()]);
        view.rows_batch_into(&nodes, &mut view.scratch(), &mut a).unwrap();
        again.rows_batch_into(&nodes, &mut again.scratch(), &mut b).unwrap();
        assert!(!a[0].is_empty());
        assert_eq!(a, b);
        let other = model([2, 2, 2]);
        assert_eq!(SparseFactorView::with_pattern(other.cholesky(), &pattern).unwrap_err(), SparseComplianceError::PatternMismatch);
    }

    /// `rows_into` reuses its output's storage: a second node with a reach no longer than the
    /// first's keeps the buffers (no allocation), and the scratch is left zeroed.
    #[test]
    fn rows_into_reuses_storage_and_resets_scratch() {
        let m = model([5, 5, 5]);
        let view = SparseFactorView::new(m.cholesky()).unwrap();
        let mut scratch = view.scratch();
        let mut rows = NodeRows::default();
        let n = m.mesh().n_nodes();
        let longest = (0..n).max_by_key(|&v| {
            view.rows_into(v, &mut scratch, &mut rows).unwrap();
            rows.len()
        });
        view.rows_into(longest.unwrap(), &mut scratch, &mut rows).unwrap();
        let ptr = rows.values.as_ptr();
        for v in 0..n {
            view.rows_into(v, &mut scratch, &mut rows).unwrap();
            assert_eq!(rows.values.as_ptr(), ptr, "node {v}: storage reused");
            assert!(scratch.x.iter().all(|&x| x == 0.0) && scratch.on_reach.iter().all(|&f| !f));
        }
    }

    /// Compliance figures of one factor (printed): one-node and batched rows, node, point and
    /// point-row blocks, memory, one full solve.
    fn report(label: &str, m: &TetTissueModel, chol: &SparseCholesky, nodes: &[usize], needle: &[usize], pts: &[PointLocation]) {
        use std::time::Instant;
        let n_free = chol.n_free();
        let mut sc = SparseCompliance::from_factor(chol).unwrap();
        println!(
            "[{label}] nnz(L) {} ({:.0} MB), {} supernodes",
            chol.factor_nnz(),
            chol.factor_nnz() as f64 * 8e-6,
            sc.view().n_supernodes()
        );
        let few = &nodes[..nodes.len().min(50)];
        let t = Instant::now();
        let mut len = 0;
        for &v in few {
            len += sc.sparse_rows(v).unwrap().len();
        }
        println!(
            "[{label}] one-node rows: {:?} per node (mean of {}), mean reach {} of {n_free} DOFs, {} bytes per node cached (full columns: {} bytes)",
            t.elapsed() / few.len() as u32,
            few.len(),
            len / few.len(),
            sc.cached_bytes() / sc.n_cached(),
            3 * m.n_dofs() * 8
        );
        for batch in [1, 8, 32] {
            for (what, set) in [("scattered nodes", nodes), ("needle line", needle)] {
                let mut fresh = SparseCompliance::from_factor(chol).unwrap();
                let t = Instant::now();
                fresh.prefetch(set, batch).unwrap();
                println!("[{label}] batched rows ({what}, batch {batch}): {:?} per node", t.elapsed() / set.len() as u32);
            }
        }
        sc.prefetch(nodes, 32).unwrap();
        sc.prefetch(needle, 32).unwrap();
        let mut acc = 0.0;
        for (what, set, step) in [("scattered nodes", nodes, 10), ("needle line", needle, 1)] {
            let t = Instant::now();
            let mut n_blocks = 0;
            for &a in set {
                for &b in set.iter().step_by(step) {
                    acc += sc.block(a, b).unwrap()[0][0];
                    n_blocks += 1;
                }
            }
            println!("[{label}] node block ({what}): {:?} per block ({n_blocks}) [{acc:e}]", t.elapsed() / n_blocks);
        }
        let pnodes: Vec<usize> = pts.iter().flat_map(|p| p.nodes).collect();
        sc.prefetch(&pnodes, 32).unwrap();
        let t = Instant::now();
        let mut n_pb = 0;
        for a in pts {
            for b in pts {
                acc += sc.point_block(a, b).unwrap()[2][2];
                n_pb += 1;
            }
        }
        println!("[{label}] point block from 16 node blocks (cached rows): {:?} [{acc:e}]", t.elapsed() / n_pb);
        let t = Instant::now();
        let prows: Vec<NodeRows> = pts.iter().map(|p| sc.point_rows(p).unwrap()).collect();
        println!(
            "[{label}] point rows (cached nodes): {:?} per point, mean length {}",
            t.elapsed() / pts.len() as u32,
            prows.iter().map(NodeRows::len).sum::<usize>() / pts.len()
        );
        let t = Instant::now();
        for a in &prows {
            for b in &prows {
                acc += SparseFactorView::block(a, b)[2][2];
            }
        }
        println!("[{label}] point block from point rows: {:?} per block [{acc:e}]", t.elapsed() / n_pb);
        println!("[{label}] cache: {} nodes, {:.1} MB", sc.n_cached(), sc.cached_bytes() as f64 * 1e-6);
        let mut rhs = faer::Mat::<f64>::from_fn(n_free, 1, |i, _| (i % 7) as f64 - 3.0);
        let mut chs = chol.scratch(1);
        let t = Instant::now();
        for _ in 0..5 {
            chol.solve_in_place(rhs.as_mut(), &mut chs);
        }
        println!("[{label}] one full solve (1 rhs): {:?}", t.elapsed() / 5);
    }

    /// Timing against the full-column path on a box grid of `NEEDLESIM_GRID`³ nodes (default 21:
    /// 48 000 tetrahedra; 36: 257 250), bottom fixed, with faer's AMD ordering and with
    /// [`nested_dissection_order`]; run in release:
    /// `NEEDLESIM_GRID=21 cargo test --release -p needlesim-core --lib compliance::sparse::tests::timing_box -- --ignored --nocapture`.
    #[test]
    #[ignore = "timing; run in release"]
    fn timing_box() {
        use std::time::Instant;
        let g: usize = std::env::var("NEEDLESIM_GRID").ok().and_then(|v| v.parse().ok()).unwrap_or(21);
        let mesh = BoxGridParams::new([g, g, g], [0.1, 0.1, 0.1]).build(&TetMeshLimits::default()).unwrap();
        let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }]).unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        let t0 = Instant::now();
        let m = TetTissueModel::new(mesh, mats, &fixed).unwrap();
        println!(
            "{g}^3 box: {} nodes, {} tets, {} free DOFs; assemble + factorise (AMD, supernodal {}) {:?}",
            m.mesh().n_nodes(),
            m.mesh().n_tets(),
            m.cholesky().n_free(),
            m.cholesky().is_supernodal(),
            t0.elapsed()
        );
        let nodes: Vec<usize> = (0..m.mesh().n_nodes()).filter(|&n| !m.is_fixed(n)).step_by(37).take(200).collect();
        // A needle's working set: the nodes of a vertical grid line through the centre.
        let needle: Vec<usize> = (1..g).map(|k| (k * g + g / 2) * g + g / 2).filter(|&n| !m.is_fixed(n)).collect();
        let pts: Vec<PointLocation> = (1..20).map(|k| m.locate([0.0513, 0.0487, 0.005 * k as f64 + 0.0011]).unwrap()).collect();
        let mut scratch = m.column_scratch();
        let mut out = vec![0.0; 3 * m.n_dofs()];
        let t = Instant::now();
        for &v in &nodes[..10] {
            m.compliance_columns_into(v, &mut out, &mut scratch).unwrap();
        }
        println!("[AMD] full columns (TetTissueModel): {:?} per node (mean of 10)", t.elapsed() / 10);
        report("AMD", &m, m.cholesky(), &nodes, &needle, &pts);
        let t = Instant::now();
        let fwd = nested_dissection_order(m.mesh(), m.cholesky().dofs(), 64);
        let t_order = t.elapsed();
        let n = fwd.len();
        let mut inv = vec![0; n];
        for (k, &f) in fwd.iter().enumerate() {
            inv[f] = k;
        }
        let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
        let t = Instant::now();
        let nd = SparseCholesky::with_ordering(
            m.stiffness(),
            m.cholesky().dofs().clone(),
            faer::sparse::linalg::cholesky::SymmetricOrdering::Custom(perm),
            Default::default(),
        )
        .unwrap();
        println!("[ND] ordering {t_order:?}, factorise (supernodal {}) {:?}", nd.is_supernodal(), t.elapsed());
        report("ND", &m, &nd, &nodes, &needle, &pts);
    }
}
