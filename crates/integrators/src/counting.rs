//! A global allocator that counts the allocations made on the threads that ask it to: what
//! the tests that prove a solver's steady loop allocates nothing install with
//! `#[global_allocator] static GLOBAL: Counting = Counting;`, then bracket the steps they
//! watch with [`Counting::start`] and [`Counting::stop`]. It allocates through the system
//! allocator; a thread that has not called `start` is not counted.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The counting allocator (see the module documentation).
pub struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

impl Counting {
    /// Counts, from zero, the allocations and reallocations of this thread from now on.
    pub fn start() {
        ALLOCATIONS.store(0, Ordering::Relaxed);
        COUNTING.with(|c| c.set(true));
    }

    /// Stops counting on this thread; returns the count since [`Counting::start`].
    pub fn stop() -> usize {
        COUNTING.with(|c| c.set(false));
        ALLOCATIONS.load(Ordering::Relaxed)
    }

    fn count() {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator; counting touches
// only an atomic and a `const`-initialised thread-local, neither of which allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        Counting::count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        Counting::count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}
