//! The Jacobian through every control-flow form the macro accepts, and through every supported
//! function, against central differences of the model's own derivative (common::check, 1e-6
//! relative). Each model here once either failed to compile or, worse, compiled to a wrong
//! Jacobian: an early `return` on a parameter was ignored, and a loop over parameters was
//! dropped from the Jacobian's code.

use crate::common;

use common::{Rng, check};
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

/// A forced oscillator: ẍ = −x + A·sin(ωt)·e^(−t/τ). Its ∂f/∂t is generated exactly; a model
/// that reads the time through a function of the user's own gets the runtime's central
/// difference; an autonomous one a constant zero.
#[system]
#[derive(Clone, Copy, Debug)]
struct Forced {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    amplitude: f64,
    omega: f64,
    tau: f64,
}

#[system]
impl Forced {
    fn acceleration(&self, t: f64) -> f64 {
        let envelope = (-t / self.tau).exp();
        let drive = if t < 10.0 {
            (self.omega * t).sin()
        } else {
            0.0
        };
        -self.x + self.amplitude * drive * envelope * self.v.cos()
    }
}

fn pulse(t: f64) -> f64 {
    (-t * t).exp()
}

/// The time reaches f through `pulse`, a function odyn cannot see into.
#[system]
#[derive(Clone, Copy, Debug)]
struct Pulsed {
    #[state]
    y: f64,
}

#[system]
impl Pulsed {
    fn derivative(&self, t: f64) -> PulsedState {
        PulsedState {
            y: -self.y + pulse(t),
        }
    }
}

#[test]
fn the_time_derivative_is_exact_where_it_can_be() {
    let forced = Forced {
        x: 0.3,
        v: -0.2,
        amplitude: 1.5,
        omega: 2.0,
        tau: 4.0,
    };
    const { assert!(<Forced as odyn::Jacobian>::TIME_DEPENDENT) };
    let y = forced.state();
    for t in [0.0, 0.7, 3.1, 9.5, 12.0] {
        let mut dfdt = y;
        forced.time_derivative(t, &y, &mut dfdt);
        // Central difference in t of f(t, y), h = 1e-6.
        let (mut plus, mut minus) = (y, y);
        forced.derivative(t + 1e-6, &y, &mut plus);
        forced.derivative(t - 1e-6, &y, &mut minus);
        let fd = (plus.v - minus.v) / 2e-6;
        assert_eq!(dfdt.x, 0.0, "ẋ = v does not read t");
        assert!(
            (dfdt.v - fd).abs() < 1e-6 * (1.0 + fd.abs()),
            "t = {t}: {} vs {fd}",
            dfdt.v
        );
    }
    // Exact: at t = 0, ∂/∂t [A·sin(ωt)·e^(−t/τ)·cos v] = A·ω·cos(v).
    let mut dfdt = y;
    forced.time_derivative(0.0, &y, &mut dfdt);
    assert!((dfdt.v - 1.5 * 2.0 * (-0.2f64).cos()).abs() < 1e-15);

    let pulsed = Pulsed { y: 1.0 };
    let mut dfdt = pulsed.state();
    pulsed.time_derivative(0.5, &pulsed.state(), &mut dfdt);
    // d/dt e^(−t²) = −2t·e^(−t²).
    let exact = -2.0 * 0.5 * (-0.25f64).exp();
    assert!((dfdt.y - exact).abs() < 1e-8, "{} vs {exact}", dfdt.y);

    const { assert!(!<common::Lorenz as odyn::Jacobian>::TIME_DEPENDENT) };
}

/// The time shadowed by a shifted copy, and an alias of it passed to a function odyn cannot see
/// into: ẏ = −y + sin(t − t₀)·y + pulse(s), s = t.
#[system]
#[derive(Clone, Copy, Debug)]
struct Shifted {
    #[state]
    y: f64,
    t0: f64,
}

#[system]
impl Shifted {
    fn derivative(&self, t: f64) -> ShiftedState {
        let s = t;
        let kick = pulse(s);
        let t = t - self.t0;
        ShiftedState {
            y: -self.y + t.sin() * self.y + kick,
        }
    }
}

