//! Identification of Young's modulus and Poisson's ratio from a probing experiment by least squares
//! against the FEM model of the phantom.
//!
//! The model: a mesh carrying the markers (a grid whose every `refine`-th node is a marker, or a
//! scene's mesh with the markers registered to its nodes), its fixed nodes held, and the measured
//! probe force $F(t)$ (relative to frame 0) applied at the probed node. By linearity the markers'
//! displacements are $u(t) = \frac{1}{E}\,(F_x(t)\,V_x(\nu) + F_y(t)\,V_y(\nu))$, where $V_{x,y}$
//! are the displacements under a unit force and $E = 1$: under force control $\nu$ sets the
//! pattern and $E$ only scales it. The residuals are the free markers' displacements (not the
//! probe's) in every frame after the first, $(u^{model} - u^{meas})/\sigma_u$, with $F$ at each
//! frame from a least-squares straight line of the logged force in the logged probe displacement
//! (a linear tissue's force is one; the line averages the force noise over every log sample; a
//! log without probe displacements falls back to interpolating the force in time).
//!
//! Why force control (issue 19): a probe is small against the mesh, and in 2D the displacement
//! under a point load grows like $\log(1/h)$ as the mesh is refined, so the force a *prescribed*
//! probe displacement needs depends on the model's mesh: fitted on the markers' 10 mm grid, data
//! from a mesh 4× finer (made by the independent reference FEM) gave E 29 % low and ν 0.05 low.
//! The markers' displacements under a given force converge with the mesh (the probe marker's own
//! does not, so it is left out), which makes the fit mesh-independent to within the model's
//! discretisation error (the grid model is refined twice by default: E within 1 %).
//!
//! The fit eliminates $E$ (variable projection: for a given $\nu$ the best $a = 1/E$ is the
//! linear least-squares solution $a^*(\nu) = \sum (WG)\cdot(Wu^{meas}) / \sum (WG)\cdot(WG)$ with
//! $G = F_x V_x + F_y V_y$ and $W$ the whitening below), then minimises the weighted sum of
//! squares $S(\nu)$ over $\nu \in [0, 0.499]$ by a coarse scan and a golden-section search. Each
//! marker's displacements share the noise of its frame-0 position, so the $K$ displacement
//! residuals of one marker component are whitened with
//! $(I + \mathbf{1}\mathbf{1}^\top)^{-1/2} = I - c\,\mathbf{1}\mathbf{1}^\top$,
//! $c = (1 - 1/\sqrt{1+K})/K$. The marker noise $\sigma_u$, unless given, is estimated from the
//! residuals of a first fit and the fit repeated. Uncertainties:
//! $\operatorname{cov}(\log E, \nu) = s^2 (J^\top J)^{-1}$ with $J$ the Jacobian of the weighted
//! residuals and $s^2 = S/(m - 2)$, plus the load's share: the fit repeated with the force
//! line's slopes moved along each principal direction of their covariance by one standard
//! deviation, the changes of $(\log E, \nu)$ added as outer products (the lateral force of a
//! vertical probe is small and its slope the least certain: that share dominates ν's σ).

