//! Fixtures shared by the core's integration tests (`mod common;` in each test file).

use std::sync::Arc;

use needlesim_core::compliance::TissueModel;
use needlesim_core::{Material, MaterialMap, MeshLimits, PlaneModel, RectMeshParams};

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
