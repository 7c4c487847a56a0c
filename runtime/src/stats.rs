//! [`Stats`]: what a run cost, counted the same way for every method, with its sections
//! ([`LinearWork`] and its [`KrylovWork`], [`SensitivityWork`]).

use std::fmt;

/// The work a run did. Every trajectory carries one, fixed-step or adaptive.
///
/// Evaluations made to locate events or fill dense output (a cubic Hermite interpolant needs
/// f at both ends of a step) are counted with the method's own.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps (for a fixed-step run with step halving, the sub-steps actually taken).
    pub steps: u64,
    /// Rejected step attempts: error estimate above tolerance, or a failed implicit solve.
    pub rejected: u64,
    /// Evaluations of f(t, y) (or of the acceleration, for second-order methods).
    pub evaluations: u64,
    /// Evaluations of the Jacobian ∂f/∂y.
    pub jacobian_evaluations: u64,
    /// Evaluations of ∂f/∂t (Rosenbrock methods on models that read the time).
    pub time_derivative_evaluations: u64,
    /// Matrix factorizations (LU or Cholesky) of implicit methods.
    pub factorizations: u64,
    /// Solves with a factorized matrix (one per Newton iteration or Rosenbrock stage).
    pub linear_solves: u64,
    /// A particle or field model's sparse factorizations by kind, and its Krylov solves (all
    /// zero for dense models and explicit methods).
    pub linear: LinearWork,
    /// What a sensitivity run's model evaluations were ([`crate::sensitivity::Sensitive`]; all
    /// zero for other runs).
    pub sensitivity: SensitivityWork,
}

impl Stats {
    /// Force and Jacobian evaluations together: the cost axis of work-precision charts.
    pub fn function_evaluations(&self) -> u64 {
        self.evaluations + self.jacobian_evaluations + self.time_derivative_evaluations
    }
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} steps ({} rejected), {} f, {} J",
            self.steps, self.rejected, self.evaluations, self.jacobian_evaluations
        )?;
        if self.time_derivative_evaluations > 0 {
            write!(f, ", {} ∂f/∂t", self.time_derivative_evaluations)?;
        }
        if self.factorizations > 0 {
            write!(
                f,
                ", {} factorizations, {} solves",
                self.factorizations, self.linear_solves
            )?;
        }
        let (linear, krylov) = (&self.linear, &self.linear.krylov);
        if linear.cholesky + linear.cholesky_failed + linear.lu > 0 {
            write!(
                f,
                " ({} Cholesky, {} LU, {} failed Cholesky)",
                linear.cholesky, linear.lu, linear.cholesky_failed
            )?;
        }
        if krylov.solves > 0 {
            write!(
                f,
                ", {} Krylov solves in {} iterations ({} fell back to the direct solve)",
                krylov.solves, krylov.iterations, krylov.fallbacks
            )?;
        }
        let sensitivity = &self.sensitivity;
        if sensitivity.derivatives > 0 {
            write!(
                f,
                "; the model's own: {} f, {} J, {} ∂f/∂p",
                sensitivity.derivatives, sensitivity.jacobians, sensitivity.parameter_jacobians
            )?;
        }
        Ok(())
    }
}

/// The sparse linear algebra of a particle or field model's implicit steps ([`Stats::linear`]),
/// by kind: [`Stats::factorizations`] counts every factorization, dense or sparse; this says
/// which sparse ones they were, and what the Krylov solves did. The symbolic analyses happen
/// once per run, the numeric factorizations once per Newton iteration (or Rosenbrock step). All
/// zero for dense models.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LinearWork {
    /// Symbolic Cholesky analyses (fill-reducing ordering and elimination tree).
    pub symbolic_cholesky: u64,
    /// Symbolic LU analyses (made only if a Newton matrix is unsymmetric or indefinite).
    pub symbolic_lu: u64,
    /// Numeric Cholesky factorizations that succeeded.
    pub cholesky: u64,
    /// Numeric Cholesky factorizations abandoned at a non-positive pivot (a symmetric but
    /// indefinite matrix), each followed by an LU: work done twice.
    pub cholesky_failed: u64,
    /// Numeric LU factorizations.
    pub lu: u64,
    /// The Krylov solves, when [`crate::LinearSolver`] chose them.
    pub krylov: KrylovWork,
}

/// The Krylov solves of a sparse Newton matrix ([`LinearWork::krylov`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct KrylovWork {
    /// Solves by a Krylov method.
    pub solves: u64,
    /// Their iterations, together.
    pub iterations: u64,
    /// Block-Jacobi, ILU(0) and multigrid preconditioners built (a reused factorization counts
    /// as a Cholesky or LU instead).
    pub preconditioners: u64,
    /// Solves redone by the direct solver (no convergence within `max_iterations`, or a
    /// breakdown).
    pub fallbacks: u64,
    /// 1 when [`crate::LinearSolver::Auto`] moved from block Jacobi to Fourier for this run (0 again
    /// when it tried Fourier and gave it back, [`crate::AutoPolicy::fourier_iteration_cost`]).
    pub switched_to_fourier: u64,
    /// 1 when [`crate::LinearSolver::Auto`] moved from block Jacobi or Fourier to multigrid for this
    /// run.
    pub switched_to_multigrid: u64,
    /// 1 when [`crate::LinearSolver::Auto`] gave up Krylov solves for this run.
    pub switched_to_direct: u64,
}

/// The model's own evaluations a [`crate::sensitivity::Sensitive`] run made: what the sensitivities cost beyond the
/// run's [`crate::Stats`] (which count evaluations of the augmented system).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SensitivityWork {
    /// Evaluations of f (one per augmented derivative).
    pub derivatives: u64,
    /// Evaluations of ∂f/∂y: one per augmented derivative, 1 + 2n per augmented Jacobian (its
    /// coupling blocks are central differences of J in each of the n components).
    pub jacobians: u64,
    /// Evaluations of ∂f/∂p: one per augmented derivative, 2n per augmented Jacobian.
    pub parameter_jacobians: u64,
}

impl SensitivityWork {
    /// The evaluations made since `earlier` was read from the same count.
    pub(crate) fn since(self, earlier: SensitivityWork) -> SensitivityWork {
        SensitivityWork {
            derivatives: self.derivatives - earlier.derivatives,
            jacobians: self.jacobians - earlier.jacobians,
            parameter_jacobians: self.parameter_jacobians - earlier.parameter_jacobians,
        }
    }
}
