//! Consistent initial values before the first step and after an event, the methods and
//! features that refuse a DAE, and hostile input.

use odyn::prelude::*;
use odyn::sensitivity::Sensitive;
use odyn::{Event, Stepper};
use scenes::{CartesianPendulum, CartesianPendulumState, PENDULUM_Y0, RobertsonDae};

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
/// that take one; so do a `Stepper` and the sensitivities of a DAE under an explicit method.
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
    // g = x·ẍ + … with an infinite mass has residual NaN at the start: the start cannot be made
    // consistent, and the error names the equation.
    assert!(
        matches!(&error, Error::InconsistentStart { residual, .. } if residual == "lambda"),
        "m = ∞: {error}"
    );

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
    assert!(
        matches!(&error, Error::BadModel { what, .. } if what.contains("(z, x)")),
        "{error}"
    );

    // Absurd tolerances are the options' own errors.
    for (rtol, atol) in [(0.0, 0.0), (f64::NAN, 1e-8), (1e-8, -1.0)] {
        let error = RobertsonDae::classic()
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(rtol, atol)
            .duration(1.0)
            .run()
            .unwrap_err();
        assert!(
            matches!(error, Error::InvalidInput { .. }),
            "rtol {rtol:e}, atol {atol:e}: {error}"
        );
    }
    // Tolerances that accept anything are allowed (every step passes): the run still ends at
    // the end time with a finite state on its constraint y₁ + y₂ + y₃ = 1, which each step's
    // linear solve imposes exactly (the constraint is linear).
    let run = RobertsonDae::classic()
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e300, 1e300)
        .duration(1.0)
        .run()
        .unwrap();
    let end = run.last();
    assert_eq!(end.t, 1.0);
    let y = end.state.as_slice();
    assert!(y.iter().all(|v| v.is_finite()), "{y:?}");
    assert!((y.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{y:?}");
}

/// Two algebraic equations in units far apart (a row of 1e-15, as a femtofarad capacitance's
/// current would be, beside a row of order 1) and a differential component of 1e12: the start
/// is repaired to z₁ = z₂ = 2u (the root), not refused as singular, and the run follows
/// u = u₀·e⁻ᵗ.
#[system]
#[derive(Clone, Copy, Debug)]
pub struct Scaled {
    #[state]
    pub u: f64,
    #[state]
    pub big: f64,
    #[algebraic]
    pub z: [f64; 2],
}

#[system]
impl Scaled {
    fn derivative(&self) -> ScaledState {
        ScaledState {
            u: -self.u,
            big: 0.0,
            z: [1e-15 * (self.z[0] - 2.0 * self.u), self.z[1] - self.z[0]],
        }
    }
}

#[test]
fn equations_in_units_far_apart_are_not_singular() {
    let model = Scaled {
        u: 1.5,
        big: 1e12,
        z: [0.0, 7.0],
    };
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-10, 1e-12)
        .duration(1.0)
        .run()
        .unwrap();
    let first = run.first().state;
    assert!(
        (first.z[0] - 3.0).abs() < 1e-12 && (first.z[1] - 3.0).abs() < 1e-12,
        "{first:?}"
    );
    let end = run.last().state;
    let exact = 1.5 * (-1.0f64).exp();
    assert!(
        (end.u - exact).abs() < 1e-9 && (end.z[1] - 2.0 * exact).abs() < 1e-8,
        "{end:?}"
    );
}
