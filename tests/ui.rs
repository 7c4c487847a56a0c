//! Compile-fail tests: every model the macro rejects is a clear error at the offending token.
//! One case per distinct message, under `tests/ui/<topic>/`; the expected output is the `.stderr`
//! beside each case (regenerate with `TRYBUILD=overwrite cargo test -p odyn-tests --test ui` and review).

#[test]
fn rejected_models() {
    trybuild::TestCases::new().compile_fail("ui/*/*.rs");
}
