//! Forward-mode automatic differentiation: what `#[system(jacobian = dual)]` generates for a
//! fixed-size model whose code the macro does not differentiate symbolically.
//!
//! A [`Dual`] number a + b·ε (ε² = 0) carries a value and its derivative along one direction;
//! evaluating f on dual numbers whose ε-parts seed component j of the state gives f(y) and
//! ∂f/∂yⱼ, exact to rounding (Griewank & Walther, *Evaluating Derivatives*, 2nd ed., SIAM 2008,
//! §3.1). The type exists so code written for `f64` also reads for dual numbers: `2.0 * x` and
//! `self.k * v` (an `f64` on the left), `k * v` for a nalgebra vector `v` of dual numbers,
//! comparisons with `f64`, `as` casts, and every method of `f64` a force uses.
//!
//! The derivative rules (`rules.rs`, `piecewise.rs`) are the generated Jacobian's own
//! (`macros/src/derivative.rs`), so the two paths agree to rounding wherever the generated one
//! is finite: the quotient rule as a′/b − (a/b)·b′/b (finite where a/b is, even when b²
//! overflows), xⁿ′ = n·xⁿ⁻¹ (not exp(n·ln x), NaN at x ≤ 0), rounding functions with derivative
//! zero, and a term whose direction is zero left out rather than multiplied (0·∞ is NaN). The
//! values are `f64`'s through [`crate::math::Transcendental`], so the `deterministic` feature
//! covers the dual copies too.
//!
//! The macro writes a copy of the model's function over `Dual` (`f64` in its types read as
//! `Dual`, its float literals and parameters as constants) and calls it once per state component
//! ([`Seeded`] seeds the arguments, [`Tangent`] reads a column back): n evaluations of f at
//! roughly twice the cost of one each, against central differences' 2n, and no step size.

mod arithmetic;
mod piecewise;
mod rules;
mod seed;
mod traits;

pub use seed::{DualCast, Seeded, Tangent, ToDual};

use std::fmt;

/// A dual number: a value and its derivative along one direction of the state.
/// Comparisons (`==`, `<`, with another `Dual` or an `f64`) read the values only, as the
/// model's `f64` code compares them.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dual {
    re: f64,
    eps: f64,
}

impl Dual {
    /// A constant: derivative zero.
    #[inline(always)]
    pub fn constant(value: f64) -> Self {
        Dual {
            re: value,
            eps: 0.0,
        }
    }

    /// The value `value` with derivative `derivative`.
    #[inline(always)]
    pub fn new(value: f64, derivative: f64) -> Self {
        Dual {
            re: value,
            eps: derivative,
        }
    }

    /// The value.
    #[inline(always)]
    pub fn value(self) -> f64 {
        self.re
    }

    /// The derivative.
    #[inline(always)]
    pub fn derivative(self) -> f64 {
        self.eps
    }
}

impl From<f64> for Dual {
    #[inline(always)]
    fn from(value: f64) -> Self {
        Dual::constant(value)
    }
}

/// `f64::from(n)` in a model's code reads `Dual::from(n)` in its dual copy: the same lossless
/// conversions as `f64`'s.
macro_rules! from_lossless {
    ($($p:ty),*) => {$(
        impl From<$p> for Dual {
            #[inline(always)]
            fn from(value: $p) -> Self {
                Dual::constant(f64::from(value))
            }
        }
    )*};
}

from_lossless!(f32, i8, i16, i32, u8, u16, u32);

impl fmt::Display for Dual {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} + {}ε", self.re, self.eps)
    }
}

impl PartialEq for Dual {
    #[inline(always)]
    fn eq(&self, other: &Dual) -> bool {
        self.re == other.re
    }
}

impl PartialOrd for Dual {
    #[inline(always)]
    fn partial_cmp(&self, other: &Dual) -> Option<std::cmp::Ordering> {
        self.re.partial_cmp(&other.re)
    }
}

impl PartialEq<f64> for Dual {
    #[inline(always)]
    fn eq(&self, other: &f64) -> bool {
        self.re == *other
    }
}

impl PartialOrd<f64> for Dual {
    #[inline(always)]
    fn partial_cmp(&self, other: &f64) -> Option<std::cmp::Ordering> {
        self.re.partial_cmp(other)
    }
}

impl PartialEq<Dual> for f64 {
    #[inline(always)]
    fn eq(&self, other: &Dual) -> bool {
        *self == other.re
    }
}

impl PartialOrd<Dual> for f64 {
    #[inline(always)]
    fn partial_cmp(&self, other: &Dual) -> Option<std::cmp::Ordering> {
        self.partial_cmp(&other.re)
    }
}

#[cfg(test)]
mod tests;
