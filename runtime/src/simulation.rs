//! [`Simulation`]: configure a run, pick the integrator at run time, record a [`Trajectory`].

use crate::checks::{check_dt, divergence_limit};
use crate::drive::{Driver, Progress, Recording, StepControl};
use crate::integrators::Integrator;
use crate::{
    Error, Event, Method, Model, NewtonOptions, Result, SecondOrder, State, Stepping, Tolerances,
    Trajectory,
};

/// The run's dispatch from the one table of methods: each [`Method`] drives its integrator
/// type (same name, in [`crate::integrators`]) on the model, its second-order split or its
/// Jacobian, as the row's `needs` says. Exhaustive by construction.
macro_rules! dispatch {
    (
        [$run:ident $plan:ident $method:ident]
        $(
            $(#[$doc:meta])* $variant:ident $module:ident $name:literal $label:literal
            $order:literal $adaptive:literal $needs:ident $stability:ident;
        )*
    ) => {
        match $method {
            $(Method::$variant => dispatch!(@drive $needs $run $plan $variant),)*
        }
    };
    (@drive Nothing $run:ident $plan:ident $variant:ident) => {
        $plan.drive::<M, crate::integrators::$variant<_>>($run.model)
    };
    (@drive Split $run:ident $plan:ident $variant:ident) => {
        $plan.drive::<_, crate::integrators::$variant<_>>($run.split()?)
    };
    (@drive VelocityFree $run:ident $plan:ident $variant:ident) => {
        $plan.drive::<_, crate::integrators::$variant<_>>($run.split()?)
    };
    (@drive Jacobian $run:ident $plan:ident $variant:ident) => {
        $plan.drive::<_, crate::integrators::$variant<_>>($run.jacobian()?)
    };
}

/// How long a run lasts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// Exactly this many steps (fixed-step runs only).
    Steps(u64),
    /// Simulated seconds. An adaptive run ends exactly at t₀ + duration; a fixed-step run takes
    /// ⌈duration/dt⌉ steps (a ratio within 1e-9 of a whole number counts as that number), so it
    /// ends at or just past it.
    Duration(f64),
}

/// Everything a run needs besides the model, its initial state and its events.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOptions {
    /// The integrator. Default: the model's `#[system(integrator = ...)]`, else [`Method::Rk4`].
    pub method: Method,
    /// Fixed dt or tolerances. Default: the attribute's `rtol`/`atol`, else its `dt`; with
    /// neither, adaptive methods use the default [`Tolerances`] and fixed-step methods need a
    /// `.dt(..)`.
    pub stepping: Option<Stepping>,
    /// How long to run. Default: none; a run without one is an error.
    pub length: Option<Length>,
    /// Start time (default 0).
    pub t0: f64,
    /// Record every n-th step (default 1: every grid step, or every accepted step of an adaptive
    /// run); the initial and final states are always recorded.
    pub record_every: u64,
    /// Record only at these times (strictly increasing), evaluated on the dense output, besides
    /// the initial and final states; times outside the run are skipped. Default: none.
    pub save_at: Option<Vec<f64>>,
    /// Keep every step's dense-output polynomial so [`Trajectory::at`] works anywhere. Default:
    /// on for adaptive runs, off for fixed-step ones (where it costs one more evaluation of f a
    /// step for the Hermite interpolant).
    pub dense_output: Option<bool>,
    /// |component| beyond which a step counts as diverged. Default: 10¹⁰ × max(1, largest
    /// |component| of the initial state) — far beyond anything an accurate run of a bounded model
    /// reaches, and where an exploded explicit run of a stiff model is caught before its values
    /// overflow. A non-finite state always stops the run, whatever the limit (`f64::INFINITY`
    /// catches only infinities and NaN).
    pub divergence_limit: Option<f64>,
    /// Newton's method in implicit steps (see [`NewtonOptions`] for the defaults).
    pub newton: NewtonOptions,
    /// First step, step bounds, step budget and controller of adaptive runs.
    pub step_control: StepControl,
    /// Events are located to within this time (default 1e-12, or the resolution of t if
    /// coarser). Crossings within it of each other are one instant (see [`Event`]).
    pub event_tolerance: f64,
    /// The most events one run records (default 100 000): past it the run ends with
    /// [`Error::EventsAccumulate`] rather than fill memory with an event that fires without end.
    pub max_events: u64,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            method: Method::Rk4,
            stepping: None,
            length: None,
            t0: 0.0,
            record_every: 1,
            save_at: None,
            dense_output: None,
            divergence_limit: None,
            newton: NewtonOptions::default(),
            step_control: StepControl::default(),
            event_tolerance: 1e-12,
            max_events: 100_000,
        }
    }
}

