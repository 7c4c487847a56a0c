//! The history a BDF run keeps — the backward differences and the order — and how a caller or
//! the first step sets it.

use super::Bdf;
use super::coefficients::MAX_ORDER;
use crate::{Error, Jacobian, Result, State, Stats};

impl<M: Jacobian> Bdf<M> {
    /// Caps the order at `order` (1 … 5). At a fixed step the order then rises to it (and stays):
    /// with [`Bdf::set_history`], a fixed-order method.
    ///
    /// Errors: [`Error::InvalidInput`] for an order outside 1 … 5.
    pub fn set_max_order(&mut self, order: usize) -> Result<()> {
        if !(1..=MAX_ORDER).contains(&order) {
            return Err(Error::invalid(
                "max_order",
                format!("must be from 1 to {MAX_ORDER}, got {order}"),
            ));
        }
        self.max_order = Some(order);
        if self.order > order {
            self.order = order;
            self.equal_steps = 0;
            self.factored = false;
        }
        Ok(())
    }

    /// Starts from past values at a constant step `h` instead of from order 1: `past[j]` is
    /// y(t − j·h), `past[0]` the state the next step starts from, and the order becomes
    /// `past.len() − 1` (1 … 5). A multistep method's start from exact values, for measuring its
    /// order at a fixed step.
    ///
    /// Errors: [`Error::InvalidInput`] for fewer than 2 or more than 6 values, values of another
    /// size, or an order above [`Bdf::set_max_order`]'s.
    pub fn set_history(&mut self, h: f64, past: &[&M::State]) -> Result<()> {
        let k = past.len().wrapping_sub(1);
        if !(1..=self.max_order.unwrap_or(MAX_ORDER)).contains(&k) {
            return Err(Error::invalid(
                "past",
                format!(
                    "needs 2 to {} values (orders 1 to {}), got {}",
                    self.max_order.unwrap_or(MAX_ORDER) + 1,
                    self.max_order.unwrap_or(MAX_ORDER),
                    past.len()
                ),
            ));
        }
        let n = self.predict.as_slice().len();
        if past.iter().any(|y| y.as_slice().len() != n) {
            return Err(Error::invalid(
                "past",
                format!("values must have {n} components"),
            ));
        }
        // ∇ʲy at t by repeated differences: after pass j, D[i] (i ≥ j) is ∇ʲy(t − (i − j)h).
        for (dj, y) in self.differences.iter_mut().zip(past) {
            dj.as_mut_slice().copy_from_slice(y.as_slice());
        }
        for j in 1..=k {
            for i in (j..=k).rev() {
                let (low, high) = self.differences.split_at_mut(i);
                for (x, y) in high[0].as_mut_slice().iter_mut().zip(low[i - 1].as_slice()) {
                    *x = *y - *x;
                }
            }
        }
        for dj in self.differences.iter_mut().skip(k + 1) {
            dj.as_mut_slice().fill(0.0);
        }
        self.spacing = h;
        self.order = k;
        self.last_order = k;
        self.equal_steps = 0;
        self.factored = false;
        self.rejected = false;
        self.change = None;
        self.next = Some(h);
        Ok(())
    }

    /// The order the next step will take.
    pub fn order(&self) -> usize {
        self.order
    }

    /// D = (y, f(t, y)) at spacing 1 — scaled to the first step's h when it is attempted —
    /// order 1, no factorization.
    pub(super) fn start_history(&mut self, model: &M, t: f64, y: &M::State, stats: &mut Stats) {
        let [d0, d1, rest @ ..] = &mut self.differences;
        d0.clone_from(y);
        model.derivative(t, y, d1);
        stats.evaluations += 1;
        if let Some(mass) = &self.mass {
            // f is y′ only in rows where M is the identity's; elsewhere (algebraic rows, a
            // circuit's coupled capacitances) the start predicts no change.
            let entries = mass.entries();
            for (i, d) in d1.as_mut_slice().iter_mut().enumerate() {
                let mut row = entries.iter().filter(|e| e.0 == i);
                let unit = matches!((row.next(), row.next()), (Some(&(_, j, m)), None) if j == i && m == 1.0);
                if !unit {
                    *d = 0.0;
                }
            }
        }
        for dj in rest {
            dj.as_mut_slice().fill(0.0);
        }
        self.spacing = 1.0;
        self.order = 1;
        self.last_order = 1;
        self.equal_steps = 0;
        self.factored = false;
        self.rejected = false;
        self.change = None;
    }
}
