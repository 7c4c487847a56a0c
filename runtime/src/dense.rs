//! Dense square matrices for the Newton systems of implicit methods: fixed-size `nalgebra`
//! matrices on the stack up to 32×32, faer's LU above that; neither allocates after creation.

use std::fmt;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{Mat, MatMut, Par};

/// A dense square matrix an implicit method can form I − h·J in and solve with.
pub trait DenseMatrix: Clone + fmt::Debug {
    /// The all-zero matrix; every buffer the matrix needs is allocated here, once.
    fn zeros() -> Self;
    /// Entry (row, column).
    fn entry(&self, row: usize, column: usize) -> f64;
    /// Number of rows (= columns).
    fn dim(&self) -> usize;
    /// Replaces `self` (a Jacobian J) by I − h·J.
    fn identity_minus(&mut self, h: f64);
    /// Solves `self`·x = b in place, overwriting `self` with its factors; false when `self` is
    /// singular (or so close that the solution is not finite).
    fn solve_in_place(&mut self, b: &mut [f64]) -> bool;
}

/// The linear algebra of a Newton iteration of implicit Euler: a Jacobian J, written by
/// [`crate::Jacobian::jacobian`], and the solve of (I − h·J)·x = b.
///
/// Dense models use a [`DenseMatrix`]; particle models a [`crate::particles::ParticleJacobian`],
/// which solves the same system through the sparse velocity form of Baraff & Witkin.
pub trait NewtonMatrix: Clone + fmt::Debug {
    /// Solves (I − h·J)·x = b in place, J being the Jacobian last written into `self`, which
    /// this may overwrite; false when the matrix is singular or the solution is not finite.
    fn solve_identity_minus(&mut self, h: f64, b: &mut [f64]) -> bool;

    /// Takes the options of the run that will solve with this matrix (dense matrices have none
    /// to take; particle Jacobians read [`crate::NewtonOptions::definite`]).
    fn configure(&mut self, newton: &crate::NewtonOptions) {
        let _ = newton;
    }
}

impl<T: DenseMatrix> NewtonMatrix for T {
    #[inline]
    fn solve_identity_minus(&mut self, h: f64, b: &mut [f64]) -> bool {
        self.identity_minus(h);
        self.solve_in_place(b)
    }
}

/// `DenseMatrix` for `SMatrix<f64, N, N>`: nalgebra's fixed-size LU needs each size spelled out.
macro_rules! dense_matrix {
    ($($n:literal)*) => {$(
        impl DenseMatrix for nalgebra::SMatrix<f64, $n, $n> {
            #[inline]
            fn zeros() -> Self {
                nalgebra::SMatrix::zeros()
            }
            #[inline]
            fn entry(&self, row: usize, column: usize) -> f64 {
                self[(row, column)]
            }
            #[inline]
            fn dim(&self) -> usize {
                $n
            }
            #[inline]
            fn identity_minus(&mut self, h: f64) {
                *self = nalgebra::SMatrix::identity() - *self * h;
            }
            #[inline]
            fn solve_in_place(&mut self, b: &mut [f64]) -> bool {
                let mut rhs = nalgebra::SVector::<f64, $n>::from_column_slice(b);
                // Up to 3×3 nalgebra inverts in closed form (cofactors), several times faster
                // than a pivoted LU at these sizes (3.3× on a 2×2 Newton step, measured in
                // benches/peers.rs); the Newton matrices I − h·J are far from singular unless
                // h·J has an eigenvalue near 1, which the singular check reports.
                let solved = if $n <= 3 {
                    match self.try_inverse() {
                        Some(inverse) => {
                            rhs = inverse * rhs;
                            true
                        }
                        None => false,
                    }
                } else {
                    self.lu().solve_mut(&mut rhs)
                };
                b.copy_from_slice(rhs.as_slice());
                solved && b.iter().all(|x| x.is_finite())
            }
        }
    )*};
}

dense_matrix!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32);

impl DenseMatrix for nalgebra::SMatrix<f64, 0, 0> {
    fn zeros() -> Self {
        nalgebra::SMatrix::zeros()
    }
    fn entry(&self, _: usize, _: usize) -> f64 {
        0.0
    }
    fn dim(&self) -> usize {
        0
    }
    fn identity_minus(&mut self, _: f64) {}
    fn solve_in_place(&mut self, _: &mut [f64]) -> bool {
        true
    }
}

/// An N×N matrix on the heap, solved with faer's partial-pivoting LU: the Newton matrix of
/// models with more than 32 state components. The matrix, the permutations and the scratch
/// space are allocated by [`DenseMatrix::zeros`] and reused by every solve.
pub struct FaerDense<const N: usize> {
    matrix: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    scratch: MemBuffer,
}

impl<const N: usize> FaerDense<N> {
    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        self.matrix.fill(0.0);
    }

    /// Sets entry (row, column).
    pub fn set(&mut self, row: usize, column: usize, value: f64) {
        self.matrix[(row, column)] = value;
    }

    fn scratch_size() -> StackReq {
        let par = Par::Seq;
        factor::lu_in_place_scratch::<usize, f64>(N, N, par, Default::default())
            .or(solve::solve_in_place_scratch::<usize, f64>(N, 1, par))
    }
}

impl<const N: usize> Clone for FaerDense<N> {
    fn clone(&self) -> Self {
        FaerDense {
            matrix: self.matrix.clone(),
            perm: self.perm.clone(),
            perm_inv: self.perm_inv.clone(),
            scratch: MemBuffer::new(Self::scratch_size()),
        }
    }
}

impl<const N: usize> fmt::Debug for FaerDense<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FaerDense")
            .field("matrix", &self.matrix)
            .finish_non_exhaustive()
    }
}

impl<const N: usize> DenseMatrix for FaerDense<N> {
    fn zeros() -> Self {
        FaerDense {
            matrix: Mat::zeros(N, N),
            perm: vec![0; N],
            perm_inv: vec![0; N],
            scratch: MemBuffer::new(Self::scratch_size()),
        }
    }

    fn entry(&self, row: usize, column: usize) -> f64 {
        self.matrix[(row, column)]
    }

    fn dim(&self) -> usize {
        N
    }

    fn identity_minus(&mut self, h: f64) {
        for column in 0..N {
            for row in 0..N {
                let identity = if row == column { 1.0 } else { 0.0 };
                self.matrix[(row, column)] = identity - h * self.matrix[(row, column)];
            }
        }
    }

    fn solve_in_place(&mut self, b: &mut [f64]) -> bool {
        let par = Par::Seq;
        let stack = MemStack::new(&mut self.scratch);
        let (_, perm) = factor::lu_in_place(
            self.matrix.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            par,
            stack,
            Default::default(),
        );
        let rhs = MatMut::from_column_major_slice_mut(b, N, 1);
        let lu = self.matrix.as_ref();
        solve::solve_in_place(lu, lu, perm, rhs, par, MemStack::new(&mut self.scratch));
        b.iter().all(|x| x.is_finite())
    }
}
