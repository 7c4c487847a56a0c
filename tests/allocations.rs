//! Stepping a fixed-size model allocates nothing per step, adaptive runs and events included:
//! a run ten times longer makes exactly as many allocations (counted by a global allocator).
//! One test in its own binary, so no other test's allocations are counted.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering};

use common::{Kepler, KeplerState};
use odyn::prelude::*;

/// Counts allocations and hands them to the system allocator.
struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

// SAFETY: forwards every call to `System` unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_longer_run_allocates_no_more() {
    let model = Kepler {
        r: Vector2::new(0.5, 0.0),
        v: Vector2::new(0.0, 3f64.sqrt()),
        gm: 1.0,
    };
    // An event that is watched every step but never fires (the orbit stays beyond r = 0.1).
    let watch = || Event::crossing("close", |_, s: &KeplerState| s.r.norm() - 0.1).record();
    let count = |method: Method, duration: f64, fixed: bool| {
        let sim = model
            .simulate()
            .integrator(method)
            .duration(duration)
            .record_every(u64::MAX)
            .dense_output(false)
            .event(watch());
        let sim = if fixed { sim.dt(1e-3) } else { sim };
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        let run = sim.run().unwrap();
        let made = ALLOCATIONS.load(Ordering::Relaxed) - before;
        (made, run.steps())
    };
    for (method, fixed) in [
        (Method::Tsit5, false),
        (Method::Dop853, false),
        (Method::Tsit5, true),
        (Method::Rk4, true),
        (Method::Leapfrog, true),
        (Method::ImplicitEuler, true),
    ] {
        let (short, short_steps) = count(method, 6.0, fixed);
        let (long, long_steps) = count(method, 60.0, fixed);
        assert!(
            long_steps > 5 * short_steps,
            "{method}: {short_steps} vs {long_steps}"
        );
        assert_eq!(
            short, long,
            "{method} (fixed: {fixed}): allocations grew with the steps"
        );
    }
}
