//! The one interface of the sparse linear solvers, after diffsol's `LinearSolver`: a backend is
//! made for a pattern (its `new`, diffsol's `set_problem`), prepared for a matrix's values
//! ([`LinearSolve::set_linearisation`]: a factorization made, or a preconditioner built), and
//! then solves right-hand sides in place ([`LinearSolve::solve_in_place`]). Each backend names
//! its own failures as types.
//!
//! The backends, each its own type:
//! - [`SparseCholesky`](super::direct::SparseCholesky): LLᵀ of a symmetric positive definite
//!   matrix;
//! - [`SparseLu`](super::direct::SparseLu): LU of any regular one;
//! - [`Direct`](super::direct::Direct): Cholesky when the values are symmetric, LU otherwise or
//!   when Cholesky meets a non-positive pivot;
//! - [`Krylov`](super::krylov::Krylov): conjugate gradient or BiCGSTAB with one of the
//!   [`Preconditioning`](super::precond::Preconditioning) types.
//!
//! The policy that chooses among them for a run, and falls back to the direct solve when a
//! Krylov solve fails, is [`SparseSolver`](super::sparse::SparseSolver).

use faer::sparse::SymbolicSparseColMat;

use super::operator::{Products, StencilMatrix};
use crate::stats::LinearWork;

/// A sparse square matrix as the backends read it: its pattern (structurally symmetric, the
/// diagonal included) and values in the pattern's column-major order, whether those values are
/// symmetric, the products a Krylov solve multiplies by, and what the preconditioners are built
/// from.
#[derive(Clone, Copy)]
pub(crate) struct SparseView<'a> {
    pub(crate) pattern: &'a SymbolicSparseColMat<usize>,
    pub(crate) values: &'a [f64],
    /// The values are symmetric to rounding (see `SparseSolver::is_symmetric`).
    pub(crate) symmetric: bool,
    /// The matrix's products: by rows (particle models) or by a field model's stencil; `None`
    /// when no Krylov solve was configured.
    pub(crate) products: Option<Products<'a>>,
    /// A field model's matrix by its cells' blocks, which the Fourier preconditioner reads.
    pub(crate) stencil: Option<&'a StencilMatrix>,
    /// The groups of unknowns block Jacobi inverts and multigrid aggregates: their size, and
    /// group k's unknowns at `k·size..(k+1)·size`.
    pub(crate) blocks: (usize, &'a [usize]),
}

/// A linear solver of sparse systems A·x = b for one pattern.
pub(crate) trait LinearSolve {
    /// Why [`LinearSolve::set_linearisation`] can fail.
    type SetupError;
    /// Why [`LinearSolve::solve_in_place`] can fail.
    type SolveError;

    /// Prepares to solve with `a`'s values, counting what it does in `work`.
    fn set_linearisation(
        &mut self,
        a: &SparseView<'_>,
        work: &mut LinearWork,
    ) -> Result<(), Self::SetupError>;

    /// Solves A·x = b with the last linearisation, b given in `x`.
    fn solve_in_place(
        &mut self,
        a: &SparseView<'_>,
        x: &mut [f64],
        work: &mut LinearWork,
    ) -> Result<(), Self::SolveError>;
}
