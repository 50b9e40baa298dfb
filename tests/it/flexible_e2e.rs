//! Issue 8 through the real binaries: the Fig. 4 steering example (`needlesim-server simulate
//! --scene fig4-steering`) hits its off-axis target where a straight insertion misses, and a
//! session with a bevel-tip needle streams the needle's bent shape and flips its bevel on the
//! FlipBevel call and on a Control message, while a symmetric needle refuses the flip.

use std::process::Command;

use needlesim_proto::v1 as pb;
use needlesim_tests::{ServerProcess, TempDir, bin, connect, create_example_session, run, text, with_token};

/// The last row of a `simulate` CSV as (column name → value).
fn last_row(csv: &str) -> std::collections::HashMap<String, f64> {
    let lines: Vec<&str> = csv.lines().filter(|l| !l.trim().is_empty()).collect();
    let header: Vec<&str> = lines.first().expect("a header").split(',').collect();
    let last = lines.get(1..).and_then(<[&str]>::last).expect("rows");
    header.iter().zip(last.split(',')).map(|(h, v)| ((*h).to_owned(), v.parse().expect("a number"))).collect()
}

#[test]
fn issue_8_fig4_steering_example_hits_where_straight_misses() {
    let dir = TempDir::new("fig4");
    let steered = dir.join("steered.csv");
    let out = run(Command::new(bin("needlesim-server")).args(["simulate", "--scene", "fig4-steering", "-o"]).arg(&steered));
    assert!(out.status.success(), "{}", text(&out).1);
    let s = last_row(&std::fs::read_to_string(&steered).unwrap());
    // Straight down to the same depth, no lateral step.
    let straight_traj = dir.join("straight.csv");
    std::fs::write(&straight_traj, "t_s,x_m,y_m,theta_rad\n0,0.05,0.205,-1.5707963267948966\n9,0.05,0.115,-1.5707963267948966\n").unwrap();
    let straight = dir.join("straight_out.csv");
    let out = run(Command::new(bin("needlesim-server"))
        .args(["simulate", "--scene", "fig4-steering", "--trajectory"])
        .arg(&straight_traj)
        .arg("-o")
        .arg(&straight));
    assert!(out.status.success(), "{}", text(&out).1);
    let t = last_row(&std::fs::read_to_string(&straight).unwrap());
    let radius = 0.0006;
    println!(
        "fig4-steering: steered tip {:.2} mm from the lesion (hit {}), straight {:.2} mm (hit {})",
        s["target_lesion_distance_m"] * 1e3,
        s["target_lesion_hit"],
        t["target_lesion_distance_m"] * 1e3,
        t["target_lesion_hit"]
    );
    assert!(s["target_lesion_distance_m"] < radius && s["target_lesion_hit"] == 1.0);
    assert!(t["target_lesion_distance_m"] > radius && t["target_lesion_hit"] == 0.0);
    // The steered tip ends on the other side of the axis from the base's step.
    assert!(s["x_m"] > 0.05 && s["tip_x_m"] < 0.05, "base x {} tip x {}", s["x_m"], s["tip_x_m"]);
}

/// The first frame (within 5 s) for which `pred` holds.
async fn frame_where(obs: &mut tonic::Streaming<pb::Frame>, pred: impl Fn(&pb::Frame) -> bool) -> Option<pb::Frame> {
    let deadline = tokio::time::Instant::now() + std::time::Duration::from_secs(5);
    while tokio::time::Instant::now() < deadline {
        let f = obs.message().await.expect("frames").expect("the stream goes on");
        if pred(&f) {
            return Some(f);
        }
    }
    None
}

