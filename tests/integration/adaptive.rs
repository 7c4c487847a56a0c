//! Adaptive stepping, dense output and events: Tsit5 and DOP853 reach their orders at a fixed
//! step, their interpolants theirs, the controller meets the tolerance, events land on the closed
//! form, and every way an adaptive run can fail is a typed error.

use crate::common;

use common::{Kepler, KeplerState, Robertson, Spring, SpringState, slope};
use odyn::prelude::*;
use odyn::reference::{DampedOscillator, KeplerOrbit};
use odyn::{AdaptiveOptions, Error, Stepping};

fn damped() -> (Spring, DampedOscillator) {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 4.0,
        b: 0.5,
        m: 1.0,
    };
    let exact = DampedOscillator {
        k: 4.0,
        b: 0.5,
        m: 1.0,
    };
    (spring, exact)
}

/// GM = 1, a = 1, eccentricity `e`, from pericentre (1 − e, 0) at the vis-viva speed.
fn kepler_with(e: f64) -> (Kepler, KeplerOrbit) {
    let model = Kepler {
        r: Vector2::new(1.0 - e, 0.0),
        v: Vector2::new(0.0, ((1.0 + e) / (1.0 - e)).sqrt()),
        gm: 1.0,
    };
    (model, KeplerOrbit { gm: 1.0, a: 1.0, e })
}

fn kepler() -> (Kepler, KeplerOrbit) {
    kepler_with(0.5)
}

fn kepler_error(state: &KeplerState, orbit: &KeplerOrbit, t: f64) -> f64 {
    let ([x, y], [vx, vy]) = orbit.state_at(t);
    [state.r.x - x, state.r.y - y, state.v.x - vx, state.v.y - vy]
        .iter()
        .fold(0.0, |m: f64, e| m.max(e.abs()))
}

/// At a fixed step the global error falls as dt⁵ for Tsit5 and dt⁸ for DOP853 (Tsitouras 2011;
/// Hairer, Nørsett & Wanner §II.5), ±0.3. One Kepler orbit with e = 0.2 (exact by Kepler's
/// equation): smooth enough for the asymptotic rate at coarse steps, whose errors stay well above
/// round-off.
#[test]
fn fixed_step_orders_are_five_and_eight() {
    let (model, orbit) = kepler_with(0.2);
    let period = orbit.period();
    for (method, steps, order) in [
        (Method::Tsit5, [50.0, 71.0, 100.0, 141.0, 200.0], 5.0),
        (Method::Dop853, [40.0, 50.0, 63.0, 80.0, 100.0], 8.0),
    ] {
        let points: Vec<(f64, f64)> = steps
            .iter()
            .map(|&n| {
                let dt = period / n;
                let run = model
                    .simulate()
                    .integrator(method)
                    .dt(dt)
                    .steps(n as u64)
                    .record_every(u64::MAX)
                    .run()
                    .unwrap();
                (dt, kepler_error(&run.last().state, &orbit, run.last().t))
            })
            .collect();
        let observed = slope(&points);
        eprintln!("{method}: order {observed:.3} from {points:?}");
        assert!((observed - order).abs() <= 0.3, "{method}: {observed}");
    }
}

/// The dense output of one step from the exact state: its error inside the step (the worst of
/// θ = ¼, ½, ¾) is a local error of
/// order q + 1 for an interpolant of order q — 5 for Tsit5's (q = 4), 8 for DOP853's (q = 7), 4
/// for the cubic Hermite interpolant fixed-step methods get (q = 3; HNW §II.6). ±0.3.
#[test]
fn dense_output_has_the_interpolants_order() {
    let (model, orbit) = kepler();
    for (method, hs, order) in [
        (Method::Tsit5, [0.2, 0.1, 0.05, 0.025], 5.0),
        (Method::Dop853, [0.2, 0.14, 0.1, 0.07], 8.0),
        (Method::Rk4, [0.2, 0.1, 0.05, 0.025], 4.0),
    ] {
        let points: Vec<(f64, f64)> = hs
            .iter()
            .map(|&h| {
                // Start near pericentre (t = 0.1), where the orbit curves most.
                let ([x, y], [vx, vy]) = orbit.state_at(0.1);
                let start = KeplerState {
                    r: Vector2::new(x, y),
                    v: Vector2::new(vx, vy),
                };
                let run = model
                    .simulate()
                    .integrator(method)
                    .initial_state(start)
                    .start_time(0.1)
                    .dt(h)
                    .steps(1)
                    .dense_output(true)
                    .run()
                    .unwrap();
                let worst = [0.25, 0.5, 0.75]
                    .iter()
                    .map(|theta| {
                        let t = 0.1 + theta * h;
                        kepler_error(&run.at(t).unwrap(), &orbit, t)
                    })
                    .fold(0.0, f64::max);
                (h, worst)
            })
            .collect();
        let observed = slope(&points);
        eprintln!("{method} interpolant: order {observed:.3} from {points:?}");
        assert!((observed - order).abs() <= 0.3, "{method}: {observed}");
    }
}

