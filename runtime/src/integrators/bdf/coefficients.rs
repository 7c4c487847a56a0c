//! The constants of SciPy's `BDF` (NDF coefficients, error constants, the interpolation basis)
//! and the re-sampling of the backward differences when the step size changes.

use crate::State;

/// The highest order.
pub(super) const MAX_ORDER: usize = 5;
/// Newton iterations allowed per attempt of an adaptive run (SciPy's `NEWTON_MAXITER`).
pub(super) const NEWTON_MAXITER: usize = 4;
/// Newton iterations allowed per attempt under CVODE's test (CVODE's `NLS_MAXCOR`).
pub(super) const CVODE_MAXCOR: usize = 3;
/// CVODE's test accepts a correction whose remaining error, weighted by the step's error
/// constant, is at most this fraction of the error tolerance (CVODE's `nlscoef`).
pub(super) const CVODE_NLSCOEF: f64 = 0.1;
/// CVODE's rate estimate falls by at most this factor an iteration: R = max(0.3·R, rate)
/// (CVODE's `CRDOWN`).
pub(super) const CVODE_CRDOWN: f64 = 0.3;
/// CVODE's test abandons an iteration whose update grew more than this factor (`RDIV`).
pub(super) const CVODE_RDIV: f64 = 2.0;
/// The step-size safety factor with CVODE's test, in place of SciPy's 0.9 × (2·4 + 1)/(2·4 +
/// iterations): odyn's choice, measured (`Bdf`'s doc): 0.9 stepped so close to the tolerance
/// that the looser Newton solutions tipped 6–12 % of the attempts over it.
pub(super) const CVODE_SAFETY: f64 = 0.7;
/// Bounds of the step-size ratio (SciPy's `MIN_FACTOR`, `MAX_FACTOR`).
pub(super) const MIN_FACTOR: f64 = 0.2;
pub(super) const MAX_FACTOR: f64 = 10.0;
/// The orders a fixed-step run rises to when no other cap is set: the A-stable ones.
pub(super) const FIXED_STEP_ORDER: usize = 2;

/// κₖ of the NDFs (Shampine & Reichelt 1997, Table 1; κ₅ = 0: order 5 is plain BDF5).
pub(super) const KAPPA: [f64; MAX_ORDER + 1] = [0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0];

/// γₖ = Σⱼ₌₁ᵏ 1/j.
pub(super) const GAMMA: [f64; MAX_ORDER + 1] = {
    let mut gamma = [0.0; MAX_ORDER + 1];
    let mut k = 1;
    while k <= MAX_ORDER {
        gamma[k] = gamma[k - 1] + 1.0 / k as f64;
        k += 1;
    }
    gamma
};

/// αₖ = (1 − κₖ)·γₖ: the step is solved for c = h/αₖ.
pub(super) const ALPHA: [f64; MAX_ORDER + 1] = {
    let mut alpha = [0.0; MAX_ORDER + 1];
    let mut k = 0;
    while k <= MAX_ORDER {
        alpha[k] = (1.0 - KAPPA[k]) * GAMMA[k];
        k += 1;
    }
    alpha
};

/// The error constants κₖγₖ + 1/(k + 1): the local error of order k is ≈ this × ∇ᵏ⁺¹yₙ₊₁.
pub(super) const ERROR_CONST: [f64; MAX_ORDER + 2] = {
    let mut c = [0.0; MAX_ORDER + 2];
    let mut k = 0;
    while k <= MAX_ORDER + 1 {
        let kappa_gamma = if k <= MAX_ORDER {
            KAPPA[k] * GAMMA[k]
        } else {
            0.0
        };
        c[k] = kappa_gamma + 1.0 / (k + 1) as f64;
        k += 1;
    }
    c
};

/// Monomial coefficients of the Newton backward basis on the last step,
/// pⱼ(θ) = Πₘ₌₀ʲ⁻¹ (θ − 1 + m)/(m + 1): `BASIS[j][i]` is the coefficient of θⁱ in pⱼ.
pub(super) const BASIS: [[f64; MAX_ORDER + 1]; MAX_ORDER + 1] = {
    let mut basis = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
    basis[0][0] = 1.0;
    let mut j = 1;
    while j <= MAX_ORDER {
        // pⱼ = pⱼ₋₁ · (θ + j − 2)/j.
        let shift = (j as f64 - 2.0) / j as f64;
        let slope = 1.0 / j as f64;
        let mut i = 0;
        while i <= MAX_ORDER {
            let from_shift = basis[j - 1][i] * shift;
            let from_slope = if i > 0 {
                basis[j - 1][i - 1] * slope
            } else {
                0.0
            };
            basis[j][i] = from_shift + from_slope;
            i += 1;
        }
        j += 1;
    }
    basis
};

