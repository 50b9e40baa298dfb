//! The step's scratch, sized up front from the parameters and separate from the persistent
//! state: buffers a stage fills and reads within one tick, and caches keyed by what they were
//! computed for. Architecture invariant: nothing here carries information from one tick to the
//! next that is not rebuilt on a key mismatch, so a scratch built anew with [`Scratch::new`]
//! gives the same results (the `scratch_is_droppable` test checks it).

use crate::compliance::TissueModel;

use super::SimParams;
use super::active_set::ActiveSetScratch;
use super::capture::CaptureScratch;
use super::flexible::FlexScratch;
use super::jacobian::ProbeScratch;
use super::param_limits::{MAX_CAPTURES_PER_TICK, NEAR_TIP_CANDIDATES};

/// All per-step work space.
pub(super) struct Scratch {
    pub capture: CaptureScratch,
    pub active_set: ActiveSetScratch,
    pub probe: ProbeScratch,
    /// The flexible needle's couplings and probe curve (`None` for a rigid needle).
    pub flex: Option<FlexScratch>,
}

impl Scratch {
    /// Scratch for `params` (validated) in `model`: every buffer at the capacity it will need
    /// (the working set's, or a named limit of [`super::param_limits`]).
    pub fn new(model: &TissueModel, params: &SimParams) -> Self {
        let cap = params.max_needle_nodes;
        Self {
            capture: CaptureScratch {
                candidates: Vec::with_capacity(NEAR_TIP_CANDIDATES),
                captured: Vec::with_capacity(MAX_CAPTURES_PER_TICK),
                columns: model.column_scratch(),
                column_buf: vec![0.0; 2 * model.n_dofs()],
            },
            active_set: ActiveSetScratch { order: Vec::with_capacity(cap), changes: Vec::with_capacity(2 * cap) },
            probe: ProbeScratch::new(cap),
            flex: params.needle.flexible().map(|f| FlexScratch::new(f, params.initial_pose, cap)),
        }
    }
}
