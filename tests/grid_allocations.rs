//! Stepping a field model allocates nothing after the first step: explicit Euler, RK4, and
//! implicit Euler with its sparse Newton solve by Cholesky (heat), counted by a global
//! allocator; by LU (Gray–Scott, whose Newton matrix is unsymmetric) only faer's numeric
//! factorization allocates, the same number of times every call (as in `tests/allocations.rs`
//! for particles). With Krylov solves (`LinearSolver::Krylov`, CG on heat, BiCGSTAB on
//! Gray–Scott) nothing allocates at all. One test in its own binary, so no other test's
//! allocations are counted.

mod common;

use std::sync::atomic::Ordering;

use common::ALLOCATIONS;
use scenes::GrayScott;

use odyn::grid::{Boundary, Grid, Stencil};
use odyn::integrators::{ExplicitEuler, ImplicitEuler, Rk4};
use odyn::{
    Integrator, KrylovOptions, LinearSolver, Model, NewtonOptions, Preconditioner, Stepper, system,
};

#[global_allocator]
static GLOBAL: common::Counting = common::Counting;

#[system(integrator = ImplicitEuler, dt = 1e-4)]
struct Heat {
    #[field]
    u: Grid,
    d: f64,
    dx: f64,
}

#[system]
impl Heat {
    #[cell]
    fn conduction(&self, u: Stencil) -> f64 {
        self.d * u.laplacian() / (self.dx * self.dx)
    }
}

/// Allocations made by steps 2..=21 of integrator `I` on `model` at `dt`.
fn allocations<M: Model, I: Integrator<M>>(model: &M, dt: f64) -> u64 {
    allocations_with::<M, I>(model, dt, &NewtonOptions::default())
}

/// Allocations made by steps 2..=21 of integrator `I` on `model` at `dt` with `newton`.
fn allocations_with<M: Model, I: Integrator<M>>(model: &M, dt: f64, newton: &NewtonOptions) -> u64 {
    let mut stepper = Stepper::<M, I>::with_newton(model, model.state(), 0.0, dt, newton).unwrap();
    stepper.step().unwrap();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..20 {
        stepper.step().unwrap();
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

#[test]
fn stepping_a_field_model_allocates_nothing() {
    common::count_this_thread();
    let n = 12;
    let bump = |i: usize, j: usize| ((i * 7 + j * 3) % 5) as f64 * 0.1;
    let heat = Heat {
        u: Grid::from_fn(n, n, Boundary::Dirichlet(0.0), bump).unwrap(),
        d: 0.1,
        dx: 1.0 / (n as f64 + 1.0),
    };
    let counts = [
        (
            "explicit Euler",
            allocations::<Heat, ExplicitEuler<_>>(&heat, 1e-4),
        ),
        ("RK4", allocations::<Heat, Rk4<_>>(&heat, 1e-4)),
        (
            "implicit Euler (Cholesky)",
            allocations::<Heat, ImplicitEuler<_>>(&heat, 1e-2),
        ),
    ];
    for (method, count) in counts {
        assert_eq!(count, 0, "{method} allocated {count} times in 20 steps");
    }
    let gray_scott = |side: usize| GrayScott {
        u: Grid::from_fn(side, side, Boundary::Periodic, |i, j| 1.0 - bump(i, j)).unwrap(),
        v: Grid::from_fn(side, side, Boundary::Periodic, bump).unwrap(),
        du: 2e-5,
        dv: 1e-5,
        feed: 0.04,
        kill: 0.06,
        dx: 2.5 / 256.0,
    };
    let krylov = |preconditioner| NewtonOptions {
        linear: LinearSolver::Krylov(KrylovOptions {
            preconditioner,
            ..KrylovOptions::default()
        }),
        ..NewtonOptions::default()
    };
    let (jacobi, multigrid, fourier) = (
        krylov(Preconditioner::BlockJacobi),
        krylov(Preconditioner::Multigrid),
        krylov(Preconditioner::Fourier),
    );
    // Multigrid on heat's 144 unknowns is its coarsest level alone (a dense LU); on Gray–Scott
    // at 24² cells (1 152 unknowns, above the 300 a dense LU takes) it has coarse levels: its
    // hierarchy is built when the run is set up, its values refilled in place and its V-cycles
    // run in faer's work stack.
    let counts = [
        (
            "implicit Euler, heat, CG",
            allocations_with::<Heat, ImplicitEuler<_>>(&heat, 1e-2, &jacobi),
        ),
        (
            "implicit Euler, Gray–Scott, BiCGSTAB",
            allocations_with::<GrayScott, ImplicitEuler<_>>(&gray_scott(n), 5.0, &jacobi),
        ),
        (
            "implicit Euler, heat, multigrid CG",
            allocations_with::<Heat, ImplicitEuler<_>>(&heat, 1e-2, &multigrid),
        ),
        (
            "implicit Euler, Gray–Scott, multigrid BiCGSTAB",
            allocations_with::<GrayScott, ImplicitEuler<_>>(&gray_scott(24), 5.0, &multigrid),
        ),
        (
            // Its transforms and per-wave-number solves run in faer's work stack.
            "implicit Euler, Gray–Scott, Fourier BiCGSTAB",
            allocations_with::<GrayScott, ImplicitEuler<_>>(&gray_scott(24), 5.0, &fourier),
        ),
    ];
    for (method, count) in counts {
        assert_eq!(count, 0, "{method} allocated {count} times in 20 steps");
    }
    // faer 0.24's supernodal numeric LU allocates its per-supernode buffers on every call:
    // exactly 67 times a factorization on this 12² grid (measured: 4556 more allocations for 68
    // more factorizations, and 5494 for 82, between runs of 20, 40 and 80 steps). Everything
    // else on the LU path — odyn's blocks, assembly, solves — allocates nothing per step: the
    // allocations beyond those do not grow with the steps.
    const PER_NUMERIC_LU: u64 = 67;
    let gray_scott = gray_scott(n);
    let lu_window = |steps: usize| {
        let newton = NewtonOptions::default();
        let mut stepper = Stepper::<GrayScott, ImplicitEuler<_>>::with_newton(
            &gray_scott,
            gray_scott.state(),
            0.0,
            5.0,
            &newton,
        )
        .unwrap();
        stepper.step().unwrap();
        let lus = stepper.integrator().matrix().factorizations().lu;
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        for _ in 0..steps {
            stepper.step().unwrap();
        }
        let count = ALLOCATIONS.load(Ordering::Relaxed) - before;
        let lus = stepper.integrator().matrix().factorizations().lu - lus;
        assert!(lus > 0, "the LU path was not taken");
        count - PER_NUMERIC_LU * lus
    };
    let (short, long) = (lu_window(20), lu_window(80));
    assert_eq!(
        short, long,
        "implicit Euler by sparse LU: allocations beyond faer's numeric LU grew with the steps"
    );
}
