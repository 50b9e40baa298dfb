//! Test and benchmark fixtures: the paper's phantom (a 0.1 m square of PVC-like tissue on an
//! n × n grid, fixed along its bottom edge) and the needle set-ups the tests and benchmarks of
//! every crate start from, written once. Pure data, no I/O; not meant for production scenes
//! (those come from scene files).
//!
//! The functions panic on an invalid grid size (`n < 2`): they are fixtures, and a failure is a
//! bug in the caller's set-up. [`random_spd_compliance`] is a mesh-free stand-in for a tissue's
//! compliance in 2D or 3D (the mixed solver's dimension-generic tests and benchmarks).

use std::sync::Arc;

use crate::assembly::MaterialMap;
use crate::compliance::{ComplianceCache, TissueModel};
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
        viscoelastic: None,
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

/// A random symmetric positive definite "compliance" of `n_nodes` nodes in dimension `D`, with
/// a cache holding every node's columns: $C = s\,(A A^\top / (Dn) + \varepsilon I)$ with the
/// entries of $A$ uniform in $[-1, 1]$ (SplitMix64 from `seed`, so no `rand` dependency),
/// $\varepsilon = 0.05$ and $s = 10^{-3}$ m/N (a soft tissue's order of magnitude). Its
/// condition number is of order $4 / \varepsilon$ at most. Returns $C$ (row-major, $Dn \times Dn$,
/// exactly symmetric) and the filled cache. A mesh-free fixture: no element, no factorisation.
pub fn random_spd_compliance<const D: usize>(n_nodes: usize, seed: u64) -> (Vec<f64>, ComplianceCache<D>) {
    let n = D * n_nodes;
    let mut state = seed;
    let mut next = || {
        // SplitMix64.
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let a: Vec<f64> = (0..n * n).map(|_| next()).collect();
    let (scale, eps) = (1e-3, 0.05);
    let mut c = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let dot: f64 = (0..n).map(|k| a[i * n + k] * a[j * n + k]).sum();
            let v = scale * (dot / n as f64 + if i == j { eps } else { 0.0 });
            c[i * n + j] = v;
            c[j * n + i] = v;
        }
    }
    let mut cache = ComplianceCache::<D>::for_nodes(n_nodes);
    let mut cols = vec![0.0; D * n];
    for node in 0..n_nodes {
        for comp in 0..D {
            for r in 0..n {
                cols[comp * n + r] = c[r * n + D * node + comp];
            }
        }
        cache.insert(node, &cols);
    }
    (c, cache)
}

/// The 3D cube phantom (issue 16): a 0.1 m cube of `n × n × n` nodes
/// ([`crate::d3::BoxGridParams`], 6 Kuhn tetrahedra per cell), E = 30 kPa, ν = 0.45, its bottom
/// ($z = 0$) fixed; the top face is $z = 0.1$ m.
pub fn box_phantom3(n: usize) -> Arc<crate::d3::TetTissueModel> {
    use crate::d3::{BoxGridParams, TetMaterials, TetMeshLimits, TetTissueModel};
    let mesh = BoxGridParams::new([n; 3], [0.1; 3]).build(&TetMeshLimits::default()).expect("the box grid builds");
    let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 30e3, poisson_ratio: 0.45 }]).expect("valid material");
    let fixed = mesh.boundary_set("bottom").expect("a bottom face").to_vec();
    Arc::new(TetTissueModel::new(mesh, mats, &fixed).expect("the phantom factorises"))
}

/// 3D simulation parameters for [`box_phantom3`]: a 0.12 m rigid needle pointing straight down
/// with its tip `tip_above_m` above the entry point `entry_m` on the top face; friction 10 N/m,
/// puncture 0.3 N, cutting 0.05 N ([`RegionNeedleParams::default`]), 2 mm spacing.
pub fn box_phantom3_params(entry_m: [f64; 3], tip_above_m: f64) -> crate::sim3::Sim3Params {
    let len = 0.12;
    let pose = crate::sim3::BasePose3::straight_down([entry_m[0], entry_m[1], entry_m[2] + tip_above_m + len]);
    crate::sim3::Sim3Params::new(len, pose)
}
