//! Static solves of a full problem, written once for both dimensions ([`Dim2`], [`Dim3`]): fixed
//! nodes, prescribed world components, components prescribed in a node's frame, conditions at
//! material points, nodal and point loads; results with reactions (world and frame), point
//! reactions, strain energy and stresses.
//!
//! **Node conditions are eliminated.** A node with a frame $F$ (rows $t, n$ and in 3D $b$; in 2D
//! the rotation by an angle $a$, $t = (\cos a, \sin a)$, $n = (-\sin a, \cos a)$) takes the DOFs
//! $u_{loc} = F u$. With $u = T u_{loc}$ ($T = F^\top$ on that node's block, the identity
//! elsewhere) the system is $T^\top K T\, u_{loc} = T^\top f$, assembled element by element
//! ([`rotate_element_node`]). The prescribed DOFs $D$ (fixed nodes, `World` components, `Local`
//! components in their frame) are eliminated: $K_{II} u_I = f_I - K_{ID} u_D$.
//!
//! **Material points are constraint rows.** A point at $x$ in element $(k_1, \dots, k_{N+1})$ with
//! weights $N_i(x)$ prescribes $F_c \cdot \sum_i N_i(x)\, u_{k_i} = g$ for its listed components
//! $c$; together $G u = g$ ($q$ rows, written in the node frames where a node has one). A point
//! force $f_p$ at $x$ adds $N_i(x) f_p$ to each of its element's nodes. $K_{II}$ is factorised once
//! (sparse Cholesky) and the constraints are condensed onto a dense $q \times q$ Schur complement:
//! $$u^0_I = K_{II}^{-1}(f_I - K_{ID} u_D),\quad Y = K_{II}^{-1} G_I^\top,\quad S = G_I Y,$$
//! $$S\,\lambda = G_I u^0_I + G_D u_D - g,\qquad u_I = u^0_I - Y\lambda .$$
//! This is the KKT system $K u + G^\top\lambda = f$, $G u = g$; the force the constraints exert on
//! the tissue is $\mu = -\lambda$. The cost is one factorisation, $q + 1$ solves and an $O(q^3)$
//! dense factorisation, so it scales to meshes of $10^5$ nodes with tens of points.
//!
//! **Independence.** $S$ is factorised row by row (Cholesky, in the order the points are given,
//! components $t, n, b$). A row whose pivot falls to $\le 10^{-10}$ of its diagonal
//! ([`DEPENDENT_PIVOT`]) is (numerically) a combination of the rows before it — e.g. a third
//! point of one straight needle in one linear tetrahedron, or a point whose element nodes are
//! all fixed — and the solve stops with [`StaticError::DependentConstraint`] naming it and the
//! points sharing its element, instead of returning a meaningless answer.
//!
//! **Patches are constraint rows too.** A contact spread over the tissue (the needle's
//! cross-section: [`crate::d3::disc`]) conditions a weighted node sum $u_p = \sum_k w_k u_k$
//! instead of one element's interpolation: its rows are $F_c \cdot \sum_k w_k u_k = g$ and its
//! force $f_p$ adds $w_k f_p$ to node $k$. Points come first, then patches, in every ordering
//! (rows, pivots, reactions), as in the reference (../shared/validation, `patches`).
//!
//! **Outputs.** The residual $r = K u - f - G^\top\mu$ (in the node frames) gives the reactions at
//! the prescribed DOFs: in world components ($F^\top r_{loc}$, every component, at a frame node)
//! and, at frame nodes, in the frame. A point's reaction is the world force $\sum_c \mu_c F_c$ of
//! its constraint, its frame components $\mu_c$ and the displacement $u(x)$. Strain energy
//! $\tfrac12 u^\top K u$.
//!
//! **Per dimension** (methods of [`Dim`]): the frame's representation (2D an angle, which the
//! results give back as given; 3D rows, checked orthonormal), point location (3D
//! [`crate::d3::TetLocator`]; the 2D core has none for statics, see [`tri`]), and the wording
//! of the errors that differ. [`StaticProblem`] without a dimension is the 2D one;
//! [`crate::d3::TetStaticProblem`] and its companions are the 3D aliases.

use faer::Mat;

