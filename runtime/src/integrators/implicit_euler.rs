//! Implicit (backward) Euler, solved by Newton's method with the generated Jacobian.

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
}

impl<M: Jacobian> Integrator<M> for ImplicitEuler<M> {
    const METHOD: Method = Method::ImplicitEuler;

    fn prepare(
        model: &M,
        _: f64,
        y0: &M::State,
        newton: &NewtonOptions,
        _: &mut Stats,
    ) -> Result<Self> {
        let mut jacobian = model.jacobian_matrix(y0);
        jacobian.configure(newton);
        Ok(ImplicitEuler {
            newton: *newton,
            force: y0.clone(),
            update: y0.clone(),
            factors: jacobian.factors(),
            jacobian,
        })
    }

    /// Newton's method for y = yₙ + h·f(tₙ₊₁, y), from y⁰ = yₙ.
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y: &mut M::State) -> Result<f64> {
        let (t1, h) = (s.t + s.h, s.h);
        y.clone_from(s.y);
        let mut residual = f64::NAN;
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
            residual = 0.0;
            let terms =
                s.y.as_slice()
                    .iter()
                    .zip(self.force.as_slice())
                    .zip(y.as_slice());
            for (bi, ((y0, f), yk)) in rhs.iter_mut().zip(terms) {
                *bi = y0 + h * f - yk;
                // NaN-propagating max: a NaN residual must not read as converged.
                if bi.abs() > residual || bi.is_nan() {
                    residual = bi.abs();
                }
            }
            if !residual.is_finite() {
                return Err(fail(iter, residual, NewtonFailure::NotFinite));
            }
            model.jacobian(t1, y, &mut self.jacobian);
            s.stats.jacobian_evaluations += 1;
            s.stats.factorizations += 1;
            s.stats.linear_solves += 1;
            if !(self.jacobian.factorize(h, &mut self.factors)
                && self.jacobian.solve(&mut self.factors, rhs))
            {
                let cause = if rhs.iter().all(|x| x.is_finite()) {
                    NewtonFailure::Singular
                } else {
                    NewtonFailure::NotFinite
                };
                return Err(fail(iter, residual, cause));
            }
            // Newton that stops contracting (θ = ‖Δₖ‖/‖Δₖ₋₁‖ ≥ 1) is heading for another root
            // of the implicit equations, or none: give up so the step can be halved (the test of
            // Hairer & Wanner 1996, §IV.8).
            let update = rhs.iter().fold(0.0, |m: f64, d| m.max(d.abs()));
            if update >= previous_update && !self.newton.linearized {
                return Err(fail(iter, residual, NewtonFailure::Diverging));
            }
            previous_update = update;
            let mut converged = true;
            for (yi, di) in y.as_mut_slice().iter_mut().zip(rhs.iter()) {
                *yi += di;
                converged &= di.abs() <= self.newton.tol * (1.0 + yi.abs());
            }
            if converged || self.newton.linearized {
                return Ok(0.0);
            }
        }
        Err(fail(
            self.newton.max_iters,
            residual,
            NewtonFailure::Iterations,
        ))
    }
}

impl<M: Jacobian> ImplicitEuler<M> {
    /// The Newton matrix, holding the last Jacobian or its factors: particle models read their
    /// factorization counts from it.
    pub fn matrix(&self) -> &M::Matrix {
        &self.jacobian
    }
}
