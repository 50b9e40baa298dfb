//! Point location in a tetrahedral mesh: which tetrahedron holds a point, and its barycentric
//! weights — the shape functions $N_i(x)$ of the linear tetrahedron, so that
//! $u(x) = \sum_{i=1}^4 N_i(x)\, u_{t_i}$. Material points (the needle's contact points) use it.
//!
//! For a tetrahedron $(a, b, c, d)$ of volume $V$, $N_a(x) = V(x, b, c, d) / V$ and likewise for the
//! others (each corner replaced by $x$); the four weights sum to 1 and all lie in $[0, 1]$ inside.
//! [`TetLocator`] buckets the tetrahedra's bounding boxes in a uniform grid (compressed rows, built
//! once); a query tests the tetrahedra of the point's cell and keeps the one whose smallest weight
//! is largest (the first such in index order on a tie, as the reference does), accepting it when
//! that weight is at least $-10^{-10}$ ([`BARYCENTRIC_TOL`]): a point on a shared face or edge
//! belongs to either neighbour, which interpolate the same displacement there.

use super::mesh::{TetMesh, signed_volume_m3};

/// A point is inside a tetrahedron when its smallest barycentric weight is at least minus this.
pub const BARYCENTRIC_TOL: f64 = 1e-10;

/// Where a point lies: its tetrahedron, that tetrahedron's nodes and the weights $N_i(x)$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLocation {
    /// Index of the tetrahedron holding the point.
    pub tet_idx: usize,
    /// Its four nodes.
    pub nodes: [usize; 4],
    /// The barycentric weights $N_i(x)$ of those nodes (sum 1).
    pub weights: [f64; 4],
}

/// Errors of point location.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LocateError {
    /// No tetrahedron holds the point (within [`BARYCENTRIC_TOL`]).
    #[error("the point ({}, {}, {}) m lies outside the mesh", crate::num::num(x_m[0]), crate::num::num(x_m[1]), crate::num::num(x_m[2]))]
    Outside { x_m: [f64; 3] },
    /// A coordinate of the point is NaN or infinite.
    #[error("the point {x_m:?} has a non-finite coordinate")]
    NonFinite { x_m: [f64; 3] },
}

/// The barycentric weights of `x_m` in the tetrahedron with corners `p` (any orientation).
pub fn barycentric(p: [[f64; 3]; 4], x_m: [f64; 3]) -> [f64; 4] {
    let v = signed_volume_m3(p[0], p[1], p[2], p[3]);
    [
        signed_volume_m3(x_m, p[1], p[2], p[3]) / v,
        signed_volume_m3(p[0], x_m, p[2], p[3]) / v,
        signed_volume_m3(p[0], p[1], x_m, p[3]) / v,
        signed_volume_m3(p[0], p[1], p[2], x_m) / v,
    ]
}

/// The bounding box of tetrahedron `t`.
fn tet_box(mesh: &TetMesh, t: usize) -> ([f64; 3], [f64; 3]) {
    let p = mesh.tet_points_m(t);
    let mut l = p[0];
    let mut h = p[0];
    for q in &p[1..] {
        for k in 0..3 {
            l[k] = l[k].min(q[k]);
            h[k] = h[k].max(q[k]);
        }
    }
    (l, h)
}

/// A uniform grid of buckets over the tetrahedra's bounding boxes, for [`TetLocator::locate`].
#[derive(Debug, Clone)]
pub struct TetLocator {
    origin_m: [f64; 3],
    cell_m: f64,
    n_cells: [usize; 3],
    cell_start: Vec<usize>,
    tets: Vec<u32>,
}

