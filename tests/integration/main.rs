//! The runtime's integration tests — methods, drivers, solvers, particle, grid and fluid models —
//! one module per topic, in one test binary: each binary links faer, plotters and image on its
//! own, so few binaries save most of `cargo test`'s link time. The macro's models (what
//! `#[system]` generates: Jacobians, parameters, dual numbers, DAEs) are the other binary,
//! `tests/models/` (package `odyn-model-tests`, unoptimised); two binaries rather than one let
//! the compiler's serial front end run on both cores. Run one topic with `cargo test -p odyn-tests --test integration grid::`.
//!
//! A new topic is `tests/integration/NAME.rs`, listed below (a folder `NAME/` of files by
//! subtopic once it passes 600 lines); it reaches the shared models with `use crate::common;`.
//! Tests that count every allocation of the process stay binaries of their own
//! (`tests/allocations.rs`, `tests/grid_allocations.rs`, `tests/particle_allocations.rs`): here
//! other tests run beside them. `grid/budget.rs` installs this binary's global allocator, which
//! refuses allocations only on a thread that has been given a budget and passes every other
//! call to the system allocator.

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
mod flip;
mod fluids;
mod grid;
mod hardening;
mod implicit;
mod krylov;
mod mpm;
mod output;
mod particles;
mod quasi_newton;
mod reference_dop853;
mod rosenbrock;
mod runner;
mod sph;
mod stability;
mod typed;
mod work_precision;
mod xpbd;
