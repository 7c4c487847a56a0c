//! odyn's adaptive Runge–Kutta methods against the peer crates' adaptive methods of the same
//! families, at equal final error — never at equal tolerance, because every code weighs its error
//! estimate differently, so the same `rtol` buys different accuracy in each.
//!
//! `cargo bench --manifest-path peers/Cargo.toml --bench adaptive`
//!
//! # Problems
//!
//! Each with a reference final state from `scripts/reference_adaptive.py` (Taylor-series
//! integration at 40–50 digits of the IVP exactly as an f64 program holds its data):
//!
//! - `lorenz`: σ = 10, ρ = 28, β = 8.0/3.0 (f64), from (1, 0, 0) to t = 20. Chaotic: the flow
//!   amplifies errors by ~e^{0.9t}, so tight targets cost many steps.
//! - `arenstorf`: the periodic Arenstorf orbit (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.0),
//!   μ = 0.012277471, over one period t = 17.065216560157964.
//! - `pleiades`: seven bodies in the plane, masses mᵢ = i (HNW I, §II.10; Bari test set PLEI), to
//!   t = 3; 28 components.
//!
//! # Method
//!
//! For each solver, rtol = atol is swept over 10⁻³ … 10⁻¹³ in quarter decades and the final
//! max-norm error against the reference is recorded. For each target error (1e-6, 1e-9) the
//! solver's configuration is the loosest tolerance whose error is at or below the target; a target
//! a solver never reaches is skipped for it. `main` prints this calibration (tolerance, error,
//! steps, f-evaluations) before anything is timed; then every solver of a problem and target runs
//! side by side in one divan group (`lorenz_1e6`, `lorenz_1e9`, …). Compare medians within a
//! group: the machine is shared, so absolute times drift between runs. `PEERS_SWEEP=1` also prints
//! every solver's whole sweep.
//!
//! # Variants
//!
//! - `odyn_tsit5`, `odyn_dop853`: the `#[system]` model through `simulate()` with
//!   `Method::Tsit5` / `Method::Dop853`, recording only the initial and final states
//!   (`record_every(u64::MAX)`) and keeping no dense output.
//! - `ode_solvers_dopri5`, `ode_solvers_dop853`: `ode_solvers::{Dopri5, Dop853}` with
//!   `OutputType::Sparse`.
//! - `de_dopri5`, `de_dop853`: `differential-equations`' `ExplicitRungeKutta::{dopri5, dop853}`
//!   through `IVP::ode(..).t_eval([t_end])`.
//! - `diffsol_tsit45`: diffsol's `tsit45()` (Tsitouras 5(4)) on nalgebra vectors, stepped with
//!   `set_stop_time(t_end)` until it reports `TstopReached`.
//!
//! Every variant solves from scratch (building its problem and solver) and returns only its final
//! state. Every solver keeps its own defaults for the controller, first step and norm; step limits
//! (`differential-equations` stops at 10 000 steps by default) are raised where they would end a
//! run, which costs nothing.
//!
//! # The peers' costs are kept, not worked around
//!
//! Each gets the cheapest output mode it has:
//!
//! - `ode_solvers` has no final-state-only mode. `Sparse` output pushes (t, y) for every accepted
//!   step into growing vectors; its `Dense` output with one output interval would store two points
//!   but compute dense-output coefficients each step (for `Dop853`, three more f-evaluations a
//!   step), so `Sparse` is the cheaper. Its stiffness detection runs every 1000 steps, as by
//!   default.
//! - `differential-equations`' `t_eval([t_end])` stores only the final state, but its solve loop
//!   clones the current and previous states every step, and its DOP853 computes the three extra
//!   dense-output stages and the interpolation coefficients on every accepted step whether or
//!   not anything is interpolated (its f-evaluation counts include them).
//! - diffsol works on heap vectors (`NalgebraVec`) behind closures over slices, and builds its
//!   problem (`OdeBuilder::build`) and solver on every solve; it reports no f-evaluation count, so
//!   the calibration counts its right-hand-side calls itself (not while timing).
//!
//! Before anything is timed, `main` also checks that every solver's right-hand side agrees with
//! the `#[system]` model's at the initial state, so all of them integrate the same equations.

#![allow(
    clippy::excessive_precision,
    reason = "reference values are quoted with the 17 digits the reference script prints"
)]

use std::cell::Cell;
use std::collections::HashMap;
use std::hint::black_box;
use std::sync::OnceLock;

use differential_equations::ivp::IVP;
use differential_equations::methods::ExplicitRungeKutta;
use differential_equations::ode::ODE;
use diffsol::{NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason};
use odyn::prelude::*;