/// At tolerance 1e-8 both methods hold the global error of the damped spring near the tolerance,
/// end exactly at the requested time, report their statistics, and `at(t)` agrees with the exact
/// solution between steps as well as at them.
#[test]
fn adaptive_runs_meet_the_tolerance_and_end_on_time() {
    let (spring, exact) = damped();
    for method in [Method::Tsit5, Method::Dop853] {
        let run = spring
            .simulate()
            .integrator(method)
            .tolerances(1e-8, 1e-10)
            .duration(10.0)
            .run()
            .unwrap();
        assert_eq!(run.last().t, 10.0, "{method}");
        assert_eq!(run.stepping.dt(), None);
        let stats = run.stats;
        assert!(stats.steps > 10 && stats.steps < 2000, "{method}: {stats}");
        assert_eq!(run.samples.len() as u64, stats.steps + 1, "{method}");
        let mut worst: f64 = 0.0;
        for k in 0..=1000 {
            let t = 0.01 * f64::from(k);
            let s = run.at(t).unwrap();
            let (x, v) = exact.state_at(1.0, 0.0, t);
            worst = worst.max((s.x - x).abs()).max((s.v - v).abs());
        }
        eprintln!("{method}: {stats}, worst dense-output error {worst:.2e}");
        assert!(worst < 1e-6, "{method}: {worst}");
        assert!(run.at(10.5).is_err() && run.at(f64::NAN).is_err());
    }
}

/// `save_at` records exactly the requested times (plus the end), through the dense output.
#[test]
fn save_at_records_the_requested_times() {
    let (spring, exact) = damped();
    let times: Vec<f64> = (0..=20).map(|k| 0.5 * f64::from(k)).collect();
    let run = spring
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-10, 1e-12)
        .duration(9.75)
        .save_at(&times)
        .run()
        .unwrap();
    let recorded: Vec<f64> = run.times().collect();
    let mut expected: Vec<f64> = times.iter().copied().filter(|&t| t <= 9.75).collect();
    expected.push(9.75);
    assert_eq!(recorded, expected);
    for s in &run.samples {
        let (x, _) = exact.state_at(1.0, 0.0, s.t);
        assert!((s.state.x - x).abs() < 1e-8, "t = {}", s.t);
    }
    // A run that records only where asked keeps no interpolants (a big model's memory) unless
    // asked; one that records every step keeps them.
    assert!(run.dense.is_none() && run.at(1.1).is_err());
    let every = spring.simulate().integrator(Method::Dop853).duration(1.0);
    assert!(every.clone().run().unwrap().dense.is_some());
    assert!(
        every
            .clone()
            .record_every(10)
            .run()
            .unwrap()
            .dense
            .is_none()
    );
    let kept = every.save_at(&times).dense_output(true).run().unwrap();
    assert!(kept.at(0.3).is_ok());
    // Fixed-step runs can save at chosen times too (cubic Hermite between grid points).
    let run = spring
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.01)
        .duration(2.0)
        .save_at(&[0.333, 1.777])
        .run()
        .unwrap();
    assert_eq!(
        run.times().collect::<Vec<_>>(),
        vec![0.0, 0.333, 1.777, 2.0]
    );
}

