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

/// ċ = −(c − ½): relaxation to ½.
#[system]
#[derive(Clone, Copy, Debug)]
struct Level {
    #[state]
    c: f64,
}

#[system]
impl Level {
    fn derivative(&self) -> LevelState {
        LevelState { c: -(self.c - 0.5) }
    }
}

/// BDF to t = 1e30 from c = 1 once stopped at t = 5e21 after 10⁶ steps: at steps of 1e16 and
/// more, Newton's updates are rounding noise of equal size, and their ratio near 1 read as
/// divergence, so every other step was halved. An update at the rounding of y converges now:
/// 148 steps (Rodas5P takes 52). Started at t₀ = 1e12, BDF's order-1 first step (1.4e-4) was
/// below the resolution of t there (1.2e-3) and the run failed before it began; a proposal
/// below the resolution is tried at the resolution now.
#[test]
fn bdf_steps_as_long_as_the_solution_allows() {
    let model = Level { c: 1.0 };
    let run = model
        .simulate()
        .integrator(Method::Bdf)
        .duration(1e30)
        .record_every(1_000_000)
        .run()
        .unwrap();
    assert!(run.stats.steps < 500, "{:?}", run.stats);
    assert_eq!(run.last().t, 1e30);
    assert!((run.last().state.c - 0.5).abs() < 1e-12);
    let late = model
        .simulate()
        .integrator(Method::Bdf)
        .start_time(1e12)
        .duration(10.0)
        .run()
        .unwrap();
    // c − ½ = ½·e^{−10} at the end.
    let expected = 0.5 + 0.5 * (-10.0f64).exp();
    assert!(
        (late.last().state.c - expected).abs() < 1e-4,
        "{:?}",
        late.last()
    );
}

/// A Krylov residual target near 1 once made Rodas5P crawl (and fill memory with every step's
/// samples and dense output): 513 steps at 1e-3 where 1e-8 needs 21 on a heat grid. Targets
/// that cannot serve the method are refused, naming the option.
#[test]
fn krylov_targets_that_cannot_serve_the_method_are_refused() {
    use odyn::{KrylovOptions, LinearSolver, NewtonOptions};
    for (krylov, field) in [
        (
            KrylovOptions {
                rtol: 0.999,
                ..KrylovOptions::default()
            },
            "Krylov::rtol",
        ),
        (
            KrylovOptions {
                newton_rtol: 0.5,
                ..KrylovOptions::default()
            },
            "Krylov::newton_rtol",
        ),
        (
            KrylovOptions {
                bdf_rtol: 0.9,
                ..KrylovOptions::default()
            },
            "Krylov::bdf_rtol",
        ),
    ] {
        let newton = NewtonOptions {
            linear: LinearSolver::Krylov(krylov),
            ..NewtonOptions::default()
        };
        let model = Level { c: 1.0 };
        match model
            .simulate()
            .integrator(Method::Rodas5P)
            .duration(1.0)
            .newton(newton)
            .run()
        {
            Err(Error::InvalidInput { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: expected InvalidInput, got {other:?}"),
        }
    }
}

/// ẋ = −signum(x)·(1 + x²): x reaches 0 at a finite time and f switches sign there, which no
/// step resolves.
#[system]
#[derive(Clone, Copy, Debug)]
struct Switch {
    #[state]
    x: f64,
}

#[system]
impl Switch {
    fn derivative(&self) -> SwitchState {
        SwitchState {
            x: -self.x.signum() * (1.0 + self.x * self.x),
        }
    }
}

/// "the problem is probably stiff here (use an implicit method)" was the advice whatever the
/// method; an implicit method that cannot step past a switch in f is told about the switch.
#[test]
fn a_step_size_failure_advises_for_the_method_that_failed() {
    let model = Switch { x: 1.0 };
    for method in [Method::Rodas5P, Method::Bdf, Method::Tsit5] {
        let result = model
            .simulate()
            .integrator(method)
            .duration(2.0)
            .adaptive(odyn::AdaptiveOptions {
                max_steps: 20_000,
                ..Default::default()
            })
            .run();
        let Err(error @ (Error::StepSizeTooSmall { .. } | Error::MaxSteps { .. })) = result else {
            panic!("{method:?}: {result:?}");
        };
        let text = error.to_string();
        if method.needs_jacobian() {
            assert!(
                !text.contains("implicit method") && text.contains("switch"),
                "{method:?}: {text}"
            );
        } else {
            assert!(text.contains("stiff"), "{method:?}: {text}");
        }
    }
}
