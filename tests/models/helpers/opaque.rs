//! Calls odyn cannot see inside (free functions, a lookup table, methods of numbers it does not
//! differentiate itself): differentiated by central differences of the call.

use odyn::prelude::*;

use super::nested::Duffing;
use crate::common::check;

/// A force odyn cannot see inside: a crate-style free function (not `#[odyn::function]`), and a
/// measured force curve looked up in a table and interpolated. The macro evaluates both calls as
/// written and differentiates each by a central difference of the call
/// (`Jacobian::EXACT = false`); the chain rule around them stays exact.
fn stiffening(x: f64, k: f64) -> f64 {
    -k * x * (1.0 + x * x)
}

/// −x³ − x tabulated at 0.05 over [−3, 3] (121 points) and linearly interpolated: a lookup
/// table of the kind a measured spring curve comes in.
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

#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct Opaque {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
}

#[system]
impl Opaque {
    fn acceleration(&self) -> f64 {
        stiffening(self.x, self.k) + 0.5 * tabulated(self.x * self.v) - self.c * self.v
    }
}

#[test]
fn calls_odyn_cannot_see_inside_are_differentiated_by_differences_of_the_call() {
    use odyn::Jacobian;
    const { assert!(!<Opaque as Jacobian>::EXACT) };
    const { assert!(<Duffing as Jacobian>::EXACT) };
    let model = Opaque {
        x: 0.3,
        v: -0.2,
        k: 4.0,
        c: 50.0,
    };
    // Off the table's nodes, where a difference quotient straddles two segments (x·v within
    // 1e-3 of a multiple of 0.05), and inside it (|x·v| < 2.25).
    check(&model, 0.0, 50, |rng| {
        loop {
            let (x, v) = (rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
            let s = (x * v + 3.0) / 0.05;
            if (s - s.round()).abs() > 0.02 {
                break OpaqueState { x, v };
            }
        }
    });
}

/// Rodas5P on the model with opaque calls (c = 50: stiff against k = 4) against DOP853 on the
/// same model at rtol 1e-12 (an explicit method never uses the Jacobian): they agree to the
/// Rosenbrock run's tolerance, 1e-6, at t = 5.
#[test]
fn rodas5p_runs_on_a_model_with_opaque_calls() {
    let model = Opaque {
        x: 1.0,
        v: 0.0,
        k: 4.0,
        c: 50.0,
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
    let (rodas, reference) = (run(Method::Rodas5P, 1e-8), run(Method::Dop853, 1e-12));
    assert!(
        (rodas.x - reference.x).abs() < 1e-6 * reference.x.abs().max(1e-3),
        "{rodas:?} against {reference:?}"
    );
    assert!((rodas.v - reference.v).abs() < 1e-6 * reference.v.abs().max(1e-3));
}

/// A method of a number odyn does not differentiate itself (`to_radians`, `fract`) is called as
/// written and differentiated by a central difference of the call: 1 for `fract` away from the
/// integers, π/180 for `to_radians`.
#[system]
#[derive(Clone, Copy, Debug)]
struct Sawtooth {
    #[state]
    x: f64,
    #[state]
    y: f64,
}

#[system]
impl Sawtooth {
    fn derivative(&self) -> SawtoothState {
        SawtoothState {
            x: -self.x.fract() * self.y,
            y: self.x.to_radians().sin() + self.y.mul_add(2.0, 1.0),
        }
    }
}

#[test]
fn unknown_methods_of_numbers_are_differentiated_by_differences_of_the_call() {
    use odyn::Jacobian;
    const { assert!(!<Sawtooth as Jacobian>::EXACT) };
    // Off the integers, where `fract` jumps.
    check(&Sawtooth { x: 0.5, y: 1.0 }, 0.0, 50, |rng| {
        loop {
            let (x, y) = (rng.uniform(-3.0, 3.0), rng.uniform(-2.0, 2.0));
            if (x - x.round()).abs() > 0.01 {
                break SawtoothState { x, y };
            }
        }
    });
}
