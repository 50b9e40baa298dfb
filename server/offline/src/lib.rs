//! needlesim-offline: the simulator run from a script, faster than real time, on the caller's
//! thread. [`driver`] is the one run loop (trajectory → step → prefetch, one tick limit, one error
//! policy) that every offline caller uses: [`simulate`] (the `simulate` command's CSV and
//! `--dump-state`), [`plan`] (insertion planning), the Simulate RPC of the service crate; the
//! measurement pipeline's synthetic experiments and the benchmarks can take it too.

pub mod convergence;
pub mod driver;
pub mod plan;
pub mod plan3;
pub mod simulate;
pub mod simulate3;

pub use convergence::{ConvergencePolicy, UnconvergedTick};
pub use driver::{
    DEFAULT_MAX_TICKS, DEFAULT_PREFETCH_NODES_PER_TICK, MAX_TICKS_LIMIT, PREALLOCATED_TICKS, RunError, RunOptions, RunTotals, Script,
    ScriptedRun, Tick, preallocated_ticks,
};
