//! `#[system(jacobian = dual)]`: the Jacobian by forward-mode automatic differentiation of the
//! model's own code over dual numbers. Both it and the generated Jacobian are exact, so they agree
//! to rounding on the same code; a table lookup (a `floor`, an `as usize`) gets its segment's
//! slope exactly; and the stiff methods run on it.

use crate::common::{Rng, check};
use crate::shapes::Chain;

use odyn::prelude::*;
use odyn::{DenseMatrix, Jacobian, Method};

/// [`Chain`] for any number of masses — code the lowering does not read (its loops run to `N`) —
/// its Jacobian by dual numbers.
#[system(jacobian = dual)]
#[derive(Clone, Copy)]
struct DualLinks<const N: usize> {
    #[position]
    q: [Vector2<f64>; N],
    #[velocity]
    p: [Vector2<f64>; N],
    #[param]
    k: f64,
}

#[system]
impl<const N: usize> DualLinks<N> {
    fn acceleration(&self) -> [Vector2<f64>; N] {
        let mut a = [Vector2::new(0.0, -9.81); N];
        let mut previous = Vector2::<f64>::zeros();
        for i in 0..N {
            let d = self.q[i] - previous;
            let length = d.norm();
            let f = d * (self.k * (length - 1.0) / length);
            a[i] -= f;
            if i > 0 {
                a[i - 1] += f;
            }
            previous = self.q[i];
        }
        a
    }
}

/// The largest |a − b| over the entries of two n×n Jacobians, relative to b's largest entry.
fn relative_difference(a: &impl DenseMatrix, b: &impl DenseMatrix, n: usize) -> f64 {
    let (mut difference, mut scale) = (0.0f64, 0.0f64);
    for row in 0..n {
        for column in 0..n {
            let (x, y) = (a.entry(row, column), b.entry(row, column));
            difference = difference.max((x - y).abs());
            scale = scale.max(y.abs());
        }
    }
    difference / scale
}

/// Two exact Jacobians of the same code, evaluated in different orders: they agree to a few
/// ulps of the largest entry (measured ≤ 3.2e-16 over these 20 states; the bound leaves room
/// for other compilers and platforms).
#[test]
fn the_dual_jacobian_of_a_const_generic_chain_is_the_generated_one() {
    const { assert!(<DualLinks<4> as Jacobian>::EXACT) };
    let exact = Chain {
        q: std::array::from_fn(|i| Vector2::new(1.1 * (i + 1) as f64, 0.0)),
        p: [Vector2::zeros(); 4],
        k: 50.0,
    };
    let dual = DualLinks::<4> {
        q: exact.q,
        p: exact.p,
        k: exact.k,
    };
    let mut rng = Rng(7);
    for _ in 0..20 {
        let mut y = exact.state();
        for value in y.as_mut_slice() {
            *value = rng.uniform(-2.0, 2.0);
        }
        let mut z = dual.state();
        z.as_mut_slice().copy_from_slice(y.as_slice());
        let (mut a, mut b) = (dual.jacobian_matrix(&z), exact.jacobian_matrix(&y));
        dual.jacobian(0.0, &z, &mut a);
        exact.jacobian(0.0, &y, &mut b);
        let difference = relative_difference(&a, &b, 16);
        assert!(difference < 1e-14, "{difference:e} at {y:?}");
        // ∂f/∂k of a const-generic model, by dual numbers, against a central difference in k
        // (step 1e-4·k: truncation ~1e-8 relative, rounding ~1e-12).
        let mut dfdk = odyn::nalgebra::DMatrix::zeros(0, 0);
        odyn::Parameters::parameter_jacobian(&dual, 0.0, &z, &mut dfdk);
        let h = 1e-4 * dual.k;
        let (mut plus, mut minus) = (z, z);
        DualLinks {
            k: dual.k + h,
            ..dual
        }
        .derivative(0.0, &z, &mut plus);
        DualLinks {
            k: dual.k - h,
            ..dual
        }
        .derivative(0.0, &z, &mut minus);
        for row in 0..16 {
            let central = (plus.as_slice()[row] - minus.as_slice()[row]) / (2.0 * h);
            assert!(
                (dfdk[(row, 0)] - central).abs() < 1e-6 * (1.0 + central.abs()),
                "row {row}"
            );
        }
    }
}

/// −x³ − x tabulated at 0.05 over [−3, 3] and linearly interpolated, in a helper: the kind of
/// code the lowering refuses (a cast to an index) and dual numbers read.
#[system(integrator = Rodas5P, jacobian = dual)]
#[derive(Clone, Copy, Debug)]
struct Tabled {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    c: f64,
}

