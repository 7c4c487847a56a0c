//! [`Trajectory`]: what a run recorded, step by step.

use std::path::Path;

use crate::{Method, Result, State, output};

/// One recorded step.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample<S> {
    /// Step number; 0 is the initial state.
    pub step: u64,
    /// Time, t₀ + step·dt.
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
    /// The fixed step.
    pub dt: f64,
    /// Steps taken (the last sample's step).
    pub steps: u64,
    /// Force (derivative or acceleration) evaluations made.
    pub evaluations: u64,
    /// Jacobian evaluations made (implicit methods only).
    pub jacobian_evaluations: u64,
    /// Recorded samples, in step order; never empty (step 0 is always recorded).
    pub samples: Vec<Sample<S>>,
}

impl<S: State> Trajectory<S> {
    /// The first sample (the initial state).
    ///
    /// # Panics
    /// If `samples` was emptied by hand; every trajectory odyn returns holds step 0.
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

    /// Recorded energies as (t, E), for models that define an energy.
    pub fn energies(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.samples
            .iter()
            .filter_map(|s| s.energy.map(|e| (s.t, e)))
    }

    /// Final energy over initial energy, for models that define an energy.
    pub fn energy_ratio(&self) -> Option<f64> {
        Some(self.last().energy? / self.first().energy?)
    }

    /// Writes the samples as CSV (`method,step,t,<components>,energy`), atomically.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        output::write_csv(path, &[self])
    }
}
