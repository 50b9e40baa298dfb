//! Fuzzing harness for every parser of an input file (issue 13): Gmsh MSH (2D, and 3D with the
//! overlapping and cracked meshes of issue 35), scene TOML, the three
//! trajectory CSV readers (server, client, device bridge), the validation exchange JSON,
//! marker-track CSV, the identification probe and force logs (CSV) and PNG frames. Each case
//! mutates a real seed file or generates an input from a grammar, runs the parser in-process, and
//! asserts: no panic, no hang, at most `fuzz::MEMORY_CAP_BYTES` held at once, and either a valid
//! result or an error with a message.
//!
//! `cargo test` runs a bounded, seeded number of cases per parser. The long run is on demand:
//!
//! ```text
//! NEEDLESIM_FUZZ_SECONDS=1800 cargo test -p needlesim-server --test fuzz_parsers -- --ignored --nocapture
//! ```
//!
//! runs every parser in turn on one thread, that long each (`NEEDLESIM_FUZZ_TARGETS=msh,png` picks
//! some), and prints the cases per parser. See
//! `fuzz/mod.rs` for the other variables (base seed, case count, replay of one case).
//!
//! Meshes are read with smaller [`MeshLimits`] than the default (a million nodes): a valid scene of
//! the default maximum size legitimately takes gigabytes and minutes to factor, so the fuzzer
//! checks that the parsers respect the limits they are given, at a size where each case is quick.

mod fuzz;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Duration;

use fuzz::{Target, Verdict, verdict};
use needlesim_core::MeshLimits;
use needlesim_core::d3::mesh::signed_volume_m3;
use needlesim_core::d3::{BoxGridParams, TetMesh, TetMeshLimits};
use needlesim_identify::logs::{ForceLog, ProbeLog};
use needlesim_identify::track::{Polarity, Scale, TrackParams, track_png_bytes};
use needlesim_identify::tracks::MarkerTracks;
use needlesim_scene::exchange::{Scenario, solve_scenario};
use rand::Rng;
use rand::rngs::SmallRng;

#[global_allocator]
static ALLOC: fuzz::CappedAlloc = fuzz::CappedAlloc;

/// Mesh limits for the text parsers (meshes are parsed, not factored).
const PARSE_LIMITS: MeshLimits = MeshLimits { max_nodes: 20_000, max_triangles: 40_000 };
/// Mesh limits where the parsed mesh is factored or solved (scenes, exchange scenarios).
const SOLVE_LIMITS: MeshLimits = MeshLimits { max_nodes: 3_000, max_triangles: 6_000 };

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap()
}

fn validation_dir() -> PathBuf {
    std::env::var_os("NEEDLESIM_VALIDATION").map_or_else(|| repo().join("../shared/validation"), PathBuf::from)
}

/// The files in `dir` ending in `ext` (sorted), read as bytes.
fn files(dir: &Path, ext: &str) -> Vec<Vec<u8>> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    paths.sort();
    paths.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

