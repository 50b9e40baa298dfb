//! The spatial dimension as a type parameter: [`Dim`], implemented by [`Dim2`] (linear triangles)
//! and [`Dim3`] (linear tetrahedra).
//!
//! What is written once over `D: Dim` (the mesh's storage, accessors, regions, boundary sets and
//! the checks that do not depend on the element's shape) takes its dimension from here; what
//! truly differs per dimension is a method of the trait: the element's signed measure (area,
//! volume) and its degeneracy test, the orientation a stored element is given, and the
//! conformity checks (2D: no two triangles overlap; 3D: faces pair up, no tissue outside a
//! boundary face). As in rapier's `dim2`/`dim3`, the types are associated types of fixed size
//! (`Point = [f64; N]`, `Element = [usize; N + 1]`), not const-generic arrays: stable Rust
//! cannot write `[usize; N + 1]` for a generic `N` (that needs `generic_const_exprs`), and
//! monomorphised code over fixed arrays compiles to what the per-dimension code did.
//!
//! The static solve ([`crate::statics`]) takes from here what its conditions need per dimension:
//! the frame's representation (2D an angle, 3D rows) and check, point location (3D only), and
//! the wording of the errors that differ.
//!
//! DOF layout everywhere: $[u_{x0}, u_{y0}, (u_{z0},) u_{x1}, \dots]$, DOF $= N\cdot\mathrm{node}
//! + \mathrm{axis}$ ([`Dim::dof`]).

use std::fmt::Debug;
use std::hash::Hash;
use std::ops::{Index, IndexMut};

use crate::d3::locate::{LocateError, PointLocation, TetLocator};
use crate::d3::mesh::{TetMeshError, TetMeshLimits, signed_volume_m3};
use crate::material::{Material, PlaneModel};
use crate::mesh::{MeshError, MeshFault, MeshLimits, SimplexMesh};

