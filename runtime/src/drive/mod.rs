//! The drivers: everything about a run that is not the method's own formula, written once.
//!
//! A method ([`crate::Integrator`]) attempts steps; a `Driver` decides which steps to attempt
//! and what to do with them:
//!
//! - the **fixed-step** loop walks the grid t₀ + n·dt, retrying a step whose implicit solve failed
//!   as two half steps (up to [`crate::NewtonOptions::max_halvings`] deep);
//! - the **adaptive** loop sizes each step with the [`Controller`] from the method's error
//!   estimate (or takes the size a method that chooses its own proposes, BDF's step and order
//!   being chosen together: `Integrator::next_step`), picks the first step by Hairer's algorithm, lands exactly on the end time and on
//!   time events, and fails with a typed error when the step collapses or the step budget runs
//!   out;
//! - after every accepted step, both check for divergence, look for [`Event`]s, evaluate the
//!   dense output where it is needed (save times, events, [`crate::Trajectory::at`]) and record,
//!   counting everything in [`Stats`].

mod adaptive;
mod controller;
mod dense;
mod events;
mod fixed;
mod record;
mod stats;
mod step;
mod tolerances;

pub use crate::integrators::DenseStep;
pub use controller::{AdaptiveOptions, Controller};
pub use dense::DenseOutput;
pub use events::{Action, Direction, Event, EventRecord, StateChange};
pub use stats::Stats;
pub use tolerances::{Atol, Tolerances};

use controller::{ControllerState, initial_step};
use events::{Outcome, Watch};
use record::sample;

use crate::checks::first_outside;
use crate::integrators::{Integrator, Step};
use crate::{Error, Model, NewtonOptions, Result, Sample, State};

/// Where a long run is, for a progress bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Simulated time reached.
    pub t: f64,
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t_end: f64,
    /// Steps accepted so far.
    pub steps: u64,
}

impl Progress {
    /// The fraction of the run done, in [0, 1].
    pub fn fraction(&self) -> f64 {
        if self.t_end > self.t0 {
            ((self.t - self.t0) / (self.t_end - self.t0)).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }
}

/// What to keep of a run.
pub(crate) struct Recording<'a> {
    /// Record every n-th step (grid step for fixed runs, accepted step for adaptive ones).
    pub(crate) every: u64,
    /// Record only at these times (increasing), through the dense output.
    pub(crate) save_at: Option<&'a [f64]>,
    /// Keep every step's dense polynomial.
    pub(crate) dense: bool,
    /// Called at every recorded sample.
    pub(crate) progress: Option<&'a dyn Fn(&Progress)>,
}

/// Everything the driver records.
pub(crate) struct Record<S> {
    pub(crate) samples: Vec<Sample<S>>,
    pub(crate) events: Vec<EventRecord<S>>,
    pub(crate) dense: Option<DenseOutput>,
}

/// How a step ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Flow {
    /// On to the next step.
    Continue,
    /// An event changed the state; the method restarted there.
    Changed,
    /// An event stopped the run.
    Stopped,
}

/// A run in progress: the model, the method, the state and everything recorded.
pub(crate) struct Driver<'a, 'm, M: Model, I> {
    model: &'m M,
    integrator: I,
    t: f64,
    t0: f64,
    y: M::State,
    y_new: M::State,
    /// The state at an event.
    at: M::State,
    /// The state at a save time.
    saved: M::State,
    /// f at the start and end of the step, for the Hermite interpolant.
    ends: [M::State; 2],
    /// Whether `ends[0]` holds f(t, y).
    f_start: bool,
    dense: DenseStep<M::State>,
    pub(crate) stats: Stats,
    watch: Watch<'a, M::State>,
    limit: f64,
    max_halvings: u32,
    /// Sub-step ends for halving: (end, depth).
    pending: Vec<(f64, u32)>,
    recording: Recording<'a>,
    next_save: usize,
    pub(crate) record: Record<M::State>,
    /// Whether recording is off entirely (a bare stepper).
    quiet: bool,
    /// Whether the state was changed from outside since the last step.
    dirty: bool,
    /// The grid step being taken, for a fixed-step run: samples and errors number steps by the
    /// grid (t = t₀ + n·dt), whatever sub-steps halving took.
    grid: Option<u64>,
}

