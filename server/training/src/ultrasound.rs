//! A simulated B-mode ultrasound slice (pure): the deformed tissue in the probe's image plane →
//! an 8-bit gray image; a 2D triangle mesh ([`render_slice`]: the slice is the tissue plane) or
//! a 3D tetrahedral mesh cut by a movable probe plane ([`render_slice_3d`]).
//!
//! **Geometry.** The image has `width × height` pixels of `pixel_m`; pixel $(i, j)$'s centre is
//! $o + (i + \frac12) p\, e_u + (j + \frac12) p\, e_v$ ($o$ the probe's corner, $e_u$ lateral,
//! $e_v$ the beam's depth direction). Each deformed triangle (nodes $x_a = X_a + u_a$) is
//! rasterised: a pixel inside it with barycentric weights $\lambda$ (of the deformed triangle)
//! sits at the material point $X = \sum_a \lambda_a X_a$ of region $r$ — exact for linear
//! elements, whose map $X \mapsto X + u$ is affine per triangle.
//!
//! **Echo.** Speckle is a function of the material point, so it moves with the tissue:
//! value noise on a lattice of `speckle_m` cells in reference coordinates, $s(X) \in [0, 1)$
//! (a hash of the lattice corners, bilinear in between), times the region's echogenicity $g_r$.
//! A pixel whose 4-neighbour lies in another region (or outside) is an interface: $+0.5$.
//! Inside a target (material distance $|X - C| < R$ from its reference centre) the echo is
//! scaled by 0.25 (hypoechoic, moving with the tissue). The needle (a segment, world) is a
//! bright line (pixels within `needle_halfwidth_px` of it: 1.0), and every pixel deeper along
//! $e_v$ than the needle in its column is in its acoustic shadow: $\times 0.3$. The image is
//! $\min(1, \cdot) \times 255$, 0 outside the tissue.
//!
//! Cost: $O(\text{triangles} + \text{pixels})$ per image (the triangles' pixel boxes), no
//! allocation beyond the image and two per-pixel buffers ([`UltrasoundScratch`]), for the
//! observers' side of a session (never the real-time thread).
//!
//! **The deformed 3D tissue.** A 3D session computes no interior displacement field; its tick
//! record carries the contact points (reference position $X_i$, force $f_i$ of the needle on the
//! tissue). [`DeformedTissue3::solve`] turns them into every node's displacement by one sparse
//! solve with the tissue's factorisation,
//! $$u = K_{ff}^{-1} \sum_i \sum_a N_a(X_i)\, e_{k_a} \otimes f_i$$
//! ([`TetTissueModel::displacement_for_point_loads_into`]; linear elasticity, the same $u$ the
//! simulation's point compliance gives at the contacts), which [`render_slice_3d`] draws. Cost
//! $O(\mathrm{nnz}(L))$ per tick, however many contacts — memory-bound, tens of milliseconds on
//! the 48,000-tetrahedron cube (nnz(L) = 16.6 M; the `slice_cost` timing below, BENCHMARKS.md).

use needlesim_core::d3::{PointLocation, TetColumnScratch, TetTissueError, TetTissueModel};

/// The probe's image plane and resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// The image's corner (pixel (0, 0)'s outer corner), world, m.
    pub origin_m: [f64; 2],
    /// Lateral unit vector (image columns).
    pub e_u: [f64; 2],
    /// Depth unit vector (image rows, the beam direction).
    pub e_v: [f64; 2],
    pub pixel_m: f64,
    pub width: usize,
    pub height: usize,
}

/// What the slice shows besides the tissue.
#[derive(Debug, Clone, PartialEq)]
pub struct SliceScene<'a> {
    /// Echogenicity per region (indexes the triangles' regions), about 0.3–1.
    pub region_gain: &'a [f64],
    /// Targets: reference centre, radius (m).
    pub targets: &'a [([f64; 2], f64)],
    /// The needle's inserted segment, world (base side, tip), if any.
    pub needle_m: Option<([f64; 2], [f64; 2])>,
    pub needle_halfwidth_px: f64,
    /// Speckle lattice cell, m (about the wavelength: 0.2–0.5 mm).
    pub speckle_m: f64,
    pub seed: u64,
}

/// An 8-bit gray image, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct GrayImage8 {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<u8>,
}

/// Per-pixel buffers, reusable between images.
#[derive(Debug, Default)]
pub struct UltrasoundScratch {
    value: Vec<f32>,
    region: Vec<i32>,
}

