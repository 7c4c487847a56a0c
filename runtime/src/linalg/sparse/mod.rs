//! The sparse solver of the particle and grid Newton matrices: a matrix of fixed pattern, its
//! values and a right-hand side, and the policy that chooses its backend for a run.
//!
//! The pattern is given once ([`SparseSolver::new`]) and made structurally symmetric. Each
//! factorization hands the values to the run's backend (`linalg/solver.rs`): the
//! [`Direct`] solve (Cholesky when the values are symmetric and positive definite, else LU), or
//! a [`Krylov`] solve with its preconditioner, chosen by [`LinearSolver`]. A Krylov solve that
//! fails is redone by the direct solve, which then decides whether the matrix is singular; a
//! preconditioner that cannot be built has the direct solve take that factorization.

use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

use super::dense::{FactorizeError, SolveError};
use super::direct::Direct;
use super::krylov::{Krylov, LinearSolver, Solves, Structure, Unprepared};
use super::solver::{LinearSolve, SparseView};
use crate::stats::LinearWork;

#[cfg(test)]
mod backends;
mod pattern;
#[cfg(test)]
mod tests;

pub(crate) use super::operator::{Edge, Products, RowMatrix, StencilBlock, StencilMatrix};

/// A sparse matrix of fixed pattern, its values, a right-hand side, and its run's backend.
#[derive(Clone)]
pub(crate) struct SparseSolver {
    pattern: SymbolicSparseColMat<usize>,
    /// The matrix's values, in the pattern's column-major order (see [`SparseSolver::slot`]).
    pub(crate) values: Vec<f64>,
    /// Slot of each entry's transpose.
    transpose: Vec<usize>,
    /// The right-hand side [`SparseSolver::substitute`] solves in place.
    pub(crate) rhs: Vec<f64>,
    pub(crate) counts: LinearWork,
    /// The groups of unknowns ([`SparseSolver::set_blocks`]): their size and the unknowns.
    blocks: (usize, Vec<usize>),
    /// The matrix by rows for the Krylov solves' products, made when a run first asks for them
    /// (unless the caller brings its own: [`SparseSolver::on_grid`]).
    rows: Option<RowMatrix>,
    /// The caller passes the Krylov solves' products to [`SparseSolver::substitute_with`].
    products_given: bool,
    direct: Direct,
    /// The Krylov solves, when the run chose them ([`SparseSolver::configure`]).
    krylov: Option<Box<Krylov>>,
    /// The values were symmetric at the last factorization.
    symmetric: bool,
    /// The last factorization prepared a Krylov solve (else [`SparseSolver::substitute`]
    /// substitutes in the direct factors).
    iterative: bool,
}

/// The matrix as the backends read it: a macro, so that the view borrows the solver's storage
/// while its backends are borrowed mutably.
macro_rules! view {
    ($solver:expr, $stencil:expr) => {
        SparseView {
            pattern: &$solver.pattern,
            values: &$solver.values,
            symmetric: $solver.symmetric,
            products: match ($stencil, &$solver.rows) {
                (Some(stencil), _) => Some(Products::Stencil(stencil)),
                (None, Some(rows)) => Some(Products::Rows(rows)),
                (None, None) => None,
            },
            stencil: $stencil,
            blocks: ($solver.blocks.0, &$solver.blocks.1),
        }
    };
}

impl SparseSolver {
    /// An n × n matrix whose structural non-zeros are `entries` (row, column), their transposes
    /// and the diagonal; every value zero. Duplicates are merged.
    ///
    /// The caller guarantees every index is below `n` (checked topology or grid).
    pub(crate) fn new(n: usize, entries: &[(usize, usize)]) -> Self {
        let pattern = pattern::symmetric(n, entries);
        let mut transpose = vec![0; pattern.compute_nnz()];
        for col in 0..n {
            let start = pattern.col_ptr()[col];
            for (k, &row) in pattern.row_idx_of_col_raw(col).iter().enumerate() {
                transpose[start + k] = slot_in(&pattern, col, row);
            }
        }
        SparseSolver {
            values: vec![0.0; pattern.compute_nnz()],
            pattern,
            transpose,
            rhs: vec![0.0; n],
            counts: LinearWork::default(),
            blocks: (1, (0..n).collect()),
            rows: None,
            products_given: false,
            direct: Direct::new(),
            krylov: None,
            symmetric: false,
            iterative: false,
        }
    }

    /// Groups the unknowns into blocks of `size` for block Jacobi: group k is
    /// `index[k·size..(k+1)·size]` (every unknown once).
    pub(crate) fn set_blocks(&mut self, size: usize, index: Vec<usize>) {
        self.blocks = (size, index);
    }

    /// The matrix is a field model's: the caller passes its stencil to
    /// [`SparseSolver::factorize_with`] and [`SparseSolver::substitute_with`] for the Krylov
    /// solves' products (no matrix by rows is made or filled) and, on a periodic grid, for
    /// [`Preconditioner::Fourier`](crate::Preconditioner::Fourier).
    pub(crate) fn on_grid(&mut self) {
        self.products_given = true;
    }

    /// Chooses how the systems of this run are solved: directly, or by the Krylov method
    /// `linear` gives for this size, for what the solves are for (`solves`).
    pub(crate) fn configure(
        &mut self,
        linear: &LinearSolver,
        structure: Structure,
        solves: Solves,
    ) {
        let n = self.rhs.len();
        // A solver configured again (BDF's first attempt) keeps its preconditioners' structures.
        self.krylov = match (linear.krylov_for(n, structure), self.krylov.take()) {
            (Some((options, policy)), Some(old)) => {
                Some(Box::new(old.reconfigured(options, policy, solves, n)))
            }
            (Some((options, policy)), None) => {
                Some(Box::new(Krylov::new(options, policy, solves, n)))
            }
            (None, _) => None,
        };
        if self.krylov.is_some() && self.rows.is_none() && !self.products_given {
            self.rows = RowMatrix::new(&self.pattern);
            if self.rows.is_none() {
                // Beyond 32-bit indices (2³² entries): a size no Krylov run here has reached.
                self.krylov = None;
            }
        }
    }

