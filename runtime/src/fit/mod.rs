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

use nalgebra::{DMatrix, DVector};

use crate::sensitivity::Sensitive;
use crate::{DenseMatrix, Error, Jacobian, Method, Model, Parameters, Result, State};

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
    pub method: Method,
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
            method: Method::Dop853,
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
}

/// Fits the `#[param]` parameters of `model` (its values are the initial guess) to `data`: one
/// [`Data`] per measured state component, their residuals weighed together.
///
/// # Errors
///
/// [`Error::InvalidInput`] for data that cannot be fitted (unequal lengths, times not
/// increasing or before the start, a component out of range, fewer samples than parameters, a
/// non-positive parameter with `log_parameters`); [`Error::FitDidNotConverge`] when the
/// iterations run out; any error of the solves.
pub fn fit<M>(model: &M, data: &[Data], options: &FitOptions) -> Result<Fit>
where
    M: Parameters + Jacobian + Clone,
    M::Matrix: DenseMatrix,
{
    check(model, data, options)?;
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
    let result = levenberg_marquardt(&mut residuals, q0, options)?;
    let p = from_search(result.q.as_slice());
    let standard_errors = result
        .standard_errors
        .iter()
        .zip(&p)
        .map(|(s, pj)| if options.log_parameters { s * pj } else { *s })
        .collect();
    Ok(Fit {
        parameters: p,
        standard_errors,
        cost: result.cost,
        initial_cost: result.initial_cost,
        iterations: result.iterations,
        solves,
    })
}

fn check<M: Parameters>(model: &M, data: &[Data], options: &FitOptions) -> Result<()> {
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
    let m: usize = data.iter().map(|d| d.times.len()).sum();
    if m < M::NAMES.len() {
        return reject(format!(
            "{m} samples for {} parameters: a fit needs at least one sample per parameter",
            M::NAMES.len()
        ));
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

/// The weighted residuals wₖ·(y_c(tₖ) − dₖ) of every data set, one after the other, and their
/// Jacobian wₖ·∂y_c(tₖ)/∂p, from one solve saving at `times` (every data set's, merged).
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
        .integrator(options.method)
        .with_tolerances(tolerances)
        .duration(end)
        .save_at(times)
        .dense_output(false)
        .run()?;
    let m: usize = data.iter().map(|d| d.times.len()).sum();
    let p = M::NAMES.len();
    let mut r = DVector::zeros(m);
    let mut jacobian = DMatrix::zeros(m, p);
    let mut row = 0;
    for data in data {
        for (k, &t) in data.times.iter().enumerate() {
            let sample = if t == 0.0 {
                run.first()
            } else {
                run.sample_at(t)?
            };
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

/// r and ∂r/∂q at q.
type Residuals<'a> = dyn FnMut(&DVector<f64>) -> Result<(DVector<f64>, DMatrix<f64>)> + 'a;

/// The minimiser's result in the search variables.
struct Minimum {
    q: DVector<f64>,
    cost: f64,
    initial_cost: f64,
    iterations: usize,
    standard_errors: Vec<f64>,
}

/// Levenberg–Marquardt with Marquardt's diagonal scaling and Nielsen's damping update, on
/// `residuals` (r and ∂r/∂q at q) from `q`.
fn levenberg_marquardt(
    residuals: &mut Residuals<'_>,
    mut q: DVector<f64>,
    options: &FitOptions,
) -> Result<Minimum> {
    let (mut r, mut jacobian) = residuals(&q)?;
    let mut cost = 0.5 * r.norm_squared();
    let initial_cost = cost;
    let (mut lambda, mut nu) = (1e-3, 2.0);
    for iteration in 1..=options.max_iterations {
        let normal = jacobian.tr_mul(&jacobian);
        let gradient = jacobian.tr_mul(&r);
        let mut damped = normal.clone();
        for i in 0..q.len() {
            damped[(i, i)] += lambda * normal[(i, i)].max(1e-300);
        }
        let Some(step) = damped.cholesky().map(|c| c.solve(&-&gradient)) else {
            lambda *= nu;
            nu *= 2.0;
            continue;
        };
        // A step this small, taken or not, changes nothing the solves can resolve: done.
        if small(&step, &q, options.step_tolerance) {
            return Ok(minimum(q, &jacobian, cost, initial_cost, iteration));
        }
        let trial = &q + &step;
        let outcome = residuals(&trial);
        let accepted = match outcome {
            Ok((r_new, j_new)) => {
                let new_cost = 0.5 * r_new.norm_squared();
                // The decrease the linear model predicts: ½δᵀ(λ·D·δ − g).
                let scaled: f64 = (0..q.len())
                    .map(|i| lambda * normal[(i, i)] * step[i] * step[i])
                    .sum();
                let predicted = 0.5 * (scaled - step.dot(&gradient));
                let rho = (cost - new_cost) / predicted.max(f64::MIN_POSITIVE);
                if new_cost.is_finite() && new_cost < cost && rho > 0.0 {
                    let decrease = cost - new_cost;
                    q = trial;
                    (r, jacobian) = (r_new, j_new);
                    cost = new_cost;
                    lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                    nu = 2.0;
                    if decrease <= options.cost_tolerance * cost || cost == 0.0 {
                        return Ok(minimum(q, &jacobian, cost, initial_cost, iteration));
                    }
                    true
                } else {
                    false
                }
            }
            // A trial so far off that its solve failed: shorten the step.
            Err(_) => false,
        };
        if !accepted {
            lambda *= nu;
            nu *= 2.0;
        }
    }
    Err(Error::FitDidNotConverge {
        iterations: options.max_iterations,
        cost,
    })
}

/// Whether every component of `step` is within `tolerance` of `q`'s, relatively.
fn small(step: &DVector<f64>, q: &DVector<f64>, tolerance: f64) -> bool {
    step.iter()
        .zip(q.iter())
        .all(|(d, x)| d.abs() <= tolerance * x.abs().max(1e-300))
}

/// The result at `q`, with the standard errors √diag(σ²(JᵀJ)⁻¹), σ² = 2·cost/(m − n) (NaN when
/// JᵀJ is singular or there are no degrees of freedom left).
fn minimum(
    q: DVector<f64>,
    jacobian: &DMatrix<f64>,
    cost: f64,
    initial_cost: f64,
    iterations: usize,
) -> Minimum {
    let (m, n) = jacobian.shape();
    let covariance = jacobian.tr_mul(jacobian).try_inverse();
    let variance = if m > n {
        2.0 * cost / (m - n) as f64
    } else {
        f64::NAN
    };
    let standard_errors = (0..n)
        .map(|j| match &covariance {
            Some(c) => (variance * c[(j, j)]).sqrt(),
            None => f64::NAN,
        })
        .collect();
    Minimum {
        q,
        cost,
        initial_cost,
        iterations,
        standard_errors,
    }
}
