//! The compliance store's plumbing, between steps: columns computed here
//! ([`Simulation3::prefetch_columns`]) or by a worker ([`Simulation3::insert_columns`]), node
//! blocks requested and inserted ([`Simulation3::requests_into`],
//! [`Simulation3::insert_payload`], [`Simulation3::prefetch_blocks`]), either store filled on
//! this thread by the simulation itself ([`Simulation3::prefetch`], what the offline runs call),
//! pinned nodes, and the least-recently-used eviction that makes room.

use std::sync::Arc;

use crate::compliance::ComplianceCache3;

use super::{BlockPayload, BlockRequest, ComplianceStore3, NodeBlockStore, Sim3BlockWorker, SimError3, Simulation3};
#[cfg(doc)]
use super::{Sim3Stats, TetTissueModel};

/// What [`Simulation3::insert_columns_owned`] returns: the evicted node, if any, and the box not
/// kept.
pub type InsertedColumns = (Option<usize>, Option<Box<[f64]>>);

impl Simulation3 {
    /// Computes (allocating, outside any step) the columns of up to `max_nodes` of the nodes the
    /// last step reported as approaching, nearest first. Returns how many it computed.
    ///
    /// Errors: [`SimError3::Tissue`] when a column solve fails (those before it stay);
    /// [`SimError3::WrongStore`] with node blocks (use [`Simulation3::prefetch_blocks`]).
    pub fn prefetch_columns(&mut self, max_nodes: usize) -> Result<usize, SimError3> {
        self.columns_mut("prefetch_columns")?;
        let mut n = 0;
        // The pinned nodes first, then the approaching ones.
        for k in 0..self.pins.len() + self.out.approaching.len() {
            let node = if k < self.pins.len() { self.pins[k] } else { self.out.approaching[k - self.pins.len()] };
            if n == max_nodes {
                break;
            }
            if !self.cache.contains(node) {
                let scratch = self.scratch.column_scratch.get_or_insert_with(|| self.model.column_scratch());
                self.model.compliance_columns_into(node, &mut self.scratch.column_buf, scratch)?;
                self.make_room();
                if let ComplianceStore3::Columns(c) = &mut self.cache {
                    c.insert(node, &self.scratch.column_buf);
                }
                self.stamp[node] = self.tick + 1;
                n += 1;
            }
        }
        Ok(n)
    }

    /// Stores the columns of `node_idx` computed elsewhere
    /// ([`TetTissueModel::compliance_columns_into`], length $9n$); in a full cache they replace
    /// the least recently used node's, which is returned.
    ///
    /// Errors: [`SimError3::WrongStore`] with node blocks.
    pub fn insert_columns(&mut self, node_idx: usize, columns: &[f64]) -> Result<Option<usize>, SimError3> {
        let evicted = if self.columns_mut("insert_columns")?.contains(node_idx) { None } else { self.make_room() };
        self.columns_mut("insert_columns")?.insert(node_idx, columns);
        self.stamp[node_idx] = self.tick + 1;
        Ok(evicted)
    }

    /// [`Simulation3::insert_columns`] for columns handed over as an owned box (length $9n$):
    /// the box is kept, or copied into reused storage, so that nothing is allocated (a real-time
    /// thread receiving a worker's columns). Returns the evicted node, if any, and the box not
    /// kept (for the caller to hand back to the worker).
    ///
    /// Errors: [`SimError3::WrongStore`] with node blocks (the box is dropped).
    pub fn insert_columns_owned(&mut self, node_idx: usize, columns: Box<[f64]>) -> Result<InsertedColumns, SimError3> {
        let evicted = if self.columns_mut("insert_columns_owned")?.contains(node_idx) { None } else { self.make_room() };
        let spare = self.columns_mut("insert_columns_owned")?.insert_owned(node_idx, columns);
        self.stamp[node_idx] = self.tick + 1;
        Ok((evicted, spare))
    }

    fn columns_mut(&mut self, call: &'static str) -> Result<&mut ComplianceCache3, SimError3> {
        match &mut self.cache {
            ComplianceStore3::Columns(c) => Ok(c),
            ComplianceStore3::Blocks(_) => Err(SimError3::WrongStore { call, needs: "columns", has: "node-block" }),
        }
    }

    fn blocks_mut(&mut self, call: &'static str) -> Result<&mut NodeBlockStore, SimError3> {
        match &mut self.cache {
            ComplianceStore3::Blocks(b) => Ok(b),
            ComplianceStore3::Columns(_) => Err(SimError3::WrongStore { call, needs: "node-block", has: "columns" }),
        }
    }

