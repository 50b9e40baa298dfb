//! The 2D step's round-off checks of the hybrid matrix ([`crate::drift`], one code with 3D's):
//! a long random session keeps $H$ exact, a drifted row is found.

#[cfg(test)]
mod tests {
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    use crate::drift::{Checked, DriftCheck, check_one, row_residual};
    use crate::fixtures::{phantom, phantom_params};
    use crate::ids::{Axis, Slot};
    use crate::mixed::Condition;
    use crate::needle::{BasePose, FlexibleNeedle, NeedleShape, RigidNeedle};
    use crate::sim::{ContactModel, SimParams, Simulation};

    const SIDE_M: f64 = 0.1;

    /// A trainee's random session on the `n × n` phantom: every 400 ticks a new goal (depth
    /// −5…60 mm, angle ±8.6° off vertical, entry ±2 mm), approached at ≤ 20 mm/s and ≤ 6°/s.
    struct RandomSession {
        rng: SmallRng,
        now: [f64; 3],
        goal: [f64; 3],
        length_m: f64,
    }

    impl RandomSession {
        fn new(seed: u64, length_m: f64) -> Self {
            let start = [-0.005, -std::f64::consts::FRAC_PI_2, 0.5 * SIDE_M];
            Self { rng: SmallRng::seed_from_u64(seed), now: start, goal: start, length_m }
        }
        /// `[depth, angle, entry x]` → the base pose of a needle through the entry point.
        fn pose(&self) -> BasePose {
            let [d, a, x0] = self.now;
            BasePose::new(x0 + (d - self.length_m) * a.cos(), SIDE_M + (d - self.length_m) * a.sin(), a)
        }
        fn next(&mut self, k: u64) -> BasePose {
            if k.is_multiple_of(400) {
                let half_pi = std::f64::consts::FRAC_PI_2;
                self.goal = [
                    self.rng.random_range(-0.005..0.06),
                    -half_pi + self.rng.random_range(-0.15..0.15),
                    0.05 + self.rng.random_range(-0.002..0.002),
                ];
            }
            let max_step = [2e-5, 1e-4, 2e-5];
            for i in 0..3 {
                self.now[i] += (self.goal[i] - self.now[i]).clamp(-max_step[i], max_step[i]);
            }
            self.pose()
        }
    }

    fn params(needle: NeedleShape) -> SimParams {
        SimParams {
            contact: ContactModel::MaterialPoints { spacing_m: 0.002, width_m: 0.0 },
            columns_in_step: false,
            max_needle_nodes: 48,
            initial_pose: RandomSession::new(0, needle.tip_s_m()).pose(),
            ..phantom_params(needle)
        }
    }

    /// The hybrid matrix's largest deviation from a rebuild, relative per row and per kind of
    /// column (prescribed displacement or force: their entries have different units).
    fn h_drift(sim: &Simulation) -> f64 {
        let (solver, cache) = (&sim.state.ws.solver, &sim.state.cache);
        let href = solver.hybrid_from_scratch(cache).unwrap();
        let d = solver.n_dofs();
        let kind = |k: usize| solver.condition(Slot::new(k / 2), Axis::of_local_dof::<2>(k));
        let mut worst = 0.0f64;
        for i in 0..d {
            for cond in [Condition::Displacement, Condition::Force] {
                let cols: Vec<usize> = (0..d).filter(|&j| kind(j) == cond).collect();
                let scale = cols.iter().map(|&j| href[(i, j)].abs()).fold(0.0, f64::max);
                if scale > 0.0 {
                    let diff = cols.iter().map(|&j| (solver.hybrid(i, j) - href[(i, j)]).abs()).fold(0.0, f64::max);
                    worst = worst.max(diff / scale);
                }
            }
        }
        worst
    }

    /// Runs `ticks` of a seeded random session; every `compare_every` ticks the hybrid matrix is
    /// compared with a rebuild. Returns the simulation and the largest drift seen.
    fn random_session(needle: NeedleShape, seed: u64, ticks: u64, compare_every: u64) -> (Simulation, f64, usize) {
        let len = needle.tip_s_m();
        let mut sim = Simulation::new(phantom(19), params(needle)).unwrap();
        let mut session = RandomSession::new(seed, len);
        let (mut worst, mut compared) = (0.0f64, 0);
        for k in 0..ticks {
            sim.step(session.next(k)).unwrap();
            sim.prefetch_columns(32).unwrap();
            if k % compare_every == compare_every - 1 && sim.state.ws.len() > 0 {
                worst = worst.max(h_drift(&sim));
                compared += 1;
            }
        }
        (sim, worst, compared)
    }