use crate::assembly::{ElementMaterials, assemble_stiffness_with, element_stresses_pa, mul_stiffness, rotate_element_node};
use crate::dim::{ConditionLabel, Dim, Dim2};
use crate::factor::{DofMap, FactorError, SparseCholesky};
use crate::mesh::SimplexMesh;

pub mod tri;

/// A constraint row whose Cholesky pivot in the Schur complement is at most this fraction of its
/// diagonal depends on the rows before it.
pub const DEPENDENT_PIVOT: f64 = 1e-10;

/// A constraint row whose weights on free DOFs are at most this fraction of its weights (2-norm)
/// involves no free DOF: its point lies on an entirely fixed face, edge or node (to the
/// round-off of the barycentric weights).
pub const FIXED_ROW_WEIGHT: f64 = 1e-10;

/// Frame components, in the order of a frame's rows: along the needle, and across it.
pub const FRAME_COMPONENTS: [&str; 3] = ["t", "n", "b"];

/// A condition on one node. Components set to `None` are free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeCondition<D: Dim = Dim2> {
    /// Every component zero.
    Fixed,
    /// Prescribed world components ($[u_x, u_y(, u_z)]$) in m.
    World { u_m: D::Components },
    /// Prescribed components $[u_t, u_n(, u_b)]$ in m in the node's frame: $u_c = F_c \cdot u$.
    Local { frame: D::Frame, u_m: D::Components },
}

/// Conditions at a material point: the point at reference position `x_m`, displacement
/// $u(x) = \sum_i N_i(x) u_i$; its frame components `u_m` (`None` = free) are prescribed, and the
/// world force `force_n` is applied at it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointCondition<D: Dim = Dim2> {
    pub x_m: D::Point,
    pub frame: D::Frame,
    pub u_m: D::Components,
    pub force_n: D::Point,
}

/// Conditions on a patch: the weighted node sum $u_p = \sum_k w_k u_k$ (`nodes` and `weights`
/// of one length, e.g. the shape functions averaged over the needle's cross-section); its frame
/// components `u_m` (`None` = free) are prescribed and the world force `force_n` acts as the
/// nodal loads $w_k f$.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchCondition<D: Dim = Dim2> {
    pub nodes: Vec<usize>,
    pub weights: Vec<f64>,
    pub frame: D::Frame,
    pub u_m: D::Components,
    pub force_n: D::Point,
}

/// A static problem on a mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StaticProblem<D: Dim = Dim2> {
    /// Conditions by node; a node takes one kind (world entries for one node merge).
    pub conditions: Vec<(usize, NodeCondition<D>)>,
    /// Nodal forces `(node, [fx, fy(, fz)])` in N, world components; repeated entries add.
    pub loads_n: Vec<(usize, D::Point)>,
    /// Material-point conditions (3D; a 2D problem takes none, see [`tri`]).
    pub points: Vec<PointCondition<D>>,
    /// Patch conditions (both dimensions), after the points.
    pub patches: Vec<PatchCondition<D>>,
}

/// Errors of a static problem, each naming the offending node, point or condition.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError<D: Dim = Dim2> {
    /// A condition or load names a node that does not exist.
    #[error("{what} names node {node_idx}, but the mesh has only {n_nodes} nodes")]
    UnknownNode { what: &'static str, node_idx: usize, n_nodes: usize },
    /// A prescribed value, load, angle, frame or position is NaN or infinite.
    #[error("{what} is not finite")]
    NonFinite { what: String },
    /// A node has more than one kind of condition (fixed, world, local frame), or two frames.
    #[error("node {node_idx} has more than one kind of condition (fixed, prescribed, prescribed_local); a node takes at most one")]
    Conflict { node_idx: usize },
    /// A 3D frame is not three orthonormal rows (within [`crate::d3::statics::FRAME_TOL`]).
    #[error("{what}: the frame must be three orthonormal rows [t, n, b] (max |F Fᵀ − I| = {deviation:e})")]
    Frame { what: String, deviation: f64 },
    /// A patch's nodes and weights do not make a weighted sum (empty, of two lengths, a node
    /// twice, a weight not finite, or weights summing to zero).
    #[error("patch {patch_idx}: {reason}")]
    Patch { patch_idx: usize, reason: String },
    /// A material point was not located (outside the mesh; in 2D, any point).
    #[error("point {point_idx}: {source}")]
    PointOutside { point_idx: usize, source: D::LocateError },
    /// A constraint row is a combination of the rows before it (see the module docs; points are
    /// 3D only, hence the message's tetrahedra).
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
pub struct PointReaction<D: Dim = Dim2> {
    /// The force the point's constraint exerts on the tissue, world components, N.
    pub force_n: D::Point,
    /// Its frame components $[r_t, r_n(, r_b)]$, `None` where free.
    pub local_n: D::Components,
    /// The displacement $u(x)$ at the point, m.
    pub u_m: D::Point,
    /// Where the point lies.
    pub location: D::PointLocation,
}

/// The result at one patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchReaction<D: Dim = Dim2> {
    /// The force the patch's constraint exerts on the tissue, world components, N.
    pub force_n: D::Point,
    /// Its frame components, `None` where free.
    pub local_n: D::Components,
    /// The weighted node sum $\sum_k w_k u_k$, m.
    pub u_m: D::Point,
}

