//! The operator layer, the leaf of the linear algebra: what a solve multiplies by (the assembled
//! matrix by rows, a field model's blocks on its grid) and what a preconditioner applies, one
//! column at a time, each as one of faer's operators.
//!
//! The layers above, in dependency order: preconditioners (`precond`), multigrid, the Krylov
//! iterations (`krylov`), then the sparse solver that chooses among them (`sparse`).

use faer::dyn_stack::{MemStack, StackReq};
use faer::{MatMut, MatRef};

mod products;
mod rows;
mod stencil;

pub(crate) use products::Products;
pub(crate) use rows::RowMatrix;
pub(crate) use stencil::{Edge, StencilBlock, StencilMatrix};

/// Writes P·rhs into `out` column by column with `apply(out_column, rhs_column, stack)`.
pub(crate) fn columns(
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

/// An operator applied one column at a time: a matrix's products or a preconditioner.
/// [`column_operator!`] makes it faer's operator, [`as_precond!`] faer's preconditioner.
pub(crate) trait Column {
    fn n(&self) -> usize;
    fn scratch(&self) -> StackReq;
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack);
}

/// faer's operator trait for a [`Column`] type (a blanket impl would break the orphan rule).
macro_rules! column_operator {
    ($ty:ty) => {
        impl faer::matrix_free::LinOp<f64> for $ty {
            fn apply_scratch(&self, _: usize, _: faer::Par) -> faer::dyn_stack::StackReq {
                $crate::linalg::operator::Column::scratch(self)
            }
            fn nrows(&self) -> usize {
                $crate::linalg::operator::Column::n(self)
            }
            fn ncols(&self) -> usize {
                $crate::linalg::operator::Column::n(self)
            }
            fn apply(
                &self,
                out: faer::MatMut<'_, f64>,
                rhs: faer::MatRef<'_, f64>,
                _: faer::Par,
                stack: &mut faer::dyn_stack::MemStack,
            ) {
                $crate::linalg::operator::columns(out, rhs, stack, |o, r, s| {
                    $crate::linalg::operator::Column::apply_column(self, o, r, s)
                });
            }
            fn conj_apply(
                &self,
                out: faer::MatMut<'_, f64>,
                rhs: faer::MatRef<'_, f64>,
                par: faer::Par,
                stack: &mut faer::dyn_stack::MemStack,
            ) {
                faer::matrix_free::LinOp::apply(self, out, rhs, par, stack);
            }
        }
    };
}

/// faer's preconditioner traits for a [`Column`] type.
macro_rules! as_precond {
    ($ty:ty) => {
        $crate::linalg::operator::column_operator!($ty);
        impl faer::matrix_free::Precond<f64> for $ty {}
    };
}

pub(crate) use {as_precond, column_operator};

column_operator!(Products<'_>);
column_operator!(RowMatrix);
column_operator!(StencilMatrix);
