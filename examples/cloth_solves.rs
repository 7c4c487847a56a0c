//! How accurate each implicit Euler solve of the stiff cloth is, from checkpoints of a falling
//! cloth (issue "Stiff cloth in real time", criteria (a)–(c)).
//!
//! A reference run of the `cloth` example's sheet (k = 10⁴ N/m, undamped springs, dt = 1/60 s,
//! the one-step Baraff–Witkin form) is stopped at t = 0.5, 1, 2 and 5 s. From each checkpoint one
//! step is taken three ways: Newton converged to 10⁻¹⁰ (the implicit Euler step itself), the
//! Baraff–Witkin step, and the quasi-Newton step (`ParticleSolve::QuasiNewton`). For each it
//! prints
//!
//! - (a) the largest particle distance from the converged step (m);
//! - (b) the quasi-Newton step's acceleration residual ‖v − vₙ − h·a(x, v)‖∞ / h (m/s²),
//!   against 10⁻³·g;
//! - (c) the quasi-Newton step's convergence ratio (g(ṽ) − g(v*)) / (g(v⁰) − g(v*)) of the
//!   implicit Euler objective g(v) = ½‖v − vₙ‖²_M + E(xₙ + h·v) + ½h·c_drag·‖v‖², and the
//!   iterations that take it to 10⁻³;
//! - the plain `ImplicitEuler` step (`NewtonOptions::default()`: full Newton, halving a step it
//!   cannot take whole), its distance from the converged step and its time;
//!
//! and the time of each step.
//!
//! With `--whole-run SECONDS` it runs each solve over the fall instead and compares the energy
//! traces: the largest step-to-step energy gain and the largest difference from the full-Newton
//! run's trace (the full-Newton run takes about a minute at 32² over 5 s, and half an hour at
//! 64²).
//!
//! `cargo run --release --example cloth_solves [-- --sizes 32,64 --qn-iterations 8]` (about a minute at 32²; the
//! converged step from the buckling cloth at 0.5 s takes most of it, and minutes at 64²)

use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use odyn::integrators::ImplicitEuler;
use odyn::particles::ParticleState;
use odyn::prelude::*;
use odyn::{NewtonOptions, ParticleSolve, QuasiNewtonOptions, Stepper};
use scenes::{Cloth, Sheet};

/// Accuracy of the cloth's implicit Euler solves from checkpoints.
#[derive(Parser)]
#[command(about)]
struct Cli {
    /// Particles per side, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "32")]
    sizes: Vec<usize>,
    /// Checkpoint times (s), comma-separated and increasing.
    #[arg(long, value_delimiter = ',', default_value = "0.5,1,2,5")]
    checkpoints: Vec<f64>,
    /// The quasi-Newton solve's iterations per step (`QuasiNewtonOptions::max_iterations`).
    #[arg(long, default_value_t = QuasiNewtonOptions::default().max_iterations)]
    qn_iterations: u32,
    /// Instead of the checkpoints, run each solve over the whole fall for this many seconds and
    /// compare the energy traces (the whole-run criteria).
    #[arg(long)]
    whole_run: Option<f64>,
}

const H: f64 = 1.0 / 60.0;

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> odyn::Result<()> {
    if let Some(seconds) = cli.whole_run {
        return whole_runs(&cli.sizes, seconds, cli.qn_iterations);
    }
    println!(
        "size  t(s)   BW→IE (m)  QN→IE (m)  QN accel res (m/s²)  QN ratio  IE ms  BW ms  QN ms  QN iters  default→IE (m)  default ms"
    );
    for &n in &cli.sizes {
        let cloth = Sheet::falling(n).build().0;
        let budget = QuasiNewtonOptions {
            max_iterations: cli.qn_iterations,
            ..QuasiNewtonOptions::default()
        };
        for point in checkpoints(&cloth, &cli.checkpoints, budget)? {
            let (t, state) = (point.t, &point.state);
            // Where Newton cannot take the step whole (a buckling cloth), the quasi-Newton solve
            // run to convergence gives the same implicit Euler step.
            let ((converged, ie_ms), by) = match step(&cloth, state, t, newton_converged()) {
                Ok(converged) => (converged, "N"),
                Err(_) => (
                    step(&cloth, state, t, quasi_newton(converged_options()))?,
                    "Q",
                ),
            };
            let (bw, bw_ms) = step(&cloth, state, t, baraff_witkin())?;
            // The plain `ImplicitEuler` step: NewtonOptions::default(), halvings allowed.
            let (plain, plain_ms) = step(&cloth, state, t, NewtonOptions::default())?;
            let qn = &point.next;
            let objective = |y: &ParticleState<3>| objective(&cloth, state, y);
            let g_star = objective(&converged);
            let ratio = (objective(qn) - g_star) / (objective(&inertial(state)) - g_star);
            println!(
                "{n:>4}  {t:>4}  {:>9.2e}  {:>9.2e}  {:>19.2e}  {ratio:>8.1e}  \
                 {ie_ms:>7.1}{by}  {bw_ms:>5.1}  {:>5.2}  {:>8}  {:>14.2e}  {plain_ms:>10.1}",
                distance(&bw, &converged),
                distance(qn, &converged),
                acceleration_residual(&cloth, state, qn, t),
                point.ms,
                point.iterations,
                distance(&plain, &converged),
            );
        }
    }
    Ok(())
}

