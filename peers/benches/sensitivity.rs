//! odyn's forward sensitivities against diffsol's, on Robertson's kinetics at equal accuracy —
//! never at equal tolerance, because each code weighs its error estimate differently.
//!
//! `cargo bench --manifest-path peers/Cargo.toml --bench sensitivity`
//!
//! # Problem
//!
//! `scenes::Robertson::classic()` (a = 1, b = c = 0; k₁ = 0.04, k₂ = 10⁴, k₃ = 3·10⁷, the three
//! `#[param]`s) to t = 40 (Hairer & Wanner's output time) and to t = 10⁵: the state y and the
//! sensitivities ∂y/∂kⱼ, 3 + 3·3 = 12 numbers, at the end time.
//!
//! # Reference and error
//!
//! The reference is odyn's Rodas5P on the augmented system at rtol 10⁻¹², atol 10⁻¹⁸ (10⁻¹⁸/|kⱼ|
//! on ∂y/∂kⱼ). `main` prints how far it is from central differences of whole plain solutions
//! (Rodas5P at rtol 10⁻¹², atol 10⁻²⁰, step hⱼ = 10⁻⁴·kⱼ, as the integration test
//! `stiff_methods_give_robertson_sensitivities_that_match_differences_of_solutions` does), in the
//! error measure below, and how far its y is from the tight plain solve (and, at t = 10⁵, from the
//! 36-digit `scenes::ROBERTSON_1E5`).
//!
//! The error of a run is the largest of: the relative error of each component of y, and for each
//! parameter the largest error in the column ∂y/∂kⱼ relative to that column's largest entry.
//!
//! # Calibration
//!
//! Every solver is swept over rtol = 10⁻² … 10⁻¹¹ in sixteenths of a decade, with atol =
//! rtol·10⁻⁶ on y (Robertson's b is ~10⁻⁵ of a) and atol/|kⱼ| on ∂y/∂kⱼ (CVODES's scaling, as
//! `odyn::fit` uses). Among the tolerances from which on every tighter one stays within
//! 1.2 × 10⁻⁶, the one whose error is closest to 10⁻⁶ (in ratio) is timed; looser tolerances that
//! land within 1.2 × 10⁻⁶ only by cancellation are counted in the printout, not used. `main` prints
//! each pick (rtol, error, steps, rejected steps, the model's f, J and ∂f/∂p evaluations and the
//! factorizations) before anything is timed; `PEERS_SWEEP=1` prints every sweep, and
//! `PEERS_PICK=loosest` times the loosest tolerance within 1.2 × 10⁻⁶ instead, cancellation or
//! not (the stiff bench's rule; diffsol's BDF errors zigzag with rtol, so it gains). Then all
//! solvers of a horizon run side by side in one divan group (`robertson_t40`, `robertson_t1e5`).
//!
//! # Variants
//!
//! - `odyn_rodas5p`, `odyn_bdf`: `Sensitive::new(&model)` through `simulate()` with
//!   `Method::Rodas5P` / `Method::Bdf` and per-component tolerances, recording only the initial
//!   and final states, no dense output. The augmented Jacobian is 12 × 12 (J on its diagonal,
//!   its coupling blocks central differences of the exact J and ∂f/∂p); its W is solved by block
//!   forward substitution on one factorization of the model's 3 × 3 I − cJ.
//! - `diffsol_bdf`, `diffsol_esdirk34`: diffsol 0.18's `bdf_sens` / `esdirk34_sens` on nalgebra
//!   dense matrices with `NalgebraLU`, built with `rhs_sens_implicit` (f, J·v, ∂f/∂p·v) and
//!   `init_sens` (∂y₀/∂p = 0), `sens_rtol` = rtol, `sens_atol` = atol and `param_scales` = k (so
//!   diffsol's ∂y/∂kⱼ tolerance is atol/|kⱼ|, the same rule), stepped with `set_stop_time`. It
//!   factorizes the 3 × 3 iteration matrix and solves each sensitivity against it.
//!
//! Both codes integrate the same equations with odyn's generated f, exact J and exact ∂f/∂p:
//! diffsol asks for products J·v and ∂f/∂p·v, which evaluate J (or ∂f/∂p) once per (t, y) and
//! multiply the cached matrix. Every timed run builds its problem and solver from scratch and
//! returns the final y and ∂y/∂k; each code keeps its own defaults for the controller, first step
//! and Newton settings.

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::hint::black_box;
use std::sync::OnceLock;

