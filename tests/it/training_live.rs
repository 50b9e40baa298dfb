//! Live training sessions end to end (issue 20), through the real server binary and gRPC
//! clients: a trainee drives a 2D and a 3D exercise (SetPose / SetPose3 along the exercise's own
//! trajectory), the instructor takes control (the trainee's poses, a take-over and a new Control
//! stream are refused with FAILED_PRECONDITION meanwhile), drives, places a marker and hands
//! control back; the trainee declares "placed" (the targeting error equals the tip's distance to
//! the displaced target in the session's own frame), the instructor ends the exercise; the report
//! exists, parses as HTML and carries the final metrics and the marker; observers received score
//! updates showing the hand-over, and ultrasound images that change as the needle advances.
//! The ultrasound slice's cost on the real-time thread (1 kHz, 10 observers) is an ignored
//! measurement.

use std::process::Command;
use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_tests::{REALTIME, ServerProcess, connect, python, repo_root, run, text, with_token};
use tokio_stream::StreamExt;
use tonic::Code;

/// A pose of an exercise's trajectory: 2D `(x, y, θ)` or 3D position + quaternion.
#[derive(Debug, Clone, Copy)]
enum Pose {
    Two([f64; 3]),
    Three([f64; 3], [f64; 4]),
}

/// The first two rows of the exercise's CSV (its straight insertion), interpolated at `s` ∈ [0, 1].
struct Path {
    a: Vec<f64>,
    b: Vec<f64>,
    dim: usize,
    duration_s: f64,
}

impl Path {
    fn of(exercise: &str, dim: usize) -> Self {
        let csv = std::fs::read_to_string(repo_root().join(format!("server/scenes/exercises/{exercise}.csv"))).unwrap();
        let rows: Vec<Vec<f64>> = csv
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("t_s"))
            .map(|l| l.split(',').map(|x| x.trim().parse::<f64>().unwrap()).collect())
            .collect();
        Self { a: rows[0][1..].to_vec(), b: rows[1][1..].to_vec(), dim, duration_s: rows[1][0] - rows[0][0] }
    }
    fn at(&self, s: f64) -> Pose {
        let v: Vec<f64> = self.a.iter().zip(&self.b).map(|(a, b)| a + (b - a) * s).collect();
        if self.dim == 2 { Pose::Two([v[0], v[1], v[2]]) } else { Pose::Three([v[0], v[1], v[2]], [v[3], v[4], v[5], v[6]]) }
    }
}

/// One SetPose / SetPose3 with `token`.
async fn set_pose(ch: &tonic::transport::Channel, sid: &str, token: &str, pose: Pose, take_over: bool) -> Result<(), tonic::Status> {
    let mut c = pb::control_service_client::ControlServiceClient::new(ch.clone());
    match pose {
        Pose::Two(p) => {
            let msg = pb::SetPoseRequest {
                session_id: sid.into(),
                base: Some(pb::Pose2 { x_m: p[0], y_m: p[1], theta_rad: p[2] }),
                client_id: "test".into(),
                take_over,
            };
            c.set_pose(with_token(msg, token)).await.map(|_| ())
        }
        Pose::Three(p, q) => {
            let msg = pb::SetPoseRequest3 {
                session_id: sid.into(),
                base3: Some(pb::Pose3 {
                    position_m: Some(pb::Vec3 { x: p[0], y: p[1], z: p[2] }),
                    orientation: Some(pb::Quaternion { w: q[0], x: q[1], y: q[2], z: q[3] }),
                }),
                client_id: "test".into(),
                take_over,
            };
            c.set_pose3(with_token(msg, token)).await.map(|_| ())
        }
    }
}

