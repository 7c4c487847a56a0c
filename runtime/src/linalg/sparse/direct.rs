//! The direct solve: Cholesky when the values are symmetric and positive definite, else LU, both
//! on symbolic analyses kept for the run, and substitution in their factors.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::linalg::lu::{LuRef, LuSymbolicParams, NumericLu, factorize_symbolic_lu};
use faer::{Conj, MatMut, Par, Side};

use super::{Factored, SparseSolver};
use crate::linalg::dense::FactorizeError;

/// After an indefinite matrix, this many factorizations skip the Cholesky attempt: an undamped
/// 32² cloth hanging in its plane failed Cholesky on 132 of 133 Newton matrices, doing every
/// factorization twice; retrying every ninth bounds that waste and still returns to Cholesky
/// when the matrices become definite again.
const SKIP_CHOLESKY_AFTER_FAILURE: u32 = 8;

impl SparseSolver {
    pub(super) fn cholesky_scratch(symbolic: &SymbolicCholesky<usize>) -> StackReq {
        symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
    }

    /// The symbolic Cholesky analysis (AMD ordering), made the first time it is needed with room
    /// for the factor's values and the scratch, counted in `symbolic_cholesky`.
    fn symbolic_cholesky(&mut self) -> Arc<SymbolicCholesky<usize>> {
        if let Some(symbolic) = &self.cholesky {
            return Arc::clone(symbolic);
        }
        let symbolic = Arc::new(
            factorize_symbolic_cholesky(
                self.pattern.as_ref(),
                Side::Lower,
                SymmetricOrdering::Amd,
                CholeskySymbolicParams::default(),
            )
            .expect("a symmetric pattern of checked size always has a symbolic Cholesky factor"),
        );
        self.cholesky_values = vec![0.0; symbolic.len_val()];
        self.cholesky = Some(Arc::clone(&symbolic));
        self.scratch = MemBuffer::new(self.scratch_size());
        self.counts.symbolic_cholesky += 1;
        symbolic
    }

    /// Factorizes the values: Cholesky when symmetric and positive definite, else LU (each
    /// symbolic analysis made the first time; see [`SKIP_CHOLESKY_AFTER_FAILURE`]).
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub(super) fn factorize_direct(&mut self) -> Result<(), FactorizeError> {
        self.factored = None;
        if self.skip_cholesky > 0 {
            self.skip_cholesky -= 1;
        } else if self.is_symmetric() {
            let symbolic = self.symbolic_cholesky();
            let matrix = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
            let factored = symbolic.factorize_numeric_llt(
                &mut self.cholesky_values,
                matrix,
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut self.scratch),
                Default::default(),
            );
            if factored.is_ok() {
                self.counts.cholesky += 1;
                self.factored = Some(Factored::Cholesky);
                return Ok(());
            }
            self.counts.cholesky_failed += 1;
            self.skip_cholesky = SKIP_CHOLESKY_AFTER_FAILURE;
        }
        self.factorize_lu()
    }

    /// The LU, its symbolic analysis made the first time.
    ///
    /// Errors: [`FactorizeError::Singular`], when the pattern is structurally singular or the
    /// values numerically.
    fn factorize_lu(&mut self) -> Result<(), FactorizeError> {
        if self.lu.is_none() {
            // faer's simplicial LU spent 92 % of a 64-particle cloth run (measured with perf);
            // the supernodal one is the fast path for these block-structured matrices.
            let params = LuSymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..LuSymbolicParams::default()
            };
            let symbolic = factorize_symbolic_lu(self.pattern.as_ref(), params)
                .map_err(|_| FactorizeError::Singular)?;
            self.lu = Some((Arc::new(symbolic), NumericLu::new()));
            self.scratch = MemBuffer::new(self.scratch_size());
            self.counts.symbolic_lu += 1;
        }
        let Some((symbolic, numeric)) = &mut self.lu else {
            return Err(FactorizeError::Singular);
        };
        let matrix = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let factored = symbolic.factorize_numeric_lu(
            numeric,
            matrix,
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        factored.map_err(|_| FactorizeError::Singular)?;
        self.counts.lu += 1;
        self.factored = Some(Factored::Lu);
        Ok(())
    }

    /// Solves the last direct factorization against [`SparseSolver::rhs`], in place.
    pub(super) fn substitute_direct(&mut self) {
        let n = self.rhs.len();
        let rhs = MatMut::from_column_major_slice_mut(&mut self.rhs, n, 1);
        let stack = MemStack::new(&mut self.scratch);
        match (&self.factored, &self.cholesky, &self.lu) {
            (Some(Factored::Cholesky), Some(cholesky), _) => LltRef::new(
                cholesky,
                &self.cholesky_values,
            )
            .solve_in_place_with_conj(Conj::No, rhs, Par::Seq, stack),
            (Some(Factored::Lu), _, Some((symbolic, numeric))) => LuRef::new_unchecked(
                symbolic, numeric,
            )
            .solve_in_place_with_conj(Conj::No, rhs, Par::Seq, stack),
            _ => {}
        }
    }

    /// The scratch the analyses made so far need.
    pub(super) fn scratch_size(&self) -> StackReq {
        let cholesky = self
            .cholesky
            .as_deref()
            .map_or(StackReq::EMPTY, Self::cholesky_scratch);
        match &self.lu {
            None => cholesky,
            Some((lu, _)) => cholesky
                .or(lu.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()))
                .or(lu.solve_in_place_scratch::<f64>(1, Par::Seq)),
        }
    }
}
