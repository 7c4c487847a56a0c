//! The derivative rules: every method of `f64` a model's code may call, on a dual number.
//!
//! Each rule is the one the generated Jacobian uses (`macros/src/derivative.rs`), written in the
//! same order of operations, so the two Jacobians agree to rounding wherever the generated one
//! is finite. Functions with kinks take the derivative of the side Rust's definition falls on
//! (|x|′ = signum x, ±1 at ±0; `max`/`min` the first argument's at a tie); step functions
//! (`floor`, `ceil`, `round`, `trunc`, `signum`) have derivative zero, `fract` one. Values come
//! from [`Transcendental`], the platform's functions or, under the `deterministic` feature,
//! `libm`'s.

use std::cmp::Ordering;
use std::f64::consts::{LN_2, LN_10};

use super::Dual;
use super::arithmetic::term;
use crate::math::Transcendental;

impl Dual {
    /// f(a) with derivative f′(a)·a′; `slope` (f′(a)) is evaluated only when a′ ≠ 0.
    #[inline(always)]
    fn chain(self, value: f64, slope: impl FnOnce() -> f64) -> Dual {
        let eps = if self.eps == 0.0 {
            0.0
        } else {
            slope() * self.eps
        };
        Dual::new(value, eps)
    }

    /// √a; derivative 1/(2√a).
    #[inline(always)]
    pub fn sqrt(self) -> Dual {
        let root = self.re.sqrt();
        self.chain(root, || 1.0 / (2.0 * root))
    }

    /// ∛a; derivative 1/(3·∛a²).
    #[inline(always)]
    pub fn cbrt(self) -> Dual {
        let root = Transcendental::cbrt(self.re);
        self.chain(root, || 1.0 / (3.0 * root.powi(2)))
    }

    /// eᵃ.
    #[inline(always)]
    pub fn exp(self) -> Dual {
        let value = Transcendental::exp(self.re);
        self.chain(value, || value)
    }

    /// 2ᵃ; derivative ln 2·2ᵃ.
    #[inline(always)]
    pub fn exp2(self) -> Dual {
        let value = Transcendental::exp2(self.re);
        self.chain(value, || LN_2 * value)
    }

    /// eᵃ − 1; derivative (eᵃ − 1) + 1.
    #[inline(always)]
    pub fn exp_m1(self) -> Dual {
        let value = Transcendental::exp_m1(self.re);
        self.chain(value, || value + 1.0)
    }

    /// ln a; derivative 1/a.
    #[inline(always)]
    pub fn ln(self) -> Dual {
        self.chain(Transcendental::ln(self.re), || 1.0 / self.re)
    }

    /// ln(1 + a); derivative 1/(1 + a).
    #[inline(always)]
    pub fn ln_1p(self) -> Dual {
        self.chain(Transcendental::ln_1p(self.re), || 1.0 / (1.0 + self.re))
    }

    /// log₂ a; derivative 1/(ln 2·a).
    #[inline(always)]
    pub fn log2(self) -> Dual {
        self.chain(Transcendental::log2(self.re), || 1.0 / (LN_2 * self.re))
    }

    /// log₁₀ a; derivative 1/(ln 10·a).
    #[inline(always)]
    pub fn log10(self) -> Dual {
        self.chain(Transcendental::log10(self.re), || 1.0 / (LN_10 * self.re))
    }

    /// log_b a = ln a / ln b.
    #[inline(always)]
    pub fn log(self, base: Dual) -> Dual {
        self.ln() / base.ln()
    }

    /// sin a.
    #[inline(always)]
    pub fn sin(self) -> Dual {
        self.chain(Transcendental::sin(self.re), || {
            Transcendental::cos(self.re)
        })
    }

    /// cos a.
    #[inline(always)]
    pub fn cos(self) -> Dual {
        self.chain(Transcendental::cos(self.re), || {
            -Transcendental::sin(self.re)
        })
    }

    /// (sin a, cos a).
    #[inline(always)]
    pub fn sin_cos(self) -> (Dual, Dual) {
        (self.sin(), self.cos())
    }

    /// tan a; derivative 1 + tan²a.
    #[inline(always)]
    pub fn tan(self) -> Dual {
        let value = Transcendental::tan(self.re);
        self.chain(value, || 1.0 + value.powi(2))
    }

    /// asin a; derivative 1/√(1 − a²).
    #[inline(always)]
    pub fn asin(self) -> Dual {
        self.chain(Transcendental::asin(self.re), || {
            1.0 / (1.0 - self.re.powi(2)).sqrt()
        })
    }

    /// acos a; derivative −1/√(1 − a²).
    #[inline(always)]
    pub fn acos(self) -> Dual {
        self.chain(Transcendental::acos(self.re), || {
            -(1.0 / (1.0 - self.re.powi(2)).sqrt())
        })
    }

    /// atan a; derivative 1/(1 + a²).
    #[inline(always)]
    pub fn atan(self) -> Dual {
        self.chain(Transcendental::atan(self.re), || {
            1.0 / (1.0 + self.re.powi(2))
        })
    }

    /// sinh a.
    #[inline(always)]
    pub fn sinh(self) -> Dual {
        self.chain(Transcendental::sinh(self.re), || {
            Transcendental::cosh(self.re)
        })
    }

