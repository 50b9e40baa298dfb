//! Linear-simplex (constant-strain) element matrices, assembly of the sparse stiffness $K$ and
//! element stresses, written once for both dimensions over [`Dim`].
//!
//! For an element with strain–displacement matrix $B$ (Voigt rows × element DOFs; from the
//! shape-function gradients, constant over a linear simplex), material matrix $D$ and measure
//! $|V|$ (area or volume), the element stiffness is $K_e = w\,B^\top D B$ with the weight
//! $w = t\,|A|$ in 2D (the plane model's thickness $t$) and $w = |V|$ in 3D, and the element's
//! stress is $\sigma = D B u_e$. What differs per dimension is a method of [`Dim`]: $B$
//! ([`Dim::element_b`]: the triangle's in [`tri`], the tetrahedron's in
//! [`crate::d3::assembly`]), $D$ ([`Dim::d_matrix`]: plane strain or stress in
//! [`crate::material`], 3D Hooke in [`crate::d3::assembly`]) and the weight. DOFs are
//! interleaved: $[u_{x0}, u_{y0}, (u_{z0},) u_{x1}, \dots]$.
//!
//! The sums run in the order the former per-dimension code ran them (over the Voigt index,
//! ascending, from the iterator's zero), so $K$ and the stresses are bit-identical to before.

use faer::sparse::{SparseColMat, Triplet};

use crate::dim::Dim;
use crate::material::Material;
use crate::mesh::SimplexMesh;

pub mod tri;

pub use tri::{MaterialMap, assemble_stiffness};

/// A material per element (expanded from regions, or given per element) and the dimension's
/// material model besides E and ν (2D: the plane model; 3D: none): everything besides the mesh
/// that $K$ depends on. Built through [`MaterialMap`]'s or [`crate::d3::TetMaterials`]'s
/// constructors, which validate it for their dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementMaterials<D: Dim> {
    material_of_element: Vec<Material>,
    model: D::Model,
}

impl<D: Dim> ElementMaterials<D> {
    /// From already validated parts (the dimension's constructors check them first).
    pub(crate) fn from_parts(material_of_element: Vec<Material>, model: D::Model) -> Self {
        Self { material_of_element, model }
    }
    /// The material of each element.
    pub fn material_of_element(&self) -> &[Material] {
        &self.material_of_element
    }
    /// The dimension's material model besides E and ν.
    pub fn model(&self) -> D::Model {
        self.model
    }
    /// The material matrix $D$ of element `elem_idx`, in Pa.
    pub fn d_matrix(&self, elem_idx: usize) -> D::DMatrix {
        D::d_matrix(&self.material_of_element[elem_idx], &self.model)
    }
}

/// The strain–displacement matrix $B$ of element `elem_idx` and its unsigned measure (area in
/// m², volume in m³).
pub fn element_b<D: Dim>(mesh: &SimplexMesh<D>, elem_idx: usize) -> (D::BMatrix, f64) {
    D::element_b(&mesh.element_points_m(elem_idx))
}

/// The element stiffness $K_e = w\,B^\top D B$ (element DOFs squared), in N/m.
pub fn element_stiffness<D: Dim>(mesh: &SimplexMesh<D>, materials: &ElementMaterials<D>, elem_idx: usize) -> D::ElementMatrix {
    let (b, measure) = element_b(mesh, elem_idx);
    let d = materials.d_matrix(elem_idx);
    let w = D::stiffness_weight(measure, &materials.model);
    // db = D B (Voigt × element DOFs)
    let mut db = D::BMatrix::default();
    for i in 0..D::VOIGT {
        for j in 0..D::ELEMENT_DOFS {
            db[i][j] = (0..D::VOIGT).map(|k| d[i][k] * b[k][j]).sum();
        }
    }
    let mut ke = D::ElementMatrix::default();
    for i in 0..D::ELEMENT_DOFS {
        for j in 0..D::ELEMENT_DOFS {
            ke[i][j] = w * (0..D::VOIGT).map(|k| b[k][i] * db[k][j]).sum::<f64>();
        }
    }
    ke
}

