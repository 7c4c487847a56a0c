//! Velocity Verlet.

use super::verlet::{VerletForm, Verlet};
use super::{Step, axpy};
use crate::model::{split, split_mut};
use crate::{Method, SecondOrder, State};

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
pub type VelocityVerlet<S> = Verlet<S, VelocityVerletForm>;

/// The step of [`VelocityVerlet`]: positions from aₙ, then velocities from the mean of aₙ and
/// aₙ₊₁.
#[derive(Clone, Copy, Debug)]
pub struct VelocityVerletForm;

impl crate::integrators::sealed::Sealed for VelocityVerletForm {}

impl VerletForm for VelocityVerletForm {
    const METHOD: Method = Method::VelocityVerlet;

    #[inline(always)]
    fn step<M: SecondOrder>(
        model: &M,
        s: Step<'_, M::State>,
        accel: &M::State,
        next: &mut M::State,
        probe: &mut M::State,
        y_new: &mut M::State,
    ) {
        let h = s.h;
        let (_, a) = split(accel.as_slice());
        let (x0, v0) = split(s.y.as_slice());
        {
            let (x, v) = split_mut(y_new.as_mut_slice());
            for (((xi, x0i), v0i), ai) in x.iter_mut().zip(x0).zip(v0).zip(a) {
                *xi = x0i + h * v0i + 0.5 * h * h * ai;
            }
            v.copy_from_slice(v0);
        }
        let probe = if M::READS_VELOCITY {
            probe.clone_from(y_new);
            let (_, v_probe) = split_mut(probe.as_mut_slice());
            axpy(v_probe, h, a);
            &*probe
        } else {
            &*y_new
        };
        model.acceleration(s.t + h, probe, next);
        s.stats.evaluations += 1;
        let (_, a_next) = split(next.as_slice());
        let (_, v) = split_mut(y_new.as_mut_slice());
        for ((vi, ai), bi) in v.iter_mut().zip(a).zip(a_next) {
            *vi += 0.5 * h * (ai + bi);
        }
    }
}