/// The solution of a static problem.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution<D: Dim = Dim2> {
    /// World displacements, interleaved `[ux0, uy0, (uz0,) …]`, in m.
    pub displacement_m: Vec<f64>,
    /// For every node with a prescribed component: `(node, [rx, ry(, rz)])` in world components;
    /// a free component is `None`, except at frame nodes where every world component is given.
    /// Sorted by node.
    pub reactions_n: Vec<(usize, D::Components)>,
    /// For frame nodes with a prescribed component, sorted by node: `(node, frame, [rt, rn(, rb)])`,
    /// `None` for a free component.
    pub reactions_local_n: Vec<(usize, D::Frame, D::Components)>,
    /// One per material point, in the order given.
    pub point_reactions: Vec<PointReaction<D>>,
    /// One per patch, in the order given.
    pub patch_reactions: Vec<PatchReaction<D>>,
    /// $\tfrac12 u^\top K u$ in J.
    pub strain_energy_j: f64,
}

/// One constraint row of point `point`: $\sum$ coef·u[dof] = value.
struct Row {
    /// The point's index, or the number of points plus the patch's.
    point: usize,
    comp: usize,
    entries: Vec<(usize, f64)>,
    value: f64,
}

fn check_finite<D: Dim>(what: impl Fn() -> String, values: &[Option<f64>]) -> Result<(), StaticError<D>> {
    if values.iter().flatten().any(|v| !v.is_finite()) {
        return Err(StaticError::NonFinite { what: what() });
    }
    Ok(())
}

/// $F v$: world components to the frame's, summed in the order of the frame's columns.
fn to_frame<D: Dim>(f: &D::FrameRows, v: &[f64]) -> [f64; 3] {
    std::array::from_fn(|c| {
        if c >= D::N {
            return 0.0;
        }
        let mut s = f[c][0] * v[0];
        for a in 1..D::N {
            s += f[c][a] * v[a];
        }
        s
    })
}

/// $F^\top v$: the frame's components to world components.
fn to_world<D: Dim>(f: &D::FrameRows, v: &[f64]) -> [f64; 3] {
    std::array::from_fn(|a| {
        if a >= D::N {
            return 0.0;
        }
        let mut s = f[0][a] * v[0];
        for c in 1..D::N {
            s += f[c][a] * v[c];
        }
        s
    })
}

impl<D: Dim> StaticProblem<D> {
    /// Solves the problem with a fresh factorisation (see the module docs). Errors: unknown or
    /// doubly conditioned nodes, non-finite values, frames that are not orthonormal, points
    /// outside the mesh, dependent constraints, and a singular stiffness (rigid-body motion).
    pub fn solve(&self, mesh: &SimplexMesh<D>, materials: &ElementMaterials<D>) -> Result<StaticSolution<D>, StaticError<D>> {
        let locator = D::locator(mesh);
        self.solve_with_locator(mesh, materials, &locator)
    }

