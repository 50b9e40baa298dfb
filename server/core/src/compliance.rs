//! The tissue model and its compliance on demand: columns of $C = K_{ff}^{-1}$ for the nodes the
//! needle touches, from a sparse factorisation instead of a dense inverse — written once for both
//! dimensions.
//!
//! [`TissueModel`] ([`tissue`], generic over [`crate::Dim`]) assembles $K$, removes the fixed nodes
//! and factorises $K_{ff}$ once. The $D$ columns of node $w$ are $D$ sparse solves,
//! $K_{ff}\,[c_{x}, c_{y}(, c_z)] = [e_{Dw}, e_{Dw+1}(, e_{Dw+2})]$, cost $O(\mathrm{nnz}(L))$.
//! [`ComplianceCache`] keeps them (full DOF length, zero at fixed DOFs) so the working set
//! $\mathcal W$ grows node by node without refactorisation, gives the blocks of
//! $C_{\mathcal{WW}}$, and the displacement of every node caused by forces on $\mathcal W$:
//! $u = \sum_{w \in \mathcal W} C_{:,w} f_w$, cost $O(n\,|\mathcal W|)$.
//!
//! For large meshes the compliance is kept as node blocks instead of columns: [`sparse`] computes
//! a node's rows $Y_v$ of $C = Y^\top Y$ by sparse forward solves and the $D \times D$ blocks
//! $C_{vw} = Y_v^\top Y_w$; [`worker`] computes them off the real-time thread; [`store`] holds
//! the blocks among a bounded set of nodes ([`store::NodeBlockStore`]) or the columns, behind one
//! enum ([`store::ComplianceStore`]).
//!
//! The cache and the stores serve 2D and 3D: `ComplianceCache<D>` holds, per node, the $D$ columns
//! of length $Dn$ (world DOF $Di + c$ of node $i$, component $c$), and its blocks are $D \times D$
//! arrays. The storage's dimension is a const generic (default 2, so `ComplianceCache` in a type
//! is the 2D cache of the sim) for the reason given in [`crate::mixed`]: the blocks are
//! fixed-size arrays the compiler unrolls. The model's dimension is a [`crate::Dim`] (its mesh and
//! elements are); where the two meet (the block worker) both are named and checked equal at
//! compile time. 3D columns come from the 3D tissue model through [`ComplianceCache::insert`] or
//! [`ComplianceCache::ensure_with`].

use std::sync::Arc;

use crate::contact::ContactPoint;

pub mod sparse;
pub mod store;
mod tissue;
pub mod worker;

pub use tissue::{ColumnScratch, TissueError, TissueModel};

/// Cached compliance columns by node, one boxed set of `D` columns per node (so memory follows
/// the nodes cached, and growth never copies other nodes' columns). Storage grows only in
/// [`ComplianceCache::insert`] (and the `ensure` calls that insert); evicted storage is reused;
/// reads allocate nothing. `D` is the dimension, 2 (the default) or 3.
#[derive(Debug, Clone)]
pub struct ComplianceCache<const D: usize = 2> {
    n_dofs: usize,
    slot_of_node: Vec<u32>,
    node_of_slot: Vec<usize>,
    free_slots: Vec<u32>,
    columns: Vec<Box<[f64]>>,
    n_computed: u64,
}

const NO_SLOT: u32 = u32::MAX;

/// The 3D compliance cache: three columns of length $3n$ per node.
pub type ComplianceCache3 = ComplianceCache<3>;

impl ComplianceCache<2> {
    /// An empty 2D cache for a model of `n_nodes` nodes ([`ComplianceCache::for_nodes`]).
    pub fn new(n_nodes: usize) -> Self {
        Self::for_nodes(n_nodes)
    }

    /// Computes and stores the columns of `node_idx` unless cached. Returns whether it computed.
    pub fn ensure(&mut self, model: &TissueModel, node_idx: usize, scratch: &mut ColumnScratch) -> Result<bool, TissueError> {
        if node_idx >= self.slot_of_node.len() {
            return Err(TissueError::UnknownNode { node_idx, n_nodes: self.slot_of_node.len() });
        }
        self.ensure_with(node_idx, |out| model.compliance_columns_into(node_idx, out, scratch))
    }
}

