//! A sparse symmetric positive definite matrix, factorized once by faer's Cholesky and solved
//! many times: the grid fluid's Poisson and diffusion operators are fixed for a given grid and
//! step, so the symbolic analysis (fill-reducing ordering) and the numeric factor are both made
//! once and every step only substitutes.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};

use crate::{Error, Result};

/// A factorized sparse SPD matrix.
pub(crate) struct SpdSolver {
    symbolic: SymbolicCholesky<usize>,
    factor: Vec<f64>,
    scratch: MemBuffer,
}

impl SpdSolver {
    /// Factorizes the n×n matrix with the given (row, column, value) entries (both triangles,
    /// duplicates summed).
    ///
    /// Errors: [`Error::InvalidInput`] if the matrix is not positive definite.
    pub(crate) fn new(n: usize, entries: &[(usize, usize, f64)]) -> Result<SpdSolver> {
        Self::with_columns(n, entries, 1)
    }

    /// [`SpdSolver::new`], with room to solve `columns` right-hand sides at once
    /// ([`SpdSolver::solve_columns`]).
    pub(crate) fn with_columns(
        n: usize,
        entries: &[(usize, usize, f64)],
        columns: usize,
    ) -> Result<SpdSolver> {
        let mut entries: Vec<(usize, usize, f64)> = entries.to_vec();
        entries.sort_by_key(|&(r, c, _)| (c, r));
        let mut merged: Vec<(usize, usize, f64)> = Vec::with_capacity(entries.len());
        for (r, c, v) in entries {
            match merged.last_mut() {
                Some(last) if (last.0, last.1) == (r, c) => last.2 += v,
                _ => merged.push((r, c, v)),
            }
        }
        let pairs: Vec<Pair<usize, usize>> =
            merged.iter().map(|&(r, c, _)| Pair::new(r, c)).collect();
        let (pattern, order) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|_| Error::invalid("matrix", "entries out of range"))?;
        let mut values = vec![0.0; pattern.compute_nnz()];
        let unsorted: Vec<f64> = merged.iter().map(|e| e.2).collect();
        // `order` maps the entries to the pattern's storage; the entries are distinct, so each
        // slot gets exactly one value.
        let filled =
            faer::sparse::SparseColMat::new_from_argsort(pattern.clone(), &order, &unsorted)
                .map_err(|_| Error::invalid("matrix", "entries could not be assembled"))?;
        values.copy_from_slice(filled.val());
        let symbolic = factorize_symbolic_cholesky(
            pattern.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|_| Error::invalid("matrix", "no symbolic Cholesky factor"))?;
        let need = symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(columns.max(1), Par::Seq));
        let mut scratch = MemBuffer::new(need);
        let mut factor = vec![0.0; symbolic.len_val()];
        symbolic
            .factorize_numeric_llt(
                &mut factor,
                SparseColMatRef::new(pattern.as_ref(), &values),
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut scratch),
                Default::default(),
            )
            .map_err(|_| Error::invalid("matrix", "not positive definite"))?;
        Ok(SpdSolver {
            symbolic,
            factor,
            scratch,
        })
    }

    /// Overwrites `rhs` with the solution x of A·x = rhs.
    pub(crate) fn solve_in_place(&mut self, rhs: &mut [f64]) {
        self.solve_columns(rhs, 1);
    }

    /// Overwrites the `columns` right-hand sides stored one after the other in `rhs` (column
    /// major) with their solutions; `columns` at most what the solver was made for.
    pub(crate) fn solve_columns(&mut self, rhs: &mut [f64], columns: usize) {
        let n = rhs.len() / columns;
        let rhs = MatMut::from_column_major_slice_mut(rhs, n, columns);
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
    }
}
