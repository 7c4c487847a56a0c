//! The simplified Newton iteration of one BDF step, on the Jacobian and factorization the step
//! reuses.

use super::Bdf;
use super::coefficients::{
    CVODE_CRDOWN, CVODE_MAXCOR, CVODE_NLSCOEF, CVODE_RDIV, ERROR_CONST, NEWTON_MAXITER,
};
use crate::{
    Error, Jacobian, NewtonFailure, NewtonMatrix, NewtonOptions, Result, State, Stats, Tolerances,
};

/// When the Newton iteration of a step has converged; ‖Δ‖ is the update's weighted RMS norm and
/// the rate ‖Δ‖/‖Δ_prev‖ is measured within the step.
#[derive(Clone, Copy, Debug)]
pub(super) enum Convergence {
    /// SciPy's test: rate/(1 − rate)·‖Δ‖ < `tol` (so two iterations at least, unless Δ = 0);
    /// abandoned when the rate reaches 1 or cannot reach `tol` in the iterations left.
    SciPy { tol: f64, max_iterations: usize },
    /// CVODE's test (`cvNlsConvTest` in `cvode_nls.c`): ‖Δ‖·min(1, R) ≤ `tol`, R = 1 at the
    /// first iteration and max(0.3·R, rate) after, so one iteration suffices when its update
    /// is itself below `tol`; abandoned when ‖Δ‖ exceeds twice the one before or after
    /// `max_iterations`. (CVODE carries R from step to step; here it starts at 1 in each step: with
    /// this test forced on Robertson, HIRES and van der Pol at rtol 1e-6, 20–40 % fewer steps
    /// than carrying R, which let a first iteration pass on an old, small rate.)
    Cvode { tol: f64, max_iterations: usize },
}

impl<M: Jacobian> Bdf<M> {
    /// Whether an adaptive run with `newton` stops Newton by CVODE's test: where a solve is the
    /// cost ([`NewtonMatrix::COSTLY_SOLVES`]) and CVODE's rules are on ([`Bdf::refactor_ratio`]
    /// > 0).
    pub(super) fn cvode_test(newton: &NewtonOptions) -> bool {
        Self::refactor_ratio(newton) > 0.0 && <M::Matrix as NewtonMatrix>::COSTLY_SOLVES
    }

    /// [`NewtonOptions::refactor_ratio`], or 0 (SciPy's rules) for a model with a mass matrix.
    /// CVODE's reuse of a factorization made with another c, its updates scaled by
    /// 2/(1 + c/c_old), is a rule for I − c·J; in M − c·J the algebraic rows scale with c alone.
    /// Measured on a one-rod `RodRope` (a field model, whose solves are costly) at rtol 1e-8:
    /// with CVODE's rules the step fell to 4e-16 at t = 0.27, with SciPy's it ran to t = 10
    /// within 1e-6 of the exact pendulum, as the dense Cartesian pendulum does.
    pub(super) fn refactor_ratio(newton: &NewtonOptions) -> f64 {
        match M::MASS_MATRIX {
            true => 0.0,
            false => newton.refactor_ratio,
        }
    }

    /// What the matrix's solves are for in a run with `newton`: loose ([`crate::Solves::LooseNewton`],
    /// `KrylovOptions::bdf_rtol`) where Newton stops by CVODE's test, which only adaptive runs
    /// use; else to Newton's forcing term. A fixed-step run stops Newton by SciPy's test at
    /// `NewtonOptions::tol`, which updates solved to 0.05 would end far from the implicit
    /// solution (1e-4 relatively on a 2² Gray–Scott grid, `tests/continua/krylov/policy.rs`).
    pub(super) fn solves(newton: &NewtonOptions, adaptive: bool) -> crate::Solves {
        if adaptive && Self::cvode_test(newton) {
            crate::Solves::LooseNewton
        } else {
            crate::Solves::Newton
        }
    }

