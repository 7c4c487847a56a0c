//! [`Simulation`]: configure a run, pick the integrator at run time, record a [`Trajectory`].
//!
//! The builder is here; its options and their check are in `options`, the validated run and
//! its dispatch in `plan`.

mod options;
mod plan;
mod typed;

pub use options::{Length, RunOptions};
pub use typed::MethodType;

use crate::drive::{AdaptiveOptions, Progress};
use crate::{Error, Event, Method, Model, NewtonOptions, Result, Stepping, Tolerances, Trajectory};

/// A progress callback (see [`Simulation::progress`]).
#[derive(Clone, Copy)]
struct ProgressFn<'m>(&'m dyn Fn(&Progress));

impl std::fmt::Debug for ProgressFn<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress(..)")
    }
}

/// `model.simulate()`: starts configuring a run of any [`Model`] from its own state, method and
/// dt. Every model has it; the trait is in `odyn::prelude` (and at the crate root) so the call
/// needs it in scope. It lives beside [`Simulation`] rather than on [`Model`] so that the model
/// traits do not depend on the runner.
pub trait Simulate: Model + Sized {
    /// Starts configuring a run from the model's own state, method and dt.
    fn simulate(&self) -> Simulation<'_, Self> {
        Simulation::new(self)
    }
}

impl<M: Model> Simulate for M {}

/// A run being configured: created by [`Simulate::simulate`], finished by [`Simulation::run`].
///
/// Each setter is named for the option it sets. Where an option has a short form of plain
/// numbers beside its full type, the short form has the plain name and the full one `with_`:
/// [`Simulation::tolerances`]`(rtol, atol)` and [`Simulation::with_tolerances`]`(Tolerances)`
/// (per-component tolerances); [`Simulation::with_options`] replaces every option at once.
#[derive(Clone, Debug)]
pub struct Simulation<'m, M: Model> {
    model: &'m M,
    initial: Option<M::State>,
    progress: Option<ProgressFn<'m>>,
    events: Vec<Event<'m, M::State>>,
    /// Whether `options.stepping` is the attribute's `dt`, which a switch to an adaptive method
    /// drops in favour of tolerances.
    attribute_dt: bool,
    /// The options the setters below assign ([`Simulation::options`] reads them,
    /// [`Simulation::with_options`] replaces them whole).
    options: RunOptions,
}

impl<'m, M: Model> Simulation<'m, M> {
    /// A run of `model` from its own state, with its attribute's method and dt or tolerances.
    pub fn new(model: &'m M) -> Self {
        let tolerances = match (M::DEFAULT_RTOL, M::DEFAULT_ATOL) {
            (None, None) => None,
            (rtol, atol) => {
                let default = Tolerances::default();
                Some(Tolerances::new(
                    rtol.unwrap_or(default.rtol),
                    atol.unwrap_or(1e-9),
                ))
            }
        };
        let (stepping, attribute_dt) = match (tolerances, M::DEFAULT_DT) {
            (Some(t), _) => (Some(Stepping::Adaptive(t)), false),
            (None, Some(dt)) => (Some(Stepping::Fixed(dt)), true),
            (None, None) => (None, false),
        };
        let options = RunOptions {
            integrator: M::DEFAULT_METHOD,
            stepping,
            ..RunOptions::default()
        };
        Simulation {
            model,
            initial: None,
            progress: None,
            events: Vec::new(),
            attribute_dt,
            options,
        }
    }

    /// Uses `method` instead of the attribute's. Choosing an adaptive method drops a `dt` that
    /// came from the attribute (the run then uses tolerances); an explicit `.dt(..)` stays.
    pub fn integrator(mut self, method: Method) -> Self {
        self.options.integrator = method;
        if method.is_adaptive() && self.attribute_dt {
            self.options.stepping = None;
            self.attribute_dt = false;
        }
        self
    }

    /// The run's options as the builder has set them so far.
    pub fn options(&self) -> &RunOptions {
        &self.options
    }

    /// Replaces every option at once (a `RunOptions` kept from another run, or built as a
    /// plain struct). Its `stepping` is taken as given: a switch to an adaptive method no
    /// longer drops it.
    pub fn with_options(mut self, options: RunOptions) -> Self {
        self.options = options;
        self.attribute_dt = false;
        self
    }

    /// Locates events to within `tolerance` seconds (default 1e-12, or the resolution of t if
    /// coarser; see [`RunOptions::event_tolerance`]).
    pub fn event_tolerance(mut self, tolerance: f64) -> Self {
        self.options.event_tolerance = tolerance;
        self
    }

    /// Ends the run with [`Error::EventsAccumulate`] past `count` events (default 100 000; see
    /// [`RunOptions::max_events`]).
    pub fn max_events(mut self, count: u64) -> Self {
        self.options.max_events = count;
        self
    }

    /// Uses the fixed step `dt` (with any method, adaptive ones included).
    pub fn dt(mut self, dt: f64) -> Self {
        self.options.stepping = Some(Stepping::Fixed(dt));
        self.attribute_dt = false;
        self
    }

    /// Steps adaptively to relative tolerance `rtol` and absolute tolerance `atol`.
    pub fn tolerances(self, rtol: f64, atol: f64) -> Self {
        self.with_tolerances(Tolerances::new(rtol, atol))
    }

    /// Steps adaptively to `tolerances` (per-component absolute tolerances, for instance).
    pub fn with_tolerances(mut self, tolerances: Tolerances) -> Self {
        self.options.stepping = Some(Stepping::Adaptive(tolerances));
        self.attribute_dt = false;
        self
    }

