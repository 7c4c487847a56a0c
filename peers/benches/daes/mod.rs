//! The DAE bench's problems: M·y′ = f(t, y) with a constant mass matrix, each with its
//! reference final state.

pub mod odyn;
pub mod problems;
pub mod transamp;
