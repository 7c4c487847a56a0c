//! Where each method stops being stable: predicted from the spectrum of the generated Jacobian
//! ([`predicted_limit`]; for field models, whose Jacobians are too big for dense eigenvalues,
//! from Gershgorin's discs, [`gershgorin_limit`]), and measured by bisection on long runs.
//!
//! A limit is a step dt: `0.0` means no dt is stable (explicit Euler on an undamped oscillator)
//! and `f64::INFINITY` means every dt is (implicit Euler on a dissipative or conservative linear
//! model).

use nalgebra::{Complex, DMatrix};

use crate::{DenseMatrix, Error, Jacobian, Method, Model, Result, State};

/// How a measured limit is found. [`measured_limit`] checks every field first.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityProbe {
    /// Steps per trial run, at least 2 (default 20 000).
    pub steps: u64,
    /// A run is unstable when the largest energy of its second half exceeds that of its first
    /// half by more than this fraction, finite and non-negative (default 1e-3), or when it
    /// diverges. Bounded methods
    /// oscillate within a fixed band, so both halves see the same maximum; an unstable one grows.
    pub growth: f64,
    /// Bisection stops when the bracket is this narrow relative to its lower end, from 1e-15
    /// (about the resolution of `f64`) to 1 (default 1e-6).
    pub precision: f64,
    /// The scan from below raises dt by this ratio a trial, from 1.001 to 2 (default 1.01): a
    /// band of unstable dt narrower than this ratio may be stepped over.
    pub scan_ratio: f64,
}

impl StabilityProbe {
    /// Checks every setting.
    ///
    /// Errors: [`Error::InvalidInput`] naming the first setting out of its documented range.
    pub fn check(&self) -> Result<()> {
        if self.steps < 2 {
            return Err(Error::invalid(
                "StabilityProbe::steps",
                format!("must be at least 2, got {}", self.steps),
            ));
        }
        if !(self.growth.is_finite() && self.growth >= 0.0) {
            return Err(Error::invalid(
                "StabilityProbe::growth",
                format!("must be finite and non-negative, got {:?}", self.growth),
            ));
        }
        if !(1e-15..=1.0).contains(&self.precision) {
            return Err(Error::invalid(
                "StabilityProbe::precision",
                format!("must be from 1e-15 to 1, got {:?}", self.precision),
            ));
        }
        if !(1.001..=2.0).contains(&self.scan_ratio) {
            return Err(Error::invalid(
                "StabilityProbe::scan_ratio",
                format!("must be from 1.001 to 2, got {:?}", self.scan_ratio),
            ));
        }
        Ok(())
    }
}

impl Default for StabilityProbe {
    fn default() -> Self {
        StabilityProbe {
            steps: 20_000,
            growth: 1e-3,
            precision: 1e-6,
            scan_ratio: 1.01,
        }
    }
}

/// The range of dt the search covers: far beyond any step a run takes either way, with room
/// for the products of dt with the model's rates (ω²dt² stays finite for |ω| < 10¹⁰⁰).
const SMALLEST_DT: f64 = 1e-150;
const LARGEST_DT: f64 = 1e150;

