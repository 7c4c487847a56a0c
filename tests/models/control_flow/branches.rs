//! Branches on the state (`if` as a value and as statements, compound conditions, a local chosen
//! by the state, a parameter flag among the conditions), each arm differentiated on its own.

use crate::common::{Rng, check};
use odyn::prelude::*;

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
