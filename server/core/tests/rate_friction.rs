//! Rate-dependent friction ([`needlesim_core::needle`]): insertions at 1, 5 and 10 mm/s give
//! increasing force at equal depth, by the amount the law $q_0 + b_v |v|$ predicts.

use needlesim_core::fixtures::{phantom, phantom_params};
use needlesim_core::sim::{ContactModel, NodeState, SimParams, Simulation};
use needlesim_core::{BasePose, NeedleShape, RegionNeedleParams, RigidNeedle};

const DOWN: f64 = -std::f64::consts::FRAC_PI_2;
/// Kinetic friction per length, N/m, and viscous friction per length and speed, N·s/m².
const Q0: f64 = 10.0;
const B_V: f64 = 1000.0;

fn params() -> SimParams {
    SimParams {
        contact: ContactModel::default_points(),
        regions: vec![RegionNeedleParams {
            friction_n_per_m: Q0,
            tip_peak_ratio: 0.0,
            friction_damping_n_s_per_m2: B_V,
            static_friction_ratio: 1.0,
            ..Default::default()
        }],
        ..phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))
    }
}

/// One tick's measures at a depth: the axial force on the base (N, positive resisting the
/// insertion), the slipping contacts' friction sum (N), the friction length $s_{tip} - s_{min}$
/// over which the shares are spread (m), and whether every shaft contact slips.
#[derive(Debug, Clone, Copy)]
struct Sample {
    force_n: f64,
    friction_n: f64,
    length_m: f64,
    all_slipping: bool,
}

/// Inserts straight down at `speed` m/s from 5 mm above the surface and samples every tick whose
/// depth is a multiple of 0.1 mm, as `(depth in 0.1 mm, sample)`.
fn insert(speed: f64, depth_m: f64) -> Vec<(usize, Sample)> {
    let model = phantom(37);
    let mut sim = Simulation::new(model, params()).unwrap();
    let dt = 1e-3;
    let n = ((0.005 + depth_m) / (speed * dt)).round() as usize;
    let per_tenth = (1e-4 / (speed * dt)).round() as usize;
    let mut out = Vec::new();
    for k in 1..=n {
        let o = sim.step(BasePose::new(0.05, 0.205 - speed * dt * k as f64, DOWN)).unwrap();
        let tip_s = 0.1; // the rigid needle's tip arc length
        let (mut friction_n, mut s_min, mut all_slipping) = (0.0, f64::INFINITY, true);
        for nn in &o.needle_nodes {
            match nn.state {
                NodeState::Slipping => {
                    friction_n -= nn.force_n[1];
                    s_min = s_min.min(nn.s_m);
                }
                NodeState::Stuck => all_slipping = false,
                NodeState::Tip => {}
            }
        }
        let sample = Sample { force_n: -o.force_axial_n, friction_n, length_m: (tip_s - s_min).max(0.0), all_slipping };
        if k % per_tenth == 0 {
            let tenths = k / per_tenth;
            if tenths >= 50 {
                out.push((tenths - 50, sample));
            }
        }
        sim.prefetch_columns(16).unwrap();
    }
    out
}

/// Uniform friction ($q_0$ = 10 N/m, no tip peak, static = kinetic so every shaft contact
/// slides), $b_v$ = 1000 N·s/m²: at 10, 20, 30 and 40 mm depth the axial force grows with the
/// speed; the slipping contacts carry exactly $(q_0 + b_v V)\,\ell$ over the friction length
/// $\ell$ they span; and by hand $\ell$ lies between the depth less 5 mm (the first point is taken
/// within the first triangle, the tissue is dragged along) and the depth, so the force is
/// $(q_0 + b_v V)$ times that: 11, 15 and 20 N/m at 1, 5 and 10 mm/s.
#[test]
fn faster_insertions_meet_more_friction_by_the_laws_amount() {
    let speeds = [0.001, 0.005, 0.01];
    let runs: Vec<Vec<(usize, Sample)>> = speeds.iter().map(|&v| insert(v, 0.04)).collect();
    for depth_tenths in [100, 200, 300, 400] {
        let depth_m = depth_tenths as f64 * 1e-4;
        let at: Vec<Sample> = runs.iter().map(|r| r.iter().find(|(d, _)| *d == depth_tenths).unwrap().1).collect();
        for (v, s) in speeds.iter().zip(&at) {
            let q = Q0 + B_V * v;
            eprintln!(
                "depth {:.0} mm, {:.0} mm/s: force {:.4} N, friction {:.4} N = {q} N/m × {:.2} mm",
                depth_m * 1e3,
                v * 1e3,
                s.force_n,
                s.friction_n,
                s.length_m * 1e3
            );
            assert!(s.all_slipping, "every shaft contact slides at {v} m/s, {depth_m} m");
            // The shares follow the contacts' positions to 1e-6 of the total per contact (the
            // active set's friction tolerance), at most a few contacts.
            assert!((s.friction_n - q * s.length_m).abs() <= 2e-5 * s.friction_n, "{v} m/s, {depth_m} m: {s:?}");
            assert!(s.length_m > depth_m - 0.005 && s.length_m <= depth_m, "{v} m/s, {depth_m} m: {s:?}");
            assert!(s.force_n >= s.friction_n - 1e-12, "the tip adds to the friction: {s:?}");
        }
        for w in at.windows(2) {
            assert!(w[1].force_n > w[0].force_n, "faster, more force at {depth_m} m: {at:?}");
        }
    }
}
