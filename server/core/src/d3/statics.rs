//! Static solves on a tetrahedral mesh: fixed nodes, prescribed world components, components
//! prescribed in a node's local frame, conditions at material points, nodal and point loads;
//! results with reactions (world and frame), point reactions, strain energy.
//!
//! **Conditions.** World-prescribed DOFs $D$ (fixed nodes, `World` components) are eliminated. Every
//! other condition is a constraint row: a `Local` node with frame rows $t, n, b$ prescribes
//! $F_c \cdot u_k = g$ for its listed components $c$; a material point at $x$ in tetrahedron
//! $(k_1..k_4)$ with weights $N_i(x)$ prescribes $F_c \cdot \sum_i N_i(x) u_{k_i} = g$. Together
//! $G u = g$ ($q$ rows, $G$ is $q \times 3n$). A point force $f_p$ at $x$ adds $N_i(x) f_p$ to each of its
//! element's nodes.
//!
//! **Solve.** With $I$ the remaining DOFs, $K_{II}$ is factorised once (sparse Cholesky) and the
//! constraints are condensed onto a dense $q \times q$ Schur complement:
//! $$u^0_I = K_{II}^{-1}(f_I - K_{ID} u_D),\quad Y = K_{II}^{-1} G_I^\top,\quad S = G_I Y,$$
//! $$S\,\lambda = G_I u^0_I + G_D u_D - g,\qquad u_I = u^0_I - Y\lambda .$$
//! This is the KKT system $K u + G^\top\lambda = f$, $G u = g$; the force the constraints exert on
//! the tissue is $\mu = -\lambda$. The cost is one factorisation, $q + 1$ solves and an
//! $O(q^3)$ dense factorisation, so it scales to meshes of $10^5$ nodes with tens of points.
//!
//! **Independence.** $S$ is factorised row by row (Cholesky, in the order the conditions are
//! given: local nodes, then points in order, components $t, n, b$). A row whose pivot falls to
//! $\le 10^{-10}$ of its diagonal ([`DEPENDENT_PIVOT`]) is (numerically) a combination of the rows
//! before it — e.g. a third point of one straight needle in one linear tetrahedron, or a point
//! whose element nodes are all fixed — and the solve stops with
//! [`TetStaticError::DependentConstraint`] naming it and the points sharing its element, instead of
//! returning a meaningless answer.
//!
//! **Outputs.** Reactions $r = K u - f - G^\top\mu$ at the world-prescribed DOFs (the point and
//! local constraints' share removed); a local node's reaction is the world force
//! $\sum_c \mu_c F_c$ of its constraint and its frame components $\mu_c$; likewise for points, with
//! the displacement $u(x)$. Strain energy $\tfrac12 u^\top K u$.

use faer::Mat;

use super::assembly::{TetMaterials, assemble_stiffness, element_stresses_pa};
use super::locate::{LocateError, PointLocation, TetLocator};
use super::mesh::TetMesh;
use crate::assembly::mul_stiffness;
use crate::factor::{DofMap, FactorError, SparseCholesky};

/// A constraint row whose Cholesky pivot in the Schur complement is at most this fraction of its
/// diagonal depends on the rows before it.
pub const DEPENDENT_PIVOT: f64 = 1e-10;

/// A constraint row whose weights on free DOFs are at most this fraction of its weights (2-norm)
/// involves no free DOF: its point lies on an entirely fixed face, edge or node (to the
/// round-off of the barycentric weights).
pub const FIXED_ROW_WEIGHT: f64 = 1e-10;

/// Largest deviation $\max|F F^\top - I|$ accepted for a frame.
pub const FRAME_TOL: f64 = 1e-9;

/// Frame components, in the order of a frame's rows: along the needle, and two across it.
pub const FRAME_COMPONENTS: [&str; 3] = ["t", "n", "b"];

