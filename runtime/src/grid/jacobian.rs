//! The sparse Jacobian of a field model and its Newton solve.

use std::fmt;

use faer::sparse::SparseColMatRef;

use super::stencil::neighbour;
use super::{Block, Boundary, NEIGHBOURS};
use crate::linalg::dense::finite;
use crate::linalg::sparse::{Factorizations, SparseSolver};
use crate::{FactorizeError, NewtonMatrix, SolveError};

/// The Jacobian ∂f/∂y of a field model, assembled from its cells' blocks, and the sparse
/// matrix I − c·J the implicit methods solve with.
///
/// The pattern is stencil × grid × boundary: for every cell and every [`Block`] of the model,
/// row (output field, cell) and column (input field, the neighbour through the input field's
/// [`Boundary`]) — a periodic read wraps, a Neumann read past the edge lands on the edge cell
/// (adding into its entry), a Dirichlet read past the edge is a constant and has no column.
/// The pattern, where each cell's blocks go in it, and the symbolic factorization are made once,
/// in [`GridJacobian::new`]; an evaluation writes values only, a factorization refills I − c·J
/// and factorizes numerically (Cholesky when symmetric positive definite, as for diffusion, else
/// LU), with no allocation.
pub struct GridJacobian {
    nx: usize,
    ny: usize,
    blocks: usize,
    /// Per cell and block, the slot in the matrix of the block's entry; `usize::MAX` for a read
    /// of a Dirichlet value.
    slots: Vec<usize>,
    /// Slot of every diagonal entry.
    diagonal: Vec<usize>,
    /// J's values, in the matrix's slots.
    jacobian: Vec<f64>,
    /// The blocks of the cell being evaluated.
    cell: Vec<f64>,
    solver: SparseSolver,
}

impl GridJacobian {
    /// The Jacobian of a model whose fields have `boundaries` on an nx × ny grid and whose cells
    /// have `blocks`.
    pub fn new(nx: usize, ny: usize, boundaries: &[Boundary], blocks: &[Block]) -> Self {
        let cells = nx * ny;
        let n = boundaries.len() * cells;
        let column = |k: usize, b: &Block| {
            let (_, di, dj) = NEIGHBOURS[b.neighbour];
            let to = neighbour(nx, ny, boundaries[b.column], k % nx, k / nx, di, dj)?;
            Some((b.row * cells + k, b.column * cells + to))
        };
        let mut entries = Vec::with_capacity(cells * blocks.len());
        for k in 0..cells {
            entries.extend(blocks.iter().filter_map(|b| column(k, b)));
        }
        let mut solver = SparseSolver::new(n, &entries);
        // Block Jacobi inverts each cell's fields × fields block.
        let fields = boundaries.len();
        solver.set_blocks(
            fields,
            (0..cells)
                .flat_map(|k| (0..fields).map(move |f| f * cells + k))
                .collect(),
        );
        let mut slots = Vec::with_capacity(cells * blocks.len());
        for k in 0..cells {
            slots.extend(
                blocks
                    .iter()
                    .map(|b| column(k, b).map_or(usize::MAX, |(row, col)| solver.slot(row, col))),
            );
        }
        GridJacobian {
            nx,
            ny,
            blocks: blocks.len(),
            slots,
            diagonal: (0..n).map(|i| solver.slot(i, i)).collect(),
            jacobian: vec![0.0; solver.values.len()],
            cell: vec![0.0; blocks.len()],
            solver,
        }
    }

