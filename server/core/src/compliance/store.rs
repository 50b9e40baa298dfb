//! The compliance stores, written once for both dimensions ($N$ = 2 or 3, a const generic as in
//! [`ComplianceCache`]): full node columns ([`ComplianceCache`], small meshes) or node blocks
//! among a bounded set of nodes ([`NodeBlockStore`], large meshes), behind one enum
//! ([`ComplianceStore`]) that the mixed solver reads through
//! [`ContactBlocks`](crate::compliance::ContactBlocks). The 3D simulation ([`crate::sim3`]) uses
//! them as [`ComplianceStore3`], [`NodeBlockStore3`] and [`BlockPayload3`].
//!
//! # Node blocks
//!
//! For up to $M$ cached nodes (slots $0..M$) the store holds the dense symmetric matrix of
//! $N \times N$ blocks $C_{vw}$ between the cached nodes, $N^2 M^2$ doubles (3D, $M = 384$: 10.6 MB),
//! and nothing else: a point block is
//! $W_{ab} = \sum_{k,l} N_{a,k} N_{b,l}\, C_{v_{a,k} v_{b,l}}$ (sixteen reads in 3D), a displacement
//! $u_a = \sum_b W_{ab} f_b$. The blocks are computed off the real-time thread by a
//! [`BlockWorker`](super::worker::BlockWorker) from sparse compliance rows,
//! $C_{vw} = Y_v^\top Y_w$ ([`crate::compliance::sparse`]); inserting a node here copies its
//! row of blocks ($O(M)$, no solve).
//!
//! **Protocol.** The real-time side decides the slots. A [`BlockRequest`] `(node, slot)` reserves
//! `slot` for `node` (the slot is then *pending*; a node previously there is evicted at once and
//! never read again). The worker handles requests in the order issued; for each it puts the
//! node's rows into its mirror of the slot and returns a [`BlockPayload`]: the blocks of the node
//! against the node in every slot of its mirror at that moment, itself included. The real-time
//! side applies payloads in the same order ([`NodeBlockStore::insert`]: row and column of the
//! slot), which makes the slot *ready*. Invariant: for two ready slots $i, j$ the stored block is
//! $C_{v_i v_j}$, because it was last written by the later of the two payloads, computed when the
//! other slot already held its node (its request came first and a slot changes hands only
//! through a later request). An eviction without a replacement ([`NodeBlockStore::evict`])
//! needs no message: the worker's stale rows in that slot only produce blocks that are never
//! read, and are overwritten when the slot is requested again. Which ready node gives up its
//! slot is the caller's rule (the simulation: least recently used, never a pinned node, never one
//! used by the last step).
//!
//! **Reads beyond the working points** (a target's displacement
//! $u_T = \sum_k N_{T,k} \sum_i C_{v_{T,k}\, \cdot} P_i^\top f_i$): [`ComplianceStore::block`]
//! serves $C_{ab}$ from either store; with node blocks both nodes must be cached, so the reader
//! pins the nodes it needs ([`crate::sim3::Simulation3::pin_node`]): a pinned node is requested before
//! the approaching ones and never gives its slot up.

use crate::compliance::{ComplianceCache, ContactBlocks};
use crate::contact::{ContactPoint, MAX_TERMS};

/// An $N \times N$ block of $C$ (m/N), `[r][s]`: displacement along axis r per unit force along s.
pub type Block<const N: usize> = [[f64; N]; N];
/// A $3 \times 3$ block.
pub type Block3 = Block<3>;
/// The 3D node-block store.
pub type NodeBlockStore3 = NodeBlockStore<3>;
/// A 3D worker's answer.
pub type BlockPayload3 = BlockPayload<3>;
/// The compliance store of the 3D simulation.
pub type ComplianceStore3 = ComplianceStore<3>;

const NO_SLOT: u32 = u32::MAX;

/// Errors of the node-block store.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BlockStoreError {
    /// [`NodeBlockStore::insert`]: the payload's slot is not pending for its node (payloads
    /// applied out of order, twice, or from another simulation).
    #[error("block payload for node {node_idx} in slot {slot}: the slot is not pending for that node")]
    NotPending { node_idx: usize, slot: usize },
    /// [`NodeBlockStore::insert`]: the payload holds another number of blocks than the store's
    /// slots.
    #[error("block payload for node {node_idx}: {got} blocks, the store has {cap} slots")]
    WrongLength { node_idx: usize, got: usize, cap: usize },
    /// A node id that does not exist.
    #[error("node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownNode { node_idx: usize, n_nodes: usize },
}

