//! What a fit refuses before it solves anything: data that cannot be fitted and options that
//! cannot be met.

use super::{Data, FitOptions};
use crate::{Error, Parameters, Result, State};

/// Checks the data against the model and the options.
///
/// Errors: [`Error::InvalidInput`] naming the data set and sample, or the option.
pub(super) fn check<M: Parameters>(model: &M, data: &[Data], options: &FitOptions) -> Result<()> {
    check_options(options)?;
    let n = model.state().as_slice().len();
    let reject = |reason: String| Err(Error::invalid("fit data", reason));
    for (i, data) in data.iter().enumerate() {
        let m = data.times.len();
        if data.values.len() != m || !(data.weights.is_empty() || data.weights.len() == m) {
            return reject(format!(
                "data set {i}: {m} times, {} values and {} weights; give one value (and \
                 weight, if any) per time",
                data.values.len(),
                data.weights.len()
            ));
        }
        if data.component >= n {
            return reject(format!(
                "data set {i}: component {} of a state of {n} components",
                data.component
            ));
        }
        if data.times.iter().any(|t| !t.is_finite()) || data.times.windows(2).any(|w| w[1] <= w[0])
        {
            return reject(format!(
                "data set {i}: the times must be finite and increasing"
            ));
        }
        if let Some(k) = data.values.iter().position(|v| !v.is_finite()) {
            return reject(format!(
                "data set {i}: value {k} is {:?}; every value must be finite",
                data.values[k]
            ));
        }
        if let Some(k) = data
            .weights
            .iter()
            .position(|w| !(w.is_finite() && *w >= 0.0))
        {
            return reject(format!(
                "data set {i}: weight {k} is {:?}; weights must be finite and non-negative",
                data.weights[k]
            ));
        }
        if data.times.first().is_some_and(|&t| t < 0.0) {
            return reject(format!(
                "data set {i}: the first sample is at t = {}, before the model's start at t = 0",
                data.times[0]
            ));
        }
    }
    // Samples that count: a zero weight removes a sample from the fit.
    let weighted: usize = data
        .iter()
        .map(|d| match d.weights.is_empty() {
            true => d.times.len(),
            false => d.weights.iter().filter(|&&w| w > 0.0).count(),
        })
        .sum();
    let p = M::NAMES.len();
    if weighted < p {
        let all: usize = data.iter().map(|d| d.times.len()).sum();
        return reject(if all > weighted {
            format!(
                "{weighted} samples of non-zero weight ({all} in all) for {p} parameters: a \
                 zero weight removes a sample, and a fit needs at least one per parameter"
            )
        } else {
            format!("{all} samples for {p} parameters: a fit needs at least one per parameter")
        });
    }
    if options.log_parameters && model.parameters().iter().any(|p| p.is_nan() || *p <= 0.0) {
        return reject(format!(
            "log-parameters need positive initial values; got {:?} for {:?}",
            model.parameters(),
            M::NAMES
        ));
    }
    Ok(())
}

/// Checks every option of a fit.
///
/// Errors: [`Error::InvalidInput`] naming the option: a fixed-step method (a fit has no `dt` to
/// give it), tolerances that are not finite and positive, no iterations.
fn check_options(options: &FitOptions) -> Result<()> {
    if !options.integrator.is_adaptive() {
        return Err(Error::invalid(
            "FitOptions::method",
            format!(
                "{} steps at a fixed dt, which a fit cannot give it; a fit's solves are adaptive, \
                 to rtol and atol: use Dop853 or Tsit5, or Rodas5P, Rosenbrock23 or Bdf for a \
                 stiff model",
                options.integrator.name()
            ),
        ));
    }
    let positive = [
        ("FitOptions::rtol", options.rtol),
        ("FitOptions::atol", options.atol),
        ("FitOptions::step_tolerance", options.step_tolerance),
        ("FitOptions::cost_tolerance", options.cost_tolerance),
    ];
    for (field, value) in positive {
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::invalid(
                field,
                format!("must be finite and positive, got {value:?}"),
            ));
        }
    }
    if options.max_iterations == 0 {
        return Err(Error::invalid(
            "FitOptions::max_iterations",
            "must be at least 1",
        ));
    }
    Ok(())
}
