//! How accurate an adaptive run must be and how it sizes its steps: [`Tolerances`] and their
//! error norm, the step-size [`Controller`] and [`AdaptiveOptions`]. Below the integrators (which
//! measure their error against the tolerances) and the drivers (which run the controller).

mod controller;
mod tolerances;

pub use controller::{AdaptiveOptions, Controller};
pub(crate) use controller::{ControllerState, initial_step};
pub use tolerances::{Atol, Tolerances};