    /// Weighs the components for this step's norms (atol + rtol·|yₙ₊₁⁽⁰⁾| to tolerances, 1 + |y⁽⁰⁾|
    /// at a fixed step), from the predictor in `self.predict`, and says when Newton converges
    /// at order `k`: CVODE's test or SciPy's (see [`Bdf::cvode_test`]), or the fixed-step run's
    /// [`NewtonOptions`].
    pub(super) fn weigh(&mut self, tolerances: Option<&Tolerances>, k: usize) -> Convergence {
        let predict = self.predict.as_slice();
        match tolerances {
            Some(tolerances) => {
                // A component left out of the error test (atol +∞) is weighed by the smallest
                // finite atol: found once, not per component.
                let fallback = tolerances.smallest_finite_atol();
                for (i, (w, p)) in self
                    .scale
                    .as_mut_slice()
                    .iter_mut()
                    .zip(predict)
                    .enumerate()
                {
                    let atol = tolerances.atol(i);
                    let atol = if atol.is_finite() { atol } else { fallback };
                    *w = atol + tolerances.rtol * p.abs();
                }
                if Self::cvode_test(&self.newton) {
                    // The error estimate is ‖ERROR_CONST[k]·d‖: d's own error may use a tenth.
                    Convergence::Cvode {
                        tol: CVODE_NLSCOEF / ERROR_CONST[k],
                        max_iterations: CVODE_MAXCOR,
                    }
                } else {
                    let rtol = tolerances.rtol.max(100.0 * f64::EPSILON);
                    Convergence::SciPy {
                        tol: (10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt())),
                        max_iterations: NEWTON_MAXITER,
                    }
                }
            }
            None => {
                for (w, p) in self.scale.as_mut_slice().iter_mut().zip(predict) {
                    *w = 1.0 + p.abs();
                }
                Convergence::SciPy {
                    tol: self.newton.tol,
                    max_iterations: self.newton.max_iterations as usize,
                }
            }
        }
    }

    /// The simplified Newton iteration for d = c·f(tₙ₊₁, y⁽⁰⁾ + d) − ψ from d = 0 (SciPy's
    /// `solve_bdf_system`), leaving yₙ₊₁ in `y` and d in `self.correction`; returns the
    /// iterations made. Each update is multiplied by `scale` (CVODE's correction for a matrix
    /// made with another c); `test` says when it has converged.
    ///
    /// Errors: [`Error::NewtonDidNotConverge`] with the cause.
    pub(super) fn solve(
        &mut self,
        model: &M,
        (t_new, h, c, scale): (f64, f64, f64, f64),
        test: Convergence,
        y: &mut M::State,
        stats: &mut Stats,
    ) -> Result<usize> {
        y.clone_from(&self.predict);
        self.correction.as_mut_slice().fill(0.0);
        let max_iterations = match test {
            Convergence::SciPy { max_iterations, .. } | Convergence::Cvode { max_iterations, .. } => {
                max_iterations
            }
        };
        let mut previous: Option<f64> = None;
        // CVODE's R.
        let mut rate_bound = 1.0f64;
        let mut residual = f64::NAN;
        let fail = |iters: usize, residual, cause| Error::NewtonDidNotConverge {
            t: t_new,
            dt: h,
            iters: iters as u32,
            residual,
            cause,
            halvings: 0,
        };
        for iter in 0..max_iterations {
            model.derivative(t_new, y, &mut self.update);
            stats.evaluations += 1;
            // The residual c·f − ψ − d, solved in place into the update Δ.
            residual = 0.0;
            let update = self.update.as_mut_slice();
            match &self.mass {
                // c·f − M(ψ + d)
                Some(mass) if M::MASS_MATRIX => {
                    for u in update.iter_mut() {
                        *u *= c;
                    }
                    mass.apply_add(-1.0, self.psi.as_slice(), update);
                    mass.apply_add(-1.0, self.correction.as_slice(), update);
                }
                _ => {
                    for ((u, q), d) in update
                        .iter_mut()
                        .zip(self.psi.as_slice())
                        .zip(self.correction.as_slice())
                    {
                        *u = c * *u - q - d;
                    }
                }
            }
            for u in update.iter() {
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
                .map_err(|error| {
                    // The residual is finite here, so the model is not to blame.
                    let cause = match error {
                        crate::SolveError::Singular => NewtonFailure::Singular,
                        _ => NewtonFailure::UpdateNotFinite,
                    };
                    fail(iter + 1, residual, cause)
                })?;
            if scale != 1.0 {
                for u in update.iter_mut() {
                    *u *= scale;
                }
            }
            // The update's norm, and the norm of the rounding of y itself: an update no larger
            // than that has converged whatever its rate (at h ≫ the solution's time scales,
            // near an equilibrium, successive updates are rounding noise of equal size, and a
            // rate near 1 must not read as divergence).
            let (mut sum, mut noise) = (0.0, 0.0);
            for ((u, w), yi) in update.iter().zip(self.scale.as_slice()).zip(y.as_slice()) {
                let r = u / w;
                sum += r * r;
                let e = f64::EPSILON * yi.abs() / w;
                noise += e * e;
            }
            let len = update.len().max(1) as f64;
            let norm = (sum / len).sqrt();
            let settled = norm <= 4.0 * (noise / len).sqrt();
            let rate = previous.map(|p| norm / p);
            let failure = match (test, rate) {
                _ if settled => None,
                (Convergence::SciPy { .. }, Some(rate)) if rate >= 1.0 => {
                    Some(NewtonFailure::Diverging)
                }
                (Convergence::SciPy { tol, .. }, Some(rate))
                    if rate.powi((max_iterations - iter) as i32) / (1.0 - rate) * norm > tol =>
                {
                    Some(NewtonFailure::Iterations)
                }
                (Convergence::Cvode { .. }, Some(rate)) if rate > CVODE_RDIV => {
                    Some(NewtonFailure::Diverging)
                }
                _ => None,
            };
            // A model with a mass matrix: before failing, compare the update with the rounding
            // of its own residual carried through the solve (the noise floor of M − c·J's
            // algebraic directions, which ε·|y| does not see), a bound of which a quarter is
            // taken (see `ROUNDING_SHARE`).
            let settled = settled
                || (failure.is_some()
                    && norm
                        <= ROUNDING_SHARE
                            * residual_rounding(
                                &mut self.jacobian,
                                &mut self.factors,
                                self.mass.as_ref(),
                                (c, y.as_slice(), self.psi.as_slice()),
                                self.correction.as_slice(),
                                self.scale.as_slice(),
                                &mut self.rounding,
                            ));
            if let Some(cause) = failure.filter(|_| !settled) {
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
            let converged = settled
                || match test {
                    Convergence::SciPy { tol, .. } => {
                        norm == 0.0 || rate.is_some_and(|rate| rate / (1.0 - rate) * norm < tol)
                    }
                    Convergence::Cvode { tol, .. } => {
                        if let Some(rate) = rate {
                            rate_bound = (CVODE_CRDOWN * rate_bound).max(rate);
                        }
                        norm * rate_bound.min(1.0) <= tol
                    }
                };
            if converged {
                return Ok(iter + 1);
            }
            previous = Some(norm);
        }
        Err(fail(max_iterations, residual, NewtonFailure::Iterations))
    }
}

/// The share of [`residual_rounding`]'s bound below which an update of a mass-matrix step is
/// rounding noise. The bound adds every term's rounding at a full ε with one sign; measured on
/// the DAE suite (`examples/dae_suite.rs`) at rtol 1e-8: with the whole bound (1) the
/// Robertson DAE's error at t = 1e11 grew from 1.2e-7 to 7.4e-7 (iterations that had not
/// converged passed as noise); with a quarter it stays 1.3e-7, and the transistor amplifier,
/// which without the floor stalls at t = 0.0263 (Newton failing at rates 0.2–0.7 on U₈'s
/// noise), runs to 0.2 with an error of 3.6e-8.
const ROUNDING_SHARE: f64 = 0.25;

/// The weighted RMS norm of the rounding of a Newton update of a mass-matrix step, or 0 for a
/// model without a mass matrix or with a sparse J: the residual c·f − M(ψ + d)'s rounding,
/// ε·(c·Σₖ|Jⱼₖ||yₖ| + Σₖ|Mⱼₖ|(|ψₖ| + |dₖ|)) in row j, solved through the factors with two sign
/// patterns (all +, alternating) and the larger magnitude kept per component.
///
/// Near an equilibrium of a stiff circuit at tight tolerances (the transistor amplifier at
/// atol 1e-12 V), an algebraic node's updates are this noise: rounding of the large node
/// voltages it is coupled to through M and J, far above ε·|yᵢ| of its own small value.
fn residual_rounding<N: NewtonMatrix>(
    jacobian: &mut N,
    factors: &mut N::Factors,
    mass: Option<&crate::Mass>,
    (c, y, psi): (f64, &[f64], &[f64]),
    correction: &[f64],
    scale: &[f64],
    rounding: &mut Vec<f64>,
) -> f64 {
    let Some(mass) = mass else { return 0.0 };
    let n = y.len();
    rounding.clear();
    rounding.resize(2 * n, 0.0);
    let (plus, alternating) = rounding.split_at_mut(n);
    for (j, r) in plus.iter_mut().enumerate() {
        let mut sum = 0.0;
        for (k, yk) in y.iter().enumerate() {
            match jacobian.dense_entry(j, k) {
                Some(entry) => sum += (entry * yk).abs(),
                None => return 0.0,
            }
        }
        *r = c * sum;
    }
    for &(i, j, m) in mass.entries() {
        plus[i] += m.abs() * (psi[j].abs() + correction[j].abs());
    }
    for (j, (p, a)) in plus.iter_mut().zip(alternating.iter_mut()).enumerate() {
        *p *= f64::EPSILON;
        *a = if j % 2 == 0 { *p } else { -*p };
    }
    if jacobian.solve(factors, plus).is_err() || jacobian.solve(factors, alternating).is_err() {
        return 0.0;
    }
    let sum: f64 = plus
        .iter()
        .zip(alternating.iter())
        .zip(scale)
        .map(|((p, a), w)| {
            let r = p.abs().max(a.abs()) / w;
            r * r
        })
        .sum();
    (sum / n.max(1) as f64).sqrt()
}