/// A spatial dimension: its point and element types, the element's name in messages, and the
/// geometry and checks of its simplex element (see the module docs for what lives here and why).
pub trait Dim: Copy + Debug + PartialEq + Eq + Send + Sync + 'static + Sized {
    /// The number of coordinates of a point (2 or 3).
    const N: usize;
    /// Nodes per element, $N + 1$ (3: a triangle, 4: a tetrahedron).
    const NODES_PER_ELEMENT: usize;
    /// The element's name in messages ("triangle", "tetrahedron").
    const ELEMENT: &'static str;
    /// Its plural ("triangles", "tetrahedra").
    const ELEMENTS: &'static str;

    /// A point or vector, `[f64; N]`, in m where it is a position.
    type Point: Copy + Debug + PartialEq + Default + Index<usize, Output = f64> + IndexMut<usize> + AsRef<[f64]> + Send + Sync + 'static;
    /// An element's node indices, `[usize; N + 1]`.
    type Element: Copy
        + Debug
        + PartialEq
        + Eq
        + Ord
        + Hash
        + Default
        + Index<usize, Output = usize>
        + AsRef<[usize]>
        + AsMut<[usize]>
        + Send
        + Sync
        + 'static;
    /// An element's corner coordinates, `[Point; N + 1]`.
    type ElementPoints: Copy + Debug + Index<usize, Output = Self::Point> + AsRef<[Self::Point]>;
    /// The size limits a mesh of this dimension is checked against ([`MeshLimits`],
    /// [`TetMeshLimits`]: distinct types because the scenes and the CLI name their fields).
    type Limits: Copy + Debug + PartialEq + Default;
    /// The mesh errors of this dimension ([`MeshError`], [`TetMeshError`]: distinct because
    /// their messages name the element and are quoted by tests and the CLI).
    type MeshError: From<MeshFault<Self>> + std::error::Error + Clone + PartialEq;

    /// The global DOF of `node`'s coordinate `axis`, $N\cdot\mathrm{node} + \mathrm{axis}$.
    #[inline]
    fn dof(node: usize, axis: usize) -> usize {
        Self::N * node + axis
    }
    /// A point from its coordinates.
    fn point_from_fn(f: impl FnMut(usize) -> f64) -> Self::Point;
    /// The corners of element `e`.
    fn element_points(nodes_m: &[Self::Point], e: &Self::Element) -> Self::ElementPoints;
    /// The Euclidean length of `v`, in the operations each dimension has always used (2D:
    /// `hypot`; 3D: the square root of the dot product), so tolerances derived from it are
    /// bit-identical to before.
    fn norm(v: Self::Point) -> f64;
    /// The element's signed measure: the area in m² (positive counter-clockwise), the volume
    /// in m³ (positive when $\det[x_1 - x_0, x_2 - x_0, x_3 - x_0] > 0$).
    fn signed_measure(p: &Self::ElementPoints) -> f64;
    /// The element's degeneracy test: an element flat to round-off relative to its size has a
    /// meaningless stiffness. Names element `elem_idx` in the error.
    fn check_shape(elem_idx: usize, nodes: &Self::Element, p: &Self::ElementPoints) -> Result<(), Self::MeshError>;
    /// The orientation a validated element is stored in: 2D keeps triangles as given (the
    /// element matrices use the signed area, so clockwise ones are right too); 3D stores every
    /// tetrahedron positively oriented (swapping its last two nodes).
    fn orient(e: &mut Self::Element, p: &Self::ElementPoints);
    /// The conformity checks run after the shared ones (duplicate nodes and elements are among
    /// them, in each dimension's historical order, so the first error reported is unchanged).
    fn check_conformity(mesh: &SimplexMesh<Self>) -> Result<(), Self::MeshError>;
    /// `(max_nodes, max_elements)` of `limits`.
    fn max_counts(limits: &Self::Limits) -> (usize, usize);

    /// DOFs per element, $N(N + 1)$ (6, 12).
    const ELEMENT_DOFS: usize;
    /// Strain and stress components in Voigt order (3: $[xx, yy, xy]$; 6: $[xx, yy, zz, yz,
    /// xz, xy]$), engineering shear.
    const VOIGT: usize;
    /// A vector over the element's DOFs, `[f64; ELEMENT_DOFS]`: a row of $B$ or of $K_e$.
    type ElementVector: Copy + Debug + Default + Index<usize, Output = f64> + IndexMut<usize> + AsRef<[f64]>;
    /// A Voigt vector, `[f64; VOIGT]`: a strain, a stress, a row of $D$.
    type Voigt: Copy + Debug + PartialEq + Default + Index<usize, Output = f64> + IndexMut<usize> + AsRef<[f64]> + Send + Sync + 'static;
    /// The strain–displacement matrix $B$, `VOIGT` rows of [`Dim::ElementVector`].
    type BMatrix: Copy + Debug + Default + Index<usize, Output = Self::ElementVector> + IndexMut<usize>;
    /// The element stiffness $K_e$, `ELEMENT_DOFS` rows of [`Dim::ElementVector`].
    type ElementMatrix: Copy + Debug + Default + Index<usize, Output = Self::ElementVector> + IndexMut<usize>;
    /// The material matrix $D$, `VOIGT` rows of [`Dim::Voigt`].
    type DMatrix: Copy + Debug + Index<usize, Output = Self::Voigt>;
    /// The element's global DOFs, `[usize; ELEMENT_DOFS]`.
    type ElementDofs: Copy + Debug + Index<usize, Output = usize> + AsRef<[usize]>;
    /// What $D$ and the element's weight depend on besides E and ν: 2D the plane model (strain or
    /// stress, and the thickness that scales $K$), 3D nothing.
    type Model: Copy + Debug + PartialEq + Send + Sync + 'static;

    /// The element's DOFs, $[N a, N a + 1, \dots, N b, \dots]$.
    fn element_dofs(e: &Self::Element) -> Self::ElementDofs;
    /// The element's strain–displacement matrix $B$ (constant: linear shape functions) and its
    /// unsigned measure (area in m², volume in m³).
    fn element_b(p: &Self::ElementPoints) -> (Self::BMatrix, f64);
    /// The material matrix $D$ in Pa.
    fn d_matrix(m: &Material, model: &Self::Model) -> Self::DMatrix;
    /// The factor $w$ of $K_e = w\,B^\top D B$: $t\,|A|$ in 2D, $|V|$ in 3D.
    fn stiffness_weight(measure: f64, model: &Self::Model) -> f64;

    /// A frame at a node or a material point ([`crate::statics`]): 2D its angle in rad
    /// ($t = (\cos a, \sin a)$, $n = (-\sin a, \cos a)$; the results give it back as given), 3D
    /// its orthonormal rows $t, n, b$.
    type Frame: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// A frame as its rows $t, n(, b)$, `[Point; N]`: the components in it are $u_c = F_c \cdot u$.
    type FrameRows: Copy + Debug + Index<usize, Output = Self::Point>;
    /// Components that may be prescribed, `[Option<f64>; N]` (`None`: free).
    type Components: Copy
        + Debug
        + PartialEq
        + Default
        + Index<usize, Output = Option<f64>>
        + IndexMut<usize>
        + AsRef<[Option<f64>]>
        + Send
        + Sync
        + 'static;
    /// Where a material point lies: its element, that element's nodes and their weights $N_i(x)$
    /// (3D [`crate::d3::PointLocation`]; 2D none, see [`crate::statics::tri`]).
    type PointLocation: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// What finds material points in a mesh (3D [`crate::d3::TetLocator`]).
    type Locator;
    /// Why a material point was not located (its message follows `point i: `).
    type LocateError: std::error::Error + Clone + PartialEq + Send + Sync + 'static;
    /// The tissue model's fill-reducing ordering ([`crate::compliance::TissueModel`]): from this
    /// many nodes on, a nested dissection of the mesh ([`crate::compliance::sparse::nested_dissection_order`]),
    /// below it faer's AMD. 2D: `None`, AMD always (its results stay those it always had); 3D: 2000
    /// (below it AMD fills less: a 6³ box, 76 k against 49 k non-zeros).
    const NESTED_DISSECTION_MIN_NODES: Option<usize>;
    /// What an unknown node of a local-frame condition is called in the error ("a condition" in
    /// 3D, "a local-frame condition" in 2D: each dimension's messages are quoted as they are).
    const LOCAL_CONDITION: &'static str;

    /// Components from their values.
    fn components_from_fn(f: impl FnMut(usize) -> Option<f64>) -> Self::Components;
    /// The rows of `frame`.
    fn frame_rows(frame: &Self::Frame) -> Self::FrameRows;
    /// Checks a frame given for `what` ("point 3", or [`Dim::condition_label`]'s
    /// [`ConditionLabel::LocalFrame`]): finite, and in 3D orthonormal.
    fn check_frame(frame: &Self::Frame, what: &str) -> Result<(), crate::statics::StaticError<Self>>;
    /// What a node's condition is called in a `NonFinite` error (the wording of each
    /// dimension's messages, quoted by tests and users).
    fn condition_label(label: ConditionLabel, node: usize) -> String;
    /// A point locator of `mesh`.
    fn locator(mesh: &SimplexMesh<Self>) -> Self::Locator;
    /// The element holding `x_m` and the weights of its nodes.
    fn locate(locator: &Self::Locator, mesh: &SimplexMesh<Self>, x_m: Self::Point) -> Result<Self::PointLocation, Self::LocateError>;
    /// A location's element, nodes and weights.
    fn location_terms(loc: &Self::PointLocation) -> (usize, &[usize], &[f64]);
}

