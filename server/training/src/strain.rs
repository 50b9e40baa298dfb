//! Tissue strain of a 2D exercise from the displacement field: per linear triangle the small
//! strain of the FE model, an equivalent strain, and the area above a damage threshold
//! ([`StrainField`]; metrics.rs for how the tracker accumulates it).
//!
//! A linear triangle $e$ with nodes $a, b, c$ at reference positions $X_a, X_b, X_c$ has the
//! constant displacement gradient $\nabla u = \sum_{i\in\{a,b,c\}} u_i \otimes \nabla N_i$ with
//! $\nabla N_a = \frac{1}{2A_e}\,(y_b - y_c,\; x_c - x_b)$ (and cyclically), $A_e$ its area; its
//! small strain $\varepsilon = \tfrac12(\nabla u + \nabla u^\top)$ (the linear model's own).
//! The **equivalent strain** is the largest principal strain in magnitude,
//! $$\varepsilon_{eq} = \Big|\tfrac{\varepsilon_{xx}+\varepsilon_{yy}}{2}\Big| + \sqrt{\Big(\tfrac{\varepsilon_{xx}-\varepsilon_{yy}}{2}\Big)^2 + \varepsilon_{xy}^2}$$
//! (tension or compression alike), and a sample's **damaged area** above the threshold $\varepsilon_d$ is
//! $A_d = \sum_{e:\ \varepsilon_{eq,e} > \varepsilon_d} A_e$.

/// A sample's strain: the largest equivalent strain over the tissue and the area above the threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrainSummary {
    /// $\max_e \varepsilon_{eq,e}$ (dimensionless).
    pub max_strain: f64,
    /// $A_d$, m².
    pub area_above_m2: f64,
    /// The threshold $\varepsilon_d$ it was evaluated for.
    pub damage_strain: f64,
}

/// The reference geometry of a 2D mesh's triangles and a displacement buffer (sized once).
#[derive(Debug, Clone)]
pub struct StrainField {
    triangles: Vec<[usize; 3]>,
    /// Per triangle, $\nabla N_i$ of its three nodes.
    grads: Vec<[[f64; 2]; 3]>,
    area_m2: Vec<f64>,
    /// Nodal displacements, $u_{2i+c}$, m.
    u_m: Vec<f64>,
}

/// $\varepsilon_{eq}$ of a strain tensor (module docs).
pub fn equivalent_strain(exx: f64, eyy: f64, exy: f64) -> f64 {
    let m = 0.5 * (exx + eyy);
    let r = (0.25 * (exx - eyy).powi(2) + exy * exy).sqrt();
    m.abs() + r
}

impl StrainField {
    /// For a mesh of `nodes_m` and counter-clockwise or clockwise `triangles` (degenerate ones
    /// are skipped: they carry no area).
    pub fn new(nodes_m: &[[f64; 2]], triangles: &[[usize; 3]]) -> Self {
        let mut tris = Vec::with_capacity(triangles.len());
        let mut grads = Vec::with_capacity(triangles.len());
        let mut area = Vec::with_capacity(triangles.len());
        for t in triangles {
            let [a, b, c] = [nodes_m[t[0]], nodes_m[t[1]], nodes_m[t[2]]];
            let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            if det.abs() <= f64::MIN_POSITIVE {
                continue;
            }
            let g = |p: [f64; 2], q: [f64; 2]| [(p[1] - q[1]) / det, (q[0] - p[0]) / det];
            tris.push(*t);
            grads.push([g(b, c), g(c, a), g(a, b)]);
            area.push(0.5 * det.abs());
        }
        Self { triangles: tris, grads, area_m2: area, u_m: vec![0.0; 2 * nodes_m.len()] }
    }

    /// The nodal displacement buffer to fill ($2n$ values, $u_{2i+c}$).
    pub fn displacements_mut(&mut self) -> &mut [f64] {
        &mut self.u_m
    }

