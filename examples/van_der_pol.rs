//! Van der Pol at μ = 1000, y1′ = y2, y2′ = μ(1 − y1²)y2 − y1, from (2, 0) to t = 3000: a stiff
//! relaxation oscillation, integrated with implicit Euler and the generated Jacobian, and with
//! Rosenbrock23 and Rodas5P at two tolerances to each reference time (printed).
//!
//! `cargo run --release --example van_der_pol` writes, under `out/van_der_pol/`:
//! `trajectory.csv` (`method,step,t,y1,y2`) and `trajectory.png` at dt = 5e-4;
//! `convergence.csv` (`t,dt,steps,error`) and `convergence.png`: the error at t = 100 and t = 808
//! against an independent reference (SciPy Radau at rtol 1e-12, confirmed by BDF;
//! `scripts/reference.py`).

use std::process::ExitCode;

use odyn::output::{number, write_csv, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;

// The model, written once for the examples, tests and benches (`scenes/src/stiff.rs`): y₁′ = y₂,
// y₂′ = μ(1 − y₁²)y₂ − y₁, implicit Euler by default.
use scenes::VanDerPol;

/// SciPy Radau, rtol 1e-12, atol 1e-14 (`scripts/reference.py`); BDF agrees to 3.5e-9 at t = 100,
/// 8.2e-9 at t = 808 (just after the first relaxation jump, at t ≈ 807.1) and 5.0e-8 at t = 3000.
const REFERENCE: [(f64, [f64; 2]); 3] = [
    (100.0, [1.931361320527369, -7.074176282303548e-04]),
    (808.0, [-1.999_467_145_947_18, 6.669627202749569e-04]),
    (3000.0, [-1.510606936743998, 1.178380000731138e-03]),
];

/// Van der Pol at μ = 1000, y1′ = y2, y2′ = μ(1 − y1²)y2 − y1, from (2, 0) to t = 3000.
///
/// Writes its CSV files and charts under `out/van_der_pol/` (the example's source says what each
/// holds); takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> ExitCode {
    <Cli as clap::Parser>::parse();
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> odyn::Result<()> {
    let dir = std::path::Path::new("out/van_der_pol");
    let model = VanDerPol {
        y1: 2.0,
        y2: 0.0,
        mu: 1000.0,
    };
    println!("van der Pol, mu = 1000, from (2, 0): implicit Euler error against SciPy Radau");
    let mut rows = Vec::new();
    let mut series = Vec::new();
    // On the slow branch (t = 100) any dt is in the asymptotic regime. Through the relaxation jump
    // (t = 808) the local stiffness μ(y1² − 1) ≈ 3000 must be resolved: at dt = 0.05 implicit
    // Euler lands at y1 = −1.68 instead of −2, and the error only halves with dt once
    // dt ≲ 1/3000. Its phase error then makes the t = 3000 state O(1) off at every affordable dt.
    for (t_end, reference, dts) in [
        (
            REFERENCE[0].0,
            REFERENCE[0].1,
            vec![0.4, 0.2, 0.1, 0.05, 0.025],
        ),
        (REFERENCE[1].0, REFERENCE[1].1, vec![4e-4, 2e-4, 1e-4, 5e-5]),
    ] {
        println!("  to t = {t_end}:");
        println!(
            "  {:>8} {:>9} {:>12} {:>12} {:>9}",
            "dt", "steps", "max error", "Newton/step", "seconds"
        );
        let mut points = Vec::new();
        for dt in dts {
            let clock = std::time::Instant::now();
            let run = model
                .simulate()
                .dt(dt)
                .duration(t_end)
                .record_every(u64::MAX)
                .run()?;
            let seconds = clock.elapsed().as_secs_f64();
            let s = run.last().state;
            let error = (s.y1 - reference[0]).abs().max((s.y2 - reference[1]).abs());
            let newton = run.stats.jacobian_evaluations as f64 / run.steps() as f64;
            println!(
                "  {dt:>8} {:>9} {error:>12.3e} {newton:>12.2} {seconds:>9.3}",
                run.steps()
            );
            rows.push(vec![
                number(t_end),
                number(dt),
                run.steps().to_string(),
                number(error),
            ]);
            points.push((dt, error));
        }
        let (first, last) = (points[0], points[points.len() - 1]);
        println!(
            "  observed order: {:.3}",
            (first.1 / last.1).ln() / (first.0 / last.0).ln()
        );
        series.push(Series::markers(format!("t = {t_end}"), points));
    }
    write_table(
        dir.join("convergence.csv"),
        &["t", "dt", "steps", "error"],
        &rows,
    )?;
    Chart {
        title: "Van der Pol μ = 1000: implicit Euler error against SciPy Radau".to_owned(),
        x_label: "dt".to_owned(),
        y_label: "max |y − y_ref|".to_owned(),
        log_x: true,
        log_y: true,
        series,
        ..Chart::default()
    }
    .write(dir.join("convergence.png"), (960, 600))?;

    // The Rosenbrock methods to each reference time, choosing their own steps.
    println!("\nRosenbrock methods, rtol = atol·10³:");
    println!(
        "  {:<13} {:>6} {:>7} {:>7} {:>12}",
        "method", "rtol", "t", "steps", "max error"
    );
    for method in [Method::Rosenbrock23, Method::Rodas5P] {
        for rtol in [1e-5, 1e-8] {
            for (t_end, reference) in REFERENCE {
                let run = model
                    .simulate()
                    .integrator(method)
                    .tolerances(rtol, rtol * 1e-3)
                    .duration(t_end)
                    .record_every(u64::MAX)
                    .run()?;
                let y = run.last().state;
                let error = (y.y1 - reference[0]).abs().max((y.y2 - reference[1]).abs());
                println!(
                    "  {:<13} {rtol:>6.0e} {t_end:>7} {:>7} {error:>12.3e}",
                    method.label(),
                    run.steps()
                );
            }
        }
    }

    let run = model
        .simulate()
        .dt(5e-4)
        .duration(3000.0)
        .record_every(2000)
        .run()?;
    let (y, reference) = (run.last().state, REFERENCE[2].1);
    println!(
        "  t = 3000 at dt = 5e-4: y1 = {:.4} (reference {:.4}): the accumulated phase error",
        y.y1, reference[0]
    );
    write_csv(dir.join("trajectory.csv"), &[&run])?;
    let y1: Vec<_> = run.samples.iter().map(|s| (s.t, s.state.y1)).collect();
    Chart {
        title: "Van der Pol μ = 1000, implicit Euler, dt = 5e-4".to_owned(),
        x_label: "t".to_owned(),
        y_label: "y1".to_owned(),
        series: vec![Series::line("y1(t)", y1)],
        ..Chart::default()
    }
    .write(dir.join("trajectory.png"), (960, 500))?;
    println!(
        "wrote {}/{{trajectory,convergence}}.{{csv,png}}",
        dir.display()
    );
    Ok(())
}
