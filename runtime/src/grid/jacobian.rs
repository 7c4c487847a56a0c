//! The sparse Jacobian of a field model and its Newton solve.

use std::fmt;

use faer::sparse::SparseColMatRef;

use super::stencil::neighbour;
use super::{Block, Boundary, NEIGHBOURS};
use crate::linalg::dense::finite;
use crate::linalg::sparse::{Edge, SparseSolver, StencilBlock, StencilMatrix};
use crate::stats::LinearWork;
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
    /// J by its cells' blocks, for the matrix-free products of Krylov solves.
    stencil: StencilMatrix,
    /// c of the last assembly of I − c·J.
    c: f64,
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
        let edge = |boundary: Boundary| match boundary {
            Boundary::Periodic => Edge::Wrap,
            Boundary::Neumann => Edge::Clamp,
            Boundary::Dirichlet(_) => Edge::Drop,
        };
        let stencil: Vec<StencilBlock> = blocks
            .iter()
            .map(|b| {
                let (_, di, dj) = NEIGHBOURS[b.neighbour];
                let edge = edge(boundaries[b.column]);
                StencilBlock {
                    row: b.row,
                    column: b.column,
                    di,
                    dj,
                    edge,
                }
            })
            .collect();
        let stencil = StencilMatrix::new(nx, ny, fields, stencil);
        solver.on_grid();
        GridJacobian {
            nx,
            ny,
            blocks: blocks.len(),
            stencil,
            c: 0.0,
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
    pub fn factorizations(&self) -> LinearWork {
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
        for (b, (&slot, &value)) in slots.iter().zip(&self.cell).enumerate() {
            if let Some(entry) = self.jacobian.get_mut(slot) {
                *entry += value;
            }
            self.stencil.set(k, b, value);
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
        self.c = c;
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
        // The stencil serves the Krylov solves only: a direct run skips its scan of the blocks.
        if !self.solver.krylov_configured() {
            return self.solver.factorize();
        }
        self.stencil.prepare(self.c);
        self.solver.factorize_with(Some(&self.stencil))
    }

    /// Solves the last factorization against `b` in place: the "solve" of a step's cost.
    ///
    /// Errors: [`SolveError::WrongLength`], [`SolveError::NotFinite`], [`SolveError::Singular`].
    pub fn substitute(&mut self, b: &mut [f64]) -> Result<(), SolveError> {
        let expected = self.solver.rhs.len();
        if b.len() != expected {
            return Err(SolveError::WrongLength {
                expected,
                found: b.len(),
            });
        }
        self.solver.rhs.copy_from_slice(b);
        self.solver.substitute_with(Some(&self.stencil))?;
        b.copy_from_slice(&self.solver.rhs);
        finite(b)
    }
}

impl NewtonMatrix for GridJacobian {
    const COSTLY_SOLVES: bool = true;

    fn work(&self) -> LinearWork {
        self.solver.counts
    }

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

    /// Assembles M − c·J and factorizes it directly: the Krylov solves' matrix-free products
    /// and preconditioners are built for I − c·J, so a field model with algebraic fields solves
    /// by sparse LU whatever [`crate::LinearSolver`] the run chose.
    fn factorize_mass(
        &mut self,
        c: f64,
        mass: &[(usize, usize, f64)],
        _: &mut (),
    ) -> Result<(), FactorizeError> {
        self.c = c;
        for (w, j) in self.solver.values.iter_mut().zip(&self.jacobian) {
            *w = -c * j;
        }
        for &(row, column, m) in mass {
            let slot = match row == column {
                true => self.diagonal[row],
                false => self.solver.slot(row, column),
            };
            self.solver.values[slot] += m;
        }
        self.solver.factorize_direct_only()
    }

    fn solve(&mut self, _: &mut (), b: &mut [f64]) -> Result<(), SolveError> {
        self.substitute(b)
    }

    fn entries_among(&self, components: &[usize], out: &mut Vec<(usize, usize, f64)>) {
        let matrix = SparseColMatRef::new(self.solver.matrix().symbolic(), &self.jacobian);
        for (b, &column) in components.iter().enumerate() {
            for (row, &value) in matrix.row_idx_of_col(column).zip(matrix.val_of_col(column)) {
                if let Ok(a) = components.binary_search(&row) {
                    out.push((a, b, value));
                }
            }
        }
    }

    fn non_finite_entry(&self) -> Option<(usize, usize, f64)> {
        if self.jacobian.iter().all(|x| x.is_finite()) {
            return None;
        }
        let matrix = SparseColMatRef::new(self.solver.matrix().symbolic(), &self.jacobian);
        (0..matrix.ncols()).find_map(|column| {
            matrix
                .row_idx_of_col(column)
                .zip(matrix.val_of_col(column))
                .find(|(_, value)| !value.is_finite())
                .map(|(row, &value)| (row, column, value))
        })
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
            stencil: self.stencil.clone(),
            c: self.c,
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The matrix-free products equal the assembled I − c·J's (`to_dense`, placed through
    /// `stencil::neighbour`), on every boundary, grids down to one cell a side, the nine
    /// neighbours, couplings between fields, and blocks varying by cell or uniform.
    #[test]
    fn stencil_products_are_the_assembled_matrix() {
        let mut random = crate::linalg::signed(7);
        let mut blocks: Vec<Block> = (0..9)
            .map(|neighbour| Block {
                row: 0,
                column: 0,
                neighbour,
            })
            .collect();
        for (row, column, neighbour) in [(0, 1, 0), (1, 0, 1), (1, 1, 0), (1, 1, 8), (1, 0, 6)] {
            blocks.push(Block {
                row,
                column,
                neighbour,
            });
        }
        let c = 0.37;
        for (nx, ny, boundaries) in [
            (3, 3, [Boundary::Periodic, Boundary::Periodic]),
            (5, 4, [Boundary::Periodic, Boundary::Neumann]),
            (4, 3, [Boundary::Neumann, Boundary::Dirichlet(0.5)]),
            (1, 4, [Boundary::Neumann, Boundary::Dirichlet(-1.0)]),
            (2, 1, [Boundary::Dirichlet(2.0), Boundary::Neumann]),
            (1, 1, [Boundary::Neumann, Boundary::Neumann]),
        ] {
            let mut jacobian = GridJacobian::new(nx, ny, &boundaries, &blocks);
            // Block 3 (north) is the same in every cell; the others vary.
            let uniform = random();
            jacobian.begin();
            for k in 0..nx * ny {
                for (b, value) in jacobian.cell_blocks().iter_mut().enumerate() {
                    *value = if b == 3 { uniform } else { random() };
                }
                jacobian.place(k);
            }
            jacobian.assemble(c);
            jacobian.stencil.prepare(c);
            assert_eq!(jacobian.stencil.uniform(3), Some(uniform));
            let n = 2 * nx * ny;
            let x: Vec<f64> = (0..n).map(|_| random()).collect();
            let w: Vec<f64> = (0..n).map(|_| random()).collect();
            let mut y = vec![f64::NAN; n];
            let (wy, yy) = jacobian.stencil.product(&x, &mut y, &w);
            let mut matrix = -c * jacobian.to_dense();
            for i in 0..n {
                matrix[(i, i)] += 1.0;
            }
            let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
            // Sums of at most 15 terms of size ≤ 1 in different orders: far below 1e-12.
            for (i, yi) in y.iter().enumerate() {
                let expected: f64 = (0..n).map(|j| matrix[(i, j)] * x[j]).sum();
                assert!(
                    (yi - expected).abs() < 1e-12,
                    "{nx}×{ny} row {i}: {yi} against {expected}"
                );
            }
            assert!((wy - dot(&w, &y)).abs() < 1e-12 && (yy - dot(&y, &y)).abs() < 1e-12);
        }
    }
}
