//! Implicit (backward) Euler, solved by Newton's method with the generated Jacobian.

use super::{Evaluations, Integrator};
use crate::{Error, Jacobian, Method, NewtonMatrix, NewtonOptions, Result, State};

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
/// factorization per step. When the iteration fails — too many iterations,
/// a singular matrix, or updates that stop shrinking — the step is retried as two half steps,
/// recursively up to [`NewtonOptions::max_halvings`] deep, and past that fails with
/// [`Error::NewtonDidNotConverge`]. The recorded grid keeps the fixed dt.
///
/// - **Order** 1.
/// - **Energy**: on ẍ = −ω²x the step divides (x, v/ω) by 1 − iωh, so the energy is multiplied by
///   exactly 1/(1 + ω²h²) every step: artificial damping, strongest for stiff modes.
/// - **Stability**: A- and L-stable, |1/(1 − hλ)| < 1 for every Re λ < 0 and → 0 as hλ → −∞, so
///   any dt is stable on a stiff spring.
///
/// Reference: E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed.,
/// Springer 1996, §IV.3 (stability) and §IV.8 (Newton iterations).
#[derive(Clone, Debug)]
pub struct ImplicitEuler<M: Jacobian> {
    dt: f64,
    newton: NewtonOptions,
    /// yₙ, the start of the step.
    start: M::State,
    /// f(tₙ₊₁, yᵏ).
    force: M::State,
    /// −G(yᵏ), then the Newton update Δ.
    update: M::State,
    /// J(yᵏ), overwritten by the solve of (I − h·J)·Δ = −G.
    jacobian: M::Matrix,
    evaluations: Evaluations,
}

impl<M: Jacobian> Integrator<M> for ImplicitEuler<M> {
    const METHOD: Method = Method::ImplicitEuler;
    const STARTUP_EVALUATIONS: u64 = 0;
    const EVALUATIONS_PER_STEP: u64 = 0;

    fn start(model: &M, _: f64, dt: f64, state: &M::State, newton: &NewtonOptions) -> Result<Self> {
        let mut jacobian = model.jacobian_matrix(state);
        jacobian.configure(newton);
        Ok(ImplicitEuler {
            dt,
            newton: *newton,
            start: state.clone(),
            force: state.clone(),
            update: state.clone(),
            jacobian,
            evaluations: Evaluations::default(),
        })
    }

    fn step(&mut self, model: &M, t: f64, y: &mut M::State) -> Result<()> {
        self.advance(model, t, self.dt, y, 0)
    }

    fn evaluations(&self, _: u64) -> Evaluations {
        self.evaluations
    }
}

impl<M: Jacobian> ImplicitEuler<M> {
    /// The Newton matrix, holding the last Jacobian or its factors: particle models read their
    /// factorization counts from it.
    pub fn matrix(&self) -> &M::Matrix {
        &self.jacobian
    }

    /// One step of size `h` from `t`, retried as two half steps when Newton fails.
    fn advance(&mut self, model: &M, t: f64, h: f64, y: &mut M::State, depth: u32) -> Result<()> {
        self.start.clone_from(y);
        match self.solve(model, t + h, h, y) {
            Err(_) if depth < self.newton.max_halvings => {
                // The failure path may allocate (a dynamic state's copy); success never does.
                y.clone_from(&self.start);
                let saved = y.clone();
                if let Err(error) = self.advance(model, t, 0.5 * h, y, depth + 1) {
                    y.clone_from(&saved);
                    return Err(error);
                }
                self.advance(model, t + 0.5 * h, 0.5 * h, y, depth + 1)
            }
            result => result,
        }
    }

    /// Newton's method for y = yₙ + h·f(t₁, y), from y = yₙ = `self.start`.
    fn solve(&mut self, model: &M, t1: f64, h: f64, y: &mut M::State) -> Result<()> {
        let mut residual = f64::NAN;
        let mut previous_update = f64::INFINITY;
        for iter in 1..=self.newton.max_iters {
            model.derivative(t1, y, &mut self.force);
            self.evaluations.force += 1;
            let rhs = self.update.as_mut_slice();
            residual = 0.0;
            let terms = self
                .start
                .as_slice()
                .iter()
                .zip(self.force.as_slice())
                .zip(y.as_slice());
            for (bi, ((y0, f), yk)) in rhs.iter_mut().zip(terms) {
                *bi = y0 + h * f - yk;
                residual = residual.max(bi.abs());
            }
            model.jacobian(t1, y, &mut self.jacobian);
            self.evaluations.jacobian += 1;
            if !self.jacobian.solve_identity_minus(h, rhs) {
                return Err(Error::NewtonDidNotConverge {
                    t: t1,
                    iters: iter,
                    residual,
                });
            }
            // Newton that stops contracting (θ = ‖Δₖ‖/‖Δₖ₋₁‖ ≥ 1) is heading for another root
            // of the implicit equations, or none: give up so the step can be halved (the test of
            // Hairer & Wanner 1996, §IV.8).
            let update = rhs.iter().fold(0.0, |m: f64, d| m.max(d.abs()));
            if update.is_nan() || (update >= previous_update && !self.newton.linearized) {
                return Err(Error::NewtonDidNotConverge {
                    t: t1,
                    iters: iter,
                    residual,
                });
            }
            previous_update = update;
            let mut converged = true;
            for (yi, di) in y.as_mut_slice().iter_mut().zip(rhs.iter()) {
                *yi += di;
                converged &= di.abs() <= self.newton.tol * (1.0 + yi.abs());
            }
            if converged || self.newton.linearized {
                return Ok(());
            }
        }
        Err(Error::NewtonDidNotConverge {
            t: t1,
            iters: self.newton.max_iters,
            residual,
        })
    }
}