    /// The run solves by a Krylov method (until `Auto` gives it up).
    pub(crate) fn krylov_configured(&self) -> bool {
        self.krylov.is_some()
    }

    /// The index in [`SparseSolver::values`] of entry (row, column), which must be structural.
    pub(crate) fn slot(&self, row: usize, col: usize) -> usize {
        slot_in(&self.pattern, row, col)
    }

    /// The matrix as faer sees it.
    pub(crate) fn matrix(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.pattern.as_ref(), &self.values)
    }

    /// Whether the values are symmetric to rounding: every |aᵢⱼ − aⱼᵢ| within 1e-12 of the
    /// largest entry. (Entry-wise relative tests fail on entries that are differences of nearly
    /// equal terms, such as a spring's k·(1 − L/|d|) near rest.) Cholesky reads the lower
    /// triangle, so what it ignores is a perturbation of that size.
    fn is_symmetric(&self) -> bool {
        let largest = self.values.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let tolerance = 1e-12 * largest;
        self.values
            .iter()
            .zip(&self.transpose)
            .all(|(&a, &t)| (a - self.values[t]).abs() <= tolerance)
    }

    /// Prepares to solve with the values: builds the Krylov solve's preconditioner (or keeps
    /// an earlier factorization as the preconditioner until a solve asks for a fresh one), or
    /// factorizes directly for a direct run or when the preconditioner cannot be built.
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub(crate) fn factorize(&mut self) -> Result<(), FactorizeError> {
        self.factorize_with(None)
    }

    /// [`SparseSolver::factorize`] of a field model's matrix, `stencil` the same matrix by its
    /// cells' blocks (prepared), which the Fourier preconditioner is built from.
    pub(crate) fn factorize_with(
        &mut self,
        stencil: Option<&StencilMatrix>,
    ) -> Result<(), FactorizeError> {
        self.iterative = false;
        self.symmetric = self.is_symmetric();
        let Some(krylov) = &mut self.krylov else {
            return self
                .direct
                .set_linearisation(&view!(self, stencil), &mut self.counts);
        };
        if let Some(rows) = &mut self.rows {
            rows.update(&self.values);
        }
        let a = view!(self, stencil);
        match krylov.set_linearisation(&a, &mut self.counts) {
            Ok(()) => {
                self.iterative = true;
                Ok(())
            }
            Err(Unprepared::Unbuilt(_)) => self.direct.set_linearisation(&a, &mut self.counts),
            Err(Unprepared::Singular) => Err(FactorizeError::Singular),
        }
    }

    /// Factorizes the values directly whatever the run configured: the next solves substitute
    /// in the factors (a mass-matrix system, which the Krylov products do not know).
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub(crate) fn factorize_direct_only(&mut self) -> Result<(), FactorizeError> {
        self.iterative = false;
        self.symmetric = self.is_symmetric();
        self.direct
            .set_linearisation(&view!(self, None), &mut self.counts)
    }

    /// Solves the matrix against [`SparseSolver::rhs`], in place: by the Krylov method when
    /// the last factorization prepared one (redone directly if it fails), else by
    /// substitution in the direct factors.
    ///
    /// Errors: [`SolveError::Singular`] when the Krylov solve failed and the direct solve that
    /// took over found the matrix singular (a zero pivot, or a solution that is not finite),
    /// or when no factorization was made; the right-hand side's contents are then unspecified.
    pub(crate) fn substitute(&mut self) -> Result<(), SolveError> {
        self.substitute_with(None)
    }

    /// [`SparseSolver::substitute`], a Krylov solve multiplying by `stencil` when given (it must
    /// be the same matrix as the values).
    pub(crate) fn substitute_with(
        &mut self,
        stencil: Option<&StencilMatrix>,
    ) -> Result<(), SolveError> {
        let a = view!(self, stencil);
        if self.iterative {
            if let Some(krylov) = &mut self.krylov
                && krylov
                    .solve_in_place(&a, &mut self.rhs, &mut self.counts)
                    .is_ok()
            {
                if krylov.exhausted() {
                    // `Auto` gave the Krylov solves up: the next factorizations are direct.
                    self.krylov = None;
                }
                return Ok(());
            }
            // The Krylov solve failed (its right-hand side was finite): the direct solve of the
            // same matrix decides, and a solution that is not finite means W is singular (faer's
            // LU takes a zero pivot and divides by it).
            self.iterative = false;
            self.direct
                .set_linearisation(&a, &mut self.counts)
                .map_err(|FactorizeError::Singular| SolveError::Singular)?;
            self.direct
                .solve_in_place(&a, &mut self.rhs, &mut self.counts)
                .map_err(|_| SolveError::Singular)?;
            return match self.rhs.iter().all(|x| x.is_finite()) {
                true => Ok(()),
                false => Err(SolveError::Singular),
            };
        }
        self.direct
            .solve_in_place(&a, &mut self.rhs, &mut self.counts)
            .map_err(|_| SolveError::Singular)
    }
}

fn slot_in(pattern: &SymbolicSparseColMat<usize>, row: usize, col: usize) -> usize {
    let start = pattern.col_ptr()[col];
    let rows = pattern.row_idx_of_col_raw(col);
    start
        + rows
            .binary_search(&row)
            .expect("every entry asked for is in the pattern")
}
