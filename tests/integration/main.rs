//! The integration tests, one module per topic, in one test binary: each binary links faer,
//! plotters and image on its own, so one binary instead of 23 saves most of `cargo test`'s link
//! time. Run one topic with `cargo test -p odyn-tests --test integration grid::`.
//!
//! A new topic is `tests/integration/NAME.rs`, listed below; it reaches the shared models with
//! `use crate::common;`. Tests that count every allocation of the process stay binaries of their
//! own (`tests/allocations.rs`, `tests/grid_allocations.rs`, `tests/particle_allocations.rs`):
//! here other tests run beside them. `grid` installs this binary's global allocator, which
//! refuses allocations only on a thread that has been given a budget and passes every other
//! call to the system allocator.

#[path = "../common/mod.rs"]
mod common;

mod adaptive;
mod bdf;
mod big_models;
mod compositions;
mod const_generic;
mod control_flow;
mod convergence;
mod dae;
mod differences;
mod dual;
mod dual_rules;
mod energy;
mod ensemble;
mod ensemble_files;
mod extremes;
mod fit;
mod flip;
mod fluids;
mod grid;
mod hardening;
mod helpers;
mod implicit;
mod jacobian;
mod krylov;
mod mpm;
mod output;
mod parameters;
mod particles;
mod quasi_newton;
mod reference_dop853;
mod rosenbrock;
mod runner;
mod sensitivity_events;
mod shapes;
mod sph;
mod stability;
mod state;
mod trajectory;
mod unrolled;
mod work_precision;
mod xpbd;
