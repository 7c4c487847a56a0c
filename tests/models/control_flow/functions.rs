//! Every supported function, destructuring, and arrays filled in place.

use crate::common::check;
use odyn::prelude::*;

/// Natural Rust: tuple destructuring of state-dependent values (`sin_cos`), a component
/// assignment, and every supported function.
#[system]
#[derive(Clone, Copy, Debug)]
struct Functions {
    #[state]
    p: f64,
    #[state]
    q: f64,
    #[state]
    r: Vector2<f64>,
}

#[system]
impl Functions {
    fn derivative(&self) -> FunctionsState {
        let (s, c) = self.p.sin_cos();
        let (u, w) = (0.3 * self.p, 0.2 * self.q);
        let mut v = self.r;
        v[0] *= s;
        v.y += c;
        let angles = u.atan2(w) + u.asin() + w.acos() + u.atan() + u.hypot(w);
        let hyperbolic = u.sinh() + w.cosh() + u.tanh();
        let logs = (1.0 + u * u).log10() + (2.0 + w).log2() + u.exp2() + w.ln_1p() + u.exp_m1();
        let roots = (1.5 + w).cbrt() + u.abs() * 0.5 + (u - w).signum();
        let kinks = u.min(w) + u.max(w) + self.q.clamp(-0.5, 0.5) + (2.0 * u).clamp(w, w + 1.0);
        FunctionsState {
            p: angles + hyperbolic * s,
            q: logs * c + roots + kinks,
            r: Vector2::new(v.x * v.y, v.x + u.recip()),
        }
    }
}

#[test]
fn every_function_and_destructuring_is_differentiated() {
    let model = Functions {
        p: 0.1,
        q: 0.2,
        r: Vector2::new(0.3, 0.4),
    };
    check(&model, 0.0, 100, |r| FunctionsState {
        // Away from the kinks' measure-zero sets: u ≠ w, |q| ≠ 0.5, u ≠ 0.
        p: r.uniform(0.2, 2.0),
        q: r.uniform(-2.0, -0.6),
        r: Vector2::new(r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0)),
    });
}

const LEN: usize = 2;

/// An array filled component by component, and state-free locals odyn reads by name: a `usize`,
/// and an array of a computed length changed in place. Each once failed to compile: `o[0] = …`
/// into `[0.0; 2]` was refused (odyn read the array as one number), and the Jacobian's code
/// computed `self.n` and `[0.0; LEN]` as `f64`s it never read.
#[system]
#[derive(Clone, Copy, Debug)]
struct Filled {
    #[state]
    x: [f64; 2],
    k: f64,
    n: usize,
}

#[system]
impl Filled {
    fn derivative(&self) -> FilledState {
        let n = self.n;
        let mut gains = [0.0; LEN];
        gains[1] = self.k;
        let mut rates = [0.0; 2];
        rates[0] = -self.k * self.x[0] * n as f64;
        rates[1] = gains[1] * self.x[0];
        rates[1] -= self.x[1].powi(2);
        FilledState { x: rates }
    }
}

#[test]
fn arrays_filled_in_place_are_differentiated() {
    let model = Filled {
        x: [0.5, -0.25],
        k: 3.0,
        n: 2,
    };
    check(&model, 0.0, 20, |r| FilledState {
        x: [r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0)],
    });
    let mut jacobian = model.jacobian_matrix(&model.state());
    model.jacobian(0.0, &model.state(), &mut jacobian);
    // [[−k·n, 0], [k, −2·x₁]]
    assert_eq!(jacobian, odyn::nalgebra::Matrix2::new(-6.0, 0.0, 3.0, 0.5));
}
