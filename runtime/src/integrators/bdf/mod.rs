//! Bdf: the variable-order (1–5), variable-step backward differentiation formulas of SciPy's
//! `BDF`, in the numerical differentiation (NDF) form of MATLAB's `ode15s`.

mod coefficients;
mod history;
mod newton;
mod order;

use coefficients::{
    ALPHA, BASIS, CVODE_SAFETY, ERROR_CONST, FIXED_STEP_ORDER, GAMMA, MAX_ORDER, MIN_FACTOR,
    NEWTON_MAXITER, change_d,
};
use newton::Convergence;

use super::linearization::finite_jacobian;
use super::{DenseStep, Integrator, Step, copies};
use crate::math::Transcendental;
use crate::{Error, Jacobian, Method, NewtonMatrix, NewtonOptions, Result, State, Stats};

/// The variable-order, variable-step numerical differentiation formulas (NDFs) of Shampine &
/// Reichelt, as SciPy's `scipy.integrate.BDF` implements them: the solution is carried as the
/// backward differences D = (yₙ, ∇yₙ, …, ∇ᵏ⁺²yₙ) of the values at a constant step h, and a step
/// of order k solves
///
/// ```text
/// Σⱼ₌₁ᵏ γⱼ∇ʲyₙ₊₁ − h·f(tₙ₊₁, yₙ₊₁) − κₖγₖ·(yₙ₊₁ − yₙ₊₁⁽⁰⁾) = 0,   γⱼ = Σᵢ₌₁ʲ 1/i,
/// ```
///
/// with the predictor yₙ₊₁⁽⁰⁾ = Σⱼ₌₀ᵏ ∇ʲyₙ (Shampine & Reichelt 1997, §2). Writing
/// yₙ₊₁ = yₙ₊₁⁽⁰⁾ + d, it is d = c·f(tₙ₊₁, yₙ₊₁⁽⁰⁾ + d) − ψ with c = h/αₖ, αₖ = (1 − κₖ)γₖ and
/// ψ = Σⱼ₌₁ᵏ γⱼ∇ʲyₙ/αₖ, solved by the simplified Newton iteration (I − c·J)·Δ = c·f − ψ − d with
/// one J and one LU held across steps:
///
/// - **κ** = (−0.1850, −1/9, −0.0823, −0.0415, 0) for k = 1 … 5: the NDFs, which take steps 26 %
///   longer than the BDFs at the same accuracy at orders 1–3 (12 % at order 4; order 5 is BDF5)
///   for little loss of stability (NDF1, NDF2 are A-stable; NDF3–5 A(α)-stable, α = 80°, 66°,
///   51°).
/// - **Newton**, norms weighted by atol + rtol·|yₙ₊₁⁽⁰⁾| (so 1 is the error tolerance), SciPy's
///   test: at most 4 iterations, converged when rate/(1 − rate)·‖Δ‖ < tol, tol = max(10ε/rtol,
///   min(0.03, √rtol)) (rate the ratio of successive ‖Δ‖), abandoned when the rate reaches 1 or
///   cannot reach tol in the iterations left. Where a solve is the cost (the sparse systems of
///   particle and field models, [`NewtonMatrix::COSTLY_SOLVES`]) and CVODE's rules are on (see
///   Reuse), CVODE's test (Hindmarsh et al. 2005, §2.1; `cvNlsConvTest`): at most 3
///   iterations, converged when ‖Δ‖·min(1, R) ≤ 0.1/(κₖγₖ + 1/(k + 1)), R the rate
///   (max(0.3·R, ‖Δ‖/‖Δ_prev‖), 1 at a step's first iteration), abandoned when ‖Δ‖ more than
///   doubles. It halves the sparse systems' solves at equal error (SciPy's tol is 300–1 000
///   times tighter at rtol 1e-6); on small dense systems it does not pay (`BENCHMARKS.md`).
/// - **Reuse**: the LU of I − c·J is kept while c = h/αₖ stays within
///   [`NewtonOptions::refactor_ratio`] (default 0.3) of the c it was made with, each Newton
///   update then scaled by 2/(1 + c/c_old) (CVODE's rule: Hindmarsh et al., "SUNDIALS", ACM
///   TOMS 31 (2005), §2.1, and `cvode_ls.c`); with a ratio of 0, and always for a model with
///   a mass matrix (the rule is for I − c·J; see `Bdf::refactor_ratio`), SciPy's rule: kept across every
///   step that neither changes h nor the order, and after a step rejected by its error estimate
///   (the fixed point d does not depend on the iteration matrix, only the rate does). J is
///   re-evaluated only when Newton fails with a J older than the current step; if it fails
///   with a fresh one, the step is halved ([`Error::NewtonDidNotConverge`], its residual the
///   max-norm of c·f − ψ − d, is the retriable failure the driver sees).
/// - **Error**: err = (κₖγₖ + 1/(k + 1))·d ≈ (κₖγₖ + 1/(k + 1))·∇ᵏ⁺¹yₙ₊₁, in the tolerances'
///   norm at yₙ₊₁. A rejected step shrinks h by max(0.2, s·err^(−1/(k+1))), with the safety
///   s = 0.9·(2·4 + 1)/(2·4 + Newton iterations) under SciPy's Newton test and s = 0.7 under
///   CVODE's (odyn's choice: SciPy's formula with it rejected 6–12 % of the Brusselator's
///   attempts and about 1 % with 0.7).
/// - **Order and step**: after k + 1 steps at the same h, the estimates of orders k − 1, k and
///   k + 1 (from ∇ᵏyₙ₊₁, d and ∇ᵏ⁺²yₙ₊₁) each propose a step, h·err_q^(−1/(q+1)); the largest
///   wins, times s, at most ×10. When h changes, D is re-sampled at the new spacing from the
///   same interpolating polynomial (`change_d`: D ← (R·U)ᵀ·D).
/// - **Dense output**: that polynomial on the last step, Σⱼ₌₀ᵏ ∇ʲyₙ₊₁·pⱼ(θ) with
///   pⱼ(θ) = Πₘ₌₀ʲ⁻¹ (θ − 1 + m)/(m + 1) (SciPy's `BdfDenseOutput`), of degree k.
/// - **Start and events**: order 1 from D = (y₀, h·f(t₀, y₀)), again after a change event.
/// - **Mass matrix** (a DAE, M·y′ = f): M(d + ψ) = c·f(tₙ₊₁, y⁽⁰⁾ + d), Newton with M − c·J,
///   as `ode15s` (Shampine, Reichelt & Kierzenka, SIAM Review 41 (1999) 538–552); the ODE's
///   error estimate and order selection over every component; the start takes h·f(t₀, y₀) for
///   h·y′₀ in rows where M is the identity's, 0 elsewhere.
///
/// The method chooses its own step sizes ([`Integrator::next_step`]; a
/// [`crate::AdaptiveOptions::controller`] is not used); the adaptive driver still caps them at
/// `dt_max` and shortens them to land on the end and on time events.
///
/// **Fixed-step runs** have no error estimate to choose the order by: the order rises by one
/// after every k + 1 steps, to 2 (the A-stable orders) unless [`Bdf::set_max_order`] says
/// otherwise, and Newton follows [`NewtonOptions`] (`tol` on ‖Δ‖ weighted by 1 + |y|,
/// `max_iterations`), its updates solved to Newton's forcing term (`KrylovOptions::newton_rtol`)
/// rather than CVODE's looser one; a failing solve is retried as two half steps by the
/// driver. Steps that differ from dt only by the rounding of t₀ + n·dt count as equal.
///
/// - **Order** 1–5 (2 at a fixed step, so [`Method::order`] is 2).
/// - **Stability**: A-stable at orders 1 and 2, A(α)-stable above; the adaptive order selection
///   keeps a step within the region of its order.
///
/// References: L. F. Shampine, M. W. Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18
/// (1997) 1–22, §2; SciPy's `scipy/integrate/_ivp/bdf.py`; E. Hairer, G. Wanner, *Solving
/// Ordinary Differential Equations I*, 2nd ed., §III.1 (the backward-difference form).
pub struct Bdf<M: Jacobian> {
    /// J, kept across steps.
    jacobian: M::Matrix,
    factors: <M::Matrix as NewtonMatrix>::Factors,
    /// Whether `factors` hold a factorization to solve with.
    factored: bool,
    /// The c = h/αₖ `factors` were made with.
    factored_c: f64,
    /// Whether J was evaluated during the current step (SciPy's `current_jac`): a Newton
    /// failure then halves the step instead of re-evaluating J.
    fresh: bool,
    /// D: ∇ʲyₙ for j = 0 … k + 2, at the spacing `spacing`.
    differences: [M::State; MAX_ORDER + 3],
    /// The step D is sampled at.
    spacing: f64,
    /// The order of the next step.
    order: usize,
    /// The order of the last accepted step (its dense output's degree).
    last_order: usize,
    /// Steps accepted since h or the order last changed.
    equal_steps: usize,
    /// The highest order allowed (`None`: 5 adaptive, 2 at a fixed step).
    max_order: Option<usize>,
    /// Whether the last attempt had tolerances (an adaptive run).
    adaptive: bool,
    newton: NewtonOptions,
    /// The step the method proposes next.
    next: Option<f64>,
    /// Whether the last attempt was rejected by its error estimate: its LU is then kept for
    /// the retry at the proposed step (SciPy's rule).
    rejected: bool,
    /// For an accepted adaptive attempt: the order chosen for what follows (with the step in
    /// `next`), when the step was the (k + 1)-th at this h.
    change: Option<usize>,
    /// The predictor yₙ₊₁⁽⁰⁾.
    predict: M::State,
    /// ψ.
    psi: M::State,
    /// The correction d of the last attempt.
    correction: M::State,
    /// f at the iterate, then the Newton update.
    update: M::State,
    /// Weights of the norms.
    scale: M::State,
    /// M, for a model with a mass matrix: the step solves M(d + ψ) = c·f, Newton with M − c·J.
    mass: Option<crate::Mass>,
    /// Room for the rounding of a Newton update of a mass-matrix step (filled on the first
    /// failing iteration only).
    rounding: Vec<f64>,
    /// What the matrix's solves are configured for: loose under CVODE's Newton test (adaptive
    /// runs of particle and field models), else to Newton's own forcing term.
    solves: crate::Solves,
}

