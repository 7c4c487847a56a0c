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
mod attempt;
mod events;
mod fixed;
mod record;
mod track;

pub use crate::control::{AdaptiveOptions, Atol, Controller, Tolerances};
pub use crate::integrators::DenseStep;
pub use crate::model::Jump;
pub use crate::stats::Stats;
pub use crate::trajectory::{DenseOutput, EventRecord};
pub use events::{Action, Direction, Event, StateChange};

use crate::control::{ControllerState, initial_step};
pub(crate) use track::{Start, Track};

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

/// A run in progress: the method and its [`Track`].
///
/// Only what calls the method is generic over it (the loops, one attempted step, its acceptance
/// around the method's own `accept` and interpolant); everything else is on the track, generic
/// over the model alone, so a model run by fifteen methods compiles it once, not fifteen times.
pub(crate) struct Driver<'a, 'm, M: Model, I> {
    integrator: I,
    pub(crate) track: Track<'a, 'm, M>,
}

impl<'a, 'm, M: Model, I: Integrator<M>> Driver<'a, 'm, M, I> {
    /// The track, its [`Stats::linear`] read from the method's Newton matrix: what the run
    /// leaves once it has stopped.
    pub(crate) fn into_track(mut self) -> Track<'a, 'm, M> {
        self.track.stats.linear = self.integrator.linear_work();
        self.track
    }

    /// Prepares the method on a started track ([`Track::new`] checked the state and the model
    /// and recorded the initial sample).
    pub(crate) fn on(mut track: Track<'a, 'm, M>, newton: &NewtonOptions) -> Result<Self> {
        let integrator = I::prepare(track.model, track.t0, &track.y, newton, &mut track.stats)?;
        Ok(Driver { integrator, track })
    }

    /// The current time.
    pub(crate) fn t(&self) -> f64 {
        self.track.t
    }

    /// The current state.
    pub(crate) fn state(&self) -> &M::State {
        &self.track.y
    }

    /// The current state, to change between steps (a user's impulse): the method restarts from
    /// it at the next step.
    pub(crate) fn state_mut(&mut self) -> &mut M::State {
        self.track.dirty = true;
        &mut self.track.y
    }

    /// The integrator.
    pub(crate) fn integrator(&self) -> &I {
        &self.integrator
    }

    /// The model.
    pub(crate) fn model(&self) -> &'m M {
        self.track.model
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
