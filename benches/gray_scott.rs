//! One implicit Euler step of Gray–Scott (the `gray_scott` example's model) at 64², 128² and
//! 256² cells, and its parts: the cell kernel's derivative blocks placed into J, assembly of
//! I − h·J, numeric sparse LU factorization (I − h·J is unsymmetric: u and v couple through
//! −2uv and v²), and the triangular solves.
//!
//! The state is Pearson's initial square on the (1, 0) background; h = 10, about 8.6× explicit
//! Euler's limit at 256². The step is the one-Newton-iteration (linearized) form, one force
//! evaluation, one Jacobian, one assembly, one factorization and one solve, as in the cloth
//! bench. `cargo bench --bench gray_scott`.
//!
//! `step_krylov`: the same step with the linear system solved by block-Jacobi BiCGSTAB
//! (`LinearSolver::Krylov`, relative residual 1e-8, no warm start: every sample solves the same
//! system), and `run_direct` / `run_krylov`: ten full-Newton implicit Euler steps of h = 10 from
//! the same state (Newton tolerance 1e-8), sparse LU against Krylov with the warm start.
//!
//! `explicit_bare` and `explicit_runner`: 1000 explicit Euler steps of dt = 1 through the
//! `Integrator` trait and through `Simulation::run`, for the runner's overhead on a field model.
//!
//! `equal_accuracy`: whole solves of "coral" (F = 0.0545, k = 0.062) on 64² cells to t = 500 at
//! equal final error (largest absolute error over u and v: 1e-3 and 1e-6), against a DOP853
//! reference at rtol 1e-12 that `tests/continua/grid/gray_scott.rs` checks against SciPy's. Each
//! adaptive method's configuration is the loosest rtol (= atol) in a half-decade sweep from 1e-2
//! meeting the target, as in `scripts/scipy_gray_scott.py`, which runs SciPy's BDF (with
//! `jac_sparsity`), RK45 and DOP853 the same way. The calibration is printed before the timings.

use odyn::grid::{GridJacobian, GridState};
use odyn::integrators::ImplicitEuler;
use std::sync::OnceLock;

use scenes::GrayScott;

use odyn::{
    Integrator, Jacobian, KrylovOptions, LinearSolver, Method, Model, NewtonOptions,
    Preconditioner, Simulate, State, Stats, Stepper,
};

fn main() {
    divan::main();
}

const SIZES: [usize; 3] = [64, 128, 256];
const H: f64 = 10.0;

/// Pearson's initial state without noise, F = 0.0367, k = 0.0649 (`scenes/src/fields.rs`).
fn model(n: usize) -> GrayScott {
    with_rates(n, 0.0367, 0.0649)
}

/// Pearson's initial state without noise, feed F and kill k.
fn with_rates(n: usize, feed: f64, kill: f64) -> GrayScott {
    GrayScott::pearson(n, feed, kill).expect("a grid of at least one cell")
}

/// The model, its state and a Jacobian evaluated, assembled and factorized there.
fn prepared(n: usize) -> (GrayScott, GridState, GridJacobian) {
    let model = model(n);
    let state = model.state();
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut jacobian);
    jacobian.assemble(H);
    jacobian.factorize().expect("I − h·J is regular");
    (model, state, jacobian)
}

/// One linearized implicit Euler step from Pearson's state, its linear system solved by `linear`.
fn linearized_step(bencher: divan::Bencher, n: usize, linear: LinearSolver) {
    let model = model(n);
    let state = model.state();
    let mut stats = Stats::default();
    let options = NewtonOptions {
        linear,
        ..NewtonOptions::linearized()
    };
    let mut integrator = ImplicitEuler::start(&model, 0.0, &state, &options, &mut stats).unwrap();
    let (mut y, mut scratch) = (state.clone(), state.clone());
    bencher.bench_local(|| {
        y.clone_from(&state);
        integrator
            .step(&model, 0.0, H, &mut y, &mut scratch, &mut stats)
            .unwrap();
    });
}

