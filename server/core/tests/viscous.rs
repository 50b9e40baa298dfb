//! Viscoelastic tissue (`needlesim_core::viscous`, 2D and 3D): a step held still relaxes as the
//! closed-form standard linear solid, an insertion held still relaxes with the scene's time
//! constant, and an elastic tissue is untouched.

use needlesim_core::fixtures::{box_phantom3, box_phantom3_params, phantom, phantom_params};
use needlesim_core::sim::{ContactModel, SimParams, Simulation, Viscoelastic};
use needlesim_core::sim3::{BasePose3, NearField3, Sim3Params, Simulation3};
use needlesim_core::{BasePose, NeedleShape, RegionNeedleParams, RigidNeedle};

const DOWN: f64 = -std::f64::consts::FRAC_PI_2;

fn params(viscoelastic: Option<Viscoelastic>, puncture_force_n: f64) -> SimParams {
    SimParams {
        contact: ContactModel::default_points(),
        max_base_step_m: 0.01,
        regions: vec![RegionNeedleParams { puncture_force_n, cutting_force_n: 0.05, ..Default::default() }],
        viscoelastic,
        ..phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))
    }
}

/// The base force of each tick along `base_y` (a vertical needle above the top centre).
fn forces(model: &std::sync::Arc<needlesim_core::TissueModel>, p: SimParams, base_y: &[f64]) -> Vec<[f64; 2]> {
    let mut sim = Simulation::new(model.clone(), p).unwrap();
    base_y
        .iter()
        .map(|&y| {
            let f = sim.step(BasePose::new(0.05, y, DOWN)).unwrap().force_n;
            sim.prefetch_columns(16).unwrap();
            f
        })
        .collect()
}

/// The standard linear solid's force at every tick for the elastic force history `f_el`
/// (linear in time between ticks, zero before the first): the convolution
/// $F(t_n) = \sum_j \frac{F_j - F_{j-1}}{\Delta t}\int_{t_{j-1}}^{t_j} g(t_n - s)\,ds$ summed directly,
/// each integral in closed form.
fn sls_closed_form<const D: usize>(v: &Viscoelastic, dt: f64, f_el: &[[f64; D]]) -> Vec<[f64; D]> {
    let (g, tau) = (v.long_term_ratio, v.relaxation_time_s);
    (0..f_el.len())
        .map(|n| {
            let mut out = [0.0; D];
            for j in 0..=n {
                let prev = if j == 0 { [0.0; D] } else { f_el[j - 1] };
                let (age0, age1) = ((n - j + 1) as f64 * dt, (n - j) as f64 * dt);
                let int = g * dt + (1.0 - g) * tau * ((-age1 / tau).exp() - (-age0 / tau).exp());
                for k in 0..D {
                    out[k] += (f_el[j][k] - prev[k]) / dt * int;
                }
            }
            out
        })
        .collect()
}

