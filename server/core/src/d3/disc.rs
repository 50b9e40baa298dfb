//! The needle's contact patch in 3D: the shape functions averaged over a disc across the shaft,
//! integrated exactly over the tetrahedra the disc crosses.
//!
//! # Mathematics
//!
//! A disc $\mathcal D$ of radius $r$ centred at $c$ across the unit axis $a$ (the needle's
//! cross-section) lies in the plane $\{c + x e_1 + y e_2\}$, $(e_1, e_2, a)$ orthonormal. Its
//! patch weights are the mean values of the shape functions over it,
//! $$w_k = \frac{1}{|\mathcal D \cap \Omega|} \int_{\mathcal D \cap \Omega} N_k \,\mathrm dA ,$$
//! so that $u(\mathcal D) = \sum_k w_k u_k$ is the tissue's mean displacement over the needle's
//! cross-section ($\Omega$ the mesh; $|\mathcal D \cap \Omega| = \pi r^2$ unless the disc leaves
//! the tissue). In a tetrahedron $T$ the shape functions are affine,
//! $N_k(c + x e_1 + y e_2) = N_k(c) + x\, \nabla N_k \cdot e_1 + y\, \nabla N_k \cdot e_2$, so with
//! the area $A_T$ and first moments $(M_{x,T}, M_{y,T})$ of $R_T = \mathcal D \cap T$ (in the
//! plane's coordinates, about $c$)
//! $$\int_{R_T} N_k \,\mathrm dA = N_k(c)\, A_T + (\nabla N_k \cdot e_1)\, M_{x,T} + (\nabla N_k \cdot e_2)\, M_{y,T} ,$$
//! exactly. The plane cuts $T$ in a convex polygon $Q_T$ (a triangle or a quadrilateral); the area
//! and moments of $Q_T$ clipped by the circle are sums over its edges of signed fans from the
//! centre (Green's theorem): for an edge piece $s \to u$ inside the circle the triangle
//! $(0, s, u)$, with area $\tfrac12 s \times u$ and moment $\tfrac12 (s \times u)\,(s + u)/3$; for a
//! piece outside it the sector from angle $\alpha$ to $\beta$, with area $\tfrac12 r^2 (\beta - \alpha)$
//! and moment $\tfrac13 r^3 (\sin\beta - \sin\alpha,\ \cos\alpha - \cos\beta)$. A tetrahedron
//! with a face in the plane shares that face with its neighbour: each counts it half. The reference
//! (../shared/validation, fem_ref3d.py `discs`) integrates the same mean by a polar quadrature.

use super::locate::{TetLocator, barycentric};
use super::mesh::{TetMesh, cross, dot, sub};

/// A disc across the needle's shaft: its centre, the shaft's axis (need not be unit), its radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    /// The centre, on the needle's axis, in m.
    pub centre_m: [f64; 3],
    /// The needle's axis at the centre (normalised here).
    pub axis: [f64; 3],
    /// The radius (the needle's), in m.
    pub radius_m: f64,
}

/// Errors of [`disc_weights_into`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DiscError {
    /// The disc is not finite, its axis is zero, or its radius is not positive.
    #[error(
        "a contact disc needs a finite centre, a non-zero axis and a positive radius: centre {centre_m:?} m, axis {axis:?}, radius {radius_m} m"
    )]
    Invalid { centre_m: [f64; 3], axis: [f64; 3], radius_m: f64 },
    /// The disc does not meet the mesh.
    #[error("the contact disc at {centre_m:?} m (radius {radius_m} m) lies outside the tissue")]
    Outside { centre_m: [f64; 3], radius_m: f64 },
    /// The disc crosses more nodes than the weights were sized for.
    #[error("the contact disc at {centre_m:?} m crosses more than {capacity} nodes")]
    TooManyNodes { centre_m: [f64; 3], capacity: usize },
}

/// A disc's patch weights: nodes (in the order first met) and their weights (sum 1), sized once.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscWeights {
    nodes: Vec<usize>,
    weights: Vec<f64>,
    covered_fraction: f64,
}

