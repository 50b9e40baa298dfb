//! The mesh-refinement study of issue 19 (`needlesim_lab::refine`): a cheap check of the
//! energy-based cutting mechanism on two small meshes, and the whole study with its convergence
//! criterion.

use std::path::Path;

use needlesim_core::mesh::MeshLimits;
use needlesim_lab::refine::{self, Figure, Model, RIGID_DIAMETER_M, TOUGHNESS_J_PER_M2};
use needlesim_scene::{EXAMPLES, Trajectory, parse_scene};

fn measure_text(text: &str, figure: Figure) -> refine::Measured {
    let scene = parse_scene(text, Path::new("."), &MeshLimits::default()).unwrap();
    let csv = EXAMPLES.iter().find(|e| e.0 == figure.scene_name()).unwrap().2;
    refine::measure(&scene, &Trajectory::parse_csv(csv).unwrap()).unwrap()
}

/// Energy-based cutting on the paper phantom, 19² and 37² nodes: no contact is carried by the
/// tip once the surface is punctured; the mean cutting force is the toughness's $G_c w$ on both
/// meshes (the difference to $G_c = 0$ on the same mesh is $G_c w$ within 10 %: the force rides
/// on the most distal contact, which slides most of the time with $F_c$ on top of its friction
/// share but sticks part of it, when its force is its elastic reaction below the static
/// threshold; measured 93 % on 19²), and it changes by less than 5 % between them.
#[test]
fn toughness_cutting_force_is_g_c_w_on_two_meshes() {
    let fc_n = TOUGHNESS_J_PER_M2 * RIGID_DIAMETER_M;
    let mut means = Vec::new();
    for n in [19, 37] {
        let text = refine::variant_toml(Figure::Phantom, n, n, Model::Toughness).unwrap();
        let tough = measure_text(&text, Figure::Phantom);
        let zero = measure_text(
            &text.replace(&format!("fracture_toughness_j_per_m2 = {TOUGHNESS_J_PER_M2}"), "fracture_toughness_j_per_m2 = 0"),
            Figure::Phantom,
        );
        assert_eq!(tough.carried_tip_n, 0.0, "{n}²: a contact was carried by the tip after the puncture");
        assert_eq!(tough.punctures, 1, "{n}²: only the surface is punctured");
        let delta = tough.mean_cutting_n - zero.mean_cutting_n;
        eprintln!("{n}²: mean cutting force {} N, {} N with G_c = 0; G_c w = {fc_n} N", tough.mean_cutting_n, zero.mean_cutting_n);
        assert!((delta - fc_n).abs() <= 0.10 * fc_n, "{n}²: the cutting force adds {delta} N, G_c w = {fc_n} N");
        means.push(tough.mean_cutting_n);
    }
    assert!(refine::rel_change(means[0], means[1]) < 0.05, "mean cutting force {means:?}");
}

