//! The 3D pieces of assembly: isotropic 3D Hooke's law, the linear 4-node tetrahedron's
//! shape-function gradients and $B$, and [`TetMaterials`] (validated for 3D). $K_e$, the sparse
//! stiffness $K$ ($3n \times 3n$) and element stresses are the generic ones of
//! [`crate::assembly`] (re-exported here under their former paths).
//!
//! Voigt order $[\sigma_{xx}, \sigma_{yy}, \sigma_{zz}, \sigma_{yz}, \sigma_{xz}, \sigma_{xy}] = D\,
//! [\varepsilon_{xx}, \varepsilon_{yy}, \varepsilon_{zz}, \gamma_{yz}, \gamma_{xz}, \gamma_{xy}]$ with
//! engineering shear $\gamma_{ij} = 2\varepsilon_{ij}$, $\sigma = 2\mu\varepsilon + \lambda\,\mathrm{tr}(\varepsilon) I$,
//! $\mu = E / (2(1+\nu))$, $\lambda = E\nu / ((1+\nu)(1-2\nu))$; so $D_{ij} = \lambda + 2\mu\delta_{ij}$
//! for $i, j < 3$ and $D_{kk} = \mu$ for the shears.
//!
//! For a tetrahedron with corners $x_0..x_3$, $J = [x_1 - x_0,\ x_2 - x_0,\ x_3 - x_0]$ (columns),
//! the gradients of the shape functions are $\nabla N_k = (J^{-1})_{k-1,:}$ for $k = 1..3$ and
//! $\nabla N_0 = -\sum_k \nabla N_k$; $V = |\det J| / 6$. With $g = \nabla N_i$, node $i$'s block of
//! $B$ (6 × 3) is $\begin{bmatrix} g_x&0&0\\0&g_y&0\\0&0&g_z\\0&g_z&g_y\\g_z&0&g_x\\g_y&g_x&0\end{bmatrix}$ and
//! $K_e = V B^\top D B$ (12 × 12). DOFs $[u_{x0}, u_{y0}, u_{z0}, u_{x1}, \dots]$.

use faer::sparse::SparseColMat;

use super::mesh::TetMesh;
use crate::assembly::{ElementMaterials, assemble_stiffness_with};
pub use crate::assembly::{element_b, element_stiffness, element_stresses_pa};
use crate::dim::{Dim, Dim3};
use crate::material::Material;

/// Errors in 3D material parameters, naming the region or element.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TetMaterialError {
    /// Young's modulus is not finite, positive and at most
    /// [`crate::sim::param_limits::MAX_YOUNG_MODULUS_PA`] (the 2D bound).
    #[error("{item}: Young's modulus E = {} Pa must be finite, > 0 and ≤ {:e} Pa", crate::num::num(*young_modulus_pa), crate::sim::param_limits::MAX_YOUNG_MODULUS_PA)]
    YoungModulus { item: String, young_modulus_pa: f64 },
    /// Poisson's ratio is outside (−1, 0.5) (ν = 0.5, incompressible, makes λ infinite).
    #[error("{item}: Poisson ratio ν = {} must be finite and in (−1, 0.5) in 3D (ν = 0.5 makes λ infinite)", crate::num::num(*poisson_ratio))]
    PoissonRatio { item: String, poisson_ratio: f64 },
    /// The number of materials does not match the regions (or tetrahedra) of the mesh.
    #[error("the mesh has {expected} {what} but {n_materials} material(s) were given")]
    Count { what: &'static str, expected: usize, n_materials: usize },
}

/// Checks E and ν for 3D; `item` names the region or element in the error.
pub fn validate_material(m: &Material, item: &str) -> Result<(), TetMaterialError> {
    let (e, nu) = (m.young_modulus_pa, m.poisson_ratio);
    if !(e.is_finite() && e > 0.0 && e <= crate::sim::param_limits::MAX_YOUNG_MODULUS_PA) {
        return Err(TetMaterialError::YoungModulus { item: item.to_owned(), young_modulus_pa: e });
    }
    if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
        return Err(TetMaterialError::PoissonRatio { item: item.to_owned(), poisson_ratio: nu });
    }
    Ok(())
}

/// The 3D Lamé parameters $(\lambda, \mu)$ in Pa.
pub fn lame_pa(m: &Material) -> (f64, f64) {
    let (e, nu) = (m.young_modulus_pa, m.poisson_ratio);
    (e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu)))
}

/// The 6 × 6 elasticity matrix $D$ in Voigt order (module docs), in Pa.
pub fn d_matrix(m: &Material) -> [[f64; 6]; 6] {
    let (lam, mu) = lame_pa(m);
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            d[i][j] = lam;
        }
        d[i][i] += 2.0 * mu;
        d[i + 3][i + 3] = mu;
    }
    d
}

/// A material per tetrahedron (expanded from regions, or given per element), validated for 3D.
pub type TetMaterials = ElementMaterials<Dim3>;

