//! Linear algebra of the implicit methods on sparse models: the sparse direct solver, Krylov
//! iterations and their preconditioners.

pub(crate) mod krylov;
mod multigrid;
mod precond;
pub(crate) mod sparse;

pub use krylov::{Krylov, KrylovCounts, LinearSolver, Preconditioner};
