//! Robertson's chemical kinetics (Robertson 1966), the classic stiff problem: rate constants
//! 0.04, 10⁴ and 3·10⁷ span nine decades. Implicit Euler with the generated Jacobian, to t = 40
//! and on to t = 4·10⁴; Rosenbrock23 and Rodas5P at three tolerances to t = 40.
//!
//! `cargo run --release --example robertson` writes, under `out/robertson/`:
//! `trajectory.csv` (`method,step,t,a,b,c`) and `trajectory.png` to t = 4·10⁴ at dt = 0.1;
//! `convergence.csv` (`dt,steps,error`) and `convergence.png`: the error at t = 40 against SciPy
//! Radau at rtol 1e-12 (`scripts/reference.py`), which matches Hairer & Wanner's published values.

use std::process::ExitCode;

use odyn::output::{number, write_csv, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;

// The model, written once for the examples, tests and benches (`scenes/src/stiff.rs`): A → B
// (0.04), B + C → A + C (10⁴), 2B → B + C (3·10⁷), implicit Euler by default.
use scenes::{Robertson, RobertsonState};

/// y(40): SciPy Radau (rtol 1e-12, atol 1e-14), BDF agrees to 2.4e-9; Hairer & Wanner, *Solving
/// ODEs II*, §IV.10 give 0.7158270687, 9.185534764e-6, 0.2841637457.
const REFERENCE_40: [f64; 3] = [
    7.158270687199023e-01,
    9.185534764554085e-06,
    2.841637457453337e-01,
];

/// Robertson's chemical kinetics (Robertson 1966), the classic stiff problem: rate constants 0.04,
/// 10⁴ and 3·10⁷ span nine decades.
///
/// Writes its CSV files and charts under `out/robertson/` (the example's source says what each
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
    let dir = std::path::Path::new("out/robertson");
    let model = Robertson::classic();
    println!("Robertson kinetics: implicit Euler error at t = 40 against SciPy Radau");
    println!(
        "  {:>7} {:>7} {:>12} {:>12}",
        "dt", "steps", "max error", "a+b+c-1"
    );
    let mut rows = Vec::new();
    let mut points = Vec::new();
    for dt in [0.04, 0.02, 0.01, 0.005, 0.0025] {
        let run = model
            .simulate()
            .dt(dt)
            .duration(40.0)
            .record_every(u64::MAX)
            .run()?;
        let s = run.last().state;
        let error = [s.a, s.b, s.c]
            .iter()
            .zip(REFERENCE_40)
            .map(|(y, r)| (y - r).abs())
            .fold(0.0, f64::max);
        println!(
            "  {dt:>7} {:>7} {error:>12.3e} {:>12.1e}",
            run.steps(),
            s.a + s.b + s.c - 1.0
        );
        rows.push(vec![number(dt), run.steps().to_string(), number(error)]);
        points.push((dt, error));
    }
    let (first, last) = (points[0], points[points.len() - 1]);
    println!(
        "  observed order: {:.3}",
        (first.1 / last.1).ln() / (first.0 / last.0).ln()
    );
    write_table(
        dir.join("convergence.csv"),
        &["dt", "steps", "error"],
        &rows,
    )?;

    // The Rosenbrock methods choose their own steps for a requested accuracy.
    println!("\nRosenbrock methods to t = 40, rtol = atol·10⁴:");
    println!(
        "  {:<13} {:>6} {:>7} {:>12} {:>12}",
        "method", "rtol", "steps", "max error", "a+b+c-1"
    );
    for method in [Method::Rosenbrock23, Method::Rodas5P] {
        for rtol in [1e-4, 1e-6, 1e-8] {
            let run = model
                .simulate()
                .integrator(method)
                .tolerances(rtol, rtol * 1e-4)
                .duration(40.0)
                .record_every(u64::MAX)
                .run()?;
            let s = run.last().state;
            let error = [s.a, s.b, s.c]
                .iter()
                .zip(REFERENCE_40)
                .map(|(y, r)| (y - r).abs())
                .fold(0.0, f64::max);
            println!(
                "  {:<13} {rtol:>6.0e} {:>7} {error:>12.3e} {:>12.1e}",
                method.label(),
                run.steps(),
                s.a + s.b + s.c - 1.0
            );
        }
    }
    Chart {
        title: "Robertson at t = 40: implicit Euler error against SciPy Radau".to_owned(),
        x_label: "dt".to_owned(),
        y_label: "max |y − y_ref|".to_owned(),
        log_x: true,
        log_y: true,
        series: vec![Series::markers("implicit Euler", points)],
        ..Chart::default()
    }
    .write(dir.join("convergence.png"), (960, 600))?;

    let run = model
        .simulate()
        .dt(0.1)
        .duration(4e4)
        .record_every(10)
        .run()?;
    write_csv(dir.join("trajectory.csv"), &[&run])?;
    let species = |label: &str, f: fn(&RobertsonState) -> f64| {
        Series::line(
            label,
            run.samples
                .iter()
                .skip(1)
                .map(|s| (s.t, f(&s.state)))
                .collect(),
        )
    };
    Chart {
        title: "Robertson kinetics, implicit Euler, dt = 0.1".to_owned(),
        x_label: "t".to_owned(),
        y_label: "concentration".to_owned(),
        log_x: true,
        series: vec![
            species("a", |s| s.a),
            species("10⁴·b", |s| 1e4 * s.b),
            species("c", |s| s.c),
        ],
        ..Chart::default()
    }
    .write(dir.join("trajectory.png"), (960, 500))?;
    let end = run.last().state;
    println!(
        "  t = 4e4 at dt = 0.1: a = {:.6}, b = {:.4e}, c = {:.6} (Radau: 0.038983, 1.6218e-7, 0.961016)",
        end.a, end.b, end.c
    );
    println!(
        "wrote {}/{{trajectory,convergence}}.{{csv,png}}",
        dir.display()
    );
    Ok(())
}
