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
use faer::matrix_free::{LinOp, Precond};
use faer::sparse::linalg::cholesky::LltRef;
use faer::sparse::linalg::lu::LuRef;
use faer::{Conj, MatMut, MatRef, Par};

mod fourier;
mod ilu;
mod jacobi;

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

/// Writes P·rhs into `out` column by column with `apply(out_column, rhs_column, stack)`.
pub(crate) fn columns(
    mut out: MatMut<'_, f64>,
    rhs: MatRef<'_, f64>,
    stack: &mut MemStack,
    mut apply: impl FnMut(&mut [f64], &[f64], &mut MemStack),
) {
    for j in 0..rhs.ncols() {
        let r: Vec<f64>;
        let r_col = rhs.col(j);
        let r_slice = match r_col.try_as_col_major() {
            Some(c) => c.as_slice(),
            None => {
                // faer's solvers pass contiguous columns; this path is never taken by them.
                r = r_col.iter().copied().collect();
                &r
            }
        };
        let out_slice = out
            .as_mut()
            .col_mut(j)
            .try_as_col_major_mut()
            .expect("faer's Krylov solvers pass contiguous columns")
            .as_slice_mut();
        apply(out_slice, r_slice, stack);
    }
}

/// A preconditioner applied one column at a time; [`as_precond!`] makes it a faer operator.
pub(crate) trait Column {
    fn n(&self) -> usize;
    fn scratch(&self) -> StackReq;
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack);
}

/// faer's operator traits for a [`Column`] type (a blanket impl would break the orphan rule).
macro_rules! as_precond {
    ($ty:ty) => {
        impl LinOp<f64> for $ty {
            fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
                Column::scratch(self)
            }
            fn nrows(&self) -> usize {
                Column::n(self)
            }
            fn ncols(&self) -> usize {
                Column::n(self)
            }
            fn apply(
                &self,
                out: MatMut<'_, f64>,
                rhs: MatRef<'_, f64>,
                _: Par,
                stack: &mut MemStack,
            ) {
                columns(out, rhs, stack, |o, r, s| self.apply_column(o, r, s));
            }
            fn conj_apply(
                &self,
                out: MatMut<'_, f64>,
                rhs: MatRef<'_, f64>,
                par: Par,
                stack: &mut MemStack,
            ) {
                self.apply(out, rhs, par, stack);
            }
        }
        impl Precond<f64> for $ty {}
    };
}

as_precond!(BlockJacobiRef<'_>);
as_precond!(Factors<'_>);
as_precond!(Ilu0Ref<'_>);
as_precond!(FourierRef<'_>);
as_precond!(super::multigrid::MultigridRef<'_>);
