//! The transcendental functions odyn and the code `#[system]` generates call, in one place.
//!
//! By default each is the float type's own method: the platform's implementation (glibc's on
//! x86-64 Linux, a port of musl's on WebAssembly), which may differ in the last bit between
//! platforms. With the **`deterministic`** feature each is the [`libm`](https://docs.rs/libm)
//! crate's pure-Rust implementation (a port of musl's), the same code on every target, so a run
//! compiled for x86-64 and the same run compiled to WebAssembly give bit-identical trajectories.
//! `sqrt`, `abs` and the arithmetic operators need nothing: IEEE 754 defines them exactly, and
//! Rust never fuses or reassociates floating-point operations.
//!
//! `#[system]` routes every such call in a model's code here, `x.sin()` becoming
//! `Transcendental::sin(x)`; call these yourself in code outside the model (an event function, a
//! forcing) that a run's result depends on.

/// The transcendental functions of a float type, with the platform's or, under `deterministic`,
/// `libm`'s implementation; implemented for `f64` and `f32` and references to them (a method call
/// `x.sin()` auto-dereferences, so its routed form must too).
pub trait Transcendental: Copy {
    /// The float type.
    type Output;
    /// Sine.
    fn sin(self) -> Self::Output;
    /// Cosine.
    fn cos(self) -> Self::Output;
    /// Tangent.
    fn tan(self) -> Self::Output;
    /// Arcsine.
    fn asin(self) -> Self::Output;
    /// Arccosine.
    fn acos(self) -> Self::Output;
    /// Arctangent.
    fn atan(self) -> Self::Output;
    /// Hyperbolic sine.
    fn sinh(self) -> Self::Output;
    /// Hyperbolic cosine.
    fn cosh(self) -> Self::Output;
    /// Hyperbolic tangent.
    fn tanh(self) -> Self::Output;
    /// Inverse hyperbolic sine.
    fn asinh(self) -> Self::Output;
    /// Inverse hyperbolic cosine.
    fn acosh(self) -> Self::Output;
    /// Inverse hyperbolic tangent.
    fn atanh(self) -> Self::Output;
    /// eˣ.
    fn exp(self) -> Self::Output;
    /// 2ˣ.
    fn exp2(self) -> Self::Output;
    /// eˣ − 1.
    fn exp_m1(self) -> Self::Output;
    /// Natural logarithm.
    fn ln(self) -> Self::Output;
    /// ln(1 + x).
    fn ln_1p(self) -> Self::Output;
    /// Base-2 logarithm.
    fn log2(self) -> Self::Output;
    /// Base-10 logarithm.
    fn log10(self) -> Self::Output;
    /// Cube root.
    fn cbrt(self) -> Self::Output;
    /// selfᵉ for a float exponent.
    fn powf(self, e: Self::Output) -> Self::Output;
    /// The angle of (self, x) = atan(self/x) in the right quadrant (`self` is y).
    fn atan2(self, x: Self::Output) -> Self::Output;
    /// √(self² + y²) without overflow.
    fn hypot(self, y: Self::Output) -> Self::Output;
    /// Logarithm in base `base`.
    fn log(self, base: Self::Output) -> Self::Output;
}

/// Implements [`Transcendental`] for `$t` with the platform's methods, or `libm`'s functions
/// (`$sin`, …) under `deterministic`.
macro_rules! transcendental {
    ($t:ty: $($method:ident => $libm:ident),* ; $($method2:ident => $libm2:ident),*) => {
        impl Transcendental for $t {
            type Output = $t;
            $(
                #[inline(always)]
                fn $method(self) -> Self {
                    #[cfg(feature = "deterministic")]
                    {
                        libm::$libm(self)
                    }
                    #[cfg(not(feature = "deterministic"))]
                    {
                        <$t>::$method(self)
                    }
                }
            )*
            $(
                #[inline(always)]
                fn $method2(self, other: Self) -> Self {
                    #[cfg(feature = "deterministic")]
                    {
                        libm::$libm2(self, other)
                    }
                    #[cfg(not(feature = "deterministic"))]
                    {
                        <$t>::$method2(self, other)
                    }
                }
            )*
            #[inline(always)]
            fn log(self, base: Self) -> Self {
                Transcendental::ln(self) / Transcendental::ln(base)
            }
        }

        impl Transcendental for &$t {
            type Output = $t;
            $(
                #[inline(always)]
                fn $method(self) -> $t {
                    Transcendental::$method(*self)
                }
            )*
            $(
                #[inline(always)]
                fn $method2(self, other: $t) -> $t {
                    Transcendental::$method2(*self, other)
                }
            )*
            #[inline(always)]
            fn log(self, base: $t) -> $t {
                Transcendental::log(*self, base)
            }
        }
    };
}

