//! The rules of `f64`'s piecewise methods on a dual number — kinks, steps and remainders —
//! and its predicates and order, which read the value only.
//!
//! Functions with kinks take the derivative of the side Rust's definition falls on
//! (|x|′ = signum x, ±1 at ±0; `max`/`min` the first argument's at a tie); step functions
//! (`floor`, `ceil`, `round`, `trunc`, `signum`) have derivative zero, `fract` one, as in the
//! generated Jacobian (`macros/src/derivative.rs`).

use std::cmp::Ordering;

use super::Dual;
use super::arithmetic::term;

impl Dual {
    /// |a|; derivative signum a (±1 at ±0).
    #[inline(always)]
    pub fn abs(self) -> Dual {
        self.chain(self.re.abs(), || self.re.signum())
    }

    /// signum a; derivative zero.
    #[inline(always)]
    pub fn signum(self) -> Dual {
        Dual::constant(self.re.signum())
    }

    /// The larger of a and b with its derivative (a's at a tie); a NaN argument is ignored,
    /// as `f64::max` ignores it.
    #[inline(always)]
    pub fn max(self, b: Dual) -> Dual {
        if self.re.is_nan() || b.re > self.re {
            b
        } else {
            self
        }
    }

    /// The smaller of a and b with its derivative (a's at a tie); a NaN argument is ignored,
    /// as `f64::min` ignores it.
    #[inline(always)]
    pub fn min(self, b: Dual) -> Dual {
        if self.re.is_nan() || b.re < self.re {
            b
        } else {
            self
        }
    }

    /// a restricted to [lo, hi]: max(a, lo), then min with hi; at a bound, the bound's
    /// derivative. NaN stays NaN, as `f64::clamp` keeps it.
    #[inline(always)]
    pub fn clamp(self, lo: Dual, hi: Dual) -> Dual {
        if self.re.is_nan() {
            return self;
        }
        let above = if lo.re <= self.re { self } else { lo };
        if above.re <= hi.re { above } else { hi }
    }

    /// ⌊a⌋; derivative zero.
    #[inline(always)]
    pub fn floor(self) -> Dual {
        Dual::constant(self.re.floor())
    }

    /// ⌈a⌉; derivative zero.
    #[inline(always)]
    pub fn ceil(self) -> Dual {
        Dual::constant(self.re.ceil())
    }

    /// a rounded half away from zero; derivative zero.
    #[inline(always)]
    pub fn round(self) -> Dual {
        Dual::constant(self.re.round())
    }

    /// a rounded half to even; derivative zero.
    #[inline(always)]
    pub fn round_ties_even(self) -> Dual {
        Dual::constant(self.re.round_ties_even())
    }

    /// a rounded toward zero; derivative zero.
    #[inline(always)]
    pub fn trunc(self) -> Dual {
        Dual::constant(self.re.trunc())
    }

    /// a − trunc(a); derivative one.
    #[inline(always)]
    pub fn fract(self) -> Dual {
        Dual::new(self.re.fract(), self.eps)
    }

    /// a with the sign of b; derivative ±a′ (b's sign is a step).
    #[inline(always)]
    pub fn copysign(self, b: Dual) -> Dual {
        let value = self.re.copysign(b.re);
        let flipped = value.is_sign_negative() != self.re.is_sign_negative();
        Dual::new(value, if flipped { -self.eps } else { self.eps })
    }

    /// a − b·⌊a/b⌋ for b > 0 (Rust's Euclidean remainder, never negative).
    #[inline(always)]
    pub fn rem_euclid(self, b: Dual) -> Dual {
        let quotient = self.re.div_euclid(b.re);
        Dual::new(self.re.rem_euclid(b.re), self.eps - term(quotient, b.eps))
    }

    /// The Euclidean quotient, an integer; derivative zero.
    #[inline(always)]
    pub fn div_euclid(self, b: Dual) -> Dual {
        Dual::constant(self.re.div_euclid(b.re))
    }

    /// Whether the value is NaN.
    #[inline(always)]
    pub fn is_nan(self) -> bool {
        self.re.is_nan()
    }

    /// Whether the value and the derivative are finite.
    #[inline(always)]
    pub fn is_finite(self) -> bool {
        self.re.is_finite() && self.eps.is_finite()
    }

    /// Whether the value is infinite.
    #[inline(always)]
    pub fn is_infinite(self) -> bool {
        self.re.is_infinite()
    }

    /// Whether the value has a positive sign (+0 included).
    #[inline(always)]
    pub fn is_sign_positive(self) -> bool {
        self.re.is_sign_positive()
    }

    /// Whether the value has a negative sign (−0 included).
    #[inline(always)]
    pub fn is_sign_negative(self) -> bool {
        self.re.is_sign_negative()
    }

    /// The values' total order, as `f64::total_cmp`.
    #[inline(always)]
    pub fn total_cmp(&self, other: &Dual) -> Ordering {
        self.re.total_cmp(&other.re)
    }
}