impl TetLocator {
    /// Buckets the tetrahedra of `mesh`: cells about the mean tetrahedron extent, at most about
    /// two cells per tetrahedron.
    pub fn new(mesh: &TetMesh) -> Self {
        let (lo, hi) = mesh.bounding_box_m();
        let n_tets = mesh.n_tets();
        let boxes: Vec<([f64; 3], [f64; 3])> = (0..n_tets).map(|t| tet_box(mesh, t)).collect();
        let mean_extent = boxes.iter().map(|(l, h)| (0..3).map(|k| h[k] - l[k]).fold(0.0, f64::max)).sum::<f64>() / n_tets as f64;
        let volume = (0..3).map(|k| (hi[k] - lo[k]).max(0.0)).product::<f64>();
        let cell_m = mean_extent.max((volume / (2.0 * n_tets as f64)).cbrt()).max(f64::MIN_POSITIVE);
        let n_cells = [0, 1, 2].map(|k| (((hi[k] - lo[k]) / cell_m).floor() as usize).saturating_add(1).min(1 << 12));
        let mut this = Self { origin_m: lo, cell_m, n_cells, cell_start: Vec::new(), tets: Vec::new() };
        let range = |this: &Self, b: &([f64; 3], [f64; 3])| this.cells_of_box(b);
        let total = n_cells[0] * n_cells[1] * n_cells[2];
        let mut start = vec![0usize; total + 1];
        let index = |c: [usize; 3]| c[0] + n_cells[0] * (c[1] + n_cells[1] * c[2]);
        for b in &boxes {
            let (l, h) = range(&this, b);
            for k in l[2]..=h[2] {
                for j in l[1]..=h[1] {
                    for i in l[0]..=h[0] {
                        start[index([i, j, k]) + 1] += 1;
                    }
                }
            }
        }
        for c in 1..start.len() {
            start[c] += start[c - 1];
        }
        let mut fill = start.clone();
        let mut tets = vec![0u32; start[total]];
        for (t, b) in boxes.iter().enumerate() {
            let (l, h) = range(&this, b);
            for k in l[2]..=h[2] {
                for j in l[1]..=h[1] {
                    for i in l[0]..=h[0] {
                        let c = index([i, j, k]);
                        tets[fill[c]] = t as u32;
                        fill[c] += 1;
                    }
                }
            }
        }
        this.cell_start = start;
        this.tets = tets;
        this
    }

    fn cell_of(&self, x_m: [f64; 3]) -> [usize; 3] {
        [0, 1, 2].map(|k| (((x_m[k] - self.origin_m[k]) / self.cell_m).floor().max(0.0) as usize).min(self.n_cells[k] - 1))
    }

    /// Calls `visit` once for every tetrahedron whose bucket cells meet the cells of the box
    /// `[lo_m, hi_m]`: every tetrahedron that meets the box, and some near it. A tetrahedron in
    /// several cells is visited from the first of its cells inside the box only, so nothing is
    /// visited twice and nothing is allocated.
    pub fn for_each_tet_near_box(&self, mesh: &TetMesh, lo_m: [f64; 3], hi_m: [f64; 3], mut visit: impl FnMut(usize)) {
        let l = self.cell_of(lo_m);
        let h = self.cell_of(hi_m);
        for k in l[2]..=h[2] {
            for j in l[1]..=h[1] {
                for i in l[0]..=h[0] {
                    let cell = i + self.n_cells[0] * (j + self.n_cells[1] * k);
                    for &t in &self.tets[self.cell_start[cell]..self.cell_start[cell + 1]] {
                        let (tl, _) = self.cells_of_box(&tet_box(mesh, t as usize));
                        if [tl[0].max(l[0]), tl[1].max(l[1]), tl[2].max(l[2])] == [i, j, k] {
                            visit(t as usize);
                        }
                    }
                }
            }
        }
    }

    /// The first and last cells of a tetrahedron's bounding box, widened by the location
    /// tolerance's worth of its extent (so a point on a cell border finds every tetrahedron that
    /// may hold it).
    fn cells_of_box(&self, b: &([f64; 3], [f64; 3])) -> ([usize; 3], [usize; 3]) {
        let pad = 1e-9 * (0..3).map(|k| b.1[k] - b.0[k]).fold(0.0, f64::max);
        (self.cell_of(b.0.map(|v| v - pad)), self.cell_of(b.1.map(|v| v + pad)))
    }

