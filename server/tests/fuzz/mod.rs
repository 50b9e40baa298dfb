//! A small mutation fuzzer for the parser harness (`fuzz_parsers.rs`): seeded, structure-aware
//! mutations of real seed files, a per-thread peak-memory cap enforced by the global allocator,
//! a hang detector, and a bounded or time-budgeted run with per-case seeds that replay.
//!
//! Why not cargo-fuzz or proptest: cargo-fuzz needs a nightly toolchain, and what finds bugs in
//! these parsers is mutating their real inputs line- and field-wise (numbers swapped for 1e308,
//! NaN, huge counts; lines deleted, duplicated, spliced), which a generic byte or value
//! generator does not do; a seeded loop over such mutators runs under plain `cargo test` and,
//! with a time budget, as a long fuzzing run, and each failure names a seed that replays it.
//!
//! Environment:
//! - `NEEDLESIM_FUZZ_CASES`: cases per parser in a bounded run (default: each target's own count).
//! - `NEEDLESIM_FUZZ_SEED`: the base seed (default [`DEFAULT_SEED`]).
//! - `NEEDLESIM_FUZZ_SECONDS`: the CPU time (of the fuzzing thread) each parser gets in the on-demand run (the ignored test);
//!   `NEEDLESIM_FUZZ_TARGETS`: which parsers it runs (comma separated; default all).
//! - `NEEDLESIM_FUZZ_REPLAY=parser:seed`: runs only that case of that parser and prints its input.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::io::Write as _;
use std::panic::AssertUnwindSafe;
use std::time::{Duration, Instant};

use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// The base seed of a run when `NEEDLESIM_FUZZ_SEED` is not set.
pub const DEFAULT_SEED: u64 = 0x6e65_6564_6c65;
/// The most memory one case may hold at once (bytes allocated and not yet freed on its thread).
pub const MEMORY_CAP_BYTES: usize = 512 << 20;
/// A case whose thread spends longer than this on the CPU is reported as a hang (a generous
/// bound: cases take milliseconds; this only catches loops that do not end). CPU time, not wall
/// time: a long run beside builds (niced, load 4–12) saw an 880 kB msh3d case take 17.4 s of
/// wall time that replays in 0.45 s of CPU (issue 35).
pub const HANG_LIMIT: Duration = Duration::from_secs(10);
/// A case that takes longer than this in wall time is reported as a hang whatever its CPU time
/// (a case blocked on something).
pub const WALL_HANG_LIMIT: Duration = Duration::from_secs(300);

/// The CPU time this thread has used.
fn thread_cpu_time() -> Duration {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the struct it is given; CLOCK_THREAD_CPUTIME_ID is always there on Linux.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID)");
    Duration::new(u64::try_from(ts.tv_sec).unwrap_or(0), u32::try_from(ts.tv_nsec).unwrap_or(0))
}

// ---------------------------------------------------------------------------------------------
// Memory: a global allocator that tracks, per thread, the live and peak bytes of the running case.

/// Counts the bytes each fuzzing thread holds while a case runs; an allocation that would take
/// it over [`MEMORY_CAP_BYTES`] is refused (the process then aborts, after this prints which case).
pub struct CappedAlloc;