impl TetMaterials {
    /// One material per region of `mesh`; errors name the region as `region <name>`.
    pub fn per_region(mesh: &TetMesh, materials: &[Material]) -> Result<Self, TetMaterialError> {
        let n_regions = mesh.region_names().len();
        if materials.len() != n_regions {
            return Err(TetMaterialError::Count { what: "region(s)", expected: n_regions, n_materials: materials.len() });
        }
        for (m, name) in materials.iter().zip(mesh.region_names()) {
            validate_material(m, &format!("region {name}"))?;
        }
        Ok(Self::from_parts(mesh.region_of_tet().iter().map(|&r| materials[r]).collect(), ()))
    }

    /// One material per tetrahedron; errors name it as `element <index>`.
    pub fn per_element(mesh: &TetMesh, material_of_tet: Vec<Material>) -> Result<Self, TetMaterialError> {
        if material_of_tet.len() != mesh.n_tets() {
            return Err(TetMaterialError::Count { what: "tetrahedra", expected: mesh.n_tets(), n_materials: material_of_tet.len() });
        }
        for (i, m) in material_of_tet.iter().enumerate() {
            validate_material(m, &format!("element {i}"))?;
        }
        Ok(Self::from_parts(material_of_tet, ()))
    }

    /// The material of each tetrahedron.
    pub fn material_of_tet(&self) -> &[Material] {
        self.material_of_element()
    }
}

/// The shape-function gradients $\nabla N_i$ (rows, in 1/m) of a tetrahedron with corners `p`,
/// and its volume $|V|$ in m³.
pub fn shape_gradients(p: [[f64; 3]; 4]) -> ([[f64; 3]; 4], f64) {
    // J columns: edges from corner 0.
    let e = [1, 2, 3].map(|k| [p[k][0] - p[0][0], p[k][1] - p[0][1], p[k][2] - p[0][2]]);
    // J[r][c] = e[c][r]
    let j = |r: usize, c: usize| e[c][r];
    let det = j(0, 0) * (j(1, 1) * j(2, 2) - j(1, 2) * j(2, 1)) - j(0, 1) * (j(1, 0) * j(2, 2) - j(1, 2) * j(2, 0))
        + j(0, 2) * (j(1, 0) * j(2, 1) - j(1, 1) * j(2, 0));
    // inv(J) = adj(J) / det; row k of inv(J) is grad N_{k+1}.
    let mut inv = [[0.0; 3]; 3];
    for r in 0..3 {
        for c in 0..3 {
            // cofactor of J[c][r]
            let (r1, r2) = ([1, 0, 0][c], [2, 2, 1][c]);
            let (c1, c2) = ([1, 0, 0][r], [2, 2, 1][r]);
            let minor = j(r1, c1) * j(r2, c2) - j(r1, c2) * j(r2, c1);
            let sign = if (r + c) % 2 == 0 { 1.0 } else { -1.0 };
            inv[r][c] = sign * minor / det;
        }
    }
    let mut g = [[0.0; 3]; 4];
    for k in 0..3 {
        g[k + 1] = inv[k];
        for a in 0..3 {
            g[0][a] -= inv[k][a];
        }
    }
    (g, det.abs() / 6.0)
}

/// The strain–displacement matrix $B$ (6 × 12) of the tetrahedron with corners `p` (module
/// docs) and its volume in m³.
pub fn tetrahedron_b(p: &[[f64; 3]; 4]) -> ([[f64; 12]; 6], f64) {
    let (g, vol) = shape_gradients(*p);
    let mut b = [[0.0; 12]; 6];
    for (i, gi) in g.iter().enumerate() {
        let [gx, gy, gz] = *gi;
        let c = 3 * i;
        b[0][c] = gx;
        b[1][c + 1] = gy;
        b[2][c + 2] = gz;
        b[3][c + 1] = gz;
        b[3][c + 2] = gy;
        b[4][c] = gz;
        b[4][c + 2] = gx;
        b[5][c] = gy;
        b[5][c + 1] = gx;
    }
    (b, vol)
}

/// The DOFs of a tetrahedron's nodes, $[3a, 3a+1, 3a+2, 3b, \dots]$.
pub fn tet_dofs(tet: &[usize; 4]) -> [usize; 12] {
    Dim3::element_dofs(tet)
}