/// The real-time side's request for a node's blocks, in slot `slot` (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockRequest {
    pub node_idx: usize,
    pub slot: usize,
}

/// A worker's answer to a [`BlockRequest`]: `blocks[j]` $= C_{v, w_j}$ for the node $w_j$ in
/// slot `j` of the worker's mirror (zero for a slot never filled), `blocks[slot]` $= C_{vv}$.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockPayload<const N: usize> {
    pub node_idx: usize,
    pub slot: usize,
    pub blocks: Vec<Block<N>>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SlotState {
    Empty,
    Pending,
    Ready,
}

/// The node blocks among at most `cap` cached nodes (module docs). Sized once; nothing in it
/// allocates afterwards.
#[derive(Debug, Clone)]
pub struct NodeBlockStore<const N: usize> {
    cap: usize,
    slot_of_node: Vec<u32>,
    node_of_slot: Vec<usize>,
    state: Vec<SlotState>,
    /// `cap × cap` blocks, row-major by slot.
    blocks: Vec<Block<N>>,
    n_ready: usize,
    n_inserted: u64,
}

impl<const N: usize> NodeBlockStore<N> {
    /// An empty store for a mesh of `n_nodes` nodes with `cap` slots ($8 N^2\,\mathrm{cap}^2$
    /// bytes: 72 cap² in 3D).
    pub fn new(n_nodes: usize, cap: usize) -> Self {
        Self {
            cap,
            slot_of_node: vec![NO_SLOT; n_nodes],
            node_of_slot: vec![usize::MAX; cap],
            state: vec![SlotState::Empty; cap],
            blocks: vec![[[0.0; N]; N]; cap * cap],
            n_ready: 0,
            n_inserted: 0,
        }
    }

    /// Number of slots.
    pub fn cap(&self) -> usize {
        self.cap
    }
    /// Number of ready nodes.
    pub fn len(&self) -> usize {
        self.n_ready
    }
    /// Whether no node is ready.
    pub fn is_empty(&self) -> bool {
        self.n_ready == 0
    }
    /// Payloads applied over the store's life.
    pub fn n_inserted(&self) -> u64 {
        self.n_inserted
    }
    /// Bytes of the block matrix and the slot tables.
    pub fn bytes(&self) -> usize {
        self.blocks.len() * std::mem::size_of::<Block<N>>()
            + self.slot_of_node.len() * 4
            + self.cap * (std::mem::size_of::<usize>() + std::mem::size_of::<SlotState>())
    }

    /// Whether `node_idx`'s blocks are ready.
    #[inline]
    pub fn contains(&self, node_idx: usize) -> bool {
        self.ready_slot(node_idx).is_some()
    }
    /// Whether `node_idx` has a slot whose payload has not arrived.
    pub fn is_pending(&self, node_idx: usize) -> bool {
        match self.slot_of_node.get(node_idx) {
            Some(&s) if s != NO_SLOT => self.state[s as usize] == SlotState::Pending,
            _ => false,
        }
    }
    /// The ready slot of `node_idx`.
    #[inline]
    pub fn ready_slot(&self, node_idx: usize) -> Option<usize> {
        let s = *self.slot_of_node.get(node_idx)?;
        (s != NO_SLOT && self.state[s as usize] == SlotState::Ready).then_some(s as usize)
    }
    /// The node holding slot `slot`, pending or ready.
    pub fn node_in_slot(&self, slot: usize) -> Option<usize> {
        (slot < self.cap && self.state[slot] != SlotState::Empty).then(|| self.node_of_slot[slot])
    }
    /// The ready node in slot `slot`.
    pub fn ready_node_in_slot(&self, slot: usize) -> Option<usize> {
        (slot < self.cap && self.state[slot] == SlotState::Ready).then(|| self.node_of_slot[slot])
    }
    /// An empty slot, if any (the lowest).
    pub fn empty_slot(&self) -> Option<usize> {
        self.state.iter().position(|&s| s == SlotState::Empty)
    }

    /// The node block $C_{ab}$; `None` unless both nodes are ready.
    #[inline]
    pub fn block(&self, a: usize, b: usize) -> Option<Block<N>> {
        let (sa, sb) = (self.ready_slot(a)?, self.ready_slot(b)?);
        Some(self.blocks[sa * self.cap + sb])
    }

    /// Whether every node of `contact` is ready.
    pub fn contains_contact(&self, contact: &ContactPoint) -> bool {
        contact.nodes().iter().all(|n| self.contains(n.index()))
    }

