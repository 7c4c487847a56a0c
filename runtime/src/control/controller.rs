//! Step-size control: the PI controller that turns error estimates into step sizes, and Hairer's
//! algorithm for the first step.

use crate::math::Transcendental;
use crate::{Error, Model, Result, State, Tolerances};

/// Options of an adaptive run beyond its tolerances. Every field has a documented default, and
/// [`Controller`] settings default per method (each integrator's `Integrator::CONTROLLER`).
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptiveOptions {
    /// The first step; `None` (the default) picks one by Hairer's algorithm (see
    /// `initial_step`).
    pub dt_initial: Option<f64>,
    /// The smallest step allowed (default 0: only the resolution of `t` limits it, ten units in
    /// the last place, as in SciPy). A step that would have to be smaller fails with
    /// [`Error::StepSizeTooSmall`].
    pub dt_min: f64,
    /// The largest step allowed (default ∞).
    pub dt_max: f64,
    /// Step attempts allowed, accepted and rejected together (default 1 000 000); past it the run
    /// fails with [`Error::MaxSteps`] — a stiff problem under an explicit method ends here rather
    /// than running for hours.
    pub max_steps: u64,
    /// The step-size controller; `None` (the default) takes the method's own.
    pub controller: Option<Controller>,
}

impl Default for AdaptiveOptions {
    fn default() -> Self {
        AdaptiveOptions {
            dt_initial: None,
            dt_min: 0.0,
            dt_max: f64::INFINITY,
            max_steps: 1_000_000,
            controller: None,
        }
    }
}

impl AdaptiveOptions {
    /// Checks every option.
    ///
    /// Errors: [`Error::InvalidInput`] naming the first option out of range.
    pub fn check(&self) -> Result<()> {
        if let Some(h) = self.dt_initial
            && !(h.is_finite() && h > 0.0)
        {
            return Err(Error::invalid(
                "dt_initial",
                format!("must be finite and positive, got {h:?}"),
            ));
        }
        if !(self.dt_min.is_finite() && self.dt_min >= 0.0) {
            return Err(Error::invalid(
                "dt_min",
                format!("must be finite and non-negative, got {:?}", self.dt_min),
            ));
        }
        if !(self.dt_max > 0.0 && self.dt_max >= self.dt_min) {
            return Err(Error::invalid(
                "dt_max",
                format!(
                    "must be positive and at least dt_min ({:?}), got {:?}",
                    self.dt_min, self.dt_max
                ),
            ));
        }
        if self.max_steps == 0 {
            return Err(Error::invalid("max_steps", "must be at least 1"));
        }
        if let Some(c) = &self.controller {
            c.check()?;
        }
        Ok(())
    }
}

/// The PI step-size controller of Gustafsson (1991) in the form of Hairer's DOPRI5 and DOP853
/// codes (Hairer, Nørsett & Wanner, *Solving ODEs I*, 2nd ed., §II.4; Hairer & Wanner, *Solving
/// ODEs II*, §IV.2, "Lund-stabilization"). After a step of size h with error norm err:
///
/// - accepted (err ≤ 1): h_new = h · clamp(safety · err^(−α) · err_prev^β, min_factor, max_factor),
///   with err_prev the norm of the previous accepted step (at least 1e-4), and no growth
///   (h_new ≤ h) right after a rejection;
/// - rejected: h_new = h · max(min_factor, safety · err^(−α)).
///
/// β = 0 is plain integral control, h_new ∝ err^(−1/(q+1)); β > 0 damps the oscillation of step
/// sizes that plain control shows when stability, not accuracy, limits the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller {
    /// Exponent α of the current error.
    pub alpha: f64,
    /// Exponent β of the previous error (0: integral control only).
    pub beta: f64,
    /// Safety factor, below 1 so the next step is likely to pass.
    pub safety: f64,
    /// Smallest ratio h_new/h.
    pub min_factor: f64,
    /// Largest ratio h_new/h.
    pub max_factor: f64,
}