use anyhow::{Context, Result, bail};
use needlesim_core::num::num;
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
/// markers' lower-left reference position; the bottom row is fixed. The mesh is `refine` times
/// finer than the markers' grid (`refine` ≥ 1; the markers sit on every `refine`-th node).
///
/// Errors: the grid's node count differs from the marker count, `refine` is 0 or makes a mesh
/// beyond the mesh limits, a marker not on a grid node. The words name the grid, not how it was
/// given: the API's field `grid` and the CLI's flag `--grid` are each added by their caller.
pub fn grid_model(
    tracks: &MarkerTracks,
    nx: usize,
    ny: usize,
    width_m: f64,
    height_m: f64,
    plane: PlaneModel,
    refine: usize,
) -> Result<ProbeModel> {
    if nx.saturating_mul(ny) != tracks.n_markers {
        bail!("a grid of {nx} × {ny} markers has {} nodes but the tracks have {} markers", nx.saturating_mul(ny), tracks.n_markers);
    }
    if refine == 0 {
        bail!("refine = 0: the model mesh must be at least the markers' grid (refine ≥ 1)");
    }
    let p0: Vec<[f64; 2]> = (0..tracks.n_markers).map(|m| tracks.position_m(0, m)).collect();
    let origin = p0.iter().fold([f64::INFINITY; 2], |a, p| [a[0].min(p[0]), a[1].min(p[1])]);
    let (mx, my) = ((nx.saturating_sub(1)).saturating_mul(refine) + 1, (ny.saturating_sub(1)).saturating_mul(refine) + 1);
    let mut g = RectMeshParams::new(mx, my, width_m, height_m);
    g.origin_m = origin;
    let mesh = g.build(&MeshLimits::default()).with_context(|| format!("a grid of {nx} × {ny} markers refined {refine} times"))?;
    let tol = 0.25 * (width_m / (nx - 1) as f64).min(height_m / (ny - 1) as f64) / refine as f64;
    let marker_node = register_markers(&mesh, &p0, tol)?;
    let fixed_nodes = mesh.boundary_set("bottom").map(<[usize]>::to_vec).unwrap_or_default();
    Ok(ProbeModel { mesh, plane, fixed_nodes, marker_node })
}

/// The default refinement of a grid model: the mesh twice as fine as the markers' grid.
pub const DEFAULT_GRID_REFINE: usize = 2;

/// Fit options.
#[derive(Debug, Clone, Default)]
pub struct ProbeFitOptions {
    /// The marker the probe presses (default: the marker whose last displacement is nearest the
    /// probe's).
    pub probe_marker: Option<usize>,
    /// Marker position noise, m (default: estimated from the residuals).
    pub marker_sigma_m: Option<f64>,
    /// Force noise, N, as reported (default: the residual RMS of a straight-line fit of the logged
    /// force against the logged probe displacement). The fit itself does not weigh it: the force
    /// is the model's load.
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
    /// RMS of the force log's deviations from a straight-line fit against the probe
    /// displacement, N (the force noise seen in the log).
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
    /// Probe force at those frames relative to frame 0 (interpolated from the log).
    frame_force: Vec<[f64; 2]>,
    /// Free markers (not fixed, not the probe): (marker, node).
    free: Vec<(usize, usize)>,
}

/// The model's displacements under a unit probe force along x and along y, for one ν (E = 1).
struct Unit {
    v: [Vec<f64>; 2],
}

fn unit_solutions(model: &ProbeModel, probe_node: usize, nu: f64) -> Result<Unit> {
    let mats = MaterialMap::per_region(
        &model.mesh,
        &vec![Material { young_modulus_pa: 1.0, poisson_ratio: nu }; model.mesh.region_names().len()],
        model.plane,
    )
    .context("material")?;
    let conditions: Vec<(usize, NodeCondition)> =
        model.fixed_nodes.iter().filter(|&&n| n != probe_node).map(|&n| (n, NodeCondition::Fixed)).collect();
    let mut v: [Vec<f64>; 2] = Default::default();
    for (c, f) in [[1.0, 0.0], [0.0, 1.0]].into_iter().enumerate() {
        let problem = StaticProblem { conditions: conditions.clone(), loads_n: vec![(probe_node, f)], points: vec![], patches: vec![] };
        v[c] = problem.solve(&model.mesh, &mats).context("probe model solve")?.displacement_m;
    }
    Ok(Unit { v })
}

