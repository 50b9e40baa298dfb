//! Conformity checks of a tetrahedral mesh (issue 35): what a mesh cut apart or folded over
//! itself has and a conforming one cannot.
//!
//! - **Cracks**: two nodes within [`DUPLICATE_NODE_TOL`] × the bounding-box diagonal of each
//!   other (a check shared with 2D, in [`crate::mesh::SimplexMesh`]). A mesh that repeats a node
//!   instead of sharing it has an internal boundary there: the tissue is cut apart, and its
//!   surface has faces inside it.
//! - **Overlaps across a face**: a triangular face is shared by at most two tetrahedra, and two
//!   that share it lie on opposite sides of it ([`check_faces`]). A positive tetrahedron added on
//!   top of a boundary face, or folded back over a neighbour, fails here.
//! - **Overlaps elsewhere**: just outside every boundary face there is no tissue
//!   ([`check_boundary_probes`]): four points of each boundary face (its centre and three points
//!   near its corners), moved outwards by $10^{-7}$ of the face's longest edge, must lie in no
//!   tetrahedron. A tetrahedron (or a whole part) lying inside others has its boundary faces
//!   inside them.
//!
//! Why these suffice when faces pair up: with every tetrahedron positive and every interior face
//! shared by two from opposite sides, the number of tetrahedra holding a point equals the
//! winding number of the boundary surface about it (the interior faces cancel). That number is
//! 0 just outside every boundary face, and it changes by one across the surface; where the
//! boundary surface does not cross itself, it is therefore at most 1 everywhere: no overlaps.
//! What is not searched for is a boundary surface crossing itself where none of the probe
//! points of its faces lies in the other part (a sliver of overlap between two parts of the
//! boundary). Note that comparing the sum of the element volumes with the volume the boundary
//! encloses (divergence theorem) finds nothing: once faces pair up, the two are equal by
//! construction, counting the overlapped volume twice on both sides.
//!
//! Costs: $O(n \log n)$ sorts (nodes by cell, faces by nodes) and one point location per probe
//! ([`TetLocator`], $O(1)$ expected).

use super::locate::TetLocator;
use super::mesh::{TetMesh, TetMeshError, cross, dot, signed_volume_m3, sub};

/// Two nodes closer than this fraction of the mesh's bounding-box diagonal are the same node (as
/// in 2D: [`crate::mesh::DUPLICATE_NODE_TOL`]).
pub const DUPLICATE_NODE_TOL: f64 = crate::mesh::DUPLICATE_NODE_TOL;

/// A probe point is moved off its boundary face by this fraction of the face's longest edge.
pub const PROBE_OFFSET: f64 = 1e-7;

/// A probe point lies inside a tetrahedron when its smallest barycentric weight there exceeds
/// this (a point on a face or an edge does not count).
pub const PROBE_INSIDE_TOL: f64 = 1e-9;

/// The face of `tet` opposite its corner `skip`, sorted, and that corner.
fn face(tet: [usize; 4], skip: usize) -> ([usize; 3], usize) {
    let mut f = [0; 3];
    let mut k = 0;
    for (i, &n) in tet.iter().enumerate() {
        if i != skip {
            f[k] = n;
            k += 1;
        }
    }
    f.sort_unstable();
    (f, tet[skip])
}

