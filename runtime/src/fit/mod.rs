//! Parameter estimation: the `#[param]` parameters that make a model's solution fit measured
//! samples, by Levenberg–Marquardt on weighted least squares with the residuals' Jacobian from
//! the forward sensitivities ([`crate::sensitivity`]) — no finite differences.
//!
//! Minimises ½ Σₖ wₖ² (y_c(tₖ; p) − dₖ)² (summed over every measured component c) over p (or over q = ln p for positive parameters, the
//! usual way of fitting rates spread over orders of magnitude). Each iteration solves
//! (JᵀJ + λ·diag(JᵀJ))·δ = −Jᵀr (Marquardt's scaling: Marquardt, SIAM J. Appl. Math. 11 (1963)
//! 431; Moré, "The Levenberg–Marquardt algorithm: implementation and theory", LNM 630 (1978)),
//! accepts δ when it lowers the cost, and updates λ by Nielsen's rule (H. B. Nielsen, "Damping
//! parameter in Marquardt's method", IMM-REP-1999-05: λ ← λ·max(1/3, 1 − (2ρ − 1)³) on a gain
//! ratio ρ > 0, else λ ← λ·ν, ν ← 2ν). The standard errors come from the Gauss–Newton
//! covariance σ²(JᵀJ)⁻¹, σ² = 2·cost/(m − n).
//!
//! Why not a crate: `levenberg-marquardt` 0.15 is built on nalgebra 0.34 (odyn on 0.35: a second
//! nalgebra in every build and conversions at the boundary), and argmin's least-squares solvers
//! need their own math backend crate per nalgebra version; the method itself is the ~65 lines
//! of `levenberg_marquardt` below.

mod check;
mod marquardt;

use crate::Simulate;
use nalgebra::{DMatrix, DVector};

use crate::sensitivity::{Sensitive, SensitivityState};
use crate::{DenseMatrix, Error, Jacobian, Method, Parameters, Result, Sample};

/// Measured samples of one state component: `(t, value)` pairs, with optional weights
/// (1/σ of each measurement; all 1 when empty). A fit takes one per measured component.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Data {
    /// The state component measured (its index in the state's layout).
    pub component: usize,
    /// The sample times, increasing, at or after the model's start.
    pub times: Vec<f64>,
    /// The measured values.
    pub values: Vec<f64>,
    /// The weight of each sample (empty: all 1).
    pub weights: Vec<f64>,
}

/// How a fit runs.
#[derive(Clone, Debug, PartialEq)]
pub struct FitOptions {
    /// The integrator of the model and its sensitivities (default DOP853; for stiff models
    /// Rodas5P, Rosenbrock23 or BDF, on the augmented Jacobian).
    pub integrator: Method,
    /// Its relative and absolute tolerance (default 1e-10, 1e-12: the fit cannot be more
    /// accurate than the solves its residuals come from). The sensitivities ∂y/∂pⱼ are held
    /// to atol/|pⱼ| (CVODES's rule with p̄ = p; `Sensitive::tolerances`).
    pub rtol: f64,
    /// The absolute tolerance (default 1e-12); see [`FitOptions::rtol`].
    pub atol: f64,
    /// Whether the sensitivities count in the solves' error test (default true, CVODES's
    /// default); false sizes the steps for the state alone (`Sensitive::tolerances`).
    pub sensitivities_in_error_test: bool,
    /// Fit ln p instead of p for every parameter (they must then be positive; default false).
    pub log_parameters: bool,
    /// The most iterations (default 100).
    pub max_iterations: usize,
    /// Stop when a step (accepted or not) changes no parameter by more than this, relatively
    /// (default 1e-8: well above the solves' own error).
    pub step_tolerance: f64,
    /// Stop when an accepted step lowers the cost by less than this, relatively (default 1e-12).
    pub cost_tolerance: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            integrator: Method::Dop853,
            rtol: 1e-10,
            atol: 1e-12,
            sensitivities_in_error_test: true,
            log_parameters: false,
            max_iterations: 100,
            step_tolerance: 1e-8,
            cost_tolerance: 1e-12,
        }
    }
}

/// What a fit found.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// The fitted parameters, in the order of [`Parameters::NAMES`].
    pub parameters: Vec<f64>,
    /// Their standard errors from the Gauss–Newton covariance (for log-parameters, of p by the
    /// delta method, p·σ(ln p)).
    pub standard_errors: Vec<f64>,
    /// ½ Σ wₖ² rₖ² at the fitted parameters.
    pub cost: f64,
    /// ½ Σ wₖ² rₖ² at the initial guess.
    pub initial_cost: f64,
    /// Iterations taken (each one model solve with sensitivities, more when a step is rejected).
    pub iterations: usize,
    /// Model solves (with sensitivities) in all.
    pub solves: usize,
    /// m − n: the samples of non-zero weight less the parameters.
    pub degrees_of_freedom: usize,
    /// The reduced χ², 2·cost/(m − n) (NaN without degrees of freedom). With weights 1/σᵢ of
    /// independent normal errors it is near 1 at the best fit; see [`Fit::consistent`].
    pub reduced_chi_squared: f64,
}

