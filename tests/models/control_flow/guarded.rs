//! Loops bounded at run time (by parameters, nested to one bound): their iterations guarded by
//! the state's length (`lower/guarded.rs`).

use crate::common::{Rng, check};
use odyn::prelude::*;

/// Loops bounded by parameters: a `for` to `self.active` over the first masses of a chain (the
/// rest at rest) with a free end (an `if` on the bound that reads past the state's end in the
/// arm the last iteration does not take), a `while` on a counter up to `self.coupled`, and a
/// `for … ..=` after them.
/// The state's length (6) caps the iterations; each runs only when its test holds at run time.
#[system]
#[derive(Clone, Copy, Debug)]
struct Partial {
    #[state]
    x: [f64; 6],
    active: usize,
    coupled: usize,
    last: usize,
    k: [f64; 6],
}

#[system]
#[allow(
    clippy::needless_range_loop,
    reason = "index loops bounded by a parameter are the form under test"
)]
impl Partial {
    fn derivative(&self) -> PartialState {
        let mut out = [0.0; 6];
        for i in 0..self.active {
            out[i] = -self.k[i] * self.x[i] * self.x[i].abs();
            // A free end: the last active mass has no right neighbour. At i = 5 the arm that
            // reads `self.x[6]` cannot be taken, and the iteration still runs (active = 6).
            let right = if i + 1 < self.active {
                self.x[i + 1]
            } else {
                0.0
            };
            out[i] += 0.5 * (right - self.x[i]);
        }
        let mut i = 1;
        while i < self.coupled {
            let spring = self.x[i] - self.x[i - 1];
            out[i] -= spring;
            out[i - 1] += spring;
            i += 1;
        }
        let mut sum = 0.0;
        for j in 2..=self.last {
            sum += self.x[j].sin();
        }
        out[0] += sum;
        PartialState { x: out }
    }
}

#[test]
fn loops_bounded_by_parameters_are_guarded() {
    let mut rng = Rng(11);
    // Every bound from none to all of the state (and `last` one short of the end).
    for (active, coupled, last) in [(0, 0, 0), (3, 2, 4), (6, 6, 5), (1, 5, 2), (6, 0, 1)] {
        let model = Partial {
            x: [0.0; 6],
            active,
            coupled,
            last,
            k: [1.0, 2.0, 0.5, 1.5, 3.0, 0.7],
        };
        check(&model, 0.0, 30, |r| PartialState {
            x: [(); 6].map(|()| r.uniform(-2.0, 2.0)),
        });
        // Entries outside the loops' reach are exactly zero: rows of inactive masses.
        let x = [(); 6].map(|()| rng.uniform(-2.0, 2.0));
        let mut j = model.jacobian_matrix(&PartialState { x });
        model.jacobian(0.0, &PartialState { x }, &mut j);
        for i in active.max(coupled)..6 {
            for c in 0..6 {
                assert_eq!(j[(i, c)], 0.0, "({i}, {c}) at {active}, {coupled}, {last}");
            }
        }
    }
}

/// Forms a review found the guarded loops and rows mishandling: a test on the state after `&&`
/// that reads past the end only when the bound test before it fails, a row set past the end in
/// an arm that cannot be taken, the loop variable used as the end's integer type, and
/// parameter-only rows changed in place (`w[k][0] = …`, `w[k] = [ … ]`) before the state reads
/// them; and two nested loops bounded at run time.
#[system]
#[derive(Clone, Copy, Debug)]
struct Reviewed {
    #[state]
    x: [f64; 3],
    n: usize,
    c: [f64; 3],
    v: Vector2<f64>,
}

