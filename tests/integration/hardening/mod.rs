//! Inputs that once crashed, hung, or returned a wrong number without an error: each is now a
//! typed error or a correct result. One test per failure mode found by bad-input probing.

mod implicit;

use crate::common;

use std::path::PathBuf;

use common::{Oscillator, OscillatorState, Spring};
use odyn::integrators::{ImplicitEuler, SymplecticEuler};
use odyn::plot::{Chart, Series, View, views};
use odyn::prelude::*;
use odyn::stability::{StabilityProbe, measured_limit};
use odyn::{AdaptiveOptions, FixedTimestep, NewtonOptions, Stepper};

/// ẍ = −ω²x from (1, 0).
fn oscillator(omega: f64) -> Oscillator {
    Oscillator {
        x: 1.0,
        v: 0.0,
        omega,
    }
}

fn invalid_field<T: std::fmt::Debug>(result: odyn::Result<T>) -> String {
    match result {
        Err(Error::InvalidInput { field, .. }) => field,
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

/// A file in a directory of its own per test (tests run in parallel in one process, and one
/// test lists its directory for leftover temporaries).
fn scratch(test: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("odyn-hardening-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// `steps(u64::MAX)` on a model that diverges used to overflow the step counter; now it stops
/// at the divergence with a typed error naming the step.
#[test]
fn a_huge_step_count_stops_at_the_divergence() {
    let osc = oscillator(10.0);
    let error = osc
        .simulate()
        .integrator(Method::SymplecticEuler)
        .dt(0.25)
        .steps(u64::MAX)
        .run()
        .unwrap_err();
    assert!(
        matches!(error, Error::Diverged { step, .. } if step < 100),
        "{error}"
    );
}

/// Newton options are checked up front: a NaN or non-positive tolerance, no iterations, or more
/// halvings than the resolution of t allows (`u32::MAX` once recursed until the stack overflowed).
#[test]
fn newton_options_are_validated() {
    let model = common::VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    let run = |newton| model.simulate().dt(0.1).steps(5).newton(newton).run();
    for (newton, field) in [
        (
            NewtonOptions {
                tol: f64::NAN,
                ..NewtonOptions::default()
            },
            "NewtonOptions::tol",
        ),
        (
            NewtonOptions {
                tol: 0.0,
                ..NewtonOptions::default()
            },
            "NewtonOptions::tol",
        ),
        (
            NewtonOptions {
                max_iters: 0,
                ..NewtonOptions::default()
            },
            "NewtonOptions::max_iters",
        ),
        (
            NewtonOptions {
                max_halvings: u32::MAX,
                ..NewtonOptions::default()
            },
            "NewtonOptions::max_halvings",
        ),
    ] {
        assert_eq!(invalid_field(run(newton)), field);
    }
}

/// A NaN parameter with the most halvings allowed: every attempt fails at once, the halving is
/// iterative and bounded, and the error names the cause — the model's derivative is NaN at the
/// initial state — rather than the Newton iteration (it once said "residual 0").
#[test]
fn newton_on_nan_input_fails_fast_and_says_why() {
    let model = common::VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: f64::NAN,
    };
    let newton = NewtonOptions {
        max_halvings: 52,
        ..NewtonOptions::default()
    };
    let error = model
        .simulate()
        .dt(0.1)
        .steps(5)
        .newton(newton)
        .run()
        .unwrap_err();
    match &error {
        Error::BadModel { reason, .. } => assert!(reason.contains("`y2` of f is NaN"), "{error}"),
        other => panic!("{other}"),
    }
}

/// Robertson at dt = 1e3: the default halving depth carries implicit Euler through; when the
/// halvings are cut to 4 it fails, and the advice names `max_halvings`, which is what helps
/// (raising `max_iters` does not).
#[test]
fn newton_advice_names_the_option_that_helps() {
    let model = common::Robertson::classic();
    let run = |newton: NewtonOptions| model.simulate().dt(1e3).steps(100).newton(newton).run();
    let ok = run(NewtonOptions::default()).unwrap();
    assert!((ok.last().state.a + ok.last().state.b + ok.last().state.c - 1.0).abs() < 1e-12);
    let shallow = NewtonOptions {
        max_halvings: 4,
        ..NewtonOptions::default()
    };
    let error = run(shallow).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("raise `NewtonOptions::max_halvings`"),
        "{error}"
    );
    let more_iterations = NewtonOptions {
        max_iters: 100,
        ..shallow
    };
    assert!(
        run(more_iterations).is_err(),
        "iterations are not what fails here"
    );
}

/// The real-time accumulator caps the steps a frame takes (a 1e-12 s step and a 0.1 s frame
/// once ran 1e11 steps), rejects a NaN or negative frame-time cap, and reports dropped time.
#[test]
fn the_frame_loop_cannot_spiral_or_hang() {
    let model = Spring::released();
    let mut stepper =
        Stepper::<_, SymplecticEuler<_>>::new(&model, model.state(), 0.0, 1e-12).unwrap();
    let mut clock = FixedTimestep::new();
    let tick = clock.advance(0.1, &mut stepper).unwrap();
    assert_eq!(tick.steps, clock.max_steps_per_frame);
    // What was neither stepped nor dropped is the leftover (less than one step).
    let accounted = 1000.0 * 1e-12 + tick.dropped + clock.leftover();
    assert!((accounted - 0.1).abs() < 1e-13, "{tick:?}");
    assert!((0.0..1.0).contains(&tick.alpha));
    // A long frame is cut to the cap, and the cut is reported.
    let mut stepper =
        Stepper::<_, SymplecticEuler<_>>::new(&model, model.state(), 0.0, 0.01).unwrap();
    let tick = clock.advance(1e9, &mut stepper).unwrap();
    assert_eq!(tick.steps, 10);
    assert!((tick.dropped - (1e9 - 0.1)).abs() < 1e-3);
    for cap in [f64::NAN, -1.0, 0.0, f64::INFINITY] {
        let mut clock = FixedTimestep::new();
        clock.max_frame_time = cap;
        assert_eq!(
            invalid_field(clock.advance(0.016, &mut stepper)),
            "max_frame_time"
        );
    }
}

/// Driving an integrator by hand goes through the same start-up checks as a run: a particle
/// model with a link to a particle that does not exist is a typed error, not an index panic.
#[test]
fn integrators_check_the_model_when_they_start() {
    use odyn::Integrator;
    use odyn::nalgebra::Vector2;
    use odyn::particles::Spring as Link;
    #[system(dt = 1e-3)]
    struct Pair {
        #[position]
        x: Vec<Vector2<f64>>,
        #[velocity]
        v: Vec<Vector2<f64>>,
        #[mass]
        m: Vec<f64>,
        links: Vec<Link>,
    }
    #[system]
    impl Pair {
        #[pair(links)]
        fn spring(&self, link: &Link, xa: Vector2<f64>, xb: Vector2<f64>) -> Vector2<f64> {
            let d = xb - xa;
            link.stiffness * (d.norm() - link.rest) * d / d.norm()
        }
    }
    let model = Pair {
        x: vec![Vector2::zeros(), Vector2::new(1.0, 0.0)],
        v: vec![Vector2::zeros(); 2],
        m: vec![1.0, 1.0],
        links: vec![Link {
            a: 0,
            b: 7,
            rest: 1.0,
            stiffness: 10.0,
            damping: 0.0,
        }],
    };
    let mut stats = odyn::Stats::default();
    let started = ImplicitEuler::start(
        &model,
        0.0,
        &model.state(),
        &NewtonOptions::default(),
        &mut stats,
    );
    let error = started.err();
    assert!(matches!(error, Some(Error::BadModel { .. })), "{error:?}");
    // A NaN divergence limit on a bare stepper is refused too.
    let s = Spring::released();
    let limit = Stepper::<_, SymplecticEuler<_>>::with_limit(
        &s,
        s.state(),
        0.0,
        0.01,
        &NewtonOptions::default(),
        Some(f64::NAN),
    );
    assert_eq!(invalid_field(limit), "divergence_limit");
}

/// An initial state already beyond the divergence limit is an input error, not a divergence
/// that advises reducing dt.
#[test]
fn an_initial_state_beyond_the_limit_is_an_input_error() {
    let field = invalid_field(
        Spring::released()
            .simulate()
            .divergence_limit(0.5)
            .steps(10)
            .run(),
    );
    assert_eq!(field, "initial state `x`");
}

/// Charts refuse what they cannot draw with typed errors, never a panic or a hang: empty or
/// all-NaN data, values near ±1e308 (padding used to overflow to ±∞ and hang), views with
/// infinite or NaN bounds (a NaN bound used to panic and leave the temporary file behind).
#[test]
fn charts_refuse_what_they_cannot_draw() {
    let path = scratch("charts", "chart.png");
    let chart = |points: Vec<(f64, f64)>| Chart {
        series: vec![Series::line("s", points)],
        ..Chart::default()
    };
    assert!(matches!(
        chart(vec![]).write(&path, (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        chart(vec![(f64::NAN, f64::NAN)]).write(&path, (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        chart(vec![(0.0, -1.7e308), (1.0, 1.7e308)]).write(&path, (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    // A constant series is fine: its axis is widened around the value.
    chart(vec![(0.0, 3.0), (1.0, 3.0)])
        .write(&path, (400, 300))
        .unwrap();
    for bounds in [
        ((0.0, f64::INFINITY), (0.0, 1.0)),
        ((0.0, 1.0), (f64::NAN, 1.0)),
        ((1.0, 0.0), (0.0, 1.0)),
    ] {
        let view = View {
            bounds,
            segments: vec![[(0.0, 0.0), (1.0, 1.0)]],
            ..View::default()
        };
        let file = scratch("charts", "view.png");
        assert!(matches!(
            views(&file, "t", &[view], (400, 300)),
            Err(Error::InvalidInput { .. })
        ));
        assert!(!file.exists());
    }
    assert!(matches!(
        views(scratch("charts", "none.png"), "t", &[], (400, 300)),
        Err(Error::InvalidInput { .. })
    ));
    let leftovers: Vec<_> = std::fs::read_dir(path.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// Writing a trajectory whose samples were emptied is a typed error (it was an index panic).
#[test]
fn an_emptied_trajectory_is_a_typed_error() {
    let mut run = Spring::released().simulate().steps(3).run().unwrap();
    run.samples.clear();
    assert_eq!(
        invalid_field(run.write_csv(scratch("emptied", "empty.csv"))),
        "trajectory"
    );
    assert!(run.at(0.0).is_err());
}

/// A write that cannot happen is a clean `Io` error for a PNG as for a CSV; a read-only target
/// is refused rather than replaced; a symlink is followed (the file it points to is replaced,
/// the link stays); no temporary survives.
#[cfg(unix)]
#[test]
fn output_files_respect_permissions_and_links() {
    use std::os::unix::fs::PermissionsExt;
    let run = Spring::released().simulate().steps(3).run().unwrap();
    let dir = scratch("outputs", "locked");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o555)).unwrap();
    let root = std::fs::File::create(dir.join("probe")).is_ok();
    if !root {
        // (As root every write succeeds, so only an unprivileged run can see the refusal.)
        let png = odyn::plot::energy(dir.join("e.png"), &[("s", &run)]);
        assert!(matches!(png, Err(Error::Io { .. })), "{png:?}");
        assert!(matches!(
            run.write_csv(dir.join("e.csv")),
            Err(Error::Io { .. })
        ));
    }
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o755)).unwrap();
    let readonly = scratch("outputs", "readonly.csv");
    std::fs::write(&readonly, "keep me").unwrap();
    std::fs::set_permissions(&readonly, std::fs::Permissions::from_mode(0o444)).unwrap();
    assert!(matches!(run.write_csv(&readonly), Err(Error::Io { .. })));
    assert_eq!(std::fs::read_to_string(&readonly).unwrap(), "keep me");
    let target = scratch("outputs", "target.csv");
    std::fs::write(&target, "old").unwrap();
    let link = scratch("outputs", "link.csv");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&target, &link).unwrap();
    run.write_csv(&link).unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        std::fs::read_to_string(&target)
            .unwrap()
            .starts_with("method,")
    );
}

/// Every stability-explorer setting is validated: `max_doublings: u32::MAX` used to wrap to a
/// negative exponent and report ∞ (the true limit is 0.4), `steps: 0` reported ∞, `growth: NaN`
/// reported 0, `precision: 0` bisected forever.
#[test]
fn stability_probe_settings_are_validated() {
    let osc = oscillator(5.0);
    let measure =
        |probe: StabilityProbe| measured_limit(&osc, &osc.state(), Method::Leapfrog, 0.2, &probe);
    for (probe, field) in [
        (
            StabilityProbe {
                scan_ratio: 1.0,
                ..StabilityProbe::default()
            },
            "StabilityProbe::scan_ratio",
        ),
        (
            StabilityProbe {
                steps: 0,
                ..StabilityProbe::default()
            },
            "StabilityProbe::steps",
        ),
        (
            StabilityProbe {
                growth: f64::NAN,
                ..StabilityProbe::default()
            },
            "StabilityProbe::growth",
        ),
        (
            StabilityProbe {
                precision: 0.0,
                ..StabilityProbe::default()
            },
            "StabilityProbe::precision",
        ),
    ] {
        assert_eq!(invalid_field(measure(probe)), field);
    }
    // The limit itself: 2/ω = 0.4 for leapfrog.
    let limit = measure(StabilityProbe::default()).unwrap();
    assert!((limit - 0.4).abs() < 1e-5, "{limit}");
}

/// A Jacobian with a NaN entry (a NaN parameter) is refused before the eigenvalue solve, which
/// never returned on NaN input; the prediction is an error, not a silent ∞.
#[test]
fn a_nan_jacobian_has_no_predicted_limit() {
    let osc = oscillator(f64::NAN);
    let result = odyn::stability::predicted_limit(&osc, 0.0, &osc.state(), Method::Rk4);
    assert_eq!(invalid_field(result), "jacobian");
}

/// An exploded explicit run is reported, not returned as success: the default divergence limit
/// is relative to the initial state (RK4 on a stiff spring at ω·dt = 10 used to run to
/// velocities of 1e12, under the old absolute 1e100, and return Ok).
#[test]
fn an_exploded_run_is_a_divergence() {
    let stiff = oscillator(1000.0);
    let error = stiff
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.01)
        .steps(20)
        .run()
        .unwrap_err();
    match error {
        Error::Diverged { limit, value, .. } => {
            assert_eq!(limit, 1e10);
            assert!(value.abs() > limit && value.is_finite(), "{value}");
        }
        other => panic!("{other}"),
    }
}

/// Numbers in error messages print in their shortest exact form (`1e-300`), never as hundreds of
/// digits.
#[test]
fn error_messages_print_numbers_compactly() {
    let error = Spring::released()
        .simulate()
        .dt(-1e-300)
        .steps(1)
        .run()
        .unwrap_err();
    let text = error.to_string();
    assert!(text.contains("-1e-300"), "{text}");
    assert!(text.len() < 120, "{text}");
}

/// A time step below the resolution of t (t₀ = 10¹², dt = 10⁻⁶, where one ulp is 1.2e-4) used
/// to run: most steps had length 0 and the state did not move, without a word. Now `dt` is
/// rejected, for a run, a `Stepper`, and an adaptive run whose whole duration vanishes at t₀.
/// Three ulps of t are enough (steps of uneven but positive length, consistent with the
/// recorded times).
#[test]
fn a_step_below_the_resolution_of_t_is_an_input_error() {
    let osc = oscillator(1.0);
    let t0: f64 = 1e12;
    let ulp = f64::from_bits(t0.to_bits() + 1) - t0; // 2⁻¹³ = 1.22e-4 at 10¹²
    let run = osc.simulate().dt(1e-6).steps(10).start_time(t0).run();
    assert_eq!(invalid_field(run), "dt");
    let stepper = Stepper::<_, SymplecticEuler<_>>::new(&osc, osc.state(), t0, 1e-6);
    assert_eq!(invalid_field(stepper.unwrap().step()), "dt");
    let adaptive = osc
        .simulate()
        .integrator(Method::Tsit5)
        .duration(1e-6)
        .start_time(t0)
        .run();
    assert_eq!(invalid_field(adaptive), "duration");

    let run = osc.simulate().dt(3.0 * ulp).steps(10).start_time(t0).run();
    let run = run.unwrap();
    let times: Vec<f64> = run.times().collect();
    assert!(times.windows(2).all(|w| w[1] > w[0]), "{times:?}");
}

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
    let mut sim = ball
        .simulate()
        .integrator(Method::Tsit5)
        .duration(100.0)
        .event(bounce);
    sim.options.max_events = 10;
    let error = sim.run().unwrap_err();
    match &error {
        Error::EventsAccumulate { count, reason, .. } => {
            assert_eq!(*count, 11);
            assert!(reason.contains("`max_events` = 10"), "{error}");
        }
        other => panic!("expected EventsAccumulate, got {other:?}"),
    }
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

/// `measured_limit` used to answer with whichever edge its doublings straddled: Yoshida6 on
/// ω = 1 reported 2.817 although runs diverge from 2.269 to 2.328, Kahan–Li 6 reported 3.329
/// against a first edge at 2.533; and it depended on the guess: RK4 gave 0 for a guess of 1e300
/// and ∞ for 1e-300. It scans from below now and reports the first instability from any guess:
/// the first ωh with |tr P(ωh)| = 2 for the composed leapfrog matrices and RK4's 2√2, in 40-digit
/// arithmetic by scripts/stability_boundaries.py.
#[test]
fn measured_limits_are_the_first_instability_from_any_guess() {
    let osc = oscillator(1.0);
    let probe = StabilityProbe::default();
    let cases = [
        (Method::Yoshida6, 2.269_057_996_397_659, 1.0),
        (Method::Yoshida6, 2.269_057_996_397_659, 2.5),
        (Method::KahanLi6, 2.532_627_388_334_297, 1.0),
        (Method::KahanLi6, 2.532_627_388_334_297, 3.0),
        (Method::Rk4, 2.0 * 2f64.sqrt(), 1e300),
        (Method::Rk4, 2.0 * 2f64.sqrt(), 1e-300),
        (Method::Leapfrog, 2.0, f64::MAX),
    ];
    for (method, first_edge, guess) in cases {
        let measured = measured_limit(&osc, &osc.state(), method, guess, &probe).unwrap();
        assert!(
            (measured / first_edge - 1.0).abs() < 1e-4,
            "{method} from {guess:e}: {measured} vs {first_edge}"
        );
    }
    // A-stable methods are stable at every dt, from any guess.
    for guess in [1e-300, 1.0, 1e300] {
        let measured =
            measured_limit(&osc, &osc.state(), Method::ImplicitEuler, guess, &probe).unwrap();
        assert_eq!(measured, f64::INFINITY, "from {guess:e}");
    }
}

/// `divergence_limit(f64::INFINITY)` let an infinite state through (y′ = y² under RK4 returned
/// Ok with y = inf): a non-finite state always stops the run.
#[test]
fn an_infinite_divergence_limit_still_stops_an_infinite_state() {
    // y′ = y² from y = 1 blows up at t = 1; RK4 at dt = 0.1 overflows to inf past it.
    let model = Riccati { y: 1.0 };
    let error = model
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.1)
        .steps(40)
        .divergence_limit(f64::INFINITY)
        .run()
        .unwrap_err();
    match &error {
        Error::Diverged { value, .. } => assert!(!value.is_finite(), "{error}"),
        other => panic!("expected Diverged, got {other:?}"),
    }
}

/// y′ = y², which blows up at t = 1/y₀.
#[system]
pub struct Riccati {
    /// The solution.
    #[state]
    pub y: f64,
}

#[system]
impl Riccati {
    fn derivative(&self) -> RiccatiState {
        RiccatiState { y: self.y * self.y }
    }
}

/// Non-finite parameters and initial values used to read `the step size fell to 0e0 at t = 0.0
/// … probably stiff`, and so did a `dt_min` longer than the run, a start time of 1e15 and
/// atol 1e-300 with rtol 0. Each now says what is wrong: the derivative at the initial state,
/// the option, the bound that was hit.
#[test]
fn bad_parameters_and_impossible_bounds_say_what_is_wrong() {
    let bad_model = |error: Error| match error {
        Error::BadModel { what, reason, .. } => {
            assert!(what.contains("initial state"), "{what}");
            assert!(reason.contains("not finite"), "{reason}");
        }
        other => panic!("expected BadModel, got {other:?}"),
    };
    for k in [f64::NAN, f64::INFINITY] {
        let model = Spring {
            k,
            ..Spring::released()
        };
        bad_model(
            model
                .simulate()
                .integrator(Method::Tsit5)
                .duration(1.0)
                .run()
                .unwrap_err(),
        );
        bad_model(
            model
                .simulate()
                .integrator(Method::Rk4)
                .dt(0.01)
                .steps(10)
                .run()
                .unwrap_err(),
        );
        bad_model(
            model
                .simulate()
                .integrator(Method::ImplicitEuler)
                .dt(0.01)
                .steps(10)
                .run()
                .unwrap_err(),
        );
    }
    // 50·1e308 overflows.
    let huge = Spring {
        x: 1e308,
        ..Spring::released()
    };
    bad_model(
        huge.simulate()
            .integrator(Method::Dop853)
            .duration(1.0)
            .run()
            .unwrap_err(),
    );

    let control = AdaptiveOptions {
        dt_min: 10.0,
        ..AdaptiveOptions::default()
    };
    let model = Spring::released();
    let sim = model.simulate().integrator(Method::Tsit5).duration(1.0);
    assert_eq!(invalid_field(sim.clone().adaptive(control).run()), "dt_min");
    assert_eq!(
        invalid_field(sim.clone().tolerances(0.0, 1e-300).run()),
        "tolerances"
    );
    let error = sim.start_time(1e15).run().unwrap_err();
    let message = error.to_string();
    assert!(
        matches!(error, Error::StepSizeTooSmall { .. })
            && message.contains("resolution of t")
            && message.contains("nearer 0"),
        "{message}"
    );
}
