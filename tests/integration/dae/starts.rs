//! Consistent initial values before the first step and after an event, the methods and
//! features that refuse a DAE, and hostile input.

use odyn::prelude::*;
use odyn::sensitivity::Sensitive;
use odyn::{Event, Stepper};
use scenes::{CartesianPendulum, CartesianPendulumState, PENDULUM_1, PENDULUM_Y0, RobertsonDae};

use super::relative;

/// Consistent initial values: the algebraic components of a start are solved for before the
/// first step (and recorded so), the differential ones kept bit for bit.
#[test]
fn an_inconsistent_start_is_repaired() {
    // λ = 0 → m·g·cos θ₀/L (scripts/reference_dae.py's consistent λ₀).
    let run = CartesianPendulum::released(0.0, 0.0)
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(0.1)
        .run()
        .unwrap();
    let first = run.first().state;
    assert_eq!(&first.as_slice()[..4], &PENDULUM_Y0[..4]);
    let lambda = first.lambda;
    assert!(
        ((lambda - PENDULUM_Y0[4]) / PENDULUM_Y0[4]).abs() < 1e-14,
        "{lambda}"
    );
    // y₃ = 0.5 → 1 − y₁ − y₂ = 0 (a linear constraint: one Newton step).
    let mut robertson = RobertsonDae::classic();
    robertson.y3 = 0.5;
    let run = robertson
        .simulate()
        .integrator(Method::Bdf)
        .duration(1.0)
        .run()
        .unwrap();
    assert_eq!(run.first().state.y3, 0.0);
}

/// A constraint that does not involve its algebraic component (index 2), and one with no real
/// root, are typed errors that name the equation and the component.
#[test]
fn an_unrepairable_start_is_a_typed_error() {
    #[system]
    #[derive(Clone, Copy, Debug)]
    struct IndexTwo {
        #[state]
        x: f64,
        #[algebraic]
        z: f64,
    }
    #[system]
    impl IndexTwo {
        fn derivative(&self) -> IndexTwoState {
            // x′ = z, 0 = x − 1: z is fixed only through x′ (index 2).
            IndexTwoState {
                x: self.z,
                z: self.x - 1.0,
            }
        }
    }
    let error = IndexTwo { x: 0.5, z: 0.0 }
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(1.0)
        .run()
        .unwrap_err();
    eprintln!("{error}");
    let Error::InconsistentStart {
        residual,
        component,
        value,
        ..
    } = &error
    else {
        panic!("{error}")
    };
    assert_eq!((residual.as_str(), component.as_str()), ("z", "z"));
    assert_eq!(*value, 0.5);

    #[system]
    #[derive(Clone, Copy, Debug)]
    struct NoRoot {
        #[state]
        x: f64,
        #[algebraic]
        z: f64,
    }
    #[system]
    impl NoRoot {
        fn derivative(&self) -> NoRootState {
            NoRootState {
                x: -self.x,
                z: self.z * self.z + 1.0,
            }
        }
    }
    let error = NoRoot { x: 1.0, z: 0.3 }
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(1.0)
        .run()
        .unwrap_err();
    eprintln!("{error}");
    assert!(
        matches!(&error, Error::InconsistentStart { component, .. } if component == "z"),
        "{error}"
    );
}

/// An event that changes the differential components leaves the algebraic one consistent with
/// them: stopping the mass (u = v = 0) at t = 0.5 leaves λ = −m·g·y/(x² + y²), the rod force
/// of a mass at rest.
#[test]
fn an_event_that_changes_the_state_restores_consistency() {
    let pendulum = CartesianPendulum::released(0.0, 0.0);
    let stop = Event::at_times("stop", vec![0.5]).change(|_, s: &mut CartesianPendulumState| {
        s.u = 0.0;
        s.v = 0.0;
    });
    let run = pendulum
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(1.0)
        .event(stop)
        .run()
        .unwrap();
    let after = run.events[0].after;
    let at_rest = -9.81 * after.y / (after.x * after.x + after.y * after.y);
    assert!(
        ((after.lambda - at_rest) / at_rest).abs() < 1e-12,
        "{after:?}"
    );
    assert_ne!(run.events[0].before.lambda, after.lambda);
}

