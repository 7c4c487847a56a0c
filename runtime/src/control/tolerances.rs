//! [`Tolerances`]: the accuracy an adaptive run is asked for, and the error norm that judges a
//! step against it.

use crate::{Error, Result};

/// Absolute tolerance: one for every component, or one per component.
#[derive(Clone, Debug, PartialEq)]
pub enum Atol {
    /// The same for every component.
    Scalar(f64),
    /// One per state component, in layout order. `f64::INFINITY` leaves a component out of the
    /// error test (its error weighs nothing and it does not count in the norm's n): how
    /// sensitivities are excluded, as CVODES's `errconS = false` does
    /// ([`crate::sensitivity::Sensitive::tolerances`]).
    PerComponent(Vec<f64>),
}

/// Relative and absolute tolerances, in the vocabulary of SciPy, DifferentialEquations.jl and
/// SUNDIALS: a step is accepted when its estimated local error eᵢ satisfies
///
/// ‖e‖ = √( (1/n) Σᵢ (eᵢ / (atolᵢ + rtol·max(|yᵢ|, |ŷᵢ|)))² ) ≤ 1,
///
/// y being the state at the start of the step and ŷ at its end (Hairer, Nørsett & Wanner,
/// *Solving ODEs I*, 2nd ed., §II.4, eq. (4.11)). `rtol` bounds the error relative to the
/// solution's size; `atol` takes over where the solution is near zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance (default 1e-6).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-9 for every component).
    pub atol: Atol,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances {
            rtol: 1e-6,
            atol: Atol::Scalar(1e-9),
        }
    }
}