#[tokio::test]
async fn issue_8_bevel_flips_over_grpc_and_the_shape_is_streamed() {
    let _turn = needlesim_tests::REALTIME.lock().await;
    let server = ServerProcess::start(&[]);
    let ch = connect(&server).await;
    let toml = std::fs::read_to_string(needlesim_tests::repo_root().join("server/scenes/fig4-steering.toml"))
        .unwrap()
        .replace("gauge = 22", "gauge = 22\nbevel_force_ratio = 0.3");
    let created = needlesim_tests::create_toml_session(&ch, toml).await;
    let sid = created.session.unwrap().session_id;
    let mut observe = pb::observe_service_client::ObserveServiceClient::new(ch.clone());
    let mut obs = observe
        .observe(with_token(
            pb::ObserveRequest { session_id: sid.clone(), rate_hz: 60.0, include_displacements: false },
            &created.observer_token,
        ))
        .await
        .unwrap()
        .into_inner();
    let mut control = pb::control_service_client::ControlServiceClient::new(ch.clone());
    // Insert 20 mm with a slight sideways push, so that the needle bends.
    for k in 1..=40 {
        let pose = pb::Pose2 { x_m: 0.05 + 2e-5 * k as f64, y_m: 0.205 - 5e-4 * k as f64, theta_rad: -std::f64::consts::FRAC_PI_2 };
        control
            .set_pose(with_token(
                pb::SetPoseRequest { session_id: sid.clone(), base: Some(pose), client_id: String::new(), take_over: false },
                &created.controller_token,
            ))
            .await
            .unwrap();
        tokio::time::sleep(std::time::Duration::from_millis(10)).await;
    }
    // A frame from after the insertion.
    let f = frame_where(&mut obs, |f| f.base.is_some_and(|b| b.y_m < 0.1851)).await.expect("the needle was inserted");
    assert_eq!(f.bevel_side, 1.0, "faulted {} {:?}, tick {}", f.faulted, f.fault, f.tick);
    assert_eq!(f.needle_shape_m.len(), 33, "a flexible needle's shape: 33 points");
    let (first, last) = (f.needle_shape_m[0], f.needle_shape_m[32]);
    let base = f.base.unwrap();
    let tip = f.tip_m.unwrap();
    assert!((first.x - base.x_m).abs() < 1e-12 && (last.x - tip.x).abs() < 1e-12 && (last.y - tip.y).abs() < 1e-12);

    // FlipBevel: the next ticks have the bevel on the other side.
    let r = control
        .flip_bevel(with_token(pb::FlipBevelRequest { session_id: sid.clone(), ..Default::default() }, &created.controller_token))
        .await
        .unwrap()
        .into_inner();
    assert_eq!(r.flips_requested, 1);
    let f = frame_where(&mut obs, |f| f.bevel_side == -1.0).await.expect("the bevel flips");
    let later = frame_where(&mut obs, |g| g.tick > f.tick + 50).await.unwrap();
    assert_eq!(later.bevel_side, -1.0, "and stays flipped");
    // An observer may not flip.
    let e = control
        .flip_bevel(with_token(pb::FlipBevelRequest { session_id: sid.clone(), ..Default::default() }, &created.observer_token))
        .await
        .unwrap_err();
    assert_eq!(e.code(), tonic::Code::PermissionDenied);

    // A Control message that only flips (no pose).
    let (tx, rx) = tokio::sync::mpsc::channel(4);
    let pose = pb::Pose2 { x_m: 0.0508, y_m: 0.185, theta_rad: -std::f64::consts::FRAC_PI_2 };
    tx.send(pb::ControlRequest {
        session_id: sid.clone(),
        base: Some(pose),
        client_time_ns: 0,
        seq: 1,
        flip_bevel: false,
        take_over: false,
    })
    .await
    .unwrap();
    tx.send(pb::ControlRequest { session_id: String::new(), base: None, client_time_ns: 0, seq: 0, flip_bevel: true, take_over: false })
        .await
        .unwrap();
    let mut responses =
        control.control(with_token(tokio_stream::wrappers::ReceiverStream::new(rx), &created.controller_token)).await.unwrap().into_inner();
    let mut flipped_back = false;
    for _ in 0..200 {
        let r = responses.message().await.unwrap().expect("responses");
        assert_eq!(r.needle_shape_m.len(), 33);
        if r.bevel_side == 1.0 {
            flipped_back = true;
            break;
        }
    }
    assert!(flipped_back, "the Control message flipped the bevel back");
    // Issue 13, one controller at a time: while the stream drives, a FlipBevel from another client
    // is refused (a flip is driving) unless it takes over, which ends the stream.
    let flip = |take_over: bool| pb::FlipBevelRequest { session_id: sid.clone(), client_id: "other".into(), take_over };
    let e = control.flip_bevel(with_token(flip(false), &created.controller_token)).await.unwrap_err();
    assert_eq!(e.code(), tonic::Code::FailedPrecondition, "{e:?}");
    assert!(e.message().contains("take_over"), "{}", e.message());
    let r = control.flip_bevel(with_token(flip(true), &created.controller_token)).await.expect("a flip that takes over").into_inner();
    assert_eq!(r.flips_requested, 3);
    let ended = loop {
        match responses.message().await {
            Ok(Some(_)) => continue,
            Ok(None) => break None,
            Err(s) => break Some(s),
        }
    };
    assert_eq!(ended.map(|s| s.code()), Some(tonic::Code::Aborted), "the revoked stream ends with ABORTED");
    drop(tx);

    // A rigid needle has nothing to flip.
    let rigid = create_example_session(&ch, "paper-phantom").await;
    let rid = rigid.session.unwrap().session_id;
    let e = control
        .flip_bevel(with_token(pb::FlipBevelRequest { session_id: rid, ..Default::default() }, &rigid.controller_token))
        .await
        .unwrap_err();
    assert_eq!(e.code(), tonic::Code::FailedPrecondition);
    assert!(e.message().contains("symmetric tip"), "{}", e.message());
}
