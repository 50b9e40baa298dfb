//! Tearing: a held point whose force across the shaft exceeds what its region's tissue can hold
//! tears free (issue 35). A rigid needle turned while inserted drags its held points sideways
//! with it; linear elasticity answers with forces that grow without bound (60–107 N, points
//! dragged out of the phantom), which no tissue exerts: it tears, and the shaft cuts sideways.
//!
//! **The bound.** The tissue of region $r$ fails under the tip at its puncture force $P_r$ (or,
//! once cut, its cutting force $C_r$), spread over the tip's cross-section. Across the shaft, a
//! held point bears on a strip of the shaft one point spacing long; the force that point's
//! tissue can hold across the shaft is taken as $F_{tear,r} = \kappa \max(P_r, C_r)$ with
//! $\kappa$ = [`Sim3Params::tear_force_factor`](super::Sim3Params::tear_force_factor) (default
//! [`DEFAULT_TEAR_FORCE_FACTOR`] = 100, the margin of the 2D divergence bounds): generous, so
//! that the shipped runs and a steering turn stay below it (a 10° turn about the entry point,
//! 75 mm deep in the 9³ cube phantom: 13 N on one point against 30 N; the shipped 3D examples
//! tear nothing, their outputs unchanged), while a needle dragging tissue by centimetres goes
//! past (the turn of 34° about the base: 71 N). A region with $P_r = C_r = 0$ offers no
//! resistance to cutting and holds nothing across the shaft either. The bound is on force: a
//! point at its tear force on a free face still sits a few millimetres to a centimetre outside
//! the undeformed surface, as linear elasticity puts it.
//!
//! **The release.** After the tick's stick/slip iteration, the point most over its bound
//! (largest ratio) is released ([`super::Sim3Stats::tears`]) and the working set solved again;
//! repeated until no point is over, at most once per point. The output then carries no held
//! point above its bound.

use super::{SimError3, Simulation3};
use crate::ids::{Axis, Slot};

/// The default $\kappa$ of the module docs: 100.
pub const DEFAULT_TEAR_FORCE_FACTOR: f64 = 100.0;

impl Simulation3 {
    /// The force across the shaft (N) that the tissue of `region` holds at one point before it
    /// tears (module docs).
    pub fn tear_force_n(&self, region: usize) -> f64 {
        let r = &self.params.regions[region];
        self.params.tear_force_factor * r.puncture_force_n.max(r.cutting_force_n)
    }

    /// Releases the held points over their tear force, the worst first, solving the working
    /// set again after each (module docs). Returns the last solve's (iterations, converged),
    /// `None` when nothing tore.
    pub(super) fn tear_overloaded(&mut self, frame: &[[f64; 3]; 3]) -> Result<Option<(usize, bool)>, SimError3> {
        let mut last = None;
        for _ in 0..self.pts.len() {
            let mut worst: Option<(Slot, f64)> = None;
            for slot in Slot::all(self.pts.len()) {
                let f = self.solver.force_local(slot);
                let across = f[Axis::Lateral].hypot(f[Axis::Binormal]);
                let ratio = across / self.tear_force_n(self.pts[slot.index()].region);
                if ratio > 1.0 && worst.is_none_or(|(_, w)| ratio > w) {
                    worst = Some((slot, ratio));
                }
            }
            let Some((slot, _)) = worst else { break };
            self.remove(slot)?;
            self.stats.tears += 1;
            self.stats.releases += 1;
            last = Some(self.resolve_active_set(frame)?);
        }
        Ok(last)
    }
}