/// A falling ball: y″ = −g, bouncing with restitution e. From height H at rest, the first impact
/// is at t₁ = √(2H/g) with speed v₁ = g·t₁; the k-th bounce leaves at vₖ₊₁ = eᵏ·v₁ and lands
/// 2vₖ₊₁/g later, so tₖ₊₁ = tₖ + 2·eᵏ·v₁/g (elementary kinematics). Tsit5 and DOP853 at rtol 1e-10 hit every
/// time to 1e-9 relative; every event is recorded with its state before and after.
#[test]
fn bounces_land_on_the_closed_form() {
    let (g, e, height): (f64, f64, f64) = (9.81, 0.8, 10.0);
    let ball = common::Ball {
        y: height,
        v: 0.0,
        g,
    };
    let t1 = (2.0 * height / g).sqrt();
    let v1 = g * t1;
    let exact: Vec<f64> = (0..10)
        .scan(t1, |t, k| {
            let now = *t;
            *t += 2.0 * e.powi(k + 1) * v1 / g;
            Some(now)
        })
        .collect();
    for method in [Method::Tsit5, Method::Dop853] {
        let bounce = Event::crossing("ground", |_, s: &common::BallState| s.y)
            .falling()
            .change(move |_, s: &mut common::BallState| s.v *= -e);
        let run = ball
            .simulate()
            .integrator(method)
            .tolerances(1e-10, 1e-12)
            .duration(exact[9] + 0.01)
            .event(bounce)
            .run()
            .unwrap();
        assert_eq!(run.events.len(), 10, "{method}");
        for (k, (record, t)) in run.events.iter().zip(&exact).enumerate() {
            assert!(
                ((record.t - t) / t).abs() < 1e-9,
                "{method} bounce {k}: {} vs {t}",
                record.t
            );
            assert_eq!(record.name, "ground");
            assert!(record.before.v < 0.0 && record.after.v > 0.0);
            assert!((record.after.v + e * record.before.v).abs() < 1e-12);
        }
        // The discontinuity shows in the samples: two samples at each bounce time.
        let at_first: Vec<_> = run
            .samples
            .iter()
            .filter(|s| s.t == run.events[0].t)
            .collect();
        assert_eq!(at_first.len(), 2, "{method}");
    }
}

/// Fixed-step methods locate events on the cubic Hermite interpolant: the first impact time's
/// error falls with dt at least as the interpolant's order 3 (the exact solution is a quadratic,
/// so every method's own error, not the interpolant's, sets it).
#[test]
fn fixed_step_methods_locate_events_too() {
    let (g, height) = (9.81, 10.0);
    let ball = common::Ball {
        y: height,
        v: 0.0,
        g,
    };
    let t1 = (2.0 * height / g).sqrt();
    for method in [
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Rk4,
        Method::ImplicitEuler,
        Method::Tsit5,
    ] {
        let errors: Vec<(f64, f64)> = [0.01, 0.005, 0.0025]
            .iter()
            .map(|&dt| {
                let stop = Event::crossing("ground", |_, s: &common::BallState| s.y).falling();
                let run = ball
                    .simulate()
                    .integrator(method)
                    .dt(dt)
                    .duration(5.0)
                    .event(stop)
                    .run()
                    .unwrap();
                assert_eq!(run.events.len(), 1);
                assert_eq!(run.last().t, run.events[0].t, "a stop ends the run there");
                (dt, (run.events[0].t - t1).abs().max(1e-15))
            })
            .collect();
        let worst = errors.iter().map(|e| e.1).fold(0.0, f64::max);
        eprintln!("{method}: impact-time errors {errors:?}");
        assert!(worst < 0.02, "{method}: {errors:?}");
        if errors[2].1 > 1e-13 {
            let order = slope(&errors);
            assert!(order > 0.8, "{method}: {order}");
        }
    }
}

