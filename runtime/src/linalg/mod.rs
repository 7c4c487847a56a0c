//! The linear algebra of the implicit methods: dense Newton matrices, the sparse direct solver,
//! Krylov iterations and their preconditioners, Newton's options, and the sparse SPD solver of
//! the grid fluid.

pub(crate) mod dense;
pub(crate) mod krylov;
mod multigrid;
mod newton;
mod precond;
pub(crate) mod sparse;
pub(crate) mod spd;

pub use dense::{DenseMatrix, FactorizeError, FaerDense, NewtonMatrix, SolveError};
pub use krylov::{Krylov, KrylovCounts, LinearSolver, Preconditioner, Solves};
pub use newton::NewtonOptions;