/// The whitened model pattern $WG$ and measurement $Wu^{meas}$ (unit E) for one ν.
fn whitened(tracks: &MarkerTracks, data: &Data, unit: &Unit) -> (Vec<f64>, Vec<f64>) {
    let mut g = Vec::with_capacity(data.frames.len() * data.free.len() * 2);
    let mut u = Vec::with_capacity(g.capacity());
    for (fi, &frame) in data.frames.iter().enumerate() {
        let f = data.frame_force[fi];
        for &(m, n) in &data.free {
            let meas = tracks.displacement_m(frame, m);
            for (c, mc) in meas.iter().enumerate() {
                g.push(f[0] * unit.v[0][2 * n + c] + f[1] * unit.v[1][2 * n + c]);
                u.push(*mc);
            }
        }
    }
    // Whitening: every displacement shares its marker's frame-0 noise, so the K residuals of one
    // marker component have covariance σ²(I + 11ᵀ); (I + 11ᵀ)^{-1/2} = I − c 11ᵀ with
    // c = (1 − 1/√(1+K))/K makes them independent with variance σ².
    let (k, stride) = (data.frames.len(), 2 * data.free.len());
    let c = (1.0 - 1.0 / (1.0 + k as f64).sqrt()) / k as f64;
    for v in [&mut g, &mut u] {
        for j in 0..stride {
            let sum: f64 = (0..k).map(|fi| v[fi * stride + j]).sum();
            for fi in 0..k {
                v[fi * stride + j] -= c * sum;
            }
        }
    }
    (g, u)
}