/// Several events in one step are taken in time order; a recording event does not cut the step;
/// time events land on their times exactly; a stop ends the run there.
#[test]
fn events_are_handled_in_time_order() {
    let (g, height) = (9.81, 10.0);
    let ball = common::Ball {
        y: height,
        v: 0.0,
        g,
    };
    // With one large step, both crossings (y = 8 then y = 5) fall in the same step.
    let control = AdaptiveOptions {
        dt_initial: Some(1.4),
        dt_max: 1.4,
        ..AdaptiveOptions::default()
    };
    let run = ball
        .simulate()
        .integrator(Method::Tsit5)
        .tolerances(1e-3, 1e-3)
        .adaptive(control)
        .duration(1.35)
        .event(Event::crossing("five", |_, s: &common::BallState| s.y - 5.0).record())
        .event(Event::crossing("eight", |_, s: &common::BallState| s.y - 8.0).record())
        .event(Event::at_times("ticks", vec![0.25, 0.5, 1.0]))
        .run()
        .unwrap();
    let names: Vec<&str> = run.events.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["ticks", "ticks", "eight", "ticks", "five"]);
    // y = H − g t²/2: exact crossing times.
    let cross = |y: f64| (2.0 * (height - y) / g).sqrt();
    assert!((run.events[2].t - cross(8.0)).abs() < 1e-9);
    assert!((run.events[4].t - cross(5.0)).abs() < 1e-9);
    assert_eq!(run.events[0].t, 0.25);
    assert_eq!(run.events[3].t, 1.0);
    // A time event that stops: the run ends exactly there.
    let run = ball
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.1)
        .duration(5.0)
        .event(Event::at_times("halt", vec![0.333]).stop())
        .run()
        .unwrap();
    assert_eq!(run.last().t, 0.333);
    assert!((run.last().state.y - (height - 0.5 * g * 0.333 * 0.333)).abs() < 1e-12);
}

/// After a bounce the state sits on g = 0; the event must not fire again at once, even when it
/// counts crossings either way.
#[test]
fn a_reset_does_not_retrigger() {
    let ball = common::Ball {
        y: 1.0,
        v: 0.0,
        g: 9.81,
    };
    let bounce = Event::crossing("ground", |_, s: &common::BallState| s.y)
        .change(|_, s: &mut common::BallState| s.v *= -0.5);
    let run = ball
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-10, 1e-12)
        .duration(1.0)
        .event(bounce)
        .run()
        .unwrap();
    // First impact at √(2/9.81) = 0.4515 s, the next 2·0.5·4.43/9.81 = 0.4515 s later (0.903 s).
    assert_eq!(run.events.len(), 2, "{:?}", run.events);
    assert!(matches!(run.events[0].name.as_str(), "ground"));
    assert!(run.events[1].t - run.events[0].t > 0.4);
}

/// A stiff problem under an explicit adaptive method stops with a typed error instead of
/// running for hours: Robertson to t = 1e5 needs ~1e8 Tsit5 steps (its stability limit is
/// 3.5/|λ| with |λ| ≈ 1e4).
#[test]
fn a_stiff_problem_under_tsit5_hits_the_step_budget() {
    let model = Robertson::classic();
    let control = AdaptiveOptions {
        max_steps: 20_000,
        ..AdaptiveOptions::default()
    };
    let error = model
        .simulate()
        .integrator(Method::Tsit5)
        .tolerances(1e-6, 1e-10)
        .adaptive(control)
        .duration(1e5)
        .run()
        .unwrap_err();
    assert!(
        matches!(error, Error::MaxSteps { steps: 20_000, t, .. } if t > 0.0 && t < 1e5),
        "{error}"
    );
    assert!(error.to_string().contains("stiff"), "{error}");
    // dt_min turns the same collapse into StepSizeTooSmall.
    let control = AdaptiveOptions {
        dt_min: 1e-3,
        ..AdaptiveOptions::default()
    };
    let error = model
        .simulate()
        .integrator(Method::Dop853)
        .adaptive(control)
        .duration(1e5)
        .run()
        .unwrap_err();
    assert!(matches!(error, Error::StepSizeTooSmall { .. }), "{error}");
}

