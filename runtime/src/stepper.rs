//! [`Stepper`]: a model, an integrator and a state, advanced one checked step at a time.

use crate::checks::check_dt;
use crate::drive::{Driver, Recording, Start, Track};
use crate::{Error, Integrator, Model, NewtonOptions, Result, State, Stats};

/// Advances one state with a fixed method and a fixed dt, refusing non-finite results.
///
/// The real-time loop ([`crate::FixedTimestep`]) steps through it, and so can code that drives a
/// model by hand. It runs the same driver as [`crate::Simulation`] — the same checks at the start
/// (including [`Model::check`]), the same step halving for implicit methods, the same divergence
/// test — without recording. Time is computed as t₀ + n·dt, never accumulated, so two steppers
/// that have taken the same number of steps are at bit-identical times.
pub struct Stepper<'m, M: Model, I: Integrator<M>> {
    // Boxed: the driver holds the integrator's scratch states, dozens for big models.
    driver: Box<Driver<'static, 'm, M, I>>,
    dt: f64,
    steps: u64,
    /// Components of the state stepped: a run's buffers are sized to it, once.
    components: usize,
    /// Whether [`Stepper::state_mut`] lent the state out since it was last checked.
    lent: bool,
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
    ///
    /// Errors: as [`Stepper::new`], and [`Error::InvalidInput`] for Newton options out of their
    /// ranges (see [`NewtonOptions::check`]).
    pub fn with_newton(
        model: &'m M,
        state: M::State,
        t0: f64,
        dt: f64,
        newton: &NewtonOptions,
    ) -> Result<Self> {
        Self::with_limit(model, state, t0, dt, newton, None)
    }

    /// [`Stepper::with_newton`] with a divergence limit: the bound on |component| beyond which a
    /// step counts as diverged (default: see [`crate::RunOptions::divergence_limit`];
    /// `f64::INFINITY` catches only infinities and NaN).
    ///
    /// Errors: as [`Stepper::with_newton`], and [`Error::InvalidInput`] for a limit that is not
    /// positive (NaN included).
    pub fn with_limit(
        model: &'m M,
        state: M::State,
        t0: f64,
        dt: f64,
        newton: &NewtonOptions,
        divergence_limit: Option<f64>,
    ) -> Result<Self> {
        check_dt(dt)?;
        let limit = crate::checks::divergence_limit(divergence_limit, state.as_slice())?;
        crate::checks::check_t0(t0)?;
        let quiet = Recording {
            every: 0,
            save_at: None,
            dense: false,
            progress: None,
        };
        // The closure captures the state boxed: a megabyte state captured by value is copied
        // into each frame on the way to the bigger stack.
        let components = state.as_slice().len();
        let state = Box::new(state);
        let start = Start {
            t0,
            newton,
            limit,
            event_options: (0.0, 0),
            dense_degree: I::DENSE_DEGREE,
            method: I::METHOD,
        };
        let driver = crate::stack::with_room::<M::State, _>(move || {
            let track = Track::new(model, *state, start, Vec::new(), quiet)?;
            Driver::on(track, newton).map(Box::new)
        })?;
        Ok(Stepper {
            driver,
            dt,
            steps: 0,
            components,
            lent: false,
        })
    }

    /// The integrator, with whatever it counts (an implicit method's factorizations).
    pub fn integrator(&self) -> &I {
        self.driver.integrator()
    }

    /// Takes one step.
    ///
    /// Errors with [`Error::Diverged`] when a component of the new state is non-finite or beyond
    /// the divergence limit, and with [`Error::NewtonDidNotConverge`] when an implicit step
    /// fails even after halving; the state is then the last good one. A state set through
    /// [`Stepper::state_mut`] that no longer fits the run is refused without a step (see there).
    #[inline]
    pub fn step(&mut self) -> Result<()> {
        if self.lent {
            self.check_lent()?;
        }
        let (dt, steps) = (self.dt, self.steps);
        let stepped =
            crate::stack::with_room::<M::State, _>(|| self.driver.run_fixed(dt, steps, 1));
        if stepped.is_ok() {
            self.steps += 1;
        }
        stepped
    }

    /// The current state.
    pub fn state(&self) -> &M::State {
        self.driver.state()
    }

    /// The current state, to change between steps (an impulse, a user's drag): the method
    /// restarts from the changed state at the next step, as after an event.
    ///
    /// The state keeps its size: the run's buffers were made for it. The next
    /// [`Stepper::step`] checks a state changed here and refuses, without stepping, one of
    /// another number of components ([`Error::InvalidInput`] naming both sizes: a particle
    /// state of other particles, a grid state of another grid) or one the model's own check
    /// rejects ([`Error::BadModel`]: a grid state of as many cells in another shape); the
    /// state stays as set until it is set right. Change values in place, or start a new
    /// `Stepper` for a state of another size.
    pub fn state_mut(&mut self) -> &mut M::State {
        self.lent = true;
        self.driver.state_mut()
    }

    /// The current time, t₀ + steps·dt.
    pub fn t(&self) -> f64 {
        self.driver.t()
    }

    /// The fixed step.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Steps taken so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// What the steps so far cost.
    pub fn stats(&self) -> Stats {
        Stats {
            linear: self.driver.integrator().linear_work(),
            ..self.driver.track.stats
        }
    }

    /// The model being stepped.
    pub fn model(&self) -> &'m M {
        self.driver.model()
    }

    /// Checks a state lent out by [`Stepper::state_mut`] before it is stepped: one length
    /// comparison, then [`Model::check`] (a particle model's topology against it, a grid's shape).
    #[cold]
    fn check_lent(&mut self) -> Result<()> {
        let state = self.driver.state();
        let found = state.as_slice().len();
        if found != self.components {
            return Err(Error::invalid(
                "state",
                format!(
                    "was replaced through `Stepper::state_mut` by one of {found} components, but \
                     this stepper's has {}: a state keeps its size for a run; change its values \
                     in place, or start a new `Stepper` for a state of another size",
                    self.components
                ),
            ));
        }
        self.driver.model().check(state)?;
        self.lent = false;
        Ok(())
    }
}

impl<M: Model, I: Integrator<M>> std::fmt::Debug for Stepper<'_, M, I> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Stepper")
            .field("model", &M::NAME)
            .field("method", &I::METHOD)
            .field("t", &self.t())
            .field("dt", &self.dt)
            .field("steps", &self.steps)
            .finish_non_exhaustive()
    }
}
