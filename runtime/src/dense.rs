//! Dense square matrices for the Newton systems of implicit methods: fixed-size `nalgebra`
//! matrices on the stack up to 32×32, faer's LU above that; neither allocates after creation.

use std::fmt;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{Mat, MatMut, Par};

/// A dense square Jacobian: what the stability explorer reads entry by entry.
pub trait DenseMatrix: Clone + fmt::Debug {
    /// The all-zero matrix; every buffer the matrix needs is allocated here, once.
    fn zeros() -> Self;
    /// Entry (row, column).
    fn entry(&self, row: usize, column: usize) -> f64;
    /// Number of rows (= columns).
    fn dim(&self) -> usize;
}

/// The linear algebra of implicit methods: a Jacobian J, written by
/// [`crate::Jacobian::jacobian`], and solves with W = I − c·J.
///
/// The factorization is kept apart from J — in [`NewtonMatrix::Factors`] — so a method can
/// factorize once and solve several right-hand sides (the stages of a Rosenbrock method), and
/// refactorize for another c without re-evaluating J (a step retried at a smaller size).
///
/// Dense models use `SMatrix` (nalgebra, on the stack; up to 3×3 by the closed-form inverse) or
/// [`FaerDense`] (faer's LU); particle models a [`crate::particles::ParticleJacobian`], which
/// solves the same systems through the sparse velocity form of Baraff & Witkin.
pub trait NewtonMatrix: Clone + fmt::Debug {
    /// What a factorization of W keeps (LU factors and pivots), allocated once by
    /// [`NewtonMatrix::factors`].
    type Factors: Clone + fmt::Debug;

    /// Room for the factors of a matrix like this one.
    fn factors(&self) -> Self::Factors;

    /// Forms W = I − c·J from the Jacobian last written into `self`, which stays as it was, and
    /// factorizes it into `factors`; false when W is singular.
    fn factorize(&mut self, c: f64, factors: &mut Self::Factors) -> bool;

    /// Solves W·x = b in place with the last factorization; false when x is not finite.
    fn solve(&mut self, factors: &mut Self::Factors, b: &mut [f64]) -> bool;

    /// Takes the options of the run that will solve with this matrix (dense matrices have none
    /// to take; particle Jacobians read [`crate::NewtonOptions::definite`]).
    fn configure(&mut self, newton: &crate::NewtonOptions) {
        let _ = newton;
    }
}

/// The factors of a small dense W: its inverse up to 3×3 (closed form by cofactors, several
/// times faster than a pivoted LU at these sizes: 3.3× on a 2×2 Newton step, measured in the
/// peers bench), an LU with partial pivoting above.
/// (`I` is the inverse's type, `L` the LU's: both fixed-size nalgebra types.)
#[derive(Clone, Debug)]
pub enum SmallFactors<I, L> {
    /// W⁻¹.
    Inverse(I),
    /// P·W = L·U.
    Lu(L),
}