use diffsol::{
    NalgebraLU, NalgebraMat, OdeBuilder, OdeEquations, OdeSolverMethod, OdeSolverStopReason, Vector,
};
use odyn::nalgebra::{DMatrix, SMatrix};
use odyn::prelude::*;
use odyn::sensitivity::Sensitive;
use odyn::{Parameters, Tolerances};
use scenes::Robertson;

/// Species.
const N: usize = 3;
/// Parameters (k₁, k₂, k₃).
const P: usize = 3;
/// The target error.
const TARGET: f64 = 1e-6;
/// How far above the target a pick may land.
const SLACK: f64 = 1.2;
/// atol = rtol · ATOL_SCALE on y.
const ATOL_SCALE: f64 = 1e-6;
/// The end times, with their divan group names.
const HORIZONS: [(&str, f64); 2] = [("robertson_t40", 40.0), ("robertson_t1e5", 1e5)];

/// Relative tolerances swept, loosest first: 10⁻² … 10⁻¹¹ in sixteenths of a decade.
fn tolerances() -> impl Iterator<Item = f64> {
    (0..=144).map(|k| 10f64.powf(-2.0 - f64::from(k) / 16.0))
}

/// y and ∂y/∂k at the end time: `s[i][j]` = ∂yᵢ/∂kⱼ.
#[derive(Clone, Copy, Debug)]
struct End {
    y: [f64; N],
    s: [[f64; P]; N],
}

/// One solve: the end values and what it cost.
struct Run {
    end: End,
    steps: u64,
    rejected: u64,
    /// The model's f evaluations.
    f: u64,
    /// The model's J evaluations.
    jacobians: u64,
    /// The model's ∂f/∂p evaluations.
    parameter_jacobians: u64,
    factorizations: u64,
}

/// Every solver compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Solver {
    OdynRodas5P,
    OdynBdf,
    DiffsolBdf,
    DiffsolEsdirk34,
}

impl Solver {
    const ALL: [Solver; 4] = [
        Solver::OdynRodas5P,
        Solver::OdynBdf,
        Solver::DiffsolBdf,
        Solver::DiffsolEsdirk34,
    ];

    /// The divan bench name.
    fn name(self) -> &'static str {
        match self {
            Solver::OdynRodas5P => "odyn_rodas5p",
            Solver::OdynBdf => "odyn_bdf",
            Solver::DiffsolBdf => "diffsol_bdf",
            Solver::DiffsolEsdirk34 => "diffsol_esdirk34",
        }
    }
}

/// Solves to `t_end` with `solver` at rtol = `rtol`, atol = rtol · `ATOL_SCALE` (over |kⱼ| on
/// ∂y/∂kⱼ), or `None` if the solver fails.
fn solve(solver: Solver, rtol: f64, t_end: f64) -> Option<Run> {
    let atol = rtol * ATOL_SCALE;
    match solver {
        Solver::OdynRodas5P => odyn_run(Method::Rodas5P, rtol, atol, t_end),
        Solver::OdynBdf => odyn_run(Method::Bdf, rtol, atol, t_end),
        Solver::DiffsolBdf | Solver::DiffsolEsdirk34 => diffsol_run(solver, rtol, atol, t_end),
    }
}

// ---------------------------------------------------------------------------------------------
// odyn.