impl Tolerances {
    /// `rtol` and one `atol` for every component.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Tolerances {
            rtol,
            atol: Atol::Scalar(atol),
        }
    }

    /// `rtol` and an `atol` per component.
    pub fn per_component(rtol: f64, atol: Vec<f64>) -> Self {
        Tolerances {
            rtol,
            atol: Atol::PerComponent(atol),
        }
    }

    /// Checks the tolerances for a state of `len` components.
    ///
    /// Errors: [`Error::InvalidInput`] when `rtol` is not finite or negative, an `atol` is not
    /// finite or negative, both are zero (no step could ever pass where y = 0), or a per-component
    /// `atol` has the wrong length.
    pub fn check(&self, len: usize) -> Result<()> {
        if !(self.rtol.is_finite() && self.rtol >= 0.0) {
            return Err(Error::invalid(
                "rtol",
                format!("must be finite and non-negative, got {:?}", self.rtol),
            ));
        }
        let atols: &[f64] = match &self.atol {
            Atol::Scalar(a) => std::slice::from_ref(a),
            Atol::PerComponent(a) => {
                if a.len() != len {
                    return Err(Error::invalid(
                        "atol",
                        format!("has {} components but the state has {len}", a.len()),
                    ));
                }
                a
            }
        };
        // Per component, +∞ leaves the component out of the error test.
        let excluded = |a: f64| matches!(self.atol, Atol::PerComponent(_)) && a == f64::INFINITY;
        if let Some((i, a)) = atols
            .iter()
            .enumerate()
            .find(|(_, a)| !((a.is_finite() || excluded(**a)) && **a >= 0.0))
        {
            let reason = if matches!(self.atol, Atol::PerComponent(_)) {
                format!(
                    "must be finite and non-negative (or +inf: not error-controlled), got {a:?}"
                )
            } else {
                format!("must be finite and non-negative, got {a:?}")
            };
            return Err(Error::invalid(format!("atol[{i}]"), reason));
        }
        if len > 0 && self.controlled(len) == 0 {
            return Err(Error::invalid(
                "atol",
                "every component is +inf: no component would be error-controlled",
            ));
        }
        if self.rtol == 0.0 && atols.contains(&0.0) {
            return Err(Error::invalid(
                "tolerances",
                "rtol and atol are both zero: no step can meet that; give at least one a \
                 positive value",
            ));
        }
        if self.rtol > 0.0 && self.rtol < 1e-15 {
            return Err(Error::invalid(
                "rtol",
                format!(
                    "{:e} is below the resolution of f64 (about 2.2e-16 relative): no method can \
                     meet it; use 1e-14 or more",
                    self.rtol
                ),
            ));
        }
        Ok(())
    }

    /// Checks that every non-zero component of `state` can be held to the tolerances: a
    /// tolerance below the spacing of floats at a component's value (atol 1e-300 with rtol 0 on
    /// a value of 1) cannot be met by any step.
    ///
    /// Errors: [`Error::InvalidInput`] naming the first such component.
    pub(crate) fn check_against<S: crate::State>(&self, state: &S) -> Result<()> {
        for (i, &y) in state.as_slice().iter().enumerate() {
            let tolerance = self.atol(i) + self.rtol * y.abs();
            if y != 0.0 && tolerance < 4.0 * f64::EPSILON * y.abs() {
                return Err(Error::invalid(
                    "tolerances",
                    format!(
                        "rtol {:e} and atol {:e} ask component `{}` = {y:e} for an error of \
                         {tolerance:e}, below the spacing of floats there ({:e}): no step can \
                         meet it; raise rtol to 1e-14 or more, or atol",
                        self.rtol,
                        self.atol(i),
                        state.component_name(i),
                        f64::EPSILON * y.abs()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The absolute tolerance of component `i`.
    #[inline]
    pub(crate) fn atol(&self, i: usize) -> f64 {
        match &self.atol {
            Atol::Scalar(a) => *a,
            Atol::PerComponent(a) => a[i],
        }
    }

    /// The components of a state of `len` that the error test counts: all but those of
    /// per-component atol +∞.
    #[inline]
    pub(crate) fn controlled(&self, len: usize) -> usize {
        match &self.atol {
            Atol::Scalar(_) => len,
            Atol::PerComponent(a) => a.iter().filter(|a| a.is_finite()).count(),
        }
    }

    /// The absolute tolerance that weighs Newton updates of a component left out of the error
    /// test (atol +∞): the smallest finite one, so its iterates must still converge.
    pub(crate) fn smallest_finite_atol(&self) -> f64 {
        match &self.atol {
            Atol::Scalar(a) => *a,
            Atol::PerComponent(a) => a
                .iter()
                .copied()
                .filter(|a| a.is_finite())
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// The weight of component i's error in a step from `y` to `y_new`:
    /// atolᵢ + rtol·max(|yᵢ|, |ŷᵢ|).
    #[inline]
    pub(crate) fn scale(&self, i: usize, y: f64, y_new: f64) -> f64 {
        self.atol(i) + self.rtol * y.abs().max(y_new.abs())
    }

    /// The weighted RMS norm of the error whose component i is `e(i)`, for a step from `y` to
    /// `y_new`: for methods that form their error estimate component by component.
    #[inline]
    pub(crate) fn norm_of(&self, e: impl Fn(usize) -> f64, y: &[f64], y_new: &[f64]) -> f64 {
        let mut sum = 0.0;
        for i in 0..y.len() {
            let r = e(i) / self.scale(i, y[i], y_new[i]);
            sum += r * r;
        }
        (sum / self.controlled(y.len()).max(1) as f64).sqrt()
    }

    /// The weighted RMS norm of an error vector `e` for a step from `y` to `y_new`.
    #[inline]
    pub(crate) fn norm(&self, e: &[f64], y: &[f64], y_new: &[f64]) -> f64 {
        self.sum_squares(e, y, y_new, 1.0).sqrt() / (self.controlled(e.len()).max(1) as f64).sqrt()
    }

    /// Σᵢ (scale·eᵢ / scᵢ)², the building block of [`Tolerances::norm`] and of DOP853's
    /// combined estimate.
    #[inline]
    pub(crate) fn sum_squares(&self, e: &[f64], y: &[f64], y_new: &[f64], scale: f64) -> f64 {
        let mut sum = 0.0;
        for (i, ((ei, yi), zi)) in e.iter().zip(y).zip(y_new).enumerate() {
            let r = scale * ei / self.scale(i, *yi, *zi);
            sum += r * r;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::Tolerances;

    #[test]
    fn the_norm_is_the_weighted_rms() {
        let tol = Tolerances::new(1e-3, 1e-6);
        // sc = 1e-6 + 1e-3·max(|y|, |ŷ|): 1.001e-3 for the first component, 1e-6 for the second.
        let e = [1.001e-3, 2e-6];
        let n = tol.norm(&e, &[1.0, 0.0], &[0.5, 0.0]);
        assert!((n - (2.5f64).sqrt()).abs() < 1e-12, "{n}");
    }

    /// A component of per-component atol +∞ weighs nothing and does not count in n: the norm
    /// of the other components alone.
    #[test]
    fn an_infinite_atol_leaves_a_component_out_of_the_norm() {
        let tol = Tolerances::per_component(1e-3, vec![1e-6, f64::INFINITY]);
        tol.check(2).unwrap();
        let n = tol.norm(&[1.001e-3, 5.0], &[1.0, 0.0], &[0.5, 0.0]);
        assert!((n - 1.0).abs() < 1e-12, "{n}");
        assert!(Tolerances::new(1e-3, f64::INFINITY).check(2).is_err());
        assert!(
            Tolerances::per_component(1e-3, vec![f64::INFINITY; 2])
                .check(2)
                .is_err()
        );
    }

    #[test]
    fn bad_tolerances_are_refused() {
        for (rtol, atol) in [
            (-1.0, 1e-6),
            (f64::NAN, 1e-6),
            (1e-6, -1.0),
            (1e-6, f64::INFINITY),
        ] {
            assert!(
                Tolerances::new(rtol, atol).check(2).is_err(),
                "{rtol} {atol}"
            );
        }
        assert!(Tolerances::new(0.0, 0.0).check(2).is_err());
        assert!(Tolerances::new(1e-20, 1e-9).check(2).is_err());
        assert!(
            Tolerances::per_component(1e-6, vec![1e-9])
                .check(2)
                .is_err()
        );
        assert!(
            Tolerances::per_component(1e-6, vec![1e-9, 0.0])
                .check(2)
                .is_ok()
        );
        assert!(Tolerances::new(0.0, 1e-9).check(2).is_ok());
    }
}