/// Which part of a node's condition an error names ([`Dim::condition_label`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConditionLabel {
    /// A world component of a `World` condition.
    World,
    /// The frame of a `Local` condition.
    LocalFrame,
    /// A component of a `Local` condition.
    LocalValue,
}

/// Two dimensions: linear (constant-strain) triangles, nodes `[x, y]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Dim2;

/// Three dimensions: linear 4-node tetrahedra, nodes `[x, y, z]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Dim3;

impl Dim for Dim2 {
    const N: usize = 2;
    const NODES_PER_ELEMENT: usize = 3;
    const ELEMENT: &'static str = "triangle";
    const ELEMENTS: &'static str = "triangles";
    type Point = [f64; 2];
    type Element = [usize; 3];
    type ElementPoints = [[f64; 2]; 3];
    type Limits = MeshLimits;
    type MeshError = MeshError;

    #[inline]
    fn point_from_fn(f: impl FnMut(usize) -> f64) -> [f64; 2] {
        std::array::from_fn(f)
    }
    #[inline]
    fn element_points(nodes_m: &[[f64; 2]], e: &[usize; 3]) -> [[f64; 2]; 3] {
        e.map(|i| nodes_m[i])
    }
    #[inline]
    fn norm(v: [f64; 2]) -> f64 {
        v[0].hypot(v[1])
    }
    /// $A = \tfrac12[(x_2-x_1)(y_3-y_1) - (x_3-x_1)(y_2-y_1)]$.
    #[inline]
    fn signed_measure(p: &[[f64; 2]; 3]) -> f64 {
        let [a, b, c] = *p;
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
    }
    fn check_shape(elem_idx: usize, nodes: &[usize; 3], p: &[[f64; 2]; 3]) -> Result<(), MeshError> {
        crate::mesh::tri::check_shape(elem_idx, nodes, p)
    }
    #[inline]
    fn orient(_e: &mut [usize; 3], _p: &[[f64; 2]; 3]) {}
    fn check_conformity(mesh: &SimplexMesh<Self>) -> Result<(), MeshError> {
        mesh.check_duplicate_nodes()?;
        mesh.check_duplicate_elements()?;
        crate::mesh::tri::check_overlaps(mesh)
    }
    fn max_counts(limits: &MeshLimits) -> (usize, usize) {
        (limits.max_nodes, limits.max_triangles)
    }