    /// Whether node `j` may give up its cached data: not pinned, not used by the last step.
    fn evictable(&self, j: usize) -> bool {
        !self.pinned[j] && self.stamp[j] < self.tick
    }

    /// Evicts the least recently used cached node that the last step did not use and that is
    /// not pinned, when the column cache is full.
    fn make_room(&mut self) -> Option<usize> {
        let ComplianceStore3::Columns(cache) = &self.cache else { return None };
        if cache.len() < self.params.max_cached_nodes {
            return None;
        }
        let mut victim: Option<(usize, u64)> = None;
        for slot in 0..cache.n_slots() {
            if let Some(j) = cache.node_in_slot(slot) {
                let s = self.stamp[j];
                if self.evictable(j) && victim.is_none_or(|(_, v)| s < v) {
                    victim = Some((j, s));
                }
            }
        }
        match victim {
            Some((j, _)) => {
                if let ComplianceStore3::Columns(c) = &mut self.cache {
                    c.evict(j);
                }
                self.stats.columns_evicted += 1;
                Some(j)
            }
            None => {
                self.stats.cache_over_cap += 1;
                None
            }
        }
    }

    /// Pins `node_idx`: its compliance data is never evicted, and it is fetched before the
    /// approaching nodes ([`Simulation3::prefetch_columns`], [`Simulation3::requests_into`]).
    /// For what a step reads beyond the working points (a target's element nodes: with node
    /// blocks, $C_{vw}$ needs both nodes cached). Idempotent; allocates (between steps).
    ///
    /// Errors: [`SimError3::UnknownNode`].
    pub fn pin_node(&mut self, node_idx: usize) -> Result<(), SimError3> {
        let n_nodes = self.pinned.len();
        if node_idx >= n_nodes {
            return Err(SimError3::UnknownNode { node_idx, n_nodes });
        }
        if !self.pinned[node_idx] {
            self.pinned[node_idx] = true;
            self.pins.push(node_idx);
        }
        Ok(())
    }

    /// Unpins `node_idx` (it may be evicted again); nothing for an unknown or unpinned node.
    pub fn unpin_node(&mut self, node_idx: usize) {
        if self.pinned.get(node_idx).copied().unwrap_or(false) {
            self.pinned[node_idx] = false;
            self.pins.retain(|&v| v != node_idx);
        }
    }

    /// The pinned nodes, in the order they were pinned (a live session's worker fetches them
    /// before the approaching nodes).
    pub fn pinned_nodes(&self) -> &[usize] {
        &self.pins
    }

    /// Whether `node_idx` is pinned.
    pub fn is_pinned(&self, node_idx: usize) -> bool {
        self.pinned.get(node_idx).copied().unwrap_or(false)
    }

    /// With node blocks: up to `max_nodes` requests for the worker, appended to `out` (cleared
    /// first), for the pinned nodes not cached, then the approaching ones (nearest first); each
    /// reserves its slot ([`NodeBlockStore::reserve`]: an empty one, else the least recently
    /// used node's that is neither pinned nor used by the last step, evicted now; when there is
    /// none, counted in [`Sim3Stats::cache_over_cap`] and the list ends). Nodes already
    /// requested are not requested again. Returns how many. Allocates nothing when `out` has
    /// room.
    ///
    /// Errors: [`SimError3::WrongStore`] with columns.
    pub fn requests_into(&mut self, max_nodes: usize, out: &mut Vec<BlockRequest>) -> Result<usize, SimError3> {
        self.blocks_mut("requests_into")?;
        out.clear();
        let n_pins = self.pins.len();
        for k in 0..n_pins + self.out.approaching.len() {
            if out.len() == max_nodes {
                break;
            }
            let node = if k < n_pins { self.pins[k] } else { self.out.approaching[k - n_pins] };
            let ComplianceStore3::Blocks(store) = &self.cache else { unreachable!("checked above") };
            if self.model.is_fixed(node) || store.contains(node) || store.is_pending(node) {
                continue;
            }
            let Some(slot) = store.choose_slot(|j| self.evictable(j), |j| self.stamp[j]) else {
                self.stats.cache_over_cap += 1;
                break;
            };
            let (req, evicted) = self.blocks_mut("requests_into")?.reserve(node, slot)?;
            if evicted.is_some() {
                self.stats.columns_evicted += 1;
            }
            self.stamp[node] = self.tick + 1;
            out.push(req);
        }
        Ok(out.len())
    }

