//! Rate-dependent friction in 3D ([`needlesim_core::needle`], issue 19: "both 2D and 3D"):
//! insertions into the cube phantom at 1, 5 and 10 mm/s give increasing force at equal depth,
//! by the amount the law $q_0 + b_v |v|$ predicts.

use needlesim_core::RegionNeedleParams;
use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
use needlesim_core::sim3::{BasePose3, PointState3, Simulation3};

/// Kinetic friction per length, N/m, and viscous friction per length and speed, N·s/m².
const Q0: f64 = 10.0;
const B_V: f64 = 1000.0;
const ENTRY: [f64; 3] = [0.05, 0.05, 0.1];

/// One tick's measures: the axial force on the base (N, positive resisting), the slipping
/// points' axial forces summed (N), the friction length $L - s_{min}$ they span (m), and whether
/// every shaft point slips.
#[derive(Debug, Clone, Copy)]
struct Sample {
    force_n: f64,
    friction_n: f64,
    length_m: f64,
    all_slipping: bool,
}

/// Inserts straight down at `speed` m/s from 5 mm above the surface into the 13³ cube and
/// samples every whole millimetre of depth, as `(depth in mm, sample)`.
fn insert(speed: f64, depth_m: f64) -> Vec<(usize, Sample)> {
    let mut params = box_phantom3_params(ENTRY, 0.005);
    params.regions = vec![RegionNeedleParams {
        friction_n_per_m: Q0,
        tip_peak_ratio: 0.0,
        friction_damping_n_s_per_m2: B_V,
        static_friction_ratio: 1.0,
        ..Default::default()
    }];
    let start = params.initial_pose;
    let len = params.needle_length_m;
    let mut sim = Simulation3::new(box_phantom3(13), params).unwrap();
    let dt = 1e-3;
    let n = ((0.005 + depth_m) / (speed * dt)).round() as usize;
    let per_mm = (1e-3 / (speed * dt)).round() as usize;
    let mut out = Vec::new();
    for k in 1..=n {
        let p = start.position_m;
        let pose = BasePose3::straight_down([p[0], p[1], p[2] - speed * dt * k as f64]);
        let o = sim.step(pose).unwrap().clone();
        sim.prefetch_columns(usize::MAX).unwrap();
        let base = o.pose.position_m;
        let t = o.pose.axis();
        let (mut friction_n, mut s_min, mut all_slipping) = (0.0, f64::INFINITY, true);
        for c in &o.contacts {
            let s = (0..3).map(|i| t[i] * (c.x_m[i] - base[i])).sum::<f64>();
            match c.state {
                PointState3::Slipping => {
                    friction_n += (0..3).map(|i| t[i] * c.force_n[i]).sum::<f64>();
                    s_min = s_min.min(s);
                }
                PointState3::Stuck => all_slipping = false,
                PointState3::Tip => {}
            }
        }
        let sample = Sample { force_n: o.axial_force_n.abs(), friction_n, length_m: (len - s_min).max(0.0), all_slipping };
        if k % per_mm == 0 && k / per_mm >= 5 {
            out.push((k / per_mm - 5, sample));
        }
    }
    out
}

/// Uniform friction ($q_0$ = 10 N/m, no tip peak, static = kinetic so every shaft point slides),
/// $b_v$ = 1000 N·s/m²: at 20 and 35 mm depth the axial force grows with the speed, and the
/// slipping points carry $(q_0 + b_v V)\,\ell$ over the friction length $\ell$ they span: 11, 15
/// and 20 N/m at 1, 5 and 10 mm/s (the hand computation of the law for a uniform case).
#[test]
fn issue_19_faster_3d_insertions_meet_more_friction_by_the_laws_amount() {
    let speeds = [0.001, 0.005, 0.01];
    let runs: Vec<Vec<(usize, Sample)>> = speeds.iter().map(|&v| insert(v, 0.035)).collect();
    for depth_mm in [20, 35] {
        let at: Vec<Sample> = runs.iter().map(|r| r.iter().find(|(d, _)| *d == depth_mm).unwrap().1).collect();
        for (v, s) in speeds.iter().zip(&at) {
            let q = Q0 + B_V * v;
            eprintln!(
                "depth {depth_mm} mm, {:.0} mm/s: force {:.4} N, friction {:.4} N = {q} N/m × {:.2} mm",
                v * 1e3,
                s.force_n,
                s.friction_n,
                s.length_m * 1e3
            );
            assert!(s.all_slipping, "every shaft point slides at {v} m/s, {depth_mm} mm: {s:?}");
            // By hand: the points span the inserted length less at most the spacing rule's gap
            // at the entry (the first point within the first tetrahedron, 8.3 mm cells).
            let depth_m = depth_mm as f64 * 1e-3;
            assert!(s.length_m > depth_m - 0.0084 && s.length_m <= depth_m + 1e-9, "{v} m/s, {depth_mm} mm: {s:?}");
            assert!((s.friction_n - q * s.length_m).abs() <= 2e-5 * s.friction_n, "{v} m/s, {depth_mm} mm: {s:?}");
            assert!(s.force_n >= s.friction_n - 1e-9, "the tip adds to the friction: {s:?}");
        }
        for w in at.windows(2) {
            assert!(w[1].force_n > w[0].force_n, "faster, more force at {depth_mm} mm: {at:?}");
        }
    }
}
