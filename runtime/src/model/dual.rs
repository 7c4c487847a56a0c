//! Forward-mode automatic differentiation: what `#[system(jacobian = dual)]` generates for a
//! fixed-size model whose code the macro does not differentiate symbolically.
//!
//! A [`Dual`] number a + b·ε (ε² = 0) carries a value and its derivative along one direction;
//! evaluating f on dual numbers whose ε-parts seed component j of the state gives f(y) and
//! ∂f/∂yⱼ, exact to rounding (Griewank & Walther, *Evaluating Derivatives*, 2nd ed., SIAM 2008,
//! §3.1). The derivative rules are `num-dual`'s ([`num_dual::Dual64`]); this newtype exists so
//! code written for `f64` also reads for dual numbers: `2.0 * x` and `self.k * v` (an `f64` on
//! the left), `k * v` for a nalgebra vector `v` of dual numbers, comparisons with `f64`, and
//! `as` casts, none of which Rust lets a crate add to a foreign type.
//!
//! The macro writes a copy of the model's function over `Dual` (`f64` in its types read as
//! `Dual`, its float literals and parameters as constants) and calls it once per state component
//! ([`Seeded`] seeds the arguments, [`Seeded::tangent`] reads a column back): n evaluations of
//! f at roughly twice the cost of one each, against central differences' 2n, and no step size.

use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

use nalgebra::allocator::Allocator;
use nalgebra::{ComplexField, DefaultAllocator, Dim, Matrix, OMatrix, RealField, Storage};
use num_dual::Dual64;

use crate::math::Transcendental;
use num_traits::{FromPrimitive, Num, One, Signed, Zero};
use simba::scalar::{SubsetOf, SupersetOf};

/// A dual number: a value and its derivative along one direction of the state.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Dual(Dual64);

impl Dual {
    /// A constant: derivative zero.
    #[inline(always)]
    pub fn constant(value: f64) -> Self {
        Dual(Dual64::from_re(value))
    }

    /// The value `value` with derivative `derivative`.
    #[inline(always)]
    pub fn new(value: f64, derivative: f64) -> Self {
        Dual(Dual64::new(value, derivative))
    }

    /// The value.
    #[inline(always)]
    pub fn value(self) -> f64 {
        self.0.re
    }

    /// The derivative.
    #[inline(always)]
    pub fn derivative(self) -> f64 {
        self.0.eps
    }
}

impl Default for Dual {
    fn default() -> Self {
        Dual::constant(0.0)
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
        write!(f, "{} + {}ε", self.0.re, self.0.eps)
    }
}

impl PartialEq<f64> for Dual {
    #[inline(always)]
    fn eq(&self, other: &f64) -> bool {
        self.0.re == *other
    }
}

impl PartialOrd<f64> for Dual {
    #[inline(always)]
    fn partial_cmp(&self, other: &f64) -> Option<std::cmp::Ordering> {
        self.0.re.partial_cmp(other)
    }
}

impl PartialEq<Dual> for f64 {
    #[inline(always)]
    fn eq(&self, other: &Dual) -> bool {
        *self == other.0.re
    }
}

impl PartialOrd<Dual> for f64 {
    #[inline(always)]
    fn partial_cmp(&self, other: &Dual) -> Option<std::cmp::Ordering> {
        self.partial_cmp(&other.0.re)
    }
}

impl Neg for Dual {
    type Output = Dual;
    #[inline(always)]
    fn neg(self) -> Dual {
        Dual(-self.0)
    }
}

/// `Dual ∘ Dual`, `Dual ∘ f64` and `f64 ∘ Dual`, and the assigning forms, for one operator.
macro_rules! arithmetic {
    ($($op:ident $method:ident $assign:ident $assign_method:ident),*) => {$(
        impl $op for Dual {
            type Output = Dual;
            #[inline(always)]
            fn $method(self, other: Dual) -> Dual {
                Dual($op::$method(self.0, other.0))
            }
        }
        impl $op<f64> for Dual {
            type Output = Dual;
            #[inline(always)]
            fn $method(self, other: f64) -> Dual {
                Dual($op::$method(self.0, Dual64::from_re(other)))
            }
        }
        impl $op<Dual> for f64 {
            type Output = Dual;
            #[inline(always)]
            fn $method(self, other: Dual) -> Dual {
                Dual($op::$method(Dual64::from_re(self), other.0))
            }
        }
        impl $assign for Dual {
            #[inline(always)]
            fn $assign_method(&mut self, other: Dual) {
                *self = $op::$method(*self, other);
            }
        }
        impl $assign<f64> for Dual {
            #[inline(always)]
            fn $assign_method(&mut self, other: f64) {
                *self = $op::$method(*self, other);
            }
        }
    )*};
}