/// Assembles the full $Nn \times Nn$ stiffness (both triangles of it stored); `adjust` may change
/// each element matrix before it is added (2D: node DOFs in rotated frames, [`assemble_stiffness`]).
pub fn assemble_stiffness_with<D: Dim>(
    mesh: &SimplexMesh<D>,
    materials: &ElementMaterials<D>,
    mut adjust: impl FnMut(&D::Element, &mut D::ElementMatrix),
) -> SparseColMat<usize, f64> {
    let n_dofs = mesh.n_dofs();
    let mut triplets = Vec::with_capacity(D::ELEMENT_DOFS * D::ELEMENT_DOFS * mesh.n_elements());
    for (elem_idx, e) in mesh.elements().iter().enumerate() {
        let mut ke = element_stiffness(mesh, materials, elem_idx);
        adjust(e, &mut ke);
        let dofs = D::element_dofs(e);
        for i in 0..D::ELEMENT_DOFS {
            for j in 0..D::ELEMENT_DOFS {
                triplets.push(Triplet::new(dofs[i], dofs[j], ke[i][j]));
            }
        }
    }
    // Indices are in range by construction (the mesh is validated), so this cannot fail.
    SparseColMat::try_new_from_triplets(n_dofs, n_dofs, &triplets).expect("assembly indices are in range")
}

/// $K_e \leftarrow T_k^\top K_e T_k$ for element node `k` whose DOFs are taken in the frame with
/// rows `frame` ($u_{loc} = F u$, $T_k = F^\top$ on the node's block): columns first ($K_e T$), then
/// rows. Each new entry is summed in the order of the frame's columns (in 2D the operations of the
/// former rotation by an angle, so the same bits).
pub fn rotate_element_node<D: Dim>(ke: &mut D::ElementMatrix, k: usize, frame: &D::FrameRows) {
    let n = D::N;
    let i0 = n * k;
    for r in 0..D::ELEMENT_DOFS {
        let row = &mut ke[r];
        let old: [f64; 3] = std::array::from_fn(|a| if a < n { row[i0 + a] } else { 0.0 });
        for c in 0..n {
            let mut s = old[0] * frame[c][0];
            for a in 1..n {
                s += old[a] * frame[c][a];
            }
            row[i0 + c] = s;
        }
    }
    for j in 0..D::ELEMENT_DOFS {
        let old: [f64; 3] = std::array::from_fn(|a| if a < n { ke[i0 + a][j] } else { 0.0 });
        for c in 0..n {
            let mut s = frame[c][0] * old[0];
            for a in 1..n {
                s += frame[c][a] * old[a];
            }
            ke[i0 + c][j] = s;
        }
    }
}

/// $y = K x$ for the full stiffness.
pub fn mul_stiffness(k: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    y.fill(0.0);
    let sym = k.symbolic();
    let vals = k.val();
    for j in 0..k.ncols() {
        let xj = x[j];
        if xj == 0.0 {
            continue;
        }
        for p in sym.col_ptr()[j]..sym.col_ptr()[j + 1] {
            y[sym.row_idx()[p]] += vals[p] * xj;
        }
    }
}

/// The constant stress $\sigma = D B u_e$ of each element in the dimension's Voigt order (2D
/// $[\sigma_{xx}, \sigma_{yy}, \sigma_{xy}]$; 3D $[\sigma_{xx}, \sigma_{yy}, \sigma_{zz},
/// \sigma_{yz}, \sigma_{xz}, \sigma_{xy}]$), in Pa, from world displacements (length $Nn$).
pub fn element_stresses_pa<D: Dim>(mesh: &SimplexMesh<D>, materials: &ElementMaterials<D>, displacement_m: &[f64]) -> Vec<D::Voigt> {
    (0..mesh.n_elements())
        .map(|elem_idx| {
            let (b, _) = element_b(mesh, elem_idx);
            let dofs = D::element_dofs(&mesh.elements()[elem_idx]);
            let mut strain = D::Voigt::default();
            for i in 0..D::VOIGT {
                strain[i] = (0..D::ELEMENT_DOFS).map(|j| b[i][j] * displacement_m[dofs[j]]).sum();
            }
            let d = materials.d_matrix(elem_idx);
            let mut stress = D::Voigt::default();
            for i in 0..D::VOIGT {
                stress[i] = (0..D::VOIGT).map(|k| d[i][k] * strain[k]).sum();
            }
            stress
        })
        .collect()
}