fn hash(ix: i64, iy: i64, seed: u64) -> f64 {
    let mut z = seed ^ (ix as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (iy as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The speckle $s(X)$ (module docs).
pub fn speckle(x_ref: [f64; 2], cell_m: f64, seed: u64) -> f64 {
    let (fx, fy) = (x_ref[0] / cell_m, x_ref[1] / cell_m);
    let (ix, iy) = (fx.floor(), fy.floor());
    let (tx, ty) = (fx - ix, fy - iy);
    let (ix, iy) = (ix as i64, iy as i64);
    let a = hash(ix, iy, seed) * (1.0 - tx) + hash(ix + 1, iy, seed) * tx;
    let b = hash(ix, iy + 1, seed) * (1.0 - tx) + hash(ix + 1, iy + 1, seed) * tx;
    a * (1.0 - ty) + b * ty
}

/// Renders the slice (module docs). `nodes_ref_m`, `u_m`: reference positions and
/// displacements per node; `triangles` with `regions` per triangle. Triangles naming a node out
/// of range are skipped.
pub fn render_slice(
    nodes_ref_m: &[[f64; 2]],
    u_m: &[[f64; 2]],
    triangles: &[[usize; 3]],
    regions: &[usize],
    scene: &SliceScene<'_>,
    probe: &Probe,
    scratch: &mut UltrasoundScratch,
) -> GrayImage8 {
    let (w, h) = (probe.width, probe.height);
    let n = w * h;
    scratch.value.clear();
    scratch.value.resize(n, 0.0);
    scratch.region.clear();
    scratch.region.resize(n, -1);
    let to_px = |q: [f64; 2]| {
        let d = [q[0] - probe.origin_m[0], q[1] - probe.origin_m[1]];
        (
            (d[0] * probe.e_u[0] + d[1] * probe.e_u[1]) / probe.pixel_m - 0.5,
            (d[0] * probe.e_v[0] + d[1] * probe.e_v[1]) / probe.pixel_m - 0.5,
        )
    };
    for (t, tri) in triangles.iter().enumerate() {
        if tri.iter().any(|&a| a >= nodes_ref_m.len() || a >= u_m.len()) {
            continue;
        }
        let p: [(f64, f64); 3] = std::array::from_fn(|k| {
            let a = tri[k];
            to_px([nodes_ref_m[a][0] + u_m[a][0], nodes_ref_m[a][1] + u_m[a][1]])
        });
        let det = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        if det.abs() < 1e-12 {
            continue;
        }
        let (x0, x1) = (p.iter().map(|q| q.0).fold(f64::INFINITY, f64::min), p.iter().map(|q| q.0).fold(f64::NEG_INFINITY, f64::max));
        let (y0, y1) = (p.iter().map(|q| q.1).fold(f64::INFINITY, f64::min), p.iter().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max));
        let (i0, i1) = (x0.ceil().max(0.0) as usize, (x1.floor().min(w as f64 - 1.0)).max(-1.0));
        let (j0, j1) = (y0.ceil().max(0.0) as usize, (y1.floor().min(h as f64 - 1.0)).max(-1.0));
        if i1 < 0.0 || j1 < 0.0 {
            continue;
        }
        let region = regions.get(t).copied().unwrap_or(0);
        let gain = scene.region_gain.get(region).copied().unwrap_or(0.6);
        for j in j0..=j1 as usize {
            for i in i0..=i1 as usize {
                let (x, y) = (i as f64, j as f64);
                let l1 = ((x - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (y - p[0].1)) / det;
                let l2 = ((p[1].0 - p[0].0) * (y - p[0].1) - (x - p[0].0) * (p[1].1 - p[0].1)) / det;
                let l0 = 1.0 - l1 - l2;
                if l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12 {
                    continue;
                }
                let (a, b, c) = (nodes_ref_m[tri[0]], nodes_ref_m[tri[1]], nodes_ref_m[tri[2]]);
                let xr = [l0 * a[0] + l1 * b[0] + l2 * c[0], l0 * a[1] + l1 * b[1] + l2 * c[1]];
                let mut v = speckle(xr, scene.speckle_m, scene.seed) * gain;
                if scene.targets.iter().any(|(cen, r)| (xr[0] - cen[0]).powi(2) + (xr[1] - cen[1]).powi(2) < r * r) {
                    v *= 0.25;
                }
                scratch.value[j * w + i] = v as f32;
                scratch.region[j * w + i] = region as i32;
            }
        }
    }
    let needle_px = scene.needle_m.map(|(a, b)| (to_px(a), to_px(b)));
    shade(w, h, needle_px, scene.needle_halfwidth_px, scratch)
}

/// The shared second pass (module docs): interfaces, the needle (a segment in pixel
/// coordinates) and its shadow, quantisation.
fn shade(w: usize, h: usize, needle_px: Option<((f64, f64), (f64, f64))>, halfwidth_px: f64, scratch: &UltrasoundScratch) -> GrayImage8 {
    let n = w * h;
    let mut out = vec![0u8; n];
    for j in 0..h {
        for i in 0..w {
            let k = j * w + i;
            let r = scratch.region[k];
            if r < 0 {
                continue;
            }
            let mut v = scratch.value[k];
            let other = |ii: isize, jj: isize| {
                if ii < 0 || jj < 0 || ii >= w as isize || jj >= h as isize {
                    return false;
                }
                scratch.region[jj as usize * w + ii as usize] != r
            };
            let (ii, jj) = (i as isize, j as isize);
            if other(ii - 1, jj) || other(ii + 1, jj) || other(ii, jj - 1) || other(ii, jj + 1) {
                v += 0.5;
            }
            out[k] = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        }
    }
    if let Some((pa, pb)) = needle_px {
        let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
        let len2 = dx * dx + dy * dy;
        // Per column, the shallowest needle pixel: deeper pixels are in its shadow.
        for i in 0..w {
            let mut top: Option<usize> = None;
            for j in 0..h {
                let (x, y) = (i as f64, j as f64);
                let s = if len2 > 0.0 { (((x - pa.0) * dx + (y - pa.1) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let d = ((x - pa.0 - s * dx).powi(2) + (y - pa.1 - s * dy).powi(2)).sqrt();
                if d <= halfwidth_px {
                    out[j * w + i] = 255;
                    top.get_or_insert(j);
                } else if top.is_some() && scratch.region[j * w + i] >= 0 {
                    out[j * w + i] = (out[j * w + i] as f32 * 0.3).round() as u8;
                }
            }
        }
    }
    GrayImage8 { width: w, height: h, pixels: out }
}

/// A probe plane in 3D: the image plane through `origin_m` spanned by the orthonormal `e_u`
/// (lateral) and `e_v` (depth); the needle is drawn where it lies within `thickness_m / 2` of
/// the plane (the beam's elevation thickness).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe3 {
    pub origin_m: [f64; 3],
    pub e_u: [f64; 3],
    pub e_v: [f64; 3],
    pub pixel_m: f64,
    pub width: usize,
    pub height: usize,
    pub thickness_m: f64,
}

/// What a 3D slice shows besides the tissue ([`SliceScene`] in 3D).
#[derive(Debug, Clone, PartialEq)]
pub struct SliceScene3<'a> {
    pub region_gain: &'a [f64],
    /// Targets: reference centre, radius (m).
    pub targets: &'a [([f64; 3], f64)],
    /// The needle's inserted segment, world (base side, tip), if any.
    pub needle_m: Option<([f64; 3], [f64; 3])>,
    pub needle_halfwidth_px: f64,
    pub speckle_m: f64,
    pub seed: u64,
}

fn hash3(ix: i64, iy: i64, iz: i64, seed: u64) -> f64 {
    hash(ix, iy ^ iz.wrapping_mul(0x2545_F491_4F6C_DD1D), seed ^ 0x5851_F42D_4C95_7F2D)
}

/// The 3D speckle: trilinear value noise on `cell_m` cells of the reference coordinates.
pub fn speckle3(x_ref: [f64; 3], cell_m: f64, seed: u64) -> f64 {
    let f = [x_ref[0] / cell_m, x_ref[1] / cell_m, x_ref[2] / cell_m];
    let i = [f[0].floor(), f[1].floor(), f[2].floor()];
    let t = [f[0] - i[0], f[1] - i[1], f[2] - i[2]];
    let i = [i[0] as i64, i[1] as i64, i[2] as i64];
    let mut v = 0.0;
    for c in 0..8 {
        let (dx, dy, dz) = (c & 1, (c >> 1) & 1, (c >> 2) & 1);
        let w = (if dx == 1 { t[0] } else { 1.0 - t[0] })
            * (if dy == 1 { t[1] } else { 1.0 - t[1] })
            * (if dz == 1 { t[2] } else { 1.0 - t[2] });
        v += w * hash3(i[0] + dx as i64, i[1] + dy as i64, i[2] + dz as i64, seed);
    }
    v
}

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Renders the slice of a deformed tetrahedral mesh in the probe plane (module docs; each
/// deformed tetrahedron the plane crosses is sampled at the pixels of its projected box,
/// barycentric weights of the deformed tetrahedron giving the material point).
pub fn render_slice_3d(
    nodes_ref_m: &[[f64; 3]],
    u_m: &[[f64; 3]],
    tets: &[[usize; 4]],
    regions: &[usize],
    scene: &SliceScene3<'_>,
    probe: &Probe3,
    scratch: &mut UltrasoundScratch,
) -> GrayImage8 {
    let (w, h) = (probe.width, probe.height);
    scratch.value.clear();
    scratch.value.resize(w * h, 0.0);
    scratch.region.clear();
    scratch.region.resize(w * h, -1);
    let normal = cross3(probe.e_u, probe.e_v);
    let to_px = |q: [f64; 3]| {
        let d = sub3(q, probe.origin_m);
        (dot3(d, probe.e_u) / probe.pixel_m - 0.5, dot3(d, probe.e_v) / probe.pixel_m - 0.5)
    };
    for (t, tet) in tets.iter().enumerate() {
        if tet.iter().any(|&a| a >= nodes_ref_m.len() || a >= u_m.len()) {
            continue;
        }
        let y: [[f64; 3]; 4] = std::array::from_fn(|k| {
            let a = tet[k];
            [nodes_ref_m[a][0] + u_m[a][0], nodes_ref_m[a][1] + u_m[a][1], nodes_ref_m[a][2] + u_m[a][2]]
        });
        let d: [f64; 4] = std::array::from_fn(|k| dot3(sub3(y[k], probe.origin_m), normal));
        if d.iter().all(|&x| x > 0.0) || d.iter().all(|&x| x < 0.0) {
            continue;
        }
        // Barycentric weights: [l1, l2, l3] = M^{-1} (q - y0), M = [y1-y0, y2-y0, y3-y0] by columns.
        let (c1, c2, c3) = (sub3(y[1], y[0]), sub3(y[2], y[0]), sub3(y[3], y[0]));
        let det = dot3(c1, cross3(c2, c3));
        if det.abs() < 1e-18 {
            continue;
        }
        let rows = [cross3(c2, c3), cross3(c3, c1), cross3(c1, c2)];
        let px: [(f64, f64); 4] = std::array::from_fn(|k| to_px(y[k]));
        let (x0, x1) = px.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.0), a.1.max(p.0)));
        let (y0, y1) = px.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.1), a.1.max(p.1)));
        if x1 < 0.0 || y1 < 0.0 || x0 > w as f64 - 1.0 || y0 > h as f64 - 1.0 {
            continue;
        }
        let (i0, i1) = (x0.ceil().max(0.0) as usize, x1.floor().min(w as f64 - 1.0) as usize);
        let (j0, j1) = (y0.ceil().max(0.0) as usize, y1.floor().min(h as f64 - 1.0) as usize);
        let region = regions.get(t).copied().unwrap_or(0);
        let gain = scene.region_gain.get(region).copied().unwrap_or(0.6);
        let xr: [[f64; 3]; 4] = std::array::from_fn(|k| nodes_ref_m[tet[k]]);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let (a, b) = ((i as f64 + 0.5) * probe.pixel_m, (j as f64 + 0.5) * probe.pixel_m);
                let q = [
                    probe.origin_m[0] + a * probe.e_u[0] + b * probe.e_v[0],
                    probe.origin_m[1] + a * probe.e_u[1] + b * probe.e_v[1],
                    probe.origin_m[2] + a * probe.e_u[2] + b * probe.e_v[2],
                ];
                let r = sub3(q, y[0]);
                let l = [dot3(rows[0], r) / det, dot3(rows[1], r) / det, dot3(rows[2], r) / det];
                let l0 = 1.0 - l[0] - l[1] - l[2];
                if l0 < -1e-12 || l.iter().any(|&x| x < -1e-12) {
                    continue;
                }
                let lam = [l0, l[0], l[1], l[2]];
                let x: [f64; 3] = std::array::from_fn(|c| (0..4).map(|k| lam[k] * xr[k][c]).sum());
                let mut v = speckle3(x, scene.speckle_m, scene.seed) * gain;
                if scene.targets.iter().any(|(cen, rad)| dot3(sub3(x, *cen), sub3(x, *cen)) < rad * rad) {
                    v *= 0.25;
                }
                scratch.value[j * w + i] = v as f32;
                scratch.region[j * w + i] = region as i32;
            }
        }
    }
    // The needle where it lies within half the thickness of the plane: clip, then project.
    let needle_px = scene.needle_m.and_then(|(a, b)| {
        let (da, db) = (dot3(sub3(a, probe.origin_m), normal), dot3(sub3(b, probe.origin_m), normal));
        let half = 0.5 * probe.thickness_m;
        let (mut s0, mut s1) = (0.0f64, 1.0f64);
        let dd = db - da;
        if dd.abs() < 1e-15 {
            if da.abs() > half {
                return None;
            }
        } else {
            let (ta, tb) = ((-half - da) / dd, (half - da) / dd);
            s0 = s0.max(ta.min(tb));
            s1 = s1.min(ta.max(tb));
            if s0 > s1 {
                return None;
            }
        }
        let at = |s: f64| [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])];
        Some((to_px(at(s0)), to_px(at(s1))))
    });
    shade(w, h, needle_px, scene.needle_halfwidth_px, scratch)
}

