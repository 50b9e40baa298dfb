//! The 3D step's scratch: buffers a stage fills and reads within one tick (the friction order,
//! the active set's changes) and the column solve's work space between steps, sized up front.

use crate::d3::TetColumnScratch;
use crate::ids::Slot;

use super::active_set::Change;

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
}
