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

use std::path::Path;
use std::time::Instant;

use crate::output::{number, write_table};
use crate::{
    Error, Method, Model, NewtonOptions, Result, State, Stats, Stepping, Tolerances, Trajectory,
};

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

/// Runs a work-precision study.
///
/// Errors: [`Error::InvalidInput`] for no methods, a method with nothing to sweep (no `dts` for
/// a fixed-step one, no `tolerances` for an adaptive one), a step that is not finite and
/// positive, a repeated step or tolerance, a horizon that is not finite and positive, a reference
/// whose dimension differs from the state's or that is not finite, or a run that cannot end at
/// the horizon a [`Reference::Final`] or [`Reference::Computed`] describes; [`Error::Unsupported`]
/// when a method cannot integrate the model. A run that fails (diverges, or its step collapses)
/// is a measurement with an infinite error, not an error.
pub fn measure<M: Model>(model: &M, study: &WorkPrecision<M::State>) -> Result<WorkPrecisionSet> {
    check(study)?;
    let dimension = study.initial.as_slice().len();
    let (reference, reference_error) = reference_final(model, study)?;
    if let Some(reference) = &reference {
        if reference.len() != dimension {
            return Err(Error::invalid(
                "reference",
                format!(
                    "has {} components but the state has {dimension}",
                    reference.len()
                ),
            ));
        }
        if let Some((i, v)) = reference.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(Error::invalid(
                "reference",
                format!("component {i} is {v:?}: a reference must be finite"),
            ));
        }
    }
    let mut measurements = Vec::new();
    for &method in &study.methods {
        let steppings: Vec<Stepping> = if method.is_adaptive() {
            study
                .tolerances
                .iter()
                .cloned()
                .map(Stepping::Adaptive)
                .collect()
        } else {
            study.dts.iter().copied().map(Stepping::Fixed).collect()
        };
        for stepping in steppings {
            measurements.push(measure_one(
                model,
                study,
                method,
                stepping,
                reference.as_deref(),
            )?);
        }
    }
    Ok(WorkPrecisionSet {
        scene: study.scene.clone(),
        title: study.title.clone(),
        reference_error,
        measurements,
    })
}

fn check<S: State>(study: &WorkPrecision<S>) -> Result<()> {
    if study.methods.is_empty() {
        return Err(Error::invalid(
            "methods",
            "the study has no methods to compare",
        ));
    }
    if !(study.horizon.is_finite() && study.horizon > 0.0) {
        return Err(Error::invalid(
            "horizon",
            format!("must be finite and positive, got {:?}", study.horizon),
        ));
    }
    if let Some(m) = study.methods.iter().find(|m| !m.is_adaptive())
        && study.dts.is_empty()
    {
        return Err(Error::invalid(
            "dts",
            format!("{m} steps with a fixed dt, but the study has no steps to run"),
        ));
    }
    if let Some(m) = study.methods.iter().find(|m| m.is_adaptive())
        && study.tolerances.is_empty()
    {
        return Err(Error::invalid(
            "tolerances",
            format!("{m} is adaptive, but the study has no tolerances to run it at"),
        ));
    }
    if let Some(dt) = study.dts.iter().find(|dt| !(dt.is_finite() && **dt > 0.0)) {
        return Err(Error::invalid(
            "dts",
            format!("every step must be finite and positive, got {dt:?}"),
        ));
    }
    if let Some(dt) = repeated(&study.dts) {
        return Err(Error::invalid(
            "dts",
            format!("dt = {dt:?} appears twice: every step must be distinct"),
        ));
    }
    for t in &study.tolerances {
        t.check(study.initial.as_slice().len())?;
    }
    let rtols: Vec<f64> = study.tolerances.iter().map(|t| t.rtol).collect();
    if let Some(rtol) = repeated(&rtols) {
        return Err(Error::invalid(
            "tolerances",
            format!("rtol = {rtol:?} appears twice: every tolerance must be distinct"),
        ));
    }
    if !matches!(study.reference, Reference::Exact(_)) {
        for &dt in &study.dts {
            ends_at_horizon(study.horizon, dt, "dts")?;
        }
        if let Reference::Computed { dt, .. } = study.reference {
            ends_at_horizon(study.horizon, dt, "reference dt")?;
        }
    }
    Ok(())
}

