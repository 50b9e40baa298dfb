//! Issue 35, item 9: overlapping and cracked tetrahedral meshes are refused, naming the problem,
//! by `needlesim-server simulate` (a 3D scene whose `.msh` has the defect) and by CreateSession
//! with `uploaded3d` (INVALID_ARGUMENT), while the same mesh without the defect runs.

use std::process::Command;

use needlesim_core::d3::mesh::signed_volume_m3;
use needlesim_core::d3::{BoxGridParams, TetMeshLimits};
use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, bin, connect, repo_root, run, text, with_token};
use tonic::Code;

/// Nodes per axis of the test cube (0.1 m, 3.3 cm cells, 162 tetrahedra).
const N: usize = 4;

fn node(i: usize, j: usize, k: usize) -> usize {
    i + N * (j + N * k)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Defect {
    None,
    /// A tetrahedron on the bottom face (0,0,0), (1,0,0), (1,1,0) reaching up to (1,1,2): it lies
    /// over the tetrahedron that already has that face.
    Overlap,
    /// The tetrahedra right of the plane x = 3.3 cm get their own copies of its nodes.
    Crack,
}

/// The cube as Gmsh MSH 2.2: positive tetrahedra (6 per cell) in physical volume 1 "gel", the
/// bottom face's triangles in physical surface 2 "bottom".
fn cube_msh(defect: Defect) -> String {
    let boxed = BoxGridParams::new([N; 3], [0.1; 3]).build(&TetMeshLimits::default()).expect("the cube");
    let (mut xyz, mut tets) = (boxed.nodes_m().to_vec(), boxed.tets().to_vec());
    match defect {
        Defect::None => {}
        Defect::Overlap => tets.push([node(0, 0, 0), node(1, 0, 0), node(1, 1, 0), node(1, 1, 2)]),
        Defect::Crack => {
            let mut copy = std::collections::BTreeMap::new();
            for t in tets.iter_mut() {
                if t.iter().any(|&v| v % N >= 2) {
                    for v in t.iter_mut().filter(|v| **v % N == 1) {
                        *v = *copy.entry(*v).or_insert_with(|| {
                            xyz.push(xyz[*v]);
                            xyz.len() - 1
                        });
                    }
                }
            }
        }
    }
    for t in tets.iter_mut() {
        if signed_volume_m3(xyz[t[0]], xyz[t[1]], xyz[t[2]], xyz[t[3]]) < 0.0 {
            t.swap(2, 3);
        }
    }
    let mut bottom = Vec::new();
    for j in 0..N - 1 {
        for i in 0..N - 1 {
            bottom.push([node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0)]);
            bottom.push([node(i, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0)]);
        }
    }
    let mut s = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 2 \"bottom\"\n3 1 \"gel\"\n$EndPhysicalNames\n");
    s += &format!("$Nodes\n{}\n", xyz.len());
    for (k, p) in xyz.iter().enumerate() {
        s += &format!("{} {} {} {}\n", k + 1, p[0], p[1], p[2]);
    }
    s += &format!("$EndNodes\n$Elements\n{}\n", bottom.len() + tets.len());
    for (e, t) in bottom.iter().enumerate() {
        s += &format!("{} 2 2 2 1 {} {} {}\n", e + 1, t[0] + 1, t[1] + 1, t[2] + 1);
    }
    for (e, t) in tets.iter().enumerate() {
        s += &format!("{} 4 2 1 1 {} {} {} {}\n", e + 1 + bottom.len(), t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
    s + "$EndElements\n"
}

/// The shipped cube phantom's TOML on the mesh file `msh`, without its trajectory.
fn scene_toml(msh: &str) -> String {
    let cube = std::fs::read_to_string(repo_root().join("server/scenes/cube-phantom-3d.toml")).unwrap();
    let start = cube.find("[mesh]").unwrap();
    let end = start + cube[start..].find("[[regions]]").unwrap();
    let toml = format!("{}[mesh]\ntype = \"msh\"\nfile = \"{msh}\"\n\n{}", &cube[..start], &cube[end..]);
    let toml = toml.replace("trajectory = \"cube-phantom-3d.csv\"\n", "");
    assert!(!toml.contains("trajectory") && toml.contains("fixed = [\"bottom\"]"), "{toml}");
    toml
}

/// What each defect's message must say.
fn expected(defect: Defect) -> &'static [&'static str] {
    match defect {
        Defect::None => &[],
        // Tetrahedron 162 (the added one) and the one below it that has the bottom face.
        Defect::Overlap => &["tetrahedra ", "and 162 (nodes [", "overlap"],
        Defect::Crack => &["nodes ", "coincide at", "crack"],
    }
}