/// Every node's displacement of a 3D tissue at one tick from its contact points (module docs):
/// buffers sized once for a model, reused tick after tick (no allocation once the contacts fit).
pub struct DeformedTissue3 {
    locations: Vec<PointLocation>,
    forces_n: Vec<[f64; 3]>,
    scratch: TetColumnScratch,
    u_m: Vec<[f64; 3]>,
    n_outside: usize,
}

impl DeformedTissue3 {
    /// Buffers for `model` (its solve scratch, one displacement per node, room for 64 contacts).
    pub fn new(model: &TetTissueModel) -> Self {
        Self {
            locations: Vec::with_capacity(64),
            forces_n: Vec::with_capacity(64),
            scratch: model.column_scratch(),
            u_m: vec![[0.0; 3]; model.mesh().n_nodes()],
            n_outside: 0,
        }
    }

    /// Solves for the displacement of every node of `model` (which these buffers were made for)
    /// under the tick's contacts, `(x_ref_m, force_n)`: the reference position of each contact
    /// point and the force of the needle on the tissue there (world, m and N). A contact whose
    /// reference position lies outside the mesh is left out (counted: [`Self::n_outside`]).
    /// No contacts: $u = 0$, without a solve.
    ///
    /// Errors ([`TetTissueModel::displacement_for_point_loads_into`]'s; the displacement is then
    /// zero): a non-finite force ([`TetTissueError::NonFiniteForce`], its `point_idx` counting
    /// the contacts inside the mesh), and
    /// [`TetTissueError::OutputLength`] when `model` is not the one these buffers were made for.
    pub fn solve(
        &mut self,
        model: &TetTissueModel,
        contacts: impl IntoIterator<Item = ([f64; 3], [f64; 3])>,
    ) -> Result<&[[f64; 3]], TetTissueError> {
        self.locations.clear();
        self.forces_n.clear();
        self.n_outside = 0;
        for (x_ref_m, force_n) in contacts {
            match model.locate(x_ref_m) {
                Ok(loc) => {
                    self.locations.push(loc);
                    self.forces_n.push(force_n);
                }
                Err(_) => self.n_outside += 1,
            }
        }
        self.solve_located(model)
    }