    /// Reserves `slot` for `node_idx` (pending until its payload is inserted), evicting the node
    /// there. Returns the request to hand to the worker and the evicted ready node.
    ///
    /// Errors: [`BlockStoreError::UnknownNode`]. A programming error (panics): `slot` out of
    /// range or pending, `node_idx` already holding a slot.
    pub fn reserve(&mut self, node_idx: usize, slot: usize) -> Result<(BlockRequest, Option<usize>), BlockStoreError> {
        let n_nodes = self.slot_of_node.len();
        if node_idx >= n_nodes {
            return Err(BlockStoreError::UnknownNode { node_idx, n_nodes });
        }
        assert!(self.state[slot] != SlotState::Pending, "slot {slot} is pending");
        assert!(self.slot_of_node[node_idx] == NO_SLOT, "node {node_idx} already has a slot");
        let evicted = (self.state[slot] == SlotState::Ready).then(|| self.node_of_slot[slot]);
        if let Some(old) = evicted {
            self.slot_of_node[old] = NO_SLOT;
            self.n_ready -= 1;
        }
        self.node_of_slot[slot] = node_idx;
        self.slot_of_node[node_idx] = slot as u32;
        self.state[slot] = SlotState::Pending;
        Ok((BlockRequest { node_idx, slot }, evicted))
    }

    /// Applies a worker's payload: row and column `slot` of the block matrix; the slot becomes
    /// ready. $O(M)$, no allocation.
    ///
    /// Errors: [`BlockStoreError::NotPending`] when the slot is not pending for the payload's
    /// node, [`BlockStoreError::WrongLength`] for a payload of another length; nothing changes.
    pub fn insert(&mut self, p: &BlockPayload<N>) -> Result<(), BlockStoreError> {
        let (node_idx, slot) = (p.node_idx, p.slot);
        if p.blocks.len() != self.cap {
            return Err(BlockStoreError::WrongLength { node_idx, got: p.blocks.len(), cap: self.cap });
        }
        if slot >= self.cap || self.state[slot] != SlotState::Pending || self.node_of_slot[slot] != node_idx {
            return Err(BlockStoreError::NotPending { node_idx, slot });
        }
        let m = self.cap;
        for (j, b) in p.blocks.iter().enumerate() {
            self.blocks[slot * m + j] = *b;
            self.blocks[j * m + slot] = std::array::from_fn(|r| std::array::from_fn(|c| b[c][r]));
        }
        self.blocks[slot * m + slot] = p.blocks[slot];
        self.state[slot] = SlotState::Ready;
        self.n_ready += 1;
        self.n_inserted += 1;
        Ok(())
    }

    /// Forgets `node_idx` (ready or pending; a pending slot's payload will then be refused). The
    /// slot becomes empty.
    pub fn evict(&mut self, node_idx: usize) {
        if let Some(&s) = self.slot_of_node.get(node_idx)
            && s != NO_SLOT
        {
            if self.state[s as usize] == SlotState::Ready {
                self.n_ready -= 1;
            }
            self.state[s as usize] = SlotState::Empty;
            self.slot_of_node[node_idx] = NO_SLOT;
        }
    }

    /// The slot for a new node: an empty one, else the ready node's for which `evictable` holds
    /// with the smallest `rank` (least recently used first); `None` when none qualifies.
    pub fn choose_slot(&self, evictable: impl Fn(usize) -> bool, rank: impl Fn(usize) -> u64) -> Option<usize> {
        if let Some(s) = self.empty_slot() {
            return Some(s);
        }
        let mut best: Option<(usize, u64)> = None;
        for s in 0..self.cap {
            if self.state[s] == SlotState::Ready {
                let v = self.node_of_slot[s];
                if evictable(v) {
                    let r = rank(v);
                    if best.is_none_or(|(_, b)| r < b) {
                        best = Some((s, r));
                    }
                }
            }
        }
        best.map(|(s, _)| s)
    }
}

impl<const N: usize> ContactBlocks<N> for NodeBlockStore<N> {
    /// $W_{ab} = \sum_{k,l} N_{a,k} N_{b,l} C_{v_{a,k} v_{b,l}}$: sixteen block reads for two
    /// material points in tetrahedra; `None` unless every node of both contacts is ready.
    #[inline]
    fn contact_block(&self, a: &ContactPoint, b: &ContactPoint) -> Option<Block<N>> {
        let mut out = [[0.0; N]; N];
        let m = self.cap;
        let (mut sa, mut na) = ([(0usize, 0.0f64); MAX_TERMS], 0);
        for (i, wi) in a.terms() {
            sa[na] = (self.ready_slot(i.index())?, wi);
            na += 1;
        }
        for (j, wj) in b.terms() {
            let sj = self.ready_slot(j.index())?;
            for &(si, wi) in &sa[..na] {
                let w = wi * wj;
                let blk = &self.blocks[si * m + sj];
                for r in 0..N {
                    for c in 0..N {
                        out[r][c] += w * blk[r][c];
                    }
                }
            }
        }
        Some(out)
    }
}

