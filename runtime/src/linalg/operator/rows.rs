//! The matrix by rows, for the products of the Krylov solves: rows in chunks of [`CHUNK`], each
//! chunk's rows padded to its widest, with 32-bit column indices.
//!
//! faer keeps a sparse matrix by columns, where a product scatters into the result; by rows each
//! result entry is one short dot product, and the dot products the Krylov methods need of the
//! result come in the same pass. Padding a chunk's rows to one width takes the row length out of
//! the inner loop, and 32-bit indices halve their share of the memory read: on Gray–Scott at
//! 256² (131 072 rows of 6 entries) such a product took 0.3–0.4 ms against 0.5–0.7 ms for a
//! compressed-row loop with 32-bit indices and 0.6–1.0 ms with 64-bit ones (standalone loops,
//! fastest of eight runs each, on the shared machine).

use faer::dyn_stack::{MemStack, StackReq};
use faer::sparse::SymbolicSparseColMat;

use super::Column;

/// Rows a chunk pads to one width.
const CHUNK: usize = 64;

/// A square sparse matrix by rows, its pattern fixed and its values copied from the column-major
/// values of [`crate::linalg::sparse::SparseSolver`] at every factorization.
#[derive(Clone, Debug)]
pub(crate) struct RowMatrix {
    /// Rows (and columns).
    n: usize,
    /// Entries of chunk c's rows start at `start[c]`, `width[c]` a row.
    start: Vec<usize>,
    width: Vec<usize>,
    /// The column of each entry (a padding entry repeats its row's last column).
    column: Vec<u32>,
    values: Vec<f64>,
    /// The slot in the column-major values each entry copies; [`PADDING`] for padding.
    source: Vec<u32>,
}

/// [`RowMatrix::source`] of a padding entry.
const PADDING: u32 = u32::MAX;

impl RowMatrix {
    /// The rows of a structurally symmetric `pattern` (every entry's transpose is in it, as in
    /// [`crate::linalg::sparse::SparseSolver`]'s), values zero. None when it has too many rows or entries for
    /// 32-bit indices.
    pub(crate) fn new(pattern: &SymbolicSparseColMat<usize>) -> Option<Self> {
        let n = pattern.nrows();
        let nnz = pattern.compute_nnz();
        // Structural symmetry makes column i's row indices row i's column indices.
        let row = |i: usize| pattern.row_idx_of_col_raw(i);
        let chunks = n.div_ceil(CHUNK);
        let mut start = Vec::with_capacity(chunks);
        let mut width = Vec::with_capacity(chunks);
        let mut stored = 0;
        for c in 0..chunks {
            let rows = c * CHUNK..((c + 1) * CHUNK).min(n);
            let w = rows.clone().map(|i| row(i).len()).max().unwrap_or(0);
            start.push(stored);
            width.push(w);
            stored += w * rows.len();
        }
        if u32::try_from(n).is_err() || u32::try_from(nnz).is_err() || stored >= PADDING as usize {
            return None;
        }
        let mut column = Vec::with_capacity(stored);
        let mut source = Vec::with_capacity(stored);
        for (c, &w) in width.iter().enumerate() {
            for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                let columns = row(i);
                for &j in columns {
                    column.push(j as u32);
                    // Entry (i, j) is in column j, at row i.
                    let at = pattern.row_idx_of_col_raw(j).binary_search(&i).expect(
                        "the pattern is structurally symmetric: (i, j) is there with (j, i)",
                    );
                    source.push((pattern.col_ptr()[j] + at) as u32);
                }
                let last = columns.last().map_or(i as u32, |&j| j as u32);
                for _ in columns.len()..w {
                    column.push(last);
                    source.push(PADDING);
                }
            }
        }
        Some(RowMatrix {
            n,
            start,
            width,
            column,
            values: vec![0.0; stored],
            source,
        })
    }

    /// Copies the values of the matrix from its column-major `values`.
    pub(crate) fn update(&mut self, values: &[f64]) {
        for (v, &s) in self.values.iter_mut().zip(&self.source) {
            *v = values.get(s as usize).copied().unwrap_or(0.0);
        }
    }

    /// y = A·x, and (w·y, y·y), the dot products summed row by row in order.
    pub(crate) fn product(&self, x: &[f64], y: &mut [f64], w: &[f64]) -> (f64, f64) {
        let (mut wy, mut yy) = (0.0, 0.0);
        for ((y, w), (&start, &width)) in y
            .chunks_mut(CHUNK)
            .zip(w.chunks(CHUNK))
            .zip(self.start.iter().zip(&self.width))
        {
            let len = y.len() * width;
            // max(1): chunks_exact(0) panics; a chunk of empty rows (none in the solver's
            // patterns, which hold the diagonal) then yields no rows, and its y is zeroed here.
            let columns = self.column[start..start + len].chunks_exact(width.max(1));
            let values = self.values[start..start + len].chunks_exact(width.max(1));
            if width == 0 {
                y.fill(0.0);
            }
            for (((yi, wi), columns), values) in y.iter_mut().zip(w).zip(columns).zip(values) {
                let sum: f64 = columns
                    .iter()
                    .zip(values)
                    .map(|(&j, a)| a * x[j as usize])
                    .sum();
                *yi = sum;
                wy += wi * sum;
                yy += sum * sum;
            }
        }
        (wy, yy)
    }
}

