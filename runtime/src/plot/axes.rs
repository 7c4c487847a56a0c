//! The ranges a chart shows: fitted to the data, padded, and refused when they cannot be drawn.

use crate::{Error, Result};

/// Linear-axis values beyond this magnitude are refused: plotters computes spans and tick steps
/// in `f64`, and padding a range near ±1.8e308 overflows to infinity (its tick loop then never
/// ends). A log axis draws log₁₀ of the data, so it takes any positive finite value.
pub(crate) const LARGEST: f64 = 1e300;

/// One axis: the drawn range, in drawn units (log₁₀ of the data on a log axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Axis {
    pub(crate) log: bool,
    pub(crate) lo: f64,
    pub(crate) hi: f64,
}

impl Axis {
    /// Whether `v` can be drawn on this axis.
    pub(crate) fn takes(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    /// `v` in drawn units.
    pub(crate) fn project(&self, v: f64) -> f64 {
        if self.log { v.log10() } else { v }
    }

    /// The axis that shows every value of `values` it [`takes`](Axis::takes), padded by 5 % on
    /// each side; a single value gets a range around it.
    ///
    /// Errors: [`Error::InvalidInput`] (field `what`) when no value can be drawn, or a linear axis
    /// would have to show a value beyond ±[`LARGEST`].
    pub(crate) fn fit(what: &str, log: bool, values: impl Iterator<Item = f64>) -> Result<Axis> {
        let probe = Axis {
            log,
            lo: 0.0,
            hi: 0.0,
        };
        let mut range: Option<(f64, f64)> = None;
        for v in values.filter(|&v| probe.takes(v)) {
            let p = probe.project(v);
            range = Some(match range {
                None => (p, p),
                Some((lo, hi)) => (lo.min(p), hi.max(p)),
            });
        }
        let Some((lo, hi)) = range else {
            return Err(Error::invalid(
                what,
                if log {
                    "no positive finite value to draw on a log axis"
                } else {
                    "no finite value to draw"
                },
            ));
        };
        if !log && (lo < -LARGEST || hi > LARGEST) {
            return Err(Error::invalid(
                what,
                format!(
                    "values reach {:e}, beyond the ±1e300 a linear axis can draw; use a log axis \
                     or rescale the data",
                    if hi > LARGEST { hi } else { lo }
                ),
            ));
        }
        Ok(padded(log, lo, hi))
    }

    /// A fixed range given by the caller (a scene's bounds), checked like [`Axis::fit`].
    pub(crate) fn fixed(what: &str, lo: f64, hi: f64) -> Result<Axis> {
        if !(lo.is_finite() && hi.is_finite()) || lo > hi {
            return Err(Error::invalid(
                what,
                format!("must be a finite range lo ≤ hi, got ({lo:?}, {hi:?})"),
            ));
        }
        if lo < -LARGEST || hi > LARGEST {
            return Err(Error::invalid(
                what,
                format!("({lo:e}, {hi:e}) is beyond the ±1e300 a chart can draw"),
            ));
        }
        let mut axis = padded(false, lo, hi);
        if hi > lo {
            // The caller chose the range: keep it exactly, only widen a degenerate one.
            axis.lo = lo;
            axis.hi = hi;
        }
        Ok(axis)
    }
}

/// Pads [lo, hi] by 5 % a side, without overflow. A range too narrow for ticks to divide (a single
/// value, or a spread below 1e-9 of the magnitude) gets ±5 % of its value instead (±0.5 around
/// zero, and ±half a decade on a log axis).
fn padded(log: bool, lo: f64, hi: f64) -> Axis {
    let mid = 0.5 * lo + 0.5 * hi;
    let half = 0.5 * hi - 0.5 * lo;
    let half = if half > (1e-9 * mid.abs()).max(1e-290) {
        1.1 * half
    } else if log || mid == 0.0 {
        0.5
    } else {
        0.05 * mid.abs()
    };
    Axis {
        log,
        lo: mid - half,
        hi: mid + half,
    }
}

#[cfg(test)]
mod tests {
    use super::{Axis, LARGEST};

    #[test]
    fn ranges_are_padded_and_never_overflow() {
        let axis = Axis::fit("y", false, [0.0, 1.0].into_iter()).unwrap();
        assert!((axis.lo + 0.05).abs() < 1e-12 && (axis.hi - 1.05).abs() < 1e-12);
        // Values at the edge of what is allowed still pad to finite bounds.
        let axis = Axis::fit("y", false, [-LARGEST, LARGEST].into_iter()).unwrap();
        assert!(axis.lo.is_finite() && axis.hi.is_finite() && axis.lo < axis.hi);
        // A single value, zero, and a huge constant all get a usable span.
        for v in [0.0, 3.0, -7e20, 1e-300] {
            let axis = Axis::fit("y", false, [v, v].into_iter()).unwrap();
            assert!(axis.lo < v && v < axis.hi, "{v}: {axis:?}");
            assert!(axis.hi - axis.lo > v.abs() * 1e-12, "{v}: {axis:?}");
        }
        let axis = Axis::fit("y", true, [1e-200, 1e200].into_iter()).unwrap();
        assert!(axis.lo < -200.0 && axis.hi > 200.0);
    }

    #[test]
    fn data_that_cannot_be_drawn_is_refused() {
        assert!(Axis::fit("y", false, [f64::NAN, f64::INFINITY].into_iter()).is_err());
        assert!(Axis::fit("y", false, std::iter::empty()).is_err());
        assert!(Axis::fit("y", true, [0.0, -1.0].into_iter()).is_err());
        assert!(Axis::fit("y", false, [1e308, 1.0].into_iter()).is_err());
        assert!(Axis::fixed("x", 0.0, f64::INFINITY).is_err());
        assert!(Axis::fixed("x", f64::NAN, 1.0).is_err());
        assert!(Axis::fixed("x", 1.0, 0.0).is_err());
        assert_eq!(Axis::fixed("x", -1.0, 2.0).unwrap().lo, -1.0);
    }
}
