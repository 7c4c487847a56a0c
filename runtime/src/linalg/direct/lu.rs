//! [`SparseLu`]: LU with partial pivoting of any regular sparse matrix, on faer's supernodal LU,
//! the symbolic analysis made once.

use std::sync::Arc;

use faer::Par;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::lu::{
    LuRef, LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu,
};

use super::{Factors, NoFactors};
use crate::linalg::dense::FactorizeError;
use crate::linalg::solver::{LinearSolve, SparseView};
use crate::stats::LinearWork;

/// The symbolic analysis (shared by clones) and the numeric factors.
type LuFactors = (Arc<SymbolicLu<usize>>, NumericLu<usize, f64>);

/// The sparse factorization P·A·Q = L·U, its symbolic analysis made the first time it is needed
/// and shared by clones.
pub(crate) struct SparseLu {
    factors: Option<LuFactors>,
    scratch: MemBuffer,
    /// The last factorization succeeded.
    factored: bool,
}

impl SparseLu {
    pub(crate) fn new() -> Self {
        SparseLu {
            factors: None,
            scratch: MemBuffer::new(StackReq::EMPTY),
            factored: false,
        }
    }

    /// The last factorization's factors, to substitute in as a preconditioner.
    pub(crate) fn factors(&self) -> Option<LuRef<'_, usize, f64>> {
        match (&self.factors, self.factored) {
            (Some((symbolic, numeric)), true) => Some(LuRef::new_unchecked(symbolic, numeric)),
            _ => None,
        }
    }

    fn scratch_size(symbolic: &SymbolicLu<usize>) -> StackReq {
        symbolic
            .factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
    }
}

impl LinearSolve for SparseLu {
    type SetupError = FactorizeError;
    type SolveError = NoFactors;

    /// Factorizes `a`, counted in `lu` (and the first symbolic analysis in `symbolic_lu`).
    ///
    /// Errors: [`FactorizeError::Singular`], when the pattern is structurally singular or the
    /// values numerically.
    fn set_linearisation(
        &mut self,
        a: &SparseView<'_>,
        work: &mut LinearWork,
    ) -> Result<(), FactorizeError> {
        self.factored = false;
        if self.factors.is_none() {
            // faer's simplicial LU spent 92 % of a 64-particle cloth run (measured with perf);
            // the supernodal one is the fast path for these block-structured matrices.
            let params = LuSymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..LuSymbolicParams::default()
            };
            let symbolic = factorize_symbolic_lu(a.pattern.as_ref(), params)
                .map_err(|_| FactorizeError::Singular)?;
            self.scratch = MemBuffer::new(Self::scratch_size(&symbolic));
            self.factors = Some((Arc::new(symbolic), NumericLu::new()));
            work.symbolic_lu += 1;
        }
        let Some((symbolic, numeric)) = &mut self.factors else {
            return Err(FactorizeError::Singular);
        };
        let matrix = SparseColMatRef::new(a.pattern.as_ref(), a.values);
        symbolic
            .factorize_numeric_lu(
                numeric,
                matrix,
                Par::Seq,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|_| FactorizeError::Singular)?;
        self.factored = true;
        work.lu += 1;
        Ok(())
    }

    fn solve_in_place(
        &mut self,
        _: &SparseView<'_>,
        x: &mut [f64],
        _: &mut LinearWork,
    ) -> Result<(), NoFactors> {
        let (Some((symbolic, numeric)), true) = (&self.factors, self.factored) else {
            return Err(NoFactors);
        };
        Factors::Lu(LuRef::new_unchecked(symbolic, numeric))
            .substitute(x, MemStack::new(&mut self.scratch));
        Ok(())
    }
}

impl Clone for SparseLu {
    fn clone(&self) -> Self {
        SparseLu {
            factors: self.factors.clone(),
            scratch: MemBuffer::new(
                self.factors
                    .as_ref()
                    .map_or(StackReq::EMPTY, |(symbolic, _)| {
                        Self::scratch_size(symbolic)
                    }),
            ),
            factored: self.factored,
        }
    }
}
