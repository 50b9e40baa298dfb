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
//! The type is the same in both dimensions (a triangle's point uses three terms, a
//! tetrahedron's four): the dimension is a property of the mesh and of the solver
//! ([`crate::mixed`]), not of where a contact sits, and [`ContactPoint::interpolate`] is generic
//! over the vector length.
//!
//! A **patch** (2D, issue 19) spreads a contact over a segment $S$ of length $w$ (the needle's
//! width) instead of a point: its weights are the shape functions averaged over the segment,
//! $N_k = \frac{1}{|S|}\int_S N_k(X)\,dX$ (exact: $N_k$ is linear on each triangle's piece), so
//! its displacement is the segment's mean displacement and its force is spread evenly along it.
//! A point load's compliance grows like $\ln(1/h)$ under refinement in 2D; a segment's is finite,
//! so the contact's stiffness, and everything it sets, converges. Up to [`MAX_TERMS`] nodes.
//!
//! A **disc** (3D, issue 37) is the same over the needle's cross-section: a disc across the
//! shaft, its weights the shape functions averaged over it ([`crate::d3::disc`], exact), built by
//! [`ContactPoint::disc`] from any list of terms.

use crate::ids::NodeIdx;

/// The most nodes a contact interpolates (a patch's; a point uses at most four).
pub const MAX_TERMS: usize = 12;

/// What a [`ContactPoint`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Node,
    Triangle,
    Tetrahedron,
    Patch,
    Disc,
}

/// A contact's place in the mesh: one node (weight 1), or a material point inside triangle
/// `tri_idx` (2D) with the triangle's three nodes, or inside tetrahedron `tet_idx` (3D) with its
/// four nodes, and the point's barycentric weights; or a 2D patch or a 3D disc (module docs) with
/// up to [`MAX_TERMS`] nodes and its centre's triangle or tetrahedron.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    nodes: [NodeIdx; MAX_TERMS],
    weights: [f64; MAX_TERMS],
    /// Number of terms.
    len: u8,
    kind: Kind,
    /// The element a material point lies in (a patch's or a disc's: the one its centre lies in).
    elem_idx: Option<u32>,
}

/// Why [`ContactPoint::patch`] or [`ContactPoint::disc`] refused a patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum PatchError {
    /// The segment touches more than [`MAX_TERMS`] nodes (a needle far wider than the elements).
    #[error("the contact patch touches more than {MAX_TERMS} nodes")]
    TooManyNodes,
    /// No part of the segment has a weight (an empty or degenerate segment).
    #[error("the contact patch has no length inside the mesh")]
    Empty,
}

impl ContactPoint {
    /// The mesh node `node_idx` itself.
    pub fn node(node_idx: NodeIdx) -> Self {
        let mut weights = [0.0; MAX_TERMS];
        weights[0] = 1.0;
        Self { nodes: [node_idx; MAX_TERMS], weights, len: 1, kind: Kind::Node, elem_idx: None }
    }

    /// The first `N` terms of `nodes`/`weights`, the rest empty.
    fn with_terms<const N: usize>(kind: Kind, elem_idx: usize, nodes: [usize; N], weights: [f64; N]) -> Self {
        let mut n = [NodeIdx(nodes[N - 1]); MAX_TERMS];
        let mut w = [0.0; MAX_TERMS];
        for k in 0..N {
            n[k] = NodeIdx(nodes[k]);
            w[k] = weights[k];
        }
        Self { nodes: n, weights: w, len: N as u8, kind, elem_idx: Some(elem_idx as u32) }
    }

    /// The material point of triangle `tri_idx` (nodes `nodes`) with barycentric weights
    /// `weights` (summing to 1). 2D.
    pub fn in_triangle(tri_idx: usize, nodes: [usize; 3], weights: [f64; 3]) -> Self {
        Self::with_terms(Kind::Triangle, tri_idx, nodes, weights)
    }