arithmetic!(
    Add add AddAssign add_assign,
    Sub sub SubAssign sub_assign,
    Mul mul MulAssign mul_assign,
    Div div DivAssign div_assign
);

/// The remainder's derivative: a mod b = a − b·trunc(a/b), trunc's derivative zero.
impl Rem for Dual {
    type Output = Dual;
    #[inline(always)]
    fn rem(self, other: Dual) -> Dual {
        self - other * Dual::constant((self.0.re / other.0.re).trunc())
    }
}

impl Rem<f64> for Dual {
    type Output = Dual;
    #[inline(always)]
    fn rem(self, other: f64) -> Dual {
        self % Dual::constant(other)
    }
}

impl RemAssign for Dual {
    #[inline(always)]
    fn rem_assign(&mut self, other: Dual) {
        *self = *self % other;
    }
}

impl Sum for Dual {
    fn sum<I: Iterator<Item = Dual>>(iter: I) -> Dual {
        iter.fold(Dual::constant(0.0), Add::add)
    }
}

impl<'a> Sum<&'a Dual> for Dual {
    fn sum<I: Iterator<Item = &'a Dual>>(iter: I) -> Dual {
        iter.copied().sum()
    }
}

impl Product for Dual {
    fn product<I: Iterator<Item = Dual>>(iter: I) -> Dual {
        iter.fold(Dual::constant(1.0), Mul::mul)
    }
}

/// `k * v` for a nalgebra matrix or vector `v` of dual numbers (nalgebra implements the scalar
/// on the left for primitive numbers only).
impl<R: Dim, C: Dim, S: Storage<Dual, R, C>> Mul<Matrix<Dual, R, C, S>> for Dual
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = OMatrix<Dual, R, C>;
    #[inline(always)]
    fn mul(self, matrix: Matrix<Dual, R, C, S>) -> Self::Output {
        matrix * self
    }
}

impl<'a, R: Dim, C: Dim, S: Storage<Dual, R, C>> Mul<&'a Matrix<Dual, R, C, S>> for Dual
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = OMatrix<Dual, R, C>;
    #[inline(always)]
    fn mul(self, matrix: &'a Matrix<Dual, R, C, S>) -> Self::Output {
        matrix * self
    }
}

impl Zero for Dual {
    #[inline(always)]
    fn zero() -> Self {
        Dual::constant(0.0)
    }
    #[inline(always)]
    fn is_zero(&self) -> bool {
        self.0.re == 0.0 && self.0.eps == 0.0
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
        Dual(Signed::abs(&self.0))
    }
    fn abs_sub(&self, other: &Self) -> Self {
        Dual(Signed::abs_sub(&self.0, &other.0))
    }
    fn signum(&self) -> Self {
        Dual(Signed::signum(&self.0))
    }
    fn is_positive(&self) -> bool {
        self.0.re.is_sign_positive()
    }
    fn is_negative(&self) -> bool {
        self.0.re.is_sign_negative()
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
        self.0.re.abs_diff_eq(&other.0.re, epsilon.0.re)
    }
}

impl approx::RelativeEq for Dual {
    fn default_max_relative() -> Self {
        Dual::constant(f64::default_max_relative())
    }
    fn relative_eq(&self, other: &Self, epsilon: Self, max_relative: Self) -> bool {
        self.0
            .re
            .relative_eq(&other.0.re, epsilon.0.re, max_relative.0.re)
    }
}

impl approx::UlpsEq for Dual {
    fn default_max_ulps() -> u32 {
        f64::default_max_ulps()
    }
    fn ulps_eq(&self, other: &Self, epsilon: Self, max_ulps: u32) -> bool {
        self.0.re.ulps_eq(&other.0.re, epsilon.0.re, max_ulps)
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
        self.0.eps == 0.0
    }
    fn to_subset_unchecked(&self) -> f64 {
        self.0.re
    }
    fn from_subset(element: &f64) -> Self {
        Dual::constant(*element)
    }
}

