//! The direct solves of sparse matrices: [`SparseCholesky`], [`SparseLu`], and [`Direct`], which
//! takes Cholesky when the values are symmetric and LU otherwise. [`Factors`] applies either's
//! factors as a Krylov preconditioner.

use std::fmt;

use faer::dyn_stack::{MemStack, StackReq};
use faer::sparse::linalg::cholesky::LltRef;
use faer::sparse::linalg::lu::LuRef;
use faer::{Conj, MatMut, Par};

mod cholesky;
mod lu;

pub(crate) use cholesky::SparseCholesky;
pub(crate) use lu::SparseLu;

use super::dense::FactorizeError;
use super::operator::Column;
use super::solver::{LinearSolve, SparseView};
use crate::stats::LinearWork;

/// After an indefinite matrix, this many factorizations skip the Cholesky attempt: an undamped
/// 32² cloth hanging in its plane failed Cholesky on 132 of 133 Newton matrices, doing every
/// factorization twice; retrying every ninth bounds that waste and still returns to Cholesky
/// when the matrices become definite again.
const SKIP_CHOLESKY_AFTER_FAILURE: u32 = 8;

/// A solve asked of a backend that holds no factorization (none made, or the last one failed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct NoFactors;

/// Cholesky when the values are symmetric and positive definite, else LU (see
/// [`SKIP_CHOLESKY_AFTER_FAILURE`]), each on a symbolic analysis made the first time it is
/// needed and kept for the run.
#[derive(Clone)]
pub(crate) struct Direct {
    cholesky: SparseCholesky,
    lu: SparseLu,
    /// Which factorization the last linearisation made.
    factored: Option<Factored>,
    /// Factorizations left to go straight to LU after a Cholesky failed.
    skip_cholesky: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Factored {
    Cholesky,
    Lu,
}

impl Direct {
    pub(crate) fn new() -> Self {
        Direct {
            cholesky: SparseCholesky::new(),
            lu: SparseLu::new(),
            factored: None,
            skip_cholesky: 0,
        }
    }

    /// Whether the last linearisation made factors.
    pub(crate) fn factored(&self) -> bool {
        self.factored.is_some()
    }

    /// The last factorization's factors, as a preconditioner.
    pub(crate) fn factors(&self) -> Option<Factors<'_>> {
        match self.factored? {
            Factored::Cholesky => self.cholesky.factors().map(Factors::Cholesky),
            Factored::Lu => self.lu.factors().map(Factors::Lu),
        }
    }
}

impl LinearSolve for Direct {
    type SetupError = FactorizeError;
    type SolveError = NoFactors;

    /// Errors: [`FactorizeError::Singular`] when LU fails too.
    fn set_linearisation(
        &mut self,
        a: &SparseView<'_>,
        work: &mut LinearWork,
    ) -> Result<(), FactorizeError> {
        self.factored = None;
        if self.skip_cholesky > 0 {
            self.skip_cholesky -= 1;
        } else if a.symmetric {
            if self.cholesky.set_linearisation(a, work).is_ok() {
                self.factored = Some(Factored::Cholesky);
                return Ok(());
            }
            self.skip_cholesky = SKIP_CHOLESKY_AFTER_FAILURE;
        }
        self.lu.set_linearisation(a, work)?;
        self.factored = Some(Factored::Lu);
        Ok(())
    }

    fn solve_in_place(
        &mut self,
        a: &SparseView<'_>,
        x: &mut [f64],
        work: &mut LinearWork,
    ) -> Result<(), NoFactors> {
        match self.factored {
            Some(Factored::Cholesky) => self.cholesky.solve_in_place(a, x, work),
            Some(Factored::Lu) => self.lu.solve_in_place(a, x, work),
            None => Err(NoFactors),
        }
    }
}

/// The sparse factors of an earlier matrix, substituted in as a preconditioner.
#[derive(Clone, Copy)]
pub(crate) enum Factors<'a> {
    Cholesky(LltRef<'a, usize, f64>),
    Lu(LuRef<'a, usize, f64>),
}

impl Factors<'_> {
    /// Solves A·x = b by substitution in the factors, b given in `x`.
    pub(crate) fn substitute(&self, x: &mut [f64], stack: &mut MemStack) {
        let n = x.len();
        let column = MatMut::from_column_major_slice_mut(x, n, 1);
        match self {
            Factors::Cholesky(llt) => {
                llt.solve_in_place_with_conj(Conj::No, column, Par::Seq, stack)
            }
            Factors::Lu(lu) => lu.solve_in_place_with_conj(Conj::No, column, Par::Seq, stack),
        }
    }
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
        self.substitute(out, stack);
    }
}
