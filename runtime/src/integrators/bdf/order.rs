//! The choice of the next step's order and size after a step at one h for k + 1 steps.

use super::Bdf;
use super::coefficients::{ERROR_CONST, MAX_FACTOR, MAX_ORDER};
use crate::math::Transcendental;
use crate::{Jacobian, State, Tolerances};

impl<M: Jacobian> Bdf<M> {
    /// Proposes the order and step after a step of size `h` at order k with error estimate
    /// `error` (at the new state `y`, correction d in `self.correction`) and step safety factor
    /// `safety`: the estimates of orders k − 1 and k + 1 from the differences the update will
    /// make, ∇ᵏyₙ₊₁ = ∇ᵏyₙ + d and ∇ᵏ⁺²yₙ₊₁ = d − ∇ᵏ⁺¹yₙ, each propose h·err_q^(−1/(q+1)); the
    /// largest wins, times `safety`, at most ×10 (SciPy's `BDF`).
    pub(super) fn propose(
        &mut self,
        h: f64,
        (safety, error): (f64, f64),
        tolerances: &Tolerances,
        y: &[f64],
    ) {
        let k = self.order;
        let d = self.correction.as_slice();
        let norm = |e: &dyn Fn(usize) -> f64| tolerances.norm_of(e, y, y);
        let max_order = self.max_order.unwrap_or(MAX_ORDER);
        let lower = if k > 1 {
            let dk = self.differences[k].as_slice();
            norm(&|i| ERROR_CONST[k - 1] * (dk[i] + d[i]))
        } else {
            f64::INFINITY
        };
        let higher = if k < max_order {
            let dk1 = self.differences[k + 1].as_slice();
            norm(&|i| ERROR_CONST[k + 1] * (d[i] - dk1[i]))
        } else {
            f64::INFINITY
        };
        let factors = [
            Transcendental::powf(lower, -1.0 / k as f64),
            Transcendental::powf(error, -1.0 / (k + 1) as f64),
            Transcendental::powf(higher, -1.0 / (k + 2) as f64),
        ];
        // The first largest, as NumPy's argmax.
        let mut best = 0;
        for (q, f) in factors.iter().enumerate() {
            if *f > factors[best] {
                best = q;
            }
        }
        let order = (k + best).saturating_sub(1).clamp(1, max_order);
        let factor = MAX_FACTOR.min(safety * factors[best]);
        self.change = Some(order);
        self.next = Some(h * factor);
    }
}