    /// The material point of tetrahedron `tet_idx` (nodes `nodes`) with barycentric weights
    /// `weights` (summing to 1). 3D.
    pub fn in_tetrahedron(tet_idx: usize, nodes: [usize; 4], weights: [f64; 4]) -> Self {
        Self::with_terms(Kind::Tetrahedron, tet_idx, nodes, weights)
    }

    /// A 2D patch (module docs) whose centre lies in triangle `centre_tri_idx`, from its pieces:
    /// `pieces` yields, for each part of the segment inside one triangle, the triangle's nodes,
    /// the barycentric weights at the part's midpoint and the part's length. Terms of the same
    /// node are merged and the weights normalised by the total length (so a segment partly
    /// outside the mesh is the mean over the part inside).
    ///
    /// Errors: [`PatchError::TooManyNodes`] when the pieces touch more than [`MAX_TERMS`]
    /// nodes, [`PatchError::Empty`] when their total length is not positive.
    pub fn patch(centre_tri_idx: usize, pieces: impl IntoIterator<Item = ([usize; 3], [f64; 3], f64)>) -> Result<Self, PatchError> {
        let mut out = Self {
            nodes: [NodeIdx(0); MAX_TERMS],
            weights: [0.0; MAX_TERMS],
            len: 0,
            kind: Kind::Patch,
            elem_idx: Some(centre_tri_idx as u32),
        };
        let mut total = 0.0;
        for (nodes, bary, len_m) in pieces {
            total += len_m;
            for (j, b) in nodes.into_iter().zip(bary) {
                out.add_term(j, b * len_m)?;
            }
        }
        if !(total > 0.0) {
            return Err(PatchError::Empty);
        }
        for w in &mut out.weights[..out.len as usize] {
            *w /= total;
        }
        Ok(out)
    }

    /// A 3D disc (module docs) whose centre lies in tetrahedron `centre_tet_idx`, from its terms
    /// $(k, w_k)$ as given (the weights of [`crate::d3::disc::disc_weights_into`], summing to 1):
    /// terms of the same node are merged, terms with a zero weight dropped; the weights are kept
    /// as given (not normalised).
    ///
    /// Errors: [`PatchError::TooManyNodes`] when more than [`MAX_TERMS`] nodes carry a weight,
    /// [`PatchError::Empty`] when the weights do not sum to a positive number.
    pub fn disc(centre_tet_idx: usize, terms: impl IntoIterator<Item = (usize, f64)>) -> Result<Self, PatchError> {
        let mut out = Self {
            nodes: [NodeIdx(0); MAX_TERMS],
            weights: [0.0; MAX_TERMS],
            len: 0,
            kind: Kind::Disc,
            elem_idx: Some(centre_tet_idx as u32),
        };
        let mut total = 0.0;
        for (j, w) in terms {
            if w == 0.0 {
                continue;
            }
            total += w;
            out.add_term(j, w)?;
        }
        if !(total > 0.0) {
            return Err(PatchError::Empty);
        }
        Ok(out)
    }

    /// Adds weight `w` to node `j`'s term (merged with an existing one), for [`Self::patch`] and
    /// [`Self::disc`].
    ///
    /// Errors: [`PatchError::TooManyNodes`] when `j` would be term [`MAX_TERMS`] + 1.
    fn add_term(&mut self, j: usize, w: f64) -> Result<(), PatchError> {
        let len = self.len as usize;
        match self.nodes[..len].iter().position(|n| n.0 == j) {
            Some(k) => self.weights[k] += w,
            None if len < MAX_TERMS => {
                self.nodes[len] = NodeIdx(j);
                self.weights[len] = w;
                self.len += 1;
            }
            None => return Err(PatchError::TooManyNodes),
        }
        Ok(())
    }

    /// Whether this contact is spread over the tissue: a 2D patch or a 3D disc.
    #[inline]
    pub fn is_patch(&self) -> bool {
        matches!(self.kind, Kind::Patch | Kind::Disc)
    }

