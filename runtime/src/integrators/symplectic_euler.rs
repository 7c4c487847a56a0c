//! Symplectic (semi-implicit) Euler.

use super::{Integrator, axpy};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State};

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
    dt: f64,
    accel: S,
}

impl<M: SecondOrder> Integrator<M> for SymplecticEuler<M::State> {
    const METHOD: Method = Method::SymplecticEuler;
    const STARTUP_EVALUATIONS: u64 = 0;
    const EVALUATIONS_PER_STEP: u64 = 1;

    fn start(_: &M, _: f64, dt: f64, state: &M::State, _: &NewtonOptions) -> Result<Self> {
        Ok(SymplecticEuler {
            dt,
            accel: state.clone(),
        })
    }

    #[inline]
    fn step(&mut self, model: &M, t: f64, state: &mut M::State) -> Result<()> {
        model.acceleration(t, state, &mut self.accel);
        let (_, a) = split(self.accel.as_slice());
        let (x, v) = split_mut(state.as_mut_slice());
        axpy(v, self.dt, a);
        axpy(x, self.dt, v);
        Ok(())
    }
}
