//! The flexible needle (issue 8): a stiff flexible needle reproduces the rigid one, a lateral base
//! step steers the tip with the paper's non-minimum-phase response (Fig. 4), a bevel tip curves
//! the path towards its bevel side and a 180° flip reverses the curvature, and the needle nodes
//! lie on the bent shape.

use needlesim_core::fixtures::{phantom, phantom_params as params};
use needlesim_core::sim::{Simulation, StepOutput};
use needlesim_core::{BasePose, FlexibleNeedle, NeedleShape, RigidNeedle};

const FRAC_PI_2: f64 = std::f64::consts::FRAC_PI_2;

fn flexible(ei_scale: f64, bevel: f64) -> NeedleShape {
    let mut f = FlexibleNeedle::gauge17_steel(0.1);
    f.flexural_rigidity_nm2 *= ei_scale;
    f.bevel_force_ratio = bevel;
    NeedleShape::Flexible(f)
}

fn run(sim: &mut Simulation, poses: &[BasePose]) -> Vec<StepOutput> {
    poses
        .iter()
        .map(|p| {
            let o = sim.step(*p).unwrap().clone();
            sim.prefetch_columns(16).unwrap();
            o
        })
        .collect()
}

/// Straight down from y0 to y1 at x, 1 mm per 100 ticks (10 mm/s).
fn down(x: f64, y0: f64, y1: f64) -> Vec<BasePose> {
    let n = ((y0 - y1) / 1e-5).round() as usize;
    (1..=n).map(|k| BasePose::new(x, y0 + (y1 - y0) * k as f64 / n as f64, -FRAC_PI_2)).collect()
}

/// Insertion 45 mm at 10 mm/s, a lateral base move and a rotation, then withdrawal: a path
/// that exercises capture, puncture, stick–slip, frame rotation and release.
fn mixed_path() -> Vec<BasePose> {
    let mut poses = down(0.05, 0.205, 0.16);
    for k in 1..=400 {
        let a = k as f64 / 400.0;
        poses.push(BasePose::new(0.05 + 0.003 * a, 0.16, -FRAC_PI_2 + 0.03 * a));
    }
    poses.extend((1..=500).map(|k| BasePose::new(0.053, 0.16 + 0.02 * k as f64 / 500.0, -FRAC_PI_2 + 0.03)));
    poses
}

#[test]
fn stiff_flexible_needle_matches_the_rigid_needle() {
    let model = phantom(19);
    let poses = mixed_path();
    let mut rigid = Simulation::new(model.clone(), params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))).unwrap();
    let mut stiff = Simulation::new(model, params(flexible(1e6, 0.0))).unwrap();
    let (a, b) = (run(&mut rigid, &poses), run(&mut stiff, &poses));
    let f_scale = a.iter().map(|o| o.force_n[0].hypot(o.force_n[1])).fold(0.0, f64::max);
    let t_scale = a.iter().map(|o| o.torque_nm.abs()).fold(0.0, f64::max);
    assert!(f_scale > 0.3 && t_scale > 1e-3, "the path loads the needle: {f_scale} N, {t_scale} N·m");
    // Differences over the whole path: the force relative to the largest force; the torque, a sum
    // of moments of the contact forces, relative to the largest sum of their magnitudes times
    // the needle's length L = 0.1 m; positions relative to L.
    let m_scale = a.iter().map(|o| o.needle_nodes.iter().map(|n| n.force_n[0].hypot(n.force_n[1])).sum::<f64>() * 0.1).fold(0.0, f64::max);
    let diff = |b: &[StepOutput]| {
        let (mut df, mut dtau, mut dpos): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for (ra, rb) in a.iter().zip(b) {
            assert_eq!(ra.needle_nodes.len(), rb.needle_nodes.len(), "tick {}", ra.tick);
            df = df.max((ra.force_n[0] - rb.force_n[0]).hypot(ra.force_n[1] - rb.force_n[1]));
            dtau = dtau.max((ra.torque_nm - rb.torque_nm).abs());
            dpos = dpos.max((ra.tip_m[0] - rb.tip_m[0]).hypot(ra.tip_m[1] - rb.tip_m[1]));
            for (na, nb) in ra.needle_nodes.iter().zip(&rb.needle_nodes) {
                assert_eq!((na.node_idx, na.state), (nb.node_idx, nb.state), "tick {}", ra.tick);
                dpos = dpos.max((na.position_m[0] - nb.position_m[0]).hypot(na.position_m[1] - nb.position_m[1]));
            }
        }
        (df / f_scale, dtau, dpos / 0.1)
    };
    let (df, dtau, dpos) = diff(&b);
    println!(
        "EI x 1e6 vs rigid: force {df:.2e}, torque {:.2e} of Σ|f|·L ({:.2e} of its own largest value), positions {dpos:.2e}",
        dtau / m_scale,
        dtau / t_scale
    );
    assert!(df <= 1e-6, "the force differs by {df:.3e} of the largest force");
    assert!(dtau <= 1e-6 * m_scale, "the torque differs by {:.3e} of Σ|f|·L", dtau / m_scale);
    assert!(dpos <= 1e-6, "tip and node positions differ by {dpos:.3e} of the needle length");
    // The difference is the needle's compliance, not a numerical floor: ten times stiffer, ten
    // times closer.
    let mut stiffer = Simulation::new(phantom(19), params(flexible(1e7, 0.0))).unwrap();
    let (df7, dtau7, dpos7) = diff(&run(&mut stiffer, &poses));
    println!("EI x 1e7 vs rigid: force {df7:.2e}, torque {:.2e}, positions {dpos7:.2e}", dtau7 / m_scale);
    assert!(df7 < 0.2 * df && dtau7 < 0.2 * dtau && dpos7 < 0.2 * dpos, "{df7:.3e} vs {df:.3e}, {dpos7:.3e} vs {dpos:.3e}");
    // The real needle does bend on this path.
    let mut bendy = Simulation::new(phantom(19), params(flexible(1.0, 0.0))).unwrap();
    let c = run(&mut bendy, &poses);
    let dtip_real = a.iter().zip(&c).map(|(ra, rc)| (ra.tip_m[0] - rc.tip_m[0]).hypot(ra.tip_m[1] - rc.tip_m[1])).fold(0.0, f64::max);
    assert!(dtip_real > 1e-4, "a 17-gauge needle bends by {dtip_real:.3e} m");
}

