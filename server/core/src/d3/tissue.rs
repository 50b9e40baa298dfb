//! The 3D names of the tissue model ([`crate::compliance::TissueModel`], written once over the
//! dimension): [`TetTissueModel`] $=$ `TissueModel<Dim3>` — one factorisation of $K_{ff}$
//! ($3n \times 3n$, nested dissection from 2000 nodes), the three compliance columns of a node, the
//! point compliance $W = P C P^\top$ of material points located in the tetrahedra, and every
//! node's displacement under point loads by one solve — with its error and scratch types; and
//! its 3D tests; and the 3D names of the sparse compliance ([`crate::compliance::sparse`]).

use crate::dim::Dim3;

/// The 3D tissue: mesh, materials, fixed nodes, $K$, the factorised $K_{ff}$ and a point locator.
pub type TetTissueModel = crate::compliance::TissueModel<Dim3>;
/// Errors of the 3D tissue model.
pub type TetTissueError = crate::compliance::TissueError<Dim3>;
/// Scratch for [`TetTissueModel::compliance_columns_into`] and
/// [`TetTissueModel::displacement_for_point_loads_into`] (the same type in both dimensions).
pub type TetColumnScratch = crate::compliance::ColumnScratch;

pub use crate::compliance::sparse::{FactorPattern, SparseComplianceError, SparseRowsScratch};
/// A node's compliance rows $Y_v$, three force axes ([`crate::compliance::sparse`]).
pub type NodeRows = crate::compliance::sparse::NodeRows<3>;
/// The walkable view of a 3D factor ([`crate::compliance::sparse`]).
pub type SparseFactorView<'f> = crate::compliance::sparse::SparseFactorView<'f, 3>;
/// The sparse compliance of a 3D factor: $3 \times 3$ node and point blocks ([`crate::compliance::sparse`]).
pub type SparseCompliance<'f> = crate::compliance::sparse::SparseCompliance<'f, 3>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
    use crate::d3::assembly::TetMaterials;
    use crate::d3::locate::PointLocation;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use nalgebra::DMatrix;

    fn model() -> TetTissueModel {
        let mesh = BoxGridParams::new([4, 3, 4], [0.1, 0.08, 0.1]).build(&TetMeshLimits::default()).unwrap();
        // Two materials: the upper half 5x stiffer.
        let mats: Vec<Material> = (0..mesh.n_tets())
            .map(|t| {
                let z = mesh.tet_points_m(t).iter().map(|p| p[2]).sum::<f64>() / 4.0;
                Material { young_modulus_pa: if z > 0.05 { 75e3 } else { 15e3 }, poisson_ratio: 0.45 }
            })
            .collect();
        let mats = TetMaterials::per_element(&mesh, mats).unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        TetTissueModel::new(mesh, mats, &fixed).unwrap()
    }

    /// The columns equal those of $K_{ff}^{-1}$ computed densely, zero at the fixed DOFs.
    #[test]
    fn columns_equal_the_dense_inverse() {
        let m = model();
        let n_dofs = m.n_dofs();
        let kd = m.stiffness().to_dense();
        let free: Vec<usize> = (0..n_dofs).filter(|&d| !m.is_fixed(d / 3)).collect();
        let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| kd[(free[i], free[j])]);
        let inv = kff.try_inverse().unwrap();
        let scale = inv.amax();
        let mut scratch = m.column_scratch();
        let mut out = vec![0.0; 3 * n_dofs];
        for node in [0, 13, 20, m.mesh().n_nodes() - 1] {
            m.compliance_columns_into(node, &mut out, &mut scratch).unwrap();
            for axis in 0..3 {
                let col = &out[axis * n_dofs..(axis + 1) * n_dofs];
                match free.iter().position(|&d| d == 3 * node + axis) {
                    None => assert!(col.iter().all(|&v| v == 0.0), "fixed node {node} has zero columns"),
                    Some(j) => {
                        for d in 0..n_dofs {
                            let want = free.iter().position(|&f| f == d).map_or(0.0, |i| inv[(i, j)]);
                            assert!((col[d] - want).abs() < 1e-10 * scale, "node {node} axis {axis} dof {d}: {} vs {want}", col[d]);
                        }
                    }
                }
            }
        }
        // The node compliance block is the dense one.
        let nodes = [13, 20];
        let c = m.node_compliance(&nodes).unwrap();
        for (a, &na) in nodes.iter().enumerate() {
            for (b, &nb) in nodes.iter().enumerate() {
                for r in 0..3 {
                    for s in 0..3 {
                        let i = free.iter().position(|&f| f == 3 * na + r).unwrap();
                        let j = free.iter().position(|&f| f == 3 * nb + s).unwrap();
                        assert!((c[(3 * a + r) * 6 + 3 * b + s] - inv[(i, j)]).abs() < 1e-10 * scale);
                    }
                }
            }
        }
        assert_eq!(
            m.compliance_columns_into(999, &mut out, &mut scratch).unwrap_err(),
            TetTissueError::UnknownNode { node_idx: 999, n_nodes: 48 }
        );
    }

    /// $W = P C P^\top$ against the dense product at random material points.
    #[test]
    fn point_compliance_is_p_c_pt() {
        let m = model();
        let n_dofs = m.n_dofs();
        let kd = m.stiffness().to_dense();
        let free: Vec<usize> = (0..n_dofs).filter(|&d| !m.is_fixed(d / 3)).collect();
        let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| kd[(free[i], free[j])]);
        let inv = kff.try_inverse().unwrap();
        let xs = [[0.031, 0.042, 0.077], [0.051, 0.011, 0.033], [0.099, 0.07, 0.1]];
        let w = m.point_compliance_at(&xs).unwrap();
        let locs: Vec<PointLocation> = xs.iter().map(|&x| m.locate(x).unwrap()).collect();
        let mut p = DMatrix::<f64>::zeros(9, free.len());
        for (a, l) in locs.iter().enumerate() {
            for i in 0..4 {
                for r in 0..3 {
                    if let Some(f) = free.iter().position(|&d| d == 3 * l.nodes[i] + r) {
                        p[(3 * a + r, f)] += l.weights[i];
                    }
                }
            }
        }
        let want = &p * &inv * p.transpose();
        let scale = want.amax();
        for i in 0..9 {
            for j in 0..9 {
                assert!((w[i * 9 + j] - want[(i, j)]).abs() < 1e-10 * scale, "({i}, {j})");
            }
        }
        let e = m.point_compliance_at(&[[0.0, 0.0, 0.5]]).unwrap_err();
        assert!(e.to_string().starts_with("working point 0: the point"), "{e}");
    }

    /// The displacement under point loads (one solve) equals $\sum_i \sum_a N_a C_{\cdot,a} f_i$
    /// built from the compliance columns, at every DOF (the surface nodes among them: the session's
    /// surface field is this sum restricted to them), is zero at the fixed DOFs, and at the points
    /// themselves equals $W f$ with the point compliance.
    #[test]
    fn point_load_displacement_is_the_sum_of_compliance_columns() {
        let m = model();
        let n_dofs = m.n_dofs();
        // Three points inside, one in a tetrahedron touching the fixed bottom (z = 4 mm).
        let xs = [[0.031, 0.042, 0.077], [0.051, 0.011, 0.033], [0.0712, 0.0555, 0.004], [0.0499, 0.0401, 0.0903]];
        let forces = [[0.3, -0.1, -0.8], [-0.05, 0.2, 0.4], [0.1, 0.1, -0.6], [0.0, -0.25, 0.15]];
        let locs: Vec<PointLocation> = xs.iter().map(|&x| m.locate(x).unwrap()).collect();
        assert!(locs.iter().any(|l| l.nodes.iter().any(|&v| m.is_fixed(v))), "a point next to the support");
        let mut scratch = m.column_scratch();
        let mut u = vec![f64::NAN; n_dofs];
        m.displacement_for_point_loads_into(&locs, &forces, &mut u, &mut scratch).unwrap();
        let mut want = vec![0.0; n_dofs];
        let mut cols = vec![0.0; 3 * n_dofs];
        for (l, f) in locs.iter().zip(&forces) {
            for (&node, &weight) in l.nodes.iter().zip(&l.weights) {
                m.compliance_columns_into(node, &mut cols, &mut scratch).unwrap();
                for (axis, &fa) in f.iter().enumerate() {
                    for (w, c) in want.iter_mut().zip(&cols[axis * n_dofs..(axis + 1) * n_dofs]) {
                        *w += weight * fa * c;
                    }
                }
            }
        }
        let scale = want.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        assert!(scale > 1e-6, "the loads move the tissue: {scale} m");
        for d in 0..n_dofs {
            assert!((u[d] - want[d]).abs() <= 1e-12 * scale, "dof {d}: {} vs {}", u[d], want[d]);
            if m.is_fixed(d / 3) {
                assert_eq!(u[d], 0.0, "fixed dof {d}");
            }
        }
        // At the points: P u = W f.
        let w = m.point_compliance(&locs).unwrap();
        let f: Vec<f64> = forces.iter().flatten().copied().collect();
        for (a, l) in locs.iter().enumerate() {
            for r in 0..3 {
                let pu: f64 = (0..4).map(|k| l.weights[k] * u[3 * l.nodes[k] + r]).sum();
                let wf: f64 = (0..f.len()).map(|j| w[(3 * a + r) * f.len() + j] * f[j]).sum();
                assert!((pu - wf).abs() <= 1e-12 * scale, "point {a} axis {r}: {pu} vs {wf}");
            }
        }
        // No points: no displacement, over whatever was there.
        m.displacement_for_point_loads_into(&[], &[], &mut u, &mut scratch).unwrap();
        assert!(u.iter().all(|&v| v == 0.0));
    }

    /// Bad input to the point-load solve is refused with the error naming it, and nothing is written.
    #[test]
    fn point_load_errors() {
        let m = model();
        let n_dofs = m.n_dofs();
        let mut scratch = m.column_scratch();
        let good = m.locate([0.05, 0.04, 0.05]).unwrap();
        let mut u = vec![7.0; n_dofs];
        let e = m.displacement_for_point_loads_into(&[good, good], &[[0.0; 3]], &mut u, &mut scratch).unwrap_err();
        assert_eq!(e, TetTissueError::LoadCount { n_points: 2, n_forces: 1 });
        let e = m.displacement_for_point_loads_into(&[good], &[[0.0; 3]], &mut u[1..], &mut scratch).unwrap_err();
        assert_eq!(e, TetTissueError::OutputLength { len: n_dofs - 1, n_dofs });
        let bad = PointLocation { nodes: [0, 1, 2, 48], ..good };
        let e = m.displacement_for_point_loads_into(&[good, bad], &[[0.0; 3]; 2], &mut u, &mut scratch).unwrap_err();
        assert_eq!(e, TetTissueError::UnknownNode { node_idx: 48, n_nodes: 48 });
        let e = m.displacement_for_point_loads_into(&[good, good], &[[0.0; 3], [0.0, f64::NAN, 1.0]], &mut u, &mut scratch).unwrap_err();
        assert!(matches!(e, TetTissueError::NonFiniteForce { point_idx: 1, .. }), "{e:?}");
        assert!(e.to_string().contains("load point 1"), "{e}");
        assert!(u.iter().all(|&v| v == 7.0), "nothing written on an error");
    }

    /// A 3D insertion's contact points sit where the one solve puts the tissue: interpolating
    /// $u = K_{ff}^{-1} P^\top f$ of the tick's contact forces at each contact's reference
    /// position gives its deformed position $x_i - X_i$ (the simulation's own displacements, from
    /// its point compliance); and the shared model solves the same from another thread.
    #[test]
    fn point_load_displacement_puts_the_contacts_where_the_simulation_has_them() {
        use crate::fixtures::{box_phantom3, box_phantom3_params};
        use crate::sim3::{BasePose3, Simulation3};
        let model = box_phantom3(9);
        let mut sim = Simulation3::new(model.clone(), box_phantom3_params([0.0513, 0.0487, 0.1], 0.005)).unwrap();
        let start = sim.pose();
        let p0 = start.position_m;
        // 40 mm down, then 1.5 mm sideways (lateral loads too).
        for k in 1..=2000 {
            sim.step(BasePose3::from_rotation([p0[0], p0[1], p0[2] - 2e-5 * k as f64], start.orientation)).unwrap();
            sim.prefetch_columns(usize::MAX).unwrap();
        }
        for k in 1..=150 {
            sim.step(BasePose3::from_rotation([p0[0] + 1e-5 * k as f64, p0[1], p0[2] - 0.04], start.orientation)).unwrap();
            sim.prefetch_columns(usize::MAX).unwrap();
        }
        let out = sim.output();
        assert!(out.contacts.len() >= 2, "the needle holds points: {}", out.contacts.len());
        let locs: Vec<PointLocation> = out.contacts.iter().map(|c| model.locate(c.x_ref_m).unwrap()).collect();
        let forces: Vec<[f64; 3]> = out.contacts.iter().map(|c| c.force_n).collect();
        let mut u = vec![0.0; model.n_dofs()];
        model.displacement_for_point_loads_into(&locs, &forces, &mut u, &mut model.column_scratch()).unwrap();
        let (mut err, mut size, mut lateral) = (0.0_f64, 0.0_f64, 0.0_f64);
        for (c, l) in out.contacts.iter().zip(&locs) {
            for r in 0..3 {
                let at: f64 = (0..4).map(|k| l.weights[k] * u[3 * l.nodes[k] + r]).sum();
                let want = c.x_m[r] - c.x_ref_m[r];
                err = err.max((at - want).abs());
                size = size.max(want.abs());
            }
            lateral = lateral.max(c.force_n[0].abs());
        }
        assert!(size > 1e-4 && lateral > 1e-3, "the tissue moved ({size} m) under lateral loads ({lateral} N)");
        assert!(err <= 1e-9 * size, "contacts off their solved positions by {err:e} m (displacements up to {size:e} m)");
        let (m2, l2, f2) = (model.clone(), locs.clone(), forces.clone());
        let other = std::thread::spawn(move || {
            let mut u = vec![0.0; m2.n_dofs()];
            m2.displacement_for_point_loads_into(&l2, &f2, &mut u, &mut m2.column_scratch()).unwrap();
            u
        })
        .join()
        .unwrap();
        assert_eq!(other, u, "the same solve from another thread");
    }

    /// Timing on the 21³ box grid (48 000 tetrahedra), bottom fixed; run in release:
    /// `cargo test --release -p needlesim-core --lib d3::tissue::tests::timing_21_cubed -- --ignored --nocapture`.
    #[test]
    #[ignore = "timing; run in release"]
    fn timing_21_cubed() {
        use std::time::Instant;
        let t0 = Instant::now();
        let mesh = BoxGridParams::new([21, 21, 21], [0.1, 0.1, 0.1]).build(&TetMeshLimits::default()).unwrap();
        let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }]).unwrap();
        let fixed = mesh.boundary_set("bottom").unwrap().to_vec();
        let t_mesh = t0.elapsed();
        let t1 = Instant::now();
        let m = TetTissueModel::new(mesh, mats, &fixed).unwrap();
        let t_model = t1.elapsed();
        let mut scratch = m.column_scratch();
        let mut out = vec![0.0; 3 * m.n_dofs()];
        let nodes: Vec<usize> = (0..m.mesh().n_nodes()).filter(|&n| !m.is_fixed(n)).step_by(37).take(200).collect();
        let t2 = Instant::now();
        for &n in &nodes {
            m.compliance_columns_into(n, &mut out, &mut scratch).unwrap();
        }
        let per_node = t2.elapsed() / nodes.len() as u32;
        println!(
            "21^3 box: {} nodes, {} tets, factor nnz {}, mesh {:?}, assemble + factorise (and locator) {:?}, 3 columns per node {:?} (mean of {})",
            m.mesh().n_nodes(),
            m.mesh().n_tets(),
            m.cholesky().factor_nnz(),
            t_mesh,
            t_model,
            per_node,
            nodes.len()
        );
    }
}