thread_local! {
    static ARMED: Cell<bool> = const { Cell::new(false) };
    static LIVE: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
    static CASE: Cell<(&'static str, u64)> = const { Cell::new(("", 0)) };
}

impl CappedAlloc {
    /// Whether this thread may take `size` more bytes.
    fn admit(size: usize) -> bool {
        if !ARMED.try_with(Cell::get).unwrap_or(false) {
            return true;
        }
        let live = LIVE.with(Cell::get).saturating_add(size);
        if live > MEMORY_CAP_BYTES {
            ARMED.with(|a| a.set(false));
            let (name, seed) = CASE.with(Cell::get);
            let mut msg = [0u8; 320];
            let mut w = &mut msg[..];
            let _ = write!(
                w,
                "\nfuzz: parser {name}, case seed {seed:#x}: an allocation of {size} bytes takes the case over the \
                 {MEMORY_CAP_BYTES}-byte cap; replay with NEEDLESIM_FUZZ_REPLAY={name}:{seed:#x}\n"
            );
            let n = 320 - w.len();
            let _ = std::io::stderr().write_all(&msg[..n]);
            return false;
        }
        LIVE.with(|l| l.set(live));
        PEAK.with(|p| p.set(p.get().max(live)));
        true
    }
    fn release(size: usize) {
        if ARMED.try_with(Cell::get).unwrap_or(false) {
            LIVE.with(|l| l.set(l.get().saturating_sub(size)));
        }
    }
}

unsafe impl GlobalAlloc for CappedAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !Self::admit(layout.size()) {
            return std::ptr::null_mut();
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !Self::admit(layout.size()) {
            return std::ptr::null_mut();
        }
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        Self::release(layout.size());
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() && !Self::admit(new_size - layout.size()) {
            return std::ptr::null_mut();
        }
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size < layout.size() && !p.is_null() {
            Self::release(layout.size() - new_size);
        }
        p
    }
}

// ---------------------------------------------------------------------------------------------
// Targets and runs

/// How one case turned out, from a target's check.
pub type Verdict = Result<(), String>;

/// One parser under test.
pub struct Target {
    /// Short name, used in messages and `NEEDLESIM_FUZZ_REPLAY`.
    pub name: &'static str,
    /// Real inputs to mutate (at least one).
    pub seeds: Vec<Vec<u8>>,
    /// Tokens the mutator splices in (section markers, keys, separators).
    pub dict: Vec<Vec<u8>>,
    /// Grammar-aware generator of whole inputs, used for a part of the cases when present.
    pub generate: Option<fn(&mut SmallRng) -> Vec<u8>>,
    /// Extra structure-aware mutation (e.g. PNG chunks with their checksums fixed).
    pub mutate: Option<fn(&mut SmallRng, &mut Vec<u8>)>,
    /// Runs the parser on an input: `Ok` when it returned a valid result or an error with a
    /// message, `Err(why)` when the result is invalid or the error says nothing.
    pub check: fn(&[u8]) -> Verdict,
    /// Cases in a bounded run.
    pub cases: u64,
}

/// What a run of one target did.
#[derive(Debug, Default, Clone, Copy)]
pub struct Stats {
    pub cases: u64,
    /// Cases the parser accepted (the rest were rejected with an error).
    pub accepted: u64,
    pub peak_bytes: usize,
    /// The most CPU time one case took.
    pub slowest: Duration,
}

fn env_u64(name: &str) -> Option<u64> {
    let v = std::env::var(name).ok()?;
    let v = v.trim();
    let parsed = match v.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => v.parse(),
    };
    Some(parsed.unwrap_or_else(|_| panic!("{name} = {v:?} is not an integer")))
}

/// The base seed of this run.
pub fn base_seed() -> u64 {
    env_u64("NEEDLESIM_FUZZ_SEED").unwrap_or(DEFAULT_SEED)
}

fn case_seed(base: u64, name: &str, i: u64) -> u64 {
    // FNV-1a of the name, so parsers draw different streams from one base seed.
    let h = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    (base ^ h).wrapping_add(i.wrapping_mul(0x9e37_79b9_7f4a_7c15))
}

impl Target {
    /// The input of the case with this seed.
    pub fn input(&self, seed: u64) -> Vec<u8> {
        let mut rng = SmallRng::seed_from_u64(seed);
        let mut data = match self.generate {
            Some(g) if rng.random_bool(0.3) => g(&mut rng),
            _ => self.seeds[rng.random_range(0..self.seeds.len())].clone(),
        };
        // Some cases stay unmutated (a generated input, or a seed that must parse).
        let n_mutations = [0, 1, 1, 1, 2, 2, 3, 4, 6, 10][rng.random_range(0..10)];
        for _ in 0..n_mutations {
            match self.mutate {
                Some(m) if rng.random_bool(0.5) => m(&mut rng, &mut data),
                _ => mutate(&mut rng, &mut data, &self.seeds, &self.dict),
            }
        }
        data
    }