impl<M: Jacobian> crate::integrators::sealed::Sealed for Bdf<M> {}

impl<M: Jacobian> Integrator<M> for Bdf<M> {
    const METHOD: Method = Method::Bdf;
    const DENSE_DEGREE: usize = MAX_ORDER;
    const START_ORDER: u32 = 1;

    fn linear_work(&self) -> crate::LinearWork {
        crate::NewtonMatrix::work(&self.jacobian)
    }

    /// Evaluates f(t₀, y₀) for D and J at (t₀, y₀), as SciPy does on creation.
    fn prepare(
        model: &M,
        t0: f64,
        y0: &M::State,
        newton: &NewtonOptions,
        stats: &mut Stats,
    ) -> Result<Self> {
        let mut jacobian = model.jacobian_matrix(y0);
        // Configured for an adaptive run; a fixed-step run's first attempt reconfigures.
        let solves = Self::solves(newton, true);
        jacobian.configure(newton, solves);
        model.jacobian(t0, y0, &mut jacobian);
        stats.jacobian_evaluations += 1;
        let mut bdf = Bdf {
            factors: jacobian.factors(),
            jacobian,
            factored: false,
            factored_c: f64::NAN,
            fresh: false,
            differences: copies(y0)?,
            spacing: 1.0,
            order: 1,
            last_order: 1,
            equal_steps: 0,
            max_order: None,
            adaptive: false,
            newton: *newton,
            next: None,
            rejected: false,
            change: None,
            predict: y0.try_clone()?,
            psi: y0.try_clone()?,
            correction: y0.try_clone()?,
            update: y0.try_clone()?,
            scale: y0.try_clone()?,
            mass: crate::model::mass_of(model, y0)?,
            rounding: Vec::new(),
            solves,
        };
        bdf.start_history(model, t0, y0, stats);
        Ok(bdf)
    }

