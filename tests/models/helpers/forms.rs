//! Helpers that branch on the state, return tuples, take and return vectors, read the time, or
//! are called in an arm of an `if` on the state with locals of their own.

use odyn::nalgebra::Vector2;
use odyn::prelude::*;

use crate::common::check;

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
    soft: bool,
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
            q: radius.sin() - self.q * Self::stepped(self.a),
            r: self.gravity(self.r),
        }
    }

    /// Smooth (C¹) at 1: x² below, 2x − 1 above, times a gain chosen by a parameter: a branch
    /// on parameters and an early `return` on the state inside a helper.
    #[odyn::function]
    fn ramp(&self, x: f64) -> f64 {
        let k = if self.soft {
            self.k * self.scale
        } else {
            self.k
        };
        if x > 1.0 {
            return k * (2.0 * x - 1.0);
        }
        k * x * x
    }

    /// Not differentiable by odyn (`floor`), and called only on parameters: evaluated by the
    /// user's code, as any call on parameters.
    #[odyn::function]
    fn stepped(x: f64) -> f64 {
        x.floor()
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
        soft: true,
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
    // The other arm of the helper's branch on `soft`: gain k = 3, so 2·3 − 2; and ∂q̇/∂q =
    // −floor(a).
    let hard = Helped {
        soft: false,
        ..model
    };
    hard.jacobian(0.0, &y, &mut j);
    assert_eq!(j[(0, 0)], 4.0);
    let radius = 0.5f64.hypot(2.5);
    let exact = radius.cos() * 0.5 / radius - 1.0;
    assert!(
        (j[(1, 1)] - exact).abs() < 1e-15,
        "{} vs {exact}",
        j[(1, 1)]
    );
    check(&hard, 0.3, 100, |r| HelpedState {
        p: r.uniform(-2.0, 3.0),
        q: r.uniform(0.1, 1.0),
        r: Vector2::new(r.uniform(0.5, 2.0), r.uniform(-2.0, -0.5)),
    });
}

/// A helper called in an arm of an `if` on the state, given a parameter, changing a local of its
/// own that has the name of one of its caller's: the helper's code runs in a block of its own,
/// so it neither changes the caller's `g` nor counts as the arm changing it.
#[system]
#[derive(Clone, Copy, Debug)]
struct Armed {
    #[state]
    x: f64,
    k: f64,
}

#[system]
impl Armed {
    fn derivative(&self) -> ArmedState {
        let g = self.k + 1.0;
        let y = if self.x > 0.0 {
            self.scaled(self.x, self.k)
        } else {
            -self.x
        };
        ArmedState {
            x: y * g.floor() - self.x,
        }
    }

    #[odyn::function]
    fn scaled(&self, x: f64, k: f64) -> f64 {
        let mut g = k;
        g *= 2.0;
        g * x * x
    }
}

#[test]
fn a_helper_in_an_arm_on_the_state_keeps_its_locals_to_itself() {
    let model = Armed { x: 0.0, k: 1.25 };
    check(&model, 0.0, 100, |r| ArmedState {
        x: if r.uniform(0.0, 1.0) < 0.5 {
            r.uniform(-2.0, -0.01)
        } else {
            r.uniform(0.01, 2.0)
        },
    });
    // x > 0: ẋ = 2k·x²·floor(k + 1) − x, so ∂ẋ/∂x = 4k·x·2 − 1 with the caller's g = 2.25.
    let mut j = model.jacobian_matrix(&model.state());
    model.jacobian(0.0, &ArmedState { x: 0.5 }, &mut j);
    assert_eq!(j[(0, 0)], 4.0 * 1.25 * 0.5 * 2.0 - 1.0);
}