/// Drives the path from `s0` to `s1` in real time (a pose every 5 ms), every pose accepted.
async fn drive(ch: &tonic::transport::Channel, sid: &str, token: &str, path: &Path, s0: f64, s1: f64) {
    let secs = (s1 - s0) * path.duration_s;
    let start = Instant::now();
    let mut tick = tokio::time::interval(Duration::from_millis(5));
    loop {
        tick.tick().await;
        let f = (start.elapsed().as_secs_f64() / secs).min(1.0);
        set_pose(ch, sid, token, path.at(s0 + (s1 - s0) * f), false).await.expect("a pose of the driver in control");
        if f >= 1.0 {
            return;
        }
    }
}

fn controller(st: &pb::ExerciseStatus) -> pb::ControllerRole {
    pb::ControllerRole::try_from(st.controller).unwrap()
}

/// The report's metrics (`data-metric` cells), after Python's html.parser found every element
/// closed in order; and its marker labels.
fn parse_report(path: &std::path::Path) -> (serde_json::Value, Vec<String>) {
    let script = r##"
import json, sys
from html.parser import HTMLParser
VOID = {"meta", "br", "img", "input", "link", "hr", "area", "base", "col", "source", "wbr"}
class P(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.metrics, self.errors, self.markers, self.in_markers = [], {}, [], [], False
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "table": self.in_markers = a.get("id") == "markers"
        if "data-metric" in a: self.metrics[a["data-metric"]] = float(a["data-value"])
        if tag not in VOID: self.stack.append(tag)
    def handle_data(self, data):
        if self.in_markers and self.stack and self.stack[-1] == "td": self.markers.append(data)
    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append("</%s> closes %s" % (tag, self.stack[-1] if self.stack else "nothing"))
        else:
            self.stack.pop()
p = P()
p.feed(open(sys.argv[1], encoding="utf-8").read())
p.close()
print(json.dumps({"metrics": p.metrics, "errors": p.errors, "open": p.stack, "markers": p.markers}))
"##;
    let out = run(Command::new(python()).arg("-c").arg(script).arg(path));
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "html.parser: {stderr}");
    let r: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(r["errors"].as_array().unwrap().len(), 0, "{}", r["errors"]);
    assert_eq!(r["open"].as_array().unwrap().len(), 0, "unclosed {}", r["open"]);
    let markers = r["markers"].as_array().unwrap().iter().map(|m| m.as_str().unwrap().to_owned()).collect();
    (r["metrics"].clone(), markers)
}

/// The tip's distance to target 0's displaced centre in the session's latest frame.
async fn frame_distance(ch: &tonic::transport::Channel, sid: &str, obs: &str) -> (u64, f64) {
    let f = needlesim_tests::latest_frame(ch, sid, obs).await;
    match &f.d3 {
        Some(d3) => (f.tick, d3.targets[0].distance_m),
        None => (f.tick, f.targets[0].distance_m),
    }
}

