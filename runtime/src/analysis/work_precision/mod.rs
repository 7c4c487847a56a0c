//! Work-precision: how much accuracy each method buys for how much work, on one model.
//!
//! For every method, [`measure`] runs the model over a horizon once per stepping — each step
//! `dt` of [`WorkPrecision::dts`] for fixed-step methods, each tolerance of
//! [`WorkPrecision::tolerances`] for adaptive ones — and records the final-state error against a
//! reference, the largest energy error along the way, the wall time (the minimum of several
//! repeats) and the evaluations. Both kinds land on one chart, compared where it matters: at
//! equal error, never at equal dt or tolerance. The chart follows DifferentialEquations.jl's
//! `WorkPrecisionSet` (DiffEqDevTools): error on the horizontal axis, cost on the vertical one,
//! both logarithmic, one line per method, a marker per run; lower-left is better.
mod measure;
mod report;

pub use measure::measure;

use crate::{Method, NewtonOptions, State, Stats, Stepping, Tolerances};

/// What a run's final state is compared with.
pub enum Reference<S> {
    /// The exact solution y(t): compared at the time each run actually ended (the energy error
    /// then compares with its energy, too).
    Exact(Box<dyn Fn(f64) -> S>),
    /// A known final state y(horizon), component by component (from another solver or a paper).
    /// Fixed-step runs must then end exactly at the horizon: every dt must divide it.
    Final(Vec<f64>),
    /// A fixed-step run of `method` at `dt`; its own error is estimated against a run at `dt/2`
    /// and reported as [`WorkPrecisionSet::reference_error`].
    Computed {
        /// The method of the reference run.
        method: Method,
        /// Its step; it must divide the horizon.
        dt: f64,
    },
}

/// A work-precision study: one model, one horizon, several methods and steppings.
pub struct WorkPrecision<S> {
    /// Name of the scene, the first CSV column.
    pub scene: String,
    /// The scene as the charts title it (default: the name with spaces for underscores and a
    /// capital first letter, `van_der_pol` → `Van der pol`).
    pub title: String,
    /// The initial state.
    pub initial: S,
    /// Final time (the runs start at 0).
    pub horizon: f64,
    /// What errors are measured against.
    pub reference: Reference<S>,
    /// The methods to compare (default: none; a study needs at least one).
    pub methods: Vec<Method>,
    /// The steps to run each fixed-step method at (default: none).
    pub dts: Vec<f64>,
    /// The tolerances to run each adaptive method at (default: none).
    pub tolerances: Vec<Tolerances>,
    /// Timed repeats of each run; the minimum time is kept (default 3).
    pub repeats: u32,
    /// At most this many samples are recorded for the energy error (default 100 000).
    pub samples: u64,
    /// Newton's method for implicit runs.
    pub newton: NewtonOptions,
}

impl<S: State> WorkPrecision<S> {
    /// A study of `scene` from `initial` to `horizon` against `reference`, with no methods yet
    /// and the default repeats, samples and Newton options.
    pub fn new(
        scene: impl Into<String>,
        initial: S,
        horizon: f64,
        reference: Reference<S>,
    ) -> Self {
        let scene = scene.into();
        WorkPrecision {
            title: readable(&scene),
            scene,
            initial,
            horizon,
            reference,
            methods: Vec::new(),
            dts: Vec::new(),
            tolerances: Vec::new(),
            repeats: 3,
            samples: 100_000,
            newton: NewtonOptions::default(),
        }
    }

    /// Tolerances rtol = 10⁻ᵏ for each k in `exponents`, with atol = rtol·`atol_ratio`: the
    /// usual sweep (e.g. `WorkPrecision::rtols(3..=12, 1e-3)`).
    pub fn rtols(exponents: impl IntoIterator<Item = i32>, atol_ratio: f64) -> Vec<Tolerances> {
        exponents
            .into_iter()
            .map(|k| {
                let rtol = 10f64.powi(-k);
                Tolerances::new(rtol, rtol * atol_ratio)
            })
            .collect()
    }
}

/// One run of a study.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The method.
    pub method: Method,
    /// Its step or tolerances.
    pub stepping: Stepping,
    /// Max-norm of the final state's error; infinite when the run failed.
    pub error: f64,
    /// Largest |E(t) − E_ref(t)| / |E_ref(0)| over the recorded samples, where E_ref is the exact
    /// solution's energy for an exact reference and E(0) otherwise; `None` without `fn energy`.
    pub energy_error: Option<f64>,
    /// Wall time of the run without recording, the minimum over the repeats; NaN if it failed.
    pub seconds: f64,
    /// Steps, rejections and evaluations.
    pub stats: Stats,
    /// Whether the run stopped with a divergence, a failed Newton solve, a collapsed step or an
    /// exhausted step budget.
    pub diverged: bool,
}

impl Measurement {
    /// Force, Jacobian and ∂f/∂t evaluations: the cost that does not depend on the machine.
    pub fn evaluations(&self) -> u64 {
        self.stats.function_evaluations()
    }
}

/// The result of [`measure`].
#[derive(Clone, Debug, PartialEq)]
pub struct WorkPrecisionSet {
    /// The scene.
    pub scene: String,
    /// Its title on charts.
    pub title: String,
    /// The estimated error of the reference itself: 0 for an exact one, NaN when unknown (a
    /// given final state), the max-norm difference between the dt and dt/2 runs for a computed one.
    pub reference_error: f64,
    /// One entry per method and stepping, in the order of the study.
    pub measurements: Vec<Measurement>,
}

/// `van_der_pol` → `Van der pol`: a scene name as a chart title.
fn readable(scene: &str) -> String {
    let spaced = scene.replace('_', " ");
    let mut chars = spaced.chars();
    chars
        .next()
        .map(|first| first.to_uppercase().chain(chars).collect())
        .unwrap_or_default()
}

/// The accuracy axis of a work-precision chart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Accuracy {
    /// Max-norm error of the final state.
    FinalState,
    /// Largest relative energy error along the run (for long conservative runs, where the final
    /// state's phase error says little).
    Energy,
}

/// The cost axis of a work-precision chart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cost {
    /// Wall time.
    Seconds,
    /// Force and Jacobian evaluations.
    Evaluations,
}
