//! A session with a shared-memory device channel: the device drives the needle and reads force,
//! torque and stiffness; when the bridge goes away the server holds the needle and marks the
//! device stale; a new bridge re-attaches and drives again.

use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use needlesim_channel::shm::{DeviceChannel, DeviceEnd, DevicePose, ServerForce, monotonic_ns};
use needlesim_core::MeshLimits;
use needlesim_session::Session;

fn drive(device: &mut DeviceEnd, from_y: f64, to_y: f64, secs: f64) -> Option<ServerForce> {
    drive_buttons(device, from_y, to_y, secs, |_| 0)
}

/// As `drive`, with the buttons a function of the elapsed fraction of `secs`.
fn drive_buttons(device: &mut DeviceEnd, from_y: f64, to_y: f64, secs: f64, buttons: impl Fn(f64) -> u32) -> Option<ServerForce> {
    let start = Instant::now();
    let mut last = None;
    while start.elapsed().as_secs_f64() < secs {
        let a = start.elapsed().as_secs_f64() / secs;
        let y = from_y + (to_y - from_y) * a;
        device.write_pose_from_device(&DevicePose::planar(monotonic_ns(), [0.05, y, -std::f64::consts::FRAC_PI_2], buttons(a))).unwrap();
        let f = device.read_force_from_device();
        if f.fresh() {
            last = f.value;
        }
        std::thread::sleep(Duration::from_micros(500));
    }
    last
}

