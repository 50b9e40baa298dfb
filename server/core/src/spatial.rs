//! A uniform bucket grid over the reference node positions, for finding the nodes near the needle
//! tip without scanning the mesh. Built once; queries write into a caller-owned buffer.

/// Nodes bucketed by cell, in compressed (CSR) form.
#[derive(Debug, Clone)]
pub struct NodeGrid {
    origin_m: [f64; 2],
    cell_m: f64,
    n_cells: [usize; 2],
    cell_start: Vec<usize>,
    nodes: Vec<usize>,
}

impl NodeGrid {
    /// Buckets `points_m` into square cells of side `cell_m` (> 0).
    pub fn new(points_m: &[[f64; 2]], cell_m: f64) -> Self {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in points_m {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        // At most ~4 cells per point keeps memory linear whatever cell size is asked for.
        let area = ((hi[0] - lo[0]) * (hi[1] - lo[1])).max(0.0);
        let min_cell = (area / (4.0 * points_m.len().max(1) as f64)).sqrt();
        let cell_m = cell_m.max(min_cell).max(1e-12);
        let n_cells = [((hi[0] - lo[0]) / cell_m) as usize + 1, ((hi[1] - lo[1]) / cell_m) as usize + 1];
        let cell_of = |p: &[f64; 2]| {
            let i = (((p[0] - lo[0]) / cell_m) as usize).min(n_cells[0] - 1);
            let j = (((p[1] - lo[1]) / cell_m) as usize).min(n_cells[1] - 1);
            j * n_cells[0] + i
        };
        let total = n_cells[0] * n_cells[1];
        let mut count = vec![0usize; total + 1];
        for p in points_m {
            count[cell_of(p) + 1] += 1;
        }
        for c in 0..total {
            count[c + 1] += count[c];
        }
        let cell_start = count.clone();
        let mut fill = count;
        let mut nodes = vec![0; points_m.len()];
        for (idx, p) in points_m.iter().enumerate() {
            let c = cell_of(p);
            nodes[fill[c]] = idx;
            fill[c] += 1;
        }
        Self { origin_m: lo, cell_m, n_cells, cell_start, nodes }
    }

    /// Appends to `out` the nodes in all cells that overlap the square of half-side `radius_m`
    /// around `center_m` (a superset of the nodes within `radius_m`). Allocates nothing when
    /// `out` has capacity.
    pub fn query_into(&self, center_m: [f64; 2], radius_m: f64, out: &mut Vec<usize>) {
        let range = |k: usize| {
            let lo = ((center_m[k] - radius_m - self.origin_m[k]) / self.cell_m).floor();
            let hi = ((center_m[k] + radius_m - self.origin_m[k]) / self.cell_m).floor();
            if !(hi >= 0.0) || !(lo < self.n_cells[k] as f64) {
                return None;
            }
            Some((lo.max(0.0) as usize, (hi as usize).min(self.n_cells[k] - 1)))
        };
        let (Some((i0, i1)), Some((j0, j1))) = (range(0), range(1)) else { return };
        for j in j0..=j1 {
            for i in i0..=i1 {
                let c = j * self.n_cells[0] + i;
                out.extend_from_slice(&self.nodes[self.cell_start[c]..self.cell_start[c + 1]]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    #[test]
    fn query_finds_every_node_within_radius() {
        let mut rng = SmallRng::seed_from_u64(7);
        let pts: Vec<[f64; 2]> = (0..2000).map(|_| [rng.random_range(0.0..0.1), rng.random_range(0.0..0.05)]).collect();
        let grid = NodeGrid::new(&pts, 0.004);
        let mut out = Vec::new();
        for _ in 0..200 {
            let c = [rng.random_range(-0.01..0.11), rng.random_range(-0.01..0.06)];
            let r = rng.random_range(0.0..0.01);
            out.clear();
            grid.query_into(c, r, &mut out);
            for (i, p) in pts.iter().enumerate() {
                if (p[0] - c[0]).hypot(p[1] - c[1]) <= r {
                    assert!(out.contains(&i), "node {i} missed");
                }
            }
            // The covered cells span at most (2r + 2 cell)² = 0.028² m² at 4e5 points/m².
            assert!(out.len() < 400, "query should be local, got {}", out.len());
        }
    }
}
