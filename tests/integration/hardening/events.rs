//! Events that misbehave: NaN conditions and changes, bouncing balls at the Zeno time, events
//! that fire without end or at one instant, changes that do not reverse the crossing.

use odyn::RunOptions;
use odyn::prelude::*;

use super::oscillator;
use crate::common::{self, OscillatorState};

/// An event whose condition returns NaN used to be silently never fired (a NaN has no sign);
/// a change that leaves the state NaN used to end in a misleading `StepSizeTooSmall`. Both are
/// now `BadEvent`, naming the event, the time and what was wrong.
#[test]
fn a_nan_event_condition_or_change_is_a_typed_error() {
    let osc = oscillator(1.0);
    // Tsit5 to t = 3 with one event; the error it must stop with.
    let tsit5 = |event: Event<'_, OscillatorState>| {
        osc.simulate()
            .integrator(Method::Tsit5)
            .duration(3.0)
            .event(event)
            .run()
            .unwrap_err()
    };
    // √x is NaN once x < 0, first at t = π/2: the first step ending past it reports.
    let error = tsit5(Event::crossing("root", |_, s: &OscillatorState| s.x.sqrt() - 0.5).record());
    match &error {
        Error::BadEvent { event, t, reason } => {
            assert_eq!(event, "root");
            assert!(*t > std::f64::consts::FRAC_PI_2 && *t < 3.0, "{error}");
            assert!(reason.contains("NaN"), "{error}");
        }
        other => panic!("expected BadEvent, got {other:?}"),
    }
    // NaN at the start is reported before any step, on the fixed-step path too.
    let error = osc
        .simulate()
        .dt(0.1)
        .steps(10)
        .event(Event::crossing("nan", |_, _: &OscillatorState| f64::NAN))
        .run()
        .unwrap_err();
    assert!(
        matches!(&error, Error::BadEvent { t, .. } if *t == 0.0),
        "{error}"
    );

    // NaN only near the crossing at t = π/2, inside a step whose ends are finite: the search
    // for the crossing meets it.
    let error = tsit5(
        Event::crossing("inside", |t, s: &OscillatorState| {
            if (t - std::f64::consts::FRAC_PI_2).abs() < 1e-3 {
                f64::NAN
            } else {
                s.x
            }
        })
        .record(),
    );
    assert!(
        matches!(&error, Error::BadEvent { t, .. } if (t - std::f64::consts::FRAC_PI_2).abs() < 1e-3),
        "{error}"
    );

    // x crosses 0 at t = π/2; the change sets v to NaN there.
    let error = tsit5(
        Event::crossing("zero", |_, s: &OscillatorState| s.x)
            .change(|_, s: &mut OscillatorState| s.v = f64::NAN),
    );
    match &error {
        Error::BadEvent { event, t, reason } => {
            assert_eq!(event, "zero");
            assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-6, "{error}");
            assert!(reason.contains("`v`"), "{error}");
        }
        other => panic!("expected BadEvent, got {other:?}"),
    }
}

/// A ball dropped from H = 10 under g = 9.81, bouncing with restitution `e`: the first impact is
/// at t₁ = √(2H/g) and the bounces accumulate at t∞ = t₁·(1 + e)/(1 − e) (the hops form a
/// geometric series: tₖ₊₁ − tₖ = 2eᵏv₁/g; elementary kinematics).
fn bouncing(e: f64) -> (common::Ball, f64, Event<'static, common::BallState>) {
    let (g, height) = (9.81, 10.0);
    let ball = common::Ball {
        y: height,
        v: 0.0,
        g,
    };
    let t1: f64 = (2.0 * height / g).sqrt();
    let bounce = Event::crossing("bounce", |_, s: &common::BallState| s.y)
        .falling()
        .change(move |_, s: &mut common::BallState| s.v *= -e);
    (ball, t1 * (1.0 + e) / (1.0 - e), bounce)
}

