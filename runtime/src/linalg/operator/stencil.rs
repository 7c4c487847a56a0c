//! I − c·J of a field model applied on its grid, from the cells' Jacobian blocks, without the
//! assembled matrix: the matrix-free products of the Krylov solves of field models.
//!
//! Each block is one structural non-zero of a cell's Jacobian — ∂(field `row` at the
//! cell)/∂(field `column` at the neighbour (i + di, j + dj)) — with a value per cell, or one
//! value for the whole grid when every cell has the same (a constant diffusion coefficient's
//! blocks: found at every [`StencilMatrix::prepare`]). A product walks the grid row by row and,
//! in each row, block by block over contiguous runs of cells, so it reads x, the varying
//! blocks' values and writes y once, with no column indices: on Gray–Scott (two fields, a
//! five-point Laplacian) that is 4 values a cell where the matrix by rows reads 12 values and
//! 12 indices.

use faer::dyn_stack::{MemStack, StackReq};

use super::Column;

/// What a read past the grid's edge in one direction gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Edge {
    /// The opposite edge's cell (periodic).
    Wrap,
    /// The edge cell itself (zero flux).
    Clamp,
    /// A constant, which has no column (a fixed boundary value).
    Drop,
}

impl Edge {
    /// The index of cell p + d of a line of `len` cells (|d| ≤ 1), None for a dropped read.
    #[inline(always)]
    fn at(self, p: usize, d: isize, len: usize) -> Option<usize> {
        let q = p as isize + d;
        if (0..len as isize).contains(&q) {
            return Some(q as usize);
        }
        match self {
            Edge::Wrap if q < 0 => Some((q + len as isize) as usize),
            Edge::Wrap => Some((q - len as isize) as usize),
            Edge::Clamp => Some(q.clamp(0, len as isize - 1) as usize),
            Edge::Drop => None,
        }
    }
}

/// One structural non-zero of every cell's Jacobian.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct StencilBlock {
    /// The output field.
    pub(crate) row: usize,
    /// The input field.
    pub(crate) column: usize,
    /// The neighbour's offset, |di|, |dj| ≤ 1.
    pub(crate) di: isize,
    pub(crate) dj: isize,
    /// The input field's boundary.
    pub(crate) edge: Edge,
}

/// I − c·J on an nx × ny grid of `fields` fields stored field after field, J given by its
/// cells' blocks.
#[derive(Clone, Debug)]
pub(crate) struct StencilMatrix {
    nx: usize,
    ny: usize,
    fields: usize,
    blocks: Vec<StencilBlock>,
    /// J's value of block b at cell k, at `values[b·cells + k]`.
    values: Vec<f64>,
    /// Block b's value where every cell has the same, found by [`StencilMatrix::prepare`].
    uniform: Vec<Option<f64>>,
    /// Block b's mean over the cells, found by [`StencilMatrix::prepare`].
    mean: Vec<f64>,
    c: f64,
}

impl StencilMatrix {
    /// The operator of `blocks` on an nx × ny grid of `fields` fields, every value zero.
    pub(crate) fn new(nx: usize, ny: usize, fields: usize, blocks: Vec<StencilBlock>) -> Self {
        StencilMatrix {
            nx,
            ny,
            fields,
            values: vec![0.0; blocks.len() * nx * ny],
            uniform: vec![None; blocks.len()],
            mean: vec![0.0; blocks.len()],
            blocks,
            c: 0.0,
        }
    }

    /// Sets J's value of block b at cell k (before the next [`StencilMatrix::prepare`]).
    #[inline(always)]
    pub(crate) fn set(&mut self, k: usize, b: usize, value: f64) {
        self.values[b * self.nx * self.ny + k] = value;
    }

    /// Makes the operator I − c·J of the values set: finds the blocks with one value for every
    /// cell, whose products then read that value alone, and each block's mean.
    pub(crate) fn prepare(&mut self, c: f64) {
        self.c = c;
        let cells = self.nx * self.ny;
        for ((uniform, mean), values) in self
            .uniform
            .iter_mut()
            .zip(&mut self.mean)
            .zip(self.values.chunks_exact(cells))
        {
            let first = values[0];
            *uniform = values.iter().all(|&v| v == first).then_some(first);
            *mean = match *uniform {
                Some(value) => value,
                None => values.iter().sum::<f64>() / cells as f64,
            };
        }
    }

    /// The grid and its fields, (nx, ny, fields).
    pub(crate) fn shape(&self) -> (usize, usize, usize) {
        (self.nx, self.ny, self.fields)
    }

    /// c of I − c·J.
    pub(crate) fn c(&self) -> f64 {
        self.c
    }

    /// Block b's mean over the cells.
    pub(crate) fn mean(&self, b: usize) -> f64 {
        self.mean[b]
    }

    /// The blocks.
    pub(crate) fn blocks(&self) -> &[StencilBlock] {
        &self.blocks
    }

    /// Block b's value for the whole grid, if it has one.
    #[cfg(test)]
    pub(crate) fn uniform(&self, b: usize) -> Option<f64> {
        self.uniform[b]
    }

    /// y = (I − c·J)·x, and (w·y, y·y).
    pub(crate) fn product(&self, x: &[f64], y: &mut [f64], w: &[f64]) -> (f64, f64) {
        let (nx, ny) = (self.nx, self.ny);
        let cells = nx * ny;
        let (mut wy, mut yy) = (0.0, 0.0);
        for j in 0..ny {
            let row = j * nx;
            for f in 0..self.fields {
                y[f * cells + row..][..nx].fill(0.0);
            }
            // y's rows gather J·x, block by block.
            for (b, block) in self.blocks.iter().enumerate() {
                let Some(source) = block.edge.at(j, block.dj, ny) else {
                    continue;
                };
                let x = &x[block.column * cells + source * nx..][..nx];
                let out = &mut y[block.row * cells + row..][..nx];
                let values = &self.values[b * cells + row..][..nx];
                // Cells whose neighbour is inside the row: lo..hi, read at i + di.
                let lo = (-block.di).max(0) as usize;
                let hi = (nx - block.di.max(0) as usize).max(lo);
                let shifted = &x[(lo as isize + block.di) as usize..][..hi - lo];
                match self.uniform[b] {
                    Some(a) => {
                        for (o, s) in out[lo..hi].iter_mut().zip(shifted) {
                            *o += a * s;
                        }
                    }
                    None => {
                        for ((o, s), a) in out[lo..hi].iter_mut().zip(shifted).zip(&values[lo..hi])
                        {
                            *o += a * s;
                        }
                    }
                }
                for i in (0..lo).chain(hi..nx) {
                    if let Some(at) = block.edge.at(i, block.di, nx) {
                        out[i] += self.uniform[b].unwrap_or(values[i]) * x[at];
                    }
                }
            }
            for f in 0..self.fields {
                let range = f * cells + row..f * cells + row + nx;
                for ((yi, xi), wi) in y[range.clone()]
                    .iter_mut()
                    .zip(&x[range.clone()])
                    .zip(&w[range])
                {
                    *yi = xi - self.c * *yi;
                    wy += wi * *yi;
                    yy += *yi * *yi;
                }
            }
        }
        (wy, yy)
    }
}

/// faer's operator, for its conjugate gradient (through [`super::column_operator!`]).
impl Column for StencilMatrix {
    fn n(&self) -> usize {
        self.fields * self.nx * self.ny
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.product(r, out, r);
    }
}
