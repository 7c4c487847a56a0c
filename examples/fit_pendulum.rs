//! Fitting a model to a recorded swing: the damped pendulum θ̈ = −ω²·sin θ − γ·θ̇, whose ω² and
//! γ are recovered from noisy samples of θ(t) by `odyn::fit` (Levenberg–Marquardt on the exact
//! forward sensitivities ∂θ/∂ω², ∂θ/∂γ that `#[param]` makes the macro derive).
//!
//! The "recording" is synthetic, so the answer is known: ω² = 9.81 s⁻² (a 1 m pendulum), γ =
//! 0.3 s⁻¹, released from rest at θ₀ = 1 rad, sampled 100 times over 10 s with Gaussian noise of
//! σ = 0.02 rad (a seeded generator: the run is reproducible). The fit starts from ω² = 7,
//! γ = 0.1 and should land within a few of its standard errors of the truth.
//!
//! `cargo run --release --example fit_pendulum` writes `out/fit_pendulum/fit.csv` (time, data,
//! initial guess, fitted model, truth) and `fit.png`.

use std::f64::consts::PI;
use std::path::Path;
use std::process::ExitCode;

use odyn::Parameters;
use odyn::fit::{Data, FitOptions, fit};
use odyn::output::{number, write_table};
use odyn::plot::{Chart, Series};
use odyn::prelude::*;
use odyn::rand::rngs::StdRng;
use odyn::rand::{Rng, SeedableRng};

// The model, written once for the examples and tests (`scenes/src/pendulums.rs`):
// θ̈ = −ω²·sin θ − γ·θ̇ with ω² and γ `#[param]`s.
use scenes::DampedPendulum as Pendulum;

const SIGMA: f64 = 0.02;

fn main() -> ExitCode {
    match run(Path::new("out/fit_pendulum")) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// θ at `times` (and on a fine grid for the chart) for `model`.
fn swing(model: &Pendulum, times: &[f64]) -> odyn::Result<Vec<f64>> {
    let run = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-10, 1e-12)
        .duration(*times.last().unwrap_or(&0.0))
        .save_at(times)
        .run()?;
    times
        .iter()
        .map(|&t| Ok(run.sample_at(t)?.state.theta))
        .collect()
}

fn run(dir: &Path) -> odyn::Result<()> {
    let truth = Pendulum::released();
    let times: Vec<f64> = (1..=100).map(|k| 0.1 * k as f64).collect();
    // Gaussian noise by Box–Muller from a seeded generator.
    let mut rng = StdRng::seed_from_u64(2026);
    let values: Vec<f64> = swing(&truth, &times)?
        .into_iter()
        .map(|theta| {
            let (u, v): (f64, f64) = (rng.random(), rng.random());
            theta + SIGMA * (-2.0 * (1.0 - u).ln()).sqrt() * (2.0 * PI * v).cos()
        })
        .collect();
    let data = Data {
        component: 0,
        times: times.clone(),
        values,
        weights: vec![1.0 / SIGMA; times.len()],
    };
    let guess = Pendulum {
        omega2: 7.0,
        gamma: 0.1,
        ..truth
    };
    let found = fit(&guess, std::slice::from_ref(&data), &FitOptions::default())?;
    println!(
        "fitted in {} iterations ({} solves with sensitivities); cost {:.4} → {:.4} (≈ (m − n)/2 = 49 for noise of the assumed σ)",
        found.iterations, found.solves, found.initial_cost, found.cost
    );
    println!(
        "{:>8}{:>12}{:>12}{:>12}{:>12}",
        "", "truth", "guess", "fitted", "std error"
    );
    for (j, name) in Pendulum::NAMES.iter().enumerate() {
        println!(
            "{name:>8}{:>12.4}{:>12.4}{:>12.5}{:>12.5}",
            truth.parameters()[j],
            guess.parameters()[j],
            found.parameters[j],
            found.standard_errors[j]
        );
    }
    let mut fitted = guess;
    fitted.set_parameters(&found.parameters)?;
    let fine: Vec<f64> = (1..=1000).map(|k| 0.01 * k as f64).collect();
    let curves = [&guess, &fitted, &truth].map(|m| swing(m, &fine));
    let [initial, best, exact] = curves;
    let (initial, best, exact) = (initial?, best?, exact?);
    let at_samples = [
        swing(&guess, &times)?,
        swing(&fitted, &times)?,
        swing(&truth, &times)?,
    ];
    let rows: Vec<Vec<String>> = times
        .iter()
        .enumerate()
        .map(|(k, t)| {
            vec![
                number(*t),
                number(data.values[k]),
                number(at_samples[0][k]),
                number(at_samples[1][k]),
                number(at_samples[2][k]),
            ]
        })
        .collect();
    write_table(
        dir.join("fit.csv"),
        &["t", "data", "initial_guess", "fitted", "truth"],
        &rows,
    )?;
    let curve = |values: &[f64]| fine.iter().copied().zip(values.iter().copied()).collect();
    Chart {
        title: format!(
            "Damped pendulum: ω² = {:.3} ± {:.3}, γ = {:.4} ± {:.4} fitted (truth 9.81, 0.3)",
            found.parameters[0],
            found.standard_errors[0],
            found.parameters[1],
            found.standard_errors[1]
        ),
        note: format!(
            "100 samples of θ with noise σ = {SIGMA} rad; the fit starts from ω² = 7, γ = 0.1"
        ),
        x_label: "t [s]".into(),
        y_label: "θ [rad]".into(),
        series: vec![
            Series::markers(
                "data",
                times
                    .iter()
                    .copied()
                    .zip(data.values.iter().copied())
                    .collect(),
            ),
            Series::line("initial guess", curve(&initial)),
            Series::line("fitted", curve(&best)),
            Series::line("truth", curve(&exact)),
        ],
        ..Chart::default()
    }
    .write(dir.join("fit.png"), (1000, 600))?;
    println!("wrote out/fit_pendulum/fit.csv and fit.png");
    Ok(())
}
