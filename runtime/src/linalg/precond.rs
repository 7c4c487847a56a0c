//! Preconditioners for the Krylov solves of sparse Newton matrices.
//!
//! - [`BlockJacobi`]: the inverse of each small diagonal block — a particle's D×D block of
//!   M − h·∂f/∂v − h²·∂f/∂x, or a cell's fields × fields block of I − h·J — built from the
//!   assembled values every factorization. Cheap (a few flops per unknown), and exact for the
//!   couplings inside a particle or a cell.
//! - [`Ilu0`]: the incomplete LU factorization on the matrix's own pattern (no fill), rebuilt
//!   every factorization: a sparse product's cost per application, and far fewer iterations
//!   than block Jacobi on diffusion-dominated matrices.
//! - [`Factors`]: the sparse Cholesky or LU factors of an earlier matrix, applied by
//!   substitution: the strongest preconditioner odyn can offer for a slowly changing matrix,
//!   refreshed when the Krylov iteration count says the matrix has moved on.

use std::fmt;

use faer::dyn_stack::{MemStack, StackReq};
use faer::matrix_free::{LinOp, Precond};
use faer::sparse::SymbolicSparseColMat;
use faer::sparse::linalg::cholesky::LltRef;
use faer::sparse::linalg::lu::LuRef;
use faer::{Conj, MatMut, MatRef, Par};

/// Why a preconditioner could not be built from a matrix's values; the sparse solver then
/// factorizes directly, which decides whether the matrix is singular.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PrecondError {
    /// A diagonal block (block Jacobi's, or a multigrid level's smoother's) has a zero or
    /// non-finite pivot.
    SingularBlock,
    /// ILU(0) met a zero or non-finite pivot.
    ZeroPivot,
    /// Multigrid's coarsest matrix has a zero or non-finite pivot.
    SingularCoarsest,
    /// Multigrid's bound on ρ(D⁻¹A) is zero or not finite: there is no weight to smooth the
    /// prolongator with.
    NoSmoothingWeight,
}

/// Block Jacobi: z = diag(B₁⁻¹, …, B_g⁻¹)·r, with Bₖ the matrix's entries among the unknowns of
/// group k.
#[derive(Clone)]
pub(crate) struct BlockJacobi {
    /// Unknowns per group.
    size: usize,
    /// Group k's unknowns at k·size … (k+1)·size.
    index: Vec<usize>,
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
        BlockJacobi {
            size,
            inverse: vec![0.0; slots.len()],
            index,
            slots,
            work: vec![0.0; 2 * size * size],
        }
    }

    /// Inverts every block of the matrix with `values`.
    ///
    /// Errors: [`PrecondError::SingularBlock`].
    pub(crate) fn update(&mut self, values: &[f64]) -> Result<(), PrecondError> {
        let b = self.size;
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

    /// A view faer's Krylov solvers apply.
    pub(crate) fn as_precond(&self, n: usize) -> BlockJacobiRef<'_> {
        BlockJacobiRef { jacobi: self, n }
    }

    fn apply(&self, out: &mut [f64], r: &[f64]) {
        let b = self.size;
        for (unknowns, inverse) in self.index.chunks(b).zip(self.inverse.chunks(b * b)) {
            for (i, &row) in unknowns.iter().enumerate() {
                out[row] = unknowns
                    .iter()
                    .zip(&inverse[i * b..(i + 1) * b])
                    .map(|(&col, m)| m * r[col])
                    .sum();
            }
        }
    }
}

/// A⁻¹ of the b × b row-major matrix `a` (overwritten) into `inverse`, by Gauss–Jordan
/// elimination with partial pivoting.
///
/// Errors: [`PrecondError::SingularBlock`] when a pivot is zero or not finite.
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

/// [`Ilu0`] as a faer operator.
#[derive(Clone, Copy)]
pub(crate) struct Ilu0Ref<'a>(pub(crate) &'a Ilu0);

impl fmt::Debug for Ilu0Ref<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Ilu0")
            .field("n", &self.0.diagonal.len())
            .finish()
    }
}

impl Column for Ilu0Ref<'_> {
    fn n(&self) -> usize {
        self.0.diagonal.len()
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.0.apply(out, r);
    }
}

