//! [`FaerDense`]: the dense Jacobian of models above 32 components, solved with faer's LU.

use std::fmt;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{Mat, MatMut, Par};

use super::{DenseMatrix, FactorizeError, NewtonMatrix, SolveError, finite, first_non_finite};

/// An n×n matrix on the heap, sized at run time and solved with faer's partial-pivoting LU: the
/// Jacobian of models with more than 32 state components, and of const-generic models (whose
/// size the macro does not know). Every buffer is allocated by [`FaerDense::zeros`] and
/// [`NewtonMatrix::factors`]; factorizations and solves allocate nothing.
#[derive(Clone, Debug)]
pub struct FaerDense {
    matrix: Mat<f64>,
}

/// The LU factors of a [`FaerDense`] W, with its permutation and scratch space.
pub struct FaerLu {
    lu: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    scratch: MemBuffer,
}

impl FaerDense {
    /// The n×n zero matrix.
    pub fn zeros(n: usize) -> Self {
        FaerDense {
            matrix: Mat::zeros(n, n),
        }
    }

    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        self.matrix.fill(0.0);
    }

    /// Sets entry (row, column).
    pub fn set(&mut self, row: usize, column: usize, value: f64) {
        self.matrix[(row, column)] = value;
    }
}

impl FaerLu {
    /// Room for the factors of an n×n matrix.
    fn new(n: usize) -> Self {
        FaerLu {
            lu: Mat::zeros(n, n),
            perm: vec![0; n],
            perm_inv: vec![0; n],
            scratch: MemBuffer::new(Self::scratch_size(n)),
        }
    }

    fn scratch_size(n: usize) -> StackReq {
        let par = Par::Seq;
        factor::lu_in_place_scratch::<usize, f64>(n, n, par, Default::default())
            .or(solve::solve_in_place_scratch::<usize, f64>(n, 1, par))
    }
}

impl Clone for FaerLu {
    fn clone(&self) -> Self {
        FaerLu {
            lu: self.lu.clone(),
            perm: self.perm.clone(),
            perm_inv: self.perm_inv.clone(),
            scratch: MemBuffer::new(Self::scratch_size(self.lu.nrows())),
        }
    }
}

impl fmt::Debug for FaerLu {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FaerLu").finish_non_exhaustive()
    }
}

impl DenseMatrix for FaerDense {
    fn entry(&self, row: usize, column: usize) -> f64 {
        self.matrix[(row, column)]
    }

    fn dim(&self) -> usize {
        self.matrix.nrows()
    }
}

impl NewtonMatrix for FaerDense {
    type Factors = FaerLu;

    fn factors(&self) -> FaerLu {
        FaerLu::new(self.dim())
    }

    fn factorize(&mut self, c: f64, f: &mut FaerLu) -> Result<(), FactorizeError> {
        let n = self.dim();
        for column in 0..n {
            for row in 0..n {
                let identity = if row == column { 1.0 } else { 0.0 };
                f.lu[(row, column)] = identity - c * self.matrix[(row, column)];
            }
        }
        f.factor()
    }

    fn factorize_mass(
        &mut self,
        c: f64,
        mass: &[(usize, usize, f64)],
        f: &mut FaerLu,
    ) -> Result<(), FactorizeError> {
        let n = self.dim();
        for column in 0..n {
            for row in 0..n {
                f.lu[(row, column)] = -c * self.matrix[(row, column)];
            }
        }
        for &(row, column, m) in mass {
            f.lu[(row, column)] += m;
        }
        f.factor()
    }

    fn dense_entry(&self, row: usize, column: usize) -> Option<f64> {
        Some(self.matrix[(row, column)])
    }

    fn solve(&mut self, f: &mut FaerLu, b: &mut [f64]) -> Result<(), SolveError> {
        let n = self.dim();
        if b.len() != n {
            return Err(SolveError::WrongLength {
                expected: n,
                found: b.len(),
            });
        }
        let perm = faer::perm::PermRef::new_checked(&f.perm, &f.perm_inv, n);
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        let lu = f.lu.as_ref();
        solve::solve_in_place(lu, lu, perm, rhs, Par::Seq, MemStack::new(&mut f.scratch));
        finite(b)
    }

    fn non_finite_entry(&self) -> Option<(usize, usize, f64)> {
        first_non_finite(self.dim(), |row, column| self.matrix[(row, column)])
    }
}

impl FaerLu {
    /// Factorizes the W written into `lu` in place.
    fn factor(&mut self) -> Result<(), FactorizeError> {
        let (n, f) = (self.lu.nrows(), self);
        factor::lu_in_place(
            f.lu.as_mut(),
            &mut f.perm,
            &mut f.perm_inv,
            Par::Seq,
            MemStack::new(&mut f.scratch),
            Default::default(),
        );
        // A zero pivot leaves U singular: the solve would produce infinities.
        if (0..n).all(|i| f.lu[(i, i)] != 0.0 && f.lu[(i, i)].is_finite()) {
            Ok(())
        } else {
            Err(FactorizeError::Singular)
        }
    }
}
