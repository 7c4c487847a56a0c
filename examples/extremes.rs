//! The extremes suite: every method on an undamped spring across nine decades of stiffness and
//! six of dt. Each cell finishes finite or reports a typed divergence; nothing panics.
//!
//! `cargo run --release --example extremes` writes `out/extremes/extremes.csv`
//! (`method,k,dt,outcome,final_energy`) and prints the grid.

use std::process::ExitCode;

use odyn::Error;
use odyn::output::{number, write_table};
use odyn::prelude::*;
// The undamped spring m·ẍ = −k·x, here with m = 1 (`scenes/src/oscillators.rs`).
use scenes::UndampedSpring as Spring;

const STIFFNESS: [f64; 4] = [1.0, 1e3, 1e6, 1e9];
const STEPS: [f64; 5] = [1e-6, 1e-3, 1.0 / 60.0, 0.1, 1.0];

/// The extremes suite: every method on an undamped spring across nine decades of stiffness and six
/// of dt.
///
/// Writes its CSV files and charts under `out/extremes/` (the example's source says what each
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
    let mut rows = Vec::new();
    println!(
        "1000 steps per cell; F = finite, D = diverged (typed error); columns dt = 1e-6, 1e-3, 1/60, 0.1, 1"
    );
    for method in Method::ALL {
        let mut line = format!("  {:<17}", method.name());
        for k in STIFFNESS {
            line.push_str(" |");
            for dt in STEPS {
                let spring = Spring {
                    x: 1.0,
                    v: 0.0,
                    k,
                    m: 1.0,
                };
                let result = spring
                    .simulate()
                    .integrator(method)
                    .dt(dt)
                    .steps(1000)
                    .record_every(1000)
                    .run();
                let (outcome, energy) = match result {
                    Ok(run) => ("finite", run.last().energy.unwrap_or(f64::NAN)),
                    Err(Error::Diverged { .. }) => ("diverged", f64::NAN),
                    Err(other) => return Err(other),
                };
                line.push(if outcome == "finite" { 'F' } else { 'D' });
                rows.push(vec![
                    method.name().to_owned(),
                    number(k),
                    number(dt),
                    outcome.to_owned(),
                    number(energy),
                ]);
            }
        }
        println!("{line}   (k = 1 | 1e3 | 1e6 | 1e9)");
    }
    let path = std::path::Path::new("out/extremes/extremes.csv");
    write_table(
        path,
        &["method", "k", "dt", "outcome", "final_energy"],
        &rows,
    )?;
    println!("wrote {}", path.display());
    Ok(())
}