/// Needle nodes lie on the bent needle and the shape is in equilibrium with their forces.
#[test]
fn needle_nodes_lie_on_the_bent_shape() {
    let mut sim = Simulation::new(phantom(19), params(flexible(0.3, 0.0))).unwrap();
    let poses = mixed_path();
    let mut worst: f64 = 0.0;
    let mut bent: f64 = 0.0;
    for (k, p) in poses.iter().enumerate() {
        let o = sim.step(*p).unwrap().clone();
        sim.prefetch_columns(16).unwrap();
        if k % 50 != 0 {
            continue;
        }
        let curve = sim.needle_curve().unwrap();
        for n in &o.needle_nodes {
            let c = curve.point_at(n.s_m);
            let a = curve.tangent_angle_at(n.s_m);
            let d = [n.position_m[0] - c[0], n.position_m[1] - c[1]];
            let lateral = -a.sin() * d[0] + a.cos() * d[1];
            if n.state != needlesim_core::NodeState::Tip {
                worst = worst.max(lateral.abs());
            }
        }
        let straight = needlesim_core::NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }).tip_m(&o.base);
        bent = bent.max((o.tip_m[0] - straight[0]).hypot(o.tip_m[1] - straight[1]));
    }
    println!("largest lateral gap node–needle {worst:.3e} m; largest tip deflection {bent:.3e} m");
    assert!(bent > 5e-4, "the needle bends ({bent:.3e} m)");
    assert!(worst < 1e-3 * bent, "nodes leave the needle by {worst:.3e} m (deflection {bent:.3e} m)");
    assert_eq!(sim.stats().shape_unconverged, 0);
}

/// Inserts straight down 60 mm with a bevel tip; returns the tip's lateral offset (x) per tick.
fn bevel_run(side: f64, flip_at_tick: Option<usize>) -> Vec<f64> {
    let mut shape = flexible(0.3, 0.5);
    if let NeedleShape::Flexible(f) = &mut shape {
        f.bevel_side = side;
    }
    // A curved path passes between node columns: the capture radius must cover half the node
    // spacing (31 × 31 nodes: 3.3 mm) so that the tip keeps cutting nodes.
    let mut p = params(shape);
    p.regions[0].cutting_force_n = 0.2;
    p.capture_radius_m = 0.0018;
    let mut sim = Simulation::new(phantom(31), p).unwrap();
    let poses = down(0.05, 0.205, 0.145);
    let mut xs = Vec::new();
    for (k, p) in poses.iter().enumerate() {
        if Some(k) == flip_at_tick {
            sim.flip_bevel();
        }
        let o = sim.step(*p).unwrap();
        xs.push(o.tip_m[0] - 0.05);
        sim.prefetch_columns(16).unwrap();
    }
    xs
}

