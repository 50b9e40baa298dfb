//! Where a needle contact sits in the tissue ([`ContactPoint`]): a mesh node, or a material point
//! inside a triangle whose displacement is interpolated from the triangle's nodes.
//!
//! A material point $X$ in triangle $T$ with barycentric weights $N_k(X)$ moves as
//! $u(X) = \sum_{k \in T} N_k(X)\,u_k$, and a force $f$ applied there loads node $k$ with
//! $N_k(X)\,f$. The compliance between two contacts $a$ and $b$ is therefore
//! $W_{ab} = \sum_{i \in a}\sum_{j \in b} N_{a,i} N_{b,j}\, C_{ij}$ (2 × 2 blocks of the nodal
//! compliance $C = K_{ff}^{-1}$), which is what [`crate::ComplianceCache::contact_block`] computes;
//! a node is the special case of one term with weight 1. The same condensation, pivots and
//! rotations then work on nodes and material points alike.

use crate::ids::NodeIdx;

/// A contact's place in the mesh: one node (weight 1), or a material point inside triangle
/// `tri_idx` with the triangle's three nodes and the point's barycentric weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    nodes: [NodeIdx; 3],
    weights: [f64; 3],
    len: u8,
    tri_idx: Option<u32>,
}

impl ContactPoint {
    /// The mesh node `node_idx` itself.
    pub fn node(node_idx: NodeIdx) -> Self {
        Self { nodes: [node_idx; 3], weights: [1.0, 0.0, 0.0], len: 1, tri_idx: None }
    }

    /// The material point of triangle `tri_idx` (nodes `nodes`) with barycentric weights
    /// `weights` (summing to 1).
    pub fn in_triangle(tri_idx: usize, nodes: [usize; 3], weights: [f64; 3]) -> Self {
        Self { nodes: nodes.map(NodeIdx), weights, len: 3, tri_idx: Some(tri_idx as u32) }
    }

    /// The interpolation terms $(k, N_k)$: one for a node, three for a material point.
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

    /// The triangle a material point lies in (`None` for a node contact).
    #[inline]
    pub fn tri_idx(&self) -> Option<usize> {
        self.tri_idx.map(|t| t as usize)
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

    /// The interpolated value $\sum_k N_k v_k$ of a nodal field given per node by `value`.
    #[inline]
    pub fn interpolate(&self, mut value: impl FnMut(NodeIdx) -> [f64; 2]) -> [f64; 2] {
        let mut out = [0.0; 2];
        for (k, w) in self.terms() {
            let v = value(k);
            out[0] += w * v[0];
            out[1] += w * v[1];
        }
        out
    }
}

impl std::fmt::Display for ContactPoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.tri_idx {
            None => write!(f, "node {}", self.nodes[0]),
            Some(t) => write!(f, "the material point in triangle {t} (nodes {}, {}, {})", self.nodes[0], self.nodes[1], self.nodes[2]),
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
    }
}
