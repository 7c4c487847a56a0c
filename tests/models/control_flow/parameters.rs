//! Branches on parameters: an early `return`, and `if`, `match` and `if let` in every position.

use crate::common::{Rng, check};
use odyn::prelude::*;
use odyn::stability::predicted_limit;

/// An early `return` on a parameter: the Jacobian must follow the branch the derivative takes.
#[system]
#[derive(Clone, Copy, Debug)]
struct Cutoff {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
}

#[system]
impl Cutoff {
    fn acceleration(&self) -> f64 {
        if self.k > 10.0 {
            return 0.0;
        }
        -self.k * self.x
    }
}

#[test]
fn an_early_return_on_a_parameter_is_differentiated() {
    let draw = |r: &mut Rng| CutoffState {
        x: r.uniform(-2.0, 2.0),
        v: r.uniform(-2.0, 2.0),
    };
    for k in [5.0, 20.0] {
        let model = Cutoff { x: 1.0, v: 0.0, k };
        check(&model, 0.0, 20, draw);
    }
    // k = 20 returns 0: a free particle, for which RK4 has no stability limit (∞) — the wrong
    // Jacobian [[0, 1], [−20, 0]] predicted 2√2/√20 = 0.632.
    let free = Cutoff {
        x: 1.0,
        v: 0.0,
        k: 20.0,
    };
    let limit = predicted_limit(&free, 0.0, &free.state(), Method::Rk4).unwrap();
    assert_eq!(limit, f64::INFINITY);
}

/// Branches on parameters in every position: a value (`if` and `match`), a statement changing a
/// state-dependent local, `if let`, a `match` with guards and bindings, nested returns.
#[system]
#[derive(Clone, Copy, Debug)]
struct Branchy {
    #[state]
    a: f64,
    #[state]
    b: f64,
    mode: u32,
    gain: f64,
    scale: Option<f64>,
}

#[system]
impl Branchy {
    fn derivative(&self) -> BranchyState {
        let (m1, m2) = (1.0, 2.0);
        let base = if self.gain > 1.0 {
            self.a * self.a
        } else {
            self.a.sin()
        };
        let mut extra = self.b * m1;
        if self.mode == 2 {
            extra = extra * self.a + m2;
        } else if self.mode == 3 {
            extra *= 3.0;
        }
        let factor = match self.mode {
            0 => 1.0,
            n if n > 5 => 1.0 / f64::from(n),
            _ => self.b.exp(),
        };
        if let Some(s) = self.scale {
            if s < 0.0 {
                return BranchyState {
                    a: -self.a,
                    b: s * self.b,
                };
            }
            return BranchyState {
                a: s * base + extra,
                b: factor * self.a,
            };
        }
        BranchyState {
            a: base + extra * factor,
            b: -self.b * factor,
        }
    }
}

#[test]
fn branches_on_parameters_are_differentiated_on_every_path() {
    let draw = |r: &mut Rng| BranchyState {
        a: r.uniform(-1.5, 1.5),
        b: r.uniform(-1.5, 1.5),
    };
    for mode in [0, 2, 3, 4, 7] {
        for gain in [0.5, 2.0] {
            for scale in [None, Some(0.7), Some(-0.3)] {
                let model = Branchy {
                    a: 0.0,
                    b: 0.0,
                    mode,
                    gain,
                    scale,
                };
                check(&model, 0.0, 10, draw);
            }
        }
    }
}
