//! Rosenbrock (linearly implicit) methods: what [`Rodas5P`](super::Rodas5P) and
//! [`Rosenbrock23`](super::Rosenbrock23) share around their stages — f(tₙ, yₙ) kept across the
//! retries of one state (or taken from the step before, when its last evaluation was
//! f(tₙ₊₁, yₙ₊₁)), J and ∂f/∂t evaluated once per state, W = I − γh·J factorized once per step
//! size, and all of it dropped when a step is accepted or an event changes the state.

use std::fmt::Debug;
use std::marker::PhantomData;

use super::linearization::Linearization;
use super::{DenseStep, Integrator, Step, copies};
use crate::{Controller, Jacobian, Method, NewtonOptions, Result, State, Stats};

/// The stages of one Rosenbrock method: its formulas, given W factorized and f(tₙ, yₙ).
pub trait RosenbrockTableau: Clone + Debug + super::Sealed {
    /// The method.
    const METHOD: Method;
    /// The step-size controller of adaptive runs.
    const CONTROLLER: Controller;
    /// Degree of the polynomial [`RosenbrockTableau::dense`] fills.
    const DENSE_DEGREE: usize;
    /// γ of W = I − γh·J.
    const GAMMA: f64;
    /// The work vector in which [`RosenbrockTableau::stages`] leaves f(tₙ₊₁, yₙ₊₁), if it
    /// evaluates it: the next step's f(tₙ, yₙ) (first same as last).
    const FSAL: Option<usize>;

    /// One step of size h from (t, y) = (`s.t`, `s.y`) into `y_new`, with W = I − γh·J
    /// factorized in `linear` (which also holds ∂f/∂t) and `f0` = f(t, y); `work` holds the
    /// method's stage vectors, kept for [`RosenbrockTableau::dense`]. Returns the error norm
    /// against `s.tolerances` (0 without them).
    ///
    /// Errors: [`crate::Error::SingularMatrix`] from a solve.
    fn stages<M: Jacobian>(
        model: &M,
        s: Step<'_, M::State>,
        linear: &mut Linearization<M>,
        f0: &M::State,
        work: &mut [M::State],
        y_new: &mut M::State,
    ) -> Result<f64>;

    /// Fills `dense` for the accepted step from (t, y) to (t + h, `y_new`) from its stages.
    fn dense<S: State>(s: Step<'_, S>, y_new: &S, work: &[S], dense: &mut DenseStep<S>);
}

/// A Rosenbrock method with the stages `T` and `K` work vectors.
///
/// One Jacobian, one ∂f/∂t (only when the model reads the time) and one factorization a step;
/// a rejected step keeps f(tₙ, yₙ), J and ∂f/∂t and only refactorizes W for its new h.
pub struct Rosenbrock<M: Jacobian, T, const K: usize> {
    linear: Linearization<M>,
    /// f(tₙ, yₙ), kept across retries of one state.
    f0: M::State,
    /// Whether `f0` holds f at the current state.
    have_f0: bool,
    /// Whether the last attempt was accepted and left f(tₙ₊₁, yₙ₊₁) in `work[T::FSAL]`.
    fsal: bool,
    work: [M::State; K],
    tableau: PhantomData<T>,
}

impl<M: Jacobian, T: RosenbrockTableau, const K: usize> crate::integrators::sealed::Sealed
    for Rosenbrock<M, T, K>
{
}

impl<M: Jacobian, T: RosenbrockTableau, const K: usize> Integrator<M> for Rosenbrock<M, T, K> {
    const METHOD: Method = T::METHOD;
    const CONTROLLER: Controller = T::CONTROLLER;
    const DENSE_DEGREE: usize = T::DENSE_DEGREE;

    fn linear_work(&self) -> crate::LinearWork {
        crate::NewtonMatrix::work(&self.linear.jacobian)
    }

    fn prepare(
        model: &M,
        _: f64,
        y0: &M::State,
        newton: &NewtonOptions,
        _: &mut Stats,
    ) -> Result<Self> {
        let mut linear = Linearization::new(model, y0)?;
        crate::NewtonMatrix::configure(&mut linear.jacobian, newton, crate::Solves::OneStep);
        Ok(Rosenbrock {
            linear,
            f0: y0.try_clone()?,
            have_f0: false,
            fsal: false,
            work: copies(y0)?,
            tableau: PhantomData,
        })
    }

    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let (t, h, y) = (s.t, s.h, s.y);
        if self.fsal {
            if let Some(last) = T::FSAL {
                std::mem::swap(&mut self.f0, &mut self.work[last]);
            }
            self.fsal = false;
            self.have_f0 = true;
        } else if !self.have_f0 {
            model.derivative(t, y, &mut self.f0);
            s.stats.evaluations += 1;
            self.have_f0 = true;
        }
        self.linear.evaluate(model, t, y, s.stats)?;
        self.linear.factorize(T::GAMMA * h, t, h, s.stats)?;
        T::stages(model, s, &mut self.linear, &self.f0, &mut self.work, y_new)
    }

    fn accept(&mut self) {
        if T::FSAL.is_some() {
            self.fsal = true;
        } else {
            self.have_f0 = false;
        }
        self.linear.invalidate();
    }

    fn restart(&mut self, _: &M, _: f64, _: &M::State, _: &mut Stats) {
        self.fsal = false;
        self.have_f0 = false;
        self.linear.invalidate();
    }

    fn dense(
        &mut self,
        _: &M,
        s: Step<'_, M::State>,
        y_new: &M::State,
        dense: &mut DenseStep<M::State>,
    ) -> bool {
        T::dense(s, y_new, &self.work, dense);
        true
    }
}