impl Fit {
    /// Whether the fit is consistent with weights that are 1/σ of each sample's error: 2·cost
    /// then follows a χ² distribution of ν = m − n degrees of freedom, whose mean is ν and
    /// standard deviation √(2ν), so the rule is reduced χ² ≤ 1 + 3·√(2/ν) (three standard
    /// deviations; the χ²'s own upper tail is heavier for small ν, so the rule is strict there).
    /// False at a local minimum that fits the data worse than its noise explains — try other
    /// starting guesses, fit log-parameters, or start closer. Meaningless unless the weights are
    /// 1/σ (with the default weights 1, compare `reduced_chi_squared` with σ² instead).
    pub fn consistent(&self) -> bool {
        let nu = self.degrees_of_freedom as f64;
        self.degrees_of_freedom > 0 && self.reduced_chi_squared <= 1.0 + 3.0 * (2.0 / nu).sqrt()
    }
}

/// Fits the `#[param]` parameters of `model` (its values are the initial guess) to `data`: one
/// [`Data`] per measured state component, their residuals weighed together.
///
/// The model must be `Clone` (`#[derive(Clone)]` on its struct): each trial of the search is a
/// copy with its own parameters. Check [`Fit::consistent`] (with weights 1/σ) before trusting
/// the result: a fit converges to the nearest minimum of the cost, which need not be the best
/// one.
///
/// # Errors
///
/// [`Error::InvalidInput`] for data that cannot be fitted (unequal lengths, times not
/// increasing or before the start, a component out of range, non-finite values or weights,
/// negative weights, fewer samples of non-zero weight than parameters, a non-positive parameter
/// with `log_parameters`) and for options that cannot be met (a fixed-step method, a tolerance
/// that is not finite and positive); [`Error::FitStart`] when the model cannot be solved at the
/// initial guess or its cost there is not finite; [`Error::FitDidNotConverge`] when the
/// iterations run out.
pub fn fit<M>(model: &M, data: &[Data], options: &FitOptions) -> Result<Fit>
where
    M: Parameters + Jacobian + Clone,
    M::Matrix: DenseMatrix,
{
    check::check(model, data, options)?;
    let mut times: Vec<f64> = data.iter().flat_map(|d| d.times.iter().copied()).collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    let guess = model.parameters();
    let to_search = |p: &[f64]| -> Vec<f64> {
        if options.log_parameters {
            p.iter().map(|v| v.ln()).collect()
        } else {
            p.to_vec()
        }
    };
    let from_search = |q: &[f64]| -> Vec<f64> {
        if options.log_parameters {
            q.iter().map(|v| v.exp()).collect()
        } else {
            q.to_vec()
        }
    };
    let mut solves = 0;
    let mut residuals = |q: &DVector<f64>| -> Result<(DVector<f64>, DMatrix<f64>)> {
        solves += 1;
        let p = from_search(q.as_slice());
        let mut trial = model.clone();
        trial.set_parameters(&p)?;
        let (r, mut jacobian) = residuals_and_jacobian(&trial, data, &times, options)?;
        if options.log_parameters {
            for (j, pj) in p.iter().enumerate() {
                jacobian.column_mut(j).scale_mut(*pj);
            }
        }
        Ok((r, jacobian))
    };
    let q0 = DVector::from_vec(to_search(&guess));
    let start = residuals(&q0).map_err(|error| start_error::<M>(&guess, solve_problem(&error)))?;
    if !start.0.norm_squared().is_finite() {
        // The residual whose square overflows (or is not finite itself).
        let k = start.0.iamax();
        let (set, sample) = locate(data, k);
        let problem = format!(
            "the cost is not finite: the weighted residual of data set {set}, sample {sample} \
             (t = {:e}, value {:e}) is {:?}",
            data[set].times[sample], data[set].values[sample], start.0[k]
        );
        return Err(start_error::<M>(&guess, problem));
    }
    let result = marquardt::levenberg_marquardt(&mut residuals, q0, start, options)?;
    let p = from_search(result.q.as_slice());
    let standard_errors = result
        .standard_errors
        .iter()
        .zip(&p)
        .map(|(s, pj)| if options.log_parameters { s * pj } else { *s })
        .collect();
    let weighted: usize = data
        .iter()
        .map(|d| match d.weights.is_empty() {
            true => d.times.len(),
            false => d.weights.iter().filter(|&&w| w > 0.0).count(),
        })
        .sum();
    let degrees_of_freedom = weighted.saturating_sub(M::NAMES.len());
    Ok(Fit {
        parameters: p,
        standard_errors,
        cost: result.cost,
        initial_cost: result.initial_cost,
        iterations: result.iterations,
        solves,
        degrees_of_freedom,
        reduced_chi_squared: if degrees_of_freedom > 0 {
            2.0 * result.cost / degrees_of_freedom as f64
        } else {
            f64::NAN
        },
    })
}