async fn run_exercise_live(exercise: &str, dim: usize) {
    let _turn = REALTIME.lock().await;
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let created = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest {
            exercise: exercise.into(),
            tick_rate_hz: 1000.0,
            record: false,
            device_channel: false,
        })
        .await
        .expect("an exercise session")
        .into_inner();
    let sess = created.session.as_ref().unwrap();
    let info = sess.session.as_ref().unwrap();
    let sid = info.session_id.clone();
    let (trainee, obs, instructor) = (sess.controller_token.clone(), sess.observer_token.clone(), created.instructor_token.clone());
    assert_eq!(info.dimension as usize, dim);
    assert_eq!(instructor.len(), 32, "a 128-bit token in hex");
    assert!(instructor != trainee && instructor != obs);
    let ex = created.exercise.as_ref().unwrap();
    assert_eq!((ex.name.as_str(), ex.dimension as usize, ex.targets.len()), (exercise, dim, 1));

    // Observers: three score watchers and one ultrasound watcher, with the observer token.
    let mut watchers = Vec::new();
    for _ in 0..3 {
        let mut c = tr.clone();
        let req = with_token(pb::WatchScoreRequest { session_id: sid.clone(), rate_hz: 20.0 }, &obs);
        watchers.push(tokio::spawn(async move {
            let mut stream = c.watch_score(req).await.expect("WatchScore").into_inner();
            let mut got = Vec::new();
            while let Ok(Some(Ok(st))) = tokio::time::timeout(Duration::from_secs(30), stream.next()).await {
                got.push(st);
            }
            got
        }));
    }
    let (stop_ultrasound, mut stop_rx) = tokio::sync::oneshot::channel::<()>();
    let ultrasound = {
        let mut c = tr.clone();
        let req = with_token(pb::WatchUltrasoundRequest { session_id: sid.clone(), rate_hz: 10.0 }, &obs);
        tokio::spawn(async move {
            let mut stream = c.watch_ultrasound(req).await.expect("WatchUltrasound").into_inner();
            let mut got: Vec<pb::UltrasoundImage> = Vec::new();
            loop {
                tokio::select! {
                    img = stream.next() => match img {
                        Some(Ok(img)) => got.push(img),
                        _ => return got,
                    },
                    _ = &mut stop_rx => break,
                }
            }
            // The images come from a niced renderer, fewer a second with a build beside the
            // test: at the stop, the stream goes on until it has shown 10 (a hang guard of 60 s,
            // not a rate; the exercise has ended, the session still renders its last state).
            let until = tokio::time::Instant::now() + Duration::from_secs(60);
            while got.len() < 10
                && let Ok(Some(Ok(img))) = tokio::time::timeout_at(until, stream.next()).await
            {
                got.push(img);
            }
            got
        })
    };
    // 3D: the probe moves 4 mm off the needle's plane, beyond the beam's half-thickness, so the
    // needle is not drawn: what changes in that slice as the needle advances is the tissue it
    // deforms (the renderer's solve from the tick's contacts).
    let off_needle = if dim == 3 {
        let mut c = tr.clone();
        let req = with_token(pb::WatchUltrasoundRequest { session_id: sid.clone(), rate_hz: 10.0 }, &obs);
        let mut stream = c.watch_ultrasound(req).await.expect("WatchUltrasound").into_inner();
        let first = stream.next().await.expect("a first image").expect("an image");
        let mut p = first.probe.expect("the image's probe");
        let (u, v) = (p.e_u.unwrap(), p.e_v.unwrap());
        let n = [u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x];
        let o = p.origin_m.unwrap();
        p.origin_m = Some(pb::Vec3 { x: o.x + 0.004 * n[0], y: o.y + 0.004 * n[1], z: o.z + 0.004 * n[2] });
        assert!(p.thickness_m < 0.008, "the needle lies outside half the beam's thickness: {} m", p.thickness_m);
        let req = pb::SetProbeRequest { session_id: sid.clone(), probe: Some(p) };
        Some(tr.set_probe(with_token(req, &instructor)).await.expect("SetProbe").into_inner())
    } else {
        None
    };
    // Roles: the observer may not place, the trainee may not take control.
    let e = tr.place(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &obs)).await.unwrap_err();
    assert_eq!(e.code(), Code::PermissionDenied, "{e:?}");
    let e = tr.take_control(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &trainee)).await.unwrap_err();
    assert_eq!(e.code(), Code::PermissionDenied, "{e:?}");

    let path = Path::of(exercise, dim);
    // The trainee drives half way in.
    println!("{exercise}: the trainee drives");
    drive(&ch, &sid, &trainee, &path, 0.0, 0.5).await;
    println!("{exercise}: the instructor takes control");

    // The instructor takes control: the trainee is refused, also with take_over and a new stream.
    let st = tr.take_control(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &instructor)).await.unwrap().into_inner();
    assert_eq!(controller(&st), pb::ControllerRole::Instructor);
    for take_over in [false, true] {
        let e = set_pose(&ch, &sid, &trainee, path.at(0.55), take_over).await.unwrap_err();
        assert_eq!(e.code(), Code::FailedPrecondition, "take_over {take_over}: {e:?}");
        assert!(e.message().contains("instructor has control"), "{}", e.message());
    }
    {
        let mut c = pb::control_service_client::ControlServiceClient::new(ch.clone());
        let first = match path.at(0.55) {
            Pose::Two(p) => pb::ControlRequest {
                session_id: sid.clone(),
                base: Some(pb::Pose2 { x_m: p[0], y_m: p[1], theta_rad: p[2] }),
                seq: 1,
                take_over: true,
                ..Default::default()
            },
            Pose::Three(..) => pb::ControlRequest { session_id: sid.clone(), seq: 1, take_over: true, ..Default::default() },
        };
        if dim == 2 {
            let r = c.control(with_token(tokio_stream::iter(vec![first]), &trainee)).await;
            let code = match r {
                Err(e) => e.code(),
                Ok(resp) => resp.into_inner().next().await.and_then(|m| m.err()).map_or(Code::Ok, |e| e.code()),
            };
            assert_eq!(code, Code::FailedPrecondition, "a new Control stream of the trainee is refused");
        }
    }
    // The instructor drives a stretch and marks the timeline.
    println!("{exercise}: the instructor drives");
    drive(&ch, &sid, &instructor, &path, 0.5, 0.7).await;
    let marker = tr
        .add_marker(with_token(pb::AddMarkerRequest { session_id: sid.clone(), label: "instructor demo <1>".into() }, &instructor))
        .await
        .unwrap()
        .into_inner();
    assert!(marker.t_s > 0.5 * path.duration_s, "the marker's exercise time {} s", marker.t_s);
    let e =
        tr.add_marker(with_token(pb::AddMarkerRequest { session_id: sid.clone(), label: "x".repeat(201) }, &instructor)).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("label:"), "{}", e.message());
    let st = tr.hand_back_control(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &instructor)).await.unwrap().into_inner();
    assert_eq!(controller(&st), pb::ControllerRole::Trainee);
    // The instructor no longer drives.
    let e = set_pose(&ch, &sid, &instructor, path.at(0.7), false).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");

    // The trainee finishes the insertion, holds, and declares "placed".
    println!("{exercise}: the trainee drives again");
    drive(&ch, &sid, &trainee, &path, 0.7, 1.0).await;
    tokio::time::sleep(Duration::from_millis(400)).await;
    let placed = tr.place(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &trainee)).await.unwrap().into_inner();
    let p = placed.placement.unwrap();
    assert_eq!((p.target_index, p.target.as_str()), (0, ex.targets[0].name.as_str()));
    // The needle is held still: the session's state does not change, so the targeting error is
    // the distance the session's own frame reports.
    let (_, d) = frame_distance(&ch, &sid, &obs).await;
    assert!((p.error_m - d).abs() <= 1e-9, "placed error {} vs the frame's distance {d}", p.error_m);
    assert!(p.error_m < 0.01, "the insertion reached the target's neighbourhood: {} m", p.error_m);
    let e = tr.place(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &trainee)).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition, "every target is placed: {e:?}");

    // The end: the final result and the report.
    println!("{exercise}: the end");
    let fin = tr.end_exercise(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &instructor)).await.unwrap().into_inner();
    assert!(fin.finished && !fin.report_name.is_empty());
    assert_eq!(fin.insertions, 1, "one insertion");
    assert!(fin.samples > 1000 && fin.path_length_m > 0.02, "{fin:?}");
    assert_eq!(fin.markers.len(), 1);
    let again = tr.end_exercise(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &trainee)).await.unwrap().into_inner();
    assert_eq!((again.score, again.samples), (fin.score, fin.samples), "ending twice gives the same result");
    let report = server.data_dir.path().join("reports").join(&fin.report_name);
    assert!(report.is_file(), "{} exists", report.display());
    let mut chunks = tr.get_report(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &obs)).await.unwrap().into_inner();
    let mut html = Vec::new();
    while let Some(c) = chunks.next().await {
        html.extend(c.unwrap().html);
    }
    assert_eq!(html, std::fs::read(&report).unwrap(), "GetReport streams the file");
    let (m, markers) = parse_report(&report);
    let close = |k: &str, v: f64| {
        let got = m[k].as_f64().unwrap_or_else(|| panic!("no {k} in the report"));
        assert!((got - v).abs() <= 1e-12 * v.abs().max(1.0), "{k}: {got} in the report, {v} in the final status");
    };
    close("score", fin.score);
    close("insertions", fin.insertions as f64);
    close("path_length_m", fin.path_length_m);
    close("peak_axial_force_n", fin.peak_axial_force_n);
    close("target_0_error_m", p.error_m);
    assert!(markers.iter().any(|l| l == "instructor demo <1>"), "the marker in the report: {markers:?}");
    // Tissue strain: sampled live in 2D on the fan-out side from the displacement field; not in 3D.
    if dim == 2 {
        let (n, peak) = (m["strain_samples"].as_f64().unwrap_or(0.0), m["peak_strain"].as_f64().unwrap_or(f64::NAN));
        assert!(n >= 1.0 && peak.is_finite() && peak > 0.0, "live strain in the report: {n} samples, peak {peak}");
    } else {
        assert!(m.get("strain_samples").is_none_or(|v| v.is_null()), "no strain in 3D");
    }
    // The exercise names an expert run (server/scenes/exercises/NAME-expert.csv): overlaid and compared.
    let page = String::from_utf8(html).unwrap();
    assert!(page.contains("<table id=\"expert\">") && page.contains(&format!("expert ({exercise}-expert.csv)")), "the expert overlay");

    // Observers saw the score evolve, the hand-over, and the final result.
    println!("{exercise}: the observers");
    for w in watchers {
        let got = w.await.unwrap();
        assert!(got.len() >= 5, "{} score updates", got.len());
        assert!(got.windows(2).all(|w| w[1].samples >= w[0].samples), "samples only grow");
        assert!(got.iter().any(|s| controller(s) == pb::ControllerRole::Instructor), "the hand-over was visible");
        let last = got.last().unwrap();
        assert!(last.finished && last.score == fin.score, "the stream ends with the final result");
    }
    let _ = stop_ultrasound.send(());
    let images = ultrasound.await.unwrap();
    assert!(images.len() >= 10, "{} ultrasound images", images.len());
    for img in &images {
        assert_eq!(img.gray8.len(), (img.width * img.height) as usize);
    }
    let (first, last) = (images.first().unwrap(), images.last().unwrap());
    assert!(last.tick > first.tick);
    let changed = first.gray8.iter().zip(&last.gray8).filter(|(a, b)| a != b).count();
    assert!(changed > 50, "the slice changed as the needle advanced: {changed} pixels");
    if let Some(probe) = &off_needle {
        // The slice off the needle's plane, before the needle went in and at the end.
        let off: Vec<&pb::UltrasoundImage> = images.iter().filter(|i| i.probe.as_ref() == Some(probe)).collect();
        let (a, b) = (off.first().expect("images off the needle"), off.last().unwrap());
        assert!(b.tick > a.tick && a.gray8.len() == b.gray8.len());
        let n = a.gray8.len();
        let changed = a.gray8.iter().zip(&b.gray8).filter(|(x, y)| x != y).count();
        println!("{exercise}: off the needle's plane, {changed} of {n} pixels changed from tick {} to {}", a.tick, b.tick);
        // Undeformed, this slice would not change at all (no needle in it, targets and speckle
        // attached to the reference configuration).
        assert!(changed > n / 50, "the deformed tissue changed the slice off the needle: {changed} of {n} pixels");
    }

    // Closing the session: its exercise is gone.
    let mut sc = pb::session_service_client::SessionServiceClient::new(ch.clone());
    sc.close_session(with_token(pb::CloseSessionRequest { session_id: sid.clone() }, &trainee)).await.unwrap();
    let e = tr.get_status(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &obs)).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_2d_exercise_with_a_hand_over_a_marker_and_a_report() {
    run_exercise_live("biopsy-2d", 2).await;
}