/// Every face is shared by at most two tetrahedra, and two that share one lie on opposite sides
/// of it. Returns the boundary faces (shared by none): `(tet_idx, corner)`, the corner of the
/// tetrahedron opposite the face.
pub fn check_faces(mesh: &TetMesh) -> Result<Vec<(usize, usize)>, TetMeshError> {
    let tets = mesh.tets();
    let nodes = mesh.nodes_m();
    // 16 bytes a face: node ids and 4 × tet + corner as u32 (far above any mesh that fits in
    // memory; a larger one is refused rather than checked with wrapped ids).
    if mesh.n_nodes() > u32::MAX as usize {
        return Err(TetMeshError::TooManyNodes { n_nodes: mesh.n_nodes(), max_nodes: u32::MAX as usize });
    }
    if tets.len() > (u32::MAX / 4) as usize {
        return Err(TetMeshError::TooManyTets { n_tets: tets.len(), max_tets: (u32::MAX / 4) as usize });
    }
    let mut faces: Vec<([u32; 3], u32)> = Vec::with_capacity(4 * tets.len());
    for (t, &tet) in tets.iter().enumerate() {
        for skip in 0..4 {
            faces.push((face(tet, skip).0.map(|n| n as u32), (4 * t + skip) as u32));
        }
    }
    faces.sort_unstable();
    let mut boundary = Vec::new();
    let mut i = 0;
    while i < faces.len() {
        let f = faces[i].0;
        let mut j = i + 1;
        while j < faces.len() && faces[j].0 == f {
            j += 1;
        }
        let tet_of = |e: usize| (faces[e].1 / 4) as usize;
        let corner_of = |e: usize| (faces[e].1 % 4) as usize;
        match j - i {
            1 => boundary.push((tet_of(i), corner_of(i))),
            2 => {
                let (a, b) = (tet_of(i), tet_of(i + 1));
                let [p, q, r] = f.map(|n| nodes[n as usize]);
                let side = |e: usize| signed_volume_m3(p, q, r, nodes[tets[tet_of(e)][corner_of(e)]]);
                // Non-degenerate tetrahedra: each far corner lies off the face's plane.
                if side(i) * side(i + 1) > 0.0 {
                    return Err(overlapping(mesh, a, b));
                }
            }
            _ => {
                return Err(TetMeshError::FaceSharedByMany {
                    face: f.map(|n| n as usize),
                    tets: [tet_of(i), tet_of(i + 1), tet_of(i + 2)],
                    n_tets: j - i,
                });
            }
        }
        i = j;
    }
    Ok(boundary)
}

fn overlapping(mesh: &TetMesh, a: usize, b: usize) -> TetMeshError {
    let (first_idx, second_idx) = (a.min(b), a.max(b));
    TetMeshError::OverlappingTets { first_idx, first_nodes: mesh.tets()[first_idx], second_idx, second_nodes: mesh.tets()[second_idx] }
}

