//! The one convergence policy of every scripted driver (2D and 3D: `simulate`, the Simulate
//! RPC, `plan`, exercise runs, the Python package): a tick whose step did not converge
//! ([`Unconverged`]: the stick/slip iteration or the flexible needle's shape passes stopped at
//! their cap) stops the run with an error naming the tick ([`UnconvergedTick`]), unless the
//! caller asked to keep such ticks ([`ConvergencePolicy::Keep`]: `--keep-unconverged`, the
//! request's `keep_unconverged`), which are then marked in its output. A live session's
//! counterpart is its fault (needlesim-session).

use needlesim_core::sim::Unconverged;

/// What a scripted run does with a tick that did not converge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ConvergencePolicy {
    /// Stop at the first such tick with [`UnconvergedTick`] (the default).
    #[default]
    Fail,
    /// Keep it (the caller marks it in its output).
    Keep,
}

impl ConvergencePolicy {
    /// `Keep` when `keep` is true, else `Fail`.
    pub fn keeping(keep: bool) -> Self {
        if keep { ConvergencePolicy::Keep } else { ConvergencePolicy::Fail }
    }

    /// Applies the policy to tick `tick` (script time `t_s`) whose output is unconverged for
    /// `why` (`None`: converged, always fine).
    pub fn check(self, tick: u64, t_s: f64, why: Option<Unconverged>) -> Result<(), UnconvergedTick> {
        match (self, why) {
            (ConvergencePolicy::Fail, Some(why)) => Err(UnconvergedTick { tick, t_s, why }),
            _ => Ok(()),
        }
    }
}

/// A run stopped by [`ConvergencePolicy::Fail`] at a tick that did not converge.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "the run stopped at tick {tick} (t = {t_s:.4} s): the tick did not converge ({why}); its forces and contact states would be the solver's last iterate, not an answer (ask to keep unconverged ticks, marked as such, with --keep-unconverged or keep_unconverged)"
)]
pub struct UnconvergedTick {
    pub tick: u64,
    /// The script's time at that tick, s.
    pub t_s: f64,
    pub why: Unconverged,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fail_stops_at_an_unconverged_tick_naming_it_and_keep_does_not() {
        let why = Some(Unconverged::ShapePassCap);
        let e = ConvergencePolicy::Fail.check(17, 0.017, why).unwrap_err();
        assert_eq!((e.tick, e.why), (17, Unconverged::ShapePassCap));
        assert!(e.to_string().starts_with("the run stopped at tick 17 (t = 0.0170 s): the tick did not converge"), "{e}");
        assert!(ConvergencePolicy::Keep.check(17, 0.017, why).is_ok());
        assert!(ConvergencePolicy::Fail.check(17, 0.017, None).is_ok());
        assert_eq!(ConvergencePolicy::default(), ConvergencePolicy::Fail);
    }
}
