//! Sensitivities across an event that changes the state: the jump conditions.
//!
//! At a change y⁺ = h(t, y⁻) at the zero τ of g(t, y), both τ and the state after it move with
//! the parameters. Differentiating y⁺(p) = h(τ(p), y⁻(τ(p), p)) and the sensitivity after the
//! event, s⁺ = dy⁺/dp − f⁺·τ′, gives
//!
//! s⁺ = H_y·s⁻ + (H_y·f⁻ + H_t − f⁺)·τ′,   τ′ = −(g_y·s⁻)/(g_t + g_y·f⁻),
//!
//! with f∓ = f(τ, y∓) (Rozenvasser, "General sensitivity equations of discontinuous systems",
//! Automation and Remote Control 28 (1967) 400; the rule of CVODES's root finding with
//! sensitivities and of DifferentialEquations.jl's callbacks). A time event has τ′ = 0. The
//! change and the condition are the user's closures: H_y, H_t, g_y and g_t are central
//! differences of them (step ε^⅓·max(|x|, 1): exact to rounding when they are linear, as a
//! bounce v ← −e·v and a height g = y are, ~1e-10 relative otherwise). They must not depend on
//! the parameters themselves (a restitution that is a `#[param]`): that term is not included.

use nalgebra::{DMatrix, DVector};

use super::{Sensitive, SensitivityState};
use crate::drive::Jump;
use crate::{DenseMatrix, Error, Jacobian, Parameters, Result, State};

/// The step of a central difference at `x`.
fn step(x: f64) -> f64 {
    f64::EPSILON.cbrt() * x.abs().max(1.0)
}

impl<M> Sensitive<'_, M>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
    /// Applies the jump conditions to the sensitivities of `after`, the state `jump.change` made
    /// of `before` at `t`.
    ///
    /// Errors: [`Error::BadEvent`] when the crossing is tangential (g_t + g_y·f⁻ = 0): the event
    /// time's sensitivity is then infinite.
    pub(super) fn jump(
        &self,
        t: f64,
        before: &SensitivityState,
        after: &mut SensitivityState,
        jump: Jump<'_, SensitivityState>,
    ) -> Result<()> {
        let n = self.model.state().as_slice().len();
        let y_before = &before.as_slice()[..n];
        // H_y and H_t: the change's derivatives, by central differences of it.
        let mut h_y = DMatrix::zeros(n, n);
        let mut h_t = DVector::zeros(n);
        let mut trial = before.clone();
        let mut changed = |t: f64, k: Option<(usize, f64)>| -> Vec<f64> {
            trial.clone_from(before);
            if let Some((k, shift)) = k {
                trial.as_mut_slice()[k] += shift;
            }
            (jump.change)(t, &mut trial);
            trial.as_slice()[..n].to_vec()
        };
        for (k, &x) in y_before.iter().enumerate() {
            let d = step(x);
            let (plus, minus) = (changed(t, Some((k, d))), changed(t, Some((k, -d))));
            for i in 0..n {
                h_y[(i, k)] = (plus[i] - minus[i]) / (2.0 * d);
            }
        }
        let d = step(t);
        let (plus, minus) = (changed(t + d, None), changed(t - d, None));
        for i in 0..n {
            h_t[i] = (plus[i] - minus[i]) / (2.0 * d);
        }
        // f on both sides.
        let f = |y: &[f64]| {
            let mut state = self.model.state();
            state.as_mut_slice().copy_from_slice(y);
            let mut rate = state.clone();
            self.model.derivative(t, &state, &mut rate);
            self.count(1, 0, 0);
            DVector::from_column_slice(rate.as_slice())
        };
        let f_before = f(y_before);
        let f_after = f(&after.as_slice()[..n]);
        // τ′ = −(g_y·s⁻)/(g_t + g_y·f⁻); none for a time event.
        let timing = match jump.condition {
            None => None,
            Some(g) => {
                let mut probe = before.clone();
                let mut g_y = DVector::zeros(n);
                for (k, &x) in y_before.iter().enumerate() {
                    let d = step(x);
                    probe.as_mut_slice()[k] = x + d;
                    let plus = g(t, &probe);
                    probe.as_mut_slice()[k] = x - d;
                    let minus = g(t, &probe);
                    probe.as_mut_slice()[k] = x;
                    g_y[k] = (plus - minus) / (2.0 * d);
                }
                let d = step(t);
                let g_t = (g(t + d, before) - g(t - d, before)) / (2.0 * d);
                let rate = g_t + g_y.dot(&f_before);
                let scale = g_t.abs() + g_y.abs().dot(&f_before.abs());
                // Tangential, or NaN: not a crossing whose time moves smoothly.
                let crossing = rate.abs().partial_cmp(&(1e-12 * scale));
                if crossing != Some(std::cmp::Ordering::Greater) {
                    return Err(Error::BadEvent {
                        event: jump.name.to_owned(),
                        t,
                        reason: format!(
                            "the state grazes the event's surface there (dg/dt = {rate:e} along \
                             the solution), so the event time's sensitivity to the parameters is \
                             infinite and the sensitivities after the change are undefined"
                        ),
                    });
                }
                Some((g_y, rate))
            }
        };
        let carried = &h_y * &f_before + h_t - f_after;
        let columns = (before.as_slice().len() - n) / n;
        let values = after.as_mut_slice();
        for c in 0..columns {
            let range = n * (1 + c)..n * (2 + c);
            let s = DVector::from_column_slice(&before.as_slice()[range.clone()]);
            let mut jumped = &h_y * &s;
            if let Some((g_y, rate)) = &timing {
                let tau = -g_y.dot(&s) / rate;
                jumped += &carried * tau;
            }
            values[range].copy_from_slice(jumped.as_slice());
        }
        Ok(())
    }
}
