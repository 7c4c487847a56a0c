//! The Krylov solves against the direct solve, on a symmetric and an unsymmetric matrix; a
//! singular matrix behind a failed Krylov solve; a cloned solver.

use super::*;
use crate::linalg::krylov::{Solves, Structure};
use crate::{KrylovOptions, LinearSolver, Preconditioner};

/// The couplings of an m × m grid's five-point stencil, each once (row < column).
fn five_point(m: usize) -> Vec<(usize, usize)> {
    let mut entries = Vec::new();
    for i in 0..m {
        for j in 0..m {
            let k = i * m + j;
            if j + 1 < m {
                entries.push((k, k + 1));
            }
            if i + 1 < m {
                entries.push((k, k + m));
            }
        }
    }
    entries
}

/// −1 + `skew` above the diagonal and −1 − `skew` below it at every coupling, and a diagonal of
/// 4.5 to 5.1: strictly diagonally dominant for |skew| ≤ 1 (a row's couplings sum to 4 in
/// magnitude), so regular, and positive definite when `skew` is 0.
fn fill(s: &mut SparseSolver, entries: &[(usize, usize)], skew: f64) {
    for &(r, c) in entries {
        let (a, b) = (s.slot(r, c), s.slot(c, r));
        s.values[a] = -1.0 + skew;
        s.values[b] = -1.0 - skew;
    }
    for i in 0..s.rhs.len() {
        let d = s.slot(i, i);
        s.values[d] = 4.5 + (i % 7) as f64 * 0.1;
    }
}

/// max |aᵢ − bᵢ|.
fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// A 2-D Laplacian-like SPD matrix, and an unsymmetric one, solved directly and by each
/// Krylov configuration: same answer to the Krylov tolerance.
#[test]
fn krylov_solves_agree_with_the_direct_solve() {
    let m = 12;
    let n = m * m;
    let entries = five_point(m);
    for skew in [0.0, 0.3] {
        let fill = |s: &mut SparseSolver| fill(s, &entries, skew);
        let b: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
        let mut direct = SparseSolver::new(n, &entries);
        fill(&mut direct);
        direct.factorize().expect("the matrix is regular");
        direct.rhs.copy_from_slice(&b);
        direct.substitute().expect("the matrix is regular");
        for preconditioner in [
            Preconditioner::BlockJacobi,
            Preconditioner::Ilu0,
            Preconditioner::Factorization { refresh_above: 5 },
        ] {
            let mut krylov = SparseSolver::new(n, &entries);
            krylov.set_blocks(2, (0..n).collect());
            let linear = LinearSolver::Krylov(KrylovOptions {
                preconditioner,
                rtol: 1e-12,
                ..KrylovOptions::default()
            });
            krylov.configure(&linear, Structure::Field, Solves::OneStep);
            fill(&mut krylov);
            for _ in 0..2 {
                krylov.factorize().expect("the matrix is regular");
                krylov.rhs.copy_from_slice(&b);
                krylov.substitute().expect("the matrix is regular");
                let error = largest_difference(&krylov.rhs, &direct.rhs);
                assert!(error < 1e-10, "{skew} {preconditioner:?}: {error:e}");
            }
            assert_eq!(krylov.counts.krylov.fallbacks, 0, "{:?}", krylov.counts);
            assert_eq!(krylov.counts.krylov.solves, 2);
        }
    }
}

/// A singular matrix whose diagonal blocks are regular: block Jacobi builds, the Krylov solve
/// cannot converge (b is outside the range of A = [[1, 1], [1, 1]]), and the direct solve
/// that takes over finds A singular. The failure is a typed error, not a right-hand side of NaN
/// left for the caller to find.
#[test]
fn a_singular_matrix_behind_a_failed_krylov_solve_is_a_typed_error() {
    let mut solver = SparseSolver::new(2, &[(0, 1)]);
    let linear = LinearSolver::Krylov(KrylovOptions {
        preconditioner: Preconditioner::BlockJacobi,
        ..KrylovOptions::default()
    });
    solver.configure(&linear, Structure::Particles, Solves::OneStep);
    solver.values.fill(1.0);
    solver
        .factorize()
        .expect("block Jacobi's 1×1 blocks are regular");
    solver.rhs.copy_from_slice(&[1.0, -1.0]);
    assert_eq!(solver.substitute(), Err(SolveError::Singular));
    assert_eq!(
        solver.counts.krylov.fallbacks, 1,
        "the Krylov solve failed first"
    );
}