/// Assembles the full $3n \times 3n$ stiffness (both triangles stored).
pub fn assemble_stiffness(mesh: &TetMesh, materials: &TetMaterials) -> SparseColMat<usize, f64> {
    assemble_stiffness_with(mesh, materials, |_, _| {})
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use nalgebra::{DMatrix, SymmetricEigen};

    fn one_tet() -> TetMesh {
        let nodes = vec![[0.01, 0.0, 0.002], [0.03, 0.004, 0.0], [0.005, 0.02, 0.001], [0.012, 0.007, 0.025]];
        TetMesh::new(nodes, vec![[0, 1, 2, 3]], &TetMeshLimits::default()).unwrap()
    }

    #[test]
    fn element_stiffness_is_symmetric_with_a_six_dimensional_null_space() {
        let mesh = one_tet();
        let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }]).unwrap();
        let ke = element_stiffness(&mesh, &mats, 0);
        let scale = (0..12).map(|i| ke[i][i]).fold(0.0, f64::max);
        for i in 0..12 {
            for j in 0..12 {
                assert!((ke[i][j] - ke[j][i]).abs() < 1e-13 * scale, "({i}, {j})");
            }
        }
        let eig = SymmetricEigen::new(DMatrix::from_fn(12, 12, |i, j| ke[i][j]));
        let zero = eig.eigenvalues.iter().filter(|&&l| l.abs() < 1e-10 * scale).count();
        let positive = eig.eigenvalues.iter().filter(|&&l| l > 1e-10 * scale).count();
        assert_eq!((zero, positive), (6, 6), "eigenvalues {:?}", eig.eigenvalues);
        // The rigid motions (3 translations, 3 rotations) are in the null space.
        let p = mesh.tet_points_m(0);
        for mode in 0..6 {
            let u: Vec<f64> = (0..12)
                .map(|k| {
                    let (node, axis) = (k / 3, k % 3);
                    if mode < 3 {
                        if axis == mode { 1.0 } else { 0.0 }
                    } else {
                        // rotation about axis (mode - 3): w × x
                        let mut w = [0.0; 3];
                        w[mode - 3] = 1.0;
                        let x = p[node];
                        let r = [w[1] * x[2] - w[2] * x[1], w[2] * x[0] - w[0] * x[2], w[0] * x[1] - w[1] * x[0]];
                        r[axis]
                    }
                })
                .collect();
            for i in 0..12 {
                let f: f64 = (0..12).map(|j| ke[i][j] * u[j]).sum();
                assert!(f.abs() < 1e-12 * scale, "mode {mode}: force {f}");
            }
        }
    }

    /// The patch test: on a distorted mesh, nodal displacements of a linear field give its
    /// constant strain in every element and zero force at every interior node.
    #[test]
    fn patch_test_reproduces_a_linear_field_on_a_distorted_mesh() {
        let grid = BoxGridParams::new([4, 4, 4], [1.0, 1.0, 1.0]).build(&TetMeshLimits::default()).unwrap();
        let mut nodes = grid.nodes_m().to_vec();
        for (i, p) in nodes.iter_mut().enumerate() {
            if p.iter().all(|&v| v > 1e-9 && v < 1.0 - 1e-9) {
                let s = (i as f64 * 0.7).sin();
                p[0] += 0.08 * s;
                p[1] -= 0.06 * (i as f64 * 1.3).cos();
                p[2] += 0.05 * s * s;
            }
        }
        let mesh = TetMesh::new(nodes, grid.tets().to_vec(), &TetMeshLimits::default()).unwrap();
        let mat = Material { young_modulus_pa: 1000.0, poisson_ratio: 0.3 };
        let mats = TetMaterials::per_region(&mesh, &[mat]).unwrap();
        let a = [[1e-3, 2e-3, -5e-4], [3e-4, -1e-3, 7e-4], [-2e-4, 6e-4, 1.5e-3]];
        let u: Vec<f64> = mesh.nodes_m().iter().flat_map(|x| (0..3).map(move |r| (0..3).map(|c| a[r][c] * x[c]).sum::<f64>())).collect();
        let strain = [a[0][0], a[1][1], a[2][2], a[1][2] + a[2][1], a[0][2] + a[2][0], a[0][1] + a[1][0]];
        let d = d_matrix(&mat);
        let sigma: [f64; 6] = std::array::from_fn(|i| (0..6).map(|k| d[i][k] * strain[k]).sum());
        for s in element_stresses_pa(&mesh, &mats, &u) {
            for i in 0..6 {
                assert!((s[i] - sigma[i]).abs() < 1e-12 * 10.0, "{s:?} vs {sigma:?}");
            }
        }
        let k = assemble_stiffness(&mesh, &mats);
        let mut f = vec![0.0; u.len()];
        crate::assembly::mul_stiffness(&k, &u, &mut f);
        for (node, p) in mesh.nodes_m().iter().enumerate() {
            if p.iter().all(|&v| v > 1e-9 && v < 1.0 - 1e-9) {
                for axis in 0..3 {
                    assert!(f[3 * node + axis].abs() < 1e-13, "interior node {node}: {}", f[3 * node + axis]);
                }
            }
        }
    }

    #[test]
    fn materials_are_checked_and_named() {
        let mesh = one_tet();
        let e = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 1.0, poisson_ratio: 0.5 }]).unwrap_err();
        assert!(e.to_string().starts_with("region tissue: Poisson ratio"), "{e}");
        let e = TetMaterials::per_element(&mesh, vec![Material { young_modulus_pa: -1.0, poisson_ratio: 0.3 }]).unwrap_err();
        assert!(e.to_string().starts_with("element 0: Young's modulus"), "{e}");
    }
}
