//! Identification of Young's modulus and Poisson's ratio from a probing experiment by least squares
//! against the FEM model of the phantom.
//!
//! The model: the markers' mesh (a grid whose nodes are the markers, or a scene's mesh with the
//! markers registered to its nodes), its fixed nodes held, and the probed node moved by the
//! logged probe displacement $d(t)$ (relative to the reference frame 0). By linearity
//! $u(t) = d_x(t)\,U_x(\nu) + d_y(t)\,U_y(\nu)$ and the probe force
//! $F(t) = E\,(d_x(t)\,R_x(\nu) + d_y(t)\,R_y(\nu))$, where $U_{x,y}$, $R_{x,y}$ are the
//! displacements and the probe reaction for a unit probe displacement and $E = 1$: under
//! displacement control the displacements depend on $\nu$ only and the force is proportional to
//! $E$. The residuals are the free markers' displacements in every frame after the first,
//! $(u^{model} - u^{meas})/\sigma_u$, and the probe force at every log sample within the frames'
//! time span, $(F^{model} - F^{meas})/\sigma_F$.
//!
//! The fit eliminates $E$ (variable projection: for a given $\nu$ the best $E$ is the linear
//! least-squares solution $E^*(\nu) = \sum F^{meas}\cdot G / \sum G\cdot G$ with
//! $G = d_x R_x + d_y R_y$), then minimises the weighted sum of squares $S(\nu)$ over
//! $\nu \in [0, 0.499]$ by a coarse scan and a golden-section search. Each marker's displacements
//! share the noise of its frame-0 position, so the $K$ displacement residuals of one marker
//! component are whitened with $(I + \mathbf{1}\mathbf{1}^\top)^{-1/2} = I - c\,\mathbf{1}\mathbf{1}^\top$,
//! $c = (1 - 1/\sqrt{1+K})/K$, before they enter the sums. The noise levels
//! $\sigma_u$, $\sigma_F$, unless given, are estimated from the residuals of a first fit and the
//! fit repeated. Uncertainties: $\operatorname{cov}(\log E, \nu) = s^2 (J^\top J)^{-1}$ with $J$ the
//! Jacobian of the weighted residuals and $s^2 = S/(m - 2)$.

use anyhow::{Context, Result, bail};
use needlesim_core::{Material, MaterialMap, Mesh, MeshLimits, NodeCondition, PlaneModel, RectMeshParams, StaticProblem};
use serde::Serialize;

use crate::logs::{ProbeLog, interp};
use crate::tracks::MarkerTracks;

/// The FEM model of the probed phantom: a mesh, its plane model and fixed nodes, and the node
/// of every marker.
#[derive(Debug, Clone)]
pub struct ProbeModel {
    pub mesh: Mesh,
    pub plane: PlaneModel,
    pub fixed_nodes: Vec<usize>,
    /// `marker_node[k]`: the mesh node of marker k.
    pub marker_node: Vec<usize>,
}

/// Registers the markers' reference positions to mesh nodes: each marker to its nearest node,
/// which must lie within `tol_m`.
///
/// Errors: a marker outside every triangle ("mesh does not cover marker k at (x, y)"), a marker
/// farther than `tol_m` from every node, two markers on one node.
pub fn register_markers(mesh: &Mesh, positions_m: &[[f64; 2]], tol_m: f64) -> Result<Vec<usize>> {
    let nodes = mesh.nodes_m();
    let mut owner = vec![usize::MAX; nodes.len()];
    let mut out = Vec::with_capacity(positions_m.len());
    for (k, p) in positions_m.iter().enumerate() {
        let (best, dist) = nodes
            .iter()
            .enumerate()
            .map(|(i, x)| (i, (x[0] - p[0]).hypot(x[1] - p[1])))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        if dist > tol_m {
            if !covers(mesh, *p, tol_m) {
                bail!("mesh does not cover marker {k} at ({:.6}, {:.6}) m", p[0], p[1]);
            }
            bail!(
                "marker {k} at ({:.6}, {:.6}) m is {:.3} mm from the nearest mesh node {best}: markers must sit on mesh nodes (tolerance {:.3} mm)",
                p[0],
                p[1],
                dist * 1e3,
                tol_m * 1e3
            );
        }
        if owner[best] != usize::MAX {
            bail!("markers {} and {k} both lie on mesh node {best}", owner[best]);
        }
        owner[best] = k;
        out.push(best);
    }
    Ok(out)
}

