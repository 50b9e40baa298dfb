//! Cross-process tests of the device channel: a real second process (`shm-probe`) writes while this one reads.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use needlesim_channel::shm::{Broken, DeviceChannel, ReadStatus, ServerForce, monotonic_ns};

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("needlesim-shm-it-{}-{name}", std::process::id()))
}

/// Wait until the probe has attached (its pid shows up in the header).
fn wait_attached(server: &needlesim_channel::shm::ServerEnd, pid: u32) {
    let t0 = Instant::now();
    while server.attacher_pid() != Some(pid) {
        assert!(t0.elapsed() < Duration::from_secs(20), "probe did not attach");
        std::thread::sleep(Duration::from_micros(100));
    }
}

#[test]
fn cross_process_poses_are_never_torn() {
    // 10 000 writes take well under a scheduler time slice here (2 shared, busy cores), so the reader
    // often catches only the last one; 300 000 gives it many chances to land mid-stream.
    const N: u64 = 300_000;
    let path = temp_path("poses");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_shm-probe"))
        .args(["write-poses", path.to_str().unwrap(), &N.to_string()])
        .stderr(Stdio::inherit())
        .spawn()
        .unwrap();
    wait_attached(&server, child.id());
    server.write_force_from_rt(&ServerForce { tick: 1, ..Default::default() }); // go
    let (mut fresh, mut contended, mut last) = (0u64, 0u64, 0u64);
    let t0 = Instant::now();
    loop {
        let s = server.read_pose_from_rt();
        match s.status {
            needlesim_channel::shm::ReadStatus::Contended => contended += 1,
            _ if s.fresh() => {
                fresh += 1;
                let p = s.value.unwrap();
                let c = p.counter as f64;
                assert!(p.position_m == [c; 3] && p.orientation == [c; 4] && p.buttons == p.counter as u32, "torn read: {p:?}");
                assert!(p.counter > last, "counter went back: {} after {last}", p.counter);
                last = p.counter;
            }
            _ => {}
        }
        if last == N {
            break;
        }
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "probe failed: {status}");
            // Child is done: one more read must see the final value.
            let s = server.read_pose_from_rt();
            if let Some(p) = s.value {
                last = last.max(p.counter);
            }
            assert_eq!(last, N);
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "timed out at counter {last}");
    }
    assert!(child.wait().unwrap().success());
    eprintln!("cross-process: {fresh} fresh reads of {N} writes, {contended} contended, last counter {last}");
    // How many writes the reader catches depends on scheduling; a writer writing back to back keeps the
    // sequence odd most of the time, so most reads here are `Contended` (they return the last good value).
    assert!(fresh >= 1);
}

#[test]
fn cross_process_ping_pong_both_slots() {
    const ROUNDS: u64 = 2_000;
    let path = temp_path("pingpong");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_shm-probe")).args(["echo", path.to_str().unwrap()]).spawn().unwrap();
    wait_attached(&server, child.id());
    let mut force = ServerForce { stiffness: [[1.0; 6]; 6], ..Default::default() };
    let t0 = Instant::now();
    for tick in 1..=ROUNDS {
        force.tick = tick;
        force.t_ns = monotonic_ns();
        server.write_force_from_rt(&force);
        loop {
            let s = server.read_pose_from_rt();
            if s.fresh() && s.value.unwrap().position_m[0] == tick as f64 {
                break;
            }
            assert!(t0.elapsed() < Duration::from_secs(60), "no echo of tick {tick}");
            std::hint::spin_loop();
        }
        assert!(server.device_alive(0));
    }
    let echoed = server.read_pose_from_rt().value.unwrap();
    assert_eq!(echoed.counter, ROUNDS);
    drop(server); // state = closing: the probe exits
    assert!(child.wait().unwrap().success());
    assert!(!path.exists());
}

#[test]
fn bridge_notices_a_recreated_channel_across_processes() {
    let path = temp_path("recreate");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_shm-probe")).args(["echo", path.to_str().unwrap()]).spawn().unwrap();
    wait_attached(&server, child.id());
    server.write_force_from_rt(&ServerForce { tick: 1, ..Default::default() });
    std::mem::forget(server); // crash
    let mut server = DeviceChannel::create(&path).unwrap(); // re-create in place: the probe sees Stale and exits
    let status = child.wait().unwrap();
    assert!(status.success());
    assert!(!server.read_pose_from_rt().fresh());
    assert_eq!(server.attacher_pid(), None);
}

/// Issue 13: truncating the channel file under both processes killed them with SIGBUS. Now the
/// server end (this test process) keeps running and reports the channel broken, and the probe on
/// the other end exits on its own with its "broken" status (3), not by a signal.
#[test]
fn issue_13_a_truncated_channel_kills_neither_process() {
    use std::os::unix::process::ExitStatusExt;
    let path = temp_path("truncate");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_shm-probe")).args(["echo", path.to_str().unwrap()]).spawn().unwrap();
    wait_attached(&server, child.id());
    // A few echoed ticks: both ends are live on the mapping.
    let t0 = Instant::now();
    for tick in 1..=50u64 {
        server.write_force_from_rt(&ServerForce { tick, t_ns: monotonic_ns(), ..Default::default() });
        while !(server.read_pose_from_rt().value.is_some_and(|p| p.position_m[0] == tick as f64)) {
            assert!(t0.elapsed() < Duration::from_secs(30), "no echo of tick {tick}");
            std::hint::spin_loop();
        }
    }
    std::fs::OpenOptions::new().write(true).open(&path).unwrap().set_len(0).unwrap();
    // The server end keeps going through the fault: writes and reads are harmless.
    for tick in 51..=100u64 {
        server.write_force_from_rt(&ServerForce { tick, t_ns: monotonic_ns(), ..Default::default() });
        let s = server.read_pose_from_rt();
        assert_eq!(s.status, ReadStatus::Broken, "tick {tick}");
    }
    assert_eq!(server.broken(), Some(Broken::Faulted));
    let status = child.wait().unwrap();
    assert_eq!(status.signal(), None, "the probe was killed by signal {:?}", status.signal());
    assert_eq!(status.code(), Some(3), "the probe did not report a broken channel: {status}");
    drop(server);
    assert!(!path.exists(), "the server end removes its truncated file");
}

/// The SIGBUS handler only takes faults on channel mappings: a fault on any other mapping (a
/// genuine bug) still kills the process with SIGBUS.
#[test]
fn issue_13_a_fault_outside_any_channel_still_kills_the_process() {
    use std::os::unix::process::ExitStatusExt;
    let path = temp_path("foreign");
    let scratch = temp_path("foreign-scratch");
    let _server = DeviceChannel::create(&path).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_shm-probe"))
        .args(["foreign-sigbus", path.to_str().unwrap(), scratch.to_str().unwrap()])
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let _ = std::fs::remove_file(&scratch);
    assert_eq!(out.status.signal(), Some(libc::SIGBUS), "{:?}: {}", out.status, String::from_utf8_lossy(&out.stderr));
}