#[test]
fn a_shadowed_or_aliased_time_keeps_the_jacobian_and_time_derivative_right() {
    // The derivative code copies the time before the user's state-free lets run, so J reads
    // sin(t − t₀), not sin(t − 2t₀); and `pulse(s)` with s = t makes ∂f/∂t the runtime's
    // central difference (exact ∂f/∂t would have dropped pulse's part).
    let model = Shifted { y: 0.8, t0: 0.5 };
    let (t, y) = (1.3, model.state());
    let mut jacobian = model.jacobian_matrix(&y);
    model.jacobian(t, &y, &mut jacobian);
    let expected = -1.0 + (t - 0.5f64).sin();
    assert!(
        (jacobian[(0, 0)] - expected).abs() < 1e-15,
        "{}",
        jacobian[(0, 0)]
    );
    let mut dfdt = y;
    model.time_derivative(t, &y, &mut dfdt);
    // ∂f/∂t = cos(t − t₀)·y − 2t·e^(−t²).
    let exact = (t - 0.5f64).cos() * 0.8 - 2.0 * t * (-t * t).exp();
    assert!((dfdt.y - exact).abs() < 1e-8, "{} vs {exact}", dfdt.y);
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

/// Branches on the state: a contact force only while the ball is inside the wall (`if` as a
/// value), drag that switches on above a speed in either direction (`if`/`else if` as
/// statements changing a local), a kick under a compound condition (`&&`, `||`, `!`), and an
/// early `return` past a line. Each arm is differentiated on its own.
#[system]
#[derive(Clone, Copy, Debug)]
struct Wall {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
    c: f64,
}

#[system]
impl Wall {
    fn acceleration(&self) -> f64 {
        let contact = if self.x < 0.0 { -self.k * self.x } else { 0.0 };
        let mut drag = 0.0;
        if self.v > 1.0 {
            drag = -self.c * (self.v - 1.0) * (self.v - 1.0);
        } else if self.v <= -1.0 {
            drag = self.c * (self.v + 1.0).powi(2);
        }
        if self.x >= 3.0 {
            return -self.x * self.v;
        }
        let mut kick = 0.0;
        if (self.x > 1.0 && self.v < 0.0) || !(self.x < 2.5 || self.v > 5.0) {
            kick = 0.2 * self.v * self.x;
        }
        contact + drag + kick - 0.1 * self.x * self.x.sin()
    }
}

#[test]
fn branches_on_the_state_are_differentiated_arm_by_arm() {
    let model = Wall {
        x: 1.0,
        v: 0.0,
        k: 1e3,
        c: 0.5,
    };
    // Central differences straddle no switching surface: x = 0, 1, 2.5 and 3, v = 0 and ±1 are
    // avoided.
    let away = |r: &mut Rng, lo: f64, hi: f64, surfaces: &[f64]| loop {
        let value = r.uniform(lo, hi);
        if surfaces.iter().all(|s| (value - s).abs() > 0.05) {
            return value;
        }
    };
    check(&model, 0.0, 200, |r| WallState {
        x: away(r, -1.0, 4.0, &[0.0, 1.0, 2.5, 3.0]),
        v: away(r, -2.0, 2.0, &[-1.0, 0.0, 1.0]),
    });
    // On a switching surface the comparison chooses the arm, and the Jacobian is that arm's:
    // at x = 0, `x < 0.0` is false, so the contact's −k is not in ∂a/∂x; at x = 3, `x >= 3.0`
    // holds, so ∂a/∂x = −v.
    for (x, expected) in [(0.0, 0.0), (3.0, -0.5)] {
        let y = WallState { x, v: 0.5 };
        let mut jacobian = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut jacobian);
        assert_eq!(
            odyn::DenseMatrix::entry(&jacobian, 1, 0),
            expected,
            "x = {x}"
        );
    }
}

/// A ball falling onto a stiff penalty wall, a = −g + k·max(−x, 0) written as an `if`, bounces
/// back to the height it fell from: the contact is conservative (energy v²/2 + g·x +
/// k·min(x, 0)²/2), and the stiff methods, which need the Jacobian through the branch, keep it.
#[system]
#[derive(Clone, Copy, Debug)]
struct Drop {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
}

#[system]
impl Drop {
    fn acceleration(&self) -> f64 {
        if self.x < 0.0 {
            -9.81 - self.k * self.x
        } else {
            -9.81
        }
    }
}

#[test]
fn a_stiff_method_runs_through_a_branch_on_the_state() {
    let ball = Drop {
        x: 1.0,
        v: 0.0,
        k: 1e6,
    };
    for method in [Method::Rodas5P, Method::Bdf] {
        let run = ball
            .simulate()
            .integrator(method)
            .tolerances(1e-9, 1e-12)
            .duration(0.9)
            .run()
            .unwrap();
        // Free fall from 1 m lasts √(2/g) = 0.4515 s; the contact, half a period of √k rad/s,
        // 3.1 ms; the way back up another 0.4515 s: at t = 0.9 the ball is near the top again,
        // out of the wall, with the energy it fell with, g·1 m.
        assert!(
            run.samples.iter().any(|s| s.state.x < 0.0),
            "{method:?} never touched"
        );
        let end = run.last().state;
        let energy = 0.5 * end.v * end.v + 9.81 * end.x;
        assert!(end.x > 0.9, "{method:?}: x(0.9) = {}", end.x);
        assert!(
            (energy / 9.81 - 1.0).abs() < 1e-4,
            "{method:?}: energy {energy}"
        );
    }
}

