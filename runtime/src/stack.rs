//! Room on the stack for big states.
//!
//! States are values (`[f64; N]` and `SVector` fields), and a run holds a few dozen of them at
//! once: the initial state, the integrator's stages and scratch, the copies generated code makes.
//! A state of a megabyte (Gray–Scott on 256² as two `[f64; 65536]`) overflowed the main thread's
//! 8 MiB stack and aborted the process. Runs on states above [`BIG`] bytes therefore go on on a
//! stack segment sized to the state, which `stacker` allocates (and frees) when the current
//! stack has too little room left; smaller states never pay for the check, a compile-time
//! constant.

/// States above this many bytes (2048 `f64`s) get their room checked.
pub(crate) const BIG: usize = 16 * 1024;

/// Runs `f` with room for at least 128 values of type `S` on the stack (DOP853's start alone
/// holds about 40 in an unoptimised build), growing it if needed: the segment is virtual memory,
/// committed only as it is touched.
pub(crate) fn with_room<S, R>(f: impl FnOnce() -> R) -> R {
    let size = std::mem::size_of::<S>();
    if size <= BIG {
        return f();
    }
    stacker::maybe_grow(128 * size + (256 << 10), 256 * size + (1 << 20), || {
        apart(f)
    })
}

/// Calls `f` in a frame of its own: inlined, its megabyte locals would enlarge the frame that
/// decides whether the stack has room for them, before the check can help.
#[inline(never)]
fn apart<R>(f: impl FnOnce() -> R) -> R {
    f()
}
