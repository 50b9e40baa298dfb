//! The 3D step's scratch: buffers a stage fills and reads within one tick (the friction order,
//! the active set's changes) and the work space of the prefetch between steps (a column solve's,
//! or the node-block store's own worker), sized up front or made on first use.

use crate::d3::TetColumnScratch;
use crate::ids::Slot;

use super::active_set::Change;
use super::{BlockRequest, Sim3BlockWorker};

/// All per-step work space.
pub(super) struct Scratch3 {
    /// The non-tip working points by arc length (friction shares).
    pub order: Vec<Slot>,
    /// The active set's changes of one iteration.
    pub changes: Vec<(Slot, Change)>,
    /// One node's columns (column store), between steps.
    pub column_buf: Vec<f64>,
    /// The column solve's work space, made on first use (between steps).
    pub column_scratch: Option<TetColumnScratch>,
    /// With node blocks, the worker of [`super::Simulation3::prefetch`], made on its first call
    /// and kept (its mirror of the slots is the store's).
    pub block_worker: Option<Box<Sim3BlockWorker>>,
    /// The requests of one [`super::Simulation3::prefetch`] (storage reused).
    pub block_requests: Vec<BlockRequest>,
}