/// A condition on one node. Components set to `None` are free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TetNodeCondition {
    /// All three components zero.
    Fixed,
    /// Prescribed world components $[u_x, u_y, u_z]$ in m.
    World { u_m: [Option<f64>; 3] },
    /// Prescribed components $[u_t, u_n, u_b]$ in m in the frame whose orthonormal rows are
    /// $t, n, b$: $u_c = F_c \cdot u$.
    Local { frame: [[f64; 3]; 3], u_m: [Option<f64>; 3] },
}

/// Conditions at a material point: the point at reference position `x_m`, displacement
/// $u(x) = \sum_i N_i(x) u_i$; its frame components `u_m` ($[u_t, u_n, u_b]$, `None` = free) are
/// prescribed, and the world force `force_n` is applied at it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointCondition {
    pub x_m: [f64; 3],
    pub frame: [[f64; 3]; 3],
    pub u_m: [Option<f64>; 3],
    pub force_n: [f64; 3],
}

/// A static problem on a tetrahedral mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TetStaticProblem {
    /// Conditions by node; a node takes one kind (world entries for one node merge).
    pub conditions: Vec<(usize, TetNodeCondition)>,
    /// Nodal forces `(node, [fx, fy, fz])` in N; repeated entries add.
    pub loads_n: Vec<(usize, [f64; 3])>,
    /// Material-point conditions.
    pub points: Vec<PointCondition>,
}

/// Errors of a 3D static problem, each naming the offending node, point or condition.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TetStaticError {
    /// A condition or load names a node that does not exist.
    #[error("{what} names node {node_idx}, but the mesh has only {n_nodes} nodes")]
    UnknownNode { what: &'static str, node_idx: usize, n_nodes: usize },
    /// A prescribed value, load, frame or position is NaN or infinite.
    #[error("{what} is not finite")]
    NonFinite { what: String },
    /// A node has more than one kind of condition (fixed, world, local frame), or two local frames.
    #[error("node {node_idx} has more than one kind of condition (fixed, prescribed, prescribed_local); a node takes at most one")]
    Conflict { node_idx: usize },
    /// A frame is not three orthonormal rows (within [`FRAME_TOL`]).
    #[error("{what}: the frame must be three orthonormal rows [t, n, b] (max |F Fᵀ − I| = {deviation:e})")]
    Frame { what: String, deviation: f64 },
    /// A material point lies outside the mesh.
    #[error("point {point_idx}: {source}")]
    PointOutside { point_idx: usize, source: LocateError },
    /// A constraint row is a combination of the rows before it (see the module docs).
    #[error(
        "the condition {what} depends on the conditions before it ({detail}): the constraints must be independent — no more than two points of one straight needle in one tetrahedron, and no point whose tetrahedron is entirely fixed"
    )]
    DependentConstraint { what: String, detail: String, points: Vec<usize> },
    /// The factorisation failed (for example: rigid-body motion).
    #[error(transparent)]
    Factor(#[from] FactorError),
}

/// The result at one material point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointReaction {
    /// The force the point's constraint exerts on the tissue, world components, N.
    pub force_n: [f64; 3],
    /// Its frame components $[r_t, r_n, r_b]$, `None` where free.
    pub local_n: [Option<f64>; 3],
    /// The displacement $u(x)$ at the point, m.
    pub u_m: [f64; 3],
    /// Where the point lies.
    pub location: PointLocation,
}

/// The solution of a 3D static problem.
#[derive(Debug, Clone, PartialEq)]
pub struct TetStaticSolution {
    /// World displacements `[ux0, uy0, uz0, …]` in m.
    pub displacement_m: Vec<f64>,
    /// For every node with a world-prescribed component: `(node, [rx, ry, rz])`, `None` where
    /// free; for a local-frame node the world force of its constraint (all three given). Sorted by node.
    pub reactions_n: Vec<(usize, [Option<f64>; 3])>,
    /// For local-frame nodes, in the order given: `(node, [rt, rn, rb])`, `None` for a free component.
    pub reactions_local_n: Vec<(usize, [Option<f64>; 3])>,
    /// One per material point, in the order given.
    pub point_reactions: Vec<PointReaction>,
    /// $\tfrac12 u^\top K u$ in J.
    pub strain_energy_j: f64,
}