/// Each solve over the whole fall: its step time, its factorizations, the largest energy it
/// gains from one step to the next (J; the cloth's air drag only takes energy away, so implicit
/// Euler never gains any), and its energy trace against the plain `ImplicitEuler` run's (full
/// Newton), as the largest difference at any step over that run's largest |E|.
fn whole_runs(sizes: &[usize], seconds: f64, qn_iterations: u32) -> odyn::Result<()> {
    // At least two steps (a gain needs two), at most an hour of simulated time.
    if !(2.0 * H..=3600.0).contains(&seconds) {
        return Err(odyn::Error::InvalidInput {
            field: "--whole-run".into(),
            reason: format!("must be between {:.3} and 3600 s, got {seconds}", 2.0 * H),
        });
    }
    println!(
        "size  solve           mean ms  max ms  factorizations  largest gain (J)  trace vs Newton"
    );
    let budget = QuasiNewtonOptions {
        max_iterations: qn_iterations,
        ..QuasiNewtonOptions::default()
    };
    for &n in sizes {
        let cloth = Sheet::falling(n).build().0;
        let solves = [
            ("Newton (default)", NewtonOptions::default()),
            ("Baraff–Witkin", baraff_witkin()),
            ("quasi-Newton", quasi_newton(budget)),
        ];
        let mut newton_trace = Vec::new();
        for (name, newton) in solves {
            let mut stepper = Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(
                &cloth,
                cloth.state(),
                0.0,
                H,
                &newton,
            )?;
            let steps = (seconds / H).round() as usize;
            let (mut trace, mut times) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
            for _ in 0..steps {
                let begin = Instant::now();
                stepper.step()?;
                times.push(begin.elapsed().as_secs_f64() * 1e3);
                let energy = cloth.energy(stepper.state());
                trace.push(energy.expect("the cloth has a potential"));
            }
            if newton_trace.is_empty() {
                newton_trace.clone_from(&trace);
            }
            let scale = newton_trace.iter().fold(0.0, |m: f64, e| m.max(e.abs()));
            let apart = (trace.iter().zip(&newton_trace))
                .map(|(e, r)| (e - r).abs() / scale)
                .fold(0.0, f64::max);
            let gain = trace
                .windows(2)
                .map(|w| w[1] - w[0])
                .fold(f64::MIN, f64::max);
            let mean = times.iter().sum::<f64>() / times.len() as f64;
            let max = times.iter().copied().fold(0.0, f64::max);
            println!(
                "{n:>4}  {name:<16} {mean:>7.2}  {max:>6.1}  {:>14}  {gain:>16.2e}  {apart:>15.1e}",
                stepper.stats().factorizations
            );
        }
    }
    Ok(())
}

/// A checkpoint of the reference run: its state, and the quasi-Newton step from it with its
/// time and iterations.
struct Checkpoint {
    t: f64,
    state: ParticleState<3>,
    next: ParticleState<3>,
    ms: f64,
    iterations: u32,
}

