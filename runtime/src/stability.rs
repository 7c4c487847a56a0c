//! Where each method stops being stable: predicted from the spectrum of the generated Jacobian,
//! and measured by bisection on long runs.
//!
//! A limit is a step dt: `0.0` means no dt is stable (explicit Euler on an undamped oscillator)
//! and `f64::INFINITY` means every dt is (implicit Euler on a dissipative or conservative linear
//! model).

use nalgebra::{Complex, DMatrix};

use crate::{DenseMatrix, Error, Jacobian, Method, Model, Result, State};

/// How a measured limit is found.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityProbe {
    /// Steps per trial run (default 20 000).
    pub steps: u64,
    /// A run is unstable when the largest energy of its second half exceeds that of its first
    /// half by more than this fraction (default 1e-3), or when it diverges. Bounded methods
    /// oscillate within a fixed band, so both halves see the same maximum; an unstable one grows.
    pub growth: f64,
    /// Bisection stops when the bracket is this narrow relative to its lower end (default 1e-6).
    pub precision: f64,
    /// The bracket search gives up — the limit is 0 or ∞ — after this many halvings or
    /// doublings of the first guess (default 40).
    pub max_doublings: u32,
}

impl Default for StabilityProbe {
    fn default() -> Self {
        StabilityProbe {
            steps: 20_000,
            growth: 1e-3,
            precision: 1e-6,
            max_doublings: 40,
        }
    }
}

/// The largest dt at which `method` keeps `model` bounded from `state`, by bisection, starting
/// the bracket search from `guess`.
///
/// The energy is the model's own when it defines one, else the squared norm of the state.
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
    let stable = |dt: f64| bounded(model, state, method, dt, probe);
    let (mut lo, mut hi) = if stable(guess)? {
        let mut lo = guess;
        loop {
            if lo > guess * 2f64.powi(probe.max_doublings as i32) {
                return Ok(f64::INFINITY);
            }
            if !stable(2.0 * lo)? {
                break (lo, 2.0 * lo);
            }
            lo *= 2.0;
        }
    } else {
        let mut hi = guess;
        loop {
            if hi < guess / 2f64.powi(probe.max_doublings as i32) {
                return Ok(0.0);
            }
            if stable(0.5 * hi)? {
                break (0.5 * hi, hi);
            }
            hi *= 0.5;
        }
    };
    while hi - lo > probe.precision * lo {
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
pub fn eigenvalues<M: Jacobian>(model: &M, t: f64, state: &M::State) -> Vec<Complex<f64>>
where
    M::Matrix: DenseMatrix,
{
    let mut jacobian = model.jacobian_matrix(state);
    model.jacobian(t, state, &mut jacobian);
    let n = jacobian.dim();
    let dense = DMatrix::from_fn(n, n, |r, c| jacobian.entry(r, c));
    dense.complex_eigenvalues().iter().copied().collect()
}

/// The largest stable dt `method` is predicted to have, from the eigenvalues λ of the Jacobian at
/// `state`:
///
/// - explicit Euler: |1 + dt·λ| ≤ 1 for every λ, i.e. dt ≤ −2·Re λ/|λ|² (0 when some λ has
///   Re λ ≥ 0 and λ ≠ 0, as on an undamped oscillator);
/// - RK4: |R(dt·λ)| ≤ 1 with R(z) = 1 + z + z²/2 + z³/6 + z⁴/24, found along each ray (2√2/ω on
///   the imaginary axis);
/// - symplectic Euler, both Verlets, leapfrog: dt < 2/ω with ω = max |λ|, the oscillator limit
///   (these methods are for undamped mechanics; with damping the true limit differs slightly);
/// - implicit Euler: unconditional (∞) when every Re λ ≤ 0.
pub fn predicted_limit<M: Jacobian>(model: &M, t: f64, state: &M::State, method: Method) -> f64
where
    M::Matrix: DenseMatrix,
{
    let lambdas: Vec<_> = eigenvalues(model, t, state)
        .into_iter()
        .filter(|l| l.norm() > 1e-300)
        .collect();
    let fastest = lambdas.iter().map(|l| l.norm()).fold(0.0, f64::max);
    if lambdas.is_empty() {
        return f64::INFINITY;
    }
    match method {
        Method::ExplicitEuler => lambdas
            .iter()
            .map(|l| {
                if l.re < 0.0 {
                    -2.0 * l.re / l.norm_sqr()
                } else {
                    0.0
                }
            })
            .fold(f64::INFINITY, f64::min),
        Method::Rk4 => lambdas
            .iter()
            .map(|l| rk4_ray_limit(*l))
            .fold(f64::INFINITY, f64::min),
        Method::ImplicitEuler => {
            if lambdas.iter().all(|l| l.re <= 0.0) {
                f64::INFINITY
            } else {
                0.0
            }
        }
        Method::SymplecticEuler
        | Method::PositionVerlet
        | Method::VelocityVerlet
        | Method::Leapfrog => 2.0 / fastest,
    }
}

/// The first h > 0 at which |R(h·λ)| exceeds 1 for RK4, by a scan then bisection.
fn rk4_ray_limit(lambda: Complex<f64>) -> f64 {
    let r = |h: f64| {
        let z = lambda * h;
        (Complex::new(1.0, 0.0) + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0).norm()
    };
    // |R| ≤ 1 up to |z| ≈ 2.8 on every stable ray; scan in steps of |z| = 0.01 up to 4.
    let step = 0.01 / lambda.norm();
    let mut h = step;
    while h * lambda.norm() < 4.0 {
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
