//! The track of a run: time, state, its copies, events, recording and counts — everything a
//! driver keeps that does not depend on the method, generic over the model alone.

use super::events::{Outcome, Watch};
use super::record::sample;
use super::{DenseOutput, DenseStep, Event, Flow, Record, Recording, Stats};
use crate::checks::first_outside;
use crate::integrators::check_start;
use crate::{Error, Method, Model, NewtonOptions, Result, State};

/// The options a run starts with, beyond its model, state, events and recording.
pub(crate) struct Start<'n> {
    pub(crate) t0: f64,
    pub(crate) newton: &'n NewtonOptions,
    pub(crate) limit: f64,
    /// The event tolerance and the most events a run may handle.
    pub(crate) event_options: (f64, u64),
    /// The degree of the method's own interpolant (3 for the Hermite one).
    pub(crate) dense_degree: usize,
    /// The method: a model with a mass matrix runs only with one that takes it.
    pub(crate) method: Method,
}

/// Why a method that does not take a mass matrix refuses a model that has one.
const fn mass_matrix_reason() -> &'static str {
    "it is differential–algebraic (`#[algebraic]` fields or `fn mass`: M·y′ = f with M ≠ I), \
     which only Rodas5P, Rosenbrock23, Bdf and ImplicitEuler integrate (each solves with \
     M − c·J); explicit methods have no matrix to put M in"
}

/// A run's time, state and record (see [`super::Driver`]).
pub(crate) struct Track<'a, 'm, M: Model> {
    pub(super) model: &'m M,
    pub(super) t: f64,
    pub(super) t0: f64,
    pub(super) y: M::State,
    pub(super) y_new: M::State,
    /// The state at an event.
    pub(super) at: M::State,
    /// The state at a save time.
    pub(super) saved: M::State,
    /// f at the start and end of the step, for the Hermite interpolant.
    pub(super) ends: [M::State; 2],
    /// Whether `ends[0]` holds f(t, y).
    pub(super) f_start: bool,
    pub(super) dense: DenseStep<M::State>,
    pub(crate) stats: Stats,
    pub(super) watch: Watch<'a, M::State>,
    pub(super) limit: f64,
    pub(super) max_halvings: u32,
    /// Sub-step ends for halving: (end, depth).
    pub(super) pending: Vec<(f64, u32)>,
    pub(super) recording: Recording<'a>,
    pub(super) next_save: usize,
    pub(crate) record: Record<M::State>,
    /// Whether recording is off entirely (a bare stepper).
    pub(super) quiet: bool,
    /// Whether the state was changed from outside since the last step.
    pub(super) dirty: bool,
    /// The grid step being taken, for a fixed-step run: samples and errors number steps by the
    /// grid (t = t₀ + n·dt), whatever sub-steps halving took.
    pub(super) grid: Option<u64>,
}

