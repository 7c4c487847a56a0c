//! The work-precision API: it reproduces the theoretical orders, tells bounded from drifting
//! energy errors, and rejects malformed studies with typed errors.

use crate::common;

use common::{Kepler, KeplerState, Spring, SpringState};
use odyn::Error;
use odyn::prelude::*;
use odyn::reference::{DampedOscillator, KeplerOrbit};
use odyn::work_precision::{Reference, WorkPrecision, measure};

fn spring_study(methods: Vec<Method>, dts: Vec<f64>) -> (Spring, WorkPrecision<SpringState>) {
    spring_study_to(2.0, methods, dts)
}

fn spring_study_to(
    horizon: f64,
    methods: Vec<Method>,
    dts: Vec<f64>,
) -> (Spring, WorkPrecision<SpringState>) {
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
    let reference = Reference::Exact(Box::new(move |t| {
        let (x, v) = exact.state_at(1.0, 0.0, t);
        SpringState { x, v }
    }));
    let mut study = WorkPrecision::new("spring", spring.state(), horizon, reference);
    study.methods = methods;
    study.dts = dts;
    study.repeats = 1;
    (spring, study)
}

/// log(error) against log(dt) has slope = order (Hairer, Nørsett & Wanner, §II.1; HLW §I), ±0.2.
#[test]
fn slopes_are_the_theoretical_orders() {
    let methods = vec![
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::VelocityVerlet,
        Method::Leapfrog,
        Method::Rk4,
        Method::ImplicitEuler,
    ];
    let (spring, study) = spring_study(methods.clone(), vec![0.02, 0.01, 0.005, 0.0025]);
    let set = measure(&spring, &study).unwrap();
    assert_eq!(set.reference_error, 0.0);
    assert_eq!(set.measurements.len(), 24);
    for method in methods {
        let order = set.observed_order(method).unwrap();
        assert!(
            (order - f64::from(method.order())).abs() <= 0.2,
            "{method}: {order}"
        );
    }
    for m in &set.measurements {
        assert!(
            m.seconds > 0.0 && m.evaluations() > 0 && !m.diverged,
            "{m:?}"
        );
        let dt = m.stepping.dt().unwrap();
        assert_eq!(m.stats.steps, (2.0 / dt).round() as u64);
    }
}

/// Kepler, GM = 1, e = 0.5 from pericentre (0.5, 0) with speed √3: leapfrog's energy error over
/// 1000 orbits is the one it makes in the first orbit (a symplectic method's error is bounded);
/// RK4's grows with the number of orbits, about linearly (HLW 2006, §I.2 and Fig. I.2.3).
#[test]
fn leapfrog_energy_error_is_bounded_and_rk4s_grows() {
    let kepler = Kepler {
        r: Vector2::new(0.5, 0.0),
        v: Vector2::new(0.0, 3f64.sqrt()),
        gm: 1.0,
    };
    let orbit = KeplerOrbit {
        gm: 1.0,
        a: 1.0,
        e: 0.5,
    };
    let energy_error = |method, dt, orbits: f64| {
        let reference = Reference::Exact(Box::new(move |t| {
            let ([x, y], [vx, vy]) = orbit.state_at(t);
            KeplerState {
                r: Vector2::new(x, y),
                v: Vector2::new(vx, vy),
            }
        }));
        let mut study =
            WorkPrecision::new("kepler", kepler.state(), orbits * orbit.period(), reference);
        study.methods = vec![method];
        study.dts = vec![dt];
        study.repeats = 1;
        measure(&kepler, &study).unwrap().measurements[0]
            .energy_error
            .unwrap()
    };
    let (first, thousand) = (
        energy_error(Method::Leapfrog, 0.01, 1.0),
        energy_error(Method::Leapfrog, 0.01, 1000.0),
    );
    eprintln!("leapfrog energy error: {first:.3e} after 1 orbit, {thousand:.3e} after 1000");
    assert!(
        thousand <= first * 1.05 && thousand >= first * 0.95,
        "leapfrog: {first} after 1 orbit, {thousand} after 1000"
    );
    let (ten, hundred) = (
        energy_error(Method::Rk4, 0.05, 10.0),
        energy_error(Method::Rk4, 0.05, 100.0),
    );
    let growth = hundred / ten;
    eprintln!(
        "RK4 energy error: {ten:.3e} after 10 orbits, {hundred:.3e} after 100 ({growth:.2}x)"
    );
    assert!(
        (7.0..14.0).contains(&growth),
        "RK4 energy error grew {growth}× over 10× the orbits"
    );
}

