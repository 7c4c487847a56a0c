//! odyn's Rosenbrock methods against the peer crates' stiff solvers, at equal final error — never
//! at equal tolerance, because every code weighs its error estimate differently.
//!
//! `cargo bench --manifest-path peers/Cargo.toml --bench stiff`
//!
//! # Problems
//!
//! Three problems of the Bari stiff test set, the `#[system]` models of the `stiff_suite` example
//! (`scenes/src/stiff.rs`, shared so both integrate the same equations), with
//! the reference final states `stiff_suite` uses:
//!
//! - `robertson`: Robertson's kinetics to t = 1e5 (3 species; the 36-digit Radau IIA run of
//!   `scripts/reference_stiff.py`);
//! - `hires`: HIRES to t = 321.8122 (8 species; the test set's `hires.f` value);
//! - `pollu`: POLLU to t = 60 (20 species; the test set's `pollu.f` value);
//! - `orego`: OREGO, the Oregonator, to t = 360 (3 species round a limit cycle; the test set's
//!   `orego.f` value).
//!
//! # Method
//!
//! The error of a run is the largest relative error of the final state over the components whose
//! reference is at least 1e-10 in magnitude (as in `scripts/reference_stiff.py`, so SciPy's
//! figures compare). Each solver is swept over rtol = 10⁻² … 10⁻¹¹ in quarter decades with
//! atol = rtol·`ATOL_SCALE` (the problem's typical small component: Robertson's y₂ is ~1e-6 of
//! y₁). For each target error (1e-4, 1e-7) the solver's configuration is the loosest tolerance
//! whose error is at or below the target. `main` prints this calibration (tolerance, error,
//! steps, rejected steps, f- and J-evaluations, factorizations) before anything is timed; then
//! every solver of a problem and target runs side by side in one divan group (`robertson_1e4`,
//! …). `PEERS_SWEEP=1` also prints every solver's whole sweep.
//!
//! # Variants
//!
//! - `odyn_rodas5p`, `odyn_rosenbrock23`, `odyn_bdf`: the model through `simulate()` with
//!   `Method::Rodas5P` / `Method::Rosenbrock23` / `Method::Bdf`, recording only the initial and
//!   final states, no dense output.
//! - `diffsol_bdf`, `diffsol_esdirk34`: diffsol's variable-order BDF and its ESDIRK 3(4) on
//!   nalgebra dense matrices with `NalgebraLU`, stepped with `set_stop_time(t_end)`.
//! - `de_radau5`, `de_bdf`: `differential-equations`' `ImplicitRungeKutta::radau5()` (Hairer &
//!   Wanner's RADAU5) and `BackwardDifferentiationFormula::adaptive()` through
//!   `IVP::ode(..).t_eval([t_end])`.
//! - `cvode_bdf`: SUNDIALS CVODE 6.4 (C; `cvode/mod.rs`), variable-order BDF with Newton on its
//!   dense direct solver and the analytic Jacobian, scalar tolerances, `CVodeSetStopTime(t_end)`;
//!   needs `libsundials-dev`.
//!
//! Every solver gets odyn's generated f and exact Jacobian, so all integrate the same equations
//! with the same arithmetic and none pays for finite differences: `differential-equations` through
//! `ODE::jacobian`; diffsol, which asks for Jacobian-vector products and assembles its matrix
//! column by column from them, through a J·v that evaluates J once per (t, y) and multiplies the
//! cached matrix. Every variant solves from scratch (building its problem and solver) and returns
//! only its final state; each keeps its own defaults for the controller, first step and Newton
//! settings. Step limits are raised where they would end a run.

#![allow(
    clippy::excessive_precision,
    reason = "reference values are quoted with the 17 digits the reference files give"
)]

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::hint::black_box;
use std::sync::OnceLock;

use differential_equations::ivp::IVP;
use differential_equations::linalg::Matrix;
use differential_equations::methods::{BackwardDifferentiationFormula, ImplicitRungeKutta};
use differential_equations::ode::ODE;
use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason};
use odyn::nalgebra::SMatrix;
use odyn::prelude::*;

