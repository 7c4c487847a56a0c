//! [`Statistics`]: the reductions over a complete ensemble, summed in member order.

use super::Members;
use crate::{Error, Result};

impl Members {
    /// Mean, sample variance and sorted values of each observation over the members.
    ///
    /// Errors: [`Error::InvalidInput`] unless every member is present, once, in order, with as
    /// many observations as the others.
    pub fn statistics(&self) -> Result<Statistics> {
        self.check()?;
        if !self.is_complete() {
            return Err(Error::invalid(
                "members",
                format!(
                    "statistics need every member: {} of {} present (merge the shards first)",
                    self.rows.len(),
                    self.members
                ),
            ));
        }
        let width = self.rows.first().map_or(0, |(_, r)| r.len());
        let n = self.rows.len() as f64;
        let column = |k: usize| self.rows.iter().map(move |(_, r)| r[k]);
        let mean: Vec<f64> = (0..width).map(|k| column(k).sum::<f64>() / n).collect();
        let variance = (0..width)
            .map(|k| {
                if self.rows.len() < 2 {
                    return 0.0;
                }
                column(k)
                    .map(|v| (v - mean[k]) * (v - mean[k]))
                    .sum::<f64>()
                    / (n - 1.0)
            })
            .collect();
        let sorted = (0..width)
            .map(|k| {
                let mut values: Vec<f64> = column(k).collect();
                values.sort_by(f64::total_cmp);
                values
            })
            .collect();
        Ok(Statistics {
            mean,
            variance,
            sorted,
        })
    }
}

/// Reductions over the members, one entry per observation.
#[derive(Clone, Debug, PartialEq)]
pub struct Statistics {
    /// Mean, summed in member order.
    pub mean: Vec<f64>,
    /// Sample variance Σ(v − mean)²/(M − 1) (0 for one member).
    pub variance: Vec<f64>,
    /// Each observation's values over the members, ascending (NaN last).
    pub sorted: Vec<Vec<f64>>,
}

impl Statistics {
    /// The `q`-quantile of observation `k`, interpolated linearly between order statistics
    /// (Hyndman & Fan 1996, definition 7, NumPy's and R's default): position (M − 1)·q.
    ///
    /// NaN when any member's value is NaN (NumPy's rule), as the mean is.
    ///
    /// Errors: [`Error::InvalidInput`] for `q` outside [0, 1] or `k` out of range.
    pub fn quantile(&self, k: usize, q: f64) -> Result<f64> {
        let values = self.sorted.get(k).ok_or_else(|| {
            Error::invalid("observation", format!("{k} of {}", self.sorted.len()))
        })?;
        if !(0.0..=1.0).contains(&q) {
            return Err(Error::invalid(
                "quantile",
                format!("must be in [0, 1], got {q:?}"),
            ));
        }
        // NumPy's rule: a NaN among the values makes every quantile NaN, as it does the mean
        // (`total_cmp` sorts NaNs to the ends, where they would shift the others silently).
        if values.first().is_some_and(|v| v.is_nan()) || values.last().is_some_and(|v| v.is_nan()) {
            return Ok(f64::NAN);
        }
        let position = q * (values.len() - 1) as f64;
        let (lo, frac) = (position.floor() as usize, position.fract());
        let hi = (lo + 1).min(values.len() - 1);
        Ok(values[lo] + frac * (values[hi] - values[lo]))
    }
}
