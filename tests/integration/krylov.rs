//! Krylov solves of the sparse Newton matrices (`odyn::LinearSolver`): each against the direct
//! solve on cloth and Gray–Scott matrices (relative residual and solution difference), whole
//! runs of every implicit method against the direct runs, the automatic choice, fallbacks and
//! option errors.

use odyn::grid::{Boundary, Grid};
use odyn::integrators::{ImplicitEuler, Rodas5P, Rosenbrock23};
use odyn::particles::ParticleState;
use odyn::prelude::*;
use odyn::{
    Error, Integrator, Jacobian, Krylov, KrylovCounts, LinearSolver, NewtonMatrix, NewtonOptions,
    Preconditioner, Stepper,
};

use crate::grid::{GrayScott, gray_scott};
use crate::particles::{Cloth, cloth, shaken};

/// The Krylov configurations under test, solving to a relative residual of 1e-12 (inside Newton
/// too).
fn krylovs() -> [LinearSolver; 5] {
    [
        Preconditioner::BlockJacobi,
        Preconditioner::Ilu0,
        Preconditioner::Multigrid,
        // Periodic grids; block Jacobi for the cloth and other boundaries.
        Preconditioner::Fourier,
        Preconditioner::Factorization { refresh_above: 5 },
    ]
    .map(|preconditioner| {
        LinearSolver::Krylov(Krylov {
            preconditioner,
            rtol: 1e-12,
            newton_rtol: 1e-12,
            bdf_rtol: 1e-12,
            ..Krylov::default()
        })
    })
}

fn with(linear: LinearSolver) -> NewtonOptions {
    NewtonOptions {
        linear,
        ..NewtonOptions::default()
    }
}

/// Solves (I − c·J)·x = b with the Jacobian of `model` at `state`, configured by `newton`.
fn solve<M: Jacobian>(
    model: &M,
    state: &M::State,
    c: f64,
    newton: &NewtonOptions,
    b: &[f64],
) -> Vec<f64> {
    let mut matrix = model.jacobian_matrix(state);
    matrix.configure(newton, odyn::Solves::OneStep);
    model.jacobian(0.0, state, &mut matrix);
    let mut factors = matrix.factors();
    matrix.factorize(c, &mut factors).expect("W is regular");
    let mut x = b.to_vec();
    matrix.solve(&mut factors, &mut x).expect("x is finite");
    x
}

/// max |x − y| / max |y|.
fn difference(x: &[f64], y: &[f64]) -> f64 {
    let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// ‖b − A·x‖₂ / ‖b‖₂ for a dense A.
fn relative_residual(a: &odyn::nalgebra::DMatrix<f64>, x: &[f64], b: &[f64]) -> f64 {
    let x = odyn::nalgebra::DVector::from_column_slice(x);
    let b = odyn::nalgebra::DVector::from_column_slice(b);
    (&b - a * x).norm() / b.norm()
}

#[test]
fn krylov_solves_of_gray_scott_matrices_match_the_direct_solve() {
    // A 24² grid (1 152 unknowns), h = 10 at dx = 2.5/256 (h·D_u/dx² ≈ 2.1, Pearson's setup):
    // I − h·J is unsymmetric (the reaction couples u and v), so BiCGSTAB.
    let mut model = gray_scott(24, Boundary::Periodic);
    model.dx = 2.5 / 256.0;
    let state = model.state();
    let n = state.as_slice().len();
    let b: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
    let h = 10.0;
    let direct = solve(&model, &state, h, &with(LinearSolver::Direct), &b);
    // The dense I − h·J for the residual.
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut jacobian);
    let dense = jacobian.to_dense();
    let w = odyn::nalgebra::DMatrix::from_fn(n, n, |r, c| {
        f64::from(u8::from(r == c)) - h * dense[(r, c)]
    });
    for linear in krylovs() {
        let x = solve(&model, &state, h, &with(linear), &b);
        let residual = relative_residual(&w, &x, &b);
        // The solver's own test is on this residual, to 1e-12 (rounding in the dense product
        // adds about n·ε·‖W‖·‖x‖/‖b‖ ≈ 1e-13).
        assert!(residual < 2e-12, "{linear:?}: residual {residual:e}");
        let d = difference(&x, &direct);
        // The direct solve's own error is about κ·ε; κ(I − h·J) ≈ 20 here.
        assert!(
            d < 1e-10,
            "{linear:?}: differs from the direct solve by {d:e}"
        );
    }
}