/// The largest dt at which `method` keeps `model` bounded from `state`: the first instability,
/// met scanning dt upwards.
///
/// The energy is the model's own when it defines one, else the squared norm of the state.
///
/// The search, whatever the `guess` (it only sets where the search starts):
///
/// 1. **bracket**: from the guess, dt is multiplied (or divided) by 2, 4, 16, 256, … — the
///    factor squares each trial, so any dt from 10⁻¹⁵⁰ to 10¹⁵⁰ is reached in about 10 trials —
///    until stability changes; a method stable at 10¹⁵⁰ is stable everywhere (∞), one unstable
///    at 10⁻¹⁵⁰ nowhere (0);
/// 2. the bracket is halved geometrically until its ends are within a factor 2;
/// 3. **scan from below**: from half the stable end, dt rises by `probe.scan_ratio` a trial to
///    the first unstable dt, so a method whose stable set has gaps (the sixth-order
///    compositions, stable again past their first limit) reports its first edge;
/// 4. bisection between the last stable and the first unstable dt to `probe.precision`.
///
/// An unstable band below half the stable end the bracket found, or narrower than
/// `probe.scan_ratio`, is not seen.
///
/// Errors: [`Error::InvalidInput`] for a guess that is not finite and positive or a `probe`
/// setting out of range (see [`StabilityProbe::check`]); the run's own input errors.
pub fn measured_limit<M: Model>(
    model: &M,
    state: &M::State,
    method: Method,
    guess: f64,
    probe: &StabilityProbe,
) -> Result<f64> {
    if !(guess.is_finite() && guess > 0.0) {
        return Err(Error::invalid(
            "guess",
            format!("must be finite and positive, got {guess}"),
        ));
    }
    probe.check()?;
    let stable = |dt: f64| bounded(model, state, method, dt, probe);
    let largest = LARGEST_DT;
    let guess = guess.clamp(SMALLEST_DT, largest);
    // 1. Bracket: lo stable, hi unstable.
    let (mut lo, mut hi) = if stable(guess)? {
        let (mut lo, mut factor) = (guess, 2.0f64);
        loop {
            if lo >= largest {
                return Ok(f64::INFINITY);
            }
            let next = (lo * factor).min(largest);
            if !stable(next)? {
                break (lo, next);
            }
            (lo, factor) = (next, factor * factor);
        }
    } else {
        let (mut hi, mut factor) = (guess, 2.0f64);
        loop {
            if hi <= SMALLEST_DT {
                return Ok(0.0);
            }
            let next = (hi / factor).max(SMALLEST_DT);
            if stable(next)? {
                break (next, hi);
            }
            (hi, factor) = (next, factor * factor);
        }
    };
    // 2. To within a factor 2, halving the bracket's logarithm.
    while hi > 2.0 * lo {
        let mid = lo.sqrt() * hi.sqrt();
        if stable(mid)? { lo = mid } else { hi = mid }
    }
    // 3. Scan from below, from a stable start.
    let mut from = 0.5 * lo;
    while !stable(from)? {
        if from <= SMALLEST_DT {
            return Ok(0.0);
        }
        (hi, from) = (from, 0.5 * from);
    }
    let (mut lo, mut hi) = loop {
        let next = from * probe.scan_ratio;
        if next >= hi {
            break (from, hi);
        }
        if !stable(next)? {
            break (from, next);
        }
        from = next;
    };
    // 4. Bisection. precision ≥ 1e-15 ends this within ~50 halvings; the cap guards against a
    // bracket the relative test cannot shrink.
    for _ in 0..200 {
        if hi - lo <= probe.precision * lo {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if stable(mid)? { lo = mid } else { hi = mid }
    }
    Ok(lo)
}

/// One trial: does `method` at `dt` stay bounded over `probe.steps` steps?
fn bounded<M: Model>(
    model: &M,
    state: &M::State,
    method: Method,
    dt: f64,
    probe: &StabilityProbe,
) -> Result<bool> {
    let run = model
        .simulate()
        .initial_state(state.clone())
        .integrator(method)
        .dt(dt)
        .steps(probe.steps)
        .run_partial();
    let (trajectory, failure) = run?;
    match failure {
        Some(Error::Diverged { .. } | Error::NewtonDidNotConverge { .. }) => return Ok(false),
        Some(other) => return Err(other),
        None => {}
    }
    let energy = |s: &crate::Sample<M::State>| {
        s.energy
            .unwrap_or_else(|| s.state.as_slice().iter().map(|x| x * x).sum())
    };
    let half = trajectory.samples.len() / 2;
    let peak = |samples: &[crate::Sample<M::State>]| samples.iter().map(energy).fold(0.0, f64::max);
    let (first, second) = (
        peak(&trajectory.samples[..=half]),
        peak(&trajectory.samples[half..]),
    );
    Ok(second.is_finite() && second <= first * (1.0 + probe.growth))
}

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
            let polynomial = crate::integrators::stability_polynomial(method);
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
    let polynomial = crate::integrators::stability_polynomial(method);
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
