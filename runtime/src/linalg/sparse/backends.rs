//! Every backend through the one trait ([`LinearSolve`]), against faer's dense LU.

use faer::linalg::solvers::Solve;
use faer::sparse::{Pair, SparseColMat};
use faer::{Mat, MatRef};

use crate::linalg::direct::{Direct, NoFactors, SparseCholesky, SparseLu};
use crate::linalg::krylov::{Krylov, NoConvergence, Solves};
use crate::linalg::operator::Products;
use crate::linalg::operator::RowMatrix;
use crate::linalg::solver::{LinearSolve, SparseView};
use crate::stats::LinearWork;
use crate::{KrylovOptions, Preconditioner};
use faer::sparse::SymbolicSparseColMat;

/// An m × m grid's five-point matrix: diagonal `diagonal(i)`, −1 ± `skew` to the
/// neighbours (the transpose gets −1 ∓ `skew`): its pattern, values, and the same as a dense
/// matrix.
fn grid(
    m: usize,
    skew: f64,
    diagonal: impl Fn(usize) -> f64,
) -> (SymbolicSparseColMat<usize>, Vec<f64>, Mat<f64>) {
    let n = m * m;
    let mut dense = Mat::<f64>::zeros(n, n);
    for k in 0..n {
        dense[(k, k)] = diagonal(k);
        let (i, j) = (k / m, k % m);
        for (other, near) in [(k + 1, j + 1 < m), (k + m, i + 1 < m)] {
            if near {
                dense[(k, other)] = -1.0 + skew;
                dense[(other, k)] = -1.0 - skew;
            }
        }
    }
    let pairs: Vec<Pair<usize, usize>> = (0..n)
        .flat_map(|c| (0..n).map(move |r| (r, c)))
        .filter(|&(r, c)| dense[(r, c)] != 0.0)
        .map(|(r, c)| Pair::new(r, c))
        .collect();
    let values: Vec<f64> = pairs.iter().map(|p| dense[(p.row, p.col)]).collect();
    let (pattern, order) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).unwrap();
    let matrix = SparseColMat::new_from_argsort(pattern, &order, &values).unwrap();
    let values = matrix.val().to_vec();
    (matrix.symbolic().to_owned().unwrap(), values, dense)
}

/// The largest |xᵢ − yᵢ| over the largest |yᵢ|.
fn relative_error(x: &[f64], y: MatRef<'_, f64>) -> f64 {
    let scale = (0..x.len()).map(|i| y[(i, 0)].abs()).fold(0.0, f64::max);
    let error = (0..x.len())
        .map(|i| (x[i] - y[(i, 0)]).abs())
        .fold(0.0, f64::max);
    error / scale
}