#[test]
fn krylov_solves_of_cloth_matrices_match_the_direct_solve() {
    // A shaken 8×8 undamped cloth (k = 1e3): M − h·∂f/∂v − h²·∂f/∂x is symmetric, definite
    // after projection, so CG; the first-order system (I − h·J)·(Δx, Δv) = b is solved through
    // it, so the residual is measured on that system with J from the dense force Jacobians.
    let model = cloth(8, 1e3, 0.0, 0.1);
    let state: ParticleState<3> = shaken(&model, 0.01, 7);
    let n = state.as_slice().len();
    // Zero on the pinned particles (the velocity form holds their Δv at zero).
    let pins = model.pinned().to_vec();
    let b: Vec<f64> = (0..n)
        .map(|i| {
            let held = pins.contains(&((i % (n / 2)) / 3));
            if held {
                0.0
            } else {
                ((i * 29) % 13) as f64 * 0.1 - 0.6
            }
        })
        .collect();
    let h = 1.0 / 60.0;
    let definite = |linear| NewtonOptions {
        definite: true,
        linear,
        ..NewtonOptions::default()
    };
    let direct = solve(&model, &state, h, &definite(LinearSolver::Direct), &b);
    for linear in krylovs() {
        let x = solve(&model, &state, h, &definite(linear), &b);
        let d = difference(&x, &direct);
        assert!(
            d < 1e-9,
            "{linear:?}: differs from the direct solve by {d:e}"
        );
    }
    // Unprojected, with damping: unsymmetric, so BiCGSTAB, against the direct LU, and the
    // residual of the first-order system.
    let damped = cloth(8, 1e3, 2.0, 0.1);
    let state = shaken(&damped, 0.01, 9);
    let direct = solve(&damped, &state, h, &with(LinearSolver::Direct), &b);
    let mut jacobian = damped.jacobian_matrix(&state);
    damped.jacobian(0.0, &state, &mut jacobian);
    let (dx, dv) = jacobian.force_jacobians();
    let half = n / 2;
    let mass = damped.masses();
    let pinned = |row: usize| damped.pinned().contains(&(row / 3));
    let w = odyn::nalgebra::DMatrix::from_fn(n, n, |r, c| {
        let identity = f64::from(u8::from(r == c));
        match (r < half, c < half) {
            (true, true) => identity,
            (true, false) => -h * f64::from(u8::from(r + half == c)),
            // Pinned particles feel no force: their acceleration rows are zero.
            (false, _) if pinned(r - half) => identity,
            (false, true) => identity - h * dx[(r - half, c)] / mass[(r - half) / 3],
            (false, false) => identity - h * dv[(r - half, c - half)] / mass[(r - half) / 3],
        }
    });
    for linear in krylovs() {
        let x = solve(&damped, &state, h, &with(linear), &b);
        let d = difference(&x, &direct);
        assert!(
            d < 1e-9,
            "{linear:?}: differs from the direct solve by {d:e}"
        );
        let residual = relative_residual(&w, &x, &b);
        // The solve's test is on the velocity form's residual (1e-12); the first-order
        // system's rows are that residual scaled by M⁻¹ and mixed with h·Δv, about 1e3 larger.
        assert!(residual < 1e-8, "{linear:?}: residual {residual:e}");
    }
}

/// The final state of `steps` steps of `I` on `model` from its state at `dt`.
fn stepped<M: Jacobian, I: Integrator<M>>(
    model: &M,
    dt: f64,
    steps: usize,
    newton: &NewtonOptions,
) -> (Vec<f64>, odyn::Stats) {
    let mut stepper = Stepper::<M, I>::with_newton(model, model.state(), 0.0, dt, newton).unwrap();
    for _ in 0..steps {
        stepper.step().unwrap();
    }
    (stepper.state().as_slice().to_vec(), stepper.stats())
}

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

