//! Position (Störmer) Verlet.

use super::Integrator;
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State};

/// Position (Störmer) Verlet: xₙ₊₁ = 2xₙ − xₙ₋₁ + h²·a(xₙ).
///
/// The velocity never enters the position update; the first step uses the Taylor start
/// x₁ = x₀ + h·v₀ + ½h²·a(x₀), and the recorded velocity is the second-order estimate
/// vₙ = (xₙ − xₙ₋₁)/h + ½h·a(xₙ). The force at xₙ₊₁ is kept for the next step, so each step costs
/// one evaluation. The forces must not read velocities (the macro knows from the body and the
/// runner refuses such a model), since there is no consistent velocity to give them.
///
/// - **Order** 2.
/// - **Energy**: symplectic; algebraically the same trajectory as velocity Verlet, so on
///   ẍ = −ω²x from x₀ = 1, v₀ = 0, E/E₀ stays in [1 − ω²h²/4, 1].
/// - **Stability**: ωh < 2.
///
/// Reference: L. Verlet, "Computer experiments on classical fluids", Phys. Rev. 159 (1967) 98;
/// Hairer, Lubich & Wanner, "Geometric numerical integration illustrated by the Störmer–Verlet
/// method", Acta Numerica 12 (2003) 399.
#[derive(Clone, Debug)]
pub struct PositionVerlet<S> {
    dt: f64,
    /// Whether a step was taken, so `previous` holds xₙ₋₁.
    started: bool,
    /// The state of the previous step (its position half is xₙ₋₁).
    previous: S,
    /// The state at the start of the current step.
    current: S,
    /// a(xₙ) in the velocity half.
    accel: S,
}

impl<M: SecondOrder> Integrator<M> for PositionVerlet<M::State> {
    const METHOD: Method = Method::PositionVerlet;
    const STARTUP_EVALUATIONS: u64 = 1;
    const EVALUATIONS_PER_STEP: u64 = 1;

    fn start(model: &M, t0: f64, dt: f64, state: &M::State, _: &NewtonOptions) -> Result<Self> {
        let mut accel = state.clone();
        model.acceleration(t0, state, &mut accel);
        Ok(PositionVerlet {
            dt,
            started: false,
            previous: state.clone(),
            current: state.clone(),
            accel,
        })
    }

    #[inline]
    fn step(&mut self, model: &M, t: f64, state: &mut M::State) -> Result<()> {
        let h = self.dt;
        self.current.clone_from(state);
        {
            let (_, a) = split(self.accel.as_slice());
            let (x, v) = split_mut(state.as_mut_slice());
            if self.started {
                let (x_prev, _) = split(self.previous.as_slice());
                for ((xi, pi), ai) in x.iter_mut().zip(x_prev).zip(a) {
                    *xi = 2.0 * *xi - pi + h * h * ai;
                }
            } else {
                for ((xi, vi), ai) in x.iter_mut().zip(v.iter()).zip(a) {
                    *xi += h * vi + 0.5 * h * h * ai;
                }
            }
        }
        model.acceleration(t + h, state, &mut self.accel);
        let (_, a) = split(self.accel.as_slice());
        let (x_old, _) = split(self.current.as_slice());
        let (x, v) = split_mut(state.as_mut_slice());
        for (((vi, xi), oi), ai) in v.iter_mut().zip(x.iter()).zip(x_old).zip(a) {
            *vi = (xi - oi) / h + 0.5 * h * ai;
        }
        std::mem::swap(&mut self.previous, &mut self.current);
        self.started = true;
        Ok(())
    }
}