fn odyn_run(method: Method, rtol: f64, atol: f64, t_end: f64) -> Option<Run> {
    let model = Robertson::classic();
    let mut atols = vec![atol; N];
    for k in model.parameters() {
        atols.extend([atol / k.abs(); N]);
    }
    let sensitive = Sensitive::new(&model);
    let run = sensitive
        .simulate()
        .integrator(method)
        .with_tolerances(Tolerances::per_component(rtol, atols))
        .duration(t_end)
        .record_every(u64::MAX)
        .dense_output(false)
        .run()
        .ok()?;
    let last = &run.last().state;
    let (y, s) = (last.state(), last.sensitivities());
    let mut end = End {
        y: [0.0; N],
        s: [[0.0; P]; N],
    };
    for i in 0..N {
        end.y[i] = y[i];
        for j in 0..P {
            end.s[i][j] = s[(i, j)];
        }
    }
    let work = sensitive.work();
    Some(Run {
        end,
        steps: run.stats.steps,
        rejected: run.stats.rejected,
        f: work.derivatives,
        jacobians: work.jacobians,
        parameter_jacobians: work.parameter_jacobians,
        factorizations: run.stats.factorizations,
    })
}

// ---------------------------------------------------------------------------------------------
// diffsol.

/// The model's generated f, J and ∂f/∂p on plain slices, with the caches diffsol's products read
/// and counters.
struct Plain {
    model: Robertson,
    y: RefCell<<Robertson as Model>::State>,
    dy: RefCell<<Robertson as Model>::State>,
    /// J at (t, y) of the last evaluation.
    jacobian: RefCell<(f64, [f64; N], SMatrix<f64, N, N>)>,
    /// ∂f/∂p at (t, y) of the last evaluation.
    dfdp: RefCell<(f64, [f64; N], DMatrix<f64>)>,
    evaluations: Cell<u64>,
    jacobians: Cell<u64>,
    parameter_jacobians: Cell<u64>,
}

