//! Symplectic (semi-implicit) Euler.

use super::{Integrator, Step, set_axpy};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State, Stats};

/// Symplectic (semi-implicit) Euler, velocity first:
/// vₙ₊₁ = vₙ + h·a(tₙ, xₙ, vₙ), xₙ₊₁ = xₙ + h·vₙ₊₁.
///
/// The same cost as explicit Euler with the two updates swapped.
///
/// - **Order** 1.
/// - **Energy**: symplectic, so it conserves a shadow Hamiltonian. On ẍ = −ω²x that is
///   H̃ = E − (ωh/2)·ω·x·v, which bounds E/E₀ to [2/(2 + ωh), 2/(2 − ωh)] from x₀ = 1, v₀ = 0.
/// - **Stability**: ωh < 2 on an undamped oscillator.
///
/// Reference: E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed.,
/// Springer 2006, §I.1.2 and Theorem VI.3.3.
#[derive(Clone, Debug)]
pub struct SymplecticEuler<S> {
    accel: S,
}

impl<S> crate::integrators::sealed::Sealed for SymplecticEuler<S> {}

impl<M: SecondOrder> Integrator<M> for SymplecticEuler<M::State> {
    const METHOD: Method = Method::SymplecticEuler;

    fn prepare(_: &M, _: f64, y0: &M::State, _: &NewtonOptions, _: &mut Stats) -> Result<Self> {
        Ok(SymplecticEuler {
            accel: y0.try_clone()?,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        model.acceleration(s.t, s.y, &mut self.accel);
        s.stats.evaluations += 1;
        let (_, a) = split(self.accel.as_slice());
        let (x0, v0) = split(s.y.as_slice());
        let (x, v) = split_mut(y_new.as_mut_slice());
        set_axpy(v, v0, s.h, a);
        set_axpy(x, x0, s.h, v);
        Ok(0.0)
    }
}
