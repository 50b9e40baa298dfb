//! A counting global allocator (the system allocator underneath): live and peak heap bytes, and
//! the allocator calls a thread makes while counting is on for it.
//!
//! Install it once per binary with `#[global_allocator]`:
//!
//! - [`CountingAlloc::new`]: counting is on for a thread between [`count_on_this_thread`]`(true)`
//!   and `(false)`;
//! - [`CountingAlloc::counting_when`]: also whenever a predicate, evaluated on the allocating
//!   thread, is true (e.g. a thread-local flag a library sets around its real-time work).
//!
//! Counted are `alloc`, `alloc_zeroed`, `realloc` and `dealloc`: a call that must not touch the
//! heap does none of them. Counts are kept per thread ([`thread_allocations`]) and in total
//! ([`allocations`]). Byte figures ([`live_bytes`], [`peak_bytes`], [`reset_peak`]) cover every
//! thread, always.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

// Const-initialised and without destructors: usable from the allocator at any point of a
// thread's life.
thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static THREAD_ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

/// The global allocator: the system allocator, with counters.
pub struct CountingAlloc {
    when: Option<fn() -> bool>,
}

impl CountingAlloc {
    /// Counts a thread's allocator calls while [`count_on_this_thread`] is on for it.
    pub const fn new() -> Self {
        Self { when: None }
    }

    /// Also counts whenever `when()`, called on the allocating thread, is true. It must not
    /// allocate (a thread-local `Cell<bool>` read is fine).
    pub const fn counting_when(when: fn() -> bool) -> Self {
        Self { when: Some(when) }
    }

    fn note_call(&self) {
        let on = COUNTING.try_with(Cell::get).unwrap_or(false) || self.when.is_some_and(|f| f());
        if on {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
            let _ = THREAD_ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        }
    }
}

impl Default for CountingAlloc {
    fn default() -> Self {
        Self::new()
    }
}

fn add_live(size: usize) {
    let now = LIVE.fetch_add(size, Ordering::Relaxed) + size;
    PEAK.fetch_max(now, Ordering::Relaxed);
}

// SAFETY: every call is forwarded to the system allocator unchanged; only counters are updated,
// without allocating.
unsafe impl GlobalAlloc for CountingAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        self.note_call();
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            add_live(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        self.note_call();
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            add_live(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        self.note_call();
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        self.note_call();
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
            add_live(new_size);
        }
        p
    }
}

/// Turns counting on or off for the calling thread.
pub fn count_on_this_thread(on: bool) {
    COUNTING.with(|c| c.set(on));
}

/// Allocator calls counted on the calling thread so far.
pub fn thread_allocations() -> u64 {
    THREAD_ALLOCATIONS.with(Cell::get)
}

/// Allocator calls counted on every thread so far.
pub fn allocations() -> u64 {
    ALLOCATIONS.load(Ordering::Relaxed)
}

/// Live heap bytes (0 when [`CountingAlloc`] is not the global allocator).
pub fn live_bytes() -> usize {
    LIVE.load(Ordering::Relaxed)
}

/// The most live heap bytes since the start or the last [`reset_peak`].
pub fn peak_bytes() -> usize {
    PEAK.load(Ordering::Relaxed)
}

/// Starts a peak measurement: the peak is set to the live heap, which is returned (the baseline
/// to subtract from a later [`peak_bytes`]).
pub fn reset_peak() -> usize {
    let now = LIVE.load(Ordering::Relaxed);
    PEAK.store(now, Ordering::Relaxed);
    now
}
