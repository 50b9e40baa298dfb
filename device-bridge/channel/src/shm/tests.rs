//! The unit tests of the shared-memory channel.

use super::mapping::map;
use super::sigbus::REGISTRY;
use super::*;
use std::fs::{File, OpenOptions};
use std::os::unix::fs::{FileExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

fn temp_path(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    std::env::temp_dir().join(format!("needlesim-shm-test-{}-{n}-{name}", std::process::id()))
}

fn patch(path: &Path, offset: u64, bytes: &[u8]) {
    OpenOptions::new().write(true).open(path).unwrap().write_all_at(bytes, offset).unwrap();
}

fn at_x(x_m: f64) -> DevicePose {
    DevicePose { position_m: [x_m, 0.0, 0.0], ..Default::default() }
}

fn force(tick: u64) -> ServerForce {
    ServerForce {
        t_ns: monotonic_ns(),
        tick,
        force_n: [1.5, -2.5, 0.75],
        torque_nm: [0.25, -0.125, 0.0625],
        stiffness: std::array::from_fn(|r| std::array::from_fn(|c| (6 * r + c) as f64 * 10.0 + tick as f64)),
        base_position_m: [0.01, 0.02, -0.03],
        base_orientation: crate::spatial::quat_normalize([0.9, 0.1, -0.2, 0.3]).unwrap(),
        state: ServerForce::STATE_OK,
        pose_counter: tick + 7,
    }
}

#[test]
fn the_tick_phase_is_published_once_and_reset_by_a_new_channel() {
    let path = temp_path("phase");
    let mut server = DeviceChannel::create(&path).unwrap();
    let device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.server_schedule(), None, "nothing published yet");
    server.publish_schedule_from_rt(0, 1_000_000);
    assert_eq!(device.server_schedule(), None, "a zero origin is not published");
    server.publish_schedule_from_rt(123_456_789, 1_000_000);
    assert_eq!(device.server_schedule(), Some((Duration::from_nanos(123_456_789), Duration::from_millis(1))));
    // Re-created in place (a new session in the same file): the phase is gone with the old generation.
    let _server2 = DeviceChannel::create(&path).unwrap();
    assert_eq!(device.server_schedule(), None, "a stale end has no phase");
    let again = DeviceChannel::attach(&path).unwrap();
    assert_eq!(again.server_schedule(), None, "the new channel has not published its phase");
}

#[test]
fn round_trip_both_slots() {
    let path = temp_path("rt");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.generation(), server.generation());
    assert_eq!(server.attacher_pid(), Some(std::process::id()));
    assert_eq!(device.creator_pid(), std::process::id());

    // Nothing written yet: no value, not fresh, not alive.
    let s = server.read_pose_from_rt();
    assert_eq!((s.value, s.status), (None, ReadStatus::Unchanged));
    assert!(!server.device_alive(10));
    let f = device.read_force_from_device();
    assert_eq!((f.value, f.status), (None, ReadStatus::Unchanged));
    assert!(!device.server_alive(10));

    for k in 1..=3u64 {
        let pose = DevicePose {
            t_ns: monotonic_ns(),
            position_m: [0.1 * k as f64, -0.2, 0.05],
            orientation: crate::spatial::quat_normalize([0.5, -0.5, 0.25, 0.7]).unwrap(),
            buttons: 0b101,
            counter: 999,
        };
        assert_eq!(device.write_pose_from_device(&pose).unwrap(), k);
        let s = server.read_pose_from_rt();
        assert!(s.fresh());
        assert_eq!(s.reads_since_fresh, 0);
        assert_eq!(s.value, Some(DevicePose { counter: k, ..pose }));
        let again = server.read_pose_from_rt();
        assert_eq!((again.status, again.value, again.reads_since_fresh), (ReadStatus::Unchanged, s.value, 1));
        assert!(server.device_alive(1));
        assert!(!server.device_alive(0));

        let fw = force(100 + k);
        server.write_force_from_rt(&fw);
        let f = device.read_force_from_device();
        assert!(f.fresh());
        assert_eq!(f.value, Some(fw));
        assert!(device.server_alive(0));
        let again = device.read_force_from_device();
        assert_eq!((again.status, again.value), (ReadStatus::Unchanged, Some(fw)));
    }
    assert!(device.is_current());

    // Closing: the bridge sees state 2 and a closed, removed channel.
    drop(server);
    assert!(!path.exists());
    let f = device.read_force_from_device();
    assert_eq!(f.status, ReadStatus::Stale);
    assert_eq!(f.value.unwrap().state, ServerForce::STATE_CLOSING);
    assert_eq!(f.value.unwrap().tick, 103);
    assert!(!device.is_current());
    assert!(!device.server_alive(10));
    assert_eq!(device.write_pose_from_device(&DevicePose::default()), Err(Stale));
}

