//! The runtime's integration tests for particle, grid, fluid and hybrid models — particle
//! systems and their solves (direct, Krylov, quasi-Newton), XPBD, grid models and their
//! preconditioners, Stable Fluids, SPH, FLIP and MPM — one module per topic (the methods'
//! and drivers' tests are `tests/integration/`). Run one topic with `cargo test -p odyn-tests
//! --test continua grid::`.
//!
//! `grid/budget.rs` installs this binary's global allocator, which refuses allocations only on
//! a thread that has been given a budget and passes every other call to the system allocator.

#[path = "../common/mod.rs"]
mod common;

mod dae_grid;
mod flip;
mod fluids;
mod grid;
mod krylov;
mod mpm;
mod particle_forces;
mod particles;
mod quasi_newton;
mod rope_dae;
mod sph;
mod xpbd;