/// Balls used to fall through the floor without a word: restitution 1e-3 under the adaptive
/// methods recorded 4 events and ended at y(3) = −12.08, restitution 0.9 recorded 183 events up
/// to the Zeno time 27.129 and ended at y(40) = −812.6, leapfrog at e = 0.5 and dt = 0.01 ended
/// at y(6) = −14.45. Every hop is now found, however short, and the accumulation of bounces is
/// `EventsAccumulate` at the Zeno time, naming the event and its count; no sample goes below
/// the floor by more than the location tolerance allows.
#[test]
fn bouncing_balls_stop_at_the_zeno_time_instead_of_falling_through() {
    let cases = [
        (1e-3, Method::Tsit5, None, 3.0),
        (1e-3, Method::Dop853, None, 3.0),
        (1e-3, Method::Rodas5P, None, 3.0),
        (0.9, Method::Tsit5, None, 40.0),
        (0.9, Method::Dop853, None, 40.0),
        (0.9, Method::Rodas5P, None, 40.0),
        (0.5, Method::Leapfrog, Some(0.01), 6.0),
        (0.5, Method::Rk4, Some(0.01), 6.0),
    ];
    for (e, method, dt, duration) in cases {
        let (ball, zeno, bounce) = bouncing(e);
        let sim = ball
            .simulate()
            .integrator(method)
            .duration(duration)
            .event(bounce);
        let sim = match dt {
            Some(dt) => sim.dt(dt),
            None => sim.tolerances(1e-10, 1e-12),
        };
        let (run, error) = sim.run_partial().unwrap();
        let lowest = run.samples.iter().map(|s| s.state.y).fold(0.0, f64::min);
        assert!(lowest > -1e-9, "{method} e = {e}: y = {lowest}");
        match error {
            Some(Error::EventsAccumulate {
                event, count, t, ..
            }) => {
                assert_eq!(event, "bounce");
                assert_eq!(count as usize, run.events.len(), "{method} e = {e}");
                assert!(count >= 3, "{method} e = {e}: {count}");
                assert!(
                    (t - zeno).abs() < 1e-6 * zeno,
                    "{method} e = {e}: {t} vs {zeno}"
                );
            }
            other => panic!("{method} e = {e}: expected EventsAccumulate, got {other:?}"),
        }
    }
}

/// A change that flips the state back across its own surface re-triggers at once: it used to
/// fill memory (30 M events in 27 s); it is `EventsAccumulate` now. An event that fires without
/// accumulating ends at the run's `max_events`.
#[test]
fn an_event_that_fires_without_end_is_a_typed_error() {
    let ball = common::Ball {
        y: 1.0,
        v: 0.0,
        g: 9.81,
    };
    let flip = Event::crossing("flip", |_, s: &common::BallState| s.y)
        .change(|_, s: &mut common::BallState| s.y = -s.y);
    let error = ball
        .simulate()
        .integrator(Method::Tsit5)
        .duration(3.0)
        .event(flip)
        .run()
        .unwrap_err();
    assert!(
        matches!(&error, Error::EventsAccumulate { event, .. } if event == "flip"),
        "{error}"
    );
    // An elastic ball bounces every 2√(2/g) = 0.9 s, for ever: 10 events end a 100 s run.
    let bounce = Event::crossing("bounce", |_, s: &common::BallState| s.y)
        .falling()
        .change(|_, s: &mut common::BallState| s.v = -s.v);
    let sim = ball
        .simulate()
        .integrator(Method::Tsit5)
        .duration(100.0)
        .event(bounce)
        .max_events(10);
    let error = sim.run().unwrap_err();
    match &error {
        Error::EventsAccumulate { count, reason, .. } => {
            assert_eq!(*count, 11);
            assert!(reason.contains("`max_events` = 10"), "{error}");
        }
        other => panic!("expected EventsAccumulate, got {other:?}"),
    }
    // `max_events(0)`: no event may fire. The first bounce, at t = √(2·1 m/g) = 0.4515 s (free
    // fall), ends the run with the error, and the partial run keeps the samples before it.
    let (partial, failure) = sim.clone().max_events(0).run_partial().unwrap();
    match &failure {
        Some(Error::EventsAccumulate { count, reason, .. }) => {
            assert_eq!(*count, 1);
            assert!(reason.contains("`max_events` = 0"), "{reason}");
        }
        other => panic!("expected EventsAccumulate, got {other:?}"),
    }
    let first_bounce = (2.0f64 / 9.81).sqrt();
    let end = partial.last().t;
    assert!(
        end > 0.0 && end <= first_bounce + 1e-9,
        "ended at t = {end}"
    );
}

/// A change that does not reverse the crossing (the ball keeps falling, faster) fires once and
/// the run goes on through the surface, as asked.
#[test]
fn a_change_that_does_not_reverse_the_crossing_fires_once() {
    let ball = common::Ball {
        y: 1.0,
        v: 0.0,
        g: 9.81,
    };
    let push = Event::crossing("push", |_, s: &common::BallState| s.y)
        .change(|_, s: &mut common::BallState| s.v *= 2.0);
    for method in [Method::Tsit5, Method::Leapfrog] {
        let sim = ball
            .simulate()
            .integrator(method)
            .duration(2.0)
            .event(push.clone());
        let sim = if method == Method::Leapfrog {
            sim.dt(0.01)
        } else {
            sim
        };
        let run = sim.run().unwrap();
        assert_eq!(run.events.len(), 1, "{method}");
        assert!(run.last().state.y < -5.0, "{method}");
    }
}

