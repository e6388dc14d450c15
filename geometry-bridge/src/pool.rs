//! Copies of one OCCT geometry object, so threads evaluating it at once do not queue.
//!
//! An OCCT evaluator is not safe to share (a B-spline's adaptor keeps a span cache that every
//! call rewrites), so each copy sits behind its own lock. A call takes the copy its thread
//! used last if that is free, else any free one, and makes a new copy (a deep copy of the
//! first) when all are busy, up to [`MAX_COPIES`]. One thread never makes a second copy; two
//! threads on one face (a face cut into parts, a face's sizing samples in rows) each get one,
//! without the caller asking. The copies are exact: every one evaluates to the same bits.

use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, TryLockError};

use cxx::memory::UniquePtrTarget;
use cxx::UniquePtr;

/// Copies at most per object; beyond that, threads wait for one.
pub const MAX_COPIES: usize = 16;

/// One copy's lock on a cache line of its own: two threads locking neighbouring slots on
/// every call would otherwise bounce one line between their cores.
#[repr(align(128))]
struct Padded<T>(T);

/// One slot: a copy, or nothing yet, behind its lock.
type SlotLock<T> = Padded<Mutex<Option<UniquePtr<T>>>>;

pub(crate) struct CopyPool<T: UniquePtrTarget> {
    /// Slot 0 holds the original, the next `filled - 1` its copies, the rest nothing yet.
    slots: Box<[SlotLock<T>]>,
    filled: AtomicUsize,
    /// Held while a copy is made, so slots fill one at a time and in order.
    growing: Mutex<()>,
    copy: fn(&T) -> Result<UniquePtr<T>, cxx::Exception>,
}

/// A small number per thread, to spread threads over the copies.
fn thread_slot() -> usize {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    thread_local!(static SLOT: Cell<Option<usize>> = const { Cell::new(None) });
    SLOT.with(|s| match s.get() {
        Some(k) => k,
        None => {
            let k = NEXT.fetch_add(1, Ordering::Relaxed);
            s.set(Some(k));
            k
        }
    })
}

/// A lock that a panic elsewhere left poisoned is still usable: OCCT calls are atomic from
/// Rust's view, so they cannot leave the object half-updated.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

fn try_lock<T>(m: &Mutex<T>) -> Option<MutexGuard<'_, T>> {
    match m.try_lock() {
        Ok(g) => Some(g),
        Err(TryLockError::Poisoned(e)) => Some(e.into_inner()),
        Err(TryLockError::WouldBlock) => None,
    }
}

type Slot<'a, T> = MutexGuard<'a, Option<UniquePtr<T>>>;

impl<T: UniquePtrTarget> CopyPool<T> {
    pub(crate) fn new(
        original: UniquePtr<T>,
        copy: fn(&T) -> Result<UniquePtr<T>, cxx::Exception>,
    ) -> Self {
        let mut slots = vec![Padded(Mutex::new(Some(original)))];
        slots.extend((1..MAX_COPIES).map(|_| Padded(Mutex::new(None))));
        CopyPool {
            slots: slots.into_boxed_slice(),
            filled: AtomicUsize::new(1),
            growing: Mutex::new(()),
            copy,
        }
    }

    /// Run `f` on a copy no other thread is using.
    pub(crate) fn with<R>(&self, f: impl FnOnce(&mut UniquePtr<T>) -> R) -> R {
        let filled = self.filled.load(Ordering::Acquire);
        let start = thread_slot() % filled;
        for k in (0..filled).map(|i| (start + i) % filled) {
            if let Some(mut g) = try_lock(&self.slots[k].0) {
                if let Some(obj) = g.as_mut() {
                    return f(obj);
                }
            }
        }
        if let Some(mut g) = self.grow() {
            if let Some(obj) = g.as_mut() {
                return f(obj);
            }
        }
        // As many copies as allowed, all busy (or copying failed): wait for one.
        let mut g = lock(&self.slots[start].0);
        f(g.as_mut().expect("slots below `filled` hold an object"))
    }

    /// A new copy in the next empty slot, returned locked; `None` when the slots are full or
    /// OCCT cannot copy the object.
    fn grow(&self) -> Option<Slot<'_, T>> {
        let _one_at_a_time = lock(&self.growing);
        let m = self.filled.load(Ordering::Acquire);
        let slot = self.slots.get(m)?;
        let made = {
            let original = lock(&self.slots[0].0);
            (self.copy)(original.as_ref()?).ok()?
        };
        let mut g = lock(&slot.0);
        *g = Some(made);
        self.filled.store(m + 1, Ordering::Release);
        Some(g)
    }
}