/// The (whitened) residuals $a\,WG - Wu^{meas}$ for ν with compliance scale `a` = 1/E, or the
/// best `a` for this ν when `None`; returns them with the `a` used.
fn residuals(tracks: &MarkerTracks, data: &Data, unit: &Unit, a_fixed: Option<f64>) -> (Vec<f64>, f64) {
    let (g, u) = whitened(tracks, data, unit);
    let a = a_fixed.unwrap_or_else(|| {
        let den = dot(&g, &g);
        if den > 0.0 { dot(&g, &u) / den } else { 0.0 }
    });
    (g.iter().zip(&u).map(|(g, u)| a * g - u).collect(), a)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn ss(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum()
}

/// The logged force as a straight line in the probe displacement, fitted by least squares over
/// the log samples `samples`: $F_c \approx b_c + a_{c,x} d_x + a_{c,y} d_y$ (an SVD solve: a probe
/// that moved along one line gets the minimum-norm line, exact along it).
struct ForceLine {
    /// `[[a_xx, a_xy], [a_yx, a_yy]]`.
    slope: [[f64; 2]; 2],
    /// Residual RMS over both components, N.
    rms_n: f64,
    /// One-standard-deviation perturbations of the slopes: the principal directions of each
    /// component's coefficient covariance $\sigma_c^2 (X^\top X)^{+}$, scaled by the square
    /// roots of its eigenvalues (their sum of outer products is the slopes' covariance).
    perturbations: Vec<[[f64; 2]; 2]>,
}

/// [`ForceLine`] of the log, or `None` when the probe displacement never changes (no line).
fn force_line(log: &ProbeLog, samples: &[usize]) -> Option<ForceLine> {
    use nalgebra::{DMatrix, Matrix3, SymmetricEigen};
    let n = samples.len();
    let first = log.disp_m[*samples.first()?];
    if n < 4 || samples.iter().all(|&k| log.disp_m[k] == first) {
        return None;
    }
    let x = DMatrix::from_fn(n, 3, |i, j| if j == 0 { 1.0 } else { log.disp_m[samples[i]][j - 1] - first[j - 1] });
    let f = DMatrix::from_fn(n, 2, |i, c| log.force_n[samples[i]][c]);
    let coef = x.clone().svd(true, true).solve(&f, 1e-12).ok()?;
    let resid = &x * &coef - &f;
    let rms_n = (resid.norm_squared() / (2 * n) as f64).sqrt();
    let xtx: Matrix3<f64> = Matrix3::from_fn(|i, j| x.column(i).dot(&x.column(j)));
    let pinv = xtx.pseudo_inverse(1e-12 * xtx.norm()).ok()?;
    let mut perturbations = Vec::new();
    for c in 0..2 {
        let var_c = resid.column(c).norm_squared() / n.saturating_sub(3).max(1) as f64;
        let eig = SymmetricEigen::new(pinv * var_c);
        for (k, &lambda) in eig.eigenvalues.iter().enumerate() {
            let v = eig.eigenvectors.column(k) * lambda.max(0.0).sqrt();
            if v[1] == 0.0 && v[2] == 0.0 {
                continue;
            }
            let mut d = [[0.0; 2]; 2];
            d[c] = [v[1], v[2]];
            perturbations.push(d);
        }
    }
    Some(ForceLine { slope: [[coef[(1, 0)], coef[(2, 0)]], [coef[(1, 1)], coef[(2, 1)]]], rms_n, perturbations })
}

/// The probe force at each frame from `slope` (relative to frame 0).
fn forces_from_slope(slope: &[[f64; 2]; 2], frame_disp: &[[f64; 2]]) -> Vec<[f64; 2]> {
    frame_disp.iter().map(|d| [0, 1].map(|c| slope[c][0] * d[0] + slope[c][1] * d[1])).collect()
}

/// The ν minimising the residuals for `data`: a coarse scan, then golden section on the bracket
/// around the best point.
fn best_nu(tracks: &MarkerTracks, data: &Data, eval: &mut dyn FnMut(f64) -> Result<Unit>) -> Result<f64> {
    let mut cost = |nu: f64| -> Result<f64> {
        let unit = eval(nu)?;
        Ok(ss(&residuals(tracks, data, &unit, None).0))
    };
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
    Ok(0.5 * (lo + hi))
}

/// Fits E and ν. `progress(done, total)` is called after every model evaluation (`total` is an
/// estimate; `Break` stops the fit with [`crate::Cancelled`]).
///
/// Errors (checked before any solve): fewer than 2 frames; a probe log that does not cover the
/// reference frame's time ("probe log covers t = a..b s but frames cover c..d s"); a probe marker
/// out of range; a model whose marker count differs from the tracks'; no free marker; no probe
/// force change at the frame times; displacements that do not follow the force (E* ≤ 0: check
/// the force's sign, the force the probe applies to the tissue).
pub fn fit_probe(
    tracks: &MarkerTracks,
    log: &ProbeLog,
    model: &ProbeModel,
    opts: &ProbeFitOptions,
    progress: crate::Progress<'_>,
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
            "probe log covers t = {}..{} s but frames cover {}..{} s (the log must cover the reference frame 0 and at least one more)",
            num(a),
            num(b),
            num(c),
            num(d)
        );
    }
    let frames: Vec<usize> = (1..nf).filter(|&k| tracks.times_s[k] <= b + eps).collect();
    if frames.is_empty() {
        bail!(
            "probe log covers t = {}..{} s but frames cover {}..{} s (the log must cover the reference frame 0 and at least one more)",
            num(a),
            num(b),
            num(c),
            num(d)
        );
    }
    let (d0, f0) = (interp(&log.times_s, &log.disp_m, c), interp(&log.times_s, &log.force_n, c));
    let rel = |x: [f64; 2], o: [f64; 2]| [x[0] - o[0], x[1] - o[1]];
    let frame_disp: Vec<[f64; 2]> = frames.iter().map(|&k| rel(interp(&log.times_s, &log.disp_m, tracks.times_s[k]), d0)).collect();
    let t_last = tracks.times_s[*frames.last().expect("non-empty")];
    let samples: Vec<usize> = (0..log.times_s.len()).filter(|&k| log.times_s[k] >= c - eps && log.times_s[k] <= t_last + eps).collect();
    // The probe force at each frame: from the force log's straight line in the probe
    // displacement (a linear tissue's force is one; it averages the force noise over every
    // sample), or, when the log has no probe displacement, interpolated in time.
    let line = force_line(log, &samples);
    let frame_force: Vec<[f64; 2]> = match &line {
        Some(l) => forces_from_slope(&l.slope, &frame_disp),
        None => frames.iter().map(|&k| rel(interp(&log.times_s, &log.force_n, tracks.times_s[k]), f0)).collect(),
    };
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
    if frame_force.iter().all(|f| f[0] == 0.0 && f[1] == 0.0) {
        bail!("the probe log shows no change of the probe force at the frame times: nothing to fit");
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
    let data = Data { frames, frame_force, free };
    let mut evals = 0usize;
    let total_est = 2 * 45 + 2;
    let mut eval = |nu: f64| -> Result<Unit> {
        let u = unit_solutions(model, probe_node, nu)?;
        evals += 1;
        crate::report(progress, evals, total_est)?;
        Ok(u)
    };
    let mut sigma_u = opts.marker_sigma_m.unwrap_or(0.0);
    let auto = opts.marker_sigma_m.is_none();
    if sigma_u <= 0.0 {
        // First pass weight: 0.1 % of the largest measured displacement (it cancels in the fit;
        // only the uncertainties use it).
        let umax = data.frames.iter().flat_map(|&f| data.free.iter().map(move |&(m, _)| (f, m))).fold(0.0f64, |acc, (f, m)| {
            let u = tracks.displacement_m(f, m);
            acc.max(u[0].hypot(u[1]))
        });
        sigma_u = 1e-3 * umax.max(1e-12);
    }
    // σ_u scales the cost and does not move the minimum: one pass.
    let nu_best = best_nu(tracks, &data, &mut eval)?;
    let unit = eval(nu_best)?;
    let (ru, a_best) = residuals(tracks, &data, &unit, None);
    if a_best.is_nan() || a_best <= 0.0 {
        bail!(
            "the markers do not move with the measured probe force (best compliance scale 1/E = {a_best:.3e} 1/Pa): check the force signs (the force the probe applies to the tissue)"
        );
    }
    let e = 1.0 / a_best;
    if auto {
        sigma_u = (ss(&ru) / ru.len() as f64).sqrt().max(1e-15);
    }
    // Jacobian of the weighted residuals in (log E, ν): ∂r/∂log E = −a WG / σ_u (since a = e^{−log E}),
    // ∂r/∂ν by central differences at fixed a.
    let h = 1e-4_f64.min(0.499 - nu_best).min(nu_best).max(1e-6);
    let (up, um) = (eval(nu_best + h)?, eval(nu_best - h)?);
    let (rup, _) = residuals(tracks, &data, &up, Some(a_best));
    let (rum, _) = residuals(tracks, &data, &um, Some(a_best));
    let (g, _) = whitened(tracks, &data, &unit);
    let m = ru.len();
    let (mut a11, mut a12, mut a22) = (0.0, 0.0, 0.0);
    for i in 0..m {
        let dl = -a_best * g[i] / sigma_u;
        let dn = (rup[i] - rum[i]) / (2.0 * h) / sigma_u;
        a11 += dl * dl;
        a12 += dl * dn;
        a22 += dn * dn;
    }
    let s_cost = ss(&ru) / (sigma_u * sigma_u);
    let s2 = s_cost / (m.saturating_sub(2).max(1)) as f64;
    let det = a11 * a22 - a12 * a12;
    let (mut var_log_e, mut var_nu) = if det > 0.0 { (s2 * a22 / det, s2 * a11 / det) } else { (f64::INFINITY, f64::INFINITY) };
    // The load's own uncertainty: the fit repeated with the force line's slopes moved by each of
    // their one-σ principal perturbations; the changes of (log E, ν) add their outer products.
    if let Some(l) = &line {
        for dp in &l.perturbations {
            let slope = [0, 1].map(|c| [0, 1].map(|j| l.slope[c][j] + dp[c][j]));
            let moved = Data { frames: data.frames.clone(), frame_force: forces_from_slope(&slope, &frame_disp), free: data.free.clone() };
            let nu = best_nu(tracks, &moved, &mut eval)?;
            let (_, a) = residuals(tracks, &moved, &eval(nu)?, None);
            if a > 0.0 {
                var_log_e += (a_best / a).ln().powi(2);
                var_nu += (nu - nu_best).powi(2);
            }
        }
    }
    let force_rms_n = line.as_ref().map_or(0.0, |l| l.rms_n);
    Ok(ProbeFit {
        young_modulus_pa: e,
        young_modulus_sigma_pa: e * var_log_e.sqrt(),
        poisson_ratio: nu_best,
        poisson_ratio_sigma: var_nu.sqrt(),
        displacement_rms_m: (ss(&ru) / m.max(1) as f64).sqrt(),
        force_rms_n,
        weighted_rms: (s_cost / m.max(1) as f64).sqrt(),
        marker_sigma_m: sigma_u,
        force_sigma_n: opts.force_sigma_n.unwrap_or(force_rms_n),
        probe_marker,
        n_frames_used: data.frames.len(),
        n_force_samples: samples.len(),
        n_residuals: m,
        iterations: evals,
    })
}

