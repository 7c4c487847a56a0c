//! Cramer's rule for the small dense Newton matrices against an LU, and singular ones reported.

use super::*;

/// Cramer's rule (1×1 to 3×3) against nalgebra's pivoted LU on the same W = I − c·J, and
/// adj(W)·W = det W·I, which defines the adjugate; a singular W is reported.
fn check<const N: usize>(jacobian: nalgebra::SMatrix<f64, N, N>)
where
    nalgebra::SMatrix<f64, N, N>: NewtonMatrix,
{
    let c = 0.3;
    let w = nalgebra::SMatrix::<f64, N, N>::identity() - jacobian * c;
    let (adj, det) = adjugate(&w).expect("up to 3×3");
    let dynamic = nalgebra::DMatrix::from_column_slice(N, N, w.as_slice());
    assert!((det - dynamic.clone().determinant()).abs() <= 1e-14 * det.abs().max(1.0));
    let identity = adj * w / det;
    assert!((identity - nalgebra::SMatrix::<f64, N, N>::identity()).amax() <= 1e-14);

    let b: Vec<f64> = (0..N).map(|i| 1.0 - 0.7 * i as f64).collect();
    let reference = dynamic
        .lu()
        .solve(&nalgebra::DVector::from_column_slice(&b));
    let mut matrix = jacobian;
    let mut factors = matrix.factors();
    matrix.factorize(c, &mut factors).expect("W is regular");
    let mut x = b.clone();
    matrix.solve(&mut factors, &mut x).expect("x is finite");
    let reference = reference.expect("W is regular");
    for (xi, ri) in x.iter().zip(reference.iter()) {
        assert!((xi - ri).abs() <= 1e-13 * ri.abs().max(1.0), "{xi} vs {ri}");
    }
}

#[test]
fn cramers_rule_solves_like_an_lu() {
    check(nalgebra::SMatrix::<f64, 1, 1>::new(-4.0));
    check(nalgebra::SMatrix::<f64, 2, 2>::new(0.0, 1.0, -5.0, -2.5));
    // The Lorenz Jacobian at (1, 2, 3), σ = 10, ρ = 28, β = 8/3: nonsymmetric, every
    // entry of the adjugate from a different minor.
    check(nalgebra::SMatrix::<f64, 3, 3>::new(
        -10.0,
        10.0,
        0.0,
        25.0,
        -1.0,
        -1.0,
        2.0,
        1.0,
        -8.0 / 3.0,
    ));
}

#[test]
fn a_singular_small_matrix_is_reported() {
    // W = I − 1·J = 0 for J = I: every size's determinant is zero.
    let mut j = nalgebra::SMatrix::<f64, 3, 3>::identity();
    let mut factors = j.factors();
    assert_eq!(
        j.factorize(1.0, &mut factors),
        Err(FactorizeError::Singular)
    );
    let mut j = nalgebra::SMatrix::<f64, 2, 2>::identity();
    let mut factors = j.factors();
    assert_eq!(
        j.factorize(1.0, &mut factors),
        Err(FactorizeError::Singular)
    );
}

/// The non-finite entry of a fixed-size Jacobian, found by a vectorized reduction first: none
/// among extreme finite values (±1.797e308, subnormals, −0), and NaN, +∞ or −∞ named at its
/// (row, column) wherever it sits, against the scalar scan by columns.
fn non_finite_at_every_position<const N: usize>()
where
    nalgebra::SMatrix<f64, N, N>: NewtonMatrix,
{
    let extreme = [f64::MAX, -f64::MAX, 5e-324, -0.0, 1.0];
    let finite = nalgebra::SMatrix::<f64, N, N>::from_fn(|r, c| extreme[(r * N + c) % 5]);
    assert_eq!(finite.non_finite_entry(), None);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for row in 0..N {
            for column in 0..N {
                let mut j = finite;
                j[(row, column)] = bad;
                let (r, c, value) = j.non_finite_entry().expect("found");
                assert_eq!((r, c), (row, column));
                assert_eq!(value.to_bits(), bad.to_bits());
            }
        }
    }
}

#[test]
fn non_finite_jacobian_entries_are_found_wherever_they_are() {
    non_finite_at_every_position::<1>();
    non_finite_at_every_position::<3>();
    non_finite_at_every_position::<7>();
    non_finite_at_every_position::<20>();
}
