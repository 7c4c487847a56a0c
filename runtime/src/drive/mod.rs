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

mod controller;
mod dense;
mod events;
mod stats;
mod tolerances;

pub use crate::integrators::DenseStep;
pub use controller::{Controller, StepControl};
pub use dense::DenseOutput;
pub use events::{Action, Direction, Event, EventRecord, StateChange};
pub use stats::Stats;
pub use tolerances::{Atol, Tolerances};

use controller::{Control, initial_step};
use events::{Outcome, Watch};

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
    // Called only from `Simulation::run` and `Stepper`, which pass their own option fields.
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
        if !t0.is_finite() {
            return Err(Error::invalid(
                "t0",
                format!("start time must be finite, got {t0:?}"),
            ));
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

    // ----- the fixed-step loop ----------------------------------------------------------------

    /// Takes `steps` steps of the grid t₀ + n·dt (n counted from `first`), recording per
    /// [`Recording`]. Returns early when an event stops the run.
    pub(crate) fn run_fixed(&mut self, dt: f64, first: u64, steps: u64) -> Result<()> {
        let mut until_record = self.recording.every;
        let last = first.saturating_add(steps);
        let mut n = first;
        // Steps before this grid index go through the checked path (a block being retaken).
        let mut checked_until = first;
        let recording = !self.quiet && self.recording.save_at.is_none();
        while n < last {
            let block = (last - n)
                .min(BLOCK)
                .min(if recording { until_record } else { BLOCK });
            // Checked as the run goes: a run of `steps(u64::MAX)` stops at a divergence first.
            check_resolution(self.t0, dt, n, n + block)?;
            let taken = if n >= checked_until && block > 1 && self.plain() {
                if !self.run_block(dt, n, block) {
                    checked_until = n + block;
                    continue;
                }
                block
            } else {
                // Time as t₀ + n·dt, never accumulated: two runs that took the same steps are at
                // bit-identical times.
                let target = self.t0 + (n + 1) as f64 * dt;
                self.grid = Some(n + 1);
                loop {
                    match self.advance_to(target)? {
                        Flow::Continue => break,
                        Flow::Changed => continue,
                        Flow::Stopped => return Ok(()),
                    }
                }
                1
            };
            n += taken;
            if recording {
                until_record -= taken;
                if until_record == 0 || n == last {
                    self.push_sample();
                    until_record = self.recording.every;
                    self.report(self.t);
                }
            }
        }
        self.finish();
        Ok(())
    }

    /// Whether steps need none of the per-step machinery: no events, no save times, no dense
    /// output, no change from outside pending.
    fn plain(&self) -> bool {
        self.watch.is_empty()
            && self.recording.save_at.is_none()
            && self.record.dense.is_none()
            && !self.dirty
    }

    /// Takes `count` grid steps from index `n` as a bare loop — the same attempts at the same
    /// (t, h) as the checked path — and tests the divergence limit once, on the block's last
    /// state (a state that left the limit is infinite, NaN or still growing there; one that
    /// left it and came back within a block is not reported). Returns false when a step failed
    /// or the last state is outside the limit: the state, time and counts are then back at the
    /// block's start (the method restarted there) and the caller retakes the block on the
    /// checked path, which halves the failing step or names the diverging one.
    fn run_block(&mut self, dt: f64, n: u64, count: u64) -> bool {
        self.at.clone_from(&self.y);
        let stats = self.stats;
        let inside = bare_steps(
            &mut self.integrator,
            self.model,
            (self.t0, dt, n, count),
            (&mut self.y, &mut self.y_new),
            &mut self.stats,
            self.limit,
        );
        if inside {
            self.stats.steps += count;
            self.t = self.t0 + (n + count) as f64 * dt;
            self.grid = Some(n + count);
            self.f_start = false;
            return true;
        }
        std::mem::swap(&mut self.y, &mut self.at);
        self.stats = stats;
        self.integrator
            .restart(self.model, self.t, &self.y, &mut self.stats);
        false
    }

    /// Steps from the current time to `target`, halving a step whose implicit solve fails and
    /// landing on any time event in between.
    fn advance_to(&mut self, target: f64) -> Result<Flow> {
        self.pending.clear();
        self.pending.push((target, 0));
        let stop = self.watch.next_stop();
        if stop > self.t && stop < target {
            self.pending.push((stop, 0));
        }
        while let Some(&(end, depth)) = self.pending.last() {
            let h = end - self.t;
            match self.attempt(h, None) {
                Ok(_) => {
                    self.pending.pop();
                    let flow = self.accept(end)?;
                    if flow != Flow::Continue {
                        return Ok(flow);
                    }
                }
                Err(error) if error.is_retriable() && depth < self.max_halvings => {
                    self.stats.rejected += 1;
                    let mid = self.t + 0.5 * h;
                    self.pending.pop();
                    self.pending.push((end, depth + 1));
                    self.pending.push((mid, depth + 1));
                }
                Err(error) => return Err(error.with_halvings(depth)),
            }
        }
        Ok(Flow::Continue)
    }

    // ----- the adaptive loop ------------------------------------------------------------------

    /// Steps adaptively until `t_end`, keeping the error estimate of every step within
    /// `tolerances`; `order` is the method's, for the first step.
    pub(crate) fn run_adaptive(
        &mut self,
        t_end: f64,
        tolerances: &super::Tolerances,
        control: &StepControl,
        controller: Controller,
        order: u32,
    ) -> Result<()> {
        tolerances.check(self.y.as_slice().len())?;
        tolerances.check_against(&self.y)?;
        control.check()?;
        if control.dt_min > t_end - self.t {
            return Err(Error::invalid(
                "dt_min",
                format!(
                    "{:e} is longer than the run ({:e}): no step could be taken; lower it",
                    control.dt_min,
                    t_end - self.t
                ),
            ));
        }
        let mut control_state = Control::new(control.controller.unwrap_or(controller));
        let mut h = match control.dt_initial {
            Some(h) => h,
            None => {
                let [f0, scratch] = &mut self.ends;
                self.model.derivative(self.t, &self.y, f0);
                self.stats.evaluations += 2;
                let h = initial_step(
                    self.model,
                    self.t,
                    &self.y,
                    f0,
                    order,
                    tolerances,
                    control.dt_max,
                    (&mut self.at, scratch),
                );
                self.f_start = true;
                h
            }
        };
        let mut until_record = self.recording.every;
        while self.t < t_end {
            let stop = t_end.min(self.watch.next_stop());
            let mut h_try = h.min(control.dt_max);
            // Land exactly on the end or a time event; stretch by up to 1 % to get there rather
            // than leave a sliver of a step (Hairer's codes do the same).
            let t1 = if self.t + 1.01 * h_try >= stop {
                h_try = stop - self.t;
                stop
            } else {
                self.t + h_try
            };
            let resolution = 10.0 * ulp(self.t);
            let floor = control.dt_min.max(resolution);
            let t = self.t;
            let too_small = |dt: f64| Error::StepSizeTooSmall {
                t,
                dt,
                dt_min: control.dt_min,
                resolution,
            };
            if h_try < floor && t1 != stop {
                return Err(too_small(h_try));
            }
            if self.stats.steps + self.stats.rejected >= control.max_steps {
                return Err(Error::MaxSteps {
                    t: self.t,
                    steps: control.max_steps,
                });
            }
            // A method that sizes its own steps (`Integrator::next_step`) overrides the
            // controller after each outcome; the caps and landings above still apply.
            match self.attempt(h_try, Some(tolerances)) {
                Ok(err) if err <= 1.0 => {
                    let controlled = control_state.accepted(h_try, err);
                    let flow = self.accept(t1)?;
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if flow == Flow::Stopped {
                        return Ok(());
                    }
                    if !self.quiet && self.recording.save_at.is_none() && flow == Flow::Continue {
                        until_record -= 1;
                        if until_record == 0 || self.t >= t_end {
                            self.push_sample();
                            until_record = self.recording.every;
                            self.report(t_end);
                        }
                    }
                }
                Ok(err) => {
                    self.stats.rejected += 1;
                    let controlled = control_state.rejected(h_try, err);
                    h = self.integrator.next_step().unwrap_or(controlled);
                    if h < floor {
                        return Err(too_small(h));
                    }
                }
                Err(error) if error.is_retriable() => {
                    self.stats.rejected += 1;
                    h = self.integrator.next_step().unwrap_or(0.25 * h_try);
                }
                Err(error) => return Err(error),
            }
        }
        self.finish();
        Ok(())
    }

    // ----- one step ---------------------------------------------------------------------------

    fn attempt(&mut self, h: f64, tolerances: Option<&super::Tolerances>) -> Result<f64> {
        if self.dirty {
            self.dirty = false;
            self.integrator
                .restart(self.model, self.t, &self.y, &mut self.stats);
            self.watch.restart(self.t, &self.y)?;
            self.f_start = false;
        }
        let step = Step {
            t: self.t,
            h,
            y: &self.y,
            tolerances,
            stats: &mut self.stats,
        };
        self.integrator.attempt(self.model, step, &mut self.y_new)
    }

    /// Accepts the attempt that went from (t, y) to (`t1`, `y_new`): checks for divergence,
    /// handles events and save times, and moves on.
    fn accept(&mut self, t1: f64) -> Result<Flow> {
        if let Some((index, value)) = first_outside(&self.y_new, self.limit) {
            return Err(Error::Diverged {
                method: I::METHOD,
                step: self.grid.unwrap_or(self.stats.steps + 1),
                t: t1,
                component: self.y_new.component_name(index),
                value,
                limit: self.limit,
            });
        }
        self.integrator.accept();
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
        let hermite = (events || saves || self.record.dense.is_some()) && self.build_dense(t1);
        let outcome = if events {
            self.watch.handle(
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
            Flow::Continue => {
                std::mem::swap(&mut self.y, &mut self.y_new);
                self.t = t1;
                // The Hermite interpolant evaluated f at the end: the next step's start.
                if hermite {
                    self.ends.swap(0, 1);
                }
                self.f_start = hermite;
            }
            Flow::Changed | Flow::Stopped => {
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
                    self.integrator
                        .restart(self.model, self.t, &self.y, &mut self.stats);
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
        Ok(flow)
    }

    /// Fills `self.dense` for the step from (t, y) to (t1, y_new): the method's own interpolant,
    /// or the cubic Hermite one through f at both ends (then `ends[1]` holds f(t1, y_new) and
    /// this returns true).
    fn build_dense(&mut self, t1: f64) -> bool {
        let h = t1 - self.t;
        let step = Step {
            t: self.t,
            h,
            y: &self.y,
            tolerances: None,
            stats: &mut self.stats,
        };
        if self
            .integrator
            .dense(self.model, step, &self.y_new, &mut self.dense)
        {
            return false;
        }
        let [f0, f1] = &mut self.ends;
        if !self.f_start {
            self.model.derivative(self.t, &self.y, f0);
            self.stats.evaluations += 1;
        }
        self.model.derivative(t1, &self.y_new, f1);
        self.stats.evaluations += 1;
        self.dense
            .hermite(self.t, h, [&self.y, f0, &self.y_new, f1]);
        true
    }

    /// Records the save times up to `end` (inclusive when the step went through to it).
    fn save_until(&mut self, end: f64, inclusive: bool) {
        let Some(times) = self.recording.save_at else {
            return;
        };
        while let Some(&s) = times.get(self.next_save) {
            if s > end || (!inclusive && s == end) {
                break;
            }
            let state = if s == end {
                self.y_new.clone()
            } else {
                self.dense
                    .eval((s - self.dense.t) / self.dense.h, &mut self.saved);
                self.saved.clone()
            };
            let step = self.sample_step();
            self.record.samples.push(sample(self.model, step, s, state));
            self.next_save += 1;
        }
        self.report(times.last().copied().unwrap_or(end));
    }

    fn push_sample(&mut self) {
        let (step, state) = (self.sample_step(), self.y.clone());
        self.record
            .samples
            .push(sample(self.model, step, self.t, state));
    }

    /// The step number a sample carries: the grid step of a fixed-step run, the accepted steps
    /// of an adaptive one.
    fn sample_step(&self) -> u64 {
        self.grid.unwrap_or(self.stats.steps)
    }

    /// The last sample, if the loop did not record it already.
    fn finish(&mut self) {
        if self.quiet {
            return;
        }
        let recorded = self.record.samples.last().is_some_and(|s| s.t == self.t);
        if !recorded {
            self.push_sample();
        }
    }

    fn report(&self, t_end: f64) {
        if let Some(report) = self.recording.progress {
            report(&Progress {
                t: self.t,
                t0: self.t0,
                t_end,
                steps: self.stats.steps,
            });
        }
    }
}

fn sample<M: Model>(model: &M, step: u64, t: f64, state: M::State) -> Sample<M::State> {
    Sample {
        step,
        t,
        energy: model.energy(&state),
        state,
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

/// Whether fixed steps of `dt` from grid index `first` to `last` (t = t₀ + n·dt) all advance the
/// time (one test per block of steps). Each grid time is rounded twice (n·dt, then t₀ +), by at
/// most one ulp of the largest magnitude on the way in all, so two neighbours differ by at least
/// dt − 2 ulp: more than two ulps of dt guarantees every step a positive length.
///
/// Errors: [`Error::InvalidInput`] naming `dt` when it is not that large.
fn check_resolution(t0: f64, dt: f64, first: u64, last: u64) -> Result<()> {
    let far = [
        t0,
        t0 + first as f64 * dt,
        t0 + last as f64 * dt,
        last as f64 * dt,
    ]
    .iter()
    .fold(0.0f64, |m, t| m.max(t.abs()));
    if dt > 2.0 * ulp(far) {
        return Ok(());
    }
    Err(Error::invalid(
        "dt",
        format!(
            "{dt:e} is below the resolution of t near {far:e} (one ulp there is {:e}): steps \
             would not advance the time; use a larger dt, or a start time nearer 0",
            ulp(far)
        ),
    ))
}

/// `count` steps of `integrator` from grid index `n` (t = t₀ + i·dt), as a bare loop; false as
/// soon as a step fails, or when the last state is outside `limit`. Small plain states (no heap
/// parts, at most 256 bytes) are stepped in local copies the optimiser keeps in registers, as a
/// hand-written loop's would be; the others in place. A function of its own, one call per block.
#[inline(never)]
fn bare_steps<M: Model, I: Integrator<M>>(
    integrator: &mut I,
    model: &M,
    grid: (f64, f64, u64, u64),
    (y, y_new): (&mut M::State, &mut M::State),
    stats: &mut Stats,
    limit: f64,
) -> bool {
    if std::mem::needs_drop::<M::State>() || std::mem::size_of::<M::State>() > 256 {
        return steps_in(integrator, model, grid, y, y_new, stats, limit);
    }
    let (mut a, mut b) = (y.clone(), y_new.clone());
    let mut counts = *stats;
    let local = (!std::mem::needs_drop::<I>() && std::mem::size_of::<I>() <= 1024)
        .then(|| integrator.duplicate())
        .flatten();
    let inside = match local {
        Some(mut copy) => {
            let inside = steps_in(&mut copy, model, grid, &mut a, &mut b, &mut counts, limit);
            *integrator = copy;
            inside
        }
        None => steps_in(integrator, model, grid, &mut a, &mut b, &mut counts, limit),
    };
    (*y, *y_new, *stats) = (a, b, counts);
    inside
}

#[inline(always)]
fn steps_in<M: Model, I: Integrator<M>>(
    integrator: &mut I,
    model: &M,
    (t0, dt, n, count): (f64, f64, u64, u64),
    y: &mut M::State,
    y_new: &mut M::State,
    stats: &mut Stats,
    limit: f64,
) -> bool {
    // The grid index as a float, exact below 2⁵³ (the same values as `i as f64`, without a
    // conversion per step); each step's end is the next one's start. Steps go in pairs, y → y_new
    // → y, so no state is swapped: with a swap a step, LLVM rotated a small state through extra
    // registers on the critical path (explicit-Euler Lorenz was 1.21× the bare integrator, 1.03×
    // in pairs; RK4 1.12× → 0.98×).
    let mut index = n as f64;
    let mut t = t0 + index * dt;
    let mut one = |from: &mut M::State, to: &mut M::State, stats: &mut Stats| {
        index += 1.0;
        let end = t0 + index * dt;
        let step = Step {
            t,
            h: end - t,
            y: from,
            tolerances: None,
            stats,
        };
        if integrator.attempt(model, step, to).is_err() {
            return false;
        }
        integrator.accept();
        t = end;
        true
    };
    for _ in 0..count / 2 {
        if !(one(y, y_new, stats) && one(y_new, y, stats)) {
            return false;
        }
    }
    if count % 2 == 1 {
        if !one(y, y_new, stats) {
            return false;
        }
        std::mem::swap(y, y_new);
    }
    within(y, limit)
}

/// Grid steps a fixed-step run takes per block between the driver's per-step work and the
/// divergence test (see [`Driver::run_block`]): 1024 amortises both (the runner was 1.45× a bare
/// explicit-Euler Lorenz loop with a test every step in blocks of 64, 1.20× with one test per
/// block of 1024); a diverging block is retaken step by step, so the error names the same step.
const BLOCK: u64 = 1024;

/// Whether every component is within `limit` (NaN is not): one branch-free pass.
#[inline]
fn within<S: State>(state: &S, limit: f64) -> bool {
    state
        .as_slice()
        .iter()
        .fold(true, |ok, x| ok & (x.abs() <= limit))
}
