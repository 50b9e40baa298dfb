//! A session's real-time thread allocates nothing inside a tick once warmed up: a counting global
//! allocator counts allocations made while `session::IN_TICK` is set, during a 3 s insertion at
//! 1 kHz driven through the shared-memory device channel, with observers attached; the
//! stiffness Jacobian is refreshed inside ticks too, and the fan-out's and the column worker's
//! doorbells are rung inside them (a wake is an unpark: no allocation).

use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use needlesim_alloc_count::{CountingAlloc, allocations};
use needlesim_channel::shm::{DeviceChannel, DevicePose, monotonic_ns};
use needlesim_core::{BasePose, MeshLimits};
use needlesim_session::{IN_TICK, Session, WARM_UP_TICKS};

/// Counting is on on whichever thread is inside a warm tick (the session sets `IN_TICK` there).
fn in_tick() -> bool {
    IN_TICK.with(|c| c.get())
}

#[global_allocator]
static GLOBAL: CountingAlloc = CountingAlloc::counting_when(in_tick);

/// The tests take turns: the allocation count is the process's.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[test]
fn real_time_ticks_allocate_nothing_after_warm_up() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let before = allocations();
    let scene = needlesim_scene::load_scene("paper-phantom", &MeshLimits::default()).unwrap();
    // Driven through the shared-memory device channel, as a haptic device bridge drives it.
    let dir = std::env::temp_dir().join(format!("needlesim-rt-alloc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = Session::start(&scene, 1000.0, Some(&dir)).unwrap();
    let mut device = DeviceChannel::attach(session.device_channel_path.as_ref().unwrap()).unwrap();
    let mut latest = session.latest.clone();
    let mut all = session.all_ticks.subscribe();
    let secs = 3.0;
    let start = Instant::now();
    let mut forces = 0;
    while start.elapsed().as_secs_f64() < secs + 0.3 {
        let t = start.elapsed().as_secs_f64().min(secs);
        let p = BasePose::new(0.05, 0.205 - 0.05 * t / secs, -std::f64::consts::FRAC_PI_2);
        device.write_pose_from_device(&DevicePose::planar(monotonic_ns(), [p.x_m, p.y_m, p.theta_rad], 0)).unwrap();
        forces += device.read_force_from_device().fresh() as u64;
        while all.try_recv().is_ok() {}
        let _ = latest.borrow_and_update();
        std::thread::sleep(Duration::from_micros(500));
    }
    let ticks = session.counters.ticks.load(Ordering::Relaxed);
    let rec = session.latest_record();
    drop(device);
    session.close();
    let _ = std::fs::remove_dir_all(&dir);
    println!(
        "{ticks} ticks, {forces} fresh forces read by the device, {} needle nodes at the end, {} allocations inside warm ticks",
        rec.n_nodes,
        allocations() - before
    );
    assert!(ticks > WARM_UP_TICKS + 2000, "the session ticked ({ticks})");
    assert!(forces > 1000, "the device read the server's forces");
    assert!(rec.n_nodes >= 5 && rec.force_axial_n < 0.0, "the device drove the needle into the tissue");
    assert!(rec.stiffness.iter().any(|v| *v != 0.0), "the stiffness is computed in ticks too");
    assert_eq!(session.counters.column_misses.load(Ordering::Relaxed), 0, "the worker delivered columns ahead of the tip");
    assert!(session.counters.fanout_wakes.load(Ordering::Relaxed) > 0, "the doorbell rang inside counted ticks");
    assert_eq!(allocations() - before, 0, "allocations inside real-time ticks");
}

/// The 3D session's parameters for a scene (as `needlesim_offline::simulate3::sim3_params`).
fn sim3_params(scene: &needlesim_scene::Scene3d) -> needlesim_core::sim3::Sim3Params {
    use needlesim_core::sim3::{BasePose3, Sim3Params, Target3};
    let initial = BasePose3::new(scene.initial_pose.position_m, scene.initial_pose.quat_wxyz).unwrap();
    let mut p = Sim3Params::new(scene.needle.length_m, initial);
    p.spacing_m = scene.needle.contact_spacing_m;
    p.regions = scene.regions.iter().map(|r| r.needle).collect();
    p.tick_rate_hz = scene.tick_rate_hz;
    p.max_contacts = scene.needle.max_points;
    p.targets =
        scene.targets.iter().enumerate().map(|(k, t)| Target3 { centre_m: t.center_m, radius_m: t.radius_m, name_idx: k }).collect();
    p
}

/// The same for a 3D session (the 48k-tetrahedron cube) driven by a 6-DOF device pose through a
/// channel of dimension 3, once with each compliance store: columns (the cube's default) and node
/// blocks (the large meshes' store, forced here), so that both workers' traffic is counted.
#[test]
fn real_time_3d_ticks_allocate_nothing_after_warm_up() {
    use needlesim_channel::shm::Dimension;
    use needlesim_core::sim3::StoreKind3;
    let scene = needlesim_scene::load_scene3d("cube-phantom-3d", &MeshLimits::default()).unwrap();
    let model = std::sync::Arc::new(scene.tissue_model().unwrap());
    let names: Vec<String> = scene.targets.iter().map(|t| t.name.clone()).collect();
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    for store in [StoreKind3::Columns, StoreKind3::NodeBlocks] {
        let before = allocations();
        let mut params = sim3_params(&scene);
        params.store = store;
        let dir = std::env::temp_dir().join(format!("needlesim-rt-alloc3-{}-{store:?}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let session = Session::start3("cube-phantom-3d", model.clone(), params, names.clone(), Some(&dir)).unwrap();
        let mut device = DeviceChannel::attach(session.device_channel_path.as_ref().unwrap()).unwrap();
        assert_eq!(device.session_dimension(), Some(Dimension::Three), "a 3D session's channel says so");
        let mut all = session.all_ticks.subscribe();
        let (secs, q) = (3.0, scene.initial_pose.quat_wxyz);
        let start = Instant::now();
        let mut forces = 0;
        while start.elapsed().as_secs_f64() < secs + 0.3 {
            let t = start.elapsed().as_secs_f64().min(secs);
            // From the tip 5 mm above the top face to 40 mm deep, straight down.
            let pose = DevicePose {
                t_ns: monotonic_ns(),
                position_m: [0.05, 0.05, 0.205 - 0.045 * t / secs],
                orientation: q,
                ..Default::default()
            };
            device.write_pose_from_device(&pose).unwrap();
            forces += device.read_force_from_device().fresh() as u64;
            while all.try_recv().is_ok() {}
            std::thread::sleep(Duration::from_micros(500));
        }
        let ticks = session.counters.ticks.load(Ordering::Relaxed);
        let rec = session.latest_record();
        let force = device.read_force_from_device().value.unwrap();
        drop(device);
        session.close();
        let _ = std::fs::remove_dir_all(&dir);
        println!(
            "{store:?}: {ticks} ticks, {forces} fresh forces, {} contact points, force {:?} N, {} allocations inside warm ticks",
            rec.d3.n_contacts,
            rec.d3.force_n,
            allocations() - before
        );
        assert!(ticks > WARM_UP_TICKS + 2000, "the session ticked ({ticks})");
        assert!(forces > 1000, "the device read the server's forces");
        assert!(rec.dimension == 3 && rec.d3.n_contacts >= 5, "the device drove the needle into the tissue");
        assert!(rec.d3.force_n[2] > 0.0, "the tissue pushes the needle back up: {:?}", rec.d3.force_n);
        assert!(rec.d3.stiffness.iter().flatten().any(|v| *v != 0.0), "the 6×6 stiffness is computed in ticks");
        assert!(
            force.stiffness.iter().flatten().any(|v| *v != 0.0) && force.force_n[2] > 0.0,
            "the device got the 3D wrench and stiffness"
        );
        assert_eq!(allocations() - before, 0, "allocations inside real-time 3D ticks ({store:?})");
    }
}
