//! The spring lab: explicit Euler gains energy, the symplectic methods hold it, RK4 barely drifts.
//!
//! `cargo run --release --example spring` writes, under `out/spring/`:
//! - `lab.csv`, `lab.png`: a = −x from x₀ = 1, dt = 0.05, 400 steps, four methods;
//! - `damped.csv`, `damped.png`: k = 50, b = 0.5, m = 1, dt = 0.016, 625 steps, five methods;
//! - `growth.csv`: explicit Euler's energy ratio against the closed form (1 + dt²)ⁿ.
//!
//! With `--integrator`, `--dt` or `--steps` it runs one configuration of the damped spring instead.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use odyn::output::{number, write_csv, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;
use odyn::reference::DampedOscillator;

// The model, written once for the examples, tests and benches (`scenes/src/oscillators.rs`): the
// damped spring m·ẍ = −k·x − b·ẋ with k, b, m as fields, symplectic Euler at dt = 0.016 by default,
// and its energy.
use scenes::{Spring, SpringState};

#[derive(Parser)]
#[command(about = "The spring lab: energy behaviour of six integrators on a spring")]
struct Cli {
    /// Run one configuration of the damped spring with this method
    /// (explicit_euler, symplectic_euler, position_verlet, velocity_verlet, leapfrog, rk4).
    #[arg(long)]
    integrator: Option<Method>,
    /// Time step for the single run, in seconds [default: 0.016].
    #[arg(long)]
    dt: Option<f64>,
    /// Number of steps for the single run [default: 625].
    #[arg(long)]
    steps: Option<u64>,
    /// Output directory.
    #[arg(long, default_value = "out")]
    out: PathBuf,
}

const LAB_METHODS: [Method; 4] = [
    Method::ExplicitEuler,
    Method::SymplecticEuler,
    Method::VelocityVerlet,
    Method::Rk4,
];
const DAMPED_METHODS: [Method; 5] = [
    Method::ExplicitEuler,
    Method::SymplecticEuler,
    Method::VelocityVerlet,
    Method::Leapfrog,
    Method::Rk4,
];

