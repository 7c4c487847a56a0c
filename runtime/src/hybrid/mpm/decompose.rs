//! The 2×2 polar decomposition and singular value decomposition the constitutive models need,
//! in closed form with square roots only: no iteration, and no transcendental function, so the
//! same bits on every platform (IEEE 754 rounds √ exactly).

use nalgebra::Matrix2;

/// F = R·S with R the rotation nearest F and S symmetric: R = [[c, −s], [s, c]] with
/// (c, s) ∝ (F₀₀ + F₁₁, F₁₀ − F₀₁), so that RᵀF is symmetric (its off-diagonal difference is
/// c·(F₀₁ − F₁₀) + s·(F₀₀ + F₁₁) = 0). R = I when both vanish: F is then symmetric already.
#[inline]
pub(crate) fn rotation(f: &Matrix2<f64>) -> Matrix2<f64> {
    let (a, b) = (f[(0, 0)] + f[(1, 1)], f[(1, 0)] - f[(0, 1)]);
    let norm = (a * a + b * b).sqrt();
    if norm == 0.0 || !norm.is_finite() {
        return Matrix2::identity();
    }
    let (c, s) = (a / norm, b / norm);
    Matrix2::new(c, -s, s, c)
}

/// F = U·diag(σ)·Vᵀ with U and V rotations: the polar decomposition F = R·S, then the symmetric
/// S = V·diag(σ)·Vᵀ by one Jacobi rotation (Golub & Van Loan, *Matrix Computations*, 4th ed.,
/// §8.5.2, the stable choice of t), and U = R·V. With det F < 0 one σ is negative (this
/// "rotation variant" SVD of Irving, Teran & Fedkiw 2004 keeps U and V proper rotations).
pub(crate) fn svd(f: &Matrix2<f64>) -> (Matrix2<f64>, [f64; 2], Matrix2<f64>) {
    let r = rotation(f);
    let s = r.transpose() * f;
    let (a, b, d) = (s[(0, 0)], 0.5 * (s[(0, 1)] + s[(1, 0)]), s[(1, 1)]);
    if b == 0.0 {
        return (r, [a, d], Matrix2::identity());
    }
    // The rotation by θ with tan θ = t zeroes the off-diagonal entry: t² + 2τt − 1 = 0.
    let tau = (d - a) / (2.0 * b);
    let t = if tau.is_finite() {
        tau.signum() / (tau.abs() + (1.0 + tau * tau).sqrt())
    } else {
        0.0
    };
    let c = 1.0 / (1.0 + t * t).sqrt();
    let sn = t * c;
    let v = Matrix2::new(c, sn, -sn, c);
    let sigma = [a - t * b, d + t * b];
    (r * v, sigma, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random_matrices() -> impl Iterator<Item = Matrix2<f64>> {
        let mut draw = crate::linalg::signed(11);
        (0..2000).map(move |k| {
            let scale = [1.0, 1e-6, 1e6][k % 3];
            Matrix2::new(draw(), draw(), draw(), draw()) * scale
        })
    }

    /// RᵀF symmetric, R a rotation; U·Σ·Vᵀ = F with U, V rotations; on random matrices of
    /// three scales and on degenerate ones.
    #[test]
    fn decompositions_reconstruct_their_matrix() {
        let special = [
            Matrix2::identity(),
            Matrix2::zeros(),
            Matrix2::new(1.0, 0.0, 0.0, -1.0),
            Matrix2::new(0.0, 1.0, 1.0, 0.0),
            Matrix2::new(2.0, 0.0, 0.0, 2.0),
            Matrix2::new(1.0, 1e-300, 1e-300, 1.0),
            Matrix2::new(1.0, 0.5, 0.5, 1.0),
        ];
        for f in special.into_iter().chain(random_matrices()) {
            let scale = f.abs().max().max(1e-300);
            let r = rotation(&f);
            let s = r.transpose() * f;
            assert!((r.determinant() - 1.0).abs() < 1e-14);
            assert!((s[(0, 1)] - s[(1, 0)]).abs() <= 1e-14 * scale, "{f}");
            let (u, sigma, v) = svd(&f);
            let back = u * Matrix2::from_diagonal(&sigma.into()) * v.transpose();
            assert!((back - f).abs().max() <= 1e-14 * scale, "{f} → {back}");
            assert!((u.determinant() - 1.0).abs() < 1e-14);
            assert!((v.determinant() - 1.0).abs() < 1e-14);
        }
    }
}
