//! Implicit (backward) Euler, solved by Newton's method with the generated Jacobian, or for
//! particle models by L-BFGS on a prefactored matrix.

mod lbfgs;
mod quasi_newton;

pub use quasi_newton::QuasiNewton;

use super::{Integrator, Step};
use crate::{
    Error, Jacobian, Mass, Method, NewtonFailure, NewtonMatrix, NewtonOptions, Result, State, Stats,
};

/// Implicit (backward) Euler: yₙ₊₁ = yₙ + h·f(tₙ₊₁, yₙ₊₁).
///
/// Each step solves G(y) = y − yₙ − h·f(tₙ₊₁, y) = 0 by Newton's method from y⁰ = yₙ:
/// (I − h·J(yᵏ))·Δ = −G(yᵏ), yᵏ⁺¹ = yᵏ + Δ, with J = ∂f/∂y the Jacobian `#[system]` derived from
/// the model's code, solved densely: on the stack with `nalgebra` up to 32 components, with faer's
/// LU above that (see [`crate::DenseMatrix`]); for particle models through the sparse velocity
/// form (M − h·∂f/∂v − h²·∂f/∂x)·Δv = … with faer's sparse Cholesky or LU (see
/// [`crate::particles::ParticleJacobian`]), which gives the same iterates. It stops when
/// |Δᵢ| ≤ tol·(1 + |yᵢ|) for every component. With [`NewtonOptions::linearized`] it takes exactly
/// one iteration and accepts it: the linearly implicit Euler of Baraff & Witkin (1998), one
/// factorization per step. When the iteration fails — too many iterations, a singular matrix,
/// updates that stop shrinking, or a non-finite value — the attempt fails with
/// [`Error::NewtonDidNotConverge`] naming the cause; the fixed-step driver then retries the step
/// as two half steps, up to [`NewtonOptions::max_halvings`] deep. The recorded grid keeps the
/// fixed dt.
///
/// Particle models with stiff links can solve the step with [`QuasiNewton`] instead (L-BFGS
/// whose initial Hessian is a constant link Laplacian, factorized once per step size;
/// [`crate::ParticleSolve::QuasiNewton`]): it converges to the same step.
///
/// - **Order** 1.
/// - **Energy**: on ẍ = −ω²x the step divides (x, v/ω) by 1 − iωh, so the energy is multiplied by
///   exactly 1/(1 + ω²h²) every step: artificial damping, strongest for stiff modes.
/// - **Stability**: A- and L-stable, |1/(1 − hλ)| < 1 for every Re λ < 0 and → 0 as hλ → −∞, so
///   any dt is stable on a stiff spring.
///
/// With a mass matrix (a differential–algebraic model, M·y′ = f) the step solves
/// M(yₙ₊₁ − yₙ) = h·f(tₙ₊₁, yₙ₊₁), Newton with M − h·J, and its dense output is the straight
/// line between the steps (the cubic Hermite interpolant would take f for y′).
///
/// Reference: E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed.,
/// Springer 1996, §IV.3 (stability) and §IV.8 (Newton iterations).
pub struct ImplicitEuler<M: Jacobian> {
    newton: NewtonOptions,
    /// f(tₙ₊₁, yᵏ).
    force: M::State,
    /// −G(yᵏ), then the Newton update Δ.
    update: M::State,
    /// J(yᵏ).
    jacobian: M::Matrix,
    /// The factors of I − h·J(yᵏ).
    factors: <M::Matrix as NewtonMatrix>::Factors,
    /// The quasi-Newton solve, when the options select it for this model.
    quasi_newton: Option<QuasiNewton>,
    /// M, for a model with a mass matrix: M(yₙ₊₁ − yₙ) = h·f(tₙ₊₁, yₙ₊₁) then, Newton with
    /// M − h·J.
    mass: Option<Mass>,
}

impl<M: Jacobian> crate::integrators::sealed::Sealed for ImplicitEuler<M> {}

impl<M: Jacobian> Integrator<M> for ImplicitEuler<M> {
    const METHOD: Method = Method::ImplicitEuler;

    fn linear_work(&self) -> crate::LinearWork {
        crate::NewtonMatrix::work(&self.jacobian)
    }

