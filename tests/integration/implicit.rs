//! Implicit Euler: exact energy factors, stiff decay, first-order convergence on stiff problems
//! against independent references, and typed Newton failures.

use crate::common;

use common::{Lorenz, Oscillator, Robertson, Spring, VanDerPol, slope};
use odyn::prelude::*;
use odyn::{DenseMatrix, Error, NewtonFailure, NewtonOptions};

/// On ẍ = −ω²x a step divides (x, v/ω) by 1 − iωh: the energy is multiplied by exactly
/// 1/(1 + ω²h²) (Hairer & Wanner, *Solving ODEs II*, §IV.3, R(z) = 1/(1 − z) at z = iωh).
fn energy_factors(omega: f64, dt: f64, steps: u64) -> (Vec<f64>, f64) {
    let osc = Oscillator {
        x: 1.0,
        v: 0.0,
        omega,
    };
    let run = osc
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(dt)
        .steps(steps)
        .run()
        .unwrap();
    let factors = run
        .samples
        .windows(2)
        .map(|w| w[1].energy.unwrap() / w[0].energy.unwrap())
        .collect();
    (factors, 1.0 / (1.0 + omega * omega * dt * dt))
}

#[test]
fn energy_falls_by_exactly_one_over_one_plus_dt_squared() {
    let (factors, expected) = energy_factors(1.0, 0.05, 400);
    for (n, f) in factors.iter().enumerate() {
        assert!(
            (f / expected - 1.0).abs() < 1e-12,
            "step {}: {f} vs {expected}",
            n + 1
        );
    }
}

/// The stiff spring k = 10⁶, m = 1 at dt = 1/60: ω²h² = 10⁶/3600, so the factor is
/// 1/(1 + 10⁶/3600) = 3600/1003600 = 9/2509 per step.
#[test]
fn the_stiff_spring_loses_all_but_9_2509_of_its_energy_per_step() {
    let (factors, expected) = energy_factors(1000.0, 1.0 / 60.0, 120);
    assert!((expected - 9.0 / 2509.0).abs() < 1e-18);
    for (n, f) in factors.iter().enumerate() {
        assert!(
            (f / (9.0 / 2509.0) - 1.0).abs() < 1e-12,
            "step {}: {f}",
            n + 1
        );
    }
}

#[test]
fn implicit_euler_is_first_order_and_counts_its_work() {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 4.0,
        b: 0.5,
        m: 1.0,
    };
    let exact = odyn::reference::DampedOscillator {
        k: 4.0,
        b: 0.5,
        m: 1.0,
    };
    let errors: Vec<f64> = [0.01, 0.005, 0.0025]
        .iter()
        .map(|&dt| {
            let run = spring
                .simulate()
                .integrator(Method::ImplicitEuler)
                .dt(dt)
                .duration(2.0)
                .run()
                .unwrap();
            let (x, v) = exact.state_at(1.0, 0.0, 2.0);
            (run.last().state.x - x)
                .abs()
                .max((run.last().state.v - v).abs())
        })
        .collect();
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!((order - 1.0).abs() < 0.1, "observed order {order}");
    }
    // A linear model converges in one Newton iteration; the second confirms it.
    let run = spring
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(0.01)
        .steps(100)
        .run()
        .unwrap();
    assert_eq!(
        (run.stats.evaluations, run.stats.jacobian_evaluations),
        (200, 200)
    );
    // First-order models take implicit Euler too.
    let lorenz = Lorenz::classic()
        .simulate()
        .integrator(Method::ImplicitEuler)
        .steps(100)
        .run()
        .unwrap();
    assert!(lorenz.last().state.x.is_finite());
}

/// Robertson kinetics at t = 40. Reference: SciPy 1.17 Radau (rtol 1e-12, atol 1e-14), which BDF
/// confirms to 2.4e-9 (`scripts/reference.py`); it agrees with the classic values of Hairer &
/// Wanner, *Solving ODEs II*, §IV.10 (0.7158270687, 9.185534764e-6, 0.2841637457).
#[test]
fn robertson_error_falls_linearly_with_dt() {
    let reference = [
        7.158270687199023e-01,
        9.185534764554085e-06,
        2.841637457453337e-01,
    ];
    let model = Robertson::classic();
    let points: Vec<(f64, f64)> = [0.04, 0.02, 0.01, 0.005]
        .iter()
        .map(|&dt| {
            let run = model
                .simulate()
                .dt(dt)
                .duration(40.0)
                .record_every(u64::MAX)
                .run()
                .unwrap();
            let s = run.last().state;
            let error = [s.a, s.b, s.c]
                .iter()
                .zip(reference)
                .map(|(y, r)| (y - r).abs())
                .fold(0.0, f64::max);
            (dt, error)
        })
        .collect();
    let order = slope(&points);
    eprintln!("robertson: {points:?}, order {order:.3}");
    assert!((order - 1.0).abs() < 0.1, "observed order {order}");
    // Mass is conserved exactly by the equations, and to round-off by the method.
    let run = model.simulate().dt(0.01).duration(40.0).run().unwrap();
    let s = run.last().state;
    assert!((s.a + s.b + s.c - 1.0).abs() < 1e-12);
}

