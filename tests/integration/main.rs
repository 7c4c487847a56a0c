//! The runtime's integration tests for methods and drivers — fixed-size models under every
//! integrator, adaptive control, BDF, Rosenbrock, ensembles, outputs, the hardening probes —
//! one module per topic. The particle, grid, fluid and hybrid models' tests are the binary
//! `tests/continua/`, and the macro's models (what `#[system]` generates: Jacobians,
//! parameters, dual numbers, DAEs) `tests/models/` (package `odyn-model-tests`, unoptimised).
//! Each binary links faer, plotters and image on its own, but three of about equal size let
//! the compiler's serial front end run on both cores however cargo orders them (it picks among
//! ready test binaries in no particular order, and one binary of 90 s started last was a
//! minute of one idle core). Run one topic with `cargo test -p odyn-tests --test integration
//! bdf::`.
//!
//! A new topic is `tests/integration/NAME.rs`, listed below (a folder `NAME/` of files by
//! subtopic once it passes 600 lines); it reaches the shared models with `use crate::common;`.
//! Tests that count every allocation of the process stay binaries of their own
//! (`tests/allocations.rs`, `tests/grid_allocations.rs`, `tests/particle_allocations.rs`): here
//! other tests run beside them.

#[path = "../common/mod.rs"]
mod common;

mod adaptive;
mod bdf;
mod big_states;
mod compositions;
mod convergence;
mod energy;
mod ensemble;
mod ensemble_files;
mod extremes;
mod hardening;
mod implicit;
mod output;
mod reference_dop853;
mod rosenbrock;
mod runner;
mod stability;
mod typed;
mod work_precision;