#[test]
fn stale_state_from_a_crashed_server_is_never_fresh() {
    let path = temp_path("stale");
    let mut old_server = DeviceChannel::create(&path).unwrap();
    let mut old_device = DeviceChannel::attach(&path).unwrap();
    old_server.write_force_from_rt(&force(7));
    old_device.write_pose_from_device(&at_x(1.0)).unwrap();
    let old_generation = old_server.generation();
    std::mem::forget(old_server); // crash: no cleanup, the mapping and the file stay
    assert!(path.exists());

    // A crashed server of another (dead) pid left the file: pretend so.
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    patch(&path, 32, &dead.to_le_bytes());

    let mut server = DeviceChannel::create(&path).unwrap();
    assert_ne!(server.generation(), old_generation);
    assert_eq!(std::fs::metadata(&path).unwrap().len(), CHANNEL_SIZE);

    // The old bridge end notices and refuses to write.
    assert!(!old_device.is_current());
    assert_eq!(old_device.read_force_from_device().status, ReadStatus::Stale);
    assert!(!old_device.server_alive(u64::MAX));
    assert_eq!(old_device.write_pose_from_device(&DevicePose::default()), Err(Stale));

    // The new server sees no pose; a new bridge sees no force.
    let s = server.read_pose_from_rt();
    assert_eq!((s.value, s.status), (None, ReadStatus::Unchanged));
    let mut device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.pose_counter(), 0);
    let f = device.read_force_from_device();
    assert_eq!((f.value, f.status), (None, ReadStatus::Unchanged));

    // A late write from a bridge of the old generation (raced past its is_current check) is ignored.
    // SAFETY-free way to simulate it: write into the slot with the old generation directly.
    old_device.m.layout().pose.write(old_generation, &at_x(9.0).encode(5));
    assert!(!server.read_pose_from_rt().fresh());

    // The new pair works.
    device.write_pose_from_device(&at_x(2.0)).unwrap();
    let s = server.read_pose_from_rt();
    assert!(s.fresh());
    assert_eq!(s.value.unwrap().position_m[0], 2.0);
    drop(old_device); // must not detach the new bridge
    assert_eq!(server.attacher_pid(), Some(std::process::id()));
}

#[test]
fn create_over_a_copied_leftover_file() {
    // A file copied from a live channel (same bytes as a crashed server would leave).
    let src = temp_path("copy-src");
    let path = temp_path("copy-dst");
    let mut server = DeviceChannel::create(&src).unwrap();
    server.write_force_from_rt(&force(3));
    std::fs::copy(&src, &path).unwrap();
    let mut fresh = DeviceChannel::create(&path).unwrap();
    assert_ne!(fresh.generation(), server.generation());
    assert!(!fresh.read_pose_from_rt().fresh());
    let mut device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.read_force_from_device().value, None);
    fresh.write_force_from_rt(&force(4));
    assert_eq!(device.read_force_from_device().value.unwrap().tick, 4);
}

