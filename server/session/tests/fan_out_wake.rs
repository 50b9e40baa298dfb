//! The fan-out and the column worker are woken by the real-time thread's doorbell, not by a poll
//! interval: over an insertion driven record by record, nearly every record reaches the observer
//! through a wake, and the fan-out's safety-net timeout is (almost) never what delivers one.
//! Counters only: no wall-time assertion (the machine is shared and noisy).

use std::sync::atomic::Ordering;

use needlesim_core::{BasePose, MeshLimits};
use needlesim_session::{PoseCommand, Session};

#[test]
fn records_reach_an_observer_by_a_wake_not_by_a_timeout() {
    let scene = needlesim_scene::load_scene("paper-phantom", &MeshLimits::default()).unwrap();
    let session = Session::start(&scene, 1000.0, None).unwrap();
    let mut all = session.all_ticks.subscribe();
    // 1500 records; each one received moves the needle 20 µm down (30 mm in all), so the tip
    // approaches nodes and the real-time thread asks the column worker for their columns.
    let mut received = 0u64;
    let mut last_tick = None;
    while received < 1500 {
        match all.blocking_recv() {
            Ok(rec) => {
                assert!(last_tick.is_none_or(|t| rec.tick > t), "ticks in order");
                last_tick = Some(rec.tick);
                received += 1;
                let y = 0.205 - 20e-6 * received as f64;
                session.write_pose_from_io(PoseCommand {
                    pose: BasePose::new(0.05, y, -std::f64::consts::FRAC_PI_2),
                    seq: received,
                    client_time_ns: 0,
                });
            }
            Err(tokio::sync::broadcast::error::RecvError::Lagged(n)) => received += n,
            Err(e) => panic!("the fan-out stopped: {e}"),
        }
    }
    // The session still runs: read the stats first, then the counters, which can only have grown.
    let stats = session.stats();
    let c = &session.counters;
    let (wakes, timeouts, column_wakes) =
        (c.fanout_wakes.load(Ordering::Relaxed), c.fanout_timeouts.load(Ordering::Relaxed), c.column_wakes.load(Ordering::Relaxed));
    session.close();
    println!("{received} records: {wakes} fan-out wakes, {timeouts} timeouts; {column_wakes} column worker wakes");
    assert!(
        stats.fanout_wakes > 0 && stats.fanout_wakes <= wakes && stats.fanout_timeouts <= timeouts,
        "the stats carry the counters: {stats:?}"
    );
    // Polling (or a doorbell that never rings) would deliver them all through timeouts: at most
    // one per FAN_OUT_TIMEOUT (20 ms), i.e. ≥ 75 timeouts and no wake for 1500 records.
    assert!(wakes > 0, "the real-time thread never woke the fan-out");
    assert!(wakes > 10 * timeouts, "records came through timeouts: {wakes} wakes, {timeouts} timeouts");
    assert!(column_wakes > 0, "the real-time thread never woke the column worker");
}
