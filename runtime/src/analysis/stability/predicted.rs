//! The predicted limits: from the spectrum of the Jacobian or from Gershgorin's discs, each
//! against the method's stability region along the rays of the eigenvalues.

use nalgebra::{Complex, DMatrix};

use crate::{DenseMatrix, Error, Jacobian, Method, Result};

/// The eigenvalues of ∂f/∂y at (t, `state`).
///
/// Errors: [`Error::InvalidInput`] when the Jacobian has an entry that is not finite (the
/// eigenvalue iteration would not end).
pub fn eigenvalues<M: Jacobian>(model: &M, t: f64, state: &M::State) -> Result<Vec<Complex<f64>>>
where
    M::Matrix: DenseMatrix,
{
    let mut jacobian = model.jacobian_matrix(state);
    model.jacobian(t, state, &mut jacobian);
    let n = jacobian.dim();
    let dense = DMatrix::from_fn(n, n, |r, c| jacobian.entry(r, c));
    if let Some(index) = dense.iter().position(|x| !x.is_finite()) {
        let (row, column) = (index % n, index / n);
        return Err(Error::invalid(
            "jacobian",
            format!(
                "∂f/∂y[{row}][{column}] = {:?} at t = {t:?}: no spectrum to predict from",
                dense[index]
            ),
        ));
    }
    Ok(dense.complex_eigenvalues().iter().copied().collect())
}

/// The largest stable dt `method` is predicted to have, from the eigenvalues λ of the Jacobian at
/// `state`:
///
/// - explicit Runge–Kutta methods (explicit Euler, RK4, Tsit5, DOP853 at a fixed step): the first
///   h along each ray hλ where |R(hλ)| exceeds 1, R being the method's stability polynomial
///   (explicit Euler: dt ≤ −2·Re λ/|λ|², 0 on an undamped oscillator; RK4: 2√2/ω on the
///   imaginary axis);
/// - symplectic Euler, both Verlets, leapfrog: dt < 2/ω with ω = max |λ|, the oscillator limit
///   (these methods are for undamped mechanics; with damping the true limit differs slightly);
/// - implicit Euler and the Rosenbrock methods (A-stable): unconditional (∞) when every
///   Re λ ≤ 0.
///
/// Errors: as [`eigenvalues`].
pub fn predicted_limit<M: Jacobian>(
    model: &M,
    t: f64,
    state: &M::State,
    method: Method,
) -> Result<f64>
where
    M::Matrix: DenseMatrix,
{
    let lambdas: Vec<_> = eigenvalues(model, t, state)?
        .into_iter()
        .filter(|l| l.norm() > 1e-300)
        .collect();
    if lambdas.is_empty() {
        return Ok(f64::INFINITY);
    }
    let fastest = lambdas.iter().map(|l| l.norm()).fold(0.0, f64::max);
    Ok(limit_on(&lambdas, fastest, method))
}

/// The largest stable dt of `method` on a spectrum sampled by `points` — the eigenvalues, or
/// points on the rims of discs that contain them — whose largest |λ| is `fastest` (see
/// [`predicted_limit`] for each family's rule).
fn limit_on(points: &[Complex<f64>], fastest: f64, method: Method) -> f64 {
    let left_half = points.iter().all(|l| l.re <= 1e-12 * fastest);
    use crate::integrators::StabilityRule;
    match crate::integrators::stability_rule(method) {
        // BDF at a fixed step stays at its A-stable orders 1 and 2.
        StabilityRule::AStable => {
            if left_half {
                f64::INFINITY
            } else {
                0.0
            }
        }
        StabilityRule::Verlet => 2.0 / fastest,
        StabilityRule::Composition => crate::integrators::composition_limit(method) / fastest,
        StabilityRule::RungeKutta => {
            let polynomial = crate::integrators::tableau_polynomial(method);
            points
                .iter()
                .map(|l| ray_limit(*l, &polynomial))
                .fold(f64::INFINITY, f64::min)
        }
    }
}

/// The largest stable dt `method` is predicted to have on a field model, from Gershgorin's discs
/// of its sparse Jacobian at `state` ([`crate::grid::GridJacobian::discs`]): every eigenvalue λ
/// lies in a disc centred on a diagonal entry Jᵢᵢ with radius Σⱼ≠ᵢ |Jᵢⱼ|, so a dt for which every
/// scaled disc lies in the method's stability region is stable. Dense eigenvalues
/// ([`predicted_limit`]) are out of reach at these sizes (a 256² Gray–Scott state has 131 072
/// components); the bound needs one pass over the matrix.
///
/// The bound is exact when the extreme eigenvalue sits on a disc's rim — the checkerboard mode of
/// a periodic diffusion grid, λ = −8D/dx²: explicit Euler's dt ≤ 2/(8D/dx²) = dx²/(4D) — and
/// conservative otherwise (on a Dirichlet grid of n cells a side the true limit is larger by
/// 1/sin²(nπ/(2(n + 1))), 0.2 % at n = 32). A disc reaching into the right half-plane proves
/// nothing, so the prediction is then 0 for explicit methods and for the A-stable ones.
///
/// Errors: [`Error::InvalidInput`] when the Jacobian has an entry that is not finite.
pub fn gershgorin_limit<M>(model: &M, t: f64, state: &M::State, method: Method) -> Result<f64>
where
    M: Jacobian<Matrix = crate::grid::GridJacobian>,
{
    let mut jacobian = model.jacobian_matrix(state);
    model.jacobian(t, state, &mut jacobian);
    let discs = jacobian.discs();
    if let Some(row) = discs
        .iter()
        .position(|(c, r)| !(c.is_finite() && r.is_finite()))
    {
        return Err(Error::invalid(
            "jacobian",
            format!(
                "row {row} has an entry that is not finite at t = {t:?}: no bound to predict from"
            ),
        ));
    }
    Ok(disc_limit(&discs, method))
}