/// No tissue just outside a boundary face: see the module docs. `boundary` as returned by
/// [`check_faces`].
pub fn check_boundary_probes(mesh: &TetMesh, boundary: &[(usize, usize)]) -> Result<(), TetMeshError> {
    if boundary.is_empty() {
        return Ok(());
    }
    let locator = TetLocator::new(mesh);
    let nodes = mesh.nodes_m();
    for &(t, skip) in boundary {
        let (f, corner) = face(mesh.tets()[t], skip);
        let [p, q, r] = f.map(|n| nodes[n]);
        let mut normal = cross(sub(q, p), sub(r, p));
        if dot(normal, sub(nodes[corner], p)) > 0.0 {
            normal = normal.map(|v| -v); // outwards: away from the tetrahedron's far corner
        }
        let len = dot(normal, normal).sqrt();
        let longest = [sub(q, p), sub(r, q), sub(p, r)].iter().map(|e| dot(*e, *e)).fold(0.0, f64::max).sqrt();
        let offset_m = PROBE_OFFSET * longest / len;
        for w in [[1.0 / 3.0; 3], [0.8, 0.1, 0.1], [0.1, 0.8, 0.1], [0.1, 0.1, 0.8]] {
            let x = [0, 1, 2].map(|k| w[0] * p[k] + w[1] * q[k] + w[2] * r[k] + offset_m * normal[k]);
            if let Ok(loc) = locator.locate(mesh, x) {
                let worst = loc.weights.iter().copied().fold(f64::INFINITY, f64::min);
                if worst > PROBE_INSIDE_TOL && loc.tet_idx != t {
                    return Err(overlapping(mesh, t, loc.tet_idx));
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::d3::mesh::{BoxGridParams, TetMeshLimits};
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    fn lim() -> TetMeshLimits {
        TetMeshLimits::default()
    }

    /// A 4 × 4 × 4-node grid (162 tetrahedra) of a 3 cm cube, its inner nodes moved randomly.
    fn grid() -> TetMesh {
        let m = BoxGridParams::new([4, 4, 4], [0.03; 3]).build(&lim()).unwrap();
        let mut nodes = m.nodes_m().to_vec();
        let mut rng = SmallRng::seed_from_u64(35);
        for p in nodes.iter_mut() {
            if p.iter().all(|&v| v > 1e-9 && v < 0.03 - 1e-9) {
                p.iter_mut().for_each(|v| *v += rng.random_range(-0.002..0.002));
            }
        }
        TetMesh::new(nodes, m.tets().to_vec(), &lim()).unwrap()
    }

    /// The node index of grid node (i, j, k) of [`grid`].
    fn n(i: usize, j: usize, k: usize) -> usize {
        i + 4 * (j + 4 * k)
    }

    #[test]
    fn issue_35_box_grids_distorted_grids_and_the_shipped_brachy_mesh_pass() {
        for (n, size) in [([2, 2, 2], [1.0; 3]), ([5, 3, 7], [0.1, 0.05, 0.2]), ([9, 9, 9], [0.1; 3]), ([3, 2, 2], [0.001, 0.5, 0.02])] {
            let m = BoxGridParams::new(n, size).build(&lim()).unwrap();
            let boundary = check_faces(&m).unwrap();
            // Two triangles per boundary cell face.
            let cells = [n[0] - 1, n[1] - 1, n[2] - 1];
            assert_eq!(boundary.len(), 4 * (cells[0] * cells[1] + cells[1] * cells[2] + cells[0] * cells[2]), "{n:?}");
        }
        grid();
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/brachy-3d.msh")).unwrap();
        let m = crate::msh::parse_msh3d(&text, &lim()).unwrap().mesh;
        assert!(m.n_tets() > 1000, "{}", m.n_tets());
    }

    #[test]
    fn issue_35_a_tetrahedron_on_a_boundary_face_from_inside_is_refused() {
        let m = grid();
        // The bottom face (0,0,0), (1,0,0), (1,1,0) belongs to the tetrahedron above it that
        // reaches (1,1,1); a second one above it, reaching the inner node (1,1,2), overlaps it.
        let extra = [n(0, 0, 0), n(1, 0, 0), n(1, 1, 0), n(1, 1, 2)];
        let owner = m.tets().iter().position(|t| [extra[0], extra[1], extra[2]].iter().all(|x| t.contains(x))).unwrap();
        let mut tets = m.tets().to_vec();
        tets.push(extra);
        let e = TetMesh::new(m.nodes_m().to_vec(), tets.clone(), &lim()).unwrap_err();
        let TetMeshError::OverlappingTets { first_idx, second_idx, .. } = e else { panic!("{e:?}") };
        assert_eq!((first_idx, second_idx), (owner, 162));
        assert!(e.to_string().contains(&format!("tetrahedra {owner} (nodes")) && e.to_string().ends_with("overlap"), "{e}");
        // Either orientation of the extra tetrahedron.
        tets[162].swap(0, 1);
        assert!(matches!(TetMesh::new(m.nodes_m().to_vec(), tets, &lim()), Err(TetMeshError::OverlappingTets { second_idx: 162, .. })));
    }

    #[test]
    fn issue_35_a_tetrahedron_inside_others_is_refused() {
        let m = grid();
        // Four new nodes inside the first cell, near its corner (0,0,0), which no distortion moved.
        let h = 0.01;
        let mut nodes = m.nodes_m().to_vec();
        let base = nodes.len();
        nodes.extend([[0.2 * h, 0.1 * h, 0.1 * h], [0.5 * h, 0.1 * h, 0.1 * h], [0.2 * h, 0.4 * h, 0.1 * h], [0.2 * h, 0.1 * h, 0.4 * h]]);
        let mut tets = m.tets().to_vec();
        tets.push([base, base + 1, base + 2, base + 3]);
        let e = TetMesh::new(nodes, tets, &lim()).unwrap_err();
        assert!(matches!(e, TetMeshError::OverlappingTets { second_idx: 162, .. }), "{e:?}");
        // A large tetrahedron on existing nodes: the cube's corner cut off by the plane through
        // (2,0,0), (0,2,0), (0,0,2); its three faces on the cube's surface are boundary faces too.
        let mut tets = m.tets().to_vec();
        tets.push([n(0, 0, 0), n(2, 0, 0), n(0, 2, 0), n(0, 0, 2)]);
        let e = TetMesh::new(m.nodes_m().to_vec(), tets, &lim()).unwrap_err();
        assert!(
            matches!(e, TetMeshError::OverlappingTets { second_idx: 162, .. } | TetMeshError::OverlappingTets { first_idx: 162, .. }),
            "{e:?}"
        );
        // A whole second cube inside the first (its own nodes, shrunk and moved inwards).
        let inner = BoxGridParams::new([3, 3, 3], [0.01; 3]).build(&lim()).unwrap();
        let mut nodes = m.nodes_m().to_vec();
        let off = nodes.len();
        nodes.extend(inner.nodes_m().iter().map(|p| p.map(|v| v + 0.01)));
        let mut tets = m.tets().to_vec();
        tets.extend(inner.tets().iter().map(|t| t.map(|i| i + off)));
        assert!(matches!(TetMesh::new(nodes, tets, &lim()), Err(TetMeshError::OverlappingTets { .. })));
    }

    #[test]
    fn issue_35_three_tetrahedra_on_one_face_are_refused() {
        let m = grid();
        // An inner face (shared by two tetrahedra) and a node well off its plane.
        let t = m.tets()[100];
        let f = [t[0], t[1], t[2]];
        assert_eq!(m.tets().iter().filter(|u| f.iter().all(|x| u.contains(x))).count(), 2, "an inner face");
        let p = f.map(|i| m.nodes_m()[i]);
        let far = (0..m.n_nodes()).max_by(|&a, &b| {
            let v = |i: usize| signed_volume_m3(p[0], p[1], p[2], m.nodes_m()[i]).abs();
            v(a).total_cmp(&v(b))
        });
        let mut tets = m.tets().to_vec();
        tets.push([f[0], f[1], f[2], far.unwrap()]);
        let e = TetMesh::new(m.nodes_m().to_vec(), tets, &lim()).unwrap_err();
        let mut sorted = f;
        sorted.sort_unstable();
        let TetMeshError::FaceSharedByMany { face, tets, n_tets: 3 } = e else { panic!("{e:?}") };
        assert_eq!(face, sorted);
        assert!(tets.contains(&100) && tets.contains(&162), "{tets:?}");
        assert!(e.to_string().contains("belongs to 3 tetrahedra"), "{e}");
    }

    #[test]
    fn issue_35_a_crack_of_repeated_nodes_is_refused() {
        let m = grid();
        // Cut the cube along the plane x = 1 cm: the tetrahedra on its right get their own copies
        // of the nodes on the plane (i = 1, undistorted there: on the boundary they stay put, and
        // inside they moved, but the copies sit exactly where the originals are).
        let mut nodes = m.nodes_m().to_vec();
        let mut copy = std::collections::BTreeMap::new();
        let mut tets = m.tets().to_vec();
        for t in tets.iter_mut() {
            let right = t.iter().any(|&i| i % 4 >= 2);
            if right {
                for i in t.iter_mut().filter(|i| **i % 4 == 1) {
                    *i = *copy.entry(*i).or_insert_with(|| {
                        nodes.push(nodes[*i]);
                        nodes.len() - 1
                    });
                }
            }
        }
        assert_eq!(copy.len(), 16);
        // Topologically the two halves are fine: the faces pair up, and the crack's faces are
        // boundary faces on both sides.
        let e = TetMesh::new(nodes.clone(), tets.clone(), &lim()).unwrap_err();
        let TetMeshError::DuplicateNode { first_idx, second_idx, x_m, .. } = e else { panic!("{e:?}") };
        assert_eq!(copy.get(&first_idx), Some(&second_idx));
        assert_eq!(x_m, nodes[first_idx]);
        assert!(e.to_string().contains(&format!("nodes {first_idx} and {second_idx} coincide")) && e.to_string().contains("crack"), "{e}");
        // Near-duplicates too (in any direction, across cell borders), but not nodes further apart.
        let tol_m = DUPLICATE_NODE_TOL * (3.0f64 * 0.03 * 0.03).sqrt();
        for (k, &c) in copy.values().enumerate() {
            let d = [[0.3, -0.5, 0.6], [-0.7, 0.1, -0.2], [0.0, 0.0, -0.9]][k % 3];
            nodes[c] = [0, 1, 2].map(|a| nodes[c][a] + d[a] * tol_m);
        }
        assert!(matches!(TetMesh::new(nodes.clone(), tets.clone(), &lim()), Err(TetMeshError::DuplicateNode { .. })));
        for &c in copy.values() {
            nodes[c][1] += 3.0 * tol_m;
        }
        // Then the copies are no duplicates, but the crack is thinner than the probes' offset
        // (1e-7 of an edge): tissue lies just outside its faces.
        assert!(matches!(TetMesh::new(nodes, tets, &lim()), Err(TetMeshError::OverlappingTets { .. })));
    }
}