/// The factorization and Krylov counts of 10 implicit Euler steps of `model`.
fn counts_of<M>(model: &M, dt: f64, newton: &NewtonOptions) -> odyn::particles::Factorizations
where
    M: Jacobian,
    M::Matrix: Counted,
{
    let mut stepper =
        Stepper::<M, ImplicitEuler<M>>::with_newton(model, model.state(), 0.0, dt, newton).unwrap();
    for _ in 0..10 {
        stepper.step().unwrap();
    }
    stepper.integrator().matrix().counts()
}

/// The Jacobians that count their factorizations.
trait Counted {
    fn counts(&self) -> odyn::particles::Factorizations;
}
impl Counted for odyn::grid::GridJacobian {
    fn counts(&self) -> odyn::particles::Factorizations {
        self.factorizations()
    }
}
impl Counted for odyn::particles::ParticleJacobian<3> {
    fn counts(&self) -> odyn::particles::Factorizations {
        self.factorizations()
    }
}

#[test]
fn auto_chooses_krylov_for_big_grids_only() {
    let auto = NewtonOptions::default();
    assert_eq!(auto.linear, LinearSolver::Auto);
    // 22² cells × 2 fields = 968 unknowns: below the threshold, direct.
    let small: GrayScott = gray_scott(22, Boundary::Periodic);
    let counts = counts_of(&small, 1.0, &auto);
    assert_eq!(counts.krylov.solves, 0, "{counts:?}");
    assert!(counts.lu + counts.cholesky > 0);
    // 23² × 2 = 1 058: Krylov, block Jacobi, no factorization at all.
    let big: GrayScott = gray_scott(23, Boundary::Periodic);
    let counts = counts_of(&big, 1.0, &auto);
    assert!(counts.krylov.solves >= 10, "{counts:?}");
    assert_eq!(counts.krylov.preconditioners, counts.krylov.solves);
    assert_eq!(
        (counts.lu, counts.cholesky, counts.krylov.fallbacks),
        (0, 0, 0)
    );
    // The same grid with cells 120× finer (h·D_u/Δx² = 125 at h = 1), linearized steps (solved
    // to `Krylov::rtol`, 1e-8): block Jacobi needs more than 50 iterations, so Auto moves on
    // for the rest of the run. Its moves (to Fourier, to multigrid, to the direct solver),
    // then factorizations and fallbacks, on n² cells of side `dx` with `boundary`:
    let linearized = NewtonOptions {
        linearized: true,
        ..auto
    };
    let moves = |n: usize, boundary: Boundary, dx: f64| {
        let mut fine: GrayScott = gray_scott(n, boundary);
        fine.dx = dx;
        let c = counts_of(&fine, 1.0, &linearized);
        let k = c.krylov;
        (
            k.switched_to_fourier,
            k.switched_to_multigrid,
            k.switched_to_direct,
            c.lu + c.cholesky,
            k.fallbacks,
        )
    };
    // Periodic: to Fourier, which needs no more than 50 and never factorizes.
    assert_eq!(moves(23, Boundary::Periodic, 4e-4), (1, 0, 0, 0, 0));
    // Zero-flux edges (no Fourier) below `MULTIGRID_FROM`: Auto gives Krylov up and factorizes
    // from then on.
    let (fourier, multigrid, direct, factorizations, _) = moves(23, Boundary::Neumann, 4e-4);
    assert_eq!((fourier, multigrid, direct), (0, 0, 1));
    assert!(factorizations > 0);
    // 64² cells (8 192 unknowns, `MULTIGRID_FROM`), zero-flux: on with multigrid, which needs
    // no more than 50 iterations, and never factorizes.
    assert_eq!(moves(64, Boundary::Neumann, 4e-4), (0, 1, 0, 0, 0));
    // Cells 5× coarser than that (h·D_u/Δx² = 5): block Jacobi takes 26 iterations a solve on
    // the periodic grid, 31 with zero-flux edges (10 steps, measured), more than
    // `tries_fourier_after` but within `AUTO_DIRECT_ABOVE`. The periodic grid moves to Fourier
    // (about 5 a solve then); the other keeps block Jacobi, which still pays there.
    assert_eq!(moves(23, Boundary::Periodic, 2e-3), (1, 0, 0, 0, 0));
    assert_eq!(moves(23, Boundary::Neumann, 2e-3), (0, 0, 0, 0, 0));
    // A cloth of 20² particles (1 200 unknowns in the velocity form) stays direct.
    let cloth = cloth(20, 1e3, 0.0, 0.1);
    let counts = counts_of(&cloth, 1.0 / 60.0, &auto);
    assert_eq!(counts.krylov.solves, 0, "{counts:?}");
}

