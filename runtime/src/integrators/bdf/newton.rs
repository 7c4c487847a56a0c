//! The simplified Newton iteration of one BDF step, on the Jacobian and factorization the step
//! reuses.

use super::Bdf;
use crate::{Error, Jacobian, NewtonFailure, NewtonMatrix, Result, State, Stats};

impl<M: Jacobian> Bdf<M> {
    /// The simplified Newton iteration for d = c·f(tₙ₊₁, y⁽⁰⁾ + d) − ψ from d = 0 (SciPy's
    /// `solve_bdf_system`), leaving yₙ₊₁ in `y` and d in `self.correction`; returns the
    /// iterations made. Each update is multiplied by `scale` (CVODE's correction for a matrix
    /// made with another c).
    ///
    /// Errors: [`Error::NewtonDidNotConverge`] with the cause.
    pub(super) fn solve(
        &mut self,
        model: &M,
        (t_new, h, c, scale): (f64, f64, f64, f64),
        (max_iters, tol): (usize, f64),
        y: &mut M::State,
        stats: &mut Stats,
    ) -> Result<usize> {
        y.clone_from(&self.predict);
        self.correction.as_mut_slice().fill(0.0);
        let mut previous: Option<f64> = None;
        let mut residual = f64::NAN;
        let fail = |iters: usize, residual, cause| Error::NewtonDidNotConverge {
            t: t_new,
            dt: h,
            iters: iters as u32,
            residual,
            cause,
            halvings: 0,
        };
        for iter in 0..max_iters {
            model.derivative(t_new, y, &mut self.update);
            stats.evaluations += 1;
            // The residual c·f − ψ − d, solved in place into the update Δ.
            residual = 0.0;
            let update = self.update.as_mut_slice();
            for ((u, q), d) in update
                .iter_mut()
                .zip(self.psi.as_slice())
                .zip(self.correction.as_slice())
            {
                *u = c * *u - q - d;
                residual = if u.abs() > residual || u.is_nan() {
                    u.abs()
                } else {
                    residual
                };
            }
            if !residual.is_finite() {
                return Err(fail(iter + 1, residual, NewtonFailure::NotFinite));
            }
            stats.linear_solves += 1;
            self.jacobian
                .solve(&mut self.factors, update)
                .map_err(|_| fail(iter + 1, residual, NewtonFailure::NotFinite))?;
            if scale != 1.0 {
                for u in update.iter_mut() {
                    *u *= scale;
                }
            }
            let mut sum = 0.0;
            for (u, w) in update.iter().zip(self.scale.as_slice()) {
                let r = u / w;
                sum += r * r;
            }
            let norm = (sum / update.len().max(1) as f64).sqrt();
            let rate = previous.map(|p| norm / p);
            if let Some(rate) = rate
                && (rate >= 1.0 || rate.powi((max_iters - iter) as i32) / (1.0 - rate) * norm > tol)
            {
                let cause = if rate >= 1.0 {
                    NewtonFailure::Diverging
                } else {
                    NewtonFailure::Iterations
                };
                return Err(fail(iter + 1, residual, cause));
            }
            for ((yi, d), u) in y
                .as_mut_slice()
                .iter_mut()
                .zip(self.correction.as_mut_slice())
                .zip(update.iter())
            {
                *yi += u;
                *d += u;
            }
            if norm == 0.0 || rate.is_some_and(|rate| rate / (1.0 - rate) * norm < tol) {
                return Ok(iter + 1);
            }
            previous = Some(norm);
        }
        Err(fail(max_iters, residual, NewtonFailure::Iterations))
    }
}
