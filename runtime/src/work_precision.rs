//! Work-precision: how much accuracy each method buys for how much work, on one model.
//!
//! For every method and step, [`measure`] runs the model over a horizon and records the
//! final-state error against a reference, the largest energy error along the way, the wall time
//! (the minimum of several repeats) and the force and Jacobian evaluations. The chart follows
//! DifferentialEquations.jl's `WorkPrecisionSet` (DiffEqDevTools): error on the horizontal axis,
//! cost on the vertical one, both logarithmic, one line per method; lower-left is better.

use std::path::Path;
use std::time::Instant;

use crate::output::{number, write_table};
use crate::{Error, Method, Model, NewtonOptions, Result, State};

/// What a run's final state is compared with.
pub enum Reference<S> {
    /// The exact solution y(t) (the energy error then compares with its energy, too).
    Exact(Box<dyn Fn(f64) -> S>),
    /// A known final state y(horizon), component by component (from another solver or a paper).
    Final(Vec<f64>),
    /// A run of `method` at `dt`; its own error is estimated against a run at `dt/2` and reported
    /// as [`WorkPrecisionSet::reference_error`].
    Computed {
        /// The method of the reference run.
        method: Method,
        /// Its step.
        dt: f64,
    },
}

/// A work-precision study: one model, one horizon, several methods and steps.
pub struct WorkPrecision<S> {
    /// Name of the scene, the first CSV column.
    pub scene: String,
    /// The initial state.
    pub initial: S,
    /// Final time (the runs start at 0).
    pub horizon: f64,
    /// The methods to compare.
    pub methods: Vec<Method>,
    /// The steps to run each method at.
    pub dts: Vec<f64>,
    /// What errors are measured against.
    pub reference: Reference<S>,
    /// Timed repeats of each run; the minimum time is kept (default 3).
    pub repeats: u32,
    /// At most this many samples are recorded for the energy error (default 100 000).
    pub samples: u64,
    /// Newton's method for implicit runs.
    pub newton: NewtonOptions,
}

impl<S: State> WorkPrecision<S> {
    /// A study with the default repeats, samples and Newton options.
    pub fn new(
        scene: impl Into<String>,
        initial: S,
        horizon: f64,
        methods: Vec<Method>,
        dts: Vec<f64>,
        reference: Reference<S>,
    ) -> Self {
        WorkPrecision {
            scene: scene.into(),
            initial,
            horizon,
            methods,
            dts,
            reference,
            repeats: 3,
            samples: 100_000,
            newton: NewtonOptions::default(),
        }
    }
}

/// One run of a study.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The method.
    pub method: Method,
    /// The step.
    pub dt: f64,
    /// Steps taken.
    pub steps: u64,
    /// Max-norm of the final state's error; infinite when the run diverged.
    pub error: f64,
    /// Largest |E(t) − E_ref(t)| / |E_ref(0)| over the recorded samples, where E_ref is the exact
    /// solution's energy for an exact reference and E(0) otherwise; `None` without `fn energy`.
    pub energy_error: Option<f64>,
    /// Wall time of the run without recording, the minimum over the repeats; NaN if diverged.
    pub seconds: f64,
    /// Force (derivative or acceleration) evaluations.
    pub evaluations: u64,
    /// Jacobian evaluations.
    pub jacobian_evaluations: u64,
    /// Whether the run stopped with [`Error::Diverged`] or a failed Newton solve.
    pub diverged: bool,
}

/// The result of [`measure`].
#[derive(Clone, Debug, PartialEq)]
pub struct WorkPrecisionSet {
    /// The scene.
    pub scene: String,
    /// The estimated error of the reference itself: 0 for an exact one, NaN when unknown (a
    /// given final state), the max-norm difference between the dt and dt/2 runs for a computed one.
    pub reference_error: f64,
    /// One entry per method and step, in the order of the study.
    pub measurements: Vec<Measurement>,
}

