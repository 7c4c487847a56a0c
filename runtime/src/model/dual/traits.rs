//! The number traits nalgebra, `num-traits` and `approx` ask of a scalar, so that vectors and
//! matrices of dual numbers (`Vector3<Dual>`: `norm`, `dot`, `cross`) work as `f64`'s do. Every
//! function delegates to the rules of `rules.rs` and `piecewise.rs`.

use nalgebra::{ComplexField, RealField};
use num_traits::{FromPrimitive, Num, One, Signed, Zero};
use simba::scalar::{SubsetOf, SupersetOf};

use super::Dual;

impl Zero for Dual {
    #[inline(always)]
    fn zero() -> Self {
        Dual::constant(0.0)
    }
    #[inline(always)]
    fn is_zero(&self) -> bool {
        self.re == 0.0 && self.eps == 0.0
    }
}

impl One for Dual {
    #[inline(always)]
    fn one() -> Self {
        Dual::constant(1.0)
    }
}

impl Num for Dual {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(text: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(text, radix).map(Dual::constant)
    }
}

impl Signed for Dual {
    fn abs(&self) -> Self {
        Dual::abs(*self)
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if self.re <= other.re {
            Dual::constant(0.0)
        } else {
            *self - *other
        }
    }
    fn signum(&self) -> Self {
        Dual::signum(*self)
    }
    fn is_positive(&self) -> bool {
        self.re.is_sign_positive()
    }
    fn is_negative(&self) -> bool {
        self.re.is_sign_negative()
    }
}

impl FromPrimitive for Dual {
    fn from_i64(n: i64) -> Option<Self> {
        f64::from_i64(n).map(Dual::constant)
    }
    fn from_u64(n: u64) -> Option<Self> {
        f64::from_u64(n).map(Dual::constant)
    }
    fn from_f64(n: f64) -> Option<Self> {
        Some(Dual::constant(n))
    }
}

impl approx::AbsDiffEq for Dual {
    type Epsilon = Self;
    fn default_epsilon() -> Self {
        Dual::constant(f64::EPSILON)
    }
    fn abs_diff_eq(&self, other: &Self, epsilon: Self) -> bool {
        self.re.abs_diff_eq(&other.re, epsilon.re)
    }
}

impl approx::RelativeEq for Dual {
    fn default_max_relative() -> Self {
        Dual::constant(f64::default_max_relative())
    }
    fn relative_eq(&self, other: &Self, epsilon: Self, max_relative: Self) -> bool {
        self.re.relative_eq(&other.re, epsilon.re, max_relative.re)
    }
}

impl approx::UlpsEq for Dual {
    fn default_max_ulps() -> u32 {
        f64::default_max_ulps()
    }
    fn ulps_eq(&self, other: &Self, epsilon: Self, max_ulps: u32) -> bool {
        self.re.ulps_eq(&other.re, epsilon.re, max_ulps)
    }
}

/// One lane: a dual number is a scalar to nalgebra.
impl nalgebra::SimdValue for Dual {
    const LANES: usize = 1;
    type Element = Dual;
    type SimdBool = bool;
    #[inline(always)]
    fn splat(value: Dual) -> Self {
        value
    }
    #[inline(always)]
    fn extract(&self, _: usize) -> Dual {
        *self
    }
    #[inline(always)]
    unsafe fn extract_unchecked(&self, _: usize) -> Dual {
        *self
    }
    #[inline(always)]
    fn replace(&mut self, _: usize, value: Dual) {
        *self = value;
    }
    #[inline(always)]
    unsafe fn replace_unchecked(&mut self, _: usize, value: Dual) {
        *self = value;
    }
    #[inline(always)]
    fn select(self, condition: bool, other: Self) -> Self {
        if condition { self } else { other }
    }
}

impl nalgebra::Field for Dual {}

impl SubsetOf<Dual> for Dual {
    fn to_superset(&self) -> Dual {
        *self
    }
    fn from_superset_unchecked(element: &Dual) -> Self {
        *element
    }
    fn is_in_subset(_: &Dual) -> bool {
        true
    }
}

