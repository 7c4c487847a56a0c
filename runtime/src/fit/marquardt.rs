//! Levenberg–Marquardt with Marquardt's diagonal scaling and Nielsen's damping update (the
//! references are in the module above).

use nalgebra::{DMatrix, DVector};

use super::FitOptions;
use crate::{Error, Result};

/// r and ∂r/∂q at q.
pub(super) type Residuals<'a> =
    dyn FnMut(&DVector<f64>) -> Result<(DVector<f64>, DMatrix<f64>)> + 'a;

/// The minimiser's result in the search variables.
pub(super) struct Minimum {
    pub(super) q: DVector<f64>,
    pub(super) cost: f64,
    pub(super) initial_cost: f64,
    pub(super) iterations: usize,
    pub(super) standard_errors: Vec<f64>,
}

/// Levenberg–Marquardt with Marquardt's diagonal scaling and Nielsen's damping update, on
/// `residuals` (r and ∂r/∂q at q) from `q`.
pub(super) fn levenberg_marquardt(
    residuals: &mut Residuals<'_>,
    mut q: DVector<f64>,
    (mut r, mut jacobian): (DVector<f64>, DMatrix<f64>),
    options: &FitOptions,
) -> Result<Minimum> {
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