    const ELEMENT_DOFS: usize = 6;
    const VOIGT: usize = 3;
    type ElementVector = [f64; 6];
    type Voigt = [f64; 3];
    type BMatrix = [[f64; 6]; 3];
    type ElementMatrix = [[f64; 6]; 6];
    type DMatrix = [[f64; 3]; 3];
    type ElementDofs = [usize; 6];
    type Model = PlaneModel;

    #[inline]
    fn element_dofs(e: &[usize; 3]) -> [usize; 6] {
        std::array::from_fn(|k| 2 * e[k / 2] + k % 2)
    }
    fn element_b(p: &[[f64; 2]; 3]) -> ([[f64; 6]; 3], f64) {
        crate::assembly::tri::triangle_b(p)
    }
    fn d_matrix(m: &Material, model: &PlaneModel) -> [[f64; 3]; 3] {
        m.d_matrix(*model)
    }
    #[inline]
    fn stiffness_weight(area_m2: f64, model: &PlaneModel) -> f64 {
        model.thickness_m() * area_m2
    }
    type Frame = f64;
    type FrameRows = [[f64; 2]; 2];
    type Components = [Option<f64>; 2];
    type PointLocation = crate::statics::tri::NoPointLocation;
    type Locator = ();
    type LocateError = crate::statics::tri::NoPointLocationError;
    const LOCAL_CONDITION: &'static str = "a local-frame condition";
    const NESTED_DISSECTION_MIN_NODES: Option<usize> = None;

    #[inline]
    fn components_from_fn(f: impl FnMut(usize) -> Option<f64>) -> [Option<f64>; 2] {
        std::array::from_fn(f)
    }
    /// $[[\cos a, \sin a], [-\sin a, \cos a]]$.
    #[inline]
    fn frame_rows(angle_rad: &f64) -> [[f64; 2]; 2] {
        crate::statics::tri::frame_rows(*angle_rad)
    }
    fn check_frame(angle_rad: &f64, what: &str) -> Result<(), crate::statics::StaticError<Self>> {
        crate::statics::tri::check_angle(*angle_rad, what)
    }
    fn condition_label(label: ConditionLabel, node: usize) -> String {
        crate::statics::tri::condition_label(label, node)
    }
    fn locator(_mesh: &SimplexMesh<Self>) {}
    fn locate(_locator: &(), _mesh: &SimplexMesh<Self>, _x_m: [f64; 2]) -> Result<Self::PointLocation, Self::LocateError> {
        Err(crate::statics::tri::NoPointLocationError)
    }
    fn location_terms(loc: &Self::PointLocation) -> (usize, &[usize], &[f64]) {
        match *loc {}
    }
}

impl Dim for Dim3 {
    const N: usize = 3;
    const NODES_PER_ELEMENT: usize = 4;
    const ELEMENT: &'static str = "tetrahedron";
    const ELEMENTS: &'static str = "tetrahedra";
    type Point = [f64; 3];
    type Element = [usize; 4];
    type ElementPoints = [[f64; 3]; 4];
    type Limits = TetMeshLimits;
    type MeshError = TetMeshError;

