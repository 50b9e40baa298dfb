//! The step interface both dimensions share ([`Stepper`], implemented by the 2D [`Simulation`]
//! and the 3D [`Simulation3`]): what a caller that builds a simulation and steps it tick by tick
//! needs, whatever the dimension — the scripted driver of needlesim-offline and the Python
//! package's `Simulation.step` are written once against it instead of once per dimension
//! (issue 32, item 3). Each method is the simulation's own, unchanged: the trait adds no work
//! to a step. The prefetch between steps is the one each dimension runs without a worker
//! thread (3D: either store, [`Simulation3::prefetch`]).

use std::sync::Arc;

use crate::compliance::TissueModel;
use crate::d3::TetTissueModel;
use crate::needle::BasePose;
use crate::sim::{SimError, SimParams, Simulation, StepOutput, Unconverged};
use crate::sim3::{BasePose3, Sim3Params, SimError3, Simulation3, StepOutput3};

/// A simulation stepped tick by tick towards commanded base poses, in either dimension.
pub trait Stepper: Sized {
    /// The factorised tissue it runs in.
    type Model;
    /// Its parameters (needle, limits, tick rate, targets, initial pose).
    type Params: Clone;
    /// A commanded base pose.
    type Pose: Copy;
    /// What a step writes (rewritten in place each tick).
    type Output;
    /// Why building or stepping it failed.
    type Error: StepError;

    /// 2 or 3.
    const DIM: usize;

    /// A simulation of `model` with `params`, at rest at `params`' initial pose.
    fn new(model: Arc<Self::Model>, params: Self::Params) -> Result<Self, Self::Error>;

    /// Sets the pose a simulation built from `params` starts at.
    fn set_initial_pose(params: &mut Self::Params, pose: Self::Pose);

    /// The tick rate `params` step at, Hz.
    fn tick_rate_hz(params: &Self::Params) -> f64;

    /// One tick towards `commanded` (the simulation's own `step`).
    fn step(&mut self, commanded: Self::Pose) -> Result<&Self::Output, Self::Error>;

    /// The last step's output (the initial state's before any step).
    fn output(&self) -> &Self::Output;

    /// Why the last step did not converge, if it did not (the scripted runs' convergence
    /// policy and a live session's fault read this one verdict in both dimensions).
    fn unconverged(&self) -> Option<Unconverged>;

    /// Fills the compliance store, on this thread, for up to `max_nodes` nodes the last step
    /// reported as approaching (outside any step: it allocates); returns how many. 2D: their
    /// columns ([`Simulation::prefetch_columns`]); 3D: their columns or node blocks, whichever
    /// store the simulation uses ([`Simulation3::prefetch`]).
    fn prefetch(&mut self, max_nodes: usize) -> Result<usize, Self::Error>;
}

/// What a caller adding context to a simulation's error (the tick and time a scripted run
/// stopped at, the status of an RPC) needs to know of it in either dimension.
pub trait StepError: std::error::Error + Send + Sync + 'static {
    /// Whether the message already names its tick as what ended the run (a divergence in 2D; a
    /// refused pose or a singular rod coupling in 3D): the context then names only the time, not
    /// the tick twice.
    fn names_its_tick(&self) -> bool;
    /// Whether the commanded pose was refused (not finite, or not a unit quaternion): the
    /// caller's input, not the simulation's failure; the state is unchanged.
    fn is_bad_pose(&self) -> bool;
}

impl StepError for SimError {
    fn names_its_tick(&self) -> bool {
        matches!(self, SimError::Diverged { .. })
    }

    fn is_bad_pose(&self) -> bool {
        matches!(self, SimError::NonFinitePose { .. })
    }
}

impl StepError for SimError3 {
    fn names_its_tick(&self) -> bool {
        matches!(self, SimError3::Pose { .. } | SimError3::SingularRodCoupling { .. })
    }

    fn is_bad_pose(&self) -> bool {
        matches!(self, SimError3::Pose { .. })
    }
}

impl Stepper for Simulation {
    type Model = TissueModel;
    type Params = SimParams;
    type Pose = BasePose;
    type Output = StepOutput;
    type Error = SimError;

    const DIM: usize = 2;

    fn new(model: Arc<TissueModel>, params: SimParams) -> Result<Self, SimError> {
        Simulation::new(model, params)
    }

    fn set_initial_pose(params: &mut SimParams, pose: BasePose) {
        params.initial_pose = pose;
    }

    fn tick_rate_hz(params: &SimParams) -> f64 {
        params.tick_rate_hz
    }

    fn step(&mut self, commanded: BasePose) -> Result<&StepOutput, SimError> {
        Simulation::step(self, commanded)
    }

    fn output(&self) -> &StepOutput {
        Simulation::output(self)
    }

    fn unconverged(&self) -> Option<Unconverged> {
        Simulation::output(self).unconverged()
    }

    fn prefetch(&mut self, max_nodes: usize) -> Result<usize, SimError> {
        Simulation::prefetch_columns(self, max_nodes)
    }
}

impl Stepper for Simulation3 {
    type Model = TetTissueModel;
    type Params = Sim3Params;
    type Pose = BasePose3;
    type Output = StepOutput3;
    type Error = SimError3;

    const DIM: usize = 3;

    fn new(model: Arc<TetTissueModel>, params: Sim3Params) -> Result<Self, SimError3> {
        Simulation3::new(model, params)
    }

    fn set_initial_pose(params: &mut Sim3Params, pose: BasePose3) {
        params.initial_pose = pose;
    }

    fn tick_rate_hz(params: &Sim3Params) -> f64 {
        params.tick_rate_hz
    }

    fn step(&mut self, commanded: BasePose3) -> Result<&StepOutput3, SimError3> {
        Simulation3::step(self, commanded)
    }

    fn output(&self) -> &StepOutput3 {
        Simulation3::output(self)
    }

    fn unconverged(&self) -> Option<Unconverged> {
        Simulation3::output(self).unconverged()
    }

    fn prefetch(&mut self, max_nodes: usize) -> Result<usize, SimError3> {
        Simulation3::prefetch(self, max_nodes)
    }
}
