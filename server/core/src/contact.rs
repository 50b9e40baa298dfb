//! Where a needle contact sits in the tissue ([`ContactPoint`]), in 2D and 3D: a mesh node, or a
//! material point inside an element — a triangle (3 nodes) in 2D, a tetrahedron (4 nodes) in
//! 3D — whose displacement is interpolated from the element's nodes.
//!
//! A material point $X$ in element $T$ with barycentric weights $N_k(X)$ moves as
//! $u(X) = \sum_{k \in T} N_k(X)\,u_k$, and a force $f$ applied there loads node $k$ with
//! $N_k(X)\,f$. The compliance between two contacts $a$ and $b$ is therefore
//! $W_{ab} = \sum_{i \in a}\sum_{j \in b} N_{a,i} N_{b,j}\, C_{ij}$ ($D \times D$ blocks of the
//! nodal compliance $C = K_{ff}^{-1}$, $D \in \{2, 3\}$), which is what
//! [`crate::ComplianceCache::contact_block`] computes; a node is the special case of one term
//! with weight 1. The same condensation, pivots and rotations then work on nodes and material
//! points alike.
//!
//! The type is the same in both dimensions (up to four terms; a triangle uses three): the
//! dimension is a property of the mesh and of the solver ([`crate::mixed`]), not of where a
//! contact sits, and [`ContactPoint::interpolate`] is generic over the vector length.

use crate::ids::NodeIdx;

/// A contact's place in the mesh: one node (weight 1), or a material point inside triangle
/// `tri_idx` (2D) with the triangle's three nodes, or inside tetrahedron `tet_idx` (3D) with its
/// four nodes, and the point's barycentric weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    nodes: [NodeIdx; 4],
    weights: [f64; 4],
    /// Number of terms: 1 (a node), 3 (a triangle's point) or 4 (a tetrahedron's point).
    len: u8,
    /// The element a material point lies in (a triangle when `len == 3`, a tetrahedron when
    /// `len == 4`).
    elem_idx: Option<u32>,
}

impl ContactPoint {
    /// The mesh node `node_idx` itself.
    pub fn node(node_idx: NodeIdx) -> Self {
        Self { nodes: [node_idx; 4], weights: [1.0, 0.0, 0.0, 0.0], len: 1, elem_idx: None }
    }

    /// The material point of triangle `tri_idx` (nodes `nodes`) with barycentric weights
    /// `weights` (summing to 1). 2D.
    pub fn in_triangle(tri_idx: usize, nodes: [usize; 3], weights: [f64; 3]) -> Self {
        let n = nodes.map(NodeIdx);
        Self { nodes: [n[0], n[1], n[2], n[2]], weights: [weights[0], weights[1], weights[2], 0.0], len: 3, elem_idx: Some(tri_idx as u32) }
    }

    /// The material point of tetrahedron `tet_idx` (nodes `nodes`) with barycentric weights
    /// `weights` (summing to 1). 3D.
    pub fn in_tetrahedron(tet_idx: usize, nodes: [usize; 4], weights: [f64; 4]) -> Self {
        Self { nodes: nodes.map(NodeIdx), weights, len: 4, elem_idx: Some(tet_idx as u32) }
    }