/// A block pressed by the needle's tip (the contact never punctures), stepped 2 mm in one tick
/// and held for 5 τ: the force follows the closed-form SLS of the same displacement history to
/// 1e-6 of its peak, and ends at the long-term fraction of the elastic force.
#[test]
fn a_step_held_still_relaxes_as_the_closed_form_standard_linear_solid() {
    let model = phantom(19);
    let v = Viscoelastic { long_term_ratio: 0.4, relaxation_time_s: 0.2 };
    let mut base_y: Vec<f64> = (1..=530).map(|k| 0.205 - 1e-5 * k as f64).collect();
    let y_step = base_y[base_y.len() - 1] - 0.002;
    base_y.extend(std::iter::repeat_n(y_step, 1000));
    let elastic = forces(&model, params(None, 1e3), &base_y);
    let visco = forces(&model, params(Some(v), 1e3), &base_y);
    let closed = sls_closed_form(&v, 1e-3, &elastic);
    let peak = visco.iter().map(|f| f[0].hypot(f[1])).fold(0.0, f64::max);
    assert!(peak > 0.05, "the step loads the tissue: peak {peak} N");
    let worst = visco.iter().zip(&closed).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
    assert!(worst <= 1e-6 * peak, "largest deviation from the closed form {worst:e} N of peak {peak} N");
    // Relaxed towards g∞ times the elastic force: 5 τ after the step the rest of the way is at
    // most (1 − g∞) e^{-5} times the one-tick ramp's factor (τ/Δt)(e^{Δt/τ} − 1) (the slow
    // approach before it relaxed for longer).
    let (fe, fv) = (elastic.last().unwrap()[1], visco.last().unwrap()[1]);
    let ramp = v.relaxation_time_s / 1e-3 * ((1e-3 / v.relaxation_time_s).exp() - 1.0);
    let rest = fv / fe - v.long_term_ratio;
    assert!(rest > 0.0 && rest <= (1.0 - v.long_term_ratio) * (-5.0f64).exp() * ramp, "end force {fv} N, elastic {fe} N");
    eprintln!("step relaxation: peak {peak:.4} N, worst deviation {worst:.2e} N, end {fv:.5} N (elastic {fe:.5} N)");
}

/// An insertion 35 mm deep at 10 mm/s (punctures, cuts, friction), then held still for 10 τ: the
/// axial force falls monotonically, three equally spaced samples of the hold give the scene's
/// time constant, and the force settles on the value the fit extrapolates to.
#[test]
fn an_insertion_held_still_relaxes_with_the_scenes_time_constant() {
    let model = phantom(19);
    let v = Viscoelastic { long_term_ratio: 0.5, relaxation_time_s: 0.3 };
    let mut base_y: Vec<f64> = (1..=3500).map(|k| 0.205 - 1e-5 * k as f64).collect();
    let hold_from = base_y.len();
    base_y.extend(std::iter::repeat_n(base_y[hold_from - 1], 3000));
    // Static friction well above kinetic: once the needle stops, every contact sticks and stays
    // stuck while the forces redistribute (with the default 1.3 some contacts' forces grow past
    // it as their neighbours relax and they slip, which is friction, not the tissue's law).
    let mut p = params(Some(v), 0.3);
    p.regions[0].static_friction_ratio = 3.0;
    let mut sim = Simulation::new(model, p).unwrap();
    let mut fy = Vec::new();
    for &y in &base_y {
        let out = sim.step(BasePose::new(0.05, y, DOWN)).unwrap();
        fy.push(out.force_n[1]);
        sim.prefetch_columns(16).unwrap();
    }
    let s = sim.stats();
    assert!(s.punctures >= 3 && s.captures >= 3, "a real insertion: {s:?}");
    let hold = &fy[hold_from..];
    assert!(hold[0] > 0.1, "the needle pushes into the tissue: {} N", hold[0]);
    for (k, w) in hold.windows(2).enumerate() {
        assert!(w[1] <= w[0] + 1e-12, "the force grows at hold tick {k}: {} → {} N", w[0], w[1]);
    }
    // F(t) = F∞ + A e^{-t/τ}: from three samples Δ apart, τ = Δ / ln((F₁ − F₀)/(F₂ − F₁)).
    let (k0, dk) = (100, 400);
    let (f0, f1, f2) = (hold[k0], hold[k0 + dk], hold[k0 + 2 * dk]);
    let tau_fit = dk as f64 * 1e-3 / ((f1 - f0) / (f2 - f1)).ln();
    let f_inf = f0 - (f1 - f0).powi(2) / (f2 - 2.0 * f1 + f0);
    let drop = hold[0] - f_inf;
    assert!(drop > 0.1 * hold[0], "the force relaxes noticeably: from {} N towards {f_inf} N", hold[0]);
    assert!((tau_fit - v.relaxation_time_s).abs() <= 1e-6 * v.relaxation_time_s, "fitted τ {tau_fit} s");
    let end = *hold.last().unwrap();
    let expected_end = f_inf + (f0 - f_inf) * (-((hold.len() - 1 - k0) as f64) * 1e-3 / v.relaxation_time_s).exp();
    assert!((end - expected_end).abs() <= 1e-9 * hold[0], "end force {end} N, the fit says {expected_end} N");
    eprintln!("held insertion: {:.4} N at the hold → {end:.4} N after 10 τ; fitted τ {tau_fit:.9} s, F∞ {f_inf:.4} N", hold[0]);
}

