//! Needle force distribution from an insertion experiment: nodal forces $f = K u$ from the
//! measured marker displacements, the needle nodes along the shaft, and the fitted friction per
//! length and tip peak; the fitted parameters written into a scene file.
//!
//! Every mesh node carries a marker (registered to it, see [`crate::probe::register_markers`]).
//! Frame 0 is the undeformed phantom; the reference position of every node is its mesh position
//! under the affine map fitted to the frame-0 markers (camera registration, with the frame-0 marker
//! noise averaged out). In frame $k$ the displacements $u_k = p_k - (A X + b)$ give the forces the
//! needle applies to the tissue, $f_k = K u_k$ (reactions at fixed nodes excluded). The needle nodes are the free nodes
//! whose deformed position lies within `band_m` (default: the scene's capture radius) of the
//! shaft line of the base pose at the frame's time (the trajectory), between the shaft's entry and
//! its tip. Each node's axial force $a_i = f_i\cdot t$ ($t$ the needle axis) and its distance
//! behind the tip $\ell_i = s_{tip} - s_i$ ($s$ the projection on the axis) are compared with the
//! model the simulator uses: with the nodes ordered from the tip, node $i$'s tributary segment
//! $[\ell_i^-, \ell_i^+]$ runs from the midpoint to its deeper neighbour (the tip itself for the
//! deepest) to the midpoint to its shallower neighbour (its own position for the shallowest), and
//! $$a_i = \int_{\ell_i^-}^{\ell_i^+} q(\ell)\,d\ell,\qquad q(\ell) = q_0\Big(1 + h\,\tfrac12\big(1+\cos\tfrac{\pi\ell}{w}\big)[\ell<w]\Big).$$
//! A node within `tip_tol` of the tip is the node carried by the tip (its force is the cutting
//! force, not friction): it is reported, not fitted. Only frames in which the needle advances
//! (axial base velocity > 0 on the trajectory) are used: the model is kinetic friction.
//!
//! The fit: for a given $w$ the model is linear in $(q_0, q_0 h)$, solved by linear least squares;
//! $w$ minimises the residual sum of squares (a scan over $[0.05, 3]$ mean element edges and a
//! golden-section search). Uncertainty of $q_0$: $s^2 (A^\top A)^{-1}$ of the linear problem.
//! The *peak position* is reported as $w/2$, where the peak's excess falls to half its height.
//! Per frame, $q_0$ is re-fitted with $h, w$ held (friction as a function of depth, summarised by
//! a straight line $q_0(d) = a + b\,d$), and the sum
//! of the needle nodes' axial forces is compared with the measured base force $-F\cdot t$
//! (interpolated at the frame's time).

use anyhow::{Context, Result, bail};
use needlesim_core::RegionNeedleParams;
use needlesim_core::assembly::mul_stiffness;
use needlesim_core::num::num;
use serde::Serialize;

use crate::logs::{ForceLog, interp};
use crate::probe::register_markers;
use crate::tracks::MarkerTracks;
use needlesim_scene::{Scene, Trajectory};

/// Fit options.
#[derive(Debug, Clone, Default)]
pub struct NeedleFitOptions {
    /// Lateral half-width of the band around the shaft, m (default: the scene's capture radius).
    pub band_m: Option<f64>,
    /// Distance behind the tip under which a node is the tip's node, m (default: 2 % of the mean
    /// element edge).
    pub tip_tol_m: Option<f64>,
    /// Hold the peak height $h$ at this value (e.g. the paper's 0.3) and fit $q_0$ and $w$ only:
    /// with nodes an element apart the data fix the peak's area $q_0 h w/2$ much better than
    /// $h$ and $w$ separately.
    pub tip_peak_ratio: Option<f64>,
}

/// One frame's estimate.
#[derive(Debug, Clone, Serialize)]
pub struct FrameFit {
    pub t_s: f64,
    /// Insertion depth from the force log, m.
    pub depth_m: f64,
    pub n_shaft_nodes: usize,
    /// Friction per length fitted to this frame alone (h, w held), N/m.
    pub friction_n_per_m: f64,
    /// Sum of the shaft nodes' axial forces, N.
    pub shaft_force_n: f64,
    /// Axial force on the tip's node (0 when no node is at the tip), N.
    pub tip_force_n: f64,
    /// Measured base force along the axis, $-F\cdot t$, N.
    pub base_axial_measured_n: f64,
}