/// Whether `p` lies in a triangle of the mesh (with a tolerance `tol_m` on its edges).
fn covers(mesh: &Mesh, p: [f64; 2], tol_m: f64) -> bool {
    mesh.triangles().iter().any(|t| {
        let [a, b, c] = t.map(|i| mesh.nodes_m()[i]);
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let l1 = ((b[0] - p[0]) * (c[1] - p[1]) - (c[0] - p[0]) * (b[1] - p[1])) / det;
        let l2 = ((c[0] - p[0]) * (a[1] - p[1]) - (a[0] - p[0]) * (c[1] - p[1])) / det;
        let l3 = 1.0 - l1 - l2;
        let h = (b[0] - a[0]).hypot(b[1] - a[1]).max(1e-12);
        l1.min(l2).min(l3) >= -tol_m / h
    })
}

/// The model from markers on a regular `nx × ny` grid of size `width × height`, its origin at the
/// markers' lower-left reference position; the bottom row is fixed.
///
/// Errors: the grid's node count differs from the marker count, a marker not on a grid node.
pub fn grid_model(tracks: &MarkerTracks, nx: usize, ny: usize, width_m: f64, height_m: f64, plane: PlaneModel) -> Result<ProbeModel> {
    if nx.saturating_mul(ny) != tracks.n_markers {
        bail!("--grid {nx},{ny} has {} nodes but the tracks have {} markers", nx.saturating_mul(ny), tracks.n_markers);
    }
    let p0: Vec<[f64; 2]> = (0..tracks.n_markers).map(|m| tracks.position_m(0, m)).collect();
    let origin = p0.iter().fold([f64::INFINITY; 2], |a, p| [a[0].min(p[0]), a[1].min(p[1])]);
    let mut g = RectMeshParams::new(nx, ny, width_m, height_m);
    g.origin_m = origin;
    let mesh = g.build(&MeshLimits::default()).context("--grid")?;
    let tol = 0.25 * (width_m / (nx - 1) as f64).min(height_m / (ny - 1) as f64);
    let marker_node = register_markers(&mesh, &p0, tol)?;
    let fixed_nodes = mesh.boundary_set("bottom").map(<[usize]>::to_vec).unwrap_or_default();
    Ok(ProbeModel { mesh, plane, fixed_nodes, marker_node })
}

/// Fit options.
#[derive(Debug, Clone, Default)]
pub struct ProbeFitOptions {
    /// The marker the probe presses (default: the marker whose last displacement is nearest the
    /// probe's).
    pub probe_marker: Option<usize>,
    /// Marker position noise, m (default: estimated from the residuals).
    pub marker_sigma_m: Option<f64>,
    /// Force noise, N (default: estimated from the residuals).
    pub force_sigma_n: Option<f64>,
}

/// The identified material.
#[derive(Debug, Clone, Serialize)]
pub struct ProbeFit {
    pub young_modulus_pa: f64,
    pub young_modulus_sigma_pa: f64,
    pub poisson_ratio: f64,
    pub poisson_ratio_sigma: f64,
    /// RMS of the (whitened) displacement residuals, m: ≈ the marker noise when the model fits.
    pub displacement_rms_m: f64,
    /// RMS of the force residuals, N.
    pub force_rms_n: f64,
    /// RMS of the weighted residuals (≈ 1 when the noise levels are right).
    pub weighted_rms: f64,
    pub marker_sigma_m: f64,
    pub force_sigma_n: f64,
    pub probe_marker: usize,
    pub n_frames_used: usize,
    pub n_force_samples: usize,
    pub n_residuals: usize,
    /// Evaluations of the model (two static solves each).
    pub iterations: usize,
}