mod calibration;
mod cvode;

use calibration::{Pick, pick};
use scenes::{Hires, Orego, Pollu, Robertson};

/// The target final errors (max relative error against the reference).
const TARGETS: [f64; 2] = [1e-4, 1e-7];

/// Relative tolerances swept, loosest first: 10⁻² … 10⁻¹¹ in quarter decades.
fn tolerances() -> impl Iterator<Item = f64> {
    (0..=36).map(|k| 10f64.powf(-2.0 - f64::from(k) / 4.0))
}

// ---------------------------------------------------------------------------------------------
// Problems.

impl Problem<3> for Orego {
    const GROUP: &'static str = "orego";
    const T_END: f64 = 360.0;
    const ATOL_SCALE: f64 = 1e-4;
    const REFERENCE: [f64; 3] = scenes::OREGO_REFERENCE;

    fn instance() -> Self {
        Orego { y: [1.0, 2.0, 3.0] }
    }
}

/// A stiff test problem: a `#[system]` model with a dense stack Jacobian, its initial state, end
/// time, absolute-tolerance scale and reference final state.
trait Problem<const N: usize>: Jacobian<Matrix = SMatrix<f64, N, N>> + 'static {
    /// The group name prefix.
    const GROUP: &'static str;
    /// The end time.
    const T_END: f64;
    /// atol = rtol · ATOL_SCALE.
    const ATOL_SCALE: f64;
    /// y(T_END).
    const REFERENCE: [f64; N];
    /// The model with its initial state.
    fn instance() -> Self;
}

impl Problem<3> for Robertson {
    const GROUP: &'static str = "robertson";
    const T_END: f64 = 1e5;
    const ATOL_SCALE: f64 = 1e-6;
    const REFERENCE: [f64; 3] = scenes::ROBERTSON_1E5;

    fn instance() -> Self {
        Robertson::classic()
    }
}

impl Problem<8> for Hires {
    const GROUP: &'static str = "hires";
    const T_END: f64 = 321.8122;
    const ATOL_SCALE: f64 = 1e-4;
    const REFERENCE: [f64; 8] = scenes::HIRES_REFERENCE;

    fn instance() -> Self {
        Hires {
            y: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057],
        }
    }
}

impl Problem<20> for Pollu {
    const GROUP: &'static str = "pollu";
    const T_END: f64 = 60.0;
    const ATOL_SCALE: f64 = 1e-4;
    const REFERENCE: [f64; 20] = scenes::POLLU_REFERENCE;

    fn instance() -> Self {
        Pollu {
            y: [
                0.0, 0.2, 0.0, 0.04, 0.0, 0.0, 0.1, 0.3, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                0.007, 0.0, 0.0, 0.0,
            ],
        }
    }
}

/// A typed state as a plain array.
fn flat<S: odyn::State, const N: usize>(state: &S) -> [f64; N] {
    state
        .as_slice()
        .try_into()
        .expect("state has the problem's dimension")
}

/// The model's generated f and J on plain slices, for the peers, with counters and the J cache
/// diffsol's Jacobian-vector products read.
struct Plain<P: Problem<N>, const N: usize> {
    model: P,
    y: RefCell<P::State>,
    dy: RefCell<P::State>,
    /// J at (t, y) of the last evaluation.
    jacobian: RefCell<(f64, [f64; N], SMatrix<f64, N, N>)>,
    evaluations: Cell<u64>,
    jacobians: Cell<u64>,
}

impl<P: Problem<N>, const N: usize> Plain<P, N> {
    fn new() -> Self {
        let model = P::instance();
        let state = model.state();
        Plain {
            y: RefCell::new(state.clone()),
            dy: RefCell::new(state),
            jacobian: RefCell::new((f64::NAN, [f64::NAN; N], SMatrix::zeros())),
            model,
            evaluations: Cell::new(0),
            jacobians: Cell::new(0),
        }
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.evaluations.set(self.evaluations.get() + 1);
        let mut state = self.y.borrow_mut();
        let mut rate = self.dy.borrow_mut();
        state.as_mut_slice().copy_from_slice(y);
        self.model.derivative(t, &state, &mut rate);
        dy.copy_from_slice(rate.as_slice());
    }