impl SupersetOf<f64> for Dual {
    fn is_in_subset(&self) -> bool {
        self.eps == 0.0
    }
    fn to_subset_unchecked(&self) -> f64 {
        self.re
    }
    fn from_subset(element: &f64) -> Self {
        Dual::constant(*element)
    }
}

impl SupersetOf<f32> for Dual {
    fn is_in_subset(&self) -> bool {
        self.eps == 0.0
    }
    fn to_subset_unchecked(&self) -> f32 {
        self.re as f32
    }
    fn from_subset(element: &f32) -> Self {
        Dual::constant(f64::from(*element))
    }
}

/// Methods of one dual number, delegated to its rules.
macro_rules! unary {
    ($($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self) -> Self {
            Dual::$name(self)
        }
    )*};
}

/// Constants (derivative zero).
macro_rules! constants {
    ($($name:ident),*) => {$(
        #[inline(always)]
        fn $name() -> Self {
            Dual::constant(<f64 as RealField>::$name())
        }
    )*};
}

impl ComplexField for Dual {
    type RealField = Dual;

    unary!(
        floor, ceil, round, trunc, fract, abs, recip, sin, cos, tan, asin, acos, atan, sinh, cosh,
        tanh, asinh, acosh, atanh, log2, log10, ln, ln_1p, sqrt, exp, exp2, exp_m1, cbrt, signum
    );

    #[inline(always)]
    fn from_real(re: Self) -> Self {
        re
    }
    #[inline(always)]
    fn real(self) -> Self {
        self
    }
    #[inline(always)]
    fn imaginary(self) -> Self {
        Dual::constant(0.0)
    }
    #[inline(always)]
    fn modulus(self) -> Self {
        self.abs()
    }
    #[inline(always)]
    fn modulus_squared(self) -> Self {
        self * self
    }
    /// The argument of a real number: 0 or π, a step.
    #[inline(always)]
    fn argument(self) -> Self {
        Dual::constant(if self.re >= 0.0 {
            0.0
        } else {
            std::f64::consts::PI
        })
    }
    #[inline(always)]
    fn norm1(self) -> Self {
        self.abs()
    }
    #[inline(always)]
    fn scale(self, factor: Self) -> Self {
        self * factor
    }
    #[inline(always)]
    fn unscale(self, factor: Self) -> Self {
        self / factor
    }
    #[inline(always)]
    fn conjugate(self) -> Self {
        self
    }
    #[inline(always)]
    fn hypot(self, other: Self) -> Self {
        Dual::hypot(self, other)
    }
    #[inline(always)]
    fn log(self, base: Self) -> Self {
        Dual::log(self, base)
    }
    #[inline(always)]
    fn powf(self, e: Self) -> Self {
        Dual::powf(self, e)
    }
    #[inline(always)]
    fn powc(self, e: Self) -> Self {
        Dual::powf(self, e)
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        Dual::mul_add(self, a, b)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        Dual::sin_cos(self)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        Dual::powi(self, n)
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        Dual::is_finite(*self)
    }
    #[inline(always)]
    fn try_sqrt(self) -> Option<Self> {
        (self.re >= 0.0).then(|| self.sqrt())
    }
}

impl RealField for Dual {
    constants!(
        pi,
        two_pi,
        frac_pi_2,
        frac_pi_3,
        frac_pi_4,
        frac_pi_6,
        frac_pi_8,
        frac_1_pi,
        frac_2_pi,
        frac_2_sqrt_pi,
        e,
        log2_e,
        log10_e,
        ln_2,
        ln_10
    );

    #[inline(always)]
    fn is_sign_positive(&self) -> bool {
        self.re.is_sign_positive()
    }
    #[inline(always)]
    fn is_sign_negative(&self) -> bool {
        self.re.is_sign_negative()
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        Dual::copysign(self, sign)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Dual::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Dual::min(self, other)
    }
    #[inline(always)]
    fn clamp(self, min: Self, max: Self) -> Self {
        Dual::clamp(self, min, max)
    }
    #[inline(always)]
    fn atan2(self, other: Self) -> Self {
        Dual::atan2(self, other)
    }
    fn min_value() -> Option<Self> {
        Some(Dual::constant(f64::MIN))
    }
    fn max_value() -> Option<Self> {
        Some(Dual::constant(f64::MAX))
    }
}