impl SupersetOf<f32> for Dual {
    fn is_in_subset(&self) -> bool {
        self.0.eps == 0.0
    }
    fn to_subset_unchecked(&self) -> f32 {
        self.0.re as f32
    }
    fn from_subset(element: &f32) -> Self {
        Dual::constant(f64::from(*element))
    }
}

/// Functions of one dual number, delegated to `num-dual`'s rules.
macro_rules! unary {
    ($trait:ident: $($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self) -> Self {
            Dual($trait::$name(self.0))
        }
    )*};
}

/// Functions of two dual numbers, delegated to `num-dual`'s rules.
macro_rules! binary {
    ($trait:ident: $($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self, other: Self) -> Self {
            Dual($trait::$name(self.0, other.0))
        }
    )*};
}

/// Constants (derivative zero).
macro_rules! constants {
    ($($name:ident),*) => {$(
        #[inline(always)]
        fn $name() -> Self {
            Dual(<Dual64 as RealField>::$name())
        }
    )*};
}

impl ComplexField for Dual {
    type RealField = Dual;

    unary!(ComplexField: real, imaginary, modulus, modulus_squared, argument, norm1, floor, ceil,
        round, trunc, fract, abs, recip, conjugate, sin, cos, tan, asin, acos, atan, sinh, cosh,
        tanh, asinh, acosh, atanh, log2, log10, ln, ln_1p, sqrt, exp, exp2, exp_m1, cbrt, signum);
    binary!(ComplexField: hypot, log, powf, powc, scale, unscale);

    #[inline(always)]
    fn from_real(re: Self) -> Self {
        re
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        Dual(self.0.mul_add(a.0, b.0))
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = ComplexField::sin_cos(self.0);
        (Dual(s), Dual(c))
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        Dual(ComplexField::powi(self.0, n))
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.0.re.is_finite() && self.0.eps.is_finite()
    }
    #[inline(always)]
    fn try_sqrt(self) -> Option<Self> {
        ComplexField::try_sqrt(self.0).map(Dual)
    }
}

impl RealField for Dual {
    binary!(RealField: copysign, atan2);
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
        self.0.re.is_sign_positive()
    }
    #[inline(always)]
    fn is_sign_negative(&self) -> bool {
        self.0.re.is_sign_negative()
    }
    /// The larger of the two, with its derivative (the first's at a tie, as `f64::max` returns
    /// either: the one-sided derivative, like the generated Jacobian's `max`).
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        if other.0.re > self.0.re { other } else { self }
    }
    /// The smaller of the two, with its derivative (the first's at a tie).
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        if other.0.re < self.0.re { other } else { self }
    }
    #[inline(always)]
    fn clamp(self, min: Self, max: Self) -> Self {
        RealField::min(RealField::max(self, min), max)
    }
    fn min_value() -> Option<Self> {
        Some(Dual::constant(f64::MIN))
    }
    fn max_value() -> Option<Self> {
        Some(Dual::constant(f64::MAX))
    }
}

/// What the dual copy of a model's function returns: its derivatives are a column of ∂f/∂y.
/// `#[system]` implements it for a first-order model's dual state.
pub trait Tangent {
    /// Passes each component's derivative to `out`, in layout order.
    fn tangent(&self, out: &mut impl FnMut(f64));
}

/// What the dual copy of a model's function takes: a state field's type over [`Dual`].
pub trait Seeded: Tangent + Sized {
    /// Its number of components.
    const LEN: usize;
    /// The value of components `values[..LEN]`, component `seed` with derivative one (none when
    /// `seed ≥ LEN`).
    fn seeded(values: &[f64], seed: usize) -> Self;
}

impl Tangent for Dual {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        out(self.0.eps);
    }
}

impl Seeded for Dual {
    const LEN: usize = 1;
    #[inline(always)]
    fn seeded(values: &[f64], seed: usize) -> Self {
        Dual::new(values[0], if seed == 0 { 1.0 } else { 0.0 })
    }
}

impl<T: Tangent, const N: usize> Tangent for [T; N] {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        self.iter().for_each(|x| x.tangent(out));
    }
}

