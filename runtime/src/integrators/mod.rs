//! The integrators, one per file, each generic over the model it steps.
//!
//! | method | order | force evals/step | energy on an oscillator | needs |
//! |---|---|---|---|---|
//! | [`ExplicitEuler`] | 1 | 1 | grows ×(1 + ω²dt²) per step | f(t, y) |
//! | [`SymplecticEuler`] | 1 | 1 | bounded, E/E₀ ∈ [2/(2+ωdt), 2/(2−ωdt)] | q/v split |
//! | [`PositionVerlet`] | 2 | 1 | bounded, E/E₀ ∈ [1 − ω²dt²/4, 1] | split, forces free of v |
//! | [`VelocityVerlet`] | 2 | 1 (reused) | bounded, as position Verlet | split |
//! | [`Leapfrog`] | 2 | 1 (reused) | bounded, as position Verlet | split |
//! | [`Rk4`] | 4 | 4 | slow secular decay | f(t, y) |
//! | [`ImplicitEuler`] | 1 | Newton: ≥ 2 f and 2 ∂f/∂y | decays ×1/(1 + ω²dt²) per step | ∂f/∂y |
//!
//! Stability on an undamped oscillator of angular frequency ω: the split methods are stable for
//! ω·dt < 2, RK4 for ω·dt < 2√2, explicit Euler for no dt at all, implicit Euler for every dt.
//!
//! An [`Integrator`] is created once per run by [`Integrator::start`] — which allocates its
//! scratch states and makes any start-up force evaluation — and then [`Integrator::step`]s without
//! allocating. The step dt is fixed for the life of the integrator, which is what lets the
//! Verlet family reuse the last force.

mod explicit_euler;
mod implicit_euler;
mod leapfrog;
mod position_verlet;
mod rk4;
mod symplectic_euler;
mod velocity_verlet;

pub use explicit_euler::ExplicitEuler;
pub use implicit_euler::ImplicitEuler;
pub use leapfrog::Leapfrog;
pub use position_verlet::PositionVerlet;
pub use rk4::Rk4;
pub use symplectic_euler::SymplecticEuler;
pub use velocity_verlet::VelocityVerlet;

use crate::{Method, Model, NewtonOptions, Result};

/// One integration method, specialised to a model.
pub trait Integrator<M: Model> {
    /// The [`Method`] this integrator implements.
    const METHOD: Method;
    /// Force (derivative or acceleration) evaluations made by [`Integrator::start`].
    const STARTUP_EVALUATIONS: u64;
    /// Force evaluations made by each [`Integrator::step`] (implicit methods count instead).
    const EVALUATIONS_PER_STEP: u64;

    /// Prepares to step `state` from time `t0` with the fixed step `dt`; `newton` configures the
    /// nonlinear solve of implicit methods and is ignored by explicit ones. Fails only for an
    /// implicit method whose linear solver cannot be set up (a sparse symbolic factorization).
    fn start(model: &M, t0: f64, dt: f64, state: &M::State, newton: &NewtonOptions) -> Result<Self>
    where
        Self: Sized;

    /// Advances `state` from time `t` to `t + dt`. Only implicit methods can fail here (their
    /// Newton solve); on failure the state is the last iterate.
    fn step(&mut self, model: &M, t: f64, state: &mut M::State) -> Result<()>;

    /// Evaluations made since [`Integrator::start`], after `steps` steps.
    fn evaluations(&self, steps: u64) -> Evaluations {
        Evaluations {
            force: Self::STARTUP_EVALUATIONS + steps * Self::EVALUATIONS_PER_STEP,
            jacobian: 0,
        }
    }
}

/// How much work a run did: the cost measure of work-precision comparisons.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Evaluations {
    /// Force (derivative or acceleration) evaluations.
    pub force: u64,
    /// Jacobian evaluations.
    pub jacobian: u64,
}

/// y ← y + a·x.
#[inline(always)]
fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// out ← y + a·x.
#[inline(always)]
fn set_axpy(out: &mut [f64], y: &[f64], a: f64, x: &[f64]) {
    for ((oi, yi), xi) in out.iter_mut().zip(y).zip(x) {
        *oi = yi + a * xi;
    }
}
