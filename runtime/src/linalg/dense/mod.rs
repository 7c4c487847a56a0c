//! Dense square matrices for the Newton systems of implicit methods: fixed-size `nalgebra`
//! matrices on the stack up to 32×32, faer's LU above that; neither allocates after creation.

use std::fmt;

/// A dense square Jacobian: what the stability explorer reads entry by entry.
pub trait DenseMatrix: Clone + fmt::Debug {
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
/// Dense models use `SMatrix` (nalgebra, on the stack; up to 3×3 by Cramer's rule) or
/// [`FaerDense`] (faer's LU); particle models a [`crate::particles::ParticleJacobian`], which
/// solves the same systems through the sparse velocity form of Baraff & Witkin.
pub trait NewtonMatrix: Clone + fmt::Debug {
    /// What a factorization of W keeps (LU factors and pivots), allocated once by
    /// [`NewtonMatrix::factors`].
    type Factors: Clone + fmt::Debug;

    /// Whether one solve costs about as much as the rest of a step — a sparse system of a
    /// particle or field model, solved by substitution in big factors or by Krylov iterations —
    /// rather than a dense substitution that is cheap next to f and the factorization. BDF then
    /// stops its Newton iteration by CVODE's looser test, which takes half the solves
    /// ([`crate::integrators::Bdf`]). Default false.
    const COSTLY_SOLVES: bool = false;

    /// Whether the matrix is a particle model's, whose links may give a
    /// [`NewtonMatrix::link_laplacian`]. Default false.
    const LINKS: bool = false;

    /// Room for the factors of a matrix like this one.
    fn factors(&self) -> Self::Factors;

    /// Forms W = I − c·J from the Jacobian last written into `self`, which stays as it was, and
    /// factorizes it into `factors`.
    ///
    /// Errors: [`FactorizeError::Singular`] when W is singular.
    fn factorize(&mut self, c: f64, factors: &mut Self::Factors) -> Result<(), FactorizeError>;

    /// Forms W = M − c·J, M the constant mass matrix of a differential–algebraic model given by
    /// its non-zero entries (row, column, value) ([`crate::Mass::entries`]), and factorizes it
    /// into `factors`, as [`NewtonMatrix::factorize`] does W = I − c·J.
    ///
    /// Dense matrices and field models' Jacobians implement it; the default (particle
    /// Jacobians, whose models have no mass matrix) reports the matrix singular.
    ///
    /// Errors: [`FactorizeError::Singular`] when W is singular.
    fn factorize_mass(
        &mut self,
        c: f64,
        mass: &[(usize, usize, f64)],
        factors: &mut Self::Factors,
    ) -> Result<(), FactorizeError> {
        let _ = (c, mass, factors);
        Err(FactorizeError::Singular)
    }

    /// Entry (row, column) of J as last written, for a dense matrix; `None` for sparse ones.
    /// BDF reads it to bound the rounding of a mass-matrix model's Newton residual.
    fn dense_entry(&self, row: usize, column: usize) -> Option<f64> {
        let _ = (row, column);
        None
    }

    /// Appends to `out` the entries of J as last written whose row and column are both among
    /// `components` (sorted, in the state's layout), as (row's position in `components`,
    /// column's position, value); a sparse matrix gives every structural entry, zero or not. The
    /// consistent initialization of a differential–algebraic model solves with this block,
    /// ∂g/∂z ([`crate::consistent`]). The default reads [`NewtonMatrix::dense_entry`] and gives
    /// nothing for a matrix without it.
    fn entries_among(&self, components: &[usize], out: &mut Vec<(usize, usize, f64)>) {
        for (a, &i) in components.iter().enumerate() {
            for (b, &j) in components.iter().enumerate() {
                match self.dense_entry(i, j) {
                    Some(value) if value != 0.0 => out.push((a, b, value)),
                    Some(_) => {}
                    None => return,
                }
            }
        }
    }

    /// Solves W·x = b in place with the last factorization.
    ///
    /// Errors: [`SolveError::NotFinite`] when x is not finite, [`SolveError::WrongLength`] when
    /// b is not as long as the system.
    fn solve(&mut self, factors: &mut Self::Factors, b: &mut [f64]) -> Result<(), SolveError>;

    /// Takes the options of the run that will solve with this matrix (dense matrices have none
    /// to take; particle Jacobians read [`crate::NewtonOptions::definite`]). `solves` says what
    /// the solves are for, which decides where an iterative solve stops ([`crate::Solves`]).
    fn configure(&mut self, newton: &crate::NewtonOptions, solves: crate::Solves) {
        let _ = (newton, solves);
    }

    /// The sparse factorizations and Krylov solves this matrix has made so far
    /// ([`crate::Stats::linear`]); zero (the default) for dense matrices.
    fn work(&self) -> crate::LinearWork {
        crate::LinearWork::default()
    }