struct Data {
    /// Frames used (index into the tracks), excluding the reference frame 0.
    frames: Vec<usize>,
    /// Probe displacement at those frames relative to frame 0.
    frame_disp: Vec<[f64; 2]>,
    /// Force samples: probe displacement relative to frame 0 and measured force.
    force: Vec<([f64; 2], [f64; 2])>,
    /// Free markers (not fixed, not the probe): (marker, node).
    free: Vec<(usize, usize)>,
}

/// The model's unit solutions for one ν (E = 1).
struct Unit {
    u: [Vec<f64>; 2],
    r: [[f64; 2]; 2],
}

fn unit_solutions(model: &ProbeModel, probe_node: usize, nu: f64) -> Result<Unit> {
    let mats = MaterialMap::per_region(
        &model.mesh,
        &vec![Material { young_modulus_pa: 1.0, poisson_ratio: nu }; model.mesh.region_names().len()],
        model.plane,
    )
    .context("material")?;
    let mut u: [Vec<f64>; 2] = Default::default();
    let mut r = [[0.0; 2]; 2];
    for (c, d) in [[1.0, 0.0], [0.0, 1.0]].into_iter().enumerate() {
        let mut conditions: Vec<(usize, NodeCondition)> =
            model.fixed_nodes.iter().filter(|&&n| n != probe_node).map(|&n| (n, NodeCondition::Fixed)).collect();
        conditions.push((probe_node, NodeCondition::World { ux_m: Some(d[0]), uy_m: Some(d[1]) }));
        let sol = StaticProblem { conditions, loads_n: vec![] }.solve(&model.mesh, &mats).context("probe model solve")?;
        r[c] =
            sol.reactions_n.iter().find(|x| x.0 == probe_node).map(|x| [x.1[0].unwrap_or(0.0), x.1[1].unwrap_or(0.0)]).unwrap_or([0.0; 2]);
        u[c] = sol.displacement_m;
    }
    Ok(Unit { u, r })
}

/// Residuals (unweighted) for ν: displacement residuals, force residuals, and E*(ν).
fn residuals(tracks: &MarkerTracks, data: &Data, unit: &Unit, e_fixed: Option<f64>) -> (Vec<f64>, Vec<f64>, f64) {
    let g: Vec<[f64; 2]> = data.force.iter().map(|(d, _)| [0, 1].map(|c| d[0] * unit.r[0][c] + d[1] * unit.r[1][c])).collect();
    let e = e_fixed.unwrap_or_else(|| {
        let (mut num, mut den) = (0.0, 0.0);
        for (gk, (_, f)) in g.iter().zip(&data.force) {
            num += gk[0] * f[0] + gk[1] * f[1];
            den += gk[0] * gk[0] + gk[1] * gk[1];
        }
        if den > 0.0 { num / den } else { 0.0 }
    });
    let mut ru = Vec::with_capacity(data.frames.len() * data.free.len() * 2);
    for (fi, &frame) in data.frames.iter().enumerate() {
        let d = data.frame_disp[fi];
        for &(m, n) in &data.free {
            let meas = tracks.displacement_m(frame, m);
            for (c, m) in meas.iter().enumerate() {
                ru.push(d[0] * unit.u[0][2 * n + c] + d[1] * unit.u[1][2 * n + c] - m);
            }
        }
    }
    // Whitening: every displacement shares its marker's frame-0 noise, so the K residuals of one
    // marker component have covariance σ²(I + 11ᵀ); (I + 11ᵀ)^{-1/2} = I − c 11ᵀ with
    // c = (1 − 1/√(1+K))/K makes them independent with variance σ².
    let (k, stride) = (data.frames.len(), 2 * data.free.len());
    let c = (1.0 - 1.0 / (1.0 + k as f64).sqrt()) / k as f64;
    for j in 0..stride {
        let sum: f64 = (0..k).map(|fi| ru[fi * stride + j]).sum();
        for fi in 0..k {
            ru[fi * stride + j] -= c * sum;
        }
    }
    let mut rf = Vec::with_capacity(2 * g.len());
    for (gk, (_, f)) in g.iter().zip(&data.force) {
        rf.push(e * gk[0] - f[0]);
        rf.push(e * gk[1] - f[1]);
    }
    (ru, rf, e)
}

fn ss(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum()
}