    fn prepare(
        model: &M,
        t0: f64,
        y0: &M::State,
        newton: &NewtonOptions,
        stats: &mut Stats,
    ) -> Result<Self> {
        let mut jacobian = model.jacobian_matrix(y0);
        let mut quasi_newton = None;
        if let Some(options) = newton.quasi_newton() {
            let refused = |why: &str| {
                Error::invalid(
                    "NewtonOptions::particle_solve",
                    format!("ParticleSolve::QuasiNewton needs {why}; use ParticleSolve::Newton"),
                )
            };
            if !<M::Matrix as NewtonMatrix>::LINKS {
                return Err(refused("a particle model (this model has no links)"));
            }
            // The link weights come from J at the start.
            model.jacobian(t0, y0, &mut jacobian);
            stats.jacobian_evaluations += 1;
            let laplacian = jacobian.link_laplacian().ok_or_else(|| {
                refused("links with stiffness (no pair kernel's derivative at the start pulls its ends together)")
            })?;
            quasi_newton = Some(QuasiNewton::new(options, laplacian));
        }
        jacobian.configure(
            newton,
            if newton.linearized {
                crate::Solves::OneStep
            } else {
                crate::Solves::Newton
            },
        );
        let mass = crate::model::mass_of(model, y0)?;
        Ok(ImplicitEuler {
            newton: *newton,
            force: y0.try_clone()?,
            update: y0.try_clone()?,
            factors: jacobian.factors(),
            jacobian,
            quasi_newton,
            mass,
        })
    }

    /// For a model with a mass matrix, the straight line from yₙ to yₙ₊₁ (order 1, as the
    /// method): the driver's cubic Hermite interpolant takes f for y′, which M·y′ = f is not.
    fn dense(
        &mut self,
        _: &M,
        s: Step<'_, M::State>,
        y_new: &M::State,
        dense: &mut super::DenseStep<M::State>,
    ) -> bool {
        if !M::MASS_MATRIX {
            return false;
        }
        let [c0, c1] = dense.fill(s.t, s.h, 1) else {
            unreachable!("fill returns degree + 1 coefficients")
        };
        c0.clone_from(s.y);
        for ((o, a), b) in c1
            .as_mut_slice()
            .iter_mut()
            .zip(s.y.as_slice())
            .zip(y_new.as_slice())
        {
            *o = b - a;
        }
        true
    }

