//! A helper process for the cross-process tests and benchmarks of the device channel (`needlesim_channel::shm`).
//!
//! `shm-probe write-poses PATH N`: attach, wait for the first force (the go signal), and write N poses at full speed, each with
//! `x = y = theta = counter` and `buttons = counter as u32`.
//! `shm-probe echo PATH`: attach and echo every fresh force's tick back as a pose with `x = tick`
//! until the force state is closing (or the channel goes stale); exit status 3 if the channel breaks.
//! `shm-probe foreign-sigbus PATH SCRATCH`: attach (installing the `SIGBUS` handler), then fault on a
//! truncated mapping of SCRATCH that is no channel: the process must die of `SIGBUS`.

use needlesim_channel::shm::{DeviceChannel, DevicePose, ReadStatus, ServerForce, monotonic_ns};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: shm-probe write-poses PATH N | shm-probe echo PATH | shm-probe foreign-sigbus PATH SCRATCH";
    let (mode, path) = match (args.get(1), args.get(2)) {
        (Some(m), Some(p)) => (m.as_str(), p.as_str()),
        _ => {
            eprintln!("{usage}");
            std::process::exit(2);
        }
    };
    let mut device = match DeviceChannel::attach(path) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("shm-probe: {e}");
            std::process::exit(1);
        }
    };
    match mode {
        "write-poses" => {
            let n: u64 = args.get(3).and_then(|s| s.parse().ok()).expect(usage);
            // Start together with the reader: wait for its first force (the "go").
            while !device.read_force_from_device().fresh() {
                std::hint::spin_loop();
            }
            for _ in 0..n {
                let c = (device.pose_counter() + 1) as f64;
                let pose = DevicePose { t_ns: monotonic_ns(), position_m: [c; 3], orientation: [c; 4], buttons: c as u32, counter: 0 };
                device.write_pose_from_device(&pose).expect("channel went stale");
            }
        }
        "echo" => loop {
            let f = device.read_force_from_device();
            // A broken channel may first show as stale or as a refused write (a truncation
            // between this read and the write): whichever way the loop ends, broken is exit 3.
            if f.status == ReadStatus::Broken || (f.status == ReadStatus::Stale && device.broken().is_some()) {
                eprintln!("shm-probe: channel broken: {}", device.broken().map_or("?".into(), |b| b.to_string()));
                std::process::exit(3);
            }
            if f.status == ReadStatus::Stale {
                break;
            }
            if let Some(force) = f.value {
                if force.state == ServerForce::STATE_CLOSING {
                    break;
                }
                if f.fresh() {
                    let pose = DevicePose { t_ns: monotonic_ns(), position_m: [force.tick as f64, 0.0, 0.0], ..Default::default() };
                    if device.write_pose_from_device(&pose).is_err() {
                        if let Some(b) = device.broken() {
                            eprintln!("shm-probe: channel broken: {b}");
                            std::process::exit(3);
                        }
                        break;
                    }
                }
            }
            std::hint::spin_loop();
        },
        "foreign-sigbus" => {
            // With the channel's SIGBUS handler installed, a fault on a mapping that is not a
            // channel must still kill the process (the handler chains to the default action).
            let scratch = args.get(3).expect(usage);
            let file = std::fs::OpenOptions::new().read(true).write(true).create(true).truncate(true).open(scratch).expect("scratch file");
            file.set_len(4096).expect("scratch size");
            let map = memmap2::MmapOptions::new().len(4096).map_raw(&file).expect("map the scratch file");
            file.set_len(0).expect("truncate the scratch file");
            // SAFETY: a valid mapping whose file was truncated: the read raises SIGBUS, the point of this mode.
            let v = unsafe { std::ptr::read_volatile(map.as_ptr()) };
            eprintln!("shm-probe: read {v} from a truncated foreign mapping without a fault");
            std::process::exit(4);
        }
        _ => {
            eprintln!("{usage}");
            std::process::exit(2);
        }
    }
}