/// A solver cloned after a factorization and a solve (an integrator copied mid-run) solves the
/// next right-hand side to the same bits as the original, under the direct solve and each
/// Krylov preconditioner: every buffer, factor and warm start is copied.
#[test]
fn a_cloned_solver_solves_like_the_original() {
    let m = 24;
    let n = m * m;
    let entries = five_point(m);
    let b: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
    for linear in [
        LinearSolver::Direct,
        LinearSolver::Krylov(KrylovOptions::default()),
        LinearSolver::Krylov(KrylovOptions {
            preconditioner: Preconditioner::Ilu0,
            ..KrylovOptions::default()
        }),
        LinearSolver::Krylov(KrylovOptions {
            preconditioner: Preconditioner::Multigrid,
            ..KrylovOptions::default()
        }),
        LinearSolver::Krylov(KrylovOptions {
            preconditioner: Preconditioner::Factorization { refresh_above: 5 },
            ..KrylovOptions::default()
        }),
    ] {
        let mut solver = SparseSolver::new(n, &entries);
        solver.configure(&linear, Structure::Field, Solves::OneStep);
        fill(&mut solver, &entries, 0.2);
        solver.factorize().expect("regular");
        solver.rhs.copy_from_slice(&b);
        solver.substitute().expect("regular");
        let mut copy = solver.clone();
        let next: Vec<f64> = b.iter().map(|v| 0.5 * v + 1.0).collect();
        for s in [&mut solver, &mut copy] {
            s.rhs.copy_from_slice(&next);
            s.substitute().expect("regular");
        }
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&solver.rhs), bits(&copy.rhs), "{linear:?}");
        assert_eq!(solver.counts, copy.counts, "{linear:?}");
    }
}

/// Configured again (BDF's first attempt changes what its solves are for), a Krylov solver
/// keeps what it has made: the factorization `Preconditioner::Factorization` substitutes in
/// serves the next solve without a new one, and the solve still matches the direct answer.
#[test]
fn a_solver_configured_again_keeps_its_preconditioners() {
    let m = 12;
    let entries = five_point(m);
    let b: Vec<f64> = (0..m * m).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
    let mut direct = SparseSolver::new(m * m, &entries);
    fill(&mut direct, &entries, 0.0);
    direct.factorize().expect("regular");
    direct.rhs.copy_from_slice(&b);
    direct.substitute().expect("regular");
    let linear = LinearSolver::Krylov(KrylovOptions {
        preconditioner: Preconditioner::Factorization { refresh_above: 5 },
        rtol: 1e-12,
        ..KrylovOptions::default()
    });
    let mut solver = SparseSolver::new(m * m, &entries);
    solver.configure(&linear, Structure::Field, Solves::OneStep);
    fill(&mut solver, &entries, 0.0);
    solver.factorize().expect("regular");
    solver.rhs.copy_from_slice(&b);
    solver.substitute().expect("regular");
    assert_eq!(solver.counts.cholesky, 1);
    solver.configure(&linear, Structure::Field, Solves::Newton);
    solver.factorize().expect("regular");
    solver.rhs.copy_from_slice(&b);
    solver.substitute().expect("regular");
    assert_eq!(solver.counts.cholesky, 1, "{:?}", solver.counts);
    let error = largest_difference(&solver.rhs, &direct.rhs);
    assert!(error < 1e-10, "{error:e}");
}
