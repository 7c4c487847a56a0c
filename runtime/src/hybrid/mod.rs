//! Hybrid continua: particles carry the material, a grid made afresh every step solves for its
//! motion — FLIP/APIC fluids and the material point method.
//!
//! | method | where the state lives | what it is good at |
//! |---|---|---|
//! | SPH ([`crate::sph`]) | particles | free surfaces, splashes; no grid, neighbours searched every step |
//! | Stable Fluids ([`crate::fluids`]) | grid | smoke, closed boxes; no free surface |
//! | FLIP/APIC ([`flip`]) | particles, pressure on a MAC grid | incompressible liquids with free surfaces |
//! | MPM ([`mpm`]) | particles, grid as scratch | solids and fluids together: jelly, water, snow |
//!
//! Both hybrids share the particle–grid transfer: quadratic B-spline weights (`bspline.rs`),
//! the choice of velocity transfer ([`Transfer`]: APIC, or a PIC/FLIP blend) and the
//! deterministic parallel scatter (`strips.rs`), which sums every grid node in an order fixed by
//! the particles' positions, so a run is bit-identical on any number of threads.

mod bspline;
pub mod flip;
pub mod mpm;
mod strips;
mod transfer;

pub use transfer::Transfer;