#[test]
fn malformed_studies_are_typed_errors() {
    let field = |result: odyn::Result<_>| match result {
        Err(Error::InvalidInput { field, .. }) => field,
        other => panic!("expected InvalidInput, got {other:?}"),
    };
    let (spring, study) = spring_study(vec![], vec![0.01]);
    assert_eq!(field(measure(&spring, &study)), "methods");
    let (spring, study) = spring_study(vec![Method::Rk4], vec![0.01, 0.0]);
    assert_eq!(field(measure(&spring, &study)), "dts");
    let (spring, study) = spring_study(vec![Method::Rk4], vec![0.01, -1.0]);
    assert_eq!(field(measure(&spring, &study)), "dts");
    let (spring, mut study) = spring_study(vec![Method::Rk4], vec![0.01]);
    study.reference = Reference::Final(vec![1.0, 0.0, 0.0]);
    assert_eq!(field(measure(&spring, &study)), "reference");
    // A repeated step would make the slope fit meaningless (it used to give Some(NaN)).
    let (spring, study) = spring_study(vec![Method::Rk4], vec![0.01, 0.01]);
    assert_eq!(field(measure(&spring, &study)), "dts");
    // An adaptive method needs tolerances to sweep, and they must be distinct and valid.
    let (spring, mut study) = spring_study(vec![Method::Tsit5], vec![]);
    assert_eq!(field(measure(&spring, &study)), "tolerances");
    study.tolerances = vec![Tolerances::new(1e-6, 1e-9), Tolerances::new(1e-6, 1e-8)];
    assert_eq!(field(measure(&spring, &study)), "tolerances");
    study.tolerances = vec![Tolerances::new(-1.0, 1e-9)];
    assert_eq!(field(measure(&spring, &study)), "rtol");
    // A method the model cannot take is the runner's typed error.
    let (spring, study) = spring_study(vec![Method::PositionVerlet], vec![0.01]);
    assert!(matches!(
        measure(&spring, &study),
        Err(Error::Unsupported { .. })
    ));
}

#[test]
fn a_diverging_run_is_a_measurement_not_an_error() {
    let (spring, mut study) = spring_study(vec![Method::SymplecticEuler], vec![1.5]);
    study.horizon = 300.0;
    let set = measure(&spring, &study).unwrap();
    let m = &set.measurements[0];
    // ω = 2, so ω·dt = 3 > 2: past symplectic Euler's limit.
    assert!(
        m.diverged && m.error.is_infinite() && m.seconds.is_nan(),
        "{m:?}"
    );
}

/// A reference that is NaN must not read as a perfect run (the max fold used to drop NaN and
/// report an error of 0): an exact solution or a final state that is not finite is refused.
#[test]
fn a_nan_reference_is_an_error_not_a_perfect_run() {
    let field = |result: odyn::Result<_>| match result {
        Err(Error::InvalidInput { field, .. }) => field,
        other => panic!("expected InvalidInput, got {other:?}"),
    };
    let (spring, mut study) = spring_study(vec![Method::Rk4], vec![0.01]);
    study.reference = Reference::Exact(Box::new(|_| SpringState {
        x: f64::NAN,
        v: 0.0,
    }));
    assert_eq!(field(measure(&spring, &study)), "reference");
    study.reference = Reference::Final(vec![f64::NAN, 0.0]);
    assert_eq!(field(measure(&spring, &study)), "reference");
}

/// A run at a dt that does not divide the horizon ends at ⌈H/dt⌉·dt. Against an exact solution
/// the error is measured where the run ended (H = 1, dt = 0.3: the run ends at 1.2), not against
/// y(1), which mistook the 0.2 s the run went past the horizon for error; against a final state at
/// H such a dt is refused.
#[test]
fn errors_are_measured_where_the_run_ended() {
    let (spring, study) = spring_study_to(1.0, vec![Method::Rk4], vec![0.3]);
    let m = &measure(&spring, &study).unwrap().measurements[0];
    let exact = DampedOscillator {
        k: 4.0,
        b: 0.5,
        m: 1.0,
    };
    let run = spring
        .simulate()
        .integrator(Method::Rk4)
        .dt(0.3)
        .steps(4)
        .run()
        .unwrap();
    let (x, v) = exact.state_at(1.0, 0.0, 1.2);
    let last = run.last().state;
    let expected = (last.x - x).abs().max((last.v - v).abs());
    assert_eq!(m.error, expected);
    let (x1, v1) = exact.state_at(1.0, 0.0, 1.0);
    let against_horizon = (last.x - x1).abs().max((last.v - v1).abs());
    eprintln!("error at the run's end {expected:.2e}; against y(H) {against_horizon:.2e}");
    assert!(against_horizon > 100.0 * expected);
    let (spring, mut study) = spring_study_to(1.0, vec![Method::Rk4], vec![0.3]);
    study.reference = Reference::Final(vec![x, v]);
    assert!(matches!(
        measure(&spring, &study),
        Err(Error::InvalidInput { field, .. }) if field == "dts"
    ));
}

/// Adaptive methods sweep tolerances beside the fixed methods' steps, on one study; their error
/// follows the tolerance about proportionally (slope of log error against log rtol near 1;
/// Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.4, "tolerance proportionality").
#[test]
fn adaptive_methods_sweep_tolerances_and_their_error_follows_them() {
    let (spring, mut study) = spring_study_to(
        10.0,
        vec![Method::Rk4, Method::Tsit5, Method::Dop853],
        vec![0.01, 0.005],
    );
    study.tolerances = WorkPrecision::<SpringState>::rtols(4..=10, 1e-3);
    let set = measure(&spring, &study).unwrap();
    assert_eq!(set.measurements.len(), 2 + 7 + 7);
    for method in [Method::Tsit5, Method::Dop853] {
        let slope = set.tolerance_proportionality(method).unwrap();
        eprintln!("{method}: log error / log rtol = {slope:.3}");
        assert!((0.7..=1.3).contains(&slope), "{method}: {slope}");
        assert_eq!(set.observed_order(method), None);
        for m in set.of(method) {
            let rtol = m.stepping.rtol().unwrap();
            // The global error stays within two orders of magnitude of the tolerance asked.
            assert!(m.error < 100.0 * rtol && !m.diverged, "{m:?}");
        }
    }
    assert!(set.tolerance_proportionality(Method::Rk4).is_none());
}