#[system]
impl Tabled {
    fn acceleration(&self) -> f64 {
        Self::tabulated(self.x) - self.c * self.v * (1.0 + 0.1 * self.x * self.x)
    }

    #[odyn::function]
    fn tabulated(x: f64) -> f64 {
        const STEP: f64 = 0.05;
        let s = ((x + 3.0) / STEP).clamp(0.0, 119.999_999);
        let i = s as usize;
        let f = s - i as f64;
        let at = |i: usize| {
            let x = -3.0 + i as f64 * STEP;
            -x * x * x - x
        };
        at(i) * (1.0 - f) + at(i + 1) * f
    }
}

/// Off the table's nodes the Jacobian agrees with central differences; inside a segment
/// ∂a/∂x is the segment's slope, (g(xᵢ₊₁) − g(xᵢ))/0.05 − 0.2·c·x·v, to rounding.
#[test]
fn a_table_lookup_gets_its_segments_slope() {
    let model = Tabled {
        x: 1.0,
        v: 0.0,
        c: 40.0,
    };
    check(&model, 0.0, 50, |rng| {
        loop {
            let (x, v) = (rng.uniform(-2.5, 2.5), rng.uniform(-1.0, 1.0));
            let s = (x + 3.0) / 0.05;
            if (s - s.round()).abs() > 0.02 {
                break TabledState { x, v };
            }
        }
    });
    let y = TabledState { x: 0.512, v: 0.3 };
    let mut j = model.jacobian_matrix(&y);
    model.jacobian(0.0, &y, &mut j);
    let g = |x: f64| -x * x * x - x;
    let (left, right) = (-3.0 + 70.0 * 0.05, -3.0 + 71.0 * 0.05);
    let slope = (g(right) - g(left)) / 0.05 - 0.2 * 40.0 * 0.512 * 0.3;
    assert!(
        (j[(1, 0)] - slope).abs() < 1e-12 * slope.abs(),
        "{} vs {slope}",
        j[(1, 0)]
    );
    assert_eq!((j[(0, 0)], j[(0, 1)]), (0.0, 1.0));
}

/// Rodas5P (c = 40: stiff) and BDF on the dual Jacobian against DOP853 at rtol 1e-12 (an explicit
/// method never uses the Jacobian): they agree to their own tolerance, 1e-6, at t = 5.
#[test]
fn stiff_methods_run_on_a_dual_jacobian() {
    let model = Tabled {
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
            .unwrap()
            .last()
            .state
    };
    let reference = run(Method::Dop853, 1e-12);
    for method in [Method::Rodas5P, Method::Bdf] {
        let y = run(method, 1e-8);
        assert!(
            (y.x - reference.x).abs() < 1e-6 * reference.x.abs().max(1e-3),
            "{method:?}: {y:?} against {reference:?}"
        );
    }
}

/// A first-order model reading the time, with helpers (a method and an associated function, one
/// returning a tuple, one a vector), a parameter vector, an array of them, `f64::from` and a
/// flag: ∂f/∂y and ∂f/∂t by dual numbers against central differences, and ∂f/∂t against its
/// closed form.
#[system(jacobian = dual)]
#[derive(Clone, Copy, Debug)]
struct Forced {
    #[state]
    p: f64,
    #[state]
    q: f64,
    #[state]
    r: Vector2<f64>,
    a: f64,
    wind: Vector2<f64>,
    gains: [f64; 2],
    anchors: [Vector2<f64>; 2],
    level: u8,
    soft: bool,
}

#[system]
impl Forced {
    fn derivative(&self, t: f64) -> ForcedState {
        let (radius, angle) = Self::polar(self.p, self.q);
        let gain = if self.soft {
            self.gains[0]
        } else {
            self.gains[1]
        };
        ForcedState {
            p: -gain * self.p + self.a * (2.0 * t).sin() * angle.cos(),
            q: radius.sin() - self.q * f64::max(self.p, 0.0),
            r: self.pull(self.r)
                + self.wind * t
                + (self.anchors[1] - self.r) * (f64::from(self.level) * 0.01),
        }
    }

    #[odyn::function]
    fn polar(x: f64, y: f64) -> (f64, f64) {
        (x.hypot(y), y.atan2(x))
    }

    #[odyn::function]
    fn pull(&self, r: Vector2<f64>) -> Vector2<f64> {
        -self.a * r / r.norm().powi(3)
    }
}