/// The largest dt for which every disc (centre on the real axis, radius), scaled by dt, lies in
/// `method`'s stability region (see [`gershgorin_limit`]).
pub fn disc_limit(discs: &[(f64, f64)], method: Method) -> f64 {
    // A disc with a real centre is contained in another exactly when its real interval
    // [c − r, c + r] is; keep the maximal intervals (sorted by left end, each reaching further
    // right than every one before it).
    let mut intervals: Vec<(f64, f64)> = discs.iter().map(|&(c, r)| (c - r, c + r)).collect();
    intervals.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.total_cmp(&a.1)));
    let mut maximal: Vec<(f64, f64)> = Vec::new();
    for (left, right) in intervals {
        if maximal.last().is_none_or(|&(_, r)| right > r) {
            maximal.push((left, right));
        }
    }
    let reach = maximal
        .iter()
        .map(|&(l, r)| l.abs().max(r.abs()))
        .fold(0.0, f64::max);
    if reach == 0.0 {
        return f64::INFINITY;
    }
    // 64 points on each maximal disc's rim, θ = π (the leftmost point) and θ = 0 (the
    // rightmost) among them.
    let mut rims = Vec::with_capacity(64 * maximal.len());
    for &(left, right) in &maximal {
        let (c, r) = (0.5 * (left + right), 0.5 * (right - left));
        for k in 0..64 {
            let theta = std::f64::consts::PI * f64::from(k) / 32.0;
            let lambda = Complex::new(c + r * theta.cos(), r * theta.sin());
            if lambda.norm() > 1e-12 * reach {
                rims.push(lambda);
            }
        }
    }
    limit_on(&rims, reach, method)
}

/// The coefficients γ₀ … γ_s of the stability polynomial R(z) = Σₖ γₖzᵏ of an explicit
/// Runge–Kutta method (explicit Euler, RK4, Tsit5, DOP853), computed from its tableau; `None`
/// for other methods. On y′ = λy a step multiplies y by R(h·λ).
pub fn stability_polynomial(method: Method) -> Option<Vec<f64>> {
    let polynomial = crate::integrators::tableau_polynomial(method);
    (!polynomial.is_empty()).then_some(polynomial)
}

/// The first h > 0 at which |R(h·λ)| exceeds 1, by a scan then bisection; 0 when even the
/// smallest step is unstable (λ in the right half-plane, or on the imaginary axis where |R|
/// grows from the start, as explicit Euler's 1 + iy does).
fn ray_limit(lambda: Complex<f64>, polynomial: &[f64]) -> f64 {
    if lambda.re > 1e-12 * lambda.norm() {
        return 0.0;
    }
    if lambda.re.abs() <= 1e-12 * lambda.norm() && grows_on_imaginary_axis(polynomial) {
        return 0.0;
    }
    let r = |h: f64| {
        let z = lambda * h;
        polynomial
            .iter()
            .rev()
            .fold(Complex::new(0.0, 0.0), |acc, &g| acc * z + g)
            .norm()
    };
    // Every explicit method's region lies within |z| ≤ 8 (DOP853's reaches about 6);
    // scan in steps of |z| = 0.01.
    let step = 0.01 / lambda.norm();
    let mut h = step;
    while h * lambda.norm() < 8.0 {
        if r(h) > 1.0 + 1e-12 {
            let (mut lo, mut hi) = (h - step, h);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if r(mid) > 1.0 + 1e-12 {
                    hi = mid
                } else {
                    lo = mid
                }
            }
            return lo;
        }
        h += step;
    }
    0.0
}

/// Whether |R(iy)|² − 1 = Σₖ eₖy²ᵏ is positive for small y: the sign of its lowest coefficient
/// that is not round-off. eₖ = Σᵢ₊ⱼ₌₂ₖ (−1)^(k−j)·γᵢγⱼ.
fn grows_on_imaginary_axis(polynomial: &[f64]) -> bool {
    let degree = polynomial.len().saturating_sub(1);
    for k in 1..=degree {
        let mut e = 0.0;
        for j in 0..=2 * k {
            let i = 2 * k - j;
            if i > degree || j > degree {
                continue;
            }
            // (iy)^i·(−iy)^j = i^(i−j)·y^(2k), and i − j = 2(k − j).
            let sign = if (k + j) % 2 == 0 { 1.0 } else { -1.0 };
            e += sign * polynomial[i] * polynomial[j];
        }
        if e.abs() > 1e-12 {
            return e > 0.0;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::grows_on_imaginary_axis;

    #[test]
    fn growth_on_the_imaginary_axis() {
        // Explicit Euler: |1 + iy|² = 1 + y².
        assert!(grows_on_imaginary_axis(&[1.0, 1.0]));
        // RK4: |R(iy)|² = 1 − y⁶/72 + y⁸/576.
        assert!(!grows_on_imaginary_axis(&[
            1.0,
            1.0,
            0.5,
            1.0 / 6.0,
            1.0 / 24.0
        ]));
        // Second-order Taylor: |1 + iy − y²/2|² = 1 + y⁴/4.
        assert!(grows_on_imaginary_axis(&[1.0, 1.0, 0.5]));
    }
}
