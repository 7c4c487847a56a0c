//! The runner and the real-time loop: validation, divergence, reproducibility, capabilities.

use crate::common;

use common::{Lorenz, Oscillator, OscillatorState, Pair, Spring};
use odyn::prelude::*;
use odyn::{Error, FixedTimestep, Stepper, integrators};

fn invalid_field(result: Result<impl std::fmt::Debug>) -> String {
    match result {
        Err(Error::InvalidInput { field, .. }) => field,
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

#[test]
fn attribute_sets_the_defaults_and_the_runtime_overrides_them() {
    let run = Spring::released().simulate().duration(10.0).run().unwrap();
    assert_eq!(
        (run.method, run.stepping.dt(), run.steps()),
        (Method::SymplecticEuler, Some(0.016), 625)
    );
    assert_eq!(run.samples.len(), 626);
    let rk4 = Spring::released()
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.05)
        .steps(400)
        .run()
        .unwrap();
    assert_eq!(
        (
            rk4.method,
            rk4.stepping.dt(),
            rk4.steps(),
            rk4.stats.evaluations
        ),
        (Method::Rk4, Some(0.05), 400, 1600)
    );
    assert!((rk4.last().t - 20.0).abs() < 1e-12);
}

#[test]
fn bad_inputs_are_typed_errors() {
    assert_eq!(
        invalid_field(Spring::released().simulate().dt(0.0).steps(1).run()),
        "dt"
    );
    assert_eq!(
        invalid_field(Spring::released().simulate().dt(-0.1).steps(1).run()),
        "dt"
    );
    assert_eq!(
        invalid_field(Spring::released().simulate().dt(f64::NAN).steps(1).run()),
        "dt"
    );
    assert_eq!(
        invalid_field(
            Spring::released()
                .simulate()
                .dt(f64::INFINITY)
                .steps(1)
                .run()
        ),
        "dt"
    );
    assert_eq!(invalid_field(Spring::released().simulate().run()), "length");
    assert_eq!(
        invalid_field(Spring::released().simulate().duration(-1.0).run()),
        "duration"
    );
    assert_eq!(
        invalid_field(Spring::released().simulate().duration(f64::NAN).run()),
        "duration"
    );
    assert_eq!(
        invalid_field(Spring::released().simulate().steps(3).record_every(0).run()),
        "record_every"
    );
    assert_eq!(
        invalid_field(
            Spring::released()
                .simulate()
                .steps(3)
                .start_time(f64::NAN)
                .run()
        ),
        "t0"
    );
    // Lorenz's attribute names no dt.
    assert_eq!(
        invalid_field(
            Oscillator {
                x: 1.0,
                v: 0.0,
                omega: 1.0
            }
            .simulate()
            .steps(3)
            .run()
        ),
        "dt"
    );
    let nan = Spring {
        v: f64::NAN,
        ..Spring::released()
    };
    assert_eq!(
        invalid_field(nan.simulate().steps(3).run()),
        "initial state `v`"
    );
    let error = nan.simulate().steps(3).run().unwrap_err().to_string();
    assert_eq!(error, "invalid initial state `v`: must be finite, got NaN");
}

#[test]
fn a_method_the_model_cannot_take_is_a_typed_error() {
    match Lorenz::classic()
        .simulate()
        .integrator(Method::SymplecticEuler)
        .steps(10)
        .run()
    {
        Err(Error::Unsupported {
            method: Method::SymplecticEuler,
            model: "Lorenz",
            ..
        }) => {}
        other => panic!("{other:?}"),
    }
    // The damped spring's force reads the velocity: position Verlet would silently ignore it.
    let error = Spring::released()
        .simulate()
        .integrator(Method::PositionVerlet)
        .steps(10)
        .run()
        .unwrap_err();
    assert!(matches!(
        error,
        Error::Unsupported {
            method: Method::PositionVerlet,
            model: "Spring",
            ..
        }
    ));
    assert!(error.to_string().contains("reads a velocity"), "{error}");
}

#[test]
fn divergence_stops_the_run_naming_step_and_time() {
    // ω = 10, dt = 0.25: ωdt = 2.5 > 2, symplectic Euler grows |λ| ≈ 3.2 per step.
    let osc = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 10.0,
    };
    let sim = osc
        .simulate()
        .integrator(Method::SymplecticEuler)
        .dt(0.25)
        .steps(10_000);
    let Err(Error::Diverged { step, t, value, .. }) = sim.run() else {
        panic!("expected divergence")
    };
    // The default limit: 1e10 × the initial state's scale (1 here).
    assert!(value.is_nan() || value.abs() > 1e10);
    assert_eq!(t, step as f64 * 0.25);
    // The partial run keeps every good step and says why it stopped; nothing non-finite inside.
    let (partial, failure) = sim.run_partial().unwrap();
    assert!(matches!(failure, Some(Error::Diverged { step: s, .. }) if s == step));
    assert_eq!(partial.steps(), step - 1);
    assert_eq!(partial.last().step, step - 1);
    assert!(
        partial
            .samples
            .iter()
            .all(|s| s.state.x.is_finite() && s.state.v.is_finite())
    );
    // With an infinite limit, only non-finite values count: it runs longer.
    let Err(Error::Diverged {
        step: late, value, ..
    }) = sim.clone().divergence_limit(f64::INFINITY).run()
    else {
        panic!("expected divergence")
    };
    assert!(late > step && !value.is_finite());
}

