//! What [`Simulation3::new`] derives once from the mesh and the parameters (each tetrahedron's
//! diameter, the lookahead's sampling step), the construction itself (all per-step storage
//! sized up front), and the read-only accessors.

use std::sync::Arc;

use crate::compliance::ComplianceCache3;
use crate::d3::TetTissueModel;
use crate::mixed::MixedSolver3;
use crate::viscous::ViscCoeffs;

use crate::d3::disc::DiscWeights;

use super::scratch::{DISC_SCRATCH_NODES, Scratch3};
use super::{
    BasePose3, ComplianceStore3, MAX_APPROACHING, MAX_PENDING_CAPTURES, NodeBlockStore, Sim3Params, Sim3Stats, SimError3, Simulation3,
    StepOutput3, StoreKind3, TargetsOut3, flex, stiffness, targets,
};

impl Simulation3 {
    /// Validates the parameters against the model and sizes all per-step storage.
    ///
    /// Errors: [`SimError3::InvalidParams`] for a parameter out of range
    /// ([`Sim3Params::validate`]), a number of region parameters other than the mesh's, or a
    /// target whose centre lies outside the mesh (naming it).
    pub fn new(model: Arc<TetTissueModel>, params: Sim3Params) -> Result<Self, SimError3> {
        let mesh = model.mesh();
        params.validate(mesh.region_names().len().max(1)).map_err(SimError3::InvalidParams)?;
        let tet_diam_m: Vec<f64> = (0..mesh.n_tets()).map(|t| crate::d3::mesh::longest_edge_m(mesh.tet_points_m(t))).collect();
        let min_diam = tet_diam_m.iter().copied().fold(f64::INFINITY, f64::min);
        let max_diam_m = tet_diam_m.iter().copied().fold(0.0, f64::max);
        let n_nodes = mesh.n_nodes();
        let cap = params.max_contacts;
        let (cache, column_buf) = match params.store.resolve(n_nodes) {
            StoreKind3::NodeBlocks => (ComplianceStore3::Blocks(NodeBlockStore::new(n_nodes, params.max_block_nodes)), Vec::new()),
            _ => {
                let mut c = ComplianceCache3::for_nodes(n_nodes);
                c.reserve(params.max_cached_nodes.min(n_nodes) + 16);
                (ComplianceStore3::Columns(c), vec![0.0; 9 * n_nodes])
            }
        };
        let pose = params.initial_pose;
        let visc = ViscCoeffs::new(params.viscoelastic, params.tick_rate_hz);
        let targets = targets::TargetTracker::new(&model, &params.targets)?;
        let flex = params.needle.flexible().map(|f| flex::Flex3::new(f, pose.position_m, pose.frame(), cap));
        let mut out = StepOutput3 {
            tick: 0,
            time_s: 0.0,
            pose,
            clamped: false,
            base_force_n: [0.0; 3],
            base_torque_nm: [0.0; 3],
            axial_force_n: 0.0,
            tip_m: pose.point_at(params.needle_length_m),
            inserted_length_m: 0.0,
            contacts: Vec::with_capacity(cap),
            approaching: Vec::with_capacity(MAX_APPROACHING),
            active_set_iterations: 0,
            converged: true,
            shape_passes_capped: false,
            targets: TargetsOut3::default(),
        };
        targets.initial_output(out.tip_m, pose.axis(), &mut out.targets);
        let mut sim = Self {
            setup: Setup3 {
                tet_diam_m,
                sample_step_m: 0.25 * min_diam,
                max_diam_m,
                visc,
                compliance_scale: visc.map_or(1.0, |c| c.compliance_scale()),
            },
            pose,
            solver: MixedSolver3::with_capacity(cap),
            pts: Vec::with_capacity(cap),
            pending: Vec::with_capacity(MAX_PENDING_CAPTURES),
            deferred_since_m: None,
            axial_speed_m_per_s: 0.0,
            cache,
            pinned: vec![false; n_nodes],
            pins: Vec::new(),
            stamp: vec![0; n_nodes],
            last_tip_region: None,
            tick: 0,
            stats: Sim3Stats::default(),
            scratch: Scratch3 {
                order: Vec::with_capacity(cap),
                changes: Vec::with_capacity(cap),
                column_buf,
                column_scratch: None,
                block_worker: None,
                block_requests: Vec::new(),
                disc: DiscWeights::with_capacity(DISC_SCRATCH_NODES),
            },
            out,
            stiffness: stiffness::StiffnessScratch::with_capacity(cap, flex.is_some()),
            targets,
            flex,
            drift: crate::drift::DriftCheck::new::<3>(cap),
            model,
            params,
        };
        // A target's displaced centre reads C(target node, working node): with node blocks both
        // must be cached, so the targets' (free) nodes are pinned.
        let target_nodes: Vec<usize> = sim.targets.nodes().filter(|&v| !sim.model.is_fixed(v)).collect();
        for v in target_nodes {
            sim.pin_node(v)?;
        }
        Ok(sim)
    }

    /// The tissue model.
    pub fn model(&self) -> &Arc<TetTissueModel> {
        &self.model
    }

    /// The parameters.
    pub fn params(&self) -> &Sim3Params {
        &self.params
    }

    /// The pose applied by the last step.
    pub fn pose(&self) -> BasePose3 {
        self.pose
    }

    /// The last step's output.
    pub fn output(&self) -> &StepOutput3 {
        &self.out
    }

    /// Counters over the simulation's life.
    pub fn stats(&self) -> Sim3Stats {
        self.stats
    }

    /// The working solver (for its update counters: [`MixedSolver3::stats`]).
    pub fn solver(&self) -> &MixedSolver3 {
        &self.solver
    }

    /// The compliance store (columns or node blocks).
    pub fn cache(&self) -> &ComplianceStore3 {
        &self.cache
    }

    /// The number of the next tick.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// The flexible needle's rod (`None` for a rigid needle): its shape, frames and counters.
    pub fn rod(&self) -> Option<&crate::rod3::Rod3> {
        self.flex.as_ref().map(|f| &f.rod)
    }

    /// Flexible needle: (shape passes beyond the first, shape updates that did not converge)
    /// over the simulation's life; `None` for a rigid needle.
    pub fn shape_stats(&self) -> Option<(u64, u64)> {
        self.flex.as_ref().map(|f| (f.shape_passes, f.shape_unconverged))
    }
}

/// The simulation's fixed set-up.
pub(super) struct Setup3 {
    /// Longest edge of each tetrahedron, m.
    pub tet_diam_m: Vec<f64>,
    /// Step of the axis sampling for approaching nodes (half the shortest tetrahedron edge
    /// scale), m.
    pub sample_step_m: f64,
    /// The largest tetrahedron diameter, m.
    pub max_diam_m: f64,
    /// The viscous recursion's constants (`None`: elastic tissue; [`crate::viscous`]).
    pub visc: Option<ViscCoeffs>,
    /// The working solver's scale of every compliance block (and of the near field's): $1/\gamma$,
    /// exactly 1 when elastic.
    pub compliance_scale: f64,
}
