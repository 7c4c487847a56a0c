//! Implicit Euler for particle models by L-BFGS with a prefactored initial Hessian.

use super::lbfgs::{History, dot};
use crate::linalg::spd::SpdSolver;
use crate::{LinkLaplacian, NewtonFailure, QuasiNewtonOptions, State, Stats};

/// Implicit Euler's step of a particle model solved as a minimisation (Liu, Bouaziz & Kavan,
/// "Quasi-Newton Methods for Real-Time Simulation of Hyperelastic Materials", ACM TOG 36(3),
/// 2017).
///
/// With the velocity v at tₙ₊₁ as the unknown and x = xₙ + h·v, the step's equations are the
/// stationarity of the implicit Euler objective
///
/// g(v) = ½(v − vₙ)ᵀM(v − vₙ) + E(xₙ + h·v),   ∇g = r(v) = M(v − vₙ) − h·F(xₙ + h·v, v)
///
/// (for conservative forces; with damping, r is the residual all the same). L-BFGS minimises g
/// with the initial Hessian A = M + h·C + h²·K of the model's [`LinkLaplacian`]: every link's
/// stiffness k and damping c as scalar weights, so A is a scalar n×n matrix (pinned particles
/// eliminated) that serves every axis and does not change with the state. It is factorized by
/// faer's sparse Cholesky once per step size (the last two sizes are kept: a halved step and
/// the return to the full one). Each iteration costs one force evaluation and one substitution
/// with D right-hand sides.
///
/// - **Start**: vₙ (x⁰ = xₙ + h·vₙ, the inertial position of Liu et al. 2013).
/// - **Line search**: backtracking from α = 1 on the trapezoid estimate of g's change along the
///   step, ½α(r(v)·p + r(v + αp)·p), by Armijo's condition with c = 10⁻⁴; it needs no energy
///   (the kernels need not have one) and no evaluation beyond the one the next iteration uses.
///   A direction that does not descend resets the history to A⁻¹ alone, which always does.
/// - **Stop**: at [`QuasiNewtonOptions::tolerance`] or after `max_iterations`, accepting the
///   iterate reached. It converges to the same implicit Euler step as Newton's method.
pub struct QuasiNewton {
    options: QuasiNewtonOptions,
    laplacian: LinkLaplacian,
    /// Each particle's row in A (pinned: `usize::MAX`).
    rows: Vec<usize>,
    free: usize,
    /// A's factorizations by step size, newest first.
    factors: [Option<(f64, SpdSolver)>; 2],
    factorizations: u64,
    history: History,
    velocity: Vec<f64>,
    residual: Vec<f64>,
    trial: Vec<f64>,
    direction: Vec<f64>,
    columns: Vec<f64>,
    iterations: u32,
    measure: f64,
}

impl QuasiNewton {
    /// The solver for the particles of `laplacian`.
    pub(crate) fn new(options: QuasiNewtonOptions, laplacian: LinkLaplacian) -> Self {
        let rows = laplacian.rows();
        let free = laplacian.free();
        let n = rows.len() * laplacian.dimension;
        QuasiNewton {
            options,
            history: History::new(options.history as usize, n),
            velocity: vec![0.0; n],
            residual: vec![0.0; n],
            trial: vec![0.0; n],
            direction: vec![0.0; n],
            columns: vec![0.0; free * laplacian.dimension],
            rows,
            free,
            laplacian,
            factors: [None, None],
            factorizations: 0,
            iterations: 0,
            measure: 0.0,
        }
    }

    /// How often A has been factorized: once per step size the run has used.
    pub fn factorizations(&self) -> u64 {
        self.factorizations
    }

    /// Iterations the last step took.
    pub fn iterations(&self) -> u32 {
        self.iterations
    }

    /// The last step's largest velocity residual |vᵢ − vₙ,ᵢ − h·aᵢ| / (1 + |vᵢ|) (m/s).
    pub fn residual(&self) -> f64 {
        self.measure
    }

    /// The matrix the run is factorized with.
    pub fn laplacian(&self) -> &LinkLaplacian {
        &self.laplacian
    }

    /// Solves the step of size `h` from `start` into `y`; `derivative` writes f(tₙ₊₁, y) (the
    /// velocities, then the accelerations) into its second argument.
    ///
    /// Errors: the iterations made, the residual and why, when A cannot be factorized
    /// (`Singular`), or no step along a descent direction down to a thousandth of it lowers the
    /// objective (`LineSearch`) or keeps the forces finite (`NotFinite`).
    pub(super) fn solve<S: State>(
        &mut self,
        h: f64,
        start: &S,
        y: &mut S,
        force: &mut S,
        stats: &mut Stats,
        mut derivative: impl FnMut(&S, &mut S),
    ) -> Result<(), (u32, f64, NewtonFailure)> {
        self.prepare(h, stats)
            .map_err(|cause| (0, f64::NAN, cause))?;
        let n = self.velocity.len();
        let (x0, v0) = start.as_slice().split_at(n);
        self.velocity.copy_from_slice(v0);
        self.direction.fill(0.0);
        self.place(h, x0, y, 0.0);
        derivative(y, force);
        stats.evaluations += 1;
        self.measure = self.residual_into(h, v0, force, Side::Current);
        self.history.clear();
        self.iterations = 0;
        while self.iterations < self.options.max_iterations {
            if self.measure <= self.options.tolerance {
                break;
            }
            self.iterations += 1;
            let slope = self.descend();
            if !slope.is_finite() {
                return Err((self.iterations, self.measure, NewtonFailure::NotFinite));
            }
            if slope >= 0.0 {
                // Not even the preconditioned gradient descends (a residual at rounding level,
                // or a factorization spoiled by rounding): no step can lower the objective.
                return Err((self.iterations, self.measure, NewtonFailure::LineSearch));
            }
            let mut alpha = 1.0;
            loop {
                self.place(h, x0, y, alpha);
                derivative(y, force);
                stats.evaluations += 1;
                let measure = self.residual_into(h, v0, force, Side::Trial);
                let change = 0.5 * alpha * (slope + dot(&self.trial, &self.direction));
                if change <= 1e-4 * alpha * slope && measure.is_finite() {
                    self.measure = measure;
                    break;
                }
                alpha *= 0.5;
                if alpha < 1e-3 {
                    // The caller discards y; the report carries the last iterate's residual.
                    let cause = if measure.is_finite() {
                        NewtonFailure::LineSearch
                    } else {
                        NewtonFailure::NotFinite
                    };
                    return Err((self.iterations, self.measure, cause));
                }
            }
            self.history
                .push(alpha, &self.direction, &self.trial, &self.residual);
            for (v, p) in self.velocity.iter_mut().zip(&self.direction) {
                *v += alpha * p;
            }
            std::mem::swap(&mut self.residual, &mut self.trial);
        }
        Ok(())
    }

