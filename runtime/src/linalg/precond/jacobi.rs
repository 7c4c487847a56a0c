//! Block Jacobi: the inverse of each group's diagonal block, by Gauss–Jordan elimination.

use std::fmt;

use faer::dyn_stack::{MemStack, StackReq};
use faer::sparse::SymbolicSparseColMat;

use super::{Column, PrecondError, Preconditioning};
use crate::linalg::solver::SparseView;

/// Block Jacobi: z = diag(B₁⁻¹, …, B_g⁻¹)·r, with Bₖ the matrix's entries among the unknowns of
/// group k.
#[derive(Clone)]
pub(crate) struct BlockJacobi {
    /// Unknowns per group.
    size: usize,
    /// Group k's unknowns at k·size … (k+1)·size.
    index: Vec<usize>,
    /// (a, b) when unknown f of group k is k·a + f·b: a field model's cells (a = 1, b = cells)
    /// or a particle model's particles (a = size, b = 1). Application then computes the
    /// unknowns rather than reading `index` (a megabyte at 256² cells).
    strides: Option<(usize, usize)>,
    /// Slot in the matrix's values of block entry (r, c) of group k at k·size² + r·size + c;
    /// `usize::MAX` where the pattern has no entry.
    slots: Vec<usize>,
    /// Each group's inverse block, row-major, at k·size².
    inverse: Vec<f64>,
    /// Room for one block's elimination (2·size²).
    work: Vec<f64>,
}

impl BlockJacobi {
    /// Groups of `size` unknowns listed in `index` (every unknown once), over `pattern`.
    pub(crate) fn new(
        size: usize,
        index: Vec<usize>,
        pattern: &SymbolicSparseColMat<usize>,
    ) -> Self {
        let groups = index.len() / size.max(1);
        let mut slots = Vec::with_capacity(groups * size * size);
        for k in 0..groups {
            let unknowns = &index[k * size..(k + 1) * size];
            for &row in unknowns {
                for &col in unknowns {
                    let start = pattern.col_ptr()[col];
                    let rows = pattern.row_idx_of_col_raw(col);
                    slots.push(rows.binary_search(&row).map_or(usize::MAX, |p| start + p));
                }
            }
        }
        let strides = [(1, groups), (size, 1)].into_iter().find(|&(a, b)| {
            index.chunks(size.max(1)).enumerate().all(|(k, unknowns)| {
                unknowns
                    .iter()
                    .enumerate()
                    .all(|(f, &i)| i == k * a + f * b)
            })
        });
        BlockJacobi {
            size,
            inverse: vec![0.0; slots.len()],
            strides,
            index,
            slots,
            work: vec![0.0; 2 * size * size],
        }
    }

    /// Inverts every block of the matrix with `values`.
    ///
    /// Errors: [`PrecondError::SingularBlock`].
    pub(crate) fn update(&mut self, values: &[f64]) -> Result<(), PrecondError> {
        // A constant block size unrolls the elimination, as in `apply`.
        match self.size {
            1 => self.update_sized(1, values),
            2 => self.update_sized(2, values),
            3 => self.update_sized(3, values),
            4 => self.update_sized(4, values),
            b => self.update_sized(b, values),
        }
    }

    /// [`BlockJacobi::update`] with the block size `b`.
    #[inline(always)]
    fn update_sized(&mut self, b: usize, values: &[f64]) -> Result<(), PrecondError> {
        let (a, inverse) = self.work.split_at_mut(b * b);
        for (slots, out) in self.slots.chunks(b * b).zip(self.inverse.chunks_mut(b * b)) {
            for (entry, &slot) in a.iter_mut().zip(slots) {
                *entry = values.get(slot).copied().unwrap_or(0.0);
            }
            invert(b, a, inverse)?;
            out.copy_from_slice(inverse);
        }
        Ok(())
    }

    fn apply(&self, out: &mut [f64], r: &[f64]) {
        // Blocks of a size known at compile time keep the loops over a block's entries out of
        // the code: on Gray–Scott at 256² (2 × 2 blocks) block Jacobi went from 18 % to 11 % of
        // a Krylov step (perf, one run each).
        match self.size {
            1 => self.apply_sized::<1>(out, r),
            2 => self.apply_sized::<2>(out, r),
            3 => self.apply_sized::<3>(out, r),
            4 => self.apply_sized::<4>(out, r),
            b => {
                for (unknowns, inverse) in self.index.chunks(b).zip(self.inverse.chunks(b * b)) {
                    for (&row, inverse) in unknowns.iter().zip(inverse.chunks(b)) {
                        out[row] = unknowns
                            .iter()
                            .zip(inverse)
                            .map(|(&col, m)| m * r[col])
                            .sum();
                    }
                }
            }
        }
    }

