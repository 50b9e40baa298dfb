//! Is the server process that created a channel still alive? (Issue 35, item 7: a bridge whose
//! server was `kill -9`ed ramped its force out but ran on, exited 0 and left the file.)
//!
//! A pid alone is not enough: pids are reused, a zombie still "exists" for `kill(pid, 0)`, and a
//! bridge in another pid namespace (another container of the pod, sharing only `/dev/shm`) sees
//! another process, or none, under the server's pid. So the bridge identifies the creator once, at
//! attach: the process with the header's pid whose memory maps the channel's file (its
//! `/proc/PID/maps` names the file's device and inode); if it is, its start time
//! (`/proc/PID/stat`, field 22) is kept. From then on the server is dead once `/proc/PID/stat` is
//! gone, names a process started at another time (the pid was reused), or says the process is a
//! zombie or dead (`Z`, `X`). If the creator cannot be identified at attach (another pid
//! namespace, `/proc` mounted with `hidepid`, a process that does not map the file), nothing is
//! concluded from the pid: the bridge's heartbeat (no fresh force for a while) still notices a
//! server that stopped answering. Everything here makes system calls: call it off the real-time thread.

/// A process as identified at attach: its pid and start time (clock ticks since boot).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProcessIdentity {
    pub pid: u32,
    pub start_ticks: u64,
}

/// What `/proc/PID/stat` says of a pid now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProcessState {
    /// The same process (same start time), not a zombie.
    Alive,
    /// Gone, a zombie, or another process under the same pid.
    Dead,
    /// `/proc` could not be read for another reason: nothing is concluded.
    Unknown,
}

/// (state letter, start time) from the text of `/proc/PID/stat`: the fields after the command
/// name, which is in parentheses and may itself hold spaces and parentheses.
fn parse_stat(text: &str) -> Option<(char, u64)> {
    let rest = &text[text.rfind(')')? + 1..];
    let mut fields = rest.split_ascii_whitespace();
    // Field 3 (state) is the first after the name; field 22 (starttime) the 20th.
    let state = fields.next()?.chars().next()?;
    let start = fields.nth(18)?.parse().ok()?;
    Some((state, start))
}

fn read_stat(pid: u32) -> Result<(char, u64), std::io::Error> {
    let text = std::fs::read_to_string(format!("/proc/{pid}/stat"))?;
    parse_stat(&text).ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidData, "unparsable /proc/PID/stat"))
}

/// True if a line of `/proc/PID/maps` maps the file of device `dev` and inode `ino`
/// (`address perms offset major:minor inode path`, the device in hex, the inode in decimal).
fn maps_file(maps: &str, dev: u64, ino: u64) -> bool {
    let (major, minor) = (libc::major(dev) as u64, libc::minor(dev) as u64);
    maps.lines().any(|line| {
        let mut f = line.split_ascii_whitespace();
        let (Some(device), Some(inode)) = (f.nth(3), f.next()) else { return false };
        let Some((ma, mi)) = device.split_once(':') else { return false };
        inode.parse::<u64>().ok() == Some(ino)
            && u64::from_str_radix(ma, 16).ok() == Some(major)
            && u64::from_str_radix(mi, 16).ok() == Some(minor)
    })
}

/// The process `pid` if it is alive, visible here, and maps the file (`dev`, `ino`): the creator
/// of the channel as this process can watch it. `None` when it cannot be told (see the module docs).
pub fn identify_mapper(pid: u32, dev: u64, ino: u64) -> Option<ProcessIdentity> {
    if pid == 0 {
        return None;
    }
    let (state, start_ticks) = read_stat(pid).ok()?;
    if matches!(state, 'Z' | 'X' | 'x') {
        return None;
    }
    let maps = std::fs::read_to_string(format!("/proc/{pid}/maps")).ok()?;
    maps_file(&maps, dev, ino).then_some(ProcessIdentity { pid, start_ticks })
}

/// True if a process visible here (`/proc/*/maps`) maps the file of device `dev` and inode `ino`.
/// Processes whose maps cannot be read (another user's, exiting) are not counted.
pub fn mapped_by_a_visible_process(dev: u64, ino: u64) -> bool {
    let Ok(procs) = std::fs::read_dir("/proc") else { return false };
    procs
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_str().is_some_and(|n| n.bytes().all(|b| b.is_ascii_digit())))
        .any(|e| std::fs::read_to_string(e.path().join("maps")).is_ok_and(|maps| maps_file(&maps, dev, ino)))
}

/// What became of a process identified earlier.
pub fn state_of(id: &ProcessIdentity) -> ProcessState {
    match read_stat(id.pid) {
        Ok((state, start)) if start == id.start_ticks && !matches!(state, 'Z' | 'X' | 'x') => ProcessState::Alive,
        Ok(_) => ProcessState::Dead,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => ProcessState::Dead,
        // ESRCH while reading a process that exits meanwhile.
        Err(e) if e.raw_os_error() == Some(libc::ESRCH) => ProcessState::Dead,
        Err(_) => ProcessState::Unknown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::MetadataExt;

    #[test]
    fn stat_fields_after_a_name_with_spaces_and_parentheses() {
        let text = "4242 (a (b) c) S 1 4242 4242 0 -1 4194560 100 0 0 0 1 2 0 0 20 0 3 0 987654 12345 67 18446744073709551615";
        assert_eq!(parse_stat(text), Some(('S', 987654)));
        assert_eq!(parse_stat("garbage"), None);
    }

    #[test]
    fn this_process_maps_a_file_it_mapped_and_is_alive_then_a_child_dies() {
        let path = std::env::temp_dir().join(format!("needlesim-liveness-{}", std::process::id()));
        std::fs::write(&path, [0u8; 4096]).unwrap();
        let file = std::fs::File::open(&path).unwrap();
        let meta = file.metadata().unwrap();
        let me = std::process::id();
        assert_eq!(identify_mapper(me, meta.dev(), meta.ino()), None, "not mapped yet");
        let map = unsafe { memmap2::Mmap::map(&file) }.unwrap();
        let id = identify_mapper(me, meta.dev(), meta.ino()).expect("this process maps the file");
        assert_eq!(state_of(&id), ProcessState::Alive);
        drop(map);
        let _ = std::fs::remove_file(&path);
        // Another start time under the same pid: another process.
        assert_eq!(state_of(&ProcessIdentity { pid: me, start_ticks: id.start_ticks + 1 }), ProcessState::Dead);
        // A child that exits: a zombie until reaped, then gone; dead both times.
        let mut child = std::process::Command::new("sleep").arg("0.2").spawn().unwrap();
        let (state, start_ticks) = read_stat(child.id()).unwrap();
        assert_ne!(state, 'Z');
        let child_id = ProcessIdentity { pid: child.id(), start_ticks };
        assert_eq!(state_of(&child_id), ProcessState::Alive);
        let t = std::time::Instant::now();
        while state_of(&child_id) == ProcessState::Alive {
            assert!(t.elapsed() < std::time::Duration::from_secs(30), "sleep 0.2 did not exit");
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        assert_eq!(state_of(&child_id), ProcessState::Dead, "a zombie is dead");
        child.wait().unwrap();
        assert_eq!(state_of(&child_id), ProcessState::Dead, "a reaped process is dead");
    }
}