    /// The interpolation terms $(k, N_k)$: one for a node, three for a triangle's material
    /// point, four for a tetrahedron's.
    #[inline]
    pub fn terms(&self) -> impl Iterator<Item = (NodeIdx, f64)> + '_ {
        self.nodes[..self.len as usize].iter().copied().zip(self.weights[..self.len as usize].iter().copied())
    }

    /// The mesh nodes whose displacements this contact interpolates.
    #[inline]
    pub fn nodes(&self) -> &[NodeIdx] {
        &self.nodes[..self.len as usize]
    }

    /// The node itself, for a node contact.
    #[inline]
    pub fn as_node(&self) -> Option<NodeIdx> {
        (self.len == 1).then_some(self.nodes[0])
    }

    /// The triangle a 2D material point lies in (`None` for a node contact or a tetrahedron's
    /// point).
    #[inline]
    pub fn tri_idx(&self) -> Option<usize> {
        if self.len == 3 { self.elem_idx.map(|t| t as usize) } else { None }
    }

    /// The tetrahedron a 3D material point lies in (`None` for a node contact or a triangle's
    /// point).
    #[inline]
    pub fn tet_idx(&self) -> Option<usize> {
        if self.len == 4 { self.elem_idx.map(|t| t as usize) } else { None }
    }

    /// The node with the largest weight (the node itself for a node contact): what a client that
    /// knows only nodes is told.
    pub fn nearest_node(&self) -> NodeIdx {
        let mut best = 0;
        for k in 1..self.len as usize {
            if self.weights[k] > self.weights[best] {
                best = k;
            }
        }
        self.nodes[best]
    }

    /// The interpolated value $\sum_k N_k v_k$ of a nodal field of `D`-vectors given per node by
    /// `value`.
    #[inline]
    pub fn interpolate<const D: usize>(&self, mut value: impl FnMut(NodeIdx) -> [f64; D]) -> [f64; D] {
        let mut out = [0.0; D];
        for (k, w) in self.terms() {
            let v = value(k);
            for c in 0..D {
                out[c] += w * v[c];
            }
        }
        out
    }
}

impl std::fmt::Display for ContactPoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = &self.nodes;
        match (self.elem_idx, self.len) {
            (Some(t), 4) => write!(f, "the material point in tetrahedron {t} (nodes {}, {}, {}, {})", n[0], n[1], n[2], n[3]),
            (Some(t), _) => write!(f, "the material point in triangle {t} (nodes {}, {}, {})", n[0], n[1], n[2]),
            (None, _) => write!(f, "node {}", n[0]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_and_points_interpolate_and_name_themselves() {
        let n = ContactPoint::node(NodeIdx(7));
        assert_eq!(n.as_node(), Some(NodeIdx(7)));
        assert_eq!(n.nodes(), &[NodeIdx(7)]);
        assert_eq!(n.to_string(), "node 7");
        let p = ContactPoint::in_triangle(12, [3, 4, 9], [0.2, 0.5, 0.3]);
        assert_eq!(p.as_node(), None);
        assert_eq!(p.tri_idx(), Some(12));
        assert_eq!(p.nearest_node(), NodeIdx(4));
        assert_eq!(p.to_string(), "the material point in triangle 12 (nodes 3, 4, 9)");
        let v = p.interpolate(|k| [k.0 as f64, 1.0]);
        assert!((v[0] - (0.2 * 3.0 + 0.5 * 4.0 + 0.3 * 9.0)).abs() < 1e-15 && (v[1] - 1.0).abs() < 1e-15);
        assert_eq!(p.tet_idx(), None);
        // 3D: a tetrahedron's point has four terms.
        let q = ContactPoint::in_tetrahedron(5, [1, 2, 8, 6], [0.1, 0.2, 0.3, 0.4]);
        assert_eq!((q.as_node(), q.tri_idx(), q.tet_idx()), (None, None, Some(5)));
        assert_eq!(q.nodes(), &[NodeIdx(1), NodeIdx(2), NodeIdx(8), NodeIdx(6)]);
        assert_eq!(q.terms().count(), 4);
        assert_eq!(q.nearest_node(), NodeIdx(6));
        assert_eq!(q.to_string(), "the material point in tetrahedron 5 (nodes 1, 2, 8, 6)");
        let v = q.interpolate(|k| [k.0 as f64, 1.0, -2.0]);
        assert!((v[0] - (0.1 + 0.4 + 2.4 + 2.4)).abs() < 1e-14 && (v[1] - 1.0).abs() < 1e-15 && (v[2] + 2.0).abs() < 1e-15);
    }
}
