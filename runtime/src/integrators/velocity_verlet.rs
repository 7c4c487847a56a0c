//! Velocity Verlet.

use super::{Integrator, Step, axpy};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State, Stats};

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
    /// aₙ in the velocity half.
    accel: S,
    /// aₙ₊₁ of the last attempt, in the velocity half.
    next: S,
    /// The state at which aₙ₊₁ is evaluated, when the force reads velocities.
    probe: S,
}

impl<M: SecondOrder> Integrator<M> for VelocityVerlet<M::State> {
    const METHOD: Method = Method::VelocityVerlet;

    fn prepare(
        model: &M,
        t0: f64,
        y0: &M::State,
        _: &NewtonOptions,
        stats: &mut Stats,
    ) -> Result<Self> {
        let mut accel = y0.try_clone()?;
        model.acceleration(t0, y0, &mut accel);
        stats.evaluations += 1;
        Ok(VelocityVerlet {
            next: accel.try_clone()?,
            probe: y0.try_clone()?,
            accel,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let h = s.h;
        let (_, a) = split(self.accel.as_slice());
        let (x0, v0) = split(s.y.as_slice());
        {
            let (x, v) = split_mut(y_new.as_mut_slice());
            for (((xi, x0i), v0i), ai) in x.iter_mut().zip(x0).zip(v0).zip(a) {
                *xi = x0i + h * v0i + 0.5 * h * h * ai;
            }
            v.copy_from_slice(v0);
        }
        let probe = if M::READS_VELOCITY {
            self.probe.clone_from(y_new);
            let (_, v_probe) = split_mut(self.probe.as_mut_slice());
            axpy(v_probe, h, a);
            &self.probe
        } else {
            &*y_new
        };
        model.acceleration(s.t + h, probe, &mut self.next);
        s.stats.evaluations += 1;
        let (_, a_next) = split(self.next.as_slice());
        let (_, v) = split_mut(y_new.as_mut_slice());
        for ((vi, ai), bi) in v.iter_mut().zip(a).zip(a_next) {
            *vi += 0.5 * h * (ai + bi);
        }
        Ok(0.0)
    }

    #[inline]
    fn accept(&mut self) {
        std::mem::swap(&mut self.accel, &mut self.next);
    }

    fn restart(&mut self, model: &M, t: f64, y: &M::State, stats: &mut Stats) {
        model.acceleration(t, y, &mut self.accel);
        stats.evaluations += 1;
    }
}
