//! Inputs that once crashed, hung, or returned a wrong number without an error: each is now a
//! typed error or a correct result. One test per failure mode found by bad-input probing.

mod events;
mod implicit;
mod newton;
mod output;
mod runs;
mod stability;

use std::path::PathBuf;

use crate::common::Oscillator;
use odyn::prelude::*;

/// ẍ = −ω²x from (1, 0).
fn oscillator(omega: f64) -> Oscillator {
    Oscillator {
        x: 1.0,
        v: 0.0,
        omega,
    }
}

fn invalid_field<T: std::fmt::Debug>(result: odyn::Result<T>) -> String {
    match result {
        Err(Error::InvalidInput { field, .. }) => field,
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

/// A file in a directory of its own per test (tests run in parallel in one process, and one
/// test lists its directory for leftover temporaries).
fn scratch(test: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("odyn-hardening-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}
