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
//!
//! Stability on an undamped oscillator of angular frequency ω: the split methods are stable for
//! ω·dt < 2, RK4 for ω·dt < 2√2, explicit Euler for no dt at all.
//!
//! An [`Integrator`] is created once per run by [`Integrator::start`] — which allocates its
//! scratch states and makes any start-up force evaluation — and then [`Integrator::step`]s without
//! allocating. The step dt is fixed for the life of the integrator, which is what lets the
//! Verlet family reuse the last force.

mod explicit_euler;
mod leapfrog;
mod position_verlet;
mod rk4;
mod symplectic_euler;
mod velocity_verlet;

pub use explicit_euler::ExplicitEuler;
pub use leapfrog::Leapfrog;
pub use position_verlet::PositionVerlet;
pub use rk4::Rk4;
pub use symplectic_euler::SymplecticEuler;
pub use velocity_verlet::VelocityVerlet;

use crate::{Method, Model};

/// One integration method, specialised to a model.
pub trait Integrator<M: Model> {
    /// The [`Method`] this integrator implements.
    const METHOD: Method;
    /// Force (derivative or acceleration) evaluations made by [`Integrator::start`].
    const STARTUP_EVALUATIONS: u64;
    /// Force evaluations made by each [`Integrator::step`].
    const EVALUATIONS_PER_STEP: u64;

    /// Prepares to step `state` from time `t0` with the fixed step `dt`.
    fn start(model: &M, t0: f64, dt: f64, state: &M::State) -> Self;

    /// Advances `state` from time `t` to `t + dt`.
    fn step(&mut self, model: &M, t: f64, state: &mut M::State);
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