    /// [`BlockJacobi::apply`] for blocks of `B` unknowns.
    fn apply_sized<const B: usize>(&self, out: &mut [f64], r: &[f64]) {
        if let Some((a, b)) = self.strides {
            for (k, inverse) in self.inverse.chunks_exact(B * B).enumerate() {
                let local: [f64; B] = std::array::from_fn(|f| r[k * a + f * b]);
                for (f, inverse) in inverse.chunks_exact(B).enumerate() {
                    out[k * a + f * b] = (0..B).map(|c| inverse[c] * local[c]).sum();
                }
            }
            return;
        }
        for (unknowns, inverse) in self
            .index
            .chunks_exact(B)
            .zip(self.inverse.chunks_exact(B * B))
        {
            let local: [f64; B] = std::array::from_fn(|c| r[unknowns[c]]);
            for (&row, inverse) in unknowns.iter().zip(inverse.chunks_exact(B)) {
                out[row] = (0..B).map(|c| inverse[c] * local[c]).sum();
            }
        }
    }
}

/// A⁻¹ of the b × b row-major matrix `a` (overwritten) into `inverse`, by Gauss–Jordan
/// elimination with partial pivoting.
///
/// Errors: [`PrecondError::SingularBlock`] when a pivot is zero or not finite.
#[inline(always)]
pub(crate) fn invert(b: usize, a: &mut [f64], inverse: &mut [f64]) -> Result<(), PrecondError> {
    for (k, entry) in inverse.iter_mut().enumerate() {
        *entry = if k % (b + 1) == 0 { 1.0 } else { 0.0 };
    }
    for col in 0..b {
        let pivot = (col..b)
            .max_by(|&i, &j| a[i * b + col].abs().total_cmp(&a[j * b + col].abs()))
            .unwrap_or(col);
        let p = a[pivot * b + col];
        if p == 0.0 || !p.is_finite() {
            return Err(PrecondError::SingularBlock);
        }
        for c in 0..b {
            a.swap(col * b + c, pivot * b + c);
            inverse.swap(col * b + c, pivot * b + c);
        }
        for c in 0..b {
            a[col * b + c] /= p;
            inverse[col * b + c] /= p;
        }
        for row in (0..b).filter(|&row| row != col) {
            let factor = a[row * b + col];
            if factor != 0.0 {
                for c in 0..b {
                    a[row * b + c] -= factor * a[col * b + c];
                    inverse[row * b + c] -= factor * inverse[col * b + c];
                }
            }
        }
    }
    Ok(())
}

impl fmt::Debug for BlockJacobi {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BlockJacobi")
            .field("n", &self.index.len())
            .field("block", &self.size)
            .finish()
    }
}

impl Column for BlockJacobi {
    fn n(&self) -> usize {
        self.index.len()
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.apply(out, r);
    }
}

impl Preconditioning for BlockJacobi {
    fn update_from(&mut self, a: &SparseView<'_>) -> Result<(), PrecondError> {
        self.update(a.values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_jordan_inverts_and_reports_singular_blocks() {
        // A 3×3 block needing a row swap (zero leading entry); A·A⁻¹ = I.
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let mut work = a;
        let mut inverse = [0.0; 9];
        invert(3, &mut work, &mut inverse).expect("a regular block");
        for r in 0..3 {
            for c in 0..3 {
                let product: f64 = (0..3).map(|k| a[r * 3 + k] * inverse[k * 3 + c]).sum();
                let identity = if r == c { 1.0 } else { 0.0 };
                assert!((product - identity).abs() < 1e-15, "({r}, {c}): {product}");
            }
        }
        let mut singular = [1.0, 2.0, 2.0, 4.0];
        let mut inverse = [0.0; 4];
        assert_eq!(
            invert(2, &mut singular, &mut inverse),
            Err(PrecondError::SingularBlock)
        );
    }

    /// Unknowns found by strides (a field model's order) and the same groups listed in another
    /// order give the same product to the bit: each group's arithmetic is the same.
    #[test]
    fn strided_and_listed_groups_apply_alike() {
        use faer::sparse::Pair;
        let (n, cells) = (6, 3);
        let pairs: Vec<Pair<usize, usize>> = (0..n)
            .flat_map(|i| (0..n).map(move |j| Pair::new(i, j)))
            .collect();
        let (pattern, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).unwrap();
        let values: Vec<f64> = (0..n * n)
            .map(|k| {
                if k % (n + 1) == 0 {
                    4.0
                } else {
                    (k % 5) as f64 * 0.3 - 0.6
                }
            })
            .collect();
        let strided: Vec<usize> = (0..cells).flat_map(|k| [k, cells + k]).collect();
        let listed: Vec<usize> = (0..cells).rev().flat_map(|k| [k, cells + k]).collect();
        let r = [1.0, -2.0, 0.5, 3.0, -1.5, 2.5];
        let mut outs = Vec::new();
        for index in [strided, listed] {
            let mut jacobi = BlockJacobi::new(2, index, &pattern);
            jacobi.update(&values).expect("regular blocks");
            let mut out = [0.0; 6];
            jacobi.apply(&mut out, &r);
            outs.push((jacobi.strides, out));
        }
        assert_eq!(outs[0].0, Some((1, cells)));
        assert_eq!(outs[1].0, None);
        assert_eq!(outs[0].1, outs[1].1);
    }
}