/// The methods without a linear system refuse a model with a mass matrix, naming the methods
/// that take one; so does a `Stepper`, and forward sensitivities (not supported on DAEs yet).
#[test]
fn methods_without_a_mass_matrix_refuse_a_dae() {
    let pendulum = CartesianPendulum::released(0.0, 0.0);
    for method in [
        Method::Rk4,
        Method::Dop853,
        Method::Tsit5,
        Method::ExplicitEuler,
    ] {
        let simulation = pendulum.simulate().integrator(method);
        let simulation = if method.is_adaptive() {
            simulation.duration(1.0)
        } else {
            simulation.dt(0.01).steps(10)
        };
        let error = simulation.run().unwrap_err();
        let Error::Unsupported { reason, .. } = &error else {
            panic!("{method}: {error}")
        };
        assert!(
            reason.contains("Rodas5P, Rosenbrock23, Bdf and ImplicitEuler"),
            "{error}"
        );
    }
    let refused =
        Stepper::<_, odyn::integrators::Rk4<_>>::new(&pendulum, pendulum.state(), 0.0, 0.01);
    assert!(matches!(refused, Err(Error::Unsupported { .. })));
    let error = Sensitive::new(&RobertsonDae::classic())
        .simulate()
        .integrator(Method::Dop853)
        .duration(1.0)
        .run()
        .unwrap_err();
    assert!(matches!(error, Error::Unsupported { .. }), "{error}");
}

/// Forward sensitivities of a DAE (M·sⱼ′ = J·sⱼ + ∂f/∂pⱼ, the algebraic ones made consistent):
/// Robertson-DAE's ∂y/∂(k₁, k₂, k₃) at t = 40 are the ODE form's (the two have one solution, so
/// one derivative with respect to the rates), within 1e-6 of each column's largest entry under
/// Rodas5P and BDF at rtol 1e-10 (measured 4e-14 and 5e-10: at equal tolerances Rodas5P takes
/// the same steps on both forms, whose stages keep the linear invariant); the algebraic row
/// keeps s₁ + s₂ + s₃ = 0.
#[test]
fn sensitivities_of_a_dae_match_the_ode_form() {
    let (ode_model, dae_model) = (scenes::Robertson::classic(), RobertsonDae::classic());
    let ode = Sensitive::new(&ode_model);
    let reference = ode
        .simulate()
        .integrator(Method::Rodas5P)
        .with_tolerances(ode.tolerances(1e-11, 1e-16, true))
        .duration(40.0)
        .record_every(u64::MAX)
        .run()
        .unwrap()
        .last()
        .state
        .sensitivity_matrix();
    let dae = Sensitive::new(&dae_model);
    for method in [Method::Rodas5P, Method::Bdf] {
        let run = dae
            .simulate()
            .integrator(method)
            .with_tolerances(dae.tolerances(1e-10, 1e-16, true))
            .duration(40.0)
            .record_every(u64::MAX)
            .run()
            .unwrap();
        let s = run.last().state.sensitivity_matrix();
        for c in 0..3 {
            let scale = reference.column(c).amax();
            let error = (s.column(c) - reference.column(c)).amax() / scale;
            eprintln!("{method}, ∂y/∂k{}: relative error {error:.1e}", c + 1);
            assert!(error < 1e-6, "{method}, column {c}: {error}");
            assert!(
                s.column(c).sum().abs() < 1e-12 * scale,
                "{method}: {}",
                s.column(c)
            );
        }
    }
}

/// A `Stepper` with Rodas5P repairs the start and steps the DAE at a fixed step: 100 steps of
/// 0.01 reach the exact state at t = 1 within 1e-6.
#[test]
fn a_stepper_steps_a_dae() {
    let pendulum = CartesianPendulum::released(0.0, 0.0);
    let mut stepper =
        Stepper::<_, odyn::integrators::Rodas5P<_>>::new(&pendulum, pendulum.state(), 0.0, 0.01)
            .unwrap();
    assert!((stepper.state().lambda - PENDULUM_Y0[4]).abs() < 1e-12);
    for _ in 0..100 {
        stepper.step().unwrap();
    }
    let error = relative(stepper.state().as_slice(), &PENDULUM_1);
    assert!(error < 1e-6, "{error}");
}

