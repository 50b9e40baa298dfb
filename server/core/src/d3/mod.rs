//! The static 3D tissue core: linear 4-node tetrahedra.
//!
//! [`mesh`] (the tetrahedral mesh, its validation, structured box grids), [`conform`] (its
//! conformity checks: no cracks, no overlaps), [`locate`] (which tetrahedron holds a point, and its
//! barycentric weights), [`assembly`] (3D Hooke, element matrices, sparse $K$, stresses),
//! [`statics`] (the 3D pieces and names of the static solve of [`crate::statics`]: frames as
//! orthonormal rows, material points), [`tissue`] (the 3D names of the tissue model
//! [`crate::compliance::TissueModel`] — one factorisation of $K_{ff}$, compliance columns of a
//! node, the point compliance on demand, every node's displacement under point loads by one solve —
//! and of the sparse compliance [`crate::compliance::sparse`]: node and point compliance blocks
//! from sparse forward solves along elimination-tree paths, without full columns). Gmsh files with
//! tetrahedra are read by [`crate::msh::parse_msh3d`].
//!
//! Node DOFs are $[u_x, u_y, u_z]$ per node, DOF $= 3\cdot\mathrm{node} + \mathrm{axis}$, everywhere.

pub mod assembly;
pub mod conform;
pub mod disc;
pub mod locate;
pub mod mesh;
pub mod statics;
pub mod tissue;

pub use assembly::{TetMaterialError, TetMaterials};
pub use locate::{LocateError, PointLocation, TetLocator};
pub use mesh::{BoxGridParams, TetMesh, TetMeshError, TetMeshLimits};
pub use statics::{PointCondition, PointReaction, TetNodeCondition, TetStaticError, TetStaticProblem, TetStaticSolution};
pub use tissue::{
    NodeRows, SparseCompliance, SparseComplianceError, SparseFactorView, SparseRowsScratch, TetColumnScratch, TetTissueError,
    TetTissueModel,
};