    /// As [`StaticProblem::solve`], with a prebuilt point locator of `mesh`.
    pub fn solve_with_locator(
        &self,
        mesh: &SimplexMesh<D>,
        materials: &ElementMaterials<D>,
        locator: &D::Locator,
    ) -> Result<StaticSolution<D>, StaticError<D>> {
        let n = D::N;
        let n_nodes = mesh.n_nodes();
        let n_dofs = n * n_nodes;
        let check_node = |what, node_idx| {
            if node_idx >= n_nodes { Err(StaticError::UnknownNode { what, node_idx, n_nodes }) } else { Ok(()) }
        };
        // Kinds: 1 fixed, 2 world, 4 local.
        let mut kind = vec![0u8; n_nodes];
        let mut constrained = vec![false; n_dofs];
        let mut value = vec![0.0; n_dofs];
        let mut frame_of: Vec<Option<D::Frame>> = vec![None; n_nodes];
        for &(node, c) in &self.conditions {
            let (bit, what) = match c {
                NodeCondition::Fixed => (1, "a condition"),
                NodeCondition::World { .. } => (2, "a condition"),
                NodeCondition::Local { .. } => (4, D::LOCAL_CONDITION),
            };
            check_node(what, node)?;
            if kind[node] & !bit != 0 || (bit == 4 && kind[node] != 0) {
                return Err(StaticError::Conflict { node_idx: node });
            }
            kind[node] |= bit;
            let u_m = match c {
                NodeCondition::Fixed => D::components_from_fn(|_| Some(0.0)),
                NodeCondition::World { u_m } => {
                    check_finite(|| D::condition_label(ConditionLabel::World, node), u_m.as_ref())?;
                    u_m
                }
                NodeCondition::Local { frame, u_m } => {
                    D::check_frame(&frame, &D::condition_label(ConditionLabel::LocalFrame, node))?;
                    check_finite(|| D::condition_label(ConditionLabel::LocalValue, node), u_m.as_ref())?;
                    frame_of[node] = Some(frame);
                    u_m
                }
            };
            for a in 0..n {
                if let Some(v) = u_m[a] {
                    constrained[n * node + a] = true;
                    value[n * node + a] = v;
                }
            }
        }
        let mut f = vec![0.0; n_dofs];
        for &(node, force) in &self.loads_n {
            check_node("a load", node)?;
            if force.as_ref().iter().any(|v| !v.is_finite()) {
                return Err(StaticError::NonFinite { what: format!("a load on node {node}") });
            }
            for a in 0..n {
                f[n * node + a] += force[a];
            }
        }
        let mut rows: Vec<Row> = Vec::new();
        let mut locations = Vec::with_capacity(self.points.len());
        for (i, p) in self.points.iter().enumerate() {
            D::check_frame(&p.frame, &format!("point {i}"))?;
            check_finite(|| format!("a prescribed displacement of point {i}"), p.u_m.as_ref())?;
            if p.force_n.as_ref().iter().any(|v| !v.is_finite()) {
                return Err(StaticError::NonFinite { what: format!("the force of point {i}") });
            }
            let loc = D::locate(locator, mesh, p.x_m).map_err(|source| StaticError::PointOutside { point_idx: i, source })?;
            let (_, nodes, weights) = D::location_terms(&loc);
            add_support_rows::<D>(&mut rows, &mut f, i, nodes, weights, &p.frame, &p.u_m, &p.force_n);
            locations.push(loc);
        }
        for (j, p) in self.patches.iter().enumerate() {
            let bad = |reason: String| StaticError::Patch { patch_idx: j, reason };
            if p.nodes.is_empty() || p.nodes.len() != p.weights.len() {
                return Err(bad(format!(
                    "needs nodes and weights of one length, not empty (got {} and {})",
                    p.nodes.len(),
                    p.weights.len()
                )));
            }
            for (k, &node) in p.nodes.iter().enumerate() {
                if node >= n_nodes {
                    return Err(bad(format!("names node {node}, but the mesh has only {n_nodes} nodes")));
                }
                if p.nodes[..k].contains(&node) {
                    return Err(bad(format!("names node {node} twice")));
                }
            }
            if let Some(w) = p.weights.iter().find(|w| !w.is_finite()) {
                return Err(bad(format!("a weight is not finite ({w})")));
            }
            let total: f64 = p.weights.iter().sum();
            let scale: f64 = p.weights.iter().map(|w| w.abs()).sum();
            if !(total.abs() > 1e-12 * scale) {
                return Err(bad(format!("its weights sum to {total:e}, not a weighted mean")));
            }
            D::check_frame(&p.frame, &format!("patch {j}"))?;
            check_finite(|| format!("a prescribed displacement of patch {j}"), p.u_m.as_ref())?;
            if p.force_n.as_ref().iter().any(|v| !v.is_finite()) {
                return Err(StaticError::NonFinite { what: format!("the force of patch {j}") });
            }
            add_support_rows::<D>(&mut rows, &mut f, self.points.len() + j, &p.nodes, &p.weights, &p.frame, &p.u_m, &p.force_n);
        }

        // Frame nodes: K and f in their frames, and the points' rows on their DOFs.
        let rows_of: Vec<Option<D::FrameRows>> = frame_of.iter().map(|fr| fr.as_ref().map(D::frame_rows)).collect();
        let any_frame = rows_of.iter().any(Option::is_some);
        let k = assemble_stiffness_with(mesh, materials, |e, ke| {
            if any_frame {
                for (k, &node) in e.as_ref().iter().enumerate() {
                    if let Some(fr) = &rows_of[node] {
                        rotate_element_node::<D>(ke, k, fr);
                    }
                }
            }
        });
        for (node, fr) in rows_of.iter().enumerate() {
            if let Some(fr) = fr {
                let loc = to_frame::<D>(fr, &f[n * node..n * node + n]);
                f[n * node..n * node + n].copy_from_slice(&loc[..n]);
            }
        }
        if any_frame {
            for row in &mut rows {
                // Entries come in blocks of a node's N components.
                for block in row.entries.chunks_mut(n) {
                    if let Some(fr) = &rows_of[block[0].0 / n] {
                        let w: Vec<f64> = block.iter().map(|e| e.1).collect();
                        let loc = to_frame::<D>(fr, &w);
                        for (e, v) in block.iter_mut().zip(loc) {
                            e.1 = v;
                        }
                    }
                }
            }
        }

        // u holds u_D at the prescribed DOFs and zero elsewhere; rhs = f_I - K_ID u_D.
        let mut u: Vec<f64> = (0..n_dofs).map(|d| if constrained[d] { value[d] } else { 0.0 }).collect();
        let mut ku = vec![0.0; n_dofs];
        mul_stiffness(&k, &u, &mut ku);
        let dofs = DofMap::with_dofs_per_node(&constrained, n);
        let q = rows.len();
        let mut lambda = vec![0.0; q];
        // With every DOF prescribed the displacement is known and only reactions remain.
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
                        return Err(dependent(&rows, r, &locations, &self.patches, true));
                    }
                }
                lambda = solve_schur(&mut s, h, q).map_err(|r| dependent(&rows, r, &locations, &self.patches, false))?;
            }
            for (i, &d) in dofs.free_dofs().iter().enumerate() {
                u[d] = if q == 0 { x[(i, 0)] } else { x[(i, 0)] - (0..q).map(|l| x[(i, l + 1)] * lambda[l]).sum::<f64>() };
            }
        } else if q > 0 {
            return Err(dependent(&rows, 0, &locations, &self.patches, true));
        }
        let mu: Vec<f64> = lambda.iter().map(|l| -l).collect();

        // r = K u - f - G^T mu, in the node frames.
        mul_stiffness(&k, &u, &mut ku);
        let mut r: Vec<f64> = ku.iter().zip(&f).map(|(a, b)| a - b).collect();
        let strain_energy_j = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
        for (row, m) in rows.iter().zip(&mu) {
            for &(d, c) in &row.entries {
                r[d] -= c * m;
            }
        }
        let mut u_world = u;
        let mut r_world = r.clone();
        for (node, fr) in rows_of.iter().enumerate() {
            if let Some(fr) = fr {
                for v in [&mut u_world, &mut r_world] {
                    let w = to_world::<D>(fr, &v[n * node..n * node + n]);
                    v[n * node..n * node + n].copy_from_slice(&w[..n]);
                }
            }
        }
        let mut reactions_n = Vec::new();
        let mut reactions_local_n = Vec::new();
        for node in 0..n_nodes {
            let given = |a: usize| constrained[n * node + a];
            if !(0..n).any(given) {
                continue;
            }
            if let Some(frame) = frame_of[node] {
                reactions_n.push((node, D::components_from_fn(|a| Some(r_world[n * node + a]))));
                reactions_local_n.push((node, frame, D::components_from_fn(|c| given(c).then_some(r[n * node + c]))));
            } else {
                reactions_n.push((node, D::components_from_fn(|a| given(a).then_some(r_world[n * node + a]))));
            }
        }
        // Frame components of the points' constraint forces.
        let mut point_mu: Vec<D::Components> = vec![D::Components::default(); self.points.len() + self.patches.len()];
        for (row, &m) in rows.iter().zip(&mu) {
            point_mu[row.point][row.comp] = Some(m);
        }
        let world_force = |frame: &D::Frame, comps: &D::Components| {
            let frame = D::frame_rows(frame);
            D::point_from_fn(|a| (0..n).map(|c| comps[c].unwrap_or(0.0) * frame[c][a]).sum())
        };
        let weighted_u =
            |nodes: &[usize], weights: &[f64]| D::point_from_fn(|a| (0..nodes.len()).map(|k| weights[k] * u_world[n * nodes[k] + a]).sum());
        let patch_reactions = self
            .patches
            .iter()
            .zip(&point_mu[self.points.len()..])
            .map(|(p, comps)| PatchReaction {
                force_n: world_force(&p.frame, comps),
                local_n: *comps,
                u_m: weighted_u(&p.nodes, &p.weights),
            })
            .collect();
        let point_reactions = self
            .points
            .iter()
            .zip(&locations)
            .zip(&point_mu)
            .map(|((p, loc), comps)| {
                let (_, nodes, weights) = D::location_terms(loc);
                PointReaction { force_n: world_force(&p.frame, comps), local_n: *comps, u_m: weighted_u(nodes, weights), location: *loc }
            })
            .collect();
        Ok(StaticSolution { displacement_m: u_world, reactions_n, reactions_local_n, point_reactions, patch_reactions, strain_energy_j })
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

