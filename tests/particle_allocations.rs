//! Stepping a particle model allocates nothing after the first step: every integrator, and
//! implicit Euler's sparse Newton solve (Cholesky) and its quasi-Newton solve (L-BFGS on the
//! prefactored link Laplacian), counted by a global allocator. One test in its
//! own binary, so no other test's allocations are counted.

mod common;

use std::sync::atomic::Ordering;

use common::ALLOCATIONS;

use odyn::integrators::{
    ExplicitEuler, ImplicitEuler, Leapfrog, PositionVerlet, Rk4, SymplecticEuler, VelocityVerlet,
};
use odyn::nalgebra::Vector2;
use odyn::particles::Spring;
use odyn::prelude::*;
use odyn::{
    Integrator, KrylovOptions, LinearSolver, NewtonOptions, ParticleSolve, QuasiNewtonOptions,
    Stepper,
};

#[global_allocator]
static GLOBAL: common::Counting = common::Counting;

/// A hanging chain of springs, no velocity-dependent forces (so position Verlet runs too).
#[system(dt = 1e-3)]
struct Chain {
    #[position]
    x: Vec<Vector2<f64>>,
    #[velocity]
    v: Vec<Vector2<f64>>,
    #[mass]
    m: Vec<f64>,
    #[pinned]
    fixed: Vec<usize>,
    links: Vec<Spring>,
}

#[system]
impl Chain {
    #[pair(links)]
    fn spring(&self, s: &Spring, xa: Vector2<f64>, xb: Vector2<f64>) -> Vector2<f64> {
        let d = xb - xa;
        d / d.norm() * (s.stiffness * (d.norm() - s.rest))
    }

    #[particle]
    fn weight(&self, i: usize, _x: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(0.0, -9.81 * self.m[i])
    }
}

/// Allocations made by steps 2..=21 of integrator `I` (step 1 may size solver buffers).
fn allocations<I: Integrator<Chain>>(model: &Chain, newton: &NewtonOptions) -> u64 {
    let mut stepper =
        Stepper::<Chain, I>::with_newton(model, model.state(), 0.0, 1e-3, newton).unwrap();
    stepper.step().unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..20 {
        stepper.step().unwrap();
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

#[test]
fn stepping_a_particle_model_allocates_nothing() {
    common::count_this_thread();
    let n = 12;
    let x: Vec<_> = (0..n).map(|i| Vector2::new(0.1 * i as f64, 0.0)).collect();
    let model = Chain {
        links: (0..n - 1)
            .map(|i| Spring::at_rest(&x, i, i + 1, 1e3, 0.0))
            .collect(),
        v: vec![Vector2::zeros(); n],
        m: vec![0.01; n],
        fixed: vec![0],
        x,
    };
    // Full Newton, said explicitly (`ParticleSolve::Auto`, the default, is the same).
    let newton = NewtonOptions {
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    };
    let counts = [
        (
            "explicit Euler",
            allocations::<ExplicitEuler<_>>(&model, &newton),
        ),
        (
            "symplectic Euler",
            allocations::<SymplecticEuler<_>>(&model, &newton),
        ),
        (
            "position Verlet",
            allocations::<PositionVerlet<_>>(&model, &newton),
        ),
        (
            "velocity Verlet",
            allocations::<VelocityVerlet<_>>(&model, &newton),
        ),
        ("leapfrog", allocations::<Leapfrog<_>>(&model, &newton)),
        ("RK4", allocations::<Rk4<_>>(&model, &newton)),
        (
            "implicit Euler",
            allocations::<ImplicitEuler<_>>(&model, &newton),
        ),
        (
            "implicit Euler, one step",
            allocations::<ImplicitEuler<_>>(&model, &NewtonOptions::linearized()),
        ),
        (
            "implicit Euler, the default options",
            allocations::<ImplicitEuler<_>>(&model, &NewtonOptions::default()),
        ),
        (
            "implicit Euler, Krylov solves",
            allocations::<ImplicitEuler<_>>(
                &model,
                &NewtonOptions {
                    linear: LinearSolver::Krylov(KrylovOptions::default()),
                    ..newton
                },
            ),
        ),
        (
            "implicit Euler, quasi-Newton",
            allocations::<ImplicitEuler<_>>(
                &model,
                &NewtonOptions {
                    particle_solve: ParticleSolve::QuasiNewton(QuasiNewtonOptions::default()),
                    ..NewtonOptions::default()
                },
            ),
        ),
    ];
    for (method, count) in counts {
        assert_eq!(count, 0, "{method} allocated {count} times in 20 steps");
    }
}