#[test]
fn identical_runs_are_bit_for_bit_identical() {
    for method in Method::ALL {
        let osc = Oscillator {
            x: 0.3,
            v: -1.7,
            omega: 3.0,
        };
        let a = osc
            .simulate()
            .integrator(method)
            .dt(0.01)
            .steps(5000)
            .run()
            .unwrap();
        let b = osc
            .simulate()
            .integrator(method)
            .dt(0.01)
            .steps(5000)
            .run()
            .unwrap();
        let bits = |r: &Trajectory<common::OscillatorState>| -> Vec<u64> {
            r.samples
                .iter()
                .flat_map(|s| [s.t, s.state.x, s.state.v, s.energy.unwrap()])
                .map(f64::to_bits)
                .collect()
        };
        assert_eq!(bits(&a), bits(&b), "{method}");
    }
}

/// Feeding a 30 fps and a 144 fps frame stream through the accumulator gives the physics the
/// same fixed steps, so after equal numbers of steps the states are bit-identical.
#[test]
fn frame_rate_does_not_change_the_physics() {
    fn history(fps: f64, seconds: f64) -> Vec<[u64; 3]> {
        let model = Spring::released();
        let mut stepper = Stepper::<_, integrators::VelocityVerlet<_>>::new(
            &model,
            model.state(),
            0.0,
            1.0 / 120.0,
        )
        .unwrap();
        let mut clock = FixedTimestep::new();
        let mut states = vec![];
        for _ in 0..(fps * seconds) as usize {
            let before = stepper.steps();
            let tick = clock.advance(1.0 / fps, &mut stepper).unwrap();
            assert_eq!(tick.steps, stepper.steps() - before);
            assert!((0.0..1.0).contains(&tick.alpha), "alpha {}", tick.alpha);
            let s = stepper.state();
            states.push((
                stepper.steps(),
                [stepper.t().to_bits(), s.x.to_bits(), s.v.to_bits()],
            ));
        }
        // Keep one entry per step count reached at a frame boundary.
        states.dedup_by_key(|(n, _)| *n);
        let mut by_step = vec![[0; 3]; states.last().unwrap().0 as usize + 1];
        for (n, bits) in states {
            by_step[n as usize] = bits;
        }
        by_step
    }
    let slow = history(30.0, 3.0);
    let fast = history(144.0, 3.0);
    assert!(
        slow.len() >= 350 && fast.len() >= 350,
        "{} {}",
        slow.len(),
        fast.len()
    );
    // 30 fps lands on every 4th step; compare those, where both loops have a state.
    let mut compared = 0;
    for n in (4..slow.len().min(fast.len())).step_by(4) {
        if slow[n] != [0; 3] && fast[n] != [0; 3] {
            assert_eq!(slow[n], fast[n], "step {n}");
            compared += 1;
        }
    }
    assert!(compared >= 10, "only {compared} common steps");
}

