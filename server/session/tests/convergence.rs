//! Issue 35: the live counterpart of an offline run that stops at a tick that did not converge:
//! the session faults there, its record carries zero force (a device is never left pushing an
//! unconverged answer), and it steps no more.

use std::time::{Duration, Instant};

use needlesim_core::{BasePose, MeshLimits};
use needlesim_session::{PoseCommand, Session};

#[test]
fn issue_35_a_live_session_whose_tick_does_not_converge_faults_with_zero_force() {
    // The paper's phantom with one stick/slip pass a tick: the first tick whose contacts change
    // state (the tip's puncture at the latest) ends at the cap, unconverged.
    let text = format!("{}\n[limits]\nmax_active_set_iterations = 1\n", include_str!("../../scenes/paper-phantom.toml"));
    let scene = needlesim_scene::parse_scene(&text, std::path::Path::new("."), &MeshLimits::default()).unwrap();
    let session = Session::start(&scene, 1000.0, None).unwrap();
    // Down 20 µm a millisecond (20 mm/s) from 5 mm above the top face, 105 mm at most, until
    // the session faults (30 s at most).
    let start = Instant::now();
    let mut seq = 0;
    while session.counters.fault().is_none() && start.elapsed() < Duration::from_secs(30) {
        seq += 1;
        let y = (0.205 - 20e-6 * seq as f64).max(0.1);
        session.write_pose_from_io(PoseCommand { pose: BasePose::new(0.05, y, -std::f64::consts::FRAC_PI_2), seq, client_time_ns: 0 });
        std::thread::sleep(Duration::from_millis(1));
    }
    let fault = session.counters.fault().expect("the session faulted at an unconverged tick");
    let message = fault.message();
    assert!(message.starts_with(&format!("tick {}: the tick did not converge", fault.tick)), "{message}");
    assert!(message.contains("stick/slip iteration stopped at its cap"), "{message}");
    // The faulted record is the last one: zero force, and no step after it.
    std::thread::sleep(Duration::from_millis(50));
    let rec = session.latest_record();
    assert_eq!(rec.fault.map(|f| f.message()), Some(message.clone()));
    assert_eq!((rec.tick, rec.force_n, rec.torque_nm, rec.force_axial_n), (fault.tick, [0.0; 2], 0.0, 0.0));
    assert_eq!(session.stats().fault, Some(message));
    session.close();
}