/// `DenseMatrix` and `NewtonMatrix` for `SMatrix<f64, N, N>`: nalgebra's fixed-size LU needs each
/// size spelled out.
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
        }

        impl NewtonMatrix for nalgebra::SMatrix<f64, $n, $n> {
            type Factors = SmallFactors<
                nalgebra::SMatrix<f64, $n, $n>,
                nalgebra::linalg::LU<f64, nalgebra::Const<$n>, nalgebra::Const<$n>>,
            >;

            fn factors(&self) -> Self::Factors {
                SmallFactors::Inverse(nalgebra::SMatrix::identity())
            }

            #[inline]
            fn factorize(&mut self, c: f64, factors: &mut Self::Factors) -> bool {
                let w = nalgebra::SMatrix::<f64, $n, $n>::identity() - *self * c;
                if $n <= 3 {
                    match w.try_inverse() {
                        Some(inverse) => {
                            *factors = SmallFactors::Inverse(inverse);
                            inverse.iter().all(|x| x.is_finite())
                        }
                        None => false,
                    }
                } else {
                    let lu = w.lu();
                    let ok = lu.is_invertible();
                    *factors = SmallFactors::Lu(lu);
                    ok
                }
            }

            #[inline]
            fn solve(&mut self, factors: &mut Self::Factors, b: &mut [f64]) -> bool {
                let mut rhs = nalgebra::SVector::<f64, $n>::from_column_slice(b);
                let solved = match factors {
                    SmallFactors::Inverse(inverse) => {
                        rhs = *inverse * rhs;
                        true
                    }
                    SmallFactors::Lu(lu) => lu.solve_mut(&mut rhs),
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
}

impl NewtonMatrix for nalgebra::SMatrix<f64, 0, 0> {
    type Factors = ();
    fn factors(&self) {}
    fn factorize(&mut self, _: f64, _: &mut ()) -> bool {
        true
    }
    fn solve(&mut self, _: &mut (), _: &mut [f64]) -> bool {
        true
    }
}

/// An N×N matrix on the heap, solved with faer's partial-pivoting LU: the Jacobian of models with
/// more than 32 state components. Every buffer is allocated by [`DenseMatrix::zeros`] and
/// [`NewtonMatrix::factors`]; factorizations and solves allocate nothing.
pub struct FaerDense<const N: usize> {
    matrix: Mat<f64>,
}

/// The LU factors of a [`FaerDense`] W, with its permutation and scratch space.
pub struct FaerLu<const N: usize> {
    lu: Mat<f64>,
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
}

impl<const N: usize> FaerLu<N> {
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
        }
    }
}

impl<const N: usize> Clone for FaerLu<N> {
    fn clone(&self) -> Self {
        FaerLu {
            lu: self.lu.clone(),
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
            .finish()
    }
}

impl<const N: usize> fmt::Debug for FaerLu<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FaerLu").finish_non_exhaustive()
    }
}

impl<const N: usize> DenseMatrix for FaerDense<N> {
    fn zeros() -> Self {
        FaerDense {
            matrix: Mat::zeros(N, N),
        }
    }

    fn entry(&self, row: usize, column: usize) -> f64 {
        self.matrix[(row, column)]
    }

    fn dim(&self) -> usize {
        N
    }
}

impl<const N: usize> NewtonMatrix for FaerDense<N> {
    type Factors = FaerLu<N>;

    fn factors(&self) -> FaerLu<N> {
        FaerLu {
            lu: Mat::zeros(N, N),
            perm: vec![0; N],
            perm_inv: vec![0; N],
            scratch: MemBuffer::new(FaerLu::<N>::scratch_size()),
        }
    }

    fn factorize(&mut self, c: f64, f: &mut FaerLu<N>) -> bool {
        for column in 0..N {
            for row in 0..N {
                let identity = if row == column { 1.0 } else { 0.0 };
                f.lu[(row, column)] = identity - c * self.matrix[(row, column)];
            }
        }
        factor::lu_in_place(
            f.lu.as_mut(),
            &mut f.perm,
            &mut f.perm_inv,
            Par::Seq,
            MemStack::new(&mut f.scratch),
            Default::default(),
        );
        // A zero pivot leaves U singular: the solve would produce infinities.
        (0..N).all(|i| f.lu[(i, i)] != 0.0 && f.lu[(i, i)].is_finite())
    }

    fn solve(&mut self, f: &mut FaerLu<N>, b: &mut [f64]) -> bool {
        let perm = faer::perm::PermRef::new_checked(&f.perm, &f.perm_inv, N);
        let rhs = MatMut::from_column_major_slice_mut(b, N, 1);
        let lu = f.lu.as_ref();
        solve::solve_in_place(lu, lu, perm, rhs, Par::Seq, MemStack::new(&mut f.scratch));
        b.iter().all(|x| x.is_finite())
    }
}
