//! Compile-fail tests: every model the macro rejects is a clear error at the offending token.
//! One case per distinct message: a module of `tests/ui/<topic>.rs` (trybuild compiles each file
//! as a crate of its own, and 79 one-case crates cost more than a minute of `cargo test`), or a
//! file of `tests/ui/<topic>/` for a case whose error rustc reports only when nothing else in the
//! crate failed (a `const` evaluated after type checking, a type error after expansion). The
//! expected output is the `.stderr` beside each file (regenerate with
//! `TRYBUILD=overwrite cargo test -p odyn-compile-fail --test ui` and review).

/// The flags trybuild 1.0 gives rustc when it compiles the cases (`--cfg trybuild --verbose -A
/// dead_code --diagnostic-width=140`), unit-separated as `CARGO_ENCODED_RUSTFLAGS` wants them.
/// It first checks the dependencies without the last one, then everything with it, so on a
/// clean target directory every dependency was checked twice (about 50 s of a clean `cargo
/// test`). The variable outranks the flags trybuild passes, so both passes use these.
const TRYBUILD_RUSTFLAGS: &str =
    "--cfg\u{1f}trybuild\u{1f}--verbose\u{1f}-A\u{1f}dead_code\u{1f}--diagnostic-width=140";

#[test]
fn rejected_models() {
    // SAFETY: this binary's only test, so no other thread reads or writes the environment.
    unsafe { std::env::set_var("CARGO_ENCODED_RUSTFLAGS", TRYBUILD_RUSTFLAGS) };
    let cases = trybuild::TestCases::new();
    cases.compile_fail("ui/*.rs");
    cases.compile_fail("ui/*/*.rs");
}