impl<const D: usize> ComplianceCache<D> {
    /// An empty cache for a model of `n_nodes` nodes in dimension `D`.
    pub fn for_nodes(n_nodes: usize) -> Self {
        assert!(D == 2 || D == 3, "a compliance cache is 2D or 3D");
        Self {
            n_dofs: D * n_nodes,
            slot_of_node: vec![NO_SLOT; n_nodes],
            node_of_slot: Vec::new(),
            free_slots: Vec::new(),
            columns: Vec::new(),
            n_computed: 0,
        }
    }

    /// Reserves bookkeeping room for `n_nodes` more nodes (not their columns).
    pub fn reserve(&mut self, n_nodes: usize) {
        self.columns.reserve(n_nodes);
        self.node_of_slot.reserve(n_nodes);
        self.free_slots.reserve(n_nodes);
    }

    /// Bytes held by cached columns (including evicted storage kept for reuse).
    pub fn column_bytes(&self) -> usize {
        self.columns.len() * D * self.n_dofs * std::mem::size_of::<f64>()
    }

    /// Storage slots, live or free (a slot's storage is kept for reuse after an eviction).
    pub fn n_slots(&self) -> usize {
        self.node_of_slot.len()
    }

    /// The node whose columns slot `slot` holds (`None` for a free or unknown slot).
    pub fn node_in_slot(&self, slot: usize) -> Option<usize> {
        let node_idx = *self.node_of_slot.get(slot)?;
        (self.slot_of_node[node_idx] as usize == slot).then_some(node_idx)
    }

    /// Whether the columns of `node_idx` are cached.
    pub fn contains(&self, node_idx: usize) -> bool {
        self.slot_of_node.get(node_idx).is_some_and(|&s| s != NO_SLOT)
    }

    /// Number of nodes cached.
    pub fn len(&self) -> usize {
        self.node_of_slot.len() - self.free_slots.len()
    }
    /// Whether the cache is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// How many columns pairs were computed through [`ComplianceCache::ensure`].
    pub fn n_computed(&self) -> u64 {
        self.n_computed
    }

    /// Stores columns computed elsewhere (for example by a worker thread with
    /// [`TissueModel::compliance_columns_into`]). `columns` has length $D \cdot Dn$: the column
    /// for a unit force along world $x$, then $y$ (then $z$), each over all DOFs.
    pub fn insert(&mut self, node_idx: usize, columns: &[f64]) {
        assert_eq!(columns.len(), D * self.n_dofs, "D full columns");
        let slot = match self.slot_of_node[node_idx] {
            NO_SLOT => match self.free_slots.pop() {
                Some(s) => s,
                None => {
                    self.columns.push(columns.into());
                    self.node_of_slot.push(node_idx);
                    // Room to free every slot later without allocating (evictions in a step).
                    self.free_slots.reserve(self.columns.len().saturating_sub(self.free_slots.len()));
                    (self.node_of_slot.len() - 1) as u32
                }
            },
            s => s,
        };
        self.slot_of_node[node_idx] = slot;
        self.node_of_slot[slot as usize] = node_idx;
        self.columns[slot as usize].copy_from_slice(columns);
    }

    /// Stores columns handed over as an owned box (length $D \cdot Dn$), without allocating
    /// column storage: the box is kept, or copied into reused storage. Returns a box the caller
    /// may drop elsewhere (the one not kept), so a real-time thread can hand it back to a worker.
    pub fn insert_owned(&mut self, node_idx: usize, columns: Box<[f64]>) -> Option<Box<[f64]>> {
        assert_eq!(columns.len(), D * self.n_dofs, "D full columns");
        match self.slot_of_node[node_idx] {
            NO_SLOT => match self.free_slots.pop() {
                Some(s) => {
                    self.slot_of_node[node_idx] = s;
                    self.node_of_slot[s as usize] = node_idx;
                    Some(std::mem::replace(&mut self.columns[s as usize], columns))
                }
                None => {
                    self.columns.push(columns);
                    self.node_of_slot.push(node_idx);
                    self.slot_of_node[node_idx] = (self.node_of_slot.len() - 1) as u32;
                    None
                }
            },
            s => Some(std::mem::replace(&mut self.columns[s as usize], columns)),
        }
    }

