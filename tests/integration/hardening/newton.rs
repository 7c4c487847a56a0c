//! Newton's options and failures: validated up front, fast on NaN input, advice that names the
//! option that helps.

use odyn::NewtonOptions;
use odyn::prelude::*;

use super::invalid_field;
use crate::common;

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
                max_iterations: 0,
                ..NewtonOptions::default()
            },
            "NewtonOptions::max_iterations",
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
/// (raising `max_iterations` does not).
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
        max_iterations: 100,
        ..shallow
    };
    assert!(
        run(more_iterations).is_err(),
        "iterations are not what fails here"
    );
}