#[test]
fn bevel_tip_curves_towards_its_side_and_a_flip_reverses_it() {
    // The base frame's +n for a needle pointing down (θ = -π/2) is +x.
    let plus = bevel_run(1.0, None);
    let minus = bevel_run(-1.0, None);
    let (p_end, m_end) = (*plus.last().unwrap(), *minus.last().unwrap());
    println!("tip offset after 55 mm: bevel +n {:.3} mm, bevel -n {:.3} mm", p_end * 1e3, m_end * 1e3);
    assert!(p_end > 1e-3 && m_end < -1e-3, "{p_end:.3e} {m_end:.3e}");
    assert!((p_end + m_end).abs() < 1e-3 * p_end.abs(), "mirror images: {p_end:.6e} vs {m_end:.6e}");
    // Not just a skid at the entry: the tip keeps moving towards the bevel side as it advances
    // (least-squares lateral speed, metres per metre inserted, over 40–100 % of the insertion).
    let n = plus.len();
    let slope = |x: &[f64], a: usize, b: usize| {
        let m = (b - a) as f64;
        let (mx, my) = ((a + b - 1) as f64 / 2.0, x[a..b].iter().sum::<f64>() / m);
        let sxy: f64 = (a..b).map(|k| (k as f64 - mx) * (x[k] - my)).sum();
        let sxx: f64 = (a..b).map(|k| (k as f64 - mx).powi(2)).sum();
        sxy / sxx / 1e-5
    };
    let (k40, k100) = (2 * n / 5, n);
    assert!(slope(&plus, k40, k100) > 0.02, "heading {:.4}", slope(&plus, k40, k100));
    // A 180° flip at 40 % of the depth reverses the turn: the tip then moves back, while without
    // the flip it keeps going the same way.
    let flipped = bevel_run(1.0, Some(k40));
    let before = slope(&plus, n / 5, k40);
    let (after_plain, after_flipped) = (slope(&plus, k40 + n / 10, k100), slope(&flipped, k40 + n / 10, k100));
    println!("lateral speed (m/m): before the flip {before:.4}; after it {after_flipped:.4} (unflipped {after_plain:.4})");
    assert!(before > 0.0 && after_plain > 0.0 && after_flipped < 0.0, "{before:.4} {after_plain:.4} {after_flipped:.4}");
    assert!(flipped[n - 1] < flipped[k40], "the flipped needle turns back");
}

/// The paper's Fig. 4: a 22-gauge needle (EI ≈ 0.07 × the 17-gauge one) inserted 35 mm, its base
/// stepped 5 mm sideways (angle held), then inserted 50 mm more. Returns the tip's offset from the
/// original axis at the end of the first insertion, after the step and at the end.
fn fig4_run() -> (f64, f64, f64, Vec<f64>) {
    let (outs, n_insert) = fig4_outputs(phantom(19));
    let xs: Vec<f64> = outs.iter().map(|o| o.tip_m[0] - 0.05).collect();
    (xs[n_insert - 1], xs[n_insert + 49], xs[xs.len() - 1], xs[n_insert + 50..].to_vec())
}

/// Fig. 4's path in `model`: every tick's output, and the number of ticks of the first
/// insertion (the step's 50 ticks follow).
fn fig4_outputs(model: std::sync::Arc<needlesim_core::TissueModel>) -> (Vec<StepOutput>, usize) {
    let mut sim = Simulation::new(model, params(flexible(0.0687, 0.0))).unwrap();
    let mut poses = down(0.05, 0.205, 0.165);
    let n_insert = poses.len();
    poses.extend((1..=50).map(|k| BasePose::new(0.05 + 0.005 * k as f64 / 50.0, 0.165, -FRAC_PI_2)));
    poses.extend(down(0.055, 0.165, 0.115));
    let outs = run(&mut sim, &poses);
    assert_eq!(sim.stats().shape_unconverged, 0);
    (outs, n_insert)
}

