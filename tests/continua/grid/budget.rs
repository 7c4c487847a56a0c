//! This binary's global allocator, which refuses allocations beyond a thread's budget, and the
//! grid too big for a run's copies that it tests: a typed error, not an abort.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use odyn::{Error, Method, Simulate};

use super::heat;

/// The system allocator, except that a thread given a budget ([`within_budget`]) gets a null
/// pointer for an allocation beyond what is left of it, as from a machine out of memory.
struct Budgeted;

thread_local! {
    /// Bytes this thread may still allocate; `None` for no limit.
    static LEFT: Cell<Option<usize>> = const { Cell::new(None) };
}

/// Whether `bytes` more fit the budget (taking them if so).
fn take(bytes: usize) -> bool {
    LEFT.try_with(|left| match left.get() {
        Some(n) if bytes > n => false,
        Some(n) => {
            left.set(Some(n - bytes));
            true
        }
        None => true,
    })
    .unwrap_or(true)
}

fn give(bytes: usize) {
    let _ = LEFT.try_with(|left| left.set(left.get().map(|n| n.saturating_add(bytes))));
}

// SAFETY: every call is passed on to the system allocator unchanged, or refused with null.
unsafe impl GlobalAlloc for Budgeted {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as the caller's contract.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as the caller's contract.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        give(layout.size());
        // SAFETY: as the caller's contract.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() && !take(new_size - layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as the caller's contract.
        let moved = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size < layout.size() && !moved.is_null() {
            give(layout.size() - new_size);
        }
        moved
    }
}

#[global_allocator]
static GLOBAL: Budgeted = Budgeted;

/// `f`, with this thread allowed `bytes` of new allocations.
fn within_budget<T>(bytes: usize, f: impl FnOnce() -> T) -> T {
    LEFT.with(|left| left.set(Some(bytes)));
    let out = f();
    LEFT.with(|left| left.set(None));
    out
}

/// A grid that fits in memory, with room for its state, but not for the copies a run makes of
/// it (the method's stages, the driver's buffers: ten to twenty) used to abort the process at
/// its first run (the probe's 16384² grid). Now the run stops at the first copy that
/// cannot be allocated with a typed error; modelled here by an allocator that refuses
/// allocations beyond a budget of three copies of a 256² grid's state (512 KiB each).
#[test]
fn a_grid_whose_run_copies_do_not_fit_is_a_typed_error() {
    let model = heat(256);
    let copy = 256 * 256 * std::mem::size_of::<f64>();
    for method in [
        Method::ExplicitEuler,
        Method::Rk4,
        Method::Tsit5,
        Method::Dop853,
    ] {
        let run = within_budget(3 * copy + (64 << 10), || {
            model.simulate().integrator(method).dt(1e-6).steps(1).run()
        });
        let error = run.unwrap_err();
        assert!(
            matches!(&error, Error::InvalidInput { field, .. } if field == "grid")
                && error.to_string().contains(
                    "is 256×256 with 1 field: a copy of its state (524 kB) cannot be allocated"
                ),
            "{method}: {error}"
        );
    }
    // With room for them, the same run goes through.
    let run = within_budget(64 * copy, || {
        model
            .simulate()
            .integrator(Method::Rk4)
            .dt(1e-6)
            .steps(1)
            .run()
    });
    assert_eq!(run.unwrap().steps(), 1);
}