    fn attempt(&mut self, model: &M, s: Step<'_, M::State>, y_new: &mut M::State) -> Result<f64> {
        let (t, h) = (s.t, s.h);
        let t_new = t + h;
        let k = self.order;
        let keep_lu = self.rejected && self.next == Some(h);
        self.rejected = false;
        self.change = None;
        self.adaptive = s.tolerances.is_some();
        let solves = Self::solves(&self.newton, self.adaptive);
        if solves != self.solves {
            self.jacobian.configure(&self.newton, solves);
            self.solves = solves;
            self.factored = false;
        }
        // Proposed should this attempt fail: SciPy halves a step whose Newton iteration fails.
        self.next = Some(0.5 * h);
        // A fixed-step run's steps t₀ + (n + 1)·dt − (t₀ + n·dt) differ from dt by the rounding
        // of t: within it, h is the spacing D has (re-sampling would refactorize every step and
        // never let the order rise).
        if (h - self.spacing).abs() > 4.0 * f64::EPSILON * (t.abs() + h.abs()) {
            change_d(&mut self.differences, k, h / self.spacing);
            self.spacing = h;
            self.equal_steps = 0;
            // SciPy's rule; with a refactor ratio, c decides below.
            self.factored &= keep_lu || Self::refactor_ratio(&self.newton) > 0.0;
        }
        // Predictor Σⱼ₌₀ᵏ ∇ʲyₙ and ψ = Σⱼ₌₁ᵏ γⱼ∇ʲyₙ/αₖ.
        let (predict, psi) = (self.predict.as_mut_slice(), self.psi.as_mut_slice());
        predict.copy_from_slice(self.differences[0].as_slice());
        psi.fill(0.0);
        for (j, dj) in self.differences.iter().enumerate().take(k + 1).skip(1) {
            for ((p, q), x) in predict.iter_mut().zip(psi.iter_mut()).zip(dj.as_slice()) {
                *p += x;
                *q += GAMMA[j] * x;
            }
        }
        for q in psi.iter_mut() {
            *q /= ALPHA[k];
        }
        let ratio = Self::refactor_ratio(&self.newton);
        let test = self.weigh(s.tolerances, k);
        let c = h / ALPHA[k];
        // CVODE's rule holds after a rejection too (SciPy's keeps the LU however far c moved).
        if ratio > 0.0 && (c / self.factored_c - 1.0).abs() > ratio {
            self.factored = false;
        }
        let iters = loop {
            if !self.factored {
                s.stats.factorizations += 1;
                let factored = match &self.mass {
                    Some(mass) if M::MASS_MATRIX => {
                        self.jacobian
                            .factorize_mass(c, mass.entries(), &mut self.factors)
                    }
                    _ => self.jacobian.factorize(c, &mut self.factors),
                };
                if factored.is_err() {
                    // A J that is not finite, rather than a step too large for it.
                    finite_jacobian(&self.jacobian, t, s.y)?;
                    return Err(Error::SingularMatrix { t, dt: h });
                }
                self.factored = true;
                self.factored_c = c;
            }
            // CVODE's correction for a matrix made with another c: between the factor 1 a
            // non-stiff component needs and c_old/c a stiff one does. A c equal but for the
            // rounding of t (fixed-step runs) counts as the same.
            let stale = ratio > 0.0 && (c / self.factored_c - 1.0).abs() > 1e-12;
            let scale = if stale {
                2.0 / (1.0 + c / self.factored_c)
            } else {
                1.0
            };
            match self.solve(model, (t_new, h, c, scale), test, y_new, s.stats) {
                Ok(iters) => break iters,
                Err(_) if stale => {
                    // A matrix made with another c: refactorize with this one, same J, first.
                    self.factored = false;
                }
                Err(failure) if self.fresh => {
                    finite_jacobian(&self.jacobian, t, s.y)?;
                    return Err(failure);
                }
                Err(_) => {
                    // An old J: evaluate it at the predictor and try again.
                    model.jacobian(t_new, &self.predict, &mut self.jacobian);
                    s.stats.jacobian_evaluations += 1;
                    self.fresh = true;
                    self.factored = false;
                }
            }
        };
        let Some(tolerances) = s.tolerances else {
            self.next = Some(h);
            return Ok(0.0);
        };
        let safety = match test {
            Convergence::Cvode { .. } => CVODE_SAFETY,
            Convergence::SciPy { .. } => {
                0.9 * (2 * NEWTON_MAXITER + 1) as f64 / (2 * NEWTON_MAXITER + iters) as f64
            }
        };
        let y = y_new.as_slice();
        let d = self.correction.as_slice();
        let norm = |e: &dyn Fn(usize) -> f64| tolerances.norm_of(e, y, y);
        let error = norm(&|i| ERROR_CONST[k] * d[i]);
        if error > 1.0 {
            let factor =
                MIN_FACTOR.max(safety * Transcendental::powf(error, -1.0 / (k + 1) as f64));
            self.next = Some(h * factor);
            self.rejected = true;
            return Ok(error);
        }
        self.next = Some(h);
        // This step, if accepted, is the (k + 1)-th at this h and order.
        if self.equal_steps >= k {
            self.propose(h, (safety, error), tolerances, y);
        }
        Ok(error)
    }