    /// The tetrahedron holding `x_m` and the barycentric weights of its nodes. Errors when the
    /// point is outside the mesh or not finite. Allocates nothing.
    pub fn locate(&self, mesh: &TetMesh, x_m: [f64; 3]) -> Result<PointLocation, LocateError> {
        if !x_m.iter().all(|v| v.is_finite()) {
            return Err(LocateError::NonFinite { x_m });
        }
        let c = self.cell_of(x_m);
        let cell = c[0] + self.n_cells[0] * (c[1] + self.n_cells[1] * c[2]);
        let mut best: Option<(f64, usize, [f64; 4])> = None;
        for &t in &self.tets[self.cell_start[cell]..self.cell_start[cell + 1]] {
            let t = t as usize;
            let w = barycentric(mesh.tet_points_m(t), x_m);
            let worst = w.iter().copied().fold(f64::INFINITY, f64::min);
            // Candidates come in increasing tetrahedron order: ties keep the first.
            if best.is_none_or(|(b, bt, _)| worst > b || (worst == b && t < bt)) {
                best = Some((worst, t, w));
            }
        }
        match best {
            Some((worst, tet_idx, weights)) if worst >= -BARYCENTRIC_TOL => {
                Ok(PointLocation { tet_idx, nodes: mesh.tets()[tet_idx], weights })
            }
            _ => Err(LocateError::Outside { x_m }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    #[test]
    fn random_points_are_found_with_weights_that_reproduce_them() {
        // A distorted grid, so that tetrahedra are not axis-aligned.
        let m = BoxGridParams::new([6, 5, 7], [0.1, 0.08, 0.12]).build(&TetMeshLimits::default()).unwrap();
        let mut nodes = m.nodes_m().to_vec();
        let mut rng = SmallRng::seed_from_u64(16);
        let (lo, hi) = m.bounding_box_m();
        for p in nodes.iter_mut() {
            for k in 0..3 {
                if p[k] > lo[k] + 1e-12 && p[k] < hi[k] - 1e-12 {
                    p[k] += rng.random_range(-0.002..0.002);
                }
            }
        }
        let m = TetMesh::new(nodes, m.tets().to_vec(), &TetMeshLimits::default()).unwrap();
        let loc = TetLocator::new(&m);
        for _ in 0..2000 {
            let x = [0, 1, 2].map(|k| rng.random_range(lo[k]..hi[k]));
            let p = loc.locate(&m, x).unwrap();
            let sum: f64 = p.weights.iter().sum();
            assert!((sum - 1.0).abs() < 1e-12, "weights sum to {sum}");
            assert!(p.weights.iter().all(|&w| w >= -BARYCENTRIC_TOL), "{p:?}");
            // The weights interpolate the point itself.
            for k in 0..3 {
                let xi: f64 = (0..4).map(|i| p.weights[i] * m.nodes_m()[p.nodes[i]][k]).sum();
                assert!((xi - x[k]).abs() < 1e-14, "axis {k}: {xi} vs {}", x[k]);
            }
            // No other tetrahedron holds it better (brute force).
            let best = (0..m.n_tets())
                .map(|t| barycentric(m.tet_points_m(t), x).iter().copied().fold(f64::INFINITY, f64::min))
                .fold(f64::NEG_INFINITY, f64::max);
            let got = p.weights.iter().copied().fold(f64::INFINITY, f64::min);
            assert_eq!(got, best);
        }
        // Nodes are found too (weight 1 at the node).
        let p = loc.locate(&m, m.nodes_m()[37]).unwrap();
        let k = p.nodes.iter().position(|&n| n == 37).unwrap();
        assert!((p.weights[k] - 1.0).abs() < 1e-12);
        assert_eq!(loc.locate(&m, [0.2, 0.0, 0.0]).unwrap_err(), LocateError::Outside { x_m: [0.2, 0.0, 0.0] });
        assert!(matches!(loc.locate(&m, [f64::NAN, 0.0, 0.0]).unwrap_err(), LocateError::NonFinite { .. }));
    }
}