#[ignore = "run alone by tests/run (its last phase): a live 3D session whose compliance worker must keep up with the tip; on a CPU shared with other tests its captures are lost (see ARCHITECTURE, Live 3D under load)"]
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_3d_exercise_with_a_hand_over_a_marker_and_a_report() {
    run_exercise_live("biopsy-3d", 3).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_requests_are_named() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let e = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest { exercise: "/etc/passwd".into(), ..Default::default() })
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("exercise: '/etc/passwd' is not a shipped exercise"), "{}", e.message());
    let e = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest {
            exercise: "biopsy-2d".into(),
            tick_rate_hz: 50.0,
            ..Default::default()
        })
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(e.message().starts_with("tick_rate_hz"), "{}", e.message());
    let list = tr.list_exercises(pb::ListExercisesRequest {}).await.unwrap().into_inner();
    assert_eq!(list.exercises.len(), 6);
    // A plain session is no exercise.
    let plain = needlesim_tests::create_example_session(&ch, "fig3-target").await;
    let sid = plain.session.unwrap().session_id;
    let e = tr.get_status(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &plain.observer_token)).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition);
    let created = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest { exercise: "biopsy-2d".into(), ..Default::default() })
        .await
        .unwrap()
        .into_inner();
    let sid = created.session.unwrap().session.unwrap().session_id;
    let probe = |w: u32, e_v: [f64; 3]| pb::SetProbeRequest {
        session_id: sid.clone(),
        probe: Some(pb::UltrasoundProbe {
            origin_m: Some(pb::Vec3 { x: 0.0, y: 0.1, z: 0.0 }),
            e_u: Some(pb::Vec3 { x: 1.0, y: 0.0, z: 0.0 }),
            e_v: Some(pb::Vec3 { x: e_v[0], y: e_v[1], z: e_v[2] }),
            pixel_m: 5e-4,
            width: w,
            height: 64,
            thickness_m: 0.0,
        }),
    };
    let tok = created.instructor_token;
    let e = tr.set_probe(with_token(probe(4, [0.0, -1.0, 0.0]), &tok)).await.unwrap_err();
    assert_eq!((e.code(), e.message()), (Code::InvalidArgument, "probe.width: 4 must be in 8..=512 pixels"));
    let e = tr.set_probe(with_token(probe(64, [1.0, 0.0, 0.0]), &tok)).await.unwrap_err();
    assert!(e.message().starts_with("probe.e_v:"), "{}", e.message());
    let ok = tr.set_probe(with_token(probe(64, [0.0, -1.0, 0.0]), &tok)).await.unwrap().into_inner();
    assert_eq!((ok.width, ok.height), (64, 64));
}