#[test]
fn a_long_frame_is_capped() {
    let model = Spring::released();
    let mut stepper =
        Stepper::<_, integrators::SymplecticEuler<_>>::new(&model, model.state(), 0.0, 0.01)
            .unwrap();
    let mut clock = FixedTimestep::new();
    // A 5 s stall counts as the 0.1 s cap: 10 steps, not 500.
    let tick = clock.advance(5.0, &mut stepper).unwrap();
    assert_eq!(tick.steps, 10);
    assert!(matches!(
        clock.advance(-1.0, &mut stepper),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        clock.advance(f64::NAN, &mut stepper),
        Err(Error::InvalidInput { .. })
    ));
}

/// `advance_with` takes the same steps as `advance` for the same frames (it is what `advance`
/// runs), stops at the first failing step, and refuses a dt that is not finite and positive.
#[test]
fn advance_with_steps_anything_like_advance() {
    let mut counted = FixedTimestep::new();
    let mut through_stepper = FixedTimestep::new();
    let model = Spring::released();
    let mut stepper =
        Stepper::<_, integrators::SymplecticEuler<_>>::new(&model, model.state(), 0.0, 0.01)
            .unwrap();
    let mut steps = 0;
    for frame in [0.016, 0.017, 0.004, 0.033, 0.25] {
        let a = counted
            .advance_with(frame, 0.01, || {
                steps += 1;
                Ok(())
            })
            .unwrap();
        let b = through_stepper.advance(frame, &mut stepper).unwrap();
        assert_eq!(a, b);
    }
    assert_eq!(steps, stepper.steps());
    // 0.016 + 0.017 + 0.004 + 0.033 + 0.1 (the cap) = 0.17 s: 16 or 17 steps of 0.01, as the
    // rounding of the sums falls.
    assert!((16..=17).contains(&steps), "{steps}");
    let mut failing = FixedTimestep::new();
    let mut tries = 0;
    let failed = failing.advance_with(0.05, 0.01, || {
        tries += 1;
        if tries == 3 {
            Err(Error::InvalidInput {
                field: "test".into(),
                reason: "third step".into(),
            })
        } else {
            Ok(())
        }
    });
    assert!(matches!(failed, Err(Error::InvalidInput { .. })));
    assert_eq!(tries, 3);
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            FixedTimestep::new().advance_with(0.1, dt, || Ok(())),
            Err(Error::InvalidInput { .. })
        ));
    }
}

#[test]
fn first_order_models_run_with_the_general_methods() {
    let lorenz = Lorenz::classic();
    let run = lorenz.simulate().steps(100).run().unwrap();
    assert_eq!(run.method, Method::Rk4);
    assert_eq!(run.first().energy, None);
    // One explicit Euler step is y + h·f(y): from (1, 1, 1), f = (0, 26, −5/3).
    let one = lorenz
        .simulate()
        .integrator(Method::ExplicitEuler)
        .steps(1)
        .run()
        .unwrap();
    let s = one.last().state;
    assert_eq!((s.x, s.y), (1.0, 1.0 + 0.01 * 26.0));
    assert!((s.z - (1.0 - 0.01 * 5.0 / 3.0)).abs() < 1e-15);
}

#[test]
fn time_argument_and_tuple_accelerations_reach_the_right_fields() {
    let pair = Pair {
        a: 0.0,
        b: [1.0, 1.0],
        va: 0.0,
        vb: [0.0, 0.0],
        drive: 2.0,
    };
    // Symplectic Euler's first step from rest: v = h·a(0), x = h·v.
    let h = 0.1;
    let run = pair
        .simulate()
        .integrator(Method::SymplecticEuler)
        .dt(h)
        .steps(1)
        .run()
        .unwrap();
    let s = run.last().state;
    assert_eq!(s.va, h * 2.0); // −a + drive·cos(0)
    assert_eq!(s.vb, [-h, -4.0 * h]);
    assert_eq!(s.b, [1.0 - h * h, 1.0 - 4.0 * h * h]);
    // The drive sees t: RK4 over a quarter period of cos differs from the undriven run.
    let driven = pair.simulate().dt(0.01).duration(1.0).run().unwrap();
    let still = Pair { drive: 0.0, ..pair }
        .simulate()
        .dt(0.01)
        .duration(1.0)
        .run()
        .unwrap();
    // Undriven, a stays 0; driven, ä = −a + 2cos t gives a(1) = t·sin t = sin 1 (resonance).
    assert_eq!(still.last().state.a, 0.0);
    assert!(
        (driven.last().state.a - 1f64.sin()).abs() < 1e-9,
        "{}",
        driven.last().state.a
    );
}