    /// J(t, y), evaluated only when (t, y) differs from the last call's.
    fn jacobian(
        &self,
        t: f64,
        y: &[f64],
    ) -> std::cell::Ref<'_, (f64, [f64; N], SMatrix<f64, N, N>)> {
        {
            let mut cache = self.jacobian.borrow_mut();
            if cache.0 != t || cache.1 != y {
                self.jacobians.set(self.jacobians.get() + 1);
                let mut state = self.y.borrow_mut();
                state.as_mut_slice().copy_from_slice(y);
                cache.0 = t;
                cache.1.copy_from_slice(y);
                self.model.jacobian(t, &state, &mut cache.2);
            }
        }
        self.jacobian.borrow()
    }
}

impl<P: Problem<N>, const N: usize> ODE<f64, [f64; N]> for Plain<P, N> {
    fn diff(&self, t: f64, y: &[f64; N], dydt: &mut [f64; N]) {
        self.rhs(t, y, dydt);
    }

    fn jacobian(&self, t: f64, y: &[f64; N], j: &mut Matrix<f64>) {
        let cache = Plain::jacobian(self, t, y);
        for c in 0..N {
            for r in 0..N {
                j[(r, c)] = cache.2[(r, c)];
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Solvers.

/// Every solver compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Solver {
    OdynRodas5P,
    OdynRosenbrock23,
    OdynBdf,
    DiffsolBdf,
    DiffsolEsdirk34,
    DeRadau5,
    DeBdf,
    CvodeBdf,
}

impl Solver {
    const ALL: [Solver; 8] = [
        Solver::OdynRodas5P,
        Solver::OdynRosenbrock23,
        Solver::OdynBdf,
        Solver::DiffsolBdf,
        Solver::DiffsolEsdirk34,
        Solver::DeRadau5,
        Solver::DeBdf,
        Solver::CvodeBdf,
    ];

    /// The divan bench name.
    fn name(self) -> &'static str {
        match self {
            Solver::OdynRodas5P => "odyn_rodas5p",
            Solver::OdynRosenbrock23 => "odyn_rosenbrock23",
            Solver::DiffsolBdf => "diffsol_bdf",
            Solver::DiffsolEsdirk34 => "diffsol_esdirk34",
            Solver::DeRadau5 => "de_radau5",
            Solver::DeBdf => "de_bdf",
            Solver::OdynBdf => "odyn_bdf",
            Solver::CvodeBdf => "cvode_bdf",
        }
    }
}

/// One solve: the final state and what it cost.
struct Run<const N: usize> {
    y: [f64; N],
    steps: u64,
    rejected: u64,
    evaluations: u64,
    jacobians: u64,
    factorizations: u64,
}

/// Solves `P` to `P::T_END` with `solver` at rtol = `rtol`, atol = rtol · `P::ATOL_SCALE`, or
/// `None` if the solver fails.
fn solve<P: Problem<N>, const N: usize>(solver: Solver, rtol: f64) -> Option<Run<N>> {
    let atol = rtol * P::ATOL_SCALE;
    match solver {
        Solver::OdynRodas5P => odyn_run::<P, N>(Method::Rodas5P, rtol, atol),
        Solver::OdynRosenbrock23 => odyn_run::<P, N>(Method::Rosenbrock23, rtol, atol),
        Solver::OdynBdf => odyn_run::<P, N>(Method::Bdf, rtol, atol),
        Solver::CvodeBdf => cvode_run::<P, N>(rtol, atol),
        Solver::DiffsolBdf | Solver::DiffsolEsdirk34 => diffsol_run::<P, N>(solver, rtol, atol),
        Solver::DeRadau5 => de_run::<P, _, N>(
            // Vector tolerances: with scalar ones, 0.7.0's Radau5 applies its tolerance
            // transformation (rtol ← 0.1·rtol^⅔) once per component to the one shared value,
            // which drives every rtol to ~1e-3 on a 20-component problem.
            ImplicitRungeKutta::radau5()
                .rtol([rtol; N])
                .atol([atol; N])
                .max_steps(usize::MAX),
        ),
        Solver::DeBdf => de_run::<P, _, N>(
            BackwardDifferentiationFormula::adaptive()
                .rtol(rtol)
                .atol(atol)
                .max_steps(usize::MAX),
        ),
    }
}

fn odyn_run<P: Problem<N>, const N: usize>(method: Method, rtol: f64, atol: f64) -> Option<Run<N>> {
    let run = P::instance()
        .simulate()
        .integrator(method)
        .tolerances(rtol, atol)
        .duration(P::T_END)
        .record_every(u64::MAX)
        .dense_output(false)
        .run()
        .ok()?;
    Some(Run {
        y: flat(&run.last().state),
        steps: run.stats.steps,
        rejected: run.stats.rejected,
        evaluations: run.stats.evaluations,
        jacobians: run.stats.jacobian_evaluations,
        factorizations: run.stats.factorizations,
    })
}

fn cvode_run<P: Problem<N>, const N: usize>(rtol: f64, atol: f64) -> Option<Run<N>> {
    let plain = Plain::<P, N>::new();
    let y0: [f64; N] = flat(&plain.model.state());
    let rhs = |t: f64, y: &[f64], dy: &mut [f64]| plain.rhs(t, y, dy);
    let jacobian = |t: f64, y: &[f64], j: &mut [f64]| {
        let cache = Plain::jacobian(&plain, t, y);
        // nalgebra's matrices are column-major, as CVODE's dense ones.
        j.copy_from_slice(cache.2.as_slice());
    };
    let equations = cvode::Equations {
        n: N,
        rhs: &rhs,
        jacobian: &jacobian,
    };
    let run = cvode::solve(&equations, &y0, P::T_END, rtol, atol)?;
    Some(Run {
        y: run.y.try_into().ok()?,
        steps: run.steps,
        rejected: run.rejected,
        evaluations: run.evaluations,
        jacobians: run.jacobians,
        factorizations: run.factorizations,
    })
}

fn de_run<P, S, const N: usize>(method: S) -> Option<Run<N>>
where
    P: Problem<N>,
    S: differential_equations::ode::OrdinaryNumericalMethod<f64, [f64; N]>
        + differential_equations::interpolate::Interpolation<f64, [f64; N]>,
{
    let plain = Plain::<P, N>::new();
    let y0: [f64; N] = flat(&plain.model.state());
    let solution = IVP::ode(&plain, 0.0, P::T_END, y0)
        .t_eval([P::T_END])
        .method(method)
        .solve()
        .inspect_err(|e| {
            if std::env::var_os("PEERS_SWEEP").is_some() {
                eprintln!("    differential-equations: {e:?}");
            }
        })
        .ok()?;
    (solution.t == [P::T_END]).then(|| Run {
        y: solution.y[0],
        steps: solution.steps.accepted as u64,
        rejected: solution.steps.rejected as u64,
        evaluations: solution.evals.function as u64,
        jacobians: solution.evals.jacobian as u64,
        factorizations: solution.evals.decompositions as u64,
    })
}

fn diffsol_run<P: Problem<N>, const N: usize>(
    solver: Solver,
    rtol: f64,
    atol: f64,
) -> Option<Run<N>> {
    let plain = Plain::<P, N>::new();
    let y0: [f64; N] = flat(&plain.model.state());
    let problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            |x: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| plain.rhs(t, x, dy),
            |x: &[f64], _p: &[f64], t: f64, v: &[f64], jv: &mut [f64]| {
                let cache = plain.jacobian(t, x);
                for (r, out) in jv.iter_mut().enumerate() {
                    *out = (0..N).map(|c| cache.2[(r, c)] * v[c]).sum();
                }
            },
        )
        .init(
            move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&y0),
            N,
        )
        .build()
        .ok()?;
    let (state_y, stats) = match solver {
        Solver::DiffsolBdf => {
            let mut method = problem.bdf::<NalgebraLU<f64>>().ok()?;
            step_to_end(&mut method, P::T_END)?;
            (method.state().y.clone(), method.get_statistics().clone())
        }
        _ => {
            let mut method = problem.esdirk34::<NalgebraLU<f64>>().ok()?;
            step_to_end(&mut method, P::T_END)?;
            (method.state().y.clone(), method.get_statistics().clone())
        }
    };
    let mut y = [0.0; N];
    for (i, yi) in y.iter_mut().enumerate() {
        *yi = state_y[i];
    }
    Some(Run {
        y,
        steps: stats.number_of_steps as u64,
        rejected: stats.number_of_error_test_failures as u64,
        evaluations: plain.evaluations.get(),
        jacobians: plain.jacobians.get(),
        factorizations: stats.number_of_linear_solver_setups as u64,
    })
}

