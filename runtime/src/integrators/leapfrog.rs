//! Leapfrog in kick-drift-kick form.

use super::{Integrator, axpy};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State};

/// Leapfrog, kick-drift-kick: vₙ₊½ = vₙ + ½h·aₙ, xₙ₊₁ = xₙ + h·vₙ₊½, vₙ₊₁ = vₙ₊½ + ½h·aₙ₊₁.
///
/// The form N-body codes use: the half-step velocity is the one that drifts the positions.
/// In exact arithmetic it is the same map as velocity Verlet; the two round differently.
/// When the force reads velocities, aₙ₊₁ is evaluated at ṽ = vₙ₊½ + ½h·aₙ (a first-order
/// predictor of vₙ₊₁), which keeps second order.
///
/// - **Order** 2.
/// - **Energy**: symplectic and time-reversible; on ẍ = −ω²x, E/E₀ ∈ [1 − ω²h²/4, 1].
/// - **Stability**: ωh < 2.
///
/// Reference: Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., 2006,
/// §I.3.1; V. Springel, "The cosmological simulation code GADGET-2", MNRAS 364 (2005) 1105, §4.
#[derive(Clone, Debug)]
pub struct Leapfrog<S> {
    dt: f64,
    /// aₙ in the velocity half.
    accel: S,
    /// aₙ₊₁ in the velocity half.
    next: S,
    /// The state at which aₙ₊₁ is evaluated, when the force reads velocities.
    probe: S,
}

impl<M: SecondOrder> Integrator<M> for Leapfrog<M::State> {
    const METHOD: Method = Method::Leapfrog;
    const STARTUP_EVALUATIONS: u64 = 1;
    const EVALUATIONS_PER_STEP: u64 = 1;

    fn start(model: &M, t0: f64, dt: f64, state: &M::State, _: &NewtonOptions) -> Result<Self> {
        let mut accel = state.clone();
        model.acceleration(t0, state, &mut accel);
        Ok(Leapfrog {
            dt,
            next: accel.clone(),
            probe: state.clone(),
            accel,
        })
    }

    #[inline]
    fn step(&mut self, model: &M, t: f64, state: &mut M::State) -> Result<()> {
        let half = 0.5 * self.dt;
        let (_, a) = split(self.accel.as_slice());
        {
            let (x, v) = split_mut(state.as_mut_slice());
            axpy(v, half, a); // kick
            axpy(x, self.dt, v); // drift
        }
        if M::READS_VELOCITY {
            self.probe.clone_from(state);
            let (_, v_probe) = split_mut(self.probe.as_mut_slice());
            axpy(v_probe, half, a);
            model.acceleration(t + self.dt, &self.probe, &mut self.next);
        } else {
            model.acceleration(t + self.dt, state, &mut self.next);
        }
        let (_, a_next) = split(self.next.as_slice());
        let (_, v) = split_mut(state.as_mut_slice());
        axpy(v, half, a_next); // kick
        std::mem::swap(&mut self.accel, &mut self.next);
        Ok(())
    }
}