/// The rows of one point or patch (`support`: its index among points then patches) with nodes
/// and weights: one per prescribed frame component; its force shared among the nodes.
#[allow(clippy::too_many_arguments)]
fn add_support_rows<D: Dim>(
    rows: &mut Vec<Row>,
    f: &mut [f64],
    support: usize,
    nodes: &[usize],
    weights: &[f64],
    frame: &D::Frame,
    u_m: &D::Components,
    force_n: &D::Point,
) {
    let n = D::N;
    for (k, &node) in nodes.iter().enumerate() {
        for a in 0..n {
            f[n * node + a] += weights[k] * force_n[a];
        }
    }
    let frame = D::frame_rows(frame);
    for comp in 0..n {
        if let Some(v) = u_m[comp] {
            let mut entries = Vec::with_capacity(n * nodes.len());
            for (k, &node) in nodes.iter().enumerate() {
                for a in 0..n {
                    entries.push((n * node + a, weights[k] * frame[comp][a]));
                }
            }
            rows.push(Row { point: support, comp, entries, value: v });
        }
    }
}

/// The error for constraint row `r`, naming its point and the points sharing its element (or its
/// patch and the patches sharing a node with it).
fn dependent<D: Dim>(
    rows: &[Row],
    r: usize,
    locations: &[D::PointLocation],
    patches: &[PatchCondition<D>],
    no_free_dof: bool,
) -> StaticError<D> {
    let row = &rows[r];
    let comp = FRAME_COMPONENTS[row.comp];
    let i = row.point;
    if let Some(j) = i.checked_sub(locations.len()) {
        let nodes = &patches[j].nodes;
        let sharing: Vec<usize> = (0..patches.len()).filter(|&o| patches[o].nodes.iter().any(|v| nodes.contains(v))).collect();
        let detail = if no_free_dof {
            format!("every DOF of its nodes {nodes:?} is prescribed")
        } else {
            format!("patches {sharing:?} share its nodes")
        };
        return StaticError::DependentConstraint { what: format!("u{comp} of patch {j}"), detail, points: vec![] };
    }
    let (elem, nodes, _) = D::location_terms(&locations[i]);
    let points: Vec<usize> = (0..locations.len()).filter(|&p| D::location_terms(&locations[p]).0 == elem).collect();
    let detail = if no_free_dof {
        format!("every DOF it involves is prescribed: the nodes {nodes:?} of its {} {elem} that carry it are all fixed", D::ELEMENT)
    } else {
        format!("points {points:?} lie in {} {elem}", D::ELEMENT)
    };
    StaticError::DependentConstraint { what: format!("u{comp} of point {i}"), detail, points }
}

