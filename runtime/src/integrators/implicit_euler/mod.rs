//! Implicit (backward) Euler, solved by Newton's method with the generated Jacobian, or for
//! particle models by L-BFGS on a prefactored matrix.

mod lbfgs;
mod quasi_newton;

pub use quasi_newton::QuasiNewton;

use super::{Integrator, Step};
use crate::{
    Error, Jacobian, Method, NewtonFailure, NewtonMatrix, NewtonOptions, Result, State, Stats,
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
}

impl<M: Jacobian> Integrator<M> for ImplicitEuler<M> {
    const METHOD: Method = Method::ImplicitEuler;

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
        Ok(ImplicitEuler {
            newton: *newton,
            force: y0.try_clone()?,
            update: y0.try_clone()?,
            factors: jacobian.factors(),
            jacobian,
            quasi_newton,
        })
    }

    /// Newton's method for y = yₙ + h·f(tₙ₊₁, y), from y⁰ = yₙ.
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
        for iter in 1..=self.newton.max_iters {
            model.derivative(t1, y, &mut self.force);
            s.stats.evaluations += 1;
            let rhs = self.update.as_mut_slice();
            let terms =
                s.y.as_slice()
                    .iter()
                    .zip(self.force.as_slice())
                    .zip(y.as_slice());
            for (bi, ((y0, f), yk)) in rhs.iter_mut().zip(terms) {
                *bi = y0 + h * f - yk;
            }
            model.jacobian(t1, y, &mut self.jacobian);
            s.stats.jacobian_evaluations += 1;
            s.stats.factorizations += 1;
            s.stats.linear_solves += 1;
            // A non-finite residual makes a non-finite update, which `solve` reports; the
            // residual itself is measured only for the error, off the hot path.
            let solved = self.jacobian.factorize(h, &mut self.factors).is_ok()
                && self.jacobian.solve(&mut self.factors, rhs).is_ok();
            if !solved {
                // J at yₙ itself (the first iterate) that is not finite: no smaller step helps.
                if iter == 1 {
                    super::linearization::finite_jacobian(&self.jacobian, t1, y)?;
                }
                let residual = residual_of(model, t1, h, s.y, y, &mut self.force);
                let cause = if residual.is_finite() && rhs.iter().all(|x| x.is_finite()) {
                    NewtonFailure::Singular
                } else {
                    NewtonFailure::NotFinite
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
                let residual = residual_of(model, t1, h, s.y, y, &mut self.force);
                return Err(fail(iter, residual, NewtonFailure::Diverging));
            }
            previous_update = update;
            if converged || self.newton.linearized {
                return Ok(0.0);
            }
        }
        let residual = residual_of(model, t1, h, s.y, y, &mut self.force);
        Err(fail(
            self.newton.max_iters,
            residual,
            NewtonFailure::Iterations,
        ))
    }
}

/// max |G(y)| = max |yₙ + h·f(t, y) − y|, for a failure's report (`scratch` takes f).
fn residual_of<M: Jacobian>(
    model: &M,
    t: f64,
    h: f64,
    start: &M::State,
    y: &M::State,
    scratch: &mut M::State,
) -> f64 {
    model.derivative(t, y, scratch);
    let terms = start
        .as_slice()
        .iter()
        .zip(scratch.as_slice())
        .zip(y.as_slice());
    terms.fold(0.0, |m: f64, ((y0, f), yk)| {
        let g = (y0 + h * f - yk).abs();
        // NaN-propagating: a NaN residual must not read as small.
        if g > m || g.is_nan() { g } else { m }
    })
}

impl<M: Jacobian> ImplicitEuler<M> {
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
