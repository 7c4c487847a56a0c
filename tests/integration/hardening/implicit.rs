//! Implicit methods at states where they cannot go on: each says what is wrong (the fourth
//! hardening probe found a NaN Jacobian reported as "the step size fell to 1.5e-307 … the
//! problem is probably stiff here (use an implicit method)" by implicit methods).

use odyn::prelude::*;

/// ẋ = −√x: finite at x = 0, but its derivative −1/(2√x) is −∞ there.
#[system]
#[derive(Clone, Copy, Debug)]
struct Root {
    #[state]
    x: f64,
}

#[system]
impl Root {
    fn derivative(&self) -> RootState {
        RootState { x: -self.x.sqrt() }
    }
}

#[test]
fn a_non_finite_jacobian_is_named_by_every_implicit_method() {
    let model = Root { x: 0.0 };
    for method in [
        Method::Rodas5P,
        Method::Rosenbrock23,
        Method::Bdf,
        Method::ImplicitEuler,
    ] {
        let mut simulation = model.simulate().integrator(method).duration(1.0);
        if !method.is_adaptive() {
            simulation = simulation.dt(0.1);
        }
        match simulation.run() {
            Err(Error::NonFiniteJacobian {
                t,
                row,
                column,
                value,
            }) => {
                assert!(
                    (row.as_str(), column.as_str()) == ("x", "x")
                        && value == f64::NEG_INFINITY
                        && t <= 0.1,
                    "{method:?}: ({row}, {column}) = {value} at t = {t}"
                );
            }
            other => panic!("{method:?}: expected NonFiniteJacobian, got {other:?}"),
        }
    }
}