    /// A factorized for `h`: the newest, the one before (swapped to the front), or a new one.
    /// A fixed-step run's steps differ in the last bits (tₙ₊₁ − tₙ on a grid of n·dt): sizes
    /// within 10⁻¹⁰ of each other share a factorization, which only preconditions, so the step
    /// solved is the same.
    fn prepare(&mut self, h: f64, stats: &mut Stats) -> Result<(), NewtonFailure> {
        let fits = |entry: &Option<(f64, SpdSolver)>| {
            matches!(entry, Some((size, _)) if (size - h).abs() <= 1e-10 * h.abs())
        };
        if fits(&self.factors[0]) {
            return Ok(());
        }
        self.factors.swap(0, 1);
        if fits(&self.factors[0]) {
            return Ok(());
        }
        let solver = self
            .laplacian
            .factorize(h)
            .map_err(|_| NewtonFailure::Singular)?;
        self.factors[0] = Some((h, solver));
        self.factorizations += 1;
        stats.factorizations += 1;
        Ok(())
    }

    /// y = (xₙ + h·(v + α·p), v + α·p), p the direction; pinned particles keep vₙ, whose
    /// direction is 0.
    fn place<S: State>(&self, h: f64, x0: &[f64], y: &mut S, alpha: f64) {
        let n = self.velocity.len();
        let (x, v) = y.as_mut_slice().split_at_mut(n);
        let new = self.velocity.iter().zip(&self.direction);
        for (((xi, vi), x0i), (u, p)) in x.iter_mut().zip(v.iter_mut()).zip(x0).zip(new) {
            *vi = u + alpha * p;
            *xi = x0i + h * *vi;
        }
    }

    /// r = M(v − vₙ − h·a) into the current or the trial residual, 0 at pinned particles;
    /// returns the largest |v − vₙ − h·a| / (1 + |v|), NaN-propagating.
    fn residual_into<S: State>(&mut self, h: f64, v0: &[f64], force: &S, side: Side) -> f64 {
        let d = self.laplacian.dimension;
        let n = self.velocity.len();
        let (v, a) = force.as_slice().split_at(n);
        let out = match side {
            Side::Current => &mut self.residual,
            Side::Trial => &mut self.trial,
        };
        let mut measure = 0.0f64;
        for (i, ((&row, &m), out)) in self
            .rows
            .iter()
            .zip(&self.laplacian.mass)
            .zip(out.chunks_exact_mut(d))
            .enumerate()
        {
            let range = i * d..(i + 1) * d;
            for (((o, vi), v0i), ai) in out
                .iter_mut()
                .zip(&v[range.clone()])
                .zip(&v0[range.clone()])
                .zip(&a[range])
            {
                let rv = if row == usize::MAX { 0.0 } else { vi - v0i - h * ai };
                *o = m * rv;
                let scaled = rv.abs() / (1.0 + vi.abs());
                if scaled > measure || scaled.is_nan() {
                    measure = scaled;
                }
            }
        }
        measure
    }

    /// The L-BFGS direction p = −H·r into `direction`; returns r·p (negative: descent). A
    /// direction that does not descend is replaced by −A⁻¹r.
    fn descend(&mut self) -> f64 {
        let QuasiNewton {
            history,
            direction,
            residual,
            columns,
            rows,
            factors,
            free,
            laplacian,
            ..
        } = self;
        let d = laplacian.dimension;
        let Some((_, solver)) = factors[0].as_mut() else {
            return f64::NAN;
        };
        let mut initial = |q: &mut [f64]| {
            for (i, &row) in rows.iter().enumerate() {
                if row != usize::MAX {
                    for c in 0..d {
                        columns[c * *free + row] = q[i * d + c];
                    }
                }
            }
            solver.solve_columns(columns, d);
            for (i, &row) in rows.iter().enumerate() {
                for c in 0..d {
                    q[i * d + c] = if row == usize::MAX {
                        0.0
                    } else {
                        columns[c * *free + row]
                    };
                }
            }
        };
        direction.copy_from_slice(residual);
        history.apply(direction, &mut initial);
        direction.iter_mut().for_each(|p| *p = -*p);
        let slope = dot(residual, direction);
        if slope < 0.0 {
            return slope;
        }
        history.clear();
        direction.copy_from_slice(residual);
        initial(direction);
        direction.iter_mut().for_each(|p| *p = -*p);
        dot(residual, direction)
    }
}

/// Which residual buffer [`QuasiNewton::residual_into`] writes.
#[derive(Clone, Copy)]
enum Side {
    Current,
    Trial,
}
