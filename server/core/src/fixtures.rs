//! Test and benchmark fixtures: the paper's phantom (a 0.1 m square of PVC-like tissue on an
//! n × n grid, fixed along its bottom edge) and the needle set-ups the tests and benchmarks of
//! every crate start from, written once. Pure data, no I/O; not meant for production scenes
//! (those come from scene files).
//!
//! The functions panic on an invalid grid size (`n < 2`): they are fixtures, and a failure is a
//! bug in the caller's set-up.

use std::sync::Arc;

use crate::assembly::MaterialMap;
use crate::compliance::TissueModel;
use crate::material::{Material, PlaneModel};
use crate::mesh::{Mesh, MeshLimits, RectMeshParams};
use crate::needle::{BasePose, NeedleShape, RegionNeedleParams, RigidNeedle};
use crate::sim::{ContactModel, SimParams};

/// Side of the phantom's square (m).
pub const PHANTOM_SIDE_M: f64 = 0.1;

/// The phantom's material: PVC-like, $E$ = 30 kPa, $\nu$ = 0.45.
pub const PHANTOM_MATERIAL: Material = Material { young_modulus_pa: 30e3, poisson_ratio: 0.45 };

/// The phantom's plane model: plane stress in a 1 cm slice.
pub const PHANTOM_PLANE: PlaneModel = PlaneModel::Stress { thickness_m: 0.01 };

/// Height of the needle base above the phantom's bottom edge at the start (m): the 0.1 m needle
/// pointing down from here has its tip 5 mm above the top edge.
pub const PHANTOM_BASE_Y_M: f64 = 0.205;

/// The phantom's mesh, materials and fixed (bottom) nodes on an `n × n` grid, without a node
/// limit (the benchmarks go to 200 × 200).
///
/// Panics if `n < 2`.
pub fn phantom_parts(n: usize) -> (Mesh, MaterialMap, Vec<usize>) {
    let limits = MeshLimits { max_nodes: usize::MAX, max_triangles: usize::MAX };
    let mesh = RectMeshParams::new(n, n, PHANTOM_SIDE_M, PHANTOM_SIDE_M).build(&limits).expect("phantom grid: n ≥ 2");
    let mats = MaterialMap::per_region(&mesh, &[PHANTOM_MATERIAL], PHANTOM_PLANE).expect("phantom material is valid");
    let fixed = mesh.boundary_set("bottom").expect("a grid has a bottom boundary").to_vec();
    (mesh, mats, fixed)
}

/// The phantom on an `n × n` grid, factorised.
///
/// Panics if `n < 2`.
pub fn phantom(n: usize) -> Arc<TissueModel> {
    let (mesh, mats, fixed) = phantom_parts(n);
    Arc::new(TissueModel::new(mesh, mats, &fixed).expect("the phantom factorises"))
}

/// The tests' needle set-up in the phantom: `needle` pointing down from 5 mm above the top
/// centre, the paper's node capture with a 1.5 mm capture radius (columns computed in the step
/// when missing), room for 64 needle nodes, one region of default friction,
/// no targets, 1 kHz, 2 mm / 0.05 rad per tick at most, 64 active-set iterations, 1 cm
/// lookahead. Tests change what they need with struct update syntax.
pub fn phantom_params(needle: NeedleShape) -> SimParams {
    SimParams {
        needle,
        initial_pose: BasePose::new(0.5 * PHANTOM_SIDE_M, PHANTOM_BASE_Y_M, -std::f64::consts::FRAC_PI_2),
        contact: ContactModel::Nodes,
        columns_in_step: true,
        capture_radius_m: 0.0015,
        max_needle_nodes: 64,
        regions: vec![RegionNeedleParams::default()],
        targets: vec![],
        tick_rate_hz: 1000.0,
        max_base_step_m: 0.002,
        max_base_step_rad: 0.05,
        max_active_set_iterations: 64,
        lookahead_m: 0.01,
    }
}

/// The step benchmarks' needle set-up on the `n × n` phantom: a rigid 0.1 m needle above the
/// middle grid column ($x = \lfloor (n-1)/2 \rfloor h$, $h = 0.1/(n-1)$), a capture radius of
/// $0.3\,h$, room for 160 needle nodes; otherwise as [`phantom_params`].
pub fn phantom_bench_params(n: usize) -> SimParams {
    let h = PHANTOM_SIDE_M / (n.max(2) - 1) as f64;
    let x = ((n.max(2) - 1) / 2) as f64 * h;
    SimParams {
        initial_pose: BasePose::new(x, PHANTOM_BASE_Y_M, -std::f64::consts::FRAC_PI_2),
        capture_radius_m: 0.3 * h,
        max_needle_nodes: 160,
        ..phantom_params(NeedleShape::Rigid(RigidNeedle { length_m: 0.1 }))
    }
}

/// The step benchmarks' starting point: the `n × n` phantom and [`phantom_bench_params`].
///
/// Panics if `n < 2`.
pub fn phantom_bench(n: usize) -> (Arc<TissueModel>, SimParams) {
    (phantom(n), phantom_bench_params(n))
}

/// The solver unit tests' and tissue benchmark's tissue: the 0.1 m square on an `n × n` grid,
/// $E$ = 15 kPa, $\nu$ = 0.45, plane strain of unit thickness, fixed along its bottom edge.
///
/// Panics if `n < 2` or the grid exceeds [`MeshLimits::default`].
pub fn strain_square(n: usize) -> TissueModel {
    let mesh = RectMeshParams::new(n, n, PHANTOM_SIDE_M, PHANTOM_SIDE_M).build(&MeshLimits::default()).expect("grid");
    let mats = MaterialMap::per_region(
        &mesh,
        &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }],
        PlaneModel::Strain { thickness_m: 1.0 },
    )
    .expect("valid material");
    let fixed = mesh.boundary_set("bottom").expect("a grid has a bottom boundary").to_vec();
    TissueModel::new(mesh, mats, &fixed).expect("the square factorises")
}
