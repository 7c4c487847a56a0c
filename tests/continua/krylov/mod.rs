//! Krylov solves of the sparse Newton matrices (`odyn::LinearSolver`): each against the direct
//! solve on cloth and Gray–Scott matrices (relative residual and solution difference), whole
//! runs of every implicit method against the direct runs, the automatic choice, fallbacks and
//! option errors, and every solver under hostile input (`hostile.rs`).

mod fourier;
mod hostile;
mod policy;
mod runs;
mod solves;

use odyn::integrators::ImplicitEuler;
use odyn::prelude::*;
use odyn::{
    Integrator, Jacobian, KrylovOptions, LinearSolver, NewtonMatrix, NewtonOptions, Preconditioner,
    Stepper,
};

/// The Krylov configurations under test, solving to a relative residual of 1e-12 (inside Newton
/// too).
fn krylovs() -> [LinearSolver; 5] {
    [
        Preconditioner::BlockJacobi,
        Preconditioner::Ilu0,
        Preconditioner::Multigrid,
        // Periodic grids; block Jacobi for the cloth and other boundaries.
        Preconditioner::Fourier,
        Preconditioner::Factorization { refresh_above: 5 },
    ]
    .map(|preconditioner| {
        LinearSolver::Krylov(KrylovOptions {
            preconditioner,
            rtol: 1e-12,
            newton_rtol: 1e-12,
            bdf_rtol: 1e-12,
            ..KrylovOptions::default()
        })
    })
}

fn with(linear: LinearSolver) -> NewtonOptions {
    NewtonOptions {
        linear,
        ..NewtonOptions::default()
    }
}

/// Solves (I − c·J)·x = b with the Jacobian of `model` at `state`, configured by `newton`.
fn solve<M: Jacobian>(
    model: &M,
    state: &M::State,
    c: f64,
    newton: &NewtonOptions,
    b: &[f64],
) -> Vec<f64> {
    let mut matrix = model.jacobian_matrix(state);
    matrix.configure(newton, odyn::Solves::OneStep);
    model.jacobian(0.0, state, &mut matrix);
    let mut factors = matrix.factors();
    matrix.factorize(c, &mut factors).expect("W is regular");
    let mut x = b.to_vec();
    matrix.solve(&mut factors, &mut x).expect("x is finite");
    x
}

/// max |x − y| / max |y|.
fn difference(x: &[f64], y: &[f64]) -> f64 {
    let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// ‖b − A·x‖₂ / ‖b‖₂ for a dense A.
fn relative_residual(a: &odyn::nalgebra::DMatrix<f64>, x: &[f64], b: &[f64]) -> f64 {
    let x = odyn::nalgebra::DVector::from_column_slice(x);
    let b = odyn::nalgebra::DVector::from_column_slice(b);
    (&b - a * x).norm() / b.norm()
}

/// The final state of `steps` steps of `I` on `model` from its state at `dt`.
fn stepped<M: Jacobian, I: Integrator<M>>(
    model: &M,
    dt: f64,
    steps: usize,
    newton: &NewtonOptions,
) -> (Vec<f64>, odyn::Stats) {
    let mut stepper = Stepper::<M, I>::with_newton(model, model.state(), 0.0, dt, newton).unwrap();
    for _ in 0..steps {
        stepper.step().unwrap();
    }
    (stepper.state().as_slice().to_vec(), stepper.stats())
}

/// The factorization and Krylov counts of 10 implicit Euler steps of `model`.
fn counts_of<M>(model: &M, dt: f64, newton: &NewtonOptions) -> odyn::LinearWork
where
    M: Jacobian,
    M::Matrix: Counted,
{
    let mut stepper =
        Stepper::<M, ImplicitEuler<M>>::with_newton(model, model.state(), 0.0, dt, newton).unwrap();
    for _ in 0..10 {
        stepper.step().unwrap();
    }
    stepper.integrator().matrix().counts()
}

/// The Jacobians that count their factorizations.
trait Counted {
    fn counts(&self) -> odyn::LinearWork;
}
impl Counted for odyn::grid::GridJacobian {
    fn counts(&self) -> odyn::LinearWork {
        self.factorizations()
    }
}
impl Counted for odyn::particles::ParticleJacobian<3> {
    fn counts(&self) -> odyn::LinearWork {
        self.factorizations()
    }
}
