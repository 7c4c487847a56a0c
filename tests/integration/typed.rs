//! The compile-time choice of method (`Simulation::run_with::<method::X>()`): the same run, bit
//! for bit, as the run-time choice (`.integrator(Method::X).run()`), the same refusals, and the
//! same switch from the attribute's `dt` to tolerances for an adaptive method.

use odyn::{Error, Method, MethodType, Model, Simulate, Trajectory, method};

use crate::common::{Charged, NoJacobian, Pendulum};

fn pendulum() -> Pendulum {
    Pendulum {
        theta: 1.0,
        omega: 0.0,
        g: 9.81,
        length: 1.0,
    }
}

/// Both runs of `T` on the pendulum: typed and by the enum.
fn both<T: MethodType>() -> (
    Trajectory<<Pendulum as Model>::State>,
    Trajectory<<Pendulum as Model>::State>,
) {
    let model = pendulum();
    let typed = model.simulate().duration(0.5).run_with::<T>().unwrap();
    let chosen = model
        .simulate()
        .duration(0.5)
        .integrator(T::METHOD)
        .run()
        .unwrap();
    (typed, chosen)
}

macro_rules! same_runs {
    ($($variant:ident)*) => {{
        let mut checked = Vec::new();
        $(
            let (typed, chosen) = both::<method::$variant>();
            assert_eq!(<method::$variant as MethodType>::METHOD, Method::$variant);
            assert_eq!(typed.method, Method::$variant);
            assert_eq!(typed.stepping, chosen.stepping, "{}", stringify!($variant));
            assert_eq!(typed.stats, chosen.stats, "{}", stringify!($variant));
            assert_eq!(typed.samples.len(), chosen.samples.len());
            for (a, b) in typed.samples.iter().zip(&chosen.samples) {
                assert_eq!(a.t.to_bits(), b.t.to_bits(), "{}", stringify!($variant));
                assert_eq!(a.state.theta.to_bits(), b.state.theta.to_bits());
                assert_eq!(a.state.omega.to_bits(), b.state.omega.to_bits());
            }
            checked.push(Method::$variant);
        )*
        checked
    }};
}

#[test]
fn every_method_runs_the_same_typed_or_chosen_at_run_time() {
    let checked = same_runs!(
        ExplicitEuler SymplecticEuler PositionVerlet VelocityVerlet Leapfrog Yoshida4 Yoshida6
        KahanLi6 Rk4 ImplicitEuler Tsit5 Dop853 Rosenbrock23 Rodas5P Bdf
    );
    assert_eq!(checked, Method::ALL, "a method without a typed twin");
}

#[test]
fn an_adaptive_method_steps_to_tolerances_not_the_attributes_dt() {
    // The pendulum's attribute says `VelocityVerlet, dt = 0.01`: Tsit5 by either route drops
    // that dt and steps to the default tolerances; VelocityVerlet keeps it.
    let (typed, _) = both::<method::Tsit5>();
    assert!(matches!(typed.stepping, odyn::Stepping::Adaptive(_)));
    let (typed, _) = both::<method::VelocityVerlet>();
    assert_eq!(typed.stepping, odyn::Stepping::Fixed(0.01));
    // An explicit dt stays, as with `.integrator`.
    let model = pendulum();
    let run = model
        .simulate()
        .dt(0.02)
        .steps(10)
        .run_with::<method::Tsit5>()
        .unwrap();
    assert_eq!(run.stepping, odyn::Stepping::Fixed(0.02));
}

#[test]
fn a_method_the_model_cannot_take_is_refused_by_type_as_by_name() {
    let model = NoJacobian { x: 1.0, v: 0.0 };
    let simulation = || model.simulate().dt(0.01).steps(10);
    for error in [
        simulation().run_with::<method::Rodas5P>().unwrap_err(),
        simulation().integrator(Method::Rodas5P).run().unwrap_err(),
    ] {
        assert!(
            matches!(
                error,
                Error::Unsupported {
                    method: Method::Rodas5P,
                    ..
                }
            ),
            "{error}"
        );
    }
    // A force that reads the velocity, under a method that evaluates forces at positions only.
    let charged = Charged {
        r: [1.0, 0.0, 0.0].into(),
        v: [0.0, 1.0, 0.0].into(),
        gm: 1.0,
        qb: [0.0, 0.0, 0.1].into(),
    };
    let error = charged
        .simulate()
        .steps(10)
        .run_with::<method::PositionVerlet>()
        .unwrap_err();
    assert!(
        matches!(
            error,
            Error::Unsupported {
                method: Method::PositionVerlet,
                ..
            }
        ),
        "{error}"
    );
}