/// A progress callback (see [`Simulation::progress`]).
#[derive(Clone, Copy)]
struct ProgressFn<'m>(&'m dyn Fn(&Progress));

impl std::fmt::Debug for ProgressFn<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress(..)")
    }
}

/// A run being configured: created by [`Model::simulate`], finished by [`Simulation::run`].
#[derive(Clone, Debug)]
pub struct Simulation<'m, M: Model> {
    model: &'m M,
    initial: Option<M::State>,
    progress: Option<ProgressFn<'m>>,
    events: Vec<Event<'m, M::State>>,
    /// Whether `options.stepping` is the attribute's `dt`, which a switch to an adaptive method
    /// drops in favour of tolerances.
    attribute_dt: bool,
    /// The options; the setters below are shorthands for assigning these fields.
    pub options: RunOptions,
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
            method: M::DEFAULT_METHOD,
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
        self.options.method = method;
        if method.is_adaptive() && self.attribute_dt {
            self.options.stepping = None;
            self.attribute_dt = false;
        }
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
    pub fn step_control(mut self, control: StepControl) -> Self {
        self.options.step_control = control;
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

    /// Records every `n`-th step.
    pub fn record_every(mut self, n: u64) -> Self {
        self.options.record_every = n;
        self
    }

    /// Records the state only at `times` (and at the start and end), through the dense output.
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

    /// [`Simulation::run_partial`] on the current stack.
    fn run_here(&self) -> Result<(Trajectory<M::State>, Option<Error>)> {
        let plan = self.plan()?;
        let method = self.options.method;
        let run = self;
        odyn_methods::for_each_method!(dispatch, run, plan, method)
    }

    /// The model as a second-order one, checked against what the method needs.
    fn split(&self) -> Result<&'m M::SecondOrder> {
        let Some(split) = self.model.as_second_order() else {
            return Err(self.unsupported(
                "it is first-order (`#[state]` fields) and the method needs \
                 `#[position]`/`#[velocity]` fields",
            ));
        };
        if self.options.method.needs_velocity_free_forces() && M::SecondOrder::READS_VELOCITY {
            return Err(self.unsupported(
                "its force reads a velocity (in `acceleration`, or a kernel's velocity arguments), \
                 and the method evaluates forces at positions only (position Verlet, the leapfrog \
                 compositions); use velocity Verlet or leapfrog",
            ));
        }
        Ok(split)
    }

    /// The model with its Jacobian.
    fn jacobian(&self) -> Result<&'m M::Jacobian> {
        self.model.as_jacobian().ok_or_else(|| {
            self.unsupported("it has no Jacobian (its `#[system]` says `jacobian = false`)")
        })
    }

    fn unsupported(&self, reason: &'static str) -> Error {
        Error::Unsupported {
            method: self.options.method,
            model: M::NAME,
            reason,
        }
    }

    fn plan(&self) -> Result<Plan<'_, 'm, M>> {
        let o = &self.options;
        let method = o.method;
        let initial = match &self.initial {
            Some(initial) => initial.try_clone()?,
            None => self.model.state(),
        };
        let stepping = match (&o.stepping, method.is_adaptive()) {
            (Some(Stepping::Fixed(dt)), _) => {
                check_dt(*dt)?;
                Stepping::Fixed(*dt)
            }
            (Some(Stepping::Adaptive(tolerances)), true) => {
                tolerances.check(initial.as_slice().len())?;
                Stepping::Adaptive(tolerances.clone())
            }
            (Some(Stepping::Adaptive(_)), false) => {
                return Err(self.unsupported(
                    "it has no error estimate, so it cannot step to tolerances; give it a \
                     `.dt(..)`, or choose an adaptive method (Tsit5, Dop853)",
                ));
            }
            (None, true) => Stepping::Adaptive(Tolerances::default()),
            (None, false) => {
                return Err(Error::invalid(
                    "dt",
                    "no step given: call `.dt(..)` or set `#[system(dt = ..)]`",
                ));
            }
        };
        let length = o.length.ok_or_else(|| {
            Error::invalid(
                "length",
                "no run length given: call `.steps(..)` or `.duration(..)`",
            )
        })?;
        if !o.t0.is_finite() {
            return Err(Error::invalid(
                "t0",
                format!("start time must be finite, got {:?}", o.t0),
            ));
        }
        let dense = o
            .dense_output
            .unwrap_or(matches!(stepping, Stepping::Adaptive(_)));
        let span = match (stepping, length) {
            (Stepping::Fixed(dt), Length::Steps(steps)) => Span::Fixed { dt, steps },
            (Stepping::Fixed(dt), Length::Duration(d)) => Span::Fixed {
                dt,
                steps: steps_for(d, dt)?,
            },
            (Stepping::Adaptive(tolerances), Length::Duration(d)) => {
                let t_end = o.t0 + checked_duration(d)?;
                if d > 0.0 && t_end == o.t0 {
                    return Err(Error::invalid(
                        "duration",
                        format!(
                            "{d:e} is below the resolution of t at the start time {:e}: the \
                             run would not move; use a start time nearer 0",
                            o.t0
                        ),
                    ));
                }
                Span::Adaptive { tolerances, t_end }
            }
            (Stepping::Adaptive(_), Length::Steps(_)) => {
                return Err(Error::invalid(
                    "length",
                    "an adaptive run chooses its own steps: give it a `.duration(..)`, or a \
                     `.dt(..)` to run a fixed number of fixed steps",
                ));
            }
        };
        if o.record_every == 0 {
            return Err(Error::invalid("record_every", "must be at least 1"));
        }
        if let Some(times) = &o.save_at {
            if let Some(t) = times.iter().find(|t| !t.is_finite()) {
                return Err(Error::invalid(
                    "save_at",
                    format!("times must be finite, got {t:?}"),
                ));
            }
            if times.windows(2).any(|w| w[1] <= w[0]) {
                return Err(Error::invalid(
                    "save_at",
                    "times must be strictly increasing",
                ));
            }
        }
        let limit = divergence_limit(o.divergence_limit, &initial)?;
        if !(o.event_tolerance.is_finite() && o.event_tolerance >= 0.0) {
            return Err(Error::invalid(
                "event_tolerance",
                format!(
                    "must be finite and non-negative, got {:?}",
                    o.event_tolerance
                ),
            ));
        }
        o.step_control.check()?;
        o.newton.check()?;
        Ok(Plan {
            initial,
            span,
            simulation: self,
            limit,
            dense,
        })
    }
}

