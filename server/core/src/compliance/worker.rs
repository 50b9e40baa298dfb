//! The worker side of the node-block store ([`super::store::NodeBlockStore`]), written once for
//! both dimensions: sparse compliance rows of the requested nodes and their blocks against the
//! worker's mirror of the slots ([`BlockWorker`]; the 3D simulation's is [`Sim3BlockWorker`]).
//! `Send`: it can run on its own thread; the offline runs call it between steps
//! ([`crate::sim3::Simulation3::prefetch_blocks`]).
//!
//! For a batch of requests it computes the rows $Y_v$ of up to [`ROWS_BATCH`] nodes at once
//! ([`SparseFactorView::rows_batch_into`]: one forward solve with $Nk$ right-hand sides, each
//! block of $L$ read once per batch), then, request by request in order, moves the rows into the
//! requested slot of its mirror and computes $C_{vw} = Y_v^\top Y_w$ against every filled slot
//! ([`SparseFactorView::block`]). Memory: the rows of at most $M$ nodes (about 240 KB each at
//! 257k tetrahedra) plus the payloads' $M$ blocks each.
//!
//! The model's dimension is a [`Dim`] and the blocks' a const generic `N` (as the stores'); the
//! worker names both, `BlockWorker<D, N>`, and they are checked equal when it is compiled.

use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::compliance::TissueModel;
use crate::compliance::sparse::{FactorPattern, NodeRows, SparseComplianceError, SparseFactorView, SparseRowsScratch};
use crate::dim::{Dim, Dim3};

use super::store::{Block, BlockPayload, BlockRequest};

/// Nodes per batched forward solve (BENCHMARKS.md: 32 amortises the reads of $L$).
pub const ROWS_BATCH: usize = 32;

/// Counters of a worker: work done and the time it took.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WorkerStats {
    /// Nodes whose rows were computed.
    pub rows: u64,
    /// Node blocks computed.
    pub blocks: u64,
    /// Time in the row solves.
    pub rows_time: Duration,
    /// Time in the block products.
    pub blocks_time: Duration,
}

/// The worker of a node-block store (module docs): a model of dimension `D` and blocks of
/// `N` $= D::N$ rows.
pub struct BlockWorker<D: Dim, const N: usize> {
    model: Arc<TissueModel<D>>,
    pattern: FactorPattern,
    scratch: SparseRowsScratch,
    /// The node in each slot of the mirror (`usize::MAX`: never filled).
    slot_node: Vec<usize>,
    /// The rows of each slot's node (storage reused).
    rows: Vec<NodeRows<N>>,
    /// Rows of the current batch.
    batch_rows: Vec<NodeRows<N>>,
    batch_nodes: Vec<usize>,
    /// Payload storage, reused across calls.
    payloads: Vec<BlockPayload<N>>,
    stats: WorkerStats,
}

/// The 3D simulation's worker.
pub type Sim3BlockWorker = BlockWorker<Dim3, 3>;

impl<D: Dim, const N: usize> BlockWorker<D, N> {
    /// A worker for `model` and a store of `cap` slots.
    ///
    /// Errors: [`SparseComplianceError::WrongDofsPerNode`] cannot happen for a
    /// [`TissueModel`] but is passed on.
    pub fn new(model: Arc<TissueModel<D>>, cap: usize) -> Result<Self, SparseComplianceError> {
        const { assert!(D::N == N, "the blocks have the model's dimension") };
        let (pattern, scratch) = {
            let view = SparseFactorView::<N>::new(model.cholesky())?;
            (view.pattern(), view.scratch())
        };
        Ok(Self {
            model,
            pattern,
            scratch,
            slot_node: vec![usize::MAX; cap],
            rows: vec![NodeRows::default(); cap],
            batch_rows: vec![NodeRows::default(); ROWS_BATCH],
            batch_nodes: Vec::with_capacity(ROWS_BATCH),
            payloads: Vec::new(),
            stats: WorkerStats::default(),
        })
    }

    /// Number of slots mirrored.
    pub fn cap(&self) -> usize {
        self.slot_node.len()
    }
    /// The node in slot `slot` of the mirror.
    pub fn node_in_slot(&self, slot: usize) -> Option<usize> {
        self.slot_node.get(slot).copied().filter(|&v| v != usize::MAX)
    }
    /// Work counters.
    pub fn stats(&self) -> WorkerStats {
        self.stats
    }
    /// Heap bytes of the rows held (capacity).
    pub fn rows_bytes(&self) -> usize {
        self.rows.iter().chain(&self.batch_rows).map(NodeRows::heap_bytes).sum()
    }

    /// Answers `requests` in order (module docs); the payloads are valid until the next call.
    ///
    /// Errors: [`SparseComplianceError::UnknownNode`] for a node past the mesh, or a slot past
    /// the mirror (reported as that node); the requests before the failing batch are answered
    /// in the mirror but their payloads are lost, so the caller must start over (a programming
    /// error: the simulation only requests nodes of its mesh in its slots).
    pub fn compute(&mut self, requests: &[BlockRequest]) -> Result<&[BlockPayload<N>], SparseComplianceError> {
        let cap = self.cap();
        let n_nodes = self.model.mesh().n_nodes();
        if let Some(r) = requests.iter().find(|r| r.node_idx >= n_nodes || r.slot >= cap) {
            return Err(SparseComplianceError::UnknownNode { node_idx: r.node_idx, n_nodes });
        }
        let view = SparseFactorView::<N>::with_pattern(self.model.cholesky(), &self.pattern)?;
        while self.payloads.len() < requests.len() {
            self.payloads.push(BlockPayload { node_idx: 0, slot: 0, blocks: vec![[[0.0; N]; N]; cap] });
        }
        for (chunk_idx, chunk) in requests.chunks(ROWS_BATCH).enumerate() {
            self.batch_nodes.clear();
            self.batch_nodes.extend(chunk.iter().map(|r| r.node_idx));
            let t = Instant::now();
            view.rows_batch_into(&self.batch_nodes, &mut self.scratch, &mut self.batch_rows[..chunk.len()])?;
            self.stats.rows_time += t.elapsed();
            self.stats.rows += chunk.len() as u64;
            let t = Instant::now();
            for (k, r) in chunk.iter().enumerate() {
                std::mem::swap(&mut self.rows[r.slot], &mut self.batch_rows[k]);
                self.slot_node[r.slot] = r.node_idx;
                let p = &mut self.payloads[chunk_idx * ROWS_BATCH + k];
                p.node_idx = r.node_idx;
                p.slot = r.slot;
                let yv = &self.rows[r.slot];
                for (j, b) in p.blocks.iter_mut().enumerate() {
                    *b = if self.slot_node[j] == usize::MAX {
                        [[0.0; N]; N]
                    } else {
                        self.stats.blocks += 1;
                        block_of(yv, &self.rows[j])
                    };
                }
            }
            self.stats.blocks_time += t.elapsed();
        }
        Ok(&self.payloads[..requests.len()])
    }
}

fn block_of<const N: usize>(a: &NodeRows<N>, b: &NodeRows<N>) -> Block<N> {
    SparseFactorView::block(a, b)
}
