//! The Rosenbrock methods: their orders at a fixed step (which needs the exact ∂f/∂t the macro
//! generates), their accuracy against tolerance on Robertson's kinetics, conservation, L-stable
//! damping, and typed errors for a singular W.

use crate::common;

use common::{Kepler, KeplerState, Oscillator, Robertson, slope};
use odyn::prelude::*;
use odyn::reference::KeplerOrbit;
use odyn::{AdaptiveOptions, NewtonOptions};

/// A forced oscillator, ẍ = −x + cos 2t: linear, but it reads the time. From x = 1, ẋ = 0 its
/// solution is x = (4/3)cos t − (1/3)cos 2t (undetermined coefficients: the particular solution
/// −(1/3)cos 2t, plus the homogeneous one that meets the initial conditions).
#[system]
#[derive(Clone, Copy, Debug)]
struct Driven {
    #[position]
    x: f64,
    #[velocity]
    v: f64,
}

#[system]
impl Driven {
    fn acceleration(&self, t: f64) -> f64 {
        -self.x + (2.0 * t).cos()
    }
}

fn driven_exact(t: f64) -> (f64, f64) {
    (
        4.0 / 3.0 * t.cos() - (2.0 * t).cos() / 3.0,
        -4.0 / 3.0 * t.sin() + 2.0 / 3.0 * (2.0 * t).sin(),
    )
}

/// Fixed-step orders, ±0.3: Rodas5P 5 and Rosenbrock23 2, on the driven oscillator (to t = 5)
/// and on a Kepler orbit (nonlinear; one period, e = 0.2). Without the ∂f/∂t terms Rodas5P falls
/// to order 2 on the driven oscillator (Steinebach 2023; measured in scripts/check_rosenbrock.py).
#[test]
fn fixed_step_orders_are_five_and_two() {
    let driven = Driven { x: 1.0, v: 0.0 };
    let e = 0.2;
    let kepler = Kepler {
        r: Vector2::new(1.0 - e, 0.0),
        v: Vector2::new(0.0, ((1.0 + e) / (1.0 - e)).sqrt()),
        gm: 1.0,
    };
    let orbit = KeplerOrbit { gm: 1.0, a: 1.0, e };
    for (method, order, steps) in [
        (Method::Rodas5P, 5.0, [25.0, 35.0, 50.0, 71.0, 100.0]),
        (
            Method::Rosenbrock23,
            2.0,
            [200.0, 283.0, 400.0, 566.0, 800.0],
        ),
    ] {
        let points: Vec<(f64, f64)> = steps
            .iter()
            .map(|&n| {
                let dt = 5.0 / n;
                let run = driven
                    .simulate()
                    .integrator(method)
                    .dt(dt)
                    .steps(n as u64)
                    .record_every(u64::MAX)
                    .run()
                    .unwrap();
                let (x, v) = driven_exact(run.last().t);
                let s = run.last().state;
                (dt, (s.x - x).abs().max((s.v - v).abs()))
            })
            .collect();
        let observed = slope(&points);
        eprintln!("{method} on the driven oscillator: order {observed:.3} from {points:?}");
        assert!((observed - order).abs() <= 0.3, "{method}: {observed}");
        let points: Vec<(f64, f64)> = steps
            .iter()
            .map(|&n| {
                let dt = orbit.period() / n / 2.0;
                let run = kepler
                    .simulate()
                    .integrator(method)
                    .dt(dt)
                    .steps(2 * n as u64)
                    .record_every(u64::MAX)
                    .run()
                    .unwrap();
                let ([x, y], [vx, vy]) = orbit.state_at(run.last().t);
                let s: KeplerState = run.last().state;
                let error = [s.r.x - x, s.r.y - y, s.v.x - vx, s.v.y - vy]
                    .iter()
                    .fold(0.0f64, |m, e| m.max(e.abs()));
                (dt, error)
            })
            .collect();
        let observed = slope(&points);
        eprintln!("{method} on Kepler: order {observed:.3} from {points:?}");
        assert!((observed - order).abs() <= 0.3, "{method}: {observed}");
    }
}

/// Robertson's kinetics to t = 1e5 against the 36-digit Radau IIA reference of
/// scripts/reference_stiff.py (its value agrees with the Bari test set's to 2e-14): the relative
/// error falls with the tolerance (Rodas5P within 20× rtol over rtol = 1e-4 … 1e-10), and
/// y₁ + y₂ + y₃ = 1 holds to 1e-12 — the Rosenbrock stages conserve linear invariants exactly.
#[test]
fn robertson_meets_the_tolerance_and_conserves_mass() {
    let reference = [
        1.786_592_114_209_946_4e-2,
        7.274_751_468_436_319e-8,
        9.821_340_061_103_858e-1,
    ];
    let model = Robertson::classic();
    let mut points = Vec::new();
    for k in [4, 6, 8, 10] {
        let rtol = 10f64.powi(-k);
        let run = model
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(rtol, rtol * 1e-6)
            .duration(1e5)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        let s = run.last().state;
        let error = [s.a, s.b, s.c]
            .iter()
            .zip(reference)
            .fold(0.0f64, |m, (x, r)| m.max(((x - r) / r).abs()));
        eprintln!(
            "Rodas5P rtol {rtol:e}: {}, relative error {error:.2e}",
            run.stats
        );
        assert!(error < 20.0 * rtol, "rtol {rtol}: {error}");
        assert!((s.a + s.b + s.c - 1.0).abs() < 1e-12);
        points.push((rtol, error));
    }
    let proportionality = slope(&points);
    assert!((0.6..=1.3).contains(&proportionality), "{proportionality}");
    let run = model
        .simulate()
        .integrator(Method::Rosenbrock23)
        .tolerances(1e-4, 1e-10)
        .duration(1e5)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    let s = run.last().state;
    assert!((s.a + s.b + s.c - 1.0).abs() < 1e-12);
    // Order 2 at rtol 1e-4: a few 1e-4 relative.
    let error = ((s.a - reference[0]) / reference[0]).abs();
    assert!(error < 1e-2, "{error}");
}

