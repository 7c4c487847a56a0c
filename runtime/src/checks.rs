//! Checks shared by the runners, the stepper and the integrators: a step size, a start time,
//! the divergence limit, a state's first bad component. One home, so none of them imports another for these.

use crate::{Error, Result, State};

/// A fixed step size: finite and positive.
///
/// Errors: [`Error::InvalidInput`] otherwise.
pub(crate) fn check_dt(dt: f64) -> Result<()> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            "dt",
            format!("must be finite and positive, got {dt:?}"),
        ))
    }
}

/// A start time: finite.
///
/// Errors: [`Error::InvalidInput`] otherwise.
pub(crate) fn check_t0(t0: f64) -> Result<()> {
    if t0.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(
            "t0",
            format!("start time must be finite, got {t0:?}"),
        ))
    }
}

/// The divergence limit of a run from `state`: the `option` given (see
/// [`crate::RunOptions::divergence_limit`]) or the default. An infinite limit still stops at a
/// non-finite state: it is kept as the largest finite number.
///
/// Errors: [`Error::InvalidInput`] for a limit that is not positive (NaN included).
pub(crate) fn divergence_limit(option: Option<f64>, state: &[f64]) -> Result<f64> {
    match option {
        None => {
            let scale = state.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            Ok((1e10 * scale).min(f64::MAX))
        }
        Some(limit) if limit > 0.0 => Ok(limit.min(f64::MAX)),
        Some(limit) => Err(Error::invalid(
            "divergence_limit",
            format!("must be positive, got {limit:?}"),
        )),
    }
}

/// The first component that is NaN or whose magnitude exceeds `limit`.
#[inline]
pub(crate) fn first_outside<S: State>(state: &S, limit: f64) -> Option<(usize, f64)> {
    let s = state.as_slice();
    // One branch-free pass for the common case; locate the culprit only on failure.
    let ok = s.iter().fold(true, |ok, x| ok & (x.abs() <= limit));
    if ok {
        None
    } else {
        s.iter()
            .position(|x| x.is_nan() || x.abs() > limit)
            .map(|i| (i, s[i]))
    }
}
