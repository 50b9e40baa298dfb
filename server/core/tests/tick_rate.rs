//! Tick-rate independence (issue 19): the quasi-static model has no time in it, so the same
//! scripted insertion stepped at 500 Hz, 1 kHz and 5 kHz must give the same force–depth curve;
//! only event timing (a puncture lands at the first tick past its threshold) may differ, by one
//! tick's advance. The rate-dependent parts (viscoelastic tissue, velocity-dependent friction)
//! depend on the rate of time, not of ticks, and are left out here (they are off in these
//! parameters; `viscous.rs` and `rate_friction.rs` test them).

use needlesim_core::fixtures::{phantom, phantom_params};
use needlesim_core::sim::{ContactModel, SimParams, Simulation};
use needlesim_core::{BasePose, FlexibleNeedle, NeedleShape, RegionNeedleParams, RigidNeedle};

const ENTRY: [f64; 2] = [0.05, 0.1];
const SPEED_M_PER_S: f64 = 0.01;
const DEPTH_END_M: f64 = 0.06;
const DOWN: f64 = -std::f64::consts::FRAC_PI_2;

/// One scripted insertion: a needle through the entry point along `theta_rad`.
#[derive(Clone, Copy)]
struct Case {
    name: &'static str,
    needle: NeedleShape,
    theta_rad: f64,
    contact: ContactModel,
}

fn base_at(depth_m: f64, theta_rad: f64, length_m: f64) -> BasePose {
    BasePose::new(ENTRY[0] + (depth_m - length_m) * theta_rad.cos(), ENTRY[1] + (depth_m - length_m) * theta_rad.sin(), theta_rad)
}

/// One tick of an insertion's record.
#[derive(Clone, Copy, Debug)]
struct Sample {
    depth_m: f64,
    /// The force on the base along the base's axis and across it (N).
    axial_n: f64,
    lateral_n: f64,
    /// Punctures (and cuts) so far.
    punctures: u64,
}

/// The insertion of `case` at 10 mm/s from 5 mm above the surface to 60 mm deep, stepped at
/// `rate_hz`; every tick's sample. Columns ahead of the tip are fetched until nothing waits (a
/// worker keeps up at any rate), so no contact waits for columns.
fn insertion(case: Case, rate_hz: f64) -> Vec<Sample> {
    let len = case.needle.tip_s_m();
    let params = SimParams {
        initial_pose: base_at(-0.005, case.theta_rad, len),
        contact: case.contact,
        columns_in_step: false,
        max_needle_nodes: 256,
        tick_rate_hz: rate_hz,
        regions: vec![RegionNeedleParams::default()],
        ..phantom_params(case.needle)
    };
    assert_eq!((params.viscoelastic, params.regions[0].friction_damping_n_s_per_m2), (None, 0.0), "the rate-independent model");
    let mut sim = Simulation::new(phantom(37), params).unwrap();
    let ticks = ((DEPTH_END_M + 0.005) / SPEED_M_PER_S * rate_hz).round() as usize;
    let mut curve = Vec::with_capacity(ticks + 1);
    for k in 0..=ticks {
        let depth_m = -0.005 + SPEED_M_PER_S * k as f64 / rate_hz;
        while sim.prefetch_columns(64).unwrap() > 0 {}
        let o = sim.step(base_at(depth_m, case.theta_rad, len)).unwrap();
        let (axial_n, lateral_n) = (o.force_axial_n, o.force_lateral_n);
        let st = sim.stats();
        assert_eq!((st.column_deferrals, st.unconverged_ticks), (0, 0), "{} at {rate_hz} Hz, tick {k}", case.name);
        curve.push(Sample { depth_m, axial_n, lateral_n, punctures: st.punctures });
    }
    curve
}

/// The last sample at or before `depth_m`.
fn at(curve: &[Sample], depth_m: f64) -> Sample {
    let i = curve.partition_point(|s| s.depth_m <= depth_m + 1e-12);
    curve[i.saturating_sub(1)]
}

/// The distance of the force at `depth_m` on `curve` from `reference` when events may land up to
/// `shift_m` of depth apart: $\min_{|\delta| \le \text{shift}} \lVert F(d) - F_{ref}(d + \delta)\rVert_\infty$
/// over the reference's samples in that window (axial and lateral components). A discrete step
/// decides a puncture at a tick, so the same event lands up to one tick's advance apart at two
/// tick rates; between events the curves must coincide.
fn shifted_distance(curve: &[Sample], reference: &[Sample], depth_m: f64, shift_m: f64) -> f64 {
    let f = at(curve, depth_m);
    let lo = reference.partition_point(|s| s.depth_m < depth_m - shift_m).saturating_sub(1);
    let hi = reference.partition_point(|s| s.depth_m <= depth_m + shift_m);
    reference[lo..hi.max(lo + 1)]
        .iter()
        .map(|r| (f.axial_n - r.axial_n).abs().max((f.lateral_n - r.lateral_n).abs()))
        .fold(f64::INFINITY, f64::min)
}

/// The depths at which punctures happened.
fn puncture_depths(curve: &[Sample]) -> Vec<f64> {
    curve.windows(2).filter(|w| w[1].punctures > w[0].punctures).map(|w| w[1].depth_m).collect()
}

/// The least-squares slope of the axial force over 20–60 mm (N/m).
fn slope(c: &[Sample]) -> f64 {
    let pts: Vec<(f64, f64)> = c.iter().filter(|s| (0.02..=0.06).contains(&s.depth_m)).map(|s| (s.depth_m, s.axial_n)).collect();
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>()
}

