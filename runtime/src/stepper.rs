//! [`Stepper`]: a model, an integrator and a state, advanced one checked step at a time.

use crate::integrators::Evaluations;
use crate::{Error, Integrator, Model, NewtonOptions, Result, State};

/// The default bound on |state component| beyond which a run counts as diverged.
pub(crate) const DEFAULT_DIVERGENCE_LIMIT: f64 = 1e100;

/// Advances one state with a fixed method and a fixed dt, refusing non-finite results.
///
/// The runner ([`crate::Simulation`]) and the real-time loop ([`crate::FixedTimestep`]) both step
/// through it. Time is computed as t₀ + n·dt, never accumulated, so two steppers that have taken
/// the same number of steps are at bit-identical times.
#[derive(Clone, Debug)]
pub struct Stepper<'m, M: Model, I> {
    model: &'m M,
    integrator: I,
    state: M::State,
    t0: f64,
    dt: f64,
    steps: u64,
    divergence_limit: f64,
}

impl<'m, M: Model, I: Integrator<M>> Stepper<'m, M, I> {
    /// Starts stepping `state` from `t0` with step `dt`.
    ///
    /// Errors with [`Error::InvalidInput`] when dt is not finite and positive, t0 is not finite,
    /// or the state has a non-finite component, and with [`Error::BadModel`] when the model's
    /// own check fails (a particle model's topology or masses, see [`crate::Model::check`]).
    pub fn new(model: &'m M, state: M::State, t0: f64, dt: f64) -> Result<Self> {
        Self::with_newton(model, state, t0, dt, &NewtonOptions::default())
    }

    /// [`Stepper::new`] with the Newton options of implicit methods.
    pub fn with_newton(
        model: &'m M,
        state: M::State,
        t0: f64,
        dt: f64,
        newton: &NewtonOptions,
    ) -> Result<Self> {
        check_dt(dt)?;
        if !t0.is_finite() {
            return Err(Error::invalid(
                "t0",
                format!("start time must be finite, got {t0}"),
            ));
        }
        if let Some((index, value)) = first_outside(&state, f64::MAX) {
            return Err(Error::invalid(
                format!("initial state `{}`", state.component_name(index)),
                format!("must be finite, got {value}"),
            ));
        }
        model.check(&state)?;
        let integrator = I::start(model, t0, dt, &state, newton)?;
        Ok(Stepper {
            model,
            integrator,
            state,
            t0,
            dt,
            steps: 0,
            divergence_limit: DEFAULT_DIVERGENCE_LIMIT,
        })
    }

    /// Sets the bound on |component| beyond which a step counts as diverged (default 1e100;
    /// `f64::INFINITY` catches only infinities and NaN).
    pub fn with_divergence_limit(mut self, limit: f64) -> Self {
        self.divergence_limit = limit;
        self
    }

    /// The integrator, with whatever it counts (an implicit method's factorizations).
    pub fn integrator(&self) -> &I {
        &self.integrator
    }

    /// Takes one step.
    ///
    /// Errors with [`Error::Diverged`] when a component of the new state is non-finite or beyond
    /// the divergence limit, and with [`Error::NewtonDidNotConverge`] when an implicit step
    /// fails; the state is then the rejected one, and stepping further is pointless.
    #[inline]
    pub fn step(&mut self) -> Result<()> {
        let t = self.t();
        let stepped = self.integrator.step(self.model, t, &mut self.state);
        self.steps += 1;
        stepped?;
        match first_outside(&self.state, self.divergence_limit) {
            None => Ok(()),
            Some((index, value)) => Err(Error::Diverged {
                method: I::METHOD,
                step: self.steps,
                t: self.t(),
                component: self.state.component_name(index),
                value,
                limit: self.divergence_limit,
            }),
        }
    }

    /// The current state.
    pub fn state(&self) -> &M::State {
        &self.state
    }

    /// The current time, t₀ + steps·dt.
    pub fn t(&self) -> f64 {
        self.t0 + self.steps as f64 * self.dt
    }

    /// The fixed step.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Steps taken so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Force and Jacobian evaluations made so far.
    pub fn evaluations(&self) -> Evaluations {
        self.integrator.evaluations(self.steps)
    }

    /// The model being stepped.
    pub fn model(&self) -> &'m M {
        self.model
    }
}

pub(crate) fn check_dt(dt: f64) -> Result<()> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            "dt",
            format!("must be finite and positive, got {dt}"),
        ))
    }
}

/// The first component that is NaN or whose magnitude exceeds `limit`.
#[inline]
fn first_outside<S: State>(state: &S, limit: f64) -> Option<(usize, f64)> {
    let s = state.as_slice();
    // One branch-free pass for the common case; locate the culprit only on failure.
    let ok = s.iter().fold(true, |ok, x| ok & (x.abs() <= limit));
    if ok {
        None
    } else {
        s.iter()
            .position(|x| x.is_nan() || x.abs() > limit)
            .map(|i| (i, s[i]))
    }
}