fn dict(words: &[&str]) -> Vec<Vec<u8>> {
    words.iter().map(|w| w.as_bytes().to_vec()).collect()
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn strictly_increasing(t: &[f64]) -> bool {
    t.windows(2).all(|w| w[0] < w[1])
}

// ---------------------------------------------------------------------------------------------
// Gmsh MSH

/// The folder of the MSH seeds: the core's test meshes, and the validation meshes when present.
fn msh_seeds() -> Vec<Vec<u8>> {
    let mut seeds = files(&repo().join("server/core/testdata"), "msh");
    let shared = validation_dir().join("meshes");
    if shared.is_dir() {
        seeds.extend(files(&shared, "msh"));
    }
    seeds
}

fn check_msh(input: &[u8]) -> Verdict {
    verdict(needlesim_core::msh::parse_msh(&fuzz::text(input), &PARSE_LIMITS), |m| {
        let mesh = &m.mesh;
        let n = mesh.n_nodes();
        if n == 0 || mesh.n_triangles() == 0 || m.node_tags.len() != n {
            return Err(format!("accepted a mesh of {n} nodes, {} triangles, {} tags", mesh.n_triangles(), m.node_tags.len()));
        }
        if !mesh.nodes_m().iter().all(|p| finite(p)) || mesh.triangles().iter().flatten().any(|&i| i >= n) {
            return Err("accepted a mesh with a non-finite node or a dangling triangle".into());
        }
        Ok(())
    })
}

/// A count as written in a header: right mostly, off by one or extreme now and then.
fn count(rng: &mut SmallRng, n: usize) -> String {
    match rng.random_range(0..20) {
        0 => (n + 1).to_string(),
        1 => n.saturating_sub(1).to_string(),
        2 => pick_extreme(rng),
        _ => n.to_string(),
    }
}

/// A small grid mesh (`nx × ny` nodes, two triangles per cell, a physical bottom line and a
/// physical surface) in MSH 2.2 or 4.1, with counts and fields that are sometimes wrong.
fn generate_msh(rng: &mut SmallRng) -> Vec<u8> {
    let (nx, ny) = (rng.random_range(1..7usize), rng.random_range(1..7usize));
    let v4 = rng.random_bool(0.5);
    let node = |i: usize, j: usize| 1 + j * nx + i;
    let mut tris = Vec::new();
    for j in 0..ny.saturating_sub(1) {
        for i in 0..nx.saturating_sub(1) {
            tris.push([node(i, j), node(i + 1, j), node(i + 1, j + 1)]);
            tris.push([node(i, j), node(i + 1, j + 1), node(i, j + 1)]);
        }
    }
    let lines: Vec<[usize; 2]> = (0..nx.saturating_sub(1)).map(|i| [node(i, 0), node(i + 1, 0)]).collect();
    let xy = |rng: &mut SmallRng, k: usize| {
        let (i, j) = ((k - 1) % nx, (k - 1) / nx);
        if rng.random_bool(0.97) { format!("{} {} 0", i as f64 * 0.01, j as f64 * 0.01) } else { format!("{} {} 0", pick_extreme(rng), j) }
    };
    let n_nodes = nx * ny;
    let mut s = format!("$MeshFormat\n{} 0 8\n$EndMeshFormat\n", if v4 { "4.1" } else { "2.2" });
    if rng.random_bool(0.7) {
        s += &format!("$PhysicalNames\n{}\n1 1 \"bottom\"\n2 2 \"tissue\"\n$EndPhysicalNames\n", count(rng, 2));
    }
    if v4 {
        s += &format!("$Entities\n0 {} 1 0\n1 0 0 0 1 0 0 1 1 2 1 2\n1 0 0 0 1 1 0 1 2 1 1\n$EndEntities\n", count(rng, 1));
        s += &format!("$Nodes\n1 {} 1 {n_nodes}\n2 1 0 {}\n", count(rng, n_nodes), count(rng, n_nodes));
        s += &(1..=n_nodes).map(|k| format!("{k}\n")).collect::<String>();
        s += &(1..=n_nodes).map(|k| xy(rng, k) + "\n").collect::<String>();
        s += "$EndNodes\n";
        let n_el = tris.len() + lines.len();
        s += &format!("$Elements\n2 {} 1 {n_el}\n1 1 1 {}\n", count(rng, n_el), count(rng, lines.len()));
        s += &lines.iter().enumerate().map(|(e, l)| format!("{} {} {}\n", e + 1, l[0], l[1])).collect::<String>();
        s += &format!("2 1 2 {}\n", count(rng, tris.len()));
        s += &tris.iter().enumerate().map(|(e, t)| format!("{} {} {} {}\n", e + 1 + lines.len(), t[0], t[1], t[2])).collect::<String>();
        s += "$EndElements\n";
    } else {
        s += &format!("$Nodes\n{}\n", count(rng, n_nodes));
        s += &(1..=n_nodes).map(|k| format!("{k} {}\n", xy(rng, k))).collect::<String>();
        s += "$EndNodes\n";
        s += &format!("$Elements\n{}\n", count(rng, tris.len() + lines.len()));
        s += &lines.iter().enumerate().map(|(e, l)| format!("{} 1 2 1 1 {} {}\n", e + 1, l[0], l[1])).collect::<String>();
        s += &tris
            .iter()
            .enumerate()
            .map(|(e, t)| format!("{} 2 2 2 1 {} {} {}\n", e + 1 + lines.len(), t[0], t[1], t[2]))
            .collect::<String>();
        s += "$EndElements\n";
    }
    s.into_bytes()
}

fn msh_target() -> Target {
    Target {
        name: "msh",
        seeds: msh_seeds(),
        dict: dict(&[
            "$MeshFormat\n",
            "$EndMeshFormat\n",
            "$Nodes\n",
            "$EndNodes\n",
            "$Elements\n",
            "$EndElements\n",
            "$PhysicalNames\n",
            "$EndPhysicalNames\n",
            "$Entities\n",
            "$EndEntities\n",
            "$Comments\n",
            "4.1 0 8\n",
            "2.2 0 8\n",
            "2.2 1 8\n",
            " 2 ",
            " 15 ",
            " 1 ",
            " 9 ",
            "\"",
            "\n",
        ]),
        generate: Some(generate_msh),
        mutate: None,
        check: check_msh,
        cases: 1000,
    }
}

// ---------------------------------------------------------------------------------------------
// Gmsh MSH with tetrahedra (issue 35: overlapping and cracked meshes)

/// Tetrahedral mesh limits for the 3D parser.
const PARSE_LIMITS_3D: TetMeshLimits = TetMeshLimits { max_nodes: 20_000, max_tets: 120_000 };

/// The 3D seeds: the shipped brachytherapy mesh, and the validation cube when present.
fn msh3d_seeds() -> Vec<Vec<u8>> {
    let mut seeds = vec![std::fs::read(repo().join("server/scenes/brachy-3d.msh")).expect("server/scenes/brachy-3d.msh")];
    let shared = validation_dir().join("meshes");
    for name in ["cube_sphere_v41.msh", "cube_sphere_v22.msh"] {
        if let Ok(b) = std::fs::read(shared.join(name)) {
            seeds.push(b);
        }
    }
    seeds
}

/// Whether the interior of tetrahedron `p` holds `x` (every barycentric weight above 1e-9).
fn strictly_inside(p: [[f64; 3]; 4], x: [f64; 3]) -> bool {
    let vol = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| {
        let (u, v, w) = ([0, 1, 2].map(|k| b[k] - a[k]), [0, 1, 2].map(|k| c[k] - a[k]), [0, 1, 2].map(|k| d[k] - a[k]));
        u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
    };
    let v = vol(p[0], p[1], p[2], p[3]);
    let w = [vol(x, p[1], p[2], p[3]), vol(p[0], x, p[2], p[3]), vol(p[0], p[1], x, p[3]), vol(p[0], p[1], p[2], x)];
    w.iter().all(|wi| wi / v > 1e-9)
}

/// An accepted 3D mesh must be conforming, checked here independently of the parser's own
/// checks: no two nodes within 1e-9 of the bounding-box diagonal (brute force; exact repeats by
/// sorting on large meshes), no face in more than two tetrahedra, and (on meshes up to 1,500
/// tetrahedra, brute force) no tetrahedron's centroid inside another.
fn conforming(mesh: &TetMesh) -> Verdict {
    let (nodes, tets) = (mesh.nodes_m(), mesh.tets());
    let (lo, hi) = mesh.bounding_box_m();
    let tol = 1e-9 * (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let d2 = |a: [f64; 3], b: [f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>();
    if nodes.len() <= 2_000 {
        for i in 0..nodes.len() {
            if let Some(j) = (i + 1..nodes.len()).find(|&j| d2(nodes[i], nodes[j]) <= tol * tol) {
                return Err(format!("accepted a mesh with nodes {i} and {j} at the same place (a crack)"));
            }
        }
    } else {
        let mut sorted: Vec<[u64; 3]> = nodes.iter().map(|p| p.map(f64::to_bits)).collect();
        sorted.sort_unstable();
        if sorted.windows(2).any(|w| w[0] == w[1]) {
            return Err("accepted a mesh with two nodes at the same place (a crack)".into());
        }
    }
    let mut faces = std::collections::HashMap::<[usize; 3], usize>::new();
    for t in tets {
        for skip in 0..4 {
            let mut f: Vec<usize> = (0..4).filter(|&k| k != skip).map(|k| t[k]).collect();
            f.sort_unstable();
            *faces.entry([f[0], f[1], f[2]]).or_default() += 1;
        }
    }
    if let Some((f, n)) = faces.iter().find(|(_, n)| **n > 2) {
        return Err(format!("accepted a mesh whose face {f:?} belongs to {n} tetrahedra"));
    }
    if tets.len() <= 1_500 {
        for a in 0..tets.len() {
            let p = mesh.tet_points_m(a);
            let c = [0, 1, 2].map(|k| p.iter().map(|q| q[k]).sum::<f64>() / 4.0);
            if let Some(b) = (0..tets.len()).find(|&b| b != a && strictly_inside(mesh.tet_points_m(b), c)) {
                return Err(format!("accepted overlapping tetrahedra {a} and {b} (the centroid of {a} lies inside {b})"));
            }
        }
    }
    Ok(())
}

fn check_msh3d(input: &[u8]) -> Verdict {
    verdict(needlesim_core::msh::parse_msh3d(&fuzz::text(input), &PARSE_LIMITS_3D), |m| {
        let mesh = &m.mesh;
        let n = mesh.n_nodes();
        if n == 0 || mesh.n_tets() == 0 || m.node_tags.len() != n || m.element_tags.len() != mesh.n_tets() {
            return Err(format!("accepted a mesh of {n} nodes, {} tetrahedra, {} tags", mesh.n_tets(), m.node_tags.len()));
        }
        if !mesh.nodes_m().iter().all(|p| finite(p)) || mesh.tets().iter().flatten().any(|&i| i >= n) {
            return Err("accepted a mesh with a non-finite node or a dangling tetrahedron".into());
        }
        if (0..mesh.n_tets()).any(|t| mesh.volume_m3(t).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)) {
            return Err("accepted a tetrahedron that is not positive".into());
        }
        conforming(mesh)
    })
}

/// A small box of tetrahedra (`nx × ny × nz` nodes, 1 cm apart, 6 positive tetrahedra per cell,
/// a physical volume), in MSH 2.2 or 4.1, sometimes made non-conforming the ways issue 35 found:
/// a tetrahedron overlapping others (of new nodes inside a cell, or on an outer face reaching
/// inwards), or a crack (the tetrahedra on one side of a grid plane given their own copies of its
/// nodes, coincident or within round-off). Counts are sometimes wrong, as in [`generate_msh`].
fn generate_msh3d(rng: &mut SmallRng) -> Vec<u8> {
    let n = [rng.random_range(2..5usize), rng.random_range(2..5usize), rng.random_range(2..5usize)];
    let grid = BoxGridParams::new(n, n.map(|k| (k - 1) as f64 * 0.01));
    let node = |i: usize, j: usize, k: usize| grid.node(i, j, k);
    let boxed = grid.build(&TetMeshLimits::default()).expect("a small box grid");
    let (mut xyz, mut tets) = (boxed.nodes_m().to_vec(), boxed.tets().to_vec());
    match rng.random_range(0..6) {
        // A small tetrahedron of new nodes inside the first cell.
        0 => {
            let b = xyz.len();
            xyz.extend([[0.002, 0.001, 0.001], [0.005, 0.001, 0.001], [0.002, 0.004, 0.001], [0.002, 0.001, 0.004]]);
            tets.push([b, b + 1, b + 2, b + 3]);
        }
        // On the bottom face (0,0,0), (1,0,0), (1,1,0), reaching the top corner of the grid.
        1 => tets.push([node(0, 0, 0), node(1, 0, 0), node(1, 1, 0), node(1, 1, n[2] - 1)]),
        // A crack along the plane i = 1 (when there is a cell beyond it).
        2 | 3 if n[0] >= 3 => {
            let near = rng.random_bool(0.5);
            let mut copy = std::collections::BTreeMap::new();
            for t in tets.iter_mut() {
                if t.iter().any(|&v| v % n[0] >= 2) {
                    for v in t.iter_mut().filter(|v| **v % n[0] == 1) {
                        *v = *copy.entry(*v).or_insert_with(|| {
                            let mut p = xyz[*v];
                            if near {
                                p[1] += 1e-13;
                            }
                            xyz.push(p);
                            xyz.len() - 1
                        });
                    }
                }
            }
        }
        _ => {}
    }
    for t in tets.iter_mut() {
        if signed_volume_m3(xyz[t[0]], xyz[t[1]], xyz[t[2]], xyz[t[3]]) < 0.0 {
            t.swap(2, 3);
        }
    }
    let v4 = rng.random_bool(0.5);
    let n_nodes = xyz.len();
    let mut s = format!("$MeshFormat\n{} 0 8\n$EndMeshFormat\n", if v4 { "4.1" } else { "2.2" });
    s += &format!("$PhysicalNames\n{}\n3 1 \"tissue\"\n$EndPhysicalNames\n", count(rng, 1));
    let line = |p: &[f64; 3]| format!("{} {} {}\n", p[0], p[1], p[2]);
    if v4 {
        s += &format!("$Entities\n0 0 0 {}\n1 0 0 0 0.03 0.03 0.03 1 1 0\n$EndEntities\n", count(rng, 1));
        s += &format!("$Nodes\n1 {} 1 {n_nodes}\n3 1 0 {}\n", count(rng, n_nodes), count(rng, n_nodes));
        s += &(1..=n_nodes).map(|k| format!("{k}\n")).collect::<String>();
        s += &xyz.iter().map(line).collect::<String>();
        s += "$EndNodes\n";
        s += &format!("$Elements\n1 {} 1 {}\n3 1 4 {}\n", count(rng, tets.len()), tets.len(), count(rng, tets.len()));
        s += &tets
            .iter()
            .enumerate()
            .map(|(e, t)| format!("{} {} {} {} {}\n", e + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1))
            .collect::<String>();
        s += "$EndElements\n";
    } else {
        s += &format!("$Nodes\n{}\n", count(rng, n_nodes));
        s += &xyz.iter().enumerate().map(|(k, p)| format!("{} {}", k + 1, line(p))).collect::<String>();
        s += "$EndNodes\n";
        s += &format!("$Elements\n{}\n", count(rng, tets.len()));
        s += &tets
            .iter()
            .enumerate()
            .map(|(e, t)| format!("{} 4 2 1 1 {} {} {} {}\n", e + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1))
            .collect::<String>();
        s += "$EndElements\n";
    }
    s.into_bytes()
}

fn msh3d_target() -> Target {
    Target {
        name: "msh3d",
        seeds: msh3d_seeds(),
        dict: dict(&[
            "$Nodes\n",
            "$EndNodes\n",
            "$Elements\n",
            "$EndElements\n",
            "$PhysicalNames\n",
            "$EndPhysicalNames\n",
            "$Entities\n",
            "4.1 0 8\n",
            "2.2 0 8\n",
            " 4 ",
            " 2 ",
            " 3 ",
            "\n",
        ]),
        generate: Some(generate_msh3d),
        mutate: None,
        check: check_msh3d,
        cases: 200,
    }
}

// ---------------------------------------------------------------------------------------------
// Scene TOML

/// The folder scenes' `mesh.file` is resolved against: the core's test meshes.
fn scene_base_dir() -> PathBuf {
    repo().join("server/core/testdata")
}

fn num(rng: &mut SmallRng, typical: f64) -> String {
    if rng.random_bool(0.8) { format!("{}", typical * rng.random_range(0.5..2.0)) } else { pick_extreme(rng) }
}

fn pick_extreme(rng: &mut SmallRng) -> String {
    ["0", "-1", "1e308", "-1e308", "nan", "inf", "-inf", "-0.0", "1e-300", "18446744073709551615", "\"x\"", "[]", "true"]
        [rng.random_range(0..13)]
    .to_owned()
}

fn int(rng: &mut SmallRng, lo: u64, hi: u64) -> String {
    if rng.random_bool(0.85) { rng.random_range(lo..=hi).to_string() } else { pick_extreme(rng) }
}

/// A scene from the TOML grammar of `scene.rs`: valid values mostly, an extreme now and then,
/// optional keys present or not.
fn generate_scene(rng: &mut SmallRng) -> Vec<u8> {
    let mut s = String::new();
    let mut opt = |rng: &mut SmallRng, line: String| {
        if rng.random_bool(0.5) {
            s.push_str(&line);
            s.push('\n');
        }
    };
    opt(rng, "name = \"generated\"".into());
    let tick = num(rng, 1000.0);
    opt(rng, format!("tick_rate_hz = {tick}"));
    let fixed = ["\"bottom\"", "\"top\", \"left\"", "\"nope\"", ""][rng.random_range(0..4)];
    opt(rng, format!("fixed = [{fixed}]"));
    let fixed_nodes = (0..rng.random_range(0..4)).map(|_| int(rng, 0, 500)).collect::<Vec<_>>().join(", ");
    opt(rng, format!("fixed_nodes = [{fixed_nodes}]"));
    let n_regions = rng.random_range(0..4);
    let mut body = String::new();
    if rng.random_bool(0.8) {
        let (nx, ny, w, h) = (int(rng, 0, 30), int(rng, 0, 30), num(rng, 0.1), num(rng, 0.1));
        body += &format!("[mesh]\ntype = \"grid\"\nnx = {nx}\nny = {ny}\nwidth_m = {w}\nheight_m = {h}\n");
        if rng.random_bool(0.3) {
            body += &format!("origin_m = [{}, {}]\n", num(rng, 0.01), num(rng, 0.01));
        }
        if rng.random_bool(0.3) {
            body += ["pattern = \"right\"\n", "pattern = \"alternate\"\n", "pattern = \"zigzag\"\n"][rng.random_range(0..3)];
        }
    } else {
        let file = ["inclusion_v22.msh", "inclusion_v41.msh", "missing.msh", ""][rng.random_range(0..4)];
        body += &format!("[mesh]\ntype = \"msh\"\nfile = \"{file}\"\n");
    }
    if rng.random_bool(0.6) {
        let model = ["stress", "strain", "shear"][rng.random_range(0..3)];
        body += &format!("[plane]\nmodel = \"{model}\"\nthickness_m = {}\n", num(rng, 0.01));
    }
    let names = ["tissue", "inclusion", "background", "physical1", "default"];
    for i in 0..n_regions {
        let name = names[rng.random_range(0..names.len())];
        body += &format!("[[regions]]\nname = \"{name}\"\nyoung_modulus_pa = {}\npoisson_ratio = {}\n", num(rng, 30e3), num(rng, 0.3));
        for key in
            ["friction_n_per_m", "static_friction_ratio", "tip_peak_ratio", "tip_peak_width_m", "puncture_force_n", "cutting_force_n"]
        {
            if rng.random_bool(0.3) {
                body += &format!("{key} = {}\n", num(rng, 0.5));
            }
        }
        if i > 0 || rng.random_bool(0.1) {
            body += &format!("disc = {{ center_m = [{}, {}], radius_m = {} }}\n", num(rng, 0.05), num(rng, 0.05), num(rng, 0.02));
        }
    }
    body += &format!("[needle]\nlength_m = {}\nbase = [{}, {}, {}]\n", num(rng, 0.1), num(rng, 0.05), num(rng, 0.2), num(rng, -1.57));
    if rng.random_bool(0.4) {
        body += "model = \"flexible\"\n";
        for (key, v) in [("gauge", int(rng, 15, 26)), ("n_links", int(rng, 0, 64)), ("bevel_force_ratio", num(rng, 0.5))] {
            if rng.random_bool(0.4) {
                body += &format!("{key} = {v}\n");
            }
        }
        if rng.random_bool(0.2) {
            body += &format!("flexural_rigidity_nm2 = {}\n", num(rng, 0.01));
        }
        if rng.random_bool(0.3) {
            body += &format!("bevel_side = {}\n", num(rng, 1.0));
        }
    }
    if rng.random_bool(0.3) {
        body += &format!("capture_radius_m = {}\n", num(rng, 0.002));
    }
    if rng.random_bool(0.3) {
        body += &format!("max_nodes = {}\n", int(rng, 0, 1000));
    }
    for _ in 0..rng.random_range(0..3) {
        body +=
            &format!("[[targets]]\nname = \"t\"\ncenter_m = [{}, {}]\nradius_m = {}\n", num(rng, 0.05), num(rng, 0.05), num(rng, 0.002));
    }
    if rng.random_bool(0.3) {
        body += &format!(
            "[limits]\nmax_base_step_m = {}\nmax_base_step_rad = {}\nmax_active_set_iterations = {}\nlookahead_m = {}\n",
            num(rng, 0.002),
            num(rng, 0.05),
            int(rng, 0, 100),
            num(rng, 0.01)
        );
    }
    s.push_str(&body);
    s.into_bytes()
}

fn check_scene(input: &[u8]) -> Verdict {
    verdict(needlesim_scene::parse_scene(&fuzz::text(input), &scene_base_dir(), &SOLVE_LIMITS), |scene| {
        let n = scene.tissue.mesh().n_nodes();
        if n == 0 || scene.fixed_nodes.iter().any(|&i| i >= n) {
            return Err(format!("accepted a scene of {n} nodes with fixed nodes {:?}", scene.fixed_nodes));
        }
        if scene.params.regions.len() != scene.tissue.mesh().region_names().len() {
            return Err("accepted a scene whose needle parameters do not match its regions".into());
        }
        // What a session then does with it: a simulation, or an error naming the bad parameter.
        verdict(needlesim_core::Simulation::new(scene.tissue.clone(), scene.params.clone()), |_| Ok(()))
    })
}

fn scene_target() -> Target {
    let mut seeds = files(&repo().join("server/scenes"), "toml");
    seeds.extend(files(&repo().join("server/identify-example"), "toml"));
    // A scene with an MSH mesh, resolved against scene_base_dir().
    let inclusion = "[mesh]\ntype = \"msh\"\nfile = \"inclusion_v41.msh\"\n\n[[regions]]\nname = \"background\"\nyoung_modulus_pa = 20e3\n\
                     poisson_ratio = 0.45\n\n[[regions]]\nname = \"inclusion\"\nyoung_modulus_pa = 80e3\npoisson_ratio = 0.45\n\n\
                     [needle]\nlength_m = 0.1\nbase = [0.05, 0.2, -1.5707963267948966]\n";
    seeds.push(inclusion.as_bytes().to_vec());
    Target {
        name: "scene",
        seeds,
        dict: dict(&[
            "[mesh]\n",
            "[[regions]]\n",
            "[needle]\n",
            "[[targets]]\n",
            "[limits]\n",
            "[plane]\n",
            "type = \"msh\"\n",
            "file = \"inclusion_v22.msh\"\n",
            "model = \"flexible\"\n",
            "n_links = 100000000000\n",
            "max_nodes = 18446744073709551615\n",
            "gauge = 17\n",
            "disc = { center_m = [0.05, 0.05], radius_m = 0.01 }\n",
            "fixed_nodes = [0, 1, 99999999999]\n",
            " = ",
            "\"",
            "[",
            "]",
            "\n",
        ]),
        generate: Some(generate_scene),
        mutate: None,
        check: check_scene,
        cases: 500,
    }
}

// ---------------------------------------------------------------------------------------------
// Trajectory CSV (three readers)

fn traj_seeds() -> Vec<Vec<u8>> {
    let mut seeds = files(&repo().join("server/scenes"), "csv");
    seeds.push(std::fs::read(repo().join("server/identify-example/insertion.csv")).unwrap());
    seeds.push(b"t_s,x_m,y_m,theta_rad\n# a comment\n0, 0, 1, 0\n\n2,2 ,3,1\n".to_vec());
    seeds
}

/// A trajectory CSV from its grammar: a header (usually right), rows of 3–5 fields with times
/// that mostly increase, comments, blank lines, quotes and extremes now and then.
fn generate_traj(rng: &mut SmallRng) -> Vec<u8> {
    let header =
        ["t_s,x_m,y_m,theta_rad", "t_s, x_m ,y_m,theta_rad", "x_m,t_s,y_m,theta_rad", "t_s,x_m,y_m", "", "# c\nt_s,x_m,y_m,theta_rad"];
    let mut s = header[if rng.random_bool(0.8) { 0 } else { rng.random_range(0..header.len()) }].to_owned();
    s.push('\n');
    let mut t = rng.random_range(-1.0..1.0);
    for _ in 0..rng.random_range(0..40) {
        match rng.random_range(0..20) {
            0 => s.push_str("# comment, with, commas\n"),
            1 => s.push('\n'),
            2 => s.push_str("\"1\",\"2\",\"3\",\"4\"\n"),
            _ => {
                t += if rng.random_bool(0.95) { rng.random_range(0.0..1.0) } else { -1.0 };
                let n_fields = if rng.random_bool(0.95) { 4 } else { rng.random_range(0..7) };
                let fields: Vec<String> = (0..n_fields).map(|k| if k == 0 { format!("{t}") } else { num(rng, 0.05) }).collect();
                s.push_str(&fields.join(if rng.random_bool(0.9) { "," } else { " , " }));
                s.push_str(if rng.random_bool(0.9) { "\n" } else { "\r\n" });
            }
        }
    }
    s.into_bytes()
}

fn traj_dict() -> Vec<Vec<u8>> {
    dict(&["t_s,x_m,y_m,theta_rad\n", ",", "\"", "#", "\n", "\r", "NaN", "inf", "1e999", " "])
}

fn traj_target(name: &'static str, check: fn(&[u8]) -> Verdict) -> Target {
    Target { name, seeds: traj_seeds(), dict: traj_dict(), generate: Some(generate_traj), mutate: None, check, cases: 1000 }
}

/// A trajectory the parser accepted: samples at strictly increasing finite times, finite poses.
fn valid_samples<P>(samples: &[(f64, P)], pose: fn(&P) -> [f64; 3]) -> Verdict {
    let t: Vec<f64> = samples.iter().map(|s| s.0).collect();
    let poses: Vec<f64> = samples.iter().flat_map(|(_, p)| pose(p)).collect();
    if t.is_empty() || !strictly_increasing(&t) || !finite(&t) || !finite(&poses) {
        return Err(format!("accepted a trajectory of {} samples whose times are {t:?}", t.len()));
    }
    Ok(())
}

/// The one trajectory parser (needlesim-trajectory), which the scene, the CLI and the device
/// bridge all use.
fn check_traj(input: &[u8]) -> Verdict {
    verdict(needlesim_trajectory::Trajectory::parse_csv(&fuzz::text(input)), |tr| {
        valid_samples(&tr.samples, |p| [p.x_m, p.y_m, p.theta_rad])?;
        let (t0, t1) = tr.span_s();
        let (q, v) = tr.pose_and_velocity_at(0.5 * (t0 + t1));
        if !(finite(&[q.x_m, q.y_m, q.theta_rad]) && [v.x_m, v.y_m, v.theta_rad].iter().all(|x| !x.is_nan())) {
            return Err(format!("accepted a trajectory sampling to {q:?}, {v:?}"));
        }
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------
// Exchange JSON

fn check_exchange(input: &[u8]) -> Verdict {
    let parsed = serde_json::from_str::<Scenario>(&fuzz::text(input)).map_err(anyhow::Error::from).and_then(|sc| {
        let (mesh, _) = sc.mesh_and_materials(&SOLVE_LIMITS)?;
        sc.static_problem(mesh.n_nodes())?;
        // What `solve` then does with it; a singular problem is an error, not a panic.
        solve_scenario(&sc, &SOLVE_LIMITS)
    });
    verdict(parsed, |r| {
        let flat: Vec<f64> = r.displacements.iter().flatten().copied().collect();
        if r.displacements.len() != r.n_nodes || !finite(&flat) {
            return Err(format!(
                "accepted a scenario whose solution has {} displacements for {} nodes, finite: {}",
                r.displacements.len(),
                r.n_nodes,
                finite(&flat)
            ));
        }
        Ok(())
    })
}

fn exchange_target() -> Target {
    let dir = validation_dir().join("scenarios");
    assert!(dir.is_dir(), "no validation scenarios at {} (set NEEDLESIM_VALIDATION)", dir.display());
    Target {
        name: "exchange",
        seeds: files(&dir, "json"),
        dict: dict(&[
            "\"E_elem\": [1, 2],",
            "\"nu_elem\": [0.3],",
            "\"prescribed_local\": [{\"node\": 0, \"angle_rad\": 1e308, \"ut\": 0}],",
            "\"loads\": [{\"node\": -1}],",
            "\"working_nodes\": [0, 99999999999],",
            "\"plane\": \"stress\",",
            "\"thickness\": 0,",
            "null",
            "[",
            "]",
            "{",
            "}",
            ",",
            "\"",
        ]),
        generate: None,
        mutate: None,
        check: check_exchange,
        cases: 400,
    }
}

// ---------------------------------------------------------------------------------------------
// Marker-track CSV

fn generate_tracks(rng: &mut SmallRng) -> Vec<u8> {
    let mut s = String::from("frame,t_s,marker,x_px,y_px,x_m,y_m,detected\n");
    let (frames, markers) = (rng.random_range(0..5), rng.random_range(1..5));
    for f in 0..frames {
        let t = f as f64 * 0.1;
        for m in 0..markers {
            let det = if rng.random_bool(0.9) { "1" } else { ["0", "2", "", "true"][rng.random_range(0..4)] };
            s += &format!("{f},{t},{m},{},{},{},{},{det}\n", num(rng, 100.0), num(rng, 100.0), num(rng, 0.01), num(rng, 0.01));
        }
    }
    s.into_bytes()
}

fn check_tracks(input: &[u8]) -> Verdict {
    verdict(MarkerTracks::from_csv(&fuzz::text(input)), |t| {
        let n = t.n_frames() * t.n_markers;
        if t.n_markers == 0 || t.positions_px.len() != n || t.positions_m.len() != n || t.detected.len() != n {
            return Err(format!(
                "accepted tracks of {} frames × {} markers with {} positions",
                t.n_frames(),
                t.n_markers,
                t.positions_px.len()
            ));
        }
        if !strictly_increasing(&t.times_s) || !finite(&t.times_s) {
            return Err(format!("accepted tracks whose times are {:?}", t.times_s));
        }
        // What it wrote reads back the same.
        match MarkerTracks::from_csv(&t.to_csv()) {
            Ok(back) if back == *t => Ok(()),
            other => Err(format!("accepted tracks that do not read back from their CSV: {other:?}")),
        }
    })
}

fn tracks_target() -> Target {
    Target {
        name: "tracks",
        seeds: files(&repo().join("server/identify-example"), "csv").into_iter().filter(|s| s.starts_with(b"frame,t_s,marker")).collect(),
        dict: dict(&["frame,t_s,marker,x_px,y_px,x_m,y_m,detected\n", ",", ",1\n", ",0\n", "\n"]),
        generate: Some(generate_tracks),
        mutate: None,
        check: check_tracks,
        cases: 1000,
    }
}

// ---------------------------------------------------------------------------------------------
// Identification logs: probe log and needle force log CSV (one numeric-CSV reader)

/// A log the parser accepted: strictly increasing finite times, finite values, and the CSV it
/// writes reads back the same.
fn valid_log<L: PartialEq + std::fmt::Debug>(log: &L, times_s: &[f64], values: Vec<f64>, back: anyhow::Result<L>) -> Verdict {
    if times_s.is_empty() || !strictly_increasing(times_s) || !finite(times_s) || !finite(&values) {
        return Err(format!("accepted a log whose times are {times_s:?}"));
    }
    match back {
        Ok(back) if back == *log => Ok(()),
        other => Err(format!("accepted a log that does not read back from its CSV: {other:?}")),
    }
}

fn check_logs(input: &[u8]) -> Verdict {
    let text = fuzz::text(input);
    verdict(ProbeLog::from_csv(&text), |log| {
        let values = log.disp_m.iter().chain(&log.force_n).flatten().copied().collect();
        valid_log(log, &log.times_s, values, ProbeLog::from_csv(&log.to_csv()))
    })?;
    verdict(ForceLog::from_csv(&text), |log| {
        let values = log.force_n.iter().flatten().chain(&log.depth_m).copied().collect();
        valid_log(log, &log.times_s, values, ForceLog::from_csv(&log.to_csv()))
    })
}

fn logs_target() -> Target {
    let dir = repo().join("server/identify-example");
    Target {
        name: "identify-logs",
        seeds: ["probe-log.csv", "needle-force.csv"].iter().map(|f| std::fs::read(dir.join(f)).unwrap()).collect(),
        dict: dict(&["t_s,probe_disp_x_m,probe_disp_y_m,force_x_n,force_y_n\n", "t_s,force_x_n,force_y_n,depth_m\n", ",", "#", "\n"]),
        generate: None,
        mutate: None,
        check: check_logs,
        cases: 1000,
    }
}

// ---------------------------------------------------------------------------------------------
// PNG frames

/// A phantom frame, 96 × 96 8-bit gray levels: 3 × 3 dark dots of radius 3 px on a lit
/// background, offset by `shift_px`.
fn phantom_frame(shift_px: f64) -> Vec<u8> {
    (0..96u32)
        .flat_map(|y| (0..96u32).map(move |x| (x, y)))
        .map(|(x, y)| {
            let near = (0..9).any(|k| {
                let (cx, cy) = (24.0 + 24.0 * f64::from(k % 3) + shift_px, 24.0 + 24.0 * f64::from(k / 3));
                (f64::from(x) - cx).hypot(f64::from(y) - cy) <= 3.0
            });
            if near { 40 } else { 200 }
        })
        .collect()
}

/// A 96 × 96 PNG of colour type `color` and bit depth `depth` holding `samples` (big-endian
/// 16-bit samples when `depth` is 16).
fn png(color: png::ColorType, depth: png::BitDepth, samples: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, 96, 96);
    encoder.set_color(color);
    encoder.set_depth(depth);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(samples).unwrap();
    writer.finish().unwrap();
    out
}

/// Frame 0, unmutated: the reference the mutated frame is tracked against.
fn first_frame() -> &'static [u8] {
    static FRAME: OnceLock<Vec<u8>> = OnceLock::new();
    FRAME.get_or_init(|| png(png::ColorType::Grayscale, png::BitDepth::Eight, &phantom_frame(0.0)))
}

/// The shifted frame as 8-bit gray, 8-bit RGB, 16-bit gray and 16-bit RGBA (opaque).
fn png_seeds() -> Vec<Vec<u8>> {
    use png::{BitDepth, ColorType};
    let g = phantom_frame(1.0);
    let wide = |v: u8| (u16::from(v) * 257).to_be_bytes();
    vec![
        png(ColorType::Grayscale, BitDepth::Eight, &g),
        png(ColorType::Rgb, BitDepth::Eight, &g.iter().flat_map(|&v| [v, v, v]).collect::<Vec<u8>>()),
        png(ColorType::Grayscale, BitDepth::Sixteen, &g.iter().flat_map(|&v| wide(v)).collect::<Vec<u8>>()),
        png(ColorType::Rgba, BitDepth::Sixteen, &g.iter().flat_map(|&v| [v, v, v, 255].into_iter().flat_map(wide)).collect::<Vec<u8>>()),
    ]
}

/// PNG chunks as (start, end) byte ranges of whole chunks (length, type, data, CRC).
fn png_chunks(data: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut at = 8;
    while at + 12 <= data.len() {
        let len = u32::from_be_bytes(data[at..at + 4].try_into().unwrap()) as usize;
        let end = at.saturating_add(12).saturating_add(len);
        if end > data.len() {
            break;
        }
        out.push((at, end));
        at = end;
    }
    out
}

/// Recomputes a chunk's length and CRC after its data changed, so the decoder reads it.
fn fix_chunk(data: &mut Vec<u8>, start: usize, new_data: Vec<u8>, end: usize) {
    let kind = data[start + 4..start + 8].to_vec();
    let mut chunk = (new_data.len() as u32).to_be_bytes().to_vec();
    chunk.extend_from_slice(&kind);
    chunk.extend_from_slice(&new_data);
    chunk.extend_from_slice(&crc32fast::hash(&chunk[4..]).to_be_bytes());
    data.splice(start..end, chunk);
}

/// Chunk-aware PNG mutations: header fields set to extremes, chunk data mutated, chunks removed
/// or repeated — each with a valid CRC, so the decoder gets past the checksum.
fn mutate_png(rng: &mut SmallRng, data: &mut Vec<u8>) {
    let chunks = png_chunks(data);
    let Some(&(a, b)) = chunks.get(rng.random_range(0..chunks.len().max(1))) else { return };
    let mut body = data[a + 8..b - 4].to_vec();
    match rng.random_range(0..4) {
        0 if &data[a + 4..a + 8] == b"IHDR" && body.len() == 13 => {
            let dims = [0u32, 1, 2, 95, 97, 1000, 65_535, 100_000, 1 << 24, i32::MAX as u32, u32::MAX];
            match rng.random_range(0..4) {
                0 => body[0..4].copy_from_slice(&dims[rng.random_range(0..dims.len())].to_be_bytes()),
                1 => body[4..8].copy_from_slice(&dims[rng.random_range(0..dims.len())].to_be_bytes()),
                2 => body[8] = [1, 2, 4, 8, 16, 3, 0][rng.random_range(0..7)],
                _ => body[9 + rng.random_range(0..4)] = rng.random_range(0..8),
            }
            fix_chunk(data, a, body, b);
        }
        0 | 1 => {
            fuzz::mutate(rng, &mut body, &[], &[]);
            fix_chunk(data, a, body, b);
        }
        2 => {
            data.drain(a..b);
        }
        _ => {
            let chunk = data[a..b].to_vec();
            data.splice(b..b, chunk);
        }
    }
}

fn check_png(input: &[u8]) -> Verdict {
    let params = TrackParams::new(Polarity::Dark, Scale::MetresPerPixel { m_per_px: 1e-4, origin_px: [0.0, 0.0], origin_m: [0.0, 0.0] });
    let valid = |n_frames: usize| {
        move |t: &MarkerTracks| {
            let flat: Vec<f64> = t.positions_px.iter().chain(&t.positions_m).flatten().copied().collect();
            if t.n_frames() != n_frames || t.n_markers == 0 || !finite(&flat) {
                return Err(format!("tracked {} frames of {n_frames} with {} markers, positions {flat:?}", t.n_frames(), t.n_markers));
            }
            Ok(())
        }
    };
    // The mutated image as frame 0 (detection), then as frame 1 after a good frame 0 (tracking).
    verdict(track_png_bytes(&[(0.0, input)], &params, &mut needlesim_identify::no_progress), valid(1))?;
    verdict(track_png_bytes(&[(0.0, first_frame()), (0.1, input)], &params, &mut needlesim_identify::no_progress), valid(2))
}

fn png_target() -> Target {
    Target {
        name: "png",
        seeds: png_seeds(),
        dict: dict(&["IHDR", "IDAT", "IEND", "PLTE", "tRNS"]),
        generate: None,
        mutate: Some(mutate_png),
        check: check_png,
        cases: 300,
    }
}

// ---------------------------------------------------------------------------------------------
// Tests

fn all_targets() -> Vec<Target> {
    vec![
        msh_target(),
        msh3d_target(),
        scene_target(),
        traj_target("trajectory", check_traj),
        exchange_target(),
        tracks_target(),
        logs_target(),
        png_target(),
    ]
}

#[test]
fn issue_13_fuzz_msh() {
    msh_target().run_bounded();
}

#[test]
fn issue_35_fuzz_msh3d_with_overlaps_and_cracks() {
    msh3d_target().run_bounded();
}

#[test]
fn issue_13_fuzz_scene_toml() {
    scene_target().run_bounded();
}

#[test]
fn issue_13_fuzz_trajectory_csv() {
    traj_target("trajectory", check_traj).run_bounded();
}

#[test]
fn issue_13_fuzz_exchange_json() {
    exchange_target().run_bounded();
}

#[test]
fn issue_13_fuzz_marker_tracks_csv() {
    tracks_target().run_bounded();
}

#[test]
fn issue_13_fuzz_identify_logs_csv() {
    logs_target().run_bounded();
}

#[test]
fn issue_13_fuzz_png_frames() {
    png_target().run_bounded();
}

/// The long run, on demand: every parser (or those named in `NEEDLESIM_FUZZ_TARGETS`, comma
/// separated) in turn on this one thread, `NEEDLESIM_FUZZ_SECONDS` (default 1800) of its CPU time each, printing
/// the cases per parser. Several processes with disjoint target lists use several cores.
#[test]
#[ignore = "long fuzzing run: NEEDLESIM_FUZZ_SECONDS=1800 cargo test -p needlesim-server --test fuzz_parsers -- --ignored --nocapture"]
fn fuzz_all_parsers_for_a_while() {
    let seconds: u64 = std::env::var("NEEDLESIM_FUZZ_SECONDS").map_or(1800, |s| s.parse().expect("NEEDLESIM_FUZZ_SECONDS: seconds"));
    let mut targets = all_targets();
    if let Ok(names) = std::env::var("NEEDLESIM_FUZZ_TARGETS") {
        let wanted: Vec<&str> = names.split(',').map(str::trim).collect();
        let known: Vec<&str> = targets.iter().map(|t| t.name).collect();
        assert!(wanted.iter().all(|w| known.contains(w)), "NEEDLESIM_FUZZ_TARGETS: {names}; the parsers are {}", known.join(","));
        targets.retain(|t| wanted.contains(&t.name));
    }
    // Each parser gets `seconds` of the one thread: the run takes seconds × parsers.
    let total = seconds * targets.len() as u64;
    let (failures, stats) = fuzz::run_for(&targets, Duration::from_secs(total));
    println!("fuzzing {} parser(s) for {seconds} s each ({total} s in all), base seed {:#x}:", targets.len(), fuzz::base_seed());
    for (t, s) in targets.iter().zip(&stats) {
        println!(
            "  {:<18} {:>9} cases, {:>8} accepted, peak {:>7.1} MB, slowest {:?} CPU",
            t.name,
            s.cases,
            s.accepted,
            s.peak_bytes as f64 / 1e6,
            s.slowest
        );
    }
    println!("  failures: {}", failures.len());
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}
