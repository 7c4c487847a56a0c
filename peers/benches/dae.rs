//! odyn's DAE methods against its peers of issue 50 at equal final error: SUNDIALS IDA (dense
//! and KLU) and diffsol with its mass matrix, on three index-1 problems in mass-matrix form
//! M·y′ = f(t, y).
//!
//! `cargo bench --manifest-path peers/Cargo.toml --bench dae`
//!
//! # Problems (`daes/problems.rs`, `daes/transamp.rs`; written out in `notes/dae-problems.md`)
//!
//! - `chemakzo`: Chemical Akzo Nobel to t = 180 (Bari test set; 6 unknowns, one algebraic);
//! - `transamp`: the transistor amplifier to t = 0.2 (Bari test set; 8 unknowns, singular
//!   non-diagonal M of rank 5);
//! - `transamp_se`: the same DAE in semi-explicit form (unknowns: five capacitor voltages, then
//!   three node voltages; M = diag(−C₁, …, −C₅, 0, 0, 0)), errors measured in the published
//!   unknowns — for diffsol, which takes only zero diagonal entries of M as algebraic and so
//!   cannot start the published form;
//! - `roberdae`: Robertson with y₁ + y₂ + y₃ = 1 as its third row, to t = 1e11.
//!
//! # Method
//!
//! As `stiff.rs`: the error of a run is the largest relative error of the final state over the
//! components whose reference is at least 1e-10 in magnitude; every solver is swept over
//! rtol = 10⁻² … 10⁻¹¹ in quarter decades with atol = rtol·`atol_scale`; for each target error
//! (1e-4, 1e-7) a solver runs at the loosest tolerance whose error is at or below the target
//! (`calibration/mod.rs`). `main` prints the calibration, then every solver of a problem and
//! target runs side by side in one divan group (`chemakzo_1e4`, …). `PEERS_SWEEP=1` also prints
//! every sweep (and why a run failed); `PEERS_PROBLEMS=chemakzo,roberdae` and
//! `PEERS_SOLVERS=ida_dense,diffsol_bdf` calibrate and bench only those problems and solvers (the
//! amplifier's calibration takes minutes: IDA needs up to 10⁶ steps at tight tolerances).
//!
//! # Variants
//!
//! - `ida_dense`, `ida_klu`: SUNDIALS IDA 6.4 (`ida/mod.rs`), residual M·y′ − f, analytic
//!   iteration matrix c_j·M − J, dense LU or KLU, scalar tolerances, a stop time at t_end, the
//!   exact consistent y′(0) of the problem (IDA needs one; `IDACalcIC` cannot split the
//!   amplifier's non-diagonal M into differential and algebraic components).
//! - `ida_dense_noalg`: `ida_dense` with the algebraic unknowns (zero columns of M) left out of
//!   the local error test (`IDASetId`, `IDASetSuppressAlg`), the setting IDA's guide suggests
//!   for index-1 systems whose algebraic components are poorly behaved; only on the problems
//!   that have such unknowns (not the published amplifier, where every unknown's y′ appears).
//! - `diffsol_bdf`, `diffsol_esdirk34`, `diffsol_tr_bdf2`: diffsol 0.18's BDF and SDIRK methods
//!   on nalgebra dense matrices with `NalgebraLU`, the mass matrix through the builder's `mass`
//!   (y ← M·v + β·y), the Jacobian-vector product from the analytic J (evaluated once per
//!   (t, y) and cached, as `stiff.rs` does), stepped with `set_stop_time(t_end)`. diffsol makes
//!   its own initial y′ (and, for rows of M with a zero diagonal, solves the algebraic rows).
//! - `diffsol_bdf_patient`: `diffsol_bdf` with its limits on Newton and error-test failures
//!   within one step raised from 50 and 40 to 1000: with the defaults diffsol gives up on the
//!   amplifier at every tolerance, with these it completes 20 of the 37.
//!
//! - `odyn_rodas5p`, `odyn_bdf`: odyn's Rodas5P and BDF in mass-matrix form on the problems as
//!   `scenes/src/dae.rs` writes them (`#[algebraic]` fields, the amplifier's `fn mass`; the
//!   generated Jacobian), from the same starts, with atol = rtol·`atol_scale` as the peers; only
//!   on the published problems (odyn runs the amplifier as published, so not `transamp_se`).
//!
//! Every variant builds its problem and solver from scratch and returns only its final state;
//! each keeps its own defaults for the controller, first step and Newton settings.