impl<D: Dim> StaticSolution<D> {
    /// Element stresses for this solution, in the dimension's Voigt order, Pa.
    pub fn element_stresses_pa(&self, mesh: &SimplexMesh<D>, materials: &ElementMaterials<D>) -> Vec<D::Voigt> {
        element_stresses_pa(mesh, materials, &self.displacement_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::MaterialMap;
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
            p.conditions.push((n, NodeCondition::World { u_m: [Some(0.0), (n == 0).then_some(0.0)] }));
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
        let mut world = StaticProblem { conditions: fixed.clone(), loads_n: vec![(20, [0.3, 0.1])], points: vec![], patches: vec![] };
        world.conditions.push((33, NodeCondition::World { u_m: [Some(target[0]), Some(target[1])] }));
        let a: f64 = 0.83;
        let (s, c) = a.sin_cos();
        let mut local = StaticProblem { conditions: fixed, loads_n: vec![(20, [0.3, 0.1])], points: vec![], patches: vec![] };
        local.conditions.push((
            33,
            NodeCondition::Local { frame: a, u_m: [Some(c * target[0] + s * target[1]), Some(-s * target[0] + c * target[1])] },
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
        let p = StaticProblem { conditions: fixed.clone(), loads_n: vec![(9, [1.0, 0.0])], points: vec![], patches: vec![] };
        let e = p.solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("a load names node 9"), "{e}");
        let p = StaticProblem { conditions: fixed.clone(), loads_n: vec![(4, [f64::NAN, 0.0])], points: vec![], patches: vec![] };
        assert!(p.solve(&mesh, &mats).unwrap_err().to_string().contains("a load on node 4 is not finite"));
        let mut c = fixed.clone();
        c.push((0, NodeCondition::Local { frame: 0.1, u_m: [None, Some(0.0)] }));
        let e = StaticProblem { conditions: c, loads_n: vec![], points: vec![], patches: vec![] }.solve(&mesh, &mats).unwrap_err();
        assert_eq!(e, StaticError::Conflict { node_idx: 0 });
        let e = StaticProblem { conditions: vec![], loads_n: vec![(4, [1.0, 0.0])], points: vec![], patches: vec![] }
            .solve(&mesh, &mats)
            .unwrap_err();
        assert!(e.to_string().contains("rigid body"), "{e}");
        let mut c = fixed.clone();
        c.push((1, NodeCondition::World { u_m: [Some(0.1), None] }));
        let e = StaticProblem { conditions: c, loads_n: vec![], points: vec![], patches: vec![] }.solve(&mesh, &mats).unwrap_err();
        assert!(e.to_string().contains("node 1 has more than one kind of condition"), "{e}");
    }

    /// A 2D problem takes no material points: a typed error, not a silent drop.
    #[test]
    fn a_one_node_patch_in_2d_is_that_nodes_frame_condition_and_bad_patches_are_named() {
        // A patch of weight 1 on one node prescribes that node's frame components: the same
        // answer (to round-off) as the node condition, which is eliminated instead.
        let mesh = RectMeshParams::new(6, 6, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 10.0, poisson_ratio: 0.3 }],
            PlaneModel::Strain { thickness_m: 1.0 },
        )
        .unwrap();
        let fixed: Vec<(usize, NodeCondition)> = (0..6).map(|i| (i, NodeCondition::Fixed)).collect();
        let (node, angle, u_m) = (27, 0.4, [Some(0.01), Some(-0.02)]);
        let mut by_node = fixed.clone();
        by_node.push((node, NodeCondition::Local { frame: angle, u_m }));
        let a = StaticProblem { conditions: by_node, loads_n: vec![(33, [0.1, 0.2])], points: vec![], patches: vec![] }
            .solve(&mesh, &mats)
            .unwrap();
        let patch = PatchCondition { nodes: vec![node], weights: vec![1.0], frame: angle, u_m, force_n: [0.0; 2] };
        let b = StaticProblem { conditions: fixed.clone(), loads_n: vec![(33, [0.1, 0.2])], points: vec![], patches: vec![patch.clone()] }
            .solve(&mesh, &mats)
            .unwrap();
        let scale = a.displacement_m.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = a.displacement_m.iter().zip(&b.displacement_m).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(diff < 1e-12 * scale, "patch vs node condition: {diff:e} of {scale:e}");
        let (_, _, local) = a.reactions_local_n.iter().find(|r| r.0 == node).copied().unwrap();
        let r = b.patch_reactions[0];
        for c in 0..2 {
            assert!(
                (local[c].unwrap() - r.local_n[c].unwrap()).abs() < 1e-10 * local[c].unwrap().abs().max(1e-12),
                "{local:?} vs {:?}",
                r.local_n
            );
        }
        assert!((r.u_m[0] - b.displacement_m[2 * node]).abs() < 1e-15);
        // Bad patches, each named.
        let bad = |p: PatchCondition| {
            StaticProblem { conditions: fixed.clone(), loads_n: vec![], points: vec![], patches: vec![patch.clone(), p] }
                .solve(&mesh, &mats)
                .unwrap_err()
        };
        for (p, words) in [
            (PatchCondition { nodes: vec![], weights: vec![], ..patch.clone() }, "not empty"),
            (PatchCondition { nodes: vec![3, 4], weights: vec![1.0], ..patch.clone() }, "of one length"),
            (PatchCondition { nodes: vec![3, 99], weights: vec![0.5, 0.5], ..patch.clone() }, "names node 99"),
            (PatchCondition { nodes: vec![8, 8], weights: vec![0.5, 0.5], ..patch.clone() }, "node 8 twice"),
            (PatchCondition { nodes: vec![8, 9], weights: vec![0.5, f64::NAN], ..patch.clone() }, "not finite"),
            (PatchCondition { nodes: vec![8, 9], weights: vec![0.5, -0.5], ..patch.clone() }, "sum to"),
        ] {
            let e = bad(p);
            assert!(matches!(e, StaticError::Patch { patch_idx: 1, .. }) && e.to_string().contains(words), "{e}");
        }
        // The same node condition twice, as two patches: the second depends on the first.
        let e = StaticProblem { conditions: fixed, loads_n: vec![], points: vec![], patches: vec![patch.clone(), patch] }
            .solve(&mesh, &mats)
            .unwrap_err();
        assert!(e.to_string().contains("of patch 1 depends on the conditions before it"), "{e}");
    }

