//! Issue 15 through the real server: a live session of a scene with the default contact (the
//! bevel-tip example: material points) holds the tissue at material points, says so in every
//! frame, and never computes a compliance column inside a tick.

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, connect, create_example_session, with_token};

#[tokio::test]
async fn issue_15_a_live_session_holds_the_tissue_at_material_points() {
    let _turn = needlesim_tests::REALTIME.lock().await;
    let server = ServerProcess::start(&[]);
    let ch = connect(&server).await;
    let created = create_example_session(&ch, "bevel-tip").await;
    let sid = created.session.clone().unwrap().session_id;
    let frame = insert_25mm_and_watch(&ch, &created, &sid, false).await;
    assert!(!frame.faulted, "{:?}", frame.fault);
    let contacts = &frame.needle_nodes;
    // 20 mm in the tissue at 2 mm spacing (at most one point per 3.3 mm grid triangle: ≥ 4).
    assert!(contacts.len() >= 4, "the needle holds the tissue at {} contacts", contacts.len());
    assert!(contacts.iter().all(|n| n.material_point), "every contact is a material point: {contacts:?}");
    assert!(frame.force_axial_n < 0.0, "the tissue resists the insertion: {} N", frame.force_axial_n);
    let stats = pb::session_service_client::SessionServiceClient::new(ch.clone())
        .get_stats(with_token(pb::GetSessionRequest { session_id: sid.clone() }, &created.observer_token))
        .await
        .unwrap()
        .into_inner();
    assert_eq!(stats.column_misses, 0, "no column computed inside a tick: {stats:?}");
    assert_eq!(stats.budget_exhausted_ticks, 0, "{stats:?}");
    // Issue 19: the working solver's hybrid matrix was checked for round-off drift and never
    // needed a rebuild.
    assert!(stats.hybrid_checks > 0 && stats.hybrid_rebuilds == 0, "{stats:?}");
}

/// Issue 19 through the real server: a live session of the shipped toughness phantom, whose
/// contacts are spread over the needle's width (patches of up to twelve nodes), holds the tissue
/// at patches, streams them (a tick record keeps a patch's three heaviest nodes) and the
/// displacement field drawn from them, and never computes a column inside a tick.
#[tokio::test]
async fn issue_19_a_live_session_holds_the_tissue_with_contact_patches() {
    let _turn = needlesim_tests::REALTIME.lock().await;
    let toml = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/paper-phantom-toughness.toml")).unwrap();
    assert!(toml.contains("spread_contact = true"));
    let server = ServerProcess::start(&[]);
    let ch = connect(&server).await;
    let created = needlesim_tests::create_toml_session(&ch, toml).await;
    let sid = created.session.clone().unwrap().session_id;
    let frame = insert_25mm_and_watch(&ch, &created, &sid, true).await;
    assert!(!frame.faulted, "{:?}", frame.fault);
    let contacts = &frame.needle_nodes;
    // 20 mm in the tissue, at most one contact per 5.6 mm grid triangle crossed: ≥ 3.
    assert!(contacts.len() >= 3, "the needle holds the tissue at {} contacts", contacts.len());
    assert!(contacts.iter().all(|n| n.material_point), "every contact is spread (not a node): {contacts:?}");
    assert!(frame.force_axial_n < 0.0, "the tissue resists the insertion: {} N", frame.force_axial_n);
    // The field drawn from the patches' nodes: finite, and the tissue around the shaft dragged
    // down (the 19² grid's node at the top centre, 0.05 m, 0.1 m: index 18 · 19 + 9).
    let u = &frame.node_displacement_m;
    assert_eq!(u.len(), 2 * 19 * 19);
    assert!(u.iter().all(|v| v.is_finite()));
    let top_centre = 18 * 19 + 9;
    assert!(u[2 * top_centre + 1] < -1e-4, "the entry is dragged down: {} m", u[2 * top_centre + 1]);
    let stats = pb::session_service_client::SessionServiceClient::new(ch.clone())
        .get_stats(with_token(pb::GetSessionRequest { session_id: sid.clone() }, &created.observer_token))
        .await
        .unwrap()
        .into_inner();
    assert_eq!(stats.column_misses, 0, "no column computed inside a tick: {stats:?}");
    assert!(!stats.faulted, "{stats:?}");
    assert!(!server.stderr.lock().unwrap().contains("panicked"));
}

/// Observes the session at 60 Hz (with every node's displacement when `displacements`), drives
/// the needle 25 mm down at 25 mm/s through SetPose (the tip starts 5 mm above the surface), and
/// returns the first frame from after the insertion (carrying the displacements, when asked).
async fn insert_25mm_and_watch(
    ch: &tonic::transport::Channel,
    created: &pb::CreateSessionResponse,
    sid: &str,
    displacements: bool,
) -> pb::Frame {
    let mut observe = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let mut obs = observe
        .observe(with_token(
            pb::ObserveRequest { session_id: sid.to_owned(), rate_hz: 60.0, include_displacements: displacements },
            &created.observer_token,
        ))
        .await
        .unwrap()
        .into_inner();
    let mut control = pb::control_service_client::ControlServiceClient::new(ch.clone());
    for k in 1..=50 {
        let pose = pb::Pose2 { x_m: 0.05, y_m: 0.205 - 5e-4 * k as f64, theta_rad: -std::f64::consts::FRAC_PI_2 };
        control
            .set_pose(with_token(
                pb::SetPoseRequest { session_id: sid.to_owned(), base: Some(pose), client_id: String::new(), take_over: false },
                &created.controller_token,
            ))
            .await
            .unwrap();
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    let deadline = tokio::time::Instant::now() + std::time::Duration::from_secs(5);
    loop {
        assert!(tokio::time::Instant::now() < deadline, "no frame from after the insertion");
        let f = obs.message().await.expect("frames").expect("the stream goes on");
        if f.base.is_some_and(|b| b.y_m < 0.1801) && (!displacements || !f.node_displacement_m.is_empty()) {
            return f;
        }
    }
}
