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
                candidates: Vec::with_capacity(near_tip_reserve(model, params)),
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

/// The reserve of the spatial grid's answer near the tip: [`NEAR_TIP_CANDIDATES`], or more on a
/// fine mesh, where the approaching query (a square of side $\ell + 2b$ around the path ahead:
/// lookahead $\ell$, lateral band $b$ — the longest edge, or twice the capture radius) covers
/// more nodes: twice the mean node density times that square widened by a cell on each side.
/// A query past it still works and is counted ([`super::SimStats::candidate_growths`]).
fn near_tip_reserve(model: &TissueModel, params: &SimParams) -> usize {
    let mesh = model.mesh();
    let (lo, hi) = mesh.bounding_box_m();
    let area = ((hi[0] - lo[0]) * (hi[1] - lo[1])).max(f64::MIN_POSITIVE);
    let density = mesh.n_nodes() as f64 / area;
    let nodes = mesh.nodes_m();
    let max_edge = mesh
        .triangles()
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| (nodes[a][0] - nodes[b][0]).hypot(nodes[a][1] - nodes[b][1]))
        .fold(0.0, f64::max);
    let band = max_edge.max(2.0 * params.capture_radius_m);
    let side = params.lookahead_m + 2.0 * band + 4.0 * max_edge;
    let estimate = 2.0 * density * side * side;
    // Bounded by the mesh itself.
    NEAR_TIP_CANDIDATES.max((estimate.min(mesh.n_nodes() as f64)) as usize)
}