/// A stiffness chosen by an `if` on the state, then branched on: the chosen local reads the
/// state, so the second `if` is one on the state too, and each side of the wall gets its own
/// Jacobian (a parameter-only copy of the first choice once decided the second branch for every
/// state).
#[system]
#[derive(Clone, Copy, Debug)]
struct Contact {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k_out: f64,
    k_in: f64,
}

#[system]
impl Contact {
    fn acceleration(&self) -> f64 {
        let k = if self.x < 0.0 { self.k_in } else { self.k_out };
        if k > 0.0 {
            -k * self.x - self.v
        } else {
            -self.v * self.v
        }
    }
}

#[test]
fn a_local_chosen_by_the_state_branches_on_the_state() {
    let model = Contact {
        x: 1.0,
        v: 2.0,
        k_out: 0.0,
        k_in: 1e3,
    };
    check(&model, 0.0, 100, |r| ContactState {
        x: if r.uniform(0.0, 1.0) < 0.5 {
            r.uniform(-2.0, -0.05)
        } else {
            r.uniform(0.05, 2.0)
        },
        v: r.uniform(-2.0, 2.0),
    });
    // Outside the wall (k = 0) a = −v², so ∂a/∂v = −2v = −4 at v = 2.
    let y = ContactState { x: 1.0, v: 2.0 };
    let mut jacobian = model.jacobian_matrix(&y);
    model.jacobian(0.0, &y, &mut jacobian);
    assert_eq!(odyn::DenseMatrix::entry(&jacobian, 1, 1), -4.0);
}

/// Conditions on the state that mix in a parameter-only flag: `open && x > 0 || !open && x < −1`.
#[system]
#[derive(Clone, Copy, Debug)]
struct Gate {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    open: bool,
    k: f64,
}

#[system]
impl Gate {
    fn acceleration(&self) -> f64 {
        if self.open && self.x > 0.0 || !self.open && self.x < -1.0 {
            -self.k * self.x
        } else {
            -self.v
        }
    }
}