/// Fits E and ν. `progress(done, total)` is called after every model evaluation (`total` is an
/// estimate).
///
/// Errors (checked before any solve): fewer than 2 frames; a probe log that does not cover the
/// reference frame's time ("probe log covers t = a..b s but frames cover c..d s"); a probe marker
/// out of range; a model whose marker count differs from the tracks'; no free marker; no probe
/// displacement in the frames; a force that does not oppose the probe (E* ≤ 0).
pub fn fit_probe(
    tracks: &MarkerTracks,
    log: &ProbeLog,
    model: &ProbeModel,
    opts: &ProbeFitOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<ProbeFit> {
    let nf = tracks.n_frames();
    if nf < 2 {
        bail!("the marker tracks have {nf} frame(s): the fit needs at least 2 (the unloaded reference frame 0 and a loaded one)");
    }
    if model.marker_node.len() != tracks.n_markers {
        bail!("the model registers {} markers but the tracks have {}", model.marker_node.len(), tracks.n_markers);
    }
    let (a, b) = (log.times_s[0], log.times_s[log.times_s.len() - 1]);
    let (c, d) = (tracks.times_s[0], tracks.times_s[nf - 1]);
    let eps = 1e-9 * (1.0 + b.abs().max(d.abs()));
    if c < a - eps || c > b + eps {
        bail!(
            "probe log covers t = {a}..{b} s but frames cover {c}..{d} s (the log must cover the reference frame 0 and at least one more)"
        );
    }
    let frames: Vec<usize> = (1..nf).filter(|&k| tracks.times_s[k] <= b + eps).collect();
    if frames.is_empty() {
        bail!(
            "probe log covers t = {a}..{b} s but frames cover {c}..{d} s (the log must cover the reference frame 0 and at least one more)"
        );
    }
    let d0 = interp(&log.times_s, &log.disp_m, c);
    let rel = |x: [f64; 2]| [x[0] - d0[0], x[1] - d0[1]];
    let frame_disp: Vec<[f64; 2]> = frames.iter().map(|&k| rel(interp(&log.times_s, &log.disp_m, tracks.times_s[k]))).collect();
    let t_last = tracks.times_s[*frames.last().expect("non-empty")];
    let force: Vec<([f64; 2], [f64; 2])> = (0..log.times_s.len())
        .filter(|&k| log.times_s[k] >= c - eps && log.times_s[k] <= t_last + eps)
        .map(|k| (rel(log.disp_m[k]), log.force_n[k]))
        .collect();
    let probe_marker = match opts.probe_marker {
        Some(m) if m >= tracks.n_markers => bail!("probe marker {m} does not exist (the tracks have {} markers)", tracks.n_markers),
        Some(m) => m,
        None => {
            let (fl, dl) = (*frames.last().expect("non-empty"), *frame_disp.last().expect("non-empty"));
            (0..tracks.n_markers)
                .map(|m| {
                    let u = tracks.displacement_m(fl, m);
                    (m, (u[0] - dl[0]).hypot(u[1] - dl[1]))
                })
                .fold((0, f64::INFINITY), |x, y| if y.1 < x.1 { y } else { x })
                .0
        }
    };
    let probe_node = model.marker_node[probe_marker];
    if frame_disp.iter().all(|d| d[0] == 0.0 && d[1] == 0.0) {
        bail!("the probe log shows no probe displacement at the frame times: nothing to fit");
    }
    let free: Vec<(usize, usize)> = model
        .marker_node
        .iter()
        .enumerate()
        .filter(|&(m, n)| m != probe_marker && !model.fixed_nodes.contains(n))
        .map(|(m, &n)| (m, n))
        .collect();
    if free.is_empty() {
        bail!("no marker is free (every marker is fixed or the probe): the displacements carry no information");
    }
    let data = Data { frames, frame_disp, force, free };
    let mut evals = 0usize;
    let total_est = 2 * 45 + 2;
    let mut eval = |nu: f64| -> Result<Unit> {
        let u = unit_solutions(model, probe_node, nu)?;
        evals += 1;
        progress(evals, total_est);
        Ok(u)
    };
    let mut sigma_u = opts.marker_sigma_m.unwrap_or(0.0);
    let mut sigma_f = opts.force_sigma_n.unwrap_or(0.0);
    let auto = opts.marker_sigma_m.is_none() || opts.force_sigma_n.is_none();
    if sigma_u <= 0.0 || sigma_f <= 0.0 {
        // First pass weights: 0.1 % of the largest measured displacement and force.
        let umax = data.frames.iter().flat_map(|&f| data.free.iter().map(move |&(m, _)| (f, m))).fold(0.0f64, |acc, (f, m)| {
            let u = tracks.displacement_m(f, m);
            acc.max(u[0].hypot(u[1]))
        });
        let fmax = data.force.iter().fold(0.0f64, |acc, (_, f)| acc.max(f[0].hypot(f[1])));
        if sigma_u <= 0.0 {
            sigma_u = 1e-3 * umax.max(1e-12);
        }
        if sigma_f <= 0.0 {
            sigma_f = 1e-3 * fmax.max(1e-12);
        }
    }
    let mut nu_best = 0.3;
    let passes = if auto { 2 } else { 1 };
    for pass in 0..passes {
        let (su, sf) = (sigma_u, sigma_f);
        let mut cost = |nu: f64| -> Result<f64> {
            let unit = eval(nu)?;
            let (ru, rf, _) = residuals(tracks, &data, &unit, None);
            Ok(ss(&ru) / (su * su) + ss(&rf) / (sf * sf))
        };
        // Coarse scan, then golden section on the bracket around the best point.
        let grid: Vec<f64> = (0..=10).map(|i| 0.499 * i as f64 / 10.0).collect();
        let mut costs = Vec::with_capacity(grid.len());
        for &g in &grid {
            costs.push(cost(g)?);
        }
        let ib = (0..grid.len()).fold(0, |b, i| if costs[i] < costs[b] { i } else { b });
        let (mut lo, mut hi) = (grid[ib.saturating_sub(1)], grid[(ib + 1).min(grid.len() - 1)]);
        let gr = 0.5 * (5f64.sqrt() - 1.0);
        let (mut x1, mut x2) = (hi - gr * (hi - lo), lo + gr * (hi - lo));
        let (mut f1, mut f2) = (cost(x1)?, cost(x2)?);
        while hi - lo > 1e-6 {
            if f1 < f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - gr * (hi - lo);
                f1 = cost(x1)?;
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + gr * (hi - lo);
                f2 = cost(x2)?;
            }
        }
        nu_best = 0.5 * (lo + hi);
        if auto && pass == 0 {
            let unit = eval(nu_best)?;
            let (ru, rf, _) = residuals(tracks, &data, &unit, None);
            if opts.marker_sigma_m.is_none() {
                sigma_u = (ss(&ru) / ru.len() as f64).sqrt().max(1e-15);
            }
            if opts.force_sigma_n.is_none() {
                sigma_f = (ss(&rf) / rf.len() as f64).sqrt().max(1e-15);
            }
        }
    }
    let unit = eval(nu_best)?;
    let (ru, rf, e) = residuals(tracks, &data, &unit, None);
    if e.is_nan() || e <= 0.0 {
        bail!(
            "the measured probe force does not oppose the probe displacement (best E = {e:.3e} Pa): check the force signs (force the probe applies to the tissue)"
        );
    }
    // Jacobian of the weighted residuals in (log E, ν): ∂r/∂log E = E G / σ_F (forces only), ∂r/∂ν by central differences.
    let h = 1e-4_f64.min(0.499 - nu_best).min(nu_best).max(1e-6);
    let (up, um) = (eval(nu_best + h)?, eval(nu_best - h)?);
    let (rup, rfp, _) = residuals(tracks, &data, &up, Some(e));
    let (rum, rfm, _) = residuals(tracks, &data, &um, Some(e));
    let m = ru.len() + rf.len();
    let (mut a11, mut a12, mut a22) = (0.0, 0.0, 0.0);
    for i in 0..ru.len() {
        let dn = (rup[i] - rum[i]) / (2.0 * h) / sigma_u;
        a22 += dn * dn;
    }
    for i in 0..rf.len() {
        let dl = (rf[i] + data_force(&data, i)) / sigma_f; // E·G / σ_F
        let dn = (rfp[i] - rfm[i]) / (2.0 * h) / sigma_f;
        a11 += dl * dl;
        a12 += dl * dn;
        a22 += dn * dn;
    }
    let s_cost = ss(&ru) / (sigma_u * sigma_u) + ss(&rf) / (sigma_f * sigma_f);
    let s2 = s_cost / (m.saturating_sub(2).max(1)) as f64;
    let det = a11 * a22 - a12 * a12;
    let (var_log_e, var_nu) = if det > 0.0 { (s2 * a22 / det, s2 * a11 / det) } else { (f64::INFINITY, f64::INFINITY) };
    Ok(ProbeFit {
        young_modulus_pa: e,
        young_modulus_sigma_pa: e * var_log_e.sqrt(),
        poisson_ratio: nu_best,
        poisson_ratio_sigma: var_nu.sqrt(),
        displacement_rms_m: (ss(&ru) / ru.len().max(1) as f64).sqrt(),
        force_rms_n: (ss(&rf) / rf.len().max(1) as f64).sqrt(),
        weighted_rms: (s_cost / m.max(1) as f64).sqrt(),
        marker_sigma_m: sigma_u,
        force_sigma_n: sigma_f,
        probe_marker,
        n_frames_used: data.frames.len(),
        n_force_samples: data.force.len(),
        n_residuals: m,
        iterations: evals,
    })
}

