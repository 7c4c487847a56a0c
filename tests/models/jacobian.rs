//! Every generated Jacobian against central finite differences of the model's own derivative,
//! and against hand-derived Jacobians where they are short enough to write down.

use crate::common;

use common::*;
use odyn::prelude::*;
use odyn::{Jacobian, nalgebra};

#[test]
fn spring_matches_finite_differences_and_the_hand_derived_jacobian() {
    let spring = Spring {
        x: 0.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 2.0,
    };
    check(&spring, 0.0, 200, |r| SpringState {
        x: r.uniform(-3.0, 3.0),
        v: r.uniform(-3.0, 3.0),
    });
    // By hand: f = (v, (−k·x − b·v)/m), so J = [[0, 1], [−k/m, −b/m]], at every state.
    let mut j = <Spring as Jacobian>::Matrix::zeros();
    spring.jacobian(0.0, &SpringState { x: 0.3, v: -1.2 }, &mut j);
    assert_eq!(j, nalgebra::Matrix2::new(0.0, 1.0, -50.0 / 2.0, -0.5 / 2.0));
    assert_eq!(Spring::NONZEROS, &[(0, 1), (1, 0), (1, 1)]);
}

#[test]
fn lorenz_matches_finite_differences_and_the_hand_derived_jacobian() {
    let l = Lorenz::classic();
    check(&l, 0.0, 200, |r| LorenzState {
        x: r.uniform(-20.0, 20.0),
        y: r.uniform(-20.0, 20.0),
        z: r.uniform(0.0, 50.0),
    });
    // By hand (Lorenz 1963): J = [[−σ, σ, 0], [ρ − z, −1, −x], [y, x, −β]].
    let s = LorenzState {
        x: 1.5,
        y: -2.0,
        z: 20.0,
    };
    let mut j = <Lorenz as Jacobian>::Matrix::zeros();
    l.jacobian(0.0, &s, &mut j);
    let hand = nalgebra::Matrix3::new(
        -l.sigma,
        l.sigma,
        0.0,
        l.rho - s.z,
        -1.0,
        -s.x,
        s.y,
        s.x,
        -l.beta,
    );
    assert_eq!(j, hand);
    assert_eq!(Lorenz::NONZEROS.len(), 8);
}

#[test]
fn nonlinear_models_match_finite_differences() {
    let pendulum = Pendulum {
        theta: 0.0,
        omega: 0.0,
        g: 9.81,
        length: 0.7,
    };
    check(&pendulum, 0.0, 200, |r| PendulumState {
        theta: r.uniform(-3.0, 3.0),
        omega: r.uniform(-5.0, 5.0),
    });
    let vdp = VanDerPol {
        y1: 0.0,
        y2: 0.0,
        mu: 1000.0,
    };
    check(&vdp, 0.0, 200, |r| VanDerPolState {
        y1: r.uniform(-2.5, 2.5),
        y2: r.uniform(-2.0, 2.0),
    });
    let rob = Robertson::classic();
    check(&rob, 0.0, 200, |r| RobertsonState {
        a: r.uniform(0.0, 1.0),
        b: r.uniform(0.0, 4e-5),
        c: r.uniform(0.0, 1.0),
    });
    let osc = Oscillator {
        x: 0.0,
        v: 0.0,
        omega: 3.0,
    };
    check(&osc, 0.0, 50, |r| OscillatorState {
        x: r.uniform(-1.0, 1.0),
        v: r.uniform(-1.0, 1.0),
    });
}

#[test]
fn vector_models_match_finite_differences() {
    let kepler = Kepler {
        r: Vector2::zeros(),
        v: Vector2::zeros(),
        gm: 1.0,
    };
    check(&kepler, 0.0, 200, |r| {
        let angle = r.uniform(0.0, std::f64::consts::TAU);
        let radius = r.uniform(0.3, 3.0);
        KeplerState {
            r: Vector2::new(radius * angle.cos(), radius * angle.sin()),
            v: Vector2::new(r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0)),
        }
    });
    // Kepler's structure: velocities feed positions; accelerations depend on positions only.
    assert_eq!(
        Kepler::NONZEROS,
        &[(0, 2), (1, 3), (2, 0), (2, 1), (3, 0), (3, 1)]
    );
    let charged = Charged {
        r: Vector3::zeros(),
        v: Vector3::zeros(),
        gm: 2.0,
        qb: Vector3::new(0.1, -0.4, 0.9),
    };
    for t in [0.0, 1.3] {
        check(&charged, t, 100, |r| ChargedState {
            r: Vector3::new(
                r.uniform(0.5, 2.0),
                r.uniform(-2.0, 2.0),
                r.uniform(-2.0, 2.0),
            ),
            v: Vector3::new(
                r.uniform(-1.0, 1.0),
                r.uniform(-1.0, 1.0),
                r.uniform(-1.0, 1.0),
            ),
        });
    }
    // 34 components: the faer-backed Jacobian.
    let bank = Bank {
        x: [0.0; 17],
        v: [0.0; 17],
    };
    check(&bank, 0.0, 10, |r| BankState {
        x: std::array::from_fn(|_| r.uniform(-1.0, 1.0)),
        v: std::array::from_fn(|_| r.uniform(-1.0, 1.0)),
    });
    let pair = Pair {
        a: 0.0,
        b: [0.0; 2],
        va: 0.0,
        vb: [0.0; 2],
        drive: 2.0,
    };
    check(&pair, 0.5, 20, |r| PairState {
        a: r.uniform(-1.0, 1.0),
        b: [r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0)],
        va: r.uniform(-1.0, 1.0),
        vb: [0.1, 0.2],
    });
}