mod calibration;

use calibration::{Pick, pick};
use scenes::*;

/// The target final errors (max norm against the reference).
const TARGETS: [f64; 2] = [1e-6, 1e-9];

/// Tolerances swept, loosest first: 10⁻³ … 10⁻¹³ in quarter decades.
fn tolerances() -> impl Iterator<Item = f64> {
    (0..=40).map(|k| 10f64.powf(-3.0 - f64::from(k) / 4.0))
}

// ---------------------------------------------------------------------------------------------
// Problems.

/// A test problem: a `#[system]` model with its initial state in its fields, the same right-hand
/// side on plain arrays for the peers, an end time and a reference final state.
trait Problem<const N: usize>: Model + Copy + 'static {
    /// The group name prefix.
    const GROUP: &'static str;
    /// The end time.
    const T_END: f64;
    /// y(T_END), in the layout of [`odyn::State::as_slice`].
    const REFERENCE: [f64; N];
    /// The model with its initial state.
    fn instance() -> Self;
    /// f(y) on plain arrays, with the arithmetic of the `#[system]` function.
    fn rhs(&self, y: &[f64; N], dy: &mut [f64; N]);
    /// The initial state as a plain array.
    fn y0(&self) -> [f64; N] {
        flat(&self.state())
    }
}

/// A typed odyn state as a plain array (positions before velocities for second-order models).
fn flat<S: odyn::State, const N: usize>(state: &S) -> [f64; N] {
    state
        .as_slice()
        .try_into()
        .expect("state has the problem's dimension")
}

impl Problem<3> for Lorenz {
    const GROUP: &'static str = "lorenz";
    const T_END: f64 = 20.0;
    // [f64 beta] Taylor dps=50 at t = 20.
    const REFERENCE: [f64; 3] = [
        -8.021_143_613_317_216,
        -1.190_546_474_917_122_3e1,
        1.985_637_485_839_864_5e1,
    ];

    fn instance() -> Self {
        Lorenz {
            x: 1.0,
            y: 0.0,
            z: 0.0,
            sigma: 10.0,
            rho: 28.0,
            beta: 8.0 / 3.0,
        }
    }

    fn rhs(&self, [x, y, z]: &[f64; 3], dy: &mut [f64; 3]) {
        *dy = [
            self.sigma * (y - x),
            x * (self.rho - z) - y,
            x * y - self.beta * z,
        ];
    }
}

impl Problem<4> for Arenstorf {
    const GROUP: &'static str = "arenstorf";
    const T_END: f64 = Arenstorf::PERIOD;
    const REFERENCE: [f64; 4] = Arenstorf::AT_PERIOD;

    fn instance() -> Self {
        Arenstorf::orbit()
    }

    fn rhs(&self, &[y1, y2, v1, v2]: &[f64; 4], dy: &mut [f64; 4]) {
        let mu = self.mu;
        let mup = 1.0 - self.mu;
        let d1 = ((y1 + mu).powi(2) + y2.powi(2)).powf(1.5);
        let d2 = ((y1 - mup).powi(2) + y2.powi(2)).powf(1.5);
        *dy = [
            v1,
            v2,
            y1 + 2.0 * v2 - mup * (y1 + mu) / d1 - mu * (y1 - mup) / d2,
            y2 - 2.0 * v1 - mup * y2 / d1 - mu * y2 / d2,
        ];
    }
}

/// Pleiades bodies.
const B: usize = 7;

impl Problem<28> for Pleiades {
    const GROUP: &'static str = "pleiades";
    const T_END: f64 = 3.0;
    // layout (x1..x7, y1..y7, x1'..x7', y1'..y7').
    const REFERENCE: [f64; 28] = Pleiades::AT_3;

    fn instance() -> Self {
        Pleiades::start()
    }

