//! Round-trip latency of the device channel: in-process (write + read of each slot) and cross-process ping-pong.
//!
//! `cargo bench -p needlesim-channel --bench shm` (set `SHM_BENCH_ITERS` to change the 1e6 iterations).

use std::process::Command;
use std::time::{Duration, Instant};

use needlesim_channel::shm::{DeviceChannel, DevicePose, ServerForce};

fn report(name: &str, mut ns: Vec<u64>) {
    ns.sort_unstable();
    let q = |p: f64| ns[((ns.len() - 1) as f64 * p) as usize];
    let mean = ns.iter().sum::<u64>() as f64 / ns.len() as f64;
    println!(
        "{name:<48} n={:<8} p50={:>6} ns  p99={:>6} ns  p99.9={:>7} ns  max={:>9} ns  mean={mean:>7.1} ns",
        ns.len(),
        q(0.5),
        q(0.99),
        q(0.999),
        ns[ns.len() - 1]
    );
}

fn main() {
    let iters: usize = std::env::var("SHM_BENCH_ITERS").ok().and_then(|s| s.parse().ok()).unwrap_or(1_000_000);
    let path = std::env::temp_dir().join(format!("needlesim-shm-bench-{}", std::process::id()));

    // In-process: one write + one read of each slot (the clock read costs ~20 ns of each sample).
    {
        let mut server = DeviceChannel::create(&path).unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        let mut force = ServerForce::default();
        let mut pose = DevicePose::default();
        let (mut f_ns, mut p_ns) = (Vec::with_capacity(iters), Vec::with_capacity(iters));
        for i in 0..iters {
            force.tick = i as u64;
            let t = Instant::now();
            server.write_force_from_rt(&force);
            let f = device.read_force_from_device();
            let dt = t.elapsed();
            assert!(f.fresh());
            f_ns.push(dt.as_nanos() as u64);
            pose.position_m[0] = i as f64;
            let t = Instant::now();
            device.write_pose_from_device(&pose).unwrap();
            let p = server.read_pose_from_rt();
            let dt = t.elapsed();
            assert!(p.fresh());
            p_ns.push(dt.as_nanos() as u64);
        }
        report("in-process force write+read (server→device)", f_ns);
        report("in-process pose write+read (device→server)", p_ns);
        let t = Instant::now();
        for _ in 0..1000 {
            std::hint::black_box(Instant::now());
        }
        println!("(Instant::now overhead ≈ {} ns per sample)", t.elapsed().as_nanos() / 1000);
    }

    // Cross-process ping-pong: force tick i → probe → pose x = i.
    {
        let mut server = DeviceChannel::create(&path).unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_shm-probe")).args(["echo", path.to_str().unwrap()]).spawn().unwrap();
        let t0 = Instant::now();
        while server.attacher_pid() != Some(child.id()) {
            assert!(t0.elapsed() < Duration::from_secs(20), "probe did not attach");
            std::thread::sleep(Duration::from_micros(100));
        }
        let mut force = ServerForce::default();
        let mut ns = Vec::with_capacity(iters);
        for i in 1..=iters as u64 {
            force.tick = i;
            let t = Instant::now();
            server.write_force_from_rt(&force);
            loop {
                let s = server.read_pose_from_rt();
                if s.fresh() && s.value.unwrap().position_m[0] == i as f64 {
                    break;
                }
                std::hint::spin_loop();
            }
            ns.push(t.elapsed().as_nanos() as u64);
        }
        report("cross-process ping-pong (force → echo pose)", ns);
        drop(server);
        child.wait().unwrap();
    }
}