/// Where a constraint row comes from.
#[derive(Debug, Clone, Copy)]
enum Owner {
    Node(usize),
    Point(usize),
}

/// One constraint row: $\sum$ coef·u[dof] = value.
struct Row {
    owner: Owner,
    comp: usize,
    entries: Vec<(usize, f64)>,
    value: f64,
}

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

fn check_finite(what: impl Fn() -> String, values: &[Option<f64>]) -> Result<(), TetStaticError> {
    if values.iter().flatten().any(|v| !v.is_finite()) {
        return Err(TetStaticError::NonFinite { what: what() });
    }
    Ok(())
}

impl TetStaticProblem {
    /// Solves the problem with a fresh factorisation (see the module docs). Errors: unknown or
    /// doubly conditioned nodes, non-finite values, frames that are not orthonormal, points
    /// outside the mesh, dependent constraints, and a singular stiffness (rigid-body motion).
    pub fn solve(&self, mesh: &TetMesh, materials: &TetMaterials) -> Result<TetStaticSolution, TetStaticError> {
        let locator = TetLocator::new(mesh);
        self.solve_with_locator(mesh, materials, &locator)
    }

    /// As [`TetStaticProblem::solve`], with a prebuilt point locator of `mesh`.
    pub fn solve_with_locator(
        &self,
        mesh: &TetMesh,
        materials: &TetMaterials,
        locator: &TetLocator,
    ) -> Result<TetStaticSolution, TetStaticError> {
        let n_nodes = mesh.n_nodes();
        let n_dofs = 3 * n_nodes;
        let check_node = |what, node_idx| {
            if node_idx >= n_nodes { Err(TetStaticError::UnknownNode { what, node_idx, n_nodes }) } else { Ok(()) }
        };
        // Kinds: 1 fixed, 2 world, 4 local.
        let mut kind = vec![0u8; n_nodes];
        let mut constrained = vec![false; n_dofs];
        let mut value = vec![0.0; n_dofs];
        let mut rows: Vec<Row> = Vec::new();
        let mut local_nodes: Vec<(usize, [[f64; 3]; 3], [bool; 3])> = Vec::new();
        for &(node, c) in &self.conditions {
            check_node("a condition", node)?;
            let bit = match c {
                TetNodeCondition::Fixed => 1,
                TetNodeCondition::World { .. } => 2,
                TetNodeCondition::Local { .. } => 4,
            };
            if kind[node] & !bit != 0 || (bit == 4 && kind[node] != 0) {
                return Err(TetStaticError::Conflict { node_idx: node });
            }
            kind[node] |= bit;
            match c {
                TetNodeCondition::Fixed => {
                    for a in 0..3 {
                        constrained[3 * node + a] = true;
                        value[3 * node + a] = 0.0;
                    }
                }
                TetNodeCondition::World { u_m } => {
                    check_finite(|| format!("a prescribed displacement of node {node}"), &u_m)?;
                    for a in 0..3 {
                        if let Some(v) = u_m[a] {
                            constrained[3 * node + a] = true;
                            value[3 * node + a] = v;
                        }
                    }
                }
                TetNodeCondition::Local { frame, u_m } => {
                    check_frame(&frame, &format!("prescribed_local node {node}"))?;
                    check_finite(|| format!("a prescribed_local displacement of node {node}"), &u_m)?;
                    for comp in 0..3 {
                        if let Some(v) = u_m[comp] {
                            let entries = (0..3).map(|a| (3 * node + a, frame[comp][a])).collect();
                            rows.push(Row { owner: Owner::Node(node), comp, entries, value: v });
                        }
                    }
                    local_nodes.push((node, frame, u_m.map(|v| v.is_some())));
                }
            }
        }
        let mut f = vec![0.0; n_dofs];
        for &(node, force) in &self.loads_n {
            check_node("a load", node)?;
            check_finite(|| format!("a load on node {node}"), &force.map(Some))?;
            for a in 0..3 {
                f[3 * node + a] += force[a];
            }
        }
        let mut locations = Vec::with_capacity(self.points.len());
        for (i, p) in self.points.iter().enumerate() {
            check_frame(&p.frame, &format!("point {i}"))?;
            check_finite(|| format!("a prescribed displacement of point {i}"), &p.u_m)?;
            check_finite(|| format!("the force of point {i}"), &p.force_n.map(Some))?;
            let loc = locator.locate(mesh, p.x_m).map_err(|source| TetStaticError::PointOutside { point_idx: i, source })?;
            for (k, &node) in loc.nodes.iter().enumerate() {
                for a in 0..3 {
                    f[3 * node + a] += loc.weights[k] * p.force_n[a];
                }
            }
            for comp in 0..3 {
                if let Some(v) = p.u_m[comp] {
                    let mut entries = Vec::with_capacity(12);
                    for (k, &node) in loc.nodes.iter().enumerate() {
                        for a in 0..3 {
                            entries.push((3 * node + a, loc.weights[k] * p.frame[comp][a]));
                        }
                    }
                    rows.push(Row { owner: Owner::Point(i), comp, entries, value: v });
                }
            }
            locations.push(loc);
        }

        let k = assemble_stiffness(mesh, materials);
        // u holds u_D at the prescribed DOFs and zero elsewhere; rhs = f_I - K_ID u_D.
        let mut u: Vec<f64> = (0..n_dofs).map(|d| if constrained[d] { value[d] } else { 0.0 }).collect();
        let mut ku = vec![0.0; n_dofs];
        mul_stiffness(&k, &u, &mut ku);
        let dofs = DofMap::with_dofs_per_node(&constrained, 3);
        let q = rows.len();
        let mut lambda = vec![0.0; q];
        if dofs.n_free() > 0 {
            let chol = SparseCholesky::new(&k, dofs)?;
            let dofs = chol.dofs();
            let n_free = dofs.n_free();
            // Column 0: u0; columns 1..=q: Y = K_II^-1 G_I^T.
            let mut x = Mat::<f64>::zeros(n_free, q + 1);
            for (i, &d) in dofs.free_dofs().iter().enumerate() {
                x[(i, 0)] = f[d] - ku[d];
            }
            for (r, row) in rows.iter().enumerate() {
                for &(d, c) in &row.entries {
                    if let Some(i) = dofs.free_index(d) {
                        x[(i, r + 1)] += c;
                    }
                }
            }
            let mut scratch = chol.scratch(q + 1);
            chol.solve_in_place(x.as_mut(), &mut scratch);
            if q > 0 {
                // S = G_I Y, h = G_I u0 + G_D u_D - g.
                let mut s = vec![0.0; q * q];
                let mut h = vec![0.0; q];
                for (r, row) in rows.iter().enumerate() {
                    h[r] = -row.value;
                    for &(d, c) in &row.entries {
                        match dofs.free_index(d) {
                            Some(i) => {
                                h[r] += c * x[(i, 0)];
                                for l in 0..q {
                                    s[r * q + l] += c * x[(i, l + 1)];
                                }
                            }
                            None => h[r] += c * u[d],
                        }
                    }
                }
                for r in 0..q {
                    for l in 0..r {
                        let m = 0.5 * (s[r * q + l] + s[l * q + r]);
                        s[r * q + l] = m;
                        s[l * q + r] = m;
                    }
                }
                // A row with (relatively) no weight on free DOFs cannot be satisfied by moving them.
                for (r, row) in rows.iter().enumerate() {
                    let total: f64 = row.entries.iter().map(|e| e.1 * e.1).sum();
                    let free: f64 = row.entries.iter().filter(|e| dofs.free_index(e.0).is_some()).map(|e| e.1 * e.1).sum();
                    if !(free > FIXED_ROW_WEIGHT * FIXED_ROW_WEIGHT * total) {
                        return Err(dependent(&rows, r, &locations, true));
                    }
                }
                lambda = solve_schur(&mut s, h, q).map_err(|r| dependent(&rows, r, &locations, false))?;
            }
            for (i, &d) in dofs.free_dofs().iter().enumerate() {
                u[d] = x[(i, 0)] - (0..q).map(|l| x[(i, l + 1)] * lambda[l]).sum::<f64>();
            }
        } else if q > 0 {
            return Err(dependent(&rows, 0, &locations, true));
        }
        let mu: Vec<f64> = lambda.iter().map(|l| -l).collect();

        // r = K u - f - G^T mu.
        mul_stiffness(&k, &u, &mut ku);
        let strain_energy_j = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
        let mut r: Vec<f64> = ku.iter().zip(&f).map(|(a, b)| a - b).collect();
        for (row, m) in rows.iter().zip(&mu) {
            for &(d, c) in &row.entries {
                r[d] -= c * m;
            }
        }
        // Frame components of the constraint forces, per owner.
        let mut node_mu: Vec<(usize, [Option<f64>; 3])> = Vec::new();
        let mut point_mu: Vec<[Option<f64>; 3]> = vec![[None; 3]; self.points.len()];
        for (row, &m) in rows.iter().zip(&mu) {
            match row.owner {
                Owner::Node(n) => match node_mu.last_mut() {
                    Some((last, comps)) if *last == n => comps[row.comp] = Some(m),
                    _ => {
                        let mut comps = [None; 3];
                        comps[row.comp] = Some(m);
                        node_mu.push((n, comps));
                    }
                },
                Owner::Point(i) => point_mu[i][row.comp] = Some(m),
            }
        }
        let world_of = |frame: &[[f64; 3]; 3], comps: &[Option<f64>; 3]| -> [f64; 3] {
            std::array::from_fn(|a| (0..3).map(|c| comps[c].unwrap_or(0.0) * frame[c][a]).sum())
        };
        let mut reactions_n = Vec::new();
        let mut reactions_local_n = Vec::new();
        let mut local_of_node = std::collections::BTreeMap::new();
        for &(node, frame, given) in &local_nodes {
            let comps = node_mu.iter().find(|e| e.0 == node).map_or([None; 3], |e| e.1);
            let comps: [Option<f64>; 3] = std::array::from_fn(|c| if given[c] { comps[c] } else { None });
            reactions_local_n.push((node, comps));
            local_of_node.insert(node, world_of(&frame, &comps).map(Some));
        }
        for node in 0..n_nodes {
            if let Some(w) = local_of_node.get(&node) {
                reactions_n.push((node, *w));
            } else if (0..3).any(|a| constrained[3 * node + a]) {
                reactions_n.push((node, std::array::from_fn(|a| constrained[3 * node + a].then_some(r[3 * node + a]))));
            }
        }
        let point_reactions = self
            .points
            .iter()
            .zip(&locations)
            .zip(&point_mu)
            .map(|((p, loc), comps)| {
                let u_m = std::array::from_fn(|a| (0..4).map(|k| loc.weights[k] * u[3 * loc.nodes[k] + a]).sum());
                PointReaction { force_n: world_of(&p.frame, comps), local_n: *comps, u_m, location: *loc }
            })
            .collect();
        Ok(TetStaticSolution { displacement_m: u, reactions_n, reactions_local_n, point_reactions, strain_energy_j })
    }
}