/// The same runs in four threads at once give results bit-identical to a serial run: nothing in
/// a run depends on shared state or on timing (adaptive Lorenz with DOP853 and events, a stiff
/// Rodas5P run, a fixed-step RK4 run).
#[test]
fn runs_in_parallel_threads_match_a_serial_run_bit_for_bit() {
    let lorenz = common::Lorenz::classic();
    let runs = || -> Vec<Vec<f64>> {
        let watch = Event::crossing("x = 0", |_, s: &common::LorenzState| s.x).record();
        let adaptive = lorenz
            .simulate()
            .integrator(Method::Dop853)
            .tolerances(1e-10, 1e-10)
            .duration(10.0)
            .event(watch)
            .run()
            .unwrap();
        let stiff = lorenz
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(1e-6, 1e-8)
            .duration(5.0)
            .run()
            .unwrap();
        let fixed = lorenz
            .simulate()
            .integrator(Method::Rk4)
            .dt(1e-3)
            .steps(5000)
            .run()
            .unwrap();
        [adaptive, stiff, fixed]
            .iter()
            .map(|run| {
                run.samples
                    .iter()
                    .flat_map(|s| std::iter::once(s.t).chain(s.state.as_slice().iter().copied()))
                    .chain(run.events.iter().map(|e| e.t))
                    .collect()
            })
            .collect()
    };
    let serial = runs();
    let parallel: Vec<_> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4).map(|_| scope.spawn(runs)).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for result in parallel {
        for (a, b) in result.iter().zip(&serial) {
            assert_eq!(a.len(), b.len());
            assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()));
        }
    }
}

/// A fixed-step `Simulation` without events, save times or dense output takes its steps in
/// blocks of 1024 (the divergence limit tested once per block); a `Stepper` takes them one
/// checked step at a time. Both must agree bit for bit — on the states of a run that stays
/// finite, and on the step a diverging run stops at (the block that diverged is retaken on the
/// checked path).
#[test]
fn blocked_and_checked_steps_agree_bit_for_bit() {
    fn stepped<I: odyn::Integrator<Oscillator>>(
        osc: &Oscillator,
        dt: f64,
        steps: u64,
    ) -> (OscillatorState, Option<u64>) {
        let mut stepper = Stepper::<_, I>::new(osc, osc.state(), 0.0, dt).unwrap();
        for n in 1..=steps {
            if let Err(Error::Diverged { step, .. }) = stepper.step() {
                assert_eq!(step, n);
                return (*stepper.state(), Some(step));
            }
        }
        (*stepper.state(), None)
    }
    let osc = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 10.0,
    };
    // ω·dt = 0.1: finite for every method over 3001 steps, three blocks, the last of an odd
    // length (blocks take steps in pairs; explicit Euler grows ×1.005 a step, to 3.2e6).
    for (method, stepper) in [
        (
            Method::Rk4,
            stepped::<integrators::Rk4<_>> as fn(&Oscillator, f64, u64) -> _,
        ),
        (Method::Leapfrog, stepped::<integrators::Leapfrog<_>>),
        (
            Method::ImplicitEuler,
            stepped::<integrators::ImplicitEuler<_>>,
        ),
        (
            Method::ExplicitEuler,
            stepped::<integrators::ExplicitEuler<_>>,
        ),
    ] {
        let run = osc
            .simulate()
            .integrator(method)
            .dt(0.01)
            .steps(3001)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        let (state, diverged) = stepper(&osc, 0.01, 3001);
        assert_eq!(diverged, None);
        assert_eq!(run.last().state, state, "{method}");
        // ω·dt = 3 (beyond 2√2 and 2): RK4 and leapfrog diverge; the step named is the stepper's.
        if matches!(method, Method::Rk4 | Method::Leapfrog) {
            let Err(Error::Diverged { step, .. }) = osc
                .simulate()
                .integrator(method)
                .dt(0.3)
                .steps(1000)
                .record_every(u64::MAX)
                .run()
            else {
                panic!("{method} should diverge at ω·dt = 3")
            };
            assert_eq!(Some(step), stepper(&osc, 0.3, 1000).1, "{method}");
        }
    }
}
