//! A sparse square matrix with a fixed pattern and its factorizations: Cholesky (LLᵀ) when the
//! values are symmetric and positive definite, else LU — the linear algebra of the particle and
//! grid Newton matrices.
//!
//! The pattern is given once ([`SparseSolver::new`]), made structurally symmetric, and analysed
//! symbolically once (AMD ordering, elimination tree); each solve then refills the values,
//! factorizes numerically and substitutes, with no allocation. When the values are not
//! symmetric, or Cholesky meets a non-positive pivot, the solve falls back to LU, whose symbolic
//! analysis is made the first time it is needed and kept.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, StackReq};
use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::linalg::lu::{NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

use super::dense::{FactorizeError, SolveError};
use super::krylov::{KrylovSolver, LinearSolver, Preconditioner, Solves, Structure};
use super::multigrid::Multigrid;
use super::precond::{BlockJacobi, Fourier, Ilu0};
use crate::stats::LinearWork;

mod direct;
mod iterative;
mod pattern;
#[cfg(test)]
mod tests;

pub(crate) use super::operator::{Edge, Products, RowMatrix, StencilBlock, StencilMatrix};

/// A sparse LU: the symbolic analysis (shared by clones) and the numeric factors.
type SparseLu = (Arc<SymbolicLu<usize>>, NumericLu<usize, f64>);

/// A sparse matrix of fixed pattern, its values, a right-hand side, and its factorizations.
pub(crate) struct SparseSolver {
    pattern: SymbolicSparseColMat<usize>,
    /// The matrix's values, in the pattern's column-major order (see [`SparseSolver::slot`]).
    pub(crate) values: Vec<f64>,
    /// Slot of each entry's transpose.
    transpose: Vec<usize>,
    /// The right-hand side [`SparseSolver::substitute`] solves in place.
    pub(crate) rhs: Vec<f64>,
    /// The symbolic Cholesky analysis, made the first time a direct factorization needs it
    /// ([`SparseSolver::symbolic_cholesky`]): a run that stays on a Krylov solve never pays for
    /// it (a 256² Gray–Scott pattern's AMD ordering and analysis took longer than a step).
    cholesky: Option<Arc<SymbolicCholesky<usize>>>,
    /// The Cholesky factor's values (empty until the first Cholesky factorization).
    cholesky_values: Vec<f64>,
    lu: Option<SparseLu>,
    scratch: MemBuffer,
    pub(crate) counts: LinearWork,
    factored: Option<Factored>,
    /// Factorizations left to go straight to LU after a Cholesky failed.
    skip_cholesky: u32,
    /// The Krylov solver, when the run chose one ([`SparseSolver::configure`]).
    krylov: Option<KrylovSolver>,
    /// The matrix by rows for the Krylov solver's products, made when a run first asks for them
    /// (unless the caller brings its own: [`SparseSolver::products_given`]).
    rows: Option<RowMatrix>,
    /// The caller passes the Krylov solves' products to [`SparseSolver::substitute_with`].
    products_given: bool,
    /// The Fourier preconditioner, when the caller's grid is periodic ([`SparseSolver::on_grid`]).
    fourier: Option<Fourier>,
    /// The diagonal blocks block Jacobi inverts (points until [`SparseSolver::set_blocks`]).
    jacobi: BlockJacobi,
    /// ILU(0)'s structure and factors, made when a run first asks for them.
    ilu: Option<Ilu0>,
    /// The multigrid hierarchy, made when a run first asks for it.
    multigrid: Option<Multigrid>,
    /// The groups of unknowns ([`SparseSolver::set_blocks`]): their size and the unknowns.
    blocks: (usize, Vec<usize>),
    /// The values were symmetric at the last factorization.
    symmetric: bool,
    /// The last factorization prepared a Krylov solve (else [`SparseSolver::substitute`]
    /// substitutes in the direct factors).
    iterative: bool,
}

/// Which factorization [`SparseSolver::factorize`] made last.
#[derive(Clone, Copy, Debug)]
enum Factored {
    Cholesky,
    Lu,
}

impl SparseSolver {
    /// An n × n matrix whose structural non-zeros are `entries` (row, column), their transposes
    /// and the diagonal; every value zero. Duplicates are merged.
    ///
    /// The caller guarantees every index is below `n` (checked topology or grid).
    pub(crate) fn new(n: usize, entries: &[(usize, usize)]) -> Self {
        let pattern = pattern::symmetric(n, entries);
        let mut solver_transpose = vec![0; pattern.compute_nnz()];
        for col in 0..n {
            let start = pattern.col_ptr()[col];
            for (k, &row) in pattern.row_idx_of_col_raw(col).iter().enumerate() {
                solver_transpose[start + k] = slot_in(&pattern, col, row);
            }
        }
        let jacobi = BlockJacobi::new(1, (0..n).collect(), &pattern);
        SparseSolver {
            values: vec![0.0; pattern.compute_nnz()],
            cholesky_values: Vec::new(),
            cholesky: None,
            pattern,
            transpose: solver_transpose,
            rhs: vec![0.0; n],
            lu: None,
            scratch: MemBuffer::new(StackReq::EMPTY),
            counts: LinearWork::default(),
            factored: None,
            skip_cholesky: 0,
            krylov: None,
            rows: None,
            products_given: false,
            fourier: None,
            ilu: None,
            multigrid: None,
            blocks: (1, (0..n).collect()),
            jacobi,
            symmetric: false,
            iterative: false,
        }
    }

    /// Groups the unknowns into blocks of `size` for block Jacobi: group k is
    /// `index[k·size..(k+1)·size]` (every unknown once).
    pub(crate) fn set_blocks(&mut self, size: usize, index: Vec<usize>) {
        self.jacobi = BlockJacobi::new(size, index.clone(), &self.pattern);
        self.blocks = (size, index);
    }

    /// The matrix is a field model's: the caller passes its stencil to
    /// [`SparseSolver::factorize_with`] and [`SparseSolver::substitute_with`] for the Krylov
    /// solves' products (no matrix by rows is made or filled) and, on a periodic grid, for
    /// [`Preconditioner::Fourier`].
    pub(crate) fn on_grid(&mut self, stencil: &StencilMatrix) {
        self.products_given = true;
        let (nx, ny, fields) = stencil.shape();
        self.fourier = Fourier::new(nx, ny, fields, stencil.blocks());
    }

    /// Chooses how the systems of this run are solved: direct, or the Krylov method `linear`
    /// gives for this size (its buffers allocated here).
    pub(crate) fn configure(
        &mut self,
        linear: &LinearSolver,
        structure: Structure,
        solves: Solves,
    ) {
        let n = self.rhs.len();
        self.krylov = linear.krylov_for(n, structure);
        if let Some(krylov) = &mut self.krylov {
            krylov.solves = solves;
        }
        if self.krylov.is_some() && self.rows.is_none() && !self.products_given {
            self.rows = RowMatrix::new(&self.pattern);
            if self.rows.is_none() {
                // Beyond 32-bit indices (2³² entries): a size no Krylov run here has reached.
                self.krylov = None;
            }
        }
        if let Some(krylov) = &mut self.krylov
            && krylov.options.preconditioner == Preconditioner::Fourier
            && self.fourier.is_none()
        {
            // Not a periodic grid (see `Preconditioner::Fourier`).
            krylov.options.preconditioner = Preconditioner::BlockJacobi;
        }
        if let Some(krylov) = &self.krylov
            && krylov.options.preconditioner == Preconditioner::Ilu0
            && self.ilu.is_none()
        {
            self.ilu = Some(Ilu0::new(&self.pattern));
        }
        if let Some(krylov) = &mut self.krylov
            && krylov.options.preconditioner == Preconditioner::Multigrid
            && self.multigrid.is_none()
        {
            let (size, index) = &self.blocks;
            self.multigrid = Multigrid::new(*size, index.clone(), &self.pattern);
            if self.multigrid.is_none() {
                // A matrix that does not coarsen: block Jacobi instead (see `Multigrid`).
                krylov.options.preconditioner = Preconditioner::BlockJacobi;
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

    /// Prepares to solve with the values: for a Krylov run, builds the block Jacobi
    /// preconditioner (or keeps an earlier factorization as the preconditioner until a solve
    /// asks for a fresh one); otherwise, or when a block is singular, factorizes directly.
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
        let Some(krylov) = &mut self.krylov else {
            return self.factorize_direct();
        };
        let refresh = std::mem::take(&mut krylov.refresh);
        let preconditioner = krylov.options.preconditioner;
        self.symmetric = self.is_symmetric();
        let values = &self.values;
        if let Some(rows) = &mut self.rows {
            rows.update(values);
        }
        // The preconditioners built from the values: false when one cannot be (a singular
        // block or pivot, or none made), which the direct factorization then decides.
        let built = match preconditioner {
            Preconditioner::BlockJacobi => Some(self.jacobi.update(values).is_ok()),
            Preconditioner::Ilu0 => {
                Some(self.ilu.as_mut().is_some_and(|p| p.update(values).is_ok()))
            }
            Preconditioner::Multigrid => Some(
                self.multigrid
                    .as_mut()
                    .is_some_and(|p| p.update(values).is_ok()),
            ),
            Preconditioner::Fourier => Some(match (&mut self.fourier, stencil) {
                (Some(fourier), Some(stencil)) => fourier.update(stencil).is_ok(),
                _ => false,
            }),
            Preconditioner::Factorization { .. } => None,
        };
        match built {
            Some(false) => return self.factorize_direct(),
            Some(true) => self.counts.krylov.preconditioners += 1,
            None => {
                if self.factored.is_none() || refresh {
                    self.factorize_direct()?;
                }
            }
        }
        self.iterative = true;
        Ok(())
    }

    /// Factorizes the values directly whatever the run configured: the next solves substitute
    /// in the factors (a mass-matrix system, which the Krylov products do not know).
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub(crate) fn factorize_direct_only(&mut self) -> Result<(), FactorizeError> {
        self.iterative = false;
        self.factorize_direct()
    }

    /// Solves the matrix against [`SparseSolver::rhs`], in place: by the Krylov method when
    /// the last factorization prepared one (redone directly if it fails), else by
    /// substitution in the direct factors.
    ///
    /// Errors: [`SolveError::Singular`] when the Krylov solve failed and the direct solve that
    /// took over found the matrix singular (a zero pivot, or a solution that is not finite);
    /// the right-hand side's contents are then unspecified.
    pub(crate) fn substitute(&mut self) -> Result<(), SolveError> {
        self.substitute_with(None)
    }

    /// [`SparseSolver::substitute`], a Krylov solve multiplying by `stencil` when given (it must
    /// be the same matrix as the values).
    pub(crate) fn substitute_with(
        &mut self,
        stencil: Option<&StencilMatrix>,
    ) -> Result<(), SolveError> {
        if self.iterative && self.solve_iteratively(stencil).is_ok() {
            return Ok(());
        }
        if self.iterative {
            // The Krylov solve failed (its right-hand side was finite): the direct solve of the
            // same matrix decides, and a solution that is not finite means W is singular (faer's
            // LU takes a zero pivot and divides by it).
            self.iterative = false;
            self.factorize_direct()
                .map_err(|FactorizeError::Singular| SolveError::Singular)?;
            self.substitute_direct();
            return match self.rhs.iter().all(|x| x.is_finite()) {
                true => Ok(()),
                false => Err(SolveError::Singular),
            };
        }
        self.substitute_direct();
        Ok(())
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

impl Clone for SparseSolver {
    fn clone(&self) -> Self {
        SparseSolver {
            pattern: self.pattern.clone(),
            values: self.values.clone(),
            transpose: self.transpose.clone(),
            rhs: self.rhs.clone(),
            cholesky: self.cholesky.clone(),
            cholesky_values: self.cholesky_values.clone(),
            lu: self.lu.clone(),
            scratch: MemBuffer::new(self.scratch_size()),
            counts: self.counts,
            factored: self.factored,
            skip_cholesky: self.skip_cholesky,
            krylov: self.krylov.clone(),
            rows: self.rows.clone(),
            products_given: self.products_given,
            fourier: self.fourier.clone(),
            ilu: self.ilu.clone(),
            multigrid: self.multigrid.clone(),
            blocks: self.blocks.clone(),
            jacobi: self.jacobi.clone(),
            symmetric: self.symmetric,
            iterative: self.iterative,
        }
    }
}