    fn rhs(&self, s: &[f64; 28], dy: &mut [f64; 28]) {
        let (x, rest) = s.split_at(B);
        let (y, velocities) = rest.split_at(B);
        dy[..2 * B].copy_from_slice(velocities);
        let (ax, ay) = dy[2 * B..].split_at_mut(B);
        ax.fill(0.0);
        ay.fill(0.0);
        for i in 0..B {
            for j in (i + 1)..B {
                let dx = x[j] - x[i];
                let dyy = y[j] - y[i];
                let r2 = dx * dx + dyy * dyy;
                let w = 1.0 / (r2 * r2.sqrt());
                ax[i] += self.m[j] * w * dx;
                ay[i] += self.m[j] * w * dyy;
                ax[j] -= self.m[i] * w * dx;
                ay[j] -= self.m[i] * w * dyy;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Solvers.

/// Every solver compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Solver {
    OdynTsit5,
    OdynDop853,
    OdeSolversDopri5,
    OdeSolversDop853,
    DeDopri5,
    DeDop853,
    DiffsolTsit45,
}

impl Solver {
    const ALL: [Solver; 7] = [
        Solver::OdynTsit5,
        Solver::OdynDop853,
        Solver::OdeSolversDopri5,
        Solver::OdeSolversDop853,
        Solver::DeDopri5,
        Solver::DeDop853,
        Solver::DiffsolTsit45,
    ];

    /// The divan bench name.
    fn name(self) -> &'static str {
        match self {
            Solver::OdynTsit5 => "odyn_tsit5",
            Solver::OdynDop853 => "odyn_dop853",
            Solver::OdeSolversDopri5 => "ode_solvers_dopri5",
            Solver::OdeSolversDop853 => "ode_solvers_dop853",
            Solver::DeDopri5 => "de_dopri5",
            Solver::DeDop853 => "de_dop853",
            Solver::DiffsolTsit45 => "diffsol_tsit45",
        }
    }
}

/// One solve: the final state and what it cost.
struct Run<const N: usize> {
    y: [f64; N],
    /// Accepted steps.
    steps: u64,
    /// Rejected step attempts.
    rejected: u64,
    /// Evaluations of f (for diffsol only counted when asked for; 0 otherwise).
    evaluations: u64,
}

/// Adapts a problem to the peers' traits.
#[derive(Clone, Copy)]
struct Peer<P>(P);

impl<P: Problem<N>, const N: usize> ode_solvers::System<f64, ode_solvers::SVector<f64, N>>
    for Peer<P>
{
    fn system(
        &self,
        _: f64,
        y: &ode_solvers::SVector<f64, N>,
        dy: &mut ode_solvers::SVector<f64, N>,
    ) {
        // An SVector's storage is one column, [[f64; N]; 1].
        self.0.rhs(&y.data.0[0], &mut dy.data.0[0]);
    }
}

impl<P: Problem<N>, const N: usize> ODE<f64, [f64; N]> for Peer<P> {
    fn diff(&self, _: f64, y: &[f64; N], dydt: &mut [f64; N]) {
        self.0.rhs(y, dydt);
    }
}

/// Solves `P` to `P::T_END` with `solver` at rtol = atol = `tol`. `count` counts diffsol's f
/// calls (the other solvers count their own).
fn solve<P: Problem<N>, const N: usize>(
    solver: Solver,
    tol: f64,
    count: Option<&Cell<u64>>,
) -> Run<N> {
    let problem = P::instance();
    match solver {
        Solver::OdynTsit5 => odyn_run(&problem, Method::Tsit5, tol),
        Solver::OdynDop853 => odyn_run(&problem, Method::Dop853, tol),
        Solver::OdeSolversDopri5 => {
            let mut method = ode_solvers::Dopri5::new(
                Peer(problem),
                0.0,
                P::T_END,
                P::T_END,
                problem.y0().into(),
                tol,
                tol,
            );
            method.set_output(ode_solvers::dop_shared::OutputType::Sparse);
            let stats = method.integrate().expect("ode_solvers Dopri5");
            ode_solvers_result(method.y_out(), stats)
        }
        Solver::OdeSolversDop853 => {
            let mut method = ode_solvers::Dop853::new(
                Peer(problem),
                0.0,
                P::T_END,
                P::T_END,
                problem.y0().into(),
                tol,
                tol,
            );
            method.set_output(ode_solvers::dop_shared::OutputType::Sparse);
            let stats = method.integrate().expect("ode_solvers Dop853");
            ode_solvers_result(method.y_out(), stats)
        }
        Solver::DeDopri5 => {
            let method = ExplicitRungeKutta::dopri5()
                .rtol(tol)
                .atol(tol)
                .max_steps(usize::MAX);
            de_run(&problem, method)
        }
        Solver::DeDop853 => {
            let method = ExplicitRungeKutta::dop853()
                .rtol(tol)
                .atol(tol)
                .max_steps(usize::MAX);
            de_run(&problem, method)
        }
        Solver::DiffsolTsit45 => diffsol_run(problem, tol, count),
    }
}

fn odyn_run<P: Problem<N>, const N: usize>(model: &P, method: Method, tol: f64) -> Run<N> {
    let run = model
        .simulate()
        .integrator(method)
        .tolerances(tol, tol)
        .duration(P::T_END)
        .record_every(u64::MAX)
        .dense_output(false)
        .run()
        .expect("odyn run");
    Run {
        y: flat(&run.last().state),
        steps: run.stats.steps,
        rejected: run.stats.rejected,
        evaluations: run.stats.evaluations,
    }
}

fn ode_solvers_result<const N: usize>(
    ys: &[ode_solvers::SVector<f64, N>],
    stats: ode_solvers::dop_shared::Stats,
) -> Run<N> {
    Run {
        y: (*ys.last().expect("ode_solvers records the final state")).into(),
        steps: stats.accepted_steps.into(),
        rejected: stats.rejected_steps.into(),
        evaluations: stats.num_eval.into(),
    }
}

fn de_run<P, S, const N: usize>(problem: &P, method: S) -> Run<N>
where
    P: Problem<N>,
    S: differential_equations::ode::OrdinaryNumericalMethod<f64, [f64; N]>
        + differential_equations::interpolate::Interpolation<f64, [f64; N]>,
{
    let peer = Peer(*problem);
    let solution = IVP::ode(&peer, 0.0, P::T_END, problem.y0())
        .t_eval([P::T_END])
        .method(method)
        .solve()
        .expect("differential-equations solve");
    assert_eq!(
        solution.t,
        [P::T_END],
        "differential-equations returns exactly the final state"
    );
    Run {
        y: solution.y[0],
        steps: solution.steps.accepted as u64,
        rejected: solution.steps.rejected as u64,
        evaluations: solution.evals.function as u64,
    }
}

fn diffsol_run<P: Problem<N>, const N: usize>(
    problem: P,
    tol: f64,
    count: Option<&Cell<u64>>,
) -> Run<N> {
    let y0 = problem.y0();
    let built = OdeBuilder::<NalgebraMat<f64>>::new()
        .rtol(tol)
        .atol([tol])
        .rhs(move |x: &[f64], _p: &[f64], _t: f64, dy: &mut [f64]| {
            if let Some(count) = count {
                count.set(count.get() + 1);
            }
            problem.rhs(
                x.try_into().expect("dimension N"),
                dy.try_into().expect("dimension N"),
            );
        })
        .init(
            move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&y0),
            N,
        )
        .build()
        .expect("diffsol problem");
    let mut solver = built.tsit45().expect("diffsol tsit45");
    solver.set_stop_time(P::T_END).expect("diffsol stop time");
    while solver.step().expect("diffsol step") != OdeSolverStopReason::TstopReached {}
    let state = solver.state();
    assert_eq!(state.t, P::T_END, "diffsol stops at the end time");
    let mut y = [0.0; N];
    for (i, yi) in y.iter_mut().enumerate() {
        *yi = state.y[i];
    }
    let stats = solver.get_statistics();
    Run {
        y,
        steps: stats.number_of_steps as u64,
        rejected: stats.number_of_error_test_failures as u64,
        evaluations: count.map_or(0, Cell::get),
    }
}

// ---------------------------------------------------------------------------------------------
// Calibration.

/// The chosen tolerance of each (problem, target index, solver).
static CHOSEN: OnceLock<HashMap<(&'static str, usize, Solver), f64>> = OnceLock::new();

/// Max-norm distance.
fn max_error<const N: usize>(y: &[f64; N], reference: &[f64; N]) -> f64 {
    y.iter()
        .zip(reference)
        .fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()))
}

