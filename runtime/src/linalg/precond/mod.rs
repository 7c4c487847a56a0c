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
//! - [`Factors`]: the sparse Cholesky or LU factors of an earlier matrix, applied by
//!   substitution: the strongest preconditioner odyn can offer for a slowly changing matrix,
//!   refreshed when the Krylov iteration count says the matrix has moved on.

use std::fmt;

use faer::dyn_stack::{MemStack, StackReq};
use faer::sparse::linalg::cholesky::LltRef;
use faer::sparse::linalg::lu::LuRef;
use faer::{Conj, MatMut, Par};

mod fourier;
mod ilu;
mod jacobi;

pub(crate) use super::operator::{Column, as_precond};
pub(crate) use fourier::{Fourier, FourierRef};

pub(crate) use ilu::{Ilu0, Ilu0Ref};
use jacobi::BlockJacobiRef;
pub(crate) use jacobi::{BlockJacobi, invert};

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
}

/// The sparse factors of an earlier matrix.
#[derive(Clone, Copy)]
pub(crate) enum Factors<'a> {
    Cholesky(LltRef<'a, usize, f64>),
    Lu(LuRef<'a, usize, f64>),
}

impl fmt::Debug for Factors<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self {
            Factors::Cholesky(_) => "Cholesky",
            Factors::Lu(_) => "LU",
        };
        f.debug_struct("Factors").field("kind", &kind).finish()
    }
}

impl Column for Factors<'_> {
    fn n(&self) -> usize {
        match self {
            Factors::Cholesky(llt) => llt.symbolic().nrows(),
            Factors::Lu(lu) => lu.symbolic().nrows(),
        }
    }
    fn scratch(&self) -> StackReq {
        match self {
            Factors::Cholesky(llt) => llt.symbolic().solve_in_place_scratch::<f64>(1, Par::Seq),
            Factors::Lu(lu) => lu.symbolic().solve_in_place_scratch::<f64>(1, Par::Seq),
        }
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        out.copy_from_slice(r);
        let n = out.len();
        let column = MatMut::from_column_major_slice_mut(out, n, 1);
        match self {
            Factors::Cholesky(llt) => {
                llt.solve_in_place_with_conj(Conj::No, column, Par::Seq, stack)
            }
            Factors::Lu(lu) => lu.solve_in_place_with_conj(Conj::No, column, Par::Seq, stack),
        }
    }
}

as_precond!(BlockJacobiRef<'_>);
as_precond!(Factors<'_>);
as_precond!(Ilu0Ref<'_>);
as_precond!(FourierRef<'_>);
