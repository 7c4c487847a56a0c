//! What a Krylov solve multiplies by: the assembled matrix by rows, or a field model's blocks
//! on its grid.

use faer::dyn_stack::{MemStack, StackReq};
use faer::matrix_free::LinOp;
use faer::{MatMut, MatRef, Par};

use super::{RowMatrix, StencilMatrix};

/// The products of a Krylov solve with the Newton matrix.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Products<'a> {
    /// The assembled matrix by rows (particle models).
    Rows(&'a RowMatrix),
    /// The cells' blocks applied on the grid (field models).
    Stencil(&'a StencilMatrix),
}

impl Products<'_> {
    /// y = A·x, and (w·y, y·y).
    #[inline]
    pub(crate) fn product(&self, x: &[f64], y: &mut [f64], w: &[f64]) -> (f64, f64) {
        match self {
            Products::Rows(a) => a.product(x, y, w),
            Products::Stencil(a) => a.product(x, y, w),
        }
    }
}

/// faer's operator, for its conjugate gradient.
impl LinOp<f64> for Products<'_> {
    fn apply_scratch(&self, rhs_ncols: usize, par: Par) -> StackReq {
        match self {
            Products::Rows(a) => a.apply_scratch(rhs_ncols, par),
            Products::Stencil(a) => a.apply_scratch(rhs_ncols, par),
        }
    }
    fn nrows(&self) -> usize {
        match self {
            Products::Rows(a) => a.nrows(),
            Products::Stencil(a) => a.nrows(),
        }
    }
    fn ncols(&self) -> usize {
        self.nrows()
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        match self {
            Products::Rows(a) => a.apply(out, rhs, par, stack),
            Products::Stencil(a) => a.apply(out, rhs, par, stack),
        }
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