impl DiscWeights {
    /// Room for `max_nodes` nodes: [`disc_weights_into`] then allocates nothing.
    pub fn with_capacity(max_nodes: usize) -> Self {
        Self { nodes: Vec::with_capacity(max_nodes), weights: Vec::with_capacity(max_nodes), covered_fraction: 0.0 }
    }
    /// The nodes the disc's tetrahedra hold.
    pub fn nodes(&self) -> &[usize] {
        &self.nodes
    }
    /// Their weights $w_k$, one per node, summing to 1.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
    /// The share of the disc's area inside the tissue, $|\mathcal D \cap \Omega| / (\pi r^2)$.
    pub fn covered_fraction(&self) -> f64 {
        self.covered_fraction
    }
}

/// An orthonormal basis $(e_1, e_2)$ of the plane across the unit axis `a` (the reference's).
pub fn disc_basis(a: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let pick = if a[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let along = dot(pick, a);
    let e1 = normalised([pick[0] - a[0] * along, pick[1] - a[1] * along, pick[2] - a[2] * along]);
    (e1, cross(a, e1))
}

/// Writes the patch weights of `disc` (the shape functions averaged over it, exactly) into `out`.
/// Allocates nothing when `out` has room ([`DiscWeights::with_capacity`]).
pub fn disc_weights_into(mesh: &TetMesh, locator: &TetLocator, disc: &Disc, out: &mut DiscWeights) -> Result<(), DiscError> {
    let Disc { centre_m: c, axis, radius_m: r } = *disc;
    let norm = dot(axis, axis).sqrt();
    if !(c.iter().chain(&axis).all(|v| v.is_finite()) && norm > 0.0 && norm.is_finite() && r > 0.0 && r.is_finite()) {
        return Err(DiscError::Invalid { centre_m: c, axis, radius_m: r });
    }
    let a = axis.map(|v| v / norm);
    let (e1, e2) = disc_basis(a);
    let capacity = out.nodes.capacity();
    out.nodes.clear();
    out.weights.clear();
    let mut area_m2 = 0.0;
    let mut overflow = false;
    // The disc's bounding box: along axis k it reaches r·sqrt(1 − a_k²) from the centre.
    let reach = a.map(|ak| r * (1.0 - ak * ak).max(0.0).sqrt() * (1.0 + 1e-12) + 1e-12 * r);
    let lo = [0, 1, 2].map(|k| c[k] - reach[k]);
    let hi = [0, 1, 2].map(|k| c[k] + reach[k]);
    locator.for_each_tet_near_box(mesh, lo, hi, |t| {
        let p = mesh.tet_points_m(t);
        let Some((poly, n, share)) = plane_section(&p, c, a, e1, e2) else { return };
        let (area, mx, my) = clipped_moments(&poly[..n], r);
        if area == 0.0 {
            return;
        }
        let n_c = barycentric(p, c);
        let n_1 = barycentric(p, add(c, e1, r));
        let n_2 = barycentric(p, add(c, e2, r));
        area_m2 += share * area;
        for (k, &node) in mesh.tets()[t].iter().enumerate() {
            let g1 = (n_1[k] - n_c[k]) / r;
            let g2 = (n_2[k] - n_c[k]) / r;
            let integral = share * (n_c[k] * area + g1 * mx + g2 * my);
            match out.nodes.iter().position(|&v| v == node) {
                Some(i) => out.weights[i] += integral,
                None if out.nodes.len() < capacity => {
                    out.nodes.push(node);
                    out.weights.push(integral);
                }
                None => overflow = true,
            }
        }
    });
    if overflow {
        return Err(DiscError::TooManyNodes { centre_m: c, capacity });
    }
    let full_m2 = std::f64::consts::PI * r * r;
    if area_m2 <= 1e-12 * full_m2 {
        return Err(DiscError::Outside { centre_m: c, radius_m: r });
    }
    for w in &mut out.weights {
        *w /= area_m2;
    }
    out.covered_fraction = area_m2 / full_m2;
    Ok(())
}

/// The polygon in which the plane through `c` across `a` cuts the tetrahedron `p`, in the plane's
/// coordinates about `c`, counter-clockwise about `a`: its vertices, their number (3 or 4), and
/// the share of it this tetrahedron counts (½ for a face lying in the plane, shared with the
/// neighbour). `None` when the plane misses the tetrahedron or touches it in an edge or a vertex.
fn plane_section(p: &[[f64; 3]; 4], c: [f64; 3], a: [f64; 3], e1: [f64; 3], e2: [f64; 3]) -> Option<([[f64; 2]; 4], usize, f64)> {
    let d = p.map(|q| dot(sub(q, c), a));
    if d.iter().all(|&v| v > 0.0) || d.iter().all(|&v| v < 0.0) {
        return None;
    }
    let mut pts = [[0.0; 2]; 4];
    let mut n = 0;
    let mut push = |x: [f64; 3]| {
        if n < 4 {
            let rel = sub(x, c);
            pts[n] = [dot(rel, e1), dot(rel, e2)];
            n += 1;
        }
    };
    let zeros = d.iter().filter(|&&v| v == 0.0).count();
    for i in 0..4 {
        if d[i] == 0.0 {
            push(p[i]);
        }
    }
    for i in 0..4 {
        for j in i + 1..4 {
            if (d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0) {
                let t = d[i] / (d[i] - d[j]);
                push([0, 1, 2].map(|k| p[i][k] + t * (p[j][k] - p[i][k])));
            }
        }
    }
    if n < 3 {
        return None;
    }
    // Convex: order the vertices by angle about their mean.
    let m = [pts[..n].iter().map(|q| q[0]).sum::<f64>() / n as f64, pts[..n].iter().map(|q| q[1]).sum::<f64>() / n as f64];
    let angle = |q: &[f64; 2]| (q[1] - m[1]).atan2(q[0] - m[0]);
    pts[..n].sort_by(|x, y| angle(x).total_cmp(&angle(y)));
    Some((pts, n, if zeros == 3 { 0.5 } else { 1.0 }))
}

/// Area and first moments $(A, M_x, M_y)$ of the convex counter-clockwise polygon `poly`
/// clipped by the circle of radius `r` about the origin, as signed fans over its edges.
fn clipped_moments(poly: &[[f64; 2]], r: f64) -> (f64, f64, f64) {
    let (mut area, mut mx, mut my) = (0.0, 0.0, 0.0);
    let r2 = r * r;
    // Whether any edge piece lies inside the circle: if none, the polygon either misses the
    // circle or holds all of it, and the sectors' angles sum to 0 or 2π (exactly so below, rather
    // than with their round-off).
    let mut crosses = false;
    let mut turned = 0.0;
    for i in 0..poly.len() {
        let p = poly[i];
        let q = poly[(i + 1) % poly.len()];
        let d = [q[0] - p[0], q[1] - p[1]];
        // |p + t d| = r: t² |d|² + 2 t p·d + |p|² − r² = 0.
        let aa = d[0] * d[0] + d[1] * d[1];
        let bb = p[0] * d[0] + p[1] * d[1];
        let cc = p[0] * p[0] + p[1] * p[1] - r2;
        let mut cuts = [0.0, 1.0, 1.0, 1.0];
        let mut n_cuts = 1;
        let disc = bb * bb - aa * cc;
        if aa > 0.0 && disc > 0.0 {
            let s = disc.sqrt();
            for t in [(-bb - s) / aa, (-bb + s) / aa] {
                if t > 0.0 && t < 1.0 {
                    cuts[n_cuts] = t;
                    n_cuts += 1;
                }
            }
        }
        cuts[n_cuts] = 1.0;
        for w in cuts[..=n_cuts].windows(2) {
            let s = [p[0] + w[0] * d[0], p[1] + w[0] * d[1]];
            let u = [p[0] + w[1] * d[0], p[1] + w[1] * d[1]];
            let mid = [0.5 * (s[0] + u[0]), 0.5 * (s[1] + u[1])];
            let cr = s[0] * u[1] - s[1] * u[0];
            if mid[0] * mid[0] + mid[1] * mid[1] <= r2 {
                crosses = true;
                area += 0.5 * cr;
                mx += 0.5 * cr * (s[0] + u[0]) / 3.0;
                my += 0.5 * cr * (s[1] + u[1]) / 3.0;
            } else {
                let theta = cr.atan2(s[0] * u[0] + s[1] * u[1]);
                let alpha = s[1].atan2(s[0]);
                let beta = alpha + theta;
                turned += theta;
                area += 0.5 * r2 * theta;
                mx += r2 * r / 3.0 * (beta.sin() - alpha.sin());
                my += r2 * r / 3.0 * (alpha.cos() - beta.cos());
            }
        }
    }
    match (crosses, turned.abs() > std::f64::consts::PI) {
        (true, _) => (area, mx, my),
        (false, true) => (std::f64::consts::PI * r2, 0.0, 0.0),
        (false, false) => (0.0, 0.0, 0.0),
    }
}

fn add(a: [f64; 3], b: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}
fn normalised(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    a.map(|v| v / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};
    use std::f64::consts::PI;

    fn cube(n: usize) -> (TetMesh, TetLocator) {
        let mesh = BoxGridParams::new([n; 3], [0.1; 3]).build(&TetMeshLimits::default()).expect("a box grid");
        let locator = TetLocator::new(&mesh);
        (mesh, locator)
    }

    /// A box grid with its inner nodes moved at random, so no face is axis-aligned.
    fn distorted_cube(n: usize, seed: u64) -> (TetMesh, TetLocator) {
        let m = BoxGridParams::new([n; 3], [0.1; 3]).build(&TetMeshLimits::default()).expect("a box grid");
        let mut rng = SmallRng::seed_from_u64(seed);
        let h = 0.1 / (n - 1) as f64;
        let nodes = m
            .nodes_m()
            .iter()
            .map(|p| p.map(|v| if v > 1e-12 && v < 0.1 - 1e-12 { v + rng.random_range(-0.2 * h..0.2 * h) } else { v }))
            .collect();
        let mesh = TetMesh::new(nodes, m.tets().to_vec(), &TetMeshLimits::default()).expect("still valid");
        let locator = TetLocator::new(&mesh);
        (mesh, locator)
    }

    fn random_unit(rng: &mut SmallRng) -> [f64; 3] {
        loop {
            let v = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            let n = dot(v, v).sqrt();
            if n > 0.2 && n < 1.0 {
                return v.map(|x| x / n);
            }
        }
    }

    /// The weighted node sum of the node positions: the disc's mean position.
    fn mean_position(mesh: &TetMesh, w: &DiscWeights) -> [f64; 3] {
        let mut x = [0.0; 3];
        for (&node, &wk) in w.nodes().iter().zip(w.weights()) {
            for k in 0..3 {
                x[k] += wk * mesh.nodes_m()[node][k];
            }
        }
        x
    }

    #[test]
    fn clipped_moments_of_a_square_inside_and_a_circle_inside_a_square() {
        // A square well inside the circle: its own area and centroid.
        let sq = [[0.1, 0.2], [0.3, 0.2], [0.3, 0.4], [0.1, 0.4]];
        let (a, mx, my) = clipped_moments(&sq, 10.0);
        assert!((a - 0.04).abs() < 1e-15 && (mx / a - 0.2).abs() < 1e-14 && (my / a - 0.3).abs() < 1e-14, "{a} {mx} {my}");
        // A circle inside a square: πr², centroid at the centre.
        let big = [[-5.0, -5.0], [5.0, -5.0], [5.0, 5.0], [-5.0, 5.0]];
        let (a, mx, my) = clipped_moments(&big, 1.5);
        assert!((a - PI * 2.25).abs() < 1e-13 && mx.abs() < 1e-13 && my.abs() < 1e-13, "{a} {mx} {my}");
        // Half a circle (the square's edge through the centre): πr²/2, centroid 4r/(3π) inside.
        let half = [[-5.0, 0.0], [5.0, 0.0], [5.0, 5.0], [-5.0, 5.0]];
        let (a, mx, my) = clipped_moments(&half, 2.0);
        assert!((a - 2.0 * PI).abs() < 1e-13 && mx.abs() < 1e-13, "{a} {mx}");
        assert!((my / a - 8.0 / (3.0 * PI)).abs() < 1e-13, "{}", my / a);
    }

    #[test]
    fn a_disc_inside_one_tetrahedron_weighs_its_nodes_by_their_shape_functions_at_the_centre() {
        let (mesh, locator) = cube(3);
        let loc = locator.locate(&mesh, [0.031, 0.012, 0.044]).unwrap();
        let p = mesh.tet_points_m(loc.tet_idx);
        // A tiny disc around the tetrahedron's centroid, inside it.
        let centre = [0, 1, 2].map(|k| p.iter().map(|q| q[k]).sum::<f64>() / 4.0);
        let disc = Disc { centre_m: centre, axis: [0.3, -0.2, 0.9], radius_m: 1e-5 };
        let mut w = DiscWeights::with_capacity(32);
        disc_weights_into(&mesh, &locator, &disc, &mut w).unwrap();
        assert_eq!(w.nodes().len(), 4, "{:?}", w.nodes());
        for (&node, &wk) in w.nodes().iter().zip(w.weights()) {
            assert!(mesh.tets()[loc.tet_idx].contains(&node), "node {node} is not one of the tetrahedron's");
            assert!((wk - 0.25).abs() < 1e-12, "node {node}: {wk} (the centroid's N = 1/4)");
        }
        assert!((w.covered_fraction() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn random_discs_across_many_tetrahedra_reproduce_their_centre_and_cover_their_area() {
        // Linear precision: the mean of x over the disc is its centre, so Σ w_k x_k = c and
        // Σ w_k = 1 exactly, whatever tetrahedra the disc crosses; and the covered area is πr².
        let (mesh, locator) = distorted_cube(6, 0xd15c);
        let mut rng = SmallRng::seed_from_u64(0xd15c);
        let mut w = DiscWeights::with_capacity(256);
        let mut most = 0;
        for _ in 0..200 {
            let r = rng.random_range(0.5e-3..0.03);
            let c = [0, 1, 2].map(|_| rng.random_range(0.031..0.069));
            let disc = Disc { centre_m: c, axis: random_unit(&mut rng), radius_m: r };
            disc_weights_into(&mesh, &locator, &disc, &mut w).unwrap();
            most = most.max(w.nodes().len());
            let sum: f64 = w.weights().iter().sum();
            assert!((sum - 1.0).abs() < 1e-12, "Σw = {sum}");
            assert!((w.covered_fraction() - 1.0).abs() < 1e-11, "covered {}", w.covered_fraction());
            let x = mean_position(&mesh, &w);
            let err = (0..3).map(|k| (x[k] - c[k]).abs()).fold(0.0, f64::max);
            assert!(err < 1e-13, "Σ w_k x_k − c = {err:e} for r = {r}");
            assert!(w.weights().iter().all(|&v| v > -1e-14), "mean shape functions are non-negative: {:?}", w.weights());
        }
        assert!(most > 20, "the discs crossed many tetrahedra: at most {most} nodes");
    }

    #[test]
    fn a_disc_on_the_surface_is_a_half_disc_with_its_centroid_inside() {
        // Centred on the face z = 0.1 with its axis along x: half of it is in the tissue.
        let (mesh, locator) = cube(5);
        let (r, c) = (0.01, [0.043, 0.051, 0.1]);
        let mut w = DiscWeights::with_capacity(128);
        disc_weights_into(&mesh, &locator, &Disc { centre_m: c, axis: [1.0, 0.0, 0.0], radius_m: r }, &mut w).unwrap();
        assert!((w.covered_fraction() - 0.5).abs() < 1e-12, "{}", w.covered_fraction());
        let x = mean_position(&mesh, &w);
        assert!((x[2] - (0.1 - 4.0 * r / (3.0 * PI))).abs() < 1e-13 && (x[0] - c[0]).abs() < 1e-13 && (x[1] - c[1]).abs() < 1e-13, "{x:?}");
        // Wholly outside: refused, naming it.
        let e = disc_weights_into(&mesh, &locator, &Disc { centre_m: [0.05, 0.05, 0.2], axis: [0.0, 0.0, 1.0], radius_m: r }, &mut w);
        assert!(matches!(e, Err(DiscError::Outside { .. })), "{e:?}");
    }

    #[test]
    fn a_disc_in_the_plane_of_mesh_faces_counts_each_face_once() {
        // The grid's faces at z = 0.05 lie in the plane of a disc across the z axis.
        let (mesh, locator) = cube(5);
        let c = [0.047, 0.052, 0.05];
        let mut w = DiscWeights::with_capacity(128);
        disc_weights_into(&mesh, &locator, &Disc { centre_m: c, axis: [0.0, 0.0, 1.0], radius_m: 0.02 }, &mut w).unwrap();
        assert!((w.covered_fraction() - 1.0).abs() < 1e-12, "{}", w.covered_fraction());
        let x = mean_position(&mesh, &w);
        assert!((0..3).all(|k| (x[k] - c[k]).abs() < 1e-13), "{x:?}");
        // Only the plane's nodes carry weight.
        for (&node, &wk) in w.nodes().iter().zip(w.weights()) {
            if (mesh.nodes_m()[node][2] - 0.05).abs() > 1e-12 {
                assert!(wk.abs() < 1e-14, "node {node} off the plane has weight {wk}");
            }
        }
    }

    #[test]
    fn weights_match_a_fine_polar_quadrature() {
        // The mean of each N_k by a polar midpoint rule with many points (second order in the
        // spacing, but the kinks across faces limit it): agreement to about 1e-4.
        let (mesh, locator) = distorted_cube(4, 7);
        let mut rng = SmallRng::seed_from_u64(7);
        let mut w = DiscWeights::with_capacity(128);
        for _ in 0..3 {
            let c = [0, 1, 2].map(|_| rng.random_range(0.035..0.065));
            let disc = Disc { centre_m: c, axis: random_unit(&mut rng), radius_m: 0.02 };
            disc_weights_into(&mesh, &locator, &disc, &mut w).unwrap();
            let (e1, e2) = disc_basis(normalised(disc.axis));
            let (nr, nt) = (300, 600);
            let mut sum = vec![0.0; mesh.n_nodes()];
            let mut total = 0.0;
            for i in 0..nr {
                let rho = (i as f64 + 0.5) / nr as f64 * disc.radius_m;
                for j in 0..nt {
                    let th = (j as f64 + 0.5) / nt as f64 * 2.0 * PI;
                    let x = add(add(c, e1, rho * th.cos()), e2, rho * th.sin());
                    let loc = locator.locate(&mesh, x).unwrap();
                    for (k, &node) in loc.nodes.iter().enumerate() {
                        sum[node] += rho * loc.weights[k];
                    }
                    total += rho;
                }
            }
            for (node, s) in sum.iter().enumerate() {
                let q = s / total;
                let exact = w.nodes().iter().position(|&v| v == node).map_or(0.0, |i| w.weights()[i]);
                assert!((q - exact).abs() < 2e-4, "node {node}: quadrature {q}, exact {exact}");
            }
        }
    }

    #[test]
    fn invalid_discs_and_too_small_a_capacity_are_refused() {
        let (mesh, locator) = cube(4);
        let mut w = DiscWeights::with_capacity(4);
        for disc in [
            Disc { centre_m: [f64::NAN, 0.05, 0.05], axis: [0.0, 0.0, 1.0], radius_m: 1e-3 },
            Disc { centre_m: [0.05; 3], axis: [0.0; 3], radius_m: 1e-3 },
            Disc { centre_m: [0.05; 3], axis: [0.0, 0.0, 1.0], radius_m: 0.0 },
        ] {
            let e = disc_weights_into(&mesh, &locator, &disc, &mut w);
            assert!(matches!(e, Err(DiscError::Invalid { .. })), "{e:?}");
        }
        let e = disc_weights_into(&mesh, &locator, &Disc { centre_m: [0.05; 3], axis: [0.2, 0.3, 1.0], radius_m: 0.03 }, &mut w);
        assert!(matches!(e, Err(DiscError::TooManyNodes { capacity: 4, .. })), "{e:?}");
    }
}
