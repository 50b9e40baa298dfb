//! needlesim-offline: the simulator run from a script, faster than real time, on the caller's
//! thread. [`driver`] is the one run loop (trajectory → step → prefetch, one tick limit, one tick
//! rounding, one error policy) of both dimensions ([`scripted`]: what it needs of the 2D and the
//! 3D simulation) that every offline caller uses: [`simulate`] and [`simulate3`] (the `simulate`
//! command's CSV and `--dump-state`), [`plan`] and [`plan3`] (insertion planning), the Simulate
//! RPC of the service crate, exercise runs, the measurement pipeline's synthetic experiments,
//! the lab's benchmarks and motion suite, and the Python package's `run`.

pub mod convergence;
pub mod driver;
pub mod plan;
pub mod plan3;
pub mod scripted;
pub mod simulate;
pub mod simulate3;

pub use convergence::{ConvergencePolicy, UnconvergedTick};
pub use driver::{
    DEFAULT_MAX_TICKS, DEFAULT_PREFETCH_NODES_PER_TICK, MAX_TICKS_LIMIT, PREALLOCATED_TICKS, RunError, RunOptions, RunTotals, Script,
    ScriptedRun, Tick, preallocated_ticks,
};
pub use scripted::{RunParams, ScriptedSim};