/// A compliance store: full columns or node blocks (in 3D, a [`crate::sim3::Simulation3`]'s,
/// chosen by [`crate::sim3::Sim3Params::store`]). Reads mirror [`ComplianceCache`]'s.
#[derive(Debug, Clone)]
pub enum ComplianceStore<const N: usize> {
    /// $N$ full columns per cached node ([`ComplianceCache`]).
    Columns(ComplianceCache<N>),
    /// Node blocks among a bounded set of nodes ([`NodeBlockStore`]).
    Blocks(NodeBlockStore<N>),
}

impl<const N: usize> ComplianceStore<N> {
    /// Whether `node_idx`'s data is cached (ready).
    #[inline]
    pub fn contains(&self, node_idx: usize) -> bool {
        match self {
            Self::Columns(c) => c.contains(node_idx),
            Self::Blocks(b) => b.contains(node_idx),
        }
    }
    /// Whether every node of `contact` is cached.
    pub fn contains_contact(&self, contact: &ContactPoint) -> bool {
        match self {
            Self::Columns(c) => c.contains_contact(contact),
            Self::Blocks(b) => b.contains_contact(contact),
        }
    }
    /// Nodes cached (ready).
    pub fn len(&self) -> usize {
        match self {
            Self::Columns(c) => c.len(),
            Self::Blocks(b) => b.len(),
        }
    }
    /// Whether nothing is cached.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Column sets computed through the cache itself (inside a step this must stay 0); the block
    /// store never computes.
    pub fn n_computed(&self) -> u64 {
        match self {
            Self::Columns(c) => c.n_computed(),
            Self::Blocks(_) => 0,
        }
    }
    /// Bytes held by the store (columns, or the block matrix).
    pub fn bytes(&self) -> usize {
        match self {
            Self::Columns(c) => c.column_bytes(),
            Self::Blocks(b) => b.bytes(),
        }
    }
    /// The node block $C_{ab}$ (m/N). With columns it needs `b`'s columns; with blocks both
    /// nodes ready (pin a node that must stay: [`crate::sim3::Simulation3::pin_node`]).
    #[inline]
    pub fn block(&self, a: usize, b: usize) -> Option<Block<N>> {
        match self {
            Self::Columns(c) => c.block(a, b),
            Self::Blocks(s) => s.block(a, b),
        }
    }
    /// The column cache, when the store is one.
    pub fn columns(&self) -> Option<&ComplianceCache<N>> {
        match self {
            Self::Columns(c) => Some(c),
            Self::Blocks(_) => None,
        }
    }
    /// The node-block store, when the store is one.
    pub fn blocks(&self) -> Option<&NodeBlockStore<N>> {
        match self {
            Self::Columns(_) => None,
            Self::Blocks(b) => Some(b),
        }
    }
}