/// The fitted needle force distribution.
#[derive(Debug, Clone, Serialize)]
pub struct NeedleFit {
    pub region: String,
    pub friction_n_per_m: f64,
    pub friction_sigma_n_per_m: f64,
    pub tip_peak_ratio: f64,
    pub tip_peak_width_m: f64,
    /// $w/2$: where the peak's excess falls to half its height, behind the tip, m.
    pub peak_position_m: f64,
    /// The widths whose residual sum of squares is within $s^2$ of the minimum
    /// ($\Delta\chi^2 = 1$): how well the data fix $w$, m.
    pub tip_peak_width_range_m: [f64; 2],
    /// The peak's area $\int q_0 h\,\tfrac12(1+\cos(\pi\ell/w))\,d\ell = q_0 h w / 2$, N.
    pub tip_peak_area_n: f64,
    /// Whether $h$ was held (given) rather than fitted.
    pub tip_peak_ratio_held: bool,
    /// RMS of the per-node axial force residuals, N.
    pub residual_rms_n: f64,
    pub n_residuals: usize,
    pub n_frames_used: usize,
    /// RMS of (needle nodes' axial force sum − measured base axial force) over the frames used, N.
    pub base_force_rms_diff_n: f64,
    /// RMS of the measured base axial force over the frames used, N.
    pub base_force_rms_n: f64,
    pub mean_element_edge_m: f64,
    /// The per-frame friction per length as a straight line in depth, $q_0(d) = a + b\,d$:
    /// `[a` N/m`, b` N/m²`]` (least squares over the frames; a slope near 0 means uniform friction).
    pub friction_vs_depth: [f64; 2],
    pub frames: Vec<FrameFit>,
}

/// One node's observation: distance behind the tip, tributary segment, axial force.
struct Obs {
    seg: [f64; 2],
    a: f64,
}

/// $\tfrac12\int_{l_1}^{l_2} (1+\cos(\pi\ell/w))[\ell<w]\,d\ell$.
fn peak_term(w: f64, l1: f64, l2: f64) -> f64 {
    let p = RegionNeedleParams { friction_n_per_m: 1.0, tip_peak_ratio: 1.0, tip_peak_width_m: w, ..Default::default() };
    p.friction_integral_n(l1, l2) - (l2.max(0.0) - l1.max(0.0)).max(0.0)
}

