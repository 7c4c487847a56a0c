//! `Auto`'s choice of Krylov for big grids only, and the fallback to the direct solve when a
//! Krylov solve cannot converge.

use odyn::grid::Boundary;
use odyn::integrators::ImplicitEuler;
use odyn::prelude::*;
use odyn::{AutoPolicy, KrylovOptions, LinearSolver, NewtonOptions};

use super::{counts_of, stepped, with};
use crate::grid::{GrayScott, gray_scott};
use crate::particles::cloth;

#[test]
fn auto_chooses_krylov_for_big_grids_only() {
    let auto = NewtonOptions::default();
    assert_eq!(auto.linear, LinearSolver::Auto(odyn::AutoPolicy::default()));
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
    // to `KrylovOptions::rtol`, 1e-8): block Jacobi needs more than 50 iterations, so Auto moves on
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
    // Zero-flux edges (no Fourier) below `AutoPolicy::multigrid_from`: Auto gives Krylov up and factorizes
    // from then on.
    let (fourier, multigrid, direct, factorizations, _) = moves(23, Boundary::Neumann, 4e-4);
    assert_eq!((fourier, multigrid, direct), (0, 0, 1));
    assert!(factorizations > 0);
    // 64² cells (8 192 unknowns, `AutoPolicy::multigrid_from`), zero-flux: on with multigrid, which needs
    // no more than 50 iterations, and never factorizes.
    assert_eq!(moves(64, Boundary::Neumann, 4e-4), (0, 1, 0, 0, 0));
    // Cells 5× coarser than that (h·D_u/Δx² = 5): block Jacobi takes 26 iterations a solve on
    // the periodic grid, 31 with zero-flux edges (10 steps, measured), more than
    // `AutoPolicy::fourier_iteration_cost` but within `AutoPolicy::direct_above`. The periodic grid moves to Fourier
    // (about 5 a solve then); the other keeps block Jacobi, which still pays there.
    assert_eq!(moves(23, Boundary::Periodic, 2e-3), (1, 0, 0, 0, 0));
    assert_eq!(moves(23, Boundary::Neumann, 2e-3), (0, 0, 0, 0, 0));
    // A cloth of 20² particles (1 200 unknowns in the velocity form) stays direct.
    let cloth = cloth(20, 1e3, 0.0, 0.1);
    let counts = counts_of(&cloth, 1.0 / 60.0, &auto);
    assert_eq!(counts.krylov.solves, 0, "{counts:?}");
}

/// `AutoPolicy`'s thresholds move `Auto`'s choices: the 968-unknown grid that is direct by
/// default goes Krylov from `krylov_from` = 900; the 1 058-unknown one stays direct with
/// `krylov_from` = `usize::MAX`; the coarse zero-flux grid (block Jacobi at 31 iterations a
/// solve, within the default 50) gives Krylov up with `direct_above` = 20. A Fourier cost that is
/// not finite and positive is refused before the run, naming the field.
#[test]
fn the_auto_policy_moves_its_thresholds() {
    let auto = |policy: AutoPolicy| NewtonOptions {
        linear: LinearSolver::Auto(policy),
        ..NewtonOptions::default()
    };
    let small: GrayScott = gray_scott(22, Boundary::Periodic);
    let early = auto(AutoPolicy {
        krylov_from: 900,
        ..AutoPolicy::default()
    });
    assert!(counts_of(&small, 1.0, &early).krylov.solves >= 10);
    let big: GrayScott = gray_scott(23, Boundary::Periodic);
    let never = auto(AutoPolicy {
        krylov_from: usize::MAX,
        ..AutoPolicy::default()
    });
    let counts = counts_of(&big, 1.0, &never);
    assert_eq!(counts.krylov.solves, 0, "{counts:?}");
    let mut coarse: GrayScott = gray_scott(23, Boundary::Neumann);
    coarse.dx = 2e-3;
    let impatient = NewtonOptions {
        linearized: true,
        ..auto(AutoPolicy {
            direct_above: 20,
            ..AutoPolicy::default()
        })
    };
    let counts = counts_of(&coarse, 1.0, &impatient);
    assert_eq!(counts.krylov.switched_to_direct, 1, "{counts:?}");
    for cost in [f64::NAN, 0.0, -0.33, f64::INFINITY] {
        let bad = auto(AutoPolicy {
            fourier_cost_per_log2: cost,
            ..AutoPolicy::default()
        });
        match big.simulate().newton(bad).dt(1.0).steps(1).run() {
            Err(odyn::Error::InvalidInput { field, .. }) => {
                assert_eq!(field, "AutoPolicy::fourier_cost_per_log2")
            }
            other => panic!("{cost}: expected InvalidInput, got {other:?}"),
        }
    }
}