    /// Computes (with `compute`, which fills the $D$ columns of length $Dn$ of `node_idx`) and
    /// stores the columns of `node_idx` unless cached; allocates the columns' storage. Returns
    /// whether it computed. Errors: those of `compute` (nothing is then stored). Panics only on
    /// a programming error (`node_idx` past the cache's nodes).
    pub fn ensure_with<E>(&mut self, node_idx: usize, compute: impl FnOnce(&mut [f64]) -> Result<(), E>) -> Result<bool, E> {
        if self.contains(node_idx) {
            return Ok(false);
        }
        let mut cols = vec![0.0; D * self.n_dofs];
        compute(&mut cols)?;
        self.insert(node_idx, &cols);
        self.n_computed += 1;
        Ok(true)
    }

    /// Forgets the columns of `node_idx` (its storage is reused by the next insert).
    pub fn evict(&mut self, node_idx: usize) {
        if let Some(&s) = self.slot_of_node.get(node_idx)
            && s != NO_SLOT
        {
            self.slot_of_node[node_idx] = NO_SLOT;
            self.free_slots.push(s);
        }
    }

    /// The column of all DOFs' displacement for a unit force on `node_idx`, component `comp`
    /// (0 = x, 1 = y, 2 = z); `None` when not cached.
    pub fn column(&self, node_idx: usize, comp: usize) -> Option<&[f64]> {
        let s = *self.slot_of_node.get(node_idx)?;
        if s == NO_SLOT {
            return None;
        }
        Some(&self.columns[s as usize][comp * self.n_dofs..(comp + 1) * self.n_dofs])
    }

    /// All `D` columns of `node_idx` (component-major, each of length $Dn$); `None` when not
    /// cached.
    #[inline]
    fn columns_of(&self, node_idx: usize) -> Option<&[f64]> {
        let s = *self.slot_of_node.get(node_idx)?;
        if s == NO_SLOT {
            return None;
        }
        Some(&self.columns[s as usize])
    }

    /// The world-frame block $C_{ab}$ ($D \times D$): displacement of node `a` per unit force on
    /// node `b`. Needs `b`'s columns; `None` when they are not cached.
    pub fn block(&self, a: usize, b: usize) -> Option<[[f64; D]; D]> {
        let cols = self.columns_of(b)?;
        let n = self.n_dofs;
        Some(std::array::from_fn(|r| std::array::from_fn(|c| cols[c * n + D * a + r])))
    }

    /// The world-frame compliance block between two contacts,
    /// $W_{ab} = \sum_{i \in a}\sum_{j \in b} N_{a,i} N_{b,j}\, C_{ij}$ ($D \times D$):
    /// displacement of contact `a` per unit force on contact `b` ([`crate::contact`]). Needs the
    /// columns of `b`'s nodes; `None` when one is not cached. $O(1)$: at most nine nodal blocks
    /// in 2D (triangle × triangle), sixteen in 3D (tetrahedron × tetrahedron).
    pub fn contact_block(&self, a: &ContactPoint, b: &ContactPoint) -> Option<[[f64; D]; D]> {
        let mut out = [[0.0; D]; D];
        let n = self.n_dofs;
        for (j, wj) in b.terms() {
            let cols = self.columns_of(j.index())?;
            for (i, wi) in a.terms() {
                let w = wi * wj;
                let r0 = D * i.index();
                for r in 0..D {
                    for c in 0..D {
                        out[r][c] += w * cols[c * n + r0 + r];
                    }
                }
            }
        }
        Some(out)
    }

    /// Whether the columns of every node of `contact` are cached.
    pub fn contains_contact(&self, contact: &ContactPoint) -> bool {
        contact.nodes().iter().all(|n| self.contains(n.index()))
    }

