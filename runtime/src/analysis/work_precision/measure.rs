//! [`measure`]: the study checked, the reference computed, every method run once per stepping
//! and timed.

use crate::Simulate;
use std::time::Instant;

use super::*;
use crate::{Error, Method, Model, Result, State, Stepping, Trajectory};

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