mod calibration;
mod daes;
mod ida;

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::hint::black_box;
use std::sync::OnceLock;

use calibration::{Pick, pick};
use daes::problems::{CHEMAKZO, Dae, ROBERDAE};
use daes::transamp::{TRANSAMP, TRANSAMP_SE};
use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason};

/// The target final errors (max relative error against the reference).
const TARGETS: [f64; 2] = [1e-4, 1e-7];

/// Relative tolerances swept, loosest first: 10⁻² … 10⁻¹¹ in quarter decades.
fn tolerances() -> impl Iterator<Item = f64> {
    (0..=36).map(|k| 10f64.powf(-2.0 - f64::from(k) / 4.0))
}

/// Every solver compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Solver {
    IdaDense,
    IdaKlu,
    IdaDenseNoAlg,
    DiffsolBdf,
    DiffsolBdfPatient,
    DiffsolEsdirk34,
    DiffsolTrBdf2,
    OdynRodas5P,
    OdynBdf,
}

impl Solver {
    const ALL: [Solver; 9] = [
        Solver::IdaDense,
        Solver::IdaKlu,
        Solver::IdaDenseNoAlg,
        Solver::DiffsolBdf,
        Solver::DiffsolBdfPatient,
        Solver::DiffsolEsdirk34,
        Solver::DiffsolTrBdf2,
        Solver::OdynRodas5P,
        Solver::OdynBdf,
    ];

    /// The divan bench name.
    fn name(self) -> &'static str {
        match self {
            Solver::IdaDense => "ida_dense",
            Solver::IdaKlu => "ida_klu",
            Solver::IdaDenseNoAlg => "ida_dense_noalg",
            Solver::DiffsolBdf => "diffsol_bdf",
            Solver::DiffsolBdfPatient => "diffsol_bdf_patient",
            Solver::DiffsolEsdirk34 => "diffsol_esdirk34",
            Solver::DiffsolTrBdf2 => "diffsol_tr_bdf2",
            Solver::OdynRodas5P => "odyn_rodas5p",
            Solver::OdynBdf => "odyn_bdf",
        }
    }
}

/// One solve: the final state and what it cost.
struct Run {
    y: Vec<f64>,
    steps: u64,
    rejected: u64,
    evaluations: u64,
    jacobians: u64,
    factorizations: u64,
}

/// f and a cached J on slices, with counters: diffsol asks for J·v column by column, so J is
/// evaluated once per (t, y).
struct Cached<'a> {
    dae: &'a Dae,
    /// (t, y, J) of the last evaluation.
    jacobian: RefCell<(f64, Vec<f64>, Vec<f64>)>,
    evaluations: Cell<u64>,
    jacobians: Cell<u64>,
}

impl<'a> Cached<'a> {
    fn new(dae: &'a Dae) -> Self {
        let n = dae.n;
        Cached {
            dae,
            jacobian: RefCell::new((f64::NAN, vec![f64::NAN; n], vec![0.0; n * n])),
            evaluations: Cell::new(0),
            jacobians: Cell::new(0),
        }
    }

    fn f(&self, t: f64, y: &[f64], out: &mut [f64]) {
        self.evaluations.set(self.evaluations.get() + 1);
        (self.dae.f)(t, y, out);
    }

    /// out = J(t, y)·v.
    fn jacobian_times(&self, t: f64, y: &[f64], v: &[f64], out: &mut [f64]) {
        let n = self.dae.n;
        let mut cache = self.jacobian.borrow_mut();
        if cache.0 != t || cache.1 != y {
            self.jacobians.set(self.jacobians.get() + 1);
            cache.0 = t;
            cache.1.copy_from_slice(y);
            (self.dae.jacobian)(t, y, &mut cache.2);
        }
        for (r, o) in out.iter_mut().enumerate() {
            *o = (0..n).map(|c| cache.2[c * n + r] * v[c]).sum();
        }
    }
}

