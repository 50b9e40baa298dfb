//! SIGBUS containment (see the module docs of [`super`]): the process-wide handler and the
//! lock-free registry of this process's channel mappings it looks faulting addresses up in.

use std::io;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::MAX_MAPPINGS;

/// One registered mapping: `start == 0` marks a free slot.
pub(super) struct FaultSlot {
    pub(super) start: AtomicUsize,
    pub(super) len: AtomicUsize,
    pub(super) faulted: AtomicBool,
}

#[allow(clippy::declare_interior_mutable_const)] // each array element is its own slot
const FREE_SLOT: FaultSlot = FaultSlot { start: AtomicUsize::new(0), len: AtomicUsize::new(0), faulted: AtomicBool::new(false) };
pub(super) static REGISTRY: [FaultSlot; MAX_MAPPINGS] = [FREE_SLOT; MAX_MAPPINGS];

/// The `SIGBUS` action found when the handler was installed, to chain to for faults not ours.
struct PrevAction(std::cell::UnsafeCell<std::mem::MaybeUninit<libc::sigaction>>);
// SAFETY: written once, before PREV_READY is set (release) and before our handler is installed;
// only read after PREV_READY was seen set (acquire).
unsafe impl Sync for PrevAction {}
static PREV: PrevAction = PrevAction(std::cell::UnsafeCell::new(std::mem::MaybeUninit::uninit()));
static PREV_READY: AtomicBool = AtomicBool::new(false);
static INSTALLED: std::sync::OnceLock<Result<(), i32>> = std::sync::OnceLock::new();

pub(super) fn page_size() -> usize {
    // SAFETY: sysconf has no preconditions.
    let p = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    if p > 0 { p as usize } else { 4096 }
}

/// Installs the process-wide `SIGBUS` handler once; the result of that one attempt (an errno on failure).
pub(super) fn install_sigbus_handler() -> Result<(), i32> {
    *INSTALLED.get_or_init(|| {
        // SAFETY: plain sigaction calls with valid pointers; PREV is written before PREV_READY and
        // before our handler can run.
        unsafe {
            let mut old: libc::sigaction = std::mem::zeroed();
            if libc::sigaction(libc::SIGBUS, std::ptr::null(), &mut old) != 0 {
                return Err(io::Error::last_os_error().raw_os_error().unwrap_or(0));
            }
            (*PREV.0.get()).write(old);
            PREV_READY.store(true, Ordering::Release);
            let mut sa: libc::sigaction = std::mem::zeroed();
            sa.sa_sigaction = on_sigbus as *const () as libc::sighandler_t;
            sa.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK | libc::SA_RESTART;
            libc::sigemptyset(&mut sa.sa_mask);
            if libc::sigaction(libc::SIGBUS, &sa, std::ptr::null_mut()) != 0 {
                return Err(io::Error::last_os_error().raw_os_error().unwrap_or(0));
            }
        }
        Ok(())
    })
}

/// The `SIGBUS` handler: async-signal-safe (atomics, `mmap`, `sigaction`, `raise`; errno preserved).
extern "C" fn on_sigbus(sig: libc::c_int, info: *mut libc::siginfo_t, ctx: *mut libc::c_void) {
    // SAFETY: errno is thread-local; info is the kernel's siginfo for this signal.
    unsafe {
        let errno = *libc::__errno_location();
        // Only a fault raised by the kernel (si_code > 0) carries an address; a SIGBUS sent by kill
        // (si_code <= 0) is never ours.
        if !info.is_null() && (*info).si_code > 0 {
            let addr = (*info).si_addr() as usize;
            for slot in &REGISTRY {
                let start = slot.start.load(Ordering::Acquire);
                if start == 0 {
                    continue;
                }
                let len = slot.len.load(Ordering::Acquire);
                if addr >= start && addr - start < len {
                    let p = libc::mmap(
                        start as *mut libc::c_void,
                        len,
                        libc::PROT_READ | libc::PROT_WRITE,
                        libc::MAP_FIXED | libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                        -1,
                        0,
                    );
                    if p as usize == start {
                        slot.faulted.store(true, Ordering::Release);
                        *libc::__errno_location() = errno;
                        return; // the access is retried on the zero page
                    }
                    break;
                }
            }
        }
        *libc::__errno_location() = errno;
        chain_sigbus(sig, info, ctx);
    }
}

/// A fault that is not ours: the previous handler, or the default action (the process dies of `SIGBUS`).
unsafe fn chain_sigbus(sig: libc::c_int, info: *mut libc::siginfo_t, ctx: *mut libc::c_void) {
    // SAFETY: PREV was fully written before PREV_READY was set; the previous handler is called as
    // the kernel would have called it.
    unsafe {
        if PREV_READY.load(Ordering::Acquire) {
            let prev = (*PREV.0.get()).assume_init_ref();
            let h = prev.sa_sigaction;
            if h != libc::SIG_DFL && h != libc::SIG_IGN {
                if prev.sa_flags & libc::SA_SIGINFO != 0 {
                    let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) = std::mem::transmute(h);
                    f(sig, info, ctx);
                } else {
                    let f: extern "C" fn(libc::c_int) = std::mem::transmute(h);
                    f(sig);
                }
                return;
            }
        }
        let mut dfl: libc::sigaction = std::mem::zeroed();
        dfl.sa_sigaction = libc::SIG_DFL;
        libc::sigemptyset(&mut dfl.sa_mask);
        libc::sigaction(sig, &dfl, std::ptr::null_mut());
        if info.is_null() || (*info).si_code <= 0 {
            libc::raise(sig); // sent, not a fault: deliver it again under the default action
        }
        // A fault: returning re-executes the access, which faults again and kills the process.
    }
}

/// Registers `[start, start + len)` for the handler; the slot index, or `None` if the registry is full.
pub(super) fn register_mapping(start: usize, len: usize) -> Option<usize> {
    for (i, slot) in REGISTRY.iter().enumerate() {
        if slot.start.load(Ordering::Relaxed) == 0 && slot.start.compare_exchange(0, start, Ordering::AcqRel, Ordering::Relaxed).is_ok() {
            slot.faulted.store(false, Ordering::Relaxed);
            slot.len.store(len, Ordering::Release);
            return Some(i);
        }
    }
    None
}

pub(super) fn unregister_mapping(i: usize) {
    let slot = &REGISTRY[i];
    slot.len.store(0, Ordering::Release);
    slot.faulted.store(false, Ordering::Relaxed);
    slot.start.store(0, Ordering::Release);
}
