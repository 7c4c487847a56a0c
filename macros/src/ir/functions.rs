//! The functions a [`Node`](super::Node) may call: the method each is written as and its value
//! at a point.

/// A one-argument function.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Func {
    Sqrt,
    Cbrt,
    Exp,
    Exp2,
    ExpM1,
    Ln,
    Ln1p,
    Log2,
    Log10,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Abs,
    Signum,
}

impl Func {
    /// The `f64` method that evaluates it.
    pub(crate) fn method(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Cbrt => "cbrt",
            Func::Exp => "exp",
            Func::Exp2 => "exp2",
            Func::ExpM1 => "exp_m1",
            Func::Ln => "ln",
            Func::Ln1p => "ln_1p",
            Func::Log2 => "log2",
            Func::Log10 => "log10",
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Abs => "abs",
            Func::Signum => "signum",
        }
    }

    /// Every function, for the method table.
    pub(crate) const ALL: [Func; 20] = [
        Func::Sqrt,
        Func::Cbrt,
        Func::Exp,
        Func::Exp2,
        Func::ExpM1,
        Func::Ln,
        Func::Ln1p,
        Func::Log2,
        Func::Log10,
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Abs,
        Func::Signum,
    ];

    /// Its value at `x`, with `libm`'s implementation: a constant the macro folds is the same on
    /// every host, as the `deterministic` feature's runtime values are on every target.
    pub(crate) fn eval(self, x: f64) -> f64 {
        match self {
            Func::Sqrt => x.sqrt(),
            Func::Cbrt => libm::cbrt(x),
            Func::Exp => libm::exp(x),
            Func::Exp2 => libm::exp2(x),
            Func::ExpM1 => libm::expm1(x),
            Func::Ln => libm::log(x),
            Func::Ln1p => libm::log1p(x),
            Func::Log2 => libm::log2(x),
            Func::Log10 => libm::log10(x),
            Func::Sin => libm::sin(x),
            Func::Cos => libm::cos(x),
            Func::Tan => libm::tan(x),
            Func::Asin => libm::asin(x),
            Func::Acos => libm::acos(x),
            Func::Atan => libm::atan(x),
            Func::Sinh => libm::sinh(x),
            Func::Cosh => libm::cosh(x),
            Func::Tanh => libm::tanh(x),
            Func::Abs => x.abs(),
            Func::Signum => x.signum(),
        }
    }
}

/// A two-argument function.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Func2 {
    /// `y.atan2(x)`, the angle of (x, y).
    Atan2,
    /// `libm::hypot(a, b)` = √(a² + b²) without overflow.
    Hypot,
}

impl Func2 {
    pub(crate) fn method(self) -> &'static str {
        match self {
            Func2::Atan2 => "atan2",
            Func2::Hypot => "hypot",
        }
    }

    pub(crate) fn eval(self, a: f64, b: f64) -> f64 {
        match self {
            Func2::Atan2 => libm::atan2(a, b),
            Func2::Hypot => libm::hypot(a, b),
        }
    }
}
