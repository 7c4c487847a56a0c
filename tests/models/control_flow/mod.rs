//! The Jacobian through every control-flow form the macro accepts, and through every supported
//! function, against central differences of the model's own derivative (common::check, 1e-6
//! relative). Each model here once either failed to compile or, worse, compiled to a wrong
//! Jacobian: an early `return` on a parameter was ignored, and a loop over parameters was
//! dropped from the Jacobian's code.

mod branches;
mod functions;
mod guarded;
mod loops;
mod matches;
mod parameters;
mod time;