    /// The first entry of J, as [`crate::Jacobian::jacobian`] last wrote it, that is NaN or
    /// infinite: (row, column, value) in the state's layout. The implicit methods check it after
    /// every evaluation of J and report [`crate::Error::NonFiniteJacobian`]: no step size makes
    /// such a W regular, and a singular or non-finite W would otherwise surface as a step size
    /// that falls to nothing.
    fn non_finite_entry(&self) -> Option<(usize, usize, f64)>;

    /// A scalar link Laplacian whose M + h·C + h²·K bounds this matrix's stiffness, built from
    /// the Jacobian last written into `self`, for implicit Euler's quasi-Newton solve
    /// ([`crate::ParticleSolve`]); `None` (the default) for matrices of models without links.
    fn link_laplacian(&self) -> Option<crate::LinkLaplacian> {
        None
    }
}

/// The first non-finite entry of a dense n×n matrix, by columns.
fn first_non_finite(n: usize, entry: impl Fn(usize, usize) -> f64) -> Option<(usize, usize, f64)> {
    (0..n)
        .flat_map(|column| (0..n).map(move |row| (row, column)))
        .map(|(row, column)| (row, column, entry(row, column)))
        .find(|(_, _, value)| !value.is_finite())
}

/// Why [`NewtonMatrix::factorize`] failed. The integrators take it as a failed attempt: a
/// linearly implicit step is retried smaller ([`crate::Error::SingularMatrix`] past the
/// smallest), a Newton iteration fails and its step is halved.
///
/// (Errors here and in [`SolveError`] are a byte or a few words, not [`crate::Error`]: the
/// matrix knows neither t nor the step, and a dense 2×2 solve is a few nanoseconds.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum FactorizeError {
    /// W = I − c·J is singular: a zero or non-finite determinant or pivot; for a sparse W,
    /// neither Cholesky nor LU could factorize it.
    #[error("the matrix I − c·J is singular")]
    Singular,
}

/// Why [`NewtonMatrix::solve`] failed; the integrators take it as a failed attempt, as a
/// [`FactorizeError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SolveError {
    /// The solution x has a NaN or infinite component: b was not finite, or W is singular to
    /// working precision.
    #[error("the solution of W·x = b is not finite")]
    NotFinite,
    /// W is singular: found when an iterative solve did not converge and the direct solve that
    /// took over met a zero pivot (sparse matrices only).
    #[error("the matrix W is singular (found by the direct solve after the Krylov solve failed)")]
    Singular,
    /// b does not have one entry per unknown of the system.
    #[error("the right-hand side has {found} entries, the system {expected} unknowns")]
    WrongLength {
        /// The system's unknowns.
        expected: usize,
        /// b's entries.
        found: usize,
    },
}

/// Ok when every entry of the solution `x` is finite.
#[inline]
pub(crate) fn finite(x: &[f64]) -> Result<(), SolveError> {
    if x.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(SolveError::NotFinite)
    }
}

/// The factors of a small dense W: up to 3×3 its adjugate and determinant, so a solve is
/// Cramer's rule, x = adj(W)·b · (1/det W), the reciprocal taken off the critical path while
/// adj(W)·b is formed. On a 2×2 Newton step (the peers bench, van der Pol) this is 0.97× a
/// hand-written Cramer's rule; the inverse W⁻¹ = adj(W)/det W, whose divisions sit between the
/// factorization and the product, was 1.10×, and dividing adj(W)·b by det W last 1.17× (LLVM
/// spilled the iterate there); a pivoted LU made the step 3.3× slower. Above 3×3, an LU with
/// partial pivoting.
/// (`A` is the adjugate's type, `L` the LU's: both fixed-size nalgebra types.)
#[derive(Clone, Debug)]
pub enum SmallFactors<A, L> {
    /// adj(W) and det W.
    Adjugate(A, f64),
    /// P·W = L·U.
    Lu(L),
}

/// adj(W) and det W of a 1×1, 2×2 or 3×3 matrix by cofactors (None above 3×3).
#[inline]
fn adjugate<const N: usize>(
    w: &nalgebra::SMatrix<f64, N, N>,
) -> Option<(nalgebra::SMatrix<f64, N, N>, f64)> {
    let mut adj = nalgebra::SMatrix::<f64, N, N>::zeros();
    let det = match N {
        1 => {
            adj[(0, 0)] = 1.0;
            w[(0, 0)]
        }
        2 => {
            adj[(0, 0)] = w[(1, 1)];
            adj[(0, 1)] = -w[(0, 1)];
            adj[(1, 0)] = -w[(1, 0)];
            adj[(1, 1)] = w[(0, 0)];
            w[(0, 0)] * w[(1, 1)] - w[(0, 1)] * w[(1, 0)]
        }
        3 => {
            // adj(W)ᵢⱼ is the cofactor Cⱼᵢ: rows and columns taken cyclically, so each minor
            // comes with its sign.
            for i in 0..3 {
                for j in 0..3 {
                    let (r1, r2) = ((j + 1) % 3, (j + 2) % 3);
                    let (c1, c2) = ((i + 1) % 3, (i + 2) % 3);
                    adj[(i, j)] = w[(r1, c1)] * w[(r2, c2)] - w[(r1, c2)] * w[(r2, c1)];
                }
            }
            w[(0, 0)] * adj[(0, 0)] + w[(0, 1)] * adj[(1, 0)] + w[(0, 2)] * adj[(2, 0)]
        }
        _ => return None,
    };
    Some((adj, det))
}