/// L-stability, R(∞) = 0: an oscillator a million times stiffer than the step (ω·dt = 1e4) is
/// damped to nothing in a few steps, where the A-stable but not L-stable trapezoidal rule would
/// keep |R| = 1.
#[test]
fn stiff_modes_are_damped_at_any_step() {
    let stiff = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 1e6,
    };
    for method in [Method::Rodas5P, Method::Rosenbrock23] {
        let run = stiff
            .simulate()
            .integrator(method)
            .dt(0.01)
            .steps(5)
            .run()
            .unwrap();
        let ratio = run.energy_ratio().unwrap();
        eprintln!("{method}: E/E0 after 5 steps at ω·dt = 1e4: {ratio:.2e}");
        assert!(ratio < 1e-10, "{method}: {ratio}");
    }
}

/// y′ = λy with γh·λ = 1 makes W = I − γh·J exactly singular. With no halving allowed the
/// fixed-step run fails with the typed `SingularMatrix` error; the adaptive run retries a
/// smaller step and goes on.
#[test]
fn a_singular_matrix_is_a_typed_error() {
    #[system]
    #[derive(Clone, Copy, Debug)]
    struct Growth {
        #[state]
        y: f64,
        rate: f64,
    }
    #[system]
    impl Growth {
        fn derivative(&self) -> GrowthState {
            GrowthState {
                y: self.rate * self.y,
            }
        }
    }
    // Rosenbrock23: W = I − h·d·J with d = 1/(2 + √2); h = 0.5, rate = 1/(h·d).
    let d = 1.0 / (2.0 + std::f64::consts::SQRT_2);
    let model = Growth {
        y: 1.0,
        rate: 1.0 / (0.5 * d),
    };
    let strict = NewtonOptions {
        max_halvings: 0,
        ..NewtonOptions::default()
    };
    let error = model
        .simulate()
        .integrator(Method::Rosenbrock23)
        .dt(0.5)
        .steps(1)
        .newton(strict)
        .run()
        .unwrap_err();
    assert!(
        matches!(error, Error::SingularMatrix { t: 0.0, dt: 0.5 }),
        "{error}"
    );
    let control = AdaptiveOptions {
        dt_initial: Some(0.5),
        ..AdaptiveOptions::default()
    };
    let run = model
        .simulate()
        .integrator(Method::Rosenbrock23)
        .adaptive(control)
        .duration(0.01)
        .run()
        .unwrap();
    assert!(run.stats.rejected >= 1);
}

/// Reuse across a rejected step: J and ∂f/∂t are evaluated once per accepted step (plus once at
/// the start of each retried state, never again for the retry), factorizations once per attempt.
#[test]
fn a_rejected_step_keeps_its_jacobian() {
    let model = Robertson::classic();
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-6, 1e-12)
        .duration(1e5)
        .run()
        .unwrap();
    let s = run.stats;
    eprintln!("{s}");
    assert!(s.rejected > 0, "{s}");
    assert_eq!(s.jacobian_evaluations, s.steps, "{s}");
    assert_eq!(s.factorizations, s.steps + s.rejected, "{s}");
    assert_eq!(s.linear_solves, 8 * (s.steps + s.rejected), "{s}");
    // Robertson does not read the time: no ∂f/∂t at all.
    assert_eq!(s.time_derivative_evaluations, 0);
}

/// Step counts against a reference implementation of the same methods: the plain-Python
/// Rodas5P and Rosenbrock23 of scripts/check_rosenbrock.py (written from the papers' formulas,
/// apart from this crate), on Robertson to t = 1e5 at rtol 1e-6, atol 1e-10, under the same
/// controller — integral, safety 0.9, factors in [0.2, 6], exponent 1/(q+1), no growth after a
/// rejection — from h₀ = 1e-6. Its counts: Rodas5P 99 accepted / 2 rejected, Rosenbrock23 663 /
/// 0. (odyn may take one step fewer: it stretches a step by up to 1 % to land on the end.)
#[test]
fn step_counts_match_the_reference_implementation() {
    let model = Robertson::classic();
    for (method, q, accepted, rejected) in [
        (Method::Rodas5P, 4, 99, 2),
        (Method::Rosenbrock23, 2, 663, 0),
    ] {
        let control = AdaptiveOptions {
            dt_initial: Some(1e-6),
            controller: Some(odyn::Controller {
                alpha: 1.0 / f64::from(q + 1),
                beta: 0.0,
                safety: 0.9,
                min_factor: 0.2,
                max_factor: 6.0,
            }),
            ..AdaptiveOptions::default()
        };
        let run = model
            .simulate()
            .integrator(method)
            .tolerances(1e-6, 1e-10)
            .adaptive(control)
            .duration(1e5)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        let s = run.stats;
        eprintln!("{method}: {s} (reference {accepted} / {rejected})");
        assert!(s.steps.abs_diff(accepted) <= 1, "{method}: {s}");
        assert_eq!(s.rejected, rejected, "{method}: {s}");
    }
}
