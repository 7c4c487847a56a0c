//! One implicit Euler step of a stiff cloth at 32², 64² and 128² particles, and its parts:
//! the kernels' derivative blocks, assembly of M − h·∂f/∂v − h²·∂f/∂x, numeric Cholesky
//! factorization, and the triangular solves.
//!
//! The cloth is the `cloth` example's at rest (k = 10⁴, no spring damping, so the matrix is
//! symmetric positive definite); the step is the one-Newton-iteration (Baraff–Witkin) form,
//! which is one force evaluation, one Jacobian, one assembly, one factorization and one solve.
//! `cargo bench --bench particles`.
//!
//! `step_quasi_newton`: the same step by the quasi-Newton solve (L-BFGS on the prefactored link
//! Laplacian, its default 8 iterations at most), from the same state, beside `step` (the
//! one-Newton-iteration Baraff–Witkin form on the direct solver); `step_quasi_newton_falling`
//! and `step_falling` take both from the falling cloth at t = 0.5 s, where the springs are
//! stretched and the step is no longer near rest; `setup_quasi_newton` is the one-time set-up
//! (the link weights, the symbolic and numeric Cholesky factorization of M + h²K).
//!
//! `half_second_direct` / `half_second_krylov`: 30 consecutive one-step (definite) implicit
//! Euler steps of the falling cloth from rest at 32² and 64², Cholesky against block-Jacobi CG
//! with the warm start (`LinearSolver::Krylov`, relative residual 1e-8): a single step from
//! rest is no test of an iterative solver (the cloth's plane decouples from gravity there).

use odyn::integrators::ImplicitEuler;
use odyn::particles::{ParticleJacobian, ParticleState};
use odyn::prelude::*;
use odyn::{
    Integrator, Jacobian, KrylovOptions, LinearSolver, NewtonOptions, ParticleSolve,
    QuasiNewtonOptions, Stats, Stepper,
};
use scenes::{Cloth, Sheet};

fn main() {
    divan::main();
}

const SIZES: [usize; 3] = [32, 64, 128];
const H: f64 = 1.0 / 60.0;

/// The `cloth` example's falling cloth (`scenes/src/cloth.rs`): k = 10⁴, 0.5 kg.
fn cloth(n: usize) -> Cloth {
    Sheet::falling(n).build().0
}

/// The cloth, its state and a Jacobian evaluated, assembled and factorized there.
fn prepared(n: usize) -> (Cloth, ParticleState<3>, ParticleJacobian<3>) {
    let model = cloth(n);
    let state = model.state();
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut jacobian);
    jacobian.assemble(H);
    jacobian.factorize().expect("the Newton matrix is regular");
    (model, state, jacobian)
}

/// The whole step: force, Jacobian, assembly, factorization, solve, update.
#[divan::bench(args = SIZES, sample_count = 20)]
fn step(bencher: divan::Bencher, n: usize) {
    let model = cloth(n);
    let state = model.state();
    let mut stats = Stats::default();
    let mut integrator = ImplicitEuler::start(
        &model,
        0.0,
        &state,
        &NewtonOptions::linearized(),
        &mut stats,
    )
    .unwrap();
    let (mut y, mut scratch) = (state.clone(), state.clone());
    bencher.bench_local(|| {
        y.clone_from(&state);
        integrator
            .step(&model, 0.0, H, &mut y, &mut scratch, &mut stats)
            .unwrap();
    });
}

/// The quasi-Newton options, its defaults.
fn quasi_newton() -> NewtonOptions {
    NewtonOptions {
        particle_solve: ParticleSolve::QuasiNewton(QuasiNewtonOptions::default()),
        ..NewtonOptions::default()
    }
}

/// One step from `state` with `newton`, the integrator made beforehand.
fn step_from(
    bencher: divan::Bencher,
    model: &Cloth,
    state: &ParticleState<3>,
    newton: &NewtonOptions,
) {
    let mut stats = Stats::default();
    let mut integrator = ImplicitEuler::start(model, 0.0, state, newton, &mut stats).unwrap();
    let (mut y, mut scratch) = (state.clone(), state.clone());
    bencher.bench_local(|| {
        y.clone_from(state);
        integrator
            .step(model, 0.0, H, &mut y, &mut scratch, &mut stats)
            .unwrap();
    });
}

/// The falling cloth at t = 0.5 s (30 Baraff–Witkin steps from rest).
fn falling(n: usize) -> (Cloth, ParticleState<3>) {
    let model = cloth(n);
    let mut stepper = Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(
        &model,
        model.state(),
        0.0,
        H,
        &NewtonOptions::linearized(),
    )
    .unwrap();
    for _ in 0..30 {
        stepper.step().unwrap();
    }
    let state = stepper.state().clone();
    (model, state)
}

