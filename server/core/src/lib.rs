//! needlesim-core: the pure real-time solver of needlesim.
//!
//! A 2D linear-elastic tissue model discretised with linear triangles ([`mesh`], [`material`],
//! [`assembly`]), a sparse Cholesky factorisation of its free stiffness ([`factor`]), static
//! solves with mixed and local-frame conditions ([`statics`]), compliance columns on demand
//! ([`compliance`]) and the condensed mixed boundary-condition solve on the working nodes with
//! O(d²) updates ([`mixed`]); the compliance cache, the contact points and the mixed solver
//! serve 2D and 3D (a const generic dimension). Gmsh meshes are read from text by [`msh`]. The needle ([`needle`])
//! and the insertion simulation stepped once per haptic tick ([`sim`]) sit on top, with a spatial
//! grid ([`spatial`]) for finding the nodes near the tip; [`stepper`] is the step interface the 2D
//! and 3D simulations share (the scripted driver's). Node indices, working-set slots and
//! needle-frame components have their own types ([`ids`]); the test and benchmark set-ups of
//! every crate are in [`fixtures`].
//!
//! The static 3D core (linear tetrahedra: mesh, box grids, point location, assembly, statics with
//! material-point conditions, compliance columns) is the module [`d3`].
//!
//! The dimension is a type parameter where the code is one for both ([`dim`]: `Dim2`, `Dim3`): the
//! mesh is [`mesh::SimplexMesh<D>`], with [`Mesh`] and [`d3::TetMesh`] its aliases; the element
//! assembly ([`assembly`]) and the static solve ([`statics`]: [`StaticProblem`] is the 2D one,
//! [`d3::TetStaticProblem`] the 3D one) are written once.
//!
//! The crate does no I/O and knows no async runtime or protocol: state in, state out, typed errors.

// Index loops mirror the formulas (i, j over matrix entries); `!(x > 0.0)` is deliberate: it is
// true for NaN, which must be rejected with the other invalid values.
#![allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]
// The solver's errors carry the contact they are about (a `ContactPoint` of up to twelve terms,
// about 200 bytes) by value: they are returned on cold paths, and boxing them would allocate on
// the real-time thread (a dependent material point is such an error, handled inside a step).

pub mod assembly;
pub mod beam;
pub mod compliance;
pub mod contact;
pub mod d3;
pub mod dim;
mod drift;
pub mod factor;
pub mod fixtures;
pub mod ids;
pub mod material;
pub mod mesh;
pub mod mixed;
pub mod msh;
pub mod needle;
pub mod num;
pub mod rod3;
pub mod sim;
pub mod sim3;
pub mod spatial;
pub mod statics;
pub mod stepper;
pub mod viscous;

pub use assembly::{ElementMaterials, MaterialMap};
pub use beam::NeedleCurve;
pub use compliance::{ColumnScratch, ComplianceCache, ComplianceCache3, TissueError, TissueModel};
pub use contact::{ContactId, ContactPoint};
pub use dim::{ConditionLabel, Dim, Dim2, Dim3};
pub use ids::{Axis, NodeIdx, Slot};
pub use material::{Material, MaterialError, PlaneModel};
pub use mesh::{DiagonalPattern, Mesh, MeshError, MeshLimits, RectMeshParams, SimplexMesh};
pub use mixed::{Condition, MixedError, MixedSolver, MixedSolver2, MixedSolver3};
pub use needle::{BasePose, FlexibleNeedle, NeedleShape, RegionNeedleParams, RigidNeedle};
pub use sim::{Divergence, DivergenceBounds, Inserted, NodeState, SimError, SimParams, SimStats, Simulation, StepOutput, TargetParams};
pub use statics::{NodeCondition, StaticError, StaticProblem, StaticSolution};
pub use stepper::{StepError, Stepper};
