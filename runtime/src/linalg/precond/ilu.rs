//! ILU(0), the incomplete LU factorization on the matrix's own pattern.

use std::fmt;

use faer::dyn_stack::{MemStack, StackReq};
use faer::sparse::SymbolicSparseColMat;

use super::{Column, PrecondError, Preconditioning};
use crate::linalg::solver::SparseView;

/// ILU(0): A ≈ L·U with L unit lower and U upper triangular, both on A's own pattern (no fill),
/// computed row by row in the IKJ order of Saad, *Iterative Methods for Sparse Linear
/// Systems*, 2nd ed., SIAM 2003, Algorithm 10.4, in the unknowns' natural order. For a
/// symmetric A it is the incomplete Cholesky factorization IC(0) (U = D·Lᵀ), so CG may use it.
#[derive(Clone)]
pub(crate) struct Ilu0 {
    /// Row i's entries at `row_start[i]..row_start[i + 1]`, columns ascending.
    row_start: Vec<usize>,
    columns: Vec<usize>,
    /// Slot in the matrix's (column-major) values of each entry.
    source: Vec<usize>,
    /// Where each row's diagonal entry is.
    diagonal: Vec<usize>,
    /// The factors: L below the diagonal (its unit diagonal implied), U on and above.
    factors: Vec<f64>,
    /// Position of column j in the row being factorized, `usize::MAX` if not in it.
    marker: Vec<usize>,
}

impl Ilu0 {
    /// The structure of ILU(0) on a structurally symmetric pattern with its full diagonal.
    pub(crate) fn new(pattern: &SymbolicSparseColMat<usize>) -> Self {
        let n = pattern.ncols();
        // Structurally symmetric: row i's columns are column i's rows.
        let mut row_start = Vec::with_capacity(n + 1);
        let mut columns = Vec::with_capacity(pattern.compute_nnz());
        let mut source = Vec::with_capacity(pattern.compute_nnz());
        let mut diagonal = Vec::with_capacity(n);
        for i in 0..n {
            row_start.push(columns.len());
            for &j in pattern.row_idx_of_col_raw(i) {
                if j == i {
                    diagonal.push(columns.len());
                }
                columns.push(j);
                let start = pattern.col_ptr()[j];
                let rows = pattern.row_idx_of_col_raw(j);
                source.push(start + rows.binary_search(&i).unwrap_or(0));
            }
        }
        row_start.push(columns.len());
        Ilu0 {
            factors: vec![0.0; columns.len()],
            marker: vec![usize::MAX; n],
            row_start,
            columns,
            source,
            diagonal,
        }
    }

    /// Factorizes the matrix with `values`.
    ///
    /// Errors: [`PrecondError::ZeroPivot`] at a zero or non-finite pivot.
    pub(crate) fn update(&mut self, values: &[f64]) -> Result<(), PrecondError> {
        for (f, &slot) in self.factors.iter_mut().zip(&self.source) {
            *f = values[slot];
        }
        let n = self.diagonal.len();
        for i in 0..n {
            let row = self.row_start[i]..self.row_start[i + 1];
            for p in row.clone() {
                self.marker[self.columns[p]] = p;
            }
            for p in self.row_start[i]..self.diagonal[i] {
                let k = self.columns[p];
                let l = self.factors[p] / self.factors[self.diagonal[k]];
                self.factors[p] = l;
                for q in self.diagonal[k] + 1..self.row_start[k + 1] {
                    let m = self.marker[self.columns[q]];
                    if m != usize::MAX {
                        self.factors[m] -= l * self.factors[q];
                    }
                }
            }
            for p in row {
                self.marker[self.columns[p]] = usize::MAX;
            }
            let pivot = self.factors[self.diagonal[i]];
            if pivot == 0.0 || !pivot.is_finite() {
                return Err(PrecondError::ZeroPivot);
            }
        }
        Ok(())
    }

    /// out = U⁻¹·L⁻¹·r.
    fn apply(&self, out: &mut [f64], r: &[f64]) {
        let n = self.diagonal.len();
        for i in 0..n {
            let lower = self.row_start[i]..self.diagonal[i];
            let sum: f64 = self.columns[lower.clone()]
                .iter()
                .zip(&self.factors[lower])
                .map(|(&j, l)| l * out[j])
                .sum();
            out[i] = r[i] - sum;
        }
        for i in (0..n).rev() {
            let upper = self.diagonal[i] + 1..self.row_start[i + 1];
            let sum: f64 = self.columns[upper.clone()]
                .iter()
                .zip(&self.factors[upper])
                .map(|(&j, u)| u * out[j])
                .sum();
            out[i] = (out[i] - sum) / self.factors[self.diagonal[i]];
        }
    }
}

impl fmt::Debug for Ilu0 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Ilu0")
            .field("n", &self.diagonal.len())
            .finish()
    }
}

impl Column for Ilu0 {
    fn n(&self) -> usize {
        self.diagonal.len()
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.apply(out, r);
    }
}

impl Preconditioning for Ilu0 {
    fn update_from(&mut self, a: &SparseView<'_>) -> Result<(), PrecondError> {
        self.update(a.values)
    }
}
