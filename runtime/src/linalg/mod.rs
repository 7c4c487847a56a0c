//! The linear algebra of the implicit methods: dense Newton matrices, Newton's options, the
//! sparse SPD solver of the grid fluid, and the sparse solvers of particle and field models.
//!
//! The sparse solvers are types behind one trait (`solver.rs`, `LinearSolve`), in a line of
//! dependencies: `operator` (the products) → `solver` → `direct` (Cholesky, LU) → `precond`
//! (block Jacobi, ILU(0), Fourier, multigrid) → `krylov` (CG and BiCGSTAB with a
//! preconditioner) → `sparse` (the policy that chooses one for a run).

pub(crate) mod dense;
mod direct;
pub(crate) mod krylov;
pub(crate) mod laplacian;
mod newton;
mod operator;
mod precond;
mod solver;
pub(crate) mod sparse;
pub(crate) mod spd;

pub use dense::{DenseMatrix, FactorizeError, FaerDense, NewtonMatrix, SolveError};
pub use krylov::{AutoPolicy, KrylovOptions, LinearSolver, Preconditioner, Solves};
pub use laplacian::LinkLaplacian;
pub use newton::{NewtonOptions, ParticleSolve, QuasiNewtonOptions};

/// A small linear congruential generator for tests (Knuth's MMIX constants), 31 bits a draw:
/// the tests need variety, not quality.
#[cfg(test)]
pub(crate) fn generator(mut seed: u64) -> impl FnMut() -> usize {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 33) as usize
    }
}

/// Draws in [−1, 1) from [`generator`].
#[cfg(test)]
pub(crate) fn signed(seed: u64) -> impl FnMut() -> f64 {
    let mut draw = generator(seed);
    move || draw() as f64 / (1u64 << 31) as f64 * 2.0 - 1.0
}
