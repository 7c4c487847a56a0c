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
    pub max_iterations: u32,
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
    /// step (as a quasi-Newton method); the matrix is then always factorized by Cholesky. The
    /// projection drops a block's antisymmetric part and its negative stiffness: with
    /// `linearized`, a force without symmetric part (a magnetic one) or a repulsion is then
    /// treated explicitly, and the step can gain energy.
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
    /// Particle models under implicit Euler only: how each step's equations are solved (default
    /// [`ParticleSolve::Auto`]).
    pub particle_solve: ParticleSolve,
}

/// How implicit Euler solves a particle model's step ([`NewtonOptions::particle_solve`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum ParticleSolve {
    /// [`ParticleSolve::Newton`]. Neither faster solve is chosen automatically: the
    /// quasi-Newton solve at its default budget is not as close to the converged implicit Euler
    /// step as the one-step Baraff–Witkin form, and the Baraff–Witkin form on the definite
    /// matrix can gain energy where Newton does not (a stiff rope kicked sideways, a force
    /// without symmetric part such as a magnetic one: the guide's particles chapter has the
    /// measurements). The default.
    #[default]
    Auto,
    /// Newton's method on the sparse Newton matrix, refactorized every iteration (with
    /// `linearized`, the one-iteration Baraff–Witkin step).
    Newton,
    /// L-BFGS on the implicit Euler objective with a constant, prefactored initial Hessian
    /// ([`crate::integrators::QuasiNewton`]).
    QuasiNewton(QuasiNewtonOptions),
}

/// The quasi-Newton solve of implicit Euler for particle models: L-BFGS whose initial Hessian is
/// the link Laplacian M + h·C + h²·K, factorized once per step size (Liu, Bouaziz & Kavan 2017).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuasiNewtonOptions {
    /// Iterations allowed per step (default 8); the iterate reached is accepted, as in Liu et
    /// al.'s fixed budget per frame. Each costs one force evaluation and one substitution.
    pub max_iterations: u32,
    /// Stops earlier when every free particle's velocity residual |vᵢ − vₙ,ᵢ − h·aᵢ| is at most
    /// `tolerance`·(1 + |vᵢ|) (m/s; default 1e-6).
    pub tolerance: f64,
    /// Pairs of past updates L-BFGS keeps (default 5).
    pub history: u32,
}

impl Default for QuasiNewtonOptions {
    fn default() -> Self {
        QuasiNewtonOptions {
            max_iterations: 8,
            tolerance: 1e-6,
            history: 5,
        }
    }
}

impl QuasiNewtonOptions {
    /// Checks every option.
    ///
    /// Errors: [`crate::Error::InvalidInput`] for no iterations, a tolerance that is not finite
    /// and non-negative, or a history over 64.
    pub fn check(&self) -> crate::Result<()> {
        use crate::Error;
        if self.max_iterations == 0 {
            return Err(Error::invalid(
                "QuasiNewtonOptions::max_iterations",
                "must be at least 1",
            ));
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(Error::invalid(
                "QuasiNewtonOptions::tolerance",
                format!("must be finite and non-negative, got {:?}", self.tolerance),
            ));
        }
        if self.history > 64 {
            return Err(Error::invalid(
                "QuasiNewtonOptions::history",
                format!("must be at most 64, got {}", self.history),
            ));
        }
        Ok(())
    }
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
        if self.max_iterations == 0 {
            return Err(Error::invalid(
                "NewtonOptions::max_iterations",
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
        if let ParticleSolve::QuasiNewton(options) = &self.particle_solve {
            options.check()?;
        }
        self.linear.check()
    }

    /// The quasi-Newton options `particle_solve` selects, if any.
    pub(crate) fn quasi_newton(&self) -> Option<QuasiNewtonOptions> {
        match self.particle_solve {
            ParticleSolve::QuasiNewton(options) => Some(options),
            ParticleSolve::Newton | ParticleSolve::Auto => None,
        }
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
            max_iterations: 20,
            max_halvings: 20,
            linearized: false,
            definite: false,
            linear: crate::LinearSolver::default(),
            refactor_ratio: 0.3,
            particle_solve: ParticleSolve::Auto,
        }
    }
}