/// An elastic tissue is untouched by the viscous machinery: `viscoelastic = None` and a long-term
/// ratio of 1 give the same forces bit for bit along an insertion and a hold.
#[test]
fn a_long_term_ratio_of_one_is_elastic_bit_for_bit() {
    let model = phantom(19);
    let base_y: Vec<f64> = (1..=2500).map(|k| 0.205 - 1e-5 * k.min(2000) as f64).collect();
    let a = forces(&model, params(None, 0.3), &base_y);
    let b = forces(&model, params(Some(Viscoelastic { long_term_ratio: 1.0, relaxation_time_s: 0.1 }), 0.3), &base_y);
    assert_eq!(a, b);
    let c = forces(&model, params(Some(Viscoelastic { long_term_ratio: 0.9, relaxation_time_s: 0.1 }), 0.3), &base_y);
    assert_ne!(a, c);
}

/// The 3D simulation's base force along `tip_z_m` (the tip's height over the cube phantom's top
/// entry point, a needle pointing straight down), columns prefetched between steps.
fn forces3(model: &std::sync::Arc<needlesim_core::d3::TetTissueModel>, p: &Sim3Params, tip_z_m: &[f64]) -> Vec<[f64; 3]> {
    let mut sim = Simulation3::new(model.clone(), p.clone()).unwrap();
    let len = p.needle_length_m;
    tip_z_m
        .iter()
        .map(|&z| {
            let pose = BasePose3::straight_down([ENTRY3[0], ENTRY3[1], z + len]);
            let f = sim.step(pose).unwrap().base_force_n;
            sim.prefetch_columns(usize::MAX).unwrap();
            f
        })
        .collect()
}

/// Off-node entry point on the 3D phantom's top face (z = 0.1 m).
const ENTRY3: [f64; 3] = [0.0513, 0.0487, 0.1];

fn params3(viscoelastic: Option<Viscoelastic>, near_field: Option<NearField3>) -> Sim3Params {
    let mut p = box_phantom3_params(ENTRY3, 0.005);
    p.max_base_step_m = 0.01;
    // The tip's point never punctures: one contact, carried by the tip throughout.
    p.regions[0].puncture_force_n = 1e3;
    p.viscoelastic = viscoelastic;
    p.near_field = near_field;
    p
}

