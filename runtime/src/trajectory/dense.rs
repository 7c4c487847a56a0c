//! Dense output: the store that keeps one polynomial per accepted step (each a
//! [`DenseStep`], filled by the integrator) for [`crate::Trajectory::at`].

use crate::integrators::DenseStep;
use crate::{Error, Result, State};

/// The dense output of a whole run: one polynomial per accepted step, in time order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DenseOutput {
    /// Step starts, increasing.
    starts: Vec<f64>,
    /// Step sizes h: each polynomial is in θ = (t − start)/h.
    sizes: Vec<f64>,
    /// Where each step's validity ends: start + h, or earlier when an event cut the step short.
    ends: Vec<f64>,
    /// Offsets into `values` where each step's coefficients begin (one more entry than steps).
    offsets: Vec<usize>,
    /// Coefficients, step after step, c₀ first, each `dim` long.
    values: Vec<f64>,
    dim: usize,
}

impl DenseOutput {
    pub(crate) fn new(dim: usize) -> Self {
        DenseOutput {
            offsets: vec![0],
            dim,
            ..Default::default()
        }
    }

    /// Appends one step's polynomial, valid up to `end` (≤ t + h).
    pub(crate) fn push<S: State>(&mut self, step: &DenseStep<S>, end: f64) {
        self.starts.push(step.t);
        self.sizes.push(step.h);
        self.ends.push(end);
        for c in step.coefficients() {
            self.values.extend_from_slice(c.as_slice());
        }
        self.offsets.push(self.values.len());
    }

    /// Steps held.
    pub fn len(&self) -> usize {
        self.starts.len()
    }

    /// Whether no step is held.
    pub fn is_empty(&self) -> bool {
        self.starts.is_empty()
    }

    /// The time span covered.
    pub fn span(&self) -> Option<(f64, f64)> {
        Some((*self.starts.first()?, *self.ends.last()?))
    }

    /// Writes y(t) into `out` (its components; other parts of `out` are kept).
    ///
    /// At a time shared by two steps (a step boundary, or an event that changed the state) the
    /// later step is used, so the value after a reset is the one after the event.
    ///
    /// Errors: [`Error::InvalidInput`] when `t` is outside the span or not finite.
    pub fn eval_into<S: State>(&self, t: f64, out: &mut S) -> Result<()> {
        let outside = || {
            Error::invalid(
                "t",
                format!(
                    "{t:?} is outside the dense output's span {:?}",
                    self.span().unwrap_or((f64::NAN, f64::NAN))
                ),
            )
        };
        let (lo, hi) = self.span().ok_or_else(outside)?;
        if !(t >= lo && t <= hi) {
            return Err(outside());
        }
        // The last step starting at or before t.
        let k = self.starts.partition_point(|&s| s <= t).saturating_sub(1);
        let theta = if self.sizes[k] > 0.0 {
            ((t - self.starts[k]) / self.sizes[k]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let coefficients = &self.values[self.offsets[k]..self.offsets[k + 1]];
        let out = out.as_mut_slice();
        let degree = coefficients.len() / self.dim - 1;
        out.copy_from_slice(&coefficients[degree * self.dim..]);
        for c in coefficients.chunks_exact(self.dim).rev().skip(1) {
            for (o, a) in out.iter_mut().zip(c) {
                *o = *o * theta + a;
            }
        }
        Ok(())
    }
}
