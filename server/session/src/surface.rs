//! The boundary surface of a tetrahedral tissue ([`BoundarySurface`]: the faces that belong to
//! one tetrahedron only, oriented outwards, and the nodes they use) and its displacement at a
//! tick ([`SurfaceField3`]), computed off the real-time thread by the fan-out of a 3D session.
//!
//! The displacement of surface node $v$ is $u_v = \sum_i \sum_{a} N_{a}(X_i)\, C_{v,a}\, f_i$
//! over the tick's contact points $i$ (force $f_i$ of the needle on the tissue at reference
//! position $X_i$, in the tetrahedron with nodes $a$ and barycentric weights $N_a$), from the
//! compliance columns of the points' nodes restricted to the surface rows. The fan-out computes
//! at most [`NEW_COLUMNS_PER_FIELD`] new nodes' columns per field (a contact whose columns are
//! not ready yet is left out of that field) and keeps at most [`MAX_SURFACE_COLUMNS`] nodes.

use std::collections::HashMap;
use std::sync::Arc;

use needlesim_core::d3::{TetColumnScratch, TetMesh, TetTissueModel};

use crate::record::Record3;

/// New nodes whose columns one field computation may compute.
pub const NEW_COLUMNS_PER_FIELD: usize = 8;
/// Nodes whose surface columns the fan-out keeps (all are dropped when full).
pub const MAX_SURFACE_COLUMNS: usize = 1024;

/// The boundary surface of a tetrahedral mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BoundarySurface {
    /// The mesh nodes on the surface, ascending.
    pub nodes: Vec<u32>,
    /// Triangles as indices into [`BoundarySurface::nodes`], counter-clockwise seen from
    /// outside (the normal $(b - a) \times (c - a)$ points out of the tissue).
    pub triangles: Vec<[u32; 3]>,
}

impl BoundarySurface {
    /// The faces of `mesh` that belong to one tetrahedron only.
    pub fn of(mesh: &TetMesh) -> Self {
        let nodes_m = mesh.nodes_m();
        let mut count: HashMap<[usize; 3], (u32, [usize; 3])> = HashMap::new();
        for tet in mesh.tets() {
            // The four faces, each with the vertex opposite to it.
            for (face, opp) in [
                ([tet[1], tet[2], tet[3]], tet[0]),
                ([tet[0], tet[2], tet[3]], tet[1]),
                ([tet[0], tet[1], tet[3]], tet[2]),
                ([tet[0], tet[1], tet[2]], tet[3]),
            ] {
                let mut key = face;
                key.sort_unstable();
                // Orient the face away from the opposite vertex.
                let [a, b, c] = face;
                let n = cross(sub(nodes_m[b], nodes_m[a]), sub(nodes_m[c], nodes_m[a]));
                let oriented = if dot(n, sub(nodes_m[opp], nodes_m[a])) > 0.0 { [a, c, b] } else { [a, b, c] };
                count.entry(key).and_modify(|e| e.0 += 1).or_insert((1, oriented));
            }
        }
        let mut faces: Vec<[usize; 3]> = count.into_values().filter(|(n, _)| *n == 1).map(|(_, f)| f).collect();
        faces.sort_unstable();
        let mut nodes: Vec<u32> = faces.iter().flatten().map(|&v| v as u32).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let index: HashMap<u32, u32> = nodes.iter().enumerate().map(|(k, &v)| (v, k as u32)).collect();
        let triangles = faces.iter().map(|f| f.map(|v| index[&(v as u32)])).collect();
        Self { nodes, triangles }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The fan-out's computer of surface displacements (module docs).
pub(crate) struct SurfaceField3 {
    pub(crate) model: Arc<TetTissueModel>,
    pub(crate) surface: Arc<BoundarySurface>,
    scratch: Option<TetColumnScratch>,
    column: Vec<f64>,
    /// Per node: its three columns on the surface nodes, `[dir][3 k + comp]`.
    columns: HashMap<usize, Box<[f64]>>,
}

impl SurfaceField3 {
    pub(crate) fn new(model: Arc<TetTissueModel>, surface: Arc<BoundarySurface>) -> Self {
        Self { model, surface, scratch: None, column: Vec::new(), columns: HashMap::new() }
    }

    /// The displacement of every surface node (`3 k + comp`, m) at the tick of `rec`.
    pub(crate) fn field(&mut self, rec: &Record3) -> Vec<f64> {
        let n_surf = self.surface.nodes.len();
        let mut u = vec![0.0; 3 * n_surf];
        let mut new_columns = 0;
        for c in rec.contacts() {
            let Ok(loc) = self.model.locate(c.x_ref_m) else { continue };
            for (a, w) in loc.nodes.into_iter().zip(loc.weights) {
                if w == 0.0 || self.model.is_fixed(a) {
                    continue;
                }
                if !self.columns.contains_key(&a) {
                    if new_columns == NEW_COLUMNS_PER_FIELD {
                        continue;
                    }
                    new_columns += 1;
                    let Some(cols) = self.surface_columns(a) else { continue };
                    if self.columns.len() >= MAX_SURFACE_COLUMNS {
                        self.columns.clear();
                    }
                    self.columns.insert(a, cols);
                }
                let cols = &self.columns[&a];
                for dir in 0..3 {
                    let f = w * c.force_n[dir];
                    if f != 0.0 {
                        for (o, v) in u.iter_mut().zip(&cols[dir * 3 * n_surf..(dir + 1) * 3 * n_surf]) {
                            *o += v * f;
                        }
                    }
                }
            }
        }
        u
    }

    fn surface_columns(&mut self, node: usize) -> Option<Box<[f64]>> {
        let n_dofs = self.model.n_dofs();
        self.column.resize(3 * n_dofs, 0.0);
        let scratch = self.scratch.get_or_insert_with(|| self.model.column_scratch());
        if let Err(e) = self.model.compliance_columns_into(node, &mut self.column, scratch) {
            tracing::error!("surface columns of node {node}: {e}");
            return None;
        }
        let n_surf = self.surface.nodes.len();
        let mut out = vec![0.0; 9 * n_surf].into_boxed_slice();
        for dir in 0..3 {
            for (k, &v) in self.surface.nodes.iter().enumerate() {
                for comp in 0..3 {
                    out[dir * 3 * n_surf + 3 * k + comp] = self.column[dir * n_dofs + 3 * v as usize + comp];
                }
            }
        }
        Some(out.into())
    }
}