    #[inline]
    fn point_from_fn(f: impl FnMut(usize) -> f64) -> [f64; 3] {
        std::array::from_fn(f)
    }
    #[inline]
    fn element_points(nodes_m: &[[f64; 3]], e: &[usize; 4]) -> [[f64; 3]; 4] {
        e.map(|i| nodes_m[i])
    }
    #[inline]
    fn norm(v: [f64; 3]) -> f64 {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    }
    /// $V = \tfrac16 \det[x_1 - x_0,\; x_2 - x_0,\; x_3 - x_0]$.
    #[inline]
    fn signed_measure(p: &[[f64; 3]; 4]) -> f64 {
        signed_volume_m3(p[0], p[1], p[2], p[3])
    }
    fn check_shape(elem_idx: usize, nodes: &[usize; 4], p: &[[f64; 3]; 4]) -> Result<(), TetMeshError> {
        crate::d3::mesh::check_shape(elem_idx, nodes, p)
    }
    #[inline]
    fn orient(e: &mut [usize; 4], p: &[[f64; 3]; 4]) {
        if Self::signed_measure(p) < 0.0 {
            e.swap(2, 3);
        }
    }
    fn check_conformity(mesh: &SimplexMesh<Self>) -> Result<(), TetMeshError> {
        mesh.check_duplicate_elements()?;
        mesh.check_duplicate_nodes()?;
        let boundary = crate::d3::conform::check_faces(mesh)?;
        crate::d3::conform::check_boundary_probes(mesh, &boundary)
    }
    fn max_counts(limits: &TetMeshLimits) -> (usize, usize) {
        (limits.max_nodes, limits.max_tets)
    }

    const ELEMENT_DOFS: usize = 12;
    const VOIGT: usize = 6;
    type ElementVector = [f64; 12];
    type Voigt = [f64; 6];
    type BMatrix = [[f64; 12]; 6];
    type ElementMatrix = [[f64; 12]; 12];
    type DMatrix = [[f64; 6]; 6];
    type ElementDofs = [usize; 12];
    type Model = ();

    #[inline]
    fn element_dofs(e: &[usize; 4]) -> [usize; 12] {
        std::array::from_fn(|k| 3 * e[k / 3] + k % 3)
    }
    fn element_b(p: &[[f64; 3]; 4]) -> ([[f64; 12]; 6], f64) {
        crate::d3::assembly::tetrahedron_b(p)
    }
    fn d_matrix(m: &Material, _model: &()) -> [[f64; 6]; 6] {
        crate::d3::assembly::d_matrix(m)
    }
    #[inline]
    fn stiffness_weight(volume_m3: f64, _model: &()) -> f64 {
        volume_m3
    }
    type Frame = [[f64; 3]; 3];
    type FrameRows = [[f64; 3]; 3];
    type Components = [Option<f64>; 3];
    type PointLocation = PointLocation;
    type Locator = TetLocator;
    type LocateError = LocateError;
    const LOCAL_CONDITION: &'static str = "a condition";
    const NESTED_DISSECTION_MIN_NODES: Option<usize> = Some(2000);

    #[inline]
    fn components_from_fn(f: impl FnMut(usize) -> Option<f64>) -> [Option<f64>; 3] {
        std::array::from_fn(f)
    }
    #[inline]
    fn frame_rows(frame: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        *frame
    }
    fn check_frame(frame: &[[f64; 3]; 3], what: &str) -> Result<(), crate::statics::StaticError<Self>> {
        crate::d3::statics::check_frame(frame, what)
    }
    fn condition_label(label: ConditionLabel, node: usize) -> String {
        crate::d3::statics::condition_label(label, node)
    }
    fn locator(mesh: &SimplexMesh<Self>) -> TetLocator {
        TetLocator::new(mesh)
    }
    fn locate(locator: &TetLocator, mesh: &SimplexMesh<Self>, x_m: [f64; 3]) -> Result<PointLocation, LocateError> {
        locator.locate(mesh, x_m)
    }
    fn location_terms(loc: &PointLocation) -> (usize, &[usize], &[f64]) {
        (loc.tet_idx, &loc.nodes, &loc.weights)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dofs_interleave_by_node() {
        assert_eq!(Dim2::dof(5, 1), 11);
        assert_eq!(Dim3::dof(5, 2), 17);
        assert_eq!((Dim2::NODES_PER_ELEMENT, Dim3::NODES_PER_ELEMENT), (Dim2::N + 1, Dim3::N + 1));
    }

    #[test]
    fn signed_measures_are_area_and_volume() {
        assert_eq!(Dim2::signed_measure(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]), 0.5);
        assert_eq!(Dim2::signed_measure(&[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]), -0.5);
        assert!((Dim3::signed_measure(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]) - 1.0 / 6.0).abs() < 1e-16);
    }
}
