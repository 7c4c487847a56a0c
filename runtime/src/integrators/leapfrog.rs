//! Leapfrog in kick-drift-kick form.

use super::{Integrator, Step, axpy, set_axpy};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State, Stats};

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
    /// aₙ in the velocity half.
    accel: S,
    /// aₙ₊₁ of the last attempt, in the velocity half.
    next: S,
    /// The state at which aₙ₊₁ is evaluated, when the force reads velocities.
    probe: S,
}

impl<M: SecondOrder> Integrator<M> for Leapfrog<M::State> {
    const METHOD: Method = Method::Leapfrog;

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
        Ok(Leapfrog {
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
        let (h, half) = (s.h, 0.5 * s.h);
        let (_, a) = split(self.accel.as_slice());
        let (x0, v0) = split(s.y.as_slice());
        {
            let (x, v) = split_mut(y_new.as_mut_slice());
            set_axpy(v, v0, half, a); // kick
            set_axpy(x, x0, h, v); // drift
        }
        if M::READS_VELOCITY {
            self.probe.clone_from(y_new);
            let (_, v_probe) = split_mut(self.probe.as_mut_slice());
            axpy(v_probe, half, a);
            model.acceleration(s.t + h, &self.probe, &mut self.next);
        } else {
            model.acceleration(s.t + h, y_new, &mut self.next);
        }
        s.stats.evaluations += 1;
        let (_, a_next) = split(self.next.as_slice());
        let (_, v) = split_mut(y_new.as_mut_slice());
        axpy(v, half, a_next); // kick
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