#[system]
#[allow(
    clippy::needless_range_loop,
    clippy::explicit_counter_loop,
    reason = "index loops and counters bounded by a parameter are the forms under test"
)]
impl Reviewed {
    fn derivative(&self) -> ReviewedState {
        let mut w = [[0.0; 2]; 3];
        for k in 0..3 {
            w[k][0] = self.c[k];
        }
        let mut v = [[0.0; 2]; 3];
        for k in 0..3 {
            v[k] = [self.c[k], 1.0];
        }
        let mut out = [0.0; 3];
        let mut d = [0.0; 3];
        for i in 0..self.n {
            out[i] = -w[i][0] * self.x[i] - v[i][1] * (i.pow(2) as f64) * self.x[i];
            if i + 1 < self.n && self.x[i + 1] > self.x[i] {
                out[i] += self.x[i + 1] - self.x[i];
            }
            d[i] -= self.x[i];
            if i + 1 < self.n {
                d[i + 1] += self.x[i];
            }
        }
        for i in 0..3 {
            out[i] += 0.5 * d[i];
        }
        // A vector whose number type only its state-dependent uses fix (`zeros()`), and an
        // index cast from a `u32` loop variable.
        let mut z = Vector2::zeros();
        z += self.v * self.x[1];
        out[1] += z.x - z.y;
        for k in 0..(self.n as u32) {
            out[k as usize] -= 0.01 * self.x[k as usize].powi(2);
        }
        // A counter of the body's own, not the loop variable, indexes the state.
        let mut j = 0;
        let mut s = 0.0;
        for _ in 0..self.n {
            s += self.x[j] * self.x[j];
            j += 1;
        }
        out[0] += 0.1 * s;
        // Nested loops both bounded at run time: the outer one indexes by `i` at its own level.
        for i in 0..self.n {
            out[i] -= 0.1 * self.x[i];
            for j in 0..self.n {
                out[i] += 0.05 * (self.x[j] - self.x[i]).powi(3);
            }
        }
        ReviewedState { x: out }
    }
}

#[test]
fn guarded_loops_follow_short_circuits_free_ends_and_rows_changed_in_place() {
    for n in 0..=3 {
        let model = Reviewed {
            x: [0.0; 3],
            n,
            c: [1.5, -0.5, 2.0],
            v: Vector2::new(0.7, -1.3),
        };
        // Away from the switching surface x[i + 1] = x[i], where the `if` changes arm.
        check(&model, 0.0, 40, |r| {
            let a = r.uniform(-2.0, 2.0);
            let b = a + r.uniform(0.1, 1.0) * if r.uniform(0.0, 1.0) < 0.5 { 1.0 } else { -1.0 };
            let c = b + r.uniform(0.1, 1.0) * if r.uniform(0.0, 1.0) < 0.5 { 1.0 } else { -1.0 };
            ReviewedState { x: [a, b, c] }
        });
        // Row n − 1 (the last active) reads x[n − 1] on its diagonal: never a zero row.
        if n > 0 {
            let y = ReviewedState {
                x: [0.3, -0.2, 0.9],
            };
            let mut j = model.jacobian_matrix(&y);
            model.jacobian(0.0, &y, &mut j);
            assert!(j[(n - 1, n - 1)] != 0.0, "n = {n}: {j}");
        }
    }
}

/// Two loops to the same run-time bound, the outer variable indexing only inside the inner
/// loop: the inner loop's first iteration runs whenever the outer iteration does (i < n ⇒ j = 0
/// < n), so its index past the end caps the outer loop (`lower/guarded.rs`).
#[system]
#[derive(Clone, Copy, Debug)]
struct Square {
    #[state]
    x: [[f64; 3]; 3],
    n: usize,
}

#[system]
#[allow(
    clippy::needless_range_loop,
    reason = "index loops bounded by a parameter are the form under test"
)]
impl Square {
    fn derivative(&self) -> SquareState {
        let mut d = [[0.0; 3]; 3];
        for i in 0..self.n {
            for j in 0..self.n {
                d[i][j] = -self.x[i][j] * self.x[j][i] + 0.5 * self.x[i][j];
            }
        }
        SquareState { x: d }
    }
}

#[test]
fn nested_loops_to_one_run_time_bound_are_guarded() {
    for n in 0..=3 {
        let model = Square {
            x: [[0.0; 3]; 3],
            n,
        };
        check(&model, 0.0, 20, |r| SquareState {
            x: std::array::from_fn(|_| std::array::from_fn(|_| r.uniform(-2.0, 2.0))),
        });
        // Every active entry's diagonal derivative: −x[j][i] + 0.5 (−2x[i][i] + 0.5 on the
        // diagonal), here never zero; inactive rows are zero.
        let y = SquareState {
            x: [[0.3, -0.2, 0.9], [0.1, 0.4, -0.7], [0.6, -0.5, 0.2]],
        };
        let mut j = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut j);
        for row in 0..3 {
            for column in 0..3 {
                let at = 3 * row + column;
                let active = row < n && column < n;
                assert_eq!(j[(at, at)] != 0.0, active, "n = {n}, x[{row}][{column}]");
            }
        }
    }
}
