//! The 3D pieces of the static solve ([`crate::statics`], written once over the dimension): a
//! frame is three orthonormal rows $t, n, b$ ([`check_frame`], to [`FRAME_TOL`]), material points
//! are located by [`super::TetLocator`], the 3D wording of the errors, and the 3D names of the
//! generic types: [`TetStaticProblem`] $=$ `StaticProblem<Dim3>` and its companions.
//!
//! Node conditions are eliminated (frame nodes in their frames, $T^\top K T$); material points are
//! constraint rows $G u = g$ condensed on a dense Schur complement $S = G K_{II}^{-1} G^\top$
//! after one sparse Cholesky of $K_{II}$; dependent rows (a third point of a straight needle in
//! one tetrahedron, a point on a fixed face) are a typed error naming the points. See
//! [`crate::statics`] for the mathematics.

use crate::dim::{ConditionLabel, Dim3};
pub use crate::statics::{DEPENDENT_PIVOT, FIXED_ROW_WEIGHT, FRAME_COMPONENTS};

/// Largest deviation $\max|F F^\top - I|$ accepted for a frame.
pub const FRAME_TOL: f64 = 1e-9;

/// A condition on one node: `Fixed`, `World { u_m: [ux, uy, uz] }` or `Local { frame, u_m: [ut, un, ub] }`.
pub type TetNodeCondition = crate::statics::NodeCondition<Dim3>;
/// Conditions at a material point (position, frame, prescribed frame components, force).
pub type PointCondition = crate::statics::PointCondition<Dim3>;
/// A static problem on a tetrahedral mesh.
pub type TetStaticProblem = crate::statics::StaticProblem<Dim3>;
/// Errors of a 3D static problem.
pub type TetStaticError = crate::statics::StaticError<Dim3>;
/// The result at one material point.
pub type PointReaction = crate::statics::PointReaction<Dim3>;
/// The solution of a 3D static problem.
pub type TetStaticSolution = crate::statics::StaticSolution<Dim3>;