#[test]
fn attach_errors_name_the_problem() {
    let missing = temp_path("missing");
    let e = DeviceChannel::attach(&missing).err().unwrap();
    assert!(matches!(e, ShmError::Missing { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains(&missing.display().to_string()) && msg.contains("no such file"), "{msg}");

    let short = temp_path("short");
    std::fs::write(&short, b"NDLSIMv1 too short").unwrap();
    let msg = DeviceChannel::attach(&short).err().unwrap().to_string();
    assert!(msg.contains(&short.display().to_string()) && msg.contains("is 18 bytes, expected 768"), "{msg}");

    let magic = temp_path("magic");
    let _server = DeviceChannel::create(&magic).unwrap();
    patch(&magic, 0, b"NOTMAGIC");
    let msg = DeviceChannel::attach(&magic).err().unwrap().to_string();
    assert!(msg.contains(&magic.display().to_string()) && msg.contains("wrong magic \"NOTMAGIC\""), "{msg}");

    let version = temp_path("version");
    let _server2 = DeviceChannel::create(&version).unwrap();
    patch(&version, 8, &7u32.to_le_bytes());
    let msg = DeviceChannel::attach(&version).err().unwrap().to_string();
    assert!(
        msg.contains(&version.display().to_string()) && msg.contains("layout version 7 (unknown to this build), this bridge speaks 3"),
        "{msg}"
    );

    let zeros = temp_path("zeros");
    std::fs::write(&zeros, [0u8; CHANNEL_SIZE as usize]).unwrap();
    let msg = DeviceChannel::attach(&zeros).err().unwrap().to_string();
    assert!(msg.contains(&zeros.display().to_string()) && msg.contains("not initialised yet"), "{msg}");

    let busy = temp_path("busy");
    let _server3 = DeviceChannel::create(&busy).unwrap();
    patch(&busy, 36, &1u32.to_le_bytes()); // pid 1 is always alive
    let msg = DeviceChannel::attach(&busy).err().unwrap().to_string();
    assert!(msg.contains("already attached by live pid 1"), "{msg}");

    let closed = temp_path("closed");
    let server4 = DeviceChannel::create(&closed).unwrap();
    let keep = std::fs::read(&closed).unwrap();
    drop(server4);
    let mut closed_bytes = keep;
    closed_bytes[40] = 1;
    std::fs::write(&closed, &closed_bytes).unwrap();
    let msg = DeviceChannel::attach(&closed).err().unwrap().to_string();
    assert!(msg.contains("closed by the server"), "{msg}");

    for p in [short, zeros, closed] {
        let _ = std::fs::remove_file(p);
    }
}

/// A channel file of the 2D-only layout (version 2, 512 bytes, as a server of the previous
/// release creates it, or leaves behind in /dev/shm): refused naming both versions, not the sizes.
#[test]
fn a_channel_of_the_previous_layout_is_refused_naming_both_versions() {
    let path = temp_path("layout-v2");
    let mut old = vec![0u8; 512];
    old[..8].copy_from_slice(&MAGIC);
    old[8..12].copy_from_slice(&2u32.to_le_bytes());
    old[16..24].copy_from_slice(&512u64.to_le_bytes());
    old[24..32].copy_from_slice(&0x1234u64.to_le_bytes());
    std::fs::write(&path, &old).unwrap();
    let e = DeviceChannel::attach(&path).err().unwrap();
    assert!(matches!(e, ShmError::WrongVersion { found: 2, expected: 3, .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("layout version 2 (2D pose and wrench, tick phase), this bridge speaks 3 (6-DOF pose"), "{msg}");
    // Version 1 likewise; a same-size file with another version is named too.
    old[8..12].copy_from_slice(&1u32.to_le_bytes());
    std::fs::write(&path, &old).unwrap();
    assert!(
        DeviceChannel::attach(&path).err().unwrap().to_string().contains("layout version 1 (2D pose and wrench), this bridge speaks 3")
    );
    // A server creating over the old file re-initialises it in the new layout.
    let server = DeviceChannel::create_with_dimension(&path, Dimension::Three).unwrap();
    assert_eq!(std::fs::metadata(&path).unwrap().len(), CHANNEL_SIZE);
    let device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.session_dimension(), Some(Dimension::Three));
    drop(device);
    drop(server);
    let _server2d = DeviceChannel::create(&path).unwrap();
    assert_eq!(DeviceChannel::attach(&path).unwrap().session_dimension(), Some(Dimension::Two));
}

/// A 6-DOF pose and wrench cross the channel bit for bit, and the 2D forms round-trip through it.
#[test]
fn six_dof_values_and_the_planar_forms_cross_intact() {
    let path = temp_path("6dof");
    let mut server = DeviceChannel::create_with_dimension(&path, Dimension::Three).unwrap();
    let mut device = DeviceChannel::attach(&path).unwrap();
    let q = crate::spatial::quat_normalize([0.3, -0.6, 0.2, 0.7]).unwrap();
    let pose = DevicePose { t_ns: 42, position_m: [0.011, -0.022, 0.033], orientation: q, buttons: 0b11, counter: 0 };
    device.write_pose_from_device(&pose).unwrap();
    let got = server.read_pose_from_rt().value.unwrap();
    assert_eq!(got, DevicePose { counter: 1, ..pose });
    let f = force(9);
    server.write_force_from_rt(&f);
    assert_eq!(device.read_force_from_device().value.unwrap(), f);

    // 2D through the 6-DOF fields.
    let planar = DevicePose::planar(7, [0.05, -0.01, -1.2], 1);
    device.write_pose_from_device(&planar).unwrap();
    let back = server.read_pose_from_rt().value.unwrap().to_planar();
    assert_eq!(&back[..2], &[0.05, -0.01]);
    assert!((back[2] + 1.2).abs() < 1e-15, "{back:?}");
    let mut f2 = ServerForce::default();
    let j: [f64; 9] = std::array::from_fn(|i| i as f64 - 4.5);
    f2.set_planar([0.5, -0.25, 0.002], &j, [0.05, -0.01, -1.2]);
    server.write_force_from_rt(&f2);
    let (w, k, base) = device.read_force_from_device().value.unwrap().to_planar();
    assert_eq!((w, k), ([0.5, -0.25, 0.002], j));
    assert!((base[2] + 1.2).abs() < 1e-15 && base[..2] == [0.05, -0.01], "{base:?}");
}

#[test]
fn file_mode_is_0600_even_over_an_existing_file() {
    let path = temp_path("mode");
    std::fs::write(&path, b"x").unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o666)).unwrap();
    let _server = DeviceChannel::create(&path).unwrap();
    let meta = std::fs::metadata(&path).unwrap();
    assert_eq!(meta.permissions().mode() & 0o777, 0o600);
    assert_eq!(meta.len(), CHANNEL_SIZE);
    let path2 = temp_path("mode-new");
    let _server2 = DeviceChannel::create(&path2).unwrap();
    assert_eq!(std::fs::metadata(&path2).unwrap().permissions().mode() & 0o777, 0o600);
}

#[test]
fn a_writer_that_died_mid_write_does_not_wedge_the_slot() {
    let path = temp_path("odd");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut device = DeviceChannel::attach(&path).unwrap();
    device.write_pose_from_device(&at_x(1.0)).unwrap();
    assert!(server.read_pose_from_rt().fresh());
    server.m.layout().pose.seq.fetch_add(1, Ordering::Relaxed); // odd: a write in progress forever
    let s = server.read_pose_from_rt();
    assert_eq!(s.status, ReadStatus::Contended);
    assert_eq!(s.value.unwrap().position_m[0], 1.0);
    drop(device);
    let mut device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.pose_counter(), 0); // the slot was mid-write: counter not readable, restart
    device.write_pose_from_device(&at_x(2.0)).unwrap();
    let s = server.read_pose_from_rt();
    assert!(s.fresh());
    assert_eq!(s.value.unwrap().position_m[0], 2.0);
}