fn repeated(values: &[f64]) -> Option<f64> {
    values
        .iter()
        .enumerate()
        .find(|(i, v)| values[..*i].contains(v))
        .map(|(_, v)| *v)
}

/// A reference at the horizon only compares with runs that end there.
fn ends_at_horizon(horizon: f64, dt: f64, field: &str) -> Result<()> {
    let ratio = horizon / dt;
    if (ratio - ratio.round()).abs() <= 1e-9 * ratio.round().max(1.0) {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!(
                "dt = {dt:?} does not divide the horizon {horizon:?}: the run would end at \
                 {:?}, not where the reference is; choose a dt that divides it or give an exact \
                 reference",
                ratio.ceil() * dt
            ),
        ))
    }
}

fn simulation<'m, M: Model>(
    model: &'m M,
    study: &WorkPrecision<M::State>,
    method: Method,
    stepping: &Stepping,
) -> crate::Simulation<'m, M> {
    let sim = model
        .simulate()
        .initial_state(study.initial.clone())
        .integrator(method)
        .duration(study.horizon)
        .newton(study.newton)
        .dense_output(false);
    match stepping {
        Stepping::Fixed(dt) => sim.dt(*dt),
        Stepping::Adaptive(t) => sim.with_tolerances(t.clone()),
    }
}

/// The reference final state (`None` for an exact one, which is evaluated at each run's end)
/// and its estimated error.
fn reference_final<M: Model>(
    model: &M,
    study: &WorkPrecision<M::State>,
) -> Result<(Option<Vec<f64>>, f64)> {
    match &study.reference {
        Reference::Exact(_) => Ok((None, 0.0)),
        Reference::Final(values) => Ok((Some(values.clone()), f64::NAN)),
        Reference::Computed { method, dt } => {
            let run = |dt| -> Result<Vec<f64>> {
                let sim =
                    simulation(model, study, *method, &Stepping::Fixed(dt)).record_every(u64::MAX);
                Ok(sim.run()?.last().state.as_slice().to_vec())
            };
            let (coarse, fine) = (run(*dt)?, run(0.5 * dt)?);
            Ok((Some(fine.clone()), max_difference(&coarse, &fine)))
        }
    }
}

fn measure_one<M: Model>(
    model: &M,
    study: &WorkPrecision<M::State>,
    method: Method,
    stepping: Stepping,
    reference: Option<&[f64]>,
) -> Result<Measurement> {
    let every = match stepping {
        Stepping::Fixed(dt) => {
            ((study.horizon / dt).ceil().max(1.0) as u64).div_ceil(study.samples.max(1))
        }
        Stepping::Adaptive(_) => 1,
    };
    let (recorded, failure) = simulation(model, study, method, &stepping)
        .record_every(every)
        .run_partial()?;
    let diverged = match failure {
        None => false,
        Some(
            Error::Diverged { .. }
            | Error::NewtonDidNotConverge { .. }
            | Error::StepSizeTooSmall { .. }
            | Error::MaxSteps { .. },
        ) => true,
        Some(other) => return Err(other),
    };
    let mut measurement = Measurement {
        method,
        stepping,
        error: f64::INFINITY,
        energy_error: None,
        seconds: f64::NAN,
        stats: recorded.stats,
        diverged,
    };
    if diverged {
        return Ok(measurement);
    }
    let last = recorded.last();
    measurement.error = match (&study.reference, reference) {
        (Reference::Exact(y), _) => {
            let exact = y(last.t);
            finite_reference(exact.as_slice(), last.t)?;
            max_difference(last.state.as_slice(), exact.as_slice())
        }
        (_, Some(reference)) => max_difference(last.state.as_slice(), reference),
        (_, None) => f64::NAN,
    };
    measurement.energy_error = energy_error(model, study, &recorded)?;
    let timed = simulation(model, study, method, &measurement.stepping).record_every(u64::MAX);
    for _ in 0..study.repeats.max(1) {
        let clock = Instant::now();
        let run = timed.run()?;
        let seconds = clock.elapsed().as_secs_f64();
        std::hint::black_box(run);
        measurement.seconds = if measurement.seconds.is_nan() {
            seconds
        } else {
            measurement.seconds.min(seconds)
        };
    }
    Ok(measurement)
}

