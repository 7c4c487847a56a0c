//! Explicit (forward) Euler.

use super::{Integrator, Step, set_axpy};
use crate::{Method, Model, NewtonOptions, Result, State, Stats};

/// R(z) = 1 + z: the stability polynomial the stability explorer reads.
pub(crate) fn tableau_polynomial() -> Vec<f64> {
    vec![1.0, 1.0]
}

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
    dydt: S,
}

impl<S> crate::integrators::sealed::Sealed for ExplicitEuler<S> {}

impl<M: Model> Integrator<M> for ExplicitEuler<M::State> {
    const METHOD: Method = Method::ExplicitEuler;

    fn prepare(_: &M, _: f64, y0: &M::State, _: &NewtonOptions, _: &mut Stats) -> Result<Self> {
        Ok(ExplicitEuler {
            dydt: y0.try_clone()?,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        model.derivative(s.t, s.y, &mut self.dydt);
        s.stats.evaluations += 1;
        set_axpy(
            y_new.as_mut_slice(),
            s.y.as_slice(),
            s.h,
            self.dydt.as_slice(),
        );
        Ok(0.0)
    }
}
