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

#[test]
fn real_time_ticks_allocate_nothing_after_warm_up() {
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
        allocations()
    );
    assert!(ticks > WARM_UP_TICKS + 2000, "the session ticked ({ticks})");
    assert!(forces > 1000, "the device read the server's forces");
    assert!(rec.n_nodes >= 5 && rec.force_axial_n < 0.0, "the device drove the needle into the tissue");
    assert!(rec.stiffness.iter().any(|v| *v != 0.0), "the stiffness is computed in ticks too");
    assert_eq!(session.counters.column_misses.load(Ordering::Relaxed), 0, "the worker delivered columns ahead of the tip");
    assert!(session.counters.fanout_wakes.load(Ordering::Relaxed) > 0, "the doorbell rang inside counted ticks");
    assert_eq!(allocations(), 0, "allocations inside real-time ticks");
}