/// Linear least squares for (q0, q0·h) at width w, or for q0 alone with h held: (q0, q0·h, sse,
/// (AᵀA)⁻¹[0][0]).
fn solve_w(obs: &[Obs], w: f64, hold_h: Option<f64>) -> (f64, f64, f64, f64) {
    if let Some(h) = hold_h {
        let x = |o: &Obs| (o.seg[1] - o.seg[0]) + h * peak_term(w, o.seg[0], o.seg[1]);
        let (s11, r1) = obs.iter().fold((0.0, 0.0), |acc, o| (acc.0 + x(o) * x(o), acc.1 + x(o) * o.a));
        let q = if s11 > 0.0 { r1 / s11 } else { 0.0 };
        let sse = obs.iter().map(|o| (q * x(o) - o.a).powi(2)).sum();
        return (q, q * h, sse, if s11 > 0.0 { 1.0 / s11 } else { f64::INFINITY });
    }
    let (mut s11, mut s12, mut s22, mut r1, mut r2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for o in obs {
        let (x1, x2) = (o.seg[1] - o.seg[0], peak_term(w, o.seg[0], o.seg[1]));
        s11 += x1 * x1;
        s12 += x1 * x2;
        s22 += x2 * x2;
        r1 += x1 * o.a;
        r2 += x2 * o.a;
    }
    let det = s11 * s22 - s12 * s12;
    if det.abs() <= 1e-30 * (s11 * s22).max(1e-300) || det.is_nan() {
        let q = if s11 > 0.0 { r1 / s11 } else { 0.0 };
        let sse = obs.iter().map(|o| (q * (o.seg[1] - o.seg[0]) - o.a).powi(2)).sum();
        return (q, 0.0, sse, if s11 > 0.0 { 1.0 / s11 } else { f64::INFINITY });
    }
    let q = (s22 * r1 - s12 * r2) / det;
    let b = (s11 * r2 - s12 * r1) / det;
    let sse = obs.iter().map(|o| (q * (o.seg[1] - o.seg[0]) + b * peak_term(w, o.seg[0], o.seg[1]) - o.a).powi(2)).sum();
    (q, b, sse, s22 / det)
}

/// Fits the friction distribution of an insertion; `progress(k, n_frames)` is called before each
/// frame (`Break` stops the fit with [`crate::Cancelled`]).
///
/// Errors (before any work): a marker count different from the mesh's node count, a marker that
/// the mesh does not cover or that is not on a node (or two on one node), a force log and
/// frames whose time ranges do not overlap ("force log covers t = a..b s but frames cover c..d
/// s"), fewer than 2 frames; after the nodal forces: no frame in which the needle advances with at
/// least 2 shaft nodes.
pub fn fit_needle(
    scene: &Scene,
    tracks: &MarkerTracks,
    log: &ForceLog,
    traj: &Trajectory,
    opts: &NeedleFitOptions,
    progress: crate::Progress<'_>,
) -> Result<NeedleFit> {
    let tissue = &scene.tissue;
    let mesh = tissue.mesh();
    let n = mesh.n_nodes();
    let nf = tracks.n_frames();
    if nf < 2 {
        bail!("the marker tracks have {nf} frame(s): the fit needs at least 2 (the reference frame 0 and a loaded one)");
    }
    let edge = needlesim_scene::mean_edge_m(mesh);
    if tracks.n_markers != n {
        bail!(
            "the tracks have {} markers for {n} mesh nodes: the nodal forces f = K u need the displacement of every node (a marker on each)",
            tracks.n_markers
        );
    }
    let p0: Vec<[f64; 2]> = (0..tracks.n_markers).map(|m| tracks.position_m(0, m)).collect();
    let marker_node = register_markers(mesh, &p0, 0.25 * edge)?;
    let reference = affine_reference(mesh.nodes_m(), &marker_node, &p0)?;
    let (a, b) = (log.times_s[0], log.times_s[log.times_s.len() - 1]);
    let (c, d) = (tracks.times_s[0], tracks.times_s[nf - 1]);
    if b < c || a > d {
        bail!("force log covers t = {}..{} s but frames cover {}..{} s: they must overlap", num(a), num(b), num(c), num(d));
    }
    let band = opts.band_m.unwrap_or(scene.params.capture_radius_m);
    if !(band.is_finite() && band > 0.0) {
        bail!("band_m = {} must be finite and > 0", num(band));
    }
    if let Some(h) = opts.tip_peak_ratio
        && !(h.is_finite() && h >= 0.0)
    {
        bail!("tip_peak_ratio = {} must be finite and ≥ 0", needlesim_core::num::num(h));
    }
    let tip_tol = opts.tip_tol_m.unwrap_or(0.02 * edge);
    let region = mesh.region_names().first().cloned().unwrap_or_else(|| "tissue".to_owned());
    let shape = scene.params.needle;
    let s_tip = shape.tip_s_m();
    let mut u = vec![0.0; 2 * n];
    let mut f = vec![0.0; 2 * n];
    // Per used frame: (frame, time, observations, tip force, node axial sum).
    let mut per_frame: Vec<(usize, f64, Vec<Obs>, f64, f64)> = Vec::new();
    for k in 1..nf {
        crate::report(progress, k, nf)?;
        let t = tracks.times_s[k];
        if t < a || t > b {
            continue;
        }
        let pose = needlesim_scene::base_pose(traj.pose_at(t));
        let (pp, pm) = (traj.pose_at(t + 1e-3), traj.pose_at(t - 1e-3));
        let ax = pose.axis();
        let v_axial = ((pp.x_m - pm.x_m) * ax[0] + (pp.y_m - pm.y_m) * ax[1]) / 2e-3;
        if v_axial.is_nan() || v_axial <= 0.0 {
            continue;
        }
        for (m, &node) in marker_node.iter().enumerate() {
            let (pk, x) = (tracks.position_m(k, m), reference[node]);
            u[2 * node] = pk[0] - x[0];
            u[2 * node + 1] = pk[1] - x[1];
        }
        mul_stiffness(tissue.stiffness(), &u, &mut f);
        let mut shaft: Vec<(f64, f64)> = Vec::new(); // (ℓ, axial force)
        let mut tip_force = 0.0;
        for node in 0..n {
            if tissue.is_fixed(node) {
                continue;
            }
            let x = mesh.nodes_m()[node];
            let p = [x[0] + u[2 * node], x[1] + u[2 * node + 1]];
            let (s, lat) = shape.project(&pose, p);
            let l = s_tip - s;
            if lat.abs() > band || l < -band || s < 0.0 {
                continue;
            }
            let axial = f[2 * node] * ax[0] + f[2 * node + 1] * ax[1];
            if l < tip_tol {
                tip_force += axial;
            } else {
                shaft.push((l, axial));
            }
        }
        if shaft.len() < 2 {
            continue;
        }
        shaft.sort_by(|x, y| x.0.total_cmp(&y.0));
        let m = shaft.len();
        let obs: Vec<Obs> = (0..m)
            .map(|i| {
                let l = shaft[i].0;
                let lo = if i == 0 { 0.0 } else { 0.5 * (l + shaft[i - 1].0) };
                let hi = if i + 1 == m { l } else { 0.5 * (l + shaft[i + 1].0) };
                Obs { seg: [lo, hi], a: shaft[i].1 }
            })
            .collect();
        let sum: f64 = shaft.iter().map(|s| s.1).sum::<f64>() + tip_force;
        per_frame.push((k, t, obs, tip_force, sum));
    }
    if per_frame.is_empty() {
        bail!(
            "no frame shows the needle advancing with at least 2 shaft nodes in the tissue (band {:.3} mm around the shaft of the trajectory's pose)",
            band * 1e3
        );
    }
    let all: Vec<Obs> = per_frame.iter().flat_map(|p| p.2.iter().map(|o| Obs { seg: o.seg, a: o.a })).collect();
    // Width: scan then golden section on the SSE.
    let hold = opts.tip_peak_ratio;
    let sse_w = |w: f64| solve_w(&all, w, hold).2;
    let grid: Vec<f64> = (0..=30).map(|i| edge * (0.05 + 2.95 * i as f64 / 30.0)).collect();
    let costs: Vec<f64> = grid.iter().map(|&w| sse_w(w)).collect();
    let ib = (0..grid.len()).fold(0, |bst, i| if costs[i] < costs[bst] { i } else { bst });
    let (mut lo, mut hi) = (grid[ib.saturating_sub(1)], grid[(ib + 1).min(grid.len() - 1)]);
    let gr = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - gr * (hi - lo), lo + gr * (hi - lo));
    let (mut f1, mut f2) = (sse_w(x1), sse_w(x2));
    while hi - lo > 1e-4 * edge {
        if f1 < f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - gr * (hi - lo);
            f1 = sse_w(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + gr * (hi - lo);
            f2 = sse_w(x2);
        }
    }
    let w = 0.5 * (lo + hi);
    let (q0, qh, sse, inv11) = solve_w(&all, w, hold);
    let h = hold.unwrap_or(if q0 > 0.0 { (qh / q0).max(0.0) } else { 0.0 });
    let dof = all.len().saturating_sub(if hold.is_some() { 2 } else { 3 }).max(1) as f64;
    let q_sigma = (sse / dof * inv11).sqrt();
    let fine: Vec<f64> = (0..=300).map(|i| edge * (0.05 + 2.95 * i as f64 / 300.0)).collect();
    let within: Vec<f64> = fine.iter().copied().filter(|&x| sse_w(x) <= sse + sse / dof).collect();
    let w_range = [within.first().copied().unwrap_or(w).min(w), within.last().copied().unwrap_or(w).max(w)];
    // Per frame: q0 with h, w held; base force consistency.
    let mut frames = Vec::with_capacity(per_frame.len());
    let (mut diff2, mut base2) = (0.0, 0.0);
    for (_, t, obs, tip, sum) in &per_frame {
        let shape_of = |o: &Obs| (o.seg[1] - o.seg[0]) + h * peak_term(w, o.seg[0], o.seg[1]);
        let (num, den) = obs.iter().fold((0.0, 0.0), |acc, o| (acc.0 + shape_of(o) * o.a, acc.1 + shape_of(o) * shape_of(o)));
        let fl = interp(&log.times_s, &log.force_n, *t);
        let pose = needlesim_scene::base_pose(traj.pose_at(*t));
        let ax = pose.axis();
        let base_axial = -(fl[0] * ax[0] + fl[1] * ax[1]);
        diff2 += (sum - base_axial).powi(2);
        base2 += base_axial * base_axial;
        frames.push(FrameFit {
            t_s: *t,
            depth_m: interp(&log.times_s, &log.depth_m.iter().map(|&d| [d]).collect::<Vec<_>>(), *t)[0],
            n_shaft_nodes: obs.len(),
            friction_n_per_m: if den > 0.0 { num / den } else { 0.0 },
            shaft_force_n: obs.iter().map(|o| o.a).sum(),
            tip_force_n: *tip,
            base_axial_measured_n: base_axial,
        });
    }
    let nfu = per_frame.len() as f64;
    let (md, mq) = frames.iter().fold((0.0, 0.0), |acc, fr| (acc.0 + fr.depth_m / nfu, acc.1 + fr.friction_n_per_m / nfu));
    let (sdd, sdq) = frames
        .iter()
        .fold((0.0, 0.0), |acc, fr| (acc.0 + (fr.depth_m - md).powi(2), acc.1 + (fr.depth_m - md) * (fr.friction_n_per_m - mq)));
    let slope = if sdd > 0.0 { sdq / sdd } else { 0.0 };
    Ok(NeedleFit {
        region,
        friction_n_per_m: q0,
        friction_sigma_n_per_m: q_sigma,
        tip_peak_ratio: h,
        tip_peak_width_m: w,
        peak_position_m: 0.5 * w,
        tip_peak_width_range_m: w_range,
        tip_peak_area_n: 0.5 * q0 * h * w,
        tip_peak_ratio_held: hold.is_some(),
        residual_rms_n: (sse / all.len() as f64).sqrt(),
        n_residuals: all.len(),
        n_frames_used: per_frame.len(),
        base_force_rms_diff_n: (diff2 / nfu).sqrt(),
        base_force_rms_n: (base2 / nfu).sqrt(),
        mean_element_edge_m: edge,
        friction_vs_depth: [mq - slope * md, slope],
        frames,
    })
}