/// Asserts that the peers' right-hand side is the model's, at the initial state.
fn check_rhs<P: Problem<N>, const N: usize>() {
    let model = P::instance();
    let state = model.state();
    let mut typed = state.clone();
    model.derivative(0.0, &state, &mut typed);
    let mut plain = [0.0; N];
    model.rhs(&model.y0(), &mut plain);
    let scale = plain.iter().fold(1.0, |m: f64, v| m.max(v.abs()));
    let diff = max_error(&flat(&typed), &plain);
    assert!(
        diff <= 1e-14 * scale,
        "{}: the peers' f differs from the model's by {diff:e}",
        P::GROUP
    );
}

/// One solver's sweep: (tolerance, final error, run) for each tolerance, loosest first.
type Sweep<const N: usize> = Vec<(f64, f64, Run<N>)>;

/// Sweeps every solver over the tolerances on `P`, prints the calibration for each target and
/// records the chosen tolerances.
fn calibrate<P: Problem<N>, const N: usize>(
    chosen: &mut HashMap<(&'static str, usize, Solver), f64>,
) {
    check_rhs::<P, N>();
    println!(
        "\n{}, t = {}: loosest rtol = atol whose final max-norm error is at or below the target",
        P::GROUP,
        P::T_END
    );
    let sweeps: Vec<(Solver, Sweep<N>)> = Solver::ALL
        .iter()
        .map(|&solver| {
            let sweep = tolerances()
                .map(|tol| {
                    let count = Cell::new(0);
                    let run = solve::<P, N>(solver, tol, Some(&count));
                    (tol, max_error(&run.y, &P::REFERENCE), run)
                })
                .collect();
            (solver, sweep)
        })
        .collect();
    if std::env::var_os("PEERS_SWEEP").is_some() {
        for (solver, sweep) in &sweeps {
            println!(
                "  sweep {}: tol error steps rejected f-evals",
                solver.name()
            );
            for (tol, error, run) in sweep {
                println!(
                    "    {tol:.2e} {error:.2e} {} {} {}",
                    run.steps, run.rejected, run.evaluations
                );
            }
        }
    }
    for (t, &target) in TARGETS.iter().enumerate() {
        println!(
            "  target {target:.0e}:\n    {:<20}{:>10}{:>11}{:>9}{:>10}{:>9}  tighter tolerances",
            "solver", "tol", "error", "steps", "rejected", "f-evals"
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
            let (tol, error, run) = &sweep[k];
            println!(
                "    {:<20}{tol:>10.2e}{error:>11.2e}{:>9}{:>10}{:>9}  {note}",
                solver.name(),
                run.steps,
                run.rejected,
                run.evaluations
            );
            chosen.insert((P::GROUP, t, *solver), *tol);
        }
    }
}

/// Solves with the calibrated tolerance of `solver` for `P` and target `t`.
fn timed<P: Problem<N>, const N: usize>(solver: Solver, t: usize) -> [f64; N] {
    let tol = CHOSEN.get().expect("calibrated")[&(P::GROUP, t, solver)];
    solve::<P, N>(black_box(solver), black_box(tol), None).y
}

fn main() {
    let mut chosen = HashMap::new();
    calibrate::<Lorenz, 3>(&mut chosen);
    calibrate::<Arenstorf, 4>(&mut chosen);
    calibrate::<Pleiades, 28>(&mut chosen);
    println!();
    let mut divan = divan::Divan::from_args();
    for name in [
        <Lorenz as Problem<3>>::GROUP,
        <Arenstorf as Problem<4>>::GROUP,
        <Pleiades as Problem<28>>::GROUP,
    ] {
        for t in 0..TARGETS.len() {
            for solver in Solver::ALL {
                if !chosen.contains_key(&(name, t, solver)) {
                    let group = group_name(name, t);
                    divan =
                        divan.skip_exact(format!("{}::{group}::{}", module_path!(), solver.name()));
                }
            }
        }
    }
    CHOSEN.set(chosen).expect("calibrated once");
    divan.main();
}

/// The divan group of a problem and target: `lorenz_1e6`, `lorenz_1e9`, ….
fn group_name(problem: &str, t: usize) -> String {
    format!("{problem}_1e{}", -TARGETS[t].log10().round() as i32)
}

// ---------------------------------------------------------------------------------------------
// Benches: one group per problem and target.

macro_rules! group {
    ($group:ident, $problem:ty, $n:literal, $t:literal) => {
        mod $group {
            use super::*;

            #[divan::bench]
            fn odyn_tsit5() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdynTsit5, $t)
            }

            #[divan::bench]
            fn odyn_dop853() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdynDop853, $t)
            }

            #[divan::bench]
            fn ode_solvers_dopri5() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdeSolversDopri5, $t)
            }

            #[divan::bench]
            fn ode_solvers_dop853() -> [f64; $n] {
                timed::<$problem, $n>(Solver::OdeSolversDop853, $t)
            }

            #[divan::bench]
            fn de_dopri5() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DeDopri5, $t)
            }

            #[divan::bench]
            fn de_dop853() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DeDop853, $t)
            }

            #[divan::bench]
            fn diffsol_tsit45() -> [f64; $n] {
                timed::<$problem, $n>(Solver::DiffsolTsit45, $t)
            }
        }
    };
}

group!(lorenz_1e6, Lorenz, 3, 0);
group!(lorenz_1e9, Lorenz, 3, 1);
group!(arenstorf_1e6, Arenstorf, 4, 0);
group!(arenstorf_1e9, Arenstorf, 4, 1);
group!(pleiades_1e6, Pleiades, 28, 0);
group!(pleiades_1e9, Pleiades, 28, 1);