/// (data set, sample) of residual `k`, the residuals being every data set's in order.
fn locate(data: &[Data], mut k: usize) -> (usize, usize) {
    for (set, d) in data.iter().enumerate() {
        if k < d.times.len() {
            return (set, k);
        }
        k -= d.times.len();
    }
    unreachable!("a residual index within the data")
}

/// [`Error::FitStart`] at `guess`.
fn start_error<M: Parameters>(guess: &[f64], problem: String) -> Error {
    let parameters = M::NAMES
        .iter()
        .zip(guess)
        .map(|(name, value)| format!("{name} = {value:e}"))
        .collect::<Vec<_>>()
        .join(", ");
    Error::FitStart {
        parameters,
        problem,
    }
}

/// What went wrong in a solve, in the fit's terms: the step-size advice of a run's error is for
/// a run, which a fit does not size by hand.
fn solve_problem(error: &Error) -> String {
    match error {
        Error::Diverged {
            t,
            component,
            value,
            ..
        } => format!("its solution blows up: `{component}` = {value:e} at t = {t:?}"),
        Error::StepSizeTooSmall { t, dt, .. } => {
            format!("its solve's step size fell to {dt:e} at t = {t:?}")
        }
        Error::MaxSteps { t, steps, .. } => {
            format!("its solve used up its {steps} steps by t = {t:?}")
        }
        other => format!("its solve failed ({other})"),
    }
}

/// The weighted residuals wₖ·(y_c(tₖ) − dₖ) of every data set, one after the other, and their
/// Jacobian wₖ·∂y_c(tₖ)/∂p, from one solve saving at `times` (every data set's, merged, sorted
/// and without repeats).
fn residuals_and_jacobian<M>(
    model: &M,
    data: &[Data],
    times: &[f64],
    options: &FitOptions,
) -> Result<(DVector<f64>, DMatrix<f64>)>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
    let sensitive = Sensitive::new(model);
    let end = *times.last().expect("checked: at least one sample");
    let tolerances = sensitive.tolerances(
        options.rtol,
        options.atol,
        options.sensitivities_in_error_test,
    );
    let run = sensitive
        .simulate()
        .integrator(options.integrator)
        .with_tolerances(tolerances)
        .duration(end)
        .save_at(times)
        .dense_output(false)
        .run()?;
    let samples = at_times(&run.samples, times)?;
    let m: usize = data.iter().map(|d| d.times.len()).sum();
    let p = M::NAMES.len();
    let mut r = DVector::zeros(m);
    let mut jacobian = DMatrix::zeros(m, p);
    let mut row = 0;
    for data in data {
        for (k, &t) in data.times.iter().enumerate() {
            let index = times.partition_point(|&s| s < t);
            let sample = samples[index];
            let w = data.weights.get(k).copied().unwrap_or(1.0);
            r[row] = w * (sample.state.state()[data.component] - data.values[k]);
            let s = sample.state.sensitivities();
            for j in 0..p {
                jacobian[(row, j)] = w * s[(data.component, j)];
            }
            row += 1;
        }
    }
    Ok((r, jacobian))
}

/// The sample recorded at each of `times` (sorted, no repeats), by exact time: `save_at`
/// records each at exactly its time, and t₀ is the initial sample. Matching by nearness would
/// read one sample for data spaced closer than the nearness (the fourth hardening probe: ten
/// samples between 1e-10 and 1e-9 all read the one at 5e-10).
fn at_times<'s>(
    samples: &'s [Sample<SensitivityState>],
    times: &[f64],
) -> Result<Vec<&'s Sample<SensitivityState>>> {
    let mut rest = samples;
    times
        .iter()
        .map(|&t| {
            let skip = rest.partition_point(|s| s.t < t);
            rest = &rest[skip..];
            match rest.first() {
                Some(sample) if sample.t == t => Ok(sample),
                _ => Err(Error::invalid(
                    "fit data",
                    format!("the solve recorded no sample at t = {t:?}, a time of the data"),
                )),
            }
        })
        .collect()
}