/// 3D (one code with 2D's, `needlesim_core::viscous`): the tip pressed 0.3 mm into the cube
/// phantom's top face, stepped 2 mm deeper in one tick and held for 5 τ: the base force follows
/// the closed-form SLS of the elastic force history to 1e-6 of its peak in every component, with
/// the needle's near field (its series compliance relaxes with the tissue) and without, and
/// ends at the long-term fraction of the elastic force.
#[test]
fn a_3d_step_held_still_relaxes_as_the_closed_form_standard_linear_solid() {
    let model = box_phantom3(9);
    let v = Viscoelastic { long_term_ratio: 0.4, relaxation_time_s: 0.2 };
    let mut tip_z: Vec<f64> = (1..=530).map(|k| 0.105 - 1e-5 * k as f64).collect();
    let z_step = tip_z[tip_z.len() - 1] - 0.002;
    tip_z.extend(std::iter::repeat_n(z_step, 1000));
    for nf in [None, Some(NearField3::new(0.5e-3))] {
        let elastic = forces3(&model, &params3(None, nf), &tip_z);
        let visco = forces3(&model, &params3(Some(v), nf), &tip_z);
        let closed = sls_closed_form(&v, 1e-3, &elastic);
        let norm = |f: &[f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let peak = visco.iter().map(norm).fold(0.0, f64::max);
        assert!(peak > 0.05, "the step loads the tissue: peak {peak} N");
        let worst = visco.iter().zip(&closed).map(|(a, b)| norm(&[a[0] - b[0], a[1] - b[1], a[2] - b[2]])).fold(0.0, f64::max);
        assert!(worst <= 1e-6 * peak, "near field {nf:?}: largest deviation from the closed form {worst:e} N of peak {peak} N");
        let (fe, fv) = (elastic.last().unwrap()[2], visco.last().unwrap()[2]);
        let ramp = v.relaxation_time_s / 1e-3 * ((1e-3 / v.relaxation_time_s).exp() - 1.0);
        let rest = fv / fe - v.long_term_ratio;
        assert!(rest > 0.0 && rest <= (1.0 - v.long_term_ratio) * (-5.0f64).exp() * ramp, "end force {fv} N, elastic {fe} N");
        eprintln!(
            "3D step relaxation (near field {}): peak {peak:.4} N, worst deviation {worst:.2e} N, end {fv:.5} N (elastic {fe:.5} N)",
            nf.is_some()
        );
    }
}

/// 3D: an insertion 30 mm deep (puncture, cutting, friction, several points), then held for 5 τ:
/// the axial force falls monotonically, with the tissue's time constant, below the elastic
/// force; `viscoelastic = None` and a long-term ratio of 1 give the same forces bit for bit, a
/// ratio of 0.5 does not.
#[test]
fn a_3d_insertion_relaxes_and_a_long_term_ratio_of_one_is_elastic_bit_for_bit() {
    let model = box_phantom3(9);
    let tip_z: Vec<f64> = (1..=3500).map(|k| 0.105 - 1e-5 * k.min(3000) as f64).collect();
    let base = |v| {
        let mut p = box_phantom3_params(ENTRY3, 0.005);
        p.regions[0].static_friction_ratio = 3.0;
        p.viscoelastic = v;
        p
    };
    let a = forces3(&model, &base(None), &tip_z);
    let b = forces3(&model, &base(Some(Viscoelastic { long_term_ratio: 1.0, relaxation_time_s: 0.1 })), &tip_z);
    assert_eq!(a, b);
    let c = forces3(&model, &base(Some(Viscoelastic { long_term_ratio: 0.5, relaxation_time_s: 0.1 })), &tip_z);
    assert_ne!(a, c);
    let hold = &c[3000..];
    assert!(hold[0][2] > 0.1, "the needle pushes into the tissue: {:?} N", hold[0]);
    for (k, w) in hold.windows(2).enumerate() {
        assert!(w[1][2] <= w[0][2] + 1e-12, "the force grows at hold tick {k}: {} → {} N", w[0][2], w[1][2]);
    }
    // Relaxing with τ = 100 ticks: the fall over the hold's last τ (of 5) is a few percent of
    // its first τ's (e^{-4} ≈ 2 % for one exponential), and ends below the elastic force.
    let (e_end, c_end) = (a.last().unwrap()[2], c.last().unwrap()[2]);
    let (first, last) = (hold[0][2] - hold[100][2], hold[hold.len() - 101][2] - c_end);
    assert!(first > 0.0 && last < 0.05 * first, "the fall over the first τ {first:e} N, over the last {last:e} N");
    assert!(c_end < e_end && c_end > 0.0, "relaxed: {} → {c_end} N (elastic {e_end} N)", hold[0][2]);
    eprintln!("3D held insertion: {:.4} N at the hold → {c_end:.4} N after 5 τ (elastic {e_end:.4} N)", hold[0][2]);
}
