//! [`NewtonOptions`]: how implicit methods solve their nonlinear equations.

/// Newton's method for the implicit equations of an implicit step.
///
/// An iteration stops when every component of the Newton update is small against the state:
/// |Δyᵢ| ≤ `tol`·(1 + |yᵢ|). A linear model converges in one iteration (the second only confirms
/// it), so the defaults cost two force and two Jacobian evaluations per step there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Mixed relative/absolute tolerance on the Newton update (default 1e-10).
    pub tol: f64,
    /// Iterations allowed per step before the step fails with
    /// [`crate::Error::NewtonDidNotConverge`] (default 20).
    pub max_iters: u32,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            tol: 1e-10,
            max_iters: 20,
        }
    }
}