/// Checks a frame's orthonormality and finiteness.
pub fn check_frame(frame: &[[f64; 3]; 3], what: &str) -> Result<(), TetStaticError> {
    if !frame.iter().flatten().all(|v| v.is_finite()) {
        return Err(TetStaticError::NonFinite { what: format!("{what}: the frame") });
    }
    let mut deviation = 0.0f64;
    for i in 0..3 {
        for j in 0..3 {
            let d: f64 = (0..3).map(|k| frame[i][k] * frame[j][k]).sum();
            deviation = deviation.max((d - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    if !(deviation <= FRAME_TOL) {
        return Err(TetStaticError::Frame { what: what.to_owned(), deviation });
    }
    Ok(())
}

/// The 3D wording: "a prescribed displacement of node 3", "prescribed_local node 3" (its frame),
/// "a prescribed_local displacement of node 3".
pub fn condition_label(label: ConditionLabel, node: usize) -> String {
    match label {
        ConditionLabel::World => format!("a prescribed displacement of node {node}"),
        ConditionLabel::LocalFrame => format!("prescribed_local node {node}"),
        ConditionLabel::LocalValue => format!("a prescribed_local displacement of node {node}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
    use crate::d3::assembly::TetMaterials;
    use crate::d3::locate::TetLocator;
    use crate::d3::mesh::TetMesh;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};

    fn setup(n: usize) -> (TetMesh, TetMaterials) {
        let mesh = BoxGridParams::new([n, n, n], [0.1, 0.1, 0.1]).build(&TetMeshLimits::default()).unwrap();
        let mats = TetMaterials::per_region(&mesh, &[Material { young_modulus_pa: 15e3, poisson_ratio: 0.45 }]).unwrap();
        (mesh, mats)
    }

    fn bottom_fixed(mesh: &TetMesh) -> Vec<(usize, TetNodeCondition)> {
        mesh.boundary_set("bottom").unwrap().iter().map(|&n| (n, TetNodeCondition::Fixed)).collect()
    }

    fn rotation(a: f64, b: f64) -> [[f64; 3]; 3] {
        // Rz(a) Rx(b), rows as the frame.
        let (sa, ca) = a.sin_cos();
        let (sb, cb) = b.sin_cos();
        let rz = [[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]];
        let rx = [[1.0, 0.0, 0.0], [0.0, cb, -sb], [0.0, sb, cb]];
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| rz[i][k] * rx[k][j]).sum()))
    }

    /// A node held in a tilted frame gives the same field as the same vector prescribed in world
    /// components, and a material point at a node equals that node's local condition.
    #[test]
    fn local_frames_and_points_at_nodes_agree_with_world_conditions() {
        let (mesh, mats) = setup(5);
        let node = mesh.nodes_where(2, 0.1, 1e-12)[7];
        let target = [1e-3, -2e-3, 5e-4];
        let frame = rotation(0.7, -0.4);
        let local: [Option<f64>; 3] = std::array::from_fn(|c| Some((0..3).map(|a| frame[c][a] * target[a]).sum()));
        let loads = vec![(30, [0.01, 0.02, -0.03])];
        let mut world = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: loads.clone(), points: vec![], patches: vec![] };
        world.conditions.push((node, TetNodeCondition::World { u_m: target.map(Some) }));
        let mut held = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: loads.clone(), points: vec![], patches: vec![] };
        held.conditions.push((node, TetNodeCondition::Local { frame, u_m: local }));
        let point = TetStaticProblem {
            conditions: bottom_fixed(&mesh),
            loads_n: loads,
            points: vec![PointCondition { x_m: mesh.nodes_m()[node], frame, u_m: local, force_n: [0.0; 3] }],
            patches: vec![],
        };
        let sw = world.solve(&mesh, &mats).unwrap();
        let sl = held.solve(&mesh, &mats).unwrap();
        let sp = point.solve(&mesh, &mats).unwrap();
        let scale = sw.displacement_m.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for s in [&sl, &sp] {
            for (x, y) in sw.displacement_m.iter().zip(&s.displacement_m) {
                assert!((x - y).abs() < 1e-12 * scale, "{x} vs {y}");
            }
            assert!((sw.strain_energy_j - s.strain_energy_j).abs() < 1e-11 * sw.strain_energy_j);
        }
        let rw = sw.reactions_n.iter().find(|r| r.0 == node).unwrap().1.map(Option::unwrap);
        let rl = sl.reactions_n.iter().find(|r| r.0 == node).unwrap().1.map(Option::unwrap);
        let rp = sp.point_reactions[0].force_n;
        for a in 0..3 {
            assert!((rw[a] - rl[a]).abs() < 1e-9 * rw[a].abs().max(1e-3), "{rw:?} vs {rl:?}");
            assert!((rw[a] - rp[a]).abs() < 1e-9 * rw[a].abs().max(1e-3), "{rw:?} vs {rp:?}");
        }
        // Equilibrium: the support reactions balance the load and the held node's force.
        let mut sum = [0.0; 3];
        for (_, r) in &sl.reactions_n {
            for a in 0..3 {
                sum[a] += r[a].unwrap_or(0.0);
            }
        }
        let load = [0.01, 0.02, -0.03];
        for a in 0..3 {
            assert!((sum[a] + load[a]).abs() < 1e-10, "axis {a}: {}", sum[a] + load[a]);
        }
    }

    /// Three points of one straight needle in one tetrahedron prescribe a linear field three
    /// times along a line: a typed error naming them, not a NaN answer.
    #[test]
    fn dependent_points_are_a_named_error() {
        let (mesh, mats) = setup(3);
        // A vertical line inside one tetrahedron of the upper layer (all its nodes free).
        let frame = [[0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]];
        let loc = TetLocator::new(&mesh);
        let base = [0.03, 0.02, 0.06];
        let t0 = loc.locate(&mesh, base).unwrap().tet_idx;
        let pts: Vec<PointCondition> = (0..3)
            .map(|k| PointCondition {
                x_m: [base[0], base[1], base[2] + 0.001 * k as f64],
                frame,
                u_m: [None, Some(1e-4), Some(0.0)],
                force_n: [0.0; 3],
            })
            .collect();
        for p in &pts {
            assert_eq!(loc.locate(&mesh, p.x_m).unwrap().tet_idx, t0);
        }
        let two = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: vec![], points: pts[..2].to_vec(), patches: vec![] };
        assert!(two.solve(&mesh, &mats).is_ok());
        let three = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: vec![], points: pts, patches: vec![] };
        let e = three.solve(&mesh, &mats).unwrap_err();
        match &e {
            TetStaticError::DependentConstraint { points, what, .. } => {
                assert_eq!(points, &vec![0, 1, 2]);
                assert_eq!(what, "un of point 2");
            }
            _ => panic!("{e}"),
        }
        assert!(e.to_string().contains(&format!("points [0, 1, 2] lie in tetrahedron {t0}")), "{e}");
        // A point on the fixed bottom face cannot be moved.
        let on_floor = TetStaticProblem {
            conditions: bottom_fixed(&mesh),
            loads_n: vec![],
            points: vec![PointCondition { x_m: [0.03, 0.02, 0.0], frame, u_m: [Some(1e-3), None, None], force_n: [0.0; 3] }],
            patches: vec![],
        };
        let e = on_floor.solve(&mesh, &mats).unwrap_err();
        assert!(matches!(e, TetStaticError::DependentConstraint { .. }), "{e}");
        assert!(e.to_string().contains("the condition ut of point 0 depends") && e.to_string().contains("are all fixed"), "{e}");
    }

    #[test]
    fn bad_input_is_named() {
        let (mesh, mats) = setup(3);
        let frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let p = |c: Vec<(usize, TetNodeCondition)>| TetStaticProblem { conditions: c, loads_n: vec![], points: vec![], patches: vec![] };
        let e = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: vec![(27, [1.0, 0.0, 0.0])], points: vec![], patches: vec![] }
            .solve(&mesh, &mats)
            .unwrap_err();
        assert!(e.to_string().contains("a load names node 27"), "{e}");
        let mut c = bottom_fixed(&mesh);
        c.push((0, TetNodeCondition::Local { frame, u_m: [Some(0.0); 3] }));
        assert_eq!(p(c).solve(&mesh, &mats).unwrap_err(), TetStaticError::Conflict { node_idx: 0 });
        let mut c = bottom_fixed(&mesh);
        let skew = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        c.push((20, TetNodeCondition::Local { frame: skew, u_m: [Some(0.0); 3] }));
        let e = p(c).solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().starts_with("prescribed_local node 20: the frame must be three orthonormal rows"), "{e}");
        let e = TetStaticProblem {
            conditions: bottom_fixed(&mesh),
            loads_n: vec![],
            points: vec![PointCondition { x_m: [0.2, 0.0, 0.0], frame, u_m: [None; 3], force_n: [0.0; 3] }],
            patches: vec![],
        }
        .solve(&mesh, &mats)
        .unwrap_err();
        assert!(e.to_string().starts_with("point 0: the point (0.2, 0, 0) m lies outside the mesh"), "{e}");
        let e = p(vec![]).solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("rigid body"), "{e}");
    }
}