#[test]
fn reattach_continues_the_counter_and_pid_alive_works() {
    let path = temp_path("reattach");
    let mut server = DeviceChannel::create(&path).unwrap();
    let mut device = DeviceChannel::attach(&path).unwrap();
    for _ in 0..5 {
        device.write_pose_from_device(&DevicePose::default()).unwrap();
    }
    drop(device);
    assert_eq!(server.attacher_pid(), None);
    let mut device = DeviceChannel::attach(&path).unwrap();
    assert_eq!(device.write_pose_from_device(&DevicePose::default()).unwrap(), 6);
    assert_eq!(server.read_pose_from_rt().value.unwrap().counter, 6);

    assert!(pid_alive(std::process::id()));
    assert!(pid_alive(1));
    assert!(!pid_alive(0));
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let pid = child.id();
    child.wait().unwrap();
    assert!(!pid_alive(pid));
}

/// The changes to a live channel's file of issue 13.
#[derive(Debug, Clone, Copy)]
enum Mutation {
    TruncateToZero,
    ShrinkToHalf,
    Grow,
    GarbageFill,
    Delete,
    /// A copy of the channel's bytes (a valid-looking header) renamed over the path.
    Replace,
}

const MUTATIONS: [Mutation; 6] =
    [Mutation::TruncateToZero, Mutation::ShrinkToHalf, Mutation::Grow, Mutation::GarbageFill, Mutation::Delete, Mutation::Replace];

