//! Explicit (forward) Euler.

use super::{Integrator, axpy};
use crate::{Method, Model, NewtonOptions, Result, State};

/// Explicit (forward) Euler: yₙ₊₁ = yₙ + h·f(tₙ, yₙ).
///
/// For a second-order model the position moves with the *old* velocity: xₙ₊₁ = xₙ + h·vₙ,
/// vₙ₊₁ = vₙ + h·a(xₙ, vₙ).
///
/// - **Order** 1 (global error ∝ h).
/// - **Energy**: on ẍ = −ω²x each step maps (x, ωv) by a matrix of determinant 1 + ω²h², so the
///   energy grows by exactly that factor every step, whatever h.
/// - **Stability**: |1 + hλ| < 1 for every eigenvalue λ of the Jacobian; never on an undamped
///   oscillator (λ = ±iω).
///
/// Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*,
/// 2nd ed., Springer 1993, §I.7.
#[derive(Clone, Debug)]
pub struct ExplicitEuler<S> {
    dt: f64,
    dydt: S,
}

impl<M: Model> Integrator<M> for ExplicitEuler<M::State> {
    const METHOD: Method = Method::ExplicitEuler;
    const STARTUP_EVALUATIONS: u64 = 0;
    const EVALUATIONS_PER_STEP: u64 = 1;

    fn start(_: &M, _: f64, dt: f64, state: &M::State, _: &NewtonOptions) -> Result<Self> {
        Ok(ExplicitEuler {
            dt,
            dydt: state.clone(),
        })
    }

    #[inline]
    fn step(&mut self, model: &M, t: f64, y: &mut M::State) -> Result<()> {
        model.derivative(t, y, &mut self.dydt);
        axpy(y.as_mut_slice(), self.dt, self.dydt.as_slice());
        Ok(())
    }
}
