//! Whole runs of every implicit method with Krylov solves against the direct runs, and bad
//! Krylov options as typed errors.

use odyn::grid::Boundary;
use odyn::integrators::{ImplicitEuler, Rodas5P, Rosenbrock23};
use odyn::prelude::*;
use odyn::{Error, KrylovOptions, LinearSolver, NewtonOptions, Preconditioner};

use super::{difference, krylovs, stepped, with};
use crate::grid::{GrayScott, gray_scott};
use crate::particles::{Cloth, cloth};

#[test]
fn every_implicit_method_steps_a_field_model_the_same_with_krylov_solves() {
    let mut model: GrayScott = gray_scott(24, Boundary::Periodic);
    model.dx = 2.5 / 256.0;
    for linear in krylovs() {
        let krylov = with(linear);
        let direct = with(LinearSolver::Direct);
        let pairs = [
            (
                "implicit Euler",
                stepped::<GrayScott, ImplicitEuler<_>>(&model, 2.0, 10, &krylov).0,
                stepped::<GrayScott, ImplicitEuler<_>>(&model, 2.0, 10, &direct).0,
            ),
            (
                "Rosenbrock23",
                stepped::<GrayScott, Rosenbrock23<_>>(&model, 2.0, 10, &krylov).0,
                stepped::<GrayScott, Rosenbrock23<_>>(&model, 2.0, 10, &direct).0,
            ),
            (
                "Rodas5P",
                stepped::<GrayScott, Rodas5P<_>>(&model, 2.0, 10, &direct).0,
                stepped::<GrayScott, Rodas5P<_>>(&model, 2.0, 10, &krylov).0,
            ),
        ];
        for (method, x, y) in pairs {
            let d = difference(&x, &y);
            // Ten steps of 2 (Rodas5P diverges at 10 with either solver), each solve to a
            // residual of 1e-12 with κ ≈ 5.
            assert!(d < 1e-9, "{method}, {linear:?}: {d:e}");
        }
        // BDF adaptive: the same steps (the error estimates differ by rounding only), the
        // same answer to well inside the tolerance.
        let run = |newton: NewtonOptions| {
            model
                .simulate()
                .integrator(Method::Bdf)
                .tolerances(1e-6, 1e-6)
                .newton(newton)
                .duration(200.0)
                .run()
                .unwrap()
        };
        let (a, b) = (run(krylov), run(with(LinearSolver::Direct)));
        assert_eq!(a.stats.steps, b.stats.steps, "{linear:?}");
        let d = difference(a.last().state.as_slice(), b.last().state.as_slice());
        assert!(d < 1e-9, "BDF, {linear:?}: {d:e}");
    }
}

#[test]
fn a_cloth_run_with_krylov_solves_follows_the_direct_run() {
    // One-step (Baraff–Witkin) implicit Euler on a definite 10×10 cloth for 1 s: CG with the
    // warm start against Cholesky, to 1e-9 of the cloth's size.
    let model: Cloth = cloth(10, 1e4, 0.0, 0.02);
    let options = |linear| NewtonOptions {
        linearized: true,
        definite: true,
        linear,
        ..NewtonOptions::default()
    };
    let (direct, _) =
        stepped::<Cloth, ImplicitEuler<_>>(&model, 1.0 / 60.0, 60, &options(LinearSolver::Direct));
    for linear in krylovs() {
        let (x, _) = stepped::<Cloth, ImplicitEuler<_>>(&model, 1.0 / 60.0, 60, &options(linear));
        let worst = x
            .iter()
            .zip(&direct)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "{linear:?}: {worst:e}");
    }
}

#[test]
fn bad_krylov_options_are_typed_errors() {
    let model: GrayScott = gray_scott(8, Boundary::Periodic);
    for (krylov, field) in [
        (
            KrylovOptions {
                rtol: 0.0,
                ..KrylovOptions::default()
            },
            "Krylov::rtol",
        ),
        (
            KrylovOptions {
                rtol: 1.5,
                ..KrylovOptions::default()
            },
            "Krylov::rtol",
        ),
        (
            KrylovOptions {
                rtol: f64::NAN,
                ..KrylovOptions::default()
            },
            "Krylov::rtol",
        ),
        (
            KrylovOptions {
                bdf_rtol: 1.0,
                ..KrylovOptions::default()
            },
            "Krylov::bdf_rtol",
        ),
        (
            KrylovOptions {
                max_iterations: 0,
                ..KrylovOptions::default()
            },
            "Krylov::max_iterations",
        ),
        (
            KrylovOptions {
                preconditioner: Preconditioner::Factorization { refresh_above: 0 },
                ..KrylovOptions::default()
            },
            "Preconditioner::Factorization::refresh_above",
        ),
    ] {
        let result = model
            .simulate()
            .integrator(Method::ImplicitEuler)
            .newton(with(LinearSolver::Krylov(krylov)))
            .steps(1)
            .run();
        match result {
            Err(Error::InvalidInput { field: got, .. }) => assert_eq!(got, field),
            other => panic!("{krylov:?}: expected InvalidInput, got {other:?}"),
        }
    }
}
