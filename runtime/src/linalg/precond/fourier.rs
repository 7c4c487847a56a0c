//! The Fourier (circulant) preconditioner of a field model on a periodic grid.
//!
//! Replace each block of the cells' Jacobian by its mean over the grid: the matrix I − c·J̄ is
//! then block circulant, the same stencil at every cell, and the two-dimensional discrete
//! Fourier transform diagonalises it — wave number (p, q) sees the fields × fields symbol
//!
//!   S(p, q) = I − c·Σ_b J̄_b·exp(2πi·(p·di_b/nx + q·dj_b/ny)),
//!
//! so P⁻¹·r is a transform of each field, a fields × fields solve per wave number, and the
//! inverse transform: O(N log N), exact where J is the same at every cell (diffusion with a
//! constant coefficient, a reaction at a uniform state), and close where the reaction varies
//! little over the grid against the diffusion. This is T. Chan's optimal circulant
//! preconditioner of the block Toeplitz part ("An optimal circulant preconditioner for Toeplitz
//! systems", SIAM J. Sci. Stat. Comput. 9(4):766–771, 1988; for elliptic problems R. H. Chan &
//! T. F. Chan, "Circulant preconditioners for elliptic problems", J. Numer. Linear Algebra Appl.
//! 1(1):77–101, 1992). The transforms are rustfft's.

use std::f64::consts::TAU;
use std::fmt;
use std::sync::Arc;

use faer::dyn_stack::{MemStack, StackReq};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::{Column, PrecondError, Preconditioning};
use crate::linalg::operator::{Edge, StencilBlock, StencilMatrix};
use crate::linalg::solver::SparseView;

type C = Complex<f64>;

/// The most fields a model may have for this preconditioner (block Jacobi beyond).
const MAX_FIELDS: usize = 8;

/// The transforms of a periodic grid and the inverse symbols of the last [`Fourier::update`].
#[derive(Clone)]
pub(crate) struct Fourier {
    nx: usize,
    ny: usize,
    fields: usize,
    blocks: Vec<StencilBlock>,
    /// Forward and inverse transforms along x (length nx) and along y (length ny).
    along_x: [Arc<dyn Fft<f64>>; 2],
    along_y: [Arc<dyn Fft<f64>>; 2],
    /// exp(2πi·p/nx) for p < nx, then exp(2πi·q/ny) for q < ny.
    twiddles: Vec<C>,
    /// S(p, q)⁻¹, fields × fields by rows, for wave number (p, q) at `(p·ny + q)·fields²`: the
    /// order the transforms leave the values in (x first, then y along the transposed rows).
    inverse: Vec<C>,
    /// Scratch the transforms ask for.
    fft_scratch: usize,
}

impl fmt::Debug for Fourier {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Fourier")
            .field("grid", &(self.nx, self.ny))
            .field("fields", &self.fields)
            .finish_non_exhaustive()
    }
}

impl Fourier {
    /// The preconditioner of `blocks` on an nx × ny grid of `fields` fields, None unless every
    /// field the blocks read is periodic (and there are at most [`MAX_FIELDS`] fields).
    pub(crate) fn new(
        nx: usize,
        ny: usize,
        fields: usize,
        blocks: &[StencilBlock],
    ) -> Option<Self> {
        if fields > MAX_FIELDS || blocks.iter().any(|b| b.edge != Edge::Wrap) {
            return None;
        }
        let mut planner = FftPlanner::new();
        let along_x = [planner.plan_fft_forward(nx), planner.plan_fft_inverse(nx)];
        let along_y = [planner.plan_fft_forward(ny), planner.plan_fft_inverse(ny)];
        let fft_scratch = along_x
            .iter()
            .chain(&along_y)
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let twiddles = (0..nx)
            .map(|p| C::from_polar(1.0, TAU * p as f64 / nx as f64))
            .chain((0..ny).map(|q| C::from_polar(1.0, TAU * q as f64 / ny as f64)))
            .collect();
        Some(Fourier {
            nx,
            ny,
            fields,
            twiddles,
            blocks: blocks.to_vec(),
            along_x,
            along_y,
            inverse: vec![C::default(); nx * ny * fields * fields],
            fft_scratch,
        })
    }

