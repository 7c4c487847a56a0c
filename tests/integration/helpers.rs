//! Helper functions marked `#[odyn::function]`: the Jacobians the macro derives by inlining them
//! against central differences, ∂f/∂t through a helper, and runs of a model with helpers against
//! the same model with the helpers inlined by hand.
//!
//! Tolerance: `common::check` compares with central differences at h = 1e-6·(1 + |yⱼ|): the
//! truncation error is O(h²·|f‴|) ≈ 1e-12 and the rounding error O(ε·|f|/h) ≈ 1e-10 relative to
//! the row's scale for these smooth, O(1)–O(100) forces, so 1e-6 relative fails on any wrong
//! derivative (a missing term is O(1)) and never on a right one. The random states stay off the
//! measure-zero kinks of `abs` and of the `if`s, where a difference quotient straddles two arms.

use crate::common;

use common::check;
use odyn::nalgebra::Vector2;
use odyn::prelude::*;

/// A Duffing oscillator with quadratic drag, m·ẍ = −k·x − c·x³ − b·v·|v|, written with nested
/// helpers: `total` calls `restoring` (a method reading parameters) and `drag` (an associated
/// function given a parameter and the state).
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct Duffing {
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

/// A first-order model whose helpers branch on their argument (`if` on the state inside a
/// helper), return a tuple, take and return vectors, and read the time.
#[system(integrator = Rodas5P)]
#[derive(Clone, Copy, Debug)]
struct Helped {
    #[state]
    p: f64,
    #[state]
    q: f64,
    #[state]
    r: Vector2<f64>,
    a: f64,
    gm: f64,
    scale: f64,
    k: f64,
}

#[system]
impl Helped {
    fn derivative(&self, t: f64) -> HelpedState {
        // A local the helper's own `k` must not shadow: `k.floor()` is state-free code odyn
        // leaves to the prologue, which reads `k` by name after the helper's code ran.
        let k = self.a + 0.5;
        let (radius, angle) = Self::polar(self.p, self.q);
        let soft = self.ramp(self.p - self.q);
        let kk = k.floor();
        HelpedState {
            p: soft - kk * self.p + self.drive(t) * angle.cos(),
            q: radius.sin() - self.q,
            r: self.gravity(self.r),
        }
    }

    /// Smooth (C¹) at 1: x² below, 2x − 1 above.
    #[odyn::function]
    fn ramp(&self, x: f64) -> f64 {
        let k = self.k * self.scale;
        if x > 1.0 {
            k * (2.0 * x - 1.0)
        } else {
            k * x * x
        }
    }

    #[odyn::function]
    fn polar(x: f64, y: f64) -> (f64, f64) {
        (x.hypot(y), y.atan2(x))
    }

    #[odyn::function]
    fn gravity(&self, r: Vector2<f64>) -> Vector2<f64> {
        -self.gm * r / r.norm().powi(3)
    }

    #[odyn::function]
    fn drive(&self, t: f64) -> f64 {
        self.a * (2.0 * t).sin()
    }
}

#[test]
fn helpers_with_branches_tuples_vectors_and_the_time_have_exact_derivatives() {
    let model = Helped {
        p: 0.0,
        q: 0.0,
        r: Vector2::zeros(),
        a: 1.7,
        gm: 2.0,
        scale: 0.5,
        k: 3.0,
    };
    for t in [0.0, 0.4, 2.5] {
        check(&model, t, 100, |r| HelpedState {
            // p − q on both sides of the ramp's switch at 1.
            p: r.uniform(-2.0, 3.0),
            q: r.uniform(0.1, 1.0),
            r: Vector2::new(r.uniform(0.5, 2.0), r.uniform(-2.0, -0.5)),
        });
    }
    // ∂f/∂t flows through `drive` exactly: ∂ṗ/∂t = 2a·cos(2t)·cos(atan2(q, p)).
    const { assert!(<Helped as odyn::Jacobian>::TIME_DEPENDENT) };
    let y = HelpedState {
        p: 0.8,
        q: 0.3,
        r: Vector2::new(1.0, -1.0),
    };
    let t = 0.9;
    let mut dfdt = y;
    model.time_derivative(t, &y, &mut dfdt);
    let exact = 2.0 * 1.7 * (2.0 * t).cos() * 0.3f64.atan2(0.8).cos();
    assert!((dfdt.p - exact).abs() < 1e-14, "{} vs {exact}", dfdt.p);
    assert_eq!((dfdt.q, dfdt.r), (0.0, Vector2::zeros()));
    // The caller's `k` (2.2, floored to 2), not the helper's (1.5): at t = 0 the drive is 0, so
    // in the ramp's upper arm (p − q > 1) ∂ṗ/∂p = 2·1.5 − 2.
    let y = HelpedState {
        p: 2.5,
        q: 0.5,
        r: Vector2::new(1.0, -1.0),
    };
    let mut j = model.jacobian_matrix(&y);
    model.jacobian(0.0, &y, &mut j);
    assert_eq!(j[(0, 0)], 1.0);
}
