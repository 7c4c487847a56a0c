//! What a Krylov solve multiplies by: the assembled matrix by rows, or a field model's blocks
//! on its grid.

use faer::dyn_stack::{MemStack, StackReq};

use super::{Column, RowMatrix, StencilMatrix};

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

/// faer's operator, for its conjugate gradient (through [`super::column_operator!`]).
impl Column for Products<'_> {
    fn n(&self) -> usize {
        match self {
            Products::Rows(a) => a.n(),
            Products::Stencil(a) => a.n(),
        }
    }
    fn scratch(&self) -> StackReq {
        StackReq::EMPTY
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], _: &mut MemStack) {
        self.product(r, out, r);
    }
}