#[test]
fn a_krylov_solve_that_cannot_converge_falls_back_to_the_direct_solve() {
    // One iteration to a residual of 1e-14: never enough, so every solve is redone directly,
    // counted, and the run equals the direct run.
    let mut model: GrayScott = gray_scott(24, Boundary::Periodic);
    model.dx = 2.5 / 256.0;
    let starved = with(LinearSolver::Krylov(Krylov {
        rtol: 1e-14,
        max_iters: 1,
        ..Krylov::default()
    }));
    let counts = counts_of(&model, 10.0, &starved);
    assert!(counts.krylov.fallbacks >= 10, "{counts:?}");
    assert_eq!(counts.krylov.solves, 0, "{counts:?}");
    assert_eq!(counts.lu + counts.cholesky, counts.krylov.fallbacks);
    let (x, _) = stepped::<GrayScott, ImplicitEuler<_>>(&model, 10.0, 10, &starved);
    let (y, _) =
        stepped::<GrayScott, ImplicitEuler<_>>(&model, 10.0, 10, &with(LinearSolver::Direct));
    assert_eq!(x, y);
}

#[test]
fn bad_krylov_options_are_typed_errors() {
    let model: GrayScott = gray_scott(8, Boundary::Periodic);
    for (krylov, field) in [
        (
            Krylov {
                rtol: 0.0,
                ..Krylov::default()
            },
            "Krylov::rtol",
        ),
        (
            Krylov {
                rtol: 1.5,
                ..Krylov::default()
            },
            "Krylov::rtol",
        ),
        (
            Krylov {
                rtol: f64::NAN,
                ..Krylov::default()
            },
            "Krylov::rtol",
        ),
        (
            Krylov {
                bdf_rtol: 1.0,
                ..Krylov::default()
            },
            "Krylov::bdf_rtol",
        ),
        (
            Krylov {
                max_iters: 0,
                ..Krylov::default()
            },
            "Krylov::max_iters",
        ),
        (
            Krylov {
                preconditioner: Preconditioner::Factorization { refresh_above: 0 },
                ..Krylov::default()
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

#[test]
fn multigrid_iterations_stay_flat_as_the_grid_is_refined() {
    // Gray–Scott with cells so fine that diffusion dominates (h·D_u/Δx² = 125 at h = 1), ten
    // linearized implicit Euler steps solved to 1e-8 at 32² and 64² cells. Block Jacobi's
    // iterations grow with the grid's side (CG on a Laplacian: ∝ √κ ∝ 1/Δx); a multigrid
    // V-cycle removes the smooth error block Jacobi cannot, so its count stays nearly flat
    // (Vaněk, Mandel & Brezina 1996, §6).
    let iterations = |n: usize, preconditioner: Preconditioner| {
        let mut model: GrayScott = gray_scott(n, Boundary::Periodic);
        model.dx = 4e-4;
        let newton = NewtonOptions {
            linearized: true,
            linear: LinearSolver::Krylov(Krylov {
                preconditioner,
                warm_start: false,
                ..Krylov::default()
            }),
            ..NewtonOptions::default()
        };
        let counts = counts_of(&model, 1.0, &newton);
        assert_eq!(counts.krylov.fallbacks, 0, "{counts:?}");
        counts.krylov.iterations as f64 / counts.krylov.solves as f64
    };
    let jacobi = [32, 64].map(|n| iterations(n, Preconditioner::BlockJacobi));
    let multigrid = [32, 64].map(|n| iterations(n, Preconditioner::Multigrid));
    // Measured: block Jacobi 51 and 75 a solve, multigrid 6.8 and 6.0.
    assert!(jacobi[1] > 1.3 * jacobi[0], "{jacobi:?}");
    assert!(multigrid[1] < 1.1 * multigrid[0], "{multigrid:?}");
    assert!(
        multigrid[1] < jacobi[1] / 5.0,
        "{multigrid:?} against {jacobi:?}"
    );
}

#[test]
fn krylov_solves_inside_newton_stop_at_the_forcing_term() {
    // Full-Newton implicit Euler on Gray–Scott (24², h = 10 at Pearson's Δx, h·D_u/Δx² ≈ 2):
    // with the default forcing term (newton_rtol = 1e-3) Newton corrects what each inexact solve
    // leaves, so ten steps end within Newton's own tolerance (1e-10 relative) of the direct
    // run, for fewer Krylov iterations than solves to 1e-12.
    let mut model: GrayScott = gray_scott(24, Boundary::Periodic);
    model.dx = 2.5 / 256.0;
    let newton = |newton_rtol: f64| {
        with(LinearSolver::Krylov(Krylov {
            preconditioner: Preconditioner::Multigrid,
            newton_rtol,
            ..Krylov::default()
        }))
    };
    let (loose, tight) = (newton(1e-3), newton(1e-12));
    let direct =
        stepped::<GrayScott, ImplicitEuler<_>>(&model, 10.0, 10, &with(LinearSolver::Direct)).0;
    let x = stepped::<GrayScott, ImplicitEuler<_>>(&model, 10.0, 10, &loose).0;
    let d = difference(&x, &direct);
    let (a, b) = (
        counts_of(&model, 10.0, &loose),
        counts_of(&model, 10.0, &tight),
    );
    assert!(d < 1e-9, "{d:e}");
    // Measured: 220 iterations over 73 solves against 655 over 71.
    assert!(
        2 * a.krylov.iterations < b.krylov.iterations,
        "{a:?} against {b:?}"
    );
}

/// The Fourier preconditioner inverts I − h·J exactly where J is the same at every cell (a
/// uniform state of a periodic Gray–Scott grid: constant diffusion, the same reaction block):
/// every solve then converges within its first iteration. On a varying state it still solves to
/// the tolerance (the solves above); on a grid that is not periodic, or for particles, the run
/// goes on with block Jacobi.
#[test]
fn fourier_solves_a_uniform_grid_in_one_iteration() {
    let fourier = with(LinearSolver::Krylov(Krylov {
        preconditioner: Preconditioner::Fourier,
        ..Krylov::default()
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
/// a linearized solve (to 1e-8) on average, more than `tries_fourier_after` (4.3), and Fourier
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
    let block_jacobi = LinearSolver::Krylov(Krylov::default());
    let (auto, block_jacobi) = (counts(LinearSolver::Auto), counts(block_jacobi));
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
fn counts_per_step(model: &Stiffening, linear: LinearSolver, steps: usize) -> Vec<KrylovCounts> {
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
    let auto = counts_per_step(&model, LinearSolver::Auto, steps);
    let block_jacobi = counts_per_step(&model, LinearSolver::Krylov(Krylov::default()), steps);
    // Tried at once and given back, block Jacobi's again for the next steps.
    assert_eq!(auto[1].switched_to_fourier, 0, "{:?}", auto[1]);
    // Fourier for the last steps.
    assert_eq!(
        auto[steps - 1].switched_to_fourier,
        1,
        "{:?}",
        auto[steps - 1]
    );
    let last = |c: &[KrylovCounts]| c[steps - 1].iterations - c[steps - 2].iterations;
    let cost = LinearSolver::fourier_iteration_cost(n * n);
    assert!(
        last(&auto) as f64 * cost < last(&block_jacobi) as f64,
        "the last step: {} Fourier iterations against {} block-Jacobi ones",
        last(&auto),
        last(&block_jacobi)
    );
}
