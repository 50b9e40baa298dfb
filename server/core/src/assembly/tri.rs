//! The 2D pieces of assembly: the linear triangle's $B$, [`MaterialMap`] (materials under a plane
//! model), and the stiffness with node DOFs in rotated frames. The generic part is in
//! [`super`].
//!
//! For a triangle with vertices $(x_k, y_k)$ and signed doubled area
//! $2A = (x_2-x_1)(y_3-y_1)-(x_3-x_1)(y_2-y_1)$, the strain–displacement matrix is
//! $B = \frac{1}{2A}\begin{bmatrix} b_1 & 0 & b_2 & 0 & b_3 & 0\\ 0 & c_1 & 0 & c_2 & 0 & c_3\\ c_1 & b_1 & c_2 & b_2 & c_3 & b_3\end{bmatrix}$
//! with $b = (y_2-y_3, y_3-y_1, y_1-y_2)$, $c = (x_3-x_2, x_1-x_3, x_2-x_1)$; the signed area
//! makes clockwise triangles correct too. The element stiffness is $K_e = t\,|A|\,B^\top D B$.

use faer::sparse::SparseColMat;

use super::{ElementMaterials, assemble_stiffness_with, rotate_element_node};
use crate::material::{Material, MaterialError, PlaneModel};
use crate::mesh::{Dim2, Mesh};

/// Materials per triangle under a plane model: everything besides the mesh that the 2D $K$
/// depends on.
pub type MaterialMap = ElementMaterials<Dim2>;

impl MaterialMap {
    /// One material per region of `mesh`, validated.
    pub fn per_region(mesh: &Mesh, materials: &[Material], plane: PlaneModel) -> Result<Self, MaterialError> {
        plane.validate()?;
        let n_regions = mesh.region_names().len();
        if materials.len() != n_regions {
            return Err(MaterialError::Count { n_regions, n_materials: materials.len() });
        }
        for (m, name) in materials.iter().zip(mesh.region_names()) {
            m.validate(plane, &format!("region {name}"))?;
        }
        let material_of_tri = mesh.region_of_tri().iter().map(|&r| materials[r]).collect();
        Ok(Self::from_parts(material_of_tri, plane))
    }

    /// One material per triangle, validated; errors name the triangle as `element N`.
    pub fn per_element(mesh: &Mesh, material_of_tri: Vec<Material>, plane: PlaneModel) -> Result<Self, MaterialError> {
        plane.validate()?;
        if material_of_tri.len() != mesh.n_triangles() {
            return Err(MaterialError::Count { n_regions: mesh.n_triangles(), n_materials: material_of_tri.len() });
        }
        for (i, m) in material_of_tri.iter().enumerate() {
            m.validate(plane, &format!("element {i}"))?;
        }
        Ok(Self::from_parts(material_of_tri, plane))
    }

    /// The plane model.
    pub fn plane(&self) -> PlaneModel {
        self.model()
    }
    /// The material of each triangle.
    pub fn material_of_tri(&self) -> &[Material] {
        self.material_of_element()
    }
}

/// The strain–displacement matrix $B$ (3 × 6) of the triangle with corners `p` and its unsigned
/// area $|A|$ in m² (module docs).
pub fn triangle_b(p: &[[f64; 2]; 3]) -> ([[f64; 6]; 3], f64) {
    let [p1, p2, p3] = *p;
    let a2 = (p2[0] - p1[0]) * (p3[1] - p1[1]) - (p3[0] - p1[0]) * (p2[1] - p1[1]);
    let b = [(p2[1] - p3[1]) / a2, (p3[1] - p1[1]) / a2, (p1[1] - p2[1]) / a2];
    let c = [(p3[0] - p2[0]) / a2, (p1[0] - p3[0]) / a2, (p2[0] - p1[0]) / a2];
    let mut bm = [[0.0; 6]; 3];
    for k in 0..3 {
        bm[0][2 * k] = b[k];
        bm[1][2 * k + 1] = c[k];
        bm[2][2 * k] = c[k];
        bm[2][2 * k + 1] = b[k];
    }
    (bm, 0.5 * a2.abs())
}

