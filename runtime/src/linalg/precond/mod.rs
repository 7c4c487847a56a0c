//! Preconditioners for the Krylov solves of sparse Newton matrices.
//!
//! - [`BlockJacobi`]: the inverse of each small diagonal block — a particle's D×D block of
//!   M − h·∂f/∂v − h²·∂f/∂x, or a cell's fields × fields block of I − h·J — built from the
//!   assembled values every factorization. Cheap (a few flops per unknown), and exact for the
//!   couplings inside a particle or a cell.
//! - [`Ilu0`]: the incomplete LU factorization on the matrix's own pattern (no fill), rebuilt
//!   every factorization: a sparse product's cost per application, and far fewer iterations
//!   than block Jacobi on diffusion-dominated matrices.
//! - [`Fourier`]: on a periodic grid, I − c·J with every block averaged over the cells,
//!   inverted exactly by the two-dimensional Fourier transform: O(N log N) per application,
//!   exact for constant-coefficient diffusion and a uniform reaction.
//! - [`Multigrid`]: smoothed aggregation algebraic multigrid, one V-cycle per application.
//!
//! Each is a type that implements [`Preconditioning`]: built from a matrix's values at every
//! linearisation and applied one column at a time. (The factors of an earlier matrix, the fifth
//! preconditioner, are the direct solver's: `linalg/direct`.)

use std::fmt;

use faer::dyn_stack::{MemStack, StackReq};

mod fourier;
mod ilu;
mod jacobi;
mod multigrid;

use super::direct::Factors;
pub(crate) use super::operator::{Column, as_precond};
use super::solver::SparseView;
pub(crate) use fourier::Fourier;
pub(crate) use ilu::Ilu0;
pub(crate) use jacobi::{BlockJacobi, invert};
pub(crate) use multigrid::Multigrid;

/// A preconditioner P ≈ A⁻¹: rebuilt from a matrix's values at every linearisation, applied to
/// one column at a time ([`Column`]).
pub(crate) trait Preconditioning: Column + Sync {
    /// Rebuilds P for `a`'s values (a field model's stencil, for [`Fourier`]).
    ///
    /// Errors: [`PrecondError`]; the caller then solves directly, which decides whether the
    /// matrix is singular.
    fn update_from(&mut self, a: &SparseView<'_>) -> Result<(), PrecondError>;
}

/// A preconditioner as faer's Krylov solvers take it: one of the [`Preconditioning`] types, or
/// the factors of an earlier matrix.
#[derive(Clone, Copy)]
pub(crate) enum Applied<'a> {
    Built(&'a (dyn Column + Sync)),
    Factors(Factors<'a>),
}

impl Applied<'_> {
    fn column(&self) -> &(dyn Column + Sync + '_) {
        match self {
            Applied::Built(p) => *p,
            Applied::Factors(factors) => factors,
        }
    }
}

impl fmt::Debug for Applied<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Applied::Built(p) => f.debug_struct("Preconditioner").field("n", &p.n()).finish(),
            Applied::Factors(factors) => factors.fmt(f),
        }
    }
}

impl Column for Applied<'_> {
    fn n(&self) -> usize {
        self.column().n()
    }
    fn scratch(&self) -> StackReq {
        self.column().scratch()
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        self.column().apply_column(out, r, stack);
    }
}

as_precond!(Applied<'_>);

/// Why a preconditioner could not be built from a matrix's values; the sparse solver then
/// factorizes directly, which decides whether the matrix is singular.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PrecondError {
    /// A diagonal block (block Jacobi's, or a multigrid level's smoother's) has a zero or
    /// non-finite pivot.
    SingularBlock,
    /// ILU(0) met a zero or non-finite pivot.
    ZeroPivot,
    /// Multigrid's coarsest matrix has a zero or non-finite pivot.
    SingularCoarsest,
    /// Multigrid's bound on ρ(D⁻¹A) is zero or not finite: there is no weight to smooth the
    /// prolongator with.
    NoSmoothingWeight,
    /// The Fourier preconditioner was asked for without the field model's stencil.
    NoStencil,
}
