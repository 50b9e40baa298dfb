//! Fixtures shared by the core's integration tests (`mod common;` in each test file).

use std::sync::Arc;

use needlesim_core::compliance::TissueModel;
use needlesim_core::sim::SimParams;
use needlesim_core::{BasePose, Material, MaterialMap, MeshLimits, NeedleShape, PlaneModel, RectMeshParams, RegionNeedleParams};

/// The paper's phantom: a 0.1 m square, n × n nodes, PVC-like (E = 30 kPa, ν = 0.45, plane
/// stress, 1 cm slice), fixed along its bottom edge.
pub fn phantom(n: usize) -> Arc<TissueModel> {
    let mesh = RectMeshParams::new(n, n, 0.1, 0.1).build(&MeshLimits::default()).unwrap();
    let mats = MaterialMap::per_region(
        &mesh,
        &[Material { young_modulus_pa: 30e3, poisson_ratio: 0.45 }],
        PlaneModel::Stress { thickness_m: 0.01 },
    )
    .unwrap();
    let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
    Arc::new(TissueModel::new(mesh, mats, &fixed).unwrap())
}

/// The phantom's needle set-up: `needle` pointing down from 5 mm above the top centre, a 1.5 mm
/// capture radius, one region of default friction, no targets, 1 kHz; tests change what they need
/// with struct update syntax.
#[allow(dead_code)] // not every test file uses it
pub fn phantom_params(needle: NeedleShape) -> SimParams {
    SimParams {
        needle,
        initial_pose: BasePose::new(0.05, 0.205, -std::f64::consts::FRAC_PI_2),
        capture_radius_m: 0.0015,
        max_needle_nodes: 64,
        regions: vec![RegionNeedleParams::default()],
        targets: vec![],
        tick_rate_hz: 1000.0,
        max_base_step_m: 0.002,
        max_base_step_rad: 0.05,
        max_active_set_iterations: 12,
        lookahead_m: 0.01,
    }
}