fn finite_reference(values: &[f64], t: f64) -> Result<()> {
    match values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        None => Ok(()),
        Some((i, v)) => Err(Error::invalid(
            "reference",
            format!("the exact solution's component {i} is {v:?} at t = {t:?}"),
        )),
    }
}

fn energy_error<M: Model>(
    model: &M,
    study: &WorkPrecision<M::State>,
    run: &Trajectory<M::State>,
) -> Result<Option<f64>> {
    let Some(e0) = run.first().energy else {
        return Ok(None);
    };
    let exact = match &study.reference {
        Reference::Exact(y) => Some(y),
        _ => None,
    };
    let scale = e0.abs().max(f64::MIN_POSITIVE);
    let mut worst = 0.0f64;
    for s in &run.samples {
        let target = match exact {
            Some(y) => match model.energy(&y(s.t)) {
                Some(e) if e.is_finite() => e,
                Some(e) => {
                    return Err(Error::invalid(
                        "reference",
                        format!("the exact solution's energy is {e:?} at t = {:?}", s.t),
                    ));
                }
                None => return Ok(None),
            },
            None => e0,
        };
        let Some(e) = s.energy else { return Ok(None) };
        worst = nan_max(worst, (e - target).abs() / scale);
    }
    Ok(Some(worst))
}

/// The larger of two numbers, NaN if either is: a NaN error must never read as a perfect run.
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, nan_max)
}

impl WorkPrecisionSet {
    /// The measurements of one method, in the order of the study.
    pub fn of(&self, method: Method) -> impl Iterator<Item = &Measurement> {
        self.measurements.iter().filter(move |m| m.method == method)
    }