    fn accept(&mut self) {
        let k = self.order;
        self.equal_steps += 1;
        // With d = ∇ᵏ⁺¹yₙ₊₁: ∇ᵏ⁺²yₙ₊₁ = d − ∇ᵏ⁺¹yₙ, then ∇ʲyₙ₊₁ = ∇ʲyₙ + ∇ʲ⁺¹yₙ₊₁ from the top
        // down.
        let (low, high) = self.differences.split_at_mut(k + 2);
        for ((a, b), d) in high[0]
            .as_mut_slice()
            .iter_mut()
            .zip(low[k + 1].as_mut_slice())
            .zip(self.correction.as_slice())
        {
            *a = d - *b;
            *b = *d;
        }
        for i in (0..=k).rev() {
            let (low, high) = self.differences.split_at_mut(i + 1);
            for (x, a) in low[i].as_mut_slice().iter_mut().zip(high[0].as_slice()) {
                *x += a;
            }
        }
        self.last_order = k;
        self.fresh = false;
        self.rejected = false;
        match self.change.take() {
            Some(order) => {
                // A new h (`next`) and order: re-sampled at the next attempt, refactorized (with
                // a refactor ratio, if c changed by more).
                self.order = order;
                self.equal_steps = 0;
                self.factored &= Self::refactor_ratio(&self.newton) > 0.0;
            }
            None => {
                // A fixed-step run raises the order as the history allows.
                let cap = self.max_order.unwrap_or(FIXED_STEP_ORDER);
                if !self.adaptive && self.equal_steps > k && k < cap {
                    self.order = k + 1;
                    self.equal_steps = 0;
                    self.factored &= Self::refactor_ratio(&self.newton) > 0.0;
                }
            }
        }
    }

    /// Starts at order 1 from the new state, as at t₀; J is kept (a Newton failure renews it).
    fn restart(&mut self, model: &M, t: f64, y: &M::State, stats: &mut Stats) {
        self.start_history(model, t, y, stats);
    }

    /// Σⱼ₌₀ᵏ ∇ʲyₙ₊₁·pⱼ(θ) in powers of θ.
    fn dense(
        &mut self,
        _: &M,
        s: Step<'_, M::State>,
        _: &M::State,
        dense: &mut DenseStep<M::State>,
    ) -> bool {
        let k = self.last_order;
        let coefficients = dense.fill(s.t, s.h, k);
        for (i, c) in coefficients.iter_mut().enumerate() {
            let out = c.as_mut_slice();
            out.fill(0.0);
            for (basis, dj) in BASIS.iter().zip(&self.differences).take(k + 1) {
                if basis[i] != 0.0 {
                    for (o, x) in out.iter_mut().zip(dj.as_slice()) {
                        *o += basis[i] * x;
                    }
                }
            }
        }
        true
    }

    fn next_step(&self) -> Option<f64> {
        self.next
    }
}