    /// Whether this contact is a 3D disc ([`ContactPoint::disc`]).
    #[inline]
    pub fn is_disc(&self) -> bool {
        self.kind == Kind::Disc
    }

    /// At most three terms standing for this contact where a record keeps three (a node's or a
    /// triangle's point's are its own, in order; otherwise the three heaviest, weights
    /// renormalised to sum to 1): for drawing a field, never for the physics. Returns the
    /// count used.
    pub fn three_terms(&self) -> ([NodeIdx; 3], [f64; 3], usize) {
        if self.len <= 3 {
            // A node or a triangle's point: its own terms, in order.
            let used = self.len as usize;
            let mut nodes = [self.nodes[0]; 3];
            let mut weights = [0.0; 3];
            nodes[..used].copy_from_slice(&self.nodes[..used]);
            weights[..used].copy_from_slice(&self.weights[..used]);
            return (nodes, weights, used);
        }
        let mut idx = [usize::MAX; 3];
        for slot in 0..3 {
            let mut best: Option<usize> = None;
            for k in 0..self.len as usize {
                if idx[..slot].contains(&k) {
                    continue;
                }
                if best.is_none_or(|b| self.weights[k] > self.weights[b]) {
                    best = Some(k);
                }
            }
            if let Some(b) = best {
                idx[slot] = b;
            }
        }
        let used = (self.len as usize).min(3);
        let mut nodes = [self.nodes[0]; 3];
        let mut weights = [0.0; 3];
        for k in 0..used {
            nodes[k] = self.nodes[idx[k]];
            weights[k] = self.weights[idx[k]];
        }
        let sum: f64 = weights.iter().sum();
        if used > 0 && sum != 0.0 {
            for w in &mut weights[..used] {
                *w /= sum;
            }
        }
        (nodes, weights, used)
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
        if matches!(self.kind, Kind::Triangle | Kind::Patch) { self.elem_idx.map(|t| t as usize) } else { None }
    }

    /// The tetrahedron a 3D material point lies in, or a disc's centre (`None` for a node
    /// contact or a triangle's point).
    #[inline]
    pub fn tet_idx(&self) -> Option<usize> {
        if matches!(self.kind, Kind::Tetrahedron | Kind::Disc) { self.elem_idx.map(|t| t as usize) } else { None }
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

/// A contact's identity, for errors and messages: what it is, its element and its first four
/// nodes (a [`ContactPoint`] without its weights and a patch's further nodes; small enough to
/// return by value in an error).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ContactId {
    kind: Kind,
    elem_idx: Option<u32>,
    nodes: [NodeIdx; 4],
    len: u8,
}

impl ContactPoint {
    /// This contact's identity ([`ContactId`]).
    pub fn id(&self) -> ContactId {
        ContactId { kind: self.kind, elem_idx: self.elem_idx, nodes: [0, 1, 2, 3].map(|k| self.nodes[k]), len: self.len }
    }
}

impl std::fmt::Display for ContactId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = &self.nodes;
        let t = self.elem_idx.unwrap_or(0);
        match self.kind {
            Kind::Tetrahedron => write!(f, "the material point in tetrahedron {t} (nodes {}, {}, {}, {})", n[0], n[1], n[2], n[3]),
            Kind::Triangle => write!(f, "the material point in triangle {t} (nodes {}, {}, {})", n[0], n[1], n[2]),
            Kind::Patch => write!(f, "the contact patch centred in triangle {t} ({} nodes)", self.len),
            Kind::Disc => write!(f, "the contact disc centred in tetrahedron {t} ({} nodes)", self.len),
            Kind::Node => write!(f, "node {}", n[0]),
        }
    }
}

