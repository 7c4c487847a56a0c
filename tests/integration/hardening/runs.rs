//! Runs and steppers given impossible counts, steps, limits, parameters and bounds: a typed error
//! that says what is wrong, or a correct result.

use odyn::integrators::{ImplicitEuler, SymplecticEuler};
use odyn::prelude::*;
use odyn::{AdaptiveOptions, FixedTimestep, NewtonOptions, Stepper};

use super::{invalid_field, oscillator};
use crate::common::Spring;

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

/// `divergence_limit(f64::INFINITY)` let an infinite state through (y′ = y² under RK4 returned
/// Ok with y = inf): a non-finite state always stops the run.
#[test]
fn an_infinite_divergence_limit_still_stops_an_infinite_state() {
    // y′ = y² from y = 1 blows up at t = 1; RK4 at dt = 0.1 overflows to inf past it.
    let model = Riccati { y: 1.0 };
    let error = model
        .simulate()
        .dt(0.1)
        .steps(40)
        .divergence_limit(f64::INFINITY)
        .run_with::<odyn::method::Rk4>()
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