    /// $C_{\mathcal{WW}}$ for the given nodes, DOF order `[ux(w0), uy(w0), (uz(w0),) ux(w1), …]`,
    /// row-major into `out` (length $(Dm)^2$). Symmetrised as $\tfrac12 (C + C^\top)$ to remove
    /// round-off.
    pub fn working_block_into(&self, nodes: &[usize], out: &mut [f64]) -> Option<()> {
        let d = D * nodes.len();
        assert_eq!(out.len(), d * d);
        for (j, &b) in nodes.iter().enumerate() {
            for comp in 0..D {
                let col = self.column(b, comp)?;
                for (i, &a) in nodes.iter().enumerate() {
                    for r in 0..D {
                        out[(D * i + r) * d + D * j + comp] = col[D * a + r];
                    }
                }
            }
        }
        for i in 0..d {
            for j in i + 1..d {
                let m = 0.5 * (out[i * d + j] + out[j * d + i]);
                out[i * d + j] = m;
                out[j * d + i] = m;
            }
        }
        Some(())
    }

    /// Displacement of every DOF caused by world forces on cached nodes,
    /// $u = \sum_w C_{:,w} f_w$, written into `out` (length $Dn$). Returns `None` if a node is not
    /// cached. Allocates nothing.
    pub fn displacement_from_forces_into(&self, forces_n: impl IntoIterator<Item = (usize, [f64; D])>, out: &mut [f64]) -> Option<()> {
        out.fill(0.0);
        for (node, f) in forces_n {
            for (comp, &fc) in f.iter().enumerate() {
                if fc != 0.0 {
                    for (o, c) in out.iter_mut().zip(self.column(node, comp)?) {
                        *o += c * fc;
                    }
                }
            }
        }
        Some(())
    }
}

/// What the mixed solver reads of the compliance: the world-frame block between two contacts,
/// $W_{ab} = P_a C P_b^\top$ ($D \times D$, displacement of `a` per unit force on `b`), `None`
/// when the store lacks what it needs. Implemented by the column cache
/// ([`ComplianceCache::contact_block`]) and by the 3D node-block store
/// ([`store::NodeBlockStore`]); [`crate::mixed::MixedSolver`]'s methods are generic over it
/// (monomorphised, no dynamic dispatch on the hot path).
pub trait ContactBlocks<const D: usize> {
    /// The block $W_{ab}$, or `None` when a node's data is missing.
    fn contact_block(&self, a: &ContactPoint, b: &ContactPoint) -> Option<[[f64; D]; D]>;
}

impl<const D: usize> ContactBlocks<D> for ComplianceCache<D> {
    #[inline]
    fn contact_block(&self, a: &ContactPoint, b: &ContactPoint) -> Option<[[f64; D]; D]> {
        ComplianceCache::contact_block(self, a, b)
    }
}