#[cfg(all(test, feature = "synthetic"))]
mod tests {
    use super::*;
    use crate::experiment::{ProbeSynthParams, synth_probe};

    #[test]
    fn recovers_e_and_nu_from_noisy_probing() {
        let p = ProbeSynthParams::default();
        let ex = synth_probe(&p).unwrap();
        let model = grid_model(&ex.tracks, p.nx, p.ny, p.width_m, p.height_m, p.plane, 1).unwrap();
        let fit = fit_probe(&ex.tracks, &ex.log, &model, &ProbeFitOptions::default(), &mut crate::no_progress).unwrap();
        assert_eq!(fit.probe_marker, ex.probe_marker);
        let e_err = (fit.young_modulus_pa / 30e3 - 1.0).abs();
        assert!(e_err < 0.02, "E = {} ± {}", fit.young_modulus_pa, fit.young_modulus_sigma_pa);
        assert!((fit.poisson_ratio - 0.45).abs() < 0.02, "ν = {} ± {}", fit.poisson_ratio, fit.poisson_ratio_sigma);
        assert!(fit.young_modulus_sigma_pa > 0.0 && fit.poisson_ratio_sigma > 0.0);
    }

    /// Issue 35: Identify's API (field `grid`) quoted the CLI's flag ("grid: --grid 10,11 has …").
    #[test]
    fn issue_35_grid_errors_name_the_grid_not_the_cli_flag() {
        let p = ProbeSynthParams::default();
        let ex = synth_probe(&p).unwrap();
        let e = grid_model(&ex.tracks, 10, 11, 0.1, 0.1, p.plane, 1).unwrap_err();
        assert_eq!(format!("{e:#}"), "a grid of 10 × 11 markers has 110 nodes but the tracks have 121 markers");
        let e = grid_model(&ex.tracks, 11, 11, 0.1, 0.1, p.plane, 100_000).unwrap_err();
        let m = format!("{e:#}");
        assert!(m.starts_with("a grid of 11 × 11 markers refined 100000 times: ") && !m.contains("--"), "{m}");
    }

