//! The Fourier preconditioner: exact on a uniform periodic grid, and `Auto`'s trials of it,
//! given back when it costs more and tried again as the problem stiffens.

use odyn::grid::{Boundary, Grid};
use odyn::integrators::ImplicitEuler;
use odyn::prelude::*;
use odyn::{KrylovOptions, KrylovWork, LinearSolver, NewtonOptions, Preconditioner, Stepper};

use super::{Counted, counts_of, with};
use crate::grid::{GrayScott, gray_scott};

/// The Fourier preconditioner inverts I − h·J exactly where J is the same at every cell (a
/// uniform state of a periodic Gray–Scott grid: constant diffusion, the same reaction block):
/// every solve then converges within its first iteration. On a varying state it still solves to
/// the tolerance (the solves above); on a grid that is not periodic, or for particles, the run
/// goes on with block Jacobi.
#[test]
fn fourier_solves_a_uniform_grid_in_one_iteration() {
    let fourier = with(LinearSolver::Krylov(KrylovOptions {
        preconditioner: Preconditioner::Fourier,
        ..KrylovOptions::default()
    }));
    let mut model: GrayScott = gray_scott(32, Boundary::Periodic);
    model.dx = 2.5 / 256.0;
    let uniform = |value: f64| Grid::new(32, 32, Boundary::Periodic, vec![value; 1024]).unwrap();
    (model.u, model.v) = (uniform(0.6), uniform(0.2));
    let counts = counts_of(&model, 10.0, &fourier);
    assert!(counts.krylov.solves >= 10, "{counts:?}");
    // At most one iteration a solve (none where the warm start already meets the tolerance).
    assert!(
        counts.krylov.iterations <= counts.krylov.solves,
        "{counts:?}"
    );
    assert_eq!(counts.krylov.fallbacks, 0);
    // Zero-flux edges: block Jacobi instead, still Krylov, still converging.
    let neumann: GrayScott = gray_scott(32, Boundary::Neumann);
    let counts = counts_of(&neumann, 1.0, &fourier);
    assert!(
        counts.krylov.solves >= 10 && counts.krylov.fallbacks == 0,
        "{counts:?}"
    );
}

/// `Auto`'s trial of Fourier on a periodic grid is decided by its first solve's cost: on
/// Pearson's Gray–Scott at 64² with cells 0.3× as wide, h = 10, block Jacobi needs 18 iterations
/// a linearized solve (to 1e-8) on average, more than `AutoPolicy::fourier_iteration_cost` (4.3), and Fourier
/// about 7, each costing 0.33·log₂ 8192 = 4.3 block-Jacobi iterations: tried, and given back to
/// block Jacobi for the rest of the run (its solves never need twice as many; 10 steps,
/// measured with the sweep that chose the case).
#[test]
fn auto_gives_fourier_back_when_its_solve_costs_more() {
    let mut model = GrayScott::pearson(64, 0.0367, 0.0649).unwrap();
    model.dx *= 0.3;
    let counts = |linear| {
        let newton = NewtonOptions {
            linearized: true,
            linear,
            ..NewtonOptions::default()
        };
        counts_of(&model, 10.0, &newton)
    };
    let block_jacobi = LinearSolver::Krylov(KrylovOptions::default());
    let (auto, block_jacobi) = (counts(LinearSolver::default()), counts(block_jacobi));
    let (a, b) = (auto.krylov, block_jacobi.krylov);
    assert_eq!(a.solves, b.solves);
    // One solve was Fourier's (fewer iterations than block Jacobi's), and it was given back.
    assert!(a.iterations < b.iterations, "{a:?} against {b:?}");
    assert_eq!(
        (
            a.switched_to_fourier,
            a.switched_to_multigrid,
            a.switched_to_direct
        ),
        (0, 0, 0)
    );
    assert_eq!((auto.lu, auto.cholesky, a.fallbacks), (0, 0, 0));
}

/// Decay at rates that vary from cell to cell, k ∈ {0, 50} on a fixed pattern, under diffusion
/// that strengthens with time, D(t) = d·t²: early, block Jacobi (which holds the rates) beats
/// Fourier (which sees their mean); later, the diffusion dominates and Fourier wins.
#[system(integrator = ImplicitEuler, dt = 1.0)]
pub struct Stiffening {
    #[field]
    pub u: Grid,
    /// The decay rate of each cell: a parameter grid.
    pub k: Grid,
    pub d: f64,
}

#[system]
impl Stiffening {
    #[cell]
    fn rate(&self, u: Stencil, k: Stencil, t: f64) -> f64 {
        -k.c * u.c + self.d * t * t * u.laplacian()
    }
}

/// The Krylov counts of `model` after each of `steps` linearized implicit Euler steps of 1.
fn counts_per_step(model: &Stiffening, linear: LinearSolver, steps: usize) -> Vec<KrylovWork> {
    let newton = NewtonOptions {
        linearized: true,
        linear,
        ..NewtonOptions::default()
    };
    let mut stepper = Stepper::<Stiffening, ImplicitEuler<Stiffening>>::with_newton(
        model,
        model.state(),
        0.0,
        1.0,
        &newton,
    )
    .unwrap();
    (0..steps)
        .map(|_| {
            stepper.step().unwrap();
            stepper.integrator().matrix().counts().krylov
        })
        .collect()
}

/// `Auto` tries Fourier once a block-Jacobi solve costs more than one Fourier iteration, and
/// tries it again each time block Jacobi needs twice the iterations of the solve before the
/// trial it lost. On [`Stiffening`] (32², 1 024 unknowns, a Fourier iteration worth
/// 0.33·log₂ 1024 = 3.3 block-Jacobi ones), measured: the first step's block-Jacobi solve takes
/// 7 iterations, Fourier's trial loses and is given back; the retry at 15 loses too; the one at
/// 31 (step 21) wins and Fourier stays, at 7–9 iterations a step against block Jacobi's 31 and
/// up.
#[test]
fn auto_tries_fourier_again_as_the_problem_stiffens() {
    let n = 32;
    let model = Stiffening {
        u: Grid::from_fn(n, n, Boundary::Periodic, |i, j| {
            ((i * 7 + j * 3) % 5) as f64
        })
        .unwrap(),
        k: Grid::from_fn(n, n, Boundary::Periodic, |i, j| {
            if (i * 5 + j * 11) % 7 < 3 { 50.0 } else { 0.0 }
        })
        .unwrap(),
        d: 0.1,
    };
    let steps = 30;
    let auto = counts_per_step(&model, LinearSolver::default(), steps);
    let block_jacobi = counts_per_step(
        &model,
        LinearSolver::Krylov(KrylovOptions::default()),
        steps,
    );
    // Tried at once and given back, block Jacobi's again for the next steps.
    assert_eq!(auto[1].switched_to_fourier, 0, "{:?}", auto[1]);
    // Fourier for the last steps.
    assert_eq!(
        auto[steps - 1].switched_to_fourier,
        1,
        "{:?}",
        auto[steps - 1]
    );
    let last = |c: &[KrylovWork]| c[steps - 1].iterations - c[steps - 2].iterations;
    let cost = odyn::AutoPolicy::default().fourier_iteration_cost(n * n);
    assert!(
        last(&auto) as f64 * cost < last(&block_jacobi) as f64,
        "the last step: {} Fourier iterations against {} block-Jacobi ones",
        last(&auto),
        last(&block_jacobi)
    );
}