    /// Runs one case: the parser must not panic, hang or exceed the memory cap, and its verdict
    /// must be `Ok`. Returns whether the parser accepted the input, or the failure.
    pub fn run_case(&self, seed: u64, stats: &mut Stats) -> Result<(), String> {
        let input = self.input(seed);
        CASE.with(|c| c.set((self.name, seed)));
        LIVE.with(|l| l.set(0));
        PEAK.with(|p| p.set(0));
        ACCEPTED.with(|a| a.set(false));
        ARMED.with(|a| a.set(true));
        let (t0, cpu0) = (Instant::now(), thread_cpu_time());
        let outcome = std::panic::catch_unwind(AssertUnwindSafe(|| (self.check)(&input)));
        let (took, cpu) = (t0.elapsed(), thread_cpu_time().saturating_sub(cpu0));
        ARMED.with(|a| a.set(false));
        let peak = PEAK.with(Cell::get);
        stats.cases += 1;
        stats.accepted += u64::from(ACCEPTED.with(Cell::get));
        stats.peak_bytes = stats.peak_bytes.max(peak);
        stats.slowest = stats.slowest.max(cpu);
        let failure = match outcome {
            Err(p) => {
                let msg = p.downcast_ref::<String>().cloned().or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()));
                Some(format!("panicked: {}", msg.unwrap_or_default()))
            }
            Ok(Err(why)) => Some(why),
            Ok(Ok(())) if cpu > HANG_LIMIT || took > WALL_HANG_LIMIT => {
                Some(format!("took {cpu:?} of CPU time ({took:?} of wall time), over the {HANG_LIMIT:?} ({WALL_HANG_LIMIT:?}) hang limit"))
            }
            Ok(Ok(())) => None,
        };
        match failure {
            None => Ok(()),
            Some(why) => {
                let dir = std::env::temp_dir().join("needlesim-fuzz-failures");
                let _ = std::fs::create_dir_all(&dir);
                let file = dir.join(format!("{}-{seed:#x}.bin", self.name));
                let _ = std::fs::write(&file, &input);
                Err(format!(
                    "parser {}, case seed {seed:#x}: {why}\n  input ({} bytes) saved to {}; replay with NEEDLESIM_FUZZ_REPLAY={}:{seed:#x}",
                    self.name,
                    input.len(),
                    file.display(),
                    self.name
                ))
            }
        }
    }

    /// A bounded, seeded run (or the one case of `NEEDLESIM_FUZZ_REPLAY`); panics on the first failure.
    pub fn run_bounded(&self) -> Stats {
        let mut stats = Stats::default();
        if let Ok(replay) = std::env::var("NEEDLESIM_FUZZ_REPLAY") {
            let Some((name, seed)) = replay.split_once(':') else { panic!("NEEDLESIM_FUZZ_REPLAY must be parser:seed") };
            if name == self.name {
                let seed = u64::from_str_radix(seed.trim_start_matches("0x"), 16).expect("a hexadecimal seed");
                eprintln!("replaying {name}:{seed:#x}; input:\n{}", String::from_utf8_lossy(&self.input(seed)));
                self.run_case(seed, &mut stats).unwrap_or_else(|e| panic!("{e}"));
            }
            return stats;
        }
        let base = base_seed();
        let cases = env_u64("NEEDLESIM_FUZZ_CASES").unwrap_or(self.cases);
        for i in 0..cases {
            self.run_case(case_seed(base, self.name, i), &mut stats).unwrap_or_else(|e| panic!("{e}"));
        }
        eprintln!(
            "fuzz {}: {} cases ({} accepted), base seed {base:#x}, peak {:.1} MB, slowest {:?} CPU",
            self.name,
            stats.cases,
            stats.accepted,
            stats.peak_bytes as f64 / 1e6,
            stats.slowest
        );
        assert!(stats.accepted > 0, "fuzz {}: no case was accepted: the seeds or the check are wrong", self.name);
        stats
    }
}