    /// With node blocks: applies a worker's answer (payloads in the order of the requests),
    /// $O(M)$ copies, no solve, no allocation.
    ///
    /// Errors: [`SimError3::WrongStore`] with columns; [`SimError3::Blocks`] for a payload that
    /// answers no pending request (nothing changes).
    pub fn insert_payload(&mut self, payload: &BlockPayload) -> Result<(), SimError3> {
        self.blocks_mut("insert_payload")?.insert(payload)?;
        Ok(())
    }

    /// A worker for this simulation's node-block store (same model, same number of slots).
    ///
    /// Errors: [`SimError3::WrongStore`] with columns; [`SimError3::WorkerInUse`] once
    /// [`Simulation3::prefetch`] has made the simulation's own; [`SimError3::Sparse`] passed on
    /// from [`Sim3BlockWorker::new`].
    pub fn block_worker(&self) -> Result<Sim3BlockWorker, SimError3> {
        let ComplianceStore3::Blocks(store) = &self.cache else {
            return Err(SimError3::WrongStore { call: "block_worker", needs: "node-block", has: "columns" });
        };
        if self.scratch.block_worker.is_some() {
            return Err(SimError3::WorkerInUse { call: "block_worker", by: "the simulation's own worker (prefetch)" });
        }
        Ok(Sim3BlockWorker::new(Arc::clone(&self.model), store.cap())?)
    }

    /// With node blocks, on this thread between steps: [`Simulation3::requests_into`] (up to
    /// `max_nodes`), [`Sim3BlockWorker::compute`], [`Simulation3::insert_payload`]. Returns how
    /// many nodes it inserted. Allocates (the request list; [`Simulation3::prefetch_blocks_into`]
    /// reuses one).
    ///
    /// Errors: those of the three.
    pub fn prefetch_blocks(&mut self, worker: &mut Sim3BlockWorker, max_nodes: usize) -> Result<usize, SimError3> {
        self.prefetch_blocks_into(worker, max_nodes, &mut Vec::new())
    }

    /// [`Simulation3::prefetch_blocks`] with the request list in `requests` (cleared first; it
    /// allocates only to grow).
    ///
    /// Errors: those of [`Simulation3::prefetch_blocks`].
    pub fn prefetch_blocks_into(
        &mut self,
        worker: &mut Sim3BlockWorker,
        max_nodes: usize,
        requests: &mut Vec<BlockRequest>,
    ) -> Result<usize, SimError3> {
        self.requests_into(max_nodes, requests)?;
        if requests.is_empty() {
            return Ok(0);
        }
        for p in worker.compute(requests)? {
            self.insert_payload(p)?;
        }
        Ok(requests.len())
    }

    /// Fills the compliance store on this thread, between steps, whichever store it is: the
    /// columns of up to `max_nodes` nodes ([`Simulation3::prefetch_columns`]), or with node blocks
    /// their blocks ([`Simulation3::prefetch_blocks_into`]) computed by the simulation's own
    /// worker, made here at the first call ([`Simulation3::block_worker`]) and kept, with its
    /// request list, for the simulation's life. What a run without a worker thread calls (the
    /// offline driver, the Python package's `step`). Returns how many nodes it filled.
    /// Allocates (a column solve; the worker's rows).
    ///
    /// Errors: those of the store's prefetch; [`SimError3::WorkerInUse`] with node blocks when
    /// the store already holds or awaits nodes that another worker computes (its mirror and
    /// this one's would differ).
    pub fn prefetch(&mut self, max_nodes: usize) -> Result<usize, SimError3> {
        let ComplianceStore3::Blocks(store) = &self.cache else {
            return self.prefetch_columns(max_nodes);
        };
        let mut worker = match self.scratch.block_worker.take() {
            Some(w) => w,
            None => {
                if store.n_inserted() > 0 || (0..store.cap()).any(|s| store.node_in_slot(s).is_some()) {
                    return Err(SimError3::WorkerInUse { call: "prefetch", by: "a worker from block_worker" });
                }
                Box::new(self.block_worker()?)
            }
        };
        let mut requests = std::mem::take(&mut self.scratch.block_requests);
        let n = self.prefetch_blocks_into(&mut worker, max_nodes, &mut requests);
        self.scratch.block_requests = requests;
        self.scratch.block_worker = Some(worker);
        n
    }
}