impl Controller {
    /// Hairer's DOPRI5 defaults for a pair whose error estimate has order `q` (error ∝ h^(q+1)):
    /// β = 0.04, α = 1/(q+1) − 0.75β, safety 0.9, factors in [0.2, 10] (`dopri5.f`, WORK(5..7)).
    pub const fn dopri5(q: u32) -> Self {
        let beta = 0.04;
        Controller {
            alpha: 1.0 / (q + 1) as f64 - 0.75 * beta,
            beta,
            safety: 0.9,
            min_factor: 0.2,
            max_factor: 10.0,
        }
    }

    /// Hairer's DOP853 defaults: β = 0, α = 1/8, safety 0.9, factors in [1/3, 6] (`dop853.f`,
    /// WORK(2..6); its documentation suggests β up to 0.1 for a smoother step sequence, with
    /// α = 1/8 − 0.2β).
    pub const fn dop853() -> Self {
        Controller {
            alpha: 1.0 / 8.0,
            beta: 0.0,
            safety: 0.9,
            min_factor: 1.0 / 3.0,
            max_factor: 6.0,
        }
    }

    /// MATLAB's `ode23s` constants for an order-3 estimate of an order-2 solution: exponent 1/3,
    /// safety 0.8, a rejected step at least halved, growth at most ×5 (`ode23s.m`; Shampine &
    /// Reichelt 1997, §3.1).
    pub const fn rosenbrock23() -> Self {
        Controller {
            alpha: 1.0 / 3.0,
            beta: 0.0,
            safety: 0.8,
            min_factor: 0.5,
            max_factor: 5.0,
        }
    }

    /// SciPy's `solve_ivp` controller for an error estimate of order `q` (`rk.py`: SAFETY = 0.9,
    /// MIN_FACTOR = 0.2, MAX_FACTOR = 10, exponent −1/(q+1), no PI term): for comparisons with
    /// SciPy under identical control.
    pub const fn scipy(q: u32) -> Self {
        Controller {
            alpha: 1.0 / (q + 1) as f64,
            beta: 0.0,
            safety: 0.9,
            min_factor: 0.2,
            max_factor: 10.0,
        }
    }

    /// Checks the settings.
    ///
    /// Errors: [`Error::InvalidInput`] for a non-positive α, a negative β, a safety factor
    /// outside (0, 1], or factors not bracketing 1.
    pub fn check(&self) -> Result<()> {
        let ok = self.alpha > 0.0
            && self.alpha.is_finite()
            && self.beta >= 0.0
            && self.beta.is_finite()
            && self.safety > 0.0
            && self.safety <= 1.0
            && self.min_factor > 0.0
            && self.min_factor < 1.0
            && self.max_factor > 1.0
            && self.max_factor.is_finite();
        if ok {
            Ok(())
        } else {
            Err(Error::invalid(
                "controller",
                format!(
                    "{self:?}: needs α > 0, β ≥ 0, safety in (0, 1], min_factor in (0, 1) and \
                     max_factor finite above 1"
                ),
            ))
        }
    }
}

/// A controller in use: the settings plus what it remembers between steps.
#[derive(Clone, Debug)]
pub(crate) struct ControllerState {
    settings: Controller,
    /// err of the last accepted step, at least 1e-4 (Hairer's FACOLD).
    previous: f64,
    rejected_last: bool,
}

impl ControllerState {
    pub(crate) fn new(settings: Controller) -> Self {
        ControllerState {
            settings,
            previous: 1e-4,
            rejected_last: false,
        }
    }

    /// The next step after an accepted step of size `h` with error norm `err`.
    pub(crate) fn accepted(&mut self, h: f64, err: f64) -> f64 {
        let c = &self.settings;
        let factor = if err == 0.0 {
            c.max_factor
        } else {
            (c.safety
                * Transcendental::powf(err, -c.alpha)
                * Transcendental::powf(self.previous, c.beta))
            .clamp(c.min_factor, c.max_factor)
        };
        let mut next = h * factor;
        if self.rejected_last {
            next = next.min(h);
        }
        self.previous = err.max(1e-4);
        self.rejected_last = false;
        next
    }