    /// Inverts the symbol of `stencil`'s I − c·J̄ at every wave number.
    ///
    /// Errors: [`PrecondError::SingularBlock`] when a symbol is singular (I − c·J̄ is).
    pub(crate) fn update(&mut self, stencil: &StencilMatrix) -> Result<(), PrecondError> {
        let (nx, ny, f) = (self.nx, self.ny, self.fields);
        let c = stencil.c();
        // exp(2πi·k·d/len) for an offset d of −1, 0 or 1.
        let power = |w: C, d: isize| match d {
            -1 => w.conj(),
            0 => C::new(1.0, 0.0),
            _ => w,
        };
        let mut symbol = [C::default(); MAX_FIELDS * MAX_FIELDS];
        let symbol = &mut symbol[..f * f];
        for p in 0..nx {
            for q in 0..ny {
                let (wx, wy) = (self.twiddles[p], self.twiddles[nx + q]);
                symbol.fill(C::default());
                for i in 0..f {
                    symbol[i * f + i] = C::new(1.0, 0.0);
                }
                for (b, block) in self.blocks.iter().enumerate() {
                    let phase = power(wx, block.di) * power(wy, block.dj);
                    symbol[block.row * f + block.column] -= phase * (c * stencil.mean(b));
                }
                let at = (p * ny + q) * f * f;
                invert(symbol, &mut self.inverse[at..at + f * f], f)?;
            }
        }
        Ok(())
    }
}

/// Writes the inverse of the f × f matrix `a` (by rows; destroyed) into `inverse`, by
/// Gauss–Jordan elimination with partial pivoting.
fn invert(a: &mut [C], inverse: &mut [C], f: usize) -> Result<(), PrecondError> {
    inverse.fill(C::default());
    for i in 0..f {
        inverse[i * f + i] = C::new(1.0, 0.0);
    }
    for col in 0..f {
        let pivot = (col..f)
            .max_by(|&r, &s| a[r * f + col].norm().total_cmp(&a[s * f + col].norm()))
            .unwrap_or(col);
        let size = a[pivot * f + col].norm();
        if !(size.is_finite() && size > 0.0) {
            return Err(PrecondError::SingularBlock);
        }
        for k in 0..f {
            a.swap(col * f + k, pivot * f + k);
            inverse.swap(col * f + k, pivot * f + k);
        }
        let scale = a[col * f + col].inv();
        for k in 0..f {
            a[col * f + k] *= scale;
            inverse[col * f + k] *= scale;
        }
        for row in (0..f).filter(|&row| row != col) {
            let factor = a[row * f + col];
            for k in 0..f {
                let (a_k, i_k) = (a[col * f + k], inverse[col * f + k]);
                a[row * f + k] -= factor * a_k;
                inverse[row * f + k] -= factor * i_k;
            }
        }
    }
    Ok(())
}

impl Preconditioning for Fourier {
    fn update_from(&mut self, a: &SparseView<'_>) -> Result<(), PrecondError> {
        self.update(a.stencil.ok_or(PrecondError::NoStencil)?)
    }
}

impl Column for Fourier {
    fn n(&self) -> usize {
        self.fields * self.nx * self.ny
    }

    fn scratch(&self) -> StackReq {
        let cells = self.nx * self.ny;
        StackReq::new::<C>((self.fields + 1) * cells + self.fft_scratch)
    }

    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        let Fourier {
            nx,
            ny,
            fields,
            ref along_x,
            ref along_y,
            ref inverse,
            fft_scratch,
            ..
        } = *self;
        let cells = nx * ny;
        let (mut spectra, stack) = stack.make_with(fields * cells, |_| C::default());
        let (mut grid, stack) = stack.make_with(cells, |_| C::default());
        let (mut scratch, _) = stack.make_with(fft_scratch, |_| C::default());
        let (grid, scratch) = (&mut *grid, &mut *scratch);
        // Each field: along x (rows of the grid), transpose, along y.
        for (field, spectrum) in spectra.chunks_exact_mut(cells).enumerate() {
            for (g, &v) in grid.iter_mut().zip(&r[field * cells..(field + 1) * cells]) {
                *g = C::new(v, 0.0);
            }
            along_x[0].process_with_scratch(grid, scratch);
            transpose(grid, spectrum, nx, ny);
            along_y[0].process_with_scratch(spectrum, scratch);
        }
        // Each wave number: z = S⁻¹·r̂.
        let mut z = [C::default(); MAX_FIELDS];
        for m in 0..cells {
            let s = &inverse[m * fields * fields..(m + 1) * fields * fields];
            for (i, zi) in z[..fields].iter_mut().enumerate() {
                *zi = (0..fields)
                    .map(|j| s[i * fields + j] * spectra[j * cells + m])
                    .sum();
            }
            for (i, zi) in z[..fields].iter().enumerate() {
                spectra[i * cells + m] = *zi;
            }
        }
        // Back: along y, transpose, along x; the inverse transforms leave a factor nx·ny.
        let scale = 1.0 / cells as f64;
        for (field, spectrum) in spectra.chunks_exact_mut(cells).enumerate() {
            along_y[1].process_with_scratch(spectrum, scratch);
            transpose(spectrum, grid, ny, nx);
            along_x[1].process_with_scratch(grid, scratch);
            for (o, g) in out[field * cells..(field + 1) * cells]
                .iter_mut()
                .zip(grid.iter())
            {
                *o = g.re * scale;
            }
        }
    }
}