    #[test]
    fn inconsistent_inputs_are_errors() {
        let p = ProbeSynthParams::default();
        let ex = synth_probe(&p).unwrap();
        let model = grid_model(&ex.tracks, p.nx, p.ny, p.width_m, p.height_m, p.plane, 1).unwrap();
        let mut late = ex.log.clone();
        for t in &mut late.times_s {
            *t += 100.0;
        }
        let e = fit_probe(&ex.tracks, &late, &model, &ProbeFitOptions::default(), &mut crate::no_progress).unwrap_err().to_string();
        assert!(e.contains("probe log covers t = 100..102.5 s but frames cover 0..2.5 s"), "{e}");
        let e = grid_model(&ex.tracks, 10, 11, 0.1, 0.1, p.plane, 1).unwrap_err().to_string();
        assert!(e.contains("110 nodes but the tracks have 121 markers"), "{e}");
        let small = RectMeshParams::new(11, 11, 0.05, 0.1).build(&MeshLimits::default()).unwrap();
        let p0: Vec<[f64; 2]> = (0..ex.tracks.n_markers).map(|m| ex.tracks.position_m(0, m)).collect();
        let e = register_markers(&small, &p0, 1e-3).unwrap_err().to_string();
        assert!(e.contains("mesh does not cover marker 6 at (0.0"), "{e}");
    }
}