#[test]
fn device_drives_goes_stale_and_reattaches() {
    let scene = needlesim_scene::load_scene("paper-phantom", &MeshLimits::default()).unwrap();
    let dir = std::env::temp_dir().join(format!("needlesim-device-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = Session::start(&scene, 1000.0, Some(&dir)).unwrap();
    let path = session.device_channel_path.clone().unwrap();
    let mode = std::os::unix::fs::PermissionsExt::mode(&std::fs::metadata(&path).unwrap().permissions()) & 0o777;
    assert_eq!(mode, 0o600, "the channel is readable only by its owner");

    // The device inserts the needle 30 mm and reads the tissue's force back.
    let mut device = DeviceChannel::attach(&path).unwrap();
    let f = drive(&mut device, 0.205, 0.165, 2.0).expect("forces arrive");
    assert_eq!(f.state, ServerForce::STATE_OK);
    // The force names the device pose it answers, and the session published its tick phase.
    assert!((1..=device.pose_counter()).contains(&f.pose_counter), "pose counter {} of {}", f.pose_counter, device.pose_counter());
    let (origin, period) = device.server_schedule().expect("the tick phase is published");
    assert_eq!(period, Duration::from_millis(1));
    assert!(origin.as_nanos() as u64 <= monotonic_ns(), "tick 0 is in the past");
    assert!((f.base_position_m[1] - 0.165).abs() < 0.002, "the server used the device's pose: {:?}", f.base_position_m);
    let axial = -f.force_n[1]; // the needle points down: axial = -Fy
    assert!(axial < -0.1, "the tissue resists the insertion: {f:?}");
    // Lateral stiffness (x pose → Fx) restores: negative.
    assert!(f.stiffness[0][0] < 0.0, "stiffness {:?}", f.stiffness);
    let rec = session.latest_record();
    assert!(!rec.device_stale);

    // The bridge goes away without a word: the server holds the needle and marks the device stale.
    drop(device);
    // Polled, not a fixed sleep: this machine may stall for longer than the stale timeout.
    let t0 = Instant::now();
    while !session.latest_record().device_stale {
        assert!(t0.elapsed() < Duration::from_secs(10), "the device is marked stale");
        std::thread::sleep(Duration::from_millis(10));
    }
    std::thread::sleep(Duration::from_millis(100));
    let held = session.latest_record();
    assert!(held.device_stale, "the device is marked stale");
    assert!((held.base.y_m - f.base_position_m[1]).abs() < 0.002, "the needle is held where the device left it: {:?}", held.base);
    assert_eq!(session.counters.device_stale_events.load(Ordering::Relaxed), 1);
    let t1 = held.tick;
    let t0 = Instant::now();
    while session.latest_record().tick <= t1 + 50 {
        assert!(t0.elapsed() < Duration::from_secs(10), "the session keeps ticking");
        std::thread::sleep(Duration::from_millis(10));
    }

    // A new bridge attaches and drives again.
    let mut again = DeviceChannel::attach(&path).unwrap();
    let f2 = drive(&mut again, 0.165, 0.17, 0.5).expect("forces arrive again");
    assert_eq!(f2.state, ServerForce::STATE_OK);
    assert!(!session.latest_record().device_stale);
    assert!((session.latest_record().base.y_m - 0.17).abs() < 0.002);
    drop(again);
    session.close();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 8: the device's button 0 turns the needle 180° about its axis (each press, not each
/// sample it is held down).
#[test]
fn issue_8_device_button_flips_the_bevel() {
    let text = include_str!("../../scenes/fig4-steering.toml").replace("gauge = 22", "gauge = 22\nbevel_force_ratio = 0.3");
    let scene = needlesim_scene::parse_scene(&text, std::path::Path::new("."), &MeshLimits::default()).unwrap();
    let dir = std::env::temp_dir().join(format!("needlesim-device-bevel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = Session::start(&scene, 1000.0, Some(&dir)).unwrap();
    assert!(session.has_bevel);
    let mut device = DeviceChannel::attach(session.device_channel_path.clone().unwrap()).unwrap();
    // Insert 10 mm with the button up, then press it (held for a while), release, press again.
    drive(&mut device, 0.205, 0.195, 0.5).expect("forces arrive");
    assert_eq!(session.latest_record().bevel_side, 1.0);
    let one_press = |a: f64| u32::from((0.2..0.6).contains(&a));
    drive_buttons(&mut device, 0.195, 0.19, 0.5, one_press);
    std::thread::sleep(Duration::from_millis(20));
    assert_eq!(session.counters.bevel_flips_requested.load(Ordering::Relaxed), 1, "one press, one flip");
    assert_eq!(session.latest_record().bevel_side, -1.0);
    drive_buttons(&mut device, 0.19, 0.185, 0.5, one_press);
    std::thread::sleep(Duration::from_millis(20));
    assert_eq!(session.counters.bevel_flips_applied.load(Ordering::Relaxed), 2);
    assert_eq!(session.latest_record().bevel_side, 1.0);
    let rec = session.latest_record();
    assert_eq!(rec.shape().len(), needlesim_session::MAX_RECORD_SHAPE, "a flexible needle's shape is recorded");
    let (first, last) = (rec.shape()[0], rec.shape()[rec.shape().len() - 1]);
    assert!((first[1] - rec.base.y_m).abs() < 1e-12 && (last[1] - rec.tip_m[1]).abs() < 1e-12, "base to tip: {first:?} {last:?}");
    drop(device);
    session.close();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13: the live channel file of a driven session is truncated (the server's next access
/// faulted with SIGBUS and killed the process, every session with it) or deleted (found by the
/// session's watcher thread). The session keeps ticking with its device stale and its channel
/// broken, holding the needle where the device left it; another session is untouched.
#[test]
fn issue_13_a_changed_channel_file_leaves_its_session_and_the_others_ticking() {
    use needlesim_channel::shm::{Broken, ReadStatus};
    let scene = needlesim_scene::load_scene("paper-phantom", &MeshLimits::default()).unwrap();
    let dir = std::env::temp_dir().join(format!("needlesim-device-broken-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (kind, cause) in [("truncate", Broken::Faulted), ("delete", Broken::Deleted)] {
        let bystander = Session::start(&scene, 1000.0, Some(&dir)).unwrap();
        let session = Session::start(&scene, 1000.0, Some(&dir)).unwrap();
        let path = session.device_channel_path.clone().unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        let f = drive(&mut device, 0.205, 0.185, 1.0).expect("forces arrive");
        assert_eq!(f.state, ServerForce::STATE_OK, "[{kind}]");
        match kind {
            "truncate" => std::fs::OpenOptions::new().write(true).open(&path).unwrap().set_len(0).unwrap(),
            _ => std::fs::remove_file(&path).unwrap(),
        }
        let t0 = Instant::now();
        while session.counters.device_channel_broken.load(Ordering::Relaxed) == 0 {
            assert!(t0.elapsed() < Duration::from_secs(10), "[{kind}] the session did not mark its channel broken");
            std::thread::sleep(Duration::from_millis(5));
        }
        // The device end sees it too (the truncation on its next access, the deletion by its watcher).
        let _ = device.read_force_from_device();
        let _ = device.watch().check_file();
        assert_eq!(device.broken(), Some(cause), "[{kind}]");
        assert_eq!(device.read_force_from_device().status, ReadStatus::Broken, "[{kind}]");
        assert!(device.write_pose_from_device(&DevicePose::planar(0, [0.0, 0.15, 0.0], 0)).is_err(), "[{kind}]");

        std::thread::sleep(Duration::from_millis(100));
        let held = session.latest_record();
        assert!(held.device_stale, "[{kind}] the device is marked stale");
        assert_eq!(session.counters.device_stale.load(Ordering::Relaxed), 1, "[{kind}]");
        assert!((held.base.y_m - 0.185).abs() < 0.002, "[{kind}] the needle is held where the device left it: {:?}", held.base);
        // Both sessions tick on (polled: no rate is asserted on this loaded machine).
        let (t1, b1) = (held.tick, bystander.latest_record().tick);
        let t0 = Instant::now();
        while session.latest_record().tick <= t1 + 100 || bystander.latest_record().tick <= b1 + 100 {
            assert!(t0.elapsed() < Duration::from_secs(20), "[{kind}] a session stopped ticking");
            std::thread::sleep(Duration::from_millis(20));
        }
        let later = session.latest_record();
        assert_eq!(later.base, held.base, "[{kind}] the needle moved without a device");
        assert!(later.device_stale, "[{kind}]");
        assert_eq!(bystander.counters.device_channel_broken.load(Ordering::Relaxed), 0, "[{kind}]");
        let other_path = bystander.device_channel_path.clone().unwrap();
        let mut other_device = DeviceChannel::attach(&other_path).expect("the other session's channel still attaches");
        assert!(other_device.is_current() && other_device.broken().is_none(), "[{kind}]");
        drive(&mut other_device, 0.205, 0.2, 0.2).expect("the other session's channel still carries forces");

        drop((device, other_device));
        session.close();
        bystander.close();
        assert!(!path.exists() && !other_path.exists(), "[{kind}] the channel files are removed at close");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 13: a diverging solve (a flexible needle with 1e4 N/m friction, driven by the device
/// along Fig. 4's path) faults the session: the device then reads zero force, torque and stiffness
/// every tick, and the session no longer steps.
///
/// Issue 35 (item 13): where a sticky needle diverges depends chaotically on which pose each tick
/// takes, and the device used to write poses on the wall clock (a pace search over fresh sessions):
/// on a loaded machine the ticks took other poses and none diverged. Now the device runs in
/// lockstep with the session's ticks, at 100 Hz: after tick k it writes the pose of tick k + 1 (the
/// path's time is the tick's), and every tick's force names the pose it took, so the run is checked
/// to be the designed one (each tick took the pose written for it). That run diverges, always at
/// the same tick; a run in which the test thread was late for a tick (a stall of ~10 ms) is not
/// that run and is repeated on a fresh session.
#[test]
fn issue_13_a_faulted_session_renders_zero_force_to_the_device() {
    let text = include_str!("../../scenes/fig4-steering.toml").replace("friction_n_per_m = 10\n", "friction_n_per_m = 1e4\n");
    let scene = needlesim_scene::parse_scene(&text, std::path::Path::new("."), &MeshLimits::default()).unwrap();
    let dir = std::env::temp_dir().join(format!("needlesim-device-fault-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Fig. 4's path at 7/8 of its pace (time in s): 35 mm down, 5 mm right, then down again.
    let pace = 0.875;
    let pose_at = |t: f64| {
        let t = t * pace;
        if t < 1.0 {
            (0.05, 0.205 - 0.04 * t)
        } else if t < 1.0125 {
            (0.05 + 0.005 * (t - 1.0) / 0.0125, 0.165)
        } else {
            (0.055, 0.165 - 0.05 * ((t - 1.0125) / 1.25).min(1.0))
        }
    };
    let rate_hz = 100.0;
    let write = |device: &mut DeviceEnd, (x_m, y_m): (f64, f64)| {
        let p = DevicePose::planar(monotonic_ns(), [x_m, y_m, -std::f64::consts::FRAC_PI_2], 0);
        device.write_pose_from_device(&p).unwrap()
    };
    let bound = 176_272.640_687_119_3; // DivergenceBounds::force_n of this scene
    let mut attempt = None;
    for _ in 0..10 {
        let session = Session::start(&scene, rate_hz, Some(&dir)).unwrap();
        let mut device = DeviceChannel::attach(session.device_channel_path.clone().unwrap()).unwrap();
        let ticks = || session.counters.ticks.load(Ordering::Relaxed);
        let k0 = ticks();
        // The pose counter written for each tick (by its record's tick number), and whether a
        // tick took another pose or went by without one written for it.
        let mut written = std::collections::HashMap::new();
        let (mut next, mut faithful) = (k0, true);
        let start = Instant::now();
        while session.counters.fault().is_none() && ticks() < k0 + (2.6 / pace * rate_hz) as u64 {
            assert!(start.elapsed() < Duration::from_secs(120), "the session stopped ticking");
            let k = ticks();
            if k >= next {
                faithful &= k == next;
                written.insert(k, write(&mut device, pose_at((k - k0) as f64 / rate_hz)));
                next = k + 1;
            }
            let f = device.read_force_from_device();
            if let Some(f) = f.value.filter(|_| f.fresh() && session.counters.fault().is_none()) {
                // Large forces are the model's answer to a needle that drags the tissue along;
                // what must never reach the device is a force past the divergence bound, or NaN.
                assert!(f.force_n[0].hypot(f.force_n[1]) <= bound, "a diverged force reached the device: {f:?}");
                faithful &= written.get(&f.tick).is_none_or(|&c| f.pose_counter == c);
            }
            std::thread::sleep(Duration::from_micros(200));
        }
        let faulted_at = session.counters.fault().map(|f| f.tick - k0);
        println!("a lockstep run from tick {k0}: faithful {faithful}, faulted {faulted_at:?} ticks in");
        if faithful {
            assert!(faulted_at.is_some(), "the designed run (every tick took its pose) did not diverge");
            attempt = Some((session, device));
            break;
        }
        drop(device);
        session.close();
    }
    let (session, mut device) = attempt.expect("in 10 runs the test thread was late for a tick every time (a loaded machine)");
    let fault = session.counters.fault().expect("the session faulted");
    assert_eq!(session.counters.faults.load(Ordering::Relaxed), 1);
    // Since issue 35 a tick that does not converge faults the session as a divergence does;
    // on this path its shape passes may reach their cap before anything diverges.
    let m = fault.message();
    assert!(m.contains("the solve diverged") || m.contains("the tick did not converge"), "{m}");
    // The device keeps getting fresh wrenches, all zero, wherever it moves (30 of them: the
    // session ticks on; the loop is bounded only as a guard against a hang).
    let (mut fresh, start) = (0, Instant::now());
    for k in 0.. {
        if fresh == 30 {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(120), "the device stopped hearing from the server ({fresh} fresh wrenches)");
        write(&mut device, (0.05, 0.2 - 1e-5 * (k % 1000) as f64));
        let f = device.read_force_from_device();
        if let (true, Some(f)) = (f.fresh(), f.value) {
            fresh += 1;
            assert_eq!((f.force_n, f.torque_nm), ([0.0; 3], [0.0; 3]), "zero force after the fault: {f:?}");
            assert_eq!(f.stiffness, [[0.0; 6]; 6], "zero stiffness after the fault");
        }
        std::thread::sleep(Duration::from_micros(500));
    }
    let rec = session.latest_record();
    // (Compared as text: a NaN value is not equal to itself.)
    let last = (rec.tick, rec.fault.map(|f| f.message()));
    assert_eq!(last, (fault.tick, Some(fault.message())), "the faulted record is the last one: no step after the fault");
    assert_eq!(session.stats().fault, Some(fault.message()));
    drop(device);
    session.close();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Drives the device from `from_y` to `to_y` in `secs` (as `drive`), returning every fresh force
/// it read, in order.
fn drive_collect(device: &mut DeviceEnd, from_y: f64, to_y: f64, secs: f64) -> Vec<ServerForce> {
    let start = Instant::now();
    let mut forces = Vec::new();
    while start.elapsed().as_secs_f64() < secs {
        let a = start.elapsed().as_secs_f64() / secs;
        let y = from_y + (to_y - from_y) * a;
        device.write_pose_from_device(&DevicePose::planar(monotonic_ns(), [0.05, y, -std::f64::consts::FRAC_PI_2], 0)).unwrap();
        let f = device.read_force_from_device();
        if f.fresh()
            && let Some(v) = f.value
        {
            forces.push(v);
        }
        std::thread::sleep(Duration::from_micros(500));
    }
    forces
}

fn is_zero(f: &ServerForce) -> bool {
    f.force_n == [0.0; 3] && f.torque_nm == [0.0; 3] && f.stiffness.iter().flatten().all(|&v| v == 0.0)
}

/// Issue 20: while the device is suspended (a training session's instructor has control) it does
/// not drive, its poses are counted, it gets zero force and stiffness, and a client's pose moves
/// the needle; when the suspension is lifted the needle catches up with the device at
/// `DEVICE_CATCH_UP_M_PER_S` (one step per fresh device pose: the count is exact) and the force
/// ramps back.
#[test]
fn issue_20_a_suspended_device_does_not_drive_gets_zero_force_and_catches_up_after() {
    let scene = needlesim_scene::load_scene("paper-phantom", &MeshLimits::default()).unwrap();
    let dir = std::env::temp_dir().join(format!("needlesim-device-suspend-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = Session::start(&scene, 1000.0, Some(&dir)).unwrap();
    let mut device = DeviceChannel::attach(session.device_channel_path.clone().unwrap()).unwrap();
    let c = &session.counters;

    // The device inserts the needle 20 mm and feels the tissue.
    let f = drive(&mut device, 0.205, 0.185, 1.0).expect("forces arrive");
    assert!(!is_zero(&f) && f.force_n[1] > 0.1, "the tissue resists the insertion: {f:?}");
    assert!((session.latest_record().base.y_m - 0.185).abs() < 0.002);
    assert_eq!(c.device_poses_suspended.load(Ordering::Relaxed), 0, "nothing is set aside before a suspension");

    // Suspended: the device goes on 20 mm deeper; the needle stays, the device feels nothing.
    session.suspend_device_from_io(true);
    assert!(session.device_suspended());
    let suspended_before = c.device_poses_suspended.load(Ordering::Relaxed);
    std::thread::sleep(Duration::from_millis(20));
    let held = session.latest_record();
    let during = drive_collect(&mut device, 0.185, 0.165, 1.0);
    assert!(during.len() > 100, "forces keep coming while suspended: {}", during.len());
    assert!(during.iter().all(is_zero), "zero wrench and stiffness while suspended: {:?}", during.iter().find(|f| !is_zero(f)));
    assert!(during.iter().all(|f| f.state == ServerForce::STATE_OK && f.pose_counter == 0), "state OK, answering no device pose");
    let after = session.latest_record();
    assert!(after.tick > held.tick + 100, "the session kept ticking: {} → {}", held.tick, after.tick);
    assert_eq!(after.base.y_m, held.base.y_m, "the needle does not follow a suspended device");
    let set_aside = c.device_poses_suspended.load(Ordering::Relaxed) - suspended_before;
    assert!(set_aside > 100, "the suspended poses are counted: {set_aside}");
    assert!(!after.device_stale, "a suspended device that sends poses is not stale");

    // A client (the instructor) moves the needle meanwhile: to 10.23 mm above the device.
    session.write_client_pose_from_io(needlesim_session::PoseCommand {
        pose: needlesim_core::BasePose::new(0.05, 0.17523, -std::f64::consts::FRAC_PI_2),
        seq: 1,
        client_time_ns: 0,
    });
    let during = drive_collect(&mut device, 0.165, 0.165, 0.3);
    assert!(during.iter().all(is_zero));
    assert_eq!(session.latest_record().base.y_m, 0.17523, "the client's pose drives");

    // Lifted, the device held at 0.165: the needle catches up 10.23 mm at 50 µm a fresh pose (205
    // steps: 204 part of the way, the last one reaching — a gap away from a multiple of the step,
    // so that round-off cannot add one), the device feeling nothing until then, then the force
    // ramps back over 200 ticks.
    let catch_up_before = c.device_catch_up_poses.load(Ordering::Relaxed);
    session.suspend_device_from_io(false);
    let back = drive_collect(&mut device, 0.165, 0.165, 1.5);
    let rec = session.latest_record();
    assert!((rec.base.y_m - 0.165).abs() < 1e-12, "the needle has caught up with the device: {:?}", rec.base);
    let steps = c.device_catch_up_poses.load(Ordering::Relaxed) - catch_up_before;
    let step_m = needlesim_session::DEVICE_CATCH_UP_M_PER_S / 1000.0;
    let gap_m = 0.17523 - 0.165;
    assert_eq!(steps, (gap_m / step_m).ceil() as u64 - 1, "catch-up poses for {gap_m} m at {step_m} m a pose");
    let first_nonzero = back.iter().position(|f| !is_zero(f)).expect("the force comes back");
    // The catch-up takes 200 fresh device poses (one a device period): many zero forces first.
    assert!(first_nonzero > 50, "zero force while catching up: the first nonzero at {first_nonzero}");
    let last = back.last().unwrap();
    assert!(last.force_n[1] > 0.1 && last.stiffness[0][0] < 0.0, "full force again: {last:?}");
    // Some of the forces in between are part of the way up the ramp (the stiffness at the held
    // pose scaled by a gain in (0, 1)).
    let k_full = last.stiffness[0][0];
    let ramp = back[first_nonzero..].iter().filter(|f| f.stiffness[0][0] < 0.0 && f.stiffness[0][0] > 0.5 * k_full).count();
    assert!(ramp > 10, "the force ramps back: {ramp} forces below half the full stiffness");

    drop(device);
    session.close();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 20 in 3D: a suspended device's poses are set aside, and once lifted the needle catches
/// up with the device along the straight line at `DEVICE_CATCH_UP_M_PER_S` (the count of partial
/// steps exact) and ends exactly at its pose. Above the tissue (no contact: the compliance
/// worker's pace does not matter).
#[test]
fn issue_20_a_suspended_3d_device_catches_up_along_a_straight_line() {
    let scene = needlesim_scene::load_scene3d("cube-phantom-3d", &MeshLimits::default()).unwrap();
    let model = std::sync::Arc::new(scene.tissue_model().unwrap());
    let q = scene.initial_pose.quat_wxyz;
    let initial = needlesim_core::sim3::BasePose3::new([0.05, 0.05, 0.23], q).unwrap();
    let mut params = needlesim_core::sim3::Sim3Params::new(scene.needle.length_m, initial);
    params.regions = scene.regions.iter().map(|r| r.needle).collect();
    let dir = std::env::temp_dir().join(format!("needlesim-device-suspend3-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = Session::start3("cube-phantom-3d", model, params, vec![], Some(&dir)).unwrap();
    let mut device = DeviceChannel::attach(session.device_channel_path.as_ref().unwrap()).unwrap();
    let hold = |device: &mut DeviceEnd, p: [f64; 3], secs: f64| {
        let start = Instant::now();
        while start.elapsed().as_secs_f64() < secs {
            device
                .write_pose_from_device(&DevicePose { t_ns: monotonic_ns(), position_m: p, orientation: q, ..Default::default() })
                .unwrap();
            std::thread::sleep(Duration::from_micros(500));
        }
    };
    let base = |s: &Session| s.latest_record().d3.position_m;
    hold(&mut device, [0.05, 0.05, 0.23], 0.3);
    assert_eq!(base(&session), [0.05, 0.05, 0.23], "the device drives");
    session.suspend_device_from_io(true);
    std::thread::sleep(Duration::from_millis(20));
    // 6.123 mm in x and 8 mm up: 10.07… mm, off a multiple of the 50 µm step.
    let target = [0.05 + 0.006123, 0.05, 0.238];
    hold(&mut device, target, 0.5);
    assert_eq!(base(&session), [0.05, 0.05, 0.23], "a suspended device does not drive");
    assert!(session.counters.device_poses_suspended.load(Ordering::Relaxed) > 100);
    session.suspend_device_from_io(false);
    hold(&mut device, target, 1.0);
    let b = base(&session);
    assert!(b.iter().zip(&target).all(|(a, t)| (a - t).abs() < 1e-12), "caught up: {b:?}");
    let gap_m = (0.006123f64.powi(2) + 0.008f64.powi(2)).sqrt();
    let step_m = needlesim_session::DEVICE_CATCH_UP_M_PER_S / 1000.0;
    assert_eq!(session.counters.device_catch_up_poses.load(Ordering::Relaxed), (gap_m / step_m).ceil() as u64 - 1);
    drop(device);
    session.close();
    let _ = std::fs::remove_dir_all(&dir);
}
