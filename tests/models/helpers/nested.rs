//! Nested helpers reading parameters: exact Jacobians, and runs against the same model with
//! its helpers inlined by hand.

use odyn::prelude::*;

use crate::common::check;

/// A Duffing oscillator with quadratic drag, m·ẍ = −k·x − c·x³ − b·v·|v|, written with nested
/// helpers: `total` calls `restoring` (a method reading parameters) and `drag` (an associated
/// function given a parameter and the state).
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
pub(super) struct Duffing {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
    b: f64,
    m: f64,
}

#[system]
impl Duffing {
    fn acceleration(&self) -> f64 {
        self.total(self.x, self.v) / self.m
    }

    fn energy(&self) -> f64 {
        0.5 * self.m * self.v * self.v
            + 0.5 * self.k * self.x.powi(2)
            + 0.25 * self.c * self.x.powi(4)
    }

    #[odyn::function]
    fn total(&self, x: f64, v: f64) -> f64 {
        self.restoring(x) + Self::drag(self.b, v)
    }

    #[odyn::function]
    fn restoring(&self, x: f64) -> f64 {
        -self.k * x - self.c * x.powi(3)
    }

    #[odyn::function]
    fn drag(b: f64, v: f64) -> f64 {
        -b * v * v.abs()
    }
}

/// [`Duffing`] with its helpers inlined by hand, operation for operation.
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct DuffingInline {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
    b: f64,
    m: f64,
}

#[system]
impl DuffingInline {
    fn acceleration(&self) -> f64 {
        (-self.k * self.x - self.c * self.x.powi(3) + -self.b * self.v * self.v.abs()) / self.m
    }
}

const DUFFING: Duffing = Duffing {
    x: 1.2,
    v: 0.0,
    k: 1.0,
    c: 5.0,
    b: 0.3,
    m: 0.5,
};

#[test]
fn nested_helpers_reading_parameters_have_exact_jacobians() {
    check(&DUFFING, 0.0, 200, |r| DuffingState {
        x: r.uniform(-3.0, 3.0),
        // Off the kink of |v| at 0.
        v: if r.uniform(0.0, 1.0) < 0.5 {
            r.uniform(-3.0, -0.01)
        } else {
            r.uniform(0.01, 3.0)
        },
    });
    // By hand: ∂a/∂x = (−k − 3c·x²)/m, ∂a/∂v = −2b·|v|/m.
    let y = DuffingState { x: 0.5, v: -2.0 };
    let mut j = DUFFING.jacobian_matrix(&y);
    DUFFING.jacobian(0.0, &y, &mut j);
    assert_eq!(j[(1, 0)], (-1.0 - 3.0 * 5.0 * 0.25) / 0.5);
    assert_eq!(j[(1, 1)], -2.0 * 0.3 * 2.0 / 0.5);
    assert_eq!(Duffing::NONZEROS, DuffingInline::NONZEROS);
}

#[test]
fn a_model_with_helpers_runs_as_the_same_model_inlined_by_hand() {
    // Bit for bit: the force calls the helpers, whose arithmetic is the hand-inlined force's
    // operation for operation (Rust neither reassociates nor contracts f64 arithmetic), and the
    // Jacobian code is generated from the same expression graph, so Rodas5P takes the same steps
    // on the same numbers.
    let inline = DuffingInline {
        x: DUFFING.x,
        v: DUFFING.v,
        k: DUFFING.k,
        c: DUFFING.c,
        b: DUFFING.b,
        m: DUFFING.m,
    };
    let with = DUFFING
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(20.0)
        .run()
        .unwrap();
    let by_hand = inline
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(20.0)
        .run()
        .unwrap();
    assert_eq!(with.samples.len(), by_hand.samples.len());
    assert!(with.samples.len() > 50, "{} samples", with.samples.len());
    for (a, b) in with.samples.iter().zip(&by_hand.samples) {
        assert_eq!(a.t.to_bits(), b.t.to_bits());
        assert_eq!(a.state.x.to_bits(), b.state.x.to_bits(), "x at t = {}", a.t);
        assert_eq!(a.state.v.to_bits(), b.state.v.to_bits(), "v at t = {}", a.t);
    }
    // Drag only takes energy away.
    let energy = |s: &DuffingState| {
        Duffing {
            x: s.x,
            v: s.v,
            ..DUFFING
        }
        .energy()
    };
    assert!(energy(&with.last().state) < energy(&with.first().state));
}