/// Every backend, through the one trait, solves a symmetric positive definite and an
/// unsymmetric grid matrix to the same answer as faer's dense LU (an independent solve):
/// the direct ones to rounding, the Krylov ones to their tolerance (or, on the indefinite
/// matrix, [`NoConvergence`]). Cholesky refuses the symmetric indefinite matrix, and
/// [`Direct`] then solves it by LU.
#[test]
fn every_backend_solves_through_the_trait() {
    let m = 10;
    let n = m * m;
    let b: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
    let dense_solve = |dense: &Mat<f64>| {
        dense
            .partial_piv_lu()
            .solve(MatRef::from_column_major_slice(&b, n, 1))
    };
    let mut work = LinearWork::default();
    let run = |backend: &mut dyn FnMut(&SparseView<'_>, &mut [f64]) -> bool, a: &SparseView<'_>| {
        let mut x = b.clone();
        backend(a, &mut x).then_some(x)
    };
    for (skew, diagonal_shift) in [(0.0, 4.5), (0.3, 4.5), (0.0, 1.0)] {
        let (pattern, values, dense) = grid(m, skew, |k| diagonal_shift + (k % 7) as f64 * 0.1);
        let expected = dense_solve(&dense);
        let rows = RowMatrix::new(&pattern).map(|mut rows| {
            rows.update(&values);
            rows
        });
        let index: Vec<usize> = (0..n).collect();
        let a = SparseView {
            pattern: &pattern,
            values: &values,
            symmetric: skew == 0.0,
            products: rows.as_ref().map(Products::Rows),
            stencil: None,
            blocks: (2, &index),
        };
        // The symmetric matrix is D − A, A the grid's adjacency, whose eigenvalues
        // 2cos(πi/(m + 1)) + 2cos(πj/(m + 1)) lie within ±4cos(π/(m + 1)) = ±3.92 (m = 10), and D
        // the diagonal, within [shift, shift + 0.6]. By Weyl's inequality, from a shift of 4.5
        // every eigenvalue is in [0.58, 9.0]: definite. From a shift of 1 the smallest is at most
        // 1.6 − 3.92 < 0 and the largest at least 1 + 3.92 > 0: indefinite.
        let definite = diagonal_shift > 4.0;
        let mut cholesky = SparseCholesky::new();
        let factored = cholesky.set_linearisation(&a, &mut work);
        if skew == 0.0 {
            assert_eq!(
                factored.is_ok(),
                definite,
                "skew {skew}, shift {diagonal_shift}"
            );
        }
        if skew == 0.0 && definite {
            let x = run(
                &mut |a, x| cholesky.solve_in_place(a, x, &mut work).is_ok(),
                &a,
            );
            assert!(relative_error(&x.unwrap(), expected.as_ref()) < 1e-13);
        }
        let mut lu = SparseLu::new();
        lu.set_linearisation(&a, &mut work).expect("regular");
        let x = run(&mut |a, x| lu.solve_in_place(a, x, &mut work).is_ok(), &a);
        assert!(relative_error(&x.unwrap(), expected.as_ref()) < 1e-13);
        let mut direct = Direct::new();
        direct.set_linearisation(&a, &mut work).expect("regular");
        let x = run(
            &mut |a, x| direct.solve_in_place(a, x, &mut work).is_ok(),
            &a,
        );
        assert!(relative_error(&x.unwrap(), expected.as_ref()) < 1e-13);
        for preconditioner in [
            Preconditioner::BlockJacobi,
            Preconditioner::Ilu0,
            Preconditioner::Multigrid,
            Preconditioner::Factorization { refresh_above: 5 },
        ] {
            let options = KrylovOptions {
                preconditioner,
                rtol: 1e-12,
                ..KrylovOptions::default()
            };
            let mut krylov = Krylov::new(options, None, Solves::OneStep, n);
            krylov.set_linearisation(&a, &mut work).expect("built");
            let x = run(
                &mut |a, x| krylov.solve_in_place(a, x, &mut work).is_ok(),
                &a,
            );
            // On the indefinite matrix ILU(0) meets tiny pivots and BiCGSTAB does not
            // converge: the contract is then a typed failure, never a wrong answer.
            let Some(x) = x else {
                assert!(
                    !definite,
                    "{preconditioner:?}, skew {skew}, shift {diagonal_shift}: no convergence"
                );
                continue;
            };
            let error = relative_error(&x, expected.as_ref());
            // At most κ·rtol, κ ≤ 9.0/0.58 ≈ 16 for the definite matrix: 1e-8 leaves room for
            // the unsymmetric one, whose error the residual bounds less tightly.
            assert!(error < 1e-8, "{preconditioner:?}, skew {skew}: {error:e}");
        }
    }
}

/// A solve asked before any linearisation is a typed error, not a right-hand side left
/// as it was; so is a Krylov solve without products. A Fourier preconditioner asked for
/// off a grid is replaced by block Jacobi, and the solve is right.
#[test]
fn solves_without_a_linearisation_are_errors() {
    let (pattern, values, dense) = grid(4, 0.0, |_| 4.5);
    let index: Vec<usize> = (0..16).collect();
    let mut a = SparseView {
        pattern: &pattern,
        values: &values,
        symmetric: true,
        products: None,
        stencil: None,
        blocks: (1, &index),
    };
    let mut work = LinearWork::default();
    let mut x = vec![1.0; 16];
    assert_eq!(
        SparseCholesky::new().solve_in_place(&a, &mut x, &mut work),
        Err(NoFactors)
    );
    assert_eq!(
        SparseLu::new().solve_in_place(&a, &mut x, &mut work),
        Err(NoFactors)
    );
    assert_eq!(
        Direct::new().solve_in_place(&a, &mut x, &mut work),
        Err(NoFactors)
    );
    let options = KrylovOptions {
        preconditioner: Preconditioner::Fourier,
        rtol: 1e-12,
        ..KrylovOptions::default()
    };
    let mut krylov = Krylov::new(options, None, Solves::OneStep, 16);
    assert_eq!(
        krylov.solve_in_place(&a, &mut x, &mut work),
        Err(NoConvergence)
    );
    krylov
        .set_linearisation(&a, &mut work)
        .expect("block Jacobi");
    assert_eq!(
        krylov.solve_in_place(&a, &mut x, &mut work),
        Err(NoConvergence)
    );
    let mut rows = RowMatrix::new(&pattern).unwrap();
    rows.update(&values);
    a.products = Some(Products::Rows(&rows));
    krylov
        .solve_in_place(&a, &mut x, &mut work)
        .expect("converges");
    let expected = dense
        .partial_piv_lu()
        .solve(MatRef::from_column_major_slice(&[1.0; 16], 16, 1));
    assert!(relative_error(&x, expected.as_ref()) < 1e-10);
}