fn main() -> ExitCode {
    let cli = Cli::parse();
    let dir = cli.out.join("spring");
    let result = if cli.integrator.is_some() || cli.dt.is_some() || cli.steps.is_some() {
        single(&cli, &dir)
    } else {
        lab(&dir)
            .and_then(|()| damped(&dir))
            .and_then(|()| growth(&dir))
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// a = −x, dt = 0.05, 400 steps: the published numbers.
fn lab(dir: &std::path::Path) -> odyn::Result<()> {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 1.0,
        b: 0.0,
        m: 1.0,
    };
    let runs = LAB_METHODS
        .iter()
        .map(|&m| spring.simulate().integrator(m).dt(0.05).steps(400).run())
        .collect::<odyn::Result<Vec<_>>>()?;
    write_csv(dir.join("lab.csv"), &runs.iter().collect::<Vec<_>>())?;
    plot(
        dir.join("lab.png"),
        "Spring a = −x, dt = 0.05: energy E(t)/E(0)",
        &runs,
        None,
    )?;
    println!("spring lab: a = -x, x0 = 1, v0 = 0, dt = 0.05, 400 steps (t = 20)");
    println!("  {:<18} {:>12} {:>14}", "method", "E(20)/E(0)", "expected");
    for run in &runs {
        let expected = match run.method {
            // Closed form: explicit Euler multiplies the energy by 1 + dt² per step.
            Method::ExplicitEuler => format!("{:.6}", 1.0025f64.powi(400)),
            Method::SymplecticEuler => format!("[{:.4}, {:.4}]", 2.0 / 2.05, 2.0 / 1.95),
            Method::VelocityVerlet => format!("[{:.6}, 1]", 1.0 - 0.05f64.powi(2) / 4.0),
            _ => "≈ 1".to_owned(),
        };
        println!(
            "  {:<18} {:>12.6} {:>14}",
            run.method.name(),
            ratio(run),
            expected
        );
    }
    Ok(())
}

/// k = 50, b = 0.5, m = 1, dt = 0.016, 625 steps (t = 10): the tutorial's numbers.
fn damped(dir: &std::path::Path) -> odyn::Result<()> {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let runs = DAMPED_METHODS
        .iter()
        .map(|&m| spring.simulate().integrator(m).steps(625).run())
        .collect::<odyn::Result<Vec<_>>>()?;
    write_csv(dir.join("damped.csv"), &runs.iter().collect::<Vec<_>>())?;
    let exact = DampedOscillator {
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let exact_energy = |t| {
        let (x, v) = exact.state_at(1.0, 0.0, t);
        exact.energy(x, v) / exact.energy(1.0, 0.0)
    };
    let curve = runs[0].times().map(|t| (t, exact_energy(t))).collect();
    plot(
        dir.join("damped.png"),
        "Damped spring k = 50, b = 0.5, dt = 0.016: E(t)/E(0)",
        &runs,
        Some(Series::line("exact", curve)),
    )?;
    let t = runs[0].last().t;
    let (x, v) = exact.state_at(1.0, 0.0, t);
    println!("\ndamped spring: k = 50, b = 0.5, m = 1, dt = 0.016, 625 steps (t = {t})");
    println!(
        "  exact: x = {x:.6}, E/E0 = {:.6}",
        exact.energy(x, v) / exact.energy(1.0, 0.0)
    );
    println!(
        "  {:<18} {:>12} {:>12} {:>12}",
        "method", "x(10)", "|x - exact|", "E(10)/E(0)"
    );
    for run in &runs {
        let s = run.last().state;
        println!(
            "  {:<18} {:>12.6} {:>12.2e} {:>12.6}",
            run.method.name(),
            s.x,
            (s.x - x).abs(),
            ratio(run)
        );
    }
    Ok(())
}

/// Explicit Euler's energy growth against (1 + dt²)ⁿ over t = 20.
fn growth(dir: &std::path::Path) -> odyn::Result<()> {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 1.0,
        b: 0.0,
        m: 1.0,
    };
    let mut rows = Vec::new();
    println!("\nexplicit Euler energy growth over t = 20 (a = -x)");
    println!(
        "  {:>6} {:>6} {:>16} {:>16}",
        "dt", "steps", "measured", "(1 + dt²)ⁿ"
    );
    for dt in [0.01f64, 0.02, 0.05, 0.1, 0.2] {
        let steps = (20.0 / dt).round() as u64;
        let run = spring
            .simulate()
            .integrator(Method::ExplicitEuler)
            .dt(dt)
            .steps(steps)
            .run()?;
        let closed = (1.0 + dt * dt).powi(steps as i32);
        println!(
            "  {dt:>6} {steps:>6} {:>16.10} {closed:>16.10}",
            ratio(&run)
        );
        rows.push(vec![
            number(dt),
            steps.to_string(),
            number(ratio(&run)),
            number(closed),
        ]);
    }
    write_table(
        dir.join("growth.csv"),
        &["dt", "steps", "measured_ratio", "closed_form_ratio"],
        &rows,
    )?;
    println!(
        "\nwrote {}/{{lab,damped}}.{{csv,png}} and growth.csv",
        dir.display()
    );
    Ok(())
}

/// One configuration of the damped spring, from the command line.
fn single(cli: &Cli, dir: &std::path::Path) -> odyn::Result<()> {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let mut sim = spring.simulate().steps(cli.steps.unwrap_or(625));
    if let Some(method) = cli.integrator {
        sim = sim.integrator(method);
        if method.is_adaptive() && cli.dt.is_none() {
            // An adaptive method picks its own steps: run the same 10 s at its default tolerances.
            sim = sim.duration(cli.steps.unwrap_or(625) as f64 * 0.016);
        }
    }
    if let Some(dt) = cli.dt {
        sim = sim.dt(dt);
    }
    let run = sim.run()?;
    let step = match run.stepping.dt() {
        Some(dt) => format!("dt{dt}"),
        None => "adaptive".to_owned(),
    };
    let name = format!("{}_{step}", run.method.name());
    run.write_csv(dir.join(format!("{name}.csv")))?;
    plot(
        dir.join(format!("{name}.png")),
        &format!("Damped spring, {}, {step}", run.method.label()),
        std::slice::from_ref(&run),
        None,
    )?;
    let last = run.last();
    println!(
        "{}: {} steps, t = {}, x = {:.6}, v = {:.6}, E/E0 = {:.6}; wrote {}/{name}.{{csv,png}}",
        run.method.name(),
        run.steps(),
        last.t,
        last.state.x,
        last.state.v,
        ratio(&run),
        dir.display()
    );
    Ok(())
}

fn ratio(run: &Trajectory<SpringState>) -> f64 {
    run.energy_ratio().expect("Spring defines an energy")
}

fn plot(
    path: PathBuf,
    title: &str,
    runs: &[Trajectory<SpringState>],
    exact: Option<Series>,
) -> odyn::Result<()> {
    let mut series: Vec<Series> = runs
        .iter()
        .map(|run| Series::line(run.method.label(), energy_ratio(run)))
        .collect();
    // The exact solution, drawn last so it shows over the methods that follow it; the damped
    // spring's energy spans decades, so that chart is logarithmic.
    let log_y = exact.is_some();
    series.extend(exact);
    Chart {
        title: title.to_owned(),
        x_label: "t".to_owned(),
        y_label: "E(t) / E(0)".to_owned(),
        log_y,
        series,
        ..Chart::default()
    }
    .write(path, (960, 600))
}

/// E(t)/E(0) along a run.
fn energy_ratio(run: &Trajectory<SpringState>) -> Vec<(f64, f64)> {
    let e0 = run.first().energy.unwrap_or(f64::NAN);
    run.energies().map(|(t, e)| (t, e / e0)).collect()
}
