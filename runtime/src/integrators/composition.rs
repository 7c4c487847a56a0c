//! Symmetric compositions of leapfrog: the machinery [`Yoshida4`](super::Yoshida4),
//! [`Yoshida6`](super::Yoshida6) and [`KahanLi6`](super::KahanLi6) share.

use std::fmt::Debug;
use std::marker::PhantomData;

use super::verlet::{Verlet, VerletForm};
use super::{Step, axpy};
use crate::model::{split, split_mut};
use crate::{Method, SecondOrder, State};

/// The weights γ₁ … γₛ of a symmetric composition (γᵢ = γₛ₊₁₋ᵢ, Σγᵢ = 1).
pub trait Weights: Clone + Debug + super::Sealed {
    /// The method the composition implements.
    const METHOD: Method;
    /// γ₁ … γₛ, in the order the substeps are taken.
    const WEIGHTS: &'static [f64];
}

/// Leapfrog composed with itself: one step of size h is s leapfrog (kick-drift-kick) substeps of
/// sizes γ₁h, …, γₛh,
///
/// Φₕ = Φ^{LF}_{γₛh} ∘ … ∘ Φ^{LF}_{γ₁h}.
///
/// With symmetric weights the composition of a symmetric second-order method has even order;
/// the weights are chosen to cancel the error terms up to the target order (Hairer, Lubich &
/// Wanner, *Geometric Numerical Integration*, 2nd ed., 2006, §II.4 and §V.3). The substeps pass
/// the force on (the last kick of one and the first of the next use the same aᵢ), so a step
/// costs s force evaluations. Symplectic and time-reversible like leapfrog, so energy stays
/// bounded over exponentially long times; substeps with negative γᵢ step backwards.
///
/// The forces must not read velocities: the velocity-dependent leapfrog odyn uses (a predictor
/// for vₙ₊₁) is not symmetric, and composing it would not raise its order.
pub type Composition<S, W> = Verlet<S, Composed<W>>;

/// The [`VerletForm`] of the composition with weights `W`: the Verlet family's kept force and
/// start-up evaluation, with s leapfrog substeps a step.
#[derive(Clone, Debug)]
pub struct Composed<W>(PhantomData<W>);

impl<W: Weights> crate::integrators::sealed::Sealed for Composed<W> {}

impl<W: Weights> VerletForm for Composed<W> {
    const METHOD: Method = W::METHOD;

    /// `probe` carries the force at the current substep (the forces never read velocities, so
    /// no predictor needs it); a(yₙ₊₁) ends in `next`.
    #[inline]
    fn step<M: SecondOrder>(
        model: &M,
        s: Step<'_, M::State>,
        accel: &M::State,
        next: &mut M::State,
        probe: &mut M::State,
        y_new: &mut M::State,
    ) {
        let stage = probe;
        y_new.clone_from(s.y);
        stage.clone_from(accel);
        let mut elapsed = 0.0;
        for &gamma in W::WEIGHTS {
            let (h, half) = (gamma * s.h, 0.5 * gamma * s.h);
            {
                let (_, a) = split(stage.as_slice());
                let (x, v) = split_mut(y_new.as_mut_slice());
                axpy(v, half, a); // kick
                axpy(x, h, v); // drift
            }
            elapsed += gamma;
            model.acceleration(s.t + elapsed * s.h, y_new, next);
            s.stats.evaluations += 1;
            let (_, a) = split(next.as_slice());
            let (_, v) = split_mut(y_new.as_mut_slice());
            axpy(v, half, a); // kick
            std::mem::swap(stage, next);
        }
        std::mem::swap(stage, next);
    }
}

/// The largest ω·h for which the composition is stable on ẍ = −ω²x: the first z > 0 where the
/// one-step matrix P(z) = M(γₛz)⋯M(γ₁z) has |tr P| > 2 (det P = 1), with leapfrog's
/// M(z) = [[1 − z²/2, z], [−z(1 − z²/4), 1 − z²/2]] on (x, v/ω). Scanned in steps of 1e-3, then
/// bisected to 1e-12.
pub(crate) fn oscillator_limit(weights: &[f64]) -> f64 {
    let unstable = |z: f64| {
        let mut p = [[1.0, 0.0], [0.0, 1.0]];
        for &gamma in weights {
            let w = gamma * z;
            let m = [
                [1.0 - 0.5 * w * w, w],
                [-w * (1.0 - 0.25 * w * w), 1.0 - 0.5 * w * w],
            ];
            p = [
                [
                    m[0][0] * p[0][0] + m[0][1] * p[1][0],
                    m[0][0] * p[0][1] + m[0][1] * p[1][1],
                ],
                [
                    m[1][0] * p[0][0] + m[1][1] * p[1][0],
                    m[1][0] * p[0][1] + m[1][1] * p[1][1],
                ],
            ];
        }
        (p[0][0] + p[1][1]).abs() > 2.0
    };
    let mut z = 0.0;
    while !unstable(z + 1e-3) {
        z += 1e-3;
    }
    let (mut lo, mut hi) = (z, z + 1e-3);
    while hi - lo > 1e-12 {
        let mid = 0.5 * (lo + hi);
        if unstable(mid) { hi = mid } else { lo = mid }
    }
    lo
}