/// Solves $S\lambda = h$ by Cholesky in row order; `Err(r)` names the first row whose pivot is
/// at most [`DEPENDENT_PIVOT`] of its diagonal. `s` is overwritten by the factor.
fn solve_schur(s: &mut [f64], mut h: Vec<f64>, q: usize) -> Result<Vec<f64>, usize> {
    for j in 0..q {
        let diag = s[j * q + j];
        let mut pivot = diag;
        for k in 0..j {
            pivot -= s[j * q + k] * s[j * q + k];
        }
        if !(pivot > DEPENDENT_PIVOT * diag) || !(diag > 0.0) {
            return Err(j);
        }
        let l = pivot.sqrt();
        s[j * q + j] = l;
        for i in j + 1..q {
            let mut v = s[i * q + j];
            for k in 0..j {
                v -= s[i * q + k] * s[j * q + k];
            }
            s[i * q + j] = v / l;
        }
    }
    // L y = h, then L^T x = y.
    for i in 0..q {
        for k in 0..i {
            h[i] -= s[i * q + k] * h[k];
        }
        h[i] /= s[i * q + i];
    }
    for i in (0..q).rev() {
        for k in i + 1..q {
            h[i] -= s[k * q + i] * h[k];
        }
        h[i] /= s[i * q + i];
    }
    Ok(h)
}