    /// Newton's method for y = yₙ + h·f(tₙ₊₁, y), from y⁰ = yₙ (or the quasi-Newton solve).
    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y: &mut M::State) -> Result<f64> {
        let (t1, h) = (s.t + s.h, s.h);
        if let Some(solver) = self.quasi_newton.as_mut() {
            let derivative = |y: &M::State, f: &mut M::State| model.derivative(t1, y, f);
            let solved = solver.solve(h, s.y, y, &mut self.force, s.stats, derivative);
            s.stats.linear_solves += u64::from(solver.iterations());
            return match solved {
                Ok(()) => Ok(0.0),
                Err((iters, residual, cause)) => Err(Error::NewtonDidNotConverge {
                    t: t1,
                    dt: h,
                    iters,
                    residual,
                    cause,
                    halvings: 0,
                }),
            };
        }
        y.clone_from(s.y);
        let mut previous_update = f64::INFINITY;
        let fail = |iters, residual, cause| Error::NewtonDidNotConverge {
            t: t1,
            dt: h,
            iters,
            residual,
            cause,
            halvings: 0,
        };
        for iter in 1..=self.newton.max_iterations {
            model.derivative(t1, y, &mut self.force);
            s.stats.evaluations += 1;
            let rhs = self.update.as_mut_slice();
            let terms =
                s.y.as_slice()
                    .iter()
                    .zip(self.force.as_slice())
                    .zip(y.as_slice());
            match &self.mass {
                // h·f − M(yₖ − yₙ)
                Some(mass) if M::MASS_MATRIX => {
                    for (bi, f) in rhs.iter_mut().zip(self.force.as_slice()) {
                        *bi = h * f;
                    }
                    mass.apply_add(-1.0, y.as_slice(), rhs);
                    mass.apply_add(1.0, s.y.as_slice(), rhs);
                }
                _ => {
                    for (bi, ((y0, f), yk)) in rhs.iter_mut().zip(terms) {
                        *bi = y0 + h * f - yk;
                    }
                }
            }
            model.jacobian(t1, y, &mut self.jacobian);
            s.stats.jacobian_evaluations += 1;
            s.stats.factorizations += 1;
            s.stats.linear_solves += 1;
            // A non-finite residual makes a non-finite update, which `solve` reports; the
            // residual itself is measured only for the error, off the hot path.
            let factored = match &self.mass {
                Some(mass) if M::MASS_MATRIX => {
                    self.jacobian
                        .factorize_mass(h, mass.entries(), &mut self.factors)
                }
                _ => self.jacobian.factorize(h, &mut self.factors),
            };
            let solved = factored.is_ok() && self.jacobian.solve(&mut self.factors, rhs).is_ok();
            if !solved {
                // J at yₙ itself (the first iterate) that is not finite: no smaller step helps.
                if iter == 1 {
                    super::linearization::finite_jacobian(&self.jacobian, t1, y)?;
                }
                let finite_rhs = rhs.iter().all(|x| x.is_finite());
                let residual = self.residual(model, t1, h, s.y, y);
                // The right-hand side holds the failed solve's result: finite when the
                // factorization failed, not when the solve overflowed.
                let cause = match (residual.is_finite(), finite_rhs) {
                    (false, _) => NewtonFailure::NotFinite,
                    (true, true) => NewtonFailure::Singular,
                    (true, false) => NewtonFailure::UpdateNotFinite,
                };
                return Err(fail(iter, residual, cause));
            }
            // One pass: the update's size, convergence, and the update applied. Newton that
            // stops contracting (θ = ‖Δₖ‖/‖Δₖ₋₁‖ ≥ 1) is heading for another root of the
            // implicit equations, or none: give up so the step can be halved (the test of
            // Hairer & Wanner 1996, §IV.8); the caller discards y then.
            let mut update = 0.0f64;
            let mut converged = true;
            for (yi, di) in y.as_mut_slice().iter_mut().zip(rhs.iter()) {
                *yi += di;
                update = update.max(di.abs());
                converged &= di.abs() <= self.newton.tol * (1.0 + yi.abs());
            }
            if update >= previous_update && !self.newton.linearized {
                // Reported at the iterate the failing update started from.
                for (yi, di) in y.as_mut_slice().iter_mut().zip(rhs.iter()) {
                    *yi -= di;
                }
                let residual = self.residual(model, t1, h, s.y, y);
                return Err(fail(iter, residual, NewtonFailure::Diverging));
            }
            previous_update = update;
            if converged || self.newton.linearized {
                return Ok(0.0);
            }
        }
        let residual = self.residual(model, t1, h, s.y, y);
        Err(fail(
            self.newton.max_iterations,
            residual,
            NewtonFailure::Iterations,
        ))
    }
}

/// max |G(y)| = max |yₙ + h·f(t, y) − y|, for a failure's report (`scratch` takes f).
/// The largest |gᵢ| of the implicit equations g = yₙ + h·f(t, y) − y, NaN-propagating (a NaN
/// residual must not read as small); with a mass matrix, g = h·f(t, y) − M(y − yₙ).
fn residual_of<M: Jacobian>(
    model: &M,
    (t, h): (f64, f64),
    mass: Option<&Mass>,
    start: &M::State,
    y: &M::State,
    scratch: &mut M::State,
) -> f64 {
    model.derivative(t, y, scratch);
    let g = scratch.as_mut_slice();
    match mass {
        Some(mass) => {
            for f in g.iter_mut() {
                *f *= h;
            }
            mass.apply_add(-1.0, y.as_slice(), g);
            mass.apply_add(1.0, start.as_slice(), g);
        }
        None => {
            for ((f, y0), yk) in g.iter_mut().zip(start.as_slice()).zip(y.as_slice()) {
                *f = y0 + h * *f - yk;
            }
        }
    }
    g.iter().fold(0.0, |m: f64, g| {
        let g = g.abs();
        if g > m || g.is_nan() { g } else { m }
    })
}

impl<M: Jacobian> ImplicitEuler<M> {
    /// [`residual_of`] with this method's mass matrix and scratch state.
    fn residual(&mut self, model: &M, t: f64, h: f64, start: &M::State, y: &M::State) -> f64 {
        residual_of(model, (t, h), self.mass.as_ref(), start, y, &mut self.force)
    }

    /// The Newton matrix, holding the last Jacobian or its factors: particle models read their
    /// factorization counts from it.
    pub fn matrix(&self) -> &M::Matrix {
        &self.jacobian
    }

    /// The quasi-Newton solve, when the run uses it: its factorization and iteration counts.
    pub fn quasi_newton(&self) -> Option<&QuasiNewton> {
        self.quasi_newton.as_ref()
    }
}