#[test]
fn issue_35_simulate_refuses_a_3d_scene_whose_mesh_overlaps_or_is_cracked() {
    let dir = TempDir::new("meshes3d-simulate");
    // Down 20 mm from 5 mm above the top face (0.1 m), the needle pointing down.
    let traj = dir.join("down.csv");
    std::fs::write(&traj, "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0.05,0.05,0.205,0.7071067811865475,0,0.7071067811865475,0\n1,0.05,0.05,0.185,0.7071067811865475,0,0.7071067811865475,0\n").unwrap();
    for defect in [Defect::None, Defect::Overlap, Defect::Crack] {
        let name = format!("{defect:?}").to_lowercase();
        std::fs::write(dir.join(&format!("{name}.msh")), cube_msh(defect)).unwrap();
        let scene = dir.join(&format!("{name}.toml"));
        std::fs::write(&scene, scene_toml(&format!("{name}.msh"))).unwrap();
        let o = run(Command::new(bin("needlesim-server")).args(["simulate", "--scene"]).arg(&scene).arg("--trajectory").arg(&traj));
        let (out, err) = text(&o);
        assert!(!err.contains("panicked"), "{defect:?}: {err}");
        if defect == Defect::None {
            assert!(o.status.success(), "the cube without a defect runs: {err}");
            assert!(out.lines().count() > 100, "a time series: {out:.300}");
            continue;
        }
        assert!(!o.status.success(), "{defect:?}: simulate accepted the mesh:\n{err}");
        for part in expected(defect) {
            assert!(err.contains(part), "{defect:?}: the error names the problem ({part:?}): {err}");
        }
        assert!(err.contains(&format!("{name}.msh")), "{defect:?}: the error names the file: {err}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_35_uploaded3d_refuses_an_overlapping_or_cracked_mesh() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut c = pb::session_service_client::SessionServiceClient::new(ch.clone());
    for defect in [Defect::Overlap, Defect::Crack, Defect::None] {
        let req = pb::CreateSessionRequest {
            scene: Some(pb::SceneSource {
                source: Some(pb::scene_source::Source::Uploaded3d(pb::UploadedScene3d {
                    scene_toml: scene_toml("cube.msh"),
                    mesh_file_name: "cube.msh".into(),
                    mesh_text: cube_msh(defect),
                })),
            }),
            tick_rate_hz: 1000.0,
            record: false,
            device_channel: false,
        };
        let r = c.create_session(req).await;
        if defect == Defect::None {
            let created = r.expect("the cube without a defect makes a session").into_inner();
            let info = created.session.unwrap();
            assert_eq!((info.dimension, info.n_tetrahedra), (3, 162), "{info:?}");
            c.close_session(with_token(pb::CloseSessionRequest { session_id: info.session_id }, &created.controller_token)).await.unwrap();
            continue;
        }
        let e = r.expect_err("refused");
        assert_eq!(e.code(), Code::InvalidArgument, "{defect:?}: {e:?}");
        assert!(e.message().starts_with("scene.uploaded3d"), "{defect:?}: {}", e.message());
        for part in expected(defect) {
            assert!(e.message().contains(part), "{defect:?}: the error names the problem ({part:?}): {}", e.message());
        }
    }
}
