//! Every linear solver under input a hostile user would give: a Newton matrix that is singular,
//! states of 1e300, a Krylov solve allowed one iteration (every solve then falls back to the
//! direct one), and the Fourier preconditioner asked for on a grid that is not periodic. Each
//! ends in a typed error or in the direct solve's answer.

use odyn::grid::{Boundary, Grid, Stencil};
use odyn::prelude::*;
use odyn::{AutoPolicy, Error, KrylovOptions, LinearSolver, Method, NewtonOptions, Preconditioner};

use super::{difference, krylovs, with};

/// u′ = d·∇²u + k·u on a grid (unit spacing): I − c·J = (1 − c·k)·I − c·d·∇², whose constant
/// mode on a periodic grid has the eigenvalue 1 − c·k.
#[system]
#[derive(Clone, Debug)]
struct Heat {
    #[field]
    u: Grid,
    d: f64,
    k: f64,
}

#[system]
impl Heat {
    #[cell]
    fn rate(&self, u: Stencil) -> f64 {
        self.d * u.laplacian() + self.k * u.c
    }
}

fn heat(n: usize, boundary: Boundary, d: f64, k: f64, scale: f64) -> Heat {
    let u = Grid::from_fn(n, n, boundary, |i, j| {
        scale * (1.0 + 0.5 * (0.7 * i as f64).sin() * (0.3 * j as f64).cos())
    })
    .expect("a finite grid");
    Heat { u, d, k }
}

/// Every linear solver: the direct one, `Auto` with Krylov from the first unknown, and each
/// preconditioner.
fn solvers() -> Vec<LinearSolver> {
    let mut all = vec![
        LinearSolver::Direct,
        LinearSolver::Auto(AutoPolicy {
            krylov_from: 0,
            ..AutoPolicy::default()
        }),
    ];
    all.extend(krylovs());
    all
}

/// A fixed-step run's end state after `steps` steps of `dt`, or its error.
fn end(
    model: &Heat,
    method: Method,
    linear: LinearSolver,
    dt: f64,
    steps: u64,
) -> Result<Vec<f64>, Error> {
    let run = model
        .simulate()
        .integrator(method)
        .newton(with(linear))
        .dt(dt)
        .steps(steps)
        .run()?;
    Ok(run.last().state.as_slice().to_vec())
}

const IMPLICIT: [Method; 4] = [
    Method::ImplicitEuler,
    Method::Rosenbrock23,
    Method::Rodas5P,
    Method::Bdf,
];

/// A periodic grid with k = 1/h under implicit Euler at step h: W = −h·d·∇² is singular (the
/// constant mode), and the implicit Euler equation has no solution there. Allowed no halving,
/// every solver reports it as a typed error; by default each halves the step, and the run is
/// the one of steps h/2 (each of which grows the constant mode by 1/(1 − k·h/2) = 2), to the
/// Krylov tolerance.
#[test]
fn a_singular_newton_matrix_is_a_typed_error_or_a_halved_step_under_every_solver() {
    let h = 0.05;
    let model = heat(12, Boundary::Periodic, 0.5, 1.0 / h, 1.0);
    let halves = end(
        &model,
        Method::ImplicitEuler,
        LinearSolver::Direct,
        h / 2.0,
        8,
    )
    .expect("steps of h/2 are regular");
    let mean = halves.iter().sum::<f64>() / halves.len() as f64;
    // The mean of u₀ (1 + a product of sines and cosines) times 2⁸.
    let start = model.u.values().iter().sum::<f64>() / halves.len() as f64;
    assert!(
        (mean / (start * 256.0) - 1.0).abs() < 1e-12,
        "{mean} {start}"
    );
    for linear in solvers() {
        let halved = end(&model, Method::ImplicitEuler, linear, h, 4).expect("halved steps");
        let d = difference(&halved, &halves);
        assert!(d < 1e-9, "{linear:?}: {d:e}");
        let refused = model
            .simulate()
            .integrator(Method::ImplicitEuler)
            .newton(NewtonOptions {
                linear,
                max_halvings: 0,
                ..NewtonOptions::default()
            })
            .dt(h)
            .steps(4)
            .run();
        match refused {
            Err(Error::SingularMatrix { .. } | Error::NewtonDidNotConverge { .. }) => {}
            other => panic!("{linear:?}: {other:?}"),
        }
    }
}

/// States of 1e300 on a linear model: the matrix does not depend on the state, and each
/// solver ends where the direct one does, finite, to the Krylov tolerance (1e-12 relative).
#[test]
fn states_of_1e300_end_where_the_direct_solve_does() {
    for boundary in [Boundary::Periodic, Boundary::Dirichlet(0.0)] {
        let model = heat(12, boundary, 0.5, -0.3, 1e300);
        for method in IMPLICIT {
            let direct = end(&model, method, LinearSolver::Direct, 0.05, 4).expect("a finite run");
            assert!(direct.iter().all(|x| x.is_finite()));
            for linear in solvers() {
                let other = end(&model, method, linear, 0.05, 4).expect("a finite run");
                let d = difference(&other, &direct);
                assert!(d < 1e-9, "{method} {boundary:?} {linear:?}: {d:e}");
            }
        }
    }
}

/// A Krylov solve allowed one iteration to a relative residual of 1e-12 does not converge on a
/// diffusion matrix under block Jacobi or ILU(0), so those solves fall back to the direct one
/// (counted); multigrid may converge in one. Every run ends where the direct run does.
#[test]
fn one_iteration_allowed_falls_back_to_the_direct_answer() {
    let model = heat(24, Boundary::Dirichlet(0.0), 2.0, -0.3, 1.0);
    for method in IMPLICIT {
        let direct = end(&model, method, LinearSolver::Direct, 0.05, 4).expect("a run");
        for preconditioner in [
            Preconditioner::BlockJacobi,
            Preconditioner::Ilu0,
            Preconditioner::Multigrid,
        ] {
            let linear = LinearSolver::Krylov(KrylovOptions {
                preconditioner,
                max_iterations: 1,
                rtol: 1e-12,
                newton_rtol: 1e-12,
                bdf_rtol: 1e-12,
                ..KrylovOptions::default()
            });
            let run = model
                .simulate()
                .integrator(method)
                .newton(NewtonOptions {
                    linear,
                    ..NewtonOptions::default()
                })
                .dt(0.05)
                .steps(4)
                .run()
                .expect("a run");
            let fallbacks = run.stats.linear.krylov.fallbacks;
            if preconditioner != Preconditioner::Multigrid {
                assert!(fallbacks > 0, "{method} {preconditioner:?}");
            }
            let d = difference(run.last().state.as_slice(), &direct);
            assert!(d < 1e-10, "{method} {preconditioner:?}: {d:e}");
        }
    }
}

/// The Fourier preconditioner on a grid that is not periodic is block Jacobi for the run: the
/// same arithmetic, so the same bits.
#[test]
fn fourier_off_a_periodic_grid_is_block_jacobi_to_the_bit() {
    let model = heat(12, Boundary::Dirichlet(0.0), 0.5, -0.3, 1.0);
    let krylov = |preconditioner| {
        LinearSolver::Krylov(KrylovOptions {
            preconditioner,
            ..KrylovOptions::default()
        })
    };
    for method in IMPLICIT {
        let fourier = end(&model, method, krylov(Preconditioner::Fourier), 0.05, 4).expect("a run");
        let jacobi =
            end(&model, method, krylov(Preconditioner::BlockJacobi), 0.05, 4).expect("a run");
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&fourier), bits(&jacobi), "{method}");
    }
}