fn dependent(rows: &[Row], r: usize, locations: &[PointLocation], no_free_dof: bool) -> TetStaticError {
    let row = &rows[r];
    let comp = FRAME_COMPONENTS[row.comp];
    let fixed = "every DOF it involves is prescribed";
    match row.owner {
        Owner::Node(n) => TetStaticError::DependentConstraint {
            what: format!("u{comp} of prescribed_local node {n}"),
            detail: fixed.to_owned(),
            points: Vec::new(),
        },
        Owner::Point(i) => {
            let tet = locations[i].tet_idx;
            let points: Vec<usize> = (0..locations.len()).filter(|&p| locations[p].tet_idx == tet).collect();
            let detail = if no_free_dof {
                format!("{fixed}: the nodes {:?} of its tetrahedron {tet} that carry it are all fixed", locations[i].nodes)
            } else {
                format!("points {points:?} lie in tetrahedron {tet}")
            };
            TetStaticError::DependentConstraint { what: format!("u{comp} of point {i}"), detail, points }
        }
    }
}

impl TetStaticSolution {
    /// Element stresses for this solution, Voigt order, Pa.
    pub fn element_stresses_pa(&self, mesh: &TetMesh, materials: &TetMaterials) -> Vec<[f64; 6]> {
        element_stresses_pa(mesh, materials, &self.displacement_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
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
        let mut world = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: loads.clone(), points: vec![] };
        world.conditions.push((node, TetNodeCondition::World { u_m: target.map(Some) }));
        let mut held = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: loads.clone(), points: vec![] };
        held.conditions.push((node, TetNodeCondition::Local { frame, u_m: local }));
        let point = TetStaticProblem {
            conditions: bottom_fixed(&mesh),
            loads_n: loads,
            points: vec![PointCondition { x_m: mesh.nodes_m()[node], frame, u_m: local, force_n: [0.0; 3] }],
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
        let two = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: vec![], points: pts[..2].to_vec() };
        assert!(two.solve(&mesh, &mats).is_ok());
        let three = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: vec![], points: pts };
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
        };
        let e = on_floor.solve(&mesh, &mats).unwrap_err();
        assert!(matches!(e, TetStaticError::DependentConstraint { .. }), "{e}");
        assert!(e.to_string().contains("the condition ut of point 0 depends") && e.to_string().contains("are all fixed"), "{e}");
    }

    #[test]
    fn bad_input_is_named() {
        let (mesh, mats) = setup(3);
        let frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let p = |c: Vec<(usize, TetNodeCondition)>| TetStaticProblem { conditions: c, loads_n: vec![], points: vec![] };
        let e = TetStaticProblem { conditions: bottom_fixed(&mesh), loads_n: vec![(27, [1.0, 0.0, 0.0])], points: vec![] }
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
        }
        .solve(&mesh, &mats)
        .unwrap_err();
        assert!(e.to_string().starts_with("point 0: the point (0.2, 0, 0) m lies outside the mesh"), "{e}");
        let e = p(vec![]).solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("rigid body"), "{e}");
    }
}