impl std::fmt::Display for ContactPoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.id().fmt(f)
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

    #[test]
    fn a_patch_merges_its_pieces_and_normalises_by_length() {
        // Two pieces sharing nodes 2 and 3: lengths 1 and 3.
        let p = ContactPoint::patch(7, [([1, 2, 3], [0.5, 0.5, 0.0], 1.0), ([2, 3, 4], [0.2, 0.3, 0.5], 3.0)]).unwrap();
        assert!(p.is_patch() && p.as_node().is_none());
        assert_eq!(p.tri_idx(), Some(7));
        assert_eq!(p.nodes(), &[NodeIdx(1), NodeIdx(2), NodeIdx(3), NodeIdx(4)]);
        let w: Vec<f64> = p.terms().map(|(_, w)| w).collect();
        let want = [0.5 / 4.0, (0.5 + 0.6) / 4.0, 0.9 / 4.0, 1.5 / 4.0];
        for (a, b) in w.iter().zip(want) {
            assert!((a - b).abs() < 1e-15, "{w:?} against {want:?}");
        }
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert_eq!(p.to_string(), "the contact patch centred in triangle 7 (4 nodes)");
        // The three heaviest, renormalised: nodes 4, 2, 3.
        let (n3, w3, used) = p.three_terms();
        assert_eq!((used, n3), (3, [NodeIdx(4), NodeIdx(2), NodeIdx(3)]));
        let s = 1.5 + 1.1 + 0.9;
        assert!((w3[0] - 1.5 / s).abs() < 1e-15 && (w3[1] - 1.1 / s).abs() < 1e-15 && (w3[2] - 0.9 / s).abs() < 1e-15);
        // A point's three terms are its own.
        let q = ContactPoint::in_triangle(1, [5, 6, 7], [0.2, 0.5, 0.3]);
        let (n3, w3, used) = q.three_terms();
        assert_eq!(used, 3);
        assert_eq!((n3, w3), ([NodeIdx(5), NodeIdx(6), NodeIdx(7)], [0.2, 0.5, 0.3]));
        assert_eq!(ContactPoint::node(NodeIdx(3)).three_terms().2, 1);
        // Too many nodes, and nothing at all.
        let many = (0..5).map(|k| ([3 * k, 3 * k + 1, 3 * k + 2], [0.3, 0.3, 0.4], 1.0));
        assert_eq!(ContactPoint::patch(0, many), Err(PatchError::TooManyNodes));
        assert_eq!(ContactPoint::patch(0, std::iter::empty()), Err(PatchError::Empty));
    }

    #[test]
    fn a_disc_keeps_its_weights_merging_repeats_and_dropping_zeros() {
        let d = ContactPoint::disc(9, [(4, 0.25), (7, 0.0), (5, 0.5), (4, 0.125), (6, 0.125)]).unwrap();
        assert!(d.is_patch() && d.is_disc() && d.as_node().is_none());
        assert_eq!((d.tet_idx(), d.tri_idx()), (Some(9), None));
        assert_eq!(d.nodes(), &[NodeIdx(4), NodeIdx(5), NodeIdx(6)]);
        assert_eq!(d.terms().map(|(_, w)| w).collect::<Vec<_>>(), vec![0.375, 0.5, 0.125]);
        assert_eq!(d.to_string(), "the contact disc centred in tetrahedron 9 (3 nodes)");
        assert!(!ContactPoint::in_tetrahedron(1, [1, 2, 3, 4], [0.25; 4]).is_disc());
        let many = (0..=MAX_TERMS).map(|k| (k, 1.0 / (MAX_TERMS + 1) as f64));
        assert_eq!(ContactPoint::disc(0, many), Err(PatchError::TooManyNodes));
        // A zero weight does not count against the limit.
        let zeros = (0..MAX_TERMS).map(|k| (k, 1.0 / MAX_TERMS as f64)).chain([(99, 0.0)]);
        assert_eq!(ContactPoint::disc(0, zeros).unwrap().nodes().len(), MAX_TERMS);
        assert_eq!(ContactPoint::disc(0, [(1, 0.0)]), Err(PatchError::Empty));
    }
}
