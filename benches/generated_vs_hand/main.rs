//! 10⁶ steps of generated models against the same arithmetic written by hand, per integrator.
//!
//! `cargo bench --bench generated_vs_hand`. Each pair runs side by side in one process; compare
//! medians within a pair (the machine is shared, so absolute times drift between runs).
//! `generated` drives the integrator directly; `runner` is the full `Simulation::run` with its
//! per-step divergence check and no recording.

mod double_pendulum;
mod lorenz;
mod pleiades;
mod spring;

use std::hint::black_box;

use odyn::integrators::{
    ExplicitEuler, Integrator, Leapfrog, PositionVerlet, Rk4, SymplecticEuler, VelocityVerlet,
};
use odyn::prelude::*;
use odyn::{NewtonOptions, Stats};

const STEPS: u64 = 1_000_000;
const DT: f64 = 1e-3;

use scenes::*;

fn main() {
    divan::main();
}

fn spring() -> Spring {
    black_box(Spring::released())
}

fn lorenz() -> Lorenz {
    black_box(Lorenz {
        x: 1.0,
        y: 1.0,
        z: 1.0,
        sigma: 10.0,
        rho: 28.0,
        beta: 8.0 / 3.0,
    })
}

/// Steps a model with integrator `I` through the `Integrator` trait, [`STEPS`] steps of [`DT`].
fn generated<M: Model, I: Integrator<M>>(model: &M) -> M::State {
    stepped::<M, I>(model, STEPS, DT)
}

/// `steps` steps of `dt` with integrator `I` through the `Integrator` trait.
fn stepped<M: Model, I: Integrator<M>>(model: &M, steps: u64, dt: f64) -> M::State {
    let mut state = model.state();
    let mut scratch = state.clone();
    let mut stats = Stats::default();
    let mut integrator = I::start(model, 0.0, &state, &NewtonOptions::default(), &mut stats)
        .expect("a fixed-size model always starts");
    for n in 0..steps {
        // Explicit steps cannot fail; the `Result` is for implicit ones.
        let _ = integrator.step(
            model,
            n as f64 * dt,
            dt,
            &mut state,
            &mut scratch,
            &mut stats,
        );
    }
    state
}

/// The full runner: validation, per-step divergence check, first and last samples recorded.
fn runner<M: Model>(model: &M, method: Method) -> M::State {
    let run = model
        .simulate()
        .integrator(method)
        .dt(DT)
        .steps(STEPS)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    run.last().state.clone()
}
