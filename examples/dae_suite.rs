//! Differential–algebraic problems (M·y′ = f) against their references
//! (`peers/notes/dae-problems.md`): Robertson as a DAE to t = 1e11, the Bari test set's chemical
//! Akzo Nobel problem to 180 and transistor amplifier to 0.2 (singular, non-diagonal M), and the
//! Cartesian pendulum to 10 against its exact solution — each under Rodas5P, Rosenbrock23 and
//! BDF over a sweep of tolerances; then the orders of convergence at fixed steps.
//!
//! The error of a run is the largest relative error of the final state over the components
//! with |reference| ≥ 1e-10 (the peers' rule, `peers/notes/dae-peers.md`: it leaves out
//! Robertson's y₂(1e11) = 8.3e-14); its time the best of three runs.
//!
//! `cargo run --release --example dae_suite` prints the tables and writes them to
//! `out/dae_suite/tolerances.csv` and `out/dae_suite/orders.csv`.

use std::fmt::Write as _;
use std::time::Instant;

use odyn::prelude::*;

// The problems and their references, written once (`scenes/src/dae.rs`).
use scenes::{
    CHEMAKZO_REFERENCE, CartesianPendulum, ChemAkzo, PENDULUM_1, PENDULUM_10, ROBERTSON_DAE_1E11,
    RobertsonDae, TRANSAMP_REFERENCE, Transamp, slope,
};

/// The largest relative error over the components with |reference| ≥ 1e-10.
fn error(x: &[f64], reference: &[f64]) -> f64 {
    x.iter()
        .zip(reference)
        .filter(|(_, r)| r.abs() >= 1e-10)
        .map(|(x, r)| ((x - r) / r).abs())
        .fold(0.0, f64::max)
}

/// One adaptive run, timed (best of three): its error, steps and seconds, or its failure.
fn run<M: Model>(
    model: &M,
    method: Method,
    (rtol, atol): (f64, f64),
    horizon: f64,
    reference: &[f64],
) -> Result<(f64, u64, f64), Error> {
    let mut best = f64::INFINITY;
    let mut outcome = (0.0, 0);
    for _ in 0..3 {
        let start = Instant::now();
        let trajectory = model
            .simulate()
            .integrator(method)
            .tolerances(rtol, atol)
            .duration(horizon)
            .record_every(u64::MAX)
            .run()?;
        best = best.min(start.elapsed().as_secs_f64());
        let last = trajectory.last().state.as_slice().to_vec();
        outcome = (error(&last, reference), trajectory.stats.steps);
    }
    Ok((outcome.0, outcome.1, best))
}

/// The error at t = `horizon` of a fixed-step run of `steps` steps.
fn fixed<M: Model>(
    model: &M,
    method: Method,
    horizon: f64,
    steps: u64,
    reference: &[f64],
) -> odyn::Result<f64> {
    let trajectory = model
        .simulate()
        .integrator(method)
        .dt(horizon / steps as f64)
        .steps(steps)
        .record_every(u64::MAX)
        .run()?;
    Ok(error(trajectory.last().state.as_slice(), reference))
}

/// Runs the suite; takes no options.
#[derive(clap::Parser)]
struct Cli {}