    /// The solve of [`Self::solve`] for the located contacts. Not generic and never inlined, so
    /// that the tissue's solve is compiled here, optimised, whichever crate calls `solve`
    /// (Cargo.toml: needlesim-core's generic code is compiled where it is instantiated).
    #[inline(never)]
    fn solve_located(&mut self, model: &TetTissueModel) -> Result<&[[f64; 3]], TetTissueError> {
        if self.locations.is_empty() {
            self.u_m.fill([0.0; 3]);
            return Ok(&self.u_m);
        }
        let solved =
            model.displacement_for_point_loads_into(&self.locations, &self.forces_n, self.u_m.as_flattened_mut(), &mut self.scratch);
        if let Err(e) = solved {
            self.u_m.fill([0.0; 3]);
            return Err(e);
        }
        Ok(&self.u_m)
    }

    /// The last displacement solved, per node, m.
    pub fn displacement_m(&self) -> &[[f64; 3]] {
        &self.u_m
    }

    /// How many contacts of the last [`Self::solve`] lay outside the mesh.
    pub fn n_outside(&self) -> usize {
        self.n_outside
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A structured grid of `nx × ny` cells over `[0, w] × [0, h]`, two regions split at mid-height.
    fn grid(nx: usize, ny: usize, w: f64, h: f64) -> (Vec<[f64; 2]>, Vec<[usize; 3]>, Vec<usize>) {
        let mut nodes = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                nodes.push([w * i as f64 / nx as f64, h * j as f64 / ny as f64]);
            }
        }
        let (mut tris, mut regions) = (Vec::new(), Vec::new());
        for j in 0..ny {
            for i in 0..nx {
                let a = j * (nx + 1) + i;
                let r = usize::from(j >= ny / 2);
                tris.push([a, a + 1, a + nx + 2]);
                tris.push([a, a + nx + 2, a + nx + 1]);
                regions.extend([r, r]);
            }
        }
        (nodes, tris, regions)
    }

    fn probe() -> Probe {
        // 0.1 mm pixels over the middle of a 40 × 30 mm block, depth downwards (−y).
        Probe { origin_m: [0.005, 0.025], e_u: [1.0, 0.0], e_v: [0.0, -1.0], pixel_m: 1e-4, width: 160, height: 160 }
    }

    /// The shift within ±`reach` px (10 px margin) at which `b` correlates best with `a`:
    /// (the correlation, dx, dy).
    fn ncc_peak(a: &[u8], b: &[u8], w: usize, h: usize, reach: isize) -> (f64, isize, isize) {
        let mut best = (f64::NEG_INFINITY, 0, 0);
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let c = ncc(a, b, w, h, dx, dy, 10);
                if c > best.0 {
                    best = (c, dx, dy);
                }
            }
        }
        best
    }

    fn ncc(a: &[u8], b: &[u8], w: usize, h: usize, dx: isize, dy: isize, margin: usize) -> f64 {
        let (mut sa, mut sb, mut sab, mut saa, mut sbb, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for j in margin..h - margin {
            for i in margin..w - margin {
                let x = a[j * w + i] as f64;
                let y = b[(j as isize + dy) as usize * w + (i as isize + dx) as usize] as f64;
                sa += x;
                sb += y;
                sab += x * y;
                saa += x * x;
                sbb += y * y;
                n += 1.0;
            }
        }
        let cov = sab / n - sa * sb / (n * n);
        cov / ((saa / n - (sa / n).powi(2)) * (sbb / n - (sb / n).powi(2))).sqrt()
    }

    #[test]
    fn speckle_follows_an_imposed_displacement_within_a_pixel() {
        let (nodes, tris, regions) = grid(40, 30, 0.04, 0.03);
        let scene =
            SliceScene { region_gain: &[0.8, 0.8], targets: &[], needle_m: None, needle_halfwidth_px: 1.0, speckle_m: 3e-4, seed: 7 };
        let p = probe();
        let mut scratch = UltrasoundScratch::default();
        let still = render_slice(&nodes, &vec![[0.0; 2]; nodes.len()], &tris, &regions, &scene, &p, &mut scratch);
        for shift_px in [[2.4, -1.7], [-3.6, 0.8], [0.3, 4.2]] {
            // World shift: lateral +x, depth −y.
            let u = [shift_px[0] * p.pixel_m, -shift_px[1] * p.pixel_m];
            let moved = render_slice(&nodes, &vec![u; nodes.len()], &tris, &regions, &scene, &p, &mut scratch);
            let best = ncc_peak(&still.pixels, &moved.pixels, p.width, p.height, 6);
            assert!(
                (best.1 as f64 - shift_px[0]).abs() <= 1.0 && (best.2 as f64 - shift_px[1]).abs() <= 1.0,
                "imposed {shift_px:?} px, correlation peak at ({}, {}) (r = {:.3})",
                best.1,
                best.2,
                best.0
            );
            assert!(best.0 > 0.5, "the peak correlation {:.3} is weak", best.0);
        }
    }

    #[test]
    fn needle_is_bright_with_a_shadow_target_darker_interface_brighter() {
        let (nodes, tris, regions) = grid(40, 30, 0.04, 0.03);
        let p = probe();
        let u = vec![[0.0; 2]; nodes.len()];
        let mut scratch = UltrasoundScratch::default();
        let base =
            SliceScene { region_gain: &[0.7, 0.7], targets: &[], needle_m: None, needle_halfwidth_px: 1.0, speckle_m: 3e-4, seed: 3 };
        let plain = render_slice(&nodes, &u, &tris, &regions, &base, &p, &mut scratch);
        // A horizontal needle at y = 20 mm (row 49.5) over columns 0..80.
        let with = SliceScene { needle_m: Some(([0.005, 0.02], [0.013, 0.02])), ..base.clone() };
        let img = render_slice(&nodes, &u, &tris, &regions, &with, &p, &mut scratch);
        let mean = |im: &GrayImage8, cols: std::ops::Range<usize>, rows: std::ops::Range<usize>| {
            let mut s = 0.0;
            let mut n = 0.0;
            for j in rows.clone() {
                for i in cols.clone() {
                    s += im.pixels[j * im.width + i] as f64;
                    n += 1.0;
                }
            }
            s / n
        };
        assert_eq!(img.pixels[50 * p.width + 40], 255, "the needle line");
        assert!(mean(&img, 10..70, 60..70) < 0.4 * mean(&plain, 10..70, 60..70), "the shadow below the needle");
        // A target of radius 2 mm at (12, 15) mm.
        let with = SliceScene { targets: &[([0.012, 0.015], 0.002)], ..base.clone() };
        let img = render_slice(&nodes, &u, &tris, &regions, &with, &p, &mut scratch);
        // (12, 15) mm: column 70, row 100.
        assert!(mean(&img, 62..78, 92..108) < 0.4 * mean(&plain, 62..78, 92..108), "the target is darker");
        // The interface between the regions at y = 15 mm (row 100): brighter than the rows around it.
        let two = SliceScene { region_gain: &[0.5, 0.5], ..base.clone() };
        let img = render_slice(&nodes, &u, &tris, &regions, &two, &p, &mut scratch);
        assert!(mean(&img, 0..160, 99..101) > mean(&img, 0..160, 80..90) + 60.0, "the interface");
    }

    /// A box of `n³` cubes of side `a`, 6 Kuhn tetrahedra each (sharing the cube diagonal).
    fn cube(n: usize, a: f64) -> (Vec<[f64; 3]>, Vec<[usize; 4]>) {
        let id = |i: usize, j: usize, k: usize| (k * (n + 1) + j) * (n + 1) + i;
        let mut nodes = Vec::new();
        for k in 0..=n {
            for j in 0..=n {
                for i in 0..=n {
                    nodes.push([i as f64 * a, j as f64 * a, k as f64 * a]);
                }
            }
        }
        let mut tets = Vec::new();
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let v = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                    for p in [[1, 3], [1, 5], [2, 3], [2, 6], [4, 5], [4, 6]] {
                        tets.push([v(0), v(p[0]), v(p[1]), v(7)]);
                    }
                }
            }
        }
        (nodes, tets)
    }

    #[test]
    fn speckle_3d_follows_an_in_plane_displacement_within_a_pixel() {
        let (nodes, tets) = cube(12, 0.002);
        let regions = vec![0; tets.len()];
        // The plane z = 11.3 mm, lateral +x, depth +y, 0.1 mm pixels over the middle.
        let p = Probe3 {
            origin_m: [0.004, 0.004, 0.0113],
            e_u: [1.0, 0.0, 0.0],
            e_v: [0.0, 1.0, 0.0],
            pixel_m: 1e-4,
            width: 160,
            height: 160,
            thickness_m: 1e-3,
        };
        let scene = SliceScene3 { region_gain: &[0.8], targets: &[], needle_m: None, needle_halfwidth_px: 1.0, speckle_m: 3e-4, seed: 11 };
        let mut scratch = UltrasoundScratch::default();
        let still = render_slice_3d(&nodes, &vec![[0.0; 3]; nodes.len()], &tets, &regions, &scene, &p, &mut scratch);
        assert!(still.pixels.iter().all(|&v| v > 0), "the plane lies inside the box: every pixel is tissue");
        for shift_px in [[2.4, -1.7], [-3.6, 0.8]] {
            let u = [shift_px[0] * p.pixel_m, shift_px[1] * p.pixel_m, 0.0];
            let moved = render_slice_3d(&nodes, &vec![u; nodes.len()], &tets, &regions, &scene, &p, &mut scratch);
            let best = ncc_peak(&still.pixels, &moved.pixels, p.width, p.height, 6);
            assert!(
                (best.1 as f64 - shift_px[0]).abs() <= 1.0 && (best.2 as f64 - shift_px[1]).abs() <= 1.0 && best.0 > 0.5,
                "imposed {shift_px:?} px, peak at ({}, {}) r = {:.3}",
                best.1,
                best.2,
                best.0
            );
        }
        // A needle in the plane is drawn; one 1 mm out of it (beyond half the 1 mm thickness) is not.
        let needle = |z: f64| SliceScene3 { needle_m: Some(([0.004, 0.008, z], [0.012, 0.008, z])), ..scene.clone() };
        let zero = vec![[0.0; 3]; nodes.len()];
        let on = render_slice_3d(&nodes, &zero, &tets, &regions, &needle(0.0113), &p, &mut scratch);
        let off = render_slice_3d(&nodes, &zero, &tets, &regions, &needle(0.0123), &p, &mut scratch);
        assert_eq!(on.pixels[40 * p.width + 40], 255);
        assert_eq!(off, still);
    }

    /// A contact: reference position (m), force of the needle on the tissue (N).
    type Contact = ([f64; 3], [f64; 3]);

    /// A 60 mm box tissue of 12³ cells, bottom fixed, and the contacts of a needle pushing it
    /// along +x: five points on the vertical line x = y = 30 mm, z = 35…55 mm, force `scale`
    /// N each along +x (and a little −z).
    fn pushed_box(scale: f64) -> (TetTissueModel, Vec<Contact>) {
        use needlesim_core::Material;
        use needlesim_core::d3::{BoxGridParams, TetMaterials, TetMeshLimits};
        let mesh = BoxGridParams::new([13, 13, 13], [0.06; 3]).build(&TetMeshLimits::default()).unwrap();
        let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }]).unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        let model = TetTissueModel::new(mesh, mats, &fixed).unwrap();
        let contacts = (0..5).map(|k| ([0.03, 0.03, 0.035 + 0.005 * k as f64], [scale, 0.0, -0.2 * scale])).collect();
        (model, contacts)
    }

    /// A `width × height` window of 0.1 mm pixels in the plane y = 31.2 mm (lateral +x, depth
    /// −z) centred on `centre_m`.
    fn window(centre_m: [f64; 3], width: usize, height: usize) -> Probe3 {
        Probe3 {
            origin_m: [centre_m[0] - 0.5e-4 * width as f64, centre_m[1], centre_m[2] + 0.5e-4 * height as f64],
            e_u: [1.0, 0.0, 0.0],
            e_v: [0.0, 0.0, -1.0],
            pixel_m: 1e-4,
            width,
            height,
            thickness_m: 1e-3,
        }
    }

    /// The displacement at a material point, interpolated from the nodes.
    fn u_at(model: &TetTissueModel, u: &[[f64; 3]], x_m: [f64; 3]) -> [f64; 3] {
        let l = model.locate(x_m).unwrap();
        std::array::from_fn(|c| (0..4).map(|k| l.weights[k] * u[l.nodes[k]][c]).sum())
    }

    /// The slice of the tissue a needle's contacts deform (one solve, [`DeformedTissue3`]) differs
    /// from the reference slice where the tissue moved, its speckle following the solved
    /// displacement there within a pixel, and is unchanged where the tissue did not move.
    #[test]
    fn the_slice_of_a_solved_field_moves_the_speckle_with_the_tissue() {
        let (model, unit) = pushed_box(1.0);
        let mut deformed = DeformedTissue3::new(&model);
        // Beside the needle, 4 mm off it at mid-depth; and far from it, next to the fixed bottom.
        let (near, far) = ([0.034, 0.0312, 0.045], [0.045, 0.0312, 0.0015]);
        // Scale the loads (the model is linear) so that the tissue beside the needle moves 4 px.
        let u1 = u_at(&model, deformed.solve(&model, unit.iter().copied()).unwrap(), near);
        let scale = 4e-4 / u1[0];
        assert!(scale > 0.0, "the push moves the tissue along +x: {u1:?}");
        let contacts: Vec<Contact> = unit.iter().map(|&(x, f)| (x, f.map(|v| v * scale))).collect();
        let u = deformed.solve(&model, contacts.iter().copied()).unwrap().to_vec();
        assert_eq!(deformed.n_outside(), 0);
        let regions = vec![0; model.mesh().n_tets()];
        let tets: Vec<[usize; 4]> = model.mesh().tets().to_vec();
        let nodes = model.mesh().nodes_m();
        let zero = vec![[0.0; 3]; nodes.len()];
        let scene = SliceScene3 { region_gain: &[0.8], targets: &[], needle_m: None, needle_halfwidth_px: 1.0, speckle_m: 3e-4, seed: 5 };
        let mut scratch = UltrasoundScratch::default();
        let equal =
            |a: &GrayImage8, b: &GrayImage8| a.pixels.iter().zip(&b.pixels).filter(|(x, y)| x == y).count() as f64 / a.pixels.len() as f64;

        let p = window(near, 64, 64);
        let still = render_slice_3d(nodes, &zero, &tets, &regions, &scene, &p, &mut scratch);
        let moved = render_slice_3d(nodes, &u, &tets, &regions, &scene, &p, &mut scratch);
        assert!(equal(&still, &moved) < 0.2, "the slice changed where the tissue moved: {} of the pixels equal", equal(&still, &moved));
        let uc = u_at(&model, &u, near);
        let want = [dot3(uc, p.e_u) / p.pixel_m, dot3(uc, p.e_v) / p.pixel_m];
        let best = ncc_peak(&still.pixels, &moved.pixels, p.width, p.height, 8);
        assert!(
            (best.1 as f64 - want[0]).abs() <= 1.0 && (best.2 as f64 - want[1]).abs() <= 1.0 && best.0 > 0.5,
            "solved in-plane displacement {want:?} px, speckle correlation peak at ({}, {}) r = {:.3}",
            best.1,
            best.2,
            best.0
        );

        let r0 = ncc(&still.pixels, &moved.pixels, p.width, p.height, 0, 0, 10);
        assert!(r0 < 0.5, "unshifted, the moved speckle no longer matches: r = {r0:.3}");

        // Next to the fixed bottom the tissue moves less than half a pixel: the slice stays put.
        let p = window(far, 96, 24);
        let max_px = (0..p.height)
            .step_by(7)
            .flat_map(|j| (0..p.width).step_by(7).map(move |i| (i, j)))
            .map(|(i, j)| {
                let x =
                    [0, 1, 2].map(|c| p.origin_m[c] + (i as f64 + 0.5) * p.pixel_m * p.e_u[c] + (j as f64 + 0.5) * p.pixel_m * p.e_v[c]);
                let uf = u_at(&model, &u, x);
                dot3(uf, uf).sqrt() / p.pixel_m
            })
            .fold(0.0, f64::max);
        assert!(max_px < 0.5, "the tissue by the support barely moves: up to {max_px} px");
        let still = render_slice_3d(nodes, &zero, &tets, &regions, &scene, &p, &mut scratch);
        let moved = render_slice_3d(nodes, &u, &tets, &regions, &scene, &p, &mut scratch);
        let r0 = ncc(&still.pixels, &moved.pixels, p.width, p.height, 0, 0, 2);
        assert!(r0 > 0.9, "unchanged where the tissue did not move: r = {r0:.3} ({} of the pixels equal)", equal(&still, &moved));
    }

    /// [`DeformedTissue3`]: no contacts (or only contacts outside the mesh) give $u = 0$ without a
    /// solve; a non-finite force is refused, naming the point, and leaves $u = 0$; the result is
    /// the core's one solve.
    #[test]
    fn deformed_tissue_skips_outside_points_and_refuses_bad_forces() {
        let (model, contacts) = pushed_box(0.05);
        let mut d = DeformedTissue3::new(&model);
        let u = d.solve(&model, contacts.iter().copied()).unwrap().to_vec();
        assert!(u.iter().flatten().any(|&v| v.abs() > 1e-6), "the contacts move the tissue");
        let locs: Vec<PointLocation> = contacts.iter().map(|c| model.locate(c.0).unwrap()).collect();
        let forces: Vec<[f64; 3]> = contacts.iter().map(|c| c.1).collect();
        let mut want = vec![0.0; model.n_dofs()];
        model.displacement_for_point_loads_into(&locs, &forces, &mut want, &mut model.column_scratch()).unwrap();
        assert_eq!(u.as_flattened(), &want[..]);
        // A point outside the tissue is left out.
        let with_outside = contacts.iter().copied().chain([([0.03, 0.03, 0.2], [1.0, 0.0, 0.0])]);
        assert_eq!(d.solve(&model, with_outside).unwrap(), &u[..]);
        assert_eq!(d.n_outside(), 1);
        assert!(d.solve(&model, [([0.03, 0.03, 0.2], [1.0, 0.0, 0.0])]).unwrap().iter().all(|v| *v == [0.0; 3]));
        assert!(d.solve(&model, []).unwrap().iter().all(|v| *v == [0.0; 3]));
        let bad = contacts.iter().copied().chain([([0.03, 0.03, 0.03], [f64::INFINITY, 0.0, 0.0])]);
        let e = d.solve(&model, bad).unwrap_err();
        assert!(matches!(e, TetTissueError::NonFiniteForce { point_idx: 5, .. }), "{e:?}");
        assert!(d.displacement_m().iter().all(|v| *v == [0.0; 3]));
    }

    /// The cost of a 256 × 154 slice of a 41 × 25 grid, of a 256 × 256 slice of 48,000
    /// tetrahedra (issue 20's observers' side), and of a live 3D image of the cube-phantom-3d
    /// tissue (its 21³-node, 48,000-tetrahedron box, `fixtures::box_phantom3(21)`): the
    /// displacement solve from 20 contacts of a needle 40 mm in ([`DeformedTissue3::solve`]) plus
    /// the 256 × 256 slice through the needle. Run with
    /// `cargo test -p needlesim-training --release -- --ignored --nocapture slice_cost`.
    #[test]
    #[ignore]
    fn slice_cost() {
        let (nodes, tris, regions) = grid(40, 24, 0.1, 0.06);
        let p = Probe { origin_m: [0.0, 0.06], e_u: [1.0, 0.0], e_v: [0.0, -1.0], pixel_m: 0.1 / 256.0, width: 256, height: 154 };
        let scene = SliceScene {
            region_gain: &[0.7, 0.5],
            targets: &[([0.058, 0.028], 0.0015)],
            needle_m: Some(([0.02, 0.06], [0.058, 0.028])),
            needle_halfwidth_px: 1.0,
            speckle_m: 3e-4,
            seed: 1,
        };
        let u = vec![[1e-4, -2e-4]; nodes.len()];
        let mut scratch = UltrasoundScratch::default();
        let mut times = Vec::new();
        for _ in 0..300 {
            let t = std::time::Instant::now();
            let img = render_slice(&nodes, &u, &tris, &regions, &scene, &p, &mut scratch);
            times.push(t.elapsed().as_secs_f64() * 1e6);
            assert_eq!(img.pixels.len(), 256 * 154);
        }
        times.sort_by(f64::total_cmp);
        let pct = |t: &[f64], q: f64| t[((t.len() - 1) as f64 * q).round() as usize];
        println!(
            "2D slice 256x154, {} triangles: p50 {:.0} us, p99 {:.0} us, max {:.0} us",
            tris.len(),
            pct(&times, 0.5),
            pct(&times, 0.99),
            pct(&times, 1.0)
        );
        // 3D: a 60 mm cube of 20³ cells (48,000 tetrahedra), a 256 × 256 plane through it at 30°.
        let (nodes, tets) = cube(20, 0.003);
        let regions = vec![0; tets.len()];
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let p = Probe3 {
            origin_m: [0.002, 0.03, 0.002],
            e_u: [c, 0.0, s],
            e_v: [-s, 0.0, c],
            pixel_m: 0.05 / 256.0,
            width: 256,
            height: 256,
            thickness_m: 1e-3,
        };
        let scene = SliceScene3 {
            region_gain: &[0.7],
            targets: &[([0.03, 0.03, 0.03], 0.003)],
            needle_m: Some(([0.0, 0.03, 0.0], [0.03, 0.03, 0.03])),
            needle_halfwidth_px: 1.0,
            speckle_m: 3e-4,
            seed: 1,
        };
        let u = vec![[1e-4, 0.0, -2e-4]; nodes.len()];
        let mut times = Vec::new();
        for _ in 0..100 {
            let t = std::time::Instant::now();
            let img = render_slice_3d(&nodes, &u, &tets, &regions, &scene, &p, &mut scratch);
            times.push(t.elapsed().as_secs_f64() * 1e6);
            assert_eq!(img.pixels.len(), 256 * 256);
        }
        times.sort_by(f64::total_cmp);
        println!(
            "3D slice 256x256, {} tetrahedra: p50 {:.0} us, p99 {:.0} us, max {:.0} us",
            tets.len(),
            pct(&times, 0.5),
            pct(&times, 0.99),
            pct(&times, 1.0)
        );

        // The live 3D image: solve, then render, on the cube-phantom-3d tissue.
        let t = std::time::Instant::now();
        let model = needlesim_core::fixtures::box_phantom3(21);
        let t_model = t.elapsed();
        let mesh = model.mesh();
        let regions = vec![0; mesh.n_tets()];
        let tets: Vec<[usize; 4]> = mesh.tets().to_vec();
        // A needle 40 mm into the top centre, slightly off the grid lines: 20 points 2 mm apart,
        // each dragging the tissue down (−z: pushing in) and sideways, the tip's point the most.
        let contacts: Vec<Contact> = (0..20)
            .map(|k| {
                let z = 0.0995 - 0.002 * k as f64;
                let tip = if k == 19 { 10.0 } else { 1.0 };
                ([0.0503, 0.0498, z], [0.01, 0.004, -0.02 * tip])
            })
            .collect();
        let p = Probe3 {
            origin_m: [0.0, 0.0498, 0.1],
            e_u: [1.0, 0.0, 0.0],
            e_v: [0.0, 0.0, -1.0],
            pixel_m: 0.1 / 256.0,
            width: 256,
            height: 256,
            thickness_m: 2e-3,
        };
        let scene = SliceScene3 {
            region_gain: &[0.7],
            targets: &[([0.05, 0.05, 0.05], 0.002)],
            needle_m: Some(([0.0503, 0.0498, 0.105], [0.0503, 0.0498, 0.0615])),
            needle_halfwidth_px: 1.0,
            speckle_m: 3e-4,
            seed: 1,
        };
        let mut deformed = DeformedTissue3::new(&model);
        let (mut solve, mut render, mut total) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..100 {
            // A new tick each time: the forces change a little.
            let f = 1.0 + 1e-3 * i as f64;
            let t0 = std::time::Instant::now();
            let u = deformed.solve(&model, contacts.iter().map(|&(x, g)| (x, g.map(|v| v * f)))).unwrap();
            let t1 = std::time::Instant::now();
            let img = render_slice_3d(mesh.nodes_m(), u, &tets, &regions, &scene, &p, &mut scratch);
            let t2 = std::time::Instant::now();
            assert_eq!(img.pixels.len(), 256 * 256);
            solve.push((t1 - t0).as_secs_f64() * 1e6);
            render.push((t2 - t1).as_secs_f64() * 1e6);
            total.push((t2 - t0).as_secs_f64() * 1e6);
        }
        let umax = deformed.displacement_m().iter().flatten().fold(0.0_f64, |a, v| a.max(v.abs()));
        println!(
            "3D live image, cube-phantom-3d ({} nodes, {} tetrahedra, factor nnz {}, model built in {:.2} s), 20 contacts, max |u| {:.2} mm:",
            mesh.n_nodes(),
            mesh.n_tets(),
            model.cholesky().factor_nnz(),
            t_model.as_secs_f64(),
            umax * 1e3
        );
        for (what, times) in [("solve", &mut solve), ("render 256x256", &mut render), ("solve + render", &mut total)] {
            times.sort_by(f64::total_cmp);
            println!(
                "  {what}: p50 {:.0} us, p99 {:.0} us, max {:.0} us (n = {})",
                pct(times, 0.5),
                pct(times, 0.99),
                pct(times, 1.0),
                times.len()
            );
        }
    }
}
