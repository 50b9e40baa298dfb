//! Issue 20, a trainee on a haptic device: a 2D exercise session with a device channel, driven by
//! the real `needlesim-bridge` process replaying a trajectory that keeps moving along the
//! exercise's insertion line. The device drives the needle; while the instructor has control
//! (TakeControl) the needle no longer follows it, the instructor's SetPose moves it, the bridge
//! is sent zero force and stiffness (its `--trace` shows the server's wrench and the rendered one
//! at exactly zero) and the session counts the poses it set aside (`SessionInfo`); after
//! HandBack the device drives again (the needle catches up with it and ends exactly at its pose);
//! a pause suspends it the same way.

use std::path::Path;
use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME, ServerProcess, TempDir, connect, latest_frame, repo_root, with_token};
use tonic::Code;

use crate::bridge_e2e::{RemoveOnDrop, finish_bridge, spawn_bridge};

/// The exercise's insertion line (biopsy-2d.csv's first two rows): the start `a` (5 mm outside
/// the tissue), the unit direction `u`, the needle angle.
struct Line {
    a: [f64; 2],
    u: [f64; 2],
    theta_rad: f64,
}

impl Line {
    fn of_biopsy() -> Self {
        let csv = std::fs::read_to_string(repo_root().join("server/scenes/exercises/biopsy-2d.csv")).unwrap();
        let rows: Vec<Vec<f64>> = csv
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("t_s"))
            .map(|l| l.split(',').map(|x| x.trim().parse::<f64>().unwrap()).collect())
            .collect();
        let (a, b) = ([rows[0][1], rows[0][2]], [rows[1][1], rows[1][2]]);
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        Self { a, u: [(b[0] - a[0]) / len, (b[1] - a[1]) / len], theta_rad: rows[0][3] }
    }
    /// The point `d_m` along the line.
    fn at(&self, d_m: f64) -> [f64; 2] {
        [self.a[0] + d_m * self.u[0], self.a[1] + d_m * self.u[1]]
    }
    /// How far along the line `p` is, after checking that `p` (a base pose) is on it.
    fn progress(&self, p: &pb::Pose2, what: &str) -> f64 {
        let (dx, dy) = (p.x_m - self.a[0], p.y_m - self.a[1]);
        let off = dx * self.u[1] - dy * self.u[0];
        assert!(off.abs() < 1e-9, "{what}: the base is {off} m off the insertion line: {p:?}");
        assert!((p.theta_rad - self.theta_rad).abs() < 1e-9, "{what}: the base turned: {p:?}");
        dx * self.u[0] + dy * self.u[1]
    }
}

/// One row of the bridge's 2D `--trace`: the server tick of the last force seen, the device pose,
/// whether the force was fresh, the server's wrench and the rendered one.
struct Row {
    tick: u64,
    pose: [f64; 2],
    fresh: bool,
    server: [f64; 3],
    rendered: [f64; 3],
}

fn read_trace(path: &Path) -> Vec<Row> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t_s,counter,x_m,y_m,theta_rad,fresh,tick,server_fx_n,server_fy_n,server_torque_nm,fx_n,fy_n,torque_nm,gain")
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or_else(|_| panic!("bad trace row {l}"))).collect();
            Row { tick: v[6] as u64, pose: [v[2], v[3]], fresh: v[5] == 1.0, server: [v[7], v[8], v[9]], rendered: [v[10], v[11], v[12]] }
        })
        .collect()
}

async fn session_info(ch: &tonic::transport::Channel, sid: &str) -> pb::SessionInfo {
    pb::session_service_client::SessionServiceClient::new(ch.clone())
        .get_session(pb::GetSessionRequest { session_id: sid.into() })
        .await
        .expect("GetSession")
        .into_inner()
}

async fn set_pose(ch: &tonic::transport::Channel, sid: &str, token: &str, p: [f64; 2], theta_rad: f64) -> Result<(), tonic::Status> {
    let msg = pb::SetPoseRequest {
        session_id: sid.into(),
        base: Some(pb::Pose2 { x_m: p[0], y_m: p[1], theta_rad }),
        client_id: "test".into(),
        take_over: true,
    };
    pb::control_service_client::ControlServiceClient::new(ch.clone()).set_pose(with_token(msg, token)).await.map(|_| ())
}