/// The whole step: rate, Jacobian, assembly, factorization, solve, update. Direct: the Krylov
/// default for grids would carry its warm start from sample to sample.
#[divan::bench(args = SIZES, sample_count = 10)]
fn step(bencher: divan::Bencher, n: usize) {
    linearized_step(bencher, n, LinearSolver::Direct);
}

/// The whole step with a Krylov solve in place of the sparse LU (no warm start, as above).
#[divan::bench(args = SIZES, sample_count = 10)]
fn step_krylov(bencher: divan::Bencher, n: usize) {
    let krylov = KrylovOptions {
        warm_start: false,
        ..KrylovOptions::default()
    };
    linearized_step(bencher, n, LinearSolver::Krylov(krylov));
}

/// The whole step with multigrid-preconditioned BiCGSTAB (no warm start).
#[divan::bench(args = SIZES, sample_count = 10)]
fn step_multigrid(bencher: divan::Bencher, n: usize) {
    let krylov = KrylovOptions {
        warm_start: false,
        preconditioner: Preconditioner::Multigrid,
        ..KrylovOptions::default()
    };
    linearized_step(bencher, n, LinearSolver::Krylov(krylov));
}

/// The whole step with ILU(0)-preconditioned BiCGSTAB (no warm start).
#[divan::bench(args = SIZES, sample_count = 10)]
fn step_ilu(bencher: divan::Bencher, n: usize) {
    let krylov = KrylovOptions {
        warm_start: false,
        preconditioner: Preconditioner::Ilu0,
        ..KrylovOptions::default()
    };
    linearized_step(bencher, n, LinearSolver::Krylov(krylov));
}

/// Ten full-Newton implicit Euler steps with `linear`.
fn ten_steps(bencher: divan::Bencher, n: usize, linear: LinearSolver) {
    let model = model(n);
    let newton = NewtonOptions {
        tol: 1e-8,
        linear,
        ..NewtonOptions::default()
    };
    bencher.bench_local(|| {
        let mut stepper = Stepper::<GrayScott, ImplicitEuler<GrayScott>>::with_newton(
            &model,
            model.state(),
            0.0,
            H,
            &newton,
        )
        .unwrap();
        for _ in 0..10 {
            stepper.step().unwrap();
        }
    });
}

/// Ten full-Newton steps, sparse LU.
#[divan::bench(args = SIZES, sample_count = 3)]
fn run_direct(bencher: divan::Bencher, n: usize) {
    ten_steps(bencher, n, LinearSolver::Direct);
}

/// Ten full-Newton steps, block-Jacobi BiCGSTAB with the warm start.
#[divan::bench(args = SIZES, sample_count = 3)]
fn run_krylov(bencher: divan::Bencher, n: usize) {
    ten_steps(bencher, n, LinearSolver::Krylov(KrylovOptions::default()));
}

/// A `simulate()` run of the linearized step (the default `Auto` solver): zero steps, the
/// set-up alone (the Jacobian's pattern and storage, the solver's policy), and one and five
/// steps, side by side — a zero-step run should cost less than one step.
fn plain_run(bencher: divan::Bencher, n: usize, steps: u64) {
    let model = model(n);
    bencher.bench_local(|| {
        model
            .simulate()
            .integrator(Method::ImplicitEuler)
            .newton(NewtonOptions::linearized())
            .dt(H)
            .steps(steps)
            .run()
            .unwrap()
    });
}

/// The set-up of a plain run: zero steps.
#[divan::bench(args = SIZES, sample_count = 5)]
fn run_zero_steps(bencher: divan::Bencher, n: usize) {
    plain_run(bencher, n, 0);
}

/// A plain run of one step.
#[divan::bench(args = SIZES, sample_count = 5)]
fn run_one_step(bencher: divan::Bencher, n: usize) {
    plain_run(bencher, n, 1);
}

/// A plain run of five steps.
#[divan::bench(args = SIZES, sample_count = 3)]
fn run_five_steps(bencher: divan::Bencher, n: usize) {
    plain_run(bencher, n, 5);
}

/// The cell kernel's derivative blocks, placed into J.
#[divan::bench(args = SIZES, sample_count = 10)]
fn jacobian(bencher: divan::Bencher, n: usize) {
    let (model, state, mut jacobian) = prepared(n);
    bencher.bench_local(|| model.jacobian(0.0, &state, &mut jacobian));
}

