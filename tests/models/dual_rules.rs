//! Every function `jacobian = dual` accepts, against the generated Jacobian of the same code, at
//! ordinary, negative, zero, huge and tiny arguments (the fourth hardening probe found dual
//! numbers that panicked on `floor` and returned NaN for `powf`, `hypot`, `max` and a quotient
//! where the generated Jacobian is exact).
//!
//! One model, written twice by a `macro_rules!` (under the default Jacobian and under `jacobian =
//! dual`): two inputs `a`, `b` and one output per function of them. Wherever the generated
//! entry is finite the dual one must equal it: to rounding (4 ulps of the larger, or 1e-300)
//! where the generated rule is exact, and to 1e-6 relative where it is a central difference of
//! a call the macro cannot see into (`asinh`, `floor`, ...: `Node::Extern`), except at a step
//! function's jump, where a difference is no derivative.

use odyn::prelude::*;
use odyn::{DenseMatrix, Jacobian};

/// The functions, each with whether the generated Jacobian differentiates it exactly.
const FUNCTIONS: [(&str, bool); 50] = [
    ("sqrt", true),
    ("cbrt", true),
    ("exp", true),
    ("exp2", true),
    ("exp_m1", true),
    ("ln", true),
    ("ln_1p", true),
    ("log2", true),
    ("log10", true),
    ("sin", true),
    ("cos", true),
    ("tan", true),
    ("asin", true),
    ("acos", true),
    ("atan", true),
    ("sinh", true),
    ("cosh", true),
    ("tanh", true),
    ("asinh", false),
    ("acosh", false),
    ("atanh", false),
    ("abs", true),
    ("signum", true),
    ("recip", true),
    ("powi(3)", true),
    ("powi(-2)", true),
    ("powf(3)", true),
    ("powf(2)", true),
    ("powf(1.5)", true),
    ("powf(-0.5)", true),
    ("floor", false),
    ("ceil", false),
    ("round", false),
    ("trunc", false),
    ("fract", false),
    ("to_degrees", false),
    ("sin_cos", true),
    ("sqrt(a²-4).max(0)", true),
    ("logistic", true),
    ("atan2", true),
    ("hypot", true),
    ("max", true),
    ("min", true),
    ("mul_add", true),
    ("clamp", true),
    ("a*b", true),
    ("a/b", true),
    ("copysign", false),
    ("rem_euclid", false),
    ("log", false),
];

/// Whether the function is a step function (its difference at a jump is no derivative).
fn steps(name: &str) -> bool {
    matches!(
        name,
        "floor" | "ceil" | "round" | "trunc" | "fract" | "copysign" | "rem_euclid" | "signum"
    )
}

macro_rules! functions {
    ($name:ident, $state:ident $(, $arg:meta)?) => {
        #[system$(($arg))?]
        #[derive(Clone, Copy, Debug)]
        struct $name {
            #[state]
            a: f64,
            #[state]
            b: f64,
            #[state]
            out: [f64; 50],
        }

        #[system]
        impl $name {
            fn derivative(&self) -> $state {
                let (a, b) = (self.a, self.b);
                $state {
                    a: 0.0,
                    b: 0.0,
                    out: [
                        a.sqrt(), a.cbrt(), a.exp(), a.exp2(), a.exp_m1(),
                        a.ln(), a.ln_1p(), a.log2(), a.log10(), a.sin(),
                        a.cos(), a.tan(), a.asin(), a.acos(), a.atan(),
                        a.sinh(), a.cosh(), a.tanh(), a.asinh(), a.acosh(),
                        a.atanh(), a.abs(), a.signum(), a.recip(), a.powi(3),
                        a.powi(-2), a.powf(3.0), a.powf(2.0), a.powf(1.5),
                        a.powf(-0.5), a.floor(), a.ceil(), a.round(), a.trunc(),
                        a.fract(), a.to_degrees(), a.sin_cos().0, (a * a - 4.0).sqrt().max(0.0),
                        a.exp() / (1.0 + a.exp()), a.atan2(b), a.hypot(b), a.max(b), a.min(b),
                        a.mul_add(b, 2.0), a.clamp(-1.0, 1.0), a * b, a / b, a.copysign(b),
                        a.rem_euclid(b), a.log(b),
                    ],
                }
            }
        }
    };
}

functions!(Generated, GeneratedState);
functions!(Duals, DualsState, jacobian = dual);

/// The generated and dual ∂(out)/∂(a, b) at (a, b): 2 columns of 50 rows each.
fn columns(a: f64, b: f64) -> [[(f64, f64); 50]; 2] {
    let generated = Generated {
        a,
        b,
        out: [0.0; 50],
    };
    let dual = Duals {
        a,
        b,
        out: [0.0; 50],
    };
    let (y, z) = (generated.state(), dual.state());
    let (mut g, mut d) = (generated.jacobian_matrix(&y), dual.jacobian_matrix(&z));
    generated.jacobian(0.0, &y, &mut g);
    dual.jacobian(0.0, &z, &mut d);
    std::array::from_fn(|column| {
        std::array::from_fn(|row| (g.entry(row + 2, column), d.entry(row + 2, column)))
    })
}