    /// The retry after a rejected step of size `h` with error norm `err` (NaN counts as huge).
    pub(crate) fn rejected(&mut self, h: f64, err: f64) -> f64 {
        let c = &self.settings;
        let factor = if err.is_finite() {
            (c.safety * Transcendental::powf(err, -c.alpha)).clamp(c.min_factor, 1.0)
        } else {
            c.min_factor
        };
        self.rejected_last = true;
        h * factor
    }
}

/// The first step, by the algorithm of Hairer, Nørsett & Wanner, *Solving ODEs I*, 2nd ed.,
/// §II.4, p. 169 (also SciPy's `select_initial_step`): with norms weighted by the tolerances,
/// d₀ = ‖y₀‖, d₁ = ‖f(t₀, y₀)‖, h₀ = 0.01·d₀/d₁ (1e-6 when either is below 1e-5); one explicit
/// Euler step gives d₂ = ‖f(t₀ + h₀, y₀ + h₀f₀) − f₀‖/h₀, and h₁ = (0.01/max(d₁, d₂))^(1/(p+1))
/// (max(1e-6, 1e-3·h₀) when both are tiny); the step is min(100·h₀, h₁, `dt_max`). One
/// evaluation of f besides f₀, which the caller passes in.
// The algorithm's inputs are eight independent quantities; a struct would only rename them.
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step<M: Model>(
    model: &M,
    t0: f64,
    y0: &M::State,
    f0: &M::State,
    order: u32,
    tolerances: &Tolerances,
    dt_max: f64,
    scratch: (&mut M::State, &mut M::State),
) -> f64 {
    let (y1, f1) = scratch;
    let (y, f) = (y0.as_slice(), f0.as_slice());
    let d0 = tolerances.norm(y, y, y);
    let d1 = tolerances.norm(f, y, y);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let h0 = h0.min(dt_max);
    for ((a, yi), fi) in y1.as_mut_slice().iter_mut().zip(y).zip(f) {
        *a = yi + h0 * fi;
    }
    model.derivative(t0 + h0, y1, f1);
    for (a, fi) in f1.as_mut_slice().iter_mut().zip(f) {
        *a = (*a - fi) / h0;
    }
    let d2 = tolerances.norm(f1.as_slice(), y, y);
    let h1 = if d1.max(d2) <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        Transcendental::powf(0.01 / d1.max(d2), 1.0 / f64::from(order + 1))
    };
    (100.0 * h0).min(h1).min(dt_max)
}

#[cfg(test)]
mod tests {
    use super::{Controller, ControllerState};

    #[test]
    fn integral_control_follows_the_error_exponent() {
        let mut c = ControllerState::new(Controller::scipy(4));
        // err = 2^-5 → factor 0.9·2 = 1.8 with α = 1/5.
        let next = c.accepted(1.0, 2f64.powi(-5));
        assert!((next - 1.8).abs() < 1e-12, "{next}");
        // Rejected with err = 32: 0.9·32^(-1/5) = 0.45.
        let retry = c.rejected(1.0, 32.0);
        assert!((retry - 0.45).abs() < 1e-12, "{retry}");
        // No growth right after a rejection.
        assert_eq!(c.accepted(1.0, 1e-10), 1.0);
        // NaN errors shrink by the largest allowed factor.
        assert_eq!(c.rejected(1.0, f64::NAN), 0.2);
    }

    #[test]
    fn the_pi_term_damps_growth_when_the_error_rises() {
        let pi = Controller::dopri5(4);
        let (mut a, mut b) = (ControllerState::new(pi), ControllerState::new(pi));
        a.accepted(1.0, 0.9);
        b.accepted(1.0, 1e-3);
        // Same current error; the one whose error rose to it (from 1e-3) grows less than the
        // one whose error fell to it (from 0.9).
        assert!(a.accepted(1.0, 0.1) > b.accepted(1.0, 0.1));
    }
}