impl<'a, 'm, M: Model> Track<'a, 'm, M> {
    /// Checks the state, the events and the model, allocates the run's copies of the state and
    /// records the initial sample.
    pub(crate) fn new(
        model: &'m M,
        mut y0: M::State,
        start: Start<'_>,
        events: Vec<Event<'a, M::State>>,
        recording: Recording<'a>,
    ) -> Result<Self> {
        let Start {
            t0,
            newton,
            limit,
            event_options: (event_tolerance, max_events),
            dense_degree,
            method,
        } = start;
        if M::MASS_MATRIX && !method.takes_mass_matrix() {
            return Err(Error::Unsupported {
                method,
                model: M::NAME,
                reason: mass_matrix_reason(),
            });
        }
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
        check_start(model, &y0, newton)?;
        // A differential–algebraic model's algebraic components are made consistent before the
        // first step (and the sample records them so).
        model.consistent(t0, &mut y0, newton)?;
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
        let mut track = Track {
            model,
            t: t0,
            t0,
            y_new: y0.try_clone()?,
            at: y0.try_clone()?,
            saved: y0.try_clone()?,
            ends: [y0.try_clone()?, y0.try_clone()?],
            f_start: false,
            dense: DenseStep::new(&y0, dense_degree.max(3))?,
            stats: Stats::default(),
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
        if let Some(times) = track.recording.save_at
            && times.get(track.next_save) == Some(&t0)
        {
            track.next_save += 1;
        }
        Ok(track)
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
                | Error::NonFiniteJacobian { .. }
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

    /// Whether steps need none of the per-step machinery: no events, no save times, no dense
    /// output, no change from outside pending.
    pub(super) fn plain(&self) -> bool {
        self.watch.is_empty()
            && self.recording.save_at.is_none()
            && self.record.dense.is_none()
            && !self.dirty
    }

    /// The first part of accepting the attempt that went from (t, y) to (`t1`, `y_new`), before
    /// the method's own `accept`: the divergence test.
    #[inline]
    pub(super) fn check_limit(&self, t1: f64, method: Method) -> Result<()> {
        match first_outside(&self.y_new, self.limit) {
            None => Ok(()),
            Some((index, value)) => Err(Error::Diverged {
                method,
                step: self.grid.unwrap_or(self.stats.steps + 1),
                t: t1,
                component: self.y_new.component_name(index),
                value,
                limit: self.limit,
            }),
        }
    }

    /// Counts the accepted step and looks for events and save times in it; returns whether
    /// either needs the step's dense output (events, saves), f at its start evaluated for
    /// events that need it.
    #[inline]
    pub(super) fn scan(&mut self, t1: f64) -> Result<(bool, bool)> {
        self.stats.steps += 1;
        let events = !self.watch.is_empty() && self.watch.scan(t1, &self.y_new)?;
        let saves = self
            .recording
            .save_at
            .is_some_and(|times| times.get(self.next_save).is_some_and(|&s| s <= t1));
        if events && self.watch.latched() && !self.f_start {
            self.model.derivative(self.t, &self.y, &mut self.ends[0]);
            self.stats.evaluations += 1;
            self.f_start = true;
        }
        Ok((events, saves))
    }

    /// Fills `self.dense` with the cubic Hermite interpolant from (t, y) to (`t1`, `y_new`)
    /// through f at both ends, for a method without an interpolant of its own (`ends[1]` then
    /// holds f(t1, y_new)).
    pub(super) fn hermite(&mut self, t1: f64) {
        let h = t1 - self.t;
        let [f0, f1] = &mut self.ends;
        if !self.f_start {
            self.model.derivative(self.t, &self.y, f0);
            self.stats.evaluations += 1;
        }
        self.model.derivative(t1, &self.y_new, f1);
        self.stats.evaluations += 1;
        self.dense
            .hermite(self.t, h, [&self.y, f0, &self.y_new, f1]);
    }

    /// The rest of accepting the step to `t1`: handles its events and save times, stores its
    /// dense output and moves on — to `t1`, or to the event that changed the state or stopped
    /// the run (the method must then restart from there). `hermite` says whether the step's
    /// interpolant evaluated f at its end.
    #[inline]
    pub(super) fn conclude(
        &mut self,
        t1: f64,
        (events, saves): (bool, bool),
        hermite: bool,
    ) -> Result<Flow> {
        if !self.looks_inside(events, saves) {
            // Most steps: nothing to look at inside the step.
            self.watch.advance();
            self.move_on(t1, false);
            return Ok(Flow::Continue);
        }
        self.conclude_inside(t1, (events, saves), hermite)
    }

    /// Whether accepting a step needs its dense output: for its events, its save times, or to
    /// store it.
    #[inline]
    pub(super) fn looks_inside(&self, events: bool, saves: bool) -> bool {
        events || saves || self.record.dense.is_some()
    }

    /// Moves the run to the accepted step's end `t1`; `hermite` says whether `ends[1]` holds f
    /// there (the Hermite interpolant evaluated it), which the next step then starts from.
    #[inline]
    fn move_on(&mut self, t1: f64, hermite: bool) {
        std::mem::swap(&mut self.y, &mut self.y_new);
        self.t = t1;
        if hermite {
            self.ends.swap(0, 1);
        }
        self.f_start = hermite;
    }

    /// [`Track::conclude`] for a step with events, save times or dense output to store.
    fn conclude_inside(
        &mut self,
        t1: f64,
        (events, saves): (bool, bool),
        hermite: bool,
    ) -> Result<Flow> {
        let outcome = if events {
            self.watch.handle(
                self.model,
                &self.dense,
                t1,
                &self.y_new,
                &self.ends[0],
                &mut self.at,
                &mut self.record.events,
            )?
        } else {
            self.watch.advance();
            Outcome::Continue
        };
        let (end, flow) = match outcome {
            Outcome::Continue => (t1, Flow::Continue),
            Outcome::Changed(t) => (t, Flow::Changed),
            Outcome::Stop(t) => (t, Flow::Stopped),
        };
        if saves {
            self.save_until(end, flow == Flow::Continue);
        }
        if let Some(store) = &mut self.record.dense {
            store.push(&self.dense, end);
        }
        match flow {
            Flow::Continue => self.move_on(t1, hermite),
            Flow::Changed | Flow::Stopped => self.land(end, flow),
        }
        Ok(flow)
    }

    /// Moves the run to the event at `end` that changed the state or stopped the run.
    fn land(&mut self, end: f64, flow: Flow) {
        let event_record = self.record.events.last().cloned();
        std::mem::swap(&mut self.y, &mut self.at);
        self.t = end;
        self.f_start = false;
        if !self.quiet
            && self.recording.save_at.is_none()
            && let Some(event) = event_record
        {
            // A discontinuity shows in the samples as two samples at one time.
            let step = self.sample_step();
            self.record
                .samples
                .push(sample(self.model, step, end, event.before));
            if flow == Flow::Changed {
                self.record
                    .samples
                    .push(sample(self.model, step, end, event.after));
            }
        }
        if flow == Flow::Changed {
            if let Some(times) = self.recording.save_at
                && times.get(self.next_save) == Some(&end)
            {
                self.push_sample();
                self.next_save += 1;
            }
        } else if self.recording.save_at.is_some() {
            self.finish();
        }
    }
}