#[test]
fn bad_tolerances_and_step_options_are_typed_errors() {
    let (spring, _) = damped();
    let field = |result: odyn::Result<Trajectory<SpringState>>| match result {
        Err(Error::InvalidInput { field, .. }) => field,
        other => panic!("expected InvalidInput, got {other:?}"),
    };
    let sim = || spring.simulate().integrator(Method::Tsit5).duration(1.0);
    assert_eq!(field(sim().tolerances(0.0, 0.0).run()), "tolerances");
    assert_eq!(field(sim().tolerances(f64::NAN, 1e-9).run()), "rtol");
    assert_eq!(field(sim().tolerances(-1e-6, 1e-9).run()), "rtol");
    assert_eq!(field(sim().tolerances(1e-6, -1.0).run()), "atol[0]");
    assert_eq!(
        field(
            sim()
                .with_tolerances(Tolerances::per_component(1e-6, vec![1e-9]))
                .run()
        ),
        "atol"
    );
    let control = |c: AdaptiveOptions| sim().adaptive(c).run();
    assert_eq!(
        field(control(AdaptiveOptions {
            dt_initial: Some(0.0),
            ..AdaptiveOptions::default()
        })),
        "dt_initial"
    );
    assert_eq!(
        field(control(AdaptiveOptions {
            max_steps: 0,
            ..AdaptiveOptions::default()
        })),
        "max_steps"
    );
    assert_eq!(
        field(control(AdaptiveOptions {
            dt_max: f64::NAN,
            ..AdaptiveOptions::default()
        })),
        "dt_max"
    );
    // A fixed-step method has no error estimate to hold to a tolerance.
    assert!(matches!(
        spring
            .simulate()
            .integrator(Method::Rk4)
            .tolerances(1e-6, 1e-9)
            .duration(1.0)
            .run(),
        Err(Error::Unsupported { .. })
    ));
    // An adaptive run takes a duration, not a step count.
    assert_eq!(field(sim().steps(10).run()), "length");
    assert_eq!(field(sim().save_at(&[0.5, 0.2]).run()), "save_at");
}

/// Choosing an adaptive method drops the attribute's dt (the model was declared for symplectic
/// Euler at 0.016), but an explicit `.dt(..)` keeps it fixed.
#[test]
fn adaptive_methods_step_to_tolerances_unless_given_a_dt() {
    let (spring, _) = damped();
    let adaptive = spring
        .simulate()
        .integrator(Method::Tsit5)
        .duration(1.0)
        .run()
        .unwrap();
    assert_eq!(adaptive.stepping, Stepping::Adaptive(Tolerances::default()));
    let fixed = spring
        .simulate()
        .dt(0.1)
        .integrator(Method::Tsit5)
        .duration(1.0)
        .run()
        .unwrap();
    assert_eq!(
        (&fixed.stepping, fixed.steps()),
        (&Stepping::Fixed(0.1), 10)
    );
}

/// Every action of an event: a stop's record has equal before and after states.
#[test]
fn event_records_carry_the_state() {
    let ball = common::Ball {
        y: 2.0,
        v: 0.0,
        g: 9.81,
    };
    let run = ball
        .simulate()
        .integrator(Method::Tsit5)
        .duration(5.0)
        .event(Event::crossing("ground", |_, s: &common::BallState| s.y).stop())
        .run()
        .unwrap();
    let record = &run.events[0];
    assert_eq!(record.before, record.after);
    assert!(record.before.y.abs() < 1e-9);
}

/// Saved samples are found by time without an exact float comparison (0.1·3 is not 0.3), and a
/// time that was not recorded is a typed error naming the nearest sample.
#[test]
fn saved_samples_are_found_by_time() {
    let (spring, exact) = damped();
    let times: Vec<f64> = (1..=9).map(|k| k as f64 / 10.0).collect();
    let run = spring
        .simulate()
        .integrator(Method::Tsit5)
        .tolerances(1e-10, 1e-12)
        .duration(1.0)
        .save_at(&times)
        .run()
        .unwrap();
    let sample = run.sample_at(0.1 * 3.0).unwrap();
    assert_eq!(sample.t, 0.3);
    assert!((sample.state.x - exact.state_at(1.0, 0.0, 0.3).0).abs() < 1e-8);
    match run.sample_at(0.35) {
        Err(Error::InvalidInput { reason, .. }) => assert!(reason.contains("0.3"), "{reason}"),
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}
