//! Position (Störmer) Verlet.

use super::{Integrator, Step};
use crate::model::{split, split_mut};
use crate::{Method, NewtonOptions, Result, SecondOrder, State, Stats};

/// Position (Störmer) Verlet: xₙ₊₁ = 2xₙ − xₙ₋₁ + h²·a(xₙ).
///
/// The velocity never enters the position update; the first step uses the Taylor start
/// x₁ = x₀ + h·v₀ + ½h²·a(x₀), and the recorded velocity is the second-order estimate
/// vₙ = (xₙ − xₙ₋₁)/h + ½h·a(xₙ). The force at xₙ₊₁ is kept for the next step, so each step costs
/// one evaluation. A step of another size than the last (an event cut a step short) uses the
/// variable-step form xₙ₊₁ = xₙ + (h/hₙ₋₁)(xₙ − xₙ₋₁) + ½h(h + hₙ₋₁)·a(xₙ), and after an event
/// changed the state the method starts afresh from the Taylor step. The forces must not read velocities (the macro knows from the body and the
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
    /// The step that led to the current state, once one was accepted: `previous` then holds
    /// xₙ₋₁.
    last_h: Option<f64>,
    /// The state before the current one (its position half is xₙ₋₁).
    previous: S,
    /// The start of the last attempt: it becomes `previous` when the attempt is accepted.
    current: S,
    /// a(xₙ) in the velocity half.
    accel: S,
    /// a(xₙ₊₁) of the last attempt.
    next: S,
    /// The size of the last attempt.
    h: f64,
}

impl<S> crate::integrators::sealed::Sealed for PositionVerlet<S> {}

impl<M: SecondOrder> Integrator<M> for PositionVerlet<M::State> {
    const METHOD: Method = Method::PositionVerlet;

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
        Ok(PositionVerlet {
            last_h: None,
            previous: y0.try_clone()?,
            current: y0.try_clone()?,
            next: accel.try_clone()?,
            accel,
            h: 0.0,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let h = s.h;
        self.current.clone_from(s.y);
        {
            let (_, a) = split(self.accel.as_slice());
            let (x0, v0) = split(s.y.as_slice());
            let (x, _) = split_mut(y_new.as_mut_slice());
            let (x_prev, _) = split(self.previous.as_slice());
            match self.last_h {
                // The constant-step recurrence, exactly as Störmer wrote it.
                Some(last) if last == h => {
                    for (((xi, x0i), pi), ai) in x.iter_mut().zip(x0).zip(x_prev).zip(a) {
                        *xi = 2.0 * x0i - pi + h * h * ai;
                    }
                }
                Some(last) => {
                    let ratio = h / last;
                    for (((xi, x0i), pi), ai) in x.iter_mut().zip(x0).zip(x_prev).zip(a) {
                        *xi = x0i + ratio * (x0i - pi) + 0.5 * h * (h + last) * ai;
                    }
                }
                None => {
                    for (((xi, x0i), v0i), ai) in x.iter_mut().zip(x0).zip(v0).zip(a) {
                        *xi = x0i + h * v0i + 0.5 * h * h * ai;
                    }
                }
            }
        }
        model.acceleration(s.t + h, y_new, &mut self.next);
        s.stats.evaluations += 1;
        let (_, a) = split(self.next.as_slice());
        let (x_old, _) = split(s.y.as_slice());
        let (x, v) = split_mut(y_new.as_mut_slice());
        for (((vi, xi), oi), ai) in v.iter_mut().zip(x.iter()).zip(x_old).zip(a) {
            *vi = (xi - oi) / h + 0.5 * h * ai;
        }
        self.h = h;
        Ok(0.0)
    }

    #[inline]
    fn accept(&mut self) {
        std::mem::swap(&mut self.previous, &mut self.current);
        std::mem::swap(&mut self.accel, &mut self.next);
        self.last_h = Some(self.h);
    }

    fn restart(&mut self, model: &M, t: f64, y: &M::State, stats: &mut Stats) {
        model.acceleration(t, y, &mut self.accel);
        stats.evaluations += 1;
        self.last_h = None;
    }
}
