//! Krylov solves against the direct solve on Gray–Scott and cloth matrices, multigrid's
//! iterations under refinement, and solves inside Newton stopping at the forcing term.

use odyn::grid::Boundary;
use odyn::integrators::ImplicitEuler;
use odyn::particles::ParticleState;
use odyn::prelude::*;
use odyn::{Jacobian, KrylovOptions, LinearSolver, NewtonOptions, Preconditioner};

use super::{counts_of, difference, krylovs, relative_residual, solve, stepped, with};
use crate::grid::{GrayScott, gray_scott};
use crate::particles::{cloth, shaken};

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
            linear: LinearSolver::Krylov(KrylovOptions {
                preconditioner,
                warm_start: false,
                ..KrylovOptions::default()
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
        with(LinearSolver::Krylov(KrylovOptions {
            preconditioner: Preconditioner::Multigrid,
            newton_rtol,
            ..KrylovOptions::default()
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