/// How much CPU time [`run_for`] gives one parser before moving to the next.
const SLICE: Duration = Duration::from_millis(200);

/// Runs every target in turn on this thread, an equal share of `budget` (CPU time of this thread)
/// each; returns the failures (each with its seed) and the counts.
pub fn run_for(targets: &[Target], budget: Duration) -> (Vec<String>, Vec<Stats>) {
    let base = base_seed();
    // The budget is this thread's CPU time, not wall time: a run beside builds on a shared
    // machine got ~2 minutes of CPU in 30 minutes of wall time (issue 35), which is not a
    // 30-minute fuzzing run. Wall time is printed beside it.
    let start_cpu = thread_cpu_time();
    let start_wall = Instant::now();
    let mut stats = vec![Stats::default(); targets.len()];
    let mut failures = Vec::new();
    let mut next_report = Duration::from_secs(60);
    let mut next_case = vec![0u64; targets.len()];
    while thread_cpu_time() - start_cpu < budget {
        // Equal CPU time, not equal counts: each parser in turn for a slice of SLICE.
        for ((t, s), i) in targets.iter().zip(&mut stats).zip(&mut next_case) {
            let slice = thread_cpu_time();
            while thread_cpu_time() - slice < SLICE {
                if let Err(e) = t.run_case(case_seed(base, t.name, *i), s) {
                    eprintln!("FAILURE {e}");
                    failures.push(e);
                }
                *i += 1;
            }
        }
        let cpu = thread_cpu_time() - start_cpu;
        if cpu >= next_report {
            next_report += Duration::from_secs(60);
            let counts: Vec<String> = targets.iter().zip(&stats).map(|(t, s)| format!("{} {}", t.name, s.cases)).collect();
            eprintln!("fuzz {:.0?} CPU, {:.0?} wall: {}; {} failures", cpu, start_wall.elapsed(), counts.join(", "), failures.len());
        }
    }
    eprintln!("fuzz done: {:.1?} CPU in {:.1?} wall", thread_cpu_time() - start_cpu, start_wall.elapsed());
    (failures, stats)
}

/// Marks the running case as accepted (the parser returned a valid result).
pub fn accepted() {
    ACCEPTED.with(|a| a.set(true));
}

thread_local! {
    static ACCEPTED: Cell<bool> = const { Cell::new(false) };
}

// ---------------------------------------------------------------------------------------------
// Mutations

/// Numbers that break parsers: extremes, non-finite spellings, huge counts, off-by-ones.
const EXTREMES: &[&str] = &[
    "0",
    "-0",
    "1",
    "-1",
    "2",
    "3",
    "0.5",
    "1e308",
    "-1e308",
    "1e999",
    "-1e999",
    "1e-320",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "Infinity",
    "4294967295",
    "4294967296",
    "2147483648",
    "9223372036854775807",
    "-9223372036854775808",
    "9223372036854775808",
    "18446744073709551615",
    "18446744073709551616",
    "99999999999999999999999",
    "1000000000",
    "100000",
    "65536",
    "",
    "1.",
    ".",
    "-",
    "0x10",
    "1_000",
];

/// Mutations stop growing an input past this size (the seeds are at most ~0.5 MB).
const MAX_INPUT_BYTES: usize = 2 << 20;

/// Bytes that mean something to some parser.
const SPECIAL_BYTES: &[u8] = b"\0\n\r\t ,;#$\"'[]{}=:.-+eE\\\xff\xc3";

// The helpers below look around one position rather than scanning the whole input: the seeds
// run to half a megabyte, and this code runs unoptimised under `cargo test`.