/// The quasi-Newton step from rest.
#[divan::bench(args = SIZES, sample_count = 20)]
fn step_quasi_newton(bencher: divan::Bencher, n: usize) {
    let model = cloth(n);
    step_from(bencher, &model, &model.state(), &quasi_newton());
}

/// The Baraff–Witkin step from the falling cloth at t = 0.5 s, on the definite matrix (the
/// springs are compressed there: the exact one is indefinite and would take sparse LU).
#[divan::bench(args = SIZES, sample_count = 10)]
fn step_falling(bencher: divan::Bencher, n: usize) {
    let (model, state) = falling(n);
    let newton = NewtonOptions {
        definite: true,
        ..NewtonOptions::linearized()
    };
    step_from(bencher, &model, &state, &newton);
}

/// The quasi-Newton step from the falling cloth at t = 0.5 s.
#[divan::bench(args = SIZES, sample_count = 10)]
fn step_quasi_newton_falling(bencher: divan::Bencher, n: usize) {
    let (model, state) = falling(n);
    step_from(bencher, &model, &state, &quasi_newton());
}

/// The quasi-Newton solve's one-time set-up: link weights from J, the factorization of
/// M + h²K (symbolic and numeric), and its first step's evaluation.
#[divan::bench(args = SIZES, sample_count = 10)]
fn setup_quasi_newton(bencher: divan::Bencher, n: usize) {
    let model = cloth(n);
    let state = model.state();
    let newton = quasi_newton();
    bencher.bench_local(|| {
        let mut stats = Stats::default();
        let mut integrator =
            ImplicitEuler::start(&model, 0.0, &state, &newton, &mut stats).unwrap();
        let (mut y, mut scratch) = (state.clone(), state.clone());
        // A step of zero iterations' worth would not factorize: the first step does.
        integrator
            .step(&model, 0.0, H, &mut y, &mut scratch, &mut stats)
            .unwrap();
    });
}

/// 30 one-step definite implicit Euler steps from rest with `linear`.
fn half_second(bencher: divan::Bencher, n: usize, linear: LinearSolver) {
    let model = cloth(n);
    let newton = NewtonOptions {
        definite: true,
        linear,
        ..NewtonOptions::linearized()
    };
    bencher.bench_local(|| {
        let mut stepper = Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(
            &model,
            model.state(),
            0.0,
            H,
            &newton,
        )
        .unwrap();
        for _ in 0..30 {
            stepper.step().unwrap();
        }
    });
}

/// Half a second of the falling cloth, Cholesky.
#[divan::bench(args = [32, 64], sample_count = 3)]
fn half_second_direct(bencher: divan::Bencher, n: usize) {
    half_second(bencher, n, LinearSolver::Direct);
}

/// Half a second of the falling cloth, block-Jacobi CG.
#[divan::bench(args = [32, 64], sample_count = 3)]
fn half_second_krylov(bencher: divan::Bencher, n: usize) {
    half_second(bencher, n, LinearSolver::Krylov(KrylovOptions::default()));
}

/// The kernels' derivative blocks.
#[divan::bench(args = SIZES, sample_count = 20)]
fn jacobian(bencher: divan::Bencher, n: usize) {
    let (model, state, mut jacobian) = prepared(n);
    bencher.bench_local(|| model.jacobian(0.0, &state, &mut jacobian));
}

/// Assembly of the sparse Newton matrix from the blocks.
#[divan::bench(args = SIZES, sample_count = 20)]
fn assembly(bencher: divan::Bencher, n: usize) {
    let (_, _, mut jacobian) = prepared(n);
    bencher.bench_local(|| jacobian.assemble(H));
}

/// Numeric Cholesky factorization (the symbolic one is reused).
#[divan::bench(args = SIZES, sample_count = 20)]
fn factorization(bencher: divan::Bencher, n: usize) {
    let (_, _, mut jacobian) = prepared(n);
    bencher.bench_local(|| jacobian.factorize());
}

/// Forward and back substitution.
#[divan::bench(args = SIZES, sample_count = 20)]
fn solve(bencher: divan::Bencher, n: usize) {
    let (_, state, mut jacobian) = prepared(n);
    let rhs: Vec<f64> = state
        .positions()
        .iter()
        .flat_map(|p| [p.x, 1.0, p.z])
        .collect();
    let mut x = rhs.clone();
    bencher.bench_local(|| {
        x.copy_from_slice(&rhs);
        jacobian.substitute(&mut x).expect("the matrix is regular");
    });
}