    #[test]
    fn points_in_2d_are_an_error() {
        let mesh = RectMeshParams::new(3, 3, 1.0, 1.0).build(&MeshLimits::default()).unwrap();
        let mats = MaterialMap::per_region(
            &mesh,
            &[Material { young_modulus_pa: 10.0, poisson_ratio: 0.3 }],
            PlaneModel::Strain { thickness_m: 1.0 },
        )
        .unwrap();
        let point = PointCondition { x_m: [0.5, 0.5], frame: 0.0, u_m: [None, Some(0.0)], force_n: [0.0; 2] };
        let p = StaticProblem {
            conditions: vec![(0, NodeCondition::Fixed), (1, NodeCondition::Fixed)],
            loads_n: vec![],
            points: vec![point],
            patches: vec![],
        };
        let e = p.solve(&mesh, &mats).unwrap_err();
        assert!(matches!(e, StaticError::PointOutside { point_idx: 0, .. }), "{e}");
        assert!(e.to_string().starts_with("point 0: a 2D static problem takes conditions at nodes only"), "{e}");
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
        let conditions = (0..9).map(|n| (n, NodeCondition::World { u_m: [Some(0.01 * n as f64), Some(0.0)] })).collect();
        let s = StaticProblem { conditions, loads_n: vec![], points: vec![], patches: vec![] }.solve(&mesh, &mats).unwrap();
        assert_eq!(s.displacement_m[2 * 8], 0.08);
        let sum: f64 = s.reactions_n.iter().map(|r| r.1[0].unwrap()).sum();
        assert!(sum.abs() < 1e-12, "reactions balance: {sum}");
        assert!(s.strain_energy_j > 0.0);
    }
}