impl Plain {
    fn new() -> Self {
        let model = Robertson::classic();
        let state = model.state();
        Plain {
            y: RefCell::new(state),
            dy: RefCell::new(state),
            jacobian: RefCell::new((f64::NAN, [f64::NAN; N], SMatrix::zeros())),
            dfdp: RefCell::new((f64::NAN, [f64::NAN; N], DMatrix::zeros(N, P))),
            model,
            evaluations: Cell::new(0),
            jacobians: Cell::new(0),
            parameter_jacobians: Cell::new(0),
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

    /// J(t, y)·v, J evaluated only when (t, y) differs from the last evaluation's.
    fn jacobian_times(&self, t: f64, y: &[f64], v: &[f64], out: &mut [f64]) {
        let mut cache = self.jacobian.borrow_mut();
        if cache.0 != t || cache.1 != y {
            self.jacobians.set(self.jacobians.get() + 1);
            let mut state = self.y.borrow_mut();
            state.as_mut_slice().copy_from_slice(y);
            cache.0 = t;
            cache.1.copy_from_slice(y);
            self.model.jacobian(t, &state, &mut cache.2);
        }
        for (r, o) in out.iter_mut().enumerate() {
            *o = (0..N).map(|c| cache.2[(r, c)] * v[c]).sum();
        }
    }

    /// ∂f/∂p(t, y)·v, ∂f/∂p evaluated only when (t, y) differs from the last evaluation's.
    fn parameter_jacobian_times(&self, t: f64, y: &[f64], v: &[f64], out: &mut [f64]) {
        let mut cache = self.dfdp.borrow_mut();
        if cache.0 != t || cache.1 != y {
            self.parameter_jacobians
                .set(self.parameter_jacobians.get() + 1);
            let mut state = self.y.borrow_mut();
            state.as_mut_slice().copy_from_slice(y);
            cache.0 = t;
            cache.1.copy_from_slice(y);
            self.model.parameter_jacobian(t, &state, &mut cache.2);
        }
        for (r, o) in out.iter_mut().enumerate() {
            *o = (0..P).map(|c| cache.2[(r, c)] * v[c]).sum();
        }
    }
}

fn diffsol_run(solver: Solver, rtol: f64, atol: f64, t_end: f64) -> Option<Run> {
    let plain = Plain::new();
    let y0: [f64; N] = plain
        .model
        .state()
        .as_slice()
        .try_into()
        .expect("three species");
    let rates = plain.model.parameters();
    let problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .rtol(rtol)
        .atol([atol])
        .sens_rtol(rtol)
        .sens_atol([atol])
        .param_scales(rates.iter().copied())
        // The closures read the model's own rates; diffsol needs p for their number and scales.
        .p(rates.iter().copied())
        .rhs_sens_implicit(
            |x: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| plain.rhs(t, x, dy),
            |x: &[f64], _p: &[f64], t: f64, v: &[f64], jv: &mut [f64]| {
                plain.jacobian_times(t, x, v, jv)
            },
            |x: &[f64], _p: &[f64], t: f64, v: &[f64], pv: &mut [f64]| {
                plain.parameter_jacobian_times(t, x, v, pv)
            },
        )
        .init_sens(
            move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&y0),
            |_p: &[f64], _t: f64, _v: &[f64], y: &mut [f64]| y.fill(0.0),
            N,
        )
        .build()
        .ok()?;
    let (end, stats) = match solver {
        Solver::DiffsolBdf => {
            let mut method = problem.bdf_sens::<NalgebraLU<f64>>().ok()?;
            (
                step_to_end(&mut method, t_end)?,
                method.get_statistics().clone(),
            )
        }
        _ => {
            let mut method = problem.esdirk34_sens::<NalgebraLU<f64>>().ok()?;
            (
                step_to_end(&mut method, t_end)?,
                method.get_statistics().clone(),
            )
        }
    };
    Some(Run {
        end,
        steps: stats.number_of_steps as u64,
        rejected: stats.number_of_error_test_failures as u64,
        f: plain.evaluations.get(),
        jacobians: plain.jacobians.get(),
        parameter_jacobians: plain.parameter_jacobians.get(),
        factorizations: stats.number_of_linear_solver_setups as u64,
    })
}

/// Steps a diffsol solver to `t_end` and reads y and the sensitivities (lane j of the state's
/// `s` is ∂y/∂pⱼ), or `None` if a step fails.
fn step_to_end<'a, E, S>(method: &mut S, t_end: f64) -> Option<End>
where
    E: OdeEquations<T = f64, V = diffsol::NalgebraVec<f64>> + 'a,
    S: OdeSolverMethod<'a, E>,
{
    method.set_stop_time(t_end).ok()?;
    while method.step().ok()? != OdeSolverStopReason::TstopReached {}
    let state = method.state();
    if state.t != t_end {
        return None;
    }
    let mut end = End {
        y: [0.0; N],
        s: [[0.0; P]; N],
    };
    for i in 0..N {
        end.y[i] = state.y[i];
    }
    for j in 0..P {
        let lane = state.s.get_batch(j);
        for i in 0..N {
            end.s[i][j] = lane[i];
        }
    }
    Some(end)
}

// ---------------------------------------------------------------------------------------------
// Reference and error.

/// The error measure: the largest relative error of each yᵢ and, for each column ∂y/∂kⱼ, the
/// largest error relative to the column's largest entry.
fn error(end: &End, reference: &End) -> f64 {
    error_y(end, reference).max(error_s(end, reference))
}

fn error_y(end: &End, reference: &End) -> f64 {
    (0..N).fold(0.0, |m: f64, i| {
        m.max(((end.y[i] - reference.y[i]) / reference.y[i]).abs())
    })
}

fn error_s(end: &End, reference: &End) -> f64 {
    (0..P).fold(0.0, |m: f64, j| {
        let scale = (0..N).fold(0.0, |m: f64, i| m.max(reference.s[i][j].abs()));
        (0..N).fold(m, |m, i| {
            m.max((end.s[i][j] - reference.s[i][j]).abs() / scale)
        })
    })
}

/// The reference y and ∂y/∂k at `t_end`: Rodas5P on the augmented system at rtol 1e-12.
fn reference(t_end: f64) -> End {
    odyn_run(Method::Rodas5P, 1e-12, 1e-12 * ATOL_SCALE, t_end)
        .expect("the reference solve succeeds")
        .end
}

/// y(`t_end`) of the plain model with rates `rates`, Rodas5P at rtol 1e-12, atol 1e-20.
fn plain_solution(rates: &[f64], t_end: f64) -> [f64; N] {
    let mut model = Robertson::classic();
    model.set_parameters(rates).expect("three rates");
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-12, 1e-20)
        .duration(t_end)
        .record_every(u64::MAX)
        .dense_output(false)
        .run()
        .expect("the plain solve succeeds");
    run.last()
        .state
        .as_slice()
        .try_into()
        .expect("three species")
}

