//! Loops: over parameters, changing a local the state-dependent code reads, and on the state
//! with bounds known at compile time, unrolled.

use crate::common::{Rng, check};
use odyn::prelude::*;

/// A loop over parameters that changes a local the state-dependent code then reads: the
/// Jacobian used to keep the local's value from before the loop (∂/∂x = −1 instead of −4).
#[system]
#[derive(Clone, Copy, Debug)]
struct Looped {
    #[state]
    x: f64,
    n: usize,
    weights: [f64; 3],
}

#[system]
impl Looped {
    fn derivative(&self) -> LoopedState {
        let mut c = 1.0;
        for _ in 0..self.n {
            c += 1.0;
        }
        let mut w = 0.0;
        for k in 0..3 {
            w += self.weights[k];
        }
        LoopedState {
            x: -c * self.x + w * self.x.powi(2),
        }
    }
}

#[test]
fn loops_over_parameters_reach_the_jacobian() {
    let model = Looped {
        x: 0.5,
        n: 3,
        weights: [0.1, 0.2, 0.3],
    };
    check(&model, 0.0, 20, |r| LoopedState {
        x: r.uniform(-2.0, 2.0),
    });
    let mut jacobian = model.jacobian_matrix(&model.state());
    model.jacobian(0.0, &LoopedState { x: 0.0 }, &mut jacobian);
    // ∂/∂x (−4x + 0.6x²) at x = 0.
    assert!((jacobian[(0, 0)] + 4.0).abs() < 1e-12, "{jacobian}");
}

/// The loops of [`unrolled::Unrolled`] are the form under test, and the generated code copies its
/// body (clippy's lint would fire in the copy, beyond an `allow` on the function).
mod unrolled {
    #![allow(
        clippy::needless_range_loop,
        reason = "index loops are the form under test"
    )]

    use odyn::prelude::*;

    /// Loops on the state with bounds known at compile time, unrolled by the macro: a `for` over
    /// a literal range indexing the state by its variable, with `if`s on the variable (as a
    /// statement and as a value), a `while` on a counter, a nested loop whose bound is the outer
    /// variable, and a state-free local the loop changes as it goes (`w`), which the Jacobian's
    /// prologue replays iteration by iteration.
    #[system]
    #[derive(Clone, Copy, Debug)]
    pub(super) struct Unrolled {
        #[state]
        pub(super) x: [f64; 4],
        pub(super) k: f64,
        pub(super) weights: [f64; 4],
    }

    #[system]
    impl Unrolled {
        fn derivative(&self) -> UnrolledState {
            let mut out = [0.0; 4];
            for i in 0..4 {
                // Known at compile time in each iteration: only the arm taken is lowered, so
                // `self.x[i - 1]` is never read at i = 0.
                let mut left = 0.0;
                if i > 0 {
                    left = self.x[i - 1];
                }
                out[i] = if i == 0 {
                    -self.k * self.x[0]
                } else {
                    self.k * (left - self.x[i])
                };
            }
            let mut energy = 0.0;
            let mut i = 0;
            while i < 4 {
                energy += self.x[i] * self.x[i];
                i += 1;
            }
            let mut w = 0.0;
            for k in 0..=3 {
                w += self.weights[k];
                for j in 0..k {
                    out[k] -= w * self.x[j] * energy.sqrt();
                }
            }
            UnrolledState { x: out }
        }
    }

    /// [`Unrolled`] unrolled by hand.
    #[system]
    #[derive(Clone, Copy, Debug)]
    pub(super) struct ByHand {
        #[state]
        pub(super) x: [f64; 4],
        pub(super) k: f64,
        pub(super) weights: [f64; 4],
    }

    #[system]
    impl ByHand {
        fn derivative(&self) -> ByHandState {
            let x = self.x;
            let energy = 0.0 + x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3];
            let s = energy.sqrt();
            let w = [
                0.0 + self.weights[0],
                0.0 + self.weights[0] + self.weights[1],
                0.0 + self.weights[0] + self.weights[1] + self.weights[2],
                0.0 + self.weights[0] + self.weights[1] + self.weights[2] + self.weights[3],
            ];
            let mut out = [
                -self.k * x[0],
                self.k * (x[0] - x[1]),
                self.k * (x[1] - x[2]),
                self.k * (x[2] - x[3]),
            ];
            out[1] -= w[1] * x[0] * s;
            out[2] -= w[2] * x[0] * s;
            out[2] -= w[2] * x[1] * s;
            out[3] -= w[3] * x[0] * s;
            out[3] -= w[3] * x[1] * s;
            out[3] -= w[3] * x[2] * s;
            ByHandState { x: out }
        }
    }
}

use unrolled::{ByHand, ByHandState, Unrolled, UnrolledState};

#[test]
fn loops_on_the_state_with_known_bounds_are_unrolled() {
    let model = Unrolled {
        x: [0.0; 4],
        k: 1.5,
        weights: [0.3, -0.2, 0.7, 0.4],
    };
    check(&model, 0.0, 100, |r| UnrolledState {
        x: [
            r.uniform(-2.0, 2.0),
            r.uniform(-2.0, 2.0),
            r.uniform(-2.0, 2.0),
            r.uniform(-2.0, 2.0),
        ],
    });
    let hand = ByHand {
        x: model.x,
        k: model.k,
        weights: model.weights,
    };
    let mut rng = Rng(7);
    for _ in 0..20 {
        let x = [(); 4].map(|()| rng.uniform(-2.0, 2.0));
        let (mut j, mut k) = (
            model.jacobian_matrix(&UnrolledState { x }),
            hand.jacobian_matrix(&ByHandState { x }),
        );
        model.jacobian(0.0, &UnrolledState { x }, &mut j);
        hand.jacobian(0.0, &ByHandState { x }, &mut k);
        assert_eq!(j, k, "at {x:?}");
        let (mut f, mut g) = (UnrolledState { x }, ByHandState { x });
        Model::derivative(&model, 0.0, &UnrolledState { x }, &mut f);
        Model::derivative(&hand, 0.0, &ByHandState { x }, &mut g);
        assert_eq!(f.x, g.x);
    }
}