/// Assembles the full $2n \times 2n$ stiffness (both triangles stored), optionally with node
/// DOFs in rotated local frames: where `node_angle_rad[i]` is `Some(a)`, node $i$'s DOFs are
/// $(u_t, u_n)$ with $t = (\cos a, \sin a)$, $n = (-\sin a, \cos a)$, i.e.
/// $K_{loc} = T^\top K T$ with $u = T u_{loc}$.
pub fn assemble_stiffness(mesh: &Mesh, materials: &MaterialMap, node_angle_rad: Option<&[Option<f64>]>) -> SparseColMat<usize, f64> {
    assemble_stiffness_with(mesh, materials, |tri, ke| {
        if let Some(angles) = node_angle_rad {
            for (k, &node) in tri.iter().enumerate() {
                if let Some(a) = angles[node] {
                    rotate_element_node::<Dim2>(ke, k, &crate::statics::tri::frame_rows(a));
                }
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::mul_stiffness;
    use crate::mesh::{MeshLimits, RectMeshParams};

    fn unit_square_materials(mesh: &Mesh) -> MaterialMap {
        MaterialMap::per_region(mesh, &[Material { young_modulus_pa: 1000.0, poisson_ratio: 0.3 }], PlaneModel::Stress { thickness_m: 0.5 })
            .unwrap()
    }

    #[test]
    fn rigid_motions_give_no_force_and_k_is_symmetric() {
        let mesh = RectMeshParams::new(4, 3, 2.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = unit_square_materials(&mesh);
        let k = assemble_stiffness(&mesh, &mats, None);
        let n = mesh.n_nodes();
        let mut y = vec![0.0; 2 * n];
        let scale = k.val().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for mode in 0..3 {
            let x: Vec<f64> = (0..2 * n)
                .map(|d| {
                    let p = mesh.nodes_m()[d / 2];
                    match mode {
                        0 => (d % 2 == 0) as u8 as f64,
                        1 => (d % 2 == 1) as u8 as f64,
                        _ => {
                            if d % 2 == 0 {
                                -p[1]
                            } else {
                                p[0]
                            }
                        }
                    }
                })
                .collect();
            mul_stiffness(&k, &x, &mut y);
            assert!(y.iter().all(|v| v.abs() < 1e-12 * scale), "rigid mode {mode} gives forces");
        }
        let dense = k.to_dense();
        for i in 0..2 * n {
            for j in 0..2 * n {
                assert!((dense[(i, j)] - dense[(j, i)]).abs() <= 1e-13 * scale);
            }
        }
    }

    #[test]
    fn clockwise_element_equals_counter_clockwise() {
        let lim = MeshLimits::default();
        let nodes = vec![[0.0, 0.0], [1.0, 0.2], [0.3, 0.9]];
        let ccw = Mesh::new(nodes.clone(), vec![[0, 1, 2]], &lim).unwrap();
        let cw = Mesh::new(nodes, vec![[0, 2, 1]], &lim).unwrap();
        let kc = assemble_stiffness(&ccw, &unit_square_materials(&ccw), None).to_dense();
        let kw = assemble_stiffness(&cw, &unit_square_materials(&cw), None).to_dense();
        assert!((&kc - &kw).norm_max() < 1e-12 * kc.norm_max());
    }

    #[test]
    fn rotated_assembly_is_t_transpose_k_t() {
        let mesh = RectMeshParams::new(3, 3, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = unit_square_materials(&mesh);
        let mut angles = vec![None; mesh.n_nodes()];
        angles[4] = Some(0.7);
        angles[8] = Some(-2.1);
        let k = assemble_stiffness(&mesh, &mats, None).to_dense();
        let kl = assemble_stiffness(&mesh, &mats, Some(&angles)).to_dense();
        let nd = 2 * mesh.n_nodes();
        let mut t = faer::Mat::<f64>::identity(nd, nd);
        for (node, a) in angles.iter().enumerate() {
            if let Some(a) = a {
                let (s, c) = a.sin_cos();
                t[(2 * node, 2 * node)] = c;
                t[(2 * node, 2 * node + 1)] = -s;
                t[(2 * node + 1, 2 * node)] = s;
                t[(2 * node + 1, 2 * node + 1)] = c;
            }
        }
        let expect = t.transpose() * &k * &t;
        assert!((&expect - &kl).norm_max() < 1e-12 * k.norm_max());
    }
}