transcendental!(f64:
    sin => sin, cos => cos, tan => tan, asin => asin, acos => acos, atan => atan,
    sinh => sinh, cosh => cosh, tanh => tanh, asinh => asinh, acosh => acosh, atanh => atanh,
    exp => exp, exp2 => exp2, exp_m1 => expm1, ln => log, ln_1p => log1p, log2 => log2,
    log10 => log10, cbrt => cbrt;
    powf => pow, atan2 => atan2, hypot => hypot);

transcendental!(f32:
    sin => sinf, cos => cosf, tan => tanf, asin => asinf, acos => acosf, atan => atanf,
    sinh => sinhf, cosh => coshf, tanh => tanhf, asinh => asinhf, acosh => acoshf,
    atanh => atanhf, exp => expf, exp2 => exp2f, exp_m1 => expm1f, ln => logf,
    ln_1p => log1pf, log2 => log2f, log10 => log10f, cbrt => cbrtf;
    powf => powf, atan2 => atan2f, hypot => hypotf);

#[cfg(test)]
mod tests {
    use super::Transcendental;

    /// Each function against its defining identity or an exact value, so a wrong mapping (sin
    /// to cos, ln to log10) fails: the values are exact or within a few ulps by the functions'
    /// documented accuracy (musl's and glibc's are < 1 ulp for these).
    #[test]
    fn every_function_is_the_one_named() {
        let x = 0.7_f64;
        let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON * b.abs().max(1.0);
        assert!(close(
            Transcendental::sin(x).powi(2) + Transcendental::cos(x).powi(2),
            1.0
        ));
        assert!(close(Transcendental::tan(x), x.sin() / x.cos()));
        assert!(close(Transcendental::asin(Transcendental::sin(x)), x));
        assert!(close(Transcendental::acos(Transcendental::cos(x)), x));
        assert!(close(Transcendental::atan(Transcendental::tan(x)), x));
        assert!(close(Transcendental::sinh(x), (x.exp() - (-x).exp()) / 2.0));
        assert!(close(Transcendental::cosh(x), (x.exp() + (-x).exp()) / 2.0));
        assert!(close(Transcendental::tanh(x), x.sinh() / x.cosh()));
        assert!(close(Transcendental::asinh(Transcendental::sinh(x)), x));
        assert!(close(Transcendental::acosh(Transcendental::cosh(x)), x));
        assert!(close(Transcendental::atanh(Transcendental::tanh(x)), x));
        assert_eq!(Transcendental::exp(0.0_f64), 1.0);
        assert_eq!(Transcendental::exp2(10.0_f64), 1024.0);
        assert!(close(Transcendental::exp_m1(1e-10_f64), 1e-10 + 5e-21));
        assert!(close(Transcendental::ln(Transcendental::exp(x)), x));
        assert!(close(Transcendental::ln_1p(1e-10_f64), 1e-10 - 5e-21));
        assert_eq!(Transcendental::log2(1024.0_f64), 10.0);
        assert_eq!(Transcendental::log10(1000.0_f64), 3.0);
        assert_eq!(Transcendental::cbrt(27.0_f64), 3.0);
        assert_eq!(Transcendental::powf(2.0_f64, 10.0), 1024.0);
        assert!(close(
            Transcendental::atan2(1.0_f64, -1.0),
            0.75 * std::f64::consts::PI
        ));
        assert_eq!(Transcendental::hypot(3.0_f64, 4.0), 5.0);
        assert!(close(Transcendental::log(8.0_f64, 2.0), 3.0));
        assert_eq!(Transcendental::sin(&x), Transcendental::sin(x));
        assert_eq!(Transcendental::powf(&x, 0.3), Transcendental::powf(x, 0.3));
        assert!((Transcendental::sin(0.5_f32) - 0.5_f32.sin()).abs() <= 2.0 * f32::EPSILON);
        assert!((Transcendental::powf(2.0_f32, 0.5) - 2.0_f32.sqrt()).abs() <= 2.0 * f32::EPSILON);
    }
}