impl<const N: usize> ContactBlocks<N> for ComplianceStore<N> {
    #[inline]
    fn contact_block(&self, a: &ContactPoint, b: &ContactPoint) -> Option<Block<N>> {
        match self {
            Self::Columns(c) => c.contact_block(a, b),
            Self::Blocks(s) => s.contact_block(a, b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::worker::Sim3BlockWorker;
    use crate::d3::SparseCompliance;
    type NodeBlockStore = NodeBlockStore3;
    type BlockPayload = BlockPayload3;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    /// Seeded random sequences of requests (some answered at once, some left pending across
    /// rounds as a worker thread would), explicit evictions, pins and unpins on a 5³ cube with
    /// 12 slots: after every round the worker's mirror holds the store's node in every pending
    /// and ready slot, every block between ready nodes equals $Y_v^\top Y_w$ computed directly
    /// ([`SparseCompliance::block`]), and no pinned node lost its slot.
    #[test]
    fn random_requests_evictions_and_pins_keep_the_store_and_the_worker_consistent() {
        let model = crate::fixtures::box_phantom3(5);
        let n = model.mesh().n_nodes();
        let cap = 12;
        let mut exact = SparseCompliance::new(&model);
        for seed in [1u64, 2, 3] {
            let mut rng = SmallRng::seed_from_u64(seed);
            let mut store = NodeBlockStore::new(n, cap);
            let mut worker = Sim3BlockWorker::new(model.clone(), cap).unwrap();
            let (mut stamp, mut pinned) = (vec![0u64; n], vec![false; n]);
            let mut queue: Vec<BlockRequest> = Vec::new();
            let (mut evictions, mut checked, mut deferred_rounds) = (0, 0, 0);
            for round in 1..=150u64 {
                for _ in 0..rng.random_range(1..5) {
                    let v = rng.random_range(0..n);
                    if model.is_fixed(v) || store.contains(v) || store.is_pending(v) {
                        continue;
                    }
                    let Some(slot) = store.choose_slot(|j| !pinned[j], |j| stamp[j]) else { continue };
                    let (req, evicted) = store.reserve(v, slot).unwrap();
                    if let Some(e) = evicted {
                        assert!(!pinned[e], "pinned node {e} evicted");
                        evictions += 1;
                    }
                    stamp[v] = round;
                    queue.push(req);
                }
                if rng.random_bool(0.1) {
                    let ready: Vec<usize> = (0..cap).filter_map(|s| store.ready_node_in_slot(s)).filter(|&v| !pinned[v]).collect();
                    if let Some(&v) = ready.get(rng.random_range(0..ready.len().max(1))) {
                        store.evict(v);
                    }
                }
                if rng.random_bool(0.2) {
                    let ready: Vec<usize> = (0..cap).filter_map(|s| store.ready_node_in_slot(s)).collect();
                    if let Some(&v) = ready.get(rng.random_range(0..ready.len().max(1))) {
                        pinned[v] = !pinned[v] && pinned.iter().filter(|&&p| p).count() < cap / 2;
                    }
                }
                if rng.random_bool(0.5) {
                    for p in worker.compute(&queue).unwrap() {
                        store.insert(p).unwrap();
                    }
                    queue.clear();
                } else {
                    deferred_rounds += 1;
                }
                for s in 0..cap {
                    if let Some(v) = store.node_in_slot(s)
                        && !queue.iter().any(|r| r.slot == s)
                    {
                        assert_eq!(worker.node_in_slot(s), Some(v), "seed {seed} round {round}: slot {s}");
                    }
                }
                for v in (0..n).filter(|&v| pinned[v]) {
                    assert!(store.contains(v), "pinned node {v} lost");
                }
                for sa in 0..cap {
                    for sb in 0..cap {
                        let (Some(a), Some(b)) = (store.ready_node_in_slot(sa), store.ready_node_in_slot(sb)) else { continue };
                        let got = store.block(a, b).unwrap();
                        let want = exact.block(a, b).unwrap();
                        let scale = (exact.block(a, a).unwrap()[0][0] * exact.block(b, b).unwrap()[0][0]).sqrt();
                        for r in 0..3 {
                            for c in 0..3 {
                                assert!((got[r][c] - want[r][c]).abs() <= 1e-12 * scale, "seed {seed} round {round}: C[{a},{b}]");
                            }
                        }
                        checked += 1;
                    }
                }
            }
            assert!(evictions > 20 && deferred_rounds > 20 && checked > 1000, "{evictions} evictions, {deferred_rounds}, {checked}");
        }
    }

    /// Payloads out of order, twice, or of the wrong length are refused by name and change
    /// nothing; an evicted pending slot refuses its payload.
    #[test]
    fn bad_payloads_are_refused() {
        let mut store = NodeBlockStore::new(10, 4);
        let (r1, _) = store.reserve(3, 0).unwrap();
        let (r2, _) = store.reserve(5, 1).unwrap();
        let p = |r: BlockRequest, len: usize| BlockPayload { node_idx: r.node_idx, slot: r.slot, blocks: vec![[[1.0; 3]; 3]; len] };
        assert_eq!(store.insert(&p(r1, 3)), Err(BlockStoreError::WrongLength { node_idx: 3, got: 3, cap: 4 }));
        store.insert(&p(r1, 4)).unwrap();
        assert_eq!(store.insert(&p(r1, 4)), Err(BlockStoreError::NotPending { node_idx: 3, slot: 0 }));
        assert!(store.contains(3) && !store.contains(5) && store.is_pending(5));
        store.evict(5);
        assert_eq!(store.insert(&p(r2, 4)), Err(BlockStoreError::NotPending { node_idx: 5, slot: 1 }));
        assert_eq!(store.len(), 1);
        assert!(matches!(store.reserve(10, 2), Err(BlockStoreError::UnknownNode { node_idx: 10, n_nodes: 10 })));
    }

    /// The worker can move to its own thread.
    #[test]
    fn the_worker_is_send() {
        fn send<T: Send>() {}
        send::<Sim3BlockWorker>();
        send::<BlockPayload>();
    }
}
