//! The 3D simulation's errors ([`SimError3`]).

use crate::compliance::sparse::SparseComplianceError;
use crate::d3::TetTissueError;
use crate::mixed::MixedError;

use super::{BlockStoreError, PoseError};
#[cfg(doc)]
use super::{NodeBlockStore, Simulation3, StoreKind3};

/// Errors of the 3D simulation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError3 {
    /// At [`Simulation3::new`]: a parameter out of range or not matching the mesh (the message
    /// names it).
    #[error("invalid 3D simulation parameters: {0}")]
    InvalidParams(String),
    /// At [`Simulation3::step`]: the commanded pose is not finite or its quaternion not unit;
    /// the state is unchanged.
    #[error("tick {tick}: {source}")]
    Pose { tick: u64, source: PoseError },
    /// At [`Simulation3::step`]: the working solver refused an update mid-tick (a frame, a
    /// condition switch or a release made the system singular); the tick is lost.
    #[error(transparent)]
    Mixed(#[from] MixedError),
    /// At [`Simulation3::prefetch_columns`]: a column solve failed (columns computed before it
    /// stay).
    #[error(transparent)]
    Tissue(#[from] TetTissueError),
    /// A call that needs the other compliance store ([`StoreKind3`]): `call` names it.
    #[error("Simulation3::{call} needs the {needs} store; this simulation uses {has}")]
    WrongStore { call: &'static str, needs: &'static str, has: &'static str },
    /// At [`Simulation3::prefetch`] or [`Simulation3::block_worker`]: the node-block store is
    /// fed by another worker (one from [`Simulation3::block_worker`] and the simulation's own
    /// cannot share a store: each mirrors its slots).
    #[error("Simulation3::{call}: the node-block store is already fed by {by}")]
    WorkerInUse { call: &'static str, by: &'static str },
    /// At [`Simulation3::insert_payload`]: a payload that does not answer the oldest pending
    /// request (see [`NodeBlockStore`]'s protocol).
    #[error(transparent)]
    Blocks(#[from] BlockStoreError),
    /// At [`Simulation3::prefetch_blocks`] or [`Simulation3::block_worker`]: the worker refused
    /// a request or the factor.
    #[error(transparent)]
    Sparse(#[from] SparseComplianceError),
    /// At [`Simulation3::wrench_stiffness`] of a flexible needle: rod and tissue in series,
    /// $I + H_{PP}\tilde G_{PP}$, has a pivot below 1e-14 of its largest entry (not expected:
    /// both compliances are positive semidefinite and the tissue's definite).
    #[error("tick {tick}: the flexible needle's stiffness is singular (smallest relative pivot {pivot:e})")]
    SingularRodCoupling { tick: u64, pivot: f64 },
    /// At [`Simulation3::pin_node`]: the node does not exist.
    #[error("node {node_idx} does not exist: the mesh has {n_nodes} nodes")]
    UnknownNode { node_idx: usize, n_nodes: usize },
}
