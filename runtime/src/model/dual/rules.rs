//! The derivative rules: every method of `f64` a model's code may call, on a dual number.
//!
//! Each rule is the one the generated Jacobian uses (`macros/src/derivative.rs`), written in the
//! same order of operations, so the two Jacobians agree to rounding wherever the generated one
//! is finite. This file holds the smooth functions — roots, exponentials, logarithms,
//! trigonometric and hyperbolic functions, powers — and `Transcendental` on `Dual`; the
//! piecewise ones (kinks, steps, remainders) and the predicates are in `piecewise.rs`. Values
//! come from [`Transcendental`], the platform's functions or, under the `deterministic` feature,
//! `libm`'s.

use std::f64::consts::{LN_2, LN_10};

use super::Dual;
use super::arithmetic::term;
use crate::math::Transcendental;

impl Dual {
    /// f(a) with derivative f′(a)·a′; `slope` (f′(a)) is evaluated only when a′ ≠ 0.
    #[inline(always)]
    pub(super) fn chain(self, value: f64, slope: impl FnOnce() -> f64) -> Dual {
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