/// Re-samples the differences D[0..=k] of the interpolating polynomial at a step `factor` times
/// the current one: D ← (R·U)ᵀ·D, with Rᵢⱼ = Πₘ₌₁ⁱ (m − 1 − factor·j)/m and U = R at factor 1
/// (Shampine & Reichelt 1997, §2.2; SciPy's `change_D`).
pub(super) fn change_d<S: State>(differences: &mut [S], k: usize, factor: f64) {
    let ru = resampling(k, factor);
    let n = differences[0].as_slice().len();
    let mut column = [0.0; MAX_ORDER + 1];
    for c in 0..n {
        for (x, dj) in column.iter_mut().zip(differences.iter()).take(k + 1) {
            *x = dj.as_slice()[c];
        }
        for (j, dj) in differences.iter_mut().enumerate().take(k + 1) {
            dj.as_mut_slice()[c] = (0..=k).map(|i| ru[i][j] * column[i]).sum();
        }
    }
}

/// R·U of [`change_d`].
pub(super) fn resampling(k: usize, factor: f64) -> [[f64; MAX_ORDER + 1]; MAX_ORDER + 1] {
    let r = resample(k, factor);
    let u = resample(k, 1.0);
    let mut ru = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
    for i in 0..=k {
        for j in 0..=k {
            ru[i][j] = (0..=k).map(|m| r[i][m] * u[m][j]).sum();
        }
    }
    ru
}

/// SciPy's `compute_R(k, factor)`.
pub(super) fn resample(k: usize, factor: f64) -> [[f64; MAX_ORDER + 1]; MAX_ORDER + 1] {
    let mut r = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
    r[0][..=k].fill(1.0);
    for i in 1..=k {
        let (above, row) = r.split_at_mut(i);
        let cells = row[0].iter_mut().zip(&above[i - 1]).enumerate();
        for (j, (x, a)) in cells.take(k + 1).skip(1) {
            *x = a * (i as f64 - 1.0 - factor * j as f64) / i as f64;
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::{ALPHA, BASIS, ERROR_CONST, GAMMA, resampling};

    #[test]
    fn constants_are_scipys() {
        // scipy/integrate/_ivp/bdf.py: gamma = [0, 1, 3/2, 11/6, 25/12, 137/60].
        assert_eq!(GAMMA[2], 1.5);
        assert!((GAMMA[5] - 137.0 / 60.0).abs() < 1e-15);
        assert!((ALPHA[1] - 1.185).abs() < 1e-15);
        assert!((ERROR_CONST[1] - (-0.185 + 0.5)).abs() < 1e-15);
        assert!((ERROR_CONST[6] - 1.0 / 7.0).abs() < 1e-15);
    }

    #[test]
    fn the_basis_interpolates_the_backward_values() {
        // pⱼ(1) = 0 for j ≥ 1 (the newest point), pⱼ(0) = (−1)ʲ·… gives ∇ʲ's weight at yₙ.
        for (j, b) in BASIS.iter().enumerate() {
            let at_one: f64 = b.iter().sum();
            assert!((at_one - f64::from(j == 0)).abs() < 1e-14, "{j}: {at_one}");
        }
        // p₁(θ) = θ − 1, p₂(θ) = (θ − 1)θ/2.
        assert_eq!(BASIS[1][..2], [-1.0, 1.0]);
        assert_eq!(BASIS[2][..3], [0.0, -0.5, 0.5]);
    }

    #[test]
    fn resampling_keeps_the_polynomial() {
        // y = t³ − t sampled at t = 0, −h, −2h, −3h: its backward differences at spacing 1,
        // re-sampled at factor 0.5, are those at spacing 0.5.
        let diffs = |h: f64| {
            let y = |t: f64| t * t * t - t;
            let v = [y(0.0), y(-h), y(-2.0 * h), y(-3.0 * h)];
            [
                v[0],
                v[0] - v[1],
                v[0] - 2.0 * v[1] + v[2],
                v[0] - 3.0 * v[1] + 3.0 * v[2] - v[3],
            ]
        };
        let ru = resampling(3, 0.5);
        let d = diffs(1.0);
        for (j, expected) in diffs(0.5).iter().enumerate() {
            let got: f64 = (0..4).map(|i| ru[i][j] * d[i]).sum();
            assert!((got - expected).abs() < 1e-14, "{j}: {got} vs {expected}");
        }
        // Factor 1 changes nothing: U is its own inverse.
        let identity = resampling(5, 1.0);
        for (i, row) in identity.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                assert!((x - f64::from(i == j)).abs() < 1e-12, "({i}, {j}): {x}");
            }
        }
    }
}