/// Hostile input: a non-finite start, a singular mass matrix with no algebraic equation to
/// stand for its zero row, and `fn mass` entries that are not finite or sit in an algebraic
/// row: typed errors, never a panic.
#[test]
fn hostile_inputs_are_typed_errors() {
    let mut nan = CartesianPendulum::released(0.0, 0.0);
    nan.lambda = f64::NAN;
    let error = nan
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(1.0)
        .run()
        .unwrap_err();
    assert!(matches!(error, Error::InvalidInput { .. }), "{error}");
    let mut inf = CartesianPendulum::released(0.0, 0.0);
    inf.m = f64::INFINITY;
    let error = inf
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(1.0)
        .run()
        .unwrap_err();
    eprintln!("m = ∞: {error}");

    // M = diag(1, 0) but the second row of f does not depend on the state: 0 = 1.
    #[system]
    #[derive(Clone, Copy, Debug)]
    struct Degenerate {
        #[state]
        y: [f64; 2],
        /// An entry for M[0][0].
        scale: f64,
        /// An entry for M[1][0].
        coupling: f64,
    }
    #[system]
    impl Degenerate {
        fn derivative(&self) -> DegenerateState {
            DegenerateState {
                y: [-self.y[0], 1.0],
            }
        }
        fn mass(&self) -> [[f64; 2]; 2] {
            [[self.scale, 0.0], [self.coupling, 0.0]]
        }
    }
    let degenerate = Degenerate {
        y: [1.0, 0.0],
        scale: 1.0,
        coupling: 0.0,
    };
    for method in [
        Method::Rodas5P,
        Method::Rosenbrock23,
        Method::Bdf,
        Method::ImplicitEuler,
    ] {
        let simulation = degenerate.simulate().integrator(method);
        let simulation = if method.is_adaptive() {
            simulation.duration(1.0)
        } else {
            simulation.dt(0.1).steps(10)
        };
        let error = simulation.run().unwrap_err();
        assert!(
            matches!(&error, Error::BadModel { what, .. } if what == "equation `y[1]`"),
            "{method}: {error}"
        );
    }
    let bad = Degenerate {
        scale: f64::NAN,
        ..degenerate
    };
    let error = bad
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(1.0)
        .run()
        .unwrap_err();
    assert!(matches!(error, Error::BadModel { .. }), "{error}");

    // An `fn mass` entry in an algebraic component's row.
    #[system]
    #[derive(Clone, Copy, Debug)]
    struct Crossed {
        #[state]
        x: f64,
        #[algebraic]
        z: f64,
    }
    #[system]
    impl Crossed {
        fn derivative(&self) -> CrossedState {
            CrossedState {
                x: -self.x,
                z: self.z - self.x,
            }
        }
        fn mass(&self) -> [[f64; 2]; 2] {
            [[1.0, 0.0], [1.0, 0.0]]
        }
    }
    let error = Crossed { x: 1.0, z: 1.0 }
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(1.0)
        .run()
        .unwrap_err();
    eprintln!("{error}");
    assert!(
        matches!(&error, Error::BadModel { what, .. } if what.contains("(z, x)")),
        "{error}"
    );

    // Absurd tolerances are the options' own errors.
    for (rtol, atol) in [(0.0, 0.0), (f64::NAN, 1e-8), (1e-8, -1.0), (1e300, 1e300)] {
        let error = RobertsonDae::classic()
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(rtol, atol)
            .duration(1.0)
            .run();
        eprintln!("rtol {rtol:e}, atol {atol:e}: {:?}", error.as_ref().err());
    }
}

/// A DAE above 32 components takes faer's dense LU (`FaerDense`): 20 decays xᵢ′ = −kᵢ·zᵢ with
/// the algebraic zᵢ = xᵢ, started from z = 0 (inconsistent: repaired to z = x), reach
/// xᵢ(1) = e^(−kᵢ), kᵢ = 0.1·(i + 1), within 1e-8 under Rodas5P and BDF at rtol 1e-10.
#[test]
fn a_big_dae_runs_on_the_heap_matrix() {
    #[system]
    #[derive(Clone, Copy, Debug)]
    struct Decays {
        #[state]
        x: [f64; 20],
        #[algebraic]
        z: [f64; 20],
    }
    #[system]
    impl Decays {
        fn derivative(&self) -> DecaysState {
            let mut x = [0.0; 20];
            let mut z = [0.0; 20];
            for i in 0..20 {
                x[i] = -0.1 * (i + 1) as f64 * self.z[i];
                z[i] = self.z[i] - self.x[i];
            }
            DecaysState { x, z }
        }
    }
    let model = Decays {
        x: [1.0; 20],
        z: [0.0; 20],
    };
    for method in [Method::Rodas5P, Method::Bdf] {
        let run = model
            .simulate()
            .integrator(method)
            .tolerances(1e-10, 1e-12)
            .duration(1.0)
            .run()
            .unwrap();
        assert_eq!(run.first().state.z, [1.0; 20]);
        let end = run.last().state;
        for i in 0..20 {
            let exact = (-0.1 * (i + 1) as f64).exp();
            assert!((end.x[i] - exact).abs() < 1e-8, "{method}: x[{i}] = {}", end.x[i]);
            assert!((end.z[i] - end.x[i]).abs() < 1e-12, "{method}: z[{i}]");
        }
    }
}