/// The ultrasound slice's cost on the real-time thread: an exercise (`NEEDLESIM_EXERCISE`,
/// `biopsy-2d` by default; a `-3d` one renders the deformed 3D tissue, a solve per image) at
/// 1 kHz, the needle driven in, for `NEEDLESIM_SECONDS` (10) s with 10 ultrasound observers at
/// 30 Hz, then as long without; prints the missed deadlines and lateness of each phase and the
/// load. Timing: ignored.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "a measurement (prints figures): run alone on a quiet machine"]
async fn ultrasound_cost_on_the_real_time_thread() {
    let _turn = REALTIME.lock().await;
    let secs: f64 = std::env::var("NEEDLESIM_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(10.0);
    let exercise = std::env::var("NEEDLESIM_EXERCISE").unwrap_or_else(|_| "biopsy-2d".into());
    let dim = if exercise.ends_with("-3d") { 3 } else { 2 };
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let created = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest {
            exercise: exercise.clone(),
            tick_rate_hz: 1000.0,
            ..Default::default()
        })
        .await
        .unwrap()
        .into_inner();
    let sess = created.session.unwrap();
    let sid = sess.session.unwrap().session_id;
    let (trainee, obs) = (sess.controller_token, sess.observer_token);
    let path = Path::of(&exercise, dim);
    let mut sc = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let stats = |mut sc: pb::session_service_client::SessionServiceClient<tonic::transport::Channel>, sid: String, obs: String| async move {
        sc.get_stats(with_token(pb::GetSessionRequest { session_id: sid }, &obs)).await.unwrap().into_inner()
    };
    for (phase, observers) in [("with 10 ultrasound observers", 10), ("without", 0)] {
        let before = stats(sc.clone(), sid.clone(), obs.clone()).await;
        let mut tasks = Vec::new();
        for _ in 0..observers {
            let mut c = tr.clone();
            let req = with_token(pb::WatchUltrasoundRequest { session_id: sid.clone(), rate_hz: 30.0 }, &obs);
            tasks.push(tokio::spawn(async move {
                let mut stream = c.watch_ultrasound(req).await.unwrap().into_inner();
                let (mut n, mut us) = (0u64, 0.0);
                let end = Instant::now() + Duration::from_secs_f64(secs);
                while let Ok(Some(Ok(img))) = tokio::time::timeout_at(end.into(), stream.next()).await {
                    n += 1;
                    us += img.render_us;
                }
                (n, us)
            }));
        }
        // In and out along the path, `secs` in all.
        let t0 = Instant::now();
        while t0.elapsed().as_secs_f64() < secs {
            let ph = (t0.elapsed().as_secs_f64() / 4.0) % 2.0;
            let s = if ph < 1.0 { ph } else { 2.0 - ph };
            let _ = set_pose(&ch, &sid, &trainee, path.at(0.9 * s), false).await;
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        let mut frames = 0;
        let mut render_us = 0.0;
        for t in tasks {
            let (n, us) = t.await.unwrap();
            frames += n;
            render_us += us;
        }
        let after = stats(sc.clone(), sid.clone(), obs.clone()).await;
        let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
        println!(
            "{exercise} ultrasound {phase}: {} ticks, {} missed deadlines, lateness p99 {:.1} µs p99.9 {:.1} µs, compute max {:.1} µs (whole session), {frames} images received, mean render {:.0} µs; loadavg {}",
            after.ticks - before.ticks,
            after.missed_deadlines - before.missed_deadlines,
            after.lateness_p99_us,
            after.lateness_p999_us,
            after.compute_max_us,
            if frames > 0 { render_us / frames as f64 } else { 0.0 },
            load.trim()
        );
    }
    sc.get_session(pb::GetSessionRequest { session_id: sid }).await.unwrap();
}

/// The viewer in headless Chromium (tests/web_training_e2e.mjs): the live score, who is in
/// control (seen by an observer's page while the instructor's page takes control), "Placed"
/// changing the score, and the ultrasound slice changing as the needle advances (screenshots
/// compared). Needs web/node_modules (`npm ci`) and /usr/bin/chromium (or `NEEDLESIM_CHROMIUM`).
#[test]
fn the_viewer_shows_the_score_the_controller_and_the_slice_in_headless_chromium() {
    let _turn = REALTIME.blocking_lock();
    let web = repo_root().join("web");
    assert!(web.join("node_modules/playwright-core").is_dir(), "web/node_modules is missing: run `npm ci` in web/ (tests/run does it)");
    let chromium = std::env::var("NEEDLESIM_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".to_owned());
    assert!(std::path::Path::new(&chromium).exists(), "no Chromium at {chromium}: apt-get install chromium, or set NEEDLESIM_CHROMIUM");
    let server = ServerProcess::start(&["--default-scene", "none", "--web-dir", web.to_str().unwrap()]);
    let shots = repo_root().join("target/web-screenshots");
    let names = ["slice-before.png", "slice-after.png", "training-observer.png", "training-trainee.png", "summary-training.json"];
    for f in names {
        let _ = std::fs::remove_file(shots.join(f));
    }
    let out = run(Command::new("node")
        .arg(repo_root().join("tests/web_training_e2e.mjs"))
        .arg(server.url())
        .arg(&shots)
        .env("NEEDLESIM_CHROMIUM", &chromium));
    let (so, se) = text(&out);
    println!("{so}");
    assert!(out.status.success(), "tests/web_training_e2e.mjs failed:\n{so}\n{se}\nserver log:\n{}", server.stderr.lock().unwrap());
    let summary = needlesim_tests::read_json(&shots.join("summary-training.json"));
    let f = |k: &str| summary[k].as_f64().unwrap_or_else(|| panic!("no number `{k}` in {summary}"));
    assert!(f("depth1") > f("depth0") + 0.01, "the drag did not insert the needle: {summary}");
    assert!((f("score1") - f("score0")).abs() > 1e-6, "the score did not change: {summary}");
    assert!(summary["placed"].as_str().is_some_and(|t| t.starts_with("biopsy: ") && t.contains(" mm")), "no placement shown: {summary}");
    assert_eq!(summary["controllerShown"], "instructor", "{summary}");
    assert!(f("ultrasoundFrames") >= 10.0, "{summary}");
    let (before, after) = (std::fs::read(shots.join("slice-before.png")).unwrap(), std::fs::read(shots.join("slice-after.png")).unwrap());
    for png in [&before, &after] {
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 2000, "not a real screenshot ({} bytes)", png.len());
    }
    assert_ne!(before, after, "the slice did not change as the needle advanced");
}