/// `[a, b, c]` with 11 significant digits.
fn digits(values: &[f64]) -> String {
    let shown: Vec<String> = values.iter().map(|v| format!("{v:.10e}")).collect();
    format!("[{}]", shown.join(", "))
}

/// Prints how far the reference is from central differences of tight plain solutions (and its
/// y from the plain solution, and at t = 1e5 from the 36-digit reference).
fn check_reference(t_end: f64, reference: &End) {
    let rates = Robertson::classic().parameters();
    let mut differences = End {
        y: plain_solution(&rates, t_end),
        s: [[0.0; P]; N],
    };
    for j in 0..P {
        let h = 1e-4 * rates[j];
        let at = |delta: f64| {
            let mut shifted = rates.clone();
            shifted[j] += delta;
            plain_solution(&shifted, t_end)
        };
        let (plus, minus) = (at(h), at(-h));
        for i in 0..N {
            differences.s[i][j] = (plus[i] - minus[i]) / (2.0 * h);
        }
    }
    println!(
        "  reference (Rodas5P on the augmented system, rtol 1e-12): y = {}",
        digits(&reference.y)
    );
    for i in 0..N {
        println!("    ∂y{i}/∂k = {}", digits(&reference.s[i]));
    }
    println!(
        "  reference against central differences of plain solves (h = 1e-4·k): ∂y/∂k {:.1e}; \
         y against the plain solve {:.1e}",
        error_s(&differences, reference),
        error_y(&differences, reference)
    );
    if t_end == 1e5 {
        let known = End {
            y: scenes::ROBERTSON_1E5,
            s: reference.s,
        };
        println!(
            "  reference y against scenes::ROBERTSON_1E5 (36 digits): {:.1e}",
            error_y(reference, &known)
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Calibration.

/// The chosen tolerance of each (horizon, solver).
static CHOSEN: OnceLock<HashMap<(&'static str, Solver), f64>> = OnceLock::new();

/// The pick among `errors` (one per tolerance, loosest first): among the indices from which on
/// every error is within `SLACK · TARGET`, the one closest to `TARGET` in ratio (the looser on a
/// tie), and how many looser ones are within it by cancellation; `None` if even the tightest
/// misses. With `loosest` (`PEERS_PICK=loosest`), the loosest tolerance within `SLACK · TARGET`
/// instead, cancellation or not (the stiff bench's rule).
fn pick(errors: &[f64], loosest: bool) -> Option<(usize, usize)> {
    let limit = SLACK * TARGET;
    let first = errors.iter().rposition(|&e| e > limit).map_or(0, |k| k + 1);
    if first == errors.len() {
        return None;
    }
    let lucky = errors[..first].iter().filter(|&&e| e <= limit).count();
    if loosest {
        let k = errors
            .iter()
            .position(|&e| e <= limit)
            .expect("one is within");
        return Some((k, lucky));
    }
    let distance = |e: f64| (e / TARGET).ln().abs();
    let k = (first..errors.len())
        .min_by(|&a, &b| distance(errors[a]).total_cmp(&distance(errors[b])))
        .expect("not empty");
    Some((k, lucky))
}

/// Sweeps every solver to `t_end`, prints the reference check and the picks, records the chosen
/// tolerances.
fn calibrate(group: &'static str, t_end: f64, chosen: &mut HashMap<(&'static str, Solver), f64>) {
    println!("\n{group}: Robertson with ∂y/∂(k1, k2, k3) to t = {t_end}");
    let reference = reference(t_end);
    check_reference(t_end, &reference);
    let loosest = std::env::var("PEERS_PICK").is_ok_and(|v| v == "loosest");
    if loosest {
        println!(
            "  pick (PEERS_PICK=loosest): the loosest rtol (atol = rtol·{ATOL_SCALE:.0e} on y, \
             over |k_j| on ∂y/∂k_j) with error at most {:.1e}",
            SLACK * TARGET
        );
    } else {
        println!(
            "  pick: rtol (atol = rtol·{ATOL_SCALE:.0e} on y, over |k_j| on ∂y/∂k_j) with error \
             closest to {TARGET:.0e}, at most {:.1e} from there on",
            SLACK * TARGET
        );
    }
    println!(
        "    {:<18}{:>10}{:>10}{:>10}{:>10}{:>7}{:>5}{:>7}{:>7}{:>7}{:>6}  lucky looser",
        "solver", "rtol", "error", "y", "∂y/∂k", "steps", "rej", "f", "J", "∂f/∂p", "LU"
    );
    for solver in Solver::ALL {
        let sweep: Vec<(f64, f64, Run)> = tolerances()
            .filter_map(|rtol| {
                let run = solve(solver, rtol, t_end)?;
                Some((rtol, error(&run.end, &reference), run))
            })
            .collect();
        if std::env::var_os("PEERS_SWEEP").is_some() {
            println!("    sweep {}: rtol error steps", solver.name());
            for (rtol, e, run) in &sweep {
                println!("      {rtol:.3e} {e:.3e} {}", run.steps);
            }
        }
        let errors: Vec<f64> = sweep.iter().map(|(_, e, _)| *e).collect();
        let Some((k, lucky)) = pick(&errors, loosest) else {
            let best = errors.iter().copied().fold(f64::INFINITY, f64::min);
            println!(
                "    {:<18}  not reached (best error {best:.1e})",
                solver.name()
            );
            continue;
        };
        let (rtol, e, run) = &sweep[k];
        println!(
            "    {:<18}{rtol:>10.3e}{e:>10.2e}{:>10.2e}{:>10.2e}{:>7}{:>5}{:>7}{:>7}{:>7}{:>6}  {lucky}",
            solver.name(),
            error_y(&run.end, &reference),
            error_s(&run.end, &reference),
            run.steps,
            run.rejected,
            run.f,
            run.jacobians,
            run.parameter_jacobians,
            run.factorizations,
        );
        chosen.insert((group, solver), *rtol);
    }
}

/// Solves with the calibrated tolerance of `solver` for the horizon `h`.
fn timed(solver: Solver, h: usize) -> End {
    let (group, t_end) = HORIZONS[h];
    let rtol = CHOSEN.get().expect("calibrated")[&(group, solver)];
    solve(black_box(solver), black_box(rtol), black_box(t_end))
        .expect("the calibrated run succeeded")
        .end
}

fn main() {
    let mut chosen = HashMap::new();
    for (group, t_end) in HORIZONS {
        calibrate(group, t_end, &mut chosen);
    }
    println!();
    let mut divan = divan::Divan::from_args();
    for (group, _) in HORIZONS {
        for solver in Solver::ALL {
            if !chosen.contains_key(&(group, solver)) {
                divan = divan.skip_exact(format!("{}::{group}::{}", module_path!(), solver.name()));
            }
        }
    }
    CHOSEN.set(chosen).expect("calibrated once");
    divan.main();
}

// ---------------------------------------------------------------------------------------------
// Benches: one group per horizon.

macro_rules! group {
    ($group:ident, $h:literal) => {
        mod $group {
            use super::*;

            #[divan::bench]
            fn odyn_rodas5p() -> End {
                timed(Solver::OdynRodas5P, $h)
            }

            #[divan::bench]
            fn odyn_bdf() -> End {
                timed(Solver::OdynBdf, $h)
            }

            #[divan::bench]
            fn diffsol_bdf() -> End {
                timed(Solver::DiffsolBdf, $h)
            }

            #[divan::bench]
            fn diffsol_esdirk34() -> End {
                timed(Solver::DiffsolEsdirk34, $h)
            }
        }
    };
}

group!(robertson_t40, 0);
group!(robertson_t1e5, 1);
