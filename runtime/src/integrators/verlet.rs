//! The Verlet family's shared machinery: the force kept from the end of one step for the start
//! of the next, which [`Leapfrog`](super::Leapfrog) and [`VelocityVerlet`](super::VelocityVerlet)
//! both reuse, and the predictor state of forces that read velocities.

use std::fmt::Debug;
use std::marker::PhantomData;

use super::{Integrator, Step};
use crate::{Method, NewtonOptions, Result, SecondOrder, State, Stats};

/// One form of the Verlet step: how a step goes from (xₙ, vₙ) and aₙ to (xₙ₊₁, vₙ₊₁), with one
/// evaluation of aₙ₊₁.
pub trait VerletForm: Clone + Debug + super::Sealed {
    /// The method the form implements.
    const METHOD: Method;

    /// One step from `s.y` into `y_new`, given aₙ in the velocity half of `accel`; evaluates
    /// aₙ₊₁ into `next` (at `probe`, a first-order prediction of the new state, when the force
    /// reads velocities) and counts it in `s.stats`.
    fn step<M: SecondOrder>(
        model: &M,
        s: Step<'_, M::State>,
        accel: &M::State,
        next: &mut M::State,
        probe: &mut M::State,
        y_new: &mut M::State,
    );
}

/// A second-order, one-force-per-step member of the Verlet family in the form `F`: aₙ₊₁ of an
/// accepted step is the next step's aₙ, so each step costs one force evaluation after a start-up
/// one.
#[derive(Clone, Debug)]
pub struct Verlet<S, F> {
    /// aₙ in the velocity half.
    accel: S,
    /// aₙ₊₁ of the last attempt, in the velocity half.
    next: S,
    /// The state at which aₙ₊₁ is evaluated, when the force reads velocities.
    probe: S,
    form: PhantomData<F>,
}

impl<S, F: VerletForm> crate::integrators::sealed::Sealed for Verlet<S, F> {}

impl<M: SecondOrder, F: VerletForm> Integrator<M> for Verlet<M::State, F> {
    const METHOD: Method = F::METHOD;

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
        Ok(Verlet {
            next: accel.try_clone()?,
            probe: y0.try_clone()?,
            accel,
            form: PhantomData,
        })
    }

    #[inline]
    fn duplicate(&self) -> Option<Self> {
        Some(self.clone())
    }

    #[inline]
    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        F::step(
            model,
            s,
            &self.accel,
            &mut self.next,
            &mut self.probe,
            y_new,
        );
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