/// Factorizes a small dense W into `factors`: its adjugate and determinant up to 3×3, an LU
/// above. (A macro: nalgebra's LU of a generic `Const<N>` needs bounds only each size meets.)
macro_rules! small_factorize {
    ($w:expr, $factors:expr) => {{
        let w = $w;
        let regular = match adjugate(&w) {
            Some((adj, det)) => {
                *$factors = SmallFactors::Adjugate(adj, det);
                // A non-finite adjugate makes a non-finite solution, which `solve` reports.
                det != 0.0 && det.is_finite()
            }
            None => {
                let lu = w.lu();
                let regular = lu.is_invertible();
                *$factors = SmallFactors::Lu(lu);
                regular
            }
        };
        if regular {
            Ok(())
        } else {
            Err(FactorizeError::Singular)
        }
    }};
}

/// `DenseMatrix` and `NewtonMatrix` for `SMatrix<f64, N, N>`: nalgebra's fixed-size LU needs each
/// size spelled out.
macro_rules! dense_matrix {
    ($($n:literal)*) => {$(
        impl DenseMatrix for nalgebra::SMatrix<f64, $n, $n> {
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
                SmallFactors::Adjugate(nalgebra::SMatrix::identity(), 1.0)
            }

            #[inline]
            fn factorize(
                &mut self,
                c: f64,
                factors: &mut Self::Factors,
            ) -> Result<(), FactorizeError> {
                let w = nalgebra::SMatrix::<f64, $n, $n>::identity() - *self * c;
                small_factorize!(w, factors)
            }

            #[inline]
            fn factorize_mass(
                &mut self,
                c: f64,
                mass: &[(usize, usize, f64)],
                factors: &mut Self::Factors,
            ) -> Result<(), FactorizeError> {
                let mut w = *self * -c;
                for &(i, j, m) in mass {
                    w[(i, j)] += m;
                }
                small_factorize!(w, factors)
            }

            #[inline]
            fn dense_entry(&self, row: usize, column: usize) -> Option<f64> {
                Some(self[(row, column)])
            }

            #[inline]
            fn solve(
                &mut self,
                factors: &mut Self::Factors,
                b: &mut [f64],
            ) -> Result<(), SolveError> {
                let mut rhs = nalgebra::SVector::<f64, $n>::from_column_slice(b);
                let solved = match factors {
                    SmallFactors::Adjugate(adj, det) => {
                        rhs = *adj * rhs * (1.0 / *det);
                        true
                    }
                    SmallFactors::Lu(lu) => lu.solve_mut(&mut rhs),
                };
                b.copy_from_slice(rhs.as_slice());
                // nalgebra's LU reports a singular U; its solution is not finite then.
                if solved { finite(b) } else { Err(SolveError::NotFinite) }
            }

            #[inline]
            fn non_finite_entry(&self) -> Option<(usize, usize, f64)> {
                // An integer reduction over the stored entries, which vectorizes: a scalar scan
                // that stops at the first (`iter().all(is_finite)`) cost POLLU's 20 × 20
                // Rosenbrock23 step 0.45 µs of its 2.3 µs, this one 0.1 µs (peers bench `stiff`).
                const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
                let non_finite = self
                    .as_slice()
                    .iter()
                    .fold(0u64, |n, x| n | u64::from(x.to_bits() & EXPONENT == EXPONENT));
                if non_finite == 0 {
                    return None;
                }
                first_non_finite($n, |row, column| self[(row, column)])
            }
        }
    )*};
}

dense_matrix!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32);

impl DenseMatrix for nalgebra::SMatrix<f64, 0, 0> {
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
    fn factorize(&mut self, _: f64, _: &mut ()) -> Result<(), FactorizeError> {
        Ok(())
    }
    fn solve(&mut self, _: &mut (), _: &mut [f64]) -> Result<(), SolveError> {
        Ok(())
    }
    fn non_finite_entry(&self) -> Option<(usize, usize, f64)> {
        None
    }
}

mod faer;

pub use faer::FaerDense;

#[cfg(test)]
mod tests;
