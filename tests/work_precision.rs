//! The work-precision API: it reproduces the theoretical orders, tells bounded from drifting
//! energy errors, and rejects malformed studies with typed errors.

mod common;

use common::{Kepler, KeplerState, Spring, SpringState};
use odyn::Error;
use odyn::prelude::*;
use odyn::reference::{DampedOscillator, KeplerOrbit};
use odyn::work_precision::{Reference, WorkPrecision, measure};

fn spring_study(methods: Vec<Method>, dts: Vec<f64>) -> (Spring, WorkPrecision<SpringState>) {
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
    let mut study = WorkPrecision::new("spring", spring.state(), 2.0, methods, dts, reference);
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
        assert!(m.seconds > 0.0 && m.evaluations > 0 && !m.diverged, "{m:?}");
        assert_eq!(m.steps, (2.0 / m.dt).round() as u64);
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
        let mut study = WorkPrecision::new(
            "kepler",
            kepler.state(),
            orbits * orbit.period(),
            vec![method],
            vec![dt],
            reference,
        );
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