/// Runs a work-precision study.
///
/// Errors: [`Error::InvalidInput`] for no methods, no steps, a step that is not finite and
/// positive, a horizon that is not, or a reference whose dimension differs from the state's;
/// [`Error::Unsupported`] when a method cannot integrate the model. A run that diverges is a
/// measurement with an infinite error, not an error.
pub fn measure<M: Model>(model: &M, study: &WorkPrecision<M::State>) -> Result<WorkPrecisionSet> {
    if study.methods.is_empty() {
        return Err(Error::invalid(
            "methods",
            "the study has no methods to compare",
        ));
    }
    if study.dts.is_empty() {
        return Err(Error::invalid("dts", "the study has no steps to run"));
    }
    if let Some(dt) = study.dts.iter().find(|dt| !(dt.is_finite() && **dt > 0.0)) {
        return Err(Error::invalid(
            "dts",
            format!("every step must be finite and positive, got {dt}"),
        ));
    }
    if !(study.horizon.is_finite() && study.horizon > 0.0) {
        return Err(Error::invalid(
            "horizon",
            format!("must be finite and positive, got {}", study.horizon),
        ));
    }
    let dimension = study.initial.as_slice().len();
    let (reference, reference_error) = reference_final(model, study)?;
    if reference.len() != dimension {
        return Err(Error::invalid(
            "reference",
            format!(
                "has {} components but the state has {dimension}",
                reference.len()
            ),
        ));
    }
    let mut measurements = Vec::with_capacity(study.methods.len() * study.dts.len());
    for &method in &study.methods {
        for &dt in &study.dts {
            measurements.push(measure_one(model, study, method, dt, &reference)?);
        }
    }
    Ok(WorkPrecisionSet {
        scene: study.scene.clone(),
        reference_error,
        measurements,
    })
}

fn simulation<'m, M: Model>(
    model: &'m M,
    study: &WorkPrecision<M::State>,
    method: Method,
    dt: f64,
) -> crate::Simulation<'m, M> {
    model
        .simulate()
        .initial_state(study.initial.clone())
        .integrator(method)
        .dt(dt)
        .duration(study.horizon)
        .newton(study.newton)
}

fn reference_final<M: Model>(
    model: &M,
    study: &WorkPrecision<M::State>,
) -> Result<(Vec<f64>, f64)> {
    match &study.reference {
        Reference::Exact(y) => Ok((y(study.horizon).as_slice().to_vec(), 0.0)),
        Reference::Final(values) => Ok((values.clone(), f64::NAN)),
        Reference::Computed { method, dt } => {
            let run = |dt| -> Result<Vec<f64>> {
                let sim = simulation(model, study, *method, dt).record_every(u64::MAX);
                Ok(sim.run()?.last().state.as_slice().to_vec())
            };
            let (coarse, fine) = (run(*dt)?, run(0.5 * dt)?);
            Ok((fine.clone(), max_difference(&coarse, &fine)))
        }
    }
}