/// The reference run (the one-step Baraff–Witkin form on the definite matrix) at the checkpoint
/// times, each with the quasi-Newton step from it (its matrix factorized before the clock
/// starts, as it is once per run).
fn checkpoints(
    cloth: &Cloth,
    times: &[f64],
    budget: QuasiNewtonOptions,
) -> odyn::Result<Vec<Checkpoint>> {
    let mut reference = Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(
        cloth,
        cloth.state(),
        0.0,
        H,
        &baraff_witkin(),
    )?;
    let newton = quasi_newton(budget);
    let mut fast =
        Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(cloth, cloth.state(), 0.0, H, &newton)?;
    fast.step()?;
    let mut points = Vec::new();
    for &t in times {
        let steps = (t / H).round() as u64;
        while reference.steps() < steps {
            reference.step()?;
        }
        let state = reference.state().clone();
        fast.state_mut().clone_from(&state);
        let begin = Instant::now();
        fast.step()?;
        let ms = begin.elapsed().as_secs_f64() * 1e3;
        let iterations = fast
            .integrator()
            .quasi_newton()
            .map_or(0, |s| s.iterations());
        let next = fast.state().clone();
        points.push(Checkpoint {
            t,
            state,
            next,
            ms,
            iterations,
        });
    }
    Ok(points)
}

/// The one-step (Baraff–Witkin) form on the definite matrix: one Cholesky a step, and no
/// energy gained from compressed springs.
fn baraff_witkin() -> NewtonOptions {
    NewtonOptions {
        definite: true,
        ..NewtonOptions::linearized()
    }
}

/// Newton to 10⁻¹⁰ on the direct solver, with no halving: one step of h.
fn newton_converged() -> NewtonOptions {
    NewtonOptions {
        tol: 1e-10,
        max_iterations: 200,
        max_halvings: 0,
        particle_solve: ParticleSolve::Newton,
        ..NewtonOptions::default()
    }
}

/// The quasi-Newton solve run until its velocity residual is 10⁻¹² (m/s).
fn converged_options() -> QuasiNewtonOptions {
    QuasiNewtonOptions {
        max_iterations: 100_000,
        tolerance: 1e-12,
        history: 20,
    }
}

fn quasi_newton(options: QuasiNewtonOptions) -> NewtonOptions {
    NewtonOptions {
        particle_solve: ParticleSolve::QuasiNewton(options),
        ..NewtonOptions::default()
    }
}

/// One step from `state` at `t` with `newton`, and its time in ms (set-up excluded).
fn step(
    cloth: &Cloth,
    state: &ParticleState<3>,
    t: f64,
    newton: NewtonOptions,
) -> odyn::Result<(ParticleState<3>, f64)> {
    let mut stepper =
        Stepper::<Cloth, ImplicitEuler<Cloth>>::with_newton(cloth, state.clone(), t, H, &newton)?;
    let start = Instant::now();
    stepper.step()?;
    Ok((stepper.state().clone(), start.elapsed().as_secs_f64() * 1e3))
}

/// The largest distance between corresponding particles (m).
fn distance(a: &ParticleState<3>, b: &ParticleState<3>) -> f64 {
    let pairs = a.positions().iter().zip(b.positions());
    pairs.map(|(p, q)| (p - q).norm()).fold(0.0, f64::max)
}

/// (xₙ + h·vₙ, vₙ): the quasi-Newton start.
fn inertial(state: &ParticleState<3>) -> ParticleState<3> {
    let mut y = state.clone();
    let (x, v) = y.split_mut();
    for (x, v) in x.iter_mut().zip(v.iter()) {
        *x += H * v;
    }
    y
}

/// g(v) = ½Σmᵢ|vᵢ − vₙ,ᵢ|² + E(x) + ½h·c_drag·Σ|vᵢ|² at y = (x, v): the drag is linear, so its
/// term makes ∇g the residual of the step.
fn objective(cloth: &Cloth, start: &ParticleState<3>, y: &ParticleState<3>) -> f64 {
    let mut at = cloth.clone();
    at.x = y.positions().to_vec();
    let inertia: f64 = (y.velocities().iter().zip(start.velocities()))
        .zip(&cloth.mass)
        .map(|((v, v0), m)| 0.5 * m * (v - v0).norm_squared())
        .sum();
    let drag: f64 = y.velocities().iter().map(|v| v.norm_squared()).sum();
    inertia + at.potential() + 0.5 * H * cloth.drag * drag
}

/// max |v − vₙ − h·a(x, v)| / h over the free particles (m/s²).
fn acceleration_residual(
    cloth: &Cloth,
    start: &ParticleState<3>,
    y: &ParticleState<3>,
    t: f64,
) -> f64 {
    let mut f = y.clone();
    cloth.derivative(t + H, y, &mut f);
    let accelerations = f.velocities();
    let terms = y
        .velocities()
        .iter()
        .zip(start.velocities())
        .zip(accelerations);
    terms
        .map(|((v, v0), a)| (v - v0 - H * a).amax() / H)
        .fold(0.0, f64::max)
}