/// Solves `dae` with `solver` at rtol = `rtol`, atol = rtol · `atol_scale`, or `None` if the
/// solver fails.
fn solve(dae: &Dae, solver: Solver, rtol: f64) -> Option<Run> {
    let atol = rtol * dae.atol_scale;
    match solver {
        Solver::IdaDense => ida_run(dae, ida::Linear::Dense, false, rtol, atol),
        Solver::IdaKlu => ida_run(dae, ida::Linear::Klu, false, rtol, atol),
        Solver::IdaDenseNoAlg => ida_run(dae, ida::Linear::Dense, true, rtol, atol),
        Solver::OdynRodas5P => daes::odyn::solve(dae, odyn::Method::Rodas5P, rtol, atol),
        Solver::OdynBdf => daes::odyn::solve(dae, odyn::Method::Bdf, rtol, atol),
        _ => diffsol_run(dae, solver, rtol, atol),
    }
}

/// The IDA equations of `dae`.
fn ida_equations(dae: &Dae) -> ida::Equations<'_> {
    ida::Equations {
        n: dae.n,
        f: &dae.f,
        jacobian: &dae.jacobian,
        mass: dae.mass,
    }
}

fn ida_run(dae: &Dae, linear: ida::Linear, suppress: bool, rtol: f64, atol: f64) -> Option<Run> {
    let equations = ida_equations(dae);
    let (y0, yp0) = (dae.y0, (dae.yp0)());
    let run = ida::solve(
        &equations, linear, suppress, y0, &yp0, dae.t_end, rtol, atol,
    )?;
    Some(Run {
        y: run.y,
        steps: run.steps,
        rejected: run.rejected,
        evaluations: run.evaluations,
        jacobians: run.jacobians,
        factorizations: run.factorizations,
    })
}

fn diffsol_run(dae: &Dae, solver: Solver, rtol: f64, atol: f64) -> Option<Run> {
    let cached = Cached::new(dae);
    let n = dae.n;
    let problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| cached.f(t, x, y),
            |x: &[f64], _p: &[f64], t: f64, v: &[f64], y: &mut [f64]| {
                cached.jacobian_times(t, x, v, y)
            },
        )
        .mass(|v: &[f64], _p: &[f64], _t: f64, beta: f64, y: &mut [f64]| {
            for (r, yr) in y.iter_mut().enumerate() {
                let mv: f64 = (0..n).map(|c| dae.mass[c * n + r] * v[c]).sum();
                *yr = mv + beta * *yr;
            }
        })
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(dae.y0),
            n,
        )
        .build()
        .map_err(report)
        .ok()?;
    let mut problem = problem;
    if solver == Solver::DiffsolBdfPatient {
        problem.ode_options.max_nonlinear_solver_failures = PATIENT;
        problem.ode_options.max_error_test_failures = PATIENT;
    }
    let (y, stats) = match solver {
        Solver::DiffsolBdf | Solver::DiffsolBdfPatient => {
            let mut method = problem.bdf::<NalgebraLU<f64>>().map_err(report).ok()?;
            step_to_end(&mut method, dae.t_end)?;
            (method.state().y.clone(), method.get_statistics().clone())
        }
        Solver::DiffsolEsdirk34 => {
            let mut method = problem.esdirk34::<NalgebraLU<f64>>().map_err(report).ok()?;
            step_to_end(&mut method, dae.t_end)?;
            (method.state().y.clone(), method.get_statistics().clone())
        }
        _ => {
            let mut method = problem.tr_bdf2::<NalgebraLU<f64>>().map_err(report).ok()?;
            step_to_end(&mut method, dae.t_end)?;
            (method.state().y.clone(), method.get_statistics().clone())
        }
    };
    Some(Run {
        y: (0..n).map(|i| y[i]).collect(),
        steps: stats.number_of_steps as u64,
        rejected: stats.number_of_error_test_failures as u64,
        evaluations: cached.evaluations.get(),
        jacobians: cached.jacobians.get(),
        factorizations: stats.number_of_linear_solver_setups as u64,
    })
}