/// The reference (undeformed) position of every node: the mesh node mapped by the affine map
/// $p = A x + b$ fitted by least squares to the markers' frame-0 positions. It absorbs the camera
/// registration (translation, rotation, scale, shear) while averaging out the markers' frame-0
/// noise, which would otherwise enter every frame's displacements alike.
///
/// Errors: markers that do not span the plane (all on one line).
fn affine_reference(nodes: &[[f64; 2]], marker_node: &[usize], p0: &[[f64; 2]]) -> Result<Vec<[f64; 2]>> {
    // Normal equations of [x, y, 1] · [a, b, d]ᵀ = p_c, centred for conditioning.
    let n = marker_node.len() as f64;
    let c = marker_node.iter().fold([0.0; 2], |acc, &i| [acc[0] + nodes[i][0] / n, acc[1] + nodes[i][1] / n]);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    let mut rhs = [[0.0; 3]; 2];
    for (k, &i) in marker_node.iter().enumerate() {
        let (x, y) = (nodes[i][0] - c[0], nodes[i][1] - c[1]);
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
        for d in 0..2 {
            rhs[d][0] += x * p0[k][d];
            rhs[d][1] += y * p0[k][d];
            rhs[d][2] += p0[k][d];
        }
    }
    let det = sxx * syy - sxy * sxy;
    if det.is_nan() || det <= 1e-12 * (sxx * syy).max(1e-300) {
        bail!("the markers lie on one line: they do not register the mesh");
    }
    let maps: Vec<[f64; 3]> = (0..2)
        .map(|d| {
            let (r0, r1) = (rhs[d][0], rhs[d][1]);
            [(syy * r0 - sxy * r1) / det, (sxx * r1 - sxy * r0) / det, rhs[d][2] / n]
        })
        .collect();
    Ok(nodes
        .iter()
        .map(|p| {
            let (x, y) = (p[0] - c[0], p[1] - c[1]);
            [maps[0][0] * x + maps[0][1] * y + maps[0][2], maps[1][0] * x + maps[1][1] * y + maps[1][2]]
        })
        .collect())
}