fn measure_one<M: Model>(
    model: &M,
    study: &WorkPrecision<M::State>,
    method: Method,
    dt: f64,
    reference: &[f64],
) -> Result<Measurement> {
    let steps_estimate = (study.horizon / dt).ceil().max(1.0) as u64;
    let every = steps_estimate.div_ceil(study.samples.max(1));
    let (recorded, failure) = simulation(model, study, method, dt)
        .record_every(every)
        .run_partial()?;
    let diverged = match failure {
        None => false,
        Some(Error::Diverged { .. } | Error::NewtonDidNotConverge { .. }) => true,
        Some(other) => return Err(other),
    };
    let energy_error = if diverged {
        None
    } else {
        energy_error(model, study, &recorded)
    };
    let mut measurement = Measurement {
        method,
        dt,
        steps: recorded.steps,
        error: f64::INFINITY,
        energy_error,
        seconds: f64::NAN,
        evaluations: recorded.evaluations,
        jacobian_evaluations: recorded.jacobian_evaluations,
        diverged,
    };
    if diverged {
        return Ok(measurement);
    }
    measurement.error = max_difference(recorded.last().state.as_slice(), reference);
    let timed = simulation(model, study, method, dt).record_every(u64::MAX);
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

fn energy_error<M: Model>(
    model: &M,
    study: &WorkPrecision<M::State>,
    run: &crate::Trajectory<M::State>,
) -> Option<f64> {
    let e0 = run.first().energy?;
    let exact = match &study.reference {
        Reference::Exact(y) => Some(y),
        _ => None,
    };
    let scale = e0.abs().max(f64::MIN_POSITIVE);
    let worst = run.samples.iter().filter_map(|s| {
        let target = match exact {
            Some(y) => model.energy(&y(s.t))?,
            None => e0,
        };
        Some((s.energy? - target).abs() / scale)
    });
    Some(worst.fold(0.0, f64::max))
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

impl WorkPrecisionSet {
    /// The measurements of one method, in step order.
    pub fn of(&self, method: Method) -> impl Iterator<Item = &Measurement> {
        self.measurements.iter().filter(move |m| m.method == method)
    }

    /// The least-squares slope of log(error) against log(dt) for `method` over its finite,
    /// non-zero errors: its observed order. `None` with fewer than two such points.
    pub fn observed_order(&self, method: Method) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .of(method)
            .filter(|m| m.error.is_finite() && m.error > 0.0)
            .map(|m| (m.dt.ln(), m.error.ln()))
            .collect();
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
        Some(cov / var)
    }

    /// Writes `scene,method,dt,steps,error,energy_error,seconds,evaluations`, atomically.
    /// Evaluations count force and Jacobian evaluations together; a diverged run has an
    /// infinite error and no time.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        let rows: Vec<Vec<String>> = self
            .measurements
            .iter()
            .map(|m| {
                vec![
                    self.scene.clone(),
                    m.method.name().to_owned(),
                    number(m.dt),
                    m.steps.to_string(),
                    number(m.error),
                    m.energy_error.map_or_else(String::new, number),
                    number(m.seconds),
                    (m.evaluations + m.jacobian_evaluations).to_string(),
                ]
            })
            .collect();
        let header = [
            "scene",
            "method",
            "dt",
            "steps",
            "error",
            "energy_error",
            "seconds",
            "evaluations",
        ];
        write_table(path, &header, &rows)
    }

    /// Draws `accuracy` against `cost`, log-log, one line per method, as PNG or SVG. Diverged
    /// runs, and runs without the chosen error, are left out.
    #[cfg(feature = "plot")]
    pub fn plot(&self, path: impl AsRef<Path>, accuracy: Accuracy, cost: Cost) -> Result<()> {
        use crate::plot::{Chart, Legend, Series};
        let mut methods: Vec<Method> = Vec::new();
        for m in &self.measurements {
            if !methods.contains(&m.method) {
                methods.push(m.method);
            }
        }
        let series = methods
            .into_iter()
            .map(|method| {
                let points = self
                    .of(method)
                    .filter(|m| !m.diverged)
                    .filter_map(|m| {
                        let error = match accuracy {
                            Accuracy::FinalState => m.error,
                            Accuracy::Energy => m.energy_error?,
                        };
                        Some(match cost {
                            Cost::Seconds => (error, m.seconds),
                            Cost::Evaluations => {
                                (error, (m.evaluations + m.jacobian_evaluations) as f64)
                            }
                        })
                    })
                    .collect();
                Series::line(method.label(), points)
            })
            .collect();
        let (what, unit) = match cost {
            Cost::Seconds => ("time", "wall time (s)"),
            Cost::Evaluations => ("evaluations", "force + Jacobian evaluations"),
        };
        let error = match accuracy {
            Accuracy::FinalState => "final-state error",
            Accuracy::Energy => "max relative energy error",
        };
        Chart {
            title: format!("{}: {error} against {what}", self.scene),
            x_label: error.to_owned(),
            y_label: unit.to_owned(),
            log_x: true,
            log_y: true,
            series,
            legend: Legend::UpperRight,
        }
        .write(path, (960, 640))
    }
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