/// [`BlockJacobi`] as a faer operator.
#[derive(Clone, Copy)]
pub(crate) struct BlockJacobiRef<'a> {
    jacobi: &'a BlockJacobi,
    n: usize,
}

impl fmt::Debug for BlockJacobiRef<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BlockJacobi")
            .field("n", &self.n)
            .field("block", &self.jacobi.size)
            .finish()
    }
}

/// The sparse factors of an earlier matrix.
#[derive(Clone, Copy)]
pub(crate) enum Factors<'a> {
    Cholesky(LltRef<'a, usize, f64>),
    Lu(LuRef<'a, usize, f64>),
}

impl fmt::Debug for Factors<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self {
            Factors::Cholesky(_) => "Cholesky",
            Factors::Lu(_) => "LU",
        };
        f.debug_struct("Factors").field("kind", &kind).finish()
    }
}

/// Writes P·rhs into `out` column by column with `apply(out_column, rhs_column, stack)`.
fn columns(
    mut out: MatMut<'_, f64>,
    rhs: MatRef<'_, f64>,
    stack: &mut MemStack,
    mut apply: impl FnMut(&mut [f64], &[f64], &mut MemStack),
) {
    for j in 0..rhs.ncols() {
        let r: Vec<f64>;
        let r_col = rhs.col(j);
        let r_slice = match r_col.try_as_col_major() {
            Some(c) => c.as_slice(),
            None => {
                // faer's solvers pass contiguous columns; this path is never taken by them.
                r = r_col.iter().copied().collect();
                &r
            }
        };
        let out_slice = out
            .as_mut()
            .col_mut(j)
            .try_as_col_major_mut()
            .expect("faer's Krylov solvers pass contiguous columns")
            .as_slice_mut();
        apply(out_slice, r_slice, stack);
    }
}

/// A preconditioner applied one column at a time; [`as_precond!`] makes it a faer operator.
pub(crate) trait Column {
    fn n(&self) -> usize;
    fn scratch(&self) -> StackReq;
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack);
}

impl Column for BlockJacobiRef<'_> {
    fn n(&self) -> usize {
        self.n
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.jacobi.apply(out, r);
    }
}

impl Column for Factors<'_> {
    fn n(&self) -> usize {
        match self {
            Factors::Cholesky(llt) => llt.symbolic().nrows(),
            Factors::Lu(lu) => lu.symbolic().nrows(),
        }
    }
    fn scratch(&self) -> StackReq {
        match self {
            Factors::Cholesky(llt) => llt.symbolic().solve_in_place_scratch::<f64>(1, Par::Seq),
            Factors::Lu(lu) => lu.symbolic().solve_in_place_scratch::<f64>(1, Par::Seq),
        }
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        out.copy_from_slice(r);
        let n = out.len();
        let column = MatMut::from_column_major_slice_mut(out, n, 1);
        match self {
            Factors::Cholesky(llt) => {
                llt.solve_in_place_with_conj(Conj::No, column, Par::Seq, stack)
            }
            Factors::Lu(lu) => lu.solve_in_place_with_conj(Conj::No, column, Par::Seq, stack),
        }
    }
}

/// faer's operator traits for a [`Column`] type (a blanket impl would break the orphan rule).
macro_rules! as_precond {
    ($ty:ty) => {
        impl LinOp<f64> for $ty {
            fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
                Column::scratch(self)
            }
            fn nrows(&self) -> usize {
                Column::n(self)
            }
            fn ncols(&self) -> usize {
                Column::n(self)
            }
            fn apply(
                &self,
                out: MatMut<'_, f64>,
                rhs: MatRef<'_, f64>,
                _: Par,
                stack: &mut MemStack,
            ) {
                columns(out, rhs, stack, |o, r, s| self.apply_column(o, r, s));
            }
            fn conj_apply(
                &self,
                out: MatMut<'_, f64>,
                rhs: MatRef<'_, f64>,
                par: Par,
                stack: &mut MemStack,
            ) {
                self.apply(out, rhs, par, stack);
            }
        }
        impl Precond<f64> for $ty {}
    };
}

as_precond!(BlockJacobiRef<'_>);
as_precond!(Factors<'_>);
as_precond!(Ilu0Ref<'_>);
as_precond!(super::multigrid::MultigridRef<'_>);

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
}