#[test]
fn dual_numbers_follow_the_generated_rules_at_the_extremes() {
    let points = [
        (0.7, -1.3),
        (-0.6, 0.4),
        (2.5, 3.5),
        (-2.5, -0.4),
        (0.0, 0.0),
        (-0.0, 1.0),
        (0.0, -1.0),
        (1e200, 1e200),
        (1e300, -1e300),
        (-1e150, 2e150),
        (1e-200, 1e-200),
        (-1e-300, 1e-300),
        (709.0, 1.0),
        (1.0, 1.0),
        (-709.0, 3.0),
        (4.0, 0.5),
    ];
    let mut compared = 0;
    for (a, b) in points {
        for (column, entries) in columns(a, b).iter().enumerate() {
            for (row, &(generated, dual)) in entries.iter().enumerate() {
                let (name, exact) = FUNCTIONS[row];
                // Where f itself is undefined (NaN: rem_euclid by 0), a difference around it is no
                // derivative either.
                if !generated.is_finite() || !output(row, a, b).is_finite() {
                    continue;
                }
                let at = if column == 0 { a } else { b };
                let h = f64::EPSILON.cbrt() * at.abs().max(1.0);
                if !exact {
                    // A difference across a jump or a kink (and across every float at 1e200,
                    // where `floor` is the identity) is not the derivative: compare where the
                    // one-sided differences agree.
                    let value = |s: f64| {
                        let (a, b) = if column == 0 { (a + s, b) } else { (a, b + s) };
                        output(row, a, b)
                    };
                    let (left, right) = ((value(0.0) - value(-h)) / h, (value(h) - value(0.0)) / h);
                    if (left - right).abs() > 1e-3 * left.abs().max(right.abs()).max(1e-300)
                        || (steps(name) && at.abs() >= 2f64.powi(52))
                    {
                        continue;
                    }
                }
                let bound = if exact {
                    4.0 * f64::EPSILON * generated.abs().max(dual.abs()) + 1e-300
                } else {
                    1e-6 * generated.abs().max(1e-300) + 1e-9 * at.abs().max(1.0).recip()
                };
                assert!(
                    (generated - dual).abs() <= bound,
                    "∂{name}/∂{} at (a, b) = ({a:e}, {b:e}): generated {generated:e}, dual \
                     {dual:e}",
                    ["a", "b"][column]
                );
                compared += 1;
            }
        }
    }
    // Every function is compared at most points (a count, so a refactor that skips them all
    // fails here).
    assert!(compared > 900, "{compared} entries compared");
}

/// Output `row` of the model at (a, b), as its code computes it.
fn output(row: usize, a: f64, b: f64) -> f64 {
    let model = Generated {
        a,
        b,
        out: [0.0; 50],
    };
    let y = model.state();
    let mut dy = y;
    Model::derivative(&model, 0.0, &y, &mut dy);
    dy.out[row]
}

/// −x³ − x tabulated at 0.05 and interpolated with `s - s.floor()` in a helper (the use case
/// the documentation gives for `jacobian = dual`), with `ceil`, `round` and `trunc` about too.
#[system(integrator = Rodas5P, jacobian = dual)]
#[derive(Clone, Copy, Debug)]
struct Floored {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    c: f64,
}

#[system]
impl Floored {
    fn acceleration(&self) -> f64 {
        Self::tabulated(self.x) - self.c * self.v
            + 0.0 * (self.x.ceil() + self.x.round() + self.x.trunc())
    }

    #[odyn::function]
    fn tabulated(x: f64) -> f64 {
        let s = (x + 3.0) / 0.05;
        let i = s.floor();
        let f = s - i;
        let at = |i: f64| {
            let x = -3.0 + i * 0.05;
            -x * x * x - x
        };
        at(i) * (1.0 - f) + at(i + 1.0) * f
    }
}

/// The rounding functions were a panic inside num-dual ("called floor() on a dual number"), in
/// `Model::jacobian` and in a Rodas5P run: now derivative 0 (1 for `fract`), so a table lookup
/// runs, Rodas5P (c = 40: stiff) within its tolerance of DOP853 at rtol 1e-12.
#[test]
fn rounding_functions_do_not_panic_under_dual() {
    let model = Floored {
        x: 1.5,
        v: 0.0,
        c: 40.0,
    };
    let run = |method: Method, rtol: f64| {
        model
            .simulate()
            .integrator(method)
            .tolerances(rtol, rtol * 1e-2)
            .duration(5.0)
            .run()
    };
    let reference = run(Method::Dop853, 1e-12).unwrap().last().state;
    let y = run(Method::Rodas5P, 1e-8).unwrap().last().state;
    assert!(
        (y.x - reference.x).abs() < 1e-6,
        "{y:?} against {reference:?}"
    );
}

/// Predicates and orderings on the state, which the generated Jacobian refuses (the refusal
/// advises `jacobian = dual`), compile and differentiate under `dual`: `is_nan` and `total_cmp`
/// read the value, so the branch taken is the one `f64` takes.
#[system(jacobian = dual)]
#[derive(Clone, Copy, Debug)]
struct Guarded {
    #[state]
    x: f64,
}

#[system]
impl Guarded {
    fn derivative(&self) -> GuardedState {
        let finite = !self.x.is_nan() && self.x.total_cmp(&0.0) == std::cmp::Ordering::Greater;
        GuardedState {
            x: if finite { -self.x * self.x } else { 0.0 },
        }
    }
}

/// d(−x²)/dx = −2x on the positive branch, 0 on the other.
#[test]
fn predicates_on_the_state_differentiate_under_dual() {
    for (x, expected) in [(3.0, -6.0), (-1.0, 0.0)] {
        let model = Guarded { x };
        let y = model.state();
        let mut j = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut j);
        assert_eq!(j[(0, 0)], expected, "at x = {x}");
    }
}