fn mutate(path: &Path, m: Mutation) {
    let open = || OpenOptions::new().write(true).open(path).unwrap();
    match m {
        Mutation::TruncateToZero => open().set_len(0).unwrap(),
        Mutation::ShrinkToHalf => open().set_len(CHANNEL_SIZE / 2).unwrap(),
        Mutation::Grow => open().set_len(1 << 20).unwrap(),
        Mutation::GarbageFill => {
            // Same length, same inode: every byte overwritten (splitmix64 noise).
            let mut z = 0x1234_5678_9abc_def0u64;
            let bytes: Vec<u8> = (0..CHANNEL_SIZE / 8)
                .flat_map(|_| {
                    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
                    let mut x = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                    (x ^ (x >> 31)).to_le_bytes()
                })
                .collect();
            open().write_all_at(&bytes, 0).unwrap();
        }
        Mutation::Delete => std::fs::remove_file(path).unwrap(),
        Mutation::Replace => {
            let tmp = path.with_extension("replacement");
            std::fs::copy(path, &tmp).unwrap();
            std::fs::rename(&tmp, path).unwrap();
        }
    }
}

fn expected(m: Mutation) -> Broken {
    match m {
        Mutation::TruncateToZero => Broken::Faulted,
        Mutation::ShrinkToHalf => Broken::Resized { found_bytes: CHANNEL_SIZE / 2 },
        Mutation::Grow => Broken::Resized { found_bytes: 1 << 20 },
        Mutation::GarbageFill => Broken::BadHeader,
        Mutation::Delete => Broken::Deleted,
        Mutation::Replace => Broken::Replaced,
    }
}

fn pose(x_m: f64) -> DevicePose {
    DevicePose::planar(monotonic_ns(), [x_m, 0.1, 0.2], 0)
}