/// Extreme policies on grids down to one cell, under every implicit method at a fixed step:
/// Krylov from 0 unknowns, giving up after any iteration, multigrid from 0 unknowns, on
/// periodic and zero-flux edges, stiff cells (h·D/Δx² = 62). Each run, and one with plain Krylov
/// options, ends where the direct run does to within 1e-6 relatively, and none panics. Implicit
/// Euler and BDF stop Newton at `NewtonOptions::tol` = 1e-10 with updates solved to a forcing
/// term of 1e-3 (measured at most 3e-9 apart); the Rosenbrock stages' solves, to
/// `KrylovOptions::rtol` = 1e-8, are corrected by nothing, and their error grows by the
/// matrix's condition (measured at most 1.1e-7 apart). (Found by this probe: fixed-step BDF solved its Newton updates to
/// CVODE's loose 0.05 while stopping by SciPy's test, and ended 1e-4 from the direct run on the
/// 2² grid.)
#[test]
fn extreme_auto_policies_run_like_the_direct_solve() {
    let extremes = [
        AutoPolicy {
            krylov_from: 0,
            direct_above: 0,
            multigrid_from: 0,
            fourier_cost_per_log2: 1e-300,
        },
        AutoPolicy {
            krylov_from: 0,
            direct_above: usize::MAX,
            multigrid_from: 0,
            fourier_cost_per_log2: 1e300,
        },
    ];
    // A periodic side needs 3 cells at least.
    let grids = [
        (1, Boundary::Neumann),
        (2, Boundary::Neumann),
        (3, Boundary::Periodic),
        (5, Boundary::Neumann),
        (5, Boundary::Periodic),
    ];
    for (n, boundary) in grids {
        {
            let mut model: GrayScott = gray_scott(n, boundary);
            model.dx = 4e-4;
            for method in [
                Method::ImplicitEuler,
                Method::Rosenbrock23,
                Method::Rodas5P,
                Method::Bdf,
            ] {
                let run = |linear: LinearSolver| {
                    let newton = NewtonOptions {
                        linear,
                        ..NewtonOptions::default()
                    };
                    model
                        .simulate()
                        .integrator(method)
                        .newton(newton)
                        .dt(0.5)
                        .steps(4)
                        .run()
                        .map(|run| run.last().state.as_slice().to_vec())
                };
                let direct = run(LinearSolver::Direct).unwrap();
                let plain = LinearSolver::Krylov(KrylovOptions::default());
                for linear in extremes.map(LinearSolver::Auto).into_iter().chain([plain]) {
                    let auto = run(linear)
                        .unwrap_or_else(|e| panic!("{n}² {boundary:?} {method} {linear:?}: {e}"));
                    let apart = super::difference(&auto, &direct);
                    assert!(
                        apart < 1e-6,
                        "{n}² {boundary:?} {method} {linear:?}: {apart:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_krylov_solve_that_cannot_converge_falls_back_to_the_direct_solve() {
    // One iteration to a residual of 1e-14: never enough, so every solve is redone directly,
    // counted, and the run equals the direct run.
    let mut model: GrayScott = gray_scott(24, Boundary::Periodic);
    model.dx = 2.5 / 256.0;
    let starved = with(LinearSolver::Krylov(KrylovOptions {
        rtol: 1e-14,
        max_iterations: 1,
        ..KrylovOptions::default()
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

/// A run stopped part-way (its step budget spent) still reports the linear work it did: the
/// partial trajectory's `stats.linear` counts the Krylov solves `Auto` made on a 1 058-unknown
/// grid, one or more per Newton iteration of each attempted step.
#[test]
fn a_partial_run_reports_its_linear_work() {
    let model: GrayScott = gray_scott(23, Boundary::Periodic);
    let (trajectory, failure) = model
        .simulate()
        .integrator(Method::Bdf)
        .tolerances(1e-6, 1e-9)
        .adaptive(odyn::AdaptiveOptions {
            max_steps: 5,
            ..odyn::AdaptiveOptions::default()
        })
        .duration(1e3)
        .run_partial()
        .unwrap();
    assert!(
        matches!(failure, Some(odyn::Error::MaxSteps { .. })),
        "{failure:?}"
    );
    let stats = trajectory.stats;
    assert!(stats.linear.krylov.solves >= stats.steps, "{stats}");
    assert_eq!(stats.linear.krylov.solves, stats.linear_solves, "{stats}");
}
