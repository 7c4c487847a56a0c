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
    /// Iterations allowed per solve (default 20).
    pub max_iters: u32,
    /// When Newton fails, the step is retried as two half steps, and a failing half again, up to
    /// this depth (default 20, so down to dt/1 048 576; at most 52); the recorded grid is
    /// unchanged. Halving costs nothing until a step fails; Robertson's kinetics at dt = 1e3 need
    /// 14 levels on their first step. Past it the step fails
    /// with [`crate::Error::NewtonDidNotConverge`]. A fold in the implicit equations — van der
    /// Pol's relaxation jump at dt ≫ 1/μ — needs this; 0 gives strict fixed-step behaviour.
    pub max_halvings: u32,
    /// Take exactly one Newton iteration per step, from yₙ, and accept it (default false): the
    /// linearly implicit Euler of Baraff & Witkin, "Large Steps in Cloth Simulation" (1998),
    /// §3. It is as stable as the full solve on linear forces and costs one factorization per
    /// step; on nonlinear forces it is not implicit Euler any more and `tol` is ignored.
    pub linearized: bool,
    /// Particle models only (default false): make the Newton matrix symmetric positive definite
    /// by projecting each link's and each particle's D×D force-derivative blocks onto the
    /// positive-semidefinite stiffness they would have as a spring (symmetric part, negative
    /// eigenvalues clamped to zero; Teran et al., "Robust quasistatic finite elements and flesh
    /// simulation", 2005, §4). A compressed spring's exact Jacobian has negative transverse
    /// stiffness −k(L/|d| − 1), which at cloth stiffness makes M − h²·∂f/∂x indefinite: Newton
    /// then needs many iterations and halvings, and the one-step form can gain energy. The
    /// residual is still the exact one, so full Newton converges to the same implicit Euler
    /// step (as a quasi-Newton method); the matrix is then always factorized by Cholesky.
    pub definite: bool,
    /// Particle and field models only: how the sparse linear systems are solved (default
    /// [`crate::LinearSolver::Auto`]: preconditioned Krylov iterations for field models from
    /// 1 024 unknowns, sparse direct otherwise).
    pub linear: crate::LinearSolver,
    /// BDF only: the factorization of I − c·J (c = h/αₖ) is kept while c stays within this
    /// fraction of the c it was made with (default 0.3, CVODE's `DGMAX_LSETUP`), each Newton
    /// update then scaled by 2/(1 + c/c_old) as CVODE does, and on particle and field models
    /// Newton stops by CVODE's test; 0 is SciPy's `BDF` exactly: it refactorizes whenever h or
    /// the order changes, except for the retry after an error-test failure, and stops Newton by
    /// SciPy's tighter test ([`crate::integrators::Bdf`] has both).
    pub refactor_ratio: f64,
}

impl NewtonOptions {
    /// Checks every option.
    ///
    /// Errors: [`crate::Error::InvalidInput`] for a `tol` that is not finite and positive, no
    /// iterations, or more than 52 halvings (a step of dt/2⁵² is below the resolution of t).
    pub fn check(&self) -> crate::Result<()> {
        use crate::Error;
        if !(self.tol.is_finite() && self.tol > 0.0) {
            return Err(Error::invalid(
                "NewtonOptions::tol",
                format!("must be finite and positive, got {:?}", self.tol),
            ));
        }
        if self.max_iters == 0 {
            return Err(Error::invalid(
                "NewtonOptions::max_iters",
                "must be at least 1",
            ));
        }
        if !(self.refactor_ratio.is_finite() && (0.0..1.0).contains(&self.refactor_ratio)) {
            return Err(Error::invalid(
                "NewtonOptions::refactor_ratio",
                format!("must be in [0, 1), got {:?}", self.refactor_ratio),
            ));
        }
        if self.max_halvings > 52 {
            return Err(Error::invalid(
                "NewtonOptions::max_halvings",
                format!(
                    "must be at most 52 (dt/2^52 is below the resolution of t), got {}",
                    self.max_halvings
                ),
            ));
        }
        self.linear.check()
    }

    /// The one-iteration (Baraff–Witkin) form, other options at their defaults.
    pub fn linearized() -> Self {
        NewtonOptions {
            linearized: true,
            ..NewtonOptions::default()
        }
    }
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            tol: 1e-10,
            max_iters: 20,
            max_halvings: 20,
            linearized: false,
            definite: false,
            linear: crate::LinearSolver::default(),
            refactor_ratio: 0.3,
        }
    }
}
