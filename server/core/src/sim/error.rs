//! The simulation's errors ([`SimError`]) and the quantities a divergence check names
//! ([`Divergence`]).

use crate::compliance::TissueError;
use crate::mixed::MixedError;

/// Errors of the simulation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError {
    /// A parameter is invalid, found by [`super::Simulation::new`] (through
    /// [`super::SimParams::validate`] and [`super::SimParams::validate_for_mesh`]) before
    /// anything is built; the message names it.
    #[error("invalid simulation parameter: {0}")]
    InvalidParams(String),
    /// A step was commanded a pose with a NaN or infinite component; the state is unchanged
    /// (counted in [`super::SimStats::rejected_poses`]).
    #[error("tick {tick}: the commanded base pose ({}, {}, {}) is not finite; the pose was rejected and the state kept", crate::num::num(*x_m), crate::num::num(*y_m), crate::num::num(*theta_rad))]
    NonFinitePose { tick: u64, x_m: f64, y_m: f64, theta_rad: f64 },
    /// The tissue model failed computing a compliance column: in a step, for a node the
    /// prefetch had not cached, or in [`super::Simulation::prefetch_columns`].
    #[error(transparent)]
    Tissue(#[from] TissueError),
    /// The working-set solver refused an update within a step or a stiffness probe (a singular
    /// pivot, a non-finite value or angle, a full working set); the tick is not finished.
    #[error(transparent)]
    Mixed(#[from] MixedError),
    /// A step's result is not finite or exceeds a physical bound derived from the scene
    /// ([`DivergenceBounds`](super::DivergenceBounds)): the solve diverged. The step's output is
    /// not written (the last good one stays in [`super::Simulation::output`]) and every later
    /// step returns this error again: the simulation is faulted for good.
    #[error("tick {tick}: the solve diverged: {what} = {value:.3e} {unit} is not within the bound {bound:.3e} {unit}", unit = what.unit())]
    Diverged { tick: u64, what: Divergence, value: f64, bound: f64 },
}

/// Which quantity of a step diverged (see [`SimError::Diverged`]). `Copy` and coded as a small
/// integer, so a real-time thread can store it in an atomic and name it later.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Divergence {
    /// The magnitude of the force of the tissue on the needle base, $|F|$.
    Force = 1,
    /// The torque of the tissue on the needle about the base, $|\tau|$.
    Torque = 2,
    /// The magnitude of one needle node's force on the tissue.
    NodeForce = 3,
    /// The magnitude of one needle node's displacement.
    Displacement = 4,
    /// The length of shaft in the tissue.
    InsertedLength = 5,
    /// A point of the needle's shape (a joint of a flexible needle, or its tip) is not finite,
    /// or lies farther from the base than the needle is long.
    NeedleShape = 6,
}

impl Divergence {
    /// The quantity's name, as in messages.
    pub fn as_str(&self) -> &'static str {
        match self {
            Divergence::Force => "|force|",
            Divergence::Torque => "|torque|",
            Divergence::NodeForce => "|needle node force|",
            Divergence::Displacement => "|needle node displacement|",
            Divergence::InsertedLength => "inserted length",
            Divergence::NeedleShape => "needle shape distance from the base",
        }
    }
    /// The unit of the value and the bound.
    pub fn unit(&self) -> &'static str {
        match self {
            Divergence::Force | Divergence::NodeForce => "N",
            Divergence::Torque => "N·m",
            Divergence::Displacement | Divergence::InsertedLength | Divergence::NeedleShape => "m",
        }
    }
    /// The code stored by a real-time thread (never 0, which means "no fault").
    pub fn code(&self) -> u8 {
        *self as u8
    }
    /// The quantity of a code from [`Divergence::code`].
    pub fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            1 => Divergence::Force,
            2 => Divergence::Torque,
            3 => Divergence::NodeForce,
            4 => Divergence::Displacement,
            5 => Divergence::InsertedLength,
            6 => Divergence::NeedleShape,
            _ => return None,
        })
    }
}

impl std::fmt::Display for Divergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}
