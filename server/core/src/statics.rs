//! Static solves of a full problem: fixed nodes, prescribed displacements (in world or rotated
//! local node frames) and nodal loads; results with reactions, strain energy and stresses.
//!
//! Nodes with a local frame of angle $a$ use DOFs $(u_t, u_n)$ with $t = (\cos a, \sin a)$ and
//! $n = (-\sin a, \cos a)$. With $u = T u_{loc}$ the system is $T^\top K T\, u_{loc} = T^\top f$;
//! the constrained DOFs $D$ are eliminated, $K_{II} u_I = f_I - K_{ID} u_D$, and the reactions are
//! $r = K u - f$ on the constrained DOFs.

use crate::assembly::{MaterialMap, assemble_stiffness, element_stresses_pa, mul_stiffness};
use crate::factor::{DofMap, FactorError, SparseCholesky};
use crate::mesh::Mesh;

/// A condition on one node. Components set to `None` are free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeCondition {
    /// Both components zero.
    Fixed,
    /// Prescribed world components.
    World { ux_m: Option<f64>, uy_m: Option<f64> },
    /// Prescribed components in a frame rotated by `angle_rad`.
    Local { angle_rad: f64, ut_m: Option<f64>, un_m: Option<f64> },
}

/// A static problem on a mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StaticProblem {
    /// Conditions by node; a node appears at most once (world entries for the same node merge).
    pub conditions: Vec<(usize, NodeCondition)>,
    /// Nodal point forces `(node, [fx, fy])` in N, world components; repeated entries add.
    pub loads_n: Vec<(usize, [f64; 2])>,
}