/// A shareable tissue model.
pub type SharedTissue = Arc<TissueModel>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::MaterialMap;
    use crate::material::{Material, PlaneModel};
    use crate::mesh::{MeshLimits, RectMeshParams};

    use crate::fixtures::strain_square as model;

    #[test]
    fn columns_invert_the_stiffness_and_are_symmetric() {
        let m = model(8);
        let mut cache = ComplianceCache::new(m.mesh().n_nodes());
        let mut scratch = m.column_scratch();
        let nodes = [20usize, 37, 63];
        for &n in &nodes {
            assert!(cache.ensure(&m, n, &mut scratch).unwrap());
            assert!(!cache.ensure(&m, n, &mut scratch).unwrap());
        }
        assert_eq!(cache.n_computed(), 3);
        // K c = e at free DOFs.
        let mut kc = vec![0.0; m.n_dofs()];
        for &n in &nodes {
            for comp in 0..2 {
                crate::assembly::mul_stiffness(m.stiffness(), cache.column(n, comp).unwrap(), &mut kc);
                for d in 0..m.n_dofs() {
                    if !m.is_fixed(d / 2) {
                        let e = if d == 2 * n + comp { 1.0 } else { 0.0 };
                        assert!((kc[d] - e).abs() < 1e-9, "K c at {d}: {}", kc[d]);
                    }
                }
            }
        }
        let a = cache.block(20, 63).unwrap();
        let b = cache.block(63, 20).unwrap();
        for i in 0..2 {
            for j in 0..2 {
                assert!((a[i][j] - b[j][i]).abs() < 1e-12 * a[i][j].abs().max(1e-9));
            }
        }
        let mut u = vec![0.0; m.n_dofs()];
        cache.displacement_from_forces_into([(37, [0.0, 2.0])], &mut u).unwrap();
        assert_eq!(u[2 * 20 + 1], 2.0 * cache.block(20, 37).unwrap()[1][1]);
        assert!(cache.displacement_from_forces_into([(5, [0.0, 1.0])], &mut u).is_none());
        cache.evict(37);
        assert!(!cache.contains(37));
        cache.ensure(&m, 40, &mut scratch).unwrap();
        assert_eq!(cache.len(), 3);
    }

    #[test]
    fn model_errors_are_named() {
        let mesh = RectMeshParams::new(3, 3, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 1.0, poisson_ratio: 0.3 }],
            PlaneModel::Strain { thickness_m: 1.0 },
        )
        .unwrap();
        let e = TissueModel::new(mesh.clone(), mats.clone(), &[]).unwrap_err();
        assert_eq!(e, TissueError::NoFixedNodes);
        let e = TissueModel::new(mesh.clone(), mats.clone(), &[0, 12]).unwrap_err();
        assert!(e.to_string().contains("fixed node 12 does not exist"), "{e}");
        // One fixed node: the body can still rotate about it.
        let e = TissueModel::new(mesh, mats, &[4]).unwrap_err();
        assert!(e.to_string().contains("rigid body"), "{e}");
    }

    /// The 3D cache (three columns of length 3n per node) returns the blocks, the working
    /// block and the displacement from forces of the dense compliance it was filled from;
    /// `ensure_with` computes once and reports errors without storing.
    #[test]
    fn the_3d_cache_serves_blocks_of_its_columns() {
        let n_nodes = 9;
        let (c, mut cache) = crate::fixtures::random_spd_compliance::<3>(n_nodes, 5);
        let n = 3 * n_nodes;
        assert_eq!(cache.len(), n_nodes);
        assert_eq!(cache.column_bytes(), n_nodes * 3 * n * 8);
        let b = cache.block(2, 7).unwrap();
        for r in 0..3 {
            for col in 0..3 {
                assert_eq!(b[r][col], c[(6 + r) * n + 21 + col]);
            }
        }
        let nodes = [7usize, 2, 4];
        let mut w = vec![0.0; 81];
        cache.working_block_into(&nodes, &mut w).unwrap();
        for (i, &a) in nodes.iter().enumerate() {
            for (j, &bn) in nodes.iter().enumerate() {
                for r in 0..3 {
                    for col in 0..3 {
                        assert_eq!(w[(3 * i + r) * 9 + 3 * j + col], c[(3 * a + r) * n + 3 * bn + col]);
                    }
                }
            }
        }
        let mut u = vec![0.0; n];
        cache.displacement_from_forces_into([(4, [1.0, -2.0, 0.5]), (8, [0.0, 0.0, 3.0])], &mut u).unwrap();
        for r in 0..n {
            let e = c[r * n + 12] - 2.0 * c[r * n + 13] + 0.5 * c[r * n + 14] + 3.0 * c[r * n + 26];
            assert!((u[r] - e).abs() < 1e-18, "{r}");
        }
        cache.evict(4);
        assert!(cache.block(0, 4).is_none());
        let cols: Vec<f64> = (0..3 * n).map(|k| c[(k % n) * n + 12 + k / n]).collect();
        let mut calls = 0;
        assert_eq!(cache.ensure_with(4, |_| Err::<(), _>("no columns")), Err("no columns"));
        assert!(!cache.contains(4));
        for _ in 0..2 {
            cache
                .ensure_with(4, |out| -> Result<(), ()> {
                    calls += 1;
                    out.copy_from_slice(&cols);
                    Ok(())
                })
                .unwrap();
        }
        assert_eq!((calls, cache.n_computed()), (1, 1));
        assert_eq!(cache.block(0, 4).unwrap()[2][1], c[2 * n + 13]);
    }
}