/// Sleeps until `at` after `t0`.
async fn sleep_until(t0: Instant, at_s: f64) {
    tokio::time::sleep_until((t0 + Duration::from_secs_f64(at_s)).into()).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue_20_a_device_trainee_is_locked_out_while_the_instructor_has_control() {
    let _turn = REALTIME.lock().await;
    let dir = TempDir::new("training-device");
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let created = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest {
            exercise: "biopsy-2d".into(),
            tick_rate_hz: 1000.0,
            record: false,
            device_channel: true,
        })
        .await
        .expect("an exercise session with a device channel")
        .into_inner();
    let sess = created.session.as_ref().unwrap();
    let info = sess.session.as_ref().unwrap();
    let sid = info.session_id.clone();
    let (trainee, obs, instructor) = (sess.controller_token.clone(), sess.observer_token.clone(), created.instructor_token.clone());
    let channel = std::path::PathBuf::from(&info.device_channel_path);
    assert!(channel.is_file(), "the exercise session has a device channel: {info:?}");
    let _chan_file = RemoveOnDrop(channel.clone());
    assert!(!info.device_suspended && info.device_poses_suspended == 0, "{info:?}");
    let ex = |token: &str| with_token(pb::ExerciseRequest { session_id: sid.clone() }, token);

    // The trainee's device: along the insertion line, 20 mm in 3 s, 30 mm more in 6 s (still
    // moving while the instructor has control), then held for 4 s.
    let line = Line::of_biopsy();
    let knots = [(0.0, 0.0), (3.0, 0.020), (9.0, 0.050), (13.0, 0.050)];
    let mut csv = String::from("t_s,x_m,y_m,theta_rad\n");
    for (t, d) in knots {
        let p = line.at(d);
        csv.push_str(&format!("{t},{},{},{}\n", p[0], p[1], line.theta_rad));
    }
    let traj = dir.join("device.csv");
    std::fs::write(&traj, csv).unwrap();
    let trace = dir.join("trace.csv");
    let t0 = Instant::now();
    let bridge = spawn_bridge(
        &channel,
        &["--device", "scripted", "--trajectory", traj.to_str().unwrap(), "--seconds", "13", "--trace", trace.to_str().unwrap()],
    );

    // The device drives: the needle goes in along the line with it.
    sleep_until(t0, 1.5).await;
    let f0 = latest_frame(&ch, &sid, &obs).await;
    sleep_until(t0, 2.5).await;
    let f1 = latest_frame(&ch, &sid, &obs).await;
    let (d0, d1) = (line.progress(f0.base.as_ref().unwrap(), "f0"), line.progress(f1.base.as_ref().unwrap(), "f1"));
    assert!(d1 > d0 + 0.002 && d1 > 0.008, "the device drives the needle in: {d0} m then {d1} m along the line");

    // The instructor takes control: the device no longer drives.
    let st = tr.take_control(ex(&instructor)).await.unwrap().into_inner();
    assert_eq!(pb::ControllerRole::try_from(st.controller).unwrap(), pb::ControllerRole::Instructor);
    tokio::time::sleep(Duration::from_millis(100)).await;
    let fa = latest_frame(&ch, &sid, &obs).await;
    let suspended_a = session_info(&ch, &sid).await;
    assert!(suspended_a.device_suspended, "{suspended_a:?}");
    tokio::time::sleep(Duration::from_millis(1000)).await;
    let fb = latest_frame(&ch, &sid, &obs).await;
    let suspended_b = session_info(&ch, &sid).await;
    assert!(fb.tick > fa.tick + 100, "the session ticks on: {} → {}", fa.tick, fb.tick);
    assert_eq!(fb.base, fa.base, "the needle stays while the device moves on (ticks {} → {})", fa.tick, fb.tick);
    let set_aside = suspended_b.device_poses_suspended - suspended_a.device_poses_suspended;
    assert!(set_aside >= 100, "the device's poses are read and set aside: {set_aside} in 1 s");
    assert!(!suspended_b.device_stale, "a suspended device that sends poses is not stale: {suspended_b:?}");
    // The trainee's gRPC poses are refused too, take-over or not.
    let e = set_pose(&ch, &sid, &trainee, line.at(0.02), line.theta_rad).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
    // The instructor pulls the needle back 4 mm.
    let da = line.progress(fa.base.as_ref().unwrap(), "fa");
    let pulled = line.at(da - 0.004);
    set_pose(&ch, &sid, &instructor, pulled, line.theta_rad).await.expect("the instructor drives");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let fc = latest_frame(&ch, &sid, &obs).await;
    let b = fc.base.unwrap();
    assert_eq!((b.x_m, b.y_m, b.theta_rad), (pulled[0], pulled[1], line.theta_rad), "the instructor's pose drives");

    // Hand-back: the device drives again; the needle catches up and ends at the device's pose.
    sleep_until(t0, 5.0).await;
    let fd = latest_frame(&ch, &sid, &obs).await;
    assert_eq!(fd.base, fc.base, "still the instructor's pose at the hand-back");
    let st = tr.hand_back_control(ex(&instructor)).await.unwrap().into_inner();
    assert_eq!(pb::ControllerRole::try_from(st.controller).unwrap(), pb::ControllerRole::Trainee);
    let end = line.at(0.050);
    let fe = loop {
        let f = latest_frame(&ch, &sid, &obs).await;
        let b = f.base.unwrap();
        line.progress(&b, "after the hand-back");
        if (b.x_m - end[0]).abs() < 1e-9 && (b.y_m - end[1]).abs() < 1e-9 {
            break f;
        }
        assert!(t0.elapsed() < Duration::from_millis(12_500), "the needle did not reach the device's final pose: {b:?}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    };
    let info = session_info(&ch, &sid).await;
    assert!(!info.device_suspended, "{info:?}");

    // A pause suspends the device as well; resuming lets it drive.
    tr.set_paused(with_token(pb::SetPausedRequest { session_id: sid.clone(), paused: true }, &instructor)).await.unwrap();
    let p0 = session_info(&ch, &sid).await;
    tokio::time::sleep(Duration::from_millis(50)).await;
    let fq = latest_frame(&ch, &sid, &obs).await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let p1 = session_info(&ch, &sid).await;
    assert!(p0.device_suspended && p1.device_poses_suspended > p0.device_poses_suspended, "paused: {p0:?} {p1:?}");
    let fp = latest_frame(&ch, &sid, &obs).await;
    tr.set_paused(with_token(pb::SetPausedRequest { session_id: sid.clone(), paused: false }, &instructor)).await.unwrap();
    assert!(!session_info(&ch, &sid).await.device_suspended);

    let (code, report, stderr) = finish_bridge(bridge).await;
    assert_eq!(code, Some(0), "the bridge failed: {report} {stderr}");

    // The bridge's side, by the server tick of the force it saw: pushed before, exactly zero
    // (server's wrench and rendered) while the instructor had control, pushed again after.
    let rows = read_trace(&trace);
    let before: Vec<&Row> = rows.iter().filter(|r| r.fresh && r.tick <= f1.tick).collect();
    assert!(before.iter().any(|r| r.server != [0.0; 3]), "the tissue pushed the device before ({} rows)", before.len());
    let locked: Vec<&Row> = rows.iter().filter(|r| (fa.tick..=fd.tick).contains(&r.tick)).collect();
    assert!(locked.len() >= 1000, "{} trace rows while the instructor had control", locked.len());
    for r in &locked {
        assert_eq!((r.server, r.rendered), ([0.0; 3], [0.0; 3]), "tick {}: force to a locked-out device", r.tick);
    }
    let moved = locked.iter().map(|r| (r.pose[0] - locked[0].pose[0]).hypot(r.pose[1] - locked[0].pose[1])).fold(0.0, f64::max);
    assert!(moved > 0.008, "the device kept moving while locked out: {moved} m");
    let after: Vec<&Row> = rows.iter().filter(|r| r.fresh && r.tick > fd.tick && r.tick <= fe.tick).collect();
    assert!(after.iter().any(|r| r.server != [0.0; 3] && r.rendered != [0.0; 3]), "the force came back after the hand-back");
    let paused: Vec<&Row> = rows.iter().filter(|r| r.fresh && r.tick >= fq.tick && r.tick <= fp.tick).collect();
    assert!(!paused.is_empty() && paused.iter().all(|r| r.server == [0.0; 3]), "zero force while paused ({} rows)", paused.len());
    println!(
        "locked out for ticks {}..={} ({} trace rows, {set_aside} poses set aside in 1 s; device moved {:.1} mm), needle at the device's final pose at tick {}",
        fa.tick,
        fd.tick,
        locked.len(),
        moved * 1e3,
        fe.tick
    );
    drop(server);
}