    /// cosh a.
    #[inline(always)]
    pub fn cosh(self) -> Dual {
        self.chain(Transcendental::cosh(self.re), || {
            Transcendental::sinh(self.re)
        })
    }

    /// tanh a; derivative 1 − tanh²a.
    #[inline(always)]
    pub fn tanh(self) -> Dual {
        let value = Transcendental::tanh(self.re);
        self.chain(value, || 1.0 - value.powi(2))
    }

    /// asinh a; derivative 1/√(a² + 1), as 1/hypot(a, 1) so that it does not overflow.
    #[inline(always)]
    pub fn asinh(self) -> Dual {
        self.chain(Transcendental::asinh(self.re), || {
            1.0 / Transcendental::hypot(self.re, 1.0)
        })
    }

    /// acosh a; derivative 1/√(a² − 1), as 1/(√(a − 1)·√(a + 1)).
    #[inline(always)]
    pub fn acosh(self) -> Dual {
        self.chain(Transcendental::acosh(self.re), || {
            1.0 / ((self.re - 1.0).sqrt() * (self.re + 1.0).sqrt())
        })
    }

    /// atanh a; derivative 1/(1 − a²), as 1/((1 − a)(1 + a)).
    #[inline(always)]
    pub fn atanh(self) -> Dual {
        self.chain(Transcendental::atanh(self.re), || {
            1.0 / ((1.0 - self.re) * (1.0 + self.re))
        })
    }

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

    /// 1/a.
    #[inline(always)]
    pub fn recip(self) -> Dual {
        Dual::constant(1.0) / self
    }

    /// aⁿ; derivative n·aⁿ⁻¹.
    #[inline(always)]
    pub fn powi(self, n: i32) -> Dual {
        self.chain(self.re.powi(n), || f64::from(n) * self.re.powi(n - 1))
    }

    /// aᵇ; derivative b·aᵇ⁻¹·a′ + aᵇ·ln a·b′ (the second term only when b varies: a constant
    /// exponent of a negative or zero base is as finite as `f64::powf` is there).
    #[inline(always)]
    pub fn powf(self, b: Dual) -> Dual {
        let value = Transcendental::powf(self.re, b.re);
        let by_base = term(b.re * Transcendental::powf(self.re, b.re - 1.0), self.eps);
        let by_exponent = if b.eps == 0.0 {
            0.0
        } else {
            value * Transcendental::ln(self.re) * b.eps
        };
        Dual::new(value, by_base + by_exponent)
    }

    /// atan2(a, b), the angle of (b, a); derivative (b·a′ − a·b′)/(a² + b²), computed over
    /// hypot(a, b) twice so that it does not overflow.
    #[inline(always)]
    pub fn atan2(self, b: Dual) -> Dual {
        let value = Transcendental::atan2(self.re, b.re);
        if self.eps == 0.0 && b.eps == 0.0 {
            return Dual::constant(value);
        }
        let h = Transcendental::hypot(self.re, b.re);
        let eps = (term(b.re / h, self.eps) - term(self.re / h, b.eps)) / h;
        Dual::new(value, eps)
    }

    /// √(a² + b²) without overflow; derivative (a·a′ + b·b′)/hypot(a, b).
    #[inline(always)]
    pub fn hypot(self, b: Dual) -> Dual {
        let value = Transcendental::hypot(self.re, b.re);
        if self.eps == 0.0 && b.eps == 0.0 {
            return Dual::constant(value);
        }
        Dual::new(value, (term(self.re, self.eps) + term(b.re, b.eps)) / value)
    }

    /// a·b + c; its value fused as `f64::mul_add` computes it.
    #[inline(always)]
    pub fn mul_add(self, b: Dual, c: Dual) -> Dual {
        let product = self * b;
        Dual::new(self.re.mul_add(b.re, c.re), product.eps + c.eps)
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

    /// a in degrees.
    #[inline(always)]
    pub fn to_degrees(self) -> Dual {
        Dual::new(
            self.re.to_degrees(),
            self.eps * (180.0 / std::f64::consts::PI),
        )
    }

    /// a (in degrees) in radians.
    #[inline(always)]
    pub fn to_radians(self) -> Dual {
        Dual::new(
            self.re.to_radians(),
            self.eps * (std::f64::consts::PI / 180.0),
        )
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

/// The model's code calls its transcendental functions through [`Transcendental`] (see
/// `crate::math`); its dual copy does too, with the rules above.
macro_rules! transcendental {
    ($($receiver:ty => $value:expr),*) => {$(
        impl Transcendental for $receiver {
            type Output = Dual;
            transcendental!(@unary $value; sin, cos, tan, asin, acos, atan, sinh, cosh, tanh,
                asinh, acosh, atanh, exp, exp2, exp_m1, ln, ln_1p, log2, log10, cbrt);
            transcendental!(@binary $value; powf, atan2, hypot, log);
        }
    )*};
    (@unary $value:expr; $($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self) -> Dual {
            Dual::$name($value(self))
        }
    )*};
    (@binary $value:expr; $($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self, other: Dual) -> Dual {
            Dual::$name($value(self), other)
        }
    )*};
}

transcendental!(Dual => std::convert::identity, &Dual => |x: &Dual| *x);
