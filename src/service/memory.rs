//! Per-job memory accounting: a global allocator that wraps another and charges each heap
//! block to the job whose thread allocated it, so a worker can stop a job that passes the
//! server's memory limit.
//!
//! The binary installs [`Counting`] over mimalloc (`src/main.rs`); a worker tags its own thread
//! and its job's rayon threads with the worker's [`Account`] for the length of a run. The
//! allocator never refuses a block (a refused allocation aborts the whole process, and with it
//! every other job): it only marks the account as over, and the run stops at its next check
//! (`Reporter::cancelled`, between stages and inside the long loops), failing the job with the
//! limit and the peak in its message. Memory the OpenCASCADE kernel allocates in C++ does not
//! pass through Rust's allocator and is not counted.

use std::alloc::{GlobalAlloc, Layout};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicI64, AtomicU64, Ordering};

/// One worker's running total. Lives for the whole process (a worker's account is leaked once
/// at its start), so a thread that frees a block late never touches freed memory.
#[derive(Debug, Default)]
pub struct Account {
    /// Bytes held now: blocks allocated minus blocks freed on the tagged threads (a block
    /// freed on an untagged thread is not taken off, so this errs high, never low).
    held: AtomicI64,
    peak: AtomicU64,
    /// 0: no limit.
    limit: AtomicU64,
    over: AtomicBool,
}

impl Account {
    /// A new account for the life of the process.
    pub fn leaked() -> &'static Account {
        Box::leak(Box::default())
    }

    /// Start a run with `limit` bytes (0: none): the totals go back to zero.
    pub fn reset(&self, limit: u64) {
        self.held.store(0, Ordering::Relaxed);
        self.peak.store(0, Ordering::Relaxed);
        self.limit.store(limit, Ordering::Relaxed);
        self.over.store(false, Ordering::Relaxed);
    }

    /// Whether the run has held more than its limit at some point.
    pub fn over_limit(&self) -> bool {
        self.over.load(Ordering::Relaxed)
    }

    /// The most the run has held at once, in bytes.
    pub fn peak(&self) -> u64 {
        self.peak.load(Ordering::Relaxed)
    }

    fn charge(&self, bytes: usize) {
        let held = self.held.fetch_add(bytes as i64, Ordering::Relaxed) + bytes as i64;
        let held = held.max(0) as u64;
        if held > self.peak.load(Ordering::Relaxed) {
            self.peak.fetch_max(held, Ordering::Relaxed);
            let limit = self.limit.load(Ordering::Relaxed);
            if limit > 0 && held > limit {
                self.over.store(true, Ordering::Relaxed);
            }
        }
    }

    fn refund(&self, bytes: usize) {
        self.held.fetch_sub(bytes as i64, Ordering::Relaxed);
    }
}

thread_local! {
    /// The account this thread's allocations go to (none outside a job).
    static CHARGED: Cell<Option<&'static Account>> = const { Cell::new(None) };
}

/// Charge this thread's allocations to `account` from now on (`None`: to nobody).
pub fn charge_thread_to(account: Option<&'static Account>) {
    CHARGED.with(|c| c.set(account));
}

/// A global allocator charging every block to the current thread's [`Account`] and passing
/// the work on to `A`.
pub struct Counting<A>(pub A);

fn charged() -> Option<&'static Account> {
    // `try_with`: during thread teardown the slot may be gone; such blocks go uncounted.
    CHARGED.try_with(Cell::get).ok().flatten()
}

// SAFETY: every call is passed to the wrapped allocator unchanged; the bookkeeping only reads a
// thread-local `Cell` (const-initialised, no allocation) and updates atomics.
unsafe impl<A: GlobalAlloc> GlobalAlloc for Counting<A> {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = self.0.alloc(layout);
        if !p.is_null() {
            if let Some(a) = charged() {
                a.charge(layout.size());
            }
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = self.0.alloc_zeroed(layout);
        if !p.is_null() {
            if let Some(a) = charged() {
                a.charge(layout.size());
            }
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        self.0.dealloc(ptr, layout);
        if let Some(a) = charged() {
            a.refund(layout.size());
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = self.0.realloc(ptr, layout, new_size);
        if !p.is_null() {
            if let Some(a) = charged() {
                a.refund(layout.size());
                a.charge(new_size);
            }
        }
        p
    }
}
