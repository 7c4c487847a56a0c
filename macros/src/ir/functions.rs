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

    pub(crate) fn eval(self, x: f64) -> f64 {
        match self {
            Func::Sqrt => x.sqrt(),
            Func::Cbrt => x.cbrt(),
            Func::Exp => x.exp(),
            Func::Exp2 => x.exp2(),
            Func::ExpM1 => x.exp_m1(),
            Func::Ln => x.ln(),
            Func::Ln1p => x.ln_1p(),
            Func::Log2 => x.log2(),
            Func::Log10 => x.log10(),
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
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
    /// `a.hypot(b)` = √(a² + b²) without overflow.
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
            Func2::Atan2 => a.atan2(b),
            Func2::Hypot => a.hypot(b),
        }
    }
}