/// The line holding byte `pos` (with its newline), if there is any data.
fn line_at(data: &[u8], pos: usize) -> Option<(usize, usize)> {
    if data.is_empty() {
        return None;
    }
    let pos = pos.min(data.len() - 1);
    let a = data[..pos].iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let b = data[pos..].iter().position(|&b| b == b'\n').map_or(data.len(), |i| pos + i + 1);
    Some((a, b))
}

/// A random line.
fn random_line(rng: &mut SmallRng, data: &[u8]) -> Option<(usize, usize)> {
    if data.is_empty() { None } else { line_at(data, rng.random_range(0..data.len())) }
}

fn is_num(b: u8) -> bool {
    b.is_ascii_digit() || matches!(b, b'.' | b'-' | b'+' | b'e' | b'E')
}

/// The first numeric-looking token (a run of digits, signs, dots and exponents with a digit)
/// that starts at or after `from`.
fn number_from(data: &[u8], from: usize) -> Option<(usize, usize)> {
    let mut i = from;
    while i < data.len() {
        if is_num(data[i]) && (i == from || !is_num(data[i - 1])) {
            let e = data[i..].iter().position(|&b| !is_num(b)).map_or(data.len(), |k| i + k);
            if data[i..e].iter().any(u8::is_ascii_digit) {
                return Some((i, e));
            }
            i = e;
        } else {
            i += 1;
        }
    }
    None
}

/// A numeric token after a random position (wrapping around to the start).
fn random_number(rng: &mut SmallRng, data: &[u8]) -> Option<(usize, usize)> {
    let from = rng.random_range(0..=data.len());
    let from = data[..from].iter().rposition(|&b| !is_num(b)).map_or(0, |i| i + 1);
    number_from(data, from).or_else(|| number_from(data, 0))
}

/// The first occurrence of `token` at or after `from` (wrapping around to the start).
fn find_from(data: &[u8], token: &[u8], from: usize) -> Option<usize> {
    let find = |s: usize| data[s..].windows(token.len()).position(|w| w == token).map(|i| s + i);
    find(from.min(data.len())).or_else(|| find(0))
}

fn pick<'a, T>(rng: &mut SmallRng, v: &'a [T]) -> Option<&'a T> {
    if v.is_empty() { None } else { Some(&v[rng.random_range(0..v.len())]) }
}

/// A number for a numeric field: an extreme, a random magnitude, or a neighbour of the old value.
fn number_for(rng: &mut SmallRng, old: &[u8]) -> Vec<u8> {
    match rng.random_range(0..4) {
        0 | 1 => pick(rng, EXTREMES).unwrap().as_bytes().to_vec(),
        2 => {
            let exp = rng.random_range(0..20);
            let v = rng.random_range(0..10u64.pow(exp).max(2));
            if rng.random_bool(0.3) { format!("-{v}") } else { v.to_string() }.into_bytes()
        }
        _ => {
            let v: f64 = std::str::from_utf8(old).ok().and_then(|s| s.parse().ok()).unwrap_or(0.0);
            let w = match rng.random_range(0..5) {
                0 => v + 1.0,
                1 => v - 1.0,
                2 => v * 1000.0,
                3 => -v,
                _ => v / 1000.0,
            };
            if w.fract() == 0.0 && w.abs() < 1e15 { format!("{}", w as i64) } else { format!("{w}") }.into_bytes()
        }
    }
}