/// The measured force component behind force residual `i`.
fn data_force(data: &Data, i: usize) -> f64 {
    data.force[i / 2].1[i % 2]
}

#[cfg(all(test, feature = "synthetic"))]
mod tests {
    use super::*;
    use crate::experiment::{ProbeSynthParams, synth_probe};

    #[test]
    fn recovers_e_and_nu_from_noisy_probing() {
        let p = ProbeSynthParams::default();
        let ex = synth_probe(&p).unwrap();
        let model = grid_model(&ex.tracks, p.nx, p.ny, p.width_m, p.height_m, p.plane).unwrap();
        let fit = fit_probe(&ex.tracks, &ex.log, &model, &ProbeFitOptions::default(), &mut |_, _| {}).unwrap();
        assert_eq!(fit.probe_marker, ex.probe_marker);
        let e_err = (fit.young_modulus_pa / 30e3 - 1.0).abs();
        assert!(e_err < 0.02, "E = {} ± {}", fit.young_modulus_pa, fit.young_modulus_sigma_pa);
        assert!((fit.poisson_ratio - 0.45).abs() < 0.02, "ν = {} ± {}", fit.poisson_ratio, fit.poisson_ratio_sigma);
        assert!(fit.young_modulus_sigma_pa > 0.0 && fit.poisson_ratio_sigma > 0.0);
    }