    /// Uses `control` for the first step, step bounds, budget and controller of adaptive runs.
    pub fn adaptive(mut self, control: AdaptiveOptions) -> Self {
        self.options.adaptive = control;
        self
    }

    /// Runs exactly `steps` steps.
    pub fn steps(mut self, steps: u64) -> Self {
        self.options.length = Some(Length::Steps(steps));
        self
    }

    /// Runs for `duration` simulated seconds (see [`Length::Duration`]).
    pub fn duration(mut self, duration: f64) -> Self {
        self.options.length = Some(Length::Duration(duration));
        self
    }

    /// Records every `n`-th step (and keeps no dense output unless
    /// [`Simulation::dense_output`] asks).
    pub fn record_every(mut self, n: u64) -> Self {
        self.options.record_every = n;
        self
    }

    /// Records the state only at `times` (and at the start and end), through each step's dense
    /// output; keeps no dense output for [`Trajectory::at`] unless [`Simulation::dense_output`]
    /// asks.
    pub fn save_at(mut self, times: &[f64]) -> Self {
        self.options.save_at = Some(times.to_vec());
        self
    }

    /// Keeps (or drops) every step's dense output, for [`Trajectory::at`].
    pub fn dense_output(mut self, keep: bool) -> Self {
        self.options.dense_output = Some(keep);
        self
    }

    /// Adds an event (see [`Event`]).
    pub fn event(mut self, event: Event<'m, M::State>) -> Self {
        self.events.push(event);
        self
    }

    /// Starts at time `t0`.
    pub fn start_time(mut self, t0: f64) -> Self {
        self.options.t0 = t0;
        self
    }

    /// Starts from `state` instead of the model's own fields.
    pub fn initial_state(mut self, state: M::State) -> Self {
        self.initial = Some(state);
        self
    }

    /// Sets the divergence limit (see [`RunOptions::divergence_limit`]).
    pub fn divergence_limit(mut self, limit: f64) -> Self {
        self.options.divergence_limit = Some(limit);
        self
    }

    /// Calls `report` at every recorded sample and at the end: for a progress bar on long runs
    /// ([`Progress::fraction`]). The run's numbers do not depend on it.
    pub fn progress(mut self, report: &'m dyn Fn(&Progress)) -> Self {
        self.progress = Some(ProgressFn(report));
        self
    }

    /// Uses `newton` for the nonlinear solves of implicit methods.
    pub fn newton(mut self, newton: NewtonOptions) -> Self {
        self.options.newton = newton;
        self
    }

    /// Runs and returns the trajectory.
    ///
    /// Errors: [`Error::InvalidInput`] for bad options, a non-finite initial state, or a state
    /// too large for the run's copies of it to be allocated ([`crate::State::try_clone`]: a
    /// grid that fits in memory once, not a dozen times), [`Error::Unsupported`] when the method
    /// cannot integrate this model, [`Error::Diverged`]
    /// when the state blows up, [`Error::StepSizeTooSmall`] and [`Error::MaxSteps`] when an
    /// adaptive run cannot go on (use [`Simulation::run_partial`] to keep the samples recorded
    /// before any of these).
    pub fn run(&self) -> Result<Trajectory<M::State>> {
        let (trajectory, failure) = self.run_partial()?;
        match failure {
            None => Ok(trajectory),
            Some(error) => Err(error),
        }
    }

    /// Runs and returns the trajectory up to the last good step, with the failure that stopped
    /// it, if any. Input and capability errors are still `Err`: nothing ran.
    pub fn run_partial(&self) -> Result<(Trajectory<M::State>, Option<Error>)> {
        crate::stack::with_room::<M::State, _>(|| self.run_here())
    }

    /// Runs with the method `T` and returns the trajectory: what `.integrator(T::METHOD).run()`
    /// does, but a program that runs the model only this way compiles only `T`'s loop for it
    /// (see [`MethodType`]). `T` replaces the options' method for this run; an adaptive `T` that
    /// is not the attribute's own steps to tolerances rather than the attribute's `dt`, as with
    /// [`Simulation::integrator`].
    ///
    /// `Decay { y: 1.0 }.simulate().duration(1.0).run_with::<method::Tsit5>()` runs Tsit5 alone
    /// (an example runs in the guide's chapter on choosing a method).
    ///
    /// Errors: as [`Simulation::run`].
    pub fn run_with<T: MethodType>(&self) -> Result<Trajectory<M::State>> {
        let (trajectory, failure) = self.run_partial_with::<T>()?;
        match failure {
            None => Ok(trajectory),
            Some(error) => Err(error),
        }
    }

    /// [`Simulation::run_partial`] with the method `T`, compiled alone (see
    /// [`Simulation::run_with`]).
    pub fn run_partial_with<T: MethodType>(&self) -> Result<(Trajectory<M::State>, Option<Error>)> {
        crate::stack::with_room::<M::State, _>(|| T::run(self))
    }

    /// How a run with `method` steps: the options' stepping, less the attribute's `dt` when the
    /// method is adaptive and was not the options' own (as [`Simulation::integrator`] drops it).
    fn stepping_for(&self, method: Method) -> Option<&Stepping> {
        if method != self.options.integrator && method.is_adaptive() && self.attribute_dt {
            None
        } else {
            self.options.stepping.as_ref()
        }
    }
}