/// 500 Hz and 1 kHz against 5 kHz for `case`: sampled every 0.1 mm, every force is within 1 %
/// of the largest force of the 5 kHz curve, allowing each puncture to land up to one tick's
/// advance of the slower rate apart; the punctures are as many and each within one tick's
/// advance of the 5 kHz one (so the events do not drift apart along the insertion); the
/// friction slope (least squares over 20–60 mm) within 1 %. Returns the worst difference (%).
fn compare_rates(case: Case) -> f64 {
    let reference = insertion(case, 5000.0);
    let depths: Vec<f64> = (0..=600).map(|i| i as f64 * 1e-4).collect();
    let f_max = reference.iter().map(|s| s.axial_n.abs().max(s.lateral_n.abs())).fold(0.0, f64::max);
    let s_ref = slope(&reference);
    let p_ref = puncture_depths(&reference);
    assert!(
        s_ref < -5.0 && p_ref.len() > 10,
        "{}: the reference insertion hardly resists: slope {s_ref} N/m, {} punctures",
        case.name,
        p_ref.len()
    );
    let mut worst_pct: f64 = 0.0;
    for rate in [500.0, 1000.0] {
        let c = insertion(case, rate);
        let tick_m = SPEED_M_PER_S / rate;
        let (worst, depth) = depths
            .iter()
            .map(|&d| (shifted_distance(&c, &reference, d, tick_m * (1.0 + 1e-9)), d))
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        let plain = depths.iter().map(|&d| (at(&c, d).axial_n - at(&reference, d).axial_n).powi(2)).sum::<f64>()
            / depths.iter().map(|&d| at(&reference, d).axial_n.powi(2)).sum::<f64>();
        let p = puncture_depths(&c);
        let lag = p.iter().zip(&p_ref).map(|(a, b)| a - b).fold(0.0f64, |m, x| m.max(x.abs()));
        let s = slope(&c);
        println!(
            "{} {rate} Hz: largest difference {:.1e} % of the peak force (at {:.1} mm, events within one tick); plain RMS difference {:.3} %; punctures {} (5 kHz: {}), largest shift {:.1} µm (one tick: {:.0} µm); slope {s:.4} N/m against {s_ref:.4} N/m at 5 kHz",
            case.name,
            worst / f_max * 100.0,
            depth * 1e3,
            plain.sqrt() * 100.0,
            p.len(),
            p_ref.len(),
            lag * 1e6,
            tick_m * 1e6,
        );
        assert!(worst < 0.01 * f_max, "{} {rate} Hz: {worst} N from the 5 kHz curve at {depth} m (peak {f_max} N)", case.name);
        assert_eq!(p.len(), p_ref.len(), "{} {rate} Hz: punctures at {p:?}, at 5 kHz {p_ref:?}", case.name);
        assert!(lag <= tick_m * (1.0 + 1e-6), "{} {rate} Hz: a puncture {lag} m from the 5 kHz one (one tick: {tick_m} m)", case.name);
        assert!(((s - s_ref) / s_ref).abs() < 0.01, "{} {rate} Hz: slope {s} N/m against {s_ref} N/m at 5 kHz", case.name);
        worst_pct = worst_pct.max(worst / f_max * 100.0);
    }
    worst_pct
}

/// Issue 19: the same scripted vertical insertion of the rigid needle at 500 Hz, 1 kHz and
/// 5 kHz gives the same force–depth curve within 1 % (`compare_rates`). Before contacts were
/// located within the tick, 500 Hz was 7.8 % of the peak force off (events drifting apart by
/// about a tick per puncture: 0.12 mm at 56 mm).
#[test]
fn issue_19_the_force_depth_curve_does_not_depend_on_the_tick_rate() {
    let rigid = NeedleShape::Rigid(RigidNeedle { length_m: 0.1 });
    compare_rates(Case { name: "rigid, vertical", needle: rigid, theta_rad: DOWN, contact: POINTS });
}

/// Material points every 2 mm (the scenes' default).
const POINTS: ContactModel = ContactModel::MaterialPoints { spacing_m: 0.002, width_m: 0.0 };

/// Issue 19: the same for an oblique insertion (30° off the vertical: lateral force too) of the
/// rigid needle and of a flexible one.
#[test]
fn issue_19_an_oblique_insertion_does_not_depend_on_the_tick_rate() {
    let theta = DOWN + 30f64.to_radians();
    let rigid = NeedleShape::Rigid(RigidNeedle { length_m: 0.1 });
    compare_rates(Case { name: "rigid, oblique", needle: rigid, theta_rad: theta, contact: POINTS });
    let flexible = NeedleShape::Flexible(FlexibleNeedle::gauge17_steel(0.1));
    compare_rates(Case { name: "flexible, oblique", needle: flexible, theta_rad: theta, contact: POINTS });
}

/// Issue 19, still open for the paper's node capture (`contact = "nodes"`, the figure scenes'):
/// at 500 Hz the curve is 13 % of the peak force off the 5 kHz one and the punctures drift
/// apart by up to 92 µm (4.6 ticks) over 60 mm (measured 2026-11-26). Nodes are captured when
/// the tip has passed their deformed position within the capture radius at the tick's end, and
/// a tick that passes two takes only the distal one as the tip's; locating that within the
/// tick as the material points do is not done. Run with `--ignored` to see the figures.
#[test]
#[ignore = "issue 19 open: node capture still depends on the tick rate (13 % at 500 Hz)"]
fn issue_19_node_capture_does_not_depend_on_the_tick_rate() {
    let rigid = NeedleShape::Rigid(RigidNeedle { length_m: 0.1 });
    compare_rates(Case {
        name: "rigid, oblique, node capture",
        needle: rigid,
        theta_rad: DOWN + 30f64.to_radians(),
        contact: ContactModel::Nodes,
    });
}
