//! [`Stats`]: what a run cost, counted the same way for every method.

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
        Ok(())
    }
}