/// Issue 35 (finding 4): a trainee repeating a refused "placed" declaration grew the server and
/// the report without bound (101,873 refused calls in 60 s: +42 MB, a 5.9 MB report). The
/// exercise keeps the first 1000 in full and counts the rest; the report says how many were left out.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn issue35_refused_placements_are_kept_up_to_a_bound_and_counted() {
    let server = ServerProcess::start(&["--default-scene", "none"]);
    let ch = connect(&server).await;
    let mut tr = pb::training_service_client::TrainingServiceClient::new(ch.clone());
    let created = tr
        .create_exercise_session(pb::CreateExerciseSessionRequest { exercise: "biopsy-2d".into(), ..Default::default() })
        .await
        .unwrap()
        .into_inner();
    let handle = created.session.unwrap();
    let sid = handle.session.unwrap().session_id;
    let (trainee, instructor) = (handle.controller_token, created.instructor_token);
    let calls = 1300;
    let mut refused = 0u64;
    for _ in 0..calls {
        if let Err(e) = tr.place(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &trainee)).await {
            assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
            refused += 1;
        }
    }
    assert!(refused >= calls - 1, "at most the first declaration places the one target: {refused} refused");
    let fin = tr.end_exercise(with_token(pb::ExerciseRequest { session_id: sid.clone() }, &instructor)).await.unwrap().into_inner();
    let html = std::fs::read_to_string(server.data_dir.path().join("reports").join(&fin.report_name)).unwrap();
    let section = html.split("<h2>Refused declarations</h2>").nth(1).expect("the refused declarations are in the report");
    let listed = section.split("</ul>").next().unwrap().matches("<li>").count();
    assert_eq!(listed, 1000, "the first 1000 refused declarations are listed");
    let note = format!("{refused} declarations refused in all: the first 1000 are listed, {} more are left out.", refused - 1000);
    assert!(section.contains(&note), "the report says how many were left out ({note})");
    assert!(html.len() < 1 << 20, "the report stays small: {} bytes", html.len());
}