fn main() -> odyn::Result<()> {
    <Cli as clap::Parser>::parse();
    let dir = std::path::Path::new("out/dae_suite");
    let methods = [Method::Rodas5P, Method::Rosenbrock23, Method::Bdf];
    let mut csv = String::from("problem,method,rtol,atol,error,steps,seconds,failure\n");
    println!(
        "{:<10} {:<13} {:>7} {:>9} {:>8} {:>10}",
        "problem", "method", "rtol", "error", "steps", "time"
    );
    // (name, atol/rtol, horizon, reference): atol as the peers calibrate (1e-4·rtol, and 1e-8
    // for Robertson); 1 for the pendulum, whose components are of order 1.
    let rober = RobertsonDae::classic();
    let akzo = ChemAkzo::start();
    let amp = Transamp::start();
    let pendulum = CartesianPendulum::released(10.0, 10.0);
    for rtol in [1e-4, 1e-6, 1e-7, 1e-8, 1e-10] {
        for method in methods {
            let results = [
                (
                    "robertson",
                    rtol * 1e-8,
                    run(
                        &rober,
                        method,
                        (rtol, rtol * 1e-8),
                        1e11,
                        &ROBERTSON_DAE_1E11,
                    ),
                ),
                (
                    "chemakzo",
                    rtol * 1e-4,
                    run(
                        &akzo,
                        method,
                        (rtol, rtol * 1e-4),
                        180.0,
                        &CHEMAKZO_REFERENCE,
                    ),
                ),
                (
                    "transamp",
                    rtol * 1e-4,
                    run(&amp, method, (rtol, rtol * 1e-4), 0.2, &TRANSAMP_REFERENCE),
                ),
                (
                    "pendulum",
                    rtol,
                    run(&pendulum, method, (rtol, rtol), 10.0, &PENDULUM_10),
                ),
            ];
            for (name, atol, result) in results {
                match result {
                    Ok((e, steps, seconds)) => {
                        println!(
                            "{name:<10} {:<13} {rtol:>7.0e} {e:>9.2e} {steps:>8} {:>7.3} ms",
                            method.name(),
                            seconds * 1e3
                        );
                        let _ = writeln!(
                            csv,
                            "{name},{},{rtol:e},{atol:e},{e:e},{steps},{seconds:e},",
                            method.name()
                        );
                    }
                    Err(failure) => {
                        let failure = failure.to_string().replace([',', '\n'], ";");
                        println!(
                            "{name:<10} {:<13} {rtol:>7.0e} failed: {failure}",
                            method.name()
                        );
                        let _ = writeln!(
                            csv,
                            "{name},{},{rtol:e},{atol:e},,,,{failure}",
                            method.name()
                        );
                    }
                }
            }
        }
    }
    odyn::output::write_atomic(dir.join("tolerances.csv"), csv.as_bytes())?;

    // Orders at fixed steps, on the smooth problems: the slope of log(error) against log(dt).
    let mut csv = String::from("problem,method,steps,error\n");
    println!("\nfixed-step orders (slope of log error against log dt):");
    // The pendulum without drift control to t = 1 (its exact state there), chemakzo to 180
    // past its initial layer (below ~2000 steps the error stays at the layer's, 5e-6).
    let free = CartesianPendulum::released(0.0, 0.0);
    let cases: [(&str, Method, &[u64]); 6] = [
        ("pendulum", Method::Rodas5P, &[20, 28, 40, 56, 80]),
        ("pendulum", Method::Rosenbrock23, &[100, 141, 200, 283, 400]),
        ("pendulum", Method::Bdf, &[100, 141, 200, 283, 400]),
        (
            "pendulum",
            Method::ImplicitEuler,
            &[1000, 1414, 2000, 2828, 4000],
        ),
        (
            "chemakzo",
            Method::Rodas5P,
            &[4000, 5657, 8000, 11314, 16000],
        ),
        (
            "chemakzo",
            Method::Rosenbrock23,
            &[16000, 22627, 32000, 45255, 64000],
        ),
    ];
    for (name, method, steps) in cases {
        let mut points = Vec::new();
        for &n in steps {
            let (horizon, e) = if name == "pendulum" {
                (1.0, fixed(&free, method, 1.0, n, &PENDULUM_1)?)
            } else {
                (180.0, fixed(&akzo, method, 180.0, n, &CHEMAKZO_REFERENCE)?)
            };
            let _ = writeln!(csv, "{name},{},{n},{e:e}", method.name());
            points.push((horizon / n as f64, e));
        }
        println!(
            "  {name:<9} {:<14} order {:.2} (errors {:.1e} … {:.1e})",
            method.name(),
            slope(&points),
            points[0].1,
            points[points.len() - 1].1
        );
    }
    odyn::output::write_atomic(dir.join("orders.csv"), csv.as_bytes())?;
    Ok(())
}