/// Errors of a static problem, each naming the offending node.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError {
    /// A condition or load names a node that does not exist.
    #[error("{what} names node {node_idx}, but the mesh has only {n_nodes} nodes")]
    UnknownNode { what: &'static str, node_idx: usize, n_nodes: usize },
    /// A value is NaN or infinite.
    #[error("{what} on node {node_idx} is not finite")]
    NonFinite { what: &'static str, node_idx: usize },
    /// A node has more than one kind of condition (fixed, world, local frame).
    #[error("node {node_idx} has more than one kind of condition (fixed, prescribed, prescribed_local); a node takes at most one")]
    Conflict { node_idx: usize },
    /// The factorisation failed (for example: rigid-body motion).
    #[error(transparent)]
    Factor(#[from] FactorError),
}

/// The solution of a static problem.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution {
    /// World displacements, interleaved `[ux0, uy0, …]`, in m.
    pub displacement_m: Vec<f64>,
    /// For every node with a constrained component: `(node, [rx, ry])` in world components; a
    /// free component is `None`, except at local-frame nodes where both world components are given.
    pub reactions_n: Vec<(usize, [Option<f64>; 2])>,
    /// For local-frame nodes: `(node, angle_rad, [rt, rn])`, `None` for a free component.
    pub reactions_local_n: Vec<(usize, f64, [Option<f64>; 2])>,
    /// $\tfrac12 u^\top K u$ in J.
    pub strain_energy_j: f64,
}

impl StaticProblem {
    /// Solves the problem with a fresh factorisation of the free block.
    pub fn solve(&self, mesh: &Mesh, materials: &MaterialMap) -> Result<StaticSolution, StaticError> {
        let n_nodes = mesh.n_nodes();
        let n_dofs = 2 * n_nodes;
        let mut constrained = vec![false; n_dofs];
        let mut value = vec![0.0; n_dofs];
        let mut angle: Vec<Option<f64>> = vec![None; n_nodes];
        let check_node = |what, node_idx| {
            if node_idx >= n_nodes { Err(StaticError::UnknownNode { what, node_idx, n_nodes }) } else { Ok(()) }
        };
        let check_finite = |what, node_idx, v: Option<f64>| {
            if v.is_some_and(|v| !v.is_finite()) { Err(StaticError::NonFinite { what, node_idx }) } else { Ok(()) }
        };
        let mut set = |dof: usize, v: Option<f64>| {
            if let Some(v) = v {
                constrained[dof] = true;
                value[dof] = v;
            }
        };
        // Local conditions first so that conflicts can be found in one pass.
        for &(node, c) in &self.conditions {
            if let NodeCondition::Local { angle_rad, ut_m, un_m } = c {
                check_node("a local-frame condition", node)?;
                check_finite("a local-frame condition", node, Some(angle_rad))?;
                check_finite("a local-frame condition", node, ut_m)?;
                check_finite("a local-frame condition", node, un_m)?;
                if angle[node].is_some() {
                    return Err(StaticError::Conflict { node_idx: node });
                }
                angle[node] = Some(angle_rad);
                set(2 * node, ut_m);
                set(2 * node + 1, un_m);
            }
        }
        let mut kind_seen = vec![0u8; n_nodes];
        for &(node, c) in &self.conditions {
            check_node("a condition", node)?;
            let bit = match c {
                NodeCondition::Fixed => 1,
                NodeCondition::World { .. } => 2,
                NodeCondition::Local { .. } => 4,
            };
            if kind_seen[node] & !bit != 0 {
                return Err(StaticError::Conflict { node_idx: node });
            }
            kind_seen[node] |= bit;
        }
        for &(node, c) in &self.conditions {
            let (ux, uy) = match c {
                NodeCondition::Fixed => (Some(0.0), Some(0.0)),
                NodeCondition::World { ux_m, uy_m } => (ux_m, uy_m),
                NodeCondition::Local { .. } => continue,
            };
            check_node("a fixed or prescribed node", node)?;
            check_finite("a prescribed displacement", node, ux)?;
            check_finite("a prescribed displacement", node, uy)?;
            if angle[node].is_some() {
                return Err(StaticError::Conflict { node_idx: node });
            }
            set(2 * node, ux);
            set(2 * node + 1, uy);
        }
        let mut f_world = vec![0.0; n_dofs];
        for &(node, [fx, fy]) in &self.loads_n {
            check_node("a load", node)?;
            check_finite("a load", node, Some(fx))?;
            check_finite("a load", node, Some(fy))?;
            f_world[2 * node] += fx;
            f_world[2 * node + 1] += fy;
        }
        let any_rotated = angle.iter().any(Option::is_some);
        let k = assemble_stiffness(mesh, materials, any_rotated.then_some(angle.as_slice()));
        // Loads to local frames: f_loc = T^T f.
        let mut f = f_world.clone();
        for (node, a) in angle.iter().enumerate() {
            if let Some(a) = *a {
                let (s, c) = a.sin_cos();
                let (fx, fy) = (f_world[2 * node], f_world[2 * node + 1]);
                f[2 * node] = c * fx + s * fy;
                f[2 * node + 1] = -s * fx + c * fy;
            }
        }
        // u_D known; rhs = f_I - K_ID u_D.
        let mut u = value.clone();
        for (d, c) in constrained.iter().enumerate() {
            if !c {
                u[d] = 0.0;
            }
        }
        let mut ku = vec![0.0; n_dofs];
        mul_stiffness(&k, &u, &mut ku);
        let dofs = DofMap::new(&constrained);
        // With every DOF prescribed the displacement is known and only reactions remain.
        if dofs.n_free() > 0 {
            let chol = SparseCholesky::new(&k, dofs)?;
            let free = chol.dofs().free_dofs().to_vec();
            let mut rhs = faer::Mat::<f64>::from_fn(free.len(), 1, |i, _| f[free[i]] - ku[free[i]]);
            let mut scratch = chol.scratch(1);
            chol.solve_in_place(rhs.as_mut(), &mut scratch);
            for (i, &d) in free.iter().enumerate() {
                u[d] = rhs[(i, 0)];
            }
        }
        // Residual r = K u - f: reactions at constrained DOFs (local frames where rotated).
        mul_stiffness(&k, &u, &mut ku);
        let r_loc: Vec<f64> = ku.iter().zip(&f).map(|(a, b)| a - b).collect();
        let strain_energy_j = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
        let mut u_world = u.clone();
        let mut r_world = r_loc.clone();
        for (node, a) in angle.iter().enumerate() {
            if let Some(a) = *a {
                let (s, c) = a.sin_cos();
                for v in [&mut u_world, &mut r_world] {
                    let (t, n) = (v[2 * node], v[2 * node + 1]);
                    v[2 * node] = c * t - s * n;
                    v[2 * node + 1] = s * t + c * n;
                }
            }
        }
        let mut reactions_n = Vec::new();
        let mut reactions_local_n = Vec::new();
        for node in 0..n_nodes {
            let (cx, cy) = (constrained[2 * node], constrained[2 * node + 1]);
            if !(cx || cy) {
                continue;
            }
            if let Some(a) = angle[node] {
                reactions_n.push((node, [Some(r_world[2 * node]), Some(r_world[2 * node + 1])]));
                reactions_local_n.push((node, a, [cx.then_some(r_loc[2 * node]), cy.then_some(r_loc[2 * node + 1])]));
            } else {
                reactions_n.push((node, [cx.then_some(r_world[2 * node]), cy.then_some(r_world[2 * node + 1])]));
            }
        }
        Ok(StaticSolution { displacement_m: u_world, reactions_n, reactions_local_n, strain_energy_j })
    }
}

impl StaticSolution {
    /// Element stresses for this solution.
    pub fn element_stresses_pa(&self, mesh: &Mesh, materials: &MaterialMap) -> Vec<[f64; 3]> {
        element_stresses_pa(mesh, materials, &self.displacement_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Material, PlaneModel};
    use crate::mesh::{MeshLimits, RectMeshParams};

    /// A bar under uniform tension: linear triangles reproduce the linear exact field.
    #[test]
    fn uniaxial_bar_is_exact() {
        let (l, h, e, nu, sig) = (2.0, 1.0, 1000.0, 0.3, 5.0);
        let mesh = RectMeshParams::new(9, 5, l, h).build(&MeshLimits::default()).unwrap();
        let plane = PlaneModel::Stress { thickness_m: 1.0 };
        let mats = MaterialMap::per_region(&mesh, &[Material { young_modulus_pa: e, poisson_ratio: nu }], plane).unwrap();
        let mut p = StaticProblem::default();
        for &n in mesh.boundary_set("left").unwrap() {
            p.conditions.push((n, NodeCondition::World { ux_m: Some(0.0), uy_m: (n == 0).then_some(0.0) }));
        }
        let right = mesh.boundary_set("right").unwrap();
        let seg = h / (right.len() - 1) as f64;
        for (k, &n) in right.iter().enumerate() {
            let w = if k == 0 || k + 1 == right.len() { 0.5 } else { 1.0 };
            p.loads_n.push((n, [sig * seg * w, 0.0]));
        }
        let s = p.solve(&mesh, &mats).unwrap();
        for (i, q) in mesh.nodes_m().iter().enumerate() {
            assert!((s.displacement_m[2 * i] - sig * q[0] / e).abs() < 1e-12 * sig * l / e);
            assert!((s.displacement_m[2 * i + 1] + nu * sig * q[1] / e).abs() < 1e-12 * sig * l / e);
        }
        let rx: f64 = s.reactions_n.iter().filter_map(|r| r.1[0]).sum();
        assert!((rx + sig * h).abs() < 1e-12 * sig * h);
    }

    /// A local frame at angle 0 is the world frame; at any angle the solution is the same when
    /// the prescribed vector is the same.
    #[test]
    fn local_frames_agree_with_world_conditions() {
        let mesh = RectMeshParams::new(6, 6, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let plane = PlaneModel::Strain { thickness_m: 1.0 };
        let mats = MaterialMap::per_region(&mesh, &[Material { young_modulus_pa: 10.0, poisson_ratio: 0.4 }], plane).unwrap();
        let fixed: Vec<_> = mesh.boundary_set("bottom").unwrap().iter().map(|&n| (n, NodeCondition::Fixed)).collect();
        let target = [0.01, -0.02];
        let mut world = StaticProblem { conditions: fixed.clone(), loads_n: vec![(20, [0.3, 0.1])] };
        world.conditions.push((33, NodeCondition::World { ux_m: Some(target[0]), uy_m: Some(target[1]) }));
        let a: f64 = 0.83;
        let (s, c) = a.sin_cos();
        let mut local = StaticProblem { conditions: fixed, loads_n: vec![(20, [0.3, 0.1])] };
        local.conditions.push((
            33,
            NodeCondition::Local { angle_rad: a, ut_m: Some(c * target[0] + s * target[1]), un_m: Some(-s * target[0] + c * target[1]) },
        ));
        let sw = world.solve(&mesh, &mats).unwrap();
        let sl = local.solve(&mesh, &mats).unwrap();
        let scale = sw.displacement_m.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (x, y) in sw.displacement_m.iter().zip(&sl.displacement_m) {
            assert!((x - y).abs() < 1e-12 * scale);
        }
        assert!((sw.strain_energy_j - sl.strain_energy_j).abs() < 1e-12 * sw.strain_energy_j);
    }

    #[test]
    fn bad_conditions_are_named() {
        let mesh = RectMeshParams::new(3, 3, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 10.0, poisson_ratio: 0.3 }],
            PlaneModel::Strain { thickness_m: 1.0 },
        )
        .unwrap();
        let fixed = vec![(0, NodeCondition::Fixed), (1, NodeCondition::Fixed)];
        let p = StaticProblem { conditions: fixed.clone(), loads_n: vec![(9, [1.0, 0.0])] };
        let e = p.solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("a load names node 9"), "{e}");
        let p = StaticProblem { conditions: fixed.clone(), loads_n: vec![(4, [f64::NAN, 0.0])] };
        assert!(p.solve(&mesh, &mats).unwrap_err().to_string().contains("a load on node 4 is not finite"));
        let mut c = fixed.clone();
        c.push((0, NodeCondition::Local { angle_rad: 0.1, ut_m: None, un_m: Some(0.0) }));
        let e = StaticProblem { conditions: c, loads_n: vec![] }.solve(&mesh, &mats).unwrap_err();
        assert_eq!(e, StaticError::Conflict { node_idx: 0 });
        let e = StaticProblem { conditions: vec![], loads_n: vec![(4, [1.0, 0.0])] }.solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("rigid body"), "{e}");
        let mut c = fixed.clone();
        c.push((1, NodeCondition::World { ux_m: Some(0.1), uy_m: None }));
        let e = StaticProblem { conditions: c, loads_n: vec![] }.solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("node 1 has more than one kind of condition"), "{e}");
    }

    /// With every DOF prescribed the field is known; the reactions are $K u - f$.
    #[test]
    fn fully_prescribed_problem_gives_reactions() {
        let mesh = RectMeshParams::new(3, 3, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 10.0, poisson_ratio: 0.3 }],
            PlaneModel::Strain { thickness_m: 1.0 },
        )
        .unwrap();
        let conditions = (0..9).map(|n| (n, NodeCondition::World { ux_m: Some(0.01 * n as f64), uy_m: Some(0.0) })).collect();
        let s = StaticProblem { conditions, loads_n: vec![] }.solve(&mesh, &mats).unwrap();
        assert_eq!(s.displacement_m[2 * 8], 0.08);
        let sum: f64 = s.reactions_n.iter().map(|r| r.1[0].unwrap()).sum();
        assert!(sum.abs() < 1e-12, "reactions balance: {sum}");
        assert!(s.strain_energy_j > 0.0);
    }
}
