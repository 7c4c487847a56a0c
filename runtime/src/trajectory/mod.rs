//! [`Trajectory`]: what a run recorded — samples, events, statistics, and the dense output that
//! gives the solution at any time.

mod dense;

pub use dense::DenseOutput;

use crate::{Error, Method, Result, State, Stats, Stepping};

/// One recorded state.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample<S> {
    /// The step it was recorded at: the grid step n of a fixed-step run (t = t₀ + n·dt, whatever
    /// sub-steps halving took), the number of accepted steps of an adaptive one; 0 is the initial
    /// state.
    pub step: u64,
    /// Time: t₀ + step·dt on a fixed grid, the step's end or a save time otherwise.
    pub t: f64,
    /// The typed state.
    pub state: S,
    /// The model's energy, when it defines one.
    pub energy: Option<f64>,
}

/// The recorded samples of one run and how they were made.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory<S> {
    /// The model's type name.
    pub model: &'static str,
    /// The method that produced it.
    pub method: Method,
    /// A fixed dt or the tolerances: how the run sized its steps.
    pub stepping: Stepping,
    /// What the run cost.
    pub stats: Stats,
    /// Recorded samples in time order; never empty as odyn returns them (the initial state is
    /// always recorded). An event that changed the state appears as two samples at its time,
    /// before and after.
    pub samples: Vec<Sample<S>>,
    /// Every event that happened, in time order.
    pub events: Vec<EventRecord<S>>,
    /// One polynomial per accepted step, when the run kept them (adaptive runs do by default):
    /// what [`Trajectory::at`] evaluates.
    pub dense: Option<DenseOutput>,
}

impl<S: State> Trajectory<S> {
    /// The first sample (the initial state).
    ///
    /// # Panics
    /// If `samples` was emptied by hand; every trajectory odyn returns holds the initial state.
    pub fn first(&self) -> &Sample<S> {
        &self.samples[0]
    }

    /// The last sample.
    ///
    /// # Panics
    /// If `samples` was emptied by hand, as [`Trajectory::first`].
    pub fn last(&self) -> &Sample<S> {
        self.samples
            .last()
            .expect("a trajectory always holds its initial sample")
    }

    /// Accepted steps taken, sub-steps of halved implicit steps included (see [`Stats::steps`]).
    pub fn steps(&self) -> u64 {
        self.stats.steps
    }

    /// The recorded times.
    pub fn times(&self) -> impl Iterator<Item = f64> + '_ {
        self.samples.iter().map(|s| s.t)
    }

    /// The sample recorded at time `t` — a `save_at` time, a step, an event. A sample at exactly
    /// `t` wins (at an event that changed the state, the one after the change). Otherwise the
    /// nearest sample wins if it is within 1e-9 of the spacing between it and its neighbours,
    /// or within four float spacings of `t` (so a time computed by other arithmetic, 0.1·3
    /// against 0.3, still finds its sample) — never a tolerance that could reach a neighbouring
    /// sample, however closely the samples are spaced. Samples are in time order, so this is a
    /// binary search.
    ///
    /// Errors: [`Error::InvalidInput`] for a non-finite `t`, or when no sample was recorded that
    /// near `t`, naming the nearest one (record `t` with `.save_at(..)`, or read any time with
    /// [`Trajectory::at`]).
    pub fn sample_at(&self, t: f64) -> Result<&Sample<S>> {
        if !t.is_finite() {
            return Err(Error::invalid(
                "sample time",
                format!("t = {t:?} is not a time a sample can be recorded at"),
            ));
        }
        let samples = &self.samples;
        let after = samples.partition_point(|s| s.t <= t);
        if after > 0 && samples[after - 1].t == t {
            return Ok(&samples[after - 1]);
        }
        // The nearest distinct time on either side of t, and how far it is from its own
        // neighbours.
        let below = after.checked_sub(1).map(|k| samples[k].t);
        let above = samples.get(after).map(|s| s.t);
        let nearest = match (below, above) {
            (Some(b), Some(a)) => {
                if t - b <= a - t {
                    b
                } else {
                    a
                }
            }
            (Some(b), None) => b,
            (None, Some(a)) => a,
            (None, None) => {
                return Err(Error::invalid(
                    "sample time",
                    "the trajectory has no samples",
                ));
            }
        };
        let (first, end) = (
            samples.partition_point(|s| s.t < nearest),
            samples.partition_point(|s| s.t <= nearest),
        );
        let before = first.checked_sub(1).map(|k| nearest - samples[k].t);
        let past = samples.get(end).map(|s| s.t - nearest);
        let spacing = before.into_iter().chain(past).fold(f64::INFINITY, f64::min);
        let tolerance = (1e-9 * spacing)
            .min(f64::MAX)
            .max(4.0 * f64::EPSILON * t.abs().max(nearest.abs()));
        if (nearest - t).abs() <= tolerance {
            // The last sample at that time (after an event's change).
            return Ok(&samples[end - 1]);
        }
        Err(Error::invalid(
            "sample time",
            format!(
                "no sample was recorded at t = {t:?} (the nearest is at {nearest:?}); record it \
                 with `.save_at(..)`, or read any time with `at(t)` on a run with dense output"
            ),
        ))
    }

    /// The state at time `t`, from the run's dense output: the method's own interpolant (order 4
    /// for Tsit5, 7 for DOP853) or the cubic Hermite one, never a straight line between samples.
    /// At an event that changed the state, the state after it.
    ///
    /// Errors: [`Error::InvalidInput`] when the run kept no dense output (fixed-step runs keep
    /// it only with `.dense_output(true)`), or `t` is outside the run.
    pub fn at(&self, t: f64) -> Result<S> {
        let dense = self.dense.as_ref().ok_or_else(|| {
            Error::invalid(
                "dense output",
                "this run kept none; run it with `.dense_output(true)`",
            )
        })?;
        let mut state = self
            .samples
            .first()
            .ok_or_else(|| Error::invalid("trajectory", "has no samples"))?
            .state
            .clone();
        if dense.is_empty() && t == self.first().t {
            return Ok(state);
        }
        dense.eval_into(t, &mut state)?;
        Ok(state)
    }

    /// Recorded energies as (t, E), for models that define an energy.
    pub fn energies(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.samples
            .iter()
            .filter_map(|s| s.energy.map(|e| (s.t, e)))
    }

    /// Final energy over initial energy, for models that define an energy.
    pub fn energy_ratio(&self) -> Option<f64> {
        Some(self.samples.last()?.energy? / self.samples.first()?.energy?)
    }

    /// The largest |E(t) − E(0)| / |E(0)| over the recorded samples, for models that define an
    /// energy (|E(t) − E(0)| when E(0) = 0). NaN if any recorded energy is NaN.
    pub fn max_energy_error(&self) -> Option<f64> {
        let e0 = self.samples.first()?.energy?;
        let scale = if e0 == 0.0 { 1.0 } else { e0.abs() };
        Some(self.energies().fold(0.0, |worst: f64, (_, e)| {
            let error = (e - e0).abs() / scale;
            if error.is_nan() || worst.is_nan() {
                f64::NAN
            } else {
                worst.max(error)
            }
        }))
    }
}

/// One event that happened, as a trajectory records it.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRecord<S> {
    /// When.
    pub t: f64,
    /// Which event: its index in the run's event list.
    pub event: usize,
    /// Its name.
    pub name: String,
    /// The state at the event, before its action.
    pub before: S,
    /// The state after its action (equal to `before` unless the action changed it).
    pub after: S,
}