/// Steps a diffsol solver to `t_end`, or `None` if a step fails.
fn step_to_end<'a, E, S>(method: &mut S, t_end: f64) -> Option<()>
where
    E: diffsol::OdeEquations<T = f64> + 'a,
    S: OdeSolverMethod<'a, E>,
{
    method.set_stop_time(t_end).ok()?;
    while method.step().ok()? != OdeSolverStopReason::TstopReached {}
    (method.state().t == t_end).then_some(())
}

// ---------------------------------------------------------------------------------------------
// Calibration.

/// The chosen tolerance of each (problem, target index, solver).
static CHOSEN: OnceLock<HashMap<(&'static str, usize, Solver), f64>> = OnceLock::new();

/// The largest relative error over the components whose reference is at least 1e-10.
fn max_relative_error<const N: usize>(y: &[f64; N], reference: &[f64; N]) -> f64 {
    y.iter()
        .zip(reference)
        .filter(|(_, r)| r.abs() >= 1e-10)
        .fold(0.0, |m: f64, (a, b)| m.max(((a - b) / b).abs()))
}

/// One solver's sweep: (rtol, final error, run) for each tolerance the solver completed.
type Sweep<const N: usize> = Vec<(f64, f64, Run<N>)>;

/// Sweeps every solver over the tolerances on `P`, prints the calibration for each target and
/// records the chosen tolerances.
fn calibrate<P: Problem<N>, const N: usize>(
    chosen: &mut HashMap<(&'static str, usize, Solver), f64>,
) {
    println!(
        "\n{}, t = {}: loosest rtol (atol = rtol·{:.0e}) whose final max relative error is at or \
         below the target",
        P::GROUP,
        P::T_END,
        P::ATOL_SCALE
    );
    let sweeps: Vec<(Solver, Sweep<N>)> = Solver::ALL
        .iter()
        .map(|&solver| {
            let sweep = tolerances()
                .filter_map(|rtol| {
                    let run = solve::<P, N>(solver, rtol)?;
                    Some((rtol, max_relative_error(&run.y, &P::REFERENCE), run))
                })
                .collect();
            (solver, sweep)
        })
        .collect();
    if std::env::var_os("PEERS_SWEEP").is_some() {
        for (solver, sweep) in &sweeps {
            println!(
                "  sweep {}: rtol error steps rejected f J LU",
                solver.name()
            );
            for (rtol, error, run) in sweep {
                println!(
                    "    {rtol:.2e} {error:.2e} {} {} {} {} {}",
                    run.steps, run.rejected, run.evaluations, run.jacobians, run.factorizations
                );
            }
        }
    }
    for (t, &target) in TARGETS.iter().enumerate() {
        println!(
            "  target {target:.0e}:\n    {:<20}{:>10}{:>11}{:>8}{:>6}{:>8}{:>7}{:>7}  tighter tolerances",
            "solver", "rtol", "error", "steps", "rej", "f", "J", "LU"
        );
        for (solver, sweep) in &sweeps {
            let errors: Vec<f64> = sweep.iter().map(|(_, e, _)| *e).collect();
            let (k, note) = match pick(&errors, target) {
                Pick::Met(k, note) => (k, note),
                Pick::NotReached(best) => {
                    println!(
                        "    {:<20}  not reached (best error {best:.1e})",
                        solver.name()
                    );
                    continue;
                }
            };
            let (rtol, error, run) = &sweep[k];
            println!(
                "    {:<20}{rtol:>10.2e}{error:>11.2e}{:>8}{:>6}{:>8}{:>7}{:>7}  {note}",
                solver.name(),
                run.steps,
                run.rejected,
                run.evaluations,
                run.jacobians,
                run.factorizations
            );
            chosen.insert((P::GROUP, t, *solver), *rtol);
        }
    }
}

/// Solves with the calibrated tolerance of `solver` for `P` and target `t`.
fn timed<P: Problem<N>, const N: usize>(solver: Solver, t: usize) -> [f64; N] {
    let rtol = CHOSEN.get().expect("calibrated")[&(P::GROUP, t, solver)];
    solve::<P, N>(black_box(solver), black_box(rtol))
        .expect("the calibrated run succeeded")
        .y
}

fn main() {
    let mut chosen = HashMap::new();
    calibrate::<Robertson, 3>(&mut chosen);
    calibrate::<Hires, 8>(&mut chosen);
    calibrate::<Pollu, 20>(&mut chosen);
    calibrate::<Orego, 3>(&mut chosen);
    println!();
    let mut divan = divan::Divan::from_args();
    for name in [
        <Robertson as Problem<3>>::GROUP,
        <Hires as Problem<8>>::GROUP,
        <Pollu as Problem<20>>::GROUP,
        <Orego as Problem<3>>::GROUP,
    ] {
        for (t, target) in TARGETS.iter().enumerate() {
            for solver in Solver::ALL {
                if !chosen.contains_key(&(name, t, solver)) {
                    let group = format!("{name}_1e{}", -target.log10().round() as i32);
                    divan =
                        divan.skip_exact(format!("{}::{group}::{}", module_path!(), solver.name()));
                }
            }
        }
    }
    CHOSEN.set(chosen).expect("calibrated once");
    divan.main();
}

// ---------------------------------------------------------------------------------------------
// Benches: one group per problem and target.

macro_rules! group {
    ($group:ident, $problem:ty, $n:literal, $t:literal) => {
        mod $group {
            use super::*;

            #[divan::bench]
            fn odyn_rodas5p() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdynRodas5P, $t)
            }

            #[divan::bench]
            fn odyn_rosenbrock23() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdynRosenbrock23, $t)
            }

            #[divan::bench]
            fn odyn_bdf() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdynBdf, $t)
            }

            #[divan::bench]
            fn cvode_bdf() -> [f64; $n] {
                timed::<$problem, $n>(Solver::CvodeBdf, $t)
            }

            #[divan::bench]
            fn diffsol_bdf() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DiffsolBdf, $t)
            }

            #[divan::bench]
            fn diffsol_esdirk34() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DiffsolEsdirk34, $t)
            }

            #[divan::bench]
            fn de_radau5() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DeRadau5, $t)
            }

            #[divan::bench]
            fn de_bdf() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DeBdf, $t)
            }
        }
    };
}

group!(robertson_1e4, Robertson, 3, 0);
group!(robertson_1e7, Robertson, 3, 1);
group!(hires_1e4, Hires, 8, 0);
group!(hires_1e7, Hires, 8, 1);
group!(pollu_1e4, Pollu, 20, 0);
group!(pollu_1e7, Pollu, 20, 1);
group!(orego_1e4, Orego, 3, 0);
group!(orego_1e7, Orego, 3, 1);
