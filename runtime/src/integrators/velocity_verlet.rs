//! Velocity Verlet.

use super::{Integrator, axpy};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State};

/// Velocity Verlet: xₙ₊₁ = xₙ + h·vₙ + ½h²·aₙ, vₙ₊₁ = vₙ + ½h·(aₙ + aₙ₊₁).
///
/// aₙ₊₁ is kept for the next step, so each step costs one force evaluation after a start-up one.
/// When the force reads velocities (damping), aₙ₊₁ is evaluated at the first-order predictor
/// ṽ = vₙ + h·aₙ; its O(h²) error enters the update multiplied by h, so the method stays second
/// order (checked by the convergence tests on the damped spring).
///
/// - **Order** 2.
/// - **Energy**: symplectic; on ẍ = −ω²x it conserves H̃ = ½v² + ½ω²(1 − ω²h²/4)x², so from
///   x₀ = 1, v₀ = 0, E/E₀ stays in [1 − ω²h²/4, 1].
/// - **Stability**: ωh < 2.
///
/// Reference: W. C. Swope, H. C. Andersen, P. H. Berens, K. R. Wilson, J. Chem. Phys. 76 (1982)
/// 637; Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., 2006, §I.1.4.
#[derive(Clone, Debug)]
pub struct VelocityVerlet<S> {
    dt: f64,
    /// aₙ in the velocity half.
    accel: S,
    /// aₙ₊₁ in the velocity half.
    next: S,
    /// The state at which aₙ₊₁ is evaluated.
    probe: S,
}

impl<M: SecondOrder> Integrator<M> for VelocityVerlet<M::State> {
    const METHOD: Method = Method::VelocityVerlet;
    const STARTUP_EVALUATIONS: u64 = 1;
    const EVALUATIONS_PER_STEP: u64 = 1;

    fn start(model: &M, t0: f64, dt: f64, state: &M::State, _: &NewtonOptions) -> Result<Self> {
        let mut accel = state.clone();
        model.acceleration(t0, state, &mut accel);
        Ok(VelocityVerlet {
            dt,
            next: accel.clone(),
            probe: state.clone(),
            accel,
        })
    }

    #[inline]
    fn step(&mut self, model: &M, t: f64, state: &mut M::State) -> Result<()> {
        let h = self.dt;
        let (_, a) = split(self.accel.as_slice());
        {
            let (x, v) = split_mut(state.as_mut_slice());
            for ((xi, vi), ai) in x.iter_mut().zip(v.iter()).zip(a) {
                *xi += h * vi + 0.5 * h * h * ai;
            }
        }
        self.probe.clone_from(state);
        if M::READS_VELOCITY {
            let (_, v_probe) = split_mut(self.probe.as_mut_slice());
            axpy(v_probe, h, a);
        }
        model.acceleration(t + h, &self.probe, &mut self.next);
        let (_, a_next) = split(self.next.as_slice());
        let (_, v) = split_mut(state.as_mut_slice());
        for ((vi, ai), bi) in v.iter_mut().zip(a).zip(a_next) {
            *vi += 0.5 * h * (ai + bi);
        }
        std::mem::swap(&mut self.accel, &mut self.next);
        Ok(())
    }
}