/// Two events at one instant used to lose the second when the first changed the state. All the
/// events of an instant fire now, recorded at that instant, their actions applied in the order
/// they were added (bounce then kick: v ↦ −v/2 ↦ −v/2 + 1; kick then bounce: v ↦ v + 1 ↦
/// −(v + 1)/2), and a recording event there is recorded too.
#[test]
fn simultaneous_events_all_fire_in_list_order() {
    let ball = common::Ball {
        y: 1.0,
        v: 0.0,
        g: 9.81,
    };
    let bounce = || {
        Event::crossing("bounce", |_, s: &common::BallState| s.y)
            .falling()
            .change(|_, s: &mut common::BallState| s.v *= -0.5)
    };
    let kick = || {
        Event::crossing("kick", |_, s: &common::BallState| s.y)
            .falling()
            .change(|_, s: &mut common::BallState| s.v += 1.0)
    };
    let touch = || Event::crossing("touch", |_, s: &common::BallState| s.y).record();
    // Impact speed √(2g) at t = √(2/g).
    let v1 = (2.0f64 * 9.81).sqrt();
    let t1 = (2.0f64 / 9.81).sqrt();
    for (first, second, after) in [
        (bounce(), kick(), 0.5 * v1 + 1.0),
        (kick(), bounce(), 0.5 * v1 - 0.5),
    ] {
        let run = ball
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(1e-10, 1e-12)
            .duration(t1 + 0.01)
            .event(first)
            .event(second)
            .event(touch())
            .run()
            .unwrap();
        let names: Vec<&str> = run.events.iter().map(|e| e.name.as_str()).collect();
        assert!(names.len() == 3, "{names:?}");
        assert!(run.events.iter().all(|e| e.t == run.events[0].t));
        assert!((run.events[0].t - t1).abs() < 1e-9);
        // Each record holds the state before and after its own action, in list order.
        assert_eq!(run.events[0].after, run.events[1].before);
        assert!(
            (run.events[2].after.v - after).abs() < 1e-8,
            "{:?}",
            run.events
        );
    }
}

/// Probe of the event options' builders: a NaN, infinite or negative `event_tolerance` is the
/// options' typed error naming it; ±0 asks for the resolution of t. `with_options` replaces the
/// options whole, bad ones included, and they are checked the same way.
#[test]
fn bad_event_options_are_typed_errors() {
    let ball = common::Ball {
        y: 1.0,
        v: 0.0,
        g: 9.81,
    };
    let bounce = || {
        Event::crossing("bounce", |_, s: &common::BallState| s.y)
            .falling()
            .change(|_, s: &mut common::BallState| s.v = -s.v)
    };
    for tolerance in [f64::NAN, f64::INFINITY, -1.0, -1e-300] {
        let error = ball
            .simulate()
            .integrator(Method::Tsit5)
            .duration(1.0)
            .event(bounce())
            .event_tolerance(tolerance)
            .run()
            .unwrap_err();
        assert!(
            matches!(&error, Error::InvalidInput { field, .. } if field == "event_tolerance"),
            "{tolerance:e}: {error}"
        );
    }
    // Free fall from 1 m lands at √(2/g) = 0.4515 s; at ±0 the bounce is located to the
    // resolution of t.
    let landing = (2.0f64 / 9.81).sqrt();
    for tolerance in [0.0, -0.0] {
        let run = ball
            .simulate()
            .integrator(Method::Tsit5)
            .duration(0.6)
            .event(bounce())
            .event_tolerance(tolerance)
            .run()
            .unwrap();
        assert_eq!(run.events.len(), 1, "{tolerance:e}");
        assert!(
            (run.events[0].t - landing).abs() < 1e-6,
            "{}",
            run.events[0].t
        );
    }
    let options = RunOptions {
        event_tolerance: f64::NAN,
        ..ball.simulate().integrator(Method::Tsit5).options().clone()
    };
    let error = ball
        .simulate()
        .with_options(options)
        .duration(1.0)
        .event(bounce())
        .run()
        .unwrap_err();
    assert!(
        matches!(&error, Error::InvalidInput { field, .. } if field == "event_tolerance"),
        "{error}"
    );
}