/// Writes the fitted parameters into a scene's TOML text: the region named `region` (its
/// `friction_n_per_m`, `tip_peak_ratio`, `tip_peak_width_m`) of `base_toml`. Comments and layout
/// of the base scene are not kept (the text is re-serialised).
///
/// Errors: TOML that does not parse, no `[[regions]]` entry named `region`.
pub fn write_fitted_scene(base_toml: &str, region: &str, fit: &NeedleFit) -> Result<String> {
    let mut doc: toml::Table = base_toml
        .parse()
        .map_err(|e: toml::de::Error| anyhow::anyhow!("base scene: {}", needlesim_scene::limit::toml_message(&e, base_toml)))?;
    let regions = doc.get_mut("regions").and_then(|r| r.as_array_mut()).context("base scene: no [[regions]]")?;
    let r = regions
        .iter_mut()
        .filter_map(|r| r.as_table_mut())
        .find(|r| r.get("name").and_then(|n| n.as_str()) == Some(region))
        .with_context(|| format!("base scene: no [[regions]] entry is named '{region}'"))?;
    r.insert("friction_n_per_m".into(), toml::Value::Float(fit.friction_n_per_m));
    r.insert("tip_peak_ratio".into(), toml::Value::Float(fit.tip_peak_ratio));
    r.insert("tip_peak_width_m".into(), toml::Value::Float(fit.tip_peak_width_m));
    let desc = format!(
        "identified by the needle force fit (needlesim-lab identify needle): q0 = {:.4} N/m, h = {:.3}, w = {:.3} mm",
        fit.friction_n_per_m,
        fit.tip_peak_ratio,
        fit.tip_peak_width_m * 1e3
    );
    doc.insert("description".into(), toml::Value::String(desc));
    toml::to_string(&doc).context("serialise the fitted scene")
}

#[cfg(all(test, feature = "synthetic"))]
mod tests {
    use super::*;
    use crate::experiment::{NeedleSynthParams, synth_needle};
    use needlesim_core::MeshLimits;

    #[test]
    fn recovers_friction_and_peak_from_a_synthetic_insertion() {
        let scene = needlesim_scene::load_scene("paper-phantom", &MeshLimits::default()).unwrap();
        let traj = Trajectory::parse_csv(scene.example_trajectory.unwrap()).unwrap();
        let p = NeedleSynthParams { t_end_s: Some(4.0), ..Default::default() };
        let ex = synth_needle(&scene, &traj, &p).unwrap();
        let fit = fit_needle(&scene, &ex.tracks, &ex.log, &traj, &NeedleFitOptions::default(), &mut crate::no_progress).unwrap();
        let truth = scene.params.regions[0];
        let q_err = (fit.friction_n_per_m / truth.friction_n_per_m - 1.0).abs();
        assert!(q_err < 0.05, "q0 = {} (truth {})", fit.friction_n_per_m, truth.friction_n_per_m);
        assert!((fit.peak_position_m - 0.5 * truth.tip_peak_width_m).abs() < fit.mean_element_edge_m);
    }
}
