//! Compile-fail tests: every model the macro rejects is a clear error at the offending token.
//! One case per distinct message: a module of `tests/ui/<topic>.rs` (trybuild compiles each file
//! as a crate of its own, and 79 one-case crates cost more than a minute of `cargo test`), or a
//! file of `tests/ui/<topic>/` for a case whose error rustc reports only when nothing else in the
//! crate failed (a `const` evaluated after type checking, a type error after expansion). The
//! expected output is the `.stderr` beside each file (regenerate with
//! `TRYBUILD=overwrite cargo test -p odyn-tests --test ui` and review).

#[test]
fn rejected_models() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("ui/*.rs");
    cases.compile_fail("ui/*/*.rs");
}
