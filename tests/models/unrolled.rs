//! Loops over literal ranges, unrolled in the code the macro emits for a fixed-size model
//! (`macros/src/unroll.rs`): the derivative is bit for bit the loop's — the same arithmetic in
//! the same order — and a loop variable keeps the type its range gave it.

use crate::common::Rng;
use odyn::prelude::*;
use scenes::{Pleiades, PleiadesState};

/// The Pleiades' pair loop (`scenes/src/orbits.rs`), written again as a plain loop over the
/// state: the generated derivative, whose loops are unrolled, must equal it exactly.
fn pleiades_by_hand(p: &Pleiades, s: &PleiadesState) -> ([f64; 7], [f64; 7]) {
    let mut ax = [0.0; 7];
    let mut ay = [0.0; 7];
    for i in 0..7 {
        for j in (i + 1)..7 {
            let dx = s.x[j] - s.x[i];
            let dy = s.y[j] - s.y[i];
            let r2 = dx * dx + dy * dy;
            let w = 1.0 / (r2 * r2.sqrt());
            ax[i] += p.m[j] * w * dx;
            ay[i] += p.m[j] * w * dy;
            ax[j] -= p.m[i] * w * dx;
            ay[j] -= p.m[i] * w * dy;
        }
    }
    (ax, ay)
}

#[test]
fn an_unrolled_pair_loop_is_the_loop_bit_for_bit() {
    let p = Pleiades::start();
    let mut rng = Rng(7);
    for _ in 0..50 {
        let mut s = p.state();
        for i in 0..7 {
            s.x[i] += rng.uniform(-0.5, 0.5);
            s.y[i] += rng.uniform(-0.5, 0.5);
        }
        let mut d = s;
        p.derivative(0.0, &s, &mut d);
        let (ax, ay) = pleiades_by_hand(&p, &s);
        assert_eq!((d.u, d.v), (ax, ay));
        assert_eq!((d.x, d.y), (s.u, s.v));
    }
}

/// Loops in the forms the unroller copies (a triangular pair loop, a `_` pattern, an inclusive
/// range) and one it keeps (a loop left by `break`).
#[system(jacobian = false)]
#[derive(Clone, Copy, Debug)]
struct Ring {
    #[position]
    x: [f64; 4],
    #[velocity]
    v: [f64; 4],
    k: [f64; 4],
}

#[system]
#[allow(
    clippy::needless_range_loop,
    reason = "index loops over literal ranges are the form under test"
)]
impl Ring {
    fn acceleration(&self) -> [f64; 4] {
        let mut a = [0.0; 4];
        for i in 0..4 {
            for j in (i + 1)..4 {
                // `j.pow` compiles only if `j` has a known integer type: the range gives it
                // `i`'s (`usize`, from indexing), which the unrolled copy must keep.
                let w = self.k[i] / j.pow(2) as f64;
                let d = self.x[j] - self.x[i];
                a[i] += w * d;
                a[j] -= w * d;
            }
        }
        for _ in 0..2 {
            a[0] *= 0.5;
        }
        for n in 1..=3 {
            if self.x[n] > 10.0 {
                break;
            }
            a[n] -= self.k[n] * self.x[n];
        }
        a
    }
}

#[test]
#[allow(
    clippy::needless_range_loop,
    reason = "the model's loops, written again"
)]
fn unrolled_loops_keep_their_variables_types_and_their_order() {
    let ring = Ring {
        x: [0.0; 4],
        v: [0.0; 4],
        k: [1.0, 2.0, 3.0, 4.0],
    };
    let mut rng = Rng(11);
    for _ in 0..20 {
        let x: [f64; 4] = std::array::from_fn(|_| rng.uniform(-12.0, 12.0));
        let s = RingState { x, v: [0.0; 4] };
        let mut expected = [0.0; 4];
        for i in 0..4 {
            for j in (i + 1)..4 {
                let w = ring.k[i] / (j * j) as f64;
                let d = x[j] - x[i];
                expected[i] += w * d;
                expected[j] -= w * d;
            }
        }
        expected[0] *= 0.25;
        for n in 1..=3 {
            if x[n] > 10.0 {
                break;
            }
            expected[n] -= ring.k[n] * x[n];
        }
        let mut d = s;
        ring.derivative(0.0, &s, &mut d);
        assert_eq!(d.v, expected);
    }
}