    /// For a fixed-step method, the least-squares slope of log(error) against log(dt) over its
    /// finite, non-zero errors: its observed order. `None` with fewer than two distinct such
    /// steps, and for adaptive methods (whose error follows the tolerance, not a step).
    pub fn observed_order(&self, method: Method) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .of(method)
            .filter(|m| m.error.is_finite() && m.error > 0.0)
            .filter_map(|m| Some((m.stepping.dt()?.ln(), m.error.ln())))
            .collect();
        slope(&points)
    }

    /// For an adaptive method, the least-squares slope of log(error) against log(rtol) over its
    /// finite, non-zero errors: 1 when the error follows the tolerance proportionally. `None`
    /// with fewer than two such runs, and for fixed-step methods.
    pub fn tolerance_proportionality(&self, method: Method) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .of(method)
            .filter(|m| m.error.is_finite() && m.error > 0.0)
            .filter_map(|m| Some((m.stepping.rtol()?.ln(), m.error.ln())))
            .collect();
        slope(&points)
    }

    /// Writes `scene,method,dt,rtol,atol,steps,rejected,error,energy_error,seconds,evaluations`,
    /// atomically. Evaluations count force, Jacobian and ∂f/∂t evaluations together; a failed
    /// run has an infinite error and no time.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        let rows: Vec<Vec<String>> = self
            .measurements
            .iter()
            .map(|m| {
                let (dt, rtol, atol) = match &m.stepping {
                    Stepping::Fixed(dt) => (number(*dt), String::new(), String::new()),
                    Stepping::Adaptive(t) => (
                        String::new(),
                        number(t.rtol),
                        match &t.atol {
                            crate::Atol::Scalar(a) => number(*a),
                            crate::Atol::PerComponent(_) => "per-component".to_owned(),
                        },
                    ),
                };
                vec![
                    self.scene.clone(),
                    m.method.name().to_owned(),
                    dt,
                    rtol,
                    atol,
                    m.stats.steps.to_string(),
                    m.stats.rejected.to_string(),
                    number(m.error),
                    m.energy_error.map_or_else(String::new, number),
                    number(m.seconds),
                    m.evaluations().to_string(),
                ]
            })
            .collect();
        let header = [
            "scene",
            "method",
            "dt",
            "rtol",
            "atol",
            "steps",
            "rejected",
            "error",
            "energy_error",
            "seconds",
            "evaluations",
        ];
        write_table(path, &header, &rows)
    }

    /// Draws `accuracy` against `cost`, log-log, one line per method with a marker per run, as
    /// PNG or SVG, titled with the study's title and a note that lower left is better. In an
    /// SVG each marker shows its run's dt or rtol, error and cost on hover. Failed runs, and
    /// runs without the chosen error, are left out.
    #[cfg(feature = "plot")]
    pub fn plot(&self, path: impl AsRef<Path>, accuracy: Accuracy, cost: Cost) -> Result<()> {
        use crate::plot::{Chart, Series};
        let mut methods: Vec<Method> = Vec::new();
        for m in &self.measurements {
            if !methods.contains(&m.method) {
                methods.push(m.method);
            }
        }
        let series = methods
            .into_iter()
            .map(|method| {
                let (points, notes): (Vec<_>, Vec<_>) = self
                    .of(method)
                    .filter(|m| !m.diverged)
                    .filter_map(|m| {
                        let error = match accuracy {
                            Accuracy::FinalState => m.error,
                            Accuracy::Energy => m.energy_error?,
                        };
                        let (work, spent) = match cost {
                            Cost::Seconds => (m.seconds, format!("{:.3e} s", m.seconds)),
                            Cost::Evaluations => {
                                let n = m.evaluations();
                                (n as f64, format!("{n} evaluations"))
                            }
                        };
                        let stepping = match &m.stepping {
                            Stepping::Fixed(dt) => format!("dt = {dt:e}"),
                            Stepping::Adaptive(t) => match &t.atol {
                                crate::Atol::Scalar(atol) => {
                                    format!("rtol = {:e}, atol = {atol:e}", t.rtol)
                                }
                                crate::Atol::PerComponent(_) => format!("rtol = {:e}", t.rtol),
                            },
                        };
                        let note = format!("{stepping}: error {error:.2e}, {spent}");
                        Some(((error, work), note))
                    })
                    .unzip();
                let kind = if method.is_adaptive() {
                    " (rtol)"
                } else {
                    " (dt)"
                };
                Series::line_and_markers(format!("{}{kind}", method.label()), points)
                    .with_notes(notes)
            })
            .collect();
        let (what, unit) = match cost {
            Cost::Seconds => ("time", "wall time (s)"),
            Cost::Evaluations => ("evaluations", "f + J evaluations"),
        };
        let error = match accuracy {
            Accuracy::FinalState => "final-state error",
            Accuracy::Energy => "max relative energy error",
        };
        Chart {
            title: format!("{}: {error} against {what}", self.title),
            note: "lower left is better: more accurate for less work".to_owned(),
            x_label: error.to_owned(),
            y_label: unit.to_owned(),
            log_x: true,
            log_y: true,
            series,
        }
        .write(path, (1000, 640))
    }
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

/// Least-squares slope of y against x; `None` with fewer than two distinct x.
fn slope(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let cov: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let var: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    (var > 0.0).then(|| cov / var)
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