/// Prints a diffsol failure under `PEERS_SWEEP`.
fn report(e: diffsol::DiffsolError) {
    if std::env::var_os("PEERS_SWEEP").is_some() {
        eprintln!("    diffsol: {e}");
    }
}

/// `diffsol_bdf_patient`'s limit on Newton and on error-test failures within one step (diffsol's
/// defaults: 50 and 40).
const PATIENT: usize = 1000;

/// Steps a diffsol solver to `t_end`, or `None` if a step fails.
fn step_to_end<'a, E, S>(method: &mut S, t_end: f64) -> Option<()>
where
    E: diffsol::OdeEquations<T = f64> + 'a,
    S: OdeSolverMethod<'a, E>,
{
    method.set_stop_time(t_end).map_err(report).ok()?;
    while method.step().map_err(report).ok()? != OdeSolverStopReason::TstopReached {}
    let t = method.state().t;
    if t != t_end && std::env::var_os("PEERS_SWEEP").is_some() {
        eprintln!("    diffsol: stopped at t = {t:e}, not {t_end:e}");
    }
    (t == t_end).then_some(())
}

// ---------------------------------------------------------------------------------------------
// Calibration.

/// The chosen tolerance of each (problem, target index, solver).
static CHOSEN: OnceLock<HashMap<(&'static str, usize, Solver), f64>> = OnceLock::new();

/// The largest relative error over the components whose reference is at least 1e-10.
fn max_relative_error(y: &[f64], reference: &[f64]) -> f64 {
    y.iter()
        .zip(reference)
        .filter(|(_, r)| r.abs() >= 1e-10)
        .fold(0.0, |m: f64, (a, b)| m.max(((a - b) / b).abs()))
}

/// One solver's sweep: (rtol, final error, run) for each tolerance the solver completed.
type Sweep = Vec<(f64, f64, Run)>;

/// Sweeps every solver over the tolerances on `dae`, prints the calibration for each target and
/// records the chosen tolerances.
fn calibrate(dae: &'static Dae, chosen: &mut HashMap<(&'static str, usize, Solver), f64>) {
    println!(
        "\n{}, t = {}: loosest rtol (atol = rtol·{:.0e}) whose final max relative error is at or \
         below the target",
        dae.name, dae.t_end, dae.atol_scale
    );
    // PEERS_SOLVERS=ida_dense,diffsol_bdf calibrates (and so benches) only those.
    let only = std::env::var("PEERS_SOLVERS").ok();
    let sweeps: Vec<(Solver, Sweep)> = Solver::ALL
        .iter()
        .filter(|solver| {
            only.as_ref()
                .is_none_or(|names| names.split(',').any(|n| n == solver.name()))
        })
        .filter(|&&solver| {
            // Without algebraic unknowns ida_dense_noalg is ida_dense.
            let applies = solver != Solver::IdaDenseNoAlg
                || ida::algebraic(&ida_equations(dae)).contains(&true);
            if !applies {
                println!(
                    "  {}: no zero column in M, the same as ida_dense",
                    solver.name()
                );
            }
            // odyn solves the published amplifier; the semi-explicit one is for diffsol.
            let odyn = matches!(solver, Solver::OdynRodas5P | Solver::OdynBdf);
            applies && !(odyn && dae.name == "transamp_se")
        })
        .map(|&solver| {
            let sweep = tolerances()
                .filter_map(|rtol| {
                    let run = solve(dae, solver, rtol)?;
                    let error = max_relative_error(&(dae.published)(&run.y), dae.reference);
                    Some((rtol, error, run))
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
            "  target {target:.0e}:\n    {:<20}{:>10}{:>11}{:>8}{:>7}{:>8}{:>7}{:>7}  tighter tolerances",
            "solver", "rtol", "error", "steps", "rej", "f", "J", "LU"
        );
        for (solver, sweep) in &sweeps {
            let errors: Vec<f64> = sweep.iter().map(|(_, e, _)| *e).collect();
            let (k, note) = match pick(&errors, target) {
                Pick::Met(k, note) => (k, note),
                Pick::NotReached(best) => {
                    println!(
                        "    {:<20}  not reached (best error {best:.1e}; {} of 37 runs completed)",
                        solver.name(),
                        sweep.len()
                    );
                    continue;
                }
            };
            let (rtol, error, run) = &sweep[k];
            println!(
                "    {:<20}{rtol:>10.2e}{error:>11.2e}{:>8}{:>7}{:>8}{:>7}{:>7}  {note}",
                solver.name(),
                run.steps,
                run.rejected,
                run.evaluations,
                run.jacobians,
                run.factorizations
            );
            chosen.insert((dae.name, t, *solver), *rtol);
        }
    }
}

/// Solves with the calibrated tolerance of `solver` for `dae` and target `t`.
fn timed(dae: &Dae, solver: Solver, t: usize) -> Vec<f64> {
    let rtol = CHOSEN.get().expect("calibrated")[&(dae.name, t, solver)];
    solve(dae, black_box(solver), black_box(rtol))
        .expect("the calibrated run succeeded")
        .y
}

fn main() {
    let mut chosen = HashMap::new();
    // PEERS_PROBLEMS=chemakzo,roberdae calibrates (and so benches) only those.
    let only = std::env::var("PEERS_PROBLEMS").ok();
    for dae in [&CHEMAKZO, &TRANSAMP, &TRANSAMP_SE, &ROBERDAE] {
        if only
            .as_ref()
            .is_none_or(|names| names.split(',').any(|n| n == dae.name))
        {
            calibrate(dae, &mut chosen);
        }
    }
    println!();
    let mut divan = divan::Divan::from_args();
    for name in [
        CHEMAKZO.name,
        TRANSAMP.name,
        TRANSAMP_SE.name,
        ROBERDAE.name,
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
    ($group:ident, $dae:expr, $t:literal) => {
        mod $group {
            use super::*;

            #[divan::bench]
            fn ida_dense() -> Vec<f64> {
                timed(&$dae, Solver::IdaDense, $t)
            }

            #[divan::bench]
            fn ida_klu() -> Vec<f64> {
                timed(&$dae, Solver::IdaKlu, $t)
            }

            #[divan::bench]
            fn ida_dense_noalg() -> Vec<f64> {
                timed(&$dae, Solver::IdaDenseNoAlg, $t)
            }

            #[divan::bench]
            fn diffsol_bdf() -> Vec<f64> {
                timed(&$dae, Solver::DiffsolBdf, $t)
            }

            #[divan::bench]
            fn diffsol_bdf_patient() -> Vec<f64> {
                timed(&$dae, Solver::DiffsolBdfPatient, $t)
            }

            #[divan::bench]
            fn diffsol_esdirk34() -> Vec<f64> {
                timed(&$dae, Solver::DiffsolEsdirk34, $t)
            }

            #[divan::bench]
            fn diffsol_tr_bdf2() -> Vec<f64> {
                timed(&$dae, Solver::DiffsolTrBdf2, $t)
            }

            #[divan::bench]
            fn odyn_rodas5p() -> Vec<f64> {
                timed(&$dae, Solver::OdynRodas5P, $t)
            }

            #[divan::bench]
            fn odyn_bdf() -> Vec<f64> {
                timed(&$dae, Solver::OdynBdf, $t)
            }
        }
    };
}

group!(chemakzo_1e4, CHEMAKZO, 0);
group!(chemakzo_1e7, CHEMAKZO, 1);
group!(transamp_1e4, TRANSAMP, 0);
group!(transamp_1e7, TRANSAMP, 1);
group!(transamp_se_1e4, TRANSAMP_SE, 0);
group!(transamp_se_1e7, TRANSAMP_SE, 1);
group!(roberdae_1e4, ROBERDAE, 0);
group!(roberdae_1e7, ROBERDAE, 1);