/// Every change to a live channel's file: neither end faults (this test process survives the
/// truncation, which killed it with SIGBUS before), both report the channel broken with the
/// cause, reads keep the last good value, writes are refused or harmless, and dropping the ends
/// removes the file only while the path still names it.
#[test]
fn issue_13_every_change_to_the_file_breaks_both_ends_without_a_fault() {
    for m in MUTATIONS {
        let path = temp_path(&format!("mutate-{m:?}"));
        let mut server = DeviceChannel::create(&path).unwrap();
        let mut device = DeviceChannel::attach(&path).unwrap();
        let (server_watch, device_watch) = (server.watch(), device.watch());
        device.write_pose_from_device(&pose(1.0)).unwrap();
        assert!(server.read_pose_from_rt().fresh(), "{m:?}");
        server.write_force_from_rt(&force(1));
        assert!(device.read_force_from_device().fresh(), "{m:?}");
        assert_eq!((server_watch.check_file(), device_watch.check_file()), (Ok(()), Ok(())), "{m:?}");

        mutate(&path, m);

        // Accesses first (a truncation faults on them), then the watchers (the rest).
        let s = server.read_pose_from_rt();
        server.write_force_from_rt(&force(2));
        let w = device.write_pose_from_device(&pose(2.0));
        let f = device.read_force_from_device();
        let _ = (server_watch.check_file(), device_watch.check_file());
        let want = expected(m);
        assert_eq!(server.broken(), Some(want), "{m:?}");
        assert_eq!(device.broken(), Some(want), "{m:?}");
        assert_eq!(server_watch.check_file(), Err(want), "{m:?}");
        assert_eq!(device_watch.check_file(), Err(want), "{m:?}");
        if matches!(m, Mutation::TruncateToZero | Mutation::GarbageFill) {
            // Found by the accesses themselves, no watcher needed.
            assert_eq!(s.status, ReadStatus::Broken, "{m:?}");
            assert_eq!(f.status, ReadStatus::Broken, "{m:?}");
            assert_eq!(w, Err(Stale), "{m:?}");
        }
        // From now on: broken, nothing read, the last good values kept.
        let s = server.read_pose_from_rt();
        assert_eq!(s.status, ReadStatus::Broken, "{m:?}");
        assert_eq!(s.value.map(|p| p.position_m[0]), Some(1.0), "{m:?}");
        assert!(!server.device_alive(u64::MAX), "{m:?}");
        server.write_force_from_rt(&force(3));
        let f = device.read_force_from_device();
        assert_eq!(f.status, ReadStatus::Broken, "{m:?}");
        // The accesses found truncation and garbage at once; the others only the watcher (a
        // shrink within the first page, a grown, deleted or replaced file still share memory).
        // (A shrink to half, 384 bytes, keeps the force slot's sequence and tick, which lie
        // below the new end of file, in the still-shared page: the write of tick 2 arrives.)
        let last_tick = if matches!(m, Mutation::TruncateToZero | Mutation::GarbageFill) { 1 } else { 2 };
        assert_eq!(f.value.map(|f| f.tick), Some(last_tick), "{m:?}");
        assert!(!device.is_current() && !device.server_alive(u64::MAX), "{m:?}");
        assert!(!device.closed_or_recreated(), "{m:?}: broken is not the normal end of a channel");
        assert_eq!(device.write_pose_from_device(&pose(3.0)), Err(Stale), "{m:?}");

        drop(device);
        drop(server);
        match m {
            // The replacement is someone else's file: it stays.
            Mutation::Replace => {
                assert!(path.exists(), "{m:?}");
                std::fs::remove_file(&path).unwrap();
            }
            // Our own file, whatever was done to it, is removed.
            _ => assert!(!path.exists(), "{m:?}: the server end left its broken file behind"),
        }
        // A watcher that outlives the ends keeps its verdict.
        assert_eq!(server_watch.check_file(), Err(want), "{m:?}");
    }
}

#[test]
fn issue_13_a_normal_close_is_not_reported_broken() {
    let path = temp_path("close-watch");
    let server = DeviceChannel::create(&path).unwrap();
    let device = DeviceChannel::attach(&path).unwrap();
    let (server_watch, device_watch) = (server.watch(), device.watch());
    drop(server); // closes and removes the file
    assert!(!path.exists());
    assert_eq!(server_watch.check_file(), Ok(()), "the server end's own close is no breakage");
    assert!(device.closed_or_recreated());
    assert!(!device.is_current());
    // The bridge's watcher sees the file gone: broken too, but the bridge reports the close first.
    assert_eq!(device_watch.check_file(), Err(Broken::Deleted));
}

#[test]
fn issue_13_a_file_truncated_while_attaching_or_creating_is_an_error_not_a_fault() {
    let path = temp_path("truncated-attach");
    let server = DeviceChannel::create(&path).unwrap();
    // A mapping of a zero-length file (as if truncated between attach's size check and its
    // reads): the header reads fault, and attach reports it.
    let file = OpenOptions::new().read(true).write(true).open(&path).unwrap();
    file.set_len(0).unwrap();
    let mapped = map(file, &path).unwrap();
    assert_eq!(mapped.check(false), Err(Broken::Faulted));
    assert!(mapped.faulted());
    assert_eq!(mapped.layout().header.magic.load(Ordering::Relaxed), 0, "the mapping now reads zeros");
    drop(mapped);
    let e = DeviceChannel::attach(&path).err().unwrap();
    assert!(matches!(e, ShmError::WrongSize { found: 0, .. }), "{e}");
    drop(server);
}