/// Van der Pol, μ = 1000, from (2, 0) to t = 100: the slow branch of the relaxation oscillation.
/// Reference: SciPy Radau, y(100) = (1.931361320527369, −7.074176282303548e-4), confirmed by BDF
/// to 3.5e-9 (`scripts/reference.py`).
#[test]
fn van_der_pol_error_falls_linearly_with_dt() {
    let reference = [1.931361320527369, -7.074176282303548e-04];
    let model = VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    let points: Vec<(f64, f64)> = [0.4, 0.2, 0.1, 0.05]
        .iter()
        .map(|&dt| {
            let run = model
                .simulate()
                .dt(dt)
                .duration(100.0)
                .record_every(u64::MAX)
                .run()
                .unwrap();
            let s = run.last().state;
            (
                (dt),
                (s.y1 - reference[0]).abs().max((s.y2 - reference[1]).abs()),
            )
        })
        .collect();
    let order = slope(&points);
    eprintln!("van der Pol: {points:?}, order {order:.3}");
    assert!((order - 1.0).abs() < 0.1, "observed order {order}");
}

#[test]
fn newton_failure_is_a_typed_error() {
    let model = VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    // One iteration can never confirm convergence; without halvings the first step fails.
    let strict = NewtonOptions {
        max_iterations: 1,
        max_halvings: 0,
        ..NewtonOptions::default()
    };
    match model.simulate().dt(0.1).steps(10).newton(strict).run() {
        Err(
            error @ Error::NewtonDidNotConverge {
                t,
                dt,
                iters,
                residual,
                cause,
                halvings,
            },
        ) => {
            assert_eq!((t, dt, iters, halvings), (0.1, 0.1, 1, 0));
            assert_eq!(cause, NewtonFailure::Iterations);
            assert!(residual > 0.0 && residual.is_finite());
            // The advice names the option that addresses the cause.
            assert!(
                error
                    .to_string()
                    .contains("raise `NewtonOptions::max_iterations`"),
                "{error}"
            );
        }
        other => panic!("expected NewtonDidNotConverge, got {other:?}"),
    }
    // With halvings it retries down to dt/2³ and reports the failing sub-step's end.
    let halving = NewtonOptions {
        max_iterations: 1,
        max_halvings: 3,
        ..NewtonOptions::default()
    };
    match model.simulate().dt(0.1).steps(10).newton(halving).run() {
        Err(Error::NewtonDidNotConverge {
            t, dt, halvings, ..
        }) => {
            assert!((t - 0.1 / 8.0).abs() < 1e-15, "{t}");
            assert_eq!((dt, halvings), (0.1 / 8.0, 3));
        }
        other => panic!("expected NewtonDidNotConverge, got {other:?}"),
    }
}

/// At the relaxation jump of van der Pol (t ≈ 807) plain Newton from the previous state cannot
/// find the implicit Euler solution at dt = 0.05; halving the failing steps carries the run
/// through, on the same recorded grid.
#[test]
fn halving_carries_newton_through_the_relaxation_jump() {
    let model = VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    let strict = NewtonOptions {
        max_halvings: 0,
        ..NewtonOptions::default()
    };
    let failure = model
        .simulate()
        .dt(0.05)
        .duration(900.0)
        .newton(strict)
        .run()
        .unwrap_err();
    assert!(
        matches!(failure, Error::NewtonDidNotConverge { t, .. } if (800.0..810.0).contains(&t)),
        "{failure}"
    );
    let run = model
        .simulate()
        .dt(0.05)
        .duration(900.0)
        .record_every(100)
        .run()
        .unwrap();
    // 18 000 grid steps; the halved ones add sub-steps, each failed attempt counted as rejected.
    assert_eq!(run.last().step, 18_000);
    let stats = run.stats;
    assert!(stats.rejected > 0, "{stats}");
    assert_eq!(stats.steps, 18_000 + stats.rejected, "{stats}");
    assert!(
        run.samples
            .iter()
            .all(|s| (s.t / 5.0 - (s.t / 5.0).round()).abs() < 1e-9)
    );
    // After the jump the state is on the lower branch of the slow manifold.
    assert!(run.last().state.y1 < -1.0, "{:?}", run.last().state);
}

#[test]
fn a_model_without_jacobian_cannot_take_implicit_euler() {
    let error = common::NoJacobian { x: 1.0, v: 0.0 }
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(0.1)
        .steps(1)
        .run()
        .unwrap_err();
    assert!(
        matches!(
            error,
            Error::Unsupported {
                method: Method::ImplicitEuler,
                ..
            }
        ),
        "{error}"
    );
    // It still runs the explicit methods, and its force may use anything Rust allows.
    let run = common::NoJacobian { x: 1.0, v: 0.0 }
        .simulate()
        .dt(0.1)
        .steps(10)
        .run()
        .unwrap();
    assert!(run.last().state.x < 1.0);
}

/// Past 32 state components the Newton systems are solved by faer's LU: implicit Euler still
/// multiplies each oscillator's energy by exactly 1/(1 + ωᵢ²h²) per step.
#[test]
fn large_models_solve_with_faer_exactly() {
    let bank = common::Bank {
        x: [1.0; 17],
        v: [0.0; 17],
    };
    // The generated Jacobian's matrix is faer-backed (this names its inherent method).
    let mut j = <common::Bank as odyn::Jacobian>::Matrix::zeros(34);
    j.fill_zero();
    assert_eq!(j.dim(), 34);
    let h = 0.01;
    let run = bank
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(h)
        .steps(50)
        .run()
        .unwrap();
    for pair in run.samples.windows(2) {
        for i in 0..17 {
            let omega = (i + 1) as f64;
            let energy =
                |s: &common::BankState| 0.5 * (s.v[i] * s.v[i] + omega * omega * s.x[i] * s.x[i]);
            let factor = energy(&pair[1].state) / energy(&pair[0].state);
            let expected = 1.0 / (1.0 + omega * omega * h * h);
            assert!(
                (factor / expected - 1.0).abs() < 1e-12,
                "oscillator {i}: {factor} vs {expected}"
            );
        }
    }
}