#[test]
fn a_dual_jacobian_reads_the_time_helpers_and_parameters() {
    let model = Forced {
        p: 0.0,
        q: 0.0,
        r: Vector2::zeros(),
        a: 1.7,
        wind: Vector2::new(0.3, -0.1),
        gains: [2.0, 3.0],
        anchors: [Vector2::zeros(), Vector2::new(0.5, 2.0)],
        level: 7,
        soft: true,
    };
    const { assert!(<Forced as Jacobian>::TIME_DEPENDENT) };
    for t in [0.0, 0.4, 2.5] {
        check(&model, t, 50, |r| ForcedState {
            p: r.uniform(-2.0, 3.0),
            q: r.uniform(0.1, 1.0),
            r: Vector2::new(r.uniform(0.5, 2.0), r.uniform(-2.0, -0.5)),
        });
    }
    // ∂ṗ/∂t = 2a·cos(2t)·cos(atan2(q, p)), ∂ṙ/∂t = wind.
    let y = ForcedState {
        p: 0.8,
        q: 0.3,
        r: Vector2::new(1.0, -1.0),
    };
    let t = 0.9;
    let mut dfdt = y;
    model.time_derivative(t, &y, &mut dfdt);
    let exact = 2.0 * 1.7 * (2.0 * t).cos() * 0.3f64.atan2(0.8).cos();
    assert!((dfdt.p - exact).abs() < 1e-14, "{} vs {exact}", dfdt.p);
    assert_eq!((dfdt.q, dfdt.r), (0.0, model.wind));
}

/// A driven, damped oscillator with its parameters marked and a helper reading one of them,
/// `$name` with state `$state`, under `#[system($($args)*)]`: written once, for the generated
/// ∂f/∂p and for dual numbers.
macro_rules! driven {
    ($name:ident, $state:ident, $($args:tt)*) => {
        #[system($($args)*)]
        #[derive(Clone, Copy, Debug)]
        struct $name {
            #[state]
            x: f64,
            #[state]
            v: f64,
            #[param]
            k: f64,
            #[param]
            c: f64,
            #[param]
            a: f64,
        }

        #[system]
        impl $name {
            fn derivative(&self, t: f64) -> $state {
                $state {
                    x: self.v,
                    v: self.spring(self.x) - self.c * self.v * (1.0 + self.x * self.x)
                        + self.a * (1.3 * t).cos(),
                }
            }

            #[odyn::function]
            fn spring(&self, x: f64) -> f64 {
                -self.k * x - 0.1 * self.k * self.k * x * x * x
            }
        }
    };
}

driven!(Driven, DrivenState,);
driven!(DualDriven, DualDrivenState, jacobian = dual);

/// ∂f/∂p by dual numbers (one evaluation per parameter, the helper's reads seeded too) against
/// the generated one: both exact, so equal to a few ulps (measured ≤ 1.9e-16 relative); and a
/// fit of the dual model recovers its parameters from noiseless samples of the generated one.
#[test]
fn parameters_under_dual_numbers_have_the_generated_derivatives_and_fit() {
    use odyn::Parameters;
    use odyn::fit::{Data, FitOptions, fit};
    assert_eq!(<DualDriven as Parameters>::NAMES, &["k", "c", "a"]);
    let exact = Driven {
        x: 1.0,
        v: 0.0,
        k: 4.0,
        c: 0.3,
        a: 0.8,
    };
    let dual = DualDriven {
        x: 1.0,
        v: 0.0,
        k: 4.0,
        c: 0.3,
        a: 0.8,
    };
    let mut rng = Rng(11);
    let (mut a, mut b) = (
        odyn::nalgebra::DMatrix::zeros(0, 0),
        odyn::nalgebra::DMatrix::zeros(0, 0),
    );
    for _ in 0..50 {
        let (x, v, t) = (
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(0.0, 5.0),
        );
        exact.parameter_jacobian(t, &DrivenState { x, v }, &mut b);
        dual.parameter_jacobian(t, &DualDrivenState { x, v }, &mut a);
        let scale = b.amax();
        assert!((&a - &b).amax() <= 1e-15 * scale, "{a} vs {b}");
    }
    // Noiseless samples of x from the generated model at rtol 1e-12; the fit starts 25–50 % off.
    let times: Vec<f64> = (1..=30).map(|k| 0.2 * f64::from(k)).collect();
    let run = exact
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-14)
        .duration(6.0)
        .save_at(&times)
        .run()
        .unwrap();
    let data = Data {
        component: 0,
        values: times
            .iter()
            .map(|&t| run.sample_at(t).unwrap().state.x)
            .collect(),
        times,
        weights: Vec::new(),
    };
    let guess = DualDriven {
        k: 3.0,
        c: 0.45,
        a: 0.5,
        ..dual
    };
    let found = fit(&guess, std::slice::from_ref(&data), &FitOptions::default()).unwrap();
    for (found, truth) in found.parameters.iter().zip([4.0, 0.3, 0.8]) {
        assert!((found - truth).abs() < 1e-6 * truth, "{found:?}");
    }
}