#[test]
fn issue_13_the_registry_is_reused_after_drop() {
    // More channels over time than registry slots, never more than a few at once.
    for i in 0..(MAX_MAPPINGS + 16) {
        let path = temp_path("registry");
        let server = DeviceChannel::create(&path).unwrap();
        assert!(server.broken().is_none(), "channel {i}");
    }
    let slots_in_use = REGISTRY.iter().filter(|s| s.start.load(Ordering::Relaxed) != 0).count();
    assert!(slots_in_use < 64, "{slots_in_use} registry slots still in use after every channel was dropped");
}

/// Issue 35 (L4): stale channel files piled up in /dev/shm. A sweep removes the channels whose
/// creator is gone and nothing else: not a live channel (its creator holds the owner lock),
/// not an unmarked channel of an earlier build that a live process maps, not a file under
/// another name, not a file that is not a channel, not a symbolic link; with a creator pid,
/// only that creator's.
#[test]
fn issue_35_a_sweep_removes_only_the_channels_whose_creator_is_gone() {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!("needlesim-sweep-{}-{}", std::process::id(), N.fetch_add(1, Ordering::Relaxed)));
    std::fs::create_dir(&dir).unwrap();
    let at = |id: &str| dir.join(format!("{CHANNEL_FILE_PREFIX}{id}"));
    let live = DeviceChannel::create(at("000000000001")).unwrap();
    let bytes = std::fs::read(live.path()).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[12..16].try_into().unwrap()), OWNER_LOCK, "create marks the header");
    let copy = |id: &str, patches: &[(usize, &[u8])]| {
        let mut b = bytes.clone();
        for (offset, with) in patches {
            b[*offset..*offset + with.len()].copy_from_slice(with);
        }
        std::fs::write(at(id), b).unwrap();
        at(id)
    };
    // A marked channel nobody holds: its creator is gone.
    let stale = copy("000000000002", &[]);
    // Unmarked (an earlier build's): gone unless a visible process maps it.
    let unmarked = copy("000000000003", &[(12, &0u32.to_le_bytes())]);
    let unmarked_mapped = copy("000000000004", &[(12, &0u32.to_le_bytes())]);
    let mapping = unsafe { memmap2::Mmap::map(&File::open(&unmarked_mapped).unwrap()) }.unwrap();
    // Another creator's stale channel: left by a sweep for this creator only.
    let other_creator = copy("000000000005", &[(32, &0x7fff_fff0u32.to_le_bytes())]);
    // Not ours to judge: other names, other contents, a link to a stale channel.
    let other_name = copy("shm-test-x", &[]);
    let upper_case = copy("00000000000A", &[]);
    let not_a_channel = at("000000000006");
    std::fs::write(&not_a_channel, [0x5Au8; 768]).unwrap();
    let target = copy("link-target", &[]);
    let link = at("000000000008");
    std::os::unix::fs::symlink(&target, &link).unwrap();

    let me = std::process::id();
    let sweep = remove_stale_channels(&dir, Some(me)).unwrap();
    assert!(sweep.errors.is_empty(), "{:?}", sweep.errors);
    let mut removed = sweep.removed.clone();
    removed.sort();
    assert_eq!(removed, vec![stale.clone(), unmarked.clone()]);
    assert_eq!(sweep.live, 2, "the live channel and the mapped unmarked one");
    for kept in [live.path(), &unmarked_mapped, &other_creator, &other_name, &upper_case, &not_a_channel, &target, &link] {
        assert!(std::fs::symlink_metadata(kept).is_ok(), "{} was removed", kept.display());
    }
    let sweep = remove_stale_channels(&dir, None).unwrap();
    assert_eq!(sweep.removed, vec![other_creator.clone()]);
    // The live channel keeps working, and its end removes its file when dropped.
    assert!(live.broken().is_none());
    let live_path = live.path().to_path_buf();
    drop(live);
    assert!(!live_path.exists());
    drop(mapping);
    assert_eq!(remove_stale_channels(&dir, None).unwrap().removed, vec![unmarked_mapped]);
    let _ = std::fs::remove_dir_all(&dir);
}
