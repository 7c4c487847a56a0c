//! The scenes odyn's examples, tests, benches and peer comparisons share, each written once.
//!
//! A model here is the one every user of it integrates: the tests check it against its
//! reference, the benches time it against hand-written arithmetic and the peers, the examples
//! chart it. Reference values sit beside the model they belong to, with their source.
//!
//! - [`oscillators`] — the tutorial's damped [`Spring`], the [`UndampedSpring`].
//! - [`chaos`] — [`Lorenz`].
//! - [`pendulums`] — the [`DoublePendulum`].
//! - [`orbits`] — [`Kepler`], the [`Arenstorf`] orbit, the [`Pleiades`].
//! - [`solar_system`] — the outer [`SolarSystem`], and [`SolarSystemByAxis`].
//! - [`stiff`] — [`VanDerPol`] and four problems of the Bari test set ([`Robertson`], [`Hires`],
//!   [`Pollu`], [`Orego`]) with their references.
//! - [`dae`] — differential–algebraic problems: [`RobertsonDae`], the test set's [`ChemAkzo`]
//!   and [`Transamp`], the [`CartesianPendulum`], with their references.
//! - [`rope`] — a [`RodRope`] of rigid rods, a differential–algebraic field model.
//! - [`cloth`] — the Baraff–Witkin [`Cloth`] and the [`Sheet`] that builds it.
//! - [`fields`] — Gray–Scott reaction–diffusion, [`GrayScott`].
//! - [`fluids`] — the [`dam_break`] of Martin & Moyce for SPH and FLIP ([`flip_dam_break`]), and
//!   their data ([`MARTIN_MOYCE`]).
//! - [`hybrid`] — MPM's scenes: the 88-line program's ([`hybrid::mpm88`]), jelly, water and
//!   snow, a ringing block, a spinning disc, a snow column.
//! - [`analysis`] — the fitted [`slope`] of a convergence study.
//!
//! Not published: the scenes serve odyn's own checks and examples; each example that uses one
//! imports it and says where it lives.

pub mod analysis;
pub mod chaos;
pub mod cloth;
pub mod dae;
pub mod fields;
pub mod fluids;
pub mod hybrid;
pub mod orbits;
pub mod oscillators;
pub mod pendulums;
pub mod rope;
pub mod solar_system;
pub mod stiff;

pub use analysis::slope;
pub use chaos::*;
pub use cloth::{Cloth, Hang, Sheet};
pub use dae::*;
pub use fields::*;
pub use fluids::{MARTIN_MOYCE, dam_break, flip_dam_break};
pub use orbits::*;
pub use oscillators::*;
pub use pendulums::*;
pub use rope::RodRope;
pub use solar_system::*;
pub use stiff::*;