/// The needle's heading where it enters the tissue: the lateral slope $dx/|dy|$ of the shape's
/// segment that crosses the top surface ($y$ = 0.1 m) going down (negative: turned towards
/// $-x$). NaN when no segment crosses it.
fn entry_heading(o: &StepOutput) -> f64 {
    o.shape_m
        .windows(2)
        .find(|w| (w[0][1] - 0.1) * (w[1][1] - 0.1) <= 0.0 && w[0][1] != w[1][1])
        .map_or(f64::NAN, |w| (w[1][0] - w[0][0]) / (w[0][1] - w[1][1]).abs())
}

/// Issue 19, item 6: what Fig. 4's steering claim is everywhere, not only in the paper's
/// free-sided block. The base steps +5 mm (away from a target on the $-x$ side): the needle's
/// heading where it enters the tissue turns towards the target at once (every tick of the step),
/// and after 50 mm more the tip has crossed the original axis to the target's side. Asserted
/// in the paper's phantom (free sides) and in the same block with its sides fixed too (boxed,
/// stiffer laterally). Whether the tip first moves with the base depends on the tissue: it does
/// in the free-sided block (the non-minimum-phase response of the test above); in the boxed
/// one it does not (printed, not asserted). Measured: entry heading −1.0e-3 / −1.3e-3 after the
/// step's first tick, −5.1e-2 / −6.6e-2 after it; tip +0.95 / −0.33 mm after the step and
/// −0.96 / −3.90 mm at the end (free / boxed).
#[test]
fn issue_19_fig4_the_entry_heading_turns_towards_the_target_at_once_free_or_boxed() {
    let (mesh, mats, mut fixed) = needlesim_core::fixtures::phantom_parts(19);
    for side in ["left", "right"] {
        fixed.extend_from_slice(mesh.boundary_set(side).unwrap());
    }
    fixed.sort_unstable();
    fixed.dedup();
    let boxed = std::sync::Arc::new(needlesim_core::TissueModel::new(mesh, mats, &fixed).unwrap());
    for (label, model) in [("free sides", phantom(19)), ("boxed", boxed)] {
        let (outs, n) = fig4_outputs(model);
        let before = entry_heading(&outs[n - 1]);
        let during: Vec<f64> = outs[n..n + 50].iter().map(entry_heading).collect();
        let (x_step, x_end) = (outs[n + 49].tip_m[0] - 0.05, outs[outs.len() - 1].tip_m[0] - 0.05);
        println!(
            "{label}: entry heading before the step {before:.2e}, after its first tick {:.2e}, after it {:.2e}; tip after the step {:.3} mm, at the end {:.3} mm",
            during[0],
            during[49],
            x_step * 1e3,
            x_end * 1e3
        );
        assert!(before.abs() < 1e-9, "{label}: a straight insertion enters straight: {before:e}");
        assert!(
            during.iter().all(|h| *h < 0.0),
            "{label}: the entry heading turns towards the target at every tick of the step: {during:?}"
        );
        assert!(during[49] < during[0], "{label}: and keeps turning while the base moves");
        assert!(x_end < -2e-4, "{label}: the tip ends across the axis, on the target's side: {x_end:e}");
    }
}

/// Fig. 4's non-minimum-phase response in the paper's free-sided block. The base moves +5 mm,
/// away from a target on the −x side: the tip first moves the wrong way (with the base, +x),
/// then, as the insertion goes on, the bent needle steers it the other way, across the original
/// axis towards the target. In a boxed block the tip turns towards the target at once: what
/// holds everywhere is asserted by the next test.
/// (The issue's "Done when" words this as "first opposite to the base, then follows"; the
/// simulated response, like the paper's description of Fig. 4, has the order the other way
/// round: see the session note.)
#[test]
fn issue_8_fig4_lateral_base_step_gives_a_non_minimum_phase_tip_response() {
    let (x0, x_step, x_end, after) = fig4_run();
    println!("tip offset: before the step {:.3} mm, after it {:.3} mm, after 50 mm more {:.3} mm", x0 * 1e3, x_step * 1e3, x_end * 1e3);
    assert!(x0.abs() < 1e-9, "a straight insertion stays on the axis: {x0:.3e}");
    assert!(x_step > 2e-4, "the tip first moves with the base: {x_step:.3e}");
    assert!(x_end < -2e-4, "then the needle steers it across the axis, opposite to the base: {x_end:.3e}");
    // The turn is gradual, not a snap: no tick moves the tip by more than a tenth of the turn.
    let jump = after.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
    println!("largest single-tick tip move after the step: {:.4} mm", jump * 1e3);
    assert!(jump < 0.1 * (x_step - x_end), "a jump of {jump:.3e} m in a turn of {:.3e} m", x_step - x_end);
}