/// Issue 19, the whole study (docs/guide/physics.md, "Mesh refinement"): the three figure scenes on four grids
/// each ($h \dots h/8$) with energy-based cutting and each contact spread over the needle's
/// width ([`Model::Width`]); between the two finest meshes the phantom's peak puncture force and
/// mean cutting force and the Fig. 3 and Fig. 4 closest approaches change by less than 5 %
/// (measured 0.0 %, 0.6 %, 2.0 %, 4.5 %). With point contacts (`Model::Toughness`) the Fig. 4
/// figure changed 5.3 % and then 23 % on the next grid (docs/guide/physics.md).
#[test]
fn issue_19_refinement_study_converges_with_contacts_spread_over_the_width() {
    let mut failures = Vec::new();
    for figure in [Figure::Phantom, Figure::Fig3, Figure::Fig4] {
        let st = refine::study(figure, &[Model::Width], 4, |line| eprintln!("{line}")).unwrap();
        eprint!("{}", refine::to_markdown(std::slice::from_ref(&st)));
        let (a, b) = st.finest_pair(Model::Width).unwrap();
        assert_eq!((a.patch_fallbacks, b.patch_fallbacks), (0, 0), "every contact was a patch");
        let mut check = |what: &str, x: f64, y: f64| {
            let c = refine::rel_change(x, y);
            if c >= 0.05 {
                failures.push(format!("{}: {what} changes {:.1} % ({x} → {y})", figure.scene_name(), 100.0 * c));
            }
        };
        if figure == Figure::Phantom {
            // The force–depth curve's figures (the phantom's target lies on the axis).
            check("peak puncture force", a.peak_puncture_n, b.peak_puncture_n);
            check("mean cutting force", a.mean_cutting_n, b.mean_cutting_n);
        } else {
            // The miss (Fig. 3) and the hit (Fig. 4) distances.
            check("closest approach", a.closest_m, b.closest_m);
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Issue 19: with energy-based cutting the friction peak behind the tip (+30 % over 5 mm, which
/// the paper attributes to cutting) acts only while the tip cuts. Withdrawing the needle from
/// the toughness phantom, once every contact slips, the axial force is the sum of the contacts'
/// friction shares, $\sum_i f_i \cdot t = q_0\,(s_{tip} - s_{min})$ (the distribution integrated
/// from the deepest-held contact's arc length to the tip's, $s_{tip}$ the needle's length): the
/// plain $q_0$, without the peak's $q_0 h w / 2$ (2.5 % of it here), which the threshold model
/// keeps while withdrawing.
#[test]
fn issue_19_with_toughness_the_friction_peak_acts_only_while_cutting() {
    use needlesim_core::sim::NodeState;
    use needlesim_offline::driver::{RunOptions, Script, ScriptedRun};
    let text = refine::variant_toml(Figure::Phantom, 19, 19, Model::Toughness).unwrap();
    // 40 mm down at 10 mm/s, 0.5 s still, 10 mm up at 10 mm/s.
    let traj = Trajectory::parse_csv(
        "t_s,x_m,y_m,theta_rad\n0,0.05,0.205,-1.5707963267948966\n4,0.05,0.165,-1.5707963267948966\n4.5,0.05,0.165,-1.5707963267948966\n5.5,0.05,0.175,-1.5707963267948966\n",
    )
    .unwrap();
    let (q0, h, w, len) = (10.0, 0.3, 0.005, 0.1);
    for (label, scene_text, peak_while_withdrawing) in
        [("toughness", text.clone(), false), ("thresholds", text.replace("cutting = \"toughness\"\n", ""), true)]
    {
        let scene_text = if peak_while_withdrawing {
            scene_text
                .lines()
                .filter(|l| !l.starts_with("fracture_toughness_j_per_m2") && !l.starts_with("diameter_m"))
                .collect::<Vec<_>>()
                .join("\n")
        } else {
            scene_text
        };
        let scene = parse_scene(&scene_text, Path::new("."), &MeshLimits::default()).unwrap_or_else(|e| panic!("{label}: {e:#}"));
        let mut run =
            ScriptedRun::new(scene.tissue.clone(), scene.params.clone(), Script::trajectory(&traj), RunOptions::default()).unwrap();
        let mut checked = 0;
        run.run(|tick, sim| {
            let out = sim.output();
            let withdrawing = tick.t_s > 4.6;
            let nodes = &out.needle_nodes;
            if withdrawing && nodes.len() >= 3 && nodes.iter().all(|n| n.state == NodeState::Slipping) {
                let t = [out.base.theta_rad.cos(), out.base.theta_rad.sin()];
                let axial: f64 = nodes.iter().map(|n| n.force_n[0] * t[0] + n.force_n[1] * t[1]).sum();
                let s_min = nodes.iter().map(|n| n.s_m).fold(f64::INFINITY, f64::min);
                let plain = q0 * (len - s_min);
                let want = if peak_while_withdrawing { plain + 0.5 * q0 * h * w } else { plain };
                assert!(
                    (axial.abs() - want).abs() < 1e-6 * want,
                    "{label}, t = {:.3} s: axial {axial} N against {want} N (plain q0: {plain} N)",
                    tick.t_s
                );
                checked += 1;
            }
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
        assert!(checked > 100, "{label}: only {checked} withdrawal ticks with every contact slipping");
    }
}