/// `to` (cols × rows) = the transpose of `from` (rows × cols, by rows), `cols` = `len / rows`.
fn transpose(from: &[C], to: &mut [C], cols: usize, rows: usize) {
    for (j, row) in from.chunks_exact(cols).enumerate().take(rows) {
        for (i, &v) in row.iter().enumerate() {
            to[i * rows + j] = v;
        }
    }
}

#[cfg(test)]
mod tests {
    use faer::dyn_stack::MemBuffer;

    use super::*;

    /// Every block the same at every cell makes I − c·J circulant, which the preconditioner
    /// inverts exactly: P⁻¹·(A·x) = x to rounding, on square and oblong grids of odd and even
    /// sides, one to three fields, all nine neighbours and couplings between fields. A block
    /// that varies is replaced by its mean (checked against a grid of the mean values).
    #[test]
    fn inverts_a_circulant_operator_exactly() {
        let mut random = crate::linalg::signed(11);
        let offsets = [
            (0, 0),
            (1, 0),
            (-1, 0),
            (0, 1),
            (0, -1),
            (1, 1),
            (-1, 1),
            (1, -1),
            (-1, -1),
        ];
        for (nx, ny, fields) in [(3, 3, 1), (4, 6, 2), (7, 5, 3), (16, 16, 2)] {
            let blocks: Vec<StencilBlock> = (0..fields)
                .flat_map(|row| (0..fields).map(move |column| (row, column)))
                .flat_map(|(row, column)| {
                    offsets.iter().map(move |&(di, dj)| StencilBlock {
                        row,
                        column,
                        di,
                        dj,
                        edge: Edge::Wrap,
                    })
                })
                .collect();
            let cells = nx * ny;
            let n = fields * cells;
            let mut fourier = Fourier::new(nx, ny, fields, &blocks).expect("periodic");
            // Varying blocks (each cell its own value) and the same operator with their means.
            let mut varying = StencilMatrix::new(nx, ny, fields, blocks.clone());
            let mut uniform = StencilMatrix::new(nx, ny, fields, blocks.clone());
            for b in 0..blocks.len() {
                let values: Vec<f64> = (0..cells).map(|_| random()).collect();
                let mean = values.iter().sum::<f64>() / cells as f64;
                for (k, v) in values.into_iter().enumerate() {
                    varying.set(k, b, v);
                    uniform.set(k, b, mean);
                }
            }
            let c = 0.05;
            varying.prepare(c);
            uniform.prepare(c);
            let x: Vec<f64> = (0..n).map(|_| random()).collect();
            let mut ax = vec![0.0; n];
            uniform.product(&x, &mut ax, &x);
            let apply = |fourier: &Fourier, r: &[f64]| {
                let mut buffer = MemBuffer::new(fourier.scratch());
                let mut out = vec![f64::NAN; n];
                fourier.apply_column(&mut out, r, MemStack::new(&mut buffer));
                out
            };
            fourier.update(&uniform).unwrap();
            let back = apply(&fourier, &ax);
            fourier.update(&varying).unwrap();
            let from_means = apply(&fourier, &ax);
            for i in 0..n {
                assert!(
                    (back[i] - x[i]).abs() < 1e-12,
                    "{nx}×{ny}×{fields} [{i}]: {} against {}",
                    back[i],
                    x[i]
                );
                assert_eq!(from_means[i].to_bits(), back[i].to_bits());
            }
        }
        // A field that is not periodic: no Fourier preconditioner.
        let clamped = StencilBlock {
            row: 0,
            column: 0,
            di: 1,
            dj: 0,
            edge: Edge::Clamp,
        };
        assert!(Fourier::new(4, 4, 1, &[clamped]).is_none());
    }

    /// A singular symbol (I − c·J̄ singular at wave number 0: c·J̄ = 1) is an error, not NaN.
    #[test]
    fn a_singular_symbol_is_an_error() {
        let centre = StencilBlock {
            row: 0,
            column: 0,
            di: 0,
            dj: 0,
            edge: Edge::Wrap,
        };
        let mut stencil = StencilMatrix::new(3, 3, 1, vec![centre]);
        for k in 0..9 {
            stencil.set(k, 0, 2.0);
        }
        stencil.prepare(0.5);
        let mut fourier = Fourier::new(3, 3, 1, &[centre]).unwrap();
        assert_eq!(fourier.update(&stencil), Err(PrecondError::SingularBlock));
    }
}