    /// Issue 19: over a long randomised session the $O(d^2)$ updates keep $H$ within 1e-9 of a
    /// rebuild, and the step's round-off checks see it (they ran, found nothing to rebuild).
    #[test]
    fn issue_19_the_hybrid_matrix_does_not_drift_over_a_long_random_session() {
        for (needle, seed) in
            [(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }), 7), (NeedleShape::Flexible(FlexibleNeedle::gauge17_steel(0.1)), 8)]
        {
            let (sim, worst, compared) = random_session(needle, seed, 60_000, 997);
            let s = sim.stats();
            assert!(compared > 20 && s.captures > 20 && s.releases > 10 && s.stick_to_slip > 10, "the session moved little: {s:?}");
            assert!(s.hybrid_checks > 60_000 / 16 / 2, "{s:?}");
            assert!(worst < 1e-9, "H drifted {worst:e} from a rebuild");
            assert!(sim.hybrid_max_residual() < 1e-9, "residual {:e}", sim.hybrid_max_residual());
            assert_eq!((s.hybrid_rebuilds, s.hybrid_rebuild_failures), (0, 0));
        }
    }

    /// The hour at 1 kHz (3.6 M ticks), rigid and flexible needles: `cargo test -p
    /// needlesim-core --lib sim::drift::tests::an_hour -- --ignored --nocapture` (about a minute
    /// for the rigid needle, a few for the flexible one; the core is optimised in test builds).
    #[test]
    #[ignore = "2 × 3.6 M ticks: minutes"]
    fn an_hour_of_random_session_keeps_h_exact() {
        for (needle, seed) in
            [(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }), 19), (NeedleShape::Flexible(FlexibleNeedle::gauge17_steel(0.1)), 20)]
        {
            let (sim, worst, compared) = random_session(needle, seed, 3_600_000, 10_007);
            let s = sim.stats();
            println!(
                "{}: 3.6 M ticks: {compared} comparisons with a rebuild, largest drift {worst:.2e}; {} step checks, largest residual {:.2e}, {} rebuilds ({} refused); {} captures, {} releases, {} pivots, {} stick→slip",
                if matches!(needle, NeedleShape::Rigid(_)) { "rigid" } else { "flexible" },
                s.hybrid_checks,
                sim.hybrid_max_residual(),
                s.hybrid_rebuilds,
                s.hybrid_rebuild_failures,
                s.captures,
                s.releases,
                sim.solver().stats().n_pivots,
                s.stick_to_slip
            );
            assert!(compared > 300 && s.hybrid_checks > 3_600_000 / 16 / 2, "{s:?}");
            assert!(worst < 1e-9 && sim.hybrid_max_residual() < 1e-9);
        }
    }

    /// The check sees an inconsistent solution, and a rebuild changes the results only by
    /// round-off: a run that rebuilds at every check (tolerance below zero) matches one that
    /// never does.
    #[test]
    fn a_drifted_row_is_found_and_a_rebuild_changes_nothing_but_round_off() {
        let needle = NeedleShape::Rigid(RigidNeedle { length_m: 0.1 });
        let mut a = Simulation::new(phantom(19), params(needle)).unwrap();
        let mut b = Simulation::new(phantom(19), params(needle)).unwrap();
        b.set_hybrid_drift_tol(-1.0);
        let (mut sa, mut sb) = (RandomSession::new(3, 0.1), RandomSession::new(3, 0.1));
        let mut worst = 0.0f64;
        for k in 0..6000 {
            let (oa, ob) = (a.step(sa.next(k)).unwrap().clone(), b.step(sb.next(k)).unwrap().clone());
            let scale = oa.force_n[0].abs().max(oa.force_n[1].abs()).max(1e-6);
            worst = worst.max((oa.force_n[0] - ob.force_n[0]).abs().max((oa.force_n[1] - ob.force_n[1]).abs()) / scale);
            assert_eq!(oa.needle_nodes.len(), ob.needle_nodes.len(), "tick {k}");
            a.prefetch_columns(32).unwrap();
            b.prefetch_columns(32).unwrap();
        }
        let s = b.stats();
        assert!(s.hybrid_rebuilds > 100 && s.hybrid_rebuilds == s.hybrid_checks, "{s:?}");
        assert_eq!(a.stats().hybrid_rebuilds, 0);
        assert!(worst < 1e-9, "forces differ by {worst:e} after rebuilds");

        // Compliance the hybrid matrix no longer matches (as when H drifts from C): one node's
        // columns scaled by 1 + 1e-5 is a residual of about that size.
        let ws = &mut a.state.ws;
        assert!(ws.len() > 2, "the session ended with {} contacts", ws.len());
        let mut y = Vec::new();
        let before = row_residual(&ws.solver, &a.state.cache, 1, &mut y).unwrap();
        assert!(before < 1e-9, "{before:e}");
        let node = ws.solver.contacts()[1].terms().next().unwrap().0.index();
        let cache = &mut a.state.cache;
        let mut columns: Vec<f64> = (0..2).flat_map(|c| cache.column(node, c).unwrap().to_vec()).collect();
        columns.iter_mut().for_each(|v| *v *= 1.0 + 1e-5);
        cache.insert(node, &columns);
        let after = row_residual(&ws.solver, &a.state.cache, 1, &mut y).unwrap();
        assert!(after > 1e-7, "a perturbed force gave a residual of only {after:e}");
        let mut check = DriftCheck { cursor: 1, ..DriftCheck::new::<2>(48) };
        assert_eq!(check_one(&mut ws.solver, &a.state.cache, &mut check), Checked::Rebuilt);
        assert_eq!(check.cursor, 2 % ws.len());
    }
}
