//! Stability explorer: the largest stable dt of every method on undamped springs, predicted from
//! the eigenvalues of the generated Jacobian and measured by bisection on 20 000-step runs.
//!
//! `cargo run --release --example stability` writes `out/stability/limits.csv`
//! (`method,omega,predicted_dt,measured_dt`) and `out/stability/limits.png`.

use std::process::ExitCode;

use odyn::output::{number, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;
// The undamped spring m·ẍ = −k·x (`scenes/src/oscillators.rs`).
use odyn::stability::{StabilityProbe, measured_limit, predicted_limit};
use scenes::UndampedSpring as Spring;

/// Stability explorer: the largest stable dt of every method on undamped springs, predicted from
/// the generated Jacobian's eigenvalues and measured by bisection.
///
/// Writes its CSV files and charts under `out/stability/` (the example's source says what each
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
    let dir = std::path::Path::new("out/stability");
    let probe = StabilityProbe::default();
    let mut rows = Vec::new();
    let mut series = vec![
        Series::line("2/ω: split methods, predicted", vec![]),
        Series::line("2√2/ω: RK4, predicted", vec![]),
    ];
    println!(
        "largest stable dt on undamped springs (m = 1), {} steps a trial",
        probe.steps
    );
    println!(
        "  {:<18} {:>8} {:>14} {:>14} {:>9}",
        "method", "omega", "predicted", "measured", "rel diff"
    );
    for method in Method::ALL {
        let mut measured_points = Vec::new();
        for k in [1.0, 50.0, 1e4] {
            let spring = Spring {
                x: 1.0,
                v: 0.0,
                k,
                m: 1.0,
            };
            let omega = (k / spring.m).sqrt();
            let predicted = predicted_limit(&spring, 0.0, &spring.state(), method)?;
            let measured = measured_limit(&spring, &spring.state(), method, 1.0 / omega, &probe)?;
            let diff = if predicted.is_finite() && predicted > 0.0 {
                format!("{:.2e}", (measured / predicted - 1.0).abs())
            } else {
                "—".to_owned()
            };
            println!(
                "  {:<18} {omega:>8.3} {predicted:>14.6e} {measured:>14.6e} {diff:>9}",
                method.name()
            );
            rows.push(vec![
                method.name().to_owned(),
                number(omega),
                number(predicted),
                number(measured),
            ]);
            match method {
                Method::SymplecticEuler => series[0].points.push((omega, predicted)),
                Method::Rk4 => series[1].points.push((omega, predicted)),
                _ => {}
            }
            measured_points.push((omega, measured));
        }
        // Explicit Euler (0) and implicit Euler (∞) have no finite limit to draw on a log axis.
        if method.needs_second_order() || method == Method::Rk4 {
            series.push(Series::markers(
                format!("{}, measured", method.label()),
                measured_points,
            ));
        }
    }
    write_table(
        dir.join("limits.csv"),
        &["method", "omega", "predicted_dt", "measured_dt"],
        &rows,
    )?;
    let chart = Chart {
        title: "Largest stable dt: eigenvalue prediction (lines) and bisection (dots)".to_owned(),
        x_label: "ω = √(k/m)".to_owned(),
        y_label: "dt".to_owned(),
        log_x: true,
        log_y: true,
        series,
        ..Chart::default()
    };
    chart.write(dir.join("limits.png"), (960, 640))?;
    println!(
        "\nexplicit Euler: no dt is stable (every eigenvalue is imaginary); the measured value is the"
    );
    println!(
        "largest dt whose growth stays under the probe's 0.1 % over the run, and shrinks as 1/sqrt(steps)."
    );
    println!("implicit Euler: stable at every dt tried (up to 2^40/omega).");
    println!("wrote {}/limits.{{csv,png}}", dir.display());
    Ok(())
}