/// Applies one random generic mutation to `data`.
pub fn mutate(rng: &mut SmallRng, data: &mut Vec<u8>, seeds: &[Vec<u8>], dict: &[Vec<u8>]) {
    let len = data.len();
    let pos = |rng: &mut SmallRng| rng.random_range(0..=len);
    match rng.random_range(0..16) {
        0 if len > 0 => {
            let i = rng.random_range(0..len);
            data[i] ^= 1 << rng.random_range(0..8);
        }
        1 if len > 0 => {
            let i = rng.random_range(0..len);
            data[i] = *pick(rng, SPECIAL_BYTES).unwrap();
        }
        2 if len > 0 => {
            let a = rng.random_range(0..len);
            let b = (a + rng.random_range(1..=64)).min(len);
            data.drain(a..b);
        }
        3 if len > 0 => {
            let a = rng.random_range(0..len);
            let b = (a + rng.random_range(1..=64)).min(len);
            let chunk = data[a..b].to_vec();
            let at = pos(rng);
            data.splice(at..at, chunk);
        }
        4 => {
            if let Some(tok) = pick(rng, dict) {
                let at = pos(rng);
                data.splice(at..at, tok.iter().copied());
            }
        }
        5..=7 => {
            // A numeric field replaced (the most productive mutation for these formats).
            if let Some((a, b)) = random_number(rng, data) {
                let new = number_for(rng, &data[a..b]);
                data.splice(a..b, new);
            }
        }
        8 => {
            if let Some((a, b)) = random_line(rng, data) {
                data.drain(a..b);
            }
        }
        14 | 15 => {
            // One of the first numbers after a dictionary token (a section marker, a key): the
            // counts and header fields that uniform picks among thousands of values rarely hit.
            let anchors: Vec<&Vec<u8>> = dict.iter().filter(|t| t.len() > 2).collect();
            if let Some(token) = pick(rng, &anchors)
                && let Some(at) = find_from(data, token, pos(rng))
            {
                let mut num = number_from(data, at);
                for _ in 0..rng.random_range(0..5) {
                    num = num.and_then(|(_, b)| number_from(data, b));
                }
                if let Some((a, b)) = num {
                    let new = number_for(rng, &data[a..b]);
                    data.splice(a..b, new);
                }
            }
        }
        9 => {
            // A line repeated, sometimes many times (counts that disagree, huge inputs).
            if let Some((a, b)) = random_line(rng, data) {
                let most = (MAX_INPUT_BYTES.saturating_sub(len) / (b - a)).max(1);
                let times = if rng.random_bool(0.1) { rng.random_range(1..2000).min(most) } else { 1 };
                let chunk = data[a..b].repeat(times);
                data.splice(b..b, chunk);
            }
        }
        10 => {
            if let (Some((a, b)), Some((c, d))) = (random_line(rng, data), random_line(rng, data))
                && b <= c
            {
                let (x, y) = (data[a..b].to_vec(), data[c..d].to_vec());
                data.splice(c..d, x);
                data.splice(a..b, y);
            }
        }
        11 => {
            // A line of another seed spliced in.
            if let Some(other) = pick(rng, seeds)
                && let Some((a, b)) = random_line(rng, other)
            {
                let at = random_line(rng, data).map_or(len, |l| l.0);
                data.splice(at..at, other[a..b].iter().copied());
            }
        }
        12 => data.truncate(pos(rng)),
        _ => {
            // Prefix of this input, suffix of another seed.
            if let Some(other) = pick(rng, seeds) {
                let cut = rng.random_range(0..=other.len());
                data.truncate(pos(rng));
                data.extend_from_slice(&other[cut..]);
            }
        }
    }
}

/// The input as text, as the callers (which read files with `read_to_string`) see it.
pub fn text(input: &[u8]) -> std::borrow::Cow<'_, str> {
    String::from_utf8_lossy(input)
}

/// The run's verdict for a parser's result: a valid value (checked by `valid`) or a message.
pub fn verdict<T, E: std::fmt::Display>(r: Result<T, E>, valid: impl FnOnce(&T) -> Verdict) -> Verdict {
    match r {
        Ok(v) => {
            valid(&v)?;
            accepted();
            Ok(())
        }
        Err(e) => {
            let msg = format!("{e:#}");
            if msg.trim().is_empty() { Err("rejected with an empty error message".into()) } else { Ok(()) }
        }
    }
}