/// Assembly of I − h·J.
#[divan::bench(args = SIZES, sample_count = 10)]
fn assembly(bencher: divan::Bencher, n: usize) {
    let (_, _, mut jacobian) = prepared(n);
    bencher.bench_local(|| jacobian.assemble(H));
}

/// Numeric sparse LU (the symbolic analysis is reused).
#[divan::bench(args = SIZES, sample_count = 10)]
fn factorization(bencher: divan::Bencher, n: usize) {
    let (_, _, mut jacobian) = prepared(n);
    bencher.bench_local(|| jacobian.factorize());
}

/// Forward and back substitution.
#[divan::bench(args = SIZES, sample_count = 10)]
fn solve(bencher: divan::Bencher, n: usize) {
    let (_, state, mut jacobian) = prepared(n);
    let rhs = odyn::State::as_slice(&state).to_vec();
    let mut x = rhs.clone();
    bencher.bench_local(|| {
        x.copy_from_slice(&rhs);
        jacobian.substitute(&mut x)
    });
}

/// For scale: the same grid at the background (u, v) = (1, 0), where I − h·J is symmetric
/// positive definite and factorized by Cholesky in AMD order rather than by LU in COLAMD order.
#[divan::bench(args = SIZES, sample_count = 10)]
fn factorization_symmetric(bencher: divan::Bencher, n: usize) {
    let mut model = model(n);
    model.u.values_mut().fill(1.0);
    model.v.values_mut().fill(0.0);
    let state = model.state();
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut jacobian);
    jacobian.assemble(H);
    jacobian.factorize().expect("I − h·J is regular");
    assert_eq!(jacobian.factorizations().lu, 0, "Cholesky is expected here");
    bencher.bench_local(|| jacobian.factorize());
}

/// One evaluation of the rate f(y) at every cell: the cost of an explicit Euler step.
#[divan::bench(args = SIZES, sample_count = 50)]
fn rate(bencher: divan::Bencher, n: usize) {
    let model = model(n);
    let state = model.state();
    let mut dydt = state.clone();
    bencher.bench_local(|| model.derivative(0.0, &state, &mut dydt));
}

/// The same rate written by hand over the periodic grid (interior rows by slices, edges by
/// wrapped indices): what `rate` should cost.
#[divan::bench(args = SIZES, sample_count = 50)]
fn rate_by_hand(bencher: divan::Bencher, n: usize) {
    let model = model(n);
    let state = model.state();
    let mut dydt = state.clone();
    bencher.bench_local(|| {
        let y = odyn::State::as_slice(&state);
        let out = odyn::State::as_mut_slice(&mut dydt);
        let (u, v) = y.split_at(n * n);
        let (du, dv) = out.split_at_mut(n * n);
        let h2 = model.dx * model.dx;
        let (a, b) = (model.du / h2, model.dv / h2);
        let (f, k) = (model.feed, model.kill);
        for j in 0..n {
            let (s, no) = ((j + n - 1) % n, (j + 1) % n);
            for i in 0..n {
                let (w, e) = ((i + n - 1) % n, (i + 1) % n);
                let c = j * n + i;
                let lu = u[j * n + e] + u[j * n + w] + u[no * n + i] + u[s * n + i] - 4.0 * u[c];
                let lv = v[j * n + e] + v[j * n + w] + v[no * n + i] + v[s * n + i] - 4.0 * v[c];
                let uvv = u[c] * v[c] * v[c];
                du[c] = a * lu - uvv + f * (1.0 - u[c]);
                dv[c] = b * lv + uvv - (f + k) * v[c];
            }
        }
    });
}

/// Explicit Euler steps a run of `explicit_bare` and `explicit_runner` takes (dt = 1, below the
/// 256² limit 1.1666).
const EXPLICIT_STEPS: u64 = 1000;