    #[test]
    fn inconsistent_inputs_are_errors() {
        let p = ProbeSynthParams::default();
        let ex = synth_probe(&p).unwrap();
        let model = grid_model(&ex.tracks, p.nx, p.ny, p.width_m, p.height_m, p.plane).unwrap();
        let mut late = ex.log.clone();
        for t in &mut late.times_s {
            *t += 100.0;
        }
        let e = fit_probe(&ex.tracks, &late, &model, &ProbeFitOptions::default(), &mut |_, _| {}).unwrap_err().to_string();
        assert!(e.contains("probe log covers t = 100..102.5 s but frames cover 0..2.5 s"), "{e}");
        let e = grid_model(&ex.tracks, 10, 11, 0.1, 0.1, p.plane).unwrap_err().to_string();
        assert!(e.contains("110 nodes but the tracks have 121 markers"), "{e}");
        let small = RectMeshParams::new(11, 11, 0.05, 0.1).build(&MeshLimits::default()).unwrap();
        let p0: Vec<[f64; 2]> = (0..ex.tracks.n_markers).map(|m| ex.tracks.position_m(0, m)).collect();
        let e = register_markers(&small, &p0, 1e-3).unwrap_err().to_string();
        assert!(e.contains("mesh does not cover marker 6 at (0.0"), "{e}");
    }
}