    /// The grid's size, nx × ny.
    pub fn grid(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Structural non-zeros of the matrix (with the diagonal and the transpose of every entry).
    pub fn nonzeros(&self) -> usize {
        self.jacobian.len()
    }

    /// How often this Jacobian has factorized.
    pub fn factorizations(&self) -> Factorizations {
        self.solver.counts
    }

    /// Starts an evaluation: every value to zero.
    pub(crate) fn begin(&mut self) {
        self.jacobian.fill(0.0);
    }

    /// Room for the block values of the cell being evaluated.
    #[inline(always)]
    pub(crate) fn cell_blocks(&mut self) -> &mut [f64] {
        &mut self.cell
    }

    /// Adds the block values just written for cell k into J.
    #[inline(always)]
    pub(crate) fn place(&mut self, k: usize) {
        let slots = &self.slots[k * self.blocks..(k + 1) * self.blocks];
        for (&slot, &value) in slots.iter().zip(&self.cell) {
            if let Some(entry) = self.jacobian.get_mut(slot) {
                *entry += value;
            }
        }
    }

    /// Gershgorin's discs of J, one per row: (centre Jᵢᵢ, radius Σⱼ≠ᵢ |Jᵢⱼ|). Every eigenvalue
    /// lies in their union.
    pub fn discs(&self) -> Vec<(f64, f64)> {
        let n = self.diagonal.len();
        let mut discs: Vec<(f64, f64)> = self
            .diagonal
            .iter()
            .map(|&slot| (self.jacobian[slot], 0.0))
            .collect();
        let matrix = SparseColMatRef::new(self.solver.matrix().symbolic(), &self.jacobian);
        for col in 0..n {
            for (row, value) in matrix.row_idx_of_col(col).zip(matrix.val_of_col(col)) {
                if row != col {
                    discs[row].1 += value.abs();
                }
            }
        }
        discs
    }

    /// J as a dense matrix: for tests and small grids.
    pub fn to_dense(&self) -> faer::Mat<f64> {
        SparseColMatRef::new(self.solver.matrix().symbolic(), &self.jacobian).to_dense()
    }

    /// Forms I − c·J from the last evaluation: the "assembly" of a step's cost.
    pub fn assemble(&mut self, c: f64) {
        for (w, j) in self.solver.values.iter_mut().zip(&self.jacobian) {
            *w = -c * j;
        }
        for &slot in &self.diagonal {
            self.solver.values[slot] += 1.0;
        }
    }

    /// Factorizes the assembled I − c·J numerically (Cholesky, else LU): the "factorization"
    /// of a step's cost.
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub fn factorize(&mut self) -> Result<(), FactorizeError> {
        self.solver.factorize()
    }

    /// Solves the last factorization against `b` in place: the "solve" of a step's cost.
    ///
    /// Errors: [`SolveError::WrongLength`], [`SolveError::NotFinite`].
    pub fn substitute(&mut self, b: &mut [f64]) -> Result<(), SolveError> {
        let expected = self.solver.rhs.len();
        if b.len() != expected {
            return Err(SolveError::WrongLength {
                expected,
                found: b.len(),
            });
        }
        self.solver.rhs.copy_from_slice(b);
        self.solver.substitute();
        b.copy_from_slice(&self.solver.rhs);
        finite(b)
    }
}

impl NewtonMatrix for GridJacobian {
    const COSTLY_SOLVES: bool = true;

    fn configure(&mut self, newton: &crate::NewtonOptions, solves: crate::Solves) {
        self.solver.configure(
            &newton.linear,
            crate::linalg::krylov::Structure::Field,
            solves,
        );
    }

    /// The factorization lives in the sparse solver inside the matrix.
    type Factors = ();

    fn factors(&self) {}

    /// Assembles I − c·J and factorizes it.
    fn factorize(&mut self, c: f64, _: &mut ()) -> Result<(), FactorizeError> {
        self.assemble(c);
        GridJacobian::factorize(self)
    }

    fn solve(&mut self, _: &mut (), b: &mut [f64]) -> Result<(), SolveError> {
        self.substitute(b)
    }
}

impl Clone for GridJacobian {
    fn clone(&self) -> Self {
        GridJacobian {
            nx: self.nx,
            ny: self.ny,
            blocks: self.blocks,
            slots: self.slots.clone(),
            diagonal: self.diagonal.clone(),
            jacobian: self.jacobian.clone(),
            cell: self.cell.clone(),
            solver: self.solver.clone(),
        }
    }
}

impl fmt::Debug for GridJacobian {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GridJacobian")
            .field("grid", &(self.nx, self.ny))
            .field("blocks", &self.blocks)
            .field("nonzeros", &self.jacobian.len())
            .field("factorizations", &self.solver.counts)
            .finish_non_exhaustive()
    }
}