/// faer's operator, for its conjugate gradient: the same products as BiCGSTAB's (through
/// [`super::column_operator!`]).
impl Column for RowMatrix {
    fn n(&self) -> usize {
        self.n
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.product(r, out, r);
    }
}

#[cfg(test)]
mod tests {
    use faer::sparse::{Pair, SparseColMatRef};
    use faer::{Accum, MatMut, MatRef, Par};

    use super::*;
    use crate::linalg::generator;

    /// The product by rows of the pattern of `pairs` and their transposes (with the diagonal),
    /// random values in [−1, 1] and x in [−10, 10], against faer's product by columns.
    fn matches_faer(n: usize, pairs: &[(usize, usize)], random: &mut impl FnMut() -> usize) {
        let pairs: Vec<Pair<usize, usize>> = pairs
            .iter()
            .flat_map(|&(i, j)| [Pair::new(i, j), Pair::new(j, i)])
            .chain((0..n).map(|i| Pair::new(i, i)))
            .collect();
        let (pattern, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).unwrap();
        let mut uniform = |scale: f64| (random() % 2001) as f64 / 1000.0 * scale - scale;
        let values: Vec<f64> = (0..pattern.compute_nnz()).map(|_| uniform(1.0)).collect();
        let x: Vec<f64> = (0..n).map(|_| uniform(10.0)).collect();
        let w: Vec<f64> = (0..n).map(|_| uniform(1.0)).collect();
        let mut rows = RowMatrix::new(&pattern).expect("a small pattern");
        rows.update(&values);
        let mut y = vec![f64::NAN; n];
        let (wy, yy) = rows.product(&x, &mut y, &w);
        let mut expected = vec![0.0; n];
        faer::sparse::linalg::matmul::sparse_dense_matmul(
            MatMut::from_column_major_slice_mut(&mut expected, n, 1),
            Accum::Replace,
            SparseColMatRef::new(pattern.as_ref(), &values),
            MatRef::from_column_major_slice(&x, n, 1),
            1.0,
            Par::Seq,
        );
        // The two sum a row's L products in different orders, each within (L − 1)·2⁻⁵³ of
        // Σ|aᵢⱼ·xⱼ| ≤ 10·L of the exact sum (Higham 2002, §4.2): so within 20·L²·2⁻⁵³.
        let longest = (0..n).map(|j| pattern.row_idx_of_col_raw(j).len()).max();
        let tolerance = 20.0 * (longest.unwrap_or(0) as f64).powi(2) * f64::EPSILON / 2.0;
        for (i, (a, b)) in y.iter().zip(&expected).enumerate() {
            assert!((a - b).abs() <= tolerance, "row {i}: {a} against {b}");
        }
        let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        assert!((wy - dot(&w, &expected)).abs() < 1e-10);
        assert!((yy - dot(&expected, &expected)).abs() < 1e-12 * yy);
    }

    /// Random patterns (rows of different lengths, so chunks pad), and rings of rows of 5 to 8
    /// entries, a grid's widths (i ± 1, …, i ± d, and for even widths the row half the ring
    /// away).
    #[test]
    fn the_product_by_rows_is_faers() {
        let mut random = generator(12345);
        let n = 300;
        let mut pairs = Vec::new();
        for i in 0..n {
            for _ in 0..random() % 6 {
                pairs.push((i, random() % n));
            }
        }
        matches_faer(n, &pairs, &mut random);
        for width in 5..=8 {
            let mut pairs: Vec<(usize, usize)> = (0..n)
                .flat_map(|i| (1..=(width - 1) / 2).map(move |d| (i, (i + d) % n)))
                .collect();
            if width % 2 == 0 {
                pairs.extend((0..n / 2).map(|i| (i, i + n / 2)));
            }
            matches_faer(n, &pairs, &mut random);
        }
    }
}