#[test]
fn a_parameter_flag_joins_conditions_on_the_state() {
    for open in [true, false] {
        let model = Gate {
            x: 0.0,
            v: 0.0,
            open,
            k: 7.0,
        };
        check(&model, 0.0, 50, |r| GateState {
            x: [-2.0, -0.5, 1.0][(r.uniform(0.0, 2.999)) as usize] + r.uniform(-0.4, 0.4),
            v: r.uniform(-1.0, 1.0),
        });
        // ∂a/∂x is −k where the spring acts, else 0: at x = 0.5 only when open, at x = −1.5
        // only when closed.
        for (x, acts) in [(0.5, open), (-1.5, !open), (-0.5, false)] {
            let y = GateState { x, v: 0.3 };
            let mut jacobian = model.jacobian_matrix(&y);
            model.jacobian(0.0, &y, &mut jacobian);
            let expected = if acts { -7.0 } else { 0.0 };
            assert_eq!(
                odyn::DenseMatrix::entry(&jacobian, 1, 0),
                expected,
                "open {open}, x {x}"
            );
        }
    }
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

/// `match` and `if let` on the state: the lowering reads them as the `if` chain they mean
/// (`lower/matches.rs`). Ranges, an or-pattern, a constant, a guard of comparisons and a binding
/// as a value; a `match` as a statement changing a local; an `if let` with a range; a
/// parameter's `match` with a guard on the state; a `return` from a `match` among the
/// function's statements.
#[system]
#[derive(Clone, Copy, Debug)]
struct Zones {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
}

/// A constant in a pattern: compared with, not bound.
const EDGE: f64 = 2.5;

#[system]
impl Zones {
    fn acceleration(&self) -> f64 {
        let spring = match self.x {
            ..-1.0 => -self.k * (self.x + 1.0) - 1.0,
            -1.0..0.0 | 0.5..=1.0 => -self.x,
            EDGE => 0.0,
            d if d > 2.0 && self.v < 0.0 => -d * d,
            _ => 0.1 * self.x,
        };
        let mut drag = 0.0;
        match self.v * self.x {
            p @ 1.0.. => drag = -0.3 * p,
            ..=-1.0 => drag = 0.2 * self.v,
            _ => {}
        }
        if let ..0.0 = self.v - 1.5 {
            drag += 0.05 * self.v * self.v;
        } else {
            drag -= 0.01 * self.x;
        }
        // A parameter's `match` with a guard on the state.
        let boost = match self.k as u32 {
            50 if self.v > 0.5 => 0.1 * self.v,
            _ => 0.0,
        };
        match self.x {
            far if far >= 3.5 => return -far * self.v,
            _ => {}
        }
        spring + drag + boost
    }
}

/// [`Zones`] written with `if`s, the same arithmetic.
#[system]
#[derive(Clone, Copy, Debug)]
struct ZonesByIf {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
    k: f64,
}

#[system]
impl ZonesByIf {
    fn acceleration(&self) -> f64 {
        let spring = if self.x < -1.0 {
            -self.k * (self.x + 1.0) - 1.0
        } else if (self.x >= -1.0 && self.x < 0.0) || (self.x >= 0.5 && self.x <= 1.0) {
            -self.x
        } else if self.x == EDGE {
            0.0
        } else if self.x > 2.0 && self.v < 0.0 {
            -self.x * self.x
        } else {
            0.1 * self.x
        };
        let mut drag = 0.0;
        let p = self.v * self.x;
        if p >= 1.0 {
            drag = -0.3 * p;
        } else if p <= -1.0 {
            drag = 0.2 * self.v;
        }
        if self.v - 1.5 < 0.0 {
            drag += 0.05 * self.v * self.v;
        } else {
            drag -= 0.01 * self.x;
        }
        let boost = if self.k as u32 == 50 && self.v > 0.5 {
            0.1 * self.v
        } else {
            0.0
        };
        if self.x >= 3.5 {
            return -self.x * self.v;
        }
        spring + drag + boost
    }
}

#[test]
fn matches_on_the_state_are_differentiated_arm_by_arm() {
    let model = Zones {
        x: 0.0,
        v: 0.0,
        k: 50.0,
    };
    let by_if = ZonesByIf {
        x: 0.0,
        v: 0.0,
        k: 50.0,
    };
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let mut states = Vec::new();
    for _ in 0..400 {
        let y = ZonesState {
            x: rng.uniform(-2.0, 4.0),
            v: rng.uniform(-2.0, 3.0),
        };
        states.push(y);
    }
    // On the switching surfaces too: the arm Rust's comparison takes, in both forms.
    for x in [-1.0, 0.0, 0.5, 1.0, EDGE, 3.5] {
        for v in [-1.0, 0.0, 0.5, 1.5, 2.0] {
            states.push(ZonesState { x, v });
        }
    }
    for y in states {
        let other = ZonesByIfState { x: y.x, v: y.v };
        let (mut a, mut b) = (y, y);
        model.derivative(0.0, &y, &mut a);
        let mut b_if = other;
        by_if.derivative(0.0, &other, &mut b_if);
        b.v = b_if.v;
        assert_eq!(a.v.to_bits(), b.v.to_bits(), "f at {y:?}");
        let mut j = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut j);
        let mut j_if = by_if.jacobian_matrix(&other);
        by_if.jacobian(0.0, &other, &mut j_if);
        assert_eq!(j, j_if, "∂f/∂y at {y:?}");
    }
    // At x = EDGE exactly the constant's arm is taken (∂a/∂x = 0; drag and boost vanish at
    // v = 0); a hair away, the last arm's 0.1.
    for (x, expected) in [(EDGE, 0.0), (EDGE + 1e-9, 0.1)] {
        let y = ZonesState { x, v: 0.0 };
        let mut j = model.jacobian_matrix(&y);
        model.jacobian(0.0, &y, &mut j);
        assert_eq!(odyn::DenseMatrix::entry(&j, 1, 0), expected, "x = {x}");
    }
    // Against central differences away from the switching surfaces (x = −1, 0, ½, 1, 2, 2.5,
    // 3.5; v = 0, ½, 1.5; v·x = ±1).
    let away = |r: &mut Rng| loop {
        let (x, v) = (r.uniform(-2.0, 4.0), r.uniform(-2.0, 3.0));
        let near = |value: f64, surfaces: &[f64]| surfaces.iter().any(|s| (value - s).abs() < 0.05);
        if !near(x, &[-1.0, 0.0, 0.5, 1.0, 2.0, EDGE, 3.5])
            && !near(v, &[0.0, 0.5, 1.5])
            && !near(v * x, &[-1.0, 1.0])
        {
            return ZonesState { x, v };
        }
    };
    check(&model, 0.0, 200, away);
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