/// 1000 explicit Euler steps through the `Integrator` trait: the bare integrator.
#[divan::bench(args = SIZES, sample_count = 10)]
fn explicit_bare(bencher: divan::Bencher, n: usize) {
    use odyn::integrators::ExplicitEuler;
    let model = model(n);
    bencher.bench_local(|| {
        let mut y = model.state();
        let mut scratch = y.clone();
        let mut stats = Stats::default();
        let options = NewtonOptions::default();
        let mut integrator = ExplicitEuler::start(&model, 0.0, &y, &options, &mut stats).unwrap();
        for step in 0..EXPLICIT_STEPS {
            integrator
                .step(&model, step as f64, 1.0, &mut y, &mut scratch, &mut stats)
                .unwrap();
        }
        y
    });
}

/// The same 1000 steps through `Simulation::run` (validation, the divergence test once per
/// block, first and last samples): what the runner adds to `explicit_bare`.
#[divan::bench(args = SIZES, sample_count = 10)]
fn explicit_runner(bencher: divan::Bencher, n: usize) {
    let model = model(n);
    bencher.bench_local(|| {
        model
            .simulate()
            .integrator(Method::ExplicitEuler)
            .dt(1.0)
            .steps(EXPLICIT_STEPS)
            .record_every(u64::MAX)
            .run()
            .unwrap()
    });
}

/// The methods and targets of `equal_accuracy`.
const RACES: [(&str, Method, f64); 8] = [
    ("Tsit5 1e-3", Method::Tsit5, 1e-3),
    ("Tsit5 1e-6", Method::Tsit5, 1e-6),
    ("DOP853 1e-3", Method::Dop853, 1e-3),
    ("DOP853 1e-6", Method::Dop853, 1e-6),
    ("Rosenbrock23 1e-3", Method::Rosenbrock23, 1e-3),
    ("Rosenbrock23 1e-6", Method::Rosenbrock23, 1e-6),
    ("Rodas5P 1e-3", Method::Rodas5P, 1e-3),
    ("Rodas5P 1e-6", Method::Rodas5P, 1e-6),
];

/// Coral on 64² cells, the equal-accuracy problem.
fn coral() -> GrayScott {
    with_rates(64, 0.0545, 0.062)
}

/// The final state of an adaptive solve to t = 500 and its step count.
fn adaptive(model: &GrayScott, method: Method, rtol: f64) -> Option<(GridState, u64)> {
    let run = model
        .simulate()
        .integrator(method)
        .tolerances(rtol, rtol)
        .duration(500.0)
        .record_every(u64::MAX)
        .run()
        .ok()?;
    let last = run.samples.last()?.state.clone();
    Some((last, run.stats.steps))
}

/// For each race, the loosest rtol in the sweep meeting its target.
fn calibration() -> &'static Vec<Option<f64>> {
    static CALIBRATION: OnceLock<Vec<Option<f64>>> = OnceLock::new();
    CALIBRATION.get_or_init(|| {
        let model = coral();
        let (reference, _) = adaptive(&model, Method::Dop853, 1e-12).expect("the reference solves");
        let error = |state: &GridState| {
            (state.as_slice().iter())
                .zip(reference.as_slice())
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        };
        eprintln!("race                  rtol      error     steps");
        RACES
            .iter()
            .map(|&(name, method, target)| {
                for k in 0..17 {
                    let rtol = 10f64.powf(-2.0 - f64::from(k) / 2.0);
                    let Some((state, steps)) = adaptive(&model, method, rtol) else {
                        continue;
                    };
                    let e = error(&state);
                    if e <= target {
                        eprintln!("{name:<20} {rtol:9.2e} {e:9.2e} {steps:6}");
                        return Some(rtol);
                    }
                }
                eprintln!("{name:<20} does not reach its target");
                None
            })
            .collect()
    })
}

/// A whole solve at the calibrated tolerance.
#[divan::bench(args = [0, 1, 2, 3, 4, 5, 6, 7], sample_count = 3)]
fn equal_accuracy(bencher: divan::Bencher, race: usize) {
    let (_, method, _) = RACES[race];
    let Some(rtol) = calibration()[race] else {
        return;
    };
    let model = coral();
    bencher.bench_local(|| adaptive(&model, method, rtol));
}
