//! [`SparseCholesky`]: LLᵀ of a symmetric positive definite matrix, on faer's supernodal
//! Cholesky with an AMD ordering, the symbolic analysis made once.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::{Par, Side};

use super::{Factors, NoFactors};
use crate::linalg::solver::{LinearSolve, SparseView};
use crate::stats::LinearWork;

/// The sparse Cholesky factorization A = LLᵀ (lower triangle read), its symbolic analysis made
/// the first time it is needed: a run that stays on a Krylov solve never pays for it (a 256²
/// Gray–Scott pattern's AMD ordering and analysis took longer than a step).
pub(crate) struct SparseCholesky {
    symbolic: Option<Arc<SymbolicCholesky<usize>>>,
    /// The factor's values (empty until the symbolic analysis).
    values: Vec<f64>,
    scratch: MemBuffer,
    /// The last factorization succeeded.
    factored: bool,
}

/// The matrix has a non-positive (or non-finite) pivot: it is not positive definite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct NotPositiveDefinite;

impl SparseCholesky {
    pub(crate) fn new() -> Self {
        SparseCholesky {
            symbolic: None,
            values: Vec::new(),
            scratch: MemBuffer::new(StackReq::EMPTY),
            factored: false,
        }
    }

    /// The last factorization's factors, to substitute in as a preconditioner.
    pub(crate) fn factors(&self) -> Option<LltRef<'_, usize, f64>> {
        match (&self.symbolic, self.factored) {
            (Some(symbolic), true) => Some(LltRef::new(symbolic, &self.values)),
            _ => None,
        }
    }

    fn scratch_size(symbolic: &SymbolicCholesky<usize>) -> StackReq {
        symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
    }

    /// The symbolic analysis of `a`'s pattern, made the first time with room for the factor's
    /// values and the scratch, counted in `symbolic_cholesky`.
    fn symbolic(
        &mut self,
        a: &SparseView<'_>,
        work: &mut LinearWork,
    ) -> Arc<SymbolicCholesky<usize>> {
        if let Some(symbolic) = &self.symbolic {
            return Arc::clone(symbolic);
        }
        let symbolic = Arc::new(
            factorize_symbolic_cholesky(
                a.pattern.as_ref(),
                Side::Lower,
                SymmetricOrdering::Amd,
                CholeskySymbolicParams::default(),
            )
            .expect("a symmetric pattern of checked size always has a symbolic Cholesky factor"),
        );
        self.values = vec![0.0; symbolic.len_val()];
        self.scratch = MemBuffer::new(Self::scratch_size(&symbolic));
        self.symbolic = Some(Arc::clone(&symbolic));
        work.symbolic_cholesky += 1;
        symbolic
    }
}

impl LinearSolve for SparseCholesky {
    type SetupError = NotPositiveDefinite;
    type SolveError = NoFactors;

    /// Factorizes `a`'s lower triangle, counted in `cholesky` or `cholesky_failed`.
    fn set_linearisation(
        &mut self,
        a: &SparseView<'_>,
        work: &mut LinearWork,
    ) -> Result<(), NotPositiveDefinite> {
        let symbolic = self.symbolic(a, work);
        let matrix = SparseColMatRef::new(a.pattern.as_ref(), a.values);
        let factored = symbolic.factorize_numeric_llt(
            &mut self.values,
            matrix,
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        self.factored = factored.is_ok();
        if self.factored {
            work.cholesky += 1;
            Ok(())
        } else {
            work.cholesky_failed += 1;
            Err(NotPositiveDefinite)
        }
    }

    fn solve_in_place(
        &mut self,
        _: &SparseView<'_>,
        x: &mut [f64],
        _: &mut LinearWork,
    ) -> Result<(), NoFactors> {
        let (Some(symbolic), true) = (&self.symbolic, self.factored) else {
            return Err(NoFactors);
        };
        Factors::Cholesky(LltRef::new(symbolic, &self.values))
            .substitute(x, MemStack::new(&mut self.scratch));
        Ok(())
    }
}

impl Clone for SparseCholesky {
    fn clone(&self) -> Self {
        SparseCholesky {
            symbolic: self.symbolic.clone(),
            values: self.values.clone(),
            scratch: MemBuffer::new(
                self.symbolic
                    .as_deref()
                    .map_or(StackReq::EMPTY, Self::scratch_size),
            ),
            factored: self.factored,
        }
    }
}