impl<T: Seeded, const N: usize> Seeded for [T; N] {
    const LEN: usize = N * T::LEN;
    #[inline(always)]
    fn seeded(values: &[f64], seed: usize) -> Self {
        std::array::from_fn(|i| T::seeded(&values[i * T::LEN..], seed.wrapping_sub(i * T::LEN)))
    }
}

impl<const N: usize> Tangent for nalgebra::SVector<Dual, N> {
    #[inline(always)]
    fn tangent(&self, out: &mut impl FnMut(f64)) {
        self.iter().for_each(|x| x.tangent(out));
    }
}

impl<const N: usize> Seeded for nalgebra::SVector<Dual, N> {
    const LEN: usize = N;
    #[inline(always)]
    fn seeded(values: &[f64], seed: usize) -> Self {
        Self::from_fn(|i, _| Dual::seeded(&values[i..], seed.wrapping_sub(i)))
    }
}

/// The output of a second-order model with several velocity fields: a tuple.
macro_rules! tuples {
    ($(($($t:ident $i:tt),*)),*) => {$(
        impl<$($t: Tangent),*> Tangent for ($($t,)*) {
            #[inline(always)]
            fn tangent(&self, out: &mut impl FnMut(f64)) {
                $(self.$i.tangent(out);)*
            }
        }
    )*};
}

tuples!(
    (A 0, B 1),
    (A 0, B 1, C 2),
    (A 0, B 1, C 2, D 3),
    (A 0, B 1, C 2, D 3, E 4),
    (A 0, B 1, C 2, D 3, E 4, F 5)
);

/// `e as f64` in the dual copy of a model's function: a dual number keeps its derivative, any
/// other number is a constant.
pub trait ToDual {
    /// The number as a [`Dual`].
    fn to_dual(self) -> Dual;
}

impl ToDual for Dual {
    #[inline(always)]
    fn to_dual(self) -> Dual {
        self
    }
}

/// `e as T` for a primitive `T` in the dual copy of a model's function: a dual number's value
/// cast as `as` casts it (an index computed from the state, say).
pub trait DualCast<T> {
    /// `self as T`.
    fn cast(self) -> T;
}

impl<T: 'static + Copy> DualCast<T> for Dual
where
    f64: num_traits::AsPrimitive<T>,
{
    #[inline(always)]
    fn cast(self) -> T {
        num_traits::AsPrimitive::as_(self.0.re)
    }
}

macro_rules! primitives {
    ($($p:ty),*) => {$(
        impl ToDual for $p {
            #[inline(always)]
            #[allow(clippy::cast_lossless, clippy::cast_precision_loss, reason = "`as f64` as written")]
            fn to_dual(self) -> Dual {
                Dual::constant(self as f64)
            }
        }
        impl<T: 'static + Copy> DualCast<T> for $p
        where
            $p: num_traits::AsPrimitive<T>,
        {
            #[inline(always)]
            fn cast(self) -> T {
                num_traits::AsPrimitive::as_(self)
            }
        }
    )*};
}

primitives!(
    f64, f32, i8, i16, i32, i64, i128, isize, u8, u16, u32, u64, u128, usize
);

/// The model's code calls its transcendental functions through [`Transcendental`] (see
/// `crate::math`); its dual copy does too, with these derivative rules.
macro_rules! transcendental {
    ($($receiver:ty => $value:expr),*) => {$(
        impl Transcendental for $receiver {
            type Output = Dual;
            transcendental!(@unary $value; sin, cos, tan, asin, acos, atan, sinh, cosh, tanh,
                asinh, acosh, atanh, exp, exp2, exp_m1, ln, ln_1p, log2, log10, cbrt);
            #[inline(always)]
            fn powf(self, e: Dual) -> Dual {
                ComplexField::powf($value(self), e)
            }
            #[inline(always)]
            fn atan2(self, x: Dual) -> Dual {
                RealField::atan2($value(self), x)
            }
            #[inline(always)]
            fn hypot(self, y: Dual) -> Dual {
                ComplexField::hypot($value(self), y)
            }
            #[inline(always)]
            fn log(self, base: Dual) -> Dual {
                ComplexField::log($value(self), base)
            }
        }
    )*};
    (@unary $value:expr; $($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self) -> Dual {
            ComplexField::$name($value(self))
        }
    )*};
}

transcendental!(Dual => std::convert::identity, &Dual => |x: &Dual| *x);