    /// The triangles kept (non-degenerate), in the mesh's order.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Triangle `e`'s small strain $(\varepsilon_{xx}, \varepsilon_{yy}, \varepsilon_{xy})$.
    pub fn triangle_strain(&self, e: usize) -> [f64; 3] {
        let (t, g) = (&self.triangles[e], &self.grads[e]);
        let mut du = [[0.0; 2]; 2];
        for (&n, gk) in t.iter().zip(g) {
            for (c, row) in du.iter_mut().enumerate() {
                for (d, v) in row.iter_mut().enumerate() {
                    *v += self.u_m[2 * n + c] * gk[d];
                }
            }
        }
        [du[0][0], du[1][1], 0.5 * (du[0][1] + du[1][0])]
    }

    /// The summary over every triangle for the threshold `damage_strain` (no allocation).
    pub fn evaluate(&self, damage_strain: f64) -> StrainSummary {
        let mut s = StrainSummary { max_strain: 0.0, area_above_m2: 0.0, damage_strain };
        for e in 0..self.triangles.len() {
            let [xx, yy, xy] = self.triangle_strain(e);
            let eq = equivalent_strain(xx, yy, xy);
            s.max_strain = s.max_strain.max(eq);
            if eq > damage_strain {
                s.area_above_m2 += self.area_m2[e];
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use needlesim_core::mesh::{MeshLimits, RectMeshParams};

    /// A linear displacement $u = G X$ strains every triangle alike: $\varepsilon = \mathrm{sym}(G)$.
    #[test]
    fn a_uniform_strain_is_recovered_in_every_triangle() {
        let mesh = RectMeshParams::new(7, 5, 0.06, 0.04).build(&MeshLimits::default()).unwrap();
        let mut f = StrainField::new(mesh.nodes_m(), mesh.triangles());
        let g = [[0.03, 0.02], [-0.01, -0.05]];
        for (i, x) in mesh.nodes_m().iter().enumerate() {
            let u = f.displacements_mut();
            u[2 * i] = g[0][0] * x[0] + g[0][1] * x[1] + 1e-3;
            u[2 * i + 1] = g[1][0] * x[0] + g[1][1] * x[1] - 2e-3;
        }
        let want = [0.03, -0.05, 0.5 * (0.02 - 0.01)];
        for e in 0..f.triangles().len() {
            let s = f.triangle_strain(e);
            for c in 0..3 {
                assert!((s[c] - want[c]).abs() < 1e-12, "triangle {e}: {s:?} vs {want:?}");
            }
        }
        // Principal strains of [[0.03, 0.005], [0.005, -0.05]]: -0.01 ± sqrt(0.04² + 0.005²).
        let eq = 0.01 + (0.04f64.powi(2) + 0.005f64.powi(2)).sqrt();
        let s = f.evaluate(0.04);
        assert!((s.max_strain - eq).abs() < 1e-12, "{} vs {eq}", s.max_strain);
        assert!((s.area_above_m2 - 0.06 * 0.04).abs() < 1e-15, "the whole block: {}", s.area_above_m2);
        assert_eq!(f.evaluate(eq + 1e-9).area_above_m2, 0.0);
        // A rigid translation and a small rotation strain nothing (to first order: none exactly).
        for (i, _) in mesh.nodes_m().iter().enumerate() {
            let u = f.displacements_mut();
            u[2 * i] = 0.004;
            u[2 * i + 1] = -0.002;
        }
        assert_eq!(f.evaluate(0.0).max_strain, 0.0);
    }

    #[test]
    fn only_the_strained_triangles_count_in_the_area() {
        // Two triangles of a unit square; stretch only node 2 (shared by the second triangle only).
        let nodes = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut f = StrainField::new(&nodes, &[[0, 1, 3], [1, 2, 3]]);
        f.displacements_mut()[4] = 0.1; // node 2, x
        // Triangle 1: ∂u_x/∂x = 0.1 (node 2 at x = 1, nodes 1 and 3 fixed): ε_xx = 0.1, ε_xy = 0.05.
        assert_eq!(f.triangle_strain(0), [0.0, 0.0, 0.0]);
        let s = f.triangle_strain(1);
        assert!((s[0] - 0.1).abs() < 1e-15 && s[1].abs() < 1e-15 && (s[2] - 0.05).abs() < 1e-15, "{s:?}");
        let r = f.evaluate(0.01);
        assert_eq!(r.area_above_m2, 0.5);
        assert!((r.max_strain - (0.05 + (0.05f64.powi(2) + 0.05f64.powi(2)).sqrt())).abs() < 1e-15);
    }
}