impl<'a, 'm, M: Model, I: Integrator<M>> Driver<'a, 'm, M, I> {
    /// Starts a run of `model` from (`t0`, `y0`): checks the state and the model, starts the
    /// method and records the initial sample.
    // Called only from `Simulation::run` and `Stepper`, which pass their own option fields,
    // checked (`t0` included).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        model: &'m M,
        t0: f64,
        y0: M::State,
        newton: &NewtonOptions,
        limit: f64,
        events: Vec<Event<'a, M::State>>,
        (event_tolerance, max_events): (f64, u64),
        recording: Recording<'a>,
    ) -> Result<Self> {
        if let Some((index, value)) = first_outside(&y0, limit)
            && value.is_finite()
        {
            return Err(Error::invalid(
                format!("initial state `{}`", y0.component_name(index)),
                format!(
                    "{value:e} is already beyond the divergence limit {limit:e}; raise \
                     `divergence_limit` if such values are expected"
                ),
            ));
        }
        for event in &events {
            event.check()?;
        }
        let mut stats = Stats::default();
        let integrator = I::start(model, t0, &y0, newton, &mut stats)?;
        let quiet = recording.every == 0;
        let mut record = Record {
            samples: Vec::new(),
            events: Vec::new(),
            dense: recording
                .dense
                .then(|| DenseOutput::new(y0.as_slice().len())),
        };
        let next_save = recording
            .save_at
            .map_or(0, |times| times.partition_point(|&s| s < t0));
        // The run's copies of the state, allocated fallibly: a state that fits in memory once
        // may not fit a dozen times over.
        if !quiet {
            record.samples.push(sample(model, 0, t0, y0.try_clone()?));
        }
        let mut driver = Driver {
            model,
            integrator,
            t: t0,
            t0,
            y_new: y0.try_clone()?,
            at: y0.try_clone()?,
            saved: y0.try_clone()?,
            ends: [y0.try_clone()?, y0.try_clone()?],
            f_start: false,
            dense: DenseStep::new(&y0, I::DENSE_DEGREE.max(3))?,
            stats,
            watch: Watch::new(events, t0, &y0, event_tolerance, max_events)?,
            limit,
            max_halvings: newton.max_halvings,
            pending: Vec::with_capacity(newton.max_halvings as usize + 2),
            recording,
            next_save,
            record,
            quiet,
            dirty: false,
            grid: None,
            y: y0,
        };
        // A save time at t₀ itself is the initial sample.
        if let Some(times) = driver.recording.save_at
            && times.get(driver.next_save) == Some(&t0)
        {
            driver.next_save += 1;
        }
        Ok(driver)
    }

    /// The current time.
    pub(crate) fn t(&self) -> f64 {
        self.t
    }

    /// The current state.
    pub(crate) fn state(&self) -> &M::State {
        &self.y
    }

    /// The current state, to change between steps (a user's impulse): the method restarts from
    /// it at the next step.
    pub(crate) fn state_mut(&mut self) -> &mut M::State {
        self.dirty = true;
        &mut self.y
    }

    /// `error`, or the cause behind it when the run failed before its first step because the
    /// model's derivative is not finite at the initial state (a non-finite parameter, or values
    /// so large that the force overflows): the step-size, divergence and Newton errors would
    /// blame the step for what the input did.
    pub(crate) fn explain(&mut self, error: Error) -> Error {
        let blames_the_step = matches!(
            error,
            Error::StepSizeTooSmall { .. }
                | Error::Diverged { .. }
                | Error::NewtonDidNotConverge { .. }
                | Error::SingularMatrix { .. }
        );
        if !(blames_the_step && self.t == self.t0 && self.stats.steps == 0) {
            return error;
        }
        let f = &mut self.ends[0];
        self.model.derivative(self.t, &self.y, f);
        match f.as_slice().iter().position(|x| !x.is_finite()) {
            None => error,
            Some(k) => Error::BadModel {
                model: M::NAME,
                what: format!("its derivative at the initial state (t = {:?})", self.t),
                reason: format!(
                    "is not finite: component `{}` of f is {:?}; a parameter or the initial \
                     state is not finite, or so large that the derivative overflows — check them",
                    self.y.component_name(k),
                    f.as_slice()[k]
                ),
            },
        }
    }

    /// The integrator.
    pub(crate) fn integrator(&self) -> &I {
        &self.integrator
    }

    /// The model.
    pub(crate) fn model(&self) -> &'m M {
        self.model
    }
}

/// The spacing of floats at `t`.
pub(super) fn ulp(t: f64) -> f64 {
    let t = t.abs();
    if t == 0.0 {
        f64::MIN_POSITIVE
    } else {
        f64::from_bits(t.to_bits() + 1) - t
    }
}

/// Grid steps a fixed-step run takes per block between the driver's per-step work and the
/// divergence test (see [`Driver::run_block`]): 1024 amortises both (the runner was 1.45× a bare
/// explicit-Euler Lorenz loop with a test every step in blocks of 64, 1.20× with one test per
/// block of 1024); a diverging block is retaken step by step, so the error names the same step.
const BLOCK: u64 = 1024;
