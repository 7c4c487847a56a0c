//! Leapfrog in kick-drift-kick form.

use super::verlet::{VerletForm, Verlet};
use super::{Step, axpy, set_axpy};
use crate::model::{split, split_mut};
use crate::{Method, SecondOrder, State};

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
pub type Leapfrog<S> = Verlet<S, LeapfrogForm>;

/// The kick-drift-kick step of [`Leapfrog`].
#[derive(Clone, Copy, Debug)]
pub struct LeapfrogForm;

impl crate::integrators::sealed::Sealed for LeapfrogForm {}

impl VerletForm for LeapfrogForm {
    const METHOD: Method = Method::Leapfrog;

    #[inline(always)]
    fn step<M: SecondOrder>(
        model: &M,
        s: Step<'_, M::State>,
        accel: &M::State,
        next: &mut M::State,
        probe: &mut M::State,
        y_new: &mut M::State,
    ) {
        let (h, half) = (s.h, 0.5 * s.h);
        let (_, a) = split(accel.as_slice());
        let (x0, v0) = split(s.y.as_slice());
        {
            let (x, v) = split_mut(y_new.as_mut_slice());
            set_axpy(v, v0, half, a); // kick
            set_axpy(x, x0, h, v); // drift
        }
        if M::READS_VELOCITY {
            probe.clone_from(y_new);
            let (_, v_probe) = split_mut(probe.as_mut_slice());
            axpy(v_probe, half, a);
            model.acceleration(s.t + h, probe, next);
        } else {
            model.acceleration(s.t + h, y_new, next);
        }
        s.stats.evaluations += 1;
        let (_, a_next) = split(next.as_slice());
        let (_, v) = split_mut(y_new.as_mut_slice());
        axpy(v, half, a_next); // kick
    }
}
