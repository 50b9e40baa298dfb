//! The 3D step's scratch: buffers a stage fills and reads within one tick (the friction order,
//! the active set's changes, a capture's disc weights) and the work space of the prefetch between
//! steps (a column solve's, or the node-block store's own worker), sized up front or made on
//! first use.

use crate::d3::TetColumnScratch;
use crate::d3::disc::DiscWeights;
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
    /// A capture's disc weights ([`super::Sim3Params::disc_radius_m`]), room for
    /// [`DISC_SCRATCH_NODES`] nodes.
    pub disc: DiscWeights,
}

/// Nodes a capture's disc may touch before [`crate::d3::disc::disc_weights_into`] gives up (more
/// than [`crate::contact::MAX_TERMS`], so that a disc with a few nodes of weight zero is still
/// seen whole; any disc over `MAX_TERMS` weighted nodes stays a point).
pub const DISC_SCRATCH_NODES: usize = 4 * crate::contact::MAX_TERMS;