/// How a validated run steps and where it ends.
#[derive(Clone, Debug)]
enum Span {
    /// `steps` steps of `dt`.
    Fixed { dt: f64, steps: u64 },
    /// To `t_end`, each step within `tolerances`.
    Adaptive { tolerances: Tolerances, t_end: f64 },
}

fn checked_duration(duration: f64) -> Result<f64> {
    if duration.is_finite() && duration >= 0.0 {
        Ok(duration)
    } else {
        Err(Error::invalid(
            "duration",
            format!("must be finite and non-negative, got {duration:?}"),
        ))
    }
}

fn steps_for(duration: f64, dt: f64) -> Result<u64> {
    let duration = checked_duration(duration)?;
    let ratio = duration / dt;
    let nearest = ratio.round();
    let steps = if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) {
        nearest
    } else {
        ratio.ceil()
    };
    if steps > 1e15 {
        return Err(Error::invalid(
            "duration",
            format!(
                "{duration:?} s at dt = {dt:e} is {steps:e} steps, more than this runner takes"
            ),
        ));
    }
    Ok(steps as u64)
}

/// A validated run.
struct Plan<'s, 'm, M: Model> {
    initial: M::State,
    span: Span,
    simulation: &'s Simulation<'m, M>,
    limit: f64,
    dense: bool,
}

impl<M: Model> Plan<'_, '_, M> {
    // One function per integrator: inlined into `run_partial`'s dispatch, the run loops shared
    // one body and the cheap ones ran up to 1.7× slower (measured on leapfrog).
    #[inline(never)]
    fn drive<N, I>(self, model: &N) -> Result<(Trajectory<M::State>, Option<Error>)>
    where
        N: Model<State = M::State>,
        I: Integrator<N>,
    {
        let o = &self.simulation.options;
        let recording = Recording {
            every: o.record_every,
            save_at: o.save_at.as_deref(),
            dense: self.dense,
            progress: self.simulation.progress.map(|p| p.0),
        };
        let mut driver = Driver::<N, I>::new(
            model,
            o.t0,
            self.initial,
            &o.newton,
            self.limit,
            self.simulation.events.clone(),
            (o.event_tolerance, o.max_events),
            recording,
        )?;
        let outcome = match &self.span {
            Span::Fixed { dt, steps } => driver.run_fixed(*dt, 0, *steps),
            Span::Adaptive { tolerances, t_end } => driver.run_adaptive(
                *t_end,
                tolerances,
                &o.step_control,
                I::CONTROLLER,
                I::START_ORDER,
            ),
        };
        let outcome = outcome.map_err(|error| driver.explain(error));
        let stats = driver.stats;
        let record = driver.record;
        let trajectory = Trajectory {
            model: N::NAME,
            method: I::METHOD,
            stepping: match self.span {
                Span::Fixed { dt, .. } => Stepping::Fixed(dt),
                Span::Adaptive { tolerances, .. } => Stepping::Adaptive(tolerances),
            },
            stats,
            samples: record.samples,
            events: record.events,
            dense: record.dense,
        };
        Ok((trajectory, outcome.err()))
    }
}
